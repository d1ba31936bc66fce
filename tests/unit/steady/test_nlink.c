/* Tests of the N-link steady shapes (src/nlink.c) against independent physics:
 * - the conical pendulum (N = 1): cos(theta) = g / (omega^2 l), T = m omega^2 l;
 * - critical rates against GSL's dense generalized symmetric eigensolver (K x = w^2 M x), and
 *   against the continuum's j_{0,k}/2 with an error of order 1/N;
 * - every solved shape: the gradient of the effective potential
 *   V = sum_i m_i (g z_i - omega^2 r_i^2 / 2) with respect to each link angle vanishes (a
 *   second formulation of equilibrium), link lengths kept, pivot on the axis, k-1 crossings;
 * - near-critical, high rates, tip mass; branch continuation equals fresh solves;
 * - the error paths. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_sf_bessel.h>
#include <gsl/gsl_sort_vector.h>

#include "whirl/steady.h"

/* The largest relative force imbalance of a mass and relative gradient of V over the link
 * angles, and geometric checks. */
static double equilibrium_residual(const whirl_chain *c, double omega, const whirl_shape_info *info)
{
    size_t n = c->n;
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(r);
    assert_int_equal(whirl_nlink_positions(c, omega, info->tip_r, r, z, t), GSL_SUCCESS);
    /* the pivot on the axis to round-off in the tip radius: |r0| <~ eps a |dr0/da| */
    double h = 1e-6 * info->tip_r, r0_plus, r0_minus;
    assert_int_equal(whirl_nlink_positions(c, omega, info->tip_r + h, r, z, t), GSL_SUCCESS);
    r0_plus = r[0];
    assert_int_equal(whirl_nlink_positions(c, omega, info->tip_r - h, r, z, t), GSL_SUCCESS);
    r0_minus = r[0];
    double dr0_da = (r0_plus - r0_minus) / (2 * h);
    assert_int_equal(whirl_nlink_positions(c, omega, info->tip_r, r, z, t), GSL_SUCCESS);
    assert_true(fabs(r[0]) <= 4 * DBL_EPSILON * (info->tip_r * fabs(dr0_da) + 1));
    assert_true(z[0] == 0);
    double worst = 0;
    /* the force balance of every mass with the returned tensions: link i pulls mass i towards
     * mass i-1, link i+1 towards mass i+1 */
    for (size_t i = 1; i <= n; i++) {
        double m = c->mass[i - 1], w2 = omega * omega;
        double fr = m * w2 * r[i] - t[i] * (r[i] - r[i - 1]) / c->length[i - 1];
        double fz = -m * c->gravity - t[i] * (z[i] - z[i - 1]) / c->length[i - 1];
        if (i < n) {
            fr += t[i + 1] * (r[i + 1] - r[i]) / c->length[i];
            fz += t[i + 1] * (z[i + 1] - z[i]) / c->length[i];
        }
        worst = fmax(worst, hypot(fr, fz) / t[i]);
    }
    for (size_t j = 1; j <= n; j++) {
        double dr = r[j] - r[j - 1], dz = z[j] - z[j - 1], l = c->length[j - 1];
        assert_true(fabs(hypot(dr, dz) - l) <= 1e-14 * l);
        double sin_t = dr / l, cos_t = -dz / l;
        /* dV/dtheta_j = sum_{i >= j} m_i l_j (g sin theta_j - omega^2 r_i cos theta_j) */
        double grad = 0, scale = 0;
        for (size_t i = j; i <= n; i++) {
            double m = c->mass[i - 1];
            grad += m * l * (c->gravity * sin_t - omega * omega * r[i] * cos_t);
            scale += m * l * (c->gravity + omega * omega * fabs(r[i]));
        }
        worst = fmax(worst, fabs(grad) / scale);
    }
    /* the crossings: sign changes of r[1..n] */
    int crossings = 0;
    for (size_t i = 2; i <= n; i++) crossings += (r[i] > 0) != (r[i - 1] > 0);
    assert_int_equal(crossings, info->mode - 1);
    assert_true(r[n] > 0);
    free(r);
    return worst;
}

