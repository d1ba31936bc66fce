/* Linear stability of a steady shape of the N-link chain in the frame co-rotating at omega.
 *
 * Masses m_i at x_i = sum_{j<=i} l_j u_j, u_j = (sin a_j cos b_j, sin b_j, -cos a_j cos b_j); the
 * steady shape has b_j = 0. In the co-rotating frame (Omega = omega z) the Lagrangian is
 *     L = 1/2 sum m_i |x_i' + Omega x x_i|^2 - g sum m_i z_i,
 * and the internal damping has the Rayleigh function R = D/2 sum_i |u_i' - u_{i-1}'|^2 (u_0' = 0,
 * ' the co-rotating time derivative). Linearised about the shape, with q = (a_1..a_N, b_1..b_N),
 * J_ia = dx_i/dq_a, mu_j = sum_{i>=j} m_i, e_j = du_j/da_j = (cos a_j, 0, sin a_j), du_j/db_j = y:
 *     M_ab = sum_i m_i J_ia . J_ib:
 *            M(a_j, a_k) = mu_max(j,k) l_j l_k cos(a_j - a_k),  M(b_j, b_k) = mu_max(j,k) l_j l_k;
 *     G_ab = 2 sum_i m_i J_ia . (Omega x J_ib)            (skew; from the term m x' . Omega x x):
 *            G(a_j, b_k) = -G(b_k, a_j) = -2 omega mu_max(j,k) l_j l_k cos a_j;
 *     K = Hessian of U = g sum m_i z_i - omega^2/2 sum m_i (x_i^2 + y_i^2):
 *            K(a_j, a_k) = delta_jk T_j l_j - omega^2 mu_max(j,k) l_j l_k cos a_j cos a_k,
 *            K(b_j, b_k) = delta_jk T_j l_j - omega^2 mu_max(j,k) l_j l_k,
 *        T_j = P_j . u_j the tension of link j, P_j = sum_{i>=j} m_i (omega^2 x_i, 0, -g) (the
 *        geometric term, from d2u/da2 = d2u/db2 = -u, d2u/dadb = 0 at b = 0);
 *     C = Hessian of R in q': tridiagonal in each block, C(a_j, a_j) = D (1 + [j < N]),
 *        C(a_j, a_{j+1}) = -D cos(a_{j+1} - a_j); the b block the same with cos -> 1.
 * The equilibrium condition is P_j . e_j = 0 (the force on each link lies along it).
 * First-order form y = (q, q'), y' = A y, A = [[0, I], [-M^-1 K, -M^-1 (G + C)]].
 * Symmetry: the rotation about z, s = (0, sin a_j), has K s = 0, so A (s, 0) = 0 and
 * l^T A = 0 for l = ((C - G) s, M s). Without damping l . (s, 0) = s^T C s = 0 (a Jordan pair at
 * zero): the quotient of A on ker l^T / span (s, 0) carries the other 4N - 2 eigenvalues. With
 * damping ker l^T is an invariant complement of (s, 0) and carries the other 4N - 1. Both are
 * taken with an orthonormal basis Q of the complement (Householder QR of [l, (s, 0)]): the
 * trailing block of Q^T A Q. Eigenvalues by LAPACK's dgeev (balancing + Hessenberg QR).
 * References: Meirovitch, Methods of Analytical Dynamics (1970), ch. 6 (gyroscopic systems,
 * Kelvin-Tait-Chetaev); Kolodner 1955 (whirling string); physics notes, section 7. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <lapacke.h>

#include "whirl/stability.h"
#include "error.h"

struct whirl_stability {
    size_t n;          /* links N */
    double *mat[4];    /* M, G, C, K: 2N x 2N row-major */
    double *symmetry;  /* s (2N) */
    double *alpha;     /* a_j of the shape (N) */
    double *tension;   /* T_j (N), also scratch of whirl_nlink_positions (N + 1) */
    double *r, *z;     /* the shape's nodes (N + 1), for whirl_stability_mode */
    double *horiz;     /* x_i of the masses (N) */
    double *factor;    /* 2N x 2N: Cholesky factor of M */
    double *rhs;       /* 2N x 4N column-major: [K | G + C], then M^-1 [K | G + C] */
    gsl_matrix *a;     /* 4N x 4N: the first-order form, then Q^T A Q */
    gsl_matrix *basis; /* 4N x 2: the deflated directions, QR-factorised */
    gsl_vector *tau;   /* 2 Householder coefficients */
    double *re, *im;   /* eigenvalues (4N) */
    double *work;      /* dgeev workspace */
    lapack_int lwork;
    int linearised;    /* 1 after a successful whirl_stability_linearise */
    int deflated;      /* number of removed zero eigenvalues: 0, 1 or 2 */
    double damping;    /* D of the last linearisation */
};

