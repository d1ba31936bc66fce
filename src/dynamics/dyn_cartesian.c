/* The Cartesian formulation of the N-link chain: link vectors and tensions as Lagrange multipliers,
 * O(N) per evaluation, no coordinate singularity.
 *
 * State y = (d_1..d_N, d_1'..d_N'): the link vectors d_i = x_i - x_{i-1} and their time
 * derivatives in the model's frame (3 components each in 3D; (x, z) in 2D). Link vectors rather
 * than positions keep |d_i| = l_i well conditioned at large N and make the projection separable.
 *
 * Equations (Baraff 1996, "Linear-time dynamics using Lagrange multipliers", SIGGRAPH): with
 * multipliers lambda_i (tension T_i = lambda_i l_i) and the per-mass acceleration
 * g_i = gvec + a_field(x_i, v_i) + f_i / m_i (gravity, in the co-rotating frame the centrifugal
 * w^2 (x, y, 0), Coriolis 2 w (v_y, -v_x, 0) and, with a rate w(t) that changes, Euler
 * w' (y, -x, 0) fields, applied forces f_i),
 *   m_i a_i = m_i g_i - lambda_i d_i + lambda_{i+1} d_{i+1}      (lambda_{N+1} = 0),
 *   d_i'' = a_i - a_{i-1},  a_0 = p''(t) the pivot's prescribed acceleration.
 * The second derivative of |d_i|^2 = l_i^2, d_i . d_i'' = -|d_i'|^2, gives the symmetric
 * positive definite tridiagonal system
 *   lambda_i |d_i|^2 (1/m_i + 1/m_{i-1}) - lambda_{i+1} (d_i . d_{i+1}) / m_i
 *     - lambda_{i-1} (d_i . d_{i-1}) / m_{i-1} = d_i . (g_i - g_{i-1}) + |d_i'|^2
 * (1/m_0 = 0, g_0 = p''), solved in O(N) by elimination from the tip up. The differences
 * g_i - g_{i-1} of the uniform fields are formed exactly from d_i, d_i' (gravity cancels, the
 * centrifugal difference is w^2 d_i, the Coriolis one 2 w (d_iy', -d_ix')), not by subtracting
 * nearly equal numbers.
 * Elimination from the tip up, in the form of solve_recursions below: the pivots q_i =
 * |d_i|^2 / m_{i-1} + s_i with s_i = (|d_i x d_{i+1}|^2 + m_i s_{i+1} |d_i|^2) /
 * (m_i (|d_{i+1}|^2 + m_i s_{i+1})), s_N = |d_N|^2 / m_N (Lagrange's identity |a|^2 |b|^2 -
 * (a.b)^2 = |a x b|^2: sums of non-negative terms, free of the cancellation q_1 = a - a (N-1)/N
 * of the straightforward recursion on a hanging chain), written with s_i = |d_i|^2 P_i / Q_i as
 * a recursion linear in (P, Q): no division on the serial path.
 * Round-off: the system is a discrete Laplacian (condition number ~ N^2); plain top-down Thomas
 * elimination in double loses accuracy growing with N (1.4e-8 relative tension error for the
 * hanging chain at N = 10^4). Everything here is in double; what keeps it accurate:
 *  - no coefficient is a ratio near 1: the (P, Q) recursion has the coefficients k_i =
 *    |d_i x d_{i+1}|^2 / (m_i |d_i|^2 |d_{i+1}|^2) and m_i only, and the ratios
 *    d_i . d_{i+1} / |d_{i+1}|^2 = 1 - eps_i of the recursions of the right-hand side and of the
 *    back-substitution are carried as eps_i = d_{i+1} . (d_{i+1} - d_i) / |d_{i+1}|^2, whose
 *    rounding is relative to eps_i (on a chain of equal links, |d_i|^2 / |d_{i+1}|^2 rounded to
 *    double is 1 or 1 +- 2^-52 for every link alike, and that systematic rounding gave 5e-13
 *    relative tension error on the mode-2 shape at N = 10^5);
 *  - Q, a sum of N positive terms on a hanging chain (the tension is lambda_i = nu Q_i there),
 *    carries its rounding errors exactly (Knuth's TwoSum) in a second term off the serial path.
 * The relative tension error against the same system solved in binary128 stays near round-off
 * up to N = 10^6 (tests/bench/bench_scaling.c, part tension; the figures are in the manual's
 * validation, "The chain in time").
 * Cost: two passes over the links that vectorise (the coefficients, then the accelerations;
 * one division per link) around two serial recursions of two floating-point operations' latency
 * per link each (tip-up (P, Q, rho) with one division per link off the serial path, then the
 * top-down nu). With whirl_dyn_set_threads(d, k > 1) and N >= WHIRL_DYN_THREADS_MIN_LINKS the
 * two passes are shared by k OpenMP threads (static blocks of links: every value is computed
 * as with one thread, so the results are bitwise the same); the recursions stay serial.
 * Projection: d_i <- l_i d_i / |d_i|, then d_i' <- d_i' - (d_i . d_i' / l_i^2) d_i, formed in long
 * double and rounded once (a scale factor rounded to double first makes the energy error grow
 * faster than the round-off's t^0.5). The Gauss step followed by the projection is neither
 * symplectic nor symmetric on the constraint manifold, so its truncation error can accumulate:
 * over 10^7 steps the energy error has a drift common to every run that falls fast with the
 * step (none is measurable at h = 0.00125), while the spread between runs, the round-off,
 * grows like t^0.5 (Brouwer's law).
 * Hairer's symmetric projection (pre-scaling each link by half the predicted correction) does not
 * reduce that drift, so it is not used (tests/bench/bench_stress.c, case "long"; the figures are in
 * the manual's validation, "The chain in time"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynamics/dyn_internal.h"
#include "core/error.h"
#include "core/threads.h"

static int cart_alloc(whirl_dyn *d)
{
    size_t n = d->n;
    d->size = 2 * (size_t)d->dim * n;
    d->coef = malloc(WHIRL_DYN_COEFS * n * sizeof *d->coef);
    d->multiplier = malloc(n * sizeof *d->multiplier);
    d->rescaled = malloc((n / 512 + 1) * sizeof *d->rescaled);
    if (!d->coef || !d->multiplier || !d->rescaled) return GSL_ENOMEM;
    d->co_k = d->coef, d->co_e = d->coef + n, d->co_b = d->coef + 2 * n;
    d->co_g = d->coef + 3 * n, d->co_q = d->coef + 4 * n, d->co_z = d->coef + 5 * n;
    return GSL_SUCCESS;
}

/* Component k (0..2) of link i sits at y[comp_index(d, i, k)] (2D: no y component). */
static size_t comp_index(const whirl_dyn *d, size_t i, int k)
{
    return d->dim == 3 ? 3 * i + (size_t)k : 2 * i + (k == 2);
}

