/* Linear stability of the steady shapes of the continuous chain, in the continuum.
 *
 * The chain: uniform, length 1, mass 1, g = 1, a point mass m at its free end; sigma the
 * arclength from the free end (0) to the pivot (1); X(sigma, t) its position in the frame
 * co-rotating at omega about z, T(sigma, t) its tension. Motion (unit density):
 *     X_tt + 2 omega e_z x X_t - omega^2 P X = (T X_sigma)_sigma - e_z,   |X_sigma| = 1,
 * P = diag(1, 1, 0), the pivot fixed, X(1) = 0, and at the free end
 *     m (X_tt + 2 omega e_z x X_t - omega^2 P X + e_z) = T X_sigma   (m = 0: T(0) = 0).
 * Steady shape (continuum.c): X0 = (r, 0, z) in the x-z plane, with the load ratio q = H / W
 * (H the horizontal force of the part below sigma, W = sigma + m its weight),
 *     r' = -q / S,  (sigma + m) q' + q = omega^2 r,  S = sqrt(1 + q^2),  T0 = (sigma + m) S,
 *     r(1) = 0,  q(0) = omega^2 r(0),
 * with the unit tangent t0 = X0_sigma = (r', z') = (-q, 1) / S and normal n0 = (-z', r').
 * Linearisation: X = X0 + (u, v, w) e^(lambda t), T = T0 + tau e^(lambda t):
 *     lambda^2 u - 2 omega lambda v - omega^2 u = (T0 u' + tau r')'
 *     lambda^2 w                               = (T0 w' + tau z')'
 *     lambda^2 v + 2 omega lambda u - omega^2 v = (T0 v')'
 *     r' u' + z' w' = 0   (inextensible),
 * the in-plane motion (u, w, tau) and the out-of-plane v coupled only by the Coriolis terms. With
 * vh = lambda v and the third equation multiplied by lambda (as for the N-link chain in
 * stability_windows.c) this is LINEAR in mu = lambda^2:
 *     mu u = omega^2 u + 2 omega vh + (T0 u' + tau r')'
 *     mu w = (T0 w' + tau z')'
 *     0    = r' u' + z' w'
 *     mu (vh + 2 omega u) = omega^2 vh + (T0 vh')',
 * a real generalised eigenproblem A x = mu B x in x = (u, w, tau, vh) (B singular: the
 * constraint and tau give infinite eigenvalues, dropped). Boundary conditions: u = w = vh = 0 at
 * the pivot; at the free end m (mu u - 2 omega vh - omega^2 u) = T0 u' + tau r',
 * m mu w = T0 w' + tau z', m (mu (vh + 2 omega u) - omega^2 vh) = T0 vh'; with m = 0 these are
 * tau(0) = 0 and, T0(0) = 0 making sigma = 0 a regular singular point, the boundedness of u, w,
 * vh, which collocation at sigma = 0 imposes by itself. In the tangential and normal components
 * p = t0 . xi, q_n = n0 . xi of xi = (u, w) the system has order 6 (p and tau first order, q_n
 * and vh second order): p, q_n, vh are fixed at the pivot, tau at the free end.
 * Hanging chain (r = q = 0, T0 = sigma + m): u solves mu u - omega^2 u - 2 omega vh = (T0 u')'
 * and the inertial frequencies are those of the hanging chain, j_{0,n} / 2 for m = 0
 * (u = J0(2 w sqrt(sigma))), so mu = -(j_{0,n} / 2 +- omega)^2 in the co-rotating frame; with a
 * tip mass the roots of the J0/Y0 determinant of continuum.c.
 *
 * Discretisation: the chain is cut into elements, each with the p + 1 Chebyshev points
 * sigma = a + h (1 - cos(j pi / p)) / 2 (Trefethen, Spectral Methods in MATLAB, 2000, ch. 6:
 * differentiation matrix), the fields collocated at every point, the equations at the points
 * where no condition replaces them. The coefficients T0, r', z' have branch points off the real
 * axis where q = +-i, a distance ~ W / (omega^2 |r|) from the points where the chain hangs
 * vertically (q = 0): about 0.03 for mode 3 at omega = 9, which one Chebyshev interval resolves
 * only with hundreds of points. Elements are halved (starting from four) until the last two
 * Chebyshev coefficients of r and q on each are below shape_tol of their largest value, so that
 * they are small near those points and large elsewhere, and the convergence is geometric in p.
 * Conditions, in the rows of the equations they replace (the pattern that makes the counts agree
 * with the orders above): at the right end of an element the equation rows of w, of the
 * constraint and of vh carry n0 . xi, t0 . xi and vh continuous with the next element (zero at
 * the pivot), the row of u carries the tangential equation t0 . (E_u, E_w); at the left end of an
 * element after the first the rows of u, w and vh carry the normal derivative n0 . xi', tau and
 * vh' continuous, the constraint is kept; at the free end (m = 0) the row of u carries the normal
 * equation n0 . (E_u, E_w), the row of w tau = 0 (m > 0: the rows of u, w, vh the tip mass's
 * equations). The steady shape is solved by the same collocation (Newton; r continuous at right
 * ends, q at left ends), seeded by the shooting of continuum.c, whose tip radius it reproduces.
 * Eigenvalues, in real arithmetic: the columns of tau in B are zero, so the finite mu are
 * mu = s + 1 / theta with theta the eigenvalues of the block of (A - s B)^-1 B on the rows and
 * columns of (u, w, vh) (a real shift s; one LU factorisation of the pencil, then LAPACK's dgeev
 * on 3/4 of its size; the constraint's infinite mu become theta = 0), and its eigenvectors are
 * the modes' (u, w, vh). Against LAPACK's QZ (dggev) on the whole pencil (Moler & Stewart 1973)
 * the same mu to 1e-8 relative, about 4 times faster. The collocation's round-off limits the mu to
 * about 1e-9 relative (the second-derivative matrices of short elements are large).
 * The rotation about z (v = r, u = w = tau = 0, mu = 0) is removed as the kept mu nearest 0.
 * Krein signature of a neutral mu = -w^2 with eigenvector (u, w, tau, vh) (lambda = i w,
 * v = vh / lambda): the mode's energy w^2 <xi, M xi> + <xi, K xi> = 2 w^2 <xi, xi> - i w <xi, G xi>
 * is, up to a factor 2,
 *     E = int (w^2 (|u|^2 + |w|^2) + |vh|^2 + 2 omega Re(conj(u) vh)) dsigma + (m times the
 *         same at sigma = 0),
 * by Clenshaw-Curtis quadrature on each element (Trefethen 2000, ch. 12).
 * References: Kolodner 1955, Comm. Pure Appl. Math. 8:395 (the steady shapes); Caughey 1958,
 * J. Appl. Mech. 25:465 (whirling of a heavy chain); Trefethen 2000 (collocation); Mackay 1986
 * (Krein signature); Moler & Stewart 1973, SIAM J. Numer. Anal. 10:241 (QZ). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include <lapacke.h>

#include "whirl/continuum_stability.h"
#include "core/error.h"
#include "core/worker.h"
#include "stability/windows_internal.h"

#define CS_ELEMENTS_START 4   /* uniform elements before refinement */
#define CS_ELEMENTS_MAX 64    /* elements at most */
#define CS_POINTS_MAX 360     /* collocation points at most: a pencil of 1440 (5 dense copies,
                                 83 MB; an eigen-solve of about 5 s on one idle core) */
