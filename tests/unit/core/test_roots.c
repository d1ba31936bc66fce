/* Tests of the bracketing root finder (src/core/roots.h) against independent references:
 *  - the roots of cos x - x (the fixed point of the cosine, 0.739085133215160641655312087673873,
 *    from its series in the literature) and x^3 - 2 (cbrt from libm) to the requested
 *    tolerance;
 *  - the ends' known values: f is never called at lo or hi, and the search is the same as with
 *    f evaluated there (the same estimate and iterations);
 *  - the count of iterations: GSL_EMAXITER after max_iter, with the last bracket, which holds
 *    the root;
 *  - failures: f's own status ends the search at its first failure; a bracket without a sign
 *    change is refused (bracketed = 0, the midpoint as the estimate). */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "core/roots.h"

#define DOTTIE 0.739085133215160641655312087673873

typedef struct counter {
    int calls;
    int fail_at;  /* the call that fails (0: none) */
    double lo, hi; /* calls at these abscissae are counted in at_ends */
    int at_ends;
} counter;

static int cos_minus_x(double x, void *ctx, double *fx)
{
    counter *c = ctx;
    c->calls++;
    if (x == c->lo || x == c->hi) c->at_ends++;
    *fx = cos(x) - x;
    return c->fail_at && c->calls == c->fail_at ? GSL_EDOM : GSL_SUCCESS;
}

static int cube_minus_2(double x, void *ctx, double *fx)
{
    (void)ctx;
    *fx = x * x * x - 2;
    return GSL_SUCCESS;
}

static void test_roots(void **state)
{
    (void)state;
    counter c = {0, 0, -1, -1, 0};
    const whirl_root_opts o = {0, 2 * DBL_EPSILON, 100, 0, 0, 0};
    whirl_root r;
    assert_int_equal(whirl_root_brent(cos_minus_x, &c, 0, 1, &o, &r), GSL_SUCCESS);
    assert_true(fabs(r.root - DOTTIE) <= 4 * DBL_EPSILON);
    assert_true(r.lower <= DOTTIE && DOTTIE <= r.upper);
    assert_int_equal(r.bracketed, 1);
    /* the two ends, then one per iteration (none in an iteration that finds the bracket
     * already closed to GSL's own tolerance) */
    assert_in_range(c.calls, r.iterations + 1, r.iterations + 2);
    assert_in_range(r.iterations, 3, 20);        /* superlinear: bisection needs 52 */

    const whirl_root_opts wide = {1e-6, 0, 100, 0, 0, 0};
    assert_int_equal(whirl_root_brent(cube_minus_2, NULL, 1, 2, &wide, &r), GSL_SUCCESS);
    assert_true(r.upper - r.lower < 1e-6);
    assert_true(r.lower <= cbrt(2) && cbrt(2) <= r.upper);
    assert_true(fabs(r.root - cbrt(2)) < 1e-6);
}

static void test_known_ends(void **state)
{
    (void)state;
    const double lo = 0.25, hi = 1.5;
    counter plain = {0, 0, lo, hi, 0}, known = {0, 0, lo, hi, 0};
    const whirl_root_opts o = {0, 2 * DBL_EPSILON, 100, 0, 0, 0};
    const whirl_root_opts k = {0, 2 * DBL_EPSILON, 100, 1, cos(lo) - lo, cos(hi) - hi};
    whirl_root a, b;
    assert_int_equal(whirl_root_brent(cos_minus_x, &plain, lo, hi, &o, &a), GSL_SUCCESS);
    assert_int_equal(whirl_root_brent(cos_minus_x, &known, lo, hi, &k, &b), GSL_SUCCESS);
    assert_int_equal(plain.at_ends, 2);
    assert_int_equal(known.at_ends, 0);
    assert_int_equal(known.calls, plain.calls - 2);
    assert_int_equal(a.iterations, b.iterations);
    assert_true(a.root == b.root && a.lower == b.lower && a.upper == b.upper);
}

static void test_max_iter(void **state)
{
    (void)state;
    counter c = {0, 0, -1, -1, 0};
    const whirl_root_opts o = {0, 0, 2, 0, 0, 0}; /* a tolerance of 0: never met */
    whirl_root r;
    assert_int_equal(whirl_root_brent(cos_minus_x, &c, 0, 1, &o, &r), GSL_EMAXITER);
    assert_int_equal(r.iterations, 2);
    assert_int_equal(c.calls, 4);
    assert_true(0 <= r.lower && r.lower <= DOTTIE && DOTTIE <= r.upper && r.upper <= 1);
    assert_true(r.upper - r.lower < 1);
}

static void test_failures(void **state)
{
    (void)state;
    const whirl_root_opts o = {0, 2 * DBL_EPSILON, 100, 0, 0, 0};
    whirl_root r;
    /* f fails on its 4th call (the second iteration): its status, no call after it */
    counter c = {0, 4, -1, -1, 0};
    assert_int_equal(whirl_root_brent(cos_minus_x, &c, 0, 1, &o, &r), GSL_EDOM);
    assert_int_equal(c.calls, 4);
    assert_int_equal(r.iterations, 2);
    assert_int_equal(r.bracketed, 1);
    /* f fails at an end: not started */
    counter e = {0, 1, -1, -1, 0};
    assert_int_equal(whirl_root_brent(cos_minus_x, &e, 0, 1, &o, &r), GSL_EDOM);
    assert_int_equal(r.bracketed, 0);
    assert_int_equal(r.iterations, 0);
    /* no sign change on [1, 2]: refused, the midpoint as the estimate */
    counter n = {0, 0, -1, -1, 0};
    assert_int_equal(whirl_root_brent(cos_minus_x, &n, 1, 2, &o, &r), GSL_EINVAL);
    assert_int_equal(r.bracketed, 0);
    assert_int_equal(r.iterations, 0);
    assert_true(r.root == 1.5 && r.lower == 1 && r.upper == 2);
    /* known ends of one sign: refused without a call */
    counter k = {0, 0, -1, -1, 0};
    const whirl_root_opts same = {0, 0, 100, 1, 1, 2};
    assert_int_equal(whirl_root_brent(cos_minus_x, &k, 0, 1, &same, &r), GSL_EINVAL);
    assert_int_equal(k.calls, 0);
    assert_int_equal(r.bracketed, 0);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roots),
        cmocka_unit_test(test_known_ends),
        cmocka_unit_test(test_max_iter),
        cmocka_unit_test(test_failures),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
