/* Benchmark and long-time accuracy study of the dynamics module. Writes CSV under argv[1]
 * (default out/bench) and prints the figures:
 *  - cost of one right-hand side against N = 10 .. 10^4 (3D, Cartesian; the seed formulation up
 *    to N = 100): ns per evaluation and per link, medians of 7 repeats;
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

#define REPEATS 7
#define PI 3.14159265358979323846

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, cmp_double);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static FILE *open_csv(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "w");
    if (fp == NULL) {
        fprintf(stderr, "bench_dynamics: cannot write %s\n", path);
        exit(1);
    }
    return fp;
}

static void die(const char *what)
{
    fprintf(stderr, "bench_dynamics: %s: %s\n", what, whirl_last_error());
    exit(1);
}

/* A smooth non-trivial state: link i at theta = 0.5 + 0.3 sin(0.7 i), phi = 0.05 i, rates
 * 0.2 cos(i), 0.1 (positions and velocities, 3 per mass, pivot at p). */
static void smooth_state(const whirl_chain *c, const double *p, double *x, double *v)
{
    double pos[3] = {p[0], p[1], p[2]}, vel[3] = {0, 0, 0};
    for (size_t i = 0; i < c->n; i++) {
        const double th = 0.5 + 0.3 * sin(0.7 * (double)i), ph = 0.05 * (double)i;
        const double thd = 0.2 * cos((double)i), phd = 0.1;
        const double u[3] = {sin(th) * cos(ph), sin(th) * sin(ph), -cos(th)};
        const double et[3] = {cos(th) * cos(ph), cos(th) * sin(ph), sin(th)};
        const double ep[3] = {-sin(ph), cos(ph), 0};
        for (int k = 0; k < 3; k++) {
            pos[k] += c->length[i] * u[k];
            vel[k] += c->length[i] * (thd * et[k] + phd * sin(th) * ep[k]);
            x[3 * i + k] = pos[k];
            v[3 * i + k] = vel[k];
        }
    }
}

/* Median ns per right-hand side of the model in formulation f at the smooth state. */
static double rhs_cost(const whirl_model *m, whirl_formulation f)
{
    const size_t n = m->chain->n;
    whirl_dyn *d = whirl_dyn_alloc(m, f);
    if (d == NULL) die("alloc");
    const size_t size = whirl_dyn_size(d);
    double *x = malloc(3 * n * sizeof *x), *v = malloc(3 * n * sizeof *v);
    double *y = malloc(size * sizeof *y), *dy = malloc(size * sizeof *dy);
    const double p[3] = {m->frame == WHIRL_FRAME_ROTATING ? m->drive_radius : 0, 0, 0};
    smooth_state(m->chain, p, x, v);
    if (m->frame != WHIRL_FRAME_ROTATING && m->drive_radius > 0) {
        /* the driven inertial pivot at t = 0 is at (eps, 0, 0) with velocity eps w y */
        for (size_t i = 0; i < n; i++) {
            x[3 * i] += m->drive_radius;
            v[3 * i + 1] += m->drive_radius * m->omega;
        }
    }
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) die("set_state");
    const double work = f == WHIRL_FORMULATION_SEED ? (double)n * n * n : (double)n;
    const long reps = (long)fmax(1, 2e6 / work);
    double t[REPEATS];
    whirl_dyn_rhs(0, y, dy, d); /* warm-up */
    for (int r = 0; r < REPEATS; r++) {
        const double t0 = now();
        for (long k = 0; k < reps; k++) whirl_dyn_rhs(1e-9 * (double)k, y, dy, d);
        t[r] = (now() - t0) / (double)reps * 1e9;
    }
    free(x), free(v), free(y), free(dy);
    whirl_dyn_free(d);
    return median(t, REPEATS);
}

static void bench_cost(const char *dir)
{
    FILE *fp = open_csv(dir, "dynamics_cost.csv");
    fprintf(fp, "# ns per right-hand side, 3D, median of %d repeats\n", REPEATS);
    fprintf(fp, "n,formulation,model,ns_per_rhs,ns_per_link\n");
    const size_t sizes[] = {10, 30, 100, 300, 1000, 3000, 10000};
    printf("right-hand side cost (3D; ns per evaluation, ns per link):\n");
    printf("  %6s %22s %22s %22s\n", "N", "cartesian plain", "cartesian all forces",
           "seed plain");
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        const size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        const whirl_model plain = {.chain = c, .dim = 3};
        const whirl_model full = {.chain = c,
                                  .dim = 3,
                                  .frame = WHIRL_FRAME_ROTATING,
                                  .omega = 3.5,
                                  .drive_radius = 0.02,
                                  .air_drag = 0.1,
                                  .air_drag_quadratic = 0.05,
                                  .internal_damping = 0.01};
        const double cp = rhs_cost(&plain, WHIRL_FORMULATION_CARTESIAN);
        const double cf = rhs_cost(&full, WHIRL_FORMULATION_CARTESIAN);
        const double cs = n <= 100 ? rhs_cost(&plain, WHIRL_FORMULATION_SEED) : NAN;
        fprintf(fp, "%zu,cartesian,plain,%.6g,%.6g\n", n, cp, cp / (double)n);
        fprintf(fp, "%zu,cartesian,all_forces,%.6g,%.6g\n", n, cf, cf / (double)n);
        if (n <= 100) fprintf(fp, "%zu,seed,plain,%.6g,%.6g\n", n, cs, cs / (double)n);
        printf("  %6zu %12.0f %8.1f  %12.0f %8.1f  %12.0f %8.1f\n", n, cp, cp / (double)n, cf,
               cf / (double)n, cs, cs / (double)n);
        whirl_chain_free(c);
    }
    fclose(fp);
}

