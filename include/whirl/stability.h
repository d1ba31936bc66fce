/* whirl: linear stability of the steady shapes of the N-link chain, and perturbed runs.
 *
 * A steady shape is a planar relative equilibrium: at rest in the x-z plane of the frame
 * co-rotating at omega about z. Its linearisation in that frame, in the coordinates
 * q = (alpha_1..alpha_N, beta_1..beta_N) (in-plane and out-of-plane angle of each link, beta = 0
 * at the equilibrium), is
 *     M q'' + (G + C) q' + K q = 0,
 * M the mass matrix, G the skew gyroscopic (Coriolis) matrix, C the internal damping matrix and
 * K the Hessian of the effective potential (gravity minus centrifugal). Rotation about z is a
 * symmetry: the first-order form (size 4N) always has zero eigenvalues (a Jordan pair without
 * damping, a single zero with damping); they are removed exactly by deflation and the growth
 * rate is the largest real part of the remaining eigenvalues.
 *
 * Model: whirl_model of whirl/dynamics.h with dim = 3, drive_radius = 0 and no air drag (a planar
 * shape is not a relative equilibrium under inertial-frame drag: drag exerts a torque about the
 * axis that a pivot on the axis cannot balance); internal_damping D >= 0; frame is ignored (the
 * linearisation is always in the co-rotating frame). */
#ifndef WHIRL_STABILITY_H
#define WHIRL_STABILITY_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"
#include "whirl/steady.h"

typedef struct whirl_stability whirl_stability; /* workspace of the linear analysis of N links */

/* A workspace for chains of n >= 1 links. NULL (whirl_last_error) on n = 0 or no memory. */
whirl_stability *whirl_stability_alloc(size_t n);
void whirl_stability_free(whirl_stability *w); /* NULL is a no-op */

/* Forms M, G, C, K about the planar shape with masses at (r[i], 0, z[i]), i = 0..N (i = 0: the
 * pivot; as from whirl_nlink_positions), rotating at model->omega. GSL_EINVAL if the model is not
 * supported (see above), the links' lengths differ from the chain's by more than 1e-9 relative, or
 * the shape is not an equilibrium (the force on some link has a component across it larger than
 * 1e-8 of the chain's weight plus its centrifugal scale). */
int whirl_stability_linearise(whirl_stability *w, const whirl_model *model, const double *r,
                              const double *z);

typedef enum {
    WHIRL_STABILITY_MASS = 0,      /* M, symmetric positive definite */
    WHIRL_STABILITY_GYROSCOPIC,    /* G, skew */
    WHIRL_STABILITY_DAMPING,       /* C, symmetric positive semidefinite (0 without damping) */
    WHIRL_STABILITY_STIFFNESS      /* K, symmetric, K s = 0 for the symmetry direction s */
} whirl_stability_matrix;

/* The 2N x 2N matrix (row-major, rows and columns ordered as q) of the last linearisation. */
const double *whirl_stability_get_matrix(const whirl_stability *w, whirl_stability_matrix which);

/* The symmetry direction s of the last linearisation (2N): beta_j = sin(alpha_j), alpha = 0, the
 * infinitesimal rotation about z; all zero for a chain hanging straight down. */
const double *whirl_stability_symmetry(const whirl_stability *w);

/* Eigenvalues of the last linearisation with the symmetry's zero eigenvalues removed: *count
 * (4N - 2 without damping, 4N - 1 with damping, 4N for a hanging chain, which has no symmetry
 * mode), real and imaginary parts (pointers into the workspace, valid until the next call), in
 * the chain's units of 1/time (sqrt(g/L) for the dimensionless chain). */
int whirl_stability_eigenvalues(whirl_stability *w, size_t *count, const double **re,
                                const double **im);

/* The largest real part among those eigenvalues (growth rate, 1/time). A value within round-off
 * of zero (|growth| <= 1e-10 max |lambda|: neutral stability of the conservative chain, whose
 * eigenvalues lie on the imaginary axis) is returned as exactly 0. */
