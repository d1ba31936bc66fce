/* Command-line plumbing: option parsing, one-line errors, atomic output, units, progress. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"

int cli_error(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "whirl %s: ", cmd->name);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return 1;
}

static void print_help(const cli_command *cmd, const cli_option *opts, size_t nopts)
{
    printf("usage: whirl %s %s\n%s\n\noptions:\n", cmd->name, cmd->synopsis, cmd->summary);
    for (size_t i = 0; i < nopts; i++) {
        char left[64];
        snprintf(left, sizeof left, "%s%s%s %s", opts[i].alias ? opts[i].alias : "",
                 opts[i].alias ? ", " : "", opts[i].name,
                 opts[i].type == CLI_FLAG ? "" : opts[i].meta);
        printf("  %-26s %s\n", left, opts[i].help);
    }
    printf("  %-26s %s\n", "--help", "print this help");
}

/* A finite double, the whole string. */
static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

static int parse_int(const char *s, const char **end_out, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || errno == ERANGE || v < INT_MIN || v > INT_MAX) return -1;
    *out = (int)v;
    *end_out = end;
    return 0;
}

static int parse_value(const cli_option *o, const char *text)
{
    const char *end;
    switch (o->type) {
    case CLI_DOUBLE:
        return parse_double(text, o->value);
    case CLI_INT:
        return (parse_int(text, &end, o->value) == 0 && *end == '\0') ? 0 : -1;
    case CLI_STRING:
        *(const char **)o->value = text;
        return 0;
    case CLI_INT_LIST: {
        cli_int_list *list = o->value;
        list->n = 0;
        const char *p = text;
        for (;;) {
            if (list->n == CLI_LIST_MAX) return -1;
            if (parse_int(p, &end, &list->v[list->n]) != 0) return -1;
            list->n++;
            if (*end == '\0') return 0;
            if (*end != ',') return -1;
            p = end + 1;
        }
    }
    case CLI_FLAG:
        break;
    }
    return -1;
}

static const char *type_words(cli_type t)
{
    switch (t) {
    case CLI_DOUBLE: return "a finite number";
    case CLI_INT: return "an integer";
    case CLI_INT_LIST: return "a comma-separated list of integers";
    default: return "a value";
    }
}

int cli_parse(const cli_command *cmd, int argc, char **argv, const cli_option *opts, size_t nopts,
              const char **positional, size_t npos)
{
    size_t npos_seen = 0;
    for (size_t k = 0; k < npos; k++) positional[k] = NULL;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            print_help(cmd, opts, nopts);
            return 2;
        }
        if (arg[0] != '-' || strcmp(arg, "-") == 0) {
            if (npos_seen == npos) return cli_error(cmd, "unexpected argument '%s'", arg);
            positional[npos_seen++] = arg;
            continue;
        }
        /* --name=value or --name value */
        const char *eq = strchr(arg, '=');
        size_t name_len = eq ? (size_t)(eq - arg) : strlen(arg);
        const cli_option *o = NULL;
        for (size_t k = 0; k < nopts && o == NULL; k++) {
            if ((strlen(opts[k].name) == name_len && strncmp(opts[k].name, arg, name_len) == 0) ||
                (opts[k].alias && strlen(opts[k].alias) == name_len &&
                 strncmp(opts[k].alias, arg, name_len) == 0))
                o = &opts[k];
        }
        if (o == NULL) return cli_error(cmd, "unknown option '%.*s' (see --help)", (int)name_len, arg);
        if (o->given) *o->given = 1;
        if (o->type == CLI_FLAG) {
            if (eq) return cli_error(cmd, "option %s takes no value", o->name);
            *(int *)o->value = 1;
            continue;
        }
        const char *text = eq ? eq + 1 : (i + 1 < argc ? argv[++i] : NULL);
        if (text == NULL) return cli_error(cmd, "option %s needs a value (%s)", o->name, o->meta);
        if (parse_value(o, text) != 0)
            return cli_error(cmd, "option %s needs %s, got '%s'", o->name, type_words(o->type), text);
    }
    return 0;
}

