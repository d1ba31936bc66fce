/* The tips of the conservative hanging chain's tongues on the chart of the vertically shaken
 * chain (chart.c): where a tongue's two edges meet at A = 0.
 *
 * A tongue of mode k and order n has its tip at omega = 2 omega_k / n, A = 0, where the unshaken
 * mode's multipliers exp(+-i omega_k T) pass +1 (n even) or -1 (n odd). Its two edges are simple
 * zeros of two different functions of the half period (chart.c's header, chart_modes.c): at the
 * tip, u'(T/2) = -omega_k sin(pi omega_k / omega) and v(T/2) = sin(pi omega_k / omega) / omega_k
 * (n even), u(T/2) = v'(T/2) = cos(pi omega_k / omega) (n odd) vanish together, and for A > 0
 * their zeros part (Mathieu's a_n and b_n, a_n - b_n ~ q^n / (2^(2n-3) ((n-1)!)^2)). Near the
 * tip a_n, b_n = n^2 + O(q): for n = 1 and 2 the edges leave the tip on either side of its rate
 * (a_1, b_1 = 1 +- q; a_2 = 4 + 5 q^2 / 12, b_2 = 4 - q^2 / 12), for n >= 3 both on the side of
 * the lower rates (a_n, b_n = n^2 + q^2 / (2 (n^2 - 1)) + ...: the tongue bends away from its
 * tip's rate, its width ~ A^n), A ~ sqrt|omega - tip| for n >= 2.
 *
 * The curves: an edge that ends heading for A = 0 with a tip of its family within two rates
 * ahead is carried down to the tip by its points at the scan's amplitudes, each located in the
 * rate by Brent's method on the edge's own function (the edge is smooth in omega(A) where it is
 * steep in A(omega)); the first edge down emits the tip (omega_t, 0) and the tongue's other
 * edge (the other function) from the tip up to the next rate, where the scan finds it and
 * joins it to the curve (n = 1, 2), its follower started on the chord from the tip. An edge
 * found again by the scan before the tip (its follower lost it where it is steep) that comes down
 * to the tip from no higher than an edge of its function before is not carried down again (the
 * tip's top). A tongue of n >= 3 sends both edges down: each is carried to
 * the tip, and both are one curve from their start: a new edge takes the number of the other
 * function's edge next to it at its rate when the two bound one tongue there (f_+-k < 0
 * between them, the product of the two functions) and that edge's number is its own
 * (chart_pair). The points of such a curve are its two edges' at each rate; by rate they
 * alternate between the edges.
 *
 * With drag (whirl_chart_vertical_damped) the hanging chain's tongues lift off A = 0 and have no
 * tips; a tongue's two edges are one curve through its lowest point, followed on (chart.c). Where
 * that point is sharper than the rates' grid (gamma small: the tongue's bottom a V ~ gamma wide)
 * the follower's bend test can end the curve there, and the scan finds the rising edge as a new
 * curve a rate or two later: chart_low_end and chart_join_low make them one (the same family,
 * within two and a half rates, and the rate between them inside the tongue at the higher of the
 * two amplitudes: f < 0 there, the V's inside). */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>

#include "core/error.h"
#include "core/roots.h"
#include "periodic/chart_resume.h"

/* Brent iterations in the rate (chart.c's BRENT_ITER). */
#define TIP_BRENT_ITER 100
/* The fraction of a rate's step in omega a point of a descending edge may move from the last at
 * the slope so far: half, a margin for an edge that flattens on the way down (A ~ sqrt steepens,
 * and the step is shorter than this). */
#define FILL_RATE_STEP 0.5
/* The most rows such a step may take: a nearly vertical edge still has a point every 8 rows (25
 * over a chart's 200), where one per row cost a monodromy search per row and point (the N = 10
 * chart's points 8.6 times those of its edges at the rates). */
#define FILL_ROWS_MAX 8

