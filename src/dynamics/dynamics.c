/* The dynamics module's common part: the workspace, the pivot drive, the applied forces shared by
 * both formulations, frame conversions and the diagnostics.
 *
 * Geometry: link i (1-based) has the vector d_i = x_i - x_{i-1}, |d_i| = l_i, x_0 = p(t) the pivot:
 *   inertial frame, 3D: p = eps (cos wt, sin wt, 0); 2D: p = (eps cos wt, 0, 0);
 *   co-rotating frame:  p = (eps, 0, 0) (the same circle seen from the frame turning with it).
 * A drive that depends on time (whirl_ramp: eps(t), w(t) as C1 smooth steps) replaces wt by the
 * phase phi(t) = int_0^t w: inertial p = eps (cos phi, sin phi, 0), p' = eps' (c, s) + eps w (-s, c),
 * p'' = (eps'' - eps w^2) (c, s) + (2 eps' w + eps w') (-s, c); co-rotating (the frame turns by
 * phi) p = (eps, 0, 0), p' = (eps', 0, 0), p'' = (eps'', 0, 0), plus the Euler field w' (y, -x, 0)
 * added by each formulation. The integral of s(u) = u^2 (3 - 2 u) is u^3 - u^4 / 2.
 * Applied forces on mass i (all in the model's frame; v_i^in = v_i + [rotating] w z x x_i is the
 * inertial velocity expressed in that frame's basis):
 *   air drag        F_i = -c l_i v_i^in - c2 l_i |v_i^in| v_i^in;
 *   internal damping F = -dR/dv with R = D/2 sum_i |w_i - w_{i-1}|^2,
 *                    w_i = (d_i' - [inertial] w z x d_i) / l_i, w_0 = 0: with J_i = D (w_i -
 *                    w_{i-1}) (J_{N+1} = 0) and G_i = (J_i - J_{i+1}) / l_i (G_{N+1} = 0), the
 *                    force on mass k is -(G_k - G_{k+1}), since d_k' = v_k - v_{k-1};
 *   seed forcing (2D) the generalized force f_d = sigma_d - lambda_d thetadot_d on theta_d is the
 *                    force pair +-(f_d / l_d) e_d on masses d and d-1, e_d = dd_d/dtheta_d / l_d =
 *                    (-d_z, 0, d_x) / l_d (virtual work f_d dtheta_d),
 *                    thetadot_d = e_d . d_d' / l_d.
 * Gravity (0, 0, -g) and, in the co-rotating frame, the centrifugal w^2 (x, y, 0) and Coriolis
 * -2 w z x v accelerations are added by each formulation (uniform fields: the Cartesian one uses
 * their differences between neighbours exactly).
 * Diagnostics: E = sum m_i (|v_i^in|^2 / 2 + g z_i), L_z = sum m_i (x_i v^in_iy - y_i v^in_ix),
 * Jacobi = E - w L_z (conserved without dissipation in both frames, also with the drive). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynamics/dyn_internal.h"
#include "core/error.h"

int whirl_dyn_all_finite(const double *v, size_t n)
{
    /* x * 0 is 0 for finite x and NaN for inf and NaN: four independent sums */
    double s[4] = {0, 0, 0, 0};
    size_t i = 0;
    for (; i + 4 <= n; i += 4)
        for (int k = 0; k < 4; k++) s[k] += v[i + (size_t)k] * 0.0;
    for (; i < n; i++) s[0] += v[i] * 0.0;
    return !isnan(s[0] + s[1] + s[2] + s[3]);
}

static int ramp_active(const whirl_ramp *r)
{
    return r->from != 0 || r->to != 0 || r->t_start != 0 || r->t_end != 0;
}

