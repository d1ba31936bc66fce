/* Branch following for the steady shapes: natural-parameter continuation in omega.
 *
 * At each rate the tip radius is seeded by the quadratic extrapolation a(omega) through the
 * three previous solutions of the same block (fewer after its start or a gap where the mode did
 * not exist; nothing at all at first), and whirl_steady_shoot_root brackets around the seed. The
 * rates are cut into contiguous blocks of about BLOCK_LEN, each started afresh and handed to the
 * OpenMP threads as they come free. The cut depends on the number of rates only, never on the
 * number of threads: the seed of every rate, hence the root Brent's method converges to (to its
 * last bit), is the same on one thread or many. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "steady/steady_internal.h"

#define BLOCK_LEN 32 /* rates per block: n / BLOCK_LEN blocks (at least one) */

#define PREV_MAX 3 /* solutions the predictor extrapolates: quadratic */

/* The seed at omega: the polynomial through the n_prev (<= PREV_MAX) previous solutions
 * (omega_prev[i], a_prev[i]), most recent last, evaluated at omega (Lagrange's form). */
static double predict(int n_prev, const double *omega_prev, const double *a_prev, double omega)
{
    if (n_prev == 0) return 0;
    const double *w = omega_prev + PREV_MAX - n_prev, *a = a_prev + PREV_MAX - n_prev;
    double seed = 0;
    for (int i = 0; i < n_prev; i++) {
        double basis = 1;
        for (int j = 0; j < n_prev; j++)
            if (j != i) basis *= (omega - w[j]) / (w[i] - w[j]);
        seed += basis * a[i];
    }
    double last = a_prev[PREV_MAX - 1];
    /* a wild extrapolation (near omega_k, where a ~ sqrt(omega - omega_k)): the last value */
    if (!(isfinite(seed) && seed > 0.5 * last && seed < 2 * last)) seed = last;
    return seed;
}

static int follow_block(const steady_model *m, void *ws, int mode, size_t n,
                        const double *omega, whirl_shape_info *info, int *exists)
{
    double omega_prev[PREV_MAX] = {0}, a_prev[PREV_MAX] = {0};
    int n_prev = 0;
    for (size_t j = 0; j < n; j++) {
        /* a stop ends every block at its next rate: the solver itself polls only inside long
           integrations, and the blocks not yet begun (a grid of 30001 rates has 937) would
           otherwise each run until theirs did (0.8 s of processor time after a Ctrl-C) */
        if (whirl_stop_requested()) return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request");
        double guess = predict(n_prev, omega_prev, a_prev, omega[j]);
        int status = m->solve(ws, omega[j], mode, guess, &info[j]);
        if (status == GSL_EDOM) {
            exists[j] = 0;
            n_prev = 0;
            continue;
        }
        if (status != GSL_SUCCESS) return status;
        exists[j] = 1;
        for (int i = 0; i + 1 < PREV_MAX; i++)
            omega_prev[i] = omega_prev[i + 1], a_prev[i] = a_prev[i + 1];
        omega_prev[PREV_MAX - 1] = omega[j], a_prev[PREV_MAX - 1] = info[j].tip_r;
        if (n_prev < PREV_MAX) n_prev++;
    }
    return GSL_SUCCESS;
}

int whirl_steady_branch(const steady_model *m, int mode, size_t n, const double *omega,
                        whirl_shape_info *info, int *exists)
{
    for (size_t j = 0; j < n; j++) {
        int status = whirl_steady_check_args(omega[j], mode, WHIRL_CONTINUUM_MODE_MAX);
        if (status != GSL_SUCCESS) return status;
    }
    size_t nblocks = n / BLOCK_LEN, nthreads = 1;
    if (nblocks < 1) nblocks = 1;
#ifdef _OPENMP
    if (!omp_in_parallel()) nthreads = (size_t)whirl_max_threads();
#endif
    if (nthreads > nblocks) nthreads = nblocks;
    whirl_error_record *result = malloc(nblocks * sizeof *result);
    if (result == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu blocks", nblocks);

#pragma omp parallel for schedule(dynamic, 1) num_threads((int)nthreads) if (nthreads > 1)
    for (size_t b = 0; b < nblocks; b++) {
        size_t first = n * b / nblocks, last = n * (b + 1) / nblocks;
        void *ws = m->ws_alloc(m->params);
        result[b].status = GSL_SUCCESS;
        whirl_error_keep(&result[b], ws == NULL ? whirl_last_status()
                                                : follow_block(m, ws, mode, last - first,
                                                               omega + first, info + first,
                                                               exists + first));
        m->ws_free(ws);
    }
    const int status = whirl_error_restore_first(result, nblocks);
    free(result);
    return status;
}
