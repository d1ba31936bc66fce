/* The test functions of the continuation of periodic motions and the location of its events
 * (whirl_periodic_path; the method: cycle_path.c). Three tests: det(M - I) and det(M + I) from
 * the LU factors of M -+ I, and the torus test D = prod_{k < l} (rho_k - rho_l)^2 from the
 * multipliers, each as a sign and a logarithm; Brent's method works on sign exp(ln - ref) (ref
 * the first evaluation's: a function of order 1 with the test's simple zero). */
#include <math.h>
#include <string.h>

#include <gsl/gsl_eigen.h>

#include "core/error.h"
#include "core/roots.h"
#include "periodic/cycle_internal.h"

double cycle_amplitude(const whirl_pivot_path *path)
{
    double a = 0;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < path->harmonics; j++)
            a = fmax(a, fmax(fabs(path->c[k][j]), fabs(path->s[k][j])));
    return a;
}

/* The signs and ln |det| of M - I (k = 0) and M + I (k = 1), M = w->mono. */
static void tests_of(cycle *c, int sg[2], double ln[2])
{
    const size_t m = c->m;
    for (int k = 0; k < 2; k++) {
        gsl_matrix_const_view mv = gsl_matrix_const_view_array(c->w->mono, m, m);
        gsl_matrix_memcpy(c->lu, &mv.matrix);
        for (size_t i = 0; i < m; i++)
            gsl_matrix_set(c->lu, i, i, gsl_matrix_get(c->lu, i, i) + (k == 0 ? -1 : 1));
        int sign;
        gsl_linalg_LU_decomp(c->lu, c->perm_m, &sign);
        sg[k] = gsl_linalg_LU_sgndet(c->lu, sign);
        ln[k] = sg[k] == 0 ? -INFINITY : gsl_linalg_LU_lndet(c->lu);
    }
}

/* The torus test of the multipliers re, im (m of them): the pairs mu, 1/mu matched (the two
 * closest values of s = mu + 1/mu, again and again: s is the same for both of a pair), rho_k the
 * mean of a pair's s, and D = prod_{k < l} (rho_k - rho_l)^2 into its sign and ln |D|; *gap the
 * least |rho_k - rho_l| and *rho_re the real part of that pair's mean. D changes sign where two
 * real rho meet and leave the real axis as a conjugate pair: inside (-2, 2) two pairs of
 * multipliers on the unit circle meet and leave it (a Krein collision: the conservative chain's
 * torus bifurcation). Near the meeting the pairs cannot be told apart, but there every candidate
 * D is as small as its round-off. */
static void torus_test(cycle *c, const double *re, const double *im, int *sg, double *ln,
                       double *gap, double *rho_re)
{
    const size_t m = c->m, n = m / 2;
    double *sr = c->sr, *si = c->si, *rr = c->rr, *ri = c->ri;
    for (size_t i = 0; i < m; i++) {
        const double d = re[i] * re[i] + im[i] * im[i];
        sr[i] = re[i] + re[i] / d, si[i] = im[i] - im[i] / d;
        c->used[i] = 0;
    }
    for (size_t k = 0; k < n; k++) {
        size_t bi = 0, bj = 0;
        double best = INFINITY;
        for (size_t i = 0; i < m; i++)
            for (size_t j = i + 1; j < m && !c->used[i]; j++) {
                const double d = hypot(sr[i] - sr[j], si[i] - si[j]);
                if (!c->used[j] && d < best) best = d, bi = i, bj = j;
            }
        c->used[bi] = c->used[bj] = 1;
        rr[k] = (sr[bi] + sr[bj]) / 2, ri[k] = (si[bi] + si[bj]) / 2;
    }
    double phase_re = 1, phase_im = 0, sum = 0;
    *gap = INFINITY, *rho_re = NAN;
    for (size_t k = 0; k < n; k++)
        for (size_t l = k + 1; l < n; l++) {
            const double dr = rr[k] - rr[l], di = ri[k] - ri[l];
            const double a = hypot(dr, di);
            if (a < *gap) *gap = a, *rho_re = (rr[k] + rr[l]) / 2;
            if (a == 0) {
                *sg = 0, *ln = -INFINITY;
                return;
            }
            /* (dr + i di)^2 / a^2 */
            const double zr = (dr * dr - di * di) / (a * a), zi = 2 * dr * di / (a * a);
            const double pr = phase_re * zr - phase_im * zi;
            phase_im = phase_re * zi + phase_im * zr, phase_re = pr;
            sum += 2 * log(a);
        }
    *sg = phase_re < 0 ? -1 : 1;
    *ln = sum;
}

