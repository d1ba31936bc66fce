/* Long numerical stress runs of the dynamics (the quick versions are tests/unit/dynamics/test_stress.c).
 * Usage: bench_stress [DIR [CASE|all [LONG_STEPS]]] (LONG_STEPS: steps of each long run, default
 * 10^7, about 22 minutes; make bench: 2.5 10^6). Writes argv[1]/stress.csv (default out/bench; the long case also stress_long_h<h>.csv, its
 * energy error against time) and prints one line per case: the conserved quantity's drift
 * (energy in the inertial frame, the Jacobi constant E - omega L_z in the co-rotating one; no
 * forces act, so both are exact invariants), the constraint residual, and whether the stated
 * bound is met, or the failure status and its message. A case "passes" if
 * it meets its bound (on the drift at half the case's step), or its drift shrinks under step
 * halving at the method's order (truncation error, reported as such), or it stops with a failure
 * status and a message; and never leaves a non-finite number. The program exits 1 otherwise.
 *  - long: at h = 0.005, 0.0025 and 0.00125, 8 runs of 10^7 (LONG_STEPS) gauss3 steps each (5 links, 3D,
 *    inertial, the smooth state of bench_util.h, rates scaled by 1 + 1e-9 j): |dE| <= 1e-12 |E|
 *    at the smallest step (a larger one meets it or its drift shrinks as 2^5 under halving),
 *    and the growth of the energy error's systematic part (the runs' mean) and random part (their
 *    spread; Brouwer's law: t^0.5). Measured: the spread grows like t^0.48 at every step; the
 *    mean is a truncation drift (-1.9e-12 at h = 0.005, -4.2e-14 at 0.0025), none measurable at
 *    0.00125 (5e-16 against a spread of 6.2e-15); see src/dyn_cartesian.c;
 *  - N = 10^5: the hanging chain kicked sideways, 200 gauss2 steps of h = 5e-6;
 *  - omega = 30: N = 100, mode-2 steady shape turned by 1e-3, 20 periods, gauss2 h = 2e-4;
 *  - heavy tip: N = 100 with a tip mass 100, mode 1 at omega = 4 turned by 1e-3, gauss3 h = 1e-4
 *    (the top tension ~ 10^3 M g puts the fastest mode near 2 N sqrt(10^3) ~ 6000), t = 2;
 *  - folded: 20 links in a near-vertical zig-zag (each turned 1e-2 from the axis, alternately up
 *    and down), released: gauss3 h = 1e-4, t = 2;
 *  - through the vertical: N = 100 hanging, kicked along x, gauss2 h = 1e-3, t = 20 (the chain
 *    swings through the vertical over and over);
 *  - near critical: N = 100 at omega = omega_2 (1 + 1e-6), hanging with a 1e-6 kick, co-rotating,
 *    gauss2 h = 5e-3, t = 200;
 *  - tolerance at round-off: gsl-rk8pd at tol 1e-16 on the omega = 30 case, t = 1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "bench_stress"
#include "bench_util.h"

#define PI 3.14159265358979323846

typedef struct stress_case {
    const char *name;
    const char *method;
    double h, tol, t_end;
    double bound; /* on |drift of the invariant| / scale */
} stress_case;

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static double invariant(const whirl_dyn *d, double t, const double *y)
{
    whirl_dyn_diagnostics g;
    whirl_dyn_diagnose(d, t, y, &g);
    return whirl_dyn_model(d)->frame == WHIRL_FRAME_ROTATING ? g.jacobi : g.energy;
}

/* One run of the case at step h: the invariant's largest drift relative to |its value| in
 * *drift, the largest constraint residual in *constraint, the final state's finiteness in
 * *finite, steps in *steps, wall seconds in *secs; returns the status. */
static int run_at(const stress_case *sc, const whirl_model *m, const double *x, const double *v,
                  double h, double *drift, double *constraint, int *finite, unsigned long *steps,
                  double *secs, double *t_reached)
{
    whirl_dyn *d = whirl_dyn_alloc(m, WHIRL_FORMULATION_CARTESIAN);
    if (d == NULL) bench_die("dyn alloc");
    const size_t size = whirl_dyn_size(d);
    double *y = malloc(size * sizeof *y);
    whirl_integrator *it = whirl_integrator_alloc(sc->method, d);
    if (y == NULL || it == NULL) bench_die("alloc");
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die(sc->name);
    const double i0 = invariant(d, 0, y);
    double t = 0;
    *drift = *constraint = 0;
    const double t0 = bench_now();
    int status = GSL_SUCCESS;
    for (int k = 1; k <= 100 && status == GSL_SUCCESS; k++) {
        status = whirl_integrator_advance(it, &t, y, sc->t_end * k / 100, h, sc->tol);
        whirl_dyn_diagnostics g;
        whirl_dyn_diagnose(d, t, y, &g);
        *drift = fmax(*drift, fabs(invariant(d, t, y) - i0) / fabs(i0));
        *constraint = fmax(*constraint, g.constraint);
    }
    *secs = bench_now() - t0;
    *steps = whirl_integrator_get_stats(it).steps;
    *finite = all_finite(y, size);
    *t_reached = t;
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    free(y);
    return status;
}

