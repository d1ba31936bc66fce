/* Every planar relative equilibrium of the spun chain at one rate omega, with the branch each
 * lies on.
 *
 * N-link chain. Built up from the tip with tip radius a (src/nlink.c, src/nlink_path.c), the
 * shape is an equilibrium when the pivot lands on the axis: G(omega, a) = u_0 / |u| = 0, with
 * u_i = r_i / a, and G depends on a only through a^2. Every nontrivial equilibrium has a != 0
 * (a = 0 makes every r_i zero) and its mirror image has -a, so the equilibria are the roots of
 * G(omega, .) on 0 < a < L (L = sum l_i; for a >= L, r_0 >= a - L > 0).
 *
 * Completeness argument (three methods; the result lists their union and how they agree):
 * 1. Tip scan. Below the floor a_f = 1e-8 min_i V_i / |eta_i^0| (eta^0: the linear shot's
 *    horizontal loads per unit a, V_i the weight below link i) every tension differs from V_i
 *    by a factor 1 + O(1e-16): the shot is the linear one, G(omega, a) = G(omega, 0) to
 *    round-off, and G(omega, 0) != 0 unless omega is a critical rate (refused within 1e-10
 *    relative). So every root lies in [a_f, L). In x = ln(a / (L - a)) (logarithmic at both
 *    ends: high modes have tip radii down to 1e-18 of their largest radius, mode 1 at high rates
 *    a tip radius within ~1/(2 omega^4) of L) the interval [ln a_f - 9, 36] is cut into a grid,
 *    and each cell [x_l, x_r] with its midpoint x_m is accepted when (c) and either (a) or (b)
 *    hold:
 *      (a) G has one sign at the three points and min |G| > h max |G'| (h = x_r - x_l): G
 *          stays away from zero; or
 *      (b) G' has one strict sign at the three points and the cubic Hermite interpolant of the
 *          ends predicts G(x_m) to tau |G(x_r) - G(x_l)|: G is monotone on the cell, so it has
 *          at most one root, found by the sign change;
 *      (c) every link angle theta_i = atan(H_i / V_i) is resolved: it turns by at most 0.25 rad
 *          from each of the three points to the next, and the cubic Hermite interpolant of its
 *          tangent H_i / V_i (exact derivative) predicts theta_i(x_m) to tau rad;
 *    and otherwise halved, down to a width of 1e-14 (1 + |x|) (about 50 rounding units of x; a
 *    cell accepted there is counted as unresolved: a near-tangent root, i.e. omega within
 *    ~1e-28 of a fold). G' = dG/da da/dx is exact (forward differentiation of the recursion).
 *    The scan is repeated with a grid 4 times finer and tau 4 times smaller until two
 *    successive levels give the same count.
 *    Why (c): at high rates (|H_i| >> V_i) a link angle turns by nearly pi where H_i passes
 *    through zero, over a width ~ V_i / |dH_i/dx| that shrinks with the rate (1e-11 in x for 10
 *    links at omega = 40), and every link above it follows; G varies on that scale only
 *    there, so samples on either side show nothing of it (a and b passed on cells holding two
 *    roots 1e-7 apart in a: 10 links at omega = 30 lost 10 of 1084 roots to the pivot scan's
 *    count). G is a smooth function of a and the angles (r_0 = a - sum l_i sin theta_i), so a
 *    cell on which every angle is resolved, G included, holds what (a) and (b) say. Each H_i is
 *    a smooth function of the angles below link i, which is what the Hermite test on its
 *    tangent checks, from the tip up. Clusters of roots (a hundred on 7 links at omega = 21.1,
 *    some 1e-5 apart in a; over a thousand on 10 links at omega = 40, 1e-7 apart) are resolved
 *    this way.
 * 2. Pivot scan, an independent formulation: the top link's angle theta_1 in (0, pi/2) (every
 *    nontrivial equilibrium has theta_1 != 0, and theta_1 > 0 for one of the mirror pair) fixes
 *    the horizontal force at the pivot; going down the chain the force left below the tip,
 *    H_{N+1} / H_1, vanishes for an equilibrium (whirl_nlink_pivot_residual). Scanned the same
 *    way in y = ln(theta_1 / (pi/2 - theta_1)) from its own linear floor. Its roots must be those
 *    of method 1. Every root of either scan is polished by Newton's method on all link angles
 *    (below), started from its own shot's angles, and two are the same equilibrium when every
 *    link angle agrees to 1e-8 rad.
 * 3. Continuation (whirl_nlink_path): every branch born at a critical rate below
 *    follow_factor * omega is followed from its birth, and the curve through every root not on
 *    one of them is followed both ways, each up to follow_factor * omega, until it returns to
 *    the hanging chain (a birth: the root is on that branch) or closes; each crossing of omega is
 *    matched against the scans' roots (a crossing they did not find counts as missed and is
 *    added). A curve starts from its root's polished link angles, and each crossing is polished
 *    from the path's own link angles there: where roots crowd (tip radii 1e-7 apart on 10 links
 *    at omega = 40) a tip radius does not single out one root to the shot, and a start from it
 *    failed on the first step or could begin on a neighbour. The path rejects a step on which
 *    its orientation test reverses (src/nlink_path.c): that is what a step that lands on the
 *    neighbouring curve looks like, and such jumps had put mode 7's branch of 10 links onto an
 *    isolated curve near omega = 12.89. Curves that meet no birth are isolated: they appear as pairs at folds, and the
 *    lowest fold found is reported as where the curve is born.
 * Limits: (b) and (c) test at three points per cell, they do not prove (two roots closer
 * than a cell on which the Hermite cubics fit G and every angle to tau would be missed by a
 * scan; the other scan, whose parameter runs the other way along the chain, and method 3 are
 * the checks). Curves that first cross omega after rising above follow_factor * omega are
 * followed from their own roots, and a birth reached only above that limit is not seen (the
 * root is then called isolated). The path sees a jump to the next curve (its orientation
 * reverses), not one over two curves at once, nor onto a curve closer than its shortest
 * tested step (1e-6) tells apart: the parity of the crossings (odd on a branch born below
 * omega that does not return to the hanging chain, even on a curve that meets no birth) is the
 * check (tests/test_equilibria.c). Features narrower than the cell floor (a rounding limit of
 * the parameter) are counted as unresolved. Where roots crowd within round-off of each other
 * (10 links at omega = 60: tip radii 3e-15 apart) a double shot's link angles can be too far
 * off for Newton's method: such a root is bisected again in quadruple precision and polished
 * from that shot's angles (below, polish_root); one that does not polish even so (none on 10
 * links up to omega = 80, 4 of 1511 roots at 100) is counted as not polished and left out,
 * and the two scans' lists then differ (the result says by how many). Two roots of one scan
 * polished onto one equilibrium are counted (coincident; 0 expected). The cost is about
 * proportional to the number of equilibria, which at high rates grows about exponentially
 * with N (25 links: 1354 at omega = 30, 9672 at 35, about 75000 at 40): shot_budget bounds
 * each level and GSL_EMAXITER says when it is exceeded; method 3 costs thousands of steps per
 * root and can be left out (params.continuation = 0) to count. Duplicates among the scans'
 * roots are merged after sorting by tip radius (list_unique), not by a search per root.
 *
 * Continuous chain: Kolodner (1955, Comm. Pure Appl. Math. 8:395, "Heavy rotating string - a
 * nonlinear eigenvalue problem") proves exactly n nontrivial shapes for omega_n < omega <=
 * omega_{n+1}, mode j with j - 1 axis crossings. Method 2 solves each mode 1..n
 * (whirl_continuum_solve, bracketing by the crossing count); method 1 counts the sign changes
 * of r(pivot; a) on a grid in ln a from 1e-9 / (1 + omega^2) (where the shot is linear) to 1,
 * doubled until the count repeats, and checks that each solved shape lies in its own
 * sign-change bracket.
 *
 * References: Keller 1977 and Allgower & Georg 1990 (continuation, see nlink_path.c); Brent
 * 1973, "Algorithms for minimization without derivatives", ch. 4 (GSL roots/brent.c) for the
 * roots; Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17:238 (monotone cubic Hermite
 * interpolation) for the test (b). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/linalg.h"

#include "core/error.h"
#include "core/roots.h"
#include "steady/steady_internal.h"
#include "steady/tip_up.h"

#define SCAN_X_TOP 36.0      /* top of the scan: L - a = L e^-36 ~ 2e-16 L */
#define SCAN_BELOW_FLOOR 9.0 /* the scan starts e^-9 ~ 1e-4 below the linear floor */
#define FLOOR_NONLINEAR 1e-8 /* |H_i| / V_i at the floor */
#define SCAN_H_MIN 1e-14     /* narrowest cell (x: about 50 ulp of the tip radius) */
#define SCAN_DTHETA 0.25     /* largest turn of a link angle between two points [rad] */
#define SCAN_TAU 0.01        /* Hermite test of the first level */
#define SCAN_LEVELS_MAX 5
#define SCAN_DEPTH_MAX 64
#define CRITICAL_GAP 1e-10   /* omega refused this close (relative) to a critical rate */
#define MATCH_ANGLE 1e-8     /* two polished equilibria with every link angle this close [rad]
                              * are the same (their tip radii then within MATCH_ANGLE L) */
