/* whirl: linear stability of the steady shapes of the N-link chain, and perturbed runs.
 *
 * A steady shape is a relative equilibrium: at rest in the frame co-rotating at omega about z.
 * Free shapes (whirl/steady.h) are planar; with a driven pivot (fixed at (eps, 0, 0) in that
 * frame) and inertial-frame air drag (whirl/driven.h) they are three-dimensional: the chain
 * trails. The linearisation in the co-rotating frame uses, per link j, the angles (a_j, b_j)
 * about the equilibrium direction u0_j of the link (the chart below; a = b = 0 at the shape),
 * q = (a_1..a_N, b_1..b_N), and reads
 *     M q'' + (G + C) q' + K q = 0,
 * M the mass matrix, G the skew gyroscopic (Coriolis) matrix, C the damping matrix (internal
 * damping and the velocity part of the air drag: symmetric positive semidefinite) and K the
 * stiffness: the Hessian of the effective potential (gravity minus centrifugal) plus, with air
 * drag, the non-symmetric position part of the drag (the drag depends on where a mass is, through
 * its inertial velocity omega z x x_i).
 * Chart of link j: u_j = cos a cos b u0_j + sin a cos b e1_j + sin b e2_j, with e2_j the unit
 * vector along the part of r = y (r = x if |u0_j . y| > 0.9) perpendicular to u0_j and
 * e1_j = u0_j x e2_j. For a shape in the x-z plane a_j is the in-plane and b_j the out-of-plane
 * angle (e2_j = y, e1_j = (cos t_j, 0, sin t_j), t_j the angle of the link from the downward
 * vertical towards +x).
 * Rotation about z is a symmetry only with the pivot on the axis and no air drag (eps = c = c2 =
 * 0): then the first-order form (size 4N) has zero eigenvalues (a Jordan pair without damping, a
 * single zero with damping), removed exactly by deflation; the growth rate is the largest real
 * part of the remaining eigenvalues. With a drive or drag there is no symmetry and nothing is
 * removed.
 *
 * Model: whirl_model of whirl/dynamics.h with dim = 3; drive_radius eps >= 0, air_drag c >= 0,
 * air_drag_quadratic c2 >= 0 and internal_damping D >= 0 as there; frame is ignored (the
 * linearisation is always in the co-rotating frame). */
#ifndef WHIRL_STABILITY_H
#define WHIRL_STABILITY_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/driven.h"
#include "whirl/dynamics.h"
#include "whirl/steady.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct whirl_stability whirl_stability; /* workspace of the linear analysis of N links */

/* A workspace for chains of n >= 1 links. NULL (whirl_last_error) on n = 0 or no memory.
 * @param n the links N, >= 1
 * @return the workspace, to free with whirl_stability_free; NULL with a message on n = 0 or no
 *     memory
 */
WHIRL_API whirl_stability *whirl_stability_alloc(size_t n);
/* Frees the workspace. NULL is a no-op.
 * @param w the workspace, or NULL
 */
WHIRL_API void whirl_stability_free(whirl_stability *w);

/* Forms M, G, C, K about the shape with nodes (x[i], y[i], z[i]), i = 0..N in the co-rotating
 * frame (i = 0: the pivot; as from whirl_driven_sample), rotating at model->omega. Only the
 * differences of the nodes are used: the link directions u0_j; the pivot is put at
 * (model->drive_radius, 0, 0) and mass i at the pivot plus sum_{j<=i} l_j u0_j. GSL_EINVAL if the
 * model is not supported (see above), the links' lengths differ from the chain's by more than
 * 1e-9 relative, or the shape is not an equilibrium (the load below some link has a component
 * across it larger than 1e-8 of M (g + omega^2 L) + (c + c2 omega L) omega L^2). For more than
 * 32 links (O(N^2) entries, a second at a few thousand links) the stop request is read at every
 * row: WHIRL_EINTERRUPTED (message set) and no linearisation.
 * @param w the workspace (of model->chain->n links)
 * @param model the model: the chain, omega, the drive and any damping or drag (dim 3)
 * @param x the nodes' x [L], N + 1, the pivot first
 * @param y the nodes' y [L], N + 1
 * @param z the nodes' z [L], N + 1
 * @return GSL_SUCCESS, GSL_EINVAL (unsupported model, wrong lengths, not an equilibrium) or
 *     WHIRL_EINTERRUPTED; with a message
 */
WHIRL_API int whirl_stability_linearise_3d(whirl_stability *w, const whirl_model *model,
                                           const double *x, const double *y, const double *z);

