/* A custom forcing through the general integrator interface (whirl/integrator.h).
 *
 * The forced, damped oscillator
 *   x'' + 2 zeta w x' + w^2 x = F cos(W t),   x(0) = x'(0) = 0,
 * written as the second-order system y = (x, v), dx/dt = v, dv/dt = F cos(W t) - 2 zeta w v -
 * w^2 x, and integrated by two of the library's methods: rk8 with adaptive steps and gauss3
 * with fixed steps (a second-order system: its acceleration scale is F + w^2 x_max, here w^2).
 * After the transient, which decays like exp(-zeta w t), x follows the steady response
 *   x_s(t) = A cos(W t - phi),  A = F / sqrt((w^2 - W^2)^2 + (2 zeta w W)^2),
 *   tan(phi) = 2 zeta w W / (w^2 - W^2).
 * Check (exit 1 on failure): at t = 200 (transient down by exp(-zeta w 200) = 4e-11) both
 * methods give x and v within 1e-8 A (resp. 1e-8 A W) of the steady response. Prints both
 * end states, the steady response and the integrators' step counts. */
#include <math.h>
#include <stdio.h>

#include <gsl/gsl_math.h>
#include <whirl/integrator.h>

typedef struct forcing {
    double w, zeta, F, W;
} forcing;

static int rhs(double t, const double y[], double dydt[], void *params)
{
    const forcing *p = params;
    dydt[0] = y[1];
    dydt[1] = p->F * cos(p->W * t) - 2 * p->zeta * p->w * y[1] - p->w * p->w * y[0];
    return GSL_SUCCESS;
}

int main(void)
{
    gsl_set_error_handler_off();
    forcing p = {.w = 1.7, .zeta = 0.07, .F = 0.385, .W = 1.3};
    const whirl_system sys = {.rhs = rhs, .size = 2, .params = &p, .second_order = 1,
                              .acceleration_scale = p.w * p.w};
    const double t1 = 200;
    const double A = p.F / hypot(p.w * p.w - p.W * p.W, 2 * p.zeta * p.w * p.W);
    const double phi = atan2(2 * p.zeta * p.w * p.W, p.w * p.w - p.W * p.W);
    const double xs = A * cos(p.W * t1 - phi), vs = -A * p.W * sin(p.W * t1 - phi);
    const struct {
        const whirl_integrator_type *type;
        double h, tol;
    } runs[] = {{whirl_integrator_rk8, 0.1, 1e-12}, {whirl_integrator_gauss3, 0.02, 0}};
    int ok = 1;
    for (int k = 0; k < 2; k++) {
        whirl_integrator *it = whirl_integrator_alloc_system(runs[k].type, &sys);
        double y[2] = {0, 0}, t = 0;
        if (it == NULL || whirl_integrator_advance(it, &t, y, t1, runs[k].h, runs[k].tol)) {
            fprintf(stderr, "custom_forcing: %s\n", whirl_last_error());
            whirl_integrator_free(it);
            return 1;
        }
        const double ex = fabs(y[0] - xs) / A, ev = fabs(y[1] - vs) / (A * p.W);
        const whirl_integrator_stats st = whirl_integrator_get_stats(it);
        printf("%-6s x %.9f v %.9f: errors below 1e-8 A: %s; %lu steps, %lu rejected\n",
               whirl_integrator_type_name(runs[k].type), y[0], y[1],
               ex < 1e-8 && ev < 1e-8 ? "yes" : "no", st.steps, st.rejected);
        ok = ok && ex < 1e-8 && ev < 1e-8;
        whirl_integrator_free(it);
    }
    printf("steady response: x %.9f v %.9f (A %.9f)\n%s\n", xs, vs, A, ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
