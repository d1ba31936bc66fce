/* Work-precision benchmark of the integrators: wall time against final position error on
 * reference scenes. Usage: bench_workprecision [DIR [SCENE [PERIODS [METHOD]]]] (DIR default
 * out/bench; SCENE one of the names below or "all", default all; PERIODS the chain scenes' rotation periods,
 * default 20, fewer to measure within a time budget, or P,Q: chain1000 over Q periods, the
 * other chains over P (make bench: 20,2); METHOD one method only, the CSV then named
 * workprecision_SCENE_METHOD.csv). Writes DIR/workprecision_SCENE.csv (one row per run) and
 * DIR/workprecision_summary.csv (times at equal error), and prints the figures.
 *
 * Scenes:
 *  - double_pendulum: the seed's double pendulum (data/scenes/double_pendulum.ini: 2D, l = m =
 *    1/2, released at theta = (1.2, -0.6)), inertial frame, t = 0..20;
 *  - chainN, N = 10, 100, 1000: the 3D chain seeded with its exact N-link steady shape of mode 2
 *    at omega = 4 (whirl_nlink_solve), every link vector turned by 1e-3 rad about the axis
 *    cos(2.385 i) y + sin(2.385 i) (u_i x y) (u_i its direction; deterministic), at rest in the
 *    frame co-rotating at omega, integrated there for 20 rotation periods (t = 40 pi / omega).
 * Error: max over the masses of |x_i(t_end) - x_ref,i(t_end)| [L].
 * Reference: gauss3 on the Cartesian formulation at a step 1/32 (N = 1000: 1/16) of the scene's
 * largest step, confirmed by a second method: gsl-rk8pd at tolerance 1e-13 on the seed
 * formulation (different coordinates and equations) where it is affordable (double pendulum,
 * N = 10), on the Cartesian formulation at N = 100 and 1000. Their distance is the reference floor:
 * errors below 3 times it are not resolved and are left out of the equal-error comparison.
 * Runs: every method of whirl_integrator_methods() on the Cartesian formulation (fixed steps
 * h_max / 2^k for gauss2, gauss3, rk4, gsl-rk4; tolerances 10^-3 .. 10^-13 for rk8 and the
 * adaptive GSL steppers), and the seed formulation with the seed's method gauss2 and with
 * gsl-rk8pd (N <= 10: at N = 100 one seed right-hand side costs 280 Cartesian ones and a run
 * minutes).
 * A method is refined until a run takes longer than the scene's time cap (10-15 s; at N = 1000
 * 10 s per simulated period: rk8 reaches the reference floor), its error is below 1e-11 or
 * 3 times the floor or stalls, or it fails after a success. The program takes about 10 minutes
 * without chain1000; chain1000 over its 20 periods about 100 minutes (its reference 11, the
 * confirmation 2.5). gsl-rk4imp (dense LU of 2 x dim per Newton matrix) only at
 * N <= 10, gsl-msbdf (dense LU of dim) only at N <= 100. Wall time: median of 5 (runs < 0.5 s),
 * 3 (< 3 s) or 1 repeats.
 * Equal error: for each method, log time interpolated linearly in log error between consecutive
 * runs that bracket the level; per level the best whirl method (gauss2, gauss3, rk4, rk8), the
 * best GSL stepper and the best seed-formulation run; where the seed formulation was not run
 * (N > 10) its time is extrapolated as the fastest Cartesian method's time times the measured
 * cost ratio of one right-hand side (printed next to the direct value at N = 2, 10 as a check). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "bench_workprecision"
#include "bench_util.h"

#define PI 3.14159265358979323846
#define MAX_RUNS 16
#define N_LEVELS 3

typedef struct scene {
    const char *name;
    size_t n;
    int dim;
    whirl_frame frame;
    double omega;    /* rate of the steady start and of the frame; 0: the double pendulum */
    double t_end;    /* [T] */
    double h_max;    /* largest fixed step tried */
    double ref_div;  /* reference step = h_max / ref_div */
    int seed_ref;    /* 1: confirm with the seed formulation, 0: with the Cartesian one */
    double time_cap; /* stop refining a method after a run longer than this [s] */
} scene;

typedef struct method {
    const char *label;      /* as written in the CSV */
    const char *integrator; /* whirl_integrator_alloc name */
    whirl_formulation formulation;
    int adaptive;
    size_t max_n; /* run only for N <= max_n (0: always) */
    int family;   /* 0 whirl, 1 GSL, 2 seed formulation */
} method;

