/* Internal: the atlas (include/whirl/atlas.h), shared by its computation (atlas.c) and its
 * reader (atlas_read.c). */
#ifndef WHIRL_ATLAS_INTERNAL_H
#define WHIRL_ATLAS_INTERNAL_H

#include <stddef.h>

#include "whirl/atlas.h"
#include "whirl/continuum_stability.h"

struct whirl_atlas {
    whirl_atlas_params p;
    whirl_cstab *w;             /* the collocation's workspace, for every chunk */
    size_t nchunks;             /* chunks per mode (from rate 0 to omega_max) */
    int *done;                  /* per mode and chunk (k nchunks + j): 1 once finished */
    whirl_atlas_row *rows;      /* WHIRL_ATLAS_WINDOWS of them */
    size_t count;
    double birth[WHIRL_MODE_MAX]; /* each mode's birth rate omega_k (NaN until needed) */
    whirl_window *win;          /* a chunk's windows */
    int *sig;                   /* their edges' signatures (two per window) */
};

/* Appends to the text being written into buf (size bytes) at *len, as snprintf would: *len
 * counts every character, those beyond size - 1 dropped. */
void atlas_put(char *buf, size_t size, size_t *len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* The lines before the rows, appended as atlas_put: the title, the options' line (every option
 * that changes a row), the signatures' note, the "# done" lines of the chunks done if done, the
 * columns. */
void atlas_head(const whirl_atlas *a, int done, char *buf, size_t size, size_t *len);

/* The ends of chunk j as the file writes them (WHIRL_FORMAT_MAX characters each). */
void atlas_chunk_text(const whirl_atlas *a, size_t j, char *lo, char *hi);

#endif
