/* The step tests of the N-link continuation (src/steady/nlink_path.c) that read a step's ends
 * only: the chord against the end tangents, the rate's cubic Hermite interpolant turning back,
 * and the sign changes of the nearest-zero eigenvalue's interpolant. */
#include <math.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"

/* Whether the rate turns back within a step whose ends' rates move the same way: two folds
 * inside, which the fold test (a change of sign between the ends) does not see. slope is the
 * chord's mean d ln omega / ds, r0 and r1 the end tangents' (oriented along the travel), slack
 * their round-off. The cubic Hermite interpolant of ln omega on the step, x in [0, 1] along it,
 * has the rate
 *     q(x) = 6 x (1 - x) slope + r0 (1 - 4 x + 3 x^2) + r1 (3 x^2 - 2 x)
 * (q(0) = r0, q(1) = r1, mean slope), and the step turns back where q falls below -slack inside:
 * certainly where slope itself has the other sign (the rate went back), and where the chord
 * is too short for ends that both move on at their rates (q(1/2) = 1.5 slope - (r0 + r1) / 4).
 * The interpolant errs by O(ds^4); where the curve's rate only dips towards zero, halving
 * resolves the dip (the pairs of folds this finds: docs/validation/continuation.md). */
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
const char *path_chord_test(size_t n, double w0, const double *th0, double w1, const double *th1,
                            const double *e0, double s0, const double *e1, double s1, double turn,
                            int rates)
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

/* The cubic Hermite interpolant p on [0, 1] of the values f0, f1 and the derivatives d0, d1 at
 * 0 and 1: its number of sign changes (the sign at 0, at the zeros of p' inside and at 1, in
 * order) as the return value; in *near, the least |p| at a zero of p' inside where p has the
 * sign of both ends, relative to the smaller of |f0| and |f1| (INFINITY where there is none). */
int path_hermite_crossings(double f0, double d0, double f1, double d1, double *near)
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
