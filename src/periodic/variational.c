/* The monodromy from the variational equations (whirl/periodic.h): the state and m tangent
 * vectors integrated together by the Gauss method (gauss2) on the augmented system
 * (y, Y_1..Y_m), Y_j' = J(t, y) Y_j, with the derivative of the projection after every step. A
 * Runge-Kutta method applied to the augmented system is the derivative of the same method
 * applied to the system (Hairer, Norsett, Wanner, "Solving ODEs I", II.14), so this is the
 * derivative of the discrete period map, as the central differences of periodic.c are, without
 * their error.
 *
 * The step, as src/integrate/integrator_gauss.c takes it (second-order form, stage
 * accelerations K_i, fixed-point sweeps to round-off, Kahan's compensated update), but with
 * the augmented system's structure used: the stage equations of the tangent vectors,
 *   dK_i = J_i (dq + c_i h dv + h^2 sum_j (A^2)_ij dK_j,  dv + h sum_j a_ij dK_j),
 * are linear with J_i the Jacobian at the state's stage i: the state's stages are converged
 * first (its own sweeps, O(N) each), then J_i's coefficients are formed once per stage and step
 * (the tridiagonal factors below included) and shared by every vector. The vectors are swept in
 * blocks of VAR_BLOCK side by side (the block's component r of vector c at [r VAR_BLOCK + c]:
 * the inner loops run over the block and vectorise), each block to its own round-off, its
 * working set in the cache. Equal to the former sweeps of the whole augmented system to
 * round-off: the largest difference of a monodromy entry over its matrix's largest entry was
 * below 1e-13 on the vertically shaken chain (N = 3, 5, 30; 2D and 3D) and the circle drive
 * (N = 5, 10), docs/theory/floquet.md.
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
 * and delta d_i'' the product rule on d_i''. A is factored once per stage (Thomas: it is
 * positive definite, no pivoting) and solved for every tangent vector.
 * The projection d <- l d / |d|, d' <- d' - (D . d' / l^2) D (D the projected d) has the
 * derivative delta D = (l / |d|) (delta d - (d . delta d / |d|^2) d),
 * delta R = delta d' - ((delta D . d' + D . delta d') / l^2) D - (D . d' / l^2) delta D,
 * taken at the state before its projection.
 * With damping and drag (whirl_periodic_alloc_model) the forces enter as fdiff_i (dissipation.c):
 * b_i gains d_i . fdiff_i and d_i'' gains fdiff_i, so delta b_i gains delta d_i . fdiff_i +
 * d_i . delta fdiff_i and delta d_i'' gains delta fdiff_i, with delta fdiff from the forces'
 * Jacobian (dissipation.c) per tangent vector. Without them nothing of this is computed. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "periodic/periodic_internal.h"

#define S 2          /* stages of gauss2 */
#define VAR_BLOCK 8  /* tangent vectors swept together: 8 doubles, a cache line */
#define SWEEPS_MAX 400 /* as integrator_gauss.c */

/* The coefficients of J at one stage, per link component (dim N, the state's layout) or per
 * link (N): delta lambda's right-hand side
 *   x_i = sum_k cr_ik dv_ik + cs_ik dq_ik + cu_ik dq_{i+1,k} + cl_ik dq_{i-1,k},
 * then A x = that, then the acceleration
 *   dK_ik = gx_ik x_i + sq_i dq_ik + gxu_ik x_{i+1} + squ_i dq_{i+1,k} + gxl_ik x_{i-1}
 *           + sql_i dq_{i-1,k},
 * the neighbours' coefficients 0 past the ends. */
typedef struct var_stage {
    double *cr, *cs, *cu, *cl, *gx, *gxu, *gxl; /* dim N each */
    double *sq, *squ, *sql, *den, *up, *off;    /* N each: and Thomas's factors of A */
    double *q, *fd, *da, *du; /* dissipation: the stage's links (dim N), fdiff (3 N), the drag's
                                 Jacobian factors a (N) and u (3 N) (dissipation.c) */
} var_stage;

