/* Tests of the dissipation's decay rate (whirl_model_stiff_rate, whirl_model_stiff_cause in
 * include/whirl/dynamics.h), against the header's formula computed here link by link:
 * 16 D / (m_i l_i^2) at its largest plus l_i (c + 2 c2 v) / m_i at its largest, v = |omega|
 * (L + drive_radius):
 *  - uniform chains: damping only (also the closed form 16 D N^3 / (M L^2)), linear drag only
 *    (c L / M whatever N), both;
 *  - a non-uniform chain whose least m_i l_i^2 is not min m min l^2: damping, drag, both,
 *    quadratic drag with a drive radius and a negative omega;
 *  - the cause named: damping, drag, both when each gives a tenth or more;
 *  - whirl_default_step's rk4 step is 2 / rate when the dissipation bounds it;
 *  - NULL, a model without a chain and no dissipation give 0. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/chain.h"
#include "whirl/dynamics.h"

/* The header's formula, one link at a time. */
static double expected(const whirl_model *m)
{
    const whirl_chain *c = m->chain;
    double total = 0, damping = 0, drag = 0;
    for (size_t i = 0; i < c->n; i++) total += c->length[i];
    const double v = fabs(m->omega) * (total + m->drive_radius);
    for (size_t i = 0; i < c->n; i++) {
        const double l = c->length[i], mass = c->mass[i];
        damping = fmax(damping, 16 * m->internal_damping / (mass * l * l));
        drag = fmax(drag, l / mass * (m->air_drag + 2 * m->air_drag_quadratic * v));
    }
    return damping + drag;
}

static void assert_close(double got, double want)
{
    if (!(fabs(got - want) <= 1e-14 * fabs(want))) fail_msg("rate %.17g, expected %.17g", got, want);
}

static void test_uniform(void **state)
{
    (void)state;
    const size_t n = 30;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_model m = {.chain = c, .dim = 3, .omega = 3.0, .internal_damping = 1e-3};
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    assert_close(whirl_model_stiff_rate(&m), 16 * 1e-3 * 30.0 * 30.0 * 30.0);
    assert_string_equal(whirl_model_stiff_cause(&m), "the internal damping makes");
    m.internal_damping = 0;
    m.air_drag = 500;
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    assert_close(whirl_model_stiff_rate(&m), 500.0); /* c L / M */
    assert_string_equal(whirl_model_stiff_cause(&m), "the air drag makes");
    m.internal_damping = 1e-3; /* 432 and 500 */
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    assert_close(whirl_model_stiff_rate(&m), 932.0);
    assert_string_equal(whirl_model_stiff_cause(&m), "the internal damping and the air drag make");
    m.air_drag = 20; /* under a tenth of 452 */
    assert_string_equal(whirl_model_stiff_cause(&m), "the internal damping makes");
    whirl_chain_free(c);
}

static void test_non_uniform(void **state)
{
    (void)state;
    /* m l^2 = 0.006, 0.025, 0.048: the least 0.006, not min m min l^2 = 0.001 */
    double length[] = {0.1, 0.5, 0.4}, mass[] = {0.6, 0.1, 0.3};
    whirl_chain *c = whirl_chain_alloc(3, length, mass, 1.0);
    assert_non_null(c);
    whirl_model m = {.chain = c, .dim = 3, .omega = 2.0, .internal_damping = 0.03};
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    assert_close(whirl_model_stiff_rate(&m), 16 * 0.03 / 0.006);
    m.internal_damping = 0;
    m.air_drag = 7; /* the largest l / m: 0.5 / 0.1 */
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    assert_close(whirl_model_stiff_rate(&m), 35.0);
    m.internal_damping = 0.03;
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    /* quadratic drag: v = |omega| (L + eps) = 2.5 (1 + 0.2) = 3 */
    m.air_drag = 0;
    m.internal_damping = 0;
    m.air_drag_quadratic = 4;
    m.drive_radius = 0.2;
    m.omega = -2.5;
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    assert_close(whirl_model_stiff_rate(&m), 5.0 * 2 * 4 * 3.0);
    m.air_drag = 1.5;
    m.internal_damping = 0.01;
    assert_close(whirl_model_stiff_rate(&m), expected(&m));
    whirl_chain_free(c);
}

static void test_default_step_and_edges(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(12, 0);
    whirl_model m = {.chain = c, .dim = 3, .omega = 2.0};
    assert_true(whirl_model_stiff_rate(&m) == 0);
    assert_true(whirl_model_stiff_rate(NULL) == 0);
    assert_non_null(whirl_model_stiff_cause(NULL));
    double tension[12], h;
    for (size_t j = 0; j < 12; j++) tension[j] = 1.0 - (double)j / 12;
    m.internal_damping = 5; /* 16 D N^3 = 138240: far past the waves' bound */
    assert_int_equal(whirl_default_step(&m, tension, "rk4", &h), GSL_SUCCESS);
    assert_true(h == 2 / whirl_model_stiff_rate(&m));
    whirl_model none = m;
    none.chain = NULL;
    assert_true(whirl_model_stiff_rate(&none) == 0);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform),
        cmocka_unit_test(test_non_uniform),
        cmocka_unit_test(test_default_step_and_edges),
    };
    return cmocka_run_group_tests_name("stiff_rate", tests, NULL, NULL);
}
