/* Tests of the integrators (src/integrator*.c) on the chain dynamics: observed order under step
 * halving, accuracy against an independent reference (the seed's angle formulation integrated by
 * GSL's rk8pd at tolerance 1e-14), conservation of energy / Jacobi's integral and of the
 * constraints, the steady whirling shape as a fixed point, GSL's steppers fixed and adaptive, rk8's
 * step control against its tolerance and against gsl-rk8pd's, and the failure paths of every
 * method (non-finite state, bad arguments). */
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

#define MAXN 4

/* A regular state of n <= MAXN links, angles and rates fixed "high-entropy" numbers: positions
 * x and velocities v, 3 per mass, fixed pivot at the origin. */
static void pendulum_state(const whirl_chain *c, int dim, double *x, double *v)
{
    static const double th[MAXN] = {1.137, -0.713, 2.021, 0.419},
                        thd[MAXN] = {0.317, -0.529, 0.934, 0.121},
                        ph[MAXN] = {0.31, 0.83, -1.42, 2.2}, phd[MAXN] = {0.41, -0.23, 0.67, 0.1};
    double p[3] = {0, 0, 0}, pv[3] = {0, 0, 0};
    for (size_t i = 0; i < c->n; i++) {
        const double f = dim == 3 ? ph[i] : 0, fd = dim == 3 ? phd[i] : 0;
        const double u[3] = {sin(th[i]) * cos(f), sin(th[i]) * sin(f), -cos(th[i])};
        const double et[3] = {cos(th[i]) * cos(f), cos(th[i]) * sin(f), sin(th[i])};
        const double ep[3] = {-sin(f), cos(f), 0};
        for (int k = 0; k < 3; k++) {
            p[k] += c->length[i] * u[k];
            pv[k] += c->length[i] * (thd[i] * et[k] + fd * sin(th[i]) * ep[k]);
            x[3 * i + k] = p[k];
            v[3 * i + k] = pv[k];
        }
    }
}

static whirl_chain *pendulum_chain(size_t n)
{
    static const double len[MAXN] = {0.713, 1.109, 0.887, 0.5},
                        mass[MAXN] = {1.291, 0.617, 0.934, 1.1};
    return whirl_chain_alloc(n, len, mass, 1.0);
}

/* Positions at time t1 of the model started from pendulum_state, integrated by method with step h
 * (tol as for whirl_integrator_advance) in formulation f. Returns the status. Models with a drive
 * are 2D inertial or 3D co-rotating (the pivot at rest at t = 0). */
static int run(const whirl_model *m, whirl_formulation f, const char *method, double t1, double h,
               double tol, double *x_out)
{
    whirl_dyn *d = whirl_dyn_alloc(m, f);
    assert_non_null(d);
    double x[3 * MAXN], v[3 * MAXN], y[4 * 3 * MAXN], vout[3 * MAXN];
    pendulum_state(m->chain, m->dim, x, v);
    /* at t = 0 the pivot is at (eps, 0, 0), at rest (2D inertial, 3D co-rotating) */
    for (size_t i = 0; i < m->chain->n; i++) x[3 * i] += m->drive_radius;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    whirl_integrator *it = whirl_integrator_alloc(method, d);
    assert_non_null(it);
    double t = 0;
    int status = whirl_integrator_advance(it, &t, y, t1, h, tol);
    if (status == GSL_SUCCESS) assert_true(t == t1);
    whirl_dyn_get_state(d, t, y, WHIRL_FRAME_INERTIAL, x_out, vout);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    return status;
}