static void cart_link(const whirl_dyn *d, const double *y, size_t i, double *dv, double *ddot)
{
    const double *q = y, *qd = y + d->size / 2;
    for (int k = 0; k < 3; k++) {
        if (d->dim == 2 && k == 1) {
            dv[k] = ddot[k] = 0;
            continue;
        }
        dv[k] = q[comp_index(d, i, k)];
        ddot[k] = qd[comp_index(d, i, k)];
    }
}

static void project_link(double len, double *dv, double *ddot)
{
    const long double norm2 =
        (long double)dv[0] * dv[0] + (long double)dv[1] * dv[1] + (long double)dv[2] * dv[2];
    const long double scale = len / sqrtl(norm2);
    long double d[3], along = 0;
    for (int k = 0; k < 3; k++) {
        d[k] = dv[k] * scale;
        along += d[k] * ddot[k];
    }
    along /= (long double)len * len;
    for (int k = 0; k < 3; k++) {
        dv[k] = (double)d[k];
        ddot[k] = (double)(ddot[k] - along * d[k]);
    }
}

static void store_link(const whirl_dyn *d, double *y, size_t i, const double *dv,
                       const double *ddot)
{
    double *q = y, *qd = y + d->size / 2;
    for (int k = 0; k < 3; k++) {
        if (d->dim == 2 && k == 1) continue;
        q[comp_index(d, i, k)] = dv[k];
        qd[comp_index(d, i, k)] = ddot[k];
    }
}

static int cart_project(whirl_dyn *d, double *y)
{
    const double *len = d->model.chain->length;
    for (size_t i = 0; i < d->n; i++) {
        double dv[3], dd[3];
        cart_link(d, y, i, dv, dd);
        project_link(len[i], dv, dd);
        store_link(d, y, i, dv, dd);
    }
    if (!whirl_dyn_all_finite(y, d->size))
        return whirl_fail(GSL_ERANGE, "the state is not finite (a link of zero length?)");
    return GSL_SUCCESS;
}

