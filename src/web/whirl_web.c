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
 * SharedArrayBuffer), and the work runs on the caller. The runs in time (whirl_web_run_*,
 * whirl_web_shake_alloc) are in web_run.c, the Floquet multipliers of the shaken settings
 * (whirl_web_floquet) in web_floquet.c, what the files share in web_internal.h. */
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
#include "web/web_internal.h"

#define MAX_LINKS 400       /* the live page's bound: a shape and its verdict within ~0.1 s */
#define MAX_MODE 12         /* the page's modes */
#define W_MAX 200.0         /* the highest rate the page computes live [sqrt(g/L)] */
#define CONTINUUM_POINTS 201 /* samples of the continuum's shape (whirl shape's default) */
#define BRANCH_RATES 120    /* rates of the branch diagram */
#define BRANCH_MODES 6      /* modes drawn on it at most */
#define WINDOWS_MAX 256     /* windows of one mode listed at most */
#define SHAKE_W_MAX 1000.0  /* the fastest pivot path the page computes live [sqrt(g/L)] */
#define REACH_SAMPLES 256   /* times of a period where the path's reach is sampled */
#define QUERY_MAX 2048      /* the longest query read [bytes] */

/* ---- the answer: a growing JSON text (web_internal.h) ---- */

void web_put(json *j, const char *fmt, ...)
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
void web_put_string(json *j, const char *s)
{
    web_put(j, "\"");
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            web_put(j, "\\%c", c);
        else if (c < 0x20)
            web_put(j, "\\u%04x", c);
        else
            web_put(j, "%c", c);
    }
    web_put(j, "\"");
}

/* A number in the fewest digits that read back to it (whirl_format_double); null if not
 * finite (never expected: the library's results are checked finite). */
void web_put_number(json *j, double x)
{
    char buf[32];
    if (isfinite(x))
        web_put(j, "%s", whirl_format_double(buf, x));
    else
        web_put(j, "null");
}

void web_put_key_number(json *j, const char *key, double x)
{
    web_put(j, ",\"%s\":", key);
    web_put_number(j, x);
}

static void put_array(json *j, const char *key, const double *x, size_t n, double scale)
{
    web_put(j, ",\"%s\":[", key);
    for (size_t i = 0; i < n; i++) {
        if (i) web_put(j, ",");
        web_put_number(j, scale * x[i]);
    }
    web_put(j, "]");
}

char *web_finish(json *j)
{
    if (j->failed) {
        free(j->text);
        return NULL;
    }
    return j->text;
}

char *web_error_answer(const char *field, const char *message)
{
    json j = {0};
    web_put(&j, "{\"error\":");
    web_put_string(&j, message);
    web_put(&j, ",\"field\":");
    web_put_string(&j, field);
    web_put(&j, "}");
    return web_finish(&j);
}

/* ---- the state: the query read with the command line's units (web_internal.h) ---- */

int web_state_fail(web_state *s, const char *field, const char *fmt, ...)
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
        return web_state_fail(s, name, "%s: not a number%s%s: %.40s", name,
                          kind == WHIRL_QUANTITY_NUMBER ? "" : " with a unit of ",
                          whirl_quantity_suffixes(kind), text);
    if (!(*out >= lo && *out <= hi))
        return web_state_fail(s, name, "%s: out of range [%g, %g]: %.40s", name, lo, hi, text);
    return 0;
}

