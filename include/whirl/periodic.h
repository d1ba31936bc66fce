/* whirl: the chain under a periodic pivot motion: pivot paths, periodic motions found by
 * shooting on the period map, and their Floquet multipliers.
 *
 * A pivot path is a few Fourier terms in x, y, z at the rate omega (period T = 2 pi / omega):
 *   p_k(t) = sum_{j=1..J} c_kj cos(j omega t) + s_kj sin(j omega t),   k = x, y, z,
 * in the inertial frame (z up; 2D models move in the x-z plane and need no y terms). The circle
 * (r cos, r sin, 0) is the drive of whirl_model.drive_radius; the ellipse, the line in any
 * direction (vertical shaking among them) and the figure of eight are presets.
 *
 * A periodic motion is a state y* at t = 0 with P(y*) = y*, P the period map (the flow from 0 to
 * T of the Cartesian formulation, whirl/dynamics.h, by the Gauss method of order 4 with a fixed
 * step T / steps and the projection after every step). Its neighbourhood is described in the
 * tangent space of the constraint manifold: per link, the components of the link's displacement
 * and rate along (dim - 1) unit vectors across the link (the along-link parts follow from the
 * constraints), 2 (dim - 1) N coordinates in all. The monodromy matrix is the derivative of the
 * discrete period map in these coordinates, from the variational equations integrated with the
 * motion by the same Gauss steps (or, as a cross-check, by central differences of P); Newton's
 * method on P(y) - y with it. The Floquet multipliers are its eigenvalues;
 * their error is estimated by a second solve with the step halved (the Gauss method is of order
 * 4: the error of the finer value is |mu(h/2) - mu(h)| / 15, Richardson). */
#ifndef WHIRL_PERIODIC_H
#define WHIRL_PERIODIC_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The most harmonics of a pivot path: a hand's path is smooth, a few terms describe it. */
#define WHIRL_PIVOT_HARMONICS_MAX 8

typedef struct whirl_pivot_path {
    double omega; /* rate of the path [sqrt(g/L)], > 0: the period is 2 pi / omega */
    int harmonics; /* J, 1..WHIRL_PIVOT_HARMONICS_MAX: the terms j = 1..J are used */
    double c[3][WHIRL_PIVOT_HARMONICS_MAX]; /* c[k][j - 1]: amplitude of cos(j omega t) in axis k [L] */
    double s[3][WHIRL_PIVOT_HARMONICS_MAX]; /* s[k][j - 1]: amplitude of sin(j omega t) in axis k [L] */
} whirl_pivot_path;

/* Presets at the rate omega (GSL_EINVAL on omega <= 0 or a length that is not finite):
 * circle   (r cos wt, r sin wt, 0): whirl_model's drive of radius r;
 * ellipse  (a cos wt, b sin wt, 0): semi-axes a along x, b along y;
 * line     amplitude a cos(wt) along the direction (dx, dy, dz) (normalised; (0, 0, 1): vertical
 *          shaking); GSL_EINVAL on a zero direction;
 * eight    (a sin wt, b sin 2wt, 0): a figure of eight, half-width a along x, b along y.
 * @param path out: the path
 * @param omega the rate [sqrt(g/L)], > 0
 * @param r the radius [L], finite
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_pivot_circle(whirl_pivot_path *path, double omega, double r);
/* The ellipse preset.
 * @param path out: the path
 * @param omega the rate [sqrt(g/L)], > 0
 * @param a the semi-axis along x [L], finite
 * @param b the semi-axis along y [L], finite
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_pivot_ellipse(whirl_pivot_path *path, double omega, double a, double b);
/* The line preset.
 * @param path out: the path
 * @param omega the rate [sqrt(g/L)], > 0
 * @param a the amplitude [L], finite
 * @param dir the direction (dx, dy, dz), not zero (normalised here)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_pivot_line(whirl_pivot_path *path, double omega, double a, const double dir[3]);
/* The figure-of-eight preset.
 * @param path out: the path
 * @param omega the rate [sqrt(g/L)], > 0
 * @param a the half-width along x [L], finite
 * @param b the half-width along y [L], finite
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_pivot_eight(whirl_pivot_path *path, double omega, double a, double b);

/* Parses text into path at the rate omega. The grammar (lengths with an optional unit suffix,
 * m, cm or mm, whirl_parse_quantity):
 *   circle:R | ellipse:A,B | line:A[,DX,DY,DZ] (default direction x) | vertical:A |
 *   eight:A,B | fourier:TERM[,TERM...] with TERM = AXIS J KIND=LENGTH, AXIS x, y or z, J the
 *   harmonic 1..WHIRL_PIVOT_HARMONICS_MAX, KIND c (cosine) or s (sine): "fourier:x1c=1cm,y1s=6mm".
 * length [m]: the chain's length in SI units, the lengths are then in m and divided by it; 0:
 * dimensionless, a unit suffix is then refused. dim 2 refuses y terms. GSL_EINVAL with a
 * one-line message naming the bad term (path unchanged).
 * @param text the path as text
 * @param omega the rate [sqrt(g/L)], > 0
 * @param length the chain's length [m] for lengths in SI units, or 0: dimensionless
 * @param dim the model's dimension, 2 or 3
 * @param path out: the path (unchanged on failure)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_pivot_parse(const char *text, double omega, double length, int dim,
                                whirl_pivot_path *path);

/* GSL_SUCCESS if path is valid for a model of dimension dim (omega > 0 and finite, at most
 * WHIRL_OMEGA_MAX; harmonics in range; every amplitude finite; no y term in 2D), else GSL_EINVAL
 * naming the term.
 * @param path the path
 * @param dim the model's dimension, 2 or 3
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_pivot_check(const whirl_pivot_path *path, int dim);

/* The period 2 pi / omega.
 * @param path the path
 * @return the period [sqrt(L/g)]
 */
