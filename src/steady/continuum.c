/* Steady shapes of the continuous uniform chain (length 1, mass 1, g = 1) with a point mass m at
 * its free end, rotating at omega about the vertical through its pivot.
 *
 * sigma: arclength from the free end (0) to the pivot (1). The part below sigma (mass sigma + m)
 * feels the weight W = sigma + m and the centrifugal force H(sigma) = m omega^2 a +
 * int_0^sigma omega^2 r; the tension carries both, T (dr, dz)/dsigma = (-H, W). With the mean
 * horizontal load per unit mass q = H / (sigma + m), T = (sigma + m) sqrt(1 + q^2) and
 *     dr/dsigma = -q / sqrt(1 + q^2),  dz/dsigma = 1 / sqrt(1 + q^2),
 *     dq/dsigma = (omega^2 r - q) / (sigma + m),     r(0) = a, q(0) = omega^2 a, z(0) = 0.
 * In the scaled variables R = r / a, Q = q / (omega^2 a) (order one for every a), with
 * b = omega^2 a and S = sqrt(1 + b^2 Q^2),
 *     R' = -omega^2 Q / S,  Q' = (R - Q) / (sigma + m),  z' = 1 / S,  R(0) = Q(0) = 1.
 *
 * Linear part split off. Near a critical rate the pivot's radius R(1) is a small difference
 * (the linear part, ~ omega - omega_k, minus a nonlinear part ~ b^2): integrated whole, its
 * absolute error ~ tol would cost tip_r about tol / (omega / omega_k - 1) relative. So
 * R = R0 + beta D, Q = Q0 + beta E with beta = b^2 / (1 + b^2), where (R0, Q0) is the linear
 * (b = 0) solution with the same start, and
 *     R0' = -omega^2 Q0,  Q0' = (R0 - Q0) / (sigma + m),
 *     D' = -omega^2 (E + F),  E' = (D - E) / (sigma + m),
 *     F = (Q / S - Q) / beta = -(1 + b^2) Q^3 / (S (1 + S))   (no cancellation),
 * D(0) = E(0) = 0; (D, E) are order one for every b, so their error ~ tol enters R(1) times beta.
 * The residual is R(1) = R0(1) + beta D(1), with the linear part R0(1) (and Q0(1)) computed
 * once per rate to ~1e-18 by the Taylor-series method in long double: around sigma_c with
 * t = sigma_c + m, (n + 1) R0_{n+1} = -omega^2 Q0_n and t (n + 1) Q0_{n+1} = R0_n - (n + 1) Q0_n
 * (t = 0, the free end without tip mass: Q0_n = R0_n / (n + 1)), each step as long as the last
 * two terms stay below 1e-21. (The closed form R0 = A J0(x) + B Y0(x), see below, evaluated in
 * double loses up to 2e-13 with a heavy tip, where |A|, |B| reach ~1e3 and the phases of J0, Y0
 * carry the roundings of x: 3e-10 in tip_r at 1e-6 above omega_k for m = 3.7.)
 * (R0, Q0) are also integrated alongside by the ODE solver, as Q in F needs them (their error
 * enters D times beta).
 * The split is used only for b <= 1: beyond, it gains nothing (beta > 1/2) and costs steps, as
 * the linear solution oscillates where the shape does not (right-hand sides per solve, mode 1:
 * 36198 split against 12652 whole at omega = 10, 92332 against 25730 at omega = 30), so there
 * the whole state (R, Q, z) is integrated, kept in the slots of (D, E, z) with beta = 1.
 * The ODE is integrated by GSL's rk8pd (Prince & Dormand 1981, J. Comp. Appl. Math. 7:67) with
 * tolerance 1e-13 on the state.
 * For m = 0 the free end is a regular singular point (0/0 in Q'): the integration starts at
 * sigma_0 = 1e-4 / (1 + omega^2) from the Taylor series there (to order sigma^4; remainder
 * ~ (omega^2 sigma_0)^5 ~ 1e-20): sigma Q0' + Q0 = R0 gives Q0_n = R0_n / (n + 1) and
 * R0_n = (-omega^2)^n / (n!)^2 (the J0 series); likewise E_n = D_n / (n + 1),
 * (n + 1) D_{n+1} = -omega^2 (E_n + F_n), (n + 1) z_{n+1} = [1/S]_n, with F_n, [1/S]_n by
 * power-series arithmetic on Q = Q0 + beta E (whole: (n + 1) R_{n+1} = -omega^2 [Q / S]_n).
 * Shooting: the pivot on the axis, R(1; a) = 0, see steady_shoot.c.
 *
 * Linear critical rates, where R0(1) = 0: (T r')' + omega^2 r = 0 with T = sigma + m. With
 * x = 2 omega sqrt(sigma + m) this is Bessel's equation of order 0, r = A J0(x) + B Y0(x). The
 * free end (x0 = 2 omega sqrt(m)) balances the tip mass, T r' = -m omega^2 r, i.e.
 * A (J1(x0) - x0/2 J0(x0)) + B (Y1(x0) - x0/2 Y0(x0)) = 0; the pivot (x1 = 2 omega sqrt(1 + m))
 * is on the axis, A J0(x1) + B Y0(x1) = 0. The critical rates are the roots of the determinant;
 * with m = 0, B = 0 and omega_k = j_{0,k} / 2.
 * References: Kolodner 1955, Comm. Pure Appl. Math. 8:395; Caughey 1958, J. Appl. Mech.;
 * Coomer, Lazarus, Tucker, Kershaw, Tegman 2001, J. Sound Vib. 244:845. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sf_bessel.h>

#include "core/error.h"
#include "core/roots.h"
#include "steady/steady_internal.h"

#define START_SIGMA 1e-4  /* sigma_0 (1 + omega^2) of the series start, tip mass 0 */
#define SERIES_TERMS 5    /* Taylor coefficients of sigma^0 .. sigma^4 at the free end */
#define STEP_MAX 100000   /* ODE steps per shot */
#define REFINE_MAX 100    /* iterations locating a node, an extremum or a critical rate */
#define SPLIT_B_MAX 1     /* the linear part is split off for b = omega^2 a <= this */
#define LINEAR_TERMS 30   /* Taylor terms per step of the linear solution (long double) */
#define LINEAR_TOL 1e-21L /* the bound on the last two terms of each step */
#define LINEAR_STEP_MAX 1000000 /* Taylor steps of the linear solution (about omega / 3 needed) */

