/* whirl: the command-line program. One subcommand per job; `whirl CMD --help` explains each. */
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "cli/cli.h"

static const cli_command commands[] = {
    {"critical", "[--modes K] [--links N] [--tip-mass m] [-o FILE]",
     "Linear critical rates where modes 1..K bifurcate from the hanging chain.", cmd_critical},
    {"shape", "--omega W --mode K [--links N] [--tip-mass m] [--points P] [-o FILE]",
     "The steady shape of mode K at rotation rate W.", cmd_shape},
    {"sweep", "--modes LIST --omega-min A --omega-max B --steps S [--links N] [--tip-mass m] [-o FILE]",
     "Branches of steady shapes against the rotation rate, by continuation.", cmd_sweep},
    {"stability", "--omega W --mode K | --omega-min A --omega-max B --steps S [--modes LIST] [--links N] [--periods P] [--perturb EPS] [--seed S] [--damping D] [--eps E] [--drag C] [--drag-quadratic C2] [--side S] [--method M] [--dt H] [--linear] [--trace FILE] [-o FILE]",
     "Linear stability of the steady shapes, checked by perturbed runs.", cmd_stability},
    {"simulate", "SCENE [-o FILE] [--set SECTION.KEY=VALUE ...]",
     "Runs a scene file (see data/scenes/): the N-link chain in time.", cmd_simulate},
    {"minimize", "--omega W --links N [--tip-mass m] [--algorithm NAME] [--no-polish] [-o FILE]",
     "The mode-1 shape as the minimum of the co-rotating potential (NLopt).", cmd_minimize},
    {"fit", "--shape FILE [--links N] [--mode K] [--length L] [--gravity G] [-o FILE]",
     "The rotation rate and mode that best explain a measured shape (NLopt).", cmd_fit},
    {"driven", "--omega W | --omega-min A --omega-max B [--mode K] [--side S] [--eps E] [--drag C] [--drag-quadratic C2] [--links N] [--tip-mass m] [--points P] [--step H] [-o FILE]",
     "Steady shapes with the pivot driven on a circle and air drag; branches with folds.", cmd_driven},
    {"regime", "--omega W --eps E | --omega-min A --omega-max B --omega-steps n [--eps E | --eps-min --eps-max --eps-steps m] [--sweep] [--drag C] [--drag-quadratic C2] [--links N] [--t-max T] [--resume] [--folds FILE] [-o FILE]",
     "Which node count a chain swung by hand settles into from rest: one run, a map, hysteresis.", cmd_regime},
};
static const size_t n_commands = sizeof commands / sizeof commands[0];

static void usage(FILE *fp)
{
    fprintf(fp, "usage: whirl COMMAND [OPTIONS]   (whirl COMMAND --help for its options)\n\n"
                "whirl computes the steady shapes, dynamics and stability of a chain spun about\n"
                "the vertical axis. Dimensionless units: L = M = g = 1.\n\ncommands:\n");
    for (size_t i = 0; i < n_commands; i++)
        fprintf(fp, "  %-10s %s\n", commands[i].name, commands[i].summary);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2) {
        usage(stderr);
        return 1;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < n_commands; i++)
        if (strcmp(argv[1], commands[i].name) == 0) {
            int rc = commands[i].run(&commands[i], argc - 1, argv + 1);
            return rc == 2 ? 0 : rc; /* 2: help was printed */
        }
    fprintf(stderr, "whirl: unknown command '%s' (whirl --help lists them)\n", argv[1]);
    return 1;
}
