/* whirl sweep: the branches of the listed modes over a grid of rates. The continuum's by
 * continuation in omega (whirl_continuum_branch, on all OpenMP threads); the N-link chain's by
 * pseudo-arclength continuation from each mode's birth (whirl_nlink_follow): a row at every
 * crossing of a grid rate, in the order along the branch (through folds a rate is crossed more than
 * once), and the folds, branch points and returns to the hanging chain as comment lines and, with
 * --events FILE, as CSV. On a terminal, a sweep of the N-link chain that runs longer than a second
 * shows a progress line (steady_cli.h: how far the branch being followed has come), and
 * --max-steps bounds each branch's continuation. Ctrl-C (SIGINT, SIGTERM) stops the sweep within
 * a step: the rows found so far are written (a comment line says where it stopped) and the exit
 * status is 130. A branch that fails (the step bound) writes nothing: one line names the mode,
 * the rate reached and why, exit status 1 (its rows would stop short of the grid's end). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli/steady_cli.h"

/* Rows and events of the N-link branches, grown as they come. */
typedef struct sweep_rows {
    int mode;
    size_t n, cap;
    whirl_shape_info *info;
    size_t ne, cap_e;
    whirl_branch_event *event;
    int *event_mode;
} sweep_rows;

static int sweep_visit(void *ctx, size_t j, const whirl_shape_info *info,
                       const whirl_branch_event *event)
{
    sweep_rows *rows = ctx;
    (void)j;
    if (event) {
        if (rows->ne == rows->cap_e) {
            size_t cap = rows->cap_e ? 2 * rows->cap_e : 16;
            whirl_branch_event *e = realloc(rows->event, cap * sizeof *e);
            if (e == NULL) return GSL_ENOMEM;
            rows->event = e;
            int *m = realloc(rows->event_mode, cap * sizeof *m);
            if (m == NULL) return GSL_ENOMEM;
            rows->event_mode = m;
            rows->cap_e = cap;
        }
        rows->event_mode[rows->ne] = rows->mode;
        rows->event[rows->ne++] = *event;
        return 0;
    }
    if (rows->n == rows->cap) {
        size_t cap = rows->cap ? 2 * rows->cap : 256;
        whirl_shape_info *f = realloc(rows->info, cap * sizeof *f);
        if (f == NULL) return GSL_ENOMEM;
        rows->info = f;
        rows->cap = cap;
    }
    rows->info[rows->n++] = *info;
    return 0;
}

static const char *event_name(whirl_event_kind kind)
{
    switch (kind) {
    case WHIRL_EVENT_FOLD:
        return "fold";
    case WHIRL_EVENT_BRANCH_POINT:
        return "branch_point";
    case WHIRL_EVENT_RETURN:
        return "return";
    }
    return "?";
}

/* A sweep: its options, the grid, and what the branches gave. */
typedef struct sweep {
    cli_int_list modes;
    double omega_min, omega_max;
    int count;
    const char *out_path, *events_path;
    steady_cli_model m;
    steady_cli_follow follow;
    sweep_rows rows;          /* N-link chain */
    double *omega;            /* the grid (count) */
    whirl_shape_info *info;   /* continuum: count per mode */
    int *exists;              /* continuum: count per mode */
    int interrupted;          /* the mode being followed when a stop came */
    char stopped[512];        /* why it stopped */
    char absent[1024];        /* the modes with no row */
} sweep;

static void sweep_free(sweep *s)
{
    free(s->omega);
    free(s->info);
    free(s->exists);
    free(s->rows.info);
    free(s->rows.event);
    free(s->rows.event_mode);
    steady_cli_model_free(&s->m);
}

/* Parses and checks the options and sets up the model: 0, or the exit status after an error
 * (s freed). */