/* whirl_stability_linearise_3d for the shape in the x-z plane with nodes (r[i], 0, z[i]),
 * i = 0..N (as from whirl_nlink_positions).
 * @param w the workspace (of c->n links)
 * @param model the model: the chain, omega, and any damping (dim 3)
 * @param r the nodes' signed distances from the axis [L], N + 1, the pivot first
 * @param z the nodes' heights [L], N + 1
 * @return GSL_SUCCESS, GSL_EINVAL (unsupported model, wrong lengths, not an equilibrium) or
 *     WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_stability_linearise(whirl_stability *w, const whirl_model *model,
                                        const double *r, const double *z);

typedef enum {
    WHIRL_STABILITY_MASS = 0,      /* M, symmetric positive definite */
    WHIRL_STABILITY_GYROSCOPIC,    /* G, skew */
    WHIRL_STABILITY_DAMPING,       /* C, symmetric positive semidefinite (0 without internal
                                      damping and air drag) */
    WHIRL_STABILITY_STIFFNESS      /* K, symmetric without air drag; K s = 0 for the symmetry
                                      direction s */
} whirl_stability_matrix;

/* The 2N x 2N matrix (row-major, rows and columns ordered as q) of the last linearisation (NULL
 * after an interrupted eigen-solve, until the next linearisation).
 * @param w the workspace
 * @param which the matrix: M, G, C or K
 * @return the matrix, owned by w, or NULL without a linearisation
 */
WHIRL_API const double *whirl_stability_get_matrix(const whirl_stability *w,
                                                   whirl_stability_matrix which);

/* The symmetry direction s of the last linearisation (2N): the infinitesimal rotation about z,
 * (a_j, b_j) = (e1_j, e2_j) . (z x u0_j) (for a shape in the x-z plane a_j = 0, b_j = sin t_j);
 * all zero for a chain hanging straight down and for a model without the symmetry (drive or air
 * drag). NULL after an interrupted eigen-solve, until the next linearisation.
 * @param w the workspace
 * @return the direction, 2N values owned by w, or NULL without a linearisation
 */
WHIRL_API const double *whirl_stability_symmetry(const whirl_stability *w);

/* The nodes of the last linearisation (N + 1 each, pivot first): the pivot at (eps, 0, 0), mass i
 * at the pivot plus sum_{j<=i} l_j u0_j (valid until the next linearisation).
 * @param w the workspace
 * @param x out: the nodes' x [L], N + 1, owned by w
 * @param y out: the nodes' y [L], N + 1, owned by w
 * @param z out: the nodes' z [L], N + 1, owned by w
 */
WHIRL_API void whirl_stability_nodes(const whirl_stability *w, const double **x, const double **y,
                                     const double **z);

/* Eigenvalues of the last linearisation with the symmetry's zero eigenvalues removed: *count
 * (4N - 2 without damping, 4N - 1 with damping, 4N for a hanging chain, which has no symmetry
 * mode, and for a model with a drive or air drag, which has no symmetry), real and imaginary
 * parts (pointers into the workspace, valid until the next call), in
 * the chain's units of 1/time (sqrt(g/L) for the dimensionless chain).
 * Stop request: the dense solve (O(N^3), seconds from a few hundred links) cannot poll it, so for
 * more than 32 links it runs on a thread of its own while the caller polls every 20 ms; on a
 * stop the call returns WHIRL_EINTERRUPTED at once and the linearisation is gone (linearise
 * again), while the abandoned solve finishes in the background and frees its own memory.
 * @param w the workspace, after a linearisation
 * @param count out: how many eigenvalues
 * @param re out: their real parts [1/T] (into the workspace)
 * @param im out: their imaginary parts [1/T] (into the workspace)
 * @return GSL_SUCCESS, a status with a message, or WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_stability_eigenvalues(whirl_stability *w, size_t *count, const double **re,
                                          const double **im);

/* The largest real part among those eigenvalues (growth rate, 1/time). A value within round-off
 * of zero (|growth| <= 1e-10 max |lambda|: neutral stability of the conservative chain, whose
 * eigenvalues lie on the imaginary axis) is returned as exactly 0.
 * @param w the workspace, after a linearisation
 * @param growth out: the largest real part [1/T]; 0 for neutral stability
 * @return GSL_SUCCESS, a status with a message, or WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_stability_growth(whirl_stability *w, double *growth);

/* The index of the last linearisation: the number of negative eigenvalues of the symmetric part
 * of K, the Hessian of the amended potential (gravity minus centrifugal) in the co-rotating
 * frame (with air drag, of its symmetric part), eigenvalues within 1e-9 of the largest |K|
 * (the symmetry's zero) not counted. 0: a minimum, stable in the energy sense (also with
 * dissipation); > 0: a saddle, which without dissipation only the Coriolis coupling can hold
 * (linearly neutral at best) and with any complete dissipation is unstable (Kelvin-Tait-Chetaev;
 * Merkin, Gyroscopic Systems, 1956). GSL_EINVAL without a linearisation. The dense solve
 * (O(N^3)) runs as whirl_stability_eigenvalues's: on a stop request WHIRL_EINTERRUPTED at once
 * (the linearisation kept).
 * @param w the workspace, after a linearisation
 * @param index out: the negative directions of the amended potential (0: a minimum)
 * @return GSL_SUCCESS, GSL_EINVAL without a linearisation, or WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_stability_index(const whirl_stability *w, int *index);

/* tick(data) is called on the calling thread about every 20 ms while a dense solve of w runs on
 * its worker thread (whirl_stability_eigenvalues and whirl_stability_index above 32 links, whose
 * solves take minutes at a few thousand links): for a progress display. It must not call w.
 * NULL (the default) for none.
 * @param w the workspace
 * @param tick the callback, or NULL: none
 * @param data passed to tick
 */
