/* Tests of a scene's pivot path ([run] pivot, whirl/scene.h): whirl_scene as 2.3.0 laid it out
 * (its size, every field's offset, the count of its keys), the key read beside the scene and
 * refused by whirl_scene_parse, its units, its one-line errors, the header's line that reads
 * back to the same path, and runs: the planar line path against the planar drive. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "whirl/scene.h"

/* ---- the ABI: whirl_scene of 2.3.0 (git show 9309d46:include/whirl/scene.h), field for field,
 * its types spelt as they were there ---- */

#define KEYS_2_3_0 37    /* WHIRL_SCENE_NKEYS of 2.3.0 */
#define COLUMNS_2_3_0 9  /* WHIRL_NCOLUMNS of 2.3.0 */
#define SIZE_LP64_2_3_0 512 /* sizeof(whirl_scene) of 2.3.0 on LP64 (x86-64, aarch64) */

typedef struct scene_2_3_0 {
    char *path;
    int physical;
    int dim;
    size_t links;
    double *length;
    double *mass;
    double chain_length;
    double chain_mass;
    double gravity;
    whirl_start_kind start;
    double start_omega;
    int mode;
    double perturb;
    unsigned long seed;
    double *theta;
    double *phi;
    double *theta_dot;
    double *phi_dot;
    whirl_frame frame;
    char *method;
    double dt;
    double t_end;
    whirl_formulation formulation;
    double omega;
    double drive_radius;
    double air_drag;
    double air_drag_quadratic;
    double internal_damping;
    double *seed_sigma;
    double *seed_lambda;
    double tol;
    double stop_deviation;
    int threads;
    double every;
    size_t n_columns;
    whirl_column columns[COLUMNS_2_3_0];
    int want[COLUMNS_2_3_0];
    char *trace;
    double trace_every;
    int reference_mode;
    int line[KEYS_2_3_0];
} scene_2_3_0;

#define SAME_FIELD(f)                                                                          \
    do {                                                                                       \
        assert_int_equal(offsetof(whirl_scene, f), offsetof(scene_2_3_0, f));                  \
        assert_int_equal(sizeof(((whirl_scene *)0)->f), sizeof(((scene_2_3_0 *)0)->f));        \
    } while (0)

static void test_layout_is_2_3_0s(void **state)
{
    (void)state;
    assert_int_equal(WHIRL_SCENE_NKEYS, KEYS_2_3_0);
    assert_int_equal(WHIRL_NCOLUMNS, COLUMNS_2_3_0);
    assert_int_equal(WHIRL_KEY_UNITS_SYSTEM, KEYS_2_3_0 - 1); /* the last key of 2.3.0 */
    assert_int_equal(sizeof(whirl_scene), sizeof(scene_2_3_0));
    if (sizeof(void *) == 8 && sizeof(long) == 8 && sizeof(int) == 4)
        assert_int_equal(sizeof(whirl_scene), SIZE_LP64_2_3_0);
    SAME_FIELD(path);
    SAME_FIELD(physical);
    SAME_FIELD(dim);
    SAME_FIELD(links);
    SAME_FIELD(length);
    SAME_FIELD(mass);
    SAME_FIELD(chain_length);
    SAME_FIELD(chain_mass);
    SAME_FIELD(gravity);
    SAME_FIELD(start);
    SAME_FIELD(start_omega);
    SAME_FIELD(mode);
    SAME_FIELD(perturb);
    SAME_FIELD(seed);
    SAME_FIELD(theta);
    SAME_FIELD(phi);
    SAME_FIELD(theta_dot);
    SAME_FIELD(phi_dot);
    SAME_FIELD(frame);
    SAME_FIELD(method);
    SAME_FIELD(dt);
    SAME_FIELD(t_end);
    SAME_FIELD(formulation);
    SAME_FIELD(omega);
    SAME_FIELD(drive_radius);
    SAME_FIELD(air_drag);
    SAME_FIELD(air_drag_quadratic);
    SAME_FIELD(internal_damping);
    SAME_FIELD(seed_sigma);
    SAME_FIELD(seed_lambda);
    SAME_FIELD(tol);
    SAME_FIELD(stop_deviation);
    SAME_FIELD(threads);
    SAME_FIELD(every);
    SAME_FIELD(n_columns);
    SAME_FIELD(columns);
    SAME_FIELD(want);
    SAME_FIELD(trace);
    SAME_FIELD(trace_every);
    SAME_FIELD(reference_mode);
    SAME_FIELD(line);
}

/* ---- reading the key ---- */

static char dir[] = "/tmp/whirl-test-scene-pivot-XXXXXX";
static char path[sizeof dir + 16];

static void write_scene(const char *text)
{
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(text, fp);
    assert_int_equal(fclose(fp), 0);
}