static int cart_from_links(whirl_dyn *d, const double *dv, const double *ddot, double *y)
{
    for (size_t i = 0; i < d->n; i++) store_link(d, y, i, dv + 3 * i, ddot + 3 * i);
    return cart_project(d, y);
}

/* The per-link bodies are inlined into their loops with dim a constant. */
#if defined(__GNUC__)
#define LINK_INLINE static inline __attribute__((always_inline))
#else
#define LINK_INLINE static inline
#endif

typedef struct vec3 {
    double x, y, z;
} vec3;

/* Link i of an array of dim-component vectors as a 3-vector (2D: (x, z), no y component). */
LINK_INLINE vec3 load3(const double *a, const int dim, size_t i)
{
    if (dim == 3) return (vec3){a[3 * i], a[3 * i + 1], a[3 * i + 2]};
    return (vec3){a[2 * i], 0.0, a[2 * i + 1]};
}

LINK_INLINE double dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* The parts of the right-hand side that do not depend on the link: the frame's fields, the
 * pivot's motion and the applied forces. */
typedef struct field {
    double w2, w2x; /* omega^2 and 2 omega in the co-rotating frame, else 0 */
    double dw;      /* omega' (Euler field) in the co-rotating frame, else 0 */
    double base[3]; /* link 1 only: g_1 - p'' less the part linear in d_1, d_1' */
    double *fdiff;  /* f_i / m_i - f_{i-1} / m_{i-1} (3 per link; f_0 = 0), NULL without forces */
} field;

/* g_i - g_{i-1} of link i from the co-rotating frame's fields (exact differences), less the
 * applied forces and link 1's base. */
LINK_INLINE vec3 frame_diff(const field *f, vec3 di, vec3 ri)
{
    return (vec3){f->w2 * di.x + f->w2x * ri.y + f->dw * di.y,
                  f->w2 * di.y - f->w2x * ri.x - f->dw * di.x, 0.0};
}

static void field_prepare(whirl_dyn *d, double t, const double *y, field *f)
{
    const whirl_model *m = &d->model;
    const double g = m->chain->gravity, *inv_mass = d->inv_mass;
    const int rotating = m->frame == WHIRL_FRAME_ROTATING;
    dyn_drive dr; /* the rate omega(t) and its derivative (ramps) */
    whirl_dyn_drive(d, t, &dr);
    const double w = dr.omega;
    double p[3], pv[3], pa[3];
    whirl_dyn_pivot(d, t, p, pv, pa);
    f->w2 = rotating ? w * w : 0.0;
    f->w2x = rotating ? 2 * w : 0.0;
    f->dw = rotating ? dr.domega : 0.0;
    /* link 1: the whole field at x_1 = p + d_1, v_1 = p' + d_1', less p'' */
    f->base[0] = f->w2 * p[0] + f->w2x * pv[1] + f->dw * p[1] - pa[0];
    f->base[1] = f->w2 * p[1] - f->w2x * pv[0] - f->dw * p[0] - pa[1];
    f->base[2] = -g - pa[2];
    f->fdiff = NULL;
    if (m->air_drag > 0 || m->air_drag_quadratic > 0 || m->internal_damping > 0 ||
        m->seed_sigma != NULL || m->seed_lambda != NULL) {
        whirl_dyn_prepare_forces(d, t, y, 1);
        double *fo = d->force; /* in place, from the tip up */
        for (size_t i = d->n; i-- > 0;)
            for (int k = 0; k < 3; k++)
                fo[3 * i + k] = fo[3 * i + k] * inv_mass[i] -
                                (i > 0 ? fo[3 * (i - 1) + k] * inv_mass[i - 1] : 0.0);
        f->fdiff = fo;
    }
}

/* Pass 1, per link (independent): the coefficients of the tip-up elimination of links
 * i = 0..N-2, k_i = |d_i x d_{i+1}|^2 / (m_i |d_i|^2 |d_{i+1}|^2), e_i = d_i . d_{i+1} /
 * |d_{i+1}|^2, g_i = |d_i|^2 and the right-hand side b_i = d_i . (g_i - g_{i-1}) + |d_i'|^2
 * (here without link 1's base and the applied forces). */