static void test_conical_pendulum(void **state)
{
    (void)state;
    double l = 1.385, m = 0.731, g = 9.81;
    whirl_chain *c = whirl_chain_alloc(1, &l, &m, g);
    assert_non_null(c);
    double crit;
    assert_int_equal(whirl_nlink_critical(c, 1, &crit), GSL_SUCCESS);
    assert_float_equal(crit, sqrt(g / l), 1e-15 * crit);
    for (double f = 1.0001; f < 100; f *= 3.7) {
        double omega = f * crit;
        whirl_shape_info info;
        assert_int_equal(whirl_nlink_solve(c, omega, 1, &info), GSL_SUCCESS);
        double cos_t = g / (omega * omega * l);
        double sin_t = sqrt((1 - cos_t) * (1 + cos_t));
        assert_float_equal(info.tip_r, l * sin_t, 1e-13 * l * sin_t);
        assert_float_equal(info.depth, l * cos_t, 1e-13 * l);
        assert_float_equal(info.top_tension, m * omega * omega * l, 1e-13 * m * omega * omega * l);
        assert_int_equal(info.n_nodes, 0);
    }
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(c, 0.999 * crit, 1, &info), GSL_EDOM);
    assert_int_equal(whirl_nlink_solve(c, 2 * crit, 2, &info), GSL_EDOM);
    whirl_chain_free(c);
}

/* A chain with unequal links and masses (high-entropy values). */
static whirl_chain *irregular_chain(size_t n)
{
    double *l = malloc(n * sizeof *l), *m = malloc(n * sizeof *m);
    for (size_t i = 0; i < n; i++) {
        l[i] = 0.3 + 0.217 * sin(1.7 * (double)i + 0.3);
        m[i] = 0.5 + 0.383 * cos(2.3 * (double)i);
    }
    whirl_chain *c = whirl_chain_alloc(n, l, m, 2.385);
    free(l);
    free(m);
    return c;
}

/* Critical rates from the dense generalized problem K x = lambda M x with GSL (gensymm). */
static void dense_critical(const whirl_chain *c, double *omega)
{
    size_t n = c->n;
    gsl_matrix *k = gsl_matrix_calloc(n, n), *mm = gsl_matrix_calloc(n, n);
    gsl_vector *eval = gsl_vector_alloc(n);
    gsl_eigen_gensymm_workspace *w = gsl_eigen_gensymm_alloc(n);
    /* static tension of link i (0-based): weight of masses i..n-1 */
    for (size_t i = 0; i < n; i++) {
        double t = 0;
        for (size_t j = i; j < n; j++) t += c->mass[j] * c->gravity;
        double s = t / c->length[i];
        /* link i couples mass i-1 and mass i (mass -1 is the pivot) */
        *gsl_matrix_ptr(k, i, i) += s;
        if (i > 0) {
            *gsl_matrix_ptr(k, i - 1, i - 1) += s;
            *gsl_matrix_ptr(k, i - 1, i) -= s;
            *gsl_matrix_ptr(k, i, i - 1) -= s;
        }
        gsl_matrix_set(mm, i, i, c->mass[i]);
    }
    assert_int_equal(gsl_eigen_gensymm(k, mm, eval, w), GSL_SUCCESS);
    gsl_sort_vector(eval);
    for (size_t i = 0; i < n; i++) omega[i] = sqrt(gsl_vector_get(eval, i));
    gsl_eigen_gensymm_free(w);
    gsl_vector_free(eval);
    gsl_matrix_free(k);
    gsl_matrix_free(mm);
}

static void test_critical_vs_dense(void **state)
{
    (void)state;
    size_t sizes[] = {1, 2, 7, 60};
    for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++) {
        size_t n = sizes[s];
        whirl_chain *c = irregular_chain(n);
        assert_non_null(c);
        double *mine = malloc(n * sizeof *mine), *dense = malloc(n * sizeof *dense);
        assert_int_equal(whirl_nlink_critical(c, n, mine), GSL_SUCCESS);
        dense_critical(c, dense);
        for (size_t k = 0; k < n; k++) {
            assert_float_equal(mine[k], dense[k], 1e-11 * dense[k]);
            if (k > 0) assert_true(mine[k] > mine[k - 1]);
        }
        free(mine);
        free(dense);
        whirl_chain_free(c);
    }
}

