/* Benchmark of the stability chart of the vertically shaken chain (whirl_chart_vertical): the
 * hanging chain of N equal links over rates 1 to 8 and amplitudes up to A_max (200 x 200), its
 * processor and wall time, the points, curves and modal monodromies, and the cost's growth in N;
 * then the inverted chain (rates 20 to 60, A <= 0.1). Not a test: times only.
 * Usage: bench_chart [OUT [hanging|inverted|both [N ...]]] (scripts/bench.sh passes its output
 * folder OUT, unused here; default both, N 1 3 10 30 100). Prints a table and the load. */
#define BENCH_NAME "bench_chart"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "bench_util.h"
#include "whirl/periodic.h"

typedef struct counted {
    long points;
    long monodromies;
    int curves;     /* distinct curve numbers (a joined curve takes another's: gaps) */
    char *seen;     /* per number, 1 once seen */
    int cap;
} counted;

static int count_point(void *data, const whirl_chart_point *p)
{
    counted *c = data;
    c->points++;
    if (p->curve >= c->cap) {
        const int cap = 2 * p->curve + 16;
        char *s = realloc(c->seen, (size_t)cap);
        if (s == NULL) bench_die("out of memory");
        memset(s + c->cap, 0, (size_t)(cap - c->cap));
        c->seen = s, c->cap = cap;
    }
    c->curves += !c->seen[p->curve];
    c->seen[p->curve] = 1;
    return 0;
}

static void count_tick(void *data, const whirl_chart_progress *p)
{
    ((counted *)data)->monodromies = p->monodromies;
}

static void run(int n, int inverted, double amp_max)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)n, 0);
    const whirl_chart_params p = {.inverted = inverted, .omega_min = inverted ? 20 : 1,
                                  .omega_max = inverted ? 60 : 8, .columns = 200,
                                  .amp_max = inverted ? 0.1 : amp_max, .rows = 200};
    counted k = {0, 0, 0, NULL, 0};
    /* the process's processor time: every thread of the chart (bench_cpu_now is the calling
       thread's alone) */
    const clock_t t0 = clock();
    const double w0 = bench_now();
    if (whirl_chart_vertical(c, 2, &p, count_point, &k, count_tick, &k)) bench_die("chart");
    const double cpu = (double)(clock() - t0) / CLOCKS_PER_SEC, wall = bench_now() - w0;
    printf("%-9s %5d %8ld %6d %12ld %10.3f %10.3f %10.3f\n", inverted ? "inverted" : "hanging", n,
           k.points, k.curves, k.monodromies, cpu, wall, 1e6 * cpu / (double)k.monodromies);
    fflush(stdout);
    free(k.seen);
    whirl_chain_free(c);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const double amp_max = 0.05;
    printf("# bench_chart: 200 x 200, hanging rates 1..8 A <= %g, inverted rates 20..60 "
           "A <= 0.1; load %.2f\n", amp_max, bench_load_average());
    /* monodromies: the modes' 2 x 2 ones counted by the chart, half a period each without drag */
    printf("# chain         N   points curves  monodromies    cpu [s]   wall [s]  us/mono\n");
    /* N = 100 (about 4 hours of processor time for the hanging chart: docs/theory/floquet.md)
       only when asked for */
    static const int defaults[] = {1, 3, 10, 30};
    const char *which = argc > 2 ? argv[2] : "both";
    for (int inverted = 0; inverted < 2; inverted++) {
        if (strcmp(which, "both") != 0 && strcmp(which, inverted ? "inverted" : "hanging") != 0)
            continue;
        if (argc > 3)
            for (int i = 3; i < argc; i++) run(atoi(argv[i]), inverted, amp_max);
        else
            for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; i++)
                run(defaults[i], inverted, amp_max);
    }
    printf("# load %.2f\n", bench_load_average());
    return 0;
}
