/* Branches of the N-link chain's relative equilibria by pseudo-arclength continuation.
 *
 * The shape is built up from the tip (src/nlink.c): with the tip radius a and u_i = r_i / a,
 *     eta_i = sum_{j >= i} m_j omega^2 u_j,  V_i = g sum_{j >= i} m_j,  H_i = a eta_i,
 *     T_i = sqrt(H_i^2 + V_i^2),  u_{i-1} = u_i - l_i eta_i / T_i,  u_N = 1,
 * and the pivot lands on the axis when G(omega, a) = u_0 / |u| = 0 (|u|^2 = sum_{i=0}^N u_i^2:
 * the normalisation keeps G of order one when r spans many decades, as on the high modes, whose
 * tip radius can be 1e-18 of the largest or less). G depends on a only through a^2 and
 * is the linearised shot at a = 0, whose zeros in omega are the critical rates omega_k: the
 * trivial solution a = 0 is divided out and the pitchfork at omega_k becomes a regular point of
 * the curve G = 0, with a vertical tangent. Every relative equilibrium is a point of that curve
 * (a fixes the whole chain), so continuing the curve continues the equilibrium in all its link
 * angles theta_i = atan2(H_i, V_i). G_omega, G_a and the link angles' derivatives come from the
 * forward differentiation of the recursion (exact, O(N) per shot).
 *
 * Pseudo-arclength continuation (Keller 1977, "Numerical solution of bifurcation and nonlinear
 * eigenvalue problems", in Applications of Bifurcation Theory; Allgower & Georg 1990,
 * "Numerical Continuation Methods", ch. 2; Doedel's AUTO): the arclength is measured in
 * (ln omega, theta) with the metric
 *     ds^2 = (d omega / omega)^2 + (1/N) sum_i d theta_i^2
 *          = x^T M x,  x = (d omega, d a),  M from d theta_i = theta_i,omega d omega + theta_i,a d a,
 * the tangent t solves G_omega t_omega + G_a t_a = 0, t^T M t = 1, oriented along the travel.
 * A step predicts x0 + ds t0 (or, for a, a0 exp(ds t0_a / a0): the tangent in ln|a|, when that
 * predicts the previous point better: the tip radius of a high mode varies exponentially) and
 * corrects by Newton's method on
 *     G(x) = 0,   (M0 t0) . (x - x0) = ds,
 * to round-off (one iteration after the correction falls below 1e-10, or once it stops
 * decreasing below 1e-8: the round-off floor of the shot on a high mode). The step is rejected and
 * halved if Newton needs more than NEWTON_MAX iterations, the tangent turns by more than
 * TURN_MAX or a link angle changes by more than DTHETA_MAX (the corrector never lands on another
 * curve); it grows 1.5-fold after an easy step, up to DS_MAX.
 *
 * Test functions between two accepted points: a fold where t_omega changes sign; a branch point
 * (grad G = 0 on G = 0: two curves cross, which the one-dimensional reduction makes visible as
 * the tangent (G_a, -G_omega) reversing against the direction of travel) where that orientation
 * changes; a return to the hanging chain where a changes sign. Each is located by Brent's method
 * (GSL roots/brent.c) on the step's arclength sigma in [0, ds], every evaluation a corrector
 * solve on the hyperplane at sigma: at a fold omega(sigma) is stationary, so the arclength error
 * enters omega squared. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_roots.h>

#include "error.h"
#include "steady_internal.h"

#define DS_FIRST 0.02    /* first step from a start */
#define DS_MIN 1e-7      /* smallest step before the continuation fails */
#define DS_MAX 0.1       /* largest step */
#define TURN_MAX 0.2     /* largest turn of the tangent per step [rad] */
#define DTHETA_MAX 0.2   /* largest change of a link angle per step [rad] */
#define NEWTON_MAX 10    /* corrector iterations per trial step */
#define NEWTON_EASY 4    /* a step converged in this many or fewer may grow */
#define NEWTON_TOL 1e-10 /* correction (metric norm) after which one last iteration is made */
#define NEWTON_FLOOR 1e-8 /* a correction this small that stops decreasing is round-off */
#define LOCATE_MAX 200   /* Brent iterations for an event */

typedef struct shot {
    double g, g_w, g_a;      /* G and its partial derivatives */
    double m_ww, m_wa, m_aa; /* the metric M at the point */
} shot;

/* x y / d: d = t (single = 1) or t^2; with big, as (x / t) (y / t) or (x / t) y, which do not
 * overflow where t^2 does. */
static double ratio(double x, double y, double t, double d, int big)
{
    if (!big) return d == 1 ? x * y / t : x * y / d;
    return d == 1 ? (x / t) * y : (x / t) * (y / t);
}

