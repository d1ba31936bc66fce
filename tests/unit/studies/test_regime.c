/* Tests of the spin-up from rest (include/whirl/regime.h) against independent references:
 *  - the node count of a polyline agrees with driven.c's own count on its exact steady shapes of
 *    modes 1-3 (the N-link chain, with drive and drag), and with hand-made planar polylines;
 *  - a settled run is the boundary-value shape with drag (driven.h, a different method: Newton
 *    on the tip) to within the settling tolerance, with the same node count;
 *  - the same physics integrated in the inertial frame settles onto the same shape;
 *  - the settled shape does not depend on the step (a fixed point of the co-rotating equations is
 *    one of every Runge-Kutta map), nor on the random turns of the start;
 *  - runs are deterministic (bitwise), and the first point of a sweep is the run from rest;
 *  - a violently driven chain (above the third critical rate, large eps) is found chaotic with a
 *    positive Lyapunov exponent; the observer sees the frame turn at omega;
 *  - every invalid parameter is refused with GSL_EINVAL. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#include "whirl/driven.h"
#include "whirl/regime.h"

#define LINKS 12

static whirl_regime_params params(double omega, double eps, double drag)
{
    whirl_regime_params p = whirl_regime_defaults(LINKS);
    p.omega = omega;
    p.drive_radius = eps;
    p.air_drag = drag;
    p.t_max = 300;
    return p;
}

/* Planar zigzags of k - 1 crossings below the pivot count k nodes, tilted out of the plane. */
static void test_nodes_polyline(void **state)
{
    (void)state;
    enum { NPTS = 61 };
    double pos[3 * NPTS];
    for (int k = 1; k <= 4; k++) {
        const double eps = 0.037, tilt = 0.3;
        for (int i = 0; i < NPTS; i++) {
            const double s = (double)i / (NPTS - 1); /* from the pivot */
            /* sin((k - 1/2) pi s) has k - 1 zeros in (0, 1] after the pivot's */
            const double r = 0.2 * sin((k - 0.5) * M_PI * s);
            pos[3 * i] = eps + r * cos(tilt);
            pos[3 * i + 1] = r * sin(tilt);
            pos[3 * i + 2] = -s;
        }
        assert_int_equal(whirl_driven_nodes(eps, NPTS, pos, NULL), k);
    }
}

/* driven.c's exact shapes of modes 1..3 with drive and drag: the same node counts. */
static void test_nodes_driven(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(30, 0);
    double x[31], y[31], z[31], pos[3 * 31];
    for (int mode = 1; mode <= 3; mode++) {
        const whirl_driven_params dp = {.omega = 5.1, .drive_radius = 0.013, .air_drag = 0.021,
                                        .air_drag_quadratic = 0.0144};
        whirl_driven_info info;
        assert_int_equal(whirl_driven_mode(chain, &dp, mode, 1, &info), GSL_SUCCESS);
        assert_int_equal(whirl_driven_sample(chain, &dp, info.tip, 31, NULL, x, y, z, NULL),
                         GSL_SUCCESS);
        for (int i = 0; i < 31; i++)
            pos[3 * i] = x[i], pos[3 * i + 1] = y[i], pos[3 * i + 2] = z[i];
        assert_int_equal(whirl_driven_nodes(dp.drive_radius, 31, pos, chain->length), info.nodes);
        assert_int_equal(info.nodes, mode);
    }
    whirl_chain_free(chain);
}

/* Equal results, field by field (the struct has padding). */
static void assert_same(const whirl_regime_result *a, const whirl_regime_result *b)
{
    assert_int_equal(a->state, b->state);
    assert_int_equal(a->nodes, b->nodes);
    assert_int_equal(a->period, b->period);
    assert_int_equal(a->bvp_nodes, b->bvp_nodes);
    assert_int_equal(a->steps, b->steps);
    const double va[] = {a->t_end, a->change, a->remaining, a->shape_error, a->lyapunov,
                         a->tip[0], a->tip[1], a->tip[2], a->tip_r};
    const double vb[] = {b->t_end, b->change, b->remaining, b->shape_error, b->lyapunov,
                         b->tip[0], b->tip[1], b->tip[2], b->tip_r};
    for (size_t k = 0; k < sizeof va / sizeof va[0]; k++)
        assert_true(va[k] == vb[k] || (isnan(va[k]) && isnan(vb[k])));
}

