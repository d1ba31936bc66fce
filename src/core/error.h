/* Internal: recording the message of a failure (see whirl_last_error). */
#ifndef WHIRL_ERROR_H
#define WHIRL_ERROR_H

/* Formats the message of this thread's last failure and returns status, so that a failing
 * function can end with: return whirl_fail(GSL_EINVAL, "omega must be > 0, got %g", omega); */
int whirl_fail(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* GSL_SUCCESS if the tip mass m (in chain masses) is in [0, WHIRL_TIP_MASS_MAX], else GSL_EINVAL
 * with the message. */
int whirl_check_tip_mass(double m);
/* GSL_SUCCESS if the rate omega (already checked positive and finite) is at most
 * WHIRL_OMEGA_MAX, else GSL_EINVAL with the message. */
int whirl_check_omega_max(double omega);

#endif
