/* Perturbed time-domain runs about a steady shape: the nonlinear check of the linear analysis.
 *
 * Start: the exact relative equilibrium of the N-link chain (whirl_nlink_positions), every link
 * direction u_j turned by the angle eps towards a random unit vector t_j perpendicular to it,
 * u_j <- cos(eps) u_j + sin(eps) t_j, at rest in the frame co-rotating at omega. The dynamics
 * (3D, co-rotating frame, Cartesian formulation) are integrated with a fixed step and the
 * deviation d(t) (whirl_deviation: RMS over the masses of the distance to the shape, minimised
 * over a rotation about z, so the symmetry's drift does not count) sampled 50 times a period.
 * While the linear regime holds, d(t) = |sum_k c_k v_k e^{lambda_k t}|: the unstable part takes
 * over once it exceeds the neutral ones, and the slope of log d then is the largest growth rate.
 * The slope is fitted by least squares over the samples from the first that reaches 100 d(0) to
 * the first that reaches 1e4 d(0) or 1e-2 L (still linear: the nonlinear terms are of relative
 * size d / L), or to the end of the run. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "whirl/stability.h"
#include "error.h"

#define SAMPLES_PER_PERIOD 50
#define RATIO_GROWN 100.0      /* verdict unstable */
#define RATIO_CONVERGED 1e-2   /* verdict converging (damping > 0) */
#define RATIO_FIT_FROM 100.0
#define RATIO_FIT_TO 1e4
#define LINEAR_LIMIT 1e-2      /* deviation / L beyond which the fit stops */

const char *whirl_verdict_name(whirl_verdict v)
{
    switch (v) {
    case WHIRL_VERDICT_UNSTABLE: return "unstable";
    case WHIRL_VERDICT_CONVERGING: return "converging";
    default: return "stable";
    }
}

whirl_stability_run_params whirl_stability_run_defaults(void)
{
    whirl_stability_run_params p = {100.0, 1e-6, 1, "gauss2", 0.0, NULL, NULL};
    return p;
}

