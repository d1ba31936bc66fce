/* The pencil A - s B of the continuous chain's linearisation on the collocation, and its band LU
 * (continuum_stability.c's header comment: the equations and their linearisation)
 * Conditions, in the rows of the equations they replace (the pattern that makes the counts agree
 * with the orders above): at the right end of an element the equation rows of w, of the
 * constraint and of vh carry n0 . xi, t0 . xi and vh continuous with the next element (zero at
 * the pivot), the row of u carries the tangential equation t0 . (E_u, E_w); at the left end of an
 * element after the first the rows of u, w and vh carry the normal derivative n0 . xi', tau and
 * vh' continuous, the constraint is kept; at the free end (m = 0) the row of u carries the normal
 * equation n0 . (E_u, E_w), the row of w tau = 0 (m > 0: the rows of u, w, vh the tip mass's
 * equations). The steady shape is solved by the same collocation (Newton; r continuous at right
 * ends, q at left ends), seeded by the shooting of continuum.c, whose tip radius it reproduces;
 * the elements for the phase are found from the shooting's shape before any Newton iteration,
 * and each further halving is seeded by the shape interpolated from the previous elements.
 * Structure: with the unknowns ordered point by point (u, w, tau, vh at each point) every row
 * couples only the points of its element and, for the continuity rows at an element's left end,
 * those of the previous one, so A is banded with kl = 4 (p + 1) + 3 sub- and ku = 4 p + 3
 * super-diagonals, and B couples only the fields of one point (4 x 4 blocks). The shifted pencil
 * A - s B is factored by the elimination of LAPACK's banded LU (dgbtrf, partial pivoting:
 * O(np p^2) instead of O(np^3)) in its band storage, each row and column only to its last
 * nonzero (band_lu: within an element's rows about half of the band stays zero), and the steady
 * shape's Newton iteration is banded likewise (2 fields, kl = ku = 2 p + 1). */
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

/* ---- banded LU ---- */

/* LAPACK's dgbtrf on m: the LU factors with partial pivoting in its band storage and pivots
 * (from 1), for dgbtrs and band_solve; 0, or j + 1 if the pivot of column j is zero. The same
 * elimination, unblocked, but each row and column only to its last nonzero (tracked as the fill
 * grows): a row of an element's equations couples only the points of the element (and its
 * neighbours' ends), so that about half of the band stays zero and the updates are some four
 * times fewer than those of the full band. */
int cstab_band_lu(const cstab_band *m)
{
    const size_t n = m->n, kl = m->kl, ku = m->ku, kd = kl + ku, ldab = m->ldab;
    double *restrict a = m->a;
    size_t *bottom = m->lnz, *right = m->unz; /* the last nonzero row of a column, column of a row */
#define A(r, c) a[kd + (r) - (c) + (c) * ldab]
    for (size_t c = 0; c < n; c++) {
        size_t r = c + kl < n - 1 ? c + kl : n - 1;
        while (r > c && A(r, c) == 0) r--;
        bottom[c] = r;
    }
    for (size_t r = 0; r < n; r++) {
        size_t c = r + ku < n - 1 ? r + ku : n - 1;
        while (c > r && A(r, c) == 0) c--;
        right[r] = c;
    }
    for (size_t j = 0; j < n; j++) {
        const size_t last = bottom[j] > j ? bottom[j] : j; /* rows j..last of column j */
        size_t p = j;
        double big = fabs(A(j, j));
        for (size_t r = j + 1; r <= last; r++)
            if (fabs(A(r, j)) > big) big = fabs(A(r, j)), p = r;
        m->ipiv[j] = (lapack_int)(p + 1);
        if (big == 0) return (int)j + 1;
        if (p != j) {
            const size_t end = right[j] > right[p] ? right[j] : right[p];
            for (size_t c = j; c <= end; c++) {
                const double t = A(j, c);
                A(j, c) = A(p, c), A(p, c) = t;
                if (t != 0 && bottom[c] < p) bottom[c] = p; /* row j's entries moved down to p */
            }
            const size_t t = right[j];
            right[j] = right[p], right[p] = t;
        }
        const double inv = 1 / A(j, j);
        double *restrict l = &A(j + 1, j);
        for (size_t i = 0; i < last - j; i++) l[i] *= inv;
        for (size_t c = j + 1; c <= right[j]; c++) {
            const double t = A(j, c);
            if (t == 0) continue;
            double *restrict col = &A(j + 1, c);
            for (size_t i = 0; i < last - j; i++) col[i] -= l[i] * t;
            if (bottom[c] < last) bottom[c] = last;
        }
        for (size_t r = j + 1; r <= last; r++)
            if (right[r] < right[j]) right[r] = right[j];
    }
#undef A
    for (size_t col = 0; col < n; col++) { /* the extents of the factors' columns */
        const double *c = a + col * ldab;
        size_t l = kl, u = kd;
        while (l > 0 && c[kd + l] == 0) l--;
        while (u > 0 && c[kd - u] == 0) u--;
        m->lnz[col] = l, m->unz[col] = u;
    }
    return 0;
}

