/* Internal: the workspace of the dynamics module, shared by its formulations (dynamics.c,
 * dyn_cartesian.c, dyn_seed.c) and read by the integrators.
 *
 * Every formulation's state is y = (q, qdot), two halves of equal length, with dq/dt = qdot
 * exactly: the integrators rely on it (second-order form of the stage equations). */
#ifndef WHIRL_DYN_INTERNAL_H
#define WHIRL_DYN_INTERNAL_H

#include <stddef.h>

#include "whirl/dynamics.h"

/* The operations one formulation provides. */
typedef struct dyn_ops {
    /* Link vector d_i = x_i - x_{i-1} and its time derivative in the model's frame (3 components
     * each, y component 0 in 2D), i = 0..N-1. */
    void (*link)(const whirl_dyn *d, const double *y, size_t i, double *dv, double *ddot);
    /* y from link vectors and their derivatives (3 per link, model frame), then projected. */
    int (*from_links)(whirl_dyn *d, const double *dv, const double *ddot, double *y);
    /* dydt at (t, y); GSL_EBADFUNC with a message if it is not finite */
    int (*rhs)(whirl_dyn *d, double t, const double *y, double *dydt);
    int (*project)(whirl_dyn *d, double *y);
    int (*tensions)(whirl_dyn *d, double t, const double *y, double *tension);
    int (*alloc)(whirl_dyn *d); /* the formulation's own scratch (fields below) */
} dyn_ops;

enum { WHIRL_DYN_COEFS = 6 };

struct whirl_dyn {
    whirl_model model;
    int ramped; /* 1 if a ramp of the model is active (else the constant drive, exactly) */
    double phase_offset; /* added to the phase: keeps it continuous across whirl_dyn_set_ramps */
    whirl_pivot_fn pivot_fn;   /* the pivot's path (whirl_dyn_set_pivot), NULL: the drive */
    void *pivot_params;
    whirl_formulation formulation;
    const dyn_ops *ops;
    size_t n;    /* links */
    int dim;     /* 2 or 3 */
    size_t size; /* length of y */
    int threads; /* threads of the per-link passes (whirl_dyn_set_threads), >= 1 */
    double *mass_below; /* M_i = sum_{k >= i} m_k (seed formulation) */
    double *inv_mass;   /* 1 / m_i */
    /* shared scratch, 3 per mass: positions and velocities in the model's frame, applied forces
     * (drag, internal damping, seed forcing; not gravity nor the frame's fictitious forces) */
    double *x, *v, *force;
    double *links, *link_rates; /* 3 per link */
    /* Cartesian: the multipliers and the per-link coefficients of their elimination
     * (dyn_cartesian.c), WHIRL_DYN_COEFS arrays of n in one block `coef` */
    double *multiplier, *coef;
    double *co_k, *co_e, *co_b, *co_g, *co_q, *co_z;
    size_t *rescaled; /* links where the elimination was rescaled (n / 512 + 1) */
    /* seed: dense mass matrix (k x k, k = N in 2D, 2N in 3D), right-hand side, quadratic
     * accelerations (3 per mass) */
    double *matrix, *gen_force, *quad_acc;
};

extern const dyn_ops whirl_dyn_cartesian_ops;
extern const dyn_ops whirl_dyn_seed_ops;

/* Pivot position, velocity and acceleration in the model's frame at time t (3 components). */
void whirl_dyn_pivot(const whirl_dyn *d, double t, double *p, double *pv, double *pa);

/* The drive at time t: radius eps and its first two derivatives, rate omega and its derivative,
 * phase (the angle of the pivot about z in the inertial frame, the integral of omega from 0). */
typedef struct dyn_drive {
    double eps, deps, ddeps;
    double omega, domega;
    double phase;
} dyn_drive;

void whirl_dyn_drive(const whirl_dyn *d, double t, dyn_drive *out);

/* Fills d->x, d->v (positions and velocities of the masses), d->links, d->link_rates from y and
 * d->force with the applied forces: linear and quadratic air drag, internal damping and, if
 * with_seed_forcing, the seed's forcing f_d = sigma_d - lambda_d thetadot_d as a force pair on
 * link d (2D). Gravity and the fictitious forces of the frame are not included. */
void whirl_dyn_prepare_forces(whirl_dyn *d, double t, const double *y, int with_seed_forcing);

/* 1 if every component of v[0..n-1] is finite. */
int whirl_dyn_all_finite(const double *v, size_t n);

#endif
