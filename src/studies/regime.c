/* The hand-swung chain from rest: ramp, settling and classification (include/whirl/regime.h).
 *
 * Equations: those of dynamics.h (the N-link chain, Cartesian formulation) with the pivot on the
 * circle of radius eps(t) at rate omega(t) and air drag on the inertial velocities; eps(t) follows
 * the smooth step eps u^2 (3 - 2 u), u = t / t_ramp (whirl_model.drive_radius_ramp), a change
 * of omega the same step over t_change (whirl_model.omega_ramp, set with whirl_dyn_set_ramps):
 * one model, one workspace and one integrator for the whole run.
 * Settling: stroboscopic samples once per drive period T = 2 pi / omega, change D_k between
 * consecutive samples (RMS over the masses), mean decay ratio q per period from block means of
 * D_k, and the geometric series estimate of the distance left, sum_{j>k} D_j <= D_k / (1 - q).
 * Largest Lyapunov exponent: G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn, Meccanica 15
 * (1980) 9-20: a twin trajectory at distance delta0, renormalised after each period,
 * lambda = sum log(delta_k / delta0) / (K T).
 * Node count: the definition of driven.h (principal direction of the horizontal displacements
 * from the pivot's vertical, weighted by arclength; sign changes along the chain), restated here
 * for a polyline because driven.c keeps its version private to its own shapes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>

#include "whirl/driven.h"
#include "whirl/regime.h"
#include "core/error.h"

#define TIP_HISTORY (WHIRL_REGIME_PERIOD_MAX + WHIRL_REGIME_PERIOD_CHECKS)
#define LYAPUNOV_DELTA0 1e-8
#define SETTLE_BLOCK WHIRL_REGIME_PERIOD_MAX /* periods averaged in the settling test */
#define DECAY_BLOCK 4   /* periods averaged in the CONVERGING test */
#define REGIME_PERIODS_MIN (2 * SETTLE_BLOCK) /* drive periods t_max - t_ramp must hold */
#define DECAY_BLOCKS 5  /* successive decreasing block means it needs */
#define DECAY_MAX_LEFT 0.05 /* [L]: the largest estimated distance left it accepts */
#define DECAY_FACTOR 0.995
#define CHANGE_HISTORY 32 /* >= 2 SETTLE_BLOCK and DECAY_BLOCK (DECAY_BLOCKS + 1) */
_Static_assert(CHANGE_HISTORY >= 2 * SETTLE_BLOCK &&
                   CHANGE_HISTORY >= DECAY_BLOCK * (DECAY_BLOCKS + 1),
               "the ring buffer of changes must hold both tests' windows");

struct whirl_regime {
    const whirl_chain *chain;
    size_t n;             /* links */
    whirl_model model;    /* the model of the run (the ramps in the workspace may differ) */
    whirl_dyn *dyn;       /* its workspace, or NULL */
    whirl_integrator *it; /* its integrator */
    whirl_integrator *twin; /* the Lyapunov twin's integrator */
    gsl_rng *rng;         /* the twin's random offset */
    double t;             /* time of the run */
    double angle;         /* angle of the co-rotating frame in the inertial frame */
    double *y, *y2;       /* state and Lyapunov twin */
    double *x, *v;        /* 3 per mass */
    double *prev;         /* 3 per mass: the previous stroboscopic sample */
    double *poly;         /* 3 per point: pivot and masses (node count) */
    double *bx, *by, *bz; /* the boundary-value shape, pivot and masses */
    double tips[TIP_HISTORY][3];
    size_t n_tips;        /* samples pushed into tips (ring buffer) */
    double changes[CHANGE_HISTORY]; /* the last D_k (ring buffer, n_tips of them pushed) */
    whirl_regime_observer observer;
    void *observer_ctx;
    double observe_every, next_observe;
};

static const char *const state_names[] = {"settled", "periodic", "quasiperiodic", "chaotic",
                                          "failed",  "converging"};

const char *whirl_regime_state_name(whirl_regime_state s)
{
    return (unsigned)s < sizeof state_names / sizeof state_names[0] ? state_names[s] : NULL;
}

