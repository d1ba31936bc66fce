/* The whirl program: what the steady-shape commands (critical, shape, sweep) share: the model
 * options (--links, --tip-mass, units), their checks and the unit conversions. */
#ifndef WHIRL_STEADY_CLI_H
#define WHIRL_STEADY_CLI_H

#include "cli/cli.h"
#include "whirl/steady.h"

typedef struct steady_cli_model {
    int links;        /* --links N: the N-link chain; 0: the continuum */
    int links_given;
    double tip_mass;  /* --tip-mass [M] (given in kg with units; converted by cli_parse) */
    cli_units units;  /* --length --mass --gravity */
    whirl_chain *chain; /* the N-link chain (dimensionless), NULL for the continuum */
} steady_cli_model;

#define STEADY_CLI_MODEL_INIT {0, 0, 0, CLI_UNITS_INIT, NULL}

/* The options of the model, for an option table. */
#define STEADY_CLI_MODEL_OPTIONS(m)                                                            \
    {"--links", NULL, CLI_INT, &(m).links, &(m).links_given, "N",                              \
     "the N-link chain of equal links and masses (default: the continuum, exact)", "[1, inf)",  \
     NULL, NULL, NULL, CLI_UNIT_NONE},                                                          \
    {"--tip-mass", NULL, CLI_DOUBLE, &(m).tip_mass, NULL, "m",                                 \
     "point mass at the free end (default 0)", "[0, inf)", NULL, NULL, NULL, CLI_UNIT_MASS},    \
    CLI_UNITS_OPTIONS((m).units)

/* Checks the options and allocates the chain; 0, or 1 after printing an error. */
int steady_cli_model_setup(const cli_command *cmd, steady_cli_model *m);
void steady_cli_model_free(steady_cli_model *m);
/* The tip mass in units of the chain's mass (cli_parse converted it). */
double steady_cli_tip_mass(const steady_cli_model *m);
/* 0 if the model has mode (the N-link chain: 1..N; the continuum: 1..WHIRL_CONTINUUM_MODE_MAX),
 * else 1 after printing an error naming the mode and the range. */
int steady_cli_check_mode(const cli_command *cmd, const steady_cli_model *m, int mode);
/* The linear critical rate of mode (dimensionless); 0, or 1 after printing an error. */
int steady_cli_critical(const cli_command *cmd, const steady_cli_model *m, int mode,
                        double *omega);
/* Reports a failed solve: the library's message in the user's units (a mode that does not exist
 * names its critical rate), and for an N-link branch stopped by the bound on its steps
 * (GSL_EMAXITER) the option that sets the bound. Returns 1. */
int steady_cli_solve_error(const cli_command *cmd, const steady_cli_model *m, int status);

/* ---- following an N-link branch from its birth (shape, sweep) ----
 * --max-steps S bounds the continuation steps of each branch (whirl_nlink_follow_options); on a
 * terminal, once the run has taken a second (the environment's WHIRL_PROGRESS_AFTER, in
 * seconds, if set: 0 shows it from the first step), a progress line shows where it stands:
 *   whirl shape: mode 100: omega 171.898 of 190 (now 167.295), 1024 steps (at most 200000),
 *   36 folds, 1s elapsed
 * (one line; rates in the command's units): the highest rate reached against the rate the
 * branch is followed to, the current one, the steps against their bound and the folds passed.
 * It gives no estimate of the time left: no figure of the run has a known total that the work
 * follows. The rate goes back and forth through the folds, and the highest rate stalls for
 * long stretches (N = 1000, mode 334 to omega 700: at 645.3 from step 25600 to 70400, a third
 * of the run, while the rate swings between 589 and 632: at a quarter of the run a linear
 * extrapolation of the highest rate gives 7 s left of 50); the steps go at a steady pace, but the
 * number a rate needs (120000 there) and the arclength to it are known only once it is
 * reached. The line is erased at the end: the output or the error says how the run ended. */
typedef struct steady_cli_follow {
    int max_steps;    /* --max-steps S; 0: the library's bound, max(100000, 200 N) */
    whirl_nlink_follow_options opt; /* what the library gets: the bound, the progress line */
    cli_progress_state line;
    const steady_cli_model *m;
    double target;    /* the rate the branches are followed to (dimensionless) */
    double after;     /* the line shows once the run has taken this long [s] (default 1) */
    int index, count; /* the mode being followed: its place in the list (from 1), the list's
                       * length */
} steady_cli_follow;

#define STEADY_CLI_FOLLOW_OPTIONS(f)                                                            \
    {"--max-steps", NULL, CLI_INT, &(f).max_steps, NULL, "S",                                   \
     "N-link chain: bound on the continuation steps from a birth, the run fails there "        \
     "(default max(100000, 200 N))", "[1, inf)", "--links", NULL, NULL, CLI_UNIT_NONE}

/* Sets f->opt for the model's chain and target (dimensionless) and starts the progress clock;
 * count: the modes to be followed. */
void steady_cli_follow_begin(steady_cli_follow *f, const cli_command *cmd,
                             const steady_cli_model *m, double target, int count);
/* Erases the progress line if it is shown. */
void steady_cli_follow_end(steady_cli_follow *f);

/* Writes a shape as `whirl shape` does: the summary comment line, a comment line on the columns,
 * the comment line extra (without '#' and newline; NULL for none), then CSV s,r,z,tension of the
 * n points, all converted to the user's units (the "# units:" line before the header). */
void steady_cli_write_shape(FILE *fp, const steady_cli_model *m, const whirl_shape_info *info,
                            size_t n, const double *s, const double *r, const double *z,
                            const double *tension, const char *extra);

#endif
