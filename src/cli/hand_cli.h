/* The whirl program: the hand-swung chain's options as whirl stability and whirl windows read
 * them (hand_cli.c): the pivot's circle and air drag (CLI_DRAG_OPTIONS, cli.h) and the side of
 * the seed's tip (--side), with their defaults and checks. */
#ifndef WHIRL_CLI_HAND_CLI_H
#define WHIRL_CLI_HAND_CLI_H

#include "cli/cli.h"

typedef struct hand_cli {
    double eps, drag, drag2; /* --eps, --drag, --drag-quadratic (or from --drag-cd) */
    int side;                /* --side: 1 (the pivot's side, default) or -1 */
    int eps_given, drag_given, drag2_given, side_given;
    cli_air air;             /* --drag-cd, --diameter, --air-density */
} hand_cli;

/* The options, for an option table: those of CLI_DRAG_OPTIONS, then --side. */
#define HAND_CLI_OPTIONS(h)                                                                     \
    CLI_DRAG_OPTIONS((h).eps, &(h).eps_given, (h).drag, &(h).drag_given, (h).drag2,             \
                     &(h).drag2_given, (h).air),                                                \
    {.name = "--side", .type = CLI_INT, .value = &(h).side, .given = &(h).side_given,           \
     .meta = "S",                                                                               \
     .help = "hand-swung: seed's tip on the pivot's side (1, default) or opposite (-1)"}

/* The defaults (no drive, no drag, side 1); units: the command's, for --drag-cd. */
void hand_cli_defaults(hand_cli *h, const cli_units *units);
/* cli_parse on the table, then --drag-cd applied (cli_drag_apply): 0, or the exit status. */
int hand_cli_parse(const cli_command *cmd, int argc, char **argv, const cli_option *opts,
                   size_t nopts, hand_cli *h);
/* 1 if any option of the hand-swung chain was given (--eps, the drag, --side). */
int hand_cli_given(const hand_cli *h);
/* What the table cannot say: the side is 1 or -1, and air drag needs the pivot off the axis.
 * 0, or 1 after an error. */
int hand_cli_check(const cli_command *cmd, const hand_cli *h);

#endif
