/* Tests of the page's interface (src/web/whirl_web.c) in the native build: the state read with
 * the command line's units, the answer's numbers those of the library (the tip radius of
 * whirl_continuum_solve at the same rate, written so that it reads back to the same double), a
 * bad or unknown parameter answered with its name and nothing computed, the hanging chain below
 * a mode's birth; the perturbed run: its frames in time, the links' lengths kept, the deviation
 * staying small where the verdict is neutral and growing where it is unstable, the co-rotating and
 * inertial views one motion turned by omega t; the Floquet multipliers of the shaken settings
 * those of whirl periodic of this build (BUILD/whirl, beside BUILD/tests) bit for bit, with its
 * verdict, |mu|max, period, steps, growth and e-folding time as it prints them, its one line
 * where Newton's method does not converge, and a one-line error, no multiplier, for a bad
 * setting. The page itself runs the same C as WebAssembly (tests/cli/test_web.sh, which compares
 * the run with whirl simulate and the largest multiplier with whirl periodic). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_math.h>

#include "whirl/dynamics.h"
#include "whirl/integrator.h"
#include "whirl/periodic.h"
#include "whirl/steady.h"
#include "web/whirl_web.h"

/* The number after "key": in the JSON text a (the first one). */
static double number(const char *a, const char *key)
{
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    const char *p = strstr(a, pattern);
    if (p == NULL) fail_msg("no %s in %.300s", key, a);
    return strtod(p + strlen(pattern), NULL);
}

static void shape_numbers(void **state)
{
    (void)state;
    char *a = whirl_web_shape("length=60cm&mass=50g&rate=4Hz&mode=2");
    assert_non_null(a);
    assert_null(strstr(a, "\"error\""));
    whirl_shape_info info;
    const double w = 4 * 2 * M_PI * sqrt(0.6 / 9.80665); /* the library's units */
    assert_int_equal(whirl_continuum_solve(w, 2, 0, 0, &info), GSL_SUCCESS);
    assert_true(number(a, "tip_r") == fabs(info.tip_r) * 0.6);
    assert_true(number(a, "node_count") == 2);
    assert_true(number(a, "rate") == 4);
    assert_non_null(strstr(a, "\"unit\":\"Hz\""));
    assert_non_null(strstr(a, "\"verdict\":\"neutral (gyroscopic)\""));
    assert_true(number(a, "verdict_links") == 30);
    whirl_web_free(a);
}

static void bad_parameters(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"length=60cm&mass=5x&rate=4Hz&mode=2", "\"field\":\"mass\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=2&colour=red", "\"field\":\"colour\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=2&links=1", "\"field\":\"links\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=5&links=3", "\"field\":\"mode\""},
        {"length=60cm&mass=50g&rate=400Hz&mode=2", "\"field\":\"rate\""},
        {"length=60cm&mass=50g&rate=4kHz&mode=2", "\"field\":\"rate\""},
        {"length=60cm&mass=50g&mode=2", "\"field\":\"rate\""},
        {"length=-1&mass=50g&rate=4Hz&mode=2", "\"field\":\"length\""},
        {"length=60cm&mass=50g&rate=nan&mode=2", "\"field\":\"rate\""},
        {"length", "\"field\":\"length\""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char *a = whirl_web_shape(cases[i][0]);
        assert_non_null(a);
        if (strncmp(a, "{\"error\":", 9) != 0 || strstr(a, cases[i][1]) == NULL)
            fail_msg("%s: %s", cases[i][0], a);
        assert_null(strstr(a, "\"x\""));
        whirl_web_free(a);
    }
    char *long_query = malloc(4000);
    memset(long_query, 'a', 3999);
    long_query[3999] = 0;
    char *a = whirl_web_shape(long_query);
    assert_non_null(strstr(a, "longer than"));
    whirl_web_free(a);
    free(long_query);
}

