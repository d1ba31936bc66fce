/* Tests of the stability chart of the vertically shaken chain (whirl_chart_vertical).
 *
 * N = 1 hanging is Mathieu's equation y'' + (a - 2 q cos 2 tau) y = 0 with a = 4 g / (l w^2),
 * q = 2 A / l (docs/theory/floquet.md): every edge point must lie on a characteristic value
 * a_n(q) or b_n(q). The references here come from the Hill matrices (the Fourier series of the
 * periodic solutions, truncated at 40 terms, far beyond convergence at q <= 0.6), by
 * gsl_eigen_symm, not from the code under test; they agree with scipy.special's mathieu_a and
 * mathieu_b to 2e-16 at q = 0.2 .. 0.6:
 *   /usr/bin/python3 -c "from scipy.special import mathieu_a; print(mathieu_a(1, 0.56))"
 * (1.5180110424408382, the Hill matrix's 1.5180110424408382). */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <gsl/gsl_eigen.h>

#include "whirl/periodic.h"

#define HILL 40

/* The lowest eigenvalue of the Hill matrix of the odd-index cosine (a_1, corr +q), or sine
 * (b_1, corr -q) solutions: diag (2k+1)^2, off-diagonal q, the first diagonal 1 + corr. */
static double hill_lowest(double q, double corr)
{
    gsl_matrix *m = gsl_matrix_calloc(HILL, HILL);
    for (int k = 0; k < HILL; k++) {
        gsl_matrix_set(m, k, k, (2.0 * k + 1) * (2.0 * k + 1));
        if (k + 1 < HILL) gsl_matrix_set(m, k, k + 1, q), gsl_matrix_set(m, k + 1, k, q);
    }
    gsl_matrix_set(m, 0, 0, 1 + corr);
    gsl_vector *ev = gsl_vector_alloc(HILL);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(HILL);
    gsl_eigen_symm(m, ev, ws);
    const double lo = gsl_vector_min(ev);
    gsl_eigen_symm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(m);
    return lo;
}

typedef struct seen {
    int points;
    double worst;
} seen;

static int check_point(void *data, const whirl_chart_point *p)
{
    seen *s = data;
    assert_int_equal(p->kind, WHIRL_FLOQUET_EDGE_MINUS_ONE); /* only the first tongue here */
    const double a = 4 / (p->omega * p->omega), q = 2 * p->amplitude;
    const double d = fmin(fabs(a - hill_lowest(q, q)), fabs(a - hill_lowest(q, -q)));
    if (d > s->worst) s->worst = d;
    assert_true(p->err < 1e-8);
    s->points++;
    return 0;
}

static void test_mathieu_first_tongue(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    /* rates 1.5 .. 3 about the first tongue's tip omega = 2; A up to 0.3 (q 0.6) */
    const whirl_chart_params p = {.omega_min = 1.5, .omega_max = 3, .columns = 30,
                                  .amp_max = 0.3, .rows = 50};
    seen s = {0, 0};
    assert_int_equal(whirl_chart_vertical(c, 2, &p, check_point, &s, NULL, NULL), GSL_SUCCESS);
    print_message("# Mathieu first tongue: %d points, worst |a - a_1 or b_1| %.2g\n", s.points,
                  s.worst);
    assert_true(s.points >= 20);
    assert_true(s.worst < 1e-8);
    whirl_chain_free(c);
}

static void test_bad_params(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params bad[] = {{.omega_min = 2, .omega_max = 1, .amp_max = 0.1},
                                      {.omega_min = 1, .omega_max = 2, .amp_max = 0},
                                      {.omega_min = 1, .omega_max = 2, .amp_max = NAN},
                                      {.omega_min = 1, .omega_max = 2, .amp_max = 0.1,
                                       .columns = 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(whirl_chart_vertical(c, 2, &bad[i], NULL, NULL, NULL, NULL),
                         GSL_EINVAL);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mathieu_first_tongue),
        cmocka_unit_test(test_bad_params),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
