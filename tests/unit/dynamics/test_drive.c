/* Tests of the drive that depends on time (whirl_ramp in include/whirl/dynamics.h):
 *  - the phase is the integral of omega(t): against Simpson's rule on the rate, and it stays
 *    continuous when whirl_dyn_set_ramps replaces a ramp mid-run;
 *  - two formulations of the same motion: a spin-up (eps and omega ramped together) integrated
 *    in the inertial frame (pivot p = eps (cos phi, sin phi, 0) and its derivatives) and in the
 *    co-rotating frame (pivot (eps(t), 0, 0), Euler force -omega' z x x) give the same inertial
 *    positions (rk8, tolerance 1e-11), in both the Cartesian and the seed formulation;
 *  - a ramp from a value to itself is the constant drive;
 *  - after the ramps end (no dissipation) the Jacobi integral E - omega L_z is conserved again
 *    (relative drift below 1e-9) in every frame and formulation;
 *  - error paths: bad ramps in the model and in whirl_dyn_set_ramps. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define LINKS 6

static void test_phase(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 1,
                     .omega_ramp = {0.37, 2.385, 1.3, 7.9}};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(d);
    /* Simpson's rule on omega over [0, 9.1] (the rate is C1, cubic between the kinks) */
    const int n = 9100;
    const double t1 = 9.1, h = t1 / n;
    double sum = 0;
    for (int k = 0; k <= n; k++) {
        double w;
        whirl_dyn_drive_at(d, k * h, NULL, &w, NULL);
        sum += (k == 0 || k == n ? 1 : k % 2 ? 4 : 2) * w;
    }
    double phase, w_end;
    whirl_dyn_drive_at(d, t1, NULL, &w_end, &phase);
    print_message("# phase %.15g, Simpson %.15g\n", phase, sum * h / 3);
    assert_true(fabs(phase - sum * h / 3) < 1e-9);
    assert_true(w_end == 2.385);
    /* a new ramp at t = 5 keeps the phase continuous */
    double before, after;
    whirl_dyn_drive_at(d, 5.0, NULL, NULL, &before);
    double w5;
    whirl_dyn_drive_at(d, 5.0, NULL, &w5, NULL);
    const whirl_ramp next = {w5, 0.9, 5.0, 6.0};
    assert_int_equal(whirl_dyn_set_ramps(d, 5.0, NULL, &next), GSL_SUCCESS);
    whirl_dyn_drive_at(d, 5.0, NULL, NULL, &after);
    assert_true(fabs(after - before) < 1e-12 * fabs(before));
    /* errors: the workspace keeps its ramps */
    const whirl_ramp backwards = {1, 2, 3, 3}, negative = {-0.1, 0.2, 0, 1},
                     nan_ramp = {1, NAN, 0, 1};
    assert_int_equal(whirl_dyn_set_ramps(d, 5.0, NULL, &backwards), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "omega_ramp"));
    assert_int_equal(whirl_dyn_set_ramps(d, 5.0, &negative, NULL), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "drive_radius_ramp"));
    assert_int_equal(whirl_dyn_set_ramps(d, 5.0, NULL, &nan_ramp), GSL_EINVAL);
    assert_int_equal(whirl_dyn_set_ramps(d, NAN, NULL, &next), GSL_EINVAL);
    assert_int_equal(whirl_dyn_set_ramps(NULL, 5.0, NULL, &next), GSL_EINVAL);
    whirl_dyn_drive_at(d, 5.0, NULL, NULL, &after);
    assert_true(fabs(after - before) < 1e-12 * fabs(before));
    m.omega_ramp = backwards;
    assert_null(whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN));
    assert_non_null(strstr(whirl_last_error(), "t_end"));
    m.omega_ramp = (whirl_ramp){0};
    m.drive_radius_ramp = negative;
    assert_null(whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN));
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* Inertial positions (3 per mass) at t1 of the spin-up in frame f and formulation form. */
static void spin_up(const whirl_chain *c, whirl_frame f, whirl_formulation form, double t1,
                    double *x, double *jacobi_drift)
{
    whirl_model m = {.chain = c, .dim = 3, .frame = f, .omega = 0,
                     .drive_radius_ramp = {0, 0.083, 0, 4.0},
                     .omega_ramp = {0.2, 2.07, 0.5, 5.5}};
    whirl_dyn *d = whirl_dyn_alloc(&m, form);
    assert_non_null(d);
    whirl_integrator *it = whirl_integrator_alloc("rk8", d);
    assert_non_null(it);
    double links[3 * LINKS], y[6 * LINKS], v[3 * LINKS];
    for (size_t i = 0; i < LINKS; i++) { /* a bent start, off the seed's singular vertical */
        links[3 * i] = 0.3 * sin(0.7 * (double)i + 0.2) / LINKS;
        links[3 * i + 1] = 0.2 * cos(1.3 * (double)i) / LINKS;
        links[3 * i + 2] = -1.0 / LINKS;
        const double s = (1.0 / LINKS) / sqrt(links[3 * i] * links[3 * i] +
                                              links[3 * i + 1] * links[3 * i + 1] +
                                              links[3 * i + 2] * links[3 * i + 2]);
        for (int k = 0; k < 3; k++) links[3 * i + k] *= s;
    }
    assert_int_equal(whirl_perturb_links(LINKS, links, 0.1, 3), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_state_from_shape(d, 0, links, 0, y), GSL_SUCCESS);
    double t = 0;
    assert_int_equal(whirl_integrator_advance(it, &t, y, 6.0, 0.01, 1e-12), GSL_SUCCESS);
    whirl_dyn_diagnostics d0, d1;
    assert_int_equal(whirl_dyn_diagnose(d, t, y, &d0), GSL_SUCCESS);
    assert_int_equal(whirl_integrator_advance(it, &t, y, t1, 0.01, 1e-12), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_diagnose(d, t, y, &d1), GSL_SUCCESS);
    *jacobi_drift = fabs(d1.jacobi - d0.jacobi) / fabs(d0.jacobi);
    assert_int_equal(whirl_dyn_get_state(d, t, y, WHIRL_FRAME_INERTIAL, x, v), GSL_SUCCESS);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
}

