/* The N-link chain's part of the equilibria search (method in equilibria.c): the tip and pivot
 * scans' functions and their linear floors, Newton's method on all link angles, and a root crowded
 * within round-off refined in quadruple precision. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/error.h"
#include "steady/equilibria_internal.h"
#include "steady/steady_internal.h"
#include "steady/tip_up.h"

#define BISECT_QUAD_MAX 512 /* bisections in quadruple precision (from 1 to 1e-34: 113) */

/* ---- N-link chain: the two scans ---- */

/* x = ln(a / (L - a)) */
double eq_tip_of_x(const nlink_scan *s, double x) { return s->length / (1 + exp(-x)); }

int eq_tip_fn(void *ctx, double x, double *g, double *dg, double *sl, double *sl_d)
{
    const nlink_scan *s = ctx;
    double e = exp(-x), a = s->length / (1 + e), da = s->length * e / ((1 + e) * (1 + e));
    double g_a;
    whirl_nlink_tip_shot(s->c, s->omega, a, g, &g_a, sl ? sl : s->slope, sl_d ? sl_d : s->slope_d);
    *dg = g_a * da;
    for (size_t i = 0; sl_d && i < s->c->n; i++) sl_d[i] *= da;
    return GSL_SUCCESS;
}

/* The link angles theta_i = atan(H_i / V_i) of the tip scan's own shot at x (the shot whose
 * residual changed sign there) into theta[0..N-1], as the start of Newton's method. Not those
 * of a second shot from the tip radius by the positions' recursion (whirl_nlink_positions):
 * where roots crowd, the two recursions' round-off moves the upper links as much as a change of
 * the tip radius to a neighbouring root would, and their angles differ by up to 0.11 rad (10
 * links at omega = 50: 6 roots with more than 1e-3 rad; 24 at omega = 60). Newton's method
 * reached the same equilibrium from both at every root of 5, 7, 10 and 25 links in the
 * README's tables, but only the scan's own angles belong to the sign change found. */
int eq_angles_of_scan(const nlink_scan *s, double x, double *theta)
{
    double g, dg;
    int status = eq_tip_fn((void *)s, x, &g, &dg, NULL, NULL);
    for (size_t i = 0; i < s->c->n && !status; i++) theta[i] = atan(s->slope[i]);
    return status;
}

/* y = ln(theta_1 / (pi/2 - theta_1)) */
double eq_theta_of_y(double y) { return M_PI_2 / (1 + exp(-y)); }

int eq_pivot_fn(void *ctx, double y, double *g, double *dg, double *sl, double *sl_d)
{
    const nlink_scan *s = ctx;
    double e = exp(-y), th = M_PI_2 / (1 + e), dth = M_PI_2 * e / ((1 + e) * (1 + e));
    double d;
    int status = whirl_nlink_pivot_shot(s->c, s->omega, th, g, &d, NULL, NULL, sl, sl_d);
    *dg = d * dth;
    for (size_t i = 0; sl_d && i < s->c->n; i++) sl_d[i] *= dth;
    return status;
}

/* The linear floors: the largest |H_i| / V_i per unit tip radius (shot from the tip) and per
 * unit tan(theta_1) (shot from the pivot), for the linearised chain (T_i = V_i). */
void eq_linear_loads(const whirl_chain *c, double omega, double *per_tip, double *per_top)
{
    size_t n = c->n;
    double w2 = omega * omega, worst = 0;
    tip_up s = tip_up_start(c, w2, 1, 0, 1);
    for (size_t i = n; i >= 1; i--) {
        tip_up_link(&s, c, i, TIP_UP_LINEAR);
        worst = fmax(worst, fabs(s.eta) / s.v);
    }
    *per_tip = worst;
    /* from the pivot: H_i / V_i = tan(theta_1) V_1 eta_i / V_i, eta_1 = 1 */
    double v = s.v, v1 = v, x = 0, eta = 1;
    worst = 0;
    for (size_t i = 1; i <= n; i++) {
        worst = fmax(worst, v1 * fabs(eta) / v);
        x += c->length[i - 1] * eta / v;
        eta -= c->mass[i - 1] * w2 * x;
        v -= c->mass[i - 1] * c->gravity;
    }
    *per_top = worst;
}

/* ---- N-link chain: Newton's method on all link angles ----
 * The tip shot carries the round-off of the recursion up the chain, amplified as the radii
 * grow from the tip (by up to ~1e-8 relative in the tip radius for the high modes of a 7-link
 * chain at omega = 21.1), and the pivot shot its own: each root is polished by Newton's method
 * on the force balance of every link in the link angles (whirl_nlink_balance_polish,
 * src/nlink_balance.c: the horizontal balances differenced so that the Jacobian, the in-plane
 * stiffness of the chain, is tridiagonal; regular at a root that is not a fold), from the angles
 * of the shot: the polished shape balances every link to round-off whatever shot found it. */

void eq_angle_ws_free(angle_ws *w)
{
    if (w == NULL) return;
    whirl_nlink_balance_free(w->bal);
    free(w->theta);
    free(w);
}

angle_ws *eq_angle_ws_alloc(const whirl_chain *c, double omega)
{
    size_t n = c->n;
    angle_ws *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->c = c;
    w->omega = omega;
    w->theta = malloc((2 * n + 3 * (n + 1)) * sizeof *w->theta);
    if (w->theta == NULL) goto fail;
    w->r = w->theta + n;
    w->z = w->r + n + 1;
    w->t = w->z + n + 1;
    w->start = w->t + n + 1;
    w->bal = whirl_nlink_balance_alloc(c);
    if (w->bal == NULL) goto fail;
    return w;
fail:
    eq_angle_ws_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for Newton's method on %zu links", n);
    return NULL;
}

