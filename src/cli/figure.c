/* Figures and animations of whirl's files: the kind of each file from its header, the checks
 * (one kind, one units line), and gnuplot run on the built-in copy of plots/ in a folder beside
 * the picture, from which the finished picture is renamed into place (no partial file). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/figure.h"

#define LINE_MAX_FIG 4096

static const struct {
    const char *prefix; /* the header line starts with it ("=": equals it) */
    cli_figure_kind kind;
    const char *name;
} kinds[] = {{"=s,r,z,tension", CLI_FIGURE_SHAPE, "a steady shape"},
             {"=s,x,y,z,tension", CLI_FIGURE_DRIVEN_SHAPE, "a hand-swung shape"},
             {"omega,mode,links,eig_growth", CLI_FIGURE_STABILITY, "a stability map"},
             {"omega,mode,tip_r", CLI_FIGURE_BRANCHES, "branches"},
             {"omega,tip_x,tip_y", CLI_FIGURE_DRIVEN_BRANCH, "a hand-swung branch"},
             {"index,omega,eps,state", CLI_FIGURE_REGIME_MAP, "a regime map"},
             {"leg,omega,state", CLI_FIGURE_REGIME_SWEEP, "a hysteresis sweep"},
             {"mode,from,to,open_from,", CLI_FIGURE_ATLAS, "a stability atlas"},
             {"mode,links,from,to,open_from,open_to,freq_from,freq_to,max_growth,",
              CLI_FIGURE_WINDOWS, "windows of instability"},
             {"=mode,links,from,to,open_from,open_to,freq_from,freq_to,growth,at,verdict",
              CLI_FIGURE_INTERVALS, "intervals with dissipation"},
             {"curve,edge,omega,amplitude,", CLI_FIGURE_CHART, "a stability chart"},
             {"curve,event,omega,ellipticity,", CLI_FIGURE_CHART_ELLIPSE,
              "an ellipticity chart"},
             {"t,", CLI_FIGURE_RUN, "a run"}};

static const char *kind_name(cli_figure_kind k)
{
    if (k == CLI_FIGURE_TRACE) return "a trace";
    for (size_t i = 0; i < sizeof kinds / sizeof *kinds; i++)
        if (kinds[i].kind == k) return kinds[i].name;
    return "unknown";
}

/* The kind of the file at path and its "# units:" line (units: size bytes, "" if none).
 * Returns 0, or 1 after printing an error. */
static int read_kind(const cli_command *cmd, const char *path, cli_figure_kind *kind,
                     char *units, size_t size)
{
    FILE *fp = fopen(path, "r");
    if (fp == NULL) return cli_error(cmd, "cannot read '%s': %s", path, strerror(errno));
    char line[LINE_MAX_FIG];
    int trace = 0;
    *kind = CLI_FIGURE_UNKNOWN;
    units[0] = '\0';
    while (fgets(line, sizeof line, fp)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (strncmp(line, "# trace:", 8) == 0) trace = 1;
        if (strncmp(line, "# units:", 8) == 0) snprintf(units, size, "%s", line + 9);
        if (line[0] == '#' || line[0] == '\0') continue;
        if (trace) *kind = CLI_FIGURE_TRACE;
        for (size_t i = 0; i < sizeof kinds / sizeof *kinds && !trace; i++) {
            const char *p = kinds[i].prefix;
            if (p[0] == '=' ? strcmp(line, p + 1) == 0 : strncmp(line, p, strlen(p)) == 0) {
                *kind = kinds[i].kind;
                break;
            }
        }
        break;
    }
    fclose(fp);
    if (*kind == CLI_FIGURE_UNKNOWN)
        return cli_error(cmd, "%s: not a file of whirl's (its header is none of a shape, "
                         "branches, a stability map, windows, a run, a trace, ...)", path);
    /* the atlas is of the dimensionless continuum only: its first line says so, no units line */
    if (units[0] == '\0' && *kind == CLI_FIGURE_ATLAS) snprintf(units, size, "dimensionless");
    if (units[0] == '\0') return cli_error(cmd, "%s: no '# units:' line", path);
    return 0;
}

