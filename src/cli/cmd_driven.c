/* whirl driven: steady shapes of the hand-swung chain (pivot driven on a circle of radius eps,
 * air drag in the inertial frame), in the frame co-rotating at omega (include/whirl/driven.h).
 *
 * One shape (--omega): the summary comment line (with --stability, N-link chain, a second one:
 * eig_growth, index, verdict), then the CSV s,x,y,z,tension from the pivot. --mode 0 is the
 * near-axis shape (whirl_driven_mode from the hanging chain): with --mode 1 --side 1 and -1 the
 * three shapes a forced chain has at one rate past the fold.
 * A branch (--omega-min, --omega-max): comment lines (parameters, one "# fold omega=..." per
 * fold), then the CSV omega,tip_x,tip_y,tip_r,top_tension,nodes,fold along the continued branch;
 * the branch starts at --omega (default omega_max) from mode K and leaves it towards smaller
 * omega (--up: larger). With --stability (N-link chain) each point of the branch gets the
 * columns eig_growth,index,verdict of its linearisation (whirl_stability_linearise_3d): every
 * shape of the branch, also the small near-axis one a forced chain has below resonance beyond
 * the folds. Ctrl-C (SIGINT, SIGTERM) stops a branch within a step: its points so far
 * are written (a comment line says where it stopped) and the exit status is 130. */
#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "whirl/driven.h"
#include "whirl/stability.h"


typedef struct driven_options {
    double omega, omega_min, omega_max, eps, drag, drag_quadratic, tip_mass, step;
    cli_units units;
    cli_air air;
    int mode, side, links, points, max_points, up, stability;
    int side_given, omega_given, min_given, max_given, points_given, step_given, max_points_given,
        up_given;
    const char *output;
} driven_options;

static int check_options(const cli_command *cmd, const driven_options *o)
{
    const int branch = o->min_given || o->max_given;
    if (branch && !(o->omega_min < o->omega_max))
        return cli_error(cmd, "need --omega-min < --omega-max");
    if (branch && o->omega_given && !(o->omega >= o->omega_min && o->omega <= o->omega_max))
        return cli_error(cmd, "--omega (the branch's start) is outside [--omega-min, --omega-max]");
    if (o->side != 1 && o->side != -1)
        return cli_error(cmd, "--side must be 1 or -1, got %d", o->side);
    if (o->stability && !(o->links > 0))
        return cli_error(cmd, "--stability needs --links N (the N-link chain's linearisation)");
    if (o->mode == 0 && o->side_given)
        return cli_error(cmd, "--side picks the seed of modes 1..64; mode 0 (the near-axis "
                         "shape) has none");
    if (o->eps == 0 && (o->drag > 0 || o->drag_quadratic > 0))
        return cli_error(cmd, "air drag needs --eps > 0: with the pivot on the axis nothing "
                         "balances the drag's torque");
    return 0;
}

/* A dimensionless value of the kind in the user's units. */
static double user(const driven_options *o, cli_unit kind, double x)
{
    return x * cli_units_scale(&o->units, kind);
}

static void print_parameters(FILE *fp, const driven_options *o)
{
    fprintf(fp, "# driven: mode=%d side=%d eps=%s drag=%s drag_quadratic=%s tip_mass=%s "
            "links=%d%s\n", o->mode, o->side, CLI_NUM(user(o, CLI_UNIT_LENGTH, o->eps)),
            CLI_NUM(user(o, CLI_UNIT_DRAG, o->drag)),
            CLI_NUM(user(o, CLI_UNIT_DRAG2, o->drag_quadratic)),
            CLI_NUM(user(o, CLI_UNIT_MASS, o->tip_mass)), o->links,
            o->links ? "" : " (continuum)");
    cli_units_comment(fp, &o->units);
}

