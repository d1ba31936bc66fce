/* The integrators' common driver and the classical Runge-Kutta method.
 *
 * whirl_integrator_advance takes fixed steps t_k = t0 + k h (the last one ending exactly at t1)
 * or, with tol > 0, the adaptive steps of rk8 or a GSL method, and projects the state onto the
 * constraints (the system's projection, if any) after every step.
 * Bounds: a tolerance below WHIRL_TOL_MIN is refused (it lies below the round-off of the state);
 * an adaptive step below WHIRL_STEP_MIN_ULPS units of round-off of t (64 eps max(|t|, 1)) stops
 * the run, as t would no longer advance by a representable amount; the adaptive steps, accepted
 * and rejected, of one integrator are capped (WHIRL_ADAPTIVE_STEPS_MAX by default, GSL_EMAXITER);
 * every right-hand side polls the stop request (WHIRL_EINTERRUPTED).
 * rk4: the classical 4-stage, order-4 explicit method (Kutta 1901; Hairer, Norsett, Wanner,
 * "Solving ODEs I", table II.1.2): k1 = f(t, y), k2 = f(t + h/2, y + h/2 k1),
 * k3 = f(t + h/2, y + h/2 k2), k4 = f(t + h, y + h k3), y += h/6 (k1 + 2 k2 + 2 k3 + k4). */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/integrator.h"
#include "core/error.h"
#include "integrate/integrator_internal.h"

int whirl_integrator_rhs(whirl_integrator *it, double t, const double *y, double *dydt)
{
    /* the stop request, polled inside every step (one right-hand side is far below 0.1 s) */
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request at t = " WHIRL_Q_TIME "%.17g",
                          t);
    it->stats.rhs_evals++;
    return it->sys.rhs(t, y, dydt, it->sys.params);
}

/* ---- rk4 ---- */

typedef struct rk4_state {
    double *k, *ytmp, *acc; /* k: one stage, ytmp: stage argument, acc: sum of b_i k_i */
} rk4_state;

static void rk4_free(void *state)
{
    rk4_state *s = state;
    if (s == NULL) return;
    free(s->k);
    free(s);
}

static int rk4_alloc(whirl_integrator *it)
{
    rk4_state *s = calloc(1, sizeof *s);
    if (s == NULL) return GSL_ENOMEM;
    it->state = s;
    s->k = malloc(3 * it->size * sizeof *s->k);
    if (s->k == NULL) return GSL_ENOMEM;
    s->ytmp = s->k + it->size;
    s->acc = s->ytmp + it->size;
    return GSL_SUCCESS;
}

static int rk4_step(whirl_integrator *it, double t, double h, double *y)
{
    rk4_state *s = it->state;
    const size_t n = it->size;
    static const double c[4] = {0, 0.5, 0.5, 1}, b[4] = {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6};
    memset(s->acc, 0, n * sizeof *s->acc);
    memcpy(s->ytmp, y, n * sizeof *y);
    for (int stage = 0; stage < 4; stage++) {
        int status = whirl_integrator_rhs(it, t + c[stage] * h, s->ytmp, s->k);
        if (status != GSL_SUCCESS) return status;
        for (size_t i = 0; i < n; i++) s->acc[i] += b[stage] * s->k[i];
        if (stage < 3)
            for (size_t i = 0; i < n; i++) s->ytmp[i] = y[i] + c[stage + 1] * h * s->k[i];
    }
    for (size_t i = 0; i < n; i++) y[i] += h * s->acc[i];
    return GSL_SUCCESS;
}

static const whirl_integrator_type rk4_type = {
    .name = "rk4", .adaptive = 0, .alloc = rk4_alloc, .free = rk4_free, .step = rk4_step};
const whirl_integrator_type *const whirl_integrator_rk4 = &rk4_type;

/* ---- registry: the one list of the methods, their names and the unknown-name message ---- */

static const whirl_integrator_type *const *const registry[] = {
    &whirl_integrator_gauss2,      &whirl_integrator_gauss3,    &whirl_integrator_rk4,
    &whirl_integrator_rk8,         &whirl_integrator_gsl_rk8pd, &whirl_integrator_gsl_rk4imp,
    &whirl_integrator_gsl_msadams, &whirl_integrator_gsl_msbdf, &whirl_integrator_gsl_rkf45,
    &whirl_integrator_gsl_rk4,
};
#define N_METHODS (sizeof registry / sizeof registry[0])

