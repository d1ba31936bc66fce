/* Tests of the continuum's linear stability (src/stability/continuum_*.c) against independent
 * results:
 *  - the hanging chain: its frequencies against the zeros of J0 (j_{0,n} / 2, GSL), shifted by
 *    +-omega in the co-rotating frame; with a tip mass against the roots of the J0/Y0 determinant
 *    (whirl_continuum_critical); the Krein signatures against the frequencies (negative energy
 *    exactly for the co-rotating modes slower than the frame);
 *  - spectral convergence: on elements bounded by the shape's tolerance and the phase of the
 *    waves kept (4 to 7 from degree 16) the mu of the mode-2 shape converge geometrically in the
 *    degree, to the values of the refined elements; the collocation's tip
 *    radius against the shooting's;
 *  - the Krein signatures of modes 2 and 3 against the N-link chain's (whirl_windows_spectrum);
 *  - the window of mode 2 near omega = 4.4-4.6 against the N-link chain's edges extrapolated to
 *    N -> infinity, and each edge against the growth just inside and outside;
 *  - the Arnoldi iteration on the banded pencil against the dense block's eigenvalues;
 *  - two edges that need more than one refinement against the root of their discriminant on a
 *    finer discretisation with the dense block, within their error estimates;
 *  - bad input, the memory bound and the stop request.
 * The dense block's eigenvalues and the discriminant's roots (40 s of processor time) are read
 * from tests/fixtures/ (tests/lib/fixture.h), written by this program:
 *   build/tests/test_continuum_stability --write-fixtures tests/fixtures [NAME...]
 * and computed anew and compared by make fixtures-check. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_sf_bessel.h>

#include "whirl/continuum_stability.h"
#include "fixture.h"

/* The command that writes this program's fixtures (followed by the file's name). */
#define WRITE_FIXTURES "build/tests/test_continuum_stability --write-fixtures " FIXTURE_DIR

/* Appends printf-style text to buf (size), which holds a string. */
static void append(char *buf, size_t size, const char *fmt, ...)
{
    const size_t used = strlen(buf);
    assert_true(used + 1 < size);
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(buf + used, size - used, fmt, ap);
    va_end(ap);
    assert_true(n >= 0 && (size_t)n < size - used);
}

/* The workspace's parameters as a fixture's problem line begins (every number exact). */
static void describe_params(char *buf, size_t size, const whirl_cstab_params *p)
{
    buf[0] = '\0';
    append(buf, size, "the uniform continuum (g = L = M = 1), tip mass %.17g; collocation degree "
           "%d, shape tolerance %.17g, |mu| <= max(%.17g, 3 omega)^2 kept, solver %d, memory "
           "%.17g MB", p->tip_mass, p->degree, p->shape_tol, p->freq_max, p->solver,
           p->memory_mb);
}

/* Sorts mu by decreasing real part (increasing frequency). */
static void sort_mu(size_t n, double *re, double *im, int *sig)
{
    for (size_t i = 1; i < n; i++)
        for (size_t j = i; j > 0 && re[j - 1] < re[j]; j--) {
            double t = re[j], u = im[j];
            re[j] = re[j - 1], im[j] = im[j - 1];
            re[j - 1] = t, im[j - 1] = u;
            if (sig) {
                int s = sig[j];
                sig[j] = sig[j - 1], sig[j - 1] = s;
            }
        }
}

/* The first k mu of the last linearisation, sorted, and their signatures (sig may be NULL). */
static size_t lowest(whirl_cstab *w, int signatures, size_t k, double *re, double *im, int *sig,
                     double *growth)
{
    whirl_spectrum sp;
    assert_int_equal(whirl_cstab_spectrum(w, signatures, &sp), 0);
    double *r = malloc(sp.count * sizeof *r), *m = malloc(sp.count * sizeof *m);
    int *s = malloc(sp.count * sizeof *s);
    for (size_t i = 0; i < sp.count; i++) {
        r[i] = sp.re[i], m[i] = sp.im[i];
        s[i] = signatures ? sp.signature[i] : 0;
    }
    sort_mu(sp.count, r, m, s);
    const size_t n = k < sp.count ? k : sp.count;
    for (size_t i = 0; i < n; i++) {
        re[i] = r[i], im[i] = m[i];
        if (sig) sig[i] = s[i];
    }
    if (growth) *growth = sp.growth;
    free(r), free(m), free(s);
    return n;
}

