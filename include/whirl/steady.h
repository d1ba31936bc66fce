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
#include <stdint.h>

#include "whirl/chain.h"
#include "whirl/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The node arclengths a whirl_shape_info holds: the first ones from the pivot. */
#define WHIRL_SHAPE_NODES 64

/* The summary of one steady shape (the comment line of `whirl shape`). */
typedef struct whirl_shape_info {
    double omega;       /* rotation rate [sqrt(g/L)] */
    int mode;           /* node count k: 1..N for the N-link chain, 1..WHIRL_CONTINUUM_MODE_MAX
                         * for the continuum */
    double tip_r;       /* distance of the free end from the axis [L], > 0 */
    double max_r;       /* max over the chain of |r| [L] */
    double top_tension; /* tension at the pivot [M g] */
    double depth;       /* height of the pivot above the free end [L] */
    /* A node is a point of the chain on the rotation axis; the pivot is one. The node count k
     * (mode, the command line's node_count) is 1 + the crossings below the pivot. n_nodes and
     * node_s are the names of the fields before 2.2, kept as aliases of the same storage. */
    union {
        int n_crossings; /* axis crossings below the pivot (sign changes of r along the masses
                          * for the N-link chain): mode - 1 for the continuum; on a coarse
                          * N-link chain the branch of mode k can have another count at high
                          * rates; all of them, also beyond WHIRL_SHAPE_NODES */
        int n_nodes;
    };
    union {
        double crossing_s[WHIRL_SHAPE_NODES]; /* the arclengths from the pivot [L] of the first
                                               * min(n_crossings, WHIRL_SHAPE_NODES) crossings,
                                               * increasing (an N-link shape's full list:
                                               * whirl_nlink_node_arclengths on the r of
                                               * whirl_nlink_solve_nodes) */
        double node_s[WHIRL_SHAPE_NODES];
    };
} whirl_shape_info;

/* ---- continuous chain ---- */

/* The linear critical rate of mode k (>= 1) where it bifurcates from the hanging chain: with no
 * tip mass j_{0,k}/2; with a tip mass the k-th root of the linearised problem (Bessel J0/Y0
 * determinant). GSL_EINVAL on a bad mode or tip mass.
 * @param mode the mode k, 1..WHIRL_CONTINUUM_MODE_MAX
 * @param tip_mass the point mass at the free end [M], >= 0
 * @param omega out: the critical rate omega_k [sqrt(g/L)]
 * @return GSL_SUCCESS, or GSL_EINVAL on a bad mode or tip mass
 */
WHIRL_API int whirl_continuum_critical(int mode, double tip_mass, double *omega);

/* The linear critical rates of modes 1..n (1 <= n <= WHIRL_CONTINUUM_MODE_MAX) into omega[0..n-1]
 * (caller's array): the same roots as whirl_continuum_critical, found in one sweep over the
 * rates (cost linear in n; n = 3183 with a tip mass takes about 1e5 determinant evaluations).
 * GSL_EINVAL on a bad n or tip mass, WHIRL_EINTERRUPTED on a stop request.
 * @param n how many modes, 1..WHIRL_CONTINUUM_MODE_MAX
 * @param tip_mass the point mass at the free end [M], >= 0
 * @param omega out: omega_1..omega_n [sqrt(g/L)], the caller's array of n
 * @return GSL_SUCCESS, GSL_EINVAL on a bad n or tip mass, WHIRL_EINTERRUPTED on a stop request
 */
WHIRL_API int whirl_continuum_critical_rates(size_t n, double tip_mass, double *omega);

/* The steady shape of mode k at omega. tip_r_guess > 0 seeds the root search (continuation);
 * 0 lets the solver bracket the root itself. GSL_EDOM (message naming omega_k) if mode k does not
 * exist at omega; GSL_EINVAL on omega <= 0 or non-finite, mode outside
 * 1..WHIRL_CONTINUUM_MODE_MAX or a negative tip mass. info->node_s holds the first
 * WHIRL_SHAPE_NODES nodes from the pivot, info->n_nodes counts them all. Accuracy: tip_r, top_tension and depth to 1e-10 relative or better (about
 * 1e-13 measured). Near the bifurcation tip_r ~ sqrt(omega - omega_k) is ill-conditioned
 * (d ln tip_r / d ln omega = 1 / (2 eps), eps = omega / omega_k - 1): the linear part of the
 * residual is evaluated in closed form, so the error is that of one rounding of omega, about
 * 1e-16 / eps (2e-11 at eps = 1e-6 without a tip mass); with a tip mass the Bessel combination
 * of the linear part loses digits (up to 1.3e-10 for m = 0.48, 3.4e-10 for m = 3.7 at eps = 1e-6,
 * modes 1-6).
 * @param omega the rotation rate [sqrt(g/L)], in (0, WHIRL_CONTINUUM_OMEGA_MAX]
 * @param mode the mode k (node count), 1..WHIRL_CONTINUUM_MODE_MAX
 * @param tip_mass the point mass at the free end [M], >= 0
 * @param tip_r_guess a tip radius to start the root search from [L], or 0 to bracket it
 * @param info out: the shape's summary
 * @return GSL_SUCCESS; GSL_EDOM below omega_k (the message names it); GSL_EINVAL on bad arguments
 */
WHIRL_API int whirl_continuum_solve(double omega, int mode, double tip_mass, double tip_r_guess,
                                    whirl_shape_info *info);

