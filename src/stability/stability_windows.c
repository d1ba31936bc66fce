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
 * Windows: a scan at a coarse step computes the mu and their signatures. Between two neutral scan
 * points, a window can open and close only through a collision of opposite signatures, which
 * swaps their order in frequency: the "ranks" (for each mode with E < 0, the number of modes with
 * E > 0 below it in frequency) then differ, and bisection finds the unstable rate between. An
 * edge between a neutral and an unstable rate is the root of the collision discriminant
 *     D(omega) = Re (mu_1 - mu_2)^2
 * of the two mu that meet there (positive while they are real and distinct, -4 (Im mu)^2 once
 * they are a complex pair): D is analytic across the edge, although mu_1 and mu_2 are not, and
 * its round-off is O(eps |A'|) even where the pair is defective, so Brent's method locates the
 * edge to near round-off. A divergence edge (a mu through 0) uses D = -mu of the mu nearest 0.
 * Near the edge only the colliding pair matters: D is then taken from the two eigenvalues of A'
 * nearest a real shift sigma, by Arnoldi's method on (A' - sigma)^-1 = -(K' + sigma B)^-1 B (one
 * LU factorisation and a few solves instead of the full Hessenberg QR; Saad 2011, ch. 7), with a
 * fall-back to the full eigenvalues when the Ritz values do not converge.
 * Which mu can collide. Write q^H (lambda^2 M + lambda G + K) q = 0 as lambda^2 m + i lambda g
 * + k = 0 (m = q^H M q > 0, i g = q^H G q, k = q^H K q real). By stability.c's formulas,
 * M = F^T (S (x) I) F, G = 2 omega F^T (S (x) Z) F and K = diag(T l) - omega^2 F^T (S (x) P) F
 * with F = diag(l_j E_j) (3N x 2N), S_jk = mu_max(j,k) positive definite, Z = z^x (|Z| = 1),
 * P = diag(1, 1, 0) and tensions T > 0, so |g| <= 2 omega m (Cauchy-Schwarz in the S (x) I
 * product) and k >= -omega^2 m. A lambda off the imaginary axis needs g^2 + 4 m k < 0
 * and then |lambda|^2 = -k / m <= omega^2; a neutral mode lambda = i w has
 * E / 2 >= (w^2 - omega w)(|a|_Ma^2 + |b|_Mb^2) (|Re(a^H Gab c)| <= 2 omega w |a|_Ma |b|_Mb),
 * positive for w > omega. So every unstable mu and every mode of negative energy lie in
 * |mu| <= omega^2, and the ranks and gaps need only those and the first neutral mu beyond
 * omega^2 (the mode of positive energy next above the highest of negative energy).
 * The banded path (the scan and the pair near an edge; the dense path above is the reference,
 * whirl_windows_params.krylov = 0). With S = L^T diag(m) L (L the lower triangle of ones) and
 * per link alpha_j = l_j e1_j . x, beta_j = l_j e1_j . z, gamma_j = l_j
 * (e1_j = (-u_z, 0, u_x), e2_j = y for a shape in the x-z plane, stability.c's chart):
 *     Ma = Da S Da + Db S Db,  Mb = Dg S Dg,  Gab = -2 omega Da S Dg,
 *     Ka = diag(T l) - omega^2 Da S Da,  Kb = diag(T l) - omega^2 Dg S Dg,
 * so K' + sigma B = diag(T l) + F^T (S (x) C) F, F x = (alpha_j a_j, beta_j a_j, gamma_j c_j)_j
 * on the components (x, z, y), C = [[sigma - omega^2, 0, -2 omega], [0, sigma, 0],
 * [2 omega sigma, 0, sigma - omega^2]] (B x the same with dC/dsigma). With the partial sums
 * w_j = w_(j-1) + (F x)_j and u_j = u_(j+1) + m_j C w_j, (K' + sigma B) x = r reads
 * T_j l_j a_j + alpha_j u_j,x + beta_j u_j,z = r_a,j and T_j l_j c_j + gamma_j u_j,y = r_c,j: 8
 * unknowns per link, a band of 8 sub- and 8 super-diagonals, LU with partial pivoting (dgbtrf)
 * in O(N) and each solve in O(N), where the dense LU and dgeev cost O(N^3). The form is built
 * from the nodes and T_j l_j = Kb_jj + omega^2 Mb_jj, and used only if it reproduces the five
 * dense blocks to 1e-11 of their largest entry. The mu that can collide come from Arnoldi's
 * method on (A' - sigma)^-1, sigma = omega^2 / 4, restricted to ker l^T (invariant, since
 * l^T A' = 0, and carrying the deflated spectrum; each vector is projected on it), with full
 * reorthogonalisation: the Ritz values by decreasing |theta| (increasing |mu - sigma|) are kept
 * while converged (residual <= 1e-12 |theta|) up to the first neutral mu < -omega^2, so the disc
 * kept holds |mu| <= omega^2. The Ritz vectors V s are the eigenvectors of A' in ker l^T, the
 * P [0; y] of the dense path, and give the signatures. Check (Mackay 1986): a pair lambda = +-i w of
 * negative energy carries two negative directions of the Hamiltonian, a real pair one, a complex
 * quadruplet two, so 2 #(neutral, E < 0) + #(non-neutral mu) must equal the index of K. That index
 * costs O(N): Kb is the Schur complement of W = L^-1 diag(1 / m) L^-T / omega^2 (tridiagonal,
 * definite) in [[diag(T l), Dg], [Dg, W]], whose other Schur complement is the tridiagonal
 * T_b = W - Dg diag(T l)^-1 Dg, so In(Kb) = In(T_b) (Haynsworth's inertia additivity, T > 0), and
 * likewise Ka with Da; Sturm counts below -1e-9 |T| (the rotation's zero of Kb not counted). The
 * round-off level 1e-10 sqrt(max |mu|) takes max |mu| from the out-of-plane block without the
 * Coriolis coupling: the largest eigenvalue of the tridiagonal diag(T l)^1/2 Mb^-1 diag(T l)^1/2
 * less omega^2 (bisection). Not converged in 240 steps, or the count differs: the dense path at
 * that rate.
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

#include <gsl/gsl_min.h>
#include "core/linalg.h"

#include "whirl/stability.h"
#include "core/error.h"
#include "core/input.h"
#include "core/roots.h"
#include "stability/windows_internal.h"
#include "core/worker.h"

#define WINDOWS_BAND_KRYLOV 240 /* most Arnoldi steps of the banded path */
#define WINDOWS_BAND_START 20   /* steps before its first Ritz values */
#define WINDOWS_BAND_EVERY 10   /* steps between Ritz values */
#define BAND_KL 8               /* sub- and super-diagonals of the augmented matrix */
#define BAND_LD (3 * BAND_KL + 1) /* its LAPACK band storage: 2 kl + ku + 1 rows */
#define BAND_AT(row, col) ((size_t)(2 * BAND_KL + (int)(row) - (int)(col)) + (size_t)(col) * BAND_LD)

struct whirl_windows {
    size_t n;              /* links N */
    whirl_stability *lin;  /* the linearisation */
    double *ma, *mb, *ka, *kb, *gab; /* N x N blocks, row-major */
    double *a;             /* 2N x 2N: A' (row-major), then P A' P; also K' + sigma B */
    double *hv;            /* Householder vector (2N) */
    double hv_tau;         /* its coefficient; 0: no deflation */
    size_t deflated;       /* 1 if the symmetry eigenvalue was removed */
    double *re, *im;       /* mu (2N) */
    int *sig;              /* signatures (2N) */
    double *vl;            /* eigenvectors from dgeev (2N x 2N) */
    double *x;             /* one eigenvector in the full space (2 x 2N: real and imaginary) */
    double *work;          /* dgeev workspace */
    lapack_int lwork;
    lapack_int *ipiv;      /* LU pivots (2N) */
    windows_arnoldi kr;    /* the Arnoldi iteration's workspace (vectors of 2N) */
    double *r, *z, *tension; /* nodes of a shape (N + 1) */
    /* the structured form (header comment) of the last linearisation, per link j */
    double *al, *be, *ga;  /* l_j e1_j . x, l_j e1_j . z, l_j */
    double *tl, *ms;       /* T_j l_j, m_j */
    double *tri;           /* 4N: the tridiagonal matrices of the index and of max |mu| */
    double *ab;            /* banded LU of the augmented K' + sigma B (BAND_LD x 8N) */
    lapack_int *bpiv;      /* its pivots (8N) */
    double *bx;            /* 8N scratch: right-hand side, the sums g */
    double *lv;            /* l = B^T (0, s_b) (2N), then 2N scratch */
    double bomega;         /* the rate of the structured form */
    int fast;              /* 1: scan points by the banded path (p->krylov) */
    size_t bm;             /* steps of the banded path's last Ritz values */
    size_t fallbacks;      /* evaluations where the banded path gave way to the dense one */
    windows_arnoldi kband;   /* the banded path's Arnoldi iteration (WINDOWS_BAND_KRYLOV steps) */
    int *kept;             /* Ritz column of each kept mu (WINDOWS_BAND_KRYLOV) */
    const whirl_chain *chain; /* of the current search */
    int mode;
    double lin_omega;      /* the rate of the linearisation in lin (NAN: none) */
    whirl_windows_stats *stats;
};

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

/* max(a, b), a if it is NaN (so that a NaN fails the checks below; inline where fmax is a call) */
static inline double dmax(double a, double b) { return a >= b || isnan(a) ? a : b; }

/* The blocks Ma, Mb, Ka, Kb, Gab of the last linearisation in lin, after checking the split
 * (planar, conservative) to round-off. */
static int split_blocks(whirl_windows *w, const whirl_stability *lin)
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

/* Re sqrt(mu) >= 0. */
static double root_re(double re, double im) { return sqrt(fmax(0, (hypot(re, im) + re) / 2)); }

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

void whirl_windows_classify(whirl_spectrum *out, size_t count, const double *re, const double *im,
                            double level, int *sig, double (*energy)(void *data, size_t i),
                            void *data)
{
    double growth = 0;
    for (size_t i = 0; i < count; i++) {
        const double g = root_re(re[i], im[i]);
        if (g > level) growth = fmax(growth, g);
        if (sig == NULL) continue;
        sig[i] = 0;
        if (g > level) continue;
        /* neutral: a real mu, or one of a pair of nearly equal ones split by round-off */
        const double e = energy(data, i);
        sig[i] = e > 0 ? 1 : e < 0 ? -1 : 0;
    }
    out->count = count;
    out->re = re;
    out->im = im;
    out->signature = sig;
    out->growth = growth;
    out->level = level;
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
    int status = split_blocks(w, lin);
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

/* Arnoldi step: v_(step+1) from apply(v_step), orthogonalised (Gram-Schmidt, twice) into column
 * step of the Hessenberg matrix; its norm h_(step+1,step) into *norm. GSL_CONTINUE if apply
 * failed. */
static int arnoldi_step(windows_arnoldi *k, size_t step,
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
static lapack_int ritz_values(windows_arnoldi *k, size_t m)
{
    for (size_t j = 0; j < m; j++)
        for (size_t i = 0; i < m; i++) k->hcopy[i + j * m] = k->hess[i + j * (k->km + 1)];
    return whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)m, k->hcopy, (lapack_int)m,
                              k->hre, k->him, NULL, 1, k->hvec, (lapack_int)m, k->hwork,
                              (lapack_int)k->hlwork);
}

/* The residual |h_(m+1,m) e_m^T s| / |s| of Ritz value i (its vector s: column i, or (re, im) at
 * (i, i + 1) / (i - 1, i) for a complex one). */
static double ritz_residual(const windows_arnoldi *k, size_t m, size_t i, double norm)
{
    const int cplx = k->him[i] != 0;
    const size_t cr = cplx && k->him[i] < 0 ? i - 1 : i, ci = cplx && k->him[i] > 0 ? i + 1 : i;
    const double last = hypot(k->hvec[m - 1 + cr * m], cplx ? k->hvec[m - 1 + ci * m] : 0);
    double len = 0;
    for (size_t r = 0; r < m; r++)
        len = hypot(len, hypot(k->hvec[r + cr * m], cplx ? k->hvec[r + ci * m] : 0));
    return norm * last / len;
}

/* ---- the banded path (header comment: the structured form) ---- */

/* The structured form of the last linearisation in lin (its blocks in w by split_blocks) of the
 * chain c at omega: alpha, beta, gamma from the nodes and the lengths, T_j l_j from the diagonal
 * of Kb (Kb_jj + omega^2 Mb_jj). 1 if it reproduces the five dense blocks to 1e-11 of their
 * largest entry, else 0 (then the dense path is used); -1 (WHIRL_EINTERRUPTED set) on a stop
 * request, read every row of the O(N^2) comparison. */
static int structure_of(whirl_windows *w, const whirl_chain *c, double omega,
                        const whirl_stability *lin)
{
    const size_t n = w->n;
    const double om2 = omega * omega;
    const double *x, *y, *z;
    w->bomega = NAN;
    if (c == NULL || c->n != n || !(omega > 0)) return 0;
    whirl_stability_nodes(lin, &x, &y, &z);
    for (size_t j = 0; j < n; j++) {
        const double dx = x[j + 1] - x[j], dy = y[j + 1] - y[j], dz = z[j + 1] - z[j];
        const double len = sqrt(dx * dx + dy * dy + dz * dz), l = c->length[j];
        if (!(len > 0) || !(fabs(dy) <= 1e-14 * len)) return 0; /* not in the x-z plane */
        w->al[j] = -l * dz / len; /* e1 = u x y = (-u_z, 0, u_x), e2 = y (stability.c's chart) */
        w->be[j] = l * dx / len;
        w->ga[j] = l;
        w->ms[j] = c->mass[j];
        w->tl[j] = w->kb[j * n + j] + om2 * w->mb[j * n + j];
    }
    double scale = 0, off = 0, mu = 0;
    for (size_t i = 0; i < n * n; i++)
        scale = dmax(fabs(w->ma[i]), dmax(fabs(w->mb[i]), dmax(fabs(w->gab[i]),
                     dmax(fabs(w->ka[i]), dmax(fabs(w->kb[i]), scale)))));
    for (size_t h = n; h-- > 0;) { /* entries (j, k) with max(j, k) = h */
        if (whirl_stop_requested()) {
            whirl_fail(WHIRL_EINTERRUPTED, "stopped by request while reading the linearisation");
            return -1;
        }
        mu += w->ms[h];
        for (size_t t = 0; t <= h; t++)
            for (int side = 0; side < 2; side++) {
                const size_t j = side ? t : h, k = side ? h : t, jk = j * n + k;
                const double tl = j == k ? w->tl[j] : 0;
                const double ma = mu * (w->al[j] * w->al[k] + w->be[j] * w->be[k]);
                const double mb = mu * w->ga[j] * w->ga[k];
                off = dmax(fabs(w->ma[jk] - ma), dmax(fabs(w->mb[jk] - mb), off));
                off = dmax(fabs(w->gab[jk] + 2 * omega * mu * w->al[j] * w->ga[k]), off);
                off = dmax(fabs(w->ka[jk] - (tl - om2 * mu * w->al[j] * w->al[k])), off);
                off = dmax(fabs(w->kb[jk] - (tl - om2 * mb)), off);
            }
    }
    if (!(off <= 1e-11 * scale)) return 0;
    w->bomega = omega;
    return 1;
}

/* y = F^T (S (x) C3) F x of the header comment for the 3 x 3 coupling C3 (row-major, components
 * in the order x, z, y), by the two sums w = L p and u = L^T g. */
static void structured_product(const whirl_windows *w, const double *c3, const double *x,
                               double *y)
{
    const size_t n = w->n;
    double *g = w->bx, s[3] = {0, 0, 0};
    for (size_t j = 0; j < n; j++) {
        s[0] += w->al[j] * x[j];
        s[1] += w->be[j] * x[j];
        s[2] += w->ga[j] * x[n + j];
        for (int r = 0; r < 3; r++)
            g[3 * j + r] = w->ms[j] * (c3[3 * r] * s[0] + c3[3 * r + 1] * s[1] + c3[3 * r + 2] * s[2]);
    }
    s[0] = s[1] = s[2] = 0;
    for (size_t j = n; j-- > 0;) {
        for (int r = 0; r < 3; r++) s[r] += g[3 * j + r];
        y[j] = w->al[j] * s[0] + w->be[j] * s[1];
        y[n + j] = w->ga[j] * s[2];
    }
}

/* B x (transpose 0) or B^T x (1): C3 = dC/dsigma of the header comment. */
static void b_product(const whirl_windows *w, int transpose, const double *x, double *y)
{
    const double g = 2 * w->bomega;
    const double cb[9] = {1, 0, transpose ? g : 0, 0, 1, 0, transpose ? 0 : g, 0, 1};
    structured_product(w, cb, x, y);
}

/* The banded LU factors of the augmented K' + sigma B (8N unknowns, header comment) into w->ab:
 * the LAPACK info (> 0: singular). */
static lapack_int band_factor(whirl_windows *w, double sigma)
{
    const size_t n = w->n, nb = 8 * n;
    const double om = w->bomega, om2 = om * om;
    const double cs[9] = {sigma - om2, 0, -2 * om, 0, sigma, 0, 2 * om * sigma, 0, sigma - om2};
    double *ab = w->ab;
    memset(ab, 0, BAND_LD * nb * sizeof *ab);
    for (size_t j = 0; j < n; j++) {
        const size_t b = 8 * j; /* a, c, w (x, z, y), u (x, z, y) */
        ab[BAND_AT(b, b)] = w->tl[j];
        ab[BAND_AT(b, b + 5)] = w->al[j];
        ab[BAND_AT(b, b + 6)] = w->be[j];
        ab[BAND_AT(b + 1, b + 1)] = w->tl[j];
        ab[BAND_AT(b + 1, b + 7)] = w->ga[j];
        for (size_t r = 0; r < 3; r++) { /* w_j - w_{j-1} - p_j = 0 */
            ab[BAND_AT(b + 2 + r, b + 2 + r)] = 1;
            if (j > 0) ab[BAND_AT(b + 2 + r, b - 6 + r)] = -1;
        }
        ab[BAND_AT(b + 2, b)] = -w->al[j];
        ab[BAND_AT(b + 3, b)] = -w->be[j];
        ab[BAND_AT(b + 4, b + 1)] = -w->ga[j];
        for (size_t r = 0; r < 3; r++) { /* u_j - u_{j+1} - m_j C w_j = 0 */
            ab[BAND_AT(b + 5 + r, b + 5 + r)] = 1;
            if (j + 1 < n) ab[BAND_AT(b + 5 + r, b + 13 + r)] = -1;
            for (size_t k = 0; k < 3; k++)
                if (cs[3 * r + k] != 0)
                    ab[BAND_AT(b + 5 + r, b + 2 + k)] = -w->ms[j] * cs[3 * r + k];
        }
    }
    return whirl_la_dgbtrf_work(LAPACK_COL_MAJOR, (lapack_int)nb, (lapack_int)nb, BAND_KL, BAND_KL,
                               ab, BAND_LD, w->bpiv);
}

/* y = (A' - sigma)^-1 x = -(K' + sigma B)^-1 B x with band_factor's factors; with project, y is
 * then projected on l^T y = 0 (the deflation). */
static int band_apply_any(whirl_windows *w, int project, const double *x, double *y)
{
    const size_t n = w->n, q = 2 * n, nb = 8 * n;
    b_product(w, 0, x, y);
    double *r = w->bx;
    memset(r, 0, nb * sizeof *r);
    for (size_t j = 0; j < n; j++) r[8 * j] = -y[j], r[8 * j + 1] = -y[n + j];
    lapack_int info = whirl_la_dgbtrs_work(LAPACK_COL_MAJOR, 'N', (lapack_int)nb, BAND_KL, BAND_KL,
                                          1, w->ab, BAND_LD, w->bpiv, r, (lapack_int)nb);
    if (info != 0) return GSL_CONTINUE;
    for (size_t j = 0; j < n; j++) y[j] = r[8 * j], y[n + j] = r[8 * j + 1];
    if (project) {
        double ly = 0, ll = 0;
        for (size_t i = 0; i < q; i++) ly += w->lv[i] * y[i], ll += w->lv[i] * w->lv[i];
        if (ll > 0)
            for (size_t i = 0; i < q; i++) y[i] -= ly / ll * w->lv[i];
    }
    return GSL_SUCCESS;
}

static int band_apply(void *data, const double *x, double *y) { return band_apply_any(data, 0, x, y); }
static int band_apply_projected(void *data, const double *x, double *y)
{
    return band_apply_any(data, 1, x, y);
}

/* Eigenvalues below s of the symmetric tridiagonal matrix with diagonal d and squared
 * off-diagonal e2 (e2[i] couples i and i + 1): the negative pivots of its LDL^T - s (Sturm;
 * backward stable, as LAPACK's dlaebz). */
static size_t sturm_count(const double *d, const double *e2, size_t n, double s, double pivmin)
{
    size_t count = 0;
    double piv = 1;
    for (size_t i = 0; i < n; i++) {
        piv = d[i] - s - (i > 0 ? e2[i - 1] / piv : 0);
        if (fabs(piv) < pivmin) piv = -pivmin;
        count += piv < 0;
    }
    return count;
}

/* The index of K (negative eigenvalues, the rotation's zero not counted) from the tridiagonal
 * matrices T_a, T_b of the header comment, and in *big the largest |mu| of the out-of-plane
 * block without the Coriolis coupling (the eigenvalues of the tridiagonal
 * T^1/2 l Mb^-1 l T^1/2, less omega^2). -1 if the tensions are not all positive. */
static int band_index(whirl_windows *w, double *big)
{
    const size_t n = w->n;
    const double om2 = w->bomega * w->bomega;
    double *d = w->tri, *e2 = w->tri + n, *sd = w->tri + 2 * n, *se = w->tri + 3 * n;
    for (size_t i = 0; i < n; i++) { /* S^-1 = L^-1 diag(1 / m) L^-T: sd diagonal, se below */
        if (!(w->tl[i] > 0)) return -1;
        sd[i] = 1 / w->ms[i] + (i > 0 ? 1 / w->ms[i - 1] : 0);
        se[i] = i + 1 < n ? -1 / w->ms[i] : 0;
    }
    int index = 0;
    for (int plane = 0; plane < 2; plane++) {
        const double *f = plane == 0 ? w->al : w->ga;
        double norm = 0, emax = 0;
        for (size_t i = 0; i < n; i++) {
            d[i] = sd[i] / om2 - f[i] * f[i] / w->tl[i];
            e2[i] = se[i] * se[i] / (om2 * om2);
            norm = fmax(norm, fabs(d[i]) + 2 * sqrt(e2[i]));
            emax = fmax(emax, e2[i]);
        }
        const double pivmin = fmax(DBL_MIN, DBL_MIN * emax);
        index += (int)sturm_count(d, e2, n, -1e-9 * norm, pivmin);
    }
    /* the largest eigenvalue of T^1/2 Mb^-1 T^1/2 (Mb^-1 = l^-1 S^-1 l^-1) by bisection */
    double hi = 0, emax = 0;
    for (size_t i = 0; i < n; i++) {
        d[i] = w->tl[i] * sd[i] / (w->ga[i] * w->ga[i]);
        e2[i] = i + 1 < n ? w->tl[i] * w->tl[i + 1] * se[i] * se[i] /
                                (w->ga[i] * w->ga[i] * w->ga[i + 1] * w->ga[i + 1])
                          : 0;
        emax = fmax(emax, e2[i]);
    }
    for (size_t i = 0; i < n; i++)
        hi = fmax(hi, d[i] + sqrt(e2[i]) + (i > 0 ? sqrt(e2[i - 1]) : 0));
    double lo = 0;
    const double pivmin = fmax(DBL_MIN, DBL_MIN * emax);
    for (int it = 0; it < 60 && hi - lo > 1e-12 * hi; it++) {
        const double mid = (lo + hi) / 2;
        if (sturm_count(d, e2, n, mid, pivmin) >= n)
            hi = mid;
        else
            lo = mid;
    }
    *big = fmax(0, hi - om2);
    return index;
}

/* The energy of kept mu i of the banded path: its Ritz vector V s (full space). */
static double band_energy(void *data, size_t i)
{
    whirl_windows *w = data;
    windows_arnoldi *k = &w->kband;
    const size_t q = 2 * w->n, m = w->bm, col = (size_t)w->kept[i];
    const int cplx = k->him[col] != 0;
    const size_t cr = cplx && k->him[col] < 0 ? col - 1 : col, ci = cr + 1;
    double *xr = w->x, *xi = w->x + q;
    for (size_t r = 0; r < q; r++) {
        double sr = 0, si = 0;
        for (size_t t = 0; t < m; t++) {
            sr += k->basis[t * q + r] * k->hvec[t + cr * m];
            if (cplx) si += k->basis[t * q + r] * k->hvec[t + ci * m];
        }
        xr[r] = sr, xi[r] = si;
    }
    /* E / 2 = x^T F^T (S (x) C_E) F x, C_E = [[w^2, 0, omega], [0, w^2, 0], [omega, 0, 1]]
     * (the form of full_energy in the structured form), O(N) */
    const double w2 = -w->re[i], om = w->bomega;
    const double ce[9] = {w2, 0, om, 0, w2, 0, om, 0, 1};
    double energy = 0, *y = w->lv + q;
    for (int part = 0; part < 1 + cplx; part++) {
        const double *xp = part ? xi : xr;
        structured_product(w, ce, xp, y);
        for (size_t r = 0; r < q; r++) energy += xp[r] * y[r];
    }
    return energy;
}

#define BAND_TOL 1e-12 /* Ritz residual / |theta| accepted */

/* The mu of the deflated A' with |mu - sigma| up to the first neutral mu beyond omega^2 (header
 * comment), sigma = omega^2 / 4, by shift-and-invert Arnoldi on ker l^T with the banded factors,
 * into w->re, w->im (nearest sigma first), with the signatures if asked, into out. GSL_CONTINUE
 * when the dense path must be taken (not converged, or the index check failed). */
static int band_spectrum(whirl_windows *w, int signatures, const double *symmetry,
                         whirl_spectrum *out)
{
    const size_t n = w->n, q = 2 * n;
    const double om2 = w->bomega * w->bomega;
    double sigma = om2 / 4;
    int tries = 0;
    while (band_factor(w, sigma) != 0)
        if (++tries == 4) return GSL_CONTINUE;
        else sigma *= 1.1;
    double *lv = w->lv, snorm = 0;
    for (size_t i = 0; i < q; i++) w->x[i] = i < n ? 0 : symmetry[i];
    for (size_t i = n; i < q; i++) snorm = fmax(snorm, fabs(symmetry[i]));
    if (snorm > 0)
        b_product(w, 1, w->x, lv);
    else
        memset(lv, 0, q * sizeof *lv);
    windows_arnoldi *k = &w->kband;
    const size_t dim = q - (snorm > 0), km = k->km < dim ? k->km : dim; /* dim: of ker l^T */
    double *v = k->basis, *h = k->hess;
    memset(h, 0, (k->km + 1) * k->km * sizeof(double));
    for (size_t i = 0; i < q; i++) w->x[i] = sin(0.7 * (double)i + 0.3) + 0.5;
    double norm = 0;
    band_apply_any(w, 1, w->x, v); /* a start in ker l^T, smoothed once */
    for (size_t i = 0; i < q; i++) norm = hypot(norm, v[i]);
    if (!(norm > 0)) return GSL_CONTINUE;
    for (size_t i = 0; i < q; i++) v[i] /= norm;
    double hmax = 0;
    for (size_t step = 0; step < km; step++) {
        if (arnoldi_step(k, step, band_apply_projected, w, &norm)) return GSL_CONTINUE;
        for (size_t j = 0; j <= step + 1; j++) hmax = fmax(hmax, fabs(h[j + step * (k->km + 1)]));
        const size_t m = step + 1;
        const int whole = m == dim; /* the whole of ker l^T */
        if (!whole && !(norm > 1e-14 * hmax)) return GSL_CONTINUE; /* invariant, maybe not all */
        if (!whole && (m < WINDOWS_BAND_START || (m - WINDOWS_BAND_START) % WINDOWS_BAND_EVERY))
            continue;
        if (ritz_values(k, m) != 0) return GSL_CONTINUE;
        w->bm = m;
        /* the Ritz values by decreasing |theta| (increasing |mu - sigma|), each converged, up to
         * the first neutral one beyond omega^2 */
        int *order = w->kept, done = 0;
        for (size_t i = 0; i < m; i++) {
            size_t at = i;
            const double mod = hypot(k->hre[i], k->him[i]);
            for (; at > 0 && hypot(k->hre[order[at - 1]], k->him[order[at - 1]]) < mod; at--)
                order[at] = order[at - 1];
            order[at] = (int)i;
        }
        size_t keep = 0;
        for (; keep < m; keep++) {
            const size_t i = (size_t)order[keep];
            const int cplx = k->him[i] != 0;
            const double mod = hypot(k->hre[i], k->him[i]);
            if (!whole && !(ritz_residual(k, m, i, norm) <= BAND_TOL * mod)) break;
            const double mu = sigma + k->hre[i] / (mod * mod);
            w->re[keep] = mu;
            w->im[keep] = -k->him[i] / (mod * mod);
            if (!cplx && mu < -om2 * (1 + 1e-8)) {
                done = 1;
                keep++;
                break;
            }
        }
        if (!done && !whole) continue;
        /* not done: the whole space, every mu */
        double big = 0;
        const int index = band_index(w, &big);
        for (size_t i = 0; i < keep; i++) big = fmax(big, hypot(w->re[i], w->im[i]));
        whirl_windows_classify(out, keep, w->re, w->im, 1e-10 * sqrt(big),
                               signatures ? w->sig : NULL, band_energy, w);
        if (!signatures) return GSL_SUCCESS;
        /* Mackay's count: 2 (neutral, E < 0) + (complex) + (real positive) = index of K */
        int count2 = 0;
        for (size_t i = 0; i < keep; i++)
            count2 += w->sig[i] < 0 ? 2 : (root_re(w->re[i], w->im[i]) > out->level);
        return count2 == index ? GSL_SUCCESS : GSL_CONTINUE;
    }
    return GSL_CONTINUE;
}

int whirl_windows_spectrum_banded(whirl_windows *w, const whirl_chain *c, double omega,
                                  const whirl_stability *lin, int signatures, whirl_spectrum *out)
{
    int status = split_blocks(w, lin);
    if (status) return status;
    const int banded = structure_of(w, c, omega, lin);
    if (banded < 0) return WHIRL_EINTERRUPTED;
    if (!banded) return GSL_CONTINUE;
    return band_spectrum(w, signatures, whirl_stability_symmetry(lin), out);
}

/* ---- the search ---- */

typedef struct point {
    double omega, growth;
    int unstable;
    size_t ncomplex; /* non-neutral mu */
    int *rank;       /* for each neutral mode with E < 0 (by frequency), the modes with E > 0
                        below it; NULL at points without signatures */
    size_t nrank;
    double mu_c;     /* unstable: the non-neutral mu of largest growth */
    double mu_c_im;
    double *gap;     /* for each neutral mode with E < 0 (by frequency) and the nearest mode
                        with E > 0 below (2 r) and above (2 r + 1) it in frequency: their
                        discriminant (mu_- - mu_+)^2 (NAN if there is none) */
    double *gap_mu;  /* and their mean mu */
} point;

static void point_free(point *p)
{
    free(p->rank);
    free(p->gap);
    free(p->gap_mu);
    p->rank = NULL;
    p->gap = p->gap_mu = NULL;
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

static int stop_check(const windows_source *src, double omega)
{
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "window search of mode %d interrupted at omega = "
                          WHIRL_Q_RATE "%.10g", src->mode, omega);
    return GSL_SUCCESS;
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
static int structure_of(whirl_windows *w, const whirl_chain *c, double omega,
                        const whirl_stability *lin);
static lapack_int band_factor(whirl_windows *w, double sigma);
static int band_apply(void *data, const double *x, double *y);

static int nlink_pair(void *data, double omega, double sigma, double *mu_re, double *mu_im)
{
    whirl_windows *w = data;
    int status = linearise_at(w, omega);
    if (!status) status = split_blocks(w, w->lin);
    if (status) return status;
    const int banded = w->fast ? structure_of(w, w->chain, omega, w->lin) : 0;
    if (banded < 0) return WHIRL_EINTERRUPTED;
    if (banded) { /* the banded factors */
        if (band_factor(w, sigma) != 0) return GSL_CONTINUE;
        return whirl_windows_arnoldi_pair(&w->kr, band_apply, w, sigma, mu_re, mu_im);
    }
    return krylov_pair(w, sigma, mu_re, mu_im);
}

/* A full evaluation: every mu, and with signatures the ranks. */
static int evaluate(const windows_source *src, double omega, int signatures, point *p)
{
    int status = stop_check(src, omega);
    whirl_spectrum sp;
    if (!status) status = src->spectrum(src->data, omega, signatures, &sp);
    if (status == WHIRL_EINTERRUPTED) return stop_check(src, omega); /* during the solve */
    if (status) return status;
    if (signatures)
        src->stats->solves_vectors++;
    else
        src->stats->solves_values++;
    p->omega = omega;
    p->growth = sp.growth;
    p->unstable = sp.growth > 0;
    p->ncomplex = 0;
    p->mu_c = p->mu_c_im = 0;
    double best = -1;
    for (size_t i = 0; i < sp.count; i++) {
        const double g = root_re(sp.re[i], sp.im[i]);
        if (g <= sp.level) continue;
        p->ncomplex++;
        if (g > best) best = g, p->mu_c = sp.re[i], p->mu_c_im = fabs(sp.im[i]);
    }
    point_free(p);
    p->nrank = 0;
    if (!signatures) return GSL_SUCCESS;
    /* neutral modes by frequency */
    size_t m = 0;
    int *order = malloc((sp.count + 1) * sizeof *order);
    if (order == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t i = 0; i < sp.count; i++)
        if (root_re(sp.re[i], sp.im[i]) <= sp.level) order[m++] = (int)i;
    for (size_t i = 1; i < m; i++) /* insertion sort by frequency (mu decreasing) */
        for (size_t j = i; j > 0 && sp.re[order[j - 1]] < sp.re[order[j]]; j--) {
            const int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    p->rank = malloc((m + 1) * sizeof *p->rank);
    p->gap = malloc(2 * (m + 1) * sizeof *p->gap);
    p->gap_mu = malloc(2 * (m + 1) * sizeof *p->gap_mu);
    if (!p->rank || !p->gap || !p->gap_mu) {
        free(order);
        return whirl_fail(GSL_ENOMEM, "out of memory");
    }
    size_t positive = 0;
    for (size_t i = 0; i < m; i++) {
        const int s = sp.signature[order[i]];
        if (s > 0) positive++;
        if (s >= 0) continue;
        const double mu = sp.re[order[i]];
        for (int side = 0; side < 2; side++) {
            double *g = p->gap + 2 * p->nrank + side, *gm = p->gap_mu + 2 * p->nrank + side;
            *g = *gm = NAN;
            for (size_t k = i; side == 0 ? k-- > 0 : ++k < m;)
                if (sp.signature[order[k]] > 0) {
                    const double other = sp.re[order[k]];
                    *g = (mu - other) * (mu - other);
                    *gm = (mu + other) / 2;
                    break;
                }
        }
        p->rank[p->nrank++] = (int)positive;
    }
    free(order);
    return GSL_SUCCESS;
}

static int same_ranks(const point *a, const point *b)
{
    if (a->nrank != b->nrank || a->ncomplex != b->ncomplex) return 0;
    for (size_t i = 0; i < a->nrank; i++)
        if (a->rank[i] != b->rank[i]) return 0;
    return 1;
}

/* The collision discriminant near mu_c from the eigenvalues re, im (count); updates mu_c. */
static double discriminant(const double *re, const double *im, size_t count, double level,
                           int divergence, double *mu_c)
{
    if (divergence) { /* -mu of the eigenvalue nearest 0 */
        size_t best = 0;
        for (size_t i = 1; i < count; i++)
            if (hypot(re[i], im[i]) < hypot(re[best], im[best])) best = i;
        return -re[best];
    }
    size_t first = 0;
    for (size_t i = 1; i < count; i++)
        if (hypot(re[i] - *mu_c, im[i]) < hypot(re[first] - *mu_c, im[first])) first = i;
    if (root_re(re[first], im[first]) > level && im[first] != 0) {
        *mu_c = re[first];
        return -4 * im[first] * im[first];
    }
    size_t second = first == 0 ? 1 : 0;
    for (size_t i = 0; i < count; i++)
        if (i != first && hypot(re[i] - *mu_c, im[i]) < hypot(re[second] - *mu_c, im[second]))
            second = i;
    *mu_c = (re[first] + re[second]) / 2;
    const double dr = re[first] - re[second], di = im[first] - im[second];
    return dr * dr - di * di;
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
        if (arnoldi_step(k, step, apply, data, &norm)) return GSL_CONTINUE;
        const size_t m = step + 1;
        if (m < 4 && norm > 0) continue;
        if (ritz_values(k, m) != 0) return GSL_CONTINUE;
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
            if (!(ritz_residual(k, m, best[t], norm) <= 1e-13 * big[t])) converged = 0;
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
    int status = split_blocks(w, lin);
    if (status) return status;
    if (krylov_pair(w, sigma, mu_re, mu_im) != GSL_SUCCESS)
        return whirl_fail(GSL_CONTINUE, "the Arnoldi iteration at sigma = %g did not converge in "
                                        "%d steps", sigma, WINDOWS_KRYLOV_MAX);
    return GSL_SUCCESS;
}

typedef struct root_args {
    const windows_source *src;
    const whirl_windows_params *p;
    double mu_c;
    int divergence;
    int status;
    double growth_sign; /* minimisation: -1 (maximise the growth of the pair near mu_c) */
} root_args;

/* D(omega) or -growth(omega) near mu_c: by Arnoldi when asked and converged, else in full. */
static double pair_function(double omega, void *data)
{
    root_args *r = data;
    const windows_source *src = r->src;
    if (r->status) return NAN;
    int status = stop_check(src, omega);
    if (status) {
        r->status = status;
        return NAN;
    }
    double mu_re[2], mu_im[2];
    if (r->p->krylov && src->pair && !r->divergence) {
        status = src->pair(src->data, omega, r->mu_c, mu_re, mu_im);
        if (status == GSL_SUCCESS) {
            src->stats->solves_krylov++;
            if (r->growth_sign != 0) {
                const double g = fmax(root_re(mu_re[0], mu_im[0]), root_re(mu_re[1], mu_im[1]));
                r->mu_c = mu_re[0];
                return -g;
            }
            return discriminant(mu_re, mu_im, 2, 0, 0, &r->mu_c);
        }
        if (status != GSL_CONTINUE) {
            r->status = status;
            return NAN;
        }
    }
    whirl_spectrum sp;
    status = src->spectrum(src->data, omega, 0, &sp);
    if (status) {
        r->status = status;
        return NAN;
    }
    src->stats->solves_values++;
    if (r->growth_sign != 0) { /* the growth of the mu nearest mu_c */
        size_t best = 0;
        for (size_t i = 1; i < sp.count; i++)
            if (hypot(sp.re[i] - r->mu_c, sp.im[i]) < hypot(sp.re[best] - r->mu_c, sp.im[best]))
                best = i;
        r->mu_c = sp.re[best];
        return -root_re(sp.re[best], sp.im[best]);
    }
    return discriminant(sp.re, sp.im, sp.count, sp.level, r->divergence, &r->mu_c);
}

/* pair_function for the root finder: its failure in r->status */
static int pair_value(double omega, void *data, double *value)
{
    root_args *r = data;
    *value = pair_function(omega, r);
    return r->status;
}

typedef struct edge {
    double omega, freq;
    int opens; /* 1: stable below, unstable above */
} edge;

typedef struct search {
    const windows_source *src;
    const whirl_windows_params *p;
    edge *edges;
    size_t nedges, cap;
} search;

static int add_edge(search *s, double omega, double freq, int opens)
{
    if (s->nedges == s->cap) {
        const size_t cap = s->cap ? 2 * s->cap : 16;
        edge *e = realloc(s->edges, cap * sizeof *e);
        if (e == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        s->edges = e;
        s->cap = cap;
    }
    s->edges[s->nedges++] = (edge){omega, freq, opens};
    return GSL_SUCCESS;
}

static int explore(search *s, point *a, point *b, int depth);

/* The edge between a and b (one neutral, the other unstable) by Brent's method on D of the pair
 * that is complex at the unstable end. Another pair may change the stability first (windows of
 * two pairs that overlap): full solves at 100 tol on either side of the root confirm a change of
 * the stability there (then it is an edge), and the intervals beyond them are explored again. */
static int locate(search *s, point *a, point *b, int depth)
{
    const point *un = a->unstable ? a : b;
    root_args r = {s->src, s->p, un->mu_c, 0, 0, 0};
    r.divergence = un->mu_c_im == 0 && un->mu_c > 0;
    double lo = a->omega, hi = b->omega;
    int status = GSL_SUCCESS;
    /* D at the ends must have the signs of their stability (else several pairs act at once) */
    const double f_lo = pair_function(lo, &r);
    r.mu_c = un->mu_c;
    const double f_hi = pair_function(hi, &r);
    if (r.status) return r.status;
    int bracketed = 0;
    if ((f_lo > 0) == !a->unstable && (f_hi > 0) == !b->unstable) {
        /* Brent's last bracket is taken after 200 iterations as it is */
        const whirl_root_opts o = {s->p->tol, 0, 200, 1, f_lo, f_hi};
        whirl_root root;
        status = whirl_root_brent(pair_value, &r, lo, hi, &o, &root);
        if (r.status) return r.status;
        if (status == GSL_ENOMEM) return status;
        bracketed = root.bracketed;
        if (bracketed && status && status != GSL_EMAXITER)
            return whirl_fail(status, "mode %d: the window edge between omega = " WHIRL_Q_RATE
                              "%.10g and omega = " WHIRL_Q_RATE "%.10g was not located",
                              s->src->mode, a->omega, b->omega);
        if (bracketed) lo = root.lower, hi = root.upper;
        status = GSL_SUCCESS;
    }
    if (!bracketed) { /* the discriminant does not bracket (several pairs): bisect on the
                       * stability */
        point mid = {0};
        while (hi - lo > s->p->tol) {
            const double m = (lo + hi) / 2;
            status = evaluate(s->src, m, 0, &mid);
            if (status) return status;
            if (mid.unstable == a->unstable)
                lo = m;
            else
                hi = m;
            r.mu_c = mid.unstable ? mid.mu_c : r.mu_c;
        }
    }
    const double omega = (lo + hi) / 2, freq = r.divergence ? 0 : sqrt(fmax(0, -r.mu_c));
    const double d = 100 * s->p->tol;
    if (omega - d <= a->omega || omega + d >= b->omega) /* too close to check: trust the pair */
        return add_edge(s, omega, freq, !a->unstable);
    point left = {0}, right = {0};
    status = evaluate(s->src, omega - d, 1, &left);
    if (!status) status = evaluate(s->src, omega + d, 1, &right);
    if (!status && left.unstable != right.unstable)
        status = add_edge(s, omega, freq, !left.unstable);
    if (!status) status = explore(s, a, &left, depth + 1);
    if (!status) status = explore(s, &right, b, depth + 1);
    point_free(&left);
    point_free(&right);
    return status;
}

/* Windows between the evaluated points a < b (see the header comment). */
static int explore(search *s, point *a, point *b, int depth)
{
    if (a->unstable != b->unstable) return locate(s, a, b, depth);
    /* two unstable rates: one window if the same pair (by its frequency) grows fastest at both */
    const double fa = sqrt(fmax(0, -a->mu_c)), fb = sqrt(fmax(0, -b->mu_c));
    const int other_pair = a->unstable && fabs(fa - fb) > b->omega - a->omega + 0.05;
    if (same_ranks(a, b) && !other_pair) return GSL_SUCCESS;
    const double width = b->omega - a->omega;
    if (a->unstable && width < s->p->scan_step / 16) return GSL_SUCCESS;
    if (!a->unstable && width < s->p->tol) {
        s->src->stats->unresolved++;
        return GSL_SUCCESS;
    }
    if (depth > 64) return GSL_SUCCESS;
    point mid = {0};
    const double m = (a->omega + b->omega) / 2;
    int status = evaluate(s->src, m, 1, &mid);
    if (!status) status = explore(s, a, &mid, depth + 1);
    if (!status) status = explore(s, &mid, b, depth + 1);
    point_free(&mid);
    return status;
}

/* Opposite signatures that approach without crossing (the bubble of a window between two scan
 * points that leaves the ranks as they were): where the discriminant of a neutral mode with E < 0
 * and its nearest neighbour with E > 0 (pts[j].gap[idx]) is smallest among the scan points around,
 * Brent's minimisation of that pair's D between the neighbours; a negative D is an unstable rate,
 * evaluated in full into *found (*hit = 1). */
static int approach(search *s, const point *pts, size_t npts, size_t j, size_t idx, point *found,
                    int *hit)
{
    *hit = 0;
    const point *c = &pts[j];
    const point *l = j > 0 && !pts[j - 1].unstable && same_ranks(&pts[j - 1], c) ? &pts[j - 1]
                                                                                  : NULL;
    const point *r = j + 1 < npts && !pts[j + 1].unstable && same_ranks(&pts[j + 1], c)
                         ? &pts[j + 1]
                         : NULL;
    const double g = c->gap[idx];
    if (isnan(g) || (!l && !r)) return GSL_SUCCESS;
    if ((l && !(g < l->gap[idx])) || (r && !(g < r->gap[idx]))) return GSL_SUCCESS;
    root_args ra = {s->src, s->p, c->gap_mu[idx], 0, 0, 0};
    gsl_function fn = {pair_function, &ra};
    double x = c->omega, fx = g, lo, flo, hi, fhi;
    if (l && r) {
        lo = l->omega, flo = l->gap[idx], hi = r->omega, fhi = r->gap[idx];
    } else { /* at an end of the scan or beside a change of the ranks: the interval's middle */
        const point *o = l ? l : r;
        lo = fmin(c->omega, o->omega), hi = fmax(c->omega, o->omega);
        flo = l ? l->gap[idx] : g, fhi = l ? g : r->gap[idx];
        x = (lo + hi) / 2;
        fx = pair_function(x, &ra);
        if (ra.status) return ra.status;
        if (!(fx < flo && fx < fhi)) return GSL_SUCCESS;
    }
    if (fx < 0) {
        *hit = 1;
        return evaluate(s->src, x, 1, found);
    }
    gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    if (m == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = gsl_min_fminimizer_set_with_values(m, &fn, x, fx, lo, flo, hi, fhi);
    for (int iter = 0; iter < 60 && status == GSL_SUCCESS && !ra.status; iter++) {
        status = gsl_min_fminimizer_iterate(m);
        if (status || ra.status) break;
        if (gsl_min_fminimizer_f_minimum(m) < 0) {
            *hit = 1;
            break;
        }
        /* Brent's minimisation shrinks the interval to about sqrt(eps) |x| at best (a finer
         * tol ran all 60 iterations); there D is within O(D'' 1e-12) of its least value */
        if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m),
                                  fmax(s->p->tol, 1e-6), 0) == GSL_SUCCESS)
            break;
    }
    x = gsl_min_fminimizer_x_minimum(m);
    gsl_min_fminimizer_free(m);
    if (ra.status) return ra.status;
    /* GSL's Brent may stop on a flat D (GSL_FAILURE): no window there */
    if (*hit) return evaluate(s->src, x, 1, found);
    return GSL_SUCCESS;
}

static int compare_points(const void *x, const void *y)
{
    const point *a = x, *b = y;
    return (a->omega > b->omega) - (a->omega < b->omega);
}

whirl_windows_params whirl_windows_defaults(void)
{
    whirl_windows_params p = {0};
    p.omega_min = 1;
    p.omega_max = 10;
    p.scan_step = 0.25;
    p.tol = 1e-9;
    p.krylov = 1;
    return p;
}

static int compare_edges(const void *x, const void *y)
{
    const edge *a = x, *b = y;
    return (a->omega > b->omega) - (a->omega < b->omega);
}

#define SAMPLES 8 /* full solves across a window before the maximum is refined */
#define WINDOWS_SCAN_MAX 100000 /* scan points of one mode (each a full eigen-solve) */

/* The largest growth in the window win (growth 0 at its edges; at an open end the growth of the
 * scan point there, end_from / end_to): SAMPLES full solves across it (the window may be the
 * union of several pairs' windows), then Brent's minimisation of -growth of the pair that grows
 * fastest at the best sample, between its neighbours, and a full solve at the result. */
static int largest_growth(search *s, const point *end_from, const point *end_to,
                          whirl_window *win)
{
    double x[SAMPLES + 2], f[SAMPLES + 2], mu[SAMPLES + 2];
    x[0] = win->from, f[0] = win->open_from ? -end_from->growth : 0, mu[0] = end_from->mu_c;
    x[SAMPLES + 1] = win->to, f[SAMPLES + 1] = win->open_to ? -end_to->growth : 0;
    mu[SAMPLES + 1] = end_to->mu_c;
    size_t best = 0;
    for (size_t i = 1; i <= SAMPLES + 1; i++) {
        if (i <= SAMPLES) {
            point pt = {0};
            x[i] = win->from + (win->to - win->from) * ((double)i - 0.5) / SAMPLES;
            int status = evaluate(s->src, x[i], 0, &pt);
            if (status) return status;
            f[i] = -pt.growth, mu[i] = pt.mu_c;
        }
        if (f[i] < f[best]) best = i;
    }
    win->max_growth = -f[best];
    win->at = x[best];
    if (!(f[best] < 0))
        return whirl_fail(GSL_EFAILED, "mode %d: no growth inside the window (%.10g, %.10g)",
                          s->src->mode, win->from, win->to);
    if (best == 0 || best == SAMPLES + 1) return GSL_SUCCESS; /* at an end of the range */
    root_args r = {s->src, s->p, mu[best], 0, 0, -1};
    gsl_function fn = {pair_function, &r};
    gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    if (m == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = gsl_min_fminimizer_set_with_values(m, &fn, x[best], f[best], x[best - 1],
                                                    f[best - 1], x[best + 1], f[best + 1]);
    for (int iter = 0; iter < 100 && status == GSL_SUCCESS && !r.status; iter++) {
        status = gsl_min_fminimizer_iterate(m);
        if (status || r.status) break;
        /* the maximum is flat: its place is known to about sqrt(eps) relative at best */
        if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m),
                                  1e-6, 0) == GSL_SUCCESS)
            break;
    }
    const double at = gsl_min_fminimizer_x_minimum(m);
    gsl_min_fminimizer_free(m);
    if (r.status) return r.status;
    if (status)
        return whirl_fail(status, "mode %d: the largest growth in (%.10g, %.10g) was not found",
                          s->src->mode, win->from, win->to);
    /* a full solve there: the largest growth of all pairs */
    point check = {0};
    status = evaluate(s->src, at, 0, &check);
    if (!status && check.growth > win->max_growth) win->max_growth = check.growth, win->at = at;
    return status;
}

int whirl_windows_range(const whirl_windows_params *p, int mode, double birth, double **omega,
                        size_t *npts)
{
    *omega = NULL;
    *npts = 0;
    if (!(p->omega_min > 0 && p->omega_max > p->omega_min && isfinite(p->omega_max)))
        return whirl_fail(GSL_EINVAL, "the range of rates must have 0 < omega_min < omega_max, got "
                          "omega_min = " WHIRL_Q_RATE "%g, omega_max = " WHIRL_Q_RATE "%g",
                          p->omega_min, p->omega_max);
    if (!(p->scan_step > 0) || !(p->tol > 0) || !(p->tol < p->scan_step))
        return whirl_fail(GSL_EINVAL, "the scan step and the tolerance must be > 0 (tol < step), "
                                      "got %g, %g", p->scan_step, p->tol);
    const double from = fmax(p->omega_min, birth * (1 + 1e-6));
    if (!(from < p->omega_max))
        return whirl_fail(GSL_EDOM, "mode %d exists only above omega_%d = " WHIRL_Q_RATE "%.10g, "
                          "beyond the range's end, omega = " WHIRL_Q_RATE "%.10g", mode, mode,
                          birth, p->omega_max);
    const double scan_steps = ceil((p->omega_max - from) / p->scan_step - 1e-9);
    if (!(scan_steps + 1 <= WINDOWS_SCAN_MAX))
        return whirl_fail(GSL_EINVAL, "mode %d: a scan from omega = " WHIRL_Q_RATE "%.10g to omega "
                          "= " WHIRL_Q_RATE "%.10g in steps of delta omega = " WHIRL_Q_RATE "%.10g "
                          "has %.3g points, more than %d: raise the scan step or narrow the range",
                          mode, from, p->omega_max, p->scan_step, scan_steps + 1, WINDOWS_SCAN_MAX);
    const size_t steps = (size_t)scan_steps, n = steps + 1;
    double *om = malloc(n * sizeof *om);
    if (om == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t j = 0; j < n; j++) om[j] = j == steps ? p->omega_max : from + (double)j * p->scan_step;
    *omega = om;
    *npts = n;
    return GSL_SUCCESS;
}

int whirl_windows_search(const windows_source *src, const whirl_windows_params *p,
                         const double *omega, size_t npts, whirl_window *windows, size_t max,
                         size_t *count)
{
    const int mode = src->mode;
    whirl_windows_stats *stats = src->stats;
    const double from = omega[0];
    stats->omega_from = from;
    stats->omega_to = p->omega_max;
    *count = 0;
    point *pts = calloc(npts, sizeof *pts);
    search s = {src, p, NULL, 0, 0};
    int status = pts ? GSL_SUCCESS : whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t j = 0; j < npts && !status; j++) {
        status = evaluate(src, omega[j], 1, &pts[j]);
        stats->scan++;
    }
    /* unstable rates between scan points from approaching pairs, merged into the scan */
    size_t nall = npts;
    for (size_t j = 0; j < npts && !status; j++)
        for (size_t idx = 0; !pts[j].unstable && idx < 2 * pts[j].nrank && !status; idx++) {
            point found = {0};
            int hit;
            status = approach(&s, pts, npts, j, idx, &found, &hit);
            if (!status && hit && found.unstable) {
                point *more = realloc(pts, (nall + 1) * sizeof *pts);
                if (more == NULL) {
                    point_free(&found);
                    status = whirl_fail(GSL_ENOMEM, "out of memory");
                    break;
                }
                pts = more;
                pts[nall++] = found;
                stats->approaches++;
            } else {
                point_free(&found);
            }
        }
    if (!status) qsort(pts, nall, sizeof *pts, compare_points);
    for (size_t j = 0; j + 1 < nall && !status; j++)
        status = explore(&s, &pts[j], &pts[j + 1], 0);
    if (!status && s.nedges > 0) qsort(s.edges, s.nedges, sizeof *s.edges, compare_edges);
    /* windows from the edges, the largest growth in each */
    int inside = pts && pts[0].unstable;
    whirl_window cur = {0};
    if (inside) cur.from = from, cur.open_from = 1;
    for (size_t e = 0; e <= s.nedges && !status; e++) {
        const int last = e == s.nedges;
        if (last && !inside) break;
        if (!last && s.edges[e].opens == inside)
            status = whirl_fail(GSL_EFAILED, "mode %d: the window edges do not alternate at omega "
                                "= " WHIRL_Q_RATE "%.10g", mode, s.edges[e].omega);
        if (status) break;
        if (!last && !inside) {
            cur = (whirl_window){0};
            cur.from = s.edges[e].omega;
            cur.freq_from = s.edges[e].freq;
            inside = 1;
            continue;
        }
        cur.to = last ? p->omega_max : s.edges[e].omega;
        cur.open_to = last;
        cur.freq_to = last ? 0 : s.edges[e].freq;
        status = largest_growth(&s, &pts[0], &pts[nall - 1], &cur);
        if (status) break;
        if (*count < max) windows[*count] = cur;
        ++*count;
        inside = 0;
    }
    for (size_t j = 0; pts && j < nall; j++) point_free(&pts[j]);
    free(pts);
    free(s.edges);
    if (!status && *count > max)
        return whirl_fail(GSL_EINVAL, "mode %d has %zu windows, room for %zu", mode, *count, max);
    return status;
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
