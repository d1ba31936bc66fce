/* Tests of the pivot paths (whirl/periodic.h) and of the dynamics' pivot callback
 * (whirl_dyn_set_pivot): the presets' formulas, the derivatives against central differences of
 * the position, the parser's terms and its one-line errors, and a run with the circle as a path
 * against the same run with whirl_model's circle drive (the same equations reached two ways). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "whirl/periodic.h"

static void test_presets(void **state)
{
    (void)state;
    whirl_pivot_path p;
    const double w = 3, t = 0.37;
    double x[3], v[3], a[3];
    assert_int_equal(whirl_pivot_ellipse(&p, w, 0.1, 0.06), GSL_SUCCESS);
    whirl_pivot_eval(t, x, v, a, &p);
    assert_true(fabs(x[0] - 0.1 * cos(w * t)) < 1e-16 && fabs(x[1] - 0.06 * sin(w * t)) < 1e-16);
    assert_true(x[2] == 0);
    assert_true(fabs(a[0] + w * w * x[0]) < 1e-15 && fabs(a[1] + w * w * x[1]) < 1e-15);
    const double dir[3] = {0, 3, 4};
    assert_int_equal(whirl_pivot_line(&p, w, 0.5, dir), GSL_SUCCESS);
    whirl_pivot_eval(0, x, v, a, &p);
    assert_true(fabs(x[1] - 0.3) < 1e-16 && fabs(x[2] - 0.4) < 1e-16 && x[0] == 0);
    assert_int_equal(whirl_pivot_eight(&p, w, 0.2, 0.1), GSL_SUCCESS);
    whirl_pivot_eval(t, x, v, a, &p);
    assert_true(fabs(x[0] - 0.2 * sin(w * t)) < 1e-16 && fabs(x[1] - 0.1 * sin(2 * w * t)) < 1e-16);
    assert_true(fabs(whirl_pivot_period(&p) - 2 * M_PI / w) < 1e-15);
    /* derivatives against central differences of the position (step 1e-4: error ~ 1e-8 w^3) */
    const double h = 1e-4;
    double xp[3], xm[3], vp[3], vm[3], dummy[3];
    whirl_pivot_eval(t + h, xp, vp, dummy, &p);
    whirl_pivot_eval(t - h, xm, vm, dummy, &p);
    for (int k = 0; k < 3; k++) {
        assert_true(fabs((xp[k] - xm[k]) / (2 * h) - v[k]) < 1e-6);
        assert_true(fabs((vp[k] - vm[k]) / (2 * h) - a[k]) < 1e-6);
    }
    const double zero[3] = {0, 0, 0};
    assert_int_equal(whirl_pivot_line(&p, w, 0.5, zero), GSL_EINVAL);
    assert_int_equal(whirl_pivot_circle(&p, 0, 0.1), GSL_EINVAL);
    assert_int_equal(whirl_pivot_circle(&p, w, NAN), GSL_EINVAL);
}

