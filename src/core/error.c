/* The last failure's message, one per thread so that sweeps can run threads. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>

#include "whirl/common.h"
#include "core/error.h"

static _Thread_local char last_error[512];

const char *whirl_last_error(void) { return last_error; }

int whirl_check_tip_mass(double m)
{
    if (!(isfinite(m) && m >= 0))
        return whirl_fail(GSL_EINVAL, "tip mass must be >= 0 and finite, got %g", m);
    if (m > WHIRL_TIP_MASS_MAX)
        return whirl_fail(GSL_EINVAL, "tip mass %g exceeds %g chain masses: the chain's own "
                          "weight would be lost in the rounding of the tension", m,
                          WHIRL_TIP_MASS_MAX);
    return GSL_SUCCESS;
}

int whirl_check_omega_max(double omega)
{
    if (omega > WHIRL_OMEGA_MAX)
        return whirl_fail(GSL_EINVAL, "omega=%g is above %g: the centrifugal forces ~ omega^2 "
                          "would overflow", omega, WHIRL_OMEGA_MAX);
    return GSL_SUCCESS;
}

int whirl_fail(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return status;
}
