/* The stability atlas of the continuous chain, chunk by chunk (include/whirl/atlas.h): the
 * windows of each chunk by whirl_cstab_windows, the Krein signature of the colliding pair at
 * each closed edge from the spectrum with signatures 1e-6 outside it, the windows that cross a
 * chunk's end joined (the file's text: atlas_text.c). */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "studies/atlas_internal.h"
#include "whirl/continuum_stability.h"
#include "whirl/steady.h"

#define ATLAS_CHUNK_WINDOWS 256 /* windows of one chunk at most */
#define ATLAS_SIDE 1e-6         /* the signatures are taken this far outside each edge */

whirl_atlas_params whirl_atlas_defaults(void)
{
    whirl_atlas_params p = {.n_modes = 7, .omega_max = 40, .degree = 16, .tol = 1e-9,
                            .scan_step = 0.25,
                            .memory_mb = whirl_cstab_defaults().memory_mb};
    for (int k = 0; k < p.n_modes; k++) p.modes[k] = k + 2;
    return p;
}

static int check_params(const whirl_atlas_params *p)
{
    if (p->n_modes < 1 || p->n_modes > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "the atlas needs 1..%d modes, got %d", WHIRL_MODE_MAX,
                          p->n_modes);
    for (int k = 0; k < p->n_modes; k++) {
        if (p->modes[k] < 1 || p->modes[k] > WHIRL_MODE_MAX)
            return whirl_fail(GSL_EINVAL, "a mode of the atlas must be in 1..%d, got %d",
                              WHIRL_MODE_MAX, p->modes[k]);
        for (int i = 0; i < k; i++)
            if (p->modes[i] == p->modes[k])
                return whirl_fail(GSL_EINVAL, "the atlas's modes repeat mode %d", p->modes[k]);
    }
    if (!(p->omega_max > 0 && p->omega_max <= WHIRL_CONTINUUM_OMEGA_MAX))
        return whirl_fail(GSL_EINVAL, "omega_max must be in (0, %g] for the atlas, got "
                          WHIRL_Q_RATE "%g", WHIRL_CONTINUUM_OMEGA_MAX, p->omega_max);
    if (!(p->tol >= 1e-13 && p->tol < p->scan_step))
        return whirl_fail(GSL_EINVAL, "the atlas needs 1e-13 <= tol < scan_step, got tol "
                          WHIRL_Q_RATE "%g, scan_step " WHIRL_Q_RATE "%g", p->tol,
                          p->scan_step);
    return GSL_SUCCESS;
}

whirl_atlas *whirl_atlas_alloc(const whirl_atlas_params *p)
{
    if (check_params(p)) return NULL;
    whirl_cstab_params cp = whirl_cstab_defaults();
    cp.degree = p->degree;
    cp.memory_mb = p->memory_mb;
    cp.progress = p->progress;
    cp.progress_ctx = p->progress_ctx;
    whirl_cstab *w = whirl_cstab_alloc(&cp);
    if (w == NULL) return NULL;
    whirl_atlas *a = calloc(1, sizeof *a);
    if (a == NULL) {
        whirl_cstab_free(w);
        whirl_fail(GSL_ENOMEM, "out of memory");
        return NULL;
    }
    a->p = *p;
    a->w = w;
    a->nchunks = (size_t)ceil(p->omega_max / WHIRL_ATLAS_CHUNK - 1e-12);
    a->rows = calloc(WHIRL_ATLAS_WINDOWS, sizeof *a->rows);
    a->done = calloc((size_t)p->n_modes * a->nchunks, sizeof *a->done);
    a->win = calloc(ATLAS_CHUNK_WINDOWS, sizeof *a->win);
    a->sig = calloc(2 * ATLAS_CHUNK_WINDOWS, sizeof *a->sig);
    if (!a->rows || !a->done || !a->win || !a->sig) {
        whirl_atlas_free(a);
        whirl_fail(GSL_ENOMEM, "out of memory");
        return NULL;
    }
    for (int k = 0; k < p->n_modes; k++) a->birth[k] = NAN;
    return a;
}

void whirl_atlas_free(whirl_atlas *a)
{
    if (a == NULL) return;
    whirl_cstab_free(a->w);
    free(a->rows), free(a->done), free(a->win), free(a->sig);
    free(a);
}

size_t whirl_atlas_chunks(const whirl_atlas *a)
{
    return a->nchunks;
}

void whirl_atlas_chunk_range(const whirl_atlas *a, size_t j, double *lo, double *hi)
{
    *lo = (double)j * WHIRL_ATLAS_CHUNK;
    *hi = fmin(a->p.omega_max, (double)(j + 1) * WHIRL_ATLAS_CHUNK);
}

int whirl_atlas_done(const whirl_atlas *a, size_t k, size_t j)
{
    return k < (size_t)a->p.n_modes && j < a->nchunks && a->done[k * a->nchunks + j];
}

size_t whirl_atlas_done_count(const whirl_atlas *a)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)a->p.n_modes * a->nchunks; i++) n += a->done[i] != 0;
    return n;
}

