/* The dense and banded linear algebra of the library, behind one interface (src/core/linalg.c).
 *
 * Each whirl_la_X has the arguments and the results of LAPACKE's LAPACKE_X (column-major only,
 * matrix_layout LAPACK_COL_MAJOR; the return value is LAPACK's info). The native build forwards
 * to LAPACKE; compiled with -DWHIRL_NO_LAPACK (the WebAssembly build, where no LAPACK exists)
 * every call runs the C path of src/core/linalg_c.c instead: GSL's eigensolvers for the dense
 * eigenproblems, and the unblocked reference algorithms of LAPACK (dgetf2, dpotf2, dgbtf2,
 * dgttrf, bisection with Sturm counts) for the factorisations. The C path is compiled into
 * every build, so that the native tests compare it with LAPACK (tests/unit/core/test_linalg.c).
 *
 * What the C path gives differently:
 *  - dgeev: the eigenvalues in GSL's order (each complex pair adjacent, the one with positive
 *    imaginary part first, as LAPACK stores them); each eigenvector of Euclidean norm 1 with its
 *    largest component real, as dgeev's, up to the sign (which dgeev does not fix either). The
 *    workspace query (lwork -1) answers 1: GSL allocates its own workspace.
 *  - the factorisations: the unblocked algorithms, so results differ from the blocked ones in
 *    the rounding (a few units in the last place times the condition).
 *  - dstebz: range 'I' and order 'E' only (all that the library asks), one block. */
#ifndef WHIRL_CORE_LINALG_H
#define WHIRL_CORE_LINALG_H

#ifdef WHIRL_NO_LAPACK
typedef int lapack_int;
#define LAPACK_ROW_MAJOR 101
#define LAPACK_COL_MAJOR 102
#else
#include <lapacke.h>
#endif

/* ---- the interface (LAPACKE's or the C path, by the build) ---- */
lapack_int whirl_la_dgeev_work(int layout, char jobvl, char jobvr, lapack_int n, double *a,
                               lapack_int lda, double *wr, double *wi, double *vl,
                               lapack_int ldvl, double *vr, lapack_int ldvr, double *work,
                               lapack_int lwork);
lapack_int whirl_la_dsyev(int layout, char jobz, char uplo, lapack_int n, double *a,
                          lapack_int lda, double *w);
lapack_int whirl_la_dposv_work(int layout, char uplo, lapack_int n, lapack_int nrhs, double *a,
                               lapack_int lda, double *b, lapack_int ldb);
lapack_int whirl_la_dgetrf_work(int layout, lapack_int m, lapack_int n, double *a,
                                lapack_int lda, lapack_int *ipiv);
lapack_int whirl_la_dgetrs_work(int layout, char trans, lapack_int n, lapack_int nrhs,
                                const double *a, lapack_int lda, const lapack_int *ipiv,
                                double *b, lapack_int ldb);
lapack_int whirl_la_dgbtrf_work(int layout, lapack_int m, lapack_int n, lapack_int kl,
                                lapack_int ku, double *ab, lapack_int ldab, lapack_int *ipiv);
lapack_int whirl_la_dgbtrs_work(int layout, char trans, lapack_int n, lapack_int kl,
                                lapack_int ku, lapack_int nrhs, const double *ab,
                                lapack_int ldab, const lapack_int *ipiv, double *b,
                                lapack_int ldb);
lapack_int whirl_la_dgttrf_work(lapack_int n, double *dl, double *d, double *du, double *du2,
                                lapack_int *ipiv);
lapack_int whirl_la_dstebz(char range, char order, lapack_int n, double vl, double vu,
                           lapack_int il, lapack_int iu, double abstol, const double *d,
                           const double *e, lapack_int *m, lapack_int *nsplit, double *w,
                           lapack_int *iblock, lapack_int *isplit);

/* ---- the C path (src/core/linalg_c.c): the same arguments; only what the library asks is
 * supported (column-major; trans 'N'; uplo 'L' for dposv, 'U' for dsyev with jobz 'N'),
 * anything else answers info -1. ---- */
lapack_int whirl_la_c_dgeev(char jobvl, char jobvr, lapack_int n, double *a, lapack_int lda,
                            double *wr, double *wi, double *vl, lapack_int ldvl, double *vr,
                            lapack_int ldvr, double *work, lapack_int lwork);
lapack_int whirl_la_c_dsyev(char jobz, char uplo, lapack_int n, double *a, lapack_int lda,
                            double *w);
lapack_int whirl_la_c_dposv(char uplo, lapack_int n, lapack_int nrhs, double *a, lapack_int lda,
                            double *b, lapack_int ldb);
lapack_int whirl_la_c_dgetrf(lapack_int m, lapack_int n, double *a, lapack_int lda,
                             lapack_int *ipiv);
lapack_int whirl_la_c_dgetrs(char trans, lapack_int n, lapack_int nrhs, const double *a,
                             lapack_int lda, const lapack_int *ipiv, double *b, lapack_int ldb);
lapack_int whirl_la_c_dgbtrf(lapack_int m, lapack_int n, lapack_int kl, lapack_int ku,
                             double *ab, lapack_int ldab, lapack_int *ipiv);
lapack_int whirl_la_c_dgbtrs(char trans, lapack_int n, lapack_int kl, lapack_int ku,
                             lapack_int nrhs, const double *ab, lapack_int ldab,
                             const lapack_int *ipiv, double *b, lapack_int ldb);
lapack_int whirl_la_c_dgttrf(lapack_int n, double *dl, double *d, double *du, double *du2,
                             lapack_int *ipiv);
lapack_int whirl_la_c_dstebz(char range, char order, lapack_int n, double vl, double vu,
                             lapack_int il, lapack_int iu, double abstol, const double *d,
                             const double *e, lapack_int *m, lapack_int *nsplit, double *w,
                             lapack_int *iblock, lapack_int *isplit);

#endif
