/* Tests of the modes of the linearisation (src/stability/stability_modes.c):
 *  - residual of each eigenpair on the first-order form built here from M, G, C, K (GSL's LU);
 *    the eigenvalues those of whirl_stability_eigenvalues; the normalisation; the node
 *    displacements from the link angles through the chain's geometry written here;
 *  - Krein signatures against those of the window search's reduced problem (whirl_windows_spectrum,
 *    an independent eigen-solve of lambda^2), and all +1 about a minimum of the amended potential;
 *  - a neutral mode's frequency: a nonlinear run of the dynamics module (Cartesian formulation,
 *    co-rotating frame) started at tiny amplitude along the mode (positions and velocities),
 *    its oscillation frequency from zero crossings against Im lambda;
 *  - an unstable mode's growth: whirl_stability_run_shape seeded along the mode (params.along)
 *    against Re lambda. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_math.h>

#include "whirl/dynamics.h"
#include "whirl/integrator.h"
#include "whirl/stability.h"

static whirl_model model_of(const whirl_chain *c, double omega, double damping)
{
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = omega;
    m.internal_damping = damping;
    return m;
}

/* A = [[0, I], [-M^-1 K, -M^-1 (G + C)]] (row-major 4N x 4N) by GSL's LU of M */
static double *first_order_form(const whirl_stability *w, size_t n)
{
    const size_t q = 2 * n, y = 4 * n;
    const double *mm = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
    const double *gg = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
    const double *cc = whirl_stability_get_matrix(w, WHIRL_STABILITY_DAMPING);
    const double *kk = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    double *a = calloc(y * y, sizeof *a);
    gsl_matrix *lu = gsl_matrix_alloc(q, q);
    gsl_permutation *p = gsl_permutation_alloc(q);
    gsl_vector *b = gsl_vector_alloc(q), *x = gsl_vector_alloc(q);
    memcpy(lu->data, mm, q * q * sizeof(double));
    int sign;
    gsl_linalg_LU_decomp(lu, p, &sign);
    for (size_t i = 0; i < q; i++) a[i * y + q + i] = 1;
    for (size_t j = 0; j < y; j++) {
        for (size_t i = 0; i < q; i++)
            b->data[i] = j < q ? kk[i * q + j] : gg[i * q + j - q] + cc[i * q + j - q];
        gsl_linalg_LU_solve(lu, p, b, x);
        for (size_t i = 0; i < q; i++) a[(q + i) * y + j] = -x->data[i];
    }
    gsl_matrix_free(lu);
    gsl_permutation_free(p);
    gsl_vector_free(b);
    gsl_vector_free(x);
    return a;
}

/* The residual ||A z - lambda z|| / (||A||_F ||z||) of mode k, z = (v, lambda v), and checks of
 * the node displacements and the normalisation. Returns the residual. */
static double check_mode(const whirl_stability *w, const whirl_stability_modes *md, size_t k,
                         const double *a)
{
    const size_t n = md->links, q = 2 * n, y = 4 * n, nn = 3 * (n + 1);
    const double lr = md->re[k], li = md->im[k];
    double zr[4 * 64], zi[4 * 64];
    assert_true(n <= 64);
    for (size_t i = 0; i < q; i++) {
        zr[i] = md->angle_re[k * q + i];
        zi[i] = md->angle_im[k * q + i];
        zr[q + i] = lr * zr[i] - li * zi[i];
        zi[q + i] = lr * zi[i] + li * zr[i];
    }
    double res = 0, an = 0, zn = 0;
    for (size_t i = 0; i < y; i++) {
        double sr = -(lr * zr[i] - li * zi[i]), si = -(lr * zi[i] + li * zr[i]);
        for (size_t j = 0; j < y; j++) {
            sr += a[i * y + j] * zr[j];
            si += a[i * y + j] * zi[j];
            an += a[i * y + j] * a[i * y + j];
        }
        res += sr * sr + si * si;
        zn += zr[i] * zr[i] + zi[i] * zi[i];
    }
    /* node displacements: the chart of stability.h rebuilt here from the nodes */
    const double *nx, *ny, *nz;
    whirl_stability_nodes(w, &nx, &ny, &nz);
    double dr[3] = {0, 0, 0}, di[3] = {0, 0, 0}, big = 0;
    for (size_t j = 0; j < n; j++) {
        double u[3] = {nx[j + 1] - nx[j], ny[j + 1] - ny[j], nz[j + 1] - nz[j]};
        const double l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int c = 0; c < 3; c++) u[c] /= l;
        double e2[3] = {0, 1, 0};
        if (fabs(u[1]) > 0.9) e2[0] = 1, e2[1] = 0;
        const double al = e2[0] * u[0] + e2[1] * u[1];
        for (int c = 0; c < 3; c++) e2[c] -= al * u[c];
        const double e2n = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
        for (int c = 0; c < 3; c++) e2[c] /= e2n;
        const double e1[3] = {u[1] * e2[2] - u[2] * e2[1], u[2] * e2[0] - u[0] * e2[2],
                              u[0] * e2[1] - u[1] * e2[0]};
        double size = 0;
        for (int c = 0; c < 3; c++) {
            dr[c] += l * (md->angle_re[k * q + j] * e1[c] + md->angle_re[k * q + n + j] * e2[c]);
            di[c] += l * (md->angle_im[k * q + j] * e1[c] + md->angle_im[k * q + n + j] * e2[c]);
            assert_true(fabs(dr[c] - md->node_re[k * nn + 3 * (j + 1) + c]) < 1e-12);
            assert_true(fabs(di[c] - md->node_im[k * nn + 3 * (j + 1) + c]) < 1e-12);
            size += dr[c] * dr[c] + di[c] * di[c];
        }
        big = fmax(big, sqrt(size));
    }
    for (int c = 0; c < 3; c++)
        assert_true(md->node_re[k * nn + c] == 0 && md->node_im[k * nn + c] == 0); /* pivot */
    assert_true(fabs(big - 1) < 1e-12);
    return sqrt(res) / (sqrt(an) * sqrt(zn));
}

