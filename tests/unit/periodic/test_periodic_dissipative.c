/* Tests of the periodic motions of the damped and dragged chain (whirl_periodic_alloc_model)
 * against results that no setting of the method can produce by itself:
 *  - the dissipative forces' Jacobian (the drag's derived by hand, src/periodic/dissipation.c)
 *    against central differences of the forces, and the monodromy of the variational equations
 *    against the central differences of the period map (whirl_dyn_rhs's forces: the time
 *    integrator's, not the module's own);
 *  - the hanging pendulum without drive is the damped oscillator theta'' + 2 gamma theta' +
 *    (g / l) theta = 0, gamma = c l / (2 m) (linear drag -c l v) or D / (2 m l^2) (the internal
 *    damping of the top joint, 2D): multipliers exp(lambda T), lambda = -gamma +- i sqrt(g / l -
 *    gamma^2); every multiplier of the hanging chain inside the unit circle;
 *  - the circle drive with drag and damping: its periodic motion is the steady shape of
 *    whirl_driven_solve with the same drag, and its multipliers are exp(lambda T) of the
 *    steady linearisation with drag and damping (whirl_stability_driven_mode: link angles, the
 *    damping matrix and the drag's position part, one eigen-solve);
 *  - the events of the continuation: a torus of the dragged circle drive in the rate where the
 *    steady linearisation's growth rate passes 0 (Brent on whirl_stability_driven_mode, a
 *    different formulation), confirmed by perturbed runs either side; a period doubling of the
 *    damped shaken pendulum where the undamped one under the gravity 1 - D^2/4 has the trace
 *    -2 cosh(D T / 2); a fold of the dragged circle drive at whirl_driven_branch's fold. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_roots.h>

#include "periodic/periodic_internal.h"
#include "whirl/driven.h"
#include "whirl/periodic.h"
#include "whirl/stability.h"

/* A chain of n links of unequal lengths and masses. */
static whirl_chain *uneven_chain(size_t n)
{
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    assert_non_null(c);
    for (size_t i = 0; i < n; i++) {
        c->length[i] = (1.0 + 0.3 * (double)((i * 5) % 3)) / (double)n;
        c->mass[i] = (1.0 + 0.4 * (double)((i * 3) % 4)) / (double)n;
    }
    return c;
}

/* The root of f in [lo, hi] (a sign change there, asserted) by Brent's method to tol. */
static double brent(gsl_function *f, double lo, double hi, double tol)
{
    assert_true((GSL_FN_EVAL(f, lo) < 0) != (GSL_FN_EVAL(f, hi) < 0));
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    assert_int_equal(gsl_root_fsolver_set(s, f, lo, hi), GSL_SUCCESS);
    for (int i = 0; i < 100; i++) {
        assert_int_equal(gsl_root_fsolver_iterate(s), GSL_SUCCESS);
        lo = gsl_root_fsolver_x_lower(s), hi = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(lo, hi, tol, 0) == GSL_SUCCESS) break;
    }
    const double root = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    return root;
}

/* The workspace of chain c in dim with the drags c1, c2 and the damping D, the pivot on the
 * ellipse (a, b) at omega (2D: b = 0, the line along x). */
static whirl_periodic *damped_on_ellipse(whirl_chain *c, int dim, double c1, double c2,
                                         double D, double omega, double a, double b)
{
    const whirl_model model = {.chain = c, .dim = dim, .air_drag = c1, .air_drag_quadratic = c2,
                               .internal_damping = D};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_ellipse(&path, omega, a, dim == 3 ? b : 0), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    assert_non_null(w);
    assert_int_equal(whirl_periodic_dissipative(w), 1);
    return w;
}

/* ---- the forces' Jacobian against central differences ---- */

