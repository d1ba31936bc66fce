/* The Cartesian formulation of the N-link chain: link vectors and tensions as Lagrange multipliers,
 * O(N) per evaluation, no coordinate singularity.
 *
 * State y = (d_1..d_N, d_1'..d_N'): the link vectors d_i = x_i - x_{i-1} and their time
 * derivatives in the model's frame (3 components each in 3D; (x, z) in 2D). Link vectors rather
 * than positions keep |d_i| = l_i well conditioned at large N and make the projection separable.
 *
 * Equations (Baraff 1996, "Linear-time dynamics using Lagrange multipliers", SIGGRAPH): with
 * multipliers lambda_i (tension T_i = lambda_i l_i) and the per-mass acceleration
 * g_i = gvec + a_field(x_i, v_i) + f_i / m_i (gravity, in the co-rotating frame the centrifugal
 * w^2 (x, y, 0), Coriolis 2 w (v_y, -v_x, 0) and, with a rate w(t) that changes, Euler
 * w' (y, -x, 0) fields, applied forces f_i),
 *   m_i a_i = m_i g_i - lambda_i d_i + lambda_{i+1} d_{i+1}      (lambda_{N+1} = 0),
 *   d_i'' = a_i - a_{i-1},  a_0 = p''(t) the pivot's prescribed acceleration.
 * The second derivative of |d_i|^2 = l_i^2, d_i . d_i'' = -|d_i'|^2, gives the symmetric
 * positive definite tridiagonal system
 *   lambda_i |d_i|^2 (1/m_i + 1/m_{i-1}) - lambda_{i+1} (d_i . d_{i+1}) / m_i
 *     - lambda_{i-1} (d_i . d_{i-1}) / m_{i-1} = d_i . (g_i - g_{i-1}) + |d_i'|^2
 * (1/m_0 = 0, g_0 = p''), solved in O(N) by elimination from the tip up. The differences
 * g_i - g_{i-1} of the uniform fields are formed exactly from d_i, d_i' (gravity cancels, the
 * centrifugal difference is w^2 d_i, the Coriolis one 2 w (d_iy', -d_ix')), not by subtracting
 * nearly equal numbers.
 * Round-off: the system is a discrete Laplacian (condition number ~ N^2). Plain top-down Thomas
 * elimination of the hanging chain sits on a neutral fixed point of the pivot recursion and the
 * tip-up one ends in the cancellation q_1 = a - a (N-1)/N; both lose accuracy growing with N (the
 * top-down one, even in long double, gave 1.8e-11 relative tension error at N = 1000). Here the
 * tip-up pivots are formed from Lagrange's identity |a|^2 |b|^2 - (a.b)^2 = |a x b|^2 as sums
 * of non-negative terms; the coefficients are formed in double, the recursions (pivots, reduced
 * right-hand side, back-substitution) run in long double. Measured relative tension error of the
 * hanging chain at N = 10^2, 10^3, 10^4: 9e-17, 2.4e-16, 3.1e-16 (all in double: 1.3e-15,
 * 4.3e-15, 2.6e-14; all in long double: 9e-17, 1e-16, 2e-16 at twice the cost).
 * Projection: d_i <- l_i d_i / |d_i|, then d_i' <- d_i' - (d_i . d_i' / l_i^2) d_i, formed in long
 * double and rounded once: with the scale factor rounded to double first, the energy error of
 * gauss3 (5 links, h = 0.01) grew like t^0.62 to 7e-14 over 2 10^5 steps; rounded once, to
 * 4.8e-14 over 10^6 steps (tests/bench_dynamics.c). The Gauss step followed by the projection is
 * neither symplectic nor symmetric on the constraint manifold, so its truncation error can
 * accumulate: over 10^7 steps (8 runs, tests/bench_stress.c, case "long") the energy error has a
 * drift common to every run, -1.9e-12 at h = 0.005 and -4.2e-14 at h = 0.0025, and none
 * measurable at h = 0.00125 (5e-16 against a spread of 6.2e-15); the spread between the runs,
 * the round-off, grows like t^0.48 at every step (Brouwer's law: t^0.5). Hairer's symmetric
 * projection (pre-scaling each link by half the predicted correction) left the drift at
 * h = 0.0025 unchanged (-5.7e-14), so it is not used. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dyn_internal.h"
#include "error.h"

static int cart_alloc(whirl_dyn *d)
{
    size_t n = d->n;
    d->size = 2 * (size_t)d->dim * n;
    d->tri_diag = malloc(n * sizeof *d->tri_diag);
    d->tri_off = malloc(n * sizeof *d->tri_off);
    d->tri_rhs = malloc(n * sizeof *d->tri_rhs);
    d->multiplier = malloc(n * sizeof *d->multiplier);
    d->link_acc = malloc(3 * n * sizeof *d->link_acc);
    if (!d->tri_diag || !d->tri_off || !d->tri_rhs || !d->multiplier || !d->link_acc)
        return GSL_ENOMEM;
    return GSL_SUCCESS;
}

/* Component k (0..2) of link i sits at y[comp_index(d, i, k)] (2D: no y component). */
static size_t comp_index(const whirl_dyn *d, size_t i, int k)
{
    return d->dim == 3 ? 3 * i + (size_t)k : 2 * i + (k == 2);
}

