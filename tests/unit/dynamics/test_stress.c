/* Numerical stress tests of the dynamics (quick versions; the long ones are in
 * tests/bench/bench_stress.c). Each case either meets a stated error bound against an independent
 * answer or stops with a failure status and a message; none leaves a non-finite number:
 *  - a fast spin (omega = 30, N = 100): the exact steady shape stays a fixed point in the
 *    co-rotating frame; a step too large for the fastest mode fails with GSL_EMAXITER;
 *  - a tip mass 100 times the chain's: hanging tensions equal the weight below; energy kept;
 *  - links folded back on each other (a vertical zig-zag at rest): exact tensions +-weight below
 *    (compression in the upward links) and no motion; the seed formulation refuses the state;
 *  - a chain passing through the vertical (3D, planar swing): energy and constraints kept in the
 *    Cartesian formulation; the seed formulation, singular there, agrees or stops with a status;
 *  - omega within 1e-6 of a critical rate: the N-link shape exists just above it and is a fixed
 *    point, just below it the solver says so (GSL_EDOM); the hanging chain stays hanging;
 *  - tolerances at round-off (gsl-rk8pd, tol 1e-15 and 1e-16): accurate to 1e-11 against gauss3
 *    or a failure status;
 *  - N = 10^5: hanging tensions to 1e-12 relative, a few finite steps that keep the
 *    constraints. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "test_stress"
#include "bench_util.h" /* bench_steady_positions */

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* Runs method from (x, v) at t = 0 to t1 (fixed step h, or tol > 0); final positions in x, v.
 * Returns the status; y must hold whirl_dyn_size(d) doubles. */
static int run(whirl_dyn *d, const char *method, double *x, double *v, double *y, double t1,
               double h, double tol)
{
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    whirl_integrator *it = whirl_integrator_alloc(method, d);
    assert_non_null(it);
    double t = 0;
    const int status = whirl_integrator_advance(it, &t, y, t1, h, tol);
    whirl_integrator_free(it);
    assert_true(all_finite(y, whirl_dyn_size(d)));
    whirl_dyn_get_state(d, t, y, whirl_dyn_model(d)->frame, x, v);
    return status;
}

/* omega = 30, N = 100, mode 2: the exact relative equilibrium stays put to 1e-9 over 200 gauss2
 * steps at h = 2e-4 (fastest mode ~ 2 N sqrt(T_top) ~ 4000: h omega_max rho(A) ~ 0.25); at
 * h = 0.01 the stage iteration cannot converge and says so. */
static void test_fast_spin(void **unused)
{
    (void)unused;
    const size_t n = 100;
    const double omega = 30;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    double *x0 = malloc(3 * n * sizeof *x0), *y = malloc(6 * n * sizeof *y);
    assert_int_equal(bench_steady_positions(c, omega, 2, x), GSL_SUCCESS);
    memcpy(x0, x, 3 * n * sizeof *x);
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(d);
    assert_int_equal(run(d, "gauss2", x, v, y, 0.04, 2e-4, 0), GSL_SUCCESS);
    assert_true(bench_max_distance(n, x, x0) < 1e-9);
    memcpy(x, x0, 3 * n * sizeof *x);
    memset(v, 0, 3 * n * sizeof *v);
    v[3 * (n - 1) + 1] = 0.01; /* a kick, so that the stages have something to solve */
    const int status = run(d, "gauss2", x, v, y, 0.1, 0.01, 0);
    assert_int_equal(status, GSL_EMAXITER);
    assert_non_null(strstr(whirl_last_error(), "Gauss stage iteration"));
    whirl_dyn_free(d);
    whirl_chain_free(c);
    free(x), free(v), free(x0), free(y);
}

/* Tip mass 100 (the chain's mass is 1), N = 20: hanging tensions equal 100 + the chain below to
 * 1e-14 relative; a swing (tip kicked sideways) conserves the energy to 1e-10 of the kinetic
 * energy given, and the constraints to 1e-12, over t = 3 with gauss3 at h = 2e-3. */
static void test_heavy_tip(void **unused)
{
    (void)unused;
    const size_t n = 20;
    const double tip = 100;
    whirl_chain *c = whirl_chain_alloc_uniform(n, tip);
    assert_non_null(c);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[60] = {0}, v[60] = {0}, y[120], ten[20];
    for (size_t i = 0; i < n; i++) x[3 * i + 2] = -(double)(i + 1) / (double)n;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_tensions(d, 0, y, ten), GSL_SUCCESS);
    for (size_t i = 0; i < n; i++) {
        const double below = tip + (double)(n - i) / (double)n;
        assert_true(fabs(ten[i] / below - 1) < 1e-14);
    }
    for (size_t i = 0; i < n; i++) v[3 * i] = 0.3 * (double)(i + 1) / (double)n;
    whirl_dyn_diagnostics d0, d1;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    whirl_dyn_diagnose(d, 0, y, &d0);
    assert_int_equal(run(d, "gauss3", x, v, y, 3, 2e-3, 0), GSL_SUCCESS);
    whirl_dyn_diagnose(d, 3, y, &d1);
    const double kinetic = 0.5 * (tip + 1.0 / n) * 0.09; /* about the kinetic energy given */
    assert_true(fabs(d1.energy - d0.energy) < 1e-10 * kinetic);
    assert_true(d1.constraint < 1e-12);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* Links folded back on each other: d_i = s_i l z with s_i = -1, +1, -1, ... (a vertical
 * zig-zag), at rest. Every mass then keeps the pivot's acceleration 0, and the force balance
 * -T_i s_i + T_{i+1} s_{i+1} = m_i g gives T_i = -s_i g M_i (M_i the mass below): tension in the
 * downward links, compression in the upward ones. */
