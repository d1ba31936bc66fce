/* Tests of the chart of the vertically shaken chain with linear air drag
 * (whirl_chart_vertical_damped).
 *
 * N = 1 (g = l = m = 1, gamma = c) is the pendulum theta'' + gamma theta' + (1 + z'' + gamma z')
 * theta = 0, z = A cos(w t): the drag acts on the inertial velocity, the pivot's z' included.
 * Since z'' + gamma z' = -A w sqrt(w^2 + gamma^2) cos(w t - phi), that is the damped Mathieu
 * equation theta'' + gamma theta' + (1 - A' w^2 cos(w t')) theta = 0 at the amplitude
 * A' = A sqrt(1 + gamma^2 / w^2) (a shift of time does not change the multipliers). The
 * reference here knows nothing of the chart's transformation
 * (q = exp(-gamma t / 2) y, the trace test +-2 cosh(gamma T / 2)): the damped equation's 2 x 2
 * monodromy integrated as it stands by GSL's Runge-Kutta-Prince-Dormand (8, 9) at a tolerance of
 * 1e-13, its largest multiplier's modulus from the trace and determinant. Every chart point must
 * have that modulus 1. The first tongue's lowest amplitude (the threshold below which the
 * damped pendulum is stable at every rate) is located on the reference alone (Brent's root in A
 * of |mu|max - 1, minimised over omega by golden sections) and compared with the chart's lowest
 * points and with the first-order result for Mathieu's equation: the shifted equation
 * y'' + (a' - 2 q cos 2 tau) y = 0 (tau = w t / 2, a' = 4 (1 - gamma^2 / 4) / w^2, q = 2 A) grows
 * at the rate s = sqrt(q^2 - (a' - 1)^2) / 2 per unit tau near its first tongue, w s / 2 per unit
 * t, and the damped one is unstable where that exceeds gamma / 2: the lowest A' is at a' = 1,
 * q / 2 = gamma / w, A' = gamma / w, w = 2 sqrt(1 - gamma^2 / 4), so A = gamma / sqrt(w^2 +
 * gamma^2) = gamma / 2 to first order in q.
 *
 * N = 3 with drag against the full chain's Floquet multipliers (whirl_periodic_alloc_model with
 * the model's air drag: the Cartesian chain's variational equations by Gauss steps, a method
 * that knows nothing of the modes): at the chart's points one multiplier has modulus 1. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_odeiv2.h>

#include "whirl/periodic.h"

typedef struct damped {
    double gamma, omega, amp, sigma; /* sigma +1 hanging, -1 inverted */
} damped;

/* The fundamental matrix's two columns (theta, theta') of the pendulum with linear air drag on
 * its inertial velocity: in the pivot's frame the mass feels g + z'' and the drag of the pivot's
 * velocity z' as well, gamma z' (z = A cos(w t)), so
 *   theta'' + gamma theta' + (1 + z'' + gamma z') theta = 0. */
static int damped_rhs(double t, const double y[], double f[], void *params)
{
    const damped *d = params;
    const double w = d->sigma * (1 - d->amp * d->omega * d->omega * cos(d->omega * t) -
                                 d->gamma * d->amp * d->omega * sin(d->omega * t));
    for (int k = 0; k < 2; k++) {
        f[2 * k] = y[2 * k + 1];
        f[2 * k + 1] = -d->gamma * y[2 * k + 1] - w * y[2 * k];
    }
    return GSL_SUCCESS;
}

/* The largest modulus of the damped pendulum's multipliers at (omega, amp), directly (sigma
 * -1: the inverted pendulum, theta measured from the upright). */
static double direct_modulus_of(double gamma, double omega, double amp, double sigma)
{
    damped d = {gamma, omega, amp, sigma};
    gsl_odeiv2_system sys = {damped_rhs, NULL, 4, &d};
    gsl_odeiv2_driver *drv =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3, 1e-13, 1e-13);
    double y[4] = {1, 0, 0, 1}, t = 0; /* columns (1, 0) and (0, 1) */
    assert_int_equal(gsl_odeiv2_driver_apply(drv, &t, 2 * M_PI / omega, y), GSL_SUCCESS);
    gsl_odeiv2_driver_free(drv);
    const double tr = y[0] + y[3], det = y[0] * y[3] - y[2] * y[1];
    const double disc = tr * tr / 4 - det;
    if (disc < 0) return sqrt(det); /* a complex pair */
    return fabs(tr / 2) + sqrt(disc);
}

