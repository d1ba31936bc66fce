/* Tests of the page's interface (src/web/whirl_web.c) in the native build: the state read with
 * the command line's units, the answer's numbers those of the library (the tip radius of
 * whirl_continuum_solve at the same rate, written so that it reads back to the same double), a
 * bad or unknown parameter answered with its name and nothing computed, the hanging chain below
 * a mode's birth; the perturbed run: its frames in time, the links' lengths kept, the deviation
 * staying small where the verdict is neutral and growing where it is unstable, the co-rotating and
 * inertial views one motion turned by omega t. The page itself runs the same C as WebAssembly
 * (tests/cli/test_web.sh, which compares the run with whirl simulate). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_math.h>

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

/* A run's frames, all of them: frames[k * width + j], width = 2 + 3 links. */
typedef struct frames {
    double *v;
    int count, width;
    double t_end;
} frames;

static frames run_all(const char *query, int chunk)
{
    frames f = {0};
    whirl_web_run *r = whirl_web_run_alloc(query);
    assert_non_null(r);
    for (int calls = 0;; calls++) {
        char *a = whirl_web_run_next(r, chunk);
        assert_non_null(a);
        if (strstr(a, "\"error\"")) fail_msg("%s: %s", query, a);
        f.width = 2 + 3 * (int)number(a, "links");
        f.t_end = number(a, "t_end");
        assert_true(number(a, "total") == 401);
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

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shape_numbers),
        cmocka_unit_test(bad_parameters),
        cmocka_unit_test(below_birth),
        cmocka_unit_test(branches_and_windows),
        cmocka_unit_test(run_frames),
        cmocka_unit_test(run_views),
        cmocka_unit_test(run_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
