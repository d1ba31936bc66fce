/* whirl periodic: the periodic motion of the N-link chain with its pivot on a periodic path
 * (include/whirl/periodic.h), found by Newton's method on the period map, and its Floquet
 * multipliers with their error estimates and the verdict.
 *
 * Output: comment lines (the path and the model; the period, Newton's iterations and residual,
 * the steps; the verdict with the growth per period and the e-folding time, the edge; the
 * reciprocal-pair error), the "# units:" line, then the CSV index,re,im,modulus,err of the
 * multipliers by decreasing modulus. Newton's method that does not converge: an error naming
 * the residual, no multipliers, exit status 1. Ctrl-C stops the solve (exit status 130).
 *
 * --chart hanging|inverted: the stability chart of the chain shaken vertically
 * (periodic_chart.c); --resume goes on with a chart stopped by Ctrl-C (chart_file.h).
 *
 * --chart ellipse: the ellipticity chart of the hand-swung chain (periodic_ellipse.c).
 *
 * --drag, --drag-quadratic (or --drag-cd), --damping: the damped and dragged chain
 * (whirl_periodic_alloc_model), the rows of whirl driven and whirl stability; its multipliers
 * are not in reciprocal pairs (the comment line says so) and a branch's torus test is the
 * dissipative one. --chart hanging|inverted takes --drag alone (whirl_chart_vertical_damped: a
 * drag proportional to the mass matrix keeps the modes apart); --chart ellipse none. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/periodic_cli.h"
#include "whirl/periodic.h"
#include "whirl/stability.h"

typedef struct periodic_options {
    const char *pivot, *start, *output, *chart;
    double omega, tol, arc_step, eps, e_max, drag, drag2, damping;
    cli_air air; /* --drag-cd */
    int links, dim, steps, max_iter, mode, side, differences, up, max_points;
    int mode_given, side_given, emax_given, resume;
    int omega_given, omin_given, omax_given, amin_given, amax_given;
    double omega_min, omega_max, amp_min, amp_max, edge_tol; /* --chart */
    int omega_count, amp_rows;
    cli_units units;
} periodic_options;

/* The progress line: which solve, Newton's iteration and residual, the monodromy's part done;
 * on a terminal once the run has taken cli_progress_after() seconds. */
typedef struct periodic_progress {
    cli_progress_state line;
    double after;
} periodic_progress;

static void show_progress(void *data, const whirl_periodic_progress *p)
{
    periodic_progress *pp = data;
    if (!pp->line.drawn && cli_wall_seconds() - pp->line.start < pp->after) return;
    if (p->monodromy > 0)
        cli_progress_text(&pp->line, "solve %d of 2, Newton iteration %d (residual %.2g), "
                          "monodromy %.0f%%", p->solve, p->iteration, p->residual,
                          100 * p->monodromy);
    else
        cli_progress_text(&pp->line, "solve %d of 2, Newton iteration %d (residual %.2g)",
                          p->solve, p->iteration, p->residual);
}

/* The steady shape of the circle drive (mode, tip on the pivot's side) as the start state. */
static int start_steady(const cli_command *cmd, const periodic_options *o,
                        const whirl_pivot_path *path, whirl_periodic *w, double *y)
{
    const double r = path->c[0][0];
    whirl_pivot_path circle;
    if (o->dim != 3 || whirl_pivot_circle(&circle, path->omega, r) != GSL_SUCCESS ||
        memcmp(&circle, path, sizeof circle) != 0 || !(r > 0))
        return cli_error(cmd, "--start steady needs --pivot circle:R with R > 0 and --dim 3 "
                         "(the steady shapes of the circle drive)");
    if (whirl_periodic_start_steady(w, o->mode, o->side, y) != GSL_SUCCESS)
        return cli_error(cmd, "the steady start: %s", CLI_LIBRARY_ERROR(&o->units));
    return 0;
}

/* 1 if the chain is damped or dragged. */
static int dissipative(const periodic_options *o)
{
    return o->drag > 0 || o->drag2 > 0 || o->damping > 0;
}

