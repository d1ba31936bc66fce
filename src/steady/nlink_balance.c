/* The force balance of the N-link chain's relative equilibria in its link angles, written so that
 * its Jacobian is tridiagonal.
 *
 * Link i (1..N) makes the angle theta_i with the downward vertical and carries the tension T_i
 * along it; mass i (at the lower end of link i) feels gravity (0, -m_i g) and the centrifugal
 * force (m_i omega^2 r_i, 0) in the co-rotating frame. The vertical balance of the part below
 * link i fixes T_i cos theta_i = V_i = g sum_{j >= i} m_j, so the horizontal force of link i is
 * H_i = V_i tan theta_i, and the horizontal balance of mass i reads
 *     E_i = H_i - H_{i+1} - m_i omega^2 r_i = 0,   H_{N+1} = 0,   r_i = sum_{k <= i} l_k sin theta_k.
 * Written so, dE_i/dtheta_k is dense below the diagonal (r_i depends on every link above). With
 * rho_i = (H_i - H_{i+1}) / (m_i omega^2), the radius that balances mass i, the differences of
 * successive balances are local:
 *     R_i = rho_i - rho_{i-1} - l_i sin theta_i = 0,   i = 1..N,  rho_0 = 0 (the pivot on the axis),
 * and R_i = (rho_i - r_i) - (rho_{i-1} - r_{i-1}), so R = 0 exactly when every E_i = 0. R_i
 * depends on theta_{i-1}, theta_i, theta_{i+1} only: with s_j = V_j / (omega^2 cos^2 theta_j),
 *     dR_i/dtheta_{i-1} = -s_{i-1} / m_{i-1},
 *     dR_i/dtheta_i     =  s_i / m_i + s_i / m_{i-1} [i >= 2] - l_i cos theta_i,
 *     dR_i/dtheta_{i+1} = -s_{i+1} / m_i,
 *     dR_i/domega       = -2 (rho_i - rho_{i-1}) / omega,
 * a tridiagonal matrix A factorised by Gaussian elimination with partial pivoting (LAPACK dgttrf,
 * O(N)). Numerically each R_i is formed from quantities of its own links: the round-off of a
 * residual stays that of a few neighbouring terms, where the shot from the tip (src/nlink.c)
 * carries the round-off of every link below up the chain, amplified by the ratios of the
 * tensions (on the high modes at high rates by 1e6 and more).
 *
 * The continuation (src/nlink_path.c) adds one row, the arclength condition c_theta . d theta +
 * c_omega d omega = g, and solves the bordered system
 *     [ A        b      ] [d theta]   [f]
 *     [ c_theta^T c_omega] [d omega] = [g],   b = dR/domega,
 * by block elimination: v = A^{-1} b, w = A^{-1} f, d omega = (g - c.w) / (c_omega - c.v),
 * d theta = w - d omega v (Keller 1977; Govaerts & Pryce 1990, "Block elimination with one
 * refinement solves bordered linear systems accurately", BIT 30:490: one step of iterative
 * refinement restores the accuracy lost where A is nearly singular, at a fold), O(N) per solve.
 * Its determinant det A (c_omega - c.v) changes sign where the curve of equilibria meets another
 * (a branch point) and not at a fold, where both factors do.
 *
 * The polish at fixed omega (Newton's method on R with the tridiagonal A) serves the list of all
 * equilibria (src/equilibria.c) as well. Where A is singular the equilibrium is a fold. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include "core/linalg.h"

#include "core/error.h"
#include "steady/steady_internal.h"

struct nlink_balance {
    const whirl_chain *c;
    double omega;
    double *v;                 /* V_i, N */
    double *rho;               /* rho_i, N */
    double *res;               /* R_i, N */
    double *b;                 /* dR_i/domega, N */
    double *dl, *d, *du, *du2; /* A and its LU factors: N - 1, N, N - 1, N - 2 */
    double *a_dl, *a_d, *a_du; /* a copy of A (for the refinement): N each */
    double *u, *rf;            /* scratch, 2 N each */
    double *sn, *co;           /* sin theta_i and cos theta_i of the last evaluation, N each */
    lapack_int *ipiv;
    int factored;
    int zero_pivot;            /* the last factor had a pivot exactly zero, moved (evaluate) */
    int det_sign;              /* sign of det A */
};

