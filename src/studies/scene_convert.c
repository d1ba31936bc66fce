/* Scenes: parsing and validating the INI file of one simulation run (see whirl/scene.h).
 *
 * Two passes. The first collects the raw text of every key with the line it came from (inih
 * does the syntax; a reader of our own counts the lines, hands inih lines of any length and
 * notes section headers), then applies the overrides. The second converts and checks every
 * value and the rules that tie keys together, so that each message names the key's line. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <ini.h>

#include "whirl/scene.h"
#include "whirl/common.h"
#include "core/error.h"
#include "core/input.h"

static const char *const section_names[] = {"chain", "start", "run", "output", "units"};
enum { N_SECTIONS = sizeof section_names / sizeof section_names[0] };

/* Every key: its section, its name and the kind of quantity its numbers are (the unit suffixes
 * they may carry). */
static const struct {
    int section; /* index into section_names */
    const char *name;
    whirl_quantity kind;
} key_names[WHIRL_SCENE_NKEYS] = {
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
    [WHIRL_KEY_OUTPUT_EVERY] = {3, "every", WHIRL_QUANTITY_TIME},
    [WHIRL_KEY_OUTPUT_COLUMNS] = {3, "columns"},
    [WHIRL_KEY_OUTPUT_TRACE] = {3, "trace"},
    [WHIRL_KEY_OUTPUT_TRACE_EVERY] = {3, "trace_every", WHIRL_QUANTITY_TIME},
    [WHIRL_KEY_OUTPUT_REFERENCE_MODE] = {3, "reference_mode"},
    [WHIRL_KEY_UNITS_SYSTEM] = {4, "system"},
};

static const char *const column_names[WHIRL_NCOLUMNS] = {
    "t", "tip_x", "tip_y", "tip_z", "energy", "jacobi", "lz", "constraint", "deviation"};

const char *whirl_column_name(whirl_column c)
{
    return (c >= 0 && c < WHIRL_NCOLUMNS) ? column_names[c] : NULL;
}

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
    char *raw[WHIRL_SCENE_NKEYS];
    int line_of[WHIRL_SCENE_NKEYS];
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
        if (strcmp(name, section_names[s]) == 0) return s;
    return -1;
}

static int find_key(int section, const char *name)
{
    for (int k = 0; k < WHIRL_SCENE_NKEYS; k++)
        if (key_names[k].section == section && strcmp(name, key_names[k].name) == 0) return k;
    return -1;
}

/* "a, b, c": the keys of a section, for messages. */
static void list_keys(int section, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int k = 0; k < WHIRL_SCENE_NKEYS && used < size; k++)
        if (key_names[k].section == section)
            used += (size_t)snprintf(buf + used, size - used, "%s%s", used ? ", " : "",
                                     key_names[k].name);
}

static char *copy_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

static char *trim(char *s)
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
            if (find_section(trim(start + 1)) < 0)
                collect_error(c, "[%s]: unknown section (known: chain, start, run, output)",
                              trim(start + 1));
            *end = ']';
            /* inih would drop the rest of a header line: only a comment may follow */
            const char *rest = end + 1;
            while (*rest == ' ' || *rest == '\t') rest++;
            if (*rest != '\0' && *rest != '\n' && *rest != '\r' && *rest != ';' && *rest != '#')
                collect_error(c, "text after the section header: '%.40s' (put each key on a "
                              "line of its own)", trim(end + 1));
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
    c->long_value = copy_string(trim(value));
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
    char *copy = copy_string(value);
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
    const char *section = trim(section_buf), *name = trim(name_buf);
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
    char *value = copy_string(eq + 1);
    if (value == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = store(c, k, trim(value), -1, 0);
    free(value);
    return status;
}

/* ---- second pass: typed values ---- */

typedef struct convert {
    whirl_scene *scene;
    char *const *raw;
} convert;

const char *whirl_scene_where(const whirl_scene *scene, whirl_scene_key key, char *buf,
                              size_t size)
{
    const char *sec = section_names[key_names[key].section], *name = key_names[key].name;
    int line = scene->line[key];
    if (line > 0)
        snprintf(buf, size, "%s:%d: [%s] %s", scene->path, line, sec, name);
    else if (line < 0)
        snprintf(buf, size, "%s: --set %s.%s", scene->path, sec, name);
    else
        snprintf(buf, size, "%s: [%s] %s", scene->path, sec, name);
    return buf;
}

