/* Periodic motions of the chain with its pivot on a path (whirl/periodic.h): the period map,
 * its derivative in the tangent coordinates, Newton's method on P(y) - y.
 *
 * Tangent coordinates at a state y (Cartesian formulation: link vectors d_i and rates d_i'):
 * per link the unit vectors e_ik across it (2D: one, in the x-z plane; 3D: two), and
 *   a_ik = e_ik . delta d_i,  b_ik = e_ik . delta d_i'.
 * Back to a state: delta d_i = sum_k a_ik e_ik, delta d_i' = sum_k b_ik e_ik + c_i d_i with
 * c_i = -(d_i' . delta d_i) / l_i^2, the linearised constraint d_i . d_i' = 0. The period map
 * projects after every step, so its derivative maps onto the tangent space and these
 * coordinates carry all of it: the 2N (2D and 3D) directions across the constraint manifold
 * would only add zero multipliers.
 * The monodromy: from the variational equations (variational.c), or by central differences:
 * column j of M is (P(y + h_j t_j) - P(y - h_j t_j)) / (2 h_j) read in the
 * coordinates at y (t_j the tangent vector of coordinate j, the perturbed states projected onto
 * the manifold), from h_j and h_j / 2 extrapolated: the derivative of the discrete period map
 * with the same steps as the motion, 4 m periods per matrix. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_linalg.h>

#include "core/error.h"
#include "dynamics/dyn_internal.h"
#include "periodic/periodic_internal.h"

/* Relative step of the central differences, extrapolated from h and h/2: their truncation
 * error ~ (h/l)^4 of the map's derivatives (1e-14) against the round-off ~ 1e-16 / (h/l) times
 * the map's growth (1e-12). Measured on the circle drive (N = 5, omega = 2, eps = 0.05, 6400
 * steps) as the reciprocal-pair error: 2e-11 at h/l = 3e-4, 5e-11 at 1e-4, 2e-10 at 3e-5; plain
 * central differences stop at ~1e-9 (1e-5), 6e-10 (3e-6), 3e-9 (1e-6). The perturbation grows
 * with the motion's largest multiplier: beyond |mu| ~ 100 it leaves the linear range. */
#define FD_REL 3e-4
/* Singular values of M - I below this fraction of the largest are dropped from Newton's step
 * (minimal-norm step): above the central differences' noise (1e-10 relative), below any
 * multiplier a run could tell from 1. */
#define SV_CUT 1e-9
/* Halvings of a Newton step that raises the residual before it is taken as it is. */
#define BACKTRACK_MAX 8

/* The workspace of model (inertial frame, omega the path's, its dissipation; checked by the
 * callers) on path. */
static whirl_periodic *alloc_model(const whirl_model *model, const whirl_pivot_path *path)
{
    const whirl_chain *c = model->chain;
    const int dim = model->dim;
    if (whirl_pivot_check(path, dim) != GSL_SUCCESS) return NULL;
    whirl_periodic *w = calloc(1, sizeof *w);
    if (w == NULL) goto nomem;
    w->path = *path;
    w->chain = c;
    w->dim = dim;
    w->n = c->n;
    w->drag = model->air_drag, w->drag2 = model->air_drag_quadratic;
    w->damping = model->internal_damping;
    w->dissipative = w->drag > 0 || w->drag2 > 0 || w->damping > 0;
    w->dyn = whirl_dyn_alloc(model, WHIRL_FORMULATION_CARTESIAN);
    if (w->dyn == NULL) {
        free(w);
        return NULL; /* the dynamics' message (an invalid chain, or no memory) */
    }
    if (whirl_dyn_set_pivot(w->dyn, whirl_pivot_eval, &w->path) != GSL_SUCCESS) {
        whirl_periodic_free(w); /* a drive radius or a ramp in the model: its message */
        return NULL;
    }
    w->it = whirl_integrator_alloc("gauss2", w->dyn);
    if (w->it == NULL) goto nomem;
    w->size = whirl_dyn_size(w->dyn);
    w->m = 2 * (size_t)(dim - 1) * w->n;
    const size_t m = w->m, size = w->size;
    w->basis = malloc(3 * (size_t)(dim - 1) * w->n * sizeof *w->basis);
    w->scratch = malloc(5 * size * sizeof *w->scratch);
    w->vec = malloc(5 * m * sizeof *w->vec);
    w->mono = malloc(m * m * sizeof *w->mono);
    w->work = gsl_matrix_alloc(m, m);
    w->v = gsl_matrix_alloc(m, m);
    w->out = malloc(8 * m * sizeof *w->out);
    w->eig = gsl_eigen_nonsymm_alloc(m);
    w->eval = gsl_vector_complex_alloc(m);
    if (!w->basis || !w->scratch || !w->vec || !w->mono || !w->work || !w->v || !w->out ||
        !w->eig || !w->eval)
        goto nomem;
    double total = 0;
    for (size_t i = 0; i < w->n; i++) total += c->length[i];
    w->length = total;
    w->omega_ref = fmax(path->omega, sqrt(c->gravity / total));
    return w;
nomem:
    whirl_periodic_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the periodic motion of %zu links (%zu x %zu "
               "monodromy)", c->n, 2 * (size_t)(dim - 1) * c->n, 2 * (size_t)(dim - 1) * c->n);
    return NULL;
}