#define CS_SAMPLES 2001       /* samples of the shooting's shape seeding the Newton iteration */
#define CS_NEWTON_MAX 40      /* Newton iterations per element set */

enum { F_U, F_W, F_TAU, F_V, N_FIELDS }; /* fields, and the equations in their rows (F_TAU: the
                                            constraint) */
enum { N_DYNAMIC = 3 };                  /* fields with a mass: u, w, vh */
#define CS_SHIFT 1.0 /* the real shift s of (A - s B)^-1 B [1/T^2], away from the mu of interest */

struct whirl_cstab {
    whirl_cstab_params p;
    size_t cap;               /* points allocated for */
    size_t ne, np;            /* elements and points of the last linearisation */
    int mode;
    double omega;
    double shift;             /* the shift s of the last eigen-solve [1/T^2] */
    double brk[CS_ELEMENTS_MAX + 1]; /* element ends, 0 = brk[0] < ... < brk[ne] = 1 */
    double *dref;             /* (p + 1)^2 differentiation on [0, 1], row-major */
    double *cw;               /* (p + 1) Clenshaw-Curtis weights on [0, 1] */
    double *sig, *r, *q, *wq; /* per point: sigma, the shape, quadrature weight */
    double *t0, *rp, *zp;     /* per point: tension, r', z' */
    double *jac, *res;        /* Newton: (2 np)^2 column-major, 2 np */
    lapack_int *ipiv;
    double *a0, *b0;          /* the pencil (4 np)^2 column-major */
    double *a, *b, *vr;       /* dggev's copies and eigenvectors */
    double *alphar, *alphai, *work; /* theta (3 np) and dgeev's workspace */
    lapack_int lwork;
    double *mu_re, *mu_im;    /* kept mu */
    int *sig_out;
    double *row_a, *row_b;    /* one row of the pencil (4 np) */
    double *ls, *lr, *lq;     /* samples of the shooting (CS_SAMPLES each) */
    windows_arnoldi kr;       /* the window search's Arnoldi iteration (3 np) */
};

whirl_cstab_params whirl_cstab_defaults(void)
{
    whirl_cstab_params p = {16, 0, 1e-11, 30};
    return p;
}

static int check_params(const whirl_cstab_params *p)
{
    if (p->degree < 6 || p->degree > 64)
        return whirl_fail(GSL_EINVAL, "the collocation degree must be in 6..64, got %d",
                          p->degree);
    int status = whirl_check_tip_mass(p->tip_mass);
    if (status) return status;
    if (!(p->shape_tol >= 1e-14 && p->shape_tol <= 1e-3))
        return whirl_fail(GSL_EINVAL, "the shape tolerance must be in [1e-14, 1e-3], got %g",
                          p->shape_tol);
    if (!(p->freq_max > 0 && isfinite(p->freq_max)))
        return whirl_fail(GSL_EINVAL, "the highest frequency kept must be > 0, got %g",
                          p->freq_max);
    return GSL_SUCCESS;
}

void whirl_cstab_free(whirl_cstab *w)
{
    if (w == NULL) return;
    double *arrays[] = {w->dref, w->cw,    w->sig,    w->r,      w->q,    w->wq,    w->t0,
                        w->rp,   w->zp,    w->jac,    w->res,    w->a0,   w->b0,    w->a,
                        w->b,    w->vr,    w->alphar, w->alphai, w->work,  w->mu_re,
                        w->mu_im, w->row_a, w->row_b, w->ls,     w->lr,   w->lq};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    free(w->ipiv);
    free(w->sig_out);
    whirl_windows_arnoldi_release(&w->kr);
    free(w);
}

