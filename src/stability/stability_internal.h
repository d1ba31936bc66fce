/* Rules of the linearisation shared by the files of src/stability: internal to the library. */
#ifndef WHIRL_STABILITY_INTERNAL_H
#define WHIRL_STABILITY_INTERNAL_H

#include <stddef.h>

#include "whirl/stability.h"

/* The chart of a link with unit direction u (whirl/stability.h): e2 along the part of y (x if
 * |u_y| > 0.9) perpendicular to u, e1 = u x e2. */
void stability_link_chart(const double *u, double *e1, double *e2);

/* The number of links N of the workspace. */
size_t stability_links(const whirl_stability *w);

#endif
