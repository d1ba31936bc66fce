/* Taking an atlas's file back to resume it (include/whirl/atlas.h, whirl_atlas_read): the
 * header matched and every line checked by the reader of core/resume.h, then what only the atlas
 * knows: a "# done" line names a chunk of a mode asked for, once; a row is whole, of a mode asked
 * for, in a chunk done. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/resume.h"
#include "studies/atlas_internal.h"

/* The index of mode among the modes asked for, or -1. */
static int mode_index(const whirl_atlas_params *o, long mode)
{
    for (int k = 0; k < o->n_modes; k++)
        if (o->modes[k] == mode) return k;
    return -1;
}

/* A "# done mode K omega A B" line: the chunk it names marked done, A and B exactly those this
 * atlas writes for one of its chunks and K a mode asked for; else refused. */
static int read_done(whirl_resume *in, const char *line, whirl_atlas *a)
{
    char lo_text[64], hi_text[64], end[2];
    int mode, k = -1;
    /* dimensionless: the file's text */
    const char *format = "# done mode %d omega %63s %63s%1s";
    if (sscanf(line, format, &mode, lo_text, hi_text, end) != 3 ||
        (k = mode_index(&a->p, mode)) < 0)
        return whirl_resume_refuse(in, "'%.*s' names no chunk of a mode asked for",
                                   (int)strcspn(line, "\n"), line);
    for (size_t j = 0; j < a->nchunks; j++) {
        char lo[WHIRL_FORMAT_MAX], hi[WHIRL_FORMAT_MAX];
        atlas_chunk_text(a, j, lo, hi);
        if (strcmp(lo, lo_text) != 0 || strcmp(hi, hi_text) != 0) continue;
        int *done = &a->done[(size_t)k * a->nchunks + j];
        if (*done) return whirl_resume_refuse(in, "chunk %s %s of mode %d listed twice", lo_text,
                                              hi_text, mode);
        *done = 1;
        return 0;
    }
    char wmax[WHIRL_FORMAT_MAX];
    /* dimensionless: the file's text */
    return whirl_resume_refuse(in, "omega %s %s is no chunk of this atlas (they end at the "
                               "multiples of %d and at its omega_max, %s)", lo_text, hi_text,
                               WHIRL_ATLAS_CHUNK, whirl_format_double(wmax, a->p.omega_max));
}

/* The fields of a row (13, finite: whirl_resume_row_check passed) into r: the integers whole,
 * the mode one asked for, the flags 0 or 1, the signatures -1, 0 or 1, from <= to. 0, or the
 * reason in why. */
static int parse_row(const char *line, const whirl_atlas_params *o, whirl_atlas_row *r,
                     char *why, size_t size)
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
    if (mode_index(o, r->mode) < 0)
        return snprintf(why, size, "mode %d was not asked for", r->mode), -1;
    if ((r->w.open_from | r->w.open_to) & ~1)
        return snprintf(why, size, "open_from and open_to must be 0 or 1"), -1;
    if (abs(r->sig_from) > 1 || abs(r->sig_to) > 1)
        return snprintf(why, size, "a signature must be -1, 0 or 1"), -1;
    if (!(r->w.from <= r->w.to))
        return snprintf(why, size, "from is beyond to"), -1;
    return 0;
}

/* 1 if a window of the mode of index k starting at from lies in a chunk done. */
static int in_done_chunk(const whirl_atlas *a, int k, double from)
{
    for (size_t j = 0; j < a->nchunks; j++) {
        double lo, hi;
        whirl_atlas_chunk_range(a, j, &lo, &hi);
        if (a->done[(size_t)k * a->nchunks + j] && from >= lo && from <= hi) return 1;
    }
    return 0;
}

/* The rows and "# done" lines of in (the reader past its header) into a: 0, or
 * WHIRL_RESUME_ERROR with the message. */
static int read_lines(whirl_resume *in, whirl_atlas *a)
{
    const char *line;
    char why[160];
    for (whirl_resume_kind kind; (kind = whirl_resume_next(in, &line)) != WHIRL_RESUME_END;) {
        whirl_atlas_row row = {0};
        if (kind == WHIRL_RESUME_ERROR) return kind;
        if (kind == WHIRL_RESUME_NOTE && strncmp(line, "# done ", 7) == 0 && !a->count) {
            if (read_done(in, line, a)) return WHIRL_RESUME_ERROR;
        } else if (kind == WHIRL_RESUME_NOTE) {
            return whirl_resume_refuse(in, "a comment among the rows");
        } else if (parse_row(line, &a->p, &row, why, sizeof why)) {
            return whirl_resume_refuse(in, "%s", why);
        } else if (!in_done_chunk(a, mode_index(&a->p, row.mode), row.w.from)) {
            char from[WHIRL_FORMAT_MAX];
            /* dimensionless: the file's text */
            return whirl_resume_refuse(in, "a window of mode %d at omega %s, in no chunk done",
                                       row.mode, whirl_format_double(from, row.w.from));
        } else if (a->count == WHIRL_ATLAS_WINDOWS) {
            return whirl_resume_refuse(in, "more than %d windows", WHIRL_ATLAS_WINDOWS);
        } else {
            a->rows[a->count++] = row;
        }
    }
    return 0;
}

/* The atlas emptied: no chunk done, no window. */
static void clear(whirl_atlas *a)
{
    a->count = 0;
    memset(a->done, 0, (size_t)a->p.n_modes * a->nchunks * sizeof *a->done);
}

int whirl_atlas_read(whirl_atlas *a, FILE *in, const char *path)
{
    clear(a);
    size_t size = 0, len = 0;
    atlas_head(a, 0, NULL, 0, &size);
    char *header = malloc(size + 1);
    if (header == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    atlas_head(a, 0, header, size + 1, &len);
    const whirl_resume_params rp = {.header = header, .kind = "atlas", .of = "options",
                                    .note = "# done ", .line_max = WHIRL_ATLAS_LINE_MAX};
    whirl_resume *r = whirl_resume_alloc(in, path, &rp);
    int status = r ? GSL_SUCCESS : GSL_ENOMEM;
    if (r && read_lines(r, a)) status = whirl_last_status();
    whirl_resume_free(r);
    free(header);
    if (status) clear(a);
    return status;
}

int whirl_atlas_read_text(whirl_atlas *a, const char *data, size_t size, const char *path)
{
    if (size == 0) { /* (fmemopen of no bytes may fail) */
        clear(a);
        return whirl_fail(GSL_EINVAL, "'%s' holds no atlas of these options", path);
    }
    FILE *in = fmemopen((void *)data, size, "r");
    if (in == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    const int status = whirl_atlas_read(a, in, path);
    fclose(in);
    return status;
}
