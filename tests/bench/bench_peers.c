/* whirl against the systems a user would otherwise reach for, side by side in one run.
 * Usage: bench_peers [DIR [quick|full [CONTENDER]]] (CONTENDER: run the scenes with whirl rk8
 * and that contender only, e.g. arkode-dp745), bench_peers DIR steps1000 or bench_peers DIR
 * arkode [ROUNDS] (see below). Writes DIR/peers_SCENE.csv (every run),
 * DIR/peers_steps.csv (cost per step), DIR/peers_seed.csv, DIR/peers_checks.csv (the models'
 * agreement) and appends the headline ratios to DIR/headline.csv; prints the figures.
 * quick (for make bench-quick): tolerances from 1e-4 and fixed steps from h_max / 4; MuJoCo at
 * N = 100 on chain100short (the same start over 2 periods, whirl rk8 alongside) instead of
 * chain100, refined only to below 1e-6; ARKODE without the tables that were never the best
 * (dp745 with projection, Verner without); shorter caps; 3 repeats of runs under 0.3 s, one
 * otherwise; the seed formulation over one period; no step cost at N = 1000.
 *
 * Scenes: chain10 and chain100 of bench_workprecision (the exact N-link mode-2 steady shape at
 * omega = 4, every link turned by 1e-3 rad, at rest in the frame co-rotating at omega; t_end =
 * 20 rotation periods, 10 pi). The pivot is fixed, so the co-rotating frame is a change of
 * coordinates only: every contender integrates its own model, and the error is the max over the
 * masses of |x_i(t_end) - x_ref,i(t_end)| in the inertial frame.
 * Reference: whirl gauss3 at a step h_max / 32 confirmed by GSL rk8pd at tolerance 1e-13 (both on
 * whirl's Cartesian right-hand side); their distance is the floor: errors below 3 times it are
 * left out of the comparison.
 *
 * Contenders (each refined from a coarse setting until a run is slower than the scene's cap, its
 * error is below 5e-9 or 3 times the floor, stalls, or fails twice in a row after a success):
 *  - whirl rk8 (tolerance 10^-3 .. 10^-13) and GSL rk8pd on the same right-hand side;
 *  - SUNDIALS ARKODE ERKStep (tolerance 10^-3 .. 10^-13, relative = absolute) with the explicit
 *    tables Dormand-Prince 7-4-5, Verner 8-5-6 and Fehlberg 13-7-8, each without and with
 *    whirl_dyn_project after every step (ERKStepSetPostprocessStepFn); the best table per level
 *    counts;
 *  - SUNDIALS CVODE Adams (orders up to 12, fixed-point iteration) without projection;
 *    SUNDIALS runs are given up (failed) after twice the scene's cap;
 *  - MuJoCo with its RK4 integrator (its Euler and implicit integrators are first order) at
 *    fixed steps h_max / 2^k, cap 15 times the scene's: the same point-mass chain as nested
 *    bodies hung by hinge pairs, written as XML files of 40 bodies joined by <include> (its
 *    parser refuses nesting deeper than 100); tests/lib/peer_glue.h has the model and its check:
 *    positions and velocities equal to whirl's to 1e-12, energy to 1e-10, the hanging chain's
 *    normal-mode frequencies to 1e-10 or, where larger, the eigensolver's bound eps kappa
 *    (kappa = 2e8 at N = 100, where the highest modes agree to 3.5e-10).
 * SUNDIALS contenders call whirl_dyn_rhs, so their model is whirl's by construction; the glue is
 * checked by their errors converging to the reference.
 * Wall time: contenders interleaved, median of 5 repeats (runs < 0.5 s), 3 (< 3 s) or 1.
 * Equal error: log time interpolated linearly in log error between consecutive runs bracketing
 * the level (1e-6, 1e-8).
 *
 * Right-hand side: ns per link at N = 10^4 (as bench_scaling, which has the whole range).
 * Cost per step: a MuJoCo RK4 step against a whirl rk4 step (same step, same start) at N = 10,
 * 100, 1000, interleaved, medians of 5 (N = 1000: 3, MuJoCo over 2 steps of about 10 s each;
 * left out of the quick run).
 * Seed formulation: gauss2 at equal step (h = 0.01) on chain100 over 2 rotation periods (quick: 1)
 * on the seed formulation (angles, dense mass matrix) and on the Cartesian one; the distance of
 * their end positions is printed (same method and step, same motion; Runge-Kutta methods are
 * not invariant under the change of coordinates, so it is the size of the step's error).
 * steps1000: the cost per step at N = 1000 only (as in the full run; DIR/peers_steps_1000.csv),
 * which make bench adds to the quick run.
 * arkode (ROUNDS default 15, at most 31): whirl rk8 against ARKODE with projection (its three
 * tables) on chain100 only, the ratio at 1e-6 and 1e-8 with its spread: after the sweep (from
 * tolerance 1e-4), ROUNDS rounds, each running once in turn every setting of every contender
 * whose error brackets a level;
 * per round the best table's time over whirl's at equal error (the ratio of that round), and
 * over all rounds the median, quartiles and range of those ratios and the ratio of the median
 * times; also the right-hand sides at equal error (interpolated as the times) and the time per
 * right-hand side, the two factors of the ratio. Writes DIR/peers_arkode_rounds.csv and appends
 * the medians to DIR/headline.csv.
 * A peer whose package is missing at build time (MuJoCo: mujoco/mujoco.h; SUNDIALS: arkode and
 * cvode headers) is reported as skipped, row by row. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "bench_peers"
#include "bench_util.h"

#include "peer_glue.h"

#define PI 3.14159265358979323846
#define MAX_RUNS 16
#define N_LEVELS 2
static const double levels[N_LEVELS] = {1e-6, 1e-8};

typedef enum { K_WHIRL, K_ARK, K_CVODE, K_MUJOCO } kind;

typedef struct contender {
    const char *label;
    kind kind;
    const char *method; /* whirl: integrator name */
    int table;          /* ARKODE: table id */
    int project;        /* ARKODE: whirl_dyn_project after every step */
    int adaptive;       /* 1: tolerance sweep, 0: step sweep */
    const char *group;  /* the row of the summary it competes in */
    int full_only;      /* 1: left out of the quick run (never the best in the full one) */
} contender;

