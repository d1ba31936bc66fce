/* The look ahead of the N-link continuation (src/steady/nlink_path.c): before a reversal of the
 * orientation test on a short step is taken for a branch point, a copy of the path (the probe)
 * goes on in the fine mode to see whether the curve only turns sharply there. */
#include <stddef.h>
#include <string.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"

/* A member of nlink_path beside pub, s, its own resources and the block would not be copied: */
_Static_assert(offsetof(nlink_path, s) == sizeof(whirl_nlink_path) &&
                   offsetof(nlink_path, balance) == offsetof(nlink_path, s) + sizeof(path_state) &&
                   offsetof(nlink_path, probe) == offsetof(nlink_path, balance) + sizeof(void *) &&
                   offsetof(nlink_path, block) == offsetof(nlink_path, probe) + sizeof(void *),
               "nlink_path is pub, s, balance, probe and the block: path_copy copies pub, s and "
               "the block");

/* dst becomes a copy of src at its current point: its public part, its state and its block (the
 * arrays, addressed by offsets); dst's force balance and probe are its own. */
static void path_copy(nlink_path *dst, const nlink_path *src)
{
    dst->pub = src->pub;
    dst->s = src->s;
    memcpy(dst->block, src->block, path_block_size(src->pub.chain->n) * sizeof(double));
}

/* Looks ahead from the current point before a reversal of the orientation test on a step no
 * longer than DS_BRANCH is taken for a branch point (src/steady/nlink_path.c): the probe, a copy
 * of the path, goes on from here with steps from ds, in the fine mode (a reversal taken only at
 * the smallest step) up to FINE_SPAN of arclength. Returns 1 where it gets there within
 * PROBE_STEPS steps with no branch point: the curve turns sharply here and the path should
 * follow it; 0 where it does not (a branch point at the finer scale too, or a failure: the
 * reversal is taken as before); WHIRL_EINTERRUPTED on a stop request, GSL_ENOMEM. The probe's
 * shots are counted in p->pub.shots. */
int path_look_ahead(nlink_path *p, double ds)
{
    if (p->probe == NULL && (p->probe = path_alloc(p->pub.chain)) == NULL)
        return whirl_last_status();
    nlink_path *q = p->probe;
    path_copy(q, p);
    q->pub.ds = ds;
    q->s.fine_end = p->pub.arclength + FINE_SPAN;
    int status = GSL_SUCCESS, resolved = 0;
    for (long k = 0; k < PROBE_STEPS && status == GSL_SUCCESS && !resolved; k++) {
        status = path_step(q);
        for (int e = 0; e < q->pub.n_events; e++)
            if (q->pub.event[e].kind == WHIRL_EVENT_BRANCH_POINT) status = GSL_EFAILED;
        resolved = status == GSL_SUCCESS && (q->pub.ended || !in_fine_mode(q));
    }
    p->pub.shots = q->pub.shots; /* the probe counted on from p->pub.shots */
    if (status == WHIRL_EINTERRUPTED) return status;
    return resolved;
}