/* b = (P L U)^-1 b with the factors of band_lu: the two triangular solves of LAPACK's dgbtrs for
 * one right-hand side (the row interchanges and the multipliers of each column of L, then U by
 * columns), the same operations in the same order, but each column only to its extent. */
void cstab_band_solve(const cstab_band *m, double *restrict b)
{
    const size_t n = m->n, kl = m->kl, kd = m->kl + m->ku, ldab = m->ldab;
    const double *restrict lu = m->a;
    for (size_t j = 0; j + 1 < n; j++) {
        const size_t l = (size_t)m->ipiv[j] - 1, lm = kl < n - 1 - j ? kl : n - 1 - j;
        if (l != j) {
            const double t = b[l];
            b[l] = b[j], b[j] = t;
        }
        const double bj = b[j], *col = lu + kd + 1 + j * ldab;
        double *out = b + j + 1;
        const size_t end = m->lnz[j] < lm ? m->lnz[j] : lm;
        if (bj != 0)
            for (size_t i = 0; i < end; i++) out[i] -= col[i] * bj;
    }
    for (size_t j = n; j-- > 0;) {
        const double *col = lu + j * ldab; /* col[kd] the diagonal, col[kd - i] row j - i */
        b[j] /= col[kd];
        const double bj = b[j];
        const size_t lim = m->unz[j] < j ? m->unz[j] : j;
        if (bj != 0)
            for (size_t i = 1; i <= lim; i++) b[j - i] -= col[kd - i] * bj;
    }
}

/* ---- the pencil ---- */

/* The interior equation of field eq at point g (element e, local j) into the rows ra, rb
 * (field-major, zero on entry). */
static void equation_row(const whirl_cstab *w, int eq, size_t e, size_t j, double *ra, double *rb)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, g = e * P + j;
    const double om = w->omega, w2 = om * om;
    if (eq == F_TAU) { /* constraint r' u' + z' w' = 0 */
        for (size_t k = 0; k < P; k++) {
            const double d = dmat(w, e, j, k);
            ra[F_U * np + e * P + k] = w->rp[g] * d;
            ra[F_W * np + e * P + k] = w->zp[g] * d;
        }
        return;
    }
    /* (T0 f')' = sum_l D_jl T0_l sum_k D_lk f_k on the element (D = dref / h; the row is zero
     * on entry) */
    const int f = eq;
    const double h = w->brk[e + 1] - w->brk[e], ih2 = 1 / (h * h);
    double *out = ra + f * np + e * P;
    for (size_t l = 0; l < P; l++) {
        const double djl = w->dref[j * P + l] * w->t0[e * P + l], *dl = w->dref + l * P;
        for (size_t k = 0; k < P; k++) out[k] += djl * dl[k];
    }
    for (size_t k = 0; k < P; k++) out[k] *= ih2;
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

/* The points whose columns a row of element e may touch: those of the previous element (the
 * continuity of derivatives at its left end), its own, the first of the next. */