struct periodic_var {
    size_t n, dim, sh, m, blocks;
    double c[S], a[S][S], a2[S][S], b[S], bq[S], extrap[S][S];
    double *k, *k_new, *y, *stage, *f, *comp, *pre; /* the state: S sh, S sh, size x 5 */
    double *lam, *diag, *kk, *inv_m;            /* N each */
    var_stage st[S];
    double *tan, *tcomp;  /* blocks x 2 sh x VAR_BLOCK: the tangent vectors, Kahan's terms */
    double *dk;           /* blocks x S x sh x VAR_BLOCK: their stages (kept for the guess) */
    double *dk_new;       /* S x sh x VAR_BLOCK */
    double *dq, *dv;      /* (sh + 2 dim) x VAR_BLOCK: a stage's argument, a zero link each end */
    double *x;            /* (N + 2) x VAR_BLOCK: delta lambda, a zero row each end */
    double *df;           /* dissipation: 3 N x VAR_BLOCK, delta fdiff */
    double *mem;          /* the one allocation */
};

void periodic_var_free(periodic_var *v)
{
    if (v == NULL) return;
    free(v->mem);
    free(v);
}

/* gauss2's tableau (integrator_gauss.c), in long double then rounded. */
static void tableau(periodic_var *v)
{
    const long double r = sqrtl(3.0L) / 6, c[S] = {0.5L - r, 0.5L + r};
    const long double a[S][S] = {{0.25L, 0.25L - r}, {0.25L + r, 0.25L}};
    for (int i = 0; i < S; i++) {
        v->c[i] = (double)c[i];
        v->b[i] = 0.5;
        v->bq[i] = (double)(0.5L * (1 - c[i]));
        for (int j = 0; j < S; j++) {
            v->a[i][j] = (double)a[i][j];
            v->a2[i][j] = (double)(a[i][0] * a[0][j] + a[i][1] * a[1][j]);
            /* Lagrange basis polynomial j of the nodes at 1 + c_i */
            v->extrap[i][j] = (double)((1 + c[i] - c[1 - j]) / (c[j] - c[1 - j]));
        }
    }
}

static periodic_var *var_alloc(const whirl_periodic *w)
{
    periodic_var *v = calloc(1, sizeof *v);
    if (v == NULL) return NULL;
    v->n = w->n, v->dim = (size_t)w->dim, v->sh = w->size / 2, v->m = w->m;
    v->blocks = (w->m + VAR_BLOCK - 1) / VAR_BLOCK;
    const size_t n = v->n, sh = v->sh, B = VAR_BLOCK, nb = v->blocks;
    const size_t total = 2 * S * sh + 5 * w->size + 4 * n + S * (7 * sh + 6 * n) +
                         2 * nb * 2 * sh * B + nb * S * sh * B + S * sh * B +
                         2 * (sh + 2 * v->dim) * B + (n + 2) * B +
                         (w->dissipative ? S * (sh + 7 * n) + 3 * n * B : 0);
    v->mem = calloc(total, sizeof *v->mem);
    if (v->mem == NULL) {
        free(v);
        return NULL;
    }
    double *p = v->mem;
#define TAKE(ptr, count) (ptr = p, p += (count))
    TAKE(v->k, S * sh), TAKE(v->k_new, S * sh), TAKE(v->y, w->size), TAKE(v->stage, w->size), TAKE(v->f, w->size);
    TAKE(v->comp, w->size), TAKE(v->pre, w->size);
    TAKE(v->lam, n), TAKE(v->diag, n), TAKE(v->kk, n), TAKE(v->inv_m, n);
    for (int i = 0; i < S; i++) {
        var_stage *s = &v->st[i];
        TAKE(s->cr, sh), TAKE(s->cs, sh), TAKE(s->cu, sh), TAKE(s->cl, sh), TAKE(s->gx, sh);
        TAKE(s->gxu, sh), TAKE(s->gxl, sh);
        TAKE(s->sq, n), TAKE(s->squ, n), TAKE(s->sql, n), TAKE(s->den, n), TAKE(s->up, n);
        TAKE(s->off, n);
    }
    TAKE(v->tan, nb * 2 * sh * B), TAKE(v->tcomp, nb * 2 * sh * B), TAKE(v->dk, nb * S * sh * B);
    TAKE(v->dk_new, S * sh * B), TAKE(v->dq, (sh + 2 * v->dim) * B);
    TAKE(v->dv, (sh + 2 * v->dim) * B), TAKE(v->x, (n + 2) * B);
    if (w->dissipative) {
        for (int i = 0; i < S; i++) {
            var_stage *s = &v->st[i];
            TAKE(s->q, sh), TAKE(s->fd, 3 * n), TAKE(s->da, n), TAKE(s->du, 3 * n);
        }
        TAKE(v->df, 3 * n * B);
    }
#undef TAKE
    tableau(v);
    return v;
}

