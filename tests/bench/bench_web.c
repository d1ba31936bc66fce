/* The work of one rate change on the page (make web), timed: the continuum's shape of mode 2 at
 * 4 Hz of a 60 cm chain (whirl_continuum_solve and 201 samples), the linear verdict of the
 * 30-link chain there (whirl_stability_mode and the index), and the page's whole call
 * (whirl_web_shape: both, and the JSON); 1000 gauss2 steps of a 100-link chain; and the page's
 * perturbed run (whirl_web_run: 40 turns of the 30-link chain, 10 s of motion). The same source
 * runs natively and as WebAssembly under Node (scripts/bench-web.sh prints the ratio): the
 * median of REPEATS runs of each (RUN_REPEATS of the run), in milliseconds, one line
 * "bench_web: NAME MS" per work. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#include "whirl/chain.h"
#include "whirl/dynamics.h"
#include "whirl/integrator.h"
#include "whirl/stability.h"
#include "whirl/steady.h"
#include "web/whirl_web.h"

#define REPEATS 21 /* odd: the median is one run */
#define RUN_REPEATS 5 /* of the page's whole run (0.6 s natively) */
#define POINTS 201 /* the page's samples of the continuum */

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int ascending(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* 60 cm: omega = 4 Hz in units of sqrt(g/L) */
static double rate(void) { return 4 * 2 * M_PI * sqrt(0.6 / 9.80665); }

static int shape(void)
{
    whirl_shape_info info;
    double s[POINTS], r[POINTS], z[POINTS], t[POINTS];
    int status = whirl_continuum_solve(rate(), 2, 0, 0, &info);
    if (status == GSL_SUCCESS) status = whirl_continuum_sample(rate(), 0, info.tip_r, POINTS, s, r, z, t);
    return status;
}

static int verdict(void)
{
    whirl_chain *c = whirl_chain_alloc_uniform(30, 0);
    whirl_stability *w = c ? whirl_stability_alloc(30) : NULL;
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = rate()};
    double growth;
    int index;
    int status = w ? whirl_stability_mode(w, &m, 2, NULL, &growth) : GSL_ENOMEM;
    if (status == GSL_SUCCESS) status = whirl_stability_index(w, &index);
    whirl_stability_free(w);
    whirl_chain_free(c);
    return status;
}

/* 1000 gauss2 steps of the 100-link chain hanging with the lower half kicked sideways (the
 * step 1e-3 sqrt(L/g): below the fixed-point iteration's bound h omega_max < 1, omega_max ~ 2N) */
static int run100(void)
{
    enum { N = 100, STEPS = 1000 };
    whirl_chain *c = whirl_chain_alloc_uniform(N, 0);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = c ? whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN) : NULL;
    double x[3 * N] = {0}, v[3 * N] = {0}, y[6 * N];
    double z = 0;
    int status = d ? GSL_SUCCESS : GSL_ENOMEM;
    for (size_t i = 0; c && i < N; i++) x[3 * i + 2] = z -= c->length[i];
    for (size_t i = N / 2; i < N; i++) v[3 * i] = 0.01 * (double)(i - N / 2) / N;
    if (status == GSL_SUCCESS) status = whirl_dyn_set_state(d, 0, x, v, y);
    whirl_integrator *it = status == GSL_SUCCESS ? whirl_integrator_alloc("gauss2", d) : NULL;
    const double h = 1e-3;
    double t = 0;
    if (it == NULL && status == GSL_SUCCESS) status = GSL_ENOMEM;
    if (status == GSL_SUCCESS) status = whirl_integrator_advance(it, &t, y, STEPS * h, h, 0);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    return status;
}

static int page_call(void)
{
    char *a = whirl_web_shape("length=60cm&mass=50g&rate=4Hz&mode=2");
    const int status = a == NULL || a[2] == 'e' ? GSL_EFAILED : GSL_SUCCESS; /* {"error"... */
    whirl_web_free(a);
    return status;
}

/* the page's perturbed run, whole: 40 turns at 4 Hz (10 s of motion) of the 30-link chain, its
 * 401 frames as the Worker asks for them (10 at a time) */
static int page_run(void)
{
    whirl_web_run *r = whirl_web_run_alloc("length=60cm&mass=50g&rate=4Hz&mode=2");
    int status = r ? GSL_CONTINUE : GSL_ENOMEM;
    while (status == GSL_CONTINUE) {
        char *a = whirl_web_run_next(r, 10);
        status = a == NULL || a[2] == 'e' ? GSL_EFAILED
                 : strstr(a, "\"done\":true") ? GSL_SUCCESS : GSL_CONTINUE;
        whirl_web_free(a);
    }
    whirl_web_run_free(r);
    return status;
}

static int run(const char *name, int (*work)(void), int repeats)
{
    double t[REPEATS];
    for (int i = 0; i < repeats; i++) {
        const double t0 = now();
        if (work() != GSL_SUCCESS) {
            fprintf(stderr, "bench_web: %s failed: %s\n", name, whirl_last_error());
            return 1;
        }
        t[i] = now() - t0;
    }
    qsort(t, (size_t)repeats, sizeof *t, ascending);
    printf("bench_web: %s %.3f\n", name, 1e3 * t[repeats / 2]);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    return run("shape", shape, REPEATS) || run("verdict30", verdict, REPEATS) ||
           run("page_call", page_call, REPEATS) || run("run100_1000steps", run100, REPEATS) ||
           run("page_run_10s", page_run, RUN_REPEATS);
}