WHIRL_API double whirl_pivot_period(const whirl_pivot_path *path);

/* Position, velocity and acceleration of the pivot at t (3 each); a whirl_pivot_fn with params
 * the path (whirl_dyn_set_pivot).
 * @param t the time [sqrt(L/g)]
 * @param p out: the position [L], 3
 * @param pv out: the velocity, 3
 * @param pa out: the acceleration, 3
 * @param path the path (a whirl_pivot_path *)
 */
WHIRL_API void whirl_pivot_eval(double t, double p[3], double pv[3], double pa[3], void *path);

/* ---- periodic motions ---- */

typedef struct whirl_periodic whirl_periodic; /* workspace of one chain on one path */

/* A workspace for the conservative chain c (not owned) in dimension dim (2 or 3) with its pivot
 * on path (copied). NULL with a message on invalid arguments or no memory.
 * @param c the chain (not owned)
 * @param dim 2 or 3
 * @param path the pivot's path (copied)
 * @return the workspace, to free with whirl_periodic_free; NULL with a message on invalid
 *     arguments or no memory
 */
WHIRL_API whirl_periodic *whirl_periodic_alloc(const whirl_chain *c, int dim,
                                               const whirl_pivot_path *path);
/* A workspace for the chain of model with its damping and drag: model->chain (not owned) in
 * model->dim, with the air drag c, c2 and the internal damping D of whirl_model (dynamics.h:
 * the same forces as the time integrator's), the pivot on path (copied). The model's frame and
 * omega are replaced by the inertial frame and the path's rate (the internal damping is then
 * measured in the frame co-rotating at the path's rate, as whirl_model defines it; a
 * continuation in the rate moves that frame with it); the model must have no drive radius, no
 * ramp and no seed forcing. With no damping and no drag it is whirl_periodic_alloc's workspace.
 * With any, the period map contracts volume and the multipliers are not in reciprocal pairs:
 * the verdict's margin leaves the reciprocal-pair error out (it is still reported), and the
 * continuation's torus test is the dissipative one (whirl_periodic_path).
 * NULL with a message on invalid arguments (the model's, as whirl_dyn_alloc's) or no memory.
 * @param model the model: its chain (not owned), dim, air_drag, air_drag_quadratic and
 *     internal_damping
 * @param path the pivot's path (copied)
 * @return the workspace, to free with whirl_periodic_free; NULL with a message on invalid
 *     arguments or no memory
 */
WHIRL_API whirl_periodic *whirl_periodic_alloc_model(const whirl_model *model,
                                                     const whirl_pivot_path *path);
/* Frees the workspace. NULL is a no-op.
 * @param w the workspace, or NULL
 */
WHIRL_API void whirl_periodic_free(whirl_periodic *w);
/* 1 if the chain of w is damped or dragged (whirl_periodic_alloc_model), else 0.
 * @param w the workspace
 * @return 1 with dissipation, else 0
 */
WHIRL_API int whirl_periodic_dissipative(const whirl_periodic *w);

/* The dynamics of w (inertial frame, Cartesian formulation, the pivot on the path, omega the
 * path's): for whirl_dyn_set_state, whirl_dyn_state_from_shape and runs.
 * @param w the workspace
 * @return the dynamics, owned by w
 */
WHIRL_API whirl_dyn *whirl_periodic_dyn(whirl_periodic *w);
/* Length of a state (whirl_dyn_size) and of the tangent coordinates, 2 (dim - 1) N.
 * @param w the workspace
 * @return the length of a state
 */
WHIRL_API size_t whirl_periodic_state_size(const whirl_periodic *w);
/* The length of the tangent coordinates, 2 (dim - 1) N.
 * @param w the workspace
 * @return the length of the tangent coordinates
 */
WHIRL_API size_t whirl_periodic_tangent_size(const whirl_periodic *w);

/* y <- the chain hanging straight down (inverted 0) or standing straight up (inverted 1) at
 * t = 0, moving with the pivot.
 * @param w the workspace
 * @param inverted 0: hanging straight down, 1: standing straight up
 * @param y out: the state at t = 0, whirl_periodic_state_size(w)
 * @return GSL_SUCCESS, or a status with a message
 */
WHIRL_API int whirl_periodic_start_vertical(whirl_periodic *w, int inverted, double *y);

/* How the monodromy is formed; both give the derivative of the same discrete period map. */
typedef enum {
    WHIRL_MONODROMY_VARIATIONAL = 0, /* the variational equations with the motion, by the same
                                        Gauss steps (the default; src/periodic/variational.c) */
    WHIRL_MONODROMY_DIFFERENCES = 1  /* central differences of the period map, extrapolated in
                                        their step (4 m periods; floor ~1e-11) */
} whirl_monodromy_method;

typedef struct whirl_periodic_params {
    int steps;    /* Gauss steps per period (>= 8); 0: 400. Raised to whirl_default_step's bound
                     of the start */
    double tol;   /* Newton's test: the largest component of P(y) - y (positions over L, rates
                     over omega_ref L, omega_ref = max(omega, sqrt(g/L))) at most tol; 0: 1e-10 */
    int max_iter; /* Newton iterations; 0: 30 */
    int refine;   /* 1: a second solve with 2 steps per step for the error estimate; 0: none
                     (errors reported as 0) */
    whirl_monodromy_method monodromy; /* default WHIRL_MONODROMY_VARIATIONAL */
} whirl_periodic_params;

typedef enum {
    WHIRL_FLOQUET_STABLE = 0,   /* every multiplier inside the unit circle beyond its error */
    WHIRL_FLOQUET_NEUTRAL = 1,  /* the largest on the unit circle within its error */
    WHIRL_FLOQUET_UNSTABLE = 2  /* the largest outside beyond its error */
} whirl_floquet_verdict;

