/* The eigenvalues mu of the continuous chain's pencil and their Krein signatures
 * (continuum_stability.c's header comment: the equations and their linearisation)
 * Eigenvalues, in real arithmetic: the columns of tau in B are zero, so the finite mu are
 * mu = s + 1 / theta with theta the eigenvalues of the block of (A - s B)^-1 B on the rows and
 * columns of (u, w, vh) (a real shift s; the constraint's infinite mu become theta = 0), and its
 * eigenvectors are the modes' (u, w, vh). Only the few mu with |mu| <= cut are kept (some tens
 * of the 3 np): they are the theta of largest modulus, which the Arnoldi iteration on that block
 * (shift-and-invert; one banded solve per step, full re-orthogonalisation; Saad 2011, ch. 6-7)
 * finds first; it runs until every Ritz value with |theta| >= 0.8 / (cut + |s|) has a residual
 * |h_{m+1,m} e_m^T y| below 1e-12 |theta| (Ritz pairs: theta and the eigenvector V y), and at
 * least k + 16 steps for k such values. If that takes more than CS_KRYLOV_MAX steps, or on
 * request (solver = 1, the reference), the block is formed in full by 3 np banded solves and all
 * its eigenvalues computed by LAPACK's dgeev (about 100 times the work at 300 points). Against
 * LAPACK's QZ (dggev) on the whole dense pencil (Moler & Stewart 1973) the dense block gives the
 * same mu to 1e-8 relative. The collocation's round-off limits the mu to about 1e-9 relative (the
 * second-derivative matrices of short elements are large).
 * The rotation about z (v = r, u = w = tau = 0, mu = 0) is removed as the kept mu nearest 0.
 * Krein signature of a neutral mu = -w^2 with eigenvector (u, w, tau, vh) (lambda = i w,
 * v = vh / lambda): the mode's energy w^2 <xi, M xi> + <xi, K xi> = 2 w^2 <xi, xi> - i w <xi, G xi>
 * is, up to a factor 2,
 *     E = int (w^2 (|u|^2 + |w|^2) + |vh|^2 + 2 omega Re(conj(u) vh)) dsigma + (m times the
 *         same at sigma = 0),
 * by Clenshaw-Curtis quadrature on each element (Trefethen 2000, ch. 12). */
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

/* The energy of kept mode k of the last spectrum: its eigenvector from dgeev's (dense) or the
 * Ritz vector V y (Arnoldi). */
static double cstab_energy(void *data, size_t k)
{
    whirl_cstab *w = data;
    const size_t ny = N_DYNAMIC * w->np, i = w->kept[k];
    const double *im = w->hm ? w->ke.him : w->dim, *vec = w->hm ? w->ke.hvec : w->dvr;
    const size_t len = w->hm ? w->hm : ny;
    size_t cr = i, ci = i;
    if (im[i] > 0) ci = i + 1;
    if (im[i] < 0) cr = i - 1;
    if (!w->hm) return mode_energy(w, vec + cr * len, im[i] != 0 ? vec + ci * len : NULL, -w->mu_re[k]);
    double *xr = w->ritz, *xi = w->ritz + ny;
    for (size_t t = 0; t < ny; t++) xr[t] = xi[t] = 0;
    for (size_t j = 0; j < len; j++) {
        const double *v = w->ke.basis + j * ny, yr = vec[j + cr * len];
        const double yi = im[i] != 0 ? vec[j + ci * len] : 0;
        for (size_t t = 0; t < ny; t++) xr[t] += yr * v[t], xi[t] += yi * v[t];
    }
    return mode_energy(w, xr, im[i] != 0 ? xi : NULL, -w->mu_re[k]);
}

/* The eigenvalues theta of the block C of (A - s B)^-1 B on (u, w, vh) in full: C formed by
 * 3 np banded solves, then dgeev (into w->dre, w->dim, eigenvectors w->dvr). */
