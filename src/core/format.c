/* Numbers as text: the shortest round-trip form of a double, quantities with unit suffixes,
 * the units line of every file.
 *
 * A double has 53 significant bits, so 17 significant decimal digits always identify it
 * (IEEE 754-2008, 5.12.2); fewer digits often do. Printing with %.15g, then %.16g, then %.17g
 * and keeping the first that strtod converts back to the same value gives the shortest of these
 * three forms that loses nothing (15 digits or fewer always round-trip only when the value was
 * written with that many, which is the case users care about: grids, options, rates). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "whirl/common.h"

char *whirl_format_double(char *buf, double x)
{
    if (isnan(x)) {
        snprintf(buf, WHIRL_FORMAT_MAX, "nan");
        return buf;
    }
    if (isinf(x)) {
        snprintf(buf, WHIRL_FORMAT_MAX, "%s", x > 0 ? "inf" : "-inf");
        return buf;
    }
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, WHIRL_FORMAT_MAX, "%.*g", digits, x);
        if (digits == 17 || strtod(buf, NULL) == x) break;
    }
    return buf;
}

/* ---- quantities with units ---- */

typedef struct suffix {
    const char *text;
    double factor; /* to the SI unit of the kind */
} suffix;

static const suffix rate_suffixes[] = {{"rad/s", 1},
                                       {"Hz", 6.283185307179586476925286766559},
                                       {"rpm", 0.10471975511965977461542144610932},
                                       {NULL, 0}};
static const suffix length_suffixes[] = {{"m", 1}, {"cm", 0.01}, {"mm", 0.001}, {NULL, 0}};
static const suffix mass_suffixes[] = {{"kg", 1}, {"g", 0.001}, {NULL, 0}};
static const suffix time_suffixes[] = {{"s", 1}, {"ms", 0.001}, {NULL, 0}};

static const suffix *suffixes_of(whirl_quantity kind)
{
    switch (kind) {
    case WHIRL_QUANTITY_RATE: return rate_suffixes;
    case WHIRL_QUANTITY_LENGTH: return length_suffixes;
    case WHIRL_QUANTITY_MASS: return mass_suffixes;
    case WHIRL_QUANTITY_TIME: return time_suffixes;
    default: return NULL;
    }
}

const char *whirl_quantity_suffixes(whirl_quantity kind)
{
    switch (kind) {
    case WHIRL_QUANTITY_RATE: return "rad/s, Hz or rpm";
    case WHIRL_QUANTITY_LENGTH: return "m, cm or mm";
    case WHIRL_QUANTITY_MASS: return "kg or g";
    case WHIRL_QUANTITY_TIME: return "s or ms";
    default: return "";
    }
}

int whirl_parse_quantity(const char *text, whirl_quantity kind, double *value, int *suffixed)
{
    char *end;
    if (text == NULL || value == NULL) return -1;
    errno = 0;
    double v = strtod(text, &end);
    if (end == text || errno == ERANGE || !isfinite(v)) return -1;
    if (suffixed) *suffixed = 0;
    /* "4Hz", "4 Hz", "4HZ": spaces before the suffix, which is matched without regard to case
     * (no two suffixes of a kind differ only in case) */
    while (*end == ' ') end++;
    if (*end != '\0') {
        const suffix *u = suffixes_of(kind);
        while (u && u->text && strcasecmp(u->text, end) != 0) u++;
        if (u == NULL || u->text == NULL) return -1;
        v *= u->factor;
        if (!isfinite(v)) return -1;
        if (suffixed) *suffixed = 1;
    }
    *value = v;
    return 0;
}

void whirl_write_units_line(FILE *fp, int physical, double length, double mass, double gravity)
{
    char l[WHIRL_FORMAT_MAX], m[WHIRL_FORMAT_MAX], g[WHIRL_FORMAT_MAX];
    if (physical)
        fprintf(fp, "# units: length=m mass=kg time=s rate=rad/s force=N L=%s M=%s g=%s\n",
                whirl_format_double(l, length), whirl_format_double(m, mass),
                whirl_format_double(g, gravity));
    else
        fprintf(fp, "# units: dimensionless (length L, mass M, time sqrt(L/g), rate sqrt(g/L), "
                    "force M g)\n");
}
