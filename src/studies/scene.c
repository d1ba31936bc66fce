/* Scenes: parsing and validating the INI file of one simulation run (see whirl/scene.h).
 *
 * Two passes. The first collects the raw text of every key with the line it came from (inih
 * does the syntax; a reader of our own counts the lines, hands inih lines of any length and
 * notes section headers), then applies the overrides. The second converts and checks every
 * value and the rules that tie keys together, so that each message names the key's line
 * (scene_convert.c; what the two share in scene_internal.h). Here: the names of the sections and
 * keys, the first pass, and the driver. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ini.h>

#include "whirl/scene.h"
#include "whirl/common.h"
#include "core/error.h"
#include "core/input.h"
#include "studies/scene_internal.h"

const char *const sc_section_names[] = {"chain", "start", "run", "output", "units"};
enum { N_SECTIONS = sizeof sc_section_names / sizeof sc_section_names[0] };

const sc_key_name sc_key_names[SC_NKEYS] = {
    [WHIRL_KEY_CHAIN_DIM] = {0, "dim"},
    [WHIRL_KEY_CHAIN_LINKS] = {0, "links"},
    [WHIRL_KEY_CHAIN_LENGTHS] = {0, "lengths", WHIRL_QUANTITY_LENGTH},
    [WHIRL_KEY_CHAIN_MASSES] = {0, "masses", WHIRL_QUANTITY_MASS},
    [WHIRL_KEY_CHAIN_LENGTH] = {0, "length", WHIRL_QUANTITY_LENGTH},
    [WHIRL_KEY_CHAIN_MASS] = {0, "mass", WHIRL_QUANTITY_MASS},
    [WHIRL_KEY_CHAIN_GRAVITY] = {0, "gravity"},
    [WHIRL_KEY_START_OMEGA] = {1, "omega", WHIRL_QUANTITY_RATE},
    [WHIRL_KEY_START_MODE] = {1, "mode"},
    [WHIRL_KEY_START_PERTURB] = {1, "perturb"},
    [WHIRL_KEY_START_SEED] = {1, "seed"},
    [WHIRL_KEY_START_THETA] = {1, "theta"},
    [WHIRL_KEY_START_PHI] = {1, "phi"},
    [WHIRL_KEY_START_THETA_DOT] = {1, "theta_dot", WHIRL_QUANTITY_RATE},
    [WHIRL_KEY_START_PHI_DOT] = {1, "phi_dot", WHIRL_QUANTITY_RATE},
    [WHIRL_KEY_START_HANGING] = {1, "hanging"},
    [WHIRL_KEY_RUN_FRAME] = {2, "frame"},
    [WHIRL_KEY_RUN_METHOD] = {2, "method"},
    [WHIRL_KEY_RUN_DT] = {2, "dt", WHIRL_QUANTITY_TIME},
    [WHIRL_KEY_RUN_T_END] = {2, "t_end", WHIRL_QUANTITY_TIME},
    [WHIRL_KEY_RUN_FORMULATION] = {2, "formulation"},
    [WHIRL_KEY_RUN_OMEGA] = {2, "omega", WHIRL_QUANTITY_RATE},
    [WHIRL_KEY_RUN_DRIVE_RADIUS] = {2, "drive_radius", WHIRL_QUANTITY_LENGTH},
    [WHIRL_KEY_RUN_AIR_DRAG] = {2, "air_drag"},
    [WHIRL_KEY_RUN_AIR_DRAG_QUADRATIC] = {2, "air_drag_quadratic"},
    [WHIRL_KEY_RUN_INTERNAL_DAMPING] = {2, "internal_damping"},
    [WHIRL_KEY_RUN_SEED_SIGMA] = {2, "seed_sigma"},
    [WHIRL_KEY_RUN_SEED_LAMBDA] = {2, "seed_lambda"},
    [WHIRL_KEY_RUN_TOL] = {2, "tol"},
    [WHIRL_KEY_RUN_STOP_DEVIATION] = {2, "stop_deviation", WHIRL_QUANTITY_LENGTH},
    [WHIRL_KEY_RUN_THREADS] = {2, "threads"},
    [SC_KEY_RUN_PIVOT] = {2, "pivot"},
    [WHIRL_KEY_OUTPUT_EVERY] = {3, "every", WHIRL_QUANTITY_TIME},
    [WHIRL_KEY_OUTPUT_COLUMNS] = {3, "columns"},
    [WHIRL_KEY_OUTPUT_TRACE] = {3, "trace"},
    [WHIRL_KEY_OUTPUT_TRACE_EVERY] = {3, "trace_every", WHIRL_QUANTITY_TIME},
    [WHIRL_KEY_OUTPUT_REFERENCE_MODE] = {3, "reference_mode"},
    [WHIRL_KEY_UNITS_SYSTEM] = {4, "system"},
};

/* The bounds of a scene file: its longest line (a list of 10^5 link lengths in full precision
 * is under 3 MiB) and its size; the reader checks both as it reads (core/input.h). */