typedef enum {
    WHIRL_FLOQUET_EDGE_PLUS_ONE = 0,  /* a real multiplier through +1 (fold of cycles) */
    WHIRL_FLOQUET_EDGE_MINUS_ONE = 1, /* a real multiplier through -1 (period doubling) */
    WHIRL_FLOQUET_EDGE_COMPLEX = 2    /* a complex pair through the unit circle (torus; for the
                                         conservative chain: two pairs that meet on it) */
} whirl_floquet_edge;

typedef struct whirl_periodic_result {
    size_t count;          /* multipliers: 2 (dim - 1) N */
    double *re, *im;       /* the multipliers (finer step), by decreasing modulus (owned by w,
                              valid until the next solve) */
    double *err;           /* error estimate of each, |mu(h/2) - mu(h)| / 15 (0 without refine) */
    double residual;       /* the scaled max |P(y) - y| reached (finer step) */
    int iterations;        /* Newton iterations (both solves) */
    int steps;             /* steps per period of the finer solve */
    double period;         /* T [sqrt(L/g)] */
    double max_modulus;    /* the largest |mu| */
    double max_modulus_err;
    double reciprocal_err; /* max over mu_i of min_j |mu_i mu_j - 1|: 0 for the exact
                              conservative chain (symplectic monodromy); the damped chain's
                              multipliers are not in pairs: a distance, not an error (the
                              verdict does not use it) */
    double orbit_change;   /* max |y*(h/2) - y*(h)| (scaled as the residual; 0 without refine) */
    whirl_floquet_verdict verdict;
    double growth;         /* unstable: the largest |mu| per period; else 1 */
    double efold_periods;  /* unstable: 1 / ln |mu|max periods; else 0 */
    double efold_time;     /* unstable: T / ln |mu|max [sqrt(L/g)]; else 0 */
    whirl_floquet_edge edge; /* unstable: how the largest left the circle; else the nearest */
    double edge_distance;  /* neutral: the angle [rad] to that edge (for a collision of two
                              multipliers on the circle, half the angle between them; the
                              damped chain: 0, its largest is on the edge); stable (only the
                              damped chain): 1 - |mu|max */
} whirl_periodic_result;

/* Finds the periodic motion near the start y (length whirl_periodic_state_size; overwritten by
 * the motion's state at t = 0) by Newton's method on the period map, then its multipliers.
 * params NULL: every default with refine 1. GSL_EMAXITER with the residual in the message if Newton's
 * method does not converge (result->count 0: no multiplier of a motion not found; y holds the
 * last iterate); GSL_EINVAL on bad arguments; an integration's status (and its message) if a
 * period cannot be integrated; WHIRL_EINTERRUPTED on a stop request.
 * @param w the workspace
 * @param y in: the start; out: the periodic motion's state at t = 0, whirl_periodic_state_size(w)
 * @param params the parameters, or NULL for the defaults with refine 1
 * @param result out: the multipliers (valid until the next solve), their errors and the verdict
 * @return GSL_SUCCESS, GSL_EMAXITER if Newton's method does not converge, GSL_EINVAL, an
 *     integration's status, or WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_periodic_find(whirl_periodic *w, double *y,
                                  const whirl_periodic_params *params,
                                  whirl_periodic_result *result);

/* Where a solve stands, for a progress display. */
typedef struct whirl_periodic_progress {
    int solve;        /* 1: the coarser solve, 2: the finer (or the only one without refine) */
    int iteration;    /* Newton's iteration, from 0 */
    double residual;  /* the scaled |P(y) - y| of that iterate (inf before the first) */
    double monodromy; /* the part of the monodromy under way that is done, 0..1 (0: none) */
} whirl_periodic_progress;

/* tick(data, progress) is called during whirl_periodic_find: after every residual and about 16
 * times per monodromy. It must not call w. NULL (the default): none.
 * @param w the workspace
 * @param tick the callback, or NULL: none
 * @param data passed to tick
 */
WHIRL_API void whirl_periodic_set_tick(whirl_periodic *w,
                                       void (*tick)(void *data,
                                                    const whirl_periodic_progress *progress),
                                       void *data);

/* The monodromy of the last successful solve (finer step): tangent_size x tangent_size, row
 * major, valid until the next solve; NULL before.
 * @param w the workspace
 * @return the monodromy, owned by w, or NULL before a successful solve
 */
WHIRL_API const double *whirl_periodic_monodromy(const whirl_periodic *w);

/* Advances the state y of w at t = 0 (or any whole number of periods) by periods whole periods
 * with steps Gauss steps per period (a perturbed run; WHIRL_EINTERRUPTED on a stop).
 * @param w the workspace
 * @param y the state at t = 0, advanced in place
 * @param steps the Gauss steps per period
 * @param periods how many whole periods
 * @return GSL_SUCCESS, an integration's status, or WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_periodic_run(whirl_periodic *w, double *y, int steps, int periods);

/* Reads the tangent coordinates of the difference y1 - y0 of two states near y0 (length
 * tangent_size): the perturbation's size as the multipliers act on it.
 * @param w the workspace
 * @param y0 the reference state, whirl_periodic_state_size(w)
 * @param y1 the state near it, whirl_periodic_state_size(w)
 * @param coords out: the tangent coordinates, whirl_periodic_tangent_size(w)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message on a NULL argument
 */
WHIRL_API int whirl_periodic_tangent(whirl_periodic *w, const double *y0, const double *y1,
                                     double *coords);

