/* whirl stability --atlas (stability_atlas.c). */
#ifndef WHIRL_CLI_STABILITY_ATLAS_H
#define WHIRL_CLI_STABILITY_ATLAS_H

#include <stdio.h>

#include "cli/cli.h"

/* The atlas of the continuum's windows of the modes to omega_max into output (rewritten after
 * every chunk; resume: keep the chunks already in it). Returns the exit status. */
int stability_atlas(const cli_command *cmd, const cli_int_list *modes, double omega_max,
                    int degree, double memory_mb, double tol, double scan_step,
                    const char *output, int resume);

/* Reads in, the atlas file path, as --resume of these options would (every line checked,
 * resume.h): 0, or 1 after printing the one-line error. For the fuzzing of the reader. */
int stability_atlas_check(const cli_command *cmd, FILE *in, const char *path,
                          const cli_int_list *modes, double omega_max, int degree, double tol,
                          double scan_step);

/* status, or after a failure of the continuum's collocation beyond its memory bound
 * (GSL_EMAXITER asking to raise it) the same failure with the option that raises it named. */
int stability_memory_failure(int status);

#endif
