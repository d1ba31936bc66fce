/* The flat interface of the page build/web/whirl-explore.html (make web): what the page's
 * Worker calls in the library compiled to WebAssembly. Each call takes the page's state as the
 * query of its address ("length=60cm&mass=50g&rate=4Hz&mode=2"), reads it with the command
 * line's unit grammar (whirl_parse_quantity), computes with the library and answers one JSON
 * object, malloc'd (free it with whirl_web_free): the numbers in SI (m, kg, s, N) and the rates
 * in the unit the rate was given in (Hz, rpm, or rad/s for a bare number), each written in the
 * fewest digits that read back to the same double. A bad parameter or a failure answers
 * {"error": "one line", "field": "the parameter"} and nothing else. The page does no physics:
 * it draws these numbers.
 *
 * Parameters:
 *   length 1cm..100m, mass 0.1g..10t, tip (a point mass at the free end) 0..10t, default 0,
 *   links 0 (the continuum, default) or 2..400, rate 0.001..100000 in its unit and at most 200
 *   in the chain's units sqrt(g/L) (the live page's bound), mode 1..12 (and <= links), rmax (the
 *   top of the branch diagram and of the stability windows, in the rate's unit; default 3 rate),
 *   frame (the perturbed run's positions: rotating, the default, or inertial); for the runs
 *   drag (kg/(m s)) and drag2 (kg/m^2), for the shaken run pivot, shake, start and tilt
 *   (read_run_state).
 * The verdict of the continuum is that of the 30-link chain (VERDICT_LINKS), and so is its
 * perturbed run.
 *
 * Without OpenMP the branches run on the calling thread; the library's worker threads
 * (src/core/worker.c) are not started where threads cannot be (WebAssembly without
 * SharedArrayBuffer), and the work runs on the caller. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <gsl/gsl_math.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"
#include "whirl/periodic.h"
#include "whirl/stability.h"
#include "whirl/steady.h"
#include "web/whirl_web.h"

#define VERDICT_LINKS 30    /* the N-link chain whose linearisation gives the continuum's verdict */
#define MAX_LINKS 400       /* the live page's bound: a shape and its verdict within ~0.1 s */
#define MAX_MODE 12         /* the page's modes */
#define W_MAX 200.0         /* the highest rate the page computes live [sqrt(g/L)] */
#define CONTINUUM_POINTS 201 /* samples of the continuum's shape (whirl shape's default) */
#define BRANCH_RATES 120    /* rates of the branch diagram */
#define BRANCH_MODES 6      /* modes drawn on it at most */
#define WINDOWS_MAX 256     /* windows of one mode listed at most */
#define SHAKE_W_MAX 1000.0  /* the fastest pivot path the page computes live [sqrt(g/L)] */
#define SHAKE_WORK_MAX 5e7  /* the most link-steps of a shaken run (~30 s as WebAssembly) */
#define REACH_SAMPLES 256   /* times of a period where the path's reach is sampled */
#define QUERY_MAX 2048      /* the longest query read [bytes] */
#define PIVOT_MAX 256       /* the longest pivot path read [bytes] */

/* ---- the answer: a growing JSON text ---- */

typedef struct json {
    char *text;
    size_t len, cap;
    int failed; /* out of memory: the answer becomes NULL */
} json;

static void put(json *j, const char *fmt, ...)
{
    if (j->failed) return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        const int n = vsnprintf(j->text ? j->text + j->len : NULL, j->text ? j->cap - j->len : 0,
                                fmt, ap);
        va_end(ap);
        if (n < 0) {
            j->failed = 1;
            return;
        }
        if (j->text && j->len + (size_t)n < j->cap) {
            j->len += (size_t)n;
            return;
        }
        const size_t cap = 2 * (j->cap + (size_t)n) + 256;
        char *t = realloc(j->text, cap);
        if (t == NULL) {
            j->failed = 1;
            return;
        }
        j->text = t;
        j->cap = cap;
    }
}

/* A JSON string: quotes, backslashes and control characters escaped. */
static void put_string(json *j, const char *s)
{
    put(j, "\"");
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            put(j, "\\%c", c);
        else if (c < 0x20)
            put(j, "\\u%04x", c);
        else
            put(j, "%c", c);
    }
    put(j, "\"");
}

/* A number in the fewest digits that read back to it (whirl_format_double); null if not
 * finite (never expected: the library's results are checked finite). */
static void put_number(json *j, double x)
{
    char buf[32];
    if (isfinite(x))
        put(j, "%s", whirl_format_double(buf, x));
    else
        put(j, "null");
}

static void put_key_number(json *j, const char *key, double x)
{
    put(j, ",\"%s\":", key);
    put_number(j, x);
}

static void put_array(json *j, const char *key, const double *x, size_t n, double scale)
{
    put(j, ",\"%s\":[", key);
    for (size_t i = 0; i < n; i++) {
        if (i) put(j, ",");
        put_number(j, scale * x[i]);
    }
    put(j, "]");
}

static char *finish(json *j)
{
    if (j->failed) {
        free(j->text);
        return NULL;
    }
    return j->text;
}

