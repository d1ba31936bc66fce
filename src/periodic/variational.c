/* The monodromy from the variational equations (whirl/periodic.h): the state and m tangent
 * vectors integrated together by the Gauss method on the augmented system (y, Y_1..Y_m),
 * Y_j' = J(t, y) Y_j, with the derivative of the projection after every step. A Runge-Kutta
 * method applied to the augmented system is the derivative of the same method applied to the
 * system (Hairer, Norsett, Wanner, "Solving ODEs I", II.14), so this is the derivative of the
 * discrete period map, as the central differences of periodic.c are, without their error.
 *
 * J Y of the Cartesian formulation in the inertial frame without applied forces
 * (src/dynamics/dyn_cartesian.c): with k_i = 1/m_i + 1/m_{i-1} (1/m_{-1} = 0), the multipliers
 * solve the symmetric tridiagonal A lambda = b,
 *   A_ii = |d_i|^2 k_i,  A_{i,i+1} = A_{i+1,i} = -(d_i . d_{i+1}) / m_i,
 *   b_i = |d_i'|^2 + [i = 0] d_0 . (g - p''),
 * and d_i'' = -lambda_i k_i d_i + lambda_{i+1} d_{i+1} / m_i + lambda_{i-1} d_{i-1} / m_{i-1}
 * + [i = 0] (g - p''). Their variations: A delta lambda = delta b - (delta A) lambda with
 *   delta b_i = 2 d_i' . delta d_i' + [i = 0] delta d_0 . (g - p''),
 *   ((delta A) lambda)_i = 2 (d_i . delta d_i) k_i lambda_i
 *     - (delta d_i . d_{i+1} + d_i . delta d_{i+1}) lambda_{i+1} / m_i
 *     - (delta d_i . d_{i-1} + d_i . delta d_{i-1}) lambda_{i-1} / m_{i-1},
 * and delta d_i'' the product rule on d_i''. A is factored once per evaluation (Thomas: it is
 * positive definite, no pivoting) and solved for every tangent vector.
 * The projection d <- l d / |d|, d' <- d' - (D . d' / l^2) D (D the projected d) has the
 * derivative delta D = (l / |d|) (delta d - (d . delta d / |d|^2) d),
 * delta R = delta d' - ((delta D . d' + D . delta d') / l^2) D - (D . d' / l^2) delta D,
 * taken at the state before its projection. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "periodic/periodic_internal.h"

typedef struct vec3 {
    double x, y, z;
} vec3;

typedef struct var_system {
    whirl_periodic *w;
    size_t cols;            /* tangent vectors */
    size_t sh;              /* half of a state: dim N */
    size_t half;            /* half of the augmented state: sh (1 + cols) */
    double *base, *dbase;   /* a state and its derivative (size) */
    double *lam, *diag, *off, *den, *up; /* tridiagonal system and its factors (N each) */
    double *rhs;            /* N x cols: the variations of the multipliers */
    double *k, *inv_m;      /* k_i = 1/m_i + 1/m_{i-1}, 1/m_i (N each) */
    vec3 *d, *r, *dd; /* links, rates, a tangent vector's link part (N each) */
} var_system;

static inline double dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* Link i of the half-state q (dim components per link) as a 3-vector. */
static inline vec3 load(const var_system *s, const double *q, size_t i)
{
    if (s->w->dim == 3) return (vec3){q[3 * i], q[3 * i + 1], q[3 * i + 2]};
    return (vec3){q[2 * i], 0, q[2 * i + 1]};
}

static inline void store(const var_system *s, double *q, size_t i, vec3 v)
{
    if (s->w->dim == 3) {
        q[3 * i] = v.x, q[3 * i + 1] = v.y, q[3 * i + 2] = v.z;
    } else {
        q[2 * i] = v.x, q[2 * i + 1] = v.z;
    }
}

/* Solves A x = r in place (r -> x) with the factors of factor(): cols right-hand sides side by
 * side, r[i cols + c] (the columns are independent: the inner loop vectorises). */
static void solve(const var_system *s, double *r, size_t cols)
{
    const size_t n = s->w->n;
    const double *inv_den = s->den, *off = s->off, *up = s->up;
    for (size_t c = 0; c < cols; c++) r[c] *= inv_den[0];
    for (size_t i = 1; i < n; i++) {
        double *ri = r + i * cols;
        const double *rp = ri - cols;
        for (size_t c = 0; c < cols; c++) ri[c] = (ri[c] - off[i - 1] * rp[c]) * inv_den[i];
    }
    for (size_t i = n - 1; i-- > 0;) {
        double *ri = r + i * cols;
        const double *rn = ri + cols;
        for (size_t c = 0; c < cols; c++) ri[c] -= up[i] * rn[c];
    }
}

/* Thomas's factors of A: den holds the inverse pivots, up the upper factor. */
static void factor(var_system *s)
{
    const size_t n = s->w->n;
    double den = s->diag[0];
    s->den[0] = 1 / den;
    for (size_t i = 1; i < n; i++) {
        s->up[i - 1] = s->off[i - 1] / den;
        den = s->diag[i] - s->off[i - 1] * s->up[i - 1];
        s->den[i] = 1 / den;
    }
}

