/* Tests of the dynamics module's right-hand sides (src/dynamics.c, dyn_cartesian.c, dyn_seed.c):
 * the Cartesian and the seed formulations against each other at random regular states, the
 * hanging chain and the steady whirling shape as exact equilibria, power balances of the
 * dissipative forces, frame conversions, and the error paths. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "test_dynamics"
#include "bench_util.h"
#include "tension_ref.h"

static uint64_t rng_state = 0x2545F4914F6CDD1DULL;
static double uniform(double a, double b)
{
    /* splitmix64 */
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return a + (b - a) * (double)(z >> 11) / 9007199254740992.0;
}

static whirl_chain *random_chain(size_t n)
{
    double len[16], mass[16];
    for (size_t i = 0; i < n; i++) {
        len[i] = uniform(0.3, 1.7);
        mass[i] = uniform(0.2, 2.5);
    }
    return whirl_chain_alloc(n, len, mass, 1.385);
}

/* Positions and velocities (3 per mass, model frame) of a random regular state: angles theta in
 * (0.2, 2.9), any azimuth, random rates; pivot at p, pv. */
static void random_state(const whirl_chain *c, int dim, const double *p, const double *pv,
                         double *x, double *v)
{
    double pos[3] = {p[0], p[1], p[2]}, vel[3] = {pv[0], pv[1], pv[2]};
    for (size_t i = 0; i < c->n; i++) {
        const double th = uniform(0.2, 2.9) * (dim == 2 && uniform(0, 1) < 0.5 ? -1 : 1);
        const double ph = dim == 3 ? uniform(-3.1, 3.1) : 0.0;
        const double thd = uniform(-1.5, 1.5), phd = dim == 3 ? uniform(-1.5, 1.5) : 0.0;
        const double l = c->length[i];
        const double u[3] = {sin(th) * cos(ph), sin(th) * sin(ph), -cos(th)};
        const double eth[3] = {cos(th) * cos(ph), cos(th) * sin(ph), sin(th)};
        const double eph[3] = {-sin(ph), cos(ph), 0};
        for (int k = 0; k < 3; k++) {
            pos[k] += l * u[k];
            vel[k] += l * (thd * eth[k] + phd * sin(th) * eph[k]);
            x[3 * i + k] = pos[k];
            v[3 * i + k] = vel[k];
        }
    }
}

/* The pivot of model at t, recomputed here: (eps cos wt, eps sin wt, 0) inertial (2D: y = 0),
 * (eps, 0, 0) co-rotating. */
static void pivot(const whirl_model *m, double t, double *p, double *pv)
{
    const double e = m->drive_radius, w = m->omega;
    if (m->frame == WHIRL_FRAME_ROTATING) {
        p[0] = e, p[1] = p[2] = pv[0] = pv[1] = pv[2] = 0;
        return;
    }
    p[0] = e * cos(w * t), p[1] = m->dim == 3 ? e * sin(w * t) : 0, p[2] = 0;
    pv[0] = -e * w * sin(w * t), pv[1] = m->dim == 3 ? e * w * cos(w * t) : 0, pv[2] = 0;
}

/* Mass accelerations (3 per mass, model frame) at t from the state y of d: by the difference
 * quotient of the velocities along the flow, central, of step h (exact for the velocities'
 * derivative up to O(h^2)); used only where the formulations' states differ in kind. */
static void mass_accelerations(whirl_dyn *d, double t, const double *y, double *acc)
{
    const size_t n = whirl_dyn_model(d)->chain->n, size = whirl_dyn_size(d);
    double *f = malloc(size * sizeof *f), *yp = malloc(size * sizeof *yp);
    double *x = malloc(3 * n * sizeof *x), *v0 = malloc(3 * n * sizeof *v0),
           *v1 = malloc(3 * n * sizeof *v1);
    assert_int_equal(whirl_dyn_rhs(t, y, f, d), GSL_SUCCESS);
    /* the velocities are linear in qdot, so d v/dt = dv/dq qdot + dv/dqdot qddot: evaluate by
     * Richardson-extrapolated central differences along the flow direction f */
    const double hs[2] = {1e-4, 5e-5};
    double est[2][3 * 16];
    for (int r = 0; r < 2; r++) {
        const double h = hs[r];
        for (size_t k = 0; k < size; k++) yp[k] = y[k] + h * f[k];
        whirl_dyn_get_state(d, t + h, yp, whirl_dyn_model(d)->frame, x, v1);
        for (size_t k = 0; k < size; k++) yp[k] = y[k] - h * f[k];
        whirl_dyn_get_state(d, t - h, yp, whirl_dyn_model(d)->frame, x, v0);
        for (size_t k = 0; k < 3 * n; k++) est[r][k] = (v1[k] - v0[k]) / (2 * h);
    }
    for (size_t k = 0; k < 3 * n; k++) acc[k] = (4 * est[1][k] - est[0][k]) / 3;
    free(f), free(yp), free(x), free(v0), free(v1);
}

static double max_abs(const double *a, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
    return m;
}

