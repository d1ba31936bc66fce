/* whirl periodic's parts in other files: the ellipticity chart (periodic_ellipse.c). */
#ifndef WHIRL_CLI_PERIODIC_CLI_H
#define WHIRL_CLI_PERIODIC_CLI_H

#include "cli/cli.h"

typedef struct periodic_ellipse_args {
    int links, mode, side, columns, steps;
    double eps, omega_min, omega_max, e_max, arc_step; /* dimensionless */
    const char *output;
    const cli_units *units;
} periodic_ellipse_args;

/* whirl periodic --chart ellipse: the chart written to output (or standard output); the exit
 * status. */
int periodic_chart_ellipse(const cli_command *cmd, const periodic_ellipse_args *a);

#endif
