/* whirl shape: the steady shape of mode K at rotation rate W, as CSV s,r,z,tension from the
 * pivot to the free end, after a comment line summarising it. The N-link shape is the point of
 * the branch's continuation from its birth; on a terminal a progress line shows how far a long
 * one has come (the middle modes of long chains fold thousands of times; steady_cli.h), and
 * --max-steps bounds it. A continuation that fails (Ctrl-C, the step bound) leaves no output:
 * one line names the mode, the rate reached and why; exit status 130 after Ctrl-C, else 1. */
#include <stdio.h>
#include <stdlib.h>

#include "cli/steady_cli.h"

int cmd_shape(const cli_command *cmd, int argc, char **argv)
{
    double omega = 0;
    int mode = 0, points = 201, omega_given = 0, mode_given = 0;
    const char *out_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    steady_cli_follow follow = {0};
    const cli_option opts[] = {
        {"--omega", NULL, CLI_DOUBLE, &omega, &omega_given, "W", "rotation rate", "(0, inf)",
         NULL, NULL, "", CLI_UNIT_RATE},
        {"--mode", NULL, CLI_INT, &mode, &mode_given, "K",
         "node count: the pivot plus K-1 axis crossings (1..N with --links N, 1..3183 for the "
         "continuum)", "[1, inf)", NULL, NULL, ""},
        STEADY_CLI_MODEL_OPTIONS(m),
        {"--points", NULL, CLI_INT, &points, NULL, "P", "continuum: points sampled (default 201)",
         "[2, 10000000]", NULL, "--links"},
        STEADY_CLI_FOLLOW_OPTIONS(follow),
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
    cli_catch_interrupts();
    steady_cli_follow_begin(&follow, cmd, &m, omega, 1);
    int status = m.chain ? whirl_nlink_solve_nodes_opt(m.chain, omega, mode, &info, r, z, tension,
                                                       &follow.opt)
                         : whirl_continuum_solve(omega, mode, tip_mass, 0, &info);
    steady_cli_follow_end(&follow);
    if (status == WHIRL_EINTERRUPTED) {
        cli_error(cmd, "interrupted in mode %d: %s", mode, CLI_LIBRARY_ERROR(&m.units));
        free(s);
        steady_cli_model_free(&m);
        return CLI_EXIT_INTERRUPTED;
    }
    if (status != GSL_SUCCESS) {
        steady_cli_solve_error(cmd, &m, status);
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
    cli_progress_state progress;
    cli_progress_begin(&progress, cmd, "", 0, 0);
    if (n > 100000) cli_progress_text(&progress, "sampling and writing %zu points", n);
    if (status == WHIRL_EINTERRUPTED)
        rc = cli_error(cmd, "interrupted sampling the shape: %s", CLI_LIBRARY_ERROR(&m.units));
    else if (status != GSL_SUCCESS) rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m.units));
    else rc = cli_out_open(cmd, &out, out_path);
    if (rc == 0) {
        steady_cli_write_shape(out.fp, &m, &info, n, s, r, z, tension, NULL);
        if (cli_interrupted) { /* a shape cut short is no shape: nothing is kept */
            cli_out_abort(&out);
            rc = cli_error(cmd, "interrupted while writing %zu points: nothing written", n);
        } else rc = cli_out_commit(cmd, &out);
    }
    cli_progress_clear(&progress);
    free(s);
    steady_cli_model_free(&m);
    return rc;
}