static char *error_answer(const char *field, const char *message)
{
    json j = {0};
    put(&j, "{\"error\":");
    put_string(&j, message);
    put(&j, ",\"field\":");
    put_string(&j, field);
    put(&j, "}");
    return finish(&j);
}

/* ---- the state: the query read with the command line's units ---- */

typedef struct web_state {
    double length, mass, tip; /* [m, kg, kg] */
    int links, mode;
    double omega, rmax;       /* [rad/s] */
    double unit;              /* rad/s per unit of the rate as given */
    const char *unit_name;    /* "Hz", "rpm", "rad/s" */
    double time;              /* the library's unit of time sqrt(L/g) [s] */
    double w, w_max;          /* omega, rmax in sqrt(g/L) */
    double m_tip;             /* tip / mass */
    whirl_frame frame;        /* the run's view: co-rotating (default) or inertial */
    double drag, drag2;       /* the air drag of the runs, in the library's units */
    char pivot[PIVOT_MAX];    /* the shaken run's pivot path (whirl_pivot_parse), "" or "none" */
    double shake_w;           /* its rate [sqrt(g/L)] */
    int inverted;             /* the shaken run starts standing up (1) or hanging (0) */
    double tilt;              /* each link of its start turned by tilt [rad] */
    char field[16];           /* the parameter of a failure */
    char message[512];
} web_state;

static int state_fail(web_state *s, const char *field, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->message, sizeof s->message, fmt, ap);
    va_end(ap);
    snprintf(s->field, sizeof s->field, "%s", field);
    return -1;
}

/* %XX and + of a query value, in place */
static void url_decode(char *s)
{
    char *out = s;
    for (; *s; s++) {
        if (*s == '+')
            *out++ = ' ';
        else if (*s == '%' && s[1] && s[2] && strchr("0123456789abcdefABCDEF", s[1]) &&
                 strchr("0123456789abcdefABCDEF", s[2])) {
            const char hex[3] = {s[1], s[2], 0};
            *out++ = (char)strtol(hex, NULL, 16);
            s += 2;
        } else
            *out++ = *s;
    }
    *out = 0;
}

static int read_number(web_state *s, const char *name, const char *text, whirl_quantity kind,
                       double lo, double hi, double *out)
{
    if (whirl_parse_quantity(text, kind, out, NULL) != 0)
        return state_fail(s, name, "%s: not a number%s%s: %.40s", name,
                          kind == WHIRL_QUANTITY_NUMBER ? "" : " with a unit of ",
                          whirl_quantity_suffixes(kind), text);
    if (!(*out >= lo && *out <= hi))
        return state_fail(s, name, "%s: out of range [%g, %g]: %.40s", name, lo, hi, text);
    return 0;
}

static int read_int(web_state *s, const char *name, const char *text, int lo, int hi, int *out)
{
    char *end;
    const long v = strtol(text, &end, 10);
    if (end == text || *end != 0)
        return state_fail(s, name, "%s: not a whole number: %.40s", name, text);
    if (v < lo || v > hi)
        return state_fail(s, name, "%s: out of range %d..%d: %.40s", name, lo, hi, text);
    *out = (int)v;
    return 0;
}

/* The unit the rate was written in: its suffix, or rad/s for a bare number. */
static void rate_unit(web_state *s, const char *text)
{
    char *end;
    strtod(text, &end);
    while (*end == ' ') end++;
    if (strcasecmp(end, "hz") == 0)
        s->unit = 2 * M_PI, s->unit_name = "Hz";
    else if (strcasecmp(end, "rpm") == 0)
        s->unit = 2 * M_PI / 60, s->unit_name = "rpm";
    else
        s->unit = 1, s->unit_name = "rad/s";
}

static int library_fail(web_state *s, const char *field);

/* How far the pivot's path reaches from the origin [L]: the largest |p(t)| of REACH_SAMPLES
 * times in a period (a few terms: smooth, sampled finely enough for a bound on the page). */
static double pivot_reach(const whirl_pivot_path *path)
{
    double reach = 0, p[3], pv[3], pa[3];
    for (int i = 0; i < REACH_SAMPLES; i++) {
        whirl_pivot_eval(i * whirl_pivot_period(path) / REACH_SAMPLES, p, pv, pa,
                         (void *)path);
        reach = fmax(reach, hypot(hypot(p[0], p[1]), p[2]));
    }
    return reach;
}

/* The runs' parameters: the air drag (drag: linear, force -C v per unit length in
 * kg/(m s); drag2: quadratic, -C2 |v| v in kg/m^2; bare numbers in these units), and the
 * shaken run's pivot path (the command line's grammar, lengths in m or with a unit) at the rate
 * shake, its start (hanging or inverted) and tilt [degrees]. */