whirl_stability *whirl_stability_alloc(size_t n)
{
    if (n == 0) {
        whirl_fail(GSL_EINVAL, "the linear analysis needs at least one link");
        return NULL;
    }
    const size_t q = 2 * n, y = 4 * n;
    whirl_stability *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->n = n;
    for (int k = 0; k < 4; k++)
        if ((w->mat[k] = malloc(q * q * sizeof(double))) == NULL) goto fail;
    w->symmetry = malloc(q * sizeof(double));
    w->alpha = malloc(n * sizeof(double));
    w->tension = malloc((n + 1) * sizeof(double));
    w->r = malloc((n + 1) * sizeof(double));
    w->z = malloc((n + 1) * sizeof(double));
    w->horiz = malloc(n * sizeof(double));
    w->factor = malloc(q * q * sizeof(double));
    w->rhs = malloc(q * y * sizeof(double));
    w->re = malloc(y * sizeof(double));
    w->im = malloc(y * sizeof(double));
    if (!w->symmetry || !w->alpha || !w->tension || !w->r || !w->z || !w->horiz || !w->factor ||
        !w->rhs || !w->re || !w->im)
        goto fail;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    w->a = gsl_matrix_alloc(y, y);
    w->basis = gsl_matrix_alloc(y, 2);
    w->tau = gsl_vector_alloc(2);
    gsl_set_error_handler(old);
    if (!w->a || !w->basis || !w->tau) goto fail;
    /* workspace query of dgeev for the largest matrix */
    double query;
    lapack_int ny = (lapack_int)y;
    if (LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', ny, w->a->data, ny, w->re, w->im, NULL,
                           1, NULL, 1, &query, -1) != 0)
        goto fail;
    w->lwork = (lapack_int)query;
    if ((w->work = malloc((size_t)w->lwork * sizeof(double))) == NULL) goto fail;
    return w;
fail:
    whirl_stability_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the linear analysis of %zu links", n);
    return NULL;
}

void whirl_stability_free(whirl_stability *w)
{
    if (w == NULL) return;
    for (int k = 0; k < 4; k++) free(w->mat[k]);
    free(w->symmetry);
    free(w->alpha);
    free(w->tension);
    free(w->r);
    free(w->z);
    free(w->horiz);
    free(w->factor);
    free(w->rhs);
    free(w->re);
    free(w->im);
    free(w->work);
    if (w->a) gsl_matrix_free(w->a);
    if (w->basis) gsl_matrix_free(w->basis);
    if (w->tau) gsl_vector_free(w->tau);
    free(w);
}

static int check_model(const whirl_stability *w, const whirl_model *m)
{
    if (m == NULL || m->chain == NULL) return whirl_fail(GSL_EINVAL, "no model or no chain");
    if (m->chain->n != w->n)
        return whirl_fail(GSL_EINVAL, "chain of %zu links, workspace of %zu", m->chain->n, w->n);
    if (m->dim != 3) return whirl_fail(GSL_EINVAL, "the linear analysis is 3D, got dim %d", m->dim);
    if (!isfinite(m->omega)) return whirl_fail(GSL_EINVAL, "omega must be finite");
    if (!(isfinite(m->internal_damping) && m->internal_damping >= 0))
        return whirl_fail(GSL_EINVAL, "damping must be >= 0 and finite, got %g",
                          m->internal_damping);
    if (m->drive_radius != 0)
        return whirl_fail(GSL_EINVAL, "the linear analysis needs the pivot on the axis");
    if (m->air_drag != 0 || m->air_drag_quadratic != 0)
        return whirl_fail(GSL_EINVAL, "with air drag a planar shape is not a relative "
                                      "equilibrium: the linear analysis takes no air drag");
    return GSL_SUCCESS;
}