/* The dissipative chain's torus test (whirl_periodic_alloc_model: no pairs mu, 1/mu): the
 * product P = prod_{i < j} (mu_i mu_j - 1) over the m multipliers into its sign and ln |P|, the
 * determinant of the bialternate product M (.) M - I, a polynomial in M's entries (smooth in the
 * parameter), real as the multipliers are closed under conjugation. A complex pair mu, conj mu
 * contributes |mu|^2 - 1: P changes sign where a complex pair crosses the unit circle (the
 * Neimark-Sacker, or torus, bifurcation); the factors of a complex pair with another
 * multiplier come as |mu nu - 1|^2 >= 0. Two real multipliers with mu_i mu_j = 1 (a neutral
 * saddle, no bifurcation) change its sign too: *torus_like says whether the factor nearest 0 is
 * a complex pair's, and *gap is its modulus. */
static void torus_test_dissipative(cycle *c, const double *re, const double *im, int *sg,
                                   double *ln, double *gap, int *torus_like)
{
    const size_t m = c->m;
    double phase_re = 1, phase_im = 0, sum = 0;
    *gap = INFINITY, *torus_like = 0;
    for (size_t i = 0; i < m; i++)
        for (size_t j = i + 1; j < m; j++) {
            const double zr = re[i] * re[j] - im[i] * im[j] - 1;
            const double zi = re[i] * im[j] + im[i] * re[j];
            const double a = hypot(zr, zi);
            if (a < *gap) /* a conjugate pair: im of opposite signs, not real */
                *gap = a, *torus_like = im[i] != 0 && (im[i] > 0) != (im[j] > 0);
            if (a == 0) {
                *sg = 0, *ln = -INFINITY;
                return;
            }
            const double pr = phase_re * zr / a - phase_im * zi / a;
            phase_im = phase_re * zi / a + phase_im * zr / a, phase_re = pr;
            sum += log(a);
        }
    *sg = phase_re < 0 ? -1 : 1;
    *ln = sum;
}

/* r <- the point (y, p) of w->mono: multipliers, verdict, tests. */
int cycle_describe(cycle *c, report *r, const double *y, double p, double tp, int iters,
                    double res)
{
    int status = periodic_multipliers(c->w, r->re, r->im);
    if (status) return status;
    memcpy(r->y, y, c->size * sizeof *y);
    whirl_periodic_result fr = {.count = c->m, .re = r->re, .im = r->im, .err = c->zero,
                                .period = whirl_pivot_period(&c->w->path)};
    periodic_judge(&fr, c->w->dissipative);
    int sg[2];
    double ln[2];
    tests_of(c, sg, ln);
    const double f[2] = {sg[0] * exp(ln[0] / (double)c->m), sg[1] * exp(ln[1] / (double)c->m)};
    int tsg, torus_like;
    double tln, rho_re;
    double pairs = (double)(c->m / 2) * (double)(c->m / 2 - 1) / 2;
    if (c->w->dissipative) {
        pairs = (double)c->m * (double)(c->m - 1) / 2;
        torus_test_dissipative(c, r->re, r->im, &tsg, &tln, &r->gap, &torus_like);
    } else {
        torus_test(c, r->re, r->im, &tsg, &tln, &r->gap, &rho_re);
    }
    cycle_set_param(c, p);
    r->pt = (whirl_cycle_point){
        .event = WHIRL_CYCLE_POINT, .index = c->progress.points, .parameter = p,
        .omega = c->w->path.omega, .amplitude = cycle_amplitude(&c->w->path),
        .arclength = c->arclength, .tangent = tp, .fold_test = f[0], .flip_test = f[1],
        .torus_test = pairs > 0 ? tsg * exp(tln / pairs) : 1,
        .count = c->m, .re = r->re, .im = r->im, .max_modulus = fr.max_modulus,
        .reciprocal_err = fr.reciprocal_err, .verdict = fr.verdict, .edge = fr.edge,
        .residual = res, .iterations = iters, .y = r->y};
    return GSL_SUCCESS;
}


/* The test of a change of the verdict through mode (0: +1, 1: -1, 2: a complex pair) from the
 * pairs' rho, the eigenvalues of S = M + M^{-1} (each twice): 0: the largest Re rho - 2, 1: -2 -
 * the least Re rho, 2: the largest |Im rho| - STABILITY_THRESHOLD (positive where a pair has left
 * the circle that way). Where pairs are equal by a symmetry a multiplier at +-1 is fourfold and
 * computed only to ~1e-4 (round-off to the power 1/4), but rho crosses -+2 smoothly and the
 * block of S is a multiple of I there (semisimple): rho is computed to round-off. */
