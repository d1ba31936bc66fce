/* Internal: the logic the continuous and the N-link steady-shape solvers share.
 *
 * Both are shooting problems in the tip radius a: from the free end (r = a) up to the pivot,
 * with residual(a) = r(pivot; a) / a and crossings(a) = the number of sign changes of r from the
 * free end to the pivot, the pivot's own sign included (a shot returns those strictly below the
 * pivot; the pivot's flip follows from the residual's sign). For small a the shape is the
 * linear one and crossings equals the number of critical rates below omega; as a grows the zeros
 * leave the chain through the pivot one at a time (Kolodner 1955), and the k-th leaves at the
 * mode-k root: crossings(a) >= k below it and <= k - 1 above it. */
#ifndef WHIRL_STEADY_INTERNAL_H
#define WHIRL_STEADY_INTERNAL_H

#include <float.h>
#include <stddef.h>

#include "whirl/steady.h"

/* One shot with tip radius a: residual r(pivot)/a, and crossings = the sign changes of r from
 * the free end down to (not including) the pivot. */
typedef int (*steady_shot_fn)(void *ws, double a, double *residual, int *crossings);

/* The mode-k root a in (0, a_max) of a shooting problem: brackets it by the crossing count,
 * then polishes the residual's root with Brent's method to round-off. With guess > 0 the bracket
 * grows around the guess (continuation). Otherwise it bisects the whole range (crossings known
 * to decrease with a: the continuum, its one caller). GSL_EDOM if
 * crossings at the smallest radius tried (1e-9 a_max) is below mode: mode k does not exist at
 * this rate. */
int whirl_steady_shoot_root(steady_shot_fn shot, void *ws, int mode, double a_max, double guess,
                            double *a);

/* The linear verdict of an N-link equilibrium, given by the module above (the stability module's
 * whirl_equilibria_find: the steady module does not depend on it): from the nodes r, z (N + 1)
 * of the shape at the search's rate, its growth and index; a GSL status. */
typedef struct whirl_equilibria_verdict {
    int (*judge)(void *ctx, const double *r, const double *z, double *growth, int *index);
    void *ctx;
} whirl_equilibria_verdict;

/* whirl_equilibria_find_progress (whirl/steady.h) with the verdicts of verdict (NULL: none;
 * eig_growth and index left 0). */
int whirl_equilibria_search(const whirl_chain *c, double tip_mass, double omega,
                            const whirl_equilibria_params *params,
                            const whirl_equilibria_verdict *verdict,
                            whirl_equilibria_progress_fn progress, void *ctx,
                            whirl_equilibria **out);

/* A model for branch following: a workspace per thread and a solve with a seed. */
typedef struct steady_model {
    void *(*ws_alloc)(const void *params);
    void (*ws_free)(void *ws);
    /* GSL_EDOM when the mode does not exist at omega (not an error for a branch) */
    int (*solve)(void *ws, double omega, int mode, double tip_r_guess, whirl_shape_info *info);
    const void *params;
} steady_model;

/* Follows mode over omega[0..n-1] by continuation (linear prediction from the two previous
 * solutions); the rates are split into contiguous blocks run on the OpenMP threads. */
int whirl_steady_branch(const steady_model *m, int mode, size_t n, const double *omega,
                        whirl_shape_info *info, int *exists);

/* The checks every solver starts with: omega > 0 and finite, 1 <= mode <= mode_max
 * (WHIRL_CONTINUUM_MODE_MAX for the continuum; INT_MAX for the N-link chain, which checks mode <= N
 * itself: GSL_EDOM). */
int whirl_steady_check_args(double omega, int mode, int mode_max);
/* GSL_SUCCESS if every number of the solved shape is finite, else GSL_ERANGE naming the first
 * that is not (a rate or tip mass too large for doubles). */
int whirl_steady_check_info(const whirl_shape_info *info);
/* The same for n samples of a shape (any of the arrays may be NULL). */
int whirl_steady_check_samples(double omega, size_t n, const double *r, const double *z,
                               const double *tension);

/* Node count k to the message of a missing mode: "mode k does not exist at omega=W (it
 * bifurcates at omega_k=...)" with GSL_EDOM. */
int whirl_steady_fail_missing(int mode, double omega, double omega_k);

/* The pivot-end shot of whirl_nlink_pivot_residual without its argument checks, with the
 * derivative of the residual with respect to theta_1 in *d_residual, the link angles from
 * the downward vertical in theta[0..N-1] and their tangents H_i / V_i in slope[0..N-1] with
 * the derivatives of those with respect to theta_1 in slope_d (each may be NULL). */
int whirl_nlink_pivot_shot(const whirl_chain *c, double omega, double theta_1, double *residual,
                           double *d_residual, double *tip_r, double *theta, double *slope,
                           double *slope_d);

/* The shot from the tip (src/nlink.c's recursion) at tip radius a, without argument checks:
 * G = r_0 / |r| (|r|^2 = sum_{i=0}^N r_i^2) and dG/da, the tangents of the link angles
 * H_i / V_i in slope[0..N-1] and their derivatives with respect to a in slope_a (forward
 * differentiation, exact). G is the residual of whirl_nlink_residual. */
void whirl_nlink_tip_shot(const whirl_chain *c, double omega, double a, double *g, double *g_a,
                          double *slope, double *slope_a);

/* Quadruple precision: __float128 (arithmetic in libgcc, which gcc and clang link) where long
 * double is shorter (x86-64: 64 bits of mantissa), else long double (113 bits on aarch64). */