static void test_hanging(void **state)
{
    (void)state;
    whirl_cstab_params p = whirl_cstab_defaults();
    whirl_cstab *w = whirl_cstab_alloc(&p);
    assert_non_null(w);
    /* at rest: every frequency twice (in and out of the plane), j_{0,n} / 2 */
    double re[40], im[40], freq[12];
    int sig[40];
    assert_int_equal(whirl_cstab_linearise(w, 0, 0, 0, NULL), 0);
    assert_int_equal(lowest(w, 1, 12, re, im, sig, NULL), 12);
    double worst = 0;
    for (int n = 1; n <= 6; n++) {
        const double f = gsl_sf_bessel_zero_J0((unsigned)n) / 2;
        for (int k = 0; k < 2; k++) {
            worst = fmax(worst, fabs(sqrt(-re[2 * (n - 1) + k]) / f - 1));
            assert_true(im[2 * (n - 1) + k] == 0);
            assert_int_equal(sig[2 * (n - 1) + k], 1);
        }
    }
    print_message("# hanging chain at rest: frequencies 1-6 against j_{0,n}/2 to %.2g\n", worst);
    assert_true(worst < 1e-10);
    /* co-rotating at omega between the first two: mu = -(j_{0,n}/2 -+ omega)^2, negative energy
     * for the one mode slower than the frame */
    const double omega = 1.7234;
    assert_int_equal(whirl_cstab_linearise(w, omega, 0, 0, NULL), 0);
    assert_int_equal(lowest(w, 1, 12, re, im, sig, NULL), 12);
    for (int n = 1; n <= 6; n++) {
        const double f = gsl_sf_bessel_zero_J0((unsigned)n) / 2;
        freq[2 * (n - 1)] = fabs(f - omega), freq[2 * n - 1] = f + omega;
    }
    for (size_t i = 1; i < 12; i++) /* ascending */
        for (size_t j = i; j > 0 && freq[j - 1] > freq[j]; j--) {
            double t = freq[j];
            freq[j] = freq[j - 1], freq[j - 1] = t;
        }
    worst = 0;
    int negative = 0;
    for (size_t i = 0; i < 8; i++) {
        worst = fmax(worst, fabs(sqrt(-re[i]) - freq[i]));
        negative += sig[i] < 0;
        if (fabs(sqrt(-re[i]) - (omega - gsl_sf_bessel_zero_J0(1) / 2)) < 1e-6)
            assert_int_equal(sig[i], -1);
    }
    print_message("# hanging chain at omega = %g: |j_{0,n}/2 -+ omega| to %.2g, %d mode of "
                  "negative energy\n", omega, worst, negative);
    assert_true(worst < 1e-9);
    assert_int_equal(negative, 1);
    whirl_cstab_free(w);
    /* with a tip mass: the roots of the J0/Y0 determinant */
    p.tip_mass = 0.37;
    w = whirl_cstab_alloc(&p);
    assert_int_equal(whirl_cstab_linearise(w, 0, 0, 0, NULL), 0);
    assert_int_equal(lowest(w, 0, 12, re, im, NULL, NULL), 12);
    worst = 0;
    for (int n = 1; n <= 5; n++) {
        double f;
        assert_int_equal(whirl_continuum_critical(n, p.tip_mass, &f), 0);
        worst = fmax(worst, fabs(sqrt(-re[2 * (n - 1)]) / f - 1));
        worst = fmax(worst, fabs(sqrt(-re[2 * n - 1]) / f - 1));
    }
    print_message("# hanging chain with tip mass 0.37: frequencies 1-5 against the J0/Y0 roots "
                  "to %.2g\n", worst);
    assert_true(worst < 1e-10);
    whirl_cstab_free(w);
}

/* On the four starting elements (shape_tol loose) the error of the 8 lowest mu and of the growth
 * against the reference (degree 40, refined elements) falls geometrically with the degree. */
