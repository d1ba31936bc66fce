/* whirl stability --windows --links N with --damping D or the hand-swung chain's drag (--eps,
 * --drag, --drag-quadratic / --drag-cd, --side): the intervals of omega where each mode is
 * unstable or converging (whirl_windows_dissipative), one row per interval:
 *   mode,links,from,to,open_from,open_to,freq_from,freq_to,growth,at,verdict
 * growth: the largest growth rate inside an unstable interval, the most negative one inside a
 * converging interval, at the rate at; freq: |Im lambda| of the eigenvalue that crosses the
 * imaginary axis at each edge. The modes run one per thread, the modes done shown on a
 * terminal; Ctrl-C stops them: the modes finished are written (a mode's intervals are complete
 * only at its end), the others marked "# mode K: interrupted, not done", exit 130. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/stability_dissipative.h"
#include "core/error.h"

#define DISSIPATIVE_MAX 256

int stability_dissipative(const cli_command *cmd, const cli_int_list *modes, int links,
                          double tip_mass, const whirl_model *model, int side, const whirl_windows_params *p,
                          const cli_units *units, const char *output)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)links, tip_mass);
    if (c == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(units));
    const size_t nmodes = (size_t)modes->n;
    whirl_dissipative_interval *iv = calloc(nmodes * DISSIPATIVE_MAX, sizeof *iv);
    size_t *count = calloc(nmodes, sizeof *count);
    whirl_windows_stats *stats = calloc(nmodes, sizeof *stats);
    double *seconds = calloc(nmodes, sizeof *seconds);
    whirl_error_record *err = calloc(nmodes, sizeof *err); /* each mode's failure */
    int *status = calloc(nmodes, sizeof *status);
    int rc = 0;
    if (!iv || !count || !stats || !seconds || !err || !status)
        rc = cli_error(cmd, "out of memory");
    whirl_model m = *model;
    m.chain = c;
    cli_catch_interrupts();
    cli_progress_state progress;
    long finished = 0;
    cli_progress_begin(&progress, cmd, "modes", (long)nmodes, 0);
#pragma omp parallel for schedule(dynamic, 1)
    for (size_t k = 0; k < (rc ? 0 : nmodes); k++) {
        const double t0 = cli_wall_seconds();
        status[k] = whirl_windows_dissipative(&m, modes->v[k], side, p,
                                              iv + k * DISSIPATIVE_MAX, DISSIPATIVE_MAX,
                                              &count[k], &stats[k]);
        whirl_error_keep(&err[k], status[k]);
        seconds[k] = cli_wall_seconds() - t0;
#pragma omp critical
        cli_progress_update(&progress, ++finished, 0);
    }
    cli_progress_update(&progress, finished, 1);
    /* a failure other than a stop: nothing written; a stop: the modes finished are written */
    size_t done = 0;
    for (size_t k = 0; k < (rc ? 0 : nmodes); k++) {
        done += status[k] == GSL_SUCCESS;
        if (status[k] != GSL_SUCCESS && status[k] != WHIRL_EINTERRUPTED && !rc) {
            whirl_error_restore(&err[k]);
            rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(units));
        }
    }
    cli_out out;
    if (!rc && cli_out_open(cmd, &out, output)) rc = 1;
    if (!rc) {
        const double rate = cli_units_scale(units, CLI_UNIT_RATE);
        fprintf(out.fp, "# whirl stability --windows: %d links, tip mass %s, damping %s, eps %s, "
                        "drag %s, drag_quadratic %s, side %d; omega %s..%s, scan step %s, edges "
                        "to %s (roots of the growth, Brent)\n", links,
                CLI_NUM(tip_mass * cli_units_scale(units, CLI_UNIT_MASS)),
                CLI_NUM(m.internal_damping * cli_units_scale(units, CLI_UNIT_DAMPING)),
                CLI_NUM(m.drive_radius * cli_units_scale(units, CLI_UNIT_LENGTH)),
                CLI_NUM(m.air_drag * cli_units_scale(units, CLI_UNIT_DRAG)),
                CLI_NUM(m.air_drag_quadratic * cli_units_scale(units, CLI_UNIT_DRAG2)),
                m.drive_radius > 0 ? side : 0, CLI_NUM(p->omega_min * rate),
                CLI_NUM(p->omega_max * rate), CLI_NUM(p->scan_step * rate),
                CLI_NUM(p->tol * rate));
        for (size_t k = 0; k < nmodes; k++)
            if (status[k] != GSL_SUCCESS)
                fprintf(out.fp, "# mode %d: interrupted, not done\n", modes->v[k]);
            else
                fprintf(out.fp, "# mode %d: examined %s..%s, %zu intervals, %zu scan points, "
                                "%zu eigen-solves, %zu shapes, %.3g s\n",
                        modes->v[k], CLI_NUM(stats[k].omega_from * rate),
                        CLI_NUM(stats[k].omega_to * rate), count[k], stats[k].scan,
                        stats[k].solves_values, stats[k].shapes, seconds[k]);
        cli_units_comment(out.fp, units);
        fprintf(out.fp, "mode,links,from,to,open_from,open_to,freq_from,freq_to,growth,at,"
                        "verdict\n");
        for (size_t k = 0; k < nmodes; k++)
            for (size_t i = 0; status[k] == GSL_SUCCESS && i < count[k]; i++) {
                const whirl_dissipative_interval *x = iv + k * DISSIPATIVE_MAX + i;
                fprintf(out.fp, "%d,%d,%s,%s,%d,%d,%s,%s,%s,%s,%s\n", modes->v[k], links,
                        CLI_NUM(x->from * rate), CLI_NUM(x->to * rate), x->open_from,
                        x->open_to, CLI_NUM(x->freq_from * rate), CLI_NUM(x->freq_to * rate),
                        CLI_NUM(x->growth * rate), CLI_NUM(x->at * rate),
                        whirl_verdict_name(x->verdict));
            }
        if (cli_out_commit(cmd, &out)) rc = 1;
    }
    if (!rc && done < nmodes) {
        const int file = output != NULL && strcmp(output, "-") != 0;
        cli_error(cmd, "interrupted: %zu of %zu modes done%s%s%s", done, nmodes,
                  file ? " in '" : "", file ? output : "", file ? "'" : "");
        rc = CLI_EXIT_INTERRUPTED;
    }
    free(iv), free(count), free(stats), free(seconds), free(err), free(status);
    whirl_chain_free(c);
    return rc;
}