/* The two formulations give the same dynamics at random regular states: the tensions (which
 * follow from the accelerations) to 1e-12 relative, and the mass accelerations to the accuracy
 * of the difference quotient. Every force and both frames. */
static void test_formulations_agree(void **state)
{
    (void)state;
    const size_t sizes[] = {1, 2, 3, 5, 10};
    double worst_tension = 0, worst_acc = 0;
    for (int dim = 2; dim <= 3; dim++) {
        for (int frame = 0; frame <= (dim == 3); frame++) {
            for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
                const size_t n = sizes[s];
                whirl_chain *c = random_chain(n);
                double sigma[16], lambda[16];
                for (size_t i = 0; i < n; i++) {
                    sigma[i] = uniform(-0.5, 0.5);
                    lambda[i] = uniform(0, 0.7);
                }
                whirl_model m = {.chain = c,
                                 .dim = dim,
                                 .frame = (whirl_frame)frame,
                                 .omega = 1.7342,
                                 .drive_radius = 0.135,
                                 .air_drag = 0.231,
                                 .air_drag_quadratic = 0.117,
                                 .internal_damping = 0.0523,
                                 .seed_sigma = dim == 2 ? sigma : NULL,
                                 .seed_lambda = dim == 2 ? lambda : NULL};
                whirl_dyn *dc = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
                whirl_dyn *ds = whirl_dyn_alloc(&m, WHIRL_FORMULATION_SEED);
                assert_non_null(dc);
                assert_non_null(ds);
                const double t = 0.7311;
                double p[3], pv[3], x[48], v[48], yc[96], ys[96], tc[16], ts[16];
                double ac[48], as[48];
                pivot(&m, t, p, pv);
                random_state(c, dim, p, pv, x, v);
                assert_int_equal(whirl_dyn_set_state(dc, t, x, v, yc), GSL_SUCCESS);
                assert_int_equal(whirl_dyn_set_state(ds, t, x, v, ys), GSL_SUCCESS);
                assert_int_equal(whirl_dyn_tensions(dc, t, yc, tc), GSL_SUCCESS);
                assert_int_equal(whirl_dyn_tensions(ds, t, ys, ts), GSL_SUCCESS);
                const double scale = max_abs(ts, n);
                for (size_t i = 0; i < n; i++) {
                    const double err = fabs(tc[i] - ts[i]) / scale;
                    worst_tension = fmax(worst_tension, err);
                    assert_true(err < 1e-12);
                }
                mass_accelerations(dc, t, yc, ac);
                mass_accelerations(ds, t, ys, as);
                const double ascale = max_abs(as, 3 * n);
                for (size_t k = 0; k < 3 * n; k++) {
                    const double err = fabs(ac[k] - as[k]) / ascale;
                    worst_acc = fmax(worst_acc, err);
                    assert_true(err < 1e-7);
                }
                whirl_dyn_free(dc);
                whirl_dyn_free(ds);
                whirl_chain_free(c);
            }
        }
    }
    print_message("worst relative difference: tensions %.3g, accelerations %.3g\n", worst_tension,
                  worst_acc);
}

/* The Cartesian right-hand side maps the rates exactly and its link accelerations agree with the
 * seed's angles differentiated twice: d_i'' = l (th'' e_th + ph'' sin th e_ph + c), c the
 * velocity-quadratic term, at 1e-12 relative (no difference quotient). */
