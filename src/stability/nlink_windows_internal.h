/* The N-link window search's workspace (nlink_windows.c: the reduced problem and its dense
 * solve; nlink_banded.c: the banded path), shared by its two files: internal to the library. */
#ifndef WHIRL_NLINK_WINDOWS_INTERNAL_H
#define WHIRL_NLINK_WINDOWS_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "core/linalg.h"

#include "whirl/stability.h"
#include "stability/windows_internal.h"

#define WINDOWS_BAND_KRYLOV 240 /* most Arnoldi steps of the banded path */
#define WINDOWS_BAND_START 20   /* steps before its first Ritz values */
#define WINDOWS_BAND_EVERY 10   /* steps between Ritz values */
#define BAND_KL 8               /* sub- and super-diagonals of the augmented matrix */
#define BAND_LD (3 * BAND_KL + 1) /* its LAPACK band storage: 2 kl + ku + 1 rows */
#define BAND_AT(row, col) ((size_t)(2 * BAND_KL + (int)(row) - (int)(col)) + (size_t)(col) * BAND_LD)

struct whirl_windows {
    size_t n;              /* links N */
    whirl_stability *lin;  /* the linearisation */
    double *ma, *mb, *ka, *kb, *gab; /* N x N blocks, row-major */
    double *a;             /* 2N x 2N: A' (row-major), then P A' P; also K' + sigma B */
    double *hv;            /* Householder vector (2N) */
    double hv_tau;         /* its coefficient; 0: no deflation */
    size_t deflated;       /* 1 if the symmetry eigenvalue was removed */
    double *re, *im;       /* mu (2N) */
    int *sig;              /* signatures (2N) */
    double *vl;            /* eigenvectors from dgeev (2N x 2N) */
    double *x;             /* one eigenvector in the full space (2 x 2N: real and imaginary) */
    double *work;          /* dgeev workspace */
    lapack_int lwork;
    lapack_int *ipiv;      /* LU pivots (2N) */
    windows_arnoldi kr;    /* the Arnoldi iteration's workspace (vectors of 2N) */
    double *r, *z, *tension; /* nodes of a shape (N + 1) */
    /* the structured form (header comment) of the last linearisation, per link j */
    double *al, *be, *ga;  /* l_j e1_j . x, l_j e1_j . z, l_j */
    double *tl, *ms;       /* T_j l_j, m_j */
    double *tri;           /* 4N: the tridiagonal matrices of the index and of max |mu| */
    double *ab;            /* banded LU of the augmented K' + sigma B (BAND_LD x 8N) */
    lapack_int *bpiv;      /* its pivots (8N) */
    double *bx;            /* 8N scratch: right-hand side, the sums g */
    double *lv;            /* l = B^T (0, s_b) (2N), then 2N scratch */
    double bomega;         /* the rate of the structured form */
    int fast;              /* 1: scan points by the banded path (p->krylov) */
    size_t bm;             /* steps of the banded path's last Ritz values */
    size_t fallbacks;      /* evaluations where the banded path gave way to the dense one */
    windows_arnoldi kband;   /* the banded path's Arnoldi iteration (WINDOWS_BAND_KRYLOV steps) */
    int *kept;             /* Ritz column of each kept mu (WINDOWS_BAND_KRYLOV) */
    const whirl_chain *chain; /* of the current search */
    int mode;
    double lin_omega;      /* the rate of the linearisation in lin (NAN: none) */
    whirl_windows_stats *stats;
};

/* max(a, b), a if it is NaN (so that a NaN fails the checks below; inline where fmax is a call) */
static inline double dmax(double a, double b) { return a >= b || isnan(a) ? a : b; }

/* The blocks Ma, Mb, Ka, Kb, Gab of the last linearisation in lin, after checking the split
 * (planar, conservative) to round-off. */
int windows_split_blocks(whirl_windows *w, const whirl_stability *lin);

/* The structured form of the last linearisation in lin (nlink_banded.c): 1 if it reproduces the
 * dense blocks, 0 if not (the dense path), -1 on a stop request. */
int windows_structure_of(whirl_windows *w, const whirl_chain *c, double omega,
                         const whirl_stability *lin);

/* The banded LU of the augmented K' + sigma B (LAPACK's info), and y = (A' - sigma)^-1 x with it
 * (nlink_banded.c). */
lapack_int windows_band_factor(whirl_windows *w, double sigma);
int windows_band_apply(void *data, const double *x, double *y);

#endif
