/* Tests of the scene parser: values and defaults, lines, overrides, long and continued lists,
 * and one exact message for every kind of bad input. */
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

static char dir[] = "/tmp/whirl-test-scene-XXXXXX";
static char path[sizeof dir + 16];

static void write_scene(const char *text)
{
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(text, fp);
    assert_int_equal(fclose(fp), 0);
}

static int parse(const char *text, const char *const *overrides, size_t n, whirl_scene *s)
{
    write_scene(text);
    return whirl_scene_parse(path, overrides, n, s);
}

/* A valid 3D scene with a steady start; the lines are numbered in the comments. */
static const char steady_scene[] =
    "; a mode-2 chain\n"                /* 1 */
    "[chain]\n"                         /* 2 */
    "dim = 3\n"                         /* 3 */
    "links = 4\n"                       /* 4 */
    "[start]\n"                         /* 5 */
    "omega = 3.125\n"                   /* 6 */
    "mode = 2\n"                        /* 7 */
    "perturb = 0.0125 ; radians\n"      /* 8 */
    "[run]\n"                           /* 9 */
    "frame = rotating\n"                /* 10 */
    "dt = 0.002385\n"                   /* 11 */
    "t_end = 1.5\n"                     /* 12 */
    "[output]\n"                        /* 13 */
    "columns = tip_x, deviation, t\n";  /* 14 */

static void test_values_and_defaults(void **state)
{
    (void)state;
    whirl_scene s;
    assert_int_equal(parse(steady_scene, NULL, 0, &s), GSL_SUCCESS);
    assert_string_equal(s.path, path);
    assert_int_equal(s.dim, 3);
    assert_int_equal(s.links, 4);
    for (size_t i = 0; i < 4; i++) {
        assert_true(s.length[i] == 0.25);
        assert_true(s.mass[i] == 0.25);
    }
    assert_true(s.gravity == 1);
    assert_int_equal(s.start, WHIRL_START_STEADY);
    assert_true(s.start_omega == 3.125);
    assert_int_equal(s.mode, 2);
    assert_true(s.perturb == 0.0125);
    assert_int_equal(s.seed, 1);
    assert_null(s.theta);
    assert_int_equal(s.frame, WHIRL_FRAME_ROTATING);
    assert_string_equal(s.method, "gauss2");
    assert_true(s.dt == 0.002385);
    assert_true(s.t_end == 1.5);
    assert_int_equal(s.formulation, WHIRL_FORMULATION_CARTESIAN);
    assert_true(s.omega == 3.125); /* the frame rate defaults to the start's */
    assert_true(s.drive_radius == 0 && s.air_drag == 0 && s.air_drag_quadratic == 0);
    assert_true(s.internal_damping == 0 && s.tol == 0 && s.stop_deviation == 0);
    assert_null(s.seed_sigma);
    assert_true(s.every == s.dt);
    assert_null(s.trace);
    /* t first whatever its place in the list, then the order given */
    assert_int_equal(s.n_columns, 3);
    assert_int_equal(s.columns[0], WHIRL_COLUMN_T);
    assert_int_equal(s.columns[1], WHIRL_COLUMN_TIP_X);
    assert_int_equal(s.columns[2], WHIRL_COLUMN_DEVIATION);
    assert_true(s.want[WHIRL_COLUMN_DEVIATION] && !s.want[WHIRL_COLUMN_ENERGY]);
    assert_int_equal(s.line[WHIRL_KEY_CHAIN_DIM], 3);
    assert_int_equal(s.line[WHIRL_KEY_RUN_DT], 11);
    assert_int_equal(s.line[WHIRL_KEY_OUTPUT_COLUMNS], 14);
    assert_int_equal(s.line[WHIRL_KEY_RUN_OMEGA], 0);
    char where[256], expect[256];
    snprintf(expect, sizeof expect, "%s:11: [run] dt", path);
    assert_string_equal(whirl_scene_where(&s, WHIRL_KEY_RUN_DT, where, sizeof where), expect);
    snprintf(expect, sizeof expect, "%s: [run] omega", path);
    assert_string_equal(whirl_scene_where(&s, WHIRL_KEY_RUN_OMEGA, where, sizeof where), expect);
    whirl_scene_free(&s);
    assert_null(s.path);
    whirl_scene_free(&s); /* twice is harmless */
    whirl_scene_free(NULL);
}