/* ---- stability charts of the vertically shaken chain ----
 *
 * The chain hanging straight down (or standing straight up) moves with a pivot shaken
 * vertically, A cos(omega t): the vertical state is a periodic motion for every omega and A, so
 * no Newton's method is needed, only the monodromy of its linearisation, which decouples
 * exactly into one Hill equation per mode of the pencil G v = lambda M v of the straight chain
 * (M its mass matrix, g G gravity's stiffness): q_k'' + sigma lambda_k (g + z'') q_k = 0
 * (sigma = +1 hanging, -1 inverted). With M_k the 2 x 2 monodromy of mode k,
 *   det(M - I) = prod_k (2 - tr M_k)^planes,   det(M + I) = prod_k (2 + tr M_k)^planes,
 * and each factor f_+k = 2 - tr M_k (f_-k = 2 + tr M_k) is smooth in (omega, A) and changes sign
 * where mode k's pair of multipliers passes +1 (resp. -1): the edges of the chart, one family
 * of curves per mode and kind, so that two modes' edges that cross do not interfere. Without
 * drag A cos(omega t) is even in t and each factor is the product of two functions of half a
 * period, f_+k = -4 u' v, f_-k = 4 u v' at T/2 (u, v the solutions with (u, u') = (1, 0),
 * (0, 1) at t = 0): a tongue's two edges (Mathieu's a_n, b_n) are simple zeros of the two
 * however thin it is, one family per mode, kind and function. An edge is
 * a curve A(omega), located per rate by Brent's method on A to the tolerance and followed from
 * rate to rate with the previous point as the centre of the next bracket; a mode is scanned on
 * `rows` amplitudes for new curves at the first rate, where the count of a family's edges
 * disagrees with the signs at the range's ends, and (hanging) where a tip 2 omega_k / n of its
 * tongues (omega_k = sqrt(g lambda_k), the unshaken chain's frequencies) lies between two rates
 * (src/periodic/chart.c, chart_modes.c). With linear air drag: whirl_chart_vertical_damped. */

typedef struct whirl_chart_params {
    int inverted;     /* 0: the hanging chain (its tongues of instability); 1: the inverted chain
                         (its region of stability, Acheson's); default 0 */
    double omega_min, omega_max; /* the rates [sqrt(g/L)], 0 < omega_min < omega_max (no
                                    default) */
    int columns;      /* rates, equally spaced, both ends included (>= 2); 0: 200 */
    double amp_min;   /* the lowest amplitude [L], >= 0; 0: amp_max / rows (at A = 0 the
                         tongues touch their edges without crossing them) */
    double amp_max;   /* the highest amplitude [L], > amp_min (no default) */
    int rows;         /* amplitudes of a column's scan for new curves (>= 2); 0: 200 */
    int steps;        /* steps per period of the coarser monodromy of each mode (Magnus, order
                         4), the finer has twice (>= 8); 0: 200; raised per mode so that a step
                         turns the mode's phase by at most 1/16 rad */
    double tol;       /* an edge's bracket in amplitude at most this wide [L]; 0: 1e-10 */
} whirl_chart_params;

typedef struct whirl_chart_point {
    whirl_floquet_edge kind; /* WHIRL_FLOQUET_EDGE_PLUS_ONE or _MINUS_ONE */
    int curve;        /* the curve's number, from 0 in the order found; a curve is one mode's
                         and one kind's, and a tongue's two edges joined at its tip (hanging)
                         share one number, that of the edge found first (numbers may skip); a
                         tongue of order n >= 3 brings both edges down on the side of the lower
                         rates, so its curve has a point on each edge at a rate */
    int column;       /* the rate's index, from 0 */
    double omega;     /* [sqrt(g/L)] */
    double amplitude; /* [L] */
    double err;       /* its error estimate [L]: the bracket's width plus the shift of the root
                         by the extrapolation in the step (det from steps and 2 steps, order 4) */
} whirl_chart_point;

typedef struct whirl_chart_progress {
    int column, columns; /* the rate under way (from 0) and the count */
    int curves;          /* curves found so far */
    long monodromies;    /* the modes' 2 x 2 monodromies computed so far */
} whirl_chart_progress;

/* Called once per point as soon as it is located (in order of rate); a non-zero return stops
 * the chart with that status (with no message of the chart's). */
typedef int (*whirl_chart_row_fn)(void *data, const whirl_chart_point *point);
/* Called after every column and every scan. */
typedef void (*whirl_chart_tick_fn)(void *data, const whirl_chart_progress *progress);

/* The chart of the chain c (dim 2: the x-z plane) with its pivot shaken vertically.
 * GSL_EINVAL with a message on bad parameters; WHIRL_EINTERRUPTED on a stop request (the points
 * handed to row so far stand); an integration's status. tick may be NULL.
 * @param c the chain
 * @param dim 2 or 3 (the same chart: in 3D each mode's factor appears once per plane)
 * @param params the chart's range, resolution and tolerance
 * @param row called for every point, or NULL
 * @param row_data passed to row
 * @param tick called after every column and scan, or NULL
 * @param tick_data passed to tick
 * @return GSL_SUCCESS, GSL_EINVAL, WHIRL_EINTERRUPTED, row's status, or an integration's status
 */
WHIRL_API int whirl_chart_vertical(const whirl_chain *c, int dim, const whirl_chart_params *params,
                                   whirl_chart_row_fn row, void *row_data,
                                   whirl_chart_tick_fn tick, void *tick_data);

