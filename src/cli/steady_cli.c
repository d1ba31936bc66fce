/* What the steady-shape commands share: model options, checks, unit conversions. */
#include <math.h>
#include <stdlib.h>

#include "cli/steady_cli.h"

int steady_cli_model_setup(const cli_command *cmd, steady_cli_model *m)
{
    m->chain = NULL;
    if (!m->links_given) return 0;
    m->chain = whirl_chain_alloc_uniform((size_t)m->links, steady_cli_tip_mass(m));
    if (m->chain == NULL) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m->units));
    return 0;
}

void steady_cli_model_free(steady_cli_model *m)
{
    whirl_chain_free(m->chain);
    m->chain = NULL;
}

double steady_cli_tip_mass(const steady_cli_model *m) { return m->tip_mass; }

int steady_cli_check_mode(const cli_command *cmd, const steady_cli_model *m, int mode)
{
    if (m->chain && (mode < 1 || (size_t)mode > m->chain->n))
        return cli_error(cmd, "mode %d does not exist: a chain of %d links has modes 1..%d",
                         mode, m->links, m->links);
    if (!m->chain && (mode < 1 || mode > WHIRL_CONTINUUM_MODE_MAX))
        return cli_error(cmd, "mode %d is out of range: the continuous chain's solvers take "
                         "modes 1..%d, those born below omega=%g (--links N: modes 1..N)", mode,
                         WHIRL_CONTINUUM_MODE_MAX, WHIRL_CONTINUUM_OMEGA_MAX);
    return 0;
}

int steady_cli_critical(const cli_command *cmd, const steady_cli_model *m, int mode,
                        double *omega)
{
    if (steady_cli_check_mode(cmd, m, mode)) return 1;
    int status;
    if (m->chain) {
        double *crit = malloc((size_t)mode * sizeof *crit);
        if (crit == NULL) return cli_error(cmd, "out of memory for %d critical rates", mode);
        status = whirl_nlink_critical(m->chain, (size_t)mode, crit);
        *omega = crit[mode - 1];
        free(crit);
    } else {
        status = whirl_continuum_critical(mode, steady_cli_tip_mass(m), omega);
    }
    if (status != GSL_SUCCESS) return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m->units));
    return 0;
}

int steady_cli_solve_error(const cli_command *cmd, const steady_cli_model *m, int status)
{
    if (status == GSL_EMAXITER && m->chain)
        return cli_error(cmd, "%s; --max-steps sets the bound", CLI_LIBRARY_ERROR(&m->units));
    return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&m->units));
}

/* The progress line (a whirl_nlink_progress_fn); see steady_cli.h for what it shows. */
static void follow_progress(void *ctx, const whirl_nlink_progress *at)
{
    steady_cli_follow *f = ctx;
    if (!f->line.drawn && cli_wall_seconds() - f->line.start < f->after) return;
    const double rate = cli_units_rate(&f->m->units);
    char which[64] = "", unit[32] = "";
    if (f->count > 1) snprintf(which, sizeof which, " (%d of %d)", f->index, f->count);
    if (f->m->units.physical)
        snprintf(unit, sizeof unit, " %s", cli_units_name(&f->m->units, CLI_UNIT_RATE));
    cli_progress_text(&f->line, "mode %d%s: omega %.6g of %.6g%s (now %.6g), %ld steps (at most "
                      "%ld), %ld folds", at->mode, which, at->omega_hi * rate, f->target * rate,
                      unit, at->omega * rate, at->steps, at->steps_max, at->folds);
}

void steady_cli_follow_begin(steady_cli_follow *f, const cli_command *cmd,
                             const steady_cli_model *m, double target, int count)
{
    f->opt = whirl_nlink_follow_defaults(m->chain);
    if (f->max_steps > 0) f->opt.steps_max = f->max_steps;
    f->opt.progress = follow_progress;
    f->opt.progress_ctx = f;
    f->m = m;
    f->target = target;
    f->index = 1;
    f->count = count;
    f->after = cli_progress_after();
    cli_progress_begin(&f->line, cmd, "", 0, 0);
}