/* The state: (D, E) (split: R = R0 + beta D, Q = Q0 + beta E; whole: R = D, Q = E), the height
 * z, then (R0, Q0), integrated only when split. */
enum { Y_D, Y_E, Y_Z, Y_R0, Y_Q0, N_STATE };
enum { N_WHOLE = Y_R0 };                 /* the components of the whole formulation */
enum { SHAPE_R = Y_D, SHAPE_Q = Y_E };   /* which of R, Q shape_value() returns */

typedef struct continuum_params {
    double tip_mass;
    double tol; /* ODE tolerance, absolute and relative on the state */
} continuum_params;

typedef struct continuum_ws {
    continuum_params p;
    double omega, w2;          /* the rate and omega^2 */
    double r0_pivot, q0_pivot; /* R0(1), Q0(1) */
    double a, b2;              /* the current shot: tip radius, b^2 = (omega^2 a)^2 */
    int split;                 /* b <= SPLIT_B_MAX: the linear part split off */
    double beta;               /* split: b^2 / (1 + b^2); whole: 1 */
    struct continuum_ode {     /* the integrators of the whole [0] and the split [1] state */
        gsl_odeiv2_system sys;
        gsl_odeiv2_step *step;
        gsl_odeiv2_control *control;
        gsl_odeiv2_evolve *evolve;
        gsl_odeiv2_driver *driver; /* short integrations when locating nodes and extrema */
    } ode[2];
} continuum_ws;

/* The linear solution at the pivot, R0(1) and Q0(1), by the Taylor-series method in long
 * double from the free end (see the header comment). */
static int linear_pivot(double omega, double m, double *r0_pivot, double *q0_pivot)
{
    const long double w2 = (long double)omega * omega;
    long double sigma = 0, r0 = 1, q0 = 1;
    for (long step = 0; sigma < 1; step++) {
        if (step == LINEAR_STEP_MAX)
            return whirl_fail(GSL_EMAXITER, "more than %d Taylor steps for the linear solution "
                              "(omega=" WHIRL_Q_RATE "%g): lower the rate", LINEAR_STEP_MAX, omega);
        long double r[LINEAR_TERMS], q[LINEAR_TERMS], t = sigma + m;
        r[0] = r0, q[0] = q0;
        for (int n = 1; n < LINEAR_TERMS; n++) {
            r[n] = -w2 * q[n - 1] / n;
            q[n] = t > 0 ? (r[n - 1] - n * q[n - 1]) / (t * n) : r[n] / (n + 1);
        }
        /* the step: the last two terms below LINEAR_TOL (its length needs no long double) */
        long double h = 1 - sigma;
        for (int n = LINEAR_TERMS - 2; n < LINEAR_TERMS; n++) {
            long double c = fmaxl(fabsl(r[n]), fabsl(q[n]));
            if (c > 0) h = fminl(h, pow((double)(LINEAR_TOL / c), 1.0 / n));
        }
        r0 = 0, q0 = 0;
        for (int n = LINEAR_TERMS - 1; n >= 0; n--) {
            r0 = r0 * h + r[n];
            q0 = q0 * h + q[n];
        }
        sigma = h == 1 - sigma ? 1 : sigma + h;
    }
    *r0_pivot = (double)r0;
    *q0_pivot = (double)q0;
    return GSL_SUCCESS;
}

