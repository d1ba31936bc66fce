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
 * TURN_MAX, a link angle changes by more than DTHETA_MAX (the corrector never lands on another
 * curve) or the chord of the step is not that of an arc the step resolves (chord_test: it lies
 * further than CHORD_MAX times the turn from either end's tangent, or its rate part outside the
 * tangents' range: the step passed over a small S of two folds; where it alone rejects every
 * step down to DS_MIN_CHORD in the link angles, the corrected points scatter by their round-off
 * across a turn sharper than the tangent resolves, and the step is retried from its first
 * length without it, the other tests kept); it grows 1.5-fold after an easy step, up to DS_MAX.
 * The smallest step is DS_MIN on the shot (below it the path goes over to the link angles,
 * below) and DS_MIN_ANGLES in the link angles: a branch can turn within an arclength of 1e-7
 * (a tip mass of 1e12 chain masses makes the chain a string pinned at both ends, whose
 * symmetric branches split in pitchforks; the links' own weight unfolds each at 1e-12, and
 * the branch from the birth turns onto the asymmetric side over an arclength of order the
 * square root of that), and within 1e-9 where a branch meets another mode's birth with part of
 * the chain all but hanging (links 1..7 of a 12-link chain whose lengths and masses span six
 * decades at 1e-10 rad, the rest at finite angles: the upper links split off there in a
 * pitchfork that the lower ones unfold, and the branch turns by about a radian onto it; a path
 * in 60 digits with turns of at most 0.05 rad per step does the same).
 *
 * Test functions between two accepted points: a fold where t_omega changes sign (its resolved
 * sign in the link angles: below); a branch point
 * (grad G = 0 on G = 0: two curves cross, which the one-dimensional reduction makes visible as the
 * tangent (G_a, -G_omega) reversing against the direction of travel) where that orientation
 * changes; a return to the hanging chain where a changes sign. The orientation also reverses when
 * the corrector lands on a neighbouring curve: G changes sign across each curve of G = 0, so two
 * adjacent curves carry opposite orientations (coarse chains at high rates have curves a few
 * percent apart in a over long stretches: 10 links near omega = 12.89, mode 7's branch and an
 * isolated curve 5% apart). A genuine branch point is crossed by a step of any length, a
 * neighbouring curve is not reached by a short enough one: a step longer than DS_BRANCH on which
 * the orientation reverses is rejected and halved, and only a reversal that persists down to
 * DS_BRANCH is a branch point, unless the curve turns there. An unfolded branch point, two curves
 * that turn away from each other within a distance d, is followed around its turn where the steps
 * resolve d, and the turn can be far sharper than DS_BRANCH: where a branch passes just below the
 * birth of a higher mode with part of the chain all but hanging, that part splits off in a
 * pitchfork of its own, which the rest of the chain unfolds, and the branch turns by a right angle
 * within an arclength of 3e-9 to 5e-9, the other curve 1e-10 to 2e-10 away (random chains of 2 to
 * 12 links, lengths and masses over six decades, at ten times their births; a 50-digit path in
 * mpmath with turns of at most 0.02 rad per step goes around each such turn with steps of 1e-12
 * down to 1e-17 (at the finest, the rate moves within its round-off while links 1e-20 rad from
 * hanging bend), and ends on another curve than a path that takes the reversal). So before such a
 * reversal is taken, a copy of the path (the probe, look_ahead) goes on from the step's start in
 * the fine mode: steps down to DS_MIN_FINE, a reversal taken only at the smallest step, for an
 * arclength of FINE_SPAN. Where it gets there with no branch point, the path follows the curve the
 * same way (in the fine mode up to that arclength, the steps the probe made); where it does not,
 * the unfolding is narrower than the finest step and the reversal is located as a branch point,
 * and the path does not look ahead again within FINE_SPAN of there (the probe looked over that
 * stretch; on a branch that crawls, every step would probe it again).
 * Where the path in the link angles cannot be followed at any step down to DS_MIN_ANGLES (the
 * tangent turning too fast: an unfolding too narrow for the tangent's round-off), the shortest step
 * up to DS_CROSS on which the orientation reverses is taken across, as at a branch point. Each is
 * located by Brent's method (GSL roots/brent.c) on the step's arclength sigma in [0, ds], every
 * evaluation a corrector solve on the hyperplane at sigma (at the step's ends a fold's test
 * function is known: the tangent of each end): at a fold omega(sigma) is stationary, so the
 * arclength error enters omega squared, and sigma is bracketed to LOCATE_FOLD of the step (the test
 * function's own noise where the Jacobian is singular), elsewhere to round-off. A crossing of a
 * rate is first sought by Newton's method at that rate from the point interpolated in omega (omega
 * is monotone between the step's folds, so the point whose arclength coordinate lies on the piece
 * is the one), Brent's method only where that fails. A step across an event that cannot be located
 * (the curve between its ends more intricate than the step: a tail of links all but hanging that
 * turns in a pitchfork of its own, which the tip radius shows by changing sign and the metric,
 * dominated by the links at finite angles, does not) is taken back and halved, on the shot as in
 * the link angles.
 *
 * The same curve in the link angles. The shot loses digits on long chains at high rates: the
 * tip radius of a high mode is 1e-18 of the largest radius or less and fixes the shape only to
 * the round-off of the recursion amplified by the tension ratios, the Newton steps in (omega, a)
 * stall or the shape's links are unbalanced far above round-off. There the path continues in
 * x = (omega, theta_1..theta_N) on the force balance R(omega, theta) = 0 of src/nlink_balance.c
 * (tridiagonal Jacobian A; the arclength row (M0 t0) . (x - x0) = ds with the same metric M =
 * diag(1/omega^2, 1/N, ..)), each Newton step a bordered solve by block elimination, O(N); the
 * tangent solves [A, R_omega; (M0 t0)^T] t = e_{N+1} (one step of iterative refinement), which
 * orients it along the travel. A path can also start here, from an equilibrium's link angles
 * (whirl_nlink_path_start_angles: where roots crowd, the tip radius does not tell the shot which
 * one is meant); the tangent then solves the same system with the row e_omega. Test functions:
 * a fold where the resolved sign of t_omega changes (below), a branch point where
 * det [A, R_omega; (M0 t0)^T] = det A (c_omega - c . A^-1 R_omega) does (not at a fold, where
 * both factors do), a return to the hanging chain where the shape's projection on the
 * step's start changes sign, taken only at a critical rate (at_a_birth: elsewhere the step
 * passed onto the hanging chain, and is taken back and halved); located as above. The tip radius there is g tan theta_N / omega^2
 * (the radius that balances the tip mass: no cancellation). Which formulation a step uses: the
 * shot's round-off at an accepted point is measured as |G - G_ext| (G_ext the recursion in long
 * double) and turned into the force it leaves across the links (the pivot misses the axis by
 * a |u| |G - G_ext|, and moving it there changes link i's horizontal force by omega^2 M_i r_0,
 * relative to its tension T_i); above NOISE_UP, or where the shot's Newton steps fail, the path
 * goes over to the link angles (the point polished there at fixed omega, or where A is singular
 * there, a fold, on the hyperplane normal to the shot's tangent; the tangent carried over; a
 * first step from a birth to such a point within BIRTH_NEAR of the birth's rate begins in the
 * link angles instead, birth_angles), and it returns to the shot once that falls below NOISE_DOWN (after STAY steps, doubled
 * at each failure of the shot, so that it does not flap); on the way back the shot's Newton's
 * method at fixed omega must land within SHOT_SAME of the link angles (else it found another
 * equilibrium nearby). The shot is kept where it is clean: it is about three times cheaper per
 * step, and it resolves the tail of a high mode (radii of 1e-16 of the largest) to relative
 * accuracy where the link angles resolve it only to eps. Crossings
 * found on the shot where its round-off exceeds NOISE_UP are polished on the link angles.
 *
 * The index: a count where the orientation test is a sign. A step that passes two singular
 * points sees the orientation unchanged, and so does a corrector that lands on a curve two
 * crossings away (a tip mass of 1e12 chain masses: one step of 0.05 to 0.1 passes over two splits
 * of the pinned string, unfolded at 1e-12 by the links' weight, at nearly the same rate; 14 of
 * the 459 modes of N = 4..30 ended at 2.5 times their birth on another curve than a path with
 * small steps, and tip masses from 1e3 on did the same). The force balance counts them. With
 * U = g sum_i m_i z_i - omega^2 / 2 sum_i m_i r_i^2, the potential in the rotating frame,
 *     dU/dtheta_k = l_k cos theta_k F_k,  F_k = H_k - omega^2 sum_{i >= k} m_i r_i,
 * the balance of mass i is E_i = F_i - F_{i+1}, and R_i = E_i / (m_i omega^2) - E_{i-1} /
 * (m_{i-1} omega^2), so that R = omega^-2 B M^-1 B^T C^-1 grad U (B the lower bidiagonal
 * difference, M = diag(m_i), C = diag(l_i cos theta_i)); at an equilibrium A = omega^-2 B M^-1
 * B^T C^-1 Hess U, whose first factor has a positive determinant: A is singular exactly where
 * the Hessian of U is, at a fold or a branch point. A's eigenvalues are real (a diagonal
 * similarity makes it symmetric, src/nlink_balance.c), and the number of negative ones, the
 * index (a Sturm count, O(N) per step), changes by one where a simple eigenvalue crosses zero,
 * at each fold and each branch point. A step in the link angles on which the index changes by
 * more than one passed over two singular points, or landed on a curve beyond them, and is
 * rejected and halved like a step on which the orientation reverses (down to DS_BRANCH, below
 * which it is taken unless the probe finds a turn). Where no step passes two singular points it
 * costs nothing: the steps of mode 334 of 1000 links up to omega 600 and of every test are
 * unchanged. A curve of the same
 * index and orientation is not told apart by either test (the turn, the link angles and the
 * chord are).
 *
 * Two singular points within one step. The index is a count at the step's ends: an eigenvalue
 * of A that crosses zero and back within a step (a small S of two folds) leaves it unchanged,
 * and an S narrower than the step that turns the tangent by less than the slack of the chord
 * test passes every other test too (mode 75 of 300 links: two folds 0.0015 apart in omega at
 * 142.1 within one step; mode 334 of 1000 links: 48 such pairs between omega 600 and 700). The
 * eigenvalue mu of A nearest zero is followed from point to point instead, with its rate along
 * the tangent (src/nlink_balance.c: EIG_ITERS steps of inverse iteration with A's factors from
 * the last point's eigenvector x, then, with s_i = V_i / (omega^2 cos^2 theta_i) and
 * S = diag(s) A symmetric, the Rayleigh quotient and Hellmann-Feynman's rate
 *     mu = x^T S x / x^T diag(s) x,   d mu / ds = x^T diag(s) (dA/ds) x / x^T diag(s) x,
 * dA/ds from the tangent; O(N) per point, no further sines). Along the step mu(sigma) is smooth
 * where the eigenvalue is simple, and its cubic Hermite interpolant p from mu and d mu / ds at
 * both ends, sigma in [0, ds], errs by O(ds^4 max |d^4 mu / ds^4|). A step is rejected and
 * halved where p changes sign more than once (two crossings inside), or where p turns back
 * towards zero inside the step and comes closer to it than NEAR_MAX times mu at the nearer end:
 * there the interpolant's error is not known to be small against the distance from zero (mode
 * 334 of 1000 links near omega 622.2: p turns back at -5e-9 between ends at -2.7e-7 and
 * -4.7e-8, and the eigenvalue itself crosses zero and back, at two folds 0.0023 apart). After
 * halving, an end lies in the dip (the index then counts each fold) or the turn is resolved.
 * Where the eigenvectors at the two ends are not one eigenvalue's (the cosine of their angle
 * below EIG_SAME: another eigenvalue became the nearest to zero) the interpolant would join two
 * different curves, and the test is not made. Mode 334 of 1000 links to omega 700: 5132 folds
 * in 120935 steps (5032 in 119753 without the test); the path with steps of at most 0.003 finds
 * 5128 of them, each at the same rate (to 4e-14), and passes over two of the pairs (at 579.769
 * and 620.141, found at the same rates by steps of 1e-5 there). Up to omega 600: the same 706
 * folds in 17854 steps (17860). The tip shot forms no Jacobian, so it has no mu; on the shot,
 * and in the link angles where mu is resolved at both ends, the rate itself is interpolated
 * instead: a step on which the cubic Hermite interpolant of ln omega, from the chord and the end
 * tangents, turns back against the travel is halved (rate_turns_back, in the chord test). The
 * random chains of the README (five sets, six to twelve decades, 149698 modes): 7 had an S of two
 * folds (5e-7 to 3e-5 apart in omega, relative; 6 within 1% of the birth) in one shot step, which
 * the path did not report; it reports them now, each pair confirmed by the 40-digit path of
 * tests/tools/branch_mp.py, at the cost of 189 more steps in 8.7 million and with no end moved.
 *
 * The sign of t_omega that the fold test compares (rate_sign). Near a fold t_omega =
 * -mu (psi . t_theta) / (psi . R_omega) to first order (psi the left null vector of A), so its
 * sign is mu's, and mu is known only to about eps |A|. Where a branch passes a sharp turn with
 * part of the chain all but hanging, A stays singular to working precision over the turn
 * (|mu| of 1e-24 to 1e-15 of |A|) while the curve's true t_omega is small but of one sign: the
 * computed t_omega changed sign at random there, and the path reported clusters of folds within
 * a few ulps of each other in omega (the 40-digit continuation of tests/tools/branch_mp.py has none:
 * modes 5 and 9 of a 7- and a 10-link chain, 6 and 14 such folds). In the link angles the sign
 * of t_omega at a point counts only where |mu| > MU_RESOLVED |A|; elsewhere the last resolved
 * sign is kept, and a fold is a change of that sign between a step's ends (located as above; an
 * end whose own t_omega has the other sign is the fold itself to the tangent's resolution).
 * Measured over every fold of the 25314 modes of the random chains in the README (six decades):
 * at the ends of the steps that carry a genuine fold the larger |mu| / |A| is 1e-9 to 1e-2,
 * at the clusters' 1e-24 to 1e-15; 974 of 1528 folds, all in clusters of an even number, go,
 * and nothing else changes. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    /* Newton's method on the linearised shot G(omega, 0); where the shot is too inaccurate
     * for it (the high modes of long chains: a correction beyond BIRTH_NEWTON_SPAN omega_k, or none that
     * settles), the rate from the tridiagonal eigenproblem, accurate to a few eps relative */
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
    path_tangent(&s, p->s.metric, p->s.metric, p->pub.t_omega, p->pub.t_tip, &tw, &ta, &p->s.raw_sign);
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
    for (size_t i = 0; i < n; i++) arr_t_theta(p)[i] *= sign, c_th[i] = arr_t_theta(p)[i] / (double)n;
    double t_check;
    if (path_angle_tangent(p, omega, t_w / (omega * omega), c_th, &t_check, arr_t_theta_trial(p), &det,
                      NULL, NULL))
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