static void write_result(FILE *fp, const periodic_options *o, const whirl_periodic_result *r)
{
    const double time = cli_units_scale(&o->units, CLI_UNIT_TIME);
    char rate[96];
    fprintf(fp, "# periodic motion: pivot %s at omega %s, links=%d dim=%d start=%s\n", o->pivot,
            cli_rate_words(&o->units, o->omega, rate, sizeof rate), o->links, o->dim, o->start);
    fprintf(fp, "# monodromy by %s\n", o->differences ? "central differences" :
                                                        "the variational equations");
    if (dissipative(o))
        fprintf(fp, "# dissipation: drag=%s drag_quadratic=%s damping=%s\n",
                CLI_NUM(o->drag * cli_units_scale(&o->units, CLI_UNIT_DRAG)),
                CLI_NUM(o->drag2 * cli_units_scale(&o->units, CLI_UNIT_DRAG2)),
                CLI_NUM(o->damping * cli_units_scale(&o->units, CLI_UNIT_DAMPING)));
    fprintf(fp, "# period=%s %s; Newton %d iterations, residual %.3g; %d steps per period "
            "(errors from %d)\n", CLI_NUM(r->period * time), cli_units_name(&o->units, CLI_UNIT_TIME),
            r->iterations, r->residual, r->steps, r->steps / 2);
    if (r->verdict == WHIRL_FLOQUET_UNSTABLE)
        fprintf(fp, "# verdict=unstable growth=%.10g per period, e-folding %.6g periods (%s %s); "
                "edge=%s\n", r->growth, r->efold_periods, CLI_NUM(r->efold_time * time),
                cli_units_name(&o->units, CLI_UNIT_TIME), whirl_floquet_edge_name(r->edge));
    else if (r->verdict == WHIRL_FLOQUET_STABLE)
        fprintf(fp, "# verdict=stable; nearest edge=%s, |mu|max = 1 - %.6g\n",
                whirl_floquet_edge_name(r->edge), r->edge_distance);
    else
        fprintf(fp, "# verdict=%s; nearest edge=%s at %.6g rad\n",
                whirl_floquet_verdict_name(r->verdict), whirl_floquet_edge_name(r->edge),
                r->edge_distance);
    if (dissipative(o))
        fprintf(fp, "# |mu|max=%.15g +- %.2g; reciprocal-pair distance %.2g (the damped "
                "chain's multipliers are not in pairs: not an error); orbit change with the "
                "step %.2g\n", r->max_modulus, r->max_modulus_err, r->reciprocal_err,
                r->orbit_change);
    else
        fprintf(fp, "# |mu|max=%.15g +- %.2g; reciprocal-pair error %.2g (0 for the exact "
                "conservative chain); orbit change with the step %.2g\n", r->max_modulus,
                r->max_modulus_err, r->reciprocal_err, r->orbit_change);
    cli_units_comment(fp, &o->units);
    fprintf(fp, "index,re,im,modulus,err\n");
    for (size_t i = 0; i < r->count; i++) {
        const double mod = hypot(r->re[i], r->im[i]);
        fprintf(fp, "%zu,%s,%s,%s,%s\n", i + 1, CLI_NUM(r->re[i]), CLI_NUM(r->im[i]),
                CLI_NUM(mod), CLI_NUM(r->err[i]));
    }
}