whirl_regime_params whirl_regime_defaults(size_t links)
{
    whirl_regime_params p;
    memset(&p, 0, sizeof p);
    p.frame = WHIRL_FRAME_ROTATING;
    p.method = "rk4";
    p.dt = 0.1 / (double)(links > 0 ? links : 1);
    p.t_ramp = 20;
    p.t_max = 400;
    p.settle_tol = 1e-3;
    p.settle_periods = 3;
    p.periodic_tol = 1e-3;
    p.lyapunov_periods = 60;
    p.chaos_lambda = 0.05;
    p.perturb = 1e-3;
    p.seed = 1;
    return p;
}

int whirl_regime_check(const whirl_regime_params *p)
{
    if (!(p->omega > 0 && isfinite(p->omega)))
        return whirl_fail(GSL_EINVAL, "omega must be > 0, got %g", p->omega);
    if (whirl_check_omega_max(p->omega) != GSL_SUCCESS) return GSL_EINVAL;
    if (!(p->drive_radius > 0 && p->drive_radius < 1))
        return whirl_fail(GSL_EINVAL, "drive_radius must be in (0, 1), got %g", p->drive_radius);
    const struct { const char *name; double value; } nonneg[] = {
        {"air_drag", p->air_drag}, {"air_drag_quadratic", p->air_drag_quadratic},
        {"internal_damping", p->internal_damping}, {"perturb", p->perturb}};
    for (size_t k = 0; k < sizeof nonneg / sizeof nonneg[0]; k++)
        if (!(nonneg[k].value >= 0 && isfinite(nonneg[k].value)))
            return whirl_fail(GSL_EINVAL, "%s must be >= 0, got %g", nonneg[k].name,
                              nonneg[k].value);
    const struct { const char *name; double value; } pos[] = {
        {"dt", p->dt}, {"t_ramp", p->t_ramp},
        {"settle_tol", p->settle_tol}, {"periodic_tol", p->periodic_tol},
        {"chaos_lambda", p->chaos_lambda}};
    for (size_t k = 0; k < sizeof pos / sizeof pos[0]; k++)
        if (!(pos[k].value > 0 && isfinite(pos[k].value)))
            return whirl_fail(GSL_EINVAL, "%s must be > 0, got %g", pos[k].name, pos[k].value);
    if (!(p->t_max > p->t_ramp && isfinite(p->t_max)))
        return whirl_fail(GSL_EINVAL, "t_max (%g) must exceed t_ramp (%g)", p->t_max, p->t_ramp);
    if (p->settle_periods < 1 || p->lyapunov_periods < 1)
        return whirl_fail(GSL_EINVAL, "settle_periods and lyapunov_periods must be >= 1");
    /* the classification samples once per drive period: t_max - t_ramp must hold enough of
     * them (else the run would end unclassified, and the Lyapunov window of lyapunov_periods
     * periods after it could be far longer than t_max) */
    const double period = 2 * M_PI / p->omega, need = REGIME_PERIODS_MIN * period;
    if (p->t_max - p->t_ramp < need)
        return whirl_fail(GSL_EINVAL, "t_max - t_ramp = " WHIRL_Q_TIME "%g holds %.3g drive "
                          "periods (2 pi/omega = " WHIRL_Q_TIME "%g); the classification needs "
                          "%d: raise t_max to " WHIRL_Q_TIME "%.6g or omega",
                          p->t_max - p->t_ramp, (p->t_max - p->t_ramp) / period, period,
                          REGIME_PERIODS_MIN, p->t_ramp + need);
    if (p->frame != WHIRL_FRAME_INERTIAL && p->frame != WHIRL_FRAME_ROTATING)
        return whirl_fail(GSL_EINVAL, "unknown frame %d", (int)p->frame);
    if (p->method == NULL) return whirl_fail(GSL_EINVAL, "no integration method");
    return GSL_SUCCESS;
}