WHIRL_API void whirl_stability_set_tick(whirl_stability *w, void (*tick)(void *data), void *data);

/* Linearises about the steady shape with tip radius tip_r (a root from whirl_nlink_solve or
 * whirl_nlink_branch at model->omega, nodes from whirl_nlink_positions) and returns its growth.
 * The model must have no drive and no air drag (GSL_EINVAL): those shapes are free ones. At high
 * rates the tip radius alone no longer fixes a shape (whirl_nlink_solve_nodes): the nodes
 * rebuilt from it are off the equilibrium, or refused as none (GSL_EINVAL). There use
 * whirl_stability_mode, or whirl_stability_linearise on the nodes of whirl_nlink_solve_nodes or
 * whirl_nlink_branch_nodes.
 * @param w the workspace
 * @param model the model, without drive and air drag
 * @param tip_r the shape's tip radius [L] (whirl_nlink_solve at model->omega)
 * @param growth out: the largest real part of the eigenvalues [1/T]
 * @return GSL_SUCCESS, GSL_EINVAL, or a status with a message
 */
WHIRL_API int whirl_stability_shape(whirl_stability *w, const whirl_model *model, double tip_r,
                                    double *growth);

/* The steady shape of mode k at model->omega (whirl_nlink_solve_nodes: the nodes from the
 * branch's link angles, an equilibrium to round-off at any rate), its linearisation and growth
 * rate (the branch is continued from its birth). info may be NULL. GSL_EDOM if the mode does not exist; GSL_EINVAL with a drive or
 * air drag (see whirl_stability_driven_mode).
 * @param w the workspace
 * @param model the model (its chain, omega, internal damping), without drive and air drag
 * @param mode the mode k, 1..N
 * @param info out: the shape's summary, or NULL
 * @param growth out: the largest real part of the eigenvalues [1/T]
 * @return GSL_SUCCESS, GSL_EDOM if the mode does not exist at omega, GSL_EINVAL with a drive or
 *     air drag, or a status with a message
 */
WHIRL_API int whirl_stability_mode(whirl_stability *w, const whirl_model *model, int mode,
                                   whirl_shape_info *info, double *growth);

/* The shape of the hand-swung chain of mode k at model->omega with the pivot's circle
 * model->drive_radius and the air drag of the model (whirl_driven_mode with side = +1 / -1: the
 * seed's tip on the pivot's side of the axis or opposite), its linearisation and growth rate.
 * info may be NULL. GSL_EDOM if the mode does not exist or its continuation fails (see
 * whirl_driven_mode). The nodes are then available from whirl_stability_nodes.
 * @param w the workspace
 * @param model the model: the chain, omega, the pivot's circle, the air drag and damping
 * @param mode the mode k, 1..WHIRL_MODE_MAX
 * @param side +1: the seed's tip on the pivot's side of the axis, -1: opposite
 * @param info out: the shape's summary, or NULL
 * @param growth out: the largest real part of the eigenvalues [1/T]
 * @return GSL_SUCCESS, GSL_EDOM if the mode does not exist or its continuation fails, GSL_EINVAL,
 *     or a status with a message
 */
WHIRL_API int whirl_stability_driven_mode(whirl_stability *w, const whirl_model *model, int mode,
                                          int side, whirl_driven_info *info, double *growth);

/* ---- modes of the linearisation (src/stability/stability_modes.c) ---- */

/* The eigenvectors of the last linearisation, one per eigenvalue of whirl_stability_eigenvalues
 * (same order, same values). Mode k is complex: q(t) = Re(v e^{lambda t}) with v the link-angle
 * part of the first-order form's right eigenvector (its velocity part is lambda v). */
typedef struct whirl_stability_modes {
    size_t links;          /* N */
    size_t count;          /* modes (as whirl_stability_eigenvalues) */
    double *re, *im;       /* lambda_k [1/T] */
    double *angle_re, *angle_im; /* count x 2N row-major: v_k in q = (a_1..a_N, b_1..b_N) [rad]
                                    (the chart of stability.h) */
    double *node_re, *node_im;   /* count x 3 (N + 1) row-major: the displacement (dx, dy, dz)
                                    of node i = 0..N (0: the pivot, fixed) from v_k,
                                    sum_{j<=i} l_j (a_j e1_j + b_j e2_j) [L] */
    int *krein;            /* per mode: the Krein signature of a neutral mode (|Re lambda| <=
                              1e-10 max |lambda|, Im lambda != 0) of the conservative chain (no
                              damping, no air drag: C = 0, K symmetric): the sign +1 / -1 of the energy
                              form (see stability_modes.c) on it; 0 otherwise */
} whirl_stability_modes;