/* The highest rate of the continuum solvers: beyond about 8000 the shooting's ODE needs more
 * than its cap of 100000 steps per shot (the shape varies on a scale ~ 1/omega); higher rates are
 * refused with GSL_EINVAL (the N-link chain has no such limit). */
#define WHIRL_CONTINUUM_OMEGA_MAX 5000.0

/* The highest mode of the continuum's steady shapes and critical rates: the last one born below
 * WHIRL_CONTINUUM_OMEGA_MAX without a tip mass (j_{0,3183}/2 = 4999.45, j_{0,3184}/2 = 5001.02);
 * higher modes are refused with GSL_EINVAL. */
#define WHIRL_CONTINUUM_MODE_MAX 3183

/* The ODE tolerance (absolute and relative, on order-one scaled variables) of the continuum. */
#define WHIRL_CONTINUUM_TOL 1e-13

/* whirl_continuum_solve with the ODE tolerance tol in (0, 1) instead of WHIRL_CONTINUUM_TOL:
 * for convergence studies.
 * @param omega the rotation rate [sqrt(g/L)], in (0, WHIRL_CONTINUUM_OMEGA_MAX]
 * @param mode the mode k (node count), 1..WHIRL_CONTINUUM_MODE_MAX
 * @param tip_mass the point mass at the free end [M], >= 0
 * @param tip_r_guess a tip radius to start the root search from [L], or 0 to bracket it
 * @param tol the ODE tolerance, in (0, 1)
 * @param info out: the shape's summary
 * @return as whirl_continuum_solve; GSL_EINVAL also for tol out of range, GSL_ENOMEM
 */
WHIRL_API int whirl_continuum_solve_tol(double omega, int mode, double tip_mass, double tip_r_guess,
                                        double tol, whirl_shape_info *info);

/* Samples the shape with tip radius tip_r in (0, 1] (from whirl_continuum_solve) at npts >= 2
 * arclengths equally spaced from the pivot (s = 0) to the free end (s = 1): r, z (0 at the pivot)
 * and the tension there; arrays of npts. For any tip_r it is the shot of the shooting method: r
 * at the pivot (r[0]) vanishes only for a solution.
 * @param omega the rotation rate [sqrt(g/L)]
 * @param tip_mass the point mass at the free end [M], >= 0
 * @param tip_r the tip radius [L], in (0, 1]: info.tip_r of whirl_continuum_solve for a shape
 * @param npts how many arclengths, >= 2
 * @param s out: the arclengths from the pivot [L], npts
 * @param r out: the signed distances from the axis [L], npts
 * @param z out: the heights, 0 at the pivot and negative below it [L], npts
 * @param tension out: the tensions [M g], npts
 * @return GSL_SUCCESS, or a status with a message on bad arguments or a failed integration
 */
WHIRL_API int whirl_continuum_sample(double omega, double tip_mass, double tip_r, size_t npts,
                                     double *s, double *r, double *z, double *tension);

/* Follows mode k over the rates omega[0..n-1] (any order, continuation from one to the next):
 * exists[j] = 1 and info[j] filled where the mode exists, exists[j] = 0 where it does not. The
 * rates are cut into contiguous blocks followed in parallel on the OpenMP threads (serially when
 * called from inside a parallel region). After a failure or a stop request (WHIRL_EINTERRUPTED)
 * the entries of the rates reached are valid and those of the others left as they were.
 * @param mode the mode k, 1..WHIRL_CONTINUUM_MODE_MAX
 * @param tip_mass the point mass at the free end [M], >= 0
 * @param n how many rates
 * @param omega the rates [sqrt(g/L)], n, in any order
 * @param info out: the shape at each rate where it exists, n
 * @param exists out: 1 where mode k exists at omega[j], 0 where not, n
 * @return GSL_SUCCESS, WHIRL_EINTERRUPTED on a stop request, or the status of a failed solve (the
 *     entries reached are valid)
 */
WHIRL_API int whirl_continuum_branch(int mode, double tip_mass, size_t n, const double *omega,
                                     whirl_shape_info *info, int *exists);

/* ---- N-link chain ---- */

/* The axis crossings below the pivot of the N-link shape at the rate omega (> 0) whose masses
 * lie at the radii r[0..c->n] (pivot first): returns their count, and writes the arclengths
 * from the pivot [L] of the first min(count, max) into node_s[] (increasing; node_s may be NULL
 * when max is 0). A crossing lies on link i >= 2 where r changes sign from mass i-1 to mass i
 * (or reaches 0 from a non-zero value), at the linearly interpolated point. Below the last mass
 * whose |r| is a normal double (>= DBL_MIN; the top modes of long chains decay below it towards
 * the tip, their radii there zero or subnormal) the signs are those of the force balance
 * linearised about the hanging chain at omega, followed up from the tip (src/nlink.c). That
 * mass's index into *resolved (if not NULL): c->n when every radius is counted as it is (also
 * when none is normal, the hanging chain: no crossing).
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)], > 0
 * @param r the masses' signed distances from the axis [L], c->n + 1, the pivot first
 * @param max the room in node_s
 * @param node_s out: the crossings' arclengths from the pivot [L], min(count, max); NULL if max is
 *     0
 * @param resolved out, or NULL: the index of the last mass whose radius is counted as it is
 * @return the number of crossings (the node count minus 1)
 */
WHIRL_API size_t whirl_nlink_node_arclengths(const whirl_chain *c, double omega, const double *r,
                                             size_t max, double *node_s, size_t *resolved);

