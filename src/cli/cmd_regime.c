/* whirl regime: which node count a chain swung by hand settles into, from rest
 * (include/whirl/regime.h): one run, a map over (omega, eps), or a hysteresis sweep of omega.
 * The map, its file and its sharing over threads and MPI ranks are in regime_map.c; the rows and
 * header lines that both write are in regime_rows.c.
 *
 * One run (--omega W --eps E): comment lines, the header and one row; --trace FILE writes the
 * motion in the inertial frame in the format of `whirl simulate`'s trace (plots/animate.gp).
 * A map (--omega-min A --omega-max B --omega-count n, --eps E or --eps-min --eps-max
 * --eps-count m): one row per grid point, point index = i_eps n + i_omega, written to -o FILE
 * (required) as the points finish, in index order. Each point is one independent run, seeded by
 * --seed + index: the rows do not depend on how the points are shared out. With Open MPI
 * (built with -DWHIRL_MPI, run by mpirun -n K) the points are dealt out in rounds of
 * 4 x threads points per rank: rank r takes the points r, r + K, r + 2K, ... of the round (so
 * that neighbours on the grid, of similar cost, are spread over the ranks) and runs them on its
 * OpenMP threads; rank 0 gathers the results and appends them in index order. The rows are those
 * of the single-process run.
 * Ctrl-C (SIGINT/SIGTERM) stops after the current round with the finished points kept (exit
 * 130); --resume reads FILE, checks that it was written with the same parameters, drops an
 * unfinished last line and computes only the missing points. --folds FILE writes the folds of
 * the steady driven branches (whirl_driven_branch, modes 1-3, both sides) for every eps of the
 * map. A sweep (--sweep, one eps): omega up from omega-min to omega-max in the steps, then back
 * down, the state carried over (whirl_regime_sweep); jumps of the node count are listed as
 * comment lines "# jump up|down: ...".
 * Columns of the rows: the point (index, omega, eps or leg, omega), state (settled, converging,
 * periodic, quasiperiodic, chaotic, failed), class (the node count if settled or converging, 0
 * periodic, -1 quasi-periodic, -2 chaotic, -3 failed: for the heat map), the node count of the
 * last shape, the period, t_end, change, remaining, shape_error, bvp_nodes, lyapunov, the tip
 * in the co-rotating frame and its radius, and the integrator steps; a value not computed (the
 * Lyapunov exponent of a settled run, the shape error without a steady shape) is left empty. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef WHIRL_MPI
#include <mpi.h>
#endif

#include "cli/regime_cli.h"
#include "whirl/driven.h"
#include "whirl/regime.h"
#include "whirl/steady.h"

static const char *const sweep_columns =
    "leg,omega,state,class,nodes,period,t_end,change,remaining,shape_error,bvp_nodes,lyapunov,"
    "tip_x,tip_y,tip_z,tip_r,steps";

/* ---- options ---- */

static int check_range(const cli_command *cmd, const char *name, double lo, double hi, int steps,
                       double lower, double upper)
{
    if (steps < 1 || steps > 100000)
        return cli_error(cmd, "--%s-count must be between 1 and 100000, got %d", name, steps);
    if (!(lo > lower && hi < upper))
        return cli_error(cmd, "--%s-min and --%s-max must lie in (%g, %g), got %g, %g", name,
                         name, lower, upper, lo, hi);
    if (steps == 1 ? lo != hi : !(lo < hi))
        return cli_error(cmd, "need --%s-min < --%s-max (equal with --%s-count 1), got %g, %g",
                         name, name, name, lo, hi);
    return 0;
}

