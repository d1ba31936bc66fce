/* Helpers shared by the benchmark programs (tests/bench_*.c) and tests/unit/dynamics/test_stress.c: monotonic
 * wall clock, median of repeats, opening a CSV under the output directory, fatal errors with the
 * library's message, steady shapes as positions.
 * Header-only (static functions); each program defines BENCH_NAME before including it. */
#ifndef WHIRL_BENCH_UTIL_H
#define WHIRL_BENCH_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "whirl/common.h"
#include "whirl/steady.h"

#ifndef BENCH_NAME
#error "define BENCH_NAME (the program's name, for messages) before including bench_util.h"
#endif

/* Seconds on the monotonic clock. */
static inline double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Processor seconds of the calling thread: less sensitive than the wall clock to other jobs
 * sharing the cores (not to their use of the caches and memory bandwidth). */
static inline double bench_cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int bench_cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of x[0..n-1] (sorts x in place). */
static inline double bench_median(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, bench_cmp_double);
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/* Prints the failure with whirl_last_error() and exits with status 1. */
static inline void bench_die(const char *what)
{
    fprintf(stderr, "%s: %s: %s\n", BENCH_NAME, what, whirl_last_error());
    exit(1);
}

/* dir/name opened for writing; exits with a message if that fails. */
static inline FILE *bench_open_csv(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "w");
    if (fp == NULL) {
        fprintf(stderr, "%s: cannot write %s\n", BENCH_NAME, path);
        exit(1);
    }
    return fp;
}

/* The 1-minute load average (other jobs share the cores), or -1 if unknown. */
static inline double bench_load_average(void)
{
    double load = -1;
    FILE *fp = fopen("/proc/loadavg", "r");
    if (fp != NULL) {
        if (fscanf(fp, "%lf", &load) != 1) load = -1;
        fclose(fp);
    }
    return load;
}

/* The N-link steady shape of mode `mode` at omega (whirl_nlink_solve_nodes) as positions x (3 per mass,
 * relative to the pivot) in the x-z plane. */
static inline int bench_steady_positions(const whirl_chain *c, double omega, int mode, double *x)
{
    const size_t n = c->n;
    whirl_shape_info info;
    double *r = malloc(3 * (n + 1) * sizeof *r);
    if (r == NULL) return GSL_ENOMEM;
    double *z = r + n + 1, *ten = z + n + 1;
    /* the nodes from the branch's own link angles, not rebuilt from the tip radius */
    int status = whirl_nlink_solve_nodes(c, omega, mode, &info, r, z, ten);
    for (size_t i = 0; i < n; i++) {
        x[3 * i] = r[i + 1] - r[0];
        x[3 * i + 1] = 0;
        x[3 * i + 2] = z[i + 1] - z[0];
    }
    free(r);
    return status;
}

/* The start of the chain scenes of bench_workprecision and bench_peers: the exact N-link steady
 * shape of mode 2 at omega (whirl_nlink_solve) as positions x (3 per mass), every link vector
 * turned by 1e-3 rad about the axis cos(2.385 i) y + sin(2.385 i) (u_i x y) (u_i its direction;
 * deterministic). Lengths are kept; the state is meant at rest in the frame co-rotating at omega. */
static inline int bench_scene_start(const whirl_chain *c, double omega, double *x)
{
    const int status = bench_steady_positions(c, omega, 2, x);
    if (status != GSL_SUCCESS) return status;
    /* turn each link vector d_i (in the x-z plane, so y is perpendicular to it) by 1e-3 rad */
    const double turn = 1e-3;
    double prev[3] = {0, 0, 0}, pos[3] = {0, 0, 0};
    for (size_t i = 0; i < c->n; i++) {
        double d[3], u[3];
        for (int k = 0; k < 3; k++) d[k] = x[3 * i + k] - prev[k];
        for (int k = 0; k < 3; k++) prev[k] = x[3 * i + k];
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; k++) u[k] = d[k] / len;
        const double e2[3] = {-u[2], 0, u[0]}; /* u x y */
        const double psi = 2.385 * (double)i;
        for (int k = 0; k < 3; k++) {
            const double b = cos(psi) * (k == 1) + sin(psi) * e2[k];
            pos[k] += len * (cos(turn) * u[k] + sin(turn) * b);
            x[3 * i + k] = pos[k];
        }
    }
    return GSL_SUCCESS;
}

/* A smooth non-trivial state: link i at theta = 0.5 + 0.3 sin(0.7 i), phi = 0.05 i, rates
 * 0.2 cos(i), 0.1 (positions and velocities, 3 per mass, pivot at p). */
static inline void bench_smooth_state(const whirl_chain *c, const double *p, double *x, double *v)
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

/* Work-precision: the time at error level e of a method's runs (count of them, errors err and
 * seconds secs, in refinement order), by log-log interpolation between consecutive runs that
 * bracket e, both at least 3 times floor_err (the reference's own error); NAN if no pair
 * brackets e. The fastest bracketing pair counts. */
static inline double bench_time_at(int count, const double *err, const double *secs, double e,
                                   double floor_err)
{
    double best = NAN;
    for (int j = 0; j + 1 < count; j++) {
        const double e0 = err[j], e1 = err[j + 1];
        if (!(e0 > 0 && e1 > 0) || e0 < 3 * floor_err || e1 < 3 * floor_err) continue;
        if (!((e0 >= e && e >= e1) || (e1 >= e && e >= e0))) continue;
        const double w = e0 == e1 ? 0 : log(e / e0) / log(e1 / e0);
        const double t = exp(log(secs[j]) + w * (log(secs[j + 1]) - log(secs[j])));
        if (!(t >= best)) best = t;
    }
    return best;
}

/* Least-squares slope of log y on log x over the n points (the exponent p of y ~ x^p). */
static inline double bench_fit_exponent(const double *x, const double *y, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; i++) {
        const double lx = log(x[i]), ly = log(y[i]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* Max over the n masses of the distance between x and ref (3 per mass). */
static inline double bench_max_distance(size_t n, const double *x, const double *ref)
{
    double worst = 0;
    for (size_t i = 0; i < n; i++) {
        const double dx = x[3 * i] - ref[3 * i], dy = x[3 * i + 1] - ref[3 * i + 1],
                     dz = x[3 * i + 2] - ref[3 * i + 2];
        worst = fmax(worst, sqrt(dx * dx + dy * dy + dz * dz));
    }
    return worst;
}

#endif
