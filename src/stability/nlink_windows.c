/* Exact stability windows of the free steady shapes of the N-link chain.
 *
 * The linearisation about a planar shape of the conservative chain (whirl/stability.h, no damping,
 * drag or drive) is M q'' + G q' + K q = 0 with q = (a, b), a the in-plane and b the out-of-plane
 * link angles. For a shape in the x-z plane the matrices split exactly (stability.c):
 *     M = diag(Ma, Mb),  K = diag(Ka, Kb),  G = [[0, Gab], [-Gab^T, 0]]
 * (the Coriolis force couples the two planes, nothing else does). With q = x e^(lambda t) and
 * c = lambda b the equations
 *     (lambda^2 Ma + Ka) a + lambda Gab b = 0,   (lambda^2 Mb + Kb) b - lambda Gab^T a = 0
 * become, the second multiplied by lambda, a LINEAR eigenproblem in mu = lambda^2 of half the size:
 *     mu B x + K' x = 0,  x = (a, c),  B = [[Ma, 0], [-Gab^T, Mb]],  K' = [[Ka, Gab], [0, Kb]],
 * that is A' x = mu x with A' = -B^-1 K' (2N x 2N, real; B is block triangular with definite
 * diagonal blocks, so B^-1 costs two Cholesky solves). Each mu stands for the pair
 * lambda = +-sqrt(mu): the chain is neutrally stable when every mu is real and negative, and the
 * growth rate is max Re sqrt(mu). A real eigenvalue of a real matrix stays real under round-off,
 * so "neutral" is decided exactly except where two mu nearly coincide.
 * The rotation about z (s = (0, s_b), Kb s_b = 0) gives mu = 0 with the left eigenvector
 * l = B^T (0, s_b) = (-Gab s_b, Mb s_b) (l^T A' = 0, from (0, s_b)^T K' = 0); a Householder
 * reflection P with P l parallel to e_1 turns A' into [[0, 0], [*, A'']], and A'' (2N - 1) holds
 * the other eigenvalues (deflation; as for the first-order form in stability.c).
 * Krein signature: for lambda = i w (mu = -w^2 < 0) with eigenvector x = (a, c), q = (a, c / lambda)
 * and the energy of the mode w^2 q^H M q + q^H K q = w^2 q^H M q + (w^2 q^H M q - i w q^H G q)
 * (q^H (K - w^2 M + i w G) q = 0) becomes
 *     E / 2 = w^2 a^H Ma a + c^H Mb c - Re(a^H Gab c).
 * Modes of opposite signs of E are the only ones that can leave the imaginary axis when they meet
 * (Krein collision); modes of one sign pass or avoid each other and stay neutral. At a stable rate
 * the number of modes with E < 0 is half the number of negative eigenvalues of K (Mackay 1986;
 * the count below).
 * Near the edge only the colliding pair matters: D is then taken from the two eigenvalues of A'
 * nearest a real shift sigma, by Arnoldi's method on (A' - sigma)^-1 = -(K' + sigma B)^-1 B (one
 * LU factorisation and a few solves instead of the full Hessenberg QR; Saad 2011, ch. 7), with a
 * fall-back to the full eigenvalues when the Ritz values do not converge.
 * The window search over these spectra: windows_search.c; the banded path of the scan and of the
 * pair near an edge: nlink_banded.c.
 * References: Krein 1950; Mackay, "Stability of equilibria of Hamiltonian systems", in Nonlinear
 * Phenomena and Chaos (1986); Kirillov, Nonconservative Stability Problems of Modern Physics
 * (2013), ch. 2 (gyroscopic systems, Krein signature); Saad, Numerical Methods for Large
 * Eigenvalue Problems (2011); Brent 1973 (root and minimum finding, as in GSL); Haynsworth,
 * "Determination of the inertia of a partitioned Hermitian matrix", Linear Algebra Appl. 1 (1968);
 * Golub and Van Loan, Matrix Computations (2013), 4.3 (banded LU) and 8.4 (Sturm sequences). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/linalg.h"

#include "whirl/stability.h"
#include "core/error.h"
#include "core/input.h"
#include "stability/nlink_windows_internal.h"
#include "stability/windows_internal.h"
#include "core/worker.h"

whirl_windows *whirl_windows_alloc(size_t n)
{
    if (n == 0) {
        whirl_fail(GSL_EINVAL, "the window search needs at least one link");
        return NULL;
    }
    const size_t q = 2 * n;
    whirl_windows *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->n = n;
    w->lin = whirl_stability_alloc(n);
    w->ma = malloc(n * n * sizeof(double));
    w->mb = malloc(n * n * sizeof(double));
    w->ka = malloc(n * n * sizeof(double));
    w->kb = malloc(n * n * sizeof(double));
    w->gab = malloc(n * n * sizeof(double));
    w->a = malloc(q * q * sizeof(double));
    w->hv = malloc(q * sizeof(double));
    w->re = malloc(q * sizeof(double));
    w->im = malloc(q * sizeof(double));
    w->sig = malloc(q * sizeof(int));
    w->vl = malloc(q * q * sizeof(double));
    w->x = malloc(2 * q * sizeof(double));
    w->ipiv = malloc(q * sizeof(lapack_int));
    w->r = malloc((n + 1) * sizeof(double));
    w->z = malloc((n + 1) * sizeof(double));
    w->tension = malloc((n + 1) * sizeof(double));
    double **links[] = {&w->al, &w->be, &w->ga, &w->tl, &w->ms};
    for (size_t i = 0; i < sizeof links / sizeof links[0]; i++) *links[i] = malloc(n * sizeof(double));
    w->tri = malloc(4 * n * sizeof(double));
    w->ab = malloc(BAND_LD * 8 * n * sizeof(double));
    w->bpiv = malloc(8 * n * sizeof(lapack_int));
    w->bx = malloc(8 * n * sizeof(double));
    w->lv = malloc(2 * q * sizeof(double));
    w->kept = malloc(WINDOWS_BAND_KRYLOV * sizeof(int));
    if (!w->al || !w->be || !w->ga || !w->tl || !w->ms || !w->tri || !w->ab || !w->bpiv ||
        !w->bx || !w->lv || !w->kept || whirl_windows_arnoldi_init_steps(&w->kband, q, WINDOWS_BAND_KRYLOV))
        goto fail;
    if (!w->lin || !w->ma || !w->mb || !w->ka || !w->kb || !w->gab || !w->a || !w->hv || !w->re ||
        !w->im || !w->sig || !w->vl || !w->x || !w->ipiv || !w->r || !w->z || !w->tension ||
        whirl_windows_arnoldi_init(&w->kr, q))
        goto fail;
    double size;
    if (whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'V', 'N', (lapack_int)q, w->a, (lapack_int)q, w->re,
                           w->im, w->vl, (lapack_int)q, NULL, 1, &size, -1) != 0)
        goto fail;
    w->lwork = (lapack_int)size;
    w->work = malloc((size_t)w->lwork * sizeof(double));
    if (w->work == NULL) goto fail;
    return w;
fail:
    whirl_windows_free(w);
    char need[32]; /* its 2N x 2N and N x N blocks, and the linearisation's (stability.c) */
    const double bytes = 57.0 * sizeof(double) * (double)n * (double)n;
    whirl_fail(GSL_ENOMEM, "out of memory for the window search of %zu links (it needs about %s)",
               n, whirl_bytes_words(need, sizeof need, bytes));
    return NULL;
}

