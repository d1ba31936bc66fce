/* whirl: steady shapes of a hand-swung chain: the pivot driven on a horizontal circle and air drag
 * acting in the inertial frame.
 *
 * The hand moves the top on the circle (eps cos wt, eps sin wt, 0) at rate omega. In the frame
 * co-rotating at omega about z the pivot is fixed at (eps, 0, 0) and a shape at rest there is an
 * equilibrium of gravity, the centrifugal force and the air drag of its inertial velocity
 * v = omega z x r (no Coriolis force at rest). The drag on a chain element of length ds is
 * -c ds v (linear) plus -c2 ds |v| v (quadratic), exactly the air drag of whirl_model in
 * dynamics.h (mass i of the N-link chain gets the weight l_i). The shapes are out of the plane:
 * the chain trails behind the pivot. With eps = c = c2 = 0 they are the free shapes of steady.h.
 *
 * Frame of the results: co-rotating, z up, the pivot at (eps, 0, 0); heights are measured from
 * the pivot (z <= 0 for a hanging chain).
 *
 * Two models, chosen by the chain argument of every function:
 *  - chain == NULL: the continuous uniform chain (length 1, mass 1, g = 1) with an optional point
 *    mass params->tip_mass (no drag on it) at the free end;
 *  - chain != NULL: the N-link chain (any lengths and masses, gravity chain->gravity); its shapes
 *    are exact relative equilibria (every mass in force balance to round-off); tip_mass must be 0
 *    (the chain carries its own masses).
 *
 * Unknowns: the tip's horizontal position (X, Y). The shape follows by integrating the force
 * balance up from the free end (continuum) or by the recursion over the masses (N-link); the two
 * equations are that the top lands on the pivot (eps, 0). Newton's method with the Jacobian of
 * the variational equations. Without drag the angular momentum about the axis is conserved along
 * the chain, so every shape lies in the vertical plane through the axis and the pivot (with
 * eps = 0: any such plane; the phase is fixed there) and Y = 0 replaces the second equation.
 * With eps = 0 and air drag nothing can supply the torque the drag takes (the pivot force passes
 * through the axis): only the hanging chain is steady (GSL_EDOM).
 *
 * Node count of a shape (documented definition, the free one when eps = c = c2 = 0): the
 * horizontal displacements d(s) = (x - eps, y) of the chain from the vertical line through the
 * pivot are projected onto their principal direction e (the dominant eigenvector of the
 * arclength-weighted 2 x 2 moment matrix of d; e oriented so that the tip projects positive);
 * nodes = 1 (the pivot) + the sign changes of d.e along the chain below the pivot. For the
 * continuum d is sampled at WHIRL_DRIVEN_NODE_SAMPLES points; for the N-link chain at its masses.
 * A driven chain whose tip is on the far side of the axis from the pivot (a shape of mode 1
 * hanging "anti-phase") thus still counts 1 node: the crossing of the axis near the top belongs
 * to the pivot node that it becomes when eps -> 0. */
#ifndef WHIRL_DRIVEN_H
#define WHIRL_DRIVEN_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Samples of the continuum's shape used to count its nodes. */
#define WHIRL_DRIVEN_NODE_SAMPLES 1024
/* The most folds whirl_driven_branch records. */
#define WHIRL_DRIVEN_FOLD_MAX 32

/* The parameters of the driven problem (never changed by the library). */
typedef struct whirl_driven_params {
    /* omega, drive_radius, air_drag and air_drag_quadratic are whirl_model's (dynamics.h), with
       the same names, meaning and units */
    double omega;              /* rotation rate of the hand and of the frame [sqrt(g/L)], > 0 */
    double drive_radius;       /* eps: radius of the pivot's circle [L], >= 0 */
    double air_drag;           /* c in [0, 1e6]: linear air drag per unit length [M/(L T)]: -c ds v */
    double air_drag_quadratic; /* c2 in [0, 1e6]: quadratic air drag per unit length [M/L^2]:
                                  -c2 ds |v| v */
    double tip_mass;           /* continuum only: point mass at the free end [M], >= 0; must be
                                  0 with an N-link chain */
} whirl_driven_params;

/* p <- the drive and drag of the model m (omega, drive_radius, air_drag, air_drag_quadratic;
 * tip_mass 0). The model's internal damping, frame and dimension play no part in a steady shape.
 * @param p out: the driven parameters
 * @param m the model
 */
WHIRL_API void whirl_driven_params_from_model(whirl_driven_params *p, const whirl_model *m);

