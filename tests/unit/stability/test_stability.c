/* Tests of the linear stability analysis (src/stability.c) against independent results:
 *  - the hanging chain in the rotating frame: eigenvalues +-i (nu_k +- omega), nu_k the normal-mode
 *    frequencies of the N-pendulum from its tridiagonal (position) formulation;
 *  - M, G, K and C against finite differences of the co-rotating Lagrangian and of the Rayleigh
 *    function written in Cartesian form;
 *  - the deflated spectrum against GSL's nonsymmetric eigensolver on the full first-order form;
 *  - mode k has 2(k-1) negative directions of K (k-1 in the plane), one zero (the symmetry);
 *  - without damping mode 1 is neutrally stable and the spectrum is Hamiltonian (-lambda too);
 *  - with damping (Kelvin-Tait-Chetaev) the number of growing eigenvalues equals the number of
 *    negative directions of K: mode 1 decays, modes 2 and 3 grow;
 *  - perturbed runs of the dynamics module (two integrators): the fitted growth of an unstable
 *    shape is the largest eigenvalue's real part; with damping mode 1 converges;
 *  - the hand-swung chain (driven pivot, air drag; three-dimensional shapes of the driven module):
 *    M, G, C, K against finite differences of the Lagrangian, of the Rayleigh function and of the
 *    drag's generalised force written here in the documented chart; the linear response of the
 *    accelerations of the dynamics module with the same drive and drag; the reduction to the
 *    planar formulas without drive and drag (also for a shape turned about the axis); perturbed
 *    runs: the growth of an unstable trailing shape, the convergence of a stable one;
 *  - high rates (N = 15 at omega = 150): the shape linearised is an equilibrium to round-off (a
 *    force balance written here), its growth that of a perturbed run, also in the window search;
 *  - a high mode of a long chain (N = 100, mode 50, omega 250): the leading eigenvalues equal
 *    those of a finite-difference Jacobian of the dynamics' right-hand side (Cartesian state)
 *    about the shape, by LAPACK's dgeev.
 * Equilibria come from a shooting written here (recursion up from the tip, bisection on the tip
 * radius), independent of the steady-shape module; that module's shapes are compared too. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_sort_vector.h>

#include <lapacke.h>

#include "whirl/dynamics.h"
#include "whirl/stability.h"
#include "whirl/steady.h"
#include "stop_soon.h"

#define NMAX 16

/* A non-uniform chain: every formula must hold for any lengths, masses and g. */
static whirl_chain *odd_chain(size_t n)
{
    double len[NMAX], mass[NMAX];
    for (size_t i = 0; i < n; i++) {
        len[i] = 0.11 + 0.07 * sin(1.7 * (double)i + 0.3);
        mass[i] = 0.13 + 0.05 * cos(2.3 * (double)i);
    }
    return whirl_chain_alloc(n, len, mass, 1.37);
}

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

/* ---- equilibria by shooting from the tip ---- */

/* Nodes r[0..n], z[0..n] of the shape with tip radius a; returns the pivot's radius r[0]. */
static double shoot(const whirl_chain *c, double omega, double a, double *r, double *z)
{
    const size_t n = c->n;
    double px = 0, pz = 0;
    r[n] = a;
    z[n] = 0;
    for (size_t j = n; j >= 1; j--) {
        px += c->mass[j - 1] * omega * omega * r[j];
        pz -= c->mass[j - 1] * c->gravity;
        const double p = hypot(px, pz);
        r[j - 1] = r[j] - c->length[j - 1] * px / p;
        z[j - 1] = z[j] - c->length[j - 1] * pz / p;
    }
    const double top = z[0];
    for (size_t i = 0; i <= n; i++) z[i] -= top;
    return r[0];
}

static int crossings(size_t n, const double *r)
{
    int k = 0;
    for (size_t i = 1; i < n; i++)
        if ((r[i] > 0) != (r[i + 1] > 0)) k++;
    return k;
}

/* The shape of mode k (k - 1 axis crossings below the pivot); 0 on success. */
static int find_mode(const whirl_chain *c, double omega, int mode, double *r, double *z)
{
    const double total = whirl_chain_total_length(c);
    const int grid = 4000;
    double a0 = 1e-7 * total, f0 = shoot(c, omega, a0, r, z);
    for (int i = 1; i <= grid; i++) {
        double a1 = total * i / grid, f1 = shoot(c, omega, a1, r, z);
        if ((f0 > 0) != (f1 > 0)) {
            double lo = a0, hi = a1, flo = f0;
            for (int it = 0; it < 200 && hi - lo > 1e-16 * hi; it++) {
                double mid = 0.5 * (lo + hi), fm = shoot(c, omega, mid, r, z);
                if ((fm > 0) == (flo > 0)) lo = mid, flo = fm;
                else hi = mid;
            }
            shoot(c, omega, lo, r, z);
            if (crossings(c->n, r) == mode - 1) return 0;
        }
        a0 = a1;
        f0 = f1;
    }
    return -1;
}

/* ---- helpers ---- */

static double max_abs(size_t n, const double *a)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
    return m;
}

/* Eigenvalues of the symmetric q x q matrix a (row-major), ascending. */
static void symmetric_eigenvalues(size_t q, const double *a, double *eval)
{
    gsl_matrix *m = gsl_matrix_alloc(q, q);
    gsl_vector *e = gsl_vector_alloc(q);
    gsl_eigen_symm_workspace *ws = gsl_eigen_symm_alloc(q);
    memcpy(m->data, a, q * q * sizeof(double));
    assert_int_equal(gsl_eigen_symm(m, e, ws), 0);
    gsl_sort_vector(e);
    memcpy(eval, e->data, q * sizeof(double));
    gsl_eigen_symm_free(ws);
    gsl_vector_free(e);
    gsl_matrix_free(m);
}

static size_t count_below(size_t q, const double *eval, double level)
{
    size_t k = 0;
    for (size_t i = 0; i < q; i++) k += eval[i] < level;
    return k;
}

/* ---- (a) the hanging chain ---- */

