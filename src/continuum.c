/* Steady shapes of the continuous uniform chain (length 1, mass 1, g = 1) with a point mass m at
 * its free end, rotating at omega about the vertical through its pivot.
 *
 * sigma: arclength from the free end (0) to the pivot (1). The part below sigma (mass sigma + m)
 * feels the weight W = sigma + m and the centrifugal force H(sigma) = m omega^2 a +
 * int_0^sigma omega^2 r; the tension carries both, T (dr, dz)/dsigma = (-H, W). With the mean
 * horizontal load per unit mass q = H / (sigma + m), T = (sigma + m) sqrt(1 + q^2) and
 *     dr/dsigma = -q / sqrt(1 + q^2),  dz/dsigma = 1 / sqrt(1 + q^2),
 *     dq/dsigma = (omega^2 r - q) / (sigma + m),     r(0) = a, q(0) = omega^2 a, z(0) = 0.
 * Integrated in the scaled variables R = r / a, Q = q / (omega^2 a) (order one for every a),
 *     R' = -omega^2 Q / sqrt(1 + b^2 Q^2), Q' = (R - Q) / (sigma + m), z' = 1 / sqrt(1 + b^2 Q^2),
 * b = omega^2 a, by GSL's rk8pd (Prince & Dormand 1981, J. Comp. Appl. Math. 7:67) with
 * tolerance 1e-13. For m = 0 the free end is a regular singular point (0/0 in Q'); the
 * integration starts at sigma_0 = 1e-4 / (1 + omega^2) from the Taylor series there, whose
 * coefficients follow from sigma q' + q = omega^2 r, i.e. q_n = omega^2 r_n / (n + 1), and
 * (n + 1) r_{n+1} = [f(q)]_n, (n + 1) z_{n+1} = [g(q)]_n, f = -q (1+q^2)^(-1/2),
 * g = (1+q^2)^(-1/2) (to order sigma^4; the remainder is ~ (omega^2 sigma_0)^5 ~ 1e-20).
 * Shooting: the pivot on the axis, r(1; a) = 0, see steady_shoot.c.
 *
 * Linear critical rates: (T r')' + omega^2 r = 0 with T = sigma + m. With x = 2 omega
 * sqrt(sigma + m) this is Bessel's equation of order 0, r = A J0(x) + B Y0(x). The free end
 * (x0 = 2 omega sqrt(m)) balances the tip mass, T r' = -m omega^2 r, i.e.
 * A (J1(x0) - x0/2 J0(x0)) + B (Y1(x0) - x0/2 Y0(x0)) = 0; the pivot (x1 = 2 omega sqrt(1 + m))
 * is on the axis, A J0(x1) + B Y0(x1) = 0. The critical rates are the roots of the determinant;
 * with m = 0, B = 0 and omega_k = j_{0,k} / 2.
 * References: Kolodner 1955, Comm. Pure Appl. Math. 8:395; Caughey 1958, J. Appl. Mech.;
 * Coomer, Lazarus, Tucker, Kershaw, Tegman 2001, J. Sound Vib. 244:845. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_sf_bessel.h>

#include "error.h"
#include "steady_internal.h"

#define START_SIGMA 1e-4  /* sigma_0 (1 + omega^2) of the series start, tip mass 0 */
#define STEP_MAX 100000   /* ODE steps per shot */
#define REFINE_MAX 100    /* iterations locating a node, an extremum or a critical rate */

typedef struct continuum_params {
    double tip_mass;
    double tol; /* ODE tolerance, absolute and relative on (R, Q, z) */
} continuum_params;

typedef struct continuum_ws {
    continuum_params p;
    double omega, a; /* the current shot */
    gsl_odeiv2_system sys;
    gsl_odeiv2_step *step;
    gsl_odeiv2_control *control;
    gsl_odeiv2_evolve *evolve;
    gsl_odeiv2_driver *driver;   /* short integrations when locating nodes and extrema */
} continuum_ws;

/* The right-hand side in the scaled variables y = (R, Q, z). */
static int rhs(double sigma, const double y[], double dy[], void *params)
{
    const continuum_ws *w = params;
    double w2 = w->omega * w->omega, b = w2 * w->a;
    double inv = 1 / sqrt(1 + b * b * y[1] * y[1]);
    dy[0] = -w2 * y[1] * inv;
    dy[1] = (y[0] - y[1]) / (sigma + w->p.tip_mass);
    dy[2] = inv;
    return GSL_SUCCESS;
}