void whirl_windows_free(whirl_windows *w)
{
    if (w == NULL) return;
    whirl_stability_free(w->lin);
    double *arrays[] = {w->ma, w->mb, w->ka, w->kb, w->gab, w->a, w->hv, w->re, w->im, w->vl,
                        w->x, w->work, w->r, w->z, w->tension, w->al, w->be, w->ga, w->tl,
                        w->ms, w->tri, w->ab, w->bx, w->lv};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    free(w->sig);
    free(w->ipiv);
    free(w->bpiv);
    free(w->kept);
    whirl_windows_arnoldi_release(&w->kr);
    whirl_windows_arnoldi_release(&w->kband);
    free(w);
}

whirl_stability *whirl_windows_linearisation(whirl_windows *w) { return w->lin; }

size_t whirl_windows_fallbacks(const whirl_windows *w) { return w->fallbacks; }

/* The blocks Ma, Mb, Ka, Kb, Gab of the last linearisation in lin, after checking the split
 * (planar, conservative) to round-off. */
int windows_split_blocks(whirl_windows *w, const whirl_stability *lin)
{
    const size_t n = w->n, q = 2 * n;
    const double *mm = whirl_stability_get_matrix(lin, WHIRL_STABILITY_MASS);
    const double *gg = whirl_stability_get_matrix(lin, WHIRL_STABILITY_GYROSCOPIC);
    const double *cc = whirl_stability_get_matrix(lin, WHIRL_STABILITY_DAMPING);
    const double *kk = whirl_stability_get_matrix(lin, WHIRL_STABILITY_STIFFNESS);
    double scale = 0, off = 0, damp = 0;
    for (size_t i = 0; i < q * q; i++) {
        if (i % q == 0 && whirl_stop_requested()) /* O(N) entries a row, O(N^2) in all */
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request while reading the "
                                                  "linearisation");
        scale = dmax(fabs(mm[i]), dmax(fabs(gg[i]), dmax(fabs(kk[i]), scale)));
        damp = dmax(fabs(cc[i]), damp);
    }
    for (size_t i = 0; i < n; i++) {
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request while reading the "
                                                  "linearisation");
        for (size_t j = 0; j < n; j++) {
            const size_t aa = i * q + j, ab = i * q + n + j, ba = (n + i) * q + j,
                         bb = (n + i) * q + n + j;
            off = dmax(fabs(mm[ab]), dmax(fabs(mm[ba]), dmax(fabs(kk[ab]), dmax(fabs(kk[ba]), off))));
            off = dmax(fabs(gg[aa]), dmax(fabs(gg[bb]), off));
            off = dmax(fabs(gg[ab] + gg[(n + j) * q + i]), off);
            w->ma[i * n + j] = mm[aa];
            w->mb[i * n + j] = mm[bb];
            w->ka[i * n + j] = kk[aa];
            w->kb[i * n + j] = kk[bb];
            w->gab[i * n + j] = gg[ab];
        }
    }
    if (damp > 0)
        return whirl_fail(GSL_EINVAL, "the window search needs the conservative chain (no "
                                      "damping or drag)");
    if (!(off <= 1e-13 * scale))
        return whirl_fail(GSL_EINVAL, "the window search needs a free planar shape: in-plane "
                                      "and out-of-plane motions couple (%.3g)", off);
    return GSL_SUCCESS;
}

