/* The charts' file and --resume (chart_file.h). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli/chart_file.h"

/* The longest line of a chart file: a row is five numbers (at most ~130 characters), a state's
 * line at most 400 (periodic/chart_state.c) and its prefix. */
#define CHART_LINE_MAX 1024

static int by_text(const void *a, const void *b)
{
    const chart_kept *p = *(const chart_kept *const *)a, *q = *(const chart_kept *const *)b;
    const int c = strcmp(p->line, q->line);
    return c ? c : (p->lineno > q->lineno) - (p->lineno < q->lineno);
}

/* A row read twice: the later one refused. */
static int duplicates(chart_file *f)
{
    if (f->n_kept < 2) return 0;
    const chart_kept **order = malloc(f->n_kept * sizeof *order);
    if (order == NULL) return cli_error(f->cmd, "out of memory");
    for (size_t i = 0; i < f->n_kept; i++) order[i] = &f->kept[i];
    qsort(order, f->n_kept, sizeof *order, by_text);
    int rc = 0;
    for (size_t i = 1; i < f->n_kept && rc == 0; i++)
        if (strcmp(order[i]->line, order[i - 1]->line) == 0) {
            char why[64];
            snprintf(why, sizeof why, "the row of line %ld again", order[i - 1]->lineno);
            rc = chart_file_refuse(f, order[i], why);
        }
    free(order);
    return rc;
}

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

/* One line of the file after the header's (or a "# found: " line among them). */
static int read_line(chart_file *f, cli_resume_kind kind, const char *line, long *points,
                     chart_row_check check, void *ctx)
{
    const size_t len = strlen(line);
    if (kind == CLI_RESUME_NOTE) {
        if (line[0] == '\n') return 0; /* a break between curves */
        if (strncmp(line, CHART_STATE, strlen(CHART_STATE)) == 0) {
            if (state_append(f, line + strlen(CHART_STATE)))
                return cli_error(f->cmd, "out of memory");
            return 0;
        }
        if (strncmp(line, CHART_FOUND, strlen(CHART_FOUND)) != 0 || f->n_kept > 0 || f->state)
            return cli_resume_refuse(f->in, "a comment among the rows") ? 1 : 0;
        long p;
        char *end;
        if (strncmp(line + strlen(CHART_FOUND), "points=", 7) != 0) return 0;
        p = strtol(line + strlen(CHART_FOUND) + 7, &end, 10);
        if (*points >= 0 || end == line + strlen(CHART_FOUND) + 7 || p < 0)
            return cli_resume_refuse(f->in, "a second or unreadable count of the points") ? 1
                                                                                           : 0;
        *points = p;
        return 0;
    }
    if (f->state) return cli_resume_refuse(f->in, "a row after the chart's state") ? 1 : 0;
    chart_kept k = {.lineno = cli_resume_lineno(f->in)};
    const char *why = check(ctx, line, &k);
    if (why) return cli_resume_refuse(f->in, "%s", why) ? 1 : 0;
    if ((f->n_kept & (f->n_kept - 1)) == 0) { /* 0, 1, 2, 4, ...: doubled */
        chart_kept *grown = realloc(f->kept, (f->n_kept ? 2 * f->n_kept : 1) * sizeof *grown);
        if (grown == NULL) return cli_error(f->cmd, "out of memory");
        f->kept = grown;
    }
    if ((k.line = malloc(len + 1)) == NULL) return cli_error(f->cmd, "out of memory");
    memcpy(k.line, line, len + 1);
    f->kept[f->n_kept++] = k;
    return 0;
}

int chart_file_open(const cli_command *cmd, chart_file *f, const char *path, int resume,
                    const char *header, chart_row_check check, void *ctx)
{
    *f = (chart_file){.cmd = cmd, .path = path && strcmp(path, "-") != 0 ? path : NULL};
    if (resume && f->path == NULL)
        return cli_error(cmd, "--resume needs -o FILE, not standard output");
    if (cli_lock_take(cmd, &f->lock, f->path, !resume)) return 1;
    if (!resume) return 0;
    if (f->lock.fp == NULL) {
        FILE *fp = fopen(path, "r");
        const int err = fp ? EINVAL : errno;
        if (fp) fclose(fp);
        return cli_error(cmd, "--resume: cannot read '%s': %s", path,
                         err == EINVAL ? "not a regular file" : strerror(err));
    }
    const cli_resume_params rp = {.header = header, .kind = "chart", .of = "options",
                                  .note = CHART_FOUND, .line_max = CHART_LINE_MAX, .blank = 1};
    if ((f->in = cli_resume_alloc(cmd, f->lock.fp, path, &rp)) == NULL) return 1;
    long points = -1;
    int rc = 0;
    const char *line;
    for (cli_resume_kind kind; !rc && (kind = cli_resume_next(f->in, &line)) != CLI_RESUME_END;)
        rc = kind == CLI_RESUME_ERROR ? 1 : read_line(f, kind, line, &points, check, ctx);
    if (rc) return rc;
    if (f->state == NULL)
        return cli_error(cmd, "--resume: '%s' holds no chart state (its '%s' lines at the end): "
                         "not a chart of this version, or cut short", path, CHART_STATE);
    if (points != (long)f->n_kept)
        return cli_error(cmd, "--resume: '%s' holds %zu rows where its '%spoints=' line says "
                         "%ld: rows were removed or added; the file cannot be trusted", path,
                         f->n_kept, CHART_FOUND, points);
    f->done = (int)chart_file_state_value(f, "columns", -1);
    return duplicates(f);
}

long chart_file_state_value(const chart_file *f, const char *key, long fallback)
{
    const size_t len = strlen(key);
    for (const char *s = f->state; s && (s = strstr(s, key)) != NULL; s += len)
        if ((s == f->state || s[-1] == ' ') && s[len] == '=') {
            char *end;
            const long x = strtol(s + len + 1, &end, 10);
            return end == s + len + 1 ? fallback : x;
        }
    return fallback;
}

int chart_file_refuse(chart_file *f, const chart_kept *k, const char *why)
{
    return cli_resume_refuse_at(f->in, k->lineno, "%s", why) ? 1 : 0;
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
                         "then are written%s", f->done, columns, f->n_kept + f->rows_done,
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
    for (size_t i = 0; i < f->n_kept; i++) free(f->kept[i].line);
    free(f->kept);
    free(f->state);
    cli_resume_free(f->in);
    cli_lock_release(&f->lock);
    *f = (chart_file){0};
}
