/* The N-link continuation's state (src/steady/nlink_path*.c): what include/whirl/steady.h shows
 * of a path (whirl_nlink_path, read by callers) is the first member of the path the library
 * allocates; the rest is here. Every array lives in one block after the struct, addressed by
 * offsets, so that a copy of a path (the probe, path_copy) is two assignments and one memcpy and
 * no pointer needs re-basing. */
#ifndef WHIRL_NLINK_PATH_INTERNAL_H
#define WHIRL_NLINK_PATH_INTERNAL_H

#include <stddef.h>

#include "steady/steady_internal.h"
#include "whirl/steady.h"

/* The last accepted step: its start, kept for the events and crossings. */
typedef struct path_last {
    double m0[3], w0, a0, t_w, t_a, ds; /* its start: metric (shot), point, tangent; its length */
    int raw_sign;
    int angles; /* the step was made in the link angles */
    int det_sign, index;
    double mu, mu_rate;
} path_last;

/* Everything of a path's point that is not public and not an array. No pointer into the block:
 * the arrays that a step exchanges with their trial are offsets. */
typedef struct path_state {
    double metric[3]; /* at the current point (shot): g_ww, g_wa, g_aa */
    int raw_sign;     /* orientation of the tangent against (G_a, -G_w) */
    double noise;     /* the round-off of the tip shot at the current point, as a distance from
                       * the curve in the metric */
    int stay, backoff; /* steps the path stays in the link angles before it tries the shot
                        * again, and the next such wait */
    int det_sign;     /* in the link angles: sign of det [J; tangent] (branch points) */
    int index;        /* in the link angles: the number of negative eigenvalues of the force
                       * balance's Jacobian in theta; -1 on the tip shot */
    double mu, mu_rate; /* in the link angles: the eigenvalue of that Jacobian nearest zero and
                         * its rate along the tangent (d mu / ds); NAN where not known */
    const char *why;  /* what rejected the last trial step (a string literal) */
    int floor_exit;   /* the last Newton's method on the shot stopped at its round-off floor */
    int have_last;    /* last is set (cleared by a start or a reversal) */
    path_last last;
    double fine_end;  /* the arclength up to which a reversal of the orientation test is taken
                       * for a branch point only at the smallest step (look_ahead; 0: none) */
    double probe_end; /* the arclength up to which a reversal is taken for a branch point without
                       * looking ahead again: the probe found one there at the finer scale */
    int rate_sign;    /* the sign of t_omega at the last point where it is resolved; a fold is
                       * where it changes. 0 until known (at a birth) */
    int last_rate_sign; /* that sign at the last step's start */
    /* offsets into the block of the arrays exchanged with their trial by a step (c->n each;
     * embed, embed_trial c->n + 1, then c->n of scratch) */
    size_t theta, theta_trial, t_theta, t_theta_trial, embed, embed_trial, eig, eig_trial;
} path_state;

typedef struct nlink_path {
    whirl_nlink_path pub; /* what a caller reads */
    path_state s;
    nlink_balance *balance;   /* the force balance in the link angles (own, not copied) */
    struct nlink_path *probe; /* the path that looks ahead (allocated when first needed) */
    double block[];           /* every array (path_block_size) */
} nlink_path;

static inline nlink_path *path_of(whirl_nlink_path *p)
{
    return (nlink_path *)p;
}

/* The arrays. Their offsets: the exchanged ones as path_state holds them, the rest fixed. */
static inline double *arr_theta(const nlink_path *p) { return (double *)p->block + p->s.theta; }
static inline double *arr_theta_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.theta_trial;
}
static inline double *arr_t_theta(const nlink_path *p)
{
    return (double *)p->block + p->s.t_theta;
}
static inline double *arr_t_theta_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.t_theta_trial;
}
static inline double *arr_embed(const nlink_path *p) { return (double *)p->block + p->s.embed; }
static inline double *arr_embed_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.embed_trial;
}
static inline double *arr_eig(const nlink_path *p) { return (double *)p->block + p->s.eig; }
static inline double *arr_eig_trial(const nlink_path *p)
{
    return (double *)p->block + p->s.eig_trial;
}
/* the fixed ones, after the 6 N + 2 (2 N + 1) of the exchanged: the last step's start's link
 * angles and tangent, the crossings' and the events' link angles, 7 N + 3 of scratch */
static inline size_t path_fixed(size_t n) { return 6 * n + 2 * (2 * n + 1); }
static inline double *arr_theta0(const nlink_path *p)
{
    return (double *)p->block + path_fixed(p->pub.chain->n);
}
static inline double *arr_t_theta0(const nlink_path *p)
{
    return arr_theta0(p) + p->pub.chain->n;
}
static inline double *arr_cross_theta(const nlink_path *p)
{
    return arr_t_theta0(p) + p->pub.chain->n;
}
static inline double *arr_event_theta(const nlink_path *p)
{
    return arr_cross_theta(p) + (WHIRL_PATH_EVENTS_MAX + 1) * p->pub.chain->n;
}
static inline double *arr_scratch(const nlink_path *p)
{
    return arr_event_theta(p) + WHIRL_PATH_EVENTS_MAX * p->pub.chain->n;
}
/* the doubles of the block */
static inline size_t path_block_size(size_t n)
{
    return path_fixed(n) + 2 * n + (2 * WHIRL_PATH_EVENTS_MAX + 1) * n + 7 * n + 3;
}

#endif
