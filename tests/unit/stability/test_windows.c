/* Tests of the exact stability windows (src/stability/nlink_windows.c) against independent results:
 *  - the reduced eigenvalues mu = lambda^2 (size 2N) against the squares of the first-order
 *    form's eigenvalues (size 4N, whirl_stability_eigenvalues), and the growth rates;
 *  - the Krein signatures: at a neutral rate the modes of negative energy number half the
 *    negative eigenvalues of K (GSL's symmetric eigensolver), one fewer pair inside a window;
 *  - every located edge against the first-order form's growth just inside (> 0) and just outside
 *    (0), and the windows against a grid of rates;
 *  - the same windows from a coarse scan (windows between scan points found through the ranks),
 *    a fine one, and full eigen-solves instead of Arnoldi;
 *  - perturbed runs of the dynamics just inside an edge (grow) and just outside (stay bounded);
 *  - the same above 64 rows, where the dense solve runs on a worker thread;
 *  - bad input and the stop request. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_math.h>

#include "whirl/stability.h"

#define WMAX 16

/* A non-uniform chain: the reduction must hold for any lengths, masses and g. */
static whirl_chain *odd_chain(size_t n)
{
    double len[32], mass[32];
    for (size_t i = 0; i < n; i++) {
        len[i] = 0.11 + 0.07 * sin(1.7 * (double)i + 0.3);
        mass[i] = 0.13 + 0.05 * cos(2.3 * (double)i);
    }
    return whirl_chain_alloc(n, len, mass, 1.37);
}

static whirl_model model_of(const whirl_chain *c, double omega)
{
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = omega;
    return m;
}

/* Negative eigenvalues of the stiffness K (2N x 2N) of the last linearisation. */
static int negative_directions(const whirl_stability *w, size_t n)
{
    const size_t q = 2 * n;
    gsl_matrix *k = gsl_matrix_alloc(q, q);
    gsl_vector *eval = gsl_vector_alloc(q);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(q);
    memcpy(k->data, whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS),
           q * q * sizeof(double));
    double scale = gsl_matrix_max(k) - gsl_matrix_min(k);
    assert_int_equal(gsl_eigen_symm(k, eval, ws), 0);
    int count = 0;
    for (size_t i = 0; i < q; i++) count += gsl_vector_get(eval, i) < -1e-10 * scale;
    gsl_eigen_symm_free(ws);
    gsl_vector_free(eval);
    gsl_matrix_free(k);
    return count;
}

/* The 4N first-order form's growth of mode k at omega (whirl_stability_mode). */
static double growth4(whirl_stability *w, const whirl_chain *c, int mode, double omega)
{
    whirl_model m = model_of(c, omega);
    whirl_shape_info info;
    double g;
    assert_int_equal(whirl_stability_mode(w, &m, mode, &info, &g), 0);
    return g;
}

