/* whirl stability --eigenvectors: the modes' CSV (stability_modes_csv.c). */
#ifndef WHIRL_CLI_STABILITY_MODES_CSV_H
#define WHIRL_CLI_STABILITY_MODES_CSV_H

#include <stdio.h>

#include "whirl/chain.h"
#include "whirl/stability.h"

/* The header and one row per (mode, node) of the modes md (of the chain c) in the order
 * order[0..md->count) (that of --eigenvalues), rates times rate, lengths times length (the
 * output units). */
void stability_modes_write(FILE *fp, const whirl_stability_modes *md, const size_t *order,
                           const whirl_chain *c, double rate, double length);

#endif