/* One steady shape. */
typedef struct whirl_driven_info {
    double omega;          /* rotation rate [sqrt(g/L)] */
    double tip[3];         /* position of the free end (co-rotating frame, z from the pivot) */
    double tip_r;          /* horizontal distance of the free end from the axis [L] */
    double top_force[3];   /* force of the support on the chain at the pivot [M g] */
    double top_tension;    /* |top_force| [M g] */
    double fold_function;  /* det of d(pivot miss)/d(X, Y): changes sign at a fold */
    int nodes;             /* node count (definition above) */
    double residual;       /* distance of the top from the pivot at the solution [L] */
    int iterations;        /* Newton iterations of the last solve */
} whirl_driven_info;

/* Node count (the definition above) of the polyline pos (3 per point, npts >= 2 points, the
 * pivot first, at (eps, 0, *) in the co-rotating frame), the points below the pivot weighted by
 * weight[0..npts-2] (the link lengths; NULL: equal weights, the continuum's equal samples).
 * @param eps the pivot's radius [L]
 * @param npts the points, >= 2
 * @param pos the points' positions (x, y, z), 3 npts, the pivot first
 * @param weight the weights of points 1..npts-1, npts - 1, or NULL for equal weights
 * @return the node count, >= 1
 */
WHIRL_API int whirl_driven_nodes(double eps, size_t npts, const double *pos, const double *weight);

/* The steady shape whose tip is near guess = (X, Y) (Newton from there). GSL_EINVAL on bad
 * parameters, GSL_EDOM for eps = 0 with drag, GSL_EMAXITER if Newton does not converge (the
 * message says how far it got). On success info describes the shape.
 * @param chain the N-link chain, or NULL for the continuous chain
 * @param params the rate, the pivot's circle and the drag
 * @param guess the tip's position (X, Y) to start Newton's method from [L]
 * @param info out: the shape's summary
 * @return GSL_SUCCESS, GSL_EINVAL on bad parameters, GSL_EDOM for eps = 0 with drag, GSL_EMAXITER
 *     if Newton's method does not converge
 */
WHIRL_API int whirl_driven_solve(const whirl_chain *chain, const whirl_driven_params *params,
                                 const double guess[2], whirl_driven_info *info);

/* The shape of mode k (1 <= k <= WHIRL_MODE_MAX) at params: seeded by the free shape of mode k
 * at params->omega (whirl_continuum_solve or whirl_nlink_solve) with its tip on the pivot's side
 * of the axis (side = +1) or on the opposite side (side = -1), then followed by natural
 * continuation from eps = 0 to params->drive_radius (no drag), then from no drag to params' drag.
 * Mode 0 is the near-axis shape: seeded by the hanging chain (tip on the axis, a free shape at
 * every rate; side is checked but plays no part), it is the small response that the drive pulls
 * out of the vertical chain: below the first birth omega_1 in phase with the pivot (the shape
 * of mode 1, side +1, continued below omega_1), above it opposite to the pivot; past the fold
 * where it meets mode 1's shape of side -1 it is the smallest of the triple-valued response
 * (mode 1 with side +1 and -1, and mode 0). It does not exist at a birth omega_k itself nor
 * between a birth and that fold (GSL_EDOM).
 * GSL_EDOM if mode k has no free shape at params->omega, or if the continuation breaks down:
 * the shape disappears at a fold on the way, in eps (small shapes near omega_k) or in the drag
 * (the support's torque eps F_y(top) must equal the drag's omega int (c + c2 omega rho) rho^2 ds,
 * rho the distance from the axis, so a small eps cannot carry a wide shape against much drag).
 * @param chain the N-link chain, or NULL for the continuous chain
 * @param params the rate, the pivot's circle and the drag
 * @param mode the mode k, 1..WHIRL_MODE_MAX
 * @param side +1: the seed's tip on the pivot's side of the axis, -1: opposite
 * @param info out: the shape's summary
 * @return GSL_SUCCESS, or GSL_EDOM if mode k has no shape at params->omega or the continuation
 *     breaks down
 */
WHIRL_API int whirl_driven_mode(const whirl_chain *chain, const whirl_driven_params *params,
                                int mode, int side, whirl_driven_info *info);

/* Samples the shape whose tip is at tip_xy (from a solve) from the pivot to the free end:
 * arclength s from the pivot, position (x, y, z) (z from the pivot) and tension there. Continuum:
 * npts >= 2 points equally spaced in s; N-link chain: npts must be chain->n + 1 (the pivot and
 * the masses; tension[i] of link i, tension[0] = tension[1]). The pivot point is where the
 * integration ends: it lands on (eps, 0, 0) only for a solution.
 * @param chain the N-link chain, or NULL for the continuous chain
 * @param params the rate, the pivot's circle and the drag
 * @param tip_xy the tip's position (X, Y) of a solution [L]
 * @param npts the points: >= 2 for the continuum, chain->n + 1 for the N-link chain
 * @param s out: the arclengths from the pivot [L], npts
 * @param x out: the positions' x [L], npts
 * @param y out: their y [L], npts
 * @param z out: their z, 0 at the pivot [L], npts
 * @param tension out: the tensions [M g], npts
 * @return GSL_SUCCESS, or a status with a message on bad arguments
 */