#ifdef WHIRL_HAVE_SUNDIALS
#define ARK(label, table, proj, group, full_only) \
    {label, K_ARK, NULL, table, proj, 1, group, full_only}
#endif

static const contender contenders[] = {
    {"whirl-rk8", K_WHIRL, "rk8", 0, 0, 1, "whirl", 0},
    {"gsl-rk8pd", K_WHIRL, "gsl-rk8pd", 0, 0, 1, "gsl", 0},
#ifdef WHIRL_HAVE_SUNDIALS
    ARK("arkode-dp745-proj", ARKODE_DORMAND_PRINCE_7_4_5, 1, "arkode-proj", 1),
    ARK("arkode-verner856-proj", ARKODE_VERNER_8_5_6, 1, "arkode-proj", 0),
    ARK("arkode-fehlberg1378-proj", ARKODE_FEHLBERG_13_7_8, 1, "arkode-proj", 0),
    ARK("arkode-dp745", ARKODE_DORMAND_PRINCE_7_4_5, 0, "arkode", 0),
    ARK("arkode-verner856", ARKODE_VERNER_8_5_6, 0, "arkode", 1),
    ARK("arkode-fehlberg1378", ARKODE_FEHLBERG_13_7_8, 0, "arkode", 0),
    {"cvode-adams", K_CVODE, NULL, 0, 0, 1, "cvode", 0},
#endif
#ifdef WHIRL_HAVE_MUJOCO
    {"mujoco-rk4", K_MUJOCO, NULL, 0, 0, 0, "mujoco", 0},
#endif
};
#define N_CONTENDERS (sizeof contenders / sizeof contenders[0])

/* The summary's rows: group, what it is, its target ratio against whirl (0: none) */
typedef struct group {
    const char *name, *what;
    double target;
    int available;
} group;

static const group groups[] = {
    {"gsl", "GSL rk8pd (same right-hand side)", 0, 1},
#ifdef WHIRL_HAVE_SUNDIALS
    {"arkode-proj", "ARKODE ERK (best table) with projection", 6, 1},
    {"arkode", "ARKODE ERK (best table) without projection", 0, 1},
    {"cvode", "CVODE Adams", 0, 1},
#else
    {"arkode-proj", "ARKODE ERK (best table) with projection", 6, 0},
    {"arkode", "ARKODE ERK (best table) without projection", 0, 0},
    {"cvode", "CVODE Adams", 0, 0},
#endif
#ifdef WHIRL_HAVE_MUJOCO
    {"mujoco", "MuJoCo RK4", 100, 1},
#else
    {"mujoco", "MuJoCo RK4", 100, 0},
#endif
};
#define N_GROUPS (sizeof groups / sizeof groups[0])

typedef struct scene {
    const char *name;
    size_t n;
    double t_end; /* [T] */
    double h_max; /* coarsest fixed step */
    double cap;   /* stop refining after a run longer than this [s] */
    const char *with; /* NULL: every contender; else whirl rk8 and this group only */
    int no_mujoco;    /* 1: MuJoCo left out (run on a shorter scene of its own) */
} scene;

#ifdef WHIRL_HAVE_MUJOCO
typedef struct mj_chain {
    mjModel *m;
    mjData *d;
    double *qpos, *qvel; /* the scene's start, 2 N each */
} mj_chain;
#endif

/* One scene's start and everything the runs share. */
typedef struct setup {
    const scene *sc;
    whirl_chain *chain;
    whirl_model model;
    double *y0;       /* whirl's state at t = 0 */
    double *xi, *vi;  /* inertial positions and velocities at t = 0 (3 per mass) */
    double *xref;     /* reference end positions, inertial */
    double floor_err; /* distance reference - confirmation */
    whirl_dyn *dyn;   /* Cartesian dynamics (used by the SUNDIALS runs) */
#ifdef WHIRL_HAVE_SUNDIALS
    SUNContext ctx;
#endif
#ifdef WHIRL_HAVE_MUJOCO
    peer_mj mj;
#endif
} setup;

typedef struct run_stats {
    long steps, rhs;
    double constraint; /* whirl's state only: link length drift at the end (-1: not known) */
} run_stats;

/* ---------------- whirl and GSL through whirl's integrator interface ---------------- */

static double run_whirl(const setup *s, const char *method, whirl_formulation f, double h,
                        double tol, double t_end, double *xf, run_stats *rs)
{
    whirl_dyn *d = whirl_dyn_alloc(&s->model, f);
    if (d == NULL) bench_die("dyn alloc");
    const size_t size = whirl_dyn_size(d), n = s->sc->n;
    double *y = malloc(size * sizeof *y), *vf = malloc(3 * n * sizeof *vf);
    double *x0 = malloc(3 * n * sizeof *x0), *v0 = malloc(3 * n * sizeof *v0);
    whirl_integrator *it = whirl_integrator_alloc(method, d);
    if (y == NULL || vf == NULL || x0 == NULL || v0 == NULL || it == NULL) bench_die("alloc");
    /* the start in the model's (co-rotating) frame */
    if (whirl_dyn_get_state(s->dyn, 0, s->y0, s->model.frame, x0, v0) != GSL_SUCCESS ||
        whirl_dyn_set_state(d, 0, x0, v0, y) != GSL_SUCCESS)
        bench_die("set_state");
    double t = 0;
    const double t0 = bench_now();
    const int status = whirl_integrator_advance(it, &t, y, t_end, tol > 0 ? 1e-3 : h, tol);
    double secs = bench_now() - t0;
    if (status != GSL_SUCCESS) secs = -1;
    else whirl_dyn_get_state(d, t, y, WHIRL_FRAME_INERTIAL, xf, vf);
    const whirl_integrator_stats st = whirl_integrator_get_stats(it);
    rs->steps = (long)st.steps;
    rs->rhs = (long)st.rhs_evals;
    rs->constraint = -1;
    whirl_dyn_diagnostics diag;
    if (f == WHIRL_FORMULATION_CARTESIAN && status == GSL_SUCCESS &&
        whirl_dyn_diagnose(d, t, y, &diag) == GSL_SUCCESS)
        rs->constraint = diag.constraint;
    whirl_integrator_free(it);
    whirl_dyn_free(d);
    free(y);
    free(vf);
    free(x0);
    free(v0);
    return secs;
}