/* Storage for the modes of n >= 1 links (4N of each). NULL (whirl_last_error) on n = 0 or no
 * memory.
 * @param n the links N, >= 1
 * @return the storage, to free with whirl_stability_modes_free; NULL with a message on n = 0 or no
 *     memory
 */
WHIRL_API whirl_stability_modes *whirl_stability_modes_alloc(size_t n);
/* Frees the storage. NULL is a no-op.
 * @param m the storage, or NULL
 */
WHIRL_API void whirl_stability_modes_free(whirl_stability_modes *m);

/* The eigenvalues (whirl_stability_eigenvalues, whose stop rules apply) and eigenvectors of the
 * last linearisation in w into out (allocated for w's links, GSL_EINVAL otherwise). Each mode is
 * scaled so that its largest node displacement |(dx, dy, dz)| is 1 [L] with the largest component
 * of that node real and positive (the link angles scaled alike). The eigenvectors are those of
 * the full first-order form (4N, dgeev with right vectors), matched to the deflated eigenvalues
 * by nearest distance (the symmetry's zero eigenvalues are left out as there). GSL_EFAILED if the
 * solve fails, WHIRL_EINTERRUPTED on a stop request before or during the eigenvalues' solve; the
 * solve with vectors (O(N^3), 2 (4N)^2 doubles: 256 MB at 1000 links) then runs on the calling
 * thread and does not poll the stop request.
 * @param w the workspace, after a linearisation
 * @param out out: the modes (whirl_stability_modes_alloc of w's links)
 * @return GSL_SUCCESS, GSL_EINVAL, GSL_EFAILED or WHIRL_EINTERRUPTED, with a message
 */
WHIRL_API int whirl_stability_eigenvectors(whirl_stability *w, whirl_stability_modes *out);

/* Each of the n link vectors l_j u0_j (3 per link, in place) turned in its chart (above) to
 * a = eps along_j / A, b = eps along_{n+j} / A, A = max |along| (2n angles, as a mode's
 * angle_re): u = cos a cos b u0 + sin a cos b e1 + sin b e2, lengths kept (the largest turn is
 * eps [rad]). GSL_EINVAL on NULL, n = 0, eps < 0, a non-finite or all-zero direction or a zero
 * link. (src/stability/stability_run.c)
 * @param n the links N, >= 1
 * @param links the link vectors, 3 per link, turned in place
 * @param eps the largest turn [rad], >= 0
 * @param along the direction in link angles (a_1..a_N, b_1..b_N), 2n, finite and not all zero
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_perturb_links_along(size_t n, double *links, double eps, const double *along);

/* ---- the linear stability map (src/stability/stability_map.c) ---- */

/* One point of a map: a free steady shape of the chain at a rate, given by its nodes (from
 * whirl_nlink_branch_nodes, or whirl_nlink_solve_nodes: at high rates the tip radius alone does
 * not fix the shape to round-off). */
typedef struct whirl_stability_point {
    double omega;        /* the rate [sqrt(g/L)] */
    const double *r, *z; /* the nodes r[i], z[i], i = 0..N (read, not owned) */
    int skip;            /* 1: not analysed (a point known from before) */
    double growth;       /* out: the growth rate of whirl_stability_growth [sqrt(g/L)] */
    int status;          /* out: GSL_SUCCESS once analysed, its failure, or -1 if not reached
                          * (skipped, or after a stop request) */
    int index;           /* out: the index of the shape (whirl_stability_index) */
} whirl_stability_point;

/* Called once per point analysed with the count analysed so far by this call, from the thread
 * that analysed it, one call at a time. */
typedef void (*whirl_stability_map_progress)(void *ctx, size_t done);

/* The linear stability of the free shapes pts[0..n) of the chain c with internal damping
 * damping (whirl_stability_linearise, whirl_stability_growth and whirl_stability_index in the
 * co-rotating frame, 3D),
 * the points shared over the OpenMP threads, a workspace each (the growth of a point does not
 * depend on the sharing). progress may be NULL. Returns GSL_SUCCESS; the failure of the earliest
 * point that failed, with its message (its status in pts[i].status); GSL_ENOMEM; or
 * WHIRL_EINTERRUPTED (message set) on a stop request, the points analysed until then kept.
 * @param c the chain
 * @param damping the internal damping D, >= 0
 * @param n the points
 * @param pts in: the points' rates, nodes and skip flags; out: their growth, status and index
 * @param progress called per point analysed, or NULL
 * @param ctx passed to progress
 * @return GSL_SUCCESS, the earliest failing point's status, GSL_EINVAL on a NULL chain or points or
 *     a bad damping, GSL_ENOMEM, or WHIRL_EINTERRUPTED; with a message
 */