/* A' = -B^-1 K' into w->a (row-major 2N x 2N). */
static int reduced_matrix(whirl_windows *w)
{
    const size_t n = w->n, q = 2 * n;
    double *a = w->a;
    /* rows 0..N-1: Y1 = -Ma^-1 [Ka | Gab]; rows N..2N-1: Y2 = Mb^-1 (Gab^T Y1 - [0 | Kb]).
     * Column-major solves on the transposed rows: Ma and Mb are symmetric. */
    double *y1 = w->vl, *y2 = w->vl + n * q; /* scratch: N x 2N column-major each */
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            y1[i + j * n] = -w->ka[i * n + j];
            y1[i + (n + j) * n] = -w->gab[i * n + j];
        }
    double *factor = w->a; /* N x N scratch before A' is written */
    memcpy(factor, w->ma, n * n * sizeof(double));
    int info;
    int status = whirl_worker_dposv(n, q, factor, n, y1, n, &info);
    if (status) return status; /* a stop request: the solve runs on a worker */
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the in-plane mass matrix is not positive definite "
                                       "(dposv info %d)", (int)info);
    for (size_t col = 0; col < q; col++) {
        /* N^2 operations a column: the stop request is read every column */
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request while forming the reduced "
                                                  "matrix");
        const double *v = y1 + col * n;
        for (size_t i = 0; i < n; i++) {
            double sum = col >= n ? -w->kb[i * n + col - n] : 0.0;
            for (size_t k = 0; k < n; k++) sum += w->gab[k * n + i] * v[k];
            y2[i + col * n] = sum;
        }
    }
    memcpy(factor, w->mb, n * n * sizeof(double));
    status = whirl_worker_dposv(n, q, factor, n, y2, n, &info);
    if (status) return status;
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the out-of-plane mass matrix is not positive definite "
                                       "(dposv info %d)", (int)info);
    for (size_t i = 0; i < n; i++)
        for (size_t col = 0; col < q; col++) {
            a[i * q + col] = y1[i + col * n];
            a[(n + i) * q + col] = y2[i + col * n];
        }
    return GSL_SUCCESS;
}