static int parse_sweep(const cli_command *cmd, int argc, char **argv, sweep *s)
{
    const cli_option opts[] = {
        {.name = "--modes", .type = CLI_INT_LIST, .value = &s->modes, .meta = "LIST",
         .help = "modes, e.g. 1,2,3 (1..N with --links N, 1..3183 for the continuum)",
         .range = "[1, inf)", .required = ""},
        {.name = "--omega-min", .type = CLI_DOUBLE, .value = &s->omega_min, .meta = "A",
         .help = "lowest rate", .range = "(0, inf)", .required = "", .unit = CLI_UNIT_RATE},
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &s->omega_max, .meta = "B",
         .help = "highest rate", .range = "(0, inf)", .required = "", .unit = CLI_UNIT_RATE},
        {.name = "--omega-count", .type = CLI_INT, .value = &s->count, .meta = "N",
         .help = "N equally spaced rates, both ends included", .range = "[1, 10000000]",
         .required = ""},
        STEADY_CLI_MODEL_OPTIONS(s->m),
        {.name = "--events", .type = CLI_STRING, .value = &s->events_path, .meta = "FILE",
         .help = "write the folds, branch points and returns of the N-link branches to FILE (CSV)",
         .needs = "--links"},
        STEADY_CLI_FOLLOW_OPTIONS(s->follow),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &s->out_path,
         .meta = "FILE", .help = "write the CSV to FILE (default: standard output)"},
    };
    const int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (s->count == 1 ? s->omega_min != s->omega_max : !(s->omega_min < s->omega_max))
        return cli_error(cmd, "need --omega-min < --omega-max (equal with --omega-count 1)");
    if (steady_cli_model_setup(cmd, &s->m)) return 1;
    for (int i = 0; i < s->modes.n; i++)
        if (steady_cli_check_mode(cmd, &s->m, s->modes.v[i])) {
            steady_cli_model_free(&s->m);
            return 1;
        }
    return 0;
}

/* Follows the branch of each mode over the grid (stops at a Ctrl-C: s->interrupted). 0, or 1
 * after an error. */
static int follow_branches(const cli_command *cmd, sweep *s)
{
    const size_t n = (size_t)s->count, nmodes = (size_t)s->modes.n;
    const whirl_chain *chain = s->m.chain;
    s->omega = malloc(n * sizeof *s->omega);
    s->info = chain ? NULL : malloc(n * nmodes * sizeof *s->info);
    s->exists = chain ? NULL : malloc(n * nmodes * sizeof *s->exists);
    if (s->omega == NULL || (!chain && (s->info == NULL || s->exists == NULL)))
        return cli_error(cmd, "out of memory for %zu rates", n);
    for (size_t j = 0; j < n; j++)
        s->omega[j] = cli_grid(s->omega_min, s->omega_max, s->count, (int)j);
    /* the rates not reached before a stop stay "no row" */
    for (size_t j = 0; s->exists && j < n * nmodes; j++) s->exists[j] = 0;
    steady_cli_follow_begin(&s->follow, cmd, &s->m, s->omega[n - 1], s->modes.n);
    int rc = 0;
    for (int i = 0; i < s->modes.n && rc == 0 && !s->interrupted; i++) {
        const int mode = s->modes.v[i];
        int status;
        if (chain) {
            s->rows.mode = mode;
            s->follow.index = i + 1;
            status = whirl_nlink_follow_opt(chain, mode, s->omega[n - 1], n, s->omega,
                                            sweep_visit, &s->rows, &s->follow.opt);
        } else {
            status = whirl_continuum_branch(mode, steady_cli_tip_mass(&s->m), n, s->omega,
                                            s->info + i * n, s->exists + i * n);
        }
        if (status == WHIRL_EINTERRUPTED) {
            s->interrupted = mode;
            cli_library_error(&s->m.units, s->stopped, sizeof s->stopped);
        } else if (status != GSL_SUCCESS) {
            steady_cli_follow_end(&s->follow);
            /* the N-link path's messages name the mode themselves */
            if (chain) rc = steady_cli_solve_error(cmd, &s->m, status);
            else rc = cli_error(cmd, "mode %d: %s", mode, CLI_LIBRARY_ERROR(&s->m.units));
        }
    }
    steady_cli_follow_end(&s->follow);
    return rc;
}

