/* Continuation of periodic motions in the path's rate or amplitude (whirl/periodic.h,
 * whirl_periodic_path): pseudo-arclength on the period map, with folds of cycles, branch points
 * and period doublings located on the way.
 *
 * Unknowns u = (y, p): the state at t = 0 and the parameter. Equations
 *   G(y, p) = E^T (P_p(y) - y) = 0   (m tangent coordinates, E the basis of the step's start),
 *   N(y, p) = <t0, y - y0>_W + tp0 (p - p0) - sigma = 0,
 * with <a, b>_W the scaled product of two Cartesian states (positions over L, rates over
 * omega_ref L, the scales of Newton's residual) and (t0, tp0) the unit tangent at the step's
 * start (y0, p0). E^T (P(y) - y) = 0 and P(y), y both on the constraint manifold (of dimension
 * m) give P(y) = y near y0: the equations are exact; their Jacobian in the tangent coordinates
 * at y0 is the bordered matrix
 *   J = [ M - I   P_p ]      M the monodromy at y0, P_p = E^T dP/dp by central differences
 *       [ c^T     tp0 ]      of the period map (relative step 1e-5), c_j = <t0, B e_j>_W,
 * B e_j the tangent vector of coordinate j. J is factored once per step (at its start) and
 * serves as the chord of Newton's method for every corrected point of the step: the corrector
 * converges linearly, with a ratio of the order of the step times the branch's curvature.
 * The tangent at a new point: J' z = (0, 1) with J' = [M - I, P_p; c_prev^T, tp_prev] (the row of
 * the previous tangent: the new one continues it without turning back), then normalised.
 *
 * Test functions at each point: f_+ = det(M - I), f_- = det(M + I) as sign |det|^(1/m). For
 * the conservative chain a pair mu, 1/mu (rho = mu + 1/mu) gives the factor 2 - rho of f_+ and
 * 2 + rho of f_-: they change sign where a pair passes +1 (a fold: the branch turns back, where
 * the tangent's tp changes sign; or a branch point: another branch of motions crosses) and -1
 * (period doubling). A sign change along a step is located by Brent's method in sigma in
 * [0, ds]; each evaluation corrects the point at sigma with s and with 2 s steps per period and
 * extrapolates f and p (Gauss, order 4: x = x(2s) + (x(2s) - x(s)) / 15): the location is of the
 * exact period map, not of its discretisation. Its error estimate: the bracket's width in p
 * (|tp| times the width in sigma), the change of the root by the extrapolation (the shift of f
 * over its slope, times |tp|), and the change of p by it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "periodic/cycle_internal.h"

#define STEP_DEFAULT 0.05
#define POINTS_DEFAULT 10000
#define TOL_DEFAULT 1e-10
#define ITER_DEFAULT 30
/* An event's bracket in sigma: two orders below the 1e-8 asked of the location in p
 * (|dp/dsigma| <= 1). */
#define EVENT_TOL_DEFAULT 1e-10
/* Chord iterations before a step is refused: from a predictor a step away, with the ratio of
 * the chord's linear convergence ~0.1, 1e-10 is reached in about 8. */
#define CORRECTOR_MAX 12
/* The chord refreshed (Newton's Jacobian at the iterate) where an iteration does not halve the
 * residual, at most REFRESH_MAX times per corrected point. */
#define CHORD_RATIO 0.5
#define REFRESH_MAX 3
#define CORRECTOR_EASY 5   /* a step that took at most this many: the next one longer */
#define STEP_GROW 1.5
#define STEP_MIN_RATIO 1e-6 /* the smallest step, over the largest */
/* A step whose tangent turns by more than 0.2 rad is refused: the chord and the sign tests of
 * the events assume the branch nearly straight across a step. */
#define TURN_MAX 0.2
/* Relative step of the parameter's central differences: truncation (1e-5)^2 against round-off
 * 1e-16 / 1e-5 of the map; the derivative serves the chord and the tangent only. */
#define DP_REL 1e-5

