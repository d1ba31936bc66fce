/* Tests of the C path of the linear algebra (src/core/linalg_c.c), which the WebAssembly build
 * runs instead of LAPACK, against LAPACK itself (LAPACKE) on the same matrices: pseudo-random
 * ones of the sizes the library uses (60 x 60: the first-order form of 15 links), banded and
 * tridiagonal ones, and a mass-matrix-like positive definite one. Factorisations are compared
 * entry by entry (the same pivots; the unblocked algorithms differ from LAPACK's blocked ones
 * only in the rounding), eigenvalues as sets, eigenvectors up to the normalisation dgeev
 * promises (norm 1, largest component real, up to its sign). dgttrf is LAPACK's
 * own unblocked algorithm, so it must agree to the bit. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <lapacke.h>

#include "core/linalg.h"

/* A reproducible uniform number in [-1, 1) (a 64-bit linear congruential generator, Knuth's
 * MMIX constants). */
static double uniform(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 4503599627370496.0 - 1.0; /* 2^52: 53 bits in [0, 2) */
}

static double *random_matrix(size_t rows, size_t cols, uint64_t seed)
{
    double *a = malloc(rows * cols * sizeof *a);
    assert_non_null(a);
    for (size_t i = 0; i < rows * cols; i++) a[i] = uniform(&seed);
    return a;
}

static double *copy(const double *a, size_t n)
{
    double *b = malloc(n * sizeof *b);
    assert_non_null(b);
    memcpy(b, a, n * sizeof *b);
    return b;
}

/* |x - y| <= tol max(|y|, floor) for each entry */
static void assert_close(const double *x, const double *y, size_t n, double tol, double floor)
{
    for (size_t i = 0; i < n; i++) {
        const double scale = fabs(y[i]) > floor ? fabs(y[i]) : floor;
        if (!(fabs(x[i] - y[i]) <= tol * scale))
            fail_msg("entry %zu: %.17g against %.17g (tolerance %g)", i, x[i], y[i], tol);
    }
}

static int by_re_im(const void *p, const void *q)
{
    const double *a = p, *b = q;
    if (a[0] != b[0]) return (a[0] > b[0]) - (a[0] < b[0]);
    return (a[1] > b[1]) - (a[1] < b[1]);
}

/* The eigenvalues and eigenvectors of dgeev from LAPACK and the C path, for right (left = 0)
 * or left eigenvectors of an n x n random matrix. */
static void dgeev_case(size_t n, int left, uint64_t seed)
{
    double *a = random_matrix(n, n, seed), *a1 = copy(a, n * n), *a2 = copy(a, n * n);
    double *re1 = malloc(4 * n * sizeof(double)), *im1 = re1 + n, *re2 = re1 + 2 * n,
           *im2 = re1 + 3 * n;
    double *v1 = malloc(n * n * sizeof(double)), *v2 = malloc(n * n * sizeof(double));
    double query = 0;
    const char jl = left ? 'V' : 'N', jr = left ? 'N' : 'V';
    const lapack_int m = (lapack_int)n;
    assert_int_equal(LAPACKE_dgeev_work(LAPACK_COL_MAJOR, jl, jr, m, a1, m, re1, im1, v1, m, v1,
                                        m, &query, -1), 0);
    double *work = malloc((size_t)query * sizeof(double));
    assert_int_equal(LAPACKE_dgeev_work(LAPACK_COL_MAJOR, jl, jr, m, a1, m, re1, im1, v1, m, v1,
                                        m, work, (lapack_int)query), 0);
    assert_int_equal(whirl_la_c_dgeev(jl, jr, m, a2, m, re2, im2, v2, m, v2, m, &query, -1), 0);
    assert_int_equal(whirl_la_c_dgeev(jl, jr, m, a2, m, re2, im2, v2, m, v2, m, &query, 1), 0);
    /* the same eigenvalues, pairs stored positive imaginary part first */
    double *p1 = malloc(2 * n * sizeof(double)), *p2 = malloc(2 * n * sizeof(double));
    for (size_t k = 0; k < n; k++) {
        p1[2 * k] = re1[k], p1[2 * k + 1] = im1[k];
        p2[2 * k] = re2[k], p2[2 * k + 1] = im2[k];
        if (im2[k] != 0) {
            assert_true(k + 1 < n);
            assert_true(im2[k] > 0 && im2[k + 1] == -im2[k] && re2[k + 1] == re2[k]);
            p1[2 * k + 2] = re1[k + 1], p1[2 * k + 3] = im1[k + 1];
            p2[2 * k + 2] = re2[k + 1], p2[2 * k + 3] = im2[k + 1];
            k++;
        }
    }
    qsort(p1, n, 2 * sizeof(double), by_re_im);
    qsort(p2, n, 2 * sizeof(double), by_re_im);
    /* a random matrix of norm ~ sqrt(n): eigenvalues to ~1e-13 of it */
    assert_close(p2, p1, 2 * n, 1e-11, 1.0);
    /* each C-path eigenvector is LAPACK's of the same eigenvalue, up to the sign of a real one */
    for (size_t k = 0; k < n; k++) {
        size_t j = 0; /* LAPACK's index of the eigenvalue k */
        double best = INFINITY;
        for (size_t i = 0; i < n; i++) {
            const double d = hypot(re1[i] - re2[k], im1[i] - im2[k]);
            if (d < best) best = d, j = i;
        }
        const int pair = im2[k] != 0;
        assert_int_equal(im1[j] != 0, pair);
        double dot = 0; /* dgeev fixes a vector up to its sign (dlartg's r has f's sign) */
        for (size_t c = 0; c <= (size_t)pair; c++)
            for (size_t i = 0; i < n; i++) dot += v1[i + (j + c) * n] * v2[i + (k + c) * n];
        const double sign = dot < 0 ? -1 : 1;
        for (size_t c = 0; c <= (size_t)pair; c++)
            for (size_t i = 0; i < n; i++) {
                const double x = sign * v2[i + (k + c) * n], y = v1[i + (j + c) * n];
                if (!(fabs(x - y) <= 1e-9))
                    fail_msg("eigenvector %zu (%s), entry %zu: %.17g against LAPACK's %.17g", k,
                             left ? "left" : "right", i, x, y);
            }
        k += (size_t)pair;
    }
    free(p1), free(p2), free(work), free(v1), free(v2), free(re1), free(a), free(a1), free(a2);
}