static int ramp_check(const whirl_ramp *r, const char *name, int nonnegative)
{
    if (!ramp_active(r)) return GSL_SUCCESS;
    if (!(isfinite(r->from) && isfinite(r->to) && isfinite(r->t_start) && isfinite(r->t_end)))
        return whirl_fail(GSL_EINVAL, "%s: every field must be finite", name);
    if (!(r->t_end > r->t_start))
        return whirl_fail(GSL_EINVAL, "%s: t_end (%g) must exceed t_start (%g)", name, r->t_end,
                          r->t_start);
    if (nonnegative && !(r->from >= 0 && r->to >= 0))
        return whirl_fail(GSL_EINVAL, "%s: from and to must be >= 0, got %g, %g", name, r->from,
                          r->to);
    return GSL_SUCCESS;
}

static int model_check(const whirl_model *m)
{
    if (m == NULL || m->chain == NULL) return whirl_fail(GSL_EINVAL, "no model or no chain");
    const whirl_chain *c = m->chain;
    if (c->n == 0) return whirl_fail(GSL_EINVAL, "the chain has no links");
    for (size_t i = 0; i < c->n; i++)
        if (!(isfinite(c->length[i]) && c->length[i] > 0 && isfinite(c->mass[i]) &&
              c->mass[i] > 0))
            return whirl_fail(GSL_EINVAL, "link %zu: length and mass must be positive", i + 1);
    if (!(isfinite(c->gravity) && c->gravity > 0))
        return whirl_fail(GSL_EINVAL, "gravity must be positive and finite, got %g", c->gravity);
    if (m->dim != 2 && m->dim != 3)
        return whirl_fail(GSL_EINVAL, "dim must be 2 or 3, got %d", m->dim);
    if (m->frame != WHIRL_FRAME_INERTIAL && m->frame != WHIRL_FRAME_ROTATING)
        return whirl_fail(GSL_EINVAL, "unknown frame %d", (int)m->frame);
    if (m->frame == WHIRL_FRAME_ROTATING && m->dim != 3)
        return whirl_fail(GSL_EINVAL, "the co-rotating frame needs dim = 3");
    if (!isfinite(m->omega)) return whirl_fail(GSL_EINVAL, "omega must be finite");
    const struct {
        const char *name;
        double value;
    } nonneg[] = {{"drive radius", m->drive_radius},
                  {"air drag", m->air_drag},
                  {"quadratic air drag", m->air_drag_quadratic},
                  {"internal damping", m->internal_damping}};
    for (size_t k = 0; k < sizeof nonneg / sizeof nonneg[0]; k++)
        if (!(isfinite(nonneg[k].value) && nonneg[k].value >= 0))
            return whirl_fail(GSL_EINVAL, "%s must be >= 0 and finite, got %g", nonneg[k].name,
                              nonneg[k].value);
    int status = ramp_check(&m->drive_radius_ramp, "drive_radius_ramp", 1);
    if (status == GSL_SUCCESS) status = ramp_check(&m->omega_ramp, "omega_ramp", 0);
    if (status) return status;
    if ((m->seed_sigma != NULL || m->seed_lambda != NULL) && m->dim != 2)
        return whirl_fail(GSL_EINVAL, "the seed's forcing sigma, lambda needs dim = 2");
    for (size_t i = 0; i < c->n; i++)
        if ((m->seed_sigma != NULL && !isfinite(m->seed_sigma[i])) ||
            (m->seed_lambda != NULL && !isfinite(m->seed_lambda[i])))
            return whirl_fail(GSL_EINVAL, "seed forcing of link %zu is not finite", i + 1);
    return GSL_SUCCESS;
}

