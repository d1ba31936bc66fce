/* whirl simulate SCENE [-o FILE] [--set section.key=value ...] [--pivot PATH] [--animate MOVIE]:
 * runs the scene (whirl/scene.h: the start state, the rows and the trace are the library's
 * whirl_scene_work_run; --pivot PATH the scene's [run] pivot, whirl_scene_pivot_from_text)
 * and writes the asked columns as CSV, optionally the trace of every mass, and with --animate a
 * movie of the trace (figure.h: MP4, WebM or GIF; the trace, unless the scene names one, is
 * taken every 1/25 s of the run's time in SI units, at most 250 frames, and played at 25 frames
 * a second: real time up to 10 s).
 * Exit status: 0 (also when the stop condition ends the run, with a note on stderr); 1 on bad
 * input or a failed run (nothing written); 130 after Ctrl-C (the rows so far kept). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <gsl/gsl_math.h>

#include "cli/figure.h"
#include "core/error.h"
#include "studies/scene_internal.h"
#include "whirl/scene.h"

/* Everything one run needs. */
typedef struct run {
    const cli_command *cmd;
    whirl_scene scene;
    whirl_scene_pivot pivot; /* [run] pivot, or --pivot */
    const char *pivot_text;  /* --pivot (NULL: not given) */
    whirl_scene_work *work;
    cli_out csv, trace;
    int csv_open, trace_open;
    unsigned long frames;       /* written so far */
    cli_progress_state progress; /* output intervals done of all, time left */
    char failure[CLI_MESSAGE_MAX]; /* how the run ended, printed once the files are settled */
} run;

/* "WHERE: message" for a key of the scene, as the one-line error of the command. */
static int key_error(const run *r, whirl_scene_key key, const char *message)
{
    char where[512];
    return cli_error(r->cmd, "%s: %s", whirl_scene_where(&r->scene, key, where, sizeof where),
                     message);
}

static int on_row(void *ctx, const double *value)
{
    run *r = ctx;
    return whirl_scene_write_row(r->csv.fp, &r->scene, value);
}

static int on_frame(void *ctx, double t, const double *pivot, const double *x, size_t n)
{
    run *r = ctx;
    if (r->frames == 0) { /* the trace opens with its parameters and units (the scene's) */
        const whirl_scene *s = &r->scene;
        const cli_units si = {s->chain_length, s->chain_mass, s->gravity, 1};
        const cli_units dimensionless = CLI_UNITS_INIT, u = s->physical ? si : dimensionless;
        /* a pivot on a path: named by its terms, as the CSV's "# pivot =" line (no drive
           radius with it: eps would say 0, a pivot at rest) */
        char *text = NULL;
        size_t len = 0;
        FILE *mem = r->pivot.given ? open_memstream(&text, &len) : NULL;
        if (mem) sc_write_pivot_text(mem, &r->pivot.path);
        if (mem && fclose(mem) != 0) {
            free(text);
            text = NULL;
        }
        if (r->pivot.given && text == NULL)
            return whirl_fail(GSL_ENOMEM, "out of memory for the trace's header");
        cli_trace_header(r->trace.fp, &u, "whirl simulate", s->omega / cli_units_scale(&u, CLI_UNIT_RATE),
                         s->drive_radius / cli_units_scale(&u, CLI_UNIT_LENGTH), text,
                         s->air_drag / cli_units_scale(&u, CLI_UNIT_DRAG),
                         s->air_drag_quadratic / cli_units_scale(&u, CLI_UNIT_DRAG2), (int)s->links);
        free(text);
    }
    return whirl_scene_write_frame(r->trace.fp, r->frames++, t, pivot, x, n);
}

/* The output intervals [0, every], ... up to t_end, all of them and those done at t. */
static long intervals(const whirl_scene *s, double t)
{
    const double k = ceil(t / s->every - 1e-9);
    return k < 1 ? 0 : k > 1e15 ? 1000000000000000L : (long)k;
}

static int on_progress(void *ctx, double t)
{
    run *r = ctx;
    cli_progress_update(&r->progress, intervals(&r->scene, t) - (t < r->scene.t_end), 0);
    return GSL_SUCCESS;
}

/* The run. Returns the exit status: 0 (also after a stop condition), 1 after a failure, 130
 * after an interrupt; the rows written so far are kept in every case. */
