/* whirl: which steady shape a hand-swung chain settles into, from rest.
 *
 * The N-link chain (dynamics.h) hangs at rest; the hand then brings its top up to the circle of
 * radius eps at rate omega over the ramp time t_ramp, eps(t) = eps s(t / t_ramp) with the
 * smooth step s(u) = u^2 (3 - 2 u), while air drag acts in the inertial frame. The run goes on
 * until the shape seen in the frame co-rotating at omega stops changing, or t_max.
 *
 * Ramp: the model's drive_radius_ramp (dynamics.h), so the whole run is one integration with one
 * workspace; a change of omega (whirl_regime_sweep, rotating frame) is the same smooth step of
 * the model's omega_ramp over t_change, with the Euler force of the frame's changing rate.
 *
 * Frame: WHIRL_FRAME_ROTATING (default) integrates the same equations in the co-rotating frame,
 * where the problem is autonomous and a steady shape is an exact fixed point of the integrator;
 * WHIRL_FRAME_INERTIAL integrates the physical setting directly (constant omega only).
 *
 * Classification, from the positions of the masses in the co-rotating frame sampled once per
 * drive period T = 2 pi / omega after the ramp (a stroboscopic, Poincare-like section):
 *  - change D_k = RMS over the masses of the distance between consecutive samples; block means
 *    m0, m1 of the D_k over the last two blocks of 8 periods (8: so that an oscillating decay
 *    counts as one), mean decay ratio per period q = (m1 / m0)^(1/8), and the geometric estimate
 *    of the distance left to the fixed point, max(D_k, m1 / 8) / (1 - q) (infinite if q >= 1);
 *  - SETTLED when that estimate is below settle_tol for settle_periods consecutive periods. The
 *    node count is then that of the settled shape (driven.h's definition, whirl_driven_nodes),
 *    and the shape is compared with the steady boundary-value solution with drag
 *    (whirl_driven_solve from the settled tip): shape_error = RMS distance over the masses;
 *  - otherwise at t_max, CONVERGING when the run is still approaching a steady shape too slowly
 *    to settle by t_max: the estimate of the distance left above is below 0.05 L, or each of
 *    the last five means of 4 consecutive D_k is 0.5% below the one before (20 periods of decay)
 *    and the distance left estimated from the mean ratio q of those periods, D_k / (1 - q), is
 *    below 0.05 L. The node count is that of the last shape;
 *  - otherwise PERIODIC with period p (2 <= p <= WHIRL_REGIME_PERIOD_MAX drive
 *    periods) when the tip's samples repeat: |tip_k - tip_{k-p}| < periodic_tol for the last
 *    WHIRL_REGIME_PERIOD_CHECKS samples (the smallest such p). A motion locked to a period that
 *    is no multiple of T is not caught here: it is classified by the next test;
 *  - otherwise a twin run started at a distance delta0 = 1e-8 (the whole state) and renormalised
 *    once per period over lyapunov_periods periods (Benettin's method) estimates the largest
 *    Lyapunov exponent lambda [1/T]: CHAOTIC if lambda > chaos_lambda, else QUASIPERIODIC.
 * Limits: finite-time estimates; a slow transient (weak drag) may be called quasi-periodic or
 * periodic when t_max is too short, and lambda near chaos_lambda is not conclusive. */
#ifndef WHIRL_REGIME_H
#define WHIRL_REGIME_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WHIRL_REGIME_PERIOD_MAX 8    /* longest period tested, in drive periods */
#define WHIRL_REGIME_PERIOD_CHECKS 8 /* samples that must repeat for a period */

typedef enum {
    WHIRL_REGIME_SETTLED = 0,       /* a steady shape in the co-rotating frame */
    WHIRL_REGIME_PERIODIC = 1,      /* repeats after period (>= 2) drive periods */
    WHIRL_REGIME_QUASIPERIODIC = 2, /* neither, largest Lyapunov exponent <= chaos_lambda */
    WHIRL_REGIME_CHAOTIC = 3,       /* largest Lyapunov exponent > chaos_lambda */
    WHIRL_REGIME_FAILED = 4,        /* the integration failed (not a physical state) */
    WHIRL_REGIME_CONVERGING = 5     /* still decaying towards a steady shape at t_max */
} whirl_regime_state;

/* Parameters of one run (never changed by the library). Units: L = M = g = 1. */
typedef struct whirl_regime_params {
    /* omega, drive_radius, air_drag, air_drag_quadratic, internal_damping and frame are
       whirl_model's (dynamics.h), with the same names, meaning and units */
    double omega;              /* rate of the hand [sqrt(g/L)], > 0 */
    double drive_radius;       /* eps: radius of the hand's circle at the end of the ramp [L],
                                  0 < eps < 1 */
    double air_drag;           /* linear air drag per unit length, >= 0 (default 0) */
    double air_drag_quadratic; /* quadratic air drag per unit length, >= 0 (default 0) */
    double internal_damping;   /* >= 0 (default 0) */
    whirl_frame frame;       /* frame of the integration (default rotating) */
    const char *method;      /* integrator (dynamics.h), e.g. "rk4" or "gauss2" */
    double dt;               /* fixed step [T], > 0 */
    double t_ramp;           /* ramp time of eps [T], > 0; e.g. 20 */
    double t_max;            /* end of the run if it has not settled [T], > t_ramp */
    double settle_tol;       /* [L], > 0: remaining distance below which a run has settled */
    int settle_periods;      /* >= 1: consecutive periods that must pass the test, e.g. 3 */
    double periodic_tol;     /* [L], > 0: repeat tolerance of the tip (PERIODIC) */
    int lyapunov_periods;    /* >= 1: length of the Lyapunov window in drive periods */
    double chaos_lambda;     /* [1/T] > 0: threshold of the largest Lyapunov exponent */
    double perturb;          /* >= 0: every link of the hanging start turned by this angle
                                [rad] about a random horizontal axis (breaks symmetries) */
    unsigned long seed;      /* seed of those turns (GSL's MT19937) */
} whirl_regime_params;