static const char shaken[] =
    "[chain]\n"                   /* 1 */
    "dim = 2\n"                   /* 2 */
    "links = 3\n"                 /* 3 */
    "[start]\n"                   /* 4 */
    "hanging = true\n"            /* 5 */
    "[run]\n"                     /* 6 */
    "omega = 2.5\n"               /* 7 */
    "dt = 0.0078125\n"            /* 8 */
    "t_end = 2\n"                 /* 9 */
    "pivot = vertical:0.05\n"     /* 10 */
    "[output]\n"                  /* 11 */
    "every = 0.25\n";             /* 12 */

/* The scene text with the overrides sets[0..n) must fail with_pivot with a one-line message
 * "PATH" tail... (tail a prefix), nothing kept. */
static void expect_message(const char *text, const char *const *sets, size_t n, const char *tail)
{
    whirl_scene s;
    whirl_scene_pivot p;
    write_scene(text);
    assert_int_equal(whirl_scene_parse_with_pivot(path, sets, n, &s, &p), GSL_EINVAL);
    assert_int_equal(p.given, 0);
    assert_null(s.path);
    const char *msg = whirl_last_error();
    assert_null(strchr(msg, '\n'));
    char want[600];
    snprintf(want, sizeof want, "%s%s", path, tail);
    if (strncmp(msg, want, strlen(want)) != 0) fail_msg("got '%s', want '%s...'", msg, want);
}

static void test_read_beside_the_scene(void **state)
{
    (void)state;
    whirl_scene s;
    whirl_scene_pivot p;
    write_scene(shaken);
    assert_int_equal(whirl_scene_parse_with_pivot(path, NULL, 0, &s, &p), GSL_SUCCESS);
    whirl_pivot_path want;
    assert_int_equal(whirl_pivot_parse("vertical:0.05", 2.5, 0, 2, &want), GSL_SUCCESS);
    assert_int_equal(p.given, 1);
    assert_int_equal(p.line, 10);
    assert_memory_equal(&p.path, &want, sizeof want);
    whirl_scene_free(&s);

    /* an override replaces it (line -1); --pivot's text, in the scene's units */
    const char *const sets[] = {"run.pivot = line:0.1"};
    assert_int_equal(whirl_scene_parse_with_pivot(path, sets, 1, &s, &p), GSL_SUCCESS);
    assert_int_equal(p.line, -1);
    assert_true(p.path.c[0][0] == 0.1 && p.path.c[2][0] == 0);
    assert_int_equal(whirl_scene_pivot_from_text(&s, "fourier:x1c=0.01,z2s=-0.02", &p),
                     GSL_SUCCESS);
    assert_true(p.given == 1 && p.line == 0 && p.path.harmonics == 2);
    assert_true(p.path.c[0][0] == 0.01 && p.path.s[2][1] == -0.02 && p.path.omega == 2.5);
    whirl_scene_pivot keep = p;
    assert_int_equal(whirl_scene_pivot_from_text(&s, "circle:1cm", &p), GSL_EINVAL);
    assert_string_equal(whirl_last_error(), "'circle:1cm' has a unit, but the scene is "
                        "dimensionless: give [units] system = SI (lengths in m), or lengths in "
                        "units of L");
    assert_memory_equal(&p, &keep, sizeof p); /* unchanged */
    whirl_scene_free(&s);

    /* absent: given 0, the path zero */
    assert_int_equal(whirl_scene_parse_with_pivot(path, (const char *const[]){"run.pivot="}, 1,
                                                  &s, &p),
                     GSL_EINVAL);
    write_scene("[chain]\ndim = 3\nlinks = 2\n[start]\nhanging = true\n[run]\ndt = 0.01\n"
                "t_end = 1\n");
    assert_int_equal(whirl_scene_parse_with_pivot(path, NULL, 0, &s, &p), GSL_SUCCESS);
    assert_int_equal(p.given, 0);
    assert_true(p.path.omega == 0 && p.path.c[0][0] == 0);
    whirl_scene_free(&s);

    /* SI: lengths in m, with their suffixes; the rate in rad/s */
    write_scene("[units]\nsystem = SI\n[chain]\ndim = 3\nlinks = 2\nlength = 60cm\n[start]\n"
                "hanging = true\n[run]\nomega = 2Hz\ndt = 1ms\nt_end = 1\n"
                "pivot = ellipse:2cm,15mm\n");
    assert_int_equal(whirl_scene_parse_with_pivot(path, NULL, 0, &s, &p), GSL_SUCCESS);
    assert_true(fabs(p.path.c[0][0] - 0.02) < 1e-17 && fabs(p.path.s[1][0] - 0.015) < 1e-17);
    assert_true(p.path.omega == s.omega && fabs(s.omega - 4 * 3.141592653589793) < 1e-14);
    whirl_scene_free(&s);
}

