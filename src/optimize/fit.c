/* The rotation rate (and mode) that best explains a measured steady shape.
 *
 * Data: n points (r_i, z_i) in units of the chain length, the pivot at the origin, in any order
 * along the chain. Model: the curve C(omega, k) of mode k at omega (whirl_continuum_sample
 * finely sampled, or the nodes of the uniform N-link chain from whirl_nlink_solve_nodes), a
 * polyline, mirrored (r -> -r) when the points lie on the other side of the axis.
 * Residual e_i = signed distance of point i to the polyline (sign of the cross product of the
 * nearest segment with the offset of the point); the fit minimises S(omega) = sum_i e_i^2 over
 * omega in (omega_k, omega_max]. Along a steady shape z decreases strictly from the pivot to
 * the free end (the tension's vertical component g (mu s + m_tip) never vanishes), so the nearest
 * segment is searched outwards from the one at the point's height, stopping once the height
 * gap alone exceeds the best distance.
 * Per mode: a scan on a grid of u = log(omega/omega_k - 1), NLopt's LN_BOBYQA (Powell 2009,
 * "The BOBYQA algorithm for bound constrained optimization without derivatives") on u between
 * the neighbours of the best grid point, then Gauss-Newton steps omega -= J.e / J.J with
 * J = de/domega by central differences.
 * Uncertainty: the linearised standard error of a one-parameter least-squares fit,
 *     omega_err = sqrt( s^2 / (J.J) ),   s^2 = S / (n - 1)
 * (e.g. Bates & Watts 1988, "Nonlinear Regression Analysis", ch. 2): independent errors of
 * equal variance; isotropic measurement noise of standard deviation sigma per coordinate gives
 * normal distances of standard deviation sigma, so s estimates sigma. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <nlopt.h>

#include "whirl/optimize.h"
#include "core/error.h"
#include "core/input.h"

#define FIT_MIN_POINTS 3
#define FIT_SCAN_POINTS 24
#define FIT_U_MIN (-14.0)        /* log(omega/omega_k - 1) of the lowest rate tried */
#define FIT_NEWTON_STEPS 12
#define FIT_DIFF_STEP 1e-6       /* relative step of the central differences in omega */
#define FIT_CROSSING_LEVEL 0.05  /* |r| below this fraction of max |r| is not a side */
#define FIT_MAX_POINTS 20000    /* more points are refused: every model evaluation measures the
                                    distance of each point, ~50 evaluations per mode */
#define FIT_AXIS_R 1e-9          /* |r| up to this [L] is a point on the axis (no information) */

whirl_fit_model whirl_fit_model_defaults(void)
{
    whirl_fit_model m = {0, 0.0, 50.0, 4001};
    return m;
}

/* The state of one fit: the model, its polyline and the data. */
typedef struct fit_ws {
    const whirl_fit_model *model;
    whirl_chain *chain;  /* the N-link model (links > 0), else NULL */
    size_t npoly;        /* vertices of the model polyline */
    double *pr, *pz;     /* the polyline, pivot first */
    double *tension, *s; /* scratch of the samplers */
    double *omega_crit;  /* the N-link critical rates, links values */
    size_t n;            /* data points */
    const double *r, *z;
    double *e, *e_plus, *e_minus; /* residuals, and at omega +- h */
    double tip_r_guess;  /* continuation along the current mode's branch */
    int evaluations, failures;
    whirl_fit_progress_fn progress; /* NULL: none */
    void *progress_data;
    int mode, first, last; /* the mode being fitted, of first..last */
} fit_ws;

static void fit_ws_free(fit_ws *w)
{
    whirl_chain_free(w->chain);
    free(w->pr);
    free(w->omega_crit);
    free(w->e);
}

