/* Events and crossings of the N-link continuation (src/steady/nlink_path.c): folds, branch
 * points and returns to the hanging chain on the last step, and its crossings of a rate, each
 * located by Brent's method on the step's arclength sigma in [0, ds] (every evaluation a
 * corrector solve on the hyperplane at sigma), or by Newton's method at the rate. */
#include <math.h>


#include "core/error.h"
#include "core/roots.h"
#include "steady/nlink_path_internal.h"

typedef enum { TARGET_OMEGA, TARGET_FOLD, TARGET_BRANCH, TARGET_RETURN } target_kind;

typedef struct step_frame {
    nlink_path *p;
    int angles;          /* the step was made in the link angles */
    double m0[3];        /* metric at the step's start (shot) */
    double w0, a0;       /* the step's start */
    double t0_w, t0_a;   /* its tangent */
    double c_w;          /* in the link angles: the row c_w, scr_cth(p) */
    double w1, a1, ds;   /* its end and length */
    target_kind kind;
    double target;       /* the rate for TARGET_OMEGA */
    double ref;          /* ln |det A| of the first branch test */
    int failed;
    int known;           /* phi at the ends of the step is known (in values[]) */
    double values[2];
    double at;           /* the sigma of the last corrected point (NAN: none) */
    double w, a;         /* the last corrected point */
    double *th;          /* its link angles (in the link angles) */
    shot s;              /* its shot (shot) */
} step_frame;

/* The corrected point at arclength sigma of the step (a start on the chord). */
static int frame_point(step_frame *f, double sigma)
{
    nlink_path *p = f->p;
    const double lambda = sigma / f->ds;
    int iters;
    if (f->angles) {
        const size_t n = p->pub.chain->n;
        const double *th0 = arr_theta0(p), *th1 = arr_theta(p);
        f->w = f->w0 + lambda * (f->w1 - f->w0);
        for (size_t i = 0; i < n; i++) f->th[i] = th0[i] + lambda * (th1[i] - th0[i]);
        if (path_correct_angles(p, f->w0, th0, f->c_w, scr_cth(p), sigma, &f->w, f->th, &iters,
                                LOCATE_NEWTON_MAX))
            return -1;
        f->a = tip_of(p->pub.chain, f->w, f->th);
        return 0;
    }
    double c_w = f->m0[0] * f->t0_w + f->m0[1] * f->t0_a;
    double c_a = f->m0[1] * f->t0_w + f->m0[2] * f->t0_a;
    /* from the geometric interpolation of a (a tip radius that varies exponentially), then from
     * the linear one */
    for (int geometric = (f->a0 > 0 && f->a1 > 0) || (f->a0 < 0 && f->a1 < 0); geometric >= 0;
         geometric--) {
        f->w = f->w0 + lambda * (f->w1 - f->w0);
        f->a = geometric ? f->a0 * pow(f->a1 / f->a0, lambda) : f->a0 + lambda * (f->a1 - f->a0);
        if (path_correct(p, f->m0, f->w0, f->a0, c_w, c_a, sigma, &f->w, &f->a, &f->s, &iters) == 0)
            return 0;
    }
    return -1;
}

static double frame_phi(double sigma, void *params)
{
    step_frame *f = params;
    f->at = NAN;
    if (frame_point(f, sigma) != 0) {
        f->failed = 1;
        return 0; /* ends Brent's iteration, which then reports the failure */
    }
    f->at = sigma;
    if (f->kind == TARGET_OMEGA) return f->w - f->target;
    if (f->kind == TARGET_RETURN)
        return f->angles ? path_shape_projection(f->p->pub.chain->n, f->th, arr_theta0(f->p))
                         : f->a;
    if (f->angles) {
        double t_w, test;
        int det;
        if (path_angle_tangent(f->p, f->w, f->c_w, scr_cth(f->p), &t_w, arr_t_theta_trial(f->p),
                               &det, &f->ref, &test)) {
            f->failed = 1;
            return 0;
        }
        return f->kind == TARGET_FOLD ? t_w : test;
    }
    const shot *s = &f->s;
    double r_w = s->g_a, r_a = -s->g_w;
    double along = metric_dot(f->m0, r_w, r_a, f->t0_w, f->t0_a);
    if (f->kind == TARGET_FOLD) {
        double m[3];
        shot_metric(s, m);
        return (along >= 0 ? 1 : -1) * r_w / sqrt(metric_dot(m, r_w, r_a, r_w, r_a));
    }
    return along; /* TARGET_BRANCH */
}

