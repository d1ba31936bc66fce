/* Tests of the page's interface (src/web/whirl_web.c) in the native build: the state read with
 * the command line's units, the answer's numbers those of the library (the tip radius of
 * whirl_continuum_solve at the same rate, written so that it reads back to the same double), a
 * bad or unknown parameter answered with its name and nothing computed, the hanging chain below
 * a mode's birth. The page itself runs the same C as WebAssembly (tests/cli/test_web.sh). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_math.h>

#include "whirl/steady.h"
#include "web/whirl_web.h"

/* The number after "key": in the JSON text a (the first one). */
static double number(const char *a, const char *key)
{
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    const char *p = strstr(a, pattern);
    if (p == NULL) fail_msg("no %s in %.300s", key, a);
    return strtod(p + strlen(pattern), NULL);
}

static void shape_numbers(void **state)
{
    (void)state;
    char *a = whirl_web_shape("length=60cm&mass=50g&rate=4Hz&mode=2");
    assert_non_null(a);
    assert_null(strstr(a, "\"error\""));
    whirl_shape_info info;
    const double w = 4 * 2 * M_PI * sqrt(0.6 / 9.80665); /* the library's units */
    assert_int_equal(whirl_continuum_solve(w, 2, 0, 0, &info), GSL_SUCCESS);
    assert_true(number(a, "tip_r") == fabs(info.tip_r) * 0.6);
    assert_true(number(a, "node_count") == 2);
    assert_true(number(a, "rate") == 4);
    assert_non_null(strstr(a, "\"unit\":\"Hz\""));
    assert_non_null(strstr(a, "\"verdict\":\"neutral (gyroscopic)\""));
    assert_true(number(a, "verdict_links") == 30);
    whirl_web_free(a);
}

static void bad_parameters(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"length=60cm&mass=5x&rate=4Hz&mode=2", "\"field\":\"mass\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=2&colour=red", "\"field\":\"colour\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=2&links=1", "\"field\":\"links\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=5&links=3", "\"field\":\"mode\""},
        {"length=60cm&mass=50g&rate=400Hz&mode=2", "\"field\":\"rate\""},
        {"length=60cm&mass=50g&rate=4kHz&mode=2", "\"field\":\"rate\""},
        {"length=60cm&mass=50g&mode=2", "\"field\":\"rate\""},
        {"length=-1&mass=50g&rate=4Hz&mode=2", "\"field\":\"length\""},
        {"length=60cm&mass=50g&rate=nan&mode=2", "\"field\":\"rate\""},
        {"length", "\"field\":\"length\""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char *a = whirl_web_shape(cases[i][0]);
        assert_non_null(a);
        if (strncmp(a, "{\"error\":", 9) != 0 || strstr(a, cases[i][1]) == NULL)
            fail_msg("%s: %s", cases[i][0], a);
        assert_null(strstr(a, "\"x\""));
        whirl_web_free(a);
    }
    char *long_query = malloc(4000);
    memset(long_query, 'a', 3999);
    long_query[3999] = 0;
    char *a = whirl_web_shape(long_query);
    assert_non_null(strstr(a, "longer than"));
    whirl_web_free(a);
    free(long_query);
}

static void below_birth(void **state)
{
    (void)state;
    char *a = whirl_web_shape("length=60cm&mass=50g&rate=1Hz&mode=2");
    assert_non_null(strstr(a, "\"hanging\":true"));
    double w2;
    assert_int_equal(whirl_continuum_critical(2, 0, &w2), GSL_SUCCESS);
    const double born = w2 / sqrt(0.6 / 9.80665) / (2 * M_PI);
    assert_true(fabs(number(a, "born") - born) <= 1e-15 * born);
    assert_null(strstr(a, "\"verdict\""));
    whirl_web_free(a);
}

static void branches_and_windows(void **state)
{
    (void)state;
    char *a = whirl_web_branches("length=60cm&mass=50g&rate=4Hz&mode=2&rmax=12Hz");
    assert_null(strstr(a, "\"error\""));
    assert_true(number(a, "rate_max") == 12);
    assert_non_null(strstr(a, "{\"mode\":1"));
    assert_non_null(strstr(a, "{\"mode\":4"));
    whirl_web_free(a);
    a = whirl_web_windows("length=60cm&mass=50g&rate=4Hz&mode=2&rmax=12Hz");
    assert_null(strstr(a, "\"error\""));
    assert_non_null(strstr(a, "\"windows\":[["));
    whirl_web_free(a);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shape_numbers),
        cmocka_unit_test(bad_parameters),
        cmocka_unit_test(below_birth),
        cmocka_unit_test(branches_and_windows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