const whirl_atlas_row *whirl_atlas_rows(const whirl_atlas *a, size_t *count)
{
    *count = a->count;
    return a->rows;
}

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

/* The windows of mode in the chunk (lo, hi], with the Krein signatures of their closed edges
 * (a->win, a->sig; *n of them). */
static int chunk_windows(whirl_atlas *a, int mode, double lo, double hi, size_t *n)
{
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = fmax(lo, 1e-3);
    p.omega_max = hi;
    p.tol = a->p.tol;
    p.scan_step = a->p.scan_step;
    whirl_windows_stats st;
    const whirl_window *win = a->win;
    int *sig = a->sig;
    int status = whirl_cstab_windows(a->w, mode, &p, a->win, ATLAS_CHUNK_WINDOWS, n, &st);
    for (size_t i = 0; i < *n && !status; i++) {
        sig[2 * i] = sig[2 * i + 1] = 0;
        if (!win[i].open_from && win[i].freq_from > 0)
            status = edge_signature(a->w, mode, win[i].from - ATLAS_SIDE, win[i].freq_from,
                                    &sig[2 * i]);
        if (!status && !win[i].open_to && win[i].freq_to > 0)
            status = edge_signature(a->w, mode, win[i].to + ATLAS_SIDE, win[i].freq_to,
                                    &sig[2 * i + 1]);
    }
    if (status == WHIRL_EINTERRUPTED) return status;
    if (status) {
        char from[WHIRL_FORMAT_MAX], to[WHIRL_FORMAT_MAX];
        return whirl_fail(status, "mode %d, omega " WHIRL_Q_RATE "%s.." WHIRL_Q_RATE "%s: %s",
                          mode, whirl_format_double(from, p.omega_min),
                          whirl_format_double(to, hi), whirl_error_marked());
    }
    return GSL_SUCCESS;
}

/* Adds the windows of one chunk of mode, joining one that continues a window open at the
 * chunk's start: 0, or -1 beyond WHIRL_ATLAS_WINDOWS windows. */
static int add_rows(whirl_atlas *a, int mode, const whirl_window *win, size_t n, const int *sig)
{
    for (size_t i = 0; i < n; i++) {
        whirl_atlas_row *prev = NULL;
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
        if (a->count == WHIRL_ATLAS_WINDOWS) return -1;
        whirl_atlas_row *r = &a->rows[a->count++];
        r->mode = mode;
        r->w = win[i];
        r->sig_from = sig[2 * i];
        r->sig_to = sig[2 * i + 1];
    }
    return 0;
}

static int compare_rows(const void *x, const void *y)
{
    const whirl_atlas_row *a = x, *b = y;
    if (a->mode != b->mode) return a->mode - b->mode;
    return (a->w.from > b->w.from) - (a->w.from < b->w.from);
}

/* Adds the chunk's windows (a->win, a->sig; n) as add_rows, the rows left as they were when they
 * do not fit. */
static int add_chunk(whirl_atlas *a, int mode, size_t n)
{
    whirl_atlas_row *keep = NULL;
    const size_t count = a->count;
    if (count + n > WHIRL_ATLAS_WINDOWS) { /* (joins may still make them fit) */
        keep = malloc(count * sizeof *keep + 1);
        if (keep == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        memcpy(keep, a->rows, count * sizeof *keep);
    }
    if (add_rows(a, mode, a->win, n, a->sig)) {
        memcpy(a->rows, keep, count * sizeof *keep);
        a->count = count;
        free(keep);
        return whirl_fail(GSL_EFAILED, "more than %d windows", WHIRL_ATLAS_WINDOWS);
    }
    free(keep);
    qsort(a->rows, a->count, sizeof *a->rows, compare_rows);
    return GSL_SUCCESS;
}

int whirl_atlas_compute(whirl_atlas *a, size_t k, size_t j, int *computed)
{
    if (computed) *computed = 0;
    if (k >= (size_t)a->p.n_modes || j >= a->nchunks)
        return whirl_fail(GSL_EINVAL, "the atlas has no chunk %zu of mode index %zu", j, k);
    int *done = &a->done[k * a->nchunks + j];
    const int mode = a->p.modes[k];
    double lo, hi;
    whirl_atlas_chunk_range(a, j, &lo, &hi);
    if (*done)
        return whirl_fail(GSL_EINVAL, "chunk %zu of mode %d is done already", j, mode);
    if (whirl_stop_requested())
        return whirl_fail(WHIRL_EINTERRUPTED, "atlas interrupted before mode %d, omega "
                          WHIRL_Q_RATE "%g", mode, lo);
    if (isnan(a->birth[k])) {
        const int status = whirl_continuum_critical(mode, 0, &a->birth[k]);
        if (status) {
            a->birth[k] = NAN;
            return status;
        }
    }
    if (hi <= a->birth[k] * (1 + 1e-6)) { /* the mode does not exist yet */
        *done = 1;
        return GSL_SUCCESS;
    }
    size_t n = 0;
    int status = chunk_windows(a, mode, lo, hi, &n);
    if (!status) status = add_chunk(a, mode, n);
    if (status) return status;
    *done = 1;
    if (computed) *computed = 1;
    return GSL_SUCCESS;
}