static void window(const whirl_cstab *w, size_t e, size_t *lo, size_t *hi)
{
    const size_t P = (size_t)w->p.degree + 1;
    *lo = e > 0 ? (e - 1) * P : 0;
    *hi = (e + 1) * P < w->np ? (e + 1) * P : w->np - 1;
}

/* Row (f, g) of the pencil from the field-major rows ra, rb (zeroed again over the window of
 * element e) into the band of A (point-major, LAPACK's layout) and the blocks of B. */
static void store_row(whirl_cstab *w, int f, size_t g, size_t e, double *ra, double *rb)
{
    const size_t np = w->np, off = w->kl + w->ku, i = N_FIELDS * g + (size_t)f;
    size_t lo, hi;
    window(w, e, &lo, &hi);
    for (int c = 0; c < N_FIELDS; c++)
        for (size_t h = lo; h <= hi; h++) {
            const size_t k = (size_t)c * np + h, col = N_FIELDS * h + (size_t)c;
            if (ra[k] != 0) w->ab[off + i - col + col * w->ldab] = ra[k];
            if (rb[k] != 0) w->bb[(g * N_FIELDS + (size_t)f) * N_FIELDS + (size_t)c] = rb[k];
            ra[k] = rb[k] = 0;
        }
}

/* The tangential (sign = +1) or normal (-1) combination of the u and w equations at (e, j). */
static void combined_row(whirl_cstab *w, int tangential, size_t e, size_t j, double *ra,
                         double *rb, double *ta, double *tb)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, g = e * P + j;
    const double cu = tangential ? w->rp[g] : -w->zp[g], cw = tangential ? w->zp[g] : w->rp[g];
    equation_row(w, F_U, e, j, ra, rb);
    equation_row(w, F_W, e, j, ta, tb);
    size_t lo, hi;
    window(w, e, &lo, &hi);
    for (int c = 0; c < N_FIELDS; c++)
        for (size_t h = lo; h <= hi; h++) {
            const size_t k = (size_t)c * np + h;
            ra[k] = cu * ra[k] + cw * ta[k];
            rb[k] = cu * rb[k] + cw * tb[k];
            ta[k] = tb[k] = 0;
        }
}