static int simulate(run *r)
{
    const whirl_scene *s = &r->scene;
    const whirl_scene_output out = {.row = on_row,
                                    .frame = s->trace ? on_frame : NULL,
                                    .progress = on_progress,
                                    .ctx = r};
    whirl_scene_result res;
    cli_catch_interrupts();
    cli_progress_begin(&r->progress, r->cmd, "intervals", intervals(s, s->t_end), 0);
    int status = whirl_scene_write_header_with_pivot(r->csv.fp, s, &r->pivot);
    if (status == GSL_SUCCESS) status = whirl_scene_work_run(r->work, &out, &res);
    cli_progress_update(&r->progress, intervals(s, res.t), 1);
    if (status == WHIRL_EINTERRUPTED) {
        snprintf(r->failure, sizeof r->failure, "%s: %lu rows kept", whirl_last_error(), res.rows);
        return CLI_EXIT_INTERRUPTED;
    }
    if (status != GSL_SUCCESS) {
        snprintf(r->failure, sizeof r->failure, "%s: %s; no file written", s->path,
                 whirl_last_error());
        return 1;
    }
    if (res.stopped)
        fprintf(stderr, "whirl %s: stopped at t = %.17g: deviation %.6g > %.6g\n", r->cmd->name,
                res.t, res.deviation, s->stop_deviation);
    double rate;
    if (res.stopped && whirl_scene_stiff(s, &rate)) /* the steps' blow-up, not the chain's */
        fprintf(stderr, "whirl %s: note: %s the chain stiff (decay rates up to about %.2g %s, "
                "dt x rate = %.2g): the deviation may be the steps' instability; method = "
                "gsl-msbdf with tol (1e-6) steps over it\n", r->cmd->name, sc_stiff_cause(s),
                rate, s->physical ? "/s" : "sqrt(g/L)", rate * s->dt);
    return 0;
}

/* The files of the run before it starts (cli_check_files): the CSV and the trace, not one file,
 * neither the scene; a trace named by the scene file (not by --set) replaces no file unless
 * --overwrite is given. */
static int check_trace(run *r, const char *scene_path, const char *output, int overwrite)
{
    const cli_path outs[2] = {{"--output", output}, {"[output] trace", r->scene.trace}};
    const cli_path in = {"scene", scene_path};
    if (cli_check_files(r->cmd, outs, r->scene.trace ? 2 : 1, &in, 1)) return 1;
    struct stat st;
    if (r->scene.trace && r->scene.line[WHIRL_KEY_OUTPUT_TRACE] > 0 && !overwrite &&
        lstat(r->scene.trace, &st) == 0)
    {
        char where[512];
        return cli_error(r->cmd, "%s: '%s' exists: a scene file replaces no file (give "
                         "--overwrite, or --set output.trace=PATH)",
                         whirl_scene_where(&r->scene, WHIRL_KEY_OUTPUT_TRACE, where, sizeof where),
                         r->scene.trace);
    }
    return 0;
}

/* A step that cannot resolve the motion: dt above a quarter of the rotation period (with a
 * pivot path, of its fastest harmonic's), or above half the period of the chain's fastest swing,
 * pi sqrt(L/g) / N (the top mode of N links hanging, frequency about 2 N sqrt(g/L): links of
 * length L/N under the tension of the whole chain); a message on stderr, the run goes on. */
static void check_step(const cli_command *cmd, const whirl_scene *s, const whirl_scene_pivot *p)
{
    const double pi = 3.141592653589793;
    const double g = s->physical ? s->gravity : 1, len = s->physical ? s->chain_length : 1;
    const double t_fast = pi * sqrt(len / g) / (double)s->links;
    const double fastest = p->given ? p->path.harmonics * s->omega : s->omega;
    const double t_rot = fastest > 0 ? 2 * pi / fastest : HUGE_VAL;
    const char *unit = s->physical ? " s" : " sqrt(L/g)";
    if (s->tol > 0) return;
    if (s->dt > 0.25 * t_rot)
        fprintf(stderr, "whirl %s: dt = %.3g%s is larger than a quarter of the %s period "
                "(%.3g%s): the steps cannot follow %s\n", cmd->name, s->dt, unit,
                p->given ? "pivot path's" : "rotation", t_rot, unit,
                p->given ? "the pivot" : "the turning chain");
    else if (s->dt > 0.5 * t_fast)
        fprintf(stderr, "whirl %s: dt = %.3g%s is larger than half the period of the chain's "
                "fastest swing (%.3g%s, pi sqrt(L/g) / N): the steps cannot follow it\n",
                cmd->name, s->dt, unit, t_fast, unit);
}

/* The scene with its overrides, and its pivot's path: [run] pivot, or --pivot (which replaces
 * it). 0, or 1 after an error. */
static int parse_scene(run *r, const char *scene_path, const char *const *sets, size_t n_sets)
{
    whirl_scene_free(&r->scene);
    if (whirl_scene_parse_with_pivot(scene_path, sets, n_sets, &r->scene, &r->pivot) !=
        GSL_SUCCESS)
        return cli_error(r->cmd, "%s", whirl_last_error());
    if (r->pivot_text &&
        whirl_scene_pivot_from_text(&r->scene, r->pivot_text, &r->pivot) != GSL_SUCCESS)
        return cli_error(r->cmd, "--pivot: %s", whirl_last_error());
    return 0;
}

