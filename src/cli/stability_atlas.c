/* whirl stability --atlas: every window of instability of the continuous chain's modes from
 * each mode's birth omega_k to --omega-max (whirl_cstab_windows), with the Krein signatures of
 * the colliding pair at each edge, one row per window:
 *   mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,max_growth,at,err_from,err_to
 * sig_from / sig_to: the Krein signature (sign of the mode's energy) of the slower of the two
 * neutral modes that collide there, on the stable side of the edge (1e-6 from it; the faster
 * one has the opposite sign), 0 at an open end or where no pair of opposite signs is found;
 * err: the edges' discretisation error estimates (whirl_window).
 * The range of each mode is cut into chunks at the multiples of ATLAS_CHUNK; after each chunk
 * the file is rewritten (atomically) with the windows so far and a line "# done mode K omega A
 * B" per chunk finished, windows that cross a chunk's end being joined. Ctrl-C keeps the chunks
 * finished; --resume reads them back and computes the rest (resume.h: the file locked for the
 * whole run, its header the same as this run's, which records every option that changes a row,
 * every line checked). A terminal shows the chunks done. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/resume.h"
#include "cli/stability_atlas.h"
#include "core/error.h"
#include "whirl/continuum_stability.h"
#include "whirl/steady.h"

#define ATLAS_CHUNK 5.0   /* chunk ends at the multiples of this rate [sqrt(g/L)] */
#define ATLAS_WINDOWS 4096 /* windows of all modes at most */
#define ATLAS_CHUNK_WINDOWS 256
#define ATLAS_SIDE 1e-6   /* the signatures are taken this far outside each edge */
#define ATLAS_LINE_MAX 1024 /* characters of a line of the file (a row has 13 numbers) */

typedef struct atlas_row {
    int mode;
    whirl_window w;
    int sig_from, sig_to;
} atlas_row;

/* The options that change a row (all in the file's header). */
typedef struct atlas_options {
    const cli_int_list *modes;
    double omega_max, tol, scan_step;
    int degree;
} atlas_options;

typedef struct atlas {
    atlas_row *rows;
    size_t count;
    int *done;       /* per mode and chunk: 1 once finished */
    size_t nchunks;  /* chunks per mode (from rate 0 to omega_max) */
} atlas;

/* The signature of the slower mode of the neutral pair nearest the collision frequency freq at
 * omega (0 if none of opposite signs is found). */
static int edge_signature(whirl_cstab *w, int mode, double omega, double freq, int *sig)
{
    *sig = 0;
    whirl_spectrum sp;
    int status = whirl_cstab_linearise(w, omega, mode, 0, NULL);
    if (!status) status = whirl_cstab_spectrum(w, 1, &sp);
    if (status) return status;
    const double target = -freq * freq;
    size_t a = sp.count, b = sp.count; /* the two neutral mu nearest -freq^2 */
    for (size_t i = 0; i < sp.count; i++) {
        if (sp.signature[i] == 0) continue;
        const double d = fabs(sp.re[i] - target);
        if (a == sp.count || d < fabs(sp.re[a] - target)) b = a, a = i;
        else if (b == sp.count || d < fabs(sp.re[b] - target)) b = i;
    }
    if (b == sp.count || sp.signature[a] == sp.signature[b]) return GSL_SUCCESS;
    const size_t slow = sp.re[a] > sp.re[b] ? a : b; /* mu = -f^2: the larger mu is slower */
    *sig = sp.signature[slow];
    return GSL_SUCCESS;
}

/* Adds the windows of one chunk of mode k, joining one that continues a window open at the
 * chunk's start. */
static int add_rows(atlas *a, int mode, const whirl_window *win, size_t n, const int *sig)
{
    for (size_t i = 0; i < n; i++) {
        atlas_row *prev = NULL;
        for (size_t j = 0; j < a->count; j++)
            if (a->rows[j].mode == mode && a->rows[j].w.open_to && win[i].open_from &&
                fabs(a->rows[j].w.to - win[i].from) <= 1e-12 * fmax(1, win[i].from))
                prev = &a->rows[j];
        if (prev) {
            prev->w.to = win[i].to;
            prev->w.open_to = win[i].open_to;
            prev->w.freq_to = win[i].freq_to;
            prev->w.err_to = win[i].err_to;
            prev->sig_to = sig[2 * i + 1];
            if (win[i].max_growth > prev->w.max_growth)
                prev->w.max_growth = win[i].max_growth, prev->w.at = win[i].at;
            continue;
        }
        if (a->count == ATLAS_WINDOWS) return -1;
        atlas_row *r = &a->rows[a->count++];
        r->mode = mode;
        r->w = win[i];
        r->sig_from = sig[2 * i];
        r->sig_to = sig[2 * i + 1];
    }
    return 0;
}

