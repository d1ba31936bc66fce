/* Benchmark (study) of the internal damping of the chain (whirl_model.internal_damping): the
 * time-domain dynamics (Cartesian formulation, co-rotating frame) against the damped linear
 * analysis (whirl/stability.h). Usage: bench_damping [DIR [PARTS]], DIR the output directory
 * (default out/bench), PARTS a subset of the letters "abcd" (default "abc", about 5 minutes):
 *  a. convergence to mode 1 (damping_a.csv), N = 25, omega = 2 (only mode 1 exists) for
 *     D = 0.002 .. 0.05 and omega = 5 (modes 1-3 exist) for D = 0.01, 0.05, from the mode-1
 *     shape with every link direction turned by 0.1 rad at random ("10% away", at rest in the
 *     co-rotating frame) and, at D = 0.05, from the hanging chain (links turned by 0.01 rad, at
 *     rest in the inertial frame): the decay of the deviation from the whirl_nlink_solve mode-1
 *     shape (tests/lib/damping_run.h: single-rate and two-rate fits over 1e-4 > d > 1e-10 L) against
 *     the real parts of the damped linearisation's eigenvalues, and the final shape error (the
 *     floor). rk4 with the step of tests/lib/damping_run.h: the damping's fastest rate ~16 D N^3
 *     makes a run cost ~N^3 steps per e-fold whatever D, about 1 s per e-fold at N = 25 and
 *     15 s at N = 50, so N = 50 is part d;
 *  b. modes 2 and 3 at omega = 5 (damping_b.csv): whirl_stability_run (perturbation 1e-6, rk4
 *     with the step of part a):
 *     sim_growth against eig_growth for D = 1e-4 .. 0.05; gauss2 and N = 50 for one point each;
 *  c. the scaling with D (damping_c.csv): eig_growth / D of modes 1 (omega 2 and 5), 2 and 3
 *     (omega 5) at N = 25 and 50 for D = 1e-7 .. 0.1 (linear analysis only);
 *  d. (on demand, about 3 minutes) part a at N = 50: omega = 5, D = 0.05, from the turned mode-1
 *     shape, fitted over 1e-6 > d > 1e-8 (damping_d.csv).
 * Prints every row and, for parts a and b, the largest relative error of the measured rates. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/stability.h"

#define BENCH_NAME "bench_damping"
#include "bench_util.h"
#include "damping_run.h"

/* The steady shape of mode k at omega: tip radius, nodes r, z and tensions (N + 1 each). */
static double shape_of(const whirl_chain *c, double omega, int mode, double *r, double *z,
                       double *tension)
{
    whirl_shape_info info;
    if (whirl_nlink_solve(c, omega, mode, &info)) bench_die("whirl_nlink_solve");
    if (whirl_nlink_positions(c, omega, info.tip_r, r, z, tension)) bench_die("positions");
    return info.tip_r;
}

/* The distinct real parts of the eigenvalues of the last linearisation, descending (a complex
 * pair counted once), into re_out (*count of them), and the imaginary part (>= 0) of the first. */
static void distinct_rates(whirl_stability *w, double *re_out, size_t *count, double *freq)
{
    size_t total;
    const double *re, *im;
    if (whirl_stability_eigenvalues(w, &total, &re, &im)) bench_die("eigenvalues");
    size_t best = 0;
    for (size_t i = 1; i < total; i++)
        if (re[i] > re[best]) best = i;
    *freq = fabs(im[best]);
    *count = 0;
    for (size_t i = 0; i < total; i++)
        if (im[i] >= 0) re_out[(*count)++] = re[i];
    qsort(re_out, *count, sizeof *re_out, bench_cmp_double);
    for (size_t i = 0; i < *count / 2; i++) { /* descending */
        const double tmp = re_out[i];
        re_out[i] = re_out[*count - 1 - i];
        re_out[*count - 1 - i] = tmp;
    }
}

/* Index (0 = slowest decay) of the real part nearest to rate. */
static size_t nearest_rate(const double *re, size_t count, double rate)
{
    size_t k = 0;
    for (size_t i = 1; i < count; i++)
        if (fabs(re[i] - rate) < fabs(re[k] - rate)) k = i;
    return k;
}

/* ---- part a ---- */

typedef struct {
    size_t n;
    double omega, damping;
    int hanging;        /* start: 0 turned mode-1 shape, 1 hanging chain */
    double d_hi, d_lo;  /* the fitted stretch [L] */
    double tail_factor; /* 0: no tail (no floor measured) */
} converge_case;

#define SAMPLES_PER_BLOCK 16 /* deviation samples per period of the slowest eigenvalue */
#define TURN_MODE1 0.1       /* "10% away": every link of the mode-1 shape turned by 0.1 rad */
#define TURN_HANGING 1e-2    /* the hanging chain's links turned by 0.01 rad */