static int read_run_state(web_state *s, const char *drag, const char *drag2, const char *pivot,
                          const char *shake, const char *start, const char *tilt)
{
    double c = 0, c2 = 0, deg = 5, f = 0;
    if ((drag && read_number(s, "drag", drag, WHIRL_QUANTITY_NUMBER, 0, 1e3, &c)) ||
        (drag2 && read_number(s, "drag2", drag2, WHIRL_QUANTITY_NUMBER, 0, 1e3, &c2)) ||
        (tilt && read_number(s, "tilt", tilt, WHIRL_QUANTITY_NUMBER, -90, 90, &deg)))
        return -1;
    /* force per length per velocity [kg/(m s)] over M / (L T); per velocity squared over M / L^2 */
    s->drag = c * s->length * s->time / s->mass;
    s->drag2 = c2 * s->length * s->length / s->mass;
    s->tilt = deg * M_PI / 180;
    s->inverted = start && strcmp(start, "inverted") == 0;
    if (start && !s->inverted && strcmp(start, "hanging") != 0)
        return state_fail(s, "start", "start: hanging or inverted, got %.40s", start);
    if (pivot && strlen(pivot) >= PIVOT_MAX)
        return state_fail(s, "pivot", "pivot: longer than %d bytes", PIVOT_MAX - 1);
    snprintf(s->pivot, sizeof s->pivot, "%s", pivot && strcmp(pivot, "none") ? pivot : "");
    if (!s->pivot[0]) return 0;
    if (shake == NULL) return state_fail(s, "shake", "shake: missing (the path's rate, e.g. 30Hz)");
    char *end;
    strtod(shake, &end);
    const int bare = !strpbrk(end, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ");
    if (read_number(s, "shake", shake, WHIRL_QUANTITY_RATE, 1e-3 * s->unit, 1e5 * s->unit, &f))
        return -1;
    if (bare) f *= s->unit; /* a bare shake rate is in the rate's unit */
    s->shake_w = f * s->time;
    if (s->shake_w > SHAKE_W_MAX)
        return state_fail(s, "shake", "shake: above %.4g %s, beyond what the page computes live",
                          SHAKE_W_MAX / s->time / s->unit, s->unit_name);
    whirl_pivot_path path;
    if (whirl_pivot_parse(s->pivot, s->shake_w, s->length, 3, &path) != GSL_SUCCESS)
        return library_fail(s, "pivot");
    if (pivot_reach(&path) > 1)
        return state_fail(s, "pivot", "pivot: the path reaches farther than the chain's length");
    return 0;
}

static int read_state(web_state *s, const char *query)
{
    memset(s, 0, sizeof *s);
    if (query == NULL) return state_fail(s, "", "no query");
    if (strlen(query) > QUERY_MAX)
        return state_fail(s, "", "the query is longer than %d bytes", QUERY_MAX);
    char copy[QUERY_MAX + 1];
    strcpy(copy, query);
    const char *length = NULL, *mass = NULL, *tip = NULL, *links = NULL, *rate = NULL,
               *mode = NULL, *rmax = NULL, *frame = NULL, *drag = NULL, *drag2 = NULL,
               *pivot = NULL, *shake = NULL, *start = NULL, *tilt = NULL;
    for (char *save = NULL, *p = strtok_r(copy, "&", &save); p; p = strtok_r(NULL, "&", &save)) {
        char *eq = strchr(p, '=');
        if (eq == NULL) return state_fail(s, p, "%.40s: a parameter without a value", p);
        *eq = 0;
        url_decode(p);
        url_decode(eq + 1);
        const char **slot = strcmp(p, "length") == 0 ? &length
                            : strcmp(p, "mass") == 0 ? &mass
                            : strcmp(p, "tip") == 0  ? &tip
                            : strcmp(p, "links") == 0 ? &links
                            : strcmp(p, "rate") == 0 ? &rate
                            : strcmp(p, "mode") == 0 ? &mode
                            : strcmp(p, "rmax") == 0 ? &rmax
                            : strcmp(p, "frame") == 0 ? &frame
                            : strcmp(p, "drag") == 0 ? &drag
                            : strcmp(p, "drag2") == 0 ? &drag2
                            : strcmp(p, "pivot") == 0 ? &pivot
                            : strcmp(p, "shake") == 0 ? &shake
                            : strcmp(p, "start") == 0 ? &start
                            : strcmp(p, "tilt") == 0 ? &tilt
                                                     : NULL;
        if (slot == NULL)
            return state_fail(s, p, "unknown parameter %.40s (length, mass, tip, links, rate, "
                                    "mode, rmax, frame, drag, drag2, pivot, shake, start, tilt)",
                              p);
        *slot = eq + 1;
    }
    if (length == NULL) return state_fail(s, "length", "length: missing (e.g. length=60cm)");
    if (mass == NULL) return state_fail(s, "mass", "mass: missing (e.g. mass=50g)");
    if (rate == NULL) return state_fail(s, "rate", "rate: missing (e.g. rate=4Hz)");
    if (mode == NULL) return state_fail(s, "mode", "mode: missing (e.g. mode=2)");
    /* the page's bounds: a shape and its verdict within ~0.1 s */
    if (read_number(s, "length", length, WHIRL_QUANTITY_LENGTH, 0.01, 100, &s->length) ||
        read_number(s, "mass", mass, WHIRL_QUANTITY_MASS, 1e-4, 1e4, &s->mass) ||
        (tip && read_number(s, "tip", tip, WHIRL_QUANTITY_MASS, 0, 1e4, &s->tip)) ||
        (links && read_int(s, "links", links, 0, MAX_LINKS, &s->links)) ||
        read_int(s, "mode", mode, 1, MAX_MODE, &s->mode))
        return -1;
    if (s->links == 1)
        return state_fail(s, "links", "links: 0 (the continuum) or 2..%d", MAX_LINKS);
    if (s->links && s->mode > s->links)
        return state_fail(s, "mode", "mode %d needs at least %d links", s->mode, s->mode);
    rate_unit(s, rate);
    if (read_number(s, "rate", rate, WHIRL_QUANTITY_RATE, 1e-3 * s->unit, 1e5 * s->unit, &s->omega))
        return -1;
    s->time = sqrt(s->length / WHIRL_STANDARD_GRAVITY);
    s->w = s->omega * s->time;
    if (s->w > W_MAX)
        return state_fail(s, "rate", "rate above %.4g %s: beyond what the page computes live",
                          W_MAX / s->time / s->unit, s->unit_name);
    s->rmax = 3 * s->omega;
    if (rmax && read_number(s, "rmax", rmax, WHIRL_QUANTITY_RATE, 1e-3 * s->unit, 1e5 * s->unit,
                            &s->rmax))
        return -1;
    if (rmax && !strpbrk(rmax, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"))
        s->rmax *= s->unit; /* a bare rmax is in the rate's unit */
    s->w_max = fmin(s->rmax * s->time, W_MAX);
    s->m_tip = s->tip / s->mass;
    s->frame = WHIRL_FRAME_ROTATING;
    if (frame && strcmp(frame, "inertial") == 0)
        s->frame = WHIRL_FRAME_INERTIAL;
    else if (frame && strcmp(frame, "rotating") != 0)
        return state_fail(s, "frame", "frame: rotating or inertial, got %.40s", frame);
    return read_run_state(s, drag, drag2, pivot, shake, start, tilt);
}

/* The library's last failure with its quantities in SI, as the state's failure. */
static int library_fail(web_state *s, const char *field)
{
    char buf[512];
    whirl_last_error_in_units(buf, sizeof buf, 1, s->length, s->mass, WHIRL_STANDARD_GRAVITY,
                              strcmp(s->unit_name, "Hz") == 0);
    return state_fail(s, field, "%s", buf);
}

/* The rate where mode k is born on the hanging chain [sqrt(g/L)]: the chain's critical rate. */
static int birth(web_state *s, const whirl_chain *c, int mode, double *w)
{
    double crit[MAX_MODE];
    const int status = c ? whirl_nlink_critical(c, (size_t)mode, crit)
                         : whirl_continuum_critical_rates((size_t)mode, s->m_tip, crit);
    if (status != GSL_SUCCESS) return library_fail(s, "mode");
    *w = crit[mode - 1];
    return 0;
}

/* The chain of n links with the state's tip mass (in chain masses). */
static whirl_chain *chain_of(web_state *s, int n)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)n, s->m_tip);
    if (c == NULL) library_fail(s, "links");
    return c;
}