static double direct_modulus(double gamma, double omega, double amp)
{
    return direct_modulus_of(gamma, omega, amp, 1);
}


typedef struct pts {
    whirl_chart_point p[512];
    int n;
} pts;

static int keep(void *data, const whirl_chart_point *p)
{
    pts *s = data;
    assert_true(s->n < 512);
    s->p[s->n++] = *p;
    return 0;
}

/* The inverted pendulum with drag: its region of stability's edges (Kapitza's lower one, +1,
 * and the upper, -1) on the direct integration. */
static void test_inverted_damped(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params p = {.inverted = 1, .omega_min = 20, .omega_max = 30, .columns = 6,
                                  .amp_max = 0.2, .rows = 40};
    pts s = {.n = 0};
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, 0.5, keep, &s, NULL, NULL),
                     GSL_SUCCESS);
    double worst = 0;
    int kinds[2] = {0, 0};
    for (int i = 0; i < s.n; i++) {
        kinds[s.p[i].kind]++;
        const double d = fabs(direct_modulus_of(0.5, s.p[i].omega, s.p[i].amplitude, -1) - 1);
        if (d > worst) worst = d;
    }
    print_message("# inverted, gamma 0.5: %d points (+1: %d, -1: %d), worst ||mu|max - 1| %.2g\n",
                  s.n, kinds[0], kinds[1], worst);
    assert_int_equal(kinds[0], p.columns); /* the lower edge at every rate */
    assert_true(worst < 1e-9);
    whirl_chain_free(c);
}

#define GAMMA1 0.1

/* The first tongue of the damped pendulum: every point on |mu|max = 1 (the direct integration),
 * no tip (no point at A = 0), one curve. */
static void test_mathieu_damped(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params p = {.omega_min = 1.7, .omega_max = 2.3, .columns = 13,
                                  .amp_max = 0.3, .rows = 30};
    pts s = {.n = 0};
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, GAMMA1, keep, &s, NULL, NULL),
                     GSL_SUCCESS);
    double worst = 0;
    for (int i = 0; i < s.n; i++) {
        assert_int_equal(s.p[i].kind, WHIRL_FLOQUET_EDGE_MINUS_ONE);
        assert_int_equal(s.p[i].curve, s.p[0].curve);
        assert_true(s.p[i].amplitude > 0.04); /* lifted off the axis (threshold ~0.05) */
        assert_true(s.p[i].err < 1e-8);
        const double d = fabs(direct_modulus(GAMMA1, s.p[i].omega, s.p[i].amplitude) - 1);
        if (d > worst) worst = d;
    }
    print_message("# damped Mathieu, gamma %g: %d points, worst ||mu|max - 1| %.2g\n", GAMMA1,
                  s.n, worst);
    assert_int_equal(s.n, p.columns); /* one point per rate: the tongue's two edges one curve */
    assert_true(worst < 1e-9);
    whirl_chain_free(c);
}

/* A sharp lowest point: gamma 0.02 lifts the first tongue to A ~ 0.01 in a V about 0.02 wide
 * in omega, two rates of the grid (0.5 to 2.5, 200 rates; A <= 0.3, 200 rows): the follower
 * ends at the bottom (its bend test), the scan finds the rising edge a rate later, and the two
 * are joined (chart_tips.c): the tongue's -1 edges one curve, with points on both sides of its
 * lowest, every one on |mu|max = 1 (the direct integration). */