static void test_link_accelerations_agree(void **state)
{
    (void)state;
    double worst = 0;
    for (int dim = 2; dim <= 3; dim++) {
        for (int frame = 0; frame <= (dim == 3); frame++) {
            for (size_t n = 1; n <= 10; n += 3) {
                whirl_chain *c = random_chain(n);
                double sigma[16];
                for (size_t i = 0; i < n; i++) sigma[i] = uniform(-0.5, 0.5);
                whirl_model m = {.chain = c, .dim = dim, .frame = (whirl_frame)frame,
                                 .omega = 2.213, .drive_radius = 0.071, .air_drag = 0.3,
                                 .internal_damping = 0.04,
                                 .seed_sigma = dim == 2 ? sigma : NULL};
                whirl_dyn *dc = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
                whirl_dyn *ds = whirl_dyn_alloc(&m, WHIRL_FORMULATION_SEED);
                const double t = 1.93;
                double p[3], pv[3], x[48], v[48], yc[96], ys[96], fc[96], fs[96];
                pivot(&m, t, p, pv);
                random_state(c, dim, p, pv, x, v);
                assert_int_equal(whirl_dyn_set_state(dc, t, x, v, yc), GSL_SUCCESS);
                assert_int_equal(whirl_dyn_set_state(ds, t, x, v, ys), GSL_SUCCESS);
                assert_int_equal(whirl_dyn_rhs(t, yc, fc, dc), GSL_SUCCESS);
                assert_int_equal(whirl_dyn_rhs(t, ys, fs, ds), GSL_SUCCESS);
                const size_t hc = whirl_dyn_size(dc) / 2, hs = whirl_dyn_size(ds) / 2;
                for (size_t k = 0; k < hc; k++) assert_true(fc[k] == yc[hc + k]);
                double acc_c[48], acc_s[48], scale = 0;
                for (size_t i = 0; i < n; i++) {
                    const double th = ys[i], ph = dim == 3 ? ys[n + i] : 0;
                    const double thd = ys[hs + i], phd = dim == 3 ? ys[hs + n + i] : 0;
                    const double thdd = fs[hs + i], phdd = dim == 3 ? fs[hs + n + i] : 0;
                    const double st = sin(th), ct = cos(th), sp = sin(ph), cp = cos(ph);
                    const double u[3] = {st * cp, st * sp, -ct}, eth[3] = {ct * cp, ct * sp, st},
                                 eph[3] = {-sp, cp, 0};
                    for (int k = 0; k < 3; k++) {
                        const double quad = -(thd * thd + phd * phd * st * st) * u[k] +
                                            2 * thd * phd * ct * eph[k] -
                                            phd * phd * st * ct * eth[k];
                        acc_s[3 * i + k] =
                            c->length[i] * (thdd * eth[k] + phdd * st * eph[k] + quad);
                        const size_t idx = dim == 3 ? 3 * i + k : 2 * i + (k == 2);
                        acc_c[3 * i + k] = dim == 2 && k == 1 ? 0 : fc[hc + idx];
                        scale = fmax(scale, fabs(acc_s[3 * i + k]));
                    }
                }
                for (size_t k = 0; k < 3 * n; k++) {
                    const double err = fabs(acc_c[k] - acc_s[k]) / scale;
                    worst = fmax(worst, err);
                    assert_true(err < 1e-12);
                }
                whirl_dyn_free(dc);
                whirl_dyn_free(ds);
                whirl_chain_free(c);
            }
        }
    }
    print_message("worst relative difference of the link accelerations: %.3g\n", worst);
}

/* Closed forms: the planar double pendulum (theta'' as in e.g. Goldstein's Lagrangian, solved
 * for the two accelerations) and the spherical pendulum, theta'' = ph'^2 sin th cos th
 * - (g/l) sin th, ph'' = -2 th' ph' cos th / sin th (the seed's eq. 43 misprints the latter as
 * + th' ph' cot th). Both formulations, through the seed's angle rates. */