/* An edge's points near a tongue's tip, at the amplitudes a, a + da, ... (da = +-the scan's row
 * spacing) while in (a_lo, a_hi): each located in the rate between w and the tip's rate on the
 * edge's own function (cv's mode, kind and sub) by Brent's method; it stops at the first
 * amplitude without a bracket. An edge steep in A(omega) near its tip (A ~ sqrt|omega - tip| for
 * n >= 2) is smooth in omega(A). Going down (da < 0) the step is a row's, or more where the edge
 * is steep: FILL_RATE_STEP of a rate's step in omega at the slope since the previous point (an
 * edge steepens toward its tip, A ~ sqrt, so the next step in omega is shorter still), up to
 * FILL_ROWS_MAX rows, and the lowest point one row above A = 0 (below it the edge comes so
 * near the tip's rate, omega_t - omega ~ A^2 for n >= 2, that the function's sign at the tip's
 * rate is round-off), so that the points keep within a rate's or a row's step of each other and
 * reach the lowest row. err: the rate's bracket and extrapolation shift times the edge's slope
 * dA/domega from the previous point. Returns the last amplitude located in *last (unchanged if
 * none). */
int chart_fill_rows(chart *ch, const chart_curve *cv, int column, double w, double tip,
                    double a, double da, double a_lo, double a_hi, double *last,
                    whirl_chart_row_fn row, void *row_data)
{
    chart_ws *s = &ch->ws[0];
    const double lo = fmin(w, tip), hi = fmax(w, tip);
    double pw = da < 0 ? w : tip, pa = a - da;
    s->mode = cv->mode, s->kind = cv->kind, s->sub = cv->sub;
    const double dw = (ch->p.omega_max - ch->p.omega_min) / (ch->p.columns - 1), r = fabs(da);
    for (double amp = a; amp > a_lo && amp < a_hi;) {
        double flo, fhi;
        s->amp = amp;
        int status = chart_fine_rate(lo, s, &flo);
        if (status == GSL_SUCCESS) status = chart_fine_rate(hi, s, &fhi);
        if (status) return status;
        if ((flo < 0) == (fhi < 0)) break; /* no bracket: left as it is */
        const whirl_root_opts o = {.epsabs = ch->p.tol, .max_iter = TIP_BRENT_ITER, .known = 1,
                                   .f_lo = flo, .f_hi = fhi};
        whirl_root rt;
        status = whirl_root_brent(chart_fine_rate, s, lo, hi, &o, &rt);
        double f;
        if (status == GSL_SUCCESS) status = chart_fine_rate(rt.root, s, &f); /* the shift there */
        if (status) return status;
        const double err_w = (rt.upper - rt.lower) + fabs(s->shift / ((fhi - flo) / (hi - lo)));
        const double slope = pw == rt.root ? 0 : fabs((pa - amp) / (pw - rt.root));
        const whirl_chart_point pt = {.kind = cv->kind, .curve = cv->id, .column = column,
                                      .omega = rt.root, .amplitude = amp, .err = err_w * slope};
        status = row ? row(row_data, &pt) : GSL_SUCCESS;
        if (status) return status;
        pw = rt.root, pa = amp, *last = amp;
        if (da > 0) {
            amp += da;
            continue;
        }
        const double next = amp - fmin(FILL_ROWS_MAX * r, fmax(r, FILL_RATE_STEP * slope * dw));
        amp = next < r && amp > r * (1 + 1e-9) ? r : next; /* the lowest row: one step up */
    }
    return GSL_SUCCESS;
}