static void test_force_jacobian(void **state)
{
    (void)state;
    const size_t n = 4;
    whirl_chain *c = uneven_chain(n);
    for (int dim = 2; dim <= 3; dim++) {
        whirl_periodic *w = damped_on_ellipse(c, dim, 0.7, 1.3, 0.05, 2.3, 0.2, 0.1);
        const size_t size = whirl_periodic_state_size(w), sh = size / 2;
        double *y = malloc(size * sizeof *y), *yp = malloc(size * sizeof *y);
        double *dq = malloc(sh * sizeof *dq), *dv = malloc(sh * sizeof *dv);
        double fp[12], fm[12], f0[12], a[4], u[12], ap[4], up[12], jv[12];
        /* any state: the forces do not need the constraints */
        for (size_t q = 0; q < size; q++) y[q] = 0.3 * sin(1.7 * (double)q + 0.4) - (q % 3 == 2 ? 0.2 : 0);
        for (size_t q = 0; q < sh; q++) dq[q] = cos(0.9 * (double)q), dv[q] = sin(1.3 * (double)q + 1);
        const double t = 0.37;
        periodic_diss_forces(w, t, y, f0, a, u);
        periodic_diss_apply(w, a, u, dq, dv, 1, jv);
        const double h = 1e-5;
        double worst = 0, big = 0;
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            for (size_t q = 0; q < sh; q++) yp[q] = y[q] + sgn * h * dq[q], yp[sh + q] = y[sh + q] + sgn * h * dv[q];
            periodic_diss_forces(w, t, yp, sgn > 0 ? fp : fm, ap, up);
        }
        for (size_t k = 0; k < 3 * n; k++) {
            const double fd = (fp[k] - fm[k]) / (2 * h);
            worst = fmax(worst, fabs(fd - jv[k]));
            big = fmax(big, fabs(jv[k]));
        }
        print_message("# %dD: the dissipative forces' derivative against central differences: "
                      "%.2g of its largest component %.3g\n", dim, worst / big, big);
        assert_true(big > 0.1);
        assert_true(worst < 1e-8 * big); /* the differences' h^2 error ~ 1e-10 */
        free(y), free(yp), free(dq), free(dv);
        whirl_periodic_free(w);
    }
    whirl_chain_free(c);
}

/* ---- the two monodromies of a damped motion ---- */

static void test_variational_against_differences(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        whirl_chain *c = uneven_chain(3);
        whirl_periodic *w = damped_on_ellipse(c, dim, 0.3, 0.5, 0.01, 1.7, 0.1, 0.06);
        const size_t size = whirl_periodic_state_size(w), m = whirl_periodic_tangent_size(w);
        double *y = malloc(size * sizeof *y), *mono = malloc(m * m * sizeof *mono);
        assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
        whirl_periodic_params p = {.steps = 400, .refine = 0};
        whirl_periodic_result r;
        assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
        memcpy(mono, whirl_periodic_monodromy(w), m * m * sizeof *mono);
        p.monodromy = WHIRL_MONODROMY_DIFFERENCES;
        assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
        const double *md = whirl_periodic_monodromy(w);
        double worst = 0, big = 0;
        for (size_t k = 0; k < m * m; k++)
            worst = fmax(worst, fabs(md[k] - mono[k])), big = fmax(big, fabs(mono[k]));
        print_message("# damped %dD, N = 3 on an ellipse: variational against central "
                      "differences %.2g of the largest entry %.3g; |mu|max %.10f (%s)\n", dim,
                      worst / big, big, r.max_modulus, whirl_floquet_verdict_name(r.verdict));
        assert_true(worst < 1e-9 * big); /* the differences' floor ~1e-10 (periodic.c) */
        assert_true(r.max_modulus < 1);
        free(y), free(mono);
        whirl_periodic_free(w);
        whirl_chain_free(c);
    }
}

/* ---- the hanging chain without drive: the damped oscillator ---- */

