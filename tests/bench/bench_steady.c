/* Benchmark and accuracy study of the steady shapes. Writes CSV under argv[1] (default
 * out/bench) and prints the figures:
 *  - continuum branches: modes 1-3 x 1001 rates (omega 1.25..10) by continuation, wall time
 *    (median of 5) on all threads and on one, and the accuracy of those rows against solves
 *    at ODE tolerance 1e-15;
 *  - N-link (N = 100): fresh solves per second, and per second along a branch;
 *  - N-link -> continuum: relative errors of tip_r, top_tension, depth and of the critical
 *    rates for N = 10 .. 1000 and the observed order between successive N;
 *  - near-critical accuracy (omega = omega_k (1 + eps)) against tolerance 1e-15;
 *  - Kolodner's count on a fine grid: number of roots of r(pivot; a) against the number of
 *    critical rates below omega. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <omp.h>

#include "whirl/steady.h"

#define BENCH_NAME "bench_steady"
#include "bench_util.h"

#define REPEATS 5

static double rel(double x, double ref) { return fabs(x / ref - 1); }

/* Modes 1-3 over 1001 rates: wall seconds (median), with `threads` threads; *cpu receives the
 * processor seconds (median; all threads summed). */
static double time_branches(int threads, const double *omega, size_t n, whirl_shape_info *info,
                            int *exists, double *cpu)
{
    double t[REPEATS], c[REPEATS];
    omp_set_num_threads(threads);
    for (int rep = 0; rep <= REPEATS; rep++) { /* the first run warms up */
        double t0 = omp_get_wtime();
        clock_t c0 = clock();
        for (int k = 1; k <= 3; k++)
            if (whirl_continuum_branch(k, 0, n, omega, info + (size_t)(k - 1) * n,
                                       exists + (size_t)(k - 1) * n) != GSL_SUCCESS)
                bench_die("continuum branch");
        if (rep > 0) {
            t[rep - 1] = omp_get_wtime() - t0;
            c[rep - 1] = (double)(clock() - c0) / CLOCKS_PER_SEC;
        }
    }
    *cpu = bench_median(c, REPEATS);
    return bench_median(t, REPEATS);
}

static void bench_continuum_branches(const char *dir, FILE *summary)
{
    enum { n = 1001 };
    static double omega[n];
    static whirl_shape_info info[3 * n];
    static int exists[3 * n];
    for (int j = 0; j < n; j++) omega[j] = 1.25 + 8.75 * j / (n - 1);
    int threads = omp_get_max_threads();
    double cpu_all, cpu_one;
    double t_all = time_branches(threads, omega, n, info, exists, &cpu_all);
    double t_one = time_branches(1, omega, n, info, exists, &cpu_one);
    omp_set_num_threads(threads);
    int rows = 0;
    for (int j = 0; j < 3 * n; j++) rows += exists[j];
    /* accuracy of every 10th row against tolerance 1e-15 */
    double worst[3] = {0, 0, 0};
    for (int k = 1; k <= 3; k++)
        for (int j = 0; j < n; j += 10) {
            const whirl_shape_info *f = &info[(k - 1) * n + j];
            if (!exists[(k - 1) * n + j]) continue;
            whirl_shape_info ref;
            if (whirl_continuum_solve_tol(omega[j], k, 0, 0, 1e-15, &ref) != GSL_SUCCESS)
                bench_die("reference solve");
            worst[0] = fmax(worst[0], rel(f->tip_r, ref.tip_r));
            worst[1] = fmax(worst[1], rel(f->top_tension, ref.top_tension));
            worst[2] = fmax(worst[2], rel(f->depth, ref.depth));
        }
    printf("continuum branches, modes 1-3 x %d rates (omega 1.25..10), %d rows:\n"
           "  wall %.3f s on %d threads, %.3f s on 1 thread (median of %d; processor time "
           "%.3f s and %.3f s)\n"
           "  worst relative error vs tol 1e-15 (every 10th rate): tip_r %.1e, top_tension "
           "%.1e, depth %.1e\n",
           n, rows, t_all, threads, t_one, REPEATS, cpu_all, cpu_one, worst[0], worst[1],
           worst[2]);
    fprintf(summary, "continuum_branches_3x1001_wall_s,%d,%.6g\n"
                     "continuum_branches_3x1001_wall_s,1,%.6g\n"
                     "continuum_branches_3x1001_cpu_s,1,%.6g\n", threads, t_all, t_one, cpu_one);
    FILE *fp = bench_open_csv(dir, "steady_branches.csv");
    fprintf(fp, "omega,mode,tip_r,max_r,top_tension,depth\n");
    for (int k = 1; k <= 3; k++)
        for (int j = 0; j < n; j++)
            if (exists[(k - 1) * n + j]) {
                const whirl_shape_info *f = &info[(k - 1) * n + j];
                fprintf(fp, "%.17g,%d,%.17g,%.17g,%.17g,%.17g\n", omega[j], k, f->tip_r,
                        f->max_r, f->top_tension, f->depth);
            }
    fclose(fp);
}