static void below_birth(void **state)
{
    (void)state;
    char *a = whirl_web_shape("length=60cm&mass=50g&rate=1Hz&mode=2");
    assert_non_null(strstr(a, "\"hanging\":true"));
    double w2;
    assert_int_equal(whirl_continuum_critical(2, 0, &w2), GSL_SUCCESS);
    const double born = w2 / sqrt(0.6 / 9.80665) / (2 * M_PI);
    assert_true(fabs(number(a, "born") - born) <= 1e-15 * born);
    assert_null(strstr(a, "\"verdict\""));
    whirl_web_free(a);
}

static void branches_and_windows(void **state)
{
    (void)state;
    char *a = whirl_web_branches("length=60cm&mass=50g&rate=4Hz&mode=2&rmax=12Hz");
    assert_null(strstr(a, "\"error\""));
    assert_true(number(a, "rate_max") == 12);
    assert_non_null(strstr(a, "{\"mode\":1"));
    assert_non_null(strstr(a, "{\"mode\":4"));
    whirl_web_free(a);
    a = whirl_web_windows("length=60cm&mass=50g&rate=4Hz&mode=2&rmax=12Hz");
    assert_null(strstr(a, "\"error\""));
    assert_non_null(strstr(a, "\"windows\":[["));
    whirl_web_free(a);
}

/* A run's frames, all of them: frames[k * width + j], width = 2 + 3 links (5 + 3 links for a
 * shaken run: the pivot after the deviation). */
typedef struct frames {
    double *v;
    int count, width, total, steps;
    double t_end;
} frames;

static frames run_of(whirl_web_run *r, const char *query, int chunk, int shaken)
{
    frames f = {0};
    assert_non_null(r);
    for (int calls = 0;; calls++) {
        char *a = whirl_web_run_next(r, chunk);
        assert_non_null(a);
        if (strstr(a, "\"error\"")) fail_msg("%s: %s", query, a);
        f.width = (shaken ? 5 : 2) + 3 * (int)number(a, "links");
        f.t_end = number(a, "t_end");
        f.total = (int)number(a, "total");
        f.steps = (int)number(a, "steps");
        assert_non_null(strstr(a, shaken ? "\"shaken\":true" : "\"shaken\":false"));
        f.v = realloc(f.v, (size_t)(f.count + chunk) * (size_t)f.width * sizeof *f.v);
        const char *p = strstr(a, "\"frames\":[") + strlen("\"frames\":[");
        int in_chunk = 0;
        while (*p == '[' || *p == ',') {
            p += *p == ',' ? 2 : 1; /* ",[" or "[" */
            for (int j = 0; j < f.width; j++) {
                char *end;
                f.v[f.count * f.width + j] = strtod(p, &end);
                assert_true(end != p);
                p = end + 1; /* past "," or "]" */
            }
            f.count++;
            in_chunk++;
        }
        assert_true(in_chunk <= chunk);
        const int done = strstr(a, "\"done\":true") != NULL;
        whirl_web_free(a);
        assert_true(calls < 1000);
        if (done) break;
        assert_int_equal(in_chunk, chunk);
    }
    whirl_web_run_free(r);
    assert_int_equal(f.count, f.total);
    return f;
}

static frames run_all(const char *query, int chunk)
{
    frames f = run_of(whirl_web_run_alloc(query), query, chunk, 0);
    assert_int_equal(f.total, 401);
    return f;
}

static void run_frames(void **state)
{
    (void)state;
    frames f = run_all("length=60cm&mass=50g&rate=4Hz&mode=2", 7); /* 7: chunks end anywhere */
    assert_int_equal(f.count, 401);
    assert_int_equal(f.width, 2 + 3 * 30);
    assert_true(fabs(f.t_end - 10) <= 1e-14); /* 40 periods of 0.25 s */
    double worst = 0, dev_max = 0;
    for (int k = 0; k < f.count; k++) {
        const double *x = f.v + k * f.width;
        assert_true(fabs(x[0] - k * f.t_end / 400) <= 1e-12 * f.t_end); /* a frame every 0.1 turn */
        dev_max = fmax(dev_max, x[1]);
        for (int i = 0; i < 30; i++) { /* each link 2 cm long (the positions have 7 digits) */
            const double *a = i ? x + 2 + 3 * (i - 1) : (const double[3]){0, 0, 0}, *b = x + 2 + 3 * i;
            worst = fmax(worst, fabs(hypot(hypot(b[0] - a[0], b[1] - a[1]), b[2] - a[2]) - 0.02));
        }
    }
    assert_true(worst <= 1e-6);
    /* 1 mrad per link: a start of tens of micrometres; neutral (gyroscopic): it stays so */
    assert_true(f.v[1] > 1e-6 && f.v[1] < 1e-3);
    assert_true(dev_max < 3 * f.v[1]);
    free(f.v);
    /* 6 Hz: unstable, growing e-fold in 0.7 s (whirl stability --linear): the run leaves */
    f = run_all("length=60cm&mass=50g&rate=6Hz&mode=2", 50);
    assert_true(f.v[(f.count - 1) * f.width + 1] > 100 * f.v[1]);
    free(f.v);
}

