/* Linear stability of a steady shape of the N-link chain in the frame co-rotating at omega.
 *
 * Masses m_i at x_i = p + sum_{j<=i} l_j u_j, the pivot p = (eps, 0, 0) fixed in this frame, and
 * per link the chart u_j = cos a_j cos b_j u0_j + sin a_j cos b_j e1_j + sin b_j e2_j about the
 * equilibrium direction u0_j ((u0_j, e1_j, e2_j) orthonormal, stability.h), q = (a_1..a_N,
 * b_1..b_N), q = 0 at the shape. At q = 0: du_j/da_j = e1_j, du_j/db_j = e2_j,
 * d2u_j/da_j^2 = d2u_j/db_j^2 = -u0_j, d2u_j/da_j db_j = 0. With Omega = omega z the Lagrangian is
 *     L = 1/2 sum m_i |x_i' + Omega x x_i|^2 - g sum m_i z_i,
 * the air drag on mass i the generalised force of f_i^d = -l_i (c + c2 |v_i|) v_i, v_i = x_i' +
 * Omega x x_i its inertial velocity, and the internal damping has the Rayleigh function
 * R = D/2 sum_i |u_i' - u_{i-1}'|^2 (u_0' = 0, ' the co-rotating time derivative). Lagrange's
 * equations with the load f_i = m_i (omega^2 x_i, omega^2 y_i, -g) + f_i^d (gravity, centrifugal
 * force, drag) linearised about the equilibrium, J_i = dx_i/dq, E_j = [e1_j e2_j] (3 x 2),
 * mu_j = sum_{i>=j} m_i, block (j, k) of 2 x 2 for the rows of link j, columns of link k,
 * h = max(j, k):
 *     M = sum m_i J_i^T J_i:          M_jk = mu_h l_j l_k E_j^T E_k;
 *     G = 2 sum m_i J_i^T Omega^x J_i (skew, from the term m x' . Omega x x):
 *                                     G_jk = 2 omega mu_h l_j l_k E_j^T Z E_k,  Z = z^x;
 *     C = Hessian of R in q' + sum J_i^T B_i J_i,  B_i = -df_i^d/dv
 *           = l_i ((c + c2 |v_i|) I + c2 v_i v_i^T / |v_i|)  (symmetric, >= 0; 0 where v_i = 0):
 *         C_jk(drag) = l_j l_k E_j^T S_h E_k,  S_h = sum_{i>=h} B_i;
 *         C(internal): D (1 + [j < N]) on the diagonal of each link, -D E_j^T E_{j+1} between
 *         neighbours;
 *     K = -Hessian of L - dQ/dq = -sum J_i^T (df_i/dx_i) J_i - sum f_i . d2x_i/dq dq:
 *         K_jk = -omega^2 mu_h l_j l_k E_j^T P E_k + omega l_j l_k E_j^T S_h Z E_k
 *                + delta_jk T_j l_j I_2,
 *         P = diag(1, 1, 0), df^d/dx = -B Z omega (dv/dx = omega Z: the drag depends on where the
 *         mass is, a non-symmetric, circulatory term), T_j = F_j . u0_j the tension of link j,
 *         F_j = sum_{i>=j} f_i (the geometric term, from d2u/dq2 = -u0).
 * The equilibrium condition is F_j . e1_j = F_j . e2_j = 0 (the load below each link lies along
 * it). Without a drive and drag (eps = c = c2 = 0) and a shape in the x-z plane, e2_j = y and
 * e1_j = (cos t_j, 0, sin t_j): E_j^T E_k = diag(cos(t_j - t_k), 1), E_j^T P E_k =
 * diag(cos t_j cos t_k, 1), (E_j^T Z E_k)_{ab} = -cos t_j: the classical planar formulas.
 * First-order form y = (q, q'), y' = A y, A = [[0, I], [-M^-1 K, -M^-1 (G + C)]].
 * Symmetry (eps = c = c2 = 0 only): the rotation about z, s_j = E_j^T (z x u0_j), has K s = 0
 * (K symmetric then), so A (s, 0) = 0 and l^T A = 0 for l = ((C - G) s, M s). Without damping
 * l . (s, 0) = s^T C s = 0 (a Jordan pair at zero): the quotient of A on ker l^T / span (s, 0)
 * carries the other 4N - 2 eigenvalues. With damping ker l^T is an invariant complement of (s, 0)
 * and carries the other 4N - 1. Both are taken with an orthonormal basis Q of the complement
 * (Householder QR of [l, (s, 0)]): the trailing block of Q^T A Q. With a drive or drag nothing is
 * removed. Eigenvalues by LAPACK's dgeev (balancing + Hessenberg QR).
 * References: Meirovitch, Methods of Analytical Dynamics (1970), ch. 6 (gyroscopic systems,
 * Kelvin-Tait-Chetaev); Kirillov, Nonconservative Stability Problems of Modern Physics (2013)
 * (M q'' + (D + G) q' + (K + N) q = 0, circulatory forces N); Kolodner 1955 (whirling string);
 * the manual's theory, "Linearisation and Krein signatures". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include "core/linalg.h"

#include "whirl/stability.h"
#include "core/error.h"
#include "core/input.h"
#include "core/worker.h"
#include "stability/stability_internal.h"

/* The eigen-solve of one linearisation: its matrices (written by the linearisation), their
 * first-order form and the LAPACK workspace. It runs on a worker thread (src/core/worker.h) when it is
 * large, so that a stop request ends the call at once; if the caller leaves, the worker keeps
 * the solve until LAPACK returns and frees it, and the workspace starts a new one. */