/* The linear verdict of the shape of the state's mode on the chain c: whirl stability --linear. */
static int verdict(web_state *s, const whirl_chain *c, json *j)
{
    whirl_stability *ws = whirl_stability_alloc(c->n);
    if (ws == NULL) return library_fail(s, "links");
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = s->w};
    double growth = 0;
    int index = 0;
    int status = whirl_stability_mode(ws, &m, s->mode, NULL, &growth);
    if (status == GSL_SUCCESS) status = whirl_stability_index(ws, &index);
    whirl_stability_free(ws);
    if (status != GSL_SUCCESS) return library_fail(s, "rate");
    put(j, ",\"verdict\":");
    put_string(j, whirl_verdict_name(whirl_verdict_linear(growth, index)));
    put(j, ",\"verdict_links\":%zu,\"index\":%d", c->n, index);
    put_key_number(j, "growth", growth / s->time);
    return 0;
}

char *whirl_web_shape(const char *query)
{
    web_state s;
    if (read_state(&s, query)) return error_answer(s.field, s.message);
    const size_t n = s.links ? (size_t)s.links + 1 : CONTINUUM_POINTS;
    whirl_chain *c = s.links ? chain_of(&s, s.links) : NULL;
    whirl_chain *vc = chain_of(&s, s.links ? s.links : VERDICT_LINKS);
    double *buf = malloc(4 * n * sizeof *buf);
    json j = {0};
    double born = 0;
    int failed = (s.links && c == NULL) || vc == NULL || buf == NULL ||
                 birth(&s, c, s.mode, &born) != 0;
    if (buf == NULL) state_fail(&s, "", "out of memory");
    whirl_shape_info info = {0};
    double *r = buf, *z = buf + n, *t = buf + 2 * n, *arc = buf + 3 * n;
    if (!failed) {
        int status = c ? whirl_nlink_solve_nodes(c, s.w, s.mode, &info, r, z, t)
                       : whirl_continuum_solve(s.w, s.mode, s.m_tip, 0, &info);
        if (status == GSL_SUCCESS && c == NULL)
            status = whirl_continuum_sample(s.w, s.m_tip, info.tip_r, n, arc, r, z, t);
        if (status == GSL_EDOM && s.w < born) { /* below the birth: the hanging chain */
            put(&j, "{\"hanging\":true,\"message\":\"mode %d is born at %.4g %s: below it the "
                    "chain hangs straight down\"", s.mode, born / s.time / s.unit, s.unit_name);
        } else if (status != GSL_SUCCESS)
            failed = library_fail(&s, "rate");
        else {
            put(&j, "{\"hanging\":false");
            put_array(&j, "x", r, n, s.length);
            put_array(&j, "z", z, n, s.length);
            put_array(&j, "tension", t, n, s.mass * WHIRL_STANDARD_GRAVITY);
            put_key_number(&j, "tip_r", fabs(info.tip_r) * s.length);
            put_key_number(&j, "top_tension", info.top_tension * s.mass * WHIRL_STANDARD_GRAVITY);
            put(&j, ",\"node_count\":%d", info.n_nodes + 1);
        }
    }
    if (!failed) {
        put(&j, ",\"unit\":");
        put_string(&j, s.unit_name);
        put_key_number(&j, "rate", s.omega / s.unit);
        put_key_number(&j, "omega", s.omega);
        put_key_number(&j, "period", 2 * M_PI / s.omega);
        put_key_number(&j, "born", born / s.time / s.unit);
        put_key_number(&j, "length", s.length);
        put(&j, ",\"mode\":%d,\"links\":%d", s.mode, s.links);
        if (s.w > born && vc->n >= (size_t)s.mode && verdict(&s, vc, &j) != 0) {
            /* the verdict's chain (30 links for the continuum) may be born later: said, not
             * failed */
            put(&j, ",\"verdict_error\":");
            put_string(&j, s.message);
        }
        put(&j, "}");
    }
    free(buf);
    whirl_chain_free(c);
    whirl_chain_free(vc);
    if (failed) {
        free(j.text);
        return error_answer(s.field, s.message);
    }
    return finish(&j);
}