LINK_INLINE void coef_link(whirl_dyn *restrict d, const field *f, const double *restrict y,
                           size_t i, const int dim)
{
    const double *qd = y + d->size / 2;
    const vec3 di = load3(y, dim, i), ri = load3(qd, dim, i), dn = load3(y, dim, i + 1);
    const double norm2 = dot3(di, di), nn = dot3(dn, dn);
    const double cx = di.y * dn.z - di.z * dn.y;
    const double cy = di.z * dn.x - di.x * dn.z;
    const double cz = di.x * dn.y - di.y * dn.x;
    d->co_b[i] = dot3(di, frame_diff(f, di, ri)) + dot3(ri, ri);
    d->co_g[i] = norm2;
    const double m_norm2 = d->model.chain->mass[i] * norm2;
    const double r = 1.0 / (m_norm2 * nn);
    const vec3 diff = {dn.x - di.x, dn.y - di.y, dn.z - di.z};
    d->co_k[i] = (cx * cx + cy * cy + cz * cz) * r;
    d->co_e[i] = dot3(dn, diff) * (m_norm2 * r);
}

/* The tip's coefficients (k = e = 0), link 1's base and the applied forces in b. */
static void coef_ends(whirl_dyn *d, const field *f, const double *y, const int dim)
{
    const size_t n = d->n;
    const double *qd = y + d->size / 2;
    const vec3 di = load3(y, dim, n - 1), ri = load3(qd, dim, n - 1);
    d->co_b[n - 1] = dot3(di, frame_diff(f, di, ri)) + dot3(ri, ri);
    d->co_g[n - 1] = dot3(di, di);
    d->co_k[n - 1] = d->co_e[n - 1] = 0;
    const vec3 base = {f->base[0], f->base[1], f->base[2]};
    d->co_b[0] += dot3(load3(y, dim, 0), base);
    if (f->fdiff != NULL) {
        for (size_t i = 0; i < n; i++) {
            const double *fd = f->fdiff + 3 * i;
            d->co_b[i] += dot3(load3(y, dim, i), (vec3){fd[0], fd[1], fd[2]});
        }
    }
}

/* Pass 4, per link (independent): dydt of link i from the multipliers (lambda_{-1} and
 * lambda_N are 0: the flags top, tip). Returns 0 if the values written are finite, else NaN
 * (x - x is NaN for x infinite or NaN). */
LINK_INLINE double accel_link(const whirl_dyn *restrict d, const field *f,
                            const double *restrict y, double *restrict dydt, size_t i,
                            const int dim, const int top, const int tip)
{
    const size_t half = d->size / 2;
    const double *qd = y + half, *lam = d->multiplier, *inv_mass = d->inv_mass;
    const vec3 di = load3(y, dim, i), ri = load3(qd, dim, i), acc = frame_diff(f, di, ri);
    const double self = lam[i] * (inv_mass[i] + (top ? 0.0 : inv_mass[i - 1]));
    vec3 a = {acc.x - self * di.x, acc.y - self * di.y, acc.z - self * di.z};
    if (!tip) {
        const vec3 dn = load3(y, dim, i + 1);
        const double below = lam[i + 1] * inv_mass[i];
        a.x += below * dn.x, a.y += below * dn.y, a.z += below * dn.z;
    }
    if (!top) {
        const vec3 dp = load3(y, dim, i - 1);
        const double above = lam[i - 1] * inv_mass[i - 1];
        a.x += above * dp.x, a.y += above * dp.y, a.z += above * dp.z;
    }
    double *v = dydt + dim * i, *acc_out = dydt + half + dim * i;
    if (dim == 3) {
        v[0] = ri.x, v[1] = ri.y, v[2] = ri.z;
        acc_out[0] = a.x, acc_out[1] = a.y, acc_out[2] = a.z;
    } else {
        v[0] = ri.x, v[1] = ri.z;
        acc_out[0] = a.x, acc_out[1] = a.z;
    }
    return ((a.x - a.x) + (a.y - a.y) + (a.z - a.z)) + ((ri.x - ri.x) + (ri.y - ri.y) + (ri.z - ri.z));
}