typedef struct stability_solve {
    size_t n;          /* links N */
    double *mat[4];    /* M, G, C, K: 2N x 2N row-major */
    double *symmetry;  /* s (2N) */
    int symmetric;     /* 1 if rotation about z is a symmetry of the model */
    double damping;    /* D of the linearisation */
    double *factor;    /* 2N x 2N: Cholesky factor of M */
    double *rhs;       /* 2N x 4N column-major: [K | G + C], then M^-1 [K | G + C] */
    gsl_matrix *a;     /* 4N x 4N: the first-order form, then Q^T A Q */
    gsl_matrix *basis; /* 4N x 2: the deflated directions, QR-factorised */
    gsl_vector *tau;   /* 2 Householder coefficients */
    double *re, *im;   /* eigenvalues (4N) */
    double *work;      /* dgeev workspace */
    lapack_int lwork;
    int deflated;      /* number of removed zero eigenvalues: 0, 1 or 2 */
    size_t count;      /* eigenvalues found */
    int touched;       /* mat[] written once (their pages mapped) */
    whirl_error_record error; /* of the last solve (its status GSL_SUCCESS if it worked) */
} stability_solve;

/* Linearisations of at most this many links are solved in the calling thread (a few ms). */
#define STABILITY_INLINE_LINKS 32

struct whirl_stability {
    size_t n;          /* links N */
    stability_solve *solve; /* NULL after an interrupted solve, until the next linearisation */
    double *u0, *e1, *e2; /* the chart of each link (3N each) */
    double *pos;       /* x_i of the masses (3N) */
    double *drag;      /* B_i of the masses (9N, row-major 3 x 3 each) */
    double *tension;   /* T_j (N), also scratch of whirl_nlink_positions (N + 1) */
    double *x, *y, *z; /* the nodes (N + 1): input of the wrappers, then the linearised shape */
    double *re, *im;   /* eigenvalues (4N), copied from the solve */
    int linearised;    /* 1 after a successful whirl_stability_linearise */
    void (*tick)(void *data); /* called while a dense solve runs on a worker (or NULL) */
    void *tick_data;
};

static void solve_free(void *data)
{
    stability_solve *s = data;
    if (s == NULL) return;
    for (int k = 0; k < 4; k++) free(s->mat[k]);
    free(s->symmetry);
    free(s->factor);
    free(s->rhs);
    free(s->re);
    free(s->im);
    free(s->work);
    if (s->a) gsl_matrix_free(s->a);
    if (s->basis) gsl_matrix_free(s->basis);
    if (s->tau) gsl_vector_free(s->tau);
    free(s);
}

