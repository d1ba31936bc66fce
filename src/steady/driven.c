/* Steady shapes of the chain with a driven pivot and air drag (include/whirl/driven.h).
 *
 * Co-rotating frame at omega about z, pivot at P = (eps, 0, 0). A point at rest there moves in
 * the inertial frame with v = omega z x r = omega (-y, x, 0). With rho = sqrt(x^2 + y^2) the
 * load on a piece of mass weight wm and length weight wl at r is
 *     f(r) = wm (omega^2 x, omega^2 y, -g) - wl k(rho) omega (-y, x, 0),  k = c + c2 omega rho
 * (centrifugal force, gravity, linear and quadratic air drag). The force of the support on the
 * part of the chain below a point, F = T t (T the tension, t the unit tangent pointing up the
 * chain), balances all the loads below it: F = -sum (or -integral) of f over that part.
 *
 * Continuum (uniform, mu = 1, g = 1, L = 1), arclength sigma from the free end:
 *     dr/dsigma = F/|F|,   dF/dsigma = b(r) = -f(r)|_{wm = wl = 1},
 *     r(0) = (X, Y, 0),    F(0) = -f_tip = m_tip (-omega^2 X, -omega^2 Y, g)  (no drag on it).
 * Without a tip mass F(0) = 0 and the tangent is 0/0 at the free end: the integration starts at
 * sigma0 = SERIES_START from the series (b0 = b(r(0)), T0 = |b0|, t0 = b0/T0, c1 = Db t0,
 * P = I - t0 t0^T):
 *     F = sigma b0 + sigma^2 c1 / 2 + O(sigma^3),  r = r(0) + sigma t0 + sigma^2 P c1 / (4 T0) + O(sigma^3).
 * The variational equations (derivatives with respect to p = X, Y, omega) ride along:
 *     d(dr/dp)/dsigma = (I - t t^T) (dF/dp) / |F|,   d(dF/dp)/dsigma = Db dr/dp + db/domega [p = omega].
 * ODE: GSL's rk8pd (Prince & Dormand 1981), scaled error control.
 *
 * N-link chain (mass i at the lower end of link i, mass n the tip), the exact discrete recursion
 * from the tip up (the manual's theory, "N-link statics", here in 3D, drag weight l_i as in
 * dynamics.h):
 *     r_n = (X, Y, 0),  F_i = F_{i+1} + b_i(r_i)  (F_{n+1} = 0),  r_{i-1} = r_i + l_i F_i/|F_i|,
 * b_i = -f(r_i)|_{wm = m_i, wl = l_i}; T_i = |F_i| is the tension of link i, and every mass is in
 * force balance by construction: T_i t_i - T_{i+1} t_{i+1} + f_i = 0.
 *
 * Both: the top r_0 (resp. r(1)) must land on P: R(X, Y) = (x_0 - eps, y_0) = 0, solved by
 * Newton's method with backtracking; without drag the shapes are planar (see planar()) and the
 * second equation is replaced by Y = 0. Branches against omega: pseudo-arclength continuation
 * (Keller 1977, "Numerical solution of bifurcation and nonlinear eigenvalue problems") in
 * u = (X, Y, omega): predictor u + h tau with tau the unit null vector of dR/du (the cross
 * product of its two rows), corrector Newton on (R(u), tau.(u - u_pred)). tau_omega is
 * proportional to D = det dR/d(X, Y), so a fold is a sign change of D along the branch; it is
 * located by Brent's method (GSL) on D over the arclength of the step that crossed it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_odeiv2.h>

#include "whirl/driven.h"
#include "whirl/steady.h"
#include "core/error.h"
#include "core/roots.h"

#include "steady/driven_internal.h"

/* ---- loads ---- */

/* b = -f (header comment) with mass weight wm and length weight wl at r, its Jacobian db[i][j] =
 * d b_i / d r_j and its derivative with respect to omega. */
