/* The charts' file and --resume (chart_file.h). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli/chart_file.h"

/* text appended to the state (f->state grown as needed). 0, or 1 without memory. */
static int state_append(chart_file *f, const char *text)
{
    const size_t have = f->state ? strlen(f->state) : 0, len = strlen(text);
    if (have + len + 1 > f->state_cap) {
        const size_t cap = 2 * (have + len + 1) + 256;
        char *s = realloc(f->state, cap);
        if (s == NULL) return 1;
        f->state = s, f->state_cap = cap;
    }
    memcpy(f->state + have, text, len + 1);
    return 0;
}

chart_units chart_file_units(const cli_units *u)
{
    return (chart_units){.physical = u->physical, .length = u->length, .mass = u->mass,
                         .gravity = u->gravity, .mass_given = u->mass_given};
}

int chart_file_open(const cli_command *cmd, chart_file *f, const char *path, int resume)
{
    *f = (chart_file){.cmd = cmd, .path = path && strcmp(path, "-") != 0 ? path : NULL};
    if (resume && f->path == NULL)
        return cli_error(cmd, "--resume needs -o FILE, not standard output");
    if (cli_lock_take(cmd, &f->lock, f->path, !resume)) return 1;
    if (!resume || f->lock.fp != NULL) return 0;
    FILE *fp = fopen(path, "r");
    const int err = fp ? EINVAL : errno;
    if (fp) fclose(fp);
    return cli_error(cmd, "--resume: cannot read '%s': %s", path,
                     err == EINVAL ? "not a regular file" : strerror(err));
}

int chart_file_read(chart_file *f, int status)
{
    if (status == GSL_ENOMEM) return cli_error(f->cmd, "out of memory");
    if (status) return cli_error(f->cmd, "--resume: %s", whirl_last_error());
    if (state_append(f, f->rd.state)) return cli_error(f->cmd, "out of memory");
    f->done = f->rd.done;
    return 0;
}

int chart_file_save(chart_file *f, int done, const char *state, size_t rows)
{
    if (f->state) f->state[0] = '\0';
    if (state_append(f, state)) return GSL_ENOMEM;
    f->done = done;
    f->rows_done = rows;
    return GSL_SUCCESS;
}

void chart_file_write_state(const chart_file *f, FILE *fp)
{
    for (const char *s = f->state; s && *s;) {
        const size_t len = strcspn(s, "\n");
        fprintf(fp, "%s%.*s\n", CHART_STATE, (int)len, s);
        s += len + (s[len] == '\n');
    }
}

int chart_file_commit(chart_file *f, cli_out *out)
{
    return cli_lock_commit(f->cmd, &f->lock, out);
}

int chart_file_start(chart_file *f, int rc, int links, int resume, const cli_units *units,
                     whirl_chain **c, cli_out *out, char **state)
{
    *c = rc ? NULL : whirl_chain_alloc_uniform((size_t)links, 0);
    if (rc == 0 && *c == NULL) rc = cli_error(f->cmd, "%s", CLI_LIBRARY_ERROR(units));
    if (rc == 0) rc = cli_out_open(f->cmd, out, f->path);
    if (rc) {
        whirl_chain_free(*c);
        chart_file_free(f);
        return rc;
    }
    *state = resume && f->state ? strdup(f->state) : NULL;
    return 0;
}

int chart_file_finish(chart_file *f, int status, int written, int columns, int resumed,
                      const cli_units *units)
{
    if (status == WHIRL_EINTERRUPTED && written == 0)
        return cli_error(f->cmd, "interrupted after %d of %d rates: the %zu points found until "
                         "then are written%s", f->done, columns, f->rd.n_kept + f->rows_done,
                         f->path ? " (continue with --resume)" : ""),
               CLI_EXIT_INTERRUPTED;
    if (status == GSL_SUCCESS || status == WHIRL_EINTERRUPTED) return written;
    if (resumed && status == GSL_EINVAL && strncmp(whirl_last_error(), "state line", 10) == 0)
        return cli_error(f->cmd, "--resume: '%s': the chart's %s: the file cannot be trusted",
                         f->path, whirl_last_error());
    return cli_error(f->cmd, "%s", status == GSL_ENOMEM && whirl_last_status() != GSL_ENOMEM
                                       ? "out of memory for the chart's points"
                                       : CLI_LIBRARY_ERROR(units));
}

void chart_file_free(chart_file *f)
{
    chart_read_free(&f->rd);
    free(f->state);
    cli_lock_release(&f->lock);
    *f = (chart_file){0};
}