nlink_balance *whirl_nlink_balance_alloc(const whirl_chain *c)
{
    size_t n = c->n;
    nlink_balance *b = calloc(1, sizeof *b);
    if (b == NULL) goto fail;
    b->c = c;
    b->v = malloc(17 * n * sizeof *b->v);
    b->ipiv = malloc(n * sizeof *b->ipiv);
    if (b->v == NULL || b->ipiv == NULL) goto fail;
    b->rho = b->v + n;
    b->res = b->rho + n;
    b->b = b->res + n;
    b->d = b->b + n;
    b->dl = b->d + n;
    b->du = b->dl + n;
    b->du2 = b->du + n;
    b->a_dl = b->du2 + n;
    b->a_d = b->a_dl + n;
    b->a_du = b->a_d + n;
    b->u = b->a_du + n;
    b->rf = b->u + 2 * n;
    b->sn = b->rf + 2 * n;
    b->co = b->sn + n;
    double v = 0;
    for (size_t i = n; i >= 1; i--) b->v[i - 1] = v += c->mass[i - 1] * c->gravity;
    return b;
fail:
    whirl_nlink_balance_free(b);
    whirl_fail(GSL_ENOMEM, "out of memory for the force balance of %zu links", n);
    return NULL;
}

void whirl_nlink_balance_free(nlink_balance *b)
{
    if (b == NULL) return;
    free(b->v);
    free(b->ipiv);
    free(b);
}

double whirl_nlink_balance_scale(const nlink_balance *b)
{
    const size_t n = b->c->n;
    double scale = 0;
    for (size_t i = 0; i < n; i++) {
        scale = fmax(scale, fabs(b->a_d[i]));
        if (i + 1 < n) scale = fmax(scale, fmax(fabs(b->a_dl[i]), fabs(b->a_du[i])));
    }
    return scale;
}

/* rho_i and R_i at (omega, theta); with jac, also A (factorised) and b. GSL_EDOM where a link
 * is horizontal or beyond (its tension would be infinite or negative); where A is exactly
 * singular, its zero pivot moved and b->zero_pivot set. */
static int evaluate(nlink_balance *b, double omega, const double *theta, int jac)
{
    const whirl_chain *c = b->c;
    size_t n = c->n;
    const double w2 = omega * omega;
    b->omega = omega;
    b->factored = 0;
    double h_below = 0, s_below = 0, rho_above = 0;
    /* rho_i from the tip up: H_{i+1} is the one below */
    for (size_t i = n; i >= 1; i--) {
        const double th = theta[i - 1];
        if (!(fabs(th) < M_PI_2))
            return whirl_fail(GSL_EDOM, "link %zu at %.6g rad from the vertical: not a hanging "
                              "chain", i, th);
        const double si = sin(th), co = cos(th), h = b->v[i - 1] * (si / co), m = c->mass[i - 1];
        b->sn[i - 1] = si;
        b->co[i - 1] = co;
        b->rho[i - 1] = (h - h_below) / (m * w2);
        if (jac) {
            const double s = b->v[i - 1] / (w2 * co * co);
            b->d[i - 1] = s / m - c->length[i - 1] * co + (i >= 2 ? s / c->mass[i - 2] : 0);
            if (i < n) {
                b->dl[i - 1] = -s / m;
                b->du[i - 1] = -s_below / m;
            }
            s_below = s;
        }
        h_below = h;
    }
    for (size_t i = 1; i <= n; i++) {
        double rho = b->rho[i - 1];
        b->res[i - 1] = rho - rho_above - c->length[i - 1] * b->sn[i - 1];
        if (jac) b->b[i - 1] = -2 * (rho - rho_above) / omega;
        rho_above = rho;
    }
    if (!jac) return GSL_SUCCESS;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(b->d[i]) || !isfinite(b->res[i]))
            return whirl_fail(GSL_ERANGE, "the force balance is not finite at omega=" WHIRL_Q_RATE
                              "%g", omega);
    for (size_t i = 0; i < n; i++) {
        b->a_d[i] = b->d[i];
        if (i + 1 < n) b->a_dl[i] = b->dl[i], b->a_du[i] = b->du[i];
    }
    lapack_int info = whirl_la_dgttrf_work((lapack_int)n, b->dl, b->d, b->du, b->du2, b->ipiv);
    b->zero_pivot = info > 0;
    if (info < 0)
        return whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g: dgttrf rejects argument %d", omega,
                          (int)-info);
    if (b->zero_pivot) {
        /* A pivot of U exactly zero (dgttrf completes the factors, that column's multiplier
         * zero): the point is a fold to the last bit, which a corrector's Newton iterate on a
         * curve through a fold can land on. The bordered system is regular there; the pivot is
         * moved to -eps |A| (as in whirl_nlink_balance_index, and LAPACK dstebz), the factors
         * then those of A + E with |E| <= eps |A|, a backward error of the elimination's own
         * size. Newton's method at fixed omega (the polish) stops there: GSL_ESING. */
        const double scale = whirl_nlink_balance_scale(b);
        for (size_t i = 0; i < n; i++)
            if (b->d[i] == 0) b->d[i] = -DBL_EPSILON * scale;
    }
    b->det_sign = 1;
    for (size_t i = 0; i < n; i++) {
        if (b->d[i] < 0) b->det_sign = -b->det_sign;
        if (b->ipiv[i] != (lapack_int)i + 1) b->det_sign = -b->det_sign;
    }
    b->factored = 1;
    return GSL_SUCCESS;
}

