/* Tests of the periodic motions and their Floquet multipliers (whirl/periodic.h) against
 * results that no setting of the method can produce by itself:
 *  - N = 1 with vertical shaking is Mathieu's equation: with the pivot at A cos(omega t) the
 *    pendulum's angle obeys theta'' + (g/l - (A omega^2 / l) cos omega t) sin theta = 0, which
 *    about the hanging state is y'' + (a - 2 q cos 2 tau) y = 0 with tau = omega t / 2,
 *    a = 4 g / (l omega^2), q = 2 A / l. A boundary of the tongue n is where a multiplier of the
 *    period T = 2 pi / omega (tau-period pi) is (-1)^n: a = a_n(q) or b_n(q), the Mathieu
 *    characteristic values. Located by Brent's method on omega (the trace of the monodromy,
 *    extrapolated from two steps, minus +-2) and compared with the values of
 *      /usr/bin/python3 -c "from scipy.special import mathieu_a, mathieu_b;
 *        print(repr(mathieu_a(1, 0.2)), repr(mathieu_b(1, 0.2)), repr(mathieu_a(2, 0.2)),
 *              repr(mathieu_b(2, 0.2)), repr(mathieu_a(0, 0.2)))"
 *    which a Hill matrix (the recurrence of the Fourier coefficients, 60 terms, numpy eigvalsh)
 *    reproduces to 1e-15; the inverted pendulum's lower edge of stability (Kapitza's) is
 *    a_0(q) with a = -4 g / (l omega^2);
 *  - the circle drive: the steady shape of whirl_stability_driven_mode is a periodic motion,
 *    and its multipliers are exp(lambda T) of that linearisation (a different formulation: link
 *    angles, mass, gyroscopic and stiffness matrices, one eigen-solve);
 *  - the conservative chain's multipliers in reciprocal pairs;
 *  - a perturbed run grows per period by the largest multiplier's modulus;
 *  - Newton's method that cannot converge says so and gives no multiplier. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_roots.h>

#include "whirl/periodic.h"
#include "whirl/stability.h"

/* ---- Mathieu ---- */

typedef struct mathieu_case {
    double amplitude; /* A [L], q = 2 A */
    int steps;        /* the coarser of the two solves */
    double target;    /* the trace at the boundary: 2 (-1)^n */
    int inverted;     /* 1: about the inverted state */
} mathieu_case;

/* The trace of the monodromy of the hanging pendulum shaken at omega, from steps and 2 steps
 * per period extrapolated (Gauss, order 4): tr(h/2) + (tr(h/2) - tr(h)) / 15. */
static double trace_at(const mathieu_case *mc, double omega)
{
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const double up[3] = {0, 0, 1};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_line(&path, omega, mc->amplitude, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 2, &path);
    assert_non_null(w);
    double tr[2];
    for (int k = 0; k < 2; k++) {
        double y[4];
        assert_int_equal(whirl_periodic_start_vertical(w, mc->inverted, y), GSL_SUCCESS);
        const whirl_periodic_params p = {.steps = mc->steps << k, .refine = 0};
        whirl_periodic_result r;
        assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
        assert_int_equal(r.count, 2);
        tr[k] = r.re[0] + r.re[1];
    }
    whirl_periodic_free(w);
    whirl_chain_free(c);
    return tr[1] + (tr[1] - tr[0]) / 15 - mc->target;
}

static double trace_fn(double omega, void *params) { return trace_at(params, omega); }

/* The rate in [lo, hi] where the trace is the target, by Brent's method to 1e-14. */
static double boundary(mathieu_case *mc, double lo, double hi)
{
    gsl_function f = {trace_fn, mc};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    assert_int_equal(gsl_root_fsolver_set(s, &f, lo, hi), GSL_SUCCESS);
    double root = 0;
    for (int i = 0; i < 100; i++) {
        assert_int_equal(gsl_root_fsolver_iterate(s), GSL_SUCCESS);
        root = gsl_root_fsolver_root(s);
        lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(lo, hi, 1e-14, 0) == GSL_SUCCESS) break;
    }
    gsl_root_fsolver_free(s);
    return root;
}