whirl_cstab *whirl_cstab_alloc(const whirl_cstab_params *p)
{
    if (check_params(p)) return NULL;
    whirl_cstab *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->p = *p;
    const size_t pp = (size_t)p->degree, P = pp + 1;
    w->dref = malloc(P * P * sizeof(double));
    w->cw = malloc(P * sizeof(double));
    w->ls = malloc(CS_SAMPLES * sizeof(double));
    w->lr = malloc(CS_SAMPLES * sizeof(double));
    w->lq = malloc(CS_SAMPLES * sizeof(double));
    if (!w->dref || !w->cw || !w->ls || !w->lr || !w->lq) goto fail;
    /* Chebyshev points x_j = cos(j pi / p) (Trefethen 2000, cheb.m), t = (1 - x) / 2 on [0, 1]
     * increasing with j, d/dt = -2 d/dx; off-diagonal entries exact, the diagonal as minus the
     * row sum */
    double x[65], c[65];
    for (size_t j = 0; j <= pp; j++) {
        x[j] = j == pp ? -1 : j == 0 ? 1 : sin(M_PI * ((double)pp - 2.0 * (double)j) / (2.0 * (double)pp));
        c[j] = (j == 0 || j == pp ? 2 : 1) * (j % 2 ? -1 : 1);
    }
    for (size_t i = 0; i <= pp; i++) {
        double sum = 0;
        for (size_t j = 0; j <= pp; j++) {
            if (i == j) continue;
            const double d = c[i] / (c[j] * (x[i] - x[j]));
            w->dref[i * P + j] = -2 * d;
            sum += d;
        }
        w->dref[i * P + i] = 2 * sum;
    }
    /* Clenshaw-Curtis weights (Trefethen 2000, clencurt.m), halved for [0, 1] */
    for (size_t j = 0; j <= pp; j++) {
        const double th = M_PI * (double)j / (double)pp;
        double v = 1;
        if (j == 0 || j == pp) {
            w->cw[j] = (pp % 2 == 0 ? 1.0 / ((double)(pp * pp) - 1) : 1.0 / (double)(pp * pp)) / 2;
            continue;
        }
        if (pp % 2 == 0) {
            for (size_t k = 1; k < pp / 2; k++)
                v -= 2 * cos(2 * (double)k * th) / (4 * (double)(k * k) - 1);
            v -= cos((double)pp * th) / ((double)(pp * pp) - 1);
        } else {
            for (size_t k = 1; k <= (pp - 1) / 2; k++)
                v -= 2 * cos(2 * (double)k * th) / (4 * (double)(k * k) - 1);
        }
        w->cw[j] = v / (double)pp;
    }
    return w;
fail:
    whirl_cstab_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the continuum's stability workspace");
    return NULL;
}

/* Room for np points. */
static int reserve(whirl_cstab *w, size_t np)
{
    if (np <= w->cap) return GSL_SUCCESS;
    const size_t n = N_FIELDS * np, nn = 2 * np;
    double **per_point[] = {&w->sig, &w->r, &w->q, &w->wq, &w->t0, &w->rp, &w->zp};
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++) {
        free(*per_point[i]);
        *per_point[i] = malloc(np * sizeof(double));
    }
    double **square[] = {&w->a0, &w->b0, &w->a, &w->b, &w->vr};
    for (size_t i = 0; i < sizeof square / sizeof square[0]; i++) {
        free(*square[i]);
        *square[i] = malloc(n * n * sizeof(double));
    }
    double **vec[] = {&w->alphar, &w->alphai, &w->mu_re, &w->mu_im, &w->row_a,
                      &w->row_b};
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) {
        free(*vec[i]);
        *vec[i] = malloc(n * sizeof(double));
    }
    free(w->jac);
    free(w->res);
    free(w->ipiv);
    free(w->sig_out);
    free(w->work);
    w->jac = malloc(nn * nn * sizeof(double));
    w->res = malloc(nn * sizeof(double));
    w->ipiv = malloc(n * sizeof(lapack_int));
    w->sig_out = malloc(n * sizeof(int));
    w->work = NULL;
    w->cap = 0;
    int ok = w->jac && w->res && w->ipiv && w->sig_out;
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++) ok = ok && *per_point[i];
    for (size_t i = 0; i < sizeof square / sizeof square[0]; i++) ok = ok && *square[i];
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) ok = ok && *vec[i];
    if (!ok) return whirl_fail(GSL_ENOMEM, "out of memory for %zu collocation points", np);
    double size;
    const size_t ny = N_DYNAMIC * np;
    lapack_int info = LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)ny, w->a,
                                         (lapack_int)ny, w->alphar, w->alphai, NULL, 1, w->vr,
                                         (lapack_int)ny, &size, -1);
    if (info != 0) return whirl_fail(GSL_EFAILED, "dgeev workspace query failed (%d)", (int)info);
    w->lwork = (lapack_int)size;
    w->work = malloc((size_t)w->lwork * sizeof(double));
    if (w->work == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the eigen-solver");
    w->cap = np;
    return GSL_SUCCESS;
}

/* The points of the elements brk[0..ne] (np = ne (p + 1)) and their quadrature weights. */
static void set_points(whirl_cstab *w)
{
    const size_t P = (size_t)w->p.degree + 1;
    for (size_t e = 0; e < w->ne; e++) {
        const double a = w->brk[e], h = w->brk[e + 1] - a;
        for (size_t j = 0; j < P; j++) {
            /* t_j = (1 - cos(j pi / p)) / 2 = sin^2(j pi / (2 p)) */
            const double s = sin(M_PI * (double)j / (2.0 * (double)(P - 1)));
            w->sig[e * P + j] = j == P - 1 ? w->brk[e + 1] : a + h * s * s;
            w->wq[e * P + j] = h * w->cw[j];
        }
    }
}

/* Entry (j, k) of the differentiation matrix of element e (local indices). */
static double dmat(const whirl_cstab *w, size_t e, size_t j, size_t k)
{
    const size_t P = (size_t)w->p.degree + 1;
    return w->dref[j * P + k] / (w->brk[e + 1] - w->brk[e]);
}

/* ---- the steady shape by collocation ---- */

/* The shooting's shape at CS_SAMPLES arclengths from the free end: sigma, r and q (the load
 * ratio H / W from the trapezoidal integral of omega^2 r). */
