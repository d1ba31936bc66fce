/* --resume: the header matched, the rows checked, one line at a time (resume.h). */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli/resume.h"

#define RESUME_WORD_MAX 60 /* characters of a word shown in a message (a long one is cut) */

struct cli_resume {
    const cli_command *cmd;
    FILE *in;
    const char *path;
    cli_resume_params p;
    const char *want;  /* the header line expected next (NULL: the header is matched) */
    size_t fields;     /* columns of a row: those of the header's last line */
    char *line;        /* the line read, line_max + 2 characters and a NUL */
    long lineno;
};

cli_resume *cli_resume_alloc(const cli_command *cmd, FILE *in, const char *path,
                             const cli_resume_params *params)
{
    cli_resume *r = calloc(1, sizeof *r);
    if (r) r->line = malloc(params->line_max + 3);
    if (r == NULL || r->line == NULL) {
        free(r);
        cli_error(cmd, "out of memory");
        return NULL;
    }
    r->cmd = cmd;
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

void cli_resume_free(cli_resume *r)
{
    if (r == NULL) return;
    free(r->line);
    free(r);
}

long cli_resume_lineno(const cli_resume *r)
{
    return r->lineno;
}

/* The article of a noun in messages. */
static const char *article(const char *noun)
{
    return strchr("aeiou", noun[0]) ? "an" : "a";
}

int cli_resume_refuse(cli_resume *r, const char *fmt, ...)
{
    char why[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    cli_error(r->cmd, "--resume: %s:%ld: %s: the file cannot be trusted (remove the row, or "
              "start the %s afresh)", r->path, r->lineno, why, r->p.kind);
    return CLI_RESUME_ERROR;
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

void cli_resume_difference(const char *want, const char *have, const char *of, char *buf,
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

/* Reads the next line into r->line: its length, 0 at the end of the file. *complete: it ends
 * with a newline; *bad: what is wrong with it (a NUL byte, or longer than line_max: then *cut
 * too), or NULL. */
static long read_line(cli_resume *r, int *complete, const char **bad, int *cut)
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

cli_resume_kind cli_resume_next(cli_resume *r, const char **line)
{
    for (;;) {
        int complete, cut;
        const char *bad;
        const long n = read_line(r, &complete, &bad, &cut);
        *line = r->line;
        if (ferror(r->in)) {
            cli_error(r->cmd, "--resume: cannot read '%s'", r->path);
            return CLI_RESUME_ERROR;
        }
        /* (a long unfinished last row: cut short by a kill, dropped below) */
        if (bad && (!cut || complete || r->want))
            return cli_resume_refuse(r, "%s (the limit is %zu characters)", bad, r->p.line_max);
        if (n == 0 || !complete) { /* the end, or an unfinished last line */
            if (r->want == NULL) return CLI_RESUME_END;
            cli_error(r->cmd, "--resume: '%s' holds no %s of these %s", r->path, r->p.kind,
                      r->p.of);
            return CLI_RESUME_ERROR;
        }
        if (r->want) { /* the header, line by line */
            if (r->p.note && strncmp(r->line, r->p.note, strlen(r->p.note)) == 0)
                return CLI_RESUME_NOTE;
            const size_t len = strcspn(r->want, "\n") + 1;
            if (strncmp(r->want, r->line, len) != 0 || r->line[len] != '\0') {
                char diff[3 * RESUME_WORD_MAX + 80], want[1024];
                snprintf(want, sizeof want, "%.*s", (int)(len < sizeof want ? len : sizeof want - 1),
                         r->want);
                cli_resume_difference(want, r->line, r->p.of, diff, sizeof diff);
                cli_error(r->cmd, "--resume: '%s' was not written by %s %s with these %s: line "
                          "%ld has %s", r->path, article(r->p.kind), r->p.kind, r->p.of,
                          r->lineno, diff);
                return CLI_RESUME_ERROR;
            }
            r->want = r->want[len] ? r->want + len : NULL;
            continue;
        }
        if (r->line[0] == '#') return CLI_RESUME_NOTE;
        /* a complete row must be whole and finite: a file that holds others cannot be trusted */
        char why[160];
        if (cli_row_check(r->line, r->fields, why, sizeof why) != 0)
            return cli_resume_refuse(r, "%s", why);
        return CLI_RESUME_ROW;
    }
}
