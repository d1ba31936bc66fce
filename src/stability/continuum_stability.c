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
 * nlink_windows.c) this is LINEAR in mu = lambda^2:
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
 * The files: continuum_shape.c (the steady shape by collocation), continuum_pencil.c (the
 * pencil A - s B, its conditions and its band LU), continuum_eigen.c (the eigen-solves and the
 * Krein signatures), continuum_windows.c (the window source and the edges' refinement).
 * References: Kolodner 1955, Comm. Pure Appl. Math. 8:395 (the steady shapes); Caughey 1958,
 * J. Appl. Mech. 25:465 (whirling of a heavy chain); Trefethen 2000 (collocation); Mackay 1986
 * (Krein signature); Moler & Stewart 1973, SIAM J. Numer. Anal. 10:241 (QZ). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/linalg.h"

#include "whirl/continuum_stability.h"
#include "core/error.h"
#include "core/roots.h"
#include "core/worker.h"
#include "stability/continuum_internal.h"
#include "stability/windows_internal.h"

whirl_cstab_params whirl_cstab_defaults(void)
{
    whirl_cstab_params p = {16, 0, 1e-11, 30, 0, 1024};
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
    if (p->solver != 0 && p->solver != 1)
        return whirl_fail(GSL_EINVAL, "the solver must be 0 (Arnoldi) or 1 (dense), got %d",
                          p->solver);
    if (!(p->memory_mb >= 16 && p->memory_mb <= 1048576))
        return whirl_fail(GSL_EINVAL, "the memory bound must be in 16..1048576 MB, got %g",
                          p->memory_mb);
    return GSL_SUCCESS;
}

static void release_dense(whirl_cstab *w)
{
    double *arrays[] = {w->dc, w->dvr, w->dx, w->dre, w->dim, w->dwork};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    w->dc = w->dvr = w->dx = w->dre = w->dim = w->dwork = NULL;
    w->dcap = 0;
}

void whirl_cstab_free(whirl_cstab *w)
{
    if (w == NULL) return;
    double *arrays[] = {w->brk,  w->dref, w->cw,    w->sig,   w->r,     w->q,    w->wq,
                        w->t0,   w->rp,   w->zp,    w->jac,   w->res,   w->ab,   w->bb,
                        w->lu,   w->row_a, w->ra,   w->rb,    w->ta,    w->tb,   w->solve,
                        w->mu_re, w->mu_im, w->ls,  w->lr,    w->lq,    w->ke.basis, w->ke.hess,
                        w->ke.hcopy, w->ke.hre,  w->ke.him,  w->ke.hvec,  w->ke.hwork, w->ritz};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    free(w->ipiv);
    free(w->lnz);
    free(w->unz);
    free(w->kept);
    free(w->sig_out);
    release_dense(w);
    whirl_windows_arnoldi_release(&w->kr);
    free(w);
}

whirl_cstab *whirl_cstab_alloc(const whirl_cstab_params *p)
{
    if (check_params(p)) return NULL;
    whirl_cstab *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->p = *p;
    const size_t pp = (size_t)p->degree, P = pp + 1, km = CS_KRYLOV_MAX;
    w->kl = 4 * P + 3;
    w->ku = 4 * pp + 3;
    w->ldab = 2 * w->kl + w->ku + 1;
    w->nkl = 2 * P + 1;
    w->nldab = 3 * w->nkl + 1;
    w->dref = malloc(P * P * sizeof(double));
    w->cw = malloc(P * sizeof(double));
    w->ls = malloc(CS_SAMPLES * sizeof(double));
    w->lr = malloc(CS_SAMPLES * sizeof(double));
    w->lq = malloc(CS_SAMPLES * sizeof(double));
    w->ke.hess = calloc((km + 1) * km, sizeof(double));
    w->ke.hcopy = malloc(km * km * sizeof(double));
    w->ke.hre = malloc(km * sizeof(double));
    w->ke.him = malloc(km * sizeof(double));
    w->ke.hvec = malloc(km * km * sizeof(double));
    if (!w->dref || !w->cw || !w->ls || !w->lr || !w->lq || !w->ke.hess || !w->ke.hcopy || !w->ke.hre ||
        !w->ke.him || !w->ke.hvec)
        goto fail;
    double size;
    if (whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)km, w->ke.hcopy, (lapack_int)km,
                           w->ke.hre, w->ke.him, NULL, 1, w->ke.hvec, (lapack_int)km, &size, -1) != 0)
        goto fail;
    w->ke.hlwork = (int)size;
    w->ke.km = km;
    w->ke.blocked = 1;
    if ((w->ke.hwork = malloc((size_t)w->ke.hlwork * sizeof(double))) == NULL) goto fail;
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

/* Bytes of the workspace per collocation point (the bound on the points is memory_mb over
 * this): the pencil's band and its LU, the Newton band, the Arnoldi basis, the vectors, the
 * LU's extents. */
