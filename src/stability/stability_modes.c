/* The modes of the linearisation: right eigenvectors of the first-order form
 * y' = A y, A = [[0, I], [-M^-1 K, -M^-1 (G + C)]] (stability.c), y = (q, q').
 * A right eigenvector (v, lambda v) of A gives the link-angle mode v; the node displacements are
 * dx_i = sum_{j<=i} l_j (a_j e1_j + b_j e2_j) (the chart of stability.h to first order).
 * Krein signature. Without dissipation (C = 0) and with K symmetric (no air drag: the pivot,
 * driven or not, is fixed in the co-rotating frame) the linearisation conserves the quadratic
 * form H = 1/2 q'^T M q' + 1/2 q^T K q, the second variation of the Jacobi integral (kinetic
 * energy relative to the frame plus the amended potential; the gyroscopic forces G q' do no
 * work: q'^T G q' = 0). On the mode q = Re(v e^{i w t}) its time average is
 * E = 1/4 (w^2 v^* M v + v^* K v), real because M and K are symmetric, and
 * v^* (-w^2 M + i w G + K) v = 0 gives E = w/4 v^* (2 w M - i G) v = w/4 v^* L'(i w) v / i,
 * L(lambda) = lambda^2 M + lambda G + K: its sign is the Krein signature (MacKay 1986; Kirillov
 * 2013, ch. 2), the same for the pair +-w. Two neutral modes of opposite signature can collide
 * and leave the imaginary axis (a window), two of the same cannot. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/linalg.h"
#include "stability/stability_internal.h"

/* A mode is neutral when |Re lambda| <= NEUTRAL_LEVEL max |lambda| (the rule of
 * whirl_stability_growth: round-off of the eigen-solve relative to the largest eigenvalue) */
#define NEUTRAL_LEVEL 1e-10

whirl_stability_modes *whirl_stability_modes_alloc(size_t n)
{
    if (n == 0) {
        whirl_fail(GSL_EINVAL, "a chain needs at least one link");
        return NULL;
    }
    whirl_stability_modes *m = calloc(1, sizeof *m);
    const size_t y = 4 * n, q = 2 * n, nodes = 3 * (n + 1);
    if (m != NULL) {
        m->links = n;
        m->re = calloc(y * (2 + 2 * q + 2 * nodes), sizeof(double));
        m->krein = calloc(y, sizeof *m->krein);
    }
    if (m == NULL || m->re == NULL || m->krein == NULL) {
        whirl_stability_modes_free(m);
        whirl_fail(GSL_ENOMEM, "out of memory for the modes of %zu links", n);
        return NULL;
    }
    m->im = m->re + y;
    m->angle_re = m->im + y;
    m->angle_im = m->angle_re + y * q;
    m->node_re = m->angle_im + y * q;
    m->node_im = m->node_re + y * nodes;
    return m;
}

void whirl_stability_modes_free(whirl_stability_modes *m)
{
    if (m == NULL) return;
    free(m->re);
    free(m->krein);
    free(m);
}

/* v^* S v for symmetric S (row-major q x q) and v = vr + i vi */
static double hermitian_form(size_t q, const double *s, const double *vr, const double *vi)
{
    double sum = 0;
    for (size_t i = 0; i < q; i++)
        for (size_t j = 0; j < q; j++)
            sum += s[i * q + j] * (vr[i] * vr[j] + vi[i] * vi[j]);
    return sum;
}

/* 1 if C = 0 and K is symmetric to round-off (1e-12 of max |K|: the entries are sums of a few
 * products of order max |K|) */
static int conservative(size_t q, const double *c, const double *k)
{
    double kmax = 0, asym = 0;
    for (size_t i = 0; i < q * q; i++) {
        if (c[i] != 0) return 0;
        kmax = fmax(kmax, fabs(k[i]));
    }
    for (size_t i = 0; i < q; i++)
        for (size_t j = 0; j < i; j++) asym = fmax(asym, fabs(k[i * q + j] - k[j * q + i]));
    return asym <= 1e-12 * kmax;
}