/* whirl_scene_parse has no room for the path: it refuses the key, naming it and the function
 * that reads it; a scene without the key it reads as before. */
static void test_refused_without_room(void **state)
{
    (void)state;
    whirl_scene s;
    write_scene(shaken);
    assert_int_equal(whirl_scene_parse(path, NULL, 0, &s), GSL_EINVAL);
    char want[600];
    snprintf(want, sizeof want, "%s:10: [run] pivot: not read by whirl_scene_parse, whose "
             "whirl_scene has no field for it: this program needs whirl_scene_parse_with_pivot",
             path);
    assert_string_equal(whirl_last_error(), want);
    assert_null(s.path);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    assert_int_equal(whirl_scene_parse_stream(fp, path, NULL, 0, &s), GSL_EINVAL);
    fclose(fp);
    const char *const sets[] = {"run.pivot=circle:0.1"};
    write_scene("[chain]\ndim = 3\nlinks = 2\n[start]\nhanging = true\n[run]\ndt = 0.01\n"
                "t_end = 1\nomega = 1\n");
    assert_int_equal(whirl_scene_parse(path, sets, 1, &s), GSL_EINVAL);
    assert_int_equal(whirl_scene_parse(path, NULL, 0, &s), GSL_SUCCESS);
    whirl_scene_free(&s);
}