/* The rates the shooting resolves: above WHIRL_CONTINUUM_OMEGA_MAX it is refused. */
static int check_rate(double omega)
{
    if (!(isfinite(omega) && omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be > 0 and finite, got %g", omega);
    if (omega > WHIRL_CONTINUUM_OMEGA_MAX)
        return whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g is above %g, the highest rate the "
                          "continuum shooting resolves (its ODE would need more than %d steps per "
                          "shot); use the N-link chain (--links) there", omega,
                          WHIRL_CONTINUUM_OMEGA_MAX, STEP_MAX);
    return GSL_SUCCESS;
}

/* The rate of the following shots: omega^2 and the linear solution at the pivot. */
static int set_rate(continuum_ws *w, double omega)
{
    int status = check_rate(omega);
    if (status != GSL_SUCCESS) return status;
    w->omega = omega;
    w->w2 = omega * omega;
    return linear_pivot(omega, w->p.tip_mass, &w->r0_pivot, &w->q0_pivot);
}

/* The tip radius of the following shots, and the formulation. */
static void set_tip_radius(continuum_ws *w, double a)
{
    double b = w->w2 * a;
    w->a = a;
    w->b2 = b * b;
    w->split = b <= SPLIT_B_MAX;
    w->beta = w->split ? w->b2 / (1 + w->b2) : 1;
}

/* R (c = SHAPE_R) or Q (c = SHAPE_Q) from the state y, or their derivatives from y'. */
static double shape_value(const continuum_ws *w, int c, const double y[])
{
    return w->split ? y[c + (Y_R0 - Y_D)] + w->beta * y[c] : y[c];
}

/* The right-hand sides (see the header comment): the whole state (R, Q, z) ... */
static int rhs_whole(double sigma, const double y[], double dy[], void *params)
{
    const continuum_ws *w = params;
    double q = y[Y_E], inv_s = 1 / sqrt(1 + w->b2 * q * q);
    dy[Y_D] = -w->w2 * q * inv_s;
    dy[Y_E] = (y[Y_D] - q) / (sigma + w->p.tip_mass);
    dy[Y_Z] = inv_s;
    return GSL_SUCCESS;
}

/* ... and the split one (D, E, z, R0, Q0). */
static int rhs_split(double sigma, const double y[], double dy[], void *params)
{
    const continuum_ws *w = params;
    double t = sigma + w->p.tip_mass;
    double q = y[Y_Q0] + w->beta * y[Y_E], s = sqrt(1 + w->b2 * q * q), inv_s = 1 / s;
    dy[Y_D] = -w->w2 * (y[Y_E] - (1 + w->b2) * q * q * q * inv_s / (1 + s));
    dy[Y_E] = (y[Y_D] - y[Y_E]) / t;
    dy[Y_Z] = inv_s;
    dy[Y_R0] = -w->w2 * y[Y_Q0];
    dy[Y_Q0] = (y[Y_R0] - y[Y_Q0]) / t;
    return GSL_SUCCESS;
}

static void continuum_ws_free(void *ws)
{
    continuum_ws *w = ws;
    if (w == NULL) return;
    for (int i = 0; i < 2; i++) {
        struct continuum_ode *o = &w->ode[i];
        if (o->step) gsl_odeiv2_step_free(o->step);
        if (o->control) gsl_odeiv2_control_free(o->control);
        if (o->evolve) gsl_odeiv2_evolve_free(o->evolve);
        if (o->driver) gsl_odeiv2_driver_free(o->driver);
    }
    free(w);
}

static void *continuum_ws_alloc(const void *params)
{
    continuum_ws *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->p = *(const continuum_params *)params;
    for (int i = 0; i < 2; i++) {
        struct continuum_ode *o = &w->ode[i];
        size_t dim = i ? N_STATE : N_WHOLE;
        o->sys = (gsl_odeiv2_system){i ? rhs_split : rhs_whole, NULL, dim, w};
        o->step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, dim);
        o->control = gsl_odeiv2_control_y_new(w->p.tol, w->p.tol);
        o->evolve = gsl_odeiv2_evolve_alloc(dim);
        o->driver = gsl_odeiv2_driver_alloc_y_new(&o->sys, gsl_odeiv2_step_rk8pd, 1e-6, w->p.tol,
                                                  w->p.tol);
        if (!(o->step && o->control && o->evolve && o->driver)) goto fail;
    }
    return w;
fail:
    continuum_ws_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the continuum workspace");
    return NULL;
}

