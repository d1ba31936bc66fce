/* Work the caller can walk away from (src/core/worker.h).
 *
 * The control block is shared by the caller and a detached worker thread and reference-counted
 * under its mutex: the worker marks it done and signals; the caller waits on the condition with
 * a timeout of WORKER_POLL_SECONDS and checks the stop request at each wake-up. On a stop it marks
 * the block abandoned and leaves; the worker, once fn returns, finds the mark and releases arg.
 * Whoever drops the last reference frees the block, so nothing leaks and nothing is freed under
 * the other side. A process that exits meanwhile (the command line's exit 130) ends the worker
 * with it; the worker writes only its own memory, so that is safe. */
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/linalg.h"
#include <time.h>

#include "whirl/common.h"
#include "core/error.h"
#include "core/worker.h"

#define WORKER_POLL_SECONDS 0.02

struct whirl_worker {
    pthread_mutex_t lock;
    pthread_cond_t done_cond;
    whirl_work_fn fn;
    void *arg;
    void (*release)(void *arg);
    int done;      /* fn returned */
    int abandoned; /* the caller left without waiting */
    int refs;      /* 2 while both sides hold it */
};

static void worker_unref(whirl_worker *w)
{
    pthread_mutex_lock(&w->lock);
    const int last = --w->refs == 0;
    pthread_mutex_unlock(&w->lock);
    if (!last) return;
    pthread_cond_destroy(&w->done_cond);
    pthread_mutex_destroy(&w->lock);
    free(w);
}

int whirl_worker_abandoned(const whirl_worker *self)
{
    if (self == NULL) return 0;
    whirl_worker *w = (whirl_worker *)self; /* the lock is not part of the observable state */
    pthread_mutex_lock(&w->lock);
    const int abandoned = w->abandoned;
    pthread_mutex_unlock(&w->lock);
    return abandoned;
}

static void *worker_main(void *data)
{
    whirl_worker *w = data;
    w->fn(w->arg, w);
    pthread_mutex_lock(&w->lock);
    w->done = 1;
    const int abandoned = w->abandoned;
    pthread_cond_signal(&w->done_cond);
    pthread_mutex_unlock(&w->lock);
    if (abandoned && w->release) w->release(w->arg);
    worker_unref(w);
    return NULL;
}

int whirl_worker_run(whirl_work_fn fn, void *arg, void (*release)(void *arg))
{
    return whirl_worker_run_ticked(fn, arg, release, NULL, NULL);
}

int whirl_worker_run_ticked(whirl_work_fn fn, void *arg, void (*release)(void *arg),
                            void (*tick)(void *tick_data), void *tick_data)
{
    whirl_worker *w = calloc(1, sizeof *w);
    pthread_condattr_t attr;
    int ready = w != NULL && pthread_condattr_init(&attr) == 0;
    if (ready) {
        ready = pthread_condattr_setclock(&attr, CLOCK_MONOTONIC) == 0 &&
                pthread_cond_init(&w->done_cond, &attr) == 0;
        pthread_condattr_destroy(&attr);
        if (ready && pthread_mutex_init(&w->lock, NULL) != 0) {
            pthread_cond_destroy(&w->done_cond);
            ready = 0;
        }
    }
    if (!ready) { /* no control block: the work runs here */
        free(w);
        fn(arg, NULL);
        return GSL_SUCCESS;
    }
    w->fn = fn;
    w->arg = arg;
    w->release = release;
    w->refs = 2;
    pthread_t thread;
    pthread_attr_t tattr;
    int started = pthread_attr_init(&tattr) == 0;
    if (started) {
        started = pthread_attr_setdetachstate(&tattr, PTHREAD_CREATE_DETACHED) == 0 &&
                  pthread_create(&thread, &tattr, worker_main, w) == 0;
        pthread_attr_destroy(&tattr);
    }
    if (!started) {
        w->refs = 1;
        worker_unref(w);
        fn(arg, NULL);
        return GSL_SUCCESS;
    }
    int status = GSL_SUCCESS;
    pthread_mutex_lock(&w->lock);
    while (!w->done) {
        if (whirl_stop_requested()) {
            w->abandoned = 1;
            status = whirl_fail(WHIRL_EINTERRUPTED, "stopped by request");
            break;
        }
        struct timespec until;
        clock_gettime(CLOCK_MONOTONIC, &until);
        until.tv_nsec += (long)(WORKER_POLL_SECONDS * 1e9);
        if (until.tv_nsec >= 1000000000L) until.tv_sec++, until.tv_nsec -= 1000000000L;
        const int rc = pthread_cond_timedwait(&w->done_cond, &w->lock, &until);
        (void)rc; /* ETIMEDOUT or a wake-up: the loop checks again */
        if (tick && !w->done) { /* outside the lock: tick may take its time */
            pthread_mutex_unlock(&w->lock);
            tick(tick_data);
            pthread_mutex_lock(&w->lock);
        }
    }
    pthread_mutex_unlock(&w->lock);
    worker_unref(w);
    return status;
}