static void test_default_columns_and_angles(void **state)
{
    (void)state;
    whirl_scene s;
    assert_int_equal(parse("[chain]\ndim = 2\nlinks = 2\nlengths = 0.375, 0.625\n"
                           "masses = 0.5,1.5\ngravity = 9.81\n"
                           "[start]\ntheta = 1.25, -0.5\ntheta_dot = 0, 0.75\n"
                           "[run]\nmethod = gauss3\ndt = 0.01\nt_end = 2\nformulation = seed\n"
                           "seed_sigma = 0.1, 0.2\nseed_lambda = 0.3, 0.4\ntol = 1e-9\n"
                           "[output]\nevery = 0.5\ntrace = out.dat\n",
                           NULL, 0, &s),
                     GSL_SUCCESS);
    assert_true(s.length[0] == 0.375 && s.length[1] == 0.625);
    assert_true(s.mass[0] == 0.5 && s.mass[1] == 1.5 && s.gravity == 9.81);
    assert_int_equal(s.start, WHIRL_START_ANGLES);
    assert_true(s.theta[0] == 1.25 && s.theta[1] == -0.5);
    assert_true(s.theta_dot[0] == 0 && s.theta_dot[1] == 0.75);
    assert_true(s.phi[0] == 0 && s.phi[1] == 0 && s.phi_dot[0] == 0 && s.phi_dot[1] == 0);
    assert_int_equal(s.frame, WHIRL_FRAME_INERTIAL);
    assert_string_equal(s.method, "gauss3");
    assert_int_equal(s.formulation, WHIRL_FORMULATION_SEED);
    assert_true(s.omega == 0);
    assert_true(s.seed_sigma[1] == 0.2 && s.seed_lambda[0] == 0.3 && s.tol == 1e-9);
    assert_true(s.every == 0.5 && s.trace_every == 0.5);
    /* a trace named in the file is relative to the scene's folder */
    char trace[sizeof dir + 16];
    snprintf(trace, sizeof trace, "%s/out.dat", dir);
    assert_string_equal(s.trace, trace);
    /* all columns but the deviation, in the documented order */
    assert_int_equal(s.n_columns, WHIRL_NCOLUMNS - 1);
    for (size_t c = 0; c < s.n_columns; c++) assert_int_equal(s.columns[c], (int)c);
    assert_false(s.want[WHIRL_COLUMN_DEVIATION]);
    whirl_scene_free(&s);

    assert_int_equal(parse("[chain]\ndim=3\nlinks=1\n[start]\nhanging = yes\n[run]\ndt=1\n"
                           "t_end=2\ndrive_radius=0.05\nair_drag=0.2\nair_drag_quadratic=0.1\n"
                           "internal_damping=0.01\nomega=2.5\nstop_deviation=0.3\n",
                           NULL, 0, &s),
                     GSL_SUCCESS);
    assert_int_equal(s.start, WHIRL_START_HANGING);
    assert_true(s.omega == 2.5 && s.drive_radius == 0.05 && s.air_drag == 0.2);
    assert_true(s.air_drag_quadratic == 0.1 && s.internal_damping == 0.01);
    assert_true(s.stop_deviation == 0.3);
    whirl_scene_free(&s);
}

/* Lists longer than inih's 200-character line, on one line and continued over indented lines;
 * the line numbers stay right. */
