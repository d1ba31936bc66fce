/* Scaling of the dynamics in the number of links N. Usage: bench_scaling [DIR [PART]]. Writes CSV
 * under DIR (default out/bench) and prints the figures of every part, or of PART only:
 *  - cost: against N = 10 .. 10^6 (3D, Cartesian formulation, the smooth state of bench_util.h):
 *    ns per right-hand side (plain inertial model; co-rotating with every force; the seed
 *    formulation up to N = 100), per step of rk4, gauss2, gauss3 and rk8 (all at the fixed step
 *    h = 0.05 / N, below the fixed-point bound of the Gauss methods; rk8 with tolerance 0 takes
 *    fixed steps), medians of 7 repeats (wall clock; the right-hand side also in processor
 *    time of the thread, less sensitive to other jobs on shared cores); the exponent p of
 *    time ~ N^p fitted by least squares of log time on log N over 10 .. 10^6 and over
 *    10^3 .. 10^6 (scaling.csv);
 *  - memory: the peak (getrusage ru_maxrss of a forked child that allocates the chain, the
 *    dynamics, a gauss2 integrator and the state, and takes one step) at N = 10^5 and 10^6,
 *    less that of a child that only starts (scaling_memory.csv);
 *  - tension: round-off of the tensions against N = 10 .. 10^6 (scaling_tension.csv): relative
 *    error max_i |T_i / T_i,ref - 1| of whirl_dyn_tensions for (a) the hanging chain,
 *    T_i,ref = the exact weight below link i, (b) the smooth moving 3D state and (c) the mode-2
 *    steady shape at omega = 4 in the co-rotating frame, T_ref from the same tridiagonal system
 *    re-solved in binary128 (__float128, coefficients formed from the same double link vectors);
 *    and, for comparison, plain double Thomas elimination of the same system from the top. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "bench_scaling"
#include "bench_util.h"
#include "tension_ref.h"

#define REPEATS 7


/* The start of every timing: the smooth state (pivot at the origin) in the model's frame. */
static whirl_dyn *smooth_dyn(const whirl_model *m, whirl_formulation f, double **y)
{
    const size_t n = m->chain->n;
    whirl_dyn *d = whirl_dyn_alloc(m, f);
    double *x = malloc(3 * n * sizeof *x), *v = malloc(3 * n * sizeof *v);
    *y = d != NULL ? malloc(whirl_dyn_size(d) * sizeof **y) : NULL;
    if (d == NULL || x == NULL || v == NULL || *y == NULL) bench_die("alloc");
    const double p[3] = {m->frame == WHIRL_FRAME_ROTATING ? m->drive_radius : 0, 0, 0};
    bench_smooth_state(m->chain, p, x, v);
    if (whirl_dyn_set_state(d, 0, x, v, *y) != GSL_SUCCESS) bench_die("set_state");
    free(x);
    free(v);
    return d;
}

/* Median wall ns per right-hand side of the model in formulation f at the smooth state; *cpu
 * receives the median processor ns of the thread. */
static double rhs_ns(const whirl_model *m, whirl_formulation f, double *cpu)
{
    const size_t n = m->chain->n;
    double *y;
    whirl_dyn *d = smooth_dyn(m, f, &y);
    double *dy = malloc(whirl_dyn_size(d) * sizeof *dy);
    if (dy == NULL) bench_die("alloc");
    const double work = f == WHIRL_FORMULATION_SEED ? (double)n * n * n : (double)n;
    const long reps = (long)fmax(3, 2e6 / work);
    double t[REPEATS], c[REPEATS];
    whirl_dyn_rhs(0, y, dy, d); /* warm-up */
    for (int r = 0; r < REPEATS; r++) {
        const double t0 = bench_now(), c0 = bench_cpu_now();
        for (long k = 0; k < reps; k++) whirl_dyn_rhs(1e-9 * (double)k, y, dy, d);
        c[r] = (bench_cpu_now() - c0) / (double)reps * 1e9;
        t[r] = (bench_now() - t0) / (double)reps * 1e9;
    }
    free(y);
    free(dy);
    whirl_dyn_free(d);
    *cpu = bench_median(c, REPEATS);
    return bench_median(t, REPEATS);
}

/* Median ns per step of the method with fixed step h from the smooth state; *sweeps receives
 * the stage sweeps per step (0 for explicit methods). */
