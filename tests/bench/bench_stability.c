/* Benchmark of the linear stability analysis (whirl/stability.h). Writes
 * argv[1]/stability_timing.csv (default out/bench) and prints, for N = 25, 50, 100 links, the
 * wall time (median of 7 after a warm-up, one thread) of
 *  - whirl_stability_mode: the steady shape, the matrices, the deflated eigenproblem (4N - 2);
 *  - its parts: the shape alone (whirl_nlink_solve) and the linearisation + eigenvalues;
 *  - GSL's gsl_eigen_nonsymm on the same full first-order matrix, for comparison with LAPACK's
 *    dgeev used by the library (ratio within one run);
 * and the processor time of the analysis (median), less sensitive to other loads on the machine
 * than the wall time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>

#include "whirl/stability.h"

#define REPEATS 7
#define BENCH_NAME "bench_stability"
#include "bench_util.h"

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The full first-order matrix [[0, I], [-M^-1 K, -M^-1 (G + C)]] of the last linearisation. */
static gsl_matrix *first_order(const whirl_stability *w, size_t n)
{
    const size_t q = 2 * n, y = 4 * n;
    gsl_matrix *chol = gsl_matrix_alloc(q, q), *a = gsl_matrix_calloc(y, y);
    gsl_vector *col = gsl_vector_alloc(q);
    const double *m = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
    const double *g = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
    const double *k = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    memcpy(chol->data, m, q * q * sizeof(double));
    gsl_linalg_cholesky_decomp1(chol);
    for (size_t j = 0; j < y; j++) {
        for (size_t i = 0; i < q; i++)
            gsl_vector_set(col, i, j < q ? k[i * q + j] : g[i * q + j - q]);
        gsl_linalg_cholesky_svx(chol, col);
        for (size_t i = 0; i < q; i++) gsl_matrix_set(a, q + i, j, -gsl_vector_get(col, i));
    }
    for (size_t i = 0; i < q; i++) gsl_matrix_set(a, i, q + i, 1);
    gsl_vector_free(col);
    gsl_matrix_free(chol);
    return a;
}

int main(int argc, char **argv)
{
    FILE *fp = bench_open_csv(argc > 1 ? argv[1] : "out/bench", "stability_timing.csv");
    printf("load average %.2f (2 shared cores: wall times are noisy)\n", bench_load_average());
    gsl_set_error_handler_off();
    fprintf(fp, "links,mode,omega,seconds_total,cpu_seconds_total,seconds_shape,seconds_linear,"
                "seconds_gsl_full\n");
    const size_t links[] = {25, 50, 100};
    const double omega = 6.0;
    const int mode = 3;
    for (size_t s = 0; s < sizeof links / sizeof links[0]; s++) {
        const size_t n = links[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        whirl_stability *w = whirl_stability_alloc(n);
        if (c == NULL || w == NULL) bench_die("alloc");
        whirl_model m = {0};
        m.chain = c;
        m.dim = 3;
        m.omega = omega;
        whirl_shape_info info;
        double growth, t_total[REPEATS], t_shape[REPEATS], t_lin[REPEATS], t_gsl[REPEATS];
        double t_cpu[REPEATS];
        if (whirl_stability_mode(w, &m, mode, &info, &growth)) bench_die("warm-up");
        for (int r = 0; r < REPEATS; r++) {
            double c0 = cpu_now(), t0 = bench_now();
            if (whirl_stability_mode(w, &m, mode, &info, &growth)) bench_die("analysis");
            double t1 = bench_now();
            t_cpu[r] = cpu_now() - c0;
            if (whirl_nlink_solve(c, omega, mode, &info)) bench_die("shape");
            double t2 = bench_now();
            if (whirl_stability_shape(w, &m, info.tip_r, &growth)) bench_die("linearisation");
            double t3 = bench_now();
            t_total[r] = t1 - t0;
            t_shape[r] = t2 - t1;
            t_lin[r] = t3 - t2;
            gsl_matrix *a = first_order(w, n);
            gsl_vector_complex *e = gsl_vector_complex_alloc(4 * n);
            gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc(4 * n);
            double t4 = bench_now();
            if (gsl_eigen_nonsymm(a, e, ws)) bench_die("gsl_eigen_nonsymm");
            t_gsl[r] = bench_now() - t4;
            gsl_eigen_nonsymm_free(ws);
            gsl_vector_complex_free(e);
            gsl_matrix_free(a);
        }
        const double mt = bench_median(t_total, REPEATS), ms = bench_median(t_shape, REPEATS);
        const double ml = bench_median(t_lin, REPEATS), mg = bench_median(t_gsl, REPEATS);
        const double mc = bench_median(t_cpu, REPEATS);
        fprintf(fp, "%zu,%d,%.17g,%.6g,%.6g,%.6g,%.6g,%.6g\n", n, mode, omega, mt, mc, ms, ml, mg);
        printf("N = %3zu (mode %d, omega %g, growth %.6g): analysis %.4f s wall, %.4f s cpu "
               "(shape %.4f s, linearisation + eigenvalues %.4f s); GSL nonsymm on the full "
               "matrix %.4f s\n", n, mode, omega, growth, mt, mc, ms, ml, mg);
        whirl_stability_free(w);
        whirl_chain_free(c);
    }
    fclose(fp);
    return 0;
}
