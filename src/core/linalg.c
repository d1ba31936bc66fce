/* The linear algebra interface (src/core/linalg.h): LAPACKE in the native build, the C path of
 * src/core/linalg_c.c with -DWHIRL_NO_LAPACK. The C path supports the column-major layout only,
 * which is all the library uses. */
#include "core/linalg.h"

#ifdef WHIRL_NO_LAPACK
#define LA_LAYOUT(layout) \
    if ((layout) != LAPACK_COL_MAJOR) return -1
#define LA(name, c_call, lapacke_call) c_call
#else
#define LA_LAYOUT(layout) (void)0
#define LA(name, c_call, lapacke_call) lapacke_call
#endif

lapack_int whirl_la_dgeev_work(int layout, char jobvl, char jobvr, lapack_int n, double *a,
                               lapack_int lda, double *wr, double *wi, double *vl,
                               lapack_int ldvl, double *vr, lapack_int ldvr, double *work,
                               lapack_int lwork)
{
    LA_LAYOUT(layout);
    return LA(dgeev, whirl_la_c_dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work,
                                      lwork),
              LAPACKE_dgeev_work(layout, jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr,
                                 work, lwork));
}

lapack_int whirl_la_dsyev(int layout, char jobz, char uplo, lapack_int n, double *a,
                          lapack_int lda, double *w)
{
    LA_LAYOUT(layout);
    return LA(dsyev, whirl_la_c_dsyev(jobz, uplo, n, a, lda, w),
              LAPACKE_dsyev(layout, jobz, uplo, n, a, lda, w));
}

lapack_int whirl_la_dposv_work(int layout, char uplo, lapack_int n, lapack_int nrhs, double *a,
                               lapack_int lda, double *b, lapack_int ldb)
{
    LA_LAYOUT(layout);
    return LA(dposv, whirl_la_c_dposv(uplo, n, nrhs, a, lda, b, ldb),
              LAPACKE_dposv_work(layout, uplo, n, nrhs, a, lda, b, ldb));
}

lapack_int whirl_la_dgetrf_work(int layout, lapack_int m, lapack_int n, double *a,
                                lapack_int lda, lapack_int *ipiv)
{
    LA_LAYOUT(layout);
    return LA(dgetrf, whirl_la_c_dgetrf(m, n, a, lda, ipiv),
              LAPACKE_dgetrf_work(layout, m, n, a, lda, ipiv));
}

lapack_int whirl_la_dgetrs_work(int layout, char trans, lapack_int n, lapack_int nrhs,
                                const double *a, lapack_int lda, const lapack_int *ipiv,
                                double *b, lapack_int ldb)
{
    LA_LAYOUT(layout);
    return LA(dgetrs, whirl_la_c_dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb),
              LAPACKE_dgetrs_work(layout, trans, n, nrhs, a, lda, ipiv, b, ldb));
}

lapack_int whirl_la_dgbtrf_work(int layout, lapack_int m, lapack_int n, lapack_int kl,
                                lapack_int ku, double *ab, lapack_int ldab, lapack_int *ipiv)
{
    LA_LAYOUT(layout);
    return LA(dgbtrf, whirl_la_c_dgbtrf(m, n, kl, ku, ab, ldab, ipiv),
              LAPACKE_dgbtrf_work(layout, m, n, kl, ku, ab, ldab, ipiv));
}

lapack_int whirl_la_dgbtrs_work(int layout, char trans, lapack_int n, lapack_int kl,
                                lapack_int ku, lapack_int nrhs, const double *ab,
                                lapack_int ldab, const lapack_int *ipiv, double *b,
                                lapack_int ldb)
{
    LA_LAYOUT(layout);
    return LA(dgbtrs, whirl_la_c_dgbtrs(trans, n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb),
              LAPACKE_dgbtrs_work(layout, trans, n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb));
}

lapack_int whirl_la_dgttrf_work(lapack_int n, double *dl, double *d, double *du, double *du2,
                                lapack_int *ipiv)
{
    return LA(dgttrf, whirl_la_c_dgttrf(n, dl, d, du, du2, ipiv),
              LAPACKE_dgttrf_work(n, dl, d, du, du2, ipiv));
}

lapack_int whirl_la_dstebz(char range, char order, lapack_int n, double vl, double vu,
                           lapack_int il, lapack_int iu, double abstol, const double *d,
                           const double *e, lapack_int *m, lapack_int *nsplit, double *w,
                           lapack_int *iblock, lapack_int *isplit)
{
    return LA(dstebz, whirl_la_c_dstebz(range, order, n, vl, vu, il, iu, abstol, d, e, m, nsplit,
                                        w, iblock, isplit),
              LAPACKE_dstebz(range, order, n, vl, vu, il, iu, abstol, d, e, m, nsplit, w, iblock,
                             isplit));
}
