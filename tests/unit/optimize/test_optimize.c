/* Tests of the NLopt module (whirl/optimize.h).
 * Minimisation: the analytic gradient and Hessian against central differences; the minimum
 * against the shooting solver's mode-1 shape (whirl_nlink_solve); the no-shape criterion against
 * the critical rates of the tridiagonal eigenproblem (whirl_nlink_critical); the shooting
 * solver's modes 2 and 3 as stationary points with 1 and 2 negative directions of the Hessian
 * (the manual's theory, "Linearisation and Krein signatures"), from which the minimiser falls
 * to mode 1.
 * Fitting: shapes made by the steady solvers (continuum and N-link), shuffled, mirrored, with
 * and without Gaussian noise: recovery of omega and the mode, omega_err against the scatter of
 * a Monte-Carlo sample, the signed distances against points put off the curve along its normal,
 * and the error paths. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_randist.h>
#include <lapacke.h>

#include "whirl/optimize.h"
#include "whirl/steady.h"
#include "stop_soon.h"

/* ---- shared by the tests ---- */

static double *vec(size_t n)
{
    double *v = calloc(n, sizeof *v);
    assert_non_null(v);
    return v;
}

/* Link angles from the node positions r[0..n], z[0..n] of a planar shape. */
static void angles_of(size_t n, const double *r, const double *z, double *theta)
{
    for (size_t i = 0; i < n; i++) theta[i] = atan2(r[i + 1] - r[i], z[i] - z[i + 1]);
}

/* Number of negative eigenvalues of the Hessian at theta. */
static int negative_directions(const whirl_chain *c, double omega, const double *theta)
{
    const size_t n = c->n;
    double *h = vec(n * n), *eig = vec(n);
    whirl_potential_hessian(c, omega, theta, h);
    assert_int_equal(LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'L', (lapack_int)n, h, (lapack_int)n, eig), 0);
    int neg = 0;
    for (size_t i = 0; i < n; i++) neg += eig[i] < 0;
    free(h);
    free(eig);
    return neg;
}

/* A chain of unequal links and masses (2.385-style values, not round ones). */
static whirl_chain *uneven_chain(size_t n)
{
    double *l = vec(n), *m = vec(n);
    for (size_t i = 0; i < n; i++) {
        l[i] = 0.1 * (1.0 + 0.37 * sin(1.7 * (double)i + 0.3));
        m[i] = 0.08 * (1.0 + 0.41 * cos(2.3 * (double)i));
    }
    whirl_chain *c = whirl_chain_alloc(n, l, m, 1.3);
    assert_non_null(c);
    free(l);
    free(m);
    return c;
}

/* ---- the potential ---- */

static void test_gradient_and_hessian(void **state)
{
    (void)state;
    const size_t n = 9;
    const double omega = 2.385, h = 1e-5;
    whirl_chain *c = uneven_chain(n);
    double theta[9], grad[9], gp[9], gm[9], hess[81];
    for (size_t i = 0; i < n; i++) theta[i] = 0.7 * sin(3.1 * (double)i + 1.0);
    whirl_potential(c, omega, theta, grad);
    whirl_potential_hessian(c, omega, theta, hess);
    for (size_t j = 0; j < n; j++) {
        const double t = theta[j];
        theta[j] = t + h;
        const double vp = whirl_potential(c, omega, theta, gp);
        theta[j] = t - h;
        const double vm = whirl_potential(c, omega, theta, gm);
        theta[j] = t;
        assert_true(fabs((vp - vm) / (2 * h) - grad[j]) < 1e-9);
        for (size_t k = 0; k < n; k++)
            assert_true(fabs((gp[k] - gm[k]) / (2 * h) - hess[k * n + j]) < 1e-8);
    }
    /* V itself at a hand-computable configuration: one link horizontal, m (0 - w^2 l^2 / 2) */
    whirl_chain *one = whirl_chain_alloc_uniform(1, 0.0);
    const double half_pi = 1.5707963267948966;
    assert_true(fabs(whirl_potential(one, 1.7, &half_pi, NULL) + 0.5 * 1.7 * 1.7) < 1e-15);
    whirl_chain_free(one);
    whirl_chain_free(c);
}

/* ---- the minimum against the shooting solver ---- */