/* Fails with "WHERE: message" for key. */
static int key_error(const convert *v, whirl_scene_key key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static int key_error(const convert *v, whirl_scene_key key, const char *fmt, ...)
{
    char where[300], msg[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return whirl_fail(GSL_EINVAL, "%s: %s", whirl_scene_where(v->scene, key, where, sizeof where),
                      msg);
}

static int given(const convert *v, whirl_scene_key key) { return v->raw[key] != NULL; }

static int require(const convert *v, whirl_scene_key key, const char *why)
{
    if (given(v, key)) return GSL_SUCCESS;
    return key_error(v, key, "missing%s%s", why ? " " : "", why ? why : "");
}

/* A finite number, the whole text; *suffixed: whether it carries a unit. */
static int parse_number(const char *text, whirl_quantity kind, double *out, int *suffixed)
{
    return whirl_parse_quantity(text, kind, out, suffixed);
}

/* The unit of a dimensionless scene's rate, length, mass or time, for messages. */
static const char *dimensionless_unit(whirl_quantity kind)
{
    switch (kind) {
    case WHIRL_QUANTITY_RATE: return "sqrt(g/L)";
    case WHIRL_QUANTITY_LENGTH: return "L";
    case WHIRL_QUANTITY_MASS: return "M";
    case WHIRL_QUANTITY_TIME: return "sqrt(L/g)";
    default: return "";
    }
}

/* A value written with a unit (4Hz, 5cm) in a dimensionless scene has no scale to convert it
 * with: an error that says how to switch to SI. */
static int unit_in_dimensionless(const convert *v, whirl_scene_key key, const char *text);

/* What the numbers of key may look like, for messages: "a finite number (optionally with
 * m, cm or mm)". */
static const char *number_words(whirl_scene_key key, char *buf, size_t size)
{
    const whirl_quantity kind = key_names[key].kind;
    if (kind == WHIRL_QUANTITY_NUMBER) return "a finite number";
    snprintf(buf, size, "a finite number (optionally with %s)", whirl_quantity_suffixes(kind));
    return buf;
}

/* The number of key, or dflt if absent. */
static int get_double(const convert *v, whirl_scene_key key, double dflt, double *out)
{
    *out = dflt;
    if (!given(v, key)) return GSL_SUCCESS;
    char words[80];
    int suffixed = 0;
    if (parse_number(v->raw[key], key_names[key].kind, out, &suffixed) != 0)
        return key_error(v, key, "must be %s, got '%s'", number_words(key, words, sizeof words),
                         v->raw[key]);
    if (suffixed && !v->scene->physical) return unit_in_dimensionless(v, key, v->raw[key]);
    return GSL_SUCCESS;
}

/* A number with a lower bound: > lo (strict) or >= lo. */
static int get_bounded(const convert *v, whirl_scene_key key, double dflt, double lo, int strict,
                       double *out)
{
    int status = get_double(v, key, dflt, out);
    if (status != GSL_SUCCESS) return status;
    if (strict ? !(*out > lo) : !(*out >= lo))
        return key_error(v, key, "must be %s %g, got %s", strict ? ">" : ">=", lo, v->raw[key]);
    return GSL_SUCCESS;
}

/* An integer in [lo, hi]. */
static int get_integer(const convert *v, whirl_scene_key key, long dflt, long lo, long hi,
                       long *out)
{
    *out = dflt;
    if (!given(v, key)) return GSL_SUCCESS;
    const char *text = v->raw[key];
    char *end;
    errno = 0;
    long x = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE)
        return key_error(v, key, "must be an integer, got '%s'", text);
    if (x < lo || x > hi) return key_error(v, key, "must be in %ld..%ld, got %ld", lo, hi, x);
    *out = x;
    return GSL_SUCCESS;
}

/* A comma list of exactly n finite numbers into a new array (NULL if absent). With positive,
 * each must be > 0. */
static int get_list(const convert *v, whirl_scene_key key, size_t n, int positive, double **out)
{
    *out = NULL;
    if (!given(v, key)) return GSL_SUCCESS;
    const char *text = v->raw[key];
    size_t count = 1;
    for (const char *p = text; *p; p++) count += *p == ',';
    if (count != n)
        return key_error(v, key, "expected %zu values (links = %zu), got %zu", n, n, count);
    double *x = malloc(n * sizeof *x);
    char *item = copy_string(text);
    if (x == NULL || item == NULL) {
        free(x);
        free(item);
        return whirl_fail(GSL_ENOMEM, "out of memory");
    }
    int status = GSL_SUCCESS;
    char *p = item;
    for (size_t i = 0; i < n && status == GSL_SUCCESS; i++) {
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        char *t = trim(p);
        char words[80];
        int suffixed = 0;
        if (parse_number(t, key_names[key].kind, &x[i], &suffixed) != 0)
            status = key_error(v, key, "value %zu must be %s, got '%s'", i + 1,
                               number_words(key, words, sizeof words), t);
        else if (suffixed && !v->scene->physical)
            status = unit_in_dimensionless(v, key, t);
        else if (positive && !(x[i] > 0))
            status = key_error(v, key, "value %zu must be > 0, got %s", i + 1, t);
        p = comma ? comma + 1 : p;
    }
    free(item);
    if (status != GSL_SUCCESS) {
        free(x);
        return status;
    }
    *out = x;
    return GSL_SUCCESS;
}

static int unit_in_dimensionless(const convert *v, whirl_scene_key key, const char *text)
{
    return key_error(v, key, "%s has a unit, but the scene is dimensionless: give [units] system "
                     "= SI (lengths in m, masses in kg, rates in rad/s), or a number in units of "
                     "%s", text, dimensionless_unit(key_names[key].kind));
}

/* One of the words[0..n-1] (case-insensitive): its index. */
static int get_word(const convert *v, whirl_scene_key key, const char *const *words, int n,
                    int dflt, int *out)
{
    *out = dflt;
    if (!given(v, key)) return GSL_SUCCESS;
    for (int i = 0; i < n; i++)
        if (strcasecmp(v->raw[key], words[i]) == 0) {
            *out = i;
            return GSL_SUCCESS;
        }
    char known[200];
    size_t used = 0;
    for (int i = 0; i < n && used < sizeof known; i++)
        used += (size_t)snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                                 words[i]);
    return key_error(v, key, "must be one of %s, got '%s'", known, v->raw[key]);
}