static int compare_rows(const void *x, const void *y)
{
    const atlas_row *a = x, *b = y;
    if (a->mode != b->mode) return a->mode - b->mode;
    return (a->w.from > b->w.from) - (a->w.from < b->w.from);
}

/* The chunk j of the rates: [j, j + 1) ATLAS_CHUNK, the last ending at omega_max. */
static void chunk_range(double omega_max, size_t j, double *lo, double *hi)
{
    *lo = (double)j * ATLAS_CHUNK;
    *hi = fmin(omega_max, (double)(j + 1) * ATLAS_CHUNK);
}

/* The lines before the rows: the title, the parameter line (every option that changes a row:
 * a resume with other ones is refused), the "# done" lines of a's chunks finished (a NULL:
 * none), the columns. */
static void write_head(FILE *fp, const atlas_options *o, const atlas *a)
{
    const cli_int_list *modes = o->modes;
    fprintf(fp, "# whirl stability --atlas: continuous chain (Chebyshev collocation of degree "
                "%d on elements), modes", o->degree);
    for (int k = 0; k < modes->n; k++) fprintf(fp, "%s%d", k ? "," : " ", modes->v[k]);
    fprintf(fp, ", from each mode's birth to omega %s; dimensionless (rates sqrt(g/L))\n",
            CLI_NUM(o->omega_max));
    fprintf(fp, "# atlas: modes=");
    for (int k = 0; k < modes->n; k++) fprintf(fp, "%s%d", k ? "," : "", modes->v[k]);
    fprintf(fp, " omega_max=%s degree=%d tol=%s scan_step=%s\n", CLI_NUM(o->omega_max),
            o->degree, CLI_NUM(o->tol), CLI_NUM(o->scan_step));
    fprintf(fp, "# sig_from, sig_to: Krein signature of the slower mode of the colliding pair "
                "on the stable side of the edge; err: discretisation error estimate of the "
                "edge (a refined discretisation)\n");
    for (int k = 0; a && k < modes->n; k++)
        for (size_t j = 0; j < a->nchunks; j++)
            if (a->done[(size_t)k * a->nchunks + j]) {
                double lo, hi;
                chunk_range(o->omega_max, j, &lo, &hi);
                fprintf(fp, "# done mode %d omega %s %s\n", modes->v[k], CLI_NUM(lo),
                        CLI_NUM(hi));
            }
    fprintf(fp, "mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,"
                "max_growth,at,err_from,err_to\n");
}

/* The file rewritten with a's chunks and rows, the lock passed to it. */
static int write_atlas(const cli_command *cmd, cli_lock *lock, const char *path,
                       const atlas *a, const atlas_options *o)
{
    cli_out out;
    if (cli_out_open(cmd, &out, path)) return 1;
    write_head(out.fp, o, a);
    for (size_t i = 0; i < a->count; i++) {
        const atlas_row *r = &a->rows[i];
        fprintf(out.fp, "%d,%s,%s,%d,%d,%s,%s,%d,%d,%s,%s,%s,%s\n", r->mode, CLI_NUM(r->w.from),
                CLI_NUM(r->w.to), r->w.open_from, r->w.open_to, CLI_NUM(r->w.freq_from),
                CLI_NUM(r->w.freq_to), r->sig_from, r->sig_to, CLI_NUM(r->w.max_growth),
                CLI_NUM(r->w.at), CLI_NUM(r->w.err_from), CLI_NUM(r->w.err_to));
    }
    return cli_lock_commit(cmd, lock, &out);
}

/* The index of mode among the modes asked for, or -1. */
static int mode_index(const cli_int_list *modes, long mode)
{
    for (int k = 0; k < modes->n; k++)
        if (modes->v[k] == mode) return k;
    return -1;
}

/* A "# done mode K omega A B" line: the chunk it names marked done, A and B exactly those this
 * atlas writes for one of its chunks and K a mode asked for; else refused. */
