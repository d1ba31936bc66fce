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
 * finished; --resume reads them back and computes the rest. A terminal shows the chunks done. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/stability_atlas.h"
#include "core/error.h"
#include "whirl/continuum_stability.h"
#include "whirl/steady.h"

#define ATLAS_CHUNK 5.0   /* chunk ends at the multiples of this rate [sqrt(g/L)] */
#define ATLAS_WINDOWS 4096 /* windows of all modes at most */
#define ATLAS_CHUNK_WINDOWS 256
#define ATLAS_SIDE 1e-6   /* the signatures are taken this far outside each edge */

typedef struct atlas_row {
    int mode;
    whirl_window w;
    int sig_from, sig_to;
} atlas_row;

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

static int write_atlas(const cli_command *cmd, const char *path, const atlas *a,
                       const cli_int_list *modes, double omega_max, int degree)
{
    cli_out out;
    if (cli_out_open(cmd, &out, path)) return 1;
    fprintf(out.fp, "# whirl stability --atlas: continuous chain (Chebyshev collocation of degree "
                    "%d on elements), modes", degree);
    for (int k = 0; k < modes->n; k++) fprintf(out.fp, "%s%d", k ? "," : " ", modes->v[k]);
    fprintf(out.fp, ", from each mode's birth to omega %s; dimensionless (rates sqrt(g/L))\n",
            CLI_NUM(omega_max));
    fprintf(out.fp, "# sig_from, sig_to: Krein signature of the slower mode of the colliding pair "
                    "on the stable side of the edge; err: discretisation error estimate of the "
                    "edge (a refined discretisation)\n");
    for (int k = 0; k < modes->n; k++)
        for (size_t j = 0; j < a->nchunks; j++)
            if (a->done[(size_t)k * a->nchunks + j]) {
                double lo, hi;
                chunk_range(omega_max, j, &lo, &hi);
                fprintf(out.fp, "# done mode %d omega %s %s\n", modes->v[k], CLI_NUM(lo),
                        CLI_NUM(hi));
            }
    fprintf(out.fp, "mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,"
                    "max_growth,at,err_from,err_to\n");
    for (size_t i = 0; i < a->count; i++) {
        const atlas_row *r = &a->rows[i];
        fprintf(out.fp, "%d,%s,%s,%d,%d,%s,%s,%d,%d,%s,%s,%s,%s\n", r->mode, CLI_NUM(r->w.from),
                CLI_NUM(r->w.to), r->w.open_from, r->w.open_to, CLI_NUM(r->w.freq_from),
                CLI_NUM(r->w.freq_to), r->sig_from, r->sig_to, CLI_NUM(r->w.max_growth),
                CLI_NUM(r->w.at), CLI_NUM(r->w.err_from), CLI_NUM(r->w.err_to));
    }
    return cli_out_commit(cmd, &out);
}

/* --resume: the chunks done and the rows of path. */
static int read_atlas(const cli_command *cmd, const char *path, atlas *a,
                      const cli_int_list *modes)
{
    FILE *in = fopen(path, "r");
    if (in == NULL) return cli_error(cmd, "--resume: cannot read '%s'", path);
    char line[1024];
    int rc = 0;
    while (!rc && fgets(line, sizeof line, in)) {
        int mode;
        double lo, hi;
        atlas_row r = {0};
        if (sscanf(line, "# done mode %d omega %lf %lf", &mode, &lo, &hi) == 3) {
            for (int k = 0; k < modes->n; k++)
                if (modes->v[k] == mode && lo >= 0 && lo / ATLAS_CHUNK < (double)a->nchunks)
                    a->done[(size_t)k * a->nchunks + (size_t)(lo / ATLAS_CHUNK + 0.5)] = 1;
        } else if (line[0] != '#' && line[0] != 'm' &&
                   sscanf(line, "%d,%lf,%lf,%d,%d,%lf,%lf,%d,%d,%lf,%lf,%lf,%lf", &r.mode,
                          &r.w.from, &r.w.to, &r.w.open_from, &r.w.open_to, &r.w.freq_from,
                          &r.w.freq_to, &r.sig_from, &r.sig_to, &r.w.max_growth, &r.w.at,
                          &r.w.err_from, &r.w.err_to) == 13) {
            if (a->count == ATLAS_WINDOWS) rc = cli_error(cmd, "--resume: too many windows");
            else a->rows[a->count++] = r;
        } else if (line[0] != '#' && strncmp(line, "mode,", 5) != 0) {
            rc = cli_error(cmd, "--resume: '%s' is not an atlas (line '%.*s')", path,
                           (int)strcspn(line, "\n"), line);
        }
    }
    fclose(in);
    return rc;
}

/* One run of the atlas: its options, workspace and progress. */
typedef struct atlas_run {
    const cli_command *cmd;
    const cli_int_list *modes;
    double omega_max, tol, scan_step;
    int degree;
    const char *output;
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
    p.tol = r->tol;
    p.scan_step = r->scan_step;
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
    const int mode = r->modes->v[k];
    double birth;
    if (whirl_continuum_critical(mode, 0, &birth))
        return cli_error(r->cmd, "%s", whirl_last_error());
    for (size_t j = 0; j < a->nchunks; j++) {
        int *done = &a->done[(size_t)k * a->nchunks + j];
        if (*done) continue;
        double lo, hi;
        chunk_range(r->omega_max, j, &lo, &hi);
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
        rc = write_atlas(r->cmd, r->output, a, r->modes, r->omega_max, r->degree) ? 1 : 0;
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

int stability_atlas(const cli_command *cmd, const cli_int_list *modes, double omega_max,
                    int degree, double memory_mb, double tol, double scan_step,
                    const char *output, int resume)
{
    if (!(omega_max > 0 && omega_max <= WHIRL_CONTINUUM_OMEGA_MAX))
        return cli_error(cmd, "--omega-max must be in (0, %g] for the atlas",
                         WHIRL_CONTINUUM_OMEGA_MAX);
    if (output == NULL || strcmp(output, "-") == 0)
        return cli_error(cmd, "--atlas needs -o FILE (it is rewritten after every chunk)");
    atlas a = {0};
    a.nchunks = (size_t)ceil(omega_max / ATLAS_CHUNK - 1e-12);
    a.rows = calloc(ATLAS_WINDOWS, sizeof *a.rows);
    a.done = calloc((size_t)modes->n * a.nchunks, sizeof *a.done);
    atlas_run r = {cmd, modes, omega_max, tol, scan_step, degree, output, NULL,
                   calloc(ATLAS_CHUNK_WINDOWS, sizeof *r.win),
                   calloc(2 * ATLAS_CHUNK_WINDOWS, sizeof *r.sig), {0}, 0};
    whirl_cstab_params cp = whirl_cstab_defaults();
    cp.degree = degree;
    cp.memory_mb = memory_mb;
    r.w = whirl_cstab_alloc(&cp);
    int rc = 0;
    if (!a.rows || !a.done || !r.win || !r.sig || !r.w) rc = cli_error(cmd, "out of memory");
    if (!rc && resume) rc = read_atlas(cmd, output, &a, modes);
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
    else if (!rc && write_atlas(cmd, output, &a, modes, omega_max, degree)) /* all chunks */
        rc = 1;
    whirl_cstab_free(r.w);
    free(a.rows), free(a.done), free(r.win), free(r.sig);
    return rc;
}