/* With --animate and no trace in the scene: the scene parsed again with a trace in the movie's
 * work folder, a frame every 1/25 s (SI) or every t_end/125 (dimensionless), at most 250; with
 * --slow F a frame every 1/(25 F) s (25 frames a second of the movie), with --frames-per-turn K
 * K frames a turn of the rotation (and F for 25 frames a second), at most 1500 (a minute of the
 * movie: drawing them takes about as long). */
static int add_trace(run *r, const char *scene_path, const char **sets, size_t n_sets,
                     const char *dir, char *trace, size_t size, cli_figure_style *style,
                     int frames_per_turn)
{
    /* 25 frames a second: a smooth movie in every format (GIF's delays are 1/100 s) */
    const double fps = 25;
    char every[64];
    double dt = r->scene.physical ? 1 / fps : r->scene.t_end / 125, frames_max = 250;
    if (frames_per_turn > 0) {
        if (!(fabs(r->scene.omega) > 0))
            return cli_error(r->cmd, "--frames-per-turn: the scene does not turn ([run] omega "
                             "and [start] omega are 0)");
        dt = 2 * M_PI / fabs(r->scene.omega) / frames_per_turn;
        style->slow = 1 / (fps * dt);
    } else if (style->slow > 0) {
        dt = 1 / (fps * style->slow);
    }
    if (frames_per_turn > 0 || style->slow > 0) frames_max = 1500;
    if (r->scene.t_end / dt > frames_max) {
        if (frames_max > 250)
            return cli_error(r->cmd, "the movie would have %.0f frames, over %.0f (a minute at 25 "
                             "a second): a shorter run.t_end, or less --slow or "
                             "--frames-per-turn", r->scene.t_end / dt, frames_max);
        dt = r->scene.t_end / frames_max;
    }
    snprintf(trace, size, "output.trace=%s/trace.dat", dir);
    snprintf(every, sizeof every, "output.trace_every=%.17g", dt);
    sets[n_sets] = trace;
    sets[n_sets + 1] = every;
    return parse_scene(r, scene_path, sets, n_sets + 2);
}

/* Takes every --set out of argv (sets[0..*n_sets)) and leaves the rest, argv[0] first, in
 * rest[0..*n_rest) (NULL after): 0, or 1 after an error. */
static int take_sets(const cli_command *cmd, int argc, char **argv, const char **sets,
                     size_t *n_sets, char **rest, int *n_rest)
{
    rest[(*n_rest)++] = argv[0];
    int rc = 0;
    for (int i = 1; i < argc && rc == 0; i++) {
        if (strcmp(argv[i], "--set") == 0) {
            if (i + 1 == argc) rc = cli_error(cmd, "option --set needs a value (SEC.KEY=V)");
            else sets[(*n_sets)++] = argv[++i];
        } else if (strncmp(argv[i], "--set=", 6) == 0)
            sets[(*n_sets)++] = argv[i] + 6;
        else
            rest[(*n_rest)++] = argv[i];
    }
    rest[*n_rest] = NULL;
    return rc;
}

/* Opens the outputs, runs the scene and commits them (or aborts): 0, or the exit status. */
static int run_scene(run *r, const char *output)
{
    const cli_command *cmd = r->cmd;
    int rc = 0;
    if ((r->work = whirl_scene_work_alloc_with_pivot(&r->scene, &r->pivot)) == NULL)
        rc = cli_error(cmd, "%s", whirl_last_error());
    if (rc == 0) rc = cli_out_open(cmd, &r->csv, output);
    if (rc == 0) r->csv_open = 1;
    if (rc == 0 && r->scene.trace) {
        rc = cli_out_open(cmd, &r->trace, r->scene.trace);
        if (rc == 0) r->trace_open = 1;
    }
    if (rc == 0) {
        rc = simulate(r);
        /* A run stopped by a signal keeps the rows written so far: both files, or neither. A
         * failed run leaves no file (aborted below), and says why; unless a file could not be
         * written (a full disk, a broken pipe): that is then the one error. */
        cli_out *const outs[2] = {&r->csv, &r->trace};
        const size_t n_outs = r->trace_open ? 2 : 1;
        const int write_failed = ferror(r->csv.fp) || (r->trace_open && ferror(r->trace.fp));
        if (rc != 1 || write_failed) {
            if (cli_out_commit_all(cmd, outs, n_outs) != 0) {
                if (rc == 0) rc = 1;
            } else if (r->failure[0]) cli_error(cmd, "%s", r->failure);
            r->csv_open = r->trace_open = 0;
        } else cli_error(cmd, "%s", r->failure);
    }
    if (r->csv_open) cli_out_abort(&r->csv);
    if (r->trace_open) cli_out_abort(&r->trace);
    return rc;
}

