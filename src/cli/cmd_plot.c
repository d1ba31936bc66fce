/* whirl plot FILE... -o PICTURE: a figure (PNG, SVG, PDF) of whirl's own CSV files, or the
 * animation (MP4, WebM, GIF) of a trace, drawn by gnuplot with the scripts of plots/. The kind of
 * each file comes from its header line; files of different kinds or units are refused. */
#include "cli/figure.h"

int cmd_plot(const cli_command *cmd, int argc, char **argv)
{
    const char *out = NULL;
    const char *files[CLI_LIST_MAX];
    cli_figure_style style = {0};
    const cli_option opts[] = {
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &out, .meta = "PICTURE",
         .help = "the picture: .png, .svg or .pdf (a figure), .mp4, .webm or .gif (a trace's "
                 "animation)",
         .required = ""},
        CLI_FIGURE_OPTIONS(style),
        CLI_MOVIE_OPTIONS(style),
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, files, CLI_LIST_MAX);
    if (rc) return rc;
    size_t n = 0;
    while (n < CLI_LIST_MAX && files[n]) n++;
    if (n == 0) return cli_error(cmd, "missing the files to draw (see --help)");
    return cli_figure_draw(cmd, files, n, out, &style);
}