/* ---------------- SUNDIALS ---------------- */

#ifdef WHIRL_HAVE_SUNDIALS
static double run_sundials(const setup *s, const contender *c, double tol, double *xf,
                           run_stats *rs)
{
    const size_t size = whirl_dyn_size(s->dyn), n = s->sc->n;
    double *y = malloc(size * sizeof *y), *vf = malloc(3 * n * sizeof *vf);
    if (y == NULL || vf == NULL) bench_die("alloc");
    memcpy(y, s->y0, size * sizeof *y);
    const double t0 = bench_now();
    const int status =
        peer_sun_run(s->ctx, s->dyn, y, s->sc->t_end, c->kind == K_ARK ? c->table : -1,
                     c->project, tol, 2 * s->sc->cap, &rs->steps, &rs->rhs);
    double secs = bench_now() - t0;
    if (status == -2) {
        fprintf(stderr, "%s: cannot set up %s\n", BENCH_NAME, c->label);
        exit(1);
    }
    rs->constraint = -1;
    whirl_dyn_diagnostics diag;
    if (status != 0) secs = -1;
    else {
        whirl_dyn_get_state(s->dyn, s->sc->t_end, y, WHIRL_FRAME_INERTIAL, xf, vf);
        if (whirl_dyn_diagnose(s->dyn, s->sc->t_end, y, &diag) == GSL_SUCCESS)
            rs->constraint = diag.constraint;
    }
    free(y);
    free(vf);
    return secs;
}
#endif

/* ---------------- MuJoCo ---------------- */

#ifdef WHIRL_HAVE_MUJOCO
/* Loads the chain into MuJoCo (peer_mj_load), prints and records the check; exits if the models
 * differ. */
static void mj_chain_load(const whirl_chain *c, const char *dir, const double *x, const double *v,
                          double energy, int frequencies, peer_mj *mc, FILE *checks)
{
    char msg[2048];
    peer_mj_check k;
    const double t0 = bench_now();
    if (peer_mj_load(c, dir, x, v, energy, frequencies, mc, &k, msg, sizeof msg) != 0) {
        fprintf(stderr, "%s: %s\n", BENCH_NAME, msg);
        exit(1);
    }
    printf("  MuJoCo model N = %zu (%zu files, loaded and checked in %.3g s): positions %.2g, "
           "velocities %.2g, energy %.17g vs whirl %.17g (difference %.2g)\n",
           c->n, k.files, bench_now() - t0, k.dx, k.dv, k.energy, energy, k.de);
    if (frequencies)
        printf("  MuJoCo hanging normal-mode frequencies %.10g .. %.10g: largest relative "
               "difference from whirl's %.2g (mode %zu); MuJoCo's joint-space mass matrix has "
               "condition number %.2g (eigensolver bound eps kappa = %.2g)\n",
               k.freq_lo, k.freq_hi, k.dfreq, k.worst_mode, k.kappa, DBL_EPSILON * k.kappa);
    fprintf(checks, "mujoco,%zu,%.3g,%.3g,%.3g,%.3g,%.3g\n", c->n, k.dx, k.dv, k.de, k.dfreq,
            k.kappa);
    fflush(checks);
    if (!peer_mj_agrees(&k)) {
        fprintf(stderr, "%s: the MuJoCo model of N = %zu differs from whirl's\n", BENCH_NAME,
                c->n);
        exit(1);
    }
}

static double run_mujoco(const setup *s, double h_try, double *xf, run_stats *rs)
{
    const long steps = lround(ceil(s->sc->t_end / h_try * (1 - 1e-12)));
    rs->steps = steps;
    rs->rhs = 4 * steps;
    rs->constraint = -1;
    return peer_mj_run((peer_mj *)&s->mj, s->sc->t_end, steps, xf);
}
#endif

/* ---------------- runs and the comparison ---------------- */

static double run_contender(const setup *s, const contender *c, double param, double *xf,
                            run_stats *rs)
{
    switch (c->kind) {
    case K_WHIRL:
        return run_whirl(s, c->method, WHIRL_FORMULATION_CARTESIAN, c->adaptive ? 0 : param,
                         c->adaptive ? param : 0, s->sc->t_end, xf, rs);
#ifdef WHIRL_HAVE_SUNDIALS
    case K_ARK:
    case K_CVODE:
        return run_sundials(s, c, param, xf, rs);
#endif
#ifdef WHIRL_HAVE_MUJOCO
    case K_MUJOCO:
        return run_mujoco(s, param, xf, rs);
#endif
    default:
        return -1;
    }
}

/* The runs of one contender on one scene. */
typedef struct curve {
    int count;
    double err[MAX_RUNS], param[MAX_RUNS], constraint[MAX_RUNS];
    double times[MAX_RUNS][5];
    int reps[MAX_RUNS], done[MAX_RUNS];
    long steps[MAX_RUNS], rhs[MAX_RUNS];
    double secs[MAX_RUNS]; /* median */
} curve;

static int repeats_for(double secs, int quick)
{
    if (quick) return secs < 0.3 ? 3 : 1;
    return secs < 0.5 ? 5 : secs < 3 ? 3 : 1;
}

static double time_at(const curve *c, double e, double floor_err)
{
    return bench_time_at(c->count, c->err, c->secs, e, floor_err);
}

