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
 * tip mass j_{0,k}/2; with a tip mass the k-th root of the linearised problem. */
int whirl_continuum_critical(int mode, double tip_mass, double *omega);

/* The steady shape of mode k at omega. tip_r_guess > 0 seeds the root search (continuation);
 * 0 lets the solver bracket the root itself. GSL_EDOM (message naming omega_k) if mode k does not
 * exist at omega. Accuracy: tip_r, top_tension and depth to 1e-10 relative or better. */
int whirl_continuum_solve(double omega, int mode, double tip_mass, double tip_r_guess,
                          whirl_shape_info *info);

/* Samples the shape with tip radius tip_r (from whirl_continuum_solve) at npts >= 2 arclengths
 * equally spaced from the pivot (s = 0) to the free end (s = 1): r, z and the tension there. */
int whirl_continuum_sample(double omega, double tip_mass, double tip_r, size_t npts, double *s,
                           double *r, double *z, double *tension);

/* Follows mode k over the rates omega[0..n-1] (any order, continuation from one to the next):
 * exists[j] = 1 and info[j] filled where the mode exists, exists[j] = 0 where it does not. */
int whirl_continuum_branch(int mode, double tip_mass, size_t n, const double *omega,
                           whirl_shape_info *info, int *exists);

/* ---- N-link chain ---- */

/* The first nmodes (<= c->n) linear critical rates of the chain, ascending: the normal-mode
 * frequencies of the hanging chain (a symmetric tridiagonal eigenproblem). */
int whirl_nlink_critical(const whirl_chain *c, size_t nmodes, double *omega);

/* The exact relative equilibrium of mode k at omega: the force balance of every mass holds to
 * round-off. tip_r_guess as for whirl_continuum_solve. GSL_EDOM if mode k does not exist. */
int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, double tip_r_guess,
                      whirl_shape_info *info);

/* The nodes of the shape with tip radius tip_r: r[i], z[i] of mass i (i = 0: the pivot, which
 * lands on the axis only for a solution) and tension[i] of link i (tension[0] = tension[1]),
 * arrays of c->n + 1. */
int whirl_nlink_positions(const whirl_chain *c, double omega, double tip_r, double *r, double *z,
                          double *tension);

/* Follows mode k over omega[0..n-1] as whirl_continuum_branch does. */
int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists);

#endif
