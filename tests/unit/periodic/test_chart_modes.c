/* Tests of the modes of the vertically shaken chain (src/periodic/chart_modes.c) against the
 * full monodromy of the chain (whirl_periodic_find: the Cartesian chain and its variational
 * equations, Gauss steps), a second formulation that knows nothing of the modes:
 *   det(M -+ I) = prod_k (2 -+ tr M_k)^planes   (planes = dim - 1),
 * and the multipliers of M the union of the modes' 2 x 2 ones, each planes times; for N = 2, 3, 5,
 * equal and unequal links and masses, 2D and 3D, hanging and inverted, the line A cos(omega t)
 * and a vertical path of two harmonics. Then the chart: two modes' edges that cross are passed by
 * both curves unbroken. */
#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>

#include "periodic/chart_modes.h"
#include "whirl/periodic.h"

/* det(mono -+ I), m x m row major. */
static double det_shift(const double *mono, size_t m, double shift)
{
    gsl_matrix *a = gsl_matrix_alloc(m, m);
    gsl_permutation *perm = gsl_permutation_alloc(m);
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++)
            gsl_matrix_set(a, i, j, mono[i * m + j] + (i == j ? shift : 0));
    int sign;
    gsl_linalg_LU_decomp(a, perm, &sign);
    const double d = gsl_linalg_LU_det(a, sign);
    gsl_permutation_free(perm);
    gsl_matrix_free(a);
    return d;
}

typedef struct full {
    double det[2];           /* det(M - I), det(M + I), extrapolated from steps and 2 steps */
    size_t count;
    double complex mu[64];   /* the multipliers, extrapolated as det */
} full;

static void full_monodromy(const whirl_chain *c, int dim, const whirl_pivot_path *path,
                           int inverted, int steps, full *out)
{
    whirl_periodic *w = whirl_periodic_alloc(c, dim, path);
    assert_non_null(w);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    const size_t m = whirl_periodic_tangent_size(w);
    double det[2][2];
    double complex mu[2][64];
    for (int k = 0; k < 2; k++) {
        assert_int_equal(whirl_periodic_start_vertical(w, inverted, y), GSL_SUCCESS);
        const whirl_periodic_params p = {.steps = steps << k, .refine = 0};
        whirl_periodic_result r;
        assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
        assert_int_equal(r.steps, steps << k); /* not raised: the extrapolation's ratio holds */
        const double *mono = whirl_periodic_monodromy(w);
        det[k][0] = det_shift(mono, m, -1), det[k][1] = det_shift(mono, m, 1);
        assert_true(r.count <= 64);
        out->count = r.count;
        for (size_t i = 0; i < r.count; i++) mu[k][i] = r.re[i] + I * r.im[i];
    }
    /* each finer multiplier extrapolated with the nearest coarser one */
    for (size_t i = 0; i < out->count; i++) {
        size_t best = 0;
        for (size_t j = 1; j < out->count; j++)
            if (cabs(mu[1][i] - mu[0][j]) < cabs(mu[1][i] - mu[0][best])) best = j;
        out->mu[i] = mu[1][i] + (mu[1][i] - mu[0][best]) / 15;
    }
    for (int e = 0; e < 2; e++) out->det[e] = det[1][e] + (det[1][e] - det[0][e]) / 15;
    free(y);
    whirl_periodic_free(w);
}

/* The modes' traces, extrapolated from 400 and 800 Magnus steps. */
static void mode_traces(const whirl_chain *c, const whirl_pivot_path *path, int inverted,
                        double *tr)
{
    double lambda[8];
    assert_int_equal(chart_modes(c, lambda), GSL_SUCCESS);
    for (size_t k = 0; k < c->n; k++) {
        double m1[4], m2[4];
        const double coef = inverted ? -lambda[k] : lambda[k];
        chart_mode_monodromy(path, c->gravity, coef, 0, 400, m1);
        chart_mode_monodromy(path, c->gravity, coef, 0, 800, m2);
        const double t1 = m1[0] + m1[3], t2 = m2[0] + m2[3];
        tr[k] = t2 + (t2 - t1) / 15;
        assert_true(fabs(m2[0] * m2[3] - m2[1] * m2[2] - 1) < 1e-12 * fmax(1, fabs(t2) * fabs(t2)));
    }
}

