/* Reading the measured points of `whirl fit` (see points_csv.h). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#include "cli/points_csv.h"
#include "core/input.h"

static int points_push(points_csv *p, double r, double z)
{
    if (p->n == p->cap) {
        const size_t cap = p->cap ? 2 * p->cap : 64;
        double *nr = realloc(p->r, cap * sizeof *nr);
        if (nr == NULL) return -1;
        p->r = nr;
        double *nz = realloc(p->z, cap * sizeof *nz);
        if (nz == NULL) return -1;
        p->z = nz;
        p->cap = cap;
    }
    p->r[p->n] = r;
    p->z[p->n] = z;
    p->n++;
    return 0;
}

void points_csv_free(points_csv *p)
{
    free(p->r);
    free(p->z);
    p->r = p->z = NULL;
    p->n = p->cap = 0;
}

/* Cuts the next comma-separated field off *line (NULL when none is left), without the blanks
 * and double quotes around it. */
static char *next_field(char **line)
{
    if (*line == NULL) return NULL;
    char *f = *line, *comma = strchr(f, ',');
    if (comma) {
        *comma = '\0';
        *line = comma + 1;
    } else {
        *line = NULL;
    }
    while (*f == ' ' || *f == '\t') f++;
    char *end = f + strlen(f);
    while (end > f && (end[-1] == ' ' || end[-1] == '\t' || end[-1] == '\r' || end[-1] == '\n'))
        *--end = '\0';
    if (end - f >= 2 && f[0] == '"' && end[-1] == '"') {
        end[-1] = '\0';
        f++;
    }
    return f;
}

static int is_blank_or_comment(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
    return *s == '\0' || *s == '#';
}

/* One data line into p: 0, or 1 after an error. */
static int read_row(const cli_command *cmd, const char *name, long lineno, char *rest,
                    long col_r, long col_z, points_csv *p)
{
    double v[2] = {NAN, NAN};
    int have[2] = {0, 0};
    char *f;
    for (long col = 0; (f = next_field(&rest)) != NULL; col++) {
        const int which = col == col_r ? 0 : (col == col_z ? 1 : -1);
        if (which < 0) continue;
        char *end;
        v[which] = strtod(f, &end);
        if (*f == '\0' || *end != '\0')
            return cli_error(cmd, "%s:%ld: %s = '%.40s' is not a number", name, lineno,
                             which ? "z" : "r", f);
        if (!isfinite(v[which]))
            return cli_error(cmd, "%s:%ld: %s = '%.40s' is not finite", name, lineno,
                             which ? "z" : "r", f);
        have[which] = 1;
    }
    if (!have[0] || !have[1])
        return cli_error(cmd, "%s:%ld: no value in column '%s'", name, lineno, have[0] ? "z" : "r");
    if (points_push(p, v[0], v[1]) != 0)
        return cli_error(cmd, "%s:%ld: out of memory for the points (%zu read)", name, lineno,
                         p->n);
    return 0;
}

int points_csv_read(const cli_command *cmd, FILE *fp, const char *name, points_csv *p)
{
    whirl_line_reader in =
        whirl_line_reader_init(fp, name, POINTS_CSV_LINE_MAX, POINTS_CSV_BYTES_MAX);
    long col_r = -1, col_z = -1;
    int rc = 0, header_seen = 0, got;
    while (rc == 0 && (got = whirl_line_read(&in)) > 0) {
        char *line = in.line;
        const long lineno = in.lineno;
        if (strlen(line) != in.len) {
            rc = cli_error(cmd, "%s:%ld: NUL byte at column %zu (a binary file?)", name, lineno,
                           strlen(line) + 1);
            break;
        }
        if (is_blank_or_comment(line)) continue;
        if (header_seen) {
            rc = read_row(cmd, name, lineno, line, col_r, col_z, p);
            continue;
        }
        header_seen = 1; /* the first line that is not a comment */
        char *rest = line, *f;
        for (long col = 0; (f = next_field(&rest)) != NULL; col++) {
            if (strcmp(f, "r") == 0 && col_r < 0) col_r = col;
            if (strcmp(f, "z") == 0 && col_z < 0) col_z = col;
        }
        if (col_r < 0 || col_z < 0)
            rc = cli_error(cmd, "%s:%ld: the header has no column '%s' (columns r and z are "
                           "required)", name, lineno, col_r < 0 ? "r" : "z");
    }
    if (rc == 0 && in.status != GSL_SUCCESS) rc = cli_error(cmd, "%s", whirl_last_error());
    whirl_line_reader_free(&in);
    if (rc == 0 && !header_seen)
        rc = cli_error(cmd, "%s: no header line (columns r and z are required)", name);
    return rc;
}

int points_csv_read_path(const cli_command *cmd, const char *path, points_csv *p)
{
    if (path[0] == '\0') return cli_error(cmd, "--shape: empty file name");
    const int std_in = strcmp(path, "-") == 0;
    FILE *fp = stdin;
    if (!std_in && whirl_input_open(path, &fp) != GSL_SUCCESS)
        return cli_error(cmd, "%s", whirl_last_error());
    int rc = points_csv_read(cmd, fp, std_in ? "standard input" : path, p);
    if (!std_in) fclose(fp);
    return rc;
}