char *whirl_web_branches(const char *query)
{
    web_state s;
    if (read_state(&s, query)) return error_answer(s.field, s.message);
    whirl_chain *c = s.links ? chain_of(&s, s.links) : NULL;
    const int top = s.links && s.links < MAX_MODE ? s.links : MAX_MODE;
    double crit[MAX_MODE], w[BRANCH_RATES];
    whirl_shape_info *info = malloc(BRANCH_RATES * sizeof *info);
    int exists[BRANCH_RATES];
    json j = {0};
    int failed = (s.links && c == NULL) || info == NULL;
    if (!failed && (c ? whirl_nlink_critical(c, (size_t)top, crit)
                      : whirl_continuum_critical_rates((size_t)top, s.m_tip, crit)) != GSL_SUCCESS)
        failed = library_fail(&s, "mode");
    if (info == NULL) state_fail(&s, "", "out of memory");
    for (int i = 0; i < BRANCH_RATES; i++) w[i] = s.w_max * (i + 1) / BRANCH_RATES;
    put(&j, "{\"unit\":");
    put_string(&j, s.unit_name);
    put_key_number(&j, "rate_max", s.w_max / s.time / s.unit);
    put(&j, ",\"modes\":[");
    for (int k = 1, drawn = 0; !failed && k <= top && drawn < BRANCH_MODES; k++) {
        if (!(crit[k - 1] < s.w_max)) continue;
        const int status = c ? whirl_nlink_branch(c, k, BRANCH_RATES, w, info, exists)
                             : whirl_continuum_branch(k, s.m_tip, BRANCH_RATES, w, info, exists);
        if (status != GSL_SUCCESS) {
            failed = library_fail(&s, "rmax");
            break;
        }
        /* each branch from its birth on the hanging chain (tip radius 0) */
        put(&j, "%s{\"mode\":%d", drawn++ ? "," : "", k);
        put_key_number(&j, "born", crit[k - 1] / s.time / s.unit);
        put(&j, ",\"rate\":[");
        put_number(&j, crit[k - 1] / s.time / s.unit);
        for (int i = 0; i < BRANCH_RATES; i++)
            if (exists[i]) put(&j, ","), put_number(&j, w[i] / s.time / s.unit);
        put(&j, "],\"tip_r\":[0");
        for (int i = 0; i < BRANCH_RATES; i++)
            if (exists[i]) put(&j, ","), put_number(&j, fabs(info[i].tip_r) * s.length);
        put(&j, "]}");
    }
    put(&j, "]}");
    free(info);
    whirl_chain_free(c);
    if (failed) {
        free(j.text);
        return error_answer(s.field, s.message);
    }
    return finish(&j);
}