/* First pass: refine the contender's setting run by run (one run each). */
static void sweep(const setup *s, const contender *c, int quick, curve *cv)
{
    const size_t n = s->sc->n;
    double *xf = malloc(3 * n * sizeof *xf);
    if (xf == NULL) bench_die("alloc");
    cv->count = 0;
    int succeeded = 0, failures = 0;
    /* quick: from tolerance 1e-4 (the levels are 1e-6 and 1e-8), and fixed steps from h_max / 4
     * (MuJoCo's RK4 errors there are above 1e-4) */
    for (int k = quick ? (c->adaptive ? 1 : 2) : 0; k < MAX_RUNS; k++) {
        const double param = c->adaptive ? pow(10, -3 - k) : s->sc->h_max / ldexp(1, k);
        if (c->adaptive && param < 1e-13 * 0.99) break;
        run_stats rs;
        const double secs = run_contender(s, c, param, xf, &rs);
        if (secs < 0) {
            printf("  %-26s %s %-9.3g failed\n", c->label, c->adaptive ? "tol" : "h  ", param);
            if (succeeded && ++failures == 2) break;
            continue;
        }
        succeeded = 1;
        failures = 0;
        const int j = cv->count++;
        cv->param[j] = param;
        cv->err[j] = bench_max_distance(n, xf, s->xref);
        cv->times[j][0] = secs;
        cv->reps[j] = 1;
        cv->steps[j] = rs.steps;
        cv->rhs[j] = rs.rhs;
        cv->constraint[j] = rs.constraint;
        printf("  %-26s %s %-9.3g error %9.3g  %8.3g s (first run)\n", c->label,
               c->adaptive ? "tol" : "h  ", param, cv->err[j], secs);
        const int stalled = j >= 1 && cv->err[j] > 0.5 * cv->err[j - 1] && cv->err[j] < 1e-9;
        /* MuJoCo's runs near 1e-6 take minutes at N = 100: a longer cap in the full run */
        const double cap = c->kind == K_MUJOCO && !quick ? 15 * s->sc->cap : s->sc->cap;
        /* quick: MuJoCo only to below 1e-6 (each halving doubles minutes of runs) */
        const int enough = quick && s->sc->with != NULL && c->kind == K_MUJOCO &&
                           cv->err[j] < 3e-7;
        if (enough || secs > cap || cv->err[j] < 5e-9 || cv->err[j] < 3 * s->floor_err || stalled)
            break;
    }
    free(xf);
}

/* Medians: every run repeated in turn with all the other contenders' runs (interleaved). */
static void repeat_interleaved(const setup *s, curve *curves, int quick)
{
    double *xf = malloc(3 * s->sc->n * sizeof *xf);
    if (xf == NULL) bench_die("alloc");
    for (int r = 1; r < 5; r++)
        for (size_t k = 0; k < N_CONTENDERS; k++)
            for (int j = 0; j < curves[k].count; j++) {
                curve *cv = &curves[k];
                if (r >= repeats_for(cv->times[j][0], quick)) continue;
                run_stats rs;
                const double secs = run_contender(s, &contenders[k], cv->param[j], xf, &rs);
                if (secs >= 0) cv->times[j][cv->reps[j]++] = secs;
            }
    for (size_t k = 0; k < N_CONTENDERS; k++)
        for (int j = 0; j < curves[k].count; j++)
            curves[k].secs[j] = bench_median(curves[k].times[j], curves[k].reps[j]);
    free(xf);
}

static void setup_scene(const scene *sc, const char *dir, FILE *checks, setup *s)
{
    const size_t n = sc->n;
    memset(s, 0, sizeof *s);
    s->sc = sc;
    s->chain = whirl_chain_alloc_uniform(n, 0);
    if (s->chain == NULL) bench_die("chain");
    s->model = (whirl_model){
        .chain = s->chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 4};
    s->dyn = whirl_dyn_alloc(&s->model, WHIRL_FORMULATION_CARTESIAN);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v);
    s->y0 = malloc(whirl_dyn_size(s->dyn) * sizeof *s->y0);
    s->xi = malloc(3 * n * sizeof *s->xi);
    s->vi = malloc(3 * n * sizeof *s->vi);
    s->xref = malloc(3 * n * sizeof *s->xref);
    double *xconf = malloc(3 * n * sizeof *xconf);
    if (s->dyn == NULL || x == NULL || v == NULL || s->y0 == NULL || s->xi == NULL ||
        s->vi == NULL || s->xref == NULL || xconf == NULL)
        bench_die("alloc");
    if (bench_scene_start(s->chain, s->model.omega, x) != GSL_SUCCESS) bench_die("steady shape");
    if (whirl_dyn_set_state(s->dyn, 0, x, v, s->y0) != GSL_SUCCESS ||
        whirl_dyn_get_state(s->dyn, 0, s->y0, WHIRL_FRAME_INERTIAL, s->xi, s->vi) != GSL_SUCCESS)
        bench_die("set_state");
    run_stats rs;
    const double t_ref = run_whirl(s, "gauss3", WHIRL_FORMULATION_CARTESIAN, sc->h_max / 32, 0,
                                   sc->t_end, s->xref, &rs);
    const double t_conf = run_whirl(s, "gsl-rk8pd", WHIRL_FORMULATION_CARTESIAN, 0, 1e-13,
                                    sc->t_end, xconf, &rs);
    if (t_ref < 0 || t_conf < 0) bench_die("reference run");
    s->floor_err = bench_max_distance(n, xconf, s->xref);
    printf("== %s: N = %zu, t_end = %.6g; reference gauss3 h = %.4g (%.3g s), confirmed by "
           "gsl-rk8pd tol 1e-13 (%.3g s): distance %.3g (floor)\n",
           sc->name, n, sc->t_end, sc->h_max / 32, t_ref, t_conf, s->floor_err);
#ifdef WHIRL_HAVE_SUNDIALS
    if (SUNContext_Create(NULL, &s->ctx) != 0) bench_die("SUNContext_Create");
#endif
#ifdef WHIRL_HAVE_MUJOCO
    whirl_dyn_diagnostics diag;
    if (whirl_dyn_diagnose(s->dyn, 0, s->y0, &diag) != GSL_SUCCESS) bench_die("diagnose");
    mj_chain_load(s->chain, dir, s->xi, s->vi, diag.energy, 1, &s->mj, checks);
#else
    (void)dir;
    (void)checks;
#endif
    free(x);
    free(v);
    free(xconf);
}

static void free_setup(setup *s)
{
#ifdef WHIRL_HAVE_MUJOCO
    peer_mj_free(&s->mj);
#endif
#ifdef WHIRL_HAVE_SUNDIALS
    SUNContext_Free(&s->ctx);
#endif
    whirl_dyn_free(s->dyn);
    whirl_chain_free(s->chain);
    free(s->y0), free(s->xi), free(s->vi), free(s->xref);
}

/* headline.csv: key, what, value, target (empty: none), met (yes/no/empty) */
static void headline(FILE *fp, const char *key, const char *what, double value, double target)
{
    if (!isfinite(value)) {
        fprintf(fp, "%s,%s,,,level not bracketed\n", key, what);
        return;
    }
    if (target > 0)
        fprintf(fp, "%s,%s,%.3g,>= %g,%s\n", key, what, value, target,
                value >= target ? "met" : "not met");
    else fprintf(fp, "%s,%s,%.3g,,\n", key, what, value);
}