static int sample_shape(whirl_cstab *w, double omega, double tip_r)
{
    const size_t ns = CS_SAMPLES;
    double *s = w->ls, *r = w->lr, *z = w->lq, *ten = malloc(ns * sizeof(double));
    if (ten == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = whirl_continuum_sample(omega, w->p.tip_mass, tip_r, ns, s, r, z, ten);
    free(ten);
    if (status) return status;
    /* reversed: from the free end */
    for (size_t i = 0; i < ns / 2; i++) {
        double t = r[i];
        r[i] = r[ns - 1 - i], r[ns - 1 - i] = t;
    }
    const double m = w->p.tip_mass, w2 = omega * omega;
    double h = m * w2 * r[0];
    for (size_t i = 0; i < ns; i++) {
        s[i] = (double)i / (double)(ns - 1);
        if (i > 0) h += w2 * (r[i] + r[i - 1]) / 2 * (s[i] - s[i - 1]);
        w->lq[i] = s[i] + m > 0 ? h / (s[i] + m) : w2 * r[0];
    }
    return GSL_SUCCESS;
}

/* The samples interpolated linearly at the points. */
static void seed_shape(whirl_cstab *w)
{
    const size_t ns = CS_SAMPLES;
    for (size_t g = 0; g < w->np; g++) {
        const double x = w->sig[g] * (double)(ns - 1);
        size_t i = (size_t)x;
        if (i >= ns - 1) i = ns - 2;
        const double f = x - (double)i;
        w->r[g] = w->lr[i] + f * (w->lr[i + 1] - w->lr[i]);
        w->q[g] = w->lq[i] + f * (w->lq[i + 1] - w->lq[i]);
    }
}

/* Newton's method on the collocation equations of the shape (header comment). */
static int newton_shape(whirl_cstab *w, double omega)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, nn = 2 * np;
    const double m = w->p.tip_mass, w2 = omega * omega;
    double *jac = w->jac, *f = w->res;
    for (int iter = 0; iter < CS_NEWTON_MAX; iter++) {
        memset(jac, 0, nn * nn * sizeof(double));
#define J(i, k) jac[(i) + (k) * nn]
        for (size_t e = 0; e < w->ne; e++)
            for (size_t j = 0; j < P; j++) {
                const size_t g = e * P + j, ir = g, iq = np + g;
                const double s = sqrt(1 + w->q[g] * w->q[g]);
                /* r row: r' + q / S, or r continuous / zero at the right end */
                if (j == P - 1) {
                    f[ir] = w->r[g] - (e + 1 < w->ne ? w->r[g + 1] : 0);
                    J(ir, g) = 1;
                    if (e + 1 < w->ne) J(ir, g + 1) = -1;
                } else {
                    double d = 0;
                    for (size_t k = 0; k < P; k++) {
                        const double dk = dmat(w, e, j, k);
                        d += dk * w->r[e * P + k];
                        J(ir, e * P + k) += dk;
                    }
                    f[ir] = d + w->q[g] / s;
                    J(ir, np + g) += 1 / (s * s * s);
                }
                /* q row: (sigma + m) q' + q - omega^2 r, or q continuous / the tip condition
                 * at the left end */
                if (j == 0) {
                    if (e == 0) {
                        f[iq] = w->q[g] - w2 * w->r[g];
                        J(iq, np + g) = 1;
                        J(iq, g) = -w2;
                    } else {
                        f[iq] = w->q[g] - w->q[g - 1];
                        J(iq, np + g) = 1;
                        J(iq, np + g - 1) = -1;
                    }
                } else {
                    const double wt = w->sig[g] + m;
                    double d = 0;
                    for (size_t k = 0; k < P; k++) {
                        const double dk = dmat(w, e, j, k);
                        d += dk * w->q[e * P + k];
                        J(iq, np + e * P + k) += wt * dk;
                    }
                    f[iq] = wt * d + w->q[g] - w2 * w->r[g];
                    J(iq, np + g) += 1;
                    J(iq, g) -= w2;
                }
            }
#undef J
        int info; /* on a worker thread when large: a stop request ends the call at once */
        const int status = whirl_worker_dgesv(nn, 1, jac, nn, w->ipiv, f, nn, &info);
        if (status) return status;
        if (info != 0)
            return whirl_fail(GSL_EFAILED, "the collocation of the shape at omega = " WHIRL_Q_RATE
                              "%g is singular (dgesv info "
                              "%d)", omega, (int)info);
        double step = 0, scale = 1;
        for (size_t g = 0; g < np; g++) {
            w->r[g] -= f[g];
            w->q[g] -= f[np + g];
            if (!isfinite(w->r[g]) || !isfinite(w->q[g]))
                return whirl_fail(GSL_ERANGE, "the collocation of the shape at omega = "
                                  WHIRL_Q_RATE "%g diverged", omega);
            step = fmax(step, fmax(fabs(f[g]), fabs(f[np + g])));
            scale = fmax(scale, fabs(w->q[g]));
        }
        if (step <= 1e-13 * scale) return GSL_SUCCESS;
    }
    return whirl_fail(GSL_EMAXITER, "the collocation of the shape at omega = " WHIRL_Q_RATE "%g "
                      "did not converge in %d Newton steps", omega, CS_NEWTON_MAX);
}

/* The largest of the last two Chebyshev coefficients of f on element e over scale. */
static double tail(const whirl_cstab *w, const double *f, size_t e, double scale)
{
    const size_t pp = (size_t)w->p.degree;
    double big = 0;
    for (size_t k = pp - 1; k <= pp; k++) {
        double c = 0;
        for (size_t j = 0; j <= pp; j++) {
            const double v = f[e * (pp + 1) + j] * cos(M_PI * (double)(k * j) / (double)pp);
            c += j == 0 || j == pp ? v / 2 : v;
        }
        c *= (k == pp ? 1.0 : 2.0) / (double)pp;
        big = fmax(big, fabs(c));
    }
    return scale > 0 ? big / scale : 0;
}

/* The shape on elements refined until the tails meet shape_tol. On too coarse elements Newton's
 * method may fail or find another solution of the collocation equations (the hanging chain,
 * or a shape of no mode): then (a tip radius 25% off the shooting's), or where the resolved
 * tip radius differs from the shooting's by more than max(1e-7, 1e3 shape_tol) relative, every
 * element is halved. */