static void load(const problem *pb, double wm, double wl, const double *r, double *b,
                 double db[3][3], double *dbw)
{
    const double w = pb->omega, c = pb->p.air_drag, c2 = pb->p.air_drag_quadratic;
    const double x = r[0], y = r[1];
    const double rho = hypot(x, y);
    const double k = wl * w * (c + c2 * w * rho);          /* wl omega (c + c2 omega rho) */
    const double dk_drho = wl * c2 * w * w;
    const double dk_dx = rho > 0 ? dk_drho * x / rho : 0, dk_dy = rho > 0 ? dk_drho * y / rho : 0;
    const double dk_dw = wl * (c + 2 * c2 * w * rho);
    const double w2 = wm * w * w;
    b[0] = -w2 * x - k * y;
    b[1] = -w2 * y + k * x;
    b[2] = wm * pb->gravity;
    db[0][0] = -w2 - y * dk_dx;
    db[0][1] = -k - y * dk_dy;
    db[1][0] = k + x * dk_dx;
    db[1][1] = -w2 + x * dk_dy;
    db[0][2] = db[1][2] = db[2][0] = db[2][1] = db[2][2] = 0;
    dbw[0] = -2 * wm * w * x - y * dk_dw;
    dbw[1] = -2 * wm * w * y + x * dk_dw;
    dbw[2] = 0;
}

/* The derivative of the unit vector t = F/T: dt = (dF - t (t.dF)) / T. */
static void tangent_derivative(const double *t, double T, const double *dF, double *dt)
{
    const double td = t[0] * dF[0] + t[1] * dF[1] + t[2] * dF[2];
    for (int j = 0; j < 3; j++) dt[j] = (dF[j] - t[j] * td) / T;
}

/* d(b)/dp for parameter k given dr/dp: Db dr + [k = omega] dbw. */
static void load_derivative(double db[3][3], const double *dbw, const double *dr, int k,
                            double *out)
{
    for (int i = 0; i < 3; i++)
        out[i] = db[i][0] * dr[0] + db[i][1] * dr[1] + db[i][2] * dr[2] + (k == 2 ? dbw[i] : 0);
}

/* ---- continuum ---- */

/* y = (r, F, dr/dX, dF/dX, dr/dY, dF/dY, dr/domega, dF/domega). */
static int continuum_rhs(double sigma, const double y[], double dydt[], void *params)
{
    (void)sigma;
    const problem *pb = params;
    const double *F = y + 3;
    const double T = sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    if (!(T > 0 && isfinite(T))) return GSL_EBADFUNC;
    double t[3] = {F[0] / T, F[1] / T, F[2] / T}, db[3][3], dbw[3];
    load(pb, 1, 1, y, dydt + 3, db, dbw);
    memcpy(dydt, t, sizeof t);
    for (int k = 0; k < NPAR; k++) {
        const double *s = y + STATE * (1 + k);
        double *ds = dydt + STATE * (1 + k);
        tangent_derivative(t, T, s + 3, ds);
        load_derivative(db, dbw, s, k, ds + 3);
    }
    return GSL_SUCCESS;
}

/* The state at the start sigma (the free end, or the series point sigma <= SERIES_START without
 * a tip mass) for u = (X, Y, omega). */
static void continuum_start(const problem *pb, const double *u, double sigma, double *y)
{
    const double r0[3] = {u[0], u[1], 0};
    double b[3], db[3][3], dbw[3];
    memset(y, 0, ODE_DIM * sizeof *y);
    memcpy(y, r0, sizeof r0);
    for (int k = 0; k < 2; k++) y[STATE * (1 + k) + k] = 1; /* dr/dX = e_x, dr/dY = e_y */
    if (pb->p.tip_mass > 0) {
        /* F(0) = b of the tip mass (no drag on it) */
        load(pb, pb->p.tip_mass, 0, r0, y + 3, db, dbw);
        for (int k = 0; k < NPAR; k++)
            load_derivative(db, dbw, y + STATE * (1 + k), k, y + STATE * (1 + k) + 3);
        return;
    }
    if (sigma == 0) return; /* r(0), F(0) = 0 */
    load(pb, 1, 1, r0, b, db, dbw);
    const double T0 = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    const double t0[3] = {b[0] / T0, b[1] / T0, b[2] / T0};
    double c1[3], pc1[3];
    load_derivative(db, dbw, t0, 0, c1);
    tangent_derivative(t0, 1, c1, pc1);
    for (int j = 0; j < 3; j++) {
        y[j] = r0[j] + sigma * t0[j] + sigma * sigma * pc1[j] / (4 * T0);
        y[3 + j] = sigma * b[j] + 0.5 * sigma * sigma * c1[j];
    }
    /* sensitivities to first order in sigma: dF = sigma db0, dr = dr0 + sigma dt0 */
    for (int k = 0; k < NPAR; k++) {
        double dr0[3] = {k == 0, k == 1, 0}, dbk[3], dt[3];
        load_derivative(db, dbw, dr0, k, dbk);
        tangent_derivative(t0, T0, dbk, dt);
        for (int j = 0; j < 3; j++) {
            y[STATE * (1 + k) + j] = dr0[j] + sigma * dt[j];
            y[STATE * (1 + k) + 3 + j] = sigma * dbk[j];
        }
    }
}

