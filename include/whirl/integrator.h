/* whirl: integrators of a general system of ordinary differential equations dy/dt = f(t, y),
 * optionally kept on a manifold by a projection after every step (GSL's ode-initval2 style:
 * method objects, a system struct, an integrator object that owns its workspace).
 *
 * Methods (whirl_integrator_type objects, also found by name):
 *  - "gauss2", "gauss3": Gauss-Legendre collocation, 2 stages (order 4) and 3 stages (order 6),
 *    implicit, symmetric, symplectic; fixed steps only. They need a second-order system
 *    (y = (q, v) with dq/dt = v exactly: second_order = 1) and solve the stage equations for the
 *    stage accelerations by fixed-point iteration, which converges for h omega_max rho(A) < 1
 *    (rho(A) = 0.289 gauss2, 0.215 gauss3; omega_max the fastest frequency of the system): a
 *    larger step fails with GSL_EMAXITER. The iteration stops at round-off, judged against
 *    max|dv/dt| + acceleration_scale.
 *  - "rk4": the classical explicit Runge-Kutta method; fixed steps only.
 *  - "rk8": Prince-Dormand RK8(7)13M, explicit, 13 evaluations per step, with GSL's standard
 *    step control; fixed or adaptive steps.
 *  - GSL's steppers on the same system: "gsl-rk8pd", "gsl-rk4imp", "gsl-rkf45", "gsl-rk4"
 *    (fixed or adaptive) and the multistep "gsl-msadams", "gsl-msbdf" (adaptive only).
 * Statuses: GSL's codes with a message (whirl_last_error); a right-hand side or projection that
 * returns a non-zero status stops the integration with that status, the state left at the last
 * good step. Every right-hand side polls whirl_stop_requested(): an integration then returns
 * WHIRL_EINTERRUPTED (the state at the last completed step). */
#ifndef WHIRL_INTEGRATOR_H
#define WHIRL_INTEGRATOR_H

#include <stddef.h>

#include "whirl/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A system dy/dt = f(t, y). The integrator keeps a copy of the struct, not of params. */
typedef struct whirl_system {
    /* dydt <- f(t, y); GSL's signature (a gsl_odeiv2_system function works); GSL_SUCCESS or a
       status that stops the integration (set a message with it) */
    int (*rhs)(double t, const double y[], double dydt[], void *params);
    /* optional (NULL: none): puts y back onto the system's manifold after every step, in place */
    int (*project)(double t, double y[], void *params);
    size_t size;               /* length of y, >= 1 (even if second_order) */
    void *params;              /* passed to rhs and project (not owned) */
    int second_order;          /* 1 if y = (q, v), two halves, and dq/dt = v exactly (the first
                                  half of f is the second half of y); needed by gauss2, gauss3 */
    double acceleration_scale; /* > 0 for gauss2, gauss3: the typical size of dv/dt (units of
                                  y / T^2), e.g. gravity; the stage iteration's increments below
                                  1e-8 (max|dv/dt| + scale) that stop decreasing count as
                                  converged. Unused by the other methods (default 0) */
} whirl_system;

typedef struct whirl_integrator_type whirl_integrator_type; /* a method (constant object) */
typedef struct whirl_integrator whirl_integrator;           /* an integrator of one system */

extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gauss2;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gauss3;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_rk4;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_rk8;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gsl_rk8pd;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gsl_rk4imp;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gsl_msadams;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gsl_msbdf;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gsl_rkf45;
extern WHIRL_API const whirl_integrator_type *const whirl_integrator_gsl_rk4;

typedef struct whirl_integrator_stats {
    unsigned long steps;      /* accepted steps */
    unsigned long rejected;   /* rejected steps (adaptive) */
    unsigned long rhs_evals;  /* right-hand side evaluations */
    unsigned long iterations; /* stage-equation iterations (implicit methods) */
} whirl_integrator_stats;

/* NULL-terminated list of the method names, in the registry's order (static storage).
 * @return the names, NULL-terminated (static storage)
 */
WHIRL_API const char *const *whirl_integrator_methods(void);

/* The method called name, or NULL with a message listing the known names.
 * @param name the method's name, e.g. "rk4" (NULL: not found)
 * @return the method (static storage), or NULL with a message
 */
WHIRL_API const whirl_integrator_type *whirl_integrator_type_find(const char *name);

/* The method's name (static storage); 1 if it takes adaptive steps (tol > 0), 1 if it takes
 * fixed steps (tol = 0).
 * @param type the method, or NULL
 * @return the name (static storage), or NULL for a NULL type
 */
