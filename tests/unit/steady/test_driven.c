/* Tests of the driven steady shapes (include/whirl/driven.h) against independent references:
 *  - eps = c = 0: the free shapes of steady.h (a different formulation: planar shooting on the
 *    tip radius), to 1e-10;
 *  - small eps: the linear forced response of the continuum, x(sigma) = A J0(2 omega sqrt(sigma))
 *    with A J0(2 omega) = eps (sigma from the free end), so the tip is at eps / J0(2 omega);
 *  - the N-link chain: force balance of every mass, recomputed here from the positions and
 *    tensions alone; a fixed point of the dynamics module's equations of motion (dynamics.h,
 *    co-rotating frame, same drive and drag, both formulations); the torque balance about the axis (pivot torque = drag torque), which the
 *    solver never imposes; first-order convergence to the continuum as N grows;
 *  - folds of the imperfect pitchfork at omega_1: omega_fold - omega_1 ~ eps^(2/3) (cusp: the
 *    amplitude equation (omega - omega_1) a - k a^3 + k' eps = 0), and the fold's location does
 *    not depend on the continuation's step. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>

#include <cmocka.h>
#include <gsl/gsl_sf_bessel.h>

#include "whirl/driven.h"
#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define OMEGA_1 1.2024127788478865 /* j_{0,1} / 2 */

static whirl_driven_params params(double omega, double eps, double c, double c2, double tip_mass)
{
    whirl_driven_params p = {.omega = omega, .drive_radius = eps, .air_drag = c,
                             .air_drag_quadratic = c2, .tip_mass = tip_mass};
    return p;
}

