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
#include <omp.h>

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
    double w1;     /* the rate of a1 */
    int tipward;   /* (hanging) ended at a tongue's tip, its other edge not yet joined */
    double tip;    /* that tip's rate (NAN: none) */
    double fill_top; /* the highest amplitude of the other edge located from the tip (0: none) */
} chart_curve;

typedef struct chart chart;

/* One thread's workspace: the monodromies at the chart's current rate. */
typedef struct chart_ws {
    const chart *ch;
    whirl_periodic *w;
    double *y;          /* the vertical state */
    gsl_matrix *lu;     /* m x m */
    gsl_permutation *perm;
    long monodromies;
    whirl_floquet_edge kind; /* of the root under way */
    double shift;       /* (f(h/2) - f(h)) / 15 at the last fine evaluation of kind */
    double omega;       /* the rate of the evaluations; NAN: the chart's current rate */
    double amp;         /* the amplitude of fine_rate */
} chart_ws;

struct chart {
    const whirl_chain *c;
    whirl_chart_params p;
    chart_ws *ws;       /* one per thread */
    int threads;
    double omega;       /* the current rate */
    chart_curve *curves;
    int count, cap;
    double *freq;       /* the unshaken chain's frequencies (hanging), n */
    double *tips;       /* the tips reached so far (one curve descends to each) */
    int tips_count, tips_cap;
};

/* The monodromies computed so far, by all the threads. */
static long monodromies(const chart *ch)
{
    long total = 0;
    for (int t = 0; t < ch->threads; t++) total += ch->ws[t].monodromies;
    return total;
}

/* work(ws, data, i) for i = 0..count-1 on the chart's threads (each with its own workspace), the
 * failure of the first failing item kept (whirl/common.h's records). */
