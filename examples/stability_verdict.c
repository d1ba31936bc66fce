/* Is a steady shape stable? The linear analysis and a perturbed run, side by side.
 *
 * Build and run against an installed whirl:
 *     cc stability_verdict.c $(pkg-config --cflags --libs whirl) -o stability_verdict
 *     ./stability_verdict
 *
 * What it computes. A chain of N = 25 equal links (L = M = g = 1) spun at rate omega about the
 * vertical axis. In the frame co-rotating at omega a steady shape is an equilibrium; linearising
 * the equations of motion about it, M q'' + (G + C) q' + K q = 0 with the gyroscopic matrix G,
 * gives eigenvalues lambda, and the growth rate max Re(lambda) says whether a small disturbance
 * grows (> 0: unstable) or not (0: neutrally stable; the chain has no dissipation here).
 * whirl_stability_mode returns that growth rate. whirl_stability_run checks it independently,
 * by integrating the full nonlinear motion from the shape with every link turned by 1e-6 rad at
 * random and watching the deviation: "unstable" once it reaches 100 times the initial one, with
 * the exponential rate fitted to its growth.
 *  - mode 1 at omega = 4: linearly neutral and a minimum of the amended potential (index 0); the
 *    run must stay bounded: "stable (minimum)".
 *  - mode 2 at omega = 9: linearly unstable (growth about 0.449 per unit time); the run must be
 *    "unstable" with a fitted rate within 5% of the linear one.
 *
 * Expected output (examples/stability_verdict.out; `make check` compares it):
 *     mode 1 at omega = 4: linear growth 0 -> stable (minimum); run: stable (minimum), rate 0, ...
 *       run: 35000 steps, 648660 right-hand sides
 *     mode 2 at omega = 9: linear growth 0.4486 -> unstable; run: unstable, rate 0.4486, ...
 *       run: 10292 steps, 177880 right-hand sides
 * and exit status 0; a disagreement prints why and exits 1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <whirl.h>

static void check(int status, const char *what)
{
    if (status != GSL_SUCCESS) {
        fprintf(stderr, "stability_verdict: %s: %s\n", what, whirl_last_error());
        exit(1);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    const size_t n = 25;
    const struct {
        int mode;
        double omega;
    } cases[] = {{1, 4.0}, {2, 9.0}};
    whirl_chain *chain = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    if (chain == NULL || w == NULL) check(GSL_ENOMEM, "allocation");
    int ok = 1;
    for (int c = 0; c < 2; c++) {
        /* the model: the chain seen in the frame co-rotating at omega, in 3D */
        const whirl_model model = {.chain = chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                                   .omega = cases[c].omega};
        whirl_shape_info info;
        double growth;
        check(whirl_stability_mode(w, &model, cases[c].mode, &info, &growth), "linear analysis");
        int index; /* negative directions of the amended potential: 0 for mode 1 (a minimum) */
        check(whirl_stability_index(w, &index), "index");
        const whirl_verdict linear = whirl_verdict_linear(growth, index);

        whirl_stability_run_params params = whirl_stability_run_defaults(); /* 100 periods */
        whirl_stability_run_result run;
        check(whirl_stability_run(&model, info.tip_r, &params, &run), "perturbed run");
        run.verdict = whirl_verdict_refine(run.verdict, index);
        printf("mode %d at omega = %g: linear growth %.4g -> %s; run: %s, rate %.4g, largest "
               "deviation %.3g x initial\n",
               cases[c].mode, cases[c].omega, growth, whirl_verdict_name(linear),
               whirl_verdict_name(run.verdict), run.sim_growth, run.max_deviation);
        printf("  run: %lu steps, %lu right-hand sides\n", run.stats.steps, run.stats.rhs_evals);
        if (run.verdict != linear) ok = 0;
        if (linear == WHIRL_VERDICT_UNSTABLE && fabs(run.sim_growth - growth) > 0.05 * growth)
            ok = 0;
    }
    whirl_stability_free(w);
    whirl_chain_free(chain);
    if (!ok) {
        fprintf(stderr, "stability_verdict: the run disagrees with the linear analysis\n");
        return 1;
    }
    return 0;
}
