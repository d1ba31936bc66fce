/* Steady shapes (relative equilibria) of the N-link chain rotating at omega about the vertical.
 *
 * Masses m_i at (r_i, z_i), i = 1..N, on links of lengths l_i from mass i-1 to mass i; mass 0
 * is the pivot. In the frame co-rotating at omega a mass feels gravity (0, -m_i g) and the
 * centrifugal force (m_i omega^2 r_i, 0). The part below link i is in equilibrium when link i
 * carries the resultant of those forces,
 *     H_i = sum_{j >= i} m_j omega^2 r_j,  V_i = g sum_{j >= i} m_j,  T_i = |(H_i, V_i)|,
 * and points along it: r_{i-1} = r_i - l_i H_i / T_i, z_{i-1} = z_i + l_i V_i / T_i.
 * Given the tip radius a = r_N this recursion up from the tip (steady/tip_up.h) fixes the whole
 * chain; the shape is an equilibrium when the pivot lands on the axis, r_0(a) = 0; the branches
 * of such shapes are followed from their birth by pseudo-arclength continuation (nlink_path.c).
 * Every mass's force balance then holds by construction to round-off.
 *
 * Pivot-end shooting (a second formulation, for checks): V_1 = g sum m_j is known, so the top
 * link's angle theta_1 fixes H_1 = V_1 tan(theta_1); going down, r_i = r_{i-1} + l_i H_i / T_i,
 * H_{i+1} = H_i - m_i omega^2 r_i, and the shape is an equilibrium when H_{N+1} = 0 (no force
 * below the tip). H_{N+1} / H_1 is finite at theta_1 = 0 (the linear shot from the top).
 *
 * Node count: the axis crossings below the pivot are the sign changes of r from mass to mass.
 * The top modes of long chains decay towards the tip below the smallest normal double (mode 500
 * of 500 to 1e-423 of its largest radius), where r is zero or subnormal and its signs are lost.
 * Below the last mass b whose |r_b| >= DBL_MIN the links hang at angles of order DBL_MIN / l_i,
 * so the shape there obeys the force balance linearised about the hanging chain at the same
 * omega (sin theta_i = tan theta_i = H_i / V_i and T_i = V_i, to relative order theta^2): with
 * u_i proportional to r_i,
 *     u_N = 1,  eta_i = eta_{i+1} + m_i omega^2 u_i  (eta_{N+1} = 0),
 *     u_{i-1} = u_i - l_i eta_i / V_i,
 * the recursion above with tip_r -> 0 (eta_i = H_i / tip_r). It is the solution that grows
 * upward (the tail's decay towards the tip), so the recursion from the tip is stable; u and
 * eta are rescaled by powers of two as they grow. The crossings on links b+1..N are those of
 * u_b..u_N, at the points interpolated linearly between masses as for r (a crossing does not
 * depend on the overall sign, so u matches r's sign at b without a flip). Where r is normal, on
 * the 100 masses above b, r_{i-1}/r_i and u_{i-1}/u_i (in 60 digits) agree to 1.7e-15 (modes
 * 499, 500 of 500 and 999, 1000 of 1000 at 1 + 1e-4 and 1.2 times their birth), and the nodes
 * of a 60-digit nonlinear tip shot agree with all of the count's to 7.2e-16.
 *
 * Linear critical rates: the small horizontal displacements x_i of the hanging chain satisfy
 *     m_i omega^2 x_i = K x, K_ii = T_i/l_i + T_{i+1}/l_{i+1}, K_{i,i+1} = -T_{i+1}/l_{i+1},
 * with the static tensions T_i = V_i (T_{N+1} = 0): omega^2 are the eigenvalues of the
 * symmetric tridiagonal M^{-1/2} K M^{-1/2}, computed by LAPACK's bisection dstebz (Kahan 1966;
 * Demmel & Kahan 1990) to high relative accuracy. They tend to j_{0,k}/2 with error O(1/N). */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include "core/linalg.h"

#include "core/error.h"
#include "steady/steady_internal.h"
#include "steady/tip_up.h"

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

/* The recursion up from the tip (steady/tip_up.h) with a = 1 from r_N = tip_r: the radii and
 * the horizontal loads themselves, m_i omega^2 as m_i omega omega; z relative to the pivot. */