/* Link angles from the nodes, tensions and the equilibrium residual (see the header comment). */
static int shape_from_nodes(whirl_stability *w, const whirl_model *m, const double *r,
                            const double *z)
{
    const whirl_chain *c = m->chain;
    const size_t n = w->n;
    const double om2 = m->omega * m->omega, g = c->gravity;
    double xsum = 0;
    for (size_t j = 0; j < n; j++) {
        const double dr = r[j + 1] - r[j], dz = z[j + 1] - z[j];
        const double len = hypot(dr, dz);
        if (!(isfinite(len) && fabs(len - c->length[j]) <= 1e-9 * c->length[j]))
            return whirl_fail(GSL_EINVAL, "link %zu of the shape has length %.17g, the chain's "
                                          "is %.17g", j + 1, len, c->length[j]);
        w->alpha[j] = atan2(dr, -dz);
        xsum += c->length[j] * sin(w->alpha[j]);
        w->horiz[j] = xsum; /* the pivot on the axis */
    }
    const double scale = whirl_chain_total_mass(c) * (g + om2 * whirl_chain_total_length(c));
    double px = 0, pz = 0; /* P_j */
    for (size_t j = n; j-- > 0;) {
        px += c->mass[j] * om2 * w->horiz[j];
        pz -= c->mass[j] * g;
        const double sa = sin(w->alpha[j]), ca = cos(w->alpha[j]);
        w->tension[j] = px * sa - pz * ca;  /* P . u */
        const double across = px * ca + pz * sa; /* P . e */
        if (fabs(across) > 1e-8 * scale)
            return whirl_fail(GSL_EINVAL, "the shape is not a relative equilibrium at omega = "
                                          "%g: force across link %zu is %.3g", m->omega, j + 1,
                              across);
    }
    return GSL_SUCCESS;
}

int whirl_stability_linearise(whirl_stability *w, const whirl_model *model, const double *r,
                              const double *z)
{
    w->linearised = 0;
    int status = check_model(w, model);
    if (status) return status;
    if ((status = shape_from_nodes(w, model, r, z))) return status;
    const whirl_chain *c = model->chain;
    const size_t n = w->n, q = 2 * n;
    const double om = model->omega, om2 = om * om, d = model->internal_damping;
    double *mm = w->mat[WHIRL_STABILITY_MASS], *gg = w->mat[WHIRL_STABILITY_GYROSCOPIC];
    double *cc = w->mat[WHIRL_STABILITY_DAMPING], *kk = w->mat[WHIRL_STABILITY_STIFFNESS];
    memset(gg, 0, q * q * sizeof(double));
    memset(cc, 0, q * q * sizeof(double));
    double mu = 0; /* mu_j = sum_{i>=j} m_i */
    for (size_t j = n; j-- > 0;) {
        mu += c->mass[j];
        const double lj = c->length[j], cj = cos(w->alpha[j]);
        /* row and column j against every k <= j (mu_max(j,k) = mu_j) */
        for (size_t k = 0; k <= j; k++) {
            const double lk = c->length[k], ck = cos(w->alpha[k]);
            const double ml = mu * lj * lk;
            const double maa = ml * cos(w->alpha[j] - w->alpha[k]);
            mm[j * q + k] = mm[k * q + j] = maa;
            mm[(n + j) * q + n + k] = mm[(n + k) * q + n + j] = ml;
            kk[j * q + k] = kk[k * q + j] = -om2 * ml * cj * ck;
            kk[(n + j) * q + n + k] = kk[(n + k) * q + n + j] = -om2 * ml;
            kk[j * q + n + k] = kk[k * q + n + j] = 0;
            kk[(n + j) * q + k] = kk[(n + k) * q + j] = 0;
            mm[j * q + n + k] = mm[k * q + n + j] = 0;
            mm[(n + j) * q + k] = mm[(n + k) * q + j] = 0;
            /* G(a_j, b_k) = -2 omega mu l_j l_k cos a_j and G(a_k, b_j) likewise with cos a_k */
            gg[j * q + n + k] = -2 * om * ml * cj;
            gg[(n + k) * q + j] = 2 * om * ml * cj;
            gg[k * q + n + j] = -2 * om * ml * ck;
            gg[(n + j) * q + k] = 2 * om * ml * ck;
        }
        kk[j * q + j] += w->tension[j] * lj;
        kk[(n + j) * q + n + j] += w->tension[j] * lj;
        /* internal damping: joint j (between link j-1 and link j; joint 0 is the shaft) */
        cc[j * q + j] += d;
        cc[(n + j) * q + n + j] += d;
        if (j > 0) {
            const double cr = cos(w->alpha[j] - w->alpha[j - 1]);
            cc[(j - 1) * q + j - 1] += d;
            cc[(n + j - 1) * q + n + j - 1] += d;
            cc[(j - 1) * q + j] = cc[j * q + j - 1] = -d * cr;
            cc[(n + j - 1) * q + n + j] = cc[(n + j) * q + n + j - 1] = -d;
        }
    }
    for (size_t j = 0; j < n; j++) {
        w->symmetry[j] = 0;
        w->symmetry[n + j] = sin(w->alpha[j]);
    }
    w->damping = d;
    w->linearised = 1;
    return GSL_SUCCESS;
}