static int read_done(cli_resume *in, const char *line, atlas *a, const atlas_options *o)
{
    char lo_text[64], hi_text[64], end[2];
    int mode, k = -1;
    if (sscanf(line, "# done mode %d omega %63s %63s%1s", &mode, lo_text, hi_text, end) != 3 ||
        (k = mode_index(o->modes, mode)) < 0)
        return cli_resume_refuse(in, "'%.*s' names no chunk of a mode asked for",
                                 (int)strcspn(line, "\n"), line);
    for (size_t j = 0; j < a->nchunks; j++) {
        double lo, hi;
        chunk_range(o->omega_max, j, &lo, &hi);
        if (strcmp(CLI_NUM(lo), lo_text) != 0 || strcmp(CLI_NUM(hi), hi_text) != 0) continue;
        int *done = &a->done[(size_t)k * a->nchunks + j];
        if (*done) return cli_resume_refuse(in, "chunk %s %s of mode %d listed twice", lo_text,
                                            hi_text, mode);
        *done = 1;
        return 0;
    }
    return cli_resume_refuse(in, "omega %s %s is no chunk of this atlas (they end at the "
                             "multiples of %g and at --omega-max)", lo_text, hi_text,
                             ATLAS_CHUNK);
}

/* The fields of a row (13, finite: cli_row_check passed) into r: the integers whole, the mode
 * one asked for, the flags 0 or 1, the signatures -1, 0 or 1, from <= to. 0, or the reason in
 * why. */
static int parse_row(const char *line, const atlas_options *o, atlas_row *r, char *why,
                     size_t size)
{
    int *const ints[5] = {&r->mode, &r->w.open_from, &r->w.open_to, &r->sig_from, &r->sig_to};
    double *const reals[8] = {&r->w.from, &r->w.to, &r->w.freq_from, &r->w.freq_to,
                              &r->w.max_growth, &r->w.at, &r->w.err_from, &r->w.err_to};
    /* the columns' kinds: i an integer, d a number */
    static const char kinds[] = "iddiiddiidddd";
    const char *p = line;
    for (int c = 0, ni = 0, nd = 0; kinds[c]; c++) {
        char *end;
        if (kinds[c] == 'i') {
            const long v = strtol(p, &end, 10);
            if (end == p || v < INT_MIN || v > INT_MAX)
                return snprintf(why, size, "column %d is not an integer", c + 1), -1;
            *ints[ni++] = (int)v;
        } else {
            *reals[nd++] = strtod(p, &end);
            if (end == p) return snprintf(why, size, "column %d is not a number", c + 1), -1;
        }
        if (*end != (kinds[c + 1] ? ',' : '\n'))
            return snprintf(why, size, "column %d is not a number", c + 1), -1;
        p = end + 1;
    }
    if (mode_index(o->modes, r->mode) < 0)
        return snprintf(why, size, "mode %d was not asked for (--modes)", r->mode), -1;
    if ((r->w.open_from | r->w.open_to) & ~1)
        return snprintf(why, size, "open_from and open_to must be 0 or 1"), -1;
    if (abs(r->sig_from) > 1 || abs(r->sig_to) > 1)
        return snprintf(why, size, "a signature must be -1, 0 or 1"), -1;
    if (!(r->w.from <= r->w.to))
        return snprintf(why, size, "from is beyond to"), -1;
    return 0;
}

/* The chunk of the mode of index k in which a window starting at from was found, if done. */
static int in_done_chunk(const atlas *a, const atlas_options *o, int k, double from)
{
    for (size_t j = 0; j < a->nchunks; j++) {
        double lo, hi;
        chunk_range(o->omega_max, j, &lo, &hi);
        if (a->done[(size_t)k * a->nchunks + j] && from >= lo && from <= hi) return 1;
    }
    return 0;
}

/* --resume: the chunks done and the rows of the file (in: read through the lock), every line
 * checked (resume.h); 0, or 1 after an error. */
