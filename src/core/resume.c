/* Reading back a file being resumed: the header matched, the rows checked, one line at a time
 * (resume.h). */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/resume.h"

#define RESUME_WORD_MAX 60 /* characters of a word shown in a message (a long one is cut) */

struct whirl_resume {
    FILE *in;
    const char *path;
    whirl_resume_params p;
    const char *want;  /* the header line expected next (NULL: the header is matched) */
    size_t fields;     /* columns of a row: those of the header's last line */
    char *line;        /* the line read, line_max + 2 characters and a NUL */
    long lineno;
};

whirl_resume *whirl_resume_alloc(FILE *in, const char *path, const whirl_resume_params *params)
{
    whirl_resume *r = calloc(1, sizeof *r);
    if (r) r->line = malloc(params->line_max + 3);
    if (r == NULL || r->line == NULL) {
        free(r);
        whirl_fail(GSL_ENOMEM, "out of memory");
        return NULL;
    }
    r->in = in;
    r->path = path;
    r->p = *params;
    r->want = params->header[0] ? params->header : NULL;
    /* the columns: the header's last line */
    const size_t len = strlen(params->header);
    const char *c = params->header + len - (len > 0);
    r->fields = 1;
    while (c > params->header && c[-1] != '\n') r->fields += *--c == ',';
    return r;
}

void whirl_resume_free(whirl_resume *r)
{
    if (r == NULL) return;
    free(r->line);
    free(r);
}

long whirl_resume_lineno(const whirl_resume *r)
{
    return r->lineno;
}

/* The article of a noun in messages. */
static const char *article(const char *noun)
{
    return strchr("aeiou", noun[0]) ? "an" : "a";
}