WHIRL_API int whirl_stability_map(const whirl_chain *c, double damping, size_t n,
                                  whirl_stability_point *pts,
                                  whirl_stability_map_progress progress, void *ctx);

/* ---- perturbed time-domain runs (src/stability_run.c) ---- */

typedef enum {
    WHIRL_VERDICT_STABLE = 0,    /* the deviation stayed below 100 times the initial one; with
                                    the index (whirl_verdict_refine) a minimum of the amended
                                    potential: "stable (minimum)" */
    WHIRL_VERDICT_UNSTABLE = 1,  /* the deviation grew to 100 times the initial one */
    WHIRL_VERDICT_CONVERGING = 2, /* (dissipation: internal damping or air drag) it fell to
                                    1/100 of the initial one */
    WHIRL_VERDICT_NEUTRAL = 3    /* bounded, but a saddle of the amended potential (index > 0)
                                    held by the Coriolis coupling: linearly neutral, not stable
                                    in the energy sense, destabilised by any dissipation */
} whirl_verdict;

/* "stable (minimum)", "unstable", "converging", "neutral (gyroscopic)".
 * @param v the verdict
 * @return the verdict's name (static text); "stable (minimum)" for any value not listed
 */
WHIRL_API const char *whirl_verdict_name(whirl_verdict v);

/* The verdict v of a run or of the eigenvalues with the index of the shape
 * (whirl_stability_index): STABLE with index > 0 becomes NEUTRAL; others unchanged.
 * @param v the verdict
 * @param index the shape's index (whirl_stability_index)
 * @return the refined verdict
 */
WHIRL_API whirl_verdict whirl_verdict_refine(whirl_verdict v, int index);

/* The linear verdict from the growth rate (whirl_stability_growth) and the index: UNSTABLE if
 * growth > 0, CONVERGING if < 0, else STABLE (index 0) or NEUTRAL (index > 0).
 * @param growth the growth rate [1/T] (whirl_stability_growth)
 * @param index the shape's index (whirl_stability_index)
 * @return the verdict
 */
WHIRL_API whirl_verdict whirl_verdict_linear(double growth, int index);

typedef struct whirl_stability_run_params {
    double periods;      /* P > 0: length of the run in rotation periods 2 pi / omega; 100; at
                            most 1e9 time steps in all (GSL_EINVAL beyond) */
    double perturbation; /* EPS in (0, 1): each link direction turned by EPS [rad]; 1e-10
                            (small enough for a linear stretch of some 8 e-folds of growth when
                            an unstable mode turns a few links 1e3 times faster than it moves
                            the masses, as on long chains at high modes) */
    unsigned long seed;  /* seed of the random directions (GSL's mt19937); 1 */
    const char *method;  /* integrator (whirl_integrator_methods); "gauss2" */
    double dt;           /* fixed step [T]; 0: the default, min(period / 200, 2 / (nu + omega),
                            2 / kappa) for rk4, min(period / 200, 0.7 / (nu + omega + kappa))
                            for the other methods, nu = 2 sqrt(max_j (T_j / l_j) / min m)
                            bounding the chain's highest frequency under the shape's tensions
                            T_j, kappa = 16 D / (min m min l^2) + max_i (l_i / m_i) (c + 2 c2
                            omega (eps + L)) its fastest damping rate */
    /* Called at t = 0 and at every sample with the time and the deviation over the initial one
     * (NULL: none); a non-zero return stops the run, which then returns that status. */
    int (*observe)(double t, double ratio, void *data);
    void *observe_data;  /* passed to observe */
    /* NULL: the random perturbation above. Else 2N link angles (a_1..a_N, b_1..b_N) in the
     * chart of the shape's links (as whirl_stability_modes' angle_re): the links turned by
     * whirl_perturb_links_along with EPS (seed ignored); a mode of whirl_stability_eigenvectors
     * seeds the run along it. */
    const double *along;
} whirl_stability_run_params;

/* The defaults above.
 * @return the defaults
 */
WHIRL_API whirl_stability_run_params whirl_stability_run_defaults(void);

typedef struct whirl_stability_run_result {
    double sim_growth;    /* exponential rate fitted to log(deviation) over the stretch where it
                             grows from 100 times the initial deviation until some link has
                             turned by 1e-3 rad from the shape and it is 1e4 times the initial
                             one, or until 1e8 times or 1e-2 L, or to the end of the run [1/T];
                             0 unless the verdict is unstable */
    double max_deviation; /* largest deviation over the run / the initial one */
    double end_deviation; /* deviation at the end of the run / the initial one */
    double initial;       /* the initial deviation [L] */
    double duration;      /* time integrated [T] (shorter than P periods once settled) */
    double fit_from, fit_to; /* the fitted stretch [T] (0, 0 if none) */
    whirl_verdict verdict;
    whirl_integrator_stats stats;
} whirl_stability_run_result;

