/* The C path of the linear algebra (src/core/linalg.h): what the library asks of LAPACK, in C
 * and GSL, for the builds without LAPACK (WebAssembly). Column-major storage as LAPACK's:
 * element (i, j) of a matrix with leading dimension ld at a[i + j ld], 0-based here.
 *
 * The factorisations follow LAPACK's unblocked reference routines operation for operation
 * (dgetf2 and dgetrs, dpotf2 and dpotrs, dgbtf2 and dgbtrs, dgttrf), the eigenproblems use GSL
 * (gsl_eigen_nonsymm(v) with balancing, as dgeev balances; gsl_eigen_symm), and dstebz's
 * bisection is Kahan's Sturm count with LAPACK's pivot guard (dlaebz). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>

#include "core/linalg.h"

#define AT(a, ld, i, j) (a)[(size_t)(i) + (size_t)(j) * (size_t)(ld)]

/* ---- dgeev ---- */

/* Scales the complex vector v (n entries) to Euclidean norm 1 with its largest component real
 * and positive, as dgeev normalises its eigenvectors. */
static void unit_phase(gsl_vector_complex_view v)
{
    const size_t n = v.vector.size;
    double norm = 0, big = -1;
    size_t at = 0;
    for (size_t i = 0; i < n; i++) {
        const double a2 = gsl_complex_abs2(gsl_vector_complex_get(&v.vector, i));
        norm += a2;
        if (a2 > big) big = a2, at = i;
    }
    if (!(norm > 0)) return;
    const gsl_complex top = gsl_vector_complex_get(&v.vector, at);
    /* v conj(top) / (|top| |v|): the largest component becomes |top| / |v| > 0 */
    const gsl_complex scale =
        gsl_complex_div_real(gsl_complex_conjugate(top), sqrt(big) * sqrt(norm));
    gsl_vector_complex_scale(&v.vector, scale);
}

lapack_int whirl_la_c_dgeev(char jobvl, char jobvr, lapack_int n, double *a, lapack_int lda,
                            double *wr, double *wi, double *vl, lapack_int ldvl, double *vr,
                            lapack_int ldvr, double *work, lapack_int lwork)
{
    if ((jobvl != 'N' && jobvl != 'V') || (jobvr != 'N' && jobvr != 'V') ||
        (jobvl == 'V' && jobvr == 'V') || n < 0 || lda < (n > 1 ? n : 1))
        return -1;
    if (lwork == -1) { /* the workspace query: GSL allocates its own */
        work[0] = 1;
        return 0;
    }
    if (n == 0) return 0;
    const int left = jobvl == 'V', vectors = left || jobvr == 'V';
    double *v = left ? vl : vr;
    const lapack_int ldv = left ? ldvl : ldvr;
    const size_t m = (size_t)n;
    /* the left eigenvectors of A are the conjugated right ones of A^T: u^H A = lambda u^H is
     * A^T conj(u) = lambda conj(u) for real A */
    gsl_matrix *g = gsl_matrix_alloc(m, m);
    gsl_vector_complex *eval = gsl_vector_complex_alloc(m);
    gsl_matrix_complex *evec = vectors ? gsl_matrix_complex_alloc(m, m) : NULL;
    gsl_eigen_nonsymm_workspace *w = vectors ? NULL : gsl_eigen_nonsymm_alloc(m);
    gsl_eigen_nonsymmv_workspace *wv = vectors ? gsl_eigen_nonsymmv_alloc(m) : NULL;
    lapack_int info = 0;
    if (g == NULL || eval == NULL || (vectors ? evec == NULL || wv == NULL : w == NULL)) {
        info = -1;
        goto done;
    }
    /* gsl_matrix is row-major: g(i, j) = A(i, j), or A(j, i) for the left vectors */
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++)
            gsl_matrix_set(g, i, j, left ? AT(a, lda, j, i) : AT(a, lda, i, j));
    int status;
    if (vectors) {
        gsl_eigen_nonsymmv_params(1, wv); /* balance, as dgeev does */
        status = gsl_eigen_nonsymmv(g, eval, evec, wv);
    } else {
        gsl_eigen_nonsymm_params(0, 1, w);
        status = gsl_eigen_nonsymm(g, eval, w);
    }
    if (status != GSL_SUCCESS) { /* the QR iteration did not converge */
        info = n;
        goto done;
    }
    for (size_t k = 0; k < m; k++) {
        const gsl_complex z = gsl_vector_complex_get(eval, k);
        wr[k] = GSL_REAL(z);
        wi[k] = GSL_IMAG(z);
    }
    /* LAPACK's order within a complex pair: positive imaginary part first */
    for (size_t k = 0; k + 1 < m; k++) {
        if (wi[k] == 0) continue;
        if (wi[k] < 0) {
            wi[k] = -wi[k];
            wi[k + 1] = -wi[k + 1];
            if (vectors) gsl_matrix_complex_swap_columns(evec, k, k + 1);
        }
        k++;
    }
    if (!vectors) goto done;
    for (size_t k = 0; k < m; k++) {
        unit_phase(gsl_matrix_complex_column(evec, k));
        if (wi[k] == 0) {
            for (size_t i = 0; i < m; i++)
                AT(v, ldv, i, k) = GSL_REAL(gsl_matrix_complex_get(evec, i, k));
            continue;
        }
        /* the pair k, k+1: v_k = re + i im stored as columns re, im; a left vector is the
         * conjugate of A^T's right vector of the conjugate eigenvalue, which is column k */
        const double sign = left ? -1.0 : 1.0;
        for (size_t i = 0; i < m; i++) {
            const gsl_complex z = gsl_matrix_complex_get(evec, i, k);
            AT(v, ldv, i, k) = GSL_REAL(z);
            AT(v, ldv, i, k + 1) = sign * GSL_IMAG(z);
        }
        k++;
    }