static void test_convergence(void **state)
{
    (void)state;
    const double omega = 4.4567;
    whirl_cstab_params p = whirl_cstab_defaults();
    p.degree = 40; /* the reference: degree 40 on elements refined to the shape */
    whirl_cstab *w = whirl_cstab_alloc(&p);
    double ref_re[8], ref_im[8], ref_g, tip;
    assert_int_equal(whirl_cstab_linearise(w, omega, 2, 0, &tip), 0);
    assert_int_equal(lowest(w, 0, 8, ref_re, ref_im, NULL, &ref_g), 8);
    whirl_shape_info info;
    assert_int_equal(whirl_continuum_solve(omega, 2, 0, 0, &info), 0);
    print_message("# mode 2 at %g: collocation tip radius %.15g, shooting %.15g\n", omega, tip,
                  info.tip_r);
    assert_true(fabs(tip - info.tip_r) < 1e-11);
    assert_true(ref_g > 0.03);
    whirl_cstab_free(w);
    enum { LEVELS = 7 };
    const int degree[LEVELS] = {8, 12, 16, 20, 24, 28, 32};
    double err[LEVELS];
    for (int k = 0; k < LEVELS; k++) {
        p.degree = degree[k];
        p.shape_tol = 1e-3;
        w = whirl_cstab_alloc(&p);
        double re[8], im[8], g;
        assert_int_equal(whirl_cstab_linearise(w, omega, 2, 0, NULL), 0);
        size_t ne, np;
        whirl_cstab_grid(w, &ne, &np);
        assert_true(ne >= 4);
        assert_int_equal(lowest(w, 0, 8, re, im, NULL, &g), 8);
        err[k] = fabs(g - ref_g);
        for (int i = 0; i < 8; i++) err[k] = fmax(err[k], hypot(re[i] - ref_re[i], fabs(im[i]) - fabs(ref_im[i])));
        print_message("# degree %2d, %2zu elements, %3zu points: largest error of the 8 lowest mu and the growth "
                      "%.2g\n", degree[k], ne, np, err[k]);
        whirl_cstab_free(w);
    }
    /* geometric: from degree 16, where the elements of the waves' phase (shape tolerance 1e-3:
     * a phase bound for 3e-2) are 4 to 7 for every degree, each step of 4 in the degree gains a
     * factor 5 at least, down to the round-off of the mu (about 1e-8 of their size) */
    for (int k = 2; k + 1 < LEVELS; k++) assert_true(err[k + 1] < fmax(err[k] / 5, 3e-8));
    assert_true(err[0] > 1e-6); /* the coarsest is really coarse */
    assert_true(err[LEVELS - 1] < 1e-7);
}

/* The signatures against the N-link chain's at N = 40 (two neutral rates of modes 2 and 3). */
static void test_signatures(void **state)
{
    (void)state;
    whirl_cstab_params p = whirl_cstab_defaults();
    whirl_cstab *w = whirl_cstab_alloc(&p);
    const size_t n = 40;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    whirl_windows *nw = whirl_windows_alloc(n);
    whirl_stability *lin = whirl_stability_alloc(n);
    const struct { double omega; int mode, negative; } cases[] = {{4.3, 2, 1}, {5.3, 3, 2}};
    for (int k = 0; k < 2; k++) {
        double re[40], im[40], g;
        int sig[40];
        assert_int_equal(whirl_cstab_linearise(w, cases[k].omega, cases[k].mode, 0, NULL), 0);
        const size_t m = lowest(w, 1, 40, re, im, sig, &g);
        int negative = 0;
        for (size_t i = 0; i < m; i++) negative += sig[i] < 0;
        whirl_model mod = {0};
        mod.chain = c, mod.dim = 3, mod.frame = WHIRL_FRAME_ROTATING, mod.omega = cases[k].omega;
        double gn;
        assert_int_equal(whirl_stability_mode(lin, &mod, cases[k].mode, NULL, &gn), 0);
        whirl_spectrum sp;
        assert_int_equal(whirl_windows_spectrum(nw, lin, 1, &sp), 0);
        int nneg = 0;
        for (size_t i = 0; i < sp.count; i++) nneg += sp.signature[i] < 0;
        print_message("# mode %d at %g: %d modes of negative energy (N = 40: %d), growth %g\n",
                      cases[k].mode, cases[k].omega, negative, nneg, g);
        assert_true(g == 0 && gn == 0);
        assert_int_equal(negative, cases[k].negative);
        assert_int_equal(nneg, cases[k].negative);
    }
    whirl_stability_free(lin);
    whirl_windows_free(nw);
    whirl_chain_free(c);
    whirl_cstab_free(w);
}

