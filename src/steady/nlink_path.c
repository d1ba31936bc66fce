/* Branches of the N-link chain's relative equilibria by pseudo-arclength continuation.
 *
 * The tip shot (nlink_path_shot.c). Built up from the tip (steady/tip_up.h) with tip radius a
 * and u_i = r_i / a,
 *     eta_i = sum_{j >= i} m_j omega^2 u_j,  V_i = g sum_{j >= i} m_j,  H_i = a eta_i,
 *     T_i = sqrt(H_i^2 + V_i^2),  u_{i-1} = u_i - l_i eta_i / T_i,  u_N = 1,
 * the pivot lands on the axis where G(omega, a) = u_0 / |u| = 0 (|u|^2 = sum_i u_i^2 keeps G of
 * order one where r spans many decades). G depends on a only through a^2 and is the linear shot
 * at a = 0, whose zeros are the critical rates omega_k: the pitchfork at omega_k becomes a
 * regular point of the curve G = 0 with a vertical tangent, and a fixes every link angle
 * theta_i = atan2(H_i, V_i). G_omega, G_a and d theta / d(omega, a) by forward differentiation of
 * the recursion (O(N)).
 *
 * The continuation (Keller 1977, "Numerical solution of bifurcation and nonlinear eigenvalue
 * problems", in Applications of Bifurcation Theory; Allgower & Georg 1990, "Numerical
 * Continuation Methods", ch. 2; Doedel's AUTO). Arclength in (ln omega, theta):
 *     ds^2 = (d omega / omega)^2 + (1/N) sum_i d theta_i^2 = x^T M x,
 * the unit tangent t with G_omega t_omega + G_a t_a = 0, t^T M t = 1, along the travel. A step
 * predicts x0 + ds t0 (a in ln|a| where that predicts the last point better) and corrects by
 * Newton's method on G(x) = 0, (M0 t0) . (x - x0) = ds. One loop (nlink_path_step.c) judges a
 * trial: it is halved if Newton fails, the tangent turns by more than TURN_MAX, a link angle
 * moves by more than DTHETA_MAX, or the chord is not that of an arc the step resolves
 * (nlink_path_checks.c: further than CHORD_MAX times the turn from an end tangent, its rate part
 * outside the tangents' range, or the rate's cubic Hermite interpolant turning back: a small S
 * of two folds passed over); it grows after an easy step.
 *
 * The link angles (nlink_path_angles.c). Where the shot loses digits (its round-off, |G - G_ext|
 * with G_ext in long double turned into the force it leaves across a link, above NOISE_UP) the
 * same curve is followed in (omega, theta_1..theta_N) on the force balance R(omega, theta) = 0
 * (nlink_balance.c: tridiagonal Jacobian A, each Newton step a bordered solve, O(N)); back on the
 * shot below NOISE_DOWN. With U = g sum m_i z_i - omega^2 / 2 sum m_i r_i^2,
 *     A = omega^-2 B M^-1 B^T C^-1 Hess U   (B bidiagonal, M = diag m_i, C = diag l_i cos theta_i)
 * at an equilibrium, so A is singular exactly where Hess U is; its index (negative eigenvalues, a
 * Sturm count) changes by one at each fold and branch point, and its eigenvalue mu nearest zero
 * is followed with d mu / ds (Hellmann-Feynman on the symmetrised A): a step on which the index
 * jumps by two, or the cubic Hermite interpolant of mu crosses zero and back, is halved.
 *
 * Events (nlink_path_events.c): a fold where the resolved sign of t_omega changes (in the link
 * angles only where |mu| > MU_RESOLVED |A|), a branch point where the orientation test changes
 * sign (the tangent (G_a, -G_omega) against the travel; det [A, R_omega; (M0 t0)^T] in the link
 * angles), a return to the hanging chain where a (the projection on the step's start) changes
 * sign, taken only at a critical rate; each located by Brent's method (Brent 1973) on the
 * step's arclength, every evaluation a corrector solve. A reversal of the orientation on a step
 * longer than DS_BRANCH is another curve close by (G changes sign across each curve) and is
 * halved; a shorter one is a branch point unless the probe (nlink_path_probe.c), a copy of the
 * path in the fine mode (steps down to DS_MIN_FINE), follows a sharp turn over FINE_SPAN.
 *
 * The measurements behind the constants and the audits of these tests on random and uniform
 * chains against a 40-digit continuation (tests/tools/branch_mp.py): docs/validation/
 * continuation.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"

nlink_path *path_alloc(const whirl_chain *c)
{
    if (c == NULL || c->n < 1) {
        whirl_fail(GSL_EINVAL, "a chain needs at least one link");
        return NULL;
    }
    const size_t n = c->n;
    nlink_path *p = calloc(1, sizeof *p + path_block_size(n) * sizeof(double));
    if (p == NULL) goto fail;
    p->pub.chain = c;
    /* the arrays exchanged with their trial: theta, theta_trial, t_theta, t_theta_trial (n
     * each), embed, embed_trial (2 n + 1 each), eig, eig_trial (n each) */
    p->s.theta = 0;
    p->s.theta_trial = n;
    p->s.t_theta = 2 * n;
    p->s.t_theta_trial = 3 * n;
    p->s.embed = 4 * n;
    p->s.embed_trial = 6 * n + 1;
    p->s.eig = 8 * n + 2;
    p->s.eig_trial = 9 * n + 2;
    p->balance = whirl_nlink_balance_alloc(c);
    if (p->balance == NULL) goto fail;
    return p;
