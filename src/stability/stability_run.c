/* Perturbed time-domain runs about a steady shape: the nonlinear check of the linear analysis.
 *
 * Start: a relative equilibrium of the N-link chain (free: whirl_nlink_positions; driven, with
 * air drag: whirl_driven_sample), every link turned by the angle eps (whirl_perturb_links), at
 * rest in the frame co-rotating at omega, the pivot at (eps_drive, 0, 0)
 * (whirl_dyn_state_from_shape). The step: whirl_default_step unless one is given. The dynamics (3D, co-rotating frame,
 * Cartesian formulation, the model's drive, drag and damping) are integrated with a fixed step and
 * the deviation d(t) (RMS over the masses of the distance to the shape; when rotation about z is
 * a symmetry, without drive and drag, minimised over that rotation by whirl_deviation, so the
 * symmetry's drift does not count) sampled 50 times a period.
 * While the linear regime holds, d(t) = |sum_k c_k v_k e^{lambda_k t}|: the unstable part takes
 * over once it exceeds the neutral ones, and the slope of log d then is the largest growth rate.
 * The slope is fitted by least squares over the samples from the first that reaches 100 d(0) to
 * the first where some link has turned by 1e-3 rad from its direction in the shape (the
 * nonlinear terms of the equations of motion are of the relative size of the links' turns) and d
 * has reached 1e4 d(0) (the shortest stretch, for perturbations too large to leave a linear one),
 * or to the first that reaches 1e8 d(0) or 1e-2 L, or to the end of the run. The turn, not
 * d / L, bounds the linear regime: an unstable mode of a long chain at a high mode concentrates
 * on a few links near the tip
 * (N = 100, mode 50, omega = 250: largest turn about 1e3 d / L), and a fit that ran on to
 * d = 1e-2 L there took in turns of 0.04 rad and gave 68.74 for the growth 72.33 of the
 * linearisation. The fit's stretch is long for the same reason: the unstable modes next to the
 * largest (53.6, 46.4, ... there) fade from d only as exp(-(19 t)), and a stretch of 4.6
 * e-folds (100 to 1e4 d(0)) left 1-2% of their slower growth in the slope. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "whirl/stability.h"
#include "core/error.h"
#include "stability/stability_internal.h"

#define SAMPLES_PER_PERIOD 50
#define RATIO_GROWN 100.0      /* verdict unstable */
#define RATIO_CONVERGED 1e-2   /* verdict converging (dissipation > 0), the run stops */
#define RATIO_DECAYED 1e-1     /* verdict converging at the end of the run */
#define RATIO_FIT_FROM 100.0
#define RUN_STEPS_MAX 1e9      /* time steps of one run: more are refused up front */
#define RATIO_FIT_TO 1e8
#define RATIO_FIT_MIN 1e4      /* the fit runs at least to this deviation / initial */
#define TURN_LIMIT 1e-3        /* largest turn of a link [rad] beyond which the fit stops */
#define LINEAR_LIMIT 1e-2      /* deviation / L beyond which the fit stops */

const char *whirl_verdict_name(whirl_verdict v)
{
    switch (v) {
    case WHIRL_VERDICT_UNSTABLE: return "unstable";
    case WHIRL_VERDICT_CONVERGING: return "converging";
    case WHIRL_VERDICT_NEUTRAL: return "neutral (gyroscopic)";
    default: return "stable (minimum)";
    }
}

whirl_verdict whirl_verdict_refine(whirl_verdict v, int index)
{
    return v == WHIRL_VERDICT_STABLE && index > 0 ? WHIRL_VERDICT_NEUTRAL : v;
}

whirl_verdict whirl_verdict_linear(double growth, int index)
{
    if (growth > 0) return WHIRL_VERDICT_UNSTABLE;
    if (growth < 0) return WHIRL_VERDICT_CONVERGING;
    return whirl_verdict_refine(WHIRL_VERDICT_STABLE, index);
}

whirl_stability_run_params whirl_stability_run_defaults(void)
{
    whirl_stability_run_params p = {100.0, 1e-10, 1, "gauss2", 0.0, NULL, NULL, NULL};
    return p;
}