static void test_hanging_chain(void **state)
{
    (void)state;
    const size_t n = 7;
    whirl_chain *c = odd_chain(n);
    /* normal modes: m_i xi_i'' = T_{i+1} (xi_{i+1} - xi_i) / l_{i+1} - T_i (xi_i - xi_{i-1}) / l_i */
    double t[NMAX + 1], s[NMAX * NMAX] = {0}, nu2[NMAX];
    t[n] = 0;
    for (size_t i = n; i-- > 0;) t[i] = t[i + 1] + c->gravity * c->mass[i];
    for (size_t i = 0; i < n; i++) {
        double k_up = t[i] / c->length[i], k_down = i + 1 < n ? t[i + 1] / c->length[i + 1] : 0;
        s[i * n + i] = (k_up + k_down) / c->mass[i];
        if (i + 1 < n)
            s[i * n + i + 1] = s[(i + 1) * n + i] =
                -k_down / sqrt(c->mass[i] * c->mass[i + 1]);
    }
    symmetric_eigenvalues(n, s, nu2);
    const double omega = 0.83 * sqrt(nu2[0]);

    double expected[4 * NMAX];
    for (size_t k = 0; k < n; k++) {
        double nu = sqrt(nu2[k]);
        expected[4 * k] = nu + omega;
        expected[4 * k + 1] = -(nu + omega);
        expected[4 * k + 2] = nu - omega;
        expected[4 * k + 3] = omega - nu;
    }
    gsl_sort(expected, 1, 4 * n);

    double r[NMAX + 1], z[NMAX + 1];
    r[0] = z[0] = 0;
    for (size_t i = 1; i <= n; i++) {
        r[i] = 0;
        z[i] = z[i - 1] - c->length[i - 1];
    }
    whirl_model m = model_of(c, omega, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    assert_non_null(w);
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
    size_t count;
    const double *re, *im;
    assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
    assert_int_equal(count, 4 * n); /* no symmetry mode hanging straight down */
    double got[4 * NMAX];
    memcpy(got, im, count * sizeof(double));
    gsl_sort(got, 1, count);
    const double scale = sqrt(nu2[n - 1]) + omega;
    for (size_t i = 0; i < count; i++) {
        assert_true(fabs(re[i]) < 1e-12 * scale);
        assert_true(fabs(got[i] - expected[i]) < 1e-12 * scale);
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- (b) finite differences of the Lagrangian and the Rayleigh function ---- */

typedef struct {
    const whirl_chain *c;
    double omega, damping;
} fd_problem;

/* Unit vectors of the links and their derivatives in a and b at q = (a, b) (any b). */
static void link_vectors(size_t n, const double *q, const double *qd, double (*u)[3],
                         double (*ud)[3])
{
    for (size_t j = 0; j < n; j++) {
        const double a = q[j], b = q[n + j];
        const double sa = sin(a), ca = cos(a), sb = sin(b), cb = cos(b);
        u[j][0] = sa * cb, u[j][1] = sb, u[j][2] = -ca * cb;
        const double ua[3] = {ca * cb, 0, sa * cb}, ub[3] = {-sa * sb, cb, ca * sb};
        for (int d = 0; d < 3; d++) ud[j][d] = ua[d] * qd[j] + ub[d] * qd[n + j];
    }
}

/* L = 1/2 sum m |x' + Omega x x|^2 - g sum m z in the co-rotating frame. */
static double lagrangian(const fd_problem *p, const double *q, const double *qd)
{
    const whirl_chain *c = p->c;
    const size_t n = c->n;
    double u[NMAX][3], ud[NMAX][3], x[3] = {0}, v[3] = {0}, lag = 0;
    link_vectors(n, q, qd, u, ud);
    for (size_t i = 0; i < n; i++) {
        for (int d = 0; d < 3; d++) {
            x[d] += c->length[i] * u[i][d];
            v[d] += c->length[i] * ud[i][d];
        }
        const double vx = v[0] - p->omega * x[1], vy = v[1] + p->omega * x[0], vz = v[2];
        lag += 0.5 * c->mass[i] * (vx * vx + vy * vy + vz * vz) - c->mass[i] * c->gravity * x[2];
    }
    return lag;
}

/* R = D/2 sum |u_i' - u_{i-1}'|^2, u_0' = 0. */
static double rayleigh(const fd_problem *p, const double *q, const double *qd)
{
    const size_t n = p->c->n;
    double u[NMAX][3], ud[NMAX][3], prev[3] = {0}, sum = 0;
    link_vectors(n, q, qd, u, ud);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            sum += (ud[i][d] - prev[d]) * (ud[i][d] - prev[d]);
            prev[d] = ud[i][d];
        }
    return 0.5 * p->damping * sum;
}

typedef double (*scalar_fn)(const fd_problem *, const double *, const double *);

/* Second difference of f in (x_a, y_b), x and y each either q or qd (which: 0 = q, 1 = qd). */
static double mixed(scalar_fn f, const fd_problem *p, const double *q0, int wa, size_t a,
                    double ha, int wb, size_t b, double hb)
{
    const size_t q = 2 * p->c->n;
    double sum = 0;
    for (int sa = -1; sa <= 1; sa += 2)
        for (int sb = -1; sb <= 1; sb += 2) {
            double qq[2 * NMAX], qd[2 * NMAX] = {0};
            memcpy(qq, q0, q * sizeof(double));
            (wa ? qd : qq)[a] += sa * ha;
            (wb ? qd : qq)[b] += sb * hb;
            sum += sa * sb * f(p, qq, qd);
        }
    return sum / (4 * ha * hb);
}

static void test_matrices_by_finite_differences(void **state)
{
    (void)state;
    const size_t n = 6, q = 2 * n;
    whirl_chain *c = odd_chain(n);
    const double omega = 3.9, damping = 0.173;
    double r[NMAX + 1], z[NMAX + 1], q0[2 * NMAX] = {0};
    assert_int_equal(find_mode(c, omega, 2, r, z), 0);
    for (size_t j = 0; j < n; j++) q0[j] = atan2(r[j + 1] - r[j], z[j] - z[j + 1]);

    whirl_model m = model_of(c, omega, damping);
    whirl_stability *w = whirl_stability_alloc(n);
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
    const double *mm = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
    const double *gg = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
    const double *cc = whirl_stability_get_matrix(w, WHIRL_STABILITY_DAMPING);
    const double *kk = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    const double km = max_abs(q * q, kk), mmax = max_abs(q * q, mm), gm = max_abs(q * q, gg);
    const double cm = max_abs(q * q, cc);
    assert_true(km > 0 && mmax > 0 && gm > 0 && cm > 0);
    fd_problem p = {c, omega, damping};
    const double h = 1e-4; /* in the angles; the velocities enter quadratically: step 1 is exact */
    double err_m = 0, err_g = 0, err_k = 0, err_c = 0;
    for (size_t a = 0; a < q; a++)
        for (size_t b = 0; b < q; b++) {
            double fm = mixed(lagrangian, &p, q0, 1, a, 1.0, 1, b, 1.0);
            double fg = mixed(lagrangian, &p, q0, 1, a, 1.0, 0, b, h) -
                        mixed(lagrangian, &p, q0, 0, a, h, 1, b, 1.0);
            double fk = -mixed(lagrangian, &p, q0, 0, a, h, 0, b, h);
            double fc = mixed(rayleigh, &p, q0, 1, a, 1.0, 1, b, 1.0);
            err_m = fmax(err_m, fabs(fm - mm[a * q + b]));
            err_g = fmax(err_g, fabs(fg - gg[a * q + b]));
            err_k = fmax(err_k, fabs(fk - kk[a * q + b]));
            err_c = fmax(err_c, fabs(fc - cc[a * q + b]));
        }
    print_message("# finite differences: |dM| %.2g |dG| %.2g |dK| %.2g |dC| %.2g (relative)\n",
                  err_m / mmax, err_g / gm, err_k / km, err_c / cm);
    assert_true(err_m < 1e-12 * mmax);
    assert_true(err_c < 1e-12 * cm);
    assert_true(err_g < 1e-7 * gm);
    assert_true(err_k < 1e-7 * km);
    /* K s = 0: the rotation about z */
    const double *s = whirl_stability_symmetry(w);
    double ks = 0;
    for (size_t a = 0; a < q; a++) {
        double sum = 0;
        for (size_t b = 0; b < q; b++) sum += kk[a * q + b] * s[b];
        ks = fmax(ks, fabs(sum));
    }
    assert_true(ks < 1e-12 * km * max_abs(q, s));
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- (b') against the dynamics module's equations of motion ---- */

/* Link vectors d_j = l_j u_j and rates, positions and velocities of the masses at (q, qd). */
static void cartesian_state(const whirl_chain *c, const double *q, const double *qd, double *x,
                            double *v)
{
    const size_t n = c->n;
    double u[NMAX][3], ud[NMAX][3], px[3] = {0}, pv[3] = {0};
    link_vectors(n, q, qd, u, ud);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            px[d] += c->length[i] * u[i][d];
            pv[d] += c->length[i] * ud[i][d];
            x[3 * i + d] = px[d];
            v[3 * i + d] = pv[d];
        }
}

/* The accelerations the linearisation in w predicts at (dq, dqd):
 * pred = q'' = -M^-1 (K dq + (G + C) dqd), q = 2N coordinates. */
static void linear_prediction(const whirl_stability *w, size_t q, const double *dq,
                              const double *dqd, gsl_vector *pred)
{
    const double *mm = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
    const double *gg = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
    const double *cc = whirl_stability_get_matrix(w, WHIRL_STABILITY_DAMPING);
    const double *kk = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    gsl_matrix *chol = gsl_matrix_alloc(q, q);
    memcpy(chol->data, mm, q * q * sizeof(double));
    assert_int_equal(gsl_linalg_cholesky_decomp1(chol), 0);
    for (size_t a = 0; a < q; a++) {
        double f = 0;
        for (size_t b = 0; b < q; b++)
            f -= kk[a * q + b] * dq[b] + (gg[a * q + b] + cc[a * q + b]) * dqd[b];
        gsl_vector_set(pred, a, f);
    }
    assert_int_equal(gsl_linalg_cholesky_svx(chol, pred), 0);
    gsl_matrix_free(chol);
}

static void test_against_dynamics(void **state)
{
    (void)state;
    const size_t n = 7, q = 2 * n;
    whirl_chain *c = odd_chain(n);
    const double omega = 4.0, damping = 0.087;
    double r[NMAX + 1], z[NMAX + 1], q0[2 * NMAX] = {0}, dq[2 * NMAX], dqd[2 * NMAX];
    assert_int_equal(find_mode(c, omega, 2, r, z), 0);
    for (size_t j = 0; j < n; j++) q0[j] = atan2(r[j + 1] - r[j], z[j] - z[j + 1]);
    for (size_t a = 0; a < q; a++) {
        dq[a] = sin(3.7 * (double)a + 0.4);
        dqd[a] = cos(2.9 * (double)a + 1.1);
    }
    whirl_model m = model_of(c, omega, damping);
    whirl_stability *w = whirl_stability_alloc(n);
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);

    gsl_vector *pred = gsl_vector_alloc(q);
    linear_prediction(w, q, dq, dqd, pred);

    /* the dynamics module at q0 +- h dq with rates +- h dqd; the Cartesian state is
     * (d_1..d_N, d_1'..d_N'), so the second half of dy/dt holds d_j'' = l_j u_j'' */
    whirl_dyn *dyn = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(dyn);
    const size_t size = whirl_dyn_size(dyn);
    assert_int_equal(size, 6 * n);
    const double h = 1e-5;
    double acc[2][2 * NMAX];
    for (int side = 0; side < 2; side++) {
        const double sg = side ? -h : h;
        double qq[2 * NMAX], qqd[2 * NMAX], x[3 * NMAX], v[3 * NMAX], y[6 * NMAX], dy[6 * NMAX];
        for (size_t a = 0; a < q; a++) {
            qq[a] = q0[a] + sg * dq[a];
            qqd[a] = sg * dqd[a];
        }
        cartesian_state(c, qq, qqd, x, v);
        assert_int_equal(whirl_dyn_set_state(dyn, 0, x, v, y), 0);
        assert_int_equal(whirl_dyn_rhs(0, y, dy, dyn), 0);
        for (size_t j = 0; j < n; j++) {
            const double *dd = dy + 3 * n + 3 * j;
            acc[side][j] = (cos(q0[j]) * dd[0] + sin(q0[j]) * dd[2]) / c->length[j];
            acc[side][n + j] = dd[1] / c->length[j];
        }
    }
    double err = 0, scale = 0;
    for (size_t a = 0; a < q; a++) {
        const double fd = (acc[0][a] - acc[1][a]) / (2 * h);
        err = fmax(err, fabs(fd - gsl_vector_get(pred, a)));
        scale = fmax(scale, fabs(gsl_vector_get(pred, a)));
    }
    print_message("# against whirl_dyn_rhs: |d q''| %.2g relative\n", err / scale);
    assert_true(err < 1e-6 * scale);
    whirl_dyn_free(dyn);
    gsl_vector_free(pred);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- deflation against the full spectrum ---- */

/* Eigenvalues of the full first-order form, by GSL. */
static void full_spectrum(const whirl_stability *w, size_t n, double *re, double *im)
{
    const size_t q = 2 * n, y = 4 * n;
    gsl_matrix *mm = gsl_matrix_alloc(q, q), *rhs = gsl_matrix_alloc(q, y);
    gsl_matrix *a = gsl_matrix_calloc(y, y);
    const double *m = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
    const double *g = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
    const double *c = whirl_stability_get_matrix(w, WHIRL_STABILITY_DAMPING);
    const double *k = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    memcpy(mm->data, m, q * q * sizeof(double));
    assert_int_equal(gsl_linalg_cholesky_decomp1(mm), 0);
    for (size_t j = 0; j < q; j++) {
        gsl_vector_view col_k = gsl_matrix_column(rhs, j), col_d = gsl_matrix_column(rhs, q + j);
        for (size_t i = 0; i < q; i++) {
            gsl_vector_set(&col_k.vector, i, k[i * q + j]);
            gsl_vector_set(&col_d.vector, i, g[i * q + j] + c[i * q + j]);
        }
        assert_int_equal(gsl_linalg_cholesky_svx(mm, &col_k.vector), 0);
        assert_int_equal(gsl_linalg_cholesky_svx(mm, &col_d.vector), 0);
    }
    for (size_t i = 0; i < q; i++) {
        gsl_matrix_set(a, i, q + i, 1);
        for (size_t j = 0; j < y; j++) gsl_matrix_set(a, q + i, j, -gsl_matrix_get(rhs, i, j));
    }
    gsl_vector_complex *e = gsl_vector_complex_alloc(y);
    gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc(y);
    assert_int_equal(gsl_eigen_nonsymm(a, e, ws), 0);
    for (size_t i = 0; i < y; i++) {
        re[i] = GSL_REAL(gsl_vector_complex_get(e, i));
        im[i] = GSL_IMAG(gsl_vector_complex_get(e, i));
    }
    gsl_eigen_nonsymm_free(ws);
    gsl_vector_complex_free(e);
    gsl_matrix_free(a);
    gsl_matrix_free(rhs);
    gsl_matrix_free(mm);
}

static void check_deflation(size_t n, int mode, double omega, double damping)
{
    whirl_chain *c = odd_chain(n);
    double r[NMAX + 1], z[NMAX + 1];
    assert_int_equal(find_mode(c, omega, mode, r, z), 0);
    whirl_model m = model_of(c, omega, damping);
    whirl_stability *w = whirl_stability_alloc(n);
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
    size_t count;
    const double *re, *im;
    assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
    const size_t removed = damping > 0 ? 1 : 2;
    assert_int_equal(count, 4 * n - removed);
    double fre[4 * NMAX], fim[4 * NMAX];
    int used[4 * NMAX] = {0};
    full_spectrum(w, n, fre, fim);
    double scale = 0;
    for (size_t i = 0; i < 4 * n; i++) scale = fmax(scale, hypot(fre[i], fim[i]));
    /* every deflated eigenvalue is one of the full spectrum (matched one to one) */
    double worst = 0;
    for (size_t i = 0; i < count; i++) {
        size_t best = 0;
        double dist = INFINITY;
        for (size_t j = 0; j < 4 * n; j++) {
            double dj = hypot(re[i] - fre[j], im[i] - fim[j]);
            if (!used[j] && dj < dist) dist = dj, best = j;
        }
        used[best] = 1;
        worst = fmax(worst, dist);
    }
    /* and the ones left over are the zeros (a Jordan pair splits to O(sqrt(eps)) in the full) */
    double left = 0;
    for (size_t j = 0; j < 4 * n; j++)
        if (!used[j]) left = fmax(left, hypot(fre[j], fim[j]));
    print_message("# mode %d omega %g D %g: deflated vs full %.2g, removed |lambda| <= %.2g "
                  "(scale %.3g)\n", mode, omega, damping, worst, left, scale);
    assert_true(worst < 1e-7 * scale);
    assert_true(left < 1e-6 * scale);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

static void test_deflation(void **state)
{
    (void)state;
    check_deflation(5, 1, 2.385, 0);
    check_deflation(6, 2, 4.1, 0);
    check_deflation(6, 2, 4.1, 0.05);
    check_deflation(8, 3, 6.7, 0.013);
}

/* ---- (c) negative directions of K; (d) Kelvin-Tait-Chetaev ---- */

static void test_negative_directions_and_damping(void **state)
{
    (void)state;
    const size_t n = 12, q = 2 * n;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    const double omega = 6.3; /* above the third critical rate of the 12-link chain */
    for (int mode = 1; mode <= 3; mode++) {
        double r[NMAX + 1], z[NMAX + 1], eval[2 * NMAX], half[NMAX * NMAX];
        assert_int_equal(find_mode(c, omega, mode, r, z), 0);
        whirl_model m = model_of(c, omega, 0);
        assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
        const double *kk = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
        symmetric_eigenvalues(q, kk, eval);
        const double tol = 1e-10 * fmax(fabs(eval[0]), fabs(eval[q - 1]));
        assert_int_equal(count_below(q, eval, -tol), (size_t)(2 * (mode - 1)));
        assert_int_equal(count_below(q, eval, tol) - count_below(q, eval, -tol), 1);
        for (size_t i = 0; i < n; i++) /* the in-plane block */
            for (size_t j = 0; j < n; j++) half[i * n + j] = kk[i * q + j];
        symmetric_eigenvalues(n, half, eval);
        assert_int_equal(count_below(n, eval, -tol), (size_t)(mode - 1));
        int index;
        assert_int_equal(whirl_stability_index(w, &index), 0);
        assert_int_equal(index, 2 * (mode - 1));

        /* without damping: Hamiltonian spectrum (symmetric about the imaginary axis) */
        size_t count;
        const double *re, *im;
        assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
        double hi = -INFINITY, lo = INFINITY, sc = 0;
        for (size_t i = 0; i < count; i++) {
            hi = fmax(hi, re[i]);
            lo = fmin(lo, re[i]);
            sc = fmax(sc, hypot(re[i], im[i]));
        }
        assert_true(fabs(hi + lo) < 1e-8 * sc);
        if (mode == 1) assert_true(hi < 1e-8 * sc); /* K >= 0: Lyapunov stable */

        /* with damping: as many growing eigenvalues as negative directions of K */
        m.internal_damping = 0.021;
        assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
        assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
        size_t growing = 0;
        for (size_t i = 0; i < count; i++) growing += re[i] > 0;
        double growth;
        assert_int_equal(whirl_stability_growth(w, &growth), 0);
        print_message("# mode %d omega %g: conservative max Re %.3g, damped growth %.6g, %zu "
                      "growing\n", mode, omega, hi, growth, growing);
        assert_int_equal(growing, (size_t)(2 * (mode - 1)));
        assert_int_equal(whirl_stability_index(w, &index), 0); /* Kelvin-Tait-Chetaev */
        assert_int_equal(growing, (size_t)index);
        assert_int_equal(whirl_verdict_linear(growth, index),
                         mode == 1 ? WHIRL_VERDICT_CONVERGING : WHIRL_VERDICT_UNSTABLE);
        assert_true(mode == 1 ? growth < 0 : growth > 0);
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- the steady-shape module's shapes ---- */

static void test_with_steady_module(void **state)
{
    (void)state;
    const size_t n = 10;
    whirl_chain *c = odd_chain(n);
    whirl_stability *w = whirl_stability_alloc(n);
    const double omega = 5.2;
    for (int mode = 1; mode <= 2; mode++) {
        double r[NMAX + 1], z[NMAX + 1], own, theirs;
        whirl_model m = model_of(c, omega, 0.031);
        assert_int_equal(find_mode(c, omega, mode, r, z), 0);
        assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
        assert_int_equal(whirl_stability_growth(w, &own), 0);
        whirl_shape_info info;
        assert_int_equal(whirl_stability_mode(w, &m, mode, &info, &theirs), 0);
        assert_int_equal(info.mode, mode);
        assert_true(fabs(info.tip_r - r[n]) < 1e-9);
        assert_true(fabs(own - theirs) < 1e-9 * fmax(1, fabs(own)));
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- perturbed runs ---- */

typedef struct {
    int samples, stop_after;
    double last_t, first_ratio;
} observation;

static int count_samples(double t, double ratio, void *data)
{
    observation *o = data;
    if (o->samples == 0) o->first_ratio = ratio;
    assert_true(o->samples == 0 || t > o->last_t);
    o->last_t = t;
    o->samples++;
    return (o->stop_after > 0 && o->samples >= o->stop_after) ? GSL_EFAILED : GSL_SUCCESS;
}

static void test_perturbed_runs(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_model m = model_of(c, 6.3, 0);
    whirl_shape_info info;
    double growth;
    /* mode 2 of the 12-link chain at 6.3 is unstable without damping (see above) */
    assert_int_equal(whirl_stability_mode(w, &m, 2, &info, &growth), 0);
    assert_true(growth > 0.05);
    const char *methods[] = {"gauss2", "rk4"};
    for (int k = 0; k < 2; k++) {
        whirl_stability_run_params p = whirl_stability_run_defaults();
        observation obs = {0};
        p.method = methods[k];
        p.perturbation = 2.3e-7;
        p.seed = 7;
        p.observe = count_samples;
        p.observe_data = &obs;
        whirl_stability_run_result r;
        assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &r), 0);
        print_message("# run %s: eig %.6g sim %.6g over [%.3g, %.3g], max %.4g, %lu steps\n",
                      methods[k], growth, r.sim_growth, r.fit_from, r.fit_to, r.max_deviation,
                      r.stats.steps);
        assert_int_equal(r.verdict, WHIRL_VERDICT_UNSTABLE);
        assert_true(fabs(r.sim_growth / growth - 1) < 0.02);
        assert_true(r.fit_to > r.fit_from && r.max_deviation >= 1e4);
        assert_true(r.duration < p.periods * 2 * M_PI / m.omega); /* stopped early */
        assert_true(r.initial > 0.1 * p.perturbation && r.initial < p.perturbation);
        assert_true(obs.first_ratio == 1.0 && obs.samples > 10);
    }
    /* with damping mode 1 converges */
    m.internal_damping = 0.02;
    assert_int_equal(whirl_stability_mode(w, &m, 1, &info, &growth), 0);
    assert_true(growth < 0);
    whirl_stability_run_params p = whirl_stability_run_defaults();
    whirl_stability_run_result r;
    assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &r), 0);
    assert_int_equal(r.verdict, WHIRL_VERDICT_CONVERGING);
    assert_true(r.sim_growth == 0 && r.end_deviation <= 1e-1);
    /* the observer stops a run; bad parameters */
    observation obs = {0, 5, 0, 0};
    p.observe = count_samples;
    p.observe_data = &obs;
    assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &r), GSL_EFAILED);
    assert_int_equal(obs.samples, 5);
    p = whirl_stability_run_defaults();
    p.periods = 0;
    assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &r), GSL_EINVAL);
    p = whirl_stability_run_defaults();
    p.perturbation = 1;
    assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &r), GSL_EINVAL);
    p = whirl_stability_run_defaults();
    p.method = "euler";
    assert_int_equal(whirl_stability_run(&m, info.tip_r, &p, &r), GSL_EINVAL);
    assert_string_equal(whirl_verdict_name(WHIRL_VERDICT_STABLE), "stable (minimum)");
    assert_string_equal(whirl_verdict_name(WHIRL_VERDICT_NEUTRAL), "neutral (gyroscopic)");
    assert_int_equal(whirl_verdict_refine(WHIRL_VERDICT_STABLE, 2), WHIRL_VERDICT_NEUTRAL);
    assert_int_equal(whirl_verdict_refine(WHIRL_VERDICT_STABLE, 0), WHIRL_VERDICT_STABLE);
    assert_int_equal(whirl_verdict_refine(WHIRL_VERDICT_UNSTABLE, 2), WHIRL_VERDICT_UNSTABLE);
    assert_int_equal(whirl_verdict_linear(0, 0), WHIRL_VERDICT_STABLE);
    assert_int_equal(whirl_verdict_linear(0, 4), WHIRL_VERDICT_NEUTRAL);
    assert_int_equal(whirl_verdict_linear(1e-3, 0), WHIRL_VERDICT_UNSTABLE);
    assert_int_equal(whirl_verdict_linear(-1e-3, 2), WHIRL_VERDICT_CONVERGING);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- the hand-swung chain: three-dimensional shapes, drive and air drag ---- */

