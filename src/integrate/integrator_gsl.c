/* GSL's ODE steppers (ode-initval2) on the dynamics' right-hand side: gsl-rk8pd (Prince-Dormand
 * 8(9)), gsl-rk4imp (the 2-stage Gauss method, modified Newton with a dense LU of 2 x dim, error
 * by step doubling), gsl-msadams (variable-order Adams, orders 1-12, functional iteration,
 * Nordsieck form), gsl-msbdf (variable-order BDF, Nordsieck form), gsl-rkf45, gsl-rk4. A
 * reference path, not a fast one.
 *
 * Fixed steps (all but the multistep msadams and msbdf, whose correctors are tied to their step
 * control):
 * gsl_odeiv2_evolve_apply_fixed_step without step rejection; the implicit rk4imp still iterates
 * its stage equations to the driver's control, set to GSL_FIXED_STEP_TOL. Adaptive steps:
 * gsl_odeiv2_evolve_apply with the standard control on y (relative = absolute = tol).
 * After every step the driver (integrator.c) projects the state onto the constraints. msadams
 * and msbdf continue from their own Nordsieck history (GSL reads y only on their first step), so
 * for them the projection affects the output only, and their constraint drift is bounded by
 * their tolerance.
 * Jacobian (rk4imp, msbdf need one): forward differences, column j with the increment
 * sqrt(eps) max(|y_j|, 1e-3), and df/dt likewise; dim + 2 right-hand sides, in scratch vectors
 * allocated once with the integrator. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <float.h>
#include <gsl/gsl_odeiv2.h>

#include "core/error.h"
#include "integrate/integrator_internal.h"

/* Tolerance of the implicit steppers' own iterations (Newton of rk4imp, BDF corrector of msbdf)
 * in fixed steps. */
#define GSL_FIXED_STEP_TOL 1e-12

typedef struct gsl_state {
    whirl_integrator *it;
    gsl_odeiv2_system sys;
    gsl_odeiv2_driver *driver;
    double *f0, *f1, *ytmp; /* Jacobian scratch */
    int interrupted;        /* a right-hand side saw the stop request */
} gsl_state;

/* GSL retries a step with a smaller one after any status but GSL_EBADFUNC: a stop request is
 * handed to it as GSL_EBADFUNC, so that it returns at once, and translated back in gsl_status. */
static int gsl_rhs(double t, const double y[], double dydt[], void *params)
{
    gsl_state *g = params;
    int status = whirl_integrator_rhs(g->it, t, y, dydt);
    if (status == WHIRL_EINTERRUPTED) {
        g->interrupted = 1;
        return GSL_EBADFUNC;
    }
    return status;
}

static int gsl_jacobian(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
    gsl_state *g = params;
    const size_t n = g->it->size;
    int status = gsl_rhs(t, y, g->f0, g);
    if (status != GSL_SUCCESS) return status;
    memcpy(g->ytmp, y, n * sizeof *y);
    const double root_eps = sqrt(DBL_EPSILON);
    for (size_t j = 0; j < n; j++) {
        const double step = root_eps * fmax(fabs(y[j]), 1e-3);
        g->ytmp[j] = y[j] + step;
        const double dj = g->ytmp[j] - y[j]; /* the increment actually represented */
        status = gsl_rhs(t, g->ytmp, g->f1, g);
        g->ytmp[j] = y[j];
        if (status != GSL_SUCCESS) return status;
        for (size_t i = 0; i < n; i++) dfdy[i * n + j] = (g->f1[i] - g->f0[i]) / dj;
    }
    const double dt = root_eps * fmax(fabs(t), 1.0);
    status = gsl_rhs(t + dt, y, g->f1, g);
    if (status != GSL_SUCCESS) return status;
    for (size_t i = 0; i < n; i++) dfdt[i] = (g->f1[i] - g->f0[i]) / dt;
    return GSL_SUCCESS;
}

static void gsl_free_state(void *state)
{
    gsl_state *g = state;
    if (g == NULL) return;
    if (g->driver != NULL) gsl_odeiv2_driver_free(g->driver);
    free(g->f0);
    free(g);
}