static void compare_with_shooting(const whirl_chain *c, double omega, double tol)
{
    const size_t n = c->n;
    double *theta = vec(n), *r = vec(n + 1), *z = vec(n + 1), *t = vec(n + 1);
    double *r2 = vec(n + 1), *z2 = vec(n + 1), *t2 = vec(n + 1);
    whirl_minimize_stats st;
    assert_int_equal(whirl_minimize_shape(c, omega, NULL, NULL, theta, &st), GSL_SUCCESS);
    whirl_shape_info mine, ref;
    whirl_angles_shape(c, omega, theta, r, z, t, &mine);
    assert_int_equal(whirl_nlink_solve(c, omega, 1, &ref), GSL_SUCCESS);
    assert_int_equal(whirl_nlink_positions(c, omega, ref.tip_r, r2, z2, t2), GSL_SUCCESS);
    assert_int_equal(mine.mode, 1);
    assert_int_equal(mine.n_nodes, 0);
    assert_true(st.min_curvature > 0);
    assert_true(fabs(mine.tip_r - ref.tip_r) < tol);
    assert_true(fabs(mine.depth - ref.depth) < tol);
    assert_true(fabs(mine.top_tension - ref.top_tension) < tol * ref.top_tension);
    for (size_t i = 0; i <= n; i++) {
        assert_true(fabs(r[i] - r2[i]) < tol);
        assert_true(fabs(z[i] - z2[i]) < tol);
        assert_true(fabs(t[i] - t2[i]) < tol * t2[0]);
    }
    free(theta); free(r); free(z); free(t); free(r2); free(z2); free(t2);
}

static void test_minimum_is_mode1(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(100, 0.0);
    compare_with_shooting(c, 2.385, 1e-9);
    compare_with_shooting(c, 1.2, 1e-9); /* just above omega_1 = 1.19942 of N = 100 */
    compare_with_shooting(c, 7.3, 1e-9);
    whirl_chain_free(c);
    c = whirl_chain_alloc_uniform(37, 0.43);
    compare_with_shooting(c, 3.17, 1e-9);
    whirl_chain_free(c);
    c = uneven_chain(23);
    compare_with_shooting(c, 4.4, 1e-9);
    whirl_chain_free(c);
}

/* A stop request ends the minimisation with WHIRL_EINTERRUPTED (it runs on a worker thread the
 * caller leaves: NLopt and LAPACK cannot poll); the next one, after whirl_stop_clear, runs to the
 * same minimum as the shooting. */
static void test_minimize_stop(void **state)
{
    (void)state;
    const size_t n = 400;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.0);
    double *theta = malloc(n * sizeof *theta);
    whirl_minimize_options o = whirl_minimize_options_defaults();
    o.algorithm = "LN_BOBYQA"; /* derivative-free: long between its evaluations */
    whirl_stop_clear();
    pthread_t stopper;
    assert_int_equal(pthread_create(&stopper, NULL, request_stop_soon, NULL), 0);
    const int status = whirl_minimize_shape(c, 3.3, &o, NULL, theta, NULL);
    pthread_join(stopper, NULL);
    const int named = strstr(whirl_last_error(), "stopped by request") != NULL;
    whirl_stop_clear(); /* before any assertion, so that a failure stops nothing else */
    assert_int_equal(status, WHIRL_EINTERRUPTED);
    assert_true(named);
    free(theta);
    compare_with_shooting(c, 3.3, 1e-9);
    whirl_chain_free(c);
}

/* The progress callback: on the caller's thread, evaluations never decreasing, within the cap,
 * the last no more than the minimisation's count. */
typedef struct progress_seen {
    pthread_t caller;
    int calls, other_thread, last, decreasing, cap;
} progress_seen;

static void record_progress(void *data, int evaluations, int max_evaluations)
{
    progress_seen *p = data;
    p->calls++;
    if (!pthread_equal(pthread_self(), p->caller)) p->other_thread++;
    if (evaluations < p->last) p->decreasing++;
    p->last = evaluations;
    p->cap = max_evaluations;
}