static void test_mathieu_tongues(void **state)
{
    (void)state;
    /* q = 0.2: the references of the header's command */
    const double a1 = 1.1948740592044615, b1 = 0.79512386808386326;
    const double a2 = 4.0165791529694674, b2 = 3.9966672451382044;
    /* the inverted pendulum: phi = theta - pi obeys Mathieu's equation with a = -4 g / (l w^2)
       and q -> -q, whose boundary a_0(-q) = a_0(q) bounds Kapitza's stable region from below:
       mathieu_a(0, 0.2) */
    const double a0 = -0.019913296358437527;
    mathieu_case up = {.amplitude = 0.1, .steps = 800, .target = 2, .inverted = 1};
    mathieu_case odd = {.amplitude = 0.1, .steps = 800, .target = -2, .inverted = 0};
    mathieu_case even = {.amplitude = 0.1, .steps = 800, .target = 2, .inverted = 0};
    /* brackets from the unshaken pendulum alone: the tongue n grows out of a = n^2, i.e.
       omega = 2 / n, inside it at omega = 2 / n exactly (b_n(q) < n^2 < a_n(q) for q > 0), and
       the rates 1.6, 2.6 (n = 1) and 0.95, 1.05 (n = 2) lie between tongues at q = 0.2 */
    const struct {
        mathieu_case *mc;
        double lo, hi, ref;
        const char *name;
    } rows[] = {{&odd, 1.6, 2.0, a1, "a_1"},
                {&odd, 2.0, 2.6, b1, "b_1"},
                {&even, 0.95, 1.0, a2, "a_2"},
                {&even, 1.0, 1.05, b2, "b_2"},
                /* inverted: unstable at omega = 10 (a = -0.04), stable at 20 (a = -0.01): the
                   unshaken a_0(0) = 0 and a_0(q) ~ -q^2 / 2 (A&S 20.2.25) */
                {&up, 10.0, 20.0, a0, "a_0 (inverted)"}};
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const double omega = boundary(rows[i].mc, rows[i].lo, rows[i].hi);
        const double a = (rows[i].mc->inverted ? -4 : 4) / (omega * omega);
        print_message("# Mathieu q = 0.2: %s = %.15f from the multipliers, %.15f reference, "
                      "difference %.2g\n", rows[i].name, a, rows[i].ref, a - rows[i].ref);
        assert_true(fabs(a - rows[i].ref) < 1e-8);
    }
}

/* ---- the shaken inverted chain in the limit of fast shaking ---- */

/* Averaging (Kapitza; Acheson, Proc. R. Soc. A 443, 1993): with the pivot at A cos(omega t)
 * vertically, A -> 0 at A omega fixed, the chain moves in the potential
 * V + (A omega)^2 / 4 grad(Z)^T M^-1 grad(Z), Z = sum m_i z_i, V = g Z. At the inverted state
 * grad Z = 0 and the Hessian of Z is -K, K the stiffness of the hanging chain over g in the
 * link angles, so the Hessian is -g K + (A omega)^2 / 2 K M^-1 K: positive definite iff
 * (A omega)^2 > 2 g / nu_min with K v = nu M v, i.e. nu_min = omega_1^2 / g, omega_1 the lowest
 * frequency of the hanging chain. In the angles: M_ij = l_i l_j sum_{k >= max(i, j)} m_k,
 * K_ii = l_i sum_{k >= i} m_k (gsl_eigen_gensymm here, not the code under test). */
static double averaged_limit(size_t n)
{
    gsl_matrix *m = gsl_matrix_calloc(n, n), *k = gsl_matrix_calloc(n, n);
    const double l = 1.0 / n, mass = 1.0 / n;
    for (size_t i = 0; i < n; i++) {
        for (size_t j = 0; j < n; j++)
            gsl_matrix_set(m, i, j, l * l * mass * (double)(n - (i > j ? i : j)));
        gsl_matrix_set(k, i, i, l * mass * (double)(n - i));
    }
    gsl_vector *eval = gsl_vector_alloc(n);
    gsl_eigen_gensymm_workspace *ws = gsl_eigen_gensymm_alloc(n);
    assert_int_equal(gsl_eigen_gensymm(k, m, eval, ws), GSL_SUCCESS);
    const double nu_min = gsl_vector_min(eval);
    gsl_eigen_gensymm_free(ws);
    gsl_vector_free(eval);
    gsl_matrix_free(m);
    gsl_matrix_free(k);
    return sqrt(2 / nu_min);
}

typedef struct inverted_case {
    size_t n;
    double amplitude;
} inverted_case;