void steady_cli_follow_end(steady_cli_follow *f) { cli_progress_clear(&f->line); }

void steady_cli_write_shape(FILE *fp, const steady_cli_model *m, const whirl_shape_info *info,
                            size_t n, const double *s, const double *r, const double *z,
                            const double *tension, const char *extra)
{
    double rate = cli_units_rate(&m->units), len = m->units.length;
    double force = cli_units_force(&m->units);
    /* the N-link chain's nodes from its masses' radii: all of them (info holds the first
     * WHIRL_SHAPE_NODES) */
    double *node_s = NULL;
    size_t nodes = info->n_crossings > 0 ? (size_t)info->n_crossings : 0;
    if (m->chain && nodes > WHIRL_SHAPE_NODES && (node_s = malloc(n * sizeof *node_s)) != NULL)
        nodes = whirl_nlink_node_arclengths(m->chain, info->omega, r, n, node_s, NULL);
    else if (nodes > WHIRL_SHAPE_NODES)
        nodes = WHIRL_SHAPE_NODES;
    fprintf(fp, "# omega=%s mode=%d node_count=%d tip_r=%s max_r=%s top_tension=%s depth=%s "
            "crossing_s=", CLI_NUM(info->omega * rate), info->mode, info->n_crossings + 1,
            CLI_NUM(info->tip_r * len),
            CLI_NUM(info->max_r * len), CLI_NUM(info->top_tension * force),
            CLI_NUM(info->depth * len));
    for (size_t j = 0; j < nodes; j++)
        fprintf(fp, "%s%s", j ? ";" : "", CLI_NUM((node_s ? node_s[j] : info->crossing_s[j]) * len));
    free(node_s);
    fprintf(fp, "\n# %s; s: arclength from the pivot, r: signed distance from the axis, "
            "z: height (pivot 0), tension: %s\n",
            m->chain ? "N-link chain: pivot then masses 1..N" : "continuous chain",
            m->chain ? "of the link above the node" : "at that point");
    if ((int)nodes < info->n_crossings)
        fprintf(fp, "# crossing_s: the first %zu of the %d axis crossings below the pivot\n", nodes,
                info->n_crossings);
    /* an N-link shape whose radii decay below the smallest normal double towards the tip (the
     * top modes of 500 links and more near their birth): the CSV cannot show the signs of the
     * tail's radii, which the node count takes from the linearised force balance */
    size_t resolved = n - 1;
    if (m->chain) whirl_nlink_node_arclengths(m->chain, info->omega, r, 0, NULL, &resolved);
    if (m->chain && resolved + 1 < n)
        fprintf(fp, "# the radii of masses %zu..%zu are below the smallest normal double (0 or "
                "subnormal here): their signs and nodes are those of the force balance "
                "linearised about the hanging chain at this rate, from the tip up\n",
                resolved + 1, n - 1);
    if (info->n_crossings + 1 != info->mode)
        fprintf(fp, "# the branch of mode %d (born at omega_%d) has %d nodes at this rate: on a "
                "coarse chain a branch can change its node count\n", info->mode, info->mode,
                info->n_crossings + 1);
    if (extra) fprintf(fp, "# %s\n", extra);
    cli_units_comment(fp, &m->units);
    fprintf(fp, "s,r,z,tension\n");
    /* 10^7 points are 800 MB: the stop request is polled (the caller then drops the file) */
    for (size_t i = 0; i < n && !(i % 16384 == 16383 && cli_interrupted); i++)
        fprintf(fp, "%s,%s,%s,%s\n", CLI_NUM(s[i] * len), CLI_NUM(r[i] * len),
                CLI_NUM(z[i] * len), CLI_NUM(tension[i] * force));
}