/* Passes 2 and 3, serial. With s_i = |d_i|^2 t_i and t_i = P_i / Q_i, the pivot recursion is
 * linear in (P, Q) with the coefficients k_i and m_i only (no ratio near 1 to round, no division
 * on the critical path):
 *   P_i = k_i Q_{i+1} + P_{i+1},  Q_i = Q_{i+1} + m_i P_{i+1},  P_N = 1 / m_N, Q_N = 1;
 * then ratio_i = -(1 - eps_i) Q_{i+1} / Q_i, the reduced right-hand side
 * rho_i = r'_i Q_i = b_i Q_i + (1 - eps_i) rho_{i+1}, z_i = rho_i / (Q_i g_i (Q_i / m_{i-1} + P_i))
 * = r'_i / (q_i Q_i), and from the top nu_0 = z_0, nu_{i+1} = z_{i+1} + (1 - eps_i) nu_i,
 * lambda_i = nu_i Q_i. Q never decreases and at most doubles per link; past 2^512 P, Q and rho are
 * scaled by 2^-512 (exactly) and so is nu where it crosses that link, which leaves every ratio
 * unchanged (d->rescaled lists those links, at most one in 512). */
static void solve_recursions(whirl_dyn *d)
{
    const size_t n = d->n;
    const double *k = d->co_k, *b = d->co_b, *g = d->co_g, *mass = d->model.chain->mass;
    const double *inv_mass = d->inv_mass, *eps = d->co_e;
    double *qs = d->co_q, *z = d->co_z, *lam = d->multiplier;
    size_t *rescaled = d->rescaled, n_rescaled = 0;
    const double big = 0x1p512, small = 0x1p-512;
    double Q = 1, Q_lo = 0, P = inv_mass[n - 1], rho = b[n - 1];
    qs[n - 1] = Q;
    z[n - 1] = rho / (Q * g[n - 1] * ((n > 1 ? inv_mass[n - 2] : 0.0) * Q + P));
    for (size_t i = n - 1; i-- > 0;) {
        const double add = mass[i] * P;
        double Qn = Q + add;
        double Pn = k[i] * Q + P;
        const double Qn_b = Qn - Q; /* Knuth's TwoSum: Q + add = Qn + the error, exactly */
        Q_lo += (Q - (Qn - Qn_b)) + (add - Qn_b);
        if (Qn > big) {
            Qn *= small, Q_lo *= small, Pn *= small, rho *= small;
            rescaled[n_rescaled++] = i;
        }
        Q = Qn, P = Pn;
        const double Qc = Q + Q_lo; /* Q compensated, off the recursion's path */
        rho = (b[i] * Qc + rho) - eps[i] * rho; /* two operations deep in rho */
        qs[i] = Qc;
        z[i] = rho / (Qc * g[i] * ((i > 0 ? inv_mass[i - 1] : 0.0) * Qc + P));
    }
    double nu = z[0];
    lam[0] = nu * qs[0];
    for (size_t i = 0; i + 1 < n;) {
        const size_t stop = n_rescaled > 0 ? rescaled[n_rescaled - 1] : n - 1;
        for (; i < stop; i++) {
            nu = (z[i + 1] + nu) - eps[i] * nu;
            lam[i + 1] = nu * qs[i + 1];
        }
        if (n_rescaled > 0) { /* i == stop: the link where Q was scaled */
            nu *= small;
            nu = (z[i + 1] + nu) - eps[i] * nu;
            lam[i + 1] = nu * qs[i + 1];
            i++;
            n_rescaled--;
        }
    }
}

/* Pass 1 over links lo..hi-1, vectorised. */
static void coef_block(whirl_dyn *d, const field *f, const double *y, size_t lo, size_t hi)
{
    if (d->dim == 3) {
#pragma omp simd
        for (size_t i = lo; i < hi; i++) coef_link(d, f, y, i, 3);
    } else {
#pragma omp simd
        for (size_t i = lo; i < hi; i++) coef_link(d, f, y, i, 2);
    }
}

/* The first of count items in block b of blocks equal ones (b = blocks: count). */
static size_t block_start(size_t count, int blocks, int b)
{
    return count / (size_t)blocks * (size_t)b + count % (size_t)blocks * (size_t)b / (size_t)blocks;
}

/* d->multiplier <- lambda at (t, y); *f receives the fields for the accelerations. */
static void solve_multipliers(whirl_dyn *d, double t, const double *y, field *f)
{
    const size_t n = d->n;
    field_prepare(d, t, y, f);
    const int threads = n >= WHIRL_DYN_THREADS_MIN_LINKS ? whirl_threads_for(d->threads) : 1;
    if (threads > 1) { /* links 0..N-2 in one static block per thread */
#pragma omp parallel for num_threads(threads) schedule(static)
        for (int b = 0; b < threads; b++)
            coef_block(d, f, y, block_start(n - 1, threads, b), block_start(n - 1, threads, b + 1));
        coef_ends(d, f, y, d->dim);
    } else if (d->dim == 3) {
#pragma omp simd
        for (size_t i = 0; i < n - 1; i++) coef_link(d, f, y, i, 3);
        coef_ends(d, f, y, 3);
    } else {
#pragma omp simd
        for (size_t i = 0; i < n - 1; i++) coef_link(d, f, y, i, 2);
        coef_ends(d, f, y, 2);
    }
    solve_recursions(d);
}