int chart_descend_to_tip(chart *ch, chart_curve *cv, int column, whirl_chart_row_fn row,
                         void *row_data)
{
    const double spacing = (ch->p.omega_max - ch->p.omega_min) / (ch->p.columns - 1);
    const double tip = chart_tip_in(ch, cv->w1, fmin(ch->omega + 2 * spacing, ch->p.omega_max),
                                    cv->mode, cv->kind);
    if (isnan(tip)) return GSL_SUCCESS;
    chart_tip *reached = NULL;
    for (int i = 0; i < ch->tips_count; i++)
        if (ch->tips[i].omega == tip && ch->tips[i].mode == cv->mode) reached = &ch->tips[i];
    /* this edge came down to the tip from higher up already (the scan found it again after its
       follower ended): its points are there */
    if (reached && reached->top[cv->sub] >= cv->a1) return GSL_SUCCESS;
    const double da = (ch->p.amp_max - chart_amp_floor(ch)) / (ch->p.rows - 1);
    double low = cv->a1, top = 0;
    int status = chart_fill_rows(ch, cv, column, cv->w1, tip, cv->a1 - da, -da, 1e-3 * da,
                                 INFINITY, &low, row, row_data);
    /* the edge's own tip: its points go down to the lowest row (a row's step of A = 0; 1e-9
       of it for the rounding of the rows' amplitudes) */
    if (status || low > da * (1 + 1e-9)) return status;
    if (reached) {
        /* the tongue's other edge came down first (n >= 3): the tongue is closed, neither
           waits for a new edge */
        reached->top[cv->sub] = fmax(reached->top[cv->sub], cv->a1);
        for (int i = 0; i < ch->count; i++)
            if (ch->curves[i].tipward && ch->curves[i].tip == tip &&
                ch->curves[i].mode == cv->mode && ch->curves[i].sub != cv->sub)
                ch->curves[i].tipward = 0;
        return GSL_SUCCESS;
    }
    if (ch->tips_count == ch->tips_cap) {
        const int cap = ch->tips_cap ? 2 * ch->tips_cap : 16;
        chart_tip *t = realloc(ch->tips, (size_t)cap * sizeof *t);
        if (t == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart's tips");
        ch->tips = t, ch->tips_cap = cap;
    }
    chart_tip *t = &ch->tips[ch->tips_count++];
    *t = (chart_tip){.omega = tip, .mode = cv->mode};
    t->top[cv->sub] = cv->a1;
    const whirl_chart_point pt = {.kind = cv->kind, .curve = cv->id, .column = column,
                                  .omega = tip, .amplitude = 0, .err = 0};
    status = row ? row(row_data, &pt) : GSL_SUCCESS;
    /* the other edge (the other function) up to this rate, or the next if the tip is at this
       one (where the scan finds it and chart_join_at_tip joins it); for n >= 3 it has no
       points there (it comes down on the same side) */
    const double next = ch->omega > tip ? ch->omega : fmin(ch->omega + spacing, ch->p.omega_max);
    chart_curve other = *cv;
    other.sub = 1 - cv->sub;
    if (status == GSL_SUCCESS && next > tip)
        status = chart_fill_rows(ch, &other, column, next, tip, fmin(da, low), da, 0,
                                 ch->p.amp_max, &top, row, row_data);
    cv->tipward = 1, cv->tip = tip, cv->fill_top = top;
    return status;
}

int chart_join_at_tip(chart *ch, chart_curve *cv, int column, whirl_chart_row_fn row,
                      void *row_data, int *joined)
{
    const double spacing = (ch->p.omega_max - ch->p.omega_min) / (ch->p.columns - 1);
    const double da = (ch->p.amp_max - chart_amp_floor(ch)) / (ch->p.rows - 1);
    *joined = 0;
    for (int i = 0; i < ch->count; i++) {
        chart_curve *old = &ch->curves[i];
        if (old == cv || !old->tipward || old->kind != cv->kind || old->mode != cv->mode ||
            old->sub == cv->sub || !(ch->omega > old->tip) ||
            ch->omega - old->tip > 2.5 * spacing || !(cv->a1 > old->fill_top))
            continue;
        old->tipward = 0;
        cv->id = old->id;
        *joined = 1;
        /* the previous amplitude such that the follower's linear step to the next rate lands
           where the edge's law near its tip puts it: A ~ (omega - tip) for n = 1 (a_1, b_1 =
           1 +- q), A ~ sqrt(omega - tip) for n >= 2 (a_n, b_n - n^2 ~ q^2): the follower's
           first bracket and bend test then know the edge's rise, tens of rows per rate on a
           steep edge, which a new edge's bracket of a row (doubled 5 times) misses, and a
           chord through the tip overshoots (a steep n = 2 edge rose 12 times less over the next
           rate than the chord's 0.28) */
        const double order = 2 * ch->freq[cv->mode] / old->tip, r =
            (ch->omega + spacing - old->tip) / (ch->omega - old->tip);
        /* (a0 may lie below A = 0, a point of that line, not of the chart: at most 2 amp_max
           below the amplitude, which a prediction past 2 amp_max would leave anyway) */
        const double next = fmin(cv->a1 * (order < 1.5 ? r : sqrt(r)), 2 * ch->p.amp_max);
        cv->a0 = 2 * cv->a1 - next;
        double last = 0;
        return chart_fill_rows(ch, cv, column, ch->omega, old->tip, cv->a1 - da, -da,
                               old->fill_top + 0.5 * da, INFINITY, &last, row, row_data);
    }
    return GSL_SUCCESS;
}

int chart_pair(chart *ch, chart_curve *cv)
{
    if (!chart_has_tips(ch)) return GSL_SUCCESS;
    const chart_curve *best = NULL;
    for (int i = 0; i < ch->count; i++) {
        const chart_curve *q = &ch->curves[i];
        if (q != cv && q->found && q->mode == cv->mode && q->kind == cv->kind &&
            q->sub != cv->sub && (best == NULL || fabs(q->a1 - cv->a1) < fabs(best->a1 - cv->a1)))
            best = q;
    }
    if (best == NULL) return GSL_SUCCESS;
    const double lo = fmin(best->a1, cv->a1), hi = fmax(best->a1, cv->a1);
    for (int i = 0; i < ch->count; i++) {
        const chart_curve *q = &ch->curves[i];
        if (q == cv || q == best) continue;
        if (q->id == best->id) return GSL_SUCCESS; /* that edge's tongue has its two edges */
        if (q->found && q->mode == cv->mode && q->kind == cv->kind && q->a1 > lo && q->a1 < hi)
            return GSL_SUCCESS; /* an edge of the family between: not neighbours */
    }
    /* within two tolerances: a tongue narrower than the edges' brackets (the order-26 tongue of
       a 10-link chain's ninth mode at q = 16 is 1e-34 wide in a), its edges one point */
    if (hi - lo <= 2 * ch->p.tol) {
        cv->id = best->id;
        return GSL_SUCCESS;
    }
    /* one tongue between them: its factor f[kind] f[kind + 2] < 0 (no zero of either between
       two neighbouring edges, so one point tells) */
    chart_ws *s = &ch->ws[0];
    double f[2];
    s->mode = cv->mode, s->kind = cv->kind;
    int status = GSL_SUCCESS;
    for (int k = 0; k < 2 && status == GSL_SUCCESS; k++)
        s->sub = k, status = chart_fine_edge((lo + hi) / 2, s, &f[k]);
    if (status == GSL_SUCCESS && (f[0] < 0) != (f[1] < 0)) cv->id = best->id;
    return status;
}

/* The damped hanging chart (no tips; chart_tips.c's header): 1. */
static int damped_hanging(const chart *ch) { return !ch->p.inverted && ch->gamma > 0; }

/* The window of a join: two and a half rates (a new edge is found the rate after the end, or the
 * next). */
static double join_window(const chart *ch)
{
    return 2.5 * (ch->p.omega_max - ch->p.omega_min) / (ch->p.columns - 1);
}

void chart_low_end(chart *ch, chart_curve *cv)
{
    if (!damped_hanging(ch)) return;
    cv->tipward = 1, cv->tip = cv->w1, cv->fill_top = 0;
}

void chart_low_window(chart *ch)
{
    if (!damped_hanging(ch)) return;
    for (int i = 0; i < ch->count; i++)
        if (ch->curves[i].tipward && ch->omega - ch->curves[i].tip > join_window(ch))
            ch->curves[i].tipward = 0;
}

int chart_join_low(chart *ch, chart_curve *cv, int *joined)
{
    *joined = 0;
    if (!damped_hanging(ch)) return GSL_SUCCESS;
    for (int i = 0; i < ch->count; i++) {
        chart_curve *old = &ch->curves[i];
        if (old == cv || !old->tipward || old->kind != cv->kind || old->mode != cv->mode ||
            !(ch->omega > old->tip) || ch->omega - old->tip > join_window(ch))
            continue;
        chart_ws *s = &ch->ws[0];
        double f;
        s->mode = cv->mode, s->kind = cv->kind, s->sub = 0, s->amp = fmax(old->a1, cv->a1);
        const int status = chart_fine_rate((old->tip + ch->omega) / 2, s, &f);
        if (status) return status;
        if (!(f < 0)) continue;
        old->tipward = 0;
        cv->id = old->id;
        *joined = 1;
        return GSL_SUCCESS;
    }
    return GSL_SUCCESS;
}

double chart_tip_in(const chart *ch, double w0, double w1, int mode, whirl_floquet_edge kind)
{
    double tip = NAN;
    const double f = ch->freq[mode];
    for (double n = ceil(2 * f / w1); chart_has_tips(ch) && n <= 2 * f / w0; n++) {
        const double t = 2 * f / n;
        if (n < 1 || t <= w0 || t > w1) continue;
        if ((((long)n % 2 == 1) ? WHIRL_FLOQUET_EDGE_MINUS_ONE : WHIRL_FLOQUET_EDGE_PLUS_ONE) ==
                kind && (isnan(tip) || t > tip))
            tip = t;
    }
    return tip;
}