static int read_int(web_state *s, const char *name, const char *text, int lo, int hi, int *out)
{
    char *end;
    const long v = strtol(text, &end, 10);
    if (end == text || *end != 0)
        return web_state_fail(s, name, "%s: not a whole number: %.40s", name, text);
    if (v < lo || v > hi)
        return web_state_fail(s, name, "%s: out of range %d..%d: %.40s", name, lo, hi, text);
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
    s->drag_si = c;
    s->drag2_si = c2;
    s->tilt = deg * M_PI / 180;
    s->inverted = start && strcmp(start, "inverted") == 0;
    if (start && !s->inverted && strcmp(start, "hanging") != 0)
        return web_state_fail(s, "start", "start: hanging or inverted, got %.40s", start);
    if (pivot && strlen(pivot) >= PIVOT_MAX)
        return web_state_fail(s, "pivot", "pivot: longer than %d bytes", PIVOT_MAX - 1);
    snprintf(s->pivot, sizeof s->pivot, "%s", pivot && strcmp(pivot, "none") ? pivot : "");
    if (!s->pivot[0]) return 0;
    if (shake == NULL) return web_state_fail(s, "shake", "shake: missing (the path's rate, e.g. 30Hz)");
    char *end;
    strtod(shake, &end);
    const int bare = !strpbrk(end, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ");
    if (read_number(s, "shake", shake, WHIRL_QUANTITY_RATE, 1e-3 * s->unit, 1e5 * s->unit, &f))
        return -1;
    if (bare) f *= s->unit; /* a bare shake rate is in the rate's unit */
    s->shake_omega = f;
    s->shake_w = f * s->time;
    if (s->shake_w > SHAKE_W_MAX)
        return web_state_fail(s, "shake", "shake: above %.4g %s, beyond what the page computes live",
                          SHAKE_W_MAX / s->time / s->unit, s->unit_name);
    whirl_pivot_path path;
    if (whirl_pivot_parse(s->pivot, s->shake_w, s->length, 3, &path) != GSL_SUCCESS)
        return web_library_fail(s, "pivot");
    if (pivot_reach(&path) > 1)
        return web_state_fail(s, "pivot", "pivot: the path reaches farther than the chain's length");
    return 0;
}

int web_read_state(web_state *s, const char *query)
{
    memset(s, 0, sizeof *s);
    if (query == NULL) return web_state_fail(s, "", "no query");
    if (strlen(query) > QUERY_MAX)
        return web_state_fail(s, "", "the query is longer than %d bytes", QUERY_MAX);
    char copy[QUERY_MAX + 1];
    strcpy(copy, query);
    const char *length = NULL, *mass = NULL, *tip = NULL, *links = NULL, *rate = NULL,
               *mode = NULL, *rmax = NULL, *frame = NULL, *drag = NULL, *drag2 = NULL,
               *pivot = NULL, *shake = NULL, *start = NULL, *tilt = NULL;
    for (char *save = NULL, *p = strtok_r(copy, "&", &save); p; p = strtok_r(NULL, "&", &save)) {
        char *eq = strchr(p, '=');
        if (eq == NULL) return web_state_fail(s, p, "%.40s: a parameter without a value", p);
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
            return web_state_fail(s, p, "unknown parameter %.40s (length, mass, tip, links, rate, "
                                    "mode, rmax, frame, drag, drag2, pivot, shake, start, tilt)",
                              p);
        *slot = eq + 1;
    }
    if (length == NULL) return web_state_fail(s, "length", "length: missing (e.g. length=60cm)");
    if (mass == NULL) return web_state_fail(s, "mass", "mass: missing (e.g. mass=50g)");
    if (rate == NULL) return web_state_fail(s, "rate", "rate: missing (e.g. rate=4Hz)");
    if (mode == NULL) return web_state_fail(s, "mode", "mode: missing (e.g. mode=2)");
    /* the page's bounds: a shape and its verdict within ~0.1 s */
    if (read_number(s, "length", length, WHIRL_QUANTITY_LENGTH, 0.01, 100, &s->length) ||
        read_number(s, "mass", mass, WHIRL_QUANTITY_MASS, 1e-4, 1e4, &s->mass) ||
        (tip && read_number(s, "tip", tip, WHIRL_QUANTITY_MASS, 0, 1e4, &s->tip)) ||
        (links && read_int(s, "links", links, 0, MAX_LINKS, &s->links)) ||
        read_int(s, "mode", mode, 1, MAX_MODE, &s->mode))
        return -1;
    if (s->links == 1)
        return web_state_fail(s, "links", "links: 0 (the continuum) or 2..%d", MAX_LINKS);
    if (s->links && s->mode > s->links)
        return web_state_fail(s, "mode", "mode %d needs at least %d links", s->mode, s->mode);
    rate_unit(s, rate);
    if (read_number(s, "rate", rate, WHIRL_QUANTITY_RATE, 1e-3 * s->unit, 1e5 * s->unit, &s->omega))
        return -1;
    s->time = sqrt(s->length / WHIRL_STANDARD_GRAVITY);
    s->w = s->omega * s->time;
    if (s->w > W_MAX)
        return web_state_fail(s, "rate", "rate above %.4g %s: beyond what the page computes live",
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
        return web_state_fail(s, "frame", "frame: rotating or inertial, got %.40s", frame);
    return read_run_state(s, drag, drag2, pivot, shake, start, tilt);
}

/* The library's last failure with its quantities in SI, as the state's failure. */
int web_library_fail(web_state *s, const char *field)
{
    char buf[512];
    whirl_last_error_in_units(buf, sizeof buf, 1, s->length, s->mass, WHIRL_STANDARD_GRAVITY,
                              strcmp(s->unit_name, "Hz") == 0);
    return web_state_fail(s, field, "%s", buf);
}

/* The rate where mode k is born on the hanging chain [sqrt(g/L)]: the chain's critical rate. */
int web_birth(web_state *s, const whirl_chain *c, int mode, double *w)
{
    double crit[MAX_MODE];
    const int status = c ? whirl_nlink_critical(c, (size_t)mode, crit)
                         : whirl_continuum_critical_rates((size_t)mode, s->m_tip, crit);
    if (status != GSL_SUCCESS) return web_library_fail(s, "mode");
    *w = crit[mode - 1];
    return 0;
}

/* The chain of n links with the state's tip mass (in chain masses). */
whirl_chain *web_chain_of(web_state *s, int n)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)n, s->m_tip);
    if (c == NULL) web_library_fail(s, "links");
    return c;
}