/* Growth rate of the hanging chain (escape rate from it) under the model. */
static double hanging_growth(whirl_stability *w, const whirl_model *m, double *r, double *z)
{
    const whirl_chain *c = m->chain;
    r[0] = z[0] = 0;
    for (size_t i = 1; i <= c->n; i++) {
        r[i] = 0;
        z[i] = z[i - 1] - c->length[i - 1];
    }
    double growth;
    if (whirl_stability_linearise(w, m, r, z) || whirl_stability_growth(w, &growth))
        bench_die("hanging chain");
    return growth;
}

/* One run; returns the relative error of the rate that decides the row (see part_a). */
static double part_a_row(FILE *fp, const converge_case *k)
{
    const size_t n = k->n;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    double *buf = malloc((5 * (n + 1) + 16 * n) * sizeof *buf);
    if (c == NULL || w == NULL || buf == NULL) bench_die("alloc");
    double *r = buf, *z = r + n + 1, *tension = z + n + 1, *ref = tension + n + 1;
    double *x0 = ref + 3 * n, *v0 = x0 + 3 * n, *hr = v0 + 3 * n, *hz = hr + n + 1;
    double *rates = hz + n + 1; /* 4 N */
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = k->omega;
    m.internal_damping = k->damping;
    const double escape = hanging_growth(w, &m, hr, hz);
    const double tip_r = shape_of(c, k->omega, 1, r, z, tension);
    for (size_t i = 0; i < n; i++) {
        ref[3 * i] = r[i + 1];
        ref[3 * i + 1] = 0;
        ref[3 * i + 2] = z[i + 1];
    }
    double freq, growth;
    size_t count;
    if (whirl_stability_shape(w, &m, tip_r, &growth)) bench_die("linearisation");
    distinct_rates(w, rates, &count, &freq);
    const double sigma = rates[0], sigma2 = rates[1];
    if (k->hanging) {
        if (damping_start_hanging(c, k->omega, TURN_HANGING, 1, x0, v0)) bench_die("start");
    } else if (damping_start_turned(c, r, z, TURN_MODE1, 1, x0, v0))
        bench_die("start");
    const double osc = freq > 0 ? freq : k->omega; /* the blocks: periods of the slowest mode */
    damping_run_params p = {"rk4", damping_step(&m, tension, "rk4"),
                            2 * M_PI / osc / SAMPLES_PER_BLOCK, 0, k->d_hi, k->d_lo,
                            freq > 0 ? SAMPLES_PER_BLOCK : 1, sigma, k->tail_factor};
    p.t_max = 80 / fabs(sigma) + (k->hanging ? 40 / escape : 0);
    damping_run_result res;
    const double t0 = bench_now();
    if (damping_run(&m, ref, x0, v0, &p, &res)) bench_die("run");
    const double wall = bench_now() - t0;
    const size_t rank = nearest_rate(rates, count, res.rate); /* the eigenvalue the fit shows */
    const double e_fit = res.rate / rates[rank] - 1;
    const double e_slow = res.rate_slow / sigma - 1, e_fast = res.rate_fast / sigma2 - 1;
    const char *start = k->hanging ? "hanging" : "turned";
    fprintf(fp, "%zu,%.17g,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%zu,%.17g,%.6g,%.17g,%.17g,"
                "%.6g,%.6g,%.17g,%.17g,%zu,%.6g,%.6g,%.6g,%d,%.17g,%lu,%.4g\n",
            n, k->omega, k->damping, start, escape, sigma, freq, sigma2, res.rate, rank + 1,
            rates[rank], e_fit, res.rate_slow, res.rate_fast, e_slow, e_fast, res.fit_from,
            res.fit_to,
            res.fit_samples, res.initial, res.peak, res.final_error, res.reached, res.duration,
            res.stats.steps, wall);
    printf("N %zu w %g D %-5g %-7s sigma %.6g (im %.3g) next %.6g | fit %.6g = eig #%zu %+.1e | "
           "two-rate %.6g (%+.1e) %.6g (%+.1e) [%.0f, %.0f] d0 %.2g final %.2g t %.0f %.0f s\n",
           n, k->omega, k->damping, start, sigma, freq, sigma2, res.rate, rank + 1, e_fit,
           res.rate_slow, e_slow, res.rate_fast, e_fast, res.fit_from, res.fit_to, res.initial,
           res.final_error, res.duration, wall);
    if (!res.reached) printf("  (did not reach %g within t = %g)\n", k->d_lo, p.t_max);
    fflush(stdout);
    free(buf);
    whirl_stability_free(w);
    whirl_chain_free(c);
    if (!res.reached) return INFINITY;
    /* from the turned shape the two slowest modes are both excited: the two-rate fit against
       sigma and sigma_next, unless the slowest dominates alone (the single fit shows it); from
       the hanging chain the single fit against the eigenvalue it shows */
    if (k->hanging || (rank == 0 && fabs(e_fit) < 1e-3)) return fabs(e_fit);
    return fmax(fabs(e_slow), fabs(e_fast));
}