whirl_regime *whirl_regime_alloc(const whirl_chain *chain)
{
    if (chain == NULL || chain->n < 1) {
        whirl_fail(GSL_EINVAL, "a chain of at least one link is needed");
        return NULL;
    }
    whirl_regime *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    const size_t n = chain->n;
    w->chain = chain;
    w->n = n;
    w->y = malloc(6 * n * sizeof *w->y);
    w->y2 = malloc(6 * n * sizeof *w->y2);
    w->x = malloc(3 * n * sizeof *w->x);
    w->v = malloc(3 * n * sizeof *w->v);
    w->prev = malloc(3 * n * sizeof *w->prev);
    w->poly = malloc(3 * (n + 1) * sizeof *w->poly);
    w->bx = malloc((n + 1) * sizeof *w->bx);
    w->by = malloc((n + 1) * sizeof *w->by);
    w->bz = malloc((n + 1) * sizeof *w->bz);
    w->rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!w->y || !w->y2 || !w->x || !w->v || !w->prev || !w->poly || !w->bx || !w->by || !w->bz ||
        !w->rng)
        goto fail;
    return w;
fail:
    whirl_regime_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the regime workspace");
    return NULL;
}

static void release_model(whirl_regime *w)
{
    whirl_integrator_free(w->twin);
    whirl_integrator_free(w->it);
    whirl_dyn_free(w->dyn);
    w->twin = w->it = NULL;
    w->dyn = NULL;
}

void whirl_regime_free(whirl_regime *w)
{
    if (w == NULL) return;
    release_model(w);
    free(w->y);
    free(w->y2);
    free(w->x);
    free(w->v);
    free(w->prev);
    free(w->poly);
    free(w->bx);
    free(w->by);
    free(w->bz);
    gsl_rng_free(w->rng);
    free(w);
}

void whirl_regime_observe(whirl_regime *w, whirl_regime_observer f, void *ctx, double every)
{
    w->observer = f;
    w->observer_ctx = ctx;
    w->observe_every = f && every > 0 ? every : 0;
}

/* ---- the model of a run ---- */

/* The model of a run at omega from rest: eps ramped from 0 over [0, t_ramp]; its workspace and
 * the integrators of the run and of the Lyapunov twin (the only allocations of a run). */
static int start_model(whirl_regime *w, const whirl_regime_params *p, double omega)
{
    release_model(w);
    w->model = (whirl_model){.chain = w->chain,
                             .dim = 3,
                             .frame = p->frame,
                             .omega = omega,
                             .drive_radius = p->drive_radius,
                             .air_drag = p->air_drag,
                             .air_drag_quadratic = p->air_drag_quadratic,
                             .internal_damping = p->internal_damping,
                             .drive_radius_ramp = {0, p->drive_radius, 0, p->t_ramp}};
    w->dyn = whirl_dyn_alloc(&w->model, WHIRL_FORMULATION_CARTESIAN);
    if (w->dyn == NULL) return whirl_last_status();
    w->it = whirl_integrator_alloc(p->method, w->dyn);
    if (w->it == NULL) return whirl_last_status();
    w->twin = whirl_integrator_alloc(p->method, w->dyn);
    if (w->twin == NULL) return whirl_last_status();
    return GSL_SUCCESS;
}

/* The drive now: radius and rate. */
static double drive_radius_now(const whirl_regime *w)
{
    double eps;
    whirl_dyn_drive_at(w->dyn, w->t, &eps, NULL, NULL);
    return eps;
}

static double omega_now(const whirl_regime *w)
{
    double omega;
    whirl_dyn_drive_at(w->dyn, w->t, NULL, &omega, NULL);
    return omega;
}

/* Positions of the masses in the co-rotating frame into w->x. */
static int corotating_positions(whirl_regime *w, const double *y)
{
    return whirl_dyn_get_state(w->dyn, w->t, y, WHIRL_FRAME_ROTATING, w->x, w->v);
}

