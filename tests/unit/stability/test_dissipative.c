/* Tests of the intervals of the dissipative chain (src/stability/dissipative_windows.c) against
 * independent results:
 *  - the small-damping limit: growth / D of the first-order form's eigen-solve against the
 *    first-order perturbation of the conservative chain's neutral eigenvalues (their
 *    eigenvectors from GSL's nonsymmetric eigensolver), d lambda / dD = -lambda v^H C1 v /
 *    v^H (2 lambda M + G) v, the slope of the Kelvin-Tait-Chetaev instability;
 *  - Kelvin-Tait-Chetaev: with internal damping mode 1 (a minimum) converges and mode 2 (a
 *    saddle) grows over the whole range;
 *  - the hand-swung chain with linear drag: the intervals against the sign of the growth on a
 *    grid of rates, and each edge against the growth just outside it on both sides;
 *  - a sign change of the growth between two scan rates that is a jump (the hand-swung shape
 *    found changes branch), shown to be one by the growth on a fine grid: refused, not an edge;
 *  - bad input and the stop request. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_math.h>

#include "whirl/stability.h"

#define IMAX 32

static whirl_model model_of(const whirl_chain *c, double omega)
{
    return (whirl_model){.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
}

/* Largest real part of the eigenvalues of the last linearisation, not rounded to 0. */
static double raw_growth(whirl_stability *w)
{
    size_t count;
    const double *re, *im;
    assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
    double g = -INFINITY;
    for (size_t i = 0; i < count; i++) g = fmax(g, re[i]);
    return g;
}

/* The predicted growth per unit damping of the conservative linearisation in w (M, G, K; C1 the
 * damping matrix at D = 1): max over the eigenvalues lambda = i w != 0 of A = [[0, I],
 * [-M^-1 K, -M^-1 G]] of Re(-lambda v^H C1 v / v^H (2 lambda M + G) v), v the top half of the
 * eigenvector. */
static double predicted_slope(const whirl_stability *w, const double *c1, size_t n)
{
    const size_t q = 2 * n, y = 4 * n;
    const double *mm = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
    const double *gg = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
    const double *kk = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    gsl_matrix *minv = gsl_matrix_alloc(q, q), *a = gsl_matrix_calloc(y, y);
    gsl_permutation *perm = gsl_permutation_alloc(q);
    gsl_matrix *lu = gsl_matrix_alloc(q, q);
    memcpy(lu->data, mm, q * q * sizeof(double));
    int sign;
    gsl_linalg_LU_decomp(lu, perm, &sign);
    gsl_linalg_LU_invert(lu, perm, minv);
    for (size_t i = 0; i < q; i++) {
        gsl_matrix_set(a, i, q + i, 1);
        for (size_t j = 0; j < q; j++) {
            double sk = 0, sg = 0;
            for (size_t l = 0; l < q; l++) {
                sk += gsl_matrix_get(minv, i, l) * kk[l * q + j];
                sg += gsl_matrix_get(minv, i, l) * gg[l * q + j];
            }
            gsl_matrix_set(a, q + i, j, -sk);
            gsl_matrix_set(a, q + i, q + j, -sg);
        }
    }
    gsl_vector_complex *eval = gsl_vector_complex_alloc(y);
    gsl_matrix_complex *evec = gsl_matrix_complex_alloc(y, y);
    gsl_eigen_nonsymmv_workspace *ws = gsl_eigen_nonsymmv_alloc(y);
    assert_int_equal(gsl_eigen_nonsymmv(a, eval, evec, ws), 0);
    double best = -INFINITY, scale = 0;
    for (size_t k = 0; k < y; k++) scale = fmax(scale, gsl_complex_abs(gsl_vector_complex_get(eval, k)));
    for (size_t k = 0; k < y; k++) {
        const gsl_complex lam = gsl_vector_complex_get(eval, k);
        /* the rotation's zeros (a Jordan pair, split by round-off to O(sqrt(eps))) */
        if (gsl_complex_abs(lam) < 1e-6 * scale) continue;
        assert_true(fabs(GSL_REAL(lam)) < 1e-8 * scale); /* neutral: outside a window */
        gsl_complex num = gsl_complex_rect(0, 0), den = gsl_complex_rect(0, 0);
        for (size_t i = 0; i < q; i++)
            for (size_t j = 0; j < q; j++) {
                const gsl_complex vi = gsl_complex_conjugate(gsl_matrix_complex_get(evec, i, k));
                const gsl_complex vj = gsl_matrix_complex_get(evec, j, k);
                const gsl_complex vv = gsl_complex_mul(vi, vj);
                num = gsl_complex_add(num, gsl_complex_mul_real(vv, c1[i * q + j]));
                const gsl_complex d = gsl_complex_add_real(
                    gsl_complex_mul_real(lam, 2 * mm[i * q + j]), gg[i * q + j]);
                den = gsl_complex_add(den, gsl_complex_mul(vv, d));
            }
        const gsl_complex slope =
            gsl_complex_div(gsl_complex_negative(gsl_complex_mul(lam, num)), den);
        best = fmax(best, GSL_REAL(slope));
    }
    gsl_eigen_nonsymmv_free(ws);
    gsl_matrix_complex_free(evec);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(lu);
    gsl_permutation_free(perm);
    gsl_matrix_free(a);
    gsl_matrix_free(minv);
    return best;
}

