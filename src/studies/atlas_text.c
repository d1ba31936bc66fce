/* The stability atlas's file as text (include/whirl/atlas.h): the title, the options' line, the
 * '# done' lines, the column names and one line per window, numbers in their shortest exact form
 * (whirl_format_double). Output text, not messages: the rates here are the file's dimensionless
 * numbers (tests/tools/message_quantities.py leaves this file out). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "studies/atlas_internal.h"

void atlas_put(char *buf, size_t size, size_t *len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(*len < size ? buf + *len : NULL, *len < size ? size - *len : 0, fmt,
                            ap);
    va_end(ap);
    if (n > 0) *len += (size_t)n;
}

size_t whirl_atlas_row_text(const whirl_atlas_row *r, char *buf, size_t size)
{
    char t[8][WHIRL_FORMAT_MAX];
    const double x[8] = {r->w.from, r->w.to, r->w.freq_from, r->w.freq_to, r->w.max_growth,
                         r->w.at, r->w.err_from, r->w.err_to};
    for (int i = 0; i < 8; i++) whirl_format_double(t[i], x[i]);
    size_t len = 0;
    if (size) buf[0] = '\0';
    atlas_put(buf, size, &len, "%d,%s,%s,%d,%d,%s,%s,%d,%d,%s,%s,%s,%s\n", r->mode, t[0], t[1],
              r->w.open_from, r->w.open_to, t[2], t[3], r->sig_from, r->sig_to, t[4], t[5],
              t[6], t[7]);
    return len;
}

void atlas_head(const whirl_atlas *a, int done, char *buf, size_t size, size_t *len)
{
    const whirl_atlas_params *o = &a->p;
    char wmax[WHIRL_FORMAT_MAX], tol[WHIRL_FORMAT_MAX], step[WHIRL_FORMAT_MAX];
    whirl_format_double(wmax, o->omega_max);
    whirl_format_double(tol, o->tol);
    whirl_format_double(step, o->scan_step);
    atlas_put(buf, size, len, "# whirl stability --atlas: continuous chain (Chebyshev "
              "collocation of degree %d on elements), modes", o->degree);
    for (int k = 0; k < o->n_modes; k++) atlas_put(buf, size, len, "%s%d", k ? "," : " ",
                                                   o->modes[k]);
    atlas_put(buf, size, len, ", from each mode's birth to omega %s; dimensionless (rates "
              "sqrt(g/L))\n# atlas: modes=", wmax);
    for (int k = 0; k < o->n_modes; k++) atlas_put(buf, size, len, "%s%d", k ? "," : "",
                                                   o->modes[k]);
    atlas_put(buf, size, len, " omega_max=%s degree=%d tol=%s scan_step=%s\n", wmax, o->degree,
              tol, step);
    atlas_put(buf, size, len, "# sig_from, sig_to: Krein signature of the slower mode of the "
              "colliding pair on the stable side of the edge; err: discretisation error "
              "estimate of the edge (a refined discretisation)\n");
    for (size_t k = 0; done && k < (size_t)o->n_modes; k++)
        for (size_t j = 0; j < a->nchunks; j++)
            if (a->done[k * a->nchunks + j]) {
                char lo[WHIRL_FORMAT_MAX], hi[WHIRL_FORMAT_MAX];
                atlas_chunk_text(a, j, lo, hi);
                atlas_put(buf, size, len, "# done mode %d omega %s %s\n", o->modes[k], lo, hi);
            }
    atlas_put(buf, size, len, "mode,from,to,open_from,open_to,freq_from,freq_to,sig_from,"
              "sig_to,max_growth,at,err_from,err_to\n");
}

void atlas_chunk_text(const whirl_atlas *a, size_t j, char *lo, char *hi)
{
    double x, y;
    whirl_atlas_chunk_range(a, j, &x, &y);
    whirl_format_double(lo, x);
    whirl_format_double(hi, y);
}

size_t whirl_atlas_text(const whirl_atlas *a, char *buf, size_t size)
{
    size_t len = 0;
    if (size) buf[0] = '\0';
    atlas_head(a, 1, buf, size, &len);
    for (size_t i = 0; i < a->count; i++)
        len += whirl_atlas_row_text(&a->rows[i], len < size ? buf + len : NULL,
                                    len < size ? size - len : 0);
    return len;
}