/* Integrates from the free end to sigma = 1 for u (y ends there). With nsample >= 2 it also
 * stores the position and the tension at sigma_j = j/(nsample - 1), j = 0..nsample-1, in
 * pos[3 i] and tension[i] with i = nsample - 1 - j (the pivot first). */
static int continuum_integrate(problem *pb, const double *u, size_t nsample, double *pos,
                               double *tension, double *y)
{
    pb->omega = u[2];
    const double sigma0 = pb->p.tip_mass > 0 ? 0 : SERIES_START;
    double sigma = sigma0, h = 1e-3 * (sigma0 > 0 ? sigma0 : 1e-3), here[ODE_DIM];
    gsl_odeiv2_system sys = {continuum_rhs, NULL, ODE_DIM, pb};
    continuum_start(pb, u, sigma0, y);
    gsl_odeiv2_step_reset(pb->step);
    gsl_odeiv2_evolve_reset(pb->evolve);
    long steps = 0;
    for (size_t j = 0; j < nsample || sigma < 1; j++) {
        const double target = j < nsample ? (double)j / (double)(nsample - 1) : 1.0;
        while (sigma < target) {
            if (++steps > ODE_STEP_MAX)
                return whirl_fail(GSL_EMAXITER, "the shape's integration needs more than %d steps "
                                  "(omega=" WHIRL_Q_RATE "%g): lower the rate", ODE_STEP_MAX,
                                  pb->omega);
            if (steps % ODE_POLL == 0 && whirl_stop_requested())
                return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request");
            int status = gsl_odeiv2_evolve_apply(pb->evolve, pb->control, pb->step, &sys, &sigma,
                                                 target, &h, y);
            if (status != GSL_SUCCESS)
                return whirl_fail(GSL_EFAILED, "the shape's integration failed at s = %g from "
                                  "the free end (tension vanishes)", sigma);
        }
        if (j >= nsample) continue;
        const double *st = y;
        if (target <= sigma0) { /* inside the series' reach */
            continuum_start(pb, u, target, here);
            st = here;
        }
        const size_t i = nsample - 1 - j;
        memcpy(pos + 3 * i, st, 3 * sizeof *st);
        tension[i] = sqrt(st[3] * st[3] + st[4] * st[4] + st[5] * st[5]);
    }
    return GSL_SUCCESS;
}

/* ---- N-link chain ---- */

/* The recursion up from the tip for u: r and F at the top (F_1), their sensitivities
 * (dr[j][k] = d r_j / d u_k) and, if pos != NULL, the positions of masses n..0 (pos[3i]: mass i)
 * and the tensions of the links (tension[i], link i; tension[0] = tension[1]). */
static int nlink_shoot(problem *pb, const double *u, double *r, double *F, double dr[3][3],
                       double *pos, double *tension)
{
    const whirl_chain *c = pb->chain;
    double dF[3][3] = {{0}}, b[3], db[3][3], dbw[3];
    pb->omega = u[2];
    r[0] = u[0], r[1] = u[1], r[2] = 0;
    F[0] = F[1] = F[2] = 0;
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) dr[j][k] = (j == k && k < 2);
    for (size_t i = c->n; i >= 1; i--) {
        if (pos) memcpy(pos + 3 * i, r, 3 * sizeof *r);
        load(pb, c->mass[i - 1], c->length[i - 1], r, b, db, dbw);
        for (int k = 0; k < NPAR; k++) {
            double drk[3] = {dr[0][k], dr[1][k], dr[2][k]}, dbk[3];
            load_derivative(db, dbw, drk, k, dbk);
            for (int j = 0; j < 3; j++) dF[j][k] += dbk[j];
        }
        for (int j = 0; j < 3; j++) F[j] += b[j];
        const double T = sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
        if (!(T > 0 && isfinite(T)))
            return whirl_fail(GSL_EFAILED, "the tension of link %zu is not positive", i);
        if (tension) tension[i] = T;
        const double t[3] = {F[0] / T, F[1] / T, F[2] / T}, l = c->length[i - 1];
        for (int k = 0; k < NPAR; k++) {
            double dFk[3] = {dF[0][k], dF[1][k], dF[2][k]}, dt[3];
            tangent_derivative(t, T, dFk, dt);
            for (int j = 0; j < 3; j++) dr[j][k] += l * dt[j];
        }
        for (int j = 0; j < 3; j++) r[j] += l * t[j];
    }
    if (pos) memcpy(pos, r, 3 * sizeof *r);
    if (tension) tension[0] = tension[1];
    return GSL_SUCCESS;
}