/* The rows of mode i on the grid. */
static size_t mode_rows(const sweep *s, int i)
{
    const size_t n = (size_t)s->count;
    size_t rows = 0;
    for (size_t j = 0; j < (s->m.chain ? s->rows.n : n); j++)
        rows += s->m.chain ? s->rows.info[j].mode == s->modes.v[i] : s->exists[i * n + j] != 0;
    return rows;
}

/* A mode with no row on the grid (not stopped early): its birth, above the grid's end, or a
 * branch that does not reach the grid, said in s->absent and a note; the sweep fails when no
 * mode has a row. 0, or 1 after an error. */
static int check_absent(const cli_command *cmd, sweep *s)
{
    int modes_with_rows = 0;
    char *absent = s->absent;
    const size_t size = sizeof s->absent;
    for (int i = 0; i < s->modes.n && !s->interrupted; i++) {
        if (mode_rows(s, i) > 0) {
            modes_with_rows++;
            continue;
        }
        double birth = 0;
        char words[64], hi[64];
        size_t used = strlen(absent);
        if (steady_cli_critical(cmd, &s->m, s->modes.v[i], &birth)) return 1;
        snprintf(absent + used, size - used, "%smode %d exists only above %s", used ? "; " : "",
                 s->modes.v[i], cli_rate_words(&s->m.units, birth, words, sizeof words));
        if (birth < s->omega_max)
            snprintf(absent + strlen(absent), size - strlen(absent),
                     " and has no shape at the grid's rates up to %s",
                     cli_rate_words(&s->m.units, s->omega_max, hi, sizeof hi));
    }
    if (absent[0] && modes_with_rows == 0) {
        char lo[64], hi[64];
        return cli_error(cmd, "no mode exists on the grid %s to %s: %s",
                         cli_rate_words(&s->m.units, s->omega_min, lo, sizeof lo),
                         cli_rate_words(&s->m.units, s->omega_max, hi, sizeof hi), absent);
    }
    if (absent[0]) fprintf(stderr, "whirl %s: note: %s (no rows)\n", cmd->name, absent);
    return 0;
}

/* --events FILE: the folds, branch points and returns as CSV. */
static void write_events(FILE *fp, const sweep *s)
{
    const steady_cli_model *m = &s->m;
    fprintf(fp, "# events on the branches of the N-link chain (%d links), tip mass %s %s; "
            "arclength in (ln omega, link angles) from the birth\n", m->links,
            CLI_NUM(m->tip_mass * m->units.mass), cli_units_name(&m->units, CLI_UNIT_MASS));
    cli_units_comment(fp, &m->units);
    fprintf(fp, "mode,kind,omega,tip_r,arclength,nodes\n");
    const double rate = cli_units_rate(&m->units), len = m->units.length;
    for (size_t e = 0; e < s->rows.ne; e++) {
        const whirl_branch_event *ev = &s->rows.event[e];
        fprintf(fp, "%d,%s,%s,%s,%s,%d\n", s->rows.event_mode[e], event_name(ev->kind),
                CLI_NUM(ev->omega * rate), CLI_NUM(ev->tip_r * len), CLI_NUM(ev->arclength),
                ev->n_crossings + 1);
    }
}