const char *whirl_cycle_event_name(whirl_cycle_event e)
{
    switch (e) {
    case WHIRL_CYCLE_POINT: return "point";
    case WHIRL_CYCLE_FOLD: return "fold";
    case WHIRL_CYCLE_BRANCH: return "branch";
    case WHIRL_CYCLE_PERIOD_DOUBLING: return "period-doubling";
    case WHIRL_CYCLE_TORUS: return "torus";
    }
    return "unknown";
}

void cycle_set_param(cycle *c, double p)
{
    whirl_pivot_path path = c->base;
    if (c->p.parameter == WHIRL_CYCLE_OMEGA) {
        path.omega = p;
    } else if (c->p.parameter == WHIRL_CYCLE_ELLIPTICITY) {
        for (int j = 0; j < path.harmonics; j++) path.c[1][j] *= 1 - p, path.s[1][j] *= 1 - p;
    } else {
        const double f = p / c->base_amp;
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < path.harmonics; j++) path.c[k][j] *= f, path.s[k][j] *= f;
    }
    periodic_set_path(c->w, &path);
}

const char *cycle_where(const cycle *c, double p, char *buf, size_t size)
{
    if (c->p.parameter == WHIRL_CYCLE_OMEGA) snprintf(buf, size, "omega=" WHIRL_Q_RATE "%.17g", p);
    else if (c->p.parameter == WHIRL_CYCLE_ELLIPTICITY) snprintf(buf, size, "e=%.17g", p);
    else snprintf(buf, size, "A=" WHIRL_Q_LENGTH "%.17g", p);
    return buf;
}

/* The parameter's value at the start: the path's rate, its amplitude, or e = 0. */
static double cycle_start(const cycle *c)
{
    switch (c->p.parameter) {
    case WHIRL_CYCLE_OMEGA: return c->base.omega;
    case WHIRL_CYCLE_AMPLITUDE: return c->base_amp;
    case WHIRL_CYCLE_ELLIPTICITY: return 0;
    }
    return NAN;
}

/* The largest Fourier amplitude of the path's y terms. */
static double cycle_y_amplitude(const whirl_pivot_path *path)
{
    double a = 0;
    for (int j = 0; j < path->harmonics; j++)
        a = fmax(a, fmax(fabs(path->c[1][j]), fabs(path->s[1][j])));
    return a;
}

static void tick(cycle *c)
{
    if (c->tick) c->tick(c->tick_data, &c->progress);
}

/* <a, b>_W of two Cartesian states (or differences). */
static double wdot(const cycle *c, const double *a, const double *b)
{
    const size_t half = c->size / 2;
    double sp = 0, sr = 0;
    for (size_t q = 0; q < half; q++) sp += a[q] * b[q], sr += a[half + q] * b[half + q];
    return c->wpos * sp + c->wrate * sr;
}

static void set_metric(cycle *c)
{
    const double l = c->w->length, r = c->w->omega_ref * l;
    c->wpos = 1 / (l * l), c->wrate = 1 / (r * r);
}

/* out <- P_p(y) with steps per period. */
static int period_map(cycle *c, double p, const double *y, int steps, double *out)
{
    cycle_set_param(c, p);
    memcpy(out, y, c->size * sizeof *out);
    return whirl_periodic_run(c->w, out, steps, 1);
}

/* The frame at y: basis (w->basis made here and copied) and cols (column j, size long: the
 * tangent vector of coordinate j). */
static void frame_at(cycle *c, const double *y, double *basis, double *cols)
{
    periodic_basis(c->w, y);
    memcpy(basis, c->w->basis, c->nb * sizeof *basis);
    double *x = c->a;
    memset(x, 0, c->m * sizeof *x);
    for (size_t j = 0; j < c->m; j++) {
        x[j] = 1;
        double *col = cols + j * c->size;
        periodic_tangent_add(c->w, y, x, col);
        for (size_t q = 0; q < c->size; q++) col[q] -= y[q];
        x[j] = 0;
    }
}

