/* Command-line plumbing: option parsing, one-line errors, atomic output, units, progress. */
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"

int cli_error(const cli_command *cmd, const char *fmt, ...)
{
    /* the reader of standard output has gone (SIGPIPE: `whirl shape ... | head -2`): the work
     * stops without a word, as coreutils do; the exit status (141) still tells a script */
    if (whirl_stop_signal() == SIGPIPE) return 1;
    char msg[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "whirl %s: ", cmd->name);
    cli_put_escaped(stderr, msg);
    fputc('\n', stderr);
    return 1;
}

/* ---- the option table: units, ranges, help ---- */

/* The library's kind of quantity for a unit kind: the unit suffixes it accepts. */
static whirl_quantity quantity_of(cli_unit kind)
{
    switch (kind) {
    case CLI_UNIT_RATE: return WHIRL_QUANTITY_RATE;
    case CLI_UNIT_LENGTH:
    case CLI_UNIT_SET_LENGTH: return WHIRL_QUANTITY_LENGTH;
    case CLI_UNIT_MASS:
    case CLI_UNIT_SET_MASS: return WHIRL_QUANTITY_MASS;
    case CLI_UNIT_TIME: return WHIRL_QUANTITY_TIME;
    default: return WHIRL_QUANTITY_NUMBER;
    }
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

const char *cli_suffix_name(const char *text)
{
    static const char *const names[] = {"rad/s", "Hz", "rpm", "m", "cm", "mm", "kg", "g", "s",
                                        "ms"};
    char *end;
    strtod(text, &end);
    while (*end == ' ') end++;
    for (size_t i = 0; i < sizeof names / sizeof *names; i++)
        if (strcasecmp(end, names[i]) == 0) return names[i];
    return "";
}

size_t cli_edit_distance(const char *a, size_t alen, const char *b)
{
    /* one row of the dynamic programme, for names up to 63 chars */
    size_t row[64], blen = strlen(b);
    if (alen > 63 || blen > 63) return (size_t)-1;
    for (size_t j = 0; j <= blen; j++) row[j] = j;
    for (size_t i = 1; i <= alen; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= blen; j++) {
            const size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[blen];
}

/* A comma list of quantities of the option's kind. */
static int parse_double_list(const cli_option *o, const char *text)
{
    cli_double_list *list = o->value;
    list->n = 0;
    for (const char *p = text;;) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char item[64];
        if (list->n == CLI_LIST_MAX || len == 0 || len >= sizeof item) return -1;
        memcpy(item, p, len);
        item[len] = '\0';
        if (whirl_parse_quantity(item, quantity_of(o->unit), &list->v[list->n], NULL) != 0)
            return -1;
        list->suffix[list->n++] = cli_suffix_name(item);
        if (comma == NULL) return 0;
        p = comma + 1;
    }
}

static int parse_value(const cli_option *o, const char *text)
{
    const char *end;
    switch (o->type) {
    case CLI_DOUBLE:
        return whirl_parse_quantity(text, quantity_of(o->unit), o->value, NULL);
    case CLI_DOUBLE_LIST:
        return parse_double_list(o, text);
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
            if (*end == '-') { /* a range A-B, A <= B */
                int last;
                if (parse_int(end + 1, &end, &last) != 0 || last < list->v[list->n - 1])
                    return -1;
                while (list->v[list->n - 1] < last) {
                    if (list->n == CLI_LIST_MAX) return -1;
                    list->v[list->n] = list->v[list->n - 1] + 1;
                    list->n++;
                }
            }
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

/* What option o takes, in words (buf: room for the longest, 96 chars). */
static const char *type_words(const cli_option *o, char *buf, size_t size)
{
    switch (o->type) {
    case CLI_DOUBLE: {
        const whirl_quantity q = quantity_of(o->unit);
        if (q == WHIRL_QUANTITY_NUMBER) return "a finite number";
        snprintf(buf, size, "a finite number (optionally with %s)", whirl_quantity_suffixes(q));
        return buf;
    }
    case CLI_INT: return "an integer";
    case CLI_INT_LIST: return "a comma-separated list of integers or ranges A-B";
    case CLI_DOUBLE_LIST: {
        const whirl_quantity q = quantity_of(o->unit);
        if (q == WHIRL_QUANTITY_NUMBER) return "a finite number or a comma list of them";
        snprintf(buf, size, "a finite number (optionally with %s) or a comma list of them",
                 whirl_quantity_suffixes(q));
        return buf;
    }
    default: return "a value";
    }
}

/* An interval "(0, inf)", "[1, 64]", "[0, 1)": ends, and whether each is included. */
typedef struct interval {
    double lo, hi;
    int lo_in, hi_in;
} interval;

static int parse_range(const char *text, interval *r)
{
    char open, close;
    char lo[32], hi[32];
    if (sscanf(text, " %c %31[^, ] , %31[^])] %c", &open, lo, hi, &close) != 4) return -1;
    if ((open != '(' && open != '[') || (close != ')' && close != ']')) return -1;
    r->lo = strcmp(lo, "-inf") == 0 ? -HUGE_VAL : strtod(lo, NULL);
    r->hi = strcmp(hi, "inf") == 0 ? HUGE_VAL : strtod(hi, NULL);
    r->lo_in = open == '[';
    r->hi_in = close == ']';
    return 0;
}

static int in_range(const interval *r, double x)
{
    return (r->lo_in ? x >= r->lo : x > r->lo) && (r->hi_in ? x <= r->hi : x < r->hi);
}

/* "must be > 0", "must be between 1 and 64", "must be in [0, 1)". */
static void range_words(const interval *r, char *buf, size_t size)
{
    char lo[WHIRL_FORMAT_MAX], hi[WHIRL_FORMAT_MAX];
    whirl_format_double(lo, r->lo);
    whirl_format_double(hi, r->hi);
    if (isinf(r->hi) && isinf(r->lo)) snprintf(buf, size, "must be finite");
    else if (isinf(r->hi)) snprintf(buf, size, "must be %s %s", r->lo_in ? ">=" : ">", lo);
    else if (isinf(r->lo)) snprintf(buf, size, "must be %s %s", r->hi_in ? "<=" : "<", hi);
    else if (r->lo_in && r->hi_in) snprintf(buf, size, "must be between %s and %s", lo, hi);
    else snprintf(buf, size, "must be in %c%s, %s%c", r->lo_in ? '[' : '(', lo, hi,
                  r->hi_in ? ']' : ')');
}

static const char *const si_names[] = {"", "rad/s", "m", "kg", "s", "N", "kg/(m s)", "kg/m^2",
                                       "kg m^2/s", "m", "kg", "m/s^2"};
static const char *const unit_names[] = {"", "sqrt(g/L)", "L", "M", "sqrt(L/g)", "M g",
                                         "M sqrt(g/L)/L", "M/L^2", "M L^2 sqrt(g/L)", "m", "kg",
                                         "m/s^2"};

double cli_units_scale(const cli_units *u, cli_unit kind)
{
    const double rate = cli_units_rate(u);
    switch (kind) {
    case CLI_UNIT_RATE: return rate;
    case CLI_UNIT_LENGTH: return u->length;
    case CLI_UNIT_MASS: return u->mass;
    case CLI_UNIT_TIME: return 1 / rate;
    case CLI_UNIT_FORCE: return u->mass * u->gravity;
    case CLI_UNIT_DRAG: return u->mass * rate / u->length;
    case CLI_UNIT_DRAG2: return u->mass / (u->length * u->length);
    case CLI_UNIT_DAMPING: return u->mass * u->length * u->length * rate;
    default: return 1;
    }
}

const char *cli_units_name(const cli_units *u, cli_unit kind)
{
    if ((size_t)kind >= sizeof si_names / sizeof *si_names) return "";
    return u->physical ? si_names[kind] : unit_names[kind];
}

const char *cli_rate_words(const cli_units *u, double omega, char *buf, size_t size)
{
    const double w = omega * cli_units_rate(u);
    if (u->physical) snprintf(buf, size, "%.4g rad/s (%.4g Hz)", w, w / 6.283185307179586);
    else snprintf(buf, size, "%.4g sqrt(g/L)", w);
    return buf;
}

void cli_units_comment(FILE *fp, const cli_units *u)
{
    whirl_write_units_line(fp, u->physical, u->length, u->mass, u->gravity);
    if (u->physical && !u->mass_given)
        fprintf(fp, "# mass: M=%s kg assumed (no --mass given); masses, forces and tensions "
                    "scale with M\n", CLI_NUM(u->mass));
}

int cli_drag_apply(const cli_command *cmd, const cli_air *air, double *drag2)
{
    (void)cmd;
    if (air->cd > 0)
        *drag2 = 0.5 * air->density * air->cd * air->diameter * air->units->length /
                 cli_units_scale(air->units, CLI_UNIT_DRAG2);
    return 0;
}

void cli_trace_header(FILE *fp, const cli_units *u, const char *what, double omega, double eps,
                      const char *pivot, double drag, double drag2, int links)
{
    fprintf(fp, "# trace: %s; inertial frame, columns x y z t, one block per time (the pivot, "
                "then masses 1..N); omega=%s %s%s drag=%s drag_quadratic=%s links=%d\n",
            what, CLI_NUM(omega * cli_units_scale(u, CLI_UNIT_RATE)), pivot ? "pivot=" : "eps=",
            pivot ? pivot : CLI_NUM(eps * cli_units_scale(u, CLI_UNIT_LENGTH)),
            CLI_NUM(drag * cli_units_scale(u, CLI_UNIT_DRAG)),
            CLI_NUM(drag2 * cli_units_scale(u, CLI_UNIT_DRAG2)), links);
    cli_units_comment(fp, u);
}

void cli_put_num(FILE *fp, double x)
{
    char buf[WHIRL_FORMAT_MAX];
    fputs(whirl_format_double(buf, x), fp);
}

double cli_grid(double lo, double hi, int count, int i)
{
    if (count <= 1 || i <= 0) return lo;
    if (i >= count - 1) return hi;
    const double x = lo + (hi - lo) * (double)i / (double)(count - 1);
    /* The rounding of the two operations leaves a few ulp of binary noise on a decimal grid
     * (1.4 + 4.2/14 = 1.6999999999999997): the nearest 15-digit decimal is the grid point meant
     * (it moves x by at most 5e-16 relative), and it prints as written. */
    char buf[32];
    snprintf(buf, sizeof buf, "%.15g", x);
    const double snapped = strtod(buf, NULL);
    return fabs(snapped - x) <= 4 * DBL_EPSILON * fabs(x) ? snapped : x;
}

/* The option of the table named name (up to len chars), or NULL. */
static const cli_option *find_option(const cli_option *opts, size_t nopts, const char *name,
                                     size_t len)
{
    for (size_t k = 0; k < nopts; k++)
        if ((strlen(opts[k].name) == len && strncmp(opts[k].name, name, len) == 0) ||
            (opts[k].alias && strlen(opts[k].alias) == len && strncmp(opts[k].alias, name, len) == 0))
            return &opts[k];
    return NULL;
}

/* The first option of the space-separated list that was given (want 1) or not (want 0), or
 * NULL; options of the list missing from the table count as not given. */
static const char *first_in_list(const cli_option *opts, size_t nopts, const char *given,
                                 const char *list, int want, char *buf, size_t size)
{
    for (const char *p = list; p && *p;) {
        while (*p == ' ') p++;
        size_t len = strcspn(p, " ");
        if (len == 0) break;
        const cli_option *o = find_option(opts, nopts, p, len);
        int is_given = o ? given[o - opts] : 0;
        if (is_given == want) {
            snprintf(buf, size, "%.*s", (int)len, p);
            return buf;
        }
        p += len;
    }
    return NULL;
}

static void option_left(const cli_option *o, char *buf, size_t size)
{
    snprintf(buf, size, "%s%s%s%s%s", o->alias ? o->alias : "", o->alias ? ", " : "", o->name,
             o->type == CLI_FLAG ? "" : " ", o->type == CLI_FLAG ? "" : o->meta);
}

/* The synopsis from the table: required options bare, alternatives "(--a A | --b B)", the
 * others in brackets. */
static void print_synopsis(FILE *fp, const cli_command *cmd, const cli_option *opts, size_t nopts)
{
    if (cmd->synopsis) {
        fprintf(fp, "%s", cmd->synopsis);
        return;
    }
    const char *sep = "";
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        char left[96];
        snprintf(left, sizeof left, "%s%s%s", o->name, o->type == CLI_FLAG ? "" : " ",
                 o->type == CLI_FLAG ? "" : o->meta);
        if (o->required && o->required[0] == '\0') fprintf(fp, "%s%s", sep, left);
        else if (o->required) {
            /* an alternative: printed once, at its first member */
            int first = 1;
            for (size_t k = 0; k < i; k++)
                if (opts[k].required && opts[k].required[0] && strstr(o->required, opts[k].name))
                    first = 0;
            if (!first) continue;
            fprintf(fp, "%s(%s", sep, left);
            for (size_t k = i + 1; k < nopts; k++)
                if (opts[k].required && strstr(o->required, opts[k].name) &&
                    strcmp(opts[k].name, o->name) != 0)
                    fprintf(fp, " | %s%s%s", opts[k].name, opts[k].type == CLI_FLAG ? "" : " ",
                            opts[k].type == CLI_FLAG ? "" : opts[k].meta);
            fputc(')', fp);
        } else fprintf(fp, "%s[%s]", sep, left);
        sep = " ";
    }
}

static void print_help(const cli_command *cmd, const cli_option *opts, size_t nopts)
{
    printf("usage: whirl %s ", cmd->name);
    print_synopsis(stdout, cmd, opts, nopts);
    printf("\n%s\n", cmd->summary);
    int has_units = 0;
    for (size_t i = 0; i < nopts; i++) has_units |= opts[i].unit == CLI_UNIT_SET_LENGTH;
    if (has_units)
        printf("Units: dimensionless (length L, mass M, time sqrt(L/g)) unless --length, --mass "
               "or --gravity is given; then SI (m, kg, s, rad/s, N), and values may carry "
               "their unit: 4Hz, 240rpm, 60cm, 50g (a unit without --length is an error).\n");
    printf("\noptions:\n");
    const cli_units dimensionless = {1, 1, 1, 0}, si = {1, 1, 1, 1};
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        char left[96];
        option_left(o, left, sizeof left);
        printf("  %-26s %s", left, o->help);
        if (o->unit != CLI_UNIT_NONE && o->unit < CLI_UNIT_SET_LENGTH)
            printf(" [%s; %s]", cli_units_name(&dimensionless, o->unit),
                   cli_units_name(&si, o->unit));
        if (o->range) printf(" (range %s)", o->range);
        if (o->required && o->required[0] == '\0') printf(" (required)");
        putchar('\n');
    }
    printf("  %-26s %s\n", "-h, --help", "print this help");
    if (cmd->example) printf("\nexample:\n  %s\n", cmd->example);
}

static int check_ranges(const cli_command *cmd, const cli_option *opts, size_t nopts,
                        const char *given, int units_only);

/* The table's checks, after parsing; given[i]: option i appeared. */
static int check_table(const cli_command *cmd, const cli_option *opts, size_t nopts,
                       const char *given)
{
    char name[64];
    /* conflicts first (they say most about what was meant), then what is missing */
    for (size_t i = 0; i < nopts; i++)
        if (given[i] && first_in_list(opts, nopts, given, opts[i].excludes, 1, name, sizeof name))
            return cli_error(cmd, "%s cannot be given with %s", opts[i].name, name);
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        if (!o->required || given[i]) continue;
        if (o->required[0] == '\0') return cli_error(cmd, "%s is required", o->name);
        if (first_in_list(opts, nopts, given, o->required, 1, name, sizeof name) == NULL)
            return cli_error(cmd, "%s or %s is required", o->name, o->required);
    }
    for (size_t i = 0; i < nopts; i++)
        if (given[i] && first_in_list(opts, nopts, given, opts[i].needs, 0, name, sizeof name))
            return cli_error(cmd, "%s needs %s", opts[i].name, name);
    return check_ranges(cmd, opts, nopts, given, 0);
}

