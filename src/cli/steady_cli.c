/* What the steady-shape commands share: model options, checks, unit conversions. */
#include <math.h>

#include "cli/steady_cli.h"

int steady_cli_model_setup(const cli_command *cmd, steady_cli_model *m)
{
    if (cli_units_check(cmd, &m->units)) return 1;
    if (!(m->tip_mass >= 0)) return cli_error(cmd, "--tip-mass must be >= 0, got %g", m->tip_mass);
    m->chain = NULL;
    if (!m->links_given) return 0;
    if (m->links < 1) return cli_error(cmd, "--links must be >= 1, got %d", m->links);
    m->chain = whirl_chain_alloc_uniform((size_t)m->links, steady_cli_tip_mass(m));
    if (m->chain == NULL) return cli_error(cmd, "%s", whirl_last_error());
    return 0;
}

void steady_cli_model_free(steady_cli_model *m)
{
    whirl_chain_free(m->chain);
    m->chain = NULL;
}

double steady_cli_tip_mass(const steady_cli_model *m) { return m->tip_mass / m->units.mass; }

int steady_cli_critical(const cli_command *cmd, const steady_cli_model *m, int mode,
                        double *omega)
{
    int status;
    if (m->chain) {
        if ((size_t)mode > m->chain->n)
            return cli_error(cmd, "a chain of %d links has modes 1..%d, asked for mode %d",
                             m->links, m->links, mode);
        double crit[WHIRL_MODE_MAX];
        status = whirl_nlink_critical(m->chain, (size_t)mode, crit);
        *omega = crit[mode - 1];
    } else {
        status = whirl_continuum_critical(mode, steady_cli_tip_mass(m), omega);
    }
    if (status != GSL_SUCCESS) return cli_error(cmd, "%s", whirl_last_error());
    return 0;
}

int steady_cli_check_omega(const cli_command *cmd, const char *name, double omega)
{
    if (!(omega > 0)) return cli_error(cmd, "%s must be > 0, got %g", name, omega);
    return 0;
}

int steady_cli_solve_error(const cli_command *cmd, const steady_cli_model *m, int status,
                           int mode, double omega)
{
    if (status != GSL_EDOM) return cli_error(cmd, "%s", whirl_last_error());
    double omega_k, rate = cli_units_rate(&m->units);
    if (steady_cli_critical(cmd, m, mode, &omega_k)) return 1;
    return cli_error(cmd, "mode %d does not exist at omega=%.17g: it exists only above "
                     "omega_%d=%.17g", mode, omega * rate, mode, omega_k * rate);
}

void steady_cli_write_shape(FILE *fp, const steady_cli_model *m, const whirl_shape_info *info,
                            size_t n, const double *s, const double *r, const double *z,
                            const double *tension, const char *extra)
{
    double rate = cli_units_rate(&m->units), len = m->units.length;
    double force = cli_units_force(&m->units);
    fprintf(fp, "# omega=%.17g mode=%d tip_r=%.17g max_r=%.17g top_tension=%.17g depth=%.17g nodes=",
            info->omega * rate, info->mode, info->tip_r * len, info->max_r * len,
            info->top_tension * force, info->depth * len);
    for (int j = 0; j < info->n_nodes; j++)
        fprintf(fp, "%s%.17g", j ? ";" : "", info->node_s[j] * len);
    fprintf(fp, "\n# %s; s: arclength from the pivot, r: signed distance from the axis, "
            "z: height (pivot 0), tension: %s\n",
            m->chain ? "N-link chain: pivot then masses 1..N" : "continuous chain",
            m->chain ? "of the link above the node" : "at that point");
    if (extra) fprintf(fp, "# %s\n", extra);
    fprintf(fp, "s,r,z,tension\n");
    for (size_t i = 0; i < n; i++)
        fprintf(fp, "%.17g,%.17g,%.17g,%.17g\n", s[i] * len, r[i] * len, z[i] * len,
                tension[i] * force);
}
