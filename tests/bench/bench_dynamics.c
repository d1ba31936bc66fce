/* Benchmark and long-time accuracy study of the dynamics module. Writes CSV under argv[1]
 * (default out/bench) and prints the figures:
 *  - the steady mode-2 shape at omega = 3.5, N = 100, co-rotating frame, gauss2 (and gauss3),
 *    dt = 0.01, 100 rotation periods: deviation (whirl_deviation), constraint residual, stage
 *    sweeps per step;
 *  - the stage solver: fixed-point gauss2 against GSL's rk4imp (the same method with modified
 *    Newton and a dense LU) on a perturbed whirling chain, time per unit of simulated time;
 *  - energy error of gauss3 (h = 0.01) and gauss2 (h = 0.01, 0.001) over 10^6 steps (5-link
 *    chain, inertial frame): its running maximum at log-spaced times and the exponent of its
 *    growth (least squares of log max|dE| on log t over the last three decades);
 *  - the hanging chain at N = 10^4: tension error against the exact weights, and gauss2 steps
 *    (a configuration the seed's angles cannot represent). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "bench_dynamics"
#include "bench_util.h"

#define PI 3.14159265358979323846

static void bench_steady(const char *dir)
{
    const size_t n = 100;
    const double omega = 3.5, dt = 0.01, period = 2 * PI / omega;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    double *xt = malloc(3 * n * sizeof *xt), *y = malloc(6 * n * sizeof *y);
    if (bench_steady_positions(c, omega, 2, x) != GSL_SUCCESS) bench_die("steady shape");
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    FILE *fp = bench_open_csv(dir, "dynamics_steady.csv");
    fprintf(fp, "# steady mode 2, omega 3.5, N 100, co-rotating, dt 0.01\n");
    fprintf(fp, "method,periods,deviation,max_constraint,sweeps_per_step,seconds\n");
    printf("steady mode 2 at omega = 3.5, N = 100, co-rotating, dt = 0.01, 100 periods:\n");
    const char *methods[] = {"gauss2", "gauss3"};
    for (int k = 0; k < 2; k++) {
        if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("set_state");
        whirl_integrator *it = whirl_integrator_alloc(methods[k], d);
        double t = 0, worst_c = 0, dev = 0;
        const double t0 = bench_now();
        for (int p = 1; p <= 100; p++) {
            if (whirl_integrator_advance(it, &t, y, p * period, dt, 0) != GSL_SUCCESS)
                bench_die("advance");
            whirl_dyn_diagnostics diag;
            whirl_dyn_diagnose(d, t, y, &diag);
            worst_c = fmax(worst_c, diag.constraint);
            if (p % 10 == 0) {
                whirl_dyn_get_state(d, t, y, WHIRL_FRAME_ROTATING, xt, v);
                dev = whirl_deviation(n, xt, x);
            }
        }
        const double secs = bench_now() - t0;
        const whirl_integrator_stats s = whirl_integrator_get_stats(it);
        const double sweeps = (double)s.iterations / (double)s.steps;
        fprintf(fp, "%s,100,%.6g,%.6g,%.4g,%.4g\n", methods[k], dev, worst_c, sweeps, secs);
        printf("  %s: deviation %.3g, max constraint residual %.3g, %.2f sweeps/step, %.2f s\n",
               methods[k], dev, worst_c, sweeps, secs);
        whirl_integrator_free(it);
    }
    fclose(fp);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    free(x), free(v), free(xt), free(y);
}

/* Fixed-point gauss2 against GSL's rk4imp (modified Newton, dense LU of 2 x dim) on the mode-1
 * shape at omega = 2 with a perturbation of the rates, N links: seconds per unit time. */
static void bench_stage_solver(const char *dir)
{
    FILE *fp = bench_open_csv(dir, "dynamics_stage_solver.csv");
    fprintf(fp, "n,method,h,seconds_per_unit_time,rhs_per_step,sweeps_per_step\n");
    printf("stage solver, mode 1 at omega = 2 perturbed, co-rotating (s per unit time):\n");
    const size_t sizes[] = {5, 10, 20, 40};
    for (size_t s = 0; s < 4; s++) {
        const size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
        double *y = malloc(6 * n * sizeof *y);
        if (bench_steady_positions(c, 2.0, 1, x) != GSL_SUCCESS) bench_die("steady shape");
        for (size_t i = 0; i < n; i++) v[3 * i + 1] = 0.05 * (double)(i + 1) / (double)n;
        const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 2};
        whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        const double h = 0.2 / (double)n;
        const char *methods[] = {"gauss2", "gsl-rk4imp"};
        printf("  N = %3zu, h = %.4g:", n, h);
        for (int k = 0; k < 2; k++) {
            double secs[3];
            whirl_integrator_stats st = {0};
            for (int r = 0; r < 3; r++) {
                if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("set_state");
                whirl_integrator *it = whirl_integrator_alloc(methods[k], d);
                double t = 0;
                const double t0 = bench_now();
                if (whirl_integrator_advance(it, &t, y, 0.5, h, 0) != GSL_SUCCESS) bench_die("advance");
                secs[r] = (bench_now() - t0) / 0.5;
                st = whirl_integrator_get_stats(it);
                whirl_integrator_free(it);
            }
            const double med = bench_median(secs, 3);
            fprintf(fp, "%zu,%s,%.6g,%.6g,%.4g,%.4g\n", n, methods[k], h, med,
                    (double)st.rhs_evals / (double)st.steps,
                    (double)st.iterations / (double)st.steps);
            printf("  %s %.3g s (%.1f rhs/step)", methods[k], med,
                   (double)st.rhs_evals / (double)st.steps);
        }
        printf("\n");
        whirl_dyn_free(d);
        whirl_chain_free(c);
        free(x), free(v), free(y);
    }
    fclose(fp);
}