/* The ranges of the options given (units_only: of the unit options only). */
static int check_ranges(const cli_command *cmd, const cli_option *opts, size_t nopts,
                        const char *given, int units_only)
{
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        interval r;
        char words[96];
        if (o->range == NULL || !given[i]) continue;
        if (units_only && o->unit < CLI_UNIT_SET_LENGTH) continue;
        if (parse_range(o->range, &r) != 0)
            return cli_error(cmd, "%s: bad range '%s' in the option table", o->name, o->range);
        range_words(&r, words, sizeof words);
        if (o->type == CLI_DOUBLE) {
            double x = *(double *)o->value;
            if (!in_range(&r, x)) {
                if (o->unit != CLI_UNIT_NONE && o->unit < CLI_UNIT_SET_LENGTH)
                    return cli_error(cmd, "%s %s (in %s), got %s", o->name, words,
                                     cli_units_name(&(cli_units){1, 1, 1, 0}, o->unit),
                                     CLI_NUM(x));
                return cli_error(cmd, "%s %s, got %s", o->name, words, CLI_NUM(x));
            }
        } else if (o->type == CLI_INT) {
            int x = *(int *)o->value;
            if (!in_range(&r, x)) return cli_error(cmd, "%s %s, got %d", o->name, words, x);
        } else if (o->type == CLI_DOUBLE_LIST) {
            const cli_double_list *l = o->value;
            for (int k = 0; k < l->n; k++)
                if (!in_range(&r, l->v[k]))
                    return cli_error(cmd, "%s%s %s, got %s", o->name,
                                     l->n > 1 ? ": each entry" : "", words, CLI_NUM(l->v[k]));
        } else if (o->type == CLI_INT_LIST) {
            const cli_int_list *l = o->value;
            for (int k = 0; k < l->n; k++)
                if (!in_range(&r, l->v[k]))
                    return cli_error(cmd, "%s%s %s, got %d", o->name,
                                     l->n > 1 ? ": each entry" : "", words, l->v[k]);
        }
    }
    return 0;
}

