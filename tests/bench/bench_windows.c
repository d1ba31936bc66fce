/* Benchmark and study of the exact stability windows (whirl/stability.h,
 * src/stability/nlink_windows.c).
 * Writes under argv[1] (default out/bench):
 *  - windows_cost.csv: the cost of one eigen-solve at N = 25..400 (mode 3 at omega 7.2, inside a
 *    window; median of repeats after a warm-up, one thread): the first-order form of size 4N with
 *    LAPACK's dgeev (whirl_stability_growth, the plain way), the reduced problem in lambda^2 of
 *    size 2N, eigenvalues only and with eigenvectors (whirl_windows_spectrum), and the two
 *    eigenvalues nearest a shift by shift-and-invert Arnoldi (whirl_windows_pair);
 *  - windows_N<N>.csv: the windows of modes 2 and 3 over omega 1..10 at N = 25, 50, 100, 200,
 *    400, with the wall time and the eigen-solves of each search;
 *  - windows_continuum.csv: every window edge against N, the observed order of convergence in
 *    1/N from the three finest chains, and the continuum value by Richardson extrapolation
 *    (two levels: e_N = e + a/N + b/N^2 + ...) with an error estimate (error_from "coarser":
 *    the same extrapolation from the three coarser chains; "first_order", for an edge with
 *    only three chains: the difference from the first-order extrapolation of the two finest);
 *  - windows_scan.csv: the N = 100 windows again with scan steps 0.125 and 0.5 (the edges must
 *    not depend on the scan).
 * Argument 2 (optional): the largest N (default 400); argument 3: the parts to run, "windows"
 * (2 and 3), "cost" (4), "scan" (5), "follow" or "all" (default: the windows by search up to
 * N = 200 and by following to the largest N, cost, scan).
 * "follow" reads windows_N<N>.csv of the chains below the largest N from an earlier run and finds
 * the largest chain's edges by following each edge's colliding pair: Brent's method on the
 * pair's discriminant from shift-and-invert Arnoldi alone, bracketed around the edge
 * extrapolated from the two finest chains (windows_N<N>_followed.csv; each edge then checked by
 * full solves 1e-7 on either side); then part 3 on all chains. It finds the windows that exist
 * at the smaller N, not new ones. The scan step is 0.25 up to N = 100 and
 * 0.5 above (windows_scan.csv shows that the edges do not depend on it). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_roots.h>

#include "whirl/stability.h"

#define BENCH_NAME "bench_windows"
#include "bench_util.h"

#define NLEVELS 5
#define WMAX 32

static const size_t levels[NLEVELS] = {25, 50, 100, 200, 400};

typedef struct result {
    whirl_window win[WMAX];
    size_t count;
    whirl_windows_stats stats;
    double seconds;
} result;

static void find(size_t n, int mode, double step, result *r)
{
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_windows *w = whirl_windows_alloc(n);
    if (c == NULL || w == NULL) bench_die("alloc");
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 1;
    p.omega_max = 10;
    p.scan_step = step;
    const double t0 = bench_now();
    if (whirl_windows_find(w, c, mode, &p, r->win, WMAX, &r->count, &r->stats))
        bench_die("windows");
    r->seconds = bench_now() - t0;
    whirl_windows_free(w);
    whirl_chain_free(c);
}

static size_t solves(const whirl_windows_stats *s)
{
    return s->solves_vectors + s->solves_values + s->solves_krylov;
}

/* The cost of one eigen-solve of each kind at N links. */
static void cost(FILE *fp, size_t n)
{
    enum { KINDS = 4 };
    const int repeats = n >= 400 ? 1 : n >= 200 ? 3 : 9;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_stability *lin = whirl_stability_alloc(n);
    whirl_windows *w = whirl_windows_alloc(n);
    if (c == NULL || lin == NULL || w == NULL) bench_die("alloc");
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = 7.2;
    whirl_shape_info info;
    double g4, t[KINDS][9];
    if (whirl_stability_mode(lin, &m, 3, &info, &g4)) bench_die("shape");
    whirl_spectrum sp;
    if (whirl_windows_spectrum(w, lin, 0, &sp)) bench_die("spectrum");
    /* the shift: the real part of the fastest-growing pair */
    double sigma = 0, best = -1;
    for (size_t i = 0; i < sp.count; i++)
        if (sp.im[i] > 0 && sp.im[i] > best) best = sp.im[i], sigma = sp.re[i];
    double pre[2], pim[2];
    for (int r = n >= 200 ? 0 : -1; r < repeats; r++) { /* r = -1: warm-up */
        double t0 = bench_now(), g;
        if (whirl_stability_growth(lin, &g)) bench_die("dgeev");
        double t1 = bench_now();
        if (whirl_windows_spectrum(w, lin, 0, &sp)) bench_die("spectrum");
        double t2 = bench_now();
        if (whirl_windows_spectrum(w, lin, 1, &sp)) bench_die("spectrum with vectors");
        double t3 = bench_now();
        if (whirl_windows_pair(w, lin, sigma, pre, pim)) bench_die("pair");
        double t4 = bench_now();
        if (r < 0) continue;
        t[0][r] = t1 - t0, t[1][r] = t2 - t1, t[2][r] = t3 - t2, t[3][r] = t4 - t3;
        if (fabs(g - sp.growth) > 1e-8 * (1 + g)) bench_die("growth differs");
    }
    double med[KINDS];
    for (int k = 0; k < KINDS; k++) med[k] = bench_median(t[k], repeats);
    printf("N = %3zu: dgeev 4N %.4g s, reduced 2N %.4g s (x%.1f), with vectors %.4g s (x%.1f), "
           "Arnoldi pair %.4g s (x%.1f); growth %.6g\n", n, med[0], med[1], med[0] / med[1],
           med[2], med[0] / med[2], med[3], med[0] / med[3], sp.growth);
    fprintf(fp, "%zu,%.6g,%.6g,%.6g,%.6g,%d\n", n, med[0], med[1], med[2], med[3], repeats);
    fflush(fp);
    whirl_windows_free(w);
    whirl_stability_free(lin);
    whirl_chain_free(c);
}

