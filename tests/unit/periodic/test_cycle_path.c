/* Tests of the continuation of periodic motions (whirl_periodic_path).
 *
 * Period doubling: N = 1 shaken vertically, A cos(omega t), is Mathieu's equation with
 * a = 4 / omega^2, q = 2 A (docs/theory/floquet.md). At a fixed rate the hanging branch, followed
 * in A, loses its stability where a pair of multipliers passes -1: at the edge of the first
 * tongue, a = a_1(q) (omega < 2) or b_1(q) (omega > 2). The references: whirl_chart_vertical's
 * edge at the same rate (the vertical state's monodromy alone, no continuation) and scipy's
 * characteristic values, the roots in A by scipy 1.10.1 (also in tests/cli/test_chart.sh):
 *   /usr/bin/python3 -c 'from scipy.special import mathieu_a, mathieu_b; from scipy.optimize
 *   import brentq; [print(w, repr(brentq(lambda q: f(1, q) - 4 / w**2, 1e-9, 1, xtol=1e-15) / 2))
 *   for w, f in ((1.8, mathieu_a), (2.2, mathieu_b))]'
 *
 * Fold of cycles: the circle drive's periodic motion is the steady shape turning with the pivot;
 * where the branch of steady shapes folds in the rate (whirl_driven_branch: the fold function
 * det d(pivot miss)/d(X, Y) of the shape's force balance, a different computation on a
 * different formulation), the periodic branch must fold with a multiplier pair through +1. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "whirl/driven.h"
#include "whirl/periodic.h"
#include "whirl/stability.h"

#define LOCATION_TOL 1e-8 /* the tolerance of an event's location */

typedef struct seen {
    int points, events, kind_events;
    whirl_cycle_event kind;
    double at, err;          /* the first event of kind */
    int before, after;       /* verdicts of the points just before and after it */
    int stop_after;          /* > 0: return 42 after this many rows */
} seen;

static int keep(void *data, const whirl_cycle_point *p)
{
    seen *s = data;
    assert_true(isfinite(p->parameter) && isfinite(p->fold_test) && isfinite(p->flip_test));
    if (p->event == WHIRL_CYCLE_POINT) {
        if (s->kind_events == 0) s->before = p->verdict;
        else if (s->after < 0) s->after = p->verdict;
        s->points++;
    } else {
        s->events++;
        if (p->event == s->kind && s->kind_events++ == 0) s->at = p->parameter, s->err = p->err;
    }
    if (s->stop_after > 0 && s->points + s->events == s->stop_after) return 42;
    return 0;
}

static int chart_edge(void *data, const whirl_chart_point *p)
{
    double *a = data;
    if (p->column == 0) *a = p->amplitude;
    return 0;
}

/* The event of kind (a period doubling at a first tongue's edge, a branch point at a second
 * tongue's) of the hanging pendulum at the rate omega, A rising from 0.01 to amp_max. */