static int parallel_items(chart *ch, int count, int (*work)(chart_ws *, void *, int), void *data)
{
    if (count <= 0) return GSL_SUCCESS;
    whirl_error_record *rec = malloc((size_t)count * sizeof *rec);
    if (rec == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart's threads");
#pragma omp parallel for schedule(dynamic) num_threads(ch->threads) if (ch->threads > 1)
    for (int i = 0; i < count; i++) {
        rec[i].status = GSL_SUCCESS;
        whirl_error_keep(&rec[i], work(&ch->ws[omp_get_thread_num()], data, i));
    }
    const int status = whirl_error_restore_first(rec, (size_t)count);
    free(rec);
    return status;
}

/* f_+ and f_- of the monodromy with steps per period at (omega, amp). */
static int edge_functions(chart_ws *s, double amp, int steps, double f[2])
{
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    const double omega = isnan(s->omega) ? s->ch->omega : s->omega;
    int status = whirl_pivot_line(&path, omega, amp, up);
    if (status) return status;
    periodic_set_path(s->w, &path);
    status = whirl_periodic_start_vertical(s->w, s->ch->p.inverted, s->y);
    if (status == GSL_SUCCESS) status = periodic_monodromy_variational(s->w, s->y, steps);
    if (status) return status;
    s->monodromies++;
    const size_t m = s->w->m;
    for (int k = 0; k < 2; k++) {
        gsl_matrix_const_view mv = gsl_matrix_const_view_array(s->w->mono, m, m);
        gsl_matrix_memcpy(s->lu, &mv.matrix);
        for (size_t i = 0; i < m; i++)
            gsl_matrix_set(s->lu, i, i, gsl_matrix_get(s->lu, i, i) + (k == 0 ? -1 : 1));
        int sign;
        gsl_linalg_LU_decomp(s->lu, s->perm, &sign);
        f[k] = gsl_linalg_LU_det(s->lu, sign);
    }
    return GSL_SUCCESS;
}

/* The extrapolated edge function of ch->kind at amp (whirl_root_fn); ch->shift its change by
 * the extrapolation. */
static int fine_edge(double amp, void *ctx, double *fx)
{
    chart_ws *s = ctx;
    double fc[2], ff[2];
    int status = edge_functions(s, amp, s->ch->p.steps, fc);
    if (status == GSL_SUCCESS) status = edge_functions(s, amp, 2 * s->ch->p.steps, ff);
    if (status) return status;
    s->shift = (ff[s->kind] - fc[s->kind]) / 15;
    *fx = ff[s->kind] + s->shift;
    if (!isfinite(*fx))
        return whirl_fail(GSL_EBADFUNC, "the monodromy at omega=" WHIRL_Q_RATE "%.17g, A="
                          WHIRL_Q_LENGTH "%.17g is not finite",
                          isnan(s->omega) ? s->ch->omega : s->omega, amp);
    return GSL_SUCCESS;
}

/* Brent's method on [lo, hi] with the known ends; the point with its error estimate. */
static int locate(chart_ws *s, double lo, double hi, double flo, double fhi, double *amp,
                  double *err)
{
    const chart *ch = s->ch;
    const whirl_root_opts o = {.epsabs = ch->p.tol, .max_iter = BRENT_ITER, .known = 1,
                               .f_lo = flo, .f_hi = fhi};
    whirl_root r;
    int status = whirl_root_brent(fine_edge, s, lo, hi, &o, &r);
    if (status) {
        if (status == WHIRL_EINTERRUPTED) return status;
        if (status == GSL_EMAXITER || !r.bracketed)
            return whirl_fail(GSL_EMAXITER, "the edge at omega=" WHIRL_Q_RATE "%.17g in A=["
                              WHIRL_Q_LENGTH "%.17g, " WHIRL_Q_LENGTH "%.17g] was not located",
                              ch->omega, lo, hi);
        return status;
    }
    double f;
    status = fine_edge(r.root, s, &f); /* the shift at the root */
    if (status) return status;
    const double slope = (fhi - flo) / (hi - lo);
    *amp = r.root;
    *err = (r.upper - r.lower) + fabs(s->shift / slope);
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
    *cv = (chart_curve){.kind = kind, .id = ch->count, .alive = 1, .a1 = NAN, .a0 = NAN,
                        .tip = NAN};
    ch->count++;
    return cv;
}

static double tip_in(const chart *ch, double w0, double w1, whirl_floquet_edge kind);

/* The lowest amplitude of a bracket: the hanging chain's edges are followed down to A = 0, where
 * f >= 0 (the multipliers on the unit circle, det(M -+ I) = prod (2 -+ 2 cos(omega_k T)); a
 * tongue's two edges meet there at its tip); the inverted chain's from amp_min. */
static double amp_floor(const chart *ch) { return ch->p.inverted ? ch->p.amp_min : 0; }

/* A scan's work: the coarser f at the rows (one item per row), then the sign changes that no
 * located curve explains, each located (one item per candidate). */
typedef struct scan_work {
    double lo, step;
    double (*f)[2];     /* rows: f_+, f_- of the coarser monodromy */
    int *cand;          /* 2 rows: row i and kind k of a candidate, as 2 i + k */
    double *amp, *err;  /* 2 rows: its edge, or NAN for a sign change of the coarser step alone */
} scan_work;

static double scan_amp(const chart *ch, const scan_work *sw, int i)
{
    return i == ch->p.rows - 1 ? ch->p.amp_max : sw->lo + i * sw->step;
}

static int scan_row(chart_ws *s, void *data, int i)
{
    scan_work *sw = data;
    return edge_functions(s, scan_amp(s->ch, sw, i), s->ch->p.steps, sw->f[i]);
}

static int scan_locate(chart_ws *s, void *data, int j)
{
    scan_work *sw = data;
    const int i = sw->cand[j] / 2;
    const double a0 = scan_amp(s->ch, sw, i - 1), a1 = scan_amp(s->ch, sw, i);
    double flo, fhi;
    s->kind = (whirl_floquet_edge)(sw->cand[j] % 2);
    sw->amp[j] = NAN;
    /* the scan's signs are of the coarser monodromy: the ends again, extrapolated */
    int status = fine_edge(a0, s, &flo);
    if (status == GSL_SUCCESS) status = fine_edge(a1, s, &fhi);
    if (status || (flo < 0) == (fhi < 0)) return status; /* a change of the coarser step alone */
    return locate(s, a0, a1, flo, fhi, &sw->amp[j], &sw->err[j]);
}

/* The extrapolated edge function of s->kind at the rate omega and the amplitude s->amp
 * (whirl_root_fn). */
static int fine_rate(double omega, void *ctx, double *fx)
{
    chart_ws *s = ctx;
    s->omega = omega;
    const int status = fine_edge(s->amp, s, fx);
    s->omega = NAN;
    return status;
}

/* An edge's points near a tongue's tip, at the amplitudes a, a + da, ... (da = +-the scan's row
 * spacing) while in (a_lo, a_hi): each located in the rate between w (outside the tongue at
 * that amplitude) and the tip's rate (inside) by Brent's method; it stops at the first
 * amplitude without a bracket. An edge steep in A(omega) near its tip (A ~ sqrt|omega - tip| for
 * n >= 2) is smooth in omega(A). err: the rate's bracket and extrapolation shift times the
 * edge's slope dA/domega from the previous point. Returns the last amplitude located in *last
 * (unchanged if none). */
static int fill_rows(chart *ch, const chart_curve *cv, int column, double w, double tip,
                     double a, double da, double a_lo, double a_hi, double *last,
                     whirl_chart_row_fn row, void *row_data)
{
    chart_ws *s = &ch->ws[0];
    const double lo = fmin(w, tip), hi = fmax(w, tip);
    double pw = da < 0 ? w : tip, pa = a - da;
    s->kind = cv->kind;
    for (double amp = a; amp > a_lo && amp < a_hi; amp += da) {
        double flo, fhi;
        s->amp = amp;
        int status = fine_rate(lo, s, &flo);
        if (status == GSL_SUCCESS) status = fine_rate(hi, s, &fhi);
        if (status) return status;
        if ((flo < 0) == (fhi < 0)) break; /* no bracket: left as it is */
        const whirl_root_opts o = {.epsabs = ch->p.tol, .max_iter = BRENT_ITER, .known = 1,
                                   .f_lo = flo, .f_hi = fhi};
        whirl_root r;
        status = whirl_root_brent(fine_rate, s, lo, hi, &o, &r);
        double f;
        if (status == GSL_SUCCESS) status = fine_rate(r.root, s, &f); /* the shift there */
        if (status) return status;
        const double err_w = (r.upper - r.lower) + fabs(s->shift / ((fhi - flo) / (hi - lo)));
        const double slope = pw == r.root ? 0 : fabs((pa - amp) / (pw - r.root));
        const whirl_chart_point pt = {.kind = cv->kind, .curve = cv->id, .column = column,
                                      .omega = r.root, .amplitude = amp, .err = err_w * slope};
        status = row ? row(row_data, &pt) : GSL_SUCCESS;
        if (status) return status;
        pw = r.root, pa = amp, *last = amp;
    }
    return GSL_SUCCESS;
}

/* The edge cv ended at this rate with a tongue's tip of its kind between its last rate and this
 * one (hanging), a tip no other edge reached before: its points down to the tip, the tip (2 omega_k / n, 0), and the tongue's other
 * edge from the tip up to the next rate, all on cv's curve. The tip is where the unshaken chain's
 * multipliers exp(+-i omega_k T) pass +-1 (det(M -+ I) = 0 at A = 0), the A = 0 end of both
 * edges (f is even in A: A cos(omega t) is -A cos(omega t) half a period later). */
static int descend_to_tip(chart *ch, chart_curve *cv, int column, whirl_chart_row_fn row,
                          void *row_data)
{
    const double tip = tip_in(ch, cv->w1, ch->omega, cv->kind);
    if (isnan(tip)) return GSL_SUCCESS;
    for (int i = 0; i < ch->tips_count; i++)
        if (ch->tips[i] == tip) return GSL_SUCCESS; /* another edge reached it first */
    if (ch->tips_count == ch->tips_cap) {
        const int cap = ch->tips_cap ? 2 * ch->tips_cap : 16;
        double *t = realloc(ch->tips, (size_t)cap * sizeof *t);
        if (t == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart's tips");
        ch->tips = t, ch->tips_cap = cap;
    }
    ch->tips[ch->tips_count++] = tip;
    const double da = (ch->p.amp_max - amp_floor(ch)) / (ch->p.rows - 1);
    double top = 0, low = cv->a1;
    int status = fill_rows(ch, cv, column, cv->w1, tip, cv->a1 - da, -da, 1e-3 * da, INFINITY,
                           &low, row, row_data);
    const whirl_chart_point pt = {.kind = cv->kind, .curve = cv->id, .column = column,
                                  .omega = tip, .amplitude = 0, .err = 0};
    if (status == GSL_SUCCESS) status = row ? row(row_data, &pt) : GSL_SUCCESS;
    /* the other edge up to this rate, or the next if the tip is at this one (where the scan
       finds it and join_at_tip joins it) */
    const double next = ch->omega > tip ? ch->omega
                                        : fmin(ch->omega + (ch->p.omega_max - ch->p.omega_min) /
                                                               (ch->p.columns - 1),
                                               ch->p.omega_max);
    if (status == GSL_SUCCESS && next > tip)
        status = fill_rows(ch, cv, column, next, tip, fmin(da, low), da, 0, ch->p.amp_max,
                           &top, row, row_data);
    cv->tipward = 1, cv->tip = tip, cv->fill_top = top;
    return status;
}

/* A new edge cv at this rate joined to an edge that ended at a tongue's tip of its kind at most
 * two and a half rates before (descend_to_tip): one curve, cv's points down to what was located
 * from the tip. */
static int join_at_tip(chart *ch, chart_curve *cv, int column, whirl_chart_row_fn row,
                       void *row_data)
{
    const double spacing = (ch->p.omega_max - ch->p.omega_min) / (ch->p.columns - 1);
    const double da = (ch->p.amp_max - amp_floor(ch)) / (ch->p.rows - 1);
    for (int i = 0; i < ch->count; i++) {
        chart_curve *old = &ch->curves[i];
        if (old == cv || !old->tipward || old->kind != cv->kind || !(ch->omega > old->tip) ||
            ch->omega - old->tip > 2.5 * spacing || !(cv->a1 > old->fill_top))
            continue;
        old->tipward = 0;
        cv->id = old->id;
        double last = 0;
        return fill_rows(ch, cv, column, ch->omega, old->tip, cv->a1 - da, -da,
                         old->fill_top + 0.5 * da, INFINITY, &last, row, row_data);
    }
    return GSL_SUCCESS;
}

/* A scan of the column: every sign change of f_+ and f_- between the rows amplitudes that no
 * curve located at this rate lies in is located and starts a new curve. */
static int scan(chart *ch, int column, whirl_chart_row_fn row, void *row_data)
{
    const int rows = ch->p.rows;
    scan_work sw = {.lo = amp_floor(ch), .step = (ch->p.amp_max - amp_floor(ch)) / (rows - 1)};
    sw.f = malloc((size_t)rows * sizeof *sw.f);
    sw.cand = malloc(2 * (size_t)rows * sizeof *sw.cand);
    sw.amp = malloc(4 * (size_t)rows * sizeof *sw.amp);
    int status = sw.f && sw.cand && sw.amp ? GSL_SUCCESS
                                           : whirl_fail(GSL_ENOMEM, "out of memory for a scan");
    sw.err = sw.amp ? sw.amp + 2 * rows : NULL;
    if (status == GSL_SUCCESS) status = parallel_items(ch, rows, scan_row, &sw);
    int count = 0;
    for (int i = 1; status == GSL_SUCCESS && i < rows; i++)
        for (int k = 0; k < 2; k++) {
            const double a0 = scan_amp(ch, &sw, i - 1), a1 = scan_amp(ch, &sw, i);
            if ((sw.f[i - 1][k] < 0) == (sw.f[i][k] < 0)) continue;
            int known = 0;
            for (int j = 0; j < ch->count; j++) {
                const chart_curve *cv = &ch->curves[j];
                if (cv->alive && cv->found && cv->kind == (whirl_floquet_edge)k &&
                    cv->a1 >= a0 && cv->a1 <= a1)
                    known = 1;
            }
            if (!known) sw.cand[count++] = 2 * i + k;
        }
    if (status == GSL_SUCCESS) status = parallel_items(ch, count, scan_locate, &sw);
    for (int j = 0; status == GSL_SUCCESS && j < count; j++) {
        if (isnan(sw.amp[j])) continue;
        chart_curve *cv = add_curve(ch, (whirl_floquet_edge)(sw.cand[j] % 2));
        if (cv == NULL) status = whirl_fail(GSL_ENOMEM, "out of memory for the chart's curves");
        else {
            cv->a1 = sw.amp[j], cv->found = 1;
            cv->w1 = ch->omega;
            status = join_at_tip(ch, cv, column, row, row_data);
            if (status == GSL_SUCCESS)
                status = emit(ch, cv, column, sw.amp[j], sw.err[j], row, row_data);
        }
    }
    free(sw.f), free(sw.cand), free(sw.amp);
    return status;
}

/* The followers' work at one rate: per alive curve, its root or NAN (the curve ended). */
typedef struct follow_work {
    int *index;         /* the curves followed */
    int *tipward;       /* 1: the curve ended heading for A = 0 */
    double *amp, *err;
    double spacing;
} follow_work;

/* The curve's root at this rate: a bracket about its last amplitude, Brent's method; NAN if it
 * ended (left the range, turned back, or its root is another curve's). */
static int follow(chart_ws *s, void *data, int j)
{
    follow_work *fw = data;
    const chart *ch = s->ch;
    const chart_curve *cv = &ch->curves[fw->index[j]];
    const double change = isnan(cv->a0) ? 0 : cv->a1 - cv->a0, spacing = fw->spacing;
    double half = fmax(2 * fabs(change), spacing);
    s->kind = cv->kind;
    fw->amp[j] = NAN;
    /* heading out of the range: ended (a root near the end is another curve's, or the same
       curve's back in, found by the scan) */
    if (cv->a1 + change < amp_floor(ch)) {
        fw->tipward[j] = 1;
        return GSL_SUCCESS;
    }
    if (cv->a1 + change > ch->p.amp_max) return GSL_SUCCESS;
    fw->tipward[j] = 1; /* unless found below: an end other than at the top may be at a tip */
    for (int d = 0; d <= BRACKET_DOUBLINGS; d++, half *= 2) {
        const double lo = fmax(amp_floor(ch), cv->a1 - half);
        const double hi = fmin(ch->p.amp_max, cv->a1 + half);
        double flo, fhi;
        int status = fine_edge(lo, s, &flo);
        if (status == GSL_SUCCESS) status = fine_edge(hi, s, &fhi);
        if (status) return status;
        if ((flo < 0) == (fhi < 0)) {
            if (lo == amp_floor(ch) && hi == ch->p.amp_max) break;
            continue;
        }
        double amp, err;
        status = locate(s, lo, hi, flo, fhi, &amp, &err);
        if (status) return status;
        if (!isnan(cv->a0) && fabs(amp - 2 * cv->a1 + cv->a0) > fmax(fabs(change), spacing))
            break; /* another curve's root: this one ended between the rates */
        fw->amp[j] = amp, fw->err[j] = err, fw->tipward[j] = 0;
        return GSL_SUCCESS;
    }
    return GSL_SUCCESS; /* left the range or turned back */
}

/* Every alive curve followed to this rate (on the threads), the points emitted by curve. */
static int follow_all(chart *ch, int column, double spacing, whirl_chart_row_fn row,
                      void *row_data)
{
    follow_work fw = {.spacing = spacing};
    fw.index = malloc(2 * (size_t)(ch->count + 1) * sizeof *fw.index);
    fw.tipward = fw.index ? fw.index + ch->count + 1 : NULL;
    fw.amp = malloc(2 * (size_t)(ch->count + 1) * sizeof *fw.amp);
    int status = fw.index && fw.amp ? GSL_SUCCESS
                                    : whirl_fail(GSL_ENOMEM, "out of memory for the followers");
    int count = 0;
    for (int i = 0; status == GSL_SUCCESS && i < ch->count; i++) {
        ch->curves[i].found = 0;
        if (ch->curves[i].alive) fw.tipward[count] = 0, fw.index[count++] = i;
    }
    fw.err = fw.amp ? fw.amp + ch->count + 1 : NULL;
    if (status == GSL_SUCCESS) status = parallel_items(ch, count, follow, &fw);
    for (int j = 0; status == GSL_SUCCESS && j < count; j++) {
        chart_curve *cv = &ch->curves[fw.index[j]];
        if (isnan(fw.amp[j])) {
            cv->alive = 0;
            if (fw.tipward[j] && !ch->p.inverted)
                status = descend_to_tip(ch, cv, column, row, row_data);
            continue;
        }
        cv->a0 = cv->a1, cv->a1 = fw.amp[j], cv->w1 = ch->omega, cv->found = 1;
        status = emit(ch, cv, column, fw.amp[j], fw.err[j], row, row_data);
    }
    free(fw.index), free(fw.amp);
    return status;
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

/* The tip 2 omega_k / n in (w0, w1] of a tongue whose edges are of the kind (n odd: -1, even:
 * +1), the one nearest w1; NAN if none. */
static double tip_in(const chart *ch, double w0, double w1, whirl_floquet_edge kind)
{
    double tip = NAN;
    for (size_t i = 0; !ch->p.inverted && i < ch->c->n; i++)
        for (double n = ceil(2 * ch->freq[i] / w1); n <= 2 * ch->freq[i] / w0; n++) {
            const double t = 2 * ch->freq[i] / n;
            if (n < 1 || t <= w0 || t > w1) continue;
            if ((((long)n % 2 == 1) ? WHIRL_FLOQUET_EDGE_MINUS_ONE : WHIRL_FLOQUET_EDGE_PLUS_ONE) ==
                    kind && (isnan(tip) || t > tip))
                tip = t;
        }
    return tip;
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
    for (int t = 0; ch->ws && t < ch->threads; t++) {
        chart_ws *s = &ch->ws[t];
        whirl_periodic_free(s->w);
        free(s->y);
        if (s->lu) gsl_matrix_free(s->lu);
        if (s->perm) gsl_permutation_free(s->perm);
    }
    free(ch->ws);
    free(ch->tips);
    free(ch->curves);
    free(ch->freq);
}

/* f at the range's ends (items 0 and 1) into data (2 x 2). */
static int range_ends(chart_ws *s, void *data, int i)
{
    double (*f)[2] = data;
    return edge_functions(s, i ? s->ch->p.amp_max : s->ch->p.amp_min, s->ch->p.steps, f[i]);
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
        int status = follow_all(ch, j, spacing, row, row_data);
        /* the parity of the edges of each kind against the signs at the range's ends */
        int rescan = j == 0 || tip_between(ch, last, ch->omega);
        double ends[2][2];
        if (status == GSL_SUCCESS) status = parallel_items(ch, 2, range_ends, ends);
        for (int k = 0; status == GSL_SUCCESS && k < 2; k++) {
            int found = 0;
            for (int i = 0; i < ch->count; i++)
                found += ch->curves[i].found && ch->curves[i].kind == (whirl_floquet_edge)k &&
                         ch->curves[i].a1 >= p->amp_min;
            if ((found % 2 == 1) != ((ends[0][k] < 0) != (ends[1][k] < 0))) rescan = 1;
        }
        if (status == GSL_SUCCESS && rescan) status = scan(ch, j, row, row_data);
        for (int i = 0; i < ch->count; i++)
            if (!ch->curves[i].found) ch->curves[i].alive = 0;
        if (status) return status;
        if (tick) {
            const whirl_chart_progress pr = {.column = j, .columns = p->columns,
                                             .curves = ch->count,
                                             .monodromies = monodromies(ch)};
            tick(tick_data, &pr);
        }
        last = ch->omega;
    }
    return GSL_SUCCESS;
}

/* The threads' workspaces on the path (threads as many as whirl_max_threads allows, 1 inside
 * another parallel region). */
static int workspaces(chart *ch, int dim, const whirl_pivot_path *path)
{
    ch->threads = omp_in_parallel() ? 1 : whirl_max_threads();
    if (ch->threads < 1) ch->threads = 1;
    ch->ws = calloc((size_t)ch->threads, sizeof *ch->ws);
    if (ch->ws == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart");
    for (int t = 0; t < ch->threads; t++) {
        chart_ws *s = &ch->ws[t];
        s->ch = ch, s->omega = NAN;
        s->w = whirl_periodic_alloc(ch->c, dim, path);
        if (s->w == NULL) return whirl_last_status();
        s->y = malloc(s->w->size * sizeof *s->y);
        s->lu = gsl_matrix_alloc(s->w->m, s->w->m);
        s->perm = gsl_permutation_alloc(s->w->m);
        if (!s->y || !s->lu || !s->perm)
            return whirl_fail(GSL_ENOMEM, "out of memory for the chart");
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
    if (status == GSL_SUCCESS) status = workspaces(&ch, dim, &path);
    ch.freq = malloc(c->n * sizeof *ch.freq);
    if (status == GSL_SUCCESS && ch.freq == NULL)
        status = whirl_fail(GSL_ENOMEM, "out of memory for the chart");
    /* the steps: raised, as whirl_periodic_find raises them, at the strongest shaking of both
       ends of the rates (the longest period, and the largest acceleration) */
    chart_ws *s = ch.ws;
    for (int e = 0; e < 2 && status == GSL_SUCCESS; e++) {
        status = whirl_pivot_line(&path, e ? ch.p.omega_min : ch.p.omega_max, ch.p.amp_max, up);
        if (status == GSL_SUCCESS) periodic_set_path(s->w, &path);
        if (status == GSL_SUCCESS)
            status = whirl_periodic_start_vertical(s->w, ch.p.inverted, s->y);
        if (status == GSL_SUCCESS)
            status = periodic_steps_for(s->w, s->y, ch.p.steps, &ch.p.steps);
    }
    if (status == GSL_SUCCESS && !ch.p.inverted) status = hanging_frequencies(c, ch.freq);
    if (status == GSL_SUCCESS) status = columns(&ch, row, row_data, tick, tick_data);
    chart_free(&ch);
    return status;
}