static double step_ns(const whirl_model *m, const char *method, double h, double *sweeps)
{
    const size_t n = m->chain->n;
    double *y;
    whirl_dyn *d = smooth_dyn(m, WHIRL_FORMULATION_CARTESIAN, &y);
    whirl_integrator *it = whirl_integrator_alloc(method, d);
    if (it == NULL) bench_die("integrator");
    const long steps = (long)fmax(2, 3e5 / (double)n);
    double t = 0, times[REPEATS];
    if (whirl_integrator_advance(it, &t, y, h, h, 0) != GSL_SUCCESS) bench_die("warm-up step");
    for (int r = 0; r < REPEATS; r++) {
        const double t0 = bench_now();
        if (whirl_integrator_advance(it, &t, y, t + (double)steps * h, h, 0) != GSL_SUCCESS)
            bench_die("steps");
        times[r] = (bench_now() - t0) / (double)steps * 1e9;
    }
    const whirl_integrator_stats s = whirl_integrator_get_stats(it);
    *sweeps = (double)s.iterations / (double)s.steps;
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    free(y);
    return bench_median(times, REPEATS);
}

static void bench_cost(const char *dir)
{
    enum { n_sizes = 11, n_big = 6 }; /* the last n_big sizes: N = 10^3 .. 10^6 */
    const size_t sizes[n_sizes] = {10,    30,    100,    300,    1000,   3000,
                                   10000, 30000, 100000, 300000, 1000000};
    double nn[n_sizes], c_plain[n_sizes], c_full[n_sizes];
    /* per step of each method, at the fixed step h = 0.05 / N */
    enum { n_methods = 4 };
    const char *methods[n_methods] = {"rk4", "gauss2", "gauss3", "rk8"};
    double c_step[n_methods][n_sizes];
    FILE *fp = bench_open_csv(dir, "scaling.csv");
    fprintf(fp, "# 3D, Cartesian, smooth state; ns, median of %d repeats; load average %.2f\n",
            REPEATS, bench_load_average());
    fprintf(fp, "n,rhs_plain_ns,rhs_all_forces_ns,rhs_seed_ns,rk4_step_ns,gauss2_step_ns,"
                "gauss2_sweeps_per_step,rhs_plain_ns_per_link,rhs_plain_cpu_ns_per_link,"
                "gauss3_step_ns,gauss3_sweeps_per_step,rk8_step_ns\n");
    printf("cost against N (3D; wall ns; plain = inertial, no forces; all = co-rotating, drive, "
           "drag, damping; cpu/link: processor ns per link of the plain rhs; steps at h = 0.05 / "
           "N, sweeps: stage sweeps per gauss2 / gauss3 step):\n"
           "  %7s %11s %7s %8s %11s %11s %11s %11s %11s %11s %9s\n", "N", "rhs plain", "/link",
           "cpu/link", "rhs all", "rhs seed", "rk4 step", "gauss2 step", "gauss3 step",
           "rk8 step", "sweeps");
    for (int s = 0; s < n_sizes; s++) {
        const size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        if (c == NULL) bench_die("chain");
        const whirl_model plain = {.chain = c, .dim = 3};
        const whirl_model full = {.chain = c,
                                  .dim = 3,
                                  .frame = WHIRL_FRAME_ROTATING,
                                  .omega = 3.5,
                                  .drive_radius = 0.02,
                                  .air_drag = 0.1,
                                  .air_drag_quadratic = 0.05,
                                  .internal_damping = 0.01};
        double sweeps[n_methods], unused, cpu_plain;
        nn[s] = (double)n;
        c_plain[s] = rhs_ns(&plain, WHIRL_FORMULATION_CARTESIAN, &cpu_plain);
        c_full[s] = rhs_ns(&full, WHIRL_FORMULATION_CARTESIAN, &unused);
        const double c_seed = n <= 100 ? rhs_ns(&plain, WHIRL_FORMULATION_SEED, &unused) : NAN;
        for (int k = 0; k < n_methods; k++)
            c_step[k][s] = step_ns(&plain, methods[k], 0.05 / (double)n, &sweeps[k]);
        char seed_text[32] = ""; /* the seed formulation only up to N = 100: else empty */
        if (n <= 100) snprintf(seed_text, sizeof seed_text, "%.6g", c_seed);
        fprintf(fp, "%zu,%.6g,%.6g,%s,%.6g,%.6g,%.4g,%.6g,%.6g,%.6g,%.4g,%.6g\n", n, c_plain[s],
                c_full[s], seed_text, c_step[0][s], c_step[1][s], sweeps[1],
                c_plain[s] / (double)n, cpu_plain / (double)n, c_step[2][s], sweeps[2],
                c_step[3][s]);
        printf("  %7zu %11.0f %7.1f %8.1f %11.0f %11.0f %11.0f %11.0f %11.0f %11.0f %4.1f/%4.1f\n",
               n, c_plain[s], c_plain[s] / (double)n, cpu_plain / (double)n, c_full[s], c_seed,
               c_step[0][s], c_step[1][s], c_step[2][s], c_step[3][s], sweeps[1], sweeps[2]);
        fflush(stdout);
        whirl_chain_free(c);
    }
    const int from = n_sizes - n_big;
    for (int range = 0; range < 2; range++) {
        const int i0 = range == 0 ? 0 : from, cnt = n_sizes - i0;
        const char *label = range == 0 ? "10 .. 1e6" : "1e3 .. 1e6";
        fprintf(fp, "# fitted exponents over N = %s: rhs %.4f, all forces %.4f", label,
                bench_fit_exponent(nn + i0, c_plain + i0, cnt),
                bench_fit_exponent(nn + i0, c_full + i0, cnt));
        printf("  time ~ N^p fitted over N = %s: rhs p = %.3f, rhs all forces p = %.3f", label,
               bench_fit_exponent(nn + i0, c_plain + i0, cnt),
               bench_fit_exponent(nn + i0, c_full + i0, cnt));
        for (int k = 0; k < n_methods; k++) {
            const double p = bench_fit_exponent(nn + i0, c_step[k] + i0, cnt);
            fprintf(fp, ", %s step %.4f", methods[k], p);
            printf(", %s step p = %.3f", methods[k], p);
        }
        fprintf(fp, "\n");
        printf("\n");
    }
    fclose(fp);
}

