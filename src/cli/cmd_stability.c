/* whirl stability: linear stability of the steady shapes (whirl/stability.h) and its check by
 * perturbed time-domain runs, at one rate (--omega) or over a range (--omega-min/--omega-max/
 * --omega-count, the stability map). One CSV row per rate and mode:
 *   omega,mode,links,eig_growth,sim_growth,max_deviation,verdict,index
 * eig_growth: the largest real part of the eigenvalues of the linearisation in the co-rotating
 * frame, the symmetry's zero eigenvalues removed; sim_growth, max_deviation, verdict: the
 * perturbed run (whirl_stability_run_shape). With --linear no run is made: sim_growth and
 * max_deviation are left empty and the verdict is the linear one (eig_growth > 0: unstable, < 0:
 * converging, 0: "stable (minimum)" or "neutral (gyroscopic)"). index: the negative directions
 * of the amended potential (whirl_stability_index); a bounded run or a zero growth is "stable
 * (minimum)" at index 0 (an energy minimum, stable also with dissipation) and "neutral
 * (gyroscopic)" above (a saddle held by the Coriolis coupling, destabilised by dissipation). Rates where a mode of the map does not exist are left out.
 * The hand-swung chain (--eps, --drag, --drag-quadratic, --side; whirl/driven.h): the pivot on a
 * circle of radius eps, inertial-frame air drag; the shapes come from whirl_driven_mode (mode K
 * continued from the free one with its tip on the pivot's side, --side 1, or opposite, -1; mode 0:
 * the near-axis shape, continued from the hanging chain), are
 * three-dimensional and have no rotation symmetry. Three columns are added:
 *   ...,verdict,tip_x,tip_y,nodes
 * the tip in the co-rotating frame (pivot at (eps, 0, 0)) and the node count of driven.h.
 * --windows and --atlas: aliases of whirl windows (cmd_windows.c), kept for one release: the
 * command line is handed to it without --windows.
 * A map shows its progress (points done, elapsed, time left) on a terminal. Ctrl-C stops it
 * within a run (the library polls the stop request): the rows of the points finished are
 * written, in map order, and the exit status is 130; --resume reads them back from -o FILE
 * (which must begin with the comment lines and header this map writes) and computes only the
 * missing points.
 * This file: the options, the map's rows and --resume; the points and their analysis in
 * stability_points.c, --eigenvalues and --eigenvectors in stability_eigen.c (stability_cli.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/resume.h"
#include "cli/stability_cli.h"
#include "core/error.h"
#include "whirl/stability.h"

/* The hand-swung chain: any of its options given. */
static int driven(const stability_options *o) { return hand_cli_given(&o->hand); }

/* The size of one dimensionless unit of the kind in the user's units. */
static double unit(const stability_options *o, cli_unit kind)
{
    return cli_units_scale(&o->units, kind);
}

/* The mode (or modes) within the chain's: the N-link chain has modes 1..N; the hand-swung chain
 * (seeded by the continuum's shapes) 1..WHIRL_MODE_MAX. */
static int check_modes(const cli_command *cmd, const stability_options *o)
{
    const int continuum = driven(o);
    const int top = continuum ? WHIRL_MODE_MAX : o->links;
    for (int k = 0; k < (o->mode_given ? 1 : o->modes.n); k++) {
        const int mode = o->mode_given ? o->mode : o->modes.v[k];
        if (mode == 0 && !driven(o))
            return cli_error(cmd, "mode 0 (the near-axis shape) is the hand-swung chain's: it "
                             "needs --eps");
        if (mode == 0 && o->hand.side_given)
            return cli_error(cmd, "--side picks the seed of modes 1..64; mode 0 (the near-axis "
                             "shape) has none");
        if (mode > top && continuum)
            return cli_error(cmd, "mode %d is out of range: the hand-swung chain takes modes "
                             "1..%d", mode, top);
        if (mode > top)
            return cli_error(cmd, "mode %d does not exist: a chain of %d links has modes 1..%d",
                             mode, top, top);
    }
    return 0;
}

