/* Tests of the start-state helpers (src/state.c, declared in include/whirl/dynamics.h):
 *  - whirl_perturb_links: every link keeps its length and is turned by exactly the angle (from
 *    the dot product); the turn directions about a vertical link are uniform on the circle
 *    (mean of cos and sin of their azimuth within 5 / sqrt(n) of 0); the same seed repeats;
 *  - whirl_dyn_state_from_shape: a steady shape (whirl_nlink_positions, and a driven shape with
 *    drag from whirl_driven_sample) is an equilibrium of the dynamics in the co-rotating frame
 *    (the right-hand side vanishes to the shape solvers' accuracy: an independent formulation);
 *    in the inertial frame, read back in the co-rotating frame at the same time, it is the same
 *    shape at rest;
 *  - whirl_default_step: a 200th of the period or less, and the error paths of all three. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#include "whirl/driven.h"
#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define LINKS 9

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void test_perturb(void **state)
{
    (void)state;
    enum { N = 4000 };
    static double links[3 * N], orig[3 * N], again[3 * N];
    for (size_t j = 0; j < N; j++) {
        const double l = 0.3 + 0.7 * (double)(j % 7) / 7.0;
        orig[3 * j] = j % 3 == 0 ? 0.0 : 0.2 * l;
        orig[3 * j + 1] = j % 3 == 0 ? 0.0 : -0.1 * l;
        orig[3 * j + 2] = -l;
    }
    const double angle = 0.0385;
    memcpy(links, orig, sizeof links);
    assert_int_equal(whirl_perturb_links(N, links, angle, 7), GSL_SUCCESS);
    double worst_len = 0, worst_angle = 0, mc = 0, ms = 0;
    size_t vertical = 0;
    for (size_t j = 0; j < N; j++) {
        const double *a = orig + 3 * j, *b = links + 3 * j;
        const double la = sqrt(dot(a, a)), lb = sqrt(dot(b, b));
        worst_len = fmax(worst_len, fabs(lb - la) / la);
        const double cross[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
        const double turned = atan2(sqrt(dot(cross, cross)), dot(a, b));
        worst_angle = fmax(worst_angle, fabs(turned - angle));
        if (j % 3 == 0) { /* vertical: the azimuth of the turned link */
            const double psi = atan2(b[1], b[0]);
            mc += cos(psi);
            ms += sin(psi);
            vertical++;
        }
    }
    mc /= (double)vertical;
    ms /= (double)vertical;
    print_message("# perturb: length %.2g, angle %.2g, azimuth means %.3g %.3g (n %zu)\n",
                  worst_len, worst_angle, mc, ms, vertical);
    assert_true(worst_len < 4e-16);
    assert_true(worst_angle < 1e-13);
    assert_true(fabs(mc) < 5 / sqrt((double)vertical) && fabs(ms) < 5 / sqrt((double)vertical));
    memcpy(again, orig, sizeof again);
    assert_int_equal(whirl_perturb_links(N, again, angle, 7), GSL_SUCCESS);
    assert_memory_equal(again, links, sizeof links);
    memcpy(again, orig, sizeof again);
    assert_int_equal(whirl_perturb_links(N, again, angle, 8), GSL_SUCCESS);
    assert_true(memcmp(again, links, sizeof links) != 0);
    /* errors */
    double zero[6] = {0, 0, -1, 0, 0, 0};
    assert_int_equal(whirl_perturb_links(2, zero, 0.1, 1), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "link 2"));
    assert_int_equal(whirl_perturb_links(1, NULL, 0.1, 1), GSL_EINVAL);
    assert_int_equal(whirl_perturb_links(0, links, 0.1, 1), GSL_EINVAL);
    assert_int_equal(whirl_perturb_links(1, links, -0.1, 1), GSL_EINVAL);
    assert_int_equal(whirl_perturb_links(1, links, NAN, 1), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "angle"));
}

/* max |dq'/dt| (the second half of dy/dt) and max |q'| (the first half) at (t, y). */
static void rates(whirl_dyn *d, double t, const double *y, double *acc, double *vel)
{
    const size_t size = whirl_dyn_size(d);
    double *dydt = malloc(size * sizeof *dydt);
    assert_non_null(dydt);
    assert_int_equal(whirl_dyn_rhs(t, y, dydt, d), GSL_SUCCESS);
    *acc = *vel = 0;
    for (size_t i = 0; i < size / 2; i++) {
        *vel = fmax(*vel, fabs(dydt[i]));
        *acc = fmax(*acc, fabs(dydt[size / 2 + i]));
    }
    free(dydt);
}