char *whirl_web_windows(const char *query)
{
    web_state s;
    if (read_state(&s, query)) return error_answer(s.field, s.message);
    const int links = s.links ? s.links : VERDICT_LINKS;
    json j = {0};
    put(&j, "{\"mode\":%d,\"links\":%d,\"unit\":", s.mode, links);
    put_string(&j, s.unit_name);
    put(&j, ",\"windows\":[");
    int failed = 0;
    if (s.mode >= 2 && s.mode <= links) { /* mode 1: a minimum of the amended potential */
        whirl_chain *c = chain_of(&s, links);
        whirl_windows *ws = c ? whirl_windows_alloc(c->n) : NULL;
        whirl_window *found = malloc(WINDOWS_MAX * sizeof *found);
        double lo = 0;
        if (c != NULL && (ws == NULL || found == NULL)) state_fail(&s, "", "out of memory");
        failed = c == NULL || ws == NULL || found == NULL || birth(&s, c, s.mode, &lo) != 0;
        /* from just above the birth: the branch leaves the hanging chain there */
        lo *= 1 + 1e-4;
        if (!failed && lo < s.w_max) {
            whirl_windows_params p = whirl_windows_defaults();
            p.omega_min = lo;
            p.omega_max = s.w_max;
            size_t count = 0;
            whirl_windows_stats st;
            if (whirl_windows_find(ws, c, s.mode, &p, found, WINDOWS_MAX, &count, &st) !=
                GSL_SUCCESS)
                failed = library_fail(&s, "rmax");
            for (size_t i = 0; !failed && i < count; i++) {
                put(&j, "%s[", i ? "," : "");
                put_number(&j, found[i].from / s.time / s.unit);
                put(&j, ",");
                put_number(&j, found[i].to / s.time / s.unit);
                put(&j, ",");
                put_number(&j, found[i].max_growth / s.time);
                put(&j, "]");
            }
        }
        free(found);
        whirl_windows_free(ws);
        whirl_chain_free(c);
    }
    put(&j, "]}");
    if (failed) {
        free(j.text);
        return error_answer(s.field, s.message);
    }
    return finish(&j);
}

/* ---- the perturbed run: the state's chain seeded with its steady shape, each link turned by
 * RUN_PERTURB (whirl_perturb_links, seed 1: the command line's [start] perturb), integrated by
 * gauss2 in the co-rotating frame for RUN_PERIODS rotation periods at the library's default step
 * (whirl_default_step, shortened to divide a frame's time), RUN_FRAMES frames ---- */

#define RUN_PERIODS 40
#define RUN_FRAMES 400
#define RUN_PERTURB 1e-3 /* [rad] */
#define SHAKE_FRAMES 800     /* the shaken run's frames after the start */
#define SHAKE_PER_PERIOD 8   /* its frames per period of the path */
#define SHAKE_FREE 10        /* its frames per time unit sqrt(L/g) without a path */

struct whirl_web_run {
    web_state s;
    whirl_chain *c;
    whirl_dyn *d;
    whirl_integrator *it;
    whirl_pivot_path path;   /* the shaken run's pivot path */
    int shaken, moving;      /* a shaken run (whirl_web_shake_alloc); its pivot moves */
    int total;               /* frames in all, the start's included */
    double *y, *x, *v, *ref; /* the state; positions, velocities, the unperturbed positions */
    double t, every, dt;     /* [sqrt(L/g)] */
    int frames;              /* written so far (frame 0 is the start) */
    int failed;              /* the start or a step failed: s.field and s.message say why */
};

/* The unperturbed steady shape's links, the reference positions, then the perturbed start. */
static int run_start(whirl_web_run *r)
{
    web_state *s = &r->s;
    const size_t n = r->c->n;
    double *buf = malloc(3 * (n + 1) * sizeof *buf), *links = malloc(3 * n * sizeof *links);
    whirl_shape_info info;
    double h = 0;
    int status = buf && links ? GSL_SUCCESS : GSL_ENOMEM;
    if (status == GSL_SUCCESS)
        status = whirl_nlink_solve_nodes(r->c, s->w, s->mode, &info, buf, buf + n + 1,
                                         buf + 2 * (n + 1));
    if (status == GSL_SUCCESS) status = whirl_shape_links(n, buf, NULL, buf + n + 1, links);
    if (status == GSL_SUCCESS) status = whirl_dyn_state_from_shape(r->d, 0, links, s->w, r->y);
    if (status == GSL_SUCCESS)
        status = whirl_dyn_get_state(r->d, 0, r->y, WHIRL_FRAME_INERTIAL, r->ref, r->v);
    if (status == GSL_SUCCESS) status = whirl_perturb_links(n, links, RUN_PERTURB, 1);
    if (status == GSL_SUCCESS) status = whirl_dyn_state_from_shape(r->d, 0, links, s->w, r->y);
    /* the default step from the shape's link tensions (buf + 2 (n + 1) + 1: links 1..n) */
    if (status == GSL_SUCCESS)
        status = whirl_default_step(whirl_dyn_model(r->d), buf + 2 * (n + 1) + 1, "gauss2", &h);
    free(buf);
    free(links);
    if (status == GSL_ENOMEM) return state_fail(s, "", "out of memory");
    if (status != GSL_SUCCESS) return library_fail(s, "rate");
    r->every = RUN_PERIODS * 2 * M_PI / s->w / RUN_FRAMES;
    r->dt = r->every / ceil(r->every / h);
    return 0;
}