static double max_diff(const double *a, const double *b, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

/* Order under step halving on the 2D double pendulum (Cartesian), error against the seed
 * formulation's rk8pd solution: slopes within 0.2 of 4 (gauss2, rk4) and 6 (gauss3); rk8 (fixed
 * steps 0.2, 0.1, 0.05: errors 2e-7 .. 1e-12) at least 8 - 0.3 and at most 8 + 1.3. RK8(7)13M's
 * order-8 error coefficients are small by design (Prince and Dormand minimise them), so at these
 * errors the h^9 terms still add and the measured slopes are 8.87, 8.89; the slope tends to 8
 * only below 1e-11 (a 3-link pendulum: 8.17, 8.29 between 2e-10 and 2e-15), where the reference
 * floor interferes. (Checked: b_13 off by 1e-8 stalls the errors at 3.5e-8, slopes 2.5, 0.) */
static void test_order(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(2);
    const whirl_model m = {.chain = c, .dim = 2};
    const struct {
        const char *method;
        double order, below, above, h0, t1;
    } cases[] = {{"gauss2", 4, 0.2, 0.2, 0.1, 10},
                 {"gauss3", 6, 0.2, 0.2, 0.1, 10},
                 {"rk4", 4, 0.2, 0.2, 0.02, 5},
                 {"rk8", 8, 0.3, 1.3, 0.2, 5}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double err[3], ref[6];
        assert_int_equal(
            run(&m, WHIRL_FORMULATION_SEED, "gsl-rk8pd", cases[k].t1, 1e-3, 1e-14, ref), 0);
        for (int r = 0; r < 3; r++) {
            double x[6];
            assert_int_equal(run(&m, WHIRL_FORMULATION_CARTESIAN, cases[k].method, cases[k].t1,
                                 cases[k].h0 / (1 << r), 0, x),
                             GSL_SUCCESS);
            err[r] = max_diff(x, ref, 6);
        }
        const double s1 = log2(err[0] / err[1]), s2 = log2(err[1] / err[2]);
        print_message("%s: errors %.3g %.3g %.3g, slopes %.3f %.3f\n", cases[k].method, err[0],
                      err[1], err[2], s1, s2);
        assert_true(err[2] > 1e-13); /* still above round-off */
        for (int r = 0; r < 2; r++) {
            const double slope = r == 0 ? s1 : s2;
            assert_true(slope > cases[k].order - cases[k].below &&
                        slope < cases[k].order + cases[k].above);
        }
    }
    whirl_chain_free(c);
}

#define CHAIN_LINKS 10

/* Positions at t1 of the model started from (x0, v0) (3 per mass), by method (first step 1e-3,
 * tolerance tol) in formulation f; statistics in *stats. Returns the status. */
static int run_from(const whirl_model *m, whirl_formulation f, const char *method, double t1,
                    double tol, const double *x0, const double *v0, double *x_out,
                    whirl_integrator_stats *stats)
{
    whirl_dyn *d = whirl_dyn_alloc(m, f);
    assert_non_null(d);
    double y[4 * 3 * CHAIN_LINKS], vout[3 * CHAIN_LINKS];
    assert_int_equal(whirl_dyn_set_state(d, 0, x0, v0, y), GSL_SUCCESS);
    whirl_integrator *it = whirl_integrator_alloc(method, d);
    assert_non_null(it);
    double t = 0;
    const int status = whirl_integrator_advance(it, &t, y, t1, 1e-3, tol);
    if (status == GSL_SUCCESS) assert_true(t == t1);
    whirl_dyn_get_state(d, t, y, WHIRL_FRAME_INERTIAL, x_out, vout);
    *stats = whirl_integrator_get_stats(it);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    return status;
}

/* rk8 with step control meets its tolerance: final position error within 10 tol of the seed
 * formulation's gsl-rk8pd solution at tolerance 1e-14 (different coordinates and equations), at
 * tol = 1e-6 and 1e-9, on the 2D double pendulum (t = 5) and on a 2D chain of 10 equal links
 * released from a zig-zag at rest (t = 3). It reads tol as gsl-rk8pd does (the same pair and
 * control), so both take the same accepted steps (within 2 percent); rk8 needs fewer
 * evaluations (13 per step, a retry 12). */
static void test_rk8_adaptive(void **state)
{
    (void)state;
    for (int scene = 0; scene < 2; scene++) {
        const size_t n = scene == 0 ? 2 : CHAIN_LINKS;
        whirl_chain *c = scene == 0 ? pendulum_chain(2) : whirl_chain_alloc_uniform(n, 0);
        const whirl_model m = {.chain = c, .dim = 2};
        const double t1 = scene == 0 ? 5 : 3;
        double x[3 * CHAIN_LINKS] = {0}, v[3 * CHAIN_LINKS] = {0};
        if (scene == 0) {
            pendulum_state(c, 2, x, v);
        } else {
            double px = 0, pz = 0;
            for (size_t i = 0; i < n; i++) {
                const double th = 0.6 + 0.4 * sin(2.385 * (double)i);
                px += c->length[i] * sin(th);
                pz -= c->length[i] * cos(th);
                x[3 * i] = px, x[3 * i + 2] = pz;
            }
        }
        double ref[3 * CHAIN_LINKS], xr[3 * CHAIN_LINKS], xg[3 * CHAIN_LINKS];
        whirl_integrator_stats sr, sg;
        assert_int_equal(
            run_from(&m, WHIRL_FORMULATION_SEED, "gsl-rk8pd", t1, 1e-14, x, v, ref, &sr), 0);
        const double tols[2] = {1e-6, 1e-9};
        for (int k = 0; k < 2; k++) {
            assert_int_equal(
                run_from(&m, WHIRL_FORMULATION_CARTESIAN, "rk8", t1, tols[k], x, v, xr, &sr), 0);
            assert_int_equal(run_from(&m, WHIRL_FORMULATION_CARTESIAN, "gsl-rk8pd", t1, tols[k],
                                      x, v, xg, &sg),
                             0);
            const double err = max_diff(xr, ref, 3 * n), err_gsl = max_diff(xg, ref, 3 * n);
            print_message("%zu links, tol %g: rk8 error %.3g (%lu steps, %lu rejected, %lu rhs), "
                          "gsl-rk8pd %.3g (%lu steps, %lu rhs)\n",
                          n, tols[k], err, sr.steps, sr.rejected, sr.rhs_evals, err_gsl,
                          sg.steps, sg.rhs_evals);
            assert_true(err < 10 * tols[k]);
            assert_true(fabs((double)sr.steps - (double)sg.steps) <= 0.02 * (double)sg.steps);
            assert_int_equal(sr.rhs_evals, 13 * (sr.steps + sr.rejected) - sr.rejected);
            assert_true(sr.rhs_evals < sg.rhs_evals);
        }
        whirl_chain_free(c);
    }
}

/* Every method of whirl_integrator_methods(): refuses bad arguments; takes a tolerance if and
 * only if it is adaptive (gauss2, gauss3, rk4 are not); leaves the state on the constraints to
 * 1e-12 after a run (fixed steps, or adaptive for gsl-msadams and gsl-msbdf); stops with a
 * status on a non-finite state, t unchanged, and runs again from a good state. */
static void test_every_method(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(3);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[9], v[9], y0[18], y[18];
    pendulum_state(c, 3, x, v);
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y0), GSL_SUCCESS);
    for (const char *const *p = whirl_integrator_methods(); *p != NULL; p++) {
        whirl_integrator *it = whirl_integrator_alloc(*p, d);
        assert_non_null(it);
        const int fixed_only = strcmp(*p, "gauss2") == 0 || strcmp(*p, "gauss3") == 0 ||
                               strcmp(*p, "rk4") == 0;
        const int adaptive_only = strcmp(*p, "gsl-msbdf") == 0 || strcmp(*p, "gsl-msadams") == 0;
        double t = 0;
        memcpy(y, y0, sizeof y);
        assert_int_equal(whirl_integrator_advance(it, &t, y, -1, 1e-3, 0), GSL_EINVAL);
        assert_int_equal(whirl_integrator_advance(it, &t, y, 1, 0, 0), GSL_EINVAL);
        assert_int_equal(whirl_integrator_advance(it, &t, y, 1, NAN, 0), GSL_EINVAL);
        assert_int_equal(whirl_integrator_advance(it, &t, y, 1, 1e-3, -1e-8), GSL_EINVAL);
        assert_int_equal(whirl_integrator_advance(it, &t, y, NAN, 1e-3, 0), GSL_EINVAL);
        assert_true(t == 0);
        assert_memory_equal(y, y0, sizeof y);
        const int with_tol = whirl_integrator_advance(it, &t, y, 0.5, 1e-3, 1e-9);
        assert_int_equal(with_tol, fixed_only ? GSL_EINVAL : GSL_SUCCESS);
        t = 0;
        memcpy(y, y0, sizeof y);
        assert_int_equal(whirl_integrator_advance(it, &t, y, 0.5, 2e-3, adaptive_only ? 1e-9 : 0),
                         GSL_SUCCESS);
        whirl_dyn_diagnostics diag;
        whirl_dyn_diagnose(d, t, y, &diag);
        assert_true(diag.constraint <= 1e-12);
        const whirl_integrator_stats s = whirl_integrator_get_stats(it);
        assert_true(s.steps > 0 && s.rhs_evals > 0);
        /* a non-finite state: a status, t and y as given */
        double bad[18];
        memcpy(bad, y, sizeof bad);
        bad[1] = NAN;
        memcpy(y, bad, sizeof y);
        const double tb = t;
        const int status = whirl_integrator_advance(it, &t, y, tb + 0.1, 2e-3,
                                                    adaptive_only ? 1e-9 : 0);
        print_message("%s: constraint %.3g after t = 0.5; non-finite state: status %d (%s)\n",
                      *p, diag.constraint, status, whirl_last_error());
        assert_int_not_equal(status, GSL_SUCCESS);
        assert_true(t == tb);
        assert_true(isnan(y[1]));
        memcpy(y, y0, sizeof y);
        t = 0;
        assert_int_equal(whirl_integrator_advance(it, &t, y, 0.1, 2e-3, adaptive_only ? 1e-9 : 0),
                         GSL_SUCCESS);
        whirl_integrator_free(it);
    }
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* gauss3 at dt = 1e-3 against the independent reference: 2D double and 3D triple pendulum. */
static void test_gauss3_accuracy(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        const size_t n = dim == 2 ? 2 : 3;
        whirl_chain *c = pendulum_chain(n);
        const whirl_model m = {.chain = c, .dim = dim};
        const double t1 = 10.0;
        double ref[3 * MAXN], x[3 * MAXN];
        assert_int_equal(run(&m, WHIRL_FORMULATION_SEED, "gsl-rk8pd", t1, 1e-3, 1e-14, ref), 0);
        assert_int_equal(run(&m, WHIRL_FORMULATION_CARTESIAN, "gauss3", t1, 1e-3, 0, x), 0);
        const double err = max_diff(x, ref, 3 * n);
        print_message("%dD %zu-pendulum, gauss3 dt = 1e-3, t = 10: max position error %.3g\n", dim,
                      n, err);
        assert_true(err < 1e-9);
        whirl_chain_free(c);
    }
}