static int fit_ws_init(fit_ws *w, const whirl_fit_model *m, size_t n, const double *r,
                       const double *z)
{
    memset(w, 0, sizeof *w);
    w->model = m;
    w->n = n;
    w->r = r;
    w->z = z;
    if (m->links > 0) {
        w->chain = whirl_chain_alloc_uniform(m->links, m->tip_mass);
        if (w->chain == NULL) return GSL_EINVAL;
        w->npoly = m->links + 1;
        w->omega_crit = malloc(m->links * sizeof *w->omega_crit);
    } else {
        w->npoly = m->samples;
    }
    w->pr = malloc(4 * w->npoly * sizeof *w->pr);
    w->e = malloc(3 * n * sizeof *w->e);
    if (w->pr == NULL || w->e == NULL || (m->links > 0 && w->omega_crit == NULL)) {
        fit_ws_free(w);
        return whirl_fail(GSL_ENOMEM, "out of memory for a fit of %zu points", n);
    }
    w->pz = w->pr + w->npoly;
    w->tension = w->pz + w->npoly;
    w->s = w->tension + w->npoly;
    w->e_plus = w->e + n;
    w->e_minus = w->e_plus + n;
    if (m->links > 0) {
        int status = whirl_nlink_critical(w->chain, m->links, w->omega_crit);
        if (status) {
            fit_ws_free(w);
            return status;
        }
    }
    return GSL_SUCCESS;
}

/* The linear critical rate of mode k of the model; GSL_EDOM if the model has no such mode. */
static int fit_critical(const fit_ws *w, int mode, double *omega)
{
    if (w->chain == NULL) return whirl_continuum_critical(mode, w->model->tip_mass, omega);
    if ((size_t)mode > w->model->links)
        return whirl_fail(GSL_EDOM, "a chain of %zu links has no mode %d", w->model->links, mode);
    *omega = w->omega_crit[mode - 1];
    return GSL_SUCCESS;
}

/* The model polyline of mode k at omega into w->pr, w->pz. */
static int fit_model_curve(fit_ws *w, double omega, int mode)
{
    whirl_shape_info info;
    int status;
    w->evaluations++;
    if (w->progress) w->progress(w->progress_data, w->mode, w->first, w->last, w->evaluations);
    if (w->chain == NULL) {
        status = whirl_continuum_solve(omega, mode, w->model->tip_mass, w->tip_r_guess, &info);
        if (status == GSL_SUCCESS)
            status = whirl_continuum_sample(omega, w->model->tip_mass, info.tip_r, w->npoly,
                                            w->s, w->pr, w->pz, w->tension);
    } else {
        status = whirl_nlink_solve_nodes(w->chain, omega, mode, &info, w->pr, w->pz,
                                         w->tension);
    }
    if (status == GSL_SUCCESS) w->tip_r_guess = info.tip_r;
    else if (status != GSL_EDOM) w->failures++;
    return status;
}

/* Signed distance of (qr, qz) to segment j of the polyline: > 0 on the left of its direction. */
static double segment_distance(const fit_ws *w, size_t j, double qr, double qz)
{
    const double ar = w->pr[j], az = w->pz[j];
    const double dr = w->pr[j + 1] - ar, dz = w->pz[j + 1] - az;
    const double len2 = dr * dr + dz * dz;
    double t = len2 > 0 ? ((qr - ar) * dr + (qz - az) * dz) / len2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    const double er = qr - (ar + t * dr), ez = qz - (az + t * dz);
    const double d = sqrt(er * er + ez * ez);
    return (dr * (qz - az) - dz * (qr - ar)) < 0 ? -d : d;
}

static double polyline_distance(const fit_ws *w, double qr, double qz)
{
    const size_t nseg = w->npoly - 1;
    /* the segment at the point's height: pz decreases from pz[0] = 0 */
    size_t lo = 0, hi = nseg;
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        if (w->pz[mid] > qz) lo = mid;
        else hi = mid;
    }
    /* outwards while the height gap alone does not exceed the best distance */
    double best = segment_distance(w, lo, qr, qz);
    for (size_t j = lo + 1; j < nseg && qz - w->pz[j] <= fabs(best); j++) {
        const double d = segment_distance(w, j, qr, qz);
        if (fabs(d) < fabs(best)) best = d;
    }
    for (size_t j = lo; j-- > 0 && w->pz[j + 1] - qz <= fabs(best);) {
        const double d = segment_distance(w, j, qr, qz);
        if (fabs(d) < fabs(best)) best = d;
    }
    return best;
}