/* The run's dynamics of the model m, its pivot on r->path if it moves, gauss2 and the buffers. */
static int run_workspace(whirl_web_run *r, const whirl_model *m)
{
    web_state *s = &r->s;
    r->d = whirl_dyn_alloc(m, WHIRL_FORMULATION_CARTESIAN);
    if (r->d && r->moving && whirl_dyn_set_pivot(r->d, whirl_pivot_eval, &r->path) != GSL_SUCCESS)
        return library_fail(s, "pivot");
    /* gauss2 by its type, not by its name: the table of every method would bring GSL's ODE
     * solvers into the page (50 kB of WebAssembly it does not use) */
    whirl_system sys;
    r->it = r->d && whirl_dyn_system(r->d, &sys) == GSL_SUCCESS
                ? whirl_integrator_alloc_system(whirl_integrator_gauss2, &sys)
                : NULL;
    const size_t n = r->c->n;
    if (r->it == NULL) return library_fail(s, "links");
    r->y = malloc(whirl_dyn_size(r->d) * sizeof *r->y);
    r->x = malloc(9 * n * sizeof *r->x);
    if (r->y == NULL || r->x == NULL) return state_fail(s, "", "out of memory");
    r->v = r->x + 3 * n;
    r->ref = r->x + 6 * n;
    return 0;
}

whirl_web_run *whirl_web_run_alloc(const char *query)
{
    whirl_web_run *r = calloc(1, sizeof *r);
    if (r == NULL) return NULL;
    web_state *s = &r->s;
    r->total = RUN_FRAMES + 1;
    if (read_state(s, query)) {
        r->failed = 1;
        return r;
    }
    double born = 0;
    r->c = chain_of(s, s->links ? s->links : VERDICT_LINKS);
    if (r->c == NULL || birth(s, r->c, s->mode, &born) != 0) {
        r->failed = 1;
        return r;
    }
    if (!(s->w > born)) {
        state_fail(s, "rate", "mode %d is born at %.4g %s: below it there is no shape to perturb",
                   s->mode, born / s->time / s->unit, s->unit_name);
        r->failed = 1;
        return r;
    }
    const whirl_model m = {.chain = r->c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = s->w,
                           .air_drag = s->drag, .air_drag_quadratic = s->drag2};
    r->failed = run_workspace(r, &m) != 0 || run_start(r) != 0;
    return r;
}

/* The shaken run's start: the chain straight down or up, each link turned by the tilt about y,
 * moving with the pivot; the step: whirl_default_step's under the tensions of the chain
 * hanging in the gravity raised by the pivot's largest acceleration (a bound in either
 * start); a frame every SHAKE_PER_PERIOD of the path's period (SHAKE_FREE of a time unit
 * sqrt(L/g) without a path). */
static int shake_start(whirl_web_run *r)
{
    web_state *s = &r->s;
    const size_t n = r->c->n;
    double *links = malloc(3 * n * sizeof *links), *tension = malloc(n * sizeof *tension);
    double amax = 0, h = 0;
    for (int j = 0; r->moving && j < r->path.harmonics; j++) {
        double a2 = 0;
        for (int k = 0; k < 3; k++) a2 += gsl_pow_2(r->path.c[k][j]) + gsl_pow_2(r->path.s[k][j]);
        amax += sqrt(a2) * gsl_pow_2((j + 1) * r->path.omega);
    }
    int status = links && tension ? GSL_SUCCESS : GSL_ENOMEM;
    double below = 0;
    for (size_t i = n; status == GSL_SUCCESS && i-- > 0;) {
        const double l = r->c->length[i];
        links[3 * i] = l * sin(s->tilt);
        links[3 * i + 1] = 0;
        links[3 * i + 2] = (s->inverted ? 1 : -1) * l * cos(s->tilt);
        below += r->c->mass[i];
        tension[i] = (r->c->gravity + amax) * below;
    }
    if (status == GSL_SUCCESS) status = whirl_dyn_state_from_shape(r->d, 0, links, 0, r->y);
    if (status == GSL_SUCCESS)
        status = whirl_default_step(whirl_dyn_model(r->d), tension, "gauss2", &h);
    free(links);
    free(tension);
    if (status == GSL_ENOMEM) return state_fail(s, "", "out of memory");
    if (status != GSL_SUCCESS) return library_fail(s, r->moving ? "shake" : "links");
    r->every = r->moving ? whirl_pivot_period(&r->path) / SHAKE_PER_PERIOD : 1.0 / SHAKE_FREE;
    const double steps = ceil(r->every / h) * SHAKE_FRAMES;
    if (steps * (double)n > SHAKE_WORK_MAX)
        return state_fail(s, "shake", "shake: %zu links on this path need %.3g steps, beyond "
                          "what the page computes live (fewer links, a smaller amplitude or "
                          "frequency)", n, steps);
    r->dt = r->every / ceil(r->every / h);
    return 0;
}