int whirl_nlink_balance_factor(nlink_balance *b, double omega, const double *theta)
{
    return evaluate(b, omega, theta, 1);
}

const double *whirl_nlink_balance_residual(const nlink_balance *b)
{
    return b->res;
}

double whirl_nlink_balance_logdet(const nlink_balance *b, int *sign)
{
    /* the product of the pivots of U (dgttrf) */
    double logdet = 0;
    for (size_t i = 0; i < b->c->n; i++) logdet += log(fabs(b->d[i]));
    *sign = b->det_sign;
    return logdet;
}

int whirl_nlink_balance_det_sign(const nlink_balance *b)
{
    return b->det_sign;
}

/* The inertia of A. Its off-diagonal products A_{i+1,i} A_{i,i+1} = s_i s_{i+1} / m_i^2 are
 * positive, so the diagonal similarity D A D^-1 with D_{i+1} / D_i = sqrt(A_{i,i+1} /
 * A_{i+1,i}) makes A the symmetric tridiagonal T with T_ii = A_ii and T_{i,i+1}^2 = A_{i,i+1}
 * A_{i+1,i}: its eigenvalues are real, and by Sylvester's law of inertia as many are negative
 * as pivots of T = L D L^T are, q_1 = T_11, q_i = T_ii - T_{i,i-1}^2 / q_{i-1} (the Sturm
 * count, backward stable: Kahan 1966, Demmel 1997 section 5.3.4; a zero pivot is moved to
 * -eps |T|, as LAPACK dstebz does). */
int whirl_nlink_balance_index(const nlink_balance *b)
{
    const size_t n = b->c->n;
    const double tiny = DBL_EPSILON * whirl_nlink_balance_scale(b);
    int count = 0;
    double q = 1;
    for (size_t i = 0; i < n; i++) {
        q = b->a_d[i] - (i > 0 ? b->a_dl[i - 1] * b->a_du[i - 1] / q : 0);
        if (q == 0) q = -tiny;
        if (q < 0) count++;
    }
    return count;
}

/* x <- A^-1 x for the columns x[k N .. k N + N - 1], k < nrhs, with the LU factors of dgttrf:
 * the substitutions of LAPACK's dgtts2 (no transpose), operation for operation, with the
 * columns side by side (each substitution is a chain of dependent operations, a division in
 * every link: two independent columns go at about the pace of one). */