static int var_rhs(double t, const double y[], double dydt[], void *params)
{
    var_system *s = params;
    whirl_periodic *w = s->w;
    const size_t n = w->n, sh = s->sh, half = s->half;
    const double *mass = w->chain->mass;
    /* the state: its own right-hand side */
    memcpy(s->base, y, sh * sizeof *y);
    memcpy(s->base + sh, y + half, sh * sizeof *y);
    int status = whirl_dyn_rhs(t, s->base, s->dbase, w->dyn);
    if (status) return status;
    memcpy(dydt, y + half, half * sizeof *y); /* dq/dt = v, for the state and every vector */
    memcpy(dydt + half, s->dbase + sh, sh * sizeof *y);
    /* the links, their rates, k_i, 1/m_i and the multipliers, once per evaluation */
    double p[3], pv[3], pa[3];
    whirl_pivot_eval(t, p, pv, pa, &w->path);
    const vec3 field = {-pa[0], w->dim == 3 ? -pa[1] : 0, -w->chain->gravity - pa[2]};
    vec3 *d = s->d, *r = s->r;
    for (size_t i = 0; i < n; i++) {
        d[i] = load(s, s->base, i), r[i] = load(s, s->base + sh, i);
        s->inv_m[i] = 1 / mass[i];
        s->k[i] = s->inv_m[i] + (i > 0 ? s->inv_m[i - 1] : 0);
    }
    for (size_t i = 0; i < n; i++) {
        s->diag[i] = dot(d[i], d[i]) * s->k[i];
        if (i + 1 < n) s->off[i] = -dot(d[i], d[i + 1]) * s->inv_m[i];
        s->lam[i] = dot(r[i], r[i]) + (i == 0 ? dot(d[i], field) : 0);
    }
    factor(s);
    solve(s, s->lam, 1);
    const double *lam = s->lam, *k = s->k, *inv_m = s->inv_m;
    const size_t cols = s->cols;
    double *xs = s->rhs; /* N x cols: x[i cols + c] */
    vec3 *dd = s->dd;
    /* every tangent vector: the right-hand sides of delta lambda, one solve for all, then the
       accelerations */
    for (size_t c = 1; c <= cols; c++) {
        const double *dq = y + c * sh, *dv = y + half + c * sh;
        for (size_t i = 0; i < n; i++) dd[i] = load(s, dq, i);
        for (size_t i = 0; i < n; i++) {
            double v = 2 * dot(r[i], load(s, dv, i)) - 2 * dot(d[i], dd[i]) * k[i] * lam[i];
            if (i + 1 < n) v += (dot(dd[i], d[i + 1]) + dot(d[i], dd[i + 1])) * lam[i + 1] * inv_m[i];
            if (i > 0) v += (dot(dd[i], d[i - 1]) + dot(d[i], dd[i - 1])) * lam[i - 1] * inv_m[i - 1];
            xs[i * cols + (c - 1)] = v;
        }
        xs[c - 1] += dot(dd[0], field);
    }
    solve(s, xs, cols);
    for (size_t c = 1; c <= cols; c++) {
        const double *dq = y + c * sh;
        double *acc = dydt + half + c * sh;
        for (size_t i = 0; i < n; i++) dd[i] = load(s, dq, i);
        const double *x = xs + (c - 1);
        for (size_t i = 0; i < n; i++) {
            const double gs = -x[i * cols] * k[i], ls = -lam[i] * k[i];
            vec3 a = {gs * d[i].x + ls * dd[i].x, gs * d[i].y + ls * dd[i].y,
                      gs * d[i].z + ls * dd[i].z};
            if (i + 1 < n) {
                const double g = x[(i + 1) * cols] * inv_m[i], l = lam[i + 1] * inv_m[i];
                a.x += g * d[i + 1].x + l * dd[i + 1].x;
                a.y += g * d[i + 1].y + l * dd[i + 1].y;
                a.z += g * d[i + 1].z + l * dd[i + 1].z;
            }
            if (i > 0) {
                const double g = x[(i - 1) * cols] * inv_m[i - 1], l = lam[i - 1] * inv_m[i - 1];
                a.x += g * d[i - 1].x + l * dd[i - 1].x;
                a.y += g * d[i - 1].y + l * dd[i - 1].y;
                a.z += g * d[i - 1].z + l * dd[i - 1].z;
            }
            store(s, acc, i, a);
        }
    }
    for (size_t j = 0; j < half; j++)
        if (!isfinite(dydt[half + j]))
            return whirl_fail(GSL_EBADFUNC, "the variational equations are not finite at "
                              "t = %.17g", t);
    return GSL_SUCCESS;
}

