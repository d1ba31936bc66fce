/* Runs of the internally damped chain towards its mode-1 shape, shared by tests/unit/dynamics/test_damping.c and
 * tests/bench/bench_damping.c (header-only, static inline functions).
 *
 * Model: whirl_model with dim = 3, the frame co-rotating at omega, internal damping D > 0
 * (Rayleigh function R = D/2 sum_i |w_i - w_{i-1}|^2, w_i the rate of the link direction u_i
 * relative to the frame co-rotating at omega; see whirl/dynamics.h). By Kelvin-Tait-Chetaev only
 * mode 1 is an attractor (the manual's theory, "Linearisation and Krein signatures"); near it
 * the deviation decays like
 * exp(sigma t), sigma < 0 the largest real part of the damped linearisation's eigenvalues
 * (whirl_stability_growth, the symmetry's zero removed).
 *
 * Starts (positions x and velocities v of the masses, 3 per mass, co-rotating frame):
 *  - damping_start_turned: the steady shape with nodes r, z (pivot first, as from
 *    whirl_nlink_positions), every link direction u_j turned by the angle eps towards a random
 *    unit vector t_j perpendicular to it (the library's rule, whirl_perturb_links), at rest in
 *    the co-rotating frame;
 *  - damping_start_hanging: the chain hanging straight down with every link turned the same way
 *    by eps (the exactly hanging chain is an equilibrium and would never leave), at rest in the
 *    inertial frame: v_i = -omega z x x_i in the co-rotating frame.
 * Deviation: whirl_deviation from the mode-1 shape (RMS distance of the masses, minimised over a
 * rotation about z). Decay rate: least-squares slope of log(deviation) against t over the
 * exponential stretch, the samples after the last one at or above d_hi (the linear regime: the
 * nonlinear terms are of relative size d / L) up to the first sample that ends a block (of the
 * length below) of RMS below d_lo (above the round-off floor; a single sample can dip far below
 * the trend), cut into blocks of whole periods 2 pi / Im(lambda) of the slowest
 * eigenvalue lambda: a complex mode makes the squared deviation oscillate at 2 Im(lambda) about
 * its exponential trend, so the fit takes the block means of d^2, log(d) = log(mean d^2) / 2.
 * Two modes of close rates (the slowest, oscillating, and a real one at omega = 2) make the
 * single slope an average of the two; the two-rate fit separates them: the block means
 * m_i ~ a e^{2 s1 t_i} + c e^{2 s2 t_i} (the cross terms oscillate and average out), a and c by
 * linear least squares in the relative error for given rates, the rates s1, s2 by Nelder-Mead.
 * Final shape error: the largest deviation over the last quarter of a tail run on after the
 * deviation first fell below d_lo, of length ln(tail_factor) / |sigma| (the deviation would fall
 * by tail_factor more if it were not at its floor). */
#ifndef WHIRL_DAMPING_RUN_H
#define WHIRL_DAMPING_RUN_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "whirl/stability.h"

/* The library's default fixed step (whirl_default_step) for the tensions T_j of links j = 1..N
 * given as tension[1..N] (as from whirl_nlink_positions); NAN if it fails. */
static inline double damping_step(const whirl_model *m, const double *tension, const char *method)
{
    double h;
    return whirl_default_step(m, tension + 1, method, &h) == GSL_SUCCESS ? h : NAN;
}

/* x_i = sum of the link vectors 1..i (3 per link), in place: positions from a pivot at 0. */
static inline void damping_accumulate(size_t n, double *x)
{
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) x[3 * i + k] += x[3 * (i - 1) + k];
}

/* The turned steady shape (nodes r, z; pivot first) at rest in the co-rotating frame: the links
 * turned by eps (whirl_perturb_links). */
static inline int damping_start_turned(const whirl_chain *c, const double *r, const double *z,
                                       double eps, unsigned long seed, double *x, double *v)
{
    int status = whirl_shape_links(c->n, r, NULL, z, x);
    if (status == GSL_SUCCESS) status = whirl_perturb_links(c->n, x, eps, seed);
    if (status != GSL_SUCCESS) return status;
    damping_accumulate(c->n, x);
    memset(v, 0, 3 * c->n * sizeof *v);
    return GSL_SUCCESS;
}

/* The turned hanging chain at rest in the inertial frame, seen from the frame co-rotating at
 * omega. */
static inline int damping_start_hanging(const whirl_chain *c, double omega, double eps,
                                        unsigned long seed, double *x, double *v)
{
    for (size_t j = 0; j < c->n; j++) {
        x[3 * j] = x[3 * j + 1] = 0;
        x[3 * j + 2] = -c->length[j];
    }
    const int status = whirl_perturb_links(c->n, x, eps, seed);
    if (status != GSL_SUCCESS) return status;
    damping_accumulate(c->n, x);
    for (size_t i = 0; i < c->n; i++) { /* v = -omega z x x */
        v[3 * i] = omega * x[3 * i + 1];
        v[3 * i + 1] = -omega * x[3 * i];
        v[3 * i + 2] = 0;
    }
    return GSL_SUCCESS;
}