static void run_scene(const scene *sc, const char *dir, int quick, const char *only, FILE *checks,
                      FILE *head)
{
    setup s;
    setup_scene(sc, dir, checks, &s);
    static curve curves[N_CONTENDERS];
    for (size_t k = 0; k < N_CONTENDERS; k++) {
        curves[k].count = 0;
        if (quick && contenders[k].full_only) continue;
        if (k != 0 && sc->with != NULL && strcmp(sc->with, contenders[k].group) != 0) continue;
        if (sc->no_mujoco && contenders[k].kind == K_MUJOCO) continue;
        if (k == 0 || only == NULL || strcmp(only, contenders[k].label) == 0)
            sweep(&s, &contenders[k], quick, &curves[k]);
    }
    repeat_interleaved(&s, curves, quick);
    char name[256];
    snprintf(name, sizeof name, "peers_%s.csv", sc->name);
    FILE *csv = bench_open_csv(dir, name);
    fprintf(csv, "# %s: N = %zu, t_end %.17g, error = max_i |x_i - x_ref,i| (inertial); "
                 "floor %.6g; load average %.2f\n",
            sc->name, sc->n, sc->t_end, s.floor_err, bench_load_average());
    fprintf(csv, "contender,setting,error,seconds,repeats,steps,rhs_evals,constraint\n");
    for (size_t k = 0; k < N_CONTENDERS; k++) {
        const curve *cv = &curves[k];
        for (int j = 0; j < cv->count; j++) {
            fprintf(csv, "%s,%.6g,%.6g,%.6g,%d,%ld,%ld,%.3g\n", contenders[k].label,
                    cv->param[j], cv->err[j], cv->secs[j], cv->reps[j], cv->steps[j],
                    cv->rhs[j], cv->constraint[j]);
            printf("  %-26s %s %-9.3g error %9.3g  %8.3g s (%d)  %ld steps  %ld rhs", 
                   contenders[k].label, contenders[k].adaptive ? "tol" : "h  ", cv->param[j],
                   cv->err[j], cv->secs[j], cv->reps[j], cv->steps[j], cv->rhs[j]);
            if (cv->constraint[j] >= 0) printf("  drift %.2g", cv->constraint[j]);
            printf("\n");
        }
    }
    fclose(csv);
    for (int l = 0; l < N_LEVELS; l++) {
        const double e = levels[l];
        if (quick && sc->with != NULL && e < 1e-6) continue; /* refined to 1e-6 only */
        double t_whirl = time_at(&curves[0], e, s.floor_err);
        printf("  error %.0e: whirl rk8 %.3g s\n", e, t_whirl);
        for (size_t g = 0; g < N_GROUPS; g++) {
            if (sc->with != NULL && strcmp(sc->with, groups[g].name) != 0) continue;
            if (sc->no_mujoco && strcmp(groups[g].name, "mujoco") == 0) continue;
            char key[128], what[256];
            snprintf(key, sizeof key, "%s_%s_%.0e", groups[g].name, sc->name, e);
            /* no commas: headline.csv is split on them */
            snprintf(what, sizeof what, "%s / whirl rk8; N = %zu; %.0f periods; error %.0e",
                     groups[g].what, sc->n, sc->t_end * 4 / (2 * PI), e);
            if (!groups[g].available) {
                printf("    %-45s skipped: package missing at build time\n", groups[g].what);
                fprintf(head, "%s,%s,,,skipped: package missing\n", key, what);
                continue;
            }
            double best = NAN;
            const char *who = "-";
            for (size_t k = 0; k < N_CONTENDERS; k++) {
                if (strcmp(contenders[k].group, groups[g].name) != 0) continue;
                const double t = time_at(&curves[k], e, s.floor_err);
                if (t < best || (isnan(best) && !isnan(t))) best = t, who = contenders[k].label;
            }
            const double ratio = best / t_whirl;
            printf("    %-45s %-26s %8.3g s  ratio %.3g\n", groups[g].what, who, best, ratio);
            /* the targets are set at N = 100 */
            headline(head, key, what, ratio, sc->n == 100 ? groups[g].target : 0);
        }
    }
    fflush(head);
    free_setup(&s);
}