/* pp <- E^T dP/dp at (y, p) by central differences with steps per period (E: basis). */
static int param_derivative(cycle *c, const double *y, double p, int steps, double *basis,
                            double *pp)
{
    const double h = DP_REL * (c->p.parameter == WHIRL_CYCLE_OMEGA       ? p
                               : c->p.parameter == WHIRL_CYCLE_ELLIPTICITY ? 1
                                                                           : fmax(p, c->base_amp));
    int status = period_map(c, p + h, y, steps, c->a);
    if (status == GSL_SUCCESS) status = period_map(c, p - h, y, steps, c->b);
    cycle_set_param(c, p);
    if (status) return status;
    memcpy(c->w->basis, basis, c->nb * sizeof *basis);
    periodic_tangent_read(c->w, c->b, c->a, pp);
    for (size_t i = 0; i < c->m; i++) pp[i] /= 2 * h;
    return GSL_SUCCESS;
}

/* (m+1) x (m+1) matrix [mono - I, pp; row(t) , tp] into a, row_j = <t, cols_j>_W. */
static void bordered(const cycle *c, gsl_matrix *a, const double *mono, const double *pp,
                     const double *cols, const double *t, double tp)
{
    const size_t m = c->m;
    for (size_t i = 0; i < m; i++) {
        for (size_t j = 0; j < m; j++) gsl_matrix_set(a, i, j, mono[i * m + j] - (i == j));
        gsl_matrix_set(a, i, m, pp[i]);
    }
    for (size_t j = 0; j < m; j++) gsl_matrix_set(a, m, j, t ? wdot(c, t, cols + j * c->size) : 0);
    gsl_matrix_set(a, m, m, tp);
}

/* The unit tangent (t, tp) at the point of mono, pp, cols continuing (t_prev, tp_prev). */
static int tangent(cycle *c, const double *mono, const double *pp, const double *cols,
                   const double *t_prev, double tp_prev, double *t, double *tp)
{
    const size_t m = c->m;
    int sign;
    bordered(c, c->bord, mono, pp, cols, t_prev, tp_prev);
    gsl_vector_set_zero(c->rhs);
    gsl_vector_set(c->rhs, m, 1);
    int status = gsl_linalg_LU_decomp(c->bord, c->perm_b, &sign);
    if (status == GSL_SUCCESS) status = gsl_linalg_LU_solve(c->bord, c->perm_b, c->rhs, c->sol);
    if (status)
        return whirl_fail(GSL_ESING, "the branch has no unique tangent at %s (the bordered "
                          "Jacobian is singular)", WHERE(c, c->p1));
    memset(t, 0, c->size * sizeof *t);
    for (size_t j = 0; j < m; j++) {
        const double z = gsl_vector_get(c->sol, j);
        const double *col = cols + j * c->size;
        for (size_t q = 0; q < c->size; q++) t[q] += z * col[q];
    }
    *tp = gsl_vector_get(c->sol, m);
    const double norm = sqrt(wdot(c, t, t) + *tp * *tp);
    if (!(norm > 0 && isfinite(norm)))
        return whirl_fail(GSL_ESING, "the branch has no unique tangent (the bordered Jacobian "
                          "is singular)");
    for (size_t q = 0; q < c->size; q++) t[q] /= norm;
    *tp /= norm;
    return GSL_SUCCESS;
}

/* The chord of the step: J at its start, factored. */
static int chord(cycle *c)
{
    int sign;
    bordered(c, c->jac, c->mono0, c->pp0, c->cols0, c->t0, c->tp0);
    memcpy(c->basis_j, c->basis0, c->nb * sizeof *c->basis0);
    const int status = gsl_linalg_LU_decomp(c->jac, c->perm, &sign);
    return status ? whirl_fail(status, "the chord of the continuation cannot be factored") : 0;
}

/* The chord refreshed at (y, p) with steps per period: Newton's Jacobian there. Near a pair of
 * multipliers close to +1 (the circle drive's slow mode at small radii: M - I nearly
 * singular), J changes along a step by more than the chord's linear convergence allows. */
