/* Stability charts of the vertically shaken chain (whirl/periodic.h, whirl_chart_vertical):
 * the edges where a pair of multipliers of the vertical state passes +1 or -1, as curves
 * A(omega) in the plane of the rate and the amplitude.
 *
 * The edge functions, for the monodromy M of the vertical state (2N x 2N in 2D, pairs mu, 1/mu,
 * rho_k = mu_k + 1/mu_k):
 *   f_+ = det(M - I) = prod_k (2 - rho_k),   f_- = det(M + I) = prod_k (2 + rho_k).
 * For N = 1, f_+ = 2 - tr M: the trace test of Mathieu's equation. Each is computed from the
 * monodromies with s and 2 s steps per period and extrapolated (Gauss, order 4):
 * f = f(h/2) + (f(h/2) - f(h)) / 15; the difference (f(h/2) - f(h)) / 15 over the slope in A is the
 * shift of the root by the extrapolation, part of the point's error estimate.
 *
 * Following a curve: at the next rate, a bracket centred on the previous amplitude of
 * half-width max(2 |the last change in A|, a scan's spacing), doubled up to BRACKET_DOUBLINGS
 * times until f changes sign across it, then Brent's method (core/roots.h) to the tolerance. A
 * curve that finds no bracket (it left the range, or turned back in omega) ends, so does one whose
 * linear extrapolation leaves the range, and one
 * whose root bends more than a smooth curve can between two rates (the second difference in A
 * above the last change or a scan's spacing): that root is another curve's (the two edges of a
 * tongue meet at its tip; the follower of one would otherwise walk on to the other). A column is
 * scanned for new curves (f at `rows` amplitudes, the coarser monodromy alone, each sign change
 * not explained by a followed curve located by Brent) at the first rate; when the parity of the
 * edges found disagrees with the signs of f at the range's ends (a curve entered or left); and,
 * for the hanging chain, when a tongue's tip omega = 2 omega_k / n (omega_k the unshaken chain's
 * frequencies, K v = omega_k^2 M v in the link angles) lies between the last rate and this one,
 * where a tongue's two edges are born together and the parity cannot tell. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>

#include "core/error.h"
#include "core/roots.h"
#include "periodic/periodic_internal.h"

#define COLUMNS_DEFAULT 200 /* the 200 x 200 chart */
#define ROWS_DEFAULT 200
/* Steps per period of the coarser monodromy: with the extrapolation from 200 and 400 the
 * Mathieu edges (N = 1, omega up to 10) agree with the characteristic values to ~1e-12 in q
 * (tests/unit/periodic/test_chart.c), four orders below the 1e-8. */
#define STEPS_DEFAULT 200
/* An edge's bracket width [L]: two orders below the 1e-8. */
#define TOL_DEFAULT 1e-10
/* Doublings of a follower's bracket before the curve is taken as ended: 2^5 = 32 times the
 * first half-width. */
#define BRACKET_DOUBLINGS 5
/* Brent iterations: superlinear on the smooth f, 1e-10 of a 0.5 range in ~10; bisection alone
 * would take 33. */
#define BRENT_ITER 100

typedef struct chart_curve {
    whirl_floquet_edge kind;
    int id;
    int alive;
    double a1, a0; /* the amplitude at the last rate and the one before (NAN: none) */
    int found;     /* located at the current rate */
} chart_curve;

typedef struct chart {
    const whirl_chain *c;
    whirl_chart_params p;
    whirl_periodic *w;
    double *y;          /* the vertical state */
    gsl_matrix *lu;     /* m x m */
    gsl_permutation *perm;
    double omega;       /* the current rate */
    long monodromies;
    whirl_floquet_edge kind; /* of the root under way */
    double shift;       /* (f(h/2) - f(h)) / 15 at the last fine evaluation of kind */
    chart_curve *curves;
    int count, cap;
    double *freq;       /* the unshaken chain's frequencies (hanging), n */
} chart;