/* Runs the case at its step h and, for fixed steps, at h/2. It meets its bound if the drift of
 * the invariant at h/2 (or at the tolerance) is below sc->bound; a larger drift that shrinks
 * under halving at least as 2^(order - 1) (order = 4 gauss2 and rk4, 6 gauss3) is reported as
 * truncation error converging at the method's order. Returns 1 if the case passes: it meets the
 * bound, converges so, or stops with a failure status and a message; never non-finite. */
static int run_case(FILE *csv, const stress_case *sc, const whirl_model *m, const double *x,
                    const double *v)
{
    double drift[2] = {NAN, NAN}, cons[2] = {0, 0}, secs[2] = {0, 0}, t_reached = 0;
    unsigned long steps[2] = {0, 0};
    int finite[2] = {1, 1}, status = GSL_SUCCESS;
    const int runs = sc->tol > 0 ? 1 : 2;
    for (int r = 0; r < runs && status == GSL_SUCCESS; r++)
        status = run_at(sc, m, x, v, sc->h / (1 << r), &drift[r], &cons[r], &finite[r],
                        &steps[r], &secs[r], &t_reached);
    const int last = runs - 1;
    const int order = strcmp(sc->method, "gauss3") == 0 ? 6 : 4;
    const double ratio = drift[0] / drift[1];
    const int meets = status == GSL_SUCCESS && drift[last] <= sc->bound;
    const int converges = status == GSL_SUCCESS && runs == 2 && !meets &&
                          ratio >= pow(2, order - 1);
    const int all_finite_ = finite[0] && finite[1];
    const int pass = all_finite_ && (meets || converges || status != GSL_SUCCESS);
    const char *verdict = !all_finite_ ? "NON-FINITE" : status != GSL_SUCCESS ? "stopped"
                          : meets ? "meets bound" : converges ? "truncation error converging"
                          : "EXCEEDS BOUND";
    fprintf(csv, "%s,%s,%g,%g,%g,%d,%.3g,%.3g,%.3g,%.3g,%lu,%.3g,%s\n", sc->name, sc->method,
            sc->h, sc->tol, t_reached, status, drift[0], drift[1], sc->bound,
            fmax(cons[0], cons[1]), steps[0] + steps[1], secs[0] + secs[1], verdict);
    fflush(csv);
    printf("  %-22s %-9s h %-7.2g t %-6.4g %8lu+%lu steps %6.1f s: drift %.2e, at h/2 %.2e "
           "(ratio %.3g; bound %.0e), constraint %.1e: %s%s%s\n",
           sc->name, sc->method, sc->h, t_reached, steps[0], steps[1], secs[0] + secs[1],
           drift[0], drift[1], ratio, sc->bound, fmax(cons[0], cons[1]), verdict,
           status != GSL_SUCCESS ? ": " : "", status != GSL_SUCCESS ? whirl_last_error() : "");
    fflush(stdout);
    return pass;
}

/* The mode-k steady shape at omega with every link turned by `turn` rad about y (in-plane);
 * velocities 0 (rigid rotation in the co-rotating frame). */
static void turned_steady(const whirl_chain *c, double omega, int mode, double turn, double *x,
                          double *v)
{
    const size_t n = c->n;
    if (bench_steady_positions(c, omega, mode, x) != GSL_SUCCESS) bench_die("steady shape");
    double prev[3] = {0, 0, 0}, pos[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        const double dx = x[3 * i] - prev[0], dz = x[3 * i + 2] - prev[2];
        prev[0] = x[3 * i], prev[2] = x[3 * i + 2];
        const double a = turn * sin(2.385 * (double)i);
        pos[0] += cos(a) * dx + sin(a) * dz;
        pos[2] += -sin(a) * dx + cos(a) * dz;
        x[3 * i] = pos[0], x[3 * i + 1] = 0, x[3 * i + 2] = pos[2];
    }
    memset(v, 0, 3 * n * sizeof *v);
}

