/* Tests of the continuum steady shapes (src/continuum.c) against independent physics:
 * - the small-amplitude limit: near omega_k the shape is r = a J0(2 omega sqrt(sigma));
 * - Kolodner's count: exactly n shapes for omega_n < omega < omega_{n+1}, counted as the sign
 *   changes of the pivot radius r(1; a) over a fine grid of tip radii (whirl_continuum_sample),
 *   not with the solver's crossing counts;
 * - convergence under tightened ODE tolerances;
 * - the sub-chain property: below its first node a mode-k chain is a mode-(k-1) chain of length
 *   l = 1 - s_1 at the same omega (in its own units: rate omega sqrt(l), tip mass m / l);
 * - the N-link chain converges to it as N grows (order about 1); its critical rates too;
 * - the critical rates with a tip mass: the mode exists just above and not just below; all 3183
 *   in one sweep equal the per-mode roots, tend to j_{0,k}/2 as m -> 0, and the highest equals an
 *   independent 40-digit evaluation of the Bessel determinant;
 * - near-critical tip radii against a long-double Taylor-series integration of the unsplit
 *   equations;
 * - modes up to 6, near-critical and high rates, tip masses, the sampled shape, the errors. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_sf_bessel.h>

#include "whirl/steady.h"

static const double tip_masses[] = {0, 0.0137, 0.4821, 3.7};
#define N_TIP (sizeof tip_masses / sizeof *tip_masses)

static double rel(double x, double ref) { return fabs(x / ref - 1); }

static void test_small_amplitude_limit(void **state)
{
    (void)state;
    enum { npts = 101 };
    double s[npts], r[npts], z[npts], t[npts];
    for (int k = 1; k <= 4; k++) {
        double omega_k;
        assert_int_equal(whirl_continuum_critical(k, 0, &omega_k), GSL_SUCCESS);
        double worst[2];
        double eps[2] = {1e-4, 1e-6};
        for (int e = 0; e < 2; e++) {
            double omega = omega_k * (1 + eps[e]);
            whirl_shape_info info;
            assert_int_equal(whirl_continuum_solve(omega, k, 0, 0, &info), GSL_SUCCESS);
            assert_int_equal(whirl_continuum_sample(omega, 0, info.tip_r, npts, s, r, z, t),
                             GSL_SUCCESS);
            worst[e] = 0;
            for (int j = 0; j < npts; j++) {
                double profile = gsl_sf_bessel_J0(2 * omega_k * sqrt(1 - s[j]));
                worst[e] = fmax(worst[e], fabs(r[j] / info.tip_r - profile));
            }
        }
        /* the deviation is O(a^2) = O(omega - omega_k): 100 times smaller for eps / 100 */
        assert_true(worst[1] < 1e-4);
        assert_true(worst[1] < 0.03 * worst[0]);
    }
}

/* Modes beyond the 64 node arclengths of whirl_shape_info: just above the birth the nodes are
 * the linear shape's, the zeros of J0(2 omega_k sqrt(1 - s)), s = 1 - (j_{0,m} / (2 omega_k))^2
 * (m = k-1 first from the pivot), to O(omega - omega_k): mode 300 at eps = 1e-4 and 1e-6 (the
 * deviation 100 times smaller), modes 65 and 1000 at eps = 1e-6; all k - 1 crossings counted. */