/* The growth of mode 2 at omega by a full solve. */
static double growth_at(whirl_cstab *w, double omega)
{
    double re[2], im[2], g;
    assert_int_equal(whirl_cstab_linearise(w, omega, 2, 0, NULL), 0);
    lowest(w, 0, 2, re, im, NULL, &g);
    return g;
}

/* whirl_cstab_params.progress: the calls, their mode and their range of rates. */
typedef struct progress_seen {
    size_t calls;
    int other_mode;
    double lo, hi;
} progress_seen;

static void count_progress(void *ctx, int mode, double omega)
{
    progress_seen *s = ctx;
    s->calls++;
    s->other_mode |= mode != 2;
    s->lo = fmin(s->lo, omega);
    s->hi = fmax(s->hi, omega);
}

static void test_window(void **state)
{
    (void)state;
    whirl_cstab_params cp = whirl_cstab_defaults();
    progress_seen seen = {0, 0, INFINITY, -INFINITY};
    cp.progress = count_progress;
    cp.progress_ctx = &seen;
    whirl_cstab *w = whirl_cstab_alloc(&cp);
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 4.3, p.omega_max = 4.65;
    whirl_window win[4];
    size_t count;
    whirl_windows_stats st;
    assert_int_equal(whirl_cstab_windows(w, 2, &p, win, 4, &count, &st), 0);
    assert_int_equal(count, 1);
    /* one report before each shape of the search, within its range */
    assert_int_equal(seen.calls, st.shapes);
    assert_false(seen.other_mode);
    assert_true(seen.lo >= p.omega_min && seen.hi <= p.omega_max && seen.lo < seen.hi);
    print_message("# mode 2: window [%.10f, %.10f], growth %.6g at %.6f (%zu solves); N-link "
                  "chain extrapolated [4.403221 +- 2e-6, 4.567784 +- 4e-7]\n", win[0].from,
                  win[0].to, win[0].max_growth, win[0].at,
                  st.solves_vectors + st.solves_values);
    /* the README's Richardson extrapolation of N = 100, 200, 400, with its error estimate: an
     * independent computation (no continuum equations) */
    assert_true(fabs(win[0].from - 4.403221) < 2e-6 + 5e-7);
    assert_true(fabs(win[0].to - 4.567784) < 4e-7 + 5e-7);
    assert_true(!win[0].open_from && !win[0].open_to);
    /* the edges against the growth 1e-7 inside and outside */
    assert_true(growth_at(w, win[0].from - 1e-7) == 0);
    assert_true(growth_at(w, win[0].from + 1e-7) > 0);
    assert_true(growth_at(w, win[0].to - 1e-7) > 0);
    assert_true(growth_at(w, win[0].to + 1e-7) == 0);
    whirl_cstab_free(w);
}

/* test_solvers: modes 2, 3 and 6 at rates with and without a window, the mu of the dense block
 * (at most SOLVER_K of them) from tests/fixtures/continuum_solvers.txt. */
static const struct solver_case { int mode; double omega; } solver_cases[] = {
    {2, 2.8}, {2, 4.48}, {2, 9.9}, {3, 4.4}, {3, 7.34}, {3, 10}, {6, 14}};
enum { SOLVER_CASES = sizeof solver_cases / sizeof solver_cases[0], SOLVER_K = 80 };
#define SOLVERS_FIXTURE "continuum_solvers.txt"

/* The dense block's parameters (the defaults, solver 1) and the problem line of its fixture. */
static whirl_cstab_params solvers_problem(char *buf, size_t size)
{
    whirl_cstab_params p = whirl_cstab_defaults();
    p.solver = 1;
    describe_params(buf, size, &p);
    append(buf, size, "; every mu (at most %d, by decreasing real part) with its signature, and "
           "the growth, of", SOLVER_K);
    for (size_t c = 0; c < SOLVER_CASES; c++)
        append(buf, size, "%s mode %d at omega %.17g", c ? "," : "", solver_cases[c].mode,
               solver_cases[c].omega);
    return p;
}

/* The kept mu by the Arnoldi iteration on the banded pencil against every mu of the dense block
 * (solver 1, the fixture): the same grid, count and signatures, the same mu to 1e-8 relative. */
