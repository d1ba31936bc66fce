/* Tests of the ellipticity chart of the hand-swung chain (whirl_chart_ellipse) and of the
 * continuation in the ellipticity (WHIRL_CYCLE_ELLIPTICITY).
 *
 * The end of a curve on e = 0 (N = 2 and N = 3): where the circle drive's steady shape itself
 * changes stability. The reference is the steady linearisation (whirl_stability_driven_mode's growth rate, the
 * eigenvalues of the shape in the rotating frame: no periodic motion, no monodromy), its onset
 * located by bisection against 1e-7: it grows as c sqrt(omega - omega*) (c ~ 0.5) beyond a
 * Krein collision, so the bisection ends (1e-7 / c)^2 ~ 4e-14 above it.
 *
 * The verdict on either side of e_crit: a perturbed run (the chain's dynamics with the pivot on
 * the ellipse, from the periodic motion disturbed by 1e-10) grows per period by the largest
 * multiplier's modulus beyond e_crit and stays bounded within it. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "whirl/periodic.h"
#include "whirl/stability.h"

#define LOCATION_TOL 1e-8 /* the tolerance of an event's location */
#define EPS 0.05

typedef struct rows {
    whirl_ellipse_point p[64];
    int n;
} rows;

static int keep(void *data, const whirl_ellipse_point *p)
{
    rows *r = data;
    assert_true(r->n < 64);
    assert_true(isfinite(p->omega) && isfinite(p->ellipticity) && isfinite(p->err));
    r->p[r->n++] = *p;
    return 0;
}

/* The steady shape's growth rate of mode 2 (side -1) at omega. */
static double steady_growth(whirl_stability *st, const whirl_chain *c, double omega)
{
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega,
                           .drive_radius = EPS};
    double g;
    assert_int_equal(whirl_stability_driven_mode(st, &m, 2, -1, NULL, &g), GSL_SUCCESS);
    return g;
}

/* a = 0.05, mode 2 (side -1): N = 2 is stable on the circle up to the Krein collision near
 * 4.03, N = 3 up to one near 2.85; the chart's curve must end on e = 0 there, and the rates
 * below have 0 < e_crit < 1. */
static void test_curve_end(void **state)
{
    (void)state;
    static const struct {
        int links, columns, rows;
        double lo, hi;
    } cases[] = {{2, 4, 3, 3.95, 4.1}, {3, 3, 2, 2.8, 2.9}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        whirl_chain *c = whirl_chain_alloc_uniform((size_t)cases[k].links, 0);
        whirl_stability *st = whirl_stability_alloc((size_t)cases[k].links);
        double lo = cases[k].lo, hi = cases[k].hi;
        assert_true(steady_growth(st, c, lo) == 0);
        assert_true(steady_growth(st, c, hi) > 1e-3);
        for (int i = 0; i < 60; i++) {
            const double mid = (lo + hi) / 2;
            if (steady_growth(st, c, mid) > 1e-7) hi = mid;
            else lo = mid;
        }
        const whirl_ellipse_chart_params p = {
            .radius = EPS, .mode = 2, .side = -1, .omega_min = cases[k].lo,
            .omega_max = cases[k].hi, .columns = cases[k].columns};
        rows r = {.n = 0};
        assert_int_equal(whirl_chart_ellipse(c, &p, keep, &r, NULL, NULL), GSL_SUCCESS);
        /* a row per rate stable on the circle, then the end; none at the unstable rates */
        const int n = cases[k].rows;
        assert_int_equal(r.n, n);
        const whirl_ellipse_point *end = &r.p[n - 1];
        print_message("# N = %d, a = 0.05, mode 2: the curve ends at omega = %.17g (%s, err "
                      "%.2g); the steady growth's onset %.17g, difference %.2g; e_crit(%g) = "
                      "%.12g\n", cases[k].links, end->omega, whirl_cycle_event_name(end->event),
                      end->err, hi, fabs(end->omega - hi), r.p[0].omega, r.p[0].ellipticity);
        assert_int_equal(end->column, -1);
        assert_true(end->ellipticity == 0);
        assert_int_equal(end->event, WHIRL_CYCLE_TORUS);
        assert_true(end->err < LOCATION_TOL);
        assert_true(fabs(end->omega - hi) < LOCATION_TOL);
        for (int i = 0; i < n - 1; i++) {
            assert_int_equal(r.p[i].column, i);
            assert_int_equal(r.p[i].curve, 0);
            assert_true(r.p[i].ellipticity > 0 && r.p[i].ellipticity < 1);
            assert_true(r.p[i].err < LOCATION_TOL);
        }
        whirl_stability_free(st);
        whirl_chain_free(c);
    }
}