static whirl_regime_result run(const whirl_chain *chain, const whirl_regime_params *p)
{
    whirl_regime *w = whirl_regime_alloc(chain);
    assert_non_null(w);
    whirl_regime_result r;
    assert_int_equal(whirl_regime_run(w, p, &r), GSL_SUCCESS);
    whirl_regime_free(w);
    return r;
}

/* Strong drag: the chain settles, onto the boundary-value shape with drag, in both frames. */
static void test_settles_onto_steady_shape(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(LINKS, 0);
    const double omega[] = {0.83, 2.1, 3.4}; /* below omega_1, between 1-2, between 2-3 */
    for (size_t k = 0; k < sizeof omega / sizeof omega[0]; k++) {
        whirl_regime_params p = params(omega[k], 0.061, 0.23);
        const whirl_regime_result r = run(chain, &p);
        assert_int_equal(r.state, WHIRL_REGIME_SETTLED);
        assert_int_equal(r.period, 1);
        assert_int_equal(r.nodes, r.bvp_nodes);
        assert_true(r.shape_error < p.settle_tol);
        /* the inertial frame: the same shape, up to the settling tolerance of both runs */
        p.frame = WHIRL_FRAME_INERTIAL;
        const whirl_regime_result ri = run(chain, &p);
        assert_int_equal(ri.state, WHIRL_REGIME_SETTLED);
        assert_int_equal(ri.nodes, r.nodes);
        assert_true(hypot(hypot(ri.tip[0] - r.tip[0], ri.tip[1] - r.tip[1]), ri.tip[2] - r.tip[2]) <
                    2 * p.settle_tol);
    }
    whirl_chain_free(chain);
}

/* The settled shape is the same for half the step and for other random turns of the start. */
static void test_step_and_seed(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_regime_params p = params(3.4, 0.061, 0.23);
    p.settle_tol = 1e-7;
    p.t_max = 600;
    const whirl_regime_result a = run(chain, &p);
    p.dt /= 2;
    const whirl_regime_result b = run(chain, &p);
    p.dt *= 2;
    p.seed = 977;
    const whirl_regime_result c = run(chain, &p);
    assert_int_equal(a.state, WHIRL_REGIME_SETTLED);
    assert_int_equal(b.state, WHIRL_REGIME_SETTLED);
    assert_int_equal(c.state, WHIRL_REGIME_SETTLED);
    assert_true(a.shape_error < 1e-7 && b.shape_error < 1e-7 && c.shape_error < 1e-7);
    for (int k = 0; k < 3; k++) {
        assert_true(fabs(a.tip[k] - b.tip[k]) < 2e-7);
        assert_true(fabs(a.tip[k] - c.tip[k]) < 2e-7);
    }
    /* bitwise repeatable */
    const whirl_regime_result d = run(chain, &p);
    assert_same(&c, &d);
    whirl_chain_free(chain);
}

/* An observer that stops the run at time t_stop. */
typedef struct stop_after {
    double t_stop;
} stop_after;

static int stop_late(void *ctx, double t, double frame_angle, const double *pivot, const double *x,
                     size_t n)
{
    (void)frame_angle, (void)pivot, (void)x, (void)n;
    return t >= ((const stop_after *)ctx)->t_stop ? WHIRL_EINTERRUPTED : GSL_SUCCESS;
}

/* A sweep's first point is the run from rest; the next one settles on the same branch. */
static void test_sweep(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_regime_params p = params(3.4, 0.061, 0.23);
    const double omega[] = {3.4, 3.55};
    whirl_regime_result res[2];
    whirl_regime *w = whirl_regime_alloc(chain);
    size_t done = 0;
    assert_int_equal(whirl_regime_sweep(w, &p, omega, 2, 10, res, &done), GSL_SUCCESS);
    assert_int_equal(done, 2);
    const whirl_regime_result r = run(chain, &p);
    assert_same(&res[0], &r);
    /* a stop during the second point keeps the first: *n_done says how many are complete */
    whirl_regime_result seen[2], part[2]; /* observed runs (observing moves the steps) */
    stop_after st = {INFINITY};
    whirl_regime_observe(w, stop_late, &st, 0.25);
    assert_int_equal(whirl_regime_sweep(w, &p, omega, 2, 10, seen, &done), GSL_SUCCESS);
    st.t_stop = seen[0].t_end + 1;
    assert_int_equal(whirl_regime_sweep(w, &p, omega, 2, 10, part, &done), WHIRL_EINTERRUPTED);
    whirl_regime_observe(w, NULL, NULL, 0);
    assert_int_equal(done, 1);
    assert_same(&part[0], &seen[0]);
    assert_int_equal(res[1].state, WHIRL_REGIME_SETTLED);
    assert_int_equal(res[1].nodes, res[0].nodes);
    assert_true(res[1].shape_error < p.settle_tol);
    p.frame = WHIRL_FRAME_INERTIAL;
    assert_int_equal(whirl_regime_sweep(w, &p, omega, 2, 10, res, NULL), GSL_EINVAL);
    p.frame = WHIRL_FRAME_ROTATING;
    assert_int_equal(whirl_regime_sweep(w, &p, omega, 2, 0, res, NULL), GSL_EINVAL);
    assert_int_equal(whirl_regime_sweep(w, &p, omega, 2, NAN, res, NULL), GSL_EINVAL);
    whirl_regime_free(w);
    whirl_chain_free(chain);
}

