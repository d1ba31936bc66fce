/* The adaptive sign-change scan of a function of one variable, the root in each bracket to
 * round-off (Brent), and the stop check of the equilibria search: the tests (a), (b), (c) and the
 * levels are described in equilibria.c's header comment. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/roots.h"
#include "steady/equilibria_internal.h"

#define SCAN_H_MIN 1e-14     /* narrowest cell (x: about 50 ulp of the tip radius) */
#define SCAN_DTHETA 0.25     /* largest turn of a link angle between two points [rad] */
#define SCAN_TAU 0.01        /* Hermite test of the first level */
#define SCAN_DEPTH_MAX 64
#define BRENT_MAX 200

/* ---- the adaptive sign-change scan of a function of one variable ---- */

typedef struct scan_point {
    double x, g, d;
    double *s, *sd; /* the link angles' tangents and their derivatives (n_slopes each) */
} scan_point;

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

int eq_sign_of(double g) { return signbit(g) ? -1 : 1; }

static int accept(scan_out *o, const scan_point *l, const scan_point *r)
{
    if (eq_sign_of(l->g) != eq_sign_of(r->g)) return add_bracket(o, l->x, r->x);
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

/* Test (c) of equilibria.c's header comment: every link angle turns by at most SCAN_DTHETA
 * from one point to the next, and the cubic Hermite interpolant of its tangent predicts the
 * midpoint's angle to tau. */
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

/* One level: n0 equal cells on [x0, x1], refined as in equilibria.c's header comment (a), (b),
 * (c), depth first. pt[0..top] are the points still to visit, in decreasing x from pt[0] (the
 * right end of the grid cell) to pt[top] (the left end of the cell under test); pt[top + 1] is
 * the midpoint's slot. Halving exchanges the pointers only. */
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
            int same = eq_sign_of(l->g) == eq_sign_of(m->g) && eq_sign_of(m->g) == eq_sign_of(r->g);
            double gmin = fmin(fabs(l->g), fmin(fabs(m->g), fabs(r->g)));
            double dmax = fmax(fabs(l->d), fmax(fabs(m->d), fabs(r->d)));
            double hermite = 0.5 * (l->g + r->g) + 0.125 * h * (l->d - r->d);
            int monotone = l->d != 0 && eq_sign_of(l->d) == eq_sign_of(m->d) &&
                           eq_sign_of(m->d) == eq_sign_of(r->d) && m->d != 0 && r->d != 0 &&
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

void eq_scan_out_free(scan_out *o)
{
    free(o->br);
    memset(o, 0, sizeof *o);
}

/* Levels with 4^k n0 cells and tau / 4^k until two successive counts agree; the last level's
 * brackets in *o. */
int eq_scan_settled(const scan_problem *pb, double x0, double x1, size_t n0, scan_out *o,
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
            eq_scan_out_free(&cur);
            break;
        }
        *levels = k + 1;
        counts[k] = cur.n;
        if (k > 0 && cur.n == prev.n) {
            eq_scan_out_free(&prev);
            free(store);
            *o = cur;
            return GSL_SUCCESS;
        }
        eq_scan_out_free(&prev);
        prev = cur;
    }
    free(store);
    eq_scan_out_free(&prev);
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
int eq_polish(scan_fn f, void *ctx, double lo, double hi, double *x)
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
int eq_check_stop(size_t i, size_t n)
{
    if (!whirl_stop_requested()) return GSL_SUCCESS;
    return whirl_fail(WHIRL_EINTERRUPTED, "stopped at root %zu of %zu", i + 1, n);
}