/* The rows x cols column-major block src (leading dimension lds) into dst (leading dimension
 * ldd): the copies a worker reads instead of the caller's memory, and its results back. */
static void copy_columns(double *dst, size_t ldd, const double *src, size_t lds, size_t rows,
                         size_t cols)
{
    for (size_t c = 0; c < cols; c++) memcpy(dst + c * ldd, src + c * lds, rows * sizeof(double));
}

/* ---- dgeev on a worker ---- */

typedef struct dgeev_job {
    char jobvl, jobvr;
    size_t m;
    double *a, *re, *im, *v, *work; /* one block: a (m x m), v (m x m), re, im (m), work */
    lapack_int lwork, info;
} dgeev_job;

static void dgeev_release(void *data)
{
    dgeev_job *j = data;
    free(j->a);
    free(j);
}

static lapack_int dgeev(char jobvl, char jobvr, size_t m, double *a, size_t lda, double *re,
                        double *im, double *v, size_t ldv, double *work, lapack_int lwork)
{
    return whirl_la_dgeev_work(LAPACK_COL_MAJOR, jobvl, jobvr, (lapack_int)m, a, (lapack_int)lda,
                              re, im, jobvl == 'V' ? v : NULL, jobvl == 'V' ? (lapack_int)ldv : 1,
                              jobvr == 'V' ? v : NULL, jobvr == 'V' ? (lapack_int)ldv : 1, work,
                              lwork);
}

static void dgeev_run(void *data, const whirl_worker *self)
{
    (void)self; /* one LAPACK call: nothing to poll */
    dgeev_job *j = data;
    j->info = dgeev(j->jobvl, j->jobvr, j->m, j->a, j->m, j->re, j->im, j->v, j->m, j->work,
                    j->lwork);
}

int whirl_worker_dgeev(char jobvl, char jobvr, size_t m, double *a, size_t lda, double *re,
                       double *im, double *v, size_t ldv, double *work, int lwork, int *info)
{
    if (m <= WORKER_DGEEV_INLINE_MAX) {
        *info = (int)dgeev(jobvl, jobvr, m, a, lda, re, im, v, ldv, work, (lapack_int)lwork);
        return GSL_SUCCESS;
    }
    /* 2 m^2 + 2 m + lwork doubles, without wrapping round */
    if (m > SIZE_MAX / (8 * sizeof(double)) / m || (size_t)lwork > SIZE_MAX / (4 * sizeof(double)))
        return whirl_fail(GSL_ENOMEM, "an eigen-solve of %zu rows needs more memory than can be "
                                      "addressed", m);
    dgeev_job *j = calloc(1, sizeof *j);
    const size_t size = 2 * m * m + 2 * m + (size_t)lwork;
    if (j == NULL || (j->a = malloc(size * sizeof(double))) == NULL) {
        free(j);
        return whirl_fail(GSL_ENOMEM, "out of memory for an eigen-solve of %zu rows", m);
    }
    j->jobvl = jobvl;
    j->jobvr = jobvr;
    j->m = m;
    j->v = j->a + m * m;
    j->re = j->v + m * m;
    j->im = j->re + m;
    j->work = j->im + m;
    j->lwork = (lapack_int)lwork;
    copy_columns(j->a, m, a, lda, m, m);
    if (whirl_worker_run(dgeev_run, j, dgeev_release) != GSL_SUCCESS)
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during the eigen-solve");
    *info = (int)j->info;
    memcpy(re, j->re, m * sizeof(double));
    memcpy(im, j->im, m * sizeof(double));
    if (jobvl == 'V' || jobvr == 'V')
        copy_columns(v, ldv, j->v, m, m, m);
    copy_columns(a, lda, j->a, m, m, m);
    dgeev_release(j);
    return GSL_SUCCESS;
}

