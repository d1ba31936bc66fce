/* whirl stability, as three files: cmd_stability.c (the options, the map and its rows, --resume),
 * stability_points.c (the points of the single rate or the map and the analysis of one point:
 * its linearisation and perturbed run), stability_eigen.c (--eigenvalues and --eigenvectors). */
#ifndef WHIRL_CLI_STABILITY_CLI_H
#define WHIRL_CLI_STABILITY_CLI_H

#include <stdio.h>

#include "cli/cli.h"
#include "cli/hand_cli.h"
#include "whirl/stability.h"

/* The options of whirl stability (cmd_stability.c's table). */
typedef struct stability_options {
    double omega, omega_min, omega_max, periods, perturb, damping, dt;
    int mode, links, steps, seed, linear, resume, links_given, eigenvalues, eigenvectors;
    int alias; /* --windows, --atlas: never parsed here (windows_alias), listed for the help */
    int omega_given, mode_given, min_given, max_given, steps_given, modes_given;
    cli_int_list modes;
    const char *method, *output, *trace;
    cli_units units;
    hand_cli hand; /* the hand-swung chain */
} stability_options;

/* A rate and mode: the single point (--omega) or one of the map. */
typedef struct stability_point {
    double omega, tip_r;
    const double *r, *z; /* free shapes: the nodes, from the branch's link angles (N + 1) */
    int mode;
    double eig_growth, sim_growth, max_deviation;
    double tip[2]; /* driven: the tip's horizontal position */
    int nodes;     /* driven: node count */
    whirl_verdict verdict;
    int linearised; /* free shapes: eig_growth known (whirl_stability_map) */
    int index;     /* negative directions of the amended potential (whirl_stability_index) */
    int done;
    int absent;    /* driven map: the mode has no shape at this rate */
} stability_point;

/* The points of the single rate or of the map (rates where the mode exists); *count of them,
 * their free shapes' nodes in *nodes (NULL for the hand-swung chain; the caller frees both).
 * Returns NULL after printing an error. */
stability_point *stability_cli_points(const cli_command *cmd, const stability_options *o,
                                      const whirl_chain *c, size_t *count, double **nodes);
/* The perturbed run of one point (unless --linear), and for the hand-swung chain its linear
 * analysis (that of the free shapes is whirl_stability_map's, before); trace: where the samples
 * of the run go (NULL: nowhere). A driven map point whose shape does not exist is marked absent.
 * A GSL status. */
int stability_cli_analyse(const stability_options *o, const whirl_chain *c, whirl_stability *w,
                          stability_point *p, FILE *trace);
/* --eigenvalues, --eigenvectors: every eigenvalue (and mode) of the linearisation at the one
 * rate. The exit status. */
int stability_cli_eigen(const cli_command *cmd, stability_options *o);

#endif