static int observe(whirl_regime *w)
{
    const double pivot[3] = {drive_radius_now(w), 0, 0};
    int status = corotating_positions(w, w->y);
    if (status) return status;
    return w->observer(w->observer_ctx, w->t, w->angle, pivot, w->x, w->n);
}

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* Integration failure: GSL_EFAILED, with the message set (a stop request is passed on). */
static int integration_failed(whirl_regime *w, int status)
{
    if (status == WHIRL_EINTERRUPTED) return status;
    if (status == GSL_SUCCESS)
        return whirl_fail(GSL_EFAILED, "the state is not finite at t = %.6g", w->t);
    whirl_error_record why;
    whirl_error_save(&why);
    return whirl_fail(GSL_EFAILED, "integration failed after t = %.6g: %s", w->t, why.text);
}

/* Advances the run (and the twin y2 if twin) by dt_total at the current drive, stopping at the
 * observer's times. Returns GSL_EFAILED on an integration failure, the observer's status if it
 * stopped the run, else GSL_SUCCESS. */
static int advance(whirl_regime *w, const whirl_regime_params *p, double dt_total,
                   whirl_integrator *twin)
{
    const double t_end = w->t + dt_total;
    while (w->t < t_end) {
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped at t = %.6g of the run", w->t);
        double t1 = t_end;
        if (w->observe_every > 0 && w->next_observe < t1) t1 = w->next_observe;
        const double t0 = w->t;
        int status = whirl_integrator_advance(w->it, &w->t, w->y, t1, p->dt, 0);
        if (status == WHIRL_EINTERRUPTED) return status;
        if (status || !all_finite(w->y, 6 * w->n)) return integration_failed(w, status);
        if (twin) {
            double t2 = t0;
            status = whirl_integrator_advance(twin, &t2, w->y2, t1, p->dt, 0);
            if (status == WHIRL_EINTERRUPTED) return status;
            if (status || !all_finite(w->y2, 6 * w->n)) return integration_failed(w, status);
        }
        whirl_dyn_drive_at(w->dyn, w->t, NULL, NULL, &w->angle);
        if (w->observe_every > 0 && w->t >= w->next_observe) {
            status = observe(w);
            if (status) return status;
            w->next_observe += w->observe_every;
        }
    }
    return GSL_SUCCESS;
}

/* The hanging chain at rest in the inertial frame, each link turned by p->perturb
 * (whirl_perturb_links); the pivot at its place at time w->t, moving with the hand. */
static int start_from_rest(whirl_regime *w, const whirl_regime_params *p)
{
    for (size_t i = 0; i < w->n; i++) {
        w->x[3 * i] = w->x[3 * i + 1] = 0;
        w->x[3 * i + 2] = -w->chain->length[i];
    }
    int status = whirl_perturb_links(w->n, w->x, p->perturb, p->seed);
    if (status) return status;
    return whirl_dyn_state_from_shape(w->dyn, w->t, w->x, 0, w->y);
}

/* RMS over the masses of |a_i - b_i| (3 per mass). */
static double rms_distance(size_t n, const double *a, const double *b)
{
    double sum = 0;
    for (size_t i = 0; i < 3 * n; i++) sum += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(sum / (double)n);
}

static double state_distance(size_t size, const double *a, const double *b)
{
    double sum = 0;
    for (size_t i = 0; i < size; i++) sum += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(sum);
}

/* The node count of the shape in w->x (co-rotating) with the pivot in front. */
static int shape_nodes(whirl_regime *w)
{
    const double eps = drive_radius_now(w);
    w->poly[0] = eps;
    w->poly[1] = w->poly[2] = 0;
    memcpy(w->poly + 3, w->x, 3 * w->n * sizeof *w->x);
    return whirl_driven_nodes(eps, w->n + 1, w->poly, w->chain->length);
}