WHIRL_API int whirl_driven_sample(const whirl_chain *chain, const whirl_driven_params *params,
                                  const double tip_xy[2], size_t npts, double *s, double *x,
                                  double *y, double *z, double *tension);

/* A branch of shapes against omega (whirl_driven_branch). */
typedef struct whirl_driven_curve {
    size_t capacity;          /* room for points */
    size_t n;                 /* points filled, in the order of the continuation */
    whirl_driven_info *point; /* the shapes */
    int *fold;                /* fold[j] = 1 if point j is a refined fold, else 0 */
    size_t n_folds;           /* folds found (the fold points are also in point[]) */
    double fold_omega[WHIRL_DRIVEN_FOLD_MAX]; /* their rates [sqrt(g/L)], in order found */
    int complete;             /* 1 if the branch left [omega_min, omega_max]; 0 if it stopped
                                 at the capacity or on a step that would not converge */
} whirl_driven_curve;

/* A curve with room for capacity (>= 2) points. NULL on no memory or capacity < 2.
 * @param capacity the room in points, >= 2
 * @return the curve, to free with whirl_driven_curve_free; NULL with a message on capacity < 2 or
 *     no memory
 */
WHIRL_API whirl_driven_curve *whirl_driven_curve_alloc(size_t capacity);
/* Frees the curve. NULL is a no-op.
 * @param curve the curve, or NULL
 */
WHIRL_API void whirl_driven_curve_free(whirl_driven_curve *curve);

/* Follows the branch through the shape start (a solution at params->omega, e.g. from
 * whirl_driven_mode) by pseudo-arclength continuation in (X, Y, omega), leaving start in the
 * direction of decreasing omega (direction = -1) or increasing omega (+1), until omega leaves
 * [omega_min, omega_max] or the curve is full. step: the largest arclength step in (X, Y, omega)
 * (> 0; steps adapt below it). A fold (a rate where the branch turns back: d omega/d arclength
 * changes sign, where fold_function changes sign) is refined to the point where fold_function
 * vanishes and inserted as a point with fold = 1. GSL_EINVAL on bad arguments; a step that fails
 * to converge even at the smallest step ends the branch with complete = 0 and GSL_SUCCESS.
 * @param chain the N-link chain, or NULL for the continuous chain
 * @param params the pivot's circle and the drag; params->omega the start's rate
 * @param start a solution at params->omega (whirl_driven_mode)
 * @param direction -1: towards decreasing omega, +1: increasing
 * @param omega_min the lowest rate followed [sqrt(g/L)]
 * @param omega_max the highest rate followed [sqrt(g/L)]
 * @param step the largest arclength step in (X, Y, omega), > 0
 * @param curve out: the points and the folds (whirl_driven_curve_alloc)
 * @return GSL_SUCCESS (also when a step would not converge: curve->complete 0), or GSL_EINVAL on
 *     bad arguments
 */
WHIRL_API int whirl_driven_branch(const whirl_chain *chain, const whirl_driven_params *params,
                                  const whirl_driven_info *start, int direction, double omega_min,
                                  double omega_max, double step, whirl_driven_curve *curve);

/* Called by whirl_driven_branch_tick with the curve so far, after every point (or fold and
 * point) appended, and once more at the end. It must not call the continuation. */
typedef void (*whirl_driven_branch_tick_fn)(void *data, const whirl_driven_curve *curve);

/* whirl_driven_branch reporting its progress: tick(data, curve) after every point appended
 * (the stop request is polled right after, so that a stop requested there ends the branch
 * before the next step: WHIRL_EINTERRUPTED, the points so far kept in curve).
 * @param chain the N-link chain, or NULL for the continuous chain
 * @param params the pivot's circle and the drag; params->omega the start's rate
 * @param start a solution at params->omega (whirl_driven_mode)
 * @param direction -1: towards decreasing omega, +1: increasing
 * @param omega_min the lowest rate followed [sqrt(g/L)]
 * @param omega_max the highest rate followed [sqrt(g/L)]
 * @param step the largest arclength step in (X, Y, omega), > 0
 * @param curve out: the points and the folds (whirl_driven_curve_alloc)
 * @param tick called after every point appended, or NULL: none
 * @param data passed to tick
 * @return as whirl_driven_branch; WHIRL_EINTERRUPTED on a stop request
 */
WHIRL_API int whirl_driven_branch_tick(const whirl_chain *chain,
                                       const whirl_driven_params *params,
                                       const whirl_driven_info *start, int direction,
                                       double omega_min, double omega_max, double step,
                                       whirl_driven_curve *curve, whirl_driven_branch_tick_fn tick,
                                       void *data);

#ifdef __cplusplus
}
#endif

#endif