/* Runs the dynamics (3D, co-rotating frame, Cartesian formulation, the model's drive, air drag
 * and internal damping) from the steady shape with nodes (x[i], y[i], z[i]), i = 0..N (as for
 * whirl_stability_linearise_3d: only the link directions are used, the pivot is at (eps, 0, 0))
 * with every link direction turned by params->perturbation towards a random perpendicular
 * direction, at rest in the co-rotating frame, for params->periods rotation periods, sampling the
 * deviation from the shape 50 times per period: the RMS over the masses of their distance to
 * it, minimised over a rotation about z when that is a symmetry (eps = c = c2 = 0:
 * whirl_deviation), plain otherwise. Verdict rule: unstable as soon as the deviation reaches 100
 * times the initial one; converging (internal damping or air drag > 0 only) as soon as its
 * largest value over a whole rotation period is at most 1/100 of it, or if over the last period
 * of the run it is at most 1/10 of it; stable otherwise. The run stops early once the verdict is settled: unstable
 * after the fitted stretch ends (see sim_growth), converging at once. GSL_EINVAL on bad
 * parameters or links of the wrong length (1e-9 relative). Allocates its own dynamics and
 * integrator. The shape is not checked to be an equilibrium.
 * @param model the model (3D; its drive, air drag and internal damping are used)
 * @param x the shape's nodes' x [L], N + 1, the pivot first
 * @param y the nodes' y [L], N + 1
 * @param z the nodes' z [L], N + 1
 * @param params the run's parameters (whirl_stability_run_defaults)
 * @param result out: the verdict, the fitted growth, the deviations and the integrator's
 *     statistics
 * @return GSL_SUCCESS, GSL_EINVAL on bad parameters, or the status of a failed integration
 */
WHIRL_API int whirl_stability_run_shape(const whirl_model *model, const double *x, const double *y,
                                        const double *z, const whirl_stability_run_params *params,
                                        whirl_stability_run_result *result);

/* whirl_stability_run_shape from the free steady shape with tip radius tip_r (as for
 * whirl_stability_shape; whirl_nlink_positions at model->omega, so at high rates not the
 * equilibrium: there run from the nodes of whirl_nlink_solve_nodes or whirl_stability_nodes).
 * The model must have no drive and no air drag (GSL_EINVAL).
 * @param model the model, without drive and air drag
 * @param tip_r the shape's tip radius [L] (whirl_nlink_solve at model->omega)
 * @param params the run's parameters (whirl_stability_run_defaults)
 * @param result out: the verdict, the fitted growth, the deviations and the integrator's
 *     statistics
 * @return GSL_SUCCESS, GSL_EINVAL, or the status of a failed integration
 */
WHIRL_API int whirl_stability_run(const whirl_model *model, double tip_r,
                                  const whirl_stability_run_params *params,
                                  whirl_stability_run_result *result);

/* ---- exact stability windows of the free shapes (src/stability/nlink_windows.c, nlink_banded.c,
 * windows_search.c) ----
 * For the conservative chain (no damping, drag or drive) about a planar shape, the linearisation
 * splits into in-plane and out-of-plane blocks coupled only by the Coriolis force, and
 * mu = lambda^2 solves a real eigenproblem of size 2N (half the first-order form's 4N): the
 * shape is neutrally stable when every mu is real and negative. Window edges are located as the
 * roots of the discriminant of the two mu that collide there (Krein collision). */

typedef struct whirl_windows whirl_windows; /* workspace of the window search for N links */

/* A workspace for chains of n >= 1 links. NULL (whirl_last_error) on n = 0 or no memory.
 * @param n the links N, >= 1
 * @return the workspace, to free with whirl_windows_free; NULL with a message on n = 0 or no memory
 */
WHIRL_API whirl_windows *whirl_windows_alloc(size_t n);
/* Frees the workspace. NULL is a no-op.
 * @param w the workspace, or NULL
 */
WHIRL_API void whirl_windows_free(whirl_windows *w);

/* The linearisation workspace inside w (owned by w): whirl_windows_find leaves the last
 * linearisation of its search there.
 * @param w the workspace
 * @return the linearisation workspace, owned by w
 */
WHIRL_API whirl_stability *whirl_windows_linearisation(whirl_windows *w);

typedef struct whirl_spectrum {
    size_t count;          /* number of mu: 2N - 1 (2N for a chain hanging straight down) */
    const double *re, *im; /* mu = lambda^2 [1/T^2] (pointers into the workspace, valid until its
                              next use), complex ones in conjugate pairs */
    const int *signature;  /* per mu: the Krein signature, +1 / -1 the sign of the mode's energy
                              for a neutral mu (real negative, or a pair split by round-off), 0
                              otherwise; NULL unless asked for */
    double growth;         /* max Re sqrt(mu) [1/T]; 0 if neutral (values <= level count as 0) */
    double level;          /* round-off level of the growth: 1e-10 sqrt(max |mu|) [1/T] */
} whirl_spectrum;