/* The two formulations' trajectories agree to integration accuracy with every force: 3D
 * co-rotating frame with the drive, both drags and internal damping; 2D inertial frame with the
 * drive and the seed's forcing. Both by gauss3 at h = 1e-3 over t = 5. */
static void test_formulations_trajectories(void **state)
{
    (void)state;
    const double sigma[3] = {0.21, -0.13, 0.07}, lambda[3] = {0.3, 0.05, 0.11};
    for (int dim = 2; dim <= 3; dim++) {
        whirl_chain *c = pendulum_chain(3);
        whirl_model m = {.chain = c, .dim = dim, .omega = 1.91, .drive_radius = 0.083,
                         .air_drag = 0.17, .air_drag_quadratic = 0.09, .internal_damping = 0.023};
        if (dim == 3) m.frame = WHIRL_FRAME_ROTATING;
        else m.seed_sigma = sigma, m.seed_lambda = lambda;
        double xc[9], xs[9];
        assert_int_equal(run(&m, WHIRL_FORMULATION_SEED, "gauss3", 5, 1e-3, 0, xs), 0);
        assert_int_equal(run(&m, WHIRL_FORMULATION_CARTESIAN, "gauss3", 5, 1e-3, 0, xc), 0);
        const double err = max_diff(xc, xs, 9);
        print_message("%dD with all forces: trajectories differ by %.3g at t = 5\n", dim, err);
        assert_true(err < 1e-10);
        whirl_chain_free(c);
    }
}