/* The growth and index of the linearisation about the shape q (N-link chain). */
static int point_stability(const driven_options *o, const whirl_chain *chain,
                           const whirl_driven_params *p, const whirl_driven_info *q,
                           double *growth, int *index)
{
    const size_t n = chain->n + 1;
    whirl_driven_params at = *p;
    at.omega = q->omega;
    double *buf = malloc(5 * n * sizeof *buf);
    whirl_stability *w = whirl_stability_alloc(chain->n);
    int status = buf && w ? GSL_SUCCESS : GSL_ENOMEM;
    if (!status)
        status = whirl_driven_sample(chain, &at, q->tip, n, buf, buf + n, buf + 2 * n,
                                     buf + 3 * n, buf + 4 * n);
    const whirl_model m = {.chain = chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING,
                           .omega = q->omega, .drive_radius = o->eps, .air_drag = o->drag,
                           .air_drag_quadratic = o->drag_quadratic};
    if (!status) status = whirl_stability_linearise_3d(w, &m, buf + n, buf + 2 * n, buf + 3 * n);
    if (!status) status = whirl_stability_growth(w, growth);
    if (!status) status = whirl_stability_index(w, index);
    whirl_stability_free(w);
    free(buf);
    return status;
}

/* One shape: summary and samples. */
static int run_shape(const cli_command *cmd, const driven_options *o, const whirl_chain *chain,
                     const whirl_driven_params *p)
{
    whirl_driven_info info;
    if (whirl_driven_mode(chain, p, o->mode, o->side, &info) != GSL_SUCCESS)
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    const size_t n = chain ? chain->n + 1 : (size_t)o->points;
    double *buf = malloc(5 * n * sizeof *buf);
    if (buf == NULL) return cli_error(cmd, "out of memory for %zu points", n);
    double *s = buf, *x = s + n, *y = x + n, *z = y + n, *tension = z + n;
    int rc = 1;
    double growth = 0;
    int index = 0;
    if (whirl_driven_sample(chain, p, info.tip, n, s, x, y, z, tension) != GSL_SUCCESS ||
        (o->stability && point_stability(o, chain, p, &info, &growth, &index) != GSL_SUCCESS)) {
        cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
        goto done;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, o->output)) goto done;
    print_parameters(out.fp, o);
    const double len = cli_units_scale(&o->units, CLI_UNIT_LENGTH);
    const double force = cli_units_scale(&o->units, CLI_UNIT_FORCE);
    fprintf(out.fp, "# omega=%s mode=%d node_count=%d tip_x=%s tip_y=%s tip_z=%s tip_r=%s "
            "top_tension=%s residual=%.3g\n", CLI_NUM(user(o, CLI_UNIT_RATE, info.omega)), o->mode,
            info.nodes, CLI_NUM(info.tip[0] * len), CLI_NUM(info.tip[1] * len),
            CLI_NUM(info.tip[2] * len), CLI_NUM(info.tip_r * len), CLI_NUM(info.top_tension * force),
            info.residual);
    if (o->stability)
        fprintf(out.fp, "# eig_growth=%s index=%d verdict=%s\n",
                CLI_NUM(user(o, CLI_UNIT_RATE, growth)), index,
                whirl_verdict_name(whirl_verdict_linear(growth, index)));
    fprintf(out.fp, "s,x,y,z,tension\n");
    for (size_t i = 0; i < n; i++)
        fprintf(out.fp, "%s,%s,%s,%s,%s\n", CLI_NUM(s[i] * len), CLI_NUM(x[i] * len),
                CLI_NUM(y[i] * len), CLI_NUM(z[i] * len), CLI_NUM(tension[i] * force));
    rc = cli_out_commit(cmd, &out);
done:
    free(buf);
    return rc;
}