static void solve(const nlink_balance *b, int nrhs, double *x)
{
    const size_t n = b->c->n;
    const double *dl = b->dl, *d = b->d, *du = b->du, *du2 = b->du2;
    for (size_t i = 0; i + 1 < n; i++) {
        const int swap = b->ipiv[i] != (lapack_int)i + 1;
        for (int k = 0; k < nrhs; k++) {
            double *y = x + (size_t)k * n;
            if (swap) {
                const double t = y[i];
                y[i] = y[i + 1];
                y[i + 1] = t - dl[i] * y[i];
            } else {
                y[i + 1] = y[i + 1] - dl[i] * y[i];
            }
        }
    }
    for (int k = 0; k < nrhs; k++) {
        double *y = x + (size_t)k * n;
        y[n - 1] = y[n - 1] / d[n - 1];
        if (n > 1) y[n - 2] = (y[n - 2] - du[n - 2] * y[n - 1]) / d[n - 2];
    }
    for (size_t i = n - 2; n > 2 && i-- > 0;)
        for (int k = 0; k < nrhs; k++) {
            double *y = x + (size_t)k * n;
            y[i] = (y[i] - du[i] * y[i + 1] - du2[i] * y[i + 2]) / d[i];
        }
}

/* y = A x for the tridiagonal A kept in a_dl, a_d, a_du. */
static double tri_row(const nlink_balance *b, const double *x, size_t i)
{
    size_t n = b->c->n;
    double y = b->a_d[i] * x[i];
    if (i > 0) y += b->a_dl[i - 1] * x[i - 1];
    if (i + 1 < n) y += b->a_du[i] * x[i + 1];
    return y;
}

/* One block elimination: x_theta, *x_omega from the right-hand side (f, g) (f NULL: zero);
 * the Schur complement c_omega - c.v in *schur. v = A^-1 b is solved for unless have_v (kept in
 * b->u from the last elimination at the same factor); w = A^-1 f only where f is given. */
static int eliminate(nlink_balance *b, const double *c_theta, double c_omega, const double *f,
                     double g, int have_v, double *x_theta, double *x_omega, double *schur)
{
    size_t n = b->c->n;
    double *v = b->u, *w = b->u + n;
    if (!have_v)
        for (size_t i = 0; i < n; i++) v[i] = b->b[i];
    for (size_t i = 0; i < n; i++) w[i] = f ? f[i] : 0;
    /* the columns to solve: v and w, v alone, or w alone */
    const int from = have_v ? 1 : 0, to = f ? 2 : 1;
    if (to > from) solve(b, to - from, b->u + (size_t)from * n);
    double cv = 0, cw = 0;
    for (size_t i = 0; i < n; i++) cv += c_theta[i] * v[i], cw += c_theta[i] * w[i];
    *schur = c_omega - cv;
    const double dw = (g - cw) / *schur;
    if (!isfinite(dw))
        return whirl_fail(GSL_ESING, "omega=" WHIRL_Q_RATE "%g: the bordered system is singular (a "
                          "branch point)", b->omega);
    for (size_t i = 0; i < n; i++) x_theta[i] = w[i] - dw * v[i];
    *x_omega = dw;
    return GSL_SUCCESS;
}

/* The eigenvalue of A nearest zero and its rate along the path. S = diag(s) A is symmetric
 * (s_i = V_i / (omega^2 cos^2 theta_i): S_{i,i+1} = -s_i s_{i+1} / m_i), so y = diag(s) x is the
 * left eigenvector of A to the right one x, and with z = diag(sqrt(s)) x (the eigenvector of the
 * symmetric T above)
 *     mu = x^T S x / x^T diag(s) x,   d mu = x^T diag(s) (dA) x / x^T diag(s) x
 * (the Rayleigh quotient of T, its error the square of z's; Hellmann-Feynman for T, where the
 * change of the similarity drops out: T' = D A' D^-1 + [D' D^-1, T] and z^T [., T] z = 0). dA
 * along (d omega, d theta) from ds_i = 2 s_i (tan theta_i d theta_i - d omega / omega):
 *     dA_ii = ds_i / m_i + ds_i / m_{i-1} [i >= 2] + l_i sin theta_i d theta_i,
 *     dA_{i+1,i} = -ds_i / m_i,  dA_{i,i+1} = -ds_{i+1} / m_i.
 * x by iters steps of inverse iteration (x <- A^-1 x with the factors of the last factor) from
 * x as given; s and dA from the link angles of the last factor (no further sines). */