/* The linear verdict of the shape of the state's mode on the chain c: whirl stability --linear. */
static int verdict(web_state *s, const whirl_chain *c, json *j)
{
    whirl_stability *ws = whirl_stability_alloc(c->n);
    if (ws == NULL) return web_library_fail(s, "links");
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = s->w};
    double growth = 0;
    int index = 0;
    int status = whirl_stability_mode(ws, &m, s->mode, NULL, &growth);
    if (status == GSL_SUCCESS) status = whirl_stability_index(ws, &index);
    whirl_stability_free(ws);
    if (status != GSL_SUCCESS) return web_library_fail(s, "rate");
    web_put(j, ",\"verdict\":");
    web_put_string(j, whirl_verdict_name(whirl_verdict_linear(growth, index)));
    web_put(j, ",\"verdict_links\":%zu,\"index\":%d", c->n, index);
    web_put_key_number(j, "growth", growth / s->time);
    return 0;
}

char *whirl_web_shape(const char *query)
{
    web_state s;
    if (web_read_state(&s, query)) return web_error_answer(s.field, s.message);
    const size_t n = s.links ? (size_t)s.links + 1 : CONTINUUM_POINTS;
    whirl_chain *c = s.links ? web_chain_of(&s, s.links) : NULL;
    whirl_chain *vc = web_chain_of(&s, s.links ? s.links : VERDICT_LINKS);
    double *buf = malloc(4 * n * sizeof *buf);
    json j = {0};
    double born = 0;
    int failed = (s.links && c == NULL) || vc == NULL || buf == NULL ||
                 web_birth(&s, c, s.mode, &born) != 0;
    if (buf == NULL) web_state_fail(&s, "", "out of memory");
    whirl_shape_info info = {0};
    double *r = buf, *z = buf + n, *t = buf + 2 * n, *arc = buf + 3 * n;
    if (!failed) {
        int status = c ? whirl_nlink_solve_nodes(c, s.w, s.mode, &info, r, z, t)
                       : whirl_continuum_solve(s.w, s.mode, s.m_tip, 0, &info);
        if (status == GSL_SUCCESS && c == NULL)
            status = whirl_continuum_sample(s.w, s.m_tip, info.tip_r, n, arc, r, z, t);
        if (status == GSL_EDOM && s.w < born) { /* below the birth: the hanging chain */
            web_put(&j, "{\"hanging\":true,\"message\":\"mode %d is born at %.4g %s: below it the "
                    "chain hangs straight down\"", s.mode, born / s.time / s.unit, s.unit_name);
        } else if (status != GSL_SUCCESS)
            failed = web_library_fail(&s, "rate");
        else {
            web_put(&j, "{\"hanging\":false");
            put_array(&j, "x", r, n, s.length);
            put_array(&j, "z", z, n, s.length);
            put_array(&j, "tension", t, n, s.mass * WHIRL_STANDARD_GRAVITY);
            web_put_key_number(&j, "tip_r", fabs(info.tip_r) * s.length);
            web_put_key_number(&j, "top_tension", info.top_tension * s.mass * WHIRL_STANDARD_GRAVITY);
            web_put(&j, ",\"node_count\":%d", info.n_nodes + 1);
        }
    }
    if (!failed) {
        web_put(&j, ",\"unit\":");
        web_put_string(&j, s.unit_name);
        web_put_key_number(&j, "rate", s.omega / s.unit);
        web_put_key_number(&j, "omega", s.omega);
        web_put_key_number(&j, "period", 2 * M_PI / s.omega);
        web_put_key_number(&j, "born", born / s.time / s.unit);
        web_put_key_number(&j, "length", s.length);
        web_put(&j, ",\"mode\":%d,\"links\":%d", s.mode, s.links);
        if (s.w > born && vc->n >= (size_t)s.mode && verdict(&s, vc, &j) != 0) {
            /* the verdict's chain (30 links for the continuum) may be born later: said, not
             * failed */
            web_put(&j, ",\"verdict_error\":");
            web_put_string(&j, s.message);
        }
        web_put(&j, "}");
    }
    free(buf);
    whirl_chain_free(c);
    whirl_chain_free(vc);
    if (failed) {
        free(j.text);
        return web_error_answer(s.field, s.message);
    }
    return web_finish(&j);
}