/* Residuals of the data against the current polyline into e; returns their sum of squares. */
static double fit_residuals_now(const fit_ws *w, int mirrored, double *e)
{
    const double side = mirrored ? -1.0 : 1.0;
    double ssr = 0;
    for (size_t i = 0; i < w->n; i++) {
        if (i % 1024 == 1023 && whirl_stop_requested()) return HUGE_VAL;
        e[i] = polyline_distance(w, side * w->r[i], w->z[i]);
        ssr += e[i] * e[i];
    }
    return ssr;
}

static int by_coordinates(const void *a, const void *b)
{
    const double *p = a, *q = b;
    if (p[0] != q[0]) return (p[0] > q[0]) - (p[0] < q[0]);
    return (p[1] > q[1]) - (p[1] < q[1]);
}

/* The data: at least FIT_MIN_POINTS, all finite, and that many distinct points off the axis. */
static int check_points(size_t n, const double *r, const double *z)
{
    if (n < FIT_MIN_POINTS)
        return whirl_fail(GSL_EINVAL, "a fit needs at least %d points, got %zu", FIT_MIN_POINTS, n);
    if (n > FIT_MAX_POINTS)
        return whirl_fail(GSL_EINVAL, "a fit takes at most %d points, got %zu: thin the data "
                          "(every %zu-th point); the cost grows with the points, and a few "
                          "thousand determine omega far below the noise of a measurement",
                          FIT_MAX_POINTS, n, (n + FIT_MAX_POINTS - 1) / FIT_MAX_POINTS);
    for (size_t i = 0; i < n; i++)
        if (!(isfinite(r[i]) && isfinite(z[i])))
            return whirl_fail(GSL_EINVAL, "point %zu is not finite (r = %g, z = %g)", i + 1, r[i],
                              z[i]);
    /* a rate is determined only by points off the axis, and only by distinct ones */
    double(*p)[2] = malloc(n * sizeof *p);
    if (p == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu points", n);
    size_t off = 0, distinct = 0;
    for (size_t i = 0; i < n; i++)
        if (fabs(r[i]) > FIT_AXIS_R) {
            p[off][0] = r[i];
            p[off++][1] = z[i];
        }
    qsort(p, off, sizeof *p, by_coordinates);
    for (size_t i = 0; i < off; i++)
        distinct += i == 0 || p[i][0] != p[i - 1][0] || p[i][1] != p[i - 1][1];
    free(p);
    if (distinct < FIT_MIN_POINTS)
        return whirl_fail(GSL_EINVAL, "a fit needs at least %d distinct points off the axis "
                          "(|r| > %g L), got %zu of %zu", FIT_MIN_POINTS, FIT_AXIS_R, distinct, n);
    return GSL_SUCCESS;
}

static int check_model(const whirl_fit_model *m)
{
    if (whirl_check_tip_mass(m->tip_mass) != GSL_SUCCESS) return GSL_EINVAL;
    if (!(isfinite(m->omega_max) && m->omega_max > 0))
        return whirl_fail(GSL_EINVAL, "omega_max must be > 0 and finite, got %g", m->omega_max);
    if (m->links == 0 && m->samples < 2)
        return whirl_fail(GSL_EINVAL, "the model curve needs at least 2 samples, got %zu",
                          m->samples);
    /* the counts that drive the work, bounded here and not only by the callers; the memory is
     * the model's arrays (about 12 doubles a link, 3 a sample) */
    char bytes[32];
    if (m->links > WHIRL_FIT_LINKS_MAX)
        return whirl_fail(GSL_EINVAL, "a fit takes at most %d links, got %zu (its model would "
                          "need about %s and every evaluation a shape of that many links)",
                          WHIRL_FIT_LINKS_MAX, m->links,
                          whirl_bytes_words(bytes, sizeof bytes, 96.0 * (double)m->links));
    if (m->links == 0 && m->samples > WHIRL_FIT_SAMPLES_MAX)
        return whirl_fail(GSL_EINVAL, "a fit takes at most %d samples of the model curve, got %zu "
                          "(about %s)", WHIRL_FIT_SAMPLES_MAX, m->samples,
                          whirl_bytes_words(bytes, sizeof bytes, 24.0 * (double)m->samples));
    return GSL_SUCCESS;
}

int whirl_fit_residuals(const whirl_fit_model *m, double omega, int mode, int mirrored, size_t n,
                        const double *r, const double *z, double *resid)
{
    int status = check_model(m);
    if (status == GSL_SUCCESS) status = check_points(n, r, z);
    if (status) return status;
    fit_ws w;
    status = fit_ws_init(&w, m, n, r, z);
    if (status) return status;
    status = fit_model_curve(&w, omega, mode);
    if (status == GSL_SUCCESS) fit_residuals_now(&w, mirrored, resid);
    fit_ws_free(&w);
    return status;
}

/* ---- one mode ---- */

typedef struct mode_fit {
    fit_ws *ws;
    int mode;
    double omega_crit; /* omega_k */
    int mirrored;
    nlopt_opt nl;      /* stopped when a stop is requested */
} mode_fit;

static double omega_of_u(const mode_fit *f, double u) { return f->omega_crit * (1 + exp(u)); }

/* The status of a fit stopped by request. */
static int stopped(int mode)
{
    return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request while fitting mode %d", mode);
}

/* S at omega for the fixed side; HUGE_VAL where the model has no shape (the mode does not
 * exist, or the solver failed: counted in ws->failures). */
static double mode_ssr(mode_fit *f, double omega, double *e)
{
    if (fit_model_curve(f->ws, omega, f->mode) != GSL_SUCCESS) return HUGE_VAL;
    return fit_residuals_now(f->ws, f->mirrored, e);
}

static double bobyqa_objective(unsigned nu, const double *u, double *grad, void *data)
{
    (void)nu;
    (void)grad;
    mode_fit *f = data;
    if (whirl_stop_requested()) nlopt_force_stop(f->nl);
    return mode_ssr(f, omega_of_u(f, u[0]), f->ws->e);
}

/* Gauss-Newton steps from omega; leaves the residuals at the result in ws->e and J.J. */
static int gauss_newton(mode_fit *f, double *omega, double *ssr, double *jj)
{
    fit_ws *w = f->ws;
    const size_t n = w->n;
    for (int step = 0;; step++) {
        const double h = fmin(FIT_DIFF_STEP * *omega, 0.5 * (*omega - f->omega_crit));
        const double sp = mode_ssr(f, *omega + h, w->e_plus);
        const double sm = mode_ssr(f, *omega - h, w->e_minus);
        if (!(isfinite(sp) && isfinite(sm)))
            return whirl_fail(GSL_EFAILED, "mode %d has no shape near omega = " WHIRL_Q_RATE "%g",
                              f->mode, *omega);
        double je = 0;
        *jj = 0;
        for (size_t i = 0; i < n; i++) {
            const double j = (w->e_plus[i] - w->e_minus[i]) / (2 * h);
            je += j * w->e[i];
            *jj += j * j;
        }
        if (step == FIT_NEWTON_STEPS || !(*jj > 0)) break;
        double trial = *omega - je / *jj;
        if (trial <= f->omega_crit) trial = 0.5 * (*omega + f->omega_crit);
        if (trial > w->model->omega_max) trial = w->model->omega_max;
        const double s = mode_ssr(f, trial, w->e_plus);
        if (!(s < *ssr)) break; /* no further progress: at the minimum to round-off */
        const double moved = fabs(trial - *omega);
        *omega = trial;
        *ssr = s;
        memcpy(w->e, w->e_plus, n * sizeof *w->e);
        if (moved < 1e-14 * *omega) break;
    }
    return GSL_SUCCESS;
}

/* The best omega of one mode: scan, BOBYQA, Gauss-Newton. GSL_EDOM if the mode has no shape
 * below omega_max. */
static int fit_one_mode(fit_ws *w, int mode, whirl_fit_result *res)
{
    mode_fit f = {w, mode, 0, 0, NULL};
    int status = fit_critical(w, mode, &f.omega_crit);
    if (status) return status;
    const double u_max = log(w->model->omega_max / f.omega_crit - 1);
    if (!(f.omega_crit < w->model->omega_max) || !(u_max > FIT_U_MIN))
        return whirl_fail(GSL_EDOM, "mode %d starts at omega_%d = " WHIRL_Q_RATE "%g, above the "
                          "highest rate %g", mode, mode, f.omega_crit, w->model->omega_max);

    /* scan: both sides, keeping the better */
    double u_grid[FIT_SCAN_POINTS], best_ssr = HUGE_VAL;
    int best = -1;
    w->tip_r_guess = 0;
    for (int j = 0; j < FIT_SCAN_POINTS; j++) {
        u_grid[j] = FIT_U_MIN + (u_max - FIT_U_MIN) * j / (FIT_SCAN_POINTS - 1);
        if (fit_model_curve(w, omega_of_u(&f, u_grid[j]), mode) != GSL_SUCCESS) continue;
        for (int side = 0; side < 2; side++) {
            const double s = fit_residuals_now(w, side, w->e);
            if (s < best_ssr) {
                best_ssr = s;
                best = j;
                f.mirrored = side;
            }
        }
    }
    if (whirl_stop_requested()) return stopped(mode);
    if (best < 0)
        return whirl_fail(GSL_EDOM, "mode %d has no shape between omega_%d = " WHIRL_Q_RATE "%g "
                          "and %g", mode, mode, f.omega_crit, w->model->omega_max);

    /* BOBYQA on the bracket of the best grid point */
    double lower = u_grid[best > 0 ? best - 1 : 0];
    double upper = u_grid[best < FIT_SCAN_POINTS - 1 ? best + 1 : best];
    double u = u_grid[best], s_min = best_ssr;
    nlopt_opt nl = nlopt_create(NLOPT_LN_BOBYQA, 1);
    if (nl == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for NLopt");
    f.nl = nl;
    nlopt_set_min_objective(nl, bobyqa_objective, &f);
    nlopt_set_lower_bounds(nl, &lower);
    nlopt_set_upper_bounds(nl, &upper);
    nlopt_set_initial_step1(nl, 0.25 * (upper - lower));
    nlopt_set_xtol_abs1(nl, 1e-9);
    nlopt_set_maxeval(nl, 200);
    w->tip_r_guess = 0;
    const nlopt_result nres = nlopt_optimize(nl, &u, &s_min);
    nlopt_destroy(nl);
    if (whirl_stop_requested()) return stopped(mode);
    if (nres < 0 && nres != NLOPT_ROUNDOFF_LIMITED)
        return whirl_fail(GSL_EFAILED, "NLopt LN_BOBYQA failed on mode %d: %s", mode,
                          nlopt_result_to_string(nres));

    double omega = omega_of_u(&f, u), ssr = mode_ssr(&f, omega, w->e), jj = 0;
    if (!isfinite(ssr))
        return whirl_fail(GSL_EFAILED, "mode %d has no shape at omega = " WHIRL_Q_RATE "%g", mode,
                          omega);
    status = gauss_newton(&f, &omega, &ssr, &jj);
    if (whirl_stop_requested()) return stopped(mode);
    if (status) return status;
    res->omega = omega;
    res->omega_err = sqrt(ssr / (double)(w->n - 1) / jj);
    if (!(jj > 0 && isfinite(res->omega_err)))
        return whirl_fail(GSL_EFAILED, "mode %d: the fit is ill-conditioned: the residuals do "
                          "not change with omega near %g", mode, omega);
    res->mode = mode;
    res->rms_residual = sqrt(ssr / (double)w->n);
    res->mirrored = f.mirrored;
    return GSL_SUCCESS;
}

/* ---- all modes ---- */

typedef struct height_point {
    double z, r;
} height_point;

static int by_height_descending(const void *a, const void *b)
{
    const double za = ((const height_point *)a)->z, zb = ((const height_point *)b)->z;
    return (za < zb) - (za > zb);
}

/* Sign changes of r from the pivot down, ignoring points near the axis. */
static int count_crossings(size_t n, const double *r, const double *z, int *crossings)
{
    height_point *p = malloc(n * sizeof *p);
    if (p == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    double rmax = 0;
    for (size_t i = 0; i < n; i++) {
        p[i].z = z[i];
        p[i].r = r[i];
        if (fabs(r[i]) > rmax) rmax = fabs(r[i]);
    }
    qsort(p, n, sizeof *p, by_height_descending);
    int count = 0, side = 0;
    for (size_t i = 0; i < n; i++) {
        if (fabs(p[i].r) <= FIT_CROSSING_LEVEL * rmax) continue;
        const int s = p[i].r > 0 ? 1 : -1;
        if (side != 0 && s != side) count++;
        side = s;
    }
    free(p);
    *crossings = count;
    return GSL_SUCCESS;
}

int whirl_fit(const whirl_fit_model *m, size_t n, const double *r, const double *z, int mode,
              whirl_fit_result *result)
{
    return whirl_fit_observed(m, n, r, z, mode, NULL, NULL, result);
}

int whirl_fit_observed(const whirl_fit_model *m, size_t n, const double *r, const double *z,
                       int mode, whirl_fit_progress_fn progress, void *data,
                       whirl_fit_result *result)
{
    int status = check_model(m);
    if (status == GSL_SUCCESS) status = check_points(n, r, z);
    if (status) return status;
    if (mode < 0 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "mode must be 0 (any) or 1..%d, got %d", WHIRL_MODE_MAX, mode);
    int first = mode, last = mode;
    if (mode == 0) {
        int crossings = 0;
        status = count_crossings(n, r, z, &crossings);
        if (status) return status;
        first = 1;
        last = crossings + 3 < WHIRL_MODE_MAX ? crossings + 3 : WHIRL_MODE_MAX;
    }
    fit_ws w;
    status = fit_ws_init(&w, m, n, r, z);
    if (status) return status;
    w.progress = progress;
    w.progress_data = data;
    w.first = first;
    w.last = last;
    int found = 0;
    whirl_error_record other = {GSL_SUCCESS, ""};
    for (int k = first; k <= last; k++) {
        w.mode = k;
        whirl_fit_result res;
        const int st = fit_one_mode(&w, k, &res);
        if (st && st != WHIRL_EINTERRUPTED && mode == 0) {
            if (st != GSL_EDOM) whirl_error_keep(&other, st); /* kept in case no mode fits */
            continue; /* no shape of this mode below omega_max, or no fit of it */
        }
        if (st) {
            status = st;
            goto done;
        }
        if (!found || res.rms_residual < result->rms_residual) *result = res;
        found = 1;
    }
    if (!found && other.status != GSL_SUCCESS)
        status = whirl_error_restore(&other);
    else if (!found)
        status = whirl_fail(GSL_EDOM, "no mode from %d to %d has a shape below omega = "
                            WHIRL_Q_RATE "%g", first, last, m->omega_max);
done:
    result->evaluations = w.evaluations;
    result->failures = w.failures;
    fit_ws_free(&w);
    return status;
}