/* frame_phi for core/roots.h: GSL_EFAILED where the corrected point fails (phi 0 then, which
 * GSL's iteration takes as a value). */
static int frame_root(double sigma, void *ctx, double *phi)
{
    step_frame *f = ctx;
    *phi = frame_phi(sigma, f);
    return f->failed ? GSL_EFAILED : GSL_SUCCESS;
}

/* The sigma in [lo, hi] where phi changes sign (phi(lo) and phi(hi) of opposite signs, or one
 * zero); the corrected point left in f->w, f->a, f->s or f->th. */
static int frame_locate(step_frame *f, double lo, double hi, double *sigma)
{
    double f_lo = f->known ? f->values[0] : frame_phi(lo, f);
    double f_hi = f->known ? f->values[1] : frame_phi(hi, f);
    static const char *const what[] = {"a crossing of a rate", "a fold", "a branch point",
                                       "a return to the hanging chain"};
    if (f->failed)
        return whirl_fail(GSL_EFAILED, "%s between omega=" WHIRL_Q_RATE "%.17g and omega="
                          WHIRL_Q_RATE "%.17g could not be located (no convergence at an end of "
                          "the step)", what[f->kind], f->w0, f->w1);
    if (f_lo == 0 || f_hi == 0 || (f_lo > 0) == (f_hi > 0)) {
        *sigma = fabs(f_lo) <= fabs(f_hi) ? lo : hi;
        if (f->at != *sigma) frame_phi(*sigma, f);
        return f->failed ? whirl_fail(GSL_EFAILED, "%s between omega=" WHIRL_Q_RATE "%.17g and "
                                      "omega=" WHIRL_Q_RATE "%.17g could not be located",
                                      what[f->kind], f->w0, f->w1)
                         : GSL_SUCCESS;
    }
    /* at a fold omega is stationary in sigma: its error is of the order of the square of
     * sigma's, and the test function t_omega is no better than about 1e-12 of the step there
     * (the Jacobian is singular), so its bracket is closed to LOCATE_FOLD; elsewhere to
     * round-off (the bracket at most that long: epsabs just above it) */
    const double tol = f->kind == TARGET_FOLD ? LOCATE_FOLD : LOCATE_ROUND;
    const whirl_root_opts o = {nextafter(tol * f->ds, INFINITY), 0, LOCATE_MAX + 1, 1, f_lo, f_hi};
    whirl_root r;
    int status = whirl_root_brent(frame_root, f, lo, hi, &o, &r);
    if (status == GSL_ENOMEM || !r.bracketed) return status;
    if (status == GSL_EMAXITER)
        status = whirl_fail(GSL_EMAXITER, "an event was not located in %d steps", LOCATE_MAX);
    else if (status != GSL_SUCCESS)
        status = whirl_fail(GSL_EFAILED, "%s between omega=" WHIRL_Q_RATE "%.17g and omega="
                            WHIRL_Q_RATE "%.17g could not be located", what[f->kind], f->w0, f->w1);
    else
        *sigma = r.root;
    /* the corrected point at the root (Brent's last evaluation, as a rule) */
    if (status == GSL_SUCCESS && f->at != *sigma && (frame_phi(*sigma, f), f->failed))
        status = whirl_fail(GSL_EFAILED, "%s between omega=" WHIRL_Q_RATE "%.17g and omega="
                            WHIRL_Q_RATE "%.17g could not be located", what[f->kind], f->w0, f->w1);
    return status;
}

static void frame_of_last(nlink_path *p, step_frame *f, target_kind kind, double target)
{
    f->p = p;
    f->angles = p->s.last.angles;
    for (int i = 0; i < 3; i++) f->m0[i] = p->s.last.m0[i];
    f->w0 = p->s.last.w0;
    f->a0 = p->s.last.a0;
    f->t0_w = p->s.last.t_w;
    f->t0_a = p->s.last.t_a;
    f->w1 = p->pub.omega;
    f->a1 = p->pub.tip_r;
    f->ds = p->s.last.ds;
    f->kind = kind;
    f->target = target;
    f->failed = 0;
    f->known = 0;
    f->at = NAN;
    f->ref = NAN;
    f->th = arr_theta_trial(p); /* free after a step: its start is kept in last.theta0 */
    if (f->angles) {
        const size_t n = p->pub.chain->n;
        f->c_w = f->t0_w / (f->w0 * f->w0);
        for (size_t i = 0; i < n; i++) scr_cth(p)[i] = arr_t_theta0(p)[i] / (double)n;
    }
}

