/* Internal: the modes of the vertically shaken chain (chart_modes.c), the stability chart's edge
 * functions (chart.c). */
#ifndef WHIRL_CHART_MODES_H
#define WHIRL_CHART_MODES_H

#include "whirl/periodic.h"

/* lambda <- the eigenvalues of the pencil G v = lambda M v of the straight chain's link angles,
 * ascending (n of them, all > 0): M_ij = l_i l_j sum_{q >= max(i, j)} m_q (the mass matrix),
 * G = diag(l_i sum_{q >= i} m_q) (gravity's stiffness over g). GSL_ENOMEM or the eigensolver's
 * status with a message. */
int chart_modes(const whirl_chain *c, double *lambda);

/* The coefficient's largest |z''| of path's vertical terms: sum_j (j omega)^2 (|c_j| + |s_j|). */
double chart_mode_accel(const whirl_pivot_path *path);

/* m (2 x 2, row major) <- the monodromy of y'' + (coef (g + z''(t) + gamma z'(t)) - gamma^2 / 4)
 * y = 0 over one period of path (z: its vertical terms) from steps Magnus steps of order 4; its
 * determinant is 1 to round-off (each step the exponential of a traceless matrix). gamma the
 * modes' decay rate under linear air drag (chart_modes.c: the damped mode is
 * exp(-gamma t / 2) y), 0 for the conservative chain. */
void chart_mode_monodromy(const whirl_pivot_path *path, double g, double coef, double gamma,
                          int steps, double m[4]);

/* x (2 x 2, row major) <- [[u, v], [u', v']] at T/2: the solutions of the conservative
 * y'' + coef (g + z''(t)) y = 0 from t = 0 with (u, u') = (1, 0), (v, v') = (0, 1), over half a
 * period of path in steps Magnus steps (of the same order). For a path even in t the monodromy's
 * 2 - tr = -4 u' v and 2 + tr = 4 u v' (chart_modes.c). */
void chart_mode_half(const whirl_pivot_path *path, double g, double coef, int steps, double x[4]);

/* *steps <- requested raised so that a step of the mode coef's monodromy (with gamma, as
 * above) turns its phase by at most 1 / CHART_STEPS_PER_RADIAN at the strongest shaking of both
 * paths (the same vertical terms at two rates); GSL_EINVAL with a message if over 1e8. */
int chart_mode_steps(const whirl_pivot_path *slow, const whirl_pivot_path *fast, double g,
                     double coef, double gamma, int requested, int *steps);

/* *gamma <- the decay rate c l_i / m_i of the linear air drag c (whirl_model's: -c l_i v_i on
 * mass i) on a chain of one mass per length (the drag's matrix gamma M: every mode damped alike,
 * chart_modes.c); GSL_EINVAL with a message for a drag not finite or negative, or a chain whose
 * m_i / l_i differ (its drag would couple the modes). */
int chart_mode_drag(const whirl_chain *c, double air_drag, double *gamma);

#endif