/* The multipliers of the hanging chain (no drive: a path of zero amplitude at the rate omega). */
static void hanging(const whirl_model *model, double omega, whirl_periodic_result *r,
                    whirl_periodic **out)
{
    whirl_pivot_path path;
    const double up[3] = {0, 0, 1};
    assert_int_equal(whirl_pivot_line(&path, omega, 0, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc_model(model, &path);
    assert_non_null(w);
    double y[6 * 8];
    assert_true(whirl_periodic_state_size(w) <= sizeof y / sizeof y[0]);
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    const whirl_periodic_params p = {.steps = 800, .refine = 1};
    assert_int_equal(whirl_periodic_find(w, y, &p, r), GSL_SUCCESS);
    *out = w;
}

static void test_damped_oscillator(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0); /* l = m = g = 1 */
    const double omega = 1.3, T = 2 * M_PI / omega;
    const struct {
        int dim;
        double c, D, gamma;
        const char *name;
    } rows[] = {{2, 0.2, 0, 0.1, "2D, drag c = 0.2"},
                {3, 0.2, 0, 0.1, "3D, drag c = 0.2"},
                {2, 0, 0.3, 0.15, "2D, internal damping D = 0.3"},
                {2, 0.1, 0.1, 0.1, "2D, both 0.1"}};
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        const whirl_model model = {.chain = c, .dim = rows[k].dim, .air_drag = rows[k].c,
                                   .internal_damping = rows[k].D};
        whirl_periodic_result r;
        whirl_periodic *w;
        hanging(&model, omega, &r, &w);
        const double g = rows[k].gamma, wd = sqrt(1 - g * g);
        const double complex mu = cexp((-g + I * wd) * T);
        double worst = 0, est = 0;
        for (size_t i = 0; i < r.count; i++) {
            const double complex z = r.re[i] + I * r.im[i];
            const double d = fmin(cabs(z - mu), cabs(z - conj(mu)));
            if (d > worst) worst = d, est = r.err[i];
        }
        print_message("# hanging pendulum, %s: |mu| %.15f, exp(-gamma T) %.15f; |mu - "
                      "exp(lambda T)| <= %.2g (estimate %.2g); %s, reciprocal-pair distance "
                      "%.3g\n", rows[k].name, r.max_modulus, exp(-g * T), worst, est,
                      whirl_floquet_verdict_name(r.verdict), r.reciprocal_err);
        assert_true(worst < 1e-10);
        assert_true(worst < 2 * est + 1e-12);
        assert_int_equal(r.verdict, WHIRL_FLOQUET_STABLE);
        whirl_periodic_free(w);
    }
    whirl_chain_free(c);
    /* N = 3, 2D and 3D: every multiplier inside */
    whirl_chain *c3 = uneven_chain(3);
    for (int dim = 2; dim <= 3; dim++) {
        const whirl_model model = {.chain = c3, .dim = dim, .air_drag = 0.1,
                                   .air_drag_quadratic = 0.2,
                                   .internal_damping = dim == 2 ? 0.01 : 0};
        whirl_periodic_result r;
        whirl_periodic *w;
        hanging(&model, omega, &r, &w);
        print_message("# hanging N = 3, %dD, damped: |mu|max %.12f, least %.3g\n", dim,
                      r.max_modulus, hypot(r.re[r.count - 1], r.im[r.count - 1]));
        assert_true(r.max_modulus < 1 - 1e-3);
        assert_int_equal(r.verdict, WHIRL_FLOQUET_STABLE);
        whirl_periodic_free(w);
    }
    whirl_chain_free(c3);
}

/* ---- the circle drive with drag and damping against the steady shape ---- */

typedef struct circle_case {
    size_t n;
    double omega, eps, c, c2, D;
    int mode, side, steps;
} circle_case;

/* The steady shape of the case by whirl_driven_mode and whirl_driven_solve (links: 3 n), and
 * the linearisation's eigenvalues (count, re, im owned by st). */
static void steady_of(const whirl_chain *c, const circle_case *cc, whirl_stability *st,
                      double *links, size_t *count, const double **re, const double **im)
{
    const whirl_driven_params dp = {.omega = cc->omega, .drive_radius = cc->eps,
                                    .air_drag = cc->c, .air_drag_quadratic = cc->c2};
    whirl_driven_info info, solved;
    assert_int_equal(whirl_driven_mode(c, &dp, cc->mode, cc->side, &info), GSL_SUCCESS);
    assert_int_equal(whirl_driven_solve(c, &dp, info.tip, &solved), GSL_SUCCESS);
    const size_t n = c->n;
    double *s = malloc(4 * (n + 1) * sizeof *s), *x = s + n + 1, *y = x + n + 1, *z = y + n + 1;
    double *tension = malloc((n + 1) * sizeof *tension);
    const double tip[2] = {solved.tip[0], solved.tip[1]};
    assert_int_equal(whirl_driven_sample(c, &dp, tip, n + 1, s, x, y, z, tension), GSL_SUCCESS);
    assert_int_equal(whirl_shape_links(n, x, y, z, links), GSL_SUCCESS);
    const whirl_model model = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                               .omega = cc->omega, .drive_radius = cc->eps, .air_drag = cc->c,
                               .air_drag_quadratic = cc->c2, .internal_damping = cc->D};
    double growth;
    assert_int_equal(whirl_stability_linearise_3d(st, &model, x, y, z), GSL_SUCCESS);
    (void)growth;
    assert_int_equal(whirl_stability_eigenvalues(st, count, re, im), GSL_SUCCESS);
    free(s), free(tension);
}