/* whirl_nlink_critical_report: the rates of whirl_nlink_critical, reported block by block (done
 * increasing to nmodes, total nmodes throughout); a stop requested from the report ends the
 * call with WHIRL_EINTERRUPTED after the block under way, those rates kept. */
typedef struct critical_calls {
    size_t calls, last, total, stop_after;
    int increasing;
} critical_calls;

static void count_critical(void *ctx, size_t done, size_t total)
{
    critical_calls *k = ctx;
    k->increasing &= done > k->last && done <= total;
    k->last = done;
    k->total = total;
    if (++k->calls == k->stop_after) whirl_stop_request();
}

static void test_critical_report(void **state)
{
    (void)state;
    const size_t n = 3000, modes = 1000; /* blocks of 200000 / n = 66 rates: 16 blocks */
    whirl_chain *c = irregular_chain(n);
    assert_non_null(c);
    double *plain = malloc(modes * sizeof *plain), *reported = malloc(modes * sizeof *reported);
    assert_non_null(plain);
    assert_non_null(reported);
    assert_int_equal(whirl_nlink_critical(c, modes, plain), GSL_SUCCESS);
    critical_calls k = {0, 0, 0, 0, 1};
    assert_int_equal(whirl_nlink_critical_report(c, modes, reported, count_critical, &k),
                     GSL_SUCCESS);
    assert_true(k.increasing && k.last == modes && k.total == modes && k.calls == 16);
    assert_memory_equal(plain, reported, modes * sizeof *plain);
    critical_calls stop = {0, 0, 0, 3, 1};
    memset(reported, 0, modes * sizeof *reported);
    assert_int_equal(whirl_nlink_critical_report(c, modes, reported, count_critical, &stop),
                     WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_true(stop.calls == 3 && stop.last == 3 * 66);
    assert_memory_equal(plain, reported, stop.last * sizeof *plain);
    assert_int_equal(whirl_nlink_critical_report(c, modes, reported, NULL, NULL), GSL_SUCCESS);
    assert_memory_equal(plain, reported, modes * sizeof *plain);
    free(plain);
    free(reported);
    whirl_chain_free(c);
}

/* The uniform chain's rates tend to j_{0,k}/2 with an error of order 1/N. */
static void test_critical_to_continuum(void **state)
{
    (void)state;
    double err[3][3];
    size_t sizes[3] = {100, 200, 400};
    for (int s = 0; s < 3; s++) {
        whirl_chain *c = whirl_chain_alloc_uniform(sizes[s], 0);
        double omega[3];
        assert_int_equal(whirl_nlink_critical(c, 3, omega), GSL_SUCCESS);
        for (int k = 0; k < 3; k++)
            err[s][k] = omega[k] / (0.5 * gsl_sf_bessel_zero_J0((unsigned)k + 1)) - 1;
        whirl_chain_free(c);
    }
    for (int k = 0; k < 3; k++) {
        assert_true(fabs(err[0][k]) < 0.05);
        double order = log2(err[0][k] / err[1][k]), order2 = log2(err[1][k] / err[2][k]);
        assert_true(fabs(order - 1) < 0.05 && fabs(order2 - 1) < 0.03);
    }
}

static void check_modes(const whirl_chain *c, const double *omega_crit, int max_mode,
                        double omega_over, double factor)
{
    for (int k = 1; k <= max_mode; k++) {
        double omega = omega_over > 0 ? omega_over : omega_crit[k - 1] * factor;
        whirl_shape_info info;
        int status = whirl_nlink_solve(c, omega, k, &info);
        if (status) print_message("mode %d omega %.17g: %s\n", k, omega, whirl_last_error());
        assert_int_equal(status, GSL_SUCCESS);
        assert_int_equal(info.mode, k);
        assert_int_equal(info.n_nodes, k - 1);
        for (int j = 1; j < info.n_nodes; j++) assert_true(info.node_s[j] > info.node_s[j - 1]);
        assert_true(equilibrium_residual(c, omega, &info) < 1e-13);
        assert_true(info.max_r >= info.tip_r && info.depth > 0 && info.top_tension > 0);
    }
}

static void test_modes_everywhere(void **state)
{
    (void)state;
    double tip_masses[] = {0, 0.473};
    for (int t = 0; t < 2; t++) {
        whirl_chain *c = whirl_chain_alloc_uniform(37, tip_masses[t]);
        double crit[6];
        assert_int_equal(whirl_nlink_critical(c, 6, crit), GSL_SUCCESS);
        check_modes(c, crit, 6, 0, 1 + 1e-6); /* near-critical */
        check_modes(c, crit, 6, 0, 1.3717);
        check_modes(c, crit, 6, 30, 0); /* high rate */
        /* near-critical the tip radius is small and grows like sqrt(omega - omega_k) */
        whirl_shape_info a, b;
        assert_int_equal(whirl_nlink_solve(c, crit[2] * (1 + 1e-6), 3, &a), GSL_SUCCESS);
        assert_int_equal(whirl_nlink_solve(c, crit[2] * (1 + 4e-6), 3, &b), GSL_SUCCESS);
        assert_true(a.tip_r < 1e-2);
        assert_float_equal(b.tip_r / a.tip_r, 2, 1e-3);
        /* just below the critical rate the mode does not exist */
        assert_int_equal(whirl_nlink_solve(c, crit[2] * (1 - 1e-6), 3, &a), GSL_EDOM);
        whirl_chain_free(c);
    }
    whirl_chain *c = irregular_chain(23);
    double crit[6];
    assert_int_equal(whirl_nlink_critical(c, 6, crit), GSL_SUCCESS);
    check_modes(c, crit, 6, 0, 1.05);
    whirl_chain_free(c);
}

static void test_branch_equals_fresh(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(50, 0.21);
    enum { n = 101 };
    double omega[n];
    whirl_shape_info info[n];
    int exists[n];
    for (int j = 0; j < n; j++) omega[j] = 10.0 - 9.0 * j / (n - 1); /* descending */
    double crit[2];
    assert_int_equal(whirl_nlink_critical(c, 2, crit), GSL_SUCCESS);
    assert_int_equal(whirl_nlink_branch(c, 2, n, omega, info, exists), GSL_SUCCESS);
    for (int j = 0; j < n; j++) {
        assert_int_equal(exists[j], omega[j] > crit[1]);
        if (!exists[j]) continue;
        whirl_shape_info fresh;
        assert_int_equal(whirl_nlink_solve(c, omega[j], 2, &fresh), GSL_SUCCESS);
        assert_float_equal(info[j].tip_r, fresh.tip_r, 1e-13 * fresh.tip_r);
        assert_float_equal(info[j].node_s[0], fresh.node_s[0], 1e-12);
    }
    whirl_chain_free(c);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_shape_info info;
    double omega[6];
    assert_int_equal(whirl_nlink_solve(c, 0, 1, &info), GSL_EINVAL);
    assert_int_equal(whirl_nlink_solve(c, NAN, 1, &info), GSL_EINVAL);
    assert_int_equal(whirl_nlink_solve(c, 3, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_nlink_solve(c, 30, 6, &info), GSL_EDOM);
    assert_int_equal(whirl_nlink_critical(c, 6, omega), GSL_EINVAL);
    assert_int_equal(whirl_nlink_critical(c, 0, omega), GSL_EINVAL);
    assert_int_equal(whirl_nlink_solve(c, 2.0, 2, &info), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "omega_2="));
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_conical_pendulum),
        cmocka_unit_test(test_critical_vs_dense),
        cmocka_unit_test(test_critical_to_continuum),
        cmocka_unit_test(test_critical_report),
        cmocka_unit_test(test_modes_everywhere),
        cmocka_unit_test(test_branch_equals_fresh),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("nlink", tests, NULL, NULL);
}