typedef struct point {
    double omega, amp, amp2; /* amp2: the second harmonic's sine term (0: the line) */
    int inverted;
} point;

static double worst_det, worst_mu;

static void compare(const whirl_chain *c, int dim, const point *pt)
{
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    assert_int_equal(whirl_pivot_line(&path, pt->omega, pt->amp, up), GSL_SUCCESS);
    if (pt->amp2 != 0) path.harmonics = 2, path.s[2][1] = pt->amp2;
    assert_int_equal(whirl_pivot_check(&path, dim), GSL_SUCCESS);
    full f;
    full_monodromy(c, dim, &path, pt->inverted, 1000, &f);
    double tr[8];
    mode_traces(c, &path, pt->inverted, tr);
    const int planes = dim - 1;
    assert_int_equal(f.count, 2 * (size_t)planes * c->n);
    for (int e = 0; e < 2; e++) {
        double prod = 1, scale = 1;
        for (size_t k = 0; k < c->n; k++)
            for (int p = 0; p < planes; p++)
                prod *= e ? 2 + tr[k] : 2 - tr[k], scale *= 2 + fabs(tr[k]);
        const double rel = fabs(prod - f.det[e]) / scale;
        if (rel > worst_det) worst_det = rel;
        if (rel > 1e-10)
            fail_msg("N=%zu dim %d omega=%g A=%g inverted %d: det(M %s I) %.15g, the modes' "
                     "product %.15g (%.2g of the scale)", c->n, dim, pt->omega, pt->amp,
                     pt->inverted, e ? "+" : "-", f.det[e], prod, rel);
    }
    /* the multipliers: each full one matched to a distinct modal one */
    double complex modal[64];
    int used[64] = {0};
    size_t count = 0;
    for (size_t k = 0; k < c->n; k++) {
        const double complex root = csqrt(tr[k] * tr[k] - 4 + 0 * I);
        for (int p = 0; p < planes; p++)
            modal[count++] = (tr[k] + root) / 2, modal[count++] = (tr[k] - root) / 2;
    }
    for (size_t i = 0; i < f.count; i++) {
        int best = -1;
        for (size_t j = 0; j < count; j++)
            if (!used[j] && (best < 0 || cabs(f.mu[i] - modal[j]) < cabs(f.mu[i] - modal[best])))
                best = (int)j;
        used[best] = 1;
        const double d = cabs(f.mu[i] - modal[best]) / fmax(1, cabs(modal[best]));
        if (d > worst_mu) worst_mu = d;
        if (d > 1e-8)
            fail_msg("N=%zu dim %d omega=%g A=%g: multiplier %.12g%+.12gi, the modes' %.12g%+.12gi",
                     c->n, dim, pt->omega, pt->amp, creal(f.mu[i]), cimag(f.mu[i]),
                     creal(modal[best]), cimag(modal[best]));
    }
}

static const point POINTS[] = {
    {1.7, 0.05, 0, 0}, {2.6, 0.2, 0, 0}, {4.0, 0.1, 0.03, 0}, {12, 0.1, 0, 1}, {20, 0.05, 0.02, 1},
};

static void test_second_formulation(void **state)
{
    (void)state;
    static const double len_u[] = {0.5, 0.3, 0.2}, mass_u[] = {1, 2, 0.5};
    static const double len_5[] = {0.1, 0.3, 0.2, 0.25, 0.15}, mass_5[] = {0.4, 1, 0.3, 2, 0.7};
    whirl_chain *chains[] = {whirl_chain_alloc_uniform(2, 0), whirl_chain_alloc_uniform(3, 0),
                             whirl_chain_alloc(3, len_u, mass_u, 1),
                             whirl_chain_alloc(5, len_5, mass_5, 1)};
    for (size_t i = 0; i < sizeof chains / sizeof *chains; i++) {
        assert_non_null(chains[i]);
        for (int dim = 2; dim <= 3; dim++)
            for (size_t j = 0; j < sizeof POINTS / sizeof *POINTS; j++) {
                if (dim == 3 && chains[i]->n == 5 && j > 1) continue; /* 3D N = 5: two points */
                compare(chains[i], dim, &POINTS[j]);
            }
        whirl_chain_free(chains[i]);
    }
    print_message("# det(M -+ I) against the modes' product: worst %.2g of the scale; the "
                  "multipliers: worst %.2g\n", worst_det, worst_mu);
}

