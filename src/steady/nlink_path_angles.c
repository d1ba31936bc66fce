/* The link-angle formulation of the N-link continuation (src/steady/nlink_path.c): the curve
 * in (omega, theta_1..theta_N) on the force balance R(omega, theta) = 0 of
 * src/steady/nlink_balance.c, the corrector by bordered solves, the tangent and its orientation
 * test, the eigenvalue of the Jacobian nearest zero, the hand-over from the shot, the first point
 * of a birth begun here, and the step in the link angles. */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"

/* The rate of change of the tip radius tip_of along (d omega, d theta). */
static double tip_rate(const whirl_chain *c, double w, const double *th, double dw,
                       const double *dth)
{
    const double co = cos(th[c->n - 1]);
    return c->gravity * (dth[c->n - 1] / (co * co) - 2 * tan(th[c->n - 1]) * dw / w) / (w * w);
}

/* The projection of the link angles th on th0 (it changes sign where the path passes the
 * hanging chain). */
double path_shape_projection(size_t n, const double *th, const double *th0)
{
    double q = 0;
    for (size_t i = 0; i < n; i++) q += th[i] * th0[i];
    return q;
}

/* The metric norm of (d omega, d theta) at omega0: sqrt((d omega / omega0)^2 + |d theta|^2 / N). */
static double angle_norm(size_t n, double w0, double dw, const double *dth)
{
    double q = 0;
    for (size_t i = 0; i < n; i++) q += dth[i] * dth[i];
    return sqrt(dw * dw / (w0 * w0) + q / (double)n);
}

/* Newton's method on R(omega, theta) = 0 and the row c_w (omega - w0) + c_th . (theta - th0) =
 * sigma from (*w, th) (in place), converged as path_correct(); the force balance is left factorised
 * at the converged point (or at the point before its last correction, when that was below the
 * square of NEWTON_TOL). Returns 0 when it converged, -1 otherwise. */
int path_correct_angles(nlink_path *p, double w0, const double *th0, double c_w, const double *c_th,
                        double sigma, double *w, double *th, int *iters, int max_iter)
{
    const size_t n = p->pub.chain->n;
    double *f = scr_f(p), *dth = scr_dth(p), prev = INFINITY;
    int final = 0;
    for (int it = 0; it < max_iter; it++) {
        if (whirl_nlink_balance_factor(p->balance, *w, th)) return -1;
        p->pub.shots++;
        const double *res = whirl_nlink_balance_residual(p->balance);
        double g = sigma - c_w * (*w - w0), dw, schur;
        for (size_t i = 0; i < n; i++) f[i] = -res[i], g -= c_th[i] * (th[i] - th0[i]);
        if (whirl_nlink_balance_bordered(p->balance, c_th, c_w, f, g, 0, dth, &dw, &schur))
            return -1;
        *w += dw;
        for (size_t i = 0; i < n; i++) th[i] += dth[i];
        if (!(*w > 0 && isfinite(*w))) return -1;
        const double norm = angle_norm(n, w0, dw, dth);
        if (!(norm >= 0)) return -1;
        int done = final;
        if (!final && norm <= NEWTON_TOL) {
            final = 1;
            if (iters) *iters = it + 1;
        } else if (!final && it >= NEWTON_STALL_AFTER && norm <= NEWTON_FLOOR &&
                   norm >= NEWTON_STALL * prev) {
            if (iters) *iters = it + 1;
            done = 1;
        }
        /* after the iteration that follows a correction below NEWTON_TOL, the factor is that
         * of a point within the square of it (quadratic convergence): kept for the tangent; at
         * the floor the converged point's own */
        if (done && final) return 0;
        if (done) {
            p->pub.shots++;
            return whirl_nlink_balance_factor(p->balance, *w, th) ? -1 : 0;
        }
        prev = norm;
    }
    return -1;
}