/* Peak resident memory [KiB] of a child that allocates a gauss2 run of n links and takes one
 * step (n = 0: starts only); -1 on failure. */
static long child_peak_kib(size_t n)
{
    int fd[2];
    if (pipe(fd) != 0) return -1;
    const pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        close(fd[0]);
        int ok = 1;
        if (n > 0) {
            whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
            const whirl_model m = {.chain = c, .dim = 3};
            double *y;
            whirl_dyn *d = smooth_dyn(&m, WHIRL_FORMULATION_CARTESIAN, &y);
            whirl_integrator *it = whirl_integrator_alloc("gauss2", d);
            double t = 0;
            const double h = 0.05 / (double)n;
            ok = it != NULL && whirl_integrator_advance(it, &t, y, h, h, 0) == GSL_SUCCESS;
            whirl_integrator_free(it);
            whirl_dyn_free(d);
            whirl_chain_free(c);
            free(y);
        }
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        long kib = ok ? ru.ru_maxrss : -1;
        _exit(write(fd[1], &kib, sizeof kib) == (ssize_t)sizeof kib ? 0 : 1);
    }
    close(fd[1]);
    long kib = -1;
    if (read(fd[0], &kib, sizeof kib) != (ssize_t)sizeof kib) kib = -1;
    close(fd[0]);
    int status;
    waitpid(pid, &status, 0);
    return kib;
}

static void bench_memory(const char *dir)
{
    const long base = child_peak_kib(0);
    FILE *fp = bench_open_csv(dir, "scaling_memory.csv");
    fprintf(fp, "# peak resident memory of a gauss2 run (chain, dynamics, integrator, state, one "
                "step), less a child that only starts (%ld KiB)\n", base);
    fprintf(fp, "n,peak_kib,bytes_per_link\n");
    printf("peak memory (gauss2 run, less %ld KiB of a bare child):\n", base);
    const size_t sizes[] = {100000, 1000000};
    for (int s = 0; s < 2; s++) {
        const long kib = child_peak_kib(sizes[s]);
        const double per_link = (double)(kib - base) * 1024.0 / (double)sizes[s];
        fprintf(fp, "%zu,%ld,%.1f\n", sizes[s], kib - base, per_link);
        printf("  N = %7zu: %8.1f MiB, %.0f bytes per link\n", sizes[s],
               (double)(kib - base) / 1024.0, per_link);
    }
    fclose(fp);
}


static double rel_error(size_t n, const double *t, const double *ref)
{
    double worst = 0;
    for (size_t i = 0; i < n; i++) worst = fmax(worst, fabs(t[i] / ref[i] - 1));
    return worst;
}