static void run_views(void **state)
{
    (void)state;
    frames r = run_all("length=60cm&mass=50g&rate=3Hz&mode=1&links=12&frame=rotating", 401);
    frames in = run_all("length=60cm&mass=50g&rate=3Hz&mode=1&links=12&frame=inertial", 401);
    assert_int_equal(r.count, in.count);
    const double w = 3 * 2 * M_PI;
    double worst = 0;
    for (int k = 0; k < r.count; k++) {
        const double *a = r.v + k * r.width, *b = in.v + k * in.width;
        assert_true(a[0] == b[0] && a[1] == b[1]); /* one motion: the same deviation */
        const double c = cos(w * a[0]), s = sin(w * a[0]);
        for (int i = 0; i < 12; i++) { /* inertial = rotating turned by omega t about z */
            const double *p = a + 2 + 3 * i, *q = b + 2 + 3 * i;
            worst = fmax(worst, fabs(c * p[0] - s * p[1] - q[0]));
            worst = fmax(worst, fabs(s * p[0] + c * p[1] - q[1]));
            worst = fmax(worst, fabs(p[2] - q[2]));
        }
    }
    assert_true(worst <= 1e-6); /* 7 digits of 0.6 m */
    free(r.v);
    free(in.v);
}

static void run_errors(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"length=60cm&mass=50g&rate=1Hz&mode=2", "\"field\":\"rate\""}, /* below the birth */
        {"length=60cm&mass=5x&rate=4Hz&mode=2", "\"field\":\"mass\""},
        {"length=60cm&mass=50g&rate=4Hz&mode=2&frame=sideways", "\"field\":\"frame\""},
        {"", "\"field\":\"length\""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        whirl_web_run *r = whirl_web_run_alloc(cases[i][0]);
        assert_non_null(r);
        for (int k = 0; k < 2; k++) { /* asked again: the same error, nothing computed */
            char *a = whirl_web_run_next(r, 10);
            if (strncmp(a, "{\"error\":", 9) != 0 || strstr(a, cases[i][1]) == NULL)
                fail_msg("%s: %s", cases[i][0], a);
            whirl_web_free(a);
        }
        whirl_web_run_free(r);
    }
    char *a = whirl_web_run_next(NULL, 10);
    assert_non_null(strstr(a, "\"error\""));
    whirl_web_free(a);
    whirl_web_run_free(NULL);
}

/* x written in 7 digits and read back, as the run's positions are */
static double seven(double x)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%.7g", x);
    return strtod(buf, NULL);
}

/* The shaken run of the page against the same run through the library directly: the same
 * chain, path (whirl_pivot_parse of the same text at the same rate), drag, start and step (the
 * frame's interval, an eighth of the path's period, over the answer's steps per frame). */