done:
    gsl_eigen_nonsymm_free(w);
    gsl_eigen_nonsymmv_free(wv);
    gsl_matrix_complex_free(evec);
    gsl_vector_complex_free(eval);
    gsl_matrix_free(g);
    return info;
}

/* ---- dsyev (eigenvalues only) ---- */

static int ascending(const void *p, const void *q)
{
    const double x = *(const double *)p, y = *(const double *)q;
    return (x > y) - (x < y);
}

lapack_int whirl_la_c_dsyev(char jobz, char uplo, lapack_int n, double *a, lapack_int lda,
                            double *w)
{
    if (jobz != 'N' || uplo != 'U' || n < 0 || lda < (n > 1 ? n : 1)) return -1;
    if (n == 0) return 0;
    const size_t m = (size_t)n;
    gsl_matrix *g = gsl_matrix_alloc(m, m);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(m);
    gsl_vector_view ev = gsl_vector_view_array(w, m);
    lapack_int info = -1;
    if (g != NULL && ws != NULL) {
        for (size_t j = 0; j < m; j++) /* the upper triangle, mirrored */
            for (size_t i = 0; i <= j; i++) {
                gsl_matrix_set(g, i, j, AT(a, lda, i, j));
                gsl_matrix_set(g, j, i, AT(a, lda, i, j));
            }
        info = gsl_eigen_symm(g, &ev.vector, ws) == GSL_SUCCESS ? 0 : n;
        if (info == 0) qsort(w, m, sizeof *w, ascending);
    }
    gsl_eigen_symm_free(ws);
    gsl_matrix_free(g);
    return info;
}

/* ---- dposv: Cholesky A = L L^T (dpotf2, lower), then L L^T X = B (dpotrs) ---- */