/* Energy error over 10^6 steps and the exponent of its growth. */
static void bench_energy(const char *dir)
{
    FILE *fp = bench_open_csv(dir, "dynamics_energy.csv");
    fprintf(fp, "# 5-link uniform chain, 3D, inertial, 10^6 steps of h\n");
    fprintf(fp, "method,h,t,abs_energy_error,running_max\n");
    printf("energy error over 10^6 steps (5 links, 3D, inertial):\n");
    const struct {
        const char *method;
        double h;
    } runs[] = {{"gauss3", 0.01}, {"gauss2", 0.01}, {"gauss2", 0.001}};
    for (int k = 0; k < 3; k++) {
        const size_t n = 5;
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        const whirl_model m = {.chain = c, .dim = 3};
        whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        double x[15], v[15], y[30], p[3] = {0, 0, 0};
        bench_smooth_state(c, p, x, v);
        if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("set_state");
        whirl_integrator *it = whirl_integrator_alloc(runs[k].method, d);
        whirl_dyn_diagnostics d0, di;
        whirl_dyn_diagnose(d, 0, y, &d0);
        const double h = runs[k].h;
        const long steps = 1000000;
        double t = 0, running = 0, worst_c = 0;
        /* samples at 20 per decade of the step count */
        double logt[200], logm[200];
        int ns = 0;
        long next = 10;
        const double t0 = bench_now();
        for (long done = 0; done < steps;) {
            const long target = next < steps ? next : steps;
            if (whirl_integrator_advance(it, &t, y, (double)target * h, h, 0) != GSL_SUCCESS)
                bench_die("advance");
            done = target;
            whirl_dyn_diagnose(d, t, y, &di);
            const double err = fabs(di.energy - d0.energy);
            running = fmax(running, err);
            worst_c = fmax(worst_c, di.constraint);
            fprintf(fp, "%s,%g,%.17g,%.6g,%.6g\n", runs[k].method, h, t, err, running);
            if (ns < 200 && running > 0) {
                logt[ns] = log10(t);
                logm[ns] = log10(running);
                ns++;
            }
            long nx = (long)ceil((double)next * pow(10, 0.05));
            next = nx > next ? nx : next + 1;
        }
        const double secs = bench_now() - t0;
        /* least squares slope over t >= t_end / 1000 */
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        int cnt = 0;
        const double cut = log10((double)steps * h) - 3;
        for (int i = 0; i < ns; i++) {
            if (logt[i] < cut) continue;
            sx += logt[i], sy += logm[i], sxx += logt[i] * logt[i], sxy += logt[i] * logm[i];
            cnt++;
        }
        const double slope = (cnt * sxy - sx * sy) / (cnt * sxx - sx * sx);
        printf("  %s h = %g: max |dE| %.3g (|E| %.3g), growth exponent %.2f over the last 3 "
               "decades, max constraint %.3g, %.1f s\n",
               runs[k].method, h, running, fabs(d0.energy), slope, worst_c, secs);
        whirl_integrator_free(it);
        whirl_dyn_free(d);
        whirl_chain_free(c);
    }
    fclose(fp);
}

static void bench_large(const char *dir)
{
    const size_t n = 10000;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    double *y = malloc(6 * n * sizeof *y), *ten = malloc(n * sizeof *ten);
    double z = 0;
    for (size_t i = 0; i < n; i++) x[3 * i + 2] = z -= c->length[i];
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("set_state");
    whirl_dyn_tensions(d, 0, y, ten);
    long double below = 0;
    double worst = 0;
    for (size_t i = n; i-- > 0;) {
        below += (long double)c->mass[i] * c->gravity;
        worst = fmax(worst, (double)fabsl((ten[i] - below) / below));
    }
    /* a transverse kick of the lower half, then gauss2 steps below the stability bound of the
     * fixed-point iteration (h omega_max rho(A) < 1, omega_max ~ 2 N) */
    for (size_t i = n / 2; i < n; i++) v[3 * i] = 0.01 * (double)(i - n / 2) / (double)n;
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("set_state kick");
    whirl_integrator *it = whirl_integrator_alloc("gauss2", d);
    double t = 0;
    const double h = 1e-4, t0 = bench_now();
    const int status = whirl_integrator_advance(it, &t, y, 100 * h, h, 0);
    const double secs = bench_now() - t0;
    whirl_dyn_diagnostics diag;
    whirl_dyn_diagnose(d, t, y, &diag);
    const whirl_integrator_stats s = whirl_integrator_get_stats(it);
    FILE *fp = bench_open_csv(dir, "dynamics_large.csv");
    fprintf(fp, "n,hanging_tension_rel_error,gauss2_status,steps,sweeps_per_step,"
                "max_constraint,seconds_per_step\n");
    fprintf(fp, "%zu,%.6g,%d,%lu,%.4g,%.6g,%.6g\n", n, worst, status, s.steps,
            (double)s.iterations / (double)s.steps, diag.constraint, secs / (double)s.steps);
    fclose(fp);
    printf("N = 10^4 hanging chain: tension relative error %.3g; gauss2 h = 1e-4 after a kick: "
           "status %d, %lu steps, %.1f sweeps/step, constraint %.3g, %.3g s/step\n",
           worst, status, s.steps, (double)s.iterations / (double)s.steps, diag.constraint,
           secs / (double)s.steps);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    free(x), free(v), free(y), free(ten);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    bench_large(dir);
    bench_steady(dir);
    bench_stage_solver(dir);
    bench_energy(dir);
    return 0;
}