static void test_analytic_limits(void **state)
{
    (void)state;
    const double l1 = 0.817, l2 = 1.243, m1 = 0.731, m2 = 1.388, g = 1.385;
    const double th1 = 0.913, th2 = -1.771, w1 = 0.537, w2 = -1.219;
    const double dth = th1 - th2, den = 2 * m1 + m2 - m2 * cos(2 * dth);
    const double acc1 = (-g * (2 * m1 + m2) * sin(th1) - m2 * g * sin(th1 - 2 * th2) -
                         2 * sin(dth) * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * cos(dth))) /
                        (l1 * den);
    const double acc2 = 2 * sin(dth) *
                        (w1 * w1 * l1 * (m1 + m2) + g * (m1 + m2) * cos(th1) +
                         w2 * w2 * l2 * m2 * cos(dth)) /
                        (l2 * den);
    const double len[2] = {l1, l2}, mass[2] = {m1, m2};
    whirl_chain *c = whirl_chain_alloc(2, len, mass, g);
    const whirl_model m = {.chain = c, .dim = 2};
    const double x[6] = {l1 * sin(th1), 0, -l1 * cos(th1), l1 * sin(th1) + l2 * sin(th2), 0,
                         -l1 * cos(th1) - l2 * cos(th2)};
    const double v[6] = {l1 * w1 * cos(th1), 0, l1 * w1 * sin(th1),
                         l1 * w1 * cos(th1) + l2 * w2 * cos(th2), 0,
                         l1 * w1 * sin(th1) + l2 * w2 * sin(th2)};
    double y[8], f[8];
    whirl_dyn *ds = whirl_dyn_alloc(&m, WHIRL_FORMULATION_SEED);
    assert_int_equal(whirl_dyn_set_state(ds, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(0, y, f, ds), GSL_SUCCESS);
    const double scale = fmax(fabs(acc1), fabs(acc2));
    assert_true(fabs(f[2] - acc1) < 1e-14 * scale && fabs(f[3] - acc2) < 1e-14 * scale);
    /* Cartesian: theta_i'' = e_i . d_i'' / l_i (the centripetal part is along d_i) */
    whirl_dyn *dc = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_int_equal(whirl_dyn_set_state(dc, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(0, y, f, dc), GSL_SUCCESS);
    const double c1 = (cos(th1) * f[4] + sin(th1) * f[5]) / l1;
    const double c2 = (cos(th2) * f[6] + sin(th2) * f[7]) / l2;
    assert_true(fabs(c1 - acc1) < 1e-14 * scale && fabs(c2 - acc2) < 1e-14 * scale);
    whirl_dyn_free(ds);
    whirl_dyn_free(dc);
    whirl_chain_free(c);

    /* spherical pendulum */
    const double l = 0.917, th = 1.123, ph = 0.377, thd = -0.613, phd = 1.271;
    whirl_chain *c1link = whirl_chain_alloc(1, &l, &m1, g);
    const whirl_model ms = {.chain = c1link, .dim = 3};
    whirl_dyn *d1 = whirl_dyn_alloc(&ms, WHIRL_FORMULATION_SEED);
    const double u[3] = {sin(th) * cos(ph), sin(th) * sin(ph), -cos(th)};
    const double et[3] = {cos(th) * cos(ph), cos(th) * sin(ph), sin(th)}, ep[3] = {-sin(ph),
                                                                                  cos(ph), 0};
    double xs[3], vs[3], ys[4], fs[4];
    for (int k = 0; k < 3; k++) {
        xs[k] = l * u[k];
        vs[k] = l * (thd * et[k] + phd * sin(th) * ep[k]);
    }
    assert_int_equal(whirl_dyn_set_state(d1, 0, xs, vs, ys), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(0, ys, fs, d1), GSL_SUCCESS);
    const double th_dd = phd * phd * sin(th) * cos(th) - g / l * sin(th);
    const double ph_dd = -2 * thd * phd * cos(th) / sin(th);
    assert_true(fabs(fs[2] - th_dd) < 1e-14 && fabs(fs[3] - ph_dd) < 1e-14);
    whirl_dyn_free(d1);
    whirl_chain_free(c1link);
}

/* A chain hanging straight down (singular for the seed's 3D angles) is an equilibrium of the
 * Cartesian formulation: zero accelerations, tension = weight of the masses below. */
static void test_hanging_chain(void **state)
{
    (void)state;
    const size_t sizes[] = {1, 7, 1000};
    for (int dim = 2; dim <= 3; dim++) {
        for (size_t s = 0; s < 3; s++) {
            const size_t n = sizes[s];
            whirl_chain *c = whirl_chain_alloc_uniform(n, 0.37);
            whirl_model m = {.chain = c, .dim = dim, .frame = WHIRL_FRAME_INERTIAL};
            whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
            const size_t size = whirl_dyn_size(d);
            double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
            double *y = malloc(size * sizeof *y), *f = malloc(size * sizeof *f);
            double *tension = malloc(n * sizeof *tension);
            double z = 0;
            for (size_t i = 0; i < n; i++) x[3 * i + 2] = z -= c->length[i];
            assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
            assert_int_equal(whirl_dyn_rhs(0, y, f, d), GSL_SUCCESS);
            assert_true(max_abs(f, size) < 1e-12);
            assert_int_equal(whirl_dyn_tensions(d, 0, y, tension), GSL_SUCCESS);
            long double below = 0;
            double worst = 0;
            for (size_t i = n; i-- > 0;) {
                below += (long double)c->mass[i] * c->gravity;
                worst = fmax(worst, (double)fabsl((tension[i] - below) / below));
            }
            if (n == 1000) print_message("hanging chain N = 1000: tension error %.3g\n", worst);
            assert_true(worst < 1e-15);
            free(x), free(v), free(y), free(f), free(tension);
            whirl_dyn_free(d);
            whirl_chain_free(c);
        }
    }
}

/* The multipliers of the Cartesian right-hand side against the same tridiagonal system solved by
 * plain Thomas elimination in binary128 (tests/lib/tension_ref.h), at N = 3000 for the hanging chain,
 * a moving 3D state and the mode-2 shape at omega = 4 (co-rotating): the tensions to 1e-13
 * relative (their round-off grows with N; about 1e-14 here) and the link accelerations, formed
 * in binary128 from the reference multipliers, to 1e-13 of the largest of them, of g and of the
 * constraint terms lambda_i |d_i| (1/m_i + 1/m_{i-1}) that cancel in them. */
static void test_multipliers_binary128(void **state)
{
    (void)state;
    const size_t n = 3000;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    double *y = malloc(6 * n * sizeof *y), *f = malloc(6 * n * sizeof *f);
    double *ten = malloc(n * sizeof *ten), *ref = malloc(n * sizeof *ref);
    real128 *work = malloc(3 * n * sizeof *work);
    assert_true(c && x && v && y && f && ten && ref && work);
    for (int kind = 0; kind < 3; kind++) {
        const double w = kind == 2 ? 4.0 : 0.0;
        const whirl_model m = {.chain = c,
                               .dim = 3,
                               .frame = kind == 2 ? WHIRL_FRAME_ROTATING : WHIRL_FRAME_INERTIAL,
                               .omega = w};
        memset(x, 0, 3 * n * sizeof *x);
        memset(v, 0, 3 * n * sizeof *v);
        if (kind == 0) {
            for (size_t i = 0; i < n; i++) x[3 * i + 2] = -(double)(i + 1) / (double)n;
        } else if (kind == 1) {
            const double p[3] = {0, 0, 0};
            bench_smooth_state(c, p, x, v);
        } else {
            assert_int_equal(bench_steady_positions(c, w, 2, x), GSL_SUCCESS);
        }
        whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        assert_non_null(d);
        assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
        assert_int_equal(whirl_dyn_tensions(d, 0, y, ten), GSL_SUCCESS);
        assert_int_equal(whirl_dyn_rhs(0, y, f, d), GSL_SUCCESS);
        tensions_quad(c, w, y, ref, work);
        double worst_t = 0, worst_a = 0, scale = c->gravity;
        for (size_t i = 0; i < n; i++) worst_t = fmax(worst_t, fabs(ten[i] / ref[i] - 1));
        const real128 *lam = work + n;
        double acc[3 * 3000];
        for (size_t i = 0; i < n; i++) {
            const double *di = y + 3 * i, *ri = y + 3 * n + 3 * i;
            const real128 inv_m = 1 / (real128)c->mass[0]; /* uniform chain */
            const real128 field[3] = {(real128)w * w * di[0] + 2 * (real128)w * ri[1],
                                   (real128)w * w * di[1] - 2 * (real128)w * ri[0],
                                   i == 0 ? -(real128)c->gravity : 0};
            for (int k = 0; k < 3; k++) {
                real128 a = field[k] - lam[i] * (i > 0 ? 2 : 1) * inv_m * di[k];
                if (i + 1 < n) a += lam[i + 1] * inv_m * y[3 * (i + 1) + k];
                if (i > 0) a += lam[i - 1] * inv_m * y[3 * (i - 1) + k];
                acc[3 * i + k] = (double)a;
                scale = fmax(scale, fabs(acc[3 * i + k]));
            }
            /* the size of the terms that cancel in a steady state */
            scale = fmax(scale, (double)(lam[i] * (i > 0 ? 2 : 1) * inv_m) *
                                    sqrt(di[0] * di[0] + di[1] * di[1] + di[2] * di[2]));
        }
        for (size_t k = 0; k < 3 * n; k++) worst_a = fmax(worst_a, fabs(f[3 * n + k] - acc[k]));
        worst_a /= scale;
        print_message("N = %zu, %s: tensions %.3g, accelerations %.3g relative\n", n,
                      kind == 0 ? "hanging" : kind == 1 ? "moving 3D" : "mode 2", worst_t,
                      worst_a);
        assert_true(worst_t < 1e-13);
        assert_true(worst_a < 1e-13);
        whirl_dyn_free(d);
    }
    free(x), free(v), free(y), free(f), free(ten), free(ref), free(work);
    whirl_chain_free(c);
}

/* The steady shape of whirl_nlink_solve is a fixed point in the co-rotating frame (both
 * formulations), and its tensions are those of the force balance. */
static void test_steady_shape_fixed_point(void **state)
{
    (void)state;
    const struct {
        size_t n;
        int mode;
        double omega;
    } cases[] = {{5, 1, 1.8}, {12, 2, 3.5}, {100, 2, 3.5}};
    for (size_t k = 0; k < 3; k++) {
        const size_t n = cases[k].n;
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        whirl_shape_info info;
        assert_int_equal(whirl_nlink_solve(c, cases[k].omega, cases[k].mode, &info),
                         GSL_SUCCESS);
        double *r = malloc((n + 1) * sizeof *r), *zz = malloc((n + 1) * sizeof *zz),
               *ten = malloc((n + 1) * sizeof *ten);
        assert_int_equal(whirl_nlink_positions(c, cases[k].omega, info.tip_r, r, zz, ten),
                         GSL_SUCCESS);
        double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
        for (size_t i = 0; i < n; i++) {
            x[3 * i] = r[i + 1] - r[0];
            x[3 * i + 2] = zz[i + 1] - zz[0];
        }
        whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                         .omega = cases[k].omega};
        for (int form = 0; form <= (n <= 12); form++) {
            whirl_dyn *d = whirl_dyn_alloc(&m, (whirl_formulation)form);
            const size_t size = whirl_dyn_size(d);
            double *y = malloc(size * sizeof *y), *f = malloc(size * sizeof *f);
            double *tension = malloc(n * sizeof *tension);
            assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
            assert_int_equal(whirl_dyn_rhs(0, y, f, d), GSL_SUCCESS);
            const double acc = max_abs(f, size);
            assert_int_equal(whirl_dyn_tensions(d, 0, y, tension), GSL_SUCCESS);
            double worst = 0;
            for (size_t i = 0; i < n; i++)
                worst = fmax(worst, fabs(tension[i] - ten[i + 1]) / ten[1]);
            print_message("steady mode %d N = %zu %s: max |dy/dt| %.3g, tension error %.3g\n",
                          cases[k].mode, n, form ? "seed" : "cartesian", acc, worst);
            assert_true(acc < 1e-11 * cases[k].omega * cases[k].omega * (double)n);
            assert_true(worst < 1e-12);
            free(y), free(f), free(tension);
            whirl_dyn_free(d);
        }
        free(r), free(zz), free(ten), free(x), free(v);
        whirl_chain_free(c);
    }
}