static size_t bytes_per_point(const whirl_cstab *w)
{
    const size_t band = N_FIELDS * (w->ldab + (w->kl + w->ku + 1)) + 2 * w->nldab;
    const size_t krylov = N_DYNAMIC * (CS_KRYLOV_MAX + 3);
    const size_t extents = 2 * N_FIELDS * sizeof(size_t) / sizeof(double); /* lnz, unz */
    return (band + krylov + 16 + 14 * N_FIELDS + 12 + extents) * sizeof(double);
}

/* The most points memory_mb holds. */
size_t cstab_points_max(const whirl_cstab *w)
{
    return (size_t)(w->p.memory_mb * 1048576.0 / (double)bytes_per_point(w));
}

/* Room for np points. */
int cstab_reserve(whirl_cstab *w, size_t np)
{
    if (np <= w->cap) return GSL_SUCCESS;
    const size_t n = N_FIELDS * np, ny = N_DYNAMIC * np;
    double **per_point[] = {&w->sig, &w->r, &w->q, &w->wq, &w->t0, &w->rp, &w->zp};
    double **vec[] = {&w->row_a, &w->ra, &w->rb, &w->ta, &w->tb, &w->solve, &w->mu_re, &w->mu_im};
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++) free(*per_point[i]);
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) free(*vec[i]);
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++)
        *per_point[i] = malloc(np * sizeof(double));
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) *vec[i] = calloc(n, sizeof(double));
    free(w->jac), free(w->res), free(w->ipiv), free(w->sig_out), free(w->kept);
    free(w->lnz), free(w->unz);
    free(w->ab), free(w->bb), free(w->lu), free(w->ke.basis), free(w->ritz);
    w->jac = malloc(w->nldab * 2 * np * sizeof(double));
    w->res = malloc(2 * np * sizeof(double));
    w->ipiv = malloc(n * sizeof(lapack_int));
    w->lnz = malloc(n * sizeof(size_t));
    w->unz = malloc(n * sizeof(size_t));
    w->sig_out = malloc(n * sizeof(int));
    w->kept = malloc(n * sizeof(size_t));
    w->ab = malloc(w->ldab * n * sizeof(double));
    w->bb = malloc(N_FIELDS * N_FIELDS * np * sizeof(double));
    w->lu = malloc(w->ldab * n * sizeof(double));
    w->ke.basis = malloc(ny * (CS_KRYLOV_MAX + 1) * sizeof(double));
    w->ritz = malloc(2 * ny * sizeof(double));
    w->cap = 0;
    int ok = w->jac && w->res && w->ipiv && w->lnz && w->unz && w->sig_out && w->kept && w->ab &&
             w->bb && w->lu &&
             w->ke.basis && w->ritz;
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++) ok = ok && *per_point[i];
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) ok = ok && *vec[i];
    if (!ok) return whirl_fail(GSL_ENOMEM, "out of memory for %zu collocation points", np);
    w->cap = np;
    return GSL_SUCCESS;
}

/* Room for the dense fall-back of np points (CS_DENSE_POINTS at most). */
int cstab_reserve_dense(whirl_cstab *w, size_t np)
{
    if (np <= w->dcap) return GSL_SUCCESS;
    if (np > CS_DENSE_POINTS)
        return whirl_fail(GSL_EMAXITER, "the dense eigen-solve of %zu collocation points is "
                                        "beyond its bound of %d points", np, CS_DENSE_POINTS);
    release_dense(w);
    const size_t n = N_FIELDS * np, ny = N_DYNAMIC * np;
    w->dc = malloc(ny * ny * sizeof(double));
    w->dvr = malloc(ny * ny * sizeof(double));
    w->dx = malloc(n * ny * sizeof(double));
    w->dre = malloc(ny * sizeof(double));
    w->dim = malloc(ny * sizeof(double));
    if (!w->dc || !w->dvr || !w->dx || !w->dre || !w->dim)
        return whirl_fail(GSL_ENOMEM, "out of memory for the dense eigen-solve of %zu points", np);
    double size;
    lapack_int info = whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)ny, w->dc,
                                         (lapack_int)ny, w->dre, w->dim, NULL, 1, w->dvr,
                                         (lapack_int)ny, &size, -1);
    if (info != 0) return whirl_fail(GSL_EFAILED, "dgeev workspace query failed (%d)", (int)info);
    w->dlwork = (lapack_int)size;
    w->dwork = malloc((size_t)size * sizeof(double));
    if (w->dwork == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the eigen-solver");
    w->dcap = np;
    return GSL_SUCCESS;
}

/* The points of the elements brk[0..ne] (np = ne (p + 1)) and their quadrature weights. */
void cstab_set_points(whirl_cstab *w)
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

void whirl_cstab_grid(const whirl_cstab *w, size_t *elements, size_t *points)
{
    *elements = w->np ? w->ne : 0;
    *points = w->np;
}