static int gsl_alloc_state(whirl_integrator *it)
{
    gsl_state *g = calloc(1, sizeof *g);
    if (g == NULL) return GSL_ENOMEM;
    it->state = g;
    g->it = it;
    const size_t n = it->size;
    g->f0 = malloc(3 * n * sizeof *g->f0);
    if (g->f0 == NULL) return GSL_ENOMEM;
    g->f1 = g->f0 + n;
    g->ytmp = g->f1 + n;
    g->sys = (gsl_odeiv2_system){gsl_rhs, gsl_jacobian, n, g};
    const gsl_odeiv2_step_type *const *type = it->method->params;
    g->driver = gsl_odeiv2_driver_alloc_y_new(&g->sys, *type, 1e-3, 1e-6, 1e-6);
    if (g->driver == NULL) return GSL_ENOMEM;
    return GSL_SUCCESS;
}

static void gsl_restart(whirl_integrator *it)
{
    gsl_state *g = it->state;
    gsl_odeiv2_driver_reset(g->driver);
}

static int gsl_status(gsl_state *g, int status, double t)
{
    if (g->interrupted) {
        g->interrupted = 0;
        return WHIRL_EINTERRUPTED; /* message from the right-hand side */
    }
    if (status == GSL_SUCCESS) return GSL_SUCCESS;
    if (status == GSL_EBADFUNC) return status; /* message from the right-hand side */
    return whirl_fail(status, "the GSL stepper failed at t = " WHIRL_Q_TIME "%.17g (%s)", t,
                      gsl_strerror(status));
}

static int gsl_fixed_step(whirl_integrator *it, double t, double h, double *y)
{
    gsl_state *g = it->state;
    gsl_odeiv2_driver *dr = g->driver;
    gsl_odeiv2_control_init(dr->c, GSL_FIXED_STEP_TOL, GSL_FIXED_STEP_TOL, 1, 0);
    double tt = t;
    int status = gsl_odeiv2_evolve_apply_fixed_step(dr->e, NULL, dr->s, &g->sys, &tt, h, y);
    return gsl_status(g, status, t);
}

static int gsl_adaptive_step(whirl_integrator *it, double *t, double t1, double *h, double tol,
                             double *y)
{
    gsl_state *g = it->state;
    gsl_odeiv2_driver *dr = g->driver;
    gsl_odeiv2_control_init(dr->c, tol, tol, 1, 0);
    const unsigned long failed = dr->e->failed_steps;
    const double t0 = *t;
    int status = gsl_odeiv2_evolve_apply(dr->e, dr->c, dr->s, &g->sys, t, t1, h, y);
    it->stats.rejected += dr->e->failed_steps - failed;
    return gsl_status(g, status, t0);
}

/* fixed_step: gsl_fixed_step, or NULL for the multistep methods (adaptive steps only) */
#define GSL_METHOD(var, label, type, fixed_step)                                              \
    static const whirl_integrator_type var##_type = {.name = label,                          \
                                   .adaptive = 1,                                            \
                                   .params = &type,                                          \
                                   .alloc = gsl_alloc_state,                                 \
                                   .free = gsl_free_state,                                   \
                                   .step = fixed_step,                                       \
                                   .adaptive_step = gsl_adaptive_step,                       \
                                   .restart = gsl_restart};                                  \
    const whirl_integrator_type *const var = &var##_type

GSL_METHOD(whirl_integrator_gsl_rk8pd, "gsl-rk8pd", gsl_odeiv2_step_rk8pd, gsl_fixed_step);
GSL_METHOD(whirl_integrator_gsl_rk4imp, "gsl-rk4imp", gsl_odeiv2_step_rk4imp, gsl_fixed_step);
GSL_METHOD(whirl_integrator_gsl_msadams, "gsl-msadams", gsl_odeiv2_step_msadams, NULL);
GSL_METHOD(whirl_integrator_gsl_msbdf, "gsl-msbdf", gsl_odeiv2_step_msbdf, NULL);
GSL_METHOD(whirl_integrator_gsl_rkf45, "gsl-rkf45", gsl_odeiv2_step_rkf45, gsl_fixed_step);
GSL_METHOD(whirl_integrator_gsl_rk4, "gsl-rk4", gsl_odeiv2_step_rk4, gsl_fixed_step);
