/* The whirl program: shared command-line plumbing (options, errors, atomic output, units). */
#ifndef WHIRL_CLI_H
#define WHIRL_CLI_H

#include <signal.h>
#include <stddef.h>
#include <stdio.h>

#include "whirl/atlas.h"
#include "whirl/common.h"

/* ---- options ---- */
typedef enum {
    CLI_DOUBLE,   /* finite double */
    CLI_INT,      /* int */
    CLI_STRING,   /* const char * (points into argv) */
    CLI_INT_LIST, /* comma list of ints or ranges A-B into a cli_int_list */
    CLI_DOUBLE_LIST, /* comma list of finite doubles (each with the option's unit, converted like
                      * a CLI_DOUBLE) into a cli_double_list */
    CLI_FLAG      /* int set to 1, takes no value */
} cli_type;

#define CLI_LIST_MAX 64
typedef struct cli_int_list {
    int n;
    int v[CLI_LIST_MAX];
} cli_int_list;
typedef struct cli_double_list {
    int n;
    double v[CLI_LIST_MAX];
    const char *suffix[CLI_LIST_MAX]; /* the unit each entry was written in, as cli_suffix_name
                                       * gives it ("Hz", "rpm", "cm"), or "" for none */
} cli_double_list;

/* Physical kind of a double option, for units (see cli_units below). A value given on the
 * command line is converted to the library's dimensionless units right after parsing, so the
 * command sees dimensionless numbers; defaults are dimensionless already and left alone. */
typedef enum {
    CLI_UNIT_NONE = 0,  /* a pure number */
    CLI_UNIT_RATE,      /* 1/T: sqrt(g/L); rad/s with units; suffix Hz or rpm (e.g. 4Hz, 240rpm) */
    CLI_UNIT_LENGTH,    /* L; m with units (suffix cm, mm accepted) */
    CLI_UNIT_MASS,      /* M; kg with units (suffix g accepted) */
    CLI_UNIT_TIME,      /* sqrt(L/g); s with units (suffix ms accepted) */
    CLI_UNIT_FORCE,     /* M g; N with units */
    CLI_UNIT_DRAG,      /* linear drag per unit length, M sqrt(g/L) / L; kg/(m s) with units */
    CLI_UNIT_DRAG2,     /* quadratic drag per unit length, M / L^2; kg/m^2 with units */
    CLI_UNIT_DAMPING,   /* joint damping (Rayleigh), M L^2 sqrt(g/L); kg m^2/s with units */
    CLI_UNIT_SET_LENGTH,  /* the option that sets L [m] (--length; suffix cm, mm accepted) */
    CLI_UNIT_SET_MASS,    /* the option that sets M [kg] (--mass; suffix g accepted) */
    CLI_UNIT_SET_GRAVITY  /* the option that sets g [m/s^2] (--gravity) */
} cli_unit;

/* One option, written with designated initializers ({.name = "--omega", .type = CLI_DOUBLE,
 * .value = &o->omega, ..., .needs = "--mode"}), the fields left out zero. The first seven fields
 * are the parser's; the rest, zero when left out, declare
 * the checks cli_parse makes after reading the whole command line, in this order:
 *   required  NULL: optional; "": must be given; "--a --b": must be given unless one of the
 *             listed options is (an alternative form of the command);
 *   needs     options that must be given with this one ("--omega-max --omega-count");
 *   excludes  options that cannot be given with this one;
 *   range     the accepted values of an int, int list (each entry) or double, checked on the
 *             dimensionless value (after the unit conversion) when given (defaults are trusted):
 *             "(0, inf)", "[1, 64]", "[0, 1)"; an interval, ends "inf"/"-inf" allowed;
 *   unit      the physical kind of a double (CLI_UNIT_NONE: a pure number).
 * Option names in these lists are separated by spaces. Help and synopsis are generated from
 * the table (cli_parse --help): one line per option, "  NAME META  help [unit] (range)". */