static void test_minimize_progress(void **state)
{
    (void)state;
    const size_t n = 600; /* about 0.1 s of work or more: several 20 ms polls */
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.0);
    double *theta = malloc(n * sizeof *theta);
    whirl_minimize_options o = whirl_minimize_options_defaults();
    o.polish = 0;
    o.max_evaluations = 5000;
    progress_seen seen = {.caller = pthread_self()};
    o.progress = record_progress;
    o.progress_data = &seen;
    whirl_minimize_stats st;
    assert_int_equal(whirl_minimize_shape(c, 3, &o, NULL, theta, &st), GSL_SUCCESS);
    assert_true(seen.calls >= 1);
    assert_int_equal(seen.other_thread, 0);
    assert_int_equal(seen.decreasing, 0);
    assert_int_equal(seen.cap, 5000);
    assert_true(seen.last <= st.evaluations);
    free(theta);
    whirl_chain_free(c);
}

/* No mode-1 shape exactly at or below the first critical rate of the tridiagonal eigenproblem. */
static void test_below_critical(void **state)
{
    (void)state;
    whirl_chain *c = uneven_chain(31);
    double w1, theta[31];
    assert_int_equal(whirl_nlink_critical(c, 1, &w1), GSL_SUCCESS);
    assert_int_equal(whirl_minimize_shape(c, w1 * (1 - 1e-6), NULL, NULL, theta, NULL), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "critical"));
    assert_int_equal(whirl_minimize_shape(c, 0.0, NULL, NULL, theta, NULL), GSL_EDOM);
    assert_int_equal(whirl_minimize_shape(c, w1 * (1 + 1e-3), NULL, NULL, theta, NULL), GSL_SUCCESS);
    double r[32], z[32];
    whirl_shape_info info;
    whirl_angles_shape(c, w1 * (1 + 1e-3), theta, r, z, NULL, &info);
    assert_true(info.tip_r > 1e-3 && info.mode == 1);
    whirl_chain_free(c);
}

/* Every local algorithm of the list, without the Newton polish, reaches the shooting solution
 * to the accuracy a stop on V allows: |dtheta| ~ sqrt(2 eps |V| / lambda_min) ~ 1e-7 here. */
static void test_algorithms(void **state)
{
    (void)state;
    static const char *algs[] = {"LD_LBFGS", "LD_TNEWTON_PRECOND_RESTART", "LD_VAR2", "LD_MMA",
                                 "LD_SLSQP", "LN_BOBYQA", "LN_NEWUOA", "LN_SBPLX", "LN_COBYLA",
                                 "LN_NELDERMEAD", "LN_PRAXIS"};
    whirl_chain *c = whirl_chain_alloc_uniform(8, 0.0);
    const double omega = 2.385;
    whirl_shape_info ref, got;
    assert_int_equal(whirl_nlink_solve(c, omega, 1, &ref), GSL_SUCCESS);
    for (size_t a = 0; a < sizeof algs / sizeof algs[0]; a++) {
        whirl_minimize_options o = whirl_minimize_options_defaults();
        o.algorithm = algs[a];
        o.polish = 0;
        double theta[8], r[9], z[9];
        whirl_minimize_stats st;
        assert_int_equal(whirl_minimize_shape(c, omega, &o, NULL, theta, &st), GSL_SUCCESS);
        whirl_angles_shape(c, omega, theta, r, z, NULL, &got);
        if (!(fabs(got.tip_r - ref.tip_r) < 1e-7))
            fail_msg("%s: tip_r %.17g against %.17g", algs[a], got.tip_r, ref.tip_r);
        assert_true(st.evaluations > 0);
    }
    whirl_chain_free(c);
}

/* Modes 2 and 3 of the shooting solver are stationary points of V with 1 and 2 negative
 * directions; mode 1 has none. Started next to mode 2 or 3 the minimiser ends at mode 1. */
static void test_higher_modes_are_saddles(void **state)
{
    (void)state;
    const size_t n = 40;
    const double omega = 5.3; /* above omega_3 = 4.33 */
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.0);
    double *r = vec(n + 1), *z = vec(n + 1), *t = vec(n + 1), *theta = vec(n), *grad = vec(n);
    double *out = vec(n);
    whirl_shape_info mode1, info;
    assert_int_equal(whirl_nlink_solve(c, omega, 1, &mode1), GSL_SUCCESS);
    for (int k = 1; k <= 3; k++) {
        assert_int_equal(whirl_nlink_solve(c, omega, k, &info), GSL_SUCCESS);
        assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, t), GSL_SUCCESS);
        angles_of(n, r, z, theta);
        whirl_potential(c, omega, theta, grad);
        for (size_t i = 0; i < n; i++) assert_true(fabs(grad[i]) < 1e-12);
        assert_int_equal(negative_directions(c, omega, theta), k - 1);
        if (k == 1) continue;
        for (size_t i = 0; i < n; i++) theta[i] += 1e-3 * sin(0.9 * (double)i + 0.2);
        whirl_minimize_stats st;
        if (whirl_minimize_shape(c, omega, NULL, theta, out, &st) != GSL_SUCCESS)
            fail_msg("from mode %d: %s", k, whirl_last_error());
        whirl_angles_shape(c, omega, out, r, z, NULL, &info);
        assert_int_equal(info.mode, 1);
        assert_true(fabs(info.tip_r - mode1.tip_r) < 1e-9);
    }
    free(r); free(z); free(t); free(theta); free(grad); free(out);
    whirl_chain_free(c);
}