static void test_circle_with_drag(void **state)
{
    (void)state;
    const circle_case cases[] = {{4, 2.0, 0.1, 0.05, 0.02, 0.002, 1, 1, 3200},
                                 {3, 3.5, 0.05, 0.05, 0, 0.001, 2, 1, 1600}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const circle_case *cc = &cases[k];
        whirl_chain *c = whirl_chain_alloc_uniform(cc->n, 0);
        whirl_stability *st = whirl_stability_alloc(cc->n);
        double *links = malloc(3 * cc->n * sizeof *links);
        size_t count;
        const double *lre, *lim;
        steady_of(c, cc, st, links, &count, &lre, &lim);
        const whirl_model model = {.chain = c, .dim = 3, .air_drag = cc->c,
                                   .air_drag_quadratic = cc->c2, .internal_damping = cc->D};
        whirl_pivot_path path;
        assert_int_equal(whirl_pivot_circle(&path, cc->omega, cc->eps), GSL_SUCCESS);
        whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
        assert_non_null(w);
        const size_t size = whirl_periodic_state_size(w), m = whirl_periodic_tangent_size(w);
        assert_int_equal(count, m);
        double *y = malloc(size * sizeof *y), *ys = malloc(size * sizeof *ys);
        assert_int_equal(whirl_dyn_state_from_shape(whirl_periodic_dyn(w), 0, links, cc->omega,
                                                    ys), GSL_SUCCESS);
        memcpy(y, ys, size * sizeof *y);
        for (size_t j = 0; j < size / 2; j++) y[j] += 1e-3 * (((j * 7) % 5) - 2.0) / cc->n;
        const whirl_periodic_params p = {.steps = cc->steps, .refine = 1, .tol = 1e-12};
        whirl_periodic_result r;
        assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
        double change = 0;
        for (size_t j = 0; j < size; j++) change = fmax(change, fabs(y[j] - ys[j]));
        int *used = calloc(m, sizeof *used);
        double worst = 0, est = 0;
        for (size_t i = 0; i < count; i++) {
            const double complex mu = cexp((lre[i] + I * lim[i]) * r.period);
            size_t best = 0;
            double dist = INFINITY;
            for (size_t j = 0; j < m; j++) {
                const double d = cabs(mu - (r.re[j] + I * r.im[j]));
                if (!used[j] && d < dist) dist = d, best = j;
            }
            used[best] = 1;
            if (dist > worst) worst = dist, est = r.err[best];
        }
        print_message("# circle with drag N = %zu, omega = %g, eps = %g, c = %g, c2 = %g, D = "
                      "%g, mode %d: |y* - steady| = %.2g; |mu - exp(lambda T)| <= %.2g "
                      "(estimate %.2g); |mu|max %.12f (%s); reciprocal-pair distance %.3g\n",
                      cc->n, cc->omega, cc->eps, cc->c, cc->c2, cc->D, cc->mode, change, worst,
                      est, r.max_modulus, whirl_floquet_verdict_name(r.verdict),
                      r.reciprocal_err);
        assert_true(change < 1e-9);
        assert_true(worst < 2 * est + 5e-11);
        assert_true(worst < 1e-10);
        free(used), free(y), free(ys), free(links);
        whirl_periodic_free(w);
        whirl_stability_free(st);
        whirl_chain_free(c);
    }
}

/* ---- a torus bifurcation of the damped circle drive ---- */

/* N = 3, eps = 0.05, c = 0.05: the steady shape of mode 2 with its seed's tip opposite the
 * pivot is stable at omega = 2.8 (every eigenvalue of its linearisation at Re = -c / 2, the
 * uniform drag's) and loses its stability near 2.85 by a complex pair (Im ~ 1.7: the multiplier
 * exp(lambda T) far from +-1) crossing the imaginary axis, after two pairs met. */
#define TORUS_N 3
static const circle_case torus_case = {TORUS_N, 2.8, 0.05, 0.05, 0, 0, 2, -1, 400};

