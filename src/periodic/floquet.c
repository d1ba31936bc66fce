/* Floquet multipliers of a periodic motion (whirl/periodic.h): two solves (steps and 2 steps per
 * period), the multipliers of the finer with the Richardson error estimate of the Gauss method
 * of order 4, |mu(h/2) - mu(h)| / (2^4 - 1), the reciprocal-pair error of the conservative
 * chain, the verdict and the edge.
 * Verdict: the largest modulus |mu|max is compared with 1 within the margin
 *   max(4 err(|mu|max), 2 reciprocal_err, MARGIN_FLOOR):
 * the error estimate is itself an estimate (a factor 4 for its own error); the conservative
 * chain's multipliers lie on the circle or in pairs mu, 1/mu, and how far the computed ones
 * are from pairs is how far the discrete period map is from symplectic (a modulus off 1 by
 * less than that is no evidence of growth); the floor is the central differences' noise.
 * With damping or drag (whirl_periodic_alloc_model) the period map contracts volume
 * (det M = exp(int_0^T div f dt) < 1, Liouville) and the multipliers are not in pairs: the
 * reciprocal-pair error is then reported as a measure and left out of the margin,
 *   max(4 err(|mu|max), MARGIN_FLOOR). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "core/error.h"
#include "periodic/periodic_internal.h"

/* The central differences' noise in a multiplier (FD_REL^2 truncation, round-off over FD_REL;
 * periodic.c), with a factor 10 of safety. */
#define MARGIN_FLOOR 1e-9
/* Default steps per period: the Gauss method's error (h omega)^4 ~ (2 pi / 400)^4 ~ 6e-8 on a
 * motion at the path's rate, refined by the second solve. */
#define STEPS_DEFAULT 400
/* Fewer steps per period than this cannot follow even the path's own cos(omega t) (the Gauss
 * method's error (2 pi / 8)^4 ~ 0.4). */
#define STEPS_MIN 8
/* Newton's test: 1e-10 of L (and of omega_ref L), above the round-off of a period of a few
 * thousand steps (the steady shape's residual is 6e-16 at 12800 steps, 5e-12 at 800: the
 * Gauss method's error over a period, docs/theory/floquet.md) and far below what changes a
 * multiplier at its error. */
#define TOL_DEFAULT 1e-10
/* Newton converges quadratically from a good start (3 or 4 iterations from 1e-3 off the circle
 * drive's shape); 30 allows for the halvings of a poor start. */
#define ITER_DEFAULT 30
/* Richardson for a method of order 4: mu(h/2) - mu = (mu(h) - mu(h/2)) / (2^4 - 1). */
#define RICHARDSON 15.0

const char *whirl_floquet_verdict_name(whirl_floquet_verdict v)
{
    switch (v) {
    case WHIRL_FLOQUET_STABLE: return "stable";
    case WHIRL_FLOQUET_NEUTRAL: return "neutral";
    case WHIRL_FLOQUET_UNSTABLE: return "unstable";
    }
    return "unknown";
}

const char *whirl_floquet_edge_name(whirl_floquet_edge e)
{
    switch (e) {
    case WHIRL_FLOQUET_EDGE_PLUS_ONE: return "+1";
    case WHIRL_FLOQUET_EDGE_MINUS_ONE: return "-1";
    case WHIRL_FLOQUET_EDGE_COMPLEX: return "complex";
    }
    return "unknown";
}

/* The steps per period: the requested (or the default) raised to the bound of
 * whirl_default_step at the start y, with the tensions raised by the pivot's largest
 * acceleration times the mass below each link (the tension of a shaken chain swings by it). */