/* The names, filled from the registry once (pthread_once: callers may be threads). */
static const char *names[N_METHODS + 1];
static pthread_once_t names_once = PTHREAD_ONCE_INIT;

static void fill_names(void)
{
    for (size_t k = 0; k < N_METHODS; k++) names[k] = (*registry[k])->name;
    names[N_METHODS] = NULL;
}

const char *const *whirl_integrator_methods(void)
{
    pthread_once(&names_once, fill_names);
    return names;
}

const whirl_integrator_type *whirl_integrator_type_find(const char *name)
{
    for (size_t k = 0; k < N_METHODS && name != NULL; k++)
        if (strcmp((*registry[k])->name, name) == 0) return *registry[k];
    char known[256] = "";
    size_t used = 0;
    for (size_t k = 0; k < N_METHODS && used < sizeof known; k++)
        used += (size_t)snprintf(known + used, sizeof known - used, "%s%s", k ? " " : "",
                                 (*registry[k])->name);
    whirl_fail(GSL_EINVAL, "unknown integrator '%s' (known: %s)", name ? name : "(null)", known);
    return NULL;
}

const char *whirl_integrator_type_name(const whirl_integrator_type *type)
{
    return type ? type->name : NULL;
}

int whirl_integrator_type_adaptive(const whirl_integrator_type *type)
{
    return type && type->adaptive;
}

int whirl_integrator_type_fixed(const whirl_integrator_type *type)
{
    return type && type->step != NULL;
}

const whirl_integrator_type *whirl_integrator_type_of(const whirl_integrator *it)
{
    return it ? it->method : NULL;
}

whirl_integrator *whirl_integrator_alloc_system(const whirl_integrator_type *type,
                                                const whirl_system *sys)
{
    if (type == NULL || sys == NULL) {
        whirl_fail(GSL_EINVAL, "whirl_integrator_alloc_system: needs a method and a system");
        return NULL;
    }
    if (sys->rhs == NULL || sys->size == 0) {
        whirl_fail(GSL_EINVAL, "the system needs a right-hand side and a size >= 1");
        return NULL;
    }
    whirl_integrator *it = calloc(1, sizeof *it);
    if (it == NULL) goto nomem;
    it->method = type;
    it->sys = *sys;
    it->size = sys->size;
    it->last_y = malloc(2 * it->size * sizeof *it->last_y);
    if (it->last_y == NULL) goto nomem;
    it->backup = it->last_y + it->size;
    it->max_steps = WHIRL_ADAPTIVE_STEPS_MAX;
    int status = type->alloc(it);
    if (status == GSL_ENOMEM) goto nomem;
    if (status != GSL_SUCCESS) {
        whirl_integrator_free(it);
        return NULL; /* message set by the method */
    }
    return it;
nomem:
    whirl_integrator_free(it);
    whirl_fail(GSL_ENOMEM, "out of memory for the integrator %s", type->name);
    return NULL;
}

void whirl_integrator_free(whirl_integrator *it)
{
    if (it == NULL) return;
    if (it->method != NULL && it->method->free != NULL) it->method->free(it->state);
    free(it->last_y);
    free(it);
}

void whirl_integrator_set_max_steps(whirl_integrator *it, unsigned long max_steps)
{
    it->max_steps = max_steps > 0 ? max_steps : WHIRL_ADAPTIVE_STEPS_MAX;
}

whirl_integrator_stats whirl_integrator_get_stats(const whirl_integrator *it)
{
    return it->stats;
}

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* Projection after a step; a non-finite result is a failure. */
static int project(whirl_integrator *it, double t, double *y)
{
    int status = it->sys.project ? it->sys.project(t, y, it->sys.params) : GSL_SUCCESS;
    if (status != GSL_SUCCESS) return status;
    if (!all_finite(y, it->size))
        return whirl_fail(GSL_EBADFUNC, "the state is not finite at t = " WHIRL_Q_TIME "%.17g",
                          t);
    return GSL_SUCCESS;
}