/* G, its derivatives and the metric at (omega, a); if theta is not NULL, the link angles into
 * theta[0..N-1]; if embed is not NULL, the unit tangent (G_a, -G_omega) normalised, embedded in
 * (ln omega, theta / sqrt(N)), into embed[0..N] (embed[N+1..2N] is scratch). */
static void shoot_embed(const whirl_chain *c, double omega, double a, shot *s, double *theta,
                        double *embed)
{
    size_t n = c->n;
    double u = 1, u_a = 0, u_w = 0, eta = 0, eta_a = 0, eta_w = 0, v = 0;
    double s_aa = 0, s_wa = 0, s_ww = 0, w2 = omega * omega;
    double q = 1, q_a = 0, q_w = 0; /* sum of u_i^2 and its derivatives */
    for (size_t i = n; i >= 1; i--) {
        double m = c->mass[i - 1], l = c->length[i - 1];
        eta_w += m * (2 * omega * u + w2 * u_w);
        eta += m * w2 * u;
        eta_a += m * w2 * u_a;
        v += m * c->gravity;
        double h = a * eta, h_a = eta + a * eta_a, h_w = a * eta_w;
        double t2 = h * h + v * v, t = sqrt(t2);
        /* H^2 ~ omega^4 (and H H_a) overflow from omega ~ 1e77: from T^2 = 1e300 on,
         * T = hypot(H, V) and ratios to it */
        const int big = !(t2 < 1e300);
        if (big) t = hypot(h, v);
        double t_a = ratio(h, h_a, t, 1, big), t_w = ratio(h, h_w, t, 1, big);
        u -= l * eta / t;
        u_a -= l * (eta_a / t - ratio(eta, t_a, t, t2, big));
        u_w -= l * (eta_w / t - ratio(eta, t_w, t, t2, big));
        q += u * u;
        q_a += 2 * u * u_a;
        q_w += 2 * u * u_w;
        double th_a = ratio(v, h_a, t, t2, big), th_w = ratio(v, h_w, t, t2, big);
        s_aa += th_a * th_a;
        s_wa += th_a * th_w;
        s_ww += th_w * th_w;
        if (theta) theta[i - 1] = atan2(h, v);
        if (embed) embed[i] = th_w, embed[n + i] = th_a;
    }
    /* G = u_0 / |u| */
    double norm = sqrt(q);
    s->g = u / norm;
    s->g_a = u_a / norm - 0.5 * u * q_a / (q * norm);
    s->g_w = u_w / norm - 0.5 * u * q_w / (q * norm);
    s->m_ww = 1 / w2 + s_ww / (double)n;
    s->m_wa = s_wa / (double)n;
    s->m_aa = s_aa / (double)n;
    if (embed) {
        double r_w = s->g_a, r_a = -s->g_w;
        double len = sqrt(s->m_ww * r_w * r_w + 2 * s->m_wa * r_w * r_a + s->m_aa * r_a * r_a);
        double t_w = r_w / len, t_a = r_a / len, scale = 1 / sqrt((double)n);
        embed[0] = t_w / omega;
        for (size_t i = 1; i <= n; i++) embed[i] = scale * (embed[i] * t_w + embed[n + i] * t_a);
    }
}

static void shoot(const whirl_chain *c, double omega, double a, shot *s, double *theta)
{
    shoot_embed(c, omega, a, s, theta, NULL);
}

static double metric_dot(const double *m, double x_w, double x_a, double y_w, double y_a)
{
    return m[0] * x_w * y_w + m[1] * (x_w * y_a + x_a * y_w) + m[2] * x_a * y_a;
}

static void shot_metric(const shot *s, double *m)
{
    m[0] = s->m_ww;
    m[1] = s->m_wa;
    m[2] = s->m_aa;
}

/* Newton's method on G = 0 and the row c . (x - x0) = sigma from (*w, *a). Returns 0 when it
 * converged (the last shot in *s), -1 otherwise. */
static int correct(whirl_nlink_path *p, const double *m0, double w0, double a0, double c_w,
                   double c_a, double sigma, double *w, double *a, shot *s, int *iters)
{
    int final = 0;
    double prev = INFINITY;
    for (int it = 0; it < NEWTON_MAX; it++) {
        shoot(p->chain, *w, *a, s, NULL);
        p->shots++;
        if (!(isfinite(s->g) && isfinite(s->g_a) && isfinite(s->g_w))) return -1;
        double r1 = -s->g, r2 = sigma - (c_w * (*w - w0) + c_a * (*a - a0));
        double det = s->g_w * c_a - s->g_a * c_w;
        if (!(det != 0 && isfinite(det))) return -1;
        double dw = (r1 * c_a - s->g_a * r2) / det, da = (s->g_w * r2 - c_w * r1) / det;
        *w += dw;
        *a += da;
        if (!(*w > 0 && isfinite(*w) && isfinite(*a))) return -1;
        if (final) {
            shoot(p->chain, *w, *a, s, NULL);
            p->shots++;
            return 0;
        }
        double norm2 = metric_dot(m0, dw, da, dw, da), norm = sqrt(norm2);
        if (!(norm2 >= 0)) return -1;
        if (norm <= NEWTON_TOL) {
            final = 1;
            if (iters) *iters = it + 1;
        } else if (it >= 2 && norm <= NEWTON_FLOOR && norm >= 0.5 * prev) {
            /* no longer decreasing: the round-off floor of an ill-conditioned shot */
            if (iters) *iters = it + 1;
            return 0;
        }
        prev = norm;
    }
    return -1;
}

