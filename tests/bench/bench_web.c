/* The work of one rate change on the page (make web), timed: the continuum's shape of mode 2 at
 * 4 Hz of a 60 cm chain (whirl_continuum_solve and 201 samples), the linear verdict of the
 * 30-link chain there (whirl_stability_mode and the index), and the page's whole call
 * (whirl_web_shape: both, and the JSON). The same source runs natively and as WebAssembly under
 * Node (make web-bench; scripts/bench-web.sh prints the ratio): the median of REPEATS runs of
 * each, in milliseconds, one line "bench_web: NAME MS" per work. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#include "whirl/chain.h"
#include "whirl/dynamics.h"
#include "whirl/stability.h"
#include "whirl/steady.h"
#include "web/whirl_web.h"

#define REPEATS 21 /* odd: the median is one run */
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

static int page_call(void)
{
    char *a = whirl_web_shape("length=60cm&mass=50g&rate=4Hz&mode=2");
    const int status = a == NULL || a[2] == 'e' ? GSL_EFAILED : GSL_SUCCESS; /* {"error"... */
    whirl_web_free(a);
    return status;
}

static int run(const char *name, int (*work)(void))
{
    double t[REPEATS];
    for (int i = 0; i < REPEATS; i++) {
        const double t0 = now();
        if (work() != GSL_SUCCESS) {
            fprintf(stderr, "bench_web: %s failed: %s\n", name, whirl_last_error());
            return 1;
        }
        t[i] = now() - t0;
    }
    qsort(t, REPEATS, sizeof *t, ascending);
    printf("bench_web: %s %.3f\n", name, 1e3 * t[REPEATS / 2]);
    return 0;
}

int main(void)
{
    gsl_set_error_handler_off();
    return run("shape", shape) || run("verdict30", verdict) || run("page_call", page_call);
}