static void test_steady_shape_is_equilibrium(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    const double omega = 3.385; /* mode 2 exists above omega_2 ~ 2.76 */
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(c, omega, 2, &info), GSL_SUCCESS);
    double r[LINKS + 1], z[LINKS + 1], tension[LINKS + 1], links[3 * LINKS];
    assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, tension), GSL_SUCCESS);
    assert_int_equal(whirl_shape_links(LINKS, r, NULL, z, links), GSL_SUCCESS);
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(d);
    double y[6 * LINKS], acc, vel;
    assert_int_equal(whirl_dyn_state_from_shape(d, 0.31, links, omega, y), GSL_SUCCESS);
    rates(d, 0.31, y, &acc, &vel);
    print_message("# free mode 2, co-rotating: |q''| %.2g, |q'| %.2g\n", acc, vel);
    assert_true(acc < 1e-9 && vel == 0);
    /* the same shape from the inertial frame, read back co-rotating */
    whirl_model mi = m;
    mi.frame = WHIRL_FRAME_INERTIAL;
    whirl_dyn *di = whirl_dyn_alloc(&mi, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(di);
    const double t = 1.7;
    double x[3 * LINKS], v[3 * LINKS];
    assert_int_equal(whirl_dyn_state_from_shape(di, t, links, omega, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_get_state(di, t, y, WHIRL_FRAME_ROTATING, x, v), GSL_SUCCESS);
    double worst = 0;
    for (size_t i = 0; i < LINKS; i++) {
        worst = fmax(worst, fabs(x[3 * i] - r[i + 1]) + fabs(x[3 * i + 1]) +
                                fabs(x[3 * i + 2] - z[i + 1]));
        worst = fmax(worst, fabs(v[3 * i]) + fabs(v[3 * i + 1]) + fabs(v[3 * i + 2]));
    }
    print_message("# free mode 2, inertial at t = %g read co-rotating: %.2g\n", t, worst);
    assert_true(worst < 1e-13);
    /* errors */
    assert_int_equal(whirl_dyn_state_from_shape(NULL, 0, links, omega, y), GSL_EINVAL);
    assert_int_equal(whirl_dyn_state_from_shape(d, 0, NULL, omega, y), GSL_EINVAL);
    assert_int_equal(whirl_dyn_state_from_shape(d, 0, links, NAN, y), GSL_EINVAL);
    links[5] *= 1.01; /* link 2 too long */
    assert_int_equal(whirl_dyn_state_from_shape(d, 0, links, omega, y), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "link 2"));
    assert_int_equal(whirl_shape_links(LINKS, NULL, NULL, z, links), GSL_EINVAL);
    r[3] = NAN;
    assert_int_equal(whirl_shape_links(LINKS, r, NULL, z, links), GSL_EINVAL);
    whirl_model m2 = {.chain = c, .dim = 2, .omega = omega};
    whirl_dyn *d2 = whirl_dyn_alloc(&m2, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(d2);
    assert_int_equal(whirl_dyn_state_from_shape(d2, 0, links, omega, y), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "planar"));
    whirl_dyn_free(d2);
    whirl_dyn_free(di);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

static void test_driven_shape_is_equilibrium(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 1.7,
                     .drive_radius = 0.06, .air_drag = 0.04, .air_drag_quadratic = 0.03};
    whirl_driven_params p;
    whirl_driven_params_from_model(&p, &m);
    whirl_driven_info info;
    assert_int_equal(whirl_driven_mode(c, &p, 1, -1, &info), GSL_SUCCESS);
    double x[LINKS + 1], y[LINKS + 1], z[LINKS + 1], links[3 * LINKS], s[6 * LINKS];
    assert_int_equal(whirl_driven_sample(c, &p, info.tip, LINKS + 1, NULL, x, y, z, NULL),
                     GSL_SUCCESS);
    assert_int_equal(whirl_shape_links(LINKS, x, y, z, links), GSL_SUCCESS);
    for (int f = 0; f < 2; f++) {
        m.frame = f ? WHIRL_FRAME_INERTIAL : WHIRL_FRAME_ROTATING;
        whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        assert_non_null(d);
        assert_int_equal(whirl_dyn_state_from_shape(d, 0.45, links, m.omega, s), GSL_SUCCESS);
        double pos[3 * LINKS], vel[3 * LINKS], acc, rate;
        assert_int_equal(whirl_dyn_get_state(d, 0.45, s, WHIRL_FRAME_ROTATING, pos, vel),
                         GSL_SUCCESS);
        double worst = 0;
        for (size_t i = 0; i < LINKS; i++)
            worst = fmax(worst, fabs(pos[3 * i] - x[i + 1]) + fabs(pos[3 * i + 1] - y[i + 1]) +
                                    fabs(pos[3 * i + 2] - z[i + 1]) + fabs(vel[3 * i]) +
                                    fabs(vel[3 * i + 1]) + fabs(vel[3 * i + 2]));
        rates(d, 0.45, s, &acc, &rate);
        print_message("# driven with drag, %s: shape %.2g, |q''| %.2g\n",
                      f ? "inertial" : "co-rotating", worst, acc);
        assert_true(worst < 1e-13);
        if (!f) assert_true(acc < 1e-8); /* inertial: the centripetal acceleration */
        whirl_dyn_free(d);
    }
    whirl_chain_free(c);
}

static void test_default_step(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 2.385};
    double tension[LINKS], h, h_damped;
    for (size_t j = 0; j < LINKS; j++) tension[j] = 1.0 - (double)j / LINKS;
    assert_int_equal(whirl_default_step(&m, tension, "rk4", &h), GSL_SUCCESS);
    assert_true(h > 0 && h <= 2 * M_PI / m.omega / 200);
    m.internal_damping = 0.5;
    assert_int_equal(whirl_default_step(&m, tension, "gauss2", &h_damped), GSL_SUCCESS);
    assert_true(h_damped > 0 && h_damped < h);
    assert_int_equal(whirl_default_step(NULL, tension, "rk4", &h), GSL_EINVAL);
    assert_int_equal(whirl_default_step(&m, NULL, "rk4", &h), GSL_EINVAL);
    assert_int_equal(whirl_default_step(&m, tension, NULL, &h), GSL_EINVAL);
    tension[3] = -1;
    assert_int_equal(whirl_default_step(&m, tension, "rk4", &h), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "tension 4"));
    tension[3] = 0.5;
    m.omega = 0;
    assert_int_equal(whirl_default_step(&m, tension, "rk4", &h), GSL_EINVAL);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_perturb),
        cmocka_unit_test(test_steady_shape_is_equilibrium),
        cmocka_unit_test(test_driven_shape_is_equilibrium),
        cmocka_unit_test(test_default_step),
    };
    return cmocka_run_group_tests_name("state", tests, NULL, NULL);
}