static void test_reduced_spectrum(void **state)
{
    (void)state;
    const size_t n = 9;
    whirl_chain *c = odd_chain(n);
    whirl_stability *lin = whirl_stability_alloc(n);
    whirl_windows *w = whirl_windows_alloc(n);
    double crit[3];
    assert_int_equal(whirl_nlink_critical(c, 3, crit), 0);
    int unstable = 0, neutral = 0;
    for (int mode = 1; mode <= 3; mode++)
        for (int j = 0; j < 14; j++) {
            const double omega = crit[mode - 1] * (1.02 + 0.21 * j);
            whirl_model m = model_of(c, omega);
            whirl_shape_info info;
            double g4;
            assert_int_equal(whirl_stability_mode(lin, &m, mode, &info, &g4), 0);
            size_t count4;
            const double *re4, *im4;
            assert_int_equal(whirl_stability_eigenvalues(lin, &count4, &re4, &im4), 0);
            whirl_spectrum sp;
            assert_int_equal(whirl_windows_spectrum(w, lin, 1, &sp), 0);
            assert_int_equal(sp.count, 2 * n - 1);
            assert_int_equal(count4, 4 * n - 2);
            double big = 0;
            for (size_t i = 0; i < sp.count; i++) big = fmax(big, hypot(sp.re[i], sp.im[i]));
            /* every mu is the square of an eigenvalue of the first-order form, and back */
            for (size_t i = 0; i < sp.count; i++) {
                double best = INFINITY;
                for (size_t k = 0; k < count4; k++)
                    best = fmin(best, hypot(re4[k] * re4[k] - im4[k] * im4[k] - sp.re[i],
                                            2 * re4[k] * im4[k] - sp.im[i]));
                assert_true(best <= 1e-9 * big);
            }
            for (size_t k = 0; k < count4; k++) {
                double best = INFINITY;
                for (size_t i = 0; i < sp.count; i++)
                    best = fmin(best, hypot(re4[k] * re4[k] - im4[k] * im4[k] - sp.re[i],
                                            2 * re4[k] * im4[k] - sp.im[i]));
                assert_true(best <= 1e-9 * big);
            }
            assert_true(fabs(sp.growth - g4) <= 1e-8 * sqrt(big));
            /* the two mu nearest a shift by Arnoldi: those of the full solve */
            const double sigma = sp.re[sp.count / 3] + 0.0123;
            size_t near[2] = {0, 0};
            double dist[2] = {INFINITY, INFINITY};
            for (size_t i = 0; i < sp.count; i++) {
                const double d = hypot(sp.re[i] - sigma, sp.im[i]);
                if (d < dist[0])
                    dist[1] = dist[0], near[1] = near[0], dist[0] = d, near[0] = i;
                else if (d < dist[1])
                    dist[1] = d, near[1] = i;
            }
            double pre[2], pim[2], sre[2], sim[2];
            for (int t = 0; t < 2; t++) sre[t] = sp.re[near[t]], sim[t] = sp.im[near[t]];
            assert_int_equal(whirl_windows_pair(w, lin, sigma, pre, pim), 0);
            for (int t = 0; t < 2; t++)
                assert_true(hypot(pre[t] - sre[t], fabs(pim[t]) - fabs(sim[t])) <= 1e-9 * big);
            assert_int_equal(whirl_windows_spectrum(w, lin, 1, &sp), 0);
            /* Krein signatures: k - 1 modes of negative energy when neutral (K has 2(k - 1)
             * negative directions), fewer when a pair has left the axis */
            int negative = 0, unsigned_neutral = 0;
            for (size_t i = 0; i < sp.count; i++) {
                negative += sp.signature[i] < 0;
                unsigned_neutral += sp.signature[i] == 0 && sp.im[i] == 0 && sp.re[i] < 0;
            }
            const int nu = negative_directions(lin, n);
            assert_int_equal(nu, 2 * (mode - 1));
            assert_int_equal(unsigned_neutral, 0);
            if (sp.growth == 0) {
                assert_int_equal(negative, nu / 2);
                neutral++;
            } else {
                assert_true(negative < nu / 2 || mode == 1);
                unstable++;
            }
        }
    print_message("# reduced spectrum: %d neutral, %d unstable shapes checked\n", neutral,
                  unstable);
    assert_true(neutral > 10 && unstable > 5);
    whirl_windows_free(w);
    whirl_stability_free(lin);
    whirl_chain_free(c);
}

/* Above 64 rows the dense solve runs on a worker thread (a stop request ends it at once): 40
 * links, eigenvalues and left eigenvectors (signatures) from it, against the first-order form. */
static void test_worker_spectrum(void **state)
{
    (void)state;
    const size_t n = 40;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.2);
    whirl_stability *lin = whirl_stability_alloc(n);
    whirl_windows *w = whirl_windows_alloc(n);
    double crit[3];
    assert_int_equal(whirl_nlink_critical(c, 3, crit), 0);
    for (int mode = 2; mode <= 3; mode++)
        for (int j = 0; j < 3; j++) {
            whirl_model m = model_of(c, crit[mode - 1] * (1.1 + 0.7 * j));
            double g4;
            assert_int_equal(whirl_stability_mode(lin, &m, mode, NULL, &g4), 0);
            size_t count4;
            const double *re4, *im4;
            assert_int_equal(whirl_stability_eigenvalues(lin, &count4, &re4, &im4), 0);
            whirl_spectrum sp;
            assert_int_equal(whirl_windows_spectrum(w, lin, 1, &sp), 0);
            assert_int_equal(sp.count, 2 * n - 1);
            double big = 0, worst = 0;
            for (size_t i = 0; i < sp.count; i++) big = fmax(big, hypot(sp.re[i], sp.im[i]));
            for (size_t i = 0; i < sp.count; i++) {
                double best = INFINITY;
                for (size_t k = 0; k < count4; k++)
                    best = fmin(best, hypot(re4[k] * re4[k] - im4[k] * im4[k] - sp.re[i],
                                            2 * re4[k] * im4[k] - sp.im[i]));
                worst = fmax(worst, best);
            }
            int negative = 0;
            for (size_t i = 0; i < sp.count; i++) negative += sp.signature[i] < 0;
            print_message("# 40 links, mode %d, omega %.4g: mu vs lambda^2 %.2g (scale %.3g), "
                          "growth %.6g / %.6g, %d of negative energy\n", mode, m.omega, worst,
                          big, sp.growth, g4, negative);
            assert_true(worst <= 1e-9 * big);
            assert_true(fabs(sp.growth - g4) <= 1e-8 * sqrt(big));
            if (sp.growth == 0) assert_int_equal(negative, mode - 1);
        }
    whirl_windows_free(w);
    whirl_stability_free(lin);
    whirl_chain_free(c);
}