static void test_folded(void **unused)
{
    (void)unused;
    const size_t n = 9;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.385);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[27] = {0}, v[27] = {0}, x0[27], y[54], ten[9];
    double z = 0;
    for (size_t i = 0; i < n; i++) {
        z += (i % 2 == 0 ? -1 : 1) * c->length[i];
        x[3 * i + 2] = z;
    }
    memcpy(x0, x, sizeof x);
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_tensions(d, 0, y, ten), GSL_SUCCESS);
    double below = 0;
    for (size_t i = n; i-- > 0;) {
        below += c->mass[i] * c->gravity;
        const double expected = (i % 2 == 0 ? 1 : -1) * below;
        assert_true(fabs(ten[i] / expected - 1) < 1e-14);
    }
    assert_int_equal(run(d, "gauss2", x, v, y, 1, 0.01, 0), GSL_SUCCESS);
    assert_true(bench_max_distance(n, x, x0) < 1e-14);
    /* the seed's angles are singular at sin(theta) = 0: a clear refusal */
    whirl_dyn *s = whirl_dyn_alloc(&m, WHIRL_FORMULATION_SEED);
    assert_non_null(s);
    double ys[36];
    assert_int_equal(whirl_dyn_set_state(s, 0, x0, v, ys), GSL_EINVAL);
    assert_true(strlen(whirl_last_error()) > 0);
    whirl_dyn_free(s);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* A 3D chain of 4 links swinging in the x-z plane through the vertical (start: hanging, rates
 * 1.1 / (i + 1) about y, from theta = 1e-3), t = 0..4: the Cartesian formulation keeps the energy to 1e-12 and the
 * constraints to 1e-13 with gauss3 (h = 1e-3); the seed formulation from the same start
 * (its angles need theta != 0) either agrees with it to 1e-6 or stops with a
 * failure status and a message. */