static void test_residuals_and_krein(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_stability_modes *md = whirl_stability_modes_alloc(n);
    whirl_windows *ww = whirl_windows_alloc(n);
    assert_non_null(md);
    const struct { int mode; double omega, damping; } cases[] = {
        {1, 6.3, 0}, {2, 6.3, 0}, {2, 5.3, 0}, {2, 12.0, 0}, {3, 9.0, 0}, {3, 12.0, 0},
        {2, 6.3, 0.02}};
    /* mode 2 at 5.3 lies between its windows (4.28-4.47, 6.21-16.1: whirl windows): neutral,
       a saddle, so some neutral modes have negative energy */
    size_t negative = 0; /* neutral modes of signature -1 over the cases */
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
        whirl_model m = model_of(c, cases[t].omega, cases[t].damping);
        double growth;
        assert_int_equal(whirl_stability_mode(w, &m, cases[t].mode, NULL, &growth), 0);
        size_t count;
        const double *re, *im;
        assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
        double *er = malloc(count * sizeof *er), *ei = malloc(count * sizeof *ei);
        memcpy(er, re, count * sizeof *er);
        memcpy(ei, im, count * sizeof *ei);
        assert_int_equal(whirl_stability_eigenvectors(w, md), 0);
        assert_int_equal(md->count, count);
        double *a = first_order_form(w, n);
        double worst = 0;
        for (size_t k = 0; k < count; k++) {
            assert_true(md->re[k] == er[k] && md->im[k] == ei[k]);
            worst = fmax(worst, check_mode(w, md, k, a));
        }
        print_message("# mode %d omega %g D %g: %zu modes, worst residual %.3g\n", cases[t].mode,
                      cases[t].omega, cases[t].damping, count, worst);
        assert_true(worst < 1e-12);
        /* Krein signatures against the reduced problem's, matched by frequency^2 = -mu */
        if (cases[t].damping == 0) {
            whirl_spectrum sp;
            assert_int_equal(whirl_windows_spectrum(ww, w, 1, &sp), 0);
            size_t neutral = 0, plus = 0;
            for (size_t k = 0; k < count; k++) {
                if (md->krein[k] == 0) continue;
                neutral++;
                plus += md->krein[k] > 0;
                size_t best = 0;
                double d = INFINITY;
                for (size_t i = 0; i < sp.count; i++) {
                    const double e = fabs(sp.re[i] + md->im[k] * md->im[k]) + fabs(sp.im[i]);
                    if (e < d) d = e, best = i;
                }
                assert_true(d < 1e-8 * (1 + md->im[k] * md->im[k]));
                assert_int_equal(md->krein[k], sp.signature[best]);
            }
            print_message("#   %zu neutral modes, %zu of signature +1\n", neutral, plus);
            assert_true(neutral > 0);
            if (cases[t].mode == 1) assert_true(plus == neutral); /* a minimum: H > 0 */
            negative += neutral - plus;
        } else {
            for (size_t k = 0; k < count; k++) assert_int_equal(md->krein[k], 0);
        }
        free(a);
        free(er);
        free(ei);
    }
    assert_true(negative > 0); /* the comparison saw both signs */
    /* storage of the wrong size */
    whirl_stability_modes *small = whirl_stability_modes_alloc(3);
    assert_int_equal(whirl_stability_eigenvectors(w, small), GSL_EINVAL);
    assert_null(whirl_stability_modes_alloc(0));
    whirl_stability_modes_free(small);
    whirl_stability_modes_free(NULL);
    whirl_windows_free(ww);
    whirl_stability_modes_free(md);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* A neutral mode of mode 1 at omega 6.3 (12 links): a nonlinear run started on
 * eps Re(d e^{lambda t}) at t = 0; the node's largest component (real positive by the
 * normalisation) oscillates as eps cos(Im lambda t). */