/* The first nmodes (<= c->n) linear critical rates of the chain, ascending: the normal-mode
 * frequencies of the hanging chain (a symmetric tridiagonal eigenproblem).
 * @param c the chain
 * @param nmodes how many rates, <= c->n
 * @param omega out: omega_1..omega_nmodes, ascending [sqrt(g/L)]
 * @return GSL_SUCCESS, or GSL_EINVAL on bad arguments
 */
WHIRL_API int whirl_nlink_critical(const whirl_chain *c, size_t nmodes, double *omega);

/* Called by whirl_nlink_critical_report after each block of rates: done of total found. */
typedef void (*whirl_nlink_critical_progress_fn)(void *ctx, size_t done, size_t total);

/* whirl_nlink_critical with a report of the work done: the rates come in blocks (one call of
 * LAPACK's dstebz each, about 0.02 s), the stop request polled between blocks, and after each
 * block progress(ctx, done, nmodes) with the rates found so far (done increasing, nmodes last).
 * @param c the chain
 * @param nmodes how many rates, <= c->n
 * @param omega out: omega_1..omega_nmodes, ascending [sqrt(g/L)]
 * @param progress called after each block, or NULL: none
 * @param ctx passed to progress
 * @return GSL_SUCCESS, GSL_EINVAL on bad arguments, WHIRL_EINTERRUPTED on a stop request
 */
WHIRL_API int whirl_nlink_critical_report(const whirl_chain *c, size_t nmodes, double *omega,
                                          whirl_nlink_critical_progress_fn progress, void *ctx);

/* The exact relative equilibrium of mode k at omega: the point of the branch born at omega_k
 * (the k-th critical rate) that its pseudo-arclength continuation from the birth reaches first
 * (whirl_nlink_path). The force balance of every mass holds to round-off. info->n_nodes is
 * the shape's own crossing count, which on a coarse chain at a high rate can differ from k - 1
 * (several equilibria then share a node count; the branch decides which one is mode k).
 * GSL_EDOM with a message naming
 * the rates the branch reaches if it does not reach omega (omega below its lowest rate, which
 * is omega_k unless the branch first turns to lower rates; or k > c->n); GSL_EFAILED if the
 * continuation fails (the message names the rate reached); GSL_EMAXITER at the bound on its
 * steps (whirl_nlink_follow_options); WHIRL_EINTERRUPTED on a stop request.
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)], > 0
 * @param mode the mode k (the branch born at the k-th critical rate), 1..c->n
 * @param info out: the shape's summary
 * @return GSL_SUCCESS; GSL_EDOM if the branch does not reach omega; GSL_EFAILED if the
 *     continuation fails; GSL_EMAXITER at the bound on its steps; WHIRL_EINTERRUPTED on a stop
 *     request
 */
WHIRL_API int whirl_nlink_solve(const whirl_chain *c, double omega, int mode,
                                whirl_shape_info *info);

/* whirl_nlink_solve with the shape's nodes: r[i], z[i] of mass i (i = 0: the pivot, z relative
 * to it) and tension[i] of link i (tension[0] = tension[1]), arrays of c->n + 1. At high rates
 * the tip radius alone no longer fixes the shape to round-off (whirl_nlink_positions from it
 * lands the pivot off the axis): these nodes come from the branch's own link angles.
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)], > 0
 * @param mode the mode k, 1..c->n
 * @param info out: the shape's summary
 * @param r out: the masses' signed distances from the axis [L], c->n + 1 (the pivot first)
 * @param z out: their heights relative to the pivot [L], c->n + 1
 * @param tension out: the links' tensions [M g], c->n + 1
 * @return as whirl_nlink_solve
 */
WHIRL_API int whirl_nlink_solve_nodes(const whirl_chain *c, double omega, int mode,
                                      whirl_shape_info *info, double *r, double *z,
                                      double *tension);

/* Where a continuation from a birth stands: what the drivers below report to a progress
 * function every 256 accepted steps. */
typedef struct whirl_nlink_progress {
    int mode;           /* the branch's mode */
    double omega_birth; /* its birth rate omega_k [sqrt(g/L)] */
    long steps;         /* accepted steps from the birth */
    long steps_max;     /* their bound: the path fails with GSL_EMAXITER there */
    long folds;         /* folds passed (the rate turned back) */
    double omega;       /* the current point's rate [sqrt(g/L)] */
    double omega_hi;    /* the highest rate reached [sqrt(g/L)] */
    double arclength;   /* travelled from the birth (the metric of whirl_nlink_path below) */
} whirl_nlink_progress;
typedef void (*whirl_nlink_progress_fn)(void *ctx, const whirl_nlink_progress *at);

/* How the drivers follow a branch from its birth (whirl_nlink_solve_nodes_opt,
 * whirl_nlink_follow_opt); all zero (or a NULL pointer to it): the defaults, as the functions
 * without it. */
typedef struct whirl_nlink_follow_options {
    long steps_max; /* bound on the accepted continuation steps from the birth (> 0): there the
                     * path fails with GSL_EMAXITER, naming the rate reached; 0: the default,
                     * 100000 or 200 per link, whichever is more (GSL_EINVAL if < 0) */
    whirl_nlink_progress_fn progress; /* called every 256 accepted steps; NULL: none (default) */
    void *progress_ctx;               /* passed to progress */
} whirl_nlink_follow_options;