whirl_dyn *whirl_dyn_alloc(const whirl_model *model, whirl_formulation f)
{
    if (model_check(model) != GSL_SUCCESS) return NULL;
    if (f != WHIRL_FORMULATION_CARTESIAN && f != WHIRL_FORMULATION_SEED) {
        whirl_fail(GSL_EINVAL, "unknown formulation %d", (int)f);
        return NULL;
    }
    whirl_dyn *d = calloc(1, sizeof *d);
    if (d == NULL) goto nomem;
    d->model = *model;
    d->ramped = ramp_active(&model->drive_radius_ramp) || ramp_active(&model->omega_ramp);
    d->formulation = f;
    d->ops = f == WHIRL_FORMULATION_SEED ? &whirl_dyn_seed_ops : &whirl_dyn_cartesian_ops;
    d->n = model->chain->n;
    d->dim = model->dim;
    d->threads = 1;
    size_t n = d->n;
    d->mass_below = malloc(n * sizeof *d->mass_below);
    d->inv_mass = malloc(n * sizeof *d->inv_mass);
    d->x = malloc(3 * n * sizeof *d->x);
    d->v = malloc(3 * n * sizeof *d->v);
    d->force = malloc(3 * n * sizeof *d->force);
    d->links = malloc(3 * n * sizeof *d->links);
    d->link_rates = malloc(3 * n * sizeof *d->link_rates);
    if (!d->mass_below || !d->inv_mass || !d->x || !d->v || !d->force || !d->links ||
        !d->link_rates)
        goto nomem;
    double below = 0;
    for (size_t i = n; i-- > 0;) {
        below += model->chain->mass[i];
        d->mass_below[i] = below;
        d->inv_mass[i] = 1.0 / model->chain->mass[i];
    }
    int status = d->ops->alloc(d);
    if (status != GSL_SUCCESS) goto nomem;
    return d;
nomem:
    whirl_dyn_free(d);
    whirl_fail(GSL_ENOMEM, "out of memory for the dynamics of %zu links", model->chain->n);
    return NULL;
}

void whirl_dyn_free(whirl_dyn *d)
{
    if (d == NULL) return;
    free(d->mass_below);
    free(d->inv_mass);
    free(d->x);
    free(d->v);
    free(d->force);
    free(d->links);
    free(d->link_rates);
    free(d->multiplier);
    free(d->coef);
    free(d->rescaled);
    free(d->matrix);
    free(d->gen_force);
    free(d->quad_acc);
    free(d);
}

const whirl_model *whirl_dyn_model(const whirl_dyn *d) { return &d->model; }
whirl_formulation whirl_dyn_formulation(const whirl_dyn *d) { return d->formulation; }
size_t whirl_dyn_size(const whirl_dyn *d) { return d->size; }

int whirl_dyn_set_threads(whirl_dyn *d, int threads)
{
    if (d == NULL || threads < 1 || threads > WHIRL_DYN_THREADS_MAX)
        return whirl_fail(GSL_EINVAL, "threads must be 1..%d, got %d", WHIRL_DYN_THREADS_MAX,
                          threads);
    d->threads = threads;
    return GSL_SUCCESS;
}

/* The integral of the ramp's smooth-step part from -infinity (where it is 0) to t. */
static double ramp_step_integral(const whirl_ramp *r, double t)
{
    const double span = r->t_end - r->t_start, u = (t - r->t_start) / span;
    if (u <= 0) return 0;
    if (u >= 1) return span / 2 + (t - r->t_end);
    return span * u * u * u * (1 - u / 2);
}

/* Value, first and second derivative and integral from 0 to t of an active ramp. */
static void ramp_eval(const whirl_ramp *r, double t, double *v, double *dv, double *ddv,
                      double *integral)
{
    const double span = r->t_end - r->t_start, jump = r->to - r->from;
    const double u = (t - r->t_start) / span;
    if (u <= 0 || u >= 1) {
        *v = u <= 0 ? r->from : r->to;
        *dv = *ddv = 0;
    } else {
        *v = r->from + jump * u * u * (3 - 2 * u);
        *dv = jump * 6 * u * (1 - u) / span;
        *ddv = jump * (6 - 12 * u) / (span * span);
    }
    *integral = r->from * t + jump * (ramp_step_integral(r, t) - ramp_step_integral(r, 0));
}

void whirl_dyn_drive(const whirl_dyn *d, double t, dyn_drive *out)
{
    const whirl_model *m = &d->model;
    double unused;
    *out = (dyn_drive){.eps = m->drive_radius, .omega = m->omega,
                       .phase = m->omega * t + d->phase_offset};
    if (!d->ramped) return;
    if (ramp_active(&m->drive_radius_ramp))
        ramp_eval(&m->drive_radius_ramp, t, &out->eps, &out->deps, &out->ddeps, &unused);
    if (ramp_active(&m->omega_ramp))
    {
        ramp_eval(&m->omega_ramp, t, &out->omega, &out->domega, &unused, &out->phase);
        out->phase += d->phase_offset;
    }
}

