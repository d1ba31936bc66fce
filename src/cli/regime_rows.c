/* whirl regime: the rows and header lines that one run, the sweep (cmd_regime.c) and the map
 * (regime_map.c) write, in the user's units. */
#include <math.h>

#include <gsl/gsl_errno.h>

#include "cli/regime_cli.h"
#include "whirl/regime.h"
#include "whirl/steady.h"

#define REGIME_CRITICAL 4 /* critical rates listed in the header */

const char *const regime_cli_map_columns =
    "index,omega,eps,state,class,nodes,period,t_end,change,remaining,shape_error,bvp_nodes,"
    "lyapunov,tip_x,tip_y,tip_z,tip_r,steps";

double regime_cli_user(const regime_options *o, cli_unit kind, double x)
{
    return x * cli_units_scale(&o->units, kind);
}

int regime_cli_is_map(const regime_options *o)
{
    return o->omin_given || o->omax_given || o->osteps_given;
}

/* The parameter line: a map written with another one cannot be resumed. */
void regime_cli_write_parameters(FILE *fp, const regime_options *o)
{
    const whirl_regime_params *p = &o->p;
    fprintf(fp, "# regime: links=%d drag=%s drag_quadratic=%s internal_damping=%s "
            "frame=%s method=%s dt=%s t_ramp=%s t_max=%s "
            "settle_tol=%s settle_periods=%d periodic_tol=%s lyapunov_periods=%d "
            "chaos_lambda=%s perturb=%s seed=%lu", o->links,
            CLI_NUM(regime_cli_user(o, CLI_UNIT_DRAG, p->air_drag)),
            CLI_NUM(regime_cli_user(o, CLI_UNIT_DRAG2, p->air_drag_quadratic)),
            CLI_NUM(regime_cli_user(o, CLI_UNIT_DAMPING, p->internal_damping)), o->frame, p->method,
            CLI_NUM(regime_cli_user(o, CLI_UNIT_TIME, p->dt)), CLI_NUM(regime_cli_user(o, CLI_UNIT_TIME, p->t_ramp)),
            CLI_NUM(regime_cli_user(o, CLI_UNIT_TIME, p->t_max)),
            CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, p->settle_tol)), p->settle_periods,
            CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, p->periodic_tol)), p->lyapunov_periods,
            CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, p->chaos_lambda)), CLI_NUM(p->perturb), p->seed);
    if (regime_cli_is_map(o))
        fprintf(fp, " omega=%s:%s:%d", CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, o->omega_min)),
                CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, o->omega_max)), o->omega_steps);
    else
        fprintf(fp, " omega=%s", CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, o->omega)));
    if (regime_cli_is_map(o) && !o->sweep)
        fprintf(fp, " eps=%s:%s:%d\n", CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, o->eps_min)),
                CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, o->eps_max)), o->eps_steps);
    else
        fprintf(fp, " eps=%s\n", CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, o->eps)));
    cli_units_comment(fp, &o->units);
}

/* The critical rates of the free N-link chain, for comparison with the map. */
void regime_cli_write_critical(FILE *fp, const regime_options *o, const whirl_chain *chain)
{
    double omega[REGIME_CRITICAL];
    if (whirl_nlink_critical(chain, REGIME_CRITICAL, omega) != GSL_SUCCESS) return;
    fprintf(fp, "# critical rates of the free chain (modes 1..%d):", REGIME_CRITICAL);
    for (int k = 0; k < REGIME_CRITICAL; k++)
        fprintf(fp, " %s", CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega[k])));
    fputc('\n', fp);
}

int regime_cli_state_class(const whirl_regime_result *r)
{
    switch (r->state) {
    case WHIRL_REGIME_SETTLED:
    case WHIRL_REGIME_CONVERGING: return r->nodes;
    case WHIRL_REGIME_PERIODIC: return 0;
    case WHIRL_REGIME_QUASIPERIODIC: return -1;
    case WHIRL_REGIME_CHAOTIC: return -2;
    default: return -3;
    }
}

/* A value and a comma; a value that was not computed (not finite) is left empty. */
static void put_value(FILE *fp, double x)
{
    /* (x is already in the user's units) */
    if (isfinite(x)) fprintf(fp, "%s", CLI_NUM(x));
    fputc(',', fp);
}

/* The columns from state on. */
void regime_cli_write_result(FILE *fp, const regime_options *o, const whirl_regime_result *r)
{
    const double len = regime_cli_user(o, CLI_UNIT_LENGTH, 1);
    fprintf(fp, "%s,%d,%d,%d,", whirl_regime_state_name(r->state), regime_cli_state_class(r),
            r->nodes, r->period);
    put_value(fp, regime_cli_user(o, CLI_UNIT_TIME, r->t_end));
    put_value(fp, r->change * len);
    put_value(fp, r->remaining * len);
    put_value(fp, r->shape_error * len);
    fprintf(fp, "%d,", r->bvp_nodes);
    put_value(fp, regime_cli_user(o, CLI_UNIT_RATE, r->lyapunov));
    for (int k = 0; k < 3; k++) put_value(fp, r->tip[k] * len);
    put_value(fp, r->tip_r * len);
    fprintf(fp, "%lu\n", r->steps);
}