#define PATH_STEPS_MAX 3000 /* continuation steps of one direction of one curve */
#define BRENT_MAX 200
#define BISECT_QUAD_MAX 512 /* bisections in quadruple precision (from 1 to 1e-34: 113) */

whirl_equilibria_params whirl_equilibria_defaults(void)
{
    whirl_equilibria_params p = {1, 2.0, 20000000L, 1};
    return p;
}

void whirl_equilibria_free(whirl_equilibria *e)
{
    if (e == NULL) return;
    free(e->eq);
    free(e);
}

/* ---- the adaptive sign-change scan of a function of one variable ---- */

/* G and dG/dx at x; with s, sd not NULL, the tangents of the link angles H_i / V_i and their
 * derivatives with respect to x */
typedef int (*scan_fn)(void *ctx, double x, double *g, double *dg, double *s, double *sd);

typedef struct scan_point {
    double x, g, d;
    double *s, *sd; /* the link angles' tangents and their derivatives (n_slopes each) */
} scan_point;

typedef struct scan_problem {
    scan_fn f;
    void *ctx;
    size_t n_slopes; /* N */
    long budget;     /* residual evaluations of one level */
} scan_problem;

typedef struct bracket {
    double lo, hi; /* a sign change of the function between x = lo and x = hi */
} bracket;

typedef struct scan_out {
    bracket *br;       /* the root brackets */
    size_t n, cap;
    long evals;
    size_t unresolved;
} scan_out;

static int scan_eval(const scan_problem *pb, double x, scan_point *p, scan_out *o)
{
    if (++o->evals > pb->budget)
        return whirl_fail(GSL_EMAXITER, "the scan needs more than %ld residual evaluations",
                          pb->budget);
    if ((o->evals & 1023) == 0 && whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped after %ld residual evaluations",
                          o->evals);
    p->x = x;
    int status = pb->f(pb->ctx, x, &p->g, &p->d, p->s, p->sd);
    if (status) return status;
    int finite = isfinite(p->g) && isfinite(p->d);
    for (size_t i = 0; i < pb->n_slopes; i++) finite &= isfinite(p->s[i]) && isfinite(p->sd[i]);
    if (!finite)
        return whirl_fail(GSL_ERANGE, "the shot is not finite at x=%.17g: the radii of the "
                          "shape overflow (too many links for this rate)", x);
    return GSL_SUCCESS;
}