static int run_chart(const cli_command *cmd, const periodic_options *o)
{
    const int inverted = strcmp(o->chart, "hanging") == 0    ? 0
                         : strcmp(o->chart, "inverted") == 0 ? 1
                         : strcmp(o->chart, "ellipse") == 0  ? 2
                                                             : -1;
    if (inverted < 0)
        return cli_error(cmd, "--chart must be hanging, inverted or ellipse, got '%s'",
                         o->chart);
    if (inverted == 2 && (o->drag > 0 || o->drag2 > 0 || o->damping > 0))
        return cli_error(cmd, "--chart ellipse is of the conservative chain: no --drag, "
                         "--drag-quadratic, --drag-cd or --damping");
    if (o->drag2 > 0 || o->damping > 0)
        return cli_error(cmd, "--chart %s takes linear air drag (--drag) alone: it keeps the "
                         "modes apart; the joints' --damping couples them (from 3 links on), and "
                         "quadratic drag damps at a rate that changes along the period", o->chart);
    if (inverted == 2) {
        if (!(o->eps > 0)) return cli_error(cmd, "--chart ellipse needs --eps");
        if (o->side != 1 && o->side != -1) return cli_error(cmd, "--side must be 1 or -1");
        if (o->amax_given || o->amin_given || o->amp_rows || o->edge_tol > 0)
            return cli_error(cmd, "--amp-min, --amp-max, --amp-rows and --edge-tol are for "
                             "--chart hanging or inverted");
        const periodic_ellipse_args a = {
            .links = o->links, .mode = o->mode_given ? o->mode : 2, .side = o->side,
            .columns = o->omega_count, .steps = o->steps, .eps = o->eps,
            .omega_min = o->omega_min, .omega_max = o->omega_max, .e_max = o->e_max,
            .arc_step = o->arc_step,
            .output = o->output, .units = &o->units, .resume = o->resume};
        return periodic_chart_ellipse(cmd, &a);
    }
    if (!o->amax_given) return cli_error(cmd, "--chart needs --amp-max");
    if (o->eps > 0 || o->e_max > 0 || o->mode_given || o->side_given || o->arc_step > 0)
        return cli_error(cmd, "--eps, --e-max, --mode, --side and --arc-step are for --chart "
                         "ellipse");
    if (!(o->omega_max > o->omega_min))
        return cli_error(cmd, "--omega-max must exceed --omega-min");
    if (!(o->amp_max > o->amp_min))
        return cli_error(cmd, "--amp-max must exceed --amp-min");
    const periodic_chart_args a = {
        .inverted = inverted, .links = o->links, .columns = o->omega_count, .rows = o->amp_rows,
        .steps = o->steps, .omega_min = o->omega_min, .omega_max = o->omega_max,
        .amp_min = o->amp_min, .amp_max = o->amp_max, .tol = o->edge_tol, .drag = o->drag,
        .output = o->output, .units = &o->units, .resume = o->resume};
    return periodic_chart_vertical(cmd, &a);
}

/* ---- a branch (--omega-min/--omega-max or --amp-min/--amp-max without --chart) ---- */

typedef struct branch_row {
    whirl_cycle_event event;
    double omega, amplitude, parameter, err, max_modulus, fold, flip, torus;
    whirl_floquet_verdict verdict;
    whirl_floquet_edge edge;
} branch_row;

typedef struct branch_rows {
    branch_row *r;
    size_t n, cap, events;
    cli_progress_state line;
    double after;
    whirl_cycle_parameter param; /* the rate, the amplitude or the ellipticity */
    int max_points; /* the branch's most points */
} branch_rows;

static int branch_keep(void *data, const whirl_cycle_point *p)
{
    branch_rows *b = data;
    if (b->n == b->cap) {
        const size_t cap = b->cap ? 2 * b->cap : 256;
        branch_row *r = realloc(b->r, cap * sizeof *r);
        if (r == NULL) return GSL_ENOMEM;
        b->r = r, b->cap = cap;
    }
    b->r[b->n++] = (branch_row){.event = p->event, .omega = p->omega, .amplitude = p->amplitude,
                                .parameter = p->parameter, .err = p->err, .max_modulus = p->max_modulus,
                                .fold = p->fold_test, .flip = p->flip_test,
                                .torus = p->torus_test,
                                .verdict = p->verdict, .edge = p->edge};
    b->events += p->event != WHIRL_CYCLE_POINT;
    return 0;
}

static void branch_tick(void *data, const whirl_cycle_progress *p)
{
    branch_rows *b = data;
    if (!b->line.drawn && cli_wall_seconds() - b->line.start < b->after) return;
    cli_progress_text(&b->line, "%ld points, %ld events, %s %.6g, step %.3g, corrector "
                      "iteration %d (residual %.2g)", p->points, p->events,
                      b->param == WHIRL_CYCLE_OMEGA       ? "omega"
                      : b->param == WHIRL_CYCLE_AMPLITUDE ? "A"
                                                          : "e",
                      p->parameter, p->step, p->iteration,
                      p->residual);
}

static int check_branch(const cli_command *cmd, const periodic_options *o, int branch)
{
    if (o->omin_given + o->amax_given + o->emax_given > 1)
        return cli_error(cmd, "a branch follows one parameter: --omega-min/--omega-max (the "
                         "rate), --amp-min/--amp-max (the amplitude) or --e-max (the "
                         "ellipticity), not two");
    if (o->side != 1 && o->side != -1) return cli_error(cmd, "--side must be 1 or -1");
    if (branch && o->differences)
        return cli_error(cmd, "--differences is for one motion: a branch forms its monodromies "
                         "from the variational equations");
    if (!branch && (o->up || o->arc_step > 0 || o->max_points > 0))
        return cli_error(cmd, "--up, --arc-step and --max-points need a branch (--omega-min and "
                         "--omega-max, --amp-max, or --e-max)");
    if (o->omin_given && !(o->omega_max > o->omega_min))
        return cli_error(cmd, "--omega-max must exceed --omega-min");
    if (o->amax_given && !(o->amp_max > o->amp_min))
        return cli_error(cmd, "--amp-max must exceed --amp-min");
    if (o->omin_given && o->omega_given && !(o->omega >= o->omega_min && o->omega <= o->omega_max))
        return cli_error(cmd, "--omega (the branch's start) is outside [--omega-min, --omega-max]");
    return 0;
}

