/* whirl windows: the intervals of omega in --omega-min..--omega-max where each mode of --modes is
 * linearly unstable, edges located by root-finding on the collision of two eigenvalues, of the
 * N-link chain with --links N (whirl_windows_find) or else of the continuous chain
 * (whirl_cstab_windows: the string equations by collocation, --degree, --tip-mass), one row per
 * window:
 *   mode,links,from,to,open_from,open_to,freq_from,freq_to,max_growth,at[,err_from,err_to]
 * (links "inf" for the continuum, which adds err_from, err_to: its estimate of each edge's
 * discretisation error) and a comment line per mode with the eigen-solves used and
 * those of a grid of equal resolution. With --links and dissipation (--damping, or the
 * hand-swung chain's drag) the intervals where each mode is unstable or converging
 * (stability_dissipative.c). --atlas: every window of the continuum's modes from each birth to
 * --omega-max with the Krein signatures at its edges, resumable (stability_atlas.c).
 * whirl stability --windows and --atlas run this command (aliases kept for one release); the
 * files keep the title line they had there ("# whirl stability --windows: ...", and the atlas's),
 * so that the files written before and after compare, and an atlas begun by either resumes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/hand_cli.h"
#include "core/error.h"
#include "cli/stability_atlas.h"
#include "cli/stability_dissipative.h"
#include "whirl/continuum_stability.h"
#include "whirl/stability.h"

typedef struct options {
    double omega_min, omega_max, scan_step, tol, tip_mass, memory, damping;
    int links, links_given, full, degree, degree_given, atlas, resume;
    int min_given, max_given, modes_given, memory_given;
    cli_int_list modes;
    const char *output;
    cli_units units;
    hand_cli hand; /* the hand-swung chain */
} options;

/* Internal damping or the hand-swung chain: whirl_windows_dissipative's intervals. */
static int dissipative(const options *o) { return o->damping > 0 || hand_cli_given(&o->hand); }

/* The size of one dimensionless unit of the kind in the user's units. */
static double unit(const options *o, cli_unit kind) { return cli_units_scale(&o->units, kind); }

/* The modes within the chain's: the N-link chain has modes 1..N, the continuum 1..WHIRL_MODE_MAX
 * (the atlas: each entry checked by the table, >= 1). */
static int check_modes(const cli_command *cmd, const options *o)
{
    const int continuum = o->atlas || !o->links_given;
    const int top = continuum ? WHIRL_MODE_MAX : o->links;
    for (int k = 0; k < o->modes.n; k++) {
        const int mode = o->modes.v[k];
        if (mode > top && continuum)
            return cli_error(cmd, "mode %d is out of range: the continuous chain takes modes "
                             "1..%d", mode, top);
        if (mode > top)
            return cli_error(cmd, "mode %d does not exist: a chain of %d links has modes 1..%d",
                             mode, top, top);
    }
    return 0;
}

/* --memory: the continuum's windows or atlas only, and within the machine's memory. */
static int check_memory(const cli_command *cmd, const options *o)
{
    if (!o->memory_given) return 0;
    if (!o->atlas && o->links_given)
        return cli_error(cmd, "--memory applies to the continuum's windows (no --links) or "
                         "--atlas");
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    const double physical = pages > 0 && size > 0 ? (double)pages * (double)size / 1048576 : 0;
    if (physical > 0 && o->memory > physical)
        return cli_error(cmd, "--memory %g MB is more than the machine's %.0f MB", o->memory,
                         physical);
    return 0;
}