static void bench_nlink_rate(FILE *summary)
{
    whirl_chain *c = whirl_chain_alloc_uniform(100, 0);
    double crit[3];
    if (c == NULL || whirl_nlink_critical(c, 3, crit) != GSL_SUCCESS) bench_die("nlink setup");
    enum { n = 300 };
    double omega[n], t[REPEATS];
    for (int j = 0; j < n; j++) omega[j] = crit[2] * 1.001 + (10 - crit[2]) * j / (n - 1);
    whirl_shape_info info;
    for (int rep = 0; rep <= REPEATS; rep++) {
        double t0 = omp_get_wtime();
        for (int k = 1; k <= 3; k++)
            for (int j = 0; j < n; j++)
                if (whirl_nlink_solve(c, omega[j], k, &info) != GSL_SUCCESS) bench_die("nlink solve");
        if (rep > 0) t[rep - 1] = omp_get_wtime() - t0;
    }
    double fresh = 3 * n / bench_median(t, REPEATS);
    static whirl_shape_info binfo[n];
    int exists[n];
    omp_set_num_threads(1);
    for (int rep = 0; rep <= REPEATS; rep++) {
        double t0 = omp_get_wtime();
        for (int k = 1; k <= 3; k++)
            if (whirl_nlink_branch(c, k, n, omega, binfo, exists) != GSL_SUCCESS)
                bench_die("nlink branch");
        if (rep > 0) t[rep - 1] = omp_get_wtime() - t0;
    }
    omp_set_num_threads(omp_get_num_procs());
    double branch = 3 * n / bench_median(t, REPEATS);
    printf("N-link N = 100, modes 1-3 at omega_3..10 (one thread): %.0f fresh shapes/s, %.0f "
           "shapes/s along a branch\n", fresh, branch);
    fprintf(summary, "nlink100_fresh_shapes_per_s,1,%.6g\nnlink100_branch_shapes_per_s,1,%.6g\n",
            fresh, branch);
    whirl_chain_free(c);
}

static void bench_convergence(const char *dir)
{
    const size_t sizes[] = {10, 20, 50, 100, 200, 500, 1000};
    const size_t ns = sizeof sizes / sizeof *sizes;
    const double omega = 7.2791, tip_masses[2] = {0, 0.4821};
    FILE *fp = bench_open_csv(dir, "steady_nlink_convergence.csv");
    fprintf(fp, "tip_mass,mode,N,err_tip_r,err_top_tension,err_depth,err_critical,"
                "order_tip_r,order_top_tension,order_depth,order_critical\n");
    printf("N-link -> continuum at omega = %g: relative errors and observed order "
           "log(e(N1)/e(N2))/log(N2/N1)\n", omega);
    for (int t = 0; t < 2; t++)
        for (int k = 1; k <= 3; k++) {
            whirl_shape_info cont;
            double crit_cont;
            if (whirl_continuum_solve(omega, k, tip_masses[t], 0, &cont) != GSL_SUCCESS ||
                whirl_continuum_critical(k, tip_masses[t], &crit_cont) != GSL_SUCCESS)
                bench_die("continuum reference");
            double prev[4] = {0, 0, 0, 0};
            printf("  tip mass %g, mode %d:\n", tip_masses[t], k);
            for (size_t s = 0; s < ns; s++) {
                whirl_chain *c = whirl_chain_alloc_uniform(sizes[s], tip_masses[t]);
                whirl_shape_info d;
                double crit[3];
                if (whirl_nlink_solve(c, omega, k, &d) != GSL_SUCCESS ||
                    whirl_nlink_critical(c, 3, crit) != GSL_SUCCESS)
                    bench_die("nlink solve");
                double e[4] = {rel(d.tip_r, cont.tip_r), rel(d.top_tension, cont.top_tension),
                               rel(d.depth, cont.depth), rel(crit[k - 1], crit_cont)};
                /* observed order against the previous N (none for the first: left empty) */
                char order[4][16] = {"", "", "", ""};
                const double ratio = s ? (double)sizes[s] / (double)sizes[s - 1] : 0;
                for (int q = 0; s && q < 4; q++)
                    snprintf(order[q], sizeof order[q], "%.4f", log(prev[q] / e[q]) / log(ratio));
                fprintf(fp, "%g,%d,%zu,%.6e,%.6e,%.6e,%.6e,%s,%s,%s,%s\n", tip_masses[t], k,
                        sizes[s], e[0], e[1], e[2], e[3], order[0], order[1], order[2], order[3]);
                printf("    N=%4zu  tip_r %.3e (%6.6s)  top_tension %.3e (%6.6s)  depth %.3e "
                       "(%6.6s)  omega_k %.3e (%6.6s)\n", sizes[s], e[0], order[0], e[1],
                       order[1], e[2], order[2], e[3], order[3]);
                memcpy(prev, e, sizeof prev);
                whirl_chain_free(c);
            }
        }
    fclose(fp);
}