/* P A' P with P l = alpha e_1, l = (-Gab s_b, Mb s_b) (header comment); none if s_b = 0. */
static void deflate(whirl_windows *w, const double *symmetry)
{
    const size_t n = w->n, q = 2 * n;
    const double *sb = symmetry + n;
    double snorm = 0;
    for (size_t j = 0; j < n; j++) snorm = fmax(snorm, fabs(sb[j]));
    w->deflated = 0;
    w->hv_tau = 0;
    if (snorm == 0) return; /* hanging straight down: no symmetry mode */
    double *v = w->hv;
    for (size_t i = 0; i < n; i++) {
        double g = 0, m = 0;
        for (size_t j = 0; j < n; j++) {
            g += w->gab[i * n + j] * sb[j];
            m += w->mb[i * n + j] * sb[j];
        }
        v[i] = -g;
        v[n + i] = m;
    }
    double norm = 0;
    for (size_t i = 0; i < q; i++) norm = hypot(norm, v[i]);
    const double alpha = v[0] > 0 ? -norm : norm;
    v[0] -= alpha;
    double vv = 0;
    for (size_t i = 0; i < q; i++) vv += v[i] * v[i];
    const double tau = 2 / vv;
    double *a = w->a, *t = w->x; /* t: 2N scratch */
    /* A <- A - tau v (v^T A) */
    for (size_t j = 0; j < q; j++) t[j] = 0;
    for (size_t i = 0; i < q; i++)
        for (size_t j = 0; j < q; j++) t[j] += v[i] * a[i * q + j];
    for (size_t i = 0; i < q; i++)
        for (size_t j = 0; j < q; j++) a[i * q + j] -= tau * v[i] * t[j];
    /* A <- A - tau (A v) v^T */
    for (size_t i = 0; i < q; i++) {
        double s = 0;
        for (size_t j = 0; j < q; j++) s += a[i * q + j] * v[j];
        for (size_t j = 0; j < q; j++) a[i * q + j] -= tau * s * v[j];
    }
    w->hv_tau = tau;
    w->deflated = 1;
}

/* Round-off level of the growth: as whirl_stability_growth, 1e-10 of the largest |lambda|. */
static double neutral_level(const double *re, const double *im, size_t count)
{
    double big = 0;
    for (size_t i = 0; i < count; i++) big = fmax(big, hypot(re[i], im[i]));
    return 1e-10 * sqrt(big);
}

/* E / 2 of the header comment for the eigenvector x = xr + i xi (full space, 2N; xi NULL for a
 * real one) of A', mu = -w2. */
static double full_energy(const whirl_windows *w, const double *xr, const double *xi, double w2)
{
    const size_t n = w->n;
    double energy = 0;
    for (int part = 0; part < 2; part++) {
        const double *x = part == 0 ? xr : xi;
        if (x == NULL) continue;
        const double *a = x, *c = x + n;
        for (size_t i = 0; i < n; i++) {
            double ma = 0, mb = 0, gc = 0;
            for (size_t j = 0; j < n; j++) {
                ma += w->ma[i * n + j] * a[j];
                mb += w->mb[i * n + j] * c[j];
                gc += w->gab[i * n + j] * c[j];
            }
            energy += w2 * a[i] * ma + c[i] * mb - a[i] * gc;
        }
    }
    return energy;
}

/* E / 2 for the eigenvector y (2N - deflated, real part yr, imaginary part yi or NULL) of the
 * deflated matrix, mu = -w2: full_energy of x = P [0; y]. */
static double mode_energy(whirl_windows *w, const double *yr, const double *yi, double w2)
{
    const size_t q = 2 * w->n, d = w->deflated;
    for (int part = 0; part < 2; part++) {
        const double *y = part == 0 ? yr : yi;
        if (y == NULL) continue;
        double *x = w->x + part * q;
        for (size_t i = 0; i < d; i++) x[i] = 0;
        for (size_t i = d; i < q; i++) x[i] = y[i - d];
        if (d) {
            double s = 0;
            for (size_t i = 0; i < q; i++) s += w->hv[i] * x[i];
            for (size_t i = 0; i < q; i++) x[i] -= w->hv_tau * s * w->hv[i];
        }
    }
    return full_energy(w, w->x, yi ? w->x + q : NULL, w2);
}