static void test_edges(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *lin = whirl_stability_alloc(n);
    whirl_windows *w = whirl_windows_alloc(n);
    for (int mode = 2; mode <= 3; mode++) {
        whirl_windows_params p = whirl_windows_defaults();
        p.omega_min = 2.4;
        p.omega_max = 8.1;
        whirl_window win[WMAX], coarse[WMAX], full[WMAX];
        size_t count, count_coarse, count_full;
        whirl_windows_stats st;
        assert_int_equal(whirl_windows_find(w, c, mode, &p, win, WMAX, &count, &st), 0);
        print_message("# mode %d: %zu windows, %zu solves (%zu with vectors)\n", mode, count,
                      st.solves_vectors + st.solves_values + st.solves_krylov,
                      st.solves_vectors);
        assert_true(count >= 2);
        assert_true(st.solves_vectors + st.solves_values + st.solves_krylov < 1000);
        for (size_t i = 0; i < count; i++) {
            print_message("#   [%.12f, %.12f] max %.6g at %.6f\n", win[i].from, win[i].to,
                          win[i].max_growth, win[i].at);
            assert_true(win[i].from < win[i].at && win[i].at <= win[i].to);
            assert_true(win[i].max_growth > 0);
            /* the first-order form's growth at the largest growth */
            assert_true(fabs(growth4(lin, c, mode, win[i].at) - win[i].max_growth) <=
                        1e-8 * (1 + win[i].max_growth));
            /* just outside: neutral; just inside: growing */
            const double d = 2e-7;
            if (!win[i].open_from) {
                assert_true(growth4(lin, c, mode, win[i].from - d) == 0);
                assert_true(growth4(lin, c, mode, win[i].from + d) > 0);
            }
            if (!win[i].open_to) {
                assert_true(growth4(lin, c, mode, win[i].to - d) > 0);
                assert_true(growth4(lin, c, mode, win[i].to + d) == 0);
            }
        }
        /* a grid of rates: growing exactly inside the windows */
        for (int j = 0; j <= 120; j++) {
            const double omega = st.omega_from + (p.omega_max - st.omega_from) * (j + 0.5) / 121.0;
            int inside = 0;
            for (size_t i = 0; i < count; i++)
                inside |= omega >= win[i].from && omega <= win[i].to;
            assert_int_equal(growth4(lin, c, mode, omega) > 0, inside);
        }
        /* the same windows from a scan twice as coarse and with full eigen-solves */
        whirl_windows_params q = p;
        q.scan_step = 0.5;
        assert_int_equal(whirl_windows_find(w, c, mode, &q, coarse, WMAX, &count_coarse, &st), 0);
        q = p;
        q.krylov = 0;
        q.tol = 1e-12;
        assert_int_equal(whirl_windows_find(w, c, mode, &q, full, WMAX, &count_full, &st), 0);
        assert_int_equal(st.solves_krylov, 0);
        assert_int_equal(count_coarse, count);
        assert_int_equal(count_full, count);
        for (size_t i = 0; i < count; i++) {
            assert_true(fabs(coarse[i].from - win[i].from) < 2e-9);
            assert_true(fabs(coarse[i].to - win[i].to) < 2e-9);
            assert_true(fabs(full[i].from - win[i].from) < 2e-9);
            assert_true(fabs(full[i].to - win[i].to) < 2e-9);
            assert_true(fabs(full[i].max_growth - win[i].max_growth) < 1e-9);
        }
    }
    whirl_windows_free(w);
    whirl_stability_free(lin);
    whirl_chain_free(c);
}

