/* The dissipative forces of the periodic motions (whirl_periodic_alloc_model) and their
 * Jacobian, for the variational equations (variational.c).
 *
 * The forces are whirl_model's (include/whirl/dynamics.h, src/dynamics/dynamics.c), in the
 * inertial frame with the pivot on the path:
 *   air drag on mass i:  f_i = -l_i (c + c2 |v_i|) v_i,  v_i = p'(t) + sum_{j <= i} d_j',
 *   internal damping:    W_i = (d_i' - omega z x d_i) / l_i,  J_i = D (W_i - W_{i-1}) (W_{-1} = 0),
 *                        G_i = (J_i - J_{i+1}) / l_i (J_N = 0),  f_i -= G_i - G_{i+1} (G_N = 0),
 * omega the path's rate (the frame of the internal damping: the steady rotation of the circle
 * drive costs nothing). In 2D the y components are dropped. The Cartesian formulation takes them
 * as fdiff_i = f_i / m_i - f_{i-1} / m_{i-1} (src/dynamics/dyn_cartesian.c): added to link i's
 * acceleration and, as d_i . fdiff_i, to the right-hand side of the tension system.
 *
 * Their derivative along a tangent vector (delta d, delta d'):
 *   drag:  delta f_i = -l_i (a_i delta v_i + u_i (u_i . delta v_i)),  delta v_i =
 *          sum_{j <= i} delta d_j',  a_i = c + c2 |v_i|,  u_i = sqrt(c2 / |v_i|) v_i,
 * from d(|v| v) = |v| dv + v (v . dv) / |v| (u_i = 0 at v_i = 0, where |v| v has the derivative 0);
 * the internal damping is linear in (d, d'): its derivative is the same sweeps applied to
 * (delta d, delta d'). tests/unit/periodic/test_periodic_dissipative.c checks both against central
 * differences of these forces and of whirl_dyn_rhs. */
#include <math.h>
#include <string.h>

#include "periodic/periodic_internal.h"

/* Component k (0..2) of link i in a dim-per-link array (2D: x, z). */
static size_t at(int dim, size_t i, int k)
{
    return dim == 3 ? 3 * i + (size_t)k : 2 * i + (k == 2);
}

void periodic_diss_forces(const whirl_periodic *w, double t, const double *y, double *fdiff,
                          double *a, double *u)
{
    const size_t n = w->n, sh = w->size / 2;
    const int dim = w->dim;
    const double *len = w->chain->length, *mass = w->chain->mass, om = w->path.omega;
    const double D = w->damping, c = w->drag, c2 = w->drag2;
    double p[3], pv[3], pa[3];
    whirl_pivot_eval(t, p, pv, pa, (void *)&w->path);
    double *f = fdiff; /* the forces first, then their differences in place */
    double wprev[3] = {0, 0, 0}, vel[3] = {pv[0], dim == 3 ? pv[1] : 0, pv[2]};
    for (size_t i = 0; i < n; i++) {
        double d[3], r[3];
        for (int k = 0; k < 3; k++) {
            const int skip = dim == 2 && k == 1;
            d[k] = skip ? 0 : y[at(dim, i, k)];
            r[k] = skip ? 0 : y[sh + at(dim, i, k)];
        }
        const double wc[3] = {(r[0] + om * d[1]) / len[i], (r[1] - om * d[0]) / len[i],
                              r[2] / len[i]};
        for (int k = 0; k < 3; k++) {
            f[3 * i + k] = D * (wc[k] - wprev[k]);
            wprev[k] = wc[k];
            vel[k] += r[k];
        }
        const double speed = sqrt(vel[0] * vel[0] + vel[1] * vel[1] + vel[2] * vel[2]);
        a[i] = c + c2 * speed;
        const double su = speed > 0 ? sqrt(c2 / speed) : 0;
        for (int k = 0; k < 3; k++) u[3 * i + k] = su * vel[k];
    }
    for (int sweep = 0; sweep < 2; sweep++)
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                const double next = i + 1 < n ? f[3 * (i + 1) + k] : 0.0;
                const double diff = f[3 * i + k] - next;
                f[3 * i + k] = sweep == 0 ? diff / len[i] : -diff;
            }
    vel[0] = pv[0], vel[1] = dim == 3 ? pv[1] : 0, vel[2] = pv[2];
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            const int skip = dim == 2 && k == 1;
            vel[k] += skip ? 0 : y[sh + at(dim, i, k)];
        }
        for (int k = 0; k < 3; k++) f[3 * i + k] -= len[i] * a[i] * vel[k];
        if (dim == 2) f[3 * i + 1] = 0;
    }
    for (size_t i = n; i-- > 0;)
        for (int k = 0; k < 3; k++)
            f[3 * i + k] = f[3 * i + k] / mass[i] - (i > 0 ? f[3 * (i - 1) + k] / mass[i - 1] : 0);
}