int whirl_nlink_balance_near_zero(nlink_balance *b, double d_omega, const double *d_theta,
                                  int iters, double *x, double *mu, double *mu_rate)
{
    if (!b->factored) return whirl_fail(GSL_EINVAL, "the force balance is not factorised");
    const whirl_chain *c = b->c;
    const size_t n = c->n;
    const double w2 = b->omega * b->omega;
    for (int it = 0; it < iters; it++) {
        solve(b, 1, x);
        double big = 0;
        for (size_t i = 0; i < n; i++) big = fmax(big, fabs(x[i]));
        if (!(big > 0 && isfinite(big)))
            return whirl_fail(GSL_EFAILED, "omega=" WHIRL_Q_RATE "%g: inverse iteration on the "
                              "force balance does not give a finite vector", b->omega);
        for (size_t i = 0; i < n; i++) x[i] /= big;
    }
    /* s_i, and ds_i / m_i, ds_i / m_{i-1} (the changes of A's entries) */
    double num = 0, rate = 0, den = 0, *s = b->rf, *q = b->rf + n, *p = b->u;
    const double dw = d_omega / b->omega;
    for (size_t i = 0; i < n; i++) {
        const double co = b->co[i], si = b->v[i] / (w2 * co * co);
        const double dsi = 2 * si * (b->sn[i] / co * d_theta[i] - dw);
        s[i] = si;
        q[i] = dsi / c->mass[i];
        p[i] = i > 0 ? dsi / c->mass[i - 1] : 0;
    }
    for (size_t i = 0; i < n; i++) {
        double dax = (q[i] + p[i] + c->length[i] * b->sn[i] * d_theta[i]) * x[i];
        if (i > 0) dax -= q[i - 1] * x[i - 1];
        if (i + 1 < n) dax -= p[i + 1] * x[i + 1];
        const double sx = s[i] * x[i];
        num += sx * tri_row(b, x, i);
        rate += sx * dax;
        den += sx * x[i];
    }
    *mu = num / den;
    *mu_rate = rate / den;
    if (!(isfinite(*mu) && isfinite(*mu_rate)))
        return whirl_fail(GSL_ERANGE, "omega=" WHIRL_Q_RATE "%g: the eigenvalue of the force "
                          "balance nearest zero is not finite", b->omega);
    return GSL_SUCCESS;
}

int whirl_nlink_balance_bordered(nlink_balance *b, const double *c_theta, double c_omega,
                                 const double *f, double g, int refine, double *x_theta,
                                 double *x_omega, double *schur)
{
    if (!b->factored) return whirl_fail(GSL_EINVAL, "the force balance is not factorised");
    int status = eliminate(b, c_theta, c_omega, f, g, 0, x_theta, x_omega, schur);
    if (status || !refine) return status;
    /* one step of iterative refinement: the residual of the bordered system, solved again */
    size_t n = b->c->n;
    double *rf = b->rf, *dx = rf + n, dw, s2;
    double rg = g - c_omega * *x_omega;
    for (size_t i = 0; i < n; i++) {
        rf[i] = (f ? f[i] : 0) - tri_row(b, x_theta, i) - b->b[i] * *x_omega;
        rg -= c_theta[i] * x_theta[i];
    }
    status = eliminate(b, c_theta, c_omega, rf, rg, 1, dx, &dw, &s2);
    if (!status) {
        for (size_t i = 0; i < n; i++) x_theta[i] += dx[i];
        *x_omega += dw;
    }
    return status;
}

/* The polish's failure where A is exactly singular. */
static int singular(double omega)
{
    return whirl_fail(GSL_ESING, "omega=" WHIRL_Q_RATE "%g: the force balance is singular (a fold)",
                      omega);
}