/* Cost of one step: MuJoCo RK4 against whirl rk4 at the same step from the same start. */
/* The step costs at N = 10, 100, 1000, sizes from .. to - 1 of those, into DIR/name. */
static void step_costs(const char *dir, int from, int to, const char *name, FILE *checks,
                       FILE *head)
{
    FILE *csv = bench_open_csv(dir, name);
    fprintf(csv, "n,h,whirl_rk4_s_per_step,mujoco_rk4_s_per_step,ratio\n");
    const size_t ns[3] = {10, 100, 1000};
    for (int q = from; q < to; q++) {
        const size_t n = ns[q];
        char key[64], what[128];
        snprintf(key, sizeof key, "mujoco_step_%zu", n);
        snprintf(what, sizeof what, "MuJoCo RK4 step / whirl rk4 step; N = %zu", n);
#ifndef WHIRL_HAVE_MUJOCO
        printf("== step cost N = %zu: MuJoCo skipped: package missing at build time\n", n);
        fprintf(head, "%s,%s,,,skipped: package missing\n", key, what);
        (void)checks;
#else
        /* whirl's steps take 0.01-0.1 s in all; MuJoCo's (a dense joint-space mass matrix
         * factorized per stage, O(N^3)) as few as give a stable median */
        const double h = 0.1 / (double)n;
        const long steps = n <= 10 ? 20000 : n <= 100 ? 2000 : 200;
        const long mj_steps = n <= 10 ? 2000 : n <= 100 ? 100 : 2;
        const scene sc = {"steps", n, h * (double)steps, h, 0, NULL, 0};
        const scene sc_mj = {"steps", n, h * (double)mj_steps, h, 0, NULL, 0};
        setup s;
        memset(&s, 0, sizeof s);
        s.sc = &sc;
        s.chain = whirl_chain_alloc_uniform(n, 0);
        s.model = (whirl_model){
            .chain = s.chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 4};
        s.dyn = whirl_dyn_alloc(&s.model, WHIRL_FORMULATION_CARTESIAN);
        double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v),
               *xf = malloc(3 * n * sizeof *xf);
        s.y0 = malloc(whirl_dyn_size(s.dyn) * sizeof *s.y0);
        s.xi = malloc(3 * n * sizeof *s.xi);
        s.vi = malloc(3 * n * sizeof *s.vi);
        if (s.dyn == NULL || x == NULL || v == NULL || xf == NULL || s.y0 == NULL ||
            s.xi == NULL || s.vi == NULL)
            bench_die("alloc");
        if (bench_scene_start(s.chain, 4, x) != GSL_SUCCESS) bench_die("steady shape");
        if (whirl_dyn_set_state(s.dyn, 0, x, v, s.y0) != GSL_SUCCESS ||
            whirl_dyn_get_state(s.dyn, 0, s.y0, WHIRL_FRAME_INERTIAL, s.xi, s.vi) != GSL_SUCCESS)
            bench_die("set_state");
        whirl_dyn_diagnostics diag;
        if (whirl_dyn_diagnose(s.dyn, 0, s.y0, &diag) != GSL_SUCCESS) bench_die("diagnose");
        printf("== step cost N = %zu, h = %.3g, %ld steps of whirl, %ld of MuJoCo\n", n, h, steps,
               mj_steps);
        mj_chain_load(s.chain, dir, s.xi, s.vi, diag.energy, 0, &s.mj, checks);
        double tw[5], tm[5];
        const int reps = n >= 1000 ? 3 : 5;
        for (int r = 0; r < reps; r++) {
            run_stats rs;
            tw[r] = run_whirl(&s, "rk4", WHIRL_FORMULATION_CARTESIAN, h, 0, sc.t_end, xf, &rs) /
                    (double)rs.steps;
            s.sc = &sc_mj;
            tm[r] = run_mujoco(&s, h, xf, &rs) / (double)rs.steps;
            s.sc = &sc;
            if (tw[r] <= 0 || tm[r] <= 0) bench_die("step cost run");
        }
        const double w = bench_median(tw, reps), m = bench_median(tm, reps);
        printf("  whirl rk4 %.3g s per step, MuJoCo RK4 %.3g s per step: ratio %.3g\n", w, m,
               m / w);
        fprintf(csv, "%zu,%.6g,%.6g,%.6g,%.6g\n", n, h, w, m, m / w);
        headline(head, key, what, m / w, 0);
        peer_mj_free(&s.mj);
        whirl_dyn_free(s.dyn);
        whirl_chain_free(s.chain);
        free(s.y0), free(s.xi), free(s.vi), free(x), free(v), free(xf);
#endif
    }
    fclose(csv);
    fflush(head);
}

/* ns per link of one Cartesian right-hand side at N = 10^4 (3D, inertial, the smooth state of
 * bench_util.h; median of 7 timings of 100 evaluations), as bench_scaling measures it. */
static void rhs_per_link(FILE *head)
{
    const size_t n = 10000;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    const whirl_model model = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL};
    whirl_dyn *d = c != NULL ? whirl_dyn_alloc(&model, WHIRL_FORMULATION_CARTESIAN) : NULL;
    double *x = malloc(3 * n * sizeof *x), *v = malloc(3 * n * sizeof *v);
    double *y = d != NULL ? malloc(whirl_dyn_size(d) * sizeof *y) : NULL;
    double *dy = d != NULL ? malloc(whirl_dyn_size(d) * sizeof *dy) : NULL;
    if (d == NULL || x == NULL || v == NULL || y == NULL || dy == NULL) bench_die("alloc");
    const double p[3] = {0, 0, 0};
    bench_smooth_state(c, p, x, v);
    if (whirl_dyn_set_state(d, 0, x, v, y) != GSL_SUCCESS) bench_die("set_state");
    double t[7];
    for (int r = 0; r < 7; r++) {
        const double t0 = bench_now();
        for (int k = 0; k < 100; k++) whirl_dyn_rhs(0, y, dy, d);
        t[r] = (bench_now() - t0) / 100;
    }
    const double ns = 1e9 * bench_median(t, 7) / (double)n;
    printf("== right-hand side at N = 10^4: %.3g ns per link\n", ns);
    fprintf(head, "ns_per_link,right-hand side ns per link at N = 10^4 (target: at most 12),%.3g,"
                  "<= 12,%s\n", ns, ns <= 12 ? "met" : "not met");
    fflush(head);
    whirl_dyn_free(d);
    whirl_chain_free(c);
    free(x), free(v), free(y), free(dy);
}

/* The seed formulation against the Cartesian one: gauss2 at equal step on chain100. */
static void seed_cost(const char *dir, int quick, FILE *head)
{
    const size_t n = 100;
    const double periods = quick ? 1 : 2, h = 0.01;
    const scene sc = {"seed", n, periods * 2 * PI / 4, h, 0, NULL, 0};
    setup s;
    memset(&s, 0, sizeof s);
    s.sc = &sc;
    s.chain = whirl_chain_alloc_uniform(n, 0);
    s.model = (whirl_model){.chain = s.chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = 4};
    s.dyn = whirl_dyn_alloc(&s.model, WHIRL_FORMULATION_CARTESIAN);
    double *x = calloc(3 * n, sizeof *x), *v = calloc(3 * n, sizeof *v),
           *xs = malloc(3 * n * sizeof *xs), *xc = malloc(3 * n * sizeof *xc);
    s.y0 = s.dyn != NULL ? malloc(whirl_dyn_size(s.dyn) * sizeof *s.y0) : NULL;
    if (s.dyn == NULL || x == NULL || v == NULL || xs == NULL || xc == NULL || s.y0 == NULL)
        bench_die("alloc");
    if (bench_scene_start(s.chain, 4, x) != GSL_SUCCESS) bench_die("steady shape");
    if (whirl_dyn_set_state(s.dyn, 0, x, v, s.y0) != GSL_SUCCESS) bench_die("set_state");
    run_stats rs_s, rs_c;
    double ts[3], tc[3];
    const int reps = quick ? 1 : 3;
    for (int r = 0; r < reps; r++) {
        ts[r] = run_whirl(&s, "gauss2", WHIRL_FORMULATION_SEED, h, 0, sc.t_end, xs, &rs_s);
        tc[r] = run_whirl(&s, "gauss2", WHIRL_FORMULATION_CARTESIAN, h, 0, sc.t_end, xc, &rs_c);
        if (ts[r] < 0 || tc[r] < 0) bench_die("seed formulation run");
    }
    const double t_seed = bench_median(ts, reps), t_cart = bench_median(tc, reps);
    const double dist = bench_max_distance(n, xs, xc);
    printf("== seed formulation, N = 100, gauss2 h = %g over %g periods: seed %.3g s (%ld rhs), "
           "Cartesian %.3g s (%ld rhs), ratio %.4g; end positions apart by %.2g\n",
           h, periods, t_seed, rs_s.rhs, t_cart, rs_c.rhs, t_seed / t_cart, dist);
    FILE *csv = bench_open_csv(dir, "peers_seed.csv");
    fprintf(csv, "n,h,t_end,seed_s,seed_rhs,cartesian_s,cartesian_rhs,ratio,distance\n");
    fprintf(csv, "%zu,%g,%.17g,%.6g,%ld,%.6g,%ld,%.6g,%.3g\n", n, h, sc.t_end, t_seed, rs_s.rhs,
            t_cart, rs_c.rhs, t_seed / t_cart, dist);
    fclose(csv);
    headline(head, "seed_100", "seed formulation / whirl; gauss2 at equal step; N = 100",
             t_seed / t_cart, 200);
    fflush(head);
    whirl_dyn_free(s.dyn);
    whirl_chain_free(s.chain);
    free(s.y0), free(x), free(v), free(xs), free(xc);
}