fail:
    path_free(p);
    whirl_fail(GSL_ENOMEM, "out of memory for a path on a chain of %zu links", c->n);
    return NULL;
}

void path_free(nlink_path *p)
{
    if (p == NULL) return;
    path_free(p->probe);
    whirl_nlink_balance_free(p->balance);
    free(p);
}

whirl_nlink_path *whirl_nlink_path_alloc(const whirl_chain *c)
{
    nlink_path *p = path_alloc(c);
    return p ? &p->pub : NULL;
}

void whirl_nlink_path_free(whirl_nlink_path *p)
{
    if (p) path_free(path_of(p));
}

const double *whirl_nlink_path_theta(const whirl_nlink_path *p)
{
    return arr_theta((const nlink_path *)p);
}

const double *whirl_nlink_path_cross_theta(const whirl_nlink_path *p)
{
    return arr_cross_theta((const nlink_path *)p);
}

static void reset(nlink_path *p)
{
    p->pub.arclength = 0;
    p->pub.ds = DS_FIRST;
    p->pub.steps = p->pub.rejected = p->pub.shots = 0;
    p->pub.n_events = 0;
    p->pub.ended = 0;
    p->pub.omega_lo = INFINITY;
    p->pub.omega_hi = -INFINITY;
    p->s.have_last = 0;
    p->pub.angles = 0;
    p->s.noise = 0;
    p->s.index = -1;
    p->s.mu = p->s.mu_rate = NAN;
    p->s.why = "";
    p->s.stay = 0;
    p->s.backoff = STAY_FIRST;
    p->s.fine_end = p->s.probe_end = 0;
    p->s.rate_sign = p->s.last_rate_sign = 0;
    for (size_t i = 0; i < p->pub.chain->n; i++) scr_zero(p)[i] = 0;
}

int whirl_nlink_path_birth(whirl_nlink_path *path, int mode)
{
    nlink_path *p = path_of(path);
    const whirl_chain *c = p->pub.chain;
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
    p->pub.mode = mode;
    /* Newton's method on the linearised shot G(omega, 0); where the shot is too inaccurate for
     * it (the high modes of long chains: a correction beyond BIRTH_NEWTON_SPAN omega_k, or none
     * that settles), the rate from the tridiagonal eigenproblem, accurate to a few eps
     * relative */
    shot s;
    const double omega_eig = omega;
    for (int it = 0; it < BIRTH_NEWTON_MAX; it++) {
        path_shoot(c, omega, 0, &s, NULL);
        p->pub.shots++;
        double d = s.g / s.g_w;
        if (!isfinite(d) || fabs(omega - d - omega_eig) > BIRTH_NEWTON_SPAN * omega_eig ||
            it == BIRTH_NEWTON_MAX - 1) {
            omega = omega_eig;
            break;
        }
        omega -= d;
        if (fabs(d) <= RATE_ROUND * omega) break;
    }
    path_shoot_embed(c, omega, 0, &s, arr_theta(p), arr_embed(p));
    p->pub.shots++;
    p->pub.omega_birth = omega;
    path_set_point(p, omega, 0, &s, -1);
    /* the tangent is vertical: into a > 0 */
    p->pub.t_omega = 0;
    p->pub.t_tip = 1 / sqrt(s.m_aa);
    double tw, ta;
    path_tangent(&s, p->s.metric, p->s.metric, p->pub.t_omega, p->pub.t_tip, &tw, &ta,
                 &p->s.raw_sign);
    return GSL_SUCCESS;
}

