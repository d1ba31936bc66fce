/* The banded path of the N-link window search (nlink_windows.c's reduced problem A' = -B^-1 K'
 * of the planar shape, its blocks Ma, Mb, Ka, Kb, Gab).
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
 * References: Saad, Numerical Methods for Large Eigenvalue Problems (2011); Mackay 1986;
 * Haynsworth, "Determination of the inertia of a partitioned Hermitian matrix", Linear Algebra
 * Appl. 1 (1968); Golub and Van Loan, Matrix Computations (2013), 4.3 (banded LU) and 8.4 (Sturm
 * sequences). */
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

/* The structured form of the last linearisation in lin (its blocks in w by windows_split_blocks) of the
 * chain c at omega: alpha, beta, gamma from the nodes and the lengths, T_j l_j from the diagonal
 * of Kb (Kb_jj + omega^2 Mb_jj). 1 if it reproduces the five dense blocks to 1e-11 of their
 * largest entry, else 0 (then the dense path is used); -1 (WHIRL_EINTERRUPTED set) on a stop
 * request, read every row of the O(N^2) comparison. */
int windows_structure_of(whirl_windows *w, const whirl_chain *c, double omega,
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
lapack_int windows_band_factor(whirl_windows *w, double sigma)
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

int windows_band_apply(void *data, const double *x, double *y) { return band_apply_any(data, 0, x, y); }
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
    while (windows_band_factor(w, sigma) != 0)
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
        if (whirl_windows_arnoldi_step(k, step, band_apply_projected, w, &norm)) return GSL_CONTINUE;
        for (size_t j = 0; j <= step + 1; j++) hmax = fmax(hmax, fabs(h[j + step * (k->km + 1)]));
        const size_t m = step + 1;
        const int whole = m == dim; /* the whole of ker l^T */
        if (!whole && !(norm > 1e-14 * hmax)) return GSL_CONTINUE; /* invariant, maybe not all */
        if (!whole && (m < WINDOWS_BAND_START || (m - WINDOWS_BAND_START) % WINDOWS_BAND_EVERY))
            continue;
        if (whirl_windows_ritz_values(k, m) != 0) return GSL_CONTINUE;
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
            if (!whole && !(whirl_windows_ritz_residual(k, m, i, norm) <= BAND_TOL * mod)) break;
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
    int status = windows_split_blocks(w, lin);
    if (status) return status;
    const int banded = windows_structure_of(w, c, omega, lin);
    if (banded < 0) return WHIRL_EINTERRUPTED;
    if (!banded) return GSL_CONTINUE;
    return band_spectrum(w, signatures, whirl_stability_symmetry(lin), out);
}