static int rho_test(cycle *c, int mode, double *f)
{
    const size_t m = c->m;
    gsl_matrix_const_view mv = gsl_matrix_const_view_array(c->w->mono, m, m);
    gsl_matrix_memcpy(c->lu, &mv.matrix);
    int sign;
    int status = gsl_linalg_LU_decomp(c->lu, c->perm_m, &sign);
    if (status == GSL_SUCCESS) status = gsl_linalg_LU_invert(c->lu, c->perm_m, c->inv);
    if (status) return whirl_fail(status, "the monodromy cannot be inverted");
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++)
            gsl_matrix_set(c->w->work, i, j, c->w->mono[i * m + j] + gsl_matrix_get(c->inv, i, j));
    status = gsl_eigen_nonsymm(c->w->work, c->w->eval, c->w->eig);
    if (status) return whirl_fail(status, "the eigenvalues of M + M^-1 did not converge");
    double hi = -INFINITY, lo = INFINITY, im = 0;
    for (size_t i = 0; i < m; i++) {
        const gsl_complex z = gsl_vector_complex_get(c->w->eval, i);
        hi = fmax(hi, GSL_REAL(z)), lo = fmin(lo, GSL_REAL(z)), im = fmax(im, fabs(GSL_IMAG(z)));
    }
    *f = mode == 0 ? hi - 2 : mode == 1 ? -2 - lo : im - STABILITY_THRESHOLD;
    return GSL_SUCCESS;
}

/* ---- events: Brent's method in sigma on the extrapolated test ---- */

typedef struct event_frame {
    cycle *c;
    int kind;         /* 0: f_+, 1: f_-, 2: the torus test, 3: the stability's change */
    double rho_re;    /* the torus test: the real part of the closest pair of rho */
    int torus_like;   /* the dissipative torus test: its nearest zero is a complex pair's */
    int mode;         /* kind 3: how the largest multiplier leaves the circle (rho_test) */
    double *ys, *yf;  /* the corrected points at s and 2 s steps */
    double p;         /* the extrapolated parameter at the last sigma */
    double p_shift;   /* its change by the extrapolation */
    double ref;       /* the test is det / exp(ref): ln |det| of the first evaluation (a smooth
                         function with the det's simple zero, of order 1) */
    int have_ref;
    double f_shift;   /* the test's */
    int iters;
    double res;
} event_frame;

/* The test sg exp(ln - ref) (ref set by the first call). */
static double scaled(event_frame *e, int sg, double ln)
{
    if (!e->have_ref && isfinite(ln)) e->ref = ln, e->have_ref = 1;
    return sg == 0 ? 0 : sg * exp(ln - e->ref);
}

/* The test of e->kind of w->mono into *f: the torus test from its multipliers, kind 3 (a change
 * of the verdict) rho_test's of e->mode. */
static int test_of(event_frame *e, double *f)
{
    cycle *c = e->c;
    int sgs[2], sg;
    double lns[2], gap, ln;
    if (e->kind < 2) {
        tests_of(c, sgs, lns);
        *f = scaled(e, sgs[e->kind], lns[e->kind]);
        return GSL_SUCCESS;
    }
    if (e->kind == 3 && !c->w->dissipative) return rho_test(c, e->mode, f);
    const int status = periodic_multipliers(c->w, c->re_t, c->im_t);
    if (status) return status;
    if (e->kind == 3) { /* dissipative: the largest modulus through 1 */
        *f = hypot(c->re_t[0], c->im_t[0]) - 1;
        return GSL_SUCCESS;
    }
    if (c->w->dissipative)
        torus_test_dissipative(c, c->re_t, c->im_t, &sg, &ln, &gap, &e->torus_like);
    else
        torus_test(c, c->re_t, c->im_t, &sg, &ln, &gap, &e->rho_re);
    *f = scaled(e, sg, ln);
    return GSL_SUCCESS;
}

static int event_fn(double sigma, void *ctx, double *fx)
{
    event_frame *e = ctx;
    cycle *c = e->c;
    double ps, pf, fs, ff;
    int status = cycle_point_at(c, sigma, c->steps, e->ys, &ps, &e->iters, &e->res);
    if (status == GSL_SUCCESS) status = periodic_monodromy_variational(c->w, e->ys, c->steps);
    if (status == GSL_SUCCESS) status = test_of(e, &fs);
    if (status == GSL_SUCCESS) {
        memcpy(e->yf, e->ys, c->size * sizeof *e->ys);
        pf = ps;
        status = cycle_correct(c, sigma, 2 * c->steps, e->yf, &pf, &e->iters, &e->res);
    }
    if (status == GSL_SUCCESS)
        status = periodic_monodromy_variational(c->w, e->yf, 2 * c->steps);
    if (status == GSL_EMAXITER)
        return whirl_fail(GSL_EMAXITER, "an event near %s: the corrector did not converge "
                          "(residual %.3g)", WHERE(c, ps), e->res);
    if (status == GSL_SUCCESS) status = test_of(e, &ff);
    if (status) return status;
    e->f_shift = (ff - fs) / RICHARDSON;
    e->p_shift = (pf - ps) / RICHARDSON;
    e->p = pf + e->p_shift;
    *fx = ff + e->f_shift;
    return GSL_SUCCESS;
}