static void test_minimize_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0.0);
    double theta[5];
    whirl_minimize_options o = whirl_minimize_options_defaults();
    o.algorithm = "LD_NOSUCH";
    assert_int_equal(whirl_minimize_shape(c, 2.0, &o, NULL, theta, NULL), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "LD_NOSUCH"));
    o.algorithm = "AUGLAG"; /* needs a subsidiary algorithm */
    assert_int_equal(whirl_minimize_shape(c, 2.0, &o, NULL, theta, NULL), GSL_EINVAL);
    assert_int_equal(whirl_minimize_shape(c, -1.0, NULL, NULL, theta, NULL), GSL_EINVAL);
    assert_int_equal(whirl_minimize_shape(c, NAN, NULL, NULL, theta, NULL), GSL_EINVAL);
    assert_int_equal(whirl_minimize_shape(NULL, 2.0, NULL, NULL, theta, NULL), GSL_EINVAL);
    int alg;
    assert_int_equal(whirl_minimize_algorithm("LN_BOBYQA", &alg), GSL_SUCCESS);
    assert_int_equal(whirl_minimize_algorithm(NULL, &alg), GSL_EINVAL);
    whirl_chain_free(c);
}

/* ---- fitting ---- */

/* Points of the N-link shape of mode k at omega (the nodes 1..n), shuffled, mirrored if asked,
 * with Gaussian noise of standard deviation sigma on every coordinate. */
static void nlink_points(const whirl_chain *c, double omega, int mode, int mirrored, double sigma,
                         gsl_rng *rng, double *r, double *z)
{
    const size_t n = c->n;
    double *pr = vec(n + 1), *pz = vec(n + 1), *pt = vec(n + 1);
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve(c, omega, mode, &info), GSL_SUCCESS);
    assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, pr, pz, pt), GSL_SUCCESS);
    size_t *order = malloc(n * sizeof *order);
    for (size_t i = 0; i < n; i++) order[i] = i + 1;
    gsl_ran_shuffle(rng, order, n, sizeof *order);
    for (size_t i = 0; i < n; i++) {
        r[i] = (mirrored ? -1 : 1) * pr[order[i]] + (sigma > 0 ? gsl_ran_gaussian(rng, sigma) : 0);
        z[i] = pz[order[i]] + (sigma > 0 ? gsl_ran_gaussian(rng, sigma) : 0);
    }
    free(order); free(pr); free(pz); free(pt);
}

static void test_fit_nlink_exact(void **state)
{
    (void)state;
    const size_t n = 30;
    static const struct { double omega; int mode, mirrored; } cases[] = {
        {1.913, 1, 0}, {3.71, 2, 1}, {5.63, 3, 0}, {9.4, 4, 1}};
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.0);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double r[30], z[30];
    whirl_fit_model m = whirl_fit_model_defaults();
    m.links = n;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        nlink_points(c, cases[k].omega, cases[k].mode, cases[k].mirrored, 0.0, rng, r, z);
        whirl_fit_result res;
        if (whirl_fit(&m, n, r, z, 0, &res) != GSL_SUCCESS) fail_msg("%s", whirl_last_error());
        assert_int_equal(res.mode, cases[k].mode);
        assert_int_equal(res.mirrored, cases[k].mirrored);
        assert_true(fabs(res.omega / cases[k].omega - 1) < 1e-9);
        assert_true(res.rms_residual < 1e-9);
    }
    gsl_rng_free(rng);
    whirl_chain_free(c);
}