typedef struct seen {
    int calls;
    double last_t, max_angle_error;
} seen;

static int watch(void *ctx, double t, double angle, const double *pivot, const double *x, size_t n)
{
    seen *s = ctx;
    (void)pivot;
    (void)x;
    (void)n;
    s->calls++;
    s->last_t = t;
    s->max_angle_error = fmax(s->max_angle_error, fabs(angle - 4.0 * t));
    return GSL_SUCCESS;
}

/* Driven hard between omega_3 and omega_4 on a wide circle with little drag, the chain flails:
 * chaotic, lambda > 0. The 30-period estimate depends on the random start: over the seeds 1..8
 * it was 0.29..0.86 here (at omega 5.8, eps 0.1, drag 0.05 it ranged over 0.06..2.9, and the
 * threshold 10 chaos_lambda was met by some seeds only). */
static void test_chaotic_and_observer(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_regime_params p = params(4.0, 0.15, 0.02);
    p.t_max = 100;
    p.lyapunov_periods = 30;
    whirl_regime *w = whirl_regime_alloc(chain);
    seen s = {0, 0, 0};
    whirl_regime_observe(w, watch, &s, 0.25);
    whirl_regime_result r;
    assert_int_equal(whirl_regime_run(w, &p, &r), GSL_SUCCESS);
    assert_int_equal(r.state, WHIRL_REGIME_CHAOTIC);
    assert_true(r.lyapunov > 5 * p.chaos_lambda);
    assert_true(isnan(r.shape_error));
    assert_int_equal(s.calls, (int)floor(r.t_end / 0.25 + 1e-9) + 1);
    assert_true(s.max_angle_error < 1e-9 * r.t_end * 4.0);
    whirl_regime_free(w);
    whirl_chain_free(chain);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_regime_params good = params(2.1, 0.05, 0.1);
    assert_int_equal(whirl_regime_check(&good), GSL_SUCCESS);
    whirl_regime_params p;
#define BAD(field, value)                                                                       \
    do {                                                                                        \
        p = good;                                                                               \
        p.field = value;                                                                        \
        assert_int_equal(whirl_regime_check(&p), GSL_EINVAL);                                   \
        assert_non_null(strstr(whirl_last_error(), #field));                                    \
    } while (0)
    BAD(omega, 0);
    BAD(omega, NAN);
    BAD(drive_radius, 0);
    BAD(drive_radius, 1);
    BAD(air_drag, -0.1);
    BAD(air_drag_quadratic, -1e-3);
    BAD(internal_damping, INFINITY);
    BAD(dt, 0);
    BAD(t_ramp, -1);
    BAD(t_max, 10);
    BAD(settle_tol, 0);
    BAD(settle_periods, 0);
    BAD(periodic_tol, -1);
    BAD(chaos_lambda, 0);
    BAD(perturb, -0.1);
#undef BAD
    p = good;
    p.method = "no-such-method";
    whirl_chain *chain = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_regime *w = whirl_regime_alloc(chain);
    whirl_regime_result r;
    assert_int_not_equal(whirl_regime_run(w, &p, &r), GSL_SUCCESS);
    assert_null(whirl_regime_alloc(NULL));
    assert_null(whirl_regime_state_name((whirl_regime_state)17));
    assert_string_equal(whirl_regime_state_name(WHIRL_REGIME_QUASIPERIODIC), "quasiperiodic");
    whirl_regime_free(w);
    whirl_regime_free(NULL);
    whirl_chain_free(chain);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nodes_polyline),
        cmocka_unit_test(test_nodes_driven),
        cmocka_unit_test(test_settles_onto_steady_shape),
        cmocka_unit_test(test_step_and_seed),
        cmocka_unit_test(test_sweep),
        cmocka_unit_test(test_chaotic_and_observer),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