static int refresh(cycle *c, const double *y, double p, int steps)
{
    cycle_set_param(c, p);
    int status = periodic_monodromy_variational(c->w, y, steps);
    if (status) return status;
    frame_at(c, y, c->basis_j, c->cols_j);
    status = param_derivative(c, y, p, steps, c->basis_j, c->pp_j);
    if (status) return status;
    int sign;
    bordered(c, c->jac, c->w->mono, c->pp_j, c->cols_j, c->t0, c->tp0);
    status = gsl_linalg_LU_decomp(c->jac, c->perm, &sign);
    return status ? whirl_fail(status, "the Jacobian of the continuation cannot be factored") : 0;
}

/* Corrects (y, p) (a start near the point at sigma) onto the branch with steps per period by
 * the chord, refreshed where it converges slowly; *res its residual. GSL_EMAXITER (no message)
 * if it does not converge. */
int cycle_correct(cycle *c, double sigma, int steps, double *y, double *p, int *iters,
                   double *res)
{
    const size_t m = c->m, size = c->size;
    double first = INFINITY, last = INFINITY;
    int refreshes = 0;
    for (int k = 0;; k++) {
        int status = period_map(c, *p, y, steps, c->py);
        if (status == GSL_EMAXITER || status == GSL_EBADFUNC) return GSL_EMAXITER;
        if (status) return status;
        *res = periodic_residual(c->w, y, c->py);
        for (size_t q = 0; q < size; q++) c->tmp[q] = y[q] - c->y0[q];
        const double arc = wdot(c, c->t0, c->tmp) + c->tp0 * (*p - c->p0) - sigma;
        c->progress.iteration = k, c->progress.residual = *res;
        tick(c);
        *iters = k;
        if (*res <= c->target && fabs(arc) <= c->target) return GSL_SUCCESS;
        const int slow = k > 0 && *res > CHORD_RATIO * last;
        /* the events' tighter target where round-off stops the iteration: the test's */
        if ((k == CORRECTOR_MAX || (slow && refreshes == REFRESH_MAX)) && *res <= c->p.tol &&
            fabs(arc) <= c->p.tol)
            return GSL_SUCCESS;
        if (k == CORRECTOR_MAX || !isfinite(*res) || *res > 1e3 * fmin(first, 1e-2))
            return GSL_EMAXITER;
        if (k == 0) first = *res;
        if (slow && refreshes < REFRESH_MAX) {
            refreshes++;
            if ((status = refresh(c, y, *p, steps))) return status;
        }
        last = *res;
        memcpy(c->w->basis, c->basis_j, c->nb * sizeof *c->basis_j);
        periodic_tangent_read(c->w, y, c->py, c->a);
        for (size_t i = 0; i < m; i++) gsl_vector_set(c->rhs, i, -c->a[i]);
        gsl_vector_set(c->rhs, m, -arc);
        gsl_linalg_LU_solve(c->jac, c->perm, c->rhs, c->sol);
        for (size_t i = 0; i < m; i++) c->a[i] = gsl_vector_get(c->sol, i);
        periodic_tangent_add(c->w, y, c->a, c->tmp);
        status = whirl_dyn_project(c->w->dyn, 0, c->tmp);
        if (status) return GSL_EMAXITER;
        memcpy(y, c->tmp, size * sizeof *y);
        *p += gsl_vector_get(c->sol, m);
    }
}

/* The predictor at sigma from the step's start, corrected with steps per period. */
int cycle_point_at(cycle *c, double sigma, int steps, double *y, double *p, int *iters,
                    double *res)
{
    for (size_t q = 0; q < c->size; q++) y[q] = c->y0[q] + sigma * c->t0[q];
    *p = c->p0 + sigma * c->tp0;
    if (whirl_dyn_project(c->w->dyn, 0, y)) return GSL_EMAXITER;
    return cycle_correct(c, sigma, steps, y, p, iters, res);
}

static int emit(cycle *c, const report *r)
{
    return c->row ? c->row(c->row_data, &r->pt) : GSL_SUCCESS;
}

/* ---- the branch ---- */