/* Thomas's factors of A (diag, s->off): s->den the inverse pivots, s->up the upper factor. */
static void factor(const periodic_var *v, var_stage *s)
{
    double den = v->diag[0];
    s->den[0] = 1 / den;
    for (size_t i = 1; i < v->n; i++) {
        s->up[i - 1] = s->off[i - 1] / den;
        den = v->diag[i] - s->off[i - 1] * s->up[i - 1];
        s->den[i] = 1 / den;
    }
}

/* Solves A x = r in place with s's factors, cols right-hand sides side by side (r[i cols + c]). */
static void solve(const periodic_var *v, const var_stage *s, double *r, size_t cols)
{
    const size_t n = v->n;
    for (size_t c = 0; c < cols; c++) r[c] *= s->den[0];
    for (size_t i = 1; i < n; i++) {
        double *ri = r + i * cols;
        const double *rp = ri - cols, o = s->off[i - 1], d = s->den[i];
        for (size_t c = 0; c < cols; c++) ri[c] = (ri[c] - o * rp[c]) * d;
    }
    for (size_t i = n - 1; i-- > 0;) {
        double *ri = r + i * cols;
        const double *rn = ri + cols, u = s->up[i];
        for (size_t c = 0; c < cols; c++) ri[c] -= u * rn[c];
    }
}

/* J's coefficients at the stage state y (size) at time t into s. */
static void stage_coefficients(whirl_periodic *w, periodic_var *v, var_stage *s, double t,
                               const double *y)
{
    const size_t n = v->n, dim = v->dim;
    const double *q = y, *r = y + v->sh, *mass = w->chain->mass;
    double p[3], pv[3], pa[3];
    whirl_pivot_eval(t, p, pv, pa, &w->path);
    const double f3[3] = {-pa[0], -pa[1], -w->chain->gravity - pa[2]};
    const double field[3] = {f3[0], dim == 3 ? f3[1] : f3[2], f3[2]};
    for (size_t i = 0; i < n; i++) {
        v->inv_m[i] = 1 / mass[i];
        v->kk[i] = v->inv_m[i] + (i > 0 ? v->inv_m[i - 1] : 0);
    }
    if (w->dissipative) {
        memcpy(s->q, q, v->sh * sizeof *q);
        periodic_diss_forces(w, t, y, s->fd, s->da, s->du);
    }
    for (size_t i = 0; i < n; i++) {
        double dd = 0, rr = 0, dn = 0, df = 0;
        for (size_t k = 0; k < dim; k++) {
            const double di = q[dim * i + k];
            dd += di * di, rr += r[dim * i + k] * r[dim * i + k], df += di * field[k];
            if (i + 1 < n) dn += di * q[dim * (i + 1) + k];
        }
        v->diag[i] = dd * v->kk[i];
        if (i + 1 < n) s->off[i] = -dn * v->inv_m[i];
        v->lam[i] = rr + (i == 0 ? df : 0);
        if (w->dissipative) /* d_i . fdiff_i (2D: x, z) */
            for (size_t k = 0; k < dim; k++)
                v->lam[i] += q[dim * i + k] * s->fd[3 * i + (dim == 3 ? k : 2 * k)];
    }
    factor(v, s);
    solve(v, s, v->lam, 1);
    const double *lam = v->lam, *kk = v->kk, *im = v->inv_m;
    for (size_t i = 0; i < n; i++) {
        const double up = i + 1 < n ? lam[i + 1] * im[i] : 0;
        const double lo = i > 0 ? lam[i - 1] * im[i - 1] : 0;
        s->sq[i] = -lam[i] * kk[i], s->squ[i] = up, s->sql[i] = lo;
        for (size_t k = 0; k < dim; k++) {
            const size_t e = dim * i + k;
            const double dn = i + 1 < n ? q[e + dim] : 0, dp = i > 0 ? q[e - dim] : 0;
            s->cr[e] = 2 * r[e];
            s->cs[e] = -2 * kk[i] * lam[i] * q[e] + up * dn + lo * dp + (i == 0 ? field[k] : 0);
            if (w->dissipative) s->cs[e] += s->fd[3 * i + (dim == 3 ? k : 2 * k)];
            s->cu[e] = up * q[e], s->cl[e] = lo * q[e];
            s->gx[e] = -kk[i] * q[e];
            s->gxu[e] = i + 1 < n ? dn * im[i] : 0;
            s->gxl[e] = i > 0 ? dp * im[i - 1] : 0;
        }
    }
}