/* ---- crossing edges of two modes ----
 * N = 3 hanging over rates 2.0 .. 3.4 (57 rates), A <= 0.3: mode 1's first tongue (tip 2 omega_1
 * = 2.2337, edges -1) widens to the right across mode 2's second (tip omega_2 = 2.6235, edges
 * +1). Each tongue is one curve through its tip, with a point at every rate on each side while
 * its edge is in the range: mode 1's right edge (under 0.3 up to rate 5) at every rate from the
 * tip to 3.4, mode 2's left edge (A = 0.23 at rate 2) at every rate from 2.0 to its tip; and
 * the two cross (their amplitudes' order changes between two rates). */
#define MAX_POINTS 2048

typedef struct kept {
    int n;
    whirl_chart_point p[MAX_POINTS];
} kept;

static int keep_point(void *data, const whirl_chart_point *p)
{
    kept *k = data;
    assert_true(k->n < MAX_POINTS);
    k->p[k->n++] = *p;
    return 0;
}

/* The curve whose tip point is at the rate tip; the amplitude of each on-grid column of it on
 * the side (+1 right of the tip, -1 left) into amp (NAN: none). */
static int tongue(const kept *k, double tip, int columns, const whirl_chart_params *p, int side,
                  double *amp)
{
    int curve = -1;
    for (int i = 0; i < k->n; i++)
        if (k->p[i].amplitude == 0 && fabs(k->p[i].omega - tip) < 1e-9) {
            assert_int_equal(curve, -1); /* one tip point */
            curve = k->p[i].curve;
        }
    assert_true(curve >= 0);
    for (int j = 0; j < columns; j++) amp[j] = NAN;
    for (int i = 0; i < k->n; i++) {
        const whirl_chart_point *q = &k->p[i];
        const double rate = p->omega_min + q->column * (p->omega_max - p->omega_min) /
                                               (p->columns - 1);
        if (q->curve == curve && fabs(q->omega - rate) < 1e-12 && (q->omega - tip) * side > 0) {
            assert_true(isnan(amp[q->column])); /* one point per rate and side */
            amp[q->column] = q->amplitude;
        }
    }
    return curve;
}

static void test_crossing(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    const whirl_chart_params p = {.omega_min = 2.0, .omega_max = 3.4, .columns = 57,
                                  .amp_max = 0.3, .rows = 60};
    static kept k;
    k.n = 0;
    assert_int_equal(whirl_chart_vertical(c, 2, &p, keep_point, &k, NULL, NULL), GSL_SUCCESS);
    double lambda[3];
    assert_int_equal(chart_modes(c, lambda), GSL_SUCCESS);
    const double tip1 = 2 * sqrt(lambda[0]), tip2 = sqrt(lambda[1]);
    double right1[57], left2[57];
    const int c1 = tongue(&k, tip1, p.columns, &p, 1, right1);
    const int c2 = tongue(&k, tip2, p.columns, &p, -1, left2);
    assert_true(c1 != c2);
    int crossings = 0, both = 0;
    double prev = NAN;
    for (int j = 0; j < p.columns; j++) {
        const double rate = p.omega_min + j * (p.omega_max - p.omega_min) / (p.columns - 1);
        if (rate > tip1) assert_false(isnan(right1[j])); /* mode 1's right edge, unbroken */
        if (rate < tip2) assert_false(isnan(left2[j]));  /* mode 2's left edge, unbroken */
        if (isnan(right1[j]) || isnan(left2[j])) continue;
        both++;
        const double d = right1[j] - left2[j];
        if (!isnan(prev) && (d < 0) != (prev < 0)) crossings++;
        prev = d;
    }
    print_message("# crossing: mode 1's tongue (curve %d) and mode 2's (curve %d) at %d common "
                  "rates, %d crossing\n", c1, c2, both, crossings);
    assert_int_equal(crossings, 1);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_second_formulation),
        cmocka_unit_test(test_crossing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
