/* Tests of running a scene from C (whirl_scene_work_*, whirl_scene_run in include/whirl/scene.h):
 *  - the seed's double pendulum from its angles (2D, no forces but gravity): every row's energy
 *    equals the first to 1e-9 (conservation; the start's energy is also checked against the
 *    closed form of the angles: potential only, at rest), one row per output time;
 *  - a steady mode-2 start without perturbation in the co-rotating frame stays on its shape (the
 *    deviation column below 1e-10: the steady solver and the dynamics agree);
 *  - whirl_scene_run writes the header and rows to a stream;
 *  - stops: stop_deviation (res.stopped, the row at the stop), a callback's status, a stop
 *    request (WHIRL_EINTERRUPTED, the rows so far counted);
 *  - the dissipation's rate (whirl_scene_damping_rate) on a non-uniform chain against the
 *    header's formula by hand, 16 D / min(m_i l_i^2) + max(l_i / m_i) (c + 2 c2 v) with
 *    v = |omega| (L + drive_radius), for damping, drag, quadratic drag and all of them;
 *    whirl_scene_stiff past dt x rate = 2 only, and never with tol > 0 or gsl-msbdf;
 *  - errors: NULL arguments, an unknown method and a mode without a shape named by their keys. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/scene.h"

static char dir[] = "/tmp/whirl-test-scene-run-XXXXXX";
static char path[sizeof dir + 16];

static void parse(const char *text, const char *const *sets, size_t n, whirl_scene *s)
{
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(text, fp);
    fclose(fp);
    assert_int_equal(whirl_scene_parse(path, sets, n, s), GSL_SUCCESS);
}

static const char pendulum[] = "[chain]\ndim = 2\nlinks = 2\nlengths = 0.5, 0.5\n"
                               "masses = 0.5, 0.5\n[start]\ntheta = 1.2, -0.6\n[run]\n"
                               "method = gauss2\ndt = 0.005\nt_end = 3\n[output]\nevery = 0.25\n"
                               "columns = t, tip_x, energy\n";

typedef struct rows {
    int n;
    double t[64], energy[64], deviation[64];
    int stop_after; /* > 0: the row callback fails after this many rows */
} rows;

static int collect(void *ctx, const double *value)
{
    rows *r = ctx;
    if (r->n < 64) {
        r->t[r->n] = value[WHIRL_COLUMN_T];
        r->energy[r->n] = value[WHIRL_COLUMN_ENERGY];
        r->deviation[r->n] = value[WHIRL_COLUMN_DEVIATION];
    }
    r->n++;
    return r->stop_after > 0 && r->n >= r->stop_after ? GSL_EBADFUNC : GSL_SUCCESS;
}

static void test_pendulum(void **state)
{
    (void)state;
    whirl_scene s;
    parse(pendulum, NULL, 0, &s);
    whirl_scene_work *w = whirl_scene_work_alloc(&s);
    assert_non_null(w);
    rows r = {0};
    const whirl_scene_output out = {.row = collect, .ctx = &r};
    whirl_scene_result res;
    assert_int_equal(whirl_scene_work_run(w, &out, &res), GSL_SUCCESS);
    assert_int_equal(r.n, 13);
    assert_int_equal((int)res.rows, 13);
    assert_true(res.t == 3 && r.t[12] == 3 && !res.stopped);
    /* at rest: E = sum m g z = -0.5 (0.5 cos 1.2) - 0.5 (0.5 cos 1.2 + 0.5 cos 0.6) */
    const double e0 = -0.5 * 0.5 * cos(1.2) - 0.5 * (0.5 * cos(1.2) + 0.5 * cos(-0.6));
    double drift = 0;
    for (int k = 0; k < r.n; k++) drift = fmax(drift, fabs(r.energy[k] - r.energy[0]));
    print_message("# pendulum: E(0) %.15g (closed form %.15g), drift %.2g, %lu steps\n",
                  r.energy[0], e0, drift, res.stats.steps);
    assert_true(fabs(r.energy[0] - e0) < 1e-14);
    assert_true(drift < 1e-9);
    assert_true(res.stats.steps >= 600); /* dt = 0.005 to t = 3 */
    whirl_scene_work_free(w);
    /* the same to a stream */
    FILE *fp = tmpfile();
    assert_non_null(fp);
    assert_int_equal(whirl_scene_run(&s, fp, NULL, &res), GSL_SUCCESS);
    rewind(fp);
    char line[512];
    int lines = 0, header = 0;
    while (fgets(line, sizeof line, fp)) {
        lines++;
        header += strcmp(line, "t,tip_x,energy\n") == 0;
    }
    fclose(fp);
    assert_int_equal(header, 1);
    assert_int_equal(lines, 4 + 1 + 13); /* 4 comment lines (the last: units), names, rows */
    whirl_scene_free(&s);
}