/* A model with the pivot on a circle of radius eps and air drag c, c2. */
static whirl_model driven_model(const whirl_chain *c, double omega, double damping, double eps,
                                double drag, double drag2)
{
    whirl_model m = model_of(c, omega, damping);
    m.drive_radius = eps;
    m.air_drag = drag;
    m.air_drag_quadratic = drag2;
    return m;
}

/* The documented chart of a link of direction u: e2 along the part of y (x if |u_y| > 0.9)
 * perpendicular to u, e1 = u x e2. */
typedef struct {
    double u0[3], e1[3], e2[3];
} chart;

static void make_chart(const double *u, chart *ch)
{
    const double r[3] = {fabs(u[1]) > 0.9, fabs(u[1]) <= 0.9, 0};
    const double along = r[0] * u[0] + r[1] * u[1] + r[2] * u[2];
    double e2[3], norm = 0;
    for (int k = 0; k < 3; k++) e2[k] = r[k] - along * u[k], norm += e2[k] * e2[k];
    for (int k = 0; k < 3; k++) {
        ch->u0[k] = u[k];
        ch->e2[k] = e2[k] / sqrt(norm);
    }
    ch->e1[0] = u[1] * ch->e2[2] - u[2] * ch->e2[1];
    ch->e1[1] = u[2] * ch->e2[0] - u[0] * ch->e2[2];
    ch->e1[2] = u[0] * ch->e2[1] - u[1] * ch->e2[0];
}