static int check_params(cycle *c, const whirl_cycle_params *params)
{
    whirl_cycle_params *p = &c->p;
    if (params == NULL) return whirl_fail(GSL_EINVAL, "whirl_periodic_path: needs parameters");
    *p = *params;
    if (p->step == 0) p->step = STEP_DEFAULT;
    if (p->max_points == 0) p->max_points = POINTS_DEFAULT;
    if (p->tol == 0) p->tol = TOL_DEFAULT;
    if (p->max_iter == 0) p->max_iter = ITER_DEFAULT;
    if (p->event_tol == 0) p->event_tol = EVENT_TOL_DEFAULT;
    if (p->parameter != WHIRL_CYCLE_OMEGA && p->parameter != WHIRL_CYCLE_AMPLITUDE &&
        p->parameter != WHIRL_CYCLE_ELLIPTICITY)
        return whirl_fail(GSL_EINVAL, "unknown continuation parameter %d", (int)p->parameter);
    if (!(isfinite(p->min) && isfinite(p->max) && p->min < p->max) ||
        (p->parameter == WHIRL_CYCLE_OMEGA && !(p->min > 0)) ||
        (p->parameter == WHIRL_CYCLE_AMPLITUDE && !(p->min >= 0)))
        return whirl_fail(GSL_EINVAL, "the continuation needs %s min < max, finite, got %g, %g",
                          p->parameter == WHIRL_CYCLE_OMEGA ? "0 <" : "0 <=", p->min, p->max);
    if (p->direction != 1 && p->direction != -1)
        return whirl_fail(GSL_EINVAL, "direction must be +1 or -1, got %d", p->direction);
    if (!(isfinite(p->step) && p->step > 0) || p->max_points < 1 || !(p->tol > 0) ||
        !isfinite(p->tol) || p->max_iter < 1 || !(p->event_tol > 0) || p->steps < 0 ||
        (p->steps > 0 && p->steps < 8) || p->steps > 1 << 24)
        return whirl_fail(GSL_EINVAL, "the continuation needs step > 0, max_points >= 1, tol > 0, "
                          "max_iter >= 1, event_tol > 0 and steps 0 or 8..%d", 1 << 24);
    const double start = cycle_start(c);
    if (p->parameter == WHIRL_CYCLE_AMPLITUDE && !(c->base_amp > 0))
        return whirl_fail(GSL_EINVAL, "an amplitude continuation needs a path that moves");
    if (p->parameter == WHIRL_CYCLE_ELLIPTICITY && !(cycle_y_amplitude(&c->base) > 0))
        return whirl_fail(GSL_EINVAL, "an ellipticity continuation needs a path that moves "
                          "along y");
    if (!(start >= p->min && start <= p->max))
        return whirl_fail(GSL_EINVAL, "the start's %s %.17g is outside [%.17g, %.17g]",
                          p->parameter == WHIRL_CYCLE_OMEGA         ? "rate"
                          : p->parameter == WHIRL_CYCLE_ELLIPTICITY ? "ellipticity"
                                                                    : "amplitude", start,
                          p->min, p->max);
    return GSL_SUCCESS;
}

static void cycle_free(cycle *c)
{
    double *bufs[] = {c->y0, c->t0, c->basis0, c->mono0, c->cols0, c->pp0, c->y1, c->t1,
                      c->basis1, c->mono1, c->cols1, c->pp1, c->basis_j, c->cols_j, c->pp_j,
                      c->py, c->tmp, c->a, c->b, c->ys, c->yf, c->zero, c->sr, c->si, c->rr,
                      c->ri, c->re_t, c->im_t, c->now.y, c->now.re, c->now.im, c->ev[0].y,
                      c->ev[0].re, c->ev[0].im, c->ev[1].y, c->ev[1].re, c->ev[1].im, c->ev[2].y,
                      c->ev[2].re, c->ev[2].im};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++) free(bufs[i]);
    free(c->used);
    if (c->jac) gsl_matrix_free(c->jac);
    if (c->bord) gsl_matrix_free(c->bord);
    if (c->lu) gsl_matrix_free(c->lu);
    if (c->inv) gsl_matrix_free(c->inv);
    if (c->perm) gsl_permutation_free(c->perm);
    if (c->perm_b) gsl_permutation_free(c->perm_b);
    if (c->perm_m) gsl_permutation_free(c->perm_m);
    if (c->rhs) gsl_vector_free(c->rhs);
    if (c->sol) gsl_vector_free(c->sol);
}