/* Long gauss3 runs at step h: an ensemble of LONG_MEMBERS runs of `steps` steps (10^7 unless
 * the command line says otherwise) from the smooth
 * state with the rates scaled by 1 + 1e-9 j (j = 0..LONG_MEMBERS-1; the chaotic motion makes
 * their round-off independent), the signed energy error dE_j(t) at log-spaced times. The
 * ensemble splits it into a systematic part, the mean (a drift common to every run: truncation
 * error that accumulates), and a random part, the standard deviation about it (round-off: a
 * random walk, Brouwer's law t^0.5); the exponents of both are fitted over the last three
 * decades. Writes stress_long_h<h>.csv (t, mean, std, rms). */
#define LONG_MEMBERS 8
#define LONG_SAMPLES 80
typedef struct long_result {
    double h, t;
    int status, finite;
    double worst, constraint, secs; /* max |dE|/|E| over runs and samples */
    long steps;                     /* per run */
    double mean_end, mean_exponent, std_end, std_exponent;
    char message[256];              /* whirl_last_error() of a failed run */
} long_result;

/* Exponent p of |value| ~ t^p fitted over the samples from t_from on with a non-zero value. */
static double tail_exponent(const double *ts, const double *value, int n, double t_from)
{
    double lt[LONG_SAMPLES], lv[LONG_SAMPLES];
    int used = 0;
    for (int k = 0; k < n; k++)
        if (ts[k] >= t_from && value[k] != 0) lt[used] = ts[k], lv[used++] = fabs(value[k]);
    return bench_fit_exponent(lt, lv, used);
}

static long_result long_run(const char *dir, double h, long steps)
{
    const size_t n = 5;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model m = {.chain = c, .dim = 3};
    whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
    whirl_integrator *it = whirl_integrator_alloc("gauss3", d);
    if (d == NULL || it == NULL) bench_die("long run");
    const double p[3] = {0, 0, 0};
    double ts[LONG_SAMPLES], sum[LONG_SAMPLES] = {0}, sum2[LONG_SAMPLES] = {0}, t = 0;
    double worst = 0, constraint = 0;
    int ns = 0, status = GSL_SUCCESS, finite = 1;
    const double t0 = bench_now();
    for (int j = 0; j < LONG_MEMBERS && status == GSL_SUCCESS; j++) {
        double x[15], v[15], y[30];
        bench_smooth_state(c, p, x, v);
        for (int k = 0; k < 15; k++) v[k] *= 1 + 1e-9 * j;
        if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("long run");
        whirl_dyn_diagnostics g0, g;
        whirl_dyn_diagnose(d, 0, y, &g0);
        t = 0;
        int sample = 0;
        double last = 0;
        for (double target = 10; status == GSL_SUCCESS && sample < LONG_SAMPLES;
             target *= pow(10, 0.1)) {
            const long k = (long)fmin(round(target), (double)steps);
            if ((double)k * h <= t) continue;
            status = whirl_integrator_advance(it, &t, y, (double)k * h, h, 0);
            whirl_dyn_diagnose(d, t, y, &g);
            const double de = (g.energy - g0.energy) / fabs(g0.energy);
            ts[sample] = t;
            sum[sample] += de;
            sum2[sample] += de * de;
            worst = fmax(worst, fabs(de));
            last = de;
            constraint = fmax(constraint, g.constraint);
            sample++;
            if (k == steps) break;
        }
        ns = sample;
        finite &= all_finite(y, 30);
        printf("    h %g, run %d: dE/|E| %.2e at t = %g\n", h, j, last, t);
        fflush(stdout);
    }
    const double secs = bench_now() - t0;
    double mean[LONG_SAMPLES], spread[LONG_SAMPLES], rms[LONG_SAMPLES];
    for (int k = 0; k < ns; k++) {
        mean[k] = sum[k] / LONG_MEMBERS;
        rms[k] = sqrt(sum2[k] / LONG_MEMBERS);
        spread[k] = sqrt(fmax(0, sum2[k] - LONG_MEMBERS * mean[k] * mean[k]) / (LONG_MEMBERS - 1));
    }
    char name[64];
    snprintf(name, sizeof name, "stress_long_h%g.csv", h);
    FILE *series = bench_open_csv(dir, name);
    fprintf(series, "# gauss3, h = %g, 5 links: energy error dE/|E| of %d runs\n", h,
            LONG_MEMBERS);
    fprintf(series, "t,steps,mean,std,rms\n");
    for (int k = 0; k < ns; k++)
        fprintf(series, "%.6g,%.0f,%.6g,%.6g,%.6g\n", ts[k], ts[k] / h, mean[k], spread[k], rms[k]);
    fclose(series);
    const double mean_exponent = tail_exponent(ts, mean, ns, t / 1000);
    const double spread_exponent = tail_exponent(ts, spread, ns, t / 1000);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    long_result r = {.h = h,
                     .t = t,
                     .status = status,
                     .finite = finite,
                     .worst = worst,
                     .constraint = constraint,
                     .secs = secs,
                     .steps = steps,
                     .mean_end = ns > 0 ? mean[ns - 1] : NAN,
                     .mean_exponent = mean_exponent,
                     .std_end = ns > 0 ? spread[ns - 1] : NAN,
                     .std_exponent = spread_exponent};
    if (status != GSL_SUCCESS) snprintf(r.message, sizeof r.message, "%s", whirl_last_error());
    return r;
}

