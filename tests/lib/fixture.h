/* Reference values kept as files under tests/fixtures/, for the unit tests whose independent
 * reference is too costly to compute in every `make check` (make fixtures-check computes them
 * anew and compares). A fixture is plain text:
 *   # COMMAND        the command, from the repository's root, that writes this file
 *   # PROBLEM        the parameters the values belong to (chain, discretisation, cases)
 *   # ...            further comments, anywhere
 *   VALUE            one a line, printed with %.17g (counts and signatures as integers)
 * A test opens it with the command and the problem it builds itself and reads the values in the
 * order they were written; a file that is missing, written by another command or for another
 * problem, malformed, short or long fails the test, naming the file and the command that writes
 * it. WHIRL_SOURCE_DIR (the repository's root; the Makefile passes it) locates the folder.
 * Header-only (static functions); the test programs include cmocka before it. */
#ifndef WHIRL_FIXTURE_H
#define WHIRL_FIXTURE_H

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#ifndef WHIRL_SOURCE_DIR
#error "WHIRL_SOURCE_DIR (the repository's root, a string) is needed: the Makefile defines it"
#endif

/* the folder of the fixtures, from the repository's root */
#define FIXTURE_DIR "tests/fixtures"

typedef struct fixture {
    FILE *fp;
    char path[4096];
    const char *command;
    char *line;  /* the last line read (getline's buffer) */
    size_t cap;
    size_t lineno;
} fixture;

/* The next line of f without its newline; 0 at the end of the file. */
static int fixture_line(fixture *f)
{
    const ssize_t n = getline(&f->line, &f->cap, f->fp);
    if (n < 0) {
        if (ferror(f->fp)) fail_msg("%s: read error after line %zu", f->path, f->lineno);
        return 0;
    }
    f->lineno++;
    if (n > 0 && f->line[n - 1] == '\n') f->line[n - 1] = '\0';
    return 1;
}

/* Opens fixture NAME (under FIXTURE_DIR of WHIRL_SOURCE_DIR) and checks its first two lines: the
 * command that writes it and the problem (both without the leading "# "). */
static void fixture_open(fixture *f, const char *name, const char *command, const char *problem)
{
    memset(f, 0, sizeof *f);
    f->command = command;
    snprintf(f->path, sizeof f->path, "%s/%s/%s", WHIRL_SOURCE_DIR, FIXTURE_DIR, name);
    f->fp = fopen(f->path, "r");
    if (f->fp == NULL)
        fail_msg("%s: cannot read the fixture (%s); write it from the repository's root with\n  %s",
                 f->path, strerror(errno), command);
    if (!fixture_line(f) || strncmp(f->line, "# ", 2) != 0 || strcmp(f->line + 2, command) != 0)
        fail_msg("%s: line 1 is not \"# %s\" (the file is another command's)", f->path, command);
    if (!fixture_line(f) || strncmp(f->line, "# ", 2) != 0 || strcmp(f->line + 2, problem) != 0) {
        /* the lines in full (fail_msg's text is cut at about 1000 characters) */
        fprintf(stderr, "the fixture's line 2: %s\nthis test's problem: # %s\n",
                f->lineno == 2 ? f->line : "(none)", problem);
        fail_msg("%s: the fixture belongs to another problem (its line 2 above); write it anew "
                 "with\n  %s", f->path, command);
    }
}

/* The next value of f (comment lines skipped): a finite number filling its line. */
static double fixture_value(fixture *f)
{
    do {
        if (!fixture_line(f))
            fail_msg("%s: ends after line %zu, where this test reads another value; write it "
                     "anew with\n  %s", f->path, f->lineno, f->command);
    } while (f->line[0] == '#');
    char *end;
    errno = 0;
    const double v = strtod(f->line, &end);
    if (end == f->line || *end != '\0' || errno != 0 || !isfinite(v))
        fail_msg("%s:%zu: \"%s\" is not a finite number", f->path, f->lineno, f->line);
    return v;
}

/* The next value of f as an integer in [lo, hi]. */
static long fixture_int(fixture *f, long lo, long hi)
{
    const double v = fixture_value(f);
    if (v != floor(v) || v < (double)lo || v > (double)hi)
        fail_msg("%s:%zu: \"%s\" is not an integer in [%ld, %ld]", f->path, f->lineno, f->line,
                 lo, hi);
    return (long)v;
}

/* Checks that no value follows, and closes f. */
static void fixture_close(fixture *f)
{
    while (fixture_line(f))
        if (f->line[0] != '#')
            fail_msg("%s:%zu: a value more than this test reads; write it anew with\n  %s",
                     f->path, f->lineno, f->command);
    fclose(f->fp);
    free(f->line);
    f->fp = NULL, f->line = NULL;
}

/* Writing: the values go to DIR/NAME.tmp, renamed to DIR/NAME once complete. */
typedef struct fixture_out {
    FILE *fp;
    char path[4096], tmp[4100];
} fixture_out;

static void fixture_create(fixture_out *o, const char *dir, const char *name, const char *command,
                           const char *problem)
{
    snprintf(o->path, sizeof o->path, "%s/%s", dir, name);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp", o->path);
    o->fp = fopen(o->tmp, "w");
    if (o->fp == NULL) fail_msg("cannot write '%s': %s", o->tmp, strerror(errno));
    fprintf(o->fp, "# %s\n# %s\n", command, problem);
}

static void fixture_comment(fixture_out *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("# ", o->fp);
    vfprintf(o->fp, fmt, ap);
    fputc('\n', o->fp);
    va_end(ap);
}

static void fixture_put(fixture_out *o, double v)
{
    assert_true(isfinite(v));
    fprintf(o->fp, "%.17g\n", v);
}

static void fixture_commit(fixture_out *o)
{
    const int bad = ferror(o->fp);
    if (fclose(o->fp) != 0 || bad) {
        remove(o->tmp);
        fail_msg("cannot write '%s'", o->tmp);
    }
    if (rename(o->tmp, o->path) != 0) fail_msg("cannot rename '%s': %s", o->tmp, strerror(errno));
    printf("# wrote %s\n", o->path);
}

#endif