static int add_bracket(scan_out *o, double lo, double hi)
{
    if (o->n == o->cap) {
        bracket *more = realloc(o->br, (o->cap ? 2 * o->cap : 64) * sizeof *more);
        if (more == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the roots");
        o->br = more;
        o->cap = o->cap ? 2 * o->cap : 64;
    }
    o->br[o->n].lo = lo;
    o->br[o->n++].hi = hi;
    return GSL_SUCCESS;
}

static int sign_of(double g) { return signbit(g) ? -1 : 1; }

static int accept(scan_out *o, const scan_point *l, const scan_point *r)
{
    if (sign_of(l->g) != sign_of(r->g)) return add_bracket(o, l->x, r->x);
    return GSL_SUCCESS;
}

/* Whether the angles atan(s0) and atan(s1) differ by at most the angle whose tangent is tan_d
 * (< pi/2): with 1 + s0 s1 > 0 their difference lies in (-pi/2, pi/2) and its tangent is
 * (s1 - s0) / (1 + s0 s1) (tan is increasing there); otherwise it is pi/2 or more. No atan: the
 * scans make this comparison 3 N times per cell. False where either is NaN. */
static int within_angle(double s0, double s1, double tan_d)
{
    const double q = 1 + s0 * s1;
    return q > 0 && fabs(s1 - s0) <= tan_d * q;
}

/* Test (c) of the header comment: every link angle turns by at most SCAN_DTHETA from one point
 * to the next, and the cubic Hermite interpolant of its tangent predicts the midpoint's angle
 * to tau. */
static int slopes_resolved(const scan_point *l, const scan_point *m, const scan_point *r,
                           size_t n, double tau)
{
    const double h = r->x - l->x, tan_d = tan(SCAN_DTHETA), tan_tau = tan(tau);
    for (size_t i = 0; i < n; i++) {
        if (!within_angle(l->s[i], m->s[i], tan_d) || !within_angle(m->s[i], r->s[i], tan_d))
            return 0;
        const double fit = 0.5 * (l->s[i] + r->s[i]) + 0.125 * h * (l->sd[i] - r->sd[i]);
        if (!within_angle(fit, m->s[i], tan_tau)) return 0;
    }
    return 1;
}

/* One level: n0 equal cells on [x0, x1], refined as in the header comment (a), (b), (c), depth
 * first. pt[0..top] are the points still to visit, in decreasing x from pt[0] (the right end
 * of the grid cell) to pt[top] (the left end of the cell under test); pt[top + 1] is the
 * midpoint's slot. Halving exchanges the pointers only. */
static int scan_level(const scan_problem *pb, double x0, double x1, size_t n0, double tau,
                      scan_point **pt, scan_out *o)
{
    int status = scan_eval(pb, x0, pt[1], o);
    for (size_t i = 1; i <= n0 && !status; i++) {
        double xr = i == n0 ? x1 : x0 + (x1 - x0) * (double)i / (double)n0;
        /* the left end (pt[1]) and the right end (pt[0]) of grid cell i */
        if ((status = scan_eval(pb, xr, pt[0], o))) break;
        int top = 1;
        while (top >= 1 && !status) {
            scan_point *l = pt[top], *r = pt[top - 1], *m = pt[top + 1];
            double h = r->x - l->x;
            if ((status = scan_eval(pb, 0.5 * (l->x + r->x), m, o))) break;
            int same = sign_of(l->g) == sign_of(m->g) && sign_of(m->g) == sign_of(r->g);
            double gmin = fmin(fabs(l->g), fmin(fabs(m->g), fabs(r->g)));
            double dmax = fmax(fabs(l->d), fmax(fabs(m->d), fabs(r->d)));
            double hermite = 0.5 * (l->g + r->g) + 0.125 * h * (l->d - r->d);
            int monotone = l->d != 0 && sign_of(l->d) == sign_of(m->d) &&
                           sign_of(m->d) == sign_of(r->d) && m->d != 0 && r->d != 0 &&
                           fabs(m->g - hermite) <= tau * fabs(r->g - l->g);
            int away = same && gmin > h * dmax;
            int ok = (away || monotone) && slopes_resolved(l, m, r, pb->n_slopes, tau);
            int narrow = h <= SCAN_H_MIN * fmax(1, fabs(m->x)) || top + 2 >= SCAN_DEPTH_MAX;
            if (ok || narrow) {
                if (!ok) o->unresolved++;
                if (!(status = accept(o, l, m))) status = accept(o, m, r);
                top--; /* the cell's right end is the next cell's left end */
                continue;
            }
            /* [l, m] first, then [m, r] */
            pt[top] = m;
            pt[top + 1] = l;
            top++;
        }
        /* the right end becomes the next left end */
        scan_point *tmp = pt[1];
        pt[1] = pt[0];
        pt[0] = tmp;
    }
    return status;
}

static void scan_out_free(scan_out *o)
{
    free(o->br);
    memset(o, 0, sizeof *o);
}

/* Levels with 4^k n0 cells and tau / 4^k until two successive counts agree; the last level's
 * brackets in *o. */
static int scan_settled(const scan_problem *pb, double x0, double x1, size_t n0, scan_out *o,
                        int *levels)
{
    enum { SLOTS = SCAN_DEPTH_MAX + 2 };
    scan_point pool[SLOTS], *pt[SLOTS];
    size_t n = pb->n_slopes;
    double *store = malloc((2 * n * SLOTS + 1) * sizeof *store);
    if (store == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the scan");
    for (int k = 0; k < SLOTS; k++) {
        pool[k].s = store + 2 * n * (size_t)k;
        pool[k].sd = pool[k].s + n;
        pt[k] = &pool[k];
    }
    scan_out prev = {0};
    double tau = SCAN_TAU;
    int status = GSL_SUCCESS;
    size_t counts[SCAN_LEVELS_MAX] = {0};
    _Static_assert(SCAN_LEVELS_MAX == 5, "the message below lists five counts");
    for (int k = 0; k < SCAN_LEVELS_MAX; k++, n0 *= 4, tau /= 4) {
        scan_out cur = {0};
        status = scan_level(pb, x0, x1, n0, tau, pt, &cur);
        if (status) {
            scan_out_free(&cur);
            break;
        }
        *levels = k + 1;
        counts[k] = cur.n;
        if (k > 0 && cur.n == prev.n) {
            scan_out_free(&prev);
            free(store);
            *o = cur;
            return GSL_SUCCESS;
        }
        scan_out_free(&prev);
        prev = cur;
    }
    free(store);
    scan_out_free(&prev);
    if (status) return status;
    return whirl_fail(GSL_ETOL, "the root count did not settle in %d refinement levels (%zu, "
                      "%zu, %zu, %zu, %zu roots)", SCAN_LEVELS_MAX, counts[0], counts[1],
                      counts[2], counts[3], counts[4]);
}

typedef struct brent_ctx {
    scan_fn f;
    void *ctx;
} brent_ctx;

static int brent_value(double x, void *p, double *g)
{
    brent_ctx *b = p;
    double d;
    return b->f(b->ctx, x, g, &d, NULL, NULL);
}

/* The root in the bracket [lo, hi] to round-off. */
static int polish(scan_fn f, void *ctx, double lo, double hi, double *x)
{
    brent_ctx b = {f, ctx};
    const whirl_root_opts o = {1e-300, 2 * DBL_EPSILON, BRENT_MAX + 1, 0, 0, 0};
    whirl_root r;
    int status = whirl_root_brent(brent_value, &b, lo, hi, &o, &r);
    if (status == GSL_ENOMEM) return status;
    *x = r.root;
    if (status && status != WHIRL_EINTERRUPTED)
        status = whirl_fail(status, "a root in [%.17g, %.17g] was not polished", lo, hi);
    return status;
}

/* WHIRL_EINTERRUPTED once a stop is requested, at item i of n. */
static int check_stop(size_t i, size_t n)
{
    if (!whirl_stop_requested()) return GSL_SUCCESS;
    return whirl_fail(WHIRL_EINTERRUPTED, "stopped at root %zu of %zu", i + 1, n);
}

/* ---- N-link chain: the two scans ---- */

typedef struct nlink_scan {
    const whirl_chain *c;
    double omega, length; /* the rate; L = sum of the link lengths */
    double *slope, *slope_d; /* scratch of the tip shot (N each) */
} nlink_scan;

/* x = ln(a / (L - a)) */
static double tip_of_x(const nlink_scan *s, double x) { return s->length / (1 + exp(-x)); }

static int tip_fn(void *ctx, double x, double *g, double *dg, double *sl, double *sl_d)
{
    const nlink_scan *s = ctx;
    double e = exp(-x), a = s->length / (1 + e), da = s->length * e / ((1 + e) * (1 + e));
    double g_a;
    whirl_nlink_tip_shot(s->c, s->omega, a, g, &g_a, sl ? sl : s->slope, sl_d ? sl_d : s->slope_d);
    *dg = g_a * da;
    for (size_t i = 0; sl_d && i < s->c->n; i++) sl_d[i] *= da;
    return GSL_SUCCESS;
}

/* The link angles theta_i = atan(H_i / V_i) of the tip scan's own shot at x (the shot whose
 * residual changed sign there) into theta[0..N-1], as the start of Newton's method. Not those
 * of a second shot from the tip radius by the positions' recursion (whirl_nlink_positions):
 * where roots crowd, the two recursions' round-off moves the upper links as much as a change of
 * the tip radius to a neighbouring root would, and their angles differ by up to 0.11 rad (10
 * links at omega = 50: 6 roots with more than 1e-3 rad; 24 at omega = 60). Newton's method
 * reached the same equilibrium from both at every root of 5, 7, 10 and 25 links in the
 * README's tables, but only the scan's own angles belong to the sign change found. */
static int angles_of_scan(const nlink_scan *s, double x, double *theta)
{
    double g, dg;
    int status = tip_fn((void *)s, x, &g, &dg, NULL, NULL);
    for (size_t i = 0; i < s->c->n && !status; i++) theta[i] = atan(s->slope[i]);
    return status;
}

/* y = ln(theta_1 / (pi/2 - theta_1)) */
static double theta_of_y(double y) { return M_PI_2 / (1 + exp(-y)); }

static int pivot_fn(void *ctx, double y, double *g, double *dg, double *sl, double *sl_d)
{
    const nlink_scan *s = ctx;
    double e = exp(-y), th = M_PI_2 / (1 + e), dth = M_PI_2 * e / ((1 + e) * (1 + e));
    double d;
    int status = whirl_nlink_pivot_shot(s->c, s->omega, th, g, &d, NULL, NULL, sl, sl_d);
    *dg = d * dth;
    for (size_t i = 0; sl_d && i < s->c->n; i++) sl_d[i] *= dth;
    return status;
}

/* The linear floors: the largest |H_i| / V_i per unit tip radius (shot from the tip) and per
 * unit tan(theta_1) (shot from the pivot), for the linearised chain (T_i = V_i). */
static void linear_loads(const whirl_chain *c, double omega, double *per_tip, double *per_top)
{
    size_t n = c->n;
    double w2 = omega * omega, worst = 0;
    tip_up s = tip_up_start(c, w2, 1, 0, 1);
    for (size_t i = n; i >= 1; i--) {
        tip_up_link(&s, c, i, TIP_UP_LINEAR);
        worst = fmax(worst, fabs(s.eta) / s.v);
    }
    *per_tip = worst;
    /* from the pivot: H_i / V_i = tan(theta_1) V_1 eta_i / V_i, eta_1 = 1 */
    double v = s.v, v1 = v, x = 0, eta = 1;
    worst = 0;
    for (size_t i = 1; i <= n; i++) {
        worst = fmax(worst, v1 * fabs(eta) / v);
        x += c->length[i - 1] * eta / v;
        eta -= c->mass[i - 1] * w2 * x;
        v -= c->mass[i - 1] * c->gravity;
    }
    *per_top = worst;
}

/* ---- N-link chain: Newton's method on all link angles ----
 * The tip shot carries the round-off of the recursion up the chain, amplified as the radii
 * grow from the tip (by up to ~1e-8 relative in the tip radius for the high modes of a 7-link
 * chain at omega = 21.1), and the pivot shot its own: each root is polished by Newton's method
 * on the force balance of every link in the link angles (whirl_nlink_balance_polish,
 * src/nlink_balance.c: the horizontal balances differenced so that the Jacobian, the in-plane
 * stiffness of the chain, is tridiagonal; regular at a root that is not a fold), from the angles
 * of the shot: the polished shape balances every link to round-off whatever shot found it. */

typedef struct angle_ws {
    const whirl_chain *c;
    double omega;
    nlink_balance *bal;
    double *theta, *r, *z, *t; /* N, N+1, N+1, N+1 */
    double *start;             /* N: the start of a refined root's Newton's method */
    double worst; /* largest sine of a link's angle to the force it carries, polished shapes */
} angle_ws;

static void angle_ws_free(angle_ws *w)
{
    if (w == NULL) return;
    whirl_nlink_balance_free(w->bal);
    free(w->theta);
    free(w);
}

static angle_ws *angle_ws_alloc(const whirl_chain *c, double omega)
{
    size_t n = c->n;
    angle_ws *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->c = c;
    w->omega = omega;
    w->theta = malloc((2 * n + 3 * (n + 1)) * sizeof *w->theta);
    if (w->theta == NULL) goto fail;
    w->r = w->theta + n;
    w->z = w->r + n + 1;
    w->t = w->z + n + 1;
    w->start = w->t + n + 1;
    w->bal = whirl_nlink_balance_alloc(c);
    if (w->bal == NULL) goto fail;
    return w;
fail:
    angle_ws_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for Newton's method on %zu links", n);
    return NULL;
}

/* Polishes the equilibrium near the link angles w->theta (from a shot): the polished angles
 * back in w->theta (mirrored to a positive tip radius), its tip radius in *tip_r, the nodes in
 * w->r, w->z, w->t. GSL_EFAILED if it does not converge or a link ends up horizontal or
 * compressed (a rod's equilibrium, not a chain's). */
static int angle_polish(angle_ws *w, double *tip_r)
{
    const whirl_chain *c = w->c;
    size_t n = c->n;
    int status = whirl_nlink_balance_polish(w->bal, w->omega, w->theta);
    if (status) {
        whirl_error_record why;
        whirl_error_save(&why);
        return whirl_fail(GSL_EFAILED, "tip radius " WHIRL_Q_LENGTH "%g: %s", *tip_r, why.text);
    }
    double worst = whirl_nlink_balance_nodes(c, w->omega, w->theta, w->r, w->z, w->t);
    w->worst = fmax(w->worst, worst);
    *tip_r = fabs(w->r[n]);
    if (w->r[n] < 0) {
        for (size_t i = 0; i <= n; i++) w->r[i] = -w->r[i];
        for (size_t i = 0; i < n; i++) w->theta[i] = -w->theta[i];
    }
    return GSL_SUCCESS;
}

/* ---- N-link chain: a root crowded within round-off, refined in quadruple precision ----
 * Where roots crowd (10 links at omega = 60: three tip radii within 3e-15 of each other, and at
 * the middle one the top link turns by a radian over 3.6e-18 in tip radius, less than the spacing
 * of doubles there, 6.9e-18) no double tip radius is close enough to the root for the shot's upper
 * link angles to be those of the equilibrium (the top link's off by 1.4 rad), and Newton's
 * method from them does not converge; long double (64 bits) leaves it 2e-3 rad off. The root is
 * then bisected again in quadruple precision (whirl_nlink_tip_shot_quad, _pivot_shot_quad) inside
 * its scan's bracket, down to adjacent quadruple numbers, and Newton's method (in double) starts
 * from the link angles of the shot there. The polished shape is kept only if every link angle
 * stays within MATCH_ANGLE of that start (Newton's method refined the root the shot found, it did
 * not go elsewhere) and, like every root, it must not be another root's equilibrium
 * (eq_list.coincident). The tip shot is bisected in the tip radius a, the pivot shot in
 * tan(theta_1), between the values of the double scan's bracket ends. */

typedef nlink_quad (*quad_fn)(const nlink_scan *s, nlink_quad p, double *theta);

static nlink_quad tip_quad(const nlink_scan *s, nlink_quad a, double *theta)
{
    return whirl_nlink_tip_shot_quad(s->c, s->omega, a, theta);
}

static nlink_quad pivot_quad(const nlink_scan *s, nlink_quad tan_1, double *theta)
{
    return whirl_nlink_pivot_shot_quad(s->c, s->omega, tan_1, theta);
}

/* The root of f between p = lo and hi, bisected in quadruple precision down to adjacent
 * numbers; the link angles of the shot at the end with the smaller residual into theta.
 * GSL_EFAILED if f has one sign at both ends. */
static int bisect_quad(const nlink_scan *s, quad_fn f, double lo, double hi, double *theta)
{
    nlink_quad a = lo, b = hi, fa = f(s, a, NULL), fb = f(s, b, NULL);
    if ((fa < 0) == (fb < 0))
        return whirl_fail(GSL_EFAILED, "no sign change over [%.17g, %.17g] in quadruple "
                          "precision", lo, hi);
    for (int it = 0; it < BISECT_QUAD_MAX; it++) {
        nlink_quad m = a + (b - a) / 2;
        if (!((m > a && m < b) || (m < a && m > b))) break;
        nlink_quad fm = f(s, m, NULL);
        if ((fm < 0) == (fa < 0)) a = m, fa = fm;
        else b = m, fb = fm;
    }
    f(s, (fa < 0 ? -fa : fa) <= (fb < 0 ? -fb : fb) ? a : b, theta);
    return GSL_SUCCESS;
}

/* Polishes the root of a scan between the parameters lo and hi of f from its double shot's link
 * angles (in aw->theta): Newton's method from them, and where it does not converge, from the
 * root refined in quadruple precision (above; counted in *refined). The tip radius in *a, as
 * angle_polish. */
static int polish_root(angle_ws *aw, const nlink_scan *s, quad_fn f, double lo, double hi,
                       double *a, size_t *refined)
{
    int status = angle_polish(aw, a);
    if (status != GSL_EFAILED) return status;
    size_t n = s->c->n;
    if ((status = bisect_quad(s, f, lo, hi, aw->start))) return status;
    memcpy(aw->theta, aw->start, n * sizeof *aw->theta);
    if ((status = angle_polish(aw, a))) return status;
    /* angle_polish mirrors the shape to a positive tip radius */
    double same = 0, mirror = 0;
    for (size_t i = 0; i < n; i++) {
        same = fmax(same, fabs(aw->theta[i] - aw->start[i]));
        mirror = fmax(mirror, fabs(aw->theta[i] + aw->start[i]));
    }
    if (!(fmin(same, mirror) <= MATCH_ANGLE))
        return whirl_fail(GSL_EFAILED, "tip radius " WHIRL_Q_LENGTH "%g: Newton's method moved a "
                          "link angle by %g rad from the quadruple precision shot's", *a,
                          fmin(same, mirror));
    ++*refined;
    return GSL_SUCCESS;
}

/* ---- the list of equilibria ---- */

typedef struct eq_list {
    whirl_equilibrium *eq;
    size_t n, cap;
    int *source;   /* bit 1: tip scan, 2: pivot scan or solve, 4: continuation */
    size_t links;  /* N (0: no angles kept) */
    double window; /* 2 MATCH_ANGLE L: tip radii further apart are different equilibria */
    double *theta; /* the polished link angles of entry i at theta[i N ..] */
    size_t coincident; /* roots of one scan merged into an equilibrium of the same scan */
} eq_list;

static int list_add(eq_list *l, double tip_r, const double *theta, int source)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        whirl_equilibrium *e = realloc(l->eq, cap * sizeof *e);
        if (e) l->eq = e;
        int *s = e ? realloc(l->source, cap * sizeof *s) : NULL;
        if (s) l->source = s;
        double *t = s && l->links ? realloc(l->theta, cap * l->links * sizeof *t) : NULL;
        if (t) l->theta = t;
        if (s == NULL || (l->links && t == NULL))
            return whirl_fail(GSL_ENOMEM, "out of memory for %zu equilibria", cap);
        l->cap = cap;
    }
    whirl_equilibrium *e = &l->eq[l->n];
    memset(e, 0, sizeof *e);
    e->info.tip_r = tip_r;
    e->branch = -1;
    e->born_at = GSL_NAN;
    e->eig_growth = GSL_NAN;
    e->index = -1;
    if (l->links) memcpy(l->theta + l->n * l->links, theta, l->links * sizeof *theta);
    l->source[l->n++] = source;
    return GSL_SUCCESS;
}