static stability_solve *solve_alloc(size_t n)
{
    const size_t q = 2 * n, y = 4 * n;
    stability_solve *s = calloc(1, sizeof *s);
    if (s == NULL) return NULL;
    s->n = n;
    for (int k = 0; k < 4; k++)
        if ((s->mat[k] = malloc(q * q * sizeof(double))) == NULL) goto fail;
    s->symmetry = malloc(q * sizeof(double));
    s->factor = malloc(q * q * sizeof(double));
    s->rhs = malloc(q * y * sizeof(double));
    s->re = malloc(y * sizeof(double));
    s->im = malloc(y * sizeof(double));
    if (!s->symmetry || !s->factor || !s->rhs || !s->re || !s->im) goto fail;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    s->a = gsl_matrix_alloc(y, y);
    s->basis = gsl_matrix_alloc(y, 2);
    s->tau = gsl_vector_alloc(2);
    gsl_set_error_handler(old);
    if (!s->a || !s->basis || !s->tau) goto fail;
    /* workspace query of dgeev for the largest matrix */
    double query;
    lapack_int ny = (lapack_int)y;
    if (whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', ny, s->a->data, ny, s->re, s->im, NULL,
                           1, NULL, 1, &query, -1) != 0)
        goto fail;
    s->lwork = (lapack_int)query;
    if ((s->work = malloc((size_t)s->lwork * sizeof(double))) == NULL) goto fail;
    return s;
fail:
    solve_free(s);
    return NULL;
}

whirl_stability *whirl_stability_alloc(size_t n)
{
    if (n == 0) {
        whirl_fail(GSL_EINVAL, "the linear analysis needs at least one link");
        return NULL;
    }
    const size_t y = 4 * n;
    whirl_stability *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->n = n;
    w->solve = solve_alloc(n);
    w->u0 = malloc(3 * n * sizeof(double));
    w->e1 = malloc(3 * n * sizeof(double));
    w->e2 = malloc(3 * n * sizeof(double));
    w->pos = malloc(3 * n * sizeof(double));
    w->drag = malloc(9 * n * sizeof(double));
    w->tension = malloc((n + 1) * sizeof(double));
    w->x = malloc((n + 1) * sizeof(double));
    w->y = calloc(n + 1, sizeof(double));
    w->z = malloc((n + 1) * sizeof(double));
    w->re = malloc(y * sizeof(double));
    w->im = malloc(y * sizeof(double));
    if (!w->solve || !w->u0 || !w->e1 || !w->e2 || !w->pos || !w->drag || !w->tension || !w->x ||
        !w->y || !w->z || !w->re || !w->im)
        goto fail;
    return w;
fail:
    whirl_stability_free(w);
    char need[32]; /* M, G, C, K, the factor (2N x 2N), the right-hand sides, the 4N x 4N form */
    const double bytes = 44.0 * sizeof(double) * (double)n * (double)n;
    whirl_fail(GSL_ENOMEM, "out of memory for the linear analysis of %zu links (it needs about "
               "%s)", n, whirl_bytes_words(need, sizeof need, bytes));
    return NULL;
}

void whirl_stability_free(whirl_stability *w)
{
    if (w == NULL) return;
    solve_free(w->solve);
    free(w->u0);
    free(w->e1);
    free(w->e2);
    free(w->pos);
    free(w->drag);
    free(w->tension);
    free(w->x);
    free(w->y);
    free(w->z);
    free(w->re);
    free(w->im);
    free(w);
}

static int nonnegative(double v) { return isfinite(v) && v >= 0; }

static int check_model(const whirl_stability *w, const whirl_model *m)
{
    if (m == NULL || m->chain == NULL) return whirl_fail(GSL_EINVAL, "no model or no chain");
    if (m->chain->n != w->n)
        return whirl_fail(GSL_EINVAL, "chain of %zu links, workspace of %zu", m->chain->n, w->n);
    if (m->dim != 3) return whirl_fail(GSL_EINVAL, "the linear analysis is 3D, got dim %d", m->dim);
    if (!isfinite(m->omega)) return whirl_fail(GSL_EINVAL, "omega must be finite");
    if (whirl_check_omega_max(fabs(m->omega)) != GSL_SUCCESS) return GSL_EINVAL;
    if (!nonnegative(m->internal_damping))
        return whirl_fail(GSL_EINVAL, "damping must be >= 0 and finite, got %g",
                          m->internal_damping);
    if (!nonnegative(m->drive_radius))
        return whirl_fail(GSL_EINVAL, "drive radius must be >= 0 and finite, got %g",
                          m->drive_radius);
    if (!nonnegative(m->air_drag) || !nonnegative(m->air_drag_quadratic))
        return whirl_fail(GSL_EINVAL, "air drag must be >= 0 and finite, got %g, %g",
                          m->air_drag, m->air_drag_quadratic);
    return GSL_SUCCESS;
}