/* The unit tangent at the last factorised point (rate w), its component along the row
 * (c_w, c_th) positive: d omega in *t_w, d theta in t_th. *det_sign: the sign of det [J; c],
 * which changes at a branch point; the continuous test sign(det A) exp(ln|det A| - ref) schur
 * in *test if not NULL (*ref set from the first call when NaN). Returns 0 or -1. */
int path_angle_tangent(nlink_path *p, double w, double c_w, const double *c_th, double *t_w,
                       double *t_th, int *det_sign, double *ref, double *test)
{
    const size_t n = p->pub.chain->n;
    double schur;
    if (whirl_nlink_balance_bordered(p->balance, c_th, c_w, NULL, 1, 1, t_th, t_w, &schur))
        return -1;
    const double len = angle_norm(n, w, *t_w, t_th);
    if (!(len > 0 && isfinite(len))) return -1;
    *t_w /= len;
    for (size_t i = 0; i < n; i++) t_th[i] /= len;
    int sign = whirl_nlink_balance_det_sign(p->balance);
    *det_sign = (schur > 0) == (sign > 0) ? 1 : -1;
    if (test) {
        const double logdet = whirl_nlink_balance_logdet(p->balance, &sign);
        if (isnan(*ref)) *ref = logdet;
        *test = sign * exp(fmax(-EXP_ARG_MAX, fmin(EXP_ARG_MAX, logdet - *ref))) * schur;
    }
    return 0;
}

/* The tangent embedded in (ln omega, theta / sqrt(N)). */
static void angle_embed(size_t n, double w, double t_w, const double *t_th, double *embed)
{
    const double scale = 1 / sqrt((double)n);
    embed[0] = t_w / w;
    for (size_t i = 0; i < n; i++) embed[i + 1] = scale * t_th[i];
}

/* The path at the point arr_theta(p), rate w, of a step or start in the link angles, with the
 * tangent (t_w, arr_t_theta(p)) and the orientation test's sign det. */
void path_angle_point(nlink_path *p, double w, double t_w, int det)
{
    const whirl_chain *c = p->pub.chain;
    p->pub.omega = w;
    p->pub.tip_r = tip_of(c, w, arr_theta(p));
    p->pub.t_omega = t_w;
    p->pub.t_tip = tip_rate(c, w, arr_theta(p), t_w, arr_t_theta(p));
    p->s.det_sign = det;
    p->s.index = whirl_nlink_balance_index(p->balance);
    p->s.mu = p->s.mu_rate = NAN;
    p->s.rate_sign = sign_of(t_w);
    angle_embed(c->n, w, t_w, arr_t_theta(p), arr_embed(p));
    if (w < p->pub.omega_lo) p->pub.omega_lo = w;
    if (w > p->pub.omega_hi) p->pub.omega_hi = w;
    p->pub.angles = 1;
}

/* Over to the link angles at the current point of the shot: its angles polished on the force
 * balance at fixed omega, or where that fails (A singular or nearly: a fold at or next to the
 * point) on the hyperplane through the point normal to the shot's tangent (the arclength row at
 * sigma = 0, regular at a fold); the tangent carried over (the shot's tangent in theta is
 * arr_embed(p)). Returns 0, or -1 with the path unchanged. */
int path_to_angles(nlink_path *p)
{
    const whirl_chain *c = p->pub.chain;
    const size_t n = c->n;
    double *th = arr_theta_trial(p), *c_th = scr_cth(p), t_w, w = p->pub.omega;
    const double c_w = p->pub.t_omega / (p->pub.omega * p->pub.omega);
    for (size_t i = 0; i < n; i++) {
        th[i] = arr_theta(p)[i];
        c_th[i] = p->s.raw_sign * arr_embed(p)[i + 1] * sqrt((double)n) / (double)n;
    }
    if (whirl_nlink_balance_polish(p->balance, w, th)) {
        for (size_t i = 0; i < n; i++) th[i] = arr_theta(p)[i];
        if (path_correct_angles(p, p->pub.omega, arr_theta(p), c_w, c_th, 0, &w, th, NULL,
                           LOCATE_NEWTON_MAX))
            return -1;
    }
    int det;
    if (path_angle_tangent(p, w, c_w, c_th, &t_w, arr_t_theta(p), &det, NULL, NULL)) return -1;
    swap(&p->s.theta, &p->s.theta_trial); /* th was the trial's */
    p->pub.omega = w;
    p->pub.t_omega = t_w;
    p->pub.t_tip = tip_rate(c, p->pub.omega, th, t_w, arr_t_theta(p));
    p->pub.tip_r = tip_of(c, p->pub.omega, th);
    p->s.det_sign = det;
    p->s.index = whirl_nlink_balance_index(p->balance);
    p->s.mu = p->s.mu_rate = NAN;
    angle_embed(n, p->pub.omega, t_w, arr_t_theta(p), arr_embed(p));
    p->pub.angles = 1;
    p->s.have_last = 0;
    return 0;
}