/* out (sh x VAR_BLOCK) <- J of stage s applied to v->dq, v->dv (VAR_BLOCK vectors); w's
 * dissipation (NULL: none). */
static void apply_j(const whirl_periodic *w, const periodic_var *v, const var_stage *s,
                    double *out)
{
    enum { B = VAR_BLOCK };
    const size_t n = v->n, dim = v->dim;
    const double *dq = v->dq + dim * B, *dv = v->dv + dim * B; /* past the zero link */
    double *x = v->x + B;                                       /* past the zero row */
    if (w != NULL) periodic_diss_apply(w, s->da, s->du, dq, dv, B, v->df);
    for (size_t i = 0; i < n; i++) {
        double xi[B] = {0};
        for (size_t k = 0; k < dim; k++) {
            const size_t e = dim * i + k;
            const double *q = dq + e * B, *qv = dv + e * B;
            const double cr = s->cr[e], cs = s->cs[e], cu = s->cu[e], cl = s->cl[e];
#pragma omp simd
            for (size_t c = 0; c < B; c++)
                xi[c] += cr * qv[c] + cs * q[c] + cu * q[c + dim * B] + cl * q[c - dim * B];
            if (w != NULL) { /* d_i . delta fdiff_i */
                const double qe = s->q[e], *dfk = v->df + (3 * i + (dim == 3 ? k : 2 * k)) * B;
                for (size_t c = 0; c < B; c++) xi[c] += qe * dfk[c];
            }
        }
        memcpy(x + i * B, xi, sizeof xi);
    }
    solve(v, s, x, B);
    for (size_t i = 0; i < n; i++) {
        const double sq = s->sq[i], squ = s->squ[i], sql = s->sql[i];
        const double *xi = x + i * B;
        for (size_t k = 0; k < dim; k++) {
            const size_t e = dim * i + k;
            const double *q = dq + e * B;
            const double gx = s->gx[e], gxu = s->gxu[e], gxl = s->gxl[e];
            double *o = out + e * B;
#pragma omp simd
            for (size_t c = 0; c < B; c++)
                o[c] = gx * xi[c] + sq * q[c] + gxu * xi[c + B] + squ * q[c + dim * B] +
                       gxl * xi[c - B] + sql * q[c - dim * B];
            if (w != NULL) {
                const double *dfk = v->df + (3 * i + (dim == 3 ? k : 2 * k)) * B;
                for (size_t c = 0; c < B; c++) o[c] += dfk[c];
            }
        }
    }
}

/* v->dq, v->dv <- stage i's argument from the block's vectors tan and stages dk. */
static void stage_argument(const periodic_var *v, int i, double h, const double *tan,
                           const double *dk)
{
    const size_t len = v->sh * VAR_BLOCK;
    const double *tq = tan, *tv = tan + len, *k0 = dk, *k1 = dk + len;
    const double cq = v->c[i] * h, q0 = h * h * v->a2[i][0], q1 = h * h * v->a2[i][1];
    const double v0 = h * v->a[i][0], v1 = h * v->a[i][1];
    double *dq = v->dq + v->dim * VAR_BLOCK, *dv = v->dv + v->dim * VAR_BLOCK;
#pragma omp simd
    for (size_t r = 0; r < len; r++) {
        dq[r] = tq[r] + cq * tv[r] + q0 * k0[r] + q1 * k1[r];
        dv[r] = tv[r] + v0 * k0[r] + v1 * k1[r];
    }
}

/* The stages of one block of tangent vectors (tan: 2 sh x VAR_BLOCK; dk: S x sh x VAR_BLOCK,
 * the previous step's stages, or first 1 for none; diss the dissipative workspace or NULL)
 * swept to round-off, then the block
 * advanced by the step with Kahan's compensation (tcomp). */