/* The default options for the chain c: steps_max the bound above (100000 or 200 per link,
 * whichever is more; 100000 for c NULL), no progress function.
 * @param c the chain, or NULL
 * @return the defaults
 */
WHIRL_API whirl_nlink_follow_options whirl_nlink_follow_defaults(const whirl_chain *c);

/* whirl_nlink_solve_nodes with the options opt (may be NULL). The middle modes of long chains
 * fold thousands of times on their way up (1000 links, mode 334: about 5000 folds from its
 * birth at omega 530 to 700, 120000 steps).
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)], > 0
 * @param mode the mode k, 1..c->n
 * @param info out: the shape's summary
 * @param r out: the masses' signed distances from the axis [L], c->n + 1 (the pivot first)
 * @param z out: their heights relative to the pivot [L], c->n + 1
 * @param tension out: the links' tensions [M g], c->n + 1
 * @param opt the continuation's options, or NULL for the defaults
 * @return as whirl_nlink_solve; GSL_EINVAL also on bad options
 */
WHIRL_API int whirl_nlink_solve_nodes_opt(const whirl_chain *c, double omega, int mode,
                                          whirl_shape_info *info, double *r, double *z,
                                          double *tension, const whirl_nlink_follow_options *opt);

/* The nodes of the shape with tip radius tip_r: r[i], z[i] of mass i (i = 0: the pivot, which
 * lands on the axis only for a solution) and tension[i] of link i (tension[0] = tension[1]),
 * arrays of c->n + 1.
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)]
 * @param tip_r the tip radius [L]
 * @param r out: the signed distances from the axis [L], c->n + 1 (the pivot first)
 * @param z out: the heights relative to the pivot [L], c->n + 1
 * @param tension out: the links' tensions [M g], c->n + 1
 * @return GSL_SUCCESS, or a status with a message on bad arguments
 */
WHIRL_API int whirl_nlink_positions(const whirl_chain *c, double omega, double tip_r, double *r,
                                    double *z, double *tension);

/* Follows mode k over omega[0..n-1] (any order): one pseudo-arclength continuation from the
 * birth, info[j] the point where the branch first reaches omega[j] (as whirl_nlink_solve),
 * exists[j] = 0 where it does not. Errors as whirl_nlink_solve.
 * @param c the chain
 * @param mode the mode k, 1..c->n
 * @param n how many rates
 * @param omega the rates [sqrt(g/L)], n, in any order
 * @param info out: the shape where the branch first reaches omega[j], n
 * @param exists out: 1 where it reaches omega[j], 0 where not, n
 * @return as whirl_nlink_solve
 */
WHIRL_API int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists);

/* whirl_nlink_branch with the nodes of each shape (as whirl_nlink_solve_nodes): row j of r, z
 * and tension (each n x (c->n + 1), row-major) holds the shape at omega[j] where exists[j],
 * and is left as it was elsewhere. r, z and tension are all NULL (none wanted) or none is.
 * @param c the chain
 * @param mode the mode k, 1..c->n
 * @param n how many rates
 * @param omega the rates [sqrt(g/L)], n, in any order
 * @param info out: the shape where the branch first reaches omega[j], n
 * @param exists out: 1 where it reaches omega[j], 0 where not, n
 * @param r out, or NULL: the nodes' signed distances from the axis [L], n x (c->n + 1)
 * @param z out, or NULL: their heights relative to the pivot [L], n x (c->n + 1)
 * @param tension out, or NULL: the links' tensions [M g], n x (c->n + 1)
 * @return as whirl_nlink_solve; GSL_EINVAL if some but not all of r, z, tension are NULL
 */
WHIRL_API int whirl_nlink_branch_nodes(const whirl_chain *c, int mode, size_t n,
                                       const double *omega, whirl_shape_info *info, int *exists,
                                       double *r, double *z, double *tension);

/* ---- N-link chain: branches by pseudo-arclength continuation ----
 * The relative equilibria of the N-link chain are the zeros of one function of two variables,
 * G(omega, a) = r_0 / |r|: the pivot's radius, divided by the norm of the radii of all the nodes,
 * when the shape is built up from the tip with tip radius a (src/steady/nlink_path.c). G depends on a only through a^2 and is finite at a = 0,
 * where its zeros in omega are the critical rates: a branch is a curve of G = 0 in the
 * (omega, a) plane, born at (omega_k, 0). whirl_nlink_path follows such a curve with arclength
 * measured in (ln omega, link angles): ds^2 = (d omega / omega)^2 + the mean over the links of
 * d theta_i^2, so that a step of ds changes no link angle by much more than ds. Where the shot
 * from the tip loses digits (long chains, high modes, high rates: the tip radius then fixes the
 * shape only to a few digits) the path continues the same curve in (omega, all link angles)
 * instead, on the force balance of every mass (tridiagonal Jacobian, O(N) per Newton step). */

/* What happens on a branch between two continuation points. */
typedef enum whirl_event_kind {
    WHIRL_EVENT_FOLD = 1,         /* omega has an extremum: the branch turns back */
    WHIRL_EVENT_BRANCH_POINT = 2, /* grad G vanishes: another curve of equilibria crosses */
    WHIRL_EVENT_RETURN = 3        /* a = 0: the branch returns to the hanging chain */
} whirl_event_kind;