static void test_solvers(void **state)
{
    (void)state;
    char problem[2048];
    whirl_cstab_params p = solvers_problem(problem, sizeof problem);
    p.solver = 0;
    whirl_cstab *fast = whirl_cstab_alloc(&p);
    assert_non_null(fast);
    fixture f;
    fixture_open(&f, SOLVERS_FIXTURE, WRITE_FIXTURES " " SOLVERS_FIXTURE, problem);
    double re[2][SOLVER_K], im[2][SOLVER_K], worst = 0;
    int sig[2][SOLVER_K];
    for (size_t c = 0; c < SOLVER_CASES; c++) {
        size_t n[2], ne, np;
        double growth[2];
        assert_int_equal(whirl_cstab_linearise(fast, solver_cases[c].omega, solver_cases[c].mode,
                                               0, NULL), 0);
        n[0] = lowest(fast, 1, SOLVER_K, re[0], im[0], sig[0], &growth[0]);
        whirl_cstab_grid(fast, &ne, &np);
        /* the dense block's on the same grid */
        const long ne_ref = fixture_int(&f, 1, 100000), np_ref = fixture_int(&f, 1, 10000000);
        if ((size_t)ne_ref != ne || (size_t)np_ref != np)
            fail_msg("%s: mode %d at omega %g: the fixture's grid has %ld elements and %ld points, "
                     "this build's %zu and %zu (the discretisation changed): write it anew with\n"
                     "  %s", f.path, solver_cases[c].mode, solver_cases[c].omega, ne_ref, np_ref,
                     ne, np, f.command);
        n[1] = (size_t)fixture_int(&f, 0, SOLVER_K);
        growth[1] = fixture_value(&f);
        for (size_t i = 0; i < n[1]; i++) {
            re[1][i] = fixture_value(&f);
            im[1][i] = fixture_value(&f);
            sig[1][i] = (int)fixture_int(&f, -1, 1);
        }
        assert_int_equal(n[0], n[1]);
        assert_true(n[0] < SOLVER_K);
        for (size_t i = 0; i < n[0]; i++) {
            const double d = hypot(re[0][i] - re[1][i], fabs(im[0][i]) - fabs(im[1][i]));
            worst = fmax(worst, d / fmax(1, hypot(re[1][i], im[1][i])));
            assert_int_equal(sig[0][i], sig[1][i]);
        }
        assert_true(fabs(growth[0] - growth[1]) <= 1e-8 * fmax(1, growth[1]));
    }
    fixture_close(&f);
    print_message("# Arnoldi against the dense block: largest relative difference of the mu %.2g\n",
                  worst);
    assert_true(worst <= 1e-8);
    whirl_cstab_free(fast);
}

/* Writes the fixture of test_solvers into the folder *state. */
static void write_solvers(void **state)
{
    char problem[2048];
    const whirl_cstab_params p = solvers_problem(problem, sizeof problem);
    whirl_cstab *dense = whirl_cstab_alloc(&p);
    assert_non_null(dense);
    double re[SOLVER_CASES][SOLVER_K], im[SOLVER_CASES][SOLVER_K], growth[SOLVER_CASES];
    int sig[SOLVER_CASES][SOLVER_K];
    size_t n[SOLVER_CASES], ne[SOLVER_CASES], np[SOLVER_CASES];
    for (size_t c = 0; c < SOLVER_CASES; c++) { /* every value before the file is opened */
        assert_int_equal(whirl_cstab_linearise(dense, solver_cases[c].omega, solver_cases[c].mode,
                                               0, NULL), 0);
        n[c] = lowest(dense, 1, SOLVER_K, re[c], im[c], sig[c], &growth[c]);
        assert_true(n[c] < SOLVER_K); /* every mu kept */
        whirl_cstab_grid(dense, &ne[c], &np[c]);
    }
    whirl_cstab_free(dense);
    fixture_out o;
    fixture_create(&o, *state, SOLVERS_FIXTURE, WRITE_FIXTURES " " SOLVERS_FIXTURE, problem);
    for (size_t c = 0; c < SOLVER_CASES; c++) {
        fixture_comment(&o, "mode %d at omega %g: the elements, the collocation points, the count "
                        "of mu, the growth, then Re mu, Im mu and the signature of each",
                        solver_cases[c].mode, solver_cases[c].omega);
        fixture_put(&o, (double)ne[c]);
        fixture_put(&o, (double)np[c]);
        fixture_put(&o, (double)n[c]);
        fixture_put(&o, growth[c]);
        for (size_t i = 0; i < n[c]; i++) {
            fixture_put(&o, re[c][i]);
            fixture_put(&o, im[c][i]);
            fixture_put(&o, sig[c][i]);
        }
    }
    fixture_commit(&o);
}