lapack_int whirl_la_c_dposv(char uplo, lapack_int n, lapack_int nrhs, double *a, lapack_int lda,
                            double *b, lapack_int ldb)
{
    if (uplo != 'L' || n < 0 || nrhs < 0 || lda < (n > 1 ? n : 1) || ldb < (n > 1 ? n : 1))
        return -1;
    for (lapack_int j = 0; j < n; j++) {
        double ajj = AT(a, lda, j, j);
        for (lapack_int k = 0; k < j; k++) ajj -= AT(a, lda, j, k) * AT(a, lda, j, k);
        if (!(ajj > 0)) { /* not positive definite (or NaN): dpotf2's info */
            AT(a, lda, j, j) = ajj;
            return j + 1;
        }
        ajj = sqrt(ajj);
        AT(a, lda, j, j) = ajj;
        for (lapack_int i = j + 1; i < n; i++) {
            double s = AT(a, lda, i, j);
            for (lapack_int k = 0; k < j; k++) s -= AT(a, lda, i, k) * AT(a, lda, j, k);
            AT(a, lda, i, j) = s / ajj;
        }
    }
    for (lapack_int c = 0; c < nrhs; c++) {
        double *x = b + (size_t)c * (size_t)ldb;
        for (lapack_int i = 0; i < n; i++) { /* L y = b */
            double s = x[i];
            for (lapack_int k = 0; k < i; k++) s -= AT(a, lda, i, k) * x[k];
            x[i] = s / AT(a, lda, i, i);
        }
        for (lapack_int i = n - 1; i >= 0; i--) { /* L^T x = y */
            double s = x[i];
            for (lapack_int k = i + 1; k < n; k++) s -= AT(a, lda, k, i) * x[k];
            x[i] = s / AT(a, lda, i, i);
        }
    }
    return 0;
}

/* ---- dgetrf / dgetrs: LU with partial pivoting (dgetf2), pivots from 1 ---- */

lapack_int whirl_la_c_dgetrf(lapack_int m, lapack_int n, double *a, lapack_int lda,
                             lapack_int *ipiv)
{
    if (m < 0 || n < 0 || lda < (m > 1 ? m : 1)) return -1;
    lapack_int info = 0;
    const lapack_int mn = m < n ? m : n;
    for (lapack_int j = 0; j < mn; j++) {
        lapack_int p = j; /* idamax: the first largest */
        for (lapack_int i = j + 1; i < m; i++)
            if (fabs(AT(a, lda, i, j)) > fabs(AT(a, lda, p, j))) p = i;
        ipiv[j] = p + 1;
        if (AT(a, lda, p, j) != 0) {
            if (p != j)
                for (lapack_int k = 0; k < n; k++) {
                    const double t = AT(a, lda, j, k);
                    AT(a, lda, j, k) = AT(a, lda, p, k);
                    AT(a, lda, p, k) = t;
                }
            const double r = 1 / AT(a, lda, j, j);
            for (lapack_int i = j + 1; i < m; i++) AT(a, lda, i, j) *= r;
        } else if (info == 0)
            info = j + 1;
        for (lapack_int k = j + 1; k < n; k++) {
            const double t = AT(a, lda, j, k);
            for (lapack_int i = j + 1; i < m; i++) AT(a, lda, i, k) -= AT(a, lda, i, j) * t;
        }
    }
    return info;
}

lapack_int whirl_la_c_dgetrs(char trans, lapack_int n, lapack_int nrhs, const double *a,
                             lapack_int lda, const lapack_int *ipiv, double *b, lapack_int ldb)
{
    if (trans != 'N' || n < 0 || nrhs < 0 || lda < (n > 1 ? n : 1) || ldb < (n > 1 ? n : 1))
        return -1;
    for (lapack_int c = 0; c < nrhs; c++) {
        double *x = b + (size_t)c * (size_t)ldb;
        for (lapack_int i = 0; i < n; i++) { /* the row interchanges (dlaswp) */
            const lapack_int p = ipiv[i] - 1;
            if (p != i) {
                const double t = x[i];
                x[i] = x[p];
                x[p] = t;
            }
        }
        for (lapack_int j = 0; j < n; j++) /* L, unit diagonal */
            if (x[j] != 0)
                for (lapack_int i = j + 1; i < n; i++) x[i] -= x[j] * AT(a, lda, i, j);
        for (lapack_int j = n - 1; j >= 0; j--) /* U (dtrsm's column order) */
            if (x[j] != 0) {
                x[j] /= AT(a, lda, j, j);
                for (lapack_int i = 0; i < j; i++) x[i] -= x[j] * AT(a, lda, i, j);
            }
    }
    return 0;
}

/* ---- dgbtrf / dgbtrs: banded LU with partial pivoting (dgbtf2). Band storage: A(i, j) at
 * ab[kv + i - j + j ldab] (0-based, kv = kl + ku), the first kl rows for the fill-in. ---- */

#define AB(i, j) AT(ab, ldab, (i), (j)) /* row i of the band storage, column j, 0-based */

