/* The bracketing root finder (core/roots.h): Brent's method as GSL implements it (Brent 1973,
 * "Algorithms for minimization without derivatives", ch. 4; GSL roots/brent.c), driven by one
 * loop: GSL's set on [lo, hi], then iterate until gsl_root_test_interval passes, f fails, GSL
 * fails or the count of iterations runs out. The ends' known values are handed to GSL's set
 * (which evaluates f at lo, then at hi) instead of f. The minimiser likewise: GSL's
 * gsl_min_fminimizer_brent set with the three known values, then iterated until
 * gsl_min_test_interval passes, the least value falls below a level, f fails, GSL fails or the
 * count runs out. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>

#include "core/error.h"
#include "core/roots.h"

typedef struct root_call {
    whirl_root_fn f;
    void *ctx;
    int status;      /* f's first failure */
    int in_set;      /* inside GSL's set with known ends */
    double lo, hi, f_lo, f_hi;
} root_call;

static double root_value(double x, void *p)
{
    root_call *call = p;
    if (call->in_set) {
        if (x == call->lo) return call->f_lo;
        if (x == call->hi) return call->f_hi;
    }
    double fx = GSL_NAN;
    int status = call->f(x, call->ctx, &fx);
    if (status && !call->status) call->status = status;
    return fx;
}

int whirl_root_brent(whirl_root_fn f, void *ctx, double lo, double hi, const whirl_root_opts *o,
                     whirl_root *out)
{
    const whirl_root start = {0.5 * (lo + hi), lo, hi, 0, 0};
    *out = start;
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (s == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the root solver");
    root_call call = {f, ctx, GSL_SUCCESS, o->known != 0, lo, hi, o->f_lo, o->f_hi};
    gsl_function fn = {root_value, &call};
    int status = gsl_root_fsolver_set(s, &fn, lo, hi);
    call.in_set = 0;
    out->bracketed = status == GSL_SUCCESS && call.status == GSL_SUCCESS;
    if (call.status) status = call.status;
    int it = 0;
    while (status == GSL_SUCCESS) {
        if (it == o->max_iter) {
            status = GSL_EMAXITER;
            break;
        }
        status = gsl_root_fsolver_iterate(s);
        it++;
        if (call.status) status = call.status;
        if (status) break;
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s),
                                   o->epsabs, o->epsrel) == GSL_SUCCESS)
            break;
    }
    /* (before an iteration, GSL's estimate is the start's, and it has none where it refuses
     * lo > hi) */
    if (it) {
        out->root = gsl_root_fsolver_root(s);
        out->lower = gsl_root_fsolver_x_lower(s);
        out->upper = gsl_root_fsolver_x_upper(s);
        out->iterations = it;
    }
    gsl_root_fsolver_free(s);
    return status;
}

typedef struct min_call {
    whirl_root_fn f;
    void *ctx;
    int status; /* f's first failure */
} min_call;

static double min_value(double x, void *p)
{
    min_call *call = p;
    if (call->status) return GSL_NAN;
    double fx = GSL_NAN;
    call->status = call->f(x, call->ctx, &fx);
    return fx;
}

int whirl_min_brent(whirl_root_fn f, void *ctx, double x, double fx, double lo, double f_lo,
                    double hi, double f_hi, const whirl_min_opts *o, whirl_min *out)
{
    const whirl_min start = {x, fx, lo, hi, 0, 0};
    *out = start;
    gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    if (m == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the minimiser");
    min_call call = {f, ctx, GSL_SUCCESS};
    gsl_function fn = {min_value, &call};
    int status = gsl_min_fminimizer_set_with_values(m, &fn, x, fx, lo, f_lo, hi, f_hi);
    const int set = status == GSL_SUCCESS;
    int it = 0;
    while (status == GSL_SUCCESS && it < o->max_iter) {
        status = gsl_min_fminimizer_iterate(m);
        it++;
        if (call.status) status = call.status;
        if (status) break;
        if (gsl_min_fminimizer_f_minimum(m) < o->below) {
            out->below = 1;
            break;
        }
        if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m),
                                  o->epsabs, o->epsrel) == GSL_SUCCESS)
            break;
    }
    if (set) {
        out->x = gsl_min_fminimizer_x_minimum(m);
        out->f = gsl_min_fminimizer_f_minimum(m);
        out->lower = gsl_min_fminimizer_x_lower(m);
        out->upper = gsl_min_fminimizer_x_upper(m);
    }
    out->iterations = it;
    gsl_min_fminimizer_free(m);
    return status;
}
