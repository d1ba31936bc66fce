/* Numbers as text: the shortest round-trip form of a double.
 *
 * A double has 53 significant bits, so 17 significant decimal digits always identify it
 * (IEEE 754-2008, 5.12.2); fewer digits often do. Printing with %.15g, then %.16g, then %.17g
 * and keeping the first that strtod converts back to the same value gives the shortest of these
 * three forms that loses nothing (15 digits or fewer always round-trip only when the value was
 * written with that many, which is the case users care about: grids, options, rates). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

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
