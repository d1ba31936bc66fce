/* whirl view: one self-contained HTML file (no network; plain JavaScript on a canvas) that shows
 * the chain in 3D, rotatable with the mouse, from
 *   - a trace (`whirl simulate` [output] trace, `whirl regime --trace`): blocks of lines
 *     "x y z t", the pivot first, in the inertial frame, blocks separated by blank lines; its
 *     "# trace: ..." line gives omega and eps (for the co-rotating view and the pivot's circle);
 *   - or one or more shapes (`whirl shape`, `whirl minimize`, `whirl driven --omega`): CSV with
 *     columns r and z (a planar shape, in the co-rotating frame) or x, y and z; the comment
 *     line "# omega=..." gives the rate at which it turns in the inertial view.
 * The page plays the motion (play/pause, speed; a trace also with a time slider and frame
 * stepping), in the inertial or the co-rotating frame, labels each shape "mode K, RATE" (the rate
 * as the file's writer gave it), lists the files' comment lines (the parameters) and saves the
 * current view as a PNG. Planar shapes are first seen from the side (camera 0,0: true lengths). The page's template is src/cli/view.html; the
 * Makefile turns it into the string table cli_view_html.
 * A large file (up to VIEW_BYTES_MAX, some 10^7 points) takes seconds to read and to write into
 * the page: both poll the stop request, and on a terminal, once the run has taken a second, a
 * progress line says how far they are:
 *   whirl view: reading run.dat: 120/240 MiB (50%), 3s elapsed
 *   whirl view: writing the page: 1200000/3000000 points (40%), 5s elapsed
 * erased at the end. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "core/input.h"

#define VIEW_LINE_MAX 4096                  /* longest line read, with its newline */
#define VIEW_BYTES_MAX ((size_t)256 << 20)  /* most bytes read from one file */
/* The largest coordinate drawn: the page squares coordinates (distances, the projection), and
 * 1e100 squared stays finite in the browser's doubles. */
#define VIEW_COORD_MAX 1e100
#define VIEW_INFO_MAX 24   /* comment lines shown per file */
#define VIEW_FILES_MAX 16
#define VIEW_POLL_LINES 4096    /* lines read between looks at the clock */
#define VIEW_POLL_VALUES 16384  /* numbers written between looks at the stop request */

extern const char *const cli_view_html[]; /* the template, one line per entry, NULL-terminated */

/* A growing array of doubles. */
typedef struct vec {
    double *v;
    size_t n, cap;
} vec;

static int vec_push(vec *a, double x)
{
    if (a->n == a->cap) {
        size_t cap = a->cap ? 2 * a->cap : 1024;
        double *v = realloc(a->v, cap * sizeof *v);
        if (v == NULL) return -1;
        a->v = v;
        a->cap = cap;
    }
    a->v[a->n++] = x;
    return 0;
}

/* One file read: its comment lines, omega/eps if stated, and its points (x, y, z triples) with
 * their frame boundaries (a trace) or as one frame (a shape). */
typedef struct source {
    const char *path;
    int trace;            /* 1: a trace, 0: a shape */
    double omega, eps;    /* NAN when not stated */
    int mode;             /* mode=K of a shape's summary line; 0 if none */
    int links;            /* links=N of a trace's line; 0 if none */
    char rate[96];        /* a shape's "# rate: " line up to " (": the rate as its writer gave it */
    int physical;         /* the units line says SI */
    int planar;           /* every point has y = 0 */
    char info[VIEW_INFO_MAX][256];
    int n_info;
    vec xyz;              /* points */
    vec start, time;      /* trace: first point of each frame (as a double) and its time */
} source;

/* The progress line of the reading and the writing. */
typedef struct view_progress {
    cli_progress_state line;
    double after;          /* the line shows once the run has taken this long [s] */
    size_t written, total; /* points written into the page, of all */
} view_progress;

static int progress_due(const view_progress *p)
{
    return p->line.tty && (p->line.drawn || cli_wall_seconds() - p->line.start >= p->after);
}