/* Truncated power series of n terms: c = x y, c = x / y (y[0] != 0), c = sqrt(x) (x[0] > 0). */
static void series_mul(const double *x, const double *y, int n, double *c)
{
    for (int k = 0; k < n; k++) {
        c[k] = 0;
        for (int j = 0; j <= k; j++) c[k] += x[j] * y[k - j];
    }
}

static void series_div(const double *x, const double *y, int n, double *c)
{
    for (int k = 0; k < n; k++) {
        double t = x[k];
        for (int j = 0; j < k; j++) t -= c[j] * y[k - j];
        c[k] = t / y[0];
    }
}

static void series_sqrt(const double *x, int n, double *c)
{
    c[0] = sqrt(x[0]);
    for (int k = 1; k < n; k++) {
        double t = x[k];
        for (int j = 1; j < k; j++) t -= c[j] * c[k - j];
        c[k] = t / (2 * c[0]);
    }
}

/* The first n Taylor coefficients of 1/S and of g = D' / (-omega^2) (split: E + F, whole:
 * Q / S) from those of Q and E (see the header comment). */
static void nonlinear_series(const continuum_ws *w, const double *q, const double *e, int n,
                             double *g, double *inv_s)
{
    double q2[SERIES_TERMS], q3[SERIES_TERMS], u[SERIES_TERMS], s[SERIES_TERMS],
           one_s[SERIES_TERMS], den[SERIES_TERMS], one[SERIES_TERMS];
    series_mul(q, q, n, q2);
    series_mul(q2, q, n, q3);
    for (int k = 0; k < n; k++) {
        u[k] = w->b2 * q2[k] + (k == 0);      /* S^2 = 1 + b^2 Q^2 */
        q3[k] *= -(1 + w->b2);
        one[k] = k == 0;
    }
    series_sqrt(u, n, s);
    for (int k = 0; k < n; k++) one_s[k] = s[k] + (k == 0);
    series_div(one, s, n, inv_s);
    if (w->split) {
        series_mul(s, one_s, n, den);
        series_div(q3, den, n, g);
        for (int k = 0; k < n; k++) g[k] += e[k];
    } else {
        series_mul(q, inv_s, n, g);
    }
}

/* The state at the free end: R = Q = 1, z = 0. */
static void tip_state(const continuum_ws *w, double y[N_STATE])
{
    y[Y_D] = y[Y_E] = !w->split;
    y[Y_Z] = 0;
    y[Y_R0] = y[Y_Q0] = 1;
}

/* The start of the integration: sigma and the state there (the tip, or the series point for
 * m = 0). */
static double start_state(const continuum_ws *w, double y[N_STATE])
{
    double tip[N_STATE];
    tip_state(w, tip);
    for (int i = 0; i < N_STATE; i++) y[i] = tip[i];
    if (w->p.tip_mass > 0) return 0;
    /* Taylor coefficients of the scaled state at sigma = 0 */
    double c[N_STATE][SERIES_TERMS] = {{0}}, q[SERIES_TERMS], g[SERIES_TERMS],
           inv_s[SERIES_TERMS];
    for (int i = 0; i < N_STATE; i++) c[i][0] = tip[i];
    for (int n = 0; n + 1 < SERIES_TERMS; n++) {
        c[Y_R0][n + 1] = -w->w2 * c[Y_R0][n] / ((n + 1) * (n + 1));
        c[Y_Q0][n + 1] = c[Y_R0][n + 1] / (n + 2);
        for (int k = 0; k <= n; k++)
            q[k] = w->split ? c[Y_Q0][k] + w->beta * c[Y_E][k] : c[Y_E][k];
        nonlinear_series(w, q, c[Y_E], n + 1, g, inv_s);
        c[Y_D][n + 1] = -w->w2 * g[n] / (n + 1);
        c[Y_E][n + 1] = c[Y_D][n + 1] / (n + 2);
        c[Y_Z][n + 1] = inv_s[n] / (n + 1);
    }
    double s = START_SIGMA / (1 + w->w2);
    for (int i = 0; i < N_STATE; i++) {
        y[i] = 0;
        for (int n = SERIES_TERMS - 1; n >= 0; n--) y[i] = y[i] * s + c[i][n];
    }
    return s;
}
/* What one integration from the tip to the pivot records. */
typedef struct continuum_run {
    int crossings;           /* sign changes of r at the steps below the pivot */
    double r_pivot, q_pivot, z_pivot; /* R, Q, z at sigma = 1 */
    int locate;              /* also locate the nodes and the extrema: */
    int n_nodes;             /* nodes found; the last WHIRL_SHAPE_NODES of them (those nearest
                              * the pivot) in node_sigma[j % WHIRL_SHAPE_NODES], j = 0.. */
    double node_sigma[WHIRL_SHAPE_NODES];
    double max_abs_r;        /* max |r| over the tip and the extrema */
} continuum_run;