/* The scaled norm of the tangent coordinates of y - y0 (rates over omega). */
static double tangent_norm(whirl_periodic *w, const double *y0, const double *y, double omega,
                           double *x)
{
    const size_t m = whirl_periodic_tangent_size(w);
    assert_int_equal(whirl_periodic_tangent(w, y0, y, x), GSL_SUCCESS);
    double s = 0;
    for (size_t j = 0; j < m; j++) s += x[j] * x[j] / (j < m / 2 ? 1 : omega * omega);
    return sqrt(s);
}

/* The periodic motion at ellipticity e (omega, N = 2, mode 2 side -1) into y, its multipliers
 * into r: followed in e from the circle to just below e, then Newton's method at e. */
static whirl_periodic *motion_at(const whirl_chain *c, double omega, double e, double *y,
                                 whirl_periodic_result *r)
{
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, omega, EPS), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    assert_non_null(w);
    assert_int_equal(whirl_periodic_start_steady(w, 2, -1, y), GSL_SUCCESS);
    const whirl_cycle_params cp = {.parameter = WHIRL_CYCLE_ELLIPTICITY, .min = 0, .max = e,
                                   .direction = 1, .step = 0.02};
    assert_int_equal(whirl_periodic_path(w, y, &cp, NULL, NULL, NULL, NULL), GSL_SUCCESS);
    whirl_periodic_free(w);
    assert_int_equal(whirl_pivot_ellipse(&path, omega, EPS, EPS * (1 - e)), GSL_SUCCESS);
    w = whirl_periodic_alloc(c, 3, &path);
    const whirl_periodic_params pp = {.steps = 800, .refine = 1};
    assert_int_equal(whirl_periodic_find(w, y, &pp, r), GSL_SUCCESS);
    return w;
}

/* The growth per period of a perturbation of the motion y0: exp of the least-squares slope of
 * ln |perturbation| over the periods skip..periods (a complex pair makes the norm beat within
 * its envelope; the fit averages the beats). The parts on the neutral pairs fall behind the
 * growing one as |mu|^-k: 2e-2 at k = 100 with |mu| = 1.039. */
static double run_growth(whirl_periodic *w, const double *y0, double omega, int steps, int skip,
                         int periods)
{
    const size_t size = whirl_periodic_state_size(w), m = whirl_periodic_tangent_size(w);
    double *y = malloc(size * sizeof *y), *x = malloc(m * sizeof *x);
    memcpy(y, y0, size * sizeof *y);
    for (size_t j = 0; j < size / 2; j++) y[j] += 1e-10 * (((j * 7) % 5) - 2.0);
    assert_int_equal(whirl_dyn_project(whirl_periodic_dyn(w), 0, y), GSL_SUCCESS);
    double sk = 0, sl = 0, skk = 0, skl = 0;
    int count = 0;
    for (int k = 1; k <= periods; k++) {
        assert_int_equal(whirl_periodic_run(w, y, steps, 1), GSL_SUCCESS);
        const double l = log(tangent_norm(w, y0, y, omega, x));
        if (k < skip) continue;
        sk += k, sl += l, skk += (double)k * k, skl += k * l, count++;
    }
    free(y), free(x);
    return exp((count * skl - sk * sl) / (count * skk - sk * sk));
}