static int check_options(const cli_command *cmd, regime_options *o)
{
    const int map = regime_cli_is_map(o);
    if (map && !(o->omin_given && o->omax_given && o->osteps_given))
        return cli_error(cmd, "a map or sweep needs --omega-min, --omega-max and --omega-count");
    if (!map && o->sweep) return cli_error(cmd, "--sweep needs --omega-min, --omega-max and "
                                           "--omega-count");
    if (map && o->omega_given)
        return cli_error(cmd, "--omega is for one run; a map or sweep takes --omega-min/max/count");
    if (!map && !o->omega_given)
        return cli_error(cmd, "--omega (one run) or --omega-min, --omega-max, --omega-count "
                         "(a map) is required");
    const int eps_range = o->emin_given || o->emax_given || o->esteps_given;
    if (eps_range && !(o->emin_given && o->emax_given && o->esteps_given))
        return cli_error(cmd, "an eps range needs --eps-min, --eps-max and --eps-count");
    if (eps_range && o->eps_given) return cli_error(cmd, "give --eps or an eps range, not both");
    if (eps_range && (!map || o->sweep))
        return cli_error(cmd, "an eps range is for a map; one run or a sweep takes --eps");
    if (!eps_range && !o->eps_given) return cli_error(cmd, "--eps (the hand's radius) is required");
    if (o->links < 1 || o->links > REGIME_MAX_LINKS)
        return cli_error(cmd, "--links must be between 1 and %d, got %d", REGIME_MAX_LINKS,
                         o->links);
    if (!o->dt_given) /* the library's default for the chain of --links */
        o->p.dt = whirl_regime_defaults((size_t)o->links).dt;
    if (strcmp(o->frame, "rotating") == 0) o->p.frame = WHIRL_FRAME_ROTATING;
    else if (strcmp(o->frame, "inertial") == 0) o->p.frame = WHIRL_FRAME_INERTIAL;
    else return cli_error(cmd, "--frame must be rotating or inertial, got '%s'", o->frame);
    if (o->sweep && o->p.frame != WHIRL_FRAME_ROTATING)
        return cli_error(cmd, "--sweep changes omega during the run: it needs --frame rotating");
    if (map) {
        int rc = check_range(cmd, "omega", o->omega_min, o->omega_max, o->omega_steps, 0, HUGE_VAL);
        if (rc) return rc;
        if (eps_range && (rc = check_range(cmd, "eps", o->eps_min, o->eps_max, o->eps_steps, 0, 1)))
            return rc;
        if (!eps_range) o->eps_min = o->eps_max = o->eps, o->eps_steps = 1;
        if ((long)o->omega_steps * o->eps_steps > REGIME_MAX_POINTS)
            return cli_error(cmd, "the map has more than %ld points", REGIME_MAX_POINTS);
        o->p.omega = o->omega_min;
        o->p.drive_radius = o->eps_min;
    } else {
        o->p.omega = o->omega;
        o->p.drive_radius = o->eps;
    }
    if (whirl_regime_check(&o->p) != GSL_SUCCESS) {
        /* the library names the field; the options are named like it but for these */
        static const char *const renamed[][2] = {{"drive_radius", "eps"},
                                                 {"air_drag", "drag"},
                                                 {"air_drag_quadratic", "drag_quadratic"}};
        char field[64] = "", *dash = field;
        const char *msg = CLI_LIBRARY_ERROR(&o->units);
        sscanf(msg, "%63[a-z_]", field);
        for (size_t k = 0; k < sizeof renamed / sizeof renamed[0]; k++)
            if (strcmp(field, renamed[k][0]) == 0) snprintf(field, sizeof field, "%s", renamed[k][1]);
        for (; *dash; dash++)
            if (*dash == '_') *dash = '-';
        return cli_error(cmd, "--%s: %s", field, msg);
    }
    if (whirl_integrator_type_find(o->p.method) == NULL)
        return cli_error(cmd, "--method: %s", whirl_last_error());
    if (map && !o->sweep && o->output == NULL)
        return cli_error(cmd, "a map needs -o FILE (it is written as the points finish)");
    if (map && !o->sweep && strcmp(o->output, "-") == 0)
        return cli_error(cmd, "a map needs -o FILE, not standard output");
    if (o->resume && (!map || o->sweep)) return cli_error(cmd, "--resume applies to a map");
    if (o->folds && (!map || o->sweep)) return cli_error(cmd, "--folds applies to a map");
    if (o->trace && map) return cli_error(cmd, "--trace applies to one run");
    if (o->trace && strcmp(o->trace, "-") == 0)
        return cli_error(cmd, "--trace must be a file, not standard output");
    if (o->trace_every_given && !o->trace)
        return cli_error(cmd, "--trace-every applies with --trace");
    if (!(o->trace_every > 0))
        return cli_error(cmd, "--trace-every must be > 0, got %g", o->trace_every);
    if (o->t_change_given && !o->sweep) return cli_error(cmd, "--t-change applies to --sweep");
    if (!(o->t_change > 0 && isfinite(o->t_change)))
        return cli_error(cmd, "--t-change must be > 0, got %g", o->t_change);
    return 0;
}