/* y(sigma) integrated from (sigma_a, y_a) with first step h. */
static int state_at(continuum_ws *w, double sigma_a, const double y_a[N_STATE], double h,
                    double sigma, double y[N_STATE])
{
    double t = sigma_a;
    for (int i = 0; i < N_STATE; i++) y[i] = y_a[i];
    if (sigma <= t) return GSL_SUCCESS;
    gsl_odeiv2_driver *driver = w->ode[w->split].driver;
    gsl_odeiv2_driver_reset_hstart(driver, h);
    return gsl_odeiv2_driver_apply(driver, &t, sigma, y);
}

/* The zero of v = R (c = SHAPE_R) or Q (c = SHAPE_Q) within the step [sigma_a, sigma_b] (v of
 * opposite signs at y_a and y_b), to tol in sigma, by Newton's method on v(sigma) with
 * dv/dsigma from the right-hand side, kept inside the shrinking bracket (bisection when a step
 * leaves it); y receives the state at the last point evaluated. */
static int locate_zero(continuum_ws *w, int c, double sigma_a, const double y_a[N_STATE],
                       double sigma_b, const double y_b[N_STATE], double tol, double *sigma,
                       double y[N_STATE])
{
    double lo = sigma_a, hi = sigma_b, h = sigma_b - sigma_a;
    double v_a = shape_value(w, c, y_a), v_b = shape_value(w, c, y_b);
    double s = sigma_a + h * v_a / (v_a - v_b); /* the secant's zero */
    for (int iter = 0; iter < REFINE_MAX; iter++) {
        double dy[N_STATE];
        int status = state_at(w, sigma_a, y_a, h, s, y);
        if (status != GSL_SUCCESS)
            return whirl_fail(status, "ODE integration failed locating a zero of the shape");
        w->ode[w->split].sys.function(s, y, dy, w);
        double v = shape_value(w, c, y), dv = shape_value(w, c, dy);
        if ((v > 0) == (v_a > 0)) lo = s;
        else hi = s;
        double next = dv != 0 ? s - v / dv : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (fabs(next - s) <= tol || v == 0) {
            *sigma = s;
            return GSL_SUCCESS;
        }
        s = next;
    }
    return whirl_fail(GSL_EMAXITER, "no convergence locating a zero of the shape (omega="
                      WHIRL_Q_RATE "%g, a=%g)", w->omega, w->a);
}

