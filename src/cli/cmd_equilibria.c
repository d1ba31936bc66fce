/* whirl equilibria: every planar relative equilibrium at one rate W, with its node count, the
 * branch it lies on, its summary and its linear verdict (whirl_equilibria_find). */
#include <math.h>

#include "cli/steady_cli.h"
#include "whirl/stability.h"

/* The comment lines: the rate, the chain, the count, and how the equilibria were found. */
static void write_comments(FILE *fp, const steady_cli_model *m, const whirl_equilibria *e,
                           double omega, int no_branches)
{
    const double rate = cli_units_rate(&m->units), len = m->units.length;
    const char *rate_unit = cli_units_name(&m->units, CLI_UNIT_RATE);
    fprintf(fp, "# equilibria: omega=%s %s, %s, tip mass %s %s: %zu equilibria (mirror images "
            "r -> -r not counted), %d modes born below omega\n", CLI_NUM(omega * rate),
            rate_unit, m->chain ? "N-link chain" : "continuous chain",
            CLI_NUM(m->tip_mass * m->units.mass), cli_units_name(&m->units, CLI_UNIT_MASS),
            e->count, e->born);
    if (m->chain) {
        fprintf(fp, "# links=%d; tip scan: %zu roots (%d levels, %ld shots, floor %s %s, %zu "
                "cells unresolved); pivot scan: %zu roots (%d levels, %ld shots); both: %zu; "
                "not polished: %zu\n",
                m->links, e->tip_roots, e->tip_levels, e->tip_shots, CLI_NUM(e->tip_floor * len),
                cli_units_name(&m->units, CLI_UNIT_LENGTH), e->tip_unresolved, e->check_roots,
                e->check_levels, e->check_shots, e->matched, e->unpolished);
        if (no_branches)
            fprintf(fp, "# continuation: not run (--no-branches); largest force across a link "
                    "/ tension %s\n", CLI_NUM(e->balance));
        else
            fprintf(fp, "# continuation: %zu crossings of omega, %zu missed by the scans, %zu "
                    "isolated, %zu unidentified, %zu cut short above omega, %zu curves with the "
                    "wrong parity of crossings, %ld steps; largest force across a link / tension "
                    "%s\n", e->crossings, e->missed, e->isolated, e->unidentified, e->cut_short,
                    e->wrong_parity, e->path_steps, CLI_NUM(e->balance));
        fprintf(fp, "# branch: the mode k whose birth (born_at = omega_k) the equilibrium is "
                "connected to by continuation; isolated: on a curve that meets no birth, "
                "born_at its lowest fold; unidentified: the continuation failed; wrong parity: "
                "a branch born below omega (not returning to the hanging chain) crossing it an "
                "even number of times or an isolated curve an odd number, where the "
                "continuation jumped between curves or stopped short (0 expected)\n");
        fprintf(fp, "# polish: %zu roots from a shot in quadruple precision (where the double "
                "shot's link angles were too far off: roots within round-off of each other); "
                "%zu roots on the equilibrium of another root of the same scan (0 expected)\n",
                e->refined, e->coincident);
    } else {
        fprintf(fp, "# sign changes of the pivot's radius over the tip radius: %zu (%d levels, "
                "%ld shots); shapes solved mode by mode: %zu, each alone in a sign change: %zu "
                "(Kolodner: exactly one shape per mode born)\n", e->tip_roots, e->tip_levels,
                e->tip_shots, e->check_roots, e->matched);
        fprintf(fp, "# branch: the mode; born_at: its critical rate; eig_growth, verdict, index: "
                "not computed for the continuum (use --links N)\n");
    }
}

/* The header and a row per equilibrium. */
static void write_rows(FILE *fp, const steady_cli_model *m, const whirl_equilibria *e,
                       int no_branches)
{
    const double rate = cli_units_rate(&m->units), len = m->units.length;
    const double force = cli_units_force(&m->units);
    cli_units_comment(fp, &m->units);
    fprintf(fp, "nodes,branch,born_at,tip_r,max_r,depth,top_tension,eig_growth,verdict,index\n");
    for (size_t i = 0; i < e->count; i++) {
        const whirl_equilibrium *q = &e->eq[i];
        char branch[32];
        if (q->branch > 0) snprintf(branch, sizeof branch, "%d", q->branch);
        else if (no_branches && m->chain) branch[0] = 0;
        else snprintf(branch, sizeof branch, "%s", q->branch == 0 ? "isolated" : "unidentified");
        fprintf(fp, "%d,%s,%s,%s,%s,%s,%s,", q->info.n_crossings + 1, branch,
                isfinite(q->born_at) ? CLI_NUM(q->born_at * rate) : "",
                CLI_NUM(q->info.tip_r * len), CLI_NUM(q->info.max_r * len),
                CLI_NUM(q->info.depth * len), CLI_NUM(q->info.top_tension * force));
        if (isfinite(q->eig_growth))
            fprintf(fp, "%s,%s,%d\n", CLI_NUM(q->eig_growth * rate),
                    whirl_verdict_name(whirl_verdict_linear(q->eig_growth, q->index)), q->index);
        else
            fprintf(fp, ",,\n");
    }
}

int cmd_equilibria(const cli_command *cmd, int argc, char **argv)
{
    double omega = 0;
    int no_stability = 0, no_branches = 0, shot_budget = 0;
    const char *out_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {.name = "--omega", .type = CLI_DOUBLE, .value = &omega, .meta = "W",
         .help = "rotation rate", .range = "(0, inf)", .required = "", .unit = CLI_UNIT_RATE},
        STEADY_CLI_MODEL_OPTIONS(m),
        {.name = "--no-stability", .type = CLI_FLAG, .value = &no_stability,
         .help = "N-link: leave eig_growth, verdict and index empty (faster on long chains)",
         .needs = "--links"},
        {.name = "--no-branches", .type = CLI_FLAG, .value = &no_branches,
         .help = "N-link: the two scans only, no continuation (branch and born_at empty; for "
                 "counts at high rates)",
         .needs = "--links"},
        {.name = "--shot-budget", .type = CLI_INT, .value = &shot_budget, .meta = "E",
         .help = "N-link: most residual evaluations of one refinement level of a scan (default "
                 "2e7; the count of equilibria grows about sevenfold per 5 in W at high rates, and "
                 "the scans' work with it)",
         .range = "[1000, inf)", .needs = "--links"},
        {.name = "--output", .alias = "-o", .type = CLI_STRING, .value = &out_path, .meta = "FILE",
         .help = "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (steady_cli_model_setup(cmd, &m)) return 1;
    whirl_equilibria_params par = whirl_equilibria_defaults();
    par.stability = !no_stability;
    par.continuation = !no_branches;
    if (shot_budget) par.shot_budget = shot_budget;
    whirl_equilibria *e = NULL;
    const int status = whirl_equilibria_find(m.chain, steady_cli_tip_mass(&m), omega, &par, &e);
    if (status) {
        steady_cli_model_free(&m);
        return cli_error(cmd, "%s%s", CLI_LIBRARY_ERROR(&m.units),
                         status == GSL_EMAXITER ? "; --shot-budget raises the bound" : "");
    }
    cli_out out;
    if (cli_out_open(cmd, &out, out_path)) {
        whirl_equilibria_free(e);
        steady_cli_model_free(&m);
        return 1;
    }
    write_comments(out.fp, &m, e, omega, no_branches);
    write_rows(out.fp, &m, e, no_branches);
    whirl_equilibria_free(e);
    steady_cli_model_free(&m);
    return cli_out_commit(cmd, &out);
}
