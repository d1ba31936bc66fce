/* whirl shape: the steady shape of mode K at rotation rate W, as CSV s,r,z,tension from the
 * pivot to the free end, after a comment line summarising it. The N-link shape is the point of
 * the branch's continuation from its birth; on a terminal a progress line shows the steps of a
 * long one (the middle modes of long chains fold thousands of times) and the highest rate
 * reached. Ctrl-C stops it: no output, exit status 130. */
#include <stdio.h>
#include <stdlib.h>

#include "cli/steady_cli.h"

/* The progress line: continuation steps against their bound, the highest rate reached. */
typedef struct shape_progress {
    cli_progress_state state;
    const cli_command *cmd;
    double rate, target; /* the unit of rates; the rate asked for, in it */
    const char *unit;
    long steps;          /* the last reported, -1 before the first */
    char label[128];
} shape_progress;

static void show_progress(void *ctx, long steps, long steps_max, double omega_hi)
{
    shape_progress *s = ctx;
    if (s->steps < 0) cli_progress_begin(&s->state, s->cmd, s->label, steps_max, 0);
    s->steps = steps;
    snprintf(s->label, sizeof s->label, "continuation steps (highest rate %.6g of %.6g %s)",
             omega_hi * s->rate, s->target, s->unit);
    cli_progress_update(&s->state, steps, 0);
}

int cmd_shape(const cli_command *cmd, int argc, char **argv)
{
    double omega = 0;
    int mode = 0, points = 201, omega_given = 0, mode_given = 0;
    const char *out_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {"--omega", NULL, CLI_DOUBLE, &omega, &omega_given, "W", "rotation rate", "(0, inf)",
         NULL, NULL, "", CLI_UNIT_RATE},
        {"--mode", NULL, CLI_INT, &mode, &mode_given, "K",
         "node count: the pivot plus K-1 axis crossings (1..N with --links N, 1..3183 for the "
         "continuum)", "[1, inf)", NULL, NULL, ""},
        STEADY_CLI_MODEL_OPTIONS(m),
        {"--points", NULL, CLI_INT, &points, NULL, "P", "continuum: points sampled (default 201)",
         "[2, 10000000]", NULL, "--links"},
        {"--output", "-o", CLI_STRING, &out_path, NULL, "FILE",
         "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (steady_cli_model_setup(cmd, &m)) return 1;
    if (steady_cli_check_mode(cmd, &m, mode)) {
        steady_cli_model_free(&m);
        return 1;
    }

    double tip_mass = steady_cli_tip_mass(&m);
    size_t n = m.chain ? m.chain->n + 1 : (size_t)points;
    double *s = malloc(4 * n * sizeof *s), *r = s + n, *z = r + n, *tension = z + n;
    if (s == NULL) {
        steady_cli_model_free(&m);
        return cli_error(cmd, "out of memory for %zu points", n);
    }
    /* the N-link shape with its nodes from the branch's link angles */
    whirl_shape_info info;
    shape_progress progress = {.cmd = cmd, .rate = cli_units_rate(&m.units), .steps = -1,
                               .unit = cli_units_name(&m.units, CLI_UNIT_RATE)};
    progress.target = omega * progress.rate;
    cli_catch_interrupts();
    int status = m.chain ? whirl_nlink_solve_nodes_progress(m.chain, omega, mode, &info, r, z,
                                                            tension, show_progress, &progress)
                         : whirl_continuum_solve(omega, mode, tip_mass, 0, &info);
    if (progress.steps >= 0) cli_progress_update(&progress.state, progress.steps, 1);
    if (status == WHIRL_EINTERRUPTED) {
        cli_error(cmd, "interrupted: %s", whirl_last_error());
        free(s);
        steady_cli_model_free(&m);
        return CLI_EXIT_INTERRUPTED;
    }
    if (status != GSL_SUCCESS) {
        steady_cli_solve_error(cmd, &m, status, mode, omega);
        free(s);
        steady_cli_model_free(&m);
        return 1;
    }
    if (m.chain) {
        s[0] = 0;
        for (size_t i = 1; i < n; i++) s[i] = s[i - 1] + m.chain->length[i - 1];
    } else {
        status = whirl_continuum_sample(omega, tip_mass, info.tip_r, n, s, r, z, tension);
    }
    cli_out out;
    if (status != GSL_SUCCESS) rc = cli_error(cmd, "%s", whirl_last_error());
    else rc = cli_out_open(cmd, &out, out_path);
    if (rc == 0) {
        steady_cli_write_shape(out.fp, &m, &info, n, s, r, z, tension, NULL);
        rc = cli_out_commit(cmd, &out);
    }
    free(s);
    steady_cli_model_free(&m);
    return rc;
}
