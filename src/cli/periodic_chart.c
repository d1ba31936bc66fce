/* whirl periodic --chart hanging|inverted: the stability chart of the chain shaken vertically
 * (whirl_chart_vertical; with --drag C, whirl_chart_vertical_damped) over
 * --omega-min..--omega-max (--omega-count rates) and --amp-min..--amp-max (--amp-rows amplitudes
 * scanned for new curves). The first comment line records the drag (only if not 0: a
 * conservative chart's file is as before), so --resume refuses a file of another drag.
 *
 * Output (chart_file.h): comment lines (the chain, the options that change a row, the range),
 * "# found:" lines (the counts; where a stopped chart stopped), the "# units:" line, then the
 * CSV curve,edge,omega,amplitude,err, one row per edge point (edge +1 or -1: the multiplier pair
 * passing there), the points of one curve by rate, a blank line between curves (gnuplot draws
 * each as a line), and the "# state:" lines. Ctrl-C stops it within a monodromy: the points of
 * the rates finished are written (exit status 130), and --resume computes only the others (the
 * chart hands its points out by rate: the rates finished are whole, and what the next rate needs
 * of them is the state). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/chart_file.h"
#include "cli/periodic_cli.h"
#include "periodic/chart_resume.h"
#include "whirl/periodic.h"

/* A row of the chart: read back (k) or computed (p, its place in the order found: seq). */
typedef struct chart_row {
    const chart_kept *k;
    whirl_chart_point p;
    size_t seq;
} chart_row;

typedef struct chart_rows {
    whirl_chart_point *p;
    size_t n, cap;
    cli_progress_state line;
    double after;
    int column, columns; /* the last rate finished (from 0; -1: none) and the count */
    chart_file file;
} chart_rows;

static int chart_keep(void *data, const whirl_chart_point *point)
{
    chart_rows *r = data;
    if (r->n == r->cap) {
        const size_t cap = r->cap ? 2 * r->cap : 256;
        whirl_chart_point *p = realloc(r->p, cap * sizeof *p);
        if (p == NULL) return GSL_ENOMEM;
        r->p = p;
        r->cap = cap;
    }
    r->p[r->n++] = *point;
    return 0;
}

static void chart_tick(void *data, const whirl_chart_progress *p)
{
    chart_rows *r = data;
    r->column = p->column;
    r->columns = p->columns;
    if (!r->line.drawn && cli_wall_seconds() - r->line.start < r->after) return;
    cli_progress_text(&r->line, "rate %d of %d, %d curves, %ld monodromies", p->column + 1,
                      p->columns, p->curves, p->monodromies);
}

static int chart_save(void *data, int done, const char *state)
{
    chart_rows *r = data;
    return chart_file_save(&r->file, done, state, r->n);
}

static int row_curve(const chart_row *r)
{
    return r->k ? r->k->curve - 1 : r->p.curve;
}

/* By curve, then by rate (a curve has one point per rate, and a tongue's tip between two): the
 * rows read back first (the rates before), in the file's order. */
static int chart_order(const void *a, const void *b)
{
    const chart_row *r = a, *s = b;
    const int c = row_curve(r), d = row_curve(s);
    if (c != d) return c < d ? -1 : 1;
    if (!r->k != !s->k) return r->k ? -1 : 1;
    if (r->k) return (r->k->lineno > s->k->lineno) - (r->k->lineno < s->k->lineno);
    const whirl_chart_point *p = &r->p, *q = &s->p;
    if (p->column != q->column) return p->column < q->column ? -1 : 1;
    if (p->omega != q->omega) return p->omega < q->omega ? -1 : 1;
    return (r->seq > s->seq) - (r->seq < s->seq);
}

/* The comment lines and the columns' line; the "# found:" lines with rows (NULL: the header
 * --resume matches). */
