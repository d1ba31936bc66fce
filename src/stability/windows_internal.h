/* The window search of windows_search.c over any source of squared eigenvalues mu = lambda^2
 * of a family of linearisations in omega (the N-link chain's reduced problem, the continuum's
 * collocation): internal to the library. */
#ifndef WHIRL_WINDOWS_INTERNAL_H
#define WHIRL_WINDOWS_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "whirl/stability.h"

/* Re sqrt(mu): the growth rate of the pair lambda = +-sqrt(mu) */
static inline double root_re(double re, double im)
{
    return sqrt(fmax(0, (hypot(re, im) + re) / 2));
}

typedef struct windows_source {
    /* Every mu of the linearisation about the mode's shape at omega, with signatures if asked
     * (whirl_spectrum; pointers valid until the next call). */
    int (*spectrum)(void *data, double omega, int signatures, whirl_spectrum *out);
    /* The two mu nearest the real shift sigma at omega (nearest first), GSL_CONTINUE when they
     * are not obtained that way (the search then uses spectrum); NULL: never. */
    int (*pair)(void *data, double omega, double sigma, double *mu_re, double *mu_im);
    void *data;                  /* passed to both */
    int mode;                    /* for messages */
    whirl_windows_stats *stats;  /* counts of the search (the source counts its shapes) */
} windows_source;

/* Fills out with the count mu (re, im; kept as pointers), the round-off level of the growth, the
 * growth max Re sqrt(mu) (values <= level counted as 0) and, with sig (count, else NULL), the
 * Krein signatures: the sign of energy(data, i) for each neutral mu i, 0 for the others. */
void whirl_windows_classify(whirl_spectrum *out, size_t count, const double *re, const double *im,
                            double level, int *sig, double (*energy)(void *data, size_t i),
                            void *data);

/* Shift-and-invert Arnoldi for the two eigenvalues mu nearest a real shift (Saad 2011, ch. 7): the
 * workspace for vectors of length q, at most WINDOWS_KRYLOV_MAX steps. */
#define WINDOWS_KRYLOV_MAX 40
typedef struct windows_arnoldi {
    size_t q;                   /* vector length */
    size_t km;                  /* most steps (WINDOWS_KRYLOV_MAX unless set at init) */
    double *basis;              /* q x (WINDOWS_KRYLOV_MAX + 1), column j at j * q */
    double *hess;               /* (WINDOWS_KRYLOV_MAX + 1) x WINDOWS_KRYLOV_MAX, column-major */
    double *hcopy, *hre, *him, *hvec, *hwork; /* its eigen-solve */
    int hlwork;
    /* the inner products and norms of a step: 0, one running sum and the norm by hypot (the
     * N-link chain's); 1, four partial sums and the norm as the root of the sum of squares, the
     * vectors normalised above ARNOLDI_BREAKDOWN (the continuum's long O(1) vectors). Each keeps
     * its path's rounding as it was. */
    int blocked;
} windows_arnoldi;

#define ARNOLDI_BREAKDOWN 1e-300 /* a blocked step's norm at or below this: an invariant subspace
                                    (the O(1) vectors' round-off is some 1e-16) */

/* Arnoldi step: v_(step+1) from apply(v_step), orthogonalised (Gram-Schmidt, twice) into column
 * step of the Hessenberg matrix; its norm h_(step+1,step) into *norm. GSL_CONTINUE if apply
 * failed. */
int whirl_windows_arnoldi_step(windows_arnoldi *k, size_t step,
                               int (*apply)(void *data, const double *x, double *y), void *data,
                               double *norm);
/* The Ritz values theta (hre, him) and vectors (hvec, m x m) of the leading m x m Hessenberg
 * block: the LAPACK info. */
int whirl_windows_ritz_values(windows_arnoldi *k, size_t m);
/* The residual |h_(m+1,m) e_m^T s| / |s| of Ritz value i (its vector s: column i, or (re, im) at
 * (i, i + 1) / (i - 1, i) for a complex one). */
double whirl_windows_ritz_residual(const windows_arnoldi *k, size_t m, size_t i, double norm);

/* Allocates the arrays of k for vectors of length q (GSL_ENOMEM; release frees what was got),
 * for WINDOWS_KRYLOV_MAX steps, or km steps (the arrays' sizes below with km). */
int whirl_windows_arnoldi_init(windows_arnoldi *k, size_t q);
int whirl_windows_arnoldi_init_steps(windows_arnoldi *k, size_t q, size_t km);
void whirl_windows_arnoldi_release(windows_arnoldi *k);

/* The two eigenvalues mu = sigma + 1 / theta nearest sigma, theta the eigenvalues of largest
 * modulus of the operator apply(data, x, y): y = (A - sigma)^-1 x (returns GSL_SUCCESS, else
 * GSL_CONTINUE), into mu_re[0..1], mu_im[0..1], nearest first. Converged when both Ritz residuals
 * are below 1e-13 |theta|; GSL_CONTINUE if not within WINDOWS_KRYLOV_MAX steps. */
int whirl_windows_arnoldi_pair(windows_arnoldi *k,
                               int (*apply)(void *data, const double *x, double *y), void *data,
                               double sigma, double *mu_re, double *mu_im);

/* Every eigenvalue theta of largest modulus of the operator apply (y = (A - s)^-1 x, vectors of
 * length k->q, at most k->km steps): the steps go on until every Ritz value with |theta| >= floor
 * has a residual below 1e-12 |theta|, and at least 16 more than there are of them, looking at the
 * Ritz values every eighth of the steps done (at least 4, first at 24). The Ritz values and
 * vectors of the *steps-step factorisation are in k->hre, k->him, k->hvec (basis k->basis).
 * GSL_CONTINUE if not within the steps; GSL_EFAILED (message) if apply or the Ritz values
 * fail; WHIRL_EINTERRUPTED, no message (the caller names the solve), on a stop request. */
int whirl_windows_arnoldi_above(windows_arnoldi *k,
                                int (*apply)(void *data, const double *x, double *y), void *data,
                                double floor, size_t *steps);

/* The scan's rates for mode k born at birth: from max(omega_min, birth (1 + 1e-6)) to omega_max
 * in steps of p->scan_step, both ends included; *omega malloc'ed (caller frees). GSL_EINVAL on
 * bad parameters, GSL_EDOM if the range ends before the birth. */
int whirl_windows_range(const whirl_windows_params *p, int mode, double birth, double **omega,
                        size_t *npts);

/* The windows over the scan omega[0..npts-1] (windows_search.c's header comment; the range's
 * end is p->omega_max). */
int whirl_windows_search(const windows_source *src, const whirl_windows_params *p,
                         const double *omega, size_t npts, whirl_window *windows, size_t max,
                         size_t *count);

/* The mu of the last linearisation in lin (of the chain c at omega) that can collide, by the
 * banded path of nlink_banded.c (its header comment): every mu with |mu| <= omega^2 and
 * the first neutral one beyond, with the signatures if asked. GSL_CONTINUE when that path does
 * not apply or did not converge (the dense whirl_windows_spectrum then gives them), GSL_EINVAL
 * as whirl_windows_spectrum. */
int whirl_windows_spectrum_banded(whirl_windows *w, const whirl_chain *c, double omega,
                                  const whirl_stability *lin, int signatures, whirl_spectrum *out);

/* Evaluations of the last whirl_windows_find where the banded path gave way to the dense one. */
size_t whirl_windows_fallbacks(const whirl_windows *w);

#endif