/* ---- one run with an optional trace ---- */

typedef struct trace_ctx {
    FILE *fp;
    unsigned long frames;
    double len, time; /* the user's units of length and time, in dimensionless ones */
} trace_ctx;

/* One block of the trace: the pivot, then every mass, in the inertial frame. */
static int trace_frame(void *ctx, double t, double angle, const double *pivot, const double *x,
                       size_t n)
{
    trace_ctx *tc = ctx;
    const double c = cos(angle), s = sin(angle);
    fprintf(tc->fp, "%s# t = %s\n", tc->frames++ ? "\n\n" : "", CLI_NUM(t * tc->time));
    for (size_t i = 0; i <= n; i++) {
        const double *p = i == 0 ? pivot : x + 3 * (i - 1);
        fprintf(tc->fp, "%s %s %s %s\n", CLI_NUM(tc->len * (c * p[0] - s * p[1])),
                CLI_NUM(tc->len * (s * p[0] + c * p[1])), CLI_NUM(tc->len * p[2]),
                CLI_NUM(t * tc->time));
    }
    return GSL_SUCCESS;
}

/* The observer of a single run or a sweep: the trace's frame (if any) and the progress line,
 * the time reached against the latest the run can reach, both in the user's time unit. */
typedef struct observe_ctx {
    trace_ctx *trace;             /* NULL: no trace */
    cli_progress_state progress;  /* total: the bound below, in the user's time unit */
    double bound;                 /* the latest time the run can reach [T] */
    double time;                  /* the user's time unit in dimensionless ones */
    double t;                     /* the time reached [T] */
} observe_ctx;

/* A time in the user's unit as a count of the progress line: --t-max may be as large as a
 * double (1e300), beyond any long, so the count stops at 1e15. */
static long progress_count(double x) { return x < 1e15 ? (long)x : (long)1e15; }

static int observe(void *ctx, double t, double angle, const double *pivot, const double *x,
                   size_t n)
{
    observe_ctx *oc = ctx;
    oc->t = fmin(t, oc->bound);
    cli_progress_update(&oc->progress, progress_count(oc->t * oc->time), 0);
    return oc->trace ? trace_frame(oc->trace, t, angle, pivot, x, n) : GSL_SUCCESS;
}

/* Observes the runs of w: frames every trace_every when tc is given, else the progress alone
 * once per time unit; bound: the latest time the runs can reach. */
static void observe_begin(const cli_command *cmd, const regime_options *o, whirl_regime *w,
                          observe_ctx *oc, trace_ctx *tc, const char *label, double bound)
{
    oc->trace = tc;
    oc->bound = bound;
    oc->t = 0;
    oc->time = regime_cli_user(o, CLI_UNIT_TIME, 1);
    cli_progress_begin(&oc->progress, cmd, label, progress_count(ceil(bound * oc->time)), 0);
    whirl_regime_observe(w, observe, oc, tc ? o->trace_every : fmin(1.0, bound / 100));
}