/* cli_error with the progress line erased first. */
static int read_error(view_progress *vp, const cli_command *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int read_error(view_progress *vp, const cli_command *cmd, const char *fmt, ...)
{
    char msg[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    cli_progress_clear(&vp->line);
    return cli_error(cmd, "%s", msg);
}

/* The value of key=... in a comment line, or NAN. */
static double meta_value(const char *line, const char *key)
{
    size_t len = strlen(key);
    for (const char *p = strstr(line, key); p; p = strstr(p + 1, key))
        if ((p == line || p[-1] == ' ' || p[-1] == '#') && p[len] == '=') {
            char *end;
            double v = strtod(p + len + 1, &end);
            if (end != p + len + 1) return v;
        }
    return NAN;
}

/* Column index of name in the CSV header (comma separated), or -1. */
static int column(const char *header, const char *name)
{
    int k = 0;
    size_t len = strlen(name);
    for (const char *p = header;; k++) {
        size_t n = strcspn(p, ",\r\n");
        if (n == len && strncmp(p, name, len) == 0) return k;
        if (p[n] != ',') return -1;
        p += n + 1;
    }
}

/* 1 if x, y, z (and t) are finite and within the page's range. */
static int drawable(double x, double y, double z, double t)
{
    return fabs(x) <= VIEW_COORD_MAX && fabs(y) <= VIEW_COORD_MAX && fabs(z) <= VIEW_COORD_MAX &&
           isfinite(t);
}

/* A comment line: the rate, eps, mode and links it gives (the first of each), the rate as the
 * writer gave it ("# rate: "), SI units, and the line kept for the page's list. */
static void read_comment(source *s, const char *line)
{
    double w = meta_value(line, "omega"), e = meta_value(line, "eps");
    double k = meta_value(line, "mode"), nl = meta_value(line, "links");
    if (isnan(s->omega) && isfinite(w)) s->omega = w;
    if (isnan(s->eps) && isfinite(e)) s->eps = e;
    if (s->mode == 0 && k >= 1 && k < 1e9) s->mode = (int)k;
    if (s->links == 0 && nl >= 1 && nl < 1e9) s->links = (int)nl;
    if (strncmp(line, "# rate: ", 8) == 0 && s->rate[0] == '\0') {
        snprintf(s->rate, sizeof s->rate, "%.*s", (int)sizeof s->rate - 1, line + 8);
        s->rate[strcspn(s->rate, "\r\n")] = '\0';
        char *paren = strstr(s->rate, " ("); /* "4 Hz (omega=...)": the rate as given */
        if (paren) *paren = '\0';
        for (size_t n = strlen(s->rate); n > 0 && s->rate[n - 1] == ' '; n--)
            s->rate[n - 1] = '\0';
    }
    if (strncmp(line, "# units: length=m", 17) == 0) s->physical = 1;
    if (strncmp(line, "# t = ", 6) != 0 && s->n_info < VIEW_INFO_MAX) {
        snprintf(s->info[s->n_info], sizeof s->info[0], "%s", line + 1 + (line[1] == ' '));
        s->info[s->n_info][strcspn(s->info[s->n_info], "\r\n")] = '\0';
        s->n_info++;
    }
}

/* The columns of a shape's CSV (-1: absent), from its header. */
typedef struct shape_columns {
    int header, x, y, z, r, n;
} shape_columns;

/* A line of a shape's CSV: the header (cols), then a point per row. 0, or 1 after an error. */
static int read_shape_line(const cli_command *cmd, view_progress *vp, source *s, char *line,
                           long lineno, shape_columns *cols)
{
    if (!cols->header) { /* the CSV header */
        cols->header = 1;
        cols->x = column(line, "x"), cols->y = column(line, "y"), cols->z = column(line, "z");
        cols->r = column(line, "r");
        for (const char *c = line; *c; c++) cols->n += *c == ',';
        cols->n++;
        if (cols->z < 0 || (cols->r < 0 && cols->x < 0))
            return read_error(vp, cmd, "%s:%ld: a shape needs columns r and z, or x, y and z",
                              s->path, lineno);
        return 0;
    }
    const int cx = cols->x, cy = cols->y, cz = cols->z, cr = cols->r;
    double v[64];
    int n = 0;
    char *q = line, *end;
    while (n < 64 && n < cols->n) {
        v[n++] = strtod(q, &end);
        if (end == q) break;
        q = end;
        if (*q != ',') break;
        q++;
    }
    const int need = (cx > cr ? cx : cr) > cz ? (cx > cr ? cx : cr) : cz;
    if (n <= need || (cy >= 0 && n <= cy))
        return read_error(vp, cmd, "%s:%ld: too few values", s->path, lineno);
    double x = cx >= 0 ? v[cx] : v[cr], y = cx >= 0 && cy >= 0 ? v[cy] : 0, z = v[cz];
    if (!drawable(x, y, z, 0))
        return read_error(vp, cmd, "%s:%ld: a coordinate is not finite or beyond %g", s->path,
                          lineno, VIEW_COORD_MAX);
    if (vec_push(&s->xyz, x) || vec_push(&s->xyz, y) || vec_push(&s->xyz, z))
        return read_error(vp, cmd, "%s:%ld: out of memory for the points (%zu read)", s->path,
                          lineno, s->xyz.n / 3);
    return 0;
}

/* A line "x y z t" of a trace; the first of a block (*block_open 0) starts a frame. 0, or 1
 * after an error. */
static int read_trace_line(const cli_command *cmd, view_progress *vp, source *s,
                           const char *line, long lineno, int *block_open)
{
    double x, y, z, t;
    if (sscanf(line, "%lf %lf %lf %lf", &x, &y, &z, &t) != 4 || !drawable(x, y, z, t))
        return read_error(vp, cmd, "%s:%ld: a trace line needs four finite numbers x y z t (x, "
                          "y, z at most %g)", s->path, lineno, VIEW_COORD_MAX);
    int rc = 0;
    if (!*block_open) {
        *block_open = 1;
        if (vec_push(&s->start, (double)(s->xyz.n / 3)) || vec_push(&s->time, t))
            rc = read_error(vp, cmd, "%s:%ld: out of memory for the frames (%zu read)", s->path,
                            lineno, s->start.n);
    }
    if (vec_push(&s->xyz, x) || vec_push(&s->xyz, y) || vec_push(&s->xyz, z))
        rc = read_error(vp, cmd, "%s:%ld: out of memory for the points (%zu read)", s->path,
                        lineno, s->xyz.n / 3);
    return rc;
}

/* After the reading: at least two points, planar or not, and a trace's frames of equal size.
 * 0, or 1 after an error. */
static int check_source(const cli_command *cmd, view_progress *vp, source *s)
{
    int rc = 0;
    if (s->xyz.n < 6)
        rc = read_error(vp, cmd, "%s: no chain in it (at least two points)", s->path);
    s->planar = 1;
    for (size_t i = 1; i < s->xyz.n && s->planar; i += 3) s->planar = s->xyz.v[i] == 0;
    if (rc == 0 && s->trace) { /* every frame must have the same number of points */
        size_t per = s->start.n > 1 ? (size_t)s->start.v[1] : s->xyz.n / 3;
        for (size_t k = 0; k < s->start.n; k++) {
            size_t end = k + 1 < s->start.n ? (size_t)s->start.v[k + 1] : s->xyz.n / 3;
            if (end - (size_t)s->start.v[k] != per)
                return read_error(vp, cmd, "%s: frame %zu has %zu points, the first %zu", s->path,
                                  k + 1, end - (size_t)s->start.v[k], per);
        }
    }
    return rc;
}

static int read_source(const cli_command *cmd, source *s, view_progress *vp)
{
    FILE *fp;
    if (whirl_input_open(s->path, &fp) != GSL_SUCCESS)
        return read_error(vp, cmd, "%s", whirl_last_error());
    struct stat st;
    const double mib = fstat(fileno(fp), &st) == 0 ? (double)st.st_size / 1048576 : 0;
    whirl_line_reader in = whirl_line_reader_init(fp, s->path, VIEW_LINE_MAX, VIEW_BYTES_MAX);
    int rc = 0, block_open = 0;
    shape_columns cols = {0, -1, -1, -1, -1, 0};
    s->omega = s->eps = NAN;
    s->trace = -1;
    while (rc == 0 && whirl_line_read(&in) > 0) {
        char *line = in.line;
        const long lineno = in.lineno;
        if (lineno % VIEW_POLL_LINES == 0 && progress_due(vp))
            cli_progress_text(&vp->line, "reading %s: %.0f/%.0f MiB (%.0f%%)", s->path,
                              (double)in.total / 1048576, mib,
                              mib > 0 ? 100 * (double)in.total / 1048576 / mib : 100);
        if (strlen(line) != in.len) {
            rc = read_error(vp, cmd, "%s:%ld: NUL byte at column %zu (a binary file?)", s->path,
                            lineno, strlen(line) + 1);
            continue;
        }
        if (line[0] == '#') {
            read_comment(s, line);
            continue;
        }
        const char *p = line;
        while (isspace((unsigned char)*p)) p++;
        if (*p == '\0') { /* a blank line ends a trace's block */
            block_open = 0;
            continue;
        }
        if (s->trace < 0) s->trace = strchr(line, ',') == NULL;
        if (!s->trace) rc = read_shape_line(cmd, vp, s, line, lineno, &cols);
        else rc = read_trace_line(cmd, vp, s, line, lineno, &block_open);
    }
    if (rc == 0 && in.status != GSL_SUCCESS) rc = read_error(vp, cmd, "%s", whirl_last_error());
    whirl_line_reader_free(&in);
    fclose(fp);
    return rc ? rc : check_source(cmd, vp, s);
}

/* A JSON string. */
static void put_string(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') fprintf(fp, "\\%c", c);
        else if (c < 0x20) fprintf(fp, "\\u%04x", c);
        else if (c == '<') fputs("\\u003c", fp); /* no "</script>" inside the page */
        else fputc(c, fp);
    }
    fputc('"', fp);
}

/* A point list (n numbers, x y z of each point) as a JSON array, 7 significant digits (far
 * below a pixel); stops early on a stop request (the page is then not written). */
static void put_points(FILE *fp, const double *v, size_t n, view_progress *vp)
{
    fputc('[', fp);
    for (size_t i = 0; i < n; i++) {
        if (i % VIEW_POLL_VALUES == VIEW_POLL_VALUES - 1) {
            if (cli_interrupted) break;
            if (progress_due(vp))
                cli_progress_text(&vp->line, "writing the page: %zu/%zu points (%.0f%%)",
                                  vp->written + i / 3, vp->total,
                                  100 * (double)(vp->written + i / 3) / (double)vp->total);
        }
        fprintf(fp, "%s%.7g", i ? "," : "", v[i]);
    }
    vp->written += n / 3;
    fputc(']', fp);
}

/* What a file shows, short: "mode 2, 4 Hz" (a shape, its rate as given), "mode 2, omega = 3
 * sqrt(g/L)", or "30 links, omega = 25.13 rad/s (4 Hz), eps = 0.01 m" (a trace). */
static void label_of(const source *s, char *buf, size_t size)
{
    char mode[32] = "", rate[128] = "";
    const double w = isfinite(s->omega) ? s->omega : 0;
    if (s->rate[0]) snprintf(rate, sizeof rate, "%s", s->rate);
    else if (s->physical) snprintf(rate, sizeof rate, "omega = %.4g rad/s (%.4g Hz)", w,
                                   w / 6.283185307179586);
    else snprintf(rate, sizeof rate, "omega = %.4g sqrt(g/L)", w);
    if (s->trace) {
        int n = snprintf(buf, size, "%d links, %s", s->links, rate);
        if (isfinite(s->eps) && s->eps > 0 && n > 0 && (size_t)n < size)
            snprintf(buf + n, size - (size_t)n, ", eps = %.3g %s", s->eps, s->physical ? "m" : "L");
        return;
    }
    if (s->mode > 0) snprintf(mode, sizeof mode, "mode %d, ", s->mode);
    snprintf(buf, size, "%s%s", mode, rate);
}

/* The units and the extent of the sources: radius from the axis, heights, and the chain's
 * length (first frame). */
static void write_extent(FILE *fp, const source *src, int nsrc, double eps)
{
    double r = eps > 0 ? eps : 0, zmin = 0, zmax = 0, len = 0;
    int physical = 0;
    for (int k = 0; k < nsrc; k++) {
        const vec *a = &src[k].xyz;
        for (size_t i = 0; i < a->n; i += 3) {
            r = fmax(r, hypot(a->v[i], a->v[i + 1]));
            zmin = fmin(zmin, a->v[i + 2]);
            zmax = fmax(zmax, a->v[i + 2]);
        }
        size_t per = src[k].trace && src[k].start.n > 1 ? (size_t)src[k].start.v[1] : a->n / 3;
        double l = 0;
        for (size_t i = 1; i < per; i++)
            l += hypot(hypot(a->v[3 * i] - a->v[3 * i - 3], a->v[3 * i + 1] - a->v[3 * i - 2]),
                       a->v[3 * i + 2] - a->v[3 * i - 1]);
        len = fmax(len, l);
        physical |= src[k].physical;
    }
    if (!(r > 0)) r = 0.05 * (len > 0 ? len : 1);
    fprintf(fp, "\"units\": {\"length\": \"%s\", \"time\": \"%s\"},\n", physical ? "m" : "L",
            physical ? "s" : "sqrt(L/g)");
    fprintf(fp, "\"extent\": {\"r\": %.7g, \"zmin\": %.7g, \"zmax\": %.7g, \"len\": %.7g},\n", r,
            zmin, zmax, len > 0 ? len : 1);
}

/* The summary, short: each shape's label (mode and rate as given), or the trace's links, rate
 * (and its frequency in Hz in SI units) and eps; then each file's comment lines. */
static void write_info(FILE *fp, const source *src, int nsrc)
{
    char summary[1024] = "";
    for (int k = 0; k < nsrc; k++) {
        char one[256];
        label_of(&src[k], one, sizeof one);
        size_t used = strlen(summary);
        snprintf(summary + used, sizeof summary - used, "%s%s", k ? "; " : "", one);
    }
    fprintf(fp, "\"summary\": ");
    put_string(fp, summary);
    fprintf(fp, ",\n\"info\": [");
    for (int k = 0; k < nsrc; k++) {
        char head[300];
        snprintf(head, sizeof head, "%s:", src[k].path);
        if (k) fputs(", ", fp);
        put_string(fp, head);
        for (int i = 0; i < src[k].n_info; i++) {
            fputs(", ", fp);
            put_string(fp, src[k].info[i]);
        }
    }
    fprintf(fp, "],\n");
}

/* A trace's frames, each with its time. */
static void write_frames(FILE *fp, const source *s, view_progress *vp)
{
    fprintf(fp, "\"frames\": [\n");
    for (size_t f = 0; f < s->start.n && !cli_interrupted; f++) {
        size_t a = (size_t)s->start.v[f], b = f + 1 < s->start.n ? (size_t)s->start.v[f + 1]
                                                               : s->xyz.n / 3;
        fprintf(fp, "%s{\"t\": %.17g, \"p\": ", f ? ",\n" : "", s->time.v[f]);
        put_points(fp, s->xyz.v + 3 * a, 3 * (b - a), vp);
        fputc('}', fp);
    }
    fprintf(fp, "]};\n");
}

/* The shapes, each with its label and rate. */
static void write_shapes(FILE *fp, const source *src, int nsrc, view_progress *vp)
{
    fprintf(fp, "\"shapes\": [\n");
    for (int k = 0; k < nsrc; k++) {
        char label[256];
        label_of(&src[k], label, sizeof label);
        fprintf(fp, "%s{\"label\": ", k ? ",\n" : "");
        put_string(fp, label);
        fprintf(fp, ", \"omega\": %.17g, \"p\": ", isfinite(src[k].omega) ? src[k].omega : 0);
        put_points(fp, src[k].xyz.v, src[k].xyz.n, vp);
        fputc('}', fp);
    }
    fprintf(fp, "]};\n");
}

static void write_data(FILE *fp, source *src, int nsrc, const double camera[2], double omega,
                       double eps, view_progress *vp)
{
    vp->written = vp->total = 0;
    for (int k = 0; k < nsrc; k++) vp->total += src[k].xyz.n / 3;
    fprintf(fp, "var WHIRL = {\"kind\": \"%s\", \"camera\": [%.7g, %.7g], ",
            src[0].trace ? "trace" : "shapes", camera[0], camera[1]);
    fprintf(fp, "\"omega\": %.17g, \"eps\": %.17g, \"time_unit_seconds\": 1,\n", omega, eps);
    write_extent(fp, src, nsrc, eps);
    write_info(fp, src, nsrc);
    if (src[0].trace) write_frames(fp, &src[0], vp);
    else write_shapes(fp, src, nsrc, vp);
}

int cmd_view(const cli_command *cmd, int argc, char **argv)
{
    const char *output = NULL, *camera_text = "30,15";
    int camera_given = 0;
    double omega = 0, eps = 0;
    int omega_given = 0, eps_given = 0;
    const cli_option opts[] = {
        {.name = "--camera", .type = CLI_STRING, .value = &camera_text, .given = &camera_given,
         .meta = "AZ,EL",
         .help = "first view: azimuth and elevation in degrees (default 0,0, the true side view, "
                 "for planar shapes; else 30,15; 0,0 looks along +y)"},
        {.name = "--omega", .type = CLI_DOUBLE, .value = &omega, .given = &omega_given, .meta = "W",
         .help = "rate of the co-rotating view, in the file's rate unit (default: from the file)",
         .range = "[0, inf)"},
        {.name = "--eps", .type = CLI_DOUBLE, .value = &eps, .given = &eps_given, .meta = "E",
         .help = "radius of the pivot's circle, in the file's length unit (default: from the file)",
         .range = "[0, inf)"},
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &output, .meta = "FILE",
         .help = "write the HTML page to FILE (default: standard output)"},
    };
    const char *files[VIEW_FILES_MAX + 1];
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], files,
                       VIEW_FILES_MAX + 1);
    if (rc) return rc;
    int nsrc = 0;
    while (nsrc <= VIEW_FILES_MAX && files[nsrc]) nsrc++;
    if (nsrc == 0) return cli_error(cmd, "give a trace or shape files (see --help)");
    if (nsrc > VIEW_FILES_MAX) return cli_error(cmd, "at most %d files", VIEW_FILES_MAX);
    double camera[2];
    char tail;
    if (sscanf(camera_text, "%lf,%lf%c", &camera[0], &camera[1], &tail) != 2 ||
        !isfinite(camera[0]) || !(camera[1] >= -90 && camera[1] <= 90))
        return cli_error(cmd, "--camera needs AZ,EL in degrees (EL in [-90, 90]), got '%s'",
                         camera_text);
    source *src = calloc((size_t)nsrc, sizeof *src);
    if (src == NULL) return cli_error(cmd, "out of memory");
    view_progress vp = {.after = cli_progress_after()};
    cli_progress_begin(&vp.line, cmd, "", 0, 0);
    for (int k = 0; k < nsrc && rc == 0; k++) {
        src[k].path = files[k];
        rc = read_source(cmd, &src[k], &vp);
    }
    for (int k = 1; k < nsrc && rc == 0; k++)
        if (src[k].trace || src[0].trace)
            rc = cli_error(cmd, "one trace, or any number of shapes: not both");
    /* planar shapes: the side view, in which every length in the plane is true */
    int planar = rc == 0;
    for (int k = 0; k < nsrc && rc == 0; k++) planar &= !src[k].trace && src[k].planar;
    if (planar && !camera_given) camera[0] = camera[1] = 0;
    if (rc == 0) {
        if (!omega_given) omega = isfinite(src[0].omega) ? src[0].omega : 0;
        if (!eps_given) eps = isfinite(src[0].eps) ? src[0].eps : 0;
        cli_out out;
        if ((rc = cli_out_open(cmd, &out, output)) == 0) {
            for (const char *const *l = cli_view_html; *l; l++) {
                if (strncmp(*l, "/*WHIRL_DATA*/", 14) == 0)
                    write_data(out.fp, src, nsrc, camera, omega, eps, &vp);
                else fputs(*l, out.fp);
            }
            cli_progress_clear(&vp.line);
            if (cli_interrupted) {
                cli_out_abort(&out);
                rc = cli_error(cmd, "interrupted while writing the page: nothing written");
            } else rc = cli_out_commit(cmd, &out);
        }
    }
    for (int k = 0; k < nsrc; k++) {
        free(src[k].xyz.v);
        free(src[k].start.v);
        free(src[k].time.v);
    }
    free(src);
    return rc;
}