#define WHIRL_SCENE_LINE_MAX ((size_t)16 << 20)
#define WHIRL_SCENE_BYTES_MAX ((size_t)64 << 20)

/* Placeholder handed to inih for the value of a line too long for its buffer. */
#define LONG_VALUE "\x01"

/* State of the first pass. */
typedef struct collect {
    const char *path;
    whirl_line_reader in; /* the bounded reader (core/input.h) */
    char *line;          /* the current physical line (in.line) */
    int lineno;          /* number of the current line */
    int continuation;    /* the current line is indented: it continues the previous key */
    char *long_value;    /* the value of the current line if it was too long for inih */
    char *raw[SC_NKEYS];
    int line_of[SC_NKEYS];
    int error_line;      /* line of the first error (0: none) */
    int status;
} collect;

/* Records the first error of the first pass: "FILE:LINE: message". */
static void collect_error(collect *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void collect_error(collect *c, const char *fmt, ...)
{
    if (c->status != GSL_SUCCESS) return;
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    c->status = whirl_fail(GSL_EINVAL, "%s:%d: %s", c->path, c->lineno, msg);
    c->error_line = c->lineno;
}

static int find_section(const char *name)
{
    for (int s = 0; s < N_SECTIONS; s++)
        if (strcmp(name, sc_section_names[s]) == 0) return s;
    return -1;
}

static int find_key(int section, const char *name)
{
    for (int k = 0; k < SC_NKEYS; k++)
        if (sc_key_names[k].section == section && strcmp(name, sc_key_names[k].name) == 0) return k;
    return -1;
}

/* "a, b, c": the keys of a section, for messages. */
static void list_keys(int section, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int k = 0; k < SC_NKEYS && used < size; k++)
        if (sc_key_names[k].section == section)
            used += (size_t)snprintf(buf + used, size - used, "%s%s", used ? ", " : "",
                                     sc_key_names[k].name);
}

char *sc_copy_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

char *sc_trim(char *s)
{
    while (*s == ' ' || *s == '\t') s++;
    size_t n = strlen(s);
    while (n > 0 && strchr(" \t\r\n", s[n - 1])) s[--n] = '\0';
    return s;
}

/* inih's reader: one physical line per call, counted. A line longer than inih's buffer keeps
 * its value here and reaches inih as "key=" LONG_VALUE. Section headers are checked here so
 * that an unknown section is reported even when it has no keys. */