static void mathieu_at(double omega, double scipy_root, whirl_cycle_event kind, double amp_max,
                       int dim)
{
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    assert_int_equal(whirl_pivot_line(&path, omega, 0.01, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, dim, &path);
    assert_non_null(w);
    double y[6];
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    const whirl_cycle_params p = {.parameter = WHIRL_CYCLE_AMPLITUDE, .min = 0, .max = amp_max,
                                  .direction = 1};
    seen s = {.kind = kind, .after = -1};
    assert_int_equal(whirl_periodic_path(w, y, &p, keep, &s, NULL, NULL), GSL_SUCCESS);
    /* the chart's edge at this rate (first column) */
    double edge = NAN;
    const whirl_chart_params cp = {.omega_min = omega, .omega_max = omega + 0.01, .columns = 2,
                                   .amp_max = amp_max, .rows = 30};
    assert_int_equal(whirl_chart_vertical(c, 2, &cp, chart_edge, &edge, NULL, NULL), GSL_SUCCESS);
    print_message("# omega %g: %s at A = %.17g (err %.2g); chart %.17g (%.2g), scipy %.17g "
                  "(%.2g)\n", omega, whirl_cycle_event_name(kind), s.at, s.err, edge,
                  fabs(s.at - edge), scipy_root, fabs(s.at - scipy_root));
    assert_int_equal(s.kind_events, 1);
    assert_int_equal(s.events, 1); /* the one edge below amp_max at these rates */
    assert_int_equal(s.before, WHIRL_FLOQUET_NEUTRAL);
    assert_int_equal(s.after, WHIRL_FLOQUET_UNSTABLE);
    assert_true(s.err < LOCATION_TOL);
    assert_true(fabs(s.at - edge) < LOCATION_TOL);
    assert_true(fabs(s.at - scipy_root) < LOCATION_TOL);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

static void test_mathieu_left_edge(void **state)
{
    (void)state;
    mathieu_at(1.8, 0.12105968496067503, WHIRL_CYCLE_PERIOD_DOUBLING, 0.3, 2); /* a_1 */
}

static void test_mathieu_right_edge(void **state)
{
    (void)state;
    mathieu_at(2.2, 0.08500835628918853, WHIRL_CYCLE_PERIOD_DOUBLING, 0.3, 2); /* b_1 */
}

/* The second tongue's left edge a_2 (+1): the hanging branch goes on (a branch point, not a
 * fold); scipy's root as above with mathieu_a(2, q), omega = 0.98. */
static void test_mathieu_branch_point(void **state)
{
    (void)state;
    mathieu_at(0.98, 0.3228397014390305, WHIRL_CYCLE_BRANCH, 0.5, 2);
}

/* In 3D the pendulum swings in two planes alike: every pair of multipliers is double,
 * det(M + I) has a double zero at the edge and does not change sign; the change of the verdict
 * is located on the pairs' rho instead (cycle_events.c), at the same edge a_1. */
static void test_mathieu_3d(void **state)
{
    (void)state;
    mathieu_at(1.8, 0.12105968496067503, WHIRL_CYCLE_PERIOD_DOUBLING, 0.3, 3);
}

/* The circle drive's steady shape at omega as a state of w: with guess NULL, the shape of mode
 * 1 with its tip opposite the pivot; else the one whose tip is near guess. */
static void steady_start(const whirl_chain *c, double omega, double eps, const double *guess,
                         whirl_periodic *w, double *y, whirl_driven_info *info)
{
    const size_t n = c->n;
    const whirl_driven_params dp = {.omega = omega, .drive_radius = eps};
    assert_int_equal(guess ? whirl_driven_solve(c, &dp, guess, info)
                           : whirl_driven_mode(c, &dp, 1, -1, info),
                     GSL_SUCCESS);
    double *buf = malloc(5 * (n + 1) * sizeof *buf), *links = malloc(3 * n * sizeof *links);
    assert_int_equal(whirl_driven_sample(c, &dp, info->tip, n + 1, buf, buf + n + 1,
                                         buf + 2 * (n + 1), buf + 3 * (n + 1), buf + 4 * (n + 1)),
                     GSL_SUCCESS);
    assert_int_equal(whirl_shape_links(n, buf + n + 1, buf + 2 * (n + 1), buf + 3 * (n + 1),
                                       links),
                     GSL_SUCCESS);
    assert_int_equal(whirl_dyn_state_from_shape(whirl_periodic_dyn(w), 0, links, omega, y),
                     GSL_SUCCESS);
    free(buf), free(links);
}

static void test_circle_fold(void **state)
{
    (void)state;
    const double omega = 1.3, eps = 0.05;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, omega, eps), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    assert_non_null(w);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    whirl_driven_info info;
    steady_start(c, omega, eps, NULL, w, y, &info);
    /* the steady branch's fold */
    whirl_driven_curve *curve = whirl_driven_curve_alloc(1000);
    const whirl_driven_params dp = {.omega = omega, .drive_radius = eps};
    assert_int_equal(whirl_driven_branch(c, &dp, &info, -1, 1.1, 1.5, 0.02, curve), GSL_SUCCESS);
    assert_int_equal(curve->n_folds, 1);
    const double steady_fold = curve->fold_omega[0];
    /* the periodic branch's */
    const whirl_cycle_params p = {.parameter = WHIRL_CYCLE_OMEGA, .min = 1.1, .max = 1.5,
                                  .direction = -1};
    seen s = {.kind = WHIRL_CYCLE_FOLD, .after = -1};
    assert_int_equal(whirl_periodic_path(w, y, &p, keep, &s, NULL, NULL), GSL_SUCCESS);
    print_message("# circle drive N = 2, eps = 0.05: fold at omega = %.17g (err %.2g), steady "
                  "%.17g, difference %.2g\n", s.at, s.err, steady_fold, fabs(s.at - steady_fold));
    assert_int_equal(s.kind_events, 1);
    assert_int_equal(s.events, 1);
    assert_int_equal(s.before, WHIRL_FLOQUET_UNSTABLE); /* the branch of the middle shapes */
    assert_int_equal(s.after, WHIRL_FLOQUET_NEUTRAL);   /* beyond the fold: the small shapes */
    assert_true(s.err < LOCATION_TOL);
    assert_true(fabs(s.at - steady_fold) < LOCATION_TOL);
    whirl_driven_curve_free(curve);
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* The growth rate of the steady linearisation of the circle drive's shape near guess at omega
 * (guess <- its tip). */
static double steady_growth(const whirl_chain *c, double omega, double eps, double guess[2])
{
    const size_t n = c->n + 1;
    const whirl_driven_params dp = {.omega = omega, .drive_radius = eps};
    whirl_driven_info info;
    assert_int_equal(whirl_driven_solve(c, &dp, guess, &info), GSL_SUCCESS);
    guess[0] = info.tip[0], guess[1] = info.tip[1];
    double *buf = malloc(5 * n * sizeof *buf);
    assert_int_equal(whirl_driven_sample(c, &dp, info.tip, n, buf, buf + n, buf + 2 * n,
                                         buf + 3 * n, buf + 4 * n),
                     GSL_SUCCESS);
    whirl_stability *st = whirl_stability_alloc(c->n);
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega,
                           .drive_radius = eps};
    double g;
    assert_int_equal(whirl_stability_linearise_3d(st, &m, buf + n, buf + 2 * n, buf + 3 * n),
                     GSL_SUCCESS);
    assert_int_equal(whirl_stability_growth(st, &g), GSL_SUCCESS);
    whirl_stability_free(st);
    free(buf);
    return g;
}

/* The torus: the circle drive's 2-node shape of N = 2 (eps 0.05, the branch through the fold
 * above, tip about 0.21 L from the axis) turns unstable near omega = 4.03 where two pairs of
 * eigenvalues of the steady linearisation meet on the imaginary axis and leave it (a Krein
 * collision; no fold). The periodic branch must meet it as two pairs of multipliers meeting on
 * the unit circle. The reference: bisection on the steady growth rate (whirl_stability_growth)
 * against 1e-7: it grows as c sqrt(omega - omega*) with c ~ 0.5 beyond the meeting, so the
 * bisection ends (1e-7 / c)^2 ~ 4e-14 above it. */
static void test_circle_torus(void **state)
{
    (void)state;
    const double eps = 0.05, omega = 3.95;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    double guess[2] = {-0.2076, 0}, lo = 3.95, hi = 4.1;
    assert_true(steady_growth(c, lo, eps, guess) == 0);
    double at_lo[2] = {guess[0], guess[1]};
    assert_true(steady_growth(c, hi, eps, guess) > 1e-3);
    for (int i = 0; i < 60; i++) {
        const double mid = (lo + hi) / 2;
        double g[2] = {at_lo[0], at_lo[1]};
        if (steady_growth(c, mid, eps, g) > 1e-7) hi = mid;
        else lo = mid;
    }
    /* the periodic branch from the steady shape at 3.95 */
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, omega, eps), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    const double tip[2] = {-0.2076, 0};
    whirl_driven_info info;
    steady_start(c, omega, eps, tip, w, y, &info);
    const whirl_cycle_params p = {.parameter = WHIRL_CYCLE_OMEGA, .min = 3.9, .max = 4.1,
                                  .direction = 1};
    seen s = {.kind = WHIRL_CYCLE_TORUS, .after = -1};
    assert_int_equal(whirl_periodic_path(w, y, &p, keep, &s, NULL, NULL), GSL_SUCCESS);
    print_message("# circle drive N = 2, eps = 0.05: torus at omega = %.17g (err %.2g), steady "
                  "growth's onset %.17g, difference %.2g\n", s.at, s.err, hi, fabs(s.at - hi));
    assert_int_equal(s.kind_events, 1);
    assert_int_equal(s.events, 1);
    assert_int_equal(s.before, WHIRL_FLOQUET_NEUTRAL);
    assert_int_equal(s.after, WHIRL_FLOQUET_UNSTABLE);
    assert_true(s.err < LOCATION_TOL);
    assert_true(fabs(s.at - hi) < LOCATION_TOL);
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* Bad parameters: GSL_EINVAL, no row. */
static void test_bad_input(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    assert_int_equal(whirl_pivot_line(&path, 1.8, 0.05, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 2, &path);
    double y[4];
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    seen s = {.after = -1};
    const whirl_cycle_params bad[] = {
        {.parameter = WHIRL_CYCLE_OMEGA, .min = 2, .max = 1, .direction = 1},   /* min > max */
        {.parameter = WHIRL_CYCLE_OMEGA, .min = 0, .max = 3, .direction = 1},   /* omega 0 */
        {.parameter = WHIRL_CYCLE_OMEGA, .min = 2, .max = 3, .direction = 1},   /* start out */
        {.parameter = WHIRL_CYCLE_OMEGA, .min = 1, .max = 3, .direction = 0},   /* direction */
        {.parameter = WHIRL_CYCLE_AMPLITUDE, .min = 0, .max = 1, .direction = 1, .steps = 4},
        {.parameter = 7, .min = 0, .max = 1, .direction = 1},
        {.parameter = WHIRL_CYCLE_AMPLITUDE, .min = 0, .max = INFINITY, .direction = 1},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(whirl_periodic_path(w, y, &bad[i], keep, &s, NULL, NULL), GSL_EINVAL);
    assert_int_equal(s.points + s.events, 0);
    assert_int_equal(whirl_periodic_path(w, NULL, &bad[0], keep, &s, NULL, NULL), GSL_EINVAL);
    whirl_periodic_free(w);
    /* an amplitude continuation of a path that does not move */
    assert_int_equal(whirl_pivot_line(&path, 1.8, 0, up), GSL_SUCCESS);
    w = whirl_periodic_alloc(c, 2, &path);
    const whirl_cycle_params still = {.parameter = WHIRL_CYCLE_AMPLITUDE, .min = 0, .max = 1,
                                      .direction = 1};
    assert_int_equal(whirl_periodic_path(w, y, &still, keep, &s, NULL, NULL), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "path that moves"));
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* Newton's method that does not converge at the start: GSL_EMAXITER naming the residual, no
 * row; a row callback's status ends the branch with it (the rows before it stand). */
static void test_failure_and_stop(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_ellipse(&path, 3, 0.1, 0.05), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    seen s = {.after = -1};
    const whirl_cycle_params p = {.parameter = WHIRL_CYCLE_OMEGA, .min = 2, .max = 4,
                                  .direction = 1, .max_iter = 1, .tol = 1e-14};
    assert_int_equal(whirl_periodic_path(w, y, &p, keep, &s, NULL, NULL), GSL_EMAXITER);
    assert_non_null(strstr(whirl_last_error(), "residual"));
    assert_int_equal(s.points + s.events, 0);
    whirl_periodic_free(w);
    whirl_chain_free(c);
    /* the hanging pendulum at a small amplitude: three rows, then the callback's 42 */
    c = whirl_chain_alloc_uniform(1, 0);
    const double up[3] = {0, 0, 1};
    assert_int_equal(whirl_pivot_line(&path, 1.8, 0.01, up), GSL_SUCCESS);
    w = whirl_periodic_alloc(c, 2, &path);
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    const whirl_cycle_params q = {.parameter = WHIRL_CYCLE_AMPLITUDE, .min = 0, .max = 0.3,
                                  .direction = 1, .step = 0.01};
    seen t = {.after = -1, .stop_after = 3};
    assert_int_equal(whirl_periodic_path(w, y, &q, keep, &t, NULL, NULL), 42);
    assert_int_equal(t.points, 3);
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mathieu_left_edge),
        cmocka_unit_test(test_mathieu_right_edge),
        cmocka_unit_test(test_mathieu_branch_point),
        cmocka_unit_test(test_mathieu_3d),
        cmocka_unit_test(test_circle_fold),
        cmocka_unit_test(test_circle_torus),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_failure_and_stop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