/* What the option table cannot say: 0, or 1 after an error. */
static int check_options(const cli_command *cmd, const stability_options *o)
{
    if (o->max_given && !o->min_given)
        return cli_error(cmd, "--omega-max needs --omega-min");
    if (o->modes_given && !o->min_given)
        return cli_error(cmd, "--modes needs --omega-min");
    if (o->min_given && !o->steps_given)
        return cli_error(cmd, "--omega-min needs --omega-count (windows: whirl windows)");
    if (check_modes(cmd, o)) return 1;
    if (o->min_given && !(o->omega_max > o->omega_min || (o->steps == 1 && o->omega_max == o->omega_min)))
        return cli_error(cmd, "need --omega-min < --omega-max (equal with --omega-count 1)");
    if (hand_cli_check(cmd, &o->hand)) return 1;
    if (o->resume && strcmp(o->output, "-") == 0)
        return cli_error(cmd, "--resume needs -o FILE, not standard output");
    if (whirl_integrator_type_find(o->method) == NULL)
        return cli_error(cmd, "--method: %s", whirl_last_error());
    if (o->resume && !o->min_given)
        return cli_error(cmd, "--resume needs --omega-min (a map; the atlas: whirl windows "
                         "--atlas --resume)");
    return 0;
}


/* The comment lines and the header of the output: a map resumes only a file that starts with
 * exactly these lines. */
static void write_header(FILE *fp, const stability_options *o)
{
    const double len = unit(o, CLI_UNIT_LENGTH);
    fprintf(fp, "# whirl stability: %d links, damping %s, %s\n", o->links,
            CLI_NUM(o->damping * unit(o, CLI_UNIT_DAMPING)),
            o->linear ? "linear analysis only" : "linear analysis and perturbed runs");
    if (o->min_given)
        fprintf(fp, "# map: omega %s to %s, %d rates, modes", 
                CLI_NUM(o->omega_min * unit(o, CLI_UNIT_RATE)),
                CLI_NUM(o->omega_max * unit(o, CLI_UNIT_RATE)), o->steps);
    for (int k = 0; o->min_given && k < o->modes.n; k++)
        fprintf(fp, "%s%d", k ? "," : " ", o->modes.v[k]);
    if (o->min_given) fputc('\n', fp);
    if (driven(o))
        fprintf(fp, "# hand-swung: eps %s, drag %s, drag_quadratic %s, side %d\n",
                CLI_NUM(o->hand.eps * len), CLI_NUM(o->hand.drag * unit(o, CLI_UNIT_DRAG)),
                CLI_NUM(o->hand.drag2 * unit(o, CLI_UNIT_DRAG2)), o->hand.side);
    if (!o->linear)
        fprintf(fp, "# runs: %s periods, perturbation %s, seed %d, method %s, dt %s "
                    "(0: default)\n", CLI_NUM(o->periods), CLI_NUM(o->perturb), o->seed, o->method,
                CLI_NUM(o->dt * unit(o, CLI_UNIT_TIME)));
    if (o->linear)
        fprintf(fp, "# verdict (linear): unstable where eig_growth > 0, converging where "
                    "< 0, where 0 stable (minimum) if index = 0, else neutral (gyroscopic)\n");
    else
        fprintf(fp, "# verdict: unstable once the deviation reaches 100 times the initial "
                    "one, converging (damping or drag > 0) once its largest value over a "
                    "period falls to 1/100 (or to 1/10 by the end), else stable (minimum) if "
                    "index = 0, neutral (gyroscopic) if not\n");
    fprintf(fp, "# index: negative directions of the amended potential (gravity minus "
                "centrifugal) at the shape; 0: a minimum, stable also with dissipation; > 0: a "
                "saddle that only the Coriolis coupling can hold, destabilised by dissipation\n");
    cli_units_comment(fp, &o->units);
    fprintf(fp, "omega,mode,links,eig_growth,sim_growth,max_deviation,verdict,index%s\n",
            driven(o) ? ",tip_x,tip_y,nodes" : "");
}