const double *whirl_stability_get_matrix(const whirl_stability *w, whirl_stability_matrix which)
{
    return w->mat[which];
}

const double *whirl_stability_symmetry(const whirl_stability *w) { return w->symmetry; }

/* A = [[0, I], [-M^-1 K, -M^-1 (G + C)]] into w->a. */
static int first_order_form(whirl_stability *w)
{
    const size_t q = 2 * w->n, y = 4 * w->n;
    const double *mm = w->mat[WHIRL_STABILITY_MASS], *gg = w->mat[WHIRL_STABILITY_GYROSCOPIC];
    const double *cc = w->mat[WHIRL_STABILITY_DAMPING], *kk = w->mat[WHIRL_STABILITY_STIFFNESS];
    memcpy(w->factor, mm, q * q * sizeof(double)); /* symmetric: row- = column-major */
    for (size_t i = 0; i < q; i++)
        for (size_t j = 0; j < q; j++) {
            w->rhs[i + j * q] = kk[i * q + j];
            w->rhs[i + (q + j) * q] = gg[i * q + j] + cc[i * q + j];
        }
    lapack_int info = LAPACKE_dposv_work(LAPACK_COL_MAJOR, 'L', (lapack_int)q, (lapack_int)y,
                                         w->factor, (lapack_int)q, w->rhs, (lapack_int)q);
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the mass matrix is not positive definite (dposv info "
                                       "%d)", (int)info);
    double *a = w->a->data;
    const size_t tda = w->a->tda;
    for (size_t i = 0; i < q; i++) {
        for (size_t j = 0; j < y; j++) {
            a[i * tda + j] = (j == q + i) ? 1.0 : 0.0;
            a[(q + i) * tda + j] = -w->rhs[i + j * q];
        }
    }
    return GSL_SUCCESS;
}

/* Replaces A by Q^T A Q, Q orthonormal with its first w->deflated columns spanning the removed
 * directions (see the header comment); returns the number removed. */