/* The eigenvalue of the force balance nearest zero at the trial point (factorised) and its rate
 * along the trial tangent (t_w, arr_t_theta_trial(p)) into *mu, *mu_rate, its eigenvector into
 * arr_eig_trial(p) (from the start's); NAN where not found. Returns 1 where the step of length ds
 * does not resolve it (src/steady/nlink_path.c): its cubic Hermite interpolant in the arclength
 * changes sign more than once, or turns back towards the ends' sign at less than NEAR_MAX times
 * the smaller end value from zero; 0 where it does, or where the start's eigenvector is not the
 * end's (another eigenvalue became the nearest to zero: the cubic joins two different ones). */
static int near_zero(nlink_path *p, double t_w, double ds, double *mu, double *mu_rate)
{
    const size_t n = p->pub.chain->n;
    const int known = isfinite(p->s.mu);
    for (size_t i = 0; i < n; i++) arr_eig_trial(p)[i] = known ? arr_eig(p)[i] : 1;
    if (whirl_nlink_balance_near_zero(p->balance, t_w, arr_t_theta_trial(p),
                                      known ? EIG_ITERS : EIG_ITERS_FIRST, arr_eig_trial(p), mu,
                                      mu_rate) != GSL_SUCCESS) {
        *mu = *mu_rate = NAN;
        return 0;
    }
    if (!known) return 0;
    double dot = 0, q0 = 0, q1 = 0, near;
    for (size_t i = 0; i < n; i++) {
        dot += arr_eig(p)[i] * arr_eig_trial(p)[i];
        q0 += arr_eig(p)[i] * arr_eig(p)[i];
        q1 += arr_eig_trial(p)[i] * arr_eig_trial(p)[i];
    }
    if (!(fabs(dot) >= EIG_SAME * sqrt(q0 * q1))) return 0;
    const int changes =
        path_hermite_crossings(p->s.mu, ds * p->s.mu_rate, *mu, ds * *mu_rate, &near);
    return changes > 1 || near < NEAR_MAX;
}

/* ---- the step in the link angles (the loop: src/steady/nlink_path_step.c) ----
 * Predictor x0 + ds t0 + ds^2 k / 2 (k the curvature, the change of the tangent over the last
 * step divided by its length, where that step was made in the link angles too), Newton's method
 * on R = 0 and the arclength row (M0 t0) . (x - x0) = ds. Where no step down to the smallest
 * can be followed, the crossing mode: steps doubling from twice the smallest up to DS_CROSS,
 * one taken only where the orientation reverses on it (a branch point narrower than the
 * smallest step). */

static void angle_begin(nlink_path *p, step_ctx *x)
{
    x->w0 = p->pub.omega;
    x->a0 = p->pub.tip_r;
    x->m0 = NULL;
    x->c_w = p->pub.t_omega / (x->w0 * x->w0);
    x->c_a = 0;
    x->log_predictor = 0;
    x->crossing = 0;
    x->chord_off = x->chord_failed = 0;
    x->ds_first = p->pub.ds;
    /* the step above which a reversal of the orientation is another curve close by */
    x->ds_min = ds_smallest(p);
    x->ds_branch = in_fine_mode(p) ? x->ds_min : DS_BRANCH;
    x->why = "";
}

