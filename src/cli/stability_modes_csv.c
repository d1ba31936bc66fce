/* The CSV of whirl stability --eigenvectors: per mode (eig: its row in --eigenvalues, from 1)
 * and node i = 0..N (0: the pivot) the eigenvalue re, im, the Krein signature, the arc length s
 * of the node, its displacement (dx, dy, dz) in the co-rotating frame (the real part: the mode at
 * phase 0; dx_im, dy_im, dz_im the imaginary part, a quarter period later up to sign) and the
 * link angles (a, b) of link i (the one ending at node i; empty for the pivot), real and
 * imaginary parts. The mode is scaled so that its largest node displacement is 1 in the output's
 * length unit (whirl_stability_eigenvectors scales it to 1 L: with a length unit of L metres the
 * displacements are kept and the angles divided by L). */
#include "cli/stability_modes_csv.h"

#include "cli/cli.h"

void stability_modes_write(FILE *fp, const whirl_stability_modes *md, const size_t *order,
                           const whirl_chain *c, double rate, double length)
{
    const size_t n = md->links, q = 2 * n, nn = 3 * (n + 1);
    fprintf(fp, "eig,re,im,krein,node,s,dx,dy,dz,dx_im,dy_im,dz_im,a,b,a_im,b_im\n");
    for (size_t r = 0; r < md->count; r++) {
        const size_t k = order[r];
        const double *dr = md->node_re + k * nn, *di = md->node_im + k * nn;
        const double *ar = md->angle_re + k * q, *ai = md->angle_im + k * q;
        double s = 0;
        for (size_t i = 0; i <= n; i++) {
            if (i > 0) s += c->length[i - 1];
            fprintf(fp, "%zu,%s,%s,%d,%zu,%s", r + 1, CLI_NUM(md->re[k] * rate),
                    CLI_NUM(md->im[k] * rate), md->krein[k], i, CLI_NUM(s * length));
            for (int p = 0; p < 3; p++) fprintf(fp, ",%s", CLI_NUM(dr[3 * i + (size_t)p]));
            for (int p = 0; p < 3; p++) fprintf(fp, ",%s", CLI_NUM(di[3 * i + (size_t)p]));
            if (i == 0) {
                fprintf(fp, ",,,,\n");
                continue;
            }
            fprintf(fp, ",%s,%s,%s,%s\n", CLI_NUM(ar[i - 1] / length),
                    CLI_NUM(ar[n + i - 1] / length), CLI_NUM(ai[i - 1] / length),
                    CLI_NUM(ai[n + i - 1] / length));
        }
    }
}