static int deflate(whirl_stability *w)
{
    const size_t n = w->n, q = 2 * n, y = 4 * n;
    const double *mm = w->mat[WHIRL_STABILITY_MASS], *gg = w->mat[WHIRL_STABILITY_GYROSCOPIC];
    const double *cc = w->mat[WHIRL_STABILITY_DAMPING], *s = w->symmetry;
    double snorm = 0;
    for (size_t j = 0; j < q; j++) snorm = fmax(snorm, fabs(s[j]));
    w->deflated = 0;
    if (snorm == 0) return GSL_SUCCESS; /* hanging straight down: no symmetry mode */
    const int k = (w->damping == 0) ? 2 : 1;
    /* column 0: l = ((C - G) s, M s); column 1: (s, 0) */
    for (size_t i = 0; i < q; i++) {
        double cg = 0, ms = 0;
        for (size_t j = 0; j < q; j++) {
            cg += (cc[i * q + j] - gg[i * q + j]) * s[j];
            ms += mm[i * q + j] * s[j];
        }
        gsl_matrix_set(w->basis, i, 0, cg);
        gsl_matrix_set(w->basis, q + i, 0, ms);
        gsl_matrix_set(w->basis, i, 1, s[i]);
        gsl_matrix_set(w->basis, q + i, 1, 0);
    }
    gsl_matrix_view b = gsl_matrix_submatrix(w->basis, 0, 0, y, (size_t)k);
    gsl_vector_view tau = gsl_vector_subvector(w->tau, 0, (size_t)k);
    int status = gsl_linalg_QR_decomp(&b.matrix, &tau.vector);
    if (!status) status = gsl_linalg_QR_QTmat(&b.matrix, &tau.vector, w->a);
    if (!status) status = gsl_matrix_transpose(w->a);
    if (!status) status = gsl_linalg_QR_QTmat(&b.matrix, &tau.vector, w->a);
    if (!status) status = gsl_matrix_transpose(w->a);
    if (status) return whirl_fail(status, "deflation of the symmetry mode failed");
    w->deflated = k;
    return GSL_SUCCESS;
}

int whirl_stability_eigenvalues(whirl_stability *w, size_t *count, const double **re,
                                const double **im)
{
    if (!w->linearised) return whirl_fail(GSL_EINVAL, "no linearisation to analyse");
    int status = first_order_form(w);
    if (!status) status = deflate(w);
    if (status) return status;
    const size_t k = (size_t)w->deflated, m = 4 * w->n - k, tda = w->a->tda;
    /* the trailing block read as column-major is its transpose: same eigenvalues */
    lapack_int info = LAPACKE_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)m,
                                         w->a->data + k * tda + k, (lapack_int)tda, w->re, w->im,
                                         NULL, 1, NULL, 1, w->work, w->lwork);
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the eigenvalue iteration failed (dgeev info %d)",
                          (int)info);
    for (size_t i = 0; i < m; i++)
        if (!isfinite(w->re[i]) || !isfinite(w->im[i]))
            return whirl_fail(GSL_ERANGE, "non-finite eigenvalue");
    *count = m;
    *re = w->re;
    *im = w->im;
    return GSL_SUCCESS;
}

int whirl_stability_growth(whirl_stability *w, double *growth)
{
    size_t count;
    const double *re, *im;
    int status = whirl_stability_eigenvalues(w, &count, &re, &im);
    if (status) return status;
    double g = -INFINITY, scale = 0;
    for (size_t i = 0; i < count; i++) {
        g = fmax(g, re[i]);
        scale = fmax(scale, hypot(re[i], im[i]));
    }
    *growth = fabs(g) <= 1e-10 * scale ? 0.0 : g;
    return GSL_SUCCESS;
}

int whirl_stability_shape(whirl_stability *w, const whirl_model *model, double tip_r,
                          double *growth)
{
    int status = check_model(w, model);
    if (!status)
        status = whirl_nlink_positions(model->chain, model->omega, tip_r, w->r, w->z,
                                       w->tension);
    if (!status) status = whirl_stability_linearise(w, model, w->r, w->z);
    if (!status) status = whirl_stability_growth(w, growth);
    return status;
}

int whirl_stability_mode(whirl_stability *w, const whirl_model *model, int mode,
                         double tip_r_guess, whirl_shape_info *info, double *growth)
{
    int status = check_model(w, model);
    if (status) return status;
    whirl_shape_info local;
    whirl_shape_info *out = info ? info : &local;
    status = whirl_nlink_solve(model->chain, model->omega, mode, tip_r_guess, out);
    if (!status) status = whirl_stability_shape(w, model, out->tip_r, growth);
    return status;
}