/* The arclength coordinate of the frame's corrected point along the step's tangent. */
static double frame_sigma(const step_frame *f)
{
    const nlink_path *p = f->p;
    if (f->angles) {
        double sigma = f->c_w * (f->w - f->w0);
        for (size_t i = 0; i < p->pub.chain->n; i++)
            sigma += scr_cth(p)[i] * (f->th[i] - arr_theta0(p)[i]);
        return sigma;
    }
    double c_w = f->m0[0] * f->t0_w + f->m0[1] * f->t0_a;
    double c_a = f->m0[1] * f->t0_w + f->m0[2] * f->t0_a;
    return c_w * (f->w - f->w0) + c_a * (f->a - f->a0);
}

/* The point of the frame at the rate omega exactly, by Newton's method at fixed omega from the
 * frame's point at sigma (interpolated if interpolate, else the last corrected one). */
static int frame_at_rate(step_frame *f, double omega, double sigma, int interpolate)
{
    nlink_path *p = f->p;
    int iters;
    if (interpolate) {
        const double lambda = sigma / f->ds;
        f->w = omega;
        if (f->angles) {
            for (size_t i = 0; i < p->pub.chain->n; i++)
                f->th[i] = arr_theta0(p)[i] + lambda * (arr_theta(p)[i] - arr_theta0(p)[i]);
        } else {
            int geometric = (f->a0 > 0 && f->a1 > 0) || (f->a0 < 0 && f->a1 < 0);
            f->a = geometric ? f->a0 * pow(f->a1 / f->a0, lambda)
                             : f->a0 + lambda * (f->a1 - f->a0);
        }
    }
    double w = omega;
    if (f->angles) {
        if (path_correct_angles(p, omega, f->th, 1, scr_zero(p), 0, &w, f->th, &iters,
                                LOCATE_NEWTON_MAX))
            return -1;
        f->w = w;
        f->a = tip_of(p->pub.chain, f->w, f->th);
        return 0;
    }
    /* the metric of the corrected point, or of the step's start for an interpolated one */
    double a = f->a, m[3];
    if (interpolate) m[0] = f->m0[0], m[1] = f->m0[1], m[2] = f->m0[2];
    else shot_metric(&f->s, m);
    if (path_correct(p, m, omega, f->a, 1, 0, 0, &w, &a, &f->s, &iters) != 0 || a == 0) return -1;
    f->w = w;
    f->a = a;
    return 0;
}

static int path_crossings(nlink_path *p, double omega, int max, double *tip_r);

int whirl_nlink_path_crossings(whirl_nlink_path *path, double omega, int max, double *tip_r)
{
    nlink_path *p = path_of(path);
    const int found = path_crossings(p, omega, max, tip_r);
    return found < 0 ? -path_name_mode(p, -found) : found;
}