/* ---- both models ---- */

/* The top of the chain for u: position r, support force F, dr/du. */
static int shoot(problem *pb, const double *u, double *r, double *F, double dr[3][3])
{
    if (pb->chain) return nlink_shoot(pb, u, r, F, dr, NULL, NULL);
    double y[ODE_DIM];
    int status = continuum_integrate(pb, u, 0, NULL, NULL, y);
    if (status) return status;
    memcpy(r, y, 3 * sizeof *r);
    memcpy(F, y + 3, 3 * sizeof *F);
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < NPAR; k++) dr[j][k] = y[STATE * (1 + k) + j];
    return GSL_SUCCESS;
}

/* Without drag every shape lies in the plane y = 0: the angular momentum about the axis
 * L = (r x F)_z obeys dL/dsigma = (t x F)_z - omega^2 (r x r)_z = 0 (no torque), so r_h x F_h
 * is zero all along the chain as at the free end, and r_h stays on one line through the axis;
 * with eps > 0 that line passes through the pivot, with eps = 0 it is chosen (rotation symmetry).
 * Y = 0 then replaces the second equation (whose Jacobian vanishes at eps = 0). */
static int planar(const problem *pb)
{
    return pb->p.air_drag == 0 && pb->p.air_drag_quadratic == 0;
}

/* The pivot miss R (2) and dR/du (J rows 0, 1) at u. */
int driven_pivot_miss(problem *pb, const double *u, double *R, double J[3][3])
{
    double r[3], F[3], dr[3][3];
    int status = shoot(pb, u, r, F, dr);
    if (status) return status;
    R[0] = r[0] - pb->p.drive_radius;
    R[1] = r[1];
    for (int k = 0; k < NPAR; k++) J[0][k] = dr[0][k], J[1][k] = dr[1][k];
    if (planar(pb)) {
        R[1] = u[1];
        J[1][0] = J[1][2] = 0, J[1][1] = 1;
    }
    if (!(isfinite(R[0]) && isfinite(R[1])))
        return whirl_fail(GSL_ERANGE, "the shape is not finite at tip (%g, %g), omega " WHIRL_Q_RATE
                          "%g", u[0], u[1], u[2]);
    return GSL_SUCCESS;
}

/* The system of Newton's method: R (nd = 2 or 3 components) and its Jacobian in u[0..nd-1]. */
static int system_eval(problem *pb, const double *u, const arclength *arc, double *R,
                       double J[3][3])
{
    int status = driven_pivot_miss(pb, u, R, J);
    if (status || arc == NULL) return status;
    R[2] = 0;
    for (int k = 0; k < 3; k++) R[2] += arc->tau[k] * (u[k] - arc->u_pred[k]), J[2][k] = arc->tau[k];
    return GSL_SUCCESS;
}

static double norm_inf(const double *v, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++) m = fmax(m, fabs(v[i]));
    return m;
}