int whirl_stability_growth(whirl_stability *w, double *growth);

/* Linearises about the steady shape with tip radius tip_r (a root from whirl_nlink_solve or
 * whirl_nlink_branch at model->omega, nodes from whirl_nlink_positions) and returns its growth. */
int whirl_stability_shape(whirl_stability *w, const whirl_model *model, double tip_r,
                          double *growth);

/* The steady shape of mode k at model->omega (whirl_nlink_solve, tip_r_guess as there), its
 * linearisation and growth rate. info may be NULL. GSL_EDOM if the mode does not exist. */
int whirl_stability_mode(whirl_stability *w, const whirl_model *model, int mode,
                         double tip_r_guess, whirl_shape_info *info, double *growth);

/* ---- perturbed time-domain runs (src/stability_run.c) ---- */

typedef enum {
    WHIRL_VERDICT_STABLE = 0,    /* the deviation stayed below 100 times the initial one */
    WHIRL_VERDICT_UNSTABLE = 1,  /* the deviation grew to 100 times the initial one */
    WHIRL_VERDICT_CONVERGING = 2 /* (damping > 0) it fell to 1/100 of the initial one */
} whirl_verdict;

/* "stable", "unstable", "converging". */
const char *whirl_verdict_name(whirl_verdict v);

typedef struct whirl_stability_run_params {
    double periods;      /* P > 0: length of the run in rotation periods 2 pi / omega; 100 */
    double perturbation; /* EPS in (0, 1): each link direction turned by EPS [rad]; 1e-6 */
    unsigned long seed;  /* seed of the random directions (GSL's mt19937); 1 */
    const char *method;  /* integrator (whirl_integrator_methods); "gauss2" */
    double dt;           /* fixed step [T]; 0: the default, min(period / 200,
                            0.7 / (nu + omega + kappa)), nu = 2 sqrt(max_j (T_j / l_j) / min m)
                            bounding the chain's highest frequency under the shape's tensions
                            T_j, kappa = 4 D / (min m min l^2) its fastest damping rate */
    /* Called at t = 0 and at every sample with the time and the deviation over the initial one
     * (NULL: none); a non-zero return stops the run, which then returns that status. */
    int (*observe)(double t, double ratio, void *data);
    void *observe_data;  /* passed to observe */
} whirl_stability_run_params;

/* The defaults above. */
whirl_stability_run_params whirl_stability_run_defaults(void);

typedef struct whirl_stability_run_result {
    double sim_growth;    /* exponential rate fitted to log(deviation) over the stretch where it
                             grows from 100 to 1e4 times the initial deviation (or to the end of
                             the run) [1/T]; 0 unless the verdict is unstable */
    double max_deviation; /* largest deviation over the run / the initial one */
    double end_deviation; /* deviation at the end of the run / the initial one */
    double initial;       /* the initial deviation [L] */
    double duration;      /* time integrated [T] (shorter than P periods once settled) */
    double fit_from, fit_to; /* the fitted stretch [T] (0, 0 if none) */
    whirl_verdict verdict;
    whirl_integrator_stats stats;
} whirl_stability_run_result;

/* Runs the dynamics (3D, co-rotating frame, Cartesian formulation, model's damping) from the
 * steady shape with tip radius tip_r (as for whirl_stability_shape) with every link direction
 * turned by params->perturbation towards a random perpendicular direction, at rest in the
 * co-rotating frame, for params->periods rotation periods, sampling the deviation from the shape
 * (whirl_deviation: RMS distance of the masses, minimised over a rotation about z) 50 times per
 * period. Verdict rule: unstable as soon as the deviation reaches 100 times the initial one;
 * converging (damping > 0 only) as soon as it falls to 1/100 of it; stable otherwise. The run
 * stops early once the verdict is settled: unstable after the fitted stretch ends (1e4 times or
 * 1e-2 L), converging at once. Allocates its own dynamics and integrator. */
int whirl_stability_run(const whirl_model *model, double tip_r,
                        const whirl_stability_run_params *params,
                        whirl_stability_run_result *result);

#endif
