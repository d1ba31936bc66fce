/* Scenes, the second pass (see scene.c): every value converted to its type and checked, and the
 * rules that tie keys together, so that each message names the key's line. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "whirl/scene.h"
#include "whirl/common.h"
#include "core/error.h"
#include "core/input.h"
#include "studies/scene_internal.h"

/* ---- second pass: typed values ---- */

static const char *const column_names[WHIRL_NCOLUMNS] = {
    "t", "tip_x", "tip_y", "tip_z", "energy", "jacobi", "lz", "constraint", "deviation"};

const char *whirl_column_name(whirl_column c)
{
    return (c >= 0 && c < WHIRL_NCOLUMNS) ? column_names[c] : NULL;
}

const char *whirl_scene_where(const whirl_scene *scene, whirl_scene_key key, char *buf,
                              size_t size)
{
    if ((int)key < 0 || (int)key >= WHIRL_SCENE_NKEYS) {
        snprintf(buf, size, "%s: no key %d", scene->path, (int)key);
        return buf;
    }
    return sc_where(scene, key, scene->line[key], buf, size);
}

const char *sc_where(const whirl_scene *scene, int key, int line, char *buf, size_t size)
{
    const char *sec = sc_section_names[sc_key_names[key].section], *name = sc_key_names[key].name;
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
    return whirl_fail(GSL_EINVAL, "%s: %s",
                      sc_where(v->scene, key, v->line[key], where, sizeof where), msg);
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
    const whirl_quantity kind = sc_key_names[key].kind;
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
    if (parse_number(v->raw[key], sc_key_names[key].kind, out, &suffixed) != 0)
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
    char *item = sc_copy_string(text);
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
        char *t = sc_trim(p);
        char words[80];
        int suffixed = 0;
        if (parse_number(t, sc_key_names[key].kind, &x[i], &suffixed) != 0)
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
                     "%s", text, dimensionless_unit(sc_key_names[key].kind));
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

int sc_convert_units(const convert *v)
{
    static const char *const systems[] = {"dimensionless", "SI"};
    return get_word(v, WHIRL_KEY_UNITS_SYSTEM, systems, 2, 0, &v->scene->physical);
}

/* The scalar key or the list key of the chain, not both. */
static int one_of(const convert *v, whirl_scene_key scalar, whirl_scene_key list)
{
    if (given(v, scalar) && given(v, list))
        return key_error(v, scalar, "conflicts with [chain] %s: give the chain's %s or the list "
                         "of N values", sc_key_names[list].name, sc_key_names[scalar].name);
    return GSL_SUCCESS;
}

int sc_convert_chain(const convert *v)
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

int sc_convert_start(const convert *v)
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
                             "theta, or hanging)", sc_key_names[first].name, at);
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

int sc_convert_run(const convert *v)
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
    if ((s->method = sc_copy_string(method)) == NULL)
        return whirl_fail(GSL_ENOMEM, "out of memory");
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
    char *list = sc_copy_string(v->raw[WHIRL_KEY_OUTPUT_COLUMNS]);
    if (list == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = GSL_SUCCESS;
    char *p = list;
    while (status == GSL_SUCCESS) {
        char *comma = strchr(p, ',');
        if (comma) *comma = '\0';
        char *name = sc_trim(p);
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
        if ((*out = sc_copy_string(value)) == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
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

int sc_convert_output(const convert *v)
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