/* The energy of neutral mode i of the last dgeev (its left eigenvectors in w->vl). */
static double nlink_energy(void *data, size_t i)
{
    whirl_windows *w = data;
    const size_t m = 2 * w->n - w->deflated;
    const double *yr = w->vl + i * m, *yi = NULL;
    if (w->im[i] > 0) yi = w->vl + (i + 1) * m;
    if (w->im[i] < 0) yr = w->vl + (i - 1) * m, yi = w->vl + i * m;
    return mode_energy(w, yr, yi, -w->re[i]);
}

int whirl_windows_spectrum(whirl_windows *w, const whirl_stability *lin, int signatures,
                           whirl_spectrum *out)
{
    int status = windows_split_blocks(w, lin);
    if (!status) status = reduced_matrix(w);
    if (status) return status;
    deflate(w, whirl_stability_symmetry(lin));
    const size_t q = 2 * w->n, d = w->deflated, m = q - d;
    /* the row-major trailing block read column-major is its transpose: its left eigenvectors
     * are the right eigenvectors of the block */
    int info;
    status = whirl_worker_dgeev(signatures ? 'V' : 'N', 'N', m, w->a + d * q + d, q, w->re,
                                w->im, w->vl, m, w->work, (int)w->lwork, &info);
    if (status) return status; /* a stop request: the solve runs on a worker */
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the eigenvalue iteration failed (dgeev info %d)",
                          (int)info);
    for (size_t i = 0; i < m; i++)
        if (!isfinite(w->re[i]) || !isfinite(w->im[i]))
            return whirl_fail(GSL_ERANGE, "non-finite eigenvalue");
    const double level = neutral_level(w->re, w->im, m);
    whirl_windows_classify(out, m, w->re, w->im, level, signatures ? w->sig : NULL, nlink_energy,
                           w);
    return GSL_SUCCESS;
}

/* The shape of the mode at omega, its nodes from the branch's link angles (at high rates the
 * tip radius alone does not fix them to round-off), then the linearisation. */
static int linearise_at(whirl_windows *w, double omega)
{
    if (omega == w->lin_omega) return GSL_SUCCESS;
    w->lin_omega = NAN;
    whirl_shape_info info;
    int status = whirl_nlink_solve_nodes(w->chain, omega, w->mode, &info, w->r, w->z,
                                         w->tension);
    if (status) return status;
    whirl_model m = {0};
    m.chain = w->chain;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = omega;
    status = whirl_stability_linearise(w->lin, &m, w->r, w->z);
    w->stats->shapes++;
    if (!status) w->lin_omega = omega;
    return status;
}

/* The N-link chain as a source of spectra: the shape, its linearisation. */
static int nlink_spectrum(void *data, double omega, int signatures, whirl_spectrum *out)
{
    whirl_windows *w = data;
    int status = linearise_at(w, omega);
    if (!status && w->fast) {
        status = whirl_windows_spectrum_banded(w, w->chain, omega, w->lin, signatures, out);
        if (status != GSL_CONTINUE) return status;
        w->fallbacks++;
        status = GSL_SUCCESS;
    }
    if (!status) status = whirl_windows_spectrum(w, w->lin, signatures, out);
    return status;
}

static int krylov_pair(whirl_windows *w, double sigma, double *mu_re, double *mu_im);

static int nlink_pair(void *data, double omega, double sigma, double *mu_re, double *mu_im)
{
    whirl_windows *w = data;
    int status = linearise_at(w, omega);
    if (!status) status = windows_split_blocks(w, w->lin);
    if (status) return status;
    const int banded = w->fast ? windows_structure_of(w, w->chain, omega, w->lin) : 0;
    if (banded < 0) return WHIRL_EINTERRUPTED;
    if (banded) { /* the banded factors */
        if (windows_band_factor(w, sigma) != 0) return GSL_CONTINUE;
        return whirl_windows_arnoldi_pair(&w->kr, windows_band_apply, w, sigma, mu_re, mu_im);
    }
    return krylov_pair(w, sigma, mu_re, mu_im);
}

/* y = (A' - sigma)^-1 x = -(K' + sigma B)^-1 B x, B x = (Ma x_a, -Gab^T x_a + Mb x_c), with the LU
 * factors of K' + sigma B in w->a. */
