/* whirl sweep: the branches of the listed modes over S+1 equally spaced rates, each followed by
 * continuation (whirl_continuum_branch / whirl_nlink_branch, on all OpenMP threads). */
#include <stdlib.h>

#include "cli/steady_cli.h"

int cmd_sweep(const cli_command *cmd, int argc, char **argv)
{
    cli_int_list modes = {0, {0}};
    double omega_min = 0, omega_max = 0;
    int steps = 0, modes_given = 0, min_given = 0, max_given = 0, steps_given = 0;
    const char *out_path = NULL;
    steady_cli_model m = STEADY_CLI_MODEL_INIT;
    const cli_option opts[] = {
        {"--modes", NULL, CLI_INT_LIST, &modes, &modes_given, "LIST", "modes, e.g. 1,2,3"},
        {"--omega-min", NULL, CLI_DOUBLE, &omega_min, &min_given, "A", "lowest rate"},
        {"--omega-max", NULL, CLI_DOUBLE, &omega_max, &max_given, "B", "highest rate"},
        {"--steps", NULL, CLI_INT, &steps, &steps_given, "S", "S+1 equally spaced rates"},
        STEADY_CLI_MODEL_OPTIONS(m),
        {"--output", "-o", CLI_STRING, &out_path, NULL, "FILE", "write the CSV to FILE"},
    };
    int rc = cli_parse(cmd, argc, argv, opts, sizeof opts / sizeof *opts, NULL, 0);
    if (rc) return rc;
    if (!modes_given) return cli_error(cmd, "--modes is required");
    if (!min_given) return cli_error(cmd, "--omega-min is required");
    if (!max_given) return cli_error(cmd, "--omega-max is required");
    if (!steps_given) return cli_error(cmd, "--steps is required");
    for (int i = 0; i < modes.n; i++)
        if (modes.v[i] < 1 || modes.v[i] > WHIRL_MODE_MAX)
            return cli_error(cmd, "--modes: each mode must be between 1 and %d, got %d",
                             WHIRL_MODE_MAX, modes.v[i]);
    if (steady_cli_check_omega(cmd, "--omega-min", omega_min)) return 1;
    if (steady_cli_check_omega(cmd, "--omega-max", omega_max)) return 1;
    if (omega_min > omega_max)
        return cli_error(cmd, "--omega-min %g exceeds --omega-max %g", omega_min, omega_max);
    if (steps < 1) return cli_error(cmd, "--steps must be >= 1, got %d", steps);
    if (steady_cli_model_setup(cmd, &m)) return 1;

    double rate = cli_units_rate(&m.units), len = m.units.length, force = cli_units_force(&m.units);
    size_t n = (size_t)steps + 1;
    double *omega = malloc(n * sizeof *omega);
    whirl_shape_info *info = malloc(n * (size_t)modes.n * sizeof *info);
    int *exists = malloc(n * (size_t)modes.n * sizeof *exists);
    if (omega == NULL || info == NULL || exists == NULL) {
        rc = cli_error(cmd, "out of memory for %zu rates", n);
        goto done;
    }
    for (size_t j = 0; j < n; j++)
        omega[j] = (omega_min + (omega_max - omega_min) * (double)j / (double)steps) / rate;
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
        fprintf(out.fp, "# branches of the %s, tip mass %.17g; rows where the mode exists\n",
                m.chain ? "N-link chain" : "continuous chain", m.tip_mass);
        fprintf(out.fp, "omega,mode,tip_r,max_r,top_tension,depth\n");
        for (int i = 0; i < modes.n; i++)
            for (size_t j = 0; j < n; j++) {
                const whirl_shape_info *f = &info[i * n + j];
                if (!exists[i * n + j]) continue;
                fprintf(out.fp, "%.17g,%d,%.17g,%.17g,%.17g,%.17g\n", omega[j] * rate, modes.v[i],
                        f->tip_r * len, f->max_r * len, f->top_tension * force, f->depth * len);
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
