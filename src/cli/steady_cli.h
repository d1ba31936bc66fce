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
/* Reports a failed solve at the dimensionless rate omega: for a mode that does not exist, the
 * line names its critical rate in the user's units. Returns 1. */
int steady_cli_solve_error(const cli_command *cmd, const steady_cli_model *m, int status,
                           int mode, double omega);

/* Writes a shape as `whirl shape` does: the summary comment line, a comment line on the columns,
 * the comment line extra (without '#' and newline; NULL for none), then CSV s,r,z,tension of the
 * n points, all converted to the user's units (the "# units:" line before the header). */
void steady_cli_write_shape(FILE *fp, const steady_cli_model *m, const whirl_shape_info *info,
                            size_t n, const double *s, const double *r, const double *z,
                            const double *tension, const char *extra);

#endif
