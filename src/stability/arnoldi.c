/* Shift-and-invert Arnoldi (Saad, Numerical Methods for Large Eigenvalue Problems, 2011, ch. 6-7)
 * on an operator y = (A - sigma)^-1 x given by the caller: the step (Gram-Schmidt twice, full
 * reorthogonalisation), the Ritz values of the Hessenberg matrix and their residuals, and the pair
 * of eigenvalues nearest the shift (windows_internal.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "stability/windows_internal.h"

/* Arnoldi step: v_(step+1) from apply(v_step), orthogonalised (Gram-Schmidt, twice) into column
 * step of the Hessenberg matrix; its norm h_(step+1,step) into *norm. GSL_CONTINUE if apply
 * failed. */
int whirl_windows_arnoldi_step(windows_arnoldi *k, size_t step,
                        int (*apply)(void *data, const double *x, double *y), void *data,
                        double *norm)
{
    const size_t km = k->km, q = k->q;
    double *v = k->basis, *h = k->hess;
    const double *x = v + step * q;
    double *y = v + (step + 1) * q;
    if (apply(data, x, y) != GSL_SUCCESS) return GSL_CONTINUE;
    for (int pass = 0; pass < 2; pass++)
        for (size_t j = 0; j <= step; j++) {
            double dot = 0;
            for (size_t i = 0; i < q; i++) dot += v[j * q + i] * y[i];
            for (size_t i = 0; i < q; i++) y[i] -= dot * v[j * q + i];
            h[j + step * (km + 1)] += dot;
        }
    double nrm = 0;
    for (size_t i = 0; i < q; i++) nrm = hypot(nrm, y[i]);
    h[step + 1 + step * (km + 1)] = nrm;
    if (nrm > 0)
        for (size_t i = 0; i < q; i++) y[i] /= nrm;
    *norm = nrm;
    return GSL_SUCCESS;
}

/* The Ritz values theta (hre, him) and vectors (hvec, m x m) of the leading m x m Hessenberg
 * block: the LAPACK info. */
int whirl_windows_ritz_values(windows_arnoldi *k, size_t m)
{
    for (size_t j = 0; j < m; j++)
        for (size_t i = 0; i < m; i++) k->hcopy[i + j * m] = k->hess[i + j * (k->km + 1)];
    return LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)m, k->hcopy, (lapack_int)m,
                              k->hre, k->him, NULL, 1, k->hvec, (lapack_int)m, k->hwork,
                              (lapack_int)k->hlwork);
}

/* The residual |h_(m+1,m) e_m^T s| / |s| of Ritz value i (its vector s: column i, or (re, im) at
 * (i, i + 1) / (i - 1, i) for a complex one). */
double whirl_windows_ritz_residual(const windows_arnoldi *k, size_t m, size_t i, double norm)
{
    const int cplx = k->him[i] != 0;
    const size_t cr = cplx && k->him[i] < 0 ? i - 1 : i, ci = cplx && k->him[i] > 0 ? i + 1 : i;
    const double last = hypot(k->hvec[m - 1 + cr * m], cplx ? k->hvec[m - 1 + ci * m] : 0);
    double len = 0;
    for (size_t r = 0; r < m; r++)
        len = hypot(len, hypot(k->hvec[r + cr * m], cplx ? k->hvec[r + ci * m] : 0));
    return norm * last / len;
}

int whirl_windows_arnoldi_init(windows_arnoldi *k, size_t q)
{
    return whirl_windows_arnoldi_init_steps(k, q, WINDOWS_KRYLOV_MAX);
}

int whirl_windows_arnoldi_init_steps(windows_arnoldi *k, size_t q, size_t km)
{
    memset(k, 0, sizeof *k);
    k->q = q;
    k->km = km;
    k->basis = malloc(q * (km + 1) * sizeof(double));
    k->hess = malloc((km + 1) * km * sizeof(double));
    k->hcopy = malloc(km * km * sizeof(double));
    k->hre = malloc(km * sizeof(double));
    k->him = malloc(km * sizeof(double));
    k->hvec = malloc(km * km * sizeof(double));
    if (!k->basis || !k->hess || !k->hcopy || !k->hre || !k->him || !k->hvec) return GSL_ENOMEM;
    double size;
    if (LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)km, k->hcopy, (lapack_int)km,
                           k->hre, k->him, NULL, 1, k->hvec, (lapack_int)km, &size, -1) != 0)
        return GSL_EFAILED;
    k->hlwork = (int)size;
    k->hwork = malloc((size_t)k->hlwork * sizeof(double));
    return k->hwork ? GSL_SUCCESS : GSL_ENOMEM;
}

void whirl_windows_arnoldi_release(windows_arnoldi *k)
{
    double *arrays[] = {k->basis, k->hess, k->hcopy, k->hre, k->him, k->hvec, k->hwork};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    memset(k, 0, sizeof *k);
}

int whirl_windows_arnoldi_pair(windows_arnoldi *k,
                               int (*apply)(void *data, const double *x, double *y), void *data,
                               double sigma, double *mu_re, double *mu_im)
{
    const size_t km = k->km, q = k->q;
    double *v = k->basis;
    memset(k->hess, 0, (km + 1) * km * sizeof(double));
    double norm = 0;
    for (size_t i = 0; i < q; i++) {
        v[i] = sin(0.7 * (double)i + 0.3) + 0.5;
        norm = hypot(norm, v[i]);
    }
    for (size_t i = 0; i < q; i++) v[i] /= norm;
    for (size_t step = 0; step < km; step++) {
        if (whirl_windows_arnoldi_step(k, step, apply, data, &norm)) return GSL_CONTINUE;
        const size_t m = step + 1;
        if (m < 4 && norm > 0) continue;
        if (whirl_windows_ritz_values(k, m) != 0) return GSL_CONTINUE;
        /* the two Ritz values of largest modulus and their residuals */
        size_t best[2] = {0, 0};
        double big[2] = {-1, -1};
        for (size_t i = 0; i < m; i++) {
            const double mod = hypot(k->hre[i], k->him[i]);
            if (mod > big[0]) {
                big[1] = big[0], best[1] = best[0];
                big[0] = mod, best[0] = i;
            } else if (mod > big[1]) {
                big[1] = mod, best[1] = i;
            }
        }
        int converged = big[1] > 0;
        for (int t = 0; t < 2 && converged; t++)
            if (!(whirl_windows_ritz_residual(k, m, best[t], norm) <= 1e-13 * big[t])) converged = 0;
        if (converged || norm == 0) {
            if (!converged) return GSL_CONTINUE;
            for (int t = 0; t < 2; t++) {
                const double tr = k->hre[best[t]], ti = k->him[best[t]], t2 = tr * tr + ti * ti;
                mu_re[t] = sigma + tr / t2;
                mu_im[t] = -ti / t2;
            }
            return GSL_SUCCESS;
        }
    }
    return GSL_CONTINUE;
}