static void dgeev_right(void **state)
{
    (void)state;
    dgeev_case(1, 0, 1);
    dgeev_case(7, 0, 2);
    dgeev_case(60, 0, 3);
}

static void dgeev_left(void **state)
{
    (void)state;
    dgeev_case(7, 1, 4);
    dgeev_case(60, 1, 5);
}

/* eigenvalues only, as the stability's verdict asks */
static void dgeev_values(void **state)
{
    (void)state;
    const size_t n = 40;
    double *a = random_matrix(n, n, 6), *a2 = copy(a, n * n);
    double re1[40], im1[40], re2[40], im2[40], work[40 * 34], one;
    assert_int_equal(LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', 40, a, 40, re1, im1, NULL, 1,
                                        NULL, 1, work, 40 * 34), 0);
    assert_int_equal(whirl_la_c_dgeev('N', 'N', 40, a2, 40, re2, im2, NULL, 1, NULL, 1, &one, 1),
                     0);
    double p1[80], p2[80];
    for (size_t k = 0; k < n; k++)
        p1[2 * k] = re1[k], p1[2 * k + 1] = im1[k], p2[2 * k] = re2[k], p2[2 * k + 1] = im2[k];
    qsort(p1, n, 2 * sizeof(double), by_re_im);
    qsort(p2, n, 2 * sizeof(double), by_re_im);
    assert_close(p2, p1, 2 * n, 1e-11, 1.0);
    free(a), free(a2);
}

/* A symmetric positive definite n x n matrix: B^T B + n I. */
static double *spd(size_t n, uint64_t seed)
{
    double *b = random_matrix(n, n, seed), *a = calloc(n * n, sizeof(double));
    assert_non_null(a);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            for (size_t k = 0; k < n; k++) a[i + j * n] += b[k + i * n] * b[k + j * n];
            if (i == j) a[i + j * n] += (double)n;
        }
    free(b);
    return a;
}

static void dsyev_values(void **state)
{
    (void)state;
    const size_t n = 30;
    double *a = spd(n, 7);
    for (size_t i = 0; i < n; i++) a[i + i * n] -= 2.0 * (double)n; /* indefinite */
    double *a2 = copy(a, n * n), w1[30], w2[30];
    assert_int_equal(LAPACKE_dsyev(LAPACK_COL_MAJOR, 'N', 'U', 30, a, 30, w1), 0);
    assert_int_equal(whirl_la_c_dsyev('N', 'U', 30, a2, 30, w2), 0);
    assert_close(w2, w1, n, 1e-12, 1.0);
    free(a), free(a2);
}

