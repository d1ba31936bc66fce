/* The seed's formulation of the N-link chain: link angles and a dense mass matrix, O(N^3) per
 * evaluation; the reference for small N.
 *
 * Coordinates (seed eq. 1-2 and 27-29): link i has the unit vector
 *   u_i = (sin th_i cos ph_i, sin th_i sin ph_i, -cos th_i)   (2D: ph_i = 0, the x-z plane),
 * th_i from the downward vertical, ph_i the azimuth from x; x_k = p(t) + sum_{j<=k} l_j u_j.
 * State y = (th, ph, th', ph') in 3D, (th, th') in 2D.
 * With e_th = du/dth = (cos th cos ph, cos th sin ph, sin th) and e_ph = (-sin ph, cos ph, 0),
 *   du/dt = th' e_th + ph' sin th e_ph,
 *   d2u/dt2 = th'' e_th + ph'' sin th e_ph + c,
 *   c = -(th'^2 + ph'^2 sin^2 th) u + 2 th' ph' cos th e_ph - ph'^2 sin th cos th e_th.
 * Lagrange's equations are J^T (m a - F) = Q with J the Jacobian dx/dq, i.e.
 *   A q'' = J^T (F - m alpha) + Q,   alpha_k = sum_{j<=k} l_j c_j (the velocity-quadratic part),
 * where (M_i = sum_{k>=i} m_k, seed eq. 10) the dense symmetric positive definite matrix is
 *   A_{th_i th_j} = M_max(i,j) l_i l_j (cos th_i cos th_j cos(ph_i - ph_j) + sin th_i sin th_j),
 *   A_{th_i ph_j} = M_max(i,j) l_i l_j cos th_i sin th_j sin(ph_i - ph_j),
 *   A_{ph_i ph_j} = M_max(i,j) l_i l_j sin th_i sin th_j cos(ph_i - ph_j)
 * (seed eq. 31-34 and, in 2D, eq. 22), and the generalized forces
 *   (J^T G)_{th_i} = l_i e_th_i . S_i, (J^T G)_{ph_i} = l_i sin th_i e_ph_i . S_i,
 *   S_i = sum_{k>=i} G_k.
 * F_k = applied forces + m_k (gravity + [co-rotating] centrifugal w^2 (x, y, 0) + Coriolis
 * 2 w (v_y, -v_x, 0) + Euler w' (y, -x, 0) - p''(t)); the seed's forcing enters as Q_{th_d} = sigma_d -
 * lambda_d th_d' (eq. 25-26) directly. 2D reduces to the seed's eq. 16-18 (the seed's eq. 15
 * second sum and the sign pattern of eq. 23/24 are misprinted; this is derived afresh); one link
 * in 3D gives th'' = ph'^2 sin th cos th - (g/l) sin th, ph'' = -2 th' ph' cot th (the seed's
 * eq. 43 prints + th' ph' cot th). Both closed forms are checked in tests/unit/dynamics/test_dynamics.c.
 * Tension of link i: T_i = u_i . sum_{k>=i} (F_k - m_k a_k), a_k relative to the pivot (force
 * balance of the part below).
 * Singular in 3D where sin th_i = 0 (the A_{ph ph} block degenerates): refused below
 * sin th_i = 1e-10. Solved by Cholesky (GSL). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "dynamics/dyn_internal.h"
#include "core/error.h"

#define SEED_SINGULAR_SIN 1e-10

static size_t seed_coords(const whirl_dyn *d) { return d->dim == 3 ? 2 * d->n : d->n; }

static int seed_alloc(whirl_dyn *d)
{
    size_t k = seed_coords(d);
    d->size = 2 * k;
    d->matrix = malloc(k * k * sizeof *d->matrix);
    d->gen_force = malloc(k * sizeof *d->gen_force);
    d->quad_acc = malloc(3 * d->n * sizeof *d->quad_acc);
    if (!d->matrix || !d->gen_force || !d->quad_acc) return GSL_ENOMEM;
    return GSL_SUCCESS;
}

typedef struct link_frame {
    double st, ct, sp, cp;
    double u[3], e_th[3], e_ph[3];
} link_frame;

static void frame_of(const whirl_dyn *d, const double *y, size_t i, link_frame *f)
{
    const double th = y[i], ph = d->dim == 3 ? y[d->n + i] : 0.0;
    f->st = sin(th);
    f->ct = cos(th);
    f->sp = d->dim == 3 ? sin(ph) : 0.0;
    f->cp = d->dim == 3 ? cos(ph) : 1.0;
    const double u[3] = {f->st * f->cp, f->st * f->sp, -f->ct};
    const double eth[3] = {f->ct * f->cp, f->ct * f->sp, f->st};
    const double eph[3] = {-f->sp, f->cp, 0};
    memcpy(f->u, u, sizeof u);
    memcpy(f->e_th, eth, sizeof eth);
    memcpy(f->e_ph, eph, sizeof eph);
}

static void rates_of(const whirl_dyn *d, const double *y, size_t i, double *th_dot, double *ph_dot)
{
    const size_t k = seed_coords(d);
    *th_dot = y[k + i];
    *ph_dot = d->dim == 3 ? y[k + d->n + i] : 0.0;
}

static void seed_link(const whirl_dyn *d, const double *y, size_t i, double *dv, double *ddot)
{
    const double l = d->model.chain->length[i];
    link_frame f;
    double thd, phd;
    frame_of(d, y, i, &f);
    rates_of(d, y, i, &thd, &phd);
    for (int k = 0; k < 3; k++) {
        dv[k] = l * f.u[k];
        ddot[k] = l * (thd * f.e_th[k] + phd * f.st * f.e_ph[k]);
    }
}

static int seed_from_links(whirl_dyn *d, const double *dv, const double *ddot, double *y)
{
    const size_t k = seed_coords(d), n = d->n;
    const double *len = d->model.chain->length;
    for (size_t i = 0; i < n; i++) {
        const double *a = dv + 3 * i, *b = ddot + 3 * i;
        const double rho = hypot(a[0], a[1]);
        y[i] = atan2(d->dim == 3 ? rho : a[0], -a[2]);
        if (d->dim == 3) {
            if (rho < SEED_SINGULAR_SIN * len[i])
                return whirl_fail(GSL_EINVAL,
                                  "link %zu is vertical: the seed's angles are singular there",
                                  i + 1);
            y[n + i] = atan2(a[1], a[0]);
        }
        link_frame f;
        frame_of(d, y, i, &f);
        y[k + i] = (f.e_th[0] * b[0] + f.e_th[1] * b[1] + f.e_th[2] * b[2]) / len[i];
        if (d->dim == 3) y[k + n + i] = (f.e_ph[0] * b[0] + f.e_ph[1] * b[1]) / (len[i] * f.st);
    }
    return GSL_SUCCESS;
}

/* The angles satisfy the constraints by construction. */
static int seed_project(whirl_dyn *d, double *y) { return GSL_SUCCESS; }

