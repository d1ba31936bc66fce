/* Tests of the N-link branches by pseudo-arclength continuation (src/nlink_path.c):
 * - critical rates of equal links and masses against sqrt(N x_k), x_k the zeros of the Laguerre
 *   polynomial L_N, computed here independently (Golub-Welsch: the eigenvalues of the Jacobi
 *   matrix of the three-term recurrence, GSL's symmetric eigensolver), N = 5, 10, 25, 100;
 * - along a branch: the force balance of every mass at round-off, and continuity (no link angle
 *   changes by more than the step allows), on the N = 5 mode-4 branch up to omega = 45;
 * - near the birth the shape is the linear mode shape (the dense generalized eigenvector);
 * - a branch followed up and then back down retraces itself to 1e-10 and returns to the
 *   hanging chain at its birth rate;
 * - a fold located to 1e-10 in omega, checked by the pivot-end shooting (a second formulation):
 *   two equilibria just inside the fold, none just outside;
 * - every mode up to N, mode N just above omega_N;
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
#include <gsl/gsl_sort_vector.h>

#include "whirl/steady.h"

/* The largest force imbalance of a mass, relative to the largest force on it, at (omega, tip_r);
 * the pivot must be on the axis to round-off. */
static double force_residual(const whirl_chain *c, double omega, double tip_r)
{
    size_t n = c->n;
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(r);
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r, r, z, t), GSL_SUCCESS);
    double worst = 0, w2 = omega * omega;
    for (size_t i = 1; i <= n; i++) {
        double m = c->mass[i - 1];
        double fr = m * w2 * r[i] - t[i] * (r[i] - r[i - 1]) / c->length[i - 1];
        double fz = -m * c->gravity - t[i] * (z[i] - z[i - 1]) / c->length[i - 1];
        if (i < n) {
            fr += t[i + 1] * (r[i + 1] - r[i]) / c->length[i];
            fz += t[i + 1] * (z[i + 1] - z[i]) / c->length[i];
        }
        /* relative to the largest force on the mass */
        double scale = fmax(t[i], m * fmax(c->gravity, w2 * fabs(r[i])));
        if (i < n) scale = fmax(scale, t[i + 1]);
        worst = fmax(worst, hypot(fr, fz) / scale);
    }
    /* the pivot on the axis to round-off: r_0 is a sum of N terms up to max |r| and moves with
     * the tip radius by a dr_0/da per unit relative change (a shot from the tip can be very
     * sensitive: a zigzag at a high rate), so |r_0| <~ 8 eps (a |dr_0/da| + N max |r|) */
    double r0 = r[0], h = 1e-6 * tip_r, plus, minus, r_max = 0;
    for (size_t i = 1; i <= n; i++) r_max = fmax(r_max, fabs(r[i]));
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r + h, r, z, t), GSL_SUCCESS);
    plus = r[0];
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r - h, r, z, t), GSL_SUCCESS);
    minus = r[0];
    double floor = 8 * DBL_EPSILON * (tip_r * fabs(plus - minus) / (2 * h) + (double)n * r_max);
    if (!(fabs(r0) <= floor)) print_message("omega %.17g tip %.17g: r0 %.3e floor %.3e\n", omega, tip_r, r0, floor);
    assert_true(fabs(r0) <= floor);
    free(r);
    return worst;
}

/* Link angles at (omega, tip_r). */
static void link_angles(const whirl_chain *c, double omega, double tip_r, double *theta)
{
    size_t n = c->n;
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(r);
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r, r, z, t), GSL_SUCCESS);
    for (size_t i = 1; i <= n; i++) theta[i - 1] = atan2(r[i] - r[i - 1], z[i - 1] - z[i]);
    free(r);
}