/* The steady shape of mode `mode` at omega as positions (3 per mass) in the x-z plane. */
static int steady_positions(const whirl_chain *c, double omega, int mode, double *x)
{
    const size_t n = c->n;
    whirl_shape_info info;
    int status = whirl_nlink_solve(c, omega, mode, 0, &info);
    if (status != GSL_SUCCESS) return status;
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *ten = z + n + 1;
    status = whirl_nlink_positions(c, omega, info.tip_r, r, z, ten);
    for (size_t i = 0; i < n; i++) {
        x[3 * i] = r[i + 1] - r[0];
        x[3 * i + 1] = 0;
        x[3 * i + 2] = z[i + 1] - z[0];
    }
    free(r);
    return status;
}

static void bench_steady(const char *dir)
{
    const size_t n = 100;
    const double omega = 3.5, dt = 0.01, period = 2 * PI / omega;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    double *xt = malloc(3 * n * sizeof *xt), *y = malloc(6 * n * sizeof *y);
    if (steady_positions(c, omega, 2, x) != GSL_SUCCESS) die("steady shape");
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    FILE *fp = open_csv(dir, "dynamics_steady.csv");
    fprintf(fp, "# steady mode 2, omega 3.5, N 100, co-rotating, dt 0.01\n");
    fprintf(fp, "method,periods,deviation,max_constraint,sweeps_per_step,seconds\n");
    printf("steady mode 2 at omega = 3.5, N = 100, co-rotating, dt = 0.01, 100 periods:\n");
    const char *methods[] = {"gauss2", "gauss3"};
    for (int k = 0; k < 2; k++) {
        if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) die("set_state");
        whirl_integrator *it = whirl_integrator_alloc(methods[k], d);
        double t = 0, worst_c = 0, dev = 0;
        const double t0 = now();
        for (int p = 1; p <= 100; p++) {
            if (whirl_integrator_advance(it, &t, y, p * period, dt, 0) != GSL_SUCCESS)
                die("advance");
            whirl_dyn_diagnostics diag;
            whirl_dyn_diagnose(d, t, y, &diag);
            worst_c = fmax(worst_c, diag.constraint);
            if (p % 10 == 0) {
                whirl_dyn_get_state(d, t, y, WHIRL_FRAME_ROTATING, xt, v);
                dev = whirl_deviation(n, xt, x);
            }
        }
        const double secs = now() - t0;
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
    FILE *fp = open_csv(dir, "dynamics_stage_solver.csv");
    fprintf(fp, "n,method,h,seconds_per_unit_time,rhs_per_step,sweeps_per_step\n");
    printf("stage solver, mode 1 at omega = 2 perturbed, co-rotating (s per unit time):\n");
    const size_t sizes[] = {5, 10, 20, 40};
    for (size_t s = 0; s < 4; s++) {
        const size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
        double *y = malloc(6 * n * sizeof *y);
        if (steady_positions(c, 2.0, 1, x) != GSL_SUCCESS) die("steady shape");
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
                if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) die("set_state");
                whirl_integrator *it = whirl_integrator_alloc(methods[k], d);
                double t = 0;
                const double t0 = now();
                if (whirl_integrator_advance(it, &t, y, 0.5, h, 0) != GSL_SUCCESS) die("advance");
                secs[r] = (now() - t0) / 0.5;
                st = whirl_integrator_get_stats(it);
                whirl_integrator_free(it);
            }
            const double med = median(secs, 3);
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
    FILE *fp = open_csv(dir, "dynamics_energy.csv");
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
        smooth_state(c, p, x, v);
        if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) die("set_state");
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
        const double t0 = now();
        for (long done = 0; done < steps;) {
            const long target = next < steps ? next : steps;
            if (whirl_integrator_advance(it, &t, y, (double)target * h, h, 0) != GSL_SUCCESS)
                die("advance");
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
        const double secs = now() - t0;
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
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) die("set_state");
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
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) die("set_state kick");
    whirl_integrator *it = whirl_integrator_alloc("gauss2", d);
    double t = 0;
    const double h = 1e-4, t0 = now();
    const int status = whirl_integrator_advance(it, &t, y, 100 * h, h, 0);
    const double secs = now() - t0;
    whirl_dyn_diagnostics diag;
    whirl_dyn_diagnose(d, t, y, &diag);
    const whirl_integrator_stats s = whirl_integrator_get_stats(it);
    FILE *fp = open_csv(dir, "dynamics_large.csv");
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
    bench_cost(dir);
    bench_large(dir);
    bench_steady(dir);
    bench_stage_solver(dir);
    bench_energy(dir);
    return 0;
}