/* The settled shape in w->x against the boundary-value shape with drag found from its tip. */
static void compare_with_steady(whirl_regime *w, const whirl_regime_params *p,
                                whirl_regime_result *res)
{
    whirl_driven_params dp;
    whirl_driven_params_from_model(&dp, &w->model);
    dp.omega = omega_now(w);
    dp.drive_radius = drive_radius_now(w);
    whirl_driven_info info;
    res->shape_error = NAN;
    res->bvp_nodes = 0;
    if (whirl_driven_solve(w->chain, &dp, res->tip, &info) != GSL_SUCCESS) return;
    if (whirl_driven_sample(w->chain, &dp, info.tip, w->n + 1, NULL, w->bx, w->by, w->bz, NULL) !=
        GSL_SUCCESS)
        return;
    double sum = 0;
    for (size_t i = 0; i < w->n; i++) {
        const double *x = w->x + 3 * i;
        const double dx = x[0] - w->bx[i + 1], dy = x[1] - w->by[i + 1], dz = x[2] - w->bz[i + 1];
        sum += dx * dx + dy * dy + dz * dz;
    }
    res->shape_error = sqrt(sum / (double)w->n);
    res->bvp_nodes = info.nodes;
}

/* The smallest p in 2..PERIOD_MAX with which the last PERIOD_CHECKS tips repeat, or 0. */
static int tip_period(const whirl_regime *w, double tol)
{
    for (int period = 2; period <= WHIRL_REGIME_PERIOD_MAX; period++) {
        if (w->n_tips < (size_t)(period + WHIRL_REGIME_PERIOD_CHECKS)) return 0;
        int repeats = 1;
        for (int j = 0; j < WHIRL_REGIME_PERIOD_CHECKS && repeats; j++) {
            const double *a = w->tips[(w->n_tips - 1 - (size_t)j) % TIP_HISTORY];
            const double *b = w->tips[(w->n_tips - 1 - (size_t)(j + period)) % TIP_HISTORY];
            repeats = hypot(hypot(a[0] - b[0], a[1] - b[1]), a[2] - b[2]) < tol;
        }
        if (repeats) return period;
    }
    return 0;
}

/* 1 if each of the last DECAY_BLOCKS means of DECAY_BLOCK changes is DECAY_FACTOR below the
 * mean before it and the geometric estimate of the distance left, from the mean rate of decay
 * q over those periods, D_k / (1 - q), is below DECAY_MAX_LEFT. */
static int decaying(const whirl_regime *w)
{
    const size_t span = DECAY_BLOCK * (DECAY_BLOCKS + 1);
    if (w->n_tips < span) return 0;
    double mean[DECAY_BLOCKS + 1] = {0};
    for (size_t j = 0; j < span; j++) /* block 0 is the oldest */
        mean[j / DECAY_BLOCK] += w->changes[(w->n_tips - span + j) % CHANGE_HISTORY];
    for (int b = 1; b <= DECAY_BLOCKS; b++)
        if (!(mean[b] < DECAY_FACTOR * mean[b - 1])) return 0;
    const double q = pow(mean[DECAY_BLOCKS] / mean[0], 1.0 / (DECAY_BLOCK * DECAY_BLOCKS));
    const double last = w->changes[(w->n_tips - 1) % CHANGE_HISTORY];
    return last / (1 - q) < DECAY_MAX_LEFT;
}

/* Largest Lyapunov exponent over lyapunov_periods periods (the run goes on meanwhile). */
static int lyapunov(whirl_regime *w, const whirl_regime_params *p, double period, double *lambda)
{
    const size_t size = 6 * w->n;
    whirl_integrator *twin = w->twin;
    gsl_rng *rng = w->rng;
    int status = GSL_SUCCESS;
    double sum = 0, d0 = 0;
    {
        gsl_rng_set(rng, p->seed + 1);
        for (size_t i = 0; i < size; i++) w->y2[i] = w->y[i] + (gsl_rng_uniform(rng) - 0.5);
        const double d = state_distance(size, w->y, w->y2);
        for (size_t i = 0; i < size; i++)
            w->y2[i] = w->y[i] + (w->y2[i] - w->y[i]) * LYAPUNOV_DELTA0 / d;
        status = whirl_dyn_project(w->dyn, w->t, w->y2);
        d0 = state_distance(size, w->y, w->y2);
    }
    for (int k = 0; k < p->lyapunov_periods && status == GSL_SUCCESS; k++) {
        status = advance(w, p, period, twin);
        if (status) break;
        const double d = state_distance(size, w->y, w->y2);
        sum += log(d / d0);
        for (size_t i = 0; i < size; i++)
            w->y2[i] = w->y[i] + (w->y2[i] - w->y[i]) * LYAPUNOV_DELTA0 / d;
        status = whirl_dyn_project(w->dyn, w->t, w->y2);
        d0 = state_distance(size, w->y, w->y2);
    }
    *lambda = sum / (p->lyapunov_periods * period);
    return status;
}