/* The defaults for a chain of links links, omega and drive_radius 0 (to be set): drag 0, rotating
 * frame, "rk4", dt = 0.1 / links, t_ramp 20, t_max 400, settle_tol 1e-3, settle_periods 3,
 * periodic_tol 1e-3, lyapunov_periods 60, chaos_lambda 0.05, perturb 1e-3, seed 1.
 * @param links the chain's links N, which sets dt
 * @return the defaults
 */
WHIRL_API whirl_regime_params whirl_regime_defaults(size_t links);

/* The outcome of one run. */
typedef struct whirl_regime_result {
    whirl_regime_state state;
    int nodes;          /* node count of the last sampled shape (settled: of the steady shape) */
    int period;         /* PERIODIC: in drive periods; 1 if SETTLED; 0 otherwise */
    double t_end;       /* time the run ended (settled or t_max, plus the Lyapunov window) [T] */
    double change;      /* last per-period change D_k [L] */
    double remaining;   /* last estimate of the distance left [L] (infinite if not decaying) */
    double shape_error; /* SETTLED: RMS distance from the boundary-value shape [L]; else NaN
                           (also NaN if Newton found no boundary-value shape from the tip) */
    int bvp_nodes;      /* node count of that boundary-value shape, or 0 */
    double lyapunov;    /* largest Lyapunov exponent estimate [1/T], NaN if not computed */
    double tip[3];      /* last tip position, co-rotating frame (pivot at (eps, 0, 0)) [L] */
    double tip_r;       /* its distance from the axis [L] */
    unsigned long steps; /* integrator steps taken since the start from rest */
} whirl_regime_result;

/* Called every `every` time units of a run (and at its start) with the positions of the
 * masses x[3 i..3 i + 2] (i = 0..N-1) in the co-rotating frame, the pivot there, and the angle
 * of that frame in the inertial frame: rotating by it gives the inertial positions. A non-zero
 * return stops the run with that status. */
typedef int (*whirl_regime_observer)(void *ctx, double t, double frame_angle, const double *pivot,
                                     const double *x, size_t n);

typedef struct whirl_regime whirl_regime; /* workspace of one chain */

/* A workspace for runs of chain (not owned: must outlive it). NULL on no memory.
 * @param chain the chain, of at least one link (not owned)
 * @return the workspace, to free with whirl_regime_free; NULL with a message on a chain of no link
 *     or no memory
 */
WHIRL_API whirl_regime *whirl_regime_alloc(const whirl_chain *chain);
/* Frees the workspace. NULL is a no-op.
 * @param w the workspace, or NULL
 */
WHIRL_API void whirl_regime_free(whirl_regime *w);

/* Sets (or clears, with NULL) the observer called every `every` > 0 time units.
 * @param w the workspace
 * @param f the observer, or NULL: none
 * @param ctx passed to f
 * @param every the observer's interval [T], > 0 (else no observer is called)
 */
WHIRL_API void whirl_regime_observe(whirl_regime *w, whirl_regime_observer f, void *ctx,
                                    double every);

/* Checks p: GSL_SUCCESS, or GSL_EINVAL naming the first bad field.
 * @param p the parameters
 * @return GSL_SUCCESS, or GSL_EINVAL with a message naming the first bad field
 */
WHIRL_API int whirl_regime_check(const whirl_regime_params *p);

/* One run from rest (see above). GSL_EINVAL on bad parameters; the status of the observer if it
 * stopped the run; GSL_SUCCESS otherwise, also when the integration failed (state FAILED, the
 * reason in whirl_last_error()).
 * @param w the workspace
 * @param p the run's parameters
 * @param res out: the outcome
 * @return GSL_SUCCESS (also for a FAILED run), GSL_EINVAL on bad parameters, the observer's status,
 *     or WHIRL_EINTERRUPTED; with a message
 */
WHIRL_API int whirl_regime_run(whirl_regime *w, const whirl_regime_params *p,
                               whirl_regime_result *res);

/* Hysteresis: a run from rest at omega[0] (p->omega is ignored), then omega changed to each next
 * omega[j] by a smooth step over t_change (> 0) and the run continued until it
 * settles (or for t_max - t_ramp), res[j] the outcome there. Rotating frame only (GSL_EINVAL
 * otherwise). Returns as whirl_regime_run; a FAILED point ends the sweep (later res[] FAILED).
 * If n_done is not NULL it receives the number of points of res[] completed, also when the
 * sweep stops early (a stop request: WHIRL_EINTERRUPTED, res[0..*n_done-1] kept).
 * @param w the workspace
 * @param p the runs' parameters (p->omega ignored), rotating frame
 * @param omega the rates [sqrt(g/L)], n
 * @param n the rates, >= 1
 * @param t_change the time of each change of rate [T], > 0
 * @param res out: the outcome at each rate, n
 * @param n_done out, or NULL: the points of res completed
 * @return as whirl_regime_run; GSL_EINVAL also for no rate, a bad t_change or the inertial frame
 */
WHIRL_API int whirl_regime_sweep(whirl_regime *w, const whirl_regime_params *p, const double *omega,
                                 size_t n, double t_change, whirl_regime_result *res,
                                 size_t *n_done);

/* "settled", "periodic", "quasiperiodic", "chaotic", "failed", "converging"; NULL otherwise.
 * @param s the state
 * @return the state's name (static text), or NULL for no state
 */
WHIRL_API const char *whirl_regime_state_name(whirl_regime_state s);

#ifdef __cplusplus
}
#endif

#endif