static int solve_shape(whirl_cstab *w, double omega, double tip_r)
{
    int status = sample_shape(w, omega, tip_r);
    if (status) return status;
    w->ne = CS_ELEMENTS_START;
    for (size_t e = 0; e <= w->ne; e++) w->brk[e] = (double)e / (double)w->ne;
    const size_t P = (size_t)w->p.degree + 1;
    const char *why = "";
    for (;;) {
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "the shape at omega = " WHIRL_Q_RATE "%g: "
                              "stopped by request", omega);
        w->np = w->ne * P;
        if ((status = reserve(w, w->np))) return status;
        set_points(w);
        seed_shape(w);
        status = newton_shape(w, omega);
        if (status == WHIRL_EINTERRUPTED || status == GSL_ENOMEM) return status;
        /* another solution: 25% off the shooting's tip radius; at the end max(1e-7, 1e3 tol) */
        const double off = fabs(w->r[0] - tip_r) / tip_r;
        int wrong = status || !(off <= 0.25);
        double sr = 0, sq = 0;
        for (size_t g = 0; g < w->np && !wrong; g++)
            sr = fmax(sr, fabs(w->r[g])), sq = fmax(sq, fabs(w->q[g]));
        double brk[2 * CS_ELEMENTS_MAX + 1];
        size_t nb = 0;
        for (int pass = 0; pass < 2; pass++) {
            nb = 0;
            brk[nb++] = 0;
            for (size_t e = 0; e < w->ne; e++) {
                if (wrong || fmax(tail(w, w->r, e, sr), tail(w, w->q, e, sq)) > w->p.shape_tol)
                    brk[nb++] = (w->brk[e] + w->brk[e + 1]) / 2;
                brk[nb++] = w->brk[e + 1];
            }
            if (nb > w->ne + 1 || wrong) break;
            if (off <= fmax(1e-7, 1e3 * w->p.shape_tol)) return GSL_SUCCESS;
            wrong = 1; /* resolved, yet not the shooting's shape: every element halved */
        }
        why = status ? "Newton's method failed" : wrong ? "not the shooting's shape" : "";
        if (nb - 1 > CS_ELEMENTS_MAX || (nb - 1) * P > CS_POINTS_MAX)
            return whirl_fail(GSL_EMAXITER, "the shape of omega = " WHIRL_Q_RATE "%g needs more "
                              "than %d collocation points (elements of degree %d, shape tolerance "
                              "%g%s%s): lower the rate or the degree", omega, CS_POINTS_MAX,
                              w->p.degree, w->p.shape_tol, *why ? "; " : "", why);
        w->ne = nb - 1;
        memcpy(w->brk, brk, nb * sizeof(double));
    }
}

/* ---- the pencil ---- */

/* The interior equation of field eq at point g (element e, local j) into the rows ra, rb
 * (zeroed first). */
static void equation_row(const whirl_cstab *w, int eq, size_t e, size_t j, double *ra, double *rb)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, n = N_FIELDS * np, g = e * P + j;
    const double om = w->omega, w2 = om * om;
    memset(ra, 0, n * sizeof(double));
    memset(rb, 0, n * sizeof(double));
    if (eq == F_TAU) { /* constraint r' u' + z' w' = 0 */
        for (size_t k = 0; k < P; k++) {
            const double d = dmat(w, e, j, k);
            ra[F_U * np + e * P + k] = w->rp[g] * d;
            ra[F_W * np + e * P + k] = w->zp[g] * d;
        }
        return;
    }
    /* (T0 f')' = sum_l D_jl T0_l sum_k D_lk f_k on the element */
    const int f = eq;
    for (size_t l = 0; l < P; l++) {
        const double djl = dmat(w, e, j, l) * w->t0[e * P + l];
        for (size_t k = 0; k < P; k++) ra[f * np + e * P + k] += djl * dmat(w, e, l, k);
    }
    rb[f * np + g] = 1;
    if (eq == F_U || eq == F_W) { /* + (tau r')' or (tau z')' */
        const double *c = eq == F_U ? w->rp : w->zp;
        for (size_t k = 0; k < P; k++) ra[F_TAU * np + e * P + k] = dmat(w, e, j, k) * c[e * P + k];
    }
    if (eq == F_U) {
        ra[F_U * np + g] += w2;
        ra[F_V * np + g] += 2 * om;
    }
    if (eq == F_V) {
        ra[F_V * np + g] += w2;
        rb[F_U * np + g] = 2 * om;
    }
}

static void store_row(whirl_cstab *w, size_t i, const double *ra, const double *rb)
{
    const size_t n = N_FIELDS * w->np;
    for (size_t k = 0; k < n; k++) {
        w->a0[i + k * n] = ra[k];
        w->b0[i + k * n] = rb[k];
    }
}

/* The tangential (sign = +1) or normal (-1) combination of the u and w equations at (e, j). */
static void combined_row(whirl_cstab *w, int tangential, size_t e, size_t j, double *ra,
                         double *rb, double *ta, double *tb)
{
    const size_t P = (size_t)w->p.degree + 1, n = N_FIELDS * w->np, g = e * P + j;
    const double cu = tangential ? w->rp[g] : -w->zp[g], cw = tangential ? w->zp[g] : w->rp[g];
    equation_row(w, F_U, e, j, ra, rb);
    equation_row(w, F_W, e, j, ta, tb);
    for (size_t k = 0; k < n; k++) {
        ra[k] = cu * ra[k] + cw * ta[k];
        rb[k] = cu * rb[k] + cw * tb[k];
    }
}