static void test_frames_agree(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    const double t1 = 9.0;
    double xi[3 * LINKS], xr[3 * LINKS], xs[3 * LINKS], ji, jr, js;
    spin_up(c, WHIRL_FRAME_INERTIAL, WHIRL_FORMULATION_CARTESIAN, t1, xi, &ji);
    spin_up(c, WHIRL_FRAME_ROTATING, WHIRL_FORMULATION_CARTESIAN, t1, xr, &jr);
    spin_up(c, WHIRL_FRAME_ROTATING, WHIRL_FORMULATION_SEED, t1, xs, &js);
    double dr = 0, ds = 0, moved = 0;
    for (size_t i = 0; i < 3 * LINKS; i++) {
        dr = fmax(dr, fabs(xr[i] - xi[i]));
        ds = fmax(ds, fabs(xs[i] - xi[i]));
        moved = fmax(moved, fabs(xi[i]));
    }
    print_message("# spin-up to t = %g: co-rotating vs inertial %.2g, seed vs Cartesian %.2g; "
                  "Jacobi drift after the ramps %.2g %.2g %.2g\n",
                  t1, dr, ds, ji, jr, js);
    assert_true(dr < 1e-9 && ds < 1e-9);
    assert_true(ji < 1e-9 && jr < 1e-9 && js < 1e-9);
    whirl_chain_free(c);
}

static void test_constant_ramp_is_constant(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL, .omega = 1.9,
                     .drive_radius = 0.07, .air_drag = 0.1};
    whirl_model r = m;
    r.omega = 0;
    r.drive_radius = 0;
    r.omega_ramp = (whirl_ramp){1.9, 1.9, -1, 1};
    r.drive_radius_ramp = (whirl_ramp){0.07, 0.07, 2, 3};
    whirl_dyn *a = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    whirl_dyn *b = whirl_dyn_alloc(&r, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(a);
    assert_non_null(b);
    double links[3 * LINKS], ya[6 * LINKS], yb[6 * LINKS], fa[6 * LINKS], fb[6 * LINKS];
    for (size_t i = 0; i < LINKS; i++) {
        links[3 * i] = links[3 * i + 1] = 0;
        links[3 * i + 2] = -1.0 / LINKS;
    }
    assert_int_equal(whirl_perturb_links(LINKS, links, 0.3, 11), GSL_SUCCESS);
    const double t = 2.4;
    assert_int_equal(whirl_dyn_state_from_shape(a, t, links, 0.5, ya), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_state_from_shape(b, t, links, 0.5, yb), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(t, ya, fa, a), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(t, yb, fb, b), GSL_SUCCESS);
    double worst = 0;
    for (size_t i = 0; i < 6 * LINKS; i++)
        worst = fmax(worst, fabs(ya[i] - yb[i]) + fabs(fa[i] - fb[i]));
    print_message("# constant ramps vs constant drive: %.2g\n", worst);
    assert_true(worst < 1e-12);
    whirl_dyn_free(a);
    whirl_dyn_free(b);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_phase),
        cmocka_unit_test(test_frames_agree),
        cmocka_unit_test(test_constant_ramp_is_constant),
    };
    return cmocka_run_group_tests_name("drive", tests, NULL, NULL);
}
