/* whirl minimize: the mode-1 shape of the N-link chain as the minimum of the co-rotating
 * potential V = sum_i m_i (g z_i - omega^2 r_i^2 / 2) over the link angles, with NLopt.
 * Output as `whirl shape --links N` (its two comment lines, then the CSV s,r,z,tension, one row
 * per node, the pivot first), with a third comment line of the minimiser's statistics.
 * Only mode 1 is a minimum of V: mode k >= 2 is a saddle with k-1 negative in-plane directions,
 * so a minimiser started next to it falls to mode 1 (tests/unit/optimize/test_optimize.c checks both). Below
 * the first critical rate the hanging chain is the minimum and there is no shape to report. */
#include <stdlib.h>

#include <nlopt.h>

#include "cli/steady_cli.h"
#include "whirl/optimize.h"

#define MINIMIZE_MAX_LINKS 2000 /* the dense Hessian: O(N^2) memory, O(N^3) work */

/* The progress line: NLopt's evaluations against the cap (the time left is to the cap: a run
 * that converges ends sooner). */
typedef struct minimize_progress {
    cli_progress_state state;
    long done; /* evaluations at the last call */
} minimize_progress;

static void show_progress(void *data, int evaluations, int max_evaluations)
{
    minimize_progress *p = data;
    p->state.total = max_evaluations;
    p->done = evaluations;
    cli_progress_update(&p->state, evaluations, 0);
}

/* whirl_minimize_shape with a progress line on a terminal: its status, its time in *elapsed. */
static int minimize(const cli_command *cmd, const whirl_chain *c, double omega,
                    whirl_minimize_options mo, double *theta, whirl_minimize_stats *st,
                    double *elapsed)
{
    minimize_progress progress = {.done = 0};
    cli_progress_begin(&progress.state, cmd, "evaluations (the time left: to the cap)",
                       mo.max_evaluations > 0 ? mo.max_evaluations : 100000, 0);
    mo.progress = show_progress;
    mo.progress_data = &progress;
    const double t0 = cli_wall_seconds();
    const int status = whirl_minimize_shape(c, omega, &mo, NULL, theta, st);
    *elapsed = cli_wall_seconds() - t0;
    if (progress.state.shown > progress.state.start) /* a line was shown: end it */
        cli_progress_update(&progress.state,
                            status == GSL_SUCCESS ? st->evaluations : progress.done, 1);
    return status;
}

/* The error of a failed minimisation; returns 1. */
static int minimize_error(const cli_command *cmd, const steady_cli_model *m, double omega,
                          int status)
{
    if (status == GSL_EDOM) {
        const double rate = cli_units_rate(&m->units);
        double omega_1;
        if (steady_cli_critical(cmd, m, 1, &omega_1) == 0)
            cli_error(cmd, "no mode-1 shape at omega=%s: up to omega_1=%s the hanging "
                      "chain is the minimum", CLI_NUM(omega * rate), CLI_NUM(omega_1 * rate));
        return 1;
    }
    return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m->units));
}

/* The shape of the link angles theta as `whirl shape --links N` writes it, with the minimiser's
 * statistics as an extra comment line; r: room for 3 (N + 1) numbers. 0, or 1 after an error. */
static int write_minimum(const cli_command *cmd, const steady_cli_model *m, double omega,
                         const double *theta, double *r, const char *algorithm,
                         const whirl_minimize_stats *st, double elapsed, const char *output)
{
    const double len = m->units.length, force = cli_units_force(&m->units);
    const size_t n = m->chain->n;
    double *z = r + (n + 1), *tension = z + (n + 1);
    whirl_shape_info info;
    whirl_angles_shape(m->chain, omega, theta, r, z, tension, &info);
    char stats[512];
    snprintf(stats, sizeof stats, "minimum of V: algorithm=%s evaluations=%d nlopt_result=%s "
             "newton_steps=%d potential=%s gradient_norm=%.3g min_curvature=%s seconds=%.3g",
             algorithm, st->evaluations, nlopt_result_to_string((nlopt_result)st->nlopt_result),
             st->newton_steps, CLI_NUM(st->potential * force * len),
             st->gradient_norm * force * len, CLI_NUM(st->min_curvature * force * len), elapsed);
    double *s = malloc((n + 1) * sizeof *s);
    if (s == NULL) return cli_error(cmd, "out of memory for %zu links", n);
    s[0] = 0;
    for (size_t i = 1; i <= n; i++) s[i] = s[i - 1] + m->chain->length[i - 1];
    cli_out out;
    if (cli_out_open(cmd, &out, output)) {
        free(s);
        return 1;
    }
    steady_cli_write_shape(out.fp, m, &info, n + 1, s, r, z, tension, stats);
    free(s);
    return cli_out_commit(cmd, &out);
}

int cmd_minimize(const cli_command *cmd, int argc, char **argv)
{
    double omega = 0;
    int omega_given = 0, no_polish = 0, max_evaluations = 0;
    const char *algorithm = "LD_LBFGS", *output = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {.name = "--omega", .type = CLI_DOUBLE, .value = &omega, .given = &omega_given, .meta = "W",
         .help = "rotation rate", .range = "(0, inf)", .required = "", .unit = CLI_UNIT_RATE},
        STEADY_CLI_MODEL_OPTIONS(m),
        {.name = "--algorithm", .type = CLI_STRING, .value = &algorithm, .meta = "NAME",
         .help = "NLopt algorithm (default LD_LBFGS; e.g. LD_TNEWTON, LN_BOBYQA)"},
        {.name = "--max-evaluations", .type = CLI_INT, .value = &max_evaluations, .meta = "E",
         .help = "cap on NLopt's evaluations of V (default 100000)", .range = "[0, inf)"},
        {.name = "--no-polish", .type = CLI_FLAG, .value = &no_polish,
         .help = "skip the final Newton steps on the analytic Hessian"},
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &output, .meta = "FILE",
         .help = "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    if (!m.links_given) return cli_error(cmd, "--links is required (the N-link chain is minimised)");
    if (m.links > MINIMIZE_MAX_LINKS)
        return cli_error(cmd, "--links must be at most %d, got %d", MINIMIZE_MAX_LINKS, m.links);
    int alg;
    if (whirl_minimize_algorithm(algorithm, &alg) != GSL_SUCCESS)
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m.units));
    if (steady_cli_model_setup(cmd, &m)) return 1;

    const size_t n = m.chain->n;
    double *theta = malloc(n * sizeof *theta), *r = malloc(3 * (n + 1) * sizeof *r);
    whirl_minimize_options mo = whirl_minimize_options_defaults();
    mo.algorithm = algorithm;
    mo.polish = !no_polish;
    mo.max_evaluations = max_evaluations;
    whirl_minimize_stats st;
    double elapsed = 0;
    int status = GSL_SUCCESS;
    if (theta == NULL || r == NULL)
        rc = cli_error(cmd, "out of memory for %zu links", n);
    else if ((status = minimize(cmd, m.chain, omega, mo, theta, &st, &elapsed)) != GSL_SUCCESS)
        rc = minimize_error(cmd, &m, omega, status);
    else
        rc = write_minimum(cmd, &m, omega, theta, r, algorithm, &st, elapsed, output);
    free(theta);
    free(r);
    steady_cli_model_free(&m);
    return rc;
}