static void assemble(whirl_cstab *w)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, n = N_FIELDS * np;
    const double m = w->p.tip_mass, om = w->omega;
    double *ra = w->row_a, *rb = w->row_b, *ta = w->alphar, *tb = w->alphai; /* scratch rows */
    for (size_t e = 0; e < w->ne; e++)
        for (size_t j = 0; j < P; j++) {
            const size_t g = e * P + j;
            for (int f = 0; f < N_FIELDS; f++) {
                const size_t i = f * np + g;
                if (j == P - 1 && f != F_U) { /* continuity with the next element, or the pivot */
                    memset(ra, 0, n * sizeof(double));
                    memset(rb, 0, n * sizeof(double));
                    const int next = e + 1 < w->ne;
                    if (f == F_V) {
                        ra[F_V * np + g] = 1;
                        if (next) ra[F_V * np + g + 1] = -1;
                    } else { /* F_W: n0 . xi, F_TAU: t0 . xi */
                        const double cu = f == F_W ? -w->zp[g] : w->rp[g];
                        const double cw = f == F_W ? w->rp[g] : w->zp[g];
                        ra[F_U * np + g] = cu, ra[F_W * np + g] = cw;
                        if (next) ra[F_U * np + g + 1] = -cu, ra[F_W * np + g + 1] = -cw;
                    }
                } else if (j == P - 1) { /* F_U at a right end: the tangential equation */
                    combined_row(w, 1, e, j, ra, rb, ta, tb);
                } else if (j == 0 && e > 0 && f != F_TAU) {
                    /* continuity of n0 . xi', tau, vh' with the previous element */
                    memset(ra, 0, n * sizeof(double));
                    memset(rb, 0, n * sizeof(double));
                    if (f == F_W) {
                        ra[F_TAU * np + g - 1] = 1;
                        ra[F_TAU * np + g] = -1;
                    } else {
                        for (size_t k = 0; k < P; k++) {
                            const double dl = dmat(w, e - 1, P - 1, k), dr = dmat(w, e, 0, k);
                            if (f == F_V) {
                                ra[F_V * np + (e - 1) * P + k] += dl;
                                ra[F_V * np + e * P + k] -= dr;
                            } else {
                                ra[F_U * np + (e - 1) * P + k] += -w->zp[g] * dl;
                                ra[F_W * np + (e - 1) * P + k] += w->rp[g] * dl;
                                ra[F_U * np + e * P + k] -= -w->zp[g] * dr;
                                ra[F_W * np + e * P + k] -= w->rp[g] * dr;
                            }
                        }
                    }
                } else if (j == 0 && e == 0 && f != F_TAU && m == 0) { /* the free end */
                    if (f == F_U) {
                        combined_row(w, 0, e, j, ra, rb, ta, tb);
                    } else if (f == F_W) {
                        memset(ra, 0, n * sizeof(double));
                        memset(rb, 0, n * sizeof(double));
                        ra[F_TAU * np + g] = 1;
                    } else {
                        equation_row(w, f, e, j, ra, rb);
                    }
                } else if (j == 0 && e == 0 && f != F_TAU) { /* the tip mass */
                    memset(ra, 0, n * sizeof(double));
                    memset(rb, 0, n * sizeof(double));
                    for (size_t k = 0; k < P; k++) ra[f * np + k] = w->t0[g] * dmat(w, 0, 0, k);
                    rb[f * np + g] = m;
                    if (f == F_U) {
                        ra[F_U * np + g] += m * om * om;
                        ra[F_V * np + g] += 2 * om * m;
                        ra[F_TAU * np + g] += w->rp[g];
                    } else if (f == F_W) {
                        ra[F_TAU * np + g] += w->zp[g];
                    } else {
                        ra[F_V * np + g] += m * om * om;
                        rb[F_U * np + g] = 2 * om * m;
                    }
                } else {
                    equation_row(w, f, e, j, ra, rb);
                }
                store_row(w, i, ra, rb);
            }
        }
}

int whirl_cstab_linearise(whirl_cstab *w, double omega, int mode, double tip_r_guess,
                          double *tip_r)
{
    if (!(isfinite(omega) && omega >= 0 && omega <= WHIRL_CONTINUUM_OMEGA_MAX) ||
        (mode > 0 && omega == 0))
        return whirl_fail(GSL_EINVAL, "the rate must be in %s..%g, got omega = " WHIRL_Q_RATE "%g",
                          mode > 0 ? "(0" : "[0", WHIRL_CONTINUUM_OMEGA_MAX, omega);
    if (mode < 0 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "the mode must be in 0..%d (0: the hanging chain), got %d",
                          WHIRL_MODE_MAX, mode);
    w->np = 0;
    w->omega = omega;
    w->mode = mode;
    int status;
    if (mode == 0) {
        w->ne = CS_ELEMENTS_START;
        for (size_t e = 0; e <= w->ne; e++) w->brk[e] = (double)e / (double)w->ne;
        const size_t np = w->ne * ((size_t)w->p.degree + 1);
        if ((status = reserve(w, np))) return status;
        w->np = np;
        set_points(w);
        for (size_t g = 0; g < np; g++) w->r[g] = w->q[g] = 0;
    } else {
        whirl_shape_info info;
        status = whirl_continuum_solve(omega, mode, w->p.tip_mass, tip_r_guess, &info);
        if (!status) status = solve_shape(w, omega, info.tip_r);
        if (status) {
            w->np = 0;
            return status;
        }
    }
    for (size_t g = 0; g < w->np; g++) {
        const double s = sqrt(1 + w->q[g] * w->q[g]);
        w->t0[g] = (w->sig[g] + w->p.tip_mass) * s;
        w->rp[g] = -w->q[g] / s;
        w->zp[g] = 1 / s;
    }
    assemble(w);
    if (tip_r) *tip_r = w->r[0];
    return GSL_SUCCESS;
}

void whirl_cstab_grid(const whirl_cstab *w, size_t *elements, size_t *points)
{
    *elements = w->np ? w->ne : 0;
    *points = w->np;
}

/* E of the header comment for the eigenvector (u, w, vh) (3 np: the fields with a mass) with real
 * part xr and imaginary part xi (NULL: real) at mu = -w2. */
