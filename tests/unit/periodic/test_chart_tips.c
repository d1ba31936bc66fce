/* Tests of the tips of the thin tongues (order n >= 3) on the stability chart of the vertically
 * shaken chain (whirl_chart_vertical, src/periodic/chart_tips.c), and of the half period's
 * functions (chart_mode_half) against the full period's monodromy.
 *
 * N = 1 hanging is Mathieu's equation y'' + (a - 2 q cos 2 tau) y = 0 with a = 4 g / (l w^2),
 * q = 2 A / l (docs/theory/floquet.md). The references: the characteristic values a_n(q), b_n(q)
 * from the Hill (Ince) tridiagonal matrices of the periodic solutions' Fourier series, truncated
 * at HILL terms, by gsl_eigen_symm, not from the code under test:
 *   a_2r:   cos(2 k tau),       diag (2k)^2, off-diagonal q, the first one sqrt(2) q;
 *   b_2r:   sin(2 k tau), k>=1, diag (2k)^2, off-diagonal q;
 *   a_2r+1: cos((2k+1) tau),    diag (2k+1)^2, off-diagonal q, the first diagonal 1 + q;
 *   b_2r+1: sin((2k+1) tau),    the same with the first diagonal 1 - q;
 * the r-th eigenvalue (from 0; b_2r the (r-1)-th) in increasing order (Abramowitz and Stegun
 * 20.2; McLachlan, Theory and application of Mathieu functions, 1947, ch. III). For q < 0 the
 * pairs swap; the test takes the nearer of a_n and b_n. They agree with scipy.special's
 * mathieu_a, mathieu_b (Zhang and Jin's algorithm) to 4.3e-14 for n = 3, 4, 5 at q = 1.2:
 *   /usr/bin/python3 -c "from scipy.special import mathieu_a; print(mathieu_a(4, 1.2))"
 * (16.04903270642382; the Hill matrix's 16.049032706423827). */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdlib.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_sort_vector.h>

#include "periodic/chart_modes.h"
#include "whirl/periodic.h"

/* Terms of the Hill matrices: at q <= 3 the coefficients of the n <= 5 solutions fall below
 * 1e-16 within 15 terms; 40 is far beyond. */
#define HILL 40

/* a_n(q) (sines 0) or b_n(q) (sines 1) from the Hill matrix (file header). */
static double hill(double q, int n, int sines)
{
    gsl_matrix *m = gsl_matrix_calloc(HILL, HILL);
    const int odd = n % 2, first = odd ? 0 : sines; /* b_2r starts at sin(2 tau) */
    for (int k = 0; k < HILL; k++) {
        const double w = odd ? 2.0 * k + 1 : 2.0 * (k + first);
        gsl_matrix_set(m, k, k, w * w);
        const double off = !odd && !sines && k == 0 ? sqrt(2) * q : q;
        if (k + 1 < HILL) gsl_matrix_set(m, k, k + 1, off), gsl_matrix_set(m, k + 1, k, off);
    }
    if (odd) gsl_matrix_set(m, 0, 0, 1 + (sines ? -q : q));
    gsl_vector *ev = gsl_vector_alloc(HILL);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(HILL);
    gsl_eigen_symm(m, ev, ws);
    gsl_sort_vector(ev);
    const int r = odd ? (n - 1) / 2 : n / 2 - sines;
    const double v = gsl_vector_get(ev, (size_t)r);
    gsl_eigen_symm_free(ws);
    gsl_vector_free(ev);
    gsl_matrix_free(m);
    return v;
}

#define MAX_POINTS 20000

typedef struct kept {
    int n;
    whirl_chart_point *p;
} kept;

static int keep_point(void *data, const whirl_chart_point *p)
{
    kept *k = data;
    assert_true(k->n < MAX_POINTS);
    k->p[k->n++] = *p;
    return 0;
}