/* Zeros of L_N by Golub-Welsch: the Jacobi matrix has diagonal 2k + 1 and off-diagonal k. */
static void laguerre_zeros(size_t n, double *x)
{
    gsl_matrix *j = gsl_matrix_calloc(n, n);
    gsl_vector *eval = gsl_vector_alloc(n);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc(n);
    for (size_t k = 0; k < n; k++) {
        gsl_matrix_set(j, k, k, 2.0 * (double)k + 1);
        if (k + 1 < n) {
            gsl_matrix_set(j, k, k + 1, (double)k + 1);
            gsl_matrix_set(j, k + 1, k, (double)k + 1);
        }
    }
    assert_int_equal(gsl_eigen_symm(j, eval, w), GSL_SUCCESS);
    gsl_sort_vector(eval);
    for (size_t k = 0; k < n; k++) x[k] = gsl_vector_get(eval, k);
    /* each a zero of L_N by the recurrence (k+1) L_{k+1} = (2k+1-x) L_k - k L_{k-1}, scaled */
    for (size_t k = 0; k < n; k++) {
        double l0 = 1, l1 = 1 - x[k], scale = 1 + x[k];
        for (size_t m = 1; m < n; m++) {
            double l2 = ((2.0 * (double)m + 1 - x[k]) * l1 - (double)m * l0) / ((double)m + 1);
            l0 = l1;
            l1 = l2;
            double big = fmax(fabs(l0), fabs(l1));
            if (big > 1e100) l0 /= big, l1 /= big;
            scale = fmax(scale, fabs(l1));
        }
        assert_true(fabs(l1) <= 1e-8 * scale);
    }
    gsl_eigen_symm_free(w);
    gsl_vector_free(eval);
    gsl_matrix_free(j);
}

static void test_critical_laguerre(void **state)
{
    (void)state;
    const size_t sizes[] = {5, 10, 25, 100};
    for (size_t s = 0; s < 4; s++) {
        size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *crit = malloc(n * sizeof *crit), *x = malloc(n * sizeof *x);
        assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
        laguerre_zeros(n, x);
        double worst = 0;
        for (size_t k = 0; k < n; k++)
            worst = fmax(worst, fabs(crit[k] / sqrt((double)n * x[k]) - 1));
        print_message("N = %zu: critical rates vs sqrt(N x_k): %.2e\n", n, worst);
        assert_true(worst < 1e-12);
        /* the birth of every mode is polished on the shot itself, to the same rates */
        whirl_nlink_path *p = whirl_nlink_path_alloc(c);
        assert_non_null(p);
        for (size_t k = 0; k < n; k += n / 5) {
            assert_int_equal(whirl_nlink_path_birth(p, (int)k + 1), GSL_SUCCESS);
            assert_float_equal(p->omega_birth, sqrt((double)n * x[k]), 1e-12 * p->omega_birth);
        }
        whirl_nlink_path_free(p);
        free(crit);
        free(x);
        whirl_chain_free(c);
    }
}

/* The N = 5 mode-4 branch to omega = 45: continuous, every point an equilibrium. */
static void test_branch_continuous(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 4), GSL_SUCCESS);
    double th0[5], th1[5], worst = 0, jump = 0;
    link_angles(c, p->omega, p->tip_r, th0);
    while (p->omega < 45) {
        double ds = p->ds;
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        worst = fmax(worst, force_residual(c, p->omega, p->tip_r));
        link_angles(c, p->omega, p->tip_r, th1);
        for (int i = 0; i < 5; i++) {
            jump = fmax(jump, fabs(th1[i] - th0[i]) / ds);
            th0[i] = th1[i];
        }
        assert_true(p->steps < 5000);
    }
    print_message("N = 5 mode 4 to omega = 45: %ld steps, worst force residual %.2e, "
                  "largest link-angle change per unit step %.2f\n", p->steps, worst, jump);
    assert_true(worst < 1e-13);
    /* a link angle changes by at most ~sqrt(N) times the step's rms change */
    assert_true(jump < 2.5);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* Near the birth the shape is the linear mode: the eigenvector of K x = w^2 M x. */
