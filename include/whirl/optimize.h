/* whirl: optimisation with NLopt.
 *
 * 1. The stable (mode-1) steady shape of the N-link chain as the minimum of the potential of the
 *    co-rotating frame, an independent check of the shooting solver (whirl_nlink_solve):
 *        V(theta) = sum_i m_i (g z_i - omega^2 x_i^2 / 2),
 *        x_i = sum_{j<=i} l_j sin(theta_j),  z_i = -sum_{j<=i} l_j cos(theta_j),
 *    over the planar link angles theta_j (from the downward vertical, in the x-z plane).
 *    Steady shapes are the stationary points of V; mode k has k-1 negative directions of the
 *    Hessian in the plane (the hanging chain below omega_1 and mode 1 above it are the minima;
 *    modes >= 2 are saddles that a minimiser does not find).
 * 2. The rotation rate (and mode) that best explains a measured shape: least squares of the
 *    distances of the measured points to the model curve, over omega, for each mode.
 *
 * Status codes and messages as in whirl/common.h. */
#ifndef WHIRL_OPTIMIZE_H
#define WHIRL_OPTIMIZE_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/steady.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the co-rotating potential of the planar N-link chain ---- */

/* V(theta) of the chain c (theta: c->n link angles [rad]); if grad != NULL also dV/dtheta_j
 * (n values, the analytic gradient, O(n)).
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)]
 * @param theta the link angles from the downward vertical [rad], c->n
 * @param grad out, or NULL: dV/dtheta_j [M g L], c->n
 * @return V [M g L]
 */
WHIRL_API double whirl_potential(const whirl_chain *c, double omega, const double *theta,
                                 double *grad);

/* The analytic Hessian d2V/dtheta_j dtheta_k into hess (n x n, row-major). Always succeeds.
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)]
 * @param theta the link angles [rad], c->n
 * @param hess out: the Hessian [M g L], c->n x c->n, row-major
 */
WHIRL_API void whirl_potential_hessian(const whirl_chain *c, double omega, const double *theta,
                                       double *hess);

/* The shape of the angles theta: r[i], z[i] of node i (i = 0 the pivot, arrays of n + 1),
 * tension[i] of link i from the force balance of the masses below it, projected on the link
 * (tension[0] = tension[1]), and its summary (mode = 1 + the crossings of
 * whirl_nlink_node_arclengths). If the free end has r < 0 the shape is mirrored so that it has
 * r > 0. r and z are required; tension and info may be NULL (then info->top_tension is NaN).
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)]
 * @param theta the link angles [rad], c->n
 * @param r out: the nodes' distances from the axis [L], c->n + 1
 * @param z out: the nodes' heights, 0 at the pivot [L], c->n + 1
 * @param tension out, or NULL: the links' tensions [M g], c->n + 1
 * @param info out, or NULL: the shape's summary
 */
WHIRL_API void whirl_angles_shape(const whirl_chain *c, double omega, const double *theta,
                                  double *r, double *z, double *tension, whirl_shape_info *info);

/* Options of whirl_minimize_shape. */
typedef struct whirl_minimize_options {
    const char *algorithm; /* NLopt algorithm name, e.g. "LD_LBFGS" (default when NULL),
                            * "LN_BOBYQA": anything nlopt_algorithm_from_string knows */
    int max_evaluations;   /* cap on NLopt's evaluations of V; <= 0: 100000 */
    int polish;            /* != 0: finish with Newton steps on the analytic Hessian (default 1
                            * in whirl_minimize_options_defaults) */
    /* called on the caller's thread about every 20 ms while NLopt runs, with the evaluations
     * of V so far and the cap (for a progress display; NULL: none, the default) */
    void (*progress)(void *data, int evaluations, int max_evaluations);
    void *progress_data; /* passed to progress */
} whirl_minimize_options;