static const method methods[] = {
    {"gauss2", "gauss2", WHIRL_FORMULATION_CARTESIAN, 0, 0, 0},
    {"gauss3", "gauss3", WHIRL_FORMULATION_CARTESIAN, 0, 0, 0},
    {"rk4", "rk4", WHIRL_FORMULATION_CARTESIAN, 0, 0, 0},
    {"rk8", "rk8", WHIRL_FORMULATION_CARTESIAN, 1, 0, 0},
    {"gsl-rk8pd", "gsl-rk8pd", WHIRL_FORMULATION_CARTESIAN, 1, 0, 1},
    {"gsl-rkf45", "gsl-rkf45", WHIRL_FORMULATION_CARTESIAN, 1, 0, 1},
    {"gsl-rk4", "gsl-rk4", WHIRL_FORMULATION_CARTESIAN, 0, 0, 1},
    {"gsl-msadams", "gsl-msadams", WHIRL_FORMULATION_CARTESIAN, 1, 0, 1},
    {"gsl-msbdf", "gsl-msbdf", WHIRL_FORMULATION_CARTESIAN, 1, 100, 1},
    {"gsl-rk4imp", "gsl-rk4imp", WHIRL_FORMULATION_CARTESIAN, 1, 10, 1},
    {"seed-gauss2", "gauss2", WHIRL_FORMULATION_SEED, 0, 10, 2},
    {"seed-gsl-rk8pd", "gsl-rk8pd", WHIRL_FORMULATION_SEED, 1, 10, 2},
};
#define N_METHODS (sizeof methods / sizeof methods[0])

static const double levels[N_LEVELS] = {1e-6, 1e-8, 1e-10};

/* One scene's start: chain, model, positions and velocities (3 per mass). */
typedef struct start {
    whirl_chain *chain;
    whirl_model model;
    double *x, *v;
} start;

static void make_start(const scene *sc, start *st)
{
    const size_t n = sc->n;
    st->chain = whirl_chain_alloc_uniform(n, 0);
    st->x = calloc(3 * n, sizeof *st->x);
    st->v = calloc(3 * n, sizeof *st->v);
    if (st->chain == NULL || st->x == NULL || st->v == NULL) bench_die("start");
    st->model = (whirl_model){
        .chain = st->chain, .dim = sc->dim, .frame = sc->frame, .omega = sc->omega};
    if (sc->omega == 0) { /* the seed's double pendulum, from rest */
        const double theta[2] = {1.2, -0.6};
        double px = 0, pz = 0;
        for (size_t i = 0; i < n; i++) {
            px += st->chain->length[i] * sin(theta[i]);
            pz -= st->chain->length[i] * cos(theta[i]);
            st->x[3 * i] = px;
            st->x[3 * i + 2] = pz;
        }
        return;
    }
    if (bench_scene_start(st->chain, sc->omega, st->x) != GSL_SUCCESS) bench_die("steady shape");
}

static void free_start(start *st)
{
    whirl_chain_free(st->chain);
    free(st->x);
    free(st->v);
}

/* One run from the start to t_end: final positions in xf, wall seconds returned (negative on a
 * failure), statistics in *stats. */
static double run_once(const scene *sc, const start *st, const method *m, double h, double tol,
                       double *xf, whirl_integrator_stats *stats)
{
    whirl_dyn *d = whirl_dyn_alloc(&st->model, m->formulation);
    if (d == NULL) bench_die("dyn alloc");
    double *y = malloc(whirl_dyn_size(d) * sizeof *y), *vf = malloc(3 * sc->n * sizeof *vf);
    whirl_integrator *it = whirl_integrator_alloc(m->integrator, d);
    if (y == NULL || vf == NULL || it == NULL) bench_die("run alloc");
    if (whirl_dyn_set_state(d, 0, st->x, st->v, y) != GSL_SUCCESS) bench_die("set_state");
    double t = 0;
    const double t0 = bench_now();
    const int status = whirl_integrator_advance(it, &t, y, sc->t_end, tol > 0 ? 1e-3 : h, tol);
    double secs = bench_now() - t0;
    if (status != GSL_SUCCESS) secs = -1;
    else whirl_dyn_get_state(d, t, y, sc->frame, xf, vf);
    *stats = whirl_integrator_get_stats(it);
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    free(y);
    free(vf);
    return secs;
}