static void angle_trial(nlink_path *p, step_ctx *x, step_trial *t)
{
    const size_t n = p->pub.chain->n;
    double *c_th = scr_cth(p);
    for (size_t i = 0; i < n; i++) c_th[i] = arr_t_theta(p)[i] / (double)n;
    const double ds = t->ds;
    double w = x->w0 + ds * p->pub.t_omega, *th = arr_theta_trial(p);
    for (size_t i = 0; i < n; i++) th[i] = arr_theta(p)[i] + ds * arr_t_theta(p)[i];
    if (p->s.have_last && p->s.last.angles) {
        /* the second-order term, the curvature from the tangents at the last two points */
        const double q = 0.5 * ds * ds / p->s.last.ds;
        w += q * (p->pub.t_omega - p->s.last.t_w);
        for (size_t i = 0; i < n; i++) th[i] += q * (arr_t_theta(p)[i] - arr_t_theta0(p)[i]);
    }
    t->ok = path_correct_angles(p, x->w0, arr_theta(p), x->c_w, c_th, ds, &w, th, &t->iters,
                                NEWTON_MAX) == 0;
    if (!t->ok) p->s.why = "Newton's method on the force balance does not converge";
    if (t->ok && path_angle_tangent(p, w, x->c_w, c_th, &t->t_w, arr_t_theta_trial(p), &t->det,
                                    NULL, NULL)) {
        t->ok = 0;
        p->s.why = "the tangent is not defined (a singular point)";
    }
    t->w = w;
    if (!t->ok) return;
    t->index = whirl_nlink_balance_index(p->balance);
    t->pair = near_zero(p, t->t_w, ds, &t->mu, &t->mu_rate);
    angle_embed(n, w, t->t_w, arr_t_theta_trial(p), arr_embed_trial(p));
    double cosine = 0;
    for (size_t i = 0; i <= n; i++) cosine += arr_embed_trial(p)[i] * arr_embed(p)[i];
    t->turn = acos(fmin(1, fmax(-1, cosine)));
    for (size_t i = 0; i < n; i++) t->dtheta = fmax(t->dtheta, fabs(th[i] - arr_theta(p)[i]));
    t->mu_min = MU_RESOLVED * whirl_nlink_balance_scale(p->balance);
    t->chord = path_chord_test(n, x->w0, arr_theta(p), w, th, arr_embed(p), 1, arr_embed_trial(p),
                               1, t->turn, fabs(p->s.mu) > t->mu_min && fabs(t->mu) > t->mu_min);
    t->flip = t->det != p->s.det_sign;
    t->jump = p->s.index >= 0 && abs(t->index - p->s.index) > 1;
}

/* A reversal of the orientation (or a jump of the index, or an eigenvalue that crosses zero and
 * back) on a step no longer than DS_BRANCH is a branch point, unless the curve turns within it:
 * the probe looks ahead (not again within FINE_SPAN of where it last found a branch point at
 * the finer scale: it looked over that stretch). */
static int angle_ready(nlink_path *p, step_ctx *x, step_trial *t)
{
    if (x->crossing || !(t->flip || t->jump || t->pair) || in_fine_mode(p) ||
        !(p->pub.arclength >= p->s.probe_end))
        return GSL_SUCCESS;
    const int ahead = path_look_ahead(p, 0.5 * t->ds);
    if (ahead == WHIRL_EINTERRUPTED) return path_stopped(p);
    if (ahead != 0 && ahead != 1) return ahead;
    if (ahead == 0) p->s.probe_end = p->pub.arclength + FINE_SPAN;
    if (ahead == 1) {
        /* the fine mode from here on, the steps as from a fresh call (as the probe's) */
        p->s.fine_end = p->pub.arclength + FINE_SPAN;
        p->pub.rejected++;
        p->pub.ds = 0.5 * t->ds;
        return STEP_ANGLES;
    }
    return GSL_SUCCESS;
}

