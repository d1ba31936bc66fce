/* The ellipticity chart of the hand-swung chain (whirl/periodic.h, whirl_chart_ellipse): how far
 * from a circle can the hand go before a steady shape of the circle drive is lost?
 *
 * The pivot on the ellipse (a cos wt, b sin wt, 0) with b = a (1 - e): e = 0 is the circle drive
 * of radius a, whose periodic motion is the steady shape of mode K turning with the hand (its
 * multipliers exp(lambda T) of the steady linearisation), e = 1 the line along x. At each rate
 * of the chart the motion is started from the steady shape at e = 0 (whirl_stability_driven_mode,
 * the same shape whirl driven gives) and, if it is stable there, followed in e by
 * whirl_periodic_path (WHIRL_CYCLE_ELLIPTICITY: the circle's y terms scaled by 1 - e) up to the
 * first event, where it is lost: a fold of cycles or a branch point (+1), a period doubling (-1)
 * or a torus (two pairs meet on the unit circle and leave it), each located to the
 * continuation's event_tol in the arclength with its error estimate in e. That is e_crit(omega).
 *
 * The curve ends on e = 0 where the steady shape itself changes stability: between two rates
 * of which one is stable at e = 0 and the other not (or has no shape of mode K), the circle's
 * motion is followed in the rate from the stable one (WHIRL_CYCLE_OMEGA, e = 0) and its first
 * event is the end, located in omega as the events are. Inside the window e_crit may also come
 * down to 0: where a pair of the circle's multipliers sits at -1 (an eigenvalue of the steady
 * linearisation at i omega / 2: a parametric resonance of the ellipse's second harmonic in the
 * rotating frame) or two pairs meet on the circle, any ellipticity opens a tongue. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "periodic/chart_resume.h"
#include "periodic/periodic_internal.h"
#include "whirl/stability.h"

#define COLUMNS_DEFAULT 50
#define E_MAX_DEFAULT 1.0
/* The continuation's largest step: an event is a sign change of a test between two points, and
 * a tongue entered and left within one step is passed over. N = 2, a = 0.05, mode 2 at
 * omega = 3.92: no event with 0.05, the torus at e = 0.0071857861 with 0.01 and 0.002 alike. */
#define STEP_DEFAULT 0.01
#define STOP 1001 /* a row callback's status: the first event is found (not a whirl status) */