static int var_project(double t, double y[], void *params)
{
    var_system *s = params;
    whirl_periodic *w = s->w;
    const size_t n = w->n, sh = s->sh, half = s->half;
    const double *len = w->chain->length;
    for (size_t i = 0; i < n; i++) {
        const vec3 d = load(s, y, i), r = load(s, y + half, i);
        const double l = len[i], nd2 = dot(d, d), sc = l / sqrt(nd2);
        const vec3 D = {sc * d.x, sc * d.y, sc * d.z};
        const double along = dot(D, r) / (l * l);
        for (size_t c = 1; c <= s->cols; c++) {
            const vec3 dd = load(s, y + c * sh, i), dr = load(s, y + half + c * sh, i);
            const double f = dot(d, dd) / nd2;
            const vec3 dD = {sc * (dd.x - f * d.x), sc * (dd.y - f * d.y), sc * (dd.z - f * d.z)};
            const double dal = (dot(dD, r) + dot(D, dr)) / (l * l);
            const vec3 dR = {dr.x - dal * D.x - along * dD.x, dr.y - dal * D.y - along * dD.y,
                             dr.z - dal * D.z - along * dD.z};
            store(s, y + c * sh, i, dD);
            store(s, y + half + c * sh, i, dR);
        }
    }
    /* the state: the dynamics' own projection, as in the motion */
    memcpy(s->base, y, sh * sizeof *y);
    memcpy(s->base + sh, y + half, sh * sizeof *y);
    const int status = whirl_dyn_project(w->dyn, t, s->base);
    memcpy(y, s->base, sh * sizeof *y);
    memcpy(y + half, s->base + sh, sh * sizeof *y);
    return status;
}

int periodic_monodromy_variational(whirl_periodic *w, const double *y, int steps)
{
    const size_t m = w->m, sh = w->size / 2, n = w->n;
    var_system s = {.w = w, .cols = m, .sh = sh, .half = sh * (1 + m)};
    const size_t total = 2 * s.half;
    double *aug = malloc(total * sizeof *aug);
    double *work = malloc((2 * w->size + 7 * n + n * m) * sizeof *work);
    vec3 *links = malloc(3 * n * sizeof *links);
    if (aug == NULL || work == NULL || links == NULL) {
        free(aug), free(work), free(links);
        return whirl_fail(GSL_ENOMEM, "out of memory for the variational equations (%zu "
                          "doubles)", total);
    }
    s.base = work, s.dbase = work + w->size;
    s.lam = work + 2 * w->size, s.diag = s.lam + n, s.off = s.diag + n, s.den = s.off + n;
    s.up = s.den + n, s.k = s.up + n, s.inv_m = s.k + n, s.rhs = s.inv_m + n;
    s.d = links, s.r = links + n, s.dd = links + 2 * n;
    w->have_mono = 0;
    periodic_basis(w, y);
    memcpy(aug, y, sh * sizeof *y);
    memcpy(aug + s.half, y + sh, sh * sizeof *y);
    double *x = w->vec, *vec = w->scratch + w->size, *zero = w->scratch + 2 * w->size;
    memset(zero, 0, w->size * sizeof *zero);
    for (size_t j = 0; j < m; j++) {
        memset(x, 0, m * sizeof *x);
        x[j] = 1;
        periodic_tangent_add(w, y, x, vec); /* y + t_j: the vector t_j at y */
        for (size_t k = 0; k < w->size; k++) vec[k] -= y[k];
        memcpy(aug + (j + 1) * sh, vec, sh * sizeof *vec);
        memcpy(aug + s.half + (j + 1) * sh, vec + sh, sh * sizeof *vec);
    }
    const whirl_system sys = {.rhs = var_rhs, .project = var_project, .size = total,
                              .params = &s, .second_order = 1,
                              .acceleration_scale = w->chain->gravity};
    whirl_integrator *it = whirl_integrator_alloc_system(whirl_integrator_gauss2, &sys);
    int status = it ? GSL_SUCCESS : whirl_last_status();
    /* the period in 16 pieces of whole steps, for the progress display (a piece ends at
       k h exactly as the steps of one advance would: the same fixed steps) */
    const double period = whirl_pivot_period(&w->path), h = period / steps;
    const int pieces = steps < 16 ? steps : 16;
    double t = 0;
    for (int k = 1; k <= pieces && status == GSL_SUCCESS; k++) {
        const long end = (long)steps * k / pieces;
        status = whirl_integrator_advance(it, &t, aug, k == pieces ? period : (double)end * h, h, 0);
        periodic_tick(w, (double)k / pieces);
    }
    whirl_integrator_free(it);
    if (status == GSL_SUCCESS) {
        double *col = w->vec + m;
        for (size_t j = 0; j < m; j++) {
            memcpy(vec, aug + (j + 1) * sh, sh * sizeof *vec);
            memcpy(vec + sh, aug + s.half + (j + 1) * sh, sh * sizeof *vec);
            periodic_tangent_read(w, zero, vec, col);
            for (size_t i = 0; i < m; i++) w->mono[i * m + j] = col[i];
        }
        w->have_mono = 1;
    }
    free(aug), free(work), free(links);
    return status;
}
