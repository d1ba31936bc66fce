/* The window search over any source of squared eigenvalues mu = lambda^2 of a family of
 * linearisations in omega (windows_internal.h): the N-link chain's reduced problem
 * (nlink_windows.c, whose header comment derives the Krein signatures and the ranks), the
 * continuum's collocation (continuum_windows.c).
 * Windows: a scan at a coarse step computes the mu and their signatures. Between two neutral scan
 * points, a window can open and close only through a collision of opposite signatures, which
 * swaps their order in frequency: the "ranks" (for each mode with E < 0, the number of modes with
 * E > 0 below it in frequency) then differ, and bisection finds the unstable rate between. An
 * edge between a neutral and an unstable rate is the root of the collision discriminant
 *     D(omega) = Re (mu_1 - mu_2)^2
 * of the two mu that meet there (positive while they are real and distinct, -4 (Im mu)^2 once
 * they are a complex pair): D is analytic across the edge, although mu_1 and mu_2 are not, and
 * its round-off is O(eps |A'|) even where the pair is defective, so Brent's method locates the
 * edge to near round-off. A divergence edge (a mu through 0) uses D = -mu of the mu nearest 0.
 * References: Krein 1950; Mackay 1986; Brent 1973 (root and minimum finding, as in GSL). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/stability.h"
#include "core/error.h"
#include "core/input.h"
#include "core/roots.h"
#include "stability/windows_internal.h"

void whirl_windows_classify(whirl_spectrum *out, size_t count, const double *re, const double *im,
                            double level, int *sig, double (*energy)(void *data, size_t i),
                            void *data)
{
    double growth = 0;
    for (size_t i = 0; i < count; i++) {
        const double g = root_re(re[i], im[i]);
        if (g > level) growth = fmax(growth, g);
        if (sig == NULL) continue;
        sig[i] = 0;
        if (g > level) continue;
        /* neutral: a real mu, or one of a pair of nearly equal ones split by round-off */
        const double e = energy(data, i);
        sig[i] = e > 0 ? 1 : e < 0 ? -1 : 0;
    }
    out->count = count;
    out->re = re;
    out->im = im;
    out->signature = sig;
    out->growth = growth;
    out->level = level;
}

typedef struct point {
    double omega, growth;
    int unstable;
    size_t ncomplex; /* non-neutral mu */
    int *rank;       /* for each neutral mode with E < 0 (by frequency), the modes with E > 0
                        below it; NULL at points without signatures */
    size_t nrank;
    double mu_c;     /* unstable: the non-neutral mu of largest growth */
    double mu_c_im;
    double *gap;     /* for each neutral mode with E < 0 (by frequency) and the nearest mode
                        with E > 0 below (2 r) and above (2 r + 1) it in frequency: their
                        discriminant (mu_- - mu_+)^2 (NAN if there is none) */
    double *gap_mu;  /* and their mean mu */
} point;

static void point_free(point *p)
{
    free(p->rank);
    free(p->gap);
    free(p->gap_mu);
    p->rank = NULL;
    p->gap = p->gap_mu = NULL;
}

static int windows_stop_check(const windows_source *src, double omega)
{
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "window search of mode %d interrupted at omega = "
                          WHIRL_Q_RATE "%.10g", src->mode, omega);
    return GSL_SUCCESS;
}