/* A 3D chain started hanging straight down with an in-plane kick swings through the vertical
 * (where the seed's 3D angles are singular) and stays planar: it matches the seed's 2D angles. */
static void test_through_vertical(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(3);
    double x[9] = {0}, v[9] = {0}, xt[2][9], vt[9], y[18];
    double z = 0;
    for (size_t i = 0; i < 3; i++) {
        x[3 * i + 2] = z -= c->length[i];
        v[3 * i] = 1.37 * (double)(i + 1);
    }
    for (int dim = 2; dim <= 3; dim++) {
        const whirl_model m = {.chain = c, .dim = dim};
        whirl_dyn *d = whirl_dyn_alloc(
            &m, dim == 2 ? WHIRL_FORMULATION_SEED : WHIRL_FORMULATION_CARTESIAN);
        assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
        whirl_integrator *it = whirl_integrator_alloc("gauss3", d);
        double t = 0;
        assert_int_equal(whirl_integrator_advance(it, &t, y, 10, 1e-3, 0), GSL_SUCCESS);
        whirl_dyn_get_state(d, t, y, WHIRL_FRAME_INERTIAL, xt[dim - 2], vt);
        whirl_integrator_free(it);
        whirl_dyn_free(d);
    }
    const double err = max_diff(xt[0], xt[1], 9);
    print_message("through the vertical: 3D Cartesian and 2D seed differ by %.3g at t = 10\n",
                  err);
    assert_true(err < 1e-9);
    whirl_chain_free(c);
}

