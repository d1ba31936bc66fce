/* Internal: the recursion up from the tip of the N-link chain, one link at a time: the force
 * balance that the positions and the shots (src/steady/nlink.c), the continuation
 * (src/steady/nlink_path.c) and the equilibria (src/steady/equilibria.c) are built on.
 *
 * Link i (i = N down to 1) carries the weight and the centrifugal force of the masses below it
 * and points along their resultant (nlink.c's header comment). Per unit tip radius a, with
 * u_i = r_i / a and eta_i = H_i / a,
 *     eta_i = eta_{i+1} + m_i omega^2 u_i,   V_i = V_{i+1} + m_i g,   H_i = a eta_i,
 *     T_i = |(H_i, V_i)|,   u_{i-1} = u_i - l_i eta_i / T_i,
 * from eta_{N+1} = V_{N+1} = 0 and u_N = 1; with a = 1 and u_N = r_N the same recursion gives
 * the radii and the horizontal loads themselves. Linearised about the hanging chain (links at
 * angles ~ H/V << 1: T_i = V_i to relative order (H/V)^2) it is the linear shot, the shape
 * of small a.
 *
 * The variants the callers need, each with the rounding its callers' results are defined by
 * (an order of operations changed moves roots and counts in the last bits):
 *  - precision: double (tip_up), long double (tip_up_ext: 64 bits of mantissa on x86-64) and
 *    quadruple (tip_up_quad, nlink_quad: 113 bits), one text instantiated three times;
 *  - the tension T (tip_up_tension): hypot; the square root of H^2 + V^2, alone or with hypot
 *    where H^2 + V^2 passes 1e300 (overflow of the derivatives' H H_a from omega ~ 1e77 on);
 *    or V (linearised);
 *  - m_i omega^2 as (m_i f1) f2 with f1 f2 = omega^2: (omega^2, 1) multiplies the mass by
 *    omega^2 (the shots), (omega, omega) by omega twice (the positions); a factor 1 is exact.
 * The caller runs the loop (i = N..1, or a part of it) and reads what it needs after each link:
 * h = H_i, t = T_i, v = V_i, eta = eta_i, u = u_{i-1} (t2 = H_i^2 + V_i^2 and big with the
 * square roots); the derivatives of the shots are the callers' (their own formulas and
 * rounding). */
#ifndef WHIRL_STEADY_TIP_UP_H
#define WHIRL_STEADY_TIP_UP_H

#include <math.h>

#include "steady/steady_internal.h"

typedef enum tip_up_tension {
    TIP_UP_HYPOT,    /* T = hypot(H, V) */
    TIP_UP_SQRT,     /* T = sqrt(H^2 + V^2) */
    TIP_UP_SQRT_BIG, /* T = sqrt(H^2 + V^2), or hypot(H, V) where H^2 + V^2 >= 1e300 (big) */
    TIP_UP_LINEAR    /* T = V */
} tip_up_tension;

/* Quadruple precision's square root: Newton's iteration from the long double one (which has
 * quadruple precision's range; each step doubles the correct bits, 64 -> 113 in one, a second
 * for the rounding). */
static inline nlink_quad tip_up_sqrt_quad(nlink_quad x)
{
    nlink_quad y = sqrtl((long double)x);
    y = (y + x / y) / 2;
    return (y + x / y) / 2;
}

/* |(h, v)| in quadruple precision for v > 0, without overflow */
static inline nlink_quad tip_up_hypot_quad(nlink_quad h, nlink_quad v)
{
    nlink_quad ah = h < 0 ? -h : h, big = ah > v ? ah : v, small = ah > v ? v : ah;
    nlink_quad q = small / big;
    return big * tip_up_sqrt_quad(1 + q * q);
}

/* The state of the recursion in the real type T, its start (f1 f2 = omega^2, the tip radius a,
 * u = u_N) and one link (i from N down to 1). */
#define TIP_UP_KERNEL(NAME, T, SQRT, HYPOT)                                                     \
    typedef struct NAME {                                                                      \
        T f1, f2, a, g;       /* omega^2 = f1 f2, the tip radius, gravity */                  \
        T u, eta, v, h, t, t2; /* after link i: u_{i-1}, eta_i, V_i, H_i, T_i, H_i^2 + V_i^2 */ \
        int big;              /* TIP_UP_SQRT_BIG: T_i from hypot */                           \
    } NAME;                                                                                    \
                                                                                               \
    static inline NAME NAME##_start(const whirl_chain *c, T f1, T f2, T a, T u)               \
    {                                                                                          \
        NAME s = {f1, f2, a, c->gravity, u, 0, 0, 0, 0, 0, 0};                               \
        return s;                                                                              \
    }                                                                                          \
                                                                                               \
    static inline void NAME##_link(NAME *s, const whirl_chain *c, size_t i, tip_up_tension how) \
    {                                                                                          \
        const T m = c->mass[i - 1];                                                            \
        s->eta += m * s->f1 * s->f2 * s->u;                                                    \
        s->v += m * s->g;                                                                      \
        s->h = s->a * s->eta;                                                                  \
        if (how == TIP_UP_LINEAR) {                                                            \
            s->t = s->v;                                                                       \
        } else if (how == TIP_UP_HYPOT) {                                                      \
            s->t = HYPOT(s->h, s->v);                                                          \
        } else {                                                                               \
            s->t2 = s->h * s->h + s->v * s->v;                                                 \
            s->t = SQRT(s->t2);                                                                \
            s->big = how == TIP_UP_SQRT_BIG && !(s->t2 < 1e300);                               \
            if (s->big) s->t = HYPOT(s->h, s->v);                                              \
        }                                                                                      \
        s->u -= c->length[i - 1] * s->eta / s->t;                                              \
    }

TIP_UP_KERNEL(tip_up, double, sqrt, hypot)
TIP_UP_KERNEL(tip_up_ext, long double, sqrtl, hypotl)
TIP_UP_KERNEL(tip_up_quad, nlink_quad, tip_up_sqrt_quad, tip_up_hypot_quad)

#undef TIP_UP_KERNEL

#endif