static const char steady[] = "[chain]\ndim = 3\nlinks = 8\n[start]\nomega = 3.7\nmode = 2\n"
                             "[run]\nframe = rotating\nmethod = rk8\ndt = 0.01\nt_end = 2\n"
                             "[output]\nevery = 0.5\ncolumns = t, deviation\n";

static void test_steady_and_stops(void **state)
{
    (void)state;
    whirl_scene s;
    parse(steady, NULL, 0, &s);
    whirl_scene_work *w = whirl_scene_work_alloc(&s);
    assert_non_null(w);
    rows r = {0};
    whirl_scene_output out = {.row = collect, .ctx = &r};
    whirl_scene_result res;
    assert_int_equal(whirl_scene_work_run(w, &out, &res), GSL_SUCCESS);
    double worst = 0;
    for (int k = 0; k < r.n; k++) worst = fmax(worst, r.deviation[k]);
    print_message("# steady mode 2 start: largest deviation %.2g over %d rows\n", worst, r.n);
    assert_int_equal(r.n, 5);
    assert_true(worst < 1e-10);
    whirl_scene_work_free(w);
    whirl_scene_free(&s);
    /* a perturbed start of mode 2, unstable at omega 6.3 for 12 links, stops on
       stop_deviation */
    const char *const sets[] = {"chain.links=12", "start.omega=6.3", "start.perturb=1e-3",
                                "run.stop_deviation=2e-3", "run.t_end=60"};
    parse(steady, sets, 5, &s);
    w = whirl_scene_work_alloc(&s);
    assert_non_null(w);
    r = (rows){0};
    assert_int_equal(whirl_scene_work_run(w, &out, &res), GSL_SUCCESS);
    print_message("# stopped at t = %g, deviation %.3g\n", res.t, res.deviation);
    assert_true(res.stopped && res.deviation > 2e-3 && res.t < 60);
    assert_true(r.n >= 2 && r.deviation[(r.n - 1) % 64] == res.deviation);
    whirl_scene_work_free(w);
    /* a callback's status stops the run */
    w = whirl_scene_work_alloc(&s);
    r = (rows){.stop_after = 2};
    assert_int_equal(whirl_scene_work_run(w, &out, &res), GSL_EBADFUNC);
    assert_int_equal(r.n, 2);
    whirl_scene_work_free(w);
    /* a stop request: interrupted, the first row kept */
    w = whirl_scene_work_alloc(&s);
    r = (rows){0};
    whirl_stop_request();
    assert_int_equal(whirl_scene_work_run(w, &out, &res), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_int_equal((int)res.rows, 1);
    assert_true(res.t == 0);
    assert_non_null(strstr(whirl_last_error(), "interrupted at t = 0"));
    whirl_scene_work_free(w);
    whirl_scene_free(&s);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_scene s;
    assert_null(whirl_scene_work_alloc(NULL));
    assert_int_equal(whirl_scene_run(NULL, stdout, NULL, NULL), GSL_EINVAL);
    const char *const bad_method[] = {"run.method=rk5"};
    parse(pendulum, bad_method, 1, &s);
    assert_null(whirl_scene_work_alloc(&s));
    assert_non_null(strstr(whirl_last_error(), "--set run.method: unknown integrator"));
    assert_non_null(strstr(whirl_last_error(), "rk5"));
    whirl_scene_result res;
    FILE *fp = tmpfile();
    assert_int_equal(whirl_scene_run(&s, fp, NULL, &res), GSL_EINVAL);
    fclose(fp);
    whirl_scene_free(&s);
    const char *const slow[] = {"start.omega=2.0"}; /* mode 2 needs omega > 2.7 */
    parse(steady, slow, 1, &s);
    assert_null(whirl_scene_work_alloc(&s));
    assert_non_null(strstr(whirl_last_error(), "[start] mode"));
    assert_int_equal(whirl_scene_run(&s, stdout, NULL, &res), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "no steady shape"));
    whirl_scene_free(&s);
    parse(pendulum, NULL, 0, &s);
    whirl_scene_work *w = whirl_scene_work_alloc(&s);
    assert_non_null(w);
    assert_int_equal(whirl_scene_work_run(w, NULL, &res), GSL_EINVAL);
    whirl_scene_work_free(w);
    whirl_scene_work_free(NULL);
    whirl_scene_free(&s);
}