whirl_periodic *whirl_periodic_alloc(const whirl_chain *c, int dim, const whirl_pivot_path *path)
{
    if (c == NULL || path == NULL) {
        whirl_fail(GSL_EINVAL, "whirl_periodic_alloc: needs a chain and a path");
        return NULL;
    }
    const whirl_model model = {.chain = c, .dim = dim, .frame = WHIRL_FRAME_INERTIAL,
                               .omega = path->omega};
    return alloc_model(&model, path);
}

whirl_periodic *whirl_periodic_alloc_model(const whirl_model *model,
                                           const whirl_pivot_path *path)
{
    if (model == NULL || model->chain == NULL || path == NULL) {
        whirl_fail(GSL_EINVAL, "whirl_periodic_alloc_model: needs a model with a chain and a "
                   "path");
        return NULL;
    }
    if (model->seed_sigma != NULL || model->seed_lambda != NULL) {
        whirl_fail(GSL_EINVAL, "whirl_periodic_alloc_model: the seed's forcing is not supported "
                   "with a pivot path");
        return NULL;
    }
    /* the frame and the rate are the path's: the inertial frame, the internal damping measured
       in the frame co-rotating at the path's rate */
    whirl_model m = *model;
    m.frame = WHIRL_FRAME_INERTIAL;
    m.omega = path->omega;
    return alloc_model(&m, path);
}

void whirl_periodic_free(whirl_periodic *w)
{
    if (w == NULL) return;
    whirl_integrator_free(w->it);
    whirl_dyn_free(w->dyn);
    free(w->basis);
    free(w->scratch);
    free(w->vec);
    free(w->mono);
    if (w->work) gsl_matrix_free(w->work);
    if (w->v) gsl_matrix_free(w->v);
    free(w->out);
    if (w->eig) gsl_eigen_nonsymm_free(w->eig);
    if (w->eval) gsl_vector_complex_free(w->eval);
    periodic_var_free(w->var);
    free(w);
}

whirl_dyn *whirl_periodic_dyn(whirl_periodic *w) { return w->dyn; }
int whirl_periodic_dissipative(const whirl_periodic *w) { return w->dissipative; }

void whirl_periodic_set_tick(whirl_periodic *w,
                             void (*tick)(void *data, const whirl_periodic_progress *progress),
                             void *data)
{
    w->tick = tick;
    w->tick_data = tick ? data : NULL;
}

void periodic_tick(whirl_periodic *w, double done)
{
    if (w->tick == NULL) return;
    w->progress.monodromy = done;
    w->tick(w->tick_data, &w->progress);
}
void periodic_set_path(whirl_periodic *w, const whirl_pivot_path *path)
{
    w->path = *path;
    /* the internal damping's frame turns at the path's rate (whirl_periodic_alloc_model) */
    if (w->damping > 0) w->dyn->model.omega = path->omega;
    w->omega_ref = fmax(path->omega, sqrt(w->chain->gravity / w->length));
}