/* dJ/dt along the flow = power of the dissipative forces: linear drag (inertial frame, fixed
 * pivot) -sum c l |v|^2, quadratic drag (co-rotating frame, against the inertial velocity),
 * internal damping (co-rotating frame) -2R with R = D/2 sum |w_i -
 * w_{i-1}|^2, w_i = d_i'/l_i. dJ/dt by Richardson-extrapolated central differences of
 * whirl_dyn_diagnose. */
static double jacobi_rate(whirl_dyn *d, double t, const double *y)
{
    const size_t size = whirl_dyn_size(d);
    double *f = malloc(size * sizeof *f), *yp = malloc(size * sizeof *yp);
    whirl_dyn_rhs(t, y, f, d);
    double rate[2];
    for (int r = 0; r < 2; r++) {
        const double h = r == 0 ? 2e-4 : 1e-4;
        whirl_dyn_diagnostics plus, minus;
        for (size_t k = 0; k < size; k++) yp[k] = y[k] + h * f[k];
        whirl_dyn_diagnose(d, t + h, yp, &plus);
        for (size_t k = 0; k < size; k++) yp[k] = y[k] - h * f[k];
        whirl_dyn_diagnose(d, t - h, yp, &minus);
        rate[r] = (plus.jacobi - minus.jacobi) / (2 * h);
    }
    free(f), free(yp);
    return (4 * rate[1] - rate[0]) / 3; /* Richardson: O(h^4) */
}