/* omega_err against the scatter of omega over independent noisy samples of the same shape. */
/* The progress of a fit: one call per model evaluation, counting up to the result's evaluations,
 * over the modes tried; the result is whirl_fit's. */
typedef struct progress_log {
    int calls, last_evaluations, monotone, first, last, mode_min, mode_max;
} progress_log;

static void log_progress(void *data, int mode, int first, int last, int evaluations)
{
    progress_log *p = data;
    p->monotone &= evaluations == p->last_evaluations + 1;
    p->last_evaluations = evaluations;
    p->calls++;
    p->first = first, p->last = last;
    if (mode < p->mode_min) p->mode_min = mode;
    if (mode > p->mode_max) p->mode_max = mode;
}

static void test_fit_progress(void **state)
{
    (void)state;
    const size_t n = 30;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.0);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double r[30], z[30];
    whirl_fit_model m = whirl_fit_model_defaults();
    m.links = n;
    nlink_points(c, 3.71, 2, 0, 0.0, rng, r, z);
    whirl_fit_result plain, observed;
    assert_int_equal(whirl_fit(&m, n, r, z, 0, &plain), GSL_SUCCESS);
    progress_log log = {0, 0, 1, 0, 0, 1000, 0};
    assert_int_equal(whirl_fit_observed(&m, n, r, z, 0, log_progress, &log, &observed),
                     GSL_SUCCESS);
    print_message("# fit progress: %d calls, modes %d..%d of %d..%d\n", log.calls, log.mode_min,
                  log.mode_max, log.first, log.last);
    assert_true(log.monotone);
    assert_int_equal(log.calls, observed.evaluations);
    assert_int_equal(log.first, 1);
    assert_true(log.mode_min == log.first && log.mode_max == log.last && log.last >= 2);
    assert_true(observed.omega == plain.omega && observed.mode == plain.mode);
    gsl_rng_free(rng);
    whirl_chain_free(c);
}

static void test_fit_uncertainty_monte_carlo(void **state)
{
    (void)state;
    enum { SAMPLES = 100 };
    const size_t n = 30;
    const double omega = 3.71, sigma = 1e-3;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.0);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 2385);
    whirl_fit_model m = whirl_fit_model_defaults();
    m.links = n;
    double r[30], z[30], est[SAMPLES], err_sum = 0, mean = 0, var = 0;
    for (int j = 0; j < SAMPLES; j++) {
        nlink_points(c, omega, 2, j % 2, sigma, rng, r, z);
        whirl_fit_result res;
        if (whirl_fit(&m, n, r, z, 2, &res) != GSL_SUCCESS) fail_msg("%s", whirl_last_error());
        assert_true(fabs(res.omega / omega - 1) < 0.01);
        /* the residual estimates the noise: normal distances of sd sigma */
        assert_true(res.rms_residual > 0.5 * sigma && res.rms_residual < 1.5 * sigma);
        est[j] = res.omega;
        err_sum += res.omega_err;
        mean += res.omega / SAMPLES;
    }
    for (int j = 0; j < SAMPLES; j++) var += (est[j] - mean) * (est[j] - mean) / (SAMPLES - 1);
    const double scatter = sqrt(var), predicted = err_sum / SAMPLES;
    /* the sample sd of 100 normal values has a relative sd of 7%: within +-20% at 99.5% */
    if (!(scatter > 0.8 * predicted && scatter < 1.25 * predicted))
        fail_msg("scatter %g against omega_err %g", scatter, predicted);
    /* unbiased: the mean within 3 standard errors */
    assert_true(fabs(mean - omega) < 3 * scatter / sqrt((double)SAMPLES));
    gsl_rng_free(rng);
    whirl_chain_free(c);
}

/* Points of the continuum's shape of mode k at omega at n arclengths (not on the fit's sample
 * grid), shuffled, mirrored if asked, with Gaussian noise sigma on every coordinate. */
