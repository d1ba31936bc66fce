/* Gauss-Legendre implicit Runge-Kutta methods: gauss2 (2 stages, order 4, the seed's eq. 53-59)
 * and gauss3 (3 stages, order 6). Symmetric, A-stable, symplectic for canonical Hamiltonian
 * systems, and they conserve quadratic invariants (here d_i . d_i', Cartesian).
 *
 * Coefficients (Butcher 1964, "Implicit Runge-Kutta processes", Math. Comp. 18:50; Hairer,
 * Norsett, Wanner, "Solving ODEs I", tables II.7.3-7.4), given to 36 digits, rounded to long
 * double:
 *   gauss2: c = 1/2 -+ sqrt(3)/6, b = (1/2, 1/2),
 *           A = [1/4, 1/4 - sqrt(3)/6; 1/4 + sqrt(3)/6, 1/4];
 *   gauss3: c = 1/2 - sqrt(15)/10, 1/2, 1/2 + sqrt(15)/10, b = (5/18, 4/9, 5/18),
 *           A = [5/36, 2/9 - sqrt(15)/15, 5/36 - sqrt(15)/30;
 *                5/36 + sqrt(15)/24, 2/9, 5/36 - sqrt(15)/24;
 *                5/36 + sqrt(15)/30, 2/9 + sqrt(15)/15, 5/36].
 *
 * Second-order form: the state is y = (q, v) with q' = v exactly (whirl_system.second_order), so the stage
 * equations reduce to the stage accelerations K_i (half the unknowns):
 *   Q_i = q + c_i h v + h^2 sum_j (A^2)_ij K_j,  V_i = v + h sum_j a_ij K_j,
 *   K_i = a(t + c_i h, Q_i, V_i),
 *   q+ = q + h v + h^2 sum_j b_j (1 - c_j) K_j,  v+ = v + h sum_j b_j K_j
 * (sum_i b_i a_ij = b_j (1 - c_j) for collocation methods). Updates are added with Kahan's
 * compensated summation, the compensation carried from step to step (Hairer, McLachlan,
 * Razakarivony 2008, BIT 48:231); the projection's rounding matters more (see dyn_cartesian.c).
 * Without projection the energy error grows like t^2 (constraint drift).
 *
 * Stage solver: fixed-point iteration on K, started from the extrapolated collocation
 * polynomial of the previous step (equal steps) or from a(t, y). On the position-dependent
 * (stiff, transverse-wave) part the iteration contracts like (h omega rho(A))^2, omega the
 * fastest frequency, rho(A) = 0.2887 (gauss2), 0.2153 (gauss3): the second-order form squares the
 * first-order form's factor h omega rho(A). It stops when the increment max|K^(k) - K^(k-1)|
 * is zero or stops decreasing (Antonana, Makazaga, Murua 2017, Numer. Algor.), i.e. at round-off
 * (a stall counts as convergence below 1e-8 of the acceleration scale max|K| + a, a the
 * system's acceleration_scale: gravity g for the chain); GSL_EMAXITER
 * if the increments grow to 1e3 times their smallest value (the step is too large for the fastest
 * mode: h omega_max rho(A) >= 1) or after 400 sweeps.
 * Choice against Newton: a Newton step needs the Jacobian of the constrained accelerations,
 * which is dense (the tensions couple every link), O(N^2) to form and O(N^3) to factor; the
 * fixed-point sweep costs s right-hand sides, O(N). Measured (tests/bench/bench_dynamics.c): the steady
 * mode-2 shape, N = 100, omega = 3.5, h = 0.01, takes 4.5 sweeps per step (gauss2), 5.3 (gauss3);
 * on a perturbed whirling chain at h = 0.2/N, gauss2 by fixed point costs 23-20 right-hand sides
 * per step for N = 5..40 and 15x (N = 5) to 600x (N = 40) less time per unit of simulated time
 * than GSL's rk4imp, the same method with modified Newton and a dense LU (and step doubling).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "integrate/integrator_internal.h"

#define GAUSS_MAX_STAGES 3
#define GAUSS_MAX_ITER 400

typedef struct gauss_tableau {
    int s;
    long double c[GAUSS_MAX_STAGES], b[GAUSS_MAX_STAGES], a[GAUSS_MAX_STAGES][GAUSS_MAX_STAGES];
} gauss_tableau;

static const gauss_tableau gauss2_tableau = {
    2,
    {0.211324865405187117745425609749021272L, 0.788675134594812882254574390250978728L},
    {0.5L, 0.5L},
    {{0.25L, -0.038675134594812882254574390250978728L},
     {0.538675134594812882254574390250978728L, 0.25L}},
};

static const gauss_tableau gauss3_tableau = {
    3,
    {0.112701665379258311482073460021760039L, 0.5L, 0.887298334620741688517926539978239961L},
    {0.277777777777777777777777777777777778L, 0.444444444444444444444444444444444444L,
     0.277777777777777777777777777777777778L},
    {{0.138888888888888888888888888888888889L, -0.035976667524938903456395471096604418L,
      0.009789444015308326049580042229475569L},
     {0.300263194980864592438024947213155539L, 0.222222222222222222222222222222222222L,
      -0.022485417203086814660247169435377762L},
     {0.267988333762469451728197735548302209L, 0.480421111969383347900839915541048863L,
      0.138888888888888888888888888888888889L}},
};

typedef struct gauss_state {
    int s;
    double c[GAUSS_MAX_STAGES], a[GAUSS_MAX_STAGES][GAUSS_MAX_STAGES];
    double a2[GAUSS_MAX_STAGES][GAUSS_MAX_STAGES]; /* A^2 */
    double b[GAUSS_MAX_STAGES], bq[GAUSS_MAX_STAGES]; /* b_j, b_j (1 - c_j) */
    double extrap[GAUSS_MAX_STAGES][GAUSS_MAX_STAGES]; /* L_j(1 + c_i) */
    size_t m;                 /* half the state */
    double *block;            /* the one allocation holding the arrays below */
    double *k, *k_new;        /* s * m stage accelerations (swapped by the iteration) */
    double *stage, *f;        /* stage state, right-hand side */
    double *comp;             /* Kahan compensation of y */
    int has_prev;             /* k holds the previous step's converged stages */
    double prev_h;
} gauss_state;