static int path_crossings(nlink_path *p, double omega, int max, double *tip_r)
{
    if (!p->s.have_last) return 0;
    if (max > WHIRL_PATH_EVENTS_MAX + 1) max = WHIRL_PATH_EVENTS_MAX + 1;
    const size_t n = p->pub.chain->n;
    /* the step cut at its folds into pieces where omega is monotone */
    double start = p->pub.arclength - p->s.last.ds;
    double cut[WHIRL_PATH_EVENTS_MAX + 2], w_cut[WHIRL_PATH_EVENTS_MAX + 2];
    int ncut = 0;
    cut[ncut] = 0, w_cut[ncut++] = p->s.last.w0;
    for (int i = 0; i < p->pub.n_events; i++)
        if (p->pub.event[i].kind == WHIRL_EVENT_FOLD)
            cut[ncut] = p->pub.event[i].arclength - start, w_cut[ncut++] = p->pub.event[i].omega;
    cut[ncut] = p->s.last.ds, w_cut[ncut++] = p->pub.omega;
    int found = 0;
    for (int k = 0; k + 1 < ncut && found < max; k++) {
        double lo = w_cut[k], hi = w_cut[k + 1];
        if (!((lo < omega && omega <= hi) || (hi <= omega && omega < lo))) continue;
        step_frame f;
        frame_of_last(p, &f, TARGET_OMEGA, omega);
        /* omega is monotone on the piece, so its point at omega is the one whose arclength
         * coordinate lies on the piece: first Newton's method at omega from the point
         * interpolated linearly in omega, and where that lands off the piece, Brent's method on
         * the arclength, polished at omega */
        const double guess = cut[k] + (cut[k + 1] - cut[k]) * (omega - lo) / (hi - lo);
        const double slack = CROSS_SLACK * f.ds;
        int fast = frame_at_rate(&f, omega, guess, 1) == 0;
        if (fast) {
            const double sig = frame_sigma(&f);
            fast = sig >= cut[k] - slack && sig <= cut[k + 1] + slack;
        }
        if (!fast) {
            double sigma;
            int status = frame_locate(&f, cut[k], cut[k + 1], &sigma);
            if (status) return -status;
            if (frame_at_rate(&f, omega, sigma, 0) != 0)
                return -whirl_fail(GSL_EFAILED, "no equilibrium at omega=" WHIRL_Q_RATE "%.17g "
                                   "near the branch", omega);
        }
        double *th = arr_cross_theta(p) + (size_t)found * n;
        if (f.angles) {
            for (size_t i = 0; i < n; i++) th[i] = f.th[i];
        } else {
            /* the shot's point polished on the force balance in the link angles, which the
             * shot's round-off does not limit */
            shot s;
            path_shoot(p->pub.chain, f.w, f.a, &s, th);
            p->pub.cross_angles[found] = 0;
            if (path_shot_noise(p->pub.chain, f.w, f.a, &s) > NOISE_UP) {
                for (size_t i = 0; i < n; i++) f.th[i] = th[i];
                if (whirl_nlink_balance_polish(p->balance, f.w, f.th) == GSL_SUCCESS) {
                    for (size_t i = 0; i < n; i++) th[i] = f.th[i];
                    f.a = tip_of(p->pub.chain, f.w, th);
                    p->pub.cross_angles[found] = 1;
                }
            }
        }
        if (f.angles) p->pub.cross_angles[found] = 1;
        tip_r[found++] = f.a;
    }
    return found;
}

/* The summary of the shape at (omega, a) with link angles th: from the angles on a step made
 * in them (angles), else from the tip shot; mirrored to a positive tip radius. */
int path_shape_info(nlink_path *p, int angles, double omega, double a, const double *th,
                    whirl_shape_info *info, double *r, double *z, double *t)
{
    const whirl_chain *c = p->pub.chain;
    const size_t n = c->n;
    int status;
    if (angles) {
        whirl_nlink_balance_nodes(c, omega, th, r, z, t);
        if (a < 0)
            for (size_t i = 0; i <= n; i++) r[i] = -r[i];
        status = whirl_steady_check_samples(omega, n + 1, r, z, t);
    } else {
        status = whirl_nlink_positions(c, omega, fabs(a), r, z, t);
    }
    if (status) return status;
    whirl_nlink_info_nodes(c, r, z, t, omega, p->pub.mode, info);
    if (angles && info->tip_r > 0) {
        /* the tip radius as the shot's root next to it where the shot converges there, so that
         * whirl_nlink_positions reproduces the shape to the shot's round-off */
        double w = omega, tip = info->tip_r, m[3];
        shot s;
        int iters;
        path_shoot(c, omega, tip, &s, NULL);
        shot_metric(&s, m);
        if (path_correct(p, m, omega, tip, 1, 0, 0, &w, &tip, &s, &iters) == 0 &&
            fabs(tip - info->tip_r) <= TIP_SAME * info->tip_r) {
            info->tip_r = tip;
            info->max_r = fmax(info->max_r, tip);
        }
    }
    return whirl_steady_check_info(info);
}