static void test_sharp_bottom(void **state)
{
    (void)state;
    const double gamma = 0.02;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params p = {.omega_min = 0.5, .omega_max = 2.5, .columns = 200,
                                  .amp_max = 0.3, .rows = 200};
    pts s = {.n = 0};
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, gamma, keep, &s, NULL, NULL),
                     GSL_SUCCESS);
    int curve = -1, n = 0, left = 0, right = 0;
    double worst = 0, low = INFINITY, wlow = 0;
    for (int i = 0; i < s.n; i++)
        if (s.p[i].kind == WHIRL_FLOQUET_EDGE_MINUS_ONE && s.p[i].amplitude < low)
            low = s.p[i].amplitude, wlow = s.p[i].omega, curve = s.p[i].curve;
    for (int i = 0; i < s.n; i++) {
        if (s.p[i].kind != WHIRL_FLOQUET_EDGE_MINUS_ONE) continue;
        assert_int_equal(s.p[i].curve, curve); /* one curve */
        n++, left += s.p[i].omega < wlow, right += s.p[i].omega > wlow;
        worst = fmax(worst, fabs(direct_modulus(gamma, s.p[i].omega, s.p[i].amplitude) - 1));
    }
    print_message("# sharp bottom, gamma %g: %d points of edge -1 on curve %d, lowest A %.5f at "
                  "omega %.4f, %d left and %d right of it, worst ||mu|max - 1| %.2g\n", gamma,
                  n, curve, low, wlow, left, right, worst);
    assert_true(left >= 10 && right >= 10);
    assert_true(worst < 1e-9);
    whirl_chain_free(c);
}

/* The edge amplitude at omega from the direct integration: Brent-free bisection-secant on
 * |mu|max - 1 in A over [lo, hi] (the modulus grows with A across the tongue's lower edge). */
static double direct_edge(double gamma, double omega, double lo, double hi)
{
    double flo = direct_modulus(gamma, omega, lo) - 1, fhi = direct_modulus(gamma, omega, hi) - 1;
    assert_true(flo < 0 && fhi > 0);
    for (int it = 0; it < 200 && hi - lo > 1e-13; it++) {
        double m = lo - flo * (hi - lo) / (fhi - flo); /* regula falsi (Illinois) */
        if (!(m > lo && m < hi)) m = (lo + hi) / 2;
        const double fm = direct_modulus(gamma, omega, m) - 1;
        if ((fm < 0) == (flo < 0)) lo = m, flo = fm, fhi /= 2;
        else hi = m, fhi = fm, flo /= 2;
        if (fm == 0) return m;
    }
    return (lo + hi) / 2;
}

/* The threshold: the lowest edge amplitude over omega (golden sections), directly. */
static double direct_threshold(double gamma, double wlo, double whi, double *wmin)
{
    const double r = (sqrt(5) - 1) / 2;
    double a = wlo, b = whi;
    double x1 = b - r * (b - a), x2 = a + r * (b - a);
    double f1 = direct_edge(gamma, x1, 0.5 * gamma / 2, 2 * gamma);
    double f2 = direct_edge(gamma, x2, 0.5 * gamma / 2, 2 * gamma);
    while (b - a > 1e-7) {
        if (f1 < f2) b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a),
                     f1 = direct_edge(gamma, x1, 0.5 * gamma / 2, 2 * gamma);
        else a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a),
             f2 = direct_edge(gamma, x2, 0.5 * gamma / 2, 2 * gamma);
    }
    *wmin = (a + b) / 2;
    return fmin(f1, f2);
}

/* The lifted tongue's threshold: the chart's curve near its lowest point (a parabola through
 * the three lowest points of a fine chart) against the direct threshold, that against the
 * first-order gamma / w; below the threshold the pendulum is stable at every rate. */
