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

#include <gsl/gsl_roots.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"
#include "steady/steady_internal.h"

#define DS_FIRST 0.02    /* first step from a start */
#define DS_MIN 1e-7      /* smallest step on the tip shot before it hands over to the link angles */
#define DS_MIN_ANGLES 1e-12 /* smallest step in the link angles before the continuation fails */
#define DS_MIN_FINE 1e-18 /* and in the fine mode (look_ahead): a hundredth of the rate's
                           * round-off (such a step moves only the links all but hanging, 1e-20
                           * to 1e-10 rad from the vertical, whose angles are resolved far below
                           * it; the 50-digit path turns with steps of 1e-17 at some of these
                           * corners, which 1e-16 took for branch points) */
#define DS_MIN_CHORD 1e-10 /* the step below which the chord test alone is set aside */
#define DS_MAX 0.1       /* largest step */
#define DS_BRANCH 1e-9   /* a step longer than this on which the orientation test changes sign
                          * is rejected (halved): see the header comment */
#define DS_CROSS 1e-6    /* in the link angles, the longest step taken across a branch point
                          * where the path cannot be followed at any step: see the header
                          * comment */
#define TURN_MAX 0.2     /* largest turn of the tangent per step [rad] */
#define DTHETA_MAX 0.2   /* largest change of a link angle per step [rad] */
#define CHORD_MAX 0.75   /* largest angle between a step's chord and its end tangents, relative
                          * to the turn of the tangent (see chord_angle) */
#define CHORD_SLACK 1e-3 /* and beyond that [rad] (and NEWTON_TOL over the chord's length: the
                          * round-off of its ends on short steps) */
#define SLOPE_MAX 0.5    /* the chord's rate part beyond the end tangents' [turn^2] (chord_test) */
#define SLOPE_SLACK 1e-9 /* and beyond that (the rate's round-off) */
#define NEWTON_MAX 10    /* corrector iterations per trial step */
#define NEWTON_EASY 4    /* a step converged in this many or fewer may grow */
#define NEWTON_TOL 1e-10 /* correction (metric norm) after which one last iteration is made */
#define NEWTON_FLOOR 1e-8 /* a correction this small that stops decreasing is round-off */
#define LOCATE_MAX 200   /* Brent iterations for an event */
#define LOCATE_FOLD 1e-12 /* a fold's bracket in sigma, relative to the step (see frame_locate) */
#define LOCATE_NEWTON_MAX 40 /* Newton iterations of a point of an event's location (slow near a
                              * branch point, where the corrector's system is singular) */
#ifndef NOISE_UP
#define NOISE_UP 3e-14   /* the path goes over to the link angles where the shot's round-off
                          * unbalances a link by more than this (relative to its tension) */
#define NOISE_DOWN 3e-15 /* and back to the tip shot where it falls below this */
#endif
#define SHOT_SAME 1e-9 /* back on the shot, no link angle moves more than this [rad] (else
                        * its Newton's method went to another equilibrium nearby) */
#define FINE_SPAN 1e-7  /* the arclength a probe looks ahead (look_ahead) */
#define RETURN_SPAN 1e-8 /* a return to the hanging chain is located within this of a critical
                          * rate (relative; at_a_birth) */
#define MU_RESOLVED 1e-12 /* in the link angles, the sign of t_omega at a point is the fold
                           * test's only where |mu| > MU_RESOLVED |A| (rate_sign) */
#define PROBE_STEPS 2000 /* and its most steps */
#define NEAR_MAX 0.5     /* an eigenvalue that turns back closer to zero than this times its
                          * value at the nearer end of the step: the step is halved (near_zero) */
#define EIG_ITERS 1      /* inverse iterations for the eigenvalue nearest zero, from the last */
#define EIG_ITERS_FIRST 8 /* and from a start */
#define EIG_SAME 0.5     /* the eigenvectors at a step's ends are of the same eigenvalue where
                          * their angle's cosine is at least this */
#define STAY_FIRST 16    /* steps in the link angles after the shot's Newton failed, before the
                          * shot is tried again (doubled on each such failure) */

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

/* G, with derivs its derivatives and the metric at (omega, a) (without, those are NaN); if theta
 * is not NULL, the link angles into theta[0..N-1]; if embed is not NULL (and derivs), the unit
 * tangent (G_a, -G_omega) normalised, embedded in (ln omega, theta / sqrt(N)), into embed[0..N]
 * (embed[N+1..2N] is scratch). */
