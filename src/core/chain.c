/* The N-link chain's parameters. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "core/error.h"

static whirl_chain *chain_new(size_t n)
{
    /* n * sizeof(double) must not wrap round: a wrapped size allocates a short array that the
     * fill then overruns. */
    if (n > SIZE_MAX / (2 * sizeof(double))) {
        whirl_fail(GSL_ENOMEM, "a chain of %zu links needs more memory than can be addressed "
                               "(%zu links at most)", n, SIZE_MAX / (2 * sizeof(double)));
        return NULL;
    }
    whirl_chain *c = calloc(1, sizeof *c);
    if (c == NULL) goto fail;
    c->n = n;
    c->length = malloc(n * sizeof *c->length);
    c->mass = malloc(n * sizeof *c->mass);
    if (c->length == NULL || c->mass == NULL) goto fail;
    return c;
fail:
    whirl_chain_free(c);
    whirl_fail(GSL_ENOMEM, "out of memory for a chain of %zu links", n);
    return NULL;
}

whirl_chain *whirl_chain_alloc(size_t n, const double *length, const double *mass, double g)
{
    if (n == 0) {
        whirl_fail(GSL_EINVAL, "a chain needs at least one link");
        return NULL;
    }
    if (!(isfinite(g) && g > 0)) {
        whirl_fail(GSL_EINVAL, "gravity must be positive and finite, got %g", g);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        if (!(isfinite(length[i]) && length[i] > 0)) {
            whirl_fail(GSL_EINVAL, "length of link %zu must be positive and finite, got %g",
                       i + 1, length[i]);
            return NULL;
        }
        if (!(isfinite(mass[i]) && mass[i] > 0)) {
            whirl_fail(GSL_EINVAL, "mass %zu must be positive and finite, got %g", i + 1,
                       mass[i]);
            return NULL;
        }
    }
    whirl_chain *c = chain_new(n);
    if (c == NULL) return NULL;
    memcpy(c->length, length, n * sizeof *length);
    memcpy(c->mass, mass, n * sizeof *mass);
    c->gravity = g;
    return c;
}

whirl_chain *whirl_chain_alloc_uniform(size_t n, double tip_mass)
{
    if (n == 0) {
        whirl_fail(GSL_EINVAL, "a chain needs at least one link");
        return NULL;
    }
    if (whirl_check_tip_mass(tip_mass) != GSL_SUCCESS) return NULL;
    whirl_chain *c = chain_new(n);
    if (c == NULL) return NULL;
    for (size_t i = 0; i < n; i++) {
        c->length[i] = 1.0 / (double)n;
        c->mass[i] = 1.0 / (double)n;
    }
    c->mass[n - 1] += tip_mass;
    c->gravity = 1.0;
    return c;
}

void whirl_chain_free(whirl_chain *c)
{
    if (c == NULL) return;
    free(c->length);
    free(c->mass);
    free(c);
}

double whirl_chain_total_length(const whirl_chain *c)
{
    double sum = 0;
    for (size_t i = 0; i < c->n; i++) sum += c->length[i];
    return sum;
}

double whirl_chain_total_mass(const whirl_chain *c)
{
    double sum = 0;
    for (size_t i = 0; i < c->n; i++) sum += c->mass[i];
    return sum;
}