/* ---- LU (dgetrf, dgetrs, dgesv) and Cholesky (dposv) on a worker ---- */

/* dgesv: LU_FACTOR | LU_SOLVE; dposv: LU_CHOLESKY alone (factor and solve, no pivots) */
typedef enum { LU_FACTOR = 1, LU_SOLVE = 2, LU_CHOLESKY = 4 } lu_part;

typedef struct lu_job {
    int parts;
    size_t n, nrhs;
    double *a, *b; /* one block: a (n x n), then b (n x nrhs) */
    lapack_int *ipiv;
    lapack_int info;
} lu_job;

static void lu_release(void *data)
{
    lu_job *j = data;
    free(j->a);
    free(j->ipiv);
    free(j);
}

static lapack_int lu_call(int parts, size_t n, size_t nrhs, double *a, size_t lda,
                          lapack_int *ipiv, double *b, size_t ldb)
{
    lapack_int info = 0;
    if (parts & LU_CHOLESKY)
        return whirl_la_dposv_work(LAPACK_COL_MAJOR, 'L', (lapack_int)n, (lapack_int)nrhs, a,
                                  (lapack_int)lda, b, (lapack_int)ldb);
    if (parts & LU_FACTOR)
        info = whirl_la_dgetrf_work(LAPACK_COL_MAJOR, (lapack_int)n, (lapack_int)n, a,
                                   (lapack_int)lda, ipiv);
    if (info == 0 && (parts & LU_SOLVE))
        info = whirl_la_dgetrs_work(LAPACK_COL_MAJOR, 'N', (lapack_int)n, (lapack_int)nrhs, a,
                                   (lapack_int)lda, ipiv, b, (lapack_int)ldb);
    return info;
}

static void lu_run(void *data, const whirl_worker *self)
{
    (void)self; /* one LAPACK call: nothing to poll */
    lu_job *j = data;
    j->info = lu_call(j->parts, j->n, j->nrhs, j->a, j->n, j->ipiv, j->b, j->n);
}

/* The LU work of parts on a (n x n) and b (n x nrhs): here if small, else on copies in a
 * worker, whose results are copied back. */
static int lu_work(int parts, size_t n, size_t nrhs, double *a, size_t lda, lapack_int *ipiv,
                   double *b, size_t ldb, int *info)
{
    const double dn = (double)n;
    const int factor = parts & (LU_FACTOR | LU_CHOLESKY), solve = parts & (LU_SOLVE | LU_CHOLESKY);
    const double flops = (factor ? 2.0 / 3.0 * dn * dn * dn : 0) +
                         (solve ? 2.0 * dn * dn * (double)nrhs : 0);
    if (flops <= WORKER_INLINE_FLOPS) {
        *info = (int)lu_call(parts, n, nrhs, a, lda, ipiv, b, ldb);
        return GSL_SUCCESS;
    }
    /* n^2 + n nrhs doubles, without wrapping round */
    if ((n > 0 && n > SIZE_MAX / (4 * sizeof(double)) / n) ||
        (nrhs > 0 && n > SIZE_MAX / (4 * sizeof(double)) / nrhs))
        return whirl_fail(GSL_ENOMEM, "a linear solve of %zu rows needs more memory than can be "
                                      "addressed", n);
    lu_job *j = calloc(1, sizeof *j);
    const size_t nb = solve ? n * nrhs : 0;
    if (j == NULL || (j->a = malloc((n * n + nb) * sizeof(double))) == NULL ||
        (j->ipiv = malloc((n ? n : 1) * sizeof(lapack_int))) == NULL) {
        if (j) free(j->a);
        free(j);
        return whirl_fail(GSL_ENOMEM, "out of memory for a linear solve of %zu rows", n);
    }
    j->parts = parts;
    j->n = n;
    j->nrhs = nrhs;
    j->b = j->a + n * n;
    copy_columns(j->a, n, a, lda, n, n);
    if (parts == LU_SOLVE) memcpy(j->ipiv, ipiv, n * sizeof(lapack_int));
    if (nb) copy_columns(j->b, n, b, ldb, n, nrhs);
    if (whirl_worker_run(lu_run, j, lu_release) != GSL_SUCCESS)
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during a linear solve");
    *info = (int)j->info;
    if (factor) copy_columns(a, lda, j->a, n, n, n);
    if (parts & LU_FACTOR) memcpy(ipiv, j->ipiv, n * sizeof(lapack_int));
    if (nb) copy_columns(b, ldb, j->b, n, n, nrhs);
    lu_release(j);
    return GSL_SUCCESS;
}