static void test_bad_input(void **state)
{
    (void)state;
    static const struct {
        const char *set[2];
        const char *tail;
    } bad[] = {
        {{"run.pivot=square:1"}, ": --set run.pivot: pivot path 'square': unknown kind"},
        {{"run.pivot="}, ": --set run.pivot: must not be empty"},
        {{"run.omega=0"}, ":10: [run] pivot: a pivot path needs [run] omega > 0: the path's rate"},
        {{"run.drive_radius=0.1"}, ":10: [run] pivot: a pivot path conflicts with [run] "
                                   "drive_radius: give one motion of the pivot"},
        {{"chain.dim=3", "run.frame=rotating"}, ":10: [run] pivot: a pivot path needs [run] "
                                                "frame = inertial"},
        {{"run.pivot=ellipse:0.1,0.1"}, ": --set run.pivot: pivot path: term y1s moves the "
                                        "pivot out of the x-z plane of a planar model"},
        {{"run.pivot=circle:5cm"}, ": --set run.pivot: 'circle:5cm' has a unit, but the scene "
                                   "is dimensionless"},
        {{"run.pivot=fourier:x9c=0.1"}, ": --set run.pivot: pivot path: term 'x9c' is not"},
        {{"run.pivot=eight:0.1"}, ": --set run.pivot: pivot path: eight takes eight:A,B, got 1 "
                                  "argument"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        expect_message(shaken, bad[i].set, bad[i].set[1] ? 2 : 1, bad[i].tail);
    /* in the file: its line */
    char text[sizeof shaken + 16];
    snprintf(text, sizeof text, "%s", shaken);
    memcpy(strstr(text, "vertical:0.05"), "vertical:0.0x", 13);
    expect_message(text, NULL, 0, ":10: [run] pivot: pivot path: vertical A: '0.0x' is not a "
                   "length");
}

/* The header's "# pivot = " line reads back (whirl_pivot_parse) to the same path, bit for bit. */
static void test_header_reads_back(void **state)
{
    (void)state;
    static const char *const paths[] = {("fourier:x1c=0.1234567890123456789,y1s=-1e-3,"
                                         "z3c=2.5e-7,x2s=0.3333333333333333"),
                                        "eight:0.2,0.1", "circle:0.05", "line:0"};
    whirl_scene s;
    whirl_scene_pivot p;
    write_scene("[chain]\ndim = 3\nlinks = 2\n[start]\nhanging = true\n[run]\ndt = 0.01\n"
                "t_end = 1\nomega = 0.7\n");
    assert_int_equal(whirl_scene_parse_with_pivot(path, NULL, 0, &s, &p), GSL_SUCCESS);
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
        assert_int_equal(whirl_scene_pivot_from_text(&s, paths[i], &p), GSL_SUCCESS);
        FILE *fp = tmpfile();
        assert_non_null(fp);
        assert_int_equal(whirl_scene_write_header_with_pivot(fp, &s, &p), GSL_SUCCESS);
        rewind(fp);
        char line[1024], *text = NULL;
        int units_after = 0;
        while (fgets(line, sizeof line, fp))
            if (strncmp(line, "# pivot = ", 10) == 0) text = strdup(line + 10);
            else if (text && strncmp(line, "# units:", 8) == 0) units_after = 1;
        fclose(fp);
        assert_non_null(text);
        assert_true(units_after); /* before the units line and the column names */
        text[strcspn(text, "\n")] = '\0';
        whirl_pivot_path back;
        if (whirl_pivot_parse(text, s.omega, 0, 3, &back) != GSL_SUCCESS)
            fail_msg("'%s' (from '%s'): %s", text, paths[i], whirl_last_error());
        if (memcmp(&back, &p.path, sizeof back) != 0) fail_msg("'%s' from '%s'", text, paths[i]);
        free(text);
    }
    /* without a path: no such line, as whirl_scene_write_header */
    p.given = 0;
    FILE *a = tmpfile(), *b = tmpfile();
    assert_int_equal(whirl_scene_write_header_with_pivot(a, &s, &p), GSL_SUCCESS);
    assert_int_equal(whirl_scene_write_header(b, &s), GSL_SUCCESS);
    assert_int_equal(ftell(a), ftell(b));
    fclose(a);
    fclose(b);
    whirl_scene_free(&s);
}

/* ---- runs ---- */

typedef struct capture {
    double rows[64][WHIRL_NCOLUMNS];
    double pivots[64][3];
    size_t n_rows, n_frames;
} capture;

static int on_row(void *ctx, const double *value)
{
    capture *c = ctx;
    if (c->n_rows < 64) memcpy(c->rows[c->n_rows], value, sizeof c->rows[0]);
    c->n_rows++;
    return 0;
}

static int on_frame(void *ctx, double t, const double *pivot, const double *x, size_t n)
{
    (void)t, (void)x, (void)n;
    capture *c = ctx;
    if (c->n_frames < 64) memcpy(c->pivots[c->n_frames], pivot, sizeof c->pivots[0]);
    c->n_frames++;
    return 0;
}

static void run(const char *const *sets, size_t n, capture *c)
{
    whirl_scene s;
    whirl_scene_pivot p;
    assert_int_equal(whirl_scene_parse_with_pivot(path, sets, n, &s, &p), GSL_SUCCESS);
    s.trace_every = s.every; /* frames without a file: the callback */
    whirl_scene_work *w = whirl_scene_work_alloc_with_pivot(&s, &p);
    if (w == NULL) fail_msg("%s", whirl_last_error());
    memset(c, 0, sizeof *c);
    const whirl_scene_output out = {.row = on_row, .frame = on_frame, .ctx = c};
    whirl_scene_result res;
    assert_int_equal(whirl_scene_work_run(w, &out, &res), GSL_SUCCESS);
    assert_int_equal(res.rows, c->n_rows);
    whirl_scene_work_free(w);
    whirl_scene_free(&s);
}

/* The planar line path along x, eps cos(omega t), against the planar drive of radius eps (which
 * moves along x): the same motion, and the same pivot in the trace, to round-off; the angle start
 * moves with the pivot in both. */
static void test_line_path_is_the_planar_drive(void **state)
{
    (void)state;
    static const char swinging[] = "[chain]\ndim = 2\nlinks = 3\n[start]\ntheta = 0.3, -0.2, 0.1\n"
                                   "[run]\nomega = 2.5\ndt = 0.0078125\nt_end = 2\n[output]\n"
                                   "every = 0.25\n";
    capture a, b;
    write_scene(swinging);
    const char *const path_sets[] = {"run.pivot=line:0.08"};
    const char *const drive_sets[] = {"run.drive_radius=0.08"};
    run(path_sets, 1, &a);
    run(drive_sets, 1, &b);
    assert_int_equal(a.n_rows, 9);
    assert_int_equal(b.n_rows, 9);
    assert_int_equal(a.n_frames, 9);
    double worst = 0, pivot = 0, moved = 0;
    for (size_t r = 0; r < a.n_rows; r++) {
        for (int k = 0; k < WHIRL_NCOLUMNS; k++) worst = fmax(worst, fabs(a.rows[r][k] - b.rows[r][k]));
        for (int k = 0; k < 3; k++) pivot = fmax(pivot, fabs(a.pivots[r][k] - b.pivots[r][k]));
        moved = fmax(moved, fabs(a.rows[r][WHIRL_COLUMN_TIP_X] - a.rows[0][WHIRL_COLUMN_TIP_X]));
    }
    print_message("# planar line path vs drive_radius: rows %.2g, pivot %.2g (the tip moved "
                  "%.2g)\n", worst, pivot, moved);
    assert_true(moved > 0.05);
    assert_true(worst < 1e-13);
    assert_true(pivot < 1e-15);
    /* the pivot at t = 0 where both start it, at (eps, 0, 0) */
    assert_true(a.pivots[0][0] == 0.08 && a.pivots[0][1] == 0 && a.pivots[0][2] == 0);
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
    remove(path);
    return rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_layout_is_2_3_0s),
        cmocka_unit_test(test_read_beside_the_scene),
        cmocka_unit_test(test_refused_without_room),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_header_reads_back),
        cmocka_unit_test(test_line_path_is_the_planar_drive),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