static char *read_line(char *str, int num, void *stream)
{
    collect *c = stream;
    const int got = whirl_line_read(&c->in);
    if (got < 0) { /* too long, too much, out of memory, unreadable, interrupted */
        c->status = c->in.status;
        c->error_line = (int)c->in.lineno;
        return NULL;
    }
    if (got == 0) return NULL;
    c->line = c->in.line;
    const size_t len = c->in.len;
    c->lineno++;
    free(c->long_value);
    c->long_value = NULL;

    if (strlen(c->line) != len) {
        collect_error(c, "NUL byte at column %zu (a binary file?)", strlen(c->line) + 1);
        return NULL;
    }
    char *start = c->line;
    while (*start == ' ' || *start == '\t') start++;
    int blank = *start == '\0' || *start == '\n' || *start == '\r';
    int comment = *start == ';' || *start == '#';
    c->continuation = start > c->line && !blank && !comment;

    if (*start == '[') {
        char *end = strchr(start, ']');
        if (end) {
            *end = '\0';
            if (find_section(sc_trim(start + 1)) < 0)
                collect_error(c, "[%s]: unknown section (known: chain, start, run, output)",
                              sc_trim(start + 1));
            *end = ']';
            /* inih would drop the rest of a header line: only a comment may follow */
            const char *rest = end + 1;
            while (*rest == ' ' || *rest == '\t') rest++;
            if (*rest != '\0' && *rest != '\n' && *rest != '\r' && *rest != ';' && *rest != '#')
                collect_error(c, "text after the section header: '%.40s' (put each key on a "
                              "line of its own)", sc_trim(end + 1));
        }
    }
    if (len < (size_t)num - 1) {
        memcpy(str, c->line, len + 1);
        return str;
    }
    if (comment) {
        snprintf(str, (size_t)num, ";\n");
        return str;
    }
    /* A long key = value (or continuation) line: keep the value, strip its inline comment. */
    char *value = c->continuation ? start : strpbrk(start, "=:");
    if (value == NULL || (!c->continuation && (int)(value - c->line) > num - 8)) {
        memcpy(str, c->line, (size_t)num - 1); /* inih reports the syntax error */
        str[num - 1] = '\0';
        return str;
    }
    if (!c->continuation) value++;
    for (char *p = value; *p; p++)
        if (*p == ';' && p > value && (p[-1] == ' ' || p[-1] == '\t')) {
            *p = '\0';
            break;
        }
    c->long_value = sc_copy_string(sc_trim(value));
    if (c->long_value == NULL) {
        c->status = whirl_fail(GSL_ENOMEM, "out of memory reading '%s'", c->path);
        return NULL;
    }
    if (c->continuation)
        snprintf(str, (size_t)num, " " LONG_VALUE "\n");
    else
        snprintf(str, (size_t)num, "%.*s=" LONG_VALUE "\n", (int)(value - 1 - c->line), c->line);
    return str;
}

