/* The double pendulum on a shaken pivot: periodic motions and their Floquet multipliers.
 *
 * Build and run against an installed whirl:
 *     cc periodic_pendulum.c $(pkg-config --cflags --libs whirl) -o periodic_pendulum
 *     ./periodic_pendulum
 *
 * What it computes. Two equal links (length 1/2 each, masses 1/2, g = 1: whirl_chain_alloc_uniform
 * with N = 2) in the vertical x-z plane, the pivot shaken vertically, A cos(omega t) at
 * omega = 40 (whirl_pivot_line along z). Hanging straight down, or standing straight up, the
 * chain moves with the pivot: a periodic motion of period T = 2 pi / omega, whose Floquet
 * multipliers (the eigenvalues of the period map's derivative, whirl_periodic_find) say whether
 * a small disturbance grows.
 *  1. Hanging, A = 1e-6 (next to no shaking): the multipliers are exp(+-i w_k T), w_k the double
 *     pendulum's normal-mode frequencies, in closed form w_k^2 = (g/l) (2 -+ sqrt 2), l = 1/2.
 *     Their angles must agree with w_k T to 1e-8 (measured: 1e-9).
 *  2. Upside down, A = 1e-6: unstable, the largest multiplier exp(w_2 T) (the linearisation
 *     about the top has the rates +-w_k): to 1e-8 relative.
 *  3. Upside down, A = 0.05: the fast shaking holds the pendulum up (Kapitza's pendulum, for two
 *     links: Acheson and Mullin, Nature 366:215, 1993): every multiplier on the unit circle,
 *     verdict "neutral"; at A = 0.02 the shaking is too weak: "unstable".
 *
 * Expected output (examples/periodic_pendulum.out; `make check` compares it):
 *     hanging, A = 1e-06: |arg mu| = 0.17002 and 0.41047 rad, w_k T = 0.17002 and 0.41047
 *     ...
 * and exit status 0; a failed check prints why and exits 1. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include <whirl.h>

#define OMEGA 40.0

/* stops the program with whirl's message when a call fails */
static void check(int status, const char *what)
{
    if (status != GSL_SUCCESS) {
        fprintf(stderr, "periodic_pendulum: %s: %s\n", what, whirl_last_error());
        exit(1);
    }
}

/* The vertical motion (inverted 0: hanging, 1: upside down) with the pivot shaken by amplitude
 * amp: its multipliers into *res (valid while *w lives; the caller frees *w). */
static void solve(const whirl_chain *chain, double amp, int inverted, whirl_periodic **w,
                  whirl_periodic_result *res)
{
    const double up[3] = {0, 0, 1};
    whirl_pivot_path path;
    check(whirl_pivot_line(&path, OMEGA, amp, up), "pivot path");
    *w = whirl_periodic_alloc(chain, 2, &path);
    if (*w == NULL) check(GSL_ENOMEM, "workspace");
    double *y = malloc(whirl_periodic_state_size(*w) * sizeof *y);
    if (y == NULL) check(GSL_ENOMEM, "state");
    check(whirl_periodic_start_vertical(*w, inverted, y), "start");
    check(whirl_periodic_find(*w, y, NULL, res), "periodic motion");
    free(y);
}

int main(void)
{
    gsl_set_error_handler_off(); /* errors come back as status codes */
    int ok = 1;
    whirl_chain *chain = whirl_chain_alloc_uniform(2, 0);
    if (chain == NULL) check(GSL_ENOMEM, "chain");
    const double T = 2 * M_PI / OMEGA, l = 0.5;
    const double w1 = sqrt((2 - M_SQRT2) / l), w2 = sqrt((2 + M_SQRT2) / l);

    /* 1. hanging: multipliers exp(+-i w_k T), by decreasing modulus, all of modulus 1; the two
     * angles in increasing order */
    whirl_periodic *w;
    whirl_periodic_result res;
    solve(chain, 1e-6, 0, &w, &res);
    double arg[2] = {HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < res.count; i++) {
        const double a = fabs(carg(res.re[i] + I * res.im[i]));
        arg[0] = GSL_MIN(arg[0], a);
        arg[1] = GSL_MAX(arg[1], a);
    }
    printf("hanging, A = 1e-06: |arg mu| = %.5f and %.5f rad, w_k T = %.5f and %.5f\n", arg[0],
           arg[1], w1 * T, w2 * T);
    printf("  %zu multipliers, |mu|max = %.9f, verdict %s\n", res.count, res.max_modulus,
           whirl_floquet_verdict_name(res.verdict));
    if (res.count != 4 || fabs(arg[0] - w1 * T) > 1e-8 || fabs(arg[1] - w2 * T) > 1e-8) ok = 0;
    whirl_periodic_free(w);

    /* 2. upside down, next to no shaking: |mu|max = exp(w_2 T) */
    solve(chain, 1e-6, 1, &w, &res);
    printf("inverted, A = 1e-06: |mu|max = %.6f, exp(w_2 T) = %.6f, verdict %s\n",
           res.max_modulus, exp(w2 * T), whirl_floquet_verdict_name(res.verdict));
    if (fabs(res.max_modulus / exp(w2 * T) - 1) > 1e-8 || res.verdict != WHIRL_FLOQUET_UNSTABLE)
        ok = 0;
    whirl_periodic_free(w);

    /* 3. upside down, shaken hard enough and not */
    const double amps[2] = {0.05, 0.02};
    const whirl_floquet_verdict want[2] = {WHIRL_FLOQUET_NEUTRAL, WHIRL_FLOQUET_UNSTABLE};
    for (int j = 0; j < 2; j++) {
        solve(chain, amps[j], 1, &w, &res);
        printf("inverted, A = %g: |mu|max = %.6f, verdict %s\n", amps[j], res.max_modulus,
               whirl_floquet_verdict_name(res.verdict));
        if (res.verdict != want[j]) ok = 0;
        whirl_periodic_free(w);
    }
    whirl_chain_free(chain);

    if (!ok) {
        fprintf(stderr, "periodic_pendulum: a check failed (see the comment at the top)\n");
        return 1;
    }
    return 0;
}