static void write_row(FILE *fp, const stability_options *o, const stability_point *p)
{
    const double rate = unit(o, CLI_UNIT_RATE), len = unit(o, CLI_UNIT_LENGTH);
    if (o->linear)
        fprintf(fp, "%s,%d,%d,%s,,,%s,%d", CLI_NUM(p->omega * rate), p->mode, o->links,
                CLI_NUM(p->eig_growth * rate), whirl_verdict_name(p->verdict), p->index);
    else
        fprintf(fp, "%s,%d,%d,%s,%s,%s,%s,%d", CLI_NUM(p->omega * rate), p->mode, o->links,
                CLI_NUM(p->eig_growth * rate), CLI_NUM(p->sim_growth * rate),
                CLI_NUM(p->max_deviation), whirl_verdict_name(p->verdict), p->index);
    if (driven(o))
        fprintf(fp, ",%s,%s,%d", CLI_NUM(p->tip[0] * len), CLI_NUM(p->tip[1] * len), p->nodes);
    fputc('\n', fp);
}

typedef struct map_progress {
    cli_progress_state *state;
    long already; /* points done before the map */
} map_progress;

static void linear_progress(void *ctx, size_t done)
{
    const map_progress *mp = ctx;
    cli_progress_update(mp->state, mp->already + (long)done, 0);
}

/* The growth of the free shapes of the points not done (whirl_stability_map): eig_growth and
 * linearised; with --linear their verdict too, and done (*finished counts them). Returns 0, or 1
 * with the message of the earliest failed point in message (a stop is no failure). */
static int linear_map(const stability_options *o, const whirl_chain *c, stability_point *pts,
                      size_t count, cli_progress_state *progress, long *finished, char *message,
                      size_t size)
{
    whirl_stability_point *mp = calloc(count > 0 ? count : 1, sizeof *mp);
    if (mp == NULL) {
        snprintf(message, size, "out of memory");
        return 1;
    }
    for (size_t i = 0; i < count; i++)
        mp[i] = (whirl_stability_point){pts[i].omega, pts[i].r, pts[i].z, pts[i].done, 0, 0};
    map_progress ctx = {progress, *finished};
    const int status = whirl_stability_map(c, o->damping, count, mp,
                                           o->linear ? linear_progress : NULL, &ctx);
    for (size_t i = 0; i < count; i++) {
        if (mp[i].status != GSL_SUCCESS) continue;
        pts[i].eig_growth = mp[i].growth;
        pts[i].index = mp[i].index;
        pts[i].linearised = 1;
        if (!o->linear) continue;
        pts[i].verdict = whirl_verdict_linear(mp[i].growth, mp[i].index);
        pts[i].done = 1;
        ++*finished;
    }
    int failed = 0;
    for (size_t i = 0; i < count && status != GSL_SUCCESS && status != WHIRL_EINTERRUPTED; i++)
        if (mp[i].status != GSL_SUCCESS && mp[i].status != -1) {
            snprintf(message, size, "omega %s, mode %d: %s",
                     CLI_NUM(pts[i].omega * unit(o, CLI_UNIT_RATE)), pts[i].mode,
                     CLI_LIBRARY_ERROR(&o->units));
            failed = 1;
            break;
        }
    if (status != GSL_SUCCESS && status != WHIRL_EINTERRUPTED && !failed) {
        snprintf(message, size, "%s", CLI_LIBRARY_ERROR(&o->units)); /* no workspace */
        failed = 1;
    }
    free(mp);
    return failed;
}

static void free_kept(char **kept, size_t count)
{
    for (size_t i = 0; kept && i < count; i++) free(kept[i]);
    free(kept);
}

/* The points of a single rate or of a map, with what holds them from the setup to the end. */
typedef struct point_run {
    whirl_chain *c;
    stability_point *pts;
    size_t count;
    double *nodes;
    char **kept; /* rows read back by --resume */
    size_t already;
    cli_lock lock;
    cli_out out, trace;
} point_run;

#define STABILITY_LINE_MAX 1024

