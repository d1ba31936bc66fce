/* Steady shapes (relative equilibria) of the N-link chain rotating at omega about the vertical.
 *
 * Masses m_i at (r_i, z_i), i = 1..N, on links of lengths l_i from mass i-1 to mass i; mass 0
 * is the pivot. In the frame co-rotating at omega a mass feels gravity (0, -m_i g) and the
 * centrifugal force (m_i omega^2 r_i, 0). The part below link i is in equilibrium when link i
 * carries the resultant of those forces,
 *     H_i = sum_{j >= i} m_j omega^2 r_j,  V_i = g sum_{j >= i} m_j,  T_i = |(H_i, V_i)|,
 * and points along it: r_{i-1} = r_i - l_i H_i / T_i, z_{i-1} = z_i + l_i V_i / T_i.
 * Given the tip radius a = r_N this recursion up from the tip fixes the whole chain; the shape is
 * an equilibrium when the pivot lands on the axis, r_0(a) = 0 (shooting, steady_shoot.c).
 * Every mass's force balance then holds by construction to round-off.
 *
 * Linear critical rates: the small horizontal displacements x_i of the hanging chain satisfy
 *     m_i omega^2 x_i = K x, K_ii = T_i/l_i + T_{i+1}/l_{i+1}, K_{i,i+1} = -T_{i+1}/l_{i+1},
 * with the static tensions T_i = V_i (T_{N+1} = 0): omega^2 are the eigenvalues of the
 * symmetric tridiagonal M^{-1/2} K M^{-1/2}, computed by LAPACK's bisection dstebz (Kahan 1966;
 * Demmel & Kahan 1990) to high relative accuracy. They tend to j_{0,k}/2 with error O(1/N). */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <lapacke.h>

#include "error.h"
#include "steady_internal.h"

/* The scan for a fresh solve: a coarse chain at a high rate (e.g. N = 100 at omega = 30) has
 * several equilibria with k - 1 crossings (its crossing count is not monotone in the tip
 * radius); a fresh solve returns the one with the smallest tip radius, which near omega_k is the
 * branch born there. Continuation (a seed) stays on the seed's branch. */
#define SCAN_RATIO 1.1

typedef struct nlink_ws {
    const whirl_chain *c;
    double omega;
    double *r, *z, *tension; /* c->n + 1 each */
} nlink_ws;

static void *nlink_ws_alloc(const void *params)
{
    const whirl_chain *c = params;
    nlink_ws *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->c = c;
    w->r = malloc(3 * (c->n + 1) * sizeof *w->r);
    if (w->r == NULL) goto fail;
    w->z = w->r + (c->n + 1);
    w->tension = w->z + (c->n + 1);
    return w;
fail:
    free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for a chain of %zu links", c->n);
    return NULL;
}

static void nlink_ws_free(void *ws)
{
    nlink_ws *w = ws;
    if (w == NULL) return;
    free(w->r);
    free(w);
}

/* The recursion up from the tip; z relative to the pivot. */
static void nlink_recurse(const whirl_chain *c, double omega, double tip_r, double *r, double *z,
                          double *tension)
{
    size_t n = c->n;
    double h = 0, v = 0;
    r[n] = tip_r;
    z[n] = 0;
    for (size_t i = n; i >= 1; i--) {
        h += c->mass[i - 1] * omega * omega * r[i];
        v += c->mass[i - 1] * c->gravity;
        double t = hypot(h, v);
        tension[i] = t;
        r[i - 1] = r[i] - c->length[i - 1] * h / t;
        z[i - 1] = z[i] + c->length[i - 1] * v / t;
    }
    tension[0] = tension[1];
    double z_pivot = z[0];
    for (size_t i = 0; i <= n; i++) z[i] -= z_pivot;
}

/* Sign changes of r[n], r[n-1], ..., r[1], from the tip (r > 0) up to below the pivot. */
static int nlink_sign_changes(const double *r, size_t n)
{
    int count = 0, sign = 1;
    for (size_t k = 0; k < n; k++) {
        int s = (r[n - k] > 0) - (r[n - k] < 0);
        if (s != 0 && s != sign) count++, sign = s;
    }
    return count;
}

static int nlink_shot(void *ws, double a, double *residual, int *crossings)
{
    nlink_ws *w = ws;
    nlink_recurse(w->c, w->omega, a, w->r, w->z, w->tension);
    *residual = w->r[0] / a;
    *crossings = nlink_sign_changes(w->r, w->c->n);
    return GSL_SUCCESS;
}

static int check_chain(const whirl_chain *c)
{
    if (c == NULL || c->n < 1) return whirl_fail(GSL_EINVAL, "a chain needs at least one link");
    return GSL_SUCCESS;
}

