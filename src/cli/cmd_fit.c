/* whirl fit: the rotation rate (and mode) that best explains a measured shape.
 * Reads a CSV of points with columns r and z (header required, other columns ignored, '#'
 * comments and blank lines skipped, any order along the chain, the pivot at the origin, lengths
 * in the units of --length), fits with whirl_fit and writes one row
 * omega,omega_err,mode,rms_residual: omega in the units of `whirl shape` (sqrt(g/L), or rad/s
 * with --length and --gravity), the residual in the data's units. So fit inverts shape: the
 * points of `whirl shape --omega W --mode K` (with the same unit options) give back W and K.
 * On a terminal a progress line shows the mode being fitted and the model evaluations. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/steady_cli.h"
#include "cli/points_csv.h"
#include "whirl/optimize.h"


/* The progress line: modes done of those tried, the current one and its evaluations. */
typedef struct fit_progress {
    cli_progress_state state;
    char label[96];
    long done; /* modes done */
} fit_progress;

static void show_progress(void *data, int mode, int first, int last, int evaluations)
{
    fit_progress *f = data;
    if (f->state.total == 0) {
        f->state.total = last - first + 1;
        f->state.label = f->label;
    }
    snprintf(f->label, sizeof f->label, "mode %d, %d model evaluations; modes done", mode,
             evaluations);
    f->done = mode - first;
    cli_progress_update(&f->state, f->done, 0);
}

/* The factor that takes the points, in shape_unit (NULL: m), to the units of --length (m): 0,
 * or 1 after an error. */
static int shape_scale(const cli_command *cmd, const cli_units *units, const char *shape_unit,
                       double *scale)
{
    *scale = 1;
    if (!shape_unit) return 0;
    char one[32];
    int suffixed = 0;
    snprintf(one, sizeof one, "1%s", shape_unit);
    if (!units->physical)
        return cli_error(cmd, "--shape-unit %s needs --length (the chain's length in SI units)",
                         shape_unit);
    if (strlen(shape_unit) >= sizeof one - 1 ||
        whirl_parse_quantity(one, WHIRL_QUANTITY_LENGTH, scale, &suffixed) != 0 || !suffixed)
        return cli_error(cmd, "--shape-unit must be m, cm or mm, got '%s'", shape_unit);
    return 0;
}

/* whirl_fit_observed with a progress line on a terminal; returns its status. */
static int fit(const cli_command *cmd, const whirl_fit_model *model, const points_csv *p,
               int mode, whirl_fit_result *res)
{
    fit_progress progress = {.done = 0};
    cli_progress_begin(&progress.state, cmd, "modes done", 0, 0);
    const int status = whirl_fit_observed(model, p->n, p->r, p->z, mode, show_progress,
                                          &progress, res);
    if (progress.state.total > 0)
        cli_progress_update(&progress.state, status ? progress.done : progress.state.total, 1);
    return status;
}

/* The fit as CSV: 0, or 1 after an error. */
static int write_fit(const cli_command *cmd, const steady_cli_model *m, const points_csv *p,
                     const whirl_fit_result *res, const char *output)
{
    const double rate = cli_units_rate(&m->units), len = m->units.length;
    cli_out out;
    if (cli_out_open(cmd, &out, output)) return 1;
    fprintf(out.fp, "# model=%s points=%zu side=%s evaluations=%d solver_failures=%d\n",
            m->links_given ? "n-link" : "continuum", p->n, res->mirrored ? "r<0" : "r>0",
            res->evaluations, res->failures);
    cli_units_comment(out.fp, &m->units);
    fprintf(out.fp, "omega,omega_err,mode,rms_residual\n%s,%s,%d,%s\n",
            CLI_NUM(res->omega * rate), CLI_NUM(res->omega_err * rate), res->mode,
            CLI_NUM(res->rms_residual * len));
    return cli_out_commit(cmd, &out);
}

int cmd_fit(const cli_command *cmd, int argc, char **argv)
{
    const char *shape = NULL, *output = NULL, *shape_unit = NULL;
    int mode = 0, mode_given = 0, omega_max_given = 0;
    double omega_max = 0, max_residual = 0.02;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {.name = "--shape", .type = CLI_STRING, .value = &shape, .meta = "FILE",
         .help = "CSV of measured points with columns r and z, lengths in the units of --length (- "
                 "reads stdin)",
         .required = "", .input = 1},
        {.name = "--shape-unit", .type = CLI_STRING, .value = &shape_unit, .meta = "U",
         .help = "the unit of the points' r and z: m, cm or mm (needs --length; default: m)"},
        {.name = "--mode", .type = CLI_INT, .value = &mode, .given = &mode_given, .meta = "K",
         .help = "fit only mode K (default: the best mode)", .range = "[1, 64]"},
        STEADY_CLI_MODEL_OPTIONS(m),
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &omega_max, .given = &omega_max_given,
         .meta = "W", .help = "highest rate tried (default 50 sqrt(g/L))", .range = "(0, inf)",
         .unit = CLI_UNIT_RATE},
        {.name = "--max-residual", .type = CLI_DOUBLE, .value = &max_residual, .meta = "F",
         .help = "largest rms residual accepted, as a fraction of L (default 0.02)",
         .range = "(0, inf)"},
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &output, .meta = "FILE",
         .help = "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    if (m.links_given && m.links > WHIRL_FIT_LINKS_MAX)
        return cli_error(cmd, "--links must be at most %d, got %d", WHIRL_FIT_LINKS_MAX, m.links);
    if (steady_cli_model_setup(cmd, &m)) return 1;

    const double rate = cli_units_rate(&m.units), len = m.units.length;
    double scale;
    if (shape_scale(cmd, &m.units, shape_unit, &scale)) {
        steady_cli_model_free(&m);
        return 1;
    }
    whirl_fit_model model = whirl_fit_model_defaults();
    model.links = m.links_given ? (size_t)m.links : 0;
    model.tip_mass = steady_cli_tip_mass(&m);
    if (omega_max_given) model.omega_max = omega_max;

    points_csv p = {0, 0, NULL, NULL};
    whirl_fit_result res;
    rc = points_csv_read_path(cmd, shape, &p);
    if (rc == 0 && p.n < 3)
        rc = cli_error(cmd, "%s has %zu points; a fit needs at least 3", shape, p.n);
    for (size_t i = 0; rc == 0 && i < p.n; i++) {
        p.r[i] *= scale / len;
        p.z[i] *= scale / len;
    }
    if (rc == 0 && fit(cmd, &model, &p, mode, &res) != GSL_SUCCESS)
        rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m.units));
    if (rc == 0 && !(res.rms_residual <= max_residual)) {
        char which[32] = "no mode";
        if (mode_given) snprintf(which, sizeof which, "mode %d", mode);
        rc = cli_error(cmd, "%s explains the shape: the best fit (mode %d, omega=%.6g) leaves an "
                       "rms residual of %.3g L, above --max-residual %g", which, res.mode,
                       res.omega * rate, res.rms_residual, max_residual);
    }
    if (rc == 0) rc = write_fit(cmd, &m, &p, &res, output);
    points_csv_free(&p);
    steady_cli_model_free(&m);
    return rc;
}