/* The most tangent vectors periodic_diss_apply takes at once (its scratch is on the stack). */
#define COLS_MAX 16

void periodic_diss_apply(const whirl_periodic *w, const double *a, const double *u,
                         const double *dq, const double *dv, size_t cols, double *out)
{
    const size_t n = w->n, dim = (size_t)w->dim, nc = cols;
    const double *len = w->chain->length, *mass = w->chain->mass, om = w->path.omega;
    const double D = w->damping;
    double *f = out; /* 3 n x cols: [(3 i + k) cols + col] */
    /* the state's component of axis k (2D: x and z only; y is 0) */
    const int slot[3] = {0, dim == 3 ? 1 : -1, dim == 3 ? 2 : 1};
    if (D > 0) { /* the internal damping: J_i, then G_i, then the forces, in place */
        double wprev[3][COLS_MAX] = {{0}};
        for (size_t i = 0; i < n; i++) {
            const double il = 1 / len[i];
            const double *qx = dq + (dim * i) * nc, *rx = dv + (dim * i) * nc;
            const double *qy = dim == 3 ? qx + nc : NULL, *ry = dim == 3 ? rx + nc : NULL;
            const double *rz = dv + (dim * i + (size_t)slot[2]) * nc;
            double *fx = f + 3 * i * nc, *fy = fx + nc, *fz = fy + nc;
            for (size_t c = 0; c < nc; c++) {
                const double wx = (rx[c] + (qy ? om * qy[c] : 0)) * il;
                const double wy = ((ry ? ry[c] : 0) - om * qx[c]) * il, wz = rz[c] * il;
                fx[c] = D * (wx - wprev[0][c]), fy[c] = D * (wy - wprev[1][c]);
                fz[c] = D * (wz - wprev[2][c]);
                wprev[0][c] = wx, wprev[1][c] = wy, wprev[2][c] = wz;
            }
        }
        for (size_t i = 0; i < n; i++) { /* G_i = (J_i - J_{i+1}) / l_i */
            const double il = 1 / len[i];
            double *fi = f + 3 * i * nc;
            for (size_t r = 0; r < 3 * nc; r++) fi[r] = (fi[r] - (i + 1 < n ? fi[r + 3 * nc] : 0)) * il;
        }
        for (size_t i = 0; i < n; i++) { /* f_i = -(G_i - G_{i+1}) */
            double *fi = f + 3 * i * nc;
            for (size_t r = 0; r < 3 * nc; r++) fi[r] = (i + 1 < n ? fi[r + 3 * nc] : 0) - fi[r];
        }
    } else {
        memset(f, 0, 3 * n * nc * sizeof *f);
    }
    if (w->drag > 0 || w->drag2 > 0) { /* the drag: delta v_i summed from the top */
        double dvel[3][COLS_MAX] = {{0}}, along[COLS_MAX];
        for (size_t i = 0; i < n; i++) {
            const double *ui = u + 3 * i, l = len[i], ai = a[i];
            for (int k = 0; k < 3; k++) {
                if (slot[k] < 0) continue;
                const double *r = dv + (dim * i + (size_t)slot[k]) * nc;
                for (size_t c = 0; c < nc; c++) dvel[k][c] += r[c];
            }
            for (size_t c = 0; c < nc; c++)
                along[c] = ui[0] * dvel[0][c] + ui[1] * dvel[1][c] + ui[2] * dvel[2][c];
            for (int k = 0; k < 3; k++) {
                double *fk = f + (3 * i + (size_t)k) * nc;
                for (size_t c = 0; c < nc; c++) fk[c] -= l * (ai * dvel[k][c] + ui[k] * along[c]);
            }
        }
    }
    if (dim == 2) /* no y force in the plane */
        for (size_t i = 0; i < n; i++) memset(f + (3 * i + 1) * nc, 0, nc * sizeof *f);
    for (size_t i = n; i-- > 0;) { /* fdiff_i = f_i / m_i - f_{i-1} / m_{i-1}, from the tip up */
        double *fi = f + 3 * i * nc;
        const double im = 1 / mass[i], ip = i > 0 ? 1 / mass[i - 1] : 0;
        for (size_t r = 0; r < 3 * nc; r++) fi[r] = fi[r] * im - (i > 0 ? fi[r - 3 * nc] * ip : 0);
    }
}