static int read_atlas(const cli_command *cmd, FILE *in, const char *path, atlas *a,
                      const atlas_options *o)
{
    char *header = NULL;
    size_t header_len = 0;
    FILE *mem = open_memstream(&header, &header_len);
    if (mem == NULL) return cli_error(cmd, "out of memory");
    write_head(mem, o, NULL);
    if (fclose(mem) != 0) {
        free(header);
        return cli_error(cmd, "out of memory");
    }
    const cli_resume_params rp = {.header = header, .kind = "atlas", .of = "options",
                                  .note = "# done ", .line_max = ATLAS_LINE_MAX};
    cli_resume *r = cli_resume_alloc(cmd, in, path, &rp);
    int rc = r ? 0 : 1;
    const char *line;
    char why[160];
    for (cli_resume_kind kind; !rc && (kind = cli_resume_next(r, &line)) != CLI_RESUME_END;) {
        atlas_row row = {0};
        if (kind == CLI_RESUME_ERROR) rc = 1;
        else if (kind == CLI_RESUME_NOTE && strncmp(line, "# done ", 7) == 0 && !a->count)
            rc = read_done(r, line, a, o) ? 1 : 0;
        else if (kind == CLI_RESUME_NOTE)
            rc = cli_resume_refuse(r, "a comment among the rows") ? 1 : 0;
        else if (parse_row(line, o, &row, why, sizeof why))
            rc = cli_resume_refuse(r, "%s", why) ? 1 : 0;
        else if (!in_done_chunk(a, o, mode_index(o->modes, row.mode), row.w.from))
            rc = cli_resume_refuse(r, "a window of mode %d at omega %s, in no chunk done",
                                   row.mode, CLI_NUM(row.w.from)) ? 1 : 0;
        else if (a->count == ATLAS_WINDOWS)
            rc = cli_resume_refuse(r, "more than %d windows", ATLAS_WINDOWS) ? 1 : 0;
        else
            a->rows[a->count++] = row;
    }
    cli_resume_free(r);
    free(header);
    return rc;
}

/* One run of the atlas: its options, workspace and progress. */
typedef struct atlas_run {
    const cli_command *cmd;
    atlas_options o;
    const char *output;
    cli_lock lock; /* on the output, for the whole run */
    whirl_cstab *w;
    whirl_window *win; /* a chunk's windows */
    int *sig;          /* their edges' signatures */
    cli_progress_state progress;
    long finished;
} atlas_run;

/* The windows of mode in the chunk (lo, hi], with the Krein signatures of their closed edges
 * (r->win, r->sig; *n of them): 0, CLI_EXIT_INTERRUPTED, or 1 after an error. */
static int chunk_windows(atlas_run *r, int mode, double lo, double hi, size_t *n)
{
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = fmax(lo, 1e-3);
    p.omega_max = hi;
    p.tol = r->o.tol;
    p.scan_step = r->o.scan_step;
    whirl_windows_stats st;
    const whirl_window *win = r->win;
    int *sig = r->sig;
    int status = whirl_cstab_windows(r->w, mode, &p, r->win, ATLAS_CHUNK_WINDOWS, n, &st);
    for (size_t i = 0; i < *n && !status; i++) {
        sig[2 * i] = sig[2 * i + 1] = 0;
        if (!win[i].open_from && win[i].freq_from > 0)
            status = edge_signature(r->w, mode, win[i].from - ATLAS_SIDE, win[i].freq_from,
                                    &sig[2 * i]);
        if (!status && !win[i].open_to && win[i].freq_to > 0)
            status = edge_signature(r->w, mode, win[i].to + ATLAS_SIDE, win[i].freq_to,
                                    &sig[2 * i + 1]);
    }
    if (status == WHIRL_EINTERRUPTED) return CLI_EXIT_INTERRUPTED;
    if ((status = stability_memory_failure(status)))
        return cli_error(r->cmd, "mode %d, omega %s..%s: %s", mode, CLI_NUM(p.omega_min),
                         CLI_NUM(hi), whirl_last_error());
    return 0;
}

/* The chunks of mode k not done yet, the file rewritten after each: 0, CLI_EXIT_INTERRUPTED,
 * or 1 after an error. */
static int atlas_mode(atlas_run *r, atlas *a, int k)
{
    const int mode = r->o.modes->v[k];
    double birth;
    if (whirl_continuum_critical(mode, 0, &birth))
        return cli_error(r->cmd, "%s", whirl_last_error());
    for (size_t j = 0; j < a->nchunks; j++) {
        int *done = &a->done[(size_t)k * a->nchunks + j];
        if (*done) continue;
        double lo, hi;
        chunk_range(r->o.omega_max, j, &lo, &hi);
        if (hi <= birth * (1 + 1e-6)) { /* the mode does not exist yet */
            *done = 1;
            cli_progress_update(&r->progress, ++r->finished, 0);
            continue;
        }
        size_t n = 0;
        int rc = chunk_windows(r, mode, lo, hi, &n);
        if (rc) return rc;
        if (add_rows(a, mode, r->win, n, r->sig))
            return cli_error(r->cmd, "more than %d windows", ATLAS_WINDOWS);
        *done = 1;
        qsort(a->rows, a->count, sizeof *a->rows, compare_rows);
        rc = write_atlas(r->cmd, &r->lock, r->output, a, &r->o) ? 1 : 0;
        cli_progress_update(&r->progress, ++r->finished, 0);
        if (rc) return rc;
    }
    return 0;
}