lapack_int whirl_la_c_dgbtrf(lapack_int m, lapack_int n, lapack_int kl, lapack_int ku,
                             double *ab, lapack_int ldab, lapack_int *ipiv)
{
    if (m < 0 || n < 0 || kl < 0 || ku < 0 || ldab < 2 * kl + ku + 1) return -1;
    const lapack_int kv = ku + kl;
    lapack_int info = 0;
    /* the fill-in of columns ku+1 .. kv-1 (0-based) starts at zero */
    for (lapack_int j = ku + 1; j < kv && j < n; j++)
        for (lapack_int i = kv - j; i < kl; i++) AB(i, j) = 0;
    lapack_int ju = 0; /* the last column the U factor reaches so far */
    const lapack_int mn = m < n ? m : n;
    for (lapack_int j = 0; j < mn; j++) {
        if (j + kv < n)
            for (lapack_int i = 0; i < kl; i++) AB(i, j + kv) = 0;
        const lapack_int km = kl < m - j - 1 ? kl : m - j - 1;
        lapack_int jp = 0; /* idamax over the km + 1 entries from the diagonal down */
        for (lapack_int i = 1; i <= km; i++)
            if (fabs(AB(kv + i, j)) > fabs(AB(kv + jp, j))) jp = i;
        ipiv[j] = jp + j + 1;
        if (AB(kv + jp, j) != 0) {
            const lapack_int reach = j + ku + jp < n - 1 ? j + ku + jp : n - 1;
            if (reach > ju) ju = reach;
            if (jp != 0) /* swap rows j and j + jp over columns j..ju (stride ldab - 1) */
                for (lapack_int k = 0; k <= ju - j; k++) {
                    double *x = &AB(kv + jp - k, j + k), *y = &AB(kv - k, j + k);
                    const double t = *x;
                    *x = *y;
                    *y = t;
                }
            if (km > 0) {
                const double r = 1 / AB(kv, j);
                for (lapack_int i = 1; i <= km; i++) AB(kv + i, j) *= r;
                for (lapack_int c = 1; c <= ju - j; c++) { /* the rank-1 update (dger) */
                    const double yc = AB(kv - c, j + c);
                    if (yc != 0)
                        for (lapack_int i = 1; i <= km; i++)
                            AB(kv + i - c, j + c) -= AB(kv + i, j) * yc;
                }
            }
        } else if (info == 0)
            info = j + 1;
    }
    return info;
}

lapack_int whirl_la_c_dgbtrs(char trans, lapack_int n, lapack_int kl, lapack_int ku,
                             lapack_int nrhs, const double *ab, lapack_int ldab,
                             const lapack_int *ipiv, double *b, lapack_int ldb)
{
    if (trans != 'N' || n < 0 || kl < 0 || ku < 0 || nrhs < 0 || ldab < 2 * kl + ku + 1 ||
        ldb < (n > 1 ? n : 1))
        return -1;
    const lapack_int kd = ku + kl, k = kl + ku; /* the diagonal's row; U's bandwidth */
    for (lapack_int c = 0; c < nrhs; c++) {
        double *x = b + (size_t)c * (size_t)ldb;
        if (kl > 0)
            for (lapack_int j = 0; j < n - 1; j++) { /* L, with the interchanges */
                const lapack_int lm = kl < n - j - 1 ? kl : n - j - 1, l = ipiv[j] - 1;
                if (l != j) {
                    const double t = x[l];
                    x[l] = x[j];
                    x[j] = t;
                }
                for (lapack_int i = 1; i <= lm; i++) x[j + i] -= AB(kd + i, j) * x[j];
            }
        for (lapack_int j = n - 1; j >= 0; j--) /* U (dtbsv, upper, bandwidth kl + ku) */
            if (x[j] != 0) {
                x[j] /= AB(k, j);
                const double t = x[j];
                for (lapack_int i = j - 1; i >= 0 && i >= j - k; i--) x[i] -= t * AB(k + i - j, j);
            }
    }
    return 0;
}

#undef AB

/* ---- dgttrf: tridiagonal LU with partial pivoting, LAPACK's dgttrf line for line (0-based;
 * the second super-diagonal of U in du2, pivots from 1) ---- */