int cmd_simulate(const cli_command *cmd, int argc, char **argv)
{
    const char *output = NULL, *set_help = NULL; /* --set is taken out before cli_parse */
    int overwrite = 0;
    const char *movie = NULL;
    cli_figure_style style = {0};
    int frames_per_turn = 0;
    run r;
    memset(&r, 0, sizeof r);
    r.cmd = cmd;
    const cli_option opts[] = {
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &output, .meta = "FILE",
         .help = "write the CSV to FILE (default stdout)"},
        {.name = "--set", .type = CLI_STRING, .value = &set_help, .meta = "SEC.KEY=V",
         .help = "override a key of the scene (repeatable)"},
        CLI_PIVOT_OPTION(r.pivot_text, " at the scene's [run] omega, lengths in its units "
                         "(replaces [run] pivot)", NULL),
        {.name = "--overwrite", .type = CLI_FLAG, .value = &overwrite,
         .help = "let the scene's [output] trace replace an existing file"},
        {.name = "--animate", .type = CLI_STRING, .value = &movie, .meta = "MOVIE",
         .help = "a movie of the run: MOVIE.mp4, .webm or .gif (gnuplot and ffmpeg)"},
        CLI_FIGURE_OPTIONS(style),
        CLI_MOVIE_OPTIONS(style),
        {.name = "--frames-per-turn", .type = CLI_INT, .value = &frames_per_turn, .meta = "K",
         .help = "K frames a turn of the rotation, 25 a second (slow motion to match)",
         .range = "[2, 1000]", .excludes = "--slow"},
    };
    /* --set may repeat: take every one out before the common parser sees the rest (room for two
     * more: the trace --animate adds) */
    const char **sets = malloc(((size_t)argc + 2) * sizeof *sets);
    char **rest = malloc(((size_t)argc + 1) * sizeof *rest);
    if (sets == NULL || rest == NULL) {
        free(sets);
        free(rest);
        return cli_error(cmd, "out of memory");
    }
    size_t n_sets = 0;
    int n_rest = 0;
    int rc = take_sets(cmd, argc, argv, sets, &n_sets, rest, &n_rest);
    const char *scene_path = NULL;
    if (rc == 0) rc = cli_parse(cmd, n_rest, rest, opts, sizeof opts / sizeof *opts, &scene_path, 1);
    if (rc == 0 && scene_path == NULL) rc = cli_error(cmd, "missing the scene file (see --help)");
    if (rc == 0 && movie && cli_figure_check_out(cmd, "--animate", movie, 1)) rc = 1;
    if (rc == 0 && movie && output == NULL) output = "/dev/null"; /* the movie alone */
    if (rc == 0 && !movie && (style.size || style.present || style.slow > 0 || frames_per_turn))
        rc = cli_error(cmd, "--size, --present, --slow and --frames-per-turn shape the movie of "
                       "--animate");
    int box_w, box_h;
    if (rc == 0 && cli_figure_size(cmd, &style, &box_w, &box_h)) rc = 1;

    char *dir = NULL, trace_set[4200];
    if (rc == 0) rc = parse_scene(&r, scene_path, sets, n_sets);
    if (rc == 0 && movie && r.scene.trace && frames_per_turn)
        rc = cli_error(cmd, "--frames-per-turn spaces the movie's trace, but the scene writes "
                       "its own ([output] trace): use --slow");
    if (rc == 0 && movie && r.scene.trace == NULL) {
        if ((dir = cli_figure_work_dir(cmd, movie)) == NULL) rc = 1;
        else rc = add_trace(&r, scene_path, sets, n_sets, dir, trace_set, sizeof trace_set,
                            &style, frames_per_turn);
    }
    free(sets);
    free(rest);
    if (rc != 0) {
        whirl_scene_free(&r.scene);
        cli_figure_remove_dir(dir);
        return rc;
    }
    check_step(cmd, &r.scene, &r.pivot);
    if (r.scene.trace && strcmp(r.scene.trace, "-") == 0)
        rc = key_error(&r, WHIRL_KEY_OUTPUT_TRACE, "must be a file, not standard output");
    if (rc == 0) rc = check_trace(&r, scene_path, output, overwrite);
    if (rc == 0) rc = run_scene(&r, output);
    if (rc == 0 && movie) {
        const char *trace = r.scene.trace;
        rc = cli_figure_draw(cmd, &trace, 1, movie, &style);
    }
    cli_figure_remove_dir(dir);
    whirl_scene_work_free(r.work);
    whirl_scene_free(&r.scene);
    return rc;
}
