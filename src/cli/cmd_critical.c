/* whirl critical: the linear critical rates of modes 1..K, where they bifurcate from the
 * hanging chain (continuum: j_{0,k}/2 or the tip-mass root; --links N: the N-link chain). The
 * N-link chain's come in blocks of eigenvalues (seconds to minutes for tens of thousands of
 * links); on a terminal, once that has taken a second, a progress line counts them:
 *   whirl critical: critical rates 1200/60000 (2%), 3s elapsed, about 2m40s left
 * erased at the end. */
#include <stdlib.h>

#include "cli/steady_cli.h"
#include "steady/steady_internal.h"

/* The progress line of the N-link chain's rates. */
typedef struct critical_progress {
    cli_progress_state line;
    double after; /* the line shows once the run has taken this long [s] */
} critical_progress;

static void show_progress(void *ctx, size_t done, size_t total)
{
    critical_progress *p = ctx;
    (void)total;
    if (!p->line.drawn && cli_wall_seconds() - p->line.start < p->after) return;
    cli_progress_update(&p->line, (long)done, 0);
}

int cmd_critical(const cli_command *cmd, int argc, char **argv)
{
    int modes = 3;
    const char *out_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {.name = "--modes", .type = CLI_INT, .value = &modes, .meta = "K",
         .help = "modes 1..K (default 3; up to N with --links N, up to 3183 for the continuum)",
         .range = "[1, inf)"},
        STEADY_CLI_MODEL_OPTIONS(m),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &out_path, .meta = "FILE",
         .help = "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (steady_cli_model_setup(cmd, &m)) return 1;
    if (m.chain && (size_t)modes > m.chain->n) {
        steady_cli_model_free(&m);
        return cli_error(cmd, "--modes %d exceeds the %d modes of a chain of %d links", modes,
                         m.links, m.links);
    }
    cli_catch_interrupts(); /* the continuum's rates with a tip mass: a sweep over the rates */
    if (steady_cli_check_mode(cmd, &m, modes)) {
        steady_cli_model_free(&m);
        return 1;
    }
    double *omega = malloc((size_t)modes * sizeof *omega);
    if (omega == NULL) {
        steady_cli_model_free(&m);
        return cli_error(cmd, "out of memory for %d critical rates", modes);
    }
    /* the N-link chain's in blocks of one eigen-solve, the continuum's in one sweep */
    critical_progress progress = {.after = cli_progress_after()};
    cli_progress_begin(&progress.line, cmd, "critical rates", modes, 0);
    int status = m.chain ? whirl_nlink_critical_report(m.chain, (size_t)modes, omega,
                                                       show_progress, &progress)
                         : whirl_continuum_critical_rates((size_t)modes,
                                                          steady_cli_tip_mass(&m), omega);
    cli_progress_clear(&progress.line);
    if (status == WHIRL_EINTERRUPTED || cli_interrupted)
        rc = (cli_error(cmd, "%s", status == WHIRL_EINTERRUPTED ? CLI_LIBRARY_ERROR(&m.units)
                                                                 : "interrupted"),
              CLI_EXIT_INTERRUPTED);
    else if (status != GSL_SUCCESS)
        rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m.units));
    if (rc) {
        free(omega);
        steady_cli_model_free(&m);
        return rc;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, out_path)) {
        free(omega);
        steady_cli_model_free(&m);
        return 1;
    }
    double rate = cli_units_rate(&m.units);
    fprintf(out.fp, "# linear critical rates of the %s, tip mass %s %s; omega in %s\n",
            m.chain ? "N-link chain" : "continuous chain",
            CLI_NUM(m.tip_mass * m.units.mass), cli_units_name(&m.units, CLI_UNIT_MASS),
            cli_units_name(&m.units, CLI_UNIT_RATE));
    if (m.chain) fprintf(out.fp, "# links=%d\n", m.links);
    /* in SI units the first births also in Hz, short: the frequency a turning hand counts */
    if (m.units.physical) {
        fprintf(out.fp, "# in Hz:");
        for (int k = 1; k <= modes && k <= 8; k++)
            fprintf(out.fp, "%s mode %d from %.4g Hz", k > 1 ? "," : "", k,
                    omega[k - 1] * rate / 6.283185307179586);
        fprintf(out.fp, "%s\n", modes > 8 ? ", ..." : "");
    }
    cli_units_comment(out.fp, &m.units);
    fprintf(out.fp, "mode,omega\n");
    for (int k = 1; k <= modes; k++) fprintf(out.fp, "%d,%s\n", k, CLI_NUM(omega[k - 1] * rate));
    free(omega);
    steady_cli_model_free(&m);
    return cli_out_commit(cmd, &out);
}