#if defined(__SIZEOF_FLOAT128__) && LDBL_MANT_DIG < 113
__extension__ typedef __float128 nlink_quad;
#else
typedef long double nlink_quad;
#endif

/* The tip shot's residual G at tip radius a, and the pivot shot's H_{N+1} / H_1 at tan(theta_1)
 * = tan_1, in quadruple precision, with the link angles from the downward vertical in
 * theta[0..N-1] (may be NULL); no argument checks. */
nlink_quad whirl_nlink_tip_shot_quad(const whirl_chain *c, double omega, nlink_quad a,
                                     double *theta);
nlink_quad whirl_nlink_pivot_shot_quad(const whirl_chain *c, double omega, nlink_quad tan_1,
                                       double *theta);

/* The summary of the N-link shape with nodes r, z (pivot first, z relative to the pivot) and
 * link tensions (tension[i] of link i), as whirl_nlink_info. */
void whirl_nlink_info_nodes(const whirl_chain *c, const double *r, const double *z,
                            const double *tension, double omega, int mode,
                            whirl_shape_info *info);

/* n shots of the continuous chain at omega (one workspace): the residual r(pivot) / a and the
 * axis crossings below the pivot for the tip radii a[0..n-1] in (0, 1]. Polls the stop request
 * (WHIRL_EINTERRUPTED). */
int whirl_continuum_shots(double omega, double tip_mass, size_t n, const double *a,
                          double *residual, int *crossings);

/* ---- the force balance of the N-link chain in its link angles (src/nlink_balance.c) ----
 * R_i(omega, theta) = rho_i - rho_{i-1} - l_i sin theta_i (rho_i: the radius that balances mass i
 * horizontally), zero exactly at an equilibrium; its Jacobian in theta is tridiagonal. */
typedef struct nlink_balance nlink_balance;

/* NULL (with whirl_last_error) on no memory; the chain is read, not owned. */
nlink_balance *whirl_nlink_balance_alloc(const whirl_chain *c);
void whirl_nlink_balance_free(nlink_balance *b); /* NULL is a no-op */

/* R at (omega, theta[0..N-1]) and its Jacobian, factorised. GSL_EDOM if a link is not below the
 * horizontal (|theta_i| >= pi/2), GSL_ERANGE if not finite. A Jacobian exactly singular (a fold
 * to the last bit) is factorised with its zero pivot moved to -eps |A|: the bordered solves
 * stay accurate there, and the sign and logarithm of det A are those of that pivot. */
int whirl_nlink_balance_factor(nlink_balance *b, double omega, const double *theta);
/* R_i of the last factor (N values, owned by b). */
const double *whirl_nlink_balance_residual(const nlink_balance *b);
/* ln |det A| of the last factor (O(N) logarithms), its sign in *sign. */
double whirl_nlink_balance_logdet(const nlink_balance *b, int *sign);
/* The sign of det A of the last factor. */
int whirl_nlink_balance_det_sign(const nlink_balance *b);
/* The number of negative eigenvalues of A at the last factor (all real: A is similar to a
 * symmetric tridiagonal matrix), by the Sturm count of its pivots; O(N). */
int whirl_nlink_balance_index(const nlink_balance *b);
/* The largest magnitude of an entry of A at the last factor: the scale of its round-off. */
double whirl_nlink_balance_scale(const nlink_balance *b);
/* The bordered system [A, dR/domega; c_theta^T, c_omega] (x_theta, x_omega) = (f, g) at the last
 * factor (f NULL: zero), with one step of iterative refinement if refine; the Schur complement
 * c_omega - c_theta . A^{-1} dR/domega in *schur (det of the system = det A * schur). */
int whirl_nlink_balance_bordered(nlink_balance *b, const double *c_theta, double c_omega,
                                 const double *f, double g, int refine, double *x_theta,
                                 double *x_omega, double *schur);
/* The eigenvalue of A nearest zero (all are real) into *mu, and its rate along the direction
 * (d_omega, d_theta) into *mu_rate, from iters steps of inverse iteration with the last factor
 * on x[0..N-1] (in place: the start vector, then the eigenvector, largest component 1), O(N)
 * each. GSL_EFAILED or GSL_ERANGE where they are not finite. */
int whirl_nlink_balance_near_zero(nlink_balance *b, double d_omega, const double *d_theta,
                                  int iters, double *x, double *mu, double *mu_rate);
/* Newton's method on R at fixed omega from theta (in place) to round-off; the last factor is
 * the converged point's. GSL_EFAILED if it does not converge, GSL_EDOM if it ends with a link at
 * or beyond the horizontal. */
int whirl_nlink_balance_polish(nlink_balance *b, double omega, double *theta);
/* The linear mode shape at the critical rate omega: the null vector of A at theta = 0, with
 * the relative accuracy of each component (a twisted factorization), scaled to a largest
 * component of 1 into phi[0..N-1]; *tip_sign the sign of phi_N (+1 or -1) even where phi_N
 * underflows. Leaves b unfactored. GSL_EFAILED if the vector is not finite. */
int whirl_nlink_balance_mode(nlink_balance *b, double omega, double *phi, int *tip_sign);
/* The nodes r, z (pivot first, z relative to the pivot) and the link tensions (tension[i] of
 * link i, tension[0] = tension[1]; arrays of N + 1) of the link angles theta; returns the largest
 * sine of the angle between a link and the resultant of the forces on the masses below it
 * (zero at an equilibrium). */
double whirl_nlink_balance_nodes(const whirl_chain *c, double omega, const double *theta,
                                 double *r, double *z, double *tension);

#endif