/* Free shapes (whirl_nlink_positions) need the pivot on the axis and no drag. */
static int check_free_model(const whirl_stability *w, const whirl_model *m)
{
    int status = check_model(w, m);
    if (status) return status;
    if (m->drive_radius != 0 || m->air_drag != 0 || m->air_drag_quadratic != 0)
        return whirl_fail(GSL_EINVAL, "a free steady shape needs the pivot on the axis and no "
                                      "air drag (see whirl_stability_driven_mode)");
    return GSL_SUCCESS;
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The chart of a link with direction u (stability.h): e2 along the part of y (x if |u_y| > 0.9)
 * perpendicular to u, e1 = u x e2. */
void stability_link_chart(const double *u, double *e1, double *e2)
{
    const double ref[3] = {fabs(u[1]) > 0.9, fabs(u[1]) <= 0.9, 0};
    const double along = dot3(ref, u);
    for (int k = 0; k < 3; k++) e2[k] = ref[k] - along * u[k];
    const double norm = sqrt(dot3(e2, e2));
    for (int k = 0; k < 3; k++) e2[k] /= norm;
    e1[0] = u[1] * e2[2] - u[2] * e2[1];
    e1[1] = u[2] * e2[0] - u[0] * e2[2];
    e1[2] = u[0] * e2[1] - u[1] * e2[0];
}

/* Link directions and charts, mass positions, drag matrices B_i, tensions and the equilibrium
 * residual (see the header comment). */
static int shape_from_nodes(whirl_stability *w, const whirl_model *m, const double *x,
                            const double *y, const double *z)
{
    const whirl_chain *c = m->chain;
    const size_t n = w->n;
    const double om = m->omega, om2 = om * om, g = c->gravity;
    const double cd = m->air_drag, c2 = m->air_drag_quadratic;
    double p[3] = {m->drive_radius, 0, 0};
    for (size_t j = 0; j < n; j++) {
        const double d[3] = {x[j + 1] - x[j], y[j + 1] - y[j], z[j + 1] - z[j]};
        const double len = sqrt(dot3(d, d));
        if (!(isfinite(len) && fabs(len - c->length[j]) <= 1e-9 * c->length[j]))
            return whirl_fail(GSL_EINVAL, "link %zu of the shape has length %.17g, the chain's "
                                          "is %.17g", j + 1, len, c->length[j]);
        double *u = w->u0 + 3 * j;
        for (int k = 0; k < 3; k++) u[k] = d[k] / len;
        stability_link_chart(u, w->e1 + 3 * j, w->e2 + 3 * j);
        for (int k = 0; k < 3; k++) w->pos[3 * j + k] = p[k] += c->length[j] * u[k];
    }
    const double total = whirl_chain_total_length(c);
    const double scale = whirl_chain_total_mass(c) * (g + om2 * total) +
                         (cd + c2 * fabs(om) * total) * fabs(om) * total * total;
    double load[3] = {0, 0, 0}; /* F_j */
    for (size_t j = n; j-- > 0;) {
        const double *xi = w->pos + 3 * j, li = c->length[j];
        const double v[3] = {-om * xi[1], om * xi[0], 0}; /* Omega x x_i */
        const double speed = sqrt(dot3(v, v)), k_lin = li * (cd + c2 * speed);
        double *b = w->drag + 9 * j;
        for (int r = 0; r < 3; r++)
            for (int s = 0; s < 3; s++)
                b[3 * r + s] = (r == s) * k_lin + (speed > 0 ? li * c2 * v[r] * v[s] / speed : 0);
        load[0] += c->mass[j] * om2 * xi[0] - k_lin * v[0];
        load[1] += c->mass[j] * om2 * xi[1] - k_lin * v[1];
        load[2] -= c->mass[j] * g;
        w->tension[j] = dot3(load, w->u0 + 3 * j);
        const double across = fmax(fabs(dot3(load, w->e1 + 3 * j)),
                                   fabs(dot3(load, w->e2 + 3 * j)));
        if (!(across <= 1e-8 * scale))
            return whirl_fail(GSL_EINVAL, "the shape is not a relative equilibrium at omega = "
                                          WHIRL_Q_RATE "%g: force across link %zu is %.3g",
                              m->omega, j + 1, across);
    }
    /* the nodes as linearised */
    w->x[0] = m->drive_radius, w->y[0] = w->z[0] = 0;
    for (size_t j = 0; j < n; j++) {
        w->x[j + 1] = w->pos[3 * j];
        w->y[j + 1] = w->pos[3 * j + 1];
        w->z[j + 1] = w->pos[3 * j + 2];
    }
    return GSL_SUCCESS;
}

/* a^T S b for 3-vectors and a row-major 3 x 3 matrix S. */
static double form3(const double *a, const double *s, const double *b)
{
    double sum = 0;
    for (int r = 0; r < 3; r++)
        sum += a[r] * (s[3 * r] * b[0] + s[3 * r + 1] * b[1] + s[3 * r + 2] * b[2]);
    return sum;
}

/* The 2 x 2 blocks of M, G, K and the drag part of C for the rows of link j and the columns of
 * link k, with mu = mu_h and tail = S_h, h = max(j, k) (header comment). */
static void link_pair(whirl_stability *w, const whirl_model *m, size_t j, size_t k, double mu,
                      const double *tail)
{
    const size_t n = w->n, q = 2 * n;
    const double om = m->omega, ll = m->chain->length[j] * m->chain->length[k];
    const double *row[2] = {w->e1 + 3 * j, w->e2 + 3 * j}, *col[2] = {w->e1 + 3 * k, w->e2 + 3 * k};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            const double *e = row[a], *f = col[b];
            const double zf[3] = {-f[1], f[0], 0}; /* z x f */
            const size_t at = (a * n + j) * q + b * n + k;
            w->solve->mat[WHIRL_STABILITY_MASS][at] = mu * ll * dot3(e, f);
            w->solve->mat[WHIRL_STABILITY_GYROSCOPIC][at] = 2 * om * mu * ll * dot3(e, zf);
            w->solve->mat[WHIRL_STABILITY_STIFFNESS][at] =
                -om * om * mu * ll * (e[0] * f[0] + e[1] * f[1]) + om * ll * form3(e, tail, zf);
            w->solve->mat[WHIRL_STABILITY_DAMPING][at] = ll * form3(e, tail, f);
        }
}