/* |a - a_n(q)| and |a - b_n(q)| of a point of the N = 1 chart. */
static void distances(const whirl_chart_point *p, int n, double d[2])
{
    const double a = 4 / (p->omega * p->omega), q = 2 * p->amplitude;
    d[0] = fabs(a - hill(q, n, 0));
    d[1] = fabs(a - hill(q, n, 1));
}

static int by_amplitude(const void *a, const void *b)
{
    const whirl_chart_point *p = a, *q = b;
    return (p->amplitude > q->amplitude) - (p->amplitude < q->amplitude);
}

/* N = 1 hanging over rates 0.36 .. 0.75 (80 rates), A <= 1.5 (60 rows): the tongues n = 3, 4,
 * 5 (tips 2/3, 1/2, 2/5; widths a_n - b_n ~ q^n / (2^(2n-3) ((n-1)!)^2): 1e-4 of a at q = 0.5
 * for n = 3, 3e-10 for n = 5 at q = 0.2, below a rate's step of the grid everywhere). Each must
 * be ONE curve: exactly one tip point (2/n, 0); every point of the tip's curve on a_n or b_n to
 * 1e-8 in a; at least 3 points on each edge where the two are apart (|a_n - b_n| > 1e-7); every
 * point of the chart on a_n or b_n on that curve; and each edge, sorted by A from the tip, no
 * gap wider than a row's step and a rate's step at once. */
static void test_thin_tongues(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params p = {.omega_min = 0.36, .omega_max = 0.75, .columns = 80,
                                  .amp_max = 1.5, .rows = 60};
    kept k = {0, malloc(MAX_POINTS * sizeof(whirl_chart_point))};
    whirl_chart_point *edge = malloc(MAX_POINTS * sizeof *edge);
    assert_non_null(k.p);
    assert_non_null(edge);
    assert_int_equal(whirl_chart_vertical(c, 2, &p, keep_point, &k, NULL, NULL), GSL_SUCCESS);
    const double dw = (p.omega_max - p.omega_min) / (p.columns - 1);
    const double da = p.amp_max / (p.rows - 1);
    for (int n = 3; n <= 5; n++) {
        const double tip = 2.0 / n;
        int at = -1;
        for (int i = 0; i < k.n; i++)
            if (k.p[i].amplitude == 0 && fabs(k.p[i].omega - tip) < 1e-12) at = at < 0 ? i : -2;
        assert_true(at >= 0); /* exactly one tip point */
        assert_int_equal(k.p[at].kind, n % 2 ? WHIRL_FLOQUET_EDGE_MINUS_ONE
                                             : WHIRL_FLOQUET_EDGE_PLUS_ONE);
        const int curve = k.p[at].curve;
        int on[2] = {0, 0}, elsewhere = 0, pieces[2] = {0, 0};
        double worst = 0, gap = 0, top = 0;
        for (int i = 0; i < k.n; i++) {
            const whirl_chart_point *q = &k.p[i];
            double d[2];
            distances(q, n, d);
            const double dmin = fmin(d[0], d[1]);
            if (q->curve != curve) {
                elsewhere += dmin < 1e-8; /* a point of this tongue on another curve */
                continue;
            }
            worst = fmax(worst, dmin);
            top = fmax(top, q->amplitude);
            const double qq = 2 * q->amplitude;
            if (fabs(hill(qq, n, 0) - hill(qq, n, 1)) > 1e-7) on[d[1] < d[0]]++;
        }
        /* each edge (the points nearer a_n, or b_n, and the tip) sorted by A */
        for (int e = 0; e < 2; e++) {
            int m = 0;
            for (int i = 0; i < k.n; i++) {
                double d[2];
                if (k.p[i].curve != curve) continue;
                distances(&k.p[i], n, d);
                if (i == at || (e == 0 ? d[0] <= d[1] : d[1] < d[0])) edge[m++] = k.p[i];
            }
            qsort(edge, (size_t)m, sizeof *edge, by_amplitude);
            for (int i = 1; i < m; i++) {
                const double sw = fabs(edge[i].omega - edge[i - 1].omega) / dw;
                const double sa = fabs(edge[i].amplitude - edge[i - 1].amplitude) / da;
                gap = fmax(gap, fmin(sw, sa));
                pieces[e] += fmin(sw, sa) > 1 + 1e-9;
            }
        }
        print_message("# tongue %d: tip at omega=%.15g, points on a_%d %d, on b_%d %d, up to "
                      "A=%.3g; worst |a - a_%d or b_%d| %.2g, largest gap %.3g steps, points of "
                      "the tongue on other curves %d\n", n, k.p[at].omega, n, on[0], n, on[1],
                      top, n, n, worst, gap, elsewhere);
        assert_true(on[0] >= 3 && on[1] >= 3);
        assert_true(worst < 1e-8);
        assert_int_equal(elsewhere, 0);
        assert_int_equal(pieces[0] + pieces[1], 0);
    }
    free(edge);
    free(k.p);
    whirl_chain_free(c);
}

