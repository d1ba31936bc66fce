/* Tests of the failure record (src/core/error.c): the status kept beside the message, typed
 * quantities printed in units, and a failure carried from OpenMP threads to the caller's.
 * The units are checked against the arithmetic they stand for (a rate times sqrt(g/L), and over
 * 2 pi in Hz; a length times L), written independently here with printf. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_math.h>

#include "whirl/common.h"
#include "whirl/steady.h"
#include "core/error.h"

static void status_beside_message(void **state)
{
    (void)state;
    assert_int_equal(whirl_fail(GSL_EDOM, "no shape at omega=" WHIRL_Q_RATE "%.17g", 0.1),
                     GSL_EDOM);
    assert_int_equal(whirl_last_status(), GSL_EDOM);
    assert_string_equal(whirl_last_error(), "no shape at omega=0.10000000000000001");
    assert_int_equal(whirl_fail(GSL_EINVAL, "plain"), GSL_EINVAL);
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    assert_string_equal(whirl_last_error(), "plain");
}

/* A constructor that fails leaves its status: a chain without links is a bad argument, not a
 * lack of memory. */
static void constructor_status(void **state)
{
    (void)state;
    whirl_fail(GSL_SUCCESS, "%s", "");
    assert_null(whirl_nlink_path_alloc(NULL));
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(NULL, 2, 1, &info), GSL_EINVAL);
    assert_string_equal(whirl_last_error(), "a chain needs at least one link");
}

static void quantities_in_units(void **state)
{
    (void)state;
    char buf[256], want[256];
    const double L = 0.6, M = 0.05, g = 9.80665, rate = sqrt(g / L);
    whirl_fail(GSL_EDOM, "mode 3 at omega=" WHIRL_Q_RATE "%.17g above omega_3 = " WHIRL_Q_RATE
               "%g, tip radius " WHIRL_Q_LENGTH "%.6g, mass " WHIRL_Q_MASS "%g, t " WHIRL_Q_TIME
               "%g, T " WHIRL_Q_FORCE "%g, n %d", 0.1, 4.25, 0.125, 2.0, 3.0, 0.5, 7);
    /* dimensionless: 17 digits shortened, the rest as written */
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 0, 1, 1, 1, 0),
                        "mode 3 at omega=0.1 above omega_3 = 4.25, tip radius 0.125, mass 2, "
                        "t 3, T 0.5, n 7");
    /* SI: the digits the message gave (17 -> at most 15, 3 -> at least 6) */
    snprintf(want, sizeof want, "mode 3 at omega=%.15g rad/s above omega_3 = %.6g rad/s, tip "
             "radius %.6g m, mass %.6g kg, t %.6g s, T %.6g N, n 7", 0.1 * rate, 4.25 * rate,
             0.125 * L, 2 * M, 3 / rate, 0.5 * M * g);
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 1, L, M, g, 0), want);
    snprintf(want, sizeof want, "mode 3 at omega=%.15g Hz above omega_3 = %.6g Hz, tip "
             "radius %.6g m, mass %.6g kg, t %.6g s, T %.6g N, n 7",
             0.1 * rate / (2 * M_PI), 4.25 * rate / (2 * M_PI), 0.125 * L, 2 * M, 3 / rate,
             0.5 * M * g);
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 1, L, M, g, 1), want);
    /* a number that does not print as one stays as it is; the plain text has no marks */
    whirl_fail(GSL_ERANGE, "omega=" WHIRL_Q_RATE "%g", INFINITY);
    assert_string_equal(whirl_last_error(), "omega=inf");
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 1, L, M, g, 0), "omega=inf");
    /* quoted in a second message, the quantities stay typed */
    whirl_fail(GSL_EDOM, "omega=" WHIRL_Q_RATE "%g", 2.0);
    whirl_fail(GSL_EFAILED, "start: %s", whirl_error_marked());
    snprintf(want, sizeof want, "start: omega=%.6g rad/s", 2 * rate);
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 1, L, M, g, 0), want);
    assert_string_equal(whirl_last_error(), "start: omega=2");
}

/* The hand-swung chain's drags and the internal damping: kg/(m s) = M sqrt(g/L) / L, kg/m^2 =
 * M / L^2, kg m^2/s = M L^2 sqrt(g/L) (whirl.Units' drag, drag2, damping). */
static void drags_in_units(void **state)
{
    (void)state;
    char buf[256], want[256];
    const double L = 0.6, M = 0.05, g = 9.80665, rate = sqrt(g / L);
    whirl_fail(GSL_EDOM, "eps " WHIRL_Q_LENGTH "%g, drag " WHIRL_Q_DRAG "%g, " WHIRL_Q_DRAG2
               "%g, damping " WHIRL_Q_DAMPING "%g", 0.05, 0.25, 2.0, 1e-3);
    assert_string_equal(whirl_last_error(), "eps 0.05, drag 0.25, 2, damping 0.001");
    snprintf(want, sizeof want, "eps %.6g m, drag %.6g kg/(m s), %.6g kg/m^2, damping %.6g "
             "kg m^2/s", 0.05 * L, 0.25 * M * rate / L, 2 * M / (L * L), 1e-3 * M * L * L * rate);
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 1, L, M, g, 0), want);
}

/* Failures on OpenMP threads reach the caller's thread with status, text and types: the earliest
 * block's by whirl_error_restore_first, the first to fail by whirl_error_keep. */
static void carried_from_threads(void **state)
{
    (void)state;
    enum { BLOCKS = 8 };
    whirl_error_record rec[BLOCKS], shared = {GSL_SUCCESS, ""};
    whirl_fail(GSL_SUCCESS, "%s", "");
#pragma omp parallel for num_threads(4)
    for (int b = 0; b < BLOCKS; b++) {
        rec[b].status = GSL_SUCCESS;
        int status = b >= 3 ? whirl_fail(b == 3 ? GSL_EMAXITER : GSL_EFAILED,
                                         "block %d at omega=" WHIRL_Q_RATE "%g", b, 1.5 * b)
                            : GSL_SUCCESS;
        whirl_error_keep(&rec[b], status);
        whirl_error_keep(&shared, status);
    }
    /* nothing leaked into this thread's record by the threads (the master's own was cleared) */
    assert_int_equal(whirl_error_restore_first(rec, 3), GSL_SUCCESS);
    assert_int_equal(whirl_error_restore_first(rec, BLOCKS), GSL_EMAXITER);
    assert_int_equal(whirl_last_status(), GSL_EMAXITER);
    assert_string_equal(whirl_last_error(), "block 3 at omega=4.5");
    char buf[128], want[128];
    snprintf(want, sizeof want, "block 3 at omega=%.6g rad/s", 4.5 * sqrt(9.80665 / 2));
    assert_string_equal(whirl_last_error_in_units(buf, sizeof buf, 1, 2, 1, 9.80665, 0), want);
    assert_true(shared.status == GSL_EMAXITER || shared.status == GSL_EFAILED);
    assert_int_equal(whirl_error_restore(&shared), shared.status);
    assert_non_null(strstr(whirl_last_error(), "block "));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(status_beside_message),
        cmocka_unit_test(constructor_status),
        cmocka_unit_test(quantities_in_units),
        cmocka_unit_test(drags_in_units),
        cmocka_unit_test(carried_from_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
