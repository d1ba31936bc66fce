/* The folds of the chart of the vertically shaken chain (chart.c): where an edge turns back in
 * the rate.
 *
 * An edge A(omega) of a mode's function can turn back in omega: Mathieu's a_1(q) and a_2(q) rise
 * to a maximum (a_1 2.5217 at q = 2.8772, a_2 8.1250 at q = 7.6584; scipy.special.mathieu_a)
 * and fall again, so with a = 4 g lambda_k / omega^2 the left edge of a first or second tongue
 * goes up towards lower rates to the turning point omega = 2 sqrt(g lambda_k / a_max),
 * A = q / (2 lambda_k), and back towards higher rates above it. Near the turning point the edge is a graph omega(A) with a
 * minimum; the chart, which goes from rate to rate, meets its two branches together at the first
 * rate past the minimum, where the scan finds two new edges of one function with the other sign
 * between them. The part of the edge between the two rates, its cap, is located here on the rows
 * between the two branches' amplitudes, each point in the rate between the last rate and this
 * one (chart_fill_rows): the curve of each branch gets the cap's points on its side of the
 * minimum, and both the row of the lowest rate, so that each branch's line, ordered by the
 * rate, runs from that point outwards.
 *
 * A fold is told apart from two unrelated new edges by the signs of the function at the last
 * rate: at the two branches' amplitudes and half way between them, all three the same (no edge
 * crossed that segment at the last rate), and half way between the opposite at this rate. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>

#include "core/error.h"
#include "periodic/chart_resume.h"

/* The cap's points as chart_fill_rows locates them, before they are given to their branches. */
typedef struct cap {
    whirl_chart_point *p;
    int n, size;
} cap;

static int keep(void *data, const whirl_chart_point *point)
{
    cap *c = data;
    if (c->n == c->size) {
        const int size = c->size ? 2 * c->size : 16;
        whirl_chart_point *p = realloc(c->p, (size_t)size * sizeof *p);
        if (p == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for a fold of the chart");
        c->p = p, c->size = size;
    }
    c->p[c->n++] = *point;
    return GSL_SUCCESS;
}

/* The function of lo's family at (omega, amp) into *f. */
static int value(chart *ch, const chart_curve *lo, double omega, double amp, double *f)
{
    chart_ws *s = &ch->ws[0];
    s->mode = lo->mode, s->kind = lo->kind, s->sub = lo->sub;
    s->amp = amp;
    return chart_fine_rate(omega, s, f);
}

/* 1 in *fold if the new edges lo and hi (lo->a1 < hi->a1) are the two branches of one edge that
 * turned back between the rates w0 and this one (file header). */
static int is_fold(chart *ch, const chart_curve *lo, const chart_curve *hi, double w0, int *fold)
{
    const double mid = 0.5 * (lo->a1 + hi->a1);
    double f0[3], f1;
    int status = value(ch, lo, w0, lo->a1, &f0[0]);
    if (status == GSL_SUCCESS) status = value(ch, lo, w0, mid, &f0[1]);
    if (status == GSL_SUCCESS) status = value(ch, lo, w0, hi->a1, &f0[2]);
    if (status == GSL_SUCCESS) status = value(ch, lo, ch->omega, mid, &f1);
    *fold = status == GSL_SUCCESS && (f0[0] < 0) == (f0[1] < 0) &&
            (f0[1] < 0) == (f0[2] < 0) && (f1 < 0) != (f0[1] < 0);
    return status;
}

/* The next edge above lo of its function if it is new at this rate (NULL if none, or if an
 * older one is next). The two may carry other curves' numbers (a thin tongue's edges share
 * theirs, chart_pair): the cap's points go to those. */
static chart_curve *above(chart *ch, int first, const chart_curve *lo)
{
    chart_curve *best = NULL;
    for (int i = 0; i < ch->count; i++) {
        chart_curve *q = &ch->curves[i];
        if (q == lo || !q->found || q->mode != lo->mode || q->kind != lo->kind ||
            q->sub != lo->sub || !(q->a1 > lo->a1) || (best && !(q->a1 < best->a1)))
            continue;
        best = q;
    }
    return best && best - ch->curves >= first ? best : NULL; /* new at this rate */
}

/* The previous amplitude of a branch at (w, a) for the follower's linear step to the next rate,
 * w + dw, to land on the fold's law: near its turning point (wt, at) an edge is a parabola
 * omega - wt ~ (A - at)^2, so A = at + (a - at) sqrt((omega - wt) / (w - wt)) (a chord
 * overshoots: the branch is steepest at the turn); within amp_max of a. */
static double branch_a0(double a, double w, double dw, double wt, double at, double amp_max)
{
    const double next = at + (a - at) * sqrt((w + dw - wt) / (w - wt));
    const double a0 = 2 * a - next;
    return isfinite(a0) && w > wt ? fmax(a - amp_max, fmin(a + amp_max, a0)) : NAN;
}

int chart_fold_caps(chart *ch, int first, int column, whirl_chart_row_fn row, void *row_data)
{
    if (column == 0) return GSL_SUCCESS;
    const double w0 = chart_grid(ch->p.omega_min, ch->p.omega_max, ch->p.columns, column - 1);
    const double da = (ch->p.amp_max - chart_amp_floor(ch)) / (ch->p.rows - 1);
    cap c = {NULL, 0, 0};
    int status = GSL_SUCCESS;
    for (int i = first; status == GSL_SUCCESS && i < ch->count; i++) {
        chart_curve *lo = &ch->curves[i];
        if (!lo->found) continue;
        chart_curve *hi = above(ch, first, lo);
        int fold = 0;
        if (hi == NULL || hi->a1 - lo->a1 <= 2 * da) continue; /* no row between */
        status = is_fold(ch, lo, hi, w0, &fold);
        if (status || !fold) continue;
        /* the rows between, from the lower branch up; their points by the rate from w0 on the
           side of the lower branch's point (chart_fill_rows's slope from it) */
        c.n = 0;
        double last = lo->a1;
        status = chart_fill_rows(ch, lo, column, w0, ch->omega, lo->a1 + da, da, lo->a1, hi->a1,
                                 &last, keep, &c);
        int turn = 0; /* the cap's point of the lowest rate: the turning point's row */
        for (int k = 1; k < c.n; k++)
            if (c.p[k].omega < c.p[turn].omega) turn = k;
        /* each branch's previous amplitude on the fold's law (branch_a0): the follower's first
           step then knows the branch's slope, leaves the range where the branch does, and its
           bend test keeps it off the other branch (both are roots of one function) */
        if (c.n > 0) {
            const double wt = c.p[turn].omega, at = c.p[turn].amplitude, dw = ch->omega - w0;
            lo->a0 = branch_a0(lo->a1, ch->omega, dw, wt, at, ch->p.amp_max);
            hi->a0 = branch_a0(hi->a1, ch->omega, dw, wt, at, ch->p.amp_max);
        }
        for (int k = 0; status == GSL_SUCCESS && k < c.n; k++) {
            c.p[k].curve = k <= turn ? lo->id : hi->id;
            status = row ? row(row_data, &c.p[k]) : GSL_SUCCESS;
            if (k == turn && status == GSL_SUCCESS) { /* the turning point ends both lines */
                c.p[k].curve = hi->id;
                status = row ? row(row_data, &c.p[k]) : GSL_SUCCESS;
            }
        }
    }
    free(c.p);
    return status;
}