/* rho_max - 2 for the inverted chain of ic->n links (planar: n pairs mu, 1/mu) shaken at omega,
 * rho = mu + 1/mu. For N = 2, rho_1 + rho_2 = tr M and rho_1^2 + rho_2^2 = tr M^2 + 4 (sums of mu
 * and mu^2, smooth where single multipliers near a collision are not). For N > 2 each pair's
 * rho = Re mu + Re mu / |mu|^2 from the multipliers themselves: near the collision at +1 the two
 * multipliers 1 +- d split by the square root of a perturbation e of the monodromy, but
 * rho - 2 = d^2 is linear in e, so rho stays as well conditioned as the traces. The slowest
 * mode's pair has the largest rho (the faster modes are held up more firmly: their angle per
 * period is larger). A pair through +1 is rho through 2. */
static double rho_margin(double omega, void *params)
{
    const inverted_case *ic = params;
    whirl_chain *c = whirl_chain_alloc_uniform(ic->n, 0);
    const double up[3] = {0, 0, 1};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_line(&path, omega, ic->amplitude, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 2, &path);
    double *y = malloc(4 * ic->n * sizeof *y);
    assert_non_null(y);
    assert_int_equal(whirl_periodic_start_vertical(w, 1, y), GSL_SUCCESS);
    const whirl_periodic_params p = {.steps = 400, .refine = 0};
    whirl_periodic_result r;
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
    assert_int_equal(r.count, 2 * ic->n);
    double rho;
    if (ic->n == 2) {
        double tr = 0, tr2 = 0;
        for (size_t i = 0; i < r.count; i++) {
            tr += r.re[i];
            tr2 += r.re[i] * r.re[i] - r.im[i] * r.im[i];
        }
        /* rho_1 + rho_2 = tr M, rho_1^2 + rho_2^2 = tr M^2 + 4 (mu^2 + mu^-2 = rho^2 - 2) */
        const double prod = (tr * tr - tr2 - 4) / 2;
        rho = tr / 2 + sqrt(fmax(tr * tr / 4 - prod, 0));
    } else {
        rho = -INFINITY;
        for (size_t i = 0; i < r.count; i++) {
            const double m2 = r.re[i] * r.re[i] + r.im[i] * r.im[i];
            rho = fmax(rho, r.re[i] + r.re[i] / m2);
        }
    }
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
    return rho - 2;
}

/* The inverted chain of n links: where its slowest pair of multipliers passes +1 at the shaking
 * amplitudes 0.01 and 0.005, against the averaged limit; the difference falls as A^2 (the next
 * order of the averaging), so its Richardson extrapolation in A^2 is the limit. */
static void fast_shaking(size_t n, double tol_extrapolated)
{
    const double limit = averaged_limit(n);
    double diff[2];
    for (int k = 0; k < 2; k++) {
        inverted_case ic = {n, 0.01 / (1 << k)};
        gsl_function f = {rho_margin, &ic};
        gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
        /* brackets: half and twice the limit's rate, unstable (rho > 2) and stable */
        double lo = 0.5 * limit / ic.amplitude, hi = 2 * limit / ic.amplitude;
        assert_true(rho_margin(lo, &ic) > 0 && rho_margin(hi, &ic) < 0);
        assert_int_equal(gsl_root_fsolver_set(s, &f, lo, hi), GSL_SUCCESS);
        for (int i = 0; i < 100; i++) {
            assert_int_equal(gsl_root_fsolver_iterate(s), GSL_SUCCESS);
            lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
            if (gsl_root_test_interval(lo, hi, 0, 1e-12) == GSL_SUCCESS) break;
        }
        const double omega = gsl_root_fsolver_root(s);
        gsl_root_fsolver_free(s);
        diff[k] = ic.amplitude * omega / limit - 1;
        print_message("# inverted N = %zu, A = %g: A omega* = %.12f, averaged limit %.12f, "
                      "relative difference %.3g\n", n, ic.amplitude, ic.amplitude * omega, limit,
                      diff[k]);
    }
    const double extrapolated = (4 * diff[1] - diff[0]) / 3;
    print_message("# N = %zu, extrapolated in A^2: %.2g\n", n, extrapolated);
    assert_true(fabs(diff[0]) < 1e-4);
    assert_true(fabs(diff[1] / diff[0] - 0.25) < 0.01); /* the A^2 law */
    assert_true(fabs(extrapolated) < tol_extrapolated);
}

static void test_inverted_fast_shaking(void **state)
{
    (void)state;
    fast_shaking(2, 1e-7);
}

static void test_inverted_fast_shaking_chains(void **state)
{
    (void)state;
    fast_shaking(3, 1e-7);
    fast_shaking(5, 1e-7);
    fast_shaking(10, 1e-7);
}

