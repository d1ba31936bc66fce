/* whirl: the stability atlas of the continuous chain: every window of instability of its modes
 * from each mode's birth omega_k to a rate omega_max (whirl_cstab_windows), with the Krein
 * signatures of the colliding pair at each edge. The rates of each mode are cut into chunks at
 * the multiples of WHIRL_ATLAS_CHUNK, computed one at a time (whirl_atlas_compute), so that a
 * long atlas is kept after every chunk in a file (whirl_atlas_text, one row per window):
 *   mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,sig_to,max_growth,at,err_from,err_to
 * under a header that records every option that changes a row and a line "# done mode K omega A
 * B" per chunk finished; whirl_atlas_read takes such a file back (every line checked) and the
 * rest is computed. Dimensionless (rates in sqrt(g/L)). (src/studies/atlas.c, atlas_read.c) */
#ifndef WHIRL_ATLAS_H
#define WHIRL_ATLAS_H

#include <stddef.h>
#include <stdio.h>

#include "whirl/common.h"
#include "whirl/stability.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WHIRL_ATLAS_CHUNK 5         /* the chunks end at the multiples of this rate [sqrt(g/L)] */
#define WHIRL_ATLAS_WINDOWS 4096    /* windows of all modes at most */
#define WHIRL_ATLAS_LINE_MAX 1024   /* characters of a line of the file read back at most */

typedef struct whirl_atlas_params {
    int modes[WHIRL_MODE_MAX]; /* the modes, distinct, each 1..WHIRL_MODE_MAX, in the order of
                                  the file; 2, 3, ..., 8 */
    int n_modes;               /* how many of modes[]; 7; 1..WHIRL_MODE_MAX */
    double omega_max;          /* the atlas's end [sqrt(g/L)]; 40; in
                                  (0, WHIRL_CONTINUUM_OMEGA_MAX] */
    int degree;                /* Chebyshev degree of the collocation (whirl_cstab_params);
                                  16; 6..64 */
    double tol;                /* edges located to this [sqrt(g/L)] (whirl_windows_params);
                                  1e-9; >= 1e-13 and below scan_step */
    double scan_step;          /* spacing of the scan [sqrt(g/L)]; 0.25 */
    double memory_mb;          /* the collocation's memory bound (whirl_cstab_params); 1024 */
    void (*progress)(void *ctx, int mode, double omega); /* called inside a chunk before each
                                  rate the search linearises at (whirl_cstab_params.progress);
                                  NULL: none (default) */
    void *progress_ctx;
} whirl_atlas_params;

/* The defaults above.
 * @return the defaults
 */
WHIRL_API whirl_atlas_params whirl_atlas_defaults(void);

/* A window of the atlas: the mode, the window (whirl_window, with the edges' error estimates)
 * and the Krein signature (sign of the mode's energy, -1 or +1) of the slower of the two neutral
 * modes that collide at each edge, on the stable side (1e-6 outside it; the faster one has the
 * opposite sign); 0 at an open end or where no pair of opposite signs is found. */
typedef struct whirl_atlas_row {
    int mode;
    whirl_window w;
    int sig_from, sig_to;
} whirl_atlas_row;

typedef struct whirl_atlas whirl_atlas; /* the atlas: its options, chunks done and windows */

/* An atlas of the parameters p (copied), no chunk done. NULL (whirl_last_error, GSL_EINVAL on
 * bad parameters, GSL_ENOMEM) on failure.
 * @param p the parameters (copied)
 * @return the atlas, to free with whirl_atlas_free; NULL with a message on bad parameters or no
 *     memory
 */
WHIRL_API whirl_atlas *whirl_atlas_alloc(const whirl_atlas_params *p);
/* Frees the atlas; NULL is a no-op.
 * @param a the atlas, or NULL
 */
WHIRL_API void whirl_atlas_free(whirl_atlas *a);

/* The chunks of each mode: ceil(omega_max / WHIRL_ATLAS_CHUNK). Chunk j covers the rates
 * [lo, hi] = [j, j + 1] WHIRL_ATLAS_CHUNK, the last ending at omega_max.
 * @param a the atlas
 * @return the chunks of each mode
 */