/* The complete row line (len characters, whole and finite): kept for the point of the map
 * whose rate and mode it has (r->kept[i], the line as read) and that point marked done; a row
 * of no point of the map (or of one read already) is refused. 0, or 1 after an error. */
static int keep_row(const cli_command *cmd, const stability_options *o, point_run *r,
                    cli_resume *in, const char *line, size_t len)
{
    char rate[64];
    int mode;
    if (sscanf(line, "%63[^,],%d,", rate, &mode) == 2)
        for (size_t i = 0; i < r->count; i++) {
            stability_point *p = &r->pts[i];
            if (p->done || p->mode != mode ||
                strcmp(CLI_NUM(p->omega * unit(o, CLI_UNIT_RATE)), rate) != 0)
                continue;
            if ((r->kept[i] = malloc(len + 1)) == NULL) return cli_error(cmd, "out of memory");
            memcpy(r->kept[i], line, len + 1);
            p->done = 1;
            r->already++;
            return 0;
        }
    return cli_resume_refuse(in, "a row of no point of this map (rate and mode), or of one "
                             "read already") ? 1 : 0;
}

/* The lines before the rows (write_header's) in *text (to free). 0, or 1 after an error. */
static int expected_header(const cli_command *cmd, const stability_options *o, char **text)
{
    size_t len = 0;
    *text = NULL;
    FILE *mem = open_memstream(text, &len);
    if (mem == NULL) return cli_error(cmd, "out of memory");
    write_header(mem, o);
    if (fclose(mem) == 0) return 0;
    free(*text);
    *text = NULL;
    return cli_error(cmd, "out of memory");
}

/* --resume: reads the map in o->output, which must start with the lines write_header writes
 * for these options; each complete row must be that of a point of the map (keep_row), every
 * line checked (resume.h); an unfinished last line is dropped. r->already: the points kept.
 * Returns 0, or 1 after printing an error. */
static int resume(const cli_command *cmd, const stability_options *o, point_run *r)
{
    char *expect = NULL;
    if (expected_header(cmd, o, &expect)) return 1;
    FILE *fp = fopen(o->output, "r");
    if (fp == NULL) {
        free(expect);
        return cli_error(cmd, "--resume: cannot read '%s': %s", o->output, strerror(errno));
    }
    const cli_resume_params rp = {.header = expect, .kind = "map", .of = "options",
                                  .line_max = STABILITY_LINE_MAX};
    cli_resume *in = cli_resume_alloc(cmd, fp, o->output, &rp);
    int rc = in ? 0 : 1;
    r->already = 0;
    const char *line;
    for (cli_resume_kind kind; !rc && (kind = cli_resume_next(in, &line)) != CLI_RESUME_END;) {
        if (kind == CLI_RESUME_ERROR) rc = 1;
        else if (kind == CLI_RESUME_NOTE)
            rc = cli_resume_refuse(in, "a comment among the rows") ? 1 : 0;
        else rc = keep_row(cmd, o, r, in, line, strlen(line));
    }
    cli_resume_free(in);
    fclose(fp);
    free(expect);
    return rc;
}

/* The defaults of the options; the perturbed runs' are the library's (the method apart: rk4
 * here). */
static void set_defaults(stability_options *o)
{
    *o = (stability_options){0};
    o->links = 25;
    const whirl_stability_run_params run = whirl_stability_run_defaults();
    o->periods = run.periods;
    o->perturb = run.perturbation;
    o->seed = (int)run.seed;
    o->method = "rk4";
    o->modes.n = 3;
    o->modes.v[0] = 1, o->modes.v[1] = 2, o->modes.v[2] = 3;
    o->units = (cli_units)CLI_UNITS_INIT;
    hand_cli_defaults(&o->hand, &o->units);
}

#define STABILITY_OPTIONS_MAX 40

