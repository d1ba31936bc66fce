/* The modes of the vertically shaken chain (chart_modes.h): with the pivot shaken along the
 * vertical, z(t), the straight chain (hanging or inverted) is an exact motion, and its
 * linearisation in the link angles theta is
 *   M theta'' + sigma (g + z''(t)) G theta = 0,   sigma = +1 hanging, -1 inverted,
 * the pivot's acceleration adding to gravity (M the mass matrix, g G gravity's stiffness; the
 * inverted chain's stiffness is -g G). M and G are symmetric and positive definite, so the
 * pencil G v = lambda M v has n real lambda_k > 0 and M-orthogonal v_k that make both diagonal;
 * theta = sum_k q_k v_k decouples the chain into n scalar Hill equations
 *   q_k'' + sigma lambda_k (g + z''(t)) q_k = 0
 * for every periodic z(t) and every lengths and masses (in 3D the two planes across the chain
 * are two copies). The monodromy of the chain is similar to the direct sum of the modes' 2 x 2
 * monodromies M_k, each with det M_k = 1, so its multipliers are the union of theirs and
 *   det(M -+ I) = prod_k (2 -+ tr M_k)^planes.
 * The unshaken hanging chain's frequencies are omega_k = sqrt(g lambda_k); with z = A cos(omega t)
 * and tau = omega t / 2 each mode is Mathieu's equation with a_k = 4 sigma g lambda_k / omega^2,
 * q_k = 2 sigma lambda_k A.
 *
 * M_k from Magnus's expansion of order 4 with two Gauss points (Iserles and Norsett, Phil.
 * Trans. R. Soc. A 357, 1999; Blanes, Casas and Ros, BIT 40, 2000): for x' = A(t) x,
 * x = (q, q'), A = [[0, 1], [-w, 0]], w = sigma lambda (g + z''),
 *   Omega = h/2 (A_1 + A_2) + sqrt(3)/12 h^2 [A_2, A_1],  x(t + h) = exp(Omega) x(t),
 * A_i at t + (1/2 -+ sqrt(3)/6) h; [A_2, A_1] = diag(w_2 - w_1, w_1 - w_2). Omega is traceless,
 * Omega^2 = d2 I with d2 = Omega_11^2 + Omega_12 Omega_21, so exp(Omega) = C I + S Omega with
 * C = cosh sqrt(d2), S = sinh sqrt(d2) / sqrt(d2) (cos and sin for d2 < 0): every step has
 * determinant 1, and the method is symmetric (its error even in h: the extrapolation from s and
 * 2 s steps, (f(h/2) - f(h)) / 15, removes the h^4 term). Exact for constant w, it follows the
 * mode's oscillation without the phase error of a polynomial method.
 *
 * Linear air drag (whirl_model's c: the force -c l_i v_i on mass i) does two things. On the
 * straight chain moving with the pivot (every mass at the velocity z' e_z) it is the force
 * -gamma m_i z' e_z, gamma = c l_i / m_i, along the chain: the vertical state stays a motion, and
 * its tensions are those of the gravity g + z'' + gamma z' (the pivot's frame: each mass held
 * against m_i (g + z'') and the drag). On the perturbation it adds the damping matrix
 * C_ij = c l_i l_j sum_{q >= max(i, j)} l_q, which is gamma M when every link has the same mass
 * per length (M with l_q in place of m_q): then the pencil's v_k make C diagonal too, and each
 * mode is
 *   q_k'' + gamma q_k' + sigma lambda_k (g + z''(t) + gamma z'(t)) q_k = 0.
 * With q = exp(-gamma t / 2) y,  q' = exp(-gamma t / 2) (y' - gamma y / 2),
 *   q'' = exp(-gamma t / 2) (y'' - gamma y' + gamma^2 y / 4),  so
 *   y'' + (sigma lambda_k (g + z''(t) + gamma z'(t)) - gamma^2 / 4) y = 0,
 * an undamped Hill equation (the coefficient still periodic, and even in A: A cos(omega t) is
 * -A cos(omega t) half a period later, z' and z'' both change sign) with its constant term
 * shifted by -gamma^2 / 4. For z = A cos(omega t), z'' + gamma z' = -A omega
 * sqrt(omega^2 + gamma^2) cos(omega t - phi): each mode is the damped Mathieu equation at the
 * amplitude A sqrt(1 + gamma^2 / omega^2) (a shift of time leaves the multipliers). With the
 * constant S = [[1, 0], [-gamma/2, 1]], (q, q') = exp(-gamma t / 2) S (y, y'), so the mode's
 * monodromy is exp(-gamma T / 2) S M_y S^-1, its trace exp(-gamma T / 2) tr M_y and its
 * determinant exp(-gamma T) (det M_y = 1). A multiplier mu of the mode solves
 * mu^2 - tr mu + exp(-gamma T) = 0; a complex pair has |mu|^2 = exp(-gamma T) < 1, so the mode
 * leaves the unit disc only through mu = +1 (tr = 1 + exp(-gamma T)) or mu = -1
 * (tr = -(1 + exp(-gamma T))); in terms of M_y, where tr M_y = +-2 cosh(gamma T / 2)
 * (chart.c's factors).
 *
 * The half period. A path z(t) even in t (A cos(omega t): every vertical term a cosine) makes the
 * conservative coefficient w(t) = sigma lambda_k (g + z''(t)) even, and with q(t) a solution so is
 * q(-t). Let u, v be the solutions from t = 0 with (u, u') = (1, 0) and (v, v') = (0, 1); u is
 * even, v odd, so the fundamental matrix Phi(t) = [[u, v], [u', v']] has Phi(-t) = R Phi(t) R,
 * R = diag(1, -1). Periodicity, Phi(t + T) = Phi(t) M, at t = -T/2 gives
 *   M = Phi(-T/2)^-1 Phi(T/2) = R X^-1 R X,   X = Phi(T/2),   X^-1 = [[v', -v], [-u', u]]
 * (det X = u v' - u' v = 1), so M = [[v', v], [u', u]] X and
 *   tr M = 2 (u v' + u' v),   2 - tr M = -4 u' v,   2 + tr M = 4 u v'
 * (all at T/2; with u v' - u' v = 1). Each factor is the product of two smooth functions of
 * half a period's solutions; a zero of u'(T/2) or u(T/2) is where the even solution is periodic
 * or antiperiodic (Mathieu's a_n), one of v(T/2) or v'(T/2) where the odd one is (b_n). The two
 * edges of one tongue are simple zeros of two different functions, however close they come
 * (Mathieu's a_n and b_n differ for q != 0), and half a period costs half a monodromy. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sort_vector.h>

#include "core/error.h"
#include "periodic/chart_modes.h"

/* Steps per radian of a mode's phase per period (at least): h sqrt|w| <= 1/16. With 200 and 400
 * steps the extrapolated trace of Mathieu's equation (lambda 1 to 19, omega 1 to 2.4, A = 0.1:
 * up to 12 radians per period) is within 3e-13 of 20000 steps; the modes' product equals the
 * full monodromy's det(M -+ I) to 1.5e-12 of its scale (tests/unit/periodic/test_chart_modes.c). */
