/* The checks of a steady shape's arguments and results and the message of a missing mode, shared
 * by the continuous and the N-link steady shapes (steady_internal.h). */
#include <limits.h>
#include <math.h>

#include <gsl/gsl_math.h>

#include "core/error.h"
#include "steady/steady_internal.h"

int whirl_steady_check_args(double omega, int mode, int mode_max)
{
    if (!(isfinite(omega) && omega > 0))
        return whirl_fail(GSL_EINVAL, "omega must be > 0 and finite, got %g", omega);
    if (whirl_check_omega_max(omega) != GSL_SUCCESS) return GSL_EINVAL;
    if (mode < 1 && mode_max == INT_MAX)
        return whirl_fail(GSL_EINVAL, "mode must be >= 1, got %d", mode);
    if (mode < 1 || mode > mode_max)
        return whirl_fail(GSL_EINVAL, "mode must be between 1 and %d, got %d", mode_max, mode);
    return GSL_SUCCESS;
}

int whirl_steady_check_info(const whirl_shape_info *info)
{
    const struct {
        const char *name;
        double value;
    } q[] = {{"tip_r", info->tip_r}, {"max_r", info->max_r},
             {"top_tension", info->top_tension}, {"depth", info->depth}};
    for (size_t i = 0; i < sizeof q / sizeof q[0]; i++)
        if (!isfinite(q[i].value))
            return whirl_fail(GSL_ERANGE, "mode %d at omega=" WHIRL_Q_RATE "%g: %s is not finite "
                              "(%g): the rate or the tip mass is too large", info->mode,
                              info->omega, q[i].name, q[i].value);
    for (int j = 0; j < info->n_crossings && j < WHIRL_SHAPE_NODES; j++)
        if (!isfinite(info->crossing_s[j]))
            return whirl_fail(GSL_ERANGE, "mode %d at omega=" WHIRL_Q_RATE "%g: node %d is not "
                              "finite", info->mode, info->omega, j + 1);
    return GSL_SUCCESS;
}

int whirl_steady_check_samples(double omega, size_t n, const double *r, const double *z,
                               const double *tension)
{
    const double *a[3] = {r, z, tension};
    static const char *const name[3] = {"r", "z", "tension"};
    for (int k = 0; k < 3; k++)
        for (size_t i = 0; a[k] != NULL && i < n; i++)
            if (!isfinite(a[k][i]))
                return whirl_fail(GSL_ERANGE, "the shape at omega=" WHIRL_Q_RATE "%g: %s of point "
                                  "%zu is not finite (%g): the rate or the tip mass is too large",
                                  omega, name[k], i, a[k][i]);
    return GSL_SUCCESS;
}

int whirl_steady_fail_missing(int mode, double omega, double omega_k)
{
    return whirl_fail(GSL_EDOM, "mode %d does not exist at omega=" WHIRL_Q_RATE "%.17g: it exists "
                      "only above omega_%d=" WHIRL_Q_RATE "%.17g", mode, omega, mode, omega_k);
}