WHIRL_API size_t whirl_atlas_chunks(const whirl_atlas *a);
/* The rates of chunk j: [j, j + 1] WHIRL_ATLAS_CHUNK, the upper end at most omega_max.
 * @param a the atlas
 * @param j the chunk, 0..whirl_atlas_chunks(a) - 1
 * @param lo out: the chunk's first rate [sqrt(g/L)]
 * @param hi out: the chunk's last rate [sqrt(g/L)]
 */
WHIRL_API void whirl_atlas_chunk_range(const whirl_atlas *a, size_t j, double *lo, double *hi);
/* 1 once chunk j of the mode of index k (of params.modes) is done, else 0.
 * @param a the atlas
 * @param k the index of the mode in params.modes, 0..n_modes - 1
 * @param j the chunk, 0..whirl_atlas_chunks(a) - 1
 * @return 1 if that chunk is done, 0 if not or if k or j is out of range
 */
WHIRL_API int whirl_atlas_done(const whirl_atlas *a, size_t k, size_t j);
/* The chunks done, of all modes.
 * @param a the atlas
 * @return the chunks done, 0..n_modes whirl_atlas_chunks(a)
 */
WHIRL_API size_t whirl_atlas_done_count(const whirl_atlas *a);

/* Computes chunk j of the mode of index k: its windows (whirl_cstab_windows from
 * max(lo, 1e-3) to hi) with the signatures of their closed edges join the atlas's (a window
 * that continues one open at the chunk's start is joined to it), which stay in increasing mode
 * and from; the chunk is marked done. A chunk that ends below the
 * mode's birth (times 1 + 1e-6) is marked done with nothing computed. *computed (may be NULL):
 * 1 if windows were searched for, 0 if not. Returns GSL_SUCCESS; GSL_EINVAL for a chunk out of
 * range or done already; WHIRL_EINTERRUPTED on a stop request (before the chunk, or inside it
 * between eigen-solves); the failure of the search (its message after "mode K, omega A..B: "),
 * or GSL_EFAILED beyond WHIRL_ATLAS_WINDOWS windows: then the atlas is as it was.
 * @param a the atlas
 * @param k the index of the mode in params.modes, 0..n_modes - 1
 * @param j the chunk, 0..whirl_atlas_chunks(a) - 1, not done yet
 * @param computed out, or NULL: 1 if windows were searched for, 0 if not
 * @return GSL_SUCCESS, GSL_EINVAL for a chunk out of range or done, WHIRL_EINTERRUPTED, the
 *     search's failure or GSL_EFAILED, each with a message and the atlas as it was
 */
WHIRL_API int whirl_atlas_compute(whirl_atlas *a, size_t k, size_t j, int *computed);

/* The windows so far, *count of them, in increasing mode and from (valid until the atlas's next
 * use).
 * @param a the atlas
 * @param count out: the windows
 * @return the windows, owned by the atlas
 */
WHIRL_API const whirl_atlas_row *whirl_atlas_rows(const whirl_atlas *a, size_t *count);

/* The row r as a line of the file, newline included, into buf (size bytes, NUL-terminated when
 * size > 0; numbers by whirl_format_double). Returns the line's length (as snprintf: a length
 * >= size says it was cut).
 * @param r the row
 * @param buf out: the line, or NULL with size 0
 * @param size the bytes of buf
 * @return the line's length in chars, without the NUL
 */
WHIRL_API size_t whirl_atlas_row_text(const whirl_atlas_row *r, char *buf, size_t size);
/* The whole file of the atlas as it stands: the title, the options' line, the signatures'
 * note, one "# done mode K omega A B" line per chunk done, the columns, the rows; into buf as
 * whirl_atlas_row_text (call it with size 0 for the length).
 * @param a the atlas
 * @param buf out: the file's text, or NULL with size 0
 * @param size the bytes of buf
 * @return the text's length in chars, without the NUL
 */
WHIRL_API size_t whirl_atlas_text(const whirl_atlas *a, char *buf, size_t size);