static void shake_equals_library(void **state)
{
    (void)state;
    const char *q = "length=60cm&mass=50g&rate=2Hz&mode=2&links=3&pivot=vertical:1cm&shake=55Hz"
                    "&start=inverted&tilt=3&drag=0.01&drag2=0.002";
    frames f = run_of(whirl_web_shake_alloc(q), q, 64, 1);
    assert_int_equal(f.total, 801);
    assert_int_equal(f.width, 5 + 9);
    double L, M, w;
    assert_int_equal(whirl_parse_quantity("60cm", WHIRL_QUANTITY_LENGTH, &L, NULL), 0);
    assert_int_equal(whirl_parse_quantity("50g", WHIRL_QUANTITY_MASS, &M, NULL), 0);
    assert_int_equal(whirl_parse_quantity("55Hz", WHIRL_QUANTITY_RATE, &w, NULL), 0);
    const double T = sqrt(L / 9.80665);
    w *= T;
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_parse("vertical:1cm", w, L, 3, &path), GSL_SUCCESS);
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL, .omega = w,
                           .air_drag = 0.01 * L * T / M, .air_drag_quadratic = 0.002 * L * L / M};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(d);
    assert_int_equal(whirl_dyn_set_pivot(d, whirl_pivot_eval, &path), GSL_SUCCESS);
    const double tilt = 3 * M_PI / 180;
    double links[9], y[18], x[9], v[9], p[3], pv[3], pa[3];
    for (int i = 0; i < 3; i++) {
        links[3 * i] = c->length[i] * sin(tilt);
        links[3 * i + 1] = 0;
        links[3 * i + 2] = c->length[i] * cos(tilt);
    }
    assert_true(whirl_dyn_size(d) <= 18);
    assert_int_equal(whirl_dyn_state_from_shape(d, 0, links, 0, y), GSL_SUCCESS);
    whirl_system sys;
    assert_int_equal(whirl_dyn_system(d, &sys), GSL_SUCCESS);
    whirl_integrator *it = whirl_integrator_alloc_system(whirl_integrator_gauss2, &sys);
    assert_non_null(it);
    const double every = whirl_pivot_period(&path) / 8, dt = every / f.steps;
    assert_true(f.steps >= 1);
    double t = 0, worst_h = 0, worst_x = 0, pz_lo = 1, pz_hi = -1;
    for (int k = 0; k < f.count; k++) {
        const double *g = f.v + k * f.width;
        if (k) assert_int_equal(whirl_integrator_advance(it, &t, y, k * every, dt, 0), GSL_SUCCESS);
        assert_int_equal(whirl_dyn_get_state(d, t, y, WHIRL_FRAME_INERTIAL, x, v), GSL_SUCCESS);
        whirl_pivot_eval(t, p, pv, pa, &path);
        assert_true(g[0] == t * T);
        worst_h = fmax(worst_h, fabs(g[1] - (x[8] - p[2]) * L));
        for (int j = 0; j < 12; j++) /* the pivot, then the masses */
            worst_x = fmax(worst_x, fabs(g[2 + j] - seven((j < 3 ? p[j] : x[j - 3]) * L)));
        pz_lo = fmin(pz_lo, g[4]);
        pz_hi = fmax(pz_hi, g[4]);
    }
    assert_true(worst_h <= 1e-15 * L); /* to round-off: the same operations */
    assert_true(worst_x == 0);         /* the positions, written in 7 digits */
    assert_true(pz_hi - pz_lo > 0.019 && pz_hi - pz_lo <= 0.02); /* the pivot: 1 cm either way */
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    free(f.v);
}

/* The largest |x| of the tip in the frames from k0 on, and the smallest height above the pivot. */
static void tip_extremes(const frames *f, int k0, double *x_max, double *h_min)
{
    *x_max = 0;
    *h_min = INFINITY;
    const int links = (f->width - 5) / 3;
    for (int k = k0; k < f->count; k++) {
        const double *g = f->v + k * f->width;
        *x_max = fmax(*x_max, fabs(g[5 + 3 * (links - 1)]));
        *h_min = fmin(*h_min, g[1]);
    }
}

/* Kapitza's pendulum as Acheson's chain: the 3-link chain of 60 cm standing straight up, 3
 * degrees off, stays up over 100 periods of a vertical shaking of 1 cm at 55 Hz (whirl
 * periodic --pivot vertical:1cm --omega 55Hz --links 3 --start inverted: neutral, every
 * multiplier on the unit circle); without the shaking it falls. A free swing of 20 degrees
 * with air drag dies away, without drag it does not. */