typedef struct cli_option {
    const char *name;  /* "--omega" */
    const char *alias; /* "-o" or NULL */
    cli_type type;
    void *value;       /* where the parsed value goes */
    int *given;        /* set to 1 when the option appears (may be NULL) */
    const char *meta;  /* value's name in the help, e.g. "W" */
    const char *help;  /* one line */
    const char *range;    /* accepted values, e.g. "(0, inf)"; NULL: any */
    const char *needs;    /* options required with this one; NULL: none */
    const char *excludes; /* options not allowed with this one; NULL: none */
    const char *required; /* NULL: optional, "": required, "--x ...": required unless one given */
    cli_unit unit;        /* physical kind (doubles); CLI_UNIT_NONE: a number */
    int input;            /* a CLI_STRING with meta "FILE" names a file written (an output),
                             unless this is 1: a file read (see cli_check_files) */
} cli_option;

typedef struct cli_command {
    const char *name;     /* "shape" */
    const char *synopsis; /* NULL: generated from the option table; else used as given */
    const char *summary;  /* one sentence */
    int (*run)(const struct cli_command *cmd, int argc, char **argv);
    const char *example;  /* one command line shown by --help, e.g. "whirl shape --omega 3 ..." */
} cli_command;

/* Rate grids, the same in every command: --omega-min A --omega-max B --omega-count N are the N
 * equally spaced rates A, A + (B - A)/(N - 1), ..., B, both ends included (N = 1: A alone, and
 * then B must equal A); likewise --eps-min/--eps-max/--eps-count. cli_grid gives entry i. */
double cli_grid(double lo, double hi, int count, int i);

/* Parses argv[1..argc-1] (argv[0] is the command name) into opts[0..nopts-1], converts the
 * physical values to dimensionless ones and makes the table's checks (required, needs,
 * excludes, range; an option given twice is an error), then the checks of the files
 * (cli_check_files: the options with meta "FILE" are outputs unless marked input, the
 * positional arguments are inputs). Positional arguments go to positional[0..npos-1] (NULL if absent; more
 * than npos is an error). Returns 0 on success, 1 after printing a one-line error, 2 after
 * printing the help (--help). */
int cli_parse(const cli_command *cmd, int argc, char **argv, const cli_option *opts, size_t nopts,
              const char **positional, size_t npos);

/* The unit suffix ending a quantity's text, in its usual spelling: "4 hz" -> "Hz", "60CM" ->
 * "cm", "25.1rad/s" -> "rad/s"; "" if the text ends in no known suffix. */
const char *cli_suffix_name(const char *text);

/* Levenshtein distance between a[0..alen-1] and the string b (for "did you mean"). */
size_t cli_edit_distance(const char *a, size_t alen, const char *b);

/* Prints "whirl CMD: message" on one line to stderr and returns 1 (the exit status). Control
 * characters in the message (a newline, an escape sequence from a value of a file or option it
 * echoes) are written escaped, "\n", "\x1b" (cli_put_escaped): one line, and nothing that
 * drives the terminal. */