typedef struct whirl_branch_event {
    whirl_event_kind kind;
    double omega;     /* where [sqrt(g/L)], located by Brent's method to ~1e-14 relative */
    double tip_r;     /* signed tip radius there [L] (positive on a branch from its birth) */
    double arclength; /* from the start of the path, in the metric above */
    union {
        int n_crossings; /* axis crossings below the pivot there (node count - 1) */
        int n_nodes;     /* its name before 2.2, kept: the same storage */
    };
} whirl_branch_event;

#define WHIRL_PATH_EVENTS_MAX 4 /* events one step can hold */

/* A path along a branch: alloc, start (at a birth or an equilibrium), step, free. The fields
 * are read-only for the caller, but for ds, which it may shorten before a step; the path's
 * workspace follows them in the allocation (opaque: a path exists only as
 * whirl_nlink_path_alloc returns it). */
typedef struct whirl_nlink_path {
    const whirl_chain *chain; /* read, not owned */
    int mode;         /* the branch's mode when started at a birth, 0 from an equilibrium */
    double omega_birth; /* its birth rate omega_k [sqrt(g/L)] (0 from an equilibrium) */
    double omega;     /* current point: rate [sqrt(g/L)] */
    double tip_r;     /* current point: signed tip radius [L] */
    double t_omega, t_tip; /* unit tangent (direction of travel) in the metric above (t_tip:
                            * d tip_r / ds) */
    int angles;       /* 1 while the path is continued in (omega, link angles), 0 in
                       * (omega, tip radius) */
    double arclength; /* travelled since the start */
    double ds;        /* the next step's length; adapted to the Newton convergence and the
                       * turning of the tangent */
    double omega_lo, omega_hi; /* the lowest and highest rates reached since the start */
    long steps;       /* accepted steps */
    long rejected;    /* rejected trial steps (step halved) */
    long shots;       /* evaluations of G and its derivatives */
    int n_events;     /* events in the last step, in the order met */
    whirl_branch_event event[WHIRL_PATH_EVENTS_MAX];
    int ended;        /* 1 once the path returned to the hanging chain (a = 0) */
    int cross_angles[WHIRL_PATH_EVENTS_MAX + 1]; /* 1: that crossing of the last
                                                  * whirl_nlink_path_crossings was resolved in
                                                  * the link angles, 0: by the tip shot */
} whirl_nlink_path;

/* NULL (with whirl_last_error) on no memory or a chain of no links.
 * @param c the chain, of at least one link (not owned: must outlive the path)
 * @return the path, to free with whirl_nlink_path_free; NULL with a message on failure
 */
WHIRL_API whirl_nlink_path *whirl_nlink_path_alloc(const whirl_chain *c);
/* Frees the path. NULL is a no-op.
 * @param p the path, or NULL
 */
WHIRL_API void whirl_nlink_path_free(whirl_nlink_path *p);

/* Starts at the birth of mode k (1 <= k <= N): the k-th critical rate polished by Newton's
 * method on G(omega, 0), tip radius 0, heading into a > 0. GSL_EINVAL if k is out of range.
 * @param p the path (whirl_nlink_path_alloc)
 * @param mode the mode k, 1..N
 * @return GSL_SUCCESS, or GSL_EINVAL if k is out of range
 */
WHIRL_API int whirl_nlink_path_birth(whirl_nlink_path *p, int mode);

/* Starts at an equilibrium near (omega, tip_r) (polished by Newton's method at fixed omega),
 * heading where omega increases (direction > 0) or decreases (direction < 0). GSL_EFAILED if
 * Newton's method does not converge there.
 * @param p the path (whirl_nlink_path_alloc)
 * @param omega the rate [sqrt(g/L)], > 0
 * @param tip_r the tip radius near the equilibrium [L]
 * @param direction > 0: towards increasing omega, < 0: decreasing
 * @return GSL_SUCCESS, GSL_EINVAL on a bad omega (or tip radius), GSL_EFAILED, or another status;
 *     with a message
 */
WHIRL_API int whirl_nlink_path_start(whirl_nlink_path *p, double omega, double tip_r, int direction);

/* Starts at the equilibrium near the link angles theta[0..N-1] [rad] at omega (polished by
 * Newton's method on the force balance of every link at fixed omega), in the link angles,
 * heading where omega increases (direction > 0) or decreases (direction < 0). Unlike a start
 * from the tip radius, the start is the equilibrium whose angles are given even where the shot
 * cannot resolve it (roots whose tip radii agree to 1e-7 on a coarse chain at a high rate).
 * GSL_EFAILED if Newton's method does not converge or the point is a fold.
 * @param p the path (whirl_nlink_path_alloc)
 * @param omega the rate [sqrt(g/L)], > 0
 * @param theta the link angles near the equilibrium [rad], c->n
 * @param direction > 0: towards increasing omega, < 0: decreasing
 * @return GSL_SUCCESS, GSL_EINVAL on a bad omega (or tip radius), GSL_EFAILED, or another status;
 *     with a message
 */
WHIRL_API int whirl_nlink_path_start_angles(whirl_nlink_path *p, double omega,
                                            const double *theta, int direction);

/* Reverses the direction of travel.
 * @param p the path, started
 */
WHIRL_API void whirl_nlink_path_reverse(whirl_nlink_path *p);

/* The link angles at the current point, c->n [rad] (valid until the next step or start).
 * @param p the path, started
 * @return the angles, owned by the path
 */
WHIRL_API const double *whirl_nlink_path_theta(const whirl_nlink_path *p);