/* D = Re (mu_1 - mu_2)^2 of the two mu nearest -freq^2 at omega (-4 (Im mu)^2 for a complex
 * pair), every mu from the workspace's solver */
static double discriminant_at(whirl_cstab *w, int mode, double omega, double freq)
{
    assert_int_equal(whirl_cstab_linearise(w, omega, mode, 0, NULL), 0);
    whirl_spectrum sp;
    assert_int_equal(whirl_cstab_spectrum(w, 0, &sp), 0);
    assert_true(sp.count >= 2);
    const double c = -freq * freq;
    size_t a = 0, b = 1;
    for (size_t i = 0; i < sp.count; i++) {
        const double d = hypot(sp.re[i] - c, sp.im[i]);
        if (d < hypot(sp.re[a] - c, sp.im[a])) b = a, a = i;
        else if (i != a && (b == a || d < hypot(sp.re[b] - c, sp.im[b]))) b = i;
    }
    /* the pair alone near -freq^2: every other mu ten times as far as the farther of the two */
    for (size_t i = 0; i < sp.count; i++)
        if (i != a && i != b)
            assert_true(hypot(sp.re[i] - c, sp.im[i]) > 10 * hypot(sp.re[b] - c, sp.im[b]));
    if (sp.im[a] != 0) return -4 * sp.im[a] * sp.im[a];
    const double dr = sp.re[a] - sp.re[b], di = sp.im[a] - sp.im[b];
    return dr * dr - di * di;
}

/* test_refined_edges: an edge of the windows against the root of the collision discriminant on
 * an independent discretisation and solver (degree 48, shape tolerance 1e-13, every mu from the
 * dense block, regula falsi to 1e-11 from a bracket of 1e-7 about the root, the pair the two mu
 * nearest -freq^2, freq the pair's frequency at the collision): within the edge's error estimate
 * plus the root finders' tolerances (1e-10). The mode-2 edge near 9.746 (its pair, mu about -52,
 * separates slowly: the search's discretisation has it 1.4e-5 off) and the mode-3 edge near
 * 7.480 need more than one refinement. The roots are read from
 * tests/fixtures/continuum_refined_edges.txt. */
static const struct edge_case {
    int mode;
    double from, to; /* the search's range of rates */
    int closing;     /* 0: the window's opening edge; 1: its closing one */
    double lo, hi;   /* the bracket of the root (D of opposite signs at its ends) */
    double freq;
} edge_cases[] = {{2, 9.7, 9.8, 0, 9.74606586, 9.74606596, 7.2154},
                  {3, 7.4, 7.5, 1, 7.480154, 7.4801541, 2.98607}};
enum { EDGE_CASES = sizeof edge_cases / sizeof edge_cases[0] };
#define EDGES_FIXTURE "continuum_refined_edges.txt"

/* The reference's parameters and the problem line of its fixture. */
static whirl_cstab_params edges_problem(char *buf, size_t size)
{
    whirl_cstab_params p = whirl_cstab_defaults();
    p.degree = 48, p.shape_tol = 1e-13, p.solver = 1;
    describe_params(buf, size, &p);
    append(buf, size, "; the root of D = Re (mu_1 - mu_2)^2 of the two mu nearest -freq^2 by "
           "regula falsi (Illinois) to a bracket of 1e-11, of");
    for (size_t c = 0; c < EDGE_CASES; c++) {
        const struct edge_case *e = &edge_cases[c];
        append(buf, size, "%s the %s edge of mode %d in [%.17g, %.17g] from [%.17g, %.17g] with "
               "freq %.17g", c ? "," : "", e->closing ? "closing" : "opening", e->mode, e->from,
               e->to, e->lo, e->hi, e->freq);
    }
    return p;
}