static void test_perturbed_runs(void **state)
{
    (void)state;
    const double omega = 4.0;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    const whirl_ellipse_chart_params p = {.radius = EPS, .mode = 2, .side = -1,
                                          .omega_min = omega, .omega_max = 4.01, .columns = 2};
    rows r = {.n = 0};
    assert_int_equal(whirl_chart_ellipse(c, &p, keep, &r, NULL, NULL), GSL_SUCCESS);
    assert_true(r.n >= 1 && r.p[0].column == 0);
    const double ec = r.p[0].ellipticity;
    const size_t size = 12;
    double y[12];
    /* within: neutral, a disturbance stays as it was */
    whirl_periodic_result res;
    whirl_periodic *w = motion_at(c, omega, ec - 0.02, y, &res);
    assert_int_equal(whirl_periodic_state_size(w), size);
    const double g_in = run_growth(w, y, omega, res.steps, 100, 300);
    print_message("# omega = 4, e = e_crit - 0.02 = %.6f: %s, |mu|max %.12f; growth per period "
                  "from a run %.6f\n", ec - 0.02, whirl_floquet_verdict_name(res.verdict),
                  res.max_modulus, g_in);
    assert_int_equal(res.verdict, WHIRL_FLOQUET_NEUTRAL);
    assert_true(fabs(g_in - 1) < 2e-3);
    whirl_periodic_free(w);
    /* beyond: unstable, a disturbance grows by |mu|max per period */
    w = motion_at(c, omega, ec + 0.02, y, &res);
    const double g_out = run_growth(w, y, omega, res.steps, 100, 300);
    print_message("# omega = 4, e = e_crit + 0.02 = %.6f: %s, |mu|max %.12f (edge %s); growth "
                  "per period from a run %.6f\n", ec + 0.02,
                  whirl_floquet_verdict_name(res.verdict), res.max_modulus,
                  whirl_floquet_edge_name(res.edge), g_out);
    assert_int_equal(res.verdict, WHIRL_FLOQUET_UNSTABLE);
    assert_true(res.max_modulus > 1.001);
    assert_true(fabs(g_out - res.max_modulus) < 1e-3 * (res.max_modulus - 1));
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* A thin tongue: near omega = 3.922 a torus tongue touches e = 0; at 3.92 the branch enters it
 * at e ~ 0.007 and a step of 0.05 passes over it. The chart's default step finds it, and a
 * step five times smaller finds the same point. */
static void test_thin_tongue(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    whirl_ellipse_chart_params p = {.radius = EPS, .mode = 2, .side = -1, .omega_min = 3.92,
                                    .omega_max = 3.921, .columns = 2};
    rows a = {.n = 0}, b = {.n = 0};
    assert_int_equal(whirl_chart_ellipse(c, &p, keep, &a, NULL, NULL), GSL_SUCCESS);
    p.step = 0.002;
    assert_int_equal(whirl_chart_ellipse(c, &p, keep, &b, NULL, NULL), GSL_SUCCESS);
    assert_int_equal(a.n, 2);
    assert_int_equal(b.n, 2);
    for (int i = 0; i < 2; i++) {
        print_message("# omega = %.4g: e_crit %.15g (%s), with the step 0.002 %.15g\n",
                      a.p[i].omega, a.p[i].ellipticity, whirl_cycle_event_name(a.p[i].event),
                      b.p[i].ellipticity);
        assert_int_equal(a.p[i].event, WHIRL_CYCLE_TORUS);
        assert_true(a.p[i].ellipticity > 0 && a.p[i].ellipticity < 0.01);
        assert_true(fabs(a.p[i].ellipticity - b.p[i].ellipticity) < LOCATION_TOL);
    }
    whirl_chain_free(c);
}

static void last_progress(void *data, const whirl_ellipse_chart_progress *p)
{
    *(whirl_ellipse_chart_progress *)data = *p;
}

/* A rate whose Newton's method does not converge (a tolerance below round-off) has no row and
 * is counted; the chart goes on. */
static void test_failed_rates(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    const whirl_ellipse_chart_params p = {.radius = EPS, .mode = 2, .side = -1,
                                          .omega_min = 3.9, .omega_max = 4.0, .columns = 2,
                                          .tol = 1e-300};
    rows r = {.n = 0};
    whirl_ellipse_chart_progress pr = {0};
    assert_int_equal(whirl_chart_ellipse(c, &p, keep, &r, last_progress, &pr), GSL_SUCCESS);
    assert_int_equal(r.n, 0);
    assert_int_equal(pr.failed, 2);
    assert_int_equal(pr.column, 1);
    whirl_chain_free(c);
}

/* Bad input: GSL_EINVAL, no row. */
static void test_bad_input(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    rows r = {.n = 0};
    const whirl_ellipse_chart_params bad[] = {
        {.radius = 0, .omega_min = 1, .omega_max = 2},
        {.radius = EPS, .omega_min = 2, .omega_max = 1},
        {.radius = EPS, .omega_min = 1, .omega_max = 2, .e_max = 1.5},
        {.radius = EPS, .omega_min = 1, .omega_max = 2, .side = 3},
        {.radius = EPS, .omega_min = 1, .omega_max = 2, .columns = 1},
        {.radius = NAN, .omega_min = 1, .omega_max = 2},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(whirl_chart_ellipse(c, &bad[i], keep, &r, NULL, NULL), GSL_EINVAL);
    assert_int_equal(r.n, 0);
    /* an ellipticity continuation of a path with no y term */
    whirl_pivot_path path;
    const double x[3] = {1, 0, 0};
    assert_int_equal(whirl_pivot_line(&path, 2, 0.05, x), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    double y[12];
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    const whirl_cycle_params cp = {.parameter = WHIRL_CYCLE_ELLIPTICITY, .min = 0, .max = 1,
                                   .direction = 1};
    assert_int_equal(whirl_periodic_path(w, y, &cp, NULL, NULL, NULL, NULL), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "along y"));
    /* a steady start on a path that is not a circle */
    assert_int_equal(whirl_periodic_start_steady(w, 2, 1, y), GSL_EINVAL);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_curve_end),
        cmocka_unit_test(test_perturbed_runs),
        cmocka_unit_test(test_thin_tongue),
        cmocka_unit_test(test_failed_rates),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