/* A branch by continuation from mode K at the start rate. */
static int run_branch(const cli_command *cmd, const driven_options *o, const whirl_chain *chain,
                      whirl_driven_params *p)
{
    whirl_driven_info start;
    p->omega = o->omega_given ? o->omega : o->omega_max;
    if (whirl_driven_mode(chain, p, o->mode, o->side, &start) != GSL_SUCCESS)
        return cli_error(cmd, "start at omega %s %s: %s",
                         CLI_NUM(user(o, CLI_UNIT_RATE, p->omega)),
                         cli_units_name(&o->units, CLI_UNIT_RATE), CLI_LIBRARY_ERROR(&o->units));
    whirl_driven_curve *curve = whirl_driven_curve_alloc((size_t)o->max_points);
    if (curve == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    int rc = 1, rc_stab = 0;
    char stopped[512] = "";
    const int status = whirl_driven_branch(chain, p, &start, o->up ? 1 : -1, o->omega_min,
                                           o->omega_max, o->step, curve);
    if (status == WHIRL_EINTERRUPTED) {
        cli_library_error(&o->units, stopped, sizeof stopped);
    } else if (status != GSL_SUCCESS) {
        cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
        goto done;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, o->output)) goto done;
    print_parameters(out.fp, o);
    const double len = cli_units_scale(&o->units, CLI_UNIT_LENGTH);
    const double rate = cli_units_scale(&o->units, CLI_UNIT_RATE);
    fprintf(out.fp, "# branch from omega=%s towards %s omega, %zu points, %s\n", CLI_NUM(p->omega * rate),
            o->up ? "larger" : "smaller", curve->n,
            curve->complete ? "left the interval"
            : stopped[0]    ? "interrupted"
                            : "stopped early (capacity or no convergence)");
    if (stopped[0]) fprintf(out.fp, "# interrupted (%s): the points found until then\n", stopped);
    for (size_t k = 0; k < curve->n_folds; k++)
        fprintf(out.fp, "# fold omega=%s\n", CLI_NUM(curve->fold_omega[k] * rate));
    fprintf(out.fp, "omega,tip_x,tip_y,tip_r,top_tension,nodes,fold%s\n",
            o->stability ? ",eig_growth,index,verdict" : "");
    for (size_t j = 0; j < curve->n && !rc_stab; j++) {
        const whirl_driven_info *q = &curve->point[j];
        fprintf(out.fp, "%s,%s,%s,%s,%s,%d,%d", CLI_NUM(q->omega * rate), CLI_NUM(q->tip[0] * len),
                CLI_NUM(q->tip[1] * len), CLI_NUM(q->tip_r * len),
                CLI_NUM(user(o, CLI_UNIT_FORCE, q->top_tension)), q->nodes, curve->fold[j]);
        if (o->stability) {
            double growth;
            int index;
            rc_stab = point_stability(o, chain, p, q, &growth, &index);
            if (rc_stab) break;
            fprintf(out.fp, ",%s,%d,%s", CLI_NUM(growth * rate), index,
                    whirl_verdict_name(whirl_verdict_linear(growth, index)));
        }
        fputc('\n', out.fp);
    }
    if (rc_stab) {
        cli_out_abort(&out);
        cli_error(cmd, "stability at omega %s: %s", CLI_NUM(curve->point[0].omega * rate),
                  CLI_LIBRARY_ERROR(&o->units));
        goto done;
    }
    rc = cli_out_commit(cmd, &out);
    if (rc == 0 && stopped[0]) {
        cli_error(cmd, "interrupted: the %zu points found until then are written", curve->n);
        rc = CLI_EXIT_INTERRUPTED;
    }
done:
    whirl_driven_curve_free(curve);
    return rc;
}

