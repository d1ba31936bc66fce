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

int cmd_sweep(const cli_command *cmd, int argc, char **argv)
{
    cli_int_list modes = {0, {0}};
    double omega_min = 0, omega_max = 0;
    int count = 0;
    const char *out_path = NULL, *events_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    sweep_rows rows = {0};
    steady_cli_follow follow = {0};
    const cli_option opts[] = {
        {"--modes", NULL, CLI_INT_LIST, &modes, NULL, "LIST",
         "modes, e.g. 1,2,3 (1..N with --links N, 1..3183 for the continuum)", "[1, inf)",
         NULL, NULL, ""},
        {"--omega-min", NULL, CLI_DOUBLE, &omega_min, NULL, "A", "lowest rate", "(0, inf)", NULL,
         NULL, "", CLI_UNIT_RATE},
        {"--omega-max", NULL, CLI_DOUBLE, &omega_max, NULL, "B", "highest rate", "(0, inf)", NULL,
         NULL, "", CLI_UNIT_RATE},
        {"--omega-count", NULL, CLI_INT, &count, NULL, "N",
         "N equally spaced rates, both ends included", "[1, 10000000]", NULL, NULL, ""},
        STEADY_CLI_MODEL_OPTIONS(m),
        {"--events", NULL, CLI_STRING, &events_path, NULL, "FILE",
         "write the folds, branch points and returns of the N-link branches to FILE (CSV)", NULL,
         "--links", NULL, NULL},
        STEADY_CLI_FOLLOW_OPTIONS(follow),
        {"--output", "-o", CLI_STRING, &out_path, NULL, "FILE",
         "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (count == 1 ? omega_min != omega_max : !(omega_min < omega_max))
        return cli_error(cmd, "need --omega-min < --omega-max (equal with --omega-count 1)");
    if (steady_cli_model_setup(cmd, &m)) return 1;
    for (int i = 0; i < modes.n; i++)
        if (steady_cli_check_mode(cmd, &m, modes.v[i])) {
            steady_cli_model_free(&m);
            return 1;
        }

    cli_catch_interrupts();
    double rate = cli_units_rate(&m.units), len = m.units.length, force = cli_units_force(&m.units);
    const char *rate_unit = cli_units_name(&m.units, CLI_UNIT_RATE);
    const char *len_unit = cli_units_name(&m.units, CLI_UNIT_LENGTH);
    size_t n = (size_t)count;
    double *omega = malloc(n * sizeof *omega);
    whirl_shape_info *info = m.chain ? NULL : malloc(n * (size_t)modes.n * sizeof *info);
    int *exists = m.chain ? NULL : malloc(n * (size_t)modes.n * sizeof *exists);
    if (omega == NULL || (!m.chain && (info == NULL || exists == NULL))) {
        rc = cli_error(cmd, "out of memory for %zu rates", n);
        goto done;
    }
    for (size_t j = 0; j < n; j++)
        omega[j] = cli_grid(omega_min, omega_max, count, (int)j);
    /* the rates not reached before a stop stay "no row" */
    for (size_t j = 0; exists && j < n * (size_t)modes.n; j++) exists[j] = 0;
    steady_cli_follow_begin(&follow, cmd, &m, omega[n - 1], modes.n);
    int interrupted = 0; /* the mode being followed when a stop came */
    char stopped[512] = "";
    for (int i = 0; i < modes.n && rc == 0 && !interrupted; i++) {
        int status;
        if (m.chain) {
            rows.mode = modes.v[i];
            follow.index = i + 1;
            status = whirl_nlink_follow_opt(m.chain, modes.v[i], omega[n - 1], n, omega,
                                            sweep_visit, &rows, &follow.opt);
        } else {
            status = whirl_continuum_branch(modes.v[i], steady_cli_tip_mass(&m), n, omega,
                                            info + i * n, exists + i * n);
        }
        if (status == WHIRL_EINTERRUPTED) {
            interrupted = modes.v[i];
            cli_library_error(&m.units, stopped, sizeof stopped);
        } else if (status != GSL_SUCCESS) {
            steady_cli_follow_end(&follow);
            /* the N-link path's messages name the mode themselves */
            if (m.chain) rc = steady_cli_solve_error(cmd, &m, status);
            else rc = cli_error(cmd, "mode %d: %s", modes.v[i], CLI_LIBRARY_ERROR(&m.units));
        }
    }
    steady_cli_follow_end(&follow);
    /* a mode with no row on the grid (not stopped early): its birth, above the grid's end, or a
     * branch that does not reach the grid; the sweep fails when no mode has a row */
    int modes_with_rows = 0;
    char absent[1024] = "";
    for (int i = 0; i < modes.n && rc == 0 && !interrupted; i++) {
        size_t count_i = 0;
        for (size_t j = 0; j < (m.chain ? rows.n : n); j++)
            count_i += m.chain ? rows.info[j].mode == modes.v[i] : exists[i * n + j] != 0;
        if (count_i > 0) {
            modes_with_rows++;
            continue;
        }
        double birth = 0;
        char words[64], hi[64];
        size_t used = strlen(absent);
        if (steady_cli_critical(cmd, &m, modes.v[i], &birth)) {
            rc = 1;
            break;
        }
        snprintf(absent + used, sizeof absent - used, "%smode %d exists only above %s", used ? "; " : "",
                 modes.v[i], cli_rate_words(&m.units, birth, words, sizeof words));
        if (birth < omega_max)
            snprintf(absent + strlen(absent), sizeof absent - strlen(absent),
                     " and has no shape at the grid's rates up to %s",
                     cli_rate_words(&m.units, omega_max, hi, sizeof hi));
    }
    if (rc == 0 && absent[0] && modes_with_rows == 0) {
        char lo[64], hi[64];
        rc = cli_error(cmd, "no mode exists on the grid %s to %s: %s",
                       cli_rate_words(&m.units, omega_min, lo, sizeof lo),
                       cli_rate_words(&m.units, omega_max, hi, sizeof hi), absent);
    } else if (rc == 0 && absent[0]) {
        fprintf(stderr, "whirl %s: note: %s (no rows)\n", cmd->name, absent);
    }
    cli_out out, ev;
    if (rc == 0 && events_path && (rc = cli_out_open(cmd, &ev, events_path)) == 0) {
        fprintf(ev.fp, "# events on the branches of the N-link chain (%d links), tip mass %s %s; "
                "arclength in (ln omega, link angles) from the birth\n", m.links,
                CLI_NUM(m.tip_mass * m.units.mass), cli_units_name(&m.units, CLI_UNIT_MASS));
        cli_units_comment(ev.fp, &m.units);
        fprintf(ev.fp, "mode,kind,omega,tip_r,arclength,nodes\n");
        for (size_t e = 0; e < rows.ne; e++)
            fprintf(ev.fp, "%d,%s,%s,%s,%s,%d\n", rows.event_mode[e],
                    event_name(rows.event[e].kind), CLI_NUM(rows.event[e].omega * rate),
                    CLI_NUM(rows.event[e].tip_r * len), CLI_NUM(rows.event[e].arclength),
                    rows.event[e].n_nodes + 1);
        rc = cli_out_commit(cmd, &ev);
    }
    if (rc == 0 && (rc = cli_out_open(cmd, &out, out_path)) == 0) {
        if (m.chain) {
            fprintf(out.fp, "# branches of the N-link chain (%d links), tip mass %s %s: each mode "
                    "followed from its birth by pseudo-arclength continuation, a row at every "
                    "crossing of a grid rate, in the order along the branch; nodes: the shape's "
                    "node count\n", m.links, CLI_NUM(m.tip_mass * m.units.mass),
                    cli_units_name(&m.units, CLI_UNIT_MASS));
            for (size_t e = 0; e < rows.ne; e++)
                fprintf(out.fp, "# %s: mode=%d omega=%s %s tip_r=%s %s nodes=%d\n",
                        event_name(rows.event[e].kind), rows.event_mode[e],
                        CLI_NUM(rows.event[e].omega * rate), rate_unit,
                        CLI_NUM(rows.event[e].tip_r * len), len_unit, rows.event[e].n_nodes + 1);
        } else {
            fprintf(out.fp, "# branches of the continuous chain, tip mass %s %s; rows where the "
                    "mode exists\n", CLI_NUM(m.tip_mass * m.units.mass),
                    cli_units_name(&m.units, CLI_UNIT_MASS));
        }
        if (absent[0]) fprintf(out.fp, "# no rows: %s\n", absent);
        if (interrupted)
            fprintf(out.fp, "# interrupted in mode %d (%s): the rows found until then\n",
                    interrupted, stopped);
        cli_units_comment(out.fp, &m.units);
        fprintf(out.fp, "omega,mode,tip_r,max_r,top_tension,depth,nodes\n");
        size_t total = m.chain ? rows.n : n * (size_t)modes.n, written = 0;
        for (size_t j = 0; j < total; j++) {
            const whirl_shape_info *f = m.chain ? &rows.info[j] : &info[j];
            if (!m.chain && !exists[j]) continue;
            written++;
            fprintf(out.fp, "%s,%d,%s,%s,%s,%s,%d\n", CLI_NUM(f->omega * rate), f->mode,
                    CLI_NUM(f->tip_r * len), CLI_NUM(f->max_r * len),
                    CLI_NUM(f->top_tension * force), CLI_NUM(f->depth * len), f->n_nodes + 1);
        }
        rc = cli_out_commit(cmd, &out);
        if (rc == 0 && interrupted) {
            cli_error(cmd, "interrupted in mode %d: the %zu rows found until then are written",
                      interrupted, written);
            rc = CLI_EXIT_INTERRUPTED;
        }
    }
done:
    free(omega);
    free(info);
    free(exists);
    free(rows.info);
    free(rows.event);
    free(rows.event_mode);
    steady_cli_model_free(&m);
    return rc;
}
