/* The stable steady shape of the planar N-link chain as the minimum of the co-rotating potential.
 *
 * Angles theta_j of link j from the downward vertical; l_j, m_j link length and mass below it:
 *     x_i = sum_{j<=i} l_j sin(theta_j),   z_i = -sum_{j<=i} l_j cos(theta_j),
 *     V   = sum_i m_i (g z_i - omega^2 x_i^2 / 2).
 * With the suffix sums M_j = sum_{i>=j} m_i and X_j = sum_{i>=j} m_i x_i (one backward pass):
 *     dV/dtheta_j = l_j (g M_j sin(theta_j) - omega^2 X_j cos(theta_j)),
 *     d2V/dtheta_j dtheta_k = -omega^2 l_j l_k cos(theta_j) cos(theta_k) M_max(j,k)   (j != k),
 *     d2V/dtheta_j^2 = l_j (g M_j cos(theta_j) + omega^2 X_j sin(theta_j))
 *                      - omega^2 l_j^2 M_j cos^2(theta_j).
 * The force the masses below link j exert is F_j = (omega^2 X_j, -g M_j); at equilibrium it
 * points along the link, dV/dtheta_j = 0 says exactly that, and the tension is its projection
 *     T_j = g M_j cos(theta_j) + omega^2 X_j sin(theta_j)
 * (the recursion of the shooting solver, the manual's theory, "N-link statics").
 * theta = 0 (hanging) is always stationary, with Hessian K - omega^2 M (K = diag(g l_j M_j),
 * M_jk = l_j l_k M_max(j,k)): positive definite exactly when omega is below the chain's first
 * critical rate, where it is the minimum and no mode-1 shape exists. Above it the minimum is the
 * mode-1 shape; mode k has k-1 negative in-plane directions of the Hessian (Kolodner 1955 for
 * the continuum; the manual's theory, "Linearisation and Krein signatures"), so a minimiser
 * never finds modes >= 2.
 * Minimisation: NLopt (Johnson, "The NLopt nonlinear-optimization package"; LD_LBFGS by
 * default: Nocedal 1980, Liu & Nocedal 1989), then optionally Newton steps on the analytic
 * Hessian (Cholesky, LAPACK dpotrf/dpotrs) to bring the gradient to round-off. */
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>
#include <nlopt.h>

#include "whirl/optimize.h"
#include "core/error.h"
#include "core/worker.h"

#define MINIMIZE_START_TILT 0.1     /* [rad] start of the minimisation when none is given */
#define MINIMIZE_MAX_EVALUATIONS 100000
#define NEWTON_MAX_STEPS 30
#define PI 3.14159265358979323846

double whirl_potential(const whirl_chain *c, double omega, const double *theta, double *grad)
{
    const size_t n = c->n;
    const double g = c->gravity, w2 = omega * omega;
    double x = 0, z = 0, v = 0;
    for (size_t i = 0; i < n; i++) {
        x += c->length[i] * sin(theta[i]);
        z -= c->length[i] * cos(theta[i]);
        v += c->mass[i] * (g * z - 0.5 * w2 * x * x);
        if (grad) grad[i] = x; /* x_i kept for the backward pass */
    }
    if (grad) {
        double msum = 0, xsum = 0; /* M_j, X_j */
        for (size_t j = n; j-- > 0;) {
            msum += c->mass[j];
            xsum += c->mass[j] * grad[j];
            grad[j] = c->length[j] * (g * msum * sin(theta[j]) - w2 * xsum * cos(theta[j]));
        }
    }
    return v;
}

void whirl_potential_hessian(const whirl_chain *c, double omega, const double *theta,
                             double *hess)
{
    const size_t n = c->n;
    const double g = c->gravity, w2 = omega * omega;
    double x = 0;
    for (size_t i = 0; i < n; i++) { /* x_i on the diagonal for now */
        x += c->length[i] * sin(theta[i]);
        hess[i * n + i] = x;
    }
    double msum = 0, xsum = 0;
    for (size_t j = n; j-- > 0;) {
        const double lj = c->length[j], cj = cos(theta[j]);
        msum += c->mass[j];
        xsum += c->mass[j] * hess[j * n + j];
        hess[j * n + j] = lj * (g * msum * cj + w2 * xsum * sin(theta[j])) - w2 * lj * lj * msum * cj * cj;
        double mk = msum - c->mass[j]; /* M_k for k = j + 1, j + 2, ... */
        for (size_t k = j + 1; k < n; mk -= c->mass[k], k++) {
            const double h = -w2 * lj * c->length[k] * cj * cos(theta[k]) * mk;
            hess[j * n + k] = h;
            hess[k * n + j] = h;
        }
    }
}