WHIRL_API const char *whirl_integrator_type_name(const whirl_integrator_type *type);
/* 1 if the method takes adaptive steps (tol > 0), else 0.
 * @param type the method, or NULL
 * @return 1 or 0 (0 for a NULL type)
 */
WHIRL_API int whirl_integrator_type_adaptive(const whirl_integrator_type *type);
/* 1 if the method takes fixed steps (tol = 0), else 0.
 * @param type the method, or NULL
 * @return 1 or 0 (0 for a NULL type)
 */
WHIRL_API int whirl_integrator_type_fixed(const whirl_integrator_type *type);

/* An integrator of the method type for the system sys (copied; sys->params not owned). NULL
 * with a message on NULL arguments, a system without rhs or of size 0, a method that needs
 * what the system lacks (gauss2, gauss3: second_order and acceleration_scale), or no memory.
 * @param type the method
 * @param sys the system (copied; sys->params not owned: must outlive the integrator)
 * @return the integrator, to free with whirl_integrator_free; NULL with a message on failure
 */
WHIRL_API whirl_integrator *whirl_integrator_alloc_system(const whirl_integrator_type *type,
                                                          const whirl_system *sys);
/* Frees the integrator. NULL is a no-op.
 * @param it the integrator, or NULL
 */
WHIRL_API void whirl_integrator_free(whirl_integrator *it);

/* The integrator's method.
 * @param it the integrator, or NULL
 * @return the method (static storage), or NULL for a NULL integrator
 */
WHIRL_API const whirl_integrator_type *whirl_integrator_type_of(const whirl_integrator *it);

/* The smallest adaptive tolerance: finer relative accuracy is below the round-off of doubles. */
#define WHIRL_TOL_MIN 1e-16
/* The smallest adaptive step, in units of round-off of t (DBL_EPSILON max(|t|, 1)). */
#define WHIRL_STEP_MIN_ULPS 64

/* The default cap on the adaptive steps (accepted plus rejected) of one integrator over its life:
 * 1e8, hours of work on a large chain, far beyond any run the tolerance can justify (a run of
 * 1e8 steps accumulates round-off of 1e8 eps ~ 1e-8 of the state). */
#define WHIRL_ADAPTIVE_STEPS_MAX 100000000UL

/* Sets the cap on the adaptive steps (accepted plus rejected, counted over the integrator's life,
 * across calls of whirl_integrator_advance); 0 restores WHIRL_ADAPTIVE_STEPS_MAX.
 * @param it the integrator
 * @param max_steps the cap, or 0 for WHIRL_ADAPTIVE_STEPS_MAX
 */
WHIRL_API void whirl_integrator_set_max_steps(whirl_integrator *it, unsigned long max_steps);

/* Advances (t, y) to exactly t1: with tol = 0 by fixed steps of at most h (the last one
 * shortened); with tol > 0 adaptively (relative and absolute tolerance tol, h the first step) for
 * the methods that allow it, GSL_EINVAL for the others. Projects after each step (if the system
 * has a projection). Stops with the status of a failing right-hand side, projection or stage
 * solve (t, y then hold the last good state); GSL_EINVAL for tol in (0, WHIRL_TOL_MIN);
 * GSL_EFAILED when an adaptive step falls below WHIRL_STEP_MIN_ULPS units of round-off of t;
 * GSL_EMAXITER once the adaptive steps reach the cap (whirl_integrator_set_max_steps), with a
 * message naming the cap, the time reached and what to change;
 * WHIRL_EINTERRUPTED once a stop is requested (polled in every right-hand side; t, y at the last
 * completed step). Allocates nothing. Its messages type t and the steps as times
 * (whirl_last_error_in_units scales them by sqrt(L/g), the chain's time).
 * @param it the integrator
 * @param t in: the time [T]; out: t1, or the time of the last good state after a failure
 * @param y the state, advanced in place
 * @param t1 the time to reach [T]
 * @param h the fixed step (tol = 0), or the first step (tol > 0) [T]
 * @param tol 0 for fixed steps, or the adaptive tolerance (>= WHIRL_TOL_MIN)
 * @return GSL_SUCCESS, the status of a failing right-hand side, projection or stage solve,
 *     GSL_EINVAL, GSL_EFAILED, GSL_EMAXITER or WHIRL_EINTERRUPTED as above
 */
WHIRL_API int whirl_integrator_advance(whirl_integrator *it, double *t, double *y, double t1,
                                       double h, double tol);

/* The integrator's counts over its life, across calls of whirl_integrator_advance.
 * @param it the integrator
 * @return the counts
 */
WHIRL_API whirl_integrator_stats whirl_integrator_get_stats(const whirl_integrator *it);

#ifdef __cplusplus
}
#endif

#endif