/* Pass 4 over the inner links lo..hi-1 (neither the top nor the tip), vectorised; the sum of
 * their finiteness probes. */
LINK_INLINE double accel_block(const whirl_dyn *d, const field *f, const double *y, double *dydt,
                               size_t lo, size_t hi, const int dim)
{
    double probe = 0;
#pragma omp simd reduction(+ : probe)
    for (size_t i = lo; i < hi; i++) probe += accel_link(d, f, y, dydt, i, dim, 0, 0);
    return probe;
}

/* dydt of every link, for dim = 2 or 3 (a constant where inlined); 0 if it is finite. */
LINK_INLINE int accelerations(whirl_dyn *d, const field *f, const double *y, double *dydt,
                              const int dim)
{
    const size_t n = d->n, half = d->size / 2;
    double probe = 0;
    if (n == 1) {
        probe += accel_link(d, f, y, dydt, 0, dim, 1, 1);
    } else {
        probe += accel_link(d, f, y, dydt, 0, dim, 1, 0);
        const int threads = n >= WHIRL_DYN_THREADS_MIN_LINKS ? whirl_threads_for(d->threads) : 1;
        if (threads > 1) { /* links 1..N-2 in one static block per thread */
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : probe)
            for (int b = 0; b < threads; b++) {
                const size_t lo = 1 + block_start(n - 2, threads, b);
                const size_t hi = 1 + block_start(n - 2, threads, b + 1);
                /* dim a constant again inside the outlined region, so that the loop vectorises */
                probe += dim == 3 ? accel_block(d, f, y, dydt, lo, hi, 3)
                                  : accel_block(d, f, y, dydt, lo, hi, 2);
            }
        } else {
#pragma omp simd reduction(+ : probe)
            for (size_t i = 1; i < n - 1; i++) probe += accel_link(d, f, y, dydt, i, dim, 0, 0);
        }
        probe += accel_link(d, f, y, dydt, n - 1, dim, 0, 1);
    }
    /* link 1's base and the applied forces */
    double *a = dydt + half;
    a[0] += f->base[0];
    if (dim == 3) a[1] += f->base[1];
    a[dim - 1] += f->base[2];
    probe += (a[0] - a[0]) + (a[dim - 1] - a[dim - 1]);
    if (f->fdiff != NULL) {
        if (!whirl_dyn_all_finite(f->fdiff, 3 * n)) return 1;
        for (size_t i = 0; i < n; i++) {
            const double *fd = f->fdiff + 3 * i;
            a[dim * i] += fd[0];
            if (dim == 3) a[dim * i + 1] += fd[1];
            a[dim * i + dim - 1] += fd[2];
        }
        return !whirl_dyn_all_finite(dydt, d->size);
    }
    return isnan(probe);
}

static int cart_rhs(whirl_dyn *d, double t, const double *y, double *dydt)
{
    field f;
    solve_multipliers(d, t, y, &f);
    const int bad = d->dim == 3 ? accelerations(d, &f, y, dydt, 3)
                                : accelerations(d, &f, y, dydt, 2);
    if (bad)
        return whirl_fail(GSL_EBADFUNC, "the right-hand side is not finite at t = " WHIRL_Q_TIME
                          "%.17g", t);
    return GSL_SUCCESS;
}

static int cart_tensions(whirl_dyn *d, double t, const double *y, double *tension)
{
    field f;
    solve_multipliers(d, t, y, &f);
    for (size_t i = 0; i < d->n; i++) tension[i] = d->multiplier[i] * sqrt(d->co_g[i]);
    if (!whirl_dyn_all_finite(tension, d->n))
        return whirl_fail(GSL_EBADFUNC, "the tensions are not finite at t = %.17g", t);
    return GSL_SUCCESS;
}

const dyn_ops whirl_dyn_cartesian_ops = {
    .link = cart_link,
    .from_links = cart_from_links,
    .rhs = cart_rhs,
    .project = cart_project,
    .tensions = cart_tensions,
    .alloc = cart_alloc,
};
