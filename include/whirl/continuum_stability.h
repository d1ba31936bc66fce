/* whirl: linear stability of the steady shapes of the continuous chain, computed in the
 * continuum (no N-link chain): the string equations linearised about the steady shape in the
 * co-rotating frame and discretised by Chebyshev collocation on elements in arclength
 * (src/stability/continuum_stability.c states the equations). The chain is the uniform one of
 * whirl/steady.h (length 1, mass 1, g = 1) with an optional point mass at its free end.
 * Eigenvalues are returned as mu = lambda^2 (the whirl_spectrum of whirl/stability.h): the shape
 * is neutrally stable when every mu is real and negative. */
#ifndef WHIRL_CONTINUUM_STABILITY_H
#define WHIRL_CONTINUUM_STABILITY_H

#include <stddef.h>

#include "whirl/common.h"
#include "whirl/stability.h"
#include "whirl/steady.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct whirl_cstab whirl_cstab; /* workspace of the continuum's linear analysis */

typedef struct whirl_cstab_params {
    int degree;       /* Chebyshev degree p of every element (p + 1 points each); 16; 6..64 */
    double tip_mass;  /* point mass at the free end [M]; 0; 0..WHIRL_TIP_MASS_MAX */
    double shape_tol; /* elements are halved until the last two Chebyshev coefficients of the
                         shape (r and the load ratio q) on each are at most shape_tol times their
                         largest value; 1e-11; in [1e-14, 1e-3] */
    double freq_max;  /* eigenvalues with |mu| <= max(freq_max, 3 omega)^2 are kept, the rest
                         (unresolved frequencies and the constraint's infinite eigenvalues)
                         dropped [sqrt(g/L)]; 30; > 0 */
    int solver;       /* 0: the kept mu by the Arnoldi iteration on the banded pencil (dense
                         fall-back if it does not converge); 1: every mu of the dense block
                         (the reference, O(np^3)); 0 */
    double memory_mb; /* the workspace's bound [MB]: shapes needing more collocation points
                         than it holds are refused (GSL_EMAXITER naming the mode, the rate and
                         the points); 1024; 16..1048576 */
    void (*progress)(void *ctx, int mode, double omega); /* called by whirl_cstab_windows, on
                         its thread, before each rate of the search it linearises at (a
                         progress display); NULL: none (default) */
    void *progress_ctx;
} whirl_cstab_params;

/* The defaults above.
 * @return the defaults
 */
WHIRL_API whirl_cstab_params whirl_cstab_defaults(void);

/* A workspace with the parameters p (copied). NULL (whirl_last_error) on bad parameters or no
 * memory.
 * @param p the parameters (copied)
 * @return the workspace, to free with whirl_cstab_free; NULL with a message on bad parameters or no
 *     memory
 */
WHIRL_API whirl_cstab *whirl_cstab_alloc(const whirl_cstab_params *p);
/* Frees the workspace. NULL is a no-op.
 * @param w the workspace, or NULL
 */
WHIRL_API void whirl_cstab_free(whirl_cstab *w);

/* Linearises about the steady shape of mode k >= 1 at omega (whirl_continuum_solve from
 * tip_r_guess, 0: its own bracket; then the shape re-solved by collocation on elements refined
 * until shape_tol is met), or with mode 0 about the hanging chain (omega >= 0). *tip_r (may be
 * NULL) receives the collocation's tip radius [L]. GSL_EDOM if the mode does not exist at omega,
 * GSL_EINVAL on bad arguments, GSL_EMAXITER if the collocation needs more points than memory_mb
 * holds or does not reproduce the shooting's shape, WHIRL_EINTERRUPTED on a stop request.
 * @param w the workspace
 * @param omega the rate [sqrt(g/L)], > 0 for a mode >= 1, >= 0 for mode 0
 * @param mode the mode k >= 1, or 0 for the hanging chain
 * @param tip_r_guess the tip radius to start the shooting from [L], or 0 for its own bracket
 * @param tip_r out, or NULL: the collocation's tip radius [L]
 * @return GSL_SUCCESS, GSL_EDOM, GSL_EINVAL, GSL_EMAXITER or WHIRL_EINTERRUPTED (see above), with a
 *     message
 */
WHIRL_API int whirl_cstab_linearise(whirl_cstab *w, double omega, int mode, double tip_r_guess,
                                    double *tip_r);

/* The elements and collocation points of the last linearisation.
 * @param w the workspace
 * @param elements out: the elements (0 before a linearisation)
 * @param points out: the collocation points (0 before a linearisation)
 */
WHIRL_API void whirl_cstab_grid(const whirl_cstab *w, size_t *elements, size_t *points);

/* The mu of the last linearisation with |mu| <= max(freq_max, 3 omega)^2, the rotation's mu = 0
 * removed (a shape of mode >= 1), signatures as in whirl/stability.h when asked (eigenvectors:
 * about twice the work). Pointers into the workspace, valid until its next use.
 * @param w the workspace, linearised
 * @param signatures non-zero: the Krein signatures too (eigenvectors computed)
 * @param out out: the eigenvalues mu = lambda^2 (and signatures), pointers into the workspace
 * @return GSL_SUCCESS, GSL_EINVAL with no linearisation, or the eigen-solver's failure with a
 *     message
 */
WHIRL_API int whirl_cstab_spectrum(whirl_cstab *w, int signatures, whirl_spectrum *out);

/* The windows of instability of mode k of the continuous chain over the range of p (as for
 * whirl_windows_find: scan step, tolerance, range, and krylov: near the edges the colliding pair
 * by shift-and-invert Arnoldi on the collocation's pencil), the shapes those of the branch
 * (whirl_continuum_branch over the scan), in increasing omega, into windows[0..max-1], their
 * number into *count (GSL_EINVAL if more than max). Every closed edge is then located again on a
 * refined discretisation (degree + 8, shape_tol / 100; a second workspace allocated for it);
 * where that moves it by more than 1e-8, again at degree + 16 and + 24 (64 at most) until two
 * successive refinements agree to 1e-8 or the change grows (the round-off of the higher degree:
 * then the previous level's edge): that edge is returned, its last change in err_from / err_to
 * (above 1e-8 where the target was not reached). GSL_EDOM if the mode does not exist
 * in the range, GSL_EINVAL beyond WHIRL_CONTINUUM_OMEGA_MAX, WHIRL_EINTERRUPTED on a stop request
 * (between eigen-solves).
 * @param w the workspace
 * @param mode the mode k >= 1
 * @param p the search's range, step, tolerance and krylov
 * @param windows out: the windows, max
 * @param max the room of windows
 * @param count out: the windows found
 * @param stats out: the search's counts (whirl_windows_stats)
 * @return GSL_SUCCESS, GSL_EDOM, GSL_EINVAL or WHIRL_EINTERRUPTED (see above), or the failure of a
 *     linearisation, with a message
 */
WHIRL_API int whirl_cstab_windows(whirl_cstab *w, int mode, const whirl_windows_params *p,
                                  whirl_window *windows, size_t max, size_t *count,
                                  whirl_windows_stats *stats);

#ifdef __cplusplus
}
#endif

#endif