/* The event of test kind (0: +1, 1: -1, 2: torus, 3: a change of the stability that no test's
 * sign saw) on the step of length ds into r; a torus test's sign change off the unit circle (two
 * real pairs of multipliers meet off it) leaves r->pt.event WHIRL_CYCLE_POINT: no event. */
static int locate_event_at(cycle *c, int kind, double ds, report *r)
{
    static const char *const kind_name[] = {"through +1", "through -1",
                                            "pairs meeting on the unit circle",
                                            "leaving the unit circle"};
    event_frame e = {.c = c, .kind = kind, .ys = c->ys, .yf = c->yf};
    if (kind == 3) { /* how the largest multiplier at the unstable end left the circle */
        const double re = c->unstable0 ? c->mu0[0] : c->now.re[0];
        const double im = c->unstable0 ? c->mu0[1] : c->now.im[0];
        e.mode = fabs(im) > EDGE_ANGLE * hypot(re, im) ? 2 : re > 0 ? 0 : 1;
    }
    double lo = 0, hi = ds, flo, fhi;
    int status = event_fn(lo, &e, &flo);
    if (status == GSL_SUCCESS) status = event_fn(hi, &e, &fhi);
    /* a root within the discretisation's shift of an end: the extrapolated test may change
       sign just beyond it */
    if (status == GSL_SUCCESS && (flo < 0) == (fhi < 0) && kind == 3) {
        /* the verdict changed with no pair through -+1 or leaving the circle: a modulus within
           the verdict's margin (round-off), not an event */
        r->pt.event = WHIRL_CYCLE_POINT;
        return GSL_SUCCESS;
    }
    if (status == GSL_SUCCESS && (flo < 0) == (fhi < 0)) {
        lo = -ds / 2, hi = 1.5 * ds;
        status = event_fn(lo, &e, &flo);
        if (status == GSL_SUCCESS) status = event_fn(hi, &e, &fhi);
        if (status == GSL_SUCCESS && (flo < 0) == (fhi < 0))
            return whirl_fail(GSL_EFAILED, "multipliers %s near %s could not be "
                              "located (the extrapolated test does not change sign)",
                              kind_name[kind], WHERE(c, c->p0));
    }
    if (status) return status;
    const whirl_root_opts o = {.epsabs = c->p.event_tol, .max_iter = BRENT_ITER, .known = 1,
                               .f_lo = flo, .f_hi = fhi};
    whirl_root rt;
    status = whirl_root_brent(event_fn, &e, lo, hi, &o, &rt);
    if (status && status != GSL_EMAXITER) {
        if (!rt.bracketed)
            return whirl_fail(GSL_EFAILED, "multipliers %s near %s could not be "
                              "located", kind_name[kind], WHERE(c, c->p0));
        return status;
    }
    double f;
    status = event_fn(rt.root, &e, &f); /* the point, its monodromy (2 s steps) and shifts */
    if (status) return status;
    const double slope = (fhi - flo) / (hi - lo);
    /* the tangent at the root, interpolated between the step's ends */
    const double lambda = rt.root / ds, tp = (1 - lambda) * c->tp0 + lambda * c->tp1;
    const double saved = c->arclength;
    c->arclength += rt.root;
    status = cycle_describe(c, r, e.yf, e.p, tp, e.iters, e.res);
    c->arclength = saved;
    if (status) return status;
    r->sigma = rt.root;
    if (kind == 3) kind = e.mode;
    if (kind == 2 && c->w->dissipative)
        r->pt.event = e.kind == 3 || e.torus_like ? WHIRL_CYCLE_TORUS : WHIRL_CYCLE_POINT;
    else if (kind == 2)
        r->pt.event = e.kind == 3 || fabs(e.rho_re) < 2 ? WHIRL_CYCLE_TORUS : WHIRL_CYCLE_POINT;
    else if (kind == 1)
        r->pt.event = WHIRL_CYCLE_PERIOD_DOUBLING;
    else
        r->pt.event = (c->tp0 > 0) != (c->tp1 > 0) ? WHIRL_CYCLE_FOLD : WHIRL_CYCLE_BRANCH;
    r->pt.err = (rt.upper - rt.lower) * fabs(tp) + fabs(e.f_shift / slope) * fabs(tp) +
                fabs(e.p_shift);
    return GSL_SUCCESS;
}

/* The event with the corrector's tighter target. */
int cycle_locate_event(cycle *c, int kind, double ds, report *r)
{
    c->target = fmax(EVENT_NEWTON_RATIO * c->p.tol, EVENT_NEWTON_FLOOR);
    const int status = locate_event_at(c, kind, ds, r);
    c->target = c->p.tol;
    return status;
}