static void test_high_modes(void **state)
{
    (void)state;
    const int modes[] = {65, 300, 300, 1000};
    const double eps[] = {1e-6, 1e-4, 1e-6, 1e-6};
    double dev[4];
    for (int c = 0; c < 4; c++) {
        const int k = modes[c];
        double omega_k;
        assert_int_equal(whirl_continuum_critical(k, 0, &omega_k), GSL_SUCCESS);
        whirl_shape_info info;
        assert_int_equal(whirl_continuum_solve(omega_k * (1 + eps[c]), k, 0, 0, &info),
                         GSL_SUCCESS);
        assert_int_equal(info.mode, k);
        assert_int_equal(info.n_nodes, k - 1);
        dev[c] = 0;
        for (int j = 0; j < WHIRL_SHAPE_NODES; j++) {
            const double x = gsl_sf_bessel_zero_J0((unsigned)(k - 1 - j)) / (2 * omega_k);
            dev[c] = fmax(dev[c], fabs(info.node_s[j] - (1 - x * x)));
            if (j > 0) assert_true(info.node_s[j] > info.node_s[j - 1]);
        }
        print_message("mode %d at (1 + %g) omega_k: first %d nodes within %.2e of the linear "
                      "shape's\n", k, eps[c], WHIRL_SHAPE_NODES, dev[c]);
        assert_true(dev[c] < eps[c]); /* the nodes move by O(omega - omega_k) */
    }
    assert_true(dev[2] < 0.03 * dev[1]);
    /* the last mode born below the continuum's highest rate, and the first beyond it */
    double omega;
    assert_int_equal(whirl_continuum_critical(WHIRL_CONTINUUM_MODE_MAX, 0, &omega), GSL_SUCCESS);
    assert_true(omega < WHIRL_CONTINUUM_OMEGA_MAX);
    assert_int_equal(whirl_continuum_critical(WHIRL_CONTINUUM_MODE_MAX + 1, 0, &omega),
                     GSL_EINVAL);
    whirl_shape_info info;
    assert_int_equal(whirl_continuum_solve(4999.9, WHIRL_CONTINUUM_MODE_MAX + 1, 0, 0, &info),
                     GSL_EINVAL);
}

/* Sign changes of r(pivot; a) over a log grid of a: the number of shapes at omega. */
static int count_shapes(double omega, double tip_mass)
{
    double s[2], r[2], z[2], t[2];
    int count = 0, sign = 0;
    for (int j = 0; j <= 600; j++) {
        double a = pow(10, -7 + 7.0 * j / 600);
        if (a > 1) a = 1;
        assert_int_equal(whirl_continuum_sample(omega, tip_mass, a, 2, s, r, z, t), GSL_SUCCESS);
        int sg = r[0] > 0 ? 1 : -1;
        if (sign != 0 && sg != sign) count++;
        sign = sg;
    }
    return count;
}

static void test_kolodner_count(void **state)
{
    (void)state;
    for (int tm = 0; tm < 2; tm++) {
        double m = tip_masses[tm * 2];
        double crit[6];
        for (int k = 1; k <= 6; k++) assert_int_equal(whirl_continuum_critical(k, m, &crit[k - 1]),
                                                      GSL_SUCCESS);
        for (int j = 0; j < 60; j++) {
            double omega = 0.5 + 8.5 * (j + 0.5) / 60;
            int n = 0;
            while (n < 6 && crit[n] < omega) n++;
            assert_true(n < 6);
            assert_int_equal(count_shapes(omega, m), n);
            /* and the solver finds each of them, tip radii decreasing with the mode */
            double previous = 2;
            for (int k = 1; k <= n + 1; k++) {
                whirl_shape_info info;
                int status = whirl_continuum_solve(omega, k, m, 0, &info);
                if (k == n + 1) {
                    assert_int_equal(status, GSL_EDOM);
                    break;
                }
                assert_int_equal(status, GSL_SUCCESS);
                assert_int_equal(info.n_nodes, k - 1);
                assert_true(info.tip_r < previous);
                previous = info.tip_r;
            }
        }
    }
}

static void test_tolerance_convergence(void **state)
{
    (void)state;
    const double rates[] = {1.9137, 4.4411, 7.385, 29.7};
    for (size_t t = 0; t < N_TIP; t++)
        for (size_t i = 0; i < sizeof rates / sizeof *rates; i++)
            for (int k = 1; k <= 6; k++) {
                whirl_shape_info a, b;
                int status = whirl_continuum_solve(rates[i], k, tip_masses[t], 0, &a);
                if (status == GSL_EDOM) continue;
                assert_int_equal(status, GSL_SUCCESS);
                assert_int_equal(whirl_continuum_solve_tol(rates[i], k, tip_masses[t], 0, 1e-15,
                                                           &b), GSL_SUCCESS);
                assert_true(rel(a.tip_r, b.tip_r) < 1e-11);
                assert_true(rel(a.top_tension, b.top_tension) < 1e-11);
                assert_true(rel(a.depth, b.depth) < 1e-11);
                assert_true(rel(a.max_r, b.max_r) < 1e-11);
                for (int j = 0; j < a.n_nodes; j++)
                    assert_true(fabs(a.node_s[j] - b.node_s[j]) < 1e-11);
            }
}