int whirl_stability_eigenvectors(whirl_stability *w, whirl_stability_modes *out)
{
    const size_t n = stability_links(w), q = 2 * n, y = 4 * n, nn = 3 * (n + 1);
    if (out == NULL || out->links != n)
        return whirl_fail(GSL_EINVAL, "the modes' storage is not for %zu links", n);
    size_t count;
    const double *lre, *lim;
    int status = whirl_stability_eigenvalues(w, &count, &lre, &lim);
    if (status) return status;
    const double *mat[4];
    for (int k = 0; k < 4; k++)
        if ((mat[k] = whirl_stability_get_matrix(w, (whirl_stability_matrix)k)) == NULL)
            return whirl_fail(GSL_EINVAL, "no linearisation for the modes");
    const double *nx, *ny, *nz;
    whirl_stability_nodes(w, &nx, &ny, &nz);

    double *buf = malloc((y * y + q * q + 2 * q * q + 2 * y + y * y + 9 * n + n) *
                         sizeof(double));
    char *used = calloc(y, 1);
    if (buf == NULL || used == NULL) {
        free(buf);
        free(used);
        return whirl_fail(GSL_ENOMEM, "out of memory for the modes of %zu links", n);
    }
    double *a = buf, *f = a + y * y, *r = f + q * q, *wr = r + 2 * q * q, *wi = wr + y;
    double *vr = wi + y, *chart = vr + y * y, *len = chart + 9 * n;
    status = stability_first_order(n, mat, a, 1, y, f, r); /* column-major */
    lapack_int info = 0;
    if (!status) {
        /* workspace query, then the solve */
        double query = 0;
        info = whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)y, a, (lapack_int)y,
                                   wr, wi, NULL, 1, vr, (lapack_int)y, &query, -1);
        const lapack_int lwork = (lapack_int)query;
        double *work = info == 0 ? malloc((size_t)(lwork > 1 ? lwork : 1) * sizeof *work) : NULL;
        if (info == 0 && work == NULL)
            status = whirl_fail(GSL_ENOMEM, "out of memory for the modes of %zu links", n);
        else if (info == 0)
            info = whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)y, a,
                                       (lapack_int)y, wr, wi, NULL, 1, vr, (lapack_int)y, work,
                                       lwork);
        free(work);
        if (!status && info != 0)
            status = whirl_fail(GSL_EFAILED, "the eigenvector iteration failed (dgeev info %d)",
                                (int)info);
    }
    /* the chart and length of each link, from the linearised nodes */
    for (size_t j = 0; j < n && !status; j++) {
        double u[3] = {nx[j + 1] - nx[j], ny[j + 1] - ny[j], nz[j + 1] - nz[j]};
        len[j] = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int k = 0; k < 3; k++) u[k] /= len[j];
        memcpy(chart + 9 * j, u, sizeof u);
        stability_link_chart(u, chart + 9 * j + 3, chart + 9 * j + 6);
    }
    double lmax = 0;
    for (size_t k = 0; k < count; k++) lmax = fmax(lmax, hypot(lre[k], lim[k]));
    const int cons = !status && conservative(q, mat[WHIRL_STABILITY_DAMPING],
                                             mat[WHIRL_STABILITY_STIFFNESS]);
    out->count = status ? 0 : count;
    for (size_t k = 0; k < count && !status; k++) {
        /* the nearest unused eigenvalue of the full form (a conjugate pair: dgeev stores
           columns p (real part) and p + 1 (imaginary part) for the one with wi > 0) */
        size_t best = y;
        double dist = INFINITY;
        for (size_t p = 0; p < y; p++) {
            const double d = hypot(wr[p] - lre[k], wi[p] - lim[k]);
            if (!used[p] && d < dist) {
                dist = d;
                best = p;
            }
        }
        used[best] = 1;
        const double *col_re, *col_im = NULL;
        double sign = 1;
        if (wi[best] == 0) {
            col_re = vr + best * y;
        } else if (wi[best] > 0) {
            col_re = vr + best * y;
            col_im = vr + (best + 1) * y;
        } else {
            col_re = vr + (best - 1) * y;
            col_im = vr + best * y;
            sign = -1;
        }
        double *ar = out->angle_re + k * q, *ai = out->angle_im + k * q;
        for (size_t i = 0; i < q; i++) {
            ar[i] = col_re[i];
            ai[i] = col_im ? sign * col_im[i] : 0;
        }
        double *dr = out->node_re + k * nn, *di = out->node_im + k * nn;
        double big = 0, cr = 1, ci = 0;
        memset(dr, 0, 3 * sizeof *dr);
        memset(di, 0, 3 * sizeof *di);
        for (size_t j = 0; j < n; j++) {
            const double *e1 = chart + 9 * j + 3, *e2 = chart + 9 * j + 6;
            for (int c = 0; c < 3; c++) {
                const size_t at = 3 * (j + 1) + (size_t)c;
                dr[at] = dr[at - 3] + len[j] * (ar[j] * e1[c] + ar[n + j] * e2[c]);
                di[at] = di[at - 3] + len[j] * (ai[j] * e1[c] + ai[n + j] * e2[c]);
            }
            const size_t at = 3 * (j + 1);
            double size = 0;
            for (int c = 0; c < 3; c++)
                size += dr[at + c] * dr[at + c] + di[at + c] * di[at + c];
            if (sqrt(size) > big) {
                big = sqrt(size);
                double cm = -1;
                for (int c = 0; c < 3; c++) {
                    const double mod = hypot(dr[at + c], di[at + c]);
                    if (mod > cm) {
                        cm = mod;
                        cr = dr[at + c];
                        ci = di[at + c];
                    }
                }
            }
        }
        /* scale by conj(z) / (|z| big), z the largest component of the largest node */
        const double mod = hypot(cr, ci);
        if (!(big > 0) || !(mod > 0)) {
            status = whirl_fail(GSL_EFAILED, "mode %zu moves no node", k);
            break;
        }
        const double sr = cr / (mod * big), si = -ci / (mod * big);
        for (size_t i = 0; i < q; i++) {
            const double re = ar[i] * sr - ai[i] * si, im = ar[i] * si + ai[i] * sr;
            ar[i] = re;
            ai[i] = im;
        }
        for (size_t i = 0; i < nn; i++) {
            const double re = dr[i] * sr - di[i] * si, im = dr[i] * si + di[i] * sr;
            dr[i] = re;
            di[i] = im;
        }
        out->re[k] = lre[k];
        out->im[k] = lim[k];
        out->krein[k] = 0;
        if (cons && lim[k] != 0 && fabs(lre[k]) <= NEUTRAL_LEVEL * lmax) {
            const double energy = lim[k] * lim[k] *
                                      hermitian_form(q, mat[WHIRL_STABILITY_MASS], ar, ai) +
                                  hermitian_form(q, mat[WHIRL_STABILITY_STIFFNESS], ar, ai);
            out->krein[k] = energy > 0 ? 1 : (energy < 0 ? -1 : 0);
        }
    }
    if (status) out->count = 0;
    free(buf);
    free(used);
    return status;
}