static int run_one(const cli_command *cmd, const regime_options *o, const whirl_chain *chain)
{
    whirl_regime *w = whirl_regime_alloc(chain);
    if (w == NULL) return cli_error(cmd, "out of memory");
    cli_out out, trace;
    int rc = cli_out_open(cmd, &out, o->output), trace_open = 0;
    if (rc == 0 && o->trace) {
        rc = cli_out_open(cmd, &trace, o->trace);
        trace_open = rc == 0;
        if (rc) cli_out_abort(&out);
    }
    if (rc) {
        whirl_regime_free(w);
        return rc;
    }
    trace_ctx tc = {trace_open ? trace.fp : NULL, 0, regime_cli_user(o, CLI_UNIT_LENGTH, 1),
                    regime_cli_user(o, CLI_UNIT_TIME, 1)};
    if (trace_open)
        cli_trace_header(trace.fp, &o->units, "whirl regime, one run from rest", o->p.omega,
                         o->p.drive_radius, NULL, o->p.air_drag, o->p.air_drag_quadratic, o->links);
    observe_ctx oc;
    observe_begin(cmd, o, w, &oc, trace_open ? &tc : NULL, "time", o->p.t_max);
    whirl_regime_result r;
    const int status = whirl_regime_run(w, &o->p, &r);
    cli_progress_update(&oc.progress, progress_count(oc.t * oc.time), 1);
    if (status == WHIRL_EINTERRUPTED)
        rc = CLI_EXIT_INTERRUPTED, cli_error(cmd, "interrupted: %s", CLI_LIBRARY_ERROR(&o->units));
    else if (status != GSL_SUCCESS)
        rc = cli_error(cmd, "the run failed: %s", CLI_LIBRARY_ERROR(&o->units));
    if (rc == 0) {
        fprintf(out.fp, "# whirl regime: one run from rest\n");
        regime_cli_write_parameters(out.fp, o);
        regime_cli_write_critical(out.fp, o, chain);
        if (r.state == WHIRL_REGIME_FAILED)
            fprintf(out.fp, "# failed: %s\n", CLI_LIBRARY_ERROR(&o->units));
        fprintf(out.fp, "%s\n", regime_cli_map_columns);
        fprintf(out.fp, "0,%s,%s,", CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, o->omega)),
                CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, o->eps)));
        regime_cli_write_result(out.fp, o, &r);
    }
    cli_out *const outs[2] = {&out, &trace};
    if (rc == 0) rc = cli_out_commit_all(cmd, outs, trace_open ? 2 : 1); /* both or neither */
    else if (rc == CLI_EXIT_INTERRUPTED && trace_open) { /* it keeps its trace so far */
        cli_out_abort(&out);
        if (cli_out_commit(cmd, &trace) != 0) rc = 1;
    } else {
        cli_out_abort(&out);
        if (trace_open) cli_out_abort(&trace);
    }
    whirl_regime_free(w);
    return rc;
}

/* ---- the hysteresis sweep ---- */