/* Takes back the file path (its stream in, read to its end, not closed) as resuming would: it
 * must begin with the lines an atlas of these parameters writes before its "# done" lines and
 * columns, else it is refused naming the first difference ("'PATH' was not written by an atlas
 * with these options: line N has 'X' where these options write 'Y'"); its "# done" lines must
 * name chunks of these modes, each once, before the rows; every row must be whole and finite,
 * of a mode asked for, its flags 0 or 1, its signatures -1, 0 or 1, from <= to, in a chunk done
 * ("PATH:N: WHY: the file cannot be trusted (...)"); an unfinished last line is dropped. Returns
 * GSL_SUCCESS with the chunks and rows taken (those a had before replaced), or GSL_EINVAL
 * (GSL_EFAILED on a read error) with a's chunks and rows emptied.
 * @param a the atlas, with the parameters the file must have been written with
 * @param in the stream of the file, read to its end and not closed
 * @param path the file's name, for the messages
 * @return GSL_SUCCESS, GSL_EINVAL for a file that does not match or cannot be trusted, GSL_EFAILED
 *     on a read error, GSL_ENOMEM; each with a message and a's chunks and rows emptied
 */
WHIRL_API int whirl_atlas_read(whirl_atlas *a, FILE *in, const char *path);
/* whirl_atlas_read of the file's bytes data[0..size).
 * @param a the atlas, with the parameters the file must have been written with
 * @param data the file's bytes, size (not NUL-terminated)
 * @param size the bytes of data (0: GSL_EINVAL, no atlas)
 * @param path the file's name, for the messages
 * @return as whirl_atlas_read
 */
WHIRL_API int whirl_atlas_read_text(whirl_atlas *a, const char *data, size_t size,
                                    const char *path);

/* ---- the atlas's file, written by one run at a time (src/studies/atlas_file.c) ----
 * The command line and the Python package write an atlas (and the command line its other maps)
 * through this: the file locked (flock) for the whole run, from before it is read until the
 * last row, and rewritten atomically (a file beside it, renamed over it, locked before the
 * rename so that the lock passes to the new file). */
typedef struct whirl_atlas_file whirl_atlas_file;

/* Locks the regular file path, or with make (a run that starts afresh) one that does not yet
 * exist, made empty (O_EXCL: of two runs started together on a new path one makes it).
 * @param path the file
 * @param make 1: make it when it does not exist; 0: it must exist
 * @return the locked file, to free with whirl_atlas_file_free; NULL with a message on failure:
 *     GSL_EFAILED "'PATH' is being written by another run (locked): wait for it or write
 *     another file" (or replaced by another run while this one started), GSL_EINVAL when path
 *     is not a regular file or (without make) does not exist, GSL_EFAILED when it cannot be
 *     opened or locked, GSL_ENOMEM
 */
WHIRL_API whirl_atlas_file *whirl_atlas_file_alloc(const char *path, int make);

/* The descriptor of the locked file, open for reading (read it from its start with pread or
 * lseek; do not close it). Valid until the next replace or the free.
 * @param f the file
 * @return the descriptor
 */
WHIRL_API int whirl_atlas_file_fd(const whirl_atlas_file *f);

/* 1 if this run made the file (empty) and has not replaced it yet.
 * @param f the file
 * @return 1 or 0
 */
WHIRL_API int whirl_atlas_file_made(const whirl_atlas_file *f);

/* Puts the new contents in place: the file tmp, written whole and open as fd (a descriptor the
 * caller keeps and closes), is locked, then renamed over the path (over a symlink's target),
 * and the old file's lock released.
 * @param f the file
 * @param fd a descriptor of tmp
 * @param tmp the new contents' file, beside the target
 * @return GSL_SUCCESS, or GSL_EFAILED with a message (tmp is left for the caller to remove)
 */
WHIRL_API int whirl_atlas_file_replace(whirl_atlas_file *f, int fd, const char *tmp);

/* Rewrites the file with the n bytes of data: a temporary file beside it (its mode kept),
 * written, synced, then put in place with whirl_atlas_file_replace.
 * @param f the file
 * @param data the new contents
 * @param n their length in bytes
 * @return GSL_SUCCESS, or GSL_EFAILED with a message (the file as it was)
 */
WHIRL_API int whirl_atlas_file_commit(whirl_atlas_file *f, const char *data, size_t n);

/* Releases the lock; the empty file the run made is removed if the path still names it. NULL is
 * a no-op.
 * @param f the file, or NULL
 */
WHIRL_API void whirl_atlas_file_free(whirl_atlas_file *f);

#ifdef __cplusplus
}
#endif

#endif