/* The hanging start takes perturb and seed; reference_mode lets any start have a deviation. */
static void test_perturbed_hanging_and_reference(void **state)
{
    (void)state;
    whirl_scene s;
    assert_int_equal(parse("[chain]\ndim = 3\nlinks = 5\n[start]\nhanging = yes\nperturb = 0.0125\n"
                           "seed = 17\n[run]\ndt = 0.01\nt_end = 1\nomega = 2.385\n"
                           "[output]\ncolumns = deviation\nreference_mode = 1\n",
                           NULL, 0, &s),
                     GSL_SUCCESS);
    assert_int_equal(s.start, WHIRL_START_HANGING);
    assert_true(s.perturb == 0.0125);
    assert_int_equal(s.seed, 17);
    assert_int_equal(s.reference_mode, 1);
    assert_true(s.want[WHIRL_COLUMN_DEVIATION]);
    whirl_scene_free(&s);
    assert_int_equal(parse("[chain]\ndim = 3\nlinks = 2\n[start]\ntheta = 0.1, 0.2\n[run]\n"
                           "dt = 0.01\nt_end = 1\nomega = 3\n[output]\ncolumns = deviation\n"
                           "reference_mode = 2\n",
                           NULL, 0, &s),
                     GSL_SUCCESS);
    assert_int_equal(s.start, WHIRL_START_ANGLES);
    assert_int_equal(s.reference_mode, 2);
    assert_true(s.perturb == 0);
    whirl_scene_free(&s);
}

static void test_long_lists(void **state)
{
    (void)state;
    const size_t n = 100;
    size_t cap = 64 * n + 1024, used = 0;
    char *text = malloc(cap);
    assert_non_null(text);
    used += (size_t)snprintf(text + used, cap - used, "[chain]\ndim = 3\nlinks = %zu\nmasses = ", n);
    for (size_t i = 0; i < n; i++)
        used += (size_t)snprintf(text + used, cap - used, "%s%.17g", i ? ", " : "", 0.01 + 1e-4 * (double)i);
    used += (size_t)snprintf(text + used, cap - used, " ; a comment\n[start]\ntheta = 0.5");
    for (size_t i = 1; i < n; i++)
        used += (size_t)snprintf(text + used, cap - used, "%s%.3f", i % 10 ? ", " : "\n    ",
                                 0.5 + 0.001 * (double)i);
    snprintf(text + used, cap - used, "\n[run]\ndt = 0.1\nt_end = 1\n");
    whirl_scene s;
    assert_int_equal(parse(text, NULL, 0, &s), GSL_SUCCESS);
    assert_true(strlen(strchr(text, 'm')) > 200);
    for (size_t i = 0; i < n; i++) {
        assert_true(s.mass[i] == 0.01 + 1e-4 * (double)i);
        assert_true(fabs(s.theta[i] - (0.5 + 0.001 * (double)i)) < 1e-12);
    }
    assert_int_equal(s.line[WHIRL_KEY_START_THETA], 6);
    assert_int_equal(s.line[WHIRL_KEY_RUN_DT], 17);
    whirl_scene_free(&s);
    free(text);
}

static void test_overrides(void **state)
{
    (void)state;
    const char *const set[] = {"run.dt=0.001", "output.trace_every = 0.25", "output.trace=x.dat",
                               "start.seed=42"};
    whirl_scene s;
    assert_int_equal(parse(steady_scene, set, 4, &s), GSL_SUCCESS);
    assert_true(s.dt == 0.001 && s.every == 0.001 && s.trace_every == 0.25);
    assert_string_equal(s.trace, "x.dat");
    assert_int_equal(s.seed, 42);
    assert_int_equal(s.line[WHIRL_KEY_RUN_DT], -1);
    char where[256], expect[256];
    snprintf(expect, sizeof expect, "%s: --set run.dt", path);
    assert_string_equal(whirl_scene_where(&s, WHIRL_KEY_RUN_DT, where, sizeof where), expect);
    whirl_scene_free(&s);
}

/* Bad input: each case gives exactly this message after "PATH". */
typedef struct bad_case {
    const char *text;
    const char *override;
    const char *message;
} bad_case;

#define CHAIN3 "[chain]\ndim = 3\nlinks = 2\n"
#define CHAIN2 "[chain]\ndim = 2\nlinks = 2\n"
#define HANG "[start]\nhanging = true\n"
#define RUN "[run]\ndt = 0.01\nt_end = 1\n"