/* Perturbed runs just inside and just outside the first edge of mode 2 (N = 10). */
static void test_runs_at_edges(void **state)
{
    (void)state;
    const size_t n = 10;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *lin = whirl_stability_alloc(n);
    whirl_windows *w = whirl_windows_alloc(n);
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 3;
    p.omega_max = 5;
    whirl_window win[WMAX];
    size_t count;
    whirl_windows_stats st;
    assert_int_equal(whirl_windows_find(w, c, 2, &p, win, WMAX, &count, &st), 0);
    assert_int_equal(count, 1);
    const double edges[2] = {win[0].from, win[0].to};
    for (int e = 0; e < 2; e++)
        for (int side = -1; side <= 1; side += 2) {
            const double d = 0.01 * (win[0].to - win[0].from);
            const double omega = edges[e] + side * d;
            const int inside = (e == 0) == (side > 0);
            whirl_model m = model_of(c, omega);
            whirl_shape_info info;
            double g;
            assert_int_equal(whirl_stability_mode(lin, &m, 2, &info, &g), 0);
            whirl_stability_run_params rp = whirl_stability_run_defaults();
            rp.method = "rk4";
            rp.perturbation = 1e-7;
            rp.periods = inside ? 1.2 * (log(1e4) + 6) / g * omega / (2 * M_PI) : 150;
            whirl_stability_run_result r;
            assert_int_equal(whirl_stability_run(&m, info.tip_r, &rp, &r), 0);
            print_message("# edge %.9f %s: omega %.6f eig %.5g sim %.5g max %.3g\n", edges[e],
                          inside ? "inside" : "outside", omega, g, r.sim_growth,
                          r.max_deviation);
            if (inside) {
                assert_int_equal(r.verdict, WHIRL_VERDICT_UNSTABLE);
                assert_true(fabs(r.sim_growth / g - 1) < 0.05);
            } else {
                assert_true(g == 0);
                assert_int_equal(r.verdict, WHIRL_VERDICT_STABLE);
            }
        }
    whirl_windows_free(w);
    whirl_stability_free(lin);
    whirl_chain_free(c);
}

static void test_errors(void **state)
{
    (void)state;
    const size_t n = 6;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0), *other = whirl_chain_alloc_uniform(7, 0);
    whirl_windows *w = whirl_windows_alloc(n);
    whirl_stability *lin = whirl_stability_alloc(n);
    whirl_window win[WMAX];
    size_t count;
    whirl_windows_stats st;
    whirl_windows_params p = whirl_windows_defaults();
    assert_null(whirl_windows_alloc(0));
    assert_int_equal(whirl_windows_find(w, other, 2, &p, win, WMAX, &count, &st), GSL_EINVAL);
    assert_int_equal(whirl_windows_find(w, c, 7, &p, win, WMAX, &count, &st), GSL_EINVAL);
    assert_int_equal(whirl_windows_find(w, c, 0, &p, win, WMAX, &count, &st), GSL_EINVAL);
    p.omega_max = 2;
    assert_int_equal(whirl_windows_find(w, c, 3, &p, win, WMAX, &count, &st), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "mode 3"));
    p = whirl_windows_defaults();
    p.tol = 0;
    assert_int_equal(whirl_windows_find(w, c, 2, &p, win, WMAX, &count, &st), GSL_EINVAL);
    p = whirl_windows_defaults();
    p.omega_min = 5, p.omega_max = 4;
    assert_int_equal(whirl_windows_find(w, c, 2, &p, win, WMAX, &count, &st), GSL_EINVAL);
    p = whirl_windows_defaults();
    assert_int_equal(whirl_windows_find(w, c, 2, &p, win, 0, &count, &st), GSL_EINVAL);
    assert_true(count > 0);
    /* a stop request ends the search */
    whirl_stop_request();
    assert_int_equal(whirl_windows_find(w, c, 2, &p, win, WMAX, &count, &st), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    /* damping: not the conservative chain */
    whirl_model m = model_of(c, 4);
    m.internal_damping = 0.01;
    double g;
    assert_int_equal(whirl_stability_mode(lin, &m, 2, NULL, &g), 0);
    whirl_spectrum sp;
    assert_int_equal(whirl_windows_spectrum(w, lin, 0, &sp), GSL_EINVAL);
    whirl_windows_free(NULL);
    whirl_windows_free(w);
    whirl_stability_free(lin);
    whirl_chain_free(other);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reduced_spectrum),
        cmocka_unit_test(test_worker_spectrum),
        cmocka_unit_test(test_edges),
        cmocka_unit_test(test_runs_at_edges),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