int whirl_nlink_balance_polish(nlink_balance *b, double omega, double *theta)
{
    size_t n = b->c->n;
    double prev = INFINITY;
    for (int it = 0; it < 30; it++) {
        int status = evaluate(b, omega, theta, 1);
        if (status) return status;
        if (b->zero_pivot) return singular(omega);
        double *step = b->u;
        for (size_t i = 0; i < n; i++) step[i] = -b->res[i];
        solve(b, 1, step);
        double norm = 0;
        for (size_t i = 0; i < n; i++) {
            theta[i] += step[i];
            norm = fmax(norm, fabs(step[i]));
        }
        if (!isfinite(norm)) break;
        if (norm <= 8 * DBL_EPSILON || (norm <= 1e-10 && norm >= 0.5 * prev)) {
            for (size_t i = 0; i < n; i++)
                if (!(fabs(theta[i]) < M_PI_2))
                    return whirl_fail(GSL_EDOM, "omega=" WHIRL_Q_RATE "%g: Newton's method on the "
                                      "link angles leaves link %zu horizontal or compressed", omega,
                                      i + 1);
            status = evaluate(b, omega, theta, 1);
            return status == GSL_SUCCESS && b->zero_pivot ? singular(omega) : status;
        }
        prev = norm;
    }
    return whirl_fail(GSL_EFAILED, "omega=" WHIRL_Q_RATE "%g: Newton's method on the link angles "
                      "does not converge", omega);
}

/* The null vector of A at a critical rate (theta = 0): the linear mode shape in the link angles,
 * by the twisted factorization of A (Parlett & Dhillon 1997, "Fernando's solution to
 * Wilkinson's problem", Linear Algebra Appl. 267:247; LAPACK dlar1v). The elimination from the
 * pivot down, p_1 = A_11, p_i = A_ii - A_{i,i-1} A_{i-1,i} / p_{i-1}, and from the tip up, q_N =
 * A_NN, q_i = A_ii - A_{i,i+1} A_{i+1,i} / q_{i+1}, meet at the link r where |p_r + q_r - A_rr|
 * is least; with phi_r = 1, phi_i = -A_{i,i+1} phi_{i+1} / p_i above it and phi_i = -A_{i,i-1}
 * phi_{i-1} / q_i below. Each component is a product of ratios of its own neighbourhood, so a
 * tail that decays to 1e-160 of the largest component keeps its relative accuracy and its signs
 * (inverse iteration with the LU factors of A resolves components only down to about eps of the
 * largest). A pivot that is exactly zero is moved to eps times its row. Where a component
 * underflows its sign is still known: the signs of the ratios, multiplied down to the tip, are
 * *tip_sign (+1 or -1), even where phi_N is zero. phi is scaled to a largest component of 1. */
int whirl_nlink_balance_mode(nlink_balance *b, double omega, double *phi, int *tip_sign)
{
    const size_t n = b->c->n;
    double *zero = b->rf, *p = b->u, *q = b->u + n;
    for (size_t i = 0; i < n; i++) zero[i] = 0;
    /* A itself (a_dl, a_d, a_du) is kept even where it is exactly singular */
    const int status = evaluate(b, omega, zero, 1);
    b->factored = 0;
    if (status != GSL_SUCCESS) return status;
    const double *dl = b->a_dl, *d = b->a_d, *du = b->a_du;
    for (size_t i = 0; i < n; i++) {
        const double off = (i > 0 ? dl[i - 1] * du[i - 1] / p[i - 1] : 0);
        p[i] = d[i] - off;
        if (p[i] == 0) p[i] = DBL_EPSILON * (fabs(d[i]) + fabs(off));
    }
    for (size_t i = n; i-- > 0;) {
        const double off = (i + 1 < n ? du[i] * dl[i] / q[i + 1] : 0);
        q[i] = d[i] - off;
        if (q[i] == 0) q[i] = DBL_EPSILON * (fabs(d[i]) + fabs(off));
    }
    size_t r = 0;
    double best = INFINITY;
    for (size_t i = 0; i < n; i++) {
        const double gamma = fabs(p[i] + q[i] - d[i]);
        if (gamma < best) best = gamma, r = i;
    }
    phi[r] = 1;
    for (size_t i = r; i-- > 0;) phi[i] = -du[i] * phi[i + 1] / p[i];
    int sign = 1;
    for (size_t i = r + 1; i < n; i++) {
        const double ratio = -dl[i - 1] / q[i];
        phi[i] = ratio * phi[i - 1];
        if (ratio < 0) sign = -sign;
    }
    double big = 0;
    for (size_t i = 0; i < n; i++) big = fmax(big, fabs(phi[i]));
    if (!(big > 0 && isfinite(big) && isfinite(best)))
        return whirl_fail(GSL_EFAILED, "omega=" WHIRL_Q_RATE "%g: no linear mode shape (the null "
                          "vector of the force balance is not finite)", omega);
    for (size_t i = 0; i < n; i++) phi[i] /= big;
    *tip_sign = sign;
    return GSL_SUCCESS;
}

