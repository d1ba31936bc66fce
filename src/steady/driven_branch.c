/* The hand-swung chain's branches against the rate: pseudo-arclength continuation in
 * u = (X, Y, omega) with folds located by Brent's method (the method: src/steady/driven.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "whirl/driven.h"
#include "core/error.h"
#include "core/roots.h"
#include "steady/driven_internal.h"

whirl_driven_curve *whirl_driven_curve_alloc(size_t capacity)
{
    if (capacity < 2) {
        whirl_fail(GSL_EINVAL, "a curve needs room for at least 2 points, got %zu", capacity);
        return NULL;
    }
    whirl_driven_curve *curve = calloc(1, sizeof *curve);
    if (curve == NULL) goto fail;
    curve->capacity = capacity;
    curve->point = malloc(capacity * sizeof *curve->point);
    curve->fold = malloc(capacity * sizeof *curve->fold);
    if (curve->point == NULL || curve->fold == NULL) goto fail;
    return curve;
fail:
    whirl_driven_curve_free(curve);
    whirl_fail(GSL_ENOMEM, "out of memory for a curve of %zu points", capacity);
    return NULL;
}

void whirl_driven_curve_free(whirl_driven_curve *curve)
{
    if (curve == NULL) return;
    free(curve->point);
    free(curve->fold);
    free(curve);
}

/* The unit tangent of the branch at u (null vector of dR/du = cross product of its rows),
 * oriented along ref (or with sign(tau_omega) = direction when ref is NULL), and the fold
 * function D = det dR/d(X, Y). */
static int branch_tangent(problem *pb, const double *u, const double *ref, int direction,
                          double *tau, double *D)
{
    double R[3], J[3][3];
    int status = driven_pivot_miss(pb, u, R, J);
    if (status) return status;
    tau[0] = J[0][1] * J[1][2] - J[0][2] * J[1][1];
    tau[1] = J[0][2] * J[1][0] - J[0][0] * J[1][2];
    tau[2] = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    *D = tau[2];
    const double norm = sqrt(tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]);
    if (!(norm > 0))
        return whirl_fail(GSL_EFAILED, "the branch has no unique tangent at omega " WHIRL_Q_RATE
                          "%g (a bifurcation point)", u[2]);
    const double orient = ref ? ref[0] * tau[0] + ref[1] * tau[1] + ref[2] * tau[2]
                              : direction * tau[2];
    for (int k = 0; k < 3; k++) tau[k] *= (orient < 0 ? -1 : 1) / norm;
    return GSL_SUCCESS;
}

/* The corrected point at arclength h from u along tau. */
static int branch_step(problem *pb, const double *u, const double *tau, double h, double *unew,
                       int *iterations)
{
    arclength arc;
    double rnorm;
    memcpy(arc.tau, tau, sizeof arc.tau);
    for (int k = 0; k < 3; k++) arc.u_pred[k] = unew[k] = u[k] + h * tau[k];
    return driven_newton(pb, unew, &arc, iterations, &rnorm);
}

typedef struct fold_search {
    problem *pb;
    const double *u, *tau;
    double u_at[3]; /* the last corrected point */
} fold_search;

/* D at the corrected point at arclength h into *d (the root finder's function); GSL_EFAILED
 * where the point is not found. */
static int fold_function_at(double h, void *params, double *d)
{
    fold_search *fs = params;
    double R[3], J[3][3];
    int iterations;
    if (branch_step(fs->pb, fs->u, fs->tau, h, fs->u_at, &iterations) != GSL_SUCCESS ||
        driven_pivot_miss(fs->pb, fs->u_at, R, J) != GSL_SUCCESS) {
        *d = GSL_NAN;
        return GSL_EFAILED;
    }
    *d = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    return GSL_SUCCESS;
}

/* Locates the fold between u (arclength 0) and the corrected point at arclength h, where D
 * changes sign: ufold is the corrected point where D = 0. Brent's estimate after 100 iterations
 * is taken as it is. */
static int locate_fold(problem *pb, const double *u, const double *tau, double h, double *ufold)
{
    fold_search fs = {pb, u, tau, {0}};
    const whirl_root_opts o = {FOLD_TOL, 0, 100, 0, 0, 0};
    whirl_root r;
    double d;
    int status = whirl_root_brent(fold_function_at, &fs, 0, h, &o, &r);
    if (status == GSL_ENOMEM) return status;
    if ((status && status != GSL_EMAXITER) || fold_function_at(r.root, &fs, &d))
        return whirl_fail(GSL_EFAILED, "the fold near omega " WHIRL_Q_RATE "%g could not be "
                          "located", u[2]);
    memcpy(ufold, fs.u_at, sizeof fs.u_at);
    return GSL_SUCCESS;
}