int whirl_stability_linearise_3d(whirl_stability *w, const whirl_model *model, const double *x,
                                 const double *y, const double *z)
{
    w->linearised = 0;
    int status = check_model(w, model);
    if (status) return status;
    if ((status = shape_from_nodes(w, model, x, y, z))) return status;
    if (w->solve == NULL && (w->solve = solve_alloc(w->n)) == NULL)
        return whirl_fail(GSL_ENOMEM, "out of memory for the linear analysis of %zu links", w->n);
    stability_solve *sv = w->solve;
    const whirl_chain *c = model->chain;
    const size_t n = w->n, q = 2 * n;
    /* The loop below writes the matrices by columns as well as rows: on fresh memory each of
     * those writes maps a page of its own, N^2 / 2 page faults in the first rows (seconds at
     * thousands of links, between two reads of the stop request). The first linearisation maps
     * them row by row instead, reading the stop request every row. */
    for (size_t i = 0; i < 4 * q && !sv->touched; i++) {
        if (n > STABILITY_INLINE_LINKS && whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during the linearisation");
        memset(sv->mat[i / q] + (i % q) * q, 0, q * sizeof(double));
    }
    sv->touched = 1;
    const double d = model->internal_damping;
    double *cc = sv->mat[WHIRL_STABILITY_DAMPING], *kk = sv->mat[WHIRL_STABILITY_STIFFNESS];
    double mu = 0, tail[9] = {0}; /* mu_j = sum_{i>=j} m_i, S_j = sum_{i>=j} B_i */
    for (size_t j = n; j-- > 0;) {
        if (n > STABILITY_INLINE_LINKS && whirl_stop_requested()) /* O(N) pairs a row */
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during the linearisation");
        mu += c->mass[j];
        for (int k = 0; k < 9; k++) tail[k] += w->drag[9 * j + k];
        for (size_t k = 0; k <= j; k++) {
            link_pair(w, model, j, k, mu, tail);
            if (k < j) link_pair(w, model, k, j, mu, tail);
        }
        kk[j * q + j] += w->tension[j] * c->length[j];
        kk[(n + j) * q + n + j] += w->tension[j] * c->length[j];
    }
    /* internal damping: joint j between link j-1 and link j (joint 0: the shaft) */
    for (size_t j = 0; j < n && d > 0; j++) {
        cc[j * q + j] += d * (1 + (j + 1 < n));
        cc[(n + j) * q + n + j] += d * (1 + (j + 1 < n));
        if (j == 0) continue;
        const double *rows[2] = {w->e1 + 3 * (j - 1), w->e2 + 3 * (j - 1)};
        const double *cols[2] = {w->e1 + 3 * j, w->e2 + 3 * j};
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                const double v = d * dot3(rows[a], cols[b]);
                cc[(a * n + j - 1) * q + b * n + j] -= v;
                cc[(b * n + j) * q + a * n + j - 1] -= v;
            }
    }
    sv->symmetric = model->drive_radius == 0 && model->air_drag == 0 &&
                    model->air_drag_quadratic == 0;
    for (size_t j = 0; j < n; j++) {
        const double *u = w->u0 + 3 * j, zu[3] = {-u[1], u[0], 0}; /* z x u0 */
        sv->symmetry[j] = sv->symmetric ? dot3(w->e1 + 3 * j, zu) : 0;
        sv->symmetry[n + j] = sv->symmetric ? dot3(w->e2 + 3 * j, zu) : 0;
    }
    sv->damping = d;
    w->linearised = 1;
    return GSL_SUCCESS;
}