/* The link angles of the crossings found by the last whirl_nlink_path_crossings, crossing k at
 * k c->n .. (k + 1) c->n - 1 [rad] (valid until the next call, step or start).
 * @param p the path
 * @return the angles, owned by the path
 */
WHIRL_API const double *whirl_nlink_path_cross_theta(const whirl_nlink_path *p);

/* One accepted step: predictor along the tangent, Newton corrector on the arclength hyperplane.
 * A trial step is rejected and halved when Newton needs many iterations, the tangent turns by
 * more than 0.2 rad, a link angle changes by more than 0.2 rad or the step's chord is not that
 * of an arc the step resolves (further from either end's tangent than 3/4 of the turn, or its
 * rate changing outside the range the tangents allow: the step passed over a small S of two
 * folds), or, in the link angles, the index of the force balance (its Jacobian's negative
 * eigenvalues) changes by more than one (two folds or branch points passed over). Events between
 * the old and the new point are located and listed in p->event. GSL_EFAILED if the step falls
 * below its minimum (1e-7), with a one-line message naming the rate reached (the current point,
 * where the path stays) and why the last trial was rejected; GSL_EDOM once the path has ended;
 * WHIRL_EINTERRUPTED on a stop request. The message of a failure of a path begun at a birth
 * (here, in whirl_nlink_path_crossings and in the drivers below) starts with "mode k: ".
 * @param p the path, started by whirl_nlink_path_birth, whirl_nlink_path_start or
 *     whirl_nlink_path_start_angles
 * @return GSL_SUCCESS (p->event lists the step's events), GSL_EFAILED, GSL_EDOM once the path has
 *     ended, WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_nlink_path_step(whirl_nlink_path *p);

/* Where the last step crossed the rate omega (between the previous and the current point; the
 * step is cut at its folds, so it can cross a rate more than once): the tip radii of the first
 * max crossings, in the order of travel, into tip_r[], each found by Newton's method at omega
 * from the step's interpolation (Brent's method on the step's arclength where that lands off the
 * piece), and their link angles in whirl_nlink_path_cross_theta (p->cross_angles[k]: resolved
 * on the link angles). Returns their number (0: no crossing), or minus a status on failure.
 * @param p the path, after a step
 * @param omega the rate [sqrt(g/L)], > 0
 * @param max the room in tip_r
 * @param tip_r out: the crossings' tip radii [L], the first max
 * @return the number of crossings, >= 0, or minus a status with a message
 */
WHIRL_API int whirl_nlink_path_crossings(whirl_nlink_path *p, double omega, int max, double *tip_r);

/* What whirl_nlink_follow reports: a crossing of the rate omega[j] (event NULL) or an event
 * (j = SIZE_MAX), with the shape there in info (mode: the branch's; n_nodes: the shape's own).
 * Returns 0 to go on, WHIRL_VISIT_STOP to stop with success, or a status to stop with. */
typedef int (*whirl_nlink_visit_fn)(void *ctx, size_t j, const whirl_shape_info *info,
                                    const whirl_branch_event *event);
#define WHIRL_VISIT_STOP (-100)

/* Follows the branch of mode k from its birth until its rate first exceeds omega_max or it
 * returns to the hanging chain, calling visit at every crossing of one of the rates
 * omega[0..n-1] (a rate crossed several times, through folds, is reported each time) and at every
 * event, in the order met (a step's events before its crossings). Errors as
 * whirl_nlink_path_step, GSL_EMAXITER at the bound on the steps (whirl_nlink_follow_options;
 * the message names the mode, the steps and the rates reached), or visit's status.
 * @param c the chain
 * @param mode the mode k, 1..c->n
 * @param omega_max follow until the rate first exceeds it [sqrt(g/L)]
 * @param n how many rates
 * @param omega the rates whose crossings are reported [sqrt(g/L)], n
 * @param visit called at every crossing and event, in the order met
 * @param ctx passed to visit
 * @return GSL_SUCCESS (also when visit returned WHIRL_VISIT_STOP), the status of a failed step,
 *     GSL_EMAXITER, or visit's status
 */
WHIRL_API int whirl_nlink_follow(const whirl_chain *c, int mode, double omega_max, size_t n,
                       const double *omega, whirl_nlink_visit_fn visit, void *ctx);
/* whirl_nlink_follow with the options opt (may be NULL).
 * @param c the chain
 * @param mode the mode k, 1..c->n
 * @param omega_max follow until the rate first exceeds it [sqrt(g/L)]
 * @param n how many rates
 * @param omega the rates whose crossings are reported [sqrt(g/L)], n
 * @param visit called at every crossing and event, in the order met
 * @param ctx passed to visit
 * @param opt the continuation's options, or NULL for the defaults
 * @return as whirl_nlink_follow; GSL_EINVAL also on bad options
 */
WHIRL_API int whirl_nlink_follow_opt(const whirl_chain *c, int mode, double omega_max, size_t n,
                                     const double *omega, whirl_nlink_visit_fn visit, void *ctx,
                                     const whirl_nlink_follow_options *opt);

/* The shape summary at rate omega and tip radius tip_r (an equilibrium): mode is copied.
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)]
 * @param tip_r the tip radius [L]
 * @param mode the mode, copied into info
 * @param info out: the shape's summary
 * @return GSL_SUCCESS, or a status with a message (bad arguments, no memory, a summary that is not
 *     finite)
 */
WHIRL_API int whirl_nlink_info(const whirl_chain *c, double omega, double tip_r, int mode,
                     whirl_shape_info *info);

