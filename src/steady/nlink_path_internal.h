/* The N-link continuation's state (src/steady/nlink_path*.c): what include/whirl/steady.h shows
 * of a path (whirl_nlink_path, read by callers) is the first member of the path the library
 * allocates; the rest is here. Every array lives in one block after the struct, addressed by
 * offsets, so that a copy of a path (the probe, path_copy) is two assignments and one memcpy and
 * no pointer needs re-basing. */
#ifndef WHIRL_NLINK_PATH_INTERNAL_H
#define WHIRL_NLINK_PATH_INTERNAL_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#include "steady/steady_internal.h"
#include "whirl/steady.h"

/* The last accepted step: its start, kept for the events and crossings. */
typedef struct path_last {
    double m0[3], w0, a0, t_w, t_a, ds; /* its start: metric (shot), point, tangent; its length */
    int raw_sign;
    int angles; /* the step was made in the link angles */
    int det_sign, index;
    double mu, mu_rate;
} path_last;

/* Everything of a path's point that is not public and not an array. No pointer into the block:
 * the arrays that a step exchanges with their trial are offsets. */
typedef struct path_state {
    double metric[3]; /* at the current point (shot): g_ww, g_wa, g_aa */
    int raw_sign;     /* orientation of the tangent against (G_a, -G_w) */
    double noise;     /* the round-off of the tip shot at the current point, as a distance from
                       * the curve in the metric */
    int stay, backoff; /* steps the path stays in the link angles before it tries the shot
                        * again, and the next such wait */
    int det_sign;     /* in the link angles: sign of det [J; tangent] (branch points) */
    int index;        /* in the link angles: the number of negative eigenvalues of the force
                       * balance's Jacobian in theta; -1 on the tip shot */
    double mu, mu_rate; /* in the link angles: the eigenvalue of that Jacobian nearest zero and
                         * its rate along the tangent (d mu / ds); NAN where not known */
    const char *why;  /* what rejected the last trial step (a string literal) */
    int floor_exit;   /* the last Newton's method on the shot stopped at its round-off floor */
    int have_last;    /* last is set (cleared by a start or a reversal) */
    path_last last;
    double fine_end;  /* the arclength up to which a reversal of the orientation test is taken
                       * for a branch point only at the smallest step (look_ahead; 0: none) */
    double probe_end; /* the arclength up to which a reversal is taken for a branch point without
                       * looking ahead again: the probe found one there at the finer scale */
    int rate_sign;    /* the sign of t_omega at the last point where it is resolved; a fold is
                       * where it changes. 0 until known (at a birth) */
    int last_rate_sign; /* that sign at the last step's start */
    /* offsets into the block of the arrays exchanged with their trial by a step (c->n each;
     * embed, embed_trial c->n + 1, then c->n of scratch) */
    size_t theta, theta_trial, t_theta, t_theta_trial, embed, embed_trial, eig, eig_trial;
} path_state;

typedef struct nlink_path {
    whirl_nlink_path pub; /* what a caller reads */
    path_state s;
    nlink_balance *balance;   /* the force balance in the link angles (own, not copied) */
    struct nlink_path *probe; /* the path that looks ahead (allocated when first needed) */
    double block[];           /* every array (path_block_size) */
} nlink_path;

static inline nlink_path *path_of(whirl_nlink_path *p)
{
    return (nlink_path *)p;
}

/* The arrays. Their offsets: the exchanged ones as path_state holds them, the rest fixed. */
static inline double *arr_theta(const nlink_path *p) { return (double *)p->block + p->s.theta; }
static inline double *arr_theta_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.theta_trial;
}
static inline double *arr_t_theta(const nlink_path *p)
{
    return (double *)p->block + p->s.t_theta;
}
static inline double *arr_t_theta_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.t_theta_trial;
}
static inline double *arr_embed(const nlink_path *p) { return (double *)p->block + p->s.embed; }
static inline double *arr_embed_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.embed_trial;
}
static inline double *arr_eig(const nlink_path *p) { return (double *)p->block + p->s.eig; }
static inline double *arr_eig_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.eig_trial;
}
/* the fixed ones, after the 6 N + 2 (2 N + 1) of the exchanged: the last step's start's link
 * angles and tangent, the crossings' and the events' link angles, 7 N + 3 of scratch */