/* A full evaluation: every mu, and with signatures the ranks. */
static int evaluate(const windows_source *src, double omega, int signatures, point *p)
{
    int status = windows_stop_check(src, omega);
    whirl_spectrum sp;
    if (!status) status = src->spectrum(src->data, omega, signatures, &sp);
    if (status == WHIRL_EINTERRUPTED) return windows_stop_check(src, omega); /* during the solve */
    if (status) return status;
    if (signatures)
        src->stats->solves_vectors++;
    else
        src->stats->solves_values++;
    p->omega = omega;
    p->growth = sp.growth;
    p->unstable = sp.growth > 0;
    p->ncomplex = 0;
    p->mu_c = p->mu_c_im = 0;
    double best = -1;
    for (size_t i = 0; i < sp.count; i++) {
        const double g = root_re(sp.re[i], sp.im[i]);
        if (g <= sp.level) continue;
        p->ncomplex++;
        if (g > best) best = g, p->mu_c = sp.re[i], p->mu_c_im = fabs(sp.im[i]);
    }
    point_free(p);
    p->nrank = 0;
    if (!signatures) return GSL_SUCCESS;
    /* neutral modes by frequency */
    size_t m = 0;
    int *order = malloc((sp.count + 1) * sizeof *order);
    if (order == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t i = 0; i < sp.count; i++)
        if (root_re(sp.re[i], sp.im[i]) <= sp.level) order[m++] = (int)i;
    for (size_t i = 1; i < m; i++) /* insertion sort by frequency (mu decreasing) */
        for (size_t j = i; j > 0 && sp.re[order[j - 1]] < sp.re[order[j]]; j--) {
            const int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    p->rank = malloc((m + 1) * sizeof *p->rank);
    p->gap = malloc(2 * (m + 1) * sizeof *p->gap);
    p->gap_mu = malloc(2 * (m + 1) * sizeof *p->gap_mu);
    if (!p->rank || !p->gap || !p->gap_mu) {
        free(order);
        return whirl_fail(GSL_ENOMEM, "out of memory");
    }
    size_t positive = 0;
    for (size_t i = 0; i < m; i++) {
        const int s = sp.signature[order[i]];
        if (s > 0) positive++;
        if (s >= 0) continue;
        const double mu = sp.re[order[i]];
        for (int side = 0; side < 2; side++) {
            double *g = p->gap + 2 * p->nrank + side, *gm = p->gap_mu + 2 * p->nrank + side;
            *g = *gm = NAN;
            for (size_t k = i; side == 0 ? k-- > 0 : ++k < m;)
                if (sp.signature[order[k]] > 0) {
                    const double other = sp.re[order[k]];
                    *g = (mu - other) * (mu - other);
                    *gm = (mu + other) / 2;
                    break;
                }
        }
        p->rank[p->nrank++] = (int)positive;
    }
    free(order);
    return GSL_SUCCESS;
}

static int same_ranks(const point *a, const point *b)
{
    if (a->nrank != b->nrank || a->ncomplex != b->ncomplex) return 0;
    for (size_t i = 0; i < a->nrank; i++)
        if (a->rank[i] != b->rank[i]) return 0;
    return 1;
}

/* The collision discriminant near mu_c from the eigenvalues re, im (count); updates mu_c. */
static double discriminant(const double *re, const double *im, size_t count, double level,
                           int divergence, double *mu_c)
{
    if (divergence) { /* -mu of the eigenvalue nearest 0 */
        size_t best = 0;
        for (size_t i = 1; i < count; i++)
            if (hypot(re[i], im[i]) < hypot(re[best], im[best])) best = i;
        return -re[best];
    }
    size_t first = 0;
    for (size_t i = 1; i < count; i++)
        if (hypot(re[i] - *mu_c, im[i]) < hypot(re[first] - *mu_c, im[first])) first = i;
    if (root_re(re[first], im[first]) > level && im[first] != 0) {
        *mu_c = re[first];
        return -4 * im[first] * im[first];
    }
    size_t second = first == 0 ? 1 : 0;
    for (size_t i = 0; i < count; i++)
        if (i != first && hypot(re[i] - *mu_c, im[i]) < hypot(re[second] - *mu_c, im[second]))
            second = i;
    *mu_c = (re[first] + re[second]) / 2;
    const double dr = re[first] - re[second], di = im[first] - im[second];
    return dr * dr - di * di;
}

typedef struct root_args {
    const windows_source *src;
    const whirl_windows_params *p;
    double mu_c;
    int divergence;
    int status;
    double growth_sign; /* minimisation: -1 (maximise the growth of the pair near mu_c) */
} root_args;

/* D(omega) or -growth(omega) near mu_c: by Arnoldi when asked and converged, else in full. */
static double pair_function(double omega, void *data)
{
    root_args *r = data;
    const windows_source *src = r->src;
    if (r->status) return NAN;
    int status = windows_stop_check(src, omega);
    if (status) {
        r->status = status;
        return NAN;
    }
    double mu_re[2], mu_im[2];
    if (r->p->krylov && src->pair && !r->divergence) {
        status = src->pair(src->data, omega, r->mu_c, mu_re, mu_im);
        if (status == GSL_SUCCESS) {
            src->stats->solves_krylov++;
            if (r->growth_sign != 0) {
                const double g = fmax(root_re(mu_re[0], mu_im[0]), root_re(mu_re[1], mu_im[1]));
                r->mu_c = mu_re[0];
                return -g;
            }
            return discriminant(mu_re, mu_im, 2, 0, 0, &r->mu_c);
        }
        if (status != GSL_CONTINUE) {
            r->status = status;
            return NAN;
        }
    }
    whirl_spectrum sp;
    status = src->spectrum(src->data, omega, 0, &sp);
    if (status) {
        r->status = status;
        return NAN;
    }
    src->stats->solves_values++;
    if (r->growth_sign != 0) { /* the growth of the mu nearest mu_c */
        size_t best = 0;
        for (size_t i = 1; i < sp.count; i++)
            if (hypot(sp.re[i] - r->mu_c, sp.im[i]) < hypot(sp.re[best] - r->mu_c, sp.im[best]))
                best = i;
        r->mu_c = sp.re[best];
        return -root_re(sp.re[best], sp.im[best]);
    }
    return discriminant(sp.re, sp.im, sp.count, sp.level, r->divergence, &r->mu_c);
}

/* pair_function for the root finder: its failure in r->status */
static int pair_value(double omega, void *data, double *value)
{
    root_args *r = data;
    *value = pair_function(omega, r);
    return r->status;
}

typedef struct edge {
    double omega, freq;
    int opens; /* 1: stable below, unstable above */
} edge;

typedef struct search {
    const windows_source *src;
    const whirl_windows_params *p;
    edge *edges;
    size_t nedges, cap;
} search;

static int add_edge(search *s, double omega, double freq, int opens)
{
    if (s->nedges == s->cap) {
        const size_t cap = s->cap ? 2 * s->cap : 16;
        edge *e = realloc(s->edges, cap * sizeof *e);
        if (e == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        s->edges = e;
        s->cap = cap;
    }
    s->edges[s->nedges++] = (edge){omega, freq, opens};
    return GSL_SUCCESS;
}

static int explore(search *s, point *a, point *b, int depth);

/* The edge between a and b (one neutral, the other unstable) by Brent's method on D of the pair
 * that is complex at the unstable end. Another pair may change the stability first (windows of
 * two pairs that overlap): full solves at 100 tol on either side of the root confirm a change of
 * the stability there (then it is an edge), and the intervals beyond them are explored again. */
static int locate(search *s, point *a, point *b, int depth)
{
    const point *un = a->unstable ? a : b;
    root_args r = {s->src, s->p, un->mu_c, 0, 0, 0};
    r.divergence = un->mu_c_im == 0 && un->mu_c > 0;
    double lo = a->omega, hi = b->omega;
    int status = GSL_SUCCESS;
    /* D at the ends must have the signs of their stability (else several pairs act at once) */
    const double f_lo = pair_function(lo, &r);
    r.mu_c = un->mu_c;
    const double f_hi = pair_function(hi, &r);
    if (r.status) return r.status;
    int bracketed = 0;
    if ((f_lo > 0) == !a->unstable && (f_hi > 0) == !b->unstable) {
        /* Brent's last bracket is taken after 200 iterations as it is */
        const whirl_root_opts o = {s->p->tol, 0, 200, 1, f_lo, f_hi};
        whirl_root root;
        status = whirl_root_brent(pair_value, &r, lo, hi, &o, &root);
        if (r.status) return r.status;
        if (status == GSL_ENOMEM) return status;
        bracketed = root.bracketed;
        if (bracketed && status && status != GSL_EMAXITER)
            return whirl_fail(status, "mode %d: the window edge between omega = " WHIRL_Q_RATE
                              "%.10g and omega = " WHIRL_Q_RATE "%.10g was not located",
                              s->src->mode, a->omega, b->omega);
        if (bracketed) lo = root.lower, hi = root.upper;
        status = GSL_SUCCESS;
    }
    if (!bracketed) { /* the discriminant does not bracket (several pairs): bisect on the
                       * stability */
        point mid = {0};
        while (hi - lo > s->p->tol) {
            const double m = (lo + hi) / 2;
            status = evaluate(s->src, m, 0, &mid);
            if (status) return status;
            if (mid.unstable == a->unstable)
                lo = m;
            else
                hi = m;
            r.mu_c = mid.unstable ? mid.mu_c : r.mu_c;
        }
    }
    const double omega = (lo + hi) / 2, freq = r.divergence ? 0 : sqrt(fmax(0, -r.mu_c));
    const double d = 100 * s->p->tol;
    if (omega - d <= a->omega || omega + d >= b->omega) /* too close to check: trust the pair */
        return add_edge(s, omega, freq, !a->unstable);
    point left = {0}, right = {0};
    status = evaluate(s->src, omega - d, 1, &left);
    if (!status) status = evaluate(s->src, omega + d, 1, &right);
    if (!status && left.unstable != right.unstable)
        status = add_edge(s, omega, freq, !left.unstable);
    if (!status) status = explore(s, a, &left, depth + 1);
    if (!status) status = explore(s, &right, b, depth + 1);
    point_free(&left);
    point_free(&right);
    return status;
}

/* Windows between the evaluated points a < b (see the header comment). */
static int explore(search *s, point *a, point *b, int depth)
{
    if (a->unstable != b->unstable) return locate(s, a, b, depth);
    /* two unstable rates: one window if the same pair (by its frequency) grows fastest at both */
    const double fa = sqrt(fmax(0, -a->mu_c)), fb = sqrt(fmax(0, -b->mu_c));
    const int other_pair = a->unstable && fabs(fa - fb) > b->omega - a->omega + 0.05;
    if (same_ranks(a, b) && !other_pair) return GSL_SUCCESS;
    const double width = b->omega - a->omega;
    if (a->unstable && width < s->p->scan_step / 16) return GSL_SUCCESS;
    if (!a->unstable && width < s->p->tol) {
        s->src->stats->unresolved++;
        return GSL_SUCCESS;
    }
    if (depth > 64) return GSL_SUCCESS;
    point mid = {0};
    const double m = (a->omega + b->omega) / 2;
    int status = evaluate(s->src, m, 1, &mid);
    if (!status) status = explore(s, a, &mid, depth + 1);
    if (!status) status = explore(s, &mid, b, depth + 1);
    point_free(&mid);
    return status;
}

/* Opposite signatures that approach without crossing (the bubble of a window between two scan
 * points that leaves the ranks as they were): where the discriminant of a neutral mode with E < 0
 * and its nearest neighbour with E > 0 (pts[j].gap[idx]) is smallest among the scan points around,
 * Brent's minimisation of that pair's D between the neighbours; a negative D is an unstable rate,
 * evaluated in full into *found (*hit = 1). */
static int approach(search *s, const point *pts, size_t npts, size_t j, size_t idx, point *found,
                    int *hit)
{
    *hit = 0;
    const point *c = &pts[j];
    const point *l = j > 0 && !pts[j - 1].unstable && same_ranks(&pts[j - 1], c) ? &pts[j - 1]
                                                                                  : NULL;
    const point *r = j + 1 < npts && !pts[j + 1].unstable && same_ranks(&pts[j + 1], c)
                         ? &pts[j + 1]
                         : NULL;
    const double g = c->gap[idx];
    if (isnan(g) || (!l && !r)) return GSL_SUCCESS;
    if ((l && !(g < l->gap[idx])) || (r && !(g < r->gap[idx]))) return GSL_SUCCESS;
    root_args ra = {s->src, s->p, c->gap_mu[idx], 0, 0, 0};
    double x = c->omega, fx = g, lo, flo, hi, fhi;
    if (l && r) {
        lo = l->omega, flo = l->gap[idx], hi = r->omega, fhi = r->gap[idx];
    } else { /* at an end of the scan or beside a change of the ranks: the interval's middle */
        const point *o = l ? l : r;
        lo = fmin(c->omega, o->omega), hi = fmax(c->omega, o->omega);
        flo = l ? l->gap[idx] : g, fhi = l ? g : r->gap[idx];
        x = (lo + hi) / 2;
        fx = pair_function(x, &ra);
        if (ra.status) return ra.status;
        if (!(fx < flo && fx < fhi)) return GSL_SUCCESS;
    }
    if (fx < 0) {
        *hit = 1;
        return evaluate(s->src, x, 1, found);
    }
    /* Brent's minimisation shrinks the interval to about sqrt(eps) |x| at best (a finer tol ran
     * all 60 iterations); there D is within O(D'' 1e-12) of its least value. A negative D ends
     * it: an unstable rate. */
    const whirl_min_opts o = {fmax(s->p->tol, 1e-6), 0, 60, 0};
    whirl_min least;
    const int status = whirl_min_brent(pair_value, &ra, x, fx, lo, flo, hi, fhi, &o, &least);
    if (ra.status) return ra.status;
    if (status == GSL_ENOMEM) return status;
    *hit = least.below;
    x = least.x;
    /* GSL's Brent may stop on a flat D (GSL_FAILURE): no window there */
    if (*hit) return evaluate(s->src, x, 1, found);
    return GSL_SUCCESS;
}

static int compare_points(const void *x, const void *y)
{
    const point *a = x, *b = y;
    return (a->omega > b->omega) - (a->omega < b->omega);
}

whirl_windows_params whirl_windows_defaults(void)
{
    whirl_windows_params p = {0};
    p.omega_min = 1;
    p.omega_max = 10;
    p.scan_step = 0.25;
    p.tol = 1e-9;
    p.krylov = 1;
    return p;
}

static int compare_edges(const void *x, const void *y)
{
    const edge *a = x, *b = y;
    return (a->omega > b->omega) - (a->omega < b->omega);
}

#define SAMPLES 8 /* full solves across a window before the maximum is refined */
#define WINDOWS_SCAN_MAX 100000 /* scan points of one mode (each a full eigen-solve) */

/* The largest growth in the window win (growth 0 at its edges; at an open end the growth of the
 * scan point there, end_from / end_to): SAMPLES full solves across it (the window may be the
 * union of several pairs' windows), then Brent's minimisation of -growth of the pair that grows
 * fastest at the best sample, between its neighbours, and a full solve at the result. */
static int largest_growth(search *s, const point *end_from, const point *end_to,
                          whirl_window *win)
{
    double x[SAMPLES + 2], f[SAMPLES + 2], mu[SAMPLES + 2];
    x[0] = win->from, f[0] = win->open_from ? -end_from->growth : 0, mu[0] = end_from->mu_c;
    x[SAMPLES + 1] = win->to, f[SAMPLES + 1] = win->open_to ? -end_to->growth : 0;
    mu[SAMPLES + 1] = end_to->mu_c;
    size_t best = 0;
    for (size_t i = 1; i <= SAMPLES + 1; i++) {
        if (i <= SAMPLES) {
            point pt = {0};
            x[i] = win->from + (win->to - win->from) * ((double)i - 0.5) / SAMPLES;
            int status = evaluate(s->src, x[i], 0, &pt);
            if (status) return status;
            f[i] = -pt.growth, mu[i] = pt.mu_c;
        }
        if (f[i] < f[best]) best = i;
    }
    win->max_growth = -f[best];
    win->at = x[best];
    if (!(f[best] < 0))
        return whirl_fail(GSL_EFAILED, "mode %d: no growth inside the window (%.10g, %.10g)",
                          s->src->mode, win->from, win->to);
    if (best == 0 || best == SAMPLES + 1) return GSL_SUCCESS; /* at an end of the range */
    root_args r = {s->src, s->p, mu[best], 0, 0, -1};
    /* the maximum is flat: its place is known to about sqrt(eps) relative at best */
    const whirl_min_opts o = {1e-6, 0, 100, -INFINITY};
    whirl_min most;
    int status = whirl_min_brent(pair_value, &r, x[best], f[best], x[best - 1], f[best - 1],
                                 x[best + 1], f[best + 1], &o, &most);
    const double at = most.x;
    if (r.status) return r.status;
    if (status == GSL_ENOMEM) return status;
    if (status)
        return whirl_fail(status, "mode %d: the largest growth in (%.10g, %.10g) was not found",
                          s->src->mode, win->from, win->to);
    /* a full solve there: the largest growth of all pairs */
    point check = {0};
    status = evaluate(s->src, at, 0, &check);
    if (!status && check.growth > win->max_growth) win->max_growth = check.growth, win->at = at;
    return status;
}

int whirl_windows_range(const whirl_windows_params *p, int mode, double birth, double **omega,
                        size_t *npts)
{
    *omega = NULL;
    *npts = 0;
    if (!(p->omega_min > 0 && p->omega_max > p->omega_min && isfinite(p->omega_max)))
        return whirl_fail(GSL_EINVAL, "the range of rates must have 0 < omega_min < omega_max, got "
                          "omega_min = " WHIRL_Q_RATE "%g, omega_max = " WHIRL_Q_RATE "%g",
                          p->omega_min, p->omega_max);
    if (!(p->scan_step > 0) || !(p->tol > 0) || !(p->tol < p->scan_step))
        return whirl_fail(GSL_EINVAL, "the scan step and the tolerance must be > 0 (tol < step), "
                                      "got %g, %g", p->scan_step, p->tol);
    const double from = fmax(p->omega_min, birth * (1 + 1e-6));
    if (!(from < p->omega_max))
        return whirl_fail(GSL_EDOM, "mode %d exists only above omega_%d = " WHIRL_Q_RATE "%.10g, "
                          "beyond the range's end, omega = " WHIRL_Q_RATE "%.10g", mode, mode,
                          birth, p->omega_max);
    const double scan_steps = ceil((p->omega_max - from) / p->scan_step - 1e-9);
    if (!(scan_steps + 1 <= WINDOWS_SCAN_MAX))
        return whirl_fail(GSL_EINVAL, "mode %d: a scan from omega = " WHIRL_Q_RATE "%.10g to omega "
                          "= " WHIRL_Q_RATE "%.10g in steps of delta omega = " WHIRL_Q_RATE "%.10g "
                          "has %.3g points, more than %d: raise the scan step or narrow the range",
                          mode, from, p->omega_max, p->scan_step, scan_steps + 1, WINDOWS_SCAN_MAX);
    const size_t steps = (size_t)scan_steps, n = steps + 1;
    double *om = malloc(n * sizeof *om);
    if (om == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t j = 0; j < n; j++) om[j] = j == steps ? p->omega_max : from + (double)j * p->scan_step;
    *omega = om;
    *npts = n;
    return GSL_SUCCESS;
}

int whirl_windows_search(const windows_source *src, const whirl_windows_params *p,
                         const double *omega, size_t npts, whirl_window *windows, size_t max,
                         size_t *count)
{
    const int mode = src->mode;
    whirl_windows_stats *stats = src->stats;
    const double from = omega[0];
    stats->omega_from = from;
    stats->omega_to = p->omega_max;
    *count = 0;
    point *pts = calloc(npts, sizeof *pts);
    search s = {src, p, NULL, 0, 0};
    int status = pts ? GSL_SUCCESS : whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t j = 0; j < npts && !status; j++) {
        status = evaluate(src, omega[j], 1, &pts[j]);
        stats->scan++;
    }
    /* unstable rates between scan points from approaching pairs, merged into the scan */
    size_t nall = npts;
    for (size_t j = 0; j < npts && !status; j++)
        for (size_t idx = 0; !pts[j].unstable && idx < 2 * pts[j].nrank && !status; idx++) {
            point found = {0};
            int hit;
            status = approach(&s, pts, npts, j, idx, &found, &hit);
            if (!status && hit && found.unstable) {
                point *more = realloc(pts, (nall + 1) * sizeof *pts);
                if (more == NULL) {
                    point_free(&found);
                    status = whirl_fail(GSL_ENOMEM, "out of memory");
                    break;
                }
                pts = more;
                pts[nall++] = found;
                stats->approaches++;
            } else {
                point_free(&found);
            }
        }
    if (!status) qsort(pts, nall, sizeof *pts, compare_points);
    for (size_t j = 0; j + 1 < nall && !status; j++)
        status = explore(&s, &pts[j], &pts[j + 1], 0);
    if (!status && s.nedges > 0) qsort(s.edges, s.nedges, sizeof *s.edges, compare_edges);
    /* windows from the edges, the largest growth in each */
    int inside = pts && pts[0].unstable;
    whirl_window cur = {0};
    if (inside) cur.from = from, cur.open_from = 1;
    for (size_t e = 0; e <= s.nedges && !status; e++) {
        const int last = e == s.nedges;
        if (last && !inside) break;
        if (!last && s.edges[e].opens == inside)
            status = whirl_fail(GSL_EFAILED, "mode %d: the window edges do not alternate at omega "
                                "= " WHIRL_Q_RATE "%.10g", mode, s.edges[e].omega);
        if (status) break;
        if (!last && !inside) {
            cur = (whirl_window){0};
            cur.from = s.edges[e].omega;
            cur.freq_from = s.edges[e].freq;
            inside = 1;
            continue;
        }
        cur.to = last ? p->omega_max : s.edges[e].omega;
        cur.open_to = last;
        cur.freq_to = last ? 0 : s.edges[e].freq;
        status = largest_growth(&s, &pts[0], &pts[nall - 1], &cur);
        if (status) break;
        if (*count < max) windows[*count] = cur;
        ++*count;
        inside = 0;
    }
    for (size_t j = 0; pts && j < nall; j++) point_free(&pts[j]);
    free(pts);
    free(s.edges);
    if (!status && *count > max)
        return whirl_fail(GSL_EINVAL, "mode %d has %zu windows, room for %zu", mode, *count, max);
    return status;
}
