/* Benchmark of the periodic motions (whirl/periodic.h): the multipliers of the circle drive's
 * mode-1 shape (omega = 2, eps = 0.05, the steady shape of whirl_stability_driven_mode as the
 * start) for N links, in 3D: the processor time of whirl_periodic_find (Newton's iterations,
 * the monodromy at the coarser and the finer step, the eigenvalues), the steps per period the
 * chain's bound asks for, and the cost's growth in N. Not a test: times only.
 * Usage: bench_periodic [N ...] (default 5 10 20 30 60). Prints a table and the load. */
#define BENCH_NAME "bench_periodic"
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>

#include "bench_util.h"
#include "whirl/periodic.h"
#include "whirl/stability.h"

static void run(int n)
{
    const double omega = 2, eps = 0.05;
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)n, 0);
    whirl_stability *st = whirl_stability_alloc((size_t)n);
    const whirl_model model = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                               .omega = omega, .drive_radius = eps};
    double growth;
    if (whirl_stability_driven_mode(st, &model, 1, 1, NULL, &growth)) bench_die("driven mode");
    const double *x, *y, *z;
    whirl_stability_nodes(st, &x, &y, &z);
    double *links = malloc(3 * (size_t)n * sizeof *links);
    if (whirl_shape_links((size_t)n, x, y, z, links)) bench_die("links");
    whirl_pivot_path path;
    whirl_pivot_circle(&path, omega, eps);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    if (w == NULL) bench_die("alloc");
    double *state = malloc(whirl_periodic_state_size(w) * sizeof *state);
    if (whirl_dyn_state_from_shape(whirl_periodic_dyn(w), 0, links, omega, state))
        bench_die("start");
    whirl_periodic_result r;
    const whirl_periodic_params p = {.refine = 1};
    const double t0 = bench_cpu_now(), w0 = bench_now();
    if (whirl_periodic_find(w, state, &p, &r)) bench_die("find");
    const double cpu = bench_cpu_now() - t0, wall = bench_now() - w0;
    printf("%5d %6zu %6d %4d %10.3f %10.3f %10.3g %10.3g %.12f %s\n", n, r.count, r.steps,
           r.iterations, cpu, wall, r.reciprocal_err, r.max_modulus_err, r.max_modulus,
           whirl_floquet_verdict_name(r.verdict));
    fflush(stdout);
    free(state);
    free(links);
    whirl_periodic_free(w);
    whirl_stability_free(st);
    whirl_chain_free(c);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    printf("# bench_periodic: circle drive omega=2 eps=0.05 mode 1, 3D, from the steady shape; "
           "load %.2f\n", bench_load_average());
    printf("#   N      m  steps iter    cpu [s]   wall [s]   recip_err    mu_err  |mu|max\n");
    static const int defaults[] = {5, 10, 20, 30, 60};
    if (argc > 1)
        for (int i = 1; i < argc; i++) run(atoi(argv[i]));
    else
        for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; i++) run(defaults[i]);
    printf("# load %.2f\n", bench_load_average());
    return 0;
}
