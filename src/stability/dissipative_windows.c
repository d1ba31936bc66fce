/* Intervals of instability and of convergence of the N-link chain's steady shapes with
 * dissipation: internal damping of the joints and/or air drag on the hand-swung chain.
 *
 * The linearisation (stability.c) is M q'' + (G + C) q' + K q = 0 with C != 0; its first-order
 * form y' = A y has eigenvalues lambda_i(omega), and the growth rate
 *     g(omega) = max_i Re lambda_i(omega)
 * (the rotation's zero removed) decides: unstable where g > 0, converging where g < 0. With
 * dissipation the spectrum is in general off the imaginary axis, and an edge between the two is
 * a rate where one eigenvalue (or a conjugate pair) crosses the imaginary axis: a root of g.
 * g is continuous in omega (the eigenvalues are continuous) but only piecewise smooth: where
 * the eigenvalue of largest real part changes, g has a kink. So the edges are located by a
 * bracketing method that needs continuity alone: Brent's (core/roots.h), on every bracket of
 * consecutive scan rates where g changes sign; at the root found |g| must be below 100 tol times
 * the bracket's secant slope, else g jumped there (a hand-swung shape that changes branch) and
 * the search fails rather than report a jump as an edge. An interval of either kind narrower than the
 * scan step can be passed over (no discriminant as in the conservative search,
 * nlink_windows.c, gives it away: here the crossing eigenvalue meets no partner).
 * Kelvin-Tait-Chetaev (Merkin 1956; Kirillov 2013, ch. 2): with complete dissipation (C
 * definite on the non-symmetry directions, as the internal damping is) a shape of index > 0
 * (modes 2, 3, ...) is unstable at every rate, and a minimum (index 0, mode 1) converges;
 * for small damping D a neutral mode lambda = i w with eigenvector v moves by
 *     d lambda / d D = -w v^H C1 v / E,   E = 2 w v^H M v - i v^H G v
 * (C = D C1; E / w the Krein signature: negative-energy modes grow). The air drag on the
 * hand-swung chain adds a non-symmetric (circulatory) part to K, which is not a dissipation
 * and can destabilise or stabilise: there g changes sign with the rate.
 * The shapes: free (no drive, internal damping only) from the branch born at omega_k
 * (whirl_nlink_branch_nodes over the scan, whirl_nlink_solve_nodes between); hand-swung
 * (drive_radius > 0) from whirl_driven_mode at each rate, which may find none (GSL_EDOM): a rate
 * without a shape ends an interval, whose end is then marked open. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/stability.h"
#include "core/error.h"
#include "core/roots.h"
#include "stability/windows_internal.h"

/* The search of one mode: the model at each rate, its workspace, the scan's free shapes. */
typedef struct dissip_search {
    whirl_model model;        /* omega set per evaluation */
    int mode, side, driven;
    whirl_stability *lin;
    whirl_windows_stats *stats;
    double *r, *y, *z, *tension; /* nodes of one shape (N + 1; y: hand-swung only) */
} dissip_search;

/* What the linearisation says at one rate. */
typedef struct dissip_point {
    double omega;
    int exists;    /* 0: no hand-swung shape of the mode at this rate */
    double growth; /* max Re lambda [1/T] */
    double freq;   /* |Im lambda| of that eigenvalue [1/T] */
    double level;  /* round-off of the growth: 1e-10 max |lambda| */
} dissip_point;

/* The growth of the linearisation now in s->lin. */
static int spectrum_growth(dissip_search *s, dissip_point *p)
{
    size_t count;
    const double *re, *im;
    int status = whirl_stability_eigenvalues(s->lin, &count, &re, &im);
    s->stats->solves_values++;
    if (status) return status;
    p->growth = -INFINITY, p->freq = 0;
    double scale = 0;
    for (size_t i = 0; i < count; i++) {
        if (re[i] > p->growth) p->growth = re[i], p->freq = fabs(im[i]);
        scale = fmax(scale, hypot(re[i], im[i]));
    }
    p->level = 1e-10 * scale;
    return GSL_SUCCESS;
}

/* The shape of the mode at omega (r, z: the scan's free nodes, or NULL: solved here), its
 * linearisation and growth. */
