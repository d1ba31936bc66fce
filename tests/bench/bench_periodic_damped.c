/* Benchmark of the damped chain's monodromy (whirl_periodic_alloc_model) against the
 * conservative chain's (whirl_periodic_alloc): the circle drive's mode-1 shape (omega = 2,
 * eps = 0.05) of N links in 3D, the same steps per period for both (the larger of the two
 * chains' bounds), the processor time of the monodromy by the variational equations at the
 * motion (the best of three), and the ratio. The damped chain: air drag c = 0.05, c2 = 0.02,
 * internal damping D (default 0.001; its start the driven shape with that drag). Not a test:
 * times only. Usage: bench_periodic_damped [-D D] [N ...] (default 10 30). Prints a table and
 * the load. */
#define BENCH_NAME "bench_periodic_damped"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "bench_util.h"
#include "periodic/periodic_internal.h"

/* The workspace of N links (damped or not) and its motion from the steady shape, solved with
 * steps per period (0: the default) and refined; *steps the steps the solve took. */
static whirl_periodic *motion(const whirl_chain *c, int damped, double damping, double **y,
                              int *steps)
{
    const whirl_model model = {.chain = c, .dim = 3, .air_drag = damped ? 0.05 : 0,
                               .air_drag_quadratic = damped ? 0.02 : 0,
                               .internal_damping = damped ? damping : 0};
    whirl_pivot_path path;
    whirl_pivot_circle(&path, 2, 0.05);
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    if (w == NULL) bench_die("alloc");
    *y = malloc(whirl_periodic_state_size(w) * sizeof **y);
    if (whirl_periodic_start_steady(w, 1, 1, *y)) bench_die("start");
    whirl_periodic_result r;
    const whirl_periodic_params p = {.steps = *steps, .refine = 0};
    if (whirl_periodic_find(w, *y, &p, &r)) bench_die("find");
    *steps = r.steps;
    return w;
}

static double monodromy_cpu(whirl_periodic *w, const double *y, int steps)
{
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        const double t0 = bench_cpu_now();
        if (periodic_monodromy_variational(w, y, steps)) bench_die("monodromy");
        best = fmin(best, bench_cpu_now() - t0);
    }
    return best;
}

static void run(int n, double damping)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)n, 0);
    double *y0, *y1;
    int s0 = 0, s1 = 0;
    whirl_periodic *w0 = motion(c, 0, 0, &y0, &s0), *w1 = motion(c, 1, damping, &y1, &s1);
    const int steps = s0 > s1 ? s0 : s1;
    if (s0 != steps) { /* the same steps for both */
        whirl_periodic_free(w0), free(y0);
        s0 = steps, w0 = motion(c, 0, 0, &y0, &s0);
    }
    if (s1 != steps) {
        whirl_periodic_free(w1), free(y1);
        s1 = steps, w1 = motion(c, 1, damping, &y1, &s1);
    }
    const double t0 = monodromy_cpu(w0, y0, steps), t1 = monodromy_cpu(w1, y1, steps);
    printf("%5d %6zu %6d %12.3f %12.3f %7.2f\n", n, whirl_periodic_tangent_size(w0), steps, t0,
           t1, t1 / t0);
    fflush(stdout);
    free(y0), free(y1);
    whirl_periodic_free(w0), whirl_periodic_free(w1);
    whirl_chain_free(c);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    double damping = 0.001;
    int first = 1;
    if (argc > 2 && strcmp(argv[1], "-D") == 0) damping = atof(argv[2]), first = 3;
    printf("# bench_periodic_damped: circle drive omega=2 eps=0.05 mode 1, 3D; damped: c=0.05 "
           "c2=0.02 D=%g; load %.2f\n", damping, bench_load_average());
    printf("#   N      m  steps  conservative [s]  damped [s]  ratio  (processor time of one "
           "monodromy, best of 3)\n");
    static const int defaults[] = {10, 30};
    if (argc > first)
        for (int i = first; i < argc; i++) run(atoi(argv[i]), damping);
    else
        for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; i++) run(defaults[i], damping);
    printf("# load %.2f\n", bench_load_average());
    return 0;
}