int whirl_nlink_path_start(whirl_nlink_path *path, double omega, double tip_r, int direction)
{
    nlink_path *p = path_of(path);
    if (!(isfinite(omega) && omega > 0 && isfinite(tip_r)))
        return whirl_fail(GSL_EINVAL, "a path starts at omega > 0 and a finite tip radius");
    reset(p);
    p->pub.mode = 0;
    p->pub.omega_birth = 0;
    double w = omega, a = tip_r, m[3] = {1, 0, 1};
    shot s;
    int iters;
    if (path_correct(p, m, omega, tip_r, 1, 0, 0, &w, &a, &s, &iters) != 0 || a == 0)
        return whirl_fail(GSL_EFAILED, "no equilibrium near omega=%.17g, tip radius %.17g",
                          omega, tip_r);
    path_shoot_embed(p->pub.chain, w, a, &s, arr_theta(p), arr_embed(p));
    p->pub.shots++;
    path_set_point(p, w, a, &s, -1);
    double tw, ta;
    int raw;
    path_tangent(&s, p->s.metric, p->s.metric, s.g_a, -s.g_w, &tw, &ta, &raw);
    if ((direction >= 0) != (tw >= 0)) tw = -tw, ta = -ta, raw = -raw;
    p->pub.t_omega = tw;
    p->pub.t_tip = ta;
    p->s.raw_sign = raw;
    p->s.rate_sign = sign_of(tw);
    return GSL_SUCCESS;
}

int whirl_nlink_path_start_angles(whirl_nlink_path *path, double omega, const double *theta,
                                  int direction)
{
    nlink_path *p = path_of(path);
    const whirl_chain *c = p->pub.chain;
    const size_t n = c->n;
    if (!(isfinite(omega) && omega > 0))
        return whirl_fail(GSL_EINVAL, "a path starts at omega > 0");
    reset(p);
    p->pub.mode = 0;
    p->pub.omega_birth = 0;
    for (size_t i = 0; i < n; i++) arr_theta(p)[i] = theta[i];
    if (whirl_nlink_balance_polish(p->balance, omega, arr_theta(p)) ||
        !(tip_of(c, omega, arr_theta(p)) != 0))
        return whirl_fail(GSL_EFAILED, "no equilibrium of the chain near the link angles given "
                          "at omega=%.17g", omega);
    /* the tangent with d omega > 0 (the row e_omega: regular unless the point is a fold),
     * turned to the direction asked; then the orientation test with the tangent's own row, as
     * a step makes it */
    double t_w, *c_th = scr_cth(p);
    int det;
    if (path_angle_tangent(p, omega, 1, scr_zero(p), &t_w, arr_t_theta(p), &det, NULL, NULL))
        return whirl_fail(GSL_EFAILED, "the equilibrium at omega=%.17g is a fold: no tangent "
                          "transversal to the rate", omega);
    const double sign = direction >= 0 ? 1 : -1;
    t_w *= sign;
    for (size_t i = 0; i < n; i++)
        arr_t_theta(p)[i] *= sign, c_th[i] = arr_t_theta(p)[i] / (double)n;
    double t_check;
    if (path_angle_tangent(p, omega, t_w / (omega * omega), c_th, &t_check, arr_t_theta_trial(p),
                           &det, NULL, NULL))
        return whirl_fail(GSL_EFAILED, "the tangent at omega=%.17g is not defined", omega);
    path_angle_point(p, omega, t_w, det);
    p->s.noise = path_noise_at(p, omega, p->pub.tip_r);
    return GSL_SUCCESS;
}

void whirl_nlink_path_reverse(whirl_nlink_path *path)
{
    nlink_path *p = path_of(path);
    p->pub.t_omega = -p->pub.t_omega;
    p->pub.t_tip = -p->pub.t_tip;
    p->s.raw_sign = -p->s.raw_sign;
    p->s.rate_sign = -p->s.rate_sign;
    if (p->pub.angles) {
        for (size_t i = 0; i < p->pub.chain->n; i++) arr_t_theta(p)[i] = -arr_t_theta(p)[i];
        for (size_t i = 0; i <= p->pub.chain->n; i++) arr_embed(p)[i] = -arr_embed(p)[i];
        p->s.det_sign = -p->s.det_sign;
        p->s.mu_rate = -p->s.mu_rate;
    }
    p->s.have_last = 0;
    p->s.fine_end = p->s.probe_end = 0;
}

/* status, the message of a failure (not a stop request) of a path begun at a birth led by its
 * mode: "mode k: ..." */
int path_name_mode(const nlink_path *p, int status)
{
    if (status == GSL_SUCCESS || status == WHIRL_EINTERRUPTED || p->pub.mode <= 0) return status;
    char message[512];
    snprintf(message, sizeof message, "%s", whirl_last_error());
    return whirl_fail(status, "mode %d: %s", p->pub.mode, message);
}