static void test_threshold(void **state)
{
    (void)state;
    const double gamma = 0.02;
    double wmin;
    const double thr = direct_threshold(gamma, 1.98, 2.02, &wmin);
    const double first = gamma / 2;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params p = {.omega_min = 1.995, .omega_max = 2.005, .columns = 21,
                                  .amp_max = 0.03, .rows = 30};
    pts s = {.n = 0};
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, gamma, keep, &s, NULL, NULL),
                     GSL_SUCCESS);
    assert_int_equal(s.n, p.columns);
    int lo = 0;
    for (int i = 1; i < s.n; i++)
        if (s.p[i].amplitude < s.p[lo].amplitude) lo = i;
    assert_true(lo > 0 && lo < s.n - 1);
    /* the parabola's vertex through (w_i, A_i), i = lo - 1 .. lo + 1, equally spaced */
    const double a0 = s.p[lo - 1].amplitude, a1 = s.p[lo].amplitude, a2 = s.p[lo + 1].amplitude;
    const double h = s.p[lo + 1].omega - s.p[lo].omega;
    const double curv = a0 - 2 * a1 + a2, slope = (a2 - a0) / 2;
    const double vertex = a1 - slope * slope / (2 * curv);
    const double wv = s.p[lo].omega - h * slope / curv;
    print_message("# threshold, gamma %g: direct %.12g at omega %.9g; chart's vertex %.12g at "
                  "%.9g (diff %.2g); first order gamma / 2 %.9g (relative %.2g)\n", gamma, thr,
                  wmin, vertex, wv, vertex - thr, first, (thr - first) / first);
    assert_true(fabs(vertex - thr) < 1e-8);
    assert_true(fabs(wv - wmin) < 1e-4);
    /* the first-order result's neglected terms are O(q^2) relative, q = 2 A */
    assert_true(fabs(thr - first) < 4 * first * first * first);
    /* stable below it at every rate across the tongue, unstable just above at its lowest */
    for (int i = 0; i <= 20; i++)
        assert_true(direct_modulus(gamma, 1.96 + 0.004 * i, 0.999 * thr) < 1);
    assert_true(direct_modulus(gamma, wmin, 1.001 * thr) > 1);
    whirl_chain_free(c);
}

/* Drag 0 is the conservative chart; the drag's bad values and chains refused. */
static void test_zero_and_bad(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    const whirl_chart_params p = {.omega_min = 1.8, .omega_max = 3, .columns = 9,
                                  .amp_max = 0.4, .rows = 20};
    pts a = {.n = 0}, b = {.n = 0};
    assert_int_equal(whirl_chart_vertical(c, 2, &p, keep, &a, NULL, NULL), GSL_SUCCESS);
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, 0, keep, &b, NULL, NULL), GSL_SUCCESS);
    assert_int_equal(a.n, b.n);
    for (int i = 0; i < a.n; i++) { /* field by field (the struct has padding), bit for bit */
        assert_int_equal(a.p[i].kind, b.p[i].kind);
        assert_int_equal(a.p[i].curve, b.p[i].curve);
        assert_int_equal(a.p[i].column, b.p[i].column);
        assert_memory_equal(&a.p[i].omega, &b.p[i].omega, sizeof(double));
        assert_memory_equal(&a.p[i].amplitude, &b.p[i].amplitude, sizeof(double));
        assert_memory_equal(&a.p[i].err, &b.p[i].err, sizeof(double));
    }
    const double bad[] = {-0.1, NAN, INFINITY};
    for (int i = 0; i < 3; i++) {
        assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, bad[i], keep, &b, NULL, NULL),
                         GSL_EINVAL);
        assert_non_null(strstr(whirl_last_error(), "the chart's air drag must be >= 0 and "
                                                    "finite"));
    }
    /* gamma pi / omega_min beyond 700 */
    const whirl_chart_params slow = {.omega_min = 0.01, .omega_max = 1, .amp_max = 0.1};
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &slow, 3, keep, &b, NULL, NULL),
                     GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "damps a period of the slowest rate"));
    whirl_chain_free(c);
    /* a tip mass: the drag's matrix not proportional to the mass matrix */
    c = whirl_chain_alloc_uniform(2, 0.5);
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, 0.1, keep, &b, NULL, NULL),
                     GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "one mass per length"));
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, 0, keep, &b, NULL, NULL), GSL_SUCCESS);
    whirl_chain_free(c);
    /* unequal links of one mass per length: accepted, gamma = c l_i / m_i */
    const double len[3] = {0.2, 0.3, 0.5}, mass[3] = {0.4, 0.6, 1.0};
    c = whirl_chain_alloc(3, len, mass, 1);
    b.n = 0;
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, 0.1, keep, &b, NULL, NULL),
                     GSL_SUCCESS);
    whirl_chain_free(c);
}