int whirl_stability_linearise(whirl_stability *w, const whirl_model *model, const double *r,
                              const double *z)
{
    w->linearised = 0;
    int status = check_model(w, model);
    if (status) return status;
    memset(w->y, 0, (w->n + 1) * sizeof *w->y); /* read before shape_from_nodes overwrites it */
    return whirl_stability_linearise_3d(w, model, r, w->y, z);
}

const double *whirl_stability_get_matrix(const whirl_stability *w, whirl_stability_matrix which)
{
    return w->solve ? w->solve->mat[which] : NULL;
}

const double *whirl_stability_symmetry(const whirl_stability *w)
{
    return w->solve ? w->solve->symmetry : NULL;
}

void whirl_stability_nodes(const whirl_stability *w, const double **x, const double **y,
                           const double **z)
{
    *x = w->x;
    *y = w->y;
    *z = w->z;
}

int stability_first_order(size_t n, const double *const mat[4], double *a, size_t row,
                          size_t col, double *f, double *r)
{
    const size_t q = 2 * n, y = 4 * n;
    const double *mm = mat[WHIRL_STABILITY_MASS], *gg = mat[WHIRL_STABILITY_GYROSCOPIC];
    const double *cc = mat[WHIRL_STABILITY_DAMPING], *kk = mat[WHIRL_STABILITY_STIFFNESS];
    memcpy(f, mm, q * q * sizeof(double)); /* symmetric: row- = column-major */
    for (size_t i = 0; i < q; i++)
        for (size_t j = 0; j < q; j++) {
            r[i + j * q] = kk[i * q + j];
            r[i + (q + j) * q] = gg[i * q + j] + cc[i * q + j];
        }
    lapack_int info = whirl_la_dposv_work(LAPACK_COL_MAJOR, 'L', (lapack_int)q, (lapack_int)y,
                                         f, (lapack_int)q, r, (lapack_int)q);
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the mass matrix is not positive definite (dposv info "
                                       "%d)", (int)info);
    for (size_t i = 0; i < q; i++) {
        for (size_t j = 0; j < y; j++) {
            a[i * row + j * col] = (j == q + i) ? 1.0 : 0.0;
            a[(q + i) * row + j * col] = -r[i + j * q];
        }
    }
    return GSL_SUCCESS;
}

