/* Start states of the dynamics (include/whirl/dynamics.h): a steady shape as a state, the one
 * perturbation rule, and the default fixed step.
 *
 * Shape to state: a shape is given by its link vectors d_i (3 per link) in the frame of the
 * shape, the pivot first, z up. The masses of the state are x_i = p(t) + R(a) sum_{j<=i} d_j,
 * p(t) the pivot of the model at time t and R(a) the turn about z by the frame's angle a (the
 * phase of the drive in the inertial frame in 3D; 0 in the co-rotating frame and in 2D). The
 * shape turns rigidly at the rate spin about the vertical through the pivot, which moves with
 * the drive: v_i = p'(t) + (spin - w_f) z x (x_i - p(t)), w_f the rate of the model's frame
 * (omega when co-rotating, 0 inertial). A steady shape of whirl_nlink_positions or
 * whirl_driven_sample at the model's omega is then an equilibrium: in the co-rotating frame at
 * rest, in the inertial frame turning with the pivot.
 *
 * Perturbation: each link vector d_j is turned by the angle a towards a unit vector t_j
 * perpendicular to it, d_j <- cos(a) d_j + sin(a) |d_j| t_j, t_j uniformly distributed on the
 * circle of unit vectors perpendicular to d_j (the projection of a 3D standard normal vector
 * onto the plane perpendicular to d_j, normalised; drawn again if its norm is below 1e-3),
 * from GSL's MT19937 seeded with seed. Lengths are kept exactly up to round-off.
 *
 * Default step: nu = 2 sqrt(max_j (T_j / l_j) / min m) is the Gershgorin bound of the highest
 * transverse frequency under the tensions T_j, and kappa = whirl_model_stiff_rate, 16 D /
 * min_i(m_i l_i^2) + max_i (l_i / m_i) (c + 2 c2 omega (eps + L)), that of the fastest decay of
 * the internal damping D and the air drag (src/dynamics/stiff.c).
 * - classical rk4: min(period / 200, 2 / (nu + omega), 2 / kappa): inside its stability interval
 *   on the imaginary axis (|h lambda| < 2.83) and on the negative real axis (2.79);
 * - the other methods: min(period / 200, 0.7 / (nu + omega + kappa)), so that the stage
 *   iterations of the implicit methods converge and the other explicit ones are stable. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "dynamics/dyn_internal.h"
#include "core/error.h"

int whirl_shape_links(size_t n, const double *nx, const double *ny, const double *nz,
                      double *links)
{
    if (n < 1 || nx == NULL || nz == NULL || links == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_shape_links: needs n >= 1, nx, nz and links");
    for (size_t i = 0; i < n; i++) {
        links[3 * i] = nx[i + 1] - nx[i];
        links[3 * i + 1] = ny ? ny[i + 1] - ny[i] : 0;
        links[3 * i + 2] = nz[i + 1] - nz[i];
        if (!whirl_dyn_all_finite(links + 3 * i, 3))
            return whirl_fail(GSL_EINVAL, "whirl_shape_links: node %zu is not finite", i + 1);
    }
    return GSL_SUCCESS;
}

int whirl_perturb_links(size_t n, double *links, double angle, unsigned long seed)
{
    if (n < 1 || links == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_perturb_links: needs n >= 1 and links");
    if (!(isfinite(angle) && angle >= 0))
        return whirl_fail(GSL_EINVAL, "the perturbation angle must be >= 0 and finite, got %g",
                          angle);
    for (size_t j = 0; j < n; j++) {
        const double *d = links + 3 * j;
        if (!(whirl_dyn_all_finite(d, 3) && (d[0] != 0 || d[1] != 0 || d[2] != 0)))
            return whirl_fail(GSL_EINVAL, "link %zu is zero or not finite", j + 1);
    }
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (rng == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the random generator");
    gsl_rng_set(rng, seed);
    for (size_t j = 0; j < n; j++) {
        double *d = links + 3 * j;
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double u[3] = {d[0] / len, d[1] / len, d[2] / len};
        double t[3], norm = 0;
        do { /* a random direction perpendicular to u */
            for (int k = 0; k < 3; k++) t[k] = gsl_ran_gaussian(rng, 1.0);
            const double along = t[0] * u[0] + t[1] * u[1] + t[2] * u[2];
            for (int k = 0; k < 3; k++) t[k] -= along * u[k];
            norm = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        } while (norm < 1e-3);
        for (int k = 0; k < 3; k++) d[k] = len * (cos(angle) * u[k] + sin(angle) * t[k] / norm);
    }
    gsl_rng_free(rng);
    return GSL_SUCCESS;
}