static void dposv_solve(void **state)
{
    (void)state;
    const size_t n = 24, r = 3;
    double *a = spd(n, 8), *a2 = copy(a, n * n);
    double *b = random_matrix(n, r, 9), *b2 = copy(b, n * r);
    assert_int_equal(LAPACKE_dposv_work(LAPACK_COL_MAJOR, 'L', 24, 3, a, 24, b, 24), 0);
    assert_int_equal(whirl_la_c_dposv('L', 24, 3, a2, 24, b2, 24), 0);
    assert_close(b2, b, n * r, 1e-13, 1e-3);
    for (size_t j = 0; j < n; j++) /* the factor L (lower triangle) */
        assert_close(a2 + j * n + j, a + j * n + j, n - j, 1e-13, 1e-3);
    /* not positive definite: info names the column */
    double bad[4] = {1, 2, 2, 1}, rhs[2] = {1, 1};
    assert_int_equal(whirl_la_c_dposv('L', 2, 1, bad, 2, rhs, 2), 2);
    free(a), free(a2), free(b), free(b2);
}

static void dgetrf_solve(void **state)
{
    (void)state;
    const size_t n = 50;
    double *a = random_matrix(n, n, 10), *a2 = copy(a, n * n);
    double *b = random_matrix(n, 1, 11), *b2 = copy(b, n);
    lapack_int p1[50], p2[50];
    assert_int_equal(LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, 50, 50, a, 50, p1), 0);
    assert_int_equal(whirl_la_c_dgetrf(50, 50, a2, 50, p2), 0);
    assert_memory_equal(p1, p2, sizeof p1);
    assert_close(a2, a, n * n, 1e-11, 1e-2);
    assert_int_equal(LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', 50, 1, a, 50, p1, b, 50), 0);
    assert_int_equal(whirl_la_c_dgetrs('N', 50, 1, a2, 50, p2, b2, 50), 0);
    assert_close(b2, b, n, 1e-10, 1e-1);
    free(a), free(a2), free(b), free(b2);
}

/* A banded n x n matrix with kl sub- and ku super-diagonals into LAPACK's band storage
 * (ldab = 2 kl + ku + 1), from a random dense one. */
static void dgbtrf_solve(void **state)
{
    (void)state;
    enum { N = 40, KL = 8, KU = 8, LD = 2 * KL + KU + 1 };
    double *dense = random_matrix(N, N, 12);
    double ab[LD * N], ab2[LD * N], b[2 * N], b2[2 * N];
    lapack_int p1[N], p2[N];
    for (size_t k = 0; k < LD * N; k++) ab[k] = NAN; /* the fill-in rows: must be zeroed */
    for (int j = 0; j < N; j++)
        for (int i = j - KU; i <= j + KL; i++)
            if (i >= 0 && i < N) ab[KL + KU + i - j + j * LD] = dense[i + j * N];
    memcpy(ab2, ab, sizeof ab);
    double *rhs = random_matrix(N, 2, 13);
    memcpy(b, rhs, sizeof b);
    memcpy(b2, rhs, sizeof b2);
    assert_int_equal(LAPACKE_dgbtrf_work(LAPACK_COL_MAJOR, N, N, KL, KU, ab, LD, p1), 0);
    assert_int_equal(whirl_la_c_dgbtrf(N, N, KL, KU, ab2, LD, p2), 0);
    assert_memory_equal(p1, p2, sizeof p1);
    assert_int_equal(LAPACKE_dgbtrs_work(LAPACK_COL_MAJOR, 'N', N, KL, KU, 2, ab, LD, p1, b, N), 0);
    assert_int_equal(whirl_la_c_dgbtrs('N', N, KL, KU, 2, ab2, LD, p2, b2, N), 0);
    assert_close(b2, b, 2 * N, 1e-10, 1e-1);
    free(dense), free(rhs);
}