static int block_step(const whirl_periodic *diss, periodic_var *v, double t, double h,
                      double *tan, double *tcomp, double *dk, int first)
{
    const size_t len = v->sh * VAR_BLOCK;
    if (first) { /* J_i at the step's start values */
        const double *tq = tan, *tv = tan + len;
        memcpy(v->dq + v->dim * VAR_BLOCK, tq, len * sizeof *tq);
        memcpy(v->dv + v->dim * VAR_BLOCK, tv, len * sizeof *tv);
        for (int i = 0; i < S; i++) apply_j(diss, v, &v->st[i], dk + i * len);
    } else { /* the previous step's collocation polynomial extrapolated */
        for (size_t r = 0; r < len; r++) {
            const double k0 = dk[r], k1 = dk[len + r];
            dk[r] = v->extrap[0][0] * k0 + v->extrap[0][1] * k1;
            dk[len + r] = v->extrap[1][0] * k0 + v->extrap[1][1] * k1;
        }
    }
    double prev = INFINITY, best = INFINITY;
    int converged = 0;
    for (int sweep = 0; sweep < SWEEPS_MAX && !converged; sweep++) {
        /* stage by stage, each new stage used at once by the next (Gauss-Seidel): the same
           fixed point, in fewer sweeps than with the previous sweep's stages (Jacobi) */
        double delta = 0, big = 0, *nk = v->dk_new;
        for (int i = 0; i < S; i++) {
            stage_argument(v, i, h, tan, dk);
            apply_j(diss, v, &v->st[i], nk);
            double *ki = dk + i * len;
            /* the increment's and the stages' sizes (1-norms: a sum vectorises, a maximum does
               not here) */
#pragma omp simd reduction(+ : delta, big)
            for (size_t r = 0; r < len; r++) {
                delta += fabs(nk[r] - ki[r]);
                big += fabs(nk[r]);
                ki[r] = nk[r];
            }
        }
        if (!(big < INFINITY) || !(delta < INFINITY))
            return whirl_fail(GSL_EBADFUNC, "the variational equations are not finite at "
                              "t = %.17g", t);
        /* the equations are linear: the increments shrink by rho per sweep and the iterate's
           error is about delta rho / (1 - rho); below a unit of round-off of the block it is
           converged (or, as integrator_gauss.c, when the increments stop decreasing) */
        const double rho = prev < INFINITY ? delta / prev : 1; /* none after one sweep */
        if (delta == 0 || (rho < 1 && delta * rho <= (1 - rho) * DBL_EPSILON * big) ||
            (delta >= prev && prev <= 1e-8 * big))
            converged = 1;
        else if (!(delta <= 1e3 * best))
            return whirl_fail(GSL_EMAXITER, "the variational equations' stage iteration "
                              "diverges at t = %.17g (step %g)", t, h);
        best = fmin(best, delta), prev = delta;
    }
    if (!converged)
        return whirl_fail(GSL_EMAXITER, "the variational equations' stage iteration did not "
                          "converge in %d sweeps at t = %.17g", SWEEPS_MAX, t);
    double *tq = tan, *tv = tan + len, *cq = tcomp, *cv = tcomp + len;
    const double *k0 = dk, *k1 = dk + len;
    for (size_t r = 0; r < len; r++) {
        const double iq = h * (tv[r] + h * (v->bq[0] * k0[r] + v->bq[1] * k1[r]));
        const double iv = h * (v->b[0] * k0[r] + v->b[1] * k1[r]);
        const double aq = iq + cq[r], sq = tq[r] + aq;
        cq[r] = (tq[r] - sq) + aq, tq[r] = sq;
        const double av = iv + cv[r], sv = tv[r] + av;
        cv[r] = (tv[r] - sv) + av, tv[r] = sv;
    }
    return GSL_SUCCESS;
}

/* The derivative of the projection (file header) on one block, at the state pre (before its
 * projection). */
