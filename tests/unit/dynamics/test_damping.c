/* Tests of the internal damping (whirl_model.internal_damping) in the time domain against the
 * damped linear analysis (whirl/stability.h) and the steady shapes (whirl_nlink_solve): two
 * independent formulations (Cartesian positions with tension multipliers for the runs; link
 * angles with the Hessians of the co-rotating Lagrangian and of the Rayleigh function for the
 * linearisation) and the shooting of the steady shape. Kelvin-Tait-Chetaev (the manual's theory,
 * "Linearisation and Krein signatures"): with damping only mode 1 is an attractor, so
 *  - from the hanging chain at omega = 2 (N = 8) the run converges to the mode-1 shape, to a
 *    floor of round-off, at the rate of a real eigenvalue of the damped linearisation: the orbit
 *    from the hanging chain arrives along the non-oscillating direction of the second slowest
 *    eigenvalue (the slowest, oscillating one is not excited above the floor; see
 *    tests/bench/bench_damping.c);
 *  - from the mode-1 shape with every link turned by 0.1 rad, the deviation is the sum of the two
 *    slowest modes: the two-rate fit recovers both eigenvalues;
 *  - mode 2 at omega = 5, stable in the conservative model, grows at the damped eig_growth.
 * The runs use tests/lib/damping_run.h (rk4, fixed step). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "whirl/stability.h"
#include "damping_run.h"

#define LINKS 8
#define DAMPING 0.03 /* the slowest decay rates are then 0.038 and 0.045: runs of ~1000 T */

typedef struct {
    whirl_chain *chain;
    whirl_stability *w;
    whirl_model model;
    double r[LINKS + 1], z[LINKS + 1], tension[LINKS + 1], ref[3 * LINKS];
    double rates[4 * LINKS]; /* real parts of the eigenvalues, descending, pairs once */
    size_t count;
    double freq; /* imaginary part of the slowest */
} fixture;

static int descending(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

/* The mode-1 shape at omega, its damped linearisation and the real parts of its eigenvalues. */
static void setup_mode1(fixture *f, double omega)
{
    f->chain = whirl_chain_alloc_uniform(LINKS, 0);
    f->w = whirl_stability_alloc(LINKS);
    assert_non_null(f->chain);
    assert_non_null(f->w);
    f->model = (whirl_model){.chain = f->chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                             .omega = omega, .internal_damping = DAMPING};
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(f->chain, omega, 1, &info), 0);
    assert_int_equal(whirl_nlink_positions(f->chain, omega, info.tip_r, f->r, f->z, f->tension), 0);
    for (size_t i = 0; i < LINKS; i++) {
        f->ref[3 * i] = f->r[i + 1];
        f->ref[3 * i + 1] = 0;
        f->ref[3 * i + 2] = f->z[i + 1];
    }
    double growth;
    assert_int_equal(whirl_stability_shape(f->w, &f->model, info.tip_r, &growth), 0);
    size_t total;
    const double *re, *im;
    assert_int_equal(whirl_stability_eigenvalues(f->w, &total, &re, &im), 0);
    f->count = 0;
    for (size_t i = 0; i < total; i++) {
        if (re[i] == growth) f->freq = fabs(im[i]);
        if (im[i] >= 0) f->rates[f->count++] = re[i];
    }
    qsort(f->rates, f->count, sizeof(double), descending);
    assert_true(growth < 0 && f->rates[0] == growth);
}

static void teardown_fixture(fixture *f)
{
    whirl_stability_free(f->w);
    whirl_chain_free(f->chain);
}

/* Runs from (x0, v0) to a deviation of 1e-10 and a tail of 3 more predicted decades. */
static damping_run_result run_to_floor(const fixture *f, const double *x0, const double *v0)
{
    const double sigma = f->rates[0];
    const damping_run_params p = {"rk4", damping_step(&f->model, f->tension, "rk4"),
                                  2 * M_PI / f->freq / 16, 80 / fabs(sigma) + 2000,
                                  1e-4, 1e-10, 16, sigma, 1e3};
    damping_run_result res;
    assert_int_equal(damping_run(&f->model, f->ref, x0, v0, &p, &res), 0);
    print_message("# peak %.3g, fit %.8g over [%.0f, %.0f] (%zu blocks), two-rate %.8g %.8g, "
                  "final %.3g, eigenvalues %.8g %.8g %.8g\n", res.peak, res.rate, res.fit_from,
                  res.fit_to, res.fit_samples, res.rate_slow, res.rate_fast, res.final_error,
                  f->rates[0], f->rates[1], f->rates[2]);
    assert_true(res.reached);
    return res;
}

static void test_from_hanging_chain(void **state)
{
    (void)state;
    fixture f;
    setup_mode1(&f, 2.0);
    double x0[3 * LINKS], v0[3 * LINKS];
    assert_int_equal(damping_start_hanging(f.chain, 2.0, 1e-2, 3, x0, v0), 0);
    const damping_run_result res = run_to_floor(&f, x0, v0);
    /* it left the hanging chain (0.4 L from the mode-1 shape) and converged to mode 1 */
    assert_true(res.initial > 0.3);
    assert_true(res.final_error < 1e-9);
    /* at the second slowest rate, a real eigenvalue, not at the slowest one */
    assert_true(res.fit_samples >= 10);
    assert_true(fabs(res.rate / f.rates[1] - 1) < 0.05);
    assert_true(fabs(res.rate / f.rates[0] - 1) > 0.1);
    teardown_fixture(&f);
}

static void test_from_turned_shape(void **state)
{
    (void)state;
    fixture f;
    setup_mode1(&f, 2.0);
    double x0[3 * LINKS], v0[3 * LINKS];
    assert_int_equal(damping_start_turned(f.chain, f.r, f.z, 0.1, 5, x0, v0), 0);
    const damping_run_result res = run_to_floor(&f, x0, v0);
    assert_true(res.final_error < 1e-9);
    assert_true(fabs(res.rate_slow / f.rates[0] - 1) < 0.05);
    assert_true(fabs(res.rate_fast / f.rates[1] - 1) < 0.05);
    teardown_fixture(&f);
}

static void test_mode2_grows(void **state)
{
    (void)state;
    const double omega = 5.0;
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    whirl_stability *w = whirl_stability_alloc(LINKS);
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_shape_info info;
    double r[LINKS + 1], z[LINKS + 1], tension[LINKS + 1], neutral, eig;
    /* neutrally stable without damping, growing with it */
    assert_int_equal(whirl_stability_mode(w, &m, 2, &info, &neutral), 0);
    assert_true(neutral == 0);
    m.internal_damping = DAMPING;
    assert_int_equal(whirl_stability_shape(w, &m, info.tip_r, &eig), 0);
    assert_true(eig > 0.01);
    assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, tension), 0);
    whirl_stability_run_params p = whirl_stability_run_defaults();
    p.method = "rk4";
    p.dt = damping_step(&m, tension, "rk4");
    p.perturbation = 1e-6;
    p.periods = (log(1e4) + 6) / eig * omega / (2 * M_PI) + 20;
    whirl_stability_run_result res;
    assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &res), 0);
    print_message("# mode 2, omega 5: eig_growth %.8g, sim_growth %.8g over [%.1f, %.1f]\n", eig,
                  res.sim_growth, res.fit_from, res.fit_to);
    assert_int_equal(res.verdict, WHIRL_VERDICT_UNSTABLE);
    assert_true(fabs(res.sim_growth / eig - 1) < 0.05);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_from_hanging_chain),
        cmocka_unit_test(test_from_turned_shape),
        cmocka_unit_test(test_mode2_grows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