static void write_windows(const char *dir, size_t n, const result *r2, const result *r3)
{
    char name[64];
    snprintf(name, sizeof name, "windows_N%zu.csv", n);
    FILE *fp = bench_open_csv(dir, name);
    fprintf(fp, "# windows of modes 2 and 3, omega 1..10, N = %zu; mode 2 %.3f s %zu solves, "
                "mode 3 %.3f s %zu solves\n", n, r2->seconds, solves(&r2->stats), r3->seconds,
            solves(&r3->stats));
    fprintf(fp, "mode,links,from,to,open_from,open_to,freq_from,freq_to,max_growth,at\n");
    for (int k = 0; k < 2; k++) {
        const result *r = k ? r3 : r2;
        for (size_t i = 0; i < r->count; i++) {
            const whirl_window *x = &r->win[i];
            fprintf(fp, "%d,%zu,%.17g,%.17g,%d,%d,%.17g,%.17g,%.17g,%.17g\n", k + 2, n, x->from,
                    x->to, x->open_from, x->open_to, x->freq_from, x->freq_to, x->max_growth,
                    x->at);
        }
    }
    fclose(fp);
}

/* Richardson, two levels, from e(N), e(2N), e(4N): e_N = e + a/N + b/N^2. */
static double richardson(double e1, double e2, double e4)
{
    const double r1 = 2 * e2 - e1, r2 = 2 * e4 - e2;
    return (4 * r2 - r1) / 3;
}

typedef struct follow_args {
    const whirl_chain *c;
    whirl_stability *lin;
    whirl_windows *w;
    double *r, *z, *tension;
    int mode;
    double sigma; /* the pair's mean mu [1/T^2] */
    int evals, status;
} follow_args;