static double rel_diff(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

/* eps = c = 0 from a perturbed guess lands on the free shape, for both models. */
static void check_free(const whirl_chain *chain, double omega, int mode, double tip_mass)
{
    whirl_shape_info ref;
    int status = chain ? whirl_nlink_solve(chain, omega, mode, &ref)
                       : whirl_continuum_solve(omega, mode, tip_mass, 0, &ref);
    assert_int_equal(status, GSL_SUCCESS);
    whirl_driven_params p = params(omega, 0, 0, 0, tip_mass);
    whirl_driven_info info;
    const double guess[2] = {1.02 * ref.tip_r, 0.013};
    assert_int_equal(whirl_driven_solve(chain, &p, guess, &info), GSL_SUCCESS);
    assert_true(rel_diff(info.tip_r, ref.tip_r) < 1e-10);
    assert_true(fabs(info.tip[1]) == 0);
    assert_true(rel_diff(info.top_tension, ref.top_tension) < 1e-10);
    assert_true(rel_diff(-info.tip[2], ref.depth) < 1e-10);
    assert_int_equal(info.nodes, mode);
    assert_true(info.residual < 1e-12);
    /* the mode seed (its own refinement) agrees, on both sides of the axis */
    for (int side = -1; side <= 1; side += 2) {
        whirl_driven_info seeded;
        assert_int_equal(whirl_driven_mode(chain, &p, mode, side, &seeded), GSL_SUCCESS);
        assert_true(rel_diff(seeded.tip[0], side * ref.tip_r) < 1e-10);
        assert_int_equal(seeded.nodes, mode);
    }
}

static void test_free_nlink(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(37, 0.137);
    check_free(chain, 1.9, 1, 0);
    check_free(chain, 3.7, 2, 0);
    check_free(chain, 5.3, 3, 0);
    whirl_chain_free(chain);
}

static void test_free_continuum(void **state)
{
    (void)state;
    check_free(NULL, 1.9, 1, 0);
    check_free(NULL, 3.7, 2, 0);
    check_free(NULL, 5.3, 3, 0);
    check_free(NULL, 2.385, 1, 0.137);
    check_free(NULL, 4.1, 2, 0.137);
}

/* Tiny eps: the tip of the linear forced response, eps / J0(2 omega); the nonlinear correction
 * is O(eps^2) relative, 1e-12 here. */
static void test_linear_response(void **state)
{
    (void)state;
    const double omegas[] = {0.7, 1.9, 2.385, 3.3};
    for (size_t k = 0; k < sizeof omegas / sizeof omegas[0]; k++) {
        const double omega = omegas[k], eps = 1e-6, linear = eps / gsl_sf_bessel_J0(2 * omega);
        whirl_driven_params p = params(omega, eps, 0, 0, 0);
        whirl_driven_info info;
        const double guess[2] = {1.1 * linear, 0};
        assert_int_equal(whirl_driven_solve(NULL, &p, guess, &info), GSL_SUCCESS);
        assert_true(rel_diff(info.tip[0], linear) < 1e-8);
        assert_true(fabs(info.tip[1]) < 1e-20);
    }
}

/* Mode 0, the near-axis shape: for a small drive the linear response eps / J0(2 omega) on either
 * side of omega_1 (in phase below, opposite above); at eps = 0 the hanging chain; at a rate with
 * the triple-valued response (omega = 1.5, eps = 0.05, past the fold at about 1.39) the smallest
 * of three distinct shapes, on the far side from the pivot; between omega_1 and that fold it does
 * not exist (it has met mode 1's far-side shape at the fold). */
static void test_near_axis(void **state)
{
    (void)state;
    const double omegas[] = {0.7, 1.5, 1.9, 3.3};
    whirl_driven_info info;
    for (size_t k = 0; k < sizeof omegas / sizeof omegas[0]; k++) {
        const double omega = omegas[k], eps = 1e-6, linear = eps / gsl_sf_bessel_J0(2 * omega);
        whirl_driven_params p = params(omega, eps, 0, 0, 0);
        assert_int_equal(whirl_driven_mode(NULL, &p, 0, 1, &info), GSL_SUCCESS);
        assert_true(rel_diff(info.tip[0], linear) < 1e-8);
        p.drive_radius = 0;
        assert_int_equal(whirl_driven_mode(NULL, &p, 0, 1, &info), GSL_SUCCESS);
        assert_true(info.tip_r == 0);
    }
    whirl_driven_params p = params(1.5, 0.05, 0, 0, 0);
    whirl_driven_info near, in_phase, far;
    assert_int_equal(whirl_driven_mode(NULL, &p, 0, 1, &near), GSL_SUCCESS);
    assert_int_equal(whirl_driven_mode(NULL, &p, 1, 1, &in_phase), GSL_SUCCESS);
    assert_int_equal(whirl_driven_mode(NULL, &p, 1, -1, &far), GSL_SUCCESS);
    assert_true(near.tip[0] < 0 && far.tip[0] < near.tip[0] - 0.3 && in_phase.tip[0] > 0.5);
    assert_true(near.residual < 1e-12);
    /* the small shape is the one the linear response seeds */
    const double guess[2] = {0.05 / gsl_sf_bessel_J0(3.0), 0};
    assert_int_equal(whirl_driven_solve(NULL, &p, guess, &info), GSL_SUCCESS);
    assert_true(fabs(info.tip[0] - near.tip[0]) < 1e-10);
    p.omega = 1.3;
    assert_int_equal(whirl_driven_mode(NULL, &p, 0, 1, &info), GSL_EDOM);
}

/* A non-uniform chain with eps, linear and quadratic drag: every mass in force balance. */
static void test_nlink_force_balance(void **state)
{
    (void)state;
    enum { N = 23 };
    double length[N], mass[N], g = 1.3;
    for (int i = 0; i < N; i++) {
        length[i] = (1 + 0.3 * sin(i + 1.0)) / N;
        mass[i] = (1 + 0.5 * cos(1.7 * i)) / N;
    }
    whirl_chain *chain = whirl_chain_alloc(N, length, mass, g);
    double omega_1;
    assert_int_equal(whirl_nlink_critical(chain, 1, &omega_1), GSL_SUCCESS);
    const double omega = 1.4 * omega_1, eps = 0.07, c = 0.045, c2 = 0.031;
    whirl_driven_params p = params(omega, eps, c, c2, 0);
    for (int side = -1; side <= 1; side += 2) {
        whirl_driven_info info;
        assert_int_equal(whirl_driven_mode(chain, &p, 1, side, &info), GSL_SUCCESS);
        double s[N + 1], x[N + 1], y[N + 1], z[N + 1], T[N + 1];
        assert_int_equal(whirl_driven_sample(chain, &p, info.tip, N + 1, s, x, y, z, T),
                         GSL_SUCCESS);
        assert_true(hypot(x[0] - eps, y[0]) < 1e-13 && z[0] == 0);
        double worst = 0;
        for (int i = 1; i <= N; i++) {
            /* unit vector up link i (mass i to mass i-1), length check */
            const double d[3] = {x[i - 1] - x[i], y[i - 1] - y[i], z[i - 1] - z[i]};
            const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            assert_true(fabs(len - length[i - 1]) < 1e-14);
            double f[3];
            const double vx = -omega * y[i], vy = omega * x[i], speed = hypot(vx, vy);
            const double drag = length[i - 1] * (c + c2 * speed);
            f[0] = mass[i - 1] * omega * omega * x[i] - drag * vx + T[i] * d[0] / len;
            f[1] = mass[i - 1] * omega * omega * y[i] - drag * vy + T[i] * d[1] / len;
            f[2] = -mass[i - 1] * g + T[i] * d[2] / len;
            if (i < N) { /* link i+1 pulls mass i down towards mass i+1 */
                const double e[3] = {x[i + 1] - x[i], y[i + 1] - y[i], z[i + 1] - z[i]};
                const double le = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
                for (int j = 0; j < 3; j++) f[j] += T[i + 1] * e[j] / le;
            }
            worst = fmax(worst, sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
        }
        assert_true(worst < 1e-13 * info.top_tension);
    }
    whirl_chain_free(chain);
}

/* The driven shape at rest in the co-rotating frame is a fixed point of the equations of motion of
 * dynamics.h with the same drive and drag: zero accelerations, the same link tensions. */
static void test_fixed_point_of_dynamics(void **state)
{
    (void)state;
    enum { N = 17 };
    whirl_chain *chain = whirl_chain_alloc_uniform(N, 0.2);
    whirl_driven_params p = params(1.7, 0.06, 0.04, 0.03, 0);
    for (int side = -1; side <= 1; side += 2) {
        whirl_driven_info info;
        double s[N + 1], x[N + 1], y[N + 1], z[N + 1], T[N + 1], pos[3 * N], vel[3 * N] = {0};
        assert_int_equal(whirl_driven_mode(chain, &p, 1, side, &info), GSL_SUCCESS);
        assert_int_equal(whirl_driven_sample(chain, &p, info.tip, N + 1, s, x, y, z, T),
                         GSL_SUCCESS);
        for (int i = 0; i < N; i++)
            pos[3 * i] = x[i + 1], pos[3 * i + 1] = y[i + 1], pos[3 * i + 2] = z[i + 1];
        for (int f = 0; f < 2; f++) {
            whirl_model model = {0};
            model.chain = chain;
            model.dim = 3;
            model.frame = WHIRL_FRAME_ROTATING;
            model.omega = p.omega;
            model.drive_radius = p.drive_radius;
            model.air_drag = p.air_drag;
            model.air_drag_quadratic = p.air_drag_quadratic;
            whirl_dyn *d = whirl_dyn_alloc(&model, f ? WHIRL_FORMULATION_SEED
                                                     : WHIRL_FORMULATION_CARTESIAN);
            assert_non_null(d);
            const size_t n = whirl_dyn_size(d);
            double *yv = malloc(2 * n * sizeof *yv), *dydt = yv + n, tension[N];
            assert_int_equal(whirl_dyn_set_state(d, 0, pos, vel, yv), GSL_SUCCESS);
            assert_int_equal(whirl_dyn_rhs(0, yv, dydt, d), GSL_SUCCESS);
            for (size_t k = 0; k < n; k++) assert_true(fabs(dydt[k]) < 1e-11);
            assert_int_equal(whirl_dyn_tensions(d, 0, yv, tension), GSL_SUCCESS);
            for (int i = 0; i < N; i++) assert_true(fabs(tension[i] - T[i + 1]) < 1e-12);
            free(yv);
            whirl_dyn_free(d);
        }
    }
    whirl_chain_free(chain);
}

/* The drag's torque about the axis is -omega int (c rho^2 + c2 omega rho^3) ds < 0; the only
 * other torque is the support's, eps F_y(top), so F_y(top) > 0: the chain leaves the pivot
 * towards -y, behind the hand (z x r is the direction of motion). For mode 1 the tip lags the
 * pivot by a phase in (0, pi), as a damped driven oscillator's response does: Y < 0 on both the
 * in-phase and the anti-phase shape. The identity is checked exactly (N-link sums) and to
 * quadrature accuracy (continuum, Simpson). */
static void test_trailing_and_torque(void **state)
{
    (void)state;
    const double omega = 1.6, eps = 0.05, c = 0.05, c2 = 0.02;
    whirl_driven_params p = params(omega, eps, c, c2, 0);
    enum { P = 2001, N = 41 };
    static double s[P], x[P], y[P], z[P], T[P];
    whirl_chain *chain = whirl_chain_alloc_uniform(N, 0);
    for (int model = 0; model < 2; model++) {
        const whirl_chain *ch = model ? chain : NULL;
        const size_t npts = model ? N + 1 : P;
        for (int side = -1; side <= 1; side += 2) {
            whirl_driven_info info;
            assert_int_equal(whirl_driven_mode(ch, &p, 1, side, &info), GSL_SUCCESS);
            assert_true(info.tip[1] < 0);
            assert_true(info.top_force[1] > 0);
            assert_true(side * info.tip[0] > 0);
            assert_int_equal(info.nodes, 1);
            assert_int_equal(whirl_driven_sample(ch, &p, info.tip, npts, s, x, y, z, T),
                             GSL_SUCCESS);
            /* drag torque: sum over the masses (weight l_i) or Simpson's rule over s */
            double torque = 0;
            for (size_t i = model ? 1 : 0; i < npts; i++) {
                const double rho = hypot(x[i], y[i]);
                const double simpson = (i == 0 || i == npts - 1 ? 1.0 : i % 2 ? 4.0 : 2.0) /
                                       (3.0 * (double)(npts - 1));
                const double weight = model ? chain->length[i - 1] : simpson;
                torque += weight * omega * (c * rho * rho + c2 * omega * rho * rho * rho);
            }
            assert_true(rel_diff(eps * info.top_force[1], torque) < (model ? 1e-13 : 1e-11));
        }
    }
    whirl_chain_free(chain);
}

/* The N-link chain's shape approaches the continuum's like 1/N: the errors halve as N doubles. */
static void check_converges(double omega, double eps, double c, double c2, double tip_mass,
                            size_t n0)
{
    whirl_driven_params p = params(omega, eps, c, c2, tip_mass), pn = p;
    pn.tip_mass = 0; /* the N-link chain carries it on its last mass */
    whirl_driven_info cont, disc;
    assert_int_equal(whirl_driven_mode(NULL, &p, 1, 1, &cont), GSL_SUCCESS);
    double err[3], terr[3];
    for (int k = 0; k < 3; k++) {
        whirl_chain *chain = whirl_chain_alloc_uniform(n0 << k, tip_mass);
        assert_int_equal(whirl_driven_mode(chain, &pn, 1, 1, &disc), GSL_SUCCESS);
        err[k] = hypot(disc.tip[0] - cont.tip[0], disc.tip[1] - cont.tip[1]);
        terr[k] = fabs(disc.top_tension - cont.top_tension);
        whirl_chain_free(chain);
    }
    for (int k = 0; k < 2; k++) {
        assert_in_range(err[k] / err[k + 1] * 100, 170, 230);
        assert_in_range(terr[k] / terr[k + 1] * 100, 170, 230);
    }
}

static void test_nlink_converges(void **state)
{
    (void)state;
    check_converges(1.6, 0.05, 0.05, 0, 0, 64);
    check_converges(2.1, 0.04, 0.03, 0.02, 0.3, 100);
}

/* Modes 2 and 3 keep their node count when driven and dragged. */
static void test_higher_modes(void **state)
{
    (void)state;
    whirl_chain *chain = whirl_chain_alloc_uniform(100, 0);
    const double omega[] = {4.0, 5.5};
    for (int m = 2; m <= 3; m++)
        for (int model = 0; model < 2; model++)
            for (int side = -1; side <= 1; side += 2) {
                whirl_driven_params p = params(omega[m - 2], 0.01, 0.01, 0.005, 0);
                whirl_driven_info info;
                assert_int_equal(whirl_driven_mode(model ? chain : NULL, &p, m, side, &info),
                                 GSL_SUCCESS);
                assert_int_equal(info.nodes, m);
                assert_true(info.top_force[1] > 0);
                assert_true(info.residual < 1e-12);
            }
    whirl_chain_free(chain);
}

/* The folds of the mode-1 branch leaving omega = 2 downwards on the far side of the axis. */
static int fold_of(const whirl_chain *chain, double eps, double c, int side, double step,
                   double *fold)
{
    whirl_driven_params p = params(2.0, eps, c, 0, 0);
    whirl_driven_info start;
    assert_int_equal(whirl_driven_mode(chain, &p, 1, side, &start), GSL_SUCCESS);
    whirl_driven_curve *curve = whirl_driven_curve_alloc(4000);
    assert_non_null(curve);
    assert_int_equal(whirl_driven_branch(chain, &p, &start, -1, 0.8, 2.0, step, curve),
                     GSL_SUCCESS);
    assert_int_equal(curve->complete, 1);
    const int n_folds = (int)curve->n_folds;
    for (size_t j = 0, k = 0; j < curve->n; j++) {
        if (!curve->fold[j]) continue;
        assert_true(curve->point[j].omega == curve->fold_omega[k++]);
        /* D vanishes at the fold, changes sign across it */
        assert_true(fabs(curve->point[j].fold_function) <
                    1e-8 * fabs(curve->point[j - 1].fold_function));
        assert_true(curve->point[j - 1].fold_function * curve->point[j + 1].fold_function < 0);
    }
    if (n_folds > 0) *fold = curve->fold_omega[0];
    whirl_driven_curve_free(curve);
    return n_folds;
}

static void test_folds(void **state)
{
    (void)state;
    const double eps[] = {0.00125, 0.0025, 0.005};
    double fold[3], coarse, fine;
    for (int k = 0; k < 3; k++) {
        assert_int_equal(fold_of(NULL, eps[k], 0, -1, 0.05, &fold[k]), 1);
        assert_true(fold[k] > OMEGA_1);
        print_message("# eps %.5g: fold at omega %.15g\n", eps[k], fold[k]);
    }
    /* omega_fold - omega_1 ~ eps^(2/3), the local exponent approaching 2/3 from above */
    const double p01 = log((fold[1] - OMEGA_1) / (fold[0] - OMEGA_1)) / log(2);
    const double p12 = log((fold[2] - OMEGA_1) / (fold[1] - OMEGA_1)) / log(2);
    assert_true(fabs(p01 - 2.0 / 3) < 0.03);
    assert_true(p01 < p12);
    /* the location does not depend on the step */
    assert_int_equal(fold_of(NULL, 0.02, 0, -1, 0.05, &coarse), 1);
    assert_int_equal(fold_of(NULL, 0.02, 0, -1, 0.0125, &fine), 1);
    print_message("# eps 0.02: fold at omega %.15g (step 0.05), %.15g (step 0.0125)\n", coarse,
                  fine);
    assert_true(fabs(coarse - fine) < 1e-9);
    /* with drag the fold survives nearby; the in-phase branch has none */
    double dragged;
    assert_int_equal(fold_of(NULL, 0.02, 0.01, -1, 0.05, &dragged), 1);
    assert_true(fabs(dragged - coarse) < 1e-2);
    assert_int_equal(fold_of(NULL, 0.02, 0, 1, 0.05, &dragged), 0);
    /* the N-link chain's fold approaches the continuum's */
    whirl_chain *chain = whirl_chain_alloc_uniform(200, 0);
    double discrete;
    assert_int_equal(fold_of(chain, 0.02, 0, -1, 0.05, &discrete), 1);
    assert_true(rel_diff(discrete, coarse) < 2e-3);
    whirl_chain_free(chain);
}

/* whirl_driven_branch_tick: the curve of whirl_driven_branch, reported after every point (the
 * counts increasing, the last the curve's); a stop requested from the report ends the branch
 * with WHIRL_EINTERRUPTED right there, the points reported kept as they were computed. */
typedef struct branch_calls {
    size_t calls, last, stop_after;
    int increasing;
} branch_calls;

static void count_points(void *data, const whirl_driven_curve *curve)
{
    branch_calls *k = data;
    k->increasing &= curve->n > k->last;
    k->last = curve->n;
    if (++k->calls == k->stop_after) whirl_stop_request();
}

static void test_branch_tick(void **state)
{
    (void)state;
    whirl_driven_params p = params(2.0, 0.02, 0, 0, 0);
    whirl_driven_info start;
    assert_int_equal(whirl_driven_mode(NULL, &p, 1, -1, &start), GSL_SUCCESS);
    whirl_driven_curve *plain = whirl_driven_curve_alloc(4000);
    whirl_driven_curve *ticked = whirl_driven_curve_alloc(4000);
    assert_non_null(plain);
    assert_non_null(ticked);
    assert_int_equal(whirl_driven_branch(NULL, &p, &start, -1, 0.8, 2.0, 0.05, plain),
                     GSL_SUCCESS);
    branch_calls k = {0, 0, 0, 1};
    assert_int_equal(whirl_driven_branch_tick(NULL, &p, &start, -1, 0.8, 2.0, 0.05, ticked,
                                              count_points, &k),
                     GSL_SUCCESS);
    assert_true(plain->complete && ticked->complete && plain->n_folds == 1);
    assert_true(ticked->n == plain->n && k.increasing && k.last == plain->n);
    assert_true(k.calls >= plain->n - plain->n_folds); /* a fold and its point: one call */
    assert_memory_equal(ticked->point, plain->point, plain->n * sizeof *plain->point);
    branch_calls stop = {0, 0, 5, 1};
    assert_int_equal(whirl_driven_branch_tick(NULL, &p, &start, -1, 0.8, 2.0, 0.05, ticked,
                                              count_points, &stop),
                     WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_true(stop.calls == 5 && ticked->n == stop.last && !ticked->complete);
    assert_memory_equal(ticked->point, plain->point, ticked->n * sizeof *plain->point);
    whirl_driven_curve_free(plain);
    whirl_driven_curve_free(ticked);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_driven_info info;
    const double guess[2] = {0.5, 0};
    whirl_driven_params p = params(1.5, 0.05, 0.05, 0, 0);
    whirl_chain *chain = whirl_chain_alloc_uniform(5, 0);
    whirl_driven_params bad[] = {params(0, 0.05, 0, 0, 0), params(NAN, 0.05, 0, 0, 0),
                                 params(1.5, -0.1, 0, 0, 0), params(1.5, 1.2, 0, 0, 0),
                                 params(1.5, 0.05, -1, 0, 0), params(1.5, 0.05, 0, -1, 0),
                                 params(1.5, 0.05, 0, 0, -1)};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
        assert_int_equal(whirl_driven_solve(NULL, &bad[k], guess, &info), GSL_EINVAL);
    whirl_driven_params tipped = params(1.5, 0.05, 0, 0, 0.2);
    assert_int_equal(whirl_driven_solve(chain, &tipped, guess, &info), GSL_EINVAL);
    whirl_driven_params undriven = params(1.5, 0, 0.05, 0, 0);
    assert_int_equal(whirl_driven_solve(NULL, &undriven, guess, &info), GSL_EDOM);
    assert_int_equal(whirl_driven_mode(NULL, &p, -1, 1, &info), GSL_EINVAL);
    assert_int_equal(whirl_driven_mode(NULL, &p, 1, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_driven_mode(NULL, &p, 0, 0, &info), GSL_EINVAL);
    whirl_driven_params slow = params(2.0, 0.01, 0, 0, 0); /* mode 2 needs omega > 2.76 */
    assert_int_equal(whirl_driven_mode(NULL, &slow, 2, 1, &info), GSL_EDOM);
    double buf[5][6];
    assert_int_equal(whirl_driven_sample(chain, &p, guess, 5, buf[0], buf[1], buf[2], buf[3], buf[4]),
                     GSL_EINVAL);
    assert_int_equal(whirl_driven_sample(NULL, &p, guess, 1, buf[0], buf[1], buf[2], buf[3], buf[4]),
                     GSL_EINVAL);
    assert_null(whirl_driven_curve_alloc(1));
    whirl_driven_curve *curve = whirl_driven_curve_alloc(10);
    assert_int_equal(whirl_driven_mode(chain, &p, 1, 1, &info), GSL_SUCCESS);
    assert_int_equal(whirl_driven_branch(chain, &p, &info, 0, 1, 2, 0.1, curve), GSL_EINVAL);
    assert_int_equal(whirl_driven_branch(chain, &p, &info, -1, 2, 1, 0.1, curve), GSL_EINVAL);
    assert_int_equal(whirl_driven_branch(chain, &p, &info, -1, 1.6, 2, 0.1, curve), GSL_EINVAL);
    assert_int_equal(whirl_driven_branch(chain, &p, &info, -1, 1, 2, 0, curve), GSL_EINVAL);
    /* a full curve stops early */
    assert_int_equal(whirl_driven_branch(chain, &p, &info, -1, 0.5, 2, 0.01, curve), GSL_SUCCESS);
    assert_int_equal(curve->complete, 0);
    assert_int_equal(curve->n, 10);
    whirl_driven_curve_free(curve);
    whirl_driven_curve_free(NULL);
    whirl_chain_free(chain);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_nlink),
        cmocka_unit_test(test_free_continuum),
        cmocka_unit_test(test_linear_response),
        cmocka_unit_test(test_near_axis),
        cmocka_unit_test(test_nlink_force_balance),
        cmocka_unit_test(test_fixed_point_of_dynamics),
        cmocka_unit_test(test_trailing_and_torque),
        cmocka_unit_test(test_nlink_converges),
        cmocka_unit_test(test_higher_modes),
        cmocka_unit_test(test_folds),
        cmocka_unit_test(test_branch_tick),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