static void test_neutral_frequency(void **state)
{
    (void)state;
    const size_t n = 12, nn = 3 * (n + 1);
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_stability_modes *md = whirl_stability_modes_alloc(n);
    whirl_model m = model_of(c, 6.3, 0);
    double growth;
    assert_int_equal(whirl_stability_mode(w, &m, 1, NULL, &growth), 0);
    assert_int_equal(whirl_stability_eigenvectors(w, md), 0);
    const double *nx, *ny, *nz;
    whirl_stability_nodes(w, &nx, &ny, &nz);
    /* the two lowest positive frequencies (a slow and a faster mode) */
    size_t picks[2] = {md->count, md->count};
    for (size_t k = 0; k < md->count; k++) {
        if (!(md->im[k] > 0.5) || md->krein[k] == 0) continue; /* |lambda| < 0.5: none here */
        if (picks[0] == md->count || md->im[k] < md->im[picks[0]]) {
            picks[1] = picks[0];
            picks[0] = k;
        } else if (picks[1] == md->count || md->im[k] < md->im[picks[1]]) {
            picks[1] = k;
        }
    }
    assert_true(picks[1] < md->count);
    whirl_dyn *dyn = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    whirl_integrator *it = whirl_integrator_alloc("gauss2", dyn);
    double *y = malloc(whirl_dyn_size(dyn) * sizeof *y);
    double x0[3 * 12], v0[3 * 12], xs[3 * 12], vs[3 * 12];
    /* eps: second-order effects (the constraints, the nonlinearity) at eps^2 = 1e-14 */
    const double eps = 1e-7;
    for (int p = 0; p < 2; p++) {
        const size_t k = picks[p];
        const double lr = md->re[k], li = md->im[k];
        /* the component made real positive: the largest in modulus */
        size_t best = 3;
        for (size_t i = 3; i < nn; i++)
            if (hypot(md->node_re[k * nn + i], md->node_im[k * nn + i]) >
                hypot(md->node_re[k * nn + best], md->node_im[k * nn + best]))
                best = i;
        for (size_t i = 1; i <= n; i++) {
            const double node[3] = {nx[i], ny[i], nz[i]};
            for (int cc = 0; cc < 3; cc++) {
                const double dr = md->node_re[k * nn + 3 * i + cc];
                const double di = md->node_im[k * nn + 3 * i + cc];
                x0[3 * (i - 1) + cc] = node[cc] + eps * dr;
                v0[3 * (i - 1) + cc] = eps * (lr * dr - li * di);
            }
        }
        assert_int_equal(whirl_dyn_set_state(dyn, 0, x0, v0, y), 0);
        const double freq = li, period = 2 * M_PI / freq, h = period / 400;
        double t = 0, prev = eps, tprev = 0, first = -1, last = -1;
        int crossings = 0;
        const size_t comp = best - 3; /* masses 1..N in xs, nodes 0..N in the modes */
        const double *nodes[3] = {nx, ny, nz};
        const double ref = nodes[best % 3][best / 3];
        for (int s = 1; s <= 400 * 20; s++) {
            assert_int_equal(whirl_integrator_advance(it, &t, y, s * h, h, 0), 0);
            assert_int_equal(whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, xs, vs), 0);
            const double now = xs[comp] - ref;
            if ((now > 0) != (prev > 0)) {
                const double tc = tprev + (t - tprev) * prev / (prev - now);
                if (first < 0) first = tc;
                last = tc;
                crossings++;
            }
            prev = now;
            tprev = t;
        }
        const double measured = M_PI * (crossings - 1) / (last - first);
        print_message("# neutral mode %zu (krein %+d): Im lambda %.10g, zero crossings %.10g "
                      "(%d crossings), relative %.2g\n", k, md->krein[k], li, measured, crossings,
                      measured / li - 1);
        assert_true(crossings >= 39);
        assert_true(fabs(measured / li - 1) < 1e-4);
    }
    free(y);
    whirl_integrator_free(it);
    whirl_dyn_free(dyn);
    whirl_stability_modes_free(md);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* Mode 2 of 12 links at 6.3 is unstable: a run seeded along the mode of largest Re lambda. */
