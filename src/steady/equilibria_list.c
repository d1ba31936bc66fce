/* The list of equilibria found by the search (equilibria.c): added, matched by their link
 * angles, merged. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/error.h"
#include "steady/equilibria_internal.h"

/* ---- the list of equilibria ---- */

int eq_list_add(eq_list *l, double tip_r, const double *theta, int source)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        whirl_equilibrium *e = realloc(l->eq, cap * sizeof *e);
        if (e) l->eq = e;
        int *s = e ? realloc(l->source, cap * sizeof *s) : NULL;
        if (s) l->source = s;
        double *t = s && l->links ? realloc(l->theta, cap * l->links * sizeof *t) : NULL;
        if (t) l->theta = t;
        if (s == NULL || (l->links && t == NULL))
            return whirl_fail(GSL_ENOMEM, "out of memory for %zu equilibria", cap);
        l->cap = cap;
    }
    whirl_equilibrium *e = &l->eq[l->n];
    memset(e, 0, sizeof *e);
    e->info.tip_r = tip_r;
    e->branch = -1;
    e->born_at = GSL_NAN;
    e->eig_growth = GSL_NAN;
    e->index = -1;
    if (l->links) memcpy(l->theta + l->n * l->links, theta, l->links * sizeof *theta);
    l->source[l->n++] = source;
    return GSL_SUCCESS;
}

/* The entry that is the same equilibrium as (tip_r, theta), or SIZE_MAX: every link angle
 * within MATCH_ANGLE (the tip radius of a high mode is too sensitive to compare alone). */
static size_t list_find(const eq_list *l, double tip_r, const double *theta)
{
    for (size_t i = 0; i < l->n; i++) {
        if (fabs(l->eq[i].info.tip_r - tip_r) > l->window) continue;
        double d = 0;
        for (size_t k = 0; k < l->links; k++)
            d = fmax(d, fabs(l->theta[i * l->links + k] - theta[k]));
        if (d <= MATCH_ANGLE) return i;
    }
    return SIZE_MAX;
}

/* Adds (tip_r, theta) from a source, or marks the entry that has it. Returns the index
 * (SIZE_MAX on failure, status in *status). */
size_t eq_list_merge(eq_list *l, double tip_r, const double *theta, int source, int *status)
{
    size_t i = list_find(l, tip_r, theta);
    if (i != SIZE_MAX) {
        l->source[i] |= source;
        return i;
    }
    if ((*status = eq_list_add(l, tip_r, theta, source))) return SIZE_MAX;
    return l->n - 1;
}

typedef struct tip_index {
    double tip_r;
    size_t i;
} tip_index;

static int cmp_tip_index(const void *x, const void *y)
{
    double a = ((const tip_index *)x)->tip_r, b = ((const tip_index *)y)->tip_r;
    return (a > b) - (a < b);
}

/* Merges the entries that are the same equilibrium (as list_find), in increasing tip radius:
 * O(n log n + n w) for w entries within l->window of each other, where eq_list_merge for each
 * would be O(n^2) (tens of thousands of roots on long chains at high rates). */
int eq_list_unique(eq_list *l)
{
    size_t n = l->n, kept = 0, links = l->links;
    tip_index *order = malloc(n * sizeof *order);
    whirl_equilibrium *eq = malloc(n * sizeof *eq);
    int *source = malloc(n * sizeof *source);
    double *theta = malloc(n * links * sizeof *theta);
    if (order == NULL || eq == NULL || source == NULL || (n * links > 0 && theta == NULL)) {
        free(order), free(eq), free(source), free(theta);
        return whirl_fail(GSL_ENOMEM, "out of memory for %zu equilibria", n);
    }
    for (size_t i = 0; i < n; i++) order[i] = (tip_index){l->eq[i].info.tip_r, i};
    qsort(order, n, sizeof *order, cmp_tip_index);
    for (size_t k = 0; k < n; k++) {
        size_t i = order[k].i, same = SIZE_MAX;
        double tip = l->eq[i].info.tip_r;
        const double *th = l->theta + i * links;
        for (size_t j = kept; j-- > 0 && eq[j].info.tip_r >= tip - l->window;) {
            double d = 0;
            for (size_t q = 0; q < links; q++) d = fmax(d, fabs(theta[j * links + q] - th[q]));
            if (d <= MATCH_ANGLE) {
                same = j;
                break;
            }
        }
        if (same != SIZE_MAX) {
            l->coincident += (source[same] & l->source[i]) != 0;
            source[same] |= l->source[i];
            continue;
        }
        eq[kept] = l->eq[i];
        source[kept] = l->source[i];
        memcpy(theta + kept * links, th, links * sizeof *theta);
        kept++;
    }
    free(order);
    free(l->eq), free(l->source), free(l->theta);
    l->eq = eq;
    l->source = source;
    l->theta = theta;
    l->n = l->cap = kept;
    if (kept == 0) l->cap = n; /* the arrays hold n */
    return GSL_SUCCESS;
}
