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

/* The intervals of each mode k: count[k] of them from iv + k DISSIPATIVE_MAX, found in
 * seconds[k] with stats[k] and status[k] (err[k]: its failure). */
typedef struct dissipative_found {
    whirl_dissipative_interval *iv;
    size_t *count;
    whirl_windows_stats *stats;
    double *seconds;
    whirl_error_record *err;
    int *status;
} dissipative_found;

static int found_alloc(dissipative_found *f, size_t nmodes)
{
    f->iv = calloc(nmodes * DISSIPATIVE_MAX, sizeof *f->iv);
    f->count = calloc(nmodes, sizeof *f->count);
    f->stats = calloc(nmodes, sizeof *f->stats);
    f->seconds = calloc(nmodes, sizeof *f->seconds);
    f->err = calloc(nmodes, sizeof *f->err);
    f->status = calloc(nmodes, sizeof *f->status);
    return f->iv && f->count && f->stats && f->seconds && f->err && f->status ? 0 : -1;
}

static void found_free(dissipative_found *f)
{
    free(f->iv), free(f->count), free(f->stats), free(f->seconds), free(f->err), free(f->status);
}

/* The first n modes (all, or none after a failed allocation) one per thread, the modes done
 * shown on a terminal. */
static void find_intervals(const cli_command *cmd, const cli_int_list *modes, size_t n,
                           const whirl_model *m, int side, const whirl_windows_params *p,
                           dissipative_found *f)
{
    cli_progress_state progress;
    long finished = 0;
    cli_progress_begin(&progress, cmd, "modes", (long)modes->n, 0);
#pragma omp parallel for schedule(dynamic, 1)
    for (size_t k = 0; k < n; k++) {
        const double t0 = cli_wall_seconds();
        f->status[k] = whirl_windows_dissipative(m, modes->v[k], side, p,
                                                 f->iv + k * DISSIPATIVE_MAX, DISSIPATIVE_MAX,
                                                 &f->count[k], &f->stats[k]);
        whirl_error_keep(&f->err[k], f->status[k]);
        f->seconds[k] = cli_wall_seconds() - t0;
#pragma omp critical
        cli_progress_update(&progress, ++finished, 0);
    }
    cli_progress_update(&progress, finished, 1);
}

/* The comment lines: the chain, the search, each mode's work (or that it was not done). */
static void write_comments(FILE *fp, const cli_int_list *modes, int links, double tip_mass,
                           const whirl_model *m, int side, const whirl_windows_params *p,
                           const cli_units *units, const dissipative_found *f)
{
    const double rate = cli_units_scale(units, CLI_UNIT_RATE);
    fprintf(fp, "# whirl stability --windows: %d links, tip mass %s, damping %s, eps %s, "
                "drag %s, drag_quadratic %s, side %d; omega %s..%s, scan step %s, edges "
                "to %s (roots of the growth, Brent)\n", links,
            CLI_NUM(tip_mass * cli_units_scale(units, CLI_UNIT_MASS)),
            CLI_NUM(m->internal_damping * cli_units_scale(units, CLI_UNIT_DAMPING)),
            CLI_NUM(m->drive_radius * cli_units_scale(units, CLI_UNIT_LENGTH)),
            CLI_NUM(m->air_drag * cli_units_scale(units, CLI_UNIT_DRAG)),
            CLI_NUM(m->air_drag_quadratic * cli_units_scale(units, CLI_UNIT_DRAG2)),
            m->drive_radius > 0 ? side : 0, CLI_NUM(p->omega_min * rate),
            CLI_NUM(p->omega_max * rate), CLI_NUM(p->scan_step * rate), CLI_NUM(p->tol * rate));
    for (int k = 0; k < modes->n; k++)
        if (f->status[k] != GSL_SUCCESS)
            fprintf(fp, "# mode %d: interrupted, not done\n", modes->v[k]);
        else
            fprintf(fp, "# mode %d: examined %s..%s, %zu intervals, %zu scan points, "
                        "%zu eigen-solves, %zu shapes, %.3g s\n",
                    modes->v[k], CLI_NUM(f->stats[k].omega_from * rate),
                    CLI_NUM(f->stats[k].omega_to * rate), f->count[k], f->stats[k].scan,
                    f->stats[k].solves_values, f->stats[k].shapes, f->seconds[k]);
    cli_units_comment(fp, units);
}

/* The rows: the intervals of the modes done. */
static void write_intervals(FILE *fp, const cli_int_list *modes, int links,
                            const cli_units *units, const dissipative_found *f)
{
    const double rate = cli_units_scale(units, CLI_UNIT_RATE);
    fprintf(fp, "mode,links,from,to,open_from,open_to,freq_from,freq_to,growth,at,verdict\n");
    for (int k = 0; k < modes->n; k++)
        for (size_t i = 0; f->status[k] == GSL_SUCCESS && i < f->count[k]; i++) {
            const whirl_dissipative_interval *x = f->iv + (size_t)k * DISSIPATIVE_MAX + i;
            fprintf(fp, "%d,%d,%s,%s,%d,%d,%s,%s,%s,%s,%s\n", modes->v[k], links,
                    CLI_NUM(x->from * rate), CLI_NUM(x->to * rate), x->open_from, x->open_to,
                    CLI_NUM(x->freq_from * rate), CLI_NUM(x->freq_to * rate),
                    CLI_NUM(x->growth * rate), CLI_NUM(x->at * rate),
                    whirl_verdict_name(x->verdict));
        }
}

/* The modes done; a failure other than a stop: its error (rc 1): nothing is written then. */
static size_t modes_done(const cli_command *cmd, size_t nmodes, const cli_units *units,
                         const dissipative_found *f, int *rc)
{
    size_t done = 0;
    for (size_t k = 0; k < nmodes; k++) {
        done += f->status[k] == GSL_SUCCESS;
        if (f->status[k] != GSL_SUCCESS && f->status[k] != WHIRL_EINTERRUPTED && !*rc) {
            whirl_error_restore(&f->err[k]);
            *rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(units));
        }
    }
    return done;
}

int stability_dissipative(const cli_command *cmd, const cli_int_list *modes, int links,
                          double tip_mass, const whirl_model *model, int side, const whirl_windows_params *p,
                          const cli_units *units, const char *output)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)links, tip_mass);
    if (c == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(units));
    const size_t nmodes = (size_t)modes->n;
    dissipative_found f;
    int rc = found_alloc(&f, nmodes) ? cli_error(cmd, "out of memory") : 0;
    whirl_model m = *model;
    m.chain = c;
    cli_catch_interrupts();
    find_intervals(cmd, modes, rc ? 0 : nmodes, &m, side, p, &f);
    /* a failure other than a stop: nothing written; a stop: the modes finished are written */
    const size_t done = rc ? 0 : modes_done(cmd, nmodes, units, &f, &rc);
    cli_out out;
    if (!rc && cli_out_open(cmd, &out, output)) rc = 1;
    if (!rc) {
        write_comments(out.fp, modes, links, tip_mass, &m, side, p, units, &f);
        write_intervals(out.fp, modes, links, units, &f);
        if (cli_out_commit(cmd, &out)) rc = 1;
    }
    if (!rc && done < nmodes) {
        const int file = output != NULL && strcmp(output, "-") != 0;
        cli_error(cmd, "interrupted: %zu of %zu modes done%s%s%s", done, nmodes,
                  file ? " in '" : "", file ? output : "", file ? "'" : "");
        rc = CLI_EXIT_INTERRUPTED;
    }
    found_free(&f);
    whirl_chain_free(c);
    return rc;
}