static void nlink_recurse(const whirl_chain *c, double omega, double tip_r, double *r, double *z,
                          double *tension)
{
    size_t n = c->n;
    tip_up s = tip_up_start(c, omega, omega, 1, tip_r);
    r[n] = tip_r;
    z[n] = 0;
    for (size_t i = n; i >= 1; i--) {
        tip_up_link(&s, c, i, TIP_UP_HYPOT);
        tension[i] = s.t;
        r[i - 1] = s.u;
        z[i - 1] = z[i] + c->length[i - 1] * s.v / s.t;
    }
    tension[0] = tension[1];
    double z_pivot = z[0];
    for (size_t i = 0; i <= n; i++) z[i] -= z_pivot;
}

static int check_chain(const whirl_chain *c)
{
    if (c == NULL || c->n < 1) return whirl_fail(GSL_EINVAL, "a chain needs at least one link");
    return GSL_SUCCESS;
}

/* links x eigenvalues per call of dstebz in whirl_nlink_critical: about 0.02 s of bisection */
#define CRITICAL_BLOCK_WORK 200000

int whirl_nlink_critical(const whirl_chain *c, size_t nmodes, double *omega)
{
    return whirl_nlink_critical_report(c, nmodes, omega, NULL, NULL);
}

int whirl_nlink_critical_report(const whirl_chain *c, size_t nmodes, double *omega,
                                whirl_nlink_critical_progress_fn progress, void *ctx)
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
    /* Bisection costs ~ n per eigenvalue and bisection step (60000 links, all their modes:
     * minutes): the eigenvalues are found in blocks of about CRITICAL_BLOCK_WORK / n, each
     * block a call of dstebz for eigenvalues il..iu, with the stop request polled between
     * blocks (a block takes ~0.02 s). */
    const size_t block = n < CRITICAL_BLOCK_WORK ? CRITICAL_BLOCK_WORK / n : 1;
    for (size_t il = 1; il <= nmodes && status == GSL_SUCCESS; il += block) {
        const size_t iu = il + block - 1 < nmodes ? il + block - 1 : nmodes;
        if (il > 1 && whirl_stop_requested()) {
            status = whirl_fail(WHIRL_EINTERRUPTED, "stopped after %zu of %zu critical rates",
                                il - 1, nmodes);
            break;
        }
        lapack_int found = 0, nsplit = 0;
        lapack_int info = whirl_la_dstebz('I', 'E', (lapack_int)n, 0, 0, (lapack_int)il,
                                         (lapack_int)iu, 2 * DBL_MIN, d, e, &found, &nsplit,
                                         lambda, iblock, isplit);
        if (info != 0 || found != (lapack_int)(iu - il + 1))
            status = whirl_fail(GSL_EFAILED, "tridiagonal eigensolver (dstebz) failed: info %d",
                                (int)info);
        else {
            for (size_t k = 0; k < (size_t)found; k++) omega[il - 1 + k] = sqrt(lambda[k]);
            if (progress) progress(ctx, iu, nmodes);
        }
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

/* The tail's crossings, on links b+1..N (the linear recursion of the header comment from the tip
 * up to mass b, whose arclength is s_b): their count; with first >= 0, those among them that
 * come before max in the whole list are written to node_s[first + (count - 1 - j)], j counted
 * from the tip. u and eta are rescaled by powers of two (exactly) as they grow. */
static size_t tail_crossings(const whirl_chain *c, double omega, size_t b, double s_b,
                             size_t count, size_t first, size_t max, double *node_s)
{
    const double w2 = omega * omega;
    double s = s_b; /* arclength of mass i */
    for (size_t i = b + 1; i <= c->n; i++) s += c->length[i - 1];
    tip_up t = tip_up_start(c, w2, 1, 0, 1);
    size_t found = 0;
    for (size_t i = c->n; i > b; i--) {
        const double u = t.u;
        tip_up_link(&t, c, i, TIP_UP_LINEAR);
        const double up = t.u; /* u_{i-1} */
        s -= c->length[i - 1];
        if ((up > 0 && u <= 0) || (up < 0 && u >= 0)) {
            const size_t j = first + (count - 1 - found);
            if (count > 0 && j < max) node_s[j] = s + c->length[i - 1] * up / (up - u);
            found++;
        }
        if (fabs(t.u) > 0x1p300) {
            t.u *= 0x1p-300;
            t.eta *= 0x1p-300;
        }
    }
    return found;
}

size_t whirl_nlink_node_arclengths(const whirl_chain *c, double omega, const double *r,
                                   size_t max, double *node_s, size_t *resolved)
{
    /* b: the last mass whose radius is a normal double; below it the tail's */
    size_t b = c->n;
    while (b > 0 && !(fabs(r[b]) >= DBL_MIN)) b--;
    if (b == 0) b = c->n; /* no radius resolved (the hanging chain): r as it is */
    if (resolved) *resolved = b;
    size_t count = 0;
    double s = 0; /* arclength of mass i-1 from the pivot */
    for (size_t i = 1; i <= b; i++) {
        /* a crossing on link i (below the pivot: the pivot itself is not counted) */
        if (i >= 2 && ((r[i - 1] > 0 && r[i] <= 0) || (r[i - 1] < 0 && r[i] >= 0))) {
            if (count < max) node_s[count] = s + c->length[i - 1] * r[i - 1] / (r[i - 1] - r[i]);
            count++;
        }
        s += c->length[i - 1];
    }
    if (b == c->n) return count;
    const size_t tail = tail_crossings(c, omega, b, s, 0, 0, 0, NULL);
    if (count < max) tail_crossings(c, omega, b, s, tail, count, max, node_s);
    return count + tail;
}

/* The summary of the shape with nodes r, z and tensions t (an equilibrium). */
static void nlink_info(const whirl_chain *c, const double *r, const double *z, const double *t,
                       double omega, int mode, whirl_shape_info *info)
{
    size_t n = c->n;
    info->omega = omega;
    info->mode = mode;
    info->tip_r = r[n];
    info->top_tension = t[1];
    info->depth = -z[n];
    info->max_r = 0;
    for (size_t i = 1; i <= n; i++) info->max_r = fmax(info->max_r, fabs(r[i]));
    info->n_crossings =
        (int)whirl_nlink_node_arclengths(c, omega, r, WHIRL_SHAPE_NODES, info->crossing_s, NULL);
}

void whirl_nlink_info_nodes(const whirl_chain *c, const double *r, const double *z,
                            const double *tension, double omega, int mode,
                            whirl_shape_info *info)
{
    nlink_info(c, r, z, tension, omega, mode, info);
}

int whirl_nlink_info(const whirl_chain *c, double omega, double tip_r, int mode,
                     whirl_shape_info *info)
{
    nlink_ws *w = nlink_ws_alloc(c);
    if (w == NULL) return whirl_last_status();
    int status = whirl_nlink_positions(c, omega, tip_r, w->r, w->z, w->tension);
    if (status == GSL_SUCCESS) {
        nlink_info(c, w->r, w->z, w->tension, omega, mode, info);
        status = whirl_steady_check_info(info);
    }
    nlink_ws_free(w);
    return status;
}

int whirl_nlink_pivot_shot(const whirl_chain *c, double omega, double theta_1, double *residual,
                           double *d_residual, double *tip_r, double *theta, double *slope,
                           double *slope_d)
{
    /* everything divided by H_1: eta_i = H_i / H_1, x_i = r_i / H_1; the primed quantities are
     * their derivatives with respect to theta_1 (forward differentiation, exact) */
    double v = 0;
    for (size_t i = 0; i < c->n; i++) v += c->mass[i] * c->gravity;
    double h1 = v * tan(theta_1), h1_d = v / (cos(theta_1) * cos(theta_1));
    double eta = 1, x = 0, eta_d = 0, x_d = 0, w2 = omega * omega;
    for (size_t i = 1; i <= c->n; i++) {
        double he = h1 * eta, t = hypot(he, v);
        if (theta) theta[i - 1] = atan2(he, v);
        if (slope) slope[i - 1] = he / v;
        if (slope_d) slope_d[i - 1] = (h1_d * eta + h1 * eta_d) / v;
        x += c->length[i - 1] * eta / t;
        x_d += c->length[i - 1] * (eta_d / t - eta * he * (h1_d * eta + h1 * eta_d) / (t * t * t));
        eta -= c->mass[i - 1] * w2 * x;
        eta_d -= c->mass[i - 1] * w2 * x_d;
        v -= c->mass[i - 1] * c->gravity;
    }
    *residual = eta;
    if (d_residual) *d_residual = eta_d;
    if (tip_r) *tip_r = h1 * x;
    return GSL_SUCCESS;
}

void whirl_nlink_tip_shot(const whirl_chain *c, double omega, double a, double *g, double *g_a,
                          double *slope, double *slope_a)
{
    /* u_i = r_i / a, eta_i = H_i / a and their derivatives with respect to a */
    double u_a = 0, eta_a = 0, q = 1, q_a = 0, w2 = omega * omega;
    tip_up s = tip_up_start(c, w2, 1, a, 1);
    for (size_t i = c->n; i >= 1; i--) {
        double m = c->mass[i - 1], l = c->length[i - 1];
        tip_up_link(&s, c, i, TIP_UP_HYPOT);
        eta_a += m * w2 * u_a;
        double h = s.h, h_a = s.eta + a * eta_a, t = s.t;
        slope[i - 1] = h / s.v;
        slope_a[i - 1] = h_a / s.v;
        u_a -= l * (eta_a / t - s.eta * (h / t) * (h_a / t) / t);
        q += s.u * s.u;
        q_a += 2 * s.u * u_a;
    }
    double norm = sqrt(q);
    *g = s.u / norm;
    *g_a = u_a / norm - 0.5 * s.u * q_a / (q * norm);
}

/* The two shots again in quadruple precision (113 bits of mantissa against double's 53), the
 * residuals only and the link angles. Where roots crowd within round-off of each other (10
 * links at omega = 60: three tip radii within 3e-15, and at the middle one the top link turns
 * by a radian over 3.6e-18 in tip radius, less than the spacing of doubles there) no double tip
 * radius is near enough the root for the shot's upper link angles to be the equilibrium's;
 * these refine such a root (src/equilibria.c). Same recursions as whirl_nlink_tip_shot and
 * whirl_nlink_pivot_shot, without the derivatives, and with the pivot shot's parameter
 * tan(theta_1) (no tangent in quadruple precision needed). The square root is Newton's
 * iteration from the long double one (steady/tip_up.h); the angles come out in double, atan2 of
 * the loads rounded to double (relative accuracy eps). */
nlink_quad whirl_nlink_tip_shot_quad(const whirl_chain *c, double omega, nlink_quad a,
                                     double *theta)
{
    nlink_quad q = 1, w2 = (nlink_quad)omega * omega;
    tip_up_quad s = tip_up_quad_start(c, w2, 1, a, 1);
    for (size_t i = c->n; i >= 1; i--) {
        tip_up_quad_link(&s, c, i, TIP_UP_HYPOT);
        if (theta) theta[i - 1] = atan2((double)s.h, (double)s.v);
        q += s.u * s.u;
    }
    return s.u / tip_up_sqrt_quad(q);
}

nlink_quad whirl_nlink_pivot_shot_quad(const whirl_chain *c, double omega, nlink_quad tan_1,
                                       double *theta)
{
    nlink_quad v = 0;
    for (size_t i = 0; i < c->n; i++) v += (nlink_quad)c->mass[i] * c->gravity;
    nlink_quad h1 = v * tan_1, eta = 1, x = 0, w2 = (nlink_quad)omega * omega;
    for (size_t i = 1; i <= c->n; i++) {
        nlink_quad he = h1 * eta, t = tip_up_hypot_quad(he, v);
        if (theta) theta[i - 1] = atan2((double)he, (double)v);
        x += c->length[i - 1] * eta / t;
        eta -= c->mass[i - 1] * w2 * x;
        v -= (nlink_quad)c->mass[i - 1] * c->gravity;
    }
    return eta;
}

int whirl_nlink_pivot_residual(const whirl_chain *c, double omega, double theta_1,
                               double *residual, double *tip_r)
{
    int status = check_chain(c);
    if (status != GSL_SUCCESS) return status;
    if (!(isfinite(omega) && omega > 0 && fabs(theta_1) < M_PI_2))
        return whirl_fail(GSL_EINVAL, "pivot shooting needs omega > 0 and |theta_1| < pi/2");
    return whirl_nlink_pivot_shot(c, omega, theta_1, residual, NULL, tip_r, NULL, NULL, NULL);
}