static void continuum_ws_free(void *ws)
{
    continuum_ws *w = ws;
    if (w == NULL) return;
    if (w->step) gsl_odeiv2_step_free(w->step);
    if (w->control) gsl_odeiv2_control_free(w->control);
    if (w->evolve) gsl_odeiv2_evolve_free(w->evolve);
    if (w->driver) gsl_odeiv2_driver_free(w->driver);
    free(w);
}

static void *continuum_ws_alloc(const void *params)
{
    continuum_ws *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->p = *(const continuum_params *)params;
    w->sys = (gsl_odeiv2_system){rhs, NULL, 3, w};
    w->step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 3);
    w->control = gsl_odeiv2_control_y_new(w->p.tol, w->p.tol);
    w->evolve = gsl_odeiv2_evolve_alloc(3);
    w->driver = gsl_odeiv2_driver_alloc_y_new(&w->sys, gsl_odeiv2_step_rk8pd, 1e-6, w->p.tol,
                                              w->p.tol);
    if (!(w->step && w->control && w->evolve && w->driver)) goto fail;
    return w;
fail:
    continuum_ws_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the continuum workspace");
    return NULL;
}

/* The start of the integration: sigma and y there (the tip, or the series point for m = 0). */
static double start_state(const continuum_ws *w, double y[3])
{
    double w2 = w->omega * w->omega, a = w->a;
    if (w->p.tip_mass > 0) {
        y[0] = 1, y[1] = 1, y[2] = 0;
        return 0;
    }
    /* Taylor coefficients r_n, q_n, z_n of the unscaled r, q, z at sigma = 0 */
    double r[5], q[5], z[5];
    r[0] = a, q[0] = w2 * a, z[0] = 0;
    double q0 = q[0], p = 1 + q0 * q0, sp = sqrt(p);
    double f0 = -q0 / sp, f1 = -1 / (p * sp), f2 = 3 * q0 / (p * p * sp),
           f3 = 3 / (p * p * sp) - 15 * q0 * q0 / (p * p * p * sp);
    double g0 = 1 / sp, g1 = -q0 / (p * sp), g2 = (2 * q0 * q0 - 1) / (p * p * sp),
           g3 = 4 * q0 / (p * p * sp) - 5 * q0 * (2 * q0 * q0 - 1) / (p * p * p * sp);
    r[1] = f0, z[1] = g0, q[1] = w2 * r[1] / 2;
    r[2] = f1 * q[1] / 2, z[2] = g1 * q[1] / 2, q[2] = w2 * r[2] / 3;
    r[3] = (f1 * q[2] + f2 * q[1] * q[1] / 2) / 3;
    z[3] = (g1 * q[2] + g2 * q[1] * q[1] / 2) / 3;
    q[3] = w2 * r[3] / 4;
    r[4] = (f1 * q[3] + f2 * q[1] * q[2] + f3 * q[1] * q[1] * q[1] / 6) / 4;
    z[4] = (g1 * q[3] + g2 * q[1] * q[2] + g3 * q[1] * q[1] * q[1] / 6) / 4;
    q[4] = w2 * r[4] / 5;
    double s = START_SIGMA / (1 + w2), rs = 0, qs = 0, zs = 0;
    for (int n = 4; n >= 0; n--) {
        rs = rs * s + r[n];
        qs = qs * s + q[n];
        zs = zs * s + z[n];
    }
    y[0] = rs / a, y[1] = qs / (w2 * a), y[2] = zs;
    return s;
}

/* What one integration from the tip to the pivot records. */
typedef struct continuum_run {
    int crossings;           /* sign changes of r at the steps below the pivot */
    double y_pivot[3];       /* (R, Q, z) at sigma = 1 */
    int locate;              /* also locate the nodes and the extrema: */
    int n_nodes;             /* nodes found, node_sigma[] increasing */
    double node_sigma[WHIRL_MODE_MAX];
    double max_abs_r;        /* max |r| over the tip and the extrema */
} continuum_run;

/* y(sigma) integrated from (sigma_a, y_a) with first step h. */
static int state_at(continuum_ws *w, double sigma_a, const double y_a[3], double h, double sigma,
                    double y[3])
{
    double t = sigma_a;
    for (int i = 0; i < 3; i++) y[i] = y_a[i];
    if (sigma <= t) return GSL_SUCCESS;
    gsl_odeiv2_driver_reset_hstart(w->driver, h);
    return gsl_odeiv2_driver_apply(w->driver, &t, sigma, y);
}

