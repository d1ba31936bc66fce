/* Reference solutions of the Cartesian formulation's multiplier system (src/dyn_cartesian.c),
 * shared by tests/unit/dynamics/test_dynamics.c and tests/bench/bench_scaling.c: straightforward Thomas elimination
 * from the top, in binary128 (__float128: the reference) or in double (for comparison).
 * Header-only (static functions). */
#ifndef WHIRL_TENSION_REF_H
#define WHIRL_TENSION_REF_H

#include <math.h>
#include <stddef.h>

#include "whirl/chain.h"

__extension__ typedef __float128 real128;

/* The multiplier system of dyn_cartesian.c for a 3D state y = (d, d') with the pivot fixed at
 * the origin, rotating frame at w (w = 0: inertial):
 *   lambda_i |d_i|^2 (1/m_i + 1/m_{i-1}) - lambda_{i+1} (d_i . d_{i+1}) / m_i
 *     - lambda_{i-1} (d_i . d_{i-1}) / m_{i-1} = d_i . (g_i - g_{i-1}) + |d_i'|^2,
 * g_i - g_{i-1} = w^2 (d_x, d_y, 0) + 2 w (d_y', -d_x', 0) - g z [i = 0 only], 1/m_{-1} = 0.
 * Tensions T_i = lambda_i |d_i|. Both solvers below eliminate from the top (Thomas); work holds
 * 3 N reals, and the multipliers lambda_i in work[N + i] on return. */
#define DEFINE_TENSION_SOLVER(name, real)                                                    \
    static inline void name(const whirl_chain *c, double w, const double *y, double *tension, \
                            real *work)                                                      \
    {                                                                                        \
        const size_t n = c->n;                                                               \
        const double *q = y, *qd = y + 3 * n;                                                \
        real *diag = work, *rhs = work + n, *off = work + 2 * n; /* off_i: (i, i+1) entry */ \
        for (size_t i = 0; i < n; i++) {                                                     \
            const double *d = q + 3 * i, *r = qd + 3 * i;                                    \
            const real dd = (real)d[0] * d[0] + (real)d[1] * d[1] + (real)d[2] * d[2];       \
            const real inv_up = i > 0 ? 1 / (real)c->mass[i - 1] : 0;                        \
            diag[i] = dd * (1 / (real)c->mass[i] + inv_up);                                  \
            const real a[3] = {(real)w * w * d[0] + 2 * (real)w * r[1],                      \
                               (real)w * w * d[1] - 2 * (real)w * r[0],                      \
                               i == 0 ? -(real)c->gravity : 0};                              \
            rhs[i] = (real)d[0] * a[0] + (real)d[1] * a[1] + (real)d[2] * a[2] +             \
                     (real)r[0] * r[0] + (real)r[1] * r[1] + (real)r[2] * r[2];              \
            if (i + 1 < n) {                                                                 \
                const double *e = q + 3 * (i + 1);                                           \
                off[i] = -((real)d[0] * e[0] + (real)d[1] * e[1] + (real)d[2] * e[2]) /      \
                         (real)c->mass[i];                                                   \
            }                                                                                \
        }                                                                                    \
        for (size_t i = 1; i < n; i++) {                                                     \
            const real f = off[i - 1] / diag[i - 1];                                         \
            diag[i] -= f * off[i - 1];                                                       \
            rhs[i] -= f * rhs[i - 1];                                                        \
        }                                                                                    \
        real lam = rhs[n - 1] / diag[n - 1];                                                 \
        for (size_t i = n; i-- > 0;) {                                                       \
            if (i + 1 < n) lam = (rhs[i] - off[i] * lam) / diag[i];                          \
            rhs[i] = lam;                                                                    \
            const double *d = q + 3 * i;                                                     \
            const real len = (real)sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);            \
            tension[i] = (double)(lam * len);                                                \
        }                                                                                    \
    }

DEFINE_TENSION_SOLVER(tensions_quad, real128)
DEFINE_TENSION_SOLVER(tensions_double, double)

#endif