static void test_dissipation_power(void **state)
{
    (void)state;
    for (int form = 0; form <= 1; form++) {
        const size_t n = 6;
        whirl_chain *c = random_chain(n);
        double x[18], v[18], p[3] = {0, 0, 0}, y[48];
        random_state(c, 3, p, p, x, v);
        /* drag only, inertial frame, omega = 0: dE/dt = -c sum l_i |v_i|^2 */
        whirl_model m = {.chain = c, .dim = 3, .air_drag = 0.173};
        whirl_dyn *d = whirl_dyn_alloc(&m, (whirl_formulation)form);
        assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
        double expect = 0;
        for (size_t i = 0; i < n; i++)
            expect -= m.air_drag * c->length[i] *
                      (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] +
                       v[3 * i + 2] * v[3 * i + 2]);
        double got = jacobi_rate(d, 0, y);
        assert_true(fabs(got - expect) < 1e-8 * fabs(expect));
        whirl_dyn_free(d);
        /* internal damping only, co-rotating frame: dJ/dt = -2R */
        whirl_model mr = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 1.61,
                          .drive_radius = 0.05, .internal_damping = 0.0891};
        d = whirl_dyn_alloc(&mr, (whirl_formulation)form);
        double p0[3] = {mr.drive_radius, 0, 0}, z0[3] = {0, 0, 0};
        random_state(c, 3, p0, z0, x, v);
        assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
        double rayleigh = 0, wprev[3] = {0, 0, 0};
        for (size_t i = 0; i < n; i++) {
            for (int k = 0; k < 3; k++) {
                const double vr = v[3 * i + k] - (i > 0 ? v[3 * (i - 1) + k] : 0);
                const double wi = vr / c->length[i];
                rayleigh += 0.5 * mr.internal_damping * (wi - wprev[k]) * (wi - wprev[k]);
                wprev[k] = wi;
            }
        }
        got = jacobi_rate(d, 0, y);
        print_message("%s: dJ/dt %.10g, -2R %.10g\n", form ? "seed" : "cartesian", got,
                      -2 * rayleigh);
        assert_true(fabs(got + 2 * rayleigh) < 1e-8 * rayleigh);
        whirl_dyn_free(d);
        /* quadratic drag only, co-rotating frame: dJ/dt = sum F_i . v_i (co-rotating velocity)
         * with F_i = -c2 l_i |u_i| u_i, u_i = v_i + w z x x_i the inertial velocity */
        whirl_model mq = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 1.61,
                          .drive_radius = 0.05, .air_drag_quadratic = 0.139};
        d = whirl_dyn_alloc(&mq, (whirl_formulation)form);
        assert_int_equal(whirl_dyn_set_state(d, 0, x, v, y), GSL_SUCCESS);
        expect = 0;
        for (size_t i = 0; i < n; i++) {
            const double *xi = x + 3 * i, *vi = v + 3 * i;
            const double u[3] = {vi[0] - mq.omega * xi[1], vi[1] + mq.omega * xi[0], vi[2]};
            const double speed = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
            for (int k = 0; k < 3; k++)
                expect -= mq.air_drag_quadratic * c->length[i] * speed * u[k] * vi[k];
        }
        got = jacobi_rate(d, 0, y);
        assert_true(fabs(got - expect) < 1e-8 * fabs(expect));
        whirl_dyn_free(d);
        whirl_chain_free(c);
    }
}

/* Internal damping vanishes for a rigid rotation at omega about z seen from the inertial frame,
 * and the co-rotating and inertial descriptions of one motion agree. */
