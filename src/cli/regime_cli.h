/* whirl regime: what the command's three files share, each calling only the ones after it.
 * cmd_regime.c: the options, one run and the hysteresis sweep; regime_map.c: the map, its file
 * (fresh or --resume) and the sharing of its points over OpenMP threads and MPI ranks;
 * regime_rows.c: the rows and header lines both write. */
#ifndef WHIRL_REGIME_CLI_H
#define WHIRL_REGIME_CLI_H

#include <stdio.h>

#include "cli/cli.h"
#include "whirl/regime.h"
#include "whirl/steady.h"

#define REGIME_MAX_LINKS 10000
#define REGIME_MAX_POINTS 10000000L
#define REGIME_LINE_MAX 4096
#define REGIME_MAP_FIELDS 18 /* columns of a map row */

/* The header of a map's rows. */
extern const char *const regime_cli_map_columns;

typedef struct regime_options {
    double omega, eps, omega_min, omega_max, eps_min, eps_max;
    int omega_steps, eps_steps, links;
    const char *frame, *output, *trace, *folds;
    double trace_every, t_change;
    int resume, sweep;
    cli_units units; /* the user's units (outputs converted back into them) */
    cli_air air;
    int omega_given, eps_given, omin_given, omax_given, osteps_given, emin_given, emax_given,
        esteps_given, trace_every_given, t_change_given, dt_given;
    whirl_regime_params p;
} regime_options;

typedef struct mpi_context {
    int rank, size;
} mpi_context;

/* ---- regime_rows.c ---- */
/* A dimensionless value of the kind in the user's units. */
double regime_cli_user(const regime_options *o, cli_unit kind, double x);
/* The map form (an omega range), a sweep included. */
int regime_cli_is_map(const regime_options *o);
/* The parameter line and the units line: a map written with other ones cannot be resumed. */
void regime_cli_write_parameters(FILE *fp, const regime_options *o);
/* The critical rates of the free N-link chain, for comparison with the map. */
void regime_cli_write_critical(FILE *fp, const regime_options *o, const whirl_chain *chain);
/* The class of a run's state for the heat map: the node count if settled or converging, 0
 * periodic, -1 quasi-periodic, -2 chaotic, -3 failed. */
int regime_cli_state_class(const whirl_regime_result *r);
/* The columns of a row from state on. */
void regime_cli_write_result(FILE *fp, const regime_options *o, const whirl_regime_result *r);
/* ---- regime_map.c ---- */
/* The map: -o FILE written as the points finish (fresh or --resume), shared over the threads
 * and, with MPI, the ranks; --folds after it. Returns 0, 1 after an error, 130 after Ctrl-C. */
int regime_cli_run_map(const cli_command *cmd, const regime_options *o, const whirl_chain *chain,
                       const mpi_context *mc);

#endif