/* What the option table cannot say: 0, or 1 after an error. */
static int check_options(const cli_command *cmd, const options *o)
{
    if (check_memory(cmd, o)) return 1;
    if (!(o->tol < o->scan_step))
        return cli_error(cmd, "--tol must be smaller than --scan-step");
    if (check_modes(cmd, o)) return 1;
    if (o->atlas) return 0;
    if (dissipative(o) && !o->links_given)
        return cli_error(cmd, "windows with --damping or air drag need --links N (the "
                         "continuous chain's linearisation has no dissipation)");
    if (hand_cli_given(&o->hand) && o->damping == 0 && o->hand.drag == 0 &&
        o->hand.drag2 == 0)
        return cli_error(cmd, "windows of the hand-swung chain need dissipation (--damping, "
                         "--drag, --drag-quadratic or --drag-cd): the conservative windows "
                         "are those of the free shapes");
    if (dissipative(o) && o->full)
        return cli_error(cmd, "--full applies to the conservative windows only");
    if (!(o->omega_max > o->omega_min))
        return cli_error(cmd, "need --omega-min < --omega-max");
    return hand_cli_check(cmd, &o->hand);
}

#define WINDOWS_MAX 256

/* The progress line of --windows on a terminal: the modes done and, for the continuum, the rate
 * the search of a running mode has reached (whirl_cstab_params.progress). */
typedef struct windows_progress {
    cli_progress_state line;
    const options *o;
    double after; /* the line shows after this long (cli_progress_after) [s] */
    double *reached; /* per mode: the highest rate linearised so far (NULL: not kept) */
    long done;
} windows_progress;

/* The line after mode (0: none) reached omega in its scan and linearises at now; called inside
 * the critical section. */
static void windows_progress_show(windows_progress *wp, int mode, double omega, double now)
{
    const options *o = wp->o;
    if (!wp->line.drawn && cli_wall_seconds() - wp->line.start < wp->after) return;
    const double rate = unit(o, CLI_UNIT_RATE);
    char at[96] = "";
    if (mode > 0)
        snprintf(at, sizeof at, "; mode %d: omega %.6g of %.6g (now %.6g)", mode, omega * rate,
                 o->omega_max * rate, now * rate);
    cli_progress_text(&wp->line, "windows: %ld of %d modes done%s", wp->done, o->modes.n, at);
}

/* whirl_cstab_params.progress: the rate mode's search reached. */
static void windows_progress_rate(void *ctx, int mode, double omega)
{
    windows_progress *wp = ctx;
    const double now = omega;
#pragma omp critical(windows_progress)
    {
        for (int k = 0; wp->reached && k < wp->o->modes.n; k++)
            if (wp->o->modes.v[k] == mode) {
                wp->reached[k] = fmax(wp->reached[k], omega);
                omega = wp->reached[k];
                break;
            }
        windows_progress_show(wp, mode, omega, now);
    }
}

/* The windows of one mode: of the N-link chain c, or of the continuum (c NULL); wp: the
 * progress line. */
static int find_windows(const options *o, const whirl_chain *c, int mode,
                        const whirl_windows_params *p, whirl_window *win, size_t *count,
                        whirl_windows_stats *stats, windows_progress *wp)
{
    int status;
    if (c) {
        whirl_windows *w = whirl_windows_alloc((size_t)o->links);
        status = w ? whirl_windows_find(w, c, mode, p, win, WINDOWS_MAX, count, stats)
                   : whirl_last_status();
        whirl_windows_free(w);
    } else {
        whirl_cstab_params cp = whirl_cstab_defaults();
        cp.degree = o->degree;
        cp.tip_mass = o->tip_mass;
        cp.memory_mb = o->memory;
        cp.progress = windows_progress_rate;
        cp.progress_ctx = wp;
        whirl_cstab *w = whirl_cstab_alloc(&cp);
        status = w ? whirl_cstab_windows(w, mode, p, win, WINDOWS_MAX, count, stats)
                   : whirl_last_status();
        status = stability_memory_failure(status);
        whirl_cstab_free(w);
    }
    return status;
}