/* The option table of o; returns its length. */
static size_t declare_options(stability_options *o, cli_option *opts)
{
    const cli_option table[] = {
        {.name = "--omega", .type = CLI_DOUBLE, .value = &o->omega, .given = &o->omega_given,
         .meta = "W", .help = "rotation rate (one point)", .range = "(0, inf)",
         .needs = "--mode", .excludes = "--omega-min --modes",
         .required = "--omega-min", .unit = CLI_UNIT_RATE},
        {.name = "--mode", .type = CLI_INT, .value = &o->mode, .given = &o->mode_given,
         .meta = "K",
         .help = "mode (node count) at --omega: 1..N (the hand-swung chain: 1..64, or 0: its "
                 "near-axis shape)",
         .range = "[0, inf)", .needs = "--omega"},
        {.name = "--omega-min", .type = CLI_DOUBLE, .value = &o->omega_min,
         .given = &o->min_given, .meta = "A", .help = "map: first rate", .range = "(0, inf)",
         .needs = "--omega-max", .excludes = "--trace", .required = "--omega",
         .unit = CLI_UNIT_RATE},
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &o->omega_max,
         .given = &o->max_given, .meta = "B", .help = "map: last rate",
         .range = "(0, inf)", .unit = CLI_UNIT_RATE},
        {.name = "--omega-count", .type = CLI_INT, .value = &o->steps, .given = &o->steps_given,
         .meta = "N", .help = "map: number of rates, both ends included",
         .range = "[1, 10000000]", .needs = "--omega-min"},
        {.name = "--modes", .type = CLI_INT_LIST, .value = &o->modes, .given = &o->modes_given,
         .meta = "LIST",
         .help = "map: modes (default 1,2,3): 1..N (the hand-swung chain: 1..64)",
         .range = "[1, inf)"},
        {.name = "--links", .type = CLI_INT, .value = &o->links, .given = &o->links_given,
         .meta = "N",
         .help = "links of the chain (default 25)",
         .range = "[2, 100000]"},
        {.name = "--periods", .type = CLI_DOUBLE, .value = &o->periods, .meta = "P",
         .help = "run length in rotation periods (default 100)", .range = "(0, inf)"},
        {.name = "--perturb", .type = CLI_DOUBLE, .value = &o->perturb, .meta = "EPS",
         .help = "turn of each link direction [rad] (default 1e-10)", .range = "(0, 1)"},
        {.name = "--seed", .type = CLI_INT, .value = &o->seed, .meta = "S",
         .help = "seed of the perturbation (default 1)", .range = "[0, inf)"},
        CLI_DAMPING_OPTION(o->damping),
        {.name = "--method", .type = CLI_STRING, .value = &o->method, .meta = "M",
         .help = "integrator (default rk4; gauss2 for a symplectic run)"},
        {.name = "--dt", .type = CLI_DOUBLE, .value = &o->dt, .meta = "H",
         .help = "time step (default: from the highest frequency, see stability.h)",
         .range = "[0, inf)", .unit = CLI_UNIT_TIME},
        HAND_CLI_OPTIONS(o->hand),
        {.name = "--windows", .type = CLI_FLAG, .value = &o->alias,
         .help = "alias of whirl windows, kept for one release: the command line without "
                 "--windows runs whirl windows"},
        {.name = "--atlas", .type = CLI_FLAG, .value = &o->alias,
         .help = "alias of whirl windows --atlas, kept for one release"},
        {.name = "--eigenvalues", .type = CLI_FLAG, .value = &o->eigenvalues,
         .help = "single rate: every eigenvalue lambda of the linearisation (re,im), not the "
                 "run",
         .needs = "--omega", .excludes = "--trace --periods --perturb --seed --method --dt"},
        {.name = "--eigenvectors", .type = CLI_FLAG, .value = &o->eigenvectors,
         .help = "single rate: every mode of the linearisation, one row per mode and node "
                 "(eigenvalue, Krein signature, node displacement, link angles), not the run",
         .needs = "--omega --links",
         .excludes = "--eigenvalues --trace --periods --perturb --seed --method --dt"},
        {.name = "--linear", .type = CLI_FLAG, .value = &o->linear,
         .help = "eigenvalues only: no run (sim columns left empty)", .excludes = "--trace"},
        {.name = "--trace", .type = CLI_STRING, .value = &o->trace, .meta = "FILE",
         .help = "single rate: the run's deviation / initial against t (CSV)",
         .needs = "--omega"},
        {.name = "--resume", .type = CLI_FLAG, .value = &o->resume,
         .help = "map: keep the rows already in -o FILE, compute the rest",
         .needs = "--output"},
        CLI_UNITS_OPTIONS(o->units),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &o->output,
         .meta = "FILE", .help = "output file (default stdout)"},
    };
    _Static_assert(sizeof table / sizeof *table <= STABILITY_OPTIONS_MAX, "option table");
    memcpy(opts, table, sizeof table);
    return sizeof table / sizeof *table;
}