/* The distance left to the fixed point, estimated from the last 2 SETTLE_BLOCK changes: the mean
 * decay ratio per period q = (m1 / m0)^(1 / SETTLE_BLOCK) of the block means m0, m1 (oldest
 * first), then max(D_k, m1) / (1 - q); 0 if the shape does not move, infinite if q >= 1. */
static double distance_left(const whirl_regime *w)
{
    if (w->n_tips < 2 * SETTLE_BLOCK) return INFINITY;
    double m[2] = {0, 0};
    for (size_t j = 0; j < 2 * SETTLE_BLOCK; j++)
        m[j / SETTLE_BLOCK] += w->changes[(w->n_tips - 2 * SETTLE_BLOCK + j) % CHANGE_HISTORY];
    const double last = w->changes[(w->n_tips - 1) % CHANGE_HISTORY];
    if (m[1] == 0) return 0;
    const double q = pow(m[1] / m[0], 1.0 / SETTLE_BLOCK);
    return q < 1 ? fmax(last, m[1] / SETTLE_BLOCK) / (1 - q) : INFINITY;
}

/* Runs at the current drive for at most duration, sampling once per period, and classifies. */
static int settle(whirl_regime *w, const whirl_regime_params *p, double duration,
                  whirl_regime_result *res)
{
    const double period = 2 * M_PI / omega_now(w), t_stop = w->t + duration;
    int status = corotating_positions(w, w->y), good = 0;
    if (status) return status;
    memcpy(w->prev, w->x, 3 * w->n * sizeof *w->x);
    w->n_tips = 0;
    res->change = res->remaining = INFINITY;
    while (w->t + period <= t_stop * (1 + 1e-12)) {
        status = advance(w, p, period, NULL);
        if (status == GSL_SUCCESS) status = corotating_positions(w, w->y);
        if (status) return status;
        const double change = rms_distance(w->n, w->x, w->prev);
        memcpy(w->prev, w->x, 3 * w->n * sizeof *w->x);
        w->changes[w->n_tips % CHANGE_HISTORY] = change;
        memcpy(w->tips[w->n_tips++ % TIP_HISTORY], w->x + 3 * (w->n - 1), 3 * sizeof *w->x);
        res->change = change;
        res->remaining = distance_left(w);
        good = res->remaining < p->settle_tol ? good + 1 : 0;
        if (good >= p->settle_periods) break;
    }
    memcpy(res->tip, w->x + 3 * (w->n - 1), sizeof res->tip);
    res->tip_r = hypot(res->tip[0], res->tip[1]);
    res->nodes = shape_nodes(w);
    res->lyapunov = NAN;
    res->shape_error = NAN;
    res->bvp_nodes = 0;
    res->period = 0;
    if (good >= p->settle_periods) {
        res->state = WHIRL_REGIME_SETTLED;
        res->period = 1;
        compare_with_steady(w, p, res);
    } else if (res->remaining < DECAY_MAX_LEFT || decaying(w)) {
        res->state = WHIRL_REGIME_CONVERGING;
    } else if ((res->period = tip_period(w, p->periodic_tol)) > 0) {
        res->state = WHIRL_REGIME_PERIODIC;
    } else {
        status = lyapunov(w, p, period, &res->lyapunov);
        if (status) return status;
        res->state = res->lyapunov > p->chaos_lambda ? WHIRL_REGIME_CHAOTIC
                                                     : WHIRL_REGIME_QUASIPERIODIC;
    }
    res->t_end = w->t;
    return GSL_SUCCESS;
}