static inline size_t path_fixed(size_t n) { return 6 * n + 2 * (2 * n + 1); }
static inline double *arr_theta0(const nlink_path *p)
{
    return (double *)p->block + path_fixed(p->pub.chain->n);
}
static inline double *arr_t_theta0(const nlink_path *p)
{
    return arr_theta0(p) + p->pub.chain->n;
}
static inline double *arr_cross_theta(const nlink_path *p)
{
    return arr_t_theta0(p) + p->pub.chain->n;
}
static inline double *arr_event_theta(const nlink_path *p)
{
    return arr_cross_theta(p) + (WHIRL_PATH_EVENTS_MAX + 1) * p->pub.chain->n;
}
static inline double *arr_scratch(const nlink_path *p)
{
    return arr_event_theta(p) + WHIRL_PATH_EVENTS_MAX * p->pub.chain->n;
}
/* the doubles of the block */
static inline size_t path_block_size(size_t n)
{
    return path_fixed(n) + 2 * n + (2 * WHIRL_PATH_EVENTS_MAX + 1) * n + 7 * n + 3;
}

/* ---- the continuation's constants, each with its reason (the method: src/steady/nlink_path.c;
 * the measurements behind the values: docs/validation/continuation.md) ---- */

/* steps: arclength in (ln omega, theta / sqrt(N)) */
#define DS_FIRST 0.02 /* first step from a start: a few percent of a radian, resolved at once */
#define DS_MAX 0.1    /* largest step: a tenth of a radian keeps the predictor within Newton's
                       * basin on every branch seen */
#define DS_GROW 1.5   /* an easy step (NEWTON_EASY, half of TURN_MAX and DTHETA_MAX) grows so */
#define DS_MIN 1e-7   /* smallest step on the tip shot: below it the shot's round-off, not the
                       * curve, rejects the step, and the path hands over to the link angles */
#define DS_MIN_ANGLES 1e-12 /* smallest step in the link angles before the continuation fails:
                             * a branch can turn within an arclength of 1e-9 where part of the
                             * chain all but hangs */
#define DS_MIN_FINE 1e-18 /* and in the fine mode (look_ahead): a hundredth of the rate's
                           * round-off; such a step moves only the links all but hanging (1e-20
                           * to 1e-10 rad from the vertical), whose angles are resolved far
                           * below it, and a 50-digit path turns some such corners with steps of
                           * 1e-17 */
#define DS_MIN_CHORD 1e-10 /* the step below which the chord test alone is set aside: there
                            * the corrected points scatter by their round-off across a turn
                            * sharper than the tangent resolves */
#define DS_BRANCH 1e-9 /* a step longer than this on which the orientation test reverses is
                        * another curve close by and is halved; one no longer is a branch point
                        * (adjacent curves lie further apart, genuine unfoldings closer) */
#define DS_CROSS 1e-6  /* in the link angles, the longest step taken across a branch point
                        * where no step down to the smallest can be followed */

/* the tests of a step */
#define TURN_MAX 0.2   /* largest turn of the tangent per step [rad]: the predictor's error is
                        * of order ds turn, within Newton's basin */
#define DTHETA_MAX 0.2 /* largest change of a link angle per step [rad]: no corrector lands on
                        * another curve */
#define CHORD_MAX 0.75 /* largest angle between a step's chord and its end tangents, relative to
                        * the turn: 2/3 on an arc whose curvature grows linearly from zero, 1/2 on
                        * a circle, with a margin (path_chord_test) */
#define CHORD_SLACK 1e-3 /* and beyond that [rad] (and NEWTON_TOL over the chord's length: the
                          * round-off of its ends on short steps) */
#define SLOPE_MAX 0.5  /* the chord's rate part beyond the end tangents' [turn^2]: an arc of
                        * constant sign of curvature exceeds them by at most turn^2 / 8 */
#define SLOPE_SLACK 1e-9 /* and beyond that (the rate's round-off) */
#define NEAR_MAX 0.5   /* an eigenvalue that turns back closer to zero than this times its value
                        * at the nearer end of the step: the interpolant's error is not known to
                        * be small against the distance from zero; the step is halved */
#define EIG_SAME 0.5   /* the eigenvectors at a step's ends are of the same eigenvalue where
                        * their angle's cosine is at least this (else another eigenvalue became
                        * the nearest to zero) */
