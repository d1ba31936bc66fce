/* whirl sweep: the branches of the listed modes over S+1 equally spaced rates, each followed by
 * continuation (whirl_continuum_branch / whirl_nlink_branch, on all OpenMP threads). */
#include <stdlib.h>

#include "cli/steady_cli.h"

int cmd_sweep(const cli_command *cmd, int argc, char **argv)
{
    cli_int_list modes = {0, {0}};
    double omega_min = 0, omega_max = 0;
    int count = 0;
    const char *out_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {"--modes", NULL, CLI_INT_LIST, &modes, NULL, "LIST", "modes, e.g. 1,2,3", "[1, 64]",
         NULL, NULL, ""},
        {"--omega-min", NULL, CLI_DOUBLE, &omega_min, NULL, "A", "lowest rate", "(0, inf)", NULL,
         NULL, "", CLI_UNIT_RATE},
        {"--omega-max", NULL, CLI_DOUBLE, &omega_max, NULL, "B", "highest rate", "(0, inf)", NULL,
         NULL, "", CLI_UNIT_RATE},
        {"--omega-count", NULL, CLI_INT, &count, NULL, "N",
         "N equally spaced rates, both ends included", "[1, 10000000]", NULL, NULL, ""},
        STEADY_CLI_MODEL_OPTIONS(m),
        {"--output", "-o", CLI_STRING, &out_path, NULL, "FILE",
         "write the CSV to FILE (default: standard output)"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (count == 1 ? omega_min != omega_max : !(omega_min < omega_max))
        return cli_error(cmd, "need --omega-min < --omega-max (equal with --omega-count 1)");
    if (steady_cli_model_setup(cmd, &m)) return 1;

    double rate = cli_units_rate(&m.units), len = m.units.length, force = cli_units_force(&m.units);
    size_t n = (size_t)count;
    double *omega = malloc(n * sizeof *omega);
    whirl_shape_info *info = malloc(n * (size_t)modes.n * sizeof *info);
    int *exists = malloc(n * (size_t)modes.n * sizeof *exists);
    if (omega == NULL || info == NULL || exists == NULL) {
        rc = cli_error(cmd, "out of memory for %zu rates", n);
        goto done;
    }
    for (size_t j = 0; j < n; j++)
        omega[j] = cli_grid(omega_min, omega_max, count, (int)j);
    for (int i = 0; i < modes.n && rc == 0; i++) {
        int status = m.chain ? whirl_nlink_branch(m.chain, modes.v[i], n, omega, info + i * n,
                                                  exists + i * n)
                             : whirl_continuum_branch(modes.v[i], steady_cli_tip_mass(&m), n,
                                                      omega, info + i * n, exists + i * n);
        if (status != GSL_SUCCESS)
            rc = cli_error(cmd, "mode %d: %s", modes.v[i], whirl_last_error());
    }
    cli_out out;
    if (rc == 0 && (rc = cli_out_open(cmd, &out, out_path)) == 0) {
        fprintf(out.fp, "# branches of the %s, tip mass %s %s; rows where the mode exists\n",
                m.chain ? "N-link chain" : "continuous chain", CLI_NUM(m.tip_mass * m.units.mass),
                cli_units_name(&m.units, CLI_UNIT_MASS));
        cli_units_comment(out.fp, &m.units);
        fprintf(out.fp, "omega,mode,tip_r,max_r,top_tension,depth\n");
        for (int i = 0; i < modes.n; i++)
            for (size_t j = 0; j < n; j++) {
                const whirl_shape_info *f = &info[i * n + j];
                if (!exists[i * n + j]) continue;
                fprintf(out.fp, "%s,%d,%s,%s,%s,%s\n", CLI_NUM(omega[j] * rate), modes.v[i],
                        CLI_NUM(f->tip_r * len), CLI_NUM(f->max_r * len),
                        CLI_NUM(f->top_tension * force), CLI_NUM(f->depth * len));
            }
        rc = cli_out_commit(cmd, &out);
    }
done:
    free(omega);
    free(info);
    free(exists);
    steady_cli_model_free(&m);
    return rc;
}