/* ---- the circle drive against the steady linearisation ---- */

typedef struct circle_case {
    size_t n;
    double omega, eps;
    int mode, steps;
} circle_case;

typedef struct circle_run {
    whirl_chain *c;
    whirl_stability *st;
    whirl_periodic *w;
    double *y, *y_steady;
    size_t count;
    const double *lre, *lim;
} circle_run;

static void circle_setup(const circle_case *cc, circle_run *run)
{
    run->c = whirl_chain_alloc_uniform(cc->n, 0);
    run->st = whirl_stability_alloc(cc->n);
    const whirl_model model = {.chain = run->c, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                               .omega = cc->omega, .drive_radius = cc->eps};
    double growth;
    assert_int_equal(whirl_stability_driven_mode(run->st, &model, cc->mode, 1, NULL, &growth),
                     GSL_SUCCESS);
    assert_int_equal(whirl_stability_eigenvalues(run->st, &run->count, &run->lre, &run->lim),
                     GSL_SUCCESS);
    const double *x, *y, *z;
    whirl_stability_nodes(run->st, &x, &y, &z);
    double *links = malloc(3 * cc->n * sizeof *links);
    assert_int_equal(whirl_shape_links(cc->n, x, y, z, links), GSL_SUCCESS);
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, cc->omega, cc->eps), GSL_SUCCESS);
    run->w = whirl_periodic_alloc(run->c, 3, &path);
    assert_non_null(run->w);
    const size_t size = whirl_periodic_state_size(run->w);
    run->y = malloc(size * sizeof *run->y);
    run->y_steady = malloc(size * sizeof *run->y_steady);
    assert_int_equal(whirl_dyn_state_from_shape(whirl_periodic_dyn(run->w), 0, links, cc->omega,
                                                run->y_steady),
                     GSL_SUCCESS);
    free(links);
}

static void circle_free(circle_run *run)
{
    whirl_periodic_free(run->w);
    whirl_stability_free(run->st);
    whirl_chain_free(run->c);
    free(run->y);
    free(run->y_steady);
}

/* The largest |mu - exp(lambda T)| over the linearisation's eigenvalues, each matched to the
 * nearest multiplier not yet taken; *est the error estimate of that multiplier. */
static double circle_mismatch(const circle_run *run, const whirl_periodic_result *r, double *est)
{
    int *used = calloc(r->count, sizeof *used);
    double worst = 0;
    *est = 0;
    for (size_t k = 0; k < run->count; k++) {
        const double complex mu = cexp((run->lre[k] + I * run->lim[k]) * r->period);
        size_t best = 0;
        double dist = INFINITY;
        for (size_t i = 0; i < r->count; i++) {
            const double d = cabs(mu - (r->re[i] + I * r->im[i]));
            if (!used[i] && d < dist) dist = d, best = i;
        }
        used[best] = 1;
        if (dist > worst) worst = dist, *est = r->err[best];
    }
    free(used);
    return worst;
}

static void test_circle_is_steady(void **state)
{
    (void)state;
    const circle_case cases[] = {{5, 2.0, 0.05, 1, 3200}, {5, 4.0, 0.05, 2, 800}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        circle_run run;
        circle_setup(&cases[i], &run);
        const size_t size = whirl_periodic_state_size(run.w), m = whirl_periodic_tangent_size(run.w);
        assert_int_equal(run.count, m);
        /* Newton from the steady shape with the links moved by 1e-3 (projected back onto
           the constraints by the solver): back to the steady shape */
        memcpy(run.y, run.y_steady, size * sizeof *run.y);
        for (size_t j = 0; j < size / 2; j++) run.y[j] += 1e-3 * (((j * 7) % 5) - 2.0) / cases[i].n;
        const whirl_periodic_params p = {.steps = cases[i].steps, .refine = 1, .tol = 1e-12};
        whirl_periodic_result r;
        assert_int_equal(whirl_periodic_find(run.w, run.y, &p, &r), GSL_SUCCESS);
        double change = 0;
        for (size_t j = 0; j < size; j++) change = fmax(change, fabs(run.y[j] - run.y_steady[j]));
        double est;
        const double worst = circle_mismatch(&run, &r, &est);
        print_message("# circle N = %zu, omega = %g, eps = %g, mode %d, %d steps: Newton %d "
                      "iterations from 1e-3 off, |y* - steady| = %.2g; |mu - exp(lambda T)| "
                      "<= %.2g (estimate %.2g); reciprocal pairs to %.2g; |mu|max %.12g, %s\n",
                      cases[i].n, cases[i].omega, cases[i].eps, cases[i].mode, r.steps,
                      r.iterations, change, worst, est, r.reciprocal_err, r.max_modulus,
                      whirl_floquet_verdict_name(r.verdict));
        assert_true(r.iterations >= 1);
        /* the discrete orbit is the steady shape up to the Gauss method's error at this step */
        assert_true(change < 1e-9);
        /* the multipliers agree within their own error estimate (and the central differences'
           floor, 5e-11 measured: periodic.c) */
        assert_true(worst < 2 * est + 5e-11);
        assert_true(worst < 1e-9);
        /* the derivative of the Gauss map with its projection, by the variational equations:
           symplectic to the round-off of 6400 steps and a 20 x 20 eigen-solve */
        assert_true(r.reciprocal_err < 1e-12);
        circle_free(&run);
    }
}