/* The zero of component c within the step [sigma_a, sigma_b] (y_a, y_b of opposite signs in
 * c), to tol in sigma, by Newton's method on y_c(sigma) with dy_c/dsigma from the right-hand
 * side, kept inside the shrinking bracket (bisection when a step leaves it); y receives the
 * state at the last point evaluated. */
static int locate_zero(continuum_ws *w, int c, double sigma_a, const double y_a[3],
                       double sigma_b, const double y_b[3], double tol, double *sigma,
                       double y[3])
{
    double lo = sigma_a, hi = sigma_b, h = sigma_b - sigma_a;
    double s = sigma_a + h * y_a[c] / (y_a[c] - y_b[c]); /* the secant's zero */
    for (int iter = 0; iter < REFINE_MAX; iter++) {
        double dy[3];
        int status = state_at(w, sigma_a, y_a, h, s, y);
        if (status != GSL_SUCCESS)
            return whirl_fail(status, "ODE integration failed locating a zero of the shape");
        rhs(s, y, dy, w);
        if ((y[c] > 0) == (y_a[c] > 0)) lo = s;
        else hi = s;
        double next = dy[c] != 0 ? s - y[c] / dy[c] : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (fabs(next - s) <= tol || y[c] == 0) {
            *sigma = s;
            return GSL_SUCCESS;
        }
        s = next;
    }
    return whirl_fail(GSL_EMAXITER, "no convergence locating a zero of the shape (omega=%g, a=%g)",
                      w->omega, w->a);
}

/* Integrates the shape with tip radius w->a from the tip to the pivot. */
static int integrate(continuum_ws *w, continuum_run *run)
{
    double y[3], y_prev[3];
    double sigma = start_state(w, y);
    double h = START_SIGMA / (1 + w->omega * w->omega);
    gsl_odeiv2_step_reset(w->step);
    gsl_odeiv2_evolve_reset(w->evolve);
    run->crossings = 0;
    run->n_nodes = 0;
    run->max_abs_r = w->a;
    for (int n = 0; sigma < 1; n++) {
        if (n == STEP_MAX)
            return whirl_fail(GSL_EMAXITER, "more than %d ODE steps (omega=%g, a=%g)", STEP_MAX,
                              w->omega, w->a);
        double sigma_prev = sigma;
        for (int i = 0; i < 3; i++) y_prev[i] = y[i];
        int status = gsl_odeiv2_evolve_apply(w->evolve, w->control, w->step, &w->sys, &sigma, 1,
                                             &h, y);
        if (status != GSL_SUCCESS)
            return whirl_fail(status, "ODE integration failed at sigma=%g (omega=%g, a=%g)",
                              sigma, w->omega, w->a);
        if (sigma < 1 && (y[0] > 0) != (y_prev[0] > 0)) {
            run->crossings++;
            if (run->locate && run->n_nodes < WHIRL_MODE_MAX) {
                double s_node, y_node[3];
                status = locate_zero(w, 0, sigma_prev, y_prev, sigma, y, 1e-15, &s_node, y_node);
                if (status != GSL_SUCCESS) return status;
                run->node_sigma[run->n_nodes++] = s_node;
            }
        }
        if (run->locate && (y[1] > 0) != (y_prev[1] > 0)) {
            /* an extremum of r where the horizontal load q vanishes */
            double s_ext, y_ext[3];
            status = locate_zero(w, 1, sigma_prev, y_prev, sigma, y, 1e-9, &s_ext, y_ext);
            if (status != GSL_SUCCESS) return status;
            run->max_abs_r = fmax(run->max_abs_r, w->a * fabs(y_ext[0]));
        }
    }
    for (int i = 0; i < 3; i++) run->y_pivot[i] = y[i];
    return GSL_SUCCESS;
}

static int continuum_shot(void *ws, double a, double *residual, int *crossings)
{
    continuum_ws *w = ws;
    continuum_run run = {0};
    w->a = a;
    int status = integrate(w, &run);
    *residual = run.y_pivot[0];
    *crossings = run.crossings;
    return status;
}

/* The determinant of the linearised problem with a tip mass m > 0 (see the header comment):
 * zero at the critical rates. */