/* Parses and checks the options: 0, or the exit status after an error. */
static int parse_options(const cli_command *cmd, int argc, char **argv, stability_options *o)
{
    set_defaults(o);
    cli_option opts[STABILITY_OPTIONS_MAX];
    const size_t nopts = declare_options(o, opts);
    const int rc = hand_cli_parse(cmd, argc, argv, opts, nopts, &o->hand);
    if (rc) return rc;
    return check_options(cmd, o);
}


static void point_run_free(point_run *r)
{
    cli_lock_release(&r->lock);
    free_kept(r->kept, r->count);
    free(r->pts);
    free(r->nodes);
    whirl_chain_free(r->c);
}

/* The chain and its points, the map file locked and read back (--resume), the outputs open.
 * 0, or the exit status after an error (r freed). */
static int point_run_setup(const cli_command *cmd, const stability_options *o, point_run *r)
{
    *r = (point_run){0};
    r->c = whirl_chain_alloc_uniform((size_t)o->links, 0);
    if (r->c == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    r->pts = stability_cli_points(cmd, o, r->c, &r->count, &r->nodes);
    if (r->pts == NULL) {
        whirl_chain_free(r->c);
        return 1;
    }
    r->kept = calloc(r->count, sizeof *r->kept);
    int rc = 0;
    /* the map file is locked from before it is read until it is replaced: one run at a time
     * writes it (a new path is made empty by the run that starts it, so that two runs started
     * on it together are kept apart) */
    if (r->kept && o->min_given) rc = cli_lock_take(cmd, &r->lock, o->output, !o->resume);
    if (rc == 0 && r->kept == NULL) rc = cli_error(cmd, "out of memory");
    else if (rc == 0 && o->resume) rc = resume(cmd, o, r);
    if (rc == 0) rc = cli_out_open(cmd, &r->out, o->output);
    if (rc == 0 && o->trace && (rc = cli_out_open(cmd, &r->trace, o->trace)))
        cli_out_abort(&r->out);
    if (rc) point_run_free(r);
    return rc;
}

/* The perturbed runs (and the hand-swung chain's linear analysis) of the points not done, on
 * all threads. Returns 0, or 1 with the message of the first failure (a stop is no failure). */
static int analyse_points(const stability_options *o, point_run *r, cli_progress_state *progress,
                          long *finished, char *message, size_t size)
{
    int failed = 0;
#pragma omp parallel
    {
        whirl_stability *w = whirl_stability_alloc((size_t)o->links);
        if (w == NULL) {
#pragma omp critical(stability_error)
            if (!failed) {
                cli_library_error(&o->units, message, size);
#pragma omp atomic write
                failed = 1;
            }
        }
#pragma omp for schedule(dynamic, 1)
        for (size_t i = 0; i < r->count; i++) {
            stability_point *p = &r->pts[i];
            int stop;
#pragma omp atomic read
            stop = failed;
            if (stop || w == NULL || cli_interrupted || p->done || (!driven(o) && !p->linearised))
                continue;
            if (stability_cli_analyse(o, r->c, w, p, o->trace ? r->trace.fp : NULL) !=
                GSL_SUCCESS) {
                if (cli_interrupted) continue;
#pragma omp critical(stability_error)
                if (!failed) {
                    snprintf(message, size, "omega %s, mode %d: %s",
                             CLI_NUM(p->omega * unit(o, CLI_UNIT_RATE)), p->mode,
                             CLI_LIBRARY_ERROR(&o->units));
#pragma omp atomic write
                    failed = 1;
                }
                continue;
            }
            p->done = 1;
#pragma omp critical(stability_progress)
            cli_progress_update(progress, ++*finished, 0);
        }
        whirl_stability_free(w);
    }
    return failed;
}

/* Writes the rows kept and computed, in map order, and commits the outputs; 0, 1 after an
 * error, or CLI_EXIT_INTERRUPTED when points are missing (r freed). */
static int write_points(const cli_command *cmd, const stability_options *o, point_run *r)
{
    write_header(r->out.fp, o);
    size_t written = 0;
    const size_t count = r->count;
    for (size_t i = 0; i < count; i++) {
        if (r->kept[i]) fputs(r->kept[i], r->out.fp);
        else if (r->pts[i].done && !r->pts[i].absent) write_row(r->out.fp, o, &r->pts[i]);
        written += r->kept[i] || r->pts[i].done;
    }
    cli_lock lock = r->lock;
    r->lock = (cli_lock){0}; /* held until the outputs are in place */
    point_run_free(r);
    cli_out *const outs[2] = {&r->out, &r->trace};
    const int committed = cli_out_commit_all(cmd, outs, o->trace ? 2 : 1);
    cli_lock_release(&lock);
    if (committed) return 1;
    if (written < count) {
        if (o->min_given && o->output && strcmp(o->output, "-") != 0)
            cli_error(cmd, "interrupted: %zu of %zu points in '%s' (continue with --resume)",
                      written, count, o->output);
        else
            cli_error(cmd, "interrupted after %zu of %zu points", written, count);
        return CLI_EXIT_INTERRUPTED;
    }
    return 0;
}

/* The single rate or the map: the linear analysis of the free shapes, the perturbed runs, the
 * rows. */
static int run_points(const cli_command *cmd, const stability_options *o)
{
    point_run r;
    int rc = point_run_setup(cmd, o, &r);
    if (rc) return rc;
    cli_catch_interrupts();
    int failed = 0;
    char message[512] = "";
    long finished = (long)r.already;
    cli_progress_state progress;
    cli_progress_begin(&progress, cmd, "points", (long)r.count, (long)r.already);
    if (!driven(o) && linear_map(o, r.c, r.pts, r.count, &progress, &finished, message,
                                 sizeof message))
        failed = 1;
    if (!failed && analyse_points(o, &r, &progress, &finished, message, sizeof message))
        failed = 1;
    cli_progress_update(&progress, finished, 1);
    if (failed) {
        cli_out_abort(&r.out);
        cli_out_abort(&r.trace);
        point_run_free(&r);
        return cli_error(cmd, "%s", message);
    }
    return write_points(cmd, o, &r);
}

/* --windows or --atlas (the aliases of whirl windows, kept for one release): whirl windows on the
 * command line without --windows; -1 when neither is given. */
static int windows_alias(const cli_command *cmd, int argc, char **argv)
{
    int alias = 0;
    for (int i = 1; i < argc; i++)
        alias |= strcmp(argv[i], "--windows") == 0 || strcmp(argv[i], "--atlas") == 0;
    if (!alias) return -1;
    char **args = malloc((size_t)(argc + 1) * sizeof *args);
    if (args == NULL) return cli_error(cmd, "out of memory");
    int n = 0;
    for (int i = 0; i < argc; i++)
        if (i == 0 || strcmp(argv[i], "--windows") != 0) args[n++] = argv[i];
    args[n] = NULL;
    const int rc = cmd_windows(cmd, n, args);
    free(args);
    return rc;
}

int cmd_stability(const cli_command *cmd, int argc, char **argv)
{
    const int alias = windows_alias(cmd, argc, argv);
    if (alias >= 0) return alias;
    stability_options o;
    const int rc = parse_options(cmd, argc, argv, &o);
    if (rc) return rc;
    if (o.eigenvalues || o.eigenvectors) return stability_cli_eigen(cmd, &o);
    return run_points(cmd, &o);
}