/* Stores the raw value of key (file line, or -1 for an override); a continuation appends. */
static int store(collect *c, int key, const char *value, int line, int append)
{
    if (append && c->raw[key]) {
        size_t a = strlen(c->raw[key]), b = strlen(value);
        char *joined = realloc(c->raw[key], a + b + 2);
        if (joined == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        joined[a] = ',';
        memcpy(joined + a + 1, value, b + 1);
        c->raw[key] = joined;
        return GSL_SUCCESS;
    }
    char *copy = sc_copy_string(value);
    if (copy == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    free(c->raw[key]);
    c->raw[key] = copy;
    c->line_of[key] = line;
    return GSL_SUCCESS;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
    collect *c = user;
    if (c->status != GSL_SUCCESS) return 1;
    if (c->long_value && strcmp(value, LONG_VALUE) == 0) value = c->long_value;
    if (section[0] == '\0') {
        collect_error(c, "%s: key outside any section", name);
        return 1;
    }
    int s = find_section(section);
    if (s < 0) return 1; /* reported at the section header */
    int k = find_key(s, name);
    if (k < 0) {
        char known[300];
        list_keys(s, known, sizeof known);
        collect_error(c, "[%s] %s: unknown key (known: %s)", section, name, known);
        return 1;
    }
    if (c->continuation) {
        if (store(c, k, value, c->lineno, 1) != GSL_SUCCESS) c->status = GSL_ENOMEM;
        return 1;
    }
    if (c->raw[k]) {
        collect_error(c, "[%s] %s: given twice (first at line %d)", section, name, c->line_of[k]);
        return 1;
    }
    if (store(c, k, value, c->lineno, 0) != GSL_SUCCESS) c->status = GSL_ENOMEM;
    return 1;
}

/* Applies one override "section.key=value". */
static int apply_override(collect *c, const char *text)
{
    const char *dot = strchr(text, '.');
    const char *eq = strchr(text, '=');
    if (dot == NULL || eq == NULL || dot > eq)
        return whirl_fail(GSL_EINVAL, "%s: --set '%s': expected SECTION.KEY=VALUE", c->path,
                          text);
    char section_buf[64], name_buf[64];
    snprintf(section_buf, sizeof section_buf, "%.*s", (int)(dot - text), text);
    snprintf(name_buf, sizeof name_buf, "%.*s", (int)(eq - dot - 1), dot + 1);
    const char *section = sc_trim(section_buf), *name = sc_trim(name_buf);
    int s = find_section(section);
    if (s < 0)
        return whirl_fail(GSL_EINVAL,
                          "%s: --set %s.%s: unknown section (known: chain, start, run, output)",
                          c->path, section, name);
    int k = find_key(s, name);
    if (k < 0) {
        char known[300];
        list_keys(s, known, sizeof known);
        return whirl_fail(GSL_EINVAL, "%s: --set %s.%s: unknown key (known: %s)", c->path,
                          section, name, known);
    }
    char *value = sc_copy_string(eq + 1);
    if (value == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = store(c, k, sc_trim(value), -1, 0);
    free(value);
    return status;
}


/* ---- driver ---- */

static int collect_stream(collect *c, FILE *fp, const char *path)
{
    c->path = path;
    c->in = whirl_line_reader_init(fp, path, WHIRL_SCENE_LINE_MAX, WHIRL_SCENE_BYTES_MAX);
    int rc = ini_parse_stream(read_line, c, on_key, c);
    if (ferror(fp) && c->status == GSL_SUCCESS)
        c->status = whirl_fail(GSL_EFAILED, "%s: read error", path);
    whirl_line_reader_free(&c->in);
    c->line = NULL;
    /* inih's own (syntax) error, unless ours came first */
    if (rc > 0 && (c->status == GSL_SUCCESS || rc < c->error_line))
        c->status = whirl_fail(GSL_EINVAL, "%s:%d: syntax error: expected [section] or key = value",
                               path, rc);
    else if (rc < 0 && c->status == GSL_SUCCESS)
        c->status = whirl_fail(GSL_ENOMEM, "%s: out of memory", path);
    return c->status;
}

int whirl_scene_parse_stream_with_pivot(FILE *fp, const char *path,
                                        const char *const *overrides, size_t n_overrides,
                                        whirl_scene *scene, whirl_scene_pivot *pivot)
{
    memset(scene, 0, sizeof *scene);
    if (pivot) memset(pivot, 0, sizeof *pivot);
    collect c;
    memset(&c, 0, sizeof c);
    int status = collect_stream(&c, fp, path);
    for (size_t i = 0; i < n_overrides && status == GSL_SUCCESS; i++)
        status = apply_override(&c, overrides[i]);
    if (status == GSL_SUCCESS && (scene->path = sc_copy_string(path)) == NULL)
        status = whirl_fail(GSL_ENOMEM, "out of memory");
    if (status == GSL_SUCCESS) {
        memcpy(scene->line, c.line_of, sizeof scene->line); /* the keys of whirl_scene_key */
        convert v = {scene, c.raw, c.line_of, pivot};
        status = sc_convert_units(&v);
        if (status == GSL_SUCCESS) status = sc_convert_chain(&v);
        if (status == GSL_SUCCESS) status = sc_convert_start(&v);
        if (status == GSL_SUCCESS) status = sc_convert_run(&v);
        if (status == GSL_SUCCESS) status = sc_convert_pivot(&v);
        if (status == GSL_SUCCESS) status = sc_convert_output(&v);
    }
    for (int k = 0; k < SC_NKEYS; k++) free(c.raw[k]);
    free(c.long_value);
    if (status != GSL_SUCCESS) {
        whirl_scene_free(scene);
        if (pivot) memset(pivot, 0, sizeof *pivot);
    }
    return status;
}

int whirl_scene_parse_stream(FILE *fp, const char *path, const char *const *overrides,
                             size_t n_overrides, whirl_scene *scene)
{
    return whirl_scene_parse_stream_with_pivot(fp, path, overrides, n_overrides, scene, NULL);
}

int whirl_scene_parse_with_pivot(const char *path, const char *const *overrides,
                                 size_t n_overrides, whirl_scene *scene, whirl_scene_pivot *pivot)
{
    memset(scene, 0, sizeof *scene);
    if (pivot) memset(pivot, 0, sizeof *pivot);
    FILE *fp;
    int status = whirl_input_open(path, &fp);
    if (status != GSL_SUCCESS) return status;
    status = whirl_scene_parse_stream_with_pivot(fp, path, overrides, n_overrides, scene, pivot);
    fclose(fp);
    return status;
}

int whirl_scene_parse(const char *path, const char *const *overrides, size_t n_overrides,
                      whirl_scene *scene)
{
    return whirl_scene_parse_with_pivot(path, overrides, n_overrides, scene, NULL);
}

void whirl_scene_free(whirl_scene *scene)
{
    if (scene == NULL) return;
    double **arrays[] = {&scene->length, &scene->mass, &scene->theta, &scene->phi,
                         &scene->theta_dot, &scene->phi_dot, &scene->seed_sigma,
                         &scene->seed_lambda};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(*arrays[i]);
    free(scene->path);
    free(scene->method);
    free(scene->trace);
    memset(scene, 0, sizeof *scene);
}