static int run_sweep(const cli_command *cmd, const regime_options *o, const whirl_chain *chain)
{
    const size_t n_up = (size_t)o->omega_steps, n = 2 * n_up - 1;
    double *omega = malloc(n * sizeof *omega);
    whirl_regime_result *res = malloc(n * sizeof *res);
    whirl_regime *w = whirl_regime_alloc(chain);
    if (!omega || !res || !w) {
        free(omega);
        free(res);
        whirl_regime_free(w);
        return cli_error(cmd, "out of memory");
    }
    /* the output is locked for the whole run: two sweeps on one file, even one that does not
     * exist yet, would each replace the other's rows */
    cli_lock lock;
    if (cli_lock_take(cmd, &lock, o->output, 1)) {
        free(omega);
        free(res);
        whirl_regime_free(w);
        return 1;
    }
    for (size_t j = 0; j < n; j++) /* up, then down again */
        omega[j] = cli_grid(o->omega_min, o->omega_max, o->omega_steps,
                              (int)(j < n_up ? j : n - 1 - j));
    int rc = 0;
    /* every point after the first: the change of rate, then at most t_max - t_ramp */
    observe_ctx oc;
    observe_begin(cmd, o, w, &oc, NULL, "time (of the longest possible)",
                  o->p.t_max + (double)(n - 1) * (o->t_change + o->p.t_max - o->p.t_ramp));
    size_t done = 0; /* points complete; on a stop, the rows written */
    const int status = whirl_regime_sweep(w, &o->p, omega, n, o->t_change, res, &done);
    cli_progress_update(&oc.progress, progress_count(oc.t * oc.time), 1);
    const int interrupted = status == WHIRL_EINTERRUPTED;
    char stopped[512] = "";
    if (interrupted)
        cli_library_error(&o->units, stopped, sizeof stopped);
    else if (status != GSL_SUCCESS)
        rc = cli_error(cmd, "the sweep failed: %s", CLI_LIBRARY_ERROR(&o->units));
    cli_out out;
    if (rc == 0) rc = cli_out_open(cmd, &out, o->output);
    if (rc == 0) {
        fprintf(out.fp, "# whirl regime sweep: omega up then down at eps = %s, the state "
                "carried over, t_change = %s\n", CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, o->eps)),
                CLI_NUM(regime_cli_user(o, CLI_UNIT_TIME, o->t_change)));
        if (interrupted)
            fprintf(out.fp, "# interrupted at omega %s (%s): the %zu of %zu points completed "
                    "until then\n", CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega[done < n ? done : n - 1])),
                    stopped, done, n);
        regime_cli_write_parameters(out.fp, o);
        regime_cli_write_critical(out.fp, o, chain);
        for (size_t j = 1; j < done; j++)
            if (regime_cli_state_class(&res[j]) != regime_cli_state_class(&res[j - 1]))
                fprintf(out.fp, "# jump %s: between omega %s and %s: %s %d nodes -> %s %d "
                        "nodes\n", j < n_up ? "up" : "down",
                        CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega[j - 1])),
                        CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega[j])),
                        whirl_regime_state_name(res[j - 1].state), res[j - 1].nodes,
                        whirl_regime_state_name(res[j].state), res[j].nodes);
        fprintf(out.fp, "%s\n", sweep_columns);
        for (size_t j = 0; j < done; j++) {
            fprintf(out.fp, "%s,%s,", j < n_up ? "up" : "down",
                    CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega[j])));
            regime_cli_write_result(out.fp, o, &res[j]);
        }
        rc = cli_out_commit(cmd, &out);
        if (rc == 0 && interrupted) {
            cli_error(cmd, "interrupted at omega %s: the %zu points completed until then are "
                      "written", CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega[done < n ? done : n - 1])), done);
            rc = CLI_EXIT_INTERRUPTED;
        }
    }
    cli_lock_release(&lock);
    free(omega);
    free(res);
    whirl_regime_free(w);
    return rc;
}

/* ---- the command ---- */

