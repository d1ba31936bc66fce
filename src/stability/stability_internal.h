/* Rules of the linearisation shared by the files of src/stability: internal to the library. */
#ifndef WHIRL_STABILITY_INTERNAL_H
#define WHIRL_STABILITY_INTERNAL_H

#include <stddef.h>

#include "whirl/stability.h"

/* The chart of a link with unit direction u (whirl/stability.h): e2 along the part of y (x if
 * |u_y| > 0.9) perpendicular to u, e1 = u x e2. */
void stability_link_chart(const double *u, double *e1, double *e2);

/* The first-order form A = [[0, I], [-M^-1 K, -M^-1 (G + C)]] (4N x 4N) of the linearisation's
 * mat (M, G, C, K: 2N x 2N row-major, whirl_stability_matrix order), entry (i, j) at
 * a[i * row + j * col] (row-major: row = the row stride, col = 1; column-major: row = 1,
 * col = 4N); scratch f (2N x 2N: M's Cholesky factor) and r (2N x 4N column-major: [K | G + C],
 * then M^-1 [K | G + C]). GSL_EFAILED when M is not positive definite. */
int stability_first_order(size_t n, const double *const mat[4], double *a, size_t row,
                          size_t col, double *f, double *r);

/* The number of links N of the workspace. */
size_t stability_links(const whirl_stability *w);

#endif
