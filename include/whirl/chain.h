/* whirl: the N-link chain (the seed's N-fold pendulum): N point masses on massless rigid links.
 * Link i (1-based) joins mass i-1 to mass i; mass 0 is the pivot at the origin. */
#ifndef WHIRL_CHAIN_H
#define WHIRL_CHAIN_H

#include <stddef.h>

#include "whirl/common.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct whirl_chain {
    size_t n;       /* number of links = number of point masses, >= 1 */
    double *length; /* length[i-1]: length of link i [L], > 0 */
    double *mass;   /* mass[i-1]: the point mass at the lower end of link i [M], > 0 */
    double gravity; /* g [L/T^2], > 0; default 1 */
} whirl_chain;

/* A chain of n equal links and equal masses, total length 1 and total mass 1, g = 1, with
 * tip_mass (>= 0) added to the last mass: the discrete model of the uniform chain.
 * Returns NULL on n = 0, a negative or non-finite tip mass, or no memory (whirl_last_error).
 * @param n the links N, >= 1
 * @param tip_mass the mass added at the free end [M], >= 0
 * @return the chain, to free with whirl_chain_free; NULL with a message on bad input or no memory
 */
WHIRL_API whirl_chain *whirl_chain_alloc_uniform(size_t n, double tip_mass);

/* A chain of n links with the given lengths and masses (copied), gravity g. NULL on bad input
 * (non-positive or non-finite values: whirl_last_error names the first) or no memory.
 * @param n the links N, >= 1
 * @param length the links' lengths, n (copied)
 * @param mass the point masses at their lower ends, n (copied)
 * @param g the gravity, > 0
 * @return the chain, to free with whirl_chain_free; NULL with a message on bad input or no memory
 */
WHIRL_API whirl_chain *whirl_chain_alloc(size_t n, const double *length, const double *mass,
                                         double g);

/* Frees the chain; NULL is a no-op.
 * @param c the chain, or NULL
 */
WHIRL_API void whirl_chain_free(whirl_chain *c);

/* Sum of the link lengths.
 * @param c the chain
 * @return the sum of the link lengths [L]
 */
WHIRL_API double whirl_chain_total_length(const whirl_chain *c);
/* Sum of the masses.
 * @param c the chain
 * @return the sum of the masses [M]
 */
WHIRL_API double whirl_chain_total_mass(const whirl_chain *c);

#ifdef __cplusplus
}
#endif

#endif