void whirl_angles_shape(const whirl_chain *c, double omega, const double *theta, double *r,
                        double *z, double *tension, whirl_shape_info *info)
{
    const size_t n = c->n;
    const double g = c->gravity, w2 = omega * omega;
    r[0] = z[0] = 0;
    for (size_t i = 1; i <= n; i++) {
        r[i] = r[i - 1] + c->length[i - 1] * sin(theta[i - 1]);
        z[i] = z[i - 1] - c->length[i - 1] * cos(theta[i - 1]);
    }
    /* Tension of link j: T_j = g M_j cos(theta_j) + omega^2 X_j sin(theta_j), before mirroring. */
    if (tension) {
        double msum = 0, xsum = 0;
        for (size_t j = n; j >= 1; j--) {
            msum += c->mass[j - 1];
            xsum += c->mass[j - 1] * r[j];
            tension[j] = g * msum * cos(theta[j - 1]) + w2 * xsum * sin(theta[j - 1]);
        }
        tension[0] = tension[1];
    }
    if (r[n] < 0)
        for (size_t i = 1; i <= n; i++) r[i] = -r[i];
    if (info == NULL) return;
    info->omega = omega;
    info->tip_r = r[n];
    info->max_r = 0;
    info->depth = -z[n];
    info->top_tension = tension ? tension[0] : NAN;
    for (size_t i = 1; i <= n; i++) info->max_r = fmax(info->max_r, fabs(r[i]));
    /* every crossing counted, the first WHIRL_SHAPE_NODES kept */
    info->n_crossings =
        (int)whirl_nlink_node_arclengths(c, omega, r, WHIRL_SHAPE_NODES, info->crossing_s, NULL);
    info->mode = info->n_crossings + 1;
}

whirl_minimize_options whirl_minimize_options_defaults(void)
{
    whirl_minimize_options o = {.algorithm = "LD_LBFGS",
                                .max_evaluations = MINIMIZE_MAX_EVALUATIONS,
                                .polish = 1,
                                .progress = NULL,
                                .progress_data = NULL};
    return o;
}

int whirl_minimize_algorithm(const char *name, int *algorithm)
{
    nlopt_algorithm a = name ? nlopt_algorithm_from_string(name) : (nlopt_algorithm)-1;
    if ((int)a < 0 || (int)a >= NLOPT_NUM_ALGORITHMS) {
        /* the local algorithms' names (LD_*, LN_*: 22 of NLopt 2.7's 44, about 300 characters;
         * all 44 would pass the 511 of a message) */
        char known[400] = "";
        size_t used = 0;
        for (int k = 0; k < NLOPT_NUM_ALGORITHMS && used < sizeof known; k++) {
            const char *s = nlopt_algorithm_to_string((nlopt_algorithm)k);
            if (s && s[0] == 'L')
                used += (size_t)snprintf(known + used, sizeof known - used, "%s%s",
                                         used ? " " : "", s);
        }
        return whirl_fail(GSL_EINVAL, "unknown NLopt algorithm '%s' (local ones: %s; the global "
                          "GN_*, GD_* of NLopt's list too)",
                          name ? name : "(null)", known);
    }
    *algorithm = (int)a;
    return GSL_SUCCESS;
}

/* One minimisation, run on a worker thread (src/core/worker.h) so that a stop request ends the call at
 * once even while NLopt works between two evaluations (BOBYQA on 2000 angles: over a minute) or
 * LAPACK factorises the Hessian: everything it reads is its own (a copy of the chain). */
typedef struct minimize_job {
    whirl_chain *chain;  /* a copy of the caller's */
    double omega;
    int algorithm;       /* nlopt_algorithm */
    int max_evaluations, polish;
    double *theta;       /* n: the start, then the result */
    double *work;        /* 3n + n^2 */
    double *lower;       /* 2n: bounds */
    const whirl_worker *self;
    nlopt_opt nl;        /* stopped when a stop is requested or the caller left */
    atomic_int evaluations; /* read by the caller's progress display while the job runs */
    whirl_minimize_stats stats;
    whirl_error_record error; /* its status GSL_SUCCESS if it worked */
} minimize_job;

static void job_free(void *data)
{
    minimize_job *j = data;
    if (j == NULL) return;
    whirl_chain_free(j->chain);
    free(j->theta);
    free(j->work);
    free(j->lower);
    free(j);
}

/* Whether the job should end now: a stop request, or its caller has left. */
static int job_stopped(const minimize_job *j)
{
    return whirl_stop_requested() || whirl_worker_abandoned(j->self);
}

static double potential_objective(unsigned n, const double *theta, double *grad, void *data)
{
    (void)n;
    minimize_job *j = data;
    if (job_stopped(j)) nlopt_force_stop(j->nl);
    atomic_fetch_add_explicit(&j->evaluations, 1, memory_order_relaxed);
    return whirl_potential(j->chain, j->omega, theta, grad);
}