/* The squared eigenvalues of the last linearisation in lin, which must be of a free planar shape
 * of the conservative chain (GSL_EINVAL otherwise: damping or drag, or the in-plane and
 * out-of-plane blocks coupled), with the rotation's zero removed. signatures != 0 computes the
 * eigenvectors too (about 2.5 times the work) and the signatures.
 * @param w the workspace
 * @param lin the linearisation (whirl_windows_linearisation(w), or a workspace of the same links)
 * @param signatures non-zero: the Krein signatures too
 * @param out out: the mu and the growth (pointers into w)
 * @return GSL_SUCCESS, GSL_EINVAL, or the eigen-solver's failure; with a message
 */
WHIRL_API int whirl_windows_spectrum(whirl_windows *w, const whirl_stability *lin, int signatures,
                                     whirl_spectrum *out);

/* The two mu of the last linearisation in lin nearest the real shift sigma [1/T^2], by the
 * Arnoldi method on (A' - sigma)^-1 = -(K' + sigma B)^-1 B (one LU factorisation, O(N^2) per
 * step), into mu_re[0..1], mu_im[0..1], nearest first; the rotation's mu = 0 is not removed.
 * Converged when both Ritz residuals are below 1e-13 of |1 / (mu - sigma)|; GSL_CONTINUE if not
 * within 40 steps (or sigma is an eigenvalue), GSL_EINVAL as whirl_windows_spectrum.
 * @param w the workspace
 * @param lin the linearisation
 * @param sigma the shift [1/T^2]
 * @param mu_re out: the real parts of the two mu [1/T^2], 2, nearest first
 * @param mu_im out: their imaginary parts [1/T^2], 2
 * @return GSL_SUCCESS, GSL_CONTINUE if the Arnoldi method does not converge, GSL_EINVAL, or a
 *     status with a message
 */
WHIRL_API int whirl_windows_pair(whirl_windows *w, const whirl_stability *lin, double sigma,
                                 double *mu_re, double *mu_im);

typedef struct whirl_windows_params {
    double omega_min, omega_max; /* the range of rates [sqrt(g/L)]; examined from
                                    max(omega_min, omega_k (1 + 1e-6)) to omega_max; 1, 10 */
    double scan_step;            /* spacing of the scan with signatures [sqrt(g/L)]; 0.25; at most
                                    100000 scan points (GSL_EINVAL beyond) */
    double tol;                  /* edges located to this in omega [sqrt(g/L)]; 1e-9 */
    int krylov;                  /* 1: near an edge only the colliding pair, by shift-and-invert
                                    Arnoldi (full solve if it does not converge), and for the
                                    N-link chain every rate by the banded path (the mu with
                                    |mu| <= omega^2, nlink_banded.c); 0: every evaluation a
                                    full (dense) solve; 1 */
} whirl_windows_params;

/* The defaults above.
 * @return the defaults
 */
WHIRL_API whirl_windows_params whirl_windows_defaults(void);

typedef struct whirl_window {
    double from, to;           /* the interval of rates where the mode is unstable [sqrt(g/L)] */
    int open_from, open_to;    /* 1: that end is the end of the range examined, not an edge */
    double freq_from, freq_to; /* frequency |Im lambda| where the pair meets at each edge [1/T]
                                  (0 at an open end or where a mu passes through 0) */
    double max_growth;         /* largest growth rate inside [1/T] */
    double at;                 /* the rate where it occurs [sqrt(g/L)] (to about 1e-6) */
    double err_from, err_to;   /* the continuum (whirl_cstab_windows): each closed edge is
                                  located again on a refined discretisation (degree + 8, shape
                                  tolerance / 100; where it moves by more than 1e-8, degree + 16
                                  and + 24 until two agree to 1e-8), which gives from and to; err
                                  is its last change, a bound of the discretisation error of the
                                  coarser and so an estimate (on the safe side) of the reported
                                  one's [sqrt(g/L)]; 0 at an open end, for an edge where a mu
                                  passes through 0, for the N-link chain */
} whirl_window;

typedef struct whirl_windows_stats {
    double omega_from, omega_to; /* the range examined [sqrt(g/L)] */
    size_t scan;           /* scan points */
    size_t shapes;         /* steady shapes solved */
    size_t solves_vectors; /* full eigen-solves with eigenvectors (scan, bisection) */
    size_t solves_values;  /* full eigen-solves, eigenvalues only */
    size_t solves_krylov;  /* shift-and-invert solves of the colliding pair */
    size_t approaches;     /* unstable rates found between scan points by minimising the
                              discriminant of a pair of opposite signatures that approach */
    size_t unresolved;     /* collisions of opposite signature narrower than tol without an
                              unstable rate found (touching, not opening) */
} whirl_windows_stats;

