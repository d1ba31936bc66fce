/* The tip shot of the N-link continuation (src/steady/nlink_path.c): the curve G(omega, a) = 0
 * in (omega, tip radius), G = u_0 / |u| from the recursion up from the tip (steady/tip_up.h),
 * its derivatives by forward differentiation of the recursion; the corrector on the arclength
 * hyperplane, the tangent, the shot's round-off, the hand-over back from the link angles, and
 * the step on the shot. */
#include <float.h>
#include <math.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"
#include "steady/tip_up.h"

/* x y / d: d = t (single = 1) or t^2; with big, as (x / t) (y / t) or (x / t) y, which do not
 * overflow where t^2 does. */
static double ratio(double x, double y, double t, double d, int big)
{
    if (!big) return d == 1 ? x * y / t : x * y / d;
    return d == 1 ? (x / t) * y : (x / t) * (y / t);
}

/* G, with derivs its derivatives and the metric at (omega, a) (without, those are NaN); if theta
 * is not NULL, the link angles into theta[0..N-1]; if embed is not NULL (and derivs), the unit
 * tangent (G_a, -G_omega) normalised, embedded in (ln omega, theta / sqrt(N)), into embed[0..N]
 * (embed[N+1..2N] is scratch). */
static inline void shoot_core(const whirl_chain *c, double omega, double a, shot *s,
                              double *theta, double *embed, int derivs)
{
    size_t n = c->n;
    double u_a = 0, u_w = 0, eta_a = 0, eta_w = 0;
    double s_aa = 0, s_wa = 0, s_ww = 0, w2 = omega * omega;
    double q = 1, q_a = 0, q_w = 0; /* sum of u_i^2 and its derivatives */
    /* H^2 ~ omega^4 (and H H_a) overflow from omega ~ 1e77: from T^2 = 1e300 on, T = hypot(H, V)
     * and ratios to it (TIP_UP_SQRT_BIG) */
    tip_up r = tip_up_start(c, w2, 1, a, 1);
    for (size_t i = n; i >= 1; i--) {
        double m = c->mass[i - 1], l = c->length[i - 1];
        if (derivs) eta_w += m * (2 * omega * r.u + w2 * u_w);
        tip_up_link(&r, c, i, TIP_UP_SQRT_BIG);
        const double u = r.u, eta = r.eta, v = r.v, h = r.h, t = r.t, t2 = r.t2;
        const int big = r.big;
        q += u * u;
        if (theta) theta[i - 1] = atan2(h, v);
        if (!derivs) continue;
        eta_a += m * w2 * u_a;
        double h_a = eta + a * eta_a, h_w = a * eta_w;
        double t_a = ratio(h, h_a, t, 1, big), t_w = ratio(h, h_w, t, 1, big);
        u_a -= l * (eta_a / t - ratio(eta, t_a, t, t2, big));
        u_w -= l * (eta_w / t - ratio(eta, t_w, t, t2, big));
        q_a += 2 * u * u_a;
        q_w += 2 * u * u_w;
        double th_a = ratio(v, h_a, t, t2, big), th_w = ratio(v, h_w, t, t2, big);
        s_aa += th_a * th_a;
        s_wa += th_a * th_w;
        s_ww += th_w * th_w;
        if (embed) embed[i] = th_w, embed[n + i] = th_a;
    }
    const double u = r.u;
    /* G = u_0 / |u| */
    double norm = sqrt(q);
    s->g = u / norm;
    if (!derivs) {
        s->g_a = s->g_w = s->m_ww = s->m_wa = s->m_aa = NAN;
        return;
    }
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

void path_shoot_embed(const whirl_chain *c, double omega, double a, shot *s, double *theta,
                      double *embed)
{
    shoot_core(c, omega, a, s, theta, embed, 1);
}

void path_shoot(const whirl_chain *c, double omega, double a, shot *s, double *theta)
{
    shoot_core(c, omega, a, s, theta, NULL, 1);
}

/* G alone, the same recursion in long double (64-bit significand on x86-64); the norm |u| in
 * *norm and max_i omega^2 M_i / T_i (M_i the mass below link i) in *load. */
static long double shoot_g_ext(const whirl_chain *c, double omega, double a, double *norm,
                               double *load)
{
    long double q = 1, w2 = (long double)omega * omega, worst = 0;
    tip_up_ext r = tip_up_ext_start(c, w2, 1, a, 1);
    for (size_t i = c->n; i >= 1; i--) {
        tip_up_ext_link(&r, c, i, TIP_UP_SQRT);
        const long double u = r.u, v = r.v, t = r.t;
        q += u * u;
        if (v / (c->gravity * t) > worst) worst = v / (c->gravity * t);
    }
    const long double u = r.u;
    *norm = (double)sqrtl(q);
    *load = (double)(w2 * worst);
    return u / sqrtl(q);
}

/* The round-off of the shot s at (omega, a) in the force balance: the pivot misses the axis by
 * r_0 = a |u| (G - G_ext) (G_ext the recursion in extended precision, which stands for the
 * exact G), and shifting the chain onto the axis changes the horizontal force that link i
 * carries by omega^2 M_i r_0, relative to its tension T_i; the largest over the links. At
 * least the same for one unit of round-off in G. */
double path_shot_noise(const whirl_chain *c, double omega, double a, const shot *s)
{
    double norm, load;
    const double dg = fabs(s->g - (double)shoot_g_ext(c, omega, a, &norm, &load));
    const double noise = fmax(dg, DBL_EPSILON) * fabs(a) * norm * load;
    return isfinite(noise) ? noise : INFINITY;
}

/* Newton's method on G = 0 and the row c . (x - x0) = sigma from (*w, *a). Returns 0 when it
 * converged (the last shot in *s), -1 otherwise. */
int path_correct(nlink_path *p, const double *m0, double w0, double a0, double c_w, double c_a,
                 double sigma, double *w, double *a, shot *s, int *iters)
{
    int final = 0;
    double prev = INFINITY;
    p->s.floor_exit = 0;
    for (int it = 0; it < NEWTON_MAX; it++) {
        path_shoot(p->pub.chain, *w, *a, s, NULL);
        p->pub.shots++;
        if (!(isfinite(s->g) && isfinite(s->g_a) && isfinite(s->g_w))) return -1;
        double r1 = -s->g, r2 = sigma - (c_w * (*w - w0) + c_a * (*a - a0));
        double det = s->g_w * c_a - s->g_a * c_w;
        if (!(det != 0 && isfinite(det))) return -1;
        double dw = (r1 * c_a - s->g_a * r2) / det, da = (s->g_w * r2 - c_w * r1) / det;
        *w += dw;
        *a += da;
        if (!(*w > 0 && isfinite(*w) && isfinite(*a))) return -1;
        if (final) {
            path_shoot(p->pub.chain, *w, *a, s, NULL);
            p->pub.shots++;
            return 0;
        }
        double norm2 = metric_dot(m0, dw, da, dw, da), norm = sqrt(norm2);
        if (!(norm2 >= 0)) return -1;
        if (norm <= NEWTON_TOL) {
            final = 1;
            if (iters) *iters = it + 1;
        } else if (it >= NEWTON_STALL_AFTER && norm <= NEWTON_FLOOR &&
                   norm >= NEWTON_STALL * prev) {
            /* no longer decreasing: the round-off floor of an ill-conditioned shot */
            if (iters) *iters = it + 1;
            p->s.floor_exit = 1;
            return 0;
        }
        prev = norm;
    }
    return -1;
}

/* The unit tangent at s (metric m) oriented against the previous direction (ref_w, ref_a) in the
 * metric m_ref; raw_sign: +1 if it is (G_a, -G_omega) normalised, -1 if its opposite. */
void path_tangent(const shot *s, const double *m, const double *m_ref, double ref_w, double ref_a,
                  double *t_w, double *t_a, int *raw_sign)
{
    double r_w = s->g_a, r_a = -s->g_w;
    double norm = sqrt(metric_dot(m, r_w, r_a, r_w, r_a));
    *raw_sign = metric_dot(m_ref, r_w, r_a, ref_w, ref_a) >= 0 ? 1 : -1;
    *t_w = *raw_sign * r_w / norm;
    *t_a = *raw_sign * r_a / norm;
}

/* The ratio of the largest to the smallest link tension at (omega, a). */
double path_tension_spread(const whirl_chain *c, double omega, double a)
{
    double t_min = INFINITY, t_max = 0;
    tip_up r = tip_up_start(c, omega, omega, a, 1);
    for (size_t i = c->n; i >= 1; i--) {
        tip_up_link(&r, c, i, TIP_UP_HYPOT);
        t_min = fmin(t_min, r.t);
        t_max = fmax(t_max, r.t);
    }
    return t_max / t_min;
}

/* The round-off of the shot at (omega, a) (shot_noise). */
double path_noise_at(nlink_path *p, double omega, double a)
{
    shot s;
    shoot_core(p->pub.chain, omega, a, &s, NULL, NULL, 0);
    p->pub.shots += 2;
    return path_shot_noise(p->pub.chain, omega, a, &s);
}

/* The state at an accepted point. */
void path_set_point(nlink_path *p, double omega, double a, const shot *s, double noise)
{
    p->pub.omega = omega;
    p->pub.tip_r = a;
    shot_metric(s, p->s.metric);
    p->s.noise = noise >= 0 ? noise : path_shot_noise(p->pub.chain, omega, a, s);
    if (omega < p->pub.omega_lo) p->pub.omega_lo = omega;
    if (omega > p->pub.omega_hi) p->pub.omega_hi = omega;
}

/* Back to the tip shot at the current point (polished by the shot's Newton at fixed omega).
 * Returns 0, or -1 with the path unchanged. */
int path_to_shot(nlink_path *p)
{
    double w = p->pub.omega, a = p->pub.tip_r, m[3];
    shot s;
    int iters;
    path_shoot(p->pub.chain, w, a, &s, NULL);
    shot_metric(&s, m);
    if (path_correct(p, m, w, a, 1, 0, 0, &w, &a, &s, &iters) != 0 || a == 0) return -1;
    double t_w = p->pub.t_omega, t_a = p->pub.t_tip, moved = 0;
    path_shoot_embed(p->pub.chain, w, a, &s, arr_theta_trial(p), arr_embed_trial(p));
    p->pub.shots++;
    for (size_t i = 0; i < p->pub.chain->n; i++)
        moved = fmax(moved, fabs(arr_theta_trial(p)[i] - arr_theta(p)[i]));
    if (!(moved <= SHOT_SAME)) return -1;
    swap(&p->s.theta, &p->s.theta_trial);
    swap(&p->s.embed, &p->s.embed_trial);
    path_set_point(p, w, a, &s, -1);
    path_tangent(&s, p->s.metric, p->s.metric, t_w, t_a, &p->pub.t_omega, &p->pub.t_tip,
                 &p->s.raw_sign);
    p->pub.angles = 0;
    p->s.index = -1;
    p->s.mu = p->s.mu_rate = NAN;
    p->s.have_last = 0;
    return 0;
}

/* ---- the step on the tip shot (the loop: src/steady/nlink_path_step.c) ----
 * Predictor along the tangent (for a, along it in ln|a| where that predicts the previous point
 * better: a tip radius that decays or grows exponentially, as on the high modes), Newton's
 * method on G = 0 and the arclength row. Where the shot fails, the step goes on in the link
 * angles. */

/* the largest |d ln a| the predictor in ln|a| extrapolates (exp stays finite; a larger change
 * is no prediction) */
#define LOG_PREDICT_MAX 50
#define STAY_MAX 1024 /* the longest wait in the link angles before the shot is tried again */

static void shot_begin(nlink_path *p, step_ctx *x)
{
    const double w0 = p->pub.omega, a0 = p->pub.tip_r, *m0 = p->s.metric;
    x->w0 = w0;
    x->a0 = a0;
    x->m0 = m0;
    x->c_w = m0[0] * p->pub.t_omega + m0[1] * p->pub.t_tip;
    x->c_a = m0[1] * p->pub.t_omega + m0[2] * p->pub.t_tip;
    x->log_predictor = 0;
    if (p->s.have_last && a0 != 0 && p->s.last.a0 != 0 && (a0 > 0) == (p->s.last.a0 > 0)) {
        double back = -p->s.last.ds, lin = a0 + back * p->pub.t_tip;
        double lg =
            a0 * exp(fmax(-LOG_PREDICT_MAX, fmin(LOG_PREDICT_MAX, back * p->pub.t_tip / a0)));
        x->log_predictor = fabs(lg - p->s.last.a0) < fabs(lin - p->s.last.a0);
    }
    x->crossing = 0;
    x->chord_off = x->chord_failed = 0;
    x->ds_first = p->pub.ds;
    x->ds_min = DS_MIN;
    x->ds_branch = DS_BRANCH;
    x->why = "";
}

static void shot_trial(nlink_path *p, step_ctx *x, step_trial *t)
{
    const whirl_chain *c = p->pub.chain;
    const double ds = t->ds, a0 = x->a0;
    double w = x->w0 + ds * p->pub.t_omega;
    double a = x->log_predictor
                   ? a0 * exp(fmax(-LOG_PREDICT_MAX, fmin(LOG_PREDICT_MAX, ds * p->pub.t_tip / a0)))
                   : a0 + ds * p->pub.t_tip;
    t->ok = path_correct(p, x->m0, x->w0, a0, x->c_w, x->c_a, ds, &w, &a, &t->s, &t->iters) == 0;
    t->w = w;
    t->a = a;
    if (!t->ok) p->s.why = "Newton's method on the tip shot does not converge";
    if (t->ok && p->s.floor_exit) {
        /* converged only to the shot's round-off: not an equilibrium to round-off */
        t->ok = 0;
        t->iters = NEWTON_MAX;
        p->s.why = "the tip shot's round-off exceeds the tolerance";
    }
    if (!t->ok) return;
    path_shoot_embed(c, w, a, &t->s, arr_theta_trial(p), arr_embed_trial(p));
    p->pub.shots++;
    double m1[3];
    shot_metric(&t->s, m1);
    path_tangent(&t->s, m1, x->m0, p->pub.t_omega, p->pub.t_tip, &t->t_w, &t->t_a, &t->raw);
    /* the turn of the tangent in (ln omega, theta / sqrt(N)); the embedded tangents are those of
     * (G_a, -G_omega), oriented by raw and the current orientation */
    double cosine = 0;
    for (size_t i = 0; i <= c->n; i++) cosine += arr_embed_trial(p)[i] * arr_embed(p)[i];
    cosine *= t->raw * p->s.raw_sign;
    t->turn = acos(fmin(1, fmax(-1, cosine)));
    for (size_t i = 0; i < c->n; i++)
        t->dtheta = fmax(t->dtheta, fabs(arr_theta_trial(p)[i] - arr_theta(p)[i]));
    t->chord = path_chord_test(c->n, x->w0, arr_theta(p), w, arr_theta_trial(p), arr_embed(p),
                               p->s.raw_sign, arr_embed_trial(p), t->raw, t->turn, 1);
    t->flip = t->raw != p->s.raw_sign;
}

/* A point the shot resolves only to more than NOISE_UP: the step in the link angles (measured
 * at every point: the measure is itself round-off and jumps along a branch). The first step
 * from the birth to such a point at a rate within BIRTH_NEAR of the birth's: begun in the link
 * angles instead (the force balance at fixed omega is singular there to within the shot's
 * round-off, and its Newton's method, polishing the shot's point on the hand-over, can fall onto
 * the hanging chain). */
static int shot_ready(nlink_path *p, step_ctx *x, step_trial *t)
{
    t->noise = path_shot_noise(p->pub.chain, t->w, t->a, &t->s);
    if (p->pub.steps > 0 && t->noise > NOISE_UP && path_to_angles(p) == 0) return STEP_ANGLES;
    if (p->pub.steps == 0 && x->a0 == 0 && t->noise > NOISE_UP &&
        fabs(t->w / x->w0 - 1) < BIRTH_NEAR)
        return path_begin_in_angles(p);
    return GSL_SUCCESS;
}

static int shot_rejected(nlink_path *p, step_ctx *x, const step_trial *t)
{
    /* where Newton's method on the shot fails away from the birth, the shot is too nonlinear or
     * too noisy in (omega, a): the same step in the link angles */
    if (t->iters == NEWTON_MAX && p->pub.steps > 0 && path_to_angles(p) == 0) {
        p->s.stay = p->s.backoff;
        p->s.backoff = p->s.backoff < STAY_MAX ? 2 * p->s.backoff : p->s.backoff;
        return STEP_ANGLES;
    }
    p->pub.ds *= 0.5;
    /* the first step from the birth no longer than the amplitude of the first point in the link
     * angles: begun there (a shorter one lands at amplitudes where the force balance at fixed
     * omega cannot tell the branch from the hanging chain, and the path, handed over to the link
     * angles, follows the hanging chain instead) */
    if (p->pub.steps == 0 && x->a0 == 0 && p->pub.ds < BIRTH_AMPLITUDE)
        return path_begin_in_angles(p);
    if (p->pub.ds < DS_MIN) {
        if (path_to_angles(p) == 0) {
            p->pub.ds = DS_FIRST;
            return STEP_ANGLES;
        }
        return path_fail_at(p, GSL_EFAILED, x->w0, x->a0);
    }
    return STEP_RETRY;
}

static void shot_accept(nlink_path *p, const step_ctx *x, const step_trial *t)
{
    swap(&p->s.theta, &p->s.theta_trial);
    swap(&p->s.embed, &p->s.embed_trial);
    path_set_point(p, t->w, t->a, &t->s, t->noise);
    p->pub.t_omega = t->t_w;
    p->pub.t_tip = t->t_a;
    p->s.raw_sign = t->raw;
    if (t->t_w != 0) p->s.rate_sign = sign_of(t->t_w);
}

const step_ops path_shot_ops = {shot_begin, shot_trial, shot_ready, shot_rejected, shot_accept};

int whirl_nlink_residual(const whirl_chain *c, double omega, double tip_r, double *g,
                         double *g_omega, double *g_tip)
{
    if (c == NULL || c->n < 1) return whirl_fail(GSL_EINVAL, "a chain needs at least one link");
    if (!(isfinite(omega) && omega > 0 && isfinite(tip_r)))
        return whirl_fail(GSL_EINVAL, "the residual needs omega > 0 and a finite tip radius");
    shot s;
    path_shoot(c, omega, tip_r, &s, NULL);
    *g = s.g;
    if (g_omega) *g_omega = s.g_w;
    if (g_tip) *g_tip = s.g_a;
    return GSL_SUCCESS;
}