int periodic_steps_for(whirl_periodic *w, const double *y, int requested, int *steps)
{
    const size_t n = w->n;
    double *tension = malloc(n * sizeof *tension);
    if (tension == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = whirl_dyn_tensions(w->dyn, 0, y, tension);
    double amax = 0;
    for (int j = 1; j <= w->path.harmonics; j++)
        for (int k = 0; k < 3; k++)
            amax += (j * w->path.omega) * (j * w->path.omega) *
                    (fabs(w->path.c[k][j - 1]) + fabs(w->path.s[k][j - 1]));
    double below = 0;
    for (size_t i = n; i-- > 0;) {
        below += w->chain->mass[i];
        tension[i] = fabs(tension[i]) + below * amax;
    }
    double h = 0;
    if (status == GSL_SUCCESS)
        status = whirl_default_step(whirl_dyn_model(w->dyn), tension, "gauss2", &h);
    free(tension);
    if (status) return status;
    const double period = whirl_pivot_period(&w->path);
    const double need = ceil(period / h * (1 - 1e-12));
    int s = requested > 0 ? requested : STEPS_DEFAULT;
    if (need > 1e8) return whirl_fail(GSL_EINVAL, "the pivot moves too fast for the integrator: "
                                      "%.3g steps per period needed", need);
    if (need > s) s = (int)need;
    *steps = s;
    return GSL_SUCCESS;
}

/* The margin of the verdict (file header). */
static double margin_of(const whirl_periodic_result *r, int dissipative)
{
    const double pairs = dissipative ? 0 : 2 * r->reciprocal_err;
    return fmax(fmax(4 * r->max_modulus_err, pairs), MARGIN_FLOOR);
}

static whirl_floquet_edge kind_of(double re, double im, double tol)
{
    if (fabs(im) > tol) return WHIRL_FLOQUET_EDGE_COMPLEX;
    return re > 0 ? WHIRL_FLOQUET_EDGE_PLUS_ONE : WHIRL_FLOQUET_EDGE_MINUS_ONE;
}

/* Verdict, growth, e-folding and edge of r (multipliers sorted by decreasing modulus). */
static void judge(whirl_periodic_result *r, int dissipative)
{
    const size_t m = r->count;
    const double margin = margin_of(r, dissipative), mu = r->max_modulus;
    r->growth = 1, r->efold_periods = r->efold_time = 0, r->edge_distance = 0;
    if (mu > 1 + margin) {
        r->verdict = WHIRL_FLOQUET_UNSTABLE;
        r->growth = mu;
        r->efold_periods = 1 / log(mu);
        r->efold_time = r->period / log(mu);
        r->edge = kind_of(r->re[0], r->im[0], margin + 4 * r->err[0]);
        return;
    }
    if (mu < 1 - margin) {
        r->verdict = WHIRL_FLOQUET_STABLE;
        r->edge = kind_of(r->re[0], r->im[0], margin + 4 * r->err[0]);
        r->edge_distance = 1 - mu;
        return;
    }
    r->verdict = WHIRL_FLOQUET_NEUTRAL;
    if (dissipative) { /* on the circle within the margin: the largest is on its edge */
        r->edge = kind_of(r->re[0], r->im[0], margin + 4 * r->err[0]);
        return;
    }
    /* neutral: the nearest of +1, -1 (angle of a multiplier from them) and a meeting of two
       multipliers in the upper half plane (half the angle between neighbours) */
    double best = INFINITY;
    for (size_t i = 0; i < m; i++) {
        const double theta = atan2(fabs(r->im[i]), r->re[i]);
        if (theta < best) best = theta, r->edge = WHIRL_FLOQUET_EDGE_PLUS_ONE;
        if (M_PI - theta < best) best = M_PI - theta, r->edge = WHIRL_FLOQUET_EDGE_MINUS_ONE;
        if (!(r->im[i] > margin)) continue;
        for (size_t j = 0; j < m; j++) {
            if (j == i || !(r->im[j] > margin)) continue;
            const double half = fabs(theta - atan2(r->im[j], r->re[j])) / 2;
            if (half < best) best = half, r->edge = WHIRL_FLOQUET_EDGE_COMPLEX;
        }
    }
    r->edge_distance = best;
}

void periodic_judge(whirl_periodic_result *r, int dissipative)
{
    const size_t m = r->count;
    const double *re = r->re, *im = r->im;
    r->max_modulus = hypot(re[0], im[0]);
    r->max_modulus_err = r->err[0];
    double pair = 0;
    for (size_t i = 0; i < m; i++) {
        double best = INFINITY;
        for (size_t j = 0; j < m; j++) /* |mu_i mu_j - 1| */
            best = fmin(best, hypot(re[i] * re[j] - im[i] * im[j] - 1,
                                    re[i] * im[j] + im[i] * re[j]));
        pair = fmax(pair, best);
    }
    r->reciprocal_err = pair;
    judge(r, dissipative);
}

int whirl_periodic_find(whirl_periodic *w, double *y, const whirl_periodic_params *params,
                        whirl_periodic_result *result)
{
    if (w == NULL || y == NULL || result == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_periodic_find: NULL argument");
    memset(result, 0, sizeof *result);
    whirl_periodic_params p = params ? *params : (whirl_periodic_params){.refine = 1};
    if (p.steps != 0 && p.steps < STEPS_MIN)
        return whirl_fail(GSL_EINVAL, "steps per period must be >= %d, got %d", STEPS_MIN,
                          p.steps);
    if (!(isfinite(p.tol) && p.tol >= 0) || p.max_iter < 0)
        return whirl_fail(GSL_EINVAL, "the tolerance must be >= 0 and the iterations >= 0");
    if (p.steps > 1 << 24)
        return whirl_fail(GSL_EINVAL, "steps per period must be at most %d, got %d", 1 << 24,
                          p.steps);
    if (p.monodromy != WHIRL_MONODROMY_VARIATIONAL && p.monodromy != WHIRL_MONODROMY_DIFFERENCES)
        return whirl_fail(GSL_EINVAL, "unknown monodromy method %d", (int)p.monodromy);
    w->method = p.monodromy;
    const double tol = p.tol > 0 ? p.tol : TOL_DEFAULT;
    const int max_iter = p.max_iter > 0 ? p.max_iter : ITER_DEFAULT;
    for (size_t q = 0; q < w->size; q++)
        if (!isfinite(y[q])) return whirl_fail(GSL_EINVAL, "the start state is not finite");
    int steps = 0;
    int status = whirl_dyn_project(w->dyn, 0, y);
    if (status == GSL_SUCCESS) status = periodic_steps_for(w, y, p.steps, &steps);
    if (status) return status;
    const size_t m = w->m;
    double *re = w->out, *im = w->out + m, *err = w->out + 2 * m;
    double *re_c = w->out + 3 * m, *im_c = w->out + 4 * m, *used = w->out + 5 * m;
    double *y_coarse = NULL;
    double residual;
    int iterations, coarse_iterations = 0;
    w->progress = (whirl_periodic_progress){.solve = p.refine ? 1 : 2, .residual = INFINITY};
    if (p.refine) {
        y_coarse = malloc(w->size * sizeof *y_coarse);
        if (y_coarse == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        status = periodic_solve(w, y, steps, tol, max_iter, &residual, &iterations);
        if (status == GSL_SUCCESS) status = periodic_multipliers(w, re_c, im_c);
        if (status) {
            free(y_coarse);
            return status;
        }
        memcpy(y_coarse, y, w->size * sizeof *y);
        coarse_iterations = iterations;
        steps *= 2;
        w->progress.solve = 2;
    }
    status = periodic_solve(w, y, steps, tol, max_iter, &residual, &iterations);
    if (status == GSL_SUCCESS) status = periodic_multipliers(w, re, im);
    if (status) {
        free(y_coarse);
        w->have_mono = 0;
        return status;
    }
    result->count = m;
    result->re = re, result->im = im, result->err = err;
    result->residual = residual;
    result->iterations = coarse_iterations + iterations;
    result->steps = steps;
    result->period = whirl_pivot_period(&w->path);
    /* errors: each finer multiplier against the nearest coarse one not yet taken */
    for (size_t i = 0; i < m; i++) used[i] = 0, err[i] = 0;
    if (p.refine) {
        for (size_t i = 0; i < m; i++) {
            size_t best = m;
            double dist = INFINITY;
            for (size_t j = 0; j < m; j++) {
                const double d = hypot(re[i] - re_c[j], im[i] - im_c[j]);
                if (!used[j] && d < dist) dist = d, best = j;
            }
            used[best] = 1;
            err[i] = dist / RICHARDSON;
        }
        double change = 0;
        const size_t half = w->size / 2;
        for (size_t q = 0; q < w->size; q++)
            change = fmax(change, fabs(y[q] - y_coarse[q]) /
                                      (q < half ? w->length : w->length * w->omega_ref));
        result->orbit_change = change;
    }
    free(y_coarse);
    periodic_judge(result, w->dissipative);
    return GSL_SUCCESS;
}