/* |mu| - 1 of the full chain's multiplier nearest the unit circle (air drag c) at (omega, A),
 * and the largest modulus. */
static double full_nearest(const whirl_chain *c, double drag, double omega, double amp,
                           double *largest)
{
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    assert_int_equal(whirl_pivot_line(&path, omega, amp, up), GSL_SUCCESS);
    const whirl_model model = {.chain = c, .dim = 2, .air_drag = drag};
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    assert_non_null(w);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    const whirl_periodic_params p = {.steps = 1600, .refine = 1};
    whirl_periodic_result r;
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
    double best = INFINITY;
    for (size_t i = 0; i < r.count; i++) {
        const double d = hypot(r.re[i], r.im[i]) - 1;
        if (fabs(d) < fabs(best)) best = d;
    }
    *largest = r.max_modulus;
    free(y);
    whirl_periodic_free(w);
    return best;
}

/* The chart of c with the drag: two points of each family (at every third rate from the
 * second) against the full chain's multipliers: the modulus nearest 1 crosses 1 between
 * A -+ 1e-8, and its root, from the three values, lies within 1e-9 of the chart's A (the chart's
 * bracket is 1e-10; on a steep edge |mu| changes by 200 per unit A, so 1e-10 in A is 2e-8 in
 * |mu|). */
static void check_full(const whirl_chain *c, double drag, const whirl_chart_params *pp)
{
    const whirl_chart_params p = *pp;
    pts s = {.n = 0};
    assert_int_equal(whirl_chart_vertical_damped(c, 2, &p, drag, keep, &s, NULL, NULL),
                     GSL_SUCCESS);
    int checked[2] = {0, 0};
    double worst = 0;
    for (int i = 0; i < s.n; i++) {
        const int kind = s.p[i].kind;
        if (checked[kind] >= 2 || s.p[i].column % 3 != 1) continue;
        double largest, l2;
        const double w = s.p[i].omega, a = s.p[i].amplitude, da = 1e-8;
        const double d = full_nearest(c, drag, w, a, &largest);
        const double lo = full_nearest(c, drag, w, a - da, &l2);
        const double hi = full_nearest(c, drag, w, a + da, &l2);
        assert_true((lo < 0) != (hi < 0));
        const double off = d * 2 * da / (hi - lo); /* the root's distance, by the secant */
        print_message("# N = %zu, drag %g: edge %s at omega %.6g, A %.12g: nearest |mu| - 1 "
                      "%.2g (the root %.2g away in A), |mu|max %.12g\n", c->n, drag,
                      kind ? "-1" : "+1", w, a, d, off, largest);
        if (fabs(off) > worst) worst = fabs(off);
        checked[kind]++;
    }
    assert_int_equal(checked[0], 2);
    assert_int_equal(checked[1], 2);
    assert_true(worst < 1e-9);
}

/* N = 3 with drag: mode 1's first tongue and mode 2's second (the uniform chain), and a chain of
 * unequal links of one mass per length (gamma = c l_i / m_i = c / 2). */
static void test_three_links(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    const whirl_chart_params p = {.omega_min = 2.0, .omega_max = 2.8, .columns = 9,
                                  .amp_max = 0.3, .rows = 30};
    check_full(c, 0.05, &p);
    whirl_chain_free(c);
    const double len[3] = {0.2, 0.3, 0.5}, mass[3] = {0.4, 0.6, 1.0};
    c = whirl_chain_alloc(3, len, mass, 1);
    const whirl_chart_params q = {.omega_min = 1.0, .omega_max = 4.0, .columns = 9,
                                  .amp_max = 0.3, .rows = 30};
    check_full(c, 0.1, &q);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mathieu_damped),
        cmocka_unit_test(test_threshold),
        cmocka_unit_test(test_sharp_bottom),
        cmocka_unit_test(test_inverted_damped),
        cmocka_unit_test(test_zero_and_bad),
        cmocka_unit_test(test_three_links),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
