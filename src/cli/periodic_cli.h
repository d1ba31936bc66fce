/* whirl periodic's parts in other files: the chart of the vertically shaken chain
 * (periodic_chart.c) and the ellipticity chart (periodic_ellipse.c), their files and --resume
 * (chart_file.h). */
#ifndef WHIRL_CLI_PERIODIC_CLI_H
#define WHIRL_CLI_PERIODIC_CLI_H

#include "cli/cli.h"

typedef struct periodic_ellipse_args {
    int links, mode, side, columns, steps;
    double eps, omega_min, omega_max, e_max, arc_step; /* dimensionless */
    const char *output;
    const cli_units *units;
    int resume; /* --resume: keep the rates finished in output, compute the rest */
} periodic_ellipse_args;

typedef struct periodic_chart_args {
    int inverted, links, columns, rows, steps;
    double omega_min, omega_max, amp_min, amp_max, tol; /* dimensionless; 0: the defaults */
    double drag; /* --drag: linear air drag, dimensionless (whirl_chart_vertical_damped) */
    const char *output;
    const cli_units *units;
    int resume;
} periodic_chart_args;

/* whirl periodic --chart hanging|inverted: the chart written to output (or standard output);
 * the exit status. */
int periodic_chart_vertical(const cli_command *cmd, const periodic_chart_args *a);

/* whirl periodic --chart ellipse: the chart written to output (or standard output); the exit
 * status. */
int periodic_chart_ellipse(const cli_command *cmd, const periodic_ellipse_args *a);

#endif