char *whirl_web_branches(const char *query)
{
    web_state s;
    if (web_read_state(&s, query)) return web_error_answer(s.field, s.message);
    whirl_chain *c = s.links ? web_chain_of(&s, s.links) : NULL;
    const int top = s.links && s.links < MAX_MODE ? s.links : MAX_MODE;
    double crit[MAX_MODE], w[BRANCH_RATES];
    whirl_shape_info *info = malloc(BRANCH_RATES * sizeof *info);
    int exists[BRANCH_RATES];
    json j = {0};
    int failed = (s.links && c == NULL) || info == NULL;
    if (!failed && (c ? whirl_nlink_critical(c, (size_t)top, crit)
                      : whirl_continuum_critical_rates((size_t)top, s.m_tip, crit)) != GSL_SUCCESS)
        failed = web_library_fail(&s, "mode");
    if (info == NULL) web_state_fail(&s, "", "out of memory");
    for (int i = 0; i < BRANCH_RATES; i++) w[i] = s.w_max * (i + 1) / BRANCH_RATES;
    web_put(&j, "{\"unit\":");
    web_put_string(&j, s.unit_name);
    web_put_key_number(&j, "rate_max", s.w_max / s.time / s.unit);
    web_put(&j, ",\"modes\":[");
    for (int k = 1, drawn = 0; !failed && k <= top && drawn < BRANCH_MODES; k++) {
        if (!(crit[k - 1] < s.w_max)) continue;
        const int status = c ? whirl_nlink_branch(c, k, BRANCH_RATES, w, info, exists)
                             : whirl_continuum_branch(k, s.m_tip, BRANCH_RATES, w, info, exists);
        if (status != GSL_SUCCESS) {
            failed = web_library_fail(&s, "rmax");
            break;
        }
        /* each branch from its birth on the hanging chain (tip radius 0) */
        web_put(&j, "%s{\"mode\":%d", drawn++ ? "," : "", k);
        web_put_key_number(&j, "born", crit[k - 1] / s.time / s.unit);
        web_put(&j, ",\"rate\":[");
        web_put_number(&j, crit[k - 1] / s.time / s.unit);
        for (int i = 0; i < BRANCH_RATES; i++)
            if (exists[i]) web_put(&j, ","), web_put_number(&j, w[i] / s.time / s.unit);
        web_put(&j, "],\"tip_r\":[0");
        for (int i = 0; i < BRANCH_RATES; i++)
            if (exists[i]) web_put(&j, ","), web_put_number(&j, fabs(info[i].tip_r) * s.length);
        web_put(&j, "]}");
    }
    web_put(&j, "]}");
    free(info);
    whirl_chain_free(c);
    if (failed) {
        free(j.text);
        return web_error_answer(s.field, s.message);
    }
    return web_finish(&j);
}

char *whirl_web_windows(const char *query)
{
    web_state s;
    if (web_read_state(&s, query)) return web_error_answer(s.field, s.message);
    const int links = s.links ? s.links : VERDICT_LINKS;
    json j = {0};
    web_put(&j, "{\"mode\":%d,\"links\":%d,\"unit\":", s.mode, links);
    web_put_string(&j, s.unit_name);
    web_put(&j, ",\"windows\":[");
    int failed = 0;
    if (s.mode >= 2 && s.mode <= links) { /* mode 1: a minimum of the amended potential */
        whirl_chain *c = web_chain_of(&s, links);
        whirl_windows *ws = c ? whirl_windows_alloc(c->n) : NULL;
        whirl_window *found = malloc(WINDOWS_MAX * sizeof *found);
        double lo = 0;
        if (c != NULL && (ws == NULL || found == NULL)) web_state_fail(&s, "", "out of memory");
        failed = c == NULL || ws == NULL || found == NULL || web_birth(&s, c, s.mode, &lo) != 0;
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
                failed = web_library_fail(&s, "rmax");
            for (size_t i = 0; !failed && i < count; i++) {
                web_put(&j, "%s[", i ? "," : "");
                web_put_number(&j, found[i].from / s.time / s.unit);
                web_put(&j, ",");
                web_put_number(&j, found[i].to / s.time / s.unit);
                web_put(&j, ",");
                web_put_number(&j, found[i].max_growth / s.time);
                web_put(&j, "]");
            }
        }
        free(found);
        whirl_windows_free(ws);
        whirl_chain_free(c);
    }
    web_put(&j, "]}");
    if (failed) {
        free(j.text);
        return web_error_answer(s.field, s.message);
    }
    return web_finish(&j);
}

void whirl_web_free(char *answer) { free(answer); }