int cli_out_open(const cli_command *cmd, cli_out *out, const char *path)
{
    out->fp = stdout;
    out->path = NULL;
    out->tmp = NULL;
    if (path == NULL || strcmp(path, "-") == 0) return 0;
    if (path[0] == '\0') return cli_error(cmd, "empty output file name");
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* A device or a pipe (say /dev/null) is written in place: it cannot be renamed over. */
        out->fp = fopen(path, "w");
        if (out->fp == NULL) return cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
        return 0;
    }
    size_t len = strlen(path);
    out->path = malloc(len + 1);
    out->tmp = malloc(len + 16);
    if (out->path == NULL || out->tmp == NULL) {
        cli_out_abort(out);
        return cli_error(cmd, "out of memory");
    }
    memcpy(out->path, path, len + 1);
    snprintf(out->tmp, len + 16, "%s.tmp.XXXXXX", path);
    int fd = mkstemp(out->tmp);
    if (fd < 0) {
        int err = errno;
        free(out->tmp);
        out->tmp = NULL;
        cli_out_abort(out);
        return cli_error(cmd, "cannot write '%s': %s", path, strerror(err));
    }
    /* mkstemp creates the file 0600: give it the mode a plain fopen would (0666 less umask). */
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    out->fp = fdopen(fd, "w");
    if (out->fp == NULL) {
        close(fd);
        cli_out_abort(out);
        return cli_error(cmd, "cannot write '%s': %s", path, strerror(errno));
    }
    return 0;
}

int cli_out_commit(const cli_command *cmd, cli_out *out)
{
    if (out->path == NULL) {
        if (out->fp == stdout) {
            if (fflush(stdout) != 0 || ferror(stdout))
                return cli_error(cmd, "error writing standard output");
            return 0;
        }
        int bad = ferror(out->fp) | (fclose(out->fp) != 0);
        out->fp = NULL;
        return bad ? cli_error(cmd, "error writing the output") : 0;
    }
    int bad = ferror(out->fp);
    bad |= fclose(out->fp) != 0;
    out->fp = NULL;
    if (bad || rename(out->tmp, out->path) != 0) {
        int err = errno;
        cli_error(cmd, "cannot write '%s': %s", out->path, strerror(err));
        cli_out_abort(out);
        return 1;
    }
    free(out->tmp);
    free(out->path);
    out->tmp = out->path = NULL;
    return 0;
}

void cli_out_abort(cli_out *out)
{
    if (out->fp && out->fp != stdout) fclose(out->fp);
    out->fp = NULL;
    if (out->tmp) remove(out->tmp);
    free(out->tmp);
    free(out->path);
    out->tmp = out->path = NULL;
}

int cli_units_check(const cli_command *cmd, const cli_units *u)
{
    const struct {
        const char *name;
        double value;
    } unit[3] = {{"--length", u->length}, {"--mass", u->mass}, {"--gravity", u->gravity}};
    for (int i = 0; i < 3; i++)
        if (!(unit[i].value > 0))
            return cli_error(cmd, "%s must be > 0, got %g", unit[i].name, unit[i].value);
        else if (!(unit[i].value >= CLI_UNIT_MIN && unit[i].value <= CLI_UNIT_MAX))
            return cli_error(cmd, "%s must be between %g and %g, got %g (results in these units "
                             "would overflow)", unit[i].name, CLI_UNIT_MIN, CLI_UNIT_MAX,
                             unit[i].value);
    return 0;
}

double cli_units_rate(const cli_units *u) { return sqrt(u->gravity / u->length); }
double cli_units_force(const cli_units *u) { return u->mass * u->gravity; }

void cli_catch_interrupts(void) { whirl_stop_catch_signals(); }

void cli_progress(const cli_command *cmd, const char *label, double fraction, int done)
{
    static int tty = -1;
    if (tty < 0) tty = isatty(STDERR_FILENO);
    if (!tty) return;
    fprintf(stderr, "\rwhirl %s: %s %3.0f%%", cmd->name, label, 100 * fraction);
    if (done) fputc('\n', stderr);
    fflush(stderr);
}