/* The extension of path, lower case, in ext (8 bytes); "" if none. */
static void extension(const char *path, char ext[8])
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    ext[0] = '\0';
    if (dot == NULL || (slash && dot < slash) || strlen(dot + 1) >= 8) return;
    size_t i = 0;
    for (const char *p = dot + 1; *p; p++) ext[i++] = (char)(*p >= 'A' && *p <= 'Z' ? *p + 32 : *p);
    ext[i] = '\0';
}

int cli_figure_check_out(const cli_command *cmd, const char *option, const char *path,
                         int animation)
{
    char ext[8];
    extension(path, ext);
    if (path[0] == '\0') return cli_error(cmd, "%s: empty file name", option);
    if (strchr(path, '\'') || strchr(path, '\n'))
        return cli_error(cmd, "%s %s: a picture's name cannot hold a quote or a newline", option,
                         path);
    if (animation) {
        if (strcmp(ext, "mp4") && strcmp(ext, "webm") && strcmp(ext, "gif"))
            return cli_error(cmd, "%s %s: an animation is written as .mp4, .webm or .gif", option,
                             path);
    } else if (strcmp(ext, "png") && strcmp(ext, "svg") && strcmp(ext, "pdf")) {
        return cli_error(cmd, "%s %s: a figure is written as .png, .svg or .pdf", option, path);
    }
    return 0;
}

char *cli_figure_work_dir(const cli_command *cmd, const char *path)
{
    const char *slash = strrchr(path, '/');
    const size_t dlen = slash ? (size_t)(slash - path) + 1 : 0;
    char *dir = malloc(dlen + 32);
    if (dir == NULL) {
        cli_error(cmd, "out of memory");
        return NULL;
    }
    memcpy(dir, path, dlen);
    strcpy(dir + dlen, ".whirl-figure.XXXXXX");
    if (mkdtemp(dir) == NULL) {
        cli_error(cmd, "cannot write beside '%s': %s", path, strerror(errno));
        free(dir);
        return NULL;
    }
    return dir;
}

void cli_figure_remove_dir(char *dir)
{
    if (dir == NULL) return;
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char path[LINE_MAX_FIG];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            unlink(path);
        }
        closedir(d);
    }
    rmdir(dir);
    free(dir);
}

/* dir/name, written from the built-in table (the scripts) or copied (a data file). */
static int write_scripts(const cli_command *cmd, const char *dir)
{
    char path[LINE_MAX_FIG];
    FILE *fp = NULL;
    const char *open_name = NULL;
    for (const cli_plot_line *l = cli_plot_scripts; l->file; l++) {
        if (open_name == NULL || strcmp(open_name, l->file) != 0) {
            if (fp && fclose(fp) != 0) return cli_error(cmd, "cannot write in '%s'", dir);
            snprintf(path, sizeof path, "%s/%s", dir, l->file);
            if ((fp = fopen(path, "w")) == NULL)
                return cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
            open_name = l->file;
        }
        fputs(l->line, fp);
    }
    if (fp && (ferror(fp) | (fclose(fp) != 0))) return cli_error(cmd, "cannot write in '%s'", dir);
    return 0;
}

