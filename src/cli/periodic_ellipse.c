/* whirl periodic --chart ellipse: the ellipticity chart of the hand-swung chain
 * (whirl_chart_ellipse): per rate, how far the circle of radius --eps may be flattened into the
 * ellipse of semi-axes eps and eps (1 - e) before the steady shape of --mode is lost.
 *
 * Output: comment lines (the drive, the mode, the rates, the rows' count), the "# units:" line,
 * then the CSV curve,event,omega,ellipticity,err: per rate stable at e = 0 the first event
 * (fold, branch, period-doubling, torus) at e_crit with its error estimate in e, or "none" at
 * --e-max where the shape survives up to it; per end of a curve on e = 0 (the circle's own change
 * of stability between two rates) the event with its error estimate in omega. Rows by rate, a
 * blank line between curves. Ctrl-C keeps the rows found (a comment line says where it stopped;
 * exit status 130). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/periodic_cli.h"
#include "whirl/periodic.h"

typedef struct ellipse_rows {
    whirl_ellipse_point *p;
    size_t n, cap;
    cli_progress_state line;
    double after;
    whirl_ellipse_chart_progress last;
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

static void write_rows(FILE *fp, const periodic_ellipse_args *a,
                       const whirl_ellipse_chart_params *p, const ellipse_rows *r, int stopped)
{
    const double rate = cli_units_scale(a->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(a->units, CLI_UNIT_LENGTH);
    int curves = 0, none = 0;
    for (size_t i = 0; i < r->n; i++) {
        curves += i == 0 || r->p[i].curve != r->p[i - 1].curve;
        none += r->p[i].event == WHIRL_CYCLE_POINT;
    }
    fprintf(fp, "# chart: the ellipticity of the hand-swung chain: pivot (a cos wt, a (1 - e) "
            "sin wt, 0), a=%s %s; the steady shape of mode %d (side %d) followed in e from the "
            "circle to where it is lost; links=%d\n", CLI_NUM(p->radius * len),
            cli_units_name(a->units, CLI_UNIT_LENGTH), p->mode, p->side, a->links);
    fprintf(fp, "# omega from %s to %s %s (%d rates); e up to %s; points=%zu curves=%d; "
            "none: %d rates stable up to e=%s; failed: %d continuations (stopped before an "
            "event: no row)\n", CLI_NUM(p->omega_min * rate), CLI_NUM(p->omega_max * rate),
            cli_units_name(a->units, CLI_UNIT_RATE), p->columns, CLI_NUM(p->e_max), r->n, curves,
            none, CLI_NUM(p->e_max), r->last.failed);
    fprintf(fp, "# event: how the shape is lost (fold, branch: +1; period-doubling: -1; torus: "
            "two pairs meet on the unit circle); rows with ellipticity 0 end a curve where the "
            "circle's shape itself changes stability; err: in e, or in omega at an end\n");
    if (stopped)
        fprintf(fp, "# interrupted at rate %d of %d: the points found until then\n",
                r->last.column + 1, p->columns);
    cli_units_comment(fp, a->units);
    fprintf(fp, "curve,event,omega,ellipticity,err\n");
    for (size_t i = 0; i < r->n; i++) {
        const whirl_ellipse_point *q = &r->p[i];
        if (i > 0 && q->curve != r->p[i - 1].curve) fputc('\n', fp);
        fprintf(fp, "%d,%s,%s,%s,%s\n", q->curve + 1,
                q->event == WHIRL_CYCLE_POINT ? "none" : whirl_cycle_event_name(q->event),
                CLI_NUM(q->omega * rate), CLI_NUM(q->ellipticity),
                CLI_NUM(q->column < 0 ? q->err * rate : q->err));
    }
}

int periodic_chart_ellipse(const cli_command *cmd, const periodic_ellipse_args *a)
{
    whirl_ellipse_chart_params p = {.radius = a->eps, .mode = a->mode, .side = a->side,
                                    .omega_min = a->omega_min, .omega_max = a->omega_max,
                                    .columns = a->columns, .e_max = a->e_max,
                                    .steps = a->steps, .step = a->arc_step};
    if (!(a->omega_max > a->omega_min))
        return cli_error(cmd, "--omega-max must exceed --omega-min");
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)a->links, 0);
    if (c == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(a->units));
    cli_out out;
    if (cli_out_open(cmd, &out, a->output)) {
        whirl_chain_free(c);
        return 1;
    }
    cli_catch_interrupts();
    ellipse_rows r = {.after = cli_progress_after(), .last = {.column = -1}};
    cli_progress_begin(&r.line, cmd, "", 0, 0);
    const int status = whirl_chart_ellipse(c, &p, keep, &r, tick, &r);
    cli_progress_clear(&r.line);
    /* the defaults as the chart takes them, for the comment lines */
    if (p.columns == 0) p.columns = 50;
    if (p.e_max == 0) p.e_max = 1;
    if (p.mode == 0) p.mode = 2;
    int rc;
    if (status == GSL_SUCCESS || status == WHIRL_EINTERRUPTED) {
        const int stopped = status == WHIRL_EINTERRUPTED;
        write_rows(out.fp, a, &p, &r, stopped);
        rc = cli_out_commit(cmd, &out);
        if (rc == 0 && stopped)
            rc = (cli_error(cmd, "interrupted at rate %d of %d: the %zu points found until "
                            "then are written", r.last.column + 1, p.columns, r.n),
                  CLI_EXIT_INTERRUPTED);
    } else {
        cli_out_abort(&out);
        rc = cli_error(cmd, "%s", status == GSL_ENOMEM && whirl_last_status() != GSL_ENOMEM
                                      ? "out of memory for the chart's points"
                                      : CLI_LIBRARY_ERROR(a->units));
    }
    free(r.p);
    whirl_chain_free(c);
    return rc;
}