/* The half period's functions against the full monodromy: (-2 u' tau)(2 v / tau) = 2 - tr M and
 * (2 u)(2 v') = 2 + tr M (chart_modes.c) for Mathieu's mode (N = 1) and a chain's highest mode,
 * hanging and inverted, near and far from edges, the same step h for both (half the steps over
 * half the period); and u v' - u' v = 1. */
static void test_half_period(void **state)
{
    (void)state;
    const double up[3] = {0, 0, 1};
    const struct {
        double coef, omega, amp;
    } cases[] = {{1, 2, 0.1}, {1, 0.6667, 0.4}, {1, 0.5, 0.05}, {19.3, 2.4, 0.1},
                 {-1, 30, 0.1}, {-4.2, 45, 0.08}, {7, 1.3, 0.02}};
    double worst = 0, worst_det = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        whirl_pivot_path path;
        assert_int_equal(whirl_pivot_line(&path, cases[i].omega, cases[i].amp, up), GSL_SUCCESS);
        const int steps = 400;
        double m[4], x[4];
        chart_mode_monodromy(&path, 1, cases[i].coef, 0, steps, m);
        chart_mode_half(&path, 1, cases[i].coef, steps / 2, x);
        const double tr = m[0] + m[3], tau = whirl_pivot_period(&path) / 2;
        const double fp = (-2 * x[2] * tau) * (2 * x[1] / tau), fm = (2 * x[0]) * (2 * x[3]);
        /* the scale: the trace's terms, |u v'| + |u' v| */
        const double scale = 2 + fabs(x[0] * x[3]) + fabs(x[2] * x[1]);
        worst = fmax(worst, fmax(fabs(fp - (2 - tr)), fabs(fm - (2 + tr))) / scale);
        worst_det = fmax(worst_det, fabs(x[0] * x[3] - x[1] * x[2] - 1));
    }
    print_message("# half period: the split factors against 2 -+ tr M, worst %.2g of the "
                  "scale; det - 1 %.2g\n", worst, worst_det);
    /* the same steps in both: the symmetric method's step over the mirrored half is the mirror
       of its step (R exp(Omega)^-1 R), so the two agree to round-off (1.8e-15 measured); 1e-12
       leaves the round-off of 400 steps room and no step error */
    assert_true(worst < 1e-12);
    assert_true(worst_det < 1e-12);
}

/* By the rate, then the amplitude. */
static int by_rate(const void *a, const void *b)
{
    const whirl_chart_point *p = a, *q = b;
    if (p->omega != q->omega) return p->omega < q->omega ? -1 : 1;
    return (p->amplitude > q->amplitude) - (p->amplitude < q->amplitude);
}