static void test_sub_chain(void **state)
{
    (void)state;
    const double rates[] = {6.1373, 11.29, 30};
    for (size_t t = 0; t < N_TIP; t++)
        for (size_t i = 0; i < sizeof rates / sizeof *rates; i++)
            for (int k = 2; k <= 6; k++) {
                whirl_shape_info whole, lower;
                int status = whirl_continuum_solve(rates[i], k, tip_masses[t], 0, &whole);
                if (status == GSL_EDOM) continue;
                assert_int_equal(status, GSL_SUCCESS);
                double l = 1 - whole.node_s[0];
                assert_int_equal(whirl_continuum_solve(rates[i] * sqrt(l), k - 1,
                                                       tip_masses[t] / l, 0, &lower),
                                 GSL_SUCCESS);
                assert_true(rel(lower.tip_r * l, whole.tip_r) < 1e-10);
                for (int j = 0; j < lower.n_nodes; j++)
                    assert_true(fabs(whole.node_s[0] + l * lower.node_s[j] - whole.node_s[j + 1]) <
                                1e-10);
            }
}

static void test_nlink_converges(void **state)
{
    (void)state;
    const size_t sizes[] = {200, 400, 800};
    for (size_t t = 0; t < 2; t++)
        for (int k = 1; k <= 3; k++) {
            double omega = 7.2791, m = tip_masses[2 * t];
            whirl_shape_info cont, disc[3];
            assert_int_equal(whirl_continuum_solve(omega, k, m, 0, &cont), GSL_SUCCESS);
            double crit_cont, err_crit[3];
            assert_int_equal(whirl_continuum_critical(k, m, &crit_cont), GSL_SUCCESS);
            for (int s = 0; s < 3; s++) {
                whirl_chain *c = whirl_chain_alloc_uniform(sizes[s], m);
                double crit[3];
                assert_int_equal(whirl_nlink_critical(c, 3, crit), GSL_SUCCESS);
                err_crit[s] = fabs(crit[k - 1] - crit_cont);
                assert_int_equal(whirl_nlink_solve(c, omega, k, &disc[s]), GSL_SUCCESS);
                whirl_chain_free(c);
            }
            /* relative errors of tip_r, top_tension, depth: order 1, and the Richardson
             * extrapolation 2 x(2N) - x(N) is much closer to the continuum */
            double cval[3] = {cont.tip_r, cont.top_tension, cont.depth};
            for (int q = 0; q < 3; q++) {
                double x[3], e[3];
                for (int s = 0; s < 3; s++) {
                    x[s] = q == 0 ? disc[s].tip_r : q == 1 ? disc[s].top_tension : disc[s].depth;
                    e[s] = fabs(x[s] / cval[q] - 1);
                }
                assert_true(e[2] < 0.01);
                double order = log2(e[1] / e[2]);
                assert_true(order > 0.75 && order < 1.25);
                assert_true(fabs((2 * x[2] - x[1]) / cval[q] - 1) < 0.2 * e[2]);
            }
            double order = log2(err_crit[1] / err_crit[2]);
            assert_true(order > 0.9 && order < 1.1);
        }
}

static void test_critical_with_tip_mass(void **state)
{
    (void)state;
    for (size_t t = 0; t < N_TIP; t++)
        for (int k = 1; k <= 6; k++) {
            double omega_k;
            assert_int_equal(whirl_continuum_critical(k, tip_masses[t], &omega_k), GSL_SUCCESS);
            whirl_shape_info info;
            assert_int_equal(whirl_continuum_solve(omega_k * (1 - 1e-7), k, tip_masses[t], 0,
                                                   &info), GSL_EDOM);
            assert_int_equal(whirl_continuum_solve(omega_k * (1 + 1e-6), k, tip_masses[t], 0,
                                                   &info), GSL_SUCCESS);
            assert_int_equal(info.n_nodes, k - 1);
            assert_true(info.tip_r < 0.01);
        }
    /* the limits: m -> 0 gives j_{0,k}/2; a heavy tip makes mode 1 a pendulum, omega_1 -> 1 */
    double omega;
    assert_int_equal(whirl_continuum_critical(2, 1e-12, &omega), GSL_SUCCESS);
    assert_true(rel(omega, 0.5 * gsl_sf_bessel_zero_J0(2)) < 1e-5);
    assert_int_equal(whirl_continuum_critical(1, 1e4, &omega), GSL_SUCCESS);
    assert_true(rel(omega, 1) < 1e-4);
}

