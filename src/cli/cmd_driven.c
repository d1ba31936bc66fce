/* whirl driven: steady shapes of the hand-swung chain (pivot driven on a circle of radius eps,
 * air drag in the inertial frame), in the frame co-rotating at omega (include/whirl/driven.h).
 *
 * One shape (--omega): the summary comment line, then the CSV s,x,y,z,tension from the pivot.
 * A branch (--omega-min, --omega-max): comment lines (parameters, one "# fold omega=..." per
 * fold), then the CSV omega,tip_x,tip_y,tip_r,top_tension,nodes,fold along the continued branch;
 * the branch starts at --omega (default omega_max) from mode K and leaves it towards smaller
 * omega (--up: larger). */
#include <stdlib.h>

#include "cli/cli.h"
#include "whirl/driven.h"

#define DRIVEN_MAX_LINKS 100000

typedef struct driven_options {
    double omega, omega_min, omega_max, eps, drag, drag_quadratic, tip_mass, step;
    int mode, side, links, points, max_points, up;
    int omega_given, min_given, max_given, points_given, step_given, max_points_given,
        up_given;
    const char *output;
} driven_options;

static int check_options(const cli_command *cmd, const driven_options *o)
{
    const int branch = o->min_given || o->max_given;
    if (branch && !(o->min_given && o->max_given))
        return cli_error(cmd, "a branch needs both --omega-min and --omega-max");
    if (!branch && !o->omega_given)
        return cli_error(cmd, "--omega (one shape) or --omega-min and --omega-max (a branch) "
                         "is required");
    if (!branch && (o->step_given || o->max_points_given || o->up_given))
        return cli_error(cmd, "--step, --max-points and --up apply to a branch only");
    if (branch && o->points_given) return cli_error(cmd, "--points applies to one shape only");
    if (o->omega_given && !(o->omega > 0))
        return cli_error(cmd, "--omega must be > 0, got %g", o->omega);
    if (branch && !(o->omega_min > 0 && o->omega_min < o->omega_max))
        return cli_error(cmd, "need 0 < --omega-min < --omega-max, got %g, %g", o->omega_min,
                         o->omega_max);
    if (branch && o->omega_given && !(o->omega >= o->omega_min && o->omega <= o->omega_max))
        return cli_error(cmd, "--omega %g (the branch's start) is outside [%g, %g]", o->omega,
                         o->omega_min, o->omega_max);
    if (o->mode < 1 || o->mode > WHIRL_MODE_MAX)
        return cli_error(cmd, "--mode must be between 1 and %d, got %d", WHIRL_MODE_MAX, o->mode);
    if (o->side != 1 && o->side != -1)
        return cli_error(cmd, "--side must be 1 or -1, got %d", o->side);
    if (!(o->eps >= 0 && o->eps < 1))
        return cli_error(cmd, "--eps must be in [0, 1) (the chain's length is 1), got %g", o->eps);
    if (!(o->drag >= 0)) return cli_error(cmd, "--drag must be >= 0, got %g", o->drag);
    if (!(o->drag_quadratic >= 0))
        return cli_error(cmd, "--drag-quadratic must be >= 0, got %g", o->drag_quadratic);
    if (o->eps == 0 && (o->drag > 0 || o->drag_quadratic > 0))
        return cli_error(cmd, "air drag needs --eps > 0: with the pivot on the axis nothing "
                         "balances the drag's torque");
    if (!(o->tip_mass >= 0)) return cli_error(cmd, "--tip-mass must be >= 0, got %g", o->tip_mass);
    if (o->links < 0 || o->links > DRIVEN_MAX_LINKS)
        return cli_error(cmd, "--links must be between 0 (continuum) and %d, got %d",
                         DRIVEN_MAX_LINKS, o->links);
    if (o->links > 0 && o->points_given)
        return cli_error(cmd, "--points applies to the continuum (the N-link chain prints its "
                         "N + 1 nodes)");
    if (o->points < 2 || o->points > 1000000)
        return cli_error(cmd, "--points must be between 2 and 1000000, got %d", o->points);
    if (!(o->step > 0 && o->step <= 1)) return cli_error(cmd, "--step must be in (0, 1], got %g", o->step);
    if (o->max_points < 2 || o->max_points > 10000000)
        return cli_error(cmd, "--max-points must be between 2 and 10000000, got %d", o->max_points);
    return 0;
}

static void print_parameters(FILE *fp, const driven_options *o)
{
    fprintf(fp, "# driven: mode=%d side=%d eps=%.17g drag=%.17g drag_quadratic=%.17g tip_mass=%.17g "
            "links=%d%s\n", o->mode, o->side, o->eps, o->drag, o->drag_quadratic, o->tip_mass,
            o->links, o->links ? "" : " (continuum)");
}