static void shake_runs(void **state)
{
    (void)state;
    const char *base = "length=60cm&mass=50g&rate=2Hz&mode=2&links=3&start=inverted&tilt=3";
    char q[512];
    snprintf(q, sizeof q, "%s&pivot=vertical:1cm&shake=55Hz", base);
    frames f = run_of(whirl_web_shake_alloc(q), q, 100, 1);
    double x_max, h_min;
    tip_extremes(&f, 0, &x_max, &h_min);
    assert_true(fabs(f.t_end - 100 / 55.0) <= 1e-12); /* 100 periods */
    assert_true(h_min > 0.5);                         /* up: the tip over half a metre above */
    free(f.v);
    snprintf(q, sizeof q, "%s&pivot=none", base);
    f = run_of(whirl_web_shake_alloc(q), q, 100, 1);
    tip_extremes(&f, 0, &x_max, &h_min);
    assert_true(h_min < 0); /* falls */
    free(f.v);
    const char *swing = "length=60cm&mass=50g&rate=2Hz&mode=2&links=12&start=hanging&tilt=20";
    double free_x, drag_x;
    f = run_of(whirl_web_shake_alloc(swing), swing, 100, 1);
    tip_extremes(&f, f.count - 100, &free_x, &h_min);
    free(f.v);
    snprintf(q, sizeof q, "%s&drag=0.05", swing);
    f = run_of(whirl_web_shake_alloc(q), q, 100, 1);
    tip_extremes(&f, f.count - 100, &drag_x, &h_min);
    free(f.v);
    assert_true(drag_x < 0.5 * free_x);
}

static void shake_errors(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"pivot=wobble:1cm&shake=30Hz", "\"field\":\"pivot\""},
        {"pivot=vertical:1cm", "\"field\":\"shake\""},
        {"pivot=vertical:1cm&shake=fast", "\"field\":\"shake\""},
        {"pivot=vertical:1cm&shake=0Hz", "\"field\":\"shake\""},
        {"pivot=vertical:1cm&shake=2000Hz", "\"field\":\"shake\""},
        {"pivot=vertical:2m&shake=30Hz", "\"field\":\"pivot\""},
        {"pivot=circle:43cm&shake=3Hz", "\"field\":\"pivot\""}, /* 43 cm of the chain's 30 */
        {"pivot=vertical:10cm&shake=400Hz&links=400", "\"field\":\"shake\""}, /* too much */
        {"pivot=vertical:nan&shake=30Hz", "\"field\":\"pivot\""},
        {"start=sideways", "\"field\":\"start\""},
        {"tilt=100", "\"field\":\"tilt\""},
        {"drag=-1", "\"field\":\"drag\""},
        {"drag2=x", "\"field\":\"drag2\""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char q[256];
        snprintf(q, sizeof q, "length=30cm&mass=50g&rate=2Hz&mode=2&%s", cases[i][0]);
        whirl_web_run *r = whirl_web_shake_alloc(q);
        assert_non_null(r);
        char *a = whirl_web_run_next(r, 10);
        if (strncmp(a, "{\"error\":", 9) != 0 || strstr(a, cases[i][1]) == NULL)
            fail_msg("%s: %s", q, a);
        whirl_web_free(a);
        whirl_web_run_free(r);
    }
}

/* ---- the Floquet multipliers (whirl_web_floquet) against whirl periodic of this build ---- */

static const char *cli_path; /* the build's command line: the test program's folder's ../whirl */

/* The output of whirl ARGS (standard output and error, malloc'd); fails the test if it cannot be
 * run. The same build's program: nothing installed is used. */
static char *cli_output(const char *args)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "'%s' %s 2>&1", cli_path, args);
    FILE *fp = popen(cmd, "r");
    if (fp == NULL) fail_msg("cannot run %s", cmd);
    size_t len = 0, cap = 4096;
    char *out = malloc(cap);
    for (size_t got; (got = fread(out + len, 1, cap - len - 1, fp)) > 0;) {
        len += got;
        if (cap - len < 2) out = realloc(out, cap *= 2);
    }
    out[len] = 0;
    pclose(fp);
    if (len == 0) fail_msg("%s: no output", cmd);
    return out;
}