int whirl_periodic_start_steady(whirl_periodic *w, int mode, int side, double *y)
{
    if (w == NULL || y == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_periodic_start_steady: NULL argument");
    const double r = w->path.c[0][0];
    whirl_pivot_path circle;
    if (w->dim != 3 || !(r > 0) || whirl_pivot_circle(&circle, w->path.omega, r) != GSL_SUCCESS ||
        memcmp(&circle, &w->path, sizeof circle) != 0)
        return whirl_fail(GSL_EINVAL, "a steady start needs the circle drive (a circle of "
                          "radius > 0) in 3D");
    if (side != 1 && side != -1)
        return whirl_fail(GSL_EINVAL, "the steady start's side must be 1 or -1, got %d", side);
    whirl_stability *st = whirl_stability_alloc(w->n);
    double *links = malloc(3 * w->n * sizeof *links);
    if (st == NULL || links == NULL) {
        whirl_stability_free(st);
        free(links);
        return whirl_fail(GSL_ENOMEM, "out of memory for the steady start");
    }
    /* the hand-swung chain's shape with w's drag (whirl_driven_mode; none without) */
    const whirl_model model = {.chain = w->chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                               .omega = w->path.omega, .drive_radius = r, .air_drag = w->drag,
                               .air_drag_quadratic = w->drag2, .internal_damping = w->damping};
    double growth;
    int status = whirl_stability_driven_mode(st, &model, mode, side, NULL, &growth);
    if (status == GSL_SUCCESS) {
        const double *x, *yy, *z;
        whirl_stability_nodes(st, &x, &yy, &z);
        status = whirl_shape_links(w->n, x, yy, z, links);
    }
    if (status == GSL_SUCCESS)
        status = whirl_dyn_state_from_shape(w->dyn, 0, links, w->path.omega, y);
    free(links);
    whirl_stability_free(st);
    return status;
}

/* What a continuation saw: the start's verdict, then its first event. */
typedef struct first_event {
    int rows;
    int stable;              /* the start is not unstable */
    int found;
    whirl_cycle_point event; /* the first event (its pointers not kept) */
} first_event;

static int on_row(void *data, const whirl_cycle_point *pt)
{
    first_event *f = data;
    if (f->rows++ == 0) {
        f->stable = pt->verdict != WHIRL_FLOQUET_UNSTABLE;
        return f->stable ? GSL_SUCCESS : STOP;
    }
    if (pt->event == WHIRL_CYCLE_POINT) return GSL_SUCCESS;
    f->found = 1;
    f->event = *pt;
    return STOP;
}

typedef struct ellipse_chart {
    whirl_ellipse_chart_params p;
    whirl_periodic *w;
    double *y;
    whirl_ellipse_chart_progress progress;
    whirl_ellipse_chart_tick_fn tick;
    void *tick_data;
} ellipse_chart;

static void on_tick(void *data, const whirl_cycle_progress *cp)
{
    ellipse_chart *ch = data;
    ch->progress.parameter = cp->parameter;
    if (ch->tick) ch->tick(ch->tick_data, &ch->progress);
}

/* The circle's motion at omega from the steady shape, followed in parameter (e from 0 up to
 * e_max, or the rate from omega towards omega_to) to its first event into f. GSL_EDOM (no
 * message kept) if the steady shape of the mode does not exist at omega. */
static int follow(ellipse_chart *ch, double omega, whirl_cycle_parameter parameter,
                  double omega_to, first_event *f)
{
    whirl_pivot_path circle;
    int status = whirl_pivot_circle(&circle, omega, ch->p.radius);
    if (status) return status;
    periodic_set_path(ch->w, &circle);
    status = whirl_periodic_start_steady(ch->w, ch->p.mode, ch->p.side, ch->y);
    if (status == GSL_EDOM) return status;
    if (status) return status;
    const int e = parameter == WHIRL_CYCLE_ELLIPTICITY;
    const whirl_cycle_params cp = {
        .parameter = parameter, .min = e ? 0 : fmin(omega, omega_to),
        .max = e ? ch->p.e_max : fmax(omega, omega_to), .direction = e || omega_to > omega ? 1 : -1,
        .step = ch->p.step, .steps = ch->p.steps, .tol = ch->p.tol};
    *f = (first_event){0};
    status = whirl_periodic_path(ch->w, ch->y, &cp, on_row, f, on_tick, ch);
    return status == STOP ? GSL_SUCCESS : status;
}

/* A continuation's failure that ends one rate's work, not the chart's: no convergence, no
 * unique tangent, an event that could not be located. */
static int branch_failed(int status)
{
    return status == GSL_EMAXITER || status == GSL_ESING || status == GSL_EFAILED;
}

static int check_params(const whirl_chain *c, whirl_ellipse_chart_params *p)
{
    if (c == NULL) return whirl_fail(GSL_EINVAL, "whirl_chart_ellipse: needs a chain");
    if (p->mode == 0) p->mode = 2;
    if (p->side == 0) p->side = 1;
    if (p->columns == 0) p->columns = COLUMNS_DEFAULT;
    if (p->e_max == 0) p->e_max = E_MAX_DEFAULT;
    if (p->step == 0) p->step = STEP_DEFAULT;
    if (!(p->radius > 0) || !isfinite(p->radius))
        return whirl_fail(GSL_EINVAL, "the ellipse chart needs a radius > 0, finite, got %g",
                          p->radius);
    if (!(p->omega_min > 0) || !(p->omega_max > p->omega_min) || !isfinite(p->omega_max) ||
        p->omega_max > WHIRL_OMEGA_MAX)
        return whirl_fail(GSL_EINVAL, "the rates need 0 < omega_min < omega_max <= %g",
                          WHIRL_OMEGA_MAX);
    if (p->mode < 1 || (p->side != 1 && p->side != -1) || p->columns < 2 ||
        !(p->e_max > 0 && p->e_max <= 1))
        return whirl_fail(GSL_EINVAL, "the ellipse chart needs mode >= 1, side 1 or -1, "
                          "columns >= 2 and 0 < e_max <= 1");
    return GSL_SUCCESS;
}

static int emit(ellipse_chart *ch, whirl_ellipse_chart_row_fn row, void *row_data,
                const whirl_ellipse_point *pt)
{
    ch->progress.points++;
    return row ? row(row_data, pt) : GSL_SUCCESS;
}

/* The end of a curve on e = 0 between the rates w_stable (stable at e = 0) and w_other: the
 * circle's motion followed in the rate from w_stable, its first event. */
static int curve_end(ellipse_chart *ch, double w_stable, double w_other, int curve,
                     whirl_ellipse_chart_row_fn row, void *row_data)
{
    first_event f;
    int status = follow(ch, w_stable, WHIRL_CYCLE_OMEGA, w_other, &f);
    if (branch_failed(status)) {
        ch->progress.failed++;
        return GSL_SUCCESS;
    }
    if (status) return status;
    if (!f.found) return GSL_SUCCESS; /* the change lies in the shape's existence alone */
    const whirl_ellipse_point pt = {.event = f.event.event, .curve = curve, .column = -1,
                                    .omega = f.event.omega, .ellipticity = 0,
                                    .err = f.event.err, .max_modulus = f.event.max_modulus};
    return emit(ch, row, row_data, &pt);
}

/* The state after `done` rates handed to save (chart_resume.h). */
static int save_state(const ellipse_chart *ch, int done, int prev, int curve,
                      chart_save_fn save, void *save_data)
{
    if (save == NULL) return GSL_SUCCESS;
    char text[160];
    snprintf(text, sizeof text, "ellipse columns=%d prev=%d curve=%d failed=%d\n", done, prev,
             curve, ch->progress.failed);
    return save(save_data, done, text);
}

/* The state text into *done, *prev, *curve and ch->progress.failed. */
static int read_state(ellipse_chart *ch, const char *text, int *done, int *prev, int *curve)
{
    int len = -1;
    if (sscanf(text, "ellipse columns=%d prev=%d curve=%d failed=%d\n%n", done, prev, curve,
               &ch->progress.failed, &len) != 4 || len < 0 || text[len] != '\0')
        return whirl_fail(GSL_EINVAL, "state line 1: not 'ellipse columns=J prev=P curve=C "
                          "failed=F'");
    /* a rate before the first stable one has prev 0 and curve -1; each rate begins a curve at
       most, and fails at most twice (its continuation and a curve's end) */
    if (*done < 0 || *done > ch->p.columns || *prev < -1 || *prev > 1 ||
        (*prev == -1) != (*done == 0) || *curve < -1 || *curve >= *done ||
        (*prev == 1 && *curve < 0) || ch->progress.failed < 0 ||
        ch->progress.failed > 2 * *done)
        return whirl_fail(GSL_EINVAL, "state line 1: a count out of range");
    return GSL_SUCCESS;
}

static int columns(ellipse_chart *ch, const char *state, whirl_ellipse_chart_row_fn row,
                   void *row_data, chart_save_fn save, void *save_data)
{
    const whirl_ellipse_chart_params *p = &ch->p;
    int prev = -1; /* the previous rate: -1 none, 0 unstable at e = 0 or no shape, 1 stable */
    int curve = -1, start = 0;
    if (state) {
        const int status = read_state(ch, state, &start, &prev, &curve);
        if (status) return status;
    }
    double last = start > 0 ? chart_grid(p->omega_min, p->omega_max, p->columns, start - 1) : 0;
    int status = save_state(ch, start, prev, curve, save, save_data);
    if (status) return status;
    for (int j = start; j < p->columns; j++) {
        const double omega = chart_grid(p->omega_min, p->omega_max, p->columns, j);
        ch->progress.column = j;
        first_event f;
        status = follow(ch, omega, WHIRL_CYCLE_ELLIPTICITY, 0, &f);
        int stable = 0;
        if (status == GSL_EDOM) status = GSL_SUCCESS; /* no shape of the mode at this rate */
        else if (status == GSL_SUCCESS) stable = f.stable;
        else if (branch_failed(status)) {
            /* Newton's method at the start, or the branch before an event, did not converge
               (or an event could not be located): no row at this rate (counted) */
            ch->progress.failed++;
            stable = f.rows > 0 && f.stable, status = GSL_SUCCESS;
            f.rows = 0;
        }
        if (status) return status;
        if (stable && prev != 1) curve++;
        if (j > 0 && stable != prev) {
            status = curve_end(ch, stable ? omega : last, stable ? last : omega, curve, row,
                               row_data);
            if (status) return status;
        }
        if (stable && f.rows > 0) {
            const whirl_ellipse_point pt = {
                .event = f.found ? f.event.event : WHIRL_CYCLE_POINT, .curve = curve,
                .column = j, .omega = omega, .ellipticity = f.found ? f.event.parameter : p->e_max,
                .err = f.found ? f.event.err : 0, .max_modulus = f.found ? f.event.max_modulus : 1};
            if ((status = emit(ch, row, row_data, &pt))) return status;
        }
        ch->progress.curves = curve + 1;
        if (ch->tick) ch->tick(ch->tick_data, &ch->progress);
        prev = stable, last = omega;
        if ((status = save_state(ch, j + 1, prev, curve, save, save_data))) return status;
    }
    return GSL_SUCCESS;
}

int chart_ellipse_run(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                      const char *state, whirl_ellipse_chart_row_fn row, void *row_data,
                      whirl_ellipse_chart_tick_fn tick, void *tick_data, chart_save_fn save,
                      void *save_data)
{
    ellipse_chart ch = {.tick = tick, .tick_data = tick_data};
    if (params) ch.p = *params;
    int status = check_params(c, &ch.p);
    if (status) return status;
    ch.progress.columns = ch.p.columns;
    whirl_pivot_path circle;
    status = whirl_pivot_circle(&circle, ch.p.omega_max, ch.p.radius);
    if (status) return status;
    ch.w = whirl_periodic_alloc(c, 3, &circle);
    if (ch.w == NULL) return whirl_last_status();
    ch.y = malloc(ch.w->size * sizeof *ch.y);
    if (ch.y == NULL) status = whirl_fail(GSL_ENOMEM, "out of memory for the ellipse chart");
    else status = columns(&ch, state, row, row_data, save, save_data);
    free(ch.y);
    whirl_periodic_free(ch.w);
    return status;
}

int whirl_chart_ellipse(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                        whirl_ellipse_chart_row_fn row, void *row_data,
                        whirl_ellipse_chart_tick_fn tick, void *tick_data)
{
    return chart_ellipse_run(c, params, NULL, row, row_data, tick, tick_data, NULL, NULL);
}

int whirl_chart_ellipse_resume(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                               const char *state, whirl_ellipse_chart_row_fn row, void *row_data,
                               whirl_ellipse_chart_tick_fn tick, void *tick_data,
                               whirl_chart_save_fn save, void *save_data)
{
    return chart_ellipse_run(c, params, state, row, row_data, tick, tick_data, save, save_data);
}