int cli_error(const cli_command *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Writes s to fp with its control characters (below 0x20, and 0x7f) escaped as \n, \r, \t
 * or \xNN. */
void cli_put_escaped(FILE *fp, const char *s);

/* ---- output written atomically: a temporary file beside the target, renamed at the end ----
 * (src/cli/outputs.c; docs/guide/files-and-signals.md) A symlink is written through: the
 * temporary file goes beside its target and replaces the target, with the target's mode and
 * owner. A device or FIFO is written in place; a FIFO with no reader is an error at once. */
typedef struct cli_out {
    FILE *fp;          /* where to write */
    char *path;        /* final path (a symlink's target), NULL for stdout or a device */
    char *tmp;         /* temporary path while open */
    const char *shown; /* the path as given, for messages (NULL: standard output) */
} cli_out;

/* Opens path (NULL or "-": standard output). Returns 0, or 1 after printing an error. */
int cli_out_open(const cli_command *cmd, cli_out *out, const char *path);
/* Flushes, closes and renames into place. Returns 0, or 1 after printing an error (and removing
 * the temporary file). */
int cli_out_commit(const cli_command *cmd, cli_out *out);
/* Commits the n outputs all or none: every one is flushed and closed first; if any fails,
 * none is renamed into place (all temporary files removed) and the error names it. */
int cli_out_commit_all(const cli_command *cmd, cli_out *const *outs, size_t n);
/* Removes the temporary file: nothing is left behind. */
void cli_out_abort(cli_out *out);

/* ---- the files of a command, checked before the work ----
 * A file named by an option or a scene, with what names it in messages ("--output", "[output]
 * trace"); path NULL or "-" is standard input or output. */
typedef struct cli_path {
    const char *what;
    const char *path;
} cli_path;
#define CLI_FILES_MAX 16
/* Refuses (1 after printing an error) an output that is empty, a directory, a dangling symlink,
 * a read-only file (mode without write permission, even for root) or in a folder that cannot be
 * written; two outputs that are the same file (same device and inode, or the same name in the
 * same folder when not yet written; devices apart); an output that is one of the inputs. */
int cli_check_files(const cli_command *cmd, const cli_path *outputs, size_t n_outputs,
                    const cli_path *inputs, size_t n_inputs);
/* cli_check_files on an option table after cli_parse (given[i]: option i appeared). */
int cli_check_options_files(const cli_command *cmd, const cli_option *opts, size_t nopts,
                            const char *given, const char *const *positional, size_t npos);
/* A map file written by one run at a time (flock on the file, released when the run ends
 * however it ends): taken from before the file is read until the run's last row. */
typedef struct cli_lock {
    FILE *fp;   /* the file locked, open for reading (a resumed map is read through it); NULL:
                 * no lock held */
    whirl_atlas_file *file; /* the library's lock (whirl/atlas.h); NULL: none held */
} cli_lock;
/* Locks the map file path: a regular file that exists, or with make (a run that starts the map
 * afresh) one that does not yet, made empty first (O_EXCL) so that two runs started together on
 * a new path are kept apart too; path NULL, "-" or a device: no lock, and a missing file without
 * make: no lock. 0, or 1 after the error "'PATH' is being written by another run (locked): wait
 * for it or write another file" (or that another run replaced it while this one started). */
int cli_lock_take(const cli_command *cmd, cli_lock *l, const char *path, int make);
/* Commits out, the map's new contents at l's path, with the map locked throughout: the lock
 * passes to the new file before it is renamed into place (no other run can take the map
 * between). 0, or 1 after an error (out aborted). */
int cli_lock_commit(const cli_command *cmd, cli_lock *l, cli_out *out);
/* Releases the lock; the empty file the run made is removed if the path still names it. */
void cli_lock_release(cli_lock *l);

/* ---- units: dimensionless by default (L = M = g = 1) ----
 * With any of --length, --mass, --gravity the command works in SI units: lengths in m, masses
 * in kg, times in s, rates in rad/s (or Hz, rpm with a suffix), forces in N; the ones not given
 * default to L = 1 m, M = 1 kg, g = 9.80665 m/s^2. Outputs then say so on a comment line
 *   # units: length=m mass=kg time=s rate=rad/s force=N L=0.6 M=0.05 g=9.81
 * and, dimensionless, on
 *   # units: dimensionless (length L, mass M, time sqrt(L/g), rate sqrt(g/L), force M g)
 * (cli_units_comment); plots/ read that line for their axis labels. */
typedef struct cli_units {
    double length;  /* L [m], --length (default 1) */
    double mass;    /* M [kg], --mass (default 1) */
    double gravity; /* g [m/s^2], --gravity (default 1; 9.80665 once a unit option is given) */
    int physical;   /* set by cli_parse: 1 if any of the three was given */
    int rate_hz;    /* set by cli_parse: 1 if a rate was given in Hz (the library's messages then
                     * give their rates in Hz) */
    int mass_given; /* --mass was given (else, in SI units, M = 1 kg is assumed and the units
                     * comment says so) */
} cli_units;
#define CLI_UNITS_INIT {1, 1, 1, 0, 0}
#define CLI_STANDARD_GRAVITY WHIRL_STANDARD_GRAVITY /* g when SI units are on and no --gravity */
#define CLI_UNITS_OPTIONS(u)                                                                   \
    {.name = "--length", .type = CLI_DOUBLE, .value = &(u).length, .given = &(u).physical,      \
     .meta = "L", .help = "chain length: switches to SI units (m; e.g. 0.6 or 60cm)",           \
     .range = "(0, inf)", .unit = CLI_UNIT_SET_LENGTH},                                         \
    {.name = "--mass", .type = CLI_DOUBLE, .value = &(u).mass, .given = &(u).mass_given,        \
     .meta = "M", .help = "chain mass: switches to SI units (kg; e.g. 0.05 or 50g)",            \
     .range = "(0, inf)", .unit = CLI_UNIT_SET_MASS},                                           \
    {.name = "--gravity", .type = CLI_DOUBLE, .value = &(u).gravity, .given = &(u).physical,    \
     .meta = "G", .help = "gravity: switches to SI units (m/s^2; default 9.80665 then)",        \
     .range = "(0, inf)", .unit = CLI_UNIT_SET_GRAVITY}
/* The range of each unit: wide enough for any physical chain, narrow enough that results (rates,
 * tensions, lengths of order 1e-100 to 1e100 in the dimensionless units) times the products of
 * units in them stay finite. */
#define CLI_UNIT_MIN 1e-30
#define CLI_UNIT_MAX 1e30
/* Checks the units (each in [CLI_UNIT_MIN, CLI_UNIT_MAX]); cli_parse calls it for the unit
 * options. Returns 0, or 1 after printing an error. */
int cli_units_check(const cli_command *cmd, const cli_units *u);
double cli_units_rate(const cli_units *u);    /* sqrt(g/L): one dimensionless rate in 1/s */
double cli_units_force(const cli_units *u);   /* M g */
/* The size of one dimensionless unit of the kind in the user's units (1 when dimensionless):
 * a dimensionless value times this is the value to print. */
double cli_units_scale(const cli_units *u, cli_unit kind);
/* The name of the user's unit of the kind: "m", "rad/s", ... or "L", "sqrt(g/L)", ... */
const char *cli_units_name(const cli_units *u, cli_unit kind);
/* A rate (dimensionless in) in words, short (4 significant digits): "25.13 rad/s (4 Hz)" in SI
 * units, "4.5 sqrt(g/L)" dimensionless; into buf (size bytes), returned. */
const char *cli_rate_words(const cli_units *u, double omega, char *buf, size_t size);
/* Writes the "# units: ..." comment line; in SI units without --mass, a second one:
 *   # mass: M=1 kg assumed (no --mass given); masses, forces and tensions scale with M */
void cli_units_comment(FILE *fp, const cli_units *u);
/* The library's last message (whirl_last_error) with its quantities in the user's units
 * (whirl_last_error_in_units), written into buf (size bytes); returns buf. CLI_LIBRARY_ERROR(u)
 * gives it in a buffer valid to the end of the enclosing block:
 * cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&units)). */
const char *cli_library_error(const cli_units *u, char *buf, size_t size);
#define CLI_MESSAGE_MAX 1024
#define CLI_LIBRARY_ERROR(u) cli_library_error((u), (char[CLI_MESSAGE_MAX]){0}, CLI_MESSAGE_MAX)

/* ---- the hand-swung chain: the pivot's circle and air drag, the same flags everywhere ----
 * --eps E (radius of the pivot's circle), --drag C (force -C v per unit length), --drag-quadratic
 * C2 (force -C2 |v| v per unit length), or C2 from a physical description: --drag-cd CD with
 * --diameter D [m] and --air-density RHO [kg/m^3, default 1.204: air at 20 C], for which
 * C2 = RHO CD D / 2 [kg/m^2] (the drag of a cylinder across the flow, per unit length); that
 * needs SI units (--length, --mass). The given pointers may be NULL. */
typedef struct cli_air {
    double cd;       /* drag coefficient, --drag-cd (0: not given) */
    double diameter; /* chain diameter [L] (given in m; converted by cli_parse), --diameter */
    double density;  /* air density [kg/m^3], --air-density (default 1.204) */
    const cli_units *units; /* the command's units, for the conversion of C2 */
} cli_air;
#define CLI_AIR_INIT(u) {0, 0, 1.204, &(u)}
#define CLI_DRAG_OPTIONS(eps, eps_given, drag, drag_given, drag2, drag2_given, air)             \
    {.name = "--eps", .type = CLI_DOUBLE, .value = &(eps), .given = eps_given, .meta = "E",     \
     .help = "radius of the pivot's circle (default 0)", .range = "[0, 1)",                     \
     .unit = CLI_UNIT_LENGTH},                                                                  \
    CLI_AIR_DRAG_OPTIONS(drag, drag_given, drag2, drag2_given, air)
/* The air drag's rows alone (a command whose pivot is not the circle's: whirl periodic). */
#define CLI_AIR_DRAG_OPTIONS(drag, drag_given, drag2, drag2_given, air)                         \
    {.name = "--drag", .type = CLI_DOUBLE, .value = &(drag), .given = drag_given, .meta = "C",  \
     .help = "linear air drag: force -C v per unit length (default 0)", .range = "[0, inf)",    \
     .unit = CLI_UNIT_DRAG},                                                                    \
    {.name = "--drag-quadratic", .type = CLI_DOUBLE, .value = &(drag2), .given = drag2_given,   \
     .meta = "C2", .help = "quadratic air drag: force -C2 |v| v per unit length (default 0)",   \
     .range = "[0, inf)", .excludes = "--drag-cd", .unit = CLI_UNIT_DRAG2},                     \
    {.name = "--drag-cd", .type = CLI_DOUBLE, .value = &(air).cd, .given = drag2_given,         \
     .meta = "CD", .help = "drag coefficient of the chain (about 1.2): C2 = RHO CD D / 2",      \
     .range = "(0, inf)", .needs = "--diameter --length --mass"},                               \
    {.name = "--diameter", .type = CLI_DOUBLE, .value = &(air).diameter, .meta = "D",           \
     .help = "chain diameter for --drag-cd (e.g. 4mm)", .range = "(0, inf)",                    \
     .needs = "--drag-cd", .unit = CLI_UNIT_LENGTH},                                            \
    {.name = "--air-density", .type = CLI_DOUBLE, .value = &(air).density, .meta = "RHO",       \
     .help = "air density for --drag-cd [kg/m^3] (default 1.204)", .range = "(0, inf)",         \
     .needs = "--drag-cd"}
/* ---- the pivot's path: --pivot PATH, one option row for whirl periodic and whirl simulate ----
 * The text of whirl_pivot_parse (whirl/periodic.h) at the command's rate (periodic: --omega;
 * simulate: the scene's [run] omega), lengths in the command's units (periodic: L, or m with
 * --length; simulate: the scene's, [units]); a unit suffix (cm, mm) only in SI units. The row:
 * CLI_PIVOT_OPTION(variable, words after "the pivot's path" in the help, required). */
#define CLI_PIVOT_GRAMMAR                                                                      \
    "circle:R, ellipse:A,B, line:A[,DX,DY,DZ], vertical:A, eight:A,B or fourier:x1c=A,z2s=B,..."
#define CLI_PIVOT_OPTION(var, tail, req)                                                       \
    {.name = "--pivot", .type = CLI_STRING, .value = &(var), .meta = "PATH",                   \
     .help = "the pivot's path" tail ": " CLI_PIVOT_GRAMMAR, .required = (req)}

/* The internal damping of the joints, D of whirl_model (the same row everywhere). */
#define CLI_DAMPING_OPTION(damping)                                                             \
    {.name = "--damping", .type = CLI_DOUBLE, .value = &(damping), .meta = "D",                 \
     .help = "internal damping of the joints (default 0)", .range = "[0, inf)",                 \
     .unit = CLI_UNIT_DAMPING}
/* With --drag-cd given, sets *drag2 (dimensionless) from the description. Returns 0. */
int cli_drag_apply(const cli_command *cmd, const cli_air *air, double *drag2);

/* ---- traces: every mass's position over time (plots/animate.gp, whirl view) ----
 * Blocks "x y z t" (the pivot, then masses 1..N), in the inertial frame, one per time, blocks
 * separated by two blank lines, each after a "# t = T" line. The file opens with
 *   # trace: WHAT; inertial frame ...; omega=W eps=E drag=C drag_quadratic=C2 links=N
 * and the "# units:" line; cli_trace_header writes both (values dimensionless in, printed in
 * the user's units). A pivot on a path (pivot: its text, no spaces, as the CSV's "# pivot ="
 * line) is named instead of the circle drive: "pivot=fourier:x1c=0.1,y1s=0.06" in place of
 * "eps=E" (readers of eps take the pivot for one that draws no circle). */
void cli_trace_header(FILE *fp, const cli_units *u, const char *what, double omega, double eps,
                      const char *pivot, double drag, double drag2, int links);

/* ---- numbers in text and CSV: the shortest round-trip form (whirl_format_double) ----
 * CLI_NUM(x) is a string valid to the end of the enclosing full expression's block, for use as
 * a "%s" argument: fprintf(fp, "%s,%s\n", CLI_NUM(a), CLI_NUM(b)). */
#define CLI_NUM(x) whirl_format_double((char[WHIRL_FORMAT_MAX]){0}, (x))
/* Writes x (shortest round-trip form) to fp. */
void cli_put_num(FILE *fp, double x);

/* ---- long runs ---- */
/* SIGINT, SIGTERM, SIGQUIT, SIGHUP, SIGPIPE and SIGXFSZ raise the library's stop request
 * (whirl_stop_catch_signals) once cli_catch_interrupts() ran: a long loop stops and keeps its
 * output. */
#define cli_interrupted whirl_stop_requested()
#define CLI_EXIT_INTERRUPTED 130 /* a command's status after a stop (128 + SIGINT) */
void cli_catch_interrupts(void);
/* The program's exit status for a command's status rc: after a stop raised by a signal, a
 * failure (rc 1 or CLI_EXIT_INTERRUPTED) exits 128 + the signal's number (SIGINT 130, SIGTERM
 * 143, SIGHUP 129, SIGQUIT 131, SIGPIPE 141, SIGXFSZ 153), as a shell reports a process killed by
 * it; otherwise rc. */
int cli_exit_status(int rc);
/* Progress of a long loop over a known number of items, on a terminal only:
 *   whirl CMD: points 42/120 (35%), 1m02s elapsed, about 1m55s left
 * rewritten in place, at most every 0.2 s; the estimate comes from the items done in this run
 * (already: items done before it, say from a resumed file, counted but not timed). */
typedef struct cli_progress_state {
    const cli_command *cmd;
    const char *label; /* "points" */
    long total;        /* items in all */
    long already;      /* items done before this run started */
    double start;      /* wall clock at cli_progress_begin [s] */
    double shown;      /* wall clock of the last line [s] */
    int tty;           /* standard error is a terminal */
    int drawn;         /* a line is on the terminal, not ended */
} cli_progress_state;
void cli_progress_begin(cli_progress_state *p, const cli_command *cmd, const char *label,
                        long total, long already);
/* done: items done so far, including the already ones; final != 0 prints the last line and a
 * newline. */
void cli_progress_update(cli_progress_state *p, long done, int final);
/* The line with free text where no count of items measures the work: "whirl CMD: TEXT, 12s
 * elapsed" (TEXT from the printf format), rewritten in place at most every 0.2 s, on a terminal
 * only; cli_progress_clear ends it. (begin's label, total and already are not used.) */
void cli_progress_text(cli_progress_state *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Erases the line if one is drawn, leaving the cursor at the start of the empty line. */
void cli_progress_clear(cli_progress_state *p);
/* How long a run goes before a progress line that waits shows [s]: 1, or the environment's
 * WHIRL_PROGRESS_AFTER (a number in [0, 3600]; 0 shows the line from the first report, for
 * scripts and tests; anything else keeps 1). */
double cli_progress_after(void);
/* Seconds on the monotonic clock. */
double cli_wall_seconds(void);

/* ---- the commands ---- */
int cmd_critical(const cli_command *cmd, int argc, char **argv);
int cmd_shape(const cli_command *cmd, int argc, char **argv);
int cmd_equilibria(const cli_command *cmd, int argc, char **argv);
int cmd_sweep(const cli_command *cmd, int argc, char **argv);
int cmd_stability(const cli_command *cmd, int argc, char **argv);
int cmd_windows(const cli_command *cmd, int argc, char **argv);
int cmd_simulate(const cli_command *cmd, int argc, char **argv);
int cmd_minimize(const cli_command *cmd, int argc, char **argv);
int cmd_fit(const cli_command *cmd, int argc, char **argv);
int cmd_driven(const cli_command *cmd, int argc, char **argv);
int cmd_plot(const cli_command *cmd, int argc, char **argv);
int cmd_regime(const cli_command *cmd, int argc, char **argv);
int cmd_view(const cli_command *cmd, int argc, char **argv);
int cmd_periodic(const cli_command *cmd, int argc, char **argv);

#endif