/* G(omega, a) = r_0 / |r| and its partial derivatives (forward differentiation of the recursion):
 * for tests and the completeness scan.
 * @param c the chain, of at least one link
 * @param omega the rotation rate [sqrt(g/L)], > 0
 * @param tip_r the tip radius a [L], finite
 * @param g out: G(omega, a)
 * @param g_omega out, or NULL: dG/d omega
 * @param g_tip out, or NULL: dG/da
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_nlink_residual(const whirl_chain *c, double omega, double tip_r, double *g,
                         double *g_omega, double *g_tip);

/* Pivot-end shooting, a second formulation: the top link's angle theta_1 in (-pi/2, pi/2) fixes
 * the horizontal force H_1 = V_1 tan(theta_1) at the pivot; the recursion down the chain gives
 * the force H_{N+1} left over below the tip, zero for an equilibrium. Returns H_{N+1} / H_1
 * (finite at theta_1 = 0), and the tip radius in *tip_r (may be NULL).
 * @param c the chain
 * @param omega the rotation rate [sqrt(g/L)], > 0
 * @param theta_1 the top link's angle [rad], in (-pi/2, pi/2)
 * @param residual out: H_{N+1} / H_1
 * @param tip_r out, or NULL: the tip radius [L]
 * @return GSL_SUCCESS, or GSL_EINVAL (or another status) with a message
 */
WHIRL_API int whirl_nlink_pivot_residual(const whirl_chain *c, double omega, double theta_1,
                               double *residual, double *tip_r);

/* ---- every planar relative equilibrium at a rate (src/equilibria.c) ----
 * On a coarse N-link chain at a high rate there are many more equilibria than modes born below
 * the rate: besides the branches born at the critical rates, curves of equilibria that never
 * touch the hanging chain (born in pairs at folds). whirl_equilibria_find lists all of them at
 * one rate, each with the branch it lies on; the completeness argument is in src/equilibria.c. */

typedef struct whirl_equilibrium {
    whirl_shape_info info; /* the shape (info.mode: branch, 0 when isolated or unidentified) */
    int branch;      /* k: on the curve born at omega_k from the hanging chain (reached by
                      * continuation); 0: isolated (its curve, followed both ways up to the
                      * continuation's limit, meets no birth); -1: not identified (the
                      * continuation failed before it met a birth, a closure or the limit) */
    double born_at;  /* omega_k for a branch; for an isolated curve the rate of its lowest fold
                      * found, where it appears as a pair of equilibria [sqrt(g/L)]; NaN if
                      * unidentified or no fold was found */
    double eig_growth; /* largest real part of the linearisation's eigenvalues [sqrt(g/L)]
                        * (whirl_stability_shape); NaN for the continuum or when not asked */
    int index;       /* negative directions of the amended potential (whirl_stability_index);
                      * -1 with eig_growth NaN */
} whirl_equilibrium;

typedef struct whirl_equilibria_params {
    int stability;        /* 1: compute eig_growth for each N-link equilibrium; default 1 */
    double follow_factor; /* curves are followed up to follow_factor * omega, > 1; default 2 */
    long shot_budget;     /* most residual evaluations of one refinement level of a scan,
                           * >= 1000; default 2e7 */
    int continuation;     /* 1: method 3 below, which names each equilibrium's branch; 0: the
                           * two scans only (every N-link equilibrium's branch -1); default 1 */
} whirl_equilibria_params;

/* The defaults of whirl_equilibria_params.
 * @return the defaults
 */
WHIRL_API whirl_equilibria_params whirl_equilibria_defaults(void);

/* The result: the equilibria in increasing tip radius, and the evidence of completeness. */
typedef struct whirl_equilibria {
    double omega;         /* the rate [sqrt(g/L)] */
    size_t n_links;       /* N, 0 for the continuum */
    size_t count;         /* equilibria found (the union of the methods below) */
    whirl_equilibrium *eq; /* count of them, increasing tip_r */
    int born;             /* critical rates below omega (Kolodner: the continuum's count) */
    /* method 1: sign changes of the pivot's radius over the tip radius (both chains) */
    size_t tip_roots;     /* roots found */
    double tip_floor;     /* smallest tip radius scanned [L] (below it the shot is linear) */
    long tip_shots;       /* residual evaluations of the final level */
    int tip_levels;       /* refinement levels until the count repeated (>= 2) */
    size_t tip_unresolved; /* intervals left at the resolution limit, not proven monotone */
    /* method 2, N-link: the same scan of the pivot-end shooting over the top link's angle;
     * continuum: the solve of modes 1..born by bracketing the crossing count */
    size_t check_roots;   /* roots found */
    long check_shots;     /* residual evaluations (N-link: of the final level) */
    int check_levels;
    size_t matched;       /* equilibria both methods found (N-link: every link angle of the
                           * polished shapes within 1e-8 rad; continuum: each solved shape
                           * alone in a sign change of the scan) */
    size_t unpolished;    /* N-link: roots of either scan from whose shot Newton's method on
                           * the link angles did not converge to a chain's equilibrium, even
                           * from a shot in quadruple precision (see refined; left out of eq;
                           * 0 unless roots lie within round-off of each other) */
    /* method 3, N-link: continuation of every curve through the roots (and of every branch
     * from its birth) up to follow_factor * omega, counting its crossings of omega */
    size_t crossings;     /* crossings found, each matched against the scans' roots */
    size_t missed;        /* crossings no scan found (added to eq) */
    size_t isolated;      /* equilibria on curves that meet no birth */
    size_t unidentified;  /* equilibria whose curve's continuation failed */
    long path_steps;      /* continuation steps in all */
    size_t cut_short;     /* curves' directions whose continuation failed above omega (before
                           * follow_factor * omega): their crossings of omega are all seen */
    double balance;       /* N-link: the largest force across a link over its tension among
                           * the polished equilibria (round-off: ~1e-16) */
    size_t wrong_parity;  /* method 3: curves whose crossings of omega have the wrong parity, a
                           * sign that the continuation jumped between curves or stopped short:
                           * a branch born below omega that does not return to the hanging
                           * chain with an even number, or an isolated curve (its equilibria
                           * grouped by born_at) with an odd number; 0 expected */
    size_t refined;       /* N-link: roots of either scan polished from a shot in long double,
                           * where Newton's method from the double shot's link angles did not
                           * converge (roots within round-off of each other) */
    size_t coincident;    /* N-link: roots of one scan whose polished shape is that of another
                           * root of the same scan (every link angle within 1e-8 rad), merged;
                           * 0 expected: each root a distinct equilibrium */
} whirl_equilibria;