/* The steady linearisation's growth rate at omega (whirl_stability_driven_mode). */
static double steady_growth(double omega, void *chain)
{
    whirl_stability *st = whirl_stability_alloc(TORUS_N);
    const whirl_model model = {.chain = chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                               .omega = omega, .drive_radius = torus_case.eps,
                               .air_drag = torus_case.c};
    double growth;
    assert_int_equal(whirl_stability_driven_mode(st, &model, torus_case.mode, torus_case.side,
                                                 NULL, &growth), GSL_SUCCESS);
    whirl_stability_free(st);
    return growth;
}

typedef struct torus_seen {
    int events, torus; /* events, and those of the kind looked for */
    double at, err, mu;
} torus_seen;

/* The rows of a branch: the events counted, the first of kind kept (in the fields of
 * torus_seen). */
static int event_row(void *data, const whirl_cycle_point *p, whirl_cycle_event kind)
{
    torus_seen *s = data;
    if (p->event == WHIRL_CYCLE_POINT) return 0;
    s->events++;
    if (p->event == kind && s->torus++ == 0)
        s->at = p->parameter, s->err = p->err, s->mu = p->max_modulus;
    return 0;
}

static int torus_row(void *data, const whirl_cycle_point *p)
{
    return event_row(data, p, WHIRL_CYCLE_TORUS);
}

/* The growth per period of a perturbed run from the periodic motion at omega, against |mu|max:
 * the area of two consecutive perturbations (in the tangent coordinates) grows by |mu1 mu2|
 * per period once they lie in the plane of the leading pair (the others fading as |mu3| / |mu1|
 * per period), |mu|^2 for a complex pair whatever its phase; their Gram determinant, the area
 * squared, by |mu|^4. */
static void perturbed_growth(whirl_chain *c, double omega, int first, int last, double size0,
                             double *growth, double *mu)
{
    const whirl_model model = {.chain = c, .dim = 3, .air_drag = torus_case.c};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, omega, torus_case.eps), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    const size_t size = whirl_periodic_state_size(w), m = whirl_periodic_tangent_size(w);
    double *y = malloc(size * sizeof *y), *yp = malloc(size * sizeof *yp);
    double *a = malloc(m * sizeof *a), *b = malloc(m * sizeof *b);
    assert_int_equal(whirl_periodic_start_steady(w, torus_case.mode, torus_case.side, y),
                     GSL_SUCCESS);
    whirl_periodic_result r;
    const whirl_periodic_params p = {.steps = torus_case.steps, .refine = 1};
    assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
    *mu = r.max_modulus;
    memcpy(yp, y, size * sizeof *yp);
    for (size_t j = 0; j < size / 2; j++) yp[j] += size0 * (((j * 7) % 5) - 2.0);
    assert_int_equal(whirl_dyn_project(whirl_periodic_dyn(w), 0, yp), GSL_SUCCESS);
    double g_first = 0, g_last = 0;
    for (int k = 1; k <= last + 1; k++) {
        assert_int_equal(whirl_periodic_run(w, yp, r.steps, 1), GSL_SUCCESS);
        memcpy(a, b, m * sizeof *a);
        whirl_periodic_tangent(w, y, yp, b);
        for (size_t j = m / 2; j < m; j++) b[j] /= omega; /* rates over omega */
        if (k == first + 1 || k == last + 1) {
            double aa = 0, bb = 0, ab = 0;
            for (size_t j = 0; j < m; j++) aa += a[j] * a[j], bb += b[j] * b[j], ab += a[j] * b[j];
            *(k == first + 1 ? &g_first : &g_last) = aa * bb - ab * ab;
        }
    }
    *growth = pow(g_last / g_first, 1.0 / (4.0 * (last - first))); /* area^2 ~ |mu|^4 */
    free(y), free(yp), free(a), free(b);
    whirl_periodic_free(w);
}