static void dgttrf_bits(void **state)
{
    (void)state;
    enum { N = 33 };
    uint64_t s = 14;
    double dl[N], d[N], du[N], du2[N], dl2[N], dd2[N], duu2[N], du22[N];
    lapack_int p1[N], p2[N];
    for (int i = 0; i < N; i++) d[i] = uniform(&s), dl[i] = uniform(&s), du[i] = uniform(&s);
    d[5] = 0; /* a zero pivot candidate: the row interchange */
    memcpy(dl2, dl, sizeof dl), memcpy(dd2, d, sizeof d), memcpy(duu2, du, sizeof du);
    const lapack_int i1 = LAPACKE_dgttrf_work(N, dl, d, du, du2, p1);
    const lapack_int i2 = whirl_la_c_dgttrf(N, dl2, dd2, duu2, du22, p2);
    assert_int_equal(i1, i2);
    assert_memory_equal(dl, dl2, (N - 1) * sizeof(double));
    assert_memory_equal(d, dd2, N * sizeof(double));
    assert_memory_equal(du, duu2, (N - 1) * sizeof(double));
    assert_memory_equal(du2, du22, (N - 2) * sizeof(double));
    assert_memory_equal(p1, p2, sizeof p1);
}

/* The tridiagonal eigenvalues of the hanging chain's stiffness (nlink.c's critical rates):
 * d_i, e_i of a uniform chain of 400 links, eigenvalues 1..12 and 395..400. Both bisections
 * are as accurate as the Sturm count's rounding allows, ~eps |T| absolute (|T| ~ 6e5 here):
 * eigenvalue 2 is 7.6083333397240341 (the same count in 40 digits, mpmath, on the rounded d, e),
 * LAPACK gives 7.6083333397223214 (2.3e-13 relative) and the C path 7.6083333397255046
 * (1.9e-13). So each is held to 5e-13 of the other at the small eigenvalues, and the
 * reference value to 3e-13 for each. */
static void dstebz_chain(void **state)
{
    (void)state;
    enum { N = 400 };
    double d[N], e[N], w1[N], w2[N];
    lapack_int m1, m2, ns, b1[N], s1[N];
    const double l = 1.0 / N, mass = 1.0 / N;
    double v_below = 0;
    for (int i = N; i >= 1; i--) {
        const double stiff_below = i < N ? v_below / l : 0;
        v_below += mass;
        d[i - 1] = (v_below / l + stiff_below) / mass;
        if (i < N) e[i - 1] = -stiff_below / mass;
    }
    assert_int_equal(LAPACKE_dstebz('I', 'E', N, 0, 0, 1, 12, 2 * DBL_MIN, d, e, &m1, &ns, w1,
                                    b1, s1), 0);
    assert_int_equal(whirl_la_c_dstebz('I', 'E', N, 0, 0, 1, 12, 2 * DBL_MIN, d, e, &m2, &ns, w2,
                                       b1, s1), 0);
    assert_int_equal(m1, 12);
    assert_int_equal(m2, 12);
    assert_close(w2, w1, 12, 5e-13, 0);
    const double exact = 7.6083333397240341;
    assert_close(&w1[1], &exact, 1, 3e-13, 0);
    assert_close(&w2[1], &exact, 1, 3e-13, 0);
    assert_int_equal(whirl_la_c_dstebz('I', 'E', N, 0, 0, 395, N, 2 * DBL_MIN, d, e, &m2, &ns,
                                       w2, b1, s1), 0);
    assert_int_equal(LAPACKE_dstebz('I', 'E', N, 0, 0, 395, N, 2 * DBL_MIN, d, e, &m1, &ns, w1,
                                    b1, s1), 0);
    assert_close(w2, w1, 6, 4 * DBL_EPSILON, 0); /* the largest: relative to eps |T| */
}

/* What the C path does not support is refused with info -1, never half done. */
static void unsupported(void **state)
{
    (void)state;
    double a[4] = {1, 0, 0, 1}, w[2];
    assert_int_equal(whirl_la_c_dsyev('V', 'U', 2, a, 2, w), -1);
    assert_int_equal(whirl_la_c_dposv('U', 2, 1, a, 2, w, 2), -1);
    lapack_int m, ns, ib[2], is[2];
    assert_int_equal(whirl_la_c_dstebz('A', 'E', 2, 0, 0, 1, 2, 0, a, a, &m, &ns, w, ib, is), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dgeev_right),  cmocka_unit_test(dgeev_left),
        cmocka_unit_test(dgeev_values), cmocka_unit_test(dsyev_values),
        cmocka_unit_test(dposv_solve),  cmocka_unit_test(dgetrf_solve),
        cmocka_unit_test(dgbtrf_solve), cmocka_unit_test(dgttrf_bits),
        cmocka_unit_test(dstebz_chain), cmocka_unit_test(unsupported),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
