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

/* The comment lines and the columns' line; the "# found:" lines with r (NULL: the header
 * --resume matches). */
static void write_head(FILE *fp, const periodic_ellipse_args *a,
                       const whirl_ellipse_chart_params *p, const ellipse_rows *r, int points,
                       int curves, int none, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(a->units, CLI_UNIT_LENGTH);
    fprintf(fp, "# chart: the ellipticity of the hand-swung chain: pivot (a cos wt, a (1 - e) "
            "sin wt, 0), a=%s %s; the steady shape of mode %d (side %d) followed in e from the "
            "circle to where it is lost; links=%d steps=%d arc_step=%s\n",
            CLI_NUM(p->radius * len), cli_units_name(a->units, CLI_UNIT_LENGTH), p->mode,
            p->side, a->links, p->steps, CLI_NUM(p->step));
    fprintf(fp, "# omega from %s to %s %s (%d rates); e up to %s\n",
            CLI_NUM(p->omega_min * rate), CLI_NUM(p->omega_max * rate),
            cli_units_name(a->units, CLI_UNIT_RATE), p->columns, CLI_NUM(p->e_max));
    if (r) {
        fprintf(fp, CHART_FOUND "points=%d curves=%d; none: %d rates stable up to e=%s; failed: "
                "%ld continuations (stopped before an event: no row)\n", points, curves, none,
                CLI_NUM(p->e_max), chart_file_state_value(&r->file, "failed", 0));
        if (stopped)
            fprintf(fp, CHART_FOUND "interrupted after %d of %d rates: the points found until "
                    "then (whirl periodic --resume goes on)\n", r->file.done, p->columns);
    }
    fprintf(fp, "# event: how the shape is lost (fold, branch: +1; period-doubling: -1; torus: "
            "two pairs meet on the unit circle); rows with ellipticity 0 end a curve where the "
            "circle's shape itself changes stability; err: in e, or in omega at an end\n");
    cli_units_comment(fp, a->units);
    fprintf(fp, "curve,event,omega,ellipticity,err\n");
}