/* The CSV header of parts a and d. */
static void part_a_header(FILE *fp)
{
    fprintf(fp, "# convergence to the mode-1 shape with internal damping D (co-rotating frame, "
                "rk4, tests/lib/damping_run.h): escape = growth rate of the hanging chain; sigma = "
                "slowest decay of the mode-1 linearisation (sigma_im its imaginary part, "
                "sigma_next the next real part); fit = slope of log deviation over [fit_from, "
                "fit_to] (deviation d_hi .. d_lo, block means), fit_eig the nearest real part of "
                "an eigenvalue (fit_rank: 1 = slowest); slow, fast = the two-rate fit; e_* "
                "relative errors (fit/fit_eig, slow/sigma, fast/sigma_next); final_error = floor "
                "of the deviation [L] (with a tail; else the deviation at the end); starts: "
                "turned = mode-1 shape, links turned by %g rad; hanging = links turned by %g "
                "rad, at rest in the inertial frame\n", TURN_MODE1, TURN_HANGING);
    fprintf(fp, "links,omega,damping,start,escape,sigma,sigma_im,sigma_next,fit,fit_rank,fit_eig,"
                "e_fit,slow,fast,e_slow,e_fast,fit_from,fit_to,blocks,initial,peak,final_error,"
                "reached,duration,steps,seconds\n");
}

static void part_a(const char *dir)
{
    FILE *fp = bench_open_csv(dir, "damping_a.csv");
    part_a_header(fp);
    const converge_case cases[] = {
        {25, 2, 0.002, 0, 1e-4, 1e-10, 1e3}, {25, 2, 0.005, 0, 1e-4, 1e-10, 1e3},
        {25, 2, 0.01, 0, 1e-4, 1e-10, 1e3},  {25, 2, 0.02, 0, 1e-4, 1e-10, 1e3},
        {25, 2, 0.05, 0, 1e-4, 1e-10, 1e3},  {25, 5, 0.01, 0, 1e-4, 1e-10, 1e3},
        {25, 5, 0.05, 0, 1e-4, 1e-10, 1e3},  {25, 2, 0.05, 1, 1e-4, 1e-10, 1e3},
        {25, 5, 0.05, 1, 1e-4, 1e-10, 1e3},
    };
    double worst = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        worst = fmax(worst, part_a_row(fp, &cases[i]));
    fclose(fp);
    printf("part a: largest relative error of the decay rate = %.3g\n", worst);
}

/* Part d: the convergence check at N = 50 (one run of part a, fit over 1e-6 > d > 1e-8: the
   turned start's fast modes take the deviation from 1e-2 to 1e-5 within t = 63). */
static void part_d(const char *dir)
{
    FILE *fp = bench_open_csv(dir, "damping_d.csv");
    part_a_header(fp);
    const converge_case k = {50, 5, 0.05, 0, 1e-6, 1e-8, 0};
    const double err = part_a_row(fp, &k);
    fclose(fp);
    printf("part d: relative error of the decay rate = %.3g\n", err);
}

/* ---- part b ---- */

static double part_b_row(FILE *fp, size_t n, int mode, double damping, const char *method)
{
    const double omega = 5;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *w = whirl_stability_alloc(n);
    if (c == NULL || w == NULL) bench_die("alloc");
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = omega;
    m.internal_damping = damping;
    double *r = malloc(3 * (n + 1) * sizeof *r);
    if (r == NULL) bench_die("alloc");
    double *z = r + n + 1, *tension = z + n + 1, eig;
    const double tip_r = shape_of(c, omega, mode, r, z, tension);
    if (whirl_stability_shape(w, &m, tip_r, &eig)) bench_die("linear analysis");
    whirl_stability_run_params p = whirl_stability_run_defaults();
    p.method = method;
    p.perturbation = 1e-6;
    /* long enough for the growth by 1e4 after the start-up (the rule of bench_stability.sh) */
    p.periods = fmax(100, (log(1e4) + 6) / eig * omega / (2 * M_PI) + 20);
    p.dt = damping_step(&m, tension, method);
    whirl_stability_run_result res;
    const double t0 = bench_now();
    if (whirl_stability_run(&m, tip_r, &p, &res)) bench_die("run");
    const double wall = bench_now() - t0, err = res.sim_growth / eig - 1;
    fprintf(fp, "%zu,%.17g,%d,%.17g,%s,%.17g,%.17g,%.6g,%.17g,%.17g,%s,%lu,%.4g\n", n, omega,
            mode, damping, method, eig, res.sim_growth, err, res.fit_from, res.fit_to,
            whirl_verdict_name(res.verdict), res.stats.steps, wall);
    printf("N %3zu omega %g mode %d D %-7g %-6s eig_growth %10.6g sim_growth %10.6g err %+.2e "
           "[%6.0f, %6.0f] %s, %lu steps %.1f s\n", n, omega, mode, damping, method, eig,
           res.sim_growth, err, res.fit_from, res.fit_to, whirl_verdict_name(res.verdict),
           res.stats.steps, wall);
    fflush(stdout);
    free(r);
    whirl_stability_free(w);
    whirl_chain_free(c);
    return res.verdict == WHIRL_VERDICT_UNSTABLE ? fabs(err) : INFINITY;
}

