/* whirl stability --windows with dissipation (stability_dissipative.c). */
#ifndef WHIRL_CLI_STABILITY_DISSIPATIVE_H
#define WHIRL_CLI_STABILITY_DISSIPATIVE_H

#include "cli/cli.h"
#include "whirl/stability.h"

/* The intervals where each mode of modes is unstable or converging for the N-link chain of
 * links links (tip_mass at the free end) with the dissipation of model (internal_damping, drive_radius, air_drag,
 * air_drag_quadratic; its chain is set here) and the hand-swung side, over the range of p,
 * into output. Returns the exit status. */
int stability_dissipative(const cli_command *cmd, const cli_int_list *modes, int links,
                          double tip_mass, const whirl_model *model, int side, const whirl_windows_params *p,
                          const cli_units *units, const char *output);

#endif