static void cart_link(const whirl_dyn *d, const double *y, size_t i, double *dv, double *ddot)
{
    const double *q = y, *qd = y + d->size / 2;
    for (int k = 0; k < 3; k++) {
        if (d->dim == 2 && k == 1) {
            dv[k] = ddot[k] = 0;
            continue;
        }
        dv[k] = q[comp_index(d, i, k)];
        ddot[k] = qd[comp_index(d, i, k)];
    }
}

static void project_link(double len, double *dv, double *ddot)
{
    const long double norm2 =
        (long double)dv[0] * dv[0] + (long double)dv[1] * dv[1] + (long double)dv[2] * dv[2];
    const long double scale = len / sqrtl(norm2);
    long double d[3], along = 0;
    for (int k = 0; k < 3; k++) {
        d[k] = dv[k] * scale;
        along += d[k] * ddot[k];
    }
    along /= (long double)len * len;
    for (int k = 0; k < 3; k++) {
        dv[k] = (double)d[k];
        ddot[k] = (double)(ddot[k] - along * d[k]);
    }
}

static void store_link(const whirl_dyn *d, double *y, size_t i, const double *dv,
                       const double *ddot)
{
    double *q = y, *qd = y + d->size / 2;
    for (int k = 0; k < 3; k++) {
        if (d->dim == 2 && k == 1) continue;
        q[comp_index(d, i, k)] = dv[k];
        qd[comp_index(d, i, k)] = ddot[k];
    }
}

static int cart_project(whirl_dyn *d, double *y)
{
    const double *len = d->model.chain->length;
    for (size_t i = 0; i < d->n; i++) {
        double dv[3], dd[3];
        cart_link(d, y, i, dv, dd);
        project_link(len[i], dv, dd);
        store_link(d, y, i, dv, dd);
    }
    if (!whirl_dyn_all_finite(y, d->size))
        return whirl_fail(GSL_ERANGE, "the state is not finite (a link of zero length?)");
    return GSL_SUCCESS;
}

static int cart_from_links(whirl_dyn *d, const double *dv, const double *ddot, double *y)
{
    for (size_t i = 0; i < d->n; i++) store_link(d, y, i, dv + 3 * i, ddot + 3 * i);
    return cart_project(d, y);
}