int whirl_nlink_critical(const whirl_chain *c, size_t nmodes, double *omega)
{
    int status = check_chain(c);
    if (status != GSL_SUCCESS) return status;
    size_t n = c->n;
    if (nmodes < 1 || nmodes > n)
        return whirl_fail(GSL_EINVAL, "a chain of %zu links has modes 1..%zu, asked for %zu", n,
                          n, nmodes);
    double *work = malloc((2 * n + nmodes) * sizeof *work);
    lapack_int *iblock = malloc(2 * n * sizeof *iblock);
    if (work == NULL || iblock == NULL) {
        free(work);
        free(iblock);
        return whirl_fail(GSL_ENOMEM, "out of memory for %zu critical rates", n);
    }
    double *d = work, *e = work + n, *lambda = work + 2 * n;
    lapack_int *isplit = iblock + n;
    /* d_i = K_ii / m_i, e_i = K_{i,i+1} / sqrt(m_i m_{i+1}), with the static tensions V_i */
    double v_below = 0;
    for (size_t i = n; i >= 1; i--) {
        double stiff_below = i < n ? v_below / c->length[i] : 0;
        v_below += c->mass[i - 1] * c->gravity;
        d[i - 1] = (v_below / c->length[i - 1] + stiff_below) / c->mass[i - 1];
        if (i < n) e[i - 1] = -stiff_below / sqrt(c->mass[i - 1] * c->mass[i]);
    }
    lapack_int found = 0, nsplit = 0;
    lapack_int info = LAPACKE_dstebz('I', 'E', (lapack_int)n, 0, 0, 1, (lapack_int)nmodes,
                                     2 * DBL_MIN, d, e, &found, &nsplit, lambda, iblock, isplit);
    if (info != 0 || found != (lapack_int)nmodes) {
        status = whirl_fail(GSL_EFAILED, "tridiagonal eigensolver (dstebz) failed: info %d",
                            (int)info);
    } else {
        for (size_t k = 0; k < nmodes; k++) omega[k] = sqrt(lambda[k]);
    }
    free(work);
    free(iblock);
    return status;
}

int whirl_nlink_positions(const whirl_chain *c, double omega, double tip_r, double *r, double *z,
                          double *tension)
{
    int status = check_chain(c);
    if (status != GSL_SUCCESS) return status;
    if (!(isfinite(omega) && omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be > 0 and finite, got %g", omega);
    if (!(isfinite(tip_r) && tip_r >= 0))
        return whirl_fail(GSL_EINVAL, "tip radius must be >= 0 and finite, got %g", tip_r);
    nlink_recurse(c, omega, tip_r, r, z, tension);
    return whirl_steady_check_samples(omega, c->n + 1, r, z, tension);
}

/* The summary of the shape in w (positions of the solution). */
static void nlink_info(const nlink_ws *w, double omega, int mode, whirl_shape_info *info)
{
    const whirl_chain *c = w->c;
    size_t n = c->n;
    info->omega = omega;
    info->mode = mode;
    info->tip_r = w->r[n];
    info->top_tension = w->tension[1];
    info->depth = -w->z[n];
    info->max_r = 0;
    info->n_nodes = 0;
    double s = 0; /* arclength of mass i-1 from the pivot */
    for (size_t i = 1; i <= n; i++) {
        info->max_r = fmax(info->max_r, fabs(w->r[i]));
        /* a crossing on link i (below the pivot: the pivot itself is not counted) */
        if (i >= 2 && ((w->r[i - 1] > 0 && w->r[i] <= 0) || (w->r[i - 1] < 0 && w->r[i] >= 0)) &&
            info->n_nodes < WHIRL_MODE_MAX)
            info->node_s[info->n_nodes++] =
                s + c->length[i - 1] * w->r[i - 1] / (w->r[i - 1] - w->r[i]);
        s += c->length[i - 1];
    }
}

static int nlink_solve_ws(void *ws, double omega, int mode, double tip_r_guess,
                          whirl_shape_info *info)
{
    nlink_ws *w = ws;
    const whirl_chain *c = w->c;
    int status = whirl_steady_check_args(omega, mode);
    if (status != GSL_SUCCESS) return status;
    w->omega = omega;
    double a = 0;
    if ((size_t)mode <= c->n)
        status = whirl_steady_shoot_root(nlink_shot, w, mode, whirl_chain_total_length(c),
                                         SCAN_RATIO, tip_r_guess, &a);
    else
        status = GSL_EDOM;
    if (status == GSL_EDOM) {
        if ((size_t)mode > c->n)
            return whirl_fail(GSL_EDOM, "mode %d does not exist: a chain of %zu links has modes "
                              "1..%zu", mode, c->n, c->n);
        double crit[WHIRL_MODE_MAX];
        if (whirl_nlink_critical(c, (size_t)mode, crit) != GSL_SUCCESS) return GSL_EDOM;
        return whirl_steady_fail_missing(mode, omega, crit[mode - 1]);
    }
    if (status != GSL_SUCCESS) return status;
    nlink_recurse(c, omega, a, w->r, w->z, w->tension);
    nlink_info(w, omega, mode, info);
    if (info->n_nodes != mode - 1)
        return whirl_fail(GSL_EFAILED, "mode %d at omega=%g: found %d axis crossings", mode,
                          omega, info->n_nodes);
    return whirl_steady_check_info(info);
}

int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, double tip_r_guess,
                      whirl_shape_info *info)
{
    int status = check_chain(c);
    if (status != GSL_SUCCESS) return status;
    nlink_ws *w = nlink_ws_alloc(c);
    if (w == NULL) return GSL_ENOMEM;
    status = nlink_solve_ws(w, omega, mode, tip_r_guess, info);
    nlink_ws_free(w);
    return status;
}

int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists)
{
    int status = check_chain(c);
    if (status != GSL_SUCCESS) return status;
    steady_model m = {nlink_ws_alloc, nlink_ws_free, nlink_solve_ws, c};
    return whirl_steady_branch(&m, mode, n, omega, info, exists);
}