static int check_params(const whirl_model *model, const whirl_stability_run_params *p)
{
    if (model == NULL || model->chain == NULL) return whirl_fail(GSL_EINVAL, "no model or no chain");
    if (model->drive_radius != 0 || model->air_drag != 0 || model->air_drag_quadratic != 0)
        return whirl_fail(GSL_EINVAL, "a steady shape needs the pivot on the axis and no air drag");
    if (!(isfinite(model->internal_damping) && model->internal_damping >= 0))
        return whirl_fail(GSL_EINVAL, "damping must be >= 0 and finite, got %g",
                          model->internal_damping);
    if (!(isfinite(model->omega) && model->omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be positive, got %g", model->omega);
    if (!(isfinite(p->periods) && p->periods > 0))
        return whirl_fail(GSL_EINVAL, "periods must be > 0, got %g", p->periods);
    if (!(p->perturbation > 0 && p->perturbation < 1))
        return whirl_fail(GSL_EINVAL, "perturbation must be in (0, 1), got %g", p->perturbation);
    if (!(isfinite(p->dt) && p->dt >= 0))
        return whirl_fail(GSL_EINVAL, "step must be >= 0 (0: default), got %g", p->dt);
    if (p->method == NULL) return whirl_fail(GSL_EINVAL, "no integrator method");
    return GSL_SUCCESS;
}

/* Least-squares slope of the samples (t, log d) accumulated so far. */
typedef struct {
    double n, st, sy, stt, sty, from, to;
} line_fit;

static void fit_add(line_fit *f, double t, double y)
{
    if (f->n == 0) f->from = t;
    f->to = t;
    f->n += 1;
    f->st += t;
    f->sy += y;
    f->stt += t * t;
    f->sty += t * y;
}

static double fit_slope(const line_fit *f)
{
    const double den = f->n * f->stt - f->st * f->st;
    return (f->n >= 2 && den > 0) ? (f->n * f->sty - f->st * f->sy) / den : 0.0;
}

/* Shape (ref) and its perturbation (x) from the nodes r, z (pivot first), 3 per mass. */
static int perturbed_start(const whirl_chain *c, const double *r, const double *z, double eps,
                           unsigned long seed, double *ref, double *x)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (rng == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the random generator");
    gsl_rng_set(rng, seed);
    double base[3] = {0, 0, 0}, moved[3] = {0, 0, 0};
    for (size_t j = 0; j < c->n; j++) {
        const double len = c->length[j];
        const double u[3] = {(r[j + 1] - r[j]) / len, 0, (z[j + 1] - z[j]) / len};
        double t[3], norm = 0;
        do { /* a random direction perpendicular to u */
            for (int k = 0; k < 3; k++) t[k] = gsl_ran_gaussian(rng, 1.0);
            const double along = t[0] * u[0] + t[2] * u[2];
            for (int k = 0; k < 3; k++) t[k] -= along * u[k];
            norm = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        } while (norm < 1e-3);
        for (int k = 0; k < 3; k++) {
            base[k] += len * u[k];
            moved[k] += len * (cos(eps) * u[k] + sin(eps) * t[k] / norm);
            ref[3 * j + k] = base[k];
            x[3 * j + k] = moved[k];
        }
    }
    gsl_rng_free(rng);
    return GSL_SUCCESS;
}

/* min(period / 200, f / (nu + omega + kappa)): nu = 2 sqrt(max_j (T_j / l_j) / min m), the
 * Gershgorin bound of the highest transverse frequency under the tensions T_j (tension[j],
 * j = 1..N), and kappa = 4 D / (min m min l^2) that of the fastest decay of the internal damping
 * D. For the classical rk4, f = 2: inside its stability interval on the imaginary axis
 * (|h lambda| < 2.83) and on the negative real axis (2.79); the modes that decide stability are
 * far slower and resolved (relative error (h omega)^4), the fastest ones are damped by the
 * method. For the other methods f = 0.7, so that the stage iterations of the implicit methods
 * converge and the other explicit ones are stable. */
static double default_step(const whirl_model *m, const double *tension, const char *method)
{
    const double f = strcmp(method, "rk4") == 0 ? 2.0 : 0.7;
    const whirl_chain *c = m->chain;
    double stiff = 0, light = INFINITY, shortest = INFINITY;
    for (size_t j = 0; j < c->n; j++) {
        stiff = fmax(stiff, tension[j + 1] / c->length[j]);
        light = fmin(light, c->mass[j]);
        shortest = fmin(shortest, c->length[j]);
    }
    const double nu = 2 * sqrt(stiff / light);
    const double kappa = 4 * m->internal_damping / (light * shortest * shortest);
    return fmin(2 * M_PI / m->omega / 200, f / (nu + m->omega + kappa));
}

int whirl_stability_run(const whirl_model *model, double tip_r,
                        const whirl_stability_run_params *params,
                        whirl_stability_run_result *result)
{
    int status = check_params(model, params);
    if (status) return status;
    const whirl_chain *c = model->chain;
    const size_t n = c->n;
    whirl_model m = *model;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    whirl_dyn *dyn = NULL;
    whirl_integrator *it = NULL;
    double *buf = NULL, *y = NULL;
    memset(result, 0, sizeof *result);

    buf = calloc(3 * (n + 1) + 15 * n, sizeof(double));
    if (buf == NULL) {
        status = whirl_fail(GSL_ENOMEM, "out of memory for a run of %zu links", n);
        goto done;
    }
    double *r = buf, *z = r + n + 1, *tension = z + n + 1, *ref = tension + n + 1;
    double *x = ref + 3 * n, *v = x + 3 * n, *x_now = v + 3 * n, *v_now = x_now + 3 * n;
    if ((status = whirl_nlink_positions(c, m.omega, tip_r, r, z, tension))) goto done;
    if ((status = perturbed_start(c, r, z, params->perturbation, params->seed, ref, x))) goto done;

    if ((dyn = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN)) == NULL) {
        status = GSL_EINVAL; /* message set by whirl_dyn_alloc */
        goto done;
    }
    if ((it = whirl_integrator_alloc(params->method, dyn)) == NULL) {
        status = GSL_EINVAL;
        goto done;
    }
    if ((y = malloc(whirl_dyn_size(dyn) * sizeof *y)) == NULL) {
        status = whirl_fail(GSL_ENOMEM, "out of memory for a run of %zu links", n);
        goto done;
    }
    double t = 0;
    if ((status = whirl_dyn_set_state(dyn, t, x, v, y))) goto done;
    if ((status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, x_now, v_now))) goto done;
    const double d0 = whirl_deviation(n, x_now, ref);
    if (!(d0 > 0)) {
        status = whirl_fail(GSL_ERANGE, "the perturbation %g gives no deviation",
                            params->perturbation);
        goto done;
    }
    const double period = 2 * M_PI / m.omega, t_end = params->periods * period;
    const double h = params->dt > 0 ? params->dt : default_step(&m, tension, params->method);
    const double limit = LINEAR_LIMIT * whirl_chain_total_length(c);
    line_fit fit = {0};
    int fitting = 0, fit_done = 0;
    result->initial = d0;
    result->max_deviation = 1;
    result->end_deviation = 1;
    result->verdict = WHIRL_VERDICT_STABLE;
    if (params->observe && (status = params->observe(t, 1.0, params->observe_data))) goto done;
    for (unsigned long k = 1; t < t_end; k++) {
        const double t1 = fmin((double)k * period / SAMPLES_PER_PERIOD, t_end);
        if ((status = whirl_integrator_advance(it, &t, y, t1, h, 0))) goto done;
        if ((status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, x_now, v_now)))
            goto done;
        const double d = whirl_deviation(n, x_now, ref), ratio = d / d0;
        if (!isfinite(ratio)) {
            status = whirl_fail(GSL_ERANGE, "non-finite deviation at t = %g", t);
            goto done;
        }
        if (params->observe && (status = params->observe(t, ratio, params->observe_data)))
            goto done;
        result->end_deviation = ratio;
        result->max_deviation = fmax(result->max_deviation, ratio);
        if (ratio >= RATIO_GROWN) result->verdict = WHIRL_VERDICT_UNSTABLE;
        if (!fit_done && (fitting || ratio >= RATIO_FIT_FROM)) {
            fitting = 1;
            fit_add(&fit, t, log(d));
            fit_done = ratio >= RATIO_FIT_TO || d >= limit;
        }
        if (fit_done && result->verdict == WHIRL_VERDICT_UNSTABLE) break;
        if (m.internal_damping > 0 && result->verdict == WHIRL_VERDICT_STABLE &&
            ratio <= RATIO_CONVERGED) {
            result->verdict = WHIRL_VERDICT_CONVERGING;
            break;
        }
    }
    result->duration = t;
    if (result->verdict == WHIRL_VERDICT_UNSTABLE) {
        result->sim_growth = fit_slope(&fit);
        result->fit_from = fit.from;
        result->fit_to = fit.to;
    }
    result->stats = whirl_integrator_get_stats(it);
done:
    free(y);
    whirl_integrator_free(it);
    whirl_dyn_free(dyn);
    free(buf);
    return status;
}