/* The comment lines above the rows: what was swept, the events, the modes with no row, a stop. */
static void write_comments(FILE *fp, const sweep *s)
{
    const steady_cli_model *m = &s->m;
    const char *mass_unit = cli_units_name(&m->units, CLI_UNIT_MASS);
    if (m->chain) {
        const double rate = cli_units_rate(&m->units), len = m->units.length;
        const char *rate_unit = cli_units_name(&m->units, CLI_UNIT_RATE);
        const char *len_unit = cli_units_name(&m->units, CLI_UNIT_LENGTH);
        fprintf(fp, "# branches of the N-link chain (%d links), tip mass %s %s: each mode "
                "followed from its birth by pseudo-arclength continuation, a row at every "
                "crossing of a grid rate, in the order along the branch; node_count: the shape's "
                "node count\n", m->links, CLI_NUM(m->tip_mass * m->units.mass), mass_unit);
        for (size_t e = 0; e < s->rows.ne; e++) {
            const whirl_branch_event *ev = &s->rows.event[e];
            fprintf(fp, "# %s: mode=%d omega=%s %s tip_r=%s %s node_count=%d\n",
                    event_name(ev->kind), s->rows.event_mode[e], CLI_NUM(ev->omega * rate),
                    rate_unit, CLI_NUM(ev->tip_r * len), len_unit, ev->n_crossings + 1);
        }
    } else {
        fprintf(fp, "# branches of the continuous chain, tip mass %s %s; rows where the "
                "mode exists\n", CLI_NUM(m->tip_mass * m->units.mass), mass_unit);
    }
    if (s->absent[0]) fprintf(fp, "# no rows: %s\n", s->absent);
    if (s->interrupted)
        fprintf(fp, "# interrupted in mode %d (%s): the rows found until then\n", s->interrupted,
                s->stopped);
    cli_units_comment(fp, &m->units);
}

/* The rows: the N-link chain's in the order along its branches, the continuum's where the mode
 * exists. Returns their count. */
static size_t write_rows(FILE *fp, const sweep *s)
{
    const steady_cli_model *m = &s->m;
    const double rate = cli_units_rate(&m->units), len = m->units.length;
    const double force = cli_units_force(&m->units);
    fprintf(fp, "omega,mode,tip_r,max_r,top_tension,depth,nodes\n");
    const size_t total = m->chain ? s->rows.n : (size_t)s->count * (size_t)s->modes.n;
    size_t written = 0;
    for (size_t j = 0; j < total; j++) {
        const whirl_shape_info *f = m->chain ? &s->rows.info[j] : &s->info[j];
        if (!m->chain && !s->exists[j]) continue;
        written++;
        fprintf(fp, "%s,%d,%s,%s,%s,%s,%d\n", CLI_NUM(f->omega * rate), f->mode,
                CLI_NUM(f->tip_r * len), CLI_NUM(f->max_r * len), CLI_NUM(f->top_tension * force),
                CLI_NUM(f->depth * len), f->n_crossings + 1);
    }
    return written;
}

/* Writes the CSV and the events (both files or neither): 0, 1 after an error, or
 * CLI_EXIT_INTERRUPTED after a stop. */
static int write_sweep(const cli_command *cmd, const sweep *s)
{
    cli_out out, ev;
    if (s->events_path) {
        if (cli_out_open(cmd, &ev, s->events_path)) return 1;
        write_events(ev.fp, s);
    }
    if (cli_out_open(cmd, &out, s->out_path)) {
        if (s->events_path) cli_out_abort(&ev);
        return 1;
    }
    write_comments(out.fp, s);
    const size_t written = write_rows(out.fp, s);
    cli_out *const outs[2] = {&out, &ev};
    if (cli_out_commit_all(cmd, outs, s->events_path ? 2 : 1)) return 1;
    if (s->interrupted) {
        cli_error(cmd, "interrupted in mode %d: the %zu rows found until then are written",
                  s->interrupted, written);
        return CLI_EXIT_INTERRUPTED;
    }
    return 0;
}

int cmd_sweep(const cli_command *cmd, int argc, char **argv)
{
    sweep s = {.modes = {0, {0}}, .m = STEADY_CLI_MODEL_INIT};
    int rc = parse_sweep(cmd, argc, argv, &s);
    if (rc) return rc;
    cli_catch_interrupts();
    rc = follow_branches(cmd, &s);
    if (rc == 0) rc = check_absent(cmd, &s);
    if (rc == 0) rc = write_sweep(cmd, &s);
    sweep_free(&s);
    return rc;
}
