/* The linear stability map: the growth rate max Re(lambda) of the linearisation
 * M q'' + (G + C) q' + K q = 0 about each of many free steady shapes (src/stability/stability.c
 * for the equations), the shapes shared over OpenMP threads with a workspace each. A failure on
 * a thread is carried to the caller's by its point's error record (whirl_error_keep); the
 * earliest point's is reported, so the message does not depend on the sharing. */
#include <math.h>
#include <stdlib.h>

#include "whirl/stability.h"
#include "core/error.h"

/* The growth rate and the index of one point (whirl_stability_shape's model: 3D, co-rotating
 * frame). */
static int point_growth(whirl_stability *w, const whirl_chain *c, double damping,
                        whirl_stability_point *p)
{
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = p->omega;
    m.internal_damping = damping;
    int status = whirl_stability_linearise(w, &m, p->r, p->z);
    if (!status) status = whirl_stability_growth(w, &p->growth);
    if (!status) status = whirl_stability_index(w, &p->index);
    return status;
}

int whirl_stability_map(const whirl_chain *c, double damping, size_t n,
                        whirl_stability_point *pts, whirl_stability_map_progress progress,
                        void *ctx)
{
    if (c == NULL || (n > 0 && pts == NULL))
        return whirl_fail(GSL_EINVAL, "whirl_stability_map needs a chain and its points");
    if (!(isfinite(damping) && damping >= 0))
        return whirl_fail(GSL_EINVAL, "damping must be >= 0 and finite, got %g", damping);
    whirl_error_record *err = calloc(n > 0 ? n : 1, sizeof *err);
    if (err == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu points", n);
    for (size_t i = 0; i < n; i++) pts[i].status = -1;
    whirl_error_record no_workspace = {GSL_SUCCESS, ""};
    int failed = 0;
    size_t done = 0;
#pragma omp parallel num_threads(whirl_max_threads())
    {
        whirl_stability *w = whirl_stability_alloc(c->n);
        if (w == NULL) {
            whirl_error_keep(&no_workspace, whirl_last_status());
#pragma omp atomic write
            failed = 1;
        }
#pragma omp for schedule(dynamic, 1)
        for (size_t i = 0; i < n; i++) {
            int stop;
#pragma omp atomic read
            stop = failed;
            if (stop || w == NULL || whirl_stop_requested() || pts[i].skip) continue;
            const int status = point_growth(w, c, damping, &pts[i]);
            if (status != GSL_SUCCESS && whirl_stop_requested()) continue; /* stopped inside */
            pts[i].status = status;
            if (status != GSL_SUCCESS) {
                whirl_error_keep(&err[i], status);
#pragma omp atomic write
                failed = 1;
                continue;
            }
            if (progress) {
#pragma omp critical /* unnamed: a named one would be an exported symbol */
                progress(ctx, ++done);
            }
        }
        whirl_stability_free(w);
    }
    int status = whirl_error_restore_first(err, n);
    free(err);
    if (status == GSL_SUCCESS && no_workspace.status != GSL_SUCCESS)
        status = whirl_error_restore(&no_workspace);
    if (status == GSL_SUCCESS && whirl_stop_requested()) {
        size_t analysed = 0;
        for (size_t i = 0; i < n; i++) analysed += pts[i].status == GSL_SUCCESS;
        status = whirl_fail(WHIRL_EINTERRUPTED, "stability map stopped by request after %zu of "
                            "%zu points", analysed, n);
    }
    return status;
}
