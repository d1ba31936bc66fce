/* Tests of the general integrator interface (include/whirl/integrator.h) on systems that are not
 * the chain, against closed forms:
 *  - the harmonic oscillator q'' = -w^2 q as a second-order system: every fixed-step method
 *    reaches its order (error ratio at h and h/2 = 2^p within 15%: gauss2 4, gauss3 6, rk4 4,
 *    rk8 8, gsl-rk8pd 8, gsl-rk4 4, gsl-rkf45 5 and gsl-rk4imp 4); every adaptive method's
 *    global error over 3 periods falls with its tolerance (by more than 30 from 1e-7 to 1e-10,
 *    below 1e-6 at 1e-10);
 *  - rotation on the unit circle with a projection: the projection is called after every step;
 *  - the registry: names, lookup, the unknown-name message listing every method;
 *  - error paths: NULL and inconsistent systems, a method that needs what the system lacks, a
 *    failing right-hand side (its status returned, the last good state kept), a stop request
 *    (WHIRL_EINTERRUPTED, state kept), the cap on adaptive steps (GSL_EMAXITER, state kept). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#include "whirl/integrator.h"

#define W 1.385 /* the oscillator's rate */

static int oscillator(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    (void)params;
    dydt[0] = y[1];
    dydt[1] = -W * W * y[0];
    return GSL_SUCCESS;
}

static const whirl_system oscillator_system = {.rhs = oscillator, .size = 2, .second_order = 1,
                                               .acceleration_scale = W * W};

/* |y(t1) - exact| after integrating the oscillator from (1, 0) to t1. */
static double oscillator_error(const whirl_integrator_type *type, double h, double tol, double t1)
{
    whirl_integrator *it = whirl_integrator_alloc_system(type, &oscillator_system);
    assert_non_null(it);
    double y[2] = {1, 0}, t = 0;
    assert_int_equal(whirl_integrator_advance(it, &t, y, t1, h, tol), GSL_SUCCESS);
    assert_true(t == t1);
    whirl_integrator_free(it);
    return hypot(y[0] - cos(W * t1), (y[1] + W * sin(W * t1)) / W);
}

static void test_orders(void **state)
{
    (void)state;
    static const struct {
        const char *name;
        int order;
        double h;
    } cases[] = {{"gauss2", 4, 0.2},   {"gauss3", 6, 0.4},    {"rk4", 4, 0.1},
                 {"rk8", 8, 0.25},     {"gsl-rk8pd", 8, 0.25}, {"gsl-rk4", 4, 0.1},
                 {"gsl-rkf45", 5, 0.2}, {"gsl-rk4imp", 4, 0.2}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const whirl_integrator_type *type = whirl_integrator_type_find(cases[k].name);
        assert_non_null(type);
        assert_true(whirl_integrator_type_fixed(type));
        const double e1 = oscillator_error(type, cases[k].h, 0, 4.0);
        const double e2 = oscillator_error(type, cases[k].h / 2, 0, 4.0);
        const double order = log2(e1 / e2);
        print_message("# %-10s h %.3g: error %.3g, order %.2f\n", cases[k].name, cases[k].h, e1,
                      order);
        assert_true(fabs(order - cases[k].order) < 0.15 * cases[k].order);
    }
    for (const char *const *m = whirl_integrator_methods(); *m; m++) {
        const whirl_integrator_type *type = whirl_integrator_type_find(*m);
        if (!whirl_integrator_type_adaptive(type)) continue;
        const double t1 = 3 * 2 * M_PI / W;
        const double e1 = oscillator_error(type, 0.01, 1e-7, t1);
        const double e2 = oscillator_error(type, 0.01, 1e-10, t1);
        print_message("# %-11s error at tol 1e-7 %.3g, at 1e-10 %.3g\n", *m, e1, e2);
        assert_true(e2 < 1e-6 && e1 / e2 > 30);
    }
}

static int rotation(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    (void)params;
    dydt[0] = -y[1];
    dydt[1] = y[0];
    return GSL_SUCCESS;
}

static int onto_circle(double t, double y[], void *params)
{
    (void)t;
    (*(int *)params)++;
    const double r = hypot(y[0], y[1]);
    y[0] /= r;
    y[1] /= r;
    return GSL_SUCCESS;
}

static void test_projection(void **state)
{
    (void)state;
    int calls = 0;
    const whirl_system sys = {.rhs = rotation, .project = onto_circle, .size = 2,
                              .params = &calls};
    whirl_integrator *it = whirl_integrator_alloc_system(whirl_integrator_rk4, &sys);
    assert_non_null(it);
    double y[2] = {1, 0}, t = 0;
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2.0, 0.25, 0), GSL_SUCCESS);
    assert_int_equal(calls, 8);
    assert_int_equal((int)whirl_integrator_get_stats(it).steps, 8);
    assert_true(fabs(hypot(y[0], y[1]) - 1) < 1e-15);
    assert_true(whirl_integrator_type_of(it) == whirl_integrator_rk4);
    /* gauss needs a second-order system */
    assert_null(whirl_integrator_alloc_system(whirl_integrator_gauss2, &sys));
    assert_non_null(strstr(whirl_last_error(), "second-order"));
    whirl_system no_scale = oscillator_system;
    no_scale.acceleration_scale = 0;
    assert_null(whirl_integrator_alloc_system(whirl_integrator_gauss3, &no_scale));
    assert_non_null(strstr(whirl_last_error(), "acceleration_scale"));
    /* rk4 has no adaptive steps */
    assert_int_equal(whirl_integrator_advance(it, &t, y, 3.0, 0.25, 1e-6), GSL_EINVAL);
    whirl_integrator_free(it);
}