/* One shape: summary and samples. */
static int run_shape(const cli_command *cmd, const driven_options *o, const whirl_chain *chain,
                     const whirl_driven_params *p)
{
    whirl_driven_info info;
    if (whirl_driven_mode(chain, p, o->mode, o->side, &info) != GSL_SUCCESS)
        return cli_error(cmd, "%s", whirl_last_error());
    const size_t n = chain ? chain->n + 1 : (size_t)o->points;
    double *buf = malloc(5 * n * sizeof *buf);
    if (buf == NULL) return cli_error(cmd, "out of memory for %zu points", n);
    double *s = buf, *x = s + n, *y = x + n, *z = y + n, *tension = z + n;
    int rc = 1;
    if (whirl_driven_sample(chain, p, info.tip, n, s, x, y, z, tension) != GSL_SUCCESS) {
        cli_error(cmd, "%s", whirl_last_error());
        goto done;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, o->output)) goto done;
    print_parameters(out.fp, o);
    fprintf(out.fp, "# omega=%.17g mode=%d nodes=%d tip_x=%.17g tip_y=%.17g tip_z=%.17g tip_r=%.17g "
            "top_tension=%.17g residual=%.3g\n", info.omega, o->mode, info.nodes, info.tip[0],
            info.tip[1], info.tip[2], info.tip_r, info.top_tension, info.residual);
    fprintf(out.fp, "s,x,y,z,tension\n");
    for (size_t i = 0; i < n; i++)
        fprintf(out.fp, "%.17g,%.17g,%.17g,%.17g,%.17g\n", s[i], x[i], y[i], z[i], tension[i]);
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
        return cli_error(cmd, "start at omega %g: %s", p->omega, whirl_last_error());
    whirl_driven_curve *curve = whirl_driven_curve_alloc((size_t)o->max_points);
    if (curve == NULL) return cli_error(cmd, "%s", whirl_last_error());
    int rc = 1;
    if (whirl_driven_branch(chain, p, &start, o->up ? 1 : -1, o->omega_min, o->omega_max,
                            o->step, curve) != GSL_SUCCESS) {
        cli_error(cmd, "%s", whirl_last_error());
        goto done;
    }
    cli_out out;
    if (cli_out_open(cmd, &out, o->output)) goto done;
    print_parameters(out.fp, o);
    fprintf(out.fp, "# branch from omega=%.17g towards %s omega, %zu points, %s\n", p->omega,
            o->up ? "larger" : "smaller", curve->n,
            curve->complete ? "left the interval" : "stopped early (capacity or no convergence)");
    for (size_t k = 0; k < curve->n_folds; k++)
        fprintf(out.fp, "# fold omega=%.17g\n", curve->fold_omega[k]);
    fprintf(out.fp, "omega,tip_x,tip_y,tip_r,top_tension,nodes,fold\n");
    for (size_t j = 0; j < curve->n; j++) {
        const whirl_driven_info *q = &curve->point[j];
        fprintf(out.fp, "%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d\n", q->omega, q->tip[0], q->tip[1],
                q->tip_r, q->top_tension, q->nodes, curve->fold[j]);
    }
    rc = cli_out_commit(cmd, &out);
done:
    whirl_driven_curve_free(curve);
    return rc;
}

int cmd_driven(const cli_command *cmd, int argc, char **argv)
{
    driven_options o = {0};
    o.mode = 1, o.side = 1, o.points = 201, o.step = 0.02, o.max_points = 100000;
    const cli_option opts[] = {
        {"--omega", NULL, CLI_DOUBLE, &o.omega, &o.omega_given, "W", "rotation rate [sqrt(g/L)] (one shape; a branch's start)"},
        {"--omega-min", NULL, CLI_DOUBLE, &o.omega_min, &o.min_given, "A", "branch: lower end of the rates"},
        {"--omega-max", NULL, CLI_DOUBLE, &o.omega_max, &o.max_given, "B", "branch: upper end (default start)"},
        {"--mode", NULL, CLI_INT, &o.mode, NULL, "K", "seed: the free shape of mode K (default 1)"},
        {"--side", NULL, CLI_INT, &o.side, NULL, "S", "seed's tip on the pivot's side (1, default) or opposite (-1)"},
        {"--eps", NULL, CLI_DOUBLE, &o.eps, NULL, "E", "radius of the pivot's circle [L] (default 0)"},
        {"--drag", NULL, CLI_DOUBLE, &o.drag, NULL, "C", "linear air drag per unit length (default 0)"},
        {"--drag-quadratic", NULL, CLI_DOUBLE, &o.drag_quadratic, NULL, "C2", "quadratic air drag per unit length (default 0)"},
        {"--links", NULL, CLI_INT, &o.links, NULL, "N", "N-link chain (default 0: the continuum)"},
        {"--tip-mass", NULL, CLI_DOUBLE, &o.tip_mass, NULL, "m", "point mass at the free end [M] (default 0)"},
        {"--points", NULL, CLI_INT, &o.points, &o.points_given, "P", "continuum samples from the pivot (default 201)"},
        {"--step", NULL, CLI_DOUBLE, &o.step, &o.step_given, "H", "branch: largest arclength step (default 0.02)"},
        {"--max-points", NULL, CLI_INT, &o.max_points, &o.max_points_given, "M", "branch: most points (default 100000)"},
        {"--up", NULL, CLI_FLAG, &o.up, &o.up_given, "", "branch: leave the start towards larger omega"},
        {"--output", "-o", CLI_STRING, &o.output, NULL, "FILE", "write to FILE (atomically) instead of stdout"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof opts[0], NULL, 0);
    if (rc) return rc;
    if ((rc = check_options(cmd, &o))) return rc;
    whirl_chain *chain = NULL;
    if (o.links > 0 && (chain = whirl_chain_alloc_uniform((size_t)o.links, o.tip_mass)) == NULL)
        return cli_error(cmd, "%s", whirl_last_error());
    whirl_driven_params p = {o.omega, o.eps, o.drag, o.drag_quadratic, chain ? 0 : o.tip_mass};
    rc = (o.min_given || o.max_given) ? run_branch(cmd, &o, chain, &p) : run_shape(cmd, &o, chain, &p);
    whirl_chain_free(chain);
    return rc;
}