static int evaluate(dissip_search *s, double omega, const double *r, const double *z,
                    dissip_point *p)
{
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "the search of mode %d was interrupted at omega = "
                          WHIRL_Q_RATE "%.10g", s->mode, omega);
    p->omega = omega;
    p->exists = 1;
    s->model.omega = omega;
    int status;
    if (s->driven) {
        /* as whirl_stability_driven_mode, whose growth is rounded to 0 within round-off */
        whirl_driven_params dp;
        whirl_driven_params_from_model(&dp, &s->model);
        whirl_driven_info info;
        status = whirl_driven_mode(s->model.chain, &dp, s->mode, s->side, &info);
        s->stats->shapes++;
        if (status == GSL_EDOM) {
            p->exists = 0;
            return GSL_SUCCESS;
        }
        if (!status)
            status = whirl_driven_sample(s->model.chain, &dp, info.tip, s->model.chain->n + 1,
                                         NULL, s->r, s->y, s->z, NULL);
        if (!status) status = whirl_stability_linearise_3d(s->lin, &s->model, s->r, s->y, s->z);
    } else {
        if (r == NULL) {
            whirl_shape_info info;
            status = whirl_nlink_solve_nodes(s->model.chain, omega, s->mode, &info, s->r, s->z,
                                             s->tension);
            s->stats->shapes++;
            if (status) return status;
            r = s->r, z = s->z;
        }
        status = whirl_stability_linearise(s->lin, &s->model, r, z);
    }
    if (!status) status = spectrum_growth(s, p);
    return status;
}

typedef struct edge_args {
    dissip_search *s;
    dissip_point last;
} edge_args;

static int growth_at(double omega, void *ctx, double *fx)
{
    edge_args *a = ctx;
    int status = evaluate(a->s, omega, NULL, NULL, &a->last);
    if (!status && !a->last.exists)
        status = whirl_fail(GSL_EDOM, "mode %d: the hand-swung shape disappears at omega = "
                            WHIRL_Q_RATE "%.10g, between two rates where it exists",
                            a->s->mode, omega);
    *fx = a->last.growth;
    return status;
}

/* The root of the growth between the scan points a and b (growths of opposite signs), to tol:
 * its rate and the frequency of the crossing eigenvalue there. */
static int locate_edge(dissip_search *s, const dissip_point *a, const dissip_point *b, double tol,
                       double *omega, double *freq)
{
    edge_args args = {s, *a};
    whirl_root_opts o = {nextafter(tol, INFINITY), 0, 200, 1, a->growth, b->growth};
    whirl_root root;
    int status = whirl_root_brent(growth_at, &args, a->omega, b->omega, &o, &root);
    if (status == GSL_EMAXITER || (status && !root.bracketed))
        return whirl_fail(GSL_EFAILED, "mode %d: the edge between omega = " WHIRL_Q_RATE "%.10g "
                          "and " WHIRL_Q_RATE "%.10g was not located", s->mode, a->omega,
                          b->omega);
    if (status) return status;
    *omega = root.root;
    *freq = 0;
    /* the frequency of the eigenvalue that crosses, at the estimate itself */
    dissip_point at;
    if ((status = evaluate(s, root.root, NULL, NULL, &at))) return status;
    if (!at.exists)
        return whirl_fail(GSL_EDOM, "mode %d: no hand-swung shape at the edge omega = "
                          WHIRL_Q_RATE "%.10g", s->mode, root.root);
    /* a root, not a jump of the growth (a shape that changes branch between the scan rates):
     * within tol of a root a continuous growth is at most about tol times its slope */
    const double secant = (fabs(a->growth) + fabs(b->growth)) / (b->omega - a->omega);
    if (!(fabs(at.growth) <= 100 * tol * secant + at.level))
        return whirl_fail(GSL_EFAILED, "mode %d: the growth jumps from %.3g to %.3g at omega = "
                          WHIRL_Q_RATE "%.10g instead of passing through 0 (the shape changes "
                          "there)", s->mode, a->growth, b->growth, root.root);
    *freq = at.freq;
    return GSL_SUCCESS;
}

typedef struct extreme_args {
    dissip_search *s;
    double sign; /* minimise sign * growth */
    int status;
} extreme_args;

static int extreme_fn(double omega, void *ctx, double *value)
{
    extreme_args *a = ctx;
    dissip_point p;
    if (a->status) return a->status;
    a->status = evaluate(a->s, omega, NULL, NULL, &p);
    if (!a->status && !p.exists)
        a->status = whirl_fail(GSL_EDOM, "mode %d: no hand-swung shape at omega = "
                               WHIRL_Q_RATE "%.10g", a->s->mode, omega);
    *value = a->status ? 0 : a->sign * p.growth;
    return a->status;
}

/* The extreme growth in the interval iv (largest if unstable, most negative if converging)
 * from the scan points x[0..n) inside it (ends included, value 0 at a located edge), refined
 * by Brent's minimisation (whirl_min_brent) about the best interior one to 1e-6 in omega. */
