/* Deviation of a chain from a reference shape, modulo rotation about the vertical axis.
 *
 * D(x, ref) = min over a of sqrt( (1/n) sum_i |R(a) x_i - ref_i|^2 ),  R(a) the rotation by a
 * about z. Expanding, sum_i |R x_i - ref_i|^2 = const - 2 (A cos a + B sin a) with
 *   A = sum_i (x_i ref_x,i + y_i ref_y,i),  B = sum_i (x_i ref_y,i - y_i ref_x,i),
 * so the optimal angle is a* = atan2(B, A) in closed form (any a when A = B = 0). The distances
 * are then summed directly at a* rather than through the expansion, which would cancel
 * catastrophically for a tiny deviation. Accuracy: round-off of the positions. */
#include <math.h>

#include "whirl/dynamics.h"

double whirl_deviation(size_t n, const double *x, const double *ref)
{
    if (n == 0) return NAN;
    double a = 0, b = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = x + 3 * i, *q = ref + 3 * i;
        a += p[0] * q[0] + p[1] * q[1];
        b += p[0] * q[1] - p[1] * q[0];
    }
    const double angle = atan2(b, a), c = cos(angle), s = sin(angle);
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = x + 3 * i, *q = ref + 3 * i;
        const double dx = c * p[0] - s * p[1] - q[0];
        const double dy = s * p[0] + c * p[1] - q[1];
        const double dz = p[2] - q[2];
        sum += dx * dx + dy * dy + dz * dz;
    }
    return sqrt(sum / (double)n);
}