#define TRY(expr)                                                                              \
    do {                                                                                       \
        int try_status_ = (expr);                                                              \
        if (try_status_ != GSL_SUCCESS) return try_status_;                                    \
    } while (0)

/* A list of n zeros when key is absent, else the parsed list. */
static int get_list_or_zero(const convert *v, whirl_scene_key key, size_t n, double **out)
{
    TRY(get_list(v, key, n, 0, out));
    if (*out == NULL && (*out = calloc(n, sizeof **out)) == NULL)
        return whirl_fail(GSL_ENOMEM, "out of memory");
    return GSL_SUCCESS;
}

/* The list of key (N values > 0), or, when it is absent, N equal values summing to total. The
 * sum of the values into *sum. */
static int get_weights(const convert *v, whirl_scene_key key, size_t n, double total,
                       double **out, double *sum)
{
    TRY(get_list(v, key, n, 1, out));
    if (*out == NULL) {
        if ((*out = malloc(n * sizeof **out)) == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        for (size_t i = 0; i < n; i++) (*out)[i] = total / (double)n;
        *sum = total; /* as given, not as summed */
        return GSL_SUCCESS;
    }
    *sum = 0;
    for (size_t i = 0; i < n; i++) *sum += (*out)[i];
    if (!isfinite(*sum)) return key_error(v, key, "the sum of the values overflows");
    return GSL_SUCCESS;
}

/* The first given key of keys[0..n-1], or -1. */
static int first_given(const convert *v, const whirl_scene_key *keys, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (given(v, keys[i])) return (int)keys[i];
    return -1;
}

static int convert_units(const convert *v)
{
    static const char *const systems[] = {"dimensionless", "SI"};
    return get_word(v, WHIRL_KEY_UNITS_SYSTEM, systems, 2, 0, &v->scene->physical);
}

/* The scalar key or the list key of the chain, not both. */
static int one_of(const convert *v, whirl_scene_key scalar, whirl_scene_key list)
{
    if (given(v, scalar) && given(v, list))
        return key_error(v, scalar, "conflicts with [chain] %s: give the chain's %s or the list "
                         "of N values", key_names[list].name, key_names[scalar].name);
    return GSL_SUCCESS;
}

static int convert_chain(const convert *v)
{
    whirl_scene *s = v->scene;
    long dim, links;
    double length, mass;
    TRY(require(v, WHIRL_KEY_CHAIN_DIM, NULL));
    TRY(require(v, WHIRL_KEY_CHAIN_LINKS, NULL));
    TRY(get_integer(v, WHIRL_KEY_CHAIN_DIM, 3, 2, 3, &dim));
    TRY(get_integer(v, WHIRL_KEY_CHAIN_LINKS, 1, 1, 1000000, &links));
    s->dim = (int)dim;
    s->links = (size_t)links;
    TRY(one_of(v, WHIRL_KEY_CHAIN_LENGTH, WHIRL_KEY_CHAIN_LENGTHS));
    TRY(one_of(v, WHIRL_KEY_CHAIN_MASS, WHIRL_KEY_CHAIN_MASSES));
    TRY(get_bounded(v, WHIRL_KEY_CHAIN_LENGTH, 1, 0, 1, &length));
    TRY(get_bounded(v, WHIRL_KEY_CHAIN_MASS, 1, 0, 1, &mass));
    TRY(get_weights(v, WHIRL_KEY_CHAIN_LENGTHS, s->links, length, &s->length, &s->chain_length));
    TRY(get_weights(v, WHIRL_KEY_CHAIN_MASSES, s->links, mass, &s->mass, &s->chain_mass));
    return get_bounded(v, WHIRL_KEY_CHAIN_GRAVITY, s->physical ? WHIRL_STANDARD_GRAVITY : 1, 0, 1,
                       &s->gravity);
}

static const whirl_scene_key steady_keys[] = {WHIRL_KEY_START_OMEGA, WHIRL_KEY_START_MODE};
static const whirl_scene_key perturb_keys[] = {WHIRL_KEY_START_PERTURB, WHIRL_KEY_START_SEED};
static const whirl_scene_key angle_keys[] = {WHIRL_KEY_START_THETA, WHIRL_KEY_START_PHI,
                                             WHIRL_KEY_START_THETA_DOT, WHIRL_KEY_START_PHI_DOT};

static int get_bool(const convert *v, whirl_scene_key key, int *out)
{
    static const char *const words[] = {"false", "true", "no", "yes", "0", "1", "off", "on"};
    int i;
    TRY(get_word(v, key, words, 8, 0, &i));
    *out = i % 2;
    return GSL_SUCCESS;
}

static int convert_start(const convert *v)
{
    whirl_scene *s = v->scene;
    int steady = first_given(v, steady_keys, 2), angles = first_given(v, angle_keys, 4);
    int hanging = 0;
    TRY(get_bool(v, WHIRL_KEY_START_HANGING, &hanging));
    if (given(v, WHIRL_KEY_START_HANGING) && !hanging)
        return key_error(v, WHIRL_KEY_START_HANGING,
                         "must be true when given (false is no start)");
    /* Exactly one kind of start. */
    int kinds[3] = {steady, angles, hanging ? (int)WHIRL_KEY_START_HANGING : -1};
    int first = -1;
    for (int i = 0; i < 3; i++) {
        if (kinds[i] < 0) continue;
        if (first >= 0) {
            const int other = s->line[first];
            char at[32] = "";
            if (other > 0) snprintf(at, sizeof at, " (line %d)", other);
            return key_error(v, (whirl_scene_key)kinds[i],
                             "conflicts with [start] %s%s: give one start (omega and mode, "
                             "theta, or hanging)", key_names[first].name, at);
        }
        first = kinds[i];
    }
    if (first < 0)
        return key_error(v, WHIRL_KEY_START_MODE,
                         "missing: give one start (omega and mode, theta, or hanging = true)");
    const int perturbed = first_given(v, perturb_keys, 2);
    if (perturbed >= 0 && angles >= 0)
        return key_error(v, (whirl_scene_key)perturbed,
                         "applies to the steady and the hanging start, not to theta");
    long seed;
    TRY(get_bounded(v, WHIRL_KEY_START_PERTURB, 0, 0, 0, &s->perturb));
    TRY(get_integer(v, WHIRL_KEY_START_SEED, 1, 0, 2147483647L, &seed));
    s->seed = (unsigned long)seed;
    if (hanging) {
        s->start = WHIRL_START_HANGING;
        return GSL_SUCCESS;
    }
    if (steady >= 0) {
        long mode;
        s->start = WHIRL_START_STEADY;
        TRY(require(v, WHIRL_KEY_START_MODE, "(the steady start needs omega and mode)"));
        TRY(require(v, WHIRL_KEY_START_OMEGA, "(the steady start needs omega and mode)"));
        if (s->dim != 3)
            return key_error(v, WHIRL_KEY_START_MODE,
                             "a steady start needs [chain] dim = 3, got %d", s->dim);
        TRY(get_integer(v, WHIRL_KEY_START_MODE, 1, 1, (long)s->links, &mode)); /* modes 1..N */
        s->mode = (int)mode;
        TRY(get_bounded(v, WHIRL_KEY_START_OMEGA, 0, 0, 1, &s->start_omega));
        if (!(s->start_omega <= WHIRL_OMEGA_MAX))
            return key_error(v, WHIRL_KEY_START_OMEGA, "must be at most %g (the centrifugal "
                             "forces ~ omega^2 would overflow), got %g", WHIRL_OMEGA_MAX,
                             s->start_omega);
        return GSL_SUCCESS;
    }
    s->start = WHIRL_START_ANGLES;
    TRY(require(v, WHIRL_KEY_START_THETA, "(the angle start needs theta)"));
    if (s->dim == 2)
        for (int i = 1; i < 4; i += 2)
            if (given(v, angle_keys[i]))
                return key_error(v, angle_keys[i], "not used in 2D (dim = 2)");
    TRY(get_list(v, WHIRL_KEY_START_THETA, s->links, 0, &s->theta));
    TRY(get_list_or_zero(v, WHIRL_KEY_START_PHI, s->links, &s->phi));
    TRY(get_list_or_zero(v, WHIRL_KEY_START_THETA_DOT, s->links, &s->theta_dot));
    return get_list_or_zero(v, WHIRL_KEY_START_PHI_DOT, s->links, &s->phi_dot);
}

static int convert_run(const convert *v)
{
    static const char *const frames[] = {"inertial", "rotating"};
    static const char *const formulations[] = {"default", "seed"};
    whirl_scene *s = v->scene;
    int word;
    TRY(get_word(v, WHIRL_KEY_RUN_FRAME, frames, 2, 0, &word));
    s->frame = word == 1 ? WHIRL_FRAME_ROTATING : WHIRL_FRAME_INERTIAL;
    if (s->frame == WHIRL_FRAME_ROTATING && s->dim != 3)
        return key_error(v, WHIRL_KEY_RUN_FRAME, "rotating needs [chain] dim = 3, got %d",
                         s->dim);
    const char *method = given(v, WHIRL_KEY_RUN_METHOD) ? v->raw[WHIRL_KEY_RUN_METHOD] : "gauss2";
    if (method[0] == '\0') return key_error(v, WHIRL_KEY_RUN_METHOD, "must not be empty");
    if ((s->method = copy_string(method)) == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    TRY(require(v, WHIRL_KEY_RUN_DT, NULL));
    TRY(require(v, WHIRL_KEY_RUN_T_END, NULL));
    TRY(get_bounded(v, WHIRL_KEY_RUN_DT, 0, 0, 1, &s->dt));
    TRY(get_bounded(v, WHIRL_KEY_RUN_T_END, 0, 0, 1, &s->t_end));
    TRY(get_word(v, WHIRL_KEY_RUN_FORMULATION, formulations, 2, 0, &word));
    s->formulation = word == 1 ? WHIRL_FORMULATION_SEED : WHIRL_FORMULATION_CARTESIAN;
    TRY(get_double(v, WHIRL_KEY_RUN_OMEGA, s->start == WHIRL_START_STEADY ? s->start_omega : 0,
                   &s->omega));
    if (!(fabs(s->omega) <= WHIRL_OMEGA_MAX))
        return key_error(v, WHIRL_KEY_RUN_OMEGA, "|omega| must be at most %g (the centrifugal "
                         "forces ~ omega^2 would overflow), got %g", WHIRL_OMEGA_MAX, s->omega);
    TRY(get_bounded(v, WHIRL_KEY_RUN_DRIVE_RADIUS, 0, 0, 0, &s->drive_radius));
    TRY(get_bounded(v, WHIRL_KEY_RUN_AIR_DRAG, 0, 0, 0, &s->air_drag));
    TRY(get_bounded(v, WHIRL_KEY_RUN_AIR_DRAG_QUADRATIC, 0, 0, 0, &s->air_drag_quadratic));
    TRY(get_bounded(v, WHIRL_KEY_RUN_INTERNAL_DAMPING, 0, 0, 0, &s->internal_damping));
    static const whirl_scene_key seed_forces[] = {WHIRL_KEY_RUN_SEED_SIGMA,
                                                  WHIRL_KEY_RUN_SEED_LAMBDA};
    int force = first_given(v, seed_forces, 2);
    if (force >= 0 && s->dim != 2)
        return key_error(v, (whirl_scene_key)force, "2D only (dim = 2), got dim = %d", s->dim);
    TRY(get_list(v, WHIRL_KEY_RUN_SEED_SIGMA, s->links, 0, &s->seed_sigma));
    TRY(get_list(v, WHIRL_KEY_RUN_SEED_LAMBDA, s->links, 0, &s->seed_lambda));
    TRY(get_bounded(v, WHIRL_KEY_RUN_TOL, 0, 0, 0, &s->tol));
    if (s->tol > 0 && s->tol < WHIRL_TOL_MIN)
        return key_error(v, WHIRL_KEY_RUN_TOL, "%g is below the round-off of doubles: use a "
                         "tolerance >= %g", s->tol, WHIRL_TOL_MIN);
    const double work = (double)s->links * s->t_end / s->dt;
    if (s->tol == 0 && work > WHIRL_SCENE_WORK_MAX)
        return key_error(v, WHIRL_KEY_RUN_T_END, "links x t_end / dt = %.3g link-steps exceeds the "
                         "budget of %g (hours of work): shorten t_end, raise dt or use fewer "
                         "links", work, WHIRL_SCENE_WORK_MAX);
    if (given(v, WHIRL_KEY_RUN_STOP_DEVIATION))
        TRY(get_bounded(v, WHIRL_KEY_RUN_STOP_DEVIATION, 0, 0, 1, &s->stop_deviation));
    long threads;
    TRY(get_integer(v, WHIRL_KEY_RUN_THREADS, 1, 1, WHIRL_DYN_THREADS_MAX, &threads));
    s->threads = (int)threads;
    return GSL_SUCCESS;
}

/* The deviation needs a reference: [output] reference_mode, the steady start or the hanging
 * chain. */
static int check_reference(const convert *v, whirl_scene_key key)
{
    if (v->scene->start != WHIRL_START_ANGLES || v->scene->reference_mode > 0)
        return GSL_SUCCESS;
    return key_error(v, key,
                     "the deviation needs a reference: [output] reference_mode, or a steady "
                     "start ([start] omega and mode, or hanging); the theta start is not one");
}

static int convert_columns(const convert *v)
{
    whirl_scene *s = v->scene;
    s->columns[0] = WHIRL_COLUMN_T;
    s->want[WHIRL_COLUMN_T] = 1;
    s->n_columns = 1;
    if (!given(v, WHIRL_KEY_OUTPUT_COLUMNS)) {
        for (int c = 1; c < WHIRL_NCOLUMNS; c++)
            if (c != WHIRL_COLUMN_DEVIATION) {
                s->columns[s->n_columns++] = (whirl_column)c;
                s->want[c] = 1;
            }
        return GSL_SUCCESS;
    }
    char *list = copy_string(v->raw[WHIRL_KEY_OUTPUT_COLUMNS]);
    if (list == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = GSL_SUCCESS;
    char *p = list;
    while (status == GSL_SUCCESS) {
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        char *name = trim(p);
        int c = 0;
        while (c < WHIRL_NCOLUMNS && strcmp(name, column_names[c]) != 0) c++;
        if (c == WHIRL_NCOLUMNS)
            status = key_error(v, WHIRL_KEY_OUTPUT_COLUMNS,
                               "unknown column '%s' (known: t, tip_x, tip_y, tip_z, energy, "
                               "jacobi, lz, constraint, deviation)", name);
        else if (s->want[c] && c != WHIRL_COLUMN_T)
            status = key_error(v, WHIRL_KEY_OUTPUT_COLUMNS, "column '%s' given twice", name);
        else if (c != WHIRL_COLUMN_T) {
            s->want[c] = 1;
            s->columns[s->n_columns++] = (whirl_column)c;
        }
        if (comma == NULL) break;
        p = comma + 1;
    }
    free(list);
    return status;
}

/* The rows, the trace's points and the work the output and the rotation force (whirl/scene.h:
 * WHIRL_SCENE_ROWS_MAX, WHIRL_SCENE_TRACE_MAX, WHIRL_SCENE_WORK_MAX); the counts as doubles,
 * before any is made an integer. */
static int check_work(const convert *v)
{
    const whirl_scene *s = v->scene;
    char size[32];
    const double rows = s->t_end / s->every;
    if (!(rows <= WHIRL_SCENE_ROWS_MAX))
        return key_error(v, WHIRL_KEY_OUTPUT_EVERY, "t_end / every = %.3g rows exceeds the bound "
                         "of %g rows (they would take about %s): raise every or shorten t_end",
                         rows, WHIRL_SCENE_ROWS_MAX,
                         whirl_bytes_words(size, sizeof size,
                                           rows * 20.0 * (double)s->n_columns));
    const double frames = given(v, WHIRL_KEY_OUTPUT_TRACE) ? s->t_end / s->trace_every : 0;
    const double points = frames * (double)(s->links + 1);
    if (!(points <= WHIRL_SCENE_TRACE_MAX))
        return key_error(v, WHIRL_KEY_OUTPUT_TRACE_EVERY, "t_end / trace_every x (links + 1) = "
                         "%.3g trace points exceeds the bound of %g (they would take about %s): "
                         "raise trace_every or shorten t_end", points, WHIRL_SCENE_TRACE_MAX,
                         whirl_bytes_words(size, sizeof size, points * 60.0));
    const double steps = (s->tol == 0 ? s->t_end / s->dt : 0) + rows + frames +
                         fabs(s->omega) * s->t_end;
    const double work = (double)s->links * steps;
    if (!(work <= WHIRL_SCENE_WORK_MAX))
        return key_error(v, WHIRL_KEY_RUN_T_END, "links x (steps + rows + frames + |omega| t_end) "
                         "= %.3g link-steps exceeds the budget of %g (hours of work): shorten "
                         "t_end, raise dt or every, lower omega or use fewer links", work,
                         WHIRL_SCENE_WORK_MAX);
    return GSL_SUCCESS;
}

/* The trace file of the scene: as given when it comes from an override (the command line,
 * relative to the working directory); from the file, a path relative to the scene's folder that
 * stays inside it: not absolute, no ".." component (a scene shared as data cannot write
 * anywhere else). */
static int trace_path(const convert *v, const char *value, char **out)
{
    const whirl_scene *s = v->scene;
    if (s->line[WHIRL_KEY_OUTPUT_TRACE] < 0) {
        if ((*out = copy_string(value)) == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        return GSL_SUCCESS;
    }
    if (value[0] == '/')
        return key_error(v, WHIRL_KEY_OUTPUT_TRACE, "must be a path relative to the scene's "
                         "folder, not an absolute path");
    for (const char *p = value; *p;) {
        const size_t len = strcspn(p, "/");
        if (len == 2 && p[0] == '.' && p[1] == '.')
            return key_error(v, WHIRL_KEY_OUTPUT_TRACE, "must stay in the scene's folder (no "
                             "'..'); give another place with --set output.trace=PATH");
        p += len;
        if (*p == '/') p++;
    }
    const char *slash = strrchr(s->path, '/');
    const size_t dir = slash ? (size_t)(slash - s->path) + 1 : 0, len = strlen(value);
    if ((*out = malloc(dir + len + 1)) == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    memcpy(*out, s->path, dir);
    memcpy(*out + dir, value, len + 1);
    return GSL_SUCCESS;
}

static int convert_output(const convert *v)
{
    whirl_scene *s = v->scene;
    TRY(get_bounded(v, WHIRL_KEY_OUTPUT_EVERY, s->dt, 0, 1, &s->every));
    TRY(get_bounded(v, WHIRL_KEY_OUTPUT_TRACE_EVERY, s->every, 0, 1, &s->trace_every));
    TRY(convert_columns(v));
    TRY(check_work(v));
    if (given(v, WHIRL_KEY_OUTPUT_REFERENCE_MODE)) {
        long mode;
        TRY(get_integer(v, WHIRL_KEY_OUTPUT_REFERENCE_MODE, 1, 1, (long)s->links, &mode));
        if (s->dim != 3)
            return key_error(v, WHIRL_KEY_OUTPUT_REFERENCE_MODE, "needs [chain] dim = 3, got %d",
                             s->dim);
        if (!(s->omega > 0))
            return key_error(v, WHIRL_KEY_OUTPUT_REFERENCE_MODE,
                             "needs [run] omega > 0 (the rate of the reference shape)");
        s->reference_mode = (int)mode;
    }
    if (s->want[WHIRL_COLUMN_DEVIATION]) TRY(check_reference(v, WHIRL_KEY_OUTPUT_COLUMNS));
    if (s->stop_deviation > 0) TRY(check_reference(v, WHIRL_KEY_RUN_STOP_DEVIATION));
    if (given(v, WHIRL_KEY_OUTPUT_TRACE)) {
        if (v->raw[WHIRL_KEY_OUTPUT_TRACE][0] == '\0')
            return key_error(v, WHIRL_KEY_OUTPUT_TRACE, "must not be empty");
        TRY(trace_path(v, v->raw[WHIRL_KEY_OUTPUT_TRACE], &s->trace));
    } else if (given(v, WHIRL_KEY_OUTPUT_TRACE_EVERY))
        return key_error(v, WHIRL_KEY_OUTPUT_TRACE_EVERY, "given without [output] trace");
    return GSL_SUCCESS;
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

int whirl_scene_parse_stream(FILE *fp, const char *path, const char *const *overrides,
                             size_t n_overrides, whirl_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    collect c;
    memset(&c, 0, sizeof c);
    int status = collect_stream(&c, fp, path);
    for (size_t i = 0; i < n_overrides && status == GSL_SUCCESS; i++)
        status = apply_override(&c, overrides[i]);
    if (status == GSL_SUCCESS && (scene->path = copy_string(path)) == NULL)
        status = whirl_fail(GSL_ENOMEM, "out of memory");
    if (status == GSL_SUCCESS) {
        memcpy(scene->line, c.line_of, sizeof scene->line);
        convert v = {scene, c.raw};
        status = convert_units(&v);
        if (status == GSL_SUCCESS) status = convert_chain(&v);
        if (status == GSL_SUCCESS) status = convert_start(&v);
        if (status == GSL_SUCCESS) status = convert_run(&v);
        if (status == GSL_SUCCESS) status = convert_output(&v);
    }
    for (int k = 0; k < WHIRL_SCENE_NKEYS; k++) free(c.raw[k]);
    free(c.long_value);
    if (status != GSL_SUCCESS) whirl_scene_free(scene);
    return status;
}

int whirl_scene_parse(const char *path, const char *const *overrides, size_t n_overrides,
                      whirl_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    FILE *fp;
    int status = whirl_input_open(path, &fp);
    if (status != GSL_SUCCESS) return status;
    status = whirl_scene_parse_stream(fp, path, overrides, n_overrides, scene);
    fclose(fp);
    return status;
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