static int extreme_growth(dissip_search *s, whirl_dissipative_interval *iv,
                          const dissip_point *pts, size_t n)
{
    const double sign = iv->verdict == WHIRL_VERDICT_UNSTABLE ? -1 : 1;
    size_t best = 0;
    for (size_t i = 1; i < n; i++)
        if (sign * pts[i].growth < sign * pts[best].growth) best = i;
    iv->growth = pts[best].growth;
    iv->at = pts[best].omega;
    if (best == 0 || best + 1 == n) return GSL_SUCCESS; /* at an end: nothing to bracket */
    /* a flat growth (the drag's uniform decay) equal at the neighbours: no bracket, no refinement */
    if (!(sign * pts[best].growth < sign * pts[best - 1].growth &&
          sign * pts[best].growth < sign * pts[best + 1].growth))
        return GSL_SUCCESS;
    extreme_args a = {s, sign, GSL_SUCCESS};
    const whirl_min_opts o = {1e-6, 0, 100, -INFINITY};
    whirl_min least;
    const int status = whirl_min_brent(extreme_fn, &a, pts[best].omega, sign * pts[best].growth,
                                       pts[best - 1].omega, sign * pts[best - 1].growth,
                                       pts[best + 1].omega, sign * pts[best + 1].growth, &o,
                                       &least);
    const double at = least.x, f = least.f;
    if (a.status) return a.status;
    if (status == GSL_ENOMEM) return status;
    if (status)
        return whirl_fail(status, "mode %d: the extreme growth in (%.10g, %.10g) was not found",
                          s->mode, iv->from, iv->to);
    if (f < sign * iv->growth) iv->growth = sign * f, iv->at = at;
    return GSL_SUCCESS;
}

static int check(const whirl_model *m, int mode, int side, const whirl_windows_params *p)
{
    if (m == NULL || m->chain == NULL || p == NULL)
        return whirl_fail(GSL_EINVAL, "no model, chain or parameters");
    const double d = m->internal_damping, c = m->air_drag, c2 = m->air_drag_quadratic;
    const double eps = m->drive_radius;
    if (!(d >= 0 && isfinite(d) && c >= 0 && isfinite(c) && c2 >= 0 && isfinite(c2) &&
          eps >= 0 && isfinite(eps)))
        return whirl_fail(GSL_EINVAL, "damping, air drag and drive radius must be >= 0 and "
                          "finite, got %g, %g, %g, %g", d, c, c2, eps);
    if (d == 0 && c == 0 && c2 == 0)
        return whirl_fail(GSL_EINVAL, "no dissipation (internal damping and air drag 0): the "
                          "conservative chain's windows are whirl_windows_find's");
    if (eps == 0 && (c > 0 || c2 > 0))
        return whirl_fail(GSL_EINVAL, "air drag needs a drive radius > 0 (with the pivot on the "
                          "axis only the hanging chain is steady)");
    if (mode < 1 || (size_t)mode > m->chain->n)
        return whirl_fail(GSL_EINVAL, "mode %d of a %zu-link chain does not exist", mode,
                          m->chain->n);
    if (side != 1 && side != -1) return whirl_fail(GSL_EINVAL, "side must be 1 or -1, got %d", side);
    return GSL_SUCCESS;
}

/* Closes the interval cur at the point b (a located edge if edge, else an open end), finds its
 * extreme growth over the scan points pts[first..last] and stores it. */
