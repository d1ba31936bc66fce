/* Tests of the recursion up from the tip (src/steady/tip_up.h) against independent references,
 * on a chain of unequal links and masses:
 *  - the force balance: the radii and heights it gives (a = 1, u_N = r_N) put every link along
 *    the resultant of the weights and centrifugal forces of the masses below it, summed here
 *    directly from the positions (not by the recursion), and T_i is that resultant's length;
 *  - scaling: per unit tip radius (u_N = 1, tip radius a) it gives the same shape divided by a;
 *  - precision: the long double and quadruple instantiations agree with double to a few
 *    rounding units of the whole (the recursion is well conditioned at these rates), and the
 *    quadruple one with long double to 1e-17;
 *  - the linearised recursion (T = V) is the limit a -> 0 of the nonlinear one, with an error
 *    O(a^2);
 *  - the guarded square root equals hypot to rounding where H^2 + V^2 is small, and stays
 *    finite (flag big) where it overflows, at omega = 1e160. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "steady/tip_up.h"
#include "whirl/chain.h"

#define N 12

static whirl_chain *chain(void)
{
    double l[N], m[N];
    for (int i = 0; i < N; i++) {
        l[i] = (1 + 0.3 * sin(1.7 * i)) / N;
        m[i] = (1 + 0.5 * cos(2.3 * i)) / N;
    }
    whirl_chain *c = whirl_chain_alloc(N, l, m, 1.0);
    assert_non_null(c);
    return c;
}

static void test_force_balance(void **state)
{
    (void)state;
    whirl_chain *c = chain();
    const double omega = 7.3, tip = 0.21;
    double r[N + 1], z[N + 1], t[N + 1];
    tip_up s = tip_up_start(c, omega, omega, 1, tip);
    r[N] = tip, z[N] = 0;
    for (size_t i = N; i >= 1; i--) {
        tip_up_link(&s, c, i, TIP_UP_HYPOT);
        r[i - 1] = s.u;
        z[i - 1] = z[i] + c->length[i - 1] * s.v / s.t;
        t[i] = s.t;
    }
    for (size_t i = 1; i <= N; i++) {
        double h = 0, v = 0;
        for (size_t j = i; j <= N; j++) {
            h += c->mass[j - 1] * omega * omega * r[j];
            v += c->mass[j - 1] * c->gravity;
        }
        const double dr = r[i] - r[i - 1], dz = z[i - 1] - z[i], l = c->length[i - 1];
        assert_true(fabs(dr / l - h / hypot(h, v)) < 1e-14);
        assert_true(fabs(dz / l - v / hypot(h, v)) < 1e-14);
        assert_true(fabs(t[i] - hypot(h, v)) < 1e-14 * hypot(h, v));
        assert_true(fabs(hypot(dr, dz) - l) < 1e-14);
    }
    /* per unit tip radius: the same shape over a */
    tip_up u = tip_up_start(c, omega * omega, 1, tip, 1);
    for (size_t i = N; i >= 1; i--) {
        tip_up_link(&u, c, i, TIP_UP_HYPOT);
        assert_true(fabs(u.u * tip - r[i - 1]) < 1e-14);
    }
    whirl_chain_free(c);
}

static void test_precisions(void **state)
{
    (void)state;
    whirl_chain *c = chain();
    const double omega = 9.1, a = 0.05;
    tip_up d = tip_up_start(c, omega * omega, 1, a, 1);
    tip_up_ext e = tip_up_ext_start(c, (long double)omega * omega, 1, a, 1);
    tip_up_quad q = tip_up_quad_start(c, (nlink_quad)omega * omega, 1, a, 1);
    double scale = 1;
    for (size_t i = N; i >= 1; i--) {
        tip_up_link(&d, c, i, TIP_UP_HYPOT);
        tip_up_ext_link(&e, c, i, TIP_UP_SQRT);
        tip_up_quad_link(&q, c, i, TIP_UP_HYPOT);
        scale = fmax(scale, fabs(d.u));
        assert_true(fabs(d.u - (double)q.u) < 64 * DBL_EPSILON * scale);
        assert_true(fabsl(e.u - (long double)q.u) < 1e-17L * scale);
        assert_true(fabs(d.t - (double)q.t) < 8 * DBL_EPSILON * (double)q.t);
    }
    whirl_chain_free(c);
}

static void test_linear_limit(void **state)
{
    (void)state;
    whirl_chain *c = chain();
    const double omega = 6.0;
    tip_up lin = tip_up_start(c, omega * omega, 1, 0, 1);
    for (size_t i = N; i >= 1; i--) tip_up_link(&lin, c, i, TIP_UP_LINEAR);
    double err[3];
    const double a[3] = {2e-3, 1e-3, 5e-4};
    for (int k = 0; k < 3; k++) {
        tip_up s = tip_up_start(c, omega * omega, 1, a[k], 1);
        for (size_t i = N; i >= 1; i--) tip_up_link(&s, c, i, TIP_UP_HYPOT);
        err[k] = fabs(s.u - lin.u);
        assert_true(err[k] > 0);
    }
    /* halving a quarters the error (O(a^2)) */
    for (int k = 0; k < 2; k++) assert_in_range((long)(100 * err[k] / err[k + 1]), 390, 410);
    whirl_chain_free(c);
}

static void test_guarded_sqrt(void **state)
{
    (void)state;
    whirl_chain *c = chain();
    tip_up h = tip_up_start(c, 8.0 * 8.0, 1, 0.1, 1), g = tip_up_start(c, 8.0 * 8.0, 1, 0.1, 1);
    for (size_t i = N; i >= 1; i--) {
        tip_up_link(&h, c, i, TIP_UP_HYPOT);
        tip_up_link(&g, c, i, TIP_UP_SQRT_BIG);
        assert_int_equal(g.big, 0);
        assert_true(fabs(g.t - h.t) <= 2 * DBL_EPSILON * h.t);
    }
    /* omega = 1e80: H ~ 1e159, whose square overflows H^2 + V^2, not hypot */
    tip_up b = tip_up_start(c, 1e160, 1, 1, 1), p = tip_up_start(c, 1e160, 1, 1, 1);
    tip_up_link(&b, c, N, TIP_UP_SQRT_BIG);
    tip_up_link(&p, c, N, TIP_UP_SQRT);
    assert_int_equal(b.big, 1);
    assert_true(isfinite(b.t) && b.t > 0);
    assert_false(isfinite(p.t));
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_force_balance),
        cmocka_unit_test(test_precisions),
        cmocka_unit_test(test_linear_limit),
        cmocka_unit_test(test_guarded_sqrt),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
