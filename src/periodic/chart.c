/* Stability charts of the vertically shaken chain (whirl/periodic.h, whirl_chart_vertical):
 * the edges where a pair of multipliers of the vertical state passes +1 or -1, as curves
 * A(omega) in the plane of the rate and the amplitude.
 *
 * The edge functions are the modes' (chart_modes.c): the linearisation about the vertical state
 * decouples exactly into the Hill equations q_k'' + sigma lambda_k (g + z''(t)) q_k = 0 of the
 * pencil G v = lambda M v, so det(M -+ I) of the chain's monodromy is prod_k (2 -+ tr M_k)^planes,
 * and each factor
 *   f_+k = 2 - tr M_k   (a multiplier pair of mode k through +1),
 *   f_-k = 2 + tr M_k   (through -1)
 * is a smooth function whose zeros are that mode's edges alone. A curve belongs to one family
 * (mode, kind) and is located and followed on that family's factor: two modes' edges that cross
 * are two simple roots of two functions (on the product they were a double root, and the curves
 * broke there). For N = 1, f_+ is the trace test of Mathieu's equation.
 *
 * Without drag the path A cos(omega t) makes each mode's coefficient even in t, and each factor
 * splits into two functions of half a period (chart_modes.c, chart_mode_half):
 *   f_+k = (-2 u' tau) (2 v / tau),   f_-k = (2 u) (2 v'),   at tau = T/2,
 * u and v the solutions with (u, u') = (1, 0), (v, v') = (0, 1) at t = 0. A tongue's two edges
 * are simple zeros of the two different functions (Mathieu's a_n and b_n), however thin the
 * tongue: on the factor they were two zeros closer than a bracket, and the tongues of order
 * n >= 3 (width ~ A^n) came out in pieces near their tips. A family is then (mode, kind, sub),
 * sub 0 the first function and 1 the second, and a curve is located and followed on its
 * family's function; with drag the factors do not split (below) and sub is 0. Each function is
 * computed with s and 2 s steps per period (s raised per mode, chart_mode_steps; half a period
 * in half of them, rounded up) and extrapolated (order 4): f = f(h/2) + (f(h/2) - f(h)) / 15;
 * the difference (f(h/2) - f(h)) / 15 over the slope in A is the shift of the root by the
 * extrapolation, part of the point's error estimate.
 *
 * Following a curve: at the next rate, a bracket centred on the previous amplitude of
 * half-width max(2 |the last change in A|, a scan's spacing), doubled up to BRACKET_DOUBLINGS
 * times until its factor changes sign across it, then Brent's method (core/roots.h) to the
 * tolerance. A curve that finds no bracket (it left the range, or turned back in omega) ends, so
 * does one whose linear extrapolation leaves the range, and one whose root bends more than a
 * smooth curve can between two rates (the second difference in A above the last change or a
 * scan's spacing): that root is another curve's of the same family (a follower would otherwise
 * walk on to it; the tips, where a tongue's two edges meet, chart_tips.c). Every mode's
 * functions are scanned for new curves at every rate (at `rows` amplitudes, the coarser
 * monodromy alone, each sign change not explained by a followed curve of the family located by
 * Brent). Cheaper triggers miss edges: a scan only where the parity of a family's edges
 * disagrees with the signs of its function at the range's ends, or where a tip lies between two
 * rates, does not see a pair of edges born between two rates where an edge turns back in omega
 * (Mathieu's a_1(q) and a_2(q) rise to a maximum and fall: the left edges of the first and
 * second tongues turn back towards higher rates). On the three-link chain over rates 0.5 to 8
 * and A <= 0.3 those triggers missed mode 3's first tongue from omega = 5.47 up (its left edge
 * enters and leaves through omega = 8, down to A = 0.005 there) and the upper parts of mode 2's
 * first and mode 3's second tongues; the scan at every rate costs 3.6 times the processor time
 * there.
 * The inverted chain's edges have no tips: at A = 0 its modes' multipliers are
 * exp(+-sqrt(g lambda_k) T), real, so f_+k = 2 - 2 cosh(sqrt(g lambda_k) T) < 0 < f_-k and no
 * edge reaches A = 0 (Mathieu's a_k = -4 g lambda_k / omega^2 < 0, below every tongue's tip
 * a = n^2); its edges enter and leave the chart through the range's sides.
 *
 * With linear air drag (whirl_chart_vertical_damped) every mode decays at gamma = c l_i / m_i
 * and the drag on the chain's vertical motion adds gamma z' to the gravity of its tensions
 * (chart_modes.c): q_k'' + gamma q_k' + sigma lambda_k (g + z'' + gamma z') q_k = 0 is, with
 * q = exp(-gamma t / 2) y, an undamped Hill equation of y with the constant term shifted by
 * -gamma^2 / 4, and the mode's monodromy is exp(-gamma T / 2) times one similar to y's, M_y
 * (det 1). Its multipliers exp(-gamma T / 2) mu_y pass +1 (-1) where
 * tr M_y = 2 cosh(gamma T / 2) (resp. -2 cosh(gamma T / 2)), i.e. where the damped mode's trace
 * is +-(1 + exp(-gamma T)) (its determinant exp(-gamma T)), so the factors become
 *   f_+k = 2 cosh(gamma T / 2) - tr M_y,   f_-k = 2 cosh(gamma T / 2) + tr M_y,
 * the same functions for gamma = 0 (then bit for bit the conservative chart), each a positive
 * multiple exp(gamma T / 2) of (1 + exp(-gamma T)) -+ tr M_k: their signs and zeros are the damped
 * mode's edges, and a complex pair never reaches the unit circle (|mu|^2 = exp(-gamma T)).
 * At A = 0, |tr M_y| < 2 cosh(gamma T / 2) (y's multipliers exp(+-i sqrt(g lambda_k -
 * gamma^2 / 4) T), or real with a smaller exponent), so f_+-k > 0 there: the hanging chain's
 * tongues lift off the axis and have no tips; a tongue's two edges are one curve A(omega) through
 * the tongue's lowest point (the follower's bend test lets a fall turn into a rise there: the
 * curve's own minimum, as sharp as gamma is small); a pair of edges appears between two rates
 * where a tongue's lower end bends back in omega, found by the scan at every rate. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include <omp.h>

#include "core/error.h"
#include "core/roots.h"
#include "periodic/chart_modes.h"
#include "periodic/chart_resume.h"

#define COLUMNS_DEFAULT 200 /* the 200 x 200 chart */
#define ROWS_DEFAULT 200
/* Steps per period of the coarser monodromy (at least; chart_mode_steps raises them per mode):
 * with the extrapolation from 200 and 400 the Mathieu edges (N = 1, omega up to 10) agree with
 * the characteristic values to ~1e-12 in q (tests/unit/periodic/test_chart.c), four orders below
 * the 1e-8. */
