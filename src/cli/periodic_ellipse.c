/* whirl periodic --chart ellipse: the ellipticity chart of the hand-swung chain
 * (whirl_chart_ellipse): per rate, how far the circle of radius --eps may be flattened into the
 * ellipse of semi-axes eps and eps (1 - e) before the steady shape of --mode is lost.
 *
 * Output: comment lines (the drive, the mode, the rates, the rows' count), the "# units:" line,
 * then the CSV curve,event,omega,ellipticity,err: per rate stable at e = 0 the first event
 * (fold, branch, period-doubling, torus) at e_crit with its error estimate in e, or "none" at
 * --e-max where the shape survives up to it; per end of a curve on e = 0 (the circle's own change
 * of stability between two rates) the event with its error estimate in omega. Rows by rate, a
 * blank line between curves; at the end the "# state:" line (chart_file.h). Ctrl-C keeps the
 * rows of the rates finished (a "# found:" line says where it stopped; exit status 130), and
 * --resume computes only the others: what the next rate needs of those before is the state. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/chart_file.h"
#include "cli/periodic_cli.h"
#include "periodic/chart_resume.h"
#include "whirl/periodic.h"

typedef struct ellipse_rows {
    whirl_ellipse_point *p;
    size_t n, cap;
    cli_progress_state line;
    double after;
    whirl_ellipse_chart_progress last;
    chart_file file;
} ellipse_rows;

static int keep(void *data, const whirl_ellipse_point *point)
{
    ellipse_rows *r = data;
    if (r->n == r->cap) {
        const size_t cap = r->cap ? 2 * r->cap : 64;
        whirl_ellipse_point *p = realloc(r->p, cap * sizeof *p);
        if (p == NULL) return GSL_ENOMEM;
        r->p = p, r->cap = cap;
    }
    r->p[r->n++] = *point;
    return 0;
}

static void tick(void *data, const whirl_ellipse_chart_progress *p)
{
    ellipse_rows *r = data;
    r->last = *p;
    if (!r->line.drawn && cli_wall_seconds() - r->line.start < r->after) return;
    cli_progress_text(&r->line, "rate %d of %d, %d curves, %ld points, e %.4g", p->column + 1,
                      p->columns, p->curves, p->points, p->parameter);
}

static int save(void *data, int done, const char *state)
{
    ellipse_rows *r = data;
    return chart_file_save(&r->file, done, state, r->n);
}

/* The header (periodic/chart_file.h) with the "# found:" lines of the chart written. */
static void write_head(FILE *fp, const periodic_ellipse_args *a,
                       const whirl_ellipse_chart_params *p, const ellipse_rows *r, int points,
                       int curves, int none, int stopped)
{
    char found[480], e[WHIRL_FORMAT_MAX];
    int len = snprintf(found, sizeof found, CHART_FOUND "points=%d curves=%d; none: %d rates "
                       "stable up to e=%s; failed: %ld continuations (stopped before an event: "
                       "no row)\n", points, curves, none, whirl_format_double(e, p->e_max),
                       chart_state_value(r->file.state, "failed", 0));
    if (stopped)
        snprintf(found + len, sizeof found - (size_t)len, CHART_FOUND "interrupted after %d of "
                 "%d rates: the points found until then (whirl periodic --resume goes on)\n",
                 r->file.done, p->columns);
    const chart_units u = chart_file_units(a->units);
    chart_ellipse_head(fp, p, a->links, &u, found);
}

static void write_rows(FILE *fp, const periodic_ellipse_args *a,
                       const whirl_ellipse_chart_params *p, const ellipse_rows *r, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const size_t kept = r->file.rd.n_kept, n = kept + (stopped ? r->file.rows_done : r->n);
    int curves = 0, none = 0, prev = -1;
    for (size_t i = 0; i < n; i++) { /* the rows read back, then those computed */
        const int curve = i < kept ? r->file.rd.kept[i].curve - 1 : r->p[i - kept].curve;
        curves += i == 0 || curve != prev;
        none += i < kept ? r->file.rd.kept[i].value == p->e_max && !r->file.rd.kept[i].end
                         : r->p[i - kept].event == WHIRL_CYCLE_POINT;
        prev = curve;
    }
    write_head(fp, a, p, r, (int)n, curves, none, stopped);
    for (size_t i = 0; i < n; i++) {
        const int curve = i < kept ? r->file.rd.kept[i].curve - 1 : r->p[i - kept].curve;
        if (i > 0 && curve != prev) fputc('\n', fp);
        prev = curve;
        if (i < kept) {
            fputs(r->file.rd.kept[i].line, fp);
            continue;
        }
        const whirl_ellipse_point *q = &r->p[i - kept];
        fprintf(fp, "%d,%s,%s,%s,%s\n", q->curve + 1,
                q->event == WHIRL_CYCLE_POINT ? "none" : whirl_cycle_event_name(q->event),
                CLI_NUM(q->omega * rate), CLI_NUM(q->ellipticity),
                CLI_NUM(q->column < 0 ? q->err * rate : q->err));
    }
    chart_file_write_state(&r->file, fp);
}

int periodic_chart_ellipse(const cli_command *cmd, const periodic_ellipse_args *a)
{
    whirl_ellipse_chart_params p = {.radius = a->eps, .mode = a->mode, .side = a->side,
                                    .omega_min = a->omega_min, .omega_max = a->omega_max,
                                    .columns = a->columns, .e_max = a->e_max,
                                    .steps = a->steps, .step = a->arc_step};
    if (!(a->omega_max > a->omega_min))
        return cli_error(cmd, "--omega-max must exceed --omega-min");
    chart_ellipse_defaults(&p); /* as the chart takes them, for the comment lines */
    ellipse_rows r = {.after = cli_progress_after(), .last = {.column = -1}};
    int rc = chart_file_open(cmd, &r.file, a->output, a->resume);
    if (rc == 0 && a->resume && r.file.lock.fp) {
        const chart_units u = chart_file_units(a->units);
        rc = chart_file_read(&r.file, chart_ellipse_read(&r.file.rd, r.file.lock.fp, a->output,
                                                         &p, a->links, &u));
    }
    whirl_chain *c;
    cli_out out;
    char *state;
    rc = chart_file_start(&r.file, rc, a->links, a->resume, a->units, &c, &out, &state);
    if (rc) return rc;
    cli_catch_interrupts();
    cli_progress_begin(&r.line, cmd, "", 0, 0);
    const int status =
        a->resume && state == NULL
            ? GSL_ENOMEM
            : whirl_chart_ellipse_resume(c, &p, state, keep, &r, tick, &r, save, &r);
    cli_progress_clear(&r.line);
    if (status == GSL_SUCCESS || status == WHIRL_EINTERRUPTED) {
        write_rows(out.fp, a, &p, &r, status == WHIRL_EINTERRUPTED);
        rc = chart_file_commit(&r.file, &out);
    } else
        cli_out_abort(&out);
    rc = chart_file_finish(&r.file, status, rc, p.columns, state != NULL, a->units);
    free(state);
    free(r.p);
    whirl_chain_free(c);
    chart_file_free(&r.file);
    return rc;
}