double whirl_nlink_balance_nodes(const whirl_chain *c, double omega, const double *theta,
                                 double *r, double *z, double *tension)
{
    size_t n = c->n;
    const double w2 = omega * omega;
    /* z from the pivot down. r from the tip up: r_N = rho_N = H_N / (m_N omega^2), the radius
     * that balances the last mass (relative accuracy where the tail of a high mode is 1e-16 of
     * the largest radius and less, which a sum of l_k sin theta_k from the pivot, accurate only
     * to eps times the largest radius, would lose), then r_{i-1} = r_i - l_i sin theta_i, so
     * that every link keeps its length to round-off (the radii rho_i of all the masses,
     * differences of the loads H_i - H_{i+1}, would carry an absolute error eps H_i / (m_i
     * omega^2) each: 1e-9 of a link's length near the pivot of 10^4 links). The sum ends on
     * the pivot's radius r_0, zero at an equilibrium up to its round-off (1e-17 of the chain's
     * length on 15 links at omega = 200). It is spread over the links in proportion to their
     * horizontal extents d_i = |l_i sin theta_i|, r_i -= r_0 (sum_{k > i} d_k) / (sum_k d_k):
     * the pivot on the axis, the tip radius untouched, and every link's horizontal extent
     * changed by the same relative round-off r_0 / sum_k d_k; the radii of a tail that is 1e-70
     * of the largest move by as little, relative to themselves, and keep their signs (spread in
     * proportion to the links' lengths instead, the pivot's 1e-17 would swamp them). */
    z[0] = 0;
    for (size_t i = 1; i <= n; i++) z[i] = z[i - 1] - c->length[i - 1] * cos(theta[i - 1]);
    double v = 0;
    for (size_t i = n; i >= 1; i--) {
        v += c->gravity * c->mass[i - 1];
        const double h = v * tan(theta[i - 1]);
        if (i == n) r[n] = h / (c->mass[n - 1] * w2);
        r[i - 1] = r[i] - c->length[i - 1] * sin(theta[i - 1]);
        tension[i] = hypot(h, v);
    }
    const double r0 = r[0];
    double below = 0, total = 0;
    for (size_t i = 0; i < n; i++) total += fabs(c->length[i] * sin(theta[i]));
    for (size_t i = n; i >= 1 && total > 0; i--) {
        r[i] -= r0 * (below / total);
        below += fabs(c->length[i - 1] * sin(theta[i - 1]));
    }
    r[0] = 0;
    tension[0] = tension[1];
    /* the resultant (H_i, V_i) of the forces on the masses below link i with the nodes summed
     * from the pivot, and the sine of its angle to the link */
    double h = 0, worst = 0, r_i = 0;
    v = 0;
    for (size_t i = 1; i <= n; i++) r_i += c->length[i - 1] * sin(theta[i - 1]);
    for (size_t i = n; i >= 1; i--) {
        h += w2 * c->mass[i - 1] * r_i;
        v += c->gravity * c->mass[i - 1];
        const double th = theta[i - 1];
        worst = fmax(worst, fabs(h * cos(th) - v * sin(th)) / hypot(h, v));
        r_i -= c->length[i - 1] * sin(th);
    }
    return worst;
}