static double critical_determinant(double omega, void *params)
{
    double m = *(const double *)params;
    double x0 = 2 * omega * sqrt(m), x1 = 2 * omega * sqrt(1 + m);
    return (gsl_sf_bessel_J1(x0) - 0.5 * x0 * gsl_sf_bessel_J0(x0)) * gsl_sf_bessel_Y0(x1) -
           (gsl_sf_bessel_Y1(x0) - 0.5 * x0 * gsl_sf_bessel_Y0(x0)) * gsl_sf_bessel_J0(x1);
}

int whirl_continuum_critical(int mode, double tip_mass, double *omega)
{
    if (mode < 1 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "mode must be between 1 and %d, got %d", WHIRL_MODE_MAX,
                          mode);
    if (!(isfinite(tip_mass) && tip_mass >= 0))
        return whirl_fail(GSL_EINVAL, "tip mass must be >= 0 and finite, got %g", tip_mass);
    if (tip_mass == 0) {
        *omega = 0.5 * gsl_sf_bessel_zero_J0((unsigned)mode);
        return GSL_SUCCESS;
    }
    /* omega_1 lies in (1, j_{0,1}/2] (a pendulum for a heavy tip, the chain without): scan in
     * steps of 0.05 up to it; the later roots are about pi / (2 (sqrt(1+m) - sqrt(m))) apart
     * (the phase x1 - x0 of the Bessel functions): scan in 1/32 of that */
    double spacing = M_PI / (2 * (sqrt(1 + tip_mass) - sqrt(tip_mass)));
    gsl_function f = {critical_determinant, &tip_mass};
    double lo = 0.5, f_lo = critical_determinant(lo, &tip_mass);
    int found = 0;
    for (int iter = 0; iter < 100000; iter++) {
        double step = found == 0 ? fmin(0.05, spacing / 32) : spacing / 32;
        double hi = lo + step, f_hi = critical_determinant(hi, &tip_mass);
        if ((f_lo > 0) != (f_hi > 0) && ++found == mode) {
            gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
            if (s == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the root solver");
            gsl_root_fsolver_set(s, &f, lo, hi);
            for (int k = 0; k < REFINE_MAX; k++) {
                if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
                if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s),
                                           gsl_root_fsolver_x_upper(s), 0,
                                           2 * DBL_EPSILON) == GSL_SUCCESS)
                    break;
            }
            *omega = gsl_root_fsolver_root(s);
            gsl_root_fsolver_free(s);
            return GSL_SUCCESS;
        }
        lo = hi, f_lo = f_hi;
    }
    return whirl_fail(GSL_EFAILED, "critical rate of mode %d with tip mass %g not found", mode,
                      tip_mass);
}

static int continuum_solve_ws(void *ws, double omega, int mode, double tip_r_guess,
                              whirl_shape_info *info)
{
    continuum_ws *w = ws;
    int status = whirl_steady_check_args(omega, mode);
    if (status != GSL_SUCCESS) return status;
    w->omega = omega;
    double a;
    status = whirl_steady_shoot_root(continuum_shot, w, mode, 1, 0, tip_r_guess, &a);
    if (status == GSL_EDOM) {
        double omega_k;
        if (whirl_continuum_critical(mode, w->p.tip_mass, &omega_k) != GSL_SUCCESS)
            return GSL_EDOM;
        return whirl_steady_fail_missing(mode, omega, omega_k);
    }
    if (status != GSL_SUCCESS) return status;
    continuum_run run = {0};
    run.locate = 1;
    w->a = a;
    if ((status = integrate(w, &run)) != GSL_SUCCESS) return status;
    if (run.n_nodes != mode - 1)
        return whirl_fail(GSL_EFAILED, "mode %d at omega=%g: found %d axis crossings", mode,
                          omega, run.n_nodes);
    double b = omega * omega * a;
    info->omega = omega;
    info->mode = mode;
    info->tip_r = a;
    info->max_r = run.max_abs_r;
    info->top_tension = (1 + w->p.tip_mass) * sqrt(1 + b * b * run.y_pivot[1] * run.y_pivot[1]);
    info->depth = run.y_pivot[2];
    info->n_nodes = run.n_nodes;
    for (int j = 0; j < run.n_nodes; j++) info->node_s[j] = 1 - run.node_sigma[run.n_nodes - 1 - j];
    return GSL_SUCCESS;
}