/* The unit options' values (before any default gravity is filled in). */
static cli_units given_units(const cli_option *opts, size_t nopts)
{
    cli_units u = {1, 1, 1, 0};
    for (size_t i = 0; i < nopts; i++) {
        const double *v = opts[i].value;
        if (opts[i].unit == CLI_UNIT_SET_LENGTH) u.length = *v;
        if (opts[i].unit == CLI_UNIT_SET_MASS) u.mass = *v;
        if (opts[i].unit == CLI_UNIT_SET_GRAVITY) u.gravity = *v;
    }
    return u;
}

/* Converts the physical values given to dimensionless ones. */
static void convert_units(const cli_option *opts, size_t nopts, const char *given)
{
    cli_units u = CLI_UNITS_INIT;
    double *gravity = NULL;
    int gravity_given = 0;
    for (size_t i = 0; i < nopts; i++) {
        double *v = opts[i].value;
        switch (opts[i].unit) {
        case CLI_UNIT_SET_LENGTH: u.length = *v, u.physical |= given[i]; break;
        case CLI_UNIT_SET_MASS: u.mass = *v, u.physical |= given[i]; break;
        case CLI_UNIT_SET_GRAVITY:
            gravity = v, gravity_given = given[i], u.physical |= given[i];
            break;
        default: break;
        }
    }
    if (u.physical && gravity && !gravity_given) *gravity = CLI_STANDARD_GRAVITY;
    if (gravity) u.gravity = *gravity;
    else if (u.physical) u.gravity = CLI_STANDARD_GRAVITY;
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        /* --length and --gravity report SI units on (cli_units.physical), --mass its own
         * presence (cli_units.mass_given) */
        if (u.physical && o->given && (o->unit == CLI_UNIT_SET_LENGTH ||
                                       o->unit == CLI_UNIT_SET_GRAVITY))
            *o->given = 1;
        if (!given[i] || o->unit == CLI_UNIT_NONE || o->unit >= CLI_UNIT_SET_LENGTH) continue;
        const double scale = cli_units_scale(&u, o->unit);
        if (o->type == CLI_DOUBLE) *(double *)o->value /= scale;
        if (o->type == CLI_DOUBLE_LIST) {
            cli_double_list *l = o->value;
            for (int k = 0; k < l->n; k++) l->v[k] /= scale;
        }
    }
}