/* What the minimisation did. */
typedef struct whirl_minimize_stats {
    int evaluations;      /* evaluations of V (and its gradient) by NLopt */
    int newton_steps;     /* accepted Newton steps of the polish */
    int nlopt_result;     /* NLopt's return code (nlopt_result) */
    double potential;     /* V at the result [M g L] */
    double gradient_norm; /* max_j |dV/dtheta_j| at the result [M g L] */
    double min_curvature; /* smallest eigenvalue of the Hessian at the result (> 0: a minimum) */
} whirl_minimize_stats;

/* Defaults: LD_LBFGS, 100000 evaluations, polish on.
 * @return the defaults
 */
WHIRL_API whirl_minimize_options whirl_minimize_options_defaults(void);

/* The NLopt algorithm called name (as nlopt_algorithm_from_string), into *algorithm (an
 * nlopt_algorithm). GSL_EINVAL naming it if unknown.
 * @param name the algorithm's name, e.g. "LD_LBFGS" (NULL: unknown)
 * @param algorithm out: the nlopt_algorithm (untouched on failure)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message listing the local algorithms
 */
WHIRL_API int whirl_minimize_algorithm(const char *name, int *algorithm);

/* Minimises V over the angles from theta (n values; NULL: a small uniform tilt), writing the
 * minimum to theta_out (n values). GSL_EDOM if omega is at or below the chain's first critical
 * rate (the hanging chain theta = 0 is then the minimum: there is no mode-1 shape), GSL_EINVAL
 * for bad arguments or an unknown algorithm, GSL_EFAILED if NLopt fails or the result is not a
 * minimum. stats may be NULL.
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)], above the chain's first critical rate
 * @param opt the minimiser's options (whirl_minimize_options_defaults), or NULL for them
 * @param theta the starting link angles [rad], c->n, or NULL for a small uniform tilt
 * @param theta_out out: the minimum's link angles [rad], c->n
 * @param stats out: the minimiser's work, or NULL
 * @return GSL_SUCCESS, GSL_EDOM at or below the first critical rate, GSL_EINVAL, or GSL_EFAILED
 */
WHIRL_API int whirl_minimize_shape(const whirl_chain *c, double omega,
                                   const whirl_minimize_options *opt, const double *theta,
                                   double *theta_out, whirl_minimize_stats *stats);

/* ---- fitting omega and the mode to a measured shape ---- */

/* The model of a fit. */
typedef struct whirl_fit_model {
    size_t links;     /* 0: the continuous chain; N >= 1: the uniform N-link chain */
    double tip_mass;  /* point mass at the free end [M], >= 0 (default 0) */
    double omega_max; /* upper bound of omega [sqrt(g/L)] (default 50) */
    size_t samples;   /* points of the continuum's model polyline (default 4001) */
} whirl_fit_model;

/* The largest models a fit takes: every evaluation of the fit solves the model's shape (work
 * and memory ~ links, ~ samples) and the N-link model first finds its N critical rates. */
#define WHIRL_FIT_LINKS_MAX 2000
#define WHIRL_FIT_SAMPLES_MAX 1000000

/* Defaults: the continuum, no tip mass, omega_max 50, 4001 samples.
 * @return the defaults
 */
WHIRL_API whirl_fit_model whirl_fit_model_defaults(void);

/* The result of a fit. */
typedef struct whirl_fit_result {
    double omega;        /* best rate [sqrt(g/L)] */
    double omega_err;    /* its standard uncertainty (Gauss-Newton, see whirl_fit) */
    int mode;            /* the mode fitted */
    double rms_residual; /* sqrt(mean squared distance of the points to the model) [L] */
    int mirrored;        /* 1 if the points lie on the side r < 0 of the free end */
    int evaluations;     /* model shapes computed */
    int failures;        /* of which the solver could not compute (skipped as no shape) */
} whirl_fit_result;