int whirl_integrator_advance(whirl_integrator *it, double *t, double *y, double t1, double h,
                             double tol)
{
    if (!(isfinite(*t) && isfinite(t1) && t1 >= *t))
        return whirl_fail(GSL_EINVAL, "cannot advance from t = " WHIRL_Q_TIME "%g to t1 = "
                          WHIRL_Q_TIME "%g", *t, t1);
    if (!(isfinite(h) && h > 0))
        return whirl_fail(GSL_EINVAL, "step h must be > 0, got " WHIRL_Q_TIME "%.17g", h);
    if (!(isfinite(tol) && tol >= 0))
        return whirl_fail(GSL_EINVAL, "tolerance must be >= 0, got %g", tol);
    if (tol > 0 && tol < WHIRL_TOL_MIN)
        return whirl_fail(GSL_EINVAL, "tolerance %g is below the round-off of doubles: use a "
                          "tolerance >= %g", tol, WHIRL_TOL_MIN);
    if (tol > 0 && !it->method->adaptive)
        return whirl_fail(GSL_EINVAL, "the integrator %s has no adaptive step control",
                          it->method->name);
    if (tol == 0 && it->method->step == NULL)
        return whirl_fail(GSL_EINVAL, "the integrator %s takes adaptive steps only (give a "
                          "tolerance)", it->method->name);
    /* history (stage extrapolation, compensation, multistep memory) is valid only for the state
     * this integrator returned last */
    if (!it->has_last || it->last_t != *t ||
        memcmp(it->last_y, y, it->size * sizeof *y) != 0) {
        if (it->method->restart != NULL) it->method->restart(it);
    }
    int status = GSL_SUCCESS;
    const double t0 = *t;
    if (tol == 0) {
        const double span = t1 - t0;
        const double count = ceil(span / h * (1 - 1e-12));
        if (count > 1e15) return whirl_fail(GSL_EINVAL, "too many steps (%g)", count);
        const unsigned long steps = (unsigned long)count;
        for (unsigned long k = 0; k < steps; k++) {
            const double ta = *t, tb = k + 1 == steps ? t1 : t0 + (double)(k + 1) * h;
            memcpy(it->backup, y, it->size * sizeof *y);
            status = it->method->step(it, ta, tb - ta, y);
            if (status == GSL_SUCCESS) status = project(it, tb, y);
            if (status != GSL_SUCCESS) break;
            *t = tb;
            it->stats.steps++;
        }
    } else {
        double hh = h;
        while (*t < t1) {
            const double ta = *t;
            memcpy(it->backup, y, it->size * sizeof *y);
            if (it->adaptive_steps + it->stats.rejected >= it->max_steps) {
                status = whirl_fail(GSL_EMAXITER, "%s: %lu adaptive steps (the cap) reached t = "
                                    WHIRL_Q_TIME "%.17g only, of " WHIRL_Q_TIME "%.17g: loosen "
                                    "the tolerance %g, shorten the run or raise the cap "
                                    "(whirl_integrator_set_max_steps)",
                                    it->method->name, it->max_steps, ta, t1, tol);
                break;
            }
            status = it->method->adaptive_step(it, t, t1, &hh, tol, y);
            if (status == GSL_SUCCESS) status = project(it, *t, y);
            const double h_min = WHIRL_STEP_MIN_ULPS * DBL_EPSILON * fmax(fabs(ta), 1);
            if (status == GSL_SUCCESS && *t < t1 && (*t - ta < h_min || hh < h_min))
                status = whirl_fail(GSL_EFAILED, "%s: the adaptive step fell to " WHIRL_Q_TIME
                                    "%g at t = " WHIRL_Q_TIME "%.17g, below %d units of "
                                    "round-off of t: the tolerance %g cannot be met here (raise "
                                    "it, or use an implicit method for a stiff run)",
                                    it->method->name, fmin(*t - ta, hh), ta,
                                    WHIRL_STEP_MIN_ULPS, tol);
            if (status != GSL_SUCCESS) {
                *t = ta;
                break;
            }
            it->stats.steps++;
            it->adaptive_steps++;
        }
    }
    if (status != GSL_SUCCESS) {
        /* back to the last good state; the method's history does not describe it */
        memcpy(y, it->backup, it->size * sizeof *y);
        if (it->method->restart != NULL) it->method->restart(it);
    }
    memcpy(it->last_y, y, it->size * sizeof *y);
    it->last_t = *t;
    it->has_last = 1;
    return status;
}