/* The chart of whirl_chart_vertical with linear air drag: the force -c l_i v_i on mass i (v_i
 * its inertial velocity; c = air_drag, whirl_model's air_drag, per unit length [M/(L T)]). On a
 * chain of one mass per length (m_i / l_i equal) the drag's matrix is gamma M, gamma = c l_i /
 * m_i (c for a uniform chain in the units of whirl/common.h), the drag of the pivot's velocity
 * z' adds gamma z' to gravity, and each mode obeys
 * q_k'' + gamma q_k' + sigma lambda_k (g + z'' + gamma z') q_k = 0: with q = exp(-gamma t / 2) y
 * an undamped Hill equation shifted by -gamma^2 / 4, its monodromy exp(-gamma T / 2) times y's,
 * determinant exp(-gamma T) (src/periodic/chart_modes.c). The edges are where the mode's trace is +-(1 + exp(-gamma T)) (a
 * multiplier through +1 or -1; a complex pair stays inside the unit circle): the hanging
 * chain's tongues lift off A = 0 (no tips), each tongue's edges one curve through its lowest
 * point (joined where that point is sharper than the rates' grid). air_drag 0 is
 * whirl_chart_vertical, bit for bit. GSL_EINVAL with a message also for a drag negative or not
 * finite, a chain whose m_i / l_i differ (the drag would couple its modes: only a drag
 * proportional to the mass matrix keeps them apart), or gamma pi / omega_min over 700
 * (src/periodic/chart.c).
 * @param c the chain
 * @param dim 2 or 3
 * @param params the chart's range, resolution and tolerance
 * @param air_drag c >= 0, finite [M/(L T)]
 * @param row called for every point, or NULL
 * @param row_data passed to row
 * @param tick called after every column and scan, or NULL
 * @param tick_data passed to tick
 * @return GSL_SUCCESS, GSL_EINVAL, WHIRL_EINTERRUPTED, row's status, or an integration's status
 */
WHIRL_API int whirl_chart_vertical_damped(const whirl_chain *c, int dim,
                                          const whirl_chart_params *params, double air_drag,
                                          whirl_chart_row_fn row, void *row_data,
                                          whirl_chart_tick_fn tick, void *tick_data);

/* Called with a chart's state after its first `done` rates (NUL-terminated lines, valid during
 * the call): once before the first rate computed, then after each finished rate; a non-zero
 * return stops the chart with that status. The rows handed out before the call are the finished
 * rates' (a rate's points depend on the state and the rate alone). */
typedef int (*whirl_chart_save_fn)(void *data, int done, const char *state);

/* whirl_chart_vertical_damped (air_drag 0: whirl_chart_vertical) resumed: from the state that
 * save was handed after some rates (NULL: from the first rate), computing only the rates after
 * them, bit for bit as in the chart that never stopped (whirl periodic --chart --resume). The
 * state is the lines
 *   vertical columns=J count=C curves=K tips=T [drag=C]
 *   curve I KIND MODE ID ALIVE TIPWARD A1 A0 W1 TIP FILL_TOP   (K of them, or the line none)
 *   tip OMEGA MODE                                             (T of them)
 * the doubles with 17 digits; it is checked whole against params and air_drag (counts, ranges,
 * finite numbers, the drag it was saved with): GSL_EINVAL with "state line N: what" otherwise.
 * The caller keeps the rows of the finished rates; those computed here are the others
 * (src/periodic/chart_state.c).
 * @param c the chain (the one the state was saved with)
 * @param dim 2 or 3
 * @param params the chart's range, resolution and tolerance (the state's)
 * @param air_drag c >= 0, finite [M/(L T)] (the state's)
 * @param state the text save was handed, or NULL
 * @param row called for every point, or NULL
 * @param row_data passed to row
 * @param tick called after every column and scan, or NULL
 * @param tick_data passed to tick
 * @param save called with the state before the first rate computed and after each, or NULL
 * @param save_data passed to save
 * @return GSL_SUCCESS, GSL_EINVAL, GSL_ENOMEM, WHIRL_EINTERRUPTED, row's or save's status, or an
 *         integration's status
 */
WHIRL_API int whirl_chart_vertical_resume(const whirl_chain *c, int dim,
                                          const whirl_chart_params *params, double air_drag,
                                          const char *state, whirl_chart_row_fn row,
                                          void *row_data, whirl_chart_tick_fn tick,
                                          void *tick_data, whirl_chart_save_fn save,
                                          void *save_data);

/* A chart written by whirl periodic --chart hanging|inverted -o FILE (stopped, or finished) read
 * back, as its --resume reads it: data (size bytes) must begin with the header the command line
 * writes for params (its defaults applied), the uniform chain of links links, air_drag and the
 * units (physical 0: dimensionless; 1: SI for the chain's length [m], mass [kg] and gravity
 * [m/s^2], mass_given 0 as without --mass: M = 1 kg assumed, a comment line saying so), the
 * header naming the first line that differs; its rows are checked (their fields, in the chart's
 * range, none twice, as many as its "# found: points=" line says, a curve its state has begun
 * and a rate it has finished) and its "# state: " lines (whirl_chart_vertical_resume checks
 * them in turn). Then row is called for each row in the file's order (curve from 0, column -1:
 * not recorded; omega, amplitude and err in the file's units, as written), and state once with
 * the rates finished and the state's text, to resume from. GSL_EINVAL with the one-line
 * message ("'PATH' was not written by a chart with these options: line N has ...", "PATH:N:
 * WHY: the file cannot be trusted ...") for a file refused; GSL_ENOMEM.
 * @param data the file's bytes
 * @param size their count
 * @param path the file's name in messages (NULL: "the chart's file")
 * @param params the chart's parameters, as for whirl_chart_vertical
 * @param links the uniform chain's links (whirl periodic's --links)
 * @param air_drag c >= 0 (--drag; 0: none)
 * @param physical 0: dimensionless units; 1: SI
 * @param length the chain's length [m] (physical 1)
 * @param mass the chain's mass [kg] (physical 1)
 * @param gravity the gravity [m/s^2] (physical 1)
 * @param mass_given 0: the mass assumed, as without --mass (physical 1)
 * @param row called for every row, or NULL
 * @param row_data passed to row
 * @param state called once with the rates finished and the state, or NULL
 * @param state_data passed to state
 * @return GSL_SUCCESS, GSL_EINVAL, GSL_ENOMEM, or row's or state's status
 */