/* The first comment line of --windows: the chain (c; NULL: the continuum) and the search. */
static void write_windows_title(FILE *fp, const options *o, const whirl_chain *c)
{
    const double rate = unit(o, CLI_UNIT_RATE);
    char chain[160];
    if (c)
        snprintf(chain, sizeof chain, "%d links, tip mass %s", o->links,
                 CLI_NUM(o->tip_mass * unit(o, CLI_UNIT_MASS)));
    else
        snprintf(chain, sizeof chain, "continuous chain, tip mass %s (Chebyshev collocation "
                 "of degree %d on elements)", CLI_NUM(o->tip_mass * unit(o, CLI_UNIT_MASS)),
                 o->degree);
    fprintf(fp, "# whirl stability --windows: %s, omega %s..%s, scan step %s, edges "
                "to %s, refinement %s\n", chain, CLI_NUM(o->omega_min * rate),
            CLI_NUM(o->omega_max * rate), CLI_NUM(o->scan_step * rate), CLI_NUM(o->tol * rate),
            o->full ? "full eigen-solves" : "shift-and-invert Arnoldi");
}

/* The windows of each mode k: count[k] of them from win + k WINDOWS_MAX, found in seconds[k]
 * with stats[k] and status[k] (err[k]: its failure). */
typedef struct windows_found {
    whirl_window *win;
    size_t *count;
    whirl_windows_stats *stats;
    double *seconds;
    whirl_error_record *err;
    int *status;
} windows_found;

static int windows_found_alloc(windows_found *f, size_t nmodes)
{
    f->win = calloc(nmodes * WINDOWS_MAX, sizeof *f->win);
    f->count = calloc(nmodes, sizeof *f->count);
    f->stats = calloc(nmodes, sizeof *f->stats);
    f->seconds = calloc(nmodes, sizeof *f->seconds);
    f->err = calloc(nmodes, sizeof *f->err);
    f->status = calloc(nmodes, sizeof *f->status);
    return f->win && f->count && f->stats && f->seconds && f->err && f->status ? 0 : -1;
}

static void windows_found_free(windows_found *f)
{
    free(f->win), free(f->count), free(f->stats), free(f->seconds), free(f->err);
    free(f->status);
}

/* The comment line of mode k: its eigen-solves, or why it was not done. */
static void write_windows_mode(FILE *fp, const options *o, const windows_found *f, int k)
{
    const double rate = unit(o, CLI_UNIT_RATE);
    if (f->status[k] == WHIRL_EINTERRUPTED) {
        fprintf(fp, "# mode %d: interrupted, not done\n", o->modes.v[k]);
        return;
    }
    if (f->status[k] != GSL_SUCCESS) {
        whirl_error_restore(&f->err[k]);
        fprintf(fp, "# mode %d: not done: %s\n", o->modes.v[k], CLI_LIBRARY_ERROR(&o->units));
        return;
    }
    const whirl_windows_stats *st = &f->stats[k];
    fprintf(fp, "# mode %d: examined %s..%s, %zu windows, %zu scan points, %zu "
                "eigen-solves (%zu with vectors, %zu eigenvalues only, %zu Arnoldi), "
                "%zu shapes, %.3g s; a grid of spacing %s needs %.3g solves\n",
            o->modes.v[k], CLI_NUM(st->omega_from * rate), CLI_NUM(st->omega_to * rate),
            f->count[k], st->scan, st->solves_vectors + st->solves_values + st->solves_krylov,
            st->solves_vectors, st->solves_values, st->solves_krylov, st->shapes, f->seconds[k],
            CLI_NUM(o->tol * rate), (st->omega_to - st->omega_from) / o->tol + 1);
}

/* The windows of the modes done as CSV, after a comment line per mode with its eigen-solves
 * (or that it was not done). */