static void write_rows(FILE *fp, const periodic_ellipse_args *a,
                       const whirl_ellipse_chart_params *p, const ellipse_rows *r, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const size_t kept = r->file.n_kept, n = kept + (stopped ? r->file.rows_done : r->n);
    int curves = 0, none = 0, prev = -1;
    for (size_t i = 0; i < n; i++) { /* the rows read back, then those computed */
        const int curve = i < kept ? r->file.kept[i].curve - 1 : r->p[i - kept].curve;
        curves += i == 0 || curve != prev;
        none += i < kept ? r->file.kept[i].value == p->e_max && !r->file.kept[i].end
                         : r->p[i - kept].event == WHIRL_CYCLE_POINT;
        prev = curve;
    }
    write_head(fp, a, p, r, (int)n, curves, none, stopped);
    for (size_t i = 0; i < n; i++) {
        const int curve = i < kept ? r->file.kept[i].curve - 1 : r->p[i - kept].curve;
        if (i > 0 && curve != prev) fputc('\n', fp);
        prev = curve;
        if (i < kept) {
            fputs(r->file.kept[i].line, fp);
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

/* The check of a row read back: its fields, a rate in the chart's range, an ellipticity up to
 * e_max. */
typedef struct row_ctx {
    double omega_lo, omega_hi, e_max; /* the file's units, the rates widened by 1e-12 */
} row_ctx;

static const char *check_row(void *data, const char *line, chart_kept *k)
{
    const row_ctx *c = data;
    char event[24];
    double err;
    int end = -1;
    if (sscanf(line, "%d,%23[a-z-],%lf,%lf,%lf%n", &k->curve, event, &k->omega, &k->value, &err,
               &end) != 5 || line[end] != '\n')
        return "not a row curve,event,omega,ellipticity,err";
    int known = strcmp(event, "none") == 0;
    for (int e = WHIRL_CYCLE_FOLD; e <= WHIRL_CYCLE_TORUS; e++)
        known |= strcmp(event, whirl_cycle_event_name((whirl_cycle_event)e)) == 0;
    if (!known) return "an event not fold, branch, period-doubling, torus or none";
    if (k->curve < 1) return "a curve number below 1";
    if (!(k->omega >= c->omega_lo && k->omega <= c->omega_hi)) return "a rate outside the chart";
    if (!(k->value >= 0 && k->value <= c->e_max)) return "an ellipticity outside 0..e_max";
    if (!(err >= 0)) return "a negative error";
    k->end = k->value == 0 && strcmp(event, "none") != 0;
    if (strcmp(event, "none") == 0 && k->value != c->e_max) return "none below e_max";
    return NULL;
}

/* The rows read back against the state: a curve it has begun, a rate it has finished (a row of
 * a rate: one of the grid's, once; an end: between two of them). */
static int check_kept(ellipse_rows *r, const whirl_ellipse_chart_params *p, double rate)
{
    const long curve = chart_file_state_value(&r->file, "curve", -2);
    const int done = r->file.done;
    if (curve < -1 || done < 0 || done > p->columns) return 0; /* the library refuses it */
    char *seen = calloc((size_t)done + 1, 1);
    if (seen == NULL) return cli_error(r->file.cmd, "out of memory");
    int rc = 0;
    for (size_t i = 0; i < r->file.n_kept && rc == 0; i++) {
        const chart_kept *k = &r->file.kept[i];
        const char *why = NULL;
        int j = 0;
        if (k->curve > curve + 1) why = "a curve the chart's state has not begun";
        else if (k->end) {
            if (done == 0 || k->omega > chart_grid(p->omega_min, p->omega_max, p->columns,
                                                  done - 1) * rate * (1 + 1e-12))
                why = "an end beyond the rates the state has finished";
        } else {
            while (j < done && strcmp(CLI_NUM(chart_grid(p->omega_min, p->omega_max, p->columns,
                                                       j) * rate),
                                      CLI_NUM(k->omega)) != 0)
                j++;
            if (j == done) why = "a rate not on the grid of the rates the state has finished";
            else if (seen[j]++) why = "a second row of its rate";
        }
        if (why) rc = chart_file_refuse(&r->file, k, why);
    }
    free(seen);
    return rc;
}

/* The header --resume matches, into *text (to free); 0 or 1. */
static int expected_head(const cli_command *cmd, const periodic_ellipse_args *a,
                         const whirl_ellipse_chart_params *p, char **text)
{
    size_t len = 0;
    FILE *mem = open_memstream(text, &len);
    if (mem == NULL) return cli_error(cmd, "out of memory");
    write_head(mem, a, p, NULL, 0, 0, 0, 0);
    return fclose(mem) == 0 ? 0 : cli_error(cmd, "out of memory");
}

int periodic_chart_ellipse(const cli_command *cmd, const periodic_ellipse_args *a)
{
    whirl_ellipse_chart_params p = {.radius = a->eps, .mode = a->mode, .side = a->side,
                                    .omega_min = a->omega_min, .omega_max = a->omega_max,
                                    .columns = a->columns, .e_max = a->e_max,
                                    .steps = a->steps, .step = a->arc_step};
    if (!(a->omega_max > a->omega_min))
        return cli_error(cmd, "--omega-max must exceed --omega-min");
    /* the defaults as the chart takes them (whirl_ellipse_chart_params), for the comment lines */
    if (p.columns == 0) p.columns = 50;
    if (p.e_max == 0) p.e_max = 1;
    if (p.mode == 0) p.mode = 2;
    if (p.steps == 0) p.steps = 400;
    if (p.step == 0) p.step = 0.01;
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    row_ctx ctx = {.omega_lo = p.omega_min * rate * (1 - 1e-12),
                   .omega_hi = p.omega_max * rate * (1 + 1e-12), .e_max = p.e_max};
    ellipse_rows r = {.after = cli_progress_after(), .last = {.column = -1}};
    char *head = NULL;
    int rc = expected_head(cmd, a, &p, &head);
    if (rc == 0) rc = chart_file_open(cmd, &r.file, a->output, a->resume, head, check_row, &ctx);
    if (rc == 0 && a->resume) rc = check_kept(&r, &p, rate);
    free(head);
    whirl_chain *c;
    cli_out out;
    char *state;
    rc = chart_file_start(&r.file, rc, a->links, a->resume, a->units, &c, &out, &state);
    if (rc) return rc;
    cli_catch_interrupts();
    cli_progress_begin(&r.line, cmd, "", 0, 0);
    const int status = a->resume && state == NULL
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