whirl_nlink_path *whirl_nlink_path_alloc(const whirl_chain *c)
{
    if (c == NULL || c->n < 1) {
        whirl_fail(GSL_EINVAL, "a chain needs at least one link");
        return NULL;
    }
    whirl_nlink_path *p = calloc(1, sizeof *p);
    if (p == NULL) goto fail;
    p->chain = c;
    p->work = malloc((2 * c->n + 2 * (2 * c->n + 1)) * sizeof *p->work);
    if (p->work == NULL) goto fail;
    p->theta = p->work;
    p->theta_trial = p->theta + c->n;
    p->embed = p->theta_trial + c->n;
    p->embed_trial = p->embed + 2 * c->n + 1;
    return p;
fail:
    whirl_nlink_path_free(p);
    whirl_fail(GSL_ENOMEM, "out of memory for a path on a chain of %zu links", c->n);
    return NULL;
}

void whirl_nlink_path_free(whirl_nlink_path *p)
{
    if (p == NULL) return;
    free(p->work);
    free(p);
}

/* The unit tangent at s (metric m) oriented against the previous direction (ref_w, ref_a) in the
 * metric m_ref; raw_sign: +1 if it is (G_a, -G_omega) normalised, -1 if its opposite. */
static void tangent(const shot *s, const double *m, const double *m_ref, double ref_w,
                    double ref_a, double *t_w, double *t_a, int *raw_sign)
{
    double r_w = s->g_a, r_a = -s->g_w;
    double norm = sqrt(metric_dot(m, r_w, r_a, r_w, r_a));
    *raw_sign = metric_dot(m_ref, r_w, r_a, ref_w, ref_a) >= 0 ? 1 : -1;
    *t_w = *raw_sign * r_w / norm;
    *t_a = *raw_sign * r_a / norm;
}

/* The state at an accepted point. */
static void set_point(whirl_nlink_path *p, double omega, double a, const shot *s)
{
    p->omega = omega;
    p->tip_r = a;
    shot_metric(s, p->metric);
    if (omega < p->omega_lo) p->omega_lo = omega;
    if (omega > p->omega_hi) p->omega_hi = omega;
}

static void reset(whirl_nlink_path *p)
{
    p->arclength = 0;
    p->ds = DS_FIRST;
    p->steps = p->rejected = p->shots = 0;
    p->n_events = 0;
    p->ended = 0;
    p->omega_lo = INFINITY;
    p->omega_hi = -INFINITY;
    p->have_last = 0;
}

