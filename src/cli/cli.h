/* The whirl program: shared command-line plumbing (options, errors, atomic output, units). */
#ifndef WHIRL_CLI_H
#define WHIRL_CLI_H

#include <signal.h>
#include <stddef.h>
#include <stdio.h>

#include "whirl/common.h"

/* ---- options ---- */
typedef enum {
    CLI_DOUBLE,   /* finite double */
    CLI_INT,      /* int */
    CLI_STRING,   /* const char * (points into argv) */
    CLI_INT_LIST, /* comma list of ints into a cli_int_list */
    CLI_FLAG      /* int set to 1, takes no value */
} cli_type;

#define CLI_LIST_MAX 64
typedef struct cli_int_list {
    int n;
    int v[CLI_LIST_MAX];
} cli_int_list;

typedef struct cli_option {
    const char *name;  /* "--omega" */
    const char *alias; /* "-o" or NULL */
    cli_type type;
    void *value;       /* where the parsed value goes */
    int *given;        /* set to 1 when the option appears (may be NULL) */
    const char *meta;  /* value's name in the help, e.g. "W" */
    const char *help;  /* one line */
} cli_option;

typedef struct cli_command {
    const char *name;     /* "shape" */
    const char *synopsis; /* "--omega W --mode K [--links N] ..." */
    const char *summary;  /* one sentence */
    int (*run)(const struct cli_command *cmd, int argc, char **argv);
} cli_command;

/* Parses argv[1..argc-1] (argv[0] is the command name) into opts[0..nopts-1]. Positional
 * arguments go to positional[0..npos-1] (NULL if absent; more than npos is an error). Returns
 * 0 on success, 1 after printing a one-line error, 2 after printing the help (--help). */
int cli_parse(const cli_command *cmd, int argc, char **argv, const cli_option *opts, size_t nopts,
              const char **positional, size_t npos);

/* Prints "whirl CMD: message" on one line to stderr and returns 1 (the exit status). */
int cli_error(const cli_command *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- output written atomically: a temporary file beside the target, renamed at the end ---- */
typedef struct cli_out {
    FILE *fp;   /* where to write */
    char *path; /* final path, NULL for stdout */
    char *tmp;  /* temporary path while open */
} cli_out;

/* Opens path (NULL or "-": standard output). Returns 0, or 1 after printing an error. */
int cli_out_open(const cli_command *cmd, cli_out *out, const char *path);
/* Flushes, closes and renames into place. Returns 0, or 1 after printing an error (and removing
 * the temporary file). */
int cli_out_commit(const cli_command *cmd, cli_out *out);
/* Removes the temporary file: nothing is left behind. */
void cli_out_abort(cli_out *out);

/* ---- units: dimensionless by default (L = M = g = 1) ---- */
typedef struct cli_units {
    double length;  /* L [m], --length */
    double mass;    /* M [kg], --mass */
    double gravity; /* g [m/s^2], --gravity */
} cli_units;
#define CLI_UNITS_OPTIONS(u)                                                                    \
    {"--length", NULL, CLI_DOUBLE, &(u).length, NULL, "L", "chain length in metres (physical units)"}, \
    {"--mass", NULL, CLI_DOUBLE, &(u).mass, NULL, "M", "chain mass in kg (physical units)"},          \
    {"--gravity", NULL, CLI_DOUBLE, &(u).gravity, NULL, "G", "gravity in m/s^2 (physical units)"}
/* The range of each unit: wide enough for any physical chain, narrow enough that results (rates,
 * tensions, lengths of order 1e-100 to 1e100 in the dimensionless units) times the products of
 * units in them stay finite. */
#define CLI_UNIT_MIN 1e-30
#define CLI_UNIT_MAX 1e30
/* Checks the units (each in [CLI_UNIT_MIN, CLI_UNIT_MAX]). Returns 0, or 1 after printing an
 * error. */
int cli_units_check(const cli_command *cmd, const cli_units *u);
double cli_units_rate(const cli_units *u);    /* sqrt(g/L): one dimensionless rate in 1/s */
double cli_units_force(const cli_units *u);   /* M g */

/* ---- long runs ---- */
/* SIGINT/SIGTERM raise the library's stop request (whirl_stop_request) once
 * cli_catch_interrupts() ran: a long loop stops and keeps its output. */
#define cli_interrupted whirl_stop_requested()
#define CLI_EXIT_INTERRUPTED 130 /* exit status after SIGINT/SIGTERM (128 + SIGINT) */
void cli_catch_interrupts(void);
/* Progress on a terminal only: "whirl CMD: label 42%" rewritten in place; done != 0 ends it. */
void cli_progress(const cli_command *cmd, const char *label, double fraction, int done);

/* ---- the commands ---- */
int cmd_critical(const cli_command *cmd, int argc, char **argv);
int cmd_shape(const cli_command *cmd, int argc, char **argv);
int cmd_sweep(const cli_command *cmd, int argc, char **argv);
int cmd_stability(const cli_command *cmd, int argc, char **argv);
int cmd_simulate(const cli_command *cmd, int argc, char **argv);
int cmd_minimize(const cli_command *cmd, int argc, char **argv);
int cmd_fit(const cli_command *cmd, int argc, char **argv);
int cmd_driven(const cli_command *cmd, int argc, char **argv);
int cmd_regime(const cli_command *cmd, int argc, char **argv);

#endif