/* Modes 1..3183 with a tip mass in one sweep. References: mode 3183's root of the determinant in
 * src/continuum.c's header comment, by mpmath 1.2.1 (40 digits, besselj/bessely, findroot),
 * whose count was confirmed by the sign changes of the same determinant (scipy.special) in steps
 * of 1e-3 in omega: 9655.9238544007285973 (m = 0.5), 20450.371510074109876 (m = 3.7),
 * 5617.4293884071243985 (m = 0.0137). */
static void test_critical_rates_sweep(void **state)
{
    (void)state;
    enum { K = WHIRL_CONTINUUM_MODE_MAX };
    static double rates[K];
    const double masses[] = {0.5, 3.7, 0.0137};
    const double ref[] = {9655.9238544007285973, 20450.371510074109876, 5617.4293884071243985};
    for (size_t t = 0; t < 3; t++) {
        assert_int_equal(whirl_continuum_critical_rates(K, masses[t], rates), GSL_SUCCESS);
        assert_true(rel(rates[K - 1], ref[t]) < 1e-13);
        for (int k = 2; k <= K; k++) assert_true(rates[k - 1] > rates[k - 2]);
        const int probe[] = {1, 2, 3, 61, 1000, K};
        for (size_t i = 0; i < 6; i++) {
            double omega;
            assert_int_equal(whirl_continuum_critical(probe[i], masses[t], &omega), GSL_SUCCESS);
            assert_true(omega == rates[probe[i] - 1]);
        }
    }
    /* m -> 0: every root tends to j_{0,k}/2 (a root missed would shift all later ones) */
    assert_int_equal(whirl_continuum_critical_rates(K, 1e-12, rates), GSL_SUCCESS);
    for (int k = 1; k <= K; k++)
        assert_true(rel(rates[k - 1], 0.5 * gsl_sf_bessel_zero_J0((unsigned)k)) < 1e-9);
    assert_int_equal(whirl_continuum_critical_rates(K, 0, rates), GSL_SUCCESS);
    assert_true(rates[K - 1] == 0.5 * gsl_sf_bessel_zero_J0(K));
    /* a stop request ends the sweep */
    whirl_stop_request();
    assert_int_equal(whirl_continuum_critical_rates(K, 0.5, rates), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_int_equal(whirl_continuum_critical_rates(0, 0.5, rates), GSL_EINVAL);
    assert_int_equal(whirl_continuum_critical_rates(K + 1, 0.5, rates), GSL_EINVAL);
    assert_int_equal(whirl_continuum_critical_rates(3, -1, rates), GSL_EINVAL);
}

static void test_sampled_shape(void **state)
{
    (void)state;
    enum { npts = 2001 };
    static double s[npts], r[npts], z[npts], t[npts];
    for (size_t tm = 0; tm < N_TIP; tm++) {
        double m = tip_masses[tm], omega = 8.8123;
        for (int k = 1; k <= 4; k++) {
            whirl_shape_info info;
            int status = whirl_continuum_solve(omega, k, m, 0, &info);
            if (status == GSL_EDOM) continue;
            assert_int_equal(status, GSL_SUCCESS);
            assert_int_equal(whirl_continuum_sample(omega, m, info.tip_r, npts, s, r, z, t),
                             GSL_SUCCESS);
            assert_true(s[0] == 0 && s[npts - 1] == 1);
            assert_true(fabs(r[0]) < 1e-12);
            assert_true(z[0] == 0);
            assert_true(rel(r[npts - 1], info.tip_r) < 1e-14);
            assert_true(rel(-z[npts - 1], info.depth) < 1e-11);
            assert_true(rel(t[0], info.top_tension) < 1e-11);
            /* the tip mass hangs on a tension m sqrt(g^2 + (omega^2 a)^2) */
            double b = omega * omega * info.tip_r;
            assert_true(fabs(t[npts - 1] - m * sqrt(1 + b * b)) <= 1e-15 * t[0]);
            /* inextensible: chords of length ds minus O(ds^3) */
            double length = 0, max_r = 0;
            int crossings = 0;
            for (int j = 1; j < npts; j++) {
                length += hypot(r[j] - r[j - 1], z[j] - z[j - 1]);
                max_r = fmax(max_r, fabs(r[j]));
                crossings += j > 1 && (r[j] > 0) != (r[j - 1] > 0);
                assert_true(z[j] < z[j - 1]);
            }
            assert_true(length < 1 && length > 1 - 1e-4);
            assert_int_equal(crossings, k - 1);
            assert_true(max_r <= info.max_r * (1 + 1e-12) && max_r > info.max_r * (1 - 1e-4));
        }
    }
}

static void test_branch_equals_fresh(void **state)
{
    (void)state;
    enum { n = 160 };
    double omega[n];
    whirl_shape_info info[n];
    int exists[n];
    for (int j = 0; j < n; j++) omega[j] = 1.0 + 9.0 * j / (n - 1);
    double crit;
    assert_int_equal(whirl_continuum_critical(3, 0.4821, &crit), GSL_SUCCESS);
    assert_int_equal(whirl_continuum_branch(3, 0.4821, n, omega, info, exists), GSL_SUCCESS);
    for (int j = 0; j < n; j++) {
        assert_int_equal(exists[j], omega[j] > crit);
        if (!exists[j] || j % 7) continue;
        whirl_shape_info fresh;
        assert_int_equal(whirl_continuum_solve(omega[j], 3, 0.4821, 0, &fresh), GSL_SUCCESS);
        assert_true(rel(info[j].tip_r, fresh.tip_r) < 1e-12);
    }
}

/* ---- reference for the near-critical tip radius ----
 * The whole (not split) scaled equations of src/continuum.c, R' = -omega^2 Q / S,
 * (sigma + m) Q' = R - Q, S = sqrt(1 + b^2 Q^2), R(0) = Q(0) = 1, integrated from the free end
 * by the Taylor-series method in long double (64-bit mantissa): at each centre sigma_c the
 * coefficients follow from (n + 1) R_{n+1} = -omega^2 [Q / S]_n and
 * (sigma_c + m) (n + 1) Q_{n+1} + n Q_n = R_n - Q_n (for sigma_c + m = 0: (n + 1) Q_n = R_n, the
 * regular singular free end needs no special start); the step is the largest for which the last
 * two terms are below taylor_tol. Root of R(1; a) by the secant method in long double. With
 * R(1) to ~1e-18, tip_r is good to ~1e-18 / (omega / omega_k - 1) relative. */
#define TAYLOR_TERMS 30

/* R(1) for the tip radius a, rate omega, tip mass m. */
static long double reference_pivot_radius(long double omega, long double m, long double a,
                                          long double taylor_tol)
{
    const long double w2 = omega * omega, b2 = w2 * a * w2 * a;
    long double sigma = 0, r0 = 1, q0 = 1;
    for (int steps = 0; sigma < 1; steps++) {
        assert_true(steps < 100000);
        long double r[TAYLOR_TERMS], q[TAYLOR_TERMS], s[TAYLOR_TERMS], p[TAYLOR_TERMS],
            q2[TAYLOR_TERMS];
        long double t = sigma + m;
        r[0] = r0;
        q[0] = q0;
        for (int n = 0; n < TAYLOR_TERMS; n++) {
            if (n > 0) {
                r[n] = -w2 * p[n - 1] / n;
                q[n] = t > 0 ? (r[n - 1] - n * q[n - 1]) / (t * n) : r[n] / (n + 1);
            }
            q2[n] = 0;
            for (int j = 0; j <= n; j++) q2[n] += q[j] * q[n - j];
            /* S^2 = 1 + b^2 Q^2, then P = Q / S */
            long double u = b2 * q2[n] + (n == 0);
            if (n == 0) s[0] = sqrtl(u);
            else {
                for (int j = 1; j < n; j++) u -= s[j] * s[n - j];
                s[n] = u / (2 * s[0]);
            }
            long double v = q[n];
            for (int j = 0; j < n; j++) v -= p[j] * s[n - j];
            p[n] = v / s[0];
        }
        long double h = 1 - sigma;
        for (int n = TAYLOR_TERMS - 2; n < TAYLOR_TERMS; n++) {
            long double c = fmaxl(fabsl(r[n]), fabsl(q[n]));
            if (c > 0) h = fminl(h, powl(taylor_tol / c, 1.0L / n));
        }
        if (sigma + h >= 1) h = 1 - sigma;
        r0 = 0, q0 = 0;
        for (int n = TAYLOR_TERMS - 1; n >= 0; n--) {
            r0 = r0 * h + r[n];
            q0 = q0 * h + q[n];
        }
        sigma = h == 1 - sigma ? 1 : sigma + h;
    }
    return r0;
}

/* The root of R(1; a) near a_guess. */
static long double reference_tip_radius(double omega, double tip_mass, double a_guess,
                                        long double taylor_tol)
{
    long double a0 = a_guess, a1 = a_guess * (1 + 1e-7L);
    long double f0 = reference_pivot_radius(omega, tip_mass, a0, taylor_tol);
    long double f1 = reference_pivot_radius(omega, tip_mass, a1, taylor_tol);
    for (int iter = 0; iter < 30 && f1 != f0; iter++) {
        long double a2 = a1 - f1 * (a1 - a0) / (f1 - f0);
        a0 = a1, f0 = f1;
        a1 = a2, f1 = reference_pivot_radius(omega, tip_mass, a1, taylor_tol);
        if (fabsl(a1 - a0) <= 1e-19L * a1) break;
    }
    return a1;
}

/* Near a critical rate tip_r ~ sqrt(omega - omega_k) is ill-conditioned (d ln a / d ln omega =
 * 1 / (2 eps)); at eps = omega / omega_k - 1 = 1e-6 it must still match the long-double
 * reference (at the same double omega) to 1e-10, whose own Taylor truncation is checked. */
static void test_near_critical_reference(void **state)
{
    (void)state;
    for (size_t t = 0; t < N_TIP; t++)
        for (int k = 1; k <= 6; k++) {
            double omega_k, m = tip_masses[t];
            assert_int_equal(whirl_continuum_critical(k, m, &omega_k), GSL_SUCCESS);
            double omega = omega_k * (1 + 1e-6);
            whirl_shape_info info;
            assert_int_equal(whirl_continuum_solve(omega, k, m, 0, &info), GSL_SUCCESS);
            long double ref = reference_tip_radius(omega, m, info.tip_r, 1e-22L);
            long double finer = reference_tip_radius(omega, m, info.tip_r, 1e-25L);
            assert_true(fabsl(finer / ref - 1) < 1e-12L);
            assert_true(fabsl(info.tip_r / ref - 1) < 1e-10L);
        }
}

static void test_errors(void **state)
{
    (void)state;
    whirl_shape_info info;
    double omega, s[2], r[2], z[2], t[2];
    assert_int_equal(whirl_continuum_solve(0, 1, 0, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_continuum_solve(-3, 1, 0, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_continuum_solve(INFINITY, 1, 0, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_continuum_solve(NAN, 1, 0, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_continuum_solve(3, 0, 0, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_continuum_solve(3, 1, -0.1, 0, &info), GSL_EINVAL);
    assert_int_equal(whirl_continuum_critical(0, 0, &omega), GSL_EINVAL);
    assert_int_equal(whirl_continuum_critical(1, NAN, &omega), GSL_EINVAL);
    assert_int_equal(whirl_continuum_sample(3, 0, 0.5, 1, s, r, z, t), GSL_EINVAL);
    assert_int_equal(whirl_continuum_solve(4.3, 3, 0, 0, &info), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "omega_3=4.3268"));
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_small_amplitude_limit),
        cmocka_unit_test(test_high_modes),
        cmocka_unit_test(test_kolodner_count),
        cmocka_unit_test(test_tolerance_convergence),
        cmocka_unit_test(test_sub_chain),
        cmocka_unit_test(test_nlink_converges),
        cmocka_unit_test(test_critical_with_tip_mass),
        cmocka_unit_test(test_critical_rates_sweep),
        cmocka_unit_test(test_sampled_shape),
        cmocka_unit_test(test_branch_equals_fresh),
        cmocka_unit_test(test_near_critical_reference),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("continuum", tests, NULL, NULL);
}