static int nlink_apply(void *data, const double *x, double *y)
{
    whirl_windows *w = data;
    const size_t n = w->n, q = 2 * n;
    for (size_t i = 0; i < n; i++) {
        double s1 = 0, s2 = 0;
        for (size_t j = 0; j < n; j++) {
            s1 += w->ma[i * n + j] * x[j];
            s2 += w->mb[i * n + j] * x[n + j] - w->gab[j * n + i] * x[j];
        }
        y[i] = -s1;
        y[n + i] = -s2;
    }
    lapack_int info = whirl_la_dgetrs_work(LAPACK_COL_MAJOR, 'N', (lapack_int)q, 1, w->a,
                                          (lapack_int)q, w->ipiv, y, (lapack_int)q);
    return info == 0 ? GSL_SUCCESS : GSL_CONTINUE;
}

/* The eigenvalues of A' nearest the real shift sigma by shift-and-invert Arnoldi: the two of
 * largest |theta| among the eigenvalues theta of (A' - sigma)^-1 = -(K' + sigma B)^-1 B,
 * mu = sigma + 1 / theta, into mu_re[0..1], mu_im[0..1]. GSL_CONTINUE if they did not converge. */
static int krylov_pair(whirl_windows *w, double sigma, double *mu_re, double *mu_im)
{
    const size_t n = w->n, q = 2 * n;
    double *a = w->a; /* K' + sigma B, column-major */
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            a[i + j * q] = w->ka[i * n + j] + sigma * w->ma[i * n + j];
            a[i + (n + j) * q] = w->gab[i * n + j];
            a[n + i + j * q] = -sigma * w->gab[j * n + i];
            a[n + i + (n + j) * q] = w->kb[i * n + j] + sigma * w->mb[i * n + j];
        }
    int info;
    const int status = whirl_worker_dgetrf(q, a, q, w->ipiv, &info);
    if (status) return status; /* a stop request: the factorisation runs on a worker */
    if (info != 0) return GSL_CONTINUE; /* sigma is an eigenvalue: use the full solve */
    return whirl_windows_arnoldi_pair(&w->kr, nlink_apply, w, sigma, mu_re, mu_im);
}

int whirl_windows_pair(whirl_windows *w, const whirl_stability *lin, double sigma, double *mu_re,
                       double *mu_im)
{
    int status = windows_split_blocks(w, lin);
    if (status) return status;
    if (krylov_pair(w, sigma, mu_re, mu_im) != GSL_SUCCESS)
        return whirl_fail(GSL_CONTINUE, "the Arnoldi iteration at sigma = %g did not converge in "
                                        "%d steps", sigma, WINDOWS_KRYLOV_MAX);
    return GSL_SUCCESS;
}

int whirl_windows_find(whirl_windows *w, const whirl_chain *c, int mode,
                       const whirl_windows_params *p, whirl_window *windows, size_t max,
                       size_t *count, whirl_windows_stats *stats)
{
    *count = 0;
    memset(stats, 0, sizeof *stats);
    if (c->n != w->n)
        return whirl_fail(GSL_EINVAL, "the chain has %zu links, the workspace %zu", c->n, w->n);
    if (mode < 1 || (size_t)mode > c->n)
        return whirl_fail(GSL_EINVAL, "mode %d of a %zu-link chain does not exist", mode, c->n);
    double *critical = malloc((size_t)mode * sizeof *critical);
    if (critical == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = whirl_nlink_critical(c, (size_t)mode, critical);
    const double birth = critical[mode - 1];
    free(critical);
    if (status) return status;
    double *omega;
    size_t npts;
    if ((status = whirl_windows_range(p, mode, birth, &omega, &npts))) return status;
    w->chain = c;
    w->mode = mode;
    w->stats = stats;
    w->lin_omega = NAN;
    whirl_shape_info *info = malloc(npts * sizeof *info);
    int *exists = malloc(npts * sizeof *exists);
    status = (!info || !exists) ? whirl_fail(GSL_ENOMEM, "out of memory") : 0;
    if (!status) status = whirl_nlink_branch(c, mode, npts, omega, info, exists);
    for (size_t j = 0; j < npts && !status; j++) {
        if (!exists[j])
            status = whirl_fail(GSL_EFAILED, "mode %d: no shape at omega = " WHIRL_Q_RATE "%g on "
                                "its branch", mode, omega[j]);
    }
    w->fast = p->krylov != 0;
    w->fallbacks = 0;
    windows_source src = {nlink_spectrum, p->krylov ? nlink_pair : NULL, w, mode, stats};
    if (!status) status = whirl_windows_search(&src, p, omega, npts, windows, max, count);
    w->lin_omega = NAN;
    free(omega);
    free(info);
    free(exists);
    return status;
}