/* d->link_acc <- g_i - g_{i-1} (3 per link) and d->multiplier <- lambda at (t, y). */
static void solve_multipliers(whirl_dyn *d, double t, const double *y)
{
    const whirl_model *m = &d->model;
    const double *mass = m->chain->mass, *inv_mass = d->inv_mass;
    const double g = m->chain->gravity;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    const size_t n = d->n;
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    const double w = dr.omega, dw = dr.domega;
    whirl_dyn_prepare_forces(d, t, y, 1);
    double p[3], pv[3], pa[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    for (size_t i = 0; i < n; i++) {
        /* field difference: at link 1 the whole field at mass 1 minus the pivot's acceleration */
        const double *xr = i == 0 ? d->x : d->links + 3 * i;
        const double *vr = i == 0 ? d->v : d->link_rates + 3 * i;
        double *acc = d->link_acc + 3 * i;
        for (int k = 0; k < 3; k++) {
            acc[k] = d->force[3 * i + k] * inv_mass[i];
            if (i > 0) acc[k] -= d->force[3 * (i - 1) + k] * inv_mass[i - 1];
        }
        if (rotating) {
            acc[0] += w * w * xr[0] + 2 * w * vr[1];
            acc[1] += w * w * xr[1] - 2 * w * vr[0];
            if (dw != 0) { /* Euler: -w' z x x */
                acc[0] += dw * xr[1];
                acc[1] -= dw * xr[0];
            }
        }
        if (i == 0) {
            acc[2] -= g;
            for (int k = 0; k < 3; k++) acc[k] -= pa[k];
        }
    }
    /* Elimination from the tip up (tri_diag <- pivot q_i, tri_off <- off_i / q_{i+1}, tri_rhs <-
     * reduced right-hand side r'_i), with the pivot written q_i = |d_i|^2 / m_{i-1} + s_i and
     * s_i = (|d_i x d_{i+1}|^2 + m_i s_{i+1} |d_i|^2) / (m_i (|d_{i+1}|^2 + m_i s_{i+1})),
     * s_N = |d_N|^2 / m_N (Lagrange's identity): sums of non-negative terms, free of the
     * cancellation q_1 = a - a (N-1)/N of the straightforward recursion on a hanging chain. */
    long double s_below = 0, r_below = 0;
    for (size_t i = n; i-- > 0;) {
        const double *di = d->links + 3 * i;
        const double norm2 = di[0] * di[0] + di[1] * di[1] + di[2] * di[2];
        const double *ai = d->link_acc + 3 * i, *ri = d->link_rates + 3 * i;
        const double rhs = di[0] * ai[0] + di[1] * ai[1] + di[2] * ai[2] +
                           (ri[0] * ri[0] + ri[1] * ri[1] + ri[2] * ri[2]);
        long double s_i, ratio = 0, r_i = rhs;
        if (i + 1 == n) {
            s_i = norm2 * inv_mass[i];
        } else {
            const double *dn = d->links + 3 * (i + 1);
            const double cx = di[1] * dn[2] - di[2] * dn[1];
            const double cy = di[2] * dn[0] - di[0] * dn[2];
            const double cz = di[0] * dn[1] - di[1] * dn[0];
            const double nn = dn[0] * dn[0] + dn[1] * dn[1] + dn[2] * dn[2];
            const double dd = di[0] * dn[0] + di[1] * dn[1] + di[2] * dn[2];
            const long double below = nn + mass[i] * s_below; /* m_i q_{i+1} */
            s_i = ((cx * cx + cy * cy + cz * cz) + mass[i] * s_below * norm2) / (mass[i] * below);
            ratio = -dd / below;
            r_i -= ratio * r_below;
        }
        const long double q = (i > 0 ? norm2 * inv_mass[i - 1] : 0.0L) + s_i;
        d->tri_diag[i] = q;
        d->tri_off[i] = ratio;
        d->tri_rhs[i] = r_i;
        s_below = s_i;
        r_below = r_i;
    }
    /* back-substitution from the top: lambda_{i+1} = (r'_{i+1} - off_i lambda_i) / q_{i+1} */
    long double lam = d->tri_rhs[0] / d->tri_diag[0];
    d->multiplier[0] = (double)lam;
    for (size_t i = 0; i + 1 < n; i++) {
        /* off_i / q_{i+1} = tri_off[i] */
        lam = d->tri_rhs[i + 1] / d->tri_diag[i + 1] - d->tri_off[i] * lam;
        d->multiplier[i + 1] = (double)lam;
    }
}

static int cart_rhs(whirl_dyn *d, double t, const double *y, double *dydt)
{
    const double *inv_mass = d->inv_mass;
    const size_t n = d->n, half = d->size / 2;
    solve_multipliers(d, t, y);
    memcpy(dydt, y + half, half * sizeof *dydt);
    for (size_t i = 0; i < n; i++) {
        const double *di = d->links + 3 * i, *acc = d->link_acc + 3 * i;
        const double lam = d->multiplier[i];
        const double self = lam * (inv_mass[i] + (i > 0 ? inv_mass[i - 1] : 0.0));
        double a[3];
        for (int k = 0; k < 3; k++) {
            a[k] = acc[k] - self * di[k];
            if (i + 1 < n) a[k] += d->multiplier[i + 1] * inv_mass[i] * d->links[3 * (i + 1) + k];
            if (i > 0) a[k] += d->multiplier[i - 1] * inv_mass[i - 1] * d->links[3 * (i - 1) + k];
        }
        for (int k = 0; k < 3; k++) {
            if (d->dim == 2 && k == 1) continue;
            dydt[half + comp_index(d, i, k)] = a[k];
        }
    }
    return GSL_SUCCESS;
}

static int cart_tensions(whirl_dyn *d, double t, const double *y, double *tension)
{
    solve_multipliers(d, t, y);
    for (size_t i = 0; i < d->n; i++) {
        const double *di = d->links + 3 * i;
        tension[i] = d->multiplier[i] * sqrt(di[0] * di[0] + di[1] * di[1] + di[2] * di[2]);
    }
    if (!whirl_dyn_all_finite(tension, d->n))
        return whirl_fail(GSL_EBADFUNC, "the tensions are not finite at t = %.17g", t);
    return GSL_SUCCESS;
}

const dyn_ops whirl_dyn_cartesian_ops = {
    .link = cart_link,
    .from_links = cart_from_links,
    .rhs = cart_rhs,
    .project = cart_project,
    .tensions = cart_tensions,
    .alloc = cart_alloc,
};