/* m l^2 = 0.006, 0.025, 0.048; l / m = 1/6, 5, 4/3 */
static const char hanging[] = "[chain]\ndim = 3\nlinks = 3\nlengths = 0.1, 0.5, 0.4\n"
                              "masses = 0.6, 0.1, 0.3\n[start]\nhanging = true\n[run]\n"
                              "dt = 0.01\nt_end = 1\nomega = -2.5\n";

static void test_damping_rate(void **state)
{
    (void)state;
    static const struct {
        const char *set[4];
        size_t n;
        double rate; /* by hand */
    } cases[] = {
        {{"run.internal_damping=0.03"}, 1, 16 * 0.03 / 0.006},
        {{"run.air_drag=7"}, 1, 5 * 7.0},
        /* 5 x 2 c2 |omega| (L + eps) = 5 x 2 x 4 x 2.5 x 1.2 */
        {{"run.air_drag_quadratic=4", "run.drive_radius=0.2"}, 2, 120.0},
        {{"run.internal_damping=0.01", "run.air_drag=1.5", "run.air_drag_quadratic=4",
          "run.drive_radius=0.2"}, 4, 16 * 0.01 / 0.006 + 5 * (1.5 + 2 * 4 * 2.5 * 1.2)},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        whirl_scene s;
        parse(hanging, cases[k].set, cases[k].n, &s);
        const double rate = whirl_scene_damping_rate(&s);
        assert_true(fabs(rate - cases[k].rate) <= 1e-14 * cases[k].rate);
        double got = 0;
        s.dt = 1.9 / rate;
        assert_int_equal(whirl_scene_stiff(&s, &got), 0);
        assert_true(got == rate);
        s.dt = 2.1 / rate;
        assert_int_equal(whirl_scene_stiff(&s, NULL), 1);
        s.tol = 1e-6;
        assert_int_equal(whirl_scene_stiff(&s, NULL), 0);
        whirl_scene_free(&s);
    }
    whirl_scene s;
    const char *const implicit[] = {"run.internal_damping=0.03", "run.dt=0.1",
                                    "run.method=gsl-msbdf"}; /* dt x rate = 8 */
    parse(hanging, implicit, 3, &s);
    assert_int_equal(whirl_scene_stiff(&s, NULL), 0);
    whirl_scene_free(&s);
    parse(hanging, NULL, 0, &s);
    assert_true(whirl_scene_damping_rate(&s) == 0);
    assert_int_equal(whirl_scene_stiff(&s, NULL), 0);
    whirl_scene_free(&s);
    assert_true(whirl_scene_damping_rate(NULL) == 0);
}

static int setup(void **state)
{
    (void)state;
    if (mkdtemp(dir) == NULL) return -1;
    snprintf(path, sizeof path, "%s/scene.ini", dir);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    unlink(path);
    rmdir(dir);
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pendulum),
        cmocka_unit_test(test_steady_and_stops),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_damping_rate),
    };
    return cmocka_run_group_tests_name("scene_run", tests, setup, teardown);
}
