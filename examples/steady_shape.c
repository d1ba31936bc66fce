/* A steady shape of the spun chain and its branch: the smallest program that uses libwhirl.
 *
 * Build and run against an installed whirl:
 *     cc steady_shape.c $(pkg-config --cflags --libs whirl) -o steady_shape && ./steady_shape
 *
 * What it computes. A uniform chain (length L = 1, mass M = 1, g = 1) hanging from a pivot on the
 * vertical axis and spun at rate omega has steady shapes of mode k (k nodes: the pivot plus k-1
 * crossings of the axis) for omega above the critical rate omega_k. For the continuous chain the
 * linearised shape is r(s) ~ J0(2 omega sqrt(1 - s)), so omega_k = j_{0,k} / 2 with j_{0,k} the
 * k-th zero of the Bessel function J0.
 *  1. whirl_continuum_critical for k = 1..3, checked against GSL's Bessel zeros (an independent
 *     computation): they must agree to 1e-10.
 *  2. whirl_continuum_solve: the mode-2 shape at omega = 3.5, its tip radius, the tension at the
 *     pivot, the depth and the arclength of its node; then the same shape of chains of N = 50,
 *     100 and 200 equal links (whirl_nlink_solve), exact relative equilibria that approach the
 *     continuum as the links shorten, with an error proportional to 1/N: the observed order
 *     log2(err_N / err_2N) must lie within 0.1 of 1.
 *  3. whirl_continuum_branch: the mode-1 branch from omega = 1.21 to 3, by continuation. The tip
 *     radius must grow with omega, from below 0.2 just above omega_1 = 1.2024.
 *
 * Expected output (examples/steady_shape.out; `make check` compares it to 1e-6):
 *     critical rates: omega_k = j0k/2
 *     mode 1: omega_k = 1.2024128 (j0k/2 = 1.2024128)
 *     ...
 *     mode-2 shape at omega = 3.5: tip_r = 0.230209
 *       top tension = 1.101215, depth = 0.776613, node at s = 0.742299
 *       N = 50: tip_r = 0.224974, error 5.236e-03
 *     ...
 * and exit status 0; a failed check prints why and exits 1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_sf_bessel.h>
#include <whirl.h>

/* stops the program with whirl's message when a call fails */
static void check(int status, const char *what)
{
    if (status != GSL_SUCCESS) {
        fprintf(stderr, "steady_shape: %s: %s\n", what, whirl_last_error());
        exit(1);
    }
}

int main(void)
{
    gsl_set_error_handler_off(); /* errors come back as status codes */
    int ok = 1;

    /* 1. critical rates against the Bessel zeros */
    printf("critical rates: omega_k = j0k/2\n");
    for (int k = 1; k <= 3; k++) {
        double omega;
        check(whirl_continuum_critical(k, 0, &omega), "critical rate");
        const double exact = gsl_sf_bessel_zero_J0((unsigned)k) / 2;
        printf("mode %d: omega_k = %.8f (j0k/2 = %.8f)\n", k, omega, exact);
        if (fabs(omega - exact) > 1e-10) ok = 0;
    }

    /* 2. one shape, continuum and 100 links */
    const double omega = 3.5;
    whirl_shape_info info;
    check(whirl_continuum_solve(omega, 2, 0, 0, &info), "mode-2 shape");
    printf("mode-2 shape at omega = %g: tip_r = %.6f\n", omega, info.tip_r);
    printf("  top tension = %.6f, depth = %.6f, node at s = %.6f\n", info.top_tension, info.depth,
           info.crossing_s[0]);
    double err[3];
    for (int j = 0; j < 3; j++) {
        const size_t n = 50u << j;
        whirl_chain *chain = whirl_chain_alloc_uniform(n, 0);
        if (chain == NULL) check(GSL_ENOMEM, "chain");
        whirl_shape_info links;
        check(whirl_nlink_solve(chain, omega, 2, &links), "N-link shape");
        err[j] = fabs(links.tip_r - info.tip_r);
        printf("  N = %zu: tip_r = %.6f, error %.3e", n, links.tip_r, err[j]);
        if (j > 0) {
            const double order = log2(err[j - 1] / err[j]);
            printf(", order %.2f", order);
            if (fabs(order - 1) > 0.1) ok = 0;
        }
        printf("\n");
        whirl_chain_free(chain);
    }

    /* 3. the mode-1 branch, followed by continuation */
    enum { STEPS = 8 };
    double rates[STEPS];
    whirl_shape_info branch[STEPS];
    int exists[STEPS];
    for (int j = 0; j < STEPS; j++) rates[j] = 1.21 + (3.0 - 1.21) * j / (STEPS - 1);
    check(whirl_continuum_branch(1, 0, STEPS, rates, branch, exists), "mode-1 branch");
    printf("mode-1 branch:\n  omega     tip_r     top_tension\n");
    for (int j = 0; j < STEPS; j++) {
        if (!exists[j]) {
            ok = 0;
            continue;
        }
        printf("  %.4f  %.6f  %.6f\n", rates[j], branch[j].tip_r, branch[j].top_tension);
        if (j > 0 && branch[j].tip_r <= branch[j - 1].tip_r) ok = 0;
    }
    if (!exists[0] || !(branch[0].tip_r < 0.2)) ok = 0;

    if (!ok) {
        fprintf(stderr, "steady_shape: a check failed (see the comment at the top)\n");
        return 1;
    }
    return 0;
}