static void test_through_vertical(void **unused)
{
    (void)unused;
    const size_t n = 4;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[12], v[12], y[24], xs[12], vs[12];
    /* d_i = l_i (sin th, 0, -cos th), d_i' = l_i th_i' (cos th, 0, sin th), th = 1e-3 */
    const double th = 1e-3;
    double px = 0, pz = 0, vx = 0, vz = 0;
    for (size_t i = 0; i < n; i++) {
        const double rate = 1.1 / (double)(i + 1);
        px += c->length[i] * sin(th);
        pz -= c->length[i] * cos(th);
        vx += c->length[i] * rate * cos(th);
        vz += c->length[i] * rate * sin(th);
        x[3 * i] = px, x[3 * i + 1] = 0, x[3 * i + 2] = pz;
        v[3 * i] = vx, v[3 * i + 1] = 0, v[3 * i + 2] = vz;
    }
    memcpy(xs, x, sizeof x);
    memcpy(vs, v, sizeof v);
    whirl_dyn_diagnostics d0, d1;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    whirl_dyn_diagnose(d, 0, y, &d0);
    assert_int_equal(run(d, "gauss3", x, v, y, 4, 1e-3, 0), GSL_SUCCESS);
    whirl_dyn_diagnose(d, 4, y, &d1);
    assert_true(fabs(d1.energy - d0.energy) < 1e-12);
    assert_true(d1.constraint < 1e-13);
    whirl_dyn *s = whirl_dyn_alloc(&m, WHIRL_FORMULATION_SEED);
    double ys[16];
    const int status = run(s, "gauss3", xs, vs, ys, 4, 1e-3, 0);
    if (status == GSL_SUCCESS) {
        assert_true(bench_max_distance(n, xs, x) < 1e-6);
    } else {
        assert_true(status == GSL_EBADFUNC || status == GSL_EMAXITER);
        assert_true(strlen(whirl_last_error()) > 0);
        print_message("seed formulation through the vertical: %s\n", whirl_last_error());
    }
    whirl_dyn_free(s);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* omega = omega_2 (1 +- 1e-6), N = 30: just above, mode 2 exists and its shape is a fixed point
 * of the co-rotating dynamics (accelerations below 1e-9 g) with a tip radius of order
 * sqrt(1e-6); just below, GSL_EDOM with a message. The hanging chain at that rate stays
 * hanging: no horizontal displacement at all (an equilibrium of the ODE is one of every
 * Runge-Kutta map), the heights to round-off. */
static void test_near_critical(void **unused)
{
    (void)unused;
    const size_t n = 30;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double crit[2];
    assert_int_equal(whirl_nlink_critical(c, 2, crit), GSL_SUCCESS);
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(c, crit[1] * (1 - 1e-6), 2, &info), GSL_EDOM);
    assert_true(strlen(whirl_last_error()) > 0);
    const double omega = crit[1] * (1 + 1e-6);
    assert_int_equal(whirl_nlink_solve(c, omega, 2, &info), GSL_SUCCESS);
    assert_true(info.tip_r > 1e-5 && info.tip_r < 0.1);
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[90] = {0}, v[90] = {0}, y[180], dy[180];
    assert_int_equal(bench_steady_positions(c, omega, 2, x), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(0, y, dy, d), GSL_SUCCESS);
    for (size_t k = 0; k < 90; k++) assert_true(fabs(dy[90 + k]) < 1e-9);
    memset(x, 0, sizeof x);
    for (size_t i = 0; i < n; i++) x[3 * i + 2] = -(double)(i + 1) / (double)n;
    double x0[90];
    memcpy(x0, x, sizeof x);
    assert_int_equal(run(d, "gauss2", x, v, y, 5, 0.01, 0), GSL_SUCCESS);
    for (size_t i = 0; i < n; i++) assert_true(x[3 * i] == 0 && x[3 * i + 1] == 0);
    assert_true(bench_max_distance(n, x, x0) < 1e-14);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* gsl-rk8pd at tolerances 1e-15 and 1e-16 on a 5-link 3D swing over t = 2: either within 1e-11
 * of gauss3 at h = 2.5e-3 (itself within about 1e-13: order 6) or a failure status with a
 * message, never a non-finite state. */
static void test_roundoff_tolerance(void **unused)
{
    (void)unused;
    const size_t n = 5;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[15], v[15], xr[15], vr[15], y[30], xs[15], vs[15];
    const double pivot[3] = {0, 0, 0};
    bench_smooth_state(c, pivot, xs, vs);
    memcpy(xr, xs, sizeof xr);
    memcpy(vr, vs, sizeof vr);
    assert_int_equal(run(d, "gauss3", xr, vr, y, 2, 2.5e-3, 0), GSL_SUCCESS);
    const double tols[2] = {1e-15, 1e-16};
    for (int k = 0; k < 2; k++) {
        memcpy(x, xs, sizeof x);
        memcpy(v, vs, sizeof v);
        const int status = run(d, "gsl-rk8pd", x, v, y, 2, 1e-3, tols[k]);
        if (status == GSL_SUCCESS) {
            assert_true(bench_max_distance(n, x, xr) < 1e-11);
        } else {
            assert_true(strlen(whirl_last_error()) > 0);
            print_message("gsl-rk8pd at tol %g: %s\n", tols[k], whirl_last_error());
        }
    }
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* N = 10^5 hanging: tensions equal the weight below to 1e-12 relative; after a kick of the lower
 * half, 3 rk4 steps of h = 5e-7 keep every number finite and the constraints to 1e-12. */
static void test_large_n(void **unused)
{
    (void)unused;
    const size_t n = 100000;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    double *y = malloc(6 * n * sizeof *y), *ten = malloc(n * sizeof *ten);
    assert_non_null(d);
    for (size_t i = 0; i < n; i++) x[3 * i + 2] = -(double)(i + 1) / (double)n;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_tensions(d, 0, y, ten), GSL_SUCCESS);
    double worst = 0;
    for (size_t i = 0; i < n; i++) {
        const long double below = (long double)(n - i) * c->mass[0] * c->gravity;
        worst = fmax(worst, (double)fabsl(ten[i] / below - 1));
    }
    assert_true(worst < 1e-12);
    for (size_t i = n / 2; i < n; i++) v[3 * i + 1] = 0.01 * (double)(i - n / 2) / (double)n;
    assert_int_equal(run(d, "rk4", x, v, y, 1.5e-6, 5e-7, 0), GSL_SUCCESS);
    whirl_dyn_diagnostics diag;
    whirl_dyn_diagnose(d, 1.5e-6, y, &diag);
    assert_true(diag.constraint < 1e-12);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    free(x), free(v), free(y), free(ten);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fast_spin),
        cmocka_unit_test(test_heavy_tip),
        cmocka_unit_test(test_folded),
        cmocka_unit_test(test_through_vertical),
        cmocka_unit_test(test_near_critical),
        cmocka_unit_test(test_roundoff_tolerance),
        cmocka_unit_test(test_large_n),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