#ifdef WHIRL_HAVE_SUNDIALS
#define MAX_ROUNDS 31

/* q-quantile of x[0..n-1] (sorted copy; linear between order statistics). */
static double quantile(const double *x, int n, double q)
{
    double v[MAX_ROUNDS];
    int m = 0;
    for (int i = 0; i < n; i++)
        if (isfinite(x[i])) v[m++] = x[i];
    if (m == 0) return NAN;
    qsort(v, (size_t)m, sizeof *v, bench_cmp_double);
    const double pos = q * (m - 1);
    const int i = (int)pos;
    return i + 1 < m ? v[i] + (pos - i) * (v[i + 1] - v[i]) : v[m - 1];
}

/* The best of the contenders of group g at error e, from per-run values val (times or right-hand
 * sides) of the curves; *who receives the winner's index. */
static double best_at(const curve *curves, double vals[][MAX_RUNS], const char *g, double e,
                      double floor_err, size_t *who)
{
    double best = NAN;
    for (size_t k = 0; k < N_CONTENDERS; k++) {
        if (strcmp(contenders[k].group, g) != 0 || curves[k].count == 0) continue;
        const double t = bench_time_at(curves[k].count, curves[k].err, vals[k], e, floor_err);
        if (t < best || (isnan(best) && !isnan(t))) best = t, *who = k;
    }
    return best;
}

/* bench_peers DIR arkode [ROUNDS]: whirl rk8 against ARKODE with projection on chain100, the
 * ratio per interleaved round and its spread (see the header). */
