/* whirl shape: the steady shape of mode K at rotation rate W, as CSV s,r,z,tension from the
 * pivot to the free end, after a comment line summarising it. The N-link shape is the point of
 * the branch's continuation from its birth; on a terminal a progress line shows how far a long
 * one has come (the middle modes of long chains fold thousands of times; steady_cli.h), and
 * --max-steps bounds it. A continuation that fails (Ctrl-C, the step bound) leaves no output:
 * one line names the mode, the rate reached and why; exit status 130 after Ctrl-C, else 1.
 * A comma list of rates (and one mode, or one per rate) with --plot PICTURE draws every shape on
 * one figure (figure.h); a "# rate:" comment line gives each rate as the user wrote it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/figure.h"
#include "cli/steady_cli.h"

/* The comment line of the rate as the user gave it, which figures use for their labels:
 *   rate: 4 Hz (omega=25.13 rad/s)       (given in Hz)
 *   rate: 240 rpm (omega=25.13 rad/s, 4 Hz)
 *   rate: 25.13 rad/s (4 Hz)             (SI, given in rad/s)
 *   rate: omega = 4.5 sqrt(g/L)          (dimensionless)
 * with 4 significant digits. */
static void rate_line(char *buf, size_t size, const cli_units *u, double omega,
                      const char *suffix)
{
    const double w = omega * cli_units_rate(u), hz = w / 6.283185307179586; /* 2 pi */
    if (!u->physical) snprintf(buf, size, "rate: omega = %.4g sqrt(g/L)", omega);
    else if (strcmp(suffix, "Hz") == 0)
        snprintf(buf, size, "rate: %.4g Hz (omega=%.4g rad/s)", hz, w);
    else if (strcmp(suffix, "rpm") == 0)
        snprintf(buf, size, "rate: %.4g rpm (omega=%.4g rad/s, %.4g Hz)", 60 * hz, w, hz);
    else snprintf(buf, size, "rate: %.4g rad/s (%.4g Hz)", w, hz);
}

/* One shape, solved and written to path (NULL or "-": standard output). Returns the exit
 * status. */
static int one_shape(const cli_command *cmd, steady_cli_model *m, steady_cli_follow *follow,
                     double omega, const char *suffix, int mode, int points, const char *path)
{
    if (steady_cli_check_mode(cmd, m, mode)) return 1;
    double tip_mass = steady_cli_tip_mass(m);
    size_t n = m->chain ? m->chain->n + 1 : (size_t)points;
    double *s = malloc(4 * n * sizeof *s), *r = s + n, *z = r + n, *tension = z + n;
    if (s == NULL) return cli_error(cmd, "out of memory for %zu points", n);
    /* the N-link shape with its nodes from the branch's link angles */
    whirl_shape_info info;
    cli_catch_interrupts();
    steady_cli_follow_begin(follow, cmd, m, omega, 1);
    int status = m->chain ? whirl_nlink_solve_nodes_opt(m->chain, omega, mode, &info, r, z,
                                                        tension, &follow->opt)
                          : whirl_continuum_solve(omega, mode, tip_mass, 0, &info);
    steady_cli_follow_end(follow);
    if (status == WHIRL_EINTERRUPTED) {
        cli_error(cmd, "interrupted in mode %d: %s", mode, CLI_LIBRARY_ERROR(&m->units));
        free(s);
        return CLI_EXIT_INTERRUPTED;
    }
    if (status != GSL_SUCCESS) {
        steady_cli_solve_error(cmd, m, status);
        free(s);
        return 1;
    }
    if (m->chain) {
        s[0] = 0;
        for (size_t i = 1; i < n; i++) s[i] = s[i - 1] + m->chain->length[i - 1];
    } else {
        status = whirl_continuum_sample(omega, tip_mass, info.tip_r, n, s, r, z, tension);
    }
    cli_out out;
    int rc;
    char rate[160];
    rate_line(rate, sizeof rate, &m->units, omega, suffix);
    cli_progress_state progress;
    cli_progress_begin(&progress, cmd, "", 0, 0);
    if (n > 100000) cli_progress_text(&progress, "sampling and writing %zu points", n);
    if (status == WHIRL_EINTERRUPTED)
        rc = cli_error(cmd, "interrupted sampling the shape: %s", CLI_LIBRARY_ERROR(&m->units));
    else if (status != GSL_SUCCESS) rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m->units));
    else rc = cli_out_open(cmd, &out, path);
    if (rc == 0) {
        steady_cli_write_shape(out.fp, m, &info, n, s, r, z, tension, rate);
        if (cli_interrupted) { /* a shape cut short is no shape: nothing is kept */
            cli_out_abort(&out);
            rc = cli_error(cmd, "interrupted while writing %zu points: nothing written", n);
        } else rc = cli_out_commit(cmd, &out);
    }
    cli_progress_clear(&progress);
    free(s);
    return rc;
}