#define EIG_ITERS 1    /* inverse iterations for the eigenvalue nearest zero, from the last
                        * point's eigenvector (a step moves it little) */
#define EIG_ITERS_FIRST 8 /* and from a start (a vector of ones) */
#define MU_RESOLVED 1e-12 /* in the link angles the sign of t_omega is the fold test's only
                           * where |mu| > MU_RESOLVED |A|: genuine folds lie at 1e-9 to 1e-2 of
                           * |A|, the round-off of a sharp turn at 1e-24 to 1e-15 */

/* Newton's method (the corrector) */
#define NEWTON_MAX 10    /* corrector iterations per trial step */
#define NEWTON_EASY 4    /* a step converged in this many or fewer may grow */
#define NEWTON_TOL 1e-10 /* correction (metric norm) after which one last iteration is made
                          * (quadratic convergence: then round-off) */
#define NEWTON_FLOOR 1e-8 /* a correction this small that stops decreasing is round-off (the
                           * floor of the shot on a high mode) */
#define NEWTON_STALL 0.5  /* stops decreasing: falls by less than this factor, */
#define NEWTON_STALL_AFTER 2 /* from this iteration on */
#define LOCATE_NEWTON_MAX 40 /* Newton iterations of a point of an event's location (slow near a
                              * branch point, where the corrector's system is singular) */
#define EXP_ARG_MAX 700  /* the orientation test's determinant scaled by exp of at most this
                          * (finite in double) */

/* events and crossings */
#define LOCATE_MAX 200    /* Brent iterations for an event */
#define LOCATE_FOLD 1e-12 /* a fold's bracket in sigma, relative to the step: omega is
                           * stationary there, its error the square of sigma's, and the test
                           * function t_omega no better than about this (frame_locate) */