static const bad_case bad_cases[] = {
    {"[chain]\ndim = 3\n[chian]\nlinks = 2\n", NULL,
     ":3: [chian]: unknown section (known: chain, start, run, output)"},
    {CHAIN3 "[output]\n[extra]\n", NULL,
     ":5: [extra]: unknown section (known: chain, start, run, output)"},
    {CHAIN3 "[run]\ndtt = 1\n", NULL,
     ":5: [run] dtt: unknown key (known: frame, method, dt, t_end, formulation, omega, "
     "drive_radius, air_drag, air_drag_quadratic, internal_damping, seed_sigma, seed_lambda, "
     "tol, stop_deviation, threads, pivot)"},
    {"dim = 3\n[chain]\n", NULL, ":1: dim: key outside any section"},
    {CHAIN3 "[run]\ndt 0.1\n", NULL, ":5: syntax error: expected [section] or key = value"},
    {CHAIN3 "[run]\ndt = 0.1\n\ndt = 0.2\n", NULL, ":7: [run] dt: given twice (first at line 5)"},
    {"[chain]\nlinks = 2\n" HANG RUN, NULL, ": [chain] dim: missing"},
    {"[chain]\ndim = 3\n" HANG RUN, NULL, ": [chain] links: missing"},
    {CHAIN3 HANG "[run]\nt_end = 1\n", NULL, ": [run] dt: missing"},
    {CHAIN3 HANG "[run]\ndt = 1\n", NULL, ": [run] t_end: missing"},
    {CHAIN3 RUN, NULL,
     ": [start] mode: missing: give one start (omega and mode, theta, or hanging = true)"},
    {CHAIN3 "[start]\nomega = 2\n" RUN, NULL,
     ": [start] mode: missing (the steady start needs omega and mode)"},
    {CHAIN3 "[start]\nmode = 2\n" RUN, NULL,
     ": [start] omega: missing (the steady start needs omega and mode)"},
    {CHAIN3 "[start]\nperturb = 0.1\n" RUN, NULL,
     ": [start] mode: missing: give one start (omega and mode, theta, or hanging = true)"},
    {CHAIN3 "[start]\ntheta = 0.1, 0.2\nperturb = 0.1\n" RUN, NULL,
     ":6: [start] perturb: applies to the steady and the hanging start, not to theta"},
    {CHAIN3 HANG "perturb = -1\n" RUN, NULL, ":6: [start] perturb: must be >= 0, got -1"},
    {CHAIN3 "[start]\ntheta_dot = 0.1, 0.2\n" RUN, NULL,
     ": [start] theta: missing (the angle start needs theta)"},
    {CHAIN3 "[start]\nomega = 2\nmode = 1\ntheta = 0.1, 0.2\n" RUN, NULL,
     ":7: [start] theta: conflicts with [start] omega (line 5): give one start (omega and "
     "mode, theta, or hanging)"},
    {CHAIN3 "[start]\ntheta = 0.1,0.2\nhanging = 1\n" RUN, NULL,
     ":6: [start] hanging: conflicts with [start] theta (line 5): give one start (omega and "
     "mode, theta, or hanging)"},
    {CHAIN3 "[start]\nhanging = false\n" RUN, NULL,
     ":5: [start] hanging: must be true when given (false is no start)"},
    {CHAIN3 "[start]\nhanging = maybe\n" RUN, NULL,
     ":5: [start] hanging: must be one of false, true, no, yes, 0, 1, off, on, got 'maybe'"},
    {CHAIN2 "[start]\nomega = 2\nmode = 1\n" RUN, NULL,
     ":6: [start] mode: a steady start needs [chain] dim = 3, got 2"},
    {CHAIN3 "[start]\nomega = 2\nmode = 0\n" RUN, NULL, ":6: [start] mode: must be in 1..2, got 0"},
    {CHAIN3 "[start]\nomega = -2\nmode = 1\n" RUN, NULL, ":5: [start] omega: must be > 0, got -2"},
    {CHAIN3 "[start]\nomega = 2\nmode = 1\nperturb = -0.1\n" RUN, NULL,
     ":7: [start] perturb: must be >= 0, got -0.1"},
    {CHAIN3 "[start]\nomega = 2\nmode = 1\nseed = x\n" RUN, NULL,
     ":7: [start] seed: must be an integer, got 'x'"},
    {CHAIN2 "[start]\ntheta = 0.1, 0.2\nphi = 0, 0\n" RUN, NULL,
     ":6: [start] phi: not used in 2D (dim = 2)"},
    {CHAIN2 "[start]\ntheta = 0.1, 0.2\nphi_dot = 0, 0\n" RUN, NULL,
     ":6: [start] phi_dot: not used in 2D (dim = 2)"},
    {CHAIN3 "[start]\ntheta = 0.1, 0.2, 0.3\n" RUN, NULL,
     ":5: [start] theta: expected 2 values (links = 2), got 3"},
    {CHAIN3 "[start]\ntheta = 0.1, 0.2\nphi_dot = 1\n" RUN, NULL,
     ":6: [start] phi_dot: expected 2 values (links = 2), got 1"},
    {CHAIN3 "[start]\ntheta = 0.1, \n" RUN, NULL,
     ":5: [start] theta: value 2 must be a finite number, got ''"},
    {CHAIN3 "lengths = 0.5\n" HANG RUN, NULL,
     ":4: [chain] lengths: expected 2 values (links = 2), got 1"},
    {CHAIN3 "masses = 1,2,3\n" HANG RUN, NULL,
     ":4: [chain] masses: expected 2 values (links = 2), got 3"},
    {CHAIN3 "lengths = 0.5, 0\n" HANG RUN, NULL, ":4: [chain] lengths: value 2 must be > 0, got 0"},
    {CHAIN3 "masses = -1, 1\n" HANG RUN, NULL, ":4: [chain] masses: value 1 must be > 0, got -1"},
    {CHAIN3 "masses = nan, 1\n" HANG RUN, NULL,
     ":4: [chain] masses: value 1 must be a finite number (optionally with kg or g), got 'nan'"},
    {CHAIN3 "gravity = 0\n" HANG RUN, NULL, ":4: [chain] gravity: must be > 0, got 0"},
    {"[chain]\ndim = 4\nlinks = 2\n" HANG RUN, NULL, ":2: [chain] dim: must be in 2..3, got 4"},
    {"[chain]\ndim = 3\nlinks = 0\n" HANG RUN, NULL, ":3: [chain] links: must be in 1..1000000, got 0"},
    {"[chain]\ndim = 3\nlinks = 2.5\n" HANG RUN, NULL, ":3: [chain] links: must be an integer, got '2.5'"},
    {CHAIN3 HANG "[run]\ndt = -1\nt_end = 1\n", NULL, ":7: [run] dt: must be > 0, got -1"},
    {CHAIN3 HANG "[run]\ndt = 0\nt_end = 1\n", NULL, ":7: [run] dt: must be > 0, got 0"},
    {CHAIN3 HANG "[run]\ndt = NaN\nt_end = 1\n", NULL,
     ":7: [run] dt: must be a finite number (optionally with s or ms), got 'NaN'"},
    {CHAIN3 HANG "[run]\ndt = 1e999\nt_end = 1\n", NULL,
     ":7: [run] dt: must be a finite number (optionally with s or ms), got '1e999'"},
    {CHAIN3 HANG "[run]\ndt = 0.1\nt_end = -inf\n", NULL,
     ":8: [run] t_end: must be a finite number (optionally with s or ms), got '-inf'"},
    {CHAIN3 HANG RUN "frame = spinning\n", NULL,
     ":9: [run] frame: must be one of inertial, rotating, got 'spinning'"},
    {CHAIN2 HANG RUN "frame = rotating\n", NULL,
     ":9: [run] frame: rotating needs [chain] dim = 3, got 2"},
    {CHAIN3 HANG RUN "method =\n", NULL, ":9: [run] method: must not be empty"},
    {CHAIN3 HANG RUN "formulation = angles\n", NULL,
     ":9: [run] formulation: must be one of default, seed, got 'angles'"},
    {CHAIN3 HANG RUN "omega = x\n", NULL, ":9: [run] omega: must be a finite number (optionally with rad/s, Hz or rpm), got 'x'"},
    /* a unit in a dimensionless scene: no scale to convert it with */
    {CHAIN3 HANG RUN "omega = 4Hz\n", NULL, ":9: [run] omega: 4Hz has a unit, but the scene is "
     "dimensionless: give [units] system = SI (lengths in m, masses in kg, rates in rad/s), or a "
     "number in units of sqrt(g/L)"},
    {CHAIN3 HANG "[run]\ndt = 1ms\nt_end = 1\n", NULL, ":7: [run] dt: 1ms has a unit, but the "
     "scene is dimensionless: give [units] system = SI (lengths in m, masses in kg, rates in "
     "rad/s), or a number in units of sqrt(L/g)"},
    {CHAIN3 HANG RUN "drive_radius = -0.1\n", NULL, ":9: [run] drive_radius: must be >= 0, got -0.1"},
    {CHAIN3 HANG RUN "air_drag = -1\n", NULL, ":9: [run] air_drag: must be >= 0, got -1"},
    {CHAIN3 HANG RUN "air_drag_quadratic = -1\n", NULL,
     ":9: [run] air_drag_quadratic: must be >= 0, got -1"},
    {CHAIN3 HANG RUN "internal_damping = -1\n", NULL,
     ":9: [run] internal_damping: must be >= 0, got -1"},
    {CHAIN3 HANG RUN "seed_sigma = 1, 2\n", NULL,
     ":9: [run] seed_sigma: 2D only (dim = 2), got dim = 3"},
    {CHAIN2 HANG RUN "seed_lambda = 1\n", NULL,
     ":9: [run] seed_lambda: expected 2 values (links = 2), got 1"},
    {CHAIN3 HANG RUN "tol = -1e-9\n", NULL, ":9: [run] tol: must be >= 0, got -1e-9"},
    {CHAIN3 HANG RUN "stop_deviation = 0\n", NULL, ":9: [run] stop_deviation: must be > 0, got 0"},
    {CHAIN3 "[start]\ntheta = 0.1, 0.2\n" RUN "stop_deviation = 0.1\n", NULL,
     ":9: [run] stop_deviation: the deviation needs a reference: [output] reference_mode, or a "
     "steady start ([start] omega and mode, or hanging); the theta start is not one"},
    {CHAIN3 "[start]\ntheta = 0.1, 0.2\n" RUN "[output]\ncolumns = t, deviation\n", NULL,
     ":10: [output] columns: the deviation needs a reference: [output] reference_mode, or a "
     "steady start ([start] omega and mode, or hanging); the theta start is not one"},
    {CHAIN2 "[start]\ntheta = 0.1, 0.2\n" RUN "omega = 2\n[output]\nreference_mode = 1\n", NULL,
     ":11: [output] reference_mode: needs [chain] dim = 3, got 2"},
    {CHAIN3 HANG RUN "[output]\nreference_mode = 1\n", NULL,
     ":10: [output] reference_mode: needs [run] omega > 0 (the rate of the reference shape)"},
    {CHAIN3 HANG RUN "omega = 2\n[output]\nreference_mode = 0\n", NULL,
     ":11: [output] reference_mode: must be in 1..2, got 0"},
    {CHAIN3 HANG RUN "[output]\ncolumns = t, energy, tipx\n", NULL,
     ":10: [output] columns: unknown column 'tipx' (known: t, tip_x, tip_y, tip_z, energy, "
     "jacobi, lz, constraint, deviation)"},
    {CHAIN3 HANG RUN "[output]\ncolumns = energy, lz, energy\n", NULL,
     ":10: [output] columns: column 'energy' given twice"},
    {CHAIN3 HANG RUN "[output]\nevery = 0\n", NULL, ":10: [output] every: must be > 0, got 0"},
    {CHAIN3 HANG RUN "[output]\ntrace_every = 0.1\n", NULL,
     ":10: [output] trace_every: given without [output] trace"},
    {CHAIN3 HANG RUN "[output]\ntrace =\n", NULL, ":10: [output] trace: must not be empty"},
    /* overrides */
    {CHAIN3 HANG RUN, "run.dt=-1", ": --set run.dt: must be > 0, got -1"},
    {CHAIN3 HANG RUN, "run.dt", ": --set 'run.dt': expected SECTION.KEY=VALUE"},
    {CHAIN3 HANG RUN, "dt=1", ": --set 'dt=1': expected SECTION.KEY=VALUE"},
    {CHAIN3 HANG RUN, "runs.dt=1", ": --set runs.dt: unknown section (known: chain, start, run, output)"},
    {CHAIN3 HANG RUN, "chain.link=1",
     ": --set chain.link: unknown key (known: dim, links, length, lengths, mass, masses, gravity)"},
};