/* ---- a perturbed run grows as the largest multiplier says ---- */

static void test_perturbed_growth(void **state)
{
    (void)state;
    /* inside the first Mathieu tongue (omega = 2: a = 1, q = 0.2), and mode 2 of the circle
       drive at omega = 4 (a real multiplier 2.8) */
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const double up[3] = {0, 0, 1};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_line(&path, 2.0, 0.1, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 2, &path);
    double y[4], y0[4], coords[2];
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    whirl_periodic_result r;
    const whirl_periodic_params p = {.steps = 400, .refine = 1};
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
    assert_int_equal(r.verdict, WHIRL_FLOQUET_UNSTABLE);
    assert_int_equal(r.edge, WHIRL_FLOQUET_EDGE_MINUS_ONE);
    assert_true(r.re[0] < -1);
    memcpy(y0, y, sizeof y);
    /* the pendulum turned by 1e-10 rad: after 40 periods 3e-5 rad, still linear to 1e-9 */
    const double th = 1e-10;
    y[0] = sin(th), y[1] = -cos(th);
    const int periods = 40, skip = 20; /* the other multiplier, 1/mu, fades as (1/mu^2)^k */
    double norm_skip = 0, norm_end = 0;
    for (int k = 1; k <= periods; k++) {
        assert_int_equal(whirl_periodic_run(w, y, r.steps, 1), GSL_SUCCESS);
        assert_int_equal(whirl_periodic_tangent(w, y0, y, coords), GSL_SUCCESS);
        const double norm = hypot(coords[0], coords[1] / path.omega);
        if (k == skip) norm_skip = norm;
        if (k == periods) norm_end = norm;
    }
    const double growth = pow(norm_end / norm_skip, 1.0 / (periods - skip));
    print_message("# Mathieu tongue: growth per period %.10f from a run, |mu|max %.10f "
                  "(e-folding %.4g periods, %.4g time units)\n", growth, r.max_modulus,
                  r.efold_periods, r.efold_time);
    assert_true(fabs(growth - r.max_modulus) < 1e-6 * r.max_modulus);
    assert_true(fabs(r.efold_periods - 1 / log(r.max_modulus)) < 1e-12);
    whirl_periodic_free(w);
    whirl_chain_free(c);

    const circle_case cc = {5, 4.0, 0.05, 2, 800};
    circle_run run;
    circle_setup(&cc, &run);
    const size_t size = whirl_periodic_state_size(run.w), m = whirl_periodic_tangent_size(run.w);
    memcpy(run.y, run.y_steady, size * sizeof *run.y);
    const whirl_periodic_params pc = {.steps = cc.steps, .refine = 1};
    assert_int_equal(whirl_periodic_find(run.w, run.y, &pc, &r), GSL_SUCCESS);
    assert_int_equal(r.verdict, WHIRL_FLOQUET_UNSTABLE);
    double *yp = malloc(size * sizeof *yp), *x = malloc(m * sizeof *x);
    memcpy(yp, run.y, size * sizeof *yp);
    for (size_t j = 0; j < size / 2; j++) yp[j] += 1e-11 * (((j * 7) % 5) - 2.0);
    assert_int_equal(whirl_dyn_project(whirl_periodic_dyn(run.w), 0, yp), GSL_SUCCESS);
    const int runs = 14, first = 8; /* the second multiplier fades as (|mu_2| / |mu_1|)^k */
    double n_first = 0, n_last = 0;
    for (int k = 1; k <= runs; k++) {
        assert_int_equal(whirl_periodic_run(run.w, yp, r.steps, 1), GSL_SUCCESS);
        whirl_periodic_tangent(run.w, run.y, yp, x);
        double norm = 0;
        for (size_t j = 0; j < m; j++) norm += x[j] * x[j] / (j < m / 2 ? 1 : cc.omega * cc.omega);
        norm = sqrt(norm);
        if (k == first) n_first = norm;
        if (k == runs) n_last = norm;
    }
    const double g2 = pow(n_last / n_first, 1.0 / (runs - first));
    print_message("# circle mode 2, N = 5, omega = 4: growth per period %.8f from a run, "
                  "|mu|max %.8f (the next %.4g)\n", g2, r.max_modulus, hypot(r.re[2], r.im[2]));
    assert_true(fabs(g2 - r.max_modulus) < 1e-3 * r.max_modulus);
    free(yp);
    free(x);
    circle_free(&run);
}