static void write_branch(FILE *fp, const periodic_options *o, const branch_rows *b,
                         const char *stopped)
{
    const double rate = cli_units_scale(&o->units, CLI_UNIT_RATE);
    const double len = cli_units_scale(&o->units, CLI_UNIT_LENGTH);
    const int amp = b->param == WHIRL_CYCLE_AMPLITUDE, e = b->param == WHIRL_CYCLE_ELLIPTICITY;
    const double perr = amp ? len : e ? 1 : rate;
    char words[96];
    fprintf(fp, "# periodic branch: pivot %s, links=%d dim=%d start=%s; followed in the %s "
            "from %s towards %s values, %zu rows (%zu events), %s\n", o->pivot, o->links,
            o->dim, o->start,
            amp ? "amplitude" : e ? "ellipticity (the path's y terms scaled by 1 - e)" : "rate",
            amp ? CLI_NUM(b->n ? b->r[0].amplitude * len : 0)
            : e ? "0"
                : cli_rate_words(&o->units, o->omega, words, sizeof words),
            o->up || e ? "larger" : "smaller", b->n, b->events,
            stopped[0]                                     ? "stopped early"
            : b->n - b->events >= (size_t)b->max_points ? "ended at --max-points"
                                                         : "left the range");
    if (dissipative(o))
        fprintf(fp, "# damped chain: events fold (+1, the branch turns back), branch (+1, it "
                "goes on), period-doubling (-1), torus (a complex pair crosses the unit "
                "circle); fold_test = det(M - I), flip_test = det(M + I) as sign |det|^(1/m), "
                "torus_test = prod_{i<j} (mu_i mu_j - 1) over the multipliers as sign "
                "|P|^(1/factors); err: the event's error estimate in the parameter\n");
    else
        fprintf(fp, "# events: fold (+1, the branch turns back), branch (+1, it goes on), "
                "period-doubling (-1), torus (two pairs meet on the unit circle and leave it); "
                "fold_test = det(M - I), flip_test = det(M + I) as sign |det|^(1/m), "
                "torus_test = prod (rho_k - rho_l)^2 over the pairs (rho = mu + 1/mu) as sign "
                "|D|^(1/factors); err: the event's error estimate in the parameter\n");
    for (size_t i = 0; i < b->n; i++)
        if (b->r[i].event != WHIRL_CYCLE_POINT)
            fprintf(fp, "# %s omega=%s amplitude=%s%s%s err=%.2g\n",
                    whirl_cycle_event_name(b->r[i].event), CLI_NUM(b->r[i].omega * rate),
                    CLI_NUM(b->r[i].amplitude * len), e ? " ellipticity=" : "",
                    e ? CLI_NUM(b->r[i].parameter) : "", b->r[i].err * perr);
    if (stopped[0]) fprintf(fp, "# stopped (%s): the points found until then\n", stopped);
    cli_units_comment(fp, &o->units);
    fprintf(fp, "event,omega,amplitude,%smax_modulus,verdict,edge,fold_test,flip_test,"
            "torus_test,err\n", e ? "ellipticity," : "");
    for (size_t i = 0; i < b->n; i++) {
        const branch_row *r = &b->r[i];
        fprintf(fp, "%s,%s,%s,%s%s%s,%s,%s,%s,%s,%s,%s\n", whirl_cycle_event_name(r->event),
                CLI_NUM(r->omega * rate), CLI_NUM(r->amplitude * len),
                e ? CLI_NUM(r->parameter) : "", e ? "," : "", CLI_NUM(r->max_modulus),
                whirl_floquet_verdict_name(r->verdict), whirl_floquet_edge_name(r->edge),
                CLI_NUM(r->fold), CLI_NUM(r->flip), CLI_NUM(r->torus), CLI_NUM(r->err * perr));
    }
}