/* d->force <- the total non-constraint force F_k on every mass (3 per mass). */
static void total_forces(whirl_dyn *d, double t, const double *y)
{
    const whirl_model *m = &d->model;
    const double *mass = m->chain->mass;
    const double g = m->chain->gravity;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    const double w = dr.omega, dw = dr.domega;
    whirl_dyn_prepare_forces(d, t, y, 0);
    double p[3], pv[3], pa[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    for (size_t i = 0; i < d->n; i++) {
        double acc[3] = {-pa[0], -pa[1], -g - pa[2]};
        const double *xi = d->x + 3 * i, *vi = d->v + 3 * i;
        if (rotating) {
            acc[0] += w * w * xi[0] + 2 * w * vi[1] + dw * xi[1];
            acc[1] += w * w * xi[1] - 2 * w * vi[0] - dw * xi[0];
        }
        if (d->dim == 2) acc[1] = 0;
        for (int k = 0; k < 3; k++) d->force[3 * i + k] += mass[i] * acc[k];
    }
}

/* d->quad_acc <- alpha_k = sum_{j<=k} l_j c_j. */
static void quadratic_accelerations(whirl_dyn *d, const double *y)
{
    const double *len = d->model.chain->length;
    double sum[3] = {0, 0, 0};
    for (size_t i = 0; i < d->n; i++) {
        link_frame f;
        double thd, phd;
        frame_of(d, y, i, &f);
        rates_of(d, y, i, &thd, &phd);
        for (int k = 0; k < 3; k++) {
            const double c = -(thd * thd + phd * phd * f.st * f.st) * f.u[k] +
                             2 * thd * phd * f.ct * f.e_ph[k] - phd * phd * f.st * f.ct * f.e_th[k];
            sum[k] += len[i] * c;
            d->quad_acc[3 * i + k] = sum[k];
        }
    }
}

/* Solves A q'' = J^T (F - m alpha) + Q: q'' in d->gen_force. */
static int seed_accelerations(whirl_dyn *d, double t, const double *y)
{
    const whirl_model *m = &d->model;
    const double *len = m->chain->length, *mass = m->chain->mass;
    const size_t n = d->n, kc = seed_coords(d);
    for (size_t i = 0; i < n; i++) {
        if (d->dim == 3 && fabs(sin(y[i])) < SEED_SINGULAR_SIN)
            return whirl_fail(GSL_EBADFUNC,
                              "link %zu passes the vertical at t = %.17g: the seed's angles are "
                              "singular there",
                              i + 1, t);
    }
    total_forces(d, t, y);
    quadratic_accelerations(d, y);
    double s[3] = {0, 0, 0};
    for (size_t i = n; i-- > 0;) {
        link_frame f;
        frame_of(d, y, i, &f);
        for (int k = 0; k < 3; k++) s[k] += d->force[3 * i + k] - mass[i] * d->quad_acc[3 * i + k];
        d->gen_force[i] = len[i] * (f.e_th[0] * s[0] + f.e_th[1] * s[1] + f.e_th[2] * s[2]);
        if (d->dim == 3)
            d->gen_force[n + i] = len[i] * f.st * (f.e_ph[0] * s[0] + f.e_ph[1] * s[1]);
        if (d->dim == 2) {
            double thd, phd;
            rates_of(d, y, i, &thd, &phd);
            if (m->seed_sigma != NULL) d->gen_force[i] += m->seed_sigma[i];
            if (m->seed_lambda != NULL) d->gen_force[i] -= m->seed_lambda[i] * thd;
        }
    }
    for (size_t i = 0; i < n; i++) {
        link_frame fi;
        frame_of(d, y, i, &fi);
        for (size_t j = i; j < n; j++) {
            link_frame fj;
            frame_of(d, y, j, &fj);
            const double c = d->mass_below[j] * len[i] * len[j];
            /* cos(ph_i - ph_j), sin(ph_i - ph_j) */
            const double cd = fi.cp * fj.cp + fi.sp * fj.sp, sd = fi.sp * fj.cp - fi.cp * fj.sp;
            const double tt = c * (fi.ct * fj.ct * cd + fi.st * fj.st);
            d->matrix[i * kc + j] = d->matrix[j * kc + i] = tt;
            if (d->dim == 3) {
                const double pp = c * fi.st * fj.st * cd;
                const double tp = c * fi.ct * fj.st * sd;  /* A_{th_i ph_j} */
                const double pt = -c * fi.st * fj.ct * sd; /* A_{ph_i th_j} = A_{th_j ph_i} */
                d->matrix[(n + i) * kc + n + j] = d->matrix[(n + j) * kc + n + i] = pp;
                d->matrix[i * kc + n + j] = d->matrix[(n + j) * kc + i] = tp;
                d->matrix[(n + i) * kc + j] = d->matrix[j * kc + n + i] = pt;
            }
        }
    }
    gsl_matrix_view a = gsl_matrix_view_array(d->matrix, kc, kc);
    gsl_vector_view b = gsl_vector_view_array(d->gen_force, kc);
    int status = gsl_linalg_cholesky_decomp1(&a.matrix);
    if (status == GSL_SUCCESS) status = gsl_linalg_cholesky_svx(&a.matrix, &b.vector);
    if (status != GSL_SUCCESS)
        return whirl_fail(GSL_EBADFUNC, "the seed's mass matrix is singular at t = %.17g", t);
    return GSL_SUCCESS;
}

static int seed_rhs(whirl_dyn *d, double t, const double *y, double *dydt)
{
    const size_t kc = seed_coords(d);
    int status = seed_accelerations(d, t, y);
    if (status != GSL_SUCCESS) return status;
    memcpy(dydt, y + kc, kc * sizeof *dydt);
    memcpy(dydt + kc, d->gen_force, kc * sizeof *dydt);
    if (!whirl_dyn_all_finite(dydt, d->size))
        return whirl_fail(GSL_EBADFUNC, "the right-hand side is not finite at t = " WHIRL_Q_TIME
                          "%.17g", t);
    return GSL_SUCCESS;
}

static int seed_tensions(whirl_dyn *d, double t, const double *y, double *tension)
{
    const double *len = d->model.chain->length, *mass = d->model.chain->mass;
    const size_t n = d->n;
    int status = seed_accelerations(d, t, y);
    if (status != GSL_SUCCESS) return status;
    /* a_k = sum_{j<=k} l_j (th_j'' e_th + ph_j'' sin th_j e_ph) + alpha_k, relative to the pivot
     * (F holds the fictitious -m p''), then the force balance of the masses below each link,
     * summed from the tip */
    double acc[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        link_frame f;
        frame_of(d, y, i, &f);
        const double thdd = d->gen_force[i], phdd = d->dim == 3 ? d->gen_force[n + i] : 0.0;
        for (int k = 0; k < 3; k++) {
            acc[k] += len[i] * (thdd * f.e_th[k] + phdd * f.st * f.e_ph[k]);
            d->v[3 * i + k] = acc[k] + d->quad_acc[3 * i + k]; /* scratch: a_i */
        }
    }
    double s[3] = {0, 0, 0};
    for (size_t i = n; i-- > 0;) {
        link_frame f;
        frame_of(d, y, i, &f);
        for (int k = 0; k < 3; k++) s[k] += d->force[3 * i + k] - mass[i] * d->v[3 * i + k];
        tension[i] = f.u[0] * s[0] + f.u[1] * s[1] + f.u[2] * s[2];
    }
    return GSL_SUCCESS;
}

const dyn_ops whirl_dyn_seed_ops = {
    .link = seed_link,
    .from_links = seed_from_links,
    .rhs = seed_rhs,
    .project = seed_project,
    .tensions = seed_tensions,
    .alloc = seed_alloc,
};