static void continuum_points(double omega, int mode, double tip_mass, int mirrored, double sigma,
                             gsl_rng *rng, size_t n, double *r, double *z)
{
    double *s = vec(n + 1), *pr = vec(n + 1), *pz = vec(n + 1), *pt = vec(n + 1);
    whirl_shape_info info;
    assert_int_equal(whirl_continuum_solve(omega, mode, tip_mass, 0.0, &info), GSL_SUCCESS);
    assert_int_equal(whirl_continuum_sample(omega, tip_mass, info.tip_r, n + 1, s, pr, pz, pt),
                     GSL_SUCCESS);
    size_t *order = malloc(n * sizeof *order);
    for (size_t i = 0; i < n; i++) order[i] = i + 1; /* the pivot left out */
    gsl_ran_shuffle(rng, order, n, sizeof *order);
    for (size_t i = 0; i < n; i++) {
        r[i] = (mirrored ? -1 : 1) * pr[order[i]] + (sigma > 0 ? gsl_ran_gaussian(rng, sigma) : 0);
        z[i] = pz[order[i]] + (sigma > 0 ? gsl_ran_gaussian(rng, sigma) : 0);
    }
    free(order); free(s); free(pr); free(pz); free(pt);
}

static const struct {
    double omega, tip_mass;
    int mode, mirrored;
} continuum_cases[] = {{2.385, 0, 1, 0}, {1.25, 0, 1, 1}, {4.1, 0, 2, 1}, {6.2, 0, 3, 0},
                       {5.3, 0.3, 2, 0}};

/* Without noise omega to 1e-6 relative (the model polyline's chord error is ~1e-8 L). */
static void test_fit_continuum_exact(void **state)
{
    (void)state;
    enum { N = 37 };
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double r[N], z[N];
    for (size_t k = 0; k < sizeof continuum_cases / sizeof continuum_cases[0]; k++) {
        whirl_fit_model m = whirl_fit_model_defaults();
        m.tip_mass = continuum_cases[k].tip_mass;
        continuum_points(continuum_cases[k].omega, continuum_cases[k].mode, m.tip_mass,
                         continuum_cases[k].mirrored, 0.0, rng, N, r, z);
        whirl_fit_result res;
        if (whirl_fit(&m, N, r, z, 0, &res) != GSL_SUCCESS) fail_msg("%s", whirl_last_error());
        assert_int_equal(res.mode, continuum_cases[k].mode);
        assert_int_equal(res.mirrored, continuum_cases[k].mirrored);
        if (!(fabs(res.omega / continuum_cases[k].omega - 1) < 1e-6))
            fail_msg("omega %.17g against %g", res.omega, continuum_cases[k].omega);
        assert_true(res.rms_residual < 1e-6);
    }
    gsl_rng_free(rng);
}

/* With noise 1e-3 L on every coordinate omega to 1%, and within 4 omega_err. */
static void test_fit_continuum_noise(void **state)
{
    (void)state;
    enum { N = 37 };
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 77);
    double r[N], z[N];
    for (size_t k = 0; k < sizeof continuum_cases / sizeof continuum_cases[0]; k++) {
        whirl_fit_model m = whirl_fit_model_defaults();
        m.tip_mass = continuum_cases[k].tip_mass;
        const double omega = continuum_cases[k].omega;
        continuum_points(omega, continuum_cases[k].mode, m.tip_mass, continuum_cases[k].mirrored,
                         1e-3, rng, N, r, z);
        whirl_fit_result res;
        if (whirl_fit(&m, N, r, z, 0, &res) != GSL_SUCCESS) fail_msg("%s", whirl_last_error());
        assert_int_equal(res.mode, continuum_cases[k].mode);
        assert_true(fabs(res.omega / omega - 1) < 0.01);
        assert_true(fabs(res.omega - omega) < 4 * res.omega_err);
    }
    gsl_rng_free(rng);
}

/* Signed distances: zero on the curve, +-delta a distance delta off it along the normal (the
 * normal from the neighbours' chord: its angle error ~ h^2, whose effect ~ delta h^4). */