static void write_head(FILE *fp, const periodic_chart_args *a, const whirl_chart_params *p,
                       size_t points, int curves, const chart_rows *rows, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(a->units, CLI_UNIT_LENGTH);
    const char *ru = cli_units_name(a->units, CLI_UNIT_RATE);
    const char *lu = cli_units_name(a->units, CLI_UNIT_LENGTH);
    char drag[96] = "";
    if (a->drag > 0)
        snprintf(drag, sizeof drag, " drag=%s %s",
                 CLI_NUM(a->drag * cli_units_scale(a->units, CLI_UNIT_DRAG)),
                 cli_units_name(a->units, CLI_UNIT_DRAG));
    fprintf(fp, "# chart: the %s chain shaken vertically, A cos(omega t); links=%d steps=%d "
            "tol=%s %s%s; edge +1: a multiplier %s +1, -1: through -1 (period doubling)\n",
            p->inverted ? "inverted" : "hanging", a->links, p->steps, CLI_NUM(p->tol * len), lu,
            drag, a->drag > 0 ? "through" : "pair through");
    fprintf(fp, "# omega from %s to %s %s (%d rates); A from %s to %s %s (%d rows scanned)\n",
            CLI_NUM(p->omega_min * rate), CLI_NUM(p->omega_max * rate), ru, p->columns,
            CLI_NUM(p->amp_min * len), CLI_NUM(p->amp_max * len), lu, p->rows);
    if (rows) {
        fprintf(fp, CHART_FOUND "points=%zu curves=%d\n", points, curves);
        if (stopped)
            fprintf(fp, CHART_FOUND "interrupted after %d of %d rates: the points found until "
                    "then (whirl periodic --resume goes on)\n", rows->file.done, p->columns);
    }
    cli_units_comment(fp, a->units);
    fprintf(fp, "curve,edge,omega,amplitude,err\n");
}

static int write_chart(FILE *fp, const periodic_chart_args *a, const whirl_chart_params *p,
                       chart_rows *r, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(a->units, CLI_UNIT_LENGTH);
    const size_t computed = stopped ? r->file.rows_done : r->n, n = r->file.n_kept + computed;
    chart_row *rows = malloc((n + 1) * sizeof *rows);
    if (rows == NULL) return 1;
    for (size_t i = 0; i < r->file.n_kept; i++) rows[i] = (chart_row){.k = &r->file.kept[i]};
    for (size_t i = 0; i < computed; i++)
        rows[r->file.n_kept + i] = (chart_row){.p = r->p[i], .seq = i};
    qsort(rows, n, sizeof *rows, chart_order);
    int curves = 0;
    for (size_t i = 0; i < n; i++) curves += i == 0 || row_curve(&rows[i]) != row_curve(&rows[i - 1]);
    write_head(fp, a, p, n, curves, r, stopped);
    for (size_t i = 0; i < n; i++) {
        if (i > 0 && row_curve(&rows[i]) != row_curve(&rows[i - 1])) fputc('\n', fp);
        if (rows[i].k) {
            fputs(rows[i].k->line, fp);
            continue;
        }
        const whirl_chart_point *q = &rows[i].p;
        fprintf(fp, "%d,%d,%s,%s,%s\n", q->curve + 1,
                q->kind == WHIRL_FLOQUET_EDGE_PLUS_ONE ? 1 : -1, CLI_NUM(q->omega * rate),
                CLI_NUM(q->amplitude * len), CLI_NUM(q->err * len));
    }
    chart_file_write_state(&r->file, fp);
    free(rows);
    return 0;
}

/* The check of a row read back: its fields (the module has checked their count and that they
 * are finite), a rate and an amplitude in the chart's range. */
typedef struct row_ctx {
    double omega_lo, omega_hi, amp_hi; /* the file's units, widened by 1e-12 */
} row_ctx;