/* The discriminant of the two mu nearest sigma at omega (Arnoldi); sigma follows the pair. */
static double follow_d(double omega, void *data)
{
    follow_args *a = data;
    whirl_model m = {0};
    m.chain = a->c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = omega;
    whirl_shape_info info;
    double re[2], im[2];
    a->evals++;
    if (!a->status) a->status = whirl_nlink_solve(a->c, omega, a->mode, &info);
    if (!a->status)
        a->status = whirl_nlink_positions(a->c, omega, info.tip_r, a->r, a->z, a->tension);
    if (!a->status) a->status = whirl_stability_linearise(a->lin, &m, a->r, a->z);
    if (!a->status) a->status = whirl_windows_pair(a->w, a->lin, a->sigma, re, im);
    if (a->status) return NAN;
    if (im[0] != 0) {
        a->sigma = re[0];
        return -4 * im[0] * im[0];
    }
    a->sigma = (re[0] + re[1]) / 2;
    const double dr = re[0] - re[1], di = im[0] - im[1];
    return dr * dr - di * di;
}

/* The full growth at omega (values only). */
static double full_growth(follow_args *a, double omega)
{
    whirl_model m = {0};
    m.chain = a->c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = omega;
    whirl_shape_info info;
    whirl_spectrum sp;
    if (whirl_nlink_solve(a->c, omega, a->mode, &info) ||
        whirl_nlink_positions(a->c, omega, info.tip_r, a->r, a->z, a->tension) ||
        whirl_stability_linearise(a->lin, &m, a->r, a->z) ||
        whirl_windows_spectrum(a->w, a->lin, 0, &sp))
        bench_die("full solve");
    return sp.growth;
}

/* Edge of the largest chain n from the edges e1 (n / 4), e2 (n / 2) and the collision
 * frequencies f1, f2 there: Brent on the pair's discriminant. NAN if not bracketed. */
static double follow_edge(follow_args *a, double e1, double e2, double f1, double f2,
                          double *freq)
{
    const double pred = e2 + (e2 - e1) / 2, fpred = f2 + (f2 - f1) / 2;
    double half = fmax(fabs(e2 - e1), 1e-3);
    for (int widen = 0; widen < 4; widen++, half *= 2) {
        a->sigma = -fpred * fpred;
        gsl_function fn = {follow_d, a};
        gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
        int status = gsl_root_fsolver_set(s, &fn, pred - half, pred + half);
        if (a->status) bench_die("follow");
        for (int it = 0; it < 100 && status == GSL_SUCCESS; it++) {
            status = gsl_root_fsolver_iterate(s);
            if (a->status) bench_die("follow");
            if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s),
                                       1e-9, 0) == GSL_SUCCESS)
                break;
        }
        const double root = gsl_root_fsolver_root(s);
        gsl_root_fsolver_free(s);
        if (status == GSL_SUCCESS) {
            *freq = sqrt(fmax(0, -a->sigma));
            return root;
        }
    }
    return NAN;
}

/* Reads windows_N<n>.csv into r[0..1] (modes 2, 3). */
static void read_windows(const char *dir, size_t n, result *r)
{
    char path[512], line[1024];
    snprintf(path, sizeof path, "%s/windows_N%zu.csv", dir, n);
    FILE *fp = fopen(path, "r");
    if (fp == NULL) {
        fprintf(stderr, "bench_windows: no %s (run the windows part first)\n", path);
        exit(1);
    }
    r[0].count = r[1].count = 0;
    while (fgets(line, sizeof line, fp)) {
        whirl_window x = {0};
        int mode;
        size_t links;
        if (sscanf(line, "%d,%zu,%lf,%lf,%d,%d,%lf,%lf,%lf,%lf", &mode, &links, &x.from, &x.to,
                   &x.open_from, &x.open_to, &x.freq_from, &x.freq_to, &x.max_growth,
                   &x.at) != 10 || mode < 2 || mode > 3)
            continue;
        result *t = &r[mode - 2];
        if (t->count < WMAX) t->win[t->count++] = x;
    }
    fclose(fp);
}

