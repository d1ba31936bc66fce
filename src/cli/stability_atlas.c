/* whirl windows --atlas: the library's stability atlas (whirl/atlas.h: every window of the
 * continuum's modes from each birth to --omega-max, with the Krein signatures at its edges)
 * computed chunk by chunk into -o FILE, rewritten (atomically) after each chunk computed with
 * the windows so far and the chunks done. Ctrl-C keeps the chunks finished; --resume takes them
 * back (whirl_atlas_read: the header the same as this run's, every line checked) and computes
 * the rest, the file locked for the whole run (cli_lock). A terminal shows the chunks done. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/stability_atlas.h"
#include "core/error.h"
#include "whirl/atlas.h"
#include "whirl/steady.h"

/* The file rewritten with a's chunks and rows, the lock passed to it. */
static int write_atlas(const cli_command *cmd, cli_lock *lock, const char *path,
                       const whirl_atlas *a)
{
    const size_t len = whirl_atlas_text(a, NULL, 0);
    char *text = malloc(len + 1);
    if (text == NULL) return cli_error(cmd, "out of memory");
    whirl_atlas_text(a, text, len + 1);
    cli_out out;
    int rc = cli_out_open(cmd, &out, path);
    if (!rc) {
        fwrite(text, 1, len, out.fp);
        rc = cli_lock_commit(cmd, lock, &out);
    }
    free(text);
    return rc;
}

/* The atlas of these options (NULL after printing the error). */
static whirl_atlas *atlas_alloc(const cli_command *cmd, const cli_int_list *modes,
                                double omega_max, int degree, double memory_mb, double tol,
                                double scan_step)
{
    whirl_atlas_params p = whirl_atlas_defaults();
    p.n_modes = modes->n;
    memcpy(p.modes, modes->v, (size_t)modes->n * sizeof *p.modes);
    p.omega_max = omega_max;
    p.degree = degree;
    p.tol = tol;
    p.scan_step = scan_step;
    p.memory_mb = memory_mb;
    whirl_atlas *a = whirl_atlas_alloc(&p);
    if (a == NULL) cli_error(cmd, "%s", whirl_last_error());
    return a;
}

int stability_atlas_check(const cli_command *cmd, FILE *in, const char *path,
                          const cli_int_list *modes, double omega_max, int degree, double tol,
                          double scan_step)
{
    whirl_atlas *a = atlas_alloc(cmd, modes, omega_max, degree,
                                 whirl_atlas_defaults().memory_mb, tol, scan_step);
    int rc = a ? 0 : 1;
    if (a && whirl_atlas_read(a, in, path))
        rc = cli_error(cmd, "--resume: %s", whirl_last_error());
    whirl_atlas_free(a);
    return rc;
}

int stability_memory_failure(int status)
{
    if (status == GSL_EMAXITER && strstr(whirl_last_error(), "raise the memory bound"))
        return whirl_fail(status, "%s (--memory MB)", whirl_error_marked());
    return status;
}

/* The chunks of the n modes not done yet, the file rewritten after each computed: 0,
 * CLI_EXIT_INTERRUPTED, or 1 after an error. */
static int atlas_chunks(const cli_command *cmd, whirl_atlas *a, int n, cli_lock *lock,
                        const char *output, cli_progress_state *progress, long *finished)
{
    for (size_t k = 0; k < (size_t)n; k++)
        for (size_t j = 0; j < whirl_atlas_chunks(a); j++) {
            if (whirl_atlas_done(a, k, j)) continue;
            int computed;
            const int status = stability_memory_failure(whirl_atlas_compute(a, k, j, &computed));
            if (status == WHIRL_EINTERRUPTED) return CLI_EXIT_INTERRUPTED;
            if (status) return cli_error(cmd, "%s", whirl_last_error());
            const int rc = computed ? write_atlas(cmd, lock, output, a) : 0;
            cli_progress_update(progress, ++*finished, 0);
            if (rc) return rc;
        }
    return 0;
}

int stability_atlas(const cli_command *cmd, const cli_int_list *modes, double omega_max,
                    int degree, double memory_mb, double tol, double scan_step,
                    const char *output, int resume)
{
    if (!(omega_max > 0 && omega_max <= WHIRL_CONTINUUM_OMEGA_MAX))
        return cli_error(cmd, "--omega-max must be in (0, %g] for the atlas",
                         WHIRL_CONTINUUM_OMEGA_MAX);
    if (output == NULL || strcmp(output, "-") == 0)
        return cli_error(cmd, "--atlas needs -o FILE (it is rewritten after every chunk)");
    whirl_atlas *a = atlas_alloc(cmd, modes, omega_max, degree, memory_mb, tol, scan_step);
    if (a == NULL) return 1;
    /* the file locked from before it is read until the run ends: one run at a time writes it
     * (a new path is made empty by the run that starts it) */
    cli_lock lock = {0};
    int rc = cli_lock_take(cmd, &lock, output, !resume);
    if (!rc && resume && lock.fp == NULL)
        rc = cli_error(cmd, "--resume: cannot read '%s': no such regular file", output);
    if (!rc && resume && whirl_atlas_read(a, lock.fp, output))
        rc = cli_error(cmd, "--resume: %s", whirl_last_error());
    const long total = (long)modes->n * (long)whirl_atlas_chunks(a);
    long finished = (long)whirl_atlas_done_count(a);
    cli_progress_state progress;
    cli_progress_begin(&progress, cmd, "chunks", total, finished);
    cli_catch_interrupts();
    if (!rc) rc = atlas_chunks(cmd, a, modes->n, &lock, output, &progress, &finished);
    cli_progress_update(&progress, finished, 1);
    if (rc == CLI_EXIT_INTERRUPTED)
        cli_error(cmd, "interrupted: %ld of %ld chunks in '%s' (continue with --resume)",
                  finished, total, output);
    else if (!rc && write_atlas(cmd, &lock, output, a)) /* all chunks */
        rc = 1;
    cli_lock_release(&lock);
    whirl_atlas_free(a);
    return rc;
}