static void bench_near_critical(void)
{
    printf("near-critical continuum accuracy vs tol 1e-15 (relative error of tip_r; top_tension, "
           "depth)\n");
    const double eps[] = {1e-2, 1e-4, 1e-6};
    for (int k = 1; k <= 6; k++) {
        double omega_k;
        whirl_continuum_critical(k, 0, &omega_k);
        printf("  mode %d:", k);
        for (int e = 0; e < 3; e++) {
            whirl_shape_info a, b;
            if (whirl_continuum_solve(omega_k * (1 + eps[e]), k, 0, 0, &a) != GSL_SUCCESS ||
                whirl_continuum_solve_tol(omega_k * (1 + eps[e]), k, 0, 0, 1e-15, &b) !=
                    GSL_SUCCESS)
                bench_die("near-critical solve");
            printf("  eps %.0e: %.1e; %.1e, %.1e", eps[e], rel(a.tip_r, b.tip_r),
                   rel(a.top_tension, b.top_tension), rel(a.depth, b.depth));
        }
        printf("\n");
    }
}

static void bench_kolodner(const char *dir)
{
    enum { nrates = 400, na = 800 };
    double crit[9];
    for (int k = 1; k <= 9; k++) whirl_continuum_critical(k, 0, &crit[k - 1]);
    FILE *fp = bench_open_csv(dir, "steady_kolodner.csv");
    fprintf(fp, "omega,critical_below,roots\n");
    int mismatches = 0;
    double s[2], r[2], z[2], t[2];
    for (int j = 0; j < nrates; j++) {
        double omega = 0.3 + 13.7 * (j + 0.5) / nrates;
        int n = 0;
        while (n < 9 && crit[n] < omega) n++;
        int roots = 0, sign = 0;
        for (int i = 0; i <= na; i++) {
            double a = fmin(1, pow(10, -7 + 7.0 * i / na));
            if (whirl_continuum_sample(omega, 0, a, 2, s, r, z, t) != GSL_SUCCESS) bench_die("sample");
            int sg = r[0] > 0 ? 1 : -1;
            if (sign != 0 && sg != sign) roots++;
            sign = sg;
        }
        mismatches += roots != n;
        fprintf(fp, "%.17g,%d,%d\n", omega, n, roots);
    }
    fclose(fp);
    printf("Kolodner count: %d rates in 0.3..14 (modes 0..8), %d tip radii each: %d mismatches "
           "between the roots of r(pivot; a) and the number of critical rates below omega\n",
           nrates, na + 1, mismatches);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    gsl_set_error_handler_off();
    const double load = bench_load_average();
    if (load >= 0) printf("load average at start (other jobs share the cores): %.2f\n", load);
    FILE *summary = bench_open_csv(dir, "steady_timing.csv");
    fprintf(summary, "case,threads,value\n");
    bench_continuum_branches(dir, summary);
    bench_nlink_rate(summary);
    fclose(summary);
    bench_near_critical();
    bench_convergence(dir);
    bench_kolodner(dir);
    return 0;
}