static void part_b(const char *dir)
{
    FILE *fp = bench_open_csv(dir, "damping_b.csv");
    fprintf(fp, "# modes 2 and 3 at omega = 5 with internal damping D: eig_growth of the damped "
                "linearisation against sim_growth of whirl_stability_run (perturbation 1e-6)\n");
    fprintf(fp, "links,omega,mode,damping,method,eig_growth,sim_growth,rel_error,fit_from,fit_to,"
                "verdict,steps,seconds\n");
    const double damping[] = {1e-4, 3e-4, 1e-3, 0.002, 0.005, 0.01, 0.02, 0.05};
    double worst = 0;
    for (int mode = 2; mode <= 3; mode++)
        for (size_t d = 0; d < sizeof damping / sizeof damping[0]; d++)
            worst = fmax(worst, part_b_row(fp, 25, mode, damping[d], "rk4"));
    worst = fmax(worst, part_b_row(fp, 25, 2, 0.01, "gauss2"));
    worst = fmax(worst, part_b_row(fp, 50, 2, 0.01, "rk4"));
    fclose(fp);
    printf("part b: largest |sim / eig - 1| = %.3g\n", worst);
}

/* ---- part c ---- */

static void part_c(const char *dir)
{
    FILE *fp = bench_open_csv(dir, "damping_c.csv");
    fprintf(fp, "# eig_growth / D of the damped linearisation (mode 1: the slowest decay, < 0)\n");
    fprintf(fp, "links,damping,mode1_omega2,mode1_omega5,mode2_omega5,mode3_omega5\n");
    const struct { double omega; int mode; } cols[] = {{2, 1}, {5, 1}, {5, 2}, {5, 3}};
    const double damping[] = {1e-7, 1e-6, 1e-5, 1e-4, 3e-4, 1e-3,
                              2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1};
    const size_t links[] = {25, 50};
    for (size_t s = 0; s < 2; s++) {
        const size_t n = links[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        whirl_stability *w = whirl_stability_alloc(n);
        if (c == NULL || w == NULL) bench_die("alloc");
        double tip[4];
        for (int j = 0; j < 4; j++) {
            whirl_shape_info info;
            if (whirl_nlink_solve(c, cols[j].omega, cols[j].mode, &info)) bench_die("shape");
            tip[j] = info.tip_r;
        }
        printf("eig_growth / D at N = %zu:\n%10s %14s %14s %14s %14s\n", n, "D", "mode 1 (w 2)",
               "mode 1 (w 5)", "mode 2 (w 5)", "mode 3 (w 5)");
        for (size_t d = 0; d < sizeof damping / sizeof damping[0]; d++) {
            fprintf(fp, "%zu,%.17g", n, damping[d]);
            printf("%10g", damping[d]);
            for (int j = 0; j < 4; j++) {
                whirl_model m = {0};
                m.chain = c;
                m.dim = 3;
                m.frame = WHIRL_FRAME_ROTATING;
                m.omega = cols[j].omega;
                m.internal_damping = damping[d];
                double growth;
                if (whirl_stability_shape(w, &m, tip[j], &growth)) bench_die("linearisation");
                fprintf(fp, ",%.17g", growth / damping[d]);
                printf(" %14.8g", growth / damping[d]);
            }
            fputc('\n', fp);
            putchar('\n');
        }
        whirl_stability_free(w);
        whirl_chain_free(c);
    }
    fclose(fp);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    const char *parts = argc > 2 ? argv[2] : "abc";
    printf("load average %.2f\n", bench_load_average());
    if (strchr(parts, 'c')) part_c(dir);
    if (strchr(parts, 'b')) part_b(dir);
    if (strchr(parts, 'a')) part_a(dir);
    if (strchr(parts, 'd')) part_d(dir);
    return 0;
}