int whirl_dyn_state_from_shape(whirl_dyn *d, double t, const double *links, double spin,
                               double *y)
{
    if (d == NULL || links == NULL || y == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_dyn_state_from_shape: needs d, links and y");
    if (!isfinite(t) || !isfinite(spin))
        return whirl_fail(GSL_EINVAL, "whirl_dyn_state_from_shape: t and spin must be finite");
    const whirl_model *m = &d->model;
    const size_t n = d->n;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    dyn_drive dr;
    whirl_dyn_drive(d, t, &dr);
    const double a = rotating || d->dim == 2 ? 0 : dr.phase;
    const double w = spin - (rotating ? dr.omega : 0);
    if (d->dim == 2 && spin != 0)
        return whirl_fail(GSL_EINVAL, "a planar model cannot hold a shape spinning at %g", spin);
    double *x = malloc(6 * n * sizeof *x);
    if (x == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for a state of %zu links", n);
    double *v = x + 3 * n;
    double p[3], pv[3], pa[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    const double c = cos(a), s = sin(a);
    double r[3] = {0, 0, 0}; /* x_i - p */
    for (size_t i = 0; i < n; i++) {
        const double *dl = links + 3 * i;
        r[0] += c * dl[0] - s * dl[1];
        r[1] += s * dl[0] + c * dl[1];
        r[2] += dl[2];
        for (int k = 0; k < 3; k++) x[3 * i + k] = p[k] + r[k];
        v[3 * i] = pv[0] - w * r[1];
        v[3 * i + 1] = pv[1] + w * r[0];
        v[3 * i + 2] = pv[2];
    }
    const int status = whirl_dyn_set_state(d, t, x, v, y);
    free(x);
    return status;
}

int whirl_default_step(const whirl_model *m, const double *tension, const char *method,
                       double *h)
{
    if (m == NULL || m->chain == NULL || tension == NULL || method == NULL || h == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_default_step: needs a model, tensions, a method and "
                                      "h");
    if (!(isfinite(m->omega) && m->omega > 0))
        return whirl_fail(GSL_EINVAL, "the default step needs omega > 0, got %g", m->omega);
    const whirl_chain *c = m->chain;
    double stiff = 0, light = INFINITY;
    for (size_t j = 0; j < c->n; j++) {
        if (!(isfinite(tension[j]) && tension[j] >= 0))
            return whirl_fail(GSL_EINVAL, "tension %zu must be >= 0 and finite, got %g", j + 1,
                              tension[j]);
        stiff = fmax(stiff, tension[j] / c->length[j]);
        light = fmin(light, c->mass[j]);
    }
    const double nu = 2 * sqrt(stiff / light);
    const double kappa = whirl_model_stiff_rate(m);
    const double period_step = 2 * M_PI / m->omega / 200;
    if (strcmp(method, "rk4") == 0)
        *h = fmin(period_step, fmin(2 / (nu + m->omega), 2 / kappa));
    else
        *h = fmin(period_step, 0.7 / (nu + m->omega + kappa));
    if (!(isfinite(*h) && *h > 0))
        return whirl_fail(GSL_EINVAL, "no finite default step for this model");
    return GSL_SUCCESS;
}