static void write_windows(FILE *fp, const options *o, const whirl_chain *c,
                          const windows_found *f)
{
    const double rate = unit(o, CLI_UNIT_RATE);
    write_windows_title(fp, o, c);
    for (int k = 0; k < o->modes.n; k++) write_windows_mode(fp, o, f, k);
    cli_units_comment(fp, &o->units);
    fprintf(fp, "mode,links,from,to,open_from,open_to,freq_from,freq_to,max_growth,at%s\n",
            c ? "" : ",err_from,err_to");
    char links[16];
    if (c) snprintf(links, sizeof links, "%d", o->links);
    else snprintf(links, sizeof links, "inf");
    for (int k = 0; k < o->modes.n; k++)
        for (size_t i = 0; f->status[k] == GSL_SUCCESS && i < f->count[k]; i++) {
            const whirl_window *x = f->win + (size_t)k * WINDOWS_MAX + i;
            fprintf(fp, "%d,%s,%s,%s,%d,%d,%s,%s,%s,%s", o->modes.v[k], links,
                    CLI_NUM(x->from * rate), CLI_NUM(x->to * rate), x->open_from, x->open_to,
                    CLI_NUM(x->freq_from * rate), CLI_NUM(x->freq_to * rate),
                    CLI_NUM(x->max_growth * rate), CLI_NUM(x->at * rate));
            if (!c)
                fprintf(fp, ",%s,%s", CLI_NUM(x->err_from * rate), CLI_NUM(x->err_to * rate));
            fputc('\n', fp);
        }
}

/* The windows of the first n modes (all, or none after a failed allocation), one per thread,
 * with a progress line on a terminal. */
static void find_all_windows(const cli_command *cmd, const options *o, const whirl_chain *c,
                             size_t n, const whirl_windows_params *p, windows_found *f)
{
    windows_progress wp = {.o = o, .after = cli_progress_after(),
                           .reached = calloc((size_t)o->modes.n, sizeof *wp.reached)};
    cli_progress_begin(&wp.line, cmd, "", 0, 0);
#pragma omp parallel for schedule(dynamic, 1)
    for (size_t k = 0; k < n; k++) {
        const double t0 = cli_wall_seconds();
        f->status[k] = find_windows(o, c, o->modes.v[k], p, f->win + k * WINDOWS_MAX,
                                    &f->count[k], &f->stats[k], &wp);
        whirl_error_keep(&f->err[k], f->status[k]);
#pragma omp critical(windows_progress)
        {
            f->seconds[k] = cli_wall_seconds() - t0;
            wp.done++;
            windows_progress_show(&wp, 0, 0, 0);
        }
    }
    cli_progress_clear(&wp.line);
    free(wp.reached);
}

/* The file of the modes done (none: no file) and the exit status: 0; after a failure its
 * message, 1; after a stop, CLI_EXIT_INTERRUPTED (a failure first). */
static int finish_windows(const cli_command *cmd, const options *o, const whirl_chain *c,
                          const windows_found *f)
{
    const size_t nmodes = (size_t)o->modes.n;
    size_t done = 0;
    for (size_t k = 0; k < nmodes; k++) done += f->status[k] == GSL_SUCCESS;
    cli_out out;
    if (done > 0) {
        if (cli_out_open(cmd, &out, o->output)) return 1;
        write_windows(out.fp, o, c, f);
        if (cli_out_commit(cmd, &out)) return 1;
    }
    if (done == nmodes) return 0;
    const int file = done > 0 && o->output != NULL && strcmp(o->output, "-") != 0;
    char where[CLI_MESSAGE_MAX / 2] = "";
    if (file)
        snprintf(where, sizeof where, "; %zu of %zu modes written to '%s'", done, nmodes,
                 o->output);
    const int failed = whirl_error_restore_first(f->err, nmodes);
    if (failed != WHIRL_EINTERRUPTED) {
        cli_error(cmd, "%s%s", CLI_LIBRARY_ERROR(&o->units), where);
        return 1;
    }
    for (size_t k = 0; k < nmodes; k++) /* a failure beside the stop is named first */
        if (f->status[k] != GSL_SUCCESS && f->status[k] != WHIRL_EINTERRUPTED) {
            whirl_error_restore(&f->err[k]);
            cli_error(cmd, "%s%s", CLI_LIBRARY_ERROR(&o->units), where);
            return 1;
        }
    cli_error(cmd, "interrupted: %zu of %zu modes done%s%s%s", done, nmodes,
              file ? " in '" : "", file ? o->output : "", file ? "'" : "");
    return CLI_EXIT_INTERRUPTED;
}