#define LOCATE_ROUND (4 * DBL_EPSILON) /* any other event's bracket, relative: round-off */
#define RATE_ROUND (4 * DBL_EPSILON)   /* a relative change of the rate this small is round-off
                                        * (Newton's method at a birth, the secant of birth_gap) */
#define CROSS_SLACK 1e-9 /* a crossing's arclength coordinate lies on its piece of the step to
                          * within this times the step (the corrector's round-off) */
#define RETURN_SPAN 1e-8 /* a return to the hanging chain is taken only within this (relative)
                          * of a critical rate, where the hanging chain's index changes
                          * (at_a_birth); elsewhere the step is halved */
#define TIP_SAME 1e-6    /* a shape's tip radius is the shot's root next to the link angles'
                          * where the two agree to this (relative; path_shape_info) */

/* the two formulations */
#define NOISE_UP 3e-14   /* the path goes over to the link angles where the shot's round-off
                          * unbalances a link by more than this (relative to its tension: a
                          * hundred times eps) */
#define NOISE_DOWN 3e-15 /* and back to the tip shot where it falls below this (a decade of
                          * hysteresis) */
#define STAY_FIRST 16    /* steps in the link angles after the shot's Newton failed, before the
                          * shot is tried again (doubled on each such failure, so that the path
                          * does not flap) */
#define SHOT_SAME 1e-9   /* back on the shot, no link angle moves more than this [rad] (else
                          * its Newton's method went to another equilibrium nearby) */

/* the look ahead */
#define FINE_SPAN 1e-7   /* the arclength a probe looks ahead: an unfolded branch point turns
                          * within 3e-9 to 5e-9 (look_ahead) */
#define PROBE_STEPS 2000 /* and its most steps */

/* births */
#define BIRTH_NEWTON_MAX 20 /* Newton iterations on the linearised shot G(omega, 0) at a birth */
#define BIRTH_NEWTON_SPAN 1e-6 /* a correction beyond this (relative) from the eigenproblem's
                                * rate: the shot is too inaccurate for it (the high modes of long
                                * chains), and that rate is kept */
#define BIRTH_AMPLITUDE 1e-5 /* rms link angle of the first point of a birth in the link angles:
                              * its rate moves from omega_k by O(amplitude^2), far above the
                              * round-off */
#define GAP_MAX 30 /* secant iterations of a point between the birth and that first point */
#define GAP_MIN 1e-13 /* omega / omega_k - 1 below which a rate is the birth itself (no gap) */
#define BIRTH_NEAR 1e-10 /* omega / omega_k - 1 below which the force balance at fixed omega
                          * does not tell a branch's point from the hanging chain: the
                          * eigenvalue of its Jacobian nearest zero is about that times its
                          * largest, the shot's round-off 3e-14 (NOISE_UP) */

typedef struct shot {
    double g, g_w, g_a;      /* G and its partial derivatives */
    double m_ww, m_wa, m_aa; /* the metric M at the point */
} shot;

/* Scratch arrays of the path (7 N + 3 doubles): a Newton step's residual and correction, zeros,
 * the arclength row's link-angle part, and 3 (N + 1) for a shape's nodes. */
static inline double *scr_f(const nlink_path *p) { return arr_scratch(p); }
static inline double *scr_dth(const nlink_path *p) { return arr_scratch(p) + p->pub.chain->n; }
static inline double *scr_zero(const nlink_path *p)
{
    return arr_scratch(p) + 2 * p->pub.chain->n;
}
static inline double *scr_cth(const nlink_path *p)
{
    return arr_scratch(p) + 3 * p->pub.chain->n;
}
static inline double *scr_nodes(const nlink_path *p)
{
    return arr_scratch(p) + 4 * p->pub.chain->n;
}

/* The tip radius of the link angles: at an equilibrium r_N = rho_N = g tan theta_N / omega^2, the
 * radius that balances the tip mass, free of the cancellation of the sum of l_i sin theta_i (a
 * high mode's tip radius can be 1e-18 of the largest); and its rate of change along
 * (d omega, d theta). */
static inline double tip_of(const whirl_chain *c, double w, const double *th)
{
    return c->gravity * tan(th[c->n - 1]) / (w * w);
}

static inline int sign_of(double x)
{
    return (x > 0) - (x < 0);
}

/* The path is in the fine mode at its current point (look_ahead). */
static inline int in_fine_mode(const nlink_path *p)
{
    return p->pub.arclength < p->s.fine_end;
}

/* The smallest step in the link angles at the current point: finer in the fine mode. */
static inline double ds_smallest(const nlink_path *p)
{
    return in_fine_mode(p) ? DS_MIN_FINE : DS_MIN_ANGLES;
}

static inline void swap(size_t *x, size_t *y)
{
    const size_t tmp = *x;
    *x = *y;
    *y = tmp;
}

static inline double metric_dot(const double *m, double x_w, double x_a, double y_w, double y_a)
{
    return m[0] * x_w * y_w + m[1] * (x_w * y_a + x_a * y_w) + m[2] * x_a * y_a;
}

static inline void shot_metric(const shot *s, double *m)
{
    m[0] = s->m_ww;
    m[1] = s->m_wa;
    m[2] = s->m_aa;
}

/* ---- one step: the loop (src/steady/nlink_path_step.c) and the formulations behind it ---- */

/* What a formulation's hook asks of the loop, besides a status to return */
#define STEP_RETRY (-1001)  /* the next trial, of length p->pub.ds */
#define STEP_ANGLES (-1002) /* the step afresh in the link angles from the current point */

/* A step's setup (step_ops.begin). */
typedef struct step_ctx {
    double w0, a0;    /* the step's start: rate and tip radius */
    const double *m0; /* the metric there (the shot; NULL in the link angles) */
    double c_w, c_a;  /* the arclength row's rate and tip-radius parts (the link angles': the
                       * rate part, and scr_cth) */
    int log_predictor; /* the shot predicts a in ln|a| */
    double ds_first;  /* the step's first trial length */
    double ds_min;    /* its smallest */
    double ds_branch; /* the longest on which a reversal of the orientation is taken */
    int crossing;     /* the crossing mode (link angles) */
    int chord_off;    /* the chord test set aside (link angles) */
    int chord_failed; /* the chord test rejected the last trial it judged */
    const char *why;  /* what rejected the trials before the crossing mode */
} step_ctx;

/* A trial: its length, its corrected point and the measures the tests read. */
typedef struct step_trial {
    double ds;
    int ok;              /* converged (then: passed the tests) */
    int iters;           /* Newton iterations (NEWTON_MAX: none converged) */
    double w, a;         /* the corrected point: rate, tip radius (the shot) */
    double t_w, t_a;     /* its tangent's rate and tip-radius parts */
    int raw;             /* the shot: its tangent's orientation against (G_a, -G_omega) */
    shot s;              /* the shot there */
    double noise;        /* the shot's round-off there */
    int det, index;      /* the link angles: orientation test, index */
    double mu, mu_rate, mu_min; /* the eigenvalue nearest zero, its rate, its resolution */
    double turn, dtheta; /* the tangent's turn, the largest change of a link angle */
    const char *chord;   /* path_chord_test's verdict (NULL: consistent) */
    int flip;            /* the orientation test reversed */
    int jump;            /* the index changed by more than one */
    int pair;            /* the eigenvalue nearest zero crosses zero and back within the step */
} step_trial;

/* A formulation. */
typedef struct step_ops {
    void (*begin)(nlink_path *p, step_ctx *x);
    /* predicts and corrects the trial of length t->ds, and measures it (t->ok = 0 where it does
     * not converge, the reason in p->s.why) */
    void (*trial)(nlink_path *p, step_ctx *x, step_trial *t);
    /* a trial that passed the tests, before it is taken: GSL_SUCCESS to take it, STEP_ANGLES,
     * or a status to return */
    int (*ready)(nlink_path *p, step_ctx *x, step_trial *t);
    /* after a rejected trial: STEP_RETRY (p->pub.ds shortened), STEP_ANGLES or a status */
    int (*rejected)(nlink_path *p, step_ctx *x, const step_trial *t);
    /* the trial becomes the current point (the start kept by the loop) */
    void (*accept)(nlink_path *p, const step_ctx *x, const step_trial *t);
} step_ops;

extern const step_ops path_shot_ops, path_angle_ops;

/* src/steady/nlink_path.c */
nlink_path *path_alloc(const whirl_chain *c);
void path_free(nlink_path *p);
int path_name_mode(const nlink_path *p, int status);

/* src/steady/nlink_path_step.c */
int path_step(nlink_path *p);
int path_stopped(const nlink_path *p);
int path_fail_at(nlink_path *p, int status, double w0, double a0);

/* src/steady/nlink_path_shot.c */
void path_shoot_embed(const whirl_chain *c, double omega, double a, shot *s, double *theta,
                      double *embed);
void path_shoot(const whirl_chain *c, double omega, double a, shot *s, double *theta);
double path_shot_noise(const whirl_chain *c, double omega, double a, const shot *s);
int path_correct(nlink_path *p, const double *m0, double w0, double a0, double c_w, double c_a,
                 double sigma, double *w, double *a, shot *s, int *iters);
void path_tangent(const shot *s, const double *m, const double *m_ref, double ref_w, double ref_a,
                  double *t_w, double *t_a, int *raw_sign);
double path_tension_spread(const whirl_chain *c, double omega, double a);
double path_noise_at(nlink_path *p, double omega, double a);
void path_set_point(nlink_path *p, double omega, double a, const shot *s, double noise);
int path_to_shot(nlink_path *p);

/* src/steady/nlink_path_angles.c */
double path_shape_projection(size_t n, const double *th, const double *th0);
int path_correct_angles(nlink_path *p, double w0, const double *th0, double c_w, const double *c_th,
                        double sigma, double *w, double *th, int *iters, int max_iter);
int path_angle_tangent(nlink_path *p, double w, double c_w, const double *c_th, double *t_w,
                       double *t_th, int *det_sign, double *ref, double *test);
void path_angle_point(nlink_path *p, double w, double t_w, int det);
int path_to_angles(nlink_path *p);
int path_birth_gap(nlink_path *p, double omega, double *th);
int path_begin_in_angles(nlink_path *p);

/* src/steady/nlink_path_events.c */
int path_shape_info(nlink_path *p, int angles, double omega, double a, const double *th,
                    whirl_shape_info *info, double *r, double *z, double *t);
int path_find_events(nlink_path *p, int branch);

/* src/steady/nlink_path_checks.c */
const char *path_chord_test(size_t n, double w0, const double *th0, double w1, const double *th1,
                            const double *e0, double s0, const double *e1, double s1, double turn,
                            int rates);
int path_hermite_crossings(double f0, double d0, double f1, double d1, double *near);

/* src/steady/nlink_path_probe.c */
int path_look_ahead(nlink_path *p, double ds);

#endif