typedef struct {
    const whirl_chain *c;
    double omega, damping, eps, drag, drag2;
    chart ch[NMAX];
} fd3_problem;

/* Charts from the nodes (pivot first). */
static void charts_from_nodes(fd3_problem *p, const double *x, const double *y, const double *z)
{
    for (size_t j = 0; j < p->c->n; j++) {
        double d[3] = {x[j + 1] - x[j], y[j + 1] - y[j], z[j + 1] - z[j]};
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; k++) d[k] /= len;
        make_chart(d, &p->ch[j]);
    }
}

/* Unit vectors u_j, du_j/da_j, du_j/db_j at q. */
static void chart_vectors(const fd3_problem *p, const double *q, double (*u)[3], double (*ua)[3],
                          double (*ub)[3])
{
    const size_t n = p->c->n;
    for (size_t j = 0; j < n; j++) {
        const double a = q[j], b = q[n + j], sa = sin(a), ca = cos(a), sb = sin(b), cb = cos(b);
        const chart *h = &p->ch[j];
        for (int k = 0; k < 3; k++) {
            u[j][k] = ca * cb * h->u0[k] + sa * cb * h->e1[k] + sb * h->e2[k];
            ua[j][k] = -sa * cb * h->u0[k] + ca * cb * h->e1[k];
            ub[j][k] = -ca * sb * h->u0[k] - sa * sb * h->e1[k] + cb * h->e2[k];
        }
    }
}

/* Positions, co-rotating velocities of the masses and the rates u_j' at (q, qd). */
static void chart_state(const fd3_problem *p, const double *q, const double *qd, double *x,
                        double *v, double (*ud)[3])
{
    const size_t n = p->c->n;
    double u[NMAX][3], ua[NMAX][3], ub[NMAX][3], px[3] = {p->eps, 0, 0}, pv[3] = {0};
    chart_vectors(p, q, u, ua, ub);
    for (size_t j = 0; j < n; j++)
        for (int k = 0; k < 3; k++) {
            ud[j][k] = ua[j][k] * qd[j] + ub[j][k] * qd[n + j];
            px[k] += p->c->length[j] * u[j][k];
            pv[k] += p->c->length[j] * ud[j][k];
            x[3 * j + k] = px[k];
            v[3 * j + k] = pv[k];
        }
}

static double lagrangian3(const fd3_problem *p, const double *q, const double *qd)
{
    double x[3 * NMAX], v[3 * NMAX], ud[NMAX][3], lag = 0;
    chart_state(p, q, qd, x, v, ud);
    for (size_t i = 0; i < p->c->n; i++) {
        const double *xi = x + 3 * i, *vi = v + 3 * i;
        const double vx = vi[0] - p->omega * xi[1], vy = vi[1] + p->omega * xi[0], vz = vi[2];
        lag += 0.5 * p->c->mass[i] * (vx * vx + vy * vy + vz * vz) -
               p->c->mass[i] * p->c->gravity * xi[2];
    }
    return lag;
}

static double rayleigh3(const fd3_problem *p, const double *q, const double *qd)
{
    double x[3 * NMAX], v[3 * NMAX], ud[NMAX][3], prev[3] = {0}, sum = 0;
    chart_state(p, q, qd, x, v, ud);
    for (size_t i = 0; i < p->c->n; i++)
        for (int d = 0; d < 3; d++) {
            sum += (ud[i][d] - prev[d]) * (ud[i][d] - prev[d]);
            prev[d] = ud[i][d];
        }
    return 0.5 * p->damping * sum;
}

/* Generalised force of the air drag, Q_a = sum_i f_i . dx_i/dq_a, f_i = -l_i (c + c2 |v|) v with
 * v the inertial velocity x_i' + omega z x x_i. */
static void drag_force(const fd3_problem *p, const double *q, const double *qd, double *out)
{
    const size_t n = p->c->n;
    double x[3 * NMAX], v[3 * NMAX], ud[NMAX][3], u[NMAX][3], ua[NMAX][3], ub[NMAX][3];
    double f[3 * NMAX];
    chart_state(p, q, qd, x, v, ud);
    chart_vectors(p, q, u, ua, ub);
    for (size_t i = 0; i < n; i++) {
        const double vin[3] = {v[3 * i] - p->omega * x[3 * i + 1],
                               v[3 * i + 1] + p->omega * x[3 * i], v[3 * i + 2]};
        const double speed = sqrt(vin[0] * vin[0] + vin[1] * vin[1] + vin[2] * vin[2]);
        for (int k = 0; k < 3; k++)
            f[3 * i + k] = -p->c->length[i] * (p->drag + p->drag2 * speed) * vin[k];
    }
    for (size_t j = 0; j < n; j++) { /* dx_i/da_j = l_j ua_j for i >= j */
        double fa = 0, fb = 0;
        for (size_t i = j; i < n; i++)
            for (int k = 0; k < 3; k++) {
                fa += f[3 * i + k] * p->c->length[j] * ua[j][k];
                fb += f[3 * i + k] * p->c->length[j] * ub[j][k];
            }
        out[j] = fa;
        out[n + j] = fb;
    }
}

typedef double (*scalar3_fn)(const fd3_problem *, const double *, const double *);

/* Second difference of f about q = qd = 0 in (x_a, y_b), each q (0) or qd (1). */
static double mixed3(scalar3_fn f, const fd3_problem *p, int wa, size_t a, double ha, int wb,
                     size_t b, double hb)
{
    double sum = 0;
    for (int sa = -1; sa <= 1; sa += 2)
        for (int sb = -1; sb <= 1; sb += 2) {
            double qq[2 * NMAX] = {0}, qd[2 * NMAX] = {0};
            (wa ? qd : qq)[a] += sa * ha;
            (wb ? qd : qq)[b] += sb * hb;
            sum += sa * sb * f(p, qq, qd);
        }
    return sum / (4 * ha * hb);
}

/* First difference of the drag force about q = qd = 0 in q_b (which = 0) or qd_b (1). */
static void drag_derivative(const fd3_problem *p, int which, size_t b, double h, double *out)
{
    const size_t q = 2 * p->c->n;
    double plus[2 * NMAX], minus[2 * NMAX];
    for (int side = -1; side <= 1; side += 2) {
        double qq[2 * NMAX] = {0}, qd[2 * NMAX] = {0};
        (which ? qd : qq)[b] = side * h;
        drag_force(p, qq, qd, side > 0 ? plus : minus);
    }
    for (size_t a = 0; a < q; a++) out[a] = (plus[a] - minus[a]) / (2 * h);
}