static int check_tip_mass(double tip_mass)
{
    if (!(isfinite(tip_mass) && tip_mass >= 0))
        return whirl_fail(GSL_EINVAL, "tip mass must be >= 0 and finite, got %g", tip_mass);
    return GSL_SUCCESS;
}

int whirl_continuum_solve_tol(double omega, int mode, double tip_mass, double tip_r_guess,
                              double tol, whirl_shape_info *info)
{
    int status = check_tip_mass(tip_mass);
    if (status != GSL_SUCCESS) return status;
    if (!(tol > 0 && tol < 1))
        return whirl_fail(GSL_EINVAL, "tolerance must be in (0, 1), got %g", tol);
    continuum_params p = {tip_mass, tol};
    continuum_ws *w = continuum_ws_alloc(&p);
    if (w == NULL) return GSL_ENOMEM;
    status = continuum_solve_ws(w, omega, mode, tip_r_guess, info);
    continuum_ws_free(w);
    return status;
}

int whirl_continuum_solve(double omega, int mode, double tip_mass, double tip_r_guess,
                          whirl_shape_info *info)
{
    return whirl_continuum_solve_tol(omega, mode, tip_mass, tip_r_guess, WHIRL_CONTINUUM_TOL,
                                     info);
}

int whirl_continuum_sample(double omega, double tip_mass, double tip_r, size_t npts, double *s,
                           double *r, double *z, double *tension)
{
    int status = check_tip_mass(tip_mass);
    if (status != GSL_SUCCESS) return status;
    if (!(isfinite(omega) && omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be > 0 and finite, got %g", omega);
    if (!(isfinite(tip_r) && tip_r > 0 && tip_r <= 1))
        return whirl_fail(GSL_EINVAL, "tip radius must be in (0, 1], got %g", tip_r);
    if (npts < 2) return whirl_fail(GSL_EINVAL, "need at least 2 points, got %zu", npts);
    continuum_params p = {tip_mass, WHIRL_CONTINUUM_TOL};
    continuum_ws *w = continuum_ws_alloc(&p);
    if (w == NULL) return GSL_ENOMEM;
    w->omega = omega;
    w->a = tip_r;
    double y0[3], y[3];
    double sigma0 = start_state(w, y0), b = omega * omega * tip_r;
    double t = sigma0;
    for (int i = 0; i < 3; i++) y[i] = y0[i];
    gsl_odeiv2_driver_reset(w->driver);
    /* from the free end (j = npts - 1, sigma = 0) up to the pivot (j = 0, sigma = 1) */
    for (size_t k = 0; k < npts && status == GSL_SUCCESS; k++) {
        size_t j = npts - 1 - k;
        double sigma = (double)k / (double)(npts - 1);
        if (k == npts - 1) sigma = 1;
        double yj[3];
        if (sigma <= sigma0) {
            /* within the series start: linear between the tip and sigma_0 (error ~ sigma_0^2) */
            double f = sigma0 > 0 ? sigma / sigma0 : 0;
            yj[0] = 1 + f * (y0[0] - 1), yj[1] = 1 + f * (y0[1] - 1), yj[2] = f * y0[2];
        } else {
            status = gsl_odeiv2_driver_apply(w->driver, &t, sigma, y);
            for (int i = 0; i < 3; i++) yj[i] = y[i];
        }
        s[j] = 1 - sigma;
        r[j] = tip_r * yj[0];
        z[j] = yj[2];
        tension[j] = (sigma + tip_mass) * sqrt(1 + b * b * yj[1] * yj[1]);
    }
    if (status != GSL_SUCCESS)
        status = whirl_fail(status, "ODE integration failed sampling the shape (omega=%g)", omega);
    else
        for (size_t j = npts; j-- > 0;) z[j] -= z[0]; /* heights relative to the pivot */
    continuum_ws_free(w);
    return status;
}

int whirl_continuum_branch(int mode, double tip_mass, size_t n, const double *omega,
                           whirl_shape_info *info, int *exists)
{
    int status = check_tip_mass(tip_mass);
    if (status != GSL_SUCCESS) return status;
    continuum_params p = {tip_mass, WHIRL_CONTINUUM_TOL};
    steady_model m = {continuum_ws_alloc, continuum_ws_free, continuum_solve_ws, &p};
    return whirl_steady_branch(&m, mode, n, omega, info, exists);
}