/* Every GSL stepper, fixed and adaptive, converges to the reference; the multistep msadams and
 * msbdf are adaptive only, and
 * the own methods refuse a tolerance. */
static void test_gsl_steppers(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(3);
    const whirl_model m = {.chain = c, .dim = 3};
    const double t1 = 2.0;
    double ref[9], x[9];
    assert_int_equal(run(&m, WHIRL_FORMULATION_SEED, "gauss3", t1, 1e-3, 0, ref), 0);
    const char *const names[] = {"gsl-rk8pd", "gsl-rk4imp", "gsl-msadams",
                                 "gsl-msbdf", "gsl-rkf45",  "gsl-rk4"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        const int fixed = run(&m, WHIRL_FORMULATION_CARTESIAN, names[k], t1, 2e-3, 0, x);
        if (strcmp(names[k], "gsl-msbdf") == 0 || strcmp(names[k], "gsl-msadams") == 0) {
            assert_int_equal(fixed, GSL_EINVAL);
        } else {
            assert_int_equal(fixed, GSL_SUCCESS);
            assert_true(max_diff(x, ref, 9) < 1e-8);
        }
        assert_int_equal(run(&m, WHIRL_FORMULATION_CARTESIAN, names[k], t1, 1e-3, 1e-11, x), 0);
        const double err = max_diff(x, ref, 9);
        print_message("%s adaptive tol 1e-11: error %.3g\n", names[k], err);
        assert_true(err < 1e-7);
    }
    assert_int_equal(run(&m, WHIRL_FORMULATION_CARTESIAN, "gauss2", t1, 1e-3, 1e-8, x),
                     GSL_EINVAL);
    whirl_chain_free(c);
}

