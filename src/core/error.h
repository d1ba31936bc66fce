/* Internal: recording a failure, its status and its message (see whirl_last_error,
 * whirl_last_status), and carrying it from one thread to another. */
#ifndef WHIRL_ERROR_H
#define WHIRL_ERROR_H

#include <stddef.h>

#include "whirl/common.h" /* whirl_error_record, its functions */

/* Formats the message of this thread's last failure and records status with it, so that a
 * failing function can end with: return whirl_fail(GSL_EINVAL, "omega must be > 0, got %g",
 * omega); */
int whirl_fail(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---- typed quantities in messages ----
 * A number of a message that is a physical quantity is preceded in the format by the mark of
 * its kind, so that whirl_last_error_in_units() can print it in a program's units:
 *   whirl_fail(GSL_EDOM, "no shape at omega=" WHIRL_Q_RATE "%.17g", omega);
 * The marks are not part of the text whirl_last_error() returns. */
#define WHIRL_Q_MARK "\x1d" /* ASCII group separator: never in a message's own text */
#define WHIRL_Q_RATE WHIRL_Q_MARK "r"   /* a rate, in sqrt(g/L) */
#define WHIRL_Q_LENGTH WHIRL_Q_MARK "l" /* a length, in L */
#define WHIRL_Q_MASS WHIRL_Q_MARK "m"   /* a mass, in M */
#define WHIRL_Q_TIME WHIRL_Q_MARK "t"   /* a time, in sqrt(L/g) */
#define WHIRL_Q_FORCE WHIRL_Q_MARK "F"  /* a force, in M g */
#define WHIRL_Q_DRAG WHIRL_Q_MARK "d"   /* a linear drag per unit length, in M sqrt(g/L) / L */
#define WHIRL_Q_DRAG2 WHIRL_Q_MARK "q"  /* a quadratic drag per unit length, in M / L^2 */
#define WHIRL_Q_DAMPING WHIRL_Q_MARK "D" /* an internal damping, in M L^2 sqrt(g/L) */

/* This thread's last message with its marks: for a message that quotes it,
 * whirl_fail(status, "the start: %s", whirl_error_marked()), so that its quantities stay typed. */
const char *whirl_error_marked(void);

/* GSL_SUCCESS if the tip mass m (in chain masses) is in [0, WHIRL_TIP_MASS_MAX], else GSL_EINVAL
 * with the message. */
int whirl_check_tip_mass(double m);
/* GSL_SUCCESS if the rate omega (already checked positive and finite) is at most
 * WHIRL_OMEGA_MAX, else GSL_EINVAL with the message. */
int whirl_check_omega_max(double omega);

#endif
