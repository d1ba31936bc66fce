/* A branch of the N-link chain followed by continuation, with its folds.
 *
 * Build and run against an installed whirl:
 *     cc branch_folds.c $(pkg-config --cflags --libs whirl) -o branch_folds && ./branch_folds
 *
 * What it computes. A chain of N = 7 equal links (L = M = g = 1) spun at the rate omega.
 *  1. Its critical rates (whirl_nlink_critical: the hanging chain's normal-mode frequencies, a
 *     tridiagonal eigenproblem) against a closed form: omega_k^2 = N x_k with x_k the k-th zero
 *     of the Laguerre polynomial L_N. The Newton correction L_N(x) / L_N'(x) at x = omega_k^2 / N
 *     (GSL's Laguerre polynomials; L_N' = -L_{N-1}^(1)) must be below 1e-12 x.
 *  2. whirl_nlink_follow: mode 4 from its birth (omega_4 = 5.857) up to omega = 12, by
 *     pseudo-arclength continuation, reporting every crossing of the rates 6, 7, ..., 12 and
 *     every event. On this coarse chain the branch folds twice, at omega = 7.059 and back at
 *     6.847: between the folds a rate meets three shapes of mode 4. Checks: every crossing is an
 *     equilibrium (whirl_nlink_positions from its tip radius lands the pivot on the axis, the
 *     force balance built up from the tip: |r_0| < 1e-9); the path, which starts at the birth
 *     going up and ends above 12, crosses each rate an odd number of times, three times where
 *     the folds overlap (7); two folds.
 *
 * Expected output (examples/branch_folds.out; `make check` compares it):
 *     critical rates of 7 links: omega_k^2 / N against the zeros of L_7
 *       mode 1: omega_k = 1.16245677, Newton correction ...
 *     ...
 * and exit status 0; a failed check prints why and exits 1. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_sf_laguerre.h>
#include <whirl.h>

#define N 7
#define RATES 7 /* omega = 6, 7, ..., 12 */

/* stops the program with whirl's message when a call fails */
static void check(int status, const char *what)
{
    if (status != GSL_SUCCESS) {
        fprintf(stderr, "branch_folds: %s: %s\n", what, whirl_last_error());
        exit(1);
    }
}

typedef struct tally {
    const whirl_chain *chain;
    const double *rates;
    int crossings[RATES]; /* per rate */
    int folds;
    int ok;
} tally;

/* whirl_nlink_visit_fn: a crossing of rates[j] (event NULL) or an event */
static int visit(void *ctx, size_t j, const whirl_shape_info *info, const whirl_branch_event *ev)
{
    tally *t = ctx;
    if (ev != NULL) {
        printf("  %s at omega = %.6f, tip_r = %.6f\n",
               ev->kind == WHIRL_EVENT_FOLD ? "fold" : "event", ev->omega, ev->tip_r);
        t->folds += ev->kind == WHIRL_EVENT_FOLD;
        return 0;
    }
    double r[N + 1], z[N + 1], tension[N + 1];
    check(whirl_nlink_positions(t->chain, t->rates[j], info->tip_r, r, z, tension), "positions");
    char off[32] = "below 1e-12";
    if (!(fabs(r[0]) < 1e-12)) snprintf(off, sizeof off, "%.1e", fabs(r[0]));
    printf("  omega = %4.1f: tip_r = %.6f, depth = %.6f, pivot's |r_0| %s\n", t->rates[j],
           info->tip_r, info->depth, off);
    if (!(fabs(r[0]) < 1e-9)) t->ok = 0;
    t->crossings[j]++;
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off(); /* errors come back as status codes */
    whirl_chain *chain = whirl_chain_alloc_uniform(N, 0);
    if (chain == NULL) check(GSL_ENOMEM, "chain");
    int ok = 1;

    /* 1. critical rates against the zeros of L_N */
    double omega_k[N];
    check(whirl_nlink_critical(chain, N, omega_k), "critical rates");
    printf("critical rates of %d links: omega_k^2 / N against the zeros of L_%d\n", N, N);
    for (int k = 0; k < N; k++) {
        const double x = omega_k[k] * omega_k[k] / N;
        const double newton = gsl_sf_laguerre_n(N, 0, x) / -gsl_sf_laguerre_n(N - 1, 1, x);
        printf("  mode %d: omega_k = %.8f, Newton correction %s 1e-12 x\n", k + 1, omega_k[k],
               fabs(newton) < 1e-12 * x ? "below" : "ABOVE");
        if (!(fabs(newton) < 1e-12 * x)) ok = 0;
    }

    /* 2. mode 4 followed from its birth to omega = 12 */
    double rates[RATES];
    for (int j = 0; j < RATES; j++) rates[j] = 6 + j;
    tally t = {.chain = chain, .rates = rates, .ok = 1};
    printf("mode 4 from its birth at omega = %.6f:\n", omega_k[3]);
    check(whirl_nlink_follow(chain, 4, 12, RATES, rates, visit, &t), "mode 4");
    printf("crossings per rate:");
    for (int j = 0; j < RATES; j++) {
        printf(" %d", t.crossings[j]);
        if (t.crossings[j] % 2 != 1) ok = 0;
    }
    printf("; folds: %d\n", t.folds);
    if (!t.ok || t.folds != 2 || t.crossings[1] != 3) ok = 0;
    whirl_chain_free(chain);

    if (!ok) {
        fprintf(stderr, "branch_folds: a check failed (see the comment at the top)\n");
        return 1;
    }
    return 0;
}