#define STEPS_DEFAULT 200
/* An edge's bracket width [L]: two orders below the 1e-8. */
#define TOL_DEFAULT 1e-10
/* Doublings of a follower's bracket before the curve is taken as ended: 2^5 = 32 times the
 * first half-width. */
#define BRACKET_DOUBLINGS 5
/* Brent iterations: superlinear on the smooth f, 1e-10 of a 0.5 range in ~10; bisection alone
 * would take 33. */
#define BRENT_ITER 100
/* A factor beyond this (a mode far from its edges, its monodromy overflowing) counts by its
 * sign alone. */
#define FACTOR_HUGE 1e300
/* The largest gamma T / 2 of a damped chart, below cosh's overflow at 710: an edge there needs
 * tr M_y ~ exp(700), a growth no Magnus step resolves anyway. */
#define DRAG_PERIOD_MAX 700


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

/* The mode's functions at (omega, amp) with mult times its coarser steps, at f[kind + 2 sub]
 * (ch->subs of each kind). Conservative: the half period's (file header), f_+ = f[0] f[2],
 * f_- = f[1] f[3], each made dimensionless by tau = T/2:
 *   f[0] = -2 u' tau,  f[2] = 2 v / tau,  f[1] = 2 u,  f[3] = 2 v'   (at T/2);
 * with drag the full period's f_+ at f[0] and f_- at f[1]. */