/* A value written with a physical unit (4Hz, 5cm, 10g) where the command works in dimensionless
 * units: the scale is unknown, so it is an error naming the option that gives it. Returns 0, or
 * 1 after printing the error. */
static int check_suffixes(const cli_command *cmd, const cli_option *opts, size_t nopts,
                          const char *const *text)
{
    int physical = 0, has_units = 0;
    for (size_t i = 0; i < nopts; i++)
        if (opts[i].unit >= CLI_UNIT_SET_LENGTH) {
            has_units = 1;
            physical |= text[i] != NULL;
        }
    if (physical) return 0;
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        if (text[i] == NULL || o->unit == CLI_UNIT_NONE || o->unit >= CLI_UNIT_SET_LENGTH)
            continue;
        const char *suffix = "";
        if (o->type == CLI_DOUBLE) suffix = cli_suffix_name(text[i]);
        else if (o->type == CLI_DOUBLE_LIST)
            for (int k = 0; k < ((const cli_double_list *)o->value)->n && !suffix[0]; k++)
                suffix = ((const cli_double_list *)o->value)->suffix[k];
        if (suffix[0] == '\0') continue;
        const int mass = o->unit == CLI_UNIT_MASS;
        if (!has_units)
            return cli_error(cmd, "%s %s: this command takes %s as a number in units of %s, "
                             "without a unit", o->name, text[i], o->meta,
                             cli_units_name(&(cli_units)CLI_UNITS_INIT, o->unit));
        return cli_error(cmd, "%s %s needs the chain's %s: give %s (SI units), or %s as a "
                         "number in units of %s", o->name, text[i], mass ? "mass" : "length",
                         mass ? "--mass" : "--length", o->meta,
                         cli_units_name(&(cli_units)CLI_UNITS_INIT, o->unit));
    }
    return 0;
}