static void test_fit_residuals(void **state)
{
    (void)state;
    enum { N = 81 };
    const double omega = 4.1, delta = 3e-3;
    double s[N], r[N], z[N], t[N], qr[2 * N], qz[2 * N], e[2 * N];
    whirl_shape_info info;
    assert_int_equal(whirl_continuum_solve(omega, 2, 0.0, 0.0, &info), GSL_SUCCESS);
    assert_int_equal(whirl_continuum_sample(omega, 0.0, info.tip_r, N, s, r, z, t), GSL_SUCCESS);
    for (size_t i = 1; i + 1 < N; i++) { /* the normal from the neighbours' chord */
        const double dr = r[i + 1] - r[i - 1], dz = z[i + 1] - z[i - 1], h = hypot(dr, dz);
        qr[2 * i] = r[i];
        qz[2 * i] = z[i];
        qr[2 * i + 1] = r[i] - delta * dz / h;
        qz[2 * i + 1] = z[i] + delta * dr / h;
    }
    whirl_fit_model m = whirl_fit_model_defaults();
    assert_int_equal(whirl_fit_residuals(&m, omega, 2, 0, 2 * N - 4, qr + 2, qz + 2, e),
                     GSL_SUCCESS);
    for (size_t j = 0; j < 2 * N - 4; j += 2) {
        assert_true(fabs(e[j]) < 1e-7);
        assert_true(fabs(fabs(e[j + 1]) - delta) < 1e-6 * delta + 1e-7);
        assert_true(e[j + 1] * e[1] > 0); /* all on the same side */
    }
    assert_int_equal(whirl_fit_residuals(&m, 1.0, 2, 0, 2, qr + 2, qz + 2, e), GSL_EINVAL);
    assert_int_equal(whirl_fit_residuals(&m, 2.0, 2, 0, 3, qr + 2, qz + 2, e), GSL_EDOM);
}

static void test_fit_errors(void **state)
{
    (void)state;
    whirl_fit_model m = whirl_fit_model_defaults();
    whirl_fit_result res;
    double r[4] = {0.1, 0.2, 0.3, 0.35}, z[4] = {-0.2, -0.5, -0.7, -0.9};
    assert_int_equal(whirl_fit(&m, 2, r, z, 0, &res), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "at least 3"));
    z[2] = NAN;
    assert_int_equal(whirl_fit(&m, 4, r, z, 0, &res), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "point 3"));
    z[2] = -0.7;
    assert_int_equal(whirl_fit(&m, 4, r, z, WHIRL_MODE_MAX + 1, &res), GSL_EINVAL);
    assert_int_equal(whirl_fit(&m, 4, r, z, -1, &res), GSL_EINVAL);
    m.omega_max = 1.1; /* below omega_1 = 1.2024: no mode exists */
    assert_int_equal(whirl_fit(&m, 4, r, z, 0, &res), GSL_EDOM);
    assert_int_equal(whirl_fit(&m, 4, r, z, 2, &res), GSL_EDOM);
    m = whirl_fit_model_defaults();
    m.tip_mass = -0.1;
    assert_int_equal(whirl_fit(&m, 4, r, z, 0, &res), GSL_EINVAL);
    m = whirl_fit_model_defaults();
    m.samples = 1;
    assert_int_equal(whirl_fit(&m, 4, r, z, 0, &res), GSL_EINVAL);
    m = whirl_fit_model_defaults();
    m.links = 3;
    assert_int_equal(whirl_fit(&m, 4, r, z, 4, &res), GSL_EDOM); /* 3 links: modes 1..3 */
    /* the counts that drive the work are bounded in the library (10^7 links ran 12 minutes) */
    m.links = 10000000;
    assert_int_equal(whirl_fit(&m, 4, r, z, 0, &res), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "at most 2000 links, got 10000000"));
    assert_non_null(strstr(whirl_last_error(), "916 MiB"));
    m = whirl_fit_model_defaults();
    m.samples = (size_t)WHIRL_FIT_SAMPLES_MAX + 1;
    assert_int_equal(whirl_fit(&m, 4, r, z, 0, &res), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "at most 1000000 samples"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gradient_and_hessian),
        cmocka_unit_test(test_minimum_is_mode1),
        cmocka_unit_test(test_minimize_stop),
        cmocka_unit_test(test_minimize_progress),
        cmocka_unit_test(test_below_critical),
        cmocka_unit_test(test_algorithms),
        cmocka_unit_test(test_higher_modes_are_saddles),
        cmocka_unit_test(test_minimize_errors),
        cmocka_unit_test(test_fit_nlink_exact),
        cmocka_unit_test(test_fit_progress),
        cmocka_unit_test(test_fit_uncertainty_monte_carlo),
        cmocka_unit_test(test_fit_continuum_exact),
        cmocka_unit_test(test_fit_continuum_noise),
        cmocka_unit_test(test_fit_residuals),
        cmocka_unit_test(test_fit_errors),
    };
    gsl_set_error_handler_off();
    return cmocka_run_group_tests(tests, NULL, NULL);
}