/* The branch through the start y of w: rows kept as they come, written at the end (also after
 * a stop request or a failure on the way: the rows so far, a comment line saying why). */
static int run_branch(const cli_command *cmd, const periodic_options *o, whirl_periodic *w,
                      double *y)
{
    branch_rows b = {.after = cli_progress_after(),
                     .param = o->amax_given   ? WHIRL_CYCLE_AMPLITUDE
                              : o->emax_given ? WHIRL_CYCLE_ELLIPTICITY
                                              : WHIRL_CYCLE_OMEGA,
                     .max_points = o->max_points ? o->max_points : 10000}; /* the default */
    const int e = b.param == WHIRL_CYCLE_ELLIPTICITY;
    const whirl_cycle_params p = {
        .parameter = b.param,
        .min = e ? 0 : o->amax_given ? o->amp_min : o->omega_min,
        .max = e ? o->e_max : o->amax_given ? o->amp_max : o->omega_max,
        .direction = o->up || e ? 1 : -1,
        .step = o->arc_step, .max_points = o->max_points, .steps = o->steps, .tol = o->tol,
        .max_iter = o->max_iter};
    cli_catch_interrupts();
    cli_progress_begin(&b.line, cmd, "", 0, 0);
    const int status = whirl_periodic_path(w, y, &p, branch_keep, &b, branch_tick, &b);
    cli_progress_clear(&b.line);
    char stopped[CLI_MESSAGE_MAX] = "";
    int rc = 0;
    if (status != GSL_SUCCESS) {
        if (b.n == 0 || status == GSL_ENOMEM) {
            free(b.r);
            if (status == WHIRL_EINTERRUPTED)
                return (cli_error(cmd, "interrupted: no periodic motion yet"),
                        CLI_EXIT_INTERRUPTED);
            return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
        }
        cli_library_error(&o->units, stopped, sizeof stopped);
    }
    cli_out out;
    if (cli_out_open(cmd, &out, o->output)) {
        free(b.r);
        return 1;
    }
    write_branch(out.fp, o, &b, stopped);
    rc = cli_out_commit(cmd, &out);
    if (rc == 0 && status == WHIRL_EINTERRUPTED)
        rc = (cli_error(cmd, "interrupted: the %zu rows found until then are written", b.n),
              CLI_EXIT_INTERRUPTED);
    else if (rc == 0 && status != GSL_SUCCESS)
        rc = cli_error(cmd, "the branch stopped early (the %zu rows found until then are "
                       "written): %s", b.n, stopped);
    free(b.r);
    return rc;
}