static double mode_energy(const whirl_cstab *w, const double *xr, const double *xi, double w2)
{
    const size_t np = w->np;
    double e = 0;
    for (int part = 0; part < 2; part++) {
        const double *x = part ? xi : xr;
        if (x == NULL) continue;
        for (size_t g = 0; g < np; g++) {
            const double u = x[g], ww = x[np + g], vh = x[2 * np + g];
            const double d = w2 * (u * u + ww * ww) + vh * vh + 2 * w->omega * u * vh;
            e += w->wq[g] * d + (g == 0 ? w->p.tip_mass * d : 0);
        }
    }
    return e;
}

/* The energy of kept mode k of the last eigen-solve (its eigenvector in w->vr). */
static double cstab_energy(void *data, size_t k)
{
    whirl_cstab *w = data;
    const size_t ny = N_DYNAMIC * w->np, i = (size_t)w->ipiv[k];
    const double *xr = w->vr + i * ny, *xi = NULL;
    if (w->alphai[i] > 0) xi = w->vr + (i + 1) * ny;
    if (w->alphai[i] < 0) xr = w->vr + (i - 1) * ny, xi = w->vr + i * ny;
    return mode_energy(w, xr, xi, -w->mu_re[k]);
}

/* The LU factors of R (A - s B) into w->a (pivots w->ipiv), R the row equilibration (w->row_a):
 * s = shift, or if that is an eigenvalue shift 1.7^k (k < tries). */
static int shifted_lu(whirl_cstab *w, double shift, int tries)
{
    const size_t n = N_FIELDS * w->np;
    int info = 1;
    for (int k = 0; k < tries && info != 0; k++) { /* s an eigenvalue: another s */
        w->shift = shift * pow(1.7, k);
        for (size_t i = 0; i < n * n; i++) w->a[i] = w->a0[i] - w->shift * w->b0[i];
        /* rows equilibrated (the rows of the second derivatives on short elements are ~1e8
         * times those of the conditions): the same solutions, less round-off */
        for (size_t i = 0; i < n; i++) w->row_a[i] = 0;
        for (size_t j = 0; j < n; j++)
            for (size_t i = 0; i < n; i++) w->row_a[i] = fmax(w->row_a[i], fabs(w->a[i + j * n]));
        for (size_t i = 0; i < n; i++) w->row_a[i] = w->row_a[i] > 0 ? 1 / w->row_a[i] : 1;
        for (size_t j = 0; j < n; j++)
            for (size_t i = 0; i < n; i++) w->a[i + j * n] *= w->row_a[i];
        const int status = whirl_worker_dgetrf(n, w->a, n, w->ipiv, &info); /* see dgesv */
        if (status) return status;
    }
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the shifted pencil is singular (dgetrf info %d)",
                          (int)info);
    return GSL_SUCCESS;
}

/* y = the (u, w, vh) rows of (A - s B)^-1 B x, x = (u, w, vh) (3 np): one step of the Arnoldi
 * iteration on the block of shifted_eigen, with the factors of shifted_lu. */
static int cstab_apply(void *data, const double *x, double *y)
{
    whirl_cstab *w = data;
    const size_t np = w->np, n = N_FIELDS * np;
    const size_t col[N_DYNAMIC] = {F_U, F_W, F_V};
    double *b = w->row_b;
    for (size_t i = 0; i < n; i++) b[i] = 0;
    for (size_t k = 0; k < N_DYNAMIC; k++)
        for (size_t j = 0; j < np; j++) {
            const double xj = x[k * np + j];
            if (xj == 0) continue;
            const double *c = w->b0 + (col[k] * np + j) * n;
            for (size_t i = 0; i < n; i++) b[i] += c[i] * xj;
        }
    for (size_t i = 0; i < n; i++) b[i] *= w->row_a[i];
    lapack_int info = LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', (lapack_int)n, 1, w->a,
                                          (lapack_int)n, w->ipiv, b, (lapack_int)n);
    if (info != 0) return GSL_CONTINUE;
    for (size_t k = 0; k < N_DYNAMIC; k++) memcpy(y + k * np, b + col[k] * np, np * sizeof(double));
    return GSL_SUCCESS;
}

/* The finite eigenvalues of the pencil A x = mu B x through theta = 1 / (mu - s), the eigenvalues
 * of (A - s B)^-1 B: B's columns of tau are zero, so only the block of the rows and columns of
 * (u, w, vh) is needed (size 3 np instead of 4 np, and a standard eigenproblem: dgeev), whose
 * eigenvectors are the (u, w, vh) of the modes; infinite mu become theta = 0. Into w->alphar,
 * w->alphai (theta) and w->vr. */
static int shifted_eigen(whirl_cstab *w, int vectors)
{
    const size_t np = w->np, n = N_FIELDS * np, ny = N_DYNAMIC * np;
    const size_t col[N_DYNAMIC] = {F_U, F_W, F_V}; /* field of block k of y */
    int status = shifted_lu(w, CS_SHIFT, 4);
    if (status) return status;
    int info;
    double *x = w->b; /* n x ny: B's columns of (u, w, vh), then solved */
    for (size_t k = 0; k < N_DYNAMIC; k++)
        memcpy(x + k * np * n, w->b0 + col[k] * np * n, np * n * sizeof(double));
    for (size_t j = 0; j < ny; j++)
        for (size_t i = 0; i < n; i++) x[i + j * n] *= w->row_a[i];
    status = whirl_worker_dgetrs(n, ny, w->a, n, w->ipiv, x, n, &info);
    if (status) return status;
    if (info != 0) return whirl_fail(GSL_EFAILED, "dgetrs info %d", info);
    double *c = w->a; /* ny x ny: the rows of (u, w, vh) */
    for (size_t j = 0; j < ny; j++)
        for (size_t k = 0; k < N_DYNAMIC; k++)
            memcpy(c + j * ny + k * np, x + j * n + col[k] * np, np * sizeof(double));
    status = whirl_worker_dgeev('N', vectors ? 'V' : 'N', ny, c, ny, w->alphar, w->alphai, w->vr,
                                ny, w->work, (int)w->lwork, &info);
    if (status) return status;
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the eigenvalue iteration failed (dgeev info %d)",
                          (int)info);
    return GSL_SUCCESS;
}