int whirl_nlink_path_birth(whirl_nlink_path *p, int mode)
{
    const whirl_chain *c = p->chain;
    if (mode < 1 || (size_t)mode > c->n)
        return whirl_fail(GSL_EINVAL, "mode %d does not exist: a chain of %zu links has modes "
                          "1..%zu", mode, c->n, c->n);
    double *crit = malloc((size_t)mode * sizeof *crit);
    if (crit == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %d critical rates", mode);
    int status = whirl_nlink_critical(c, (size_t)mode, crit);
    double omega = crit[mode - 1];
    free(crit);
    if (status) return status;
    reset(p);
    p->mode = mode;
    /* Newton's method on the linearised shot G(omega, 0) */
    shot s;
    for (int it = 0; it < 20; it++) {
        shoot(c, omega, 0, &s, NULL);
        p->shots++;
        double d = s.g / s.g_w;
        if (!isfinite(d) || fabs(d) > 1e-6 * omega)
            return whirl_fail(GSL_EFAILED, "mode %d: the critical rate %.17g does not polish",
                              mode, omega);
        omega -= d;
        if (fabs(d) <= 4 * DBL_EPSILON * omega) break;
    }
    shoot_embed(c, omega, 0, &s, p->theta, p->embed);
    p->shots++;
    p->omega_birth = omega;
    set_point(p, omega, 0, &s);
    /* the tangent is vertical: into a > 0 */
    p->t_omega = 0;
    p->t_tip = 1 / sqrt(s.m_aa);
    double tw, ta;
    tangent(&s, p->metric, p->metric, p->t_omega, p->t_tip, &tw, &ta, &p->raw_sign);
    return GSL_SUCCESS;
}

int whirl_nlink_path_start(whirl_nlink_path *p, double omega, double tip_r, int direction)
{
    if (!(isfinite(omega) && omega > 0 && isfinite(tip_r)))
        return whirl_fail(GSL_EINVAL, "a path starts at omega > 0 and a finite tip radius");
    reset(p);
    p->mode = 0;
    p->omega_birth = 0;
    double w = omega, a = tip_r, m[3] = {1, 0, 1};
    shot s;
    int iters;
    if (correct(p, m, omega, tip_r, 1, 0, 0, &w, &a, &s, &iters) != 0 || a == 0)
        return whirl_fail(GSL_EFAILED, "no equilibrium near omega=%.17g, tip radius %.17g",
                          omega, tip_r);
    shoot_embed(p->chain, w, a, &s, p->theta, p->embed);
    p->shots++;
    set_point(p, w, a, &s);
    double tw, ta;
    int raw;
    tangent(&s, p->metric, p->metric, s.g_a, -s.g_w, &tw, &ta, &raw);
    if ((direction >= 0) != (tw >= 0)) tw = -tw, ta = -ta, raw = -raw;
    p->t_omega = tw;
    p->t_tip = ta;
    p->raw_sign = raw;
    return GSL_SUCCESS;
}

void whirl_nlink_path_reverse(whirl_nlink_path *p)
{
    p->t_omega = -p->t_omega;
    p->t_tip = -p->t_tip;
    p->raw_sign = -p->raw_sign;
    p->have_last = 0;
}

/* ---- events: located on the last step by Brent's method on sigma ---- */

typedef enum { TARGET_OMEGA, TARGET_FOLD, TARGET_BRANCH, TARGET_RETURN } target_kind;

typedef struct step_frame {
    whirl_nlink_path *p;
    double m0[3];        /* metric at the step's start */
    double w0, a0;       /* the step's start */
    double t0_w, t0_a;   /* its tangent */
    double w1, a1, ds;   /* its end and length */
    target_kind kind;
    double target;       /* the rate for TARGET_OMEGA */
    int failed;
    double w, a;         /* the last corrected point */
    shot s;
} step_frame;

/* The corrected point at arclength sigma of the step (a start on the chord). */
static int frame_point(step_frame *f, double sigma)
{
    double lambda = sigma / f->ds;
    double c_w = f->m0[0] * f->t0_w + f->m0[1] * f->t0_a;
    double c_a = f->m0[1] * f->t0_w + f->m0[2] * f->t0_a;
    int iters;
    /* from the geometric interpolation of a (a tip radius that varies exponentially), then from
     * the linear one */
    for (int geometric = (f->a0 > 0 && f->a1 > 0) || (f->a0 < 0 && f->a1 < 0); geometric >= 0;
         geometric--) {
        f->w = f->w0 + lambda * (f->w1 - f->w0);
        f->a = geometric ? f->a0 * pow(f->a1 / f->a0, lambda) : f->a0 + lambda * (f->a1 - f->a0);
        if (correct(f->p, f->m0, f->w0, f->a0, c_w, c_a, sigma, &f->w, &f->a, &f->s, &iters) == 0)
            return 0;
    }
    return -1;
}

static double frame_phi(double sigma, void *params)
{
    step_frame *f = params;
    if (frame_point(f, sigma) != 0) {
        f->failed = 1;
        return 0; /* ends Brent's iteration, which then reports the failure */
    }
    const shot *s = &f->s;
    double r_w = s->g_a, r_a = -s->g_w;
    double along = metric_dot(f->m0, r_w, r_a, f->t0_w, f->t0_a);
    switch (f->kind) {
    case TARGET_OMEGA:
        return f->w - f->target;
    case TARGET_FOLD: {
        double m[3];
        shot_metric(s, m);
        return (along >= 0 ? 1 : -1) * r_w / sqrt(metric_dot(m, r_w, r_a, r_w, r_a));
    }
    case TARGET_BRANCH:
        return along;
    case TARGET_RETURN:
        return f->a;
    }
    return GSL_NAN;
}

/* The sigma in [lo, hi] where phi changes sign (phi(lo) and phi(hi) of opposite signs, or one
 * zero); the corrected point left in f->w, f->a, f->s. */
static int frame_locate(step_frame *f, double lo, double hi, double *sigma)
{
    double f_lo = frame_phi(lo, f), f_hi = frame_phi(hi, f);
    if (f->failed) return whirl_fail(GSL_EFAILED, "an event could not be located");
    if (f_lo == 0 || f_hi == 0 || (f_lo > 0) == (f_hi > 0)) {
        *sigma = fabs(f_lo) <= fabs(f_hi) ? lo : hi;
        frame_phi(*sigma, f);
        return GSL_SUCCESS;
    }
    gsl_function fn = {frame_phi, f};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (s == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the root solver");
    int status = gsl_root_fsolver_set(s, &fn, lo, hi);
    for (int it = 0; status == GSL_SUCCESS; it++) {
        status = gsl_root_fsolver_iterate(s);
        if (f->failed || status != GSL_SUCCESS) {
            status = whirl_fail(GSL_EFAILED, "an event at omega=%.17g could not be located",
                                f->w);
            break;
        }
        double x_lo = gsl_root_fsolver_x_lower(s), x_hi = gsl_root_fsolver_x_upper(s);
        if (x_hi - x_lo <= 4 * DBL_EPSILON * f->ds) {
            *sigma = gsl_root_fsolver_root(s);
            break;
        }
        if (it == LOCATE_MAX) {
            status = whirl_fail(GSL_EMAXITER, "an event was not located in %d steps",
                                LOCATE_MAX);
            break;
        }
    }
    gsl_root_fsolver_free(s);
    if (status == GSL_SUCCESS && (frame_phi(*sigma, f), f->failed))
        status = whirl_fail(GSL_EFAILED, "an event could not be located");
    return status;
}

static void frame_of_last(whirl_nlink_path *p, step_frame *f, target_kind kind, double target)
{
    f->p = p;
    for (int i = 0; i < 3; i++) f->m0[i] = p->last.m0[i];
    f->w0 = p->last.w0;
    f->a0 = p->last.a0;
    f->t0_w = p->last.t_w;
    f->t0_a = p->last.t_a;
    f->w1 = p->omega;
    f->a1 = p->tip_r;
    f->ds = p->last.ds;
    f->kind = kind;
    f->target = target;
    f->failed = 0;
}

int whirl_nlink_path_crossings(whirl_nlink_path *p, double omega, int max, double *tip_r)
{
    if (!p->have_last) return 0;
    /* the step cut at its folds into pieces where omega is monotone */
    double start = p->arclength - p->last.ds;
    double cut[WHIRL_PATH_EVENTS_MAX + 2], w_cut[WHIRL_PATH_EVENTS_MAX + 2];
    int ncut = 0;
    cut[ncut] = 0, w_cut[ncut++] = p->last.w0;
    for (int i = 0; i < p->n_events; i++)
        if (p->event[i].kind == WHIRL_EVENT_FOLD)
            cut[ncut] = p->event[i].arclength - start, w_cut[ncut++] = p->event[i].omega;
    cut[ncut] = p->last.ds, w_cut[ncut++] = p->omega;
    int found = 0;
    for (int k = 0; k + 1 < ncut && found < max; k++) {
        double lo = w_cut[k], hi = w_cut[k + 1];
        if (!((lo < omega && omega <= hi) || (hi <= omega && omega < lo))) continue;
        step_frame f;
        frame_of_last(p, &f, TARGET_OMEGA, omega);
        double sigma;
        int status = frame_locate(&f, cut[k], cut[k + 1], &sigma);
        if (status) return -status;
        /* polished at omega itself */
        double w = omega, a = f.a, m[3];
        shot_metric(&f.s, m);
        int iters;
        if (correct(p, m, omega, f.a, 1, 0, 0, &w, &a, &f.s, &iters) != 0 || a == 0)
            return -whirl_fail(GSL_EFAILED, "no equilibrium at omega=%.17g near the branch",
                               omega);
        tip_r[found++] = a;
    }
    return found;
}

static int add_event(whirl_nlink_path *p, whirl_event_kind kind, step_frame *f, double sigma)
{
    if (p->n_events == WHIRL_PATH_EVENTS_MAX) return GSL_SUCCESS;
    whirl_branch_event *e = &p->event[p->n_events++];
    e->kind = kind;
    e->omega = f->w;
    e->tip_r = f->a;
    e->arclength = p->arclength - p->last.ds + sigma;
    whirl_shape_info info;
    int status = whirl_nlink_info(p->chain, f->w, fabs(f->a), p->mode, &info);
    e->n_nodes = status == GSL_SUCCESS ? info.n_nodes : -1;
    return status;
}

/* Finds the events of the last step and sorts them by arclength. */
static int find_events(whirl_nlink_path *p, const shot *s1, int raw_sign1)
{
    p->n_events = 0;
    step_frame f;
    double sigma;
    int status = GSL_SUCCESS;
    if (p->last.t_w * p->t_omega < 0) {
        frame_of_last(p, &f, TARGET_FOLD, 0);
        if (!(status = frame_locate(&f, 0, f.ds, &sigma)))
            status = add_event(p, WHIRL_EVENT_FOLD, &f, sigma);
    }
    if (!status && raw_sign1 != p->last.raw_sign) {
        frame_of_last(p, &f, TARGET_BRANCH, 0);
        if (!(status = frame_locate(&f, 0, f.ds, &sigma)))
            status = add_event(p, WHIRL_EVENT_BRANCH_POINT, &f, sigma);
    }
    if (!status && p->last.a0 != 0 && (p->last.a0 > 0) != (p->tip_r > 0)) {
        frame_of_last(p, &f, TARGET_RETURN, 0);
        if (!(status = frame_locate(&f, 0, f.ds, &sigma))) {
            status = add_event(p, WHIRL_EVENT_RETURN, &f, sigma);
            /* the path ends on the hanging chain */
            p->ended = 1;
            p->omega = f.w;
            p->tip_r = 0;
        }
    }
    (void)s1;
    /* in order of arclength */
    for (int i = 1; i < p->n_events; i++)
        for (int j = i; j > 0 && p->event[j].arclength < p->event[j - 1].arclength; j--) {
            whirl_branch_event tmp = p->event[j];
            p->event[j] = p->event[j - 1];
            p->event[j - 1] = tmp;
        }
    return status;
}

/* The ratio of the largest to the smallest link tension at (omega, a). */
static double tension_spread(const whirl_chain *c, double omega, double a)
{
    double u = 1, eta = 0, v = 0, t_min = INFINITY, t_max = 0;
    for (size_t i = c->n; i >= 1; i--) {
        eta += c->mass[i - 1] * omega * omega * u;
        v += c->mass[i - 1] * c->gravity;
        const double t = hypot(a * eta, v);
        u -= c->length[i - 1] * eta / t;
        t_min = fmin(t_min, t);
        t_max = fmax(t_max, t);
    }
    return t_max / t_min;
}

/* The failure of the continuation at the last point (w0, a0), status with its message set: named
 * for what it is when round-off decides it. At high rates the higher modes fold ever more sharply
 * (a link nearly slack between taut ones, its direction set by its weight alone), and G then
 * moves by |G_a a| eps, more than the corrector's tolerance NEWTON_TOL, for one unit of round-off
 * in the tip radius: no rate beyond can be resolved. */
static int fail_at(const whirl_nlink_path *p, int status, double w0, double a0)
{
    shot s;
    shoot(p->chain, w0, a0, &s, NULL);
    const double wobble = fabs(s.g_a * a0) * DBL_EPSILON;
    if (!(wobble > NEWTON_TOL)) return status;
    char mode[32] = "";
    if (p->mode > 0) snprintf(mode, sizeof mode, "mode %d: ", p->mode);
    return whirl_fail(status, "%sthe shapes are not resolved above omega=%.6g: there one unit "
                      "of round-off in the tip radius moves the pivot by %.2g of the shape's size "
                      "(link tensions differing by a factor %.2g), more than the shooting's "
                      "tolerance; lower rates only", mode, w0,
                      wobble, tension_spread(p->chain, w0, a0));
}

int whirl_nlink_path_step(whirl_nlink_path *p)
{
    const whirl_chain *c = p->chain;
    p->n_events = 0;
    if (p->ended)
        return whirl_fail(GSL_EDOM, "the branch ended on the hanging chain at omega=%.17g",
                          p->omega);
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped at omega=%.17g after %ld steps",
                          p->omega, p->steps);
    const double w0 = p->omega, a0 = p->tip_r, *m0 = p->metric;
    const double c_w = m0[0] * p->t_omega + m0[1] * p->t_tip;
    const double c_a = m0[1] * p->t_omega + m0[2] * p->t_tip;
    /* the predictor of a: along the tangent, or along it in ln|a| (where a decays or grows
     * exponentially, as on the high modes), whichever predicts the previous point better */
    int log_predictor = 0;
    if (p->have_last && a0 != 0 && p->last.a0 != 0 && (a0 > 0) == (p->last.a0 > 0)) {
        double back = -p->last.ds, lin = a0 + back * p->t_tip;
        double lg = a0 * exp(fmax(-50, fmin(50, back * p->t_tip / a0)));
        log_predictor = fabs(lg - p->last.a0) < fabs(lin - p->last.a0);
    }
    for (;;) {
        double ds = p->ds, w = w0 + ds * p->t_omega;
        double a = log_predictor ? a0 * exp(fmax(-50, fmin(50, ds * p->t_tip / a0)))
                                 : a0 + ds * p->t_tip;
        shot s;
        int iters = NEWTON_MAX, ok = correct(p, m0, w0, a0, c_w, c_a, ds, &w, &a, &s, &iters) == 0;
        double turn = 0, dtheta = 0, t_w = 0, t_a = 0;
        int raw = 0;
        if (ok) {
            shoot_embed(c, w, a, &s, p->theta_trial, p->embed_trial);
            p->shots++;
            double m1[3];
            shot_metric(&s, m1);
            tangent(&s, m1, m0, p->t_omega, p->t_tip, &t_w, &t_a, &raw);
            /* the turn of the tangent in (ln omega, theta / sqrt(N)); the embedded tangents are
             * those of (G_a, -G_omega), oriented by raw and the current orientation */
            double cosine = 0;
            for (size_t i = 0; i <= c->n; i++) cosine += p->embed_trial[i] * p->embed[i];
            cosine *= raw * p->raw_sign;
            turn = acos(fmin(1, fmax(-1, cosine)));
            for (size_t i = 0; i < c->n; i++)
                dtheta = fmax(dtheta, fabs(p->theta_trial[i] - p->theta[i]));
            ok = turn <= TURN_MAX && dtheta <= DTHETA_MAX;
        }
        if (!ok) {
            p->rejected++;
            p->ds *= 0.5;
            if (p->ds < DS_MIN) {
                int status;
                if (p->mode > 0)
                    status = whirl_fail(GSL_EFAILED, "mode %d: the continuation fails at "
                                        "omega=%.17g (tip radius %.6g): no convergence at the "
                                        "smallest step %g", p->mode, w0, a0, DS_MIN);
                else
                    status = whirl_fail(GSL_EFAILED, "the continuation fails at omega=%.17g (tip "
                                        "radius %.6g): no convergence at the smallest step %g",
                                        w0, a0, DS_MIN);
                return fail_at(p, status, w0, a0);
            }
            continue;
        }
        /* accepted */
        for (int i = 0; i < 3; i++) p->last.m0[i] = m0[i];
        p->last.w0 = w0;
        p->last.a0 = a0;
        p->last.t_w = p->t_omega;
        p->last.t_a = p->t_tip;
        p->last.ds = ds;
        p->last.raw_sign = p->raw_sign;
        p->have_last = 1;
        double *tmp = p->theta;
        p->theta = p->theta_trial;
        p->theta_trial = tmp;
        tmp = p->embed;
        p->embed = p->embed_trial;
        p->embed_trial = tmp;
        set_point(p, w, a, &s);
        p->t_omega = t_w;
        p->t_tip = t_a;
        p->raw_sign = raw;
        p->arclength += ds;
        p->steps++;
        if (iters <= NEWTON_EASY && turn < TURN_MAX / 2 && dtheta < DTHETA_MAX / 2)
            p->ds = fmin(1.5 * ds, DS_MAX);
        const int status = find_events(p, &s, raw);
        return status ? fail_at(p, status, w0, a0) : GSL_SUCCESS;
    }
}

int whirl_nlink_residual(const whirl_chain *c, double omega, double tip_r, double *g,
                         double *g_omega, double *g_tip)
{
    if (c == NULL || c->n < 1) return whirl_fail(GSL_EINVAL, "a chain needs at least one link");
    if (!(isfinite(omega) && omega > 0 && isfinite(tip_r)))
        return whirl_fail(GSL_EINVAL, "the residual needs omega > 0 and a finite tip radius");
    shot s;
    shoot(c, omega, tip_r, &s, NULL);
    *g = s.g;
    if (g_omega) *g_omega = s.g_w;
    if (g_tip) *g_tip = s.g_a;
    return GSL_SUCCESS;
}

/* ---- drivers: a branch from its birth ---- */

#define STEPS_MAX 100000 /* accepted steps of one path */

/* Follows the path until its rate first exceeds omega_max, it returns to the hanging chain, or
 * visit returns non-zero (WHIRL_VISIT_STOP: success). visit gets every crossing of the rates
 * omega[0..n-1] (j its index, info filled) and every event (j = SIZE_MAX, event set). */
static int follow_path(whirl_nlink_path *p, double omega_max, size_t n, const double *omega,
                       whirl_nlink_visit_fn visit, void *ctx)
{
    const whirl_chain *c = p->chain;
    while (p->omega <= omega_max && !p->ended) {
        if (p->steps >= STEPS_MAX)
            return whirl_fail(GSL_EMAXITER, "mode %d: %d continuation steps reached "
                              "omega=%.17g only", p->mode, STEPS_MAX, p->omega);
        int status = whirl_nlink_path_step(p);
        if (status) return status;
        /* crossings and events in the order of arclength: events first where they come
         * first is not needed by the callers, so crossings of a step follow its events */
        for (int e = 0; e < p->n_events; e++) {
            whirl_shape_info info;
            if ((status = whirl_nlink_info(c, p->event[e].omega, fabs(p->event[e].tip_r),
                                           p->mode, &info)))
                return status;
            if ((status = visit(ctx, SIZE_MAX, &info, &p->event[e])))
                return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
        }
        for (size_t j = 0; j < n; j++) {
            double tip[WHIRL_PATH_EVENTS_MAX + 1];
            int found = whirl_nlink_path_crossings(p, omega[j], WHIRL_PATH_EVENTS_MAX + 1, tip);
            if (found < 0) return -found;
            for (int k = 0; k < found; k++) {
                whirl_shape_info info;
                if ((status = whirl_nlink_info(c, omega[j], tip[k], p->mode, &info)))
                    return status;
                if ((status = visit(ctx, j, &info, NULL)))
                    return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
            }
        }
    }
    return GSL_SUCCESS;
}

int whirl_nlink_follow(const whirl_chain *c, int mode, double omega_max, size_t n,
                       const double *omega, whirl_nlink_visit_fn visit, void *ctx)
{
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    if (p == NULL) return whirl_last_error()[0] ? GSL_ENOMEM : GSL_EINVAL;
    int status = whirl_nlink_path_birth(p, mode);
    if (!status) status = follow_path(p, omega_max, n, omega, visit, ctx);
    whirl_nlink_path_free(p);
    return status;
}

/* The first crossing of each rate. */
typedef struct first_ctx {
    whirl_shape_info *info;
    int *exists;
    size_t n, left;
} first_ctx;

static int first_visit(void *ctx, size_t j, const whirl_shape_info *info,
                       const whirl_branch_event *event)
{
    first_ctx *f = ctx;
    if (event != NULL || f->exists[j]) return 0;
    f->exists[j] = 1;
    f->info[j] = *info;
    return --f->left == 0 ? WHIRL_VISIT_STOP : 0;
}

/* The branch of mode at the rates omega[]: a path from the birth up to the largest of them (and
 * at least to twice the birth rate, where a branch that first turns to lower rates is seen). */
static int branch_path(whirl_nlink_path *p, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists)
{
    for (size_t j = 0; j < n; j++) {
        int status = whirl_steady_check_args(omega[j], mode);
        if (status != GSL_SUCCESS) return status;
        exists[j] = 0;
    }
    if ((size_t)mode > p->chain->n)
        return whirl_fail(GSL_EDOM, "mode %d does not exist: a chain of %zu links has modes "
                          "1..%zu", mode, p->chain->n, p->chain->n);
    int status = whirl_nlink_path_birth(p, mode);
    if (status) return status;
    double top = 2 * p->omega_birth;
    for (size_t j = 0; j < n; j++) top = fmax(top, omega[j]);
    first_ctx f = {info, exists, n, n};
    if (n == 0) return GSL_SUCCESS;
    status = follow_path(p, top, n, omega, first_visit, &f);
    if (status == GSL_EFAILED || status == GSL_EMAXITER) {
        /* a failure above every rate still missing, while looking for a turn of a branch
         * back below its birth: those rates are below the branch as far as it was followed */
        int below = 1;
        for (size_t j = 0; j < n; j++)
            if (!exists[j] && omega[j] >= p->omega_lo) below = 0;
        if (below) status = GSL_SUCCESS;
    }
    return status;
}

int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists)
{
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    if (p == NULL) return whirl_last_error()[0] ? GSL_ENOMEM : GSL_EINVAL;
    int status = branch_path(p, mode, n, omega, info, exists);
    whirl_nlink_path_free(p);
    return status;
}

int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, double tip_r_guess,
                      whirl_shape_info *info)
{
    (void)tip_r_guess;
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    if (p == NULL) return whirl_last_error()[0] ? GSL_ENOMEM : GSL_EINVAL;
    int exists = 0;
    int status = branch_path(p, mode, 1, &omega, info, &exists);
    if (status == GSL_SUCCESS && !exists) {
        if (p->ended)
            status = whirl_fail(GSL_EDOM, "mode %d does not exist at omega=%.17g: its branch, "
                                "born at omega_%d=%.17g, returns to the hanging chain at "
                                "omega=%.17g without reaching it", mode, omega, mode,
                                p->omega_birth, p->omega);
        else if (p->omega_lo >= p->omega_birth)
            status = whirl_steady_fail_missing(mode, omega, p->omega_birth);
        else
            status = whirl_fail(GSL_EDOM, "mode %d does not exist at omega=%.17g: its branch, "
                                "born at omega_%d=%.17g, reaches down to omega=%.17g only",
                                mode, omega, mode, p->omega_birth, p->omega_lo);
    }
    whirl_nlink_path_free(p);
    return status;
}