/* A chain's length or mass written as a bare number that is unlikely as meant: --length 60 is
 * 60 m, --mass 0.0005 is half a gram (a hand-held chain is 0.1-10 m long and weighs grams to
 * kilograms: the bounds below). A note, not an error: a 60 m cable is a chain too. */
#define CLI_PLAUSIBLE_LENGTH_MAX 10.0 /* [m] */
#define CLI_PLAUSIBLE_MASS_MIN 1e-3   /* [kg], a gram */
static void note_implausible(const cli_command *cmd, const cli_option *opts, size_t nopts,
                             const char *const *text)
{
    for (size_t i = 0; i < nopts; i++) {
        const cli_option *o = &opts[i];
        if (text[i] == NULL || cli_suffix_name(text[i])[0] != '\0' ||
            (o->unit != CLI_UNIT_SET_LENGTH && o->unit != CLI_UNIT_SET_MASS))
            continue;
        const double v = *(const double *)o->value; /* (a double: a unit option's value) */
        if (o->unit == CLI_UNIT_SET_LENGTH && v > CLI_PLAUSIBLE_LENGTH_MAX)
            fprintf(stderr, "whirl %s: note: %s %s is %g m, longer than 10 m (write the unit if "
                    "you meant otherwise: %gcm, %gmm)\n", cmd->name, o->name, text[i], v, v, v);
        if (o->unit == CLI_UNIT_SET_MASS && v < CLI_PLAUSIBLE_MASS_MIN)
            fprintf(stderr, "whirl %s: note: %s %s is %g kg (%g g), lighter than a gram (write "
                    "the unit if you meant otherwise: 50g, 2kg)\n", cmd->name, o->name, text[i],
                    v, v * 1e3);
    }
}