/* f_+ and f_- of the monodromy with steps per period at (omega, amp). */
static int edge_functions(chart *ch, double amp, int steps, double f[2])
{
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    int status = whirl_pivot_line(&path, ch->omega, amp, up);
    if (status) return status;
    periodic_set_path(ch->w, &path);
    status = whirl_periodic_start_vertical(ch->w, ch->p.inverted, ch->y);
    if (status == GSL_SUCCESS) status = periodic_monodromy_variational(ch->w, ch->y, steps);
    if (status) return status;
    ch->monodromies++;
    const size_t m = ch->w->m;
    for (int k = 0; k < 2; k++) {
        gsl_matrix_const_view mv = gsl_matrix_const_view_array(ch->w->mono, m, m);
        gsl_matrix_memcpy(ch->lu, &mv.matrix);
        for (size_t i = 0; i < m; i++)
            gsl_matrix_set(ch->lu, i, i, gsl_matrix_get(ch->lu, i, i) + (k == 0 ? -1 : 1));
        int sign;
        gsl_linalg_LU_decomp(ch->lu, ch->perm, &sign);
        f[k] = gsl_linalg_LU_det(ch->lu, sign);
    }
    return GSL_SUCCESS;
}

/* The extrapolated edge function of ch->kind at amp (whirl_root_fn); ch->shift its change by
 * the extrapolation. */
static int fine_edge(double amp, void *ctx, double *fx)
{
    chart *ch = ctx;
    double fc[2], ff[2];
    int status = edge_functions(ch, amp, ch->p.steps, fc);
    if (status == GSL_SUCCESS) status = edge_functions(ch, amp, 2 * ch->p.steps, ff);
    if (status) return status;
    ch->shift = (ff[ch->kind] - fc[ch->kind]) / 15;
    *fx = ff[ch->kind] + ch->shift;
    if (!isfinite(*fx))
        return whirl_fail(GSL_EBADFUNC, "the monodromy at omega=" WHIRL_Q_RATE "%.17g, A="
                          WHIRL_Q_LENGTH "%.17g is not finite", ch->omega, amp);
    return GSL_SUCCESS;
}

/* Brent's method on [lo, hi] with the known ends; the point with its error estimate. */
static int locate(chart *ch, double lo, double hi, double flo, double fhi, double *amp,
                  double *err)
{
    const whirl_root_opts o = {.epsabs = ch->p.tol, .max_iter = BRENT_ITER, .known = 1,
                               .f_lo = flo, .f_hi = fhi};
    whirl_root r;
    int status = whirl_root_brent(fine_edge, ch, lo, hi, &o, &r);
    if (status) {
        if (status == WHIRL_EINTERRUPTED) return status;
        if (status == GSL_EMAXITER || !r.bracketed)
            return whirl_fail(GSL_EMAXITER, "the edge at omega=" WHIRL_Q_RATE "%.17g in A=["
                              WHIRL_Q_LENGTH "%.17g, " WHIRL_Q_LENGTH "%.17g] was not located",
                              ch->omega, lo, hi);
        return status;
    }
    double f;
    status = fine_edge(r.root, ch, &f); /* the shift at the root */
    if (status) return status;
    const double slope = (fhi - flo) / (hi - lo);
    *amp = r.root;
    *err = (r.upper - r.lower) + fabs(ch->shift / slope);
    return GSL_SUCCESS;
}

static int emit(chart *ch, const chart_curve *cv, int column, double amp, double err,
                whirl_chart_row_fn row, void *row_data)
{
    const whirl_chart_point pt = {.kind = cv->kind, .curve = cv->id, .column = column,
                                  .omega = ch->omega, .amplitude = amp, .err = err};
    return row ? row(row_data, &pt) : GSL_SUCCESS;
}

static chart_curve *add_curve(chart *ch, whirl_floquet_edge kind)
{
    if (ch->count == ch->cap) {
        const int cap = ch->cap ? 2 * ch->cap : 16;
        chart_curve *c = realloc(ch->curves, (size_t)cap * sizeof *c);
        if (c == NULL) return NULL;
        ch->curves = c, ch->cap = cap;
    }
    chart_curve *cv = &ch->curves[ch->count];
    *cv = (chart_curve){.kind = kind, .id = ch->count, .alive = 1, .a1 = NAN, .a0 = NAN};
    ch->count++;
    return cv;
}