/* The search's parameters from the options: the range, the scan's step, the edges' tolerance. */
static whirl_windows_params windows_params(const options *o)
{
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = o->omega_min;
    p.omega_max = o->omega_max;
    p.scan_step = o->scan_step;
    p.tol = o->tol;
    return p;
}

/* --windows: every mode of the list, one per thread; a stop or a failure keeps the modes
 * finished (each whole), the others marked. */
static int run_windows(const cli_command *cmd, const options *o)
{
    whirl_chain *c = NULL;
    if (o->links_given && (c = whirl_chain_alloc_uniform((size_t)o->links, o->tip_mass)) == NULL)
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    const size_t nmodes = (size_t)o->modes.n;
    windows_found f;
    int rc = windows_found_alloc(&f, nmodes) ? cli_error(cmd, "out of memory") : 0;
    whirl_windows_params p = windows_params(o);
    p.krylov = !o->full;
    cli_catch_interrupts();
    find_all_windows(cmd, o, c, rc ? 0 : nmodes, &p, &f);
    if (!rc) rc = finish_windows(cmd, o, c, &f);
    windows_found_free(&f);
    whirl_chain_free(c);
    return rc;
}

/* The defaults of the options. */
static void set_defaults(options *o)
{
    *o = (options){0};
    o->links = 25;
    o->modes.n = 3;
    o->modes.v[0] = 1, o->modes.v[1] = 2, o->modes.v[2] = 3;
    o->scan_step = 0.25;
    o->tol = 1e-9;
    o->degree = whirl_cstab_defaults().degree;
    o->memory = whirl_cstab_defaults().memory_mb;
    o->units = (cli_units)CLI_UNITS_INIT;
    hand_cli_defaults(&o->hand, &o->units);
}

#define WINDOWS_OPTIONS_MAX 32