/* The largest chain's windows by following the edges of the two below it into res[nl - 1]. */
static void follow(const char *dir, int nl, result res[][2])
{
    const size_t n = levels[nl - 1];
    for (int l = 0; l + 1 < nl; l++) read_windows(dir, levels[l], res[l]);
    follow_args a = {0};
    a.c = whirl_chain_alloc_uniform(n, 0);
    a.lin = whirl_stability_alloc(n);
    a.w = whirl_windows_alloc(n);
    a.r = malloc((n + 1) * sizeof(double));
    a.z = malloc((n + 1) * sizeof(double));
    a.tension = malloc((n + 1) * sizeof(double));
    if (!a.c || !a.lin || !a.w || !a.r || !a.z || !a.tension) bench_die("alloc");
    char name[64];
    snprintf(name, sizeof name, "windows_N%zu_followed.csv", n);
    FILE *fp = bench_open_csv(dir, name);
    fprintf(fp, "mode,links,from,to,open_from,open_to,freq_from,freq_to,evaluations,seconds,"
                "growth_outside_from,growth_inside_from,growth_inside_to,growth_outside_to\n");
    for (int k = 0; k < 2; k++) {
        a.mode = k + 2;
        const result *p1 = &res[nl - 3][k], *p2 = &res[nl - 2][k];
        result *out = &res[nl - 1][k];
        out->count = 0;
        for (size_t i = 0; i < p2->count; i++) {
            const whirl_window *x2 = &p2->win[i], *x1 = NULL;
            for (size_t j = 0; j < p1->count; j++)
                if (p1->win[j].from < x2->to && p1->win[j].to > x2->from) x1 = &p1->win[j];
            if (x1 == NULL) continue;
            whirl_window y = *x2;
            y.max_growth = y.at = NAN;
            a.evals = 0;
            const double t0 = bench_now();
            if (!x2->open_from) y.from = follow_edge(&a, x1->from, x2->from, x1->freq_from,
                                                      x2->freq_from, &y.freq_from);
            if (!x2->open_to) y.to = follow_edge(&a, x1->to, x2->to, x1->freq_to, x2->freq_to,
                                                  &y.freq_to);
            const double secs = bench_now() - t0;
            if (isnan(y.from) || isnan(y.to)) {
                printf("  N = %zu mode %d window %zu: an edge was not bracketed\n", n, k + 2, i + 1);
                continue;
            }
            printf("  N = %zu mode %d: [%.10f, %.10f] (%d Arnoldi evaluations, %.1f s)\n", n,
                   k + 2, y.from, y.to, a.evals, secs);
            /* full solves 1e-7 outside and inside each closed edge */
            double g[4] = {NAN, NAN, NAN, NAN};
            if (!y.open_from) g[0] = full_growth(&a, y.from - 1e-7), g[1] = full_growth(&a, y.from + 1e-7);
            if (!y.open_to) g[2] = full_growth(&a, y.to - 1e-7), g[3] = full_growth(&a, y.to + 1e-7);
            printf("    full growth at the edges -+1e-7: %.3g %.3g | %.3g %.3g\n", g[0], g[1],
                   g[2], g[3]);
            fprintf(fp, "%d,%zu,%.17g,%.17g,%d,%d,%.17g,%.17g,%d,%.3f,%.3g,%.3g,%.3g,%.3g\n",
                    k + 2, n, y.from, y.to, y.open_from, y.open_to, y.freq_from, y.freq_to,
                    a.evals, secs, g[0], g[1], g[2], g[3]);
            fflush(fp);
            out->win[out->count++] = y;
        }
    }
    fclose(fp);
    free(a.r), free(a.z), free(a.tension);
    whirl_windows_free(a.w);
    whirl_stability_free(a.lin);
    whirl_chain_free((whirl_chain *)a.c);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    const size_t nmax = argc > 2 ? (size_t)atol(argv[2]) : 400;
    const char *part = argc > 3 ? argv[3] : "all";
    const int all = strcmp(part, "all") == 0;
    const int do_windows = all || strcmp(part, "windows") == 0;
    const int do_cost = all || strcmp(part, "cost") == 0;
    const int do_scan = all || strcmp(part, "scan") == 0;
    const int do_follow = strcmp(part, "follow") == 0;
    gsl_set_error_handler_off();
    printf("load average %.2f (2 shared cores: wall times are noisy)\n", bench_load_average());

    /* 2. windows at every N */
    static result res[NLEVELS][2];
    int nl = 0;
    setvbuf(stdout, NULL, _IOLBF, 0);
    /* "all": the search up to N = 200, then N = 400 by following the edges */
    const size_t search_max = all && nmax > 200 ? 200 : nmax;
    for (int l = 0; l < NLEVELS && levels[l] <= search_max && do_windows; l++, nl++) {
#pragma omp parallel for schedule(static, 1)
        for (int k = 0; k < 2; k++) find(levels[l], k + 2, levels[l] > 100 ? 0.5 : 0.25, &res[l][k]);
        const result *r2 = &res[l][0], *r3 = &res[l][1];
        printf("N = %3zu: modes 2-3 over omega 1..10, one thread each (mode 2: %zu windows, "
               "%.3f s, %zu solves of which %zu with vectors and %zu Arnoldi; mode 3: %zu "
               "windows, %.3f s, %zu solves of which %zu with vectors and %zu Arnoldi)\n",
               levels[l], r2->count, r2->seconds, solves(&r2->stats),
               r2->stats.solves_vectors, r2->stats.solves_krylov, r3->count, r3->seconds,
               solves(&r3->stats), r3->stats.solves_vectors, r3->stats.solves_krylov);
        for (int k = 0; k < 2; k++)
            for (size_t i = 0; i < res[l][k].count; i++) {
                const whirl_window *x = &res[l][k].win[i];
                printf("    mode %d: [%.10f, %.10f]%s max growth %.6f at %.6f\n", k + 2, x->from,
                       x->to, x->open_to ? " (open: range end)" : "", x->max_growth, x->at);
            }
        write_windows(dir, levels[l], r2, r3);
    }

    if (do_follow || search_max < nmax) {
        for (int l = 0; l < NLEVELS && levels[l] <= nmax; l++) nl = l + 1;
        if (nl < 3) bench_die("follow needs three chains");
        follow(dir, nl, res);
    }

    /* 3. continuum extrapolation of every edge found at every N */
    FILE *fp = do_windows || do_follow ? bench_open_csv(dir, "windows_continuum.csv") : NULL;
    /* every level has its column, empty above the largest N run: the layout does not depend on
     * it (tests/bench/bench_windows.sh and plots/windows.gp read the columns by position) */
    if (fp) fprintf(fp, "mode,window,edge");
    for (int l = 0; fp && l < NLEVELS; l++) fprintf(fp, ",N%zu", levels[l]);
    if (fp) fprintf(fp, ",order,continuum,error,error_from\n");
    printf("edges against N (1/N extrapolation; order from the three finest N):\n");
    for (int k = 0; k < 2 && nl >= 3; k++) {
        /* each window of the finest chain, matched at the coarser ones by overlap */
        const result *fine = &res[nl - 1][k];
        for (size_t i = 0; i < fine->count; i++)
            for (int edge = 0; edge < 2; edge++) {
                const whirl_window *f = &fine->win[i];
                double e[NLEVELS];
                int open = edge ? f->open_to : f->open_from, have = 0;
                for (int l = nl - 1; l >= 0; l--) {
                    e[l] = NAN;
                    for (size_t j = 0; j < res[l][k].count; j++) {
                        const whirl_window *x = &res[l][k].win[j];
                        if (x->from < f->to && x->to > f->from && !(edge ? x->open_to : x->open_from))
                            e[l] = edge ? x->to : x->from;
                    }
                    if (!isnan(e[l]) && have == nl - 1 - l) have++;
                }
                if (open || have < 3) continue;
                const double d1 = e[nl - 2] - e[nl - 3], d2 = e[nl - 1] - e[nl - 2];
                const double order = log2(d1 / d2);
                const double cont = richardson(e[nl - 3], e[nl - 2], e[nl - 1]);
                /* the error estimate: with four chains, the same extrapolation from the three
                 * coarser ones; with three (an edge the coarsest chain lacks), the size of the
                 * last correction, against the first-order extrapolation 2 e_N - e_{N/2} of the
                 * two finest (larger than the error of the second-order value while the edges
                 * converge at first order) */
                const int from_coarser = have >= 4;
                const double err = from_coarser
                                       ? fabs(cont - richardson(e[nl - 4], e[nl - 3], e[nl - 2]))
                                       : fabs(cont - (2 * e[nl - 1] - e[nl - 2]));
                fprintf(fp, "%d,%zu,%s", k + 2, i + 1, edge ? "to" : "from");
                printf("  mode %d window %zu %-4s:", k + 2, i + 1, edge ? "to" : "from");
                for (int l = 0; l < nl; l++) {
                    if (isnan(e[l]))
                        fprintf(fp, ",");
                    else
                        fprintf(fp, ",%.17g", e[l]);
                    printf(" %.8f", e[l]);
                }
                for (int l = nl; l < NLEVELS; l++) fprintf(fp, ",");
                fprintf(fp, ",%.6g,%.17g,%.3g,%s\n", order, cont, err,
                        from_coarser ? "coarser" : "first_order");
                printf("  order %.3f  continuum %.8f +- %.2g (%s)\n", order, cont, err,
                       from_coarser ? "from the coarser chains" : "against first order");
            }
    }
    if (fp) fclose(fp);

    /* 4. cost of one eigen-solve */
    if (do_cost) {
        fp = bench_open_csv(dir, "windows_cost.csv");
        fprintf(fp, "links,seconds_dgeev_4n,seconds_reduced,seconds_reduced_vectors,"
                    "seconds_arnoldi_pair,repeats\n");
        for (int l = 0; l < NLEVELS && levels[l] <= nmax; l++) cost(fp, levels[l]);
        fclose(fp);
    }

    /* 5. the N = 100 edges do not depend on the scan step */
    if (nmax >= 100 && do_scan) {
        if (!do_windows) {
            for (int k = 0; k < 2; k++) find(100, k + 2, 0.25, &res[2][k]);
        }
        fp = bench_open_csv(dir, "windows_scan.csv");
        fprintf(fp, "mode,scan_step,windows,largest_edge_difference,solves,seconds\n");
        const int l100 = 2;
        double worst = 0;
        for (int k = 0; k < 2; k++)
            for (int s = 0; s < 2; s++) {
                const double step = s ? 0.5 : 0.125;
                result r;
                find(100, k + 2, step, &r);
                double diff = r.count == res[l100][k].count ? 0 : INFINITY;
                for (size_t i = 0; i < r.count && isfinite(diff); i++)
                    diff = fmax(diff, fmax(fabs(r.win[i].from - res[l100][k].win[i].from),
                                           fabs(r.win[i].to - res[l100][k].win[i].to)));
                worst = fmax(worst, diff);
                fprintf(fp, "%d,%g,%zu,%.3g,%zu,%.3f\n", k + 2, step, r.count, diff,
                        solves(&r.stats), r.seconds);
                printf("N = 100 mode %d, scan step %g: %zu windows, edges within %.2g of the "
                       "step-0.25 ones, %zu solves, %.3f s\n", k + 2, step, r.count, diff,
                       solves(&r.stats), r.seconds);
            }
        fclose(fp);
        if (!(worst < 1e-8)) {
            printf("FAIL: the windows depend on the scan step\n");
            return 1;
        }
    }
    return 0;
}