/* Integrates the shape with tip radius w->a from the tip to the pivot. */
static int integrate(continuum_ws *w, continuum_run *run)
{
    double y[N_STATE], y_prev[N_STATE];
    double sigma = start_state(w, y);
    double h = START_SIGMA / (1 + w->omega * w->omega);
    struct continuum_ode *o = &w->ode[w->split];
    gsl_odeiv2_step_reset(o->step);
    gsl_odeiv2_evolve_reset(o->evolve);
    run->crossings = 0;
    run->n_nodes = 0;
    run->max_abs_r = w->a;
    for (int n = 0; sigma < 1; n++) {
        if (n % 256 == 255 && whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request");
        if (n == STEP_MAX)
            return whirl_fail(GSL_EMAXITER, "more than %d ODE steps (omega=" WHIRL_Q_RATE "%g, "
                              "a=%g)", STEP_MAX, w->omega, w->a);
        double sigma_prev = sigma;
        for (int i = 0; i < N_STATE; i++) y_prev[i] = y[i];
        int status = gsl_odeiv2_evolve_apply(o->evolve, o->control, o->step, &o->sys, &sigma, 1,
                                             &h, y);
        if (status != GSL_SUCCESS)
            return whirl_fail(status, "ODE integration failed at sigma=%g (omega=" WHIRL_Q_RATE
                              "%g, a=%g)", sigma, w->omega, w->a);
        if (sigma < 1 && (shape_value(w, SHAPE_R, y) > 0) !=
                             (shape_value(w, SHAPE_R, y_prev) > 0)) {
            run->crossings++;
            if (run->locate) {
                double s_node, y_node[N_STATE];
                status = locate_zero(w, SHAPE_R, sigma_prev, y_prev, sigma, y, 1e-15, &s_node,
                                     y_node);
                if (status != GSL_SUCCESS) return status;
                run->node_sigma[run->n_nodes++ % WHIRL_SHAPE_NODES] = s_node;
            }
        }
        if (run->locate &&
            (shape_value(w, SHAPE_Q, y) > 0) != (shape_value(w, SHAPE_Q, y_prev) > 0)) {
            /* an extremum of r where the horizontal load q vanishes */
            double s_ext, y_ext[N_STATE];
            status = locate_zero(w, SHAPE_Q, sigma_prev, y_prev, sigma, y, 1e-9, &s_ext, y_ext);
            if (status != GSL_SUCCESS) return status;
            run->max_abs_r = fmax(run->max_abs_r, w->a * fabs(shape_value(w, SHAPE_R, y_ext)));
        }
    }
    /* split: the linear part at the pivot in closed form, R(1) to ~1e-16 + beta tol */
    run->r_pivot = w->split ? w->r0_pivot + w->beta * y[Y_D] : y[Y_D];
    run->q_pivot = w->split ? w->q0_pivot + w->beta * y[Y_E] : y[Y_E];
    run->z_pivot = y[Y_Z];
    return GSL_SUCCESS;
}

static int continuum_shot(void *ws, double a, double *residual, int *crossings)
{
    continuum_ws *w = ws;
    continuum_run run = {0};
    set_tip_radius(w, a);
    int status = integrate(w, &run);
    *residual = run.r_pivot;
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

/* critical_determinant for the root finder */
static int critical_value(double omega, void *params, double *value)
{
    *value = critical_determinant(omega, params);
    return GSL_SUCCESS;
}

/* The first n roots of critical_determinant (tip mass m > 0) in one sweep: sign changes are
 * bracketed once, in steps of 1/32 of the asymptotic spacing sp = pi (sqrt(1+m) + sqrt(m)) / 2
 * (the phase x1 - x0 = 2 omega (sqrt(1+m) - sqrt(m)) of the Bessel functions grows by pi per
 * root), from omega = 0.5 (omega_1 lies in (1, j_{0,1}/2]: a pendulum for a heavy tip, the
 * chain without) in steps of at most 0.05 up to the first root, and each bracket is refined by
 * Brent's method. No root is missed: consecutive roots are at least 0.76 sp apart (measured
 * for m = 1e-12 .. 1e8, modes 1..3183; the smallest, 0.768 sp, near m = 0.5 between modes 1
 * and 2), 24 scan steps, and the count is checked against the roots' asymptotic density: the
 * k-th root lies in ((k - 1) sp, (k - 0.23) sp) (measured over the same range), so a root
 * missed or counted twice moves every later one by a whole sp out of the window
 * ((k - 1.1) sp, (k - 0.1) sp) tested here. Writes omega[0..n-1] (omega may be NULL) and the
 * n-th root to *last. Polls the stop request every 4096 evaluations. */
static int critical_sweep(double m, int n, double *omega, double *last)
{
    double spacing = 0.5 * M_PI * (sqrt(1 + m) + sqrt(m));
    /* Brent's estimate is taken after REFINE_MAX iterations, or a failed one, as it is */
    const whirl_root_opts refine = {0, 2 * DBL_EPSILON, REFINE_MAX, 0, 0, 0};
    int status = GSL_SUCCESS, found = 0;
    double lo = 0.5, f_lo = critical_determinant(lo, &m);
    /* bounded: n roots need about 32 n steps (40 n + 80 with the margin of the first) */
    for (long iter = 0; found < n; iter++) {
        if (iter > 40L * (n + 2)) {
            status = whirl_fail(GSL_EFAILED, "critical rate of mode %d with tip mass %g not "
                                "found", found + 1, m);
            break;
        }
        if (iter % 4096 == 4095 && whirl_stop_requested()) {
            status = whirl_fail(WHIRL_EINTERRUPTED, "critical rates with tip mass %g "
                                "interrupted at mode %d", m, found + 1);
            break;
        }
        double step = found == 0 ? fmin(0.05, spacing / 32) : spacing / 32;
        double hi = lo + step, f_hi = critical_determinant(hi, &m);
        if ((f_lo > 0) != (f_hi > 0)) {
            whirl_root r;
            if (whirl_root_brent(critical_value, &m, lo, hi, &refine, &r) == GSL_ENOMEM) {
                status = GSL_ENOMEM;
                break;
            }
            double root = r.root, k = ++found;
            if (root < (k - 1.1) * spacing || root > (k - 0.1) * spacing) {
                status = whirl_fail(GSL_EFAILED, "critical rate %d with tip mass %g at omega="
                                    WHIRL_Q_RATE "%g is off the roots' density (%g per unit "
                                    "omega): a root missed or counted twice", found, m, root,
                                    1 / spacing);
                break;
            }
            if (omega) omega[found - 1] = root;
            *last = root;
        }
        lo = hi, f_lo = f_hi;
    }
    return status;
}

/* The arguments of the critical rates: what (mode, number of modes) = k in
 * 1..WHIRL_CONTINUUM_MODE_MAX, a valid tip mass. */
static int critical_args(long k, const char *what, double tip_mass)
{
    if (k < 1 || k > WHIRL_CONTINUUM_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "%s must be between 1 and %d, got %ld", what,
                          WHIRL_CONTINUUM_MODE_MAX, k);
    return whirl_check_tip_mass(tip_mass);
}

int whirl_continuum_critical(int mode, double tip_mass, double *omega)
{
    int status = critical_args(mode, "mode", tip_mass);
    if (status != GSL_SUCCESS) return status;
    if (tip_mass == 0) {
        *omega = 0.5 * gsl_sf_bessel_zero_J0((unsigned)mode);
        return GSL_SUCCESS;
    }
    return critical_sweep(tip_mass, mode, NULL, omega);
}

int whirl_continuum_critical_rates(size_t n, double tip_mass, double *omega)
{
    int status = critical_args(n > (size_t)LONG_MAX ? LONG_MAX : (long)n, "the number of modes",
                               tip_mass);
    if (status != GSL_SUCCESS) return status;
    if (tip_mass > 0) return critical_sweep(tip_mass, (int)n, omega, &omega[n - 1]);
    for (size_t k = 1; k <= n; k++) omega[k - 1] = 0.5 * gsl_sf_bessel_zero_J0((unsigned)k);
    return GSL_SUCCESS;
}

static int continuum_solve_ws(void *ws, double omega, int mode, double tip_r_guess,
                              whirl_shape_info *info)
{
    continuum_ws *w = ws;
    int status = whirl_steady_check_args(omega, mode, WHIRL_CONTINUUM_MODE_MAX);
    if (status != GSL_SUCCESS) return status;
    if ((status = set_rate(w, omega)) != GSL_SUCCESS) return status;
    double a;
    status = whirl_steady_shoot_root(continuum_shot, w, mode, 1, tip_r_guess, &a);
    if (status == GSL_EDOM) {
        double omega_k;
        if (whirl_continuum_critical(mode, w->p.tip_mass, &omega_k) != GSL_SUCCESS)
            return GSL_EDOM;
        return whirl_steady_fail_missing(mode, omega, omega_k);
    }
    if (status != GSL_SUCCESS) return status;
    continuum_run run = {0};
    run.locate = 1;
    set_tip_radius(w, a);
    if ((status = integrate(w, &run)) != GSL_SUCCESS) return status;
    if (run.n_nodes != mode - 1)
        return whirl_fail(GSL_EFAILED, "mode %d at omega=" WHIRL_Q_RATE "%g: found %d axis "
                          "crossings", mode, omega, run.n_nodes);
    info->omega = omega;
    info->mode = mode;
    info->tip_r = a;
    info->max_r = run.max_abs_r;
    info->top_tension = (1 + w->p.tip_mass) * sqrt(1 + w->b2 * run.q_pivot * run.q_pivot);
    info->depth = run.z_pivot;
    info->n_crossings = run.n_nodes;
    /* the first nodes from the pivot are the last found from the tip */
    for (int j = 0; j < run.n_nodes && j < WHIRL_SHAPE_NODES; j++)
        info->crossing_s[j] = 1 - run.node_sigma[(run.n_nodes - 1 - j) % WHIRL_SHAPE_NODES];
    return whirl_steady_check_info(info);
}


int whirl_continuum_solve_tol(double omega, int mode, double tip_mass, double tip_r_guess,
                              double tol, whirl_shape_info *info)
{
    int status = whirl_check_tip_mass(tip_mass);
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
    int status = whirl_check_tip_mass(tip_mass);
    if (status != GSL_SUCCESS) return status;
    if ((status = check_rate(omega)) != GSL_SUCCESS) return status;
    if (!(isfinite(tip_r) && tip_r > 0 && tip_r <= 1))
        return whirl_fail(GSL_EINVAL, "tip radius must be in (0, 1], got %g", tip_r);
    if (npts < 2) return whirl_fail(GSL_EINVAL, "need at least 2 points, got %zu", npts);
    continuum_params p = {tip_mass, WHIRL_CONTINUUM_TOL};
    continuum_ws *w = continuum_ws_alloc(&p);
    if (w == NULL) return GSL_ENOMEM;
    if ((status = set_rate(w, omega)) != GSL_SUCCESS) {
        continuum_ws_free(w);
        return status;
    }
    set_tip_radius(w, tip_r);
    double y_tip[N_STATE], y0[N_STATE], y[N_STATE];
    tip_state(w, y_tip);
    double sigma0 = start_state(w, y0);
    double t = sigma0;
    for (int i = 0; i < N_STATE; i++) y[i] = y0[i];
    gsl_odeiv2_driver *driver = w->ode[w->split].driver;
    gsl_odeiv2_driver_reset(driver);
    /* from the free end (j = npts - 1, sigma = 0) up to the pivot (j = 0, sigma = 1) */
    for (size_t k = 0; k < npts && status == GSL_SUCCESS; k++) {
        size_t j = npts - 1 - k;
        double sigma = (double)k / (double)(npts - 1);
        if (k % 1024 == 1023 && whirl_stop_requested()) { /* 10^7 points take seconds */
            status = whirl_fail(WHIRL_EINTERRUPTED, "stopped after %zu of %zu points", k, npts);
            break;
        }
        if (k == npts - 1) sigma = 1;
        double yj[N_STATE];
        if (sigma <= sigma0) {
            /* within the series start: linear between the tip and sigma_0 (error ~ sigma_0^2) */
            double f = sigma0 > 0 ? sigma / sigma0 : 0;
            for (int i = 0; i < N_STATE; i++) yj[i] = y_tip[i] + f * (y0[i] - y_tip[i]);
        } else {
            status = gsl_odeiv2_driver_apply(driver, &t, sigma, y);
            for (int i = 0; i < N_STATE; i++) yj[i] = y[i];
        }
        double q = shape_value(w, SHAPE_Q, yj);
        s[j] = 1 - sigma;
        r[j] = tip_r * shape_value(w, SHAPE_R, yj);
        z[j] = yj[Y_Z];
        tension[j] = (sigma + tip_mass) * sqrt(1 + w->b2 * q * q);
    }
    if (status != GSL_SUCCESS && status != WHIRL_EINTERRUPTED)
        status = whirl_fail(status, "ODE integration failed sampling the shape (omega=" WHIRL_Q_RATE
                            "%g)", omega);
    else
        for (size_t j = npts; j-- > 0;) z[j] -= z[0]; /* heights relative to the pivot */
    if (status == GSL_SUCCESS) status = whirl_steady_check_samples(omega, npts, r, z, tension);
    continuum_ws_free(w);
    return status;
}

int whirl_continuum_branch(int mode, double tip_mass, size_t n, const double *omega,
                           whirl_shape_info *info, int *exists)
{
    int status = whirl_check_tip_mass(tip_mass);
    if (status != GSL_SUCCESS) return status;
    continuum_params p = {tip_mass, WHIRL_CONTINUUM_TOL};
    steady_model m = {continuum_ws_alloc, continuum_ws_free, continuum_solve_ws, &p};
    return whirl_steady_branch(&m, mode, n, omega, info, exists);
}

int whirl_continuum_shots(double omega, double tip_mass, size_t n, const double *a,
                          double *residual, int *crossings)
{
    int status = whirl_check_tip_mass(tip_mass);
    if (status != GSL_SUCCESS) return status;
    if ((status = check_rate(omega)) != GSL_SUCCESS) return status;
    continuum_params p = {tip_mass, WHIRL_CONTINUUM_TOL};
    continuum_ws *w = continuum_ws_alloc(&p);
    if (w == NULL) return GSL_ENOMEM;
    status = set_rate(w, omega);
    for (size_t i = 0; i < n && status == GSL_SUCCESS; i++) {
        if (whirl_stop_requested())
            status = whirl_fail(WHIRL_EINTERRUPTED, "stopped after %zu of %zu shots", i, n);
        else if (!(isfinite(a[i]) && a[i] > 0 && a[i] <= 1))
            status = whirl_fail(GSL_EINVAL, "tip radius must be in (0, 1], got %g", a[i]);
        else
            status = continuum_shot(w, a[i], &residual[i], &crossings[i]);
    }
    continuum_ws_free(w);
    return status;
}