size_t whirl_periodic_state_size(const whirl_periodic *w) { return w->size; }
size_t whirl_periodic_tangent_size(const whirl_periodic *w) { return w->m; }
const double *whirl_periodic_monodromy(const whirl_periodic *w)
{
    return w->have_mono ? w->mono : NULL;
}

/* Index of component k (0..2) of link i in a half of the Cartesian state (2D: x, z). */
static size_t comp(const whirl_periodic *w, size_t i, int k)
{
    return w->dim == 3 ? 3 * i + (size_t)k : 2 * i + (k == 2);
}

static void link_of(const whirl_periodic *w, const double *y, size_t i, double d[3], double r[3])
{
    const double *rate = y + w->size / 2;
    for (int k = 0; k < 3; k++) {
        const int skip = w->dim == 2 && k == 1;
        d[k] = skip ? 0 : y[comp(w, i, k)];
        r[k] = skip ? 0 : rate[comp(w, i, k)];
    }
}

/* w->basis <- the unit vectors across each link of y (3 components each, dim - 1 per link). */
void periodic_basis(whirl_periodic *w, const double *y)
{
    const int per = w->dim - 1;
    for (size_t i = 0; i < w->n; i++) {
        double d[3], r[3];
        link_of(w, y, i, d, r);
        const double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double u[3] = {d[0] / l, d[1] / l, d[2] / l};
        double *e = w->basis + 3 * (size_t)per * i;
        if (w->dim == 2) {
            e[0] = u[2], e[1] = 0, e[2] = -u[0];
            continue;
        }
        /* e1 = a x u / |a x u| with a the axis least along u, e2 = u x e1 */
        int a = 0;
        for (int k = 1; k < 3; k++)
            if (fabs(u[k]) < fabs(u[a])) a = k;
        double ax[3] = {0, 0, 0};
        ax[a] = 1;
        double e1[3] = {ax[1] * u[2] - ax[2] * u[1], ax[2] * u[0] - ax[0] * u[2],
                        ax[0] * u[1] - ax[1] * u[0]};
        const double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
        for (int k = 0; k < 3; k++) e1[k] /= n1;
        const double e2[3] = {u[1] * e1[2] - u[2] * e1[1], u[2] * e1[0] - u[0] * e1[2],
                              u[0] * e1[1] - u[1] * e1[0]};
        for (int k = 0; k < 3; k++) e[k] = e1[k], e[3 + k] = e2[k];
    }
}

/* out <- y + the tangent vector of coordinates x (length m) at y (basis of y), not projected. */
void periodic_tangent_add(const whirl_periodic *w, const double *y, const double *x,
                          double *out)
{
    const int per = w->dim - 1;
    const size_t half = w->m / 2;
    const double *len = w->chain->length;
    memcpy(out, y, w->size * sizeof *out);
    double *rate = out + w->size / 2;
    for (size_t i = 0; i < w->n; i++) {
        double d[3], r[3], dd[3] = {0, 0, 0}, dr[3] = {0, 0, 0};
        link_of(w, y, i, d, r);
        const double *e = w->basis + 3 * (size_t)per * i;
        for (int p = 0; p < per; p++)
            for (int k = 0; k < 3; k++) {
                dd[k] += x[(size_t)per * i + (size_t)p] * e[3 * p + k];
                dr[k] += x[half + (size_t)per * i + (size_t)p] * e[3 * p + k];
            }
        const double c = -(r[0] * dd[0] + r[1] * dd[1] + r[2] * dd[2]) / (len[i] * len[i]);
        for (int k = 0; k < 3; k++) {
            if (w->dim == 2 && k == 1) continue;
            out[comp(w, i, k)] += dd[k];
            rate[comp(w, i, k)] += dr[k] + c * d[k];
        }
    }
}