static double max_abs(size_t n, const double *v)
{
    double m = 0;
    for (size_t i = 0; i < n; i++)
        if (fabs(v[i]) > m) m = fabs(v[i]);
    return m;
}

/* Newton steps H d = -grad on theta (Cholesky of the analytic Hessian), each kept only while it
 * lowers max|grad|, until the job is stopped. work: 2n + n^2. Returns the number of steps kept. */
static int newton_polish(const minimize_job *j, const whirl_chain *c, double omega, double *theta,
                         double *work)
{
    const size_t n = c->n;
    double *grad = work, *trial = work + n, *hess = work + 2 * n;
    whirl_potential(c, omega, theta, grad);
    double gnorm = max_abs(n, grad);
    int kept = 0;
    for (int step = 0; step < NEWTON_MAX_STEPS && gnorm > 0 && !job_stopped(j); step++) {
        whirl_potential_hessian(c, omega, theta, hess);
        if (LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'L', (lapack_int)n, hess, (lapack_int)n) != 0) break;
        for (size_t i = 0; i < n; i++) trial[i] = -grad[i];
        if (LAPACKE_dpotrs(LAPACK_ROW_MAJOR, 'L', (lapack_int)n, 1, hess, (lapack_int)n, trial, 1) != 0)
            break;
        for (size_t i = 0; i < n; i++) trial[i] += theta[i];
        whirl_potential(c, omega, trial, grad);
        const double trial_norm = max_abs(n, grad);
        if (!(trial_norm < gnorm)) break;
        memcpy(theta, trial, n * sizeof *theta);
        gnorm = trial_norm;
        kept++;
    }
    return kept;
}

/* Smallest eigenvalue of the Hessian at theta (work: n^2 + n). */
static int min_curvature(const whirl_chain *c, double omega, const double *theta, double *work,
                         double *lambda_min)
{
    const size_t n = c->n;
    double *hess = work, *eig = work + n * n;
    whirl_potential_hessian(c, omega, theta, hess);
    if (LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'L', (lapack_int)n, hess, (lapack_int)n, eig) != 0)
        return whirl_fail(GSL_EFAILED, "the eigenvalues of the Hessian did not converge");
    *lambda_min = eig[0];
    return GSL_SUCCESS;
}

/* The minimisation of the job (a worker, src/core/worker.h): j->status, j->message, j->theta,
 * j->stats. */
static void minimize_run(void *data, const whirl_worker *self)
{
    minimize_job *j = data;
    j->self = self;
    const whirl_chain *c = j->chain;
    const double omega = j->omega;
    const size_t n = c->n;
    double *theta_out = j->theta, *work = j->work, *lower = j->lower, *upper = lower + n;
    int status = GSL_SUCCESS;
    nlopt_opt nl = j->nl = nlopt_create((nlopt_algorithm)j->algorithm, (unsigned)n);
    if (nl == NULL) {
        status = whirl_fail(GSL_ENOMEM, "out of memory minimising a chain of %zu links", n);
        goto done;
    }
    /* theta = 0 is the minimum (no mode-1 shape) iff K - omega^2 M is positive definite. */
    double *zero = work + n * n;
    memset(zero, 0, n * sizeof *zero);
    whirl_potential_hessian(c, omega, zero, work);
    if (LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'L', (lapack_int)n, work, (lapack_int)n) == 0) {
        double omega_1 = NAN;
        whirl_nlink_critical(c, 1, &omega_1); /* only to name it in the message */
        status = whirl_fail(GSL_EDOM, "no mode-1 shape at omega = " WHIRL_Q_RATE "%g: it is not "
                            "above the chain's first critical rate omega_1 = " WHIRL_Q_RATE
                            "%.10g, and the hanging chain is the minimum", omega, omega_1);
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        lower[i] = -PI;
        upper[i] = PI;
    }
    double v;
    nlopt_set_min_objective(nl, potential_objective, j);
    /* the angles are periodic: bounds only where an algorithm needs them (the global ones,
     * named G...), since a local method can stall on a bound */
    if (nlopt_algorithm_to_string((nlopt_algorithm)j->algorithm)[0] == 'G') {
        nlopt_set_lower_bounds(nl, lower);
        nlopt_set_upper_bounds(nl, upper);
    }
    nlopt_set_xtol_rel(nl, 1e-13);
    nlopt_set_ftol_rel(nl, 1e-16);
    nlopt_set_maxeval(nl, j->max_evaluations > 0 ? j->max_evaluations : MINIMIZE_MAX_EVALUATIONS);
    nlopt_result res = nlopt_optimize(nl, theta_out, &v);
    j->stats.evaluations = atomic_load(&j->evaluations);
    j->stats.nlopt_result = (int)res;
    j->stats.newton_steps = 0;
    if (job_stopped(j)) {
        status = whirl_fail(WHIRL_EINTERRUPTED, "stopped by request after %d evaluations",
                            j->stats.evaluations);
        goto done;
    }
    if (res == NLOPT_INVALID_ARGS) {
        status = whirl_fail(GSL_EINVAL, "NLopt algorithm %s cannot minimise this problem alone "
                            "(it needs a subsidiary algorithm or other settings)",
                            nlopt_algorithm_to_string((nlopt_algorithm)j->algorithm));
        goto done;
    }
    if (res < 0 && res != NLOPT_ROUNDOFF_LIMITED) {
        status = whirl_fail(GSL_EFAILED, "NLopt %s failed: %s",
                            nlopt_algorithm_to_string((nlopt_algorithm)j->algorithm),
                            nlopt_result_to_string(res));
        goto done;
    }
    const int steps = j->polish ? newton_polish(j, c, omega, theta_out, work) : 0;
    double lambda_min = 0;
    if (job_stopped(j)) {
        status = whirl_fail(WHIRL_EINTERRUPTED, "stopped by request in the Newton polish");
        goto done;
    }
    status = min_curvature(c, omega, theta_out, work, &lambda_min);
    if (status) goto done;
    j->stats.newton_steps = steps;
    j->stats.potential = whirl_potential(c, omega, theta_out, work + n * n);
    j->stats.gradient_norm = max_abs(n, work + n * n);
    j->stats.min_curvature = lambda_min;
    if (!(lambda_min > 0))
        status = whirl_fail(GSL_EFAILED, "the minimiser stopped where the Hessian has a "
                            "non-positive eigenvalue %g: not a minimum", lambda_min);