void whirl_dyn_drive_at(const whirl_dyn *d, double t, double *radius, double *omega,
                        double *phase)
{
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    if (radius) *radius = dr.eps;
    if (omega) *omega = dr.omega;
    if (phase) *phase = dr.phase;
}

int whirl_dyn_set_ramps(whirl_dyn *d, double t, const whirl_ramp *radius,
                        const whirl_ramp *omega)
{
    if (d == NULL) return whirl_fail(GSL_EINVAL, "whirl_dyn_set_ramps: no dynamics");
    if (!isfinite(t)) return whirl_fail(GSL_EINVAL, "whirl_dyn_set_ramps: t must be finite");
    int status = radius ? ramp_check(radius, "drive_radius_ramp", 1) : GSL_SUCCESS;
    if (status == GSL_SUCCESS && omega) status = ramp_check(omega, "omega_ramp", 0);
    if (status) return status;
    if (d->pivot_fn != NULL && radius != NULL && ramp_active(radius))
        return whirl_fail(GSL_EINVAL, "whirl_dyn_set_ramps: the pivot follows a path "
                                      "(whirl_dyn_set_pivot), not the drive's radius");
    dyn_drive before, after;
    whirl_dyn_drive(d, t, &before);
    if (radius) d->model.drive_radius_ramp = *radius;
    if (omega) d->model.omega_ramp = *omega;
    d->ramped = ramp_active(&d->model.drive_radius_ramp) || ramp_active(&d->model.omega_ramp);
    whirl_dyn_drive(d, t, &after);
    d->phase_offset += before.phase - after.phase;
    return GSL_SUCCESS;
}

int whirl_dyn_set_pivot(whirl_dyn *d, whirl_pivot_fn pivot, void *params)
{
    if (d == NULL) return whirl_fail(GSL_EINVAL, "whirl_dyn_set_pivot: no dynamics");
    if (pivot != NULL && (d->model.frame != WHIRL_FRAME_INERTIAL || d->model.drive_radius != 0 ||
                          d->ramped))
        return whirl_fail(GSL_EINVAL, "a pivot path needs the inertial frame, drive radius 0 and "
                                      "no ramp");
    d->pivot_fn = pivot;
    d->pivot_params = pivot != NULL ? params : NULL;
    return GSL_SUCCESS;
}

void whirl_dyn_pivot(const whirl_dyn *d, double t, double *p, double *pv, double *pa)
{
    if (d->pivot_fn != NULL) {
        d->pivot_fn(t, p, pv, pa, d->pivot_params);
        if (d->dim == 2) p[1] = pv[1] = pa[1] = 0;
        return;
    }
    for (int k = 0; k < 3; k++) p[k] = pv[k] = pa[k] = 0;
    if (!d->ramped) { /* the constant drive */
        const double eps = d->model.drive_radius, w = d->model.omega;
        if (d->model.frame == WHIRL_FRAME_ROTATING) {
            p[0] = eps;
            return;
        }
        const double c = cos(w * t), s = sin(w * t);
        p[0] = eps * c;
        pv[0] = -eps * w * s;
        if (d->dim == 3) {
            p[1] = eps * s;
            pv[1] = eps * w * c;
        }
        for (int k = 0; k < 3; k++) pa[k] = -w * w * p[k];
        return;
    }
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    if (d->model.frame == WHIRL_FRAME_ROTATING) {
        p[0] = dr.eps;
        pv[0] = dr.deps;
        pa[0] = dr.ddeps;
        return;
    }
    /* p = eps (c, s): p' = eps' (c, s) + eps w (-s, c),
       p'' = (eps'' - eps w^2) (c, s) + (2 eps' w + eps w') (-s, c) */
    const double c = cos(dr.phase), s = sin(dr.phase), w = dr.omega;
    const double radial = dr.ddeps - dr.eps * w * w;
    const double along = 2 * dr.deps * w + dr.eps * dr.domega;
    p[0] = dr.eps * c;
    pv[0] = dr.deps * c - dr.eps * w * s;
    pa[0] = radial * c - along * s;
    if (d->dim == 3) {
        p[1] = dr.eps * s;
        pv[1] = dr.deps * s + dr.eps * w * c;
        pa[1] = radial * s + along * c;
    }
}