static inline void shoot_core(const whirl_chain *c, double omega, double a, shot *s,
                              double *theta, double *embed, int derivs)
{
    size_t n = c->n;
    double u = 1, u_a = 0, u_w = 0, eta = 0, eta_a = 0, eta_w = 0, v = 0;
    double s_aa = 0, s_wa = 0, s_ww = 0, w2 = omega * omega;
    double q = 1, q_a = 0, q_w = 0; /* sum of u_i^2 and its derivatives */
    for (size_t i = n; i >= 1; i--) {
        double m = c->mass[i - 1], l = c->length[i - 1];
        if (derivs) eta_w += m * (2 * omega * u + w2 * u_w);
        eta += m * w2 * u;
        v += m * c->gravity;
        double h = a * eta, t2 = h * h + v * v, t = sqrt(t2);
        /* H^2 ~ omega^4 (and H H_a) overflow from omega ~ 1e77: from T^2 = 1e300 on,
         * T = hypot(H, V) and ratios to it */
        const int big = !(t2 < 1e300);
        if (big) t = hypot(h, v);
        u -= l * eta / t;
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

static void shoot_embed(const whirl_chain *c, double omega, double a, shot *s, double *theta,
                        double *embed)
{
    shoot_core(c, omega, a, s, theta, embed, 1);
}

static void shoot(const whirl_chain *c, double omega, double a, shot *s, double *theta)
{
    shoot_core(c, omega, a, s, theta, NULL, 1);
}

/* G alone, the same recursion in long double (64-bit significand on x86-64); the norm |u| in
 * *norm and max_i omega^2 M_i / T_i (M_i the mass below link i) in *load. */
static long double shoot_g_ext(const whirl_chain *c, double omega, double a, double *norm,
                               double *load)
{
    long double u = 1, eta = 0, v = 0, q = 1, w2 = (long double)omega * omega, worst = 0;
    for (size_t i = c->n; i >= 1; i--) {
        const long double m = c->mass[i - 1];
        eta += m * w2 * u;
        v += m * c->gravity;
        const long double h = a * eta, t = sqrtl(h * h + v * v);
        u -= c->length[i - 1] * eta / t;
        q += u * u;
        if (v / (c->gravity * t) > worst) worst = v / (c->gravity * t);
    }
    *norm = (double)sqrtl(q);
    *load = (double)(w2 * worst);
    return u / sqrtl(q);
}

/* The round-off of the shot s at (omega, a) in the force balance: the pivot misses the axis by
 * r_0 = a |u| (G - G_ext) (G_ext the recursion in extended precision, which stands for the
 * exact G), and shifting the chain onto the axis changes the horizontal force that link i
 * carries by omega^2 M_i r_0, relative to its tension T_i; the largest over the links. At
 * least the same for one unit of round-off in G. */
static double shot_noise(const whirl_chain *c, double omega, double a, const shot *s)
{
    double norm, load;
    const double dg = fabs(s->g - (double)shoot_g_ext(c, omega, a, &norm, &load));
    const double noise = fmax(dg, DBL_EPSILON) * fabs(a) * norm * load;
    return isfinite(noise) ? noise : INFINITY;
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
static int correct(nlink_path *p, const double *m0, double w0, double a0, double c_w,
                   double c_a, double sigma, double *w, double *a, shot *s, int *iters)
{
    int final = 0;
    double prev = INFINITY;
    p->s.floor_exit = 0;
    for (int it = 0; it < NEWTON_MAX; it++) {
        shoot(p->pub.chain, *w, *a, s, NULL);
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
            shoot(p->pub.chain, *w, *a, s, NULL);
            p->pub.shots++;
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
            p->s.floor_exit = 1;
            return 0;
        }
        prev = norm;
    }
    return -1;
}

static void path_free(nlink_path *p);
static void swap(size_t *x, size_t *y);

static nlink_path *path_alloc(const whirl_chain *c)
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

static void path_free(nlink_path *p)
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

/* dst becomes a copy of src at its current point: its public part, its state and its block (the
 * arrays, addressed by offsets); dst's force balance and probe are its own. */
static void path_copy(nlink_path *dst, const nlink_path *src)
{
    dst->pub = src->pub;
    dst->s = src->s;
    memcpy(dst->block, src->block, path_block_size(src->pub.chain->n) * sizeof(double));
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

/* ---- the path in the link angles (the equations: src/nlink_balance.c) ---- */

/* Scratch arrays of the path (7 N + 3 doubles). */
static double *scr_f(const nlink_path *p) { return arr_scratch(p); }
static double *scr_dth(const nlink_path *p) { return arr_scratch(p) + p->pub.chain->n; }
static double *scr_zero(const nlink_path *p) { return arr_scratch(p) + 2 * p->pub.chain->n; }
static double *scr_cth(const nlink_path *p) { return arr_scratch(p) + 3 * p->pub.chain->n; }
static double *scr_nodes(const nlink_path *p) { return arr_scratch(p) + 4 * p->pub.chain->n; }

/* The tip radius of the link angles: at an equilibrium r_N = rho_N = g tan theta_N / omega^2, the
 * radius that balances the tip mass, free of the cancellation of the sum of l_i sin theta_i (a
 * high mode's tip radius can be 1e-18 of the largest); and its rate of change along
 * (d omega, d theta). */
static double tip_of(const whirl_chain *c, double w, const double *th)
{
    return c->gravity * tan(th[c->n - 1]) / (w * w);
}

static double tip_rate(const whirl_chain *c, double w, const double *th, double dw,
                       const double *dth)
{
    const double co = cos(th[c->n - 1]);
    return c->gravity * (dth[c->n - 1] / (co * co) - 2 * tan(th[c->n - 1]) * dw / w) / (w * w);
}

/* The projection of the link angles th on th0 (it changes sign where the path passes the
 * hanging chain). */
static double shape_projection(size_t n, const double *th, const double *th0)
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
 * sigma from (*w, th) (in place), converged as correct(); the force balance is left factorised
 * at the converged point (or at the point before its last correction, when that was below the
 * square of NEWTON_TOL). Returns 0 when it converged, -1 otherwise. */
static int correct_angles(nlink_path *p, double w0, const double *th0, double c_w,
                          const double *c_th, double sigma, double *w, double *th, int *iters,
                          int max_iter)
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
        } else if (!final && it >= 2 && norm <= NEWTON_FLOOR && norm >= 0.5 * prev) {
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
static int angle_tangent(nlink_path *p, double w, double c_w, const double *c_th,
                         double *t_w, double *t_th, int *det_sign, double *ref, double *test)
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
        *test = sign * exp(fmax(-700, fmin(700, logdet - *ref))) * schur;
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

static int sign_of(double x)
{
    return (x > 0) - (x < 0);
}

/* The path at the point arr_theta(p), rate w, of a step or start in the link angles, with the tangent
 * (t_w, arr_t_theta(p)) and the orientation test's sign det. */
static void angle_point(nlink_path *p, double w, double t_w, int det)
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

/* The round-off of the shot at (omega, a) (shot_noise). */
static double noise_at(nlink_path *p, double omega, double a)
{
    shot s;
    shoot_core(p->pub.chain, omega, a, &s, NULL, NULL, 0);
    p->pub.shots += 2;
    return shot_noise(p->pub.chain, omega, a, &s);
}

/* The state at an accepted point. */
static void set_point(nlink_path *p, double omega, double a, const shot *s, double noise)
{
    p->pub.omega = omega;
    p->pub.tip_r = a;
    shot_metric(s, p->s.metric);
    p->s.noise = noise >= 0 ? noise : shot_noise(p->pub.chain, omega, a, s);
    if (omega < p->pub.omega_lo) p->pub.omega_lo = omega;
    if (omega > p->pub.omega_hi) p->pub.omega_hi = omega;
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

/* Over to the link angles at the current point of the shot: its angles polished on the force
 * balance at fixed omega, or where that fails (A singular or nearly: a fold at or next to the
 * point) on the hyperplane through the point normal to the shot's tangent (the arclength row at
 * sigma = 0, regular at a fold); the tangent carried over (the shot's tangent in theta is
 * arr_embed(p)). Returns 0, or -1 with the path unchanged. */
static int to_angles(nlink_path *p)
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
        if (correct_angles(p, p->pub.omega, arr_theta(p), c_w, c_th, 0, &w, th, NULL,
                           LOCATE_NEWTON_MAX))
            return -1;
    }
    int det;
    if (angle_tangent(p, w, c_w, c_th, &t_w, arr_t_theta(p), &det, NULL, NULL)) return -1;
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

/* Back to the tip shot at the current point (polished by the shot's Newton at fixed omega).
 * Returns 0, or -1 with the path unchanged. */
static int to_shot(nlink_path *p)
{
    double w = p->pub.omega, a = p->pub.tip_r, m[3];
    shot s;
    int iters;
    shoot(p->pub.chain, w, a, &s, NULL);
    shot_metric(&s, m);
    if (correct(p, m, w, a, 1, 0, 0, &w, &a, &s, &iters) != 0 || a == 0) return -1;
    double t_w = p->pub.t_omega, t_a = p->pub.t_tip, moved = 0;
    shoot_embed(p->pub.chain, w, a, &s, arr_theta_trial(p), arr_embed_trial(p));
    p->pub.shots++;
    for (size_t i = 0; i < p->pub.chain->n; i++)
        moved = fmax(moved, fabs(arr_theta_trial(p)[i] - arr_theta(p)[i]));
    if (!(moved <= SHOT_SAME)) return -1;
    swap(&p->s.theta, &p->s.theta_trial);
    swap(&p->s.embed, &p->s.embed_trial);
    set_point(p, w, a, &s, -1);
    tangent(&s, p->s.metric, p->s.metric, t_w, t_a, &p->pub.t_omega, &p->pub.t_tip, &p->s.raw_sign);
    p->pub.angles = 0;
    p->s.index = -1;
    p->s.mu = p->s.mu_rate = NAN;
    p->s.have_last = 0;
    return 0;
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
     * for it (the high modes of long chains: a correction beyond 1e-6 omega_k, or none that
     * settles), the rate from the tridiagonal eigenproblem, accurate to a few eps relative */
    shot s;
    const double omega_eig = omega;
    for (int it = 0; it < 20; it++) {
        shoot(c, omega, 0, &s, NULL);
        p->pub.shots++;
        double d = s.g / s.g_w;
        if (!isfinite(d) || fabs(omega - d - omega_eig) > 1e-6 * omega_eig || it == 19) {
            omega = omega_eig;
            break;
        }
        omega -= d;
        if (fabs(d) <= 4 * DBL_EPSILON * omega) break;
    }
    shoot_embed(c, omega, 0, &s, arr_theta(p), arr_embed(p));
    p->pub.shots++;
    p->pub.omega_birth = omega;
    set_point(p, omega, 0, &s, -1);
    /* the tangent is vertical: into a > 0 */
    p->pub.t_omega = 0;
    p->pub.t_tip = 1 / sqrt(s.m_aa);
    double tw, ta;
    tangent(&s, p->s.metric, p->s.metric, p->pub.t_omega, p->pub.t_tip, &tw, &ta, &p->s.raw_sign);
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
    if (correct(p, m, omega, tip_r, 1, 0, 0, &w, &a, &s, &iters) != 0 || a == 0)
        return whirl_fail(GSL_EFAILED, "no equilibrium near omega=%.17g, tip radius %.17g",
                          omega, tip_r);
    shoot_embed(p->pub.chain, w, a, &s, arr_theta(p), arr_embed(p));
    p->pub.shots++;
    set_point(p, w, a, &s, -1);
    double tw, ta;
    int raw;
    tangent(&s, p->s.metric, p->s.metric, s.g_a, -s.g_w, &tw, &ta, &raw);
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
    if (angle_tangent(p, omega, 1, scr_zero(p), &t_w, arr_t_theta(p), &det, NULL, NULL))
        return whirl_fail(GSL_EFAILED, "the equilibrium at omega=%.17g is a fold: no tangent "
                          "transversal to the rate", omega);
    const double sign = direction >= 0 ? 1 : -1;
    t_w *= sign;
    for (size_t i = 0; i < n; i++) arr_t_theta(p)[i] *= sign, c_th[i] = arr_t_theta(p)[i] / (double)n;
    double t_check;
    if (angle_tangent(p, omega, t_w / (omega * omega), c_th, &t_check, arr_t_theta_trial(p), &det,
                      NULL, NULL))
        return whirl_fail(GSL_EFAILED, "the tangent at omega=%.17g is not defined", omega);
    angle_point(p, omega, t_w, det);
    p->s.noise = noise_at(p, omega, p->pub.tip_r);
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

/* ---- events: located on the last step by Brent's method on sigma ---- */

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
    int cached;          /* phi at the bracket's ends is known: ends[], values[] */
    double ends[2], values[2];
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
        if (correct_angles(p, f->w0, th0, f->c_w, scr_cth(p), sigma, &f->w, f->th, &iters,
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
        if (correct(p, f->m0, f->w0, f->a0, c_w, c_a, sigma, &f->w, &f->a, &f->s, &iters) == 0)
            return 0;
    }
    return -1;
}

static double frame_phi(double sigma, void *params)
{
    step_frame *f = params;
    if (f->cached)
        for (int i = 0; i < 2; i++)
            if (sigma == f->ends[i]) return f->values[i];
    f->at = NAN;
    if (frame_point(f, sigma) != 0) {
        f->failed = 1;
        return 0; /* ends Brent's iteration, which then reports the failure */
    }
    f->at = sigma;
    if (f->kind == TARGET_OMEGA) return f->w - f->target;
    if (f->kind == TARGET_RETURN)
        return f->angles ? shape_projection(f->p->pub.chain->n, f->th, arr_theta0(f->p)) : f->a;
    if (f->angles) {
        double t_w, test;
        int det;
        if (angle_tangent(f->p, f->w, f->c_w, scr_cth(f->p), &t_w, arr_t_theta_trial(f->p), &det,
                          &f->ref, &test)) {
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

/* The sigma in [lo, hi] where phi changes sign (phi(lo) and phi(hi) of opposite signs, or one
 * zero); the corrected point left in f->w, f->a, f->s or f->th. */
static int frame_locate(step_frame *f, double lo, double hi, double *sigma)
{
    double f_lo = f->known ? f->values[0] : frame_phi(lo, f);
    double f_hi = f->known ? f->values[1] : frame_phi(hi, f);
    static const char *const what[] = {"a crossing of a rate", "a fold", "a branch point",
                                       "a return to the hanging chain"};
    if (f->failed)
        return whirl_fail(GSL_EFAILED, "%s between omega=%.17g and omega=%.17g could not be "
                          "located (no convergence at an end of the step)", what[f->kind], f->w0,
                          f->w1);
    if (f_lo == 0 || f_hi == 0 || (f_lo > 0) == (f_hi > 0)) {
        *sigma = fabs(f_lo) <= fabs(f_hi) ? lo : hi;
        if (f->at != *sigma) frame_phi(*sigma, f);
        return f->failed ? whirl_fail(GSL_EFAILED, "%s between omega=%.17g and "
                                      "omega=%.17g could not be located", what[f->kind],
                                      f->w0, f->w1)
                         : GSL_SUCCESS;
    }
    gsl_function fn = {frame_phi, f};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (s == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the root solver");
    /* the solver's set evaluates phi at both ends again: the values just found */
    f->ends[0] = lo, f->ends[1] = hi, f->values[0] = f_lo, f->values[1] = f_hi;
    f->cached = 1;
    int status = gsl_root_fsolver_set(s, &fn, lo, hi);
    f->cached = 0;
    for (int it = 0; status == GSL_SUCCESS; it++) {
        status = gsl_root_fsolver_iterate(s);
        if (f->failed || status != GSL_SUCCESS) {
            status = whirl_fail(GSL_EFAILED, "%s between omega=%.17g and omega=%.17g could not be "
                                "located", what[f->kind], f->w0, f->w1);
            break;
        }
        double x_lo = gsl_root_fsolver_x_lower(s), x_hi = gsl_root_fsolver_x_upper(s);
        /* at a fold omega is stationary in sigma: its error is of the order of the square of
         * sigma's, and the test function t_omega is no better than about 1e-12 of the step
         * there (the Jacobian is singular), so its bracket is closed to LOCATE_FOLD; elsewhere
         * to round-off */
        const double tol = f->kind == TARGET_FOLD ? LOCATE_FOLD : 4 * DBL_EPSILON;
        if (x_hi - x_lo <= tol * f->ds) {
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
    /* the corrected point at the root (Brent's last evaluation, as a rule) */
    if (status == GSL_SUCCESS && f->at != *sigma && (frame_phi(*sigma, f), f->failed))
        status = whirl_fail(GSL_EFAILED, "%s between omega=%.17g and omega=%.17g could not be "
                            "located", what[f->kind], f->w0, f->w1);
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
    f->cached = 0;
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
        if (correct_angles(p, omega, f->th, 1, scr_zero(p), 0, &w, f->th, &iters,
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
    if (correct(p, m, omega, f->a, 1, 0, 0, &w, &a, &f->s, &iters) != 0 || a == 0) return -1;
    f->w = w;
    f->a = a;
    return 0;
}

/* status, the message of a failure (not a stop request) of a path begun at a birth led by its
 * mode: "mode k: ..." */
static int name_mode(const nlink_path *p, int status)
{
    if (status == GSL_SUCCESS || status == WHIRL_EINTERRUPTED || p->pub.mode <= 0) return status;
    char message[512];
    snprintf(message, sizeof message, "%s", whirl_last_error());
    return whirl_fail(status, "mode %d: %s", p->pub.mode, message);
}

static int path_crossings(nlink_path *p, double omega, int max, double *tip_r);

int whirl_nlink_path_crossings(whirl_nlink_path *path, double omega, int max, double *tip_r)
{
    nlink_path *p = path_of(path);
    const int found = path_crossings(p, omega, max, tip_r);
    return found < 0 ? -name_mode(p, -found) : found;
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
        const double slack = 1e-9 * f.ds;
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
                return -whirl_fail(GSL_EFAILED, "no equilibrium at omega=%.17g near the branch",
                                   omega);
        }
        double *th = arr_cross_theta(p) + (size_t)found * n;
        if (f.angles) {
            for (size_t i = 0; i < n; i++) th[i] = f.th[i];
        } else {
            /* the shot's point polished on the force balance in the link angles, which the
             * shot's round-off does not limit */
            shot s;
            shoot(p->pub.chain, f.w, f.a, &s, th);
            p->pub.cross_angles[found] = 0;
            if (shot_noise(p->pub.chain, f.w, f.a, &s) > NOISE_UP) {
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
static int shape_info(nlink_path *p, int angles, double omega, double a, const double *th,
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
        shoot(c, omega, tip, &s, NULL);
        shot_metric(&s, m);
        if (correct(p, m, omega, tip, 1, 0, 0, &w, &tip, &s, &iters) == 0 &&
            fabs(tip - info->tip_r) <= 1e-6 * info->tip_r) {
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
        shoot(p->pub.chain, f->w, f->a, &s, th);
    }
    double *r = scr_nodes(p);
    whirl_shape_info info;
    int status = shape_info(p, f->angles, f->w, f->a, th, &info, r, r + n + 1, r + 2 * (n + 1));
    e->n_nodes = status == GSL_SUCCESS ? info.n_nodes : -1;
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

static int find_events(nlink_path *p, int branch)
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
        ? shape_projection(p->pub.chain->n, arr_theta(p), arr_theta0(p)) < 0
        : p->s.last.a0 != 0 && (p->s.last.a0 > 0) != (p->pub.tip_r > 0);
    if (!status && passed) {
        frame_of_last(p, &f, TARGET_RETURN, 0);
        if (!(status = frame_locate(&f, 0, f.ds, &sigma)) && !at_a_birth(p, f.w))
            status = whirl_fail(GSL_EFAILED, "the step between omega=%.17g and omega=%.17g meets "
                                "the hanging chain at omega=%.17g, where no branch is born",
                                f.w0, f.w1, f.w);
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

/* The counters of a step taken back after an event on it could not be located (the point and
 * tangent restored by the caller): the next trial is half as long. */
static void step_undone(nlink_path *p, double ds)
{
    p->pub.arclength -= ds;
    p->pub.steps--;
    p->s.have_last = 0;
    p->pub.n_events = 0;
    p->pub.ended = 0;
    p->pub.rejected++;
    p->pub.ds = 0.5 * ds;
}

/* A stop request at the current point. */
static int stopped(const nlink_path *p)
{
    return whirl_fail(WHIRL_EINTERRUPTED, "stopped at omega=%.17g after %ld steps", p->pub.omega,
                      p->pub.steps);
}

/* The path is in the fine mode at its current point (look_ahead). */
static int in_fine_mode(const nlink_path *p)
{
    return p->pub.arclength < p->s.fine_end;
}

/* The smallest step in the link angles at the current point: finer in the fine mode. */
static double ds_smallest(const nlink_path *p)
{
    return in_fine_mode(p) ? DS_MIN_FINE : DS_MIN_ANGLES;
}

/* The failure of the continuation at the last point (w0, a0) with a step below DS_MIN: names
 * the rate reached and why the last trial step was rejected (whirl_nlink_path_step adds the
 * mode). */
static int fail_at(nlink_path *p, int status, double w0, double a0)
{
    if (p->pub.angles)
        return whirl_fail(status, "the continuation in the link angles fails at omega=%.17g "
                          "(tip radius %.6g, link tensions differing by a factor %.2g): %s at "
                          "the smallest step %g", w0, a0, tension_spread(p->pub.chain, w0, a0),
                          p->s.why, ds_smallest(p));
    return whirl_fail(status, "the continuation fails at omega=%.17g (tip radius %.6g): %s at "
                      "the smallest step %g", w0, a0, p->s.why, DS_MIN);
}


/* The accepted step's start, kept for the events and crossings. */
static void keep_start(nlink_path *p, const double *m0, double w0, double a0, double ds)
{
    for (int i = 0; i < 3; i++) p->s.last.m0[i] = m0 ? m0[i] : 0;
    p->s.last.w0 = w0;
    p->s.last.a0 = a0;
    p->s.last.t_w = p->pub.t_omega;
    p->s.last.t_a = p->pub.t_tip;
    p->s.last.ds = ds;
    p->s.last.raw_sign = p->s.raw_sign;
    p->s.last.angles = p->pub.angles;
    p->s.last.det_sign = p->s.det_sign;
    p->s.last.index = p->s.index;
    p->s.last.mu = p->s.mu;
    p->s.last.mu_rate = p->s.mu_rate;
    p->s.last_rate_sign = p->s.rate_sign;
    if (p->pub.angles)
        for (size_t i = 0; i < p->pub.chain->n; i++)
            arr_theta0(p)[i] = arr_theta(p)[i], arr_t_theta0(p)[i] = arr_t_theta(p)[i];
    p->s.have_last = 1;
}

/* Whether the rate turns back within a step whose ends' rates move the same way: two folds
 * inside, which the fold test (a change of sign between the ends) does not see. slope is the
 * chord's mean d ln omega / ds, r0 and r1 the end tangents' (oriented along the travel), slack
 * their round-off. The cubic Hermite interpolant of ln omega on the step, x in [0, 1] along it,
 * has the rate
 *     q(x) = 6 x (1 - x) slope + r0 (1 - 4 x + 3 x^2) + r1 (3 x^2 - 2 x)
 * (q(0) = r0, q(1) = r1, mean slope), and the step turns back where q falls below -slack inside:
 * certainly where slope itself has the other sign (the rate went back), and where the chord
 * is too short for ends that both move on at their rates (q(1/2) = 1.5 slope - (r0 + r1) / 4).
 * Random chains over six decades: S-shaped pairs of folds within 1e-5 of each other in omega
 * just above a birth, a step of 0.05 across both with the rate at its ends of one sign and
 * moved on by 2e-7 of the 1e-5 the end tangents predict (the 40-digit path of
 * tests/tools/branch_mp.py finds both folds). The interpolant errs by O(ds^4); where the curve's rate
 * only dips towards zero, halving resolves the dip. */
static int rate_turns_back(double slope, double r0, double r1, double slack)
{
    if (!(r0 * r1 > 0)) return 0;
    if (r0 < 0) slope = -slope, r0 = -r0, r1 = -r1;
    if (slope < -slack) return 1;
    const double a = 3 * (r0 + r1) - 6 * slope, b = 6 * slope - 4 * r0 - 2 * r1;
    if (!(a > 0)) return 0; /* q is concave or linear: its least value is at an end */
    const double x = -b / (2 * a);
    return x > 0 && x < 1 && r0 - b * b / (4 * a) < -slack;
}

/* What the chord of a step, from (w0, th0) to (w1, th1) in (ln omega, theta / sqrt(N)), says of
 * the curve between: NULL where it is consistent with an arc the step resolves, else why not.
 * s0 e0 and s1 e1 are the unit tangents at the ends (embedded the same way: e[0] the rate's
 * part, e[1..N] the link angles'), turn the angle between them [rad].
 * - On an arc in a plane whose curvature keeps its sign the chord lies between the end tangents,
 *   at angles from them that add up to the turn: at most 2/3 of it from either where the
 *   curvature grows linearly from zero across the step, half of it on a circle. A chord further
 *   than CHORD_MAX times the turn from either tangent marks a step across a part of the curve it
 *   does not resolve (a small S of two folds, both end tangents on the same side of it).
 * - The chord's rate part (its mean d ln omega / ds) lies within the range of the tangents'
 *   rate parts along the step; on such an arc that range exceeds the ends' by at most turn^2 / 8.
 *   Beyond SLOPE_MAX turn^2 the rate went back and forth between the ends while the link angles
 *   moved on (two folds within the step on a nearly straight curve, which the angles do not
 *   show: the rate is a small part of the tangent away from folds).
 * - Where rates is set (the ends' rate parts are resolved: their signs are the fold test's), the
 *   rate's cubic Hermite interpolant does not turn back within the step (rate_turns_back). */
static const char *chord_test(size_t n, double w0, const double *th0, double w1,
                              const double *th1, const double *e0, double s0, const double *e1,
                              double s1, double turn, int rates)
{
    const double scale = 1 / sqrt((double)n), lw = log(w1 / w0);
    double q = lw * lw, c0 = lw * e0[0], c1 = lw * e1[0];
    for (size_t i = 0; i < n; i++) {
        const double d = scale * (th1[i] - th0[i]);
        q += d * d;
        c0 += d * e0[i + 1];
        c1 += d * e1[i + 1];
    }
    const double len = sqrt(q);
    if (!(len > 0 && isfinite(len))) return NULL;
    /* the chord's own round-off: its ends are converged to NEWTON_TOL */
    const double noise = NEWTON_TOL / len;
    const double chord = fmax(acos(fmin(1, fmax(-1, s0 * c0 / len))),
                              acos(fmin(1, fmax(-1, s1 * c1 / len))));
    if (chord > CHORD_MAX * turn + CHORD_SLACK + noise)
        return "the chord leaves the end tangents (a part of the curve passed over)";
    const double slope = lw / len, excess = SLOPE_MAX * turn * turn + SLOPE_SLACK + noise;
    if ((rates && rate_turns_back(slope, s0 * e0[0], s1 * e1[0], SLOPE_SLACK + noise)) ||
        slope < fmin(s0 * e0[0], s1 * e1[0]) - excess ||
        slope > fmax(s0 * e0[0], s1 * e1[0]) + excess)
        return "the rate goes back and forth within the step (two folds passed over)";
    return NULL;
}

static void swap(size_t *x, size_t *y)
{
    const size_t tmp = *x;
    *x = *y;
    *y = tmp;
}

/* The cubic Hermite interpolant p on [0, 1] of the values f0, f1 and the derivatives d0, d1 at
 * 0 and 1: its number of sign changes (the sign at 0, at the zeros of p' inside and at 1, in
 * order) as the return value; in *near, the least |p| at a zero of p' inside where p has the
 * sign of both ends, relative to the smaller of |f0| and |f1| (INFINITY where there is none). */
static int hermite_crossings(double f0, double d0, double f1, double d1, double *near)
{
    const double a = 2 * f0 + d0 - 2 * f1 + d1, b = -3 * f0 - 2 * d0 + 3 * f1 - d1, c = d0;
    double x[4] = {0, 0, 0, 1};
    int k = 1;
    /* p'(x) = 3 a x^2 + 2 b x + c */
    const double qa = 3 * a, qb = 2 * b, disc = qb * qb - 4 * qa * c;
    if (qa != 0 && disc > 0) {
        const double q = -0.5 * (qb + copysign(sqrt(disc), qb));
        double r1 = q / qa, r2 = q != 0 ? c / q : r1;
        if (r1 > r2) {
            const double t = r1;
            r1 = r2;
            r2 = t;
        }
        if (r1 > 0 && r1 < 1) x[k++] = r1;
        if (r2 > 0 && r2 < 1) x[k++] = r2;
    } else if (qa == 0 && qb != 0 && -c / qb > 0 && -c / qb < 1) {
        x[k++] = -c / qb;
    }
    x[k++] = 1;
    int changes = 0;
    double prev = f0;
    *near = INFINITY;
    const int same = (f0 > 0 && f1 > 0) || (f0 < 0 && f1 < 0);
    for (int i = 1; i < k; i++) {
        const double v = ((a * x[i] + b) * x[i] + c) * x[i] + f0;
        if ((v < 0 && prev > 0) || (v > 0 && prev < 0)) changes++;
        if (v != 0) prev = v;
        if (same && i + 1 < k && (v > 0) == (f0 > 0))
            *near = fmin(*near, fabs(v) / fmin(fabs(f0), fabs(f1)));
    }
    return changes;
}

/* The eigenvalue of the force balance nearest zero at the trial point (factorised) and its rate
 * along the trial tangent (t_w, arr_t_theta_trial(p)) into *mu, *mu_rate, its eigenvector into
 * arr_eig_trial(p) (from the start's); NAN where not found. Returns 1 where the step of length ds
 * does not resolve it (see the header comment): its cubic Hermite interpolant in the arclength
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
    const int changes = hermite_crossings(p->s.mu, ds * p->s.mu_rate, *mu, ds * *mu_rate, &near);
    return changes > 1 || near < NEAR_MAX;
}

static int path_step(nlink_path *p);

/* Looks ahead from the current point before a reversal of the orientation test on a step no
 * longer than DS_BRANCH is taken for a branch point (see the header comment): the probe, a copy
 * of the path, goes on from here with steps from ds, in the fine mode (a reversal taken only at
 * the smallest step) up to FINE_SPAN of arclength. Returns 1 where it gets there within
 * PROBE_STEPS steps with no branch point: the curve turns sharply here and the path should
 * follow it; 0 where it does not (a branch point at the finer scale too, or a failure: the
 * reversal is taken as before); WHIRL_EINTERRUPTED on a stop request, GSL_ENOMEM. The probe's
 * shots are counted in p->pub.shots. */
static int look_ahead(nlink_path *p, double ds)
{
    if (p->probe == NULL && (p->probe = path_alloc(p->pub.chain)) == NULL)
        return GSL_ENOMEM;
    nlink_path *q = p->probe;
    path_copy(q, p);
    q->pub.ds = ds;
    q->s.fine_end = p->pub.arclength + FINE_SPAN;
    int status = GSL_SUCCESS, resolved = 0;
    for (long k = 0; k < PROBE_STEPS && status == GSL_SUCCESS && !resolved; k++) {
        status = path_step(q);
        for (int e = 0; e < q->pub.n_events; e++)
            if (q->pub.event[e].kind == WHIRL_EVENT_BRANCH_POINT) status = GSL_EFAILED;
        resolved = status == GSL_SUCCESS && (q->pub.ended || !in_fine_mode(q));
    }
    p->pub.shots = q->pub.shots; /* the probe counted on from p->pub.shots */
    if (status == WHIRL_EINTERRUPTED) return status;
    return resolved;
}

/* One step in the link angles: predictor x0 + ds t0 + ds^2 k / 2 (k the curvature, the change
 * of the tangent over the last step divided by its length, where that step was made in the link
 * angles too), Newton's method on R = 0 and the arclength row (M0 t0) . (x - x0) = ds, the same
 * acceptance as in the shot. */
static int angle_step(nlink_path *p)
{
    const whirl_chain *c = p->pub.chain;
    const size_t n = c->n;
    const double w0 = p->pub.omega, a0 = p->pub.tip_r;
    double *c_th = scr_cth(p);
    const double c_w = p->pub.t_omega / (w0 * w0);
    int crossing = 0; /* the trials probe for a step across a branch point */
    int chord_off = 0, chord_failed = 0; /* the chord test set aside; it rejected the last trial */
    const double ds_first = p->pub.ds;
    /* the step above which a reversal of the orientation is another curve close by */
    const double ds_min = ds_smallest(p), ds_branch = in_fine_mode(p) ? ds_min : DS_BRANCH;
    const char *why = "";
    for (;;) {
        for (size_t i = 0; i < n; i++) c_th[i] = arr_t_theta(p)[i] / (double)n;
        const double ds = p->pub.ds;
        double w = w0 + ds * p->pub.t_omega, *th = arr_theta_trial(p), t_w = 0, turn = 0, dtheta = 0;
        for (size_t i = 0; i < n; i++) th[i] = arr_theta(p)[i] + ds * arr_t_theta(p)[i];
        if (p->s.have_last && p->s.last.angles) {
            /* the second-order term, the curvature from the tangents at the last two points */
            const double q = 0.5 * ds * ds / p->s.last.ds;
            w += q * (p->pub.t_omega - p->s.last.t_w);
            for (size_t i = 0; i < n; i++) th[i] += q * (arr_t_theta(p)[i] - arr_t_theta0(p)[i]);
        }
        int iters = NEWTON_MAX, det = 0, index = -1, pair = 0;
        double mu = NAN, mu_rate = NAN, mu_min = INFINITY; /* mu_min: mu's resolution */
        int ok = correct_angles(p, w0, arr_theta(p), c_w, c_th, ds, &w, th, &iters, NEWTON_MAX) == 0;
        if (!ok) p->s.why = "Newton's method on the force balance does not converge";
        if (ok && angle_tangent(p, w, c_w, c_th, &t_w, arr_t_theta_trial(p), &det, NULL, NULL)) {
            ok = 0;
            p->s.why = "the tangent is not defined (a singular point)";
        }
        if (ok) {
            index = whirl_nlink_balance_index(p->balance);
            pair = near_zero(p, t_w, ds, &mu, &mu_rate);
            angle_embed(n, w, t_w, arr_t_theta_trial(p), arr_embed_trial(p));
            double cosine = 0;
            for (size_t i = 0; i <= n; i++) cosine += arr_embed_trial(p)[i] * arr_embed(p)[i];
            turn = acos(fmin(1, fmax(-1, cosine)));
            for (size_t i = 0; i < n; i++) dtheta = fmax(dtheta, fabs(th[i] - arr_theta(p)[i]));
            mu_min = MU_RESOLVED * whirl_nlink_balance_scale(p->balance);
            const char *chord = chord_test(n, w0, arr_theta(p), w, th, arr_embed(p), 1,
                                           arr_embed_trial(p), 1, turn,
                                           fabs(p->s.mu) > mu_min && fabs(mu) > mu_min);
            if (turn > TURN_MAX && !crossing)
                ok = 0, p->s.why = "the tangent turns by more than 0.2 rad";
            if (dtheta > DTHETA_MAX) ok = 0, p->s.why = "a link angle changes by more than 0.2 rad";
            chord_failed = chord && !crossing && !chord_off;
            if (chord_failed) ok = 0, p->s.why = chord;
            const int jump = p->s.index >= 0 && abs(index - p->s.index) > 1;
            if (det != p->s.det_sign && ds > ds_branch && !crossing)
                ok = 0, p->s.why = "the orientation test changes sign (another curve close by)";
            if (jump && ds > ds_branch && !crossing)
                ok = 0, p->s.why = "the index of the force balance changes by more than one (two "
                                 "singular points passed over)";
            if (pair && ds > ds_branch && !crossing)
                ok = 0, p->s.why = "an eigenvalue of the force balance crosses zero and back "
                                 "within the step (two folds passed over)";
            if (det == p->s.det_sign && crossing) ok = 0;
            if (ok && !crossing && (det != p->s.det_sign || jump || pair) &&
                !in_fine_mode(p) && p->pub.arclength >= p->s.probe_end) {
                /* a branch point by the rule of DS_BRANCH: unless the curve turns within it
                 * (not looked at again within FINE_SPAN of where the probe last found a branch
                 * point at the finer scale: it looked over that stretch) */
                const int ahead = look_ahead(p, 0.5 * ds);
                if (ahead == WHIRL_EINTERRUPTED) return stopped(p);
                if (ahead != 0 && ahead != 1) return ahead;
                if (ahead == 0) p->s.probe_end = p->pub.arclength + FINE_SPAN;
                if (ahead == 1) {
                    /* the fine mode from here on, the steps as from a fresh call (as the
                     * probe's) */
                    p->s.fine_end = p->pub.arclength + FINE_SPAN;
                    p->pub.rejected++;
                    p->pub.ds = 0.5 * ds;
                    return angle_step(p);
                }
            }
        }
        if (!ok) {
            p->pub.rejected++;
            if (crossing) {
                /* the probe: steps doubling up to DS_CROSS */
                p->pub.ds *= 2;
                if (p->pub.ds > DS_CROSS) {
                    p->s.why = why;
                    return fail_at(p, GSL_EFAILED, w0, a0);
                }
                continue;
            }
            p->pub.ds *= 0.5;
            if (p->pub.ds < DS_MIN_CHORD && chord_failed && !chord_off) {
                /* the chord test alone rejected steps down to the smallest: at that scale the
                 * corrected points scatter by their own round-off across a turn of the curve
                 * sharper than the tangent resolves (a heavy tip's pinned string where it
                 * splits), and the chord measures that scatter, not a part of the curve passed
                 * over. The step is retried from its first length without the chord test,
                 * every other test kept (the turn, the link angles, the orientation: no step
                 * lands on another curve). */
                chord_off = 1;
                p->pub.ds = ds_first;
                continue;
            }
            if (p->pub.ds < ds_min) {
                /* the curve cannot be followed at any step: if a curve of the opposite
                 * orientation lies within DS_CROSS ahead, the two meet there to within the
                 * resolution of the steps (a branch point, its unfolding narrower than the
                 * smallest step): the shortest step that reaches it is taken across */
                why = p->s.why;
                crossing = 1;
                p->pub.ds = 2 * ds_min;
            }
            continue;
        }
        keep_start(p, NULL, w0, a0, ds);
        swap(&p->s.theta, &p->s.theta_trial);
        swap(&p->s.t_theta, &p->s.t_theta_trial);
        swap(&p->s.embed, &p->s.embed_trial);
        p->pub.omega = w;
        p->pub.tip_r = tip_of(c, w, arr_theta(p));
        p->pub.t_omega = t_w;
        p->pub.t_tip = tip_rate(c, w, arr_theta(p), t_w, arr_t_theta(p));
        p->s.det_sign = det;
        p->s.index = index;
        swap(&p->s.eig, &p->s.eig_trial);
        p->s.mu = mu;
        p->s.mu_rate = mu_rate;
        if (!(fabs(mu) <= mu_min) && t_w != 0) p->s.rate_sign = sign_of(t_w);
        const double lo = p->pub.omega_lo, hi = p->pub.omega_hi, noise = p->s.noise;
        if (w < p->pub.omega_lo) p->pub.omega_lo = w;
        if (w > p->pub.omega_hi) p->pub.omega_hi = w;
        p->pub.arclength += ds;
        p->pub.steps++;
        p->s.noise = noise_at(p, w, p->pub.tip_r);
        const int status = find_events(p, det != p->s.last.det_sign);
        if (status != GSL_EFAILED) {
            if (iters <= NEWTON_EASY && turn < TURN_MAX / 2 && dtheta < DTHETA_MAX / 2)
                p->pub.ds = fmin(1.5 * ds, DS_MAX);
            return status;
        }
        /* an event the step passed could not be located (the curve between the two points is
         * more intricate than the step: two close folds, a near crossing of another branch):
         * back to the step's start, half the step */
        p->s.why = "an event between two points could not be located";
        for (size_t i = 0; i < n; i++)
            arr_theta(p)[i] = arr_theta0(p)[i], arr_t_theta(p)[i] = arr_t_theta0(p)[i];
        p->pub.omega = w0;
        p->pub.tip_r = a0;
        p->pub.t_omega = p->s.last.t_w;
        p->pub.t_tip = p->s.last.t_a;
        p->s.det_sign = p->s.last.det_sign;
        p->s.index = p->s.last.index;
        swap(&p->s.eig, &p->s.eig_trial);
        p->s.mu = p->s.last.mu;
        p->s.mu_rate = p->s.last.mu_rate;
        p->s.rate_sign = p->s.last_rate_sign;
        angle_embed(n, w0, p->pub.t_omega, arr_t_theta(p), arr_embed(p));
        p->pub.omega_lo = lo, p->pub.omega_hi = hi, p->s.noise = noise;
        step_undone(p, ds);
        if (crossing || p->pub.ds < ds_min) return fail_at(p, GSL_EFAILED, w0, a0);
    }
}

#define BIRTH_AMPLITUDE 1e-5 /* rms link angle of the first point of a birth in the link angles */
#define GAP_MAX 30 /* secant iterations of a point between the birth and that first point */
#define GAP_MIN 1e-13 /* omega / omega_k - 1 below which a rate is the birth itself (no gap) */
#define BIRTH_NEAR 1e-10 /* omega / omega_k - 1 below which the force balance at fixed omega
                          * does not tell a branch's point from the hanging chain: the
                          * eigenvalue of its Jacobian nearest zero is about that times its
                          * largest, the shot's round-off 3e-14 (NOISE_UP) */

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
    return correct_angles(p, p->pub.omega_birth, scr_zero(p), 0, c_th, amplitude, w, th, NULL,
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
    if (angle_tangent(p, w, 0, scr_cth(p), &t_w, arr_t_theta(p), &det, NULL, NULL)) return -1;
    swap(&p->s.theta, &p->s.theta_trial);
    angle_point(p, w, t_w, det);
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
static int birth_gap(nlink_path *p, double omega, double *th)
{
    const double wk = p->pub.omega_birth;
    double s2_a = 0, w_a = wk, s2_b = BIRTH_AMPLITUDE * BIRTH_AMPLITUDE, w_b;
    if (birth_point(p, BIRTH_AMPLITUDE, 0, th, &w_b)) return -1;
    for (int it = 0; it < GAP_MAX; it++) {
        if (fabs(w_b - omega) <= 4 * DBL_EPSILON * omega) return 0;
        if (!(w_b != w_a)) return -1;
        const double s2 = s2_b + (omega - w_b) * (s2_b - s2_a) / (w_b - w_a);
        if (!(s2 > 0 && isfinite(s2))) return -1;
        const double guess = sqrt(s2 / s2_b);
        s2_a = s2_b, w_a = w_b, s2_b = s2;
        if (birth_point(p, sqrt(s2), guess, th, &w_b)) return -1;
    }
    return -1;
}

/* The first step from the birth, begun in the link angles instead of on the shot (birth_angles);
 * the failure at the birth where that does not start. */
static int begin_in_angles(nlink_path *p)
{
    if (birth_angles(p) == 0) return angle_step(p);
    return fail_at(p, GSL_EFAILED, p->pub.omega, p->pub.tip_r);
}

/* One step on the tip shot (the equations above the file). */
static int shot_step(nlink_path *p)
{
    const whirl_chain *c = p->pub.chain;
    const double w0 = p->pub.omega, a0 = p->pub.tip_r, *m0 = p->s.metric;
    const double c_w = m0[0] * p->pub.t_omega + m0[1] * p->pub.t_tip;
    const double c_a = m0[1] * p->pub.t_omega + m0[2] * p->pub.t_tip;
    /* the predictor of a: along the tangent, or along it in ln|a| (where a decays or grows
     * exponentially, as on the high modes), whichever predicts the previous point better */
    int log_predictor = 0;
    if (p->s.have_last && a0 != 0 && p->s.last.a0 != 0 && (a0 > 0) == (p->s.last.a0 > 0)) {
        double back = -p->s.last.ds, lin = a0 + back * p->pub.t_tip;
        double lg = a0 * exp(fmax(-50, fmin(50, back * p->pub.t_tip / a0)));
        log_predictor = fabs(lg - p->s.last.a0) < fabs(lin - p->s.last.a0);
    }
    for (;;) {
        double ds = p->pub.ds, w = w0 + ds * p->pub.t_omega;
        double a = log_predictor ? a0 * exp(fmax(-50, fmin(50, ds * p->pub.t_tip / a0)))
                                 : a0 + ds * p->pub.t_tip;
        shot s;
        int iters = NEWTON_MAX, ok = correct(p, m0, w0, a0, c_w, c_a, ds, &w, &a, &s, &iters) == 0;
        double turn = 0, dtheta = 0, t_w = 0, t_a = 0;
        int raw = 0;
        if (!ok) p->s.why = "Newton's method on the tip shot does not converge";
        if (ok && p->s.floor_exit) {
            /* converged only to the shot's round-off: not an equilibrium to round-off */
            ok = 0;
            iters = NEWTON_MAX;
            p->s.why = "the tip shot's round-off exceeds the tolerance";
        }
        if (ok) {
            shoot_embed(c, w, a, &s, arr_theta_trial(p), arr_embed_trial(p));
            p->pub.shots++;
            double m1[3];
            shot_metric(&s, m1);
            tangent(&s, m1, m0, p->pub.t_omega, p->pub.t_tip, &t_w, &t_a, &raw);
            /* the turn of the tangent in (ln omega, theta / sqrt(N)); the embedded tangents are
             * those of (G_a, -G_omega), oriented by raw and the current orientation */
            double cosine = 0;
            for (size_t i = 0; i <= c->n; i++) cosine += arr_embed_trial(p)[i] * arr_embed(p)[i];
            cosine *= raw * p->s.raw_sign;
            turn = acos(fmin(1, fmax(-1, cosine)));
            for (size_t i = 0; i < c->n; i++)
                dtheta = fmax(dtheta, fabs(arr_theta_trial(p)[i] - arr_theta(p)[i]));
            const char *chord = chord_test(c->n, w0, arr_theta(p), w, arr_theta_trial(p), arr_embed(p),
                                           p->s.raw_sign, arr_embed_trial(p), raw, turn, 1);
            if (turn > TURN_MAX) ok = 0, p->s.why = "the tangent turns by more than 0.2 rad";
            if (dtheta > DTHETA_MAX) ok = 0, p->s.why = "a link angle changes by more than 0.2 rad";
            if (chord) ok = 0, p->s.why = chord;
            if (raw != p->s.raw_sign && ds > DS_BRANCH)
                ok = 0, p->s.why = "the orientation test changes sign (another curve close by)";
        }
        if (!ok) {
            p->pub.rejected++;
            /* where Newton's method on the shot fails away from the birth, the shot is too
             * nonlinear or too noisy in (omega, a): the same step in the link angles */
            if (iters == NEWTON_MAX && p->pub.steps > 0 && to_angles(p) == 0) {
                p->s.stay = p->s.backoff;
                p->s.backoff = p->s.backoff < 1024 ? 2 * p->s.backoff : p->s.backoff;
                return angle_step(p);
            }
            p->pub.ds *= 0.5;
            /* the first step from the birth no longer than the amplitude of the first point in
             * the link angles: begun there (a shorter one lands at amplitudes where the force
             * balance at fixed omega cannot tell the branch from the hanging chain, and the
             * path, handed over to the link angles, follows the hanging chain instead) */
            if (p->pub.steps == 0 && a0 == 0 && p->pub.ds < BIRTH_AMPLITUDE) return begin_in_angles(p);
            if (p->pub.ds < DS_MIN) {
                if (to_angles(p) == 0) {
                    p->pub.ds = DS_FIRST;
                    return angle_step(p);
                }
                return fail_at(p, GSL_EFAILED, w0, a0);
            }
            continue;
        }
        /* a point the shot resolves only to more than NOISE_UP: the step in the link angles
         * (measured at every point: the measure is itself round-off and jumps along a branch) */
        const double noise = shot_noise(c, w, a, &s);
        if (p->pub.steps > 0 && noise > NOISE_UP && to_angles(p) == 0) return angle_step(p);
        /* the first step from the birth to such a point at a rate within BIRTH_NEAR of the
         * birth's: begun in the link angles instead (the force balance at fixed omega is
         * singular there to within the shot's round-off, and its Newton's method, polishing the
         * shot's point on the hand-over, can fall onto the hanging chain, as above) */
        if (p->pub.steps == 0 && a0 == 0 && noise > NOISE_UP && fabs(w / w0 - 1) < BIRTH_NEAR)
            return begin_in_angles(p);
        const double m_start[3] = {m0[0], m0[1], m0[2]}, lo = p->pub.omega_lo, hi = p->pub.omega_hi;
        const double noise_start = p->s.noise;
        keep_start(p, m0, w0, a0, ds);
        swap(&p->s.theta, &p->s.theta_trial);
        swap(&p->s.embed, &p->s.embed_trial);
        set_point(p, w, a, &s, noise);
        p->pub.t_omega = t_w;
        p->pub.t_tip = t_a;
        p->s.raw_sign = raw;
        if (t_w != 0) p->s.rate_sign = sign_of(t_w);
        p->pub.arclength += ds;
        p->pub.steps++;
        const int status = find_events(p, raw != p->s.last.raw_sign);
        if (status != GSL_EFAILED) {
            if (iters <= NEWTON_EASY && turn < TURN_MAX / 2 && dtheta < DTHETA_MAX / 2)
                p->pub.ds = fmin(1.5 * ds, DS_MAX);
            return status;
        }
        /* an event the step passed could not be located (the step went across a part of the
         * curve it does not resolve: the header comment): back to the step's start, half the
         * step */
        swap(&p->s.theta, &p->s.theta_trial);
        swap(&p->s.embed, &p->s.embed_trial);
        for (int i = 0; i < 3; i++) p->s.metric[i] = m_start[i];
        p->pub.omega = w0;
        p->pub.tip_r = a0;
        p->s.noise = noise_start;
        p->pub.omega_lo = lo, p->pub.omega_hi = hi;
        p->pub.t_omega = p->s.last.t_w;
        p->pub.t_tip = p->s.last.t_a;
        p->s.raw_sign = p->s.last.raw_sign;
        p->s.rate_sign = p->s.last_rate_sign;
        p->s.why = "an event between two points could not be located";
        step_undone(p, ds);
        if (p->pub.ds < DS_MIN) return fail_at(p, GSL_EFAILED, w0, a0);
    }
}

/* whirl_nlink_path_step, its failures not yet led by the mode */
static int path_step(nlink_path *p)
{
    p->pub.n_events = 0;
    if (p->pub.ended)
        return whirl_fail(GSL_EDOM, "the branch ended on the hanging chain at omega=%.17g",
                          p->pub.omega);
    if (whirl_stop_requested()) return stopped(p);
    /* the formulation of this step: the link angles where the shot's round-off is felt, with
     * a hysteresis (each switch polishes the point on the other formulation) */
    if (!p->pub.angles && p->s.noise > NOISE_UP) to_angles(p);
    else if (p->pub.angles && p->s.stay > 0) p->s.stay--;
    else if (p->pub.angles && p->s.noise < NOISE_DOWN) to_shot(p);
    return p->pub.angles ? angle_step(p) : shot_step(p);
}

int whirl_nlink_path_step(whirl_nlink_path *path)
{
    nlink_path *p = path_of(path);
    return name_mode(p, path_step(p));
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

#define STEPS_MIN 100000   /* accepted steps of one path: at least, */
#define STEPS_PER_LINK 200 /* and per link of the chain (a middle mode folds about once per 25
                            * steps, and the number of its folds below a given multiple of its
                            * birth grows with N) */
#define PROGRESS_STEPS 256 /* steps between two reports of the progress */

/* The bound on the accepted steps of a path on the chain c. */
static long steps_max(const whirl_chain *c)
{
    const double per_link = (double)STEPS_PER_LINK * (double)c->n;
    return per_link > STEPS_MIN ? (per_link < 1e15 ? (long)per_link : (long)1e15) : STEPS_MIN;
}

/* The shape of the branch at omega between its birth and the first point of a path begun in the
 * link angles (birth_gap), into info and, where r is not NULL, r, z, tension. */
static int gap_shape(nlink_path *p, double omega, whirl_shape_info *info, double *r,
                     double *z, double *tension)
{
    const size_t n = p->pub.chain->n;
    double *th = arr_cross_theta(p);
    if (birth_gap(p, omega, th)) return GSL_EFAILED;
    if (r == NULL) r = scr_nodes(p), z = r + n + 1, tension = z + n + 1;
    return shape_info(p, 1, omega, tip_of(p->pub.chain, omega, th), th, info, r, z, tension);
}

/* Follows the path until its rate first exceeds omega_max, it returns to the hanging chain, or
 * visit returns non-zero (WHIRL_VISIT_STOP: success). visit gets every crossing of the rates
 * omega[0..n-1] (j its index, info filled) and every event (j = SIZE_MAX, event set); the link
 * angles of the shape visited are in arr_cross_theta(p) (a crossing) or arr_event_theta(p) (an event). */
static int follow_path(nlink_path *p, double omega_max, size_t n, const double *omega,
                       whirl_nlink_visit_fn visit, void *ctx,
                       const whirl_nlink_follow_options *opt)
{
    const size_t links = p->pub.chain->n;
    double *r = scr_nodes(p), *z = r + links + 1, *t = z + links + 1;
    long folds = 0;
    if (opt && opt->steps_max < 0)
        return whirl_fail(GSL_EINVAL, "the bound on the continuation steps must be > 0 (0: the "
                          "default), got %ld", opt->steps_max);
    const long bound = opt && opt->steps_max > 0 ? opt->steps_max : steps_max(p->pub.chain);
    int first = p->pub.steps == 0; /* the first step from the birth is still to come */
    while (p->pub.omega <= omega_max && !p->pub.ended) {
        if (p->pub.steps >= bound)
            return whirl_fail(GSL_EMAXITER, "mode %d: %ld continuation steps from the birth "
                              "at omega=%.17g (arclength %.4g, %ld folds) reached omega=%.17g "
                              "at most (now at omega=%.17g)", p->pub.mode, bound, p->pub.omega_birth,
                              p->pub.arclength, folds, p->pub.omega_hi, p->pub.omega);
        if (opt && opt->progress && p->pub.steps % PROGRESS_STEPS == 0) {
            const whirl_nlink_progress at = {p->pub.mode, p->pub.omega_birth, p->pub.steps, bound, folds,
                                             p->pub.omega, p->pub.omega_hi, p->pub.arclength};
            opt->progress(opt->progress_ctx, &at);
        }
        int status = whirl_nlink_path_step(&p->pub);
        if (status) return status;
        for (int e = 0; e < p->pub.n_events; e++) folds += p->pub.event[e].kind == WHIRL_EVENT_FOLD;
        /* crossings and events in the order of arclength: events first where they come
         * first is not needed by the callers, so crossings of a step follow its events */
        for (int e = 0; e < p->pub.n_events; e++) {
            whirl_shape_info info;
            const whirl_branch_event *ev = &p->pub.event[e];
            if ((status = shape_info(p, p->s.last.angles, ev->omega, ev->tip_r,
                                     arr_event_theta(p) + (size_t)e * links, &info, r, z, t)))
                return name_mode(p, status);
            if ((status = visit(ctx, SIZE_MAX, &info, ev)))
                return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
        }
        for (size_t j = 0; j < n; j++) {
            double tip[WHIRL_PATH_EVENTS_MAX + 1];
            int found = whirl_nlink_path_crossings(&p->pub, omega[j], WHIRL_PATH_EVENTS_MAX + 1, tip);
            if (found < 0) return -found;
            if (found == 0 && first && omega[j] > p->pub.omega_birth * (1 + GAP_MIN) &&
                omega[j] < p->pub.omega) {
                /* a rate between the birth and the first point, which the step's crossings do
                 * not resolve (a path begun in the link angles): gap_shape, or left out as not
                 * resolved where that does not converge */
                whirl_shape_info info;
                if (gap_shape(p, omega[j], &info, r, z, t) != GSL_SUCCESS) continue;
                p->pub.cross_angles[0] = 1; /* the visit's link angles are in cross_theta */
                if ((status = visit(ctx, j, &info, NULL)))
                    return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
            }
            for (int k = 0; k < found; k++) {
                whirl_shape_info info;
                const double *th = arr_cross_theta(p) + (size_t)k * links;
                if ((status = shape_info(p, p->pub.cross_angles[k], omega[j], tip[k], th, &info, r,
                                         z, t)))
                    return name_mode(p, status);
                if (k > 0) {
                    for (size_t i = 0; i < links; i++) arr_cross_theta(p)[i] = th[i];
                    p->pub.cross_angles[0] = p->pub.cross_angles[k];
                }
                if ((status = visit(ctx, j, &info, NULL)))
                    return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
            }
        }
        first = 0;
    }
    return GSL_SUCCESS;
}

int whirl_nlink_follow(const whirl_chain *c, int mode, double omega_max, size_t n,
                       const double *omega, whirl_nlink_visit_fn visit, void *ctx)
{
    return whirl_nlink_follow_opt(c, mode, omega_max, n, omega, visit, ctx, NULL);
}

int whirl_nlink_follow_opt(const whirl_chain *c, int mode, double omega_max, size_t n,
                           const double *omega, whirl_nlink_visit_fn visit, void *ctx,
                           const whirl_nlink_follow_options *opt)
{
    nlink_path *p = path_alloc(c);
    if (p == NULL) return whirl_last_error()[0] ? GSL_ENOMEM : GSL_EINVAL;
    int status = whirl_nlink_path_birth(&p->pub, mode);
    if (!status) status = follow_path(p, omega_max, n, omega, visit, ctx, opt);
    path_free(p);
    return status;
}

/* The first crossing of each rate; with nodes, those of the first crossing of rate j in row j
 * (c->n + 1 each). */
typedef struct first_ctx {
    whirl_shape_info *info;
    int *exists;
    size_t n, left;
    nlink_path *p;
    double *r, *z, *tension; /* NULL: not wanted */
} first_ctx;

static int first_visit(void *ctx, size_t j, const whirl_shape_info *info,
                       const whirl_branch_event *event)
{
    first_ctx *f = ctx;
    if (event != NULL || f->exists[j]) return 0;
    f->exists[j] = 1;
    f->info[j] = *info;
    if (f->r) {
        /* the visited crossing's nodes, from its link angles (the first k of the step is
         * copied to the front of cross_theta) */
        nlink_path *p = f->p;
        const size_t n = p->pub.chain->n;
        double *r = f->r + j * (n + 1), *z = f->z + j * (n + 1), *t = f->tension + j * (n + 1);
        int status;
        if (p->pub.cross_angles[0]) {
            whirl_nlink_balance_nodes(p->pub.chain, info->omega, arr_cross_theta(p), r, z, t);
            if (r[n] < 0)
                for (size_t i = 0; i <= n; i++) r[i] = -r[i];
            status = whirl_steady_check_samples(info->omega, n + 1, r, z, t);
        } else {
            status = whirl_nlink_positions(p->pub.chain, info->omega, info->tip_r, r, z, t);
        }
        if (status) return status;
    }
    return --f->left == 0 ? WHIRL_VISIT_STOP : 0;
}

/* The branch of mode at the rates omega[]: a path from the birth up to the largest of them (and
 * at least to twice the birth rate, where a branch that first turns to lower rates is seen). */
static int branch_path(nlink_path *p, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists, double *r, double *z, double *t,
                       const whirl_nlink_follow_options *opt)
{
    for (size_t j = 0; j < n; j++) {
        int status = whirl_steady_check_args(omega[j], mode, INT_MAX);
        if (status != GSL_SUCCESS) return status;
        exists[j] = 0;
    }
    if ((size_t)mode > p->pub.chain->n)
        return whirl_fail(GSL_EDOM, "mode %d does not exist: a chain of %zu links has modes "
                          "1..%zu", mode, p->pub.chain->n, p->pub.chain->n);
    int status = whirl_nlink_path_birth(&p->pub, mode);
    if (status) return status;
    double top = 2 * p->pub.omega_birth;
    for (size_t j = 0; j < n; j++) top = fmax(top, omega[j]);
    first_ctx f = {info, exists, n, n, p, r, z, t};
    if (n == 0) return GSL_SUCCESS;
    status = follow_path(p, top, n, omega, first_visit, &f, opt);
    if (status == GSL_EFAILED || status == GSL_EMAXITER) {
        /* a failure above every rate still missing, while looking for a turn of a branch
         * back below its birth: those rates are below the branch as far as it was followed */
        int below = 1;
        for (size_t j = 0; j < n; j++)
            if (!exists[j] && omega[j] >= p->pub.omega_lo) below = 0;
        if (below) status = GSL_SUCCESS;
    }
    return status;
}

int whirl_nlink_branch_nodes(const whirl_chain *c, int mode, size_t n, const double *omega,
                             whirl_shape_info *info, int *exists, double *r, double *z,
                             double *tension)
{
    if ((r == NULL) != (z == NULL) || (r == NULL) != (tension == NULL))
        return whirl_fail(GSL_EINVAL, "the nodes need all of r, z and tension, or none");
    nlink_path *p = path_alloc(c);
    if (p == NULL) return whirl_last_error()[0] ? GSL_ENOMEM : GSL_EINVAL;
    int status = branch_path(p, mode, n, omega, info, exists, r, z, tension, NULL);
    path_free(p);
    return status;
}

int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists)
{
    return whirl_nlink_branch_nodes(c, mode, n, omega, info, exists, NULL, NULL, NULL);
}

int whirl_nlink_solve_nodes(const whirl_chain *c, double omega, int mode,
                            whirl_shape_info *info, double *r, double *z, double *tension)
{
    return whirl_nlink_solve_nodes_opt(c, omega, mode, info, r, z, tension, NULL);
}

int whirl_nlink_solve_nodes_opt(const whirl_chain *c, double omega, int mode,
                                whirl_shape_info *info, double *r, double *z, double *tension,
                                const whirl_nlink_follow_options *opt)
{
    nlink_path *p = path_alloc(c);
    if (p == NULL) return whirl_last_error()[0] ? GSL_ENOMEM : GSL_EINVAL;
    int exists = 0;
    int status = branch_path(p, mode, 1, &omega, info, &exists, r, z, tension, opt);
    if (status == GSL_SUCCESS && !exists) {
        if (p->pub.ended)
            status = whirl_fail(GSL_EDOM, "mode %d does not exist at omega=%.17g: its branch, "
                                "born at omega_%d=%.17g, returns to the hanging chain at "
                                "omega=%.17g without reaching it", mode, omega, mode,
                                p->pub.omega_birth, p->pub.omega);
        else if (p->pub.omega_lo >= p->pub.omega_birth && omega > p->pub.omega_birth * (1 + GAP_MIN))
            /* above the birth but below the first point of a branch begun in the link angles
             * (birth_angles), where birth_gap does not converge: the mode exists there, it is
             * not resolved */
            status = whirl_fail(GSL_EFAILED, "mode %d at omega=%.17g is not resolved: it lies "
                                "between the birth omega_%d=%.17g and the first point of the "
                                "branch, at omega=%.17g, where the tip shot cannot start it "
                                "(begun in the link angles at an amplitude of %g rad)", mode,
                                omega, mode, p->pub.omega_birth, p->pub.omega_lo, BIRTH_AMPLITUDE);
        else if (p->pub.omega_lo >= p->pub.omega_birth)
            status = whirl_steady_fail_missing(mode, omega, p->pub.omega_birth);
        else
            status = whirl_fail(GSL_EDOM, "mode %d does not exist at omega=%.17g: its branch, "
                                "born at omega_%d=%.17g, reaches down to omega=%.17g only",
                                mode, omega, mode, p->pub.omega_birth, p->pub.omega_lo);
    }
    path_free(p);
    return status;
}

int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, double tip_r_guess,
                      whirl_shape_info *info)
{
    (void)tip_r_guess;
    return whirl_nlink_solve_nodes(c, omega, mode, info, NULL, NULL, NULL);
}