WHIRL_API int whirl_chart_vertical_read(const char *data, size_t size, const char *path,
                                        const whirl_chart_params *params, int links,
                                        double air_drag, int physical, double length,
                                        double mass, double gravity, int mass_given,
                                        whirl_chart_row_fn row, void *row_data,
                                        whirl_chart_save_fn state, void *state_data);

/* ---- continuation of periodic motions ----
 *
 * A periodic motion followed in the path's rate, its amplitude or its ellipticity by
 * pseudo-arclength continuation (src/periodic/cycle_path.c): the unknowns are the state y at
 * t = 0 and the parameter p, the equations P_p(y) = y and the arclength condition; the tangent is the null
 * vector of the bordered Jacobian [M - I, dP/dp] of the period map. At every point the
 * multipliers, the verdict and the test functions
 *   fold test  f_+ = det(M - I)   (a multiplier, or a pair, through +1),
 *   flip test  f_- = det(M + I)   (through -1: period doubling),
 * each reported as sign(det) |det|^(1/m) (the geometric mean of the factors: no overflow at
 * large N), and the torus test D = prod_{k < l} (rho_k - rho_l)^2 over the pairs mu, 1/mu of
 * multipliers (rho = mu + 1/mu), which changes sign where two pairs on the unit circle meet and
 * leave it (the conservative chain's torus bifurcation, a Krein collision; a meeting of two
 * real pairs off the circle changes its sign too and is not an event). A sign change of a test
 * along a step is an event, located by Brent's method on the step's arclength, every evaluation
 * a corrected point at s and 2 s steps per period with the test extrapolated (Richardson, order
 * 4): to event_tol in the arclength. A +1 event where the parameter's component of the tangent
 * changes sign is a fold of cycles; one where it does not is a branch point (a symmetric branch
 * that goes on: the vertical chain's +1 tongue edges). A change of the verdict along a step that
 * no sign change explains (pairs equal by a symmetry make the tests touch zero: the 3D hanging
 * chain's two planes) is located on the pairs' rho, the eigenvalues of M + M^-1.
 * The damped or dragged chain (whirl_periodic_alloc_model) has no pairs: its torus test is
 *   P = prod_{i < j} (mu_i mu_j - 1)   over all m multipliers,
 * the determinant of the bialternate product M (.) M - I, reported as sign |P|^(1/factors):
 * a complex pair mu, conj mu contributes |mu|^2 - 1, so P changes sign where a complex pair
 * crosses the unit circle (the Neimark-Sacker, or torus, bifurcation; a sign change from two
 * real multipliers with mu_i mu_j = 1 is not an event), located as the other events; a change
 * of the verdict that no test explains is located on |mu|max - 1. */

typedef enum {
    WHIRL_CYCLE_OMEGA = 0,    /* the path's rate omega [sqrt(g/L)] */
    WHIRL_CYCLE_AMPLITUDE = 1, /* the path's amplitude [L]: the path scaled so that its largest
                                  Fourier amplitude (over c and s of every axis and harmonic) is
                                  the parameter */
    WHIRL_CYCLE_ELLIPTICITY = 2 /* the ellipticity e (dimensionless): the path's y terms scaled
                                   by 1 - e, the start's path being e = 0 (the circle of radius
                                   a becomes the ellipse of semi-axes a along x, a (1 - e) along
                                   y); the path must move along y */
} whirl_cycle_parameter;

typedef enum {
    WHIRL_CYCLE_POINT = 0,           /* a point of the branch */
    WHIRL_CYCLE_FOLD = 1,            /* +1, the branch turns back in the parameter */
    WHIRL_CYCLE_BRANCH = 2,          /* +1, the branch goes on (another branch crosses it) */
    WHIRL_CYCLE_PERIOD_DOUBLING = 3, /* -1 */
    WHIRL_CYCLE_TORUS = 4            /* two pairs meet on the unit circle and leave it */
} whirl_cycle_event;

typedef struct whirl_cycle_params {
    whirl_cycle_parameter parameter;
    double min, max;  /* the parameter's range: the branch ends where it leaves it (no default;
                         the start must lie in it) */
    int direction;    /* +1: leave the start towards larger values of the parameter, -1: smaller */
    double step;      /* the largest arclength step, in the state (positions over L, rates over
                         omega_ref L) and the parameter; 0: 0.05 */
    int max_points;   /* points at most (the start included); 0: 10000 */
    int steps;        /* Gauss steps per period (>= 8; raised as whirl_periodic_find raises them,
                         at the start and at both ends of the range); 0: 400. The events are
                         located with these and twice as many */
    double tol;       /* Newton's test as whirl_periodic_params.tol; 0: 1e-10 */
    int max_iter;     /* Newton's iterations at the start; 0: 30 */
    double event_tol; /* an event's bracket in the arclength; 0: 1e-10 */
} whirl_cycle_params;

typedef struct whirl_cycle_point {
    whirl_cycle_event event;
    long index;        /* points so far (events not counted): the point's, or the next one's */
    double parameter;  /* the continued parameter */
    double omega;      /* the path's rate [sqrt(g/L)] */
    double amplitude;  /* the path's largest Fourier amplitude [L] */
    double err;        /* an event: the estimate of the parameter's error (the bracket's width
                          and the change by the extrapolation); a point: 0 */
    double arclength;  /* from the start */
    double tangent;    /* d parameter / d arclength (a fold: 0 within the error) */
    double fold_test, flip_test; /* f_+, f_- (above) */
    double torus_test; /* D (above) as sign |D|^(1 / its factors); 1 with one pair */
    size_t count;      /* multipliers */
    const double *re, *im; /* the multipliers by decreasing modulus (valid during the call) */
    double max_modulus, reciprocal_err;
    whirl_floquet_verdict verdict; /* as whirl_periodic_result's, without the step's refinement:
                                      margin max(2 reciprocal_err, 1e-9) (damped: 1e-9) */
    whirl_floquet_edge edge;
    double residual;   /* the scaled |P(y) - y| */
    int iterations;    /* corrector iterations */
    const double *y;   /* the state at t = 0 (whirl_periodic_state_size; valid during the call) */
} whirl_cycle_point;

