/* One chain on two cores (whirl_dyn_set_threads). Usage: bench_threads [DIR]. For N = 10^4 ..
 * 10^6 (3D, Cartesian, the smooth state of bench_util.h): wall ns per link of one right-hand
 * side and of one rk4 step with 1 and with 2 threads, the two interleaved in every one of 9
 * rounds, medians; the speed-up is the ratio of the medians. The results with 2 threads are
 * checked bitwise equal to those with 1 first. Writes DIR/threads.csv (default out/bench) with
 * the load average, which decides the outcome: a fork-join per pass pays only when both cores
 * are free (on a shared machine a thread that loses its core holds up the other at the join). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/dynamics.h"
#include "whirl/integrator.h"

#define BENCH_NAME "bench_threads"
#include "bench_util.h"

#define ROUNDS 9

typedef struct setup {
    whirl_chain *chain;
    whirl_dyn *dyn[2]; /* 1 and 2 threads */
    whirl_integrator *rk4[2];
    double *y, *y_step, *dy[2];
} setup;

static void setup_alloc(setup *s, size_t n)
{
    memset(s, 0, sizeof *s);
    s->chain = whirl_chain_alloc_uniform(n, 0);
    if (s->chain == NULL) bench_die("chain");
    const whirl_model m = {.chain = s->chain, .dim = 3};
    for (int k = 0; k < 2; k++) {
        s->dyn[k] = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        if (s->dyn[k] == NULL || whirl_dyn_set_threads(s->dyn[k], k + 1) != GSL_SUCCESS)
            bench_die("dynamics");
        s->rk4[k] = whirl_integrator_alloc("rk4", s->dyn[k]);
        if (s->rk4[k] == NULL) bench_die("integrator");
    }
    const size_t size = whirl_dyn_size(s->dyn[0]);
    s->y = malloc(size * sizeof *s->y);
    s->y_step = malloc(size * sizeof *s->y_step);
    s->dy[0] = malloc(size * sizeof *s->dy[0]);
    s->dy[1] = malloc(size * sizeof *s->dy[1]);
    double *x = malloc(6 * n * sizeof *x), p[3] = {0, 0, 0};
    if (!s->y || !s->y_step || !s->dy[0] || !s->dy[1] || !x) bench_die("alloc");
    bench_smooth_state(s->chain, p, x, x + 3 * n);
    if (whirl_dyn_set_state(s->dyn[0], 0, x, x + 3 * n, s->y) != GSL_SUCCESS) bench_die("state");
    free(x);
}

static void setup_free(setup *s)
{
    for (int k = 0; k < 2; k++) {
        whirl_integrator_free(s->rk4[k]);
        whirl_dyn_free(s->dyn[k]);
        free(s->dy[k]);
    }
    free(s->y);
    free(s->y_step);
    whirl_chain_free(s->chain);
}

/* Wall ns per link of reps right-hand sides with dyn[k]. */
static double rhs_round(setup *s, int k, long reps)
{
    const double t0 = bench_now();
    for (long r = 0; r < reps; r++) whirl_dyn_rhs(1e-9 * (double)r, s->y, s->dy[k], s->dyn[k]);
    return (bench_now() - t0) / (double)reps / (double)s->chain->n * 1e9;
}

/* Wall ns per link of steps rk4 steps of h with rk4[k], from the smooth state. */
static double step_round(setup *s, int k, long steps, double h)
{
    memcpy(s->y_step, s->y, whirl_dyn_size(s->dyn[k]) * sizeof *s->y);
    double t = 0;
    const double t0 = bench_now();
    if (whirl_integrator_advance(s->rk4[k], &t, s->y_step, (double)steps * h, h, 0) !=
        GSL_SUCCESS)
        bench_die("steps");
    return (bench_now() - t0) / (double)steps / (double)s->chain->n * 1e9;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    enum { n_sizes = 5 };
    const size_t sizes[n_sizes] = {10000, 30000, 100000, 300000, 1000000};
    FILE *fp = bench_open_csv(dir, "threads.csv");
    const double load = bench_load_average();
    fprintf(fp, "# one chain on 1 and 2 threads (whirl_dyn_set_threads): wall ns per link, "
                "medians of %d interleaved rounds; load average %.2f at the start\n",
            ROUNDS, load);
    fprintf(fp, "n,rhs_1_ns_per_link,rhs_2_ns_per_link,rhs_speedup,rk4_1_ns_per_link,"
                "rk4_2_ns_per_link,rk4_speedup\n");
    printf("one chain on two cores (load average %.2f): wall ns per link, medians of %d "
           "interleaved rounds\n  %8s %10s %10s %8s %10s %10s %8s\n",
           load, ROUNDS, "N", "rhs 1 thr", "rhs 2 thr", "speedup", "rk4 1 thr", "rk4 2 thr",
           "speedup");
    for (int i = 0; i < n_sizes; i++) {
        const size_t n = sizes[i];
        setup s;
        setup_alloc(&s, n);
        /* the same numbers with two threads, bit for bit */
        whirl_dyn_rhs(0, s.y, s.dy[0], s.dyn[0]);
        whirl_dyn_rhs(0, s.y, s.dy[1], s.dyn[1]);
        if (memcmp(s.dy[0], s.dy[1], whirl_dyn_size(s.dyn[0]) * sizeof *s.y) != 0)
            bench_die("two threads changed the right-hand side");
        const long reps = (long)fmax(3, 3e6 / (double)n), steps = (long)fmax(2, 1e6 / (double)n);
        double rhs[2][ROUNDS], step[2][ROUNDS];
        for (int r = 0; r < ROUNDS; r++)
            for (int k0 = 0; k0 < 2; k0++) {
                const int k = (r + k0) % 2; /* alternate which goes first */
                rhs[k][r] = rhs_round(&s, k, reps);
                step[k][r] = step_round(&s, k, steps, 0.05 / (double)n);
            }
        const double r1 = bench_median(rhs[0], ROUNDS), r2 = bench_median(rhs[1], ROUNDS);
        const double s1 = bench_median(step[0], ROUNDS), s2 = bench_median(step[1], ROUNDS);
        fprintf(fp, "%zu,%.4g,%.4g,%.3g,%.4g,%.4g,%.3g\n", n, r1, r2, r1 / r2, s1, s2, s1 / s2);
        printf("  %8zu %10.3g %10.3g %8.2f %10.3g %10.3g %8.2f\n", n, r1, r2, r1 / r2, s1, s2,
               s1 / s2);
        fflush(stdout);
        setup_free(&s);
    }
    fclose(fp);
    return 0;
}