static void test_frames(void **state)
{
    (void)state;
    const size_t n = 5;
    whirl_chain *c = random_chain(n);
    const double w = 1.3711, t = 0.917;
    whirl_model mi = {.chain = c, .dim = 3, .omega = w, .drive_radius = 0.09},
                mr = mi;
    mr.frame = WHIRL_FRAME_ROTATING;
    whirl_dyn *di = whirl_dyn_alloc(&mi, WHIRL_FORMULATION_CARTESIAN);
    whirl_dyn *dr = whirl_dyn_alloc(&mr, WHIRL_FORMULATION_CARTESIAN);
    double p[3] = {mr.drive_radius, 0, 0}, zero[3] = {0, 0, 0};
    double xr[15], vr[15], xi[15], vi[15], x2[15], v2[15], yr[30], yi[30];
    random_state(c, 3, p, zero, xr, vr);
    assert_int_equal(whirl_dyn_set_state(dr, t, xr, vr, yr), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_get_state(dr, t, yr, WHIRL_FRAME_INERTIAL, xi, vi), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_set_state(di, t, xi, vi, yi), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_get_state(di, t, yi, WHIRL_FRAME_ROTATING, x2, v2), GSL_SUCCESS);
    for (size_t k = 0; k < 15; k++) {
        assert_true(fabs(x2[k] - xr[k]) < 1e-14);
        assert_true(fabs(v2[k] - vr[k]) < 1e-13);
    }
    whirl_dyn_diagnostics a, b;
    whirl_dyn_diagnose(dr, t, yr, &a);
    whirl_dyn_diagnose(di, t, yi, &b);
    assert_true(fabs(a.energy - b.energy) < 1e-13 && fabs(a.lz - b.lz) < 1e-13);
    assert_true(a.constraint < 1e-15 && b.constraint < 1e-15);
    /* the tensions are frame-independent */
    double ti[5], tr[5];
    whirl_dyn_tensions(di, t, yi, ti);
    whirl_dyn_tensions(dr, t, yr, tr);
    for (size_t i = 0; i < n; i++) assert_true(fabs(ti[i] - tr[i]) < 1e-12 * fabs(tr[0]));
    /* rigid rotation in the inertial frame: damping leaves the right-hand side unchanged */
    for (size_t k = 0; k < 15; k++) vr[k] = 0;
    whirl_dyn_set_state(dr, t, xr, vr, yr);
    whirl_dyn_get_state(dr, t, yr, WHIRL_FRAME_INERTIAL, xi, vi);
    whirl_model md = mi;
    md.internal_damping = 0.77;
    whirl_dyn *dd = whirl_dyn_alloc(&md, WHIRL_FORMULATION_CARTESIAN);
    double f1[30], f2[30];
    whirl_dyn_set_state(di, t, xi, vi, yi);
    whirl_dyn_rhs(t, yi, f1, di);
    whirl_dyn_rhs(t, yi, f2, dd);
    for (size_t k = 0; k < 30; k++) assert_true(fabs(f1[k] - f2[k]) < 1e-13 * (1 + fabs(f1[k])));
    whirl_dyn_free(dd);
    whirl_dyn_free(di);
    whirl_dyn_free(dr);
    whirl_chain_free(c);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(3, 0);
    whirl_model bad = {.chain = c, .dim = 2, .frame = WHIRL_FRAME_ROTATING};
    assert_null(whirl_dyn_alloc(&bad, WHIRL_FORMULATION_CARTESIAN));
    assert_non_null(strstr(whirl_last_error(), "dim = 3"));
    bad = (whirl_model){.chain = c, .dim = 4};
    assert_null(whirl_dyn_alloc(&bad, WHIRL_FORMULATION_CARTESIAN));
    bad = (whirl_model){.chain = c, .dim = 3, .air_drag = -1};
    assert_null(whirl_dyn_alloc(&bad, WHIRL_FORMULATION_SEED));
    double sigma[3] = {1, 2, 3};
    bad = (whirl_model){.chain = c, .dim = 3, .seed_sigma = sigma};
    assert_null(whirl_dyn_alloc(&bad, WHIRL_FORMULATION_CARTESIAN));
    whirl_dyn_free(NULL);

    whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *dc = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    whirl_dyn *ds = whirl_dyn_alloc(&m, WHIRL_FORMULATION_SEED);
    assert_int_equal(whirl_dyn_size(dc), 18);
    assert_int_equal(whirl_dyn_size(ds), 12);
    double x[9] = {0, 0, -1.0 / 3, 0, 0, -2.0 / 3, 0, 0, -1}, v[9] = {0}, y[18], f[18];
    /* hanging straight down: fine for the Cartesian, singular for the seed's 3D angles */
    assert_int_equal(whirl_dyn_set_state(dc, 0, x, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_rhs(0, y, f, dc), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_set_state(ds, 0, x, v, y), GSL_EINVAL);
    double ys[12] = {0.3, 0, 0.2, 0.1, 0.2, 0.3, 0, 0, 0, 0, 0, 0}; /* theta_2 = 0 */
    assert_int_equal(whirl_dyn_rhs(0, ys, f, ds), GSL_EBADFUNC);
    assert_non_null(strstr(whirl_last_error(), "link 2"));
    x[2] = -0.5; /* link 1 too long */
    assert_int_equal(whirl_dyn_set_state(dc, 0, x, v, y), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "link 1"));
    x[2] = -1.0 / 3;
    v[2] = 0.1; /* stretches link 1 */
    assert_int_equal(whirl_dyn_set_state(dc, 0, x, v, y), GSL_EINVAL);
    v[2] = 0;
    assert_int_equal(whirl_dyn_set_state(dc, 0, x, v, y), GSL_SUCCESS);
    y[4] = NAN;
    assert_int_equal(whirl_dyn_rhs(0, y, f, dc), GSL_EBADFUNC);
    whirl_dyn_diagnostics diag;
    assert_int_not_equal(whirl_dyn_diagnose(dc, 0, y, &diag), GSL_SUCCESS);
    whirl_dyn_free(dc);
    whirl_dyn_free(ds);
    /* a planar model refuses out-of-plane states and the co-rotating output frame */
    m.dim = 2;
    dc = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_int_equal(whirl_dyn_size(dc), 12);
    double xp[9] = {0.1, 0, -sqrt(1.0 / 9 - 0.01), 0, 0, 0, 0, 0, 0};
    xp[3] = xp[0], xp[5] = xp[2] - 1.0 / 3, xp[6] = xp[0], xp[8] = xp[5] - 1.0 / 3;
    assert_int_equal(whirl_dyn_set_state(dc, 0, xp, v, y), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_get_state(dc, 0, y, WHIRL_FRAME_ROTATING, x, v), GSL_EINVAL);
    xp[4] = 1e-3;
    assert_int_equal(whirl_dyn_set_state(dc, 0, xp, v, y), GSL_EINVAL);
    whirl_dyn_free(dc);
    whirl_chain_free(c);
}