#define CHART_STEPS_PER_RADIAN 16

int chart_modes(const whirl_chain *c, double *lambda)
{
    const size_t n = c->n;
    gsl_matrix *m = gsl_matrix_calloc(n, n), *g = gsl_matrix_calloc(n, n);
    gsl_vector *eval = gsl_vector_alloc(n);
    gsl_eigen_gensymm_workspace *ws = gsl_eigen_gensymm_alloc(n);
    double *below = malloc(n * sizeof *below);
    int status = m && g && eval && ws && below ? GSL_SUCCESS : GSL_ENOMEM;
    if (status == GSL_SUCCESS) {
        double sum = 0;
        for (size_t i = n; i-- > 0;) below[i] = sum += c->mass[i]; /* sum_{q >= i} m_q */
        for (size_t i = 0; i < n; i++) {
            for (size_t j = 0; j < n; j++)
                gsl_matrix_set(m, i, j, c->length[i] * c->length[j] * below[i > j ? i : j]);
            gsl_matrix_set(g, i, i, c->length[i] * below[i]);
        }
        status = gsl_eigen_gensymm(g, m, eval, ws);
    }
    if (status == GSL_SUCCESS) gsl_sort_vector(eval);
    for (size_t i = 0; status == GSL_SUCCESS && i < n; i++) {
        lambda[i] = gsl_vector_get(eval, i);
        if (!(lambda[i] > 0) || !isfinite(lambda[i])) status = GSL_ESING;
    }
    free(below);
    if (ws) gsl_eigen_gensymm_free(ws);
    if (eval) gsl_vector_free(eval);
    if (g) gsl_matrix_free(g);
    if (m) gsl_matrix_free(m);
    return status ? whirl_fail(status, "the modes of the straight chain: %s", gsl_strerror(status))
                  : GSL_SUCCESS;
}