/* A scan of the column: every sign change of f_+ and f_- between the rows amplitudes that no
 * curve located at this rate lies in is located and starts a new curve. */
static int scan(chart *ch, int column, whirl_chart_row_fn row, void *row_data)
{
    const int rows = ch->p.rows;
    const double lo = ch->p.amp_min, step = (ch->p.amp_max - lo) / (rows - 1);
    double prev[2] = {0, 0}, prev_a = lo;
    for (int i = 0; i < rows; i++) {
        const double a = i == rows - 1 ? ch->p.amp_max : lo + i * step;
        double f[2];
        int status = edge_functions(ch, a, ch->p.steps, f);
        if (status) return status;
        for (int k = 0; i > 0 && k < 2; k++) {
            if ((prev[k] < 0) == (f[k] < 0)) continue;
            int known = 0;
            for (int j = 0; j < ch->count; j++) {
                const chart_curve *cv = &ch->curves[j];
                if (cv->alive && cv->found && cv->kind == (whirl_floquet_edge)k &&
                    cv->a1 >= prev_a && cv->a1 <= a)
                    known = 1;
            }
            if (known) continue;
            ch->kind = (whirl_floquet_edge)k;
            double flo, fhi, amp, err;
            /* the scan's signs are of the coarser monodromy: the ends again, extrapolated */
            status = fine_edge(prev_a, ch, &flo);
            if (status == GSL_SUCCESS) status = fine_edge(a, ch, &fhi);
            if (status) return status;
            if ((flo < 0) == (fhi < 0)) continue; /* a sign change of the coarser step alone */
            status = locate(ch, prev_a, a, flo, fhi, &amp, &err);
            if (status) return status;
            chart_curve *cv = add_curve(ch, ch->kind);
            if (cv == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart's curves");
            cv->a1 = amp, cv->found = 1;
            status = emit(ch, cv, column, amp, err, row, row_data);
            if (status) return status;
        }
        prev[0] = f[0], prev[1] = f[1], prev_a = a;
    }
    return GSL_SUCCESS;
}

/* The curve cv at this rate: a bracket about its last amplitude, Brent's method. */
static int follow(chart *ch, chart_curve *cv, int column, double spacing,
                  whirl_chart_row_fn row, void *row_data)
{
    const double change = isnan(cv->a0) ? 0 : cv->a1 - cv->a0;
    double half = fmax(2 * fabs(change), spacing);
    ch->kind = cv->kind;
    /* heading out of the range: ended (a root near the end is another curve's, or the same
       curve's back in, found by the scan) */
    if (cv->a1 + change < ch->p.amp_min || cv->a1 + change > ch->p.amp_max) {
        cv->alive = 0;
        return GSL_SUCCESS;
    }
    for (int d = 0; d <= BRACKET_DOUBLINGS; d++, half *= 2) {
        const double lo = fmax(ch->p.amp_min, cv->a1 - half);
        const double hi = fmin(ch->p.amp_max, cv->a1 + half);
        double flo, fhi;
        int status = fine_edge(lo, ch, &flo);
        if (status == GSL_SUCCESS) status = fine_edge(hi, ch, &fhi);
        if (status) return status;
        if ((flo < 0) == (fhi < 0)) {
            if (lo == ch->p.amp_min && hi == ch->p.amp_max) break;
            continue;
        }
        double amp, err;
        status = locate(ch, lo, hi, flo, fhi, &amp, &err);
        if (status) return status;
        if (!isnan(cv->a0) && fabs(amp - 2 * cv->a1 + cv->a0) > fmax(fabs(change), spacing))
            break; /* another curve's root: this one ended between the rates */
        cv->a0 = cv->a1, cv->a1 = amp, cv->found = 1;
        return emit(ch, cv, column, amp, err, row, row_data);
    }
    cv->alive = 0; /* left the range or turned back */
    return GSL_SUCCESS;
}

/* The unshaken hanging chain's frequencies: K v = omega^2 M v in the link angles,
 * M_ij = l_i l_j sum_{k >= max(i, j)} m_k, K_ii = g l_i sum_{k >= i} m_k. */
static int hanging_frequencies(const whirl_chain *c, double *freq)
{
    const size_t n = c->n;
    gsl_matrix *m = gsl_matrix_calloc(n, n), *k = gsl_matrix_calloc(n, n);
    gsl_vector *eval = gsl_vector_alloc(n);
    gsl_eigen_gensymm_workspace *ws = gsl_eigen_gensymm_alloc(n);
    int status = m && k && eval && ws ? GSL_SUCCESS : GSL_ENOMEM;
    if (status == GSL_SUCCESS) {
        for (size_t i = 0; i < n; i++) {
            double below = 0;
            for (size_t j = i; j < n; j++) below += c->mass[j];
            for (size_t j = 0; j < n; j++) {
                double tail = 0;
                for (size_t q = i > j ? i : j; q < n; q++) tail += c->mass[q];
                gsl_matrix_set(m, i, j, c->length[i] * c->length[j] * tail);
            }
            gsl_matrix_set(k, i, i, c->gravity * c->length[i] * below);
        }
        status = gsl_eigen_gensymm(k, m, eval, ws);
    }
    for (size_t i = 0; status == GSL_SUCCESS && i < n; i++)
        freq[i] = sqrt(fmax(gsl_vector_get(eval, i), 0));
    if (ws) gsl_eigen_gensymm_free(ws);
    if (eval) gsl_vector_free(eval);
    if (m) gsl_matrix_free(m);
    if (k) gsl_matrix_free(k);
    return status ? whirl_fail(status, "the hanging chain's frequencies: %s", gsl_strerror(status))
                  : GSL_SUCCESS;
}

/* 1 if a tongue's tip 2 omega_k / n lies in (w0, w1]: floor(2 omega_k / w) changes. */
static int tip_between(const chart *ch, double w0, double w1)
{
    if (ch->p.inverted) return 0;
    for (size_t i = 0; i < ch->c->n; i++)
        if (floor(2 * ch->freq[i] / w0) != floor(2 * ch->freq[i] / w1)) return 1;
    return 0;
}

static int check_params(const whirl_chain *c, int dim, whirl_chart_params *p)
{
    if (c == NULL) return whirl_fail(GSL_EINVAL, "whirl_chart_vertical: needs a chain");
    if (dim != 2) return whirl_fail(GSL_EINVAL, "the chart needs dim 2 (the x-z plane)");
    if (p->columns == 0) p->columns = COLUMNS_DEFAULT;
    if (p->rows == 0) p->rows = ROWS_DEFAULT;
    if (p->steps == 0) p->steps = STEPS_DEFAULT;
    if (p->tol == 0) p->tol = TOL_DEFAULT;
    if (!(p->omega_min > 0) || !(p->omega_max > p->omega_min) || !isfinite(p->omega_max) ||
        p->omega_max > WHIRL_OMEGA_MAX)
        return whirl_fail(GSL_EINVAL, "the rates need 0 < omega_min < omega_max <= %g",
                          WHIRL_OMEGA_MAX);
    if (!(p->amp_max > 0) || !isfinite(p->amp_max) || !(p->amp_min >= 0) ||
        !(p->amp_min < p->amp_max))
        return whirl_fail(GSL_EINVAL, "the amplitudes need 0 <= amp_min < amp_max, finite");
    if (p->columns < 2 || p->rows < 2 || p->steps < 8 || !(p->tol > 0) || p->inverted < 0 ||
        p->inverted > 1)
        return whirl_fail(GSL_EINVAL, "the chart needs columns >= 2, rows >= 2, steps >= 8, "
                          "tol > 0 and inverted 0 or 1");
    if (p->amp_min == 0) p->amp_min = p->amp_max / p->rows;
    return GSL_SUCCESS;
}

static void chart_free(chart *ch)
{
    whirl_periodic_free(ch->w);
    free(ch->y);
    if (ch->lu) gsl_matrix_free(ch->lu);
    if (ch->perm) gsl_permutation_free(ch->perm);
    free(ch->curves);
    free(ch->freq);
}

/* The columns from first on. */
static int columns(chart *ch, whirl_chart_row_fn row, void *row_data, whirl_chart_tick_fn tick,
                   void *tick_data)
{
    const whirl_chart_params *p = &ch->p;
    const double spacing = (p->amp_max - p->amp_min) / (p->rows - 1);
    double last = 0;
    for (int j = 0; j < p->columns; j++) {
        ch->omega = j == p->columns - 1 ? p->omega_max
                                        : p->omega_min + j * (p->omega_max - p->omega_min) /
                                                             (p->columns - 1);
        int status = GSL_SUCCESS;
        for (int i = 0; i < ch->count; i++) ch->curves[i].found = 0;
        for (int i = 0; i < ch->count && status == GSL_SUCCESS; i++)
            if (ch->curves[i].alive)
                status = follow(ch, &ch->curves[i], j, spacing, row, row_data);
        /* the parity of the edges of each kind against the signs at the range's ends */
        int rescan = j == 0 || tip_between(ch, last, ch->omega);
        double fb[2], ft[2];
        if (status == GSL_SUCCESS) status = edge_functions(ch, p->amp_min, p->steps, fb);
        if (status == GSL_SUCCESS) status = edge_functions(ch, p->amp_max, p->steps, ft);
        for (int k = 0; status == GSL_SUCCESS && k < 2; k++) {
            int found = 0;
            for (int i = 0; i < ch->count; i++)
                found += ch->curves[i].found && ch->curves[i].kind == (whirl_floquet_edge)k;
            if ((found % 2 == 1) != ((fb[k] < 0) != (ft[k] < 0))) rescan = 1;
        }
        if (status == GSL_SUCCESS && rescan) status = scan(ch, j, row, row_data);
        for (int i = 0; i < ch->count; i++)
            if (!ch->curves[i].found) ch->curves[i].alive = 0;
        if (status) return status;
        if (tick) {
            const whirl_chart_progress pr = {.column = j, .columns = p->columns,
                                             .curves = ch->count,
                                             .monodromies = ch->monodromies};
            tick(tick_data, &pr);
        }
        last = ch->omega;
    }
    return GSL_SUCCESS;
}

int whirl_chart_vertical(const whirl_chain *c, int dim, const whirl_chart_params *params,
                         whirl_chart_row_fn row, void *row_data, whirl_chart_tick_fn tick,
                         void *tick_data)
{
    chart ch = {.c = c};
    if (params) ch.p = *params;
    int status = check_params(c, dim, &ch.p);
    if (status) return status;
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    status = whirl_pivot_line(&path, ch.p.omega_max, ch.p.amp_max, up);
    if (status) return status;
    ch.w = whirl_periodic_alloc(c, dim, &path);
    if (ch.w == NULL) return whirl_last_status();
    ch.y = malloc(ch.w->size * sizeof *ch.y);
    ch.lu = gsl_matrix_alloc(ch.w->m, ch.w->m);
    ch.perm = gsl_permutation_alloc(ch.w->m);
    ch.freq = malloc(c->n * sizeof *ch.freq);
    if (!ch.y || !ch.lu || !ch.perm || !ch.freq) {
        chart_free(&ch);
        return whirl_fail(GSL_ENOMEM, "out of memory for the chart");
    }
    /* the steps: raised, as whirl_periodic_find raises them, at the strongest shaking of both
       ends of the rates (the longest period, and the largest acceleration) */
    for (int e = 0; e < 2 && status == GSL_SUCCESS; e++) {
        status = whirl_pivot_line(&path, e ? ch.p.omega_min : ch.p.omega_max, ch.p.amp_max, up);
        if (status == GSL_SUCCESS) periodic_set_path(ch.w, &path);
        if (status == GSL_SUCCESS)
            status = whirl_periodic_start_vertical(ch.w, ch.p.inverted, ch.y);
        if (status == GSL_SUCCESS)
            status = periodic_steps_for(ch.w, ch.y, ch.p.steps, &ch.p.steps);
    }
    if (status == GSL_SUCCESS && !ch.p.inverted) status = hanging_frequencies(c, ch.freq);
    if (status == GSL_SUCCESS) status = columns(&ch, row, row_data, tick, tick_data);
    chart_free(&ch);
    return status;
}