int whirl_worker_dgetrf(size_t n, double *a, size_t lda, lapack_int *ipiv, int *info)
{
    return lu_work(LU_FACTOR, n, 0, a, lda, ipiv, NULL, 1, info);
}

int whirl_worker_dgetrs(size_t n, size_t nrhs, const double *a, size_t lda,
                        const lapack_int *ipiv, double *b, size_t ldb, int *info)
{
    /* the solve reads a and ipiv only (on a worker it reads copies) */
    return lu_work(LU_SOLVE, n, nrhs, (double *)a, lda, (lapack_int *)ipiv, b, ldb, info);
}

int whirl_worker_dgesv(size_t n, size_t nrhs, double *a, size_t lda, lapack_int *ipiv, double *b,
                       size_t ldb, int *info)
{
    return lu_work(LU_FACTOR | LU_SOLVE, n, nrhs, a, lda, ipiv, b, ldb, info);
}

int whirl_worker_dposv(size_t n, size_t nrhs, double *a, size_t lda, double *b, size_t ldb,
                       int *info)
{
    return lu_work(LU_CHOLESKY, n, nrhs, a, lda, NULL, b, ldb, info);
}

/* ---- dsyev (eigenvalues only) on a worker ---- */

typedef struct dsyev_job {
    size_t n;
    double *a, *ev; /* one block: a (n x n), then ev (n) */
    lapack_int info;
} dsyev_job;

static void dsyev_release(void *data)
{
    dsyev_job *j = data;
    free(j->a);
    free(j);
}

static void dsyev_run(void *data, const whirl_worker *self)
{
    (void)self; /* one LAPACK call: nothing to poll */
    dsyev_job *j = data;
    j->info = whirl_la_dsyev(LAPACK_COL_MAJOR, 'N', 'U', (lapack_int)j->n, j->a, (lapack_int)j->n,
                            j->ev);
}

int whirl_worker_dsyev(size_t n, double *a, size_t lda, double *ev, int *info,
                       void (*tick)(void *tick_data), void *tick_data)
{
    const double dn = (double)n;
    if (4.0 / 3.0 * dn * dn * dn <= WORKER_INLINE_FLOPS) { /* the tridiagonal reduction */
        *info = (int)whirl_la_dsyev(LAPACK_COL_MAJOR, 'N', 'U', (lapack_int)n, a, (lapack_int)lda,
                                   ev);
        return GSL_SUCCESS;
    }
    if (n > SIZE_MAX / (4 * sizeof(double)) / n)
        return whirl_fail(GSL_ENOMEM, "an eigen-solve of %zu rows needs more memory than can be "
                                      "addressed", n);
    dsyev_job *j = calloc(1, sizeof *j);
    if (j == NULL || (j->a = malloc((n * n + n) * sizeof(double))) == NULL) {
        free(j);
        return whirl_fail(GSL_ENOMEM, "out of memory for an eigen-solve of %zu rows", n);
    }
    j->n = n;
    j->ev = j->a + n * n;
    copy_columns(j->a, n, a, lda, n, n);
    if (whirl_worker_run_ticked(dsyev_run, j, dsyev_release, tick, tick_data) != GSL_SUCCESS)
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during an eigen-solve");
    *info = (int)j->info;
    memcpy(ev, j->ev, n * sizeof(double));
    copy_columns(a, lda, j->a, n, n, n);
    dsyev_release(j);
    return GSL_SUCCESS;
}