static void gauss_free(void *state)
{
    gauss_state *g = state;
    if (g == NULL) return;
    free(g->block);
    free(g);
}

static int gauss_alloc(whirl_integrator *it)
{
    const gauss_tableau *tab = it->method->params;
    if (!it->sys.second_order || it->size % 2 != 0)
        return whirl_fail(GSL_EINVAL, "%s needs a second-order system (y = (q, v), dq/dt = v)",
                          it->method->name);
    if (!(isfinite(it->sys.acceleration_scale) && it->sys.acceleration_scale > 0))
        return whirl_fail(GSL_EINVAL, "%s needs the system's acceleration_scale > 0, got %g",
                          it->method->name, it->sys.acceleration_scale);
    gauss_state *g = calloc(1, sizeof *g);
    if (g == NULL) return GSL_ENOMEM;
    it->state = g;
    const int s = tab->s;
    g->s = s;
    g->m = it->size / 2;
    for (int i = 0; i < s; i++) {
        g->c[i] = (double)tab->c[i];
        g->b[i] = (double)tab->b[i];
        g->bq[i] = (double)(tab->b[i] * (1 - tab->c[i]));
        for (int j = 0; j < s; j++) {
            long double sq = 0;
            for (int k = 0; k < s; k++) sq += tab->a[i][k] * tab->a[k][j];
            g->a[i][j] = (double)tab->a[i][j];
            g->a2[i][j] = (double)sq;
            /* Lagrange basis polynomial j of the nodes c, at 1 + c_i */
            long double l = 1;
            for (int k = 0; k < s; k++)
                if (k != j) l *= (1 + tab->c[i] - tab->c[k]) / (tab->c[j] - tab->c[k]);
            g->extrap[i][j] = (double)l;
        }
    }
    const size_t m = g->m, n = it->size;
    g->block = malloc((2 * (size_t)s * m + 3 * n) * sizeof *g->block);
    if (g->block == NULL) return GSL_ENOMEM;
    g->k = g->block;
    g->k_new = g->k + (size_t)s * m;
    g->stage = g->k_new + (size_t)s * m;
    g->f = g->stage + n;
    g->comp = g->f + n;
    memset(g->comp, 0, n * sizeof *g->comp);
    return GSL_SUCCESS;
}

static void gauss_restart(whirl_integrator *it)
{
    gauss_state *g = it->state;
    g->has_prev = 0;
    memset(g->comp, 0, it->size * sizeof *g->comp);
}

/* One sweep: k_new_i = a(t + c_i h, Q_i(k), V_i(k)); returns the max increment in *delta. */
static int gauss_sweep(whirl_integrator *it, double t, double h, const double *y, double *delta,
                       double *kmax)
{
    gauss_state *g = it->state;
    const size_t m = g->m;
    const int s = g->s;
    const double *q = y, *v = y + m;
    double worst = 0, big = 0;
    for (int i = 0; i < s; i++) {
        for (size_t r = 0; r < m; r++) {
            double sq = 0, sv = 0;
            for (int j = 0; j < s; j++) {
                const double kj = g->k[(size_t)j * m + r];
                sq += g->a2[i][j] * kj;
                sv += g->a[i][j] * kj;
            }
            g->stage[r] = q[r] + h * (g->c[i] * v[r] + h * sq);
            g->stage[m + r] = v[r] + h * sv;
        }
        int status = whirl_integrator_rhs(it, t + g->c[i] * h, g->stage, g->f);
        if (status != GSL_SUCCESS) return status;
        double *kn = g->k_new + (size_t)i * m;
        const double *ko = g->k + (size_t)i * m;
        for (size_t r = 0; r < m; r++) {
            kn[r] = g->f[m + r];
            worst = fmax(worst, fabs(kn[r] - ko[r]));
            big = fmax(big, fabs(kn[r]));
        }
    }
    double *swap = g->k;
    g->k = g->k_new;
    g->k_new = swap;
    *delta = worst;
    *kmax = big;
    return GSL_SUCCESS;
}