static void test_unstable_growth(void **state)
{
    (void)state;
    const size_t n = 12, q = 2 * n;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_stability_modes *md = whirl_stability_modes_alloc(n);
    whirl_model m = model_of(c, 6.3, 0);
    double growth;
    assert_int_equal(whirl_stability_mode(w, &m, 2, NULL, &growth), 0);
    assert_true(growth > 0.05);
    assert_int_equal(whirl_stability_eigenvectors(w, md), 0);
    size_t top = 0;
    for (size_t k = 1; k < md->count; k++)
        if (md->re[k] > md->re[top]) top = k;
    assert_true(md->re[top] == growth);
    const double *nx, *ny, *nz;
    whirl_stability_nodes(w, &nx, &ny, &nz);
    whirl_stability_run_params p = whirl_stability_run_defaults();
    p.perturbation = 1e-9;
    p.along = md->angle_re + top * q;
    whirl_stability_run_result r;
    assert_int_equal(whirl_stability_run_shape(&m, nx, ny, nz, &p, &r), 0);
    print_message("# unstable mode %zu: Re lambda %.10g, Im %.3g; seeded run %.10g over "
                  "[%.3g, %.3g], relative %.2g\n", top, growth, md->im[top], r.sim_growth,
                  r.fit_from, r.fit_to, r.sim_growth / growth - 1);
    assert_int_equal(r.verdict, WHIRL_VERDICT_UNSTABLE);
    assert_true(fabs(r.sim_growth / growth - 1) < 2e-3);
    /* a zero or non-finite direction is refused */
    double zero[24] = {0};
    p.along = zero;
    assert_int_equal(whirl_stability_run_shape(&m, nx, ny, nz, &p, &r), GSL_EINVAL);
    zero[3] = NAN;
    assert_int_equal(whirl_stability_run_shape(&m, nx, ny, nz, &p, &r), GSL_EINVAL);
    whirl_stability_modes_free(md);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* whirl_perturb_links_along on a planar shape: a_j turns link j in the x-z plane by a_j (towards
 * e1 = u0 x y), b_j out of it (towards y), the largest by eps; lengths kept; bad input refused. */
static void test_perturb_along(void **state)
{
    (void)state;
    const double t[3] = {0.3, 0.7, -0.2}, len[3] = {0.5, 0.3, 0.2}; /* angles from the downward
                                                                      vertical towards +x */
    double links[9], ref[9];
    for (int j = 0; j < 3; j++) {
        links[3 * j] = len[j] * sin(t[j]);
        links[3 * j + 1] = 0;
        links[3 * j + 2] = -len[j] * cos(t[j]);
    }
    memcpy(ref, links, sizeof links);
    const double along[6] = {0.5, -1.0, 0, 0, 0, 0.25}, eps = 1e-3;
    assert_int_equal(whirl_perturb_links_along(3, links, eps, along), 0);
    for (int j = 0; j < 3; j++) {
        const double a = eps * along[j], b = eps * along[3 + j];
        /* e1 = u0 x y = (cos t, 0, sin t): the angle from the vertical grows by a */
        assert_true(fabs(links[3 * j] - len[j] * cos(b) * sin(t[j] + a)) < 1e-15);
        assert_true(fabs(links[3 * j + 2] + len[j] * cos(b) * cos(t[j] + a)) < 1e-15);
        assert_true(fabs(links[3 * j + 1] - len[j] * sin(b)) < 1e-15);
    }
    const double zero[6] = {0}, bad[6] = {0, 0, NAN, 0, 0, 0};
    assert_int_equal(whirl_perturb_links_along(3, ref, eps, zero), GSL_EINVAL);
    assert_int_equal(whirl_perturb_links_along(3, ref, eps, bad), GSL_EINVAL);
    assert_int_equal(whirl_perturb_links_along(3, ref, -1, along), GSL_EINVAL);
    assert_int_equal(whirl_perturb_links_along(0, ref, eps, along), GSL_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_residuals_and_krein),
        cmocka_unit_test(test_neutral_frequency),
        cmocka_unit_test(test_unstable_growth),
        cmocka_unit_test(test_perturb_along),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