/* Polishes the equilibrium near the link angles w->theta (from a shot): the polished angles
 * back in w->theta (mirrored to a positive tip radius), its tip radius in *tip_r, the nodes in
 * w->r, w->z, w->t. GSL_EFAILED if it does not converge or a link ends up horizontal or
 * compressed (a rod's equilibrium, not a chain's). */
int eq_angle_polish(angle_ws *w, double *tip_r)
{
    const whirl_chain *c = w->c;
    size_t n = c->n;
    int status = whirl_nlink_balance_polish(w->bal, w->omega, w->theta);
    if (status) {
        whirl_error_record why;
        whirl_error_save(&why);
        return whirl_fail(GSL_EFAILED, "tip radius " WHIRL_Q_LENGTH "%g: %s", *tip_r, why.text);
    }
    double worst = whirl_nlink_balance_nodes(c, w->omega, w->theta, w->r, w->z, w->t);
    w->worst = fmax(w->worst, worst);
    *tip_r = fabs(w->r[n]);
    if (w->r[n] < 0) {
        for (size_t i = 0; i <= n; i++) w->r[i] = -w->r[i];
        for (size_t i = 0; i < n; i++) w->theta[i] = -w->theta[i];
    }
    return GSL_SUCCESS;
}

/* ---- N-link chain: a root crowded within round-off, refined in quadruple precision ----
 * Where roots crowd (10 links at omega = 60: three tip radii within 3e-15 of each other, and at
 * the middle one the top link turns by a radian over 3.6e-18 in tip radius, less than the spacing
 * of doubles there, 6.9e-18) no double tip radius is close enough to the root for the shot's upper
 * link angles to be those of the equilibrium (the top link's off by 1.4 rad), and Newton's
 * method from them does not converge; long double (64 bits) leaves it 2e-3 rad off. The root is
 * then bisected again in quadruple precision (whirl_nlink_tip_shot_quad, _pivot_shot_quad) inside
 * its scan's bracket, down to adjacent quadruple numbers, and Newton's method (in double) starts
 * from the link angles of the shot there. The polished shape is kept only if every link angle
 * stays within MATCH_ANGLE of that start (Newton's method refined the root the shot found, it did
 * not go elsewhere) and, like every root, it must not be another root's equilibrium
 * (eq_list.coincident). The tip shot is bisected in the tip radius a, the pivot shot in
 * tan(theta_1), between the values of the double scan's bracket ends. */


nlink_quad eq_tip_quad(const nlink_scan *s, nlink_quad a, double *theta)
{
    return whirl_nlink_tip_shot_quad(s->c, s->omega, a, theta);
}

nlink_quad eq_pivot_quad(const nlink_scan *s, nlink_quad tan_1, double *theta)
{
    return whirl_nlink_pivot_shot_quad(s->c, s->omega, tan_1, theta);
}

/* The root of f between p = lo and hi, bisected in quadruple precision down to adjacent
 * numbers; the link angles of the shot at the end with the smaller residual into theta.
 * GSL_EFAILED if f has one sign at both ends. */
static int bisect_quad(const nlink_scan *s, quad_fn f, double lo, double hi, double *theta)
{
    nlink_quad a = lo, b = hi, fa = f(s, a, NULL), fb = f(s, b, NULL);
    if ((fa < 0) == (fb < 0))
        return whirl_fail(GSL_EFAILED, "no sign change over [%.17g, %.17g] in quadruple "
                          "precision", lo, hi);
    for (int it = 0; it < BISECT_QUAD_MAX; it++) {
        nlink_quad m = a + (b - a) / 2;
        if (!((m > a && m < b) || (m < a && m > b))) break;
        nlink_quad fm = f(s, m, NULL);
        if ((fm < 0) == (fa < 0)) a = m, fa = fm;
        else b = m, fb = fm;
    }
    f(s, (fa < 0 ? -fa : fa) <= (fb < 0 ? -fb : fb) ? a : b, theta);
    return GSL_SUCCESS;
}

/* Polishes the root of a scan between the parameters lo and hi of f from its double shot's link
 * angles (in aw->theta): Newton's method from them, and where it does not converge, from the
 * root refined in quadruple precision (above; counted in *refined). The tip radius in *a, as
 * eq_angle_polish. */
int eq_polish_root(angle_ws *aw, const nlink_scan *s, quad_fn f, double lo, double hi,
                   double *a, size_t *refined)
{
    int status = eq_angle_polish(aw, a);
    if (status != GSL_EFAILED) return status;
    size_t n = s->c->n;
    if ((status = bisect_quad(s, f, lo, hi, aw->start))) return status;
    memcpy(aw->theta, aw->start, n * sizeof *aw->theta);
    if ((status = eq_angle_polish(aw, a))) return status;
    /* eq_angle_polish mirrors the shape to a positive tip radius */
    double same = 0, mirror = 0;
    for (size_t i = 0; i < n; i++) {
        same = fmax(same, fabs(aw->theta[i] - aw->start[i]));
        mirror = fmax(mirror, fabs(aw->theta[i] + aw->start[i]));
    }
    if (!(fmin(same, mirror) <= MATCH_ANGLE))
        return whirl_fail(GSL_EFAILED, "tip radius " WHIRL_Q_LENGTH "%g: Newton's method moved a "
                          "link angle by %g rad from the quadruple precision shot's", *a,
                          fmin(same, mirror));
    ++*refined;
    return GSL_SUCCESS;
}