static void test_refined_edges(void **state)
{
    (void)state;
    char problem[2048];
    edges_problem(problem, sizeof problem);
    fixture f;
    fixture_open(&f, EDGES_FIXTURE, WRITE_FIXTURES " " EDGES_FIXTURE, problem);
    whirl_cstab_params p = whirl_cstab_defaults();
    whirl_cstab *w = whirl_cstab_alloc(&p);
    assert_non_null(w);
    for (size_t c = 0; c < EDGE_CASES; c++) {
        const struct edge_case *e = &edge_cases[c];
        whirl_windows_params wp = whirl_windows_defaults();
        wp.omega_min = e->from, wp.omega_max = e->to;
        whirl_window win[2];
        size_t count;
        whirl_windows_stats st;
        assert_int_equal(whirl_cstab_windows(w, e->mode, &wp, win, 2, &count, &st), 0);
        assert_int_equal(count, 1);
        const double edge = e->closing ? win[0].to : win[0].from;
        const double err = e->closing ? win[0].err_to : win[0].err_from;
        assert_true(e->closing ? !win[0].open_to : !win[0].open_from);
        const double root = fixture_value(&f);
        print_message("# mode %d: edge %.12f (estimate %.2g), degree 48 and the dense block %.12f: "
                      "difference %.2g\n", e->mode, edge, err, root, fabs(edge - root));
        assert_true(err <= 1e-8);
        assert_true(fabs(edge - root) <= err + 1e-10);
    }
    fixture_close(&f);
    whirl_cstab_free(w);
}

/* The root of D in the bracket of e by regula falsi (Illinois) on the workspace ref. */
static double discriminant_root(whirl_cstab *ref, const struct edge_case *e)
{
    double lo = e->lo, hi = e->hi;
    double flo = discriminant_at(ref, e->mode, lo, e->freq);
    double fhi = discriminant_at(ref, e->mode, hi, e->freq);
    /* D > 0 on the stable side, < 0 inside */
    assert_true(e->closing ? (flo < 0 && fhi > 0) : (flo > 0 && fhi < 0));
    int side = 0;
    while (hi - lo > 1e-11) {
        const double x = (lo * fhi - hi * flo) / (fhi - flo);
        const double fx = discriminant_at(ref, e->mode, x, e->freq);
        if (fx == 0) lo = hi = x;
        else if ((fx > 0) == (flo > 0)) {
            lo = x, flo = fx;
            if (side == -1) fhi /= 2;
            side = -1;
        } else {
            hi = x, fhi = fx;
            if (side == 1) flo /= 2;
            side = 1;
        }
    }
    return (lo + hi) / 2;
}