static int edge_functions(chart_ws *s, double amp, int mode, int mult, double f[4])
{
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    const double omega = isnan(s->omega) ? s->ch->omega : s->omega;
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request at omega=" WHIRL_Q_RATE "%.17g",
                          omega);
    const int status = whirl_pivot_line(&path, omega, amp, up);
    if (status) return status;
    double m[4];
    const chart *ch = s->ch;
    if (ch->subs == 2) {
        /* half a period in half the steps (rounded up): the full period's step, or shorter */
        chart_mode_half(&path, ch->c->gravity, ch->coef[mode], mult * ((ch->steps[mode] + 1) / 2),
                        m);
        s->monodromies++;
        const double tau = whirl_pivot_period(&path) / 2;
        f[0] = -2 * m[2] * tau, f[2] = 2 * m[1] / tau;
        f[1] = 2 * m[0], f[3] = 2 * m[3];
        return GSL_SUCCESS;
    }
    chart_mode_monodromy(&path, ch->c->gravity, ch->coef[mode], ch->gamma,
                         mult * ch->steps[mode], m);
    s->monodromies++;
    /* 2 cosh(gamma T / 2): the edges of y's trace (file header); 2 without drag */
    const double edge = ch->gamma > 0 ? 2 * cosh(ch->gamma * whirl_pivot_period(&path) / 2) : 2;
    f[0] = edge - (m[0] + m[3]);
    f[1] = edge + (m[0] + m[3]);
    return GSL_SUCCESS;
}

/* The extrapolated factor of s->mode and s->kind at amp (whirl_root_fn); s->shift its change
 * by the extrapolation. */
int chart_fine_edge(double amp, void *ctx, double *fx)
{
    chart_ws *s = ctx;
    double fc[4], ff[4];
    int status = edge_functions(s, amp, s->mode, 1, fc);
    if (status == GSL_SUCCESS) status = edge_functions(s, amp, s->mode, 2, ff);
    if (status) return status;
    const double c = fc[s->kind + 2 * s->sub], f = ff[s->kind + 2 * s->sub];
    if (fabs(c) < FACTOR_HUGE && fabs(f) < FACTOR_HUGE) {
        s->shift = (f - c) / 15;
        *fx = f + s->shift;
        return GSL_SUCCESS;
    }
    if (!isnan(c) && !isnan(f) && (c < 0) == (f < 0)) {
        s->shift = 0;
        *fx = copysign(FACTOR_HUGE, f); /* far from the family's edges: its sign */
        return GSL_SUCCESS;
    }
    return whirl_fail(GSL_EBADFUNC, "the monodromy of mode %d at omega=" WHIRL_Q_RATE "%.17g, A="
                      WHIRL_Q_LENGTH "%.17g is not finite", s->mode + 1,
                      isnan(s->omega) ? s->ch->omega : s->omega, amp);
}