static int copy_file(const cli_command *cmd, const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    if (in == NULL || out == NULL) {
        if (in) fclose(in);
        return cli_error(cmd, "cannot copy '%s': %s", from, strerror(errno));
    }
    char buf[65536];
    size_t k;
    while ((k = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, k, out);
    int bad = ferror(in) | ferror(out);
    fclose(in);
    bad |= fclose(out) != 0;
    return bad ? cli_error(cmd, "cannot copy '%s' to '%s'", from, to) : 0;
}

/* Runs gnuplot -e vars dir/script, its messages into dir/gnuplot.err. Returns 0, or 1 after
 * printing gnuplot's first message. */
static int run_gnuplot(const cli_command *cmd, const char *dir, const char *script,
                       const char *vars)
{
    char script_path[LINE_MAX_FIG], err_path[LINE_MAX_FIG];
    snprintf(script_path, sizeof script_path, "%s/%s", dir, script);
    snprintf(err_path, sizeof err_path, "%s/gnuplot.err", dir);
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) return cli_error(cmd, "cannot start gnuplot: %s", strerror(errno));
    if (pid == 0) {
        int fd = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
        int null = open("/dev/null", O_WRONLY);
        if (fd >= 0) dup2(fd, STDERR_FILENO);
        if (null >= 0) dup2(null, STDOUT_FILENO);
        execlp("gnuplot", "gnuplot", "-e", vars, script_path, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return cli_error(cmd, "cannot run gnuplot (is it installed? scripts/deps.sh)");
    /* gnuplot's last non-empty message names what went wrong */
    char line[512] = "", last[512] = "";
    FILE *fp = fopen(err_path, "r");
    while (fp && fgets(line, sizeof line, fp))
        if (strspn(line, " \t\r\n^") < strlen(line)) snprintf(last, sizeof last, "%s", line);
    if (fp) fclose(fp);
    last[strcspn(last, "\r\n")] = '\0';
    if (WIFSIGNALED(status)) return cli_error(cmd, "gnuplot stopped by signal %d", WTERMSIG(status));
    return cli_error(cmd, "gnuplot failed: %s", last[0] ? last : "(no message)");
}

int cli_figure_size(const cli_command *cmd, const cli_figure_style *style, int *w, int *h)
{
    /* 16 px: a picture smaller draws nothing legible; 16384 px: cairo's largest image side */
    enum { SIDE_MIN = 16, SIDE_MAX = 16384 };
    *w = *h = 0;
    if (style == NULL) return 0;
    if (style->size == NULL) {
        if (style->present) *w = 1920, *h = 1080; /* a projector's full HD */
        return 0;
    }
    const char *p = style->size;
    char *end;
    long a = strtol(p, &end, 10), b = 0;
    int ok = end != p && p[0] >= '0' && p[0] <= '9';
    if (ok && (*end == 'x' || *end == 'X')) {
        p = end + 1;
        b = strtol(p, &end, 10);
        ok = end != p && p[0] >= '0' && p[0] <= '9';
    }
    if (!ok || *end != '\0')
        return cli_error(cmd, "--size needs WxH or W in pixels (1920x1080, 1200), got '%s'",
                         style->size);
    if (a < SIDE_MIN || a > SIDE_MAX || (b != 0 && (b < SIDE_MIN || b > SIDE_MAX)))
        return cli_error(cmd, "--size %s: each side must be %d to %d pixels", style->size,
                         SIDE_MIN, SIDE_MAX);
    *w = (int)a, *h = (int)b;
    return 0;
}

/* name (a file's, as the user gave it) with its folders left out, as a gnuplot string between
 * single quotes: a quote doubled, a control character as '?'; at most size - 1 bytes. */
static void gnuplot_name(const char *path, char *buf, size_t size)
{
    const char *slash = strrchr(path, '/');
    const char *p = slash && slash[1] ? slash + 1 : path;
    size_t k = 0;
    for (; *p && k + 3 < size; p++) {
        if (*p == '\'') buf[k++] = '\'';
        buf[k++] = (unsigned char)*p < 32 || *p == 127 ? '?' : *p;
    }
    buf[k] = '\0';
}

int cli_figure_draw(const cli_command *cmd, const char *const *files, size_t n, const char *out,
                    const cli_figure_style *style)
{
    int box_w, box_h;
    if (cli_figure_size(cmd, style, &box_w, &box_h)) return 1;
    char units0[LINE_MAX_FIG], units[LINE_MAX_FIG], ext[8];
    cli_figure_kind kind0 = CLI_FIGURE_UNKNOWN, kind = CLI_FIGURE_UNKNOWN;
    if (n == 0) return cli_error(cmd, "no file to draw");
    for (size_t i = 0; i < n; i++) {
        if (read_kind(cmd, files[i], &kind, i ? units : units0, sizeof units)) return 1;
        if (i == 0) kind0 = kind;
        else if (kind != kind0)
            return cli_error(cmd, "%s is %s, %s is %s: one figure shows files of one kind",
                             files[0], kind_name(kind0), files[i], kind_name(kind));
        else if (strcmp(units, units0) != 0)
            return cli_error(cmd, "%s and %s are in different units ('%s' and '%s'): one figure "
                             "shows one chain in one system of units", files[0], files[i],
                             units0, units);
    }
    if (n > 1 && kind0 != CLI_FIGURE_SHAPE && kind0 != CLI_FIGURE_STABILITY)
        return cli_error(cmd, "%s: a figure of %s takes one file (several: shapes, stability "
                         "maps)", files[1], kind_name(kind0));
    if (cli_figure_check_out(cmd, "-o", out, kind0 == CLI_FIGURE_TRACE)) return 1;
    if (style && style->slow > 0 && kind0 != CLI_FIGURE_TRACE)
        return cli_error(cmd, "--slow applies to a movie (a trace drawn as .mp4, .webm, .gif)");
    extension(out, ext);

    char *dir = cli_figure_work_dir(cmd, out);
    if (dir == NULL) return 1;
    int rc = write_scripts(cmd, dir);
    /* the data copied in as f1.csv, f2.csv, ...: the scripts get names without spaces or quotes */
    char name[512], style_vars[640]; /* the name and 5 numbers */
    gnuplot_name(files[0], name, sizeof name);
    snprintf(style_vars, sizeof style_vars, "; box_w=%d; box_h=%d; present=%d; name='%s'", box_w,
             box_h, style && style->present, name);
    if (style && style->slow > 0) {
        const size_t used = strlen(style_vars);
        snprintf(style_vars + used, sizeof style_vars - used, "; slow=%.17g", style->slow);
    }
    size_t vlen = 64 + n * (strlen(dir) + 16) + 2 * strlen(dir) + sizeof style_vars;
    char *vars = malloc(vlen), *list = malloc(vlen), path[LINE_MAX_FIG];
    if (rc == 0 && (vars == NULL || list == NULL)) rc = cli_error(cmd, "out of memory");
    if (rc == 0) list[0] = '\0';
    for (size_t i = 0; i < n && rc == 0; i++) {
        snprintf(path, sizeof path, "%s/f%zu.csv", dir, i + 1);
        rc = copy_file(cmd, files[i], path);
        strcat(list, i ? " " : "");
        strcat(list, path);
    }
    char picture[LINE_MAX_FIG];
    snprintf(picture, sizeof picture, "%s/picture.%s", dir, ext);
    if (rc == 0) {
        if (kind0 == CLI_FIGURE_TRACE)
            snprintf(vars, vlen, "trace='%s'; out='%s'%s", list, picture, style_vars);
        else
            snprintf(vars, vlen, "files='%s'; out='%s'; fmt='%s'%s", list, picture, ext,
                     style_vars);
        rc = run_gnuplot(cmd, dir, kind0 == CLI_FIGURE_TRACE ? "animate.gp" : "plot.gp", vars);
    }
    struct stat st;
    if (rc == 0 && (stat(picture, &st) != 0 || st.st_size == 0))
        rc = cli_error(cmd, "gnuplot wrote no picture for '%s'", out);
    if (rc == 0 && rename(picture, out) != 0)
        rc = cli_error(cmd, "cannot write '%s': %s", out, strerror(errno));
    free(vars);
    free(list);
    cli_figure_remove_dir(dir);
    return rc;
}