static int close_interval(dissip_search *s, whirl_dissipative_interval *cur, dissip_point *pts,
                          size_t first, size_t last, whirl_dissipative_interval *out, size_t max,
                          size_t *count)
{
    /* the scan points inside, with the located edges as 0 */
    const size_t n = last - first + 1;
    dissip_point *in = malloc((n + 2) * sizeof *in);
    if (in == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    size_t k = 0;
    if (!cur->open_from) in[k++] = (dissip_point){cur->from, 1, 0, cur->freq_from, 0};
    for (size_t j = first; j <= last; j++) in[k++] = pts[j];
    if (!cur->open_to) in[k++] = (dissip_point){cur->to, 1, 0, cur->freq_to, 0};
    int status = extreme_growth(s, cur, in, k);
    free(in);
    if (status) return status;
    if (*count < max) out[*count] = *cur;
    ++*count;
    return GSL_SUCCESS;
}

int whirl_windows_dissipative(const whirl_model *model, int mode, int side,
                              const whirl_windows_params *p, whirl_dissipative_interval *out,
                              size_t max, size_t *count, whirl_windows_stats *stats)
{
    *count = 0;
    memset(stats, 0, sizeof *stats);
    int status = check(model, mode, side, p);
    if (status) return status;
    const whirl_chain *c = model->chain;
    const size_t n = c->n;
    double *critical = malloc((size_t)mode * sizeof *critical);
    if (critical == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    status = whirl_nlink_critical(c, (size_t)mode, critical);
    const double birth = critical[mode - 1];
    free(critical);
    if (status) return status;
    double *omega = NULL;
    size_t npts = 0;
    if ((status = whirl_windows_range(p, mode, birth, &omega, &npts))) return status;
    stats->omega_from = omega[0];
    stats->omega_to = omega[npts - 1];
    dissip_search s = {0};
    s.model = *model;
    s.model.dim = 3;
    s.model.frame = WHIRL_FRAME_ROTATING;
    s.mode = mode;
    s.side = side;
    s.driven = model->drive_radius > 0;
    s.stats = stats;
    s.lin = whirl_stability_alloc(n);
    s.r = malloc((n + 1) * sizeof *s.r);
    s.y = malloc((n + 1) * sizeof *s.y);
    s.z = malloc((n + 1) * sizeof *s.z);
    s.tension = malloc((n + 1) * sizeof *s.tension);
    dissip_point *pts = calloc(npts, sizeof *pts);
    /* the free shapes of the scan: one continuation */
    double *nr = NULL, *nz = NULL, *nt = NULL;
    whirl_shape_info *info = NULL;
    int *exists = NULL;
    if (!s.driven) {
        nr = malloc(npts * (n + 1) * sizeof *nr);
        nz = malloc(npts * (n + 1) * sizeof *nz);
        nt = malloc(npts * (n + 1) * sizeof *nt);
        info = malloc(npts * sizeof *info);
        exists = malloc(npts * sizeof *exists);
    }
    if (!s.lin || !s.r || !s.y || !s.z || !s.tension || !pts ||
        (!s.driven && (!nr || !nz || !nt || !info || !exists)))
        status = whirl_fail(GSL_ENOMEM, "out of memory for the search of mode %d", mode);
    if (!status && !s.driven) {
        status = whirl_nlink_branch_nodes(c, mode, npts, omega, info, exists, nr, nz, nt);
        stats->shapes += npts;
    }
    for (size_t j = 0; j < npts && !status; j++) {
        if (!s.driven && !exists[j]) {
            status = whirl_fail(GSL_EFAILED, "mode %d: no shape at omega = " WHIRL_Q_RATE "%g on "
                                "its branch", mode, omega[j]);
            break;
        }
        status = evaluate(&s, omega[j], s.driven ? NULL : nr + j * (n + 1),
                          s.driven ? NULL : nz + j * (n + 1), &pts[j]);
        stats->scan++;
        if (!status && pts[j].exists && !(fabs(pts[j].growth) > pts[j].level))
            status = whirl_fail(GSL_EINVAL, "mode %d: the growth at omega = " WHIRL_Q_RATE "%.10g "
                                "is within round-off of 0 (%.3g): too little dissipation to "
                                "tell unstable from converging", mode, omega[j], pts[j].growth);
    }
    /* intervals of one sign of the growth between edges, rates without a shape, and the ends */
    whirl_dissipative_interval cur = {0};
    size_t first = 0;
    int inside = 0;
    for (size_t j = 0; j < npts && !status; j++) {
        const dissip_point *a = &pts[j];
        if (!a->exists) {
            if (inside) {
                cur.to = pts[j - 1].omega, cur.open_to = 1;
                status = close_interval(&s, &cur, pts, first, j - 1, out, max, count);
            }
            inside = 0;
            continue;
        }
        const whirl_verdict v = a->growth > 0 ? WHIRL_VERDICT_UNSTABLE : WHIRL_VERDICT_CONVERGING;
        if (!inside) {
            cur = (whirl_dissipative_interval){0};
            cur.from = a->omega, cur.open_from = 1, cur.verdict = v;
            first = j, inside = 1;
        }
        if (j + 1 == npts) {
            cur.to = a->omega, cur.open_to = 1;
            status = close_interval(&s, &cur, pts, first, j, out, max, count);
            break;
        }
        const dissip_point *b = &pts[j + 1];
        if (!b->exists || (b->growth > 0) == (a->growth > 0)) continue;
        double edge = NAN, freq = NAN;
        status = locate_edge(&s, a, b, p->tol, &edge, &freq);
        if (status) break;
        cur.to = edge, cur.freq_to = freq;
        status = close_interval(&s, &cur, pts, first, j, out, max, count);
        cur = (whirl_dissipative_interval){0};
        cur.from = edge, cur.freq_from = freq;
        cur.verdict = b->growth > 0 ? WHIRL_VERDICT_UNSTABLE : WHIRL_VERDICT_CONVERGING;
        first = j + 1;
    }
    free(omega);
    free(pts);
    free(nr), free(nz), free(nt), free(info), free(exists);
    free(s.r), free(s.y), free(s.z), free(s.tension);
    whirl_stability_free(s.lin);
    if (!status && *count > max)
        return whirl_fail(GSL_EINVAL, "mode %d has %zu intervals, room for %zu", mode, *count,
                          max);
    return status;
}