static int dense_eigen(whirl_cstab *w, int vectors)
{
    const size_t np = w->np, n = N_FIELDS * np, ny = N_DYNAMIC * np;
    int status = cstab_reserve_dense(w, np);
    if (status) return status;
    double *x = w->dx, *e = w->ritz; /* n x ny right-hand sides; a unit vector */
    for (size_t t = 0; t < ny; t++) e[t] = 0;
    for (size_t j = 0; j < ny; j++) {
        e[j] = 1;
        cstab_apply_b(w, e, x + j * n);
        e[j] = 0;
    }
    lapack_int info = whirl_la_dgbtrs_work(LAPACK_COL_MAJOR, 'N', (lapack_int)n, (lapack_int)w->kl,
                                          (lapack_int)w->ku, (lapack_int)ny, w->lu,
                                          (lapack_int)w->ldab, w->ipiv, x, (lapack_int)n);
    if (info != 0) return whirl_fail(GSL_EFAILED, "dgbtrs info %d", (int)info);
    for (size_t j = 0; j < ny; j++)
        for (size_t g = 0; g < np; g++) {
            w->dc[j * ny + g] = x[j * n + N_FIELDS * g + F_U];
            w->dc[j * ny + np + g] = x[j * n + N_FIELDS * g + F_W];
            w->dc[j * ny + 2 * np + g] = x[j * n + N_FIELDS * g + F_V];
        }
    int inf;
    status = whirl_worker_dgeev('N', vectors ? 'V' : 'N', ny, w->dc, ny, w->dre, w->dim, w->dvr,
                                ny, w->dwork, (int)w->dlwork, &inf);
    if (status) return status;
    if (inf != 0)
        return whirl_fail(GSL_EFAILED, "the eigenvalue iteration failed (dgeev info %d)", inf);
    return GSL_SUCCESS;
}

/* The theta of largest modulus of the block C by the Arnoldi iteration (header comment): into
 * w->ke.hre, w->ke.him (w->hm of them); GSL_CONTINUE if not converged in CS_KRYLOV_MAX steps. */
static int arnoldi_eigen(whirl_cstab *w, double cut)
{
    w->ke.q = N_DYNAMIC * w->np; /* the basis holds the points allocated for */
    w->hm = 0;
    const int status = whirl_windows_arnoldi_above(&w->ke, cstab_apply, w,
                                                   0.8 / (cut + fabs(w->shift)), &w->hm);
    if (status == WHIRL_EINTERRUPTED)
        return whirl_fail(WHIRL_EINTERRUPTED, "the eigen-solve at omega = " WHIRL_Q_RATE
                          "%g: stopped by request", w->omega);
    return status;
}

int whirl_cstab_spectrum(whirl_cstab *w, int signatures, whirl_spectrum *out)
{
    if (w->np == 0) return whirl_fail(GSL_EINVAL, "no linearisation to solve");
    const double fmax_kept = fmax(w->p.freq_max, 3 * w->omega);
    const double cut = fmax_kept * fmax_kept;
    int status = cstab_shifted_lu(w, CS_SHIFT, 4);
    if (status) return status;
    status = w->p.solver == 1 ? GSL_CONTINUE : arnoldi_eigen(w, cut);
    if (status == GSL_CONTINUE) { /* the reference, or the fall-back */
        w->hm = 0;
        status = dense_eigen(w, signatures);
    }
    if (status) return status;
    const size_t nt = w->hm ? w->hm : N_DYNAMIC * w->np;
    const double *tre = w->hm ? w->ke.hre : w->dre, *tim = w->hm ? w->ke.him : w->dim;
    size_t count = 0, zero = 0;
    double big = 0;
    for (size_t i = 0; i < nt; i++) {
        const double tr = tre[i], ti = tim[i], t2 = tr * tr + ti * ti;
        if (!(t2 > 0)) continue;
        const double re = w->shift + tr / t2, im = -ti / t2;
        if (!isfinite(re) || !isfinite(im) || hypot(re, im) > cut) continue;
        w->kept[count] = i;
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
            w->kept[k] = w->kept[k + 1];
        }
    }
    const double level = 1e-8 * sqrt(big);
    whirl_windows_classify(out, count, w->mu_re, w->mu_im, level, signatures ? w->sig_out : NULL,
                           cstab_energy, w);
    return GSL_SUCCESS;
}
