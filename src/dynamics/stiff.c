/* The fastest decay rate the dissipation adds to the motion (include/whirl/dynamics.h): the
 * bound on a fixed step that the scenes (whirl_scene_stiff), the default step
 * (whirl_default_step) and the Python Simulation take.
 *
 * Internal damping, R = D/2 sum_i |w_i - w_{i-1}|^2 (w_i: the angular velocity of link i): a
 * damping torque D over a link's moment m l^2, times about 4 for the alternating pattern (the
 * damping's difference operator) and 4 for the link angles' mass matrix: 16 D / min_i(m_i l_i^2),
 * 16 D N^3 / (M L^2) for equal links (measured: 15.6 D N^3 for the uniform chain of N = 25, from
 * the eigenvalues of the damped linearisation; data/scenes/spin_up_damped.ini). Measured on 100
 * equal links at dt = 1e-5: the Gauss stage iteration, a fixed point that converges for
 * h rate < 2 sqrt(3) = 3.46 (the spectral radius of Gauss-2's matrix is 1/(2 sqrt 3)), fails
 * between D = 0.0200 (h rate 3.20) and 0.0216 (3.46); rk4, stable for h rate < 2.785 on the
 * negative real axis, between D = 0.0174 (2.78) and 0.0200 (3.20).
 *
 * Air drag f_i = -l_i (c + c2 |v_i|) v_i on mass i (whirl_model): its Jacobian in v_i,
 * -l_i ((c + c2 |v|) I + c2 v v^T / |v|), has the rates l_i (c + c2 |v|) across v and
 * l_i (c + 2 c2 |v|) along it over the mass m_i; the drag and the mass matrix are both diagonal
 * by masses in Cartesian coordinates, so the rates of the constrained motion lie below their
 * largest ratio (a Rayleigh quotient), max_i l_i (c + 2 c2 v) / m_i: c L / M for a uniform chain,
 * whatever N. The speed v is that of the steady rotation's fastest point, |omega| (L + drive
 * radius); a chain slower than that has slower rates (a chain that drag has stopped, none from
 * c2). Measured on data/scenes/mode1.ini (100 links, omega = 2, dt = 2e-3): rk4 fails between
 * c = 1100 (h rate 2.2) and 1500 (3.0), the Gauss fixed point between c = 1500 (3.0) and 1800
 * (3.6), as the rate c predicts; with quadratic drag the Gauss step between c2 = 500 and 800
 * (estimated h rate 4.0 and 6.4: the estimate is an upper one). */
#include <math.h>

#include <gsl/gsl_math.h>

#include "whirl/dynamics.h"

static int usable(const whirl_model *m)
{
    return m != NULL && m->chain != NULL && m->chain->n > 0 && m->chain->length != NULL &&
           m->chain->mass != NULL;
}

static double internal_rate(const whirl_model *m)
{
    if (!(m->internal_damping > 0)) return 0;
    const whirl_chain *c = m->chain;
    double least = HUGE_VAL;
    for (size_t i = 0; i < c->n; i++)
        least = GSL_MIN(least, c->mass[i] * c->length[i] * c->length[i]);
    return 16 * m->internal_damping / least;
}

static double drag_rate(const whirl_model *m)
{
    if (!(m->air_drag > 0) && !(m->air_drag_quadratic > 0)) return 0;
    const whirl_chain *c = m->chain;
    double length = 0, most = 0;
    for (size_t i = 0; i < c->n; i++) {
        length += c->length[i];
        most = GSL_MAX(most, c->length[i] / c->mass[i]);
    }
    const double v = fabs(m->omega) * (length + m->drive_radius);
    return most * (m->air_drag + 2 * m->air_drag_quadratic * v);
}

double whirl_model_stiff_rate(const whirl_model *m)
{
    return usable(m) ? internal_rate(m) + drag_rate(m) : 0;
}

const char *whirl_model_stiff_cause(const whirl_model *m)
{
    const double damping = usable(m) ? internal_rate(m) : 0, drag = usable(m) ? drag_rate(m) : 0;
    const double all = damping + drag;
    /* a source named when it gives a tenth of the rate or more */
    if (damping >= 0.1 * all && drag >= 0.1 * all)
        return "the internal damping and the air drag make";
    return damping >= drag ? "the internal damping makes" : "the air drag makes";
}