double chart_mode_accel(const whirl_pivot_path *path)
{
    double a = 0;
    for (int j = 1; j <= path->harmonics; j++)
        a += (j * path->omega) * (j * path->omega) * (fabs(path->c[2][j - 1]) +
                                                      fabs(path->s[2][j - 1]));
    return a;
}

/* z'(t) of path's vertical terms. */
static double vel_z(const whirl_pivot_path *path, double t)
{
    double v = 0;
    for (int j = 1; j <= path->harmonics; j++) {
        const double wj = j * path->omega;
        v += wj * (path->s[2][j - 1] * cos(wj * t) - path->c[2][j - 1] * sin(wj * t));
    }
    return v;
}

/* The largest |z'| of path's vertical terms: sum_j j omega (|c_j| + |s_j|). */
static double vel_max(const whirl_pivot_path *path)
{
    double v = 0;
    for (int j = 1; j <= path->harmonics; j++)
        v += j * path->omega * (fabs(path->c[2][j - 1]) + fabs(path->s[2][j - 1]));
    return v;
}

/* z''(t) of path's vertical terms. */
static double accel_z(const whirl_pivot_path *path, double t)
{
    double a = 0;
    for (int j = 1; j <= path->harmonics; j++) {
        const double wj = j * path->omega;
        a -= wj * wj * (path->c[2][j - 1] * cos(wj * t) + path->s[2][j - 1] * sin(wj * t));
    }
    return a;
}

/* C and S of exp(Omega) = C I + S Omega for Omega^2 = d2 I (file header); the series below
 * |d2| = 1e-3 (its first term left out under 1e-21). */
static void exp_coeffs(double d2, double *c, double *s)
{
    if (fabs(d2) < 1e-3) {
        *c = 1 + d2 / 2 * (1 + d2 / 12 * (1 + d2 / 30 * (1 + d2 / 56)));
        *s = 1 + d2 / 6 * (1 + d2 / 20 * (1 + d2 / 42 * (1 + d2 / 72)));
    } else if (d2 > 0) {
        const double d = sqrt(d2);
        *c = cosh(d), *s = sinh(d) / d;
    } else {
        const double d = sqrt(-d2);
        *c = cos(d), *s = sin(d) / d;
    }
}

/* The coefficient w(t) = coef (g + z'' + gamma z') - gamma^2 / 4 (file header); without drag
 * the conservative chain's coef (g + z''), as it always was. */
static double coefficient(const whirl_pivot_path *path, double g, double coef, double gamma,
                          double t)
{
    if (!(gamma > 0)) return coef * (g + accel_z(path, t));
    return coef * (g + accel_z(path, t) + gamma * vel_z(path, t)) - gamma * gamma / 4;
}

/* x (2 x 2, row major) <- the solutions from t = 0 of the identity over span in steps Magnus
 * steps (file header). */
