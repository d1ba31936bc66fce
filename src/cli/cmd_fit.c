/* whirl fit: the rotation rate (and mode) that best explains a measured shape.
 * Reads a CSV of points with columns r and z (header required, other columns ignored, '#'
 * comments and blank lines skipped, any order along the chain, the pivot at the origin, lengths
 * in the units of --length), fits with whirl_fit and writes one row
 * omega,omega_err,mode,rms_residual: omega in the units of `whirl shape` (sqrt(g/L), or rad/s
 * with --length and --gravity), the residual in the data's units. So fit inverts shape: the
 * points of `whirl shape --omega W --mode K` (with the same unit options) give back W and K. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/steady_cli.h"
#include "whirl/optimize.h"

#define FIT_MAX_LINKS 2000
#define FIT_LINE_MAX 4096

/* The points read from the file. */
typedef struct points {
    size_t n, cap;
    double *r, *z;
} points;

static int points_push(points *p, double r, double z)
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

/* Reads the r and z columns of path. Returns 0, or 1 after printing an error. */
static int read_points(const cli_command *cmd, const char *path, points *p)
{
    FILE *fp = strcmp(path, "-") == 0 ? stdin : fopen(path, "r");
    if (fp == NULL) return cli_error(cmd, "cannot read '%s': %s", path, strerror(errno));
    char line[FIT_LINE_MAX];
    long lineno = 0, col_r = -1, col_z = -1;
    int rc = 0, header_seen = 0;
    while (fgets(line, sizeof line, fp)) {
        lineno++;
        if (strchr(line, '\n') == NULL && !feof(fp)) {
            rc = cli_error(cmd, "%s:%ld: line longer than %d characters", path, lineno, FIT_LINE_MAX - 1);
            break;
        }
        if (is_blank_or_comment(line)) continue;
        char *rest = line, *f;
        if (!header_seen) { /* the first line that is not a comment */
            header_seen = 1;
            for (long col = 0; (f = next_field(&rest)) != NULL; col++) {
                if (strcmp(f, "r") == 0 && col_r < 0) col_r = col;
                if (strcmp(f, "z") == 0 && col_z < 0) col_z = col;
            }
            if (col_r < 0 || col_z < 0) {
                rc = cli_error(cmd, "%s:%ld: the header has no column '%s' (columns r and z are required)",
                               path, lineno, col_r < 0 ? "r" : "z");
                break;
            }
            continue;
        }
        double v[2] = {NAN, NAN};
        int have[2] = {0, 0};
        for (long col = 0; (f = next_field(&rest)) != NULL; col++) {
            const int which = col == col_r ? 0 : (col == col_z ? 1 : -1);
            if (which < 0) continue;
            char *end;
            errno = 0;
            v[which] = strtod(f, &end);
            if (*f == '\0' || *end != '\0') {
                rc = cli_error(cmd, "%s:%ld: %s = '%s' is not a number", path, lineno,
                               which ? "z" : "r", f);
                goto done;
            }
            if (!isfinite(v[which])) {
                rc = cli_error(cmd, "%s:%ld: %s = '%s' is not finite", path, lineno,
                               which ? "z" : "r", f);
                goto done;
            }
            have[which] = 1;
        }
        if (!have[0] || !have[1]) {
            rc = cli_error(cmd, "%s:%ld: no value in column '%s'", path, lineno, have[0] ? "z" : "r");
            break;
        }
        if (points_push(p, v[0], v[1]) != 0) {
            rc = cli_error(cmd, "out of memory reading '%s'", path);
            break;
        }
    }
    if (rc == 0 && ferror(fp)) rc = cli_error(cmd, "error reading '%s'", path);
    if (rc == 0 && !header_seen) rc = cli_error(cmd, "%s: no header line (columns r and z are required)", path);
done:
    if (fp != stdin) fclose(fp);
    return rc;
}

int cmd_fit(const cli_command *cmd, int argc, char **argv)
{
    const char *shape = NULL, *output = NULL;
    int mode = 0, mode_given = 0, omega_max_given = 0;
    double omega_max_user = 0, max_residual = 0.02;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {"--shape", NULL, CLI_STRING, &shape, NULL, "FILE",
         "CSV of measured points with columns r and z, lengths in the units of --length (required; - reads stdin)"},
        {"--mode", NULL, CLI_INT, &mode, &mode_given, "K", "fit only mode K (default: the best mode)"},
        STEADY_CLI_MODEL_OPTIONS(m),
        {"--omega-max", NULL, CLI_DOUBLE, &omega_max_user, &omega_max_given, "W",
         "highest rate tried (default 50 sqrt(g/L))"},
        {"--max-residual", NULL, CLI_DOUBLE, &max_residual, NULL, "F",
         "largest rms residual accepted, as a fraction of L (default 0.02)"},
        {"--output", "-o", CLI_STRING, &output, NULL, "FILE", "write the CSV to FILE"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    if (shape == NULL) return cli_error(cmd, "--shape FILE is required");
    if (mode_given && (mode < 1 || mode > WHIRL_MODE_MAX))
        return cli_error(cmd, "--mode must be between 1 and %d, got %d", WHIRL_MODE_MAX, mode);
    if (m.links_given && m.links > FIT_MAX_LINKS)
        return cli_error(cmd, "--links must be at most %d, got %d", FIT_MAX_LINKS, m.links);
    if (omega_max_given && steady_cli_check_omega(cmd, "--omega-max", omega_max_user)) return 1;
    if (!(max_residual > 0)) return cli_error(cmd, "--max-residual must be > 0, got %g", max_residual);
    if (steady_cli_model_setup(cmd, &m)) return 1;

    const double rate = cli_units_rate(&m.units), len = m.units.length;
    whirl_fit_model model = whirl_fit_model_default();
    model.links = m.links_given ? (size_t)m.links : 0;
    model.tip_mass = steady_cli_tip_mass(&m);
    if (omega_max_given) model.omega_max = omega_max_user / rate;

    points p = {0, 0, NULL, NULL};
    rc = read_points(cmd, shape, &p);
    if (rc) goto done;
    rc = 1;
    if (p.n < 3) {
        cli_error(cmd, "%s has %zu points; a fit needs at least 3", shape, p.n);
        goto done;
    }
    for (size_t i = 0; i < p.n; i++) {
        p.r[i] /= len;
        p.z[i] /= len;
    }
    whirl_fit_result res;
    if (whirl_fit(&model, p.n, p.r, p.z, mode, &res) != GSL_SUCCESS) {
        cli_error(cmd, "%s", whirl_last_error());
        goto done;
    }
    if (!(res.rms_residual <= max_residual)) {
        char which[32] = "no mode";
        if (mode_given) snprintf(which, sizeof which, "mode %d", mode);
        cli_error(cmd, "%s explains the shape: the best fit (mode %d, omega=%.6g) leaves an rms "
                  "residual of %.3g L, above --max-residual %g", which, res.mode, res.omega * rate,
                  res.rms_residual, max_residual);
        goto done;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, output)) goto done;
    fprintf(out.fp, "# model=%s points=%zu side=%s evaluations=%d solver_failures=%d\n",
            m.links_given ? "n-link" : "continuum", p.n, res.mirrored ? "r<0" : "r>0",
            res.evaluations, res.failures);
    fprintf(out.fp, "omega,omega_err,mode,rms_residual\n%.17g,%.17g,%d,%.17g\n", res.omega * rate,
            res.omega_err * rate, res.mode, res.rms_residual * len);
    rc = cli_out_commit(cmd, &out);
done:
    free(p.r);
    free(p.z);
    steady_cli_model_free(&m);
    return rc;
}