int cmd_shape(const cli_command *cmd, int argc, char **argv)
{
    cli_double_list omega = {0};
    cli_int_list mode = {0};
    int points = 201;
    const char *out_path = NULL, *plot_path = NULL;
    cli_figure_style style = {0};
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    steady_cli_follow follow = {0};
    const cli_option opts[] = {
        {.name = "--omega", .type = CLI_DOUBLE_LIST, .value = &omega, .meta = "W",
         .help = "rotation rate, or a comma list of rates (2Hz,4Hz,6Hz) for --plot",
         .range = "(0, inf)", .required = "", .unit = CLI_UNIT_RATE},
        {.name = "--mode", .type = CLI_INT_LIST, .value = &mode, .meta = "K",
         .help = "node count: the pivot plus K-1 axis crossings (1..N with --links N, 1..3183 for "
                 "the continuum); one for all rates or one per rate",
         .range = "[1, inf)", .required = ""},
        STEADY_CLI_MODEL_OPTIONS(m),
        {.name = "--points", .type = CLI_INT, .value = &points, .meta = "P",
         .help = "continuum: points sampled (default 201)", .range = "[2, 10000000]",
         .excludes = "--links"},
        STEADY_CLI_FOLLOW_OPTIONS(follow),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &out_path, .meta = "FILE",
         .help = "write the CSV to FILE (default: standard output; one rate)"},
        {.name = "--plot", .type = CLI_STRING, .value = &plot_path, .meta = "PICTURE",
         .help = "draw the shapes on one figure, true to scale: PICTURE.png, .svg or .pdf "
                 "(gnuplot)"},
        CLI_FIGURE_OPTIONS(style),
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (mode.n != 1 && mode.n != omega.n)
        return cli_error(cmd, "--mode: give one mode, or one per rate (%d rates, %d modes)",
                         omega.n, mode.n);
    if (omega.n > 1 && plot_path == NULL)
        return cli_error(cmd, "--omega: %d rates make %d shapes: draw them with --plot "
                         "PICTURE, or give one rate with -o", omega.n, omega.n);
    if (omega.n > 1 && out_path)
        return cli_error(cmd, "-o writes one shape: give one rate, or --plot alone");
    if (plot_path && cli_figure_check_out(cmd, "--plot", plot_path, 0)) return 1;
    if ((style.size || style.present) && plot_path == NULL)
        return cli_error(cmd, "--size and --present shape the picture of --plot");
    int box_w, box_h;
    if (cli_figure_size(cmd, &style, &box_w, &box_h)) return 1;
    if (steady_cli_model_setup(cmd, &m)) return 1;
    if (plot_path == NULL) {
        rc = one_shape(cmd, &m, &follow, omega.v[0], omega.suffix[0], mode.v[0], points,
                       out_path);
        steady_cli_model_free(&m);
        return rc;
    }
    /* --plot: each shape into the picture's work folder, then one figure of them all (and the
     * CSV of a single shape to -o, if given) */
    char *dir = cli_figure_work_dir(cmd, plot_path);
    const char *files[CLI_LIST_MAX];
    char names[CLI_LIST_MAX][4096];
    if (dir == NULL) rc = 1;
    for (int i = 0; i < omega.n && rc == 0; i++) {
        snprintf(names[i], sizeof names[i], "%s/shape%d.csv", dir, i + 1);
        files[i] = names[i];
        rc = one_shape(cmd, &m, &follow, omega.v[i], omega.suffix[i],
                       mode.v[mode.n == 1 ? 0 : i], points, names[i]);
    }
    if (rc == 0) rc = cli_figure_draw(cmd, files, (size_t)omega.n, plot_path, &style);
    if (rc == 0 && out_path) {
        cli_out out;
        rc = cli_out_open(cmd, &out, out_path);
        FILE *in = rc == 0 ? fopen(files[0], "r") : NULL;
        char buf[4096];
        size_t k;
        while (in && (k = fread(buf, 1, sizeof buf, in)) > 0) fwrite(buf, 1, k, out.fp);
        if (in) fclose(in);
        if (rc == 0) rc = in ? cli_out_commit(cmd, &out) : (cli_out_abort(&out), 1);
    }
    cli_figure_remove_dir(dir);
    steady_cli_model_free(&m);
    return rc;
}