/* ---- the two monodromies of one motion ---- */

/* The variational equations and the central differences give the derivative of the same
 * discrete period map: the matrices agree to the differences' floor (1e-11 relative, periodic.c).
 * An ellipse, N = 3 in 3D, from the hanging chain. */
static void test_variational_against_differences(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_ellipse(&path, 2.5, 0.05, 0.03), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    const size_t size = whirl_periodic_state_size(w), m = whirl_periodic_tangent_size(w);
    double *y = malloc(size * sizeof *y), *mono = malloc(m * m * sizeof *mono);
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    whirl_periodic_result r;
    whirl_periodic_params p = {.steps = 400, .refine = 0, .tol = 1e-12};
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
    assert_true(r.iterations >= 2);
    memcpy(mono, whirl_periodic_monodromy(w), m * m * sizeof *mono);
    const double recip_var = r.reciprocal_err;
    p.monodromy = WHIRL_MONODROMY_DIFFERENCES;
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
    assert_int_equal(r.iterations, 0); /* the motion of the first solve */
    const double *fd = whirl_periodic_monodromy(w);
    double worst = 0, largest = 0;
    for (size_t k = 0; k < m * m; k++) {
        worst = fmax(worst, fabs(mono[k] - fd[k]));
        largest = fmax(largest, fabs(mono[k]));
    }
    print_message("# ellipse N = 3: monodromy by the variational equations against central "
                  "differences: %.2g of the largest entry %.3g; reciprocal pairs %.2g and %.2g\n",
                  worst, largest, recip_var, r.reciprocal_err);
    assert_true(worst < 1e-9 * largest);
    /* a pair of multipliers near +1 (the ellipse is near the circle's symmetry of rotation
       about the axis) is sensitive to the round-off of M: pairs to 1e-12 here, both ways */
    assert_true(recip_var < 1e-10);
    p.monodromy = (whirl_monodromy_method)7;
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_EINVAL);
    free(y);
    free(mono);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* ---- Newton that does not converge ---- */

static void test_newton_failure(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_ellipse(&path, 3.0, 0.1, 0.05), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 3, &path);
    const size_t size = whirl_periodic_state_size(w);
    double *y = malloc(size * sizeof *y);
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    whirl_periodic_result r;
    /* one iteration from the hanging chain cannot reach the orbit to 1e-14 */
    const whirl_periodic_params p = {.steps = 200, .max_iter = 1, .tol = 1e-14};
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_EMAXITER);
    assert_int_equal(r.count, 0);
    assert_null(r.re);
    assert_non_null(strstr(whirl_last_error(), "residual"));
    assert_null(whirl_periodic_monodromy(w));
    print_message("# %s\n", whirl_last_error());
    /* bad parameters */
    const whirl_periodic_params bad = {.steps = 3};
    assert_int_equal(whirl_periodic_find(w, y, &bad, &r), GSL_EINVAL);
    y[0] = NAN;
    assert_int_equal(whirl_periodic_find(w, y, NULL, &r), GSL_EINVAL);
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mathieu_tongues),
        cmocka_unit_test(test_inverted_fast_shaking),
        cmocka_unit_test(test_inverted_fast_shaking_chains),
        cmocka_unit_test(test_circle_is_steady),
        cmocka_unit_test(test_perturbed_growth),
        cmocka_unit_test(test_variational_against_differences),
        cmocka_unit_test(test_newton_failure),
    };
    return cmocka_run_group_tests_name("floquet", tests, NULL, NULL);
}