static int check_params(const whirl_model *model, const whirl_stability_run_params *p)
{
    if (model == NULL || model->chain == NULL) return whirl_fail(GSL_EINVAL, "no model or no chain");
    const double nonneg[4] = {model->internal_damping, model->drive_radius, model->air_drag,
                              model->air_drag_quadratic};
    const char *names[4] = {"damping", "drive radius", "air drag", "quadratic air drag"};
    for (int k = 0; k < 4; k++)
        if (!(isfinite(nonneg[k]) && nonneg[k] >= 0))
            return whirl_fail(GSL_EINVAL, "%s must be >= 0 and finite, got %g", names[k],
                              nonneg[k]);
    if (!(isfinite(model->omega) && model->omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be positive, got %g", model->omega);
    if (whirl_check_omega_max(model->omega) != GSL_SUCCESS) return GSL_EINVAL;
    if (!(isfinite(p->periods) && p->periods > 0))
        return whirl_fail(GSL_EINVAL, "periods must be > 0, got %g", p->periods);
    if (!(p->perturbation > 0 && p->perturbation < 1))
        return whirl_fail(GSL_EINVAL, "perturbation must be in (0, 1), got %g", p->perturbation);
    if (!(isfinite(p->dt) && p->dt >= 0))
        return whirl_fail(GSL_EINVAL, "step must be >= 0 (0: default), got " WHIRL_Q_TIME "%.17g",
                          p->dt);
    if (p->method == NULL) return whirl_fail(GSL_EINVAL, "no integrator method");
    return GSL_SUCCESS;
}

/* u = cos a cos b u0 + sin a cos b e1 + sin b e2 in the chart of each link (stability.h) */
int whirl_perturb_links_along(size_t n, double *links, double eps, const double *along)
{
    if (links == NULL || along == NULL || n == 0)
        return whirl_fail(GSL_EINVAL, "no links or no direction to perturb along");
    if (!(isfinite(eps) && eps >= 0))
        return whirl_fail(GSL_EINVAL, "the perturbation must be >= 0 and finite, got %g", eps);
    double big = 0;
    for (size_t i = 0; i < 2 * n; i++) {
        if (!isfinite(along[i]))
            return whirl_fail(GSL_EINVAL, "the direction's angle %zu is not finite", i);
        big = fmax(big, fabs(along[i]));
    }
    if (!(big > 0)) return whirl_fail(GSL_EINVAL, "the direction to perturb along is zero");
    for (size_t j = 0; j < n; j++) {
        double *l = links + 3 * j, u[3], e1[3], e2[3];
        const double len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        if (!(len > 0)) return whirl_fail(GSL_EINVAL, "link %zu has no length", j + 1);
        for (int k = 0; k < 3; k++) u[k] = l[k] / len;
        stability_link_chart(u, e1, e2);
        const double a = eps * along[j] / big, b = eps * along[n + j] / big;
        for (int k = 0; k < 3; k++)
            l[k] = len * (cos(a) * cos(b) * u[k] + sin(a) * cos(b) * e1[k] + sin(b) * e2[k]);
    }
    return GSL_SUCCESS;
}

static int has_symmetry(const whirl_model *m)
{
    return m->drive_radius == 0 && m->air_drag == 0 && m->air_drag_quadratic == 0;
}

/* The deviation of the masses x from ref (n each, 3 per mass): modulo the rotation about z when
 * that is a symmetry, else the plain RMS distance. */
static double deviation(const whirl_model *m, size_t n, const double *x, const double *ref)
{
    if (has_symmetry(m)) return whirl_deviation(n, x, ref);
    double sum = 0;
    for (size_t i = 0; i < 3 * n; i++) sum += (x[i] - ref[i]) * (x[i] - ref[i]);
    return sqrt(sum / (double)n);
}

/* The largest angle [rad] between a link of the positions x and the same link of ref (n masses,
 * 3 per mass; the pivot at (px, 0, 0) for both). */
static double max_turn(size_t n, const double *x, const double *ref, double px)
{
    double turn = 0;
    for (size_t i = 0; i < n; i++) {
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            const double xp = i > 0 ? x[3 * (i - 1) + k] : (k == 0 ? px : 0);
            const double rp = i > 0 ? ref[3 * (i - 1) + k] : (k == 0 ? px : 0);
            a[k] = x[3 * i + k] - xp;
            b[k] = ref[3 * i + k] - rp;
        }
        const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                             a[0] * b[1] - a[1] * b[0]};
        turn = fmax(turn, atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                                a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
    }
    return turn;
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

int whirl_stability_run_shape(const whirl_model *model, const double *nx, const double *ny,
                              const double *nz, const whirl_stability_run_params *params,
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

    buf = calloc(n + 15 * n, sizeof(double));
    if (buf == NULL) {
        status = whirl_fail(GSL_ENOMEM, "out of memory for a run of %zu links", n);
        goto done;
    }
    double *tension = buf, *ref = tension + n;
    double *links = ref + 3 * n, *turned = links + 3 * n, *x_now = turned + 3 * n;
    double *v_now = x_now + 3 * n;
    if ((status = whirl_shape_links(n, nx, ny, nz, links))) goto done;
    memcpy(turned, links, 3 * n * sizeof *links);
    status = params->along ? whirl_perturb_links_along(n, turned, params->perturbation,
                                                       params->along)
                           : whirl_perturb_links(n, turned, params->perturbation, params->seed);
    if (status) goto done;

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
    /* the shape at rest in the co-rotating frame: its positions and tensions (for the default
       step), then the perturbed start */
    if ((status = whirl_dyn_state_from_shape(dyn, t, links, m.omega, y))) goto done;
    if ((status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, ref, v_now))) goto done;
    if ((status = whirl_dyn_tensions(dyn, t, y, tension))) goto done;
    if ((status = whirl_dyn_state_from_shape(dyn, t, turned, m.omega, y))) goto done;
    if ((status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, x_now, v_now))) goto done;
    const double d0 = deviation(&m, n, x_now, ref);
    if (!(d0 > 0)) {
        status = whirl_fail(GSL_ERANGE, "the perturbation %g gives no deviation",
                            params->perturbation);
        goto done;
    }
    double h = params->dt;
    if (!(h > 0) && (status = whirl_default_step(&m, tension, params->method, &h))) goto done;
    const double period = 2 * M_PI / m.omega, t_end = params->periods * period;
    if (!(t_end / h <= RUN_STEPS_MAX)) {
        status = whirl_fail(GSL_EINVAL, "%g periods in steps of " WHIRL_Q_TIME "%.17g are %.3g "
                            "steps, more than %g: fewer periods or a larger step",
                            params->periods, h, t_end / h, RUN_STEPS_MAX);
        goto done;
    }
    const double limit = LINEAR_LIMIT * whirl_chain_total_length(c);
    const int dissipative = m.internal_damping > 0 || m.air_drag > 0 || m.air_drag_quadratic > 0;
    line_fit fit = {0};
    int fitting = 0, fit_done = 0;
    double period_max = 0, last_period_max = INFINITY;
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
        const double d = deviation(&m, n, x_now, ref), ratio = d / d0;
        if (!isfinite(ratio)) {
            status = whirl_fail(GSL_ERANGE, "non-finite deviation at t = " WHIRL_Q_TIME "%g", t);
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
            fit_done = ratio >= RATIO_FIT_TO || d >= limit ||
                       (ratio >= RATIO_FIT_MIN &&
                        max_turn(n, x_now, ref, m.drive_radius) >= TURN_LIMIT);
        }
        if (fit_done && result->verdict == WHIRL_VERDICT_UNSTABLE) break;
        /* converging: the largest deviation over a whole rotation period at or below
         * RATIO_CONVERGED (not a momentary dip of an oscillating deviation) */
        period_max = fmax(period_max, ratio);
        if (k % SAMPLES_PER_PERIOD == 0) {
            if (dissipative && result->verdict == WHIRL_VERDICT_STABLE &&
                period_max <= RATIO_CONVERGED) {
                result->verdict = WHIRL_VERDICT_CONVERGING;
                break;
            }
            last_period_max = period_max;
            period_max = 0;
        }
    }
    result->duration = t;
    /* a clear decay by the end of the run: the last period's largest deviation 1/10 or less */
    if (dissipative && result->verdict == WHIRL_VERDICT_STABLE &&
        last_period_max <= RATIO_DECAYED)
        result->verdict = WHIRL_VERDICT_CONVERGING;
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

int whirl_stability_run(const whirl_model *model, double tip_r,
                        const whirl_stability_run_params *params,
                        whirl_stability_run_result *result)
{
    int status = check_params(model, params);
    if (status) return status;
    if (!has_symmetry(model))
        return whirl_fail(GSL_EINVAL, "a free steady shape needs the pivot on the axis and no "
                                      "air drag (see whirl_stability_run_shape)");
    const size_t n = model->chain->n;
    double *buf = calloc(4 * (n + 1), sizeof(double));
    if (buf == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for a run of %zu links", n);
    double *r = buf, *zero = r + n + 1, *z = zero + n + 1, *tension = z + n + 1;
    status = whirl_nlink_positions(model->chain, model->omega, tip_r, r, z, tension);
    if (!status) status = whirl_stability_run_shape(model, r, zero, z, params, result);
    free(buf);
    return status;
}
