/* whirl: the command-line program. One subcommand per job; `whirl CMD --help` explains each. */
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "cli/cli.h"
#include "datadir.h" /* WHIRL_DATADIR: where make install puts the scenes (BUILD/gen) */
#include "whirl/version.h"

/* Synopses are generated from each command's option table (cli_parse --help). */
static const cli_command commands[] = {
    {"critical", NULL,
     "Linear critical rates where modes 1..K bifurcate from the hanging chain.", cmd_critical,
     "whirl critical --modes 4 --length 0.6 --mass 0.05"},
    {"shape", NULL, "The steady shape of mode K at rotation rate W.", cmd_shape,
     "whirl shape --omega 4Hz --mode 2 --length 0.6 -o shape.csv"},
    {"equilibria", NULL,
     "Every planar steady shape at rotation rate W: node count, branch, linear verdict.",
     cmd_equilibria, "whirl equilibria --omega 11.62 --links 5 -o equilibria.csv"},
    {"sweep", NULL, "Branches of steady shapes against the rotation rate, by continuation.",
     cmd_sweep, "whirl sweep --modes 1,2,3 --omega-min 0.5 --omega-max 8 --omega-count 151"},
    {"stability", "--omega W --mode K | --omega-min A --omega-max B --omega-count N [--modes LIST] [OPTIONS]",
     "Linear stability of the steady shapes, checked by perturbed runs.", cmd_stability,
     "whirl stability --omega-min 1 --omega-max 8 --omega-count 29 --links 20 --linear -o map.csv"},
    {"windows",
     "--omega-min A --omega-max B [--modes LIST] [--links N] [OPTIONS] | --atlas [--modes LIST] "
     "[--omega-max B] -o FILE [--resume]",
     "Intervals of omega where each mode is unstable, edges located exactly; the atlas.",
     cmd_windows, "whirl windows --omega-min 1 --omega-max 10 --modes 2,3 -o windows.csv"},
    {"simulate", "SCENE [-o FILE] [--set SECTION.KEY=VALUE ...] [--pivot PATH]",
     "Runs a scene file (examples in " WHIRL_DATADIR "/scenes, data/scenes in the source): "
     "the N-link chain in time.", cmd_simulate,
     "whirl simulate " WHIRL_DATADIR "/scenes/mode2.ini --set run.t_end=20 -o run.csv"},
    {"minimize", NULL,
     "The mode-1 shape as the minimum of the co-rotating potential (NLopt).", cmd_minimize,
     "whirl minimize --omega 3 --links 40 -o min.csv"},
    {"fit", NULL, "The rotation rate and mode that best explain a measured shape (NLopt).",
     cmd_fit, "whirl fit --shape " WHIRL_DATADIR "/fit_example.csv --shape-unit cm --length 120cm"},
    {"driven", "--omega W | --omega-min A --omega-max B [--mode K] [OPTIONS]",
     "Steady shapes with the pivot driven on a circle and air drag; branches with folds.",
     cmd_driven, "whirl driven --omega-min 1 --omega-max 6 --mode 2 --eps 0.05 --drag-quadratic 0.015"},
    {"regime", "--omega W --eps E | --omega-min A --omega-max B --omega-count N (--eps E | --eps-min C --eps-max D --eps-count M) [OPTIONS]",
     "Which node count a chain swung by hand settles into from rest: one run, a map, hysteresis.",
     cmd_regime, "whirl regime --omega 4Hz --eps 3cm --length 0.5 --mass 50g --drag-quadratic 0.0029"},
    {"periodic",
     "--pivot PATH --omega W | --pivot PATH (--omega-min A --omega-max B | --amp-max B) | "
     "--chart KIND --omega-min A --omega-max B --amp-max B [OPTIONS]",
     "The periodic motion with the pivot on a periodic path and its Floquet multipliers; "
     "branches with their folds, period doublings and tori; charts.",
     cmd_periodic, "whirl periodic --pivot vertical:0.1 --omega 2 --links 1 --dim 2"},
    {"plot", "FILE... -o PICTURE",
     "A figure (PNG, SVG, PDF) of whirl's CSV files, or a trace's animation (MP4, WebM, GIF).",
     cmd_plot, "whirl plot s2.csv s4.csv s6.csv -o shapes.png"},
    {"view", "TRACE | SHAPE... [--camera AZ,EL] [--omega W] [--eps E] [-o FILE]",
     "One self-contained HTML page showing a trace or shapes in 3D (rotatable, animated).",
     cmd_view, "whirl view run.dat -o run.html"},
};
static const size_t n_commands = sizeof commands / sizeof commands[0];

static void usage(FILE *fp)
{
    fprintf(fp, "usage: whirl COMMAND [OPTIONS]   (whirl help COMMAND: its options)\n"
                "       whirl --version           (the program's and the library's version)\n\n"
                "whirl computes the steady shapes, dynamics and stability of a chain spun about\n"
                "the vertical axis. Units: dimensionless (L = M = g = 1) unless --length,\n"
                "--mass or --gravity is given, then SI, with units on values: 4Hz, 240rpm,\n"
                "60cm, 50g. Pictures: shape --plot, simulate --animate, plot, view.\n"
                "Rate grids: --omega-min A --omega-max B --omega-count N, N rates, both ends.\n\n"
                "commands:\n");
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
    /* whirl help CMD: CMD's help, as whirl CMD --help */
    char help_flag[] = "--help";
    char *help_argv[] = {argv[0], argc > 2 ? argv[2] : NULL, help_flag, NULL};
    if (strcmp(argv[1], "help") == 0 && argc > 2) {
        argc = 3;
        argv = help_argv;
    } else if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
               strcmp(argv[1], "help") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("whirl %s (library %s)\n", WHIRL_VERSION, whirl_version());
        return 0;
    }
    for (size_t i = 0; i < n_commands; i++)
        if (strcmp(argv[1], commands[i].name) == 0) {
            /* SIGINT, SIGTERM, SIGQUIT, SIGHUP (SIGPIPE and SIGXFSZ as write errors) raise the
             * stop request: every long loop ends soon after, the command keeps the rows it
             * has, removes its temporary files and fails; a failure after a stop request exits
             * with 128 + the signal's number (cli_exit_status) */
            cli_catch_interrupts();
            int rc = commands[i].run(&commands[i], argc - 1, argv + 1);
            return rc == 2 ? 0 : cli_exit_status(rc); /* 2: help was printed */
        }
    /* the nearest command's name, if within two edits; the name echoed with its control
     * characters escaped */
    size_t best = n_commands, best_d = (size_t)-1;
    for (size_t i = 0; i < n_commands; i++) {
        const size_t d = cli_edit_distance(argv[1], strlen(argv[1]), commands[i].name);
        if (d < best_d) best_d = d, best = i;
    }
    fputs("whirl: unknown command '", stderr);
    cli_put_escaped(stderr, argv[1]);
    if (best < n_commands && best_d <= 2 && best_d < strlen(argv[1]))
        fprintf(stderr, "' (did you mean %s? known:", commands[best].name);
    else
        fputs("' (known:", stderr);
    for (size_t i = 0; i < n_commands; i++) fprintf(stderr, " %s", commands[i].name);
    fputs(")\n", stderr);
    return 1;
}
