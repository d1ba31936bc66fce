/* Shift-and-invert Arnoldi (Saad, Numerical Methods for Large Eigenvalue Problems, 2011, ch. 6-7)
 * on an operator y = (A - sigma)^-1 x given by the caller: the step (Gram-Schmidt twice, full
 * reorthogonalisation), the Ritz values of the Hessenberg matrix and their residuals, and its two
 * drivers (windows_internal.h): the pair of eigenvalues nearest the shift (the window search
 * near an edge) and every eigenvalue above a floor in modulus (the continuum's spectrum); the
 * N-link chain's banded path drives the same step and Ritz values itself (nlink_banded.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/linalg.h"

#include "core/error.h"
#include "stability/windows_internal.h"

/* The dot product of a and b (n), in four partial sums: independent additions, which the
 * processor overlaps (a single sum waits for each addition in turn). */
static double dot4(const double *a, const double *b, size_t n)
{
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        s0 += a[i] * b[i];
        s1 += a[i + 1] * b[i + 1];
        s2 += a[i + 2] * b[i + 2];
        s3 += a[i + 3] * b[i + 3];
    }
    for (; i < n; i++) s0 += a[i] * b[i];
    return (s0 + s1) + (s2 + s3);
}

/* Arnoldi step: v_(step+1) from apply(v_step), orthogonalised (Gram-Schmidt, twice) into column
 * step of the Hessenberg matrix; its norm h_(step+1,step) into *norm. GSL_CONTINUE if apply
 * failed. The inner products and the norm by k->blocked (windows_internal.h). */
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
            const double *vj = v + j * q;
            double dot = 0;
            if (k->blocked)
                dot = dot4(vj, y, q);
            else
                for (size_t i = 0; i < q; i++) dot += vj[i] * y[i];
            for (size_t i = 0; i < q; i++) y[i] -= dot * vj[i];
            h[j + step * (km + 1)] += dot;
        }
    double nrm = 0;
    if (k->blocked) { /* the vectors are O(1): no scaling needed */
        for (size_t i = 0; i < q; i++) nrm += y[i] * y[i];
        nrm = sqrt(nrm);
    } else {
        for (size_t i = 0; i < q; i++) nrm = hypot(nrm, y[i]);
    }
    h[step + 1 + step * (km + 1)] = nrm;
    if (nrm > (k->blocked ? ARNOLDI_BREAKDOWN : 0))
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
    return whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)m, k->hcopy, (lapack_int)m,
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
    if (whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)km, k->hcopy, (lapack_int)km,
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

/* The Ritz values of the m-step factorisation (whirl_windows_ritz_values); *done: every one with
 * |theta| >= floor has a residual |h_(m+1,m) e_m^T y| below 1e-12 |theta| |y|; *wanted: how many
 * have |theta| >= floor. */
static int ritz_above(windows_arnoldi *k, size_t m, double floor, int *done, size_t *wanted)
{
    const size_t km = k->km;
    const int info = whirl_windows_ritz_values(k, m);
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the Ritz values' eigen-solve failed (dgeev info %d)",
                          info);
    const double beta = m < km ? k->hess[m + (m - 1) * (km + 1)] : 0;
    *done = 1;
    *wanted = 0;
    for (size_t i = 0; i < m; i++) {
        const double mod = hypot(k->hre[i], k->him[i]);
        if (!(mod >= floor)) continue;
        ++*wanted;
        size_t cr = i, ci = i;
        const int cplx = k->him[i] != 0;
        if (cplx && k->him[i] > 0) ci = i + 1;
        if (cplx && k->him[i] < 0) cr = i - 1;
        const double last = hypot(k->hvec[m - 1 + cr * m], cplx ? k->hvec[m - 1 + ci * m] : 0);
        double len = 0;
        for (size_t r = 0; r < m; r++)
            len = hypot(len, hypot(k->hvec[r + cr * m], cplx ? k->hvec[r + ci * m] : 0));
        if (!(fabs(beta) * last <= 1e-12 * mod * len)) *done = 0;
    }
    return GSL_SUCCESS;
}

int whirl_windows_arnoldi_above(windows_arnoldi *k,
                                int (*apply)(void *data, const double *x, double *y), void *data,
                                double floor, size_t *steps)
{
    const size_t q = k->q, km = k->km < q ? k->km : q;
    double *v = k->basis;
    memset(k->hess, 0, (k->km + 1) * k->km * sizeof(double));
    double norm = 0;
    for (size_t i = 0; i < q; i++) {
        v[i] = sin(0.7 * (double)i + 0.3) + 0.5;
        norm += v[i] * v[i];
    }
    norm = sqrt(norm);
    for (size_t i = 0; i < q; i++) v[i] /= norm;
    size_t next = 24; /* the next look at the Ritz values */
    *steps = 0;
    for (size_t step = 0; step < km; step++) {
        if (whirl_windows_arnoldi_step(k, step, apply, data, &norm))
            return whirl_fail(GSL_EFAILED, "the solve of the Arnoldi iteration failed");
        const int breakdown = !(norm > ARNOLDI_BREAKDOWN);
        const size_t m = step + 1;
        if (m < next && !breakdown && m < km) continue;
        next = m + (m / 8 > 4 ? m / 8 : 4);
        int done = 0;
        size_t wanted = 0;
        int status = ritz_above(k, m, floor, &done, &wanted);
        if (status) return status;
        if (next < wanted + 16) next = wanted + 16; /* no stop before (wanted grows with m) */
        if (breakdown || m == q || (done && m >= wanted + 16)) {
            *steps = m;
            return GSL_SUCCESS;
        }
        if (whirl_stop_requested()) return WHIRL_EINTERRUPTED;
    }
    return GSL_CONTINUE;
}