static int gauss_step(whirl_integrator *it, double t, double h, double *y)
{
    gauss_state *g = it->state;
    const size_t m = g->m;
    const int s = g->s;
    /* initial guess */
    if (g->has_prev && g->prev_h == h) {
        for (size_t r = 0; r < m; r++) {
            double old[GAUSS_MAX_STAGES];
            for (int j = 0; j < s; j++) old[j] = g->k[(size_t)j * m + r];
            for (int i = 0; i < s; i++) {
                double e = 0;
                for (int j = 0; j < s; j++) e += g->extrap[i][j] * old[j];
                g->k_new[(size_t)i * m + r] = e;
            }
        }
        double *swap = g->k;
        g->k = g->k_new;
        g->k_new = swap;
    } else {
        int status = whirl_integrator_rhs(it, t, y, g->f);
        if (status != GSL_SUCCESS) return status;
        for (int i = 0; i < s; i++) memcpy(g->k + (size_t)i * m, g->f + m, m * sizeof *g->f);
    }
    g->has_prev = 0;
    /* fixed-point iteration until the increments stop decreasing (at round-off); a transient
     * rise is tolerated, growth to 1e3 times the smallest increment is divergence */
    const double g_scale = it->sys.acceleration_scale;
    double prev = INFINITY, best = INFINITY;
    int converged = 0;
    for (int iter = 0; iter < GAUSS_MAX_ITER; iter++) {
        double delta, kmax;
        int status = gauss_sweep(it, t, h, y, &delta, &kmax);
        if (status != GSL_SUCCESS) return status;
        it->stats.iterations++;
        const double scale = kmax + g_scale;
        if (delta == 0 || (delta >= prev && prev <= 1e-8 * scale)) {
            converged = 1;
            break;
        }
        /* the step in 17 digits: a step given in other units reads back in them (in 6 the
         * rounding shows: 0.1 s over sqrt(L/g) and back is 0.0999999 s) */
        if (!(delta <= 1e3 * best))
            return whirl_fail(GSL_EMAXITER,
                              "the Gauss stage iteration diverges at t = " WHIRL_Q_TIME
                              "%.17g (step " WHIRL_Q_TIME "%.17g too large for the fastest mode)",
                              t, h);
        best = fmin(best, delta);
        prev = delta;
    }
    if (!converged)
        return whirl_fail(GSL_EMAXITER,
                          "the Gauss stage iteration did not converge in %d sweeps at t = "
                          WHIRL_Q_TIME "%.17g",
                          GAUSS_MAX_ITER, t);
    /* update with compensated summation: y += delta, comp carries the rounding */
    double *q = y, *v = y + m;
    for (size_t r = 0; r < m; r++) {
        double dq = 0, dv = 0;
        for (int j = 0; j < s; j++) {
            const double kj = g->k[(size_t)j * m + r];
            dq += g->bq[j] * kj;
            dv += g->b[j] * kj;
        }
        const double inc[2] = {h * (v[r] + h * dq), h * dv};
        double *dst[2] = {q + r, v + r};
        double *cmp[2] = {g->comp + r, g->comp + m + r};
        for (int k = 0; k < 2; k++) {
            const double add = inc[k] + *cmp[k];
            const double sum = *dst[k] + add;
            *cmp[k] = (*dst[k] - sum) + add;
            *dst[k] = sum;
        }
    }
    g->has_prev = 1;
    g->prev_h = h;
    return GSL_SUCCESS;
}

static const whirl_integrator_type gauss2_type = {
    .name = "gauss2",
    .adaptive = 0,
    .params = &gauss2_tableau,
    .alloc = gauss_alloc,
    .free = gauss_free,
    .step = gauss_step,
    .restart = gauss_restart,
};

static const whirl_integrator_type gauss3_type = {
    .name = "gauss3",
    .adaptive = 0,
    .params = &gauss3_tableau,
    .alloc = gauss_alloc,
    .free = gauss_free,
    .step = gauss_step,
    .restart = gauss_restart,
};

const whirl_integrator_type *const whirl_integrator_gauss2 = &gauss2_type;
const whirl_integrator_type *const whirl_integrator_gauss3 = &gauss3_type;