static void assemble(whirl_cstab *w)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, n = N_FIELDS * np;
    const double m = w->p.tip_mass, om = w->omega;
    double *ra = w->ra, *rb = w->rb, *ta = w->ta, *tb = w->tb; /* scratch rows, zero */
    memset(w->ab, 0, w->ldab * n * sizeof(double));
    memset(w->bb, 0, N_FIELDS * N_FIELDS * np * sizeof(double));
    for (size_t e = 0; e < w->ne; e++)
        for (size_t j = 0; j < P; j++) {
            const size_t g = e * P + j;
            for (int f = 0; f < N_FIELDS; f++) {
                if (j == P - 1 && f != F_U) { /* continuity with the next element, or the pivot */
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
                        ra[F_TAU * np + g] = 1;
                    } else {
                        equation_row(w, f, e, j, ra, rb);
                    }
                } else if (j == 0 && e == 0 && f != F_TAU) { /* the tip mass */
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
                store_row(w, f, g, e, ra, rb);
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
        if ((status = cstab_reserve_elements(w, w->ne))) return status;
        for (size_t e = 0; e <= w->ne; e++) w->brk[e] = (double)e / (double)w->ne;
        const size_t np = w->ne * ((size_t)w->p.degree + 1);
        if ((status = cstab_reserve(w, np))) return status;
        w->np = np;
        cstab_set_points(w);
        for (size_t g = 0; g < np; g++) w->r[g] = w->q[g] = 0;
    } else {
        whirl_shape_info info;
        status = whirl_continuum_solve(omega, mode, w->p.tip_mass, tip_r_guess, &info);
        if (!status) status = cstab_solve_shape(w, omega, info.tip_r);
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

/* The pencil's factors of shifted_lu as a band. */
static cstab_band pencil_band(const whirl_cstab *w)
{
    cstab_band m = {w->lu, N_FIELDS * w->np, w->kl, w->ku, w->ldab, w->ipiv, w->lnz, w->unz};
    return m;
}

/* The banded LU factors of R (A - s B) into w->lu (pivots w->ipiv), R the row equilibration
 * (w->row_a): s = shift, or if that is an eigenvalue shift 1.7^k (k < tries). */
int cstab_shifted_lu(whirl_cstab *w, double shift, int tries)
{
    const size_t np = w->np, n = N_FIELDS * np, ldab = w->ldab, off = w->kl + w->ku;
    int info = 1;
    for (int k = 0; k < tries && info != 0; k++) { /* s an eigenvalue: another s */
        w->shift = shift * pow(1.7, k);
        memcpy(w->lu, w->ab, ldab * n * sizeof(double));
        for (size_t g = 0; g < np; g++)
            for (size_t a = 0; a < N_FIELDS; a++)
                for (size_t c = 0; c < N_FIELDS; c++) {
                    const double b = w->bb[(g * N_FIELDS + a) * N_FIELDS + c];
                    const size_t i = N_FIELDS * g + a, col = N_FIELDS * g + c;
                    if (b != 0) w->lu[off + i - col + col * ldab] -= w->shift * b;
                }
        /* rows equilibrated (the rows of the second derivatives on short elements are ~1e8
         * times those of the conditions): the same solutions, less round-off */
        for (size_t i = 0; i < n; i++) w->row_a[i] = 0;
        for (size_t col = 0; col < n; col++) {
            const size_t i0 = col > w->ku ? col - w->ku : 0, i1 = col + w->kl < n ? col + w->kl : n - 1;
            for (size_t i = i0; i <= i1; i++)
                w->row_a[i] = fmax(w->row_a[i], fabs(w->lu[off + i - col + col * ldab]));
        }
        for (size_t i = 0; i < n; i++) w->row_a[i] = w->row_a[i] > 0 ? 1 / w->row_a[i] : 1;
        for (size_t col = 0; col < n; col++) {
            const size_t i0 = col > w->ku ? col - w->ku : 0, i1 = col + w->kl < n ? col + w->kl : n - 1;
            for (size_t i = i0; i <= i1; i++) w->lu[off + i - col + col * ldab] *= w->row_a[i];
        }
        const cstab_band m = pencil_band(w);
        info = cstab_band_lu(&m);
    }
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the shifted pencil is singular (zero pivot in column %d)",
                          info);
    return GSL_SUCCESS;
}

/* b = R B x for x = (u, w, vh) (3 np, field-major), b point-major (4 np). */
void cstab_apply_b(const whirl_cstab *w, const double *x, double *b)
{
    const size_t np = w->np;
    const size_t src[N_FIELDS] = {0, np, 0, 2 * np}; /* where field c of x starts (tau: none) */
    for (size_t g = 0; g < np; g++)
        for (size_t a = 0; a < N_FIELDS; a++) {
            const double *row = w->bb + (g * N_FIELDS + a) * N_FIELDS;
            double sum = 0;
            for (size_t c = 0; c < N_FIELDS; c++)
                if (c != F_TAU && row[c] != 0) sum += row[c] * x[src[c] + g];
            b[N_FIELDS * g + a] = sum * w->row_a[N_FIELDS * g + a];
        }
}

/* y = the (u, w, vh) rows of (A - s B)^-1 B x, x = (u, w, vh) (3 np): one step of the Arnoldi
 * iteration, with the factors of shifted_lu. */
int cstab_apply(void *data, const double *x, double *y)
{
    whirl_cstab *w = data;
    const size_t np = w->np;
    double *b = w->solve;
    cstab_apply_b(w, x, b);
    const cstab_band m = pencil_band(w);
    cstab_band_solve(&m, b);
    for (size_t g = 0; g < np; g++) {
        y[g] = b[N_FIELDS * g + F_U];
        y[np + g] = b[N_FIELDS * g + F_W];
        y[2 * np + g] = b[N_FIELDS * g + F_V];
    }
    return GSL_SUCCESS;
}