/* x <- the coordinates of y1 - y0 (basis of y0). */
void periodic_tangent_read(const whirl_periodic *w, const double *y0, const double *y1,
                           double *x)
{
    const int per = w->dim - 1;
    const size_t half = w->m / 2, sh = w->size / 2;
    for (size_t i = 0; i < w->n; i++) {
        const double *e = w->basis + 3 * (size_t)per * i;
        for (int p = 0; p < per; p++) {
            double a = 0, b = 0;
            for (int k = 0; k < 3; k++) {
                if (w->dim == 2 && k == 1) continue;
                const size_t q = comp(w, i, k);
                a += e[3 * p + k] * (y1[q] - y0[q]);
                b += e[3 * p + k] * (y1[sh + q] - y0[sh + q]);
            }
            x[(size_t)per * i + (size_t)p] = a;
            x[half + (size_t)per * i + (size_t)p] = b;
        }
    }
}

int whirl_periodic_tangent(whirl_periodic *w, const double *y0, const double *y1, double *coords)
{
    if (w == NULL || y0 == NULL || y1 == NULL || coords == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_periodic_tangent: NULL argument");
    periodic_basis(w, y0);
    periodic_tangent_read(w, y0, y1, coords);
    return GSL_SUCCESS;
}

/* y <- P^periods(y) with steps per period. */
static int run_periods(whirl_periodic *w, double *y, int steps, int periods)
{
    const double period = whirl_pivot_period(&w->path), h = period / steps;
    for (int k = 0; k < periods; k++) {
        double t = 0;
        const int status = whirl_integrator_advance(w->it, &t, y, period, h, 0);
        if (status) return status;
    }
    return GSL_SUCCESS;
}

int whirl_periodic_run(whirl_periodic *w, double *y, int steps, int periods)
{
    if (w == NULL || y == NULL || steps < 1 || periods < 0)
        return whirl_fail(GSL_EINVAL, "whirl_periodic_run: needs a state, steps >= 1 and "
                          "periods >= 0");
    return run_periods(w, y, steps, periods);
}

int whirl_periodic_start_vertical(whirl_periodic *w, int inverted, double *y)
{
    if (w == NULL || y == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_periodic_start_vertical: NULL argument");
    double *links = w->scratch; /* 3 N <= 5 size */
    for (size_t i = 0; i < w->n; i++) {
        links[3 * i] = links[3 * i + 1] = 0;
        links[3 * i + 2] = (inverted ? 1 : -1) * w->chain->length[i];
    }
    double *tmp = malloc(w->size * sizeof *tmp);
    if (tmp == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    const int status = whirl_dyn_state_from_shape(w->dyn, 0, links, 0, tmp);
    if (status == GSL_SUCCESS) memcpy(y, tmp, w->size * sizeof *y);
    free(tmp);
    return status;
}

/* The largest scaled component of P(y) - y: positions over L, rates over omega_ref L. */
double periodic_residual(const whirl_periodic *w, const double *y, const double *py)
{
    double worst = 0;
    const size_t half = w->size / 2;
    for (size_t q = 0; q < w->size; q++) {
        const double scale = q < half ? w->length : w->length * w->omega_ref;
        worst = fmax(worst, fabs(py[q] - y[q]) / scale);
    }
    return isnan(worst) ? INFINITY : worst;
}

/* col <- the central difference (P(y + h t_j) - P(y - h t_j)) / (2 h) in the coordinates at y. */
static int central_difference(whirl_periodic *w, const double *y, size_t j, double h, int steps,
                              double *col)
{
    const size_t m = w->m;
    double *plus = w->scratch + w->size, *minus = w->scratch + 2 * w->size, *x = w->vec;
    memset(x, 0, m * sizeof *x);
    x[j] = h;
    periodic_tangent_add(w, y, x, plus);
    x[j] = -h;
    periodic_tangent_add(w, y, x, minus);
    int status = whirl_dyn_project(w->dyn, 0, plus);
    if (status == GSL_SUCCESS) status = whirl_dyn_project(w->dyn, 0, minus);
    if (status == GSL_SUCCESS) status = run_periods(w, plus, steps, 1);
    if (status == GSL_SUCCESS) status = run_periods(w, minus, steps, 1);
    if (status) return status;
    periodic_tangent_read(w, minus, plus, col);
    for (size_t i = 0; i < m; i++) col[i] /= 2 * h;
    return GSL_SUCCESS;
}

/* w->mono <- the monodromy at y (basis of y made here), steps per period: per column the
 * central differences D(h) and D(h/2), extrapolated (4 D(h/2) - D(h)) / 3 (their error is
 * c h^2 + O(h^4): the map is smooth). */
static int monodromy_differences(whirl_periodic *w, const double *y, int steps)
{
    const size_t m = w->m, half = m / 2;
    const int per = w->dim - 1;
    double *col = w->vec + m, *col2 = w->vec + 2 * m;
    periodic_basis(w, y);
    w->have_mono = 0;
    for (size_t j = 0; j < m; j++) {
        const size_t link = (j % half) / (size_t)per;
        const double h = FD_REL * w->chain->length[link] * (j < half ? 1 : w->omega_ref);
        int status = central_difference(w, y, j, h, steps, col);
        if (status == GSL_SUCCESS) status = central_difference(w, y, j, h / 2, steps, col2);
        if (status) return status;
        for (size_t i = 0; i < m; i++) w->mono[i * m + j] = (4 * col2[i] - col[i]) / 3;
        if ((j + 1) % (m / 16 + 1) == 0) periodic_tick(w, (double)(j + 1) / (double)m);
    }
    w->have_mono = 1;
    return GSL_SUCCESS;
}

/* w->mono <- the monodromy at y by w->method. */
static int monodromy(whirl_periodic *w, const double *y, int steps)
{
    if (w->method == WHIRL_MONODROMY_DIFFERENCES) return monodromy_differences(w, y, steps);
    return periodic_monodromy_variational(w, y, steps);
}

/* delta <- the minimal-norm solution of (M - I) delta = -r (SVD, singular values below SV_CUT
 * of the largest dropped). */
static int newton_step(whirl_periodic *w, const double *r, double *delta)
{
    const size_t m = w->m;
    gsl_matrix *a = w->work, *v = w->v;
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++)
            gsl_matrix_set(a, i, j, w->mono[i * m + j] - (i == j));
    gsl_vector *s = gsl_vector_alloc(m), *work = gsl_vector_alloc(m);
    if (s == NULL || work == NULL) {
        gsl_vector_free(s), gsl_vector_free(work);
        return whirl_fail(GSL_ENOMEM, "out of memory for Newton's step");
    }
    int status = gsl_linalg_SV_decomp(a, v, s, work);
    if (status) {
        gsl_vector_free(s), gsl_vector_free(work);
        return whirl_fail(status, "Newton's step: the SVD of M - I failed");
    }
    const double cut = SV_CUT * gsl_vector_get(s, 0);
    double *ut_r = w->vec + 2 * m;
    for (size_t k = 0; k < m; k++) {
        double dot = 0;
        for (size_t i = 0; i < m; i++) dot += gsl_matrix_get(a, i, k) * -r[i];
        const double sk = gsl_vector_get(s, k);
        ut_r[k] = sk > cut ? dot / sk : 0;
    }
    for (size_t i = 0; i < m; i++) {
        double sum = 0;
        for (size_t k = 0; k < m; k++) sum += gsl_matrix_get(v, i, k) * ut_r[k];
        delta[i] = sum;
    }
    gsl_vector_free(s), gsl_vector_free(work);
    return GSL_SUCCESS;
}

int periodic_solve(whirl_periodic *w, double *y, int steps, double tol, int max_iter,
                   double *residual, int *iterations)
{
    const size_t m = w->m, size = w->size;
    double *py = w->scratch + 3 * size, *trial = w->scratch + 4 * size;
    double *r = w->vec + 3 * m, *delta = w->vec + 4 * m;
    double *trial_p = malloc(size * sizeof *trial_p), *best = malloc(size * sizeof *best);
    if (trial_p == NULL || best == NULL) {
        free(trial_p), free(best);
        return whirl_fail(GSL_ENOMEM, "out of memory");
    }
    int status = whirl_dyn_project(w->dyn, 0, y);
    memcpy(py, y, size * sizeof *py);
    if (status == GSL_SUCCESS) status = run_periods(w, py, steps, 1);
    double res = status ? INFINITY : periodic_residual(w, y, py);
    int iter = 0;
    w->progress.iteration = 0, w->progress.residual = res;
    periodic_tick(w, 0);
    while (status == GSL_SUCCESS && !(res <= tol)) {
        if (iter == max_iter) {
            status = whirl_fail(GSL_EMAXITER, "Newton's method on the period map did not "
                                "converge in %d iterations: residual %.3g (tolerance %.3g); no "
                                "periodic motion, no multipliers", max_iter, res, tol);
            break;
        }
        iter++;
        status = monodromy(w, y, steps);
        if (status) break;
        periodic_tangent_read(w, y, py, r);
        status = newton_step(w, r, delta);
        if (status) break;
        /* backtracking: halve the step while it raises the residual */
        double best_res = INFINITY, scale = 1;
        for (int k = 0; k <= BACKTRACK_MAX && status == GSL_SUCCESS; k++, scale /= 2) {
            for (size_t i = 0; i < m; i++) w->vec[i] = scale * delta[i];
            periodic_tangent_add(w, y, w->vec, trial);
            status = whirl_dyn_project(w->dyn, 0, trial);
            memcpy(trial_p, trial, size * sizeof *trial_p);
            if (status == GSL_SUCCESS) status = run_periods(w, trial_p, steps, 1);
            if (status == GSL_EMAXITER || status == GSL_EBADFUNC) status = GSL_SUCCESS; /* too far */
            else if (status == GSL_SUCCESS) {
                const double tr = periodic_residual(w, trial, trial_p);
                if (tr < best_res) {
                    best_res = tr;
                    memcpy(best, trial, size * sizeof *best);
                    memcpy(w->scratch, trial_p, size * sizeof *trial_p); /* P(best) */
                }
                if (tr < res) break;
            }
        }
        if (status) break;
        if (!isfinite(best_res)) {
            status = whirl_fail(GSL_EFAILED, "Newton's method on the period map: no step from "
                                "residual %.3g can be integrated over a period", res);
            break;
        }
        memcpy(y, best, size * sizeof *y);
        memcpy(py, w->scratch, size * sizeof *py);
        res = best_res;
        w->progress.iteration = iter, w->progress.residual = res;
        periodic_tick(w, 0);
    }
    free(trial_p), free(best);
    *residual = res;
    *iterations = iter;
    if (status == GSL_SUCCESS) status = monodromy(w, y, steps);
    return status;
}

/* The multipliers of w->mono into re, im (by decreasing modulus). */
int periodic_multipliers(whirl_periodic *w, double *re, double *im)
{
    const size_t m = w->m;
    for (size_t i = 0; i < m; i++)
        for (size_t j = 0; j < m; j++) gsl_matrix_set(w->work, i, j, w->mono[i * m + j]);
    int status = gsl_eigen_nonsymm(w->work, w->eval, w->eig);
    if (status) return whirl_fail(status, "the eigenvalues of the monodromy did not converge");
    for (size_t i = 0; i < m; i++) {
        const gsl_complex z = gsl_vector_complex_get(w->eval, i);
        re[i] = GSL_REAL(z), im[i] = GSL_IMAG(z);
    }
    /* insertion sort by decreasing modulus, then decreasing imaginary part */
    for (size_t i = 1; i < m; i++) {
        const double r0 = re[i], i0 = im[i], a0 = hypot(r0, i0);
        size_t j = i;
        for (; j > 0; j--) {
            const double aj = hypot(re[j - 1], im[j - 1]);
            if (aj > a0 || (aj == a0 && im[j - 1] >= i0)) break;
            re[j] = re[j - 1], im[j] = im[j - 1];
        }
        re[j] = r0, im[j] = i0;
    }
    return GSL_SUCCESS;
}