typedef struct whirl_cycle_progress {
    long points, events;
    double parameter;  /* of the last point */
    double step;       /* the arclength step under way */
    int iteration;     /* the corrector's iteration */
    double residual;   /* its residual */
} whirl_cycle_progress;

/* Called for every point and event in the order of the branch (an event before the point that
 * ends its step); a non-zero return stops the continuation with that status. */
typedef int (*whirl_cycle_row_fn)(void *data, const whirl_cycle_point *point);
/* Called after every corrector iteration and every point. */
typedef void (*whirl_cycle_tick_fn)(void *data, const whirl_cycle_progress *progress);

/* Follows the periodic motion of w near y from w's path (its rate, its amplitude or e = 0 the
 * start, in [min, max]): Newton's method at the start (as whirl_periodic_find), then the branch
 * until the parameter leaves [min, max] (GSL_SUCCESS), max_points (GSL_SUCCESS), a stop request
 * (WHIRL_EINTERRUPTED: the rows handed out stand), or a corrector that does not converge even
 * at a step of 1e-6 of the largest (GSL_EMAXITER with the residual reached and the parameter).
 * y holds the last point's state and w's path the last point's (a failure at the start: as
 * whirl_periodic_find's, no row). GSL_EINVAL on bad parameters (an amplitude continuation of a
 * path that does not move among them). tick may be NULL.
 * @param w the workspace, its path at the start
 * @param y in: a state near the start's motion; out: the last point's state
 * @param params the continuation's parameter, range, steps and tolerances
 * @param row called for every point and event, or NULL
 * @param row_data passed to row
 * @param tick called after every corrector iteration and point, or NULL
 * @param tick_data passed to tick
 * @return GSL_SUCCESS, GSL_EINVAL, GSL_EMAXITER, WHIRL_EINTERRUPTED, row's status, or the failure
 *     of the start as whirl_periodic_find's; with a message
 */
WHIRL_API int whirl_periodic_path(whirl_periodic *w, double *y, const whirl_cycle_params *params,
                                  whirl_cycle_row_fn row, void *row_data,
                                  whirl_cycle_tick_fn tick, void *tick_data);

/* The name of the event: "point", "fold", "branch", "period-doubling", "torus".
 * @param e the event
 * @return the name (static text), "unknown" for no event
 */
WHIRL_API const char *whirl_cycle_event_name(whirl_cycle_event e);

/* y <- the steady shape of mode (its node count) of the circle drive on w's path (a circle of
 * radius > 0, dim 3), the seed's tip on the pivot's side (side 1) or opposite (-1), as
 * whirl_stability_driven_mode finds it (with w's air drag: whirl_driven_mode's shape), at t = 0 turning with the pivot: the circle's periodic
 * motion. GSL_EINVAL on another path; GSL_EDOM if the mode does not exist at the rate.
 * @param w the workspace, its path a circle of radius > 0, dim 3
 * @param mode the mode (node count) >= 1
 * @param side +1: the seed's tip on the pivot's side, -1: opposite
 * @param y out: the state at t = 0, whirl_periodic_state_size(w)
 * @return GSL_SUCCESS, GSL_EINVAL on another path, GSL_EDOM if the mode does not exist at the rate,
 *     or the solver's failure; with a message
 */
WHIRL_API int whirl_periodic_start_steady(whirl_periodic *w, int mode, int side, double *y);

/* ---- the ellipticity chart of the hand-swung chain ----
 *
 * The pivot on the ellipse (a cos wt, a (1 - e) sin wt, 0), e the ellipticity (0: the circle
 * drive of radius a, 1: the line along x). At each rate the steady shape of the circle drive's
 * mode K (whirl_periodic_start_steady), if stable at e = 0, is followed in e
 * (WHIRL_CYCLE_ELLIPTICITY) to its first event, where it is lost: e_crit(omega), located as the
 * continuation's events are (to 1e-8). The curve ends on e = 0 where the steady shape changes
 * its stability between two rates: there the circle's motion is followed in the rate from the
 * stable one and its first event located (src/periodic/chart_ellipse.c). */

typedef struct whirl_ellipse_chart_params {
    double radius;    /* a, the circle's radius and the ellipse's semi-axis along x [L], > 0 */
    int mode;         /* the steady shape's mode (node count), >= 1; 0: 2 */
    int side;         /* its seed's tip on the pivot's side (1) or opposite (-1); 0: 1 */
    double omega_min, omega_max; /* the rates [sqrt(g/L)], 0 < omega_min < omega_max */
    int columns;      /* rates, equally spaced, both ends included (>= 2); 0: 50 */
    double e_max;     /* the largest ellipticity followed, in (0, 1]; 0: 1 */
    int steps;        /* Gauss steps per period, as whirl_cycle_params.steps; 0: 400 */
    double step;      /* the continuation's largest arclength step; 0: 0.01 (a tongue entered
                         and left within one step is passed over) */
    double tol;       /* Newton's test, as whirl_cycle_params.tol; 0: 1e-10 */
} whirl_ellipse_chart_params;