/* A = [[0, I], [-M^-1 K, -M^-1 (G + C)]] into w->a (row-major). */
static int first_order_form(stability_solve *w)
{
    const double *const mat[4] = {w->mat[0], w->mat[1], w->mat[2], w->mat[3]};
    return stability_first_order(w->n, mat, w->a->data, w->a->tda, 1, w->factor, w->rhs);
}

/* Replaces A by Q^T A Q, Q orthonormal with its first w->deflated columns spanning the removed
 * directions (see the header comment); returns the number removed. */
static int deflate(stability_solve *w)
{
    const size_t n = w->n, q = 2 * n, y = 4 * n;
    const double *mm = w->mat[WHIRL_STABILITY_MASS], *gg = w->mat[WHIRL_STABILITY_GYROSCOPIC];
    const double *cc = w->mat[WHIRL_STABILITY_DAMPING], *s = w->symmetry;
    double snorm = 0;
    for (size_t j = 0; j < q; j++) snorm = fmax(snorm, fabs(s[j]));
    w->deflated = 0;
    if (!w->symmetric || snorm == 0) return GSL_SUCCESS; /* no symmetry, or hanging straight down */
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

/* The eigenvalues of the linearisation in s (first-order form, deflation, dgeev): s->error,
 * s->count, s->re, s->im. A worker (src/core/worker.h): it reads s alone. */
static void solve_run(void *data, const whirl_worker *self)
{
    (void)self; /* one LAPACK call: nothing to poll */
    stability_solve *w = data;
    int status = first_order_form(w);
    if (!status) status = deflate(w);
    const size_t k = (size_t)w->deflated, m = 4 * w->n - k, tda = w->a->tda;
    /* LAPACK is handed finite numbers only (a NaN or inf would make it fail, or print) */
    for (size_t i = k; i < k + m && !status; i++)
        for (size_t j = k; j < k + m && !status; j++)
            if (!isfinite(w->a->data[i * tda + j]))
                status = whirl_fail(GSL_ERANGE, "the linearised matrix is not finite (entry "
                                    "%zu,%zu = %g): the damping %g or the rate is too large",
                                    i - k, j - k, w->a->data[i * tda + j], w->damping);
    /* the trailing block read as column-major is its transpose: same eigenvalues */
    lapack_int info = 0;
    if (!status)
        info = whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)m,
                                  w->a->data + k * tda + k, (lapack_int)tda, w->re, w->im, NULL,
                                  1, NULL, 1, w->work, w->lwork);
    if (!status && info != 0)
        status = whirl_fail(GSL_EFAILED, "the eigenvalue iteration failed (dgeev info %d)",
                            (int)info);
    for (size_t i = 0; i < m && !status; i++)
        if (!isfinite(w->re[i]) || !isfinite(w->im[i]))
            status = whirl_fail(GSL_ERANGE, "non-finite eigenvalue");
    w->count = m;
    w->error.status = GSL_SUCCESS;
    whirl_error_keep(&w->error, status);
}

int whirl_stability_eigenvalues(whirl_stability *w, size_t *count, const double **re,
                                const double **im)
{
    if (!w->linearised) return whirl_fail(GSL_EINVAL, "no linearisation to analyse");
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request before the eigen-solve");
    stability_solve *s = w->solve;
    if (w->n <= STABILITY_INLINE_LINKS) {
        solve_run(s, NULL);
    } else if (whirl_worker_run_ticked(solve_run, s, solve_free, w->tick, w->tick_data) !=
               GSL_SUCCESS) {
        /* the worker owns s now, until LAPACK returns; the next linearisation allocates anew */
        w->solve = NULL;
        w->linearised = 0;
        return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request during the eigen-solve");
    }
    if (s->error.status) return whirl_error_restore(&s->error);
    memcpy(w->re, s->re, s->count * sizeof *w->re);
    memcpy(w->im, s->im, s->count * sizeof *w->im);
    *count = s->count;
    *re = w->re;
    *im = w->im;
    return GSL_SUCCESS;
}