/* Returns 0, or 1 if a state could not be formed (the row then says so and the others go on). */
static int bench_tension(const char *dir)
{
    int failed = 0;
    FILE *fp = bench_open_csv(dir, "scaling_tension.csv");
    fprintf(fp, "# relative tension error max_i |T_i / T_ref,i - 1|\n");
    fprintf(fp, "n,hanging,hanging_plain,smooth,smooth_plain,mode2,mode2_plain\n");
    printf("tension round-off, max_i |T_i / T_ref,i - 1| (whirl / plain double Thomas from the "
           "top):\n  %8s %22s %22s %22s\n", "N", "hanging (exact)", "smooth 3D (binary128)",
           "mode 2, omega 4");
    const size_t sizes[] = {10, 100, 1000, 10000, 100000, 1000000};
    for (int s = 0; s < 6; s++) {
        const size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
        double *y = malloc(6 * n * sizeof *y), *ten = malloc(n * sizeof *ten);
        double *ref = malloc(n * sizeof *ref), *plain = malloc(n * sizeof *plain);
        real128 *work = malloc(3 * n * sizeof *work);
        double *dwork = malloc(3 * n * sizeof *dwork);
        if (!c || !x || !v || !y || !ten || !ref || !plain || !work || !dwork) bench_die("alloc");
        printf("  %8zu", n);
        fprintf(fp, "%zu", n);
        for (int state = 0; state < 3; state++) {
            const double w = state == 2 ? 4.0 : 0.0;
            const whirl_model m = {.chain = c,
                                   .dim = 3,
                                   .frame = state == 2 ? WHIRL_FRAME_ROTATING : WHIRL_FRAME_INERTIAL,
                                   .omega = w};
            memset(v, 0, 3 * n * sizeof *v);
            if (state == 0) {
                for (size_t i = 0; i < n; i++) x[3 * i + 2] = -(double)(i + 1) / (double)n;
            } else if (state == 1) {
                const double p[3] = {0, 0, 0};
                bench_smooth_state(c, p, x, v);
            } else if (bench_steady_positions(c, w, 2, x) != GSL_SUCCESS) {
                /* no shape, no reference: say so in the row and go on with the other sizes */
                fprintf(stderr, "%s: N = %zu: mode-2 shape: %s\n", BENCH_NAME, n,
                        whirl_last_error());
                fprintf(fp, ",,");
                printf("   %21s", "failed (shape)");
                failed = 1;
                continue;
            }
            whirl_dyn *d = whirl_dyn_alloc(&m, WHIRL_FORMULATION_CARTESIAN);
            if (d == NULL || whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS)
                bench_die("tension state");
            if (whirl_dyn_tensions(d, 0, y, ten) != GSL_SUCCESS) bench_die("tensions");
            if (state == 0) /* the weight below link i, (n - i) m g, rounded once */
                for (size_t i = 0; i < n; i++)
                    ref[i] = (double)((long double)(n - i) * c->mass[0] * c->gravity);
            else
                tensions_quad(c, w, y, ref, work);
            tensions_double(c, w, y, plain, dwork);
            const double e_whirl = rel_error(n, ten, ref), e_plain = rel_error(n, plain, ref);
            fprintf(fp, ",%.6g,%.6g", e_whirl, e_plain);
            printf("   %9.2e / %9.2e", e_whirl, e_plain);
            whirl_dyn_free(d);
        }
        printf("\n");
        fprintf(fp, "\n");
        fflush(stdout);
        whirl_chain_free(c);
        free(x), free(v), free(y), free(ten), free(ref), free(plain), free(work), free(dwork);
    }
    fclose(fp);
    return failed;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    const char *only = argc > 2 ? argv[2] : NULL; /* one part: tension, memory or cost */
    if (only != NULL && strcmp(only, "tension") != 0 && strcmp(only, "memory") != 0 &&
        strcmp(only, "cost") != 0) {
        fprintf(stderr, "bench_scaling: unknown part '%s' (tension, memory, cost)\n", only);
        return 1;
    }
    printf("load average at start (other jobs share the cores): %.2f\n", bench_load_average());
    int status = 0;
    if (only == NULL || strcmp(only, "tension") == 0) status = bench_tension(dir);
    if (only == NULL || strcmp(only, "memory") == 0) bench_memory(dir);
    if (only == NULL || strcmp(only, "cost") == 0) bench_cost(dir);
    return status;
}