static void test_birth_linear_shape(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.37);
    gsl_matrix *k = gsl_matrix_calloc(n, n), *mm = gsl_matrix_calloc(n, n), *ev;
    gsl_vector *eval = gsl_vector_alloc(n);
    ev = gsl_matrix_alloc(n, n);
    gsl_eigen_gensymmv_workspace *w = gsl_eigen_gensymmv_alloc(n);
    for (size_t i = 0; i < n; i++) {
        double t = 0;
        for (size_t j = i; j < n; j++) t += c->mass[j] * c->gravity;
        double s = t / c->length[i];
        *gsl_matrix_ptr(k, i, i) += s;
        if (i > 0) {
            *gsl_matrix_ptr(k, i - 1, i - 1) += s;
            *gsl_matrix_ptr(k, i - 1, i) -= s;
            *gsl_matrix_ptr(k, i, i - 1) -= s;
        }
        gsl_matrix_set(mm, i, i, c->mass[i]);
    }
    assert_int_equal(gsl_eigen_gensymmv(k, mm, eval, ev, w), GSL_SUCCESS);
    gsl_eigen_gensymmv_sort(eval, ev, GSL_EIGEN_SORT_VAL_ASC);
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    for (size_t mode = 1; mode <= n; mode++) {
        double omega_k = sqrt(gsl_vector_get(eval, mode - 1)), dev[2];
        const double eps[2] = {1e-6, 1e-8};
        for (int e = 0; e < 2; e++) {
            double omega = omega_k * (1 + eps[e]);
            whirl_shape_info info;
            assert_int_equal(whirl_nlink_solve(c, omega, (int)mode, 0, &info), GSL_SUCCESS);
            assert_int_equal(info.n_nodes, (int)mode - 1);
            assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, t), GSL_SUCCESS);
            /* both normalised to their tip value */
            double tip_v = gsl_matrix_get(ev, n - 1, mode - 1), big = 0;
            dev[e] = 0;
            for (size_t i = 1; i <= n; i++) {
                double lin = gsl_matrix_get(ev, i - 1, mode - 1) / tip_v;
                dev[e] = fmax(dev[e], fabs(r[i] / r[n] - lin));
                big = fmax(big, fabs(lin));
            }
            dev[e] /= big;
        }
        /* the departure from the linear shape is of order omega / omega_k - 1 (and of the
         * squared amplitude, which is of that order too) */
        print_message("mode %zu: shape vs linear mode %.2e (eps 1e-6), %.2e (eps 1e-8)\n", mode,
                      dev[0], dev[1]);
        assert_true(dev[1] < 1e-5 * 1e-2 * 10);
        assert_true(dev[0] / dev[1] > 50 && dev[0] / dev[1] < 200);
    }
    free(r);
    gsl_eigen_gensymmv_free(w);
    gsl_matrix_free(k);
    gsl_matrix_free(mm);
    gsl_matrix_free(ev);
    gsl_vector_free(eval);
    whirl_chain_free(c);
}

/* Up to omega_top and back: the same points at the same rates, back to the birth. */
static void test_retrace(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(10, 0);
    enum { nr = 9 };
    double rates[nr], up[nr], down[nr];
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 3), GSL_SUCCESS);
    const double birth = p->omega_birth;
    for (int j = 0; j < nr; j++) rates[j] = birth + 0.013 + 1.7 * j, up[j] = down[j] = NAN;
    while (p->omega < 20) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int j = 0; j < nr; j++) {
            double a;
            int found = whirl_nlink_path_crossings(p, rates[j], 1, &a);
            assert_true(found >= 0);
            if (found) up[j] = a;
        }
    }
    whirl_nlink_path_reverse(p);
    while (!p->ended) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int j = 0; j < nr; j++) {
            double a;
            int found = whirl_nlink_path_crossings(p, rates[j], 1, &a);
            assert_true(found >= 0);
            if (found) down[j] = a;
        }
        assert_true(p->steps < 10000);
    }
    double worst = 0;
    for (int j = 0; j < nr; j++) {
        assert_true(isfinite(up[j]) && isfinite(down[j]));
        worst = fmax(worst, fabs(up[j] - down[j]) / up[j]);
    }
    /* the last event: the return to the hanging chain at the birth rate */
    assert_int_equal(p->event[p->n_events - 1].kind, WHIRL_EVENT_RETURN);
    double back = p->event[p->n_events - 1].omega;
    print_message("retrace N = 10 mode 3 to omega = 20 and back: tip radii agree to %.2e, "
                  "return at %.17g (birth %.17g)\n", worst, back, birth);
    assert_true(worst < 1e-10);
    assert_float_equal(back, birth, 1e-10 * birth);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* Sign changes of the pivot-end residual for theta_1 in [lo, hi] on m + 1 points. */
static int pivot_sign_changes(const whirl_chain *c, double omega, double lo, double hi, int m)
{
    int count = 0;
    double prev = 0;
    for (int i = 0; i <= m; i++) {
        double res, th = lo + (hi - lo) * i / m;
        assert_int_equal(whirl_nlink_pivot_residual(c, omega, th, &res, NULL), GSL_SUCCESS);
        if (i > 0 && (res > 0) != (prev > 0)) count++;
        prev = res;
    }
    return count;
}