typedef struct whirl_ellipse_point {
    whirl_cycle_event event; /* how the shape is lost there (fold, branch, period doubling,
                                torus); WHIRL_CYCLE_POINT: not lost up to e_max (the row at
                                e_max) */
    int curve;          /* the curve's number from 0: a run of rates stable at e = 0 */
    int column;         /* the rate's index from 0; -1: an end of the curve on e = 0 */
    double omega;       /* [sqrt(g/L)] */
    double ellipticity; /* e_crit (0 at an end) */
    double err;         /* the location's error estimate: in e at a rate, in omega at an end */
    double max_modulus; /* the largest multiplier's modulus at the event */
} whirl_ellipse_point;

typedef struct whirl_ellipse_chart_progress {
    int column, columns; /* the rate under way (from 0) and the count */
    int curves;          /* curves begun */
    long points;         /* rows handed out */
    int failed;          /* continuations that failed before their first event (Newton's
                            method or the corrector did not converge, no unique tangent, an
                            event not located): no row for them */
    double parameter;    /* the continuation's parameter under way (e, or omega at an end) */
} whirl_ellipse_chart_progress;

typedef int (*whirl_ellipse_chart_row_fn)(void *data, const whirl_ellipse_point *point);
typedef void (*whirl_ellipse_chart_tick_fn)(void *data,
                                            const whirl_ellipse_chart_progress *progress);

/* The chart of the chain c (3D) by rate: row for every point as it is located (in the order of
 * the rates; a non-zero return stops the chart with that status), tick after every point of a
 * continuation and every rate (may be NULL). GSL_EINVAL with a message on bad parameters;
 * WHIRL_EINTERRUPTED on a stop request (the points handed out stand); an integration's status.
 * @param c the chain
 * @param params the circle's radius, the mode, the rates and the continuation's settings
 * @param row called for every point, or NULL
 * @param row_data passed to row
 * @param tick called after every point of a continuation and every rate, or NULL
 * @param tick_data passed to tick
 * @return GSL_SUCCESS, GSL_EINVAL, WHIRL_EINTERRUPTED, row's status, or an integration's status
 */
WHIRL_API int whirl_chart_ellipse(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                                  whirl_ellipse_chart_row_fn row, void *row_data,
                                  whirl_ellipse_chart_tick_fn tick, void *tick_data);

/* whirl_chart_ellipse resumed: from the state that save (whirl_chart_save_fn) was handed after
 * some rates (NULL: from the first rate), computing only the rates after them, bit for bit as in
 * the chart that never stopped (whirl periodic --chart ellipse --resume). The state is the line
 *   ellipse columns=J prev=P curve=C failed=F
 * (J rates finished; P whether the last was stable at e = 0, -1 before the first rate; C the
 * curve under way, -1: none; F the failed continuations), checked against params: GSL_EINVAL
 * with "state line 1: what" otherwise. The caller keeps the rows of the finished rates.
 * @param c the chain (the one the state was saved with)
 * @param params the chart's parameters (the state's)
 * @param state the text save was handed, or NULL
 * @param row called for every point, or NULL
 * @param row_data passed to row
 * @param tick called after every point of a continuation and every rate, or NULL
 * @param tick_data passed to tick
 * @param save called with the state before the first rate computed and after each, or NULL
 * @param save_data passed to save
 * @return GSL_SUCCESS, GSL_EINVAL, WHIRL_EINTERRUPTED, row's or save's status, or an
 *         integration's status
 */
WHIRL_API int whirl_chart_ellipse_resume(const whirl_chain *c,
                                         const whirl_ellipse_chart_params *params,
                                         const char *state, whirl_ellipse_chart_row_fn row,
                                         void *row_data, whirl_ellipse_chart_tick_fn tick,
                                         void *tick_data, whirl_chart_save_fn save,
                                         void *save_data);

/* A chart written by whirl periodic --chart ellipse -o FILE read back, as its --resume reads it
 * (whirl_chart_vertical_read's rules and arguments): row is called for each row in the file's
 * order (event WHIRL_CYCLE_POINT for "none"; column the rate's index, -1 at an end; omega and
 * an end's err in the file's units; max_modulus NAN: the file has none), state once.
 * @param data the file's bytes
 * @param size their count
 * @param path the file's name in messages (NULL: "the chart's file")
 * @param params the chart's parameters, as for whirl_chart_ellipse
 * @param links the uniform chain's links (--links)
 * @param physical 0: dimensionless units; 1: SI
 * @param length the chain's length [m] (physical 1)
 * @param mass the chain's mass [kg] (physical 1)
 * @param gravity the gravity [m/s^2] (physical 1)
 * @param mass_given 0: the mass assumed, as without --mass (physical 1)
 * @param row called for every row, or NULL
 * @param row_data passed to row
 * @param state called once with the rates finished and the state, or NULL
 * @param state_data passed to state
 * @return GSL_SUCCESS, GSL_EINVAL, GSL_ENOMEM, or row's or state's status
 */
WHIRL_API int whirl_chart_ellipse_read(const char *data, size_t size, const char *path,
                                       const whirl_ellipse_chart_params *params, int links,
                                       int physical, double length, double mass, double gravity,
                                       int mass_given, whirl_ellipse_chart_row_fn row,
                                       void *row_data, whirl_chart_save_fn state,
                                       void *state_data);

/* The name of the verdict: "stable", "neutral", "unstable".
 * @param v the verdict
 * @return the name (static text), "unknown" for no verdict
 */
WHIRL_API const char *whirl_floquet_verdict_name(whirl_floquet_verdict v);
/* The name of the edge: "+1", "-1", "complex".
 * @param e the edge
 * @return the name (static text), "unknown" for no edge
 */
WHIRL_API const char *whirl_floquet_edge_name(whirl_floquet_edge e);

#ifdef __cplusplus
}
#endif

#endif