/* The block means (t_i, m_i = mean d^2) of the fitted stretch, for the two-rate fit. */
typedef struct damping_blocks {
    size_t n;
    const double *t, *m;
} damping_blocks;

/* Residual of the two-rate model m ~ a e^{2 s1 (t - t_0)} + c e^{2 s2 (t - t_0)} with the best
 * a, c (linear least squares in the relative error (model - m) / m), for gsl_multimin. */
static inline double damping_two_rate_residual(const gsl_vector *s, void *data)
{
    const damping_blocks *b = data;
    const double s1 = gsl_vector_get(s, 0), s2 = gsl_vector_get(s, 1);
    double a11 = 0, a12 = 0, a22 = 0, r1 = 0, r2 = 0;
    for (size_t i = 0; i < b->n; i++) {
        const double e1 = exp(2 * s1 * (b->t[i] - b->t[0])) / b->m[i];
        const double e2 = exp(2 * s2 * (b->t[i] - b->t[0])) / b->m[i];
        a11 += e1 * e1, a12 += e1 * e2, a22 += e2 * e2, r1 += e1, r2 += e2;
    }
    const double det = a11 * a22 - a12 * a12;
    if (!(fabs(det) > 1e-14 * a11 * a22)) return GSL_POSINF;
    const double a = (a22 * r1 - a12 * r2) / det, c = (a11 * r2 - a12 * r1) / det;
    double sum = 0;
    for (size_t i = 0; i < b->n; i++) {
        const double e1 = exp(2 * s1 * (b->t[i] - b->t[0])) / b->m[i];
        const double e2 = exp(2 * s2 * (b->t[i] - b->t[0])) / b->m[i];
        sum += (a * e1 + c * e2 - 1) * (a * e1 + c * e2 - 1);
    }
    return sum;
}

/* The two rates (slow >= fast) minimising the residual above, from the guesses s1, s2
 * (Nelder-Mead, at most 2000 iterations); NAN if the minimiser cannot be set up. */
static inline void damping_two_rate_fit(const damping_blocks *b, double s1, double s2,
                                        double *slow, double *fast)
{
    *slow = *fast = NAN;
    gsl_multimin_fminimizer *mm =
        gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 2);
    gsl_vector *x = gsl_vector_alloc(2), *step = gsl_vector_alloc(2);
    gsl_multimin_function f = {damping_two_rate_residual, 2, (void *)b};
    if (mm && x && step) {
        gsl_vector_set(x, 0, s1);
        gsl_vector_set(x, 1, s2);
        gsl_vector_set_all(step, 0.1 * fabs(s1));
        gsl_multimin_fminimizer_set(mm, &f, x, step);
        for (int k = 0; k < 2000; k++)
            if (gsl_multimin_fminimizer_iterate(mm) ||
                gsl_multimin_test_size(gsl_multimin_fminimizer_size(mm), 1e-9 * fabs(s1)) !=
                    GSL_CONTINUE)
                break;
        const double r1 = gsl_vector_get(mm->x, 0), r2 = gsl_vector_get(mm->x, 1);
        *slow = fmax(r1, r2);
        *fast = fmin(r1, r2);
    }
    gsl_vector_free(step);
    gsl_vector_free(x);
    gsl_multimin_fminimizer_free(mm);
}

typedef struct damping_run_params {
    const char *method; /* integrator */
    double dt;          /* fixed step [T] */
    double sample;      /* interval of the deviation samples [T] */
    double t_max;       /* the run stops here at the latest [T] */
    double d_hi, d_lo;  /* the fitted stretch: deviations in [d_lo, d_hi) [L] */
    size_t block;       /* samples per block of the fit (>= 1; see above) */
    double sigma;       /* the predicted decay rate (< 0), for the length of the tail */
    double tail_factor; /* > 1: the tail after d_lo (see above); 0: stop at d_lo */
} damping_run_params;

typedef struct damping_run_result {
    double initial;          /* deviation at t = 0 [L] */
    double peak;             /* largest deviation [L] */
    double rate;             /* fitted slope of log(deviation) [1/T] (0 if no stretch) */
    double rate_slow, rate_fast; /* the two-rate fit (see above) [1/T] (NAN if none) */
    double fit_from, fit_to; /* the fitted stretch: times of its first and last block [T] */
    size_t fit_samples;      /* blocks in it */
    double final_error;      /* the floor (see above), or the deviation at the end [L] */
    double duration;         /* time integrated [T] */
    int reached;             /* 1 if the deviation fell below d_lo (block RMS) */
    whirl_integrator_stats stats;
} damping_run_result;

