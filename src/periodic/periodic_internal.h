/* Internal: the workspace of the periodic motions (periodic.c: the period map, its derivative,
 * Newton's method; floquet.c: the multipliers, their errors and the verdict). */
#ifndef WHIRL_PERIODIC_INTERNAL_H
#define WHIRL_PERIODIC_INTERNAL_H

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

#include "whirl/integrator.h"
#include "whirl/periodic.h"

/* The variational equations' workspace (variational.c), made at the first monodromy. */
typedef struct periodic_var periodic_var;
void periodic_var_free(periodic_var *v);

struct whirl_periodic {
    whirl_pivot_path path; /* the pivot's path (the dynamics' pivot callback reads it) */
    const whirl_chain *chain;
    int dim;
    size_t n;           /* links */
    size_t size;        /* state length, 2 dim N */
    size_t m;           /* tangent coordinates, 2 (dim - 1) N */
    double length;      /* the chain's length: the scale of positions in the residual */
    double omega_ref;   /* max(omega, sqrt(g / L)): the scale of rates over lengths */
    whirl_dyn *dyn;     /* inertial frame, Cartesian formulation, the pivot on path */
    whirl_integrator *it; /* gauss2 on dyn */
    double *basis;      /* 3 (dim - 1) N: the unit vectors across the links */
    double *scratch;    /* 5 size */
    double *vec;        /* 5 m */
    double *mono;       /* m x m, row major: the monodromy */
    int have_mono;
    whirl_monodromy_method method; /* of the solve under way */
    void (*tick)(void *data, const whirl_periodic_progress *progress); /* NULL: none */
    void *tick_data;
    whirl_periodic_progress progress; /* where the solve under way stands */
    gsl_matrix *work, *v; /* m x m */
    double *out;        /* 8 m: re, im, err of the result; re, im of the coarse solve; scratch */
    gsl_eigen_nonsymm_workspace *eig;
    gsl_vector_complex *eval;
    periodic_var *var; /* NULL until the first monodromy by the variational equations */
    /* the dissipation of the model (whirl_periodic_alloc_model; all 0 by whirl_periodic_alloc) */
    double drag, drag2, damping; /* c, c2, D of whirl_model */
    int dissipative;             /* any of them > 0 */
};

/* Newton's method on P(y) - y from y (overwritten) with steps per period, to the scaled
 * residual tol in at most max_iter iterations; then the monodromy at the motion in w->mono. */
int periodic_solve(whirl_periodic *w, double *y, int steps, double tol, int max_iter,
                   double *residual, int *iterations);

/* w->basis <- the unit vectors across the links of y. */
void periodic_basis(whirl_periodic *w, const double *y);
/* out <- y + the tangent vector of coordinates x (w->basis), not projected. */
void periodic_tangent_add(const whirl_periodic *w, const double *y, const double *x,
                          double *out);
/* x <- the coordinates of y1 - y0 (w->basis). */
void periodic_tangent_read(const whirl_periodic *w, const double *y0, const double *y1,
                           double *x);
/* w->mono <- the monodromy at y from the variational equations (variational.c). */
int periodic_monodromy_variational(whirl_periodic *w, const double *y, int steps);

/* w's path <- path (a valid one for w's dimension): a chart's rates and amplitudes on one
 * workspace. */
void periodic_set_path(whirl_periodic *w, const whirl_pivot_path *path);
/* *steps <- requested (0: the default) raised to whirl_default_step's bound at y on w's path,
 * with the tensions raised by the pivot's largest acceleration (floquet.c). */
int periodic_steps_for(whirl_periodic *w, const double *y, int requested, int *steps);

/* Calls the tick (if any) with w->progress, its monodromy part set to done. */
void periodic_tick(whirl_periodic *w, double done);

/* The eigenvalues of w->mono into re, im, by decreasing modulus. */
int periodic_multipliers(whirl_periodic *w, double *re, double *im);

/* r's max_modulus (and its error err[0]), reciprocal-pair error, verdict, growth and edge from
 * its count multipliers re, im, err (sorted by decreasing modulus; floquet.c); dissipative: the
 * verdict's margin without the reciprocal-pair error (no pairs to expect). */
void periodic_judge(whirl_periodic_result *r, int dissipative);

/* The dissipative forces at (t, y) as the Cartesian formulation takes them, fdiff_i = f_i / m_i
 * - f_{i-1} / m_{i-1} (3 per link; 2D: y 0), and the drag's Jacobian factors a (N) and u (3 N)
 * (dissipation.c). */
void periodic_diss_forces(const whirl_periodic *w, double t, const double *y, double *fdiff,
                          double *a, double *u);
/* out (3 N x cols, [(3 i + k) cols + col]) <- the derivative of fdiff along cols tangent vectors
 * (dq, dv: the state's halves, dim per link, [(dim i + k) cols + col]), with a, u of
 * periodic_diss_forces at the state. */
void periodic_diss_apply(const whirl_periodic *w, const double *a, const double *u,
                         const double *dq, const double *dv, size_t cols, double *out);

/* The largest scaled component of py - y: positions over L, rates over omega_ref L (Newton's
 * test; periodic.c). */
double periodic_residual(const whirl_periodic *w, const double *y, const double *py);

#endif