/* Brent's method on [lo, hi] with the known ends; the point with its error estimate. */
static int locate(chart_ws *s, double lo, double hi, double flo, double fhi, double *amp,
                  double *err)
{
    const chart *ch = s->ch;
    const whirl_root_opts o = {.epsabs = ch->p.tol, .max_iter = BRENT_ITER, .known = 1,
                               .f_lo = flo, .f_hi = fhi};
    whirl_root r;
    int status = whirl_root_brent(chart_fine_edge, s, lo, hi, &o, &r);
    if (status) {
        if (status == WHIRL_EINTERRUPTED) return status;
        if (status == GSL_EMAXITER || !r.bracketed)
            return whirl_fail(GSL_EMAXITER, "the edge of mode %d at omega=" WHIRL_Q_RATE
                              "%.17g in A=[" WHIRL_Q_LENGTH "%.17g, " WHIRL_Q_LENGTH
                              "%.17g] was not located", s->mode + 1, ch->omega, lo, hi);
        return status;
    }
    double f;
    status = chart_fine_edge(r.root, s, &f); /* the shift at the root */
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

static chart_curve *add_curve(chart *ch, int mode, whirl_floquet_edge kind, int sub)
{
    if (ch->count == ch->cap) {
        const int cap = ch->cap ? 2 * ch->cap : 16;
        chart_curve *c = realloc(ch->curves, (size_t)cap * sizeof *c);
        if (c == NULL) return NULL;
        ch->curves = c, ch->cap = cap;
    }
    chart_curve *cv = &ch->curves[ch->count];
    *cv = (chart_curve){.kind = kind, .sub = sub, .mode = mode, .id = ch->count, .alive = 1,
                        .a1 = NAN, .a0 = NAN, .tip = NAN};
    ch->count++;
    return cv;
}

/* The lowest amplitude of a bracket: the hanging chain's edges are followed down to A = 0, where
 * f >= 0 (the mode's multipliers on the unit circle, 2 -+ tr M_k = 2 -+ 2 cos(omega_k T); a
 * tongue's two edges meet there at its tip); the inverted chain's from amp_min. */
double chart_amp_floor(const chart *ch) { return ch->p.inverted ? ch->p.amp_min : 0; }

/* 1 if the chart's edges reach A = 0 at tongues' tips: the conservative hanging chain's (the
 * inverted chain's edges stay off the axis, and so do the damped chain's: file header). */
int chart_has_tips(const chart *ch) { return !ch->p.inverted && !(ch->gamma > 0); }

/* A scan's work: the coarser factors of the modes scanned at the rows (one item per row), then
 * the sign changes that no located curve explains, each located (one item per candidate). */
typedef struct scan_work {
    double lo, step;
    int fams;           /* the families, 2 subs n: mode k's f[e] (edge_functions) at
                           2 subs k + e */
    double *f;          /* rows x fams: the coarser factors */
    int *cand;          /* a candidate: row i and family j as i fams + j */
    double *amp, *err;  /* per candidate: its edge, or NAN for a sign change of the coarser step
                           alone */
} scan_work;

static double scan_amp(const chart *ch, const scan_work *sw, int i)
{
    return i == ch->p.rows - 1 ? ch->p.amp_max : sw->lo + i * sw->step;
}

static int scan_row(chart_ws *s, void *data, int i)
{
    scan_work *sw = data;
    int status = GSL_SUCCESS;
    for (int k = 0; status == GSL_SUCCESS && k < s->ch->n; k++)
        status = edge_functions(s, scan_amp(s->ch, sw, i), k, 1,
                                &sw->f[(size_t)i * sw->fams + 2 * s->ch->subs * k]);
    return status;
}

static int scan_locate(chart_ws *s, void *data, int j)
{
    scan_work *sw = data;
    const int i = sw->cand[j] / sw->fams, fam = sw->cand[j] % sw->fams;
    const double a0 = scan_amp(s->ch, sw, i - 1), a1 = scan_amp(s->ch, sw, i);
    double flo, fhi;
    s->mode = fam / (2 * s->ch->subs);
    s->kind = (whirl_floquet_edge)(fam % 2);
    s->sub = fam / 2 % s->ch->subs;
    sw->amp[j] = NAN;
    /* the scan's signs are of the coarser monodromy: the ends again, extrapolated */
    int status = chart_fine_edge(a0, s, &flo);
    if (status == GSL_SUCCESS) status = chart_fine_edge(a1, s, &fhi);
    if (status || (flo < 0) == (fhi < 0)) return status; /* a change of the coarser step alone */
    return locate(s, a0, a1, flo, fhi, &sw->amp[j], &sw->err[j]);
}

/* The extrapolated factor of s->mode and s->kind at the rate omega and the amplitude s->amp
 * (whirl_root_fn). */
int chart_fine_rate(double omega, void *ctx, double *fx)
{
    chart_ws *s = ctx;
    s->omega = omega;
    const int status = chart_fine_edge(s->amp, s, fx);
    s->omega = NAN;
    return status;
}

/* The scan of every mode: every sign change of its functions between
 * the rows' amplitudes that no curve of the family located at this rate lies in is located and
 * starts a new curve. */
static int scan(chart *ch, int column, whirl_chart_row_fn row, void *row_data)
{
    const int rows = ch->p.rows;
    const double floor_ = chart_amp_floor(ch);
    scan_work sw = {.lo = floor_, .step = (ch->p.amp_max - floor_) / (rows - 1),
                    .fams = 2 * ch->subs * ch->n};
    sw.f = malloc((size_t)rows * (size_t)sw.fams * sizeof *sw.f);
    int status = sw.f ? GSL_SUCCESS : whirl_fail(GSL_ENOMEM, "out of memory for a scan");
    if (status == GSL_SUCCESS) status = parallel_items(ch, rows, scan_row, &sw);
    int count = 0;
    for (int pass = 0; pass < 2 && status == GSL_SUCCESS; pass++) { /* count, then list */
        count = 0;
        for (int i = 1; i < rows; i++)
            for (int j = 0; j < sw.fams; j++) {
                const double a0 = scan_amp(ch, &sw, i - 1), a1 = scan_amp(ch, &sw, i);
                const double f0 = sw.f[(size_t)(i - 1) * sw.fams + j];
                const double f1 = sw.f[(size_t)i * sw.fams + j];
                const int mode = j / (2 * ch->subs), sub = j / 2 % ch->subs;
                if ((f0 < 0) == (f1 < 0)) continue;
                int known = 0;
                for (int q = 0; q < ch->count && !known; q++) {
                    const chart_curve *cv = &ch->curves[q];
                    known = cv->alive && cv->found && cv->mode == mode && cv->sub == sub &&
                            cv->kind == (whirl_floquet_edge)(j % 2) && cv->a1 >= a0 &&
                            cv->a1 <= a1;
                }
                if (known) continue;
                if (pass) sw.cand[count] = i * sw.fams + j;
                count++;
            }
        if (pass == 0) {
            sw.cand = malloc(((size_t)count + 1) * sizeof *sw.cand);
            sw.amp = malloc(2 * ((size_t)count + 1) * sizeof *sw.amp);
            sw.err = sw.amp ? sw.amp + count + 1 : NULL;
            if (!sw.cand || !sw.amp) status = whirl_fail(GSL_ENOMEM, "out of memory for a scan");
        }
    }
    if (status == GSL_SUCCESS) status = parallel_items(ch, count, scan_locate, &sw);
    const int first = ch->count; /* the new curves' */
    for (int j = 0; status == GSL_SUCCESS && j < count; j++) {
        if (isnan(sw.amp[j])) continue;
        const int fam = sw.cand[j] % sw.fams;
        /* a root below the first row with a tip of its family within a rate's step is that
           tongue's edge at its tip (at A within the tolerance of 0: the tip itself, where the
           functions' signs are round-off): its edges come down to the tip by the descent,
           chart_tips.c, and a new curve there would be a one-point piece of them */
        const double dw = (ch->p.omega_max - ch->p.omega_min) / (ch->p.columns - 1);
        if (chart_has_tips(ch) && sw.amp[j] < sw.step &&
            !isnan(chart_tip_in(ch, ch->omega - dw, ch->omega + dw, fam / (2 * ch->subs),
                                (whirl_floquet_edge)(fam % 2))))
            continue;
        chart_curve *cv = add_curve(ch, fam / (2 * ch->subs), (whirl_floquet_edge)(fam % 2),
                                    fam / 2 % ch->subs);
        if (cv == NULL) status = whirl_fail(GSL_ENOMEM, "out of memory for the chart's curves");
        else {
            cv->a1 = sw.amp[j], cv->found = 1;
            cv->w1 = ch->omega;
            int joined = 0;
            status = chart_join_at_tip(ch, cv, column, row, row_data, &joined);
            if (status == GSL_SUCCESS && !joined) status = chart_join_low(ch, cv, &joined);
            if (status == GSL_SUCCESS && !joined) status = chart_pair(ch, cv);
            if (status == GSL_SUCCESS)
                status = emit(ch, cv, column, sw.amp[j], sw.err[j], row, row_data);
        }
    }
    /* the edges that turned back in omega since the last rate: their caps (chart_folds.c) */
    if (status == GSL_SUCCESS) status = chart_fold_caps(ch, first, column, row, row_data);
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
    s->mode = cv->mode, s->kind = cv->kind, s->sub = cv->sub;
    fw->amp[j] = NAN;
    /* heading out of the range: ended (a root near the end is another curve's, or the same
       curve's back in, found by the scan); the damped hanging chain's edges never reach A = 0
       (f > 0 there): one heading for it turns up at its tongue's lowest point, followed on */
    if (cv->a1 + change < chart_amp_floor(ch) && (chart_has_tips(ch) || ch->p.inverted)) {
        fw->tipward[j] = 1;
        return GSL_SUCCESS;
    }
    if (cv->a1 + change > ch->p.amp_max) return GSL_SUCCESS;
    fw->tipward[j] = 1; /* unless found below: an end other than at the top may be at a tip */
    /* the brackets: about a1 (try 0), then, where the change is more than a scan's spacing,
       about the linear prediction a1 + change, half as wide as the change (try 1: it holds the
       root alone where the curve moves fast next to another root of its function, a fold's
       two branches, chart_folds.c, which the first may hold too), then about a1 doubled */
    for (int t = 0, d = 0; d <= BRACKET_DOUBLINGS; t++) {
        const int predicted = t == 1;
        if (predicted && !(fabs(change) > spacing)) continue;
        const double mid = predicted ? cv->a1 + change : cv->a1;
        const double w = predicted ? fabs(change) / 2 : half;
        const double lo = fmax(chart_amp_floor(ch), mid - w);
        const double hi = fmin(ch->p.amp_max, mid + w);
        if (!predicted) d++, half *= 2;
        double flo, fhi;
        int status = lo < hi ? chart_fine_edge(lo, s, &flo) : GSL_SUCCESS;
        if (status == GSL_SUCCESS && lo < hi) status = chart_fine_edge(hi, s, &fhi);
        if (status) return status;
        if (!(lo < hi) || (flo < 0) == (fhi < 0)) {
            if (!predicted && lo == chart_amp_floor(ch) && hi == ch->p.amp_max) break;
            continue;
        }
        double amp, err;
        status = locate(s, lo, hi, flo, fhi, &amp, &err);
        if (status) return status;
        /* the damped chain's tongue turns up through its lowest point, one curve: a bend from
           falling to rising is its own (hanging) */
        const int lowest = !ch->p.inverted && ch->gamma > 0 && change < 0 && amp > cv->a1;
        if (!isnan(cv->a0) && !lowest &&
            fabs(amp - 2 * cv->a1 + cv->a0) > fmax(fabs(change), spacing))
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
    chart_low_window(ch);
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
            if (fw.tipward[j] && chart_has_tips(ch))
                status = chart_descend_to_tip(ch, cv, column, row, row_data);
            else if (fw.tipward[j])
                chart_low_end(ch, cv);
            continue;
        }
        cv->a0 = cv->a1, cv->a1 = fw.amp[j], cv->w1 = ch->omega, cv->found = 1;
        status = emit(ch, cv, column, fw.amp[j], fw.err[j], row, row_data);
    }
    free(fw.index), free(fw.amp);
    return status;
}