/* Root mean square of d[0..n-1]. */
static inline double block_rms(const double *d, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++) sum += d[i] * d[i];
    return sqrt(sum / (double)n);
}

/* Integrates the model (co-rotating frame, Cartesian formulation) from (x0, v0) and measures
 * the deviation from ref (3 per mass). Returns the status of the library (message in
 * whirl_last_error()) or GSL_ENOMEM. */
static inline int damping_run(const whirl_model *model, const double *ref, const double *x0,
                              const double *v0, const damping_run_params *p,
                              damping_run_result *res)
{
    const size_t n = model->chain->n;
    const size_t cap = (size_t)ceil(p->t_max / p->sample) + 2;
    whirl_model m = *model;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    memset(res, 0, sizeof *res);
    res->rate_slow = res->rate_fast = NAN;
    int status = GSL_ENOMEM;
    whirl_dyn *dyn = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    whirl_integrator *it = dyn ? whirl_integrator_alloc(p->method, dyn) : NULL;
    double *y = dyn ? malloc(whirl_dyn_size(dyn) * sizeof *y) : NULL;
    double *x = malloc(6 * n * sizeof *x), *v = x ? x + 3 * n : NULL;
    double *ts = malloc(cap * sizeof *ts), *ds = malloc(cap * sizeof *ds);
    if (dyn == NULL || it == NULL) status = GSL_EINVAL;
    if (!dyn || !it || !y || !x || !ts || !ds) goto done;
    double t = 0;
    if ((status = whirl_dyn_set_state(dyn, t, x0, v0, y))) goto done;
    if ((status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, x, v))) goto done;
    const size_t block = p->block > 0 ? p->block : 1;
    size_t count = 0, first_low = 0;
    double t_stop = p->t_max;
    ts[count] = t;
    ds[count++] = res->initial = res->peak = whirl_deviation(n, x, ref);
    for (size_t k = 1; count < cap && t < t_stop; k++) {
        const double t1 = fmin((double)k * p->sample, t_stop);
        if ((status = whirl_integrator_advance(it, &t, y, t1, p->dt, 0))) goto done;
        if ((status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, x, v))) goto done;
        const double d = whirl_deviation(n, x, ref);
        if (!isfinite(d)) {
            status = GSL_ERANGE;
            goto done;
        }
        ts[count] = t;
        ds[count++] = d;
        res->peak = fmax(res->peak, d);
        if (!res->reached && count >= block && block_rms(ds + count - block, block) < p->d_lo) {
            res->reached = 1;
            first_low = count - 1;
            t_stop = p->tail_factor > 1 ? fmin(p->t_max, t + log(p->tail_factor) / fabs(p->sigma))
                                        : t;
        }
    }
    res->duration = t;
    res->stats = whirl_integrator_get_stats(it);
    res->final_error = ds[count - 1];
    if (!res->reached) goto done;
    if (p->tail_factor > 1) { /* the floor: largest deviation over the tail's last quarter */
        const double from = ts[first_low] + 0.75 * (t - ts[first_low]);
        res->final_error = 0;
        for (size_t i = first_low; i < count; i++)
            if (ts[i] >= from) res->final_error = fmax(res->final_error, ds[i]);
    }
    size_t start = 0; /* after the last sample at or above d_hi before the first below d_lo */
    for (size_t i = 0; i < first_low; i++)
        if (ds[i] >= p->d_hi) start = i + 1;
    size_t nb = 0; /* block means, stored over the samples (i advances by block >= 1) */
    double sn = 0, st = 0, sy = 0, stt = 0, sty = 0;
    for (size_t i = start; i + block <= first_low + 1; i += block, nb++) {
        double mean_t = 0, mean_d2 = 0;
        for (size_t j = i; j < i + block; j++) {
            mean_t += ts[j] / (double)block;
            mean_d2 += ds[j] * ds[j] / (double)block;
        }
        ts[nb] = mean_t;
        ds[nb] = mean_d2;
        const double ly = 0.5 * log(mean_d2);
        sn += 1, st += mean_t, sy += ly, stt += mean_t * mean_t, sty += mean_t * ly;
    }
    const double den = sn * stt - st * st;
    if (sn >= 2 && den > 0) {
        res->fit_from = ts[0];
        res->fit_to = ts[nb - 1];
        res->rate = (sn * sty - st * sy) / den;
        res->fit_samples = nb;
        const damping_blocks b = {nb, ts, ds};
        damping_two_rate_fit(&b, res->rate, 2 * res->rate, &res->rate_slow, &res->rate_fast);
    }
done:
    free(ts);
    free(ds);
    free(x);
    free(y);
    whirl_integrator_free(it);
    whirl_dyn_free(dyn);
    return status;
}

#endif