static void block_project(const whirl_periodic *w, const periodic_var *v, const double *pre,
                          double *tan)
{
    enum { B = VAR_BLOCK };
    const size_t dim = v->dim, len = v->sh * B;
    for (size_t i = 0; i < v->n; i++) {
        const double *d = pre + dim * i, *r = pre + v->sh + dim * i, l = w->chain->length[i];
        double nd2 = 0;
        for (size_t k = 0; k < dim; k++) nd2 += d[k] * d[k];
        const double sc = l / sqrt(nd2), l2 = l * l;
        double dr = 0;
        for (size_t k = 0; k < dim; k++) dr += sc * d[k] * r[k];
        const double along = dr / l2;
        double *q = tan + dim * i * B, *u = tan + len + dim * i * B;
        double f[B] = {0}, dal[B] = {0};
        for (size_t k = 0; k < dim; k++)
            for (size_t c = 0; c < B; c++) f[c] += d[k] * q[k * B + c] / nd2;
        for (size_t k = 0; k < dim; k++)
            for (size_t c = 0; c < B; c++) {
                q[k * B + c] = sc * (q[k * B + c] - f[c] * d[k]); /* delta D */
                dal[c] += (q[k * B + c] * r[k] + sc * d[k] * u[k * B + c]) / l2;
            }
        for (size_t k = 0; k < dim; k++)
            for (size_t c = 0; c < B; c++)
                u[k * B + c] -= dal[c] * sc * d[k] + along * q[k * B + c];
    }
}

/* v->stage <- the state's stage i from y and the stages v->k. */
static void stage_state(periodic_var *v, int i, double h, const double *y)
{
    const size_t sh = v->sh;
    const double *q = y, *u = y + sh, *k0 = v->k, *k1 = v->k + sh;
    for (size_t r = 0; r < sh; r++) {
        v->stage[r] = q[r] + h * (v->c[i] * u[r] + h * (v->a2[i][0] * k0[r] + v->a2[i][1] * k1[r]));
        v->stage[sh + r] = u[r] + h * (v->a[i][0] * k0[r] + v->a[i][1] * k1[r]);
    }
}

/* The state's step (integrator_gauss.c's, with its own stages v->k), then J's coefficients at
 * the converged stages. first: no previous step to extrapolate from. */
static int state_step(whirl_periodic *w, periodic_var *v, double t, double h, double *y,
                      int first)
{
    const size_t sh = v->sh;
    if (first) {
        int status = whirl_dyn_rhs(t, y, v->f, w->dyn);
        if (status) return status;
        for (int i = 0; i < S; i++) memcpy(v->k + i * sh, v->f + sh, sh * sizeof *v->f);
    } else {
        for (size_t r = 0; r < sh; r++) {
            const double k0 = v->k[r], k1 = v->k[sh + r];
            v->k[r] = v->extrap[0][0] * k0 + v->extrap[0][1] * k1;
            v->k[sh + r] = v->extrap[1][0] * k0 + v->extrap[1][1] * k1;
        }
    }
    double prev = INFINITY, best = INFINITY;
    int converged = 0;
    for (int sweep = 0; sweep < SWEEPS_MAX && !converged; sweep++) {
        double delta = 0, big = 0;
        for (int i = 0; i < S; i++) {
            stage_state(v, i, h, y);
            int status = whirl_dyn_rhs(t + v->c[i] * h, v->stage, v->f, w->dyn);
            if (status) return status;
            for (size_t r = 0; r < sh; r++) {
                const double kn = v->f[sh + r], e = fabs(kn - v->k[i * sh + r]), a = fabs(kn);
                delta = e > delta ? e : delta;
                big = a > big ? a : big;
                v->k_new[i * sh + r] = kn;
            }
        }
        double *swap = v->k;
        v->k = v->k_new, v->k_new = swap;
        if (delta == 0 || (delta >= prev && prev <= 1e-8 * (big + w->chain->gravity)))
            converged = 1;
        else if (!(delta <= 1e3 * best))
            return whirl_fail(GSL_EMAXITER, "the Gauss stage iteration diverges at t = %.17g "
                              "(step %g too large for the fastest mode)", t, h);
        best = fmin(best, delta), prev = delta;
    }
    if (!converged)
        return whirl_fail(GSL_EMAXITER, "the Gauss stage iteration did not converge in %d "
                          "sweeps at t = %.17g", SWEEPS_MAX, t);
    for (int i = 0; i < S; i++) { /* the converged stages: J's coefficients there */
        stage_state(v, i, h, y);
        stage_coefficients(w, v, &v->st[i], t + v->c[i] * h, v->stage);
    }
    return GSL_SUCCESS;
}