static void test_small_damping_slope(void **state)
{
    (void)state;
    const size_t n = 8;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    const double q = 2.0 * (double)n;
    double *c1 = malloc((size_t)(q * q) * sizeof *c1);
    /* mode 2 and mode 3 of 8 links at neutral rates (outside their windows) */
    const int modes[3] = {2, 2, 3};
    const double rates[3] = {3.3, 6.0, 5.2};
    for (int t = 0; t < 3; t++) {
        whirl_model m = model_of(c, rates[t]);
        whirl_shape_info info;
        double g0;
        m.internal_damping = 1;
        assert_int_equal(whirl_stability_mode(w, &m, modes[t], &info, &g0), 0);
        memcpy(c1, whirl_stability_get_matrix(w, WHIRL_STABILITY_DAMPING),
               (size_t)(q * q) * sizeof *c1);
        m.internal_damping = 0;
        assert_int_equal(whirl_stability_mode(w, &m, modes[t], &info, &g0), 0);
        assert_true(g0 == 0); /* neutral */
        const double slope = predicted_slope(w, c1, n);
        assert_true(slope > 0); /* Kelvin-Tait-Chetaev: a negative-energy mode grows */
        /* growth / D converges to the slope linearly in D */
        double ratio[2];
        const double d[2] = {1e-5, 1e-4};
        for (int k = 0; k < 2; k++) {
            m.internal_damping = d[k];
            assert_int_equal(whirl_stability_mode(w, &m, modes[t], &info, &g0), 0);
            ratio[k] = raw_growth(w) / d[k];
        }
        print_message("# mode %d, omega %g: slope %.10g, growth/D %.10g (D 1e-5), %.10g (D 1e-4)\n",
                      modes[t], rates[t], slope, ratio[0], ratio[1]);
        assert_true(fabs(ratio[0] - slope) < 1e-3 * slope);
        assert_true(fabs(ratio[1] - slope) < 1e-2 * slope);
        /* first order: the error shrinks with D */
        assert_true(fabs(ratio[0] - slope) < fabs(ratio[1] - slope));
    }
    free(c1);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

static void test_kelvin_tait_chetaev(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(10, 0);
    whirl_model m = model_of(c, 0);
    m.internal_damping = 1e-3;
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 1.5, p.omega_max = 9;
    whirl_dissipative_interval iv[IMAX];
    size_t count;
    whirl_windows_stats st;
    assert_int_equal(whirl_windows_dissipative(&m, 1, 1, &p, iv, IMAX, &count, &st), 0);
    assert_int_equal(count, 1);
    assert_int_equal(iv[0].verdict, WHIRL_VERDICT_CONVERGING);
    assert_true(iv[0].open_from && iv[0].open_to && iv[0].growth < 0);
    assert_true(iv[0].from == 1.5 && iv[0].to == 9);
    for (int mode = 2; mode <= 3; mode++) {
        assert_int_equal(whirl_windows_dissipative(&m, mode, 1, &p, iv, IMAX, &count, &st), 0);
        assert_int_equal(count, 1);
        assert_int_equal(iv[0].verdict, WHIRL_VERDICT_UNSTABLE);
        assert_true(iv[0].open_from && iv[0].open_to && iv[0].growth > 0);
        assert_true(iv[0].to == 9 && st.scan >= 19);
    }
    whirl_chain_free(c);
}

/* The growth of the hand-swung shape at omega (raw), or NAN without a shape. */
static double driven_growth(whirl_stability *w, whirl_model m, int mode, int side, double omega)
{
    m.omega = omega;
    double g;
    const int status = whirl_stability_driven_mode(w, &m, mode, side, NULL, &g);
    if (status == GSL_EDOM) return NAN;
    assert_int_equal(status, 0);
    return raw_growth(w);
}

static void test_driven_intervals(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_model m = model_of(c, 0);
    m.drive_radius = 0.02;
    m.air_drag = 0.01;
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 2, p.omega_max = 9;
    whirl_dissipative_interval iv[IMAX];
    size_t count;
    whirl_windows_stats st;
    assert_int_equal(whirl_windows_dissipative(&m, 2, -1, &p, iv, IMAX, &count, &st), 0);
    print_message("# mode 2, side -1: %zu intervals\n", count);
    int edges = 0, unstable = 0;
    for (size_t i = 0; i < count; i++) {
        print_message("#   %.10f %.10f %s growth %.6g at %.6f\n", iv[i].from, iv[i].to,
                      whirl_verdict_name(iv[i].verdict), iv[i].growth, iv[i].at);
        assert_true(iv[i].from <= iv[i].to);
        if (i > 0) assert_true(iv[i].from >= iv[i - 1].to);
        unstable += iv[i].verdict == WHIRL_VERDICT_UNSTABLE;
        /* the extreme growth has the interval's sign, and is where the growth says */
        assert_true(iv[i].verdict == WHIRL_VERDICT_UNSTABLE ? iv[i].growth > 0 : iv[i].growth < 0);
        const double ga = driven_growth(w, m, 2, -1, iv[i].at);
        assert_true(fabs(ga - iv[i].growth) <= 1e-12 + 1e-9 * fabs(ga));
        if (iv[i].open_to) continue;
        /* an edge: the growth changes sign across it, 1e-7 either side */
        edges++;
        const double below = driven_growth(w, m, 2, -1, iv[i].to - 1e-7);
        const double above = driven_growth(w, m, 2, -1, iv[i].to + 1e-7);
        assert_true(below * above < 0);
        assert_true((below > 0) == (iv[i].verdict == WHIRL_VERDICT_UNSTABLE));
        assert_true(iv[i].freq_to > 0 && iv[i + 1].freq_from == iv[i].freq_to);
    }
    assert_true(edges >= 2 && unstable >= 1);
    /* a grid of rates: the sign of the growth is the verdict of the interval holding it */
    for (double om = 2.05; om < 9; om += 0.1) {
        const double g = driven_growth(w, m, 2, -1, om);
        if (isnan(g)) continue;
        for (size_t i = 0; i < count; i++)
            if (om >= iv[i].from && om <= iv[i].to)
                assert_true((g > 0) == (iv[i].verdict == WHIRL_VERDICT_UNSTABLE));
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* 10 links, eps 0.1, drag 0.1, mode 3, tip on the pivot's side: from omega = 4.276 to 4.280 the
 * hand-swung shape found (whirl_driven_mode) is another branch (index 3, tip 0.18 from the axis,
 * growing at 0.58) than at the rates around it (index 4, tip 0.14, converging at -0.05). A scan
 * of 4.27 and 4.28 sees the growth change sign; Brent's method then converges on the jump at
 * 4.2755, which must be refused rather than reported as an edge. */
static void test_jump_refused(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(10, 0);
    whirl_stability *w = whirl_stability_alloc(10);
    whirl_model m = model_of(c, 0);
    m.drive_radius = 0.1;
    m.air_drag = 0.1;
    /* the jump, independently: on a grid of 1e-3 the growth is smooth (steps below 0.01) but
     * for one step across which it changes by more than 0.5, from < 0 to > 0, and back */
    double prev = driven_growth(w, m, 3, 1, 4.270);
    int up = 0, down = 0;
    for (int i = 1; i <= 15; i++) {
        const double om = 4.270 + 1e-3 * i, g = driven_growth(w, m, 3, 1, om);
        assert_false(isnan(g));
        if (prev < 0 && g > 0 && g - prev > 0.5) up++;
        else if (prev > 0 && g < 0 && prev - g > 0.5) down++;
        else assert_true(fabs(g - prev) < 0.01);
        prev = g;
    }
    assert_int_equal(up, 1);
    assert_int_equal(down, 1);
    /* the scan's rates 4.27 and 4.28 straddle it: opposite growths, and no edge */
    assert_true(driven_growth(w, m, 3, 1, 4.27) < 0 && driven_growth(w, m, 3, 1, 4.28) > 0);
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 4.27, p.omega_max = 4.28, p.scan_step = 0.01;
    whirl_dissipative_interval iv[IMAX];
    size_t count;
    whirl_windows_stats st;
    assert_int_equal(whirl_windows_dissipative(&m, 3, 1, &p, iv, IMAX, &count, &st), GSL_EFAILED);
    assert_non_null(strstr(whirl_last_error(), "the growth jumps"));
    whirl_stability_free(w);
    whirl_chain_free(c);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(6, 0);
    whirl_model m = model_of(c, 0);
    whirl_windows_params p = whirl_windows_defaults();
    whirl_dissipative_interval iv[IMAX];
    size_t count;
    whirl_windows_stats st;
    /* no dissipation */
    assert_int_equal(whirl_windows_dissipative(&m, 2, 1, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    /* drag without a drive */
    m.air_drag = 0.1;
    assert_int_equal(whirl_windows_dissipative(&m, 2, 1, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    m.air_drag = 0, m.internal_damping = 1e-3;
    assert_int_equal(whirl_windows_dissipative(&m, 7, 1, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    assert_int_equal(whirl_windows_dissipative(&m, 2, 0, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    m.internal_damping = NAN;
    assert_int_equal(whirl_windows_dissipative(&m, 2, 1, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    m.internal_damping = 1e-3;
    p.tol = p.scan_step;
    assert_int_equal(whirl_windows_dissipative(&m, 2, 1, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    p = whirl_windows_defaults();
    /* the range ends before the birth */
    p.omega_min = 1, p.omega_max = 2;
    assert_int_equal(whirl_windows_dissipative(&m, 3, 1, &p, iv, IMAX, &count, &st), GSL_EDOM);
    /* too little dissipation to decide */
    p = whirl_windows_defaults();
    m.internal_damping = 1e-14;
    assert_int_equal(whirl_windows_dissipative(&m, 2, 1, &p, iv, IMAX, &count, &st), GSL_EINVAL);
    /* no room */
    m.internal_damping = 0, m.drive_radius = 0.02, m.air_drag = 0.01;
    p.omega_min = 2, p.omega_max = 9;
    assert_int_equal(whirl_windows_dissipative(&m, 2, -1, &p, iv, 1, &count, &st), GSL_EINVAL);
    assert_true(count > 1);
    /* a stop request ends the search */
    whirl_stop_request();
    assert_int_equal(whirl_windows_dissipative(&m, 2, -1, &p, iv, IMAX, &count, &st),
                     WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_small_damping_slope),
        cmocka_unit_test(test_kelvin_tait_chetaev),
        cmocka_unit_test(test_driven_intervals),
        cmocka_unit_test(test_jump_refused),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