static void test_registry(void **state)
{
    (void)state;
    size_t n = 0;
    for (const char *const *m = whirl_integrator_methods(); *m; m++, n++) {
        const whirl_integrator_type *type = whirl_integrator_type_find(*m);
        assert_non_null(type);
        assert_string_equal(whirl_integrator_type_name(type), *m);
    }
    assert_int_equal(n, 10);
    assert_null(whirl_integrator_type_find("rk5"));
    const char *msg = whirl_last_error();
    assert_non_null(strstr(msg, "'rk5'"));
    for (const char *const *m = whirl_integrator_methods(); *m; m++)
        assert_non_null(strstr(msg, *m));
    assert_null(whirl_integrator_type_find(NULL));
    assert_true(whirl_integrator_gsl_msbdf == whirl_integrator_type_find("gsl-msbdf"));
    assert_false(whirl_integrator_type_fixed(whirl_integrator_gsl_msbdf));
}

static int fails_late(double t, const double y[], double dydt[], void *params)
{
    (void)params;
    if (t > 1.0) return GSL_EBADFUNC;
    return oscillator(t, y, dydt, NULL);
}

static void test_errors(void **state)
{
    (void)state;
    assert_null(whirl_integrator_alloc_system(NULL, &oscillator_system));
    assert_null(whirl_integrator_alloc_system(whirl_integrator_rk8, NULL));
    whirl_system bad = oscillator_system;
    bad.rhs = NULL;
    assert_null(whirl_integrator_alloc_system(whirl_integrator_rk8, &bad));
    assert_non_null(strstr(whirl_last_error(), "right-hand side"));
    bad = oscillator_system;
    bad.size = 0;
    assert_null(whirl_integrator_alloc_system(whirl_integrator_rk8, &bad));
    whirl_integrator_free(NULL);
    /* a failing right-hand side: its status, t and y at the last good step */
    bad = oscillator_system;
    bad.rhs = fails_late;
    whirl_integrator *it = whirl_integrator_alloc_system(whirl_integrator_rk4, &bad);
    assert_non_null(it);
    double y[2] = {1, 0}, t = 0;
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2.0, 0.1, 0), GSL_EBADFUNC);
    assert_true(t <= 1.0 && t > 0.85);
    assert_true(fabs(y[0] - cos(W * t)) < 1e-4);
    whirl_integrator_free(it);
    /* a stop request: WHIRL_EINTERRUPTED, the state at the last completed step (none here) */
    it = whirl_integrator_alloc_system(whirl_integrator_rk8, &oscillator_system);
    assert_non_null(it);
    y[0] = 1, y[1] = 0, t = 0;
    whirl_stop_request();
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2.0, 0.1, 0), WHIRL_EINTERRUPTED);
    assert_non_null(strstr(whirl_last_error(), "stop"));
    assert_true(t == 0 && y[0] == 1 && y[1] == 0);
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2.0, 0.1, 1e-8), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2.0, 0.1, 0), GSL_SUCCESS);
    assert_true(t == 2.0);
    whirl_integrator_free(it);
}

/* The cap on adaptive steps: counted across calls, GSL_EMAXITER with a message naming it, t and
 * y at the last completed step (on the exact solution); 0 restores the default, and the run
 * then ends. For every adaptive method. */
static void test_step_cap(void **state)
{
    (void)state;
    for (const char *const *name = whirl_integrator_methods(); *name != NULL; name++) {
        const whirl_integrator_type *type = whirl_integrator_type_find(*name);
        if (!whirl_integrator_type_adaptive(type)) continue;
        whirl_integrator *it = whirl_integrator_alloc_system(type, &oscillator_system);
        assert_non_null(it);
        whirl_integrator_set_max_steps(it, 200);
        double y[2] = {1, 0}, t = 0;
        assert_int_equal(whirl_integrator_advance(it, &t, y, 1.0, 0.01, 1e-10), GSL_SUCCESS);
        const unsigned long first = whirl_integrator_get_stats(it).steps;
        assert_true(first > 0 && first < 200);
        assert_int_equal(whirl_integrator_advance(it, &t, y, 100.0, 0.01, 1e-10), GSL_EMAXITER);
        const whirl_integrator_stats st = whirl_integrator_get_stats(it);
        print_message("# %s: cap 200 reached at t = %g (%lu accepted, %lu rejected): %s\n", *name,
                      t, st.steps, st.rejected, whirl_last_error());
        assert_true(st.steps + st.rejected >= 200 && st.steps <= 200);
        assert_non_null(strstr(whirl_last_error(), "200 adaptive steps (the cap)"));
        assert_non_null(strstr(whirl_last_error(), "loosen the tolerance"));
        assert_true(t > 1.0 && t < 100.0);
        assert_true(hypot(y[0] - cos(W * t), (y[1] + W * sin(W * t)) / W) < 1e-6);
        whirl_integrator_set_max_steps(it, 0);
        assert_int_equal(whirl_integrator_advance(it, &t, y, 100.0, 0.01, 1e-10), GSL_SUCCESS);
        assert_true(t == 100.0);
        whirl_integrator_free(it);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_orders),
        cmocka_unit_test(test_projection),
        cmocka_unit_test(test_registry),
        cmocka_unit_test(test_step_cap),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("integrator", tests, NULL, NULL);
}