/* Energy (inertial frame, fixed pivot) and Jacobi's integral (co-rotating frame with the drive)
 * of Gauss runs (h = 0.005, t = 20, a chaotic quadruple pendulum) stay at their truncation level
 * (h^4: 1e-6 relative for gauss2, h^6: 1e-10 for gauss3), and the constraints hold to 1e-12 after
 * every step. The long-time behaviour is measured in tests/bench/bench_dynamics.c. */
static void test_conservation(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(4);
    for (int frame = 0; frame <= 1; frame++) {
        for (int method = 0; method < 2; method++) {
            whirl_model m = {.chain = c, .dim = 3, .frame = (whirl_frame)frame};
            if (frame == WHIRL_FRAME_ROTATING) m.omega = 1.37, m.drive_radius = 0.05;
            whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
            double x[12], v[12], y[24];
            pendulum_state(c, 3, x, v);
            for (size_t i = 0; i < 4; i++) x[3 * i] += m.drive_radius;
            assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
            whirl_integrator *it = whirl_integrator_alloc(method ? "gauss3" : "gauss2", d);
            whirl_dyn_diagnostics d0, di;
            whirl_dyn_diagnose(d, 0, y, &d0);
            double t = 0, worst = 0, worst_c = 0;
            for (int k = 1; k <= 200; k++) {
                assert_int_equal(whirl_integrator_advance(it, &t, y, 0.1 * k, 0.005, 0), 0);
                whirl_dyn_diagnose(d, t, y, &di);
                worst = fmax(worst, fabs(di.jacobi - d0.jacobi));
                worst_c = fmax(worst_c, di.constraint);
            }
            print_message("%s frame %d: max |dJ| %.3g, max constraint %.3g over t = 20\n",
                          method ? "gauss3" : "gauss2", frame, worst, worst_c);
            assert_true(worst < (method ? 1e-10 : 1e-6) * fmax(1, fabs(d0.jacobi)));
            assert_true(worst_c <= 1e-12);
            whirl_integrator_free(it);
            whirl_dyn_free(d);
        }
    }
    whirl_chain_free(c);
}

/* The steady shape of mode 2 at omega = 3.5 (N = 30) stays put in the co-rotating frame. */
static void test_steady_shape(void **state)
{
    (void)state;
    const size_t n = 30;
    const double omega = 3.5;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(c, omega, 2, &info), GSL_SUCCESS);
    double r[31], z[31], ten[31], x[90] = {0}, v[90] = {0}, y[180], xt[90];
    assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, ten), GSL_SUCCESS);
    for (size_t i = 0; i < n; i++) x[3 * i] = r[i + 1] - r[0], x[3 * i + 2] = z[i + 1] - z[0];
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    whirl_integrator *it = whirl_integrator_alloc("gauss2", d);
    double t = 0;
    const double t1 = 10 * 2 * 3.14159265358979323846 / omega;
    assert_int_equal(whirl_integrator_advance(it, &t, y, t1, 0.01, 0), GSL_SUCCESS);
    whirl_dyn_get_state(d, t, y, WHIRL_FRAME_ROTATING, xt, v);
    const double dev = whirl_deviation(n, xt, x);
    whirl_integrator_stats s = whirl_integrator_get_stats(it);
    print_message("steady mode 2, N = 30, 10 periods: deviation %.3g, %.2f sweeps per step\n",
                  dev, (double)s.iterations / (double)s.steps);
    assert_true(dev < 1e-12);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* An explicit method at a step far beyond its stability limit blows up: advance stops with a
 * status, t and y hold the last good (finite) state. */