static void test_bad_input(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
        const bad_case *b = &bad_cases[i];
        whirl_scene s;
        const char *const set[] = {b->override};
        int status = parse(b->text, set, b->override ? 1 : 0, &s);
        char expect[1024];
        snprintf(expect, sizeof expect, "%s%s", path, b->message);
        if (status != GSL_EINVAL || strcmp(whirl_last_error(), expect) != 0)
            print_message("case %zu: status %d\n  got:    %s\n  wanted: %s\n", i, status,
                          whirl_last_error(), expect);
        assert_int_equal(status, GSL_EINVAL);
        assert_string_equal(whirl_last_error(), expect);
        assert_null(s.path); /* nothing left allocated */
        assert_null(s.length);
        assert_null(strchr(whirl_last_error(), '\n'));
    }
}

static void test_missing_file(void **state)
{
    (void)state;
    whirl_scene s;
    char missing[sizeof path + 8];
    snprintf(missing, sizeof missing, "%s/none.ini", dir);
    assert_int_equal(whirl_scene_parse(missing, NULL, 0, &s), GSL_EFAILED);
    char expect[256];
    snprintf(expect, sizeof expect, "%s: cannot read: No such file or directory", missing);
    assert_string_equal(whirl_last_error(), expect);
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

/* A scene file's trace stays in its folder (not absolute, no ".."); an override is the command
 * line's and is taken as given. */
static void test_trace_confined(void **state)
{
    (void)state;
    static const char *const bad[] = {"/tmp/victim.txt", "../victim.txt", "a/../../victim.txt",
                                      "..", "a/.."};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[256];
        snprintf(text, sizeof text, "[chain]\ndim = 2\nlinks = 2\n[start]\nhanging = true\n"
                 "[run]\ndt = 0.01\nt_end = 1\n[output]\ntrace = %s\n", bad[i]);
        whirl_scene s;
        assert_int_equal(parse(text, NULL, 0, &s), GSL_EINVAL);
        assert_non_null(strstr(whirl_last_error(), ":10: [output] trace: must"));
    }
    static const char *const set[] = {"output.trace=/tmp/elsewhere/run.dat"};
    whirl_scene s;
    assert_int_equal(parse("[chain]\ndim = 2\nlinks = 2\n[start]\nhanging = true\n[run]\n"
                           "dt = 0.01\nt_end = 1\n[output]\ntrace = sub/..x/run.dat\n", set, 1, &s),
                     GSL_SUCCESS);
    assert_string_equal(s.trace, "/tmp/elsewhere/run.dat");
    whirl_scene_free(&s);
    assert_int_equal(parse("[chain]\ndim = 2\nlinks = 2\n[start]\nhanging = true\n[run]\n"
                           "dt = 0.01\nt_end = 1\n[output]\ntrace = sub/..x/run.dat\n", NULL, 0, &s),
                     GSL_SUCCESS);
    char want[sizeof dir + 32];
    snprintf(want, sizeof want, "%s/sub/..x/run.dat", dir); /* "..x" is a name, not ".." */
    assert_string_equal(s.trace, want);
    whirl_scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values_and_defaults),
        cmocka_unit_test(test_default_columns_and_angles),
        cmocka_unit_test(test_perturbed_hanging_and_reference),
        cmocka_unit_test(test_long_lists),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_trace_confined),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