/* "unexpected argument 'm.csv' (did you mean --shape m.csv?)": a file where the command reads
 * one through an option (the first option that reads a FILE). */
static int unexpected_argument(const cli_command *cmd, const cli_option *opts, size_t nopts,
                               const char *arg)
{
    for (size_t i = 0; i < nopts; i++)
        if (opts[i].input && opts[i].type == CLI_STRING && strcmp(opts[i].meta, "FILE") == 0)
            return cli_error(cmd, "unexpected argument '%s' (did you mean %s %s?)", arg,
                             opts[i].name, arg);
    return cli_error(cmd, "unexpected argument '%s' (see --help)", arg);
}

/* "unknown option '--omgea' (did you mean --omega? see --help)". */
static int unknown_option(const cli_command *cmd, const cli_option *opts, size_t nopts,
                          const char *arg, size_t len)
{
    const cli_option *best = NULL;
    size_t best_d = (size_t)-1;
    for (size_t i = 0; i < nopts; i++) {
        const size_t d = cli_edit_distance(arg, len, opts[i].name);
        if (d < best_d) best_d = d, best = &opts[i];
    }
    if (best && best_d <= 2 && best_d < len / 2)
        return cli_error(cmd, "unknown option '%.*s' (did you mean %s? see --help)", (int)len,
                         arg, best->name);
    return cli_error(cmd, "unknown option '%.*s' (see --help)", (int)len, arg);
}

