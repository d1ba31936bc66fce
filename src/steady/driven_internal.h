/* What the two files of the hand-swung chain share (src/steady/driven.c: the shapes, Newton's
 * method and the set-up; src/steady/driven_branch.c: the branches against the rate). The
 * method is described at the top of driven.c. */
#ifndef WHIRL_STEADY_DRIVEN_INTERNAL_H
#define WHIRL_STEADY_DRIVEN_INTERNAL_H

#include <stddef.h>

#include <gsl/gsl_odeiv2.h>

#include "whirl/driven.h"

#define STATE 6                        /* r, F */
#define NPAR 3                         /* X, Y, omega */
#define ODE_DIM (STATE * (1 + NPAR))   /* state and its three sensitivities */
#define SERIES_START 1e-6              /* sigma where the continuum's integration starts */
#define ODE_TOL 1e-13                  /* relative and absolute tolerance of the state */
#define ODE_SENS_SCALE 1e4             /* looser absolute tolerance of the sensitivities */
#define NEWTON_MAX 40
#define NEWTON_STEP_TOL 1e-11          /* converged: step below this (relative to 1 + |u|) */
#define NEWTON_RESIDUAL_OK 1e-9        /* ... and residual below this [L] */
#define NEWTON_BACKTRACK 8
#define HOMOTOPY_MIN_STEP 1e-5
#define HOMOTOPY_MAX_JUMP 0.05         /* largest corrector move of one step [L]: no branch jumps */
#define BRANCH_MAX_CORRECTOR 8         /* corrector iterations before a step is refused */
#define BRANCH_MIN_STEP_RATIO 1e-7     /* smallest step as a fraction of the largest */
#define FOLD_TOL 1e-12                 /* arclength tolerance of the fold location */
#define ODE_STEP_MAX 200000            /* ODE steps of one continuum shape (also polls the stop
                                          request every ODE_POLL steps) */
#define ODE_POLL 256
#define DRAG_MAX 1e6                   /* largest drag coefficient accepted (either kind) */

/* The problem being solved: the model, the parameters (omega comes from u[2]) and scratch. */
typedef struct problem {
    const whirl_chain *chain; /* NULL: the continuum */
    whirl_driven_params p;
    double gravity;
    double omega;             /* rate of the current integration */
    gsl_odeiv2_step *step;
    gsl_odeiv2_control *control;
    gsl_odeiv2_evolve *evolve;
    double scale_abs[ODE_DIM];
    double *pos;     /* 3 per sample: positions for the node count */
    double *tension; /* per sample */
    size_t npos;
} problem;

/* The pseudo-arclength condition tau.(u - u_pred) = 0, or none (omega fixed). */
typedef struct arclength {
    double tau[3];
    double u_pred[3];
} arclength;

int driven_pivot_miss(problem *pb, const double *u, double *R, double J[3][3]);
int driven_newton(problem *pb, double *u, const arclength *arc, int *iterations, double *rnorm);
void driven_problem_free(problem *pb);
int driven_problem_init(problem *pb, const whirl_chain *chain, const whirl_driven_params *p);
int driven_describe(problem *pb, const double *u, int iterations, whirl_driven_info *info);

#endif