static const char *check_row(void *data, const char *line, chart_kept *k)
{
    const row_ctx *c = data;
    int edge, end = -1;
    double amp, err;
    if (sscanf(line, "%d,%d,%lf,%lf,%lf%n", &k->curve, &edge, &k->omega, &amp, &err, &end) != 5 ||
        line[end] != '\n')
        return "not a row curve,edge,omega,amplitude,err";
    if (k->curve < 1) return "a curve number below 1";
    if (edge != 1 && edge != -1) return "an edge other than 1 or -1";
    if (!(k->omega >= c->omega_lo && k->omega <= c->omega_hi)) return "a rate outside the chart";
    if (!(amp >= 0 && amp <= c->amp_hi)) return "an amplitude outside the chart";
    if (!(err >= 0)) return "a negative error";
    k->value = amp;
    return NULL;
}

/* The rows read back against the state: a curve it has begun, a rate it has reached (a point
 * near a tongue's tip lies up to a rate beyond the last one finished, chart.c). */
static int check_kept(chart_rows *r, const whirl_chart_params *p, double rate)
{
    const long count = chart_file_state_value(&r->file, "count", -1);
    const int done = r->file.done;
    if (count < 0 || done < 0 || done > p->columns) return 0; /* the library refuses the state */
    const double reach = done == 0 ? 0 : chart_grid(p->omega_min, p->omega_max, p->columns,
                                                       done < p->columns ? done : done - 1) * rate;
    for (size_t i = 0; i < r->file.n_kept; i++) {
        const chart_kept *k = &r->file.kept[i];
        if (k->curve > count)
            return chart_file_refuse(&r->file, k, "a curve the chart's state has not begun");
        if (k->omega > reach * (1 + 1e-12))
            return chart_file_refuse(&r->file, k, "a rate beyond those the state has finished");
    }
    return 0;
}

/* The header --resume matches, into *text (to free); 0 or 1. */
static int expected_head(const cli_command *cmd, const periodic_chart_args *a,
                         const whirl_chart_params *p, char **text)
{
    size_t len = 0;
    FILE *mem = open_memstream(text, &len);
    if (mem == NULL) return cli_error(cmd, "out of memory");
    write_head(mem, a, p, 0, 0, NULL, 0);
    return fclose(mem) == 0 ? 0 : cli_error(cmd, "out of memory");
}

int periodic_chart_vertical(const cli_command *cmd, const periodic_chart_args *a)
{
    whirl_chart_params p = {.inverted = a->inverted, .omega_min = a->omega_min,
                            .omega_max = a->omega_max, .columns = a->columns,
                            .amp_min = a->amp_min, .amp_max = a->amp_max, .rows = a->rows,
                            .steps = a->steps, .tol = a->tol};
    /* the defaults as the chart takes them (whirl_chart_params), for the comment lines */
    if (p.columns == 0) p.columns = 200;
    if (p.rows == 0) p.rows = 200;
    if (p.steps == 0) p.steps = 200;
    if (p.tol == 0) p.tol = 1e-10;
    if (p.amp_min == 0) p.amp_min = p.amp_max / p.rows;
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(a->units, CLI_UNIT_LENGTH);
    row_ctx ctx = {.omega_lo = p.omega_min * rate * (1 - 1e-12),
                   .omega_hi = p.omega_max * rate * (1 + 1e-12),
                   .amp_hi = p.amp_max * len * (1 + 1e-12)};
    chart_rows r = {.after = cli_progress_after(), .column = -1};
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
    int status = a->resume && state == NULL ? GSL_ENOMEM
                 : whirl_chart_vertical_resume(c, 2, &p, a->drag, state, chart_keep, &r,
                                               chart_tick, &r, chart_save, &r);
    cli_progress_clear(&r.line);
    if (status == GSL_SUCCESS || status == WHIRL_EINTERRUPTED)
        rc = write_chart(out.fp, a, &p, &r, status == WHIRL_EINTERRUPTED)
                 ? (cli_out_abort(&out), cli_error(cmd, "out of memory"))
                 : chart_file_commit(&r.file, &out);
    else
        cli_out_abort(&out);
    rc = chart_file_finish(&r.file, status, rc, p.columns, state != NULL, a->units);
    free(state);
    free(r.p);
    whirl_chain_free(c);
    chart_file_free(&r.file);
    return rc;
}