/* The entry that is the same equilibrium as (tip_r, theta), or SIZE_MAX: every link angle
 * within MATCH_ANGLE (the tip radius of a high mode is too sensitive to compare alone). */
static size_t list_find(const eq_list *l, double tip_r, const double *theta)
{
    for (size_t i = 0; i < l->n; i++) {
        if (fabs(l->eq[i].info.tip_r - tip_r) > l->window) continue;
        double d = 0;
        for (size_t k = 0; k < l->links; k++)
            d = fmax(d, fabs(l->theta[i * l->links + k] - theta[k]));
        if (d <= MATCH_ANGLE) return i;
    }
    return SIZE_MAX;
}

/* Adds (tip_r, theta) from a source, or marks the entry that has it. Returns the index
 * (SIZE_MAX on failure, status in *status). */
static size_t list_merge(eq_list *l, double tip_r, const double *theta, int source, int *status)
{
    size_t i = list_find(l, tip_r, theta);
    if (i != SIZE_MAX) {
        l->source[i] |= source;
        return i;
    }
    if ((*status = list_add(l, tip_r, theta, source))) return SIZE_MAX;
    return l->n - 1;
}

typedef struct tip_index {
    double tip_r;
    size_t i;
} tip_index;

static int cmp_tip_index(const void *x, const void *y)
{
    double a = ((const tip_index *)x)->tip_r, b = ((const tip_index *)y)->tip_r;
    return (a > b) - (a < b);
}