static void arkode_rounds(const char *dir, int rounds, FILE *checks, FILE *head)
{
    const scene sc = {"chain100", 100, 20 * 2 * PI / 4, 0.01, 8, "arkode-proj", 1};
    setup s;
    setup_scene(&sc, dir, checks, &s);
    static curve curves[N_CONTENDERS];
    static double t[N_CONTENDERS][MAX_RUNS][MAX_ROUNDS];
    for (size_t k = 0; k < N_CONTENDERS; k++) {
        curves[k].count = 0;
        if (k == 0 || strcmp(contenders[k].group, "arkode-proj") == 0)
            sweep(&s, &contenders[k], 1, &curves[k]);
    }
    /* the rounds repeat only the settings that bracket a level (the others are never
     * interpolated; they keep their first run's time) */
    static int needed[N_CONTENDERS][MAX_RUNS];
    for (size_t k = 0; k < N_CONTENDERS; k++)
        for (int j = 0; j < curves[k].count; j++) {
            needed[k][j] = 0;
            for (int r = 0; r < rounds; r++) t[k][j][r] = curves[k].times[j][0];
        }
    for (size_t k = 0; k < N_CONTENDERS; k++)
        for (int j = 0; j + 1 < curves[k].count; j++)
            for (int l = 0; l < N_LEVELS; l++) {
                const double e0 = curves[k].err[j], e1 = curves[k].err[j + 1], e = levels[l];
                if ((e0 >= e && e >= e1) || (e1 >= e && e >= e0)) needed[k][j] = needed[k][j + 1] = 1;
            }
    double *xf = malloc(3 * sc.n * sizeof *xf);
    if (xf == NULL) bench_die("alloc");
    for (int r = 0; r < rounds; r++)
        for (size_t k = 0; k < N_CONTENDERS; k++)
            for (int j = 0; j < curves[k].count; j++) {
                if (!needed[k][j]) continue;
                run_stats rs;
                const double secs = run_contender(&s, &contenders[k], curves[k].param[j], xf, &rs);
                t[k][j][r] = secs >= 0 ? secs : NAN; /* a failed repeat: left out */
            }
    free(xf);
    FILE *csv = bench_open_csv(dir, "peers_arkode_rounds.csv");
    fprintf(csv, "# chain100 over 20 periods, %d interleaved rounds; load average at the end "
                 "%.2f\n", rounds, bench_load_average());
    fprintf(csv, "round,error,whirl_s,arkode_s,arkode_table,ratio\n");
    static double vals[N_CONTENDERS][MAX_RUNS], rhs[N_CONTENDERS][MAX_RUNS];
    for (size_t k = 0; k < N_CONTENDERS; k++)
        for (int j = 0; j < curves[k].count; j++) rhs[k][j] = (double)curves[k].rhs[j];
    printf("  ARKODE with projection / whirl rk8, N = 100, 20 periods, %d interleaved rounds:\n",
           rounds);
    for (int l = 0; l < N_LEVELS; l++) {
        const double e = levels[l];
        double ratio[MAX_ROUNDS];
        for (int r = 0; r < rounds; r++) {
            for (size_t k = 0; k < N_CONTENDERS; k++)
                for (int j = 0; j < curves[k].count; j++) vals[k][j] = t[k][j][r];
            size_t who = 0, w0 = 0;
            const double tw = best_at(curves, vals, "whirl", e, s.floor_err, &w0);
            const double ta = best_at(curves, vals, "arkode-proj", e, s.floor_err, &who);
            ratio[r] = ta / tw;
            fprintf(csv, "%d,%.0e,%.6g,%.6g,%s,%.4g\n", r + 1, e, tw, ta, contenders[who].label,
                    ratio[r]);
        }
        /* the median times over the rounds, and the right-hand sides, at equal error */
        for (size_t k = 0; k < N_CONTENDERS; k++)
            for (int j = 0; j < curves[k].count; j++) {
                double tmp[MAX_ROUNDS];
                for (int r = 0; r < rounds; r++) tmp[r] = t[k][j][r];
                vals[k][j] = quantile(tmp, rounds, 0.5);
            }
        size_t who = 0, w0 = 0;
        const double tw = best_at(curves, vals, "whirl", e, s.floor_err, &w0);
        const double ta = best_at(curves, vals, "arkode-proj", e, s.floor_err, &who);
        const double ew = best_at(curves, rhs, "whirl", e, s.floor_err, &w0);
        const double ea = bench_time_at(curves[who].count, curves[who].err, rhs[who], e,
                                        s.floor_err);
        const double med = quantile(ratio, rounds, 0.5);
        printf("    error %.0e: ratio per round median %.3g, quartiles %.3g-%.3g, range %.3g-%.3g; "
               "ratio of the median times %.3g (%s %.3g s, whirl %.3g s)\n",
               e, med, quantile(ratio, rounds, 0.25), quantile(ratio, rounds, 0.75),
               quantile(ratio, rounds, 0), quantile(ratio, rounds, 1), ta / tw,
               contenders[who].label, ta, tw);
        printf("      right-hand sides at equal error: %s %.4g, whirl %.4g (ratio %.3g); time per "
               "right-hand side: ratio %.3g\n",
               contenders[who].label, ea, ew, ea / ew, (ta / tw) / (ea / ew));
        char key[128], what[256];
        snprintf(key, sizeof key, "arkode-proj_rounds_chain100_%.0e", e);
        snprintf(what, sizeof what,
                 "ARKODE ERK with projection / whirl rk8; N = 100; error %.0e; median of %d "
                 "interleaved rounds (range %.2g-%.2g)",
                 e, rounds, quantile(ratio, rounds, 0), quantile(ratio, rounds, 1));
        headline(head, key, what, med, 6);
    }
    fclose(csv);
    fflush(head);
    free_setup(&s);
}
#endif

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    setvbuf(stdout, NULL, _IOLBF, 0);
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    const int quick = argc > 2 && strcmp(argv[2], "quick") == 0;
    const int arkode = argc > 2 && strcmp(argv[2], "arkode") == 0;
    const int steps1000 = argc > 2 && strcmp(argv[2], "steps1000") == 0;
    const char *only = argc > 3 && !arkode ? argv[3] : NULL;
    const int rounds = arkode && argc > 3 ? atoi(argv[3]) : 15;
    if ((argc > 2 && !quick && !arkode && !steps1000 && strcmp(argv[2], "full") != 0) ||
        rounds < 1 || rounds > 31) {
        fprintf(stderr, "%s: usage: bench_peers [DIR [quick|full [CONTENDER]]], bench_peers DIR "
                        "arkode [ROUNDS (1..31)] or bench_peers DIR steps1000\n", BENCH_NAME);
        return 1;
    }
    printf("load average at start (other jobs share the cores): %.2f\n", bench_load_average());
#ifdef WHIRL_HAVE_MUJOCO
    printf("MuJoCo %s\n", mj_versionString());
#else
    printf("MuJoCo: skipped (mujoco/mujoco.h not found at build time: libmujoco-dev)\n");
#endif
#ifdef WHIRL_HAVE_SUNDIALS
    printf("SUNDIALS %s (ARKODE, CVODE)\n", SUNDIALS_VERSION);
#else
    printf("SUNDIALS: skipped (arkode/cvode headers not found at build time: libsundials-dev)\n");
#endif
    char path[1024];
    snprintf(path, sizeof path, "%s/headline.csv", dir);
    FILE *head = fopen(path, "a");
    FILE *checks = bench_open_csv(dir, "peers_checks.csv");
    if (head == NULL) {
        fprintf(stderr, "%s: cannot write %s\n", BENCH_NAME, path);
        return 1;
    }
    fprintf(checks, "peer,n,position_diff,velocity_diff,energy_diff,frequency_rel_diff,"
                    "mass_matrix_condition\n");
    if (steps1000) {
        step_costs(dir, 2, 3, "peers_steps_1000.csv", checks, head);
        fclose(checks);
        fclose(head);
        return 0;
    }
    if (arkode) {
#ifdef WHIRL_HAVE_SUNDIALS
        arkode_rounds(dir, rounds, checks, head);
#else
        printf("ARKODE with projection: skipped (SUNDIALS headers not found at build time)\n");
        fprintf(head, "arkode-proj_rounds_chain100,ARKODE with projection / whirl rk8 over "
                      "rounds,,,skipped: package missing\n");
#endif
        fclose(checks);
        fclose(head);
        return 0;
    }
    /* quick: MuJoCo at N = 100 over 2 periods (over 20 its runs near 1e-6 take minutes) */
    const double t_end = 20 * 2 * PI / 4;
    const scene scenes_full[] = {
        {"chain10", 10, t_end, 0.1, 10, NULL, 0},
        {"chain100", 100, t_end, 0.01, 15, NULL, 0},
    };
    const scene scenes_quick[] = {
        {"chain10", 10, t_end, 0.1, 4, NULL, 0},
        {"chain100", 100, t_end, 0.01, 8, NULL, 1},
        {"chain100short", 100, t_end / 10, 0.01, 100, "mujoco", 0},
    };
    const scene *scenes = quick ? scenes_quick : scenes_full;
    const size_t n_scenes = quick ? 3 : 2;
    for (size_t k = 0; k < n_scenes; k++)
        run_scene(&scenes[k], dir, quick, only, checks, head);
    if (only == NULL) {
        rhs_per_link(head);
        step_costs(dir, 0, quick ? 2 : 3, "peers_steps.csv", checks, head);
        seed_cost(dir, quick, head);
    }
    fclose(checks);
    fclose(head);
    return 0;
}