int whirl_resume_refuse(whirl_resume *r, const char *fmt, ...)
{
    char why[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    whirl_fail(GSL_EINVAL, "%s:%ld: %s: the file cannot be trusted (remove the row, or start "
               "the %s afresh)", r->path, r->lineno, why, r->p.kind);
    return WHIRL_RESUME_ERROR;
}

int whirl_resume_refuse_at(whirl_resume *r, long lineno, const char *fmt, ...)
{
    char why[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    r->lineno = lineno;
    return whirl_resume_refuse(r, "%s", why);
}

/* Word i of s (words apart by spaces and newlines) into w; 0 if s has fewer. */
static int word(const char *s, size_t i, char *w, size_t size)
{
    for (size_t k = 0;; k++) {
        s += strspn(s, " \n");
        const size_t len = strcspn(s, " \n");
        if (len == 0) return 0;
        if (k == i) {
            snprintf(w, size, "%.*s", (int)(len < RESUME_WORD_MAX ? len : RESUME_WORD_MAX), s);
            return 1;
        }
        s += len;
    }
}

void whirl_resume_difference(const char *want, const char *have, const char *of, char *buf,
                             size_t size)
{
    char a[RESUME_WORD_MAX + 1], b[RESUME_WORD_MAX + 1], prev[RESUME_WORD_MAX + 1] = "";
    size_t i = 0;
    for (;; i++) {
        const int ia = word(want, i, a, sizeof a), ib = word(have, i, b, sizeof b);
        if (!ia && !ib) break; /* the same words: spaces differ */
        if (!ia || !ib || strcmp(a, b) != 0) {
            snprintf(buf, size, "'%s%s%s' where these %s write '%s%s%s'", prev, *prev ? " " : "",
                     ib ? b : "(the end of the line)", of, prev, *prev ? " " : "",
                     ia ? a : "(the end of the line)");
            return;
        }
        snprintf(prev, sizeof prev, "%s", a);
    }
    snprintf(buf, size, "other spacing than these %s write", of);
}

int whirl_resume_row_check(const char *line, size_t fields, char *why, size_t size)
{
    size_t n = 0;
    const char *p = line;
    for (;;) {
        size_t len = strcspn(p, ",\n");
        /* the whole field, however long (a copy cut to a buffer's length read "0...01e999"
         * as 0); strtod stops at the field's end at the latest: ',' and '\n' end any number.
         * A field that begins with a number that is not finite is refused whatever follows
         * ("nan ", "1e999x": text to this check, a number to a reader that stops there). */
        char *end = (char *)p;
        const double x = len > 0 ? strtod(p, &end) : 0;
        if (end != p && !isfinite(x)) { /* nan, inf, 1e999 */
            snprintf(why, size, "column %zu holds '%.*s%s', not a finite number", n + 1,
                     (int)(len < 40 ? len : 40), p, len < 40 ? "" : "...");
            return -1;
        }
        n++;
        if (p[len] != ',') break;
        p += len + 1;
    }
    if (n != fields) {
        snprintf(why, size, "%zu columns, the header has %zu (a row cut short or run together)",
                 n, fields);
        return -1;
    }
    return 0;
}

/* Reads the next line into r->line: its length, 0 at the end of the file. *complete: it ends
 * with a newline; *bad: what is wrong with it (a NUL byte, or longer than line_max: then *cut
 * too), or NULL. */
static long read_line(whirl_resume *r, int *complete, const char **bad, int *cut)
{
    size_t n = 0;
    int c;
    *complete = *cut = 0;
    *bad = NULL;
    while ((c = getc(r->in)) != EOF) {
        if (c == '\0') *bad = "a NUL byte";
        if (n == r->p.line_max + 1) {
            *bad = "a line too long";
            *cut = 1;
            while (c != EOF && c != '\n') c = getc(r->in);
            if (c == '\n') *complete = 1;
            break;
        }
        r->line[n++] = (char)c;
        if (c == '\n') {
            *complete = 1;
            break;
        }
    }
    r->line[n] = '\0';
    if (n > 0 || *complete) r->lineno++;
    return (long)n;
}

whirl_resume_kind whirl_resume_next(whirl_resume *r, const char **line)
{
    for (;;) {
        int complete, cut;
        const char *bad;
        const long n = read_line(r, &complete, &bad, &cut);
        *line = r->line;
        if (ferror(r->in)) {
            whirl_fail(GSL_EFAILED, "cannot read '%s'", r->path);
            return WHIRL_RESUME_ERROR;
        }
        /* (a long unfinished last row: cut short by a kill, dropped below) */
        if (bad && (!cut || complete || r->want))
            return whirl_resume_refuse(r, "%s (the limit is %zu characters)", bad,
                                       r->p.line_max);
        if (n == 0 || !complete) { /* the end, or an unfinished last line */
            if (r->want == NULL) return WHIRL_RESUME_END;
            whirl_fail(GSL_EINVAL, "'%s' holds no %s of these %s", r->path, r->p.kind, r->p.of);
            return WHIRL_RESUME_ERROR;
        }
        if (r->want) { /* the header, line by line */
            if (r->p.note && strncmp(r->line, r->p.note, strlen(r->p.note)) == 0)
                return WHIRL_RESUME_NOTE;
            const size_t len = strcspn(r->want, "\n") + 1;
            if (strncmp(r->want, r->line, len) != 0 || r->line[len] != '\0') {
                char diff[3 * RESUME_WORD_MAX + 80], want[1024];
                snprintf(want, sizeof want, "%.*s",
                         (int)(len < sizeof want ? len : sizeof want - 1), r->want);
                whirl_resume_difference(want, r->line, r->p.of, diff, sizeof diff);
                whirl_fail(GSL_EINVAL, "'%s' was not written by %s %s with these %s: line %ld "
                           "has %s", r->path, article(r->p.kind), r->p.kind, r->p.of, r->lineno,
                           diff);
                return WHIRL_RESUME_ERROR;
            }
            r->want = r->want[len] ? r->want + len : NULL;
            continue;
        }
        if (r->line[0] == '#' || (r->p.blank && r->line[0] == '\n')) return WHIRL_RESUME_NOTE;
        /* a complete row must be whole and finite: a file that holds others cannot be trusted */
        char why[160];
        if (whirl_resume_row_check(r->line, r->fields, why, sizeof why) != 0)
            return whirl_resume_refuse(r, "%s", why);
        return WHIRL_RESUME_ROW;
    }
}
