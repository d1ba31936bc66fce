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