static int cycle_alloc(cycle *c)
{
    const size_t m = c->m, size = c->size, nb = c->nb;
    double **sized[] = {&c->y0, &c->t0, &c->y1, &c->t1, &c->py, &c->tmp, &c->a, &c->b, &c->ys,
                        &c->yf, &c->now.y, &c->ev[0].y, &c->ev[1].y, &c->ev[2].y};
    double **msized[] = {&c->pp0, &c->pp1, &c->pp_j, &c->sr, &c->si, &c->rr, &c->ri,
                         &c->re_t, &c->im_t, &c->zero, &c->now.re, &c->now.im, &c->ev[0].re,
                         &c->ev[0].im, &c->ev[1].re, &c->ev[1].im, &c->ev[2].re, &c->ev[2].im};
    int ok = 1;
    for (size_t i = 0; i < sizeof sized / sizeof sized[0]; i++)
        ok &= (*sized[i] = calloc(size, sizeof **sized[i])) != NULL;
    for (size_t i = 0; i < sizeof msized / sizeof msized[0]; i++)
        ok &= (*msized[i] = calloc(m, sizeof **msized[i])) != NULL;
    ok &= (c->used = malloc(m)) != NULL;
    ok &= (c->basis0 = malloc(nb * sizeof *c->basis0)) != NULL;
    ok &= (c->basis1 = malloc(nb * sizeof *c->basis1)) != NULL;
    ok &= (c->mono0 = malloc(m * m * sizeof *c->mono0)) != NULL;
    ok &= (c->mono1 = malloc(m * m * sizeof *c->mono1)) != NULL;
    ok &= (c->cols0 = malloc(m * size * sizeof *c->cols0)) != NULL;
    ok &= (c->cols1 = malloc(m * size * sizeof *c->cols1)) != NULL;
    ok &= (c->cols_j = malloc(m * size * sizeof *c->cols_j)) != NULL;
    ok &= (c->basis_j = malloc(nb * sizeof *c->basis_j)) != NULL;
    ok &= (c->jac = gsl_matrix_alloc(m + 1, m + 1)) != NULL;
    ok &= (c->bord = gsl_matrix_alloc(m + 1, m + 1)) != NULL;
    ok &= (c->lu = gsl_matrix_alloc(m, m)) != NULL;
    ok &= (c->inv = gsl_matrix_alloc(m, m)) != NULL;
    ok &= (c->perm = gsl_permutation_alloc(m + 1)) != NULL;
    ok &= (c->perm_b = gsl_permutation_alloc(m + 1)) != NULL;
    ok &= (c->perm_m = gsl_permutation_alloc(m)) != NULL;
    ok &= (c->rhs = gsl_vector_alloc(m + 1)) != NULL;
    ok &= (c->sol = gsl_vector_alloc(m + 1)) != NULL;
    return ok ? GSL_SUCCESS
              : whirl_fail(GSL_ENOMEM, "out of memory for the continuation (%zu x %zu)", m, size);
}

/* The end point's monodromy (in w->mono, at y1) into mono1, basis1, its frame, the parameter's
 * derivative and the tangent continuing (t_prev, tp_prev). */
static int end_frame(cycle *c, const double *t_prev, double tp_prev)
{
    memcpy(c->mono1, c->w->mono, c->m * c->m * sizeof *c->mono1);
    frame_at(c, c->y1, c->basis1, c->cols1);
    int status = param_derivative(c, c->y1, c->p1, c->steps, c->basis1, c->pp1);
    if (status == GSL_SUCCESS)
        status = tangent(c, c->mono1, c->pp1, c->cols1, t_prev, tp_prev, c->t1, &c->tp1);
    return status;
}

/* The end becomes the start. */
static void advance(cycle *c)
{
#define SWAP(a, b) do { double *s_ = a; a = b; b = s_; } while (0)
    SWAP(c->y0, c->y1);
    SWAP(c->t0, c->t1);
    SWAP(c->basis0, c->basis1);
    SWAP(c->mono0, c->mono1);
    SWAP(c->cols0, c->cols1);
    SWAP(c->pp0, c->pp1);
#undef SWAP
    c->p0 = c->p1, c->tp0 = c->tp1;
}