static int regime_main(const cli_command *cmd, int argc, char **argv, const mpi_context *mc)
{
    regime_options o;
    memset(&o, 0, sizeof o);
    o.links = 20;
    o.frame = "rotating";
    o.trace_every = 0.1;
    o.t_change = 20;
    o.p = whirl_regime_defaults(20);
    o.units = (cli_units)CLI_UNITS_INIT;
    o.air = (cli_air)CLI_AIR_INIT(o.units);
    double seed = 1, settle_periods = 3, lyapunov_periods = 60;
    const cli_option opts[] = {
        {.name = "--omega", .type = CLI_DOUBLE, .value = &o.omega, .given = &o.omega_given,
         .meta = "W", .help = "rate of the hand (one run)", .range = "(0, inf)",
         .unit = CLI_UNIT_RATE},
        {.name = "--omega-min", .type = CLI_DOUBLE, .value = &o.omega_min, .given = &o.omin_given,
         .meta = "A", .help = "map or sweep: lowest omega", .range = "(0, inf)",
         .unit = CLI_UNIT_RATE},
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &o.omega_max, .given = &o.omax_given,
         .meta = "B", .help = "map or sweep: highest omega", .range = "(0, inf)",
         .unit = CLI_UNIT_RATE},
        {.name = "--omega-count", .type = CLI_INT, .value = &o.omega_steps,
         .given = &o.osteps_given, .meta = "N",
         .help = "map or sweep: number of rates, both ends included"},
        {.name = "--eps-min", .type = CLI_DOUBLE, .value = &o.eps_min, .given = &o.emin_given,
         .meta = "C", .help = "map: smallest eps", .unit = CLI_UNIT_LENGTH},
        {.name = "--eps-max", .type = CLI_DOUBLE, .value = &o.eps_max, .given = &o.emax_given,
         .meta = "D", .help = "map: largest eps", .unit = CLI_UNIT_LENGTH},
        {.name = "--eps-count", .type = CLI_INT, .value = &o.eps_steps, .given = &o.esteps_given,
         .meta = "M", .help = "map: number of radii, both ends included"},
        CLI_DRAG_OPTIONS(o.eps, &o.eps_given, o.p.air_drag, NULL, o.p.air_drag_quadratic, NULL, o.air),
        {.name = "--sweep", .type = CLI_FLAG, .value = &o.sweep,
         .help = "hysteresis: omega up, then down, state carried over"},
        {.name = "--t-change", .type = CLI_DOUBLE, .value = &o.t_change, .given = &o.t_change_given,
         .meta = "T", .help = "sweep: time of each change of omega (default 20)",
         .unit = CLI_UNIT_TIME},
        {.name = "--links", .type = CLI_INT, .value = &o.links, .meta = "N",
         .help = "links of the chain (default 20)"},
        {.name = "--internal-damping", .type = CLI_DOUBLE, .value = &o.p.internal_damping,
         .meta = "D", .help = "damping of the joints (default 0)", .unit = CLI_UNIT_DAMPING},
        {.name = "--frame", .type = CLI_STRING, .value = &o.frame, .meta = "F",
         .help = "rotating (default) or inertial"},
        {.name = "--method", .type = CLI_STRING, .value = &o.p.method, .meta = "M",
         .help = "integrator (default rk4)"},
        {.name = "--dt", .type = CLI_DOUBLE, .value = &o.p.dt, .given = &o.dt_given, .meta = "H",
         .help = "time step (default 0.1/N)", .unit = CLI_UNIT_TIME},
        {.name = "--t-ramp", .type = CLI_DOUBLE, .value = &o.p.t_ramp, .meta = "T",
         .help = "ramp time of eps (default 20)", .unit = CLI_UNIT_TIME},
        {.name = "--t-max", .type = CLI_DOUBLE, .value = &o.p.t_max, .meta = "T",
         .help = "end of a run that has not settled (default 400)", .unit = CLI_UNIT_TIME},
        {.name = "--settle-tol", .type = CLI_DOUBLE, .value = &o.p.settle_tol, .meta = "D",
         .help = "distance left to the steady shape (default 1e-3)", .unit = CLI_UNIT_LENGTH},
        {.name = "--settle-periods", .type = CLI_DOUBLE, .value = &settle_periods, .meta = "K",
         .help = "periods that must pass (default 3)"},
        {.name = "--periodic-tol", .type = CLI_DOUBLE, .value = &o.p.periodic_tol, .meta = "D",
         .help = "repeat tolerance of the tip (default 1e-3)", .unit = CLI_UNIT_LENGTH},
        {.name = "--lyapunov-periods", .type = CLI_DOUBLE, .value = &lyapunov_periods, .meta = "K",
         .help = "Lyapunov window in periods (default 60)"},
        {.name = "--chaos-lambda", .type = CLI_DOUBLE, .value = &o.p.chaos_lambda, .meta = "L",
         .help = "Lyapunov exponent above which a run is chaotic (default 0.05)",
         .unit = CLI_UNIT_RATE},
        {.name = "--perturb", .type = CLI_DOUBLE, .value = &o.p.perturb, .meta = "A",
         .help = "random turn of each hanging link [rad] (default 1e-3)"},
        {.name = "--seed", .type = CLI_DOUBLE, .value = &seed, .meta = "S",
         .help = "seed of the turns; a map's point i uses S + i (default 1)"},
        {.name = "--trace", .type = CLI_STRING, .value = &o.trace, .meta = "FILE",
         .help = "one run: the motion (inertial frame) for whirl view or plots/animate.gp"},
        {.name = "--trace-every", .type = CLI_DOUBLE, .value = &o.trace_every,
         .given = &o.trace_every_given, .meta = "T", .help = "interval of the trace (default 0.1)",
         .unit = CLI_UNIT_TIME},
        {.name = "--folds", .type = CLI_STRING, .value = &o.folds, .meta = "FILE",
         .help = "map: the folds of the steady branches"},
        {.name = "--resume", .type = CLI_FLAG, .value = &o.resume,
         .help = "map: keep the points in -o FILE, compute the rest"},
        CLI_UNITS_OPTIONS(o.units),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &o.output, .meta = "FILE",
         .help = "output CSV (default stdout; required for a map)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    const struct { const char *name; double value, max; } counts[] = {
        {"--seed", seed, 4294967295.0}, {"--settle-periods", settle_periods, 1e6},
        {"--lyapunov-periods", lyapunov_periods, 1e6}};
    for (size_t k = 0; k < sizeof counts / sizeof counts[0]; k++)
        if (!(counts[k].value >= (k ? 1 : 0) && counts[k].value <= counts[k].max &&
              counts[k].value == floor(counts[k].value)))
            return cli_error(cmd, "%s must be a whole number in [%d, %.0f], got %g", counts[k].name,
                             k ? 1 : 0, counts[k].max, counts[k].value);
    if ((rc = cli_drag_apply(cmd, &o.air, &o.p.air_drag_quadratic))) return rc;
    o.p.seed = (unsigned long)seed;
    o.p.settle_periods = (int)settle_periods;
    o.p.lyapunov_periods = (int)lyapunov_periods;
    if ((rc = check_options(cmd, &o))) return rc;
    if (mc->size > 1 && (!regime_cli_is_map(&o) || o.sweep))
        return cli_error(cmd, "one run and a sweep run on one rank; only a map is shared out");
    whirl_chain *chain = whirl_chain_alloc_uniform((size_t)o.links, 0);
    if (chain == NULL)
        return cli_error(cmd, "cannot make the chain: %s", CLI_LIBRARY_ERROR(&o.units));
    cli_catch_interrupts();
    rc = !regime_cli_is_map(&o) ? run_one(cmd, &o, chain)
         : o.sweep   ? run_sweep(cmd, &o, chain)
                     : regime_cli_run_map(cmd, &o, chain, mc);
    whirl_chain_free(chain);
    return rc;
}

int cmd_regime(const cli_command *cmd, int argc, char **argv)
{
    mpi_context mc = {0, 1};
#ifdef WHIRL_MPI
    /* MPI only when started by mpirun (Open MPI or a PMI launcher): a plain start stays a
     * single process that never touches MPI */
    const int launched = getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") ||
                         getenv("PMIX_RANK");
    if (launched) {
        int provided;
        MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided);
        MPI_Comm_rank(MPI_COMM_WORLD, &mc.rank);
        MPI_Comm_size(MPI_COMM_WORLD, &mc.size);
    }
    if (mc.rank > 0) { /* every rank checks the same options: only rank 0 speaks */
        FILE *err = freopen("/dev/null", "w", stderr), *out = freopen("/dev/null", "w", stdout);
        (void)err;
        (void)out;
    }
#endif
    const int rc = regime_main(cmd, argc, argv, &mc);
#ifdef WHIRL_MPI
    if (launched) MPI_Finalize();
#endif
    return rc;
}