/* The text after key in a, up to the first of the characters stop (static buffer). */
static const char *word_after(const char *a, const char *key, const char *stop)
{
    static char buf[128];
    const char *p = strstr(a, key);
    if (p == NULL) fail_msg("no %s in %.400s", key, a);
    p += strlen(key);
    const size_t n = strcspn(p, stop);
    snprintf(buf, sizeof buf, "%.*s", (int)(n < sizeof buf ? n : sizeof buf - 1), p);
    return buf;
}

/* x as printf's format writes it (static buffer). */
static const char *printed(const char *fmt, double x)
{
    static char buf[64];
    snprintf(buf, sizeof buf, fmt, x);
    return buf;
}

/* The page's answer for query against whirl periodic with args (the same settings): every
 * multiplier, its modulus and error equal as doubles (both written in the fewest digits that
 * read back), the verdict, the largest |mu| and its error, the period, the steps and, unstable,
 * the growth and e-folding time as whirl periodic prints them. */
static void floquet_case(const char *query, const char *args, const char *verdict)
{
    char *a = whirl_web_floquet(query);
    assert_non_null(a);
    if (strstr(a, "\"error\"")) fail_msg("%s: %s", query, a);
    char *o = cli_output(args);
    if (strstr(o, "index,re,im,modulus,err\n") == NULL) fail_msg("whirl %s: %.400s", args, o);
    assert_string_equal(word_after(a, "\"verdict\":\"", "\""), verdict);
    assert_string_equal(word_after(o, "verdict=", "; "), verdict);
    assert_string_equal(printed("%.15g", number(a, "max_modulus")), word_after(o, "|mu|max=", " "));
    assert_string_equal(printed("%.2g", number(a, "max_modulus_err")), word_after(o, " +- ", ";"));
    assert_true(number(a, "period") == strtod(word_after(o, "period=", " "), NULL));
    char line[128]; /* "2.2e-39; 800 steps per period (errors from 400)" */
    snprintf(line, sizeof line, "%s", word_after(o, ", residual ", "\n"));
    assert_true(number(a, "steps") == strtod(word_after(line, "; ", " "), NULL));
    if (strcmp(verdict, "unstable") == 0) {
        assert_string_equal(printed("%.10g", number(a, "growth")), word_after(o, "growth=", " "));
        assert_true(number(a, "efold_time") == strtod(word_after(o, "periods (", " "), NULL));
    }
    const char *p = strstr(a, "\"multipliers\":[") + strlen("\"multipliers\":[");
    const char *row = strstr(o, "index,re,im,modulus,err\n") + strlen("index,re,im,modulus,err\n");
    size_t count = 0;
    while (*p == '[' || *p == ',') {
        p += *p == ',' ? 2 : 1; /* ",[" or "[" */
        char *end;
        if (strtol(row, &end, 10) != (long)++count) fail_msg("row %zu of whirl %s", count, args);
        row = end;
        for (int k = 0; k < 4; k++) { /* re, im, |mu|, err */
            const double page = strtod(p, &end);
            p = end + 1;
            const double cli = strtod(row + 1, &end); /* past the comma */
            row = end;
            if (page != cli)
                fail_msg("%s: multiplier %zu, column %d: %.17g, whirl periodic %.17g", query,
                         count, k, page, cli);
        }
        row += *row == '\n';
    }
    assert_true(count > 0 && count == (size_t)(4 * number(a, "links")));
    assert_true(*row == 0); /* no row left over */
    whirl_web_free(a);
    free(o);
}

static void floquet_equals_cli(void **state)
{
    (void)state;
    /* Kapitza's preset standing up: neutral (every multiplier on the unit circle) */
    floquet_case("length=60cm&mass=50g&rate=2Hz&mode=1&links=3&pivot=vertical:1cm&shake=55Hz"
                 "&start=inverted&tilt=3",
                 "periodic --pivot vertical:1cm --omega 55Hz --links 3 --start inverted "
                 "--length 60cm --mass 50g", "neutral");
    /* the hanging chain on a circle of 1 cm at 4 Hz: unstable */
    floquet_case("length=60cm&mass=50g&rate=2Hz&mode=1&links=5&pivot=circle:1cm&shake=4Hz",
                 "periodic --pivot circle:1cm --omega 4Hz --links 5 --length 60cm --mass 50g",
                 "unstable");
    /* with air drag on an ellipse (the rate in rpm as the page's rate: a bare shake): stable */
    floquet_case("length=1.2&mass=0.3&rate=60rpm&mode=1&links=3&pivot=ellipse:3cm,2cm&shake=90"
                 "&drag=0.05&drag2=0.01",
                 "periodic --pivot ellipse:3cm,2cm --omega 90rpm --links 3 --length 1.2 "
                 "--mass 0.3 --drag 0.05 --drag-quadratic 0.01", "stable");
}