/* Every planar relative equilibrium (up to the mirror image r -> -r) of the N-link chain c at
 * omega, or of the continuous chain with tip mass tip_mass when c is NULL. params may be NULL
 * (the defaults). On success *out holds a result to free with whirl_equilibria_free. Errors:
 * GSL_EINVAL on omega not in (0, WHIRL_EQUILIBRIA_OMEGA_MAX] (the continuum: below
 * WHIRL_EQUILIBRIA_CONTINUUM_OMEGA_MAX), a chain of more than WHIRL_EQUILIBRIA_LINKS_MAX links
 * or bad params; GSL_EDOM when omega is within 1e-10 relative of a critical rate (a branch is
 * born there: its equilibrium is not separated from the hanging chain); GSL_EMAXITER when a
 * scan needs more than shot_budget evaluations; GSL_ETOL when its count of roots does not settle
 * (the same at two successive refinements) within its levels; GSL_ERANGE when the shot
 * overflows (the radii of a shape span more than ~1e150); WHIRL_EINTERRUPTED on a stop
 * request.
 * @param c the N-link chain, or NULL for the continuous chain
 * @param tip_mass the continuum's point mass at the free end [M], >= 0 (with c NULL)
 * @param omega the rotation rate [sqrt(g/L)]
 * @param params the parameters, or NULL for whirl_equilibria_defaults
 * @param out out: the result, to free with whirl_equilibria_free
 * @return GSL_SUCCESS, or GSL_EINVAL, GSL_EDOM, GSL_EMAXITER, GSL_ETOL, GSL_ERANGE,
 *     WHIRL_EINTERRUPTED as above
 */
WHIRL_API int whirl_equilibria_find(const whirl_chain *c, double tip_mass, double omega,
                                    const whirl_equilibria_params *params,
                                    whirl_equilibria **out);
/* Frees the result. NULL is a no-op.
 * @param e the result, or NULL
 */
WHIRL_API void whirl_equilibria_free(whirl_equilibria *e);

/* Where whirl_equilibria_find_progress stands: its stage and, within it, the items done. The
 * N-link chain's stages: 1 the scan over the tip radius, 2 the scan over the top link's angle,
 * 3 and 4 their roots polished, 5 the continuation (at once without params.continuation), 6 the
 * shapes and their verdicts; the continuum's: 1 the shapes of the modes born below omega, 2 the
 * scan. A scan and the continuation count as one item each. */
typedef struct whirl_equilibria_progress {
    int stage, stages;  /* the stage under way (1..stages) and their count */
    size_t done, total; /* its items done (0..total) and their count (>= 1) */
} whirl_equilibria_progress;
typedef void (*whirl_equilibria_progress_fn)(void *ctx, const whirl_equilibria_progress *at);

/* whirl_equilibria_find reporting its progress: progress(ctx, at) at the start of every stage
 * and after its items (at most about 256 times a stage), stage and done never decreasing. It
 * must not call the search.
 * @param c the N-link chain, or NULL for the continuous chain
 * @param tip_mass the continuum's point mass at the free end [M], >= 0 (with c NULL)
 * @param omega the rotation rate [sqrt(g/L)]
 * @param params the parameters, or NULL for whirl_equilibria_defaults
 * @param progress called as above, or NULL: none
 * @param ctx passed to progress
 * @param out out: the result, to free with whirl_equilibria_free
 * @return as whirl_equilibria_find
 */
WHIRL_API int whirl_equilibria_find_progress(const whirl_chain *c, double tip_mass, double omega,
                                             const whirl_equilibria_params *params,
                                             whirl_equilibria_progress_fn progress, void *ctx,
                                             whirl_equilibria **out);

#define WHIRL_EQUILIBRIA_OMEGA_MAX 1000.0 /* N-link: above it the mode-1 tip radius is within
                                           * ~1e-12 of the chain's length, beyond the scan */
#define WHIRL_EQUILIBRIA_CONTINUUM_OMEGA_MAX 50.0 /* continuum: 31 shapes, each shot an ODE */
#define WHIRL_EQUILIBRIA_LINKS_MAX 200 /* the budget: scans of O(N) shots, dense Newton
                                       * steps O(N^3) and eigen-solves O((4N)^3) per shape */

#ifdef __cplusplus
}
#endif

#endif