static int angle_rejected(nlink_path *p, step_ctx *x, const step_trial *t)
{
    if (x->crossing) {
        /* the steps doubling up to DS_CROSS */
        p->pub.ds *= 2;
        if (p->pub.ds > DS_CROSS) {
            p->s.why = x->why;
            return path_fail_at(p, GSL_EFAILED, x->w0, x->a0);
        }
        return STEP_RETRY;
    }
    p->pub.ds *= 0.5;
    if (p->pub.ds < DS_MIN_CHORD && x->chord_failed && !x->chord_off) {
        /* the chord test alone rejected steps down to the smallest: at that scale the corrected
         * points scatter by their own round-off across a turn of the curve sharper than the
         * tangent resolves (a heavy tip's pinned string where it splits), and the chord
         * measures that scatter, not a part of the curve passed over. The step is retried from
         * its first length without the chord test, every other test kept (the turn, the link
         * angles, the orientation: no step lands on another curve). */
        x->chord_off = 1;
        p->pub.ds = x->ds_first;
        return STEP_RETRY;
    }
    if (p->pub.ds < x->ds_min) {
        /* the curve cannot be followed at any step: if a curve of the opposite orientation lies
         * within DS_CROSS ahead, the two meet there to within the resolution of the steps (a
         * branch point, its unfolding narrower than the smallest step): the shortest step that
         * reaches it is taken across */
        x->why = p->s.why;
        x->crossing = 1;
        p->pub.ds = 2 * x->ds_min;
    }
    return STEP_RETRY;
}

static void angle_accept(nlink_path *p, const step_ctx *x, const step_trial *t)
{
    const whirl_chain *c = p->pub.chain;
    swap(&p->s.theta, &p->s.theta_trial);
    swap(&p->s.t_theta, &p->s.t_theta_trial);
    swap(&p->s.embed, &p->s.embed_trial);
    p->pub.omega = t->w;
    p->pub.tip_r = tip_of(c, t->w, arr_theta(p));
    p->pub.t_omega = t->t_w;
    p->pub.t_tip = tip_rate(c, t->w, arr_theta(p), t->t_w, arr_t_theta(p));
    p->s.det_sign = t->det;
    p->s.index = t->index;
    swap(&p->s.eig, &p->s.eig_trial);
    p->s.mu = t->mu;
    p->s.mu_rate = t->mu_rate;
    if (!(fabs(t->mu) <= t->mu_min) && t->t_w != 0) p->s.rate_sign = sign_of(t->t_w);
    if (t->w < p->pub.omega_lo) p->pub.omega_lo = t->w;
    if (t->w > p->pub.omega_hi) p->pub.omega_hi = t->w;
    p->s.noise = path_noise_at(p, t->w, p->pub.tip_r);
}

const step_ops path_angle_ops = {angle_begin, angle_trial, angle_ready, angle_rejected,
                                 angle_accept};

/* The point of the branch whose projection on the linear mode shape phi is amplitude
 * (phi . theta / sqrt(N), phi of unit norm oriented to a positive tip), by Newton's method into
 * th, from th scaled by guess (0: from amplitude phi); its rate in *w. The row phi / sqrt(N) is
 * left in scr_cth(p). Returns 0, or -1 where phi or Newton's method fails. */
static int birth_point(nlink_path *p, double amplitude, double guess, double *th, double *w)
{
    const size_t n = p->pub.chain->n;
    double *phi = arr_t_theta_trial(p), *c_th = scr_cth(p), norm = 0;
    int tip_sign;
    if (whirl_nlink_balance_mode(p->balance, p->pub.omega_birth, phi, &tip_sign)) return -1;
    for (size_t i = 0; i < n; i++) norm += phi[i] * phi[i];
    norm = sqrt(norm) * tip_sign;
    const double scale = sqrt((double)n);
    for (size_t i = 0; i < n; i++) {
        phi[i] /= norm;
        c_th[i] = phi[i] / scale;
        th[i] = guess > 0 ? guess * th[i] : amplitude * scale * phi[i];
    }
    *w = p->pub.omega_birth;
    return path_correct_angles(p, p->pub.omega_birth, scr_zero(p), 0, c_th, amplitude, w, th, NULL,
                          LOCATE_NEWTON_MAX);
}