static void test_torus_located(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(TORUS_N, 0);
    /* the reference: the steady growth rate's root, Brent on omega to 1e-12 */
    gsl_function f = {steady_growth, c};
    const double ref = brent(&f, 2.849, 2.9, 1e-13);
    /* the continuation of the periodic motion in the rate from 2.8 */
    const whirl_model model = {.chain = c, .dim = 3, .air_drag = torus_case.c};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, torus_case.omega, torus_case.eps), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    assert_int_equal(whirl_periodic_start_steady(w, torus_case.mode, torus_case.side, y),
                     GSL_SUCCESS);
    const whirl_cycle_params cp = {.parameter = WHIRL_CYCLE_OMEGA, .min = 2.8, .max = 2.9,
                                   .direction = 1, .step = 0.02, .steps = torus_case.steps};
    torus_seen seen = {0};
    assert_int_equal(whirl_periodic_path(w, y, &cp, torus_row, &seen, NULL, NULL), GSL_SUCCESS);
    print_message("# damped circle N = 3, eps 0.05, c 0.05, mode 2 side -1: torus at omega = "
                  "%.12f (estimate %.2g, |mu|max %.12f) from the continuation; %.12f from the "
                  "steady growth rate's root; difference %.2g; events %d\n", seen.at, seen.err,
                  seen.mu, ref, seen.at - ref, seen.events);
    assert_int_equal(seen.torus, 1);
    assert_int_equal(seen.events, 1);
    assert_true(fabs(seen.at - ref) < 1e-8);
    assert_true(fabs(seen.mu - 1) < 1e-8);
    /* perturbed runs either side: on the stable side the leading pair is only 1.04 times the
       next (the pairs met at 2.848), so the run is long (0.955^300 ~ 1e-6 of the others left);
       on the unstable side 0.86 per period, and the start small (1.1^120 ~ 1e5) */
    const double side_at[2] = {ref - 0.002, ref + 0.03}, size0[2] = {1e-6, 1e-12};
    const int first[2] = {300, 60}, last[2] = {600, 120};
    for (int k = 0; k < 2; k++) {
        double growth, mu;
        perturbed_growth(c, side_at[k], first[k], last[k], size0[k], &growth, &mu);
        print_message("# omega = %.6f: growth per period %.8f from a perturbed run, |mu|max "
                      "%.8f\n", side_at[k], growth, mu);
        assert_true(k == 0 ? mu < 1 && growth < 1 : mu > 1 && growth > 1);
        assert_true(fabs(growth - mu) < 1e-4 * mu);
    }
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* ---- a period doubling of the damped shaken pendulum ---- */

/* The pendulum (l = m = 1) shaken vertically, A cos(omega t), with the internal damping D of its
 * joint (2D: no coupling to the pivot's velocity, unlike the air drag): about the hanging state
 * theta'' + D theta' + (1 + p_z''(t)) theta = 0, and theta = exp(-D t / 2) phi gives the
 * undamped phi'' + (1 - D^2 / 4 + p_z''(t)) phi = 0, the pendulum under the gravity
 * 1 - D^2 / 4: a multiplier of theta is -1 where that undamped pendulum's trace is
 * -2 cosh(D T / 2). */
#define PD_OMEGA 1.8
#define PD_DAMPING 0.2