/* Appends the shape u to the curve (fold flag). */
static int curve_append(problem *pb, whirl_driven_curve *curve, const double *u, int iterations,
                        int fold)
{
    int status = driven_describe(pb, u, iterations, &curve->point[curve->n]);
    if (status) return status;
    curve->fold[curve->n++] = fold;
    return GSL_SUCCESS;
}

int whirl_driven_branch(const whirl_chain *chain, const whirl_driven_params *params,
                        const whirl_driven_info *start, int direction, double omega_min,
                        double omega_max, double step, whirl_driven_curve *curve)
{
    return whirl_driven_branch_tick(chain, params, start, direction, omega_min, omega_max, step,
                                    curve, NULL, NULL);
}

int whirl_driven_branch_tick(const whirl_chain *chain, const whirl_driven_params *params,
                             const whirl_driven_info *start, int direction, double omega_min,
                             double omega_max, double step, whirl_driven_curve *curve,
                             whirl_driven_branch_tick_fn tick, void *data)
{
    if (direction != 1 && direction != -1)
        return whirl_fail(GSL_EINVAL, "direction must be +1 or -1, got %d", direction);
    if (!(isfinite(omega_min) && isfinite(omega_max) && omega_min > 0 && omega_min < omega_max))
        return whirl_fail(GSL_EINVAL, "need 0 < omega_min < omega_max, got %g, %g", omega_min,
                          omega_max);
    if (!(isfinite(step) && step > 0))
        return whirl_fail(GSL_EINVAL, "step must be positive and finite, got %g", step);
    if (!(start->omega >= omega_min && start->omega <= omega_max))
        return whirl_fail(GSL_EINVAL, "the start's omega " WHIRL_Q_RATE "%g is outside [%g, %g]",
                          start->omega, omega_min, omega_max);
    problem pb;
    int status = driven_problem_init(&pb, chain, params);
    if (status) return status;
    double u[3] = {start->tip[0], start->tip[1], start->omega}, tau[3], D, unew[3], taunew[3], Dnew;
    double h = step;
    int iterations;
    size_t ticked = 0; /* the points tick has seen */
    curve->n = curve->n_folds = 0;
    curve->complete = 0;
    status = branch_tangent(&pb, u, NULL, direction, tau, &D);
    if (status == GSL_SUCCESS) status = curve_append(&pb, curve, u, start->iterations, 0);
    while (status == GSL_SUCCESS && curve->n < curve->capacity) {
        if (tick != NULL && curve->n > ticked) {
            tick(data, curve);
            ticked = curve->n;
        }
        if (whirl_stop_requested()) {
            status = whirl_fail(WHIRL_EINTERRUPTED, "stopped by request at omega = " WHIRL_Q_RATE
                                "%g", u[2]);
            break;
        }
        if (branch_step(&pb, u, tau, h, unew, &iterations) != GSL_SUCCESS ||
            iterations > BRANCH_MAX_CORRECTOR ||
            branch_tangent(&pb, unew, tau, direction, taunew, &Dnew) != GSL_SUCCESS) {
            if ((h *= 0.5) < BRANCH_MIN_STEP_RATIO * step) break; /* incomplete */
            continue;
        }
        if (unew[2] < omega_min || unew[2] > omega_max) {
            curve->complete = 1;
            break;
        }
        if (D != 0 && Dnew != 0 && (D > 0) != (Dnew > 0)) {
            double ufold[3];
            status = locate_fold(&pb, u, tau, h, ufold);
            if (status) break;
            if (curve->n_folds < WHIRL_DRIVEN_FOLD_MAX)
                curve->fold_omega[curve->n_folds++] = ufold[2];
            status = curve_append(&pb, curve, ufold, 0, 1);
            if (status || curve->n == curve->capacity) break;
        }
        status = curve_append(&pb, curve, unew, iterations, 0);
        memcpy(u, unew, sizeof u);
        memcpy(tau, taunew, sizeof tau);
        D = Dnew;
        if (iterations <= 3) h = fmin(step, 1.5 * h);
    }
    if (tick != NULL && curve->n > ticked) tick(data, curve);
    driven_problem_free(&pb);
    return status;
}