static void test_blow_up(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(3);
    const whirl_model m = {.chain = c, .dim = 2};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[9], v[9], y[12];
    pendulum_state(c, 2, x, v);
    for (size_t k = 0; k < 9; k++) v[k] *= 30;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    whirl_integrator *it = whirl_integrator_alloc("rk4", d);
    double t = 0;
    const int status = whirl_integrator_advance(it, &t, y, 1e4, 0.5, 0);
    print_message("rk4 blow-up: status %d at t = %g: %s\n", status, t, whirl_last_error());
    assert_int_not_equal(status, GSL_SUCCESS);
    assert_true(t < 1e4);
    for (size_t k = 0; k < 12; k++) assert_true(isfinite(y[k]));
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

/* A step far beyond the fixed-point iteration's bound h omega_max rho(A) < 1 (N = 50: omega_max
 * ~ 100) fails with GSL_EMAXITER and leaves t, y at the last good state. */
static void test_stage_divergence(void **state)
{
    (void)state;
    const size_t n = 50;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model m = {.chain = c, .dim = 2};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    double x[150] = {0}, v[150] = {0}, y[200], y0[200];
    double z = 0;
    for (size_t i = 0; i < n; i++) x[3 * i + 2] = z -= c->length[i];
    for (size_t i = n / 2; i < n; i++) v[3 * i] = 0.1 * (double)(i - n / 2) / (double)n;
    assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
    memcpy(y0, y, sizeof y);
    whirl_integrator *it = whirl_integrator_alloc("gauss2", d);
    double t = 0;
    assert_int_equal(whirl_integrator_advance(it, &t, y, 1.0, 0.5, 0), GSL_EMAXITER);
    print_message("gauss2 h = 0.5, N = 50: %s\n", whirl_last_error());
    assert_true(t == 0);
    assert_memory_equal(y, y0, sizeof y);
    /* within the bound it runs */
    assert_int_equal(whirl_integrator_advance(it, &t, y, 0.1, 0.002, 0), GSL_SUCCESS);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

static void test_api(void **state)
{
    (void)state;
    whirl_chain *c = pendulum_chain(2);
    const whirl_model m = {.chain = c, .dim = 2};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_null(whirl_integrator_alloc("euler", d));
    assert_non_null(strstr(whirl_last_error(), "gauss3"));
    size_t count = 0;
    for (const char *const *p = whirl_integrator_methods(); *p != NULL; p++, count++) {
        whirl_integrator *it = whirl_integrator_alloc(*p, d);
        assert_non_null(it);
        whirl_integrator_free(it);
    }
    assert_int_equal(count, 10);
    whirl_integrator_free(NULL);
    whirl_integrator *it = whirl_integrator_alloc("gauss2", d);
    double x[6], v[6], y[8], t = 1;
    pendulum_state(c, 2, x, v);
    whirl_dyn_set_state(d, 1, x, v, y);
    assert_int_equal(whirl_integrator_advance(it, &t, y, 0.5, 0.1, 0), GSL_EINVAL);
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2, 0, 0), GSL_EINVAL);
    assert_int_equal(whirl_integrator_advance(it, &t, y, 2, 0.3, 0), GSL_SUCCESS);
    assert_true(t == 2);
    whirl_integrator_stats s = whirl_integrator_get_stats(it);
    assert_int_equal(s.steps, 4); /* 0.3, 0.3, 0.3, 0.1 */
    assert_true(s.rhs_evals > 0 && s.iterations > 0);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_order),        cmocka_unit_test(test_rk8_adaptive),
        cmocka_unit_test(test_every_method), cmocka_unit_test(test_gauss3_accuracy),
        cmocka_unit_test(test_formulations_trajectories),
        cmocka_unit_test(test_through_vertical),
        cmocka_unit_test(test_gsl_steppers), cmocka_unit_test(test_conservation),
        cmocka_unit_test(test_steady_shape), cmocka_unit_test(test_blow_up),
        cmocka_unit_test(test_stage_divergence),
        cmocka_unit_test(test_api),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
