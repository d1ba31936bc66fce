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

/* The header (periodic/chart_file.h) with the "# found:" lines of the chart written. */
static void write_head(FILE *fp, const periodic_chart_args *a, const whirl_chart_params *p,
                       size_t points, int curves, const chart_rows *rows, int stopped)
{
    char found[320];
    int len = snprintf(found, sizeof found, CHART_FOUND "points=%zu curves=%d\n", points, curves);
    if (stopped)
        snprintf(found + len, sizeof found - (size_t)len, CHART_FOUND "interrupted after %d of "
                 "%d rates: the points found until then (whirl periodic --resume goes on)\n",
                 rows->file.done, p->columns);
    const chart_units u = chart_file_units(a->units);
    chart_vertical_head(fp, p, a->links, a->drag, &u, found);
}

static int write_chart(FILE *fp, const periodic_chart_args *a, const whirl_chart_params *p,
                       chart_rows *r, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(a->units, CLI_UNIT_LENGTH);
    const size_t computed = stopped ? r->file.rows_done : r->n, n = r->file.rd.n_kept + computed;
    chart_row *rows = malloc((n + 1) * sizeof *rows);
    if (rows == NULL) return 1;
    for (size_t i = 0; i < r->file.rd.n_kept; i++) rows[i] = (chart_row){.k = &r->file.rd.kept[i]};
    for (size_t i = 0; i < computed; i++)
        rows[r->file.rd.n_kept + i] = (chart_row){.p = r->p[i], .seq = i};
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

int periodic_chart_vertical(const cli_command *cmd, const periodic_chart_args *a)
{
    whirl_chart_params p = {.inverted = a->inverted, .omega_min = a->omega_min,
                            .omega_max = a->omega_max, .columns = a->columns,
                            .amp_min = a->amp_min, .amp_max = a->amp_max, .rows = a->rows,
                            .steps = a->steps, .tol = a->tol};
    chart_vertical_defaults(&p); /* as the chart takes them, for the comment lines */
    chart_rows r = {.after = cli_progress_after(), .column = -1};
    int rc = chart_file_open(cmd, &r.file, a->output, a->resume);
    if (rc == 0 && a->resume && r.file.lock.fp) {
        const chart_units u = chart_file_units(a->units);
        rc = chart_file_read(&r.file, chart_vertical_read(&r.file.rd, r.file.lock.fp, a->output,
                                                          &p, a->links, a->drag, &u));
    }
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