/* The state's update (Kahan) and projection, the pre-projection state kept in v->pre. */
static int state_update(whirl_periodic *w, periodic_var *v, double t1, double h, double *y)
{
    const size_t sh = v->sh;
    double *q = y, *u = y + sh;
    for (size_t r = 0; r < sh; r++) {
        const double k0 = v->k[r], k1 = v->k[sh + r];
        const double inc[2] = {h * (u[r] + h * (v->bq[0] * k0 + v->bq[1] * k1)),
                               h * (v->b[0] * k0 + v->b[1] * k1)};
        double *dst[2] = {q + r, u + r}, *cmp[2] = {v->comp + r, v->comp + sh + r};
        for (int k = 0; k < 2; k++) {
            const double add = inc[k] + *cmp[k], sum = *dst[k] + add;
            *cmp[k] = (*dst[k] - sum) + add;
            *dst[k] = sum;
        }
    }
    memcpy(v->pre, y, w->size * sizeof *y);
    int status = whirl_dyn_project(w->dyn, t1, y);
    for (size_t r = 0; status == GSL_SUCCESS && r < w->size; r++)
        if (!isfinite(y[r]))
            status = whirl_fail(GSL_EBADFUNC, "the state is not finite at t = %.17g", t1);
    return status;
}

/* The vectors t_j at y (w's basis) into v->tan, the padding columns 0. */
static void load_vectors(whirl_periodic *w, periodic_var *v, const double *y)
{
    const size_t size = w->size, B = VAR_BLOCK;
    double *x = w->vec, *vec = w->scratch + size;
    memset(v->tan, 0, v->blocks * size * B * sizeof *v->tan);
    memset(v->tcomp, 0, v->blocks * size * B * sizeof *v->tcomp);
    for (size_t j = 0; j < v->m; j++) {
        memset(x, 0, v->m * sizeof *x);
        x[j] = 1;
        periodic_tangent_add(w, y, x, vec); /* y + t_j: the vector t_j at y */
        double *blk = v->tan + (j / B) * size * B;
        for (size_t r = 0; r < size; r++) blk[r * B + j % B] = vec[r] - y[r];
    }
}

int periodic_monodromy_variational(whirl_periodic *w, const double *y, int steps)
{
    if (w->var == NULL && (w->var = var_alloc(w)) == NULL)
        return whirl_fail(GSL_ENOMEM, "out of memory for the variational equations (%zu x %zu)",
                          w->size, w->m);
    periodic_var *v = w->var;
    const size_t m = w->m, size = w->size, B = VAR_BLOCK, len = v->sh * B;
    w->have_mono = 0;
    periodic_basis(w, y);
    load_vectors(w, v, y);
    double *state = v->y;
    memcpy(state, y, size * sizeof *y);
    memset(v->comp, 0, size * sizeof *v->comp);
    const double period = whirl_pivot_period(&w->path), h = period / steps;
    const int pieces = steps < 16 ? steps : 16;
    int status = GSL_SUCCESS, piece = 1;
    for (int k = 0; k < steps && status == GSL_SUCCESS; k++) {
        const double ta = k * h, tb = k + 1 == steps ? period : (k + 1) * h;
        if (whirl_stop_requested()) {
            status = whirl_fail(WHIRL_EINTERRUPTED, "stopped by request at t = %.17g", ta);
            break;
        }
        status = state_step(w, v, ta, tb - ta, state, k == 0);
        for (size_t b = 0; b < v->blocks && status == GSL_SUCCESS; b++)
            status = block_step(w->dissipative ? w : NULL, v, ta, tb - ta,
                                v->tan + b * 2 * len, v->tcomp + b * 2 * len,
                                v->dk + b * S * len, k == 0);
        if (status == GSL_SUCCESS) status = state_update(w, v, tb, tb - ta, state);
        for (size_t b = 0; b < v->blocks && status == GSL_SUCCESS; b++)
            block_project(w, v, v->pre, v->tan + b * 2 * len);
        if ((long)(k + 1) * pieces >= (long)steps * piece) periodic_tick(w, (double)piece++ / pieces);
    }
    if (status) return status;
    double *vec = w->scratch + size, *zero = w->scratch + 2 * size, *col = w->vec + m;
    memset(zero, 0, size * sizeof *zero);
    for (size_t j = 0; j < m; j++) {
        const double *blk = v->tan + (j / B) * 2 * len;
        for (size_t r = 0; r < size; r++) vec[r] = blk[r * B + j % B];
        periodic_tangent_read(w, zero, vec, col);
        for (size_t i = 0; i < m; i++) w->mono[i * m + j] = col[i];
    }
    w->have_mono = 1;
    return GSL_SUCCESS;
}