lapack_int whirl_la_c_dgttrf(lapack_int n, double *dl, double *d, double *du, double *du2,
                             lapack_int *ipiv)
{
    if (n < 0) return -1;
    if (n == 0) return 0;
    for (lapack_int i = 0; i < n; i++) ipiv[i] = i + 1;
    for (lapack_int i = 0; i < n - 2; i++) du2[i] = 0;
    for (lapack_int i = 0; i < n - 1; i++) {
        if (fabs(d[i]) >= fabs(dl[i])) { /* no interchange */
            if (d[i] != 0) {
                const double fact = dl[i] / d[i];
                dl[i] = fact;
                d[i + 1] -= fact * du[i];
            }
        } else { /* interchange rows i and i + 1 */
            const double fact = d[i] / dl[i];
            d[i] = dl[i];
            dl[i] = fact;
            const double temp = du[i];
            du[i] = d[i + 1];
            d[i + 1] = temp - fact * d[i + 1];
            if (i < n - 2) {
                du2[i] = du[i + 1];
                du[i + 1] = -fact * du[i + 1];
            }
            ipiv[i] = i + 2;
        }
    }
    for (lapack_int i = 0; i < n; i++)
        if (d[i] == 0) return i + 1;
    return 0;
}

/* ---- dstebz: eigenvalues il..iu of the symmetric tridiagonal T (diagonal d, off-diagonal e)
 * by bisection ----
 * The Sturm count: the number of negative pivots of T - x I (Kahan 1966), with a pivot below
 * pivmin in magnitude moved to -pivmin (dlaebz's guard). Each eigenvalue is bisected from the
 * Gershgorin interval until its bracket is down to abstol or to the spacing of the numbers
 * (the midpoint equals an end). */

static lapack_int sturm_count(lapack_int n, const double *d, const double *e, double x,
                              double pivmin)
{
    lapack_int count = 0;
    double q = d[0] - x;
    if (fabs(q) <= pivmin) q = -pivmin;
    if (q < 0) count++;
    for (lapack_int i = 1; i < n; i++) {
        q = d[i] - x - e[i - 1] * e[i - 1] / q;
        if (fabs(q) <= pivmin) q = -pivmin;
        if (q < 0) count++;
    }
    return count;
}

lapack_int whirl_la_c_dstebz(char range, char order, lapack_int n, double vl, double vu,
                             lapack_int il, lapack_int iu, double abstol, const double *d,
                             const double *e, lapack_int *m, lapack_int *nsplit, double *w,
                             lapack_int *iblock, lapack_int *isplit)
{
    (void)vl, (void)vu;
    *m = 0;
    if (range != 'I' || order != 'E' || n < 0 || il < 1 || iu < il || iu > n) return -1;
    if (n == 0) return 0;
    /* the Gershgorin interval, and dstebz's pivmin: the safe minimum times the largest e^2 */
    double lo = d[0], hi = d[0], emax2 = 1;
    for (lapack_int i = 0; i < n; i++) {
        const double r = (i > 0 ? fabs(e[i - 1]) : 0) + (i < n - 1 ? fabs(e[i]) : 0);
        if (d[i] - r < lo) lo = d[i] - r;
        if (d[i] + r > hi) hi = d[i] + r;
        if (i < n - 1 && e[i] * e[i] > emax2) emax2 = e[i] * e[i];
    }
    const double pivmin = DBL_MIN * emax2;
    /* widened by a few units of the interval's scale so that the ends bracket every
     * eigenvalue despite the rounding of the counts (dstebz widens by 2 ulp n + 2 pivmin) */
    const double wide = 2 * DBL_EPSILON * n * fmax(fabs(lo), fabs(hi)) + 2 * pivmin;
    lo -= wide;
    hi += wide;
    for (lapack_int k = il; k <= iu; k++) {
        double a = lo, b = hi; /* count(a) < k <= count(b) */
        for (;;) {
            const double mid = 0.5 * (a + b);
            if (mid <= a || mid >= b || b - a <= abstol) break;
            if (sturm_count(n, d, e, mid, pivmin) >= k)
                b = mid;
            else
                a = mid;
        }
        w[k - il] = 0.5 * (a + b);
        iblock[k - il] = 1;
    }
    *m = iu - il + 1;
    *nsplit = 1;
    isplit[0] = n;
    return 0;
}
