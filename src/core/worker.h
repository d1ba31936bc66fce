/* Internal: work that cannot poll the stop request (one dense LAPACK solve, NLopt's own linear
 * algebra between two objective evaluations), run so that the caller can still return promptly
 * on a stop request (src/worker.c). */
#ifndef WHIRL_WORKER_H
#define WHIRL_WORKER_H

#include <stddef.h>

#include "core/linalg.h"

typedef struct whirl_worker whirl_worker; /* the control block of one run */

/* The work: runs fn(arg, self). It may ask whirl_worker_abandoned(self) between its pieces and
 * should then return soon; it must record its own status and message in arg, in a
 * whirl_error_record (whirl_error_keep there, whirl_error_restore on the caller's thread: the
 * thread-local last error of a worker thread is not the caller's). */
typedef void (*whirl_work_fn)(void *arg, const whirl_worker *self);

/* Runs fn(arg, self) on a thread of its own while the calling thread polls the stop request
 * (whirl_stop_requested) every WORKER_POLL_SECONDS (20 ms). Returns
 *  - GSL_SUCCESS once fn returned: arg is the caller's again, with fn's results;
 *  - WHIRL_EINTERRUPTED (message set) if a stop was requested first: the caller must not touch
 *    arg any more; it now belongs to the worker, which calls release(arg) as soon as fn returns
 *    (whirl_worker_abandoned(self) is then 1). Whatever fn reads must therefore live in arg
 *    (copies, not the caller's memory).
 * If no thread can be started, fn runs in the calling thread (GSL_SUCCESS). */
int whirl_worker_run(whirl_work_fn fn, void *arg, void (*release)(void *arg));

/* whirl_worker_run that also calls tick(tick_data) on the calling thread at every poll (about
 * every WORKER_POLL_SECONDS while fn runs; tick may be NULL): for a progress display, reading
 * what fn publishes through atomics. */
int whirl_worker_run_ticked(whirl_work_fn fn, void *arg, void (*release)(void *arg),
                            void (*tick)(void *tick_data), void *tick_data);

/* 1 once the caller of whirl_worker_run has returned without waiting for fn (self may be NULL:
 * fn run inline, never abandoned). Thread-safe. */
int whirl_worker_abandoned(const whirl_worker *self);

/* LAPACK's dgeev (column-major) of the m x m matrix a (leading dimension lda, overwritten as
 * dgeev does): eigenvalues into re, im, and the left (jobvl 'V') or the right (jobvr 'V')
 * eigenvectors, not both, into v (leading dimension ldv); work, lwork: a workspace for m as
 * dgeev's query gives. Above WORKER_DGEEV_INLINE_MAX rows it runs on a copy in a worker
 * (whirl_worker_run), so that a stop request ends the call at once. *info is dgeev's; returns
 * GSL_SUCCESS, WHIRL_EINTERRUPTED (message set; re, im, v untouched) or GSL_ENOMEM. */
#define WORKER_DGEEV_INLINE_MAX 64
int whirl_worker_dgeev(char jobvl, char jobvr, size_t m, double *a, size_t lda, double *re,
                       double *im, double *v, size_t ldv, double *work, int lwork, int *info);

/* LAPACK's LU of a dense n x n matrix (column-major, leading dimension lda), as the routines of
 * the same name: dgetrf factors a in place (pivots into ipiv); dgetrs solves with those factors
 * for the n x nrhs right-hand sides b (leading dimension ldb) in place; dgesv does both. Work
 * above WORKER_INLINE_FLOPS floating-point operations runs on copies in a worker
 * (whirl_worker_run), so that a stop request ends the call at once; smaller work runs here.
 * *info is LAPACK's; returns GSL_SUCCESS, WHIRL_EINTERRUPTED (message set; a, ipiv, b
 * untouched) or GSL_ENOMEM. */
#define WORKER_INLINE_FLOPS 2e7 /* about 10 ms of one core: below, a thread costs more */
int whirl_worker_dgetrf(size_t n, double *a, size_t lda, lapack_int *ipiv, int *info);
int whirl_worker_dgetrs(size_t n, size_t nrhs, const double *a, size_t lda,
                        const lapack_int *ipiv, double *b, size_t ldb, int *info);
int whirl_worker_dgesv(size_t n, size_t nrhs, double *a, size_t lda, lapack_int *ipiv, double *b,
                       size_t ldb, int *info);

/* LAPACK's dposv (column-major, lower triangle 'L'): the Cholesky factor of the symmetric
 * positive definite n x n matrix a into its lower triangle, and the n x nrhs right-hand sides b
 * solved in place. As the LU helpers above: above WORKER_INLINE_FLOPS on copies in a worker.
 * *info is LAPACK's; returns GSL_SUCCESS, WHIRL_EINTERRUPTED (message set; a, b untouched) or
 * GSL_ENOMEM. */
int whirl_worker_dposv(size_t n, size_t nrhs, double *a, size_t lda, double *b, size_t ldb,
                       int *info);

/* LAPACK's dsyev without eigenvectors (column-major, upper triangle 'U'): the eigenvalues of the
 * symmetric n x n matrix a (leading dimension lda, overwritten as dsyev does) in ascending order
 * into ev. Above WORKER_INLINE_FLOPS on copies in a worker. *info is LAPACK's; returns
 * GSL_SUCCESS, WHIRL_EINTERRUPTED (message set; a, ev untouched) or GSL_ENOMEM. tick(tick_data)
 * as whirl_worker_run_ticked's (may be NULL). */
int whirl_worker_dsyev(size_t n, double *a, size_t lda, double *ev, int *info,
                       void (*tick)(void *tick_data), void *tick_data);

#endif