/* The runs of one method on one scene. */
typedef struct curve {
    int count;
    double err[MAX_RUNS], secs[MAX_RUNS], param[MAX_RUNS]; /* param: h or tol */
    double secs_per_step[MAX_RUNS];
} curve;

static double time_at(const curve *c, double e, double floor_err)
{
    return bench_time_at(c->count, c->err, c->secs, e, floor_err);
}

static int repeats_for(double secs) { return secs < 0.5 ? 5 : secs < 3 ? 3 : 1; }

static void run_method(const scene *sc, const start *st, const method *m, const double *xref,
                       double floor_err, FILE *csv, curve *c)
{
    double *xf = malloc(3 * sc->n * sizeof *xf);
    if (xf == NULL) bench_die("alloc");
    c->count = 0;
    int succeeded = 0;
    for (int k = 0; k < MAX_RUNS; k++) {
        const double h = m->adaptive ? 0 : sc->h_max / ldexp(1, k);
        const double tol = m->adaptive ? pow(10, -3 - k) : 0;
        if (m->adaptive && tol < 1e-13 * 0.99) break;
        whirl_integrator_stats s;
        double secs = run_once(sc, st, m, h, tol, xf, &s);
        if (secs < 0) {
            fprintf(csv, "%s,%.6g,%.6g,,,0,%lu,%lu,failed\n", m->label, h, tol, s.steps,
                    s.rhs_evals);
            if (succeeded) break;
            continue;
        }
        succeeded = 1;
        const int reps = repeats_for(secs);
        double t[5] = {secs};
        for (int r = 1; r < reps; r++) t[r] = run_once(sc, st, m, h, tol, xf, &s);
        secs = bench_median(t, reps);
        const double err = bench_max_distance(sc->n, xf, xref);
        fprintf(csv, "%s,%.6g,%.6g,%.6g,%.6g,%d,%lu,%lu,%s\n", m->label, h, tol, err, secs, reps,
                s.steps, s.rhs_evals, err < 3 * floor_err ? "below_floor" : "ok");
        fflush(csv);
        if (c->count < MAX_RUNS) {
            c->err[c->count] = err;
            c->secs[c->count] = secs;
            c->param[c->count] = m->adaptive ? tol : h;
            c->secs_per_step[c->count] = secs / (double)s.steps;
            c->count++;
        }
        printf("  %-14s %s %-9.3g error %9.3g  %8.3g s  %lu steps  %lu rhs\n", m->label,
               m->adaptive ? "tol" : "h  ", m->adaptive ? tol : h, err, secs, s.steps,
               s.rhs_evals);
        fflush(stdout);
        /* refined far enough: slow, past the comparison levels, at the reference floor, or
         * stalled at round-off */
        const int stalled = c->count >= 2 && err > 0.5 * c->err[c->count - 2] && err < 1e-9;
        if (secs > sc->time_cap || err < 3 * floor_err || err < 1e-11 || stalled) break;
    }
    free(xf);
}

/* Median seconds of one right-hand side of the scene's start in formulation f. */
static double rhs_seconds(const start *st, whirl_formulation f, int reps)
{
    whirl_dyn *d = whirl_dyn_alloc(&st->model, f);
    if (d == NULL) bench_die("dyn alloc");
    const size_t size = whirl_dyn_size(d);
    double *y = malloc(size * sizeof *y), *dy = malloc(size * sizeof *dy), t[9];
    if (y == NULL || dy == NULL) bench_die("alloc");
    if (whirl_dyn_set_state(d, 0, st->x, st->v, y) != GSL_SUCCESS) bench_die("set_state");
    const long inner = f == WHIRL_FORMULATION_SEED ? 1 : 100;
    for (int r = 0; r < reps; r++) {
        const double t0 = bench_now();
        for (long k = 0; k < inner; k++) whirl_dyn_rhs(0, y, dy, d);
        t[r] = (bench_now() - t0) / (double)inner;
    }
    free(y);
    free(dy);
    whirl_dyn_free(d);
    return bench_median(t, reps);
}