/* The first point of the branch in the link angles, where the shot's first step from the birth
 * fails (the modes near N, whose linear mode shape has a tip displacement of 1e-10 of its
 * largest or less) or lands within BIRTH_NEAR of the birth's rate where the shot's round-off
 * exceeds NOISE_UP. At the birth (omega_k, theta = 0) the Jacobian A is singular with the null
 * vector phi, the linear mode shape in the link angles (whirl_nlink_balance_mode: a twisted
 * factorization of A, every component to its own relative accuracy, the tip's sign known even
 * where its magnitude underflows; the shot's d theta / d a at a = 0 is not used: where the
 * mode decays towards the pivot its upper links are the shot's round-off, amplified); the
 * branch is the curve through it along phi, and its point with phi . theta / sqrt(N) =
 * BIRTH_AMPLITUDE (a regular point of the system with that row: omega moves from omega_k by
 * O(amplitude^2)) is found by Newton's method from theta = amplitude phi. The half of the
 * pitchfork is that of phi oriented to a positive tip angle (the side a > 0 of the shot), by
 * the exact sign of the linear mode's tip, not by the tip of the corrected point, whose sign can
 * be round-off (its magnitude 1e-160 of the largest or less) or zero. Rates below that point's
 * (within ~1e-9 omega_k of the birth) are reached by birth_gap. */
static int birth_angles(nlink_path *p)
{
    double w, t_w;
    int det;
    if (birth_point(p, BIRTH_AMPLITUDE, 0, arr_theta_trial(p), &w)) return -1;
    if (path_angle_tangent(p, w, 0, scr_cth(p), &t_w, arr_t_theta(p), &det, NULL, NULL)) return -1;
    swap(&p->s.theta, &p->s.theta_trial);
    path_angle_point(p, w, t_w, det);
    p->s.stay = p->s.backoff;
    p->s.have_last = 0;
    p->pub.ds = DS_FIRST;
    return 0;
}

/* The point of the branch at the rate omega between the birth and the first point of
 * birth_angles, into th: the point with amplitude s (birth_point) whose rate is omega, s by the
 * secant method on omega(s^2), which is linear in s^2 near the birth (a pitchfork), from the
 * amplitude of the first point. Only the rate is ill-conditioned there (omega - omega_k of
 * 1e-9 omega_k fixes s to about 1e-7 of itself); each point is regular in the system with the
 * amplitude's row. Returns 0, or -1 where that does not converge. */
int path_birth_gap(nlink_path *p, double omega, double *th)
{
    const double wk = p->pub.omega_birth;
    double s2_a = 0, w_a = wk, s2_b = BIRTH_AMPLITUDE * BIRTH_AMPLITUDE, w_b;
    if (birth_point(p, BIRTH_AMPLITUDE, 0, th, &w_b)) return -1;
    for (int it = 0; it < GAP_MAX; it++) {
        if (fabs(w_b - omega) <= RATE_ROUND * omega) return 0;
        if (!(w_b != w_a)) return -1;
        const double s2 = s2_b + (omega - w_b) * (s2_b - s2_a) / (w_b - w_a);
        if (!(s2 > 0 && isfinite(s2))) return -1;
        const double guess = sqrt(s2 / s2_b);
        s2_a = s2_b, w_a = w_b, s2_b = s2;
        if (birth_point(p, sqrt(s2), guess, th, &w_b)) return -1;
    }
    return -1;
}

/* The first step from the birth, begun in the link angles instead of on the shot (birth_angles):
 * STEP_ANGLES; the failure at the birth where that does not start. */
int path_begin_in_angles(nlink_path *p)
{
    if (birth_angles(p) == 0) return STEP_ANGLES;
    return path_fail_at(p, GSL_EFAILED, p->pub.omega, p->pub.tip_r);
}