/* Merges the entries that are the same equilibrium (as list_find), in increasing tip radius:
 * O(n log n + n w) for w entries within l->window of each other, where list_merge for each
 * would be O(n^2) (tens of thousands of roots on long chains at high rates). */
static int list_unique(eq_list *l)
{
    size_t n = l->n, kept = 0, links = l->links;
    tip_index *order = malloc(n * sizeof *order);
    whirl_equilibrium *eq = malloc(n * sizeof *eq);
    int *source = malloc(n * sizeof *source);
    double *theta = malloc(n * links * sizeof *theta);
    if (order == NULL || eq == NULL || source == NULL || (n * links > 0 && theta == NULL)) {
        free(order), free(eq), free(source), free(theta);
        return whirl_fail(GSL_ENOMEM, "out of memory for %zu equilibria", n);
    }
    for (size_t i = 0; i < n; i++) order[i] = (tip_index){l->eq[i].info.tip_r, i};
    qsort(order, n, sizeof *order, cmp_tip_index);
    for (size_t k = 0; k < n; k++) {
        size_t i = order[k].i, same = SIZE_MAX;
        double tip = l->eq[i].info.tip_r;
        const double *th = l->theta + i * links;
        for (size_t j = kept; j-- > 0 && eq[j].info.tip_r >= tip - l->window;) {
            double d = 0;
            for (size_t q = 0; q < links; q++) d = fmax(d, fabs(theta[j * links + q] - th[q]));
            if (d <= MATCH_ANGLE) {
                same = j;
                break;
            }
        }
        if (same != SIZE_MAX) {
            l->coincident += (source[same] & l->source[i]) != 0;
            source[same] |= l->source[i];
            continue;
        }
        eq[kept] = l->eq[i];
        source[kept] = l->source[i];
        memcpy(theta + kept * links, th, links * sizeof *theta);
        kept++;
    }
    free(order);
    free(l->eq), free(l->source), free(l->theta);
    l->eq = eq;
    l->source = source;
    l->theta = theta;
    l->n = l->cap = kept;
    if (kept == 0) l->cap = n; /* the arrays hold n */
    return GSL_SUCCESS;
}