static void run_scene(const scene *sc, const char *dir, FILE *summary, const char *only_method)
{
    start st;
    make_start(sc, &st);
    const size_t n = sc->n;
    printf("== %s: N = %zu, %dD, %s frame, t_end = %.6g\n", sc->name, n, sc->dim,
           sc->frame == WHIRL_FRAME_ROTATING ? "co-rotating" : "inertial", sc->t_end);
    /* the reference and its confirmation */
    double *xref = malloc(3 * n * sizeof *xref), *xconf = malloc(3 * n * sizeof *xconf);
    if (xref == NULL || xconf == NULL) bench_die("alloc");
    const method ref = {"reference", "gauss3", WHIRL_FORMULATION_CARTESIAN, 0, 0, 0};
    const method conf = {"confirmation", "gsl-rk8pd",
                         sc->seed_ref ? WHIRL_FORMULATION_SEED : WHIRL_FORMULATION_CARTESIAN, 1,
                         0, 1};
    whirl_integrator_stats s;
    const double h_ref = sc->h_max / sc->ref_div;
    const double t_ref = run_once(sc, &st, &ref, h_ref, 0, xref, &s);
    if (t_ref < 0) bench_die("reference run");
    const double t_conf = run_once(sc, &st, &conf, 0, 1e-13, xconf, &s);
    if (t_conf < 0) bench_die("confirmation run");
    const double floor_err = bench_max_distance(n, xconf, xref);
    printf("  reference gauss3 h = %.4g (%.3g s); confirmed by gsl-rk8pd tol 1e-13 on the %s "
           "formulation (%.3g s): distance %.3g (floor)\n",
           h_ref, t_ref, sc->seed_ref ? "seed" : "Cartesian", t_conf, floor_err);
    char name[256];
    snprintf(name, sizeof name, "workprecision_%s%s%s.csv", sc->name, only_method ? "_" : "",
             only_method ? only_method : "");
    FILE *csv = bench_open_csv(dir, name);
    fprintf(csv, "# %s: N = %zu, dim %d, %s frame, t_end %.17g; error = max_i |x_i - x_ref,i|\n",
            sc->name, n, sc->dim, sc->frame == WHIRL_FRAME_ROTATING ? "rotating" : "inertial",
            sc->t_end);
    fprintf(csv, "# reference gauss3 h %.6g; confirmation gsl-rk8pd tol 1e-13 (%s): distance "
                 "%.6g\n",
            h_ref, sc->seed_ref ? "seed formulation" : "Cartesian", floor_err);
    fprintf(csv, "# load average at start %.2f\n", bench_load_average());
    fprintf(csv, "method,h,tol,error,seconds,repeats,steps,rhs_evals,note\n");
    static curve curves[N_METHODS];
    for (size_t k = 0; k < N_METHODS; k++) {
        curves[k].count = 0;
        if (methods[k].max_n != 0 && n > methods[k].max_n) continue;
        if (only_method != NULL && strcmp(only_method, methods[k].label) != 0) continue;
        run_method(sc, &st, &methods[k], xref, floor_err, csv, &curves[k]);
    }
    fclose(csv);
    /* cost of one right-hand side of the seed formulation relative to the Cartesian one */
    const double rhs_seed = rhs_seconds(&st, WHIRL_FORMULATION_SEED, n > 100 ? 1 : 5);
    const double rhs_cart = rhs_seconds(&st, WHIRL_FORMULATION_CARTESIAN, 9);
    const double seed_cost_ratio = rhs_seed / rhs_cart;
    printf("  one right-hand side: seed formulation %.3g s, Cartesian %.3g s, ratio %.4g\n",
           rhs_seed, rhs_cart, seed_cost_ratio);
    fprintf(summary, "# %s: right-hand side seed %.6g s, Cartesian %.6g s\n", sc->name, rhs_seed,
            rhs_cart);
    for (int l = 0; l < N_LEVELS; l++) {
        const double e = levels[l];
        double best[3] = {NAN, NAN, NAN};
        const char *who[3] = {"-", "-", "-"};
        for (size_t k = 0; k < N_METHODS; k++) {
            const double t = time_at(&curves[k], e, floor_err);
            const int f = methods[k].family;
            if (t < best[f] || (isnan(best[f]) && !isnan(t))) best[f] = t, who[f] = methods[k].label;
        }
        /* the seed formulation where it was not run (N > 10): the fastest Cartesian run's
         * time times the cost ratio of one right-hand side (same method, same ODE, about the
         * same number of evaluations: at N = 2 and 10, where both are run, seed-gauss2 and
         * seed-gsl-rk8pd match their Cartesian twins' errors, and the extrapolated times came
         * within a factor 1.4 of the measured ones) */
        double extrapolated = NAN;
        const char *extrapolated_from = "-";
        for (size_t k = 0; k < N_METHODS; k++) {
            const double t = time_at(&curves[k], e, floor_err) * seed_cost_ratio;
            if (methods[k].family != 2 && (t < extrapolated || (isnan(extrapolated) && !isnan(t))))
                extrapolated = t, extrapolated_from = methods[k].label;
        }
        const int seed_direct = !isnan(best[2]);
        if (!seed_direct) best[2] = extrapolated, who[2] = extrapolated_from;
        /* a level some family did not reach is left empty */
        char cell[5][32];
        const double values[5] = {best[0], best[1], best[2], best[1] / best[0],
                                  best[2] / best[0]};
        for (int q = 0; q < 5; q++) {
            cell[q][0] = '\0';
            if (isfinite(values[q])) snprintf(cell[q], sizeof cell[q], "%.6g", values[q]);
        }
        fprintf(summary, "%s,%zu,%.0e,%s,%s,%s,%s,%s,%s,%d,%s,%s\n", sc->name, n, e, who[0],
                cell[0], who[1], cell[1], who[2], cell[2], !seed_direct, cell[3], cell[4]);
        printf("  error %.0e: best whirl %s %.3g s; best GSL %s %.3g s (ratio %.3g); seed %s%s "
               "%.3g s (ratio %.3g)\n",
               e, who[0], best[0], who[1], best[1], best[1] / best[0], who[2],
               seed_direct ? "" : " (extrapolated)", best[2], best[2] / best[0]);
        if (seed_direct)
            printf("    check of the extrapolation: %s x right-hand side ratio = %.3g s\n",
                   extrapolated_from, extrapolated);
    }
    fflush(summary);
    free(xref);
    free(xconf);
    free_start(&st);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    const char *only = argc > 2 ? argv[2] : NULL;
    const char *only_method = argc > 4 ? argv[4] : NULL;
    /* rotation periods of the chain scenes: 20 unless argv[3] says otherwise (a shorter run to
     * measure within a time budget); "P,Q": chain1000 over Q periods, the others over P */
    const char *pspec = argc > 3 ? argv[3] : "20";
    char *rest;
    const double periods = strtod(pspec, &rest);
    const double periods1000 = *rest == ',' ? strtod(rest + 1, &rest) : periods;
    if (!(periods > 0) || !(periods1000 > 0) || *rest != '\0' || !isfinite(periods) ||
        !isfinite(periods1000)) {
        fprintf(stderr, "bench_workprecision: periods '%s': want a number > 0 or two, P,Q\n",
                pspec);
        return 1;
    }
    const double period20 = periods * 2 * PI / 4.0, period1000 = periods1000 * 2 * PI / 4.0;
    const scene scenes[] = {
        {"double_pendulum", 2, 2, WHIRL_FRAME_INERTIAL, 0, 20, 0.1, 32, 1, 10},
        {"chain10", 10, 3, WHIRL_FRAME_ROTATING, 4, period20, 0.1, 32, 1, 10},
        {"chain100", 100, 3, WHIRL_FRAME_ROTATING, 4, period20, 0.01, 32, 0, 15},
        {"chain1000", 1000, 3, WHIRL_FRAME_ROTATING, 4, period1000, 0.001, 16, 0, 10 * periods1000},
    };
    printf("load average at start (other jobs share the cores): %.2f\n", bench_load_average());
    char name[256];
    snprintf(name, sizeof name, "workprecision_summary%s%s.csv", only ? "_" : "", only ? only : "");
    FILE *summary = bench_open_csv(dir, name);
    fprintf(summary, "# wall seconds at equal final position error (log-log interpolation)\n");
    fprintf(summary, "scene,n,error,best_whirl,whirl_s,best_gsl,gsl_s,seed,seed_s,"
                     "seed_extrapolated,gsl_over_whirl,seed_over_whirl\n");
    int ran = 0;
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        if (only != NULL && strcmp(only, "all") != 0 && strcmp(only, scenes[k].name) != 0)
            continue;
        run_scene(&scenes[k], dir, summary, only_method);
        ran++;
    }
    fclose(summary);
    if (ran == 0) {
        fprintf(stderr, "bench_workprecision: unknown scene '%s'\n", only);
        return 1;
    }
    return 0;
}
