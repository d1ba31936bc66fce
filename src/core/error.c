/* The last failure of each thread: its status and its message, with the message's quantities
 * typed (rates, lengths, ...) so that a program can print them in its own units.
 *
 * The message is kept as the library formatted it, with a mark (WHIRL_Q_MARK and a letter of the
 * kind, core/error.h) before each quantity's number; whirl_last_error() is the text without the
 * marks, and whirl_last_error_in_units() scales each marked number. A quantity's value is the
 * number as the message prints it (17 digits where the exact value matters, %g elsewhere), and
 * in units it is printed with as many significant digits as that, but at least 6 and at most 15
 * (a rate given as 1 rad/s reads 1, not 0.9999999999999999). */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "whirl/common.h"
#include "core/error.h"

/* the plain text keeps WHIRL's historical 511 characters; the marked one has room for marks */
#define PLAIN_MAX 512

typedef struct last_failure {
    whirl_error_record record;
    char plain[PLAIN_MAX];
} last_failure;

static _Thread_local last_failure last;

const char *whirl_last_error(void) { return last.plain; }
int whirl_last_status(void) { return last.record.status; }
const char *whirl_error_marked(void) { return last.record.text; }

/* The plain text of the marked one. */
static void strip_marks(const char *marked, char *plain, size_t size)
{
    size_t len = 0;
    for (const char *p = marked; *p && len + 1 < size; p++) {
        if (*p == WHIRL_Q_MARK[0] && p[1]) {
            p++;
            continue;
        }
        plain[len++] = *p;
    }
    plain[len] = '\0';
}

static int set_last(int status, const char *marked)
{
    if (marked != last.record.text)
        snprintf(last.record.text, sizeof last.record.text, "%s", marked);
    last.record.status = status;
    strip_marks(last.record.text, last.plain, sizeof last.plain);
    return status;
}

int whirl_fail(int status, const char *fmt, ...)
{
    va_list ap;
    char text[WHIRL_ERROR_MAX];
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    return set_last(status, text);
}

void whirl_error_save(whirl_error_record *r) { *r = last.record; }

int whirl_error_restore(const whirl_error_record *r) { return set_last(r->status, r->text); }

int whirl_error_restore_first(const whirl_error_record *r, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (r[i].status != GSL_SUCCESS) return whirl_error_restore(&r[i]);
    return GSL_SUCCESS;
}

int whirl_error_keep(whirl_error_record *slot, int status)
{
    if (status == GSL_SUCCESS) return status;
#pragma omp critical /* unnamed: a named one would be an exported symbol of the library */
    if (slot->status == GSL_SUCCESS) {
        whirl_error_save(slot);
        slot->status = status;
    }
    return status;
}

/* ---- the message in units ---- */

static double quantity_scale(char kind, double length, double mass, double gravity, int rate_hz,
                             const char **unit)
{
    const double rate = sqrt(gravity / length);
    switch (kind) {
    case 'r':
        *unit = rate_hz ? "Hz" : "rad/s";
        return rate_hz ? rate / (2 * M_PI) : rate;
    case 'l': *unit = "m"; return length;
    case 'm': *unit = "kg"; return mass;
    case 't': *unit = "s"; return 1 / rate;
    case 'F': *unit = "N"; return mass * gravity;
    case 'd': *unit = "kg/(m s)"; return mass * rate / length;
    case 'q': *unit = "kg/m^2"; return mass / (length * length);
    case 'D': *unit = "kg m^2/s"; return mass * length * length * rate;
    default: *unit = ""; return 1;
    }
}

char *whirl_last_error_in_units(char *buf, size_t size, int physical, double length, double mass,
                                double gravity, int rate_hz)
{
    const char *p = last.record.text;
    size_t len = 0;
    if (size == 0) return buf;
    buf[0] = '\0';
    while (*p && len + 1 < size) {
        if (*p != WHIRL_Q_MARK[0] || p[1] == '\0') {
            buf[len++] = *p++;
            buf[len] = '\0';
            continue;
        }
        const char kind = p[1];
        p += 2;
        /* a number that does not print as one (inf, nan) is left as it is */
        if (!(isdigit((unsigned char)*p) || (*p == '-' && isdigit((unsigned char)p[1]))))
            continue;
        char *end;
        const double x = strtod(p, &end);
        const size_t nlen = (size_t)(end - p);
        int digits = 0;
        for (const char *d = p; d < end && *d != 'e' && *d != 'E'; d++)
            if (isdigit((unsigned char)*d) && (digits > 0 || *d != '0')) ++digits;
        const char *unit;
        const double scale = quantity_scale(kind, length, mass, gravity, rate_hz, &unit);
        char num[WHIRL_FORMAT_MAX];
        const int n = physical ? snprintf(buf + len, size - len, "%.*g %s",
                                          digits < 6 ? 6 : digits > 15 ? 15 : digits, x * scale,
                                          unit)
                      : digits >= 16 ? snprintf(buf + len, size - len, "%s",
                                                whirl_format_double(num, x))
                                     : snprintf(buf + len, size - len, "%.*s", (int)nlen, p);
        if (n < 0 || (size_t)n >= size - len) break;
        len += (size_t)n;
        p += nlen;
    }
    return buf;
}

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
        return whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g is above %g: the centrifugal "
                          "forces ~ omega^2 would overflow", omega, WHIRL_OMEGA_MAX);
    return GSL_SUCCESS;
}