static void magnus(const whirl_pivot_path *path, double g, double coef, double gamma, double span,
                   int steps, double m[4])
{
    const double h = span / steps;
    const double n1 = (0.5 - sqrt(3) / 6) * h, n2 = (0.5 + sqrt(3) / 6) * h;
    const double comm = sqrt(3) / 12 * h * h;
    double x[4] = {1, 0, 0, 1};
    for (int i = 0; i < steps; i++) {
        const double t = i * h;
        const double w1 = coefficient(path, g, coef, gamma, t + n1);
        const double w2 = coefficient(path, g, coef, gamma, t + n2);
        const double o11 = comm * (w2 - w1), o12 = h, o21 = -h * (w1 + w2) / 2;
        double c, s;
        exp_coeffs(o11 * o11 + o12 * o21, &c, &s);
        const double e11 = c + s * o11, e12 = s * o12, e21 = s * o21, e22 = c - s * o11;
        const double y0 = e11 * x[0] + e12 * x[2], y1 = e11 * x[1] + e12 * x[3];
        const double y2 = e21 * x[0] + e22 * x[2], y3 = e21 * x[1] + e22 * x[3];
        x[0] = y0, x[1] = y1, x[2] = y2, x[3] = y3;
    }
    for (int i = 0; i < 4; i++) m[i] = x[i];
}

void chart_mode_monodromy(const whirl_pivot_path *path, double g, double coef, double gamma,
                          int steps, double m[4])
{
    magnus(path, g, coef, gamma, whirl_pivot_period(path), steps, m);
}

void chart_mode_half(const whirl_pivot_path *path, double g, double coef, int steps, double x[4])
{
    magnus(path, g, coef, 0, whirl_pivot_period(path) / 2, steps, x);
}

/* The phase of the mode per period at its strongest:
 * T sqrt(|coef| (|g| + max |z''| + gamma max |z'|) + gamma^2 / 4) (the bound of |w|). */
static double phase(const whirl_pivot_path *path, double g, double coef, double gamma)
{
    if (!(gamma > 0))
        return whirl_pivot_period(path) * sqrt(fabs(coef) * (fabs(g) + chart_mode_accel(path)));
    return whirl_pivot_period(path) *
           sqrt(fabs(coef) * (fabs(g) + chart_mode_accel(path) + gamma * vel_max(path)) +
                gamma * gamma / 4);
}

int chart_mode_steps(const whirl_pivot_path *slow, const whirl_pivot_path *fast, double g,
                     double coef, double gamma, int requested, int *steps)
{
    const double need = ceil(CHART_STEPS_PER_RADIAN * fmax(phase(slow, g, coef, gamma),
                                                           phase(fast, g, coef, gamma)));
    if (!(need <= 1e8))
        return whirl_fail(GSL_EINVAL, "the chart's slowest rate or largest amplitude is beyond "
                          "the integrator: %.3g steps per period needed", need);
    *steps = need > requested ? (int)need : requested;
    return GSL_SUCCESS;
}

/* The relative spread of m_i / l_i a drag may see on "one mass per length": far above the
 * round-off of the quotients, far below a chain of unequal links. */
#define DRAG_DENSITY_TOL 1e-12

int chart_mode_drag(const whirl_chain *c, double air_drag, double *gamma)
{
    if (!(isfinite(air_drag) && air_drag >= 0))
        return whirl_fail(GSL_EINVAL, "the chart's air drag must be >= 0 and finite, got "
                          WHIRL_Q_DRAG "%g", air_drag);
    *gamma = 0;
    if (air_drag == 0) return GSL_SUCCESS;
    const double per = c->length[0] / c->mass[0]; /* l_i / m_i of link 1 */
    for (size_t i = 1; i < c->n; i++)
        if (fabs(c->length[i] / c->mass[i] - per) > DRAG_DENSITY_TOL * per)
            return whirl_fail(GSL_EINVAL, "the chart's air drag needs a chain of one mass per "
                              "length (m_i / l_i equal; link %zu differs from link 1): only a "
                              "drag proportional to the mass matrix keeps the modes apart", i + 1);
    *gamma = air_drag * per;
    return GSL_SUCCESS;
}
