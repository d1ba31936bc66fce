/* The continuous chain's stability workspace, shared by its files (continuum_stability.c: the
 * workspace; continuum_shape.c, continuum_pencil.c, continuum_eigen.c, continuum_windows.c):
 * internal to the library. */
#ifndef WHIRL_CONTINUUM_INTERNAL_H
#define WHIRL_CONTINUUM_INTERNAL_H

#include <stddef.h>

#include "core/linalg.h"

#include "whirl/continuum_stability.h"
#include "stability/windows_internal.h"

#define CS_ELEMENTS_START 4   /* uniform elements before refinement */
#define CS_SAMPLES 513        /* samples of the shooting's shape seeding the Newton iteration */
#define CS_NEWTON_MAX 40      /* Newton iterations per element set */
#define CS_KRYLOV_MAX 400     /* Arnoldi steps of a full spectrum before the dense fall-back */
#define CS_DENSE_POINTS 700   /* the dense block (3 np)^2 at most for this many points */

enum { F_U, F_W, F_TAU, F_V, N_FIELDS }; /* fields, and the equations in their rows (F_TAU: the
                                            constraint) */
enum { N_DYNAMIC = 3 };                  /* fields with a mass: u, w, vh */
#define CS_SHIFT 1.0 /* the real shift s of (A - s B)^-1 B [1/T^2], away from the mu of interest */

struct whirl_cstab {
    whirl_cstab_params p;
    size_t cap;               /* points allocated for */
    size_t ecap;              /* element ends allocated for */
    size_t ne, np;            /* elements and points of the last linearisation */
    size_t kl, ku, ldab;      /* the pencil's bands (point-major order) and LAPACK's ldab */
    size_t nkl, nldab;        /* the shape's Newton bands (kl = ku) and ldab */
    int mode;
    double omega;
    double shift;             /* the shift s of the last factorisation [1/T^2] */
    double *brk;              /* element ends, 0 = brk[0] < ... < brk[ne] = 1 */
    double *dref;             /* (p + 1)^2 differentiation on [0, 1], row-major */
    double *cw;               /* (p + 1) Clenshaw-Curtis weights on [0, 1] */
    double *sig, *r, *q, *wq; /* per point: sigma, the shape, quadrature weight */
    double *t0, *rp, *zp;     /* per point: tension, r', z' */
    double *jac, *res;        /* Newton: the banded Jacobian (nldab x 2 np), the residual */
    lapack_int *ipiv;
    size_t *lnz, *unz;        /* per column of the LU: the last nonzero multiplier of L and the
                                 farthest nonzero of U above the diagonal (offsets) */
    double *ab;               /* A in LAPACK's band storage (ldab x 4 np, rows kl..) */
    double *bb;               /* B: a 4 x 4 block per point, [g][row field][column field] */
    double *lu;               /* the banded LU of R (A - s B) */
    double *row_a;            /* the row equilibration R (4 np) */
    double *ra, *rb, *ta, *tb; /* one row of the pencil, field-major (4 np; zero between uses) */
    double *solve;            /* one right-hand side (4 np) */
    double *mu_re, *mu_im;    /* kept mu */
    size_t *kept;             /* their index among the Ritz values or dgeev's eigenvalues */
    int *sig_out;
    double *ls, *lr, *lq;     /* samples of the shooting (CS_SAMPLES each) */
    /* the Arnoldi iteration of the spectrum (blocked; its basis 3 cap x (CS_KRYLOV_MAX + 1),
     * allocated with the points, the rest once); the Ritz vectors of the energies (2 x 3 np) */
    windows_arnoldi ke;
    double *ritz;
    lapack_int dlwork;
    size_t hm;                /* Arnoldi steps of the last spectrum (0: it was dense) */
    /* the dense fall-back: the block (3 np)^2, eigenvectors, right-hand sides (4 np x 3 np) */
    double *dc, *dvr, *dx, *dre, *dim, *dwork;
    size_t dcap;
    windows_arnoldi kr;       /* the window search's Arnoldi iteration (3 np) */
};

/* A banded matrix in LAPACK's band storage (dgbtrf: ldab >= 2 kl + ku + 1, the kl rows of fill
 * zero), its pivots, and per column the extents of its LU factors (band_lu). */
typedef struct cstab_band {
    double *a;
    size_t n, kl, ku, ldab;
    lapack_int *ipiv;
    size_t *lnz, *unz; /* per column: the last nonzero multiplier of L, the farthest nonzero of U
                          above the diagonal (offsets); n each */
} cstab_band;

/* Entry (j, k) of the differentiation matrix of element e (local indices). */
static inline double dmat(const whirl_cstab *w, size_t e, size_t j, size_t k)
{
    const size_t P = (size_t)w->p.degree + 1;
    return w->dref[j * P + k] / (w->brk[e + 1] - w->brk[e]);
}

/* ---- continuum_stability.c ---- */

/* The most points memory_mb holds. */
size_t cstab_points_max(const whirl_cstab *w);

/* Room for the dense fall-back of np points (CS_DENSE_POINTS at most). */
int cstab_reserve_dense(whirl_cstab *w, size_t np);

/* Room for np points. */
int cstab_reserve(whirl_cstab *w, size_t np);

/* The points of the elements brk[0..ne] (np = ne (p + 1)) and their quadrature weights. */
void cstab_set_points(whirl_cstab *w);

/* ---- continuum_shape.c ---- */

/* Room for the ends of ne elements and of their halves (3 ne + 2 values). */
int cstab_reserve_elements(whirl_cstab *w, size_t ne);

/* The steady shape of the mode at omega on elements fine enough for it (halved until its
 * Chebyshev tails and the fastest wave's phase are resolved), seeded by the shooting (tip radius
 * tip_r). */
int cstab_solve_shape(whirl_cstab *w, double omega, double tip_r);

/* ---- continuum_pencil.c ---- */

/* b = R B x for x = (u, w, vh) (3 np, field-major), b point-major (4 np). */
void cstab_apply_b(const whirl_cstab *w, const double *x, double *b);

/* LAPACK's dgbtrf on m: the LU factors with partial pivoting in its band storage and pivots
 * (from 1), for dgbtrs and band_solve; 0, or j + 1 if the pivot of column j is zero. The same
 * elimination, unblocked, but each row and column only to its last nonzero (tracked as the fill
 * grows): a row of an element's equations couples only the points of the element (and its
 * neighbours' ends), so that about half of the band stays zero and the updates are some four
 * times fewer than those of the full band. */
int cstab_band_lu(const cstab_band *m);

/* b = (P L U)^-1 b with the factors of band_lu: the two triangular solves of LAPACK's dgbtrs for
 * one right-hand side (the row interchanges and the multipliers of each column of L, then U by
 * columns), the same operations in the same order, but each column only to its extent. */
void cstab_band_solve(const cstab_band *m, double *restrict b);

/* y = the (u, w, vh) rows of (A - s B)^-1 B x, x = (u, w, vh) (3 np): one step of the Arnoldi
 * iteration, with the factors of shifted_lu. */
int cstab_apply(void *data, const double *x, double *y);

/* The banded LU factors of R (A - s B) into w->lu (pivots w->ipiv), R the row equilibration
 * (w->row_a): s = shift, or if that is an eigenvalue shift 1.7^k (k < tries). */
int cstab_shifted_lu(whirl_cstab *w, double shift, int tries);

#endif