static void test_parse(void **state)
{
    (void)state;
    whirl_pivot_path p, q;
    /* SI units: a chain of 0.5 m, 1 cm is 0.02 L */
    assert_int_equal(whirl_pivot_parse("ellipse:1cm,0.6cm", 2, 0.5, 3, &p), GSL_SUCCESS);
    assert_true(fabs(p.c[0][0] - 0.02) < 1e-17 && fabs(p.s[1][0] - 0.012) < 1e-17);
    assert_int_equal(whirl_pivot_parse("vertical:0.1", 2, 0, 2, &p), GSL_SUCCESS);
    assert_true(p.c[2][0] == 0.1 && p.c[0][0] == 0);
    assert_int_equal(whirl_pivot_parse("line:0.1,1,0,1", 2, 0, 2, &p), GSL_SUCCESS);
    assert_true(fabs(p.c[0][0] - 0.1 / sqrt(2)) < 1e-17 && fabs(p.c[2][0] - 0.1 / sqrt(2)) < 1e-17);
    assert_int_equal(whirl_pivot_parse("fourier:x1c=0.1,y1s=0.06", 2, 0, 3, &q), GSL_SUCCESS);
    assert_int_equal(whirl_pivot_parse("ellipse:0.1,0.06", 2, 0, 3, &p), GSL_SUCCESS);
    assert_memory_equal(&p, &q, sizeof p);
    assert_int_equal(whirl_pivot_parse("fourier:z3s=2mm", 2, 1, 3, &p), GSL_SUCCESS);
    assert_int_equal(p.harmonics, 3);
    assert_true(fabs(p.s[2][2] - 0.002) < 1e-18);
    /* bad input: a one-line message naming the term; the path unchanged */
    const struct {
        const char *text;
        double length;
        int dim;
        const char *names;
    } bad[] = {{"ellipse:1cm", 0.5, 3, "ellipse:A,B"},
               {"ellipse:1cm,x", 0.5, 3, "ellipse B"},
               {"circle:1cm", 0, 3, "has a unit"},
               {"square:1", 0, 3, "unknown kind"},
               {"circle", 0, 3, "circle:R"},
               {"circle:", 0, 3, "circle:R"},
               {"line:1,0,0", 0, 3, "line takes"},
               {"line:1,0,0,0", 0, 3, "direction is zero"},
               {"fourier:x9c=1", 0, 3, "'x9c'"},
               {"fourier:w1c=1", 0, 3, "'w1c'"},
               {"fourier:x1c", 0, 3, "'x1c' has no '='"},
               {"fourier:x1c=1,x1c=2", 0, 3, "'x1c' is given twice"},
               {"fourier:x1q=1", 0, 3, "'x1q'"},
               {"fourier:y1c=1", 0, 2, "y1c"},
               {"ellipse:1,1", 0, 2, "y1s"},
               {"circle:1e999", 0, 3, "circle R"},
               {"circle:nan", 0, 3, "circle R"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        memset(&p, 0x5a, sizeof p);
        memcpy(&q, &p, sizeof p);
        assert_int_equal(whirl_pivot_parse(bad[i].text, 2, bad[i].length, bad[i].dim, &p),
                         GSL_EINVAL);
        const char *msg = whirl_last_error();
        if (strstr(msg, bad[i].names) == NULL)
            fail_msg("'%s': message '%s' lacks '%s'", bad[i].text, msg, bad[i].names);
        assert_null(strchr(msg, '\n'));
        assert_memory_equal(&p, &q, sizeof p);
    }
    assert_int_equal(whirl_pivot_parse("circle:0.1", 0, 0, 3, &p), GSL_EINVAL);
    assert_int_equal(whirl_pivot_parse("circle:0.1", INFINITY, 0, 3, &p), GSL_EINVAL);
}

/* The pivot's circle given as a path moves the chain as whirl_model's drive does: the two runs
 * evaluate the same formulas, so they agree to round-off. */
static void test_circle_path_is_the_drive(void **state)
{
    (void)state;
    const size_t n = 6;
    const double omega = 2.5, eps = 0.08;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    assert_non_null(c);
    const whirl_model drive = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL,
                               .omega = omega, .drive_radius = eps};
    const whirl_model free_pivot = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL,
                                    .omega = omega};
    whirl_dyn *a = whirl_dyn_alloc(&drive, WHIRL_FORMULATION_CARTESIAN);
    whirl_dyn *b = whirl_dyn_alloc(&free_pivot, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(a);
    assert_non_null(b);
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, omega, eps), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_set_pivot(a, whirl_pivot_eval, &path), GSL_EINVAL); /* radius */
    assert_int_equal(whirl_dyn_set_pivot(b, whirl_pivot_eval, &path), GSL_SUCCESS);
    const whirl_ramp ramp = {0, 0.1, 0, 1};
    assert_int_equal(whirl_dyn_set_ramps(b, 0, &ramp, NULL), GSL_EINVAL);
    /* a tilted chain, turned by 0.3 rad from hanging */
    double links[3 * 6];
    for (size_t i = 0; i < n; i++) {
        links[3 * i] = sin(0.3) / n, links[3 * i + 1] = 0, links[3 * i + 2] = -cos(0.3) / n;
    }
    const size_t size = whirl_dyn_size(a);
    double *ya = malloc(size * sizeof *ya), *yb = malloc(size * sizeof *yb);
    assert_int_equal(whirl_dyn_state_from_shape(a, 0, links, 0, ya), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_state_from_shape(b, 0, links, 0, yb), GSL_SUCCESS);
    whirl_integrator *ia = whirl_integrator_alloc("gauss2", a);
    whirl_integrator *ib = whirl_integrator_alloc("gauss2", b);
    double ta = 0, tb = 0;
    assert_int_equal(whirl_integrator_advance(ia, &ta, ya, 5.0, 0.005, 0), GSL_SUCCESS);
    assert_int_equal(whirl_integrator_advance(ib, &tb, yb, 5.0, 0.005, 0), GSL_SUCCESS);
    double worst = 0, moved = 0;
    for (size_t i = 0; i < size; i++) {
        worst = fmax(worst, fabs(ya[i] - yb[i]));
        moved = fmax(moved, fabs(ya[i]));
    }
    print_message("# circle as a path vs the drive after 5 time units: %.2g\n", worst);
    assert_true(moved > 0.1);
    assert_true(worst < 1e-13);
    /* the rotating frame refuses a path; NULL restores the drive */
    const whirl_model rot = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *r = whirl_dyn_alloc(&rot, WHIRL_FORMULATION_CARTESIAN);
    assert_int_equal(whirl_dyn_set_pivot(r, whirl_pivot_eval, &path), GSL_EINVAL);
    assert_int_equal(whirl_dyn_set_pivot(b, NULL, NULL), GSL_SUCCESS);
    whirl_dyn_free(r);
    whirl_integrator_free(ia);
    whirl_integrator_free(ib);
    whirl_dyn_free(a);
    whirl_dyn_free(b);
    free(ya);
    free(yb);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_presets),
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_circle_path_is_the_drive),
    };
    return cmocka_run_group_tests_name("pivot_path", tests, NULL, NULL);
}
