/* whirl: stationary shapes of a chain spun at a constant rate omega about the vertical axis.
 *
 * In the frame co-rotating at omega a steady shape is planar: r is the signed distance from the
 * axis in that plane (the free end at r > 0), z <= 0 the height below the pivot, s the arclength
 * measured from the pivot (s = 0) to the free end. Mode k has the pivot plus k-1 crossings of
 * the axis. Two models:
 *  - the continuous uniform chain (length 1, mass 1, g = 1) with an optional point mass tip_mass
 *    (in units of the chain's mass) at its free end;
 *  - the N-link chain (whirl_chain, any lengths and masses), whose steady shapes are its exact
 *    relative equilibria.
 * Both are found by shooting on the tip radius and root-finding on the pivot's radius. */
#ifndef WHIRL_STEADY_H
#define WHIRL_STEADY_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"

/* The summary of one steady shape (the comment line of `whirl shape`). */
typedef struct whirl_shape_info {
    double omega;       /* rotation rate [sqrt(g/L)] */
    int mode;           /* node count k, 1 <= k <= WHIRL_MODE_MAX */
    double tip_r;       /* distance of the free end from the axis [L], > 0 */
    double max_r;       /* max over the chain of |r| [L] */
    double top_tension; /* tension at the pivot [M g] */
    double depth;       /* height of the pivot above the free end [L] */
    int n_nodes;        /* axis crossings below the pivot: mode - 1 */
    double node_s[WHIRL_MODE_MAX]; /* their arclengths from the pivot [L], increasing */
} whirl_shape_info;

/* ---- continuous chain ---- */

/* The linear critical rate of mode k (>= 1) where it bifurcates from the hanging chain: with no
 * tip mass j_{0,k}/2; with a tip mass the k-th root of the linearised problem (Bessel J0/Y0
 * determinant). GSL_EINVAL on a bad mode or tip mass. */
WHIRL_API int whirl_continuum_critical(int mode, double tip_mass, double *omega);

/* The steady shape of mode k at omega. tip_r_guess > 0 seeds the root search (continuation);
 * 0 lets the solver bracket the root itself. GSL_EDOM (message naming omega_k) if mode k does not
 * exist at omega; GSL_EINVAL on omega <= 0 or non-finite, mode outside 1..WHIRL_MODE_MAX or a
 * negative tip mass. Accuracy: tip_r, top_tension and depth to 1e-10 relative or better (about
 * 1e-13 measured). Near the bifurcation tip_r ~ sqrt(omega - omega_k) is ill-conditioned
 * (d ln tip_r / d ln omega = 1 / (2 eps), eps = omega / omega_k - 1): the linear part of the
 * residual is evaluated in closed form, so the error is that of one rounding of omega, about
 * 1e-16 / eps (2e-11 at eps = 1e-6 without a tip mass); with a tip mass the Bessel combination
 * of the linear part loses digits (up to 1.3e-10 for m = 0.48, 3.4e-10 for m = 3.7 at eps = 1e-6,
 * modes 1-6). */
WHIRL_API int whirl_continuum_solve(double omega, int mode, double tip_mass, double tip_r_guess,
                                    whirl_shape_info *info);

/* The highest rate of the continuum solvers: beyond about 8000 the shooting's ODE needs more
 * than its cap of 100000 steps per shot (the shape varies on a scale ~ 1/omega); higher rates are
 * refused with GSL_EINVAL (the N-link chain has no such limit). */
#define WHIRL_CONTINUUM_OMEGA_MAX 5000.0

/* The ODE tolerance (absolute and relative, on order-one scaled variables) of the continuum. */
#define WHIRL_CONTINUUM_TOL 1e-13

/* whirl_continuum_solve with the ODE tolerance tol in (0, 1) instead of WHIRL_CONTINUUM_TOL:
 * for convergence studies. */
WHIRL_API int whirl_continuum_solve_tol(double omega, int mode, double tip_mass, double tip_r_guess,
                                        double tol, whirl_shape_info *info);

/* Samples the shape with tip radius tip_r in (0, 1] (from whirl_continuum_solve) at npts >= 2
 * arclengths equally spaced from the pivot (s = 0) to the free end (s = 1): r, z (0 at the pivot)
 * and the tension there; arrays of npts. For any tip_r it is the shot of the shooting method: r
 * at the pivot (r[0]) vanishes only for a solution. */
WHIRL_API int whirl_continuum_sample(double omega, double tip_mass, double tip_r, size_t npts,
                                     double *s, double *r, double *z, double *tension);

/* Follows mode k over the rates omega[0..n-1] (any order, continuation from one to the next):
 * exists[j] = 1 and info[j] filled where the mode exists, exists[j] = 0 where it does not. The
 * rates are cut into contiguous blocks followed in parallel on the OpenMP threads (serially when
 * called from inside a parallel region). */
WHIRL_API int whirl_continuum_branch(int mode, double tip_mass, size_t n, const double *omega,
                                     whirl_shape_info *info, int *exists);

/* ---- N-link chain ---- */

/* The first nmodes (<= c->n) linear critical rates of the chain, ascending: the normal-mode
 * frequencies of the hanging chain (a symmetric tridiagonal eigenproblem). */
WHIRL_API int whirl_nlink_critical(const whirl_chain *c, size_t nmodes, double *omega);

/* The exact relative equilibrium of mode k at omega: the force balance of every mass holds to
 * round-off. tip_r_guess as for whirl_continuum_solve. GSL_EDOM if mode k does not exist (omega
 * <= omega_k, or k > c->n). A coarse chain at a high rate (e.g. N = 100 at omega = 30) can have
 * several equilibria with k - 1 crossings: without a seed the one with the smallest tip radius
 * is returned (near omega_k the branch born there), with a seed the one nearest the seed. */
WHIRL_API int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, double tip_r_guess,
                                whirl_shape_info *info);

/* The nodes of the shape with tip radius tip_r: r[i], z[i] of mass i (i = 0: the pivot, which
 * lands on the axis only for a solution) and tension[i] of link i (tension[0] = tension[1]),
 * arrays of c->n + 1. */
WHIRL_API int whirl_nlink_positions(const whirl_chain *c, double omega, double tip_r, double *r,
                                    double *z, double *tension);

/* Follows mode k over omega[0..n-1] as whirl_continuum_branch does (the chain is only read). */
WHIRL_API int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                                 whirl_shape_info *info, int *exists);

#endif