/* Newton's method that does not converge (the hanging 3-link chain of 60 cm on a circle of 10
 * cm at 1 Hz): the library's one line, whirl periodic's, and no multiplier. */
static void floquet_no_convergence(void **state)
{
    (void)state;
    char *a = whirl_web_floquet("length=60cm&mass=50g&rate=2Hz&mode=1&links=3"
                                "&pivot=circle:10cm&shake=1Hz");
    char *o = cli_output("periodic --pivot circle:10cm --omega 1Hz --links 3 --length 60cm "
                         "--mass 50g");
    const char *message = word_after(a, "{\"error\":\"", "\"");
    if (strstr(message, "did not converge") == NULL) fail_msg("%s", a);
    assert_string_equal(message, word_after(o, "whirl periodic: ", "\n"));
    assert_null(strstr(a, "\"multipliers\""));
    assert_null(strstr(a, "max_modulus"));
    whirl_web_free(a);
    free(o);
}

static void floquet_errors(void **state)
{
    (void)state;
    static const char *const cases[][2] = {
        {"links=3&pivot=none", "\"field\":\"pivot\""},
        {"links=3", "\"field\":\"pivot\""}, /* no path: a fixed pivot */
        {"links=3&pivot=wobble:1cm&shake=30Hz", "\"field\":\"pivot\""},
        {"links=3&pivot=vertical:1cm", "\"field\":\"shake\""},
        {"links=3&pivot=vertical:1cm&shake=0Hz", "\"field\":\"shake\""},
        {"links=3&pivot=vertical:2m&shake=30Hz", "\"field\":\"pivot\""},
        {"links=1&pivot=vertical:1cm&shake=30Hz", "\"field\":\"links\""},
        {"links=3&pivot=vertical:1cm&shake=30Hz&drag=-1", "\"field\":\"drag\""},
        {"links=3&pivot=vertical:1cm&shake=30Hz&start=sideways", "\"field\":\"start\""},
        {"links=60&pivot=vertical:1cm&shake=55Hz", "\"field\":\"shake\""}, /* too much work */
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char q[256];
        snprintf(q, sizeof q, "length=60cm&mass=50g&rate=2Hz&mode=1&%s", cases[i][0]);
        char *a = whirl_web_floquet(q);
        assert_non_null(a);
        if (strncmp(a, "{\"error\":", 9) != 0 || strstr(a, cases[i][1]) == NULL ||
            strchr(a, '\n') || strstr(a, "\\n") || strstr(a, "\"multipliers\""))
            fail_msg("%s: %s", q, a);
        whirl_web_free(a);
    }
}

int main(int argc, char **argv)
{
    (void)argc;
    gsl_set_error_handler_off();
    /* the build's whirl: BUILD/tests/test_whirl_web -> BUILD/whirl */
    static char cli[4096];
    const char *slash = strrchr(argv[0], '/');
    snprintf(cli, sizeof cli, "%.*s../whirl", slash ? (int)(slash - argv[0] + 1) : 0, argv[0]);
    cli_path = cli;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shape_numbers),
        cmocka_unit_test(bad_parameters),
        cmocka_unit_test(below_birth),
        cmocka_unit_test(branches_and_windows),
        cmocka_unit_test(run_frames),
        cmocka_unit_test(run_views),
        cmocka_unit_test(run_errors),
        cmocka_unit_test(shake_equals_library),
        cmocka_unit_test(shake_runs),
        cmocka_unit_test(shake_errors),
        cmocka_unit_test(floquet_equals_cli),
        cmocka_unit_test(floquet_no_convergence),
        cmocka_unit_test(floquet_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