done:
    nlopt_destroy(nl);
    j->nl = NULL;
    j->error.status = GSL_SUCCESS;
    whirl_error_keep(&j->error, status);
}

/* The caller's progress display, called by the worker's poll on the caller's thread. */
typedef struct minimize_tick_ctx {
    minimize_job *job; /* alive while the caller waits */
    const whirl_minimize_options *opt;
    int cap;
} minimize_tick_ctx;

static void minimize_tick(void *data)
{
    const minimize_tick_ctx *t = data;
    t->opt->progress(t->opt->progress_data, atomic_load(&t->job->evaluations), t->cap);
}

int whirl_minimize_shape(const whirl_chain *c, double omega, const whirl_minimize_options *opt,
                         const double *theta, double *theta_out, whirl_minimize_stats *stats)
{
    if (c == NULL || theta_out == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_minimize_shape needs a chain and an output array");
    if (!(isfinite(omega) && omega >= 0))
        return whirl_fail(GSL_EINVAL, "omega must be >= 0 and finite, got %g", omega);
    if (whirl_check_omega_max(omega) != GSL_SUCCESS) return GSL_EINVAL;
    const whirl_minimize_options defaults = whirl_minimize_options_defaults();
    if (opt == NULL) opt = &defaults;
    int algorithm = 0;
    int status = whirl_minimize_algorithm(opt->algorithm ? opt->algorithm : defaults.algorithm,
                                          &algorithm);
    if (status) return status;

    const size_t n = c->n;
    minimize_job *j = calloc(1, sizeof *j);
    if (j != NULL) {
        j->chain = whirl_chain_alloc(n, c->length, c->mass, c->gravity);
        j->theta = malloc(n * sizeof *j->theta);
        j->work = malloc((3 * n + n * n) * sizeof *j->work);
        j->lower = malloc(2 * n * sizeof *j->lower);
    }
    if (j == NULL || j->chain == NULL || j->theta == NULL || j->work == NULL || j->lower == NULL) {
        job_free(j);
        return whirl_fail(GSL_ENOMEM, "out of memory minimising a chain of %zu links", n);
    }
    j->omega = omega;
    j->algorithm = algorithm;
    j->max_evaluations = opt->max_evaluations;
    j->polish = opt->polish;
    for (size_t i = 0; i < n; i++) j->theta[i] = theta ? theta[i] : MINIMIZE_START_TILT;
    atomic_init(&j->evaluations, 0);
    minimize_tick_ctx tc = {j, opt, j->max_evaluations > 0 ? j->max_evaluations
                                                           : MINIMIZE_MAX_EVALUATIONS};
    if (whirl_worker_run_ticked(minimize_run, j, job_free, opt->progress ? minimize_tick : NULL,
                                &tc) != GSL_SUCCESS)
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during the minimisation"); /* the
                                                     job is the worker's now */
    if (stats) *stats = j->stats;
    memcpy(theta_out, j->theta, n * sizeof *theta_out);
    status = j->error.status ? whirl_error_restore(&j->error) : GSL_SUCCESS;
    job_free(j);
    return status;
}