/* ---- N-link chain: continuation of the curves through the roots ---- */

typedef struct curve {
    int branch;        /* birth reached (k), 0 none */
    double fold_lo;    /* lowest fold found */
    size_t *members;   /* entries crossed */
    size_t n_members, cap;
    int failed;        /* a direction ended in a failure */
} curve;

static int curve_member(curve *cv, size_t i)
{
    for (size_t j = 0; j < cv->n_members; j++)
        if (cv->members[j] == i) return GSL_SUCCESS;
    if (cv->n_members == cv->cap) {
        size_t cap = cv->cap ? 2 * cv->cap : 16;
        size_t *m = realloc(cv->members, cap * sizeof *m);
        if (m == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        cv->members = m;
        cv->cap = cap;
    }
    cv->members[cv->n_members++] = i;
    return GSL_SUCCESS;
}

/* The birth whose critical rate is nearest omega (a return to the hanging chain). */
static int nearest_birth(const double *crit, size_t n, double omega)
{
    size_t best = 0;
    for (size_t k = 1; k < n; k++)
        if (fabs(crit[k] - omega) < fabs(crit[best] - omega)) best = k;
    return (int)best + 1;
}

/* Follows the path p (started) until its rate exceeds omega_max, it returns to the hanging
 * chain, it closes on the entry `start` (SIZE_MAX: no closure test) or it fails; every
 * crossing of omega goes into the list (source 4) and the curve. Returns 1 if it closed, 0
 * otherwise, or minus a status (an interrupt or no memory; a failed continuation only marks
 * the curve). */
static int follow_curve(whirl_nlink_path *p, double omega, double omega_max, const double *crit,
                        eq_list *l, curve *cv, size_t start, angle_ws *aw, whirl_equilibria *res)
{
    int status;
    while (p->omega <= omega_max && !p->ended) {
        if (p->steps >= PATH_STEPS_MAX) {
            /* the step budget: as a failure (below) */
            if (p->omega > omega) res->cut_short++;
            else cv->failed = 1;
            return 0;
        }
        status = whirl_nlink_path_step(p);
        res->path_steps++;
        if (status == WHIRL_EINTERRUPTED || status == GSL_ENOMEM) return -status;
        if (status) {
            /* above omega every crossing of omega before the failure has been seen: the curve
             * is cut short there (a birth lies beyond only if the curve comes back below
             * omega, through another root, followed on its own) */
            if (p->omega > omega) res->cut_short++;
            else cv->failed = 1;
            return 0;
        }
        for (int e = 0; e < p->n_events; e++) {
            const whirl_branch_event *ev = &p->event[e];
            if (ev->kind == WHIRL_EVENT_FOLD && ev->omega < cv->fold_lo) cv->fold_lo = ev->omega;
            if (ev->kind == WHIRL_EVENT_RETURN)
                cv->branch = nearest_birth(crit, p->chain->n, ev->omega);
        }
        double tip[WHIRL_PATH_EVENTS_MAX + 1];
        int found = whirl_nlink_path_crossings(p, omega, WHIRL_PATH_EVENTS_MAX + 1, tip);
        if (found < 0) {
            if (-found == WHIRL_EINTERRUPTED) return found;
            cv->failed = 1;
            return 0;
        }
        for (int k = 0; k < found; k++) {
            double a = fabs(tip[k]);
            size_t before = l->n;
            /* from the crossing's own link angles (the tip radius alone does not fix the
             * shape where roots crowd) */
            memcpy(aw->theta, whirl_nlink_path_cross_theta(p) + (size_t)k * l->links, l->links * sizeof *aw->theta);
            if ((status = angle_polish(aw, &a))) {
                if (status == WHIRL_EINTERRUPTED || status == GSL_ENOMEM) return -status;
                cv->failed = 1;
                return 0;
            }
            size_t i = list_merge(l, a, aw->theta, 4, &status);
            if (i == SIZE_MAX) return -status;
            res->crossings++;
            if (l->n > before) res->missed++;
            if ((status = curve_member(cv, i))) return -status;
            if (i == start && p->steps > 1) return 1;
        }
    }
    return 0;
}

static void label_curve(eq_list *l, const curve *cv, const double *crit)
{
    for (size_t j = 0; j < cv->n_members; j++) {
        whirl_equilibrium *e = &l->eq[cv->members[j]];
        if (e->branch > 0) continue;
        if (cv->branch > 0) {
            e->branch = cv->branch;
            e->born_at = crit[cv->branch - 1];
        } else if (!cv->failed) {
            e->branch = 0;
            e->born_at = isfinite(cv->fold_lo) ? cv->fold_lo : GSL_NAN;
        }
    }
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* The curves whose crossings of omega have the wrong parity. A branch born below omega that
 * does not return to the hanging chain starts below omega and ends above it: it crosses omega
 * an odd number of times; one that returns (returned[k - 1]) an even number. A curve that meets
 * no birth rises above omega at both ends: an even number. Its equilibria share born_at, the
 * same double (label_curve). */
static int parity_check(const eq_list *l, size_t n, const double *crit, double omega,
                        const int *returned, whirl_equilibria *res)
{
    double *fold = malloc((l->n + 1) * sizeof *fold);
    if (fold == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu folds", l->n);
    for (size_t k = 1; k <= n && crit[k - 1] < omega; k++) {
        size_t count = 0;
        for (size_t i = 0; i < l->n; i++) count += l->eq[i].branch == (int)k;
        res->wrong_parity += (count % 2 == 0) != (returned[k - 1] != 0);
    }
    size_t m = 0;
    for (size_t i = 0; i < l->n; i++)
        if (l->eq[i].branch == 0 && isfinite(l->eq[i].born_at)) fold[m++] = l->eq[i].born_at;
    qsort(fold, m, sizeof *fold, cmp_double);
    for (size_t i = 0, j; i < m; i = j) {
        for (j = i; j < m && fold[j] == fold[i]; j++) continue;
        res->wrong_parity += (j - i) % 2;
    }
    free(fold);
    return GSL_SUCCESS;
}

static int continue_all(const whirl_chain *c, double omega, double factor, const double *crit,
                        eq_list *l, angle_ws *aw, whirl_equilibria *res)
{
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    int *returned = calloc(c->n, sizeof *returned);
    if (p == NULL || returned == NULL) {
        whirl_nlink_path_free(p);
        free(returned);
        return whirl_fail(GSL_ENOMEM, "out of memory for the continuation");
    }
    double omega_max = factor * omega;
    int status = GSL_SUCCESS;
    curve cv = {0};
    /* every branch from its birth */
    for (size_t k = 1; k <= c->n && !status && crit[k - 1] <= omega_max; k++) {
        cv.branch = (int)k;
        cv.fold_lo = INFINITY;
        cv.n_members = 0;
        cv.failed = 0;
        if ((status = whirl_nlink_path_birth(p, (int)k))) break;
        int r = follow_curve(p, omega, omega_max, crit, l, &cv, SIZE_MAX, aw, res);
        if (r < 0) {
            status = -r;
            break;
        }
        returned[k - 1] = p->ended;
        cv.branch = (int)k; /* the birth it starts from, even if it returns at another */
        cv.failed = 0;      /* its crossings are on branch k whatever happened further on */
        label_curve(l, &cv, crit);
    }
    /* the curves through the roots no branch crossed: both ways */
    for (size_t i = 0; i < l->n && !status; i++) {
        if (l->eq[i].branch >= 0) continue;
        cv.branch = 0;
        cv.fold_lo = INFINITY;
        cv.n_members = 0;
        cv.failed = 0;
        if ((status = curve_member(&cv, i))) break;
        int closed = 0;
        for (int dir = -1; dir <= 1 && !closed && !status; dir += 2) {
            if (whirl_nlink_path_start_angles(p, omega, l->theta + i * l->links, dir)) {
                cv.failed = 1;
                continue;
            }
            int r = follow_curve(p, omega, omega_max, crit, l, &cv, i, aw, res);
            if (r < 0) status = -r;
            closed = r == 1;
        }
        if (!status) label_curve(l, &cv, crit);
    }
    if (!status) status = parity_check(l, c->n, crit, omega, returned, res);
    free(cv.members);
    free(returned);
    whirl_nlink_path_free(p);
    return status;
}

static int cmp_tip(const void *x, const void *y)
{
    double a = ((const whirl_equilibrium *)x)->info.tip_r;
    double b = ((const whirl_equilibrium *)y)->info.tip_r;
    return (a > b) - (a < b);
}

static int nlink_find(const whirl_chain *c, double omega, const whirl_equilibria_params *par,
                      angle_ws *aw, whirl_equilibria *res, eq_list *l)
{
    size_t n = c->n;
    double *crit = malloc(n * sizeof *crit);
    if (crit == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu critical rates", n);
    int status = whirl_nlink_critical(c, n, crit);
    for (size_t k = 0; k < n && !status; k++) {
        if (fabs(omega / crit[k] - 1) <= CRITICAL_GAP)
            status = whirl_fail(GSL_EDOM, "omega=" WHIRL_Q_RATE "%.17g is the critical rate of "
                                "mode %zu (omega_%zu=" WHIRL_Q_RATE "%.17g): its branch is born "
                                "there, not separated from the hanging chain", omega, k + 1, k + 1,
                                crit[k]);
        if (crit[k] < omega) res->born++;
    }
    nlink_scan s = {c, omega, 0, NULL, NULL};
    for (size_t i = 0; i < n; i++) s.length += c->length[i];
    if (!status && (s.slope = malloc(2 * n * sizeof *s.slope)) == NULL)
        status = whirl_fail(GSL_ENOMEM, "out of memory for %zu links", n);
    s.slope_d = s.slope + n;
    double per_tip, per_top;
    linear_loads(c, omega, &per_tip, &per_top);
    if (!status && !(isfinite(per_tip) && isfinite(per_top) && per_tip < 1e150 && per_top < 1e150))
        status = whirl_fail(GSL_ERANGE, "%zu links at omega=" WHIRL_Q_RATE "%g: the linear shot's "
                            "loads overflow (more than 1e150): too many links for this rate", n,
                            omega);
    scan_out tip = {0}, top = {0};
    size_t n0 = 256 + 16 * n;
    if (!status) {
        res->tip_floor = FLOOR_NONLINEAR / per_tip;
        double x0 = log(res->tip_floor / s.length) - SCAN_BELOW_FLOOR;
        scan_problem pb = {tip_fn, &s, n, par->shot_budget};
        status = scan_settled(&pb, x0, SCAN_X_TOP, n0, &tip, &res->tip_levels);
        res->tip_shots = tip.evals;
        res->tip_unresolved = tip.unresolved;
    }
    if (!status) {
        double y0 = log(FLOOR_NONLINEAR / per_top / M_PI_2) - SCAN_BELOW_FLOOR;
        scan_problem pb = {pivot_fn, &s, n, par->shot_budget};
        status = scan_settled(&pb, y0, SCAN_X_TOP, n0, &top, &res->check_levels);
        res->check_shots = top.evals;
    }
    /* the roots, polished */
    for (size_t i = 0; i < tip.n && !status; i++) {
        double x, a = 0;
        if ((status = check_stop(i, tip.n))) break;
        if (!(status = polish(tip_fn, &s, tip.br[i].lo, tip.br[i].hi, &x)))
            a = tip_of_x(&s, x), status = angles_of_scan(&s, x, aw->theta);
        if (!status)
            status = polish_root(aw, &s, tip_quad, tip_of_x(&s, tip.br[i].lo),
                                 tip_of_x(&s, tip.br[i].hi), &a, &res->refined);
        if (status == GSL_EFAILED || status == GSL_ESING) {
            res->unpolished++; /* reported; the other scan is the check */
            status = GSL_SUCCESS;
            continue;
        }
        if (!status) status = list_add(l, a, aw->theta, 1);
    }
    res->tip_roots = tip.n;
    for (size_t i = 0; i < top.n && !status; i++) {
        double y, g, a;
        if ((status = check_stop(i, top.n))) break;
        if (!(status = polish(pivot_fn, &s, top.br[i].lo, top.br[i].hi, &y)))
            status = whirl_nlink_pivot_shot(c, omega, theta_of_y(y), &g, NULL, &a, aw->theta,
                                            NULL, NULL);
        if (!status)
            status = polish_root(aw, &s, pivot_quad, tan(theta_of_y(top.br[i].lo)),
                                 tan(theta_of_y(top.br[i].hi)), &a, &res->refined);
        if (status == GSL_EFAILED || status == GSL_ESING) {
            res->unpolished++; /* reported; the other scan is the check */
            status = GSL_SUCCESS;
            continue;
        }
        if (!status) status = list_add(l, a, aw->theta, 2);
    }
    res->check_roots = top.n;
    scan_out_free(&tip);
    scan_out_free(&top);
    free(s.slope);
    if (!status) status = list_unique(l);
    res->coincident = l->coincident;
    for (size_t i = 0; i < l->n; i++) res->matched += (l->source[i] & 3) == 3;
    if (!status && par->continuation)
        status = continue_all(c, omega, par->follow_factor, crit, l, aw, res);
    free(crit);
    return status;
}

/* ---- continuous chain ---- */

static int continuum_find(double tip_mass, double omega, whirl_equilibria *res, eq_list *l)
{
    double crit[WHIRL_MODE_MAX + 1];
    int status = GSL_SUCCESS;
    int n = 0;
    for (int k = 1; k <= WHIRL_MODE_MAX + 1 && !status; k++) {
        if (k == WHIRL_MODE_MAX + 1) {
            status = whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g is above the birth of mode "
                                "%d, the most the continuum solver handles", omega,
                                WHIRL_MODE_MAX + 1);
            break;
        }
        if ((status = whirl_continuum_critical(k, tip_mass, &crit[k - 1]))) break;
        if (fabs(omega / crit[k - 1] - 1) <= CRITICAL_GAP)
            status = whirl_fail(GSL_EDOM, "omega=" WHIRL_Q_RATE "%.17g is the critical rate of "
                                "mode %d (omega_%d=" WHIRL_Q_RATE "%.17g): its branch is born "
                                "there, not separated from the hanging chain", omega, k, k,
                                crit[k - 1]);
        if (crit[k - 1] > omega) break;
        n = k;
    }
    res->born = n;
    /* method 2: Kolodner's shapes, one per mode */
    for (int k = 1; k <= n && !status; k++) {
        whirl_shape_info info;
        if ((status = whirl_continuum_solve(omega, k, tip_mass, 0, &info))) break;
        if ((status = list_add(l, info.tip_r, NULL, 2))) break;
        whirl_equilibrium *e = &l->eq[l->n - 1];
        e->info = info;
        e->branch = k;
        e->born_at = crit[k - 1];
        res->check_roots++;
    }
    /* method 1: sign changes of r(pivot) over ln a, doubled until the count repeats */
    double a_floor = 1e-9 / (1 + omega * omega), la = log(a_floor);
    size_t m = 32 + 8 * (size_t)n, prev_count = SIZE_MAX;
    double *a = NULL, *r = NULL;
    int *cr = NULL;
    res->tip_floor = a_floor;
    for (int level = 0; level < SCAN_LEVELS_MAX && !status; level++, m *= 2) {
        double *a2 = realloc(a, (m + 1) * sizeof *a), *r2 = NULL;
        if (a2) a = a2;
        if (a2) r2 = realloc(r, (m + 1) * sizeof *r);
        if (r2) r = r2;
        int *cr2 = r2 ? realloc(cr, (m + 1) * sizeof *cr) : NULL;
        if (cr2 == NULL) {
            status = whirl_fail(GSL_ENOMEM, "out of memory for %zu shots", m + 1);
            break;
        }
        cr = cr2;
        for (size_t i = 0; i <= m; i++) a[i] = i == m ? 1 : exp(la * (1 - (double)i / (double)m));
        if ((status = whirl_continuum_shots(omega, tip_mass, m + 1, a, r, cr))) break;
        res->tip_shots = (long)m + 1;
        res->tip_levels = level + 1;
        size_t count = 0, matched = 0;
        for (size_t i = 0; i < m; i++) {
            if (sign_of(r[i]) == sign_of(r[i + 1])) continue;
            count++;
            size_t inside = 0;
            for (size_t j = 0; j < l->n; j++)
                inside += l->eq[j].info.tip_r >= a[i] && l->eq[j].info.tip_r <= a[i + 1];
            matched += inside == 1;
        }
        if (count == prev_count) {
            res->tip_roots = count;
            res->matched = matched;
            break;
        }
        prev_count = count;
        if (level == SCAN_LEVELS_MAX - 1)
            status = whirl_fail(GSL_ETOL, "the continuum's root count did not settle in "
                                "%d levels", SCAN_LEVELS_MAX);
    }
    free(a);
    free(r);
    free(cr);
    return status;
}

int whirl_equilibria_search(const whirl_chain *c, double tip_mass, double omega,
                            const whirl_equilibria_params *params,
                            const whirl_equilibria_verdict *verdict, whirl_equilibria **out)
{
    *out = NULL;
    whirl_equilibria_params par = params ? *params : whirl_equilibria_defaults();
    if (!(par.follow_factor > 1 && isfinite(par.follow_factor) && par.shot_budget >= 1000))
        return whirl_fail(GSL_EINVAL, "equilibria: follow_factor must be > 1 and shot_budget "
                          ">= 1000");
    double omega_max = c ? WHIRL_EQUILIBRIA_OMEGA_MAX : WHIRL_EQUILIBRIA_CONTINUUM_OMEGA_MAX;
    if (!(isfinite(omega) && omega > 0 && omega <= omega_max))
        return whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g is out of range for %s: it must be "
                          "> 0 and at most omega=" WHIRL_Q_RATE "%g", omega,
                          c ? "the N-link chain" : "the continuum", omega_max);
    if (c != NULL && (c->n < 1 || c->n > WHIRL_EQUILIBRIA_LINKS_MAX))
        return whirl_fail(GSL_EINVAL, "a chain of 1..%d links for the equilibria, got %zu",
                          WHIRL_EQUILIBRIA_LINKS_MAX, c->n);
    whirl_equilibria *res = calloc(1, sizeof *res);
    if (res == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    res->omega = omega;
    res->n_links = c ? c->n : 0;
    eq_list l = {0};
    l.links = c ? c->n : 0;
    for (size_t i = 0; i < l.links; i++) l.window += 2 * MATCH_ANGLE * c->length[i];
    angle_ws *aw = c ? angle_ws_alloc(c, omega) : NULL;
    int status = c && aw == NULL ? whirl_last_status() : GSL_SUCCESS;
    if (!status)
        status = c ? nlink_find(c, omega, &par, aw, res, &l) : continuum_find(tip_mass, omega, res, &l);
    /* the shapes (polished once more, from their tip radii) and their linear verdicts */
    const int verdicts = c && par.stability && verdict != NULL;
    for (size_t i = 0; i < l.n && !status && c; i++) {
        whirl_equilibrium *e = &l.eq[i];
        if ((status = check_stop(i, l.n))) break;
        memcpy(aw->theta, l.theta + i * l.links, l.links * sizeof *aw->theta);
        if ((status = angle_polish(aw, &e->info.tip_r))) break;
        whirl_nlink_info_nodes(c, aw->r, aw->z, aw->t, omega, e->branch > 0 ? e->branch : 0,
                               &e->info);
        if ((status = whirl_steady_check_info(&e->info))) break;
        res->isolated += e->branch == 0;
        res->unidentified += e->branch < 0;
        if (verdicts)
            status = verdict->judge(verdict->ctx, aw->r, aw->z, &e->eig_growth, &e->index);
    }
    if (aw) res->balance = aw->worst;
    angle_ws_free(aw);
    free(l.source);
    free(l.theta);
    if (status) {
        free(l.eq);
        free(res);
        return status;
    }
    qsort(l.eq, l.n, sizeof *l.eq, cmp_tip);
    res->eq = l.eq;
    res->count = l.n;
    *out = res;
    return GSL_SUCCESS;
}