static int add_event(nlink_path *p, whirl_event_kind kind, step_frame *f, double sigma)
{
    if (p->pub.n_events == WHIRL_PATH_EVENTS_MAX) return GSL_SUCCESS;
    const size_t n = p->pub.chain->n;
    double *th = arr_event_theta(p) + (size_t)p->pub.n_events * n;
    whirl_branch_event *e = &p->pub.event[p->pub.n_events++];
    e->kind = kind;
    e->omega = f->w;
    e->tip_r = f->a;
    e->arclength = p->pub.arclength - p->s.last.ds + sigma;
    if (f->angles) {
        for (size_t i = 0; i < n; i++) th[i] = f->th[i];
    } else {
        shot s;
        path_shoot(p->pub.chain, f->w, f->a, &s, th);
    }
    double *r = scr_nodes(p);
    whirl_shape_info info;
    int status =
        path_shape_info(p, f->angles, f->w, f->a, th, &info, r, r + n + 1, r + 2 * (n + 1));
    e->n_crossings = status == GSL_SUCCESS ? info.n_crossings : -1;
    return status;
}

/* Finds the events of the last step and sorts them by arclength; branch: the orientation test
 * changed sign. */
/* A critical rate lies within RETURN_SPAN (relative) of omega: the index of the hanging chain's
 * force balance (the number of negative eigenvalues of its Jacobian, a Sturm count, backward
 * stable whatever the scaling of the links) differs at omega (1 - RETURN_SPAN) and omega (1 +
 * RETURN_SPAN). Only there can a branch meet the hanging chain: at any other rate the hanging
 * chain is an isolated equilibrium. */
static int at_a_birth(nlink_path *p, double omega)
{
    int index[2];
    for (int side = 0; side < 2; side++) {
        const double w = omega * (side ? 1 + RETURN_SPAN : 1 - RETURN_SPAN);
        if (whirl_nlink_balance_factor(p->balance, w, scr_zero(p))) return 1; /* singular */
        index[side] = whirl_nlink_balance_index(p->balance);
    }
    return index[0] != index[1];
}

int path_find_events(nlink_path *p, int branch)
{
    p->pub.n_events = 0;
    step_frame f;
    double sigma;
    int status = GSL_SUCCESS;
    if (p->s.last_rate_sign * p->s.rate_sign < 0) {
        frame_of_last(p, &f, TARGET_FOLD, 0);
        /* t_omega at the step's ends: at its start the tangent there, at its end the one
         * oriented along the step's row (the same as phi's, to the corrector's round-off) */
        f.known = 1;
        f.values[0] = p->s.last.t_w;
        f.values[1] = p->pub.t_omega;
        if (!(status = frame_locate(&f, 0, f.ds, &sigma)))
            status = add_event(p, WHIRL_EVENT_FOLD, &f, sigma);
    }
    if (!status && branch) {
        frame_of_last(p, &f, TARGET_BRANCH, 0);
        if (!(status = frame_locate(&f, 0, f.ds, &sigma)))
            status = add_event(p, WHIRL_EVENT_BRANCH_POINT, &f, sigma);
    }
    const int passed = p->s.last.angles
        ? path_shape_projection(p->pub.chain->n, arr_theta(p), arr_theta0(p)) < 0
        : p->s.last.a0 != 0 && (p->s.last.a0 > 0) != (p->pub.tip_r > 0);
    if (!status && passed) {
        frame_of_last(p, &f, TARGET_RETURN, 0);
        if (!(status = frame_locate(&f, 0, f.ds, &sigma)) && !at_a_birth(p, f.w))
            status = whirl_fail(GSL_EFAILED, "the step between omega=" WHIRL_Q_RATE "%.17g and "
                                "omega=" WHIRL_Q_RATE "%.17g meets the hanging chain at omega="
                                WHIRL_Q_RATE "%.17g, where no branch is born", f.w0, f.w1, f.w);
        if (!status) {
            status = add_event(p, WHIRL_EVENT_RETURN, &f, sigma);
            /* the path ends on the hanging chain */
            p->pub.ended = 1;
            p->pub.omega = f.w;
            p->pub.tip_r = 0;
        }
    }
    /* in order of arclength */
    for (int i = 1; i < p->pub.n_events; i++)
        for (int j = i; j > 0 && p->pub.event[j].arclength < p->pub.event[j - 1].arclength; j--) {
            whirl_branch_event tmp = p->pub.event[j];
            p->pub.event[j] = p->pub.event[j - 1];
            p->pub.event[j - 1] = tmp;
            const size_t n = p->pub.chain->n;
            double *a = arr_event_theta(p) + (size_t)j * n, *b = a - n;
            for (size_t k = 0; k < n; k++) {
                double x = a[k];
                a[k] = b[k];
                b[k] = x;
            }
        }
    return status;
}