static int in_range(const cycle *c, double p) { return p >= c->p.min && p <= c->p.max; }

/* One accepted step from (y0, p0) (its chord factored): its events and end point handed out.
 * *ds the step to try (halved on a refusal, grown after an easy one); *ended 1 where the branch
 * left the range. */
static int step(cycle *c, double *ds, int *ended)
{
    for (;;) {
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "stopped at %s after %ld points", WHERE(c, c->p0),
                              c->progress.points);
        c->progress.step = *ds;
        int iters;
        double res;
        int status = cycle_point_at(c, *ds, c->steps, c->y1, &c->p1, &iters, &res);
        if (status == GSL_SUCCESS)
            status = periodic_monodromy_variational(c->w, c->y1, c->steps);
        if (status == GSL_SUCCESS) status = end_frame(c, c->t0, c->tp0);
        int refused = status == GSL_EMAXITER || status == GSL_ESING;
        if (status == GSL_SUCCESS)
            refused = acos(fmin(1, wdot(c, c->t0, c->t1) + c->tp0 * c->tp1)) > TURN_MAX;
        else if (!refused)
            return status;
        if (refused) {
            *ds /= 2;
            if (*ds < STEP_MIN_RATIO * c->p.step)
                return whirl_fail(GSL_EMAXITER, "the continuation fails at %s: the "
                                  "corrector did not converge (residual %.3g, tolerance %.3g) "
                                  "at the smallest step %.3g", WHERE(c, c->p0), res, c->p.tol, *ds);
            continue;
        }
        /* the end point's report before the events' evaluations overwrite w->mono */
        memcpy(c->w->mono, c->mono1, c->m * c->m * sizeof *c->mono1);
        c->arclength += *ds;
        status = cycle_describe(c, &c->now, c->y1, c->p1, c->tp1, iters, res);
        c->arclength -= *ds;
        if (status) return status;
        /* the events of the step, by sigma */
        int n = 0;
        const double f1[3] = {c->now.pt.fold_test, c->now.pt.flip_test, c->now.pt.torus_test};
        for (int k = 0; k < 3; k++) {
            if ((c->f0[k] < 0) == (f1[k] < 0)) continue;
            /* a torus test that is 0 at both ends: pairs equal by a symmetry (the 3D chain
               hanging: each plane's), not a meeting */
            if (k == 2 && c->gap0 < GAP_MIN && c->now.gap < GAP_MIN) continue;
            status = cycle_locate_event(c, k, *ds, &c->ev[n]);
            if (status) return status;
            n++;
        }
        /* a change of the verdict that no test saw (pairs equal by a symmetry) */
        const int unstable1 = c->now.pt.verdict == WHIRL_FLOQUET_UNSTABLE;
        if (n == 0 && unstable1 != c->unstable0) {
            status = cycle_locate_event(c, 3, *ds, &c->ev[n]);
            if (status) return status;
            n++;
        }
        cycle_set_param(c, c->p1);
        for (int i = 1; i < n; i++) /* by sigma */
            for (int j = i; j > 0 && c->ev[j].sigma < c->ev[j - 1].sigma; j--) {
                const report r = c->ev[j];
                c->ev[j] = c->ev[j - 1], c->ev[j - 1] = r;
            }
        for (int k = 0; k < n; k++) {
            if (c->ev[k].pt.event == WHIRL_CYCLE_POINT || !in_range(c, c->ev[k].pt.parameter))
                continue;
            c->progress.events++;
            if ((status = emit(c, &c->ev[k]))) return status;
        }
        c->arclength += *ds;
        c->f0[0] = c->now.pt.fold_test, c->f0[1] = c->now.pt.flip_test;
        c->f0[2] = c->now.pt.torus_test, c->gap0 = c->now.gap;
        c->unstable0 = unstable1;
        c->mu0[0] = c->now.re[0], c->mu0[1] = c->now.im[0];
        if (!in_range(c, c->p1)) {
            *ended = 1;
            return GSL_SUCCESS;
        }
        c->progress.points++;
        c->progress.parameter = c->p1;
        if ((status = emit(c, &c->now))) return status;
        tick(c);
        if (iters <= CORRECTOR_EASY) *ds = fmin(STEP_GROW * *ds, c->p.step);
        return GSL_SUCCESS;
    }
}