/* Signed distances (positive on one side) of the points (r[i], z[i]), i < n, dimensionless
 * (lengths / L), to the curve of mode k at omega (mirrored in r if mirrored != 0), into resid.
 * GSL_EDOM if the mode does not exist at omega.
 * @param m the model
 * @param omega the rate [sqrt(g/L)]
 * @param mode the mode k >= 1
 * @param mirrored non-zero: the curve mirrored in r
 * @param n the points (as whirl_fit checks them)
 * @param r the points' distances from the axis [L], n
 * @param z their heights [L], n
 * @param resid out: the signed distances [L], n
 * @return GSL_SUCCESS, GSL_EINVAL on a bad model or points, GSL_EDOM if the mode does not exist at
 *     omega, or the solver's failure; with a message
 */
WHIRL_API int whirl_fit_residuals(const whirl_fit_model *m, double omega, int mode, int mirrored,
                                  size_t n, const double *r, const double *z, double *resid);

/* Least squares over omega in (omega_k, omega_max] of the distances of the n points to the
 * curve of mode k (mode >= 1), or (mode = 0) of every mode from 1 to c + 3, c the sign changes
 * of r down the points sorted by height (|r| below 5% of the largest ignored), keeping the one
 * of least residual (modes with no shape below omega_max, or whose fit fails, are skipped).
 * For each mode: a scan of omega on a logarithmic grid above omega_k, NLopt's LN_BOBYQA on the
 * bracket of the best point, then Gauss-Newton steps.
 * omega_err = sqrt(s^2 / J^T J) with J = d(resid)/d(omega) by central differences and
 * s^2 = SSR / (n - 1): the linearised standard error, which assumes independent errors of equal
 * variance normal to the curve (validated against Monte-Carlo scatter in tests/unit/optimize/test_optimize.c);
 * it means little when omega ends on a bound. Needs 3 to 20000 finite points, at least 3 of
 * them distinct and off the axis (|r| > 1e-9) (GSL_EINVAL otherwise); GSL_EFAILED when the
 * residuals do not change with omega (an ill-conditioned fit). GSL_EDOM if no mode has a shape
 * in the range. WHIRL_EINTERRUPTED once a stop is requested (polled every 1024 distances).
 * result->rms_residual says how well it fits; judging it is up to the caller.
 * @param m the model (whirl_fit_model_defaults: the continuum)
 * @param n how many points, 3..20000
 * @param r the points' distances from the axis [L], n
 * @param z their heights [L], n
 * @param mode the mode k to fit, or 0 to try modes 1 to c + 3 and keep the best
 * @param result out: the rate, its uncertainty, the mode and the RMS residual
 * @return GSL_SUCCESS, GSL_EINVAL on bad points, GSL_EFAILED on an ill-conditioned fit, GSL_EDOM
 *     if no mode has a shape in the range, WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_fit(const whirl_fit_model *m, size_t n, const double *r, const double *z,
                        int mode, whirl_fit_result *result);

/* Progress of a fit: called after every evaluation of the model (one shape, its distances to the
 * points), with the mode being fitted, the range of modes tried (first..last) and the
 * evaluations so far (all modes). For a progress display; it must not call the fit. */
typedef void (*whirl_fit_progress_fn)(void *data, int mode, int first, int last, int evaluations);

/* whirl_fit reporting its progress to progress(data, ...) (NULL: none).
 * @param m the model (whirl_fit_model_defaults: the continuum)
 * @param n how many points, 3..20000
 * @param r the points' distances from the axis [L], n
 * @param z their heights [L], n
 * @param mode the mode k to fit, or 0 to try modes 1 to c + 3 and keep the best
 * @param progress called after every evaluation, or NULL: none
 * @param data passed to progress
 * @param result out: the rate, its uncertainty, the mode and the RMS residual
 * @return as whirl_fit
 */
WHIRL_API int whirl_fit_observed(const whirl_fit_model *m, size_t n, const double *r,
                                 const double *z, int mode, whirl_fit_progress_fn progress,
                                 void *data, whirl_fit_result *result);

#ifdef __cplusplus
}
#endif

#endif