int cmd_periodic(const cli_command *cmd, int argc, char **argv)
{
    periodic_options o = {.start = "hanging", .links = 1, .dim = 3, .mode = 1, .side = 1,
                          .units = CLI_UNITS_INIT};
    o.air = (cli_air)CLI_AIR_INIT(o.units);
    const cli_option opts[] = {
        CLI_PIVOT_OPTION(o.pivot, "", "--chart"),
        {.name = "--omega", .type = CLI_DOUBLE, .value = &o.omega, .given = &o.omega_given,
         .meta = "W", .help = "rate of the path (period 2 pi / W; a branch in the rate: its "
                              "start, default --omega-max)",
         .range = "(0, inf)", .required = "--chart --omega-min", .unit = CLI_UNIT_RATE},
        {.name = "--chart", .type = CLI_STRING, .value = &o.chart, .meta = "KIND",
         .help = "the stability chart of the chain shaken vertically: hanging (its tongues) or "
                 "inverted (its region of stability); with --drag C, of the chain with linear "
                 "air drag (the tongues lifted off A = 0)",
         .needs = "--omega-min --omega-max",
         .excludes = "--pivot --omega --dim --start --tol --max-iter --differences "
                     "--up --max-points"},
        {.name = "--eps", .type = CLI_DOUBLE, .value = &o.eps, .meta = "A",
         .help = "--chart ellipse: the circle drive's radius, the ellipse's semi-axis along x "
                 "(the other: A (1 - e))",
         .range = "(0, inf)", .needs = "--chart", .unit = CLI_UNIT_LENGTH},
        {.name = "--e-max", .type = CLI_DOUBLE, .value = &o.e_max, .given = &o.emax_given,
         .meta = "E",
         .help = "--chart ellipse: the largest ellipticity followed (default 1, the line); "
                 "without --chart a branch in the ellipticity e (the path's y terms scaled by "
                 "1 - e) from the path (e = 0) up to E",
         .range = "(0, 1]"},
        {.name = "--omega-min", .type = CLI_DOUBLE, .value = &o.omega_min,
         .given = &o.omin_given, .meta = "W",
         .help = "the lowest rate of the chart, or of a branch followed in the rate",
         .range = "(0, inf)", .needs = "--omega-max", .unit = CLI_UNIT_RATE},
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &o.omega_max,
         .given = &o.omax_given, .meta = "W",
         .help = "the highest rate of the chart, or of a branch followed in the rate",
         .range = "(0, inf)", .needs = "--omega-min", .unit = CLI_UNIT_RATE},
        {.name = "--omega-count", .type = CLI_INT, .value = &o.omega_count, .meta = "N",
         .help = "--chart: rates, both ends included (default 200; ellipse 50)",
         .range = "[2, 1000000]",
         .needs = "--chart"},
        {.name = "--amp-min", .type = CLI_DOUBLE, .value = &o.amp_min, .given = &o.amin_given,
         .meta = "A",
         .help = "the lowest amplitude of the chart (default --amp-max / --amp-rows), or of a "
                 "branch followed in the amplitude (default 0)",
         .range = "[0, inf)", .needs = "--amp-max", .unit = CLI_UNIT_LENGTH},
        {.name = "--amp-max", .type = CLI_DOUBLE, .value = &o.amp_max, .given = &o.amax_given,
         .meta = "A",
         .help = "the highest amplitude of the chart, or of a branch followed in the amplitude "
                 "(the path scaled: its largest Fourier amplitude)",
         .range = "(0, inf)", .unit = CLI_UNIT_LENGTH},
        {.name = "--up", .type = CLI_FLAG, .value = &o.up,
         .help = "branch: leave the start towards larger values (default smaller)"},
        {.name = "--arc-step", .type = CLI_DOUBLE, .value = &o.arc_step, .meta = "H",
         .help = "branch or --chart ellipse: largest step of the continuation's arclength "
                 "(default 0.05; --chart ellipse 0.01)",
         .range = "(0, 1]"},
        {.name = "--max-points", .type = CLI_INT, .value = &o.max_points, .meta = "M",
         .help = "branch: most points (default 10000)", .range = "[2, 10000000]"},
        {.name = "--amp-rows", .type = CLI_INT, .value = &o.amp_rows, .meta = "N",
         .help = "--chart: amplitudes scanned for new curves (default 200)",
         .range = "[2, 1000000]", .needs = "--chart"},
        {.name = "--edge-tol", .type = CLI_DOUBLE, .value = &o.edge_tol, .meta = "A",
         .help = "--chart: an edge's bracket in amplitude at most this wide (default 1e-10)",
         .range = "(0, inf)", .needs = "--chart", .unit = CLI_UNIT_LENGTH},
        {.name = "--links", .type = CLI_INT, .value = &o.links, .meta = "N",
         .help = "links of the chain (default 1)", .range = "[1, 100000]"},
        {.name = "--dim", .type = CLI_INT, .value = &o.dim, .meta = "D",
         .help = "2 (the x-z plane) or 3 (default)", .range = "[2, 3]"},
        {.name = "--start", .type = CLI_STRING, .value = &o.start, .meta = "S",
         .help = "Newton's start: hanging (default), inverted, or steady (the circle drive's "
                 "steady shape of --mode)"},
        {.name = "--mode", .type = CLI_INT, .value = &o.mode, .given = &o.mode_given,
         .meta = "K",
         .help = "--start steady: the mode (default 1); --chart ellipse: the mode followed "
                 "(default 2)",
         .range = "[1, 64]"},
        {.name = "--side", .type = CLI_INT, .value = &o.side, .given = &o.side_given,
         .meta = "S",
         .help = "--start steady or --chart ellipse: the seed's tip on the pivot's side (1, "
                 "default) or opposite (-1), as whirl driven --side",
         .range = "[-1, 1]"},
        {.name = "--steps", .type = CLI_INT, .value = &o.steps, .meta = "S",
         .help = "Gauss steps per period of the coarser solve or monodromy (default 400, "
                 "raised to the chain's bound; --chart hanging or inverted: each mode's steps, "
                 "default 200, raised per mode); the finer takes twice as many",
         .range = "[8, 16777216]"},
        {.name = "--tol", .type = CLI_DOUBLE, .value = &o.tol, .meta = "TOL",
         .help = "Newton: largest scaled |P(y) - y| (default 1e-10)", .range = "(0, 1]"},
        {.name = "--max-iter", .type = CLI_INT, .value = &o.max_iter, .meta = "I",
         .help = "Newton iterations (default 30)", .range = "[1, 1000]"},
        {.name = "--differences", .type = CLI_FLAG, .value = &o.differences,
         .help = "the monodromy by central differences of the period map (a cross-check; "
                 "default: the variational equations)"},
        CLI_AIR_DRAG_OPTIONS(o.drag, NULL, o.drag2, NULL, o.air),
        CLI_DAMPING_OPTION(o.damping),
        CLI_UNITS_OPTIONS(o.units),
        {.name = "--resume", .type = CLI_FLAG, .value = &o.resume,
         .help = "--chart: keep the rates finished in -o FILE (a chart stopped by Ctrl-C), "
                 "compute the rest",
         .needs = "--chart --output"},
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &o.output,
         .meta = "FILE", .help = "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    if ((rc = cli_drag_apply(cmd, &o.air, &o.drag2))) return rc;
    if (o.chart) return run_chart(cmd, &o);
    if ((o.mode_given || o.side_given) && (o.start == NULL || strcmp(o.start, "steady") != 0))
        return cli_error(cmd, "--mode and --side need --start steady (or --chart ellipse)");
    const int branch = o.omin_given || o.amax_given || o.emax_given;
    if ((rc = check_branch(cmd, &o, branch))) return rc;
    if (branch && !o.omega_given) o.omega = o.omega_max;
    const int start = strcmp(o.start, "hanging") == 0    ? 0
                      : strcmp(o.start, "inverted") == 0 ? 1
                      : strcmp(o.start, "steady") == 0   ? 2
                                                         : -1;
    if (start < 0)
        return cli_error(cmd, "--start must be hanging, inverted or steady, got '%s'", o.start);
    whirl_pivot_path path;
    if (whirl_pivot_parse(o.pivot, o.omega, o.units.physical ? o.units.length : 0, o.dim,
                          &path) != GSL_SUCCESS)
        return cli_error(cmd, "--pivot: %s", CLI_LIBRARY_ERROR(&o.units));
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)o.links, 0);
    if (c == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o.units));
    const whirl_model model = {.chain = c, .dim = o.dim, .air_drag = o.drag,
                               .air_drag_quadratic = o.drag2, .internal_damping = o.damping};
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    double *y = w ? malloc(whirl_periodic_state_size(w) * sizeof *y) : NULL;
    if (y == NULL) {
        rc = cli_error(cmd, "%s", w ? "out of memory" : CLI_LIBRARY_ERROR(&o.units));
        goto done;
    }
    if (start == 2) {
        if ((rc = start_steady(cmd, &o, &path, w, y))) goto done;
    } else if (whirl_periodic_start_vertical(w, start, y) != GSL_SUCCESS) {
        rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o.units));
        goto done;
    }
    if (branch) {
        rc = run_branch(cmd, &o, w, y);
        goto done;
    }
    cli_catch_interrupts();
    periodic_progress progress = {.after = cli_progress_after()};
    cli_progress_begin(&progress.line, cmd, "", 0, 0);
    whirl_periodic_set_tick(w, show_progress, &progress);
    whirl_periodic_result r;
    const whirl_periodic_params params = {
        .steps = o.steps, .tol = o.tol, .max_iter = o.max_iter, .refine = 1,
        .monodromy = o.differences ? WHIRL_MONODROMY_DIFFERENCES : WHIRL_MONODROMY_VARIATIONAL};
    const int status = whirl_periodic_find(w, y, &params, &r);
    cli_progress_clear(&progress.line);
    if (status == WHIRL_EINTERRUPTED || cli_interrupted) {
        rc = (cli_error(cmd, "interrupted: no periodic motion yet"), CLI_EXIT_INTERRUPTED);
        goto done;
    }
    if (status != GSL_SUCCESS) {
        rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o.units));
        goto done;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, o.output)) {
        rc = 1;
        goto done;
    }
    write_result(out.fp, &o, &r);
    rc = cli_out_commit(cmd, &out);
done:
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
    return rc;
}