/* Newton's method with backtracking on |R|. u[2] (omega) is an unknown only with arc. */
int driven_newton(problem *pb, double *u, const arclength *arc, int *iterations, double *rnorm)
{
    const int nd = arc ? 3 : 2;
    double R[3], J[3][3], Rtry[3], Jtry[3][3], utry[3];
    int status = system_eval(pb, u, arc, R, J);
    if (status) return status;
    double norm = norm_inf(R, nd);
    for (int it = 1; it <= NEWTON_MAX; it++) {
        double lu[9], delta[3], rhs[3];
        size_t perm_data[3];
        gsl_permutation perm = {(size_t)nd, perm_data};
        int signum;
        for (int i = 0; i < nd; i++) {
            rhs[i] = -R[i];
            for (int k = 0; k < nd; k++) lu[i * nd + k] = J[i][k];
        }
        gsl_matrix_view m = gsl_matrix_view_array(lu, (size_t)nd, (size_t)nd);
        gsl_vector_view b = gsl_vector_view_array(rhs, (size_t)nd);
        gsl_vector_view x = gsl_vector_view_array(delta, (size_t)nd);
        gsl_linalg_LU_decomp(&m.matrix, &perm, &signum);
        if (gsl_linalg_LU_det(&m.matrix, signum) == 0 ||
            gsl_linalg_LU_solve(&m.matrix, &perm, &b.vector, &x.vector) != GSL_SUCCESS)
            return whirl_fail(GSL_EFAILED, "singular Jacobian at tip (%g, %g), omega " WHIRL_Q_RATE
                              "%g", u[0], u[1], u[2]);
        double lambda = 1, trynorm = HUGE_VAL;
        for (int bt = 0; bt <= NEWTON_BACKTRACK; bt++, lambda *= 0.5) {
            memcpy(utry, u, sizeof utry);
            for (int i = 0; i < nd; i++) utry[i] += lambda * delta[i];
            if (system_eval(pb, utry, arc, Rtry, Jtry) != GSL_SUCCESS) continue;
            trynorm = norm_inf(Rtry, nd);
            if (trynorm <= norm || norm < NEWTON_RESIDUAL_OK) break;
        }
        if (!isfinite(trynorm))
            return whirl_fail(GSL_EFAILED, "Newton step failed at tip (%g, %g), omega " WHIRL_Q_RATE
                              "%g", u[0], u[1], u[2]);
        memcpy(u, utry, sizeof utry);
        memcpy(R, Rtry, sizeof R);
        memcpy(J, Jtry, sizeof J);
        norm = trynorm;
        double scale = 1 + norm_inf(u, nd);
        if (lambda * norm_inf(delta, nd) <= NEWTON_STEP_TOL * scale && norm < NEWTON_RESIDUAL_OK) {
            *iterations = it;
            *rnorm = norm;
            return GSL_SUCCESS;
        }
    }
    *iterations = NEWTON_MAX;
    *rnorm = norm;
    return whirl_fail(GSL_EMAXITER, "Newton did not converge in %d iterations (pivot miss %g) at "
                      "tip (%g, %g), omega " WHIRL_Q_RATE "%g", NEWTON_MAX, norm, u[0], u[1], u[2]);
}

/* ---- set-up ---- */