/* Positions x and velocities v of the masses (3 per mass, model frame) by running sums of the
 * links from the pivot; the link vectors and rates too if links != NULL. */
static void masses_from_links(const whirl_dyn *d, double t, const double *y, double *x,
                              double *v, double *links, double *link_rates)
{
    double p[3], pv[3], pa[3], dv[3], dd[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    for (size_t i = 0; i < d->n; i++) {
        d->ops->link(d, y, i, dv, dd);
        for (int k = 0; k < 3; k++) {
            x[3 * i + k] = p[k] += dv[k];
            v[3 * i + k] = pv[k] += dd[k];
            if (links != NULL) {
                links[3 * i + k] = dv[k];
                link_rates[3 * i + k] = dd[k];
            }
        }
    }
}

/* Internal damping: force -= dR/dv, in three sweeps in place: force_i <- J_i, then G_i, then
 * -(G_i - G_{i+1}) (the notation of the file's header). */
static void add_internal_damping(const whirl_dyn *d, double w, const double *links,
                                 const double *link_rates, double *force)
{
    const whirl_model *m = &d->model;
    const double *len = m->chain->length;
    const double D = m->internal_damping;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    const size_t n = d->n;
    double w_prev[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        const double *dv = links + 3 * i, *dd = link_rates + 3 * i;
        double w_cur[3] = {dd[0], dd[1], dd[2]};
        if (!rotating) {
            w_cur[0] += w * dv[1];
            w_cur[1] -= w * dv[0];
        }
        for (int k = 0; k < 3; k++) {
            w_cur[k] /= len[i];
            force[3 * i + k] = D * (w_cur[k] - w_prev[k]);
            w_prev[k] = w_cur[k];
        }
    }
    for (int sweep = 0; sweep < 2; sweep++) {
        for (size_t i = 0; i < n; i++) {
            for (int k = 0; k < 3; k++) {
                const double next = i + 1 < n ? force[3 * (i + 1) + k] : 0.0;
                const double diff = force[3 * i + k] - next;
                force[3 * i + k] = sweep == 0 ? diff / len[i] : -diff;
            }
        }
    }
}

/* The applied forces on the masses (3 per mass, model frame): linear and quadratic air drag,
 * internal damping and, if with_seed_forcing, the seed's forcing as a force pair on link d (2D).
 * Gravity and the fictitious forces of the frame are not included. */
static void applied_forces(const whirl_dyn *d, double w, const double *x, const double *v,
                           const double *links, const double *link_rates, int with_seed_forcing,
                           double *force)
{
    const whirl_model *m = &d->model;
    const double *len = m->chain->length;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    const size_t n = d->n;
    if (m->internal_damping > 0)
        add_internal_damping(d, w, links, link_rates, force);
    else
        memset(force, 0, 3 * n * sizeof *force);
    if (m->air_drag > 0 || m->air_drag_quadratic > 0) {
        for (size_t i = 0; i < n; i++) {
            const double *xi = x + 3 * i, *vi = v + 3 * i;
            double vin[3] = {vi[0], vi[1], vi[2]};
            if (rotating) {
                vin[0] -= w * xi[1];
                vin[1] += w * xi[0];
            }
            const double speed = sqrt(vin[0] * vin[0] + vin[1] * vin[1] + vin[2] * vin[2]);
            const double coef = len[i] * (m->air_drag + m->air_drag_quadratic * speed);
            for (int k = 0; k < 3; k++) force[3 * i + k] -= coef * vin[k];
        }
    }
    if (with_seed_forcing && (m->seed_sigma != NULL || m->seed_lambda != NULL)) {
        for (size_t i = 0; i < n; i++) {
            const double *dv = links + 3 * i, *dd = link_rates + 3 * i;
            const double e[3] = {-dv[2] / len[i], 0, dv[0] / len[i]};
            const double rate = (e[0] * dd[0] + e[2] * dd[2]) / len[i];
            double f = 0;
            if (m->seed_sigma != NULL) f += m->seed_sigma[i];
            if (m->seed_lambda != NULL) f -= m->seed_lambda[i] * rate;
            for (int k = 0; k < 3; k++) {
                force[3 * i + k] += f / len[i] * e[k];
                if (i > 0) force[3 * (i - 1) + k] -= f / len[i] * e[k];
            }
        }
    }
    if (d->dim == 2)
        for (size_t i = 0; i < n; i++) force[3 * i + 1] = 0;
}

void whirl_dyn_prepare_forces(whirl_dyn *d, double t, const double *y, int with_seed_forcing)
{
    masses_from_links(d, t, y, d->x, d->v, d->links, d->link_rates);
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    applied_forces(d, dr.omega, d->x, d->v, d->links, d->link_rates, with_seed_forcing, d->force);
}

int whirl_dyn_rhs(double t, const double y[], double dydt[], void *dyn)
{
    whirl_dyn *d = dyn;
    return d->ops->rhs(d, t, y, dydt); /* each formulation checks that dydt is finite */
}

int whirl_dyn_set_state(whirl_dyn *d, double t, const double *x, const double *v, double *y)
{
    const double *len = d->model.chain->length;
    double p[3], pv[3], pa[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    if (!whirl_dyn_all_finite(x, 3 * d->n) || !whirl_dyn_all_finite(v, 3 * d->n))
        return whirl_fail(GSL_EINVAL, "positions and velocities must be finite");
    for (size_t i = 0; i < d->n; i++) {
        double *dv = d->links + 3 * i, *dd = d->link_rates + 3 * i;
        double norm2 = 0, rate2 = 0, along = 0;
        for (int k = 0; k < 3; k++) {
            dv[k] = x[3 * i + k] - (i > 0 ? x[3 * (i - 1) + k] : p[k]);
            dd[k] = v[3 * i + k] - (i > 0 ? v[3 * (i - 1) + k] : pv[k]);
            norm2 += dv[k] * dv[k];
            rate2 += dd[k] * dd[k];
            along += dv[k] * dd[k];
        }
        if (d->dim == 2 && (x[3 * i + 1] != 0 || v[3 * i + 1] != 0))
            return whirl_fail(GSL_EINVAL, "mass %zu: a planar state needs y = 0", i + 1);
        const double norm = sqrt(norm2);
        if (!(fabs(norm - len[i]) <= 1e-9 * len[i]))
            return whirl_fail(GSL_EINVAL,
                              "link %zu has length %.17g, not %.17g (relative tolerance 1e-9)",
                              i + 1, norm, len[i]);
        if (!(fabs(along) <= 1e-9 * norm * sqrt(rate2)))
            return whirl_fail(GSL_EINVAL,
                              "link %zu: the velocities stretch the link (relative rate %.3g)",
                              i + 1, along / (norm * sqrt(rate2)));
    }
    return d->ops->from_links(d, d->links, d->link_rates, y);
}

int whirl_dyn_get_state(const whirl_dyn *d, double t, const double *y, whirl_frame frame,
                        double *x, double *v)
{
    if (frame != WHIRL_FRAME_INERTIAL && frame != WHIRL_FRAME_ROTATING)
        return whirl_fail(GSL_EINVAL, "unknown frame %d", (int)frame);
    if (frame == WHIRL_FRAME_ROTATING && d->dim != 3)
        return whirl_fail(GSL_EINVAL, "a planar model has no co-rotating frame");
    masses_from_links(d, t, y, x, v, NULL, NULL);
    if (frame == d->model.frame) return GSL_SUCCESS;
    /* rotating -> inertial: x' = R x, v' = R (v + w z x x); inertial -> rotating: the inverse */
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    const double w = dr.omega, c = cos(dr.phase), s = sin(dr.phase);
    for (size_t i = 0; i < d->n; i++) {
        double *xi = x + 3 * i, *vi = v + 3 * i;
        if (frame == WHIRL_FRAME_INERTIAL) {
            const double vx = vi[0] - w * xi[1], vy = vi[1] + w * xi[0];
            const double xx = c * xi[0] - s * xi[1], xy = s * xi[0] + c * xi[1];
            vi[0] = c * vx - s * vy;
            vi[1] = s * vx + c * vy;
            xi[0] = xx;
            xi[1] = xy;
        } else {
            const double xx = c * xi[0] + s * xi[1], xy = -s * xi[0] + c * xi[1];
            const double vx = c * vi[0] + s * vi[1], vy = -s * vi[0] + c * vi[1];
            vi[0] = vx + w * xy;
            vi[1] = vy - w * xx;
            xi[0] = xx;
            xi[1] = xy;
        }
    }
    return GSL_SUCCESS;
}

static int system_project(double t, double y[], void *params)
{
    return whirl_dyn_project(params, t, y);
}

int whirl_dyn_system(whirl_dyn *d, whirl_system *sys)
{
    if (d == NULL || sys == NULL) return whirl_fail(GSL_EINVAL, "whirl_dyn_system: needs d, sys");
    *sys = (whirl_system){.rhs = whirl_dyn_rhs,
                          .project = system_project,
                          .size = d->size,
                          .params = d,
                          .second_order = 1,
                          .acceleration_scale = d->model.chain->gravity};
    return GSL_SUCCESS;
}

/* The integrators (src/integrate/) know general systems only: the dynamics hand themselves over
 * as one. */
whirl_integrator *whirl_integrator_alloc(const char *method, whirl_dyn *d)
{
    const whirl_integrator_type *type = whirl_integrator_type_find(method);
    if (type == NULL) return NULL;
    whirl_system sys;
    if (whirl_dyn_system(d, &sys) != GSL_SUCCESS) return NULL;
    return whirl_integrator_alloc_system(type, &sys);
}

int whirl_dyn_project(whirl_dyn *d, double t, double *y)
{
    return d->ops->project(d, y); /* the constraints do not depend on t */
}

int whirl_dyn_tensions(whirl_dyn *d, double t, const double *y, double *tension)
{
    return d->ops->tensions(d, t, y, tension);
}

int whirl_dyn_diagnose(const whirl_dyn *d, double t, const double *y, whirl_dyn_diagnostics *out)
{
    const whirl_model *m = &d->model;
    const double *len = m->chain->length, *mass = m->chain->mass, g = m->chain->gravity;
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    const double w = dr.omega;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    if (!whirl_dyn_all_finite(y, d->size))
        return whirl_fail(GSL_ERANGE, "the state is not finite at t = %.17g", t);
    double p[3], pv[3], pa[3], dv[3], dd[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    double kinetic = 0, potential = 0, lz = 0, worst = 0;
    for (size_t i = 0; i < d->n; i++) {
        d->ops->link(d, y, i, dv, dd);
        for (int k = 0; k < 3; k++) {
            p[k] += dv[k];
            pv[k] += dd[k];
        }
        double vin[3] = {pv[0], pv[1], pv[2]};
        if (rotating) {
            vin[0] -= w * p[1];
            vin[1] += w * p[0];
        }
        kinetic += 0.5 * mass[i] * (vin[0] * vin[0] + vin[1] * vin[1] + vin[2] * vin[2]);
        potential += mass[i] * g * p[2];
        lz += mass[i] * (p[0] * vin[1] - p[1] * vin[0]);
        const double err = fabs(sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]) - len[i]);
        worst = fmax(worst, err);
    }
    out->energy = kinetic + potential;
    out->lz = lz;
    out->jacobi = out->energy - w * lz;
    out->constraint = worst;
    return GSL_SUCCESS;
}