whirl_web_run *whirl_web_shake_alloc(const char *query)
{
    whirl_web_run *r = calloc(1, sizeof *r);
    if (r == NULL) return NULL;
    web_state *s = &r->s;
    r->shaken = 1;
    r->total = SHAKE_FRAMES + 1;
    if (read_state(s, query)) {
        r->failed = 1;
        return r;
    }
    r->moving = s->pivot[0] != 0;
    if (r->moving && whirl_pivot_parse(s->pivot, s->shake_w, s->length, 3, &r->path)) {
        r->failed = library_fail(s, "pivot");
        return r;
    }
    r->c = chain_of(s, s->links ? s->links : VERDICT_LINKS);
    /* omega: the path's (whirl_default_step's period), 1 without a path */
    const whirl_model m = {.chain = r->c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL,
                           .omega = r->moving ? s->shake_w : 1, .air_drag = s->drag,
                           .air_drag_quadratic = s->drag2};
    r->failed = r->c == NULL || run_workspace(r, &m) != 0 || shake_start(r) != 0;
    return r;
}

/* One frame at r->t (the chunk's first: no comma before it): t [s]; the deviation from the
 * unperturbed shape [m] (whirl_deviation: the RMS distance, minimised over a turn about the
 * axis), or for a shaken run the tip's height above the pivot [m] and the pivot's position;
 * then the masses' positions x, y, z [m] (7 digits: they are drawn) in the run's frame. */
static int run_frame(whirl_web_run *r, json *j, int first)
{
    const size_t n = r->c->n;
    double p[3] = {0, 0, 0}, pv[3], pa[3];
    int status = whirl_dyn_get_state(r->d, r->t, r->y, WHIRL_FRAME_INERTIAL, r->x, r->v);
    if (r->moving) whirl_pivot_eval(r->t, p, pv, pa, &r->path);
    const double dev = status != GSL_SUCCESS ? NAN
                       : r->shaken           ? r->x[3 * n - 1] - p[2]
                                             : whirl_deviation(n, r->x, r->ref);
    if (status == GSL_SUCCESS && !r->shaken && r->s.frame != WHIRL_FRAME_INERTIAL)
        status = whirl_dyn_get_state(r->d, r->t, r->y, r->s.frame, r->x, r->v);
    if (status != GSL_SUCCESS || !isfinite(dev))
        return library_fail(&r->s, r->shaken ? "shake" : "rate");
    put(j, "%s[", first ? "" : ",");
    put_number(j, r->t * r->s.time);
    put(j, ",");
    put_number(j, dev * r->s.length);
    for (int k = 0; r->shaken && k < 3; k++) put(j, ",%.7g", p[k] * r->s.length);
    for (size_t i = 0; i < 3 * n; i++) put(j, ",%.7g", r->x[i] * r->s.length);
    put(j, "]");
    r->frames++;
    return 0;
}

char *whirl_web_run_next(whirl_web_run *r, int count)
{
    if (r == NULL) return error_answer("", "no run");
    web_state *s = &r->s;
    const int last = r->total - 1;
    json j = {0};
    put(&j, "{\"links\":%zu,\"total\":%d", r->c ? r->c->n : 0, r->total);
    put_key_number(&j, "t_end", r->shaken ? last * r->every * s->time
                                          : RUN_PERIODS * 2 * M_PI / s->omega);
    const double period = !r->shaken ? 2 * M_PI / s->omega
                          : r->moving ? whirl_pivot_period(&r->path) * s->time
                                      : 0; /* a free swing: none */
    put_key_number(&j, "period", period);
    put_key_number(&j, "dt", r->dt * s->time);
    put(&j, ",\"steps\":%.0f", r->every > 0 ? round(r->every / r->dt) : 0);
    put(&j, ",\"frame\":\"%s\",\"shaken\":%s,\"frames\":[",
        r->shaken || s->frame == WHIRL_FRAME_INERTIAL ? "inertial" : "rotating",
        r->shaken ? "true" : "false");
    const int first = r->frames;
    while (!r->failed && r->frames - first < count && r->frames <= last) {
        if (r->frames > 0) { /* frame k at k every */
            if (whirl_integrator_advance(r->it, &r->t, r->y, r->frames * r->every, r->dt, 0) !=
                GSL_SUCCESS) {
                r->failed = library_fail(s, r->shaken ? "shake" : "rate");
                break;
            }
        }
        r->failed = run_frame(r, &j, r->frames == first) != 0;
    }
    put(&j, "],\"done\":%s}", r->frames > last ? "true" : "false");
    if (r->failed) {
        free(j.text);
        return error_answer(s->field, s->message);
    }
    return finish(&j);
}

void whirl_web_run_free(whirl_web_run *r)
{
    if (r == NULL) return;
    whirl_integrator_free(r->it);
    whirl_dyn_free(r->d);
    whirl_chain_free(r->c);
    free(r->y);
    free(r->x);
    free(r);
}

void whirl_web_free(char *answer) { free(answer); }