/* The verdicts of the long runs, from the largest step to the smallest: the smallest step must
 * meet the bound; a larger one meets it, or its drift shrinks at least as 2^(6 - 1) at the next
 * smaller step (gauss3's truncation error). */
static int long_report(FILE *csv, const long_result *r, int count)
{
    int ok = 1;
    for (int k = 0; k < count; k++) {
        const int meets = r[k].status == GSL_SUCCESS && r[k].worst <= 1e-12;
        const int converges = !meets && k + 1 < count && r[k].status == GSL_SUCCESS &&
                              r[k].worst >= 32 * r[k + 1].worst;
        const char *verdict = !r[k].finite ? "NON-FINITE" : r[k].status != GSL_SUCCESS ? "stopped"
                              : meets ? "meets bound" : converges ? "truncation error converging"
                              : "EXCEEDS BOUND";
        ok &= r[k].finite && (meets || converges || r[k].status != GSL_SUCCESS);
        fprintf(csv, "long_%ld_steps,gauss3,%g,0,%g,%d,%.3g,,1e-12,%.3g,%ld,%.3g,%s (%d runs at "
                     "the end: mean %.3g growing like t^%.2f; std %.3g growing like t^%.2f)\n",
                r[k].steps, r[k].h, r[k].t, r[k].status, r[k].worst, r[k].constraint,
                r[k].steps * LONG_MEMBERS, r[k].secs, verdict, LONG_MEMBERS, r[k].mean_end,
                r[k].mean_exponent, r[k].std_end, r[k].std_exponent);
        printf("  %-22s %-9s h %-7g t %-8.4g %d x %ld steps %6.1f s: max |dE|/|E| %.2e (bound "
               "1e-12); at the end mean %.2e (growing like t^%.2f), std %.2e (like t^%.2f; "
               "Brouwer: 0.5), constraint %.1e: %s%s%s\n",
               "long", "gauss3", r[k].h, r[k].t, LONG_MEMBERS, r[k].steps,
               r[k].secs, r[k].worst, r[k].mean_end, r[k].mean_exponent, r[k].std_end,
               r[k].std_exponent, r[k].constraint, verdict,
               r[k].status != GSL_SUCCESS ? ": " : "",
               r[k].status != GSL_SUCCESS ? r[k].message : "");
    }
    fflush(stdout);
    return ok;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    /* argv[2]: one case, or "all" (default); argv[3]: the steps of each long run (10^7) */
    const char *only = argc > 2 && strcmp(argv[2], "all") != 0 ? argv[2] : NULL;
    const long long_steps = argc > 3 ? atol(argv[3]) : 10000000;
    if (long_steps < 1000 || long_steps > 1000000000) {
        fprintf(stderr, "%s: the long runs' steps must be 1000 .. 1e9\n", BENCH_NAME);
        return 1;
    }
    FILE *csv = bench_open_csv(dir, "stress.csv");
    fprintf(csv, "case,method,h,tol,t_reached,status,drift,drift_half_step,bound,max_constraint,"
                 "steps,seconds,verdict\n");
    printf("stress runs (load average %.2f):\n", bench_load_average());
    int ok = 1;
#define WANT(name) (only == NULL || strcmp(only, name) == 0)
    if (WANT("long")) {
        long_result r[3];
        for (int k = 0; k < 3; k++) r[k] = long_run(dir, 0.005 / (1 << k), long_steps);
        ok &= long_report(csv, r, 3);
    }
    if (WANT("large")) { /* N = 10^5 hanging, kicked */
        const size_t n = 100000;
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        const whirl_model m = {.chain = c, .dim = 3};
        double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
        for (size_t i = 0; i < n; i++) x[3 * i + 2] = -(double)(i + 1) / (double)n;
        for (size_t i = n / 2; i < n; i++) v[3 * i] = 0.01 * (double)(i - n / 2) / (double)n;
        const stress_case sc = {"N=1e5 kicked", "gauss2", 5e-6, 0, 1e-3, 1e-10};
        ok &= run_case(csv, &sc, &m, x, v);
        free(x), free(v);
        whirl_chain_free(c);
    }
    const size_t n = 100;
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    if (WANT("omega30") || WANT("roundoff")) {
        const double omega = 30;
        const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
        turned_steady(c, omega, 2, 1e-3, x, v);
        const stress_case fast = {"omega=30", "gauss2", 2e-4, 0, 20 * 2 * PI / omega, 1e-10};
        const stress_case tight = {"tol=1e-16", "gsl-rk8pd", 1e-4, 1e-16, 1, 1e-10};
        if (WANT("omega30")) ok &= run_case(csv, &fast, &m, x, v);
        if (WANT("roundoff")) ok &= run_case(csv, &tight, &m, x, v);
    }
    if (WANT("heavytip")) {
        whirl_chain *ct = whirl_chain_alloc_uniform(n, 100);
        const whirl_model m = {.chain = ct, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 4};
        turned_steady(ct, 4, 1, 1e-3, x, v);
        const stress_case sc = {"tip mass 100", "gauss3", 1e-4, 0, 2, 1e-10};
        ok &= run_case(csv, &sc, &m, x, v);
        whirl_chain_free(ct);
    }
    if (WANT("folded")) {
        const size_t nf = 20;
        whirl_chain *cf = whirl_chain_alloc_uniform(nf, 0);
        const whirl_model m = {.chain = cf, .dim = 3};
        double pos[3] = {0, 0, 0};
        for (size_t i = 0; i < nf; i++) {
            const double th = (i % 2 == 0 ? 0.01 : PI - 0.01), ph = 2.385 * (double)i;
            pos[0] += cf->length[i] * sin(th) * cos(ph);
            pos[1] += cf->length[i] * sin(th) * sin(ph);
            pos[2] -= cf->length[i] * cos(th);
            x[3 * i] = pos[0], x[3 * i + 1] = pos[1], x[3 * i + 2] = pos[2];
        }
        memset(v, 0, 3 * nf * sizeof *v);
        const stress_case sc = {"folded zig-zag", "gauss3", 1e-4, 0, 2, 1e-10};
        ok &= run_case(csv, &sc, &m, x, v); /* |E| ~ the potential energy scale */
        whirl_chain_free(cf);
    }
    if (WANT("vertical")) {
        const whirl_model m = {.chain = c, .dim = 3};
        for (size_t i = 0; i < n; i++) {
            x[3 * i] = x[3 * i + 1] = 0, x[3 * i + 2] = -(double)(i + 1) / (double)n;
            v[3 * i] = 0.8 * (double)(i + 1) / (double)n, v[3 * i + 1] = v[3 * i + 2] = 0;
        }
        const stress_case sc = {"through the vertical", "gauss2", 1e-3, 0, 20, 1e-10};
        ok &= run_case(csv, &sc, &m, x, v);
    }
    if (WANT("critical")) {
        double crit[2];
        if (whirl_nlink_critical(c, 2, crit) != GSL_SUCCESS) bench_die("critical rates");
        const double omega = crit[1] * (1 + 1e-6);
        const whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
        for (size_t i = 0; i < n; i++) {
            x[3 * i] = x[3 * i + 1] = 0, x[3 * i + 2] = -(double)(i + 1) / (double)n;
            v[3 * i] = 1e-6 * sin(PI * (double)(i + 1) / (double)n), v[3 * i + 1] = v[3 * i + 2] = 0;
        }
        const stress_case sc = {"omega_2 (1 + 1e-6)", "gauss2", 5e-3, 0, 200, 1e-12};
        ok &= run_case(csv, &sc, &m, x, v);
    }
    whirl_chain_free(c);
    free(x), free(v);
    fclose(csv);
    printf("stress runs: %s\n", ok ? "every case met its bound or stopped with a message"
                                   : "A CASE FAILED (non-finite state or bound exceeded)");
    return ok ? 0 : 1;
}