int cmd_driven(const cli_command *cmd, int argc, char **argv)
{
    driven_options o = {0};
    o.units = (cli_units)CLI_UNITS_INIT;
    o.air = (cli_air)CLI_AIR_INIT(o.units);
    o.mode = 1, o.side = 1, o.points = 201, o.step = 0.02, o.max_points = 100000;
    const cli_option opts[] = {
        {.name = "--omega", .type = CLI_DOUBLE, .value = &o.omega, .given = &o.omega_given,
         .meta = "W", .help = "rotation rate (one shape; a branch's start)", .range = "(0, inf)",
         .required = "--omega-min", .unit = CLI_UNIT_RATE},
        {.name = "--omega-min", .type = CLI_DOUBLE, .value = &o.omega_min, .given = &o.min_given,
         .meta = "A", .help = "branch: lower end of the rates", .range = "(0, inf)",
         .needs = "--omega-max", .required = "--omega", .unit = CLI_UNIT_RATE},
        {.name = "--omega-max", .type = CLI_DOUBLE, .value = &o.omega_max, .given = &o.max_given,
         .meta = "B", .help = "branch: upper end (default start)", .range = "(0, inf)",
         .needs = "--omega-min", .unit = CLI_UNIT_RATE},
        {.name = "--mode", .type = CLI_INT, .value = &o.mode, .meta = "K",
         .help = "seed: the free shape of mode K (default 1; 0: the hanging chain, the near-axis "
                 "shape)",
         .range = "[0, 64]"},
        {.name = "--side", .type = CLI_INT, .value = &o.side, .given = &o.side_given, .meta = "S",
         .help = "seed's tip on the pivot's side (1, default) or opposite (-1)"},
        CLI_DRAG_OPTIONS(o.eps, NULL, o.drag, NULL, o.drag_quadratic, NULL, o.air),
        {.name = "--links", .type = CLI_INT, .value = &o.links, .meta = "N",
         .help = "N-link chain (default 0: the continuum)", .range = "[0, 100000]"},
        {.name = "--tip-mass", .type = CLI_DOUBLE, .value = &o.tip_mass, .meta = "m",
         .help = "point mass at the free end (default 0)", .range = "[0, inf)",
         .unit = CLI_UNIT_MASS},
        {.name = "--points", .type = CLI_INT, .value = &o.points, .given = &o.points_given,
         .meta = "P", .help = "continuum samples from the pivot (default 201)",
         .range = "[2, 1000000]", .excludes = "--omega-min --omega-max --links"},
        {.name = "--arc-step", .type = CLI_DOUBLE, .value = &o.step, .given = &o.step_given,
         .meta = "H", .help = "branch: largest step of the continuation's arclength (default 0.02)",
         .range = "(0, 1]", .needs = "--omega-min"},
        {.name = "--max-points", .type = CLI_INT, .value = &o.max_points,
         .given = &o.max_points_given, .meta = "M", .help = "branch: most points (default 100000)",
         .range = "[2, 10000000]", .needs = "--omega-min"},
        {.name = "--up", .type = CLI_FLAG, .value = &o.up, .given = &o.up_given,
         .help = "branch: leave the start towards larger omega", .needs = "--omega-min"},
        {.name = "--stability", .type = CLI_FLAG, .value = &o.stability,
         .help = "N-link chain: eig_growth, index and verdict of the shape (a branch: of every "
                 "shape)",
         .needs = "--links"},
        CLI_UNITS_OPTIONS(o.units),
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &o.output, .meta = "FILE",
         .help = "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    if ((rc = cli_drag_apply(cmd, &o.air, &o.drag_quadratic))) return rc;
    if ((rc = check_options(cmd, &o))) return rc;
    whirl_chain *chain = NULL;
    if (o.links > 0 && (chain = whirl_chain_alloc_uniform((size_t)o.links, o.tip_mass)) == NULL)
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o.units));
    whirl_driven_params p = {.omega = o.omega,
                             .drive_radius = o.eps,
                             .air_drag = o.drag,
                             .air_drag_quadratic = o.drag_quadratic,
                             .tip_mass = chain ? 0 : o.tip_mass};
    rc = (o.min_given || o.max_given) ? run_branch(cmd, &o, chain, &p) : run_shape(cmd, &o, chain, &p);
    whirl_chain_free(chain);
    return rc;
}