/* The N = 7 mode-4 branch turns back twice (an S): both folds located to 1e-10. */
static void test_folds(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(7, 0);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 4), GSL_SUCCESS);
    whirl_branch_event folds[2];
    int nf = 0;
    while (p->omega < 12) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int e = 0; e < p->n_events; e++) {
            assert_int_equal(p->event[e].kind, WHIRL_EVENT_FOLD);
            assert_true(nf < 2);
            folds[nf++] = p->event[e];
        }
    }
    assert_int_equal(nf, 2);
    double theta[7];
    for (int f = 0; f < 2; f++) {
        const whirl_branch_event *e = &folds[f];
        print_message("fold at omega = %.15f, tip radius %.6e\n", e->omega, e->tip_r);
        assert_true(force_residual(c, e->omega, e->tip_r) < 1e-13);
        link_angles(c, e->omega, e->tip_r, theta);
        /* pivot shooting: two equilibria near the fold on one side, none on the other */
        double d = 1e-10 * e->omega, h = 2e-3;
        int below = pivot_sign_changes(c, e->omega - d, theta[0] - h, theta[0] + h, 40000);
        int above = pivot_sign_changes(c, e->omega + d, theta[0] - h, theta[0] + h, 40000);
        print_message("  omega_f -+ 1e-10 omega_f: %d and %d equilibria nearby\n", below, above);
        assert_true((below == 2 && above == 0) || (below == 0 && above == 2));
        assert_true(f == 0 ? below == 2 : above == 2); /* a maximum, then a minimum */
    }
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* Modes 1..N at and above their birth, mode N just above omega_N. */
static void test_every_mode(void **state)
{
    (void)state;
    const size_t sizes[] = {15, 25};
    for (size_t s = 0; s < 2; s++) {
        size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *crit = malloc(n * sizeof *crit);
        assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
        const double factors[] = {1 + 1e-9, 1 + 1e-4, 1.2};
        for (size_t k = 1; k <= n; k++)
            for (int f = 0; f < 3; f++) {
                whirl_shape_info info;
                double omega = crit[k - 1] * factors[f];
                int status = whirl_nlink_solve(c, omega, (int)k, 0, &info);
                if (status) print_message("N %zu mode %zu: %s\n", n, k, whirl_last_error());
                assert_int_equal(status, GSL_SUCCESS);
                assert_int_equal(info.mode, (int)k);
                assert_true(info.tip_r > 0);
                assert_true(force_residual(c, omega, info.tip_r) < 1e-13);
                if (f == 0) assert_int_equal(info.n_nodes, (int)k - 1);
            }
        /* the case: mode 15 of 15 at 26.85 (omega_15 = 26.8401) */
        if (n == 15) {
            whirl_shape_info info;
            assert_int_equal(whirl_nlink_solve(c, 26.85, 15, 0, &info), GSL_SUCCESS);
            assert_int_equal(info.n_nodes, 14);
        }
        free(crit);
        whirl_chain_free(c);
    }
}

static void test_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_shape_info info;
    double crit[5];
    assert_int_equal(whirl_nlink_critical(c, 5, crit), GSL_SUCCESS);
    /* above N */
    assert_int_equal(whirl_nlink_solve(c, 30, 6, 0, &info), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "modes 1..5"));
    /* below the birth: says so, naming omega_k */
    assert_int_equal(whirl_nlink_solve(c, crit[2] * (1 - 1e-9), 3, 0, &info), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "exists only above omega_3="));
    /* exactly at the birth: the hanging chain, not a shape of the mode */
    assert_int_equal(whirl_nlink_solve(c, crit[2], 3, 0, &info), GSL_EDOM);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 0), GSL_EINVAL);
    assert_int_equal(whirl_nlink_path_birth(p, 6), GSL_EINVAL);
    assert_int_equal(whirl_nlink_path_start(p, NAN, 0.1, 1), GSL_EINVAL);
    /* a stop request ends a step */
    assert_int_equal(whirl_nlink_path_birth(p, 2), GSL_SUCCESS);
    whirl_stop_request();
    assert_int_equal(whirl_nlink_path_step(p), WHIRL_EINTERRUPTED);
    assert_int_equal(whirl_nlink_solve(c, 10, 2, 0, &info), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
    /* a start from an equilibrium found by the birth path, in both directions */
    assert_int_equal(whirl_nlink_solve(c, 7.3, 2, 0, &info), GSL_SUCCESS);
    assert_int_equal(whirl_nlink_path_start(p, 7.3, info.tip_r, -1), GSL_SUCCESS);
    assert_float_equal(p->tip_r, info.tip_r, 1e-13 * info.tip_r);
    assert_true(p->t_omega < 0);
    assert_null(whirl_nlink_path_alloc(NULL));
    whirl_nlink_path_free(NULL);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_critical_laguerre), cmocka_unit_test(test_branch_continuous),
        cmocka_unit_test(test_birth_linear_shape), cmocka_unit_test(test_retrace),
        cmocka_unit_test(test_folds),              cmocka_unit_test(test_every_mode),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("nlink_path", tests, NULL, NULL);
}