/* The option table of o; returns its length. */
static size_t declare_options(options *o, cli_option *opts)
{
    const cli_option table[] = {
        {.name = "--omega-min", .type = CLI_DOUBLE, .value = &o->omega_min,
         .given = &o->min_given, .meta = "A", .help = "first rate", .range = "(0, inf)",
         .needs = "--omega-max", .excludes = "--atlas", .required = "--atlas",
         .unit = CLI_UNIT_RATE},
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &o->omega_max,
         .given = &o->max_given, .meta = "B", .help = "last rate (--atlas: default 40)",
         .range = "(0, inf)", .unit = CLI_UNIT_RATE},
        {.name = "--modes", .type = CLI_INT_LIST, .value = &o->modes, .given = &o->modes_given,
         .meta = "LIST",
         .help = "modes (default 1,2,3; --atlas: 2-8): 1..N (the continuous chain: 1..64)",
         .range = "[1, inf)"},
        {.name = "--links", .type = CLI_INT, .value = &o->links, .given = &o->links_given,
         .meta = "N", .help = "links of the N-link chain (default: the continuous chain)",
         .range = "[2, 100000]"},
        {.name = "--scan-step", .type = CLI_DOUBLE, .value = &o->scan_step, .meta = "H",
         .help = "spacing of the scan (default 0.25)", .range = "(0, inf)",
         .unit = CLI_UNIT_RATE},
        {.name = "--tol", .type = CLI_DOUBLE, .value = &o->tol, .meta = "T",
         .help = "edges located to T in omega (default 1e-9)", .range = "[1e-13, inf)",
         .unit = CLI_UNIT_RATE},
        {.name = "--full", .type = CLI_FLAG, .value = &o->full,
         .help = "full eigen-solves near the edges, for the N-link chain at every rate "
                 "(default: shift-and-invert Arnoldi)"},
        {.name = "--degree", .type = CLI_INT, .value = &o->degree, .given = &o->degree_given,
         .meta = "P", .help = "the continuum: Chebyshev degree per element (default 16)",
         .range = "[6, 64]", .excludes = "--links"},
        {.name = "--memory", .type = CLI_DOUBLE, .value = &o->memory,
         .given = &o->memory_given, .meta = "MB",
         .help = "the continuum: memory bound of the collocation (default 1024; at most the "
                 "machine's)",
         .range = "[16, 1048576]"},
        {.name = "--tip-mass", .type = CLI_DOUBLE, .value = &o->tip_mass, .meta = "m",
         .help = "point mass at the free end (default 0)", .range = "[0, 1e12]",
         .excludes = "--atlas", .unit = CLI_UNIT_MASS},
        {.name = "--damping", .type = CLI_DOUBLE, .value = &o->damping, .meta = "D",
         .help = "internal damping of the joints (default 0; with --links: the intervals "
                 "unstable or converging)",
         .range = "[0, inf)", .excludes = "--atlas", .unit = CLI_UNIT_DAMPING},
        HAND_CLI_OPTIONS(o->hand),
        {.name = "--atlas", .type = CLI_FLAG, .value = &o->atlas,
         .help = "every window of the continuum's --modes from each birth to --omega-max, with "
                 "the Krein signatures at the edges (-o FILE, resumable)",
         .needs = "--output",
         .excludes = "--links --full --eps --drag --drag-quadratic --drag-cd --side"},
        {.name = "--resume", .type = CLI_FLAG, .value = &o->resume,
         .help = "atlas: keep the chunks already in -o FILE, compute the rest",
         .needs = "--atlas --output"},
        CLI_UNITS_OPTIONS(o->units),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &o->output,
         .meta = "FILE", .help = "output file (default stdout)"},
    };
    _Static_assert(sizeof table / sizeof *table <= WINDOWS_OPTIONS_MAX, "option table");
    memcpy(opts, table, sizeof table);
    return sizeof table / sizeof *table;
}

/* Parses and checks the options: 0, or the exit status after an error. */
static int parse_options(const cli_command *cmd, int argc, char **argv, options *o)
{
    set_defaults(o);
    cli_option opts[WINDOWS_OPTIONS_MAX];
    const size_t nopts = declare_options(o, opts);
    const int rc = hand_cli_parse(cmd, argc, argv, opts, nopts, &o->hand);
    if (rc) return rc;
    if (o->atlas) {
        if (!o->modes_given) {
            o->modes.n = 7;
            for (int k = 0; k < 7; k++) o->modes.v[k] = 2 + k;
        }
        if (!o->max_given) o->omega_max = 40;
    }
    return check_options(cmd, o);
}

/* --windows with dissipation (internal damping or the hand-swung chain's drag): the intervals
 * where each mode is unstable or converging. */
static int run_windows_dissipative(const cli_command *cmd, const options *o)
{
    whirl_model m = {0};
    m.dim = 3;
    m.internal_damping = o->damping;
    m.drive_radius = o->hand.eps;
    m.air_drag = o->hand.drag;
    m.air_drag_quadratic = o->hand.drag2;
    const whirl_windows_params p = windows_params(o);
    return stability_dissipative(cmd, &o->modes, o->links, o->tip_mass, &m, o->hand.side, &p,
                                 &o->units, o->output);
}

int cmd_windows(const cli_command *cmd, int argc, char **argv)
{
    options o;
    const int rc = parse_options(cmd, argc, argv, &o);
    if (rc) return rc;
    if (o.atlas)
        return stability_atlas(cmd, &o.modes, o.omega_max, o.degree, o.memory, o.tol,
                               o.scan_step, o.output, o.resume);
    if (dissipative(&o)) return run_windows_dissipative(cmd, &o);
    return run_windows(cmd, &o);
}