/* Two threads on one chain (whirl_dyn_set_threads) compute every value as one thread does: the
 * right-hand sides are bitwise equal, 3D with every force in the co-rotating frame and 2D. */
static void test_threads(void **state)
{
    (void)state;
    const size_t n = WHIRL_DYN_THREADS_MIN_LINKS + 905;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.1);
    assert_non_null(c);
    for (int dim = 2; dim <= 3; dim++) {
        const whirl_model m = {.chain = c,
                               .dim = dim,
                               .frame = dim == 3 ? WHIRL_FRAME_ROTATING : WHIRL_FRAME_INERTIAL,
                               .omega = 3.1,
                               .drive_radius = 0.02,
                               .air_drag = 0.1,
                               .air_drag_quadratic = 0.05,
                               .internal_damping = 0.01};
        whirl_dyn *one = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        whirl_dyn *two = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
        assert_non_null(one);
        assert_non_null(two);
        assert_int_equal(whirl_dyn_set_threads(two, 2), GSL_SUCCESS);
        const size_t size = whirl_dyn_size(one);
        double *x = malloc(6 * n * sizeof *x), *y = malloc(size * sizeof *y);
        double *f1 = malloc(size * sizeof *f1), *f2 = malloc(size * sizeof *f2);
        assert_true(x && y && f1 && f2);
        double p[3] = {0.02, 0, 0};
        if (dim == 3)
            bench_smooth_state(c, p, x, x + 3 * n);
        else { /* the x-z plane: theta_i = 0.5 + 0.3 sin(0.7 i), rates 0.2 cos(i) */
            double px = p[0], pz = 0, vx = 0, vz = 0;
            for (size_t i = 0; i < n; i++) {
                const double th = 0.5 + 0.3 * sin(0.7 * (double)i), thd = 0.2 * cos((double)i);
                const double l = c->length[i];
                px += l * sin(th), pz -= l * cos(th), vx += l * thd * cos(th), vz += l * thd * sin(th);
                x[3 * i] = px, x[3 * i + 1] = 0, x[3 * i + 2] = pz;
                x[3 * n + 3 * i] = vx, x[3 * n + 3 * i + 1] = 0, x[3 * n + 3 * i + 2] = vz;
            }
        }
        assert_int_equal(whirl_dyn_set_state(one, 0, x, x + 3 * n, y), GSL_SUCCESS);
        assert_int_equal(whirl_dyn_rhs(0.3, y, f1, one), GSL_SUCCESS);
        assert_int_equal(whirl_dyn_rhs(0.3, y, f2, two), GSL_SUCCESS);
        assert_memory_equal(f1, f2, size * sizeof *f1);
        free(x);
        free(y);
        free(f1);
        free(f2);
        whirl_dyn_free(one);
        whirl_dyn_free(two);
    }
    whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    assert_int_equal(whirl_dyn_set_threads(d, 0), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "threads must be 1.."));
    assert_int_equal(whirl_dyn_set_threads(d, WHIRL_DYN_THREADS_MAX + 1), GSL_EINVAL);
    whirl_dyn_free(d);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_formulations_agree),
        cmocka_unit_test(test_link_accelerations_agree),
        cmocka_unit_test(test_analytic_limits),
        cmocka_unit_test(test_hanging_chain),
        cmocka_unit_test(test_multipliers_binary128),
        cmocka_unit_test(test_steady_shape_fixed_point),
        cmocka_unit_test(test_dissipation_power),
        cmocka_unit_test(test_frames),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