static double reduced_trace(double amplitude, void *data)
{
    (void)data;
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    c->gravity = 1 - PD_DAMPING * PD_DAMPING / 4;
    const double up[3] = {0, 0, 1}, T = 2 * M_PI / PD_OMEGA;
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_line(&path, PD_OMEGA, amplitude, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc(c, 2, &path);
    double tr[2];
    for (int k = 0; k < 2; k++) { /* 800 and 1600 steps, extrapolated (order 4) */
        double y[4];
        assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
        const whirl_periodic_params p = {.steps = 800 << k, .refine = 0};
        whirl_periodic_result r;
        assert_int_equal(whirl_periodic_find(w, y, &p, &r), GSL_SUCCESS);
        tr[k] = r.re[0] + r.re[1];
    }
    whirl_periodic_free(w);
    whirl_chain_free(c);
    return tr[1] + (tr[1] - tr[0]) / 15 + 2 * cosh(PD_DAMPING * T / 2);
}

static int pd_row(void *data, const whirl_cycle_point *p)
{
    return event_row(data, p, WHIRL_CYCLE_PERIOD_DOUBLING);
}

static int fold_row(void *data, const whirl_cycle_point *p)
{
    return event_row(data, p, WHIRL_CYCLE_FOLD);
}

static void test_period_doubling_located(void **state)
{
    (void)state;
    /* the reference: Brent on the undamped pendulum's trace under the reduced gravity */
    gsl_function f = {reduced_trace, NULL};
    const double ref = brent(&f, 0.05, 0.4, 1e-14);
    /* the damped hanging branch followed in the amplitude */
    whirl_chain *c = whirl_chain_alloc_uniform(1, 0);
    const whirl_model model = {.chain = c, .dim = 2, .internal_damping = PD_DAMPING};
    const double up[3] = {0, 0, 1};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_line(&path, PD_OMEGA, 0.01, up), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    double y[4];
    assert_int_equal(whirl_periodic_start_vertical(w, 0, y), GSL_SUCCESS);
    const whirl_cycle_params cp = {.parameter = WHIRL_CYCLE_AMPLITUDE, .min = 0, .max = 0.4,
                                   .direction = 1, .steps = 800};
    torus_seen seen = {0};
    assert_int_equal(whirl_periodic_path(w, y, &cp, pd_row, &seen, NULL, NULL), GSL_SUCCESS);
    print_message("# damped shaken pendulum, D = %g, omega = %g: period doubling at A = %.12f "
                  "(estimate %.2g, |mu|max %.12f) from the continuation; %.12f from the "
                  "undamped pendulum under the gravity 1 - D^2/4; difference %.2g\n",
                  PD_DAMPING, PD_OMEGA, seen.at, seen.err, seen.mu, ref, seen.at - ref);
    assert_int_equal(seen.torus, 1);
    assert_int_equal(seen.events, 1);
    assert_true(fabs(seen.at - ref) < 1e-8);
    assert_true(fabs(seen.mu - 1) < 1e-8);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

/* ---- a fold of cycles of the dragged circle drive ---- */

/* N = 2, eps = 0.05, c = 0.02: the shape of mode 1 with its seed's tip opposite the pivot,
 * followed down in the rate from 1.3, folds near 1.229 (whirl_driven_branch's fold with the same
 * drag: the fold function of the shape's force balance, another formulation); the periodic
 * branch must fold there with a multiplier through +1. */
static void test_fold_located(void **state)
{
    (void)state;
    const double omega = 1.3, eps = 0.05, drag = 0.02;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    const whirl_driven_params dp = {.omega = omega, .drive_radius = eps, .air_drag = drag};
    whirl_driven_info info;
    assert_int_equal(whirl_driven_mode(c, &dp, 1, -1, &info), GSL_SUCCESS);
    whirl_driven_curve *curve = whirl_driven_curve_alloc(1000);
    assert_int_equal(whirl_driven_branch(c, &dp, &info, -1, 1.1, 1.5, 0.02, curve), GSL_SUCCESS);
    assert_int_equal(curve->n_folds, 1);
    const double steady_fold = curve->fold_omega[0];
    const whirl_model model = {.chain = c, .dim = 3, .air_drag = drag};
    whirl_pivot_path path;
    assert_int_equal(whirl_pivot_circle(&path, omega, eps), GSL_SUCCESS);
    whirl_periodic *w = whirl_periodic_alloc_model(&model, &path);
    double *y = malloc(whirl_periodic_state_size(w) * sizeof *y);
    assert_int_equal(whirl_periodic_start_steady(w, 1, -1, y), GSL_SUCCESS);
    const whirl_cycle_params cp = {.parameter = WHIRL_CYCLE_OMEGA, .min = 1.1, .max = 1.5,
                                   .direction = -1};
    torus_seen seen = {0};
    assert_int_equal(whirl_periodic_path(w, y, &cp, fold_row, &seen, NULL, NULL), GSL_SUCCESS);
    print_message("# dragged circle drive N = 2, eps = 0.05, c = 0.02: fold at omega = %.12f "
                  "(estimate %.2g) from the continuation; %.12f from whirl_driven_branch; "
                  "difference %.2g\n", seen.at, seen.err, steady_fold, seen.at - steady_fold);
    assert_int_equal(seen.torus, 1);
    assert_int_equal(seen.events, 1);
    assert_true(fabs(seen.at - steady_fold) < 1e-8);
    whirl_driven_curve_free(curve);
    free(y);
    whirl_periodic_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_force_jacobian),
        cmocka_unit_test(test_variational_against_differences),
        cmocka_unit_test(test_damped_oscillator),
        cmocka_unit_test(test_circle_with_drag),
        cmocka_unit_test(test_torus_located),
        cmocka_unit_test(test_period_doubling_located),
        cmocka_unit_test(test_fold_located),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
