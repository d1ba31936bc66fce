/* Tests of whirl_deviation: invariance under rotation about z, exact values for vertical
 * offsets, agreement with a brute-force minimisation over the angle, and precision for tiny
 * deviations (where expanding the square would cancel). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>

#include "whirl/dynamics.h"

#define N 37

/* A 3D chain-like cloud of points with coordinates of order 1. */
static void random_points(gsl_rng *r, size_t n, double *x)
{
    for (size_t i = 0; i < 3 * n; i++) x[i] = 2 * gsl_rng_uniform(r) - 1;
}

static void rotate_z(size_t n, double angle, const double *x, double *out)
{
    const double c = cos(angle), s = sin(angle);
    for (size_t i = 0; i < n; i++) {
        const double px = x[3 * i], py = x[3 * i + 1];
        out[3 * i] = c * px - s * py;
        out[3 * i + 1] = s * px + c * py;
        out[3 * i + 2] = x[3 * i + 2];
    }
}

/* RMS distance of R(angle) x from ref, summed directly. */
static double rms_at(size_t n, double angle, const double *x, const double *ref)
{
    double y[3 * N], sum = 0;
    rotate_z(n, angle, x, y);
    for (size_t i = 0; i < 3 * n; i++) sum += (y[i] - ref[i]) * (y[i] - ref[i]);
    return sqrt(sum / (double)n);
}

/* Brute force: a grid of 3600 angles, then golden-section refinement of the best cell. */
static double brute_force(size_t n, const double *x, const double *ref)
{
    const int grid = 3600;
    int best = 0;
    for (int k = 1; k < grid; k++)
        if (rms_at(n, 2 * M_PI * k / grid, x, ref) < rms_at(n, 2 * M_PI * best / grid, x, ref))
            best = k;
    double a = 2 * M_PI * (best - 1) / grid, b = 2 * M_PI * (best + 1) / grid;
    const double g = (sqrt(5.0) - 1) / 2;
    for (int it = 0; it < 200; it++) {
        double c = b - g * (b - a), d = a + g * (b - a);
        if (rms_at(n, c, x, ref) < rms_at(n, d, x, ref)) b = d;
        else a = c;
    }
    return rms_at(n, (a + b) / 2, x, ref);
}

static void test_rotation_invariance(void **state)
{
    (void)state;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    double ref[3 * N], x[3 * N];
    random_points(r, N, ref);
    assert_true(whirl_deviation(N, ref, ref) < 1e-15);
    const double angles[] = {0.3817, 2.385, -1.9, M_PI, 5.5};
    for (size_t k = 0; k < sizeof angles / sizeof angles[0]; k++) {
        rotate_z(N, angles[k], ref, x);
        assert_true(whirl_deviation(N, x, ref) < 1e-15);
    }
    gsl_rng_free(r);
}

/* Shifting every point vertically by h (then rotating) gives exactly |h|; a vertical shift
 * w_i per point gives the RMS of w, however small: to the round-off of the positions (1e-15),
 * where expanding the square would leave an error of about 1e-8. */
static void test_vertical_offsets(void **state)
{
    (void)state;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 7);
    double ref[3 * N], moved[3 * N], x[3 * N];
    random_points(r, N, ref);
    const double scales[] = {0.4375, 1e-3, 1e-10};
    for (size_t k = 0; k < 3; k++) {
        double sum = 0;
        for (size_t i = 0; i < N; i++) {
            const double w = scales[k] * (gsl_rng_uniform(r) - 0.25);
            moved[3 * i] = ref[3 * i];
            moved[3 * i + 1] = ref[3 * i + 1];
            moved[3 * i + 2] = ref[3 * i + 2] + w;
            sum += w * w;
        }
        rotate_z(N, 2.385, moved, x);
        const double expect = sqrt(sum / N);
        const double d = whirl_deviation(N, x, ref);
        assert_true(fabs(d - expect) < 1e-12 * expect + 1e-15);
    }
    gsl_rng_free(r);
}

static void test_against_brute_force(void **state)
{
    (void)state;
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(r, 2385);
    double ref[3 * N], x[3 * N];
    for (int trial = 0; trial < 20; trial++) {
        size_t n = 1 + gsl_rng_uniform_int(r, N);
        random_points(r, n, ref);
        random_points(r, n, x);
        const double d = whirl_deviation(n, x, ref), brute = brute_force(n, x, ref);
        assert_true(d <= brute + 1e-13);   /* closed form is the minimum */
        assert_true(fabs(d - brute) < 1e-10);
    }
    gsl_rng_free(r);
}

static void test_degenerate(void **state)
{
    (void)state;
    /* all points on the axis: any angle is optimal, the deviation is the vertical RMS */
    const double ref[6] = {0, 0, -1, 0, 0, -2}, x[6] = {0, 0, -1.5, 0, 0, -2};
    assert_true(fabs(whirl_deviation(2, x, ref) - sqrt(0.125)) < 1e-15);
    assert_true(isnan(whirl_deviation(0, x, ref)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rotation_invariance),
        cmocka_unit_test(test_vertical_offsets),
        cmocka_unit_test(test_against_brute_force),
        cmocka_unit_test(test_degenerate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