int stability_memory_failure(int status)
{
    if (status == GSL_EMAXITER && strstr(whirl_last_error(), "raise the memory bound"))
        return whirl_fail(status, "%s (--memory MB)", whirl_error_marked());
    return status;
}

/* The atlas's arrays for o (NULL members after a failure). */
static void atlas_init(atlas *a, const atlas_options *o)
{
    *a = (atlas){0};
    a->nchunks = (size_t)ceil(o->omega_max / ATLAS_CHUNK - 1e-12);
    a->rows = calloc(ATLAS_WINDOWS, sizeof *a->rows);
    a->done = calloc((size_t)o->modes->n * a->nchunks, sizeof *a->done);
}

int stability_atlas_check(const cli_command *cmd, FILE *in, const char *path,
                          const cli_int_list *modes, double omega_max, int degree, double tol,
                          double scan_step)
{
    const atlas_options o = {modes, omega_max, tol, scan_step, degree};
    atlas a;
    atlas_init(&a, &o);
    const int rc = a.rows && a.done ? read_atlas(cmd, in, path, &a, &o)
                                    : cli_error(cmd, "out of memory");
    free(a.rows), free(a.done);
    return rc;
}

int stability_atlas(const cli_command *cmd, const cli_int_list *modes, double omega_max,
                    int degree, double memory_mb, double tol, double scan_step,
                    const char *output, int resume)
{
    if (!(omega_max > 0 && omega_max <= WHIRL_CONTINUUM_OMEGA_MAX))
        return cli_error(cmd, "--omega-max must be in (0, %g] for the atlas",
                         WHIRL_CONTINUUM_OMEGA_MAX);
    if (output == NULL || strcmp(output, "-") == 0)
        return cli_error(cmd, "--atlas needs -o FILE (it is rewritten after every chunk)");
    atlas_run r = {cmd, {modes, omega_max, tol, scan_step, degree}, output, {0}, NULL,
                   calloc(ATLAS_CHUNK_WINDOWS, sizeof *r.win),
                   calloc(2 * ATLAS_CHUNK_WINDOWS, sizeof *r.sig), {0}, 0};
    atlas a;
    atlas_init(&a, &r.o);
    whirl_cstab_params cp = whirl_cstab_defaults();
    cp.degree = degree;
    cp.memory_mb = memory_mb;
    r.w = whirl_cstab_alloc(&cp);
    int rc = 0;
    if (!a.rows || !a.done || !r.win || !r.sig || !r.w) rc = cli_error(cmd, "out of memory");
    /* the file locked from before it is read until the run ends: one run at a time writes it
     * (a new path is made empty by the run that starts it) */
    if (!rc) rc = cli_lock_take(cmd, &r.lock, output, !resume);
    if (!rc && resume && r.lock.fp == NULL)
        rc = cli_error(cmd, "--resume: cannot read '%s': no such regular file", output);
    if (!rc && resume) rc = read_atlas(cmd, r.lock.fp, output, &a, &r.o);
    long total = (long)modes->n * (long)a.nchunks, already = 0;
    for (long i = 0; i < total && !rc; i++) already += a.done[i];
    cli_progress_begin(&r.progress, cmd, "chunks", total, already);
    r.finished = already;
    cli_catch_interrupts();
    for (int k = 0; k < modes->n && !rc; k++) rc = atlas_mode(&r, &a, k);
    cli_progress_update(&r.progress, r.finished, 1);
    if (rc == CLI_EXIT_INTERRUPTED)
        cli_error(cmd, "interrupted: %ld of %ld chunks in '%s' (continue with --resume)",
                  r.finished, total, output);
    else if (!rc && write_atlas(cmd, &r.lock, output, &a, &r.o)) /* all chunks */
        rc = 1;
    cli_lock_release(&r.lock);
    whirl_cstab_free(r.w);
    free(a.rows), free(a.done), free(r.win), free(r.sig);
    return rc;
}
