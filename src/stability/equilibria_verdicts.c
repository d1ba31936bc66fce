/* The equilibria's linear verdicts (whirl_equilibria_find, whirl/steady.h): the steady module
 * lists and polishes the equilibria (steady/equilibria.c), and this one linearises each of the
 * N-link chain's (whirl_stability_linearise in the co-rotating frame, then its growth and its
 * index), so that the dependency points from stability to steady and not back. */
#include <stdlib.h>

#include "whirl/stability.h"
#include "whirl/steady.h"
#include "steady/steady_internal.h"

typedef struct verdict_ws {
    whirl_stability *w; /* allocated at the first equilibrium */
    whirl_model model;
} verdict_ws;

static int judge(void *ctx, const double *r, const double *z, double *growth, int *index)
{
    verdict_ws *v = ctx;
    if (v->w == NULL && (v->w = whirl_stability_alloc(v->model.chain->n)) == NULL)
        return whirl_last_status();
    int status = whirl_stability_linearise(v->w, &v->model, r, z);
    if (!status) status = whirl_stability_growth(v->w, growth);
    if (!status) status = whirl_stability_index(v->w, index);
    return status;
}

int whirl_equilibria_find(const whirl_chain *c, double tip_mass, double omega,
                          const whirl_equilibria_params *params, whirl_equilibria **out)
{
    return whirl_equilibria_find_progress(c, tip_mass, omega, params, NULL, NULL, out);
}

int whirl_equilibria_find_progress(const whirl_chain *c, double tip_mass, double omega,
                                   const whirl_equilibria_params *params,
                                   whirl_equilibria_progress_fn progress, void *ctx,
                                   whirl_equilibria **out)
{
    verdict_ws v = {0};
    v.model.chain = c;
    v.model.dim = 3;
    v.model.frame = WHIRL_FRAME_ROTATING;
    v.model.omega = omega;
    const whirl_equilibria_verdict verdict = {judge, &v};
    const int status = whirl_equilibria_search(c, tip_mass, omega, params, &verdict, progress,
                                               ctx, out);
    whirl_stability_free(v.w);
    return status;
}