/* The windows of instability of mode k of the chain c (c->n links, as w) over the range of p,
 * in increasing omega, into windows[0..max-1], their number into *count (GSL_EINVAL if more
 * than max). The shapes are those of the branch born at omega_k (whirl_nlink_branch over the
 * scan, whirl_nlink_solve seeded from it in between). Windows that open and close between two
 * scan points are found when the pair that collides swaps its order in frequency (the ranks of
 * the stability.c header comment); a window nested between two others of the same pair less than
 * scan_step / 16 apart is not separated from them. GSL_EDOM if the mode does not exist in the
 * range, WHIRL_EINTERRUPTED on a stop request (between eigen-solves).
 * @param w the workspace (of c->n links)
 * @param c the chain
 * @param mode the mode k, 1..c->n
 * @param p the range and the search's parameters (whirl_windows_defaults)
 * @param windows out: the windows in increasing omega, max of them
 * @param max the room in windows
 * @param count out: how many windows
 * @param stats out: the work done, or NULL
 * @return GSL_SUCCESS, GSL_EINVAL (also with more than max windows), GSL_EDOM if the mode does not
 *     exist in the range, WHIRL_EINTERRUPTED
 */
WHIRL_API int whirl_windows_find(whirl_windows *w, const whirl_chain *c, int mode,
                                 const whirl_windows_params *p, whirl_window *windows, size_t max,
                                 size_t *count, whirl_windows_stats *stats);

/* ---- intervals of the dissipative chain (src/stability/dissipative_windows.c) ----
 * With internal damping or air drag the growth g(omega) = max Re lambda of the linearisation
 * (the rotation's zero removed) is positive (unstable) or negative (converging) except at
 * isolated rates, the edges, where an eigenvalue crosses the imaginary axis. */

typedef struct whirl_dissipative_interval {
    double from, to;           /* an interval of rates with one sign of the growth [sqrt(g/L)] */
    int open_from, open_to;    /* 1: that end is not an edge but the end of the range examined,
                                  or the last scan rate where the hand-swung shape exists */
    whirl_verdict verdict;     /* WHIRL_VERDICT_UNSTABLE (growth > 0) or
                                  WHIRL_VERDICT_CONVERGING (growth < 0) inside */
    double freq_from, freq_to; /* |Im lambda| of the eigenvalue that crosses at each edge [1/T]
                                  (0 at an open end) */
    double growth;             /* the extreme growth inside [1/T]: the largest if unstable, the
                                  most negative (fastest convergence) if converging */
    double at;                 /* the rate where it occurs [sqrt(g/L)] (to about 1e-6) */
} whirl_dissipative_interval;

/* The intervals where mode k of the N-link chain model->chain is unstable or converging with
 * the model's dissipation, over the range of p (p->krylov is not used), in increasing omega,
 * into out[0..max-1], their number into *count (GSL_EINVAL if more than max); stats counts the
 * scan points, shapes and eigen-solves (full ones, solves_values). The model needs internal
 * damping D > 0 or air drag (c or c2 > 0, which needs drive_radius > 0); its omega, frame and
 * dim are not used. Shapes: without a drive the free ones of the branch born at omega_k, with
 * a drive (drive_radius > 0) the hand-swung ones of whirl_driven_mode with side (+1 / -1; not
 * used without a drive). The growth is computed on a scan of step p->scan_step from
 * max(p->omega_min, omega_k (1 + 1e-6)) to p->omega_max; between two scan rates with growths of
 * opposite signs the edge is the root of the growth by Brent's method to p->tol, and the
 * frequency there is that of the eigenvalue of largest real part. An interval narrower than the
 * scan step can be missed. A scan rate without a hand-swung shape ends an interval (open end).
 * GSL_EINVAL without dissipation (the conservative windows are whirl_windows_find's), with a
 * growth within round-off of 0 at a scan rate (1e-10 max |lambda|: too little dissipation to
 * decide), or on bad parameters; GSL_EDOM if the mode does not exist in the range, or the
 * hand-swung shape disappears between two scan rates of opposite growth; GSL_EFAILED if the
 * growth jumps there instead of passing through 0 (a shape that changes branch);
 * WHIRL_EINTERRUPTED on a stop request (between eigen-solves).
 * @param model the model: its chain, internal damping, air drag and drive radius
 * @param mode the mode k >= 1
 * @param side +1 / -1: the hand-swung shape's side (with a drive), else not used
 * @param p the range, scan step and tolerance (krylov not used)
 * @param out out: the intervals in increasing omega, max of them
 * @param max the room in out
 * @param count out: how many intervals
 * @param stats out: the scan points, shapes and eigen-solves
 * @return GSL_SUCCESS, GSL_EINVAL, GSL_EDOM, GSL_EFAILED or WHIRL_EINTERRUPTED (see above), with a
 *     message
 */
WHIRL_API int whirl_windows_dissipative(const whirl_model *model, int mode, int side,
                                        const whirl_windows_params *p,
                                        whirl_dissipative_interval *out, size_t max,
                                        size_t *count, whirl_windows_stats *stats);

#ifdef __cplusplus
}
#endif

#endif