/* Writes the fixture of test_refined_edges into the folder *state. */
static void write_refined_edges(void **state)
{
    char problem[2048];
    const whirl_cstab_params p = edges_problem(problem, sizeof problem);
    whirl_cstab *ref = whirl_cstab_alloc(&p);
    assert_non_null(ref);
    double root[EDGE_CASES];
    for (size_t c = 0; c < EDGE_CASES; c++) root[c] = discriminant_root(ref, &edge_cases[c]);
    whirl_cstab_free(ref);
    fixture_out o;
    fixture_create(&o, *state, EDGES_FIXTURE, WRITE_FIXTURES " " EDGES_FIXTURE, problem);
    for (size_t c = 0; c < EDGE_CASES; c++) {
        fixture_comment(&o, "the %s edge of mode %d", edge_cases[c].closing ? "closing" : "opening",
                        edge_cases[c].mode);
        fixture_put(&o, root[c]);
    }
    fixture_commit(&o);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_cstab_params p = whirl_cstab_defaults();
    p.degree = 5;
    assert_null(whirl_cstab_alloc(&p));
    assert_non_null(strstr(whirl_last_error(), "degree"));
    p = whirl_cstab_defaults();
    p.tip_mass = -1;
    assert_null(whirl_cstab_alloc(&p));
    p = whirl_cstab_defaults();
    p.shape_tol = 0;
    assert_null(whirl_cstab_alloc(&p));
    p = whirl_cstab_defaults();
    p.freq_max = NAN;
    assert_null(whirl_cstab_alloc(&p));
    p = whirl_cstab_defaults();
    whirl_cstab *w = whirl_cstab_alloc(&p);
    whirl_spectrum sp;
    assert_int_equal(whirl_cstab_spectrum(w, 0, &sp), GSL_EINVAL);
    assert_int_equal(whirl_cstab_linearise(w, 3, 3, 0, NULL), GSL_EDOM);
    assert_int_equal(whirl_cstab_linearise(w, 0, 2, 0, NULL), GSL_EINVAL);
    assert_int_equal(whirl_cstab_linearise(w, NAN, 2, 0, NULL), GSL_EINVAL);
    assert_int_equal(whirl_cstab_linearise(w, 3, -1, 0, NULL), GSL_EINVAL);
    /* a shape beyond the memory bound (mode 8 at omega = 40 needs 1105 points, 16 MB hold
     * about 700): a message naming the mode, the rate and the points, no pencil */
    p.memory_mb = 8;
    assert_null(whirl_cstab_alloc(&p));
    assert_non_null(strstr(whirl_last_error(), "memory bound"));
    p.memory_mb = 16;
    whirl_cstab *small = whirl_cstab_alloc(&p);
    assert_non_null(small);
    assert_int_equal(whirl_cstab_linearise(small, 40, 8, 0, NULL), GSL_EMAXITER);
    const char *msg = whirl_last_error();
    assert_non_null(strstr(msg, "mode 8 at omega = 40 needs"));
    assert_non_null(strstr(msg, "collocation points"));
    assert_non_null(strstr(msg, "16 MB"));
    assert_int_equal(whirl_cstab_spectrum(small, 0, &sp), GSL_EINVAL);
    whirl_cstab_free(small);
    /* the same shape with the default bound */
    size_t ne, np;
    assert_int_equal(whirl_cstab_linearise(w, 40, 8, 0, NULL), GSL_SUCCESS);
    whirl_cstab_grid(w, &ne, &np);
    assert_true(np > 800);
    p = whirl_cstab_defaults();
    p.solver = 2;
    assert_null(whirl_cstab_alloc(&p));
    whirl_window win[2];
    size_t count;
    whirl_windows_stats st;
    whirl_windows_params wp = whirl_windows_defaults();
    wp.omega_min = 1, wp.omega_max = 4;
    assert_int_equal(whirl_cstab_windows(w, 3, &wp, win, 2, &count, &st), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "mode 3"));
    assert_int_equal(whirl_cstab_windows(w, 0, &wp, win, 2, &count, &st), GSL_EINVAL);
    wp.omega_max = 1e4;
    assert_int_equal(whirl_cstab_windows(w, 2, &wp, win, 2, &count, &st), GSL_EINVAL);
    wp = whirl_windows_defaults();
    wp.omega_min = 4.3, wp.omega_max = 4.65;
    whirl_stop_request();
    assert_int_equal(whirl_cstab_windows(w, 2, &wp, win, 2, &count, &st), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    whirl_cstab_free(NULL);
    whirl_cstab_free(w);
}

/* --write-fixtures DIR [NAME...]: writes the fixtures NAME (every one without NAME) into DIR,
 * each a test of its own. */
static int write_fixtures(int argc, char **argv)
{
    static const struct { const char *name; CMUnitTestFunction write; } writers[] = {
        {SOLVERS_FIXTURE, write_solvers}, {EDGES_FIXTURE, write_refined_edges}};
    enum { WRITERS = sizeof writers / sizeof writers[0] };
    if (argc < 1) {
        fprintf(stderr, "test_continuum_stability: --write-fixtures needs a folder\n");
        return 2;
    }
    struct CMUnitTest tests[WRITERS];
    size_t n = 0;
    for (int a = 1; a < argc; a++) {
        size_t k = 0;
        while (k < WRITERS && strcmp(argv[a], writers[k].name) != 0) k++;
        if (k == WRITERS) {
            fprintf(stderr, "test_continuum_stability: no fixture '%s' (%s, %s)\n", argv[a],
                    SOLVERS_FIXTURE, EDGES_FIXTURE);
            return 2;
        }
    }
    for (size_t k = 0; k < WRITERS; k++) {
        int wanted = argc == 1;
        for (int a = 1; a < argc; a++) wanted |= strcmp(argv[a], writers[k].name) == 0;
        if (wanted)
            tests[n++] = (struct CMUnitTest){.name = writers[k].name, .test_func = writers[k].write,
                                             .initial_state = argv[0]};
    }
    return _cmocka_run_group_tests("fixtures", tests, n, NULL, NULL);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc > 1 && strcmp(argv[1], "--write-fixtures") == 0)
        return write_fixtures(argc - 2, argv + 2);
    if (argc > 1) {
        fprintf(stderr, "usage: test_continuum_stability [--write-fixtures DIR [NAME...]]\n");
        return 2;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hanging),
        cmocka_unit_test(test_convergence),
        cmocka_unit_test(test_signatures),
        cmocka_unit_test(test_window),
        cmocka_unit_test(test_solvers),
        cmocka_unit_test(test_refined_edges),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