/* The trailing shape of mode k, side s of the odd chain and its linearisation. */
static void driven_shape(whirl_stability *w, const whirl_model *m, int mode, int side,
                         fd3_problem *p)
{
    whirl_driven_info info;
    double growth;
    const int status = whirl_stability_driven_mode(w, m, mode, side, &info, &growth);
    if (status) print_message("# mode %d side %d: %s\n", mode, side, whirl_last_error());
    assert_int_equal(status, 0);
    assert_true(fabs(info.tip[1]) > 1e-3); /* out of the x-z plane: it trails */
    const double *x, *y, *z;
    whirl_stability_nodes(w, &x, &y, &z);
    p->c = m->chain;
    p->omega = m->omega;
    p->damping = m->internal_damping;
    p->eps = m->drive_radius;
    p->drag = m->air_drag;
    p->drag2 = m->air_drag_quadratic;
    charts_from_nodes(p, x, y, z);
}

static void test_driven_matrices_by_finite_differences(void **state)
{
    (void)state;
    const size_t n = 6, q = 2 * n;
    whirl_chain *c = odd_chain(n);
    whirl_stability *w = whirl_stability_alloc(n);
    const whirl_model m = driven_model(c, 3.1, 0.057, 0.053, 0.083, 0.041);
    for (int side = -1; side <= 1; side += 2) {
        fd3_problem p;
        driven_shape(w, &m, 1, side, &p);
        const double *mm = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS);
        const double *gg = whirl_stability_get_matrix(w, WHIRL_STABILITY_GYROSCOPIC);
        const double *cc = whirl_stability_get_matrix(w, WHIRL_STABILITY_DAMPING);
        const double *kk = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
        const double km = max_abs(q * q, kk), mmax = max_abs(q * q, mm), gm = max_abs(q * q, gg);
        const double cm = max_abs(q * q, cc), h = 1e-4;
        /* the shape is an equilibrium here too: dL/dq + Q = 0 at rest */
        double q0[2 * NMAX] = {0}, qd0[2 * NMAX] = {0}, force[2 * NMAX], balance = 0, load = 0;
        drag_force(&p, q0, qd0, force);
        for (size_t a = 0; a < q; a++) {
            double qp[2 * NMAX] = {0}, qm[2 * NMAX] = {0};
            qp[a] = h, qm[a] = -h;
            const double dl = (lagrangian3(&p, qp, qd0) - lagrangian3(&p, qm, qd0)) / (2 * h);
            balance = fmax(balance, fabs(dl + force[a]));
            load = fmax(load, fabs(force[a]));
        }
        double err_m = 0, err_g = 0, err_k = 0, err_c = 0, skew = 0;
        for (size_t b = 0; b < q; b++) {
            double dq_force[2 * NMAX], dqd_force[2 * NMAX];
            drag_derivative(&p, 0, b, h, dq_force);
            drag_derivative(&p, 1, b, h, dqd_force);
            for (size_t a = 0; a < q; a++) {
                const double fm = mixed3(lagrangian3, &p, 1, a, 1.0, 1, b, 1.0);
                const double fg = mixed3(lagrangian3, &p, 1, a, 1.0, 0, b, h) -
                                  mixed3(lagrangian3, &p, 0, a, h, 1, b, 1.0);
                const double fk = -mixed3(lagrangian3, &p, 0, a, h, 0, b, h) - dq_force[a];
                const double fc = mixed3(rayleigh3, &p, 1, a, 1.0, 1, b, 1.0) - dqd_force[a];
                err_m = fmax(err_m, fabs(fm - mm[a * q + b]));
                err_g = fmax(err_g, fabs(fg - gg[a * q + b]));
                err_k = fmax(err_k, fabs(fk - kk[a * q + b]));
                err_c = fmax(err_c, fabs(fc - cc[a * q + b]));
                skew = fmax(skew, fabs(kk[a * q + b] - kk[b * q + a]));
            }
        }
        print_message("# driven side %+d: equilibrium %.2g of %.2g; finite differences |dM| %.2g "
                      "|dG| %.2g |dK| %.2g |dC| %.2g (relative), K skew part %.3g\n", side,
                      balance, load, err_m / mmax, err_g / gm, err_k / km, err_c / cm, skew / km);
        assert_true(load > 1e-3 && balance < 1e-7 * load);
        assert_true(err_m < 1e-12 * mmax);
        assert_true(err_g < 1e-7 * gm);
        assert_true(err_k < 1e-7 * km);
        assert_true(err_c < 1e-7 * cm);
        assert_true(skew > 1e-3 * km); /* the drag's circulatory part */
        /* no symmetry: nothing deflated */
        size_t count;
        const double *re, *im;
        assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
        assert_int_equal(count, 4 * n);
        assert_true(max_abs(q, whirl_stability_symmetry(w)) == 0);
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

static void test_driven_against_dynamics(void **state)
{
    (void)state;
    const size_t n = 7, q = 2 * n;
    whirl_chain *c = odd_chain(n);
    whirl_stability *w = whirl_stability_alloc(n);
    const whirl_model m = driven_model(c, 4.4, 0.023, 0.041, 0.087, 0.113);
    fd3_problem p;
    driven_shape(w, &m, 2, 1, &p);
    double dq[2 * NMAX], dqd[2 * NMAX];
    for (size_t a = 0; a < q; a++) {
        dq[a] = sin(3.7 * (double)a + 0.4);
        dqd[a] = cos(2.9 * (double)a + 1.1);
    }
    gsl_vector *pred = gsl_vector_alloc(q);
    linear_prediction(w, q, dq, dqd, pred);
    /* whirl_dyn_rhs at q = +-h dq, q' = +-h dqd: d_j'' projected on the chart */
    whirl_dyn *dyn = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(dyn);
    const double h = 1e-5;
    double acc[3][2 * NMAX];
    for (int side = 0; side < 3; side++) {
        const double sg = side == 0 ? h : side == 1 ? -h : 0;
        double qq[2 * NMAX], qqd[2 * NMAX], x[3 * NMAX], v[3 * NMAX], ud[NMAX][3];
        double y[6 * NMAX], dy[6 * NMAX];
        for (size_t a = 0; a < q; a++) qq[a] = sg * dq[a], qqd[a] = sg * dqd[a];
        chart_state(&p, qq, qqd, x, v, ud);
        assert_int_equal(whirl_dyn_set_state(dyn, 0, x, v, y), 0);
        assert_int_equal(whirl_dyn_rhs(0, y, dy, dyn), 0);
        for (size_t j = 0; j < n; j++) {
            const double *dd = dy + 3 * n + 3 * j;
            acc[side][j] = (p.ch[j].e1[0] * dd[0] + p.ch[j].e1[1] * dd[1] +
                            p.ch[j].e1[2] * dd[2]) / c->length[j];
            acc[side][n + j] = (p.ch[j].e2[0] * dd[0] + p.ch[j].e2[1] * dd[1] +
                                p.ch[j].e2[2] * dd[2]) / c->length[j];
        }
    }
    double err = 0, scale = 0, rest = 0;
    for (size_t a = 0; a < q; a++) {
        const double fd = (acc[0][a] - acc[1][a]) / (2 * h);
        err = fmax(err, fabs(fd - gsl_vector_get(pred, a)));
        scale = fmax(scale, fabs(gsl_vector_get(pred, a)));
        rest = fmax(rest, fabs(acc[2][a]));
    }
    print_message("# driven against whirl_dyn_rhs: |d q''| %.2g relative, at rest |q''| %.2g\n",
                  err / scale, rest);
    assert_true(err < 1e-6 * scale);
    assert_true(rest < 1e-9 * scale); /* the shape is at rest in the dynamics too */
    whirl_dyn_free(dyn);
    gsl_vector_free(pred);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* Without drive and drag: the planar formulas (header of src/stability.c), the same spectrum
 * for the shape turned about the axis, and the driven module's shape at eps = 0. */
static void test_planar_reduction(void **state)
{
    (void)state;
    const size_t n = 8, q = 2 * n;
    whirl_chain *c = odd_chain(n);
    const double omega = 4.7, damping = 0.019;
    double r[NMAX + 1], z[NMAX + 1], t[NMAX];
    assert_int_equal(find_mode(c, omega, 2, r, z), 0);
    for (size_t j = 0; j < n; j++) t[j] = atan2(r[j + 1] - r[j], z[j] - z[j + 1]);
    whirl_model m = model_of(c, omega, damping);
    whirl_stability *w = whirl_stability_alloc(n);
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
    /* the planar formulas: T_j from the loads below, mu_j the masses below */
    double expect[4][4 * NMAX * NMAX] = {{0}}, tension[NMAX], mu[NMAX];
    double px = 0, pz = 0, msum = 0, xi[NMAX], xs = 0;
    for (size_t j = 0; j < n; j++) xi[j] = xs += c->length[j] * sin(t[j]);
    for (size_t j = n; j-- > 0;) {
        px += c->mass[j] * omega * omega * xi[j];
        pz -= c->mass[j] * c->gravity;
        tension[j] = px * sin(t[j]) - pz * cos(t[j]);
        mu[j] = msum += c->mass[j];
    }
    for (size_t j = 0; j < n; j++)
        for (size_t k = 0; k < n; k++) {
            const double ml = mu[j > k ? j : k] * c->length[j] * c->length[k];
            expect[0][j * q + k] = ml * cos(t[j] - t[k]);
            expect[0][(n + j) * q + n + k] = ml;
            expect[1][j * q + n + k] = -2 * omega * ml * cos(t[j]);
            expect[1][(n + k) * q + j] = 2 * omega * ml * cos(t[j]);
            expect[3][j * q + k] = -omega * omega * ml * cos(t[j]) * cos(t[k]) +
                                   (j == k) * tension[j] * c->length[j];
            expect[3][(n + j) * q + n + k] = -omega * omega * ml +
                                             (j == k) * tension[j] * c->length[j];
            if (j == k) {
                expect[2][j * q + j] = expect[2][(n + j) * q + n + j] = damping * (1 + (j + 1 < n));
            } else if (k == j + 1) {
                expect[2][j * q + k] = expect[2][k * q + j] = -damping * cos(t[k] - t[j]);
                expect[2][(n + j) * q + n + k] = expect[2][(n + k) * q + n + j] = -damping;
            }
        }
    for (int which = 0; which < 4; which++) {
        const double *got = whirl_stability_get_matrix(w, (whirl_stability_matrix)which);
        double err = 0;
        for (size_t i = 0; i < q * q; i++) err = fmax(err, fabs(got[i] - expect[which][i]));
        assert_true(err < 1e-13 * max_abs(q * q, expect[which]));
    }
    size_t count;
    const double *re, *im;
    double plane_re[4 * NMAX], plane_im[4 * NMAX];
    assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
    assert_int_equal(count, 4 * n - 1);
    memcpy(plane_re, re, count * sizeof(double));
    memcpy(plane_im, im, count * sizeof(double));
    /* turned about the axis by 0.77: a non-planar chart, the same spectrum */
    double x[NMAX + 1], y[NMAX + 1];
    for (size_t i = 0; i <= n; i++) x[i] = cos(0.77) * r[i], y[i] = sin(0.77) * r[i];
    assert_int_equal(whirl_stability_linearise_3d(w, &m, x, y, z), 0);
    size_t count2;
    assert_int_equal(whirl_stability_eigenvalues(w, &count2, &re, &im), 0);
    assert_int_equal(count2, count);
    double worst = 0, scale = 0;
    for (size_t i = 0; i < count; i++) {
        double best = INFINITY;
        for (size_t k = 0; k < count; k++)
            best = fmin(best, hypot(re[i] - plane_re[k], im[i] - plane_im[k]));
        worst = fmax(worst, best);
        scale = fmax(scale, hypot(plane_re[i], plane_im[i]));
    }
    print_message("# turned shape: spectrum differs by %.2g (scale %.3g)\n", worst, scale);
    assert_true(worst < 1e-9 * scale);
    /* the driven module at eps = c = 0 gives the free shape and the same growth */
    double free_growth, driven_growth;
    assert_int_equal(whirl_stability_mode(w, &m, 2, NULL, &free_growth), 0);
    for (int side = -1; side <= 1; side += 2) {
        assert_int_equal(whirl_stability_driven_mode(w, &m, 2, side, NULL, &driven_growth), 0);
        assert_true(fabs(driven_growth - free_growth) < 1e-9 * fabs(free_growth));
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* The uniform chain with linear drag only: C = c M and the drag's position term c G / 2, so
 * q = e^{-ct/2} p turns M q'' + (G + c M) q' + (K + c G/2) q = 0 into the conservative
 * M p'' + G p' + (K - c^2 M / 4) p = 0: the spectrum is -c/2 plus a Hamiltonian one (symmetric
 * about the imaginary axis), and a stable shape decays at exactly c/2. */
static void test_uniform_linear_drag_spectrum(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    const double drag = 0.137;
    const whirl_model m = driven_model(c, 3.3, 0, 0.043, drag, 0);
    for (int side = -1; side <= 1; side += 2) {
        double growth;
        assert_int_equal(whirl_stability_driven_mode(w, &m, 1, side, NULL, &growth), 0);
        size_t count;
        const double *re, *im;
        assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
        double worst = 0, scale = 0;
        for (size_t i = 0; i < count; i++) { /* -(lambda + c/2) - c/2 is an eigenvalue too */
            const double mre = -re[i] - drag, mim = -im[i];
            double best = INFINITY;
            for (size_t k = 0; k < count; k++) best = fmin(best, hypot(re[k] - mre, im[k] - mim));
            worst = fmax(worst, best);
            scale = fmax(scale, hypot(re[i], im[i]));
        }
        print_message("# uniform chain, linear drag %g, mode 1 side %+d: growth %.15g, mirror "
                      "about -c/2 within %.2g (scale %.3g)\n", drag, side, growth, worst, scale);
        assert_true(worst < 1e-9 * scale);
        if (side > 0) assert_true(fabs(growth + drag / 2) < 1e-9);
        else assert_true(growth > 0.01);
    }
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* Records the run's samples (t, log ratio) for a decay fit. */
typedef struct {
    size_t count;
    double t[4096], y[4096];
} record;

static int record_samples(double t, double ratio, void *data)
{
    record *r = data;
    if (r->count < 4096) r->t[r->count] = t, r->y[r->count++] = log(ratio);
    return GSL_SUCCESS;
}

/* Perturbed runs of trailing shapes (12 links, eps 0.05): the far-side mode 1 grows as predicted
 * (linear and quadratic drag); the near-side mode 1 converges (linear drag: every mode decays at
 * c/2, see above, so the fitted decay of the whole run is the predicted rate). */
static void test_driven_runs(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    const whirl_model m = driven_model(c, 3.0, 0, 0.05, 0.1, 0.05);
    double growth;
    const double *x, *y, *z;
    whirl_stability_run_result r;
    whirl_stability_run_params p = whirl_stability_run_defaults();
    p.method = "rk4";
    assert_int_equal(whirl_stability_driven_mode(w, &m, 1, -1, NULL, &growth), 0);
    whirl_stability_nodes(w, &x, &y, &z);
    assert_int_equal(whirl_stability_run_shape(&m, x, y, z, &p, &r), 0);
    print_message("# driven mode 1 far side: eig %.6g sim %.6g over [%.3g, %.3g]\n", growth,
                  r.sim_growth, r.fit_from, r.fit_to);
    assert_true(growth > 0.01);
    assert_int_equal(r.verdict, WHIRL_VERDICT_UNSTABLE);
    assert_true(fabs(r.sim_growth / growth - 1) < 0.05);

    static record rec;
    rec.count = 0;
    p.observe = record_samples;
    p.observe_data = &rec;
    const whirl_model linear = driven_model(c, 3.0, 0, 0.05, 0.1, 0);
    assert_int_equal(whirl_stability_driven_mode(w, &linear, 1, 1, NULL, &growth), 0);
    whirl_stability_nodes(w, &x, &y, &z);
    assert_int_equal(whirl_stability_run_shape(&linear, x, y, z, &p, &r), 0);
    double st = 0, sy = 0, stt = 0, sty = 0, k = (double)rec.count;
    for (size_t i = 0; i < rec.count; i++) {
        st += rec.t[i], sy += rec.y[i], stt += rec.t[i] * rec.t[i], sty += rec.t[i] * rec.y[i];
    }
    const double decay = (k * sty - st * sy) / (k * stt - st * st);
    print_message("# driven mode 1 near side: eig %.6g, fitted decay %.6g, verdict %s at t = "
                  "%.3g\n", growth, decay, whirl_verdict_name(r.verdict), r.duration);
    assert_true(growth < -0.01);
    assert_int_equal(r.verdict, WHIRL_VERDICT_CONVERGING);
    assert_true(r.end_deviation <= 1e-2 && r.sim_growth == 0);
    assert_true(fabs(decay / growth - 1) < 0.1);
    /* the free-shape entry point refuses a drive */
    p = whirl_stability_run_defaults();
    assert_int_equal(whirl_stability_run(&m, 0.5, &p, &r), GSL_EINVAL);
    assert_int_equal(whirl_stability_shape(w, &m, 0.5, &growth), GSL_EINVAL);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- large linearisations: the eigen-solve on a worker thread ---- */

/* Above 32 links the dense solve runs on a thread of its own (stability.h): its spectrum is the
 * full first-order form's (GSL's eigensolver here), as for the small chains. */
static void test_worker_spectrum(void **state)
{
    (void)state;
    const size_t n = 40;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.3);
    whirl_model m = model_of(c, 4.3, 0.02);
    whirl_stability *w = whirl_stability_alloc(n);
    double growth;
    assert_int_equal(whirl_stability_mode(w, &m, 2, NULL, &growth), 0);
    size_t count;
    const double *re, *im;
    assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
    assert_int_equal(count, 4 * n - 1);
    double *fre = malloc(4 * n * sizeof *fre), *fim = malloc(4 * n * sizeof *fim);
    int *used = calloc(4 * n, sizeof *used);
    full_spectrum(w, n, fre, fim);
    double scale = 0, worst = 0, largest = -INFINITY;
    for (size_t i = 0; i < 4 * n; i++) scale = fmax(scale, hypot(fre[i], fim[i]));
    for (size_t i = 0; i < count; i++) {
        size_t best = 0;
        double dist = INFINITY;
        for (size_t j = 0; j < 4 * n; j++) {
            const double dj = hypot(re[i] - fre[j], im[i] - fim[j]);
            if (!used[j] && dj < dist) dist = dj, best = j;
        }
        used[best] = 1;
        worst = fmax(worst, dist);
        largest = fmax(largest, re[i]);
    }
    print_message("# 40 links, mode 2, D 0.02: worker vs GSL %.2g (scale %.3g), growth %.6g\n",
                  worst, scale, growth);
    assert_true(worst < 1e-7 * scale);
    assert_true(growth > 0); /* mode 2 with damping grows (Kelvin-Tait-Chetaev) */
    assert_true(growth == largest);
    free(fre), free(fim), free(used);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* A stop request during the dense solve of 150 links (a 600 x 600 eigenproblem, a few tenths of
 * a second) ends the call with WHIRL_EINTERRUPTED; the workspace then linearises and solves
 * again, to the same growth as before (the abandoned solve frees its own memory: the sanitizer
 * build checks that nothing leaks or races). */
static void test_worker_stop(void **state)
{
    (void)state;
    const size_t n = 150;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_model m = model_of(c, 5.1, 0.01);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_shape_info info;
    double growth, again = -1;
    whirl_stop_clear();
    assert_int_equal(whirl_stability_mode(w, &m, 2, &info, &growth), 0);
    /* linearised again, then the stop 5 ms into the call whose only work is the solve */
    const double *x, *y, *z;
    whirl_stability_nodes(w, &x, &y, &z);
    double *r = malloc(2 * (n + 1) * sizeof *r), *h = r + n + 1;
    memcpy(r, x, (n + 1) * sizeof *r);
    memcpy(h, z, (n + 1) * sizeof *h);
    assert_int_equal(whirl_stability_linearise(w, &m, r, h), 0);
    free(r);
    size_t count;
    const double *re, *im;
    pthread_t stopper;
    assert_int_equal(pthread_create(&stopper, NULL, request_stop_soon, NULL), 0);
    const int status = whirl_stability_eigenvalues(w, &count, &re, &im);
    pthread_join(stopper, NULL);
    char message[256];
    snprintf(message, sizeof message, "%s", whirl_last_error());
    const int gone = whirl_stability_get_matrix(w, WHIRL_STABILITY_MASS) == NULL;
    whirl_stop_clear(); /* before any assertion, so that a failure stops nothing else */
    assert_int_equal(status, WHIRL_EINTERRUPTED);
    assert_true(strstr(message, "stopped by request during the eigen-solve") != NULL);
    assert_true(gone);
    assert_int_equal(whirl_stability_growth(w, &again), GSL_EINVAL); /* nothing linearised */
    assert_int_equal(whirl_stability_shape(w, &m, info.tip_r, &again), 0);
    print_message("# 150 links, mode 2: growth %.17g, after the stop %.17g\n", growth, again);
    assert_true(growth > 0 && again == growth);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* The O(N^2) and O(N^3) steps before the eigen-solve read the stop request too (stability.h):
 * above 32 links a linearisation with a stop pending returns WHIRL_EINTERRUPTED and none is
 * kept; at 32 links and fewer it runs as before. The index of 400 links (dsyev of 800 rows, on a
 * worker) stopped 5 ms in returns WHIRL_EINTERRUPTED with the linearisation kept, and after the
 * stop is cleared gives the index it gave before. */
static void test_stop_before_solve(void **state)
{
    (void)state;
    const size_t n = 400;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0), *small = whirl_chain_alloc_uniform(20, 0);
    whirl_model m = model_of(c, 5.1, 0), ms = model_of(small, 5.1, 0);
    whirl_stability *w = whirl_stability_alloc(n), *ws = whirl_stability_alloc(20);
    double *r = malloc(4 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1, *rs = t + n + 1;
    whirl_shape_info info;
    whirl_stop_clear();
    assert_int_equal(whirl_nlink_solve_nodes(c, 5.1, 2, &info, r, z, t), 0);
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
    int index = -1, again = -1;
    assert_int_equal(whirl_stability_index(w, &index), 0);
    /* a stop pending: no linearisation of 400 links; one of 20 links as before */
    assert_int_equal(whirl_nlink_solve_nodes(small, 5.1, 2, &info, rs, rs + 21, rs + 42), 0);
    whirl_stop_request();
    const int stopped = whirl_stability_linearise(w, &m, r, z);
    char message[256];
    snprintf(message, sizeof message, "%s", whirl_last_error());
    const int small_status = whirl_stability_linearise(ws, &ms, rs, rs + 21);
    whirl_stop_clear();
    assert_int_equal(stopped, WHIRL_EINTERRUPTED);
    assert_non_null(strstr(message, "stopped by request during the linearisation"));
    assert_int_equal(whirl_stability_index(w, &again), GSL_EINVAL); /* none kept */
    assert_int_equal(small_status, 0);
    /* the index stopped while it runs */
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), 0);
    pthread_t stopper;
    assert_int_equal(pthread_create(&stopper, NULL, request_stop_soon, NULL), 0);
    const int status = whirl_stability_index(w, &again);
    pthread_join(stopper, NULL);
    snprintf(message, sizeof message, "%s", whirl_last_error());
    whirl_stop_clear();
    assert_int_equal(status, WHIRL_EINTERRUPTED);
    assert_non_null(strstr(message, "stopped by request"));
    assert_int_equal(whirl_stability_index(w, &again), 0); /* the linearisation kept */
    print_message("# 400 links, mode 2 at 5.1: index %d, after the stop %d\n", index, again);
    assert_int_equal(again, index);
    assert_true(index > 0); /* mode 2 is a saddle of the amended potential */
    free(r);
    whirl_stability_free(w);
    whirl_stability_free(ws);
    whirl_chain_free(c);
    whirl_chain_free(small);
}

/* ---- high rates: the shape from the branch's link angles ---- */

/* The largest force across a link of the planar shape (r[i], z[i]) at omega, from the loads
 * m_i (omega^2 (r_i - r_0), -g) of the masses below it (the pivot put on the axis, as the
 * linearisation puts it), over the scale M (g + omega^2 L) of the loads: round-off (positions
 * to eps L) at an equilibrium. */
static double force_across(const whirl_chain *c, double omega, const double *r, const double *z)
{
    double fr = 0, fz = 0, worst = 0;
    for (size_t j = c->n; j >= 1; j--) {
        fr += c->mass[j - 1] * omega * omega * (r[j] - r[0]);
        fz -= c->mass[j - 1] * c->gravity;
        const double ur = r[j] - r[j - 1], uz = z[j] - z[j - 1];
        worst = fmax(worst, fabs(fr * uz - fz * ur) / hypot(ur, uz));
    }
    return worst / (whirl_chain_total_mass(c) *
                    (c->gravity + omega * omega * whirl_chain_total_length(c)));
}

/* N = 15 at omega = 150: mode 7's tip radius (2.6e-5) no longer fixes its shape (rebuilt from
 * it, the pivot lands 3.7e-4 off the axis and the balance is lost), so the stability module
 * takes the nodes from the branch's link angles. Its linearisation point balances every link
 * to round-off; the growth is that of a perturbed run of the dynamics, and mode 3, neutral
 * there, stays bounded in a run. The window search over 140..150 linearises the same shapes. */
static void test_high_rate_shape(void **state)
{
    (void)state;
    const size_t n = 15;
    const double omega = 150;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    whirl_model m = model_of(c, omega, 0);
    whirl_shape_info info;
    double growth, r[NMAX + 1], z[NMAX + 1], t[NMAX + 1];
    /* the premise: the tip radius alone does not give the shape at this rate */
    assert_int_equal(whirl_stability_mode(w, &m, 7, &info, &growth), GSL_SUCCESS);
    assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, t), GSL_SUCCESS);
    const double miss = fabs(r[0]);
    const double *x, *y, *zz;
    whirl_stability_nodes(w, &x, &y, &zz);
    const double across = force_across(c, omega, x, zz);
    for (size_t i = 0; i <= n; i++) assert_true(y[i] == 0);
    whirl_stability_run_params p = whirl_stability_run_defaults();
    p.periods = 20;
    whirl_stability_run_result run;
    assert_int_equal(whirl_stability_run_shape(&m, x, y, zz, &p, &run), GSL_SUCCESS);
    print_message("# N = 15, mode 7, omega 150: tip radius %.3g (the pivot %.3g off the axis "
                  "from it); linearised shape: force across a link %.2e of M (g + omega^2 L); growth "
                  "%.10g, perturbed run %.10g (%s)\n", info.tip_r, miss, across, growth,
                  run.sim_growth, whirl_verdict_name(run.verdict));
    assert_true(miss > 1e-6);
    assert_true(across < 10 * (double)n * DBL_EPSILON);
    assert_true(growth > 30);
    assert_int_equal(run.verdict, WHIRL_VERDICT_UNSTABLE);
    assert_true(fabs(run.sim_growth - growth) < 0.03 * growth);
    /* mode 3: neutral, and a run stays below 100 times its perturbation */
    double neutral;
    assert_int_equal(whirl_stability_mode(w, &m, 3, NULL, &neutral), GSL_SUCCESS);
    whirl_stability_nodes(w, &x, &y, &zz);
    const double across3 = force_across(c, omega, x, zz);
    assert_int_equal(whirl_stability_run_shape(&m, x, y, zz, &p, &run), GSL_SUCCESS);
    print_message("# mode 3: force across a link %.2e of M (g + omega^2 L); growth %g, perturbed run: %s "
                  "(largest deviation %.3g times the initial one)\n", across3, neutral,
                  whirl_verdict_name(run.verdict), run.max_deviation);
    assert_true(across3 < 10 * (double)n * DBL_EPSILON);
    assert_true(neutral == 0);
    assert_int_equal(run.verdict, WHIRL_VERDICT_STABLE);
    /* the window search: mode 7 unstable over all of 140..150, the same growth at 150 */
    whirl_windows *ws = whirl_windows_alloc(n);
    whirl_windows_params wp = whirl_windows_defaults();
    wp.omega_min = 140;
    wp.omega_max = omega;
    whirl_window win[4];
    size_t count = 0;
    whirl_windows_stats stats;
    assert_int_equal(whirl_windows_find(ws, c, 7, &wp, win, 4, &count, &stats), GSL_SUCCESS);
    assert_int_equal(count, 1);
    assert_true(win[0].open_from && win[0].open_to);
    print_message("# window search 140..150: largest growth %.13g at %g\n", win[0].max_growth,
                  win[0].at);
    assert_float_equal(win[0].at, omega, 0);
    assert_float_equal(win[0].max_growth, growth, 1e-9 * growth);
    whirl_windows_free(ws);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* ---- errors ---- */

static void test_errors(void **state)
{
    (void)state;
    assert_null(whirl_stability_alloc(0));
    const size_t n = 5;
    whirl_chain *c = odd_chain(n);
    whirl_stability *w = whirl_stability_alloc(n);
    double r[NMAX + 1], z[NMAX + 1], growth;
    assert_int_equal(whirl_stability_growth(w, &growth), GSL_EINVAL); /* nothing linearised */
    assert_int_equal(find_mode(c, 2.9, 1, r, z), 0);
    whirl_model m = model_of(c, 2.9, 0);
    m.internal_damping = -0.1;
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    assert_true(strstr(whirl_last_error(), "damping") != NULL);
    m = model_of(c, 2.9, 0);
    m.air_drag = 0.2; /* the free shape is no equilibrium under drag */
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    assert_true(strstr(whirl_last_error(), "equilibrium") != NULL);
    assert_int_equal(whirl_stability_driven_mode(w, &m, 1, 1, NULL, &growth), GSL_EDOM);
    m.drive_radius = 0.05;
    assert_int_equal(whirl_stability_driven_mode(w, &m, 1, 2, NULL, &growth), GSL_EINVAL);
    m.drive_radius = -0.05;
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    assert_true(strstr(whirl_last_error(), "drive") != NULL);
    m = model_of(c, 2.9, 0);
    m.dim = 2;
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    m = model_of(c, 3.0, 0); /* the shape of 2.9 is not an equilibrium at 3.0 */
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    assert_true(strstr(whirl_last_error(), "equilibrium") != NULL);
    m = model_of(c, 2.9, 0);
    z[3] += 1e-3; /* a link of the wrong length */
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    whirl_chain *other = odd_chain(n + 1);
    m.chain = other;
    assert_int_equal(whirl_stability_linearise(w, &m, r, z), GSL_EINVAL);
    /* a mode that does not exist */
    m = model_of(c, 0.5, 0);
    assert_int_equal(whirl_stability_mode(w, &m, 1, NULL, &growth), GSL_EDOM);
    whirl_chain_free(other);
    whirl_stability_free(w);
    whirl_stability_free(NULL);
    whirl_chain_free(c);
}


/* The largest real part of the eigenvalues and of those with Im > 0 the three largest, of the
 * linearisation and of a central-difference Jacobian of whirl_dyn_rhs (steps 1e-6 of the largest
 * link vector entry, times omega for the rates) about the same shape: N = 100, mode 50, omega =
 * 250. The Cartesian state holds 2 N constraint directions more than q (their eigenvalues are 0 in
 * the exact Jacobian, order 1e-3 in the differenced one: far below the unstable ones). */
static int by_real_desc(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

static void test_high_mode_by_rhs_jacobian(void **state)
{
    (void)state;
    enum { N = 100 };
    whirl_chain *c = whirl_chain_alloc_uniform(N, 0);
    whirl_model m = {0};
    m.chain = c, m.dim = 3, m.frame = WHIRL_FRAME_ROTATING, m.omega = 250;
    whirl_stability *w = whirl_stability_alloc(N);
    assert_non_null(w);
    double growth;
    assert_int_equal(whirl_stability_mode(w, &m, 50, NULL, &growth), 0);
    size_t count;
    const double *re, *im;
    assert_int_equal(whirl_stability_eigenvalues(w, &count, &re, &im), 0);
    double lin[4 * N], fd[4];
    size_t nl = 0;
    for (size_t i = 0; i < count; i++)
        if (im[i] > 0) lin[nl++] = re[i];
    qsort(lin, nl, sizeof *lin, by_real_desc);
    const double *x, *y, *z;
    whirl_stability_nodes(w, &x, &y, &z);
    double links[3 * N];
    assert_int_equal(whirl_shape_links(N, x, y, z, links), 0);
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(d);
    const size_t n = whirl_dyn_size(d);
    double *y0 = malloc(n * sizeof *y0), *yp = malloc(n * sizeof *yp);
    double *fp = malloc(n * sizeof *fp), *fm = malloc(n * sizeof *fm);
    double *jac = malloc(n * n * sizeof *jac), *wr = malloc(n * sizeof *wr);
    double *wi = malloc(n * sizeof *wi);
    assert_true(y0 && yp && fp && fm && jac && wr && wi);
    assert_int_equal(whirl_dyn_state_from_shape(d, 0, links, m.omega, y0), 0);
    double scale = 0; /* the largest link vector entry; the rates' (all 0 at rest) times omega */
    for (size_t i = 0; 2 * i < n; i++) scale = fmax(scale, fabs(y0[i]));
    for (size_t j = 0; j < n; j++) { /* column j, column-major */
        const double h = 1e-6 * scale * (2 * j < n ? 1 : m.omega);
        memcpy(yp, y0, n * sizeof *yp);
        yp[j] = y0[j] + h;
        assert_int_equal(whirl_dyn_rhs(0, yp, fp, d), 0);
        yp[j] = y0[j] - h;
        assert_int_equal(whirl_dyn_rhs(0, yp, fm, d), 0);
        for (size_t i = 0; i < n; i++) jac[j * n + i] = (fp[i] - fm[i]) / (2 * h);
    }
    assert_int_equal(LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, jac,
                                   (lapack_int)n, wr, wi, NULL, 1, NULL, 1), 0);
    size_t nf = 0;
    for (size_t i = 0; i < n; i++)
        if (wi[i] > 0) wr[nf++] = wr[i];
    qsort(wr, nf, sizeof *wr, by_real_desc);
    for (int k = 0; k < 4; k++) fd[k] = wr[k];
    print_message("# N = 100 mode 50 omega 250: growth %.10g; linearisation %.10g %.10g %.10g, "
                  "Jacobian of the right-hand side %.10g %.10g %.10g\n", growth, lin[0], lin[1],
                  lin[2], fd[0], fd[1], fd[2]);
    assert_true(growth == lin[0] && growth > 72.3 && growth < 72.4);
    for (int k = 0; k < 3; k++) assert_true(fabs(fd[k] / lin[k] - 1) < 1e-7);
    free(y0), free(yp), free(fp), free(fm), free(jac), free(wr), free(wi);
    whirl_dyn_free(d);
    whirl_stability_free(w);
    whirl_chain_free(c);
}

/* The map (whirl_stability_map, OpenMP threads) against the same shapes analysed one by one on
 * this thread (whirl_stability_linearise, whirl_stability_growth): equal to the bit, whatever the
 * sharing; a failure is that of the earliest failed point, with its own message. */
static void test_map(void **state)
{
    (void)state;
    enum { RATES = 9, LINKS = 10 };
    whirl_chain *c = whirl_chain_alloc_uniform(LINKS, 0);
    assert_non_null(c);
    double omega[RATES], r[RATES][LINKS + 1], z[RATES][LINKS + 1], t[RATES][LINKS + 1];
    whirl_shape_info info[RATES];
    int exists[RATES];
    for (int j = 0; j < RATES; j++) omega[j] = 3 + 0.75 * j;
    assert_int_equal(whirl_nlink_branch_nodes(c, 2, RATES, omega, info, exists, &r[0][0],
                                              &z[0][0], &t[0][0]),
                     GSL_SUCCESS);
    whirl_stability_point pts[RATES];
    for (int j = 0; j < RATES; j++) {
        assert_true(exists[j]);
        pts[j] = (whirl_stability_point){omega[j], r[j], z[j], j == 4, 0, 0};
    }
    assert_int_equal(whirl_stability_map(c, 0.01, RATES, pts, NULL, NULL), GSL_SUCCESS);
    whirl_stability *w = whirl_stability_alloc(LINKS);
    assert_non_null(w);
    for (int j = 0; j < RATES; j++) {
        if (j == 4) {
            assert_int_equal(pts[j].status, -1); /* skipped */
            continue;
        }
        assert_int_equal(pts[j].status, GSL_SUCCESS);
        whirl_model m = {0};
        m.chain = c;
        m.dim = 3;
        m.frame = WHIRL_FRAME_ROTATING;
        m.omega = omega[j];
        m.internal_damping = 0.01;
        double growth;
        assert_int_equal(whirl_stability_linearise(w, &m, r[j], z[j]), GSL_SUCCESS);
        assert_int_equal(whirl_stability_growth(w, &growth), GSL_SUCCESS);
        assert_memory_equal(&growth, &pts[j].growth, sizeof growth);
        int index;
        assert_int_equal(whirl_stability_index(w, &index), GSL_SUCCESS);
        assert_int_equal(index, pts[j].index);
        assert_int_equal(whirl_verdict_linear(growth, index), growth > 0 ? WHIRL_VERDICT_UNSTABLE
                                                                         : WHIRL_VERDICT_CONVERGING);
    }
    /* two bad points: the earlier one's failure is reported */
    pts[3].omega = -1;
    pts[7].omega = -2;
    for (int j = 0; j < RATES; j++) pts[j].skip = 0;
    const int status = whirl_stability_map(c, 0, RATES, pts, NULL, NULL);
    assert_int_not_equal(status, GSL_SUCCESS);
    assert_int_equal(pts[3].status, status);
    assert_int_equal(whirl_last_status(), status);
    assert_non_null(strstr(whirl_last_error(), "-1"));
    whirl_stability_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hanging_chain),
        cmocka_unit_test(test_matrices_by_finite_differences),
        cmocka_unit_test(test_against_dynamics),
        cmocka_unit_test(test_deflation),
        cmocka_unit_test(test_negative_directions_and_damping),
        cmocka_unit_test(test_with_steady_module),
        cmocka_unit_test(test_perturbed_runs),
        cmocka_unit_test(test_driven_matrices_by_finite_differences),
        cmocka_unit_test(test_driven_against_dynamics),
        cmocka_unit_test(test_planar_reduction),
        cmocka_unit_test(test_uniform_linear_drag_spectrum),
        cmocka_unit_test(test_driven_runs),
        cmocka_unit_test(test_worker_spectrum),
        cmocka_unit_test(test_worker_stop),
        cmocka_unit_test(test_stop_before_solve),
        cmocka_unit_test(test_high_rate_shape),
        cmocka_unit_test(test_high_mode_by_rhs_jacobian),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_map),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