int whirl_cstab_spectrum(whirl_cstab *w, int signatures, whirl_spectrum *out)
{
    if (w->np == 0) return whirl_fail(GSL_EINVAL, "no linearisation to solve");
    const size_t ny = N_DYNAMIC * w->np;
    int status = shifted_eigen(w, signatures);
    if (status) return status;
    const double fmax_kept = fmax(w->p.freq_max, 3 * w->omega);
    const double cut = fmax_kept * fmax_kept;
    size_t count = 0, zero = 0;
    double big = 0;
    for (size_t i = 0; i < ny; i++) {
        const double tr = w->alphar[i], ti = w->alphai[i], t2 = tr * tr + ti * ti;
        if (!(t2 > 0)) continue;
        const double re = w->shift + tr / t2, im = -ti / t2;
        if (!isfinite(re) || !isfinite(im) || hypot(re, im) > cut) continue;
        w->ipiv[count] = (lapack_int)i;
        w->mu_re[count] = re;
        w->mu_im[count] = im;
        if (hypot(re, im) < hypot(w->mu_re[zero], w->mu_im[zero])) zero = count;
        count++;
        big = fmax(big, hypot(re, im));
    }
    if (w->mode > 0 && count > 0) { /* the rotation's mu = 0 */
        count--;
        for (size_t k = zero; k < count; k++) {
            w->mu_re[k] = w->mu_re[k + 1];
            w->mu_im[k] = w->mu_im[k + 1];
            w->ipiv[k] = w->ipiv[k + 1];
        }
    }
    const double level = 1e-8 * sqrt(big);
    whirl_windows_classify(out, count, w->mu_re, w->mu_im, level, signatures ? w->sig_out : NULL,
                           cstab_energy, w);
    return GSL_SUCCESS;
}

/* ---- windows ---- */

typedef struct cstab_search {
    whirl_cstab *w;
    const double *scan, *tip; /* the branch's tip radii at the scan's rates, for the seeds */
    size_t nscan;
    whirl_windows_stats *stats;
} cstab_search;

static int cstab_source_spectrum(void *data, double omega, int signatures, whirl_spectrum *out)
{
    cstab_search *c = data;
    size_t j = 0; /* the seed: the tip radius of the nearest scan rate below */
    while (j + 1 < c->nscan && c->scan[j + 1] <= omega) j++;
    int status = whirl_cstab_linearise(c->w, omega, c->w->mode, c->tip[j], NULL);
    c->stats->shapes++;
    if (!status) status = whirl_cstab_spectrum(c->w, signatures, out);
    return status;
}

/* The two mu nearest sigma at omega by shift-and-invert Arnoldi on the block of shifted_eigen. */
static int cstab_source_pair(void *data, double omega, double sigma, double *mu_re, double *mu_im)
{
    cstab_search *c = data;
    size_t j = 0;
    while (j + 1 < c->nscan && c->scan[j + 1] <= omega) j++;
    int status = whirl_cstab_linearise(c->w, omega, c->w->mode, c->tip[j], NULL);
    c->stats->shapes++;
    if (status) return status;
    if (shifted_lu(c->w, sigma, 1)) return GSL_CONTINUE; /* sigma is an eigenvalue */
    if (c->w->kr.q != N_DYNAMIC * c->w->np) {
        whirl_windows_arnoldi_release(&c->w->kr);
        if (whirl_windows_arnoldi_init(&c->w->kr, N_DYNAMIC * c->w->np))
            return whirl_fail(GSL_ENOMEM, "out of memory for the Arnoldi iteration");
    }
    return whirl_windows_arnoldi_pair(&c->w->kr, cstab_apply, c->w, sigma, mu_re, mu_im);
}

int whirl_cstab_windows(whirl_cstab *w, int mode, const whirl_windows_params *p,
                        whirl_window *windows, size_t max, size_t *count,
                        whirl_windows_stats *stats)
{
    *count = 0;
    memset(stats, 0, sizeof *stats);
    if (mode < 1 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "the mode must be in 1..%d, got %d", WHIRL_MODE_MAX, mode);
    double birth, *omega = NULL;
    size_t npts = 0;
    int status = whirl_continuum_critical(mode, w->p.tip_mass, &birth);
    if (!status) status = whirl_windows_range(p, mode, birth, &omega, &npts);
    if (status) return status;
    if (!(p->omega_max <= WHIRL_CONTINUUM_OMEGA_MAX)) {
        free(omega);
        return whirl_fail(GSL_EINVAL, "the continuum's rates end at omega = " WHIRL_Q_RATE "%g, "
                          "got omega = " WHIRL_Q_RATE "%g", WHIRL_CONTINUUM_OMEGA_MAX,
                          p->omega_max);
    }
    whirl_shape_info *info = malloc(npts * sizeof *info);
    int *exists = malloc(npts * sizeof *exists);
    double *tip = malloc(npts * sizeof *tip);
    status = (!info || !exists || !tip) ? whirl_fail(GSL_ENOMEM, "out of memory") : 0;
    if (!status) status = whirl_continuum_branch(mode, w->p.tip_mass, npts, omega, info, exists);
    for (size_t j = 0; j < npts && !status; j++) {
        tip[j] = info[j].tip_r;
        if (!exists[j])
            status = whirl_fail(GSL_EFAILED, "mode %d: no continuum shape at omega = " WHIRL_Q_RATE
                                "%g", mode, omega[j]);
    }
    w->mode = mode;
    cstab_search c = {w, omega, tip, npts, stats};
    windows_source src = {cstab_source_spectrum, p->krylov ? cstab_source_pair : NULL, &c, mode,
                          stats};
    if (!status) status = whirl_windows_search(&src, p, omega, npts, windows, max, count);
    free(omega);
    free(info);
    free(exists);
    free(tip);
    return status;
}