int whirl_stability_index(const whirl_stability *w, int *index)
{
    *index = 0;
    const double *k = whirl_stability_get_matrix(w, WHIRL_STABILITY_STIFFNESS);
    if (!w->linearised || k == NULL)
        return whirl_fail(GSL_EINVAL, "no linearisation for the index");
    const size_t q = 2 * w->n;
    double *a = malloc(q * q * sizeof *a), *ev = malloc(q * sizeof *ev);
    if (a == NULL || ev == NULL) {
        free(a), free(ev);
        return whirl_fail(GSL_ENOMEM, "out of memory for the index of %zu links", w->n);
    }
    for (size_t i = 0; i < q; i++) { /* the symmetric part; O(N^2) strided reads */
        if (w->n > STABILITY_INLINE_LINKS && whirl_stop_requested()) {
            free(a), free(ev);
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request before the index");
        }
        for (size_t j = 0; j < q; j++) a[i * q + j] = (k[i * q + j] + k[j * q + i]) / 2;
    }
    /* symmetric: the row-major array is its own column-major transpose */
    int info;
    const int status = whirl_worker_dsyev(q, a, q, ev, &info, w->tick, w->tick_data);
    if (status) { /* a stop request: the solve runs on a worker */
        free(a), free(ev);
        return status;
    }
    if (info == 0) {
        double big = 0;
        for (size_t i = 0; i < q; i++) big = fmax(big, fabs(ev[i]));
        for (size_t i = 0; i < q; i++) *index += ev[i] < -1e-9 * big;
    }
    free(a), free(ev);
    if (info != 0) return whirl_fail(GSL_EFAILED, "the index's eigen-solve failed (dsyev %d)", (int)info);
    return GSL_SUCCESS;
}

void whirl_stability_set_tick(whirl_stability *w, void (*tick)(void *data), void *data)
{
    w->tick = tick;
    w->tick_data = data;
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
    int status = check_free_model(w, model);
    if (!status)
        status = whirl_nlink_positions(model->chain, model->omega, tip_r, w->x, w->z,
                                       w->tension);
    if (!status) status = whirl_stability_linearise(w, model, w->x, w->z);
    if (!status) status = whirl_stability_growth(w, growth);
    return status;
}

int whirl_stability_mode(whirl_stability *w, const whirl_model *model, int mode,
                         whirl_shape_info *info, double *growth)
{
    int status = check_free_model(w, model);
    if (status) return status;
    whirl_shape_info local;
    whirl_shape_info *out = info ? info : &local;
    /* the nodes from the branch's link angles: at high rates the tip radius no longer fixes
     * the shape (whirl_nlink_solve_nodes), and its rebuilt nodes are off the equilibrium */
    status = whirl_nlink_solve_nodes(model->chain, model->omega, mode, out, w->x, w->z,
                                     w->tension);
    if (!status) status = whirl_stability_linearise(w, model, w->x, w->z);
    if (!status) status = whirl_stability_growth(w, growth);
    return status;
}

int whirl_stability_driven_mode(whirl_stability *w, const whirl_model *model, int mode, int side,
                                whirl_driven_info *info, double *growth)
{
    w->linearised = 0;
    int status = check_model(w, model);
    if (status) return status;
    whirl_driven_params p;
    whirl_driven_params_from_model(&p, model);
    whirl_driven_info local;
    whirl_driven_info *out = info ? info : &local;
    status = whirl_driven_mode(model->chain, &p, mode, side, out);
    if (!status)
        status = whirl_driven_sample(model->chain, &p, out->tip, w->n + 1, NULL, w->x, w->y,
                                     w->z, NULL);
    if (!status) status = whirl_stability_linearise_3d(w, model, w->x, w->y, w->z);
    if (!status) status = whirl_stability_growth(w, growth);
    return status;
}

size_t stability_links(const whirl_stability *w) { return w->n; }