static int check_params(const whirl_chain *chain, const whirl_driven_params *p)
{
    if (!(isfinite(p->omega) && p->omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be positive and finite, got %g", p->omega);
    if (whirl_check_omega_max(p->omega) != GSL_SUCCESS) return GSL_EINVAL;
    if (!(isfinite(p->drive_radius) && p->drive_radius >= 0))
        return whirl_fail(GSL_EINVAL, "eps must be >= 0 and finite, got " WHIRL_Q_LENGTH "%g",
                          p->drive_radius);
    if (!(isfinite(p->air_drag) && p->air_drag >= 0))
        return whirl_fail(GSL_EINVAL, "drag must be >= 0 and finite, got " WHIRL_Q_DRAG "%g",
                          p->air_drag);
    if (!(isfinite(p->air_drag_quadratic) && p->air_drag_quadratic >= 0))
        return whirl_fail(GSL_EINVAL, "quadratic drag must be >= 0 and finite, got " WHIRL_Q_DRAG2
                          "%g", p->air_drag_quadratic);
    if (p->air_drag > DRAG_MAX || p->air_drag_quadratic > DRAG_MAX)
        return whirl_fail(GSL_EINVAL, "drag coefficients above %g are refused (got " WHIRL_Q_DRAG
                          "%.17g, " WHIRL_Q_DRAG2 "%.17g): the bound is in the chain's units "
                          "(M sqrt(g/L) / L and M / L^2); the continuation from the drag-free "
                          "shape takes ever longer and is lost far below (near 1.5e3 at omega "
                          "3, eps 0.01)", DRAG_MAX, p->air_drag, p->air_drag_quadratic);
    if (whirl_check_tip_mass(p->tip_mass) != GSL_SUCCESS) return GSL_EINVAL;
    if (chain && p->tip_mass != 0)
        return whirl_fail(GSL_EINVAL, "tip mass must be 0 with an N-link chain (add it to the "
                          "chain's last mass)");
    if (p->drive_radius == 0 && (p->air_drag > 0 || p->air_drag_quadratic > 0))
        return whirl_fail(GSL_EDOM, "with eps = 0 the pivot cannot balance the torque of the air "
                          "drag: only the hanging chain is steady");
    if (p->drive_radius >= 1)
        return whirl_fail(GSL_EINVAL, "eps must be smaller than the chain length " WHIRL_Q_LENGTH
                          "1, got " WHIRL_Q_LENGTH "%.17g", p->drive_radius);
    return GSL_SUCCESS;
}

void driven_problem_free(problem *pb)
{
    if (pb->evolve) gsl_odeiv2_evolve_free(pb->evolve);
    if (pb->control) gsl_odeiv2_control_free(pb->control);
    if (pb->step) gsl_odeiv2_step_free(pb->step);
    free(pb->pos);
    free(pb->tension);
}

int driven_problem_init(problem *pb, const whirl_chain *chain, const whirl_driven_params *p)
{
    memset(pb, 0, sizeof *pb);
    int status = check_params(chain, p);
    if (status) return status;
    pb->chain = chain;
    pb->p = *p;
    pb->omega = p->omega;
    pb->gravity = chain ? chain->gravity : 1.0;
    pb->npos = chain ? chain->n + 1 : WHIRL_DRIVEN_NODE_SAMPLES;
    pb->pos = malloc(3 * pb->npos * sizeof *pb->pos);
    pb->tension = malloc(pb->npos * sizeof *pb->tension);
    if (pb->pos == NULL || pb->tension == NULL) goto fail;
    if (chain == NULL) {
        for (int i = 0; i < ODE_DIM; i++) pb->scale_abs[i] = i < STATE ? 1 : ODE_SENS_SCALE;
        pb->step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, ODE_DIM);
        pb->control = gsl_odeiv2_control_scaled_new(ODE_TOL, ODE_TOL, 1, 0, pb->scale_abs,
                                                    ODE_DIM);
        pb->evolve = gsl_odeiv2_evolve_alloc(ODE_DIM);
        if (pb->step == NULL || pb->control == NULL || pb->evolve == NULL) goto fail;
    }
    return GSL_SUCCESS;
fail:
    driven_problem_free(pb);
    return whirl_fail(GSL_ENOMEM, "out of memory for the driven chain");
}

/* ---- shapes ---- */

/* Samples the shape of u from the pivot to the free end: npts points (continuum: equally spaced
 * in arclength; N-link: the pivot and the masses), positions with z from the pivot. */
static int sample_shape(problem *pb, const double *u, size_t npts, double *s, double *pos,
                        double *tension)
{
    if (pb->chain) {
        double r[3], F[3], dr[3][3];
        int status = nlink_shoot(pb, u, r, F, dr, pos, tension);
        if (status) return status;
        double arc = 0;
        for (size_t i = 0; i < npts; i++) {
            if (i > 0) arc += pb->chain->length[i - 1];
            if (s) s[i] = arc;
        }
    } else {
        double y[ODE_DIM];
        int status = continuum_integrate(pb, u, npts, pos, tension, y);
        if (status) return status;
        for (size_t i = 0; s && i < npts; i++) s[i] = (double)i / (double)(npts - 1);
    }
    const double ztop = pos[2];
    for (size_t i = 0; i < npts; i++) pos[3 * i + 2] -= ztop;
    return GSL_SUCCESS;
}

void whirl_driven_params_from_model(whirl_driven_params *p, const whirl_model *m)
{
    *p = (whirl_driven_params){.omega = m->omega,
                               .drive_radius = m->drive_radius,
                               .air_drag = m->air_drag,
                               .air_drag_quadratic = m->air_drag_quadratic};
}

int whirl_driven_nodes(double eps, size_t npts, const double *pos, const double *weight)
{
    double mxx = 0, mxy = 0, myy = 0;
    for (size_t i = 1; i < npts; i++) { /* weighted moments of d = (x - eps, y) */
        const double dx = pos[3 * i] - eps, dy = pos[3 * i + 1];
        const double w = weight ? weight[i - 1] : 1;
        mxx += w * dx * dx, mxy += w * dx * dy, myy += w * dy * dy;
    }
    const double angle = 0.5 * atan2(2 * mxy, mxx - myy); /* principal direction e */
    double e[2] = {cos(angle), sin(angle)};
    const double *tip = pos + 3 * (npts - 1);
    if ((tip[0] - eps) * e[0] + tip[1] * e[1] < 0) e[0] = -e[0], e[1] = -e[1];
    int nodes = 1, last_sign = 0;
    for (size_t i = 1; i < npts; i++) { /* sign changes of d.e below the pivot */
        const double proj = (pos[3 * i] - eps) * e[0] + pos[3 * i + 1] * e[1];
        const int sign = (proj > 0) - (proj < 0);
        if (sign != 0 && last_sign != 0 && sign != last_sign) nodes++;
        if (sign != 0) last_sign = sign;
    }
    return nodes;
}

/* The summary of the solution u. */
int driven_describe(problem *pb, const double *u, int iterations, whirl_driven_info *info)
{
    double R[3], J[3][3], r[3], F[3], dr[3][3];
    int status = driven_pivot_miss(pb, u, R, J);
    if (status == GSL_SUCCESS) status = shoot(pb, u, r, F, dr);
    if (status == GSL_SUCCESS) status = sample_shape(pb, u, pb->npos, NULL, pb->pos, pb->tension);
    if (status) return status;
    memset(info, 0, sizeof *info);
    info->omega = u[2];
    info->tip[0] = u[0];
    info->tip[1] = u[1];
    info->tip[2] = pb->pos[3 * (pb->npos - 1) + 2];
    info->tip_r = hypot(u[0], u[1]);
    memcpy(info->top_force, F, sizeof F);
    info->top_tension = sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
    info->fold_function = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    info->nodes = whirl_driven_nodes(pb->p.drive_radius, pb->npos, pb->pos,
                                     pb->chain ? pb->chain->length : NULL);
    info->residual = hypot(r[0] - pb->p.drive_radius, r[1]);
    info->iterations = iterations;
    return GSL_SUCCESS;
}

int whirl_driven_solve(const whirl_chain *chain, const whirl_driven_params *params,
                       const double guess[2], whirl_driven_info *info)
{
    problem pb;
    int status = driven_problem_init(&pb, chain, params);
    if (status) return status;
    double u[3] = {guess[0], guess[1], params->omega}, rnorm;
    int iterations = 0;
    if (planar(&pb)) { /* rotate the guess into the plane y = 0 (eps = 0) or project on it */
        u[0] = params->drive_radius == 0 ? copysign(hypot(guess[0], guess[1]), guess[0]) : guess[0];
        u[1] = 0;
    }
    status = driven_newton(&pb, u, NULL, &iterations, &rnorm);
    if (status == GSL_SUCCESS) status = driven_describe(&pb, u, iterations, info);
    driven_problem_free(&pb);
    return status;
}

/* Natural continuation of the solution u from pb's (eps, c, c2) to the target values. */
static int homotopy(problem *pb, double *u, double eps, double c, double c2)
{
    const double from[3] = {pb->p.drive_radius, pb->p.air_drag, pb->p.air_drag_quadratic};
    const double to[3] = {eps, c, c2};
    double lambda = 0, dl = 1, u_prev[3], dl_prev = 0, rnorm;
    int iterations;
    memcpy(u_prev, u, sizeof u_prev);
    while (lambda < 1) {
        const double next = fmin(1, lambda + dl);
        double utry[3];
        for (int k = 0; k < 3; k++) /* secant predictor */
            utry[k] = u[k] + (dl_prev > 0 ? (u[k] - u_prev[k]) * (next - lambda) / dl_prev : 0);
        pb->p.drive_radius = from[0] + next * (to[0] - from[0]);
        pb->p.air_drag = from[1] + next * (to[1] - from[1]);
        pb->p.air_drag_quadratic = from[2] + next * (to[2] - from[2]);
        double upred[3];
        memcpy(upred, utry, sizeof upred);
        if (driven_newton(pb, utry, NULL, &iterations, &rnorm) == GSL_SUCCESS &&
            iterations <= BRANCH_MAX_CORRECTOR &&
            fmax(fabs(utry[0] - upred[0]), fabs(utry[1] - upred[1])) <= HOMOTOPY_MAX_JUMP) {
            memcpy(u_prev, u, sizeof u_prev);
            memcpy(u, utry, sizeof utry);
            dl_prev = next - lambda;
            lambda = next;
            dl = fmin(1, 2 * dl);
        } else if ((dl *= 0.5) < HOMOTOPY_MIN_STEP) {
            return whirl_fail(GSL_EDOM, "the shape could not be followed from the free one to "
                              "eps = " WHIRL_Q_LENGTH "%.17g, drag = " WHIRL_Q_DRAG "%.17g, "
                              WHIRL_Q_DRAG2 "%.17g (lost at eps = " WHIRL_Q_LENGTH "%g, drag = "
                              WHIRL_Q_DRAG "%g, " WHIRL_Q_DRAG2 "%g)", eps, c, c2,
                              pb->p.drive_radius, pb->p.air_drag, pb->p.air_drag_quadratic);
        }
    }
    return GSL_SUCCESS;
}

int whirl_driven_mode(const whirl_chain *chain, const whirl_driven_params *params, int mode,
                      int side, whirl_driven_info *info)
{
    if (mode < 0 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "mode must be in 0..%d, got %d", WHIRL_MODE_MAX, mode);
    if (side != 1 && side != -1)
        return whirl_fail(GSL_EINVAL, "side must be +1 or -1, got %d", side);
    problem pb;
    int status = driven_problem_init(&pb, chain, params);
    if (status) return status;
    /* mode 0: the hanging chain (tip on the axis), a free shape at every rate; its pivot-miss
       Jacobian is singular only at the births omega_k, where the message below names the rate */
    whirl_shape_info free_shape = {.tip_r = 0};
    if (mode > 0)
        status = chain ? whirl_nlink_solve(chain, params->omega, mode, &free_shape)
                       : whirl_continuum_solve(params->omega, mode, params->tip_mass, 0,
                                               &free_shape);
    double u[3] = {side * free_shape.tip_r, 0, params->omega}, rnorm;
    int iterations = 0;
    if (status == GSL_SUCCESS) {
        /* the free shape in this module's own formulation, then drive it, then add the drag */
        pb.p.drive_radius = pb.p.air_drag = pb.p.air_drag_quadratic = 0;
        status = driven_newton(&pb, u, NULL, &iterations, &rnorm);
        if (status == GSL_SUCCESS && params->drive_radius > 0) status = homotopy(&pb, u, params->drive_radius, 0, 0);
        if (status == GSL_SUCCESS)
            status = homotopy(&pb, u, params->drive_radius, params->air_drag, params->air_drag_quadratic);
        if (status == GSL_SUCCESS) status = driven_newton(&pb, u, NULL, &iterations, &rnorm);
        if (status == GSL_SUCCESS) status = driven_describe(&pb, u, iterations, info);
    }
    driven_problem_free(&pb);
    return status;
}

int whirl_driven_sample(const whirl_chain *chain, const whirl_driven_params *params,
                        const double tip_xy[2], size_t npts, double *s, double *x, double *y,
                        double *z, double *tension)
{
    if (chain ? npts != chain->n + 1 : npts < 2)
        return whirl_fail(GSL_EINVAL, chain ? "an N-link chain of %zu links has %zu + 1 sample "
                          "points, got %zu" : "need at least 2 sample points", chain ? chain->n : npts,
                          chain ? chain->n : npts, npts);
    problem pb;
    int status = driven_problem_init(&pb, chain, params);
    if (status) return status;
    double *pos = malloc(3 * npts * sizeof *pos);
    if (pos == NULL) status = whirl_fail(GSL_ENOMEM, "out of memory for %zu samples", npts);
    const double u[3] = {tip_xy[0], tip_xy[1], params->omega};
    if (status == GSL_SUCCESS) status = sample_shape(&pb, u, npts, s, pos, tension);
    for (size_t i = 0; i < npts && status == GSL_SUCCESS; i++)
        x[i] = pos[3 * i], y[i] = pos[3 * i + 1], z[i] = pos[3 * i + 2];
    free(pos);
    driven_problem_free(&pb);
    return status;
}