int whirl_periodic_path(whirl_periodic *w, double *y, const whirl_cycle_params *params,
                        whirl_cycle_row_fn row, void *row_data, whirl_cycle_tick_fn tick_fn,
                        void *tick_data)
{
    if (w == NULL || y == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_periodic_path: NULL argument");
    cycle c = {.w = w, .base = w->path, .base_amp = cycle_amplitude(&w->path), .m = w->m,
               .size = w->size, .nb = 3 * (size_t)(w->dim - 1) * w->n, .row = row,
               .row_data = row_data, .tick = tick_fn, .tick_data = tick_data};
    int status = check_params(&c, params);
    if (status) return status;
    c.target = c.p.tol;
    for (size_t q = 0; q < w->size; q++)
        if (!isfinite(y[q])) return whirl_fail(GSL_EINVAL, "the start state is not finite");
    if ((status = cycle_alloc(&c))) goto done;
    w->method = WHIRL_MONODROMY_VARIATIONAL;
    c.p1 = cycle_start(&c);
    cycle_set_param(&c, c.p1);
    status = whirl_dyn_project(w->dyn, 0, y);
    /* the steps: raised, as whirl_periodic_find raises them, at the range's ends as well (the
       longest period and the strongest shaking; as the chart does) */
    const double at[3] = {c.p.min, c.p.max, c.p1};
    for (int k = 0; k < 3 && status == GSL_SUCCESS; k++) {
        int need;
        cycle_set_param(&c, at[k]);
        status = periodic_steps_for(w, y, c.p.steps, &need);
        if (status == GSL_SUCCESS && need > c.steps) c.steps = need;
    }
    /* the start: Newton's method at the fixed parameter, the monodromy at the motion */
    double res;
    int iters;
    if (status == GSL_SUCCESS)
        status = periodic_solve(w, y, c.steps, c.p.tol, c.p.max_iter, &res, &iters);
    if (status) goto done;
    set_metric(&c);
    memcpy(c.y1, y, w->size * sizeof *y);
    status = end_frame(&c, NULL, c.p.direction);
    if (status == GSL_SUCCESS) {
        memcpy(w->mono, c.mono1, c.m * c.m * sizeof *c.mono1);
        status = cycle_describe(&c, &c.now, c.y1, c.p1, c.tp1, iters, res);
    }
    if (status) goto done;
    c.f0[0] = c.now.pt.fold_test, c.f0[1] = c.now.pt.flip_test;
    c.f0[2] = c.now.pt.torus_test, c.gap0 = c.now.gap;
    c.unstable0 = c.now.pt.verdict == WHIRL_FLOQUET_UNSTABLE;
    c.mu0[0] = c.now.re[0], c.mu0[1] = c.now.im[0];
    c.progress.points = 1;
    c.progress.parameter = c.p1;
    if ((status = emit(&c, &c.now))) goto done;
    tick(&c);
    advance(&c);
    double ds = c.p.step;
    int ended = 0;
    while (!ended && c.progress.points < c.p.max_points) {
        set_metric(&c);
        const double norm = sqrt(wdot(&c, c.t0, c.t0) + c.tp0 * c.tp0);
        for (size_t q = 0; q < c.size; q++) c.t0[q] /= norm;
        c.tp0 /= norm;
        if ((status = chord(&c))) break;
        if ((status = step(&c, &ds, &ended))) break;
        if (!ended) advance(&c);
    }
    memcpy(y, c.y0, w->size * sizeof *y);
    cycle_set_param(&c, c.p0);
    if (status == WHIRL_EINTERRUPTED) /* within a period: said of the branch */
        status = whirl_fail(WHIRL_EINTERRUPTED, "stopped at %s after %ld points",
                            WHERE(&c, c.p0), c.progress.points);
done:
    cycle_free(&c);
    return status;
}