static void result_failed(whirl_regime_result *res, const whirl_regime *w)
{
    memset(res, 0, sizeof *res);
    res->state = WHIRL_REGIME_FAILED;
    res->t_end = w->t;
    res->change = res->remaining = res->shape_error = res->lyapunov = NAN;
    for (int k = 0; k < 3; k++) res->tip[k] = NAN;
    res->tip_r = NAN;
}

/* Steps of the run's integrators so far. */
static unsigned long run_steps(const whirl_regime *w)
{
    return (w->it ? whirl_integrator_get_stats(w->it).steps : 0) +
           (w->twin ? whirl_integrator_get_stats(w->twin).steps : 0);
}

/* Ends a run or a sweep point: a failed integration is a result, other statuses are returned. */
static int finish(whirl_regime *w, int status, whirl_regime_result *res)
{
    if (status == GSL_EFAILED) {
        whirl_error_record why;
        whirl_error_save(&why);
        result_failed(res, w);
        res->steps = run_steps(w);
        whirl_error_restore(&why);
        return GSL_SUCCESS;
    }
    res->steps = run_steps(w);
    return status;
}

/* From rest through the ramp of eps at omega, then settle (the first point of either entry). */
static int from_rest(whirl_regime *w, const whirl_regime_params *p, double omega,
                     whirl_regime_result *res)
{
    w->t = w->angle = 0;
    w->next_observe = 0;
    int status = start_model(w, p, omega);
    if (status == GSL_SUCCESS) status = start_from_rest(w, p);
    if (status) return status;
    if (w->observer) {
        status = observe(w);
        w->next_observe = w->observe_every;
        if (status) return status;
    }
    status = advance(w, p, p->t_ramp, NULL);
    if (status == GSL_SUCCESS) status = settle(w, p, p->t_max - p->t_ramp, res);
    return status;
}

int whirl_regime_run(whirl_regime *w, const whirl_regime_params *p, whirl_regime_result *res)
{
    int status = whirl_regime_check(p);
    if (status) return status;
    status = from_rest(w, p, p->omega, res);
    return finish(w, status, res);
}

int whirl_regime_sweep(whirl_regime *w, const whirl_regime_params *p, const double *omega,
                       size_t n, double t_change, whirl_regime_result *res, size_t *n_done)
{
    size_t done_here = 0;
    if (n_done == NULL) n_done = &done_here;
    *n_done = 0;
    if (p->frame != WHIRL_FRAME_ROTATING)
        return whirl_fail(GSL_EINVAL, "a sweep of omega needs the rotating frame");
    if (n < 1) return whirl_fail(GSL_EINVAL, "a sweep needs at least one rate");
    if (!(t_change > 0 && isfinite(t_change)))
        return whirl_fail(GSL_EINVAL, "t_change must be > 0, got %g", t_change);
    whirl_regime_params q = *p;
    for (size_t j = 0; j < n; j++) {
        q.omega = omega[j];
        int status = whirl_regime_check(&q);
        if (status) return status;
    }
    int status = from_rest(w, p, omega[0], &res[0]);
    status = finish(w, status, &res[0]);
    if (status) return status;
    *n_done = 1;
    for (size_t j = 1; j < n; j++) {
        if (res[j - 1].state == WHIRL_REGIME_FAILED) {
            result_failed(&res[j], w);
            *n_done = j + 1;
            continue;
        }
        const whirl_ramp change = {omega[j - 1], omega[j], w->t, w->t + t_change};
        status = whirl_dyn_set_ramps(w->dyn, w->t, NULL, &change);
        if (status == GSL_SUCCESS) status = advance(w, p, t_change, NULL);
        if (status == GSL_SUCCESS) status = settle(w, p, p->t_max - p->t_ramp, &res[j]);
        status = finish(w, status, &res[j]);
        if (status) return status;
        *n_done = j + 1;
    }
    return GSL_SUCCESS;
}