/* The command's units (the --length option's value is their first member, length), told that
 * a rate was given in Hz. */
static void note_rate_hz(const cli_option *opts, size_t nopts)
{
    _Static_assert(offsetof(cli_units, length) == 0, "--length's value locates its cli_units");
    for (size_t i = 0; i < nopts; i++)
        if (opts[i].unit == CLI_UNIT_SET_LENGTH) ((cli_units *)opts[i].value)->rate_hz = 1;
}

#define CLI_MAX_OPTIONS 256

int cli_parse(const cli_command *cmd, int argc, char **argv, const cli_option *opts, size_t nopts,
              const char **positional, size_t npos)
{
    size_t npos_seen = 0;
    char given[CLI_MAX_OPTIONS] = {0};
    const char *text_of[CLI_MAX_OPTIONS] = {0}; /* the text of each value given */
    if (nopts > CLI_MAX_OPTIONS) return cli_error(cmd, "too many options in the table");
    for (size_t k = 0; k < npos; k++) positional[k] = NULL;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            print_help(cmd, opts, nopts);
            return 2;
        }
        if (arg[0] != '-' || strcmp(arg, "-") == 0) {
            if (npos_seen == npos) return unexpected_argument(cmd, opts, nopts, arg);
            positional[npos_seen++] = arg;
            continue;
        }
        /* --name=value or --name value */
        const char *eq = strchr(arg, '=');
        size_t name_len = eq ? (size_t)(eq - arg) : strlen(arg);
        const cli_option *o = find_option(opts, nopts, arg, name_len);
        if (o == NULL) return unknown_option(cmd, opts, nopts, arg, name_len);
        if (given[o - opts]) /* -o a -o b: which one was meant? */
            return cli_error(cmd, "option %s given twice", o->name);
        given[o - opts] = 1;
        if (o->given) *o->given = 1;
        if (o->type == CLI_FLAG) {
            if (eq) return cli_error(cmd, "option %s takes no value", o->name);
            *(int *)o->value = 1;
            continue;
        }
        const char *text = eq ? eq + 1 : (i + 1 < argc ? argv[++i] : NULL);
        if (text == NULL) return cli_error(cmd, "option %s needs a value (%s)", o->name, o->meta);
        char words[96];
        text_of[o - opts] = text;
        if (parse_value(o, text) != 0)
            return cli_error(cmd, "option %s needs %s, got '%s'", o->name,
                             type_words(o, words, sizeof words), text);
        /* "Hz" can only be the suffix of a rate (or of one of a list) */
        if ((o->type == CLI_DOUBLE || o->type == CLI_DOUBLE_LIST) && o->unit == CLI_UNIT_RATE &&
            strstr(text, "Hz"))
            note_rate_hz(opts, nopts);
    }
    /* the units before they are used */
    if (check_ranges(cmd, opts, nopts, given, 1)) return 1;
    const cli_units u = given_units(opts, nopts);
    if (cli_units_check(cmd, &u)) return 1;
    if (check_suffixes(cmd, opts, nopts, text_of)) return 1;
    note_implausible(cmd, opts, nopts, text_of);
    convert_units(opts, nopts, given);
    if (check_table(cmd, opts, nopts, given)) return 1;
    return cli_check_options_files(cmd, opts, nopts, given, positional, npos_seen);
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