static int check_params(const whirl_chain *c, int dim, whirl_chart_params *p)
{
    if (c == NULL) return whirl_fail(GSL_EINVAL, "whirl_chart_vertical: needs a chain");
    if (dim != 2 && dim != 3) return whirl_fail(GSL_EINVAL, "the chart needs dim 2 or 3");
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

/* The drag's decay rate (chart_modes.c) and its limit at the slowest rate. */
static int check_drag(chart *ch, double air_drag)
{
    ch->drag = air_drag;
    int status = chart_mode_drag(ch->c, air_drag, &ch->gamma);
    if (status) return status;
    if (ch->gamma * M_PI / ch->p.omega_min > DRAG_PERIOD_MAX)
        return whirl_fail(GSL_EINVAL, "the chart's air drag " WHIRL_Q_DRAG "%g damps a period of "
                          "the slowest rate " WHIRL_Q_RATE "%g by more than exp(-%d): raise the "
                          "lowest rate or lower the drag", air_drag, ch->p.omega_min,
                          2 * DRAG_PERIOD_MAX);
    return GSL_SUCCESS;
}

static void chart_free(chart *ch)
{
    free(ch->ws);
    free(ch->tips);
    free(ch->curves);
    free(ch->coef);
    free(ch->steps);
    free(ch->freq);
}

double chart_grid(double lo, double hi, int columns, int j)
{
    return j == columns - 1 ? hi : lo + j * (hi - lo) / (columns - 1);
}

/* The state after `done` columns handed to save (chart_resume.h). */
static int save_state(const chart *ch, int done, chart_save_fn save, void *save_data)
{
    if (save == NULL) return GSL_SUCCESS;
    char *text = NULL;
    int status = chart_state_write(ch, done, &text);
    if (status == GSL_SUCCESS) status = save(save_data, done, text);
    free(text);
    return status;
}

/* The columns from start on (the curves and tips those before it left). */
static int columns(chart *ch, int start, whirl_chart_row_fn row, void *row_data,
                   whirl_chart_tick_fn tick, void *tick_data, chart_save_fn save,
                   void *save_data)
{
    const whirl_chart_params *p = &ch->p;
    const double spacing = (p->amp_max - p->amp_min) / (p->rows - 1);
    int status = save_state(ch, start, save, save_data);
    if (status) return status;
    for (int j = start; j < p->columns; j++) {
        ch->omega = chart_grid(p->omega_min, p->omega_max, p->columns, j);
        status = follow_all(ch, j, spacing, row, row_data);
        /* every mode's functions scanned at every rate (file header: a pair of edges born
           between two rates, where an edge turns back in omega, changes no count at the
           range's ends) */
        if (status == GSL_SUCCESS) status = scan(ch, j, row, row_data);
        for (int i = 0; i < ch->count; i++)
            if (!ch->curves[i].found) ch->curves[i].alive = 0;
        if (status) return status;
        if (tick) {
            const whirl_chart_progress pr = {.column = j, .columns = p->columns,
                                             .curves = ch->count,
                                             .monodromies = monodromies(ch)};
            tick(tick_data, &pr);
        }
        if ((status = save_state(ch, j + 1, save, save_data))) return status;
    }
    return GSL_SUCCESS;
}

/* The modes (chart_modes.c) and their steps: each mode's coarser steps raised at the strongest
 * shaking of both ends of the rates (the longest period, and the largest acceleration). */
static int modes(chart *ch)
{
    const size_t n = ch->c->n;
    ch->n = (int)n;
    ch->coef = malloc(n * sizeof *ch->coef);
    ch->freq = malloc(n * sizeof *ch->freq);
    ch->steps = malloc(n * sizeof *ch->steps);
    if (!ch->coef || !ch->freq || !ch->steps)
        return whirl_fail(GSL_ENOMEM, "out of memory for the chart");
    int status = chart_modes(ch->c, ch->coef);
    whirl_pivot_path slow, fast;
    const double up[3] = {0, 0, 1};
    if (status == GSL_SUCCESS) status = whirl_pivot_line(&slow, ch->p.omega_min, ch->p.amp_max, up);
    if (status == GSL_SUCCESS) status = whirl_pivot_line(&fast, ch->p.omega_max, ch->p.amp_max, up);
    const double g = ch->c->gravity;
    for (size_t k = 0; status == GSL_SUCCESS && k < n; k++) {
        ch->freq[k] = sqrt(g * ch->coef[k]);
        if (ch->p.inverted) ch->coef[k] = -ch->coef[k];
        status = chart_mode_steps(&slow, &fast, g, ch->coef[k], ch->gamma, ch->p.steps,
                                  &ch->steps[k]);
    }
    return status;
}

/* The threads' workspaces (threads as many as whirl_max_threads allows, 1 inside another
 * parallel region). */
static int workspaces(chart *ch)
{
    ch->threads = omp_in_parallel() ? 1 : whirl_max_threads();
    if (ch->threads < 1) ch->threads = 1;
    ch->ws = calloc((size_t)ch->threads, sizeof *ch->ws);
    if (ch->ws == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart");
    for (int t = 0; t < ch->threads; t++) ch->ws[t].ch = ch, ch->ws[t].omega = NAN;
    return GSL_SUCCESS;
}

int chart_vertical_run(const whirl_chain *c, int dim, const whirl_chart_params *params,
                       double air_drag, const char *state, whirl_chart_row_fn row,
                       void *row_data, whirl_chart_tick_fn tick, void *tick_data,
                       chart_save_fn save, void *save_data)
{
    chart ch = {.c = c};
    if (params) ch.p = *params;
    int status = check_params(c, dim, &ch.p);
    if (status == GSL_SUCCESS) status = check_drag(&ch, air_drag);
    /* the conservative chart's functions of the half period (file header): two per kind */
    ch.subs = ch.gamma > 0 ? 1 : 2;
    if (status) return status;
    int start = 0;
    status = modes(&ch);
    if (status == GSL_SUCCESS) status = workspaces(&ch);
    if (status == GSL_SUCCESS && state) status = chart_state_read(&ch, state, &start);
    if (status == GSL_SUCCESS)
        status = columns(&ch, start, row, row_data, tick, tick_data, save, save_data);
    chart_free(&ch);
    return status;
}

int whirl_chart_vertical(const whirl_chain *c, int dim, const whirl_chart_params *params,
                         whirl_chart_row_fn row, void *row_data, whirl_chart_tick_fn tick,
                         void *tick_data)
{
    return chart_vertical_run(c, dim, params, 0, NULL, row, row_data, tick, tick_data, NULL,
                              NULL);
}

int whirl_chart_vertical_damped(const whirl_chain *c, int dim, const whirl_chart_params *params,
                                double air_drag, whirl_chart_row_fn row, void *row_data,
                                whirl_chart_tick_fn tick, void *tick_data)
{
    return chart_vertical_run(c, dim, params, air_drag, NULL, row, row_data, tick, tick_data,
                              NULL, NULL);
}

int whirl_chart_vertical_resume(const whirl_chain *c, int dim, const whirl_chart_params *params,
                                double air_drag, const char *state, whirl_chart_row_fn row,
                                void *row_data, whirl_chart_tick_fn tick, void *tick_data,
                                whirl_chart_save_fn save, void *save_data)
{
    return chart_vertical_run(c, dim, params, air_drag, state, row, row_data, tick, tick_data,
                              save, save_data);
}