/* a_1(q) peaks (2.5217 at q = 2.880): the first tongue's left edge of the N = 1 chart turns back
 * in omega at omega_f = 2 / sqrt(max a_1), A_f = q / 2 (chart_folds.c). Over rates 1.2 .. 1.6
 * (11 rates, 0.04 apart) and A <= 2 (41 rows) the turning point lies between the rates 1.24 and
 * 1.28: the cap between them must be drawn. Every point on a_1 to 1e-8 in a; the lowest rate of
 * the points within 1e-3 of omega_f (the rows are 0.05 apart: omega(A) - omega_f ~ (A - A_f)^2)
 * and not below it (without the cap it is the rate 1.28, 0.02 off); the turning point in both
 * branches' curves; each branch sorted by the rate without a gap wider than a rate's step and a
 * row's at once. */
static void test_fold_cap(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_chart_params p = {.omega_min = 1.2, .omega_max = 1.6, .columns = 11,
                                  .amp_max = 2, .rows = 41};
    kept k = {0, malloc(MAX_POINTS * sizeof(whirl_chart_point))};
    assert_non_null(k.p);
    assert_int_equal(whirl_chart_vertical(c, 2, &p, keep_point, &k, NULL, NULL), GSL_SUCCESS);
    /* the maximum of a_1 by golden sections on q in [2, 4] (the Hill matrix, not the chart) */
    double lo = 2, hi = 4;
    const double r = (sqrt(5) - 1) / 2;
    while (hi - lo > 1e-9) {
        const double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
        if (hill(x1, 1, 0) > hill(x2, 1, 0)) hi = x2;
        else lo = x1;
    }
    const double qf = 0.5 * (lo + hi), wf = 2 / sqrt(hill(qf, 1, 0));
    double worst = 0, wmin = INFINITY;
    int low = -1;
    for (int i = 0; i < k.n; i++) {
        const whirl_chart_point *q = &k.p[i];
        if (q->kind != WHIRL_FLOQUET_EDGE_MINUS_ONE) continue;
        const double a = 4 / (q->omega * q->omega), d = fabs(a - hill(2 * q->amplitude, 1, 0));
        if (d > 1e-6) continue; /* b_1, the tongue's other edge */
        worst = fmax(worst, d);
        if (q->omega < wmin) wmin = q->omega, low = i;
    }
    assert_true(low >= 0);
    int curves[2] = {-1, -1}, shared = 0;
    for (int i = 0; i < k.n; i++)
        if (k.p[i].omega == k.p[low].omega && k.p[i].amplitude == k.p[low].amplitude) {
            curves[shared < 2 ? shared : 1] = k.p[i].curve;
            shared++;
        }
    const double dw = (p.omega_max - p.omega_min) / (p.columns - 1), da = p.amp_max / (p.rows - 1);
    double gap = 0;
    for (int b = 0; b < 2 && shared == 2; b++) {
        whirl_chart_point e[MAX_POINTS / 16];
        int m = 0;
        for (int i = 0; i < k.n && m < MAX_POINTS / 16; i++)
            if (k.p[i].curve == curves[b]) e[m++] = k.p[i];
        qsort(e, (size_t)m, sizeof *e, by_rate);
        for (int i = 1; i < m; i++)
            gap = fmax(gap, fmin(fabs(e[i].omega - e[i - 1].omega) / dw,
                                 fabs(e[i].amplitude - e[i - 1].amplitude) / da));
    }
    print_message("# fold of a_1: omega_f = %.9f at A_f = %.6f; the chart's lowest rate %.9f "
                  "(%.2g above) at A = %.4f, in %d curves (%d and %d); worst |a - a_1| %.2g; "
                  "largest gap %.3g steps\n", wf, qf / 2, wmin, wmin - wf, k.p[low].amplitude,
                  shared, curves[0] + 1, curves[1] + 1, worst, gap);
    assert_true(worst < 1e-8);
    assert_true(wmin - wf >= -1e-9 && wmin - wf < 1e-3);
    assert_int_equal(shared, 2);
    assert_true(curves[0] != curves[1]);
    assert_true(gap <= 1 + 1e-9); /* a rate's step, to the rounding of the rates */
    free(k.p);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half_period),
        cmocka_unit_test(test_thin_tongues),
        cmocka_unit_test(test_fold_cap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