double cli_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_begin(cli_progress_state *p, const cli_command *cmd, const char *label,
                        long total, long already)
{
    p->cmd = cmd;
    p->label = label;
    p->total = total;
    p->already = already;
    p->start = cli_wall_seconds();
    p->shown = -HUGE_VAL;
    p->tty = isatty(STDERR_FILENO);
    p->drawn = 0;
}

/* "1h02m", "3m05s", "12s". */
static void duration_words(double seconds, char *buf, size_t size)
{
    long s = seconds > 0 && seconds < 1e9 ? (long)(seconds + 0.5) : 0;
    if (s >= 3600) snprintf(buf, size, "%ldh%02ldm", s / 3600, s / 60 % 60);
    else if (s >= 60) snprintf(buf, size, "%ldm%02lds", s / 60, s % 60);
    else snprintf(buf, size, "%lds", s);
}

/* Draws "whirl CMD: TEXT" over the line (a newline after it when final). */
static void progress_draw(cli_progress_state *p, const char *text, int final)
{
    fprintf(stderr, "\rwhirl %s: %s\033[K", p->cmd->name, text);
    if (final) fputc('\n', stderr);
    fflush(stderr);
    p->drawn = !final;
}

void cli_progress_update(cli_progress_state *p, long done, int final)
{
    const double now = cli_wall_seconds();
    if (!p->tty || (!final && now - p->shown < 0.2)) return;
    p->shown = now;
    char elapsed[32], left[48] = "", text[512];
    duration_words(now - p->start, elapsed, sizeof elapsed);
    const long run_done = done - p->already;
    if (!final && run_done > 0 && done < p->total) {
        char eta[32];
        duration_words((now - p->start) / (double)run_done * (double)(p->total - done), eta,
                       sizeof eta);
        snprintf(left, sizeof left, ", about %s left", eta);
    }
    snprintf(text, sizeof text, "%s %ld/%ld (%.0f%%), %s elapsed%s", p->label, done, p->total,
             p->total > 0 ? 100.0 * (double)done / (double)p->total : 100.0, elapsed, left);
    progress_draw(p, text, final);
}

void cli_progress_text(cli_progress_state *p, const char *fmt, ...)
{
    const double now = cli_wall_seconds();
    if (!p->tty || now - p->shown < 0.2) return;
    p->shown = now;
    char elapsed[32], text[512];
    duration_words(now - p->start, elapsed, sizeof elapsed);
    va_list ap;
    va_start(ap, fmt);
    int len = vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (len >= 0 && (size_t)len < sizeof text)
        snprintf(text + len, sizeof text - (size_t)len, ", %s elapsed", elapsed);
    progress_draw(p, text, 0);
}

void cli_progress_clear(cli_progress_state *p)
{
    if (!p->drawn) return;
    fputs("\r\033[K", stderr);
    fflush(stderr);
    p->drawn = 0;
}

double cli_progress_after(void)
{
    const char *env = getenv("WHIRL_PROGRESS_AFTER");
    char *end = NULL;
    const double after = env ? strtod(env, &end) : 1;
    return env && end != env && *end == '\0' && after >= 0 && after <= 3600 ? after : 1;
}

/* The library's messages in the user's units: the library types the rates and lengths of its
 * messages (whirl_last_error_in_units), so nothing here reads their text. */
const char *cli_library_error(const cli_units *u, char *buf, size_t size)
{
    return whirl_last_error_in_units(buf, size, u->physical, u->length, u->mass, u->gravity,
                                     u->rate_hz);
}
