/* Linear stability of the steady shapes of the continuous chain, in the continuum.
 *
 * The chain: uniform, length 1, mass 1, g = 1, a point mass m at its free end; sigma the
 * arclength from the free end (0) to the pivot (1); X(sigma, t) its position in the frame
 * co-rotating at omega about z, T(sigma, t) its tension. Motion (unit density):
 *     X_tt + 2 omega e_z x X_t - omega^2 P X = (T X_sigma)_sigma - e_z,   |X_sigma| = 1,
 * P = diag(1, 1, 0), the pivot fixed, X(1) = 0, and at the free end
 *     m (X_tt + 2 omega e_z x X_t - omega^2 P X + e_z) = T X_sigma   (m = 0: T(0) = 0).
 * Steady shape (continuum.c): X0 = (r, 0, z) in the x-z plane, with the load ratio q = H / W
 * (H the horizontal force of the part below sigma, W = sigma + m its weight),
 *     r' = -q / S,  (sigma + m) q' + q = omega^2 r,  S = sqrt(1 + q^2),  T0 = (sigma + m) S,
 *     r(1) = 0,  q(0) = omega^2 r(0),
 * with the unit tangent t0 = X0_sigma = (r', z') = (-q, 1) / S and normal n0 = (-z', r').
 * Linearisation: X = X0 + (u, v, w) e^(lambda t), T = T0 + tau e^(lambda t):
 *     lambda^2 u - 2 omega lambda v - omega^2 u = (T0 u' + tau r')'
 *     lambda^2 w                               = (T0 w' + tau z')'
 *     lambda^2 v + 2 omega lambda u - omega^2 v = (T0 v')'
 *     r' u' + z' w' = 0   (inextensible),
 * the in-plane motion (u, w, tau) and the out-of-plane v coupled only by the Coriolis terms. With
 * vh = lambda v and the third equation multiplied by lambda (as for the N-link chain in
 * stability_windows.c) this is LINEAR in mu = lambda^2:
 *     mu u = omega^2 u + 2 omega vh + (T0 u' + tau r')'
 *     mu w = (T0 w' + tau z')'
 *     0    = r' u' + z' w'
 *     mu (vh + 2 omega u) = omega^2 vh + (T0 vh')',
 * a real generalised eigenproblem A x = mu B x in x = (u, w, tau, vh) (B singular: the
 * constraint and tau give infinite eigenvalues, dropped). Boundary conditions: u = w = vh = 0 at
 * the pivot; at the free end m (mu u - 2 omega vh - omega^2 u) = T0 u' + tau r',
 * m mu w = T0 w' + tau z', m (mu (vh + 2 omega u) - omega^2 vh) = T0 vh'; with m = 0 these are
 * tau(0) = 0 and, T0(0) = 0 making sigma = 0 a regular singular point, the boundedness of u, w,
 * vh, which collocation at sigma = 0 imposes by itself. In the tangential and normal components
 * p = t0 . xi, q_n = n0 . xi of xi = (u, w) the system has order 6 (p and tau first order, q_n
 * and vh second order): p, q_n, vh are fixed at the pivot, tau at the free end.
 * Hanging chain (r = q = 0, T0 = sigma + m): u solves mu u - omega^2 u - 2 omega vh = (T0 u')'
 * and the inertial frequencies are those of the hanging chain, j_{0,n} / 2 for m = 0
 * (u = J0(2 w sqrt(sigma))), so mu = -(j_{0,n} / 2 +- omega)^2 in the co-rotating frame; with a
 * tip mass the roots of the J0/Y0 determinant of continuum.c.
 *
 * Discretisation: the chain is cut into elements, each with the p + 1 Chebyshev points
 * sigma = a + h (1 - cos(j pi / p)) / 2 (Trefethen, Spectral Methods in MATLAB, 2000, ch. 6:
 * differentiation matrix), the fields collocated at every point, the equations at the points
 * where no condition replaces them. The coefficients T0, r', z' have branch points off the real
 * axis where q = +-i, a distance ~ W / (omega^2 |r|) from the points where the chain hangs
 * vertically (q = 0): about 0.03 for mode 3 at omega = 9, which one Chebyshev interval resolves
 * only with hundreds of points. Elements are halved (starting from four) until the last two
 * Chebyshev coefficients of r and q on each are below shape_tol of their largest value, so that
 * they are small near those points and large elsewhere, and the convergence is geometric in p;
 * and until the phase of the fastest wave kept (element_phase) on each is resolved: near the free
 * end the modes behave as J0(2 Omega sqrt(sigma)), whose Taylor coefficients in sigma fall only
 * once k exceeds Omega sqrt(h) (an element of degree 16 from sigma = 0 had edges 1e-5 off).
 * Conditions, in the rows of the equations they replace (the pattern that makes the counts agree
 * with the orders above): at the right end of an element the equation rows of w, of the
 * constraint and of vh carry n0 . xi, t0 . xi and vh continuous with the next element (zero at
 * the pivot), the row of u carries the tangential equation t0 . (E_u, E_w); at the left end of an
 * element after the first the rows of u, w and vh carry the normal derivative n0 . xi', tau and
 * vh' continuous, the constraint is kept; at the free end (m = 0) the row of u carries the normal
 * equation n0 . (E_u, E_w), the row of w tau = 0 (m > 0: the rows of u, w, vh the tip mass's
 * equations). The steady shape is solved by the same collocation (Newton; r continuous at right
 * ends, q at left ends), seeded by the shooting of continuum.c, whose tip radius it reproduces;
 * the elements for the phase are found from the shooting's shape before any Newton iteration,
 * and each further halving is seeded by the shape interpolated from the previous elements.
 * Structure: with the unknowns ordered point by point (u, w, tau, vh at each point) every row
 * couples only the points of its element and, for the continuity rows at an element's left end,
 * those of the previous one, so A is banded with kl = 4 (p + 1) + 3 sub- and ku = 4 p + 3
 * super-diagonals, and B couples only the fields of one point (4 x 4 blocks). The shifted pencil
 * A - s B is factored by the elimination of LAPACK's banded LU (dgbtrf, partial pivoting:
 * O(np p^2) instead of O(np^3)) in its band storage, each row and column only to its last
 * nonzero (band_lu: within an element's rows about half of the band stays zero), and the steady
 * shape's Newton iteration is banded likewise (2 fields, kl = ku = 2 p + 1).
 * Eigenvalues, in real arithmetic: the columns of tau in B are zero, so the finite mu are
 * mu = s + 1 / theta with theta the eigenvalues of the block of (A - s B)^-1 B on the rows and
 * columns of (u, w, vh) (a real shift s; the constraint's infinite mu become theta = 0), and its
 * eigenvectors are the modes' (u, w, vh). Only the few mu with |mu| <= cut are kept (some tens
 * of the 3 np): they are the theta of largest modulus, which the Arnoldi iteration on that block
 * (shift-and-invert; one banded solve per step, full re-orthogonalisation; Saad 2011, ch. 6-7)
 * finds first; it runs until every Ritz value with |theta| >= 0.8 / (cut + |s|) has a residual
 * |h_{m+1,m} e_m^T y| below 1e-12 |theta| (Ritz pairs: theta and the eigenvector V y), and at
 * least k + 16 steps for k such values. If that takes more than CS_KRYLOV_MAX steps, or on
 * request (solver = 1, the reference), the block is formed in full by 3 np banded solves and all
 * its eigenvalues computed by LAPACK's dgeev (about 100 times the work at 300 points). Against
 * LAPACK's QZ (dggev) on the whole dense pencil (Moler & Stewart 1973) the dense block gives the
 * same mu to 1e-8 relative. The collocation's round-off limits the mu to about 1e-9 relative (the
 * second-derivative matrices of short elements are large).
 * The rotation about z (v = r, u = w = tau = 0, mu = 0) is removed as the kept mu nearest 0.
 * Krein signature of a neutral mu = -w^2 with eigenvector (u, w, tau, vh) (lambda = i w,
 * v = vh / lambda): the mode's energy w^2 <xi, M xi> + <xi, K xi> = 2 w^2 <xi, xi> - i w <xi, G xi>
 * is, up to a factor 2,
 *     E = int (w^2 (|u|^2 + |w|^2) + |vh|^2 + 2 omega Re(conj(u) vh)) dsigma + (m times the
 *         same at sigma = 0),
 * by Clenshaw-Curtis quadrature on each element (Trefethen 2000, ch. 12).
 * Windows (whirl_cstab_windows): the search of stability_windows.c on these spectra, then each
 * closed edge located again as the root of the collision discriminant on refined
 * discretisations (degree + 8, shape_tol / 100; where that moves it by more than 1e-8, degree
 * + 16 and + 24 until two successive levels agree to 1e-8, or the change grows, the round-off of
 * the higher degree: refine_levels): near such an edge the pair
 * separates slowly, dD/domega is small, and an error of mu moves the edge by much more.
 * References: Kolodner 1955, Comm. Pure Appl. Math. 8:395 (the steady shapes); Caughey 1958,
 * J. Appl. Mech. 25:465 (whirling of a heavy chain); Trefethen 2000 (collocation); Mackay 1986
 * (Krein signature); Moler & Stewart 1973, SIAM J. Numer. Anal. 10:241 (QZ). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/linalg.h"

#include "whirl/continuum_stability.h"
#include "core/error.h"
#include "core/roots.h"
#include "core/worker.h"
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
    /* the Arnoldi iteration of the spectrum: basis (3 np x (CS_KRYLOV_MAX + 1)), Hessenberg
     * matrix, its eigen-solve; the Ritz vectors of the energies (2 x 3 np) */
    double *basis, *hess, *hcopy, *hre, *him, *hvec, *hwork, *ritz;
    lapack_int hlwork, dlwork;
    size_t hm;                /* Arnoldi steps of the last spectrum (0: it was dense) */
    /* the dense fall-back: the block (3 np)^2, eigenvectors, right-hand sides (4 np x 3 np) */
    double *dc, *dvr, *dx, *dre, *dim, *dwork;
    size_t dcap;
    windows_arnoldi kr;       /* the window search's Arnoldi iteration (3 np) */
};

whirl_cstab_params whirl_cstab_defaults(void)
{
    whirl_cstab_params p = {16, 0, 1e-11, 30, 0, 1024};
    return p;
}

static int check_params(const whirl_cstab_params *p)
{
    if (p->degree < 6 || p->degree > 64)
        return whirl_fail(GSL_EINVAL, "the collocation degree must be in 6..64, got %d",
                          p->degree);
    int status = whirl_check_tip_mass(p->tip_mass);
    if (status) return status;
    if (!(p->shape_tol >= 1e-14 && p->shape_tol <= 1e-3))
        return whirl_fail(GSL_EINVAL, "the shape tolerance must be in [1e-14, 1e-3], got %g",
                          p->shape_tol);
    if (!(p->freq_max > 0 && isfinite(p->freq_max)))
        return whirl_fail(GSL_EINVAL, "the highest frequency kept must be > 0, got %g",
                          p->freq_max);
    if (p->solver != 0 && p->solver != 1)
        return whirl_fail(GSL_EINVAL, "the solver must be 0 (Arnoldi) or 1 (dense), got %d",
                          p->solver);
    if (!(p->memory_mb >= 16 && p->memory_mb <= 1048576))
        return whirl_fail(GSL_EINVAL, "the memory bound must be in 16..1048576 MB, got %g",
                          p->memory_mb);
    return GSL_SUCCESS;
}

static void release_dense(whirl_cstab *w)
{
    double *arrays[] = {w->dc, w->dvr, w->dx, w->dre, w->dim, w->dwork};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    w->dc = w->dvr = w->dx = w->dre = w->dim = w->dwork = NULL;
    w->dcap = 0;
}

void whirl_cstab_free(whirl_cstab *w)
{
    if (w == NULL) return;
    double *arrays[] = {w->brk,  w->dref, w->cw,    w->sig,   w->r,     w->q,    w->wq,
                        w->t0,   w->rp,   w->zp,    w->jac,   w->res,   w->ab,   w->bb,
                        w->lu,   w->row_a, w->ra,   w->rb,    w->ta,    w->tb,   w->solve,
                        w->mu_re, w->mu_im, w->ls,  w->lr,    w->lq,    w->basis, w->hess,
                        w->hcopy, w->hre,  w->him,  w->hvec,  w->hwork, w->ritz};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++) free(arrays[i]);
    free(w->ipiv);
    free(w->lnz);
    free(w->unz);
    free(w->kept);
    free(w->sig_out);
    release_dense(w);
    whirl_windows_arnoldi_release(&w->kr);
    free(w);
}

whirl_cstab *whirl_cstab_alloc(const whirl_cstab_params *p)
{
    if (check_params(p)) return NULL;
    whirl_cstab *w = calloc(1, sizeof *w);
    if (w == NULL) goto fail;
    w->p = *p;
    const size_t pp = (size_t)p->degree, P = pp + 1, km = CS_KRYLOV_MAX;
    w->kl = 4 * P + 3;
    w->ku = 4 * pp + 3;
    w->ldab = 2 * w->kl + w->ku + 1;
    w->nkl = 2 * P + 1;
    w->nldab = 3 * w->nkl + 1;
    w->dref = malloc(P * P * sizeof(double));
    w->cw = malloc(P * sizeof(double));
    w->ls = malloc(CS_SAMPLES * sizeof(double));
    w->lr = malloc(CS_SAMPLES * sizeof(double));
    w->lq = malloc(CS_SAMPLES * sizeof(double));
    w->hess = calloc((km + 1) * km, sizeof(double));
    w->hcopy = malloc(km * km * sizeof(double));
    w->hre = malloc(km * sizeof(double));
    w->him = malloc(km * sizeof(double));
    w->hvec = malloc(km * km * sizeof(double));
    if (!w->dref || !w->cw || !w->ls || !w->lr || !w->lq || !w->hess || !w->hcopy || !w->hre ||
        !w->him || !w->hvec)
        goto fail;
    double size;
    if (whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)km, w->hcopy, (lapack_int)km,
                           w->hre, w->him, NULL, 1, w->hvec, (lapack_int)km, &size, -1) != 0)
        goto fail;
    w->hlwork = (lapack_int)size;
    if ((w->hwork = malloc((size_t)w->hlwork * sizeof(double))) == NULL) goto fail;
    /* Chebyshev points x_j = cos(j pi / p) (Trefethen 2000, cheb.m), t = (1 - x) / 2 on [0, 1]
     * increasing with j, d/dt = -2 d/dx; off-diagonal entries exact, the diagonal as minus the
     * row sum */
    double x[65], c[65];
    for (size_t j = 0; j <= pp; j++) {
        x[j] = j == pp ? -1 : j == 0 ? 1 : sin(M_PI * ((double)pp - 2.0 * (double)j) / (2.0 * (double)pp));
        c[j] = (j == 0 || j == pp ? 2 : 1) * (j % 2 ? -1 : 1);
    }
    for (size_t i = 0; i <= pp; i++) {
        double sum = 0;
        for (size_t j = 0; j <= pp; j++) {
            if (i == j) continue;
            const double d = c[i] / (c[j] * (x[i] - x[j]));
            w->dref[i * P + j] = -2 * d;
            sum += d;
        }
        w->dref[i * P + i] = 2 * sum;
    }
    /* Clenshaw-Curtis weights (Trefethen 2000, clencurt.m), halved for [0, 1] */
    for (size_t j = 0; j <= pp; j++) {
        const double th = M_PI * (double)j / (double)pp;
        double v = 1;
        if (j == 0 || j == pp) {
            w->cw[j] = (pp % 2 == 0 ? 1.0 / ((double)(pp * pp) - 1) : 1.0 / (double)(pp * pp)) / 2;
            continue;
        }
        if (pp % 2 == 0) {
            for (size_t k = 1; k < pp / 2; k++)
                v -= 2 * cos(2 * (double)k * th) / (4 * (double)(k * k) - 1);
            v -= cos((double)pp * th) / ((double)(pp * pp) - 1);
        } else {
            for (size_t k = 1; k <= (pp - 1) / 2; k++)
                v -= 2 * cos(2 * (double)k * th) / (4 * (double)(k * k) - 1);
        }
        w->cw[j] = v / (double)pp;
    }
    return w;
fail:
    whirl_cstab_free(w);
    whirl_fail(GSL_ENOMEM, "out of memory for the continuum's stability workspace");
    return NULL;
}

/* Bytes of the workspace per collocation point (the bound on the points is memory_mb over
 * this): the pencil's band and its LU, the Newton band, the Arnoldi basis, the vectors, the
 * LU's extents. */
static size_t bytes_per_point(const whirl_cstab *w)
{
    const size_t band = N_FIELDS * (w->ldab + (w->kl + w->ku + 1)) + 2 * w->nldab;
    const size_t krylov = N_DYNAMIC * (CS_KRYLOV_MAX + 3);
    const size_t extents = 2 * N_FIELDS * sizeof(size_t) / sizeof(double); /* lnz, unz */
    return (band + krylov + 16 + 14 * N_FIELDS + 12 + extents) * sizeof(double);
}

/* The most points memory_mb holds. */
static size_t points_max(const whirl_cstab *w)
{
    return (size_t)(w->p.memory_mb * 1048576.0 / (double)bytes_per_point(w));
}

/* Room for np points. */
static int reserve(whirl_cstab *w, size_t np)
{
    if (np <= w->cap) return GSL_SUCCESS;
    const size_t n = N_FIELDS * np, ny = N_DYNAMIC * np;
    double **per_point[] = {&w->sig, &w->r, &w->q, &w->wq, &w->t0, &w->rp, &w->zp};
    double **vec[] = {&w->row_a, &w->ra, &w->rb, &w->ta, &w->tb, &w->solve, &w->mu_re, &w->mu_im};
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++) free(*per_point[i]);
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) free(*vec[i]);
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++)
        *per_point[i] = malloc(np * sizeof(double));
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) *vec[i] = calloc(n, sizeof(double));
    free(w->jac), free(w->res), free(w->ipiv), free(w->sig_out), free(w->kept);
    free(w->lnz), free(w->unz);
    free(w->ab), free(w->bb), free(w->lu), free(w->basis), free(w->ritz);
    w->jac = malloc(w->nldab * 2 * np * sizeof(double));
    w->res = malloc(2 * np * sizeof(double));
    w->ipiv = malloc(n * sizeof(lapack_int));
    w->lnz = malloc(n * sizeof(size_t));
    w->unz = malloc(n * sizeof(size_t));
    w->sig_out = malloc(n * sizeof(int));
    w->kept = malloc(n * sizeof(size_t));
    w->ab = malloc(w->ldab * n * sizeof(double));
    w->bb = malloc(N_FIELDS * N_FIELDS * np * sizeof(double));
    w->lu = malloc(w->ldab * n * sizeof(double));
    w->basis = malloc(ny * (CS_KRYLOV_MAX + 1) * sizeof(double));
    w->ritz = malloc(2 * ny * sizeof(double));
    w->cap = 0;
    int ok = w->jac && w->res && w->ipiv && w->lnz && w->unz && w->sig_out && w->kept && w->ab &&
             w->bb && w->lu &&
             w->basis && w->ritz;
    for (size_t i = 0; i < sizeof per_point / sizeof per_point[0]; i++) ok = ok && *per_point[i];
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++) ok = ok && *vec[i];
    if (!ok) return whirl_fail(GSL_ENOMEM, "out of memory for %zu collocation points", np);
    w->cap = np;
    return GSL_SUCCESS;
}

/* Room for the dense fall-back of np points (CS_DENSE_POINTS at most). */
static int reserve_dense(whirl_cstab *w, size_t np)
{
    if (np <= w->dcap) return GSL_SUCCESS;
    if (np > CS_DENSE_POINTS)
        return whirl_fail(GSL_EMAXITER, "the dense eigen-solve of %zu collocation points is "
                                        "beyond its bound of %d points", np, CS_DENSE_POINTS);
    release_dense(w);
    const size_t n = N_FIELDS * np, ny = N_DYNAMIC * np;
    w->dc = malloc(ny * ny * sizeof(double));
    w->dvr = malloc(ny * ny * sizeof(double));
    w->dx = malloc(n * ny * sizeof(double));
    w->dre = malloc(ny * sizeof(double));
    w->dim = malloc(ny * sizeof(double));
    if (!w->dc || !w->dvr || !w->dx || !w->dre || !w->dim)
        return whirl_fail(GSL_ENOMEM, "out of memory for the dense eigen-solve of %zu points", np);
    double size;
    lapack_int info = whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)ny, w->dc,
                                         (lapack_int)ny, w->dre, w->dim, NULL, 1, w->dvr,
                                         (lapack_int)ny, &size, -1);
    if (info != 0) return whirl_fail(GSL_EFAILED, "dgeev workspace query failed (%d)", (int)info);
    w->dlwork = (lapack_int)size;
    w->dwork = malloc((size_t)size * sizeof(double));
    if (w->dwork == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the eigen-solver");
    w->dcap = np;
    return GSL_SUCCESS;
}

/* The points of the elements brk[0..ne] (np = ne (p + 1)) and their quadrature weights. */
static void set_points(whirl_cstab *w)
{
    const size_t P = (size_t)w->p.degree + 1;
    for (size_t e = 0; e < w->ne; e++) {
        const double a = w->brk[e], h = w->brk[e + 1] - a;
        for (size_t j = 0; j < P; j++) {
            /* t_j = (1 - cos(j pi / p)) / 2 = sin^2(j pi / (2 p)) */
            const double s = sin(M_PI * (double)j / (2.0 * (double)(P - 1)));
            w->sig[e * P + j] = j == P - 1 ? w->brk[e + 1] : a + h * s * s;
            w->wq[e * P + j] = h * w->cw[j];
        }
    }
}

/* Entry (j, k) of the differentiation matrix of element e (local indices). */
static double dmat(const whirl_cstab *w, size_t e, size_t j, size_t k)
{
    const size_t P = (size_t)w->p.degree + 1;
    return w->dref[j * P + k] / (w->brk[e + 1] - w->brk[e]);
}

/* ---- banded LU ---- */

/* A banded matrix in LAPACK's band storage (dgbtrf: ldab >= 2 kl + ku + 1, the kl rows of fill
 * zero), its pivots, and per column the extents of its LU factors (band_lu). */
typedef struct band {
    double *a;
    size_t n, kl, ku, ldab;
    lapack_int *ipiv;
    size_t *lnz, *unz; /* per column: the last nonzero multiplier of L, the farthest nonzero of U
                          above the diagonal (offsets); n each */
} band;

/* LAPACK's dgbtrf on m: the LU factors with partial pivoting in its band storage and pivots
 * (from 1), for dgbtrs and band_solve; 0, or j + 1 if the pivot of column j is zero. The same
 * elimination, unblocked, but each row and column only to its last nonzero (tracked as the fill
 * grows): a row of an element's equations couples only the points of the element (and its
 * neighbours' ends), so that about half of the band stays zero and the updates are some four
 * times fewer than those of the full band. */
static int band_lu(const band *m)
{
    const size_t n = m->n, kl = m->kl, ku = m->ku, kd = kl + ku, ldab = m->ldab;
    double *restrict a = m->a;
    size_t *bottom = m->lnz, *right = m->unz; /* the last nonzero row of a column, column of a row */
#define A(r, c) a[kd + (r) - (c) + (c) * ldab]
    for (size_t c = 0; c < n; c++) {
        size_t r = c + kl < n - 1 ? c + kl : n - 1;
        while (r > c && A(r, c) == 0) r--;
        bottom[c] = r;
    }
    for (size_t r = 0; r < n; r++) {
        size_t c = r + ku < n - 1 ? r + ku : n - 1;
        while (c > r && A(r, c) == 0) c--;
        right[r] = c;
    }
    for (size_t j = 0; j < n; j++) {
        const size_t last = bottom[j] > j ? bottom[j] : j; /* rows j..last of column j */
        size_t p = j;
        double big = fabs(A(j, j));
        for (size_t r = j + 1; r <= last; r++)
            if (fabs(A(r, j)) > big) big = fabs(A(r, j)), p = r;
        m->ipiv[j] = (lapack_int)(p + 1);
        if (big == 0) return (int)j + 1;
        if (p != j) {
            const size_t end = right[j] > right[p] ? right[j] : right[p];
            for (size_t c = j; c <= end; c++) {
                const double t = A(j, c);
                A(j, c) = A(p, c), A(p, c) = t;
                if (t != 0 && bottom[c] < p) bottom[c] = p; /* row j's entries moved down to p */
            }
            const size_t t = right[j];
            right[j] = right[p], right[p] = t;
        }
        const double inv = 1 / A(j, j);
        double *restrict l = &A(j + 1, j);
        for (size_t i = 0; i < last - j; i++) l[i] *= inv;
        for (size_t c = j + 1; c <= right[j]; c++) {
            const double t = A(j, c);
            if (t == 0) continue;
            double *restrict col = &A(j + 1, c);
            for (size_t i = 0; i < last - j; i++) col[i] -= l[i] * t;
            if (bottom[c] < last) bottom[c] = last;
        }
        for (size_t r = j + 1; r <= last; r++)
            if (right[r] < right[j]) right[r] = right[j];
    }
#undef A
    for (size_t col = 0; col < n; col++) { /* the extents of the factors' columns */
        const double *c = a + col * ldab;
        size_t l = kl, u = kd;
        while (l > 0 && c[kd + l] == 0) l--;
        while (u > 0 && c[kd - u] == 0) u--;
        m->lnz[col] = l, m->unz[col] = u;
    }
    return 0;
}

/* b = (P L U)^-1 b with the factors of band_lu: the two triangular solves of LAPACK's dgbtrs for
 * one right-hand side (the row interchanges and the multipliers of each column of L, then U by
 * columns), the same operations in the same order, but each column only to its extent. */
static void band_solve(const band *m, double *restrict b)
{
    const size_t n = m->n, kl = m->kl, kd = m->kl + m->ku, ldab = m->ldab;
    const double *restrict lu = m->a;
    for (size_t j = 0; j + 1 < n; j++) {
        const size_t l = (size_t)m->ipiv[j] - 1, lm = kl < n - 1 - j ? kl : n - 1 - j;
        if (l != j) {
            const double t = b[l];
            b[l] = b[j], b[j] = t;
        }
        const double bj = b[j], *col = lu + kd + 1 + j * ldab;
        double *out = b + j + 1;
        const size_t end = m->lnz[j] < lm ? m->lnz[j] : lm;
        if (bj != 0)
            for (size_t i = 0; i < end; i++) out[i] -= col[i] * bj;
    }
    for (size_t j = n; j-- > 0;) {
        const double *col = lu + j * ldab; /* col[kd] the diagonal, col[kd - i] row j - i */
        b[j] /= col[kd];
        const double bj = b[j];
        const size_t lim = m->unz[j] < j ? m->unz[j] : j;
        if (bj != 0)
            for (size_t i = 1; i <= lim; i++) b[j - i] -= col[kd - i] * bj;
    }
}

/* ---- the steady shape by collocation ---- */

/* The shooting's shape at CS_SAMPLES arclengths from the free end: sigma, r and q (the load
 * ratio H / W from the trapezoidal integral of omega^2 r). */
static int sample_shape(whirl_cstab *w, double omega, double tip_r)
{
    const size_t ns = CS_SAMPLES;
    double *s = w->ls, *r = w->lr, *z = w->lq, *ten = malloc(ns * sizeof(double));
    if (ten == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = whirl_continuum_sample(omega, w->p.tip_mass, tip_r, ns, s, r, z, ten);
    free(ten);
    if (status) return status;
    /* reversed: from the free end */
    for (size_t i = 0; i < ns / 2; i++) {
        double t = r[i];
        r[i] = r[ns - 1 - i], r[ns - 1 - i] = t;
    }
    const double m = w->p.tip_mass, w2 = omega * omega;
    double h = m * w2 * r[0];
    for (size_t i = 0; i < ns; i++) {
        s[i] = (double)i / (double)(ns - 1);
        if (i > 0) h += w2 * (r[i] + r[i - 1]) / 2 * (s[i] - s[i - 1]);
        w->lq[i] = s[i] + m > 0 ? h / (s[i] + m) : w2 * r[0];
    }
    return GSL_SUCCESS;
}

/* The samples interpolated linearly at the points. */
static void seed_shape(whirl_cstab *w)
{
    const size_t ns = CS_SAMPLES;
    for (size_t g = 0; g < w->np; g++) {
        const double x = w->sig[g] * (double)(ns - 1);
        size_t i = (size_t)x;
        if (i >= ns - 1) i = ns - 2;
        const double f = x - (double)i;
        w->r[g] = w->lr[i] + f * (w->lr[i + 1] - w->lr[i]);
        w->q[g] = w->lq[i] + f * (w->lq[i + 1] - w->lq[i]);
    }
}

/* Newton's method on the collocation equations of the shape (header comment); the unknowns
 * and equations point by point, (r, q) at each, so the Jacobian is banded. */
static int newton_shape(whirl_cstab *w, double omega)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, nn = 2 * np, kl = w->nkl;
    const size_t ldab = w->nldab;
    const double m = w->p.tip_mass, w2 = omega * omega;
    double *jac = w->jac, *f = w->res, last = HUGE_VAL;
    for (int iter = 0; iter < CS_NEWTON_MAX; iter++) {
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "the shape at omega = " WHIRL_Q_RATE
                              "%g: stopped by request", omega);
        memset(jac, 0, ldab * nn * sizeof(double));
#define J(i, k) jac[2 * kl + (i) - (k) + (k) * ldab]
        for (size_t e = 0; e < w->ne; e++)
            for (size_t j = 0; j < P; j++) {
                const size_t g = e * P + j, ir = 2 * g, iq = 2 * g + 1;
                const double s = sqrt(1 + w->q[g] * w->q[g]);
                /* r row: r' + q / S, or r continuous / zero at the right end */
                if (j == P - 1) {
                    f[ir] = w->r[g] - (e + 1 < w->ne ? w->r[g + 1] : 0);
                    J(ir, 2 * g) = 1;
                    if (e + 1 < w->ne) J(ir, 2 * (g + 1)) = -1;
                } else {
                    double d = 0;
                    for (size_t k = 0; k < P; k++) {
                        const double dk = dmat(w, e, j, k);
                        d += dk * w->r[e * P + k];
                        J(ir, 2 * (e * P + k)) += dk;
                    }
                    f[ir] = d + w->q[g] / s;
                    J(ir, 2 * g + 1) += 1 / (s * s * s);
                }
                /* q row: (sigma + m) q' + q - omega^2 r, or q continuous / the tip condition
                 * at the left end */
                if (j == 0) {
                    if (e == 0) {
                        f[iq] = w->q[g] - w2 * w->r[g];
                        J(iq, 2 * g + 1) = 1;
                        J(iq, 2 * g) = -w2;
                    } else {
                        f[iq] = w->q[g] - w->q[g - 1];
                        J(iq, 2 * g + 1) = 1;
                        J(iq, 2 * (g - 1) + 1) = -1;
                    }
                } else {
                    const double wt = w->sig[g] + m;
                    double d = 0;
                    for (size_t k = 0; k < P; k++) {
                        const double dk = dmat(w, e, j, k);
                        d += dk * w->q[e * P + k];
                        J(iq, 2 * (e * P + k) + 1) += wt * dk;
                    }
                    f[iq] = wt * d + w->q[g] - w2 * w->r[g];
                    J(iq, 2 * g + 1) += 1;
                    J(iq, 2 * g) -= w2;
                }
            }
#undef J
        const band jb = {jac, nn, kl, kl, ldab, w->ipiv, w->lnz, w->unz};
        const int info = band_lu(&jb);
        if (info != 0)
            return whirl_fail(GSL_EFAILED, "the collocation of the shape at omega = "
                              WHIRL_Q_RATE "%g is singular (zero pivot in column %d)", omega, info);
        band_solve(&jb, f);
        double step = 0, scale = 1;
        for (size_t g = 0; g < np; g++) {
            w->r[g] -= f[2 * g];
            w->q[g] -= f[2 * g + 1];
            if (!isfinite(w->r[g]) || !isfinite(w->q[g]))
                return whirl_fail(GSL_ERANGE, "the collocation of the shape at omega = "
                                  WHIRL_Q_RATE "%g diverged", omega);
            step = fmax(step, fmax(fabs(f[2 * g]), fabs(f[2 * g + 1])));
            scale = fmax(scale, fabs(w->q[g]));
        }
        /* converged: the step below 1e-13, or the next one predicted below it (the rate
         * step / last, on the safe side of Newton's quadratic convergence) */
        if (step <= 1e-13 * scale || (step <= 1e-8 * scale && step * (step / last) <= 1e-13 * scale))
            return GSL_SUCCESS;
        last = step;
    }
    return whirl_fail(GSL_EMAXITER, "the collocation of the shape at omega = " WHIRL_Q_RATE "%g "
                      "did not converge in %d Newton steps", omega, CS_NEWTON_MAX);
}

/* The largest of the last two Chebyshev coefficients of f on element e over scale. */
static double tail(const whirl_cstab *w, const double *f, size_t e, double scale)
{
    const size_t pp = (size_t)w->p.degree;
    double big = 0;
    for (size_t k = pp - 1; k <= pp; k++) {
        double c = 0;
        for (size_t j = 0; j <= pp; j++) {
            const double v = f[e * (pp + 1) + j] * cos(M_PI * (double)(k * j) / (double)pp);
            c += j == 0 || j == pp ? v / 2 : v;
        }
        c *= (k == pp ? 1.0 : 2.0) / (double)pp;
        big = fmax(big, fabs(c));
    }
    return scale > 0 ? big / scale : 0;
}

/* The largest phase of a wave on one element that degree p resolves to sqrt(shape_tol): the
 * Chebyshev coefficients of sin(phi x / 2) on [-1, 1] fall as (phi / 2)^k / k!, so
 * phi = 2 (sqrt(shape_tol) p!)^(1 / p) (6.1 for p = 16 and 1e-11). The highest frequencies kept
 * need only be resolved enough to be ranked; those of the colliding pairs, lower, are then
 * resolved much better (for a wave of a third of that phase the coefficients fall to 1e-12). */
static double element_phase_max(const whirl_cstab *w)
{
    const double p = w->p.degree;
    return 2 * exp((0.5 * log(w->p.shape_tol) + lgamma(p + 1)) / p);
}

/* An upper bound of the phase int Omega / sqrt(T0) dsigma on element e of the waves kept
 * (Omega = max(freq_max, 3 omega) + omega, the highest frequency kept in the inertial frame):
 * T0 = (sigma + m) S >= (sigma + m) min S, so the phase is at most
 * 2 Omega (sqrt(b + m) - sqrt(a + m)) / sqrt(min S) (finite at the free end, where T0 = 0 and the
 * modes behave as J0(2 Omega sqrt(sigma))). */
static double element_phase(const whirl_cstab *w, double omega, size_t e)
{
    const size_t P = (size_t)w->p.degree + 1;
    const double big = fmax(w->p.freq_max, 3 * omega) + omega, m = w->p.tip_mass;
    double smin = HUGE_VAL;
    for (size_t j = 0; j < P; j++) smin = fmin(smin, sqrt(1 + w->q[e * P + j] * w->q[e * P + j]));
    return 2 * big * (sqrt(w->brk[e + 1] + m) - sqrt(w->brk[e] + m)) / sqrt(smin);
}

/* Room for the ends of ne elements and of their halves (3 ne + 2 values). */
static int reserve_elements(whirl_cstab *w, size_t ne)
{
    const size_t need = 3 * ne + 2;
    if (need <= w->ecap) return GSL_SUCCESS;
    double *b = realloc(w->brk, 2 * need * sizeof(double));
    if (b == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu elements", ne);
    w->brk = b;
    w->ecap = 2 * need;
    return GSL_SUCCESS;
}

/* The shape of the previous element set (ends obrk[0..one], r and q at its points) at the
 * points of the current one, each of whose elements lies inside one previous element (the
 * refinement only halves): the barycentric formula on the Chebyshev points (Berrut & Trefethen
 * 2004, SIAM Rev. 46:501; weights (-1)^j, halved at the ends), exact to the tails. */
static void interpolate_shape(whirl_cstab *w, const double *obrk, size_t one, const double *orr,
                              const double *oq)
{
    const size_t P = (size_t)w->p.degree + 1;
    size_t oe = 0;
    for (size_t g = 0; g < w->np; g++) {
        const size_t e = g / P;
        const double mid = (w->brk[e] + w->brk[e + 1]) / 2;
        while (oe + 1 < one && obrk[oe + 1] <= mid) oe++;
        const double a = obrk[oe], x = (w->sig[g] - a) / (obrk[oe + 1] - a);
        double nr = 0, nq = 0, den = 0;
        size_t j = 0;
        for (; j < P; j++) {
            const double st = sin(M_PI * (double)j / (2.0 * (double)(P - 1))), d = x - st * st;
            if (d == 0) break;
            const double c = (j % 2 ? -1.0 : 1.0) * (j == 0 || j == P - 1 ? 0.5 : 1.0) / d;
            nr += c * orr[oe * P + j], nq += c * oq[oe * P + j], den += c;
        }
        w->r[g] = j < P ? orr[oe * P + j] : nr / den;
        w->q[g] = j < P ? oq[oe * P + j] : nq / den;
    }
}

/* The ends of the elements halved where keep(w, omega, e) is false, into w->brk + ne + 1
 * (reserve_elements first); *nb the count of new ends. */
static void halve(whirl_cstab *w, double omega, int all,
                  int (*keep)(const whirl_cstab *w, double omega, size_t e, double sr, double sq),
                  double sr, double sq, size_t *nb)
{
    double *brk = w->brk + w->ne + 1;
    size_t n = 0;
    brk[n++] = 0;
    for (size_t e = 0; e < w->ne; e++) {
        if (all || !keep(w, omega, e, sr, sq)) brk[n++] = (w->brk[e] + w->brk[e + 1]) / 2;
        brk[n++] = w->brk[e + 1];
    }
    *nb = n;
}

/* The phase of the fastest wave kept resolved on element e (element_phase). */
static int phase_resolved(const whirl_cstab *w, double omega, size_t e, double sr, double sq)
{
    (void)sr, (void)sq;
    return element_phase(w, omega, e) <= element_phase_max(w);
}

/* The shape resolved on element e: its tails below shape_tol, and the phase resolved. */
static int shape_resolved(const whirl_cstab *w, double omega, size_t e, double sr, double sq)
{
    return fmax(tail(w, w->r, e, sr), tail(w, w->q, e, sq)) <= w->p.shape_tol &&
           phase_resolved(w, omega, e, sr, sq);
}

/* The failure of (nb - 1) elements beyond the memory bound; why: the reason of the last
 * refinement ("" if none). */
static int too_many_points(const whirl_cstab *w, double omega, size_t nb, const char *why)
{
    const size_t P = (size_t)w->p.degree + 1;
    return whirl_fail(GSL_EMAXITER, "mode %d at omega = " WHIRL_Q_RATE "%g needs %zu "
                      "collocation points (elements of degree %d, shape tolerance %g%s%s), "
                      "more than the %zu that %g MB hold: lower the rate or raise the "
                      "memory bound", w->mode, omega,
                      (nb - 1) * P, w->p.degree, w->p.shape_tol, *why ? "; " : "", why,
                      points_max(w), w->p.memory_mb);
}

/* The shape on elements refined until the tails meet shape_tol. First, from the shooting's
 * shape alone (no Newton iteration), the elements are halved until the phase of the fastest
 * wave kept is resolved (that bound needs S only to a few digits). Then Newton's method, and
 * the elements whose tails or phase fail are halved, the next Newton iteration seeded by the
 * shape interpolated from the previous elements (its error is that of the tails, so one or two
 * iterations suffice). On too coarse elements Newton's method may fail or find another
 * solution of the collocation equations (the hanging chain, or a shape of no mode): then (a tip
 * radius 25% off the shooting's), or where the resolved tip radius differs from the shooting's
 * by more than max(1e-7, 1e3 shape_tol) relative, every element is halved and seeded by the
 * shooting again. The points are bounded by the memory bound (points_max); old (*cap doubles)
 * holds the previous element set. */
static int solve_shape_in(whirl_cstab *w, double omega, double tip_r, double **old, size_t *cap)
{
    int status = sample_shape(w, omega, tip_r);
    if (status) return status;
    w->ne = CS_ELEMENTS_START;
    if ((status = reserve_elements(w, w->ne))) return status;
    for (size_t e = 0; e <= w->ne; e++) w->brk[e] = (double)e / (double)w->ne;
    const size_t P = (size_t)w->p.degree + 1;
    size_t nb = 0, one = 0; /* one: elements of the previous set to interpolate (0: none) */
    for (;;) { /* the phase, from the shooting's shape */
        if (w->ne * P > points_max(w)) return too_many_points(w, omega, w->ne + 1, "");
        w->np = w->ne * P;
        if ((status = reserve(w, w->np)) || (status = reserve_elements(w, w->ne))) return status;
        set_points(w);
        seed_shape(w);
        halve(w, omega, 0, phase_resolved, 0, 0, &nb);
        if (nb == w->ne + 1) break;
        memmove(w->brk, w->brk + w->ne + 1, nb * sizeof(double));
        w->ne = nb - 1;
    }
    const char *why = "";
    for (;;) {
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "the shape at omega = " WHIRL_Q_RATE "%g: "
                              "stopped by request", omega);
        w->np = w->ne * P;
        if ((status = reserve(w, w->np))) return status;
        set_points(w);
        if (one) {
            const double *o = *old;
            interpolate_shape(w, o, one, o + one + 1, o + one + 1 + one * P);
        } else {
            seed_shape(w);
        }
        status = newton_shape(w, omega);
        if (status == WHIRL_EINTERRUPTED || status == GSL_ENOMEM) return status;
        /* another solution: 25% off the shooting's tip radius; at the end max(1e-7, 1e3 tol) */
        const double off = fabs(w->r[0] - tip_r) / tip_r;
        int wrong = status || !(off <= 0.25);
        double sr = 0, sq = 0;
        for (size_t g = 0; g < w->np && !wrong; g++)
            sr = fmax(sr, fabs(w->r[g])), sq = fmax(sq, fabs(w->q[g]));
        if ((status = reserve_elements(w, w->ne))) return status;
        for (int pass = 0; pass < 2; pass++) {
            halve(w, omega, wrong, shape_resolved, sr, sq, &nb);
            if (nb > w->ne + 1 || wrong) break;
            if (off <= fmax(1e-7, 1e3 * w->p.shape_tol)) return GSL_SUCCESS;
            wrong = 1; /* resolved, yet not the shooting's shape: every element halved */
        }
        why = status ? "Newton's method failed" : wrong ? "not the shooting's shape" : "";
        if ((nb - 1) * P > points_max(w)) return too_many_points(w, omega, nb, why);
        one = 0;
        if (!wrong) { /* the next seed: this shape */
            const size_t need = w->ne + 1 + 2 * w->np;
            if (need > *cap) {
                double *o = realloc(*old, 2 * need * sizeof(double));
                if (o == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the shape");
                *old = o, *cap = 2 * need;
            }
            memcpy(*old, w->brk, (w->ne + 1) * sizeof(double));
            memcpy(*old + w->ne + 1, w->r, w->np * sizeof(double));
            memcpy(*old + w->ne + 1 + w->np, w->q, w->np * sizeof(double));
            one = w->ne;
        }
        memmove(w->brk, w->brk + w->ne + 1, nb * sizeof(double));
        w->ne = nb - 1;
    }
}

static int solve_shape(whirl_cstab *w, double omega, double tip_r)
{
    double *old = NULL;
    size_t cap = 0;
    const int status = solve_shape_in(w, omega, tip_r, &old, &cap);
    free(old);
    return status;
}

/* ---- the pencil ---- */

/* The interior equation of field eq at point g (element e, local j) into the rows ra, rb
 * (field-major, zero on entry). */
static void equation_row(const whirl_cstab *w, int eq, size_t e, size_t j, double *ra, double *rb)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, g = e * P + j;
    const double om = w->omega, w2 = om * om;
    if (eq == F_TAU) { /* constraint r' u' + z' w' = 0 */
        for (size_t k = 0; k < P; k++) {
            const double d = dmat(w, e, j, k);
            ra[F_U * np + e * P + k] = w->rp[g] * d;
            ra[F_W * np + e * P + k] = w->zp[g] * d;
        }
        return;
    }
    /* (T0 f')' = sum_l D_jl T0_l sum_k D_lk f_k on the element (D = dref / h; the row is zero
     * on entry) */
    const int f = eq;
    const double h = w->brk[e + 1] - w->brk[e], ih2 = 1 / (h * h);
    double *out = ra + f * np + e * P;
    for (size_t l = 0; l < P; l++) {
        const double djl = w->dref[j * P + l] * w->t0[e * P + l], *dl = w->dref + l * P;
        for (size_t k = 0; k < P; k++) out[k] += djl * dl[k];
    }
    for (size_t k = 0; k < P; k++) out[k] *= ih2;
    rb[f * np + g] = 1;
    if (eq == F_U || eq == F_W) { /* + (tau r')' or (tau z')' */
        const double *c = eq == F_U ? w->rp : w->zp;
        for (size_t k = 0; k < P; k++) ra[F_TAU * np + e * P + k] = dmat(w, e, j, k) * c[e * P + k];
    }
    if (eq == F_U) {
        ra[F_U * np + g] += w2;
        ra[F_V * np + g] += 2 * om;
    }
    if (eq == F_V) {
        ra[F_V * np + g] += w2;
        rb[F_U * np + g] = 2 * om;
    }
}

/* The points whose columns a row of element e may touch: those of the previous element (the
 * continuity of derivatives at its left end), its own, the first of the next. */
static void window(const whirl_cstab *w, size_t e, size_t *lo, size_t *hi)
{
    const size_t P = (size_t)w->p.degree + 1;
    *lo = e > 0 ? (e - 1) * P : 0;
    *hi = (e + 1) * P < w->np ? (e + 1) * P : w->np - 1;
}

/* Row (f, g) of the pencil from the field-major rows ra, rb (zeroed again over the window of
 * element e) into the band of A (point-major, LAPACK's layout) and the blocks of B. */
static void store_row(whirl_cstab *w, int f, size_t g, size_t e, double *ra, double *rb)
{
    const size_t np = w->np, off = w->kl + w->ku, i = N_FIELDS * g + (size_t)f;
    size_t lo, hi;
    window(w, e, &lo, &hi);
    for (int c = 0; c < N_FIELDS; c++)
        for (size_t h = lo; h <= hi; h++) {
            const size_t k = (size_t)c * np + h, col = N_FIELDS * h + (size_t)c;
            if (ra[k] != 0) w->ab[off + i - col + col * w->ldab] = ra[k];
            if (rb[k] != 0) w->bb[(g * N_FIELDS + (size_t)f) * N_FIELDS + (size_t)c] = rb[k];
            ra[k] = rb[k] = 0;
        }
}

/* The tangential (sign = +1) or normal (-1) combination of the u and w equations at (e, j). */
static void combined_row(whirl_cstab *w, int tangential, size_t e, size_t j, double *ra,
                         double *rb, double *ta, double *tb)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, g = e * P + j;
    const double cu = tangential ? w->rp[g] : -w->zp[g], cw = tangential ? w->zp[g] : w->rp[g];
    equation_row(w, F_U, e, j, ra, rb);
    equation_row(w, F_W, e, j, ta, tb);
    size_t lo, hi;
    window(w, e, &lo, &hi);
    for (int c = 0; c < N_FIELDS; c++)
        for (size_t h = lo; h <= hi; h++) {
            const size_t k = (size_t)c * np + h;
            ra[k] = cu * ra[k] + cw * ta[k];
            rb[k] = cu * rb[k] + cw * tb[k];
            ta[k] = tb[k] = 0;
        }
}

static void assemble(whirl_cstab *w)
{
    const size_t P = (size_t)w->p.degree + 1, np = w->np, n = N_FIELDS * np;
    const double m = w->p.tip_mass, om = w->omega;
    double *ra = w->ra, *rb = w->rb, *ta = w->ta, *tb = w->tb; /* scratch rows, zero */
    memset(w->ab, 0, w->ldab * n * sizeof(double));
    memset(w->bb, 0, N_FIELDS * N_FIELDS * np * sizeof(double));
    for (size_t e = 0; e < w->ne; e++)
        for (size_t j = 0; j < P; j++) {
            const size_t g = e * P + j;
            for (int f = 0; f < N_FIELDS; f++) {
                if (j == P - 1 && f != F_U) { /* continuity with the next element, or the pivot */
                    const int next = e + 1 < w->ne;
                    if (f == F_V) {
                        ra[F_V * np + g] = 1;
                        if (next) ra[F_V * np + g + 1] = -1;
                    } else { /* F_W: n0 . xi, F_TAU: t0 . xi */
                        const double cu = f == F_W ? -w->zp[g] : w->rp[g];
                        const double cw = f == F_W ? w->rp[g] : w->zp[g];
                        ra[F_U * np + g] = cu, ra[F_W * np + g] = cw;
                        if (next) ra[F_U * np + g + 1] = -cu, ra[F_W * np + g + 1] = -cw;
                    }
                } else if (j == P - 1) { /* F_U at a right end: the tangential equation */
                    combined_row(w, 1, e, j, ra, rb, ta, tb);
                } else if (j == 0 && e > 0 && f != F_TAU) {
                    /* continuity of n0 . xi', tau, vh' with the previous element */
                    if (f == F_W) {
                        ra[F_TAU * np + g - 1] = 1;
                        ra[F_TAU * np + g] = -1;
                    } else {
                        for (size_t k = 0; k < P; k++) {
                            const double dl = dmat(w, e - 1, P - 1, k), dr = dmat(w, e, 0, k);
                            if (f == F_V) {
                                ra[F_V * np + (e - 1) * P + k] += dl;
                                ra[F_V * np + e * P + k] -= dr;
                            } else {
                                ra[F_U * np + (e - 1) * P + k] += -w->zp[g] * dl;
                                ra[F_W * np + (e - 1) * P + k] += w->rp[g] * dl;
                                ra[F_U * np + e * P + k] -= -w->zp[g] * dr;
                                ra[F_W * np + e * P + k] -= w->rp[g] * dr;
                            }
                        }
                    }
                } else if (j == 0 && e == 0 && f != F_TAU && m == 0) { /* the free end */
                    if (f == F_U) {
                        combined_row(w, 0, e, j, ra, rb, ta, tb);
                    } else if (f == F_W) {
                        ra[F_TAU * np + g] = 1;
                    } else {
                        equation_row(w, f, e, j, ra, rb);
                    }
                } else if (j == 0 && e == 0 && f != F_TAU) { /* the tip mass */
                    for (size_t k = 0; k < P; k++) ra[f * np + k] = w->t0[g] * dmat(w, 0, 0, k);
                    rb[f * np + g] = m;
                    if (f == F_U) {
                        ra[F_U * np + g] += m * om * om;
                        ra[F_V * np + g] += 2 * om * m;
                        ra[F_TAU * np + g] += w->rp[g];
                    } else if (f == F_W) {
                        ra[F_TAU * np + g] += w->zp[g];
                    } else {
                        ra[F_V * np + g] += m * om * om;
                        rb[F_U * np + g] = 2 * om * m;
                    }
                } else {
                    equation_row(w, f, e, j, ra, rb);
                }
                store_row(w, f, g, e, ra, rb);
            }
        }
}

int whirl_cstab_linearise(whirl_cstab *w, double omega, int mode, double tip_r_guess,
                          double *tip_r)
{
    if (!(isfinite(omega) && omega >= 0 && omega <= WHIRL_CONTINUUM_OMEGA_MAX) ||
        (mode > 0 && omega == 0))
        return whirl_fail(GSL_EINVAL, "the rate must be in %s..%g, got omega = " WHIRL_Q_RATE "%g",
                          mode > 0 ? "(0" : "[0", WHIRL_CONTINUUM_OMEGA_MAX, omega);
    if (mode < 0 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "the mode must be in 0..%d (0: the hanging chain), got %d",
                          WHIRL_MODE_MAX, mode);
    w->np = 0;
    w->omega = omega;
    w->mode = mode;
    int status;
    if (mode == 0) {
        w->ne = CS_ELEMENTS_START;
        if ((status = reserve_elements(w, w->ne))) return status;
        for (size_t e = 0; e <= w->ne; e++) w->brk[e] = (double)e / (double)w->ne;
        const size_t np = w->ne * ((size_t)w->p.degree + 1);
        if ((status = reserve(w, np))) return status;
        w->np = np;
        set_points(w);
        for (size_t g = 0; g < np; g++) w->r[g] = w->q[g] = 0;
    } else {
        whirl_shape_info info;
        status = whirl_continuum_solve(omega, mode, w->p.tip_mass, tip_r_guess, &info);
        if (!status) status = solve_shape(w, omega, info.tip_r);
        if (status) {
            w->np = 0;
            return status;
        }
    }
    for (size_t g = 0; g < w->np; g++) {
        const double s = sqrt(1 + w->q[g] * w->q[g]);
        w->t0[g] = (w->sig[g] + w->p.tip_mass) * s;
        w->rp[g] = -w->q[g] / s;
        w->zp[g] = 1 / s;
    }
    assemble(w);
    if (tip_r) *tip_r = w->r[0];
    return GSL_SUCCESS;
}

void whirl_cstab_grid(const whirl_cstab *w, size_t *elements, size_t *points)
{
    *elements = w->np ? w->ne : 0;
    *points = w->np;
}

/* E of the header comment for the eigenvector (u, w, vh) (3 np: the fields with a mass) with real
 * part xr and imaginary part xi (NULL: real) at mu = -w2. */
static double mode_energy(const whirl_cstab *w, const double *xr, const double *xi, double w2)
{
    const size_t np = w->np;
    double e = 0;
    for (int part = 0; part < 2; part++) {
        const double *x = part ? xi : xr;
        if (x == NULL) continue;
        for (size_t g = 0; g < np; g++) {
            const double u = x[g], ww = x[np + g], vh = x[2 * np + g];
            const double d = w2 * (u * u + ww * ww) + vh * vh + 2 * w->omega * u * vh;
            e += w->wq[g] * d + (g == 0 ? w->p.tip_mass * d : 0);
        }
    }
    return e;
}

/* The energy of kept mode k of the last spectrum: its eigenvector from dgeev's (dense) or the
 * Ritz vector V y (Arnoldi). */
static double cstab_energy(void *data, size_t k)
{
    whirl_cstab *w = data;
    const size_t ny = N_DYNAMIC * w->np, i = w->kept[k];
    const double *im = w->hm ? w->him : w->dim, *vec = w->hm ? w->hvec : w->dvr;
    const size_t len = w->hm ? w->hm : ny;
    size_t cr = i, ci = i;
    if (im[i] > 0) ci = i + 1;
    if (im[i] < 0) cr = i - 1;
    if (!w->hm) return mode_energy(w, vec + cr * len, im[i] != 0 ? vec + ci * len : NULL, -w->mu_re[k]);
    double *xr = w->ritz, *xi = w->ritz + ny;
    for (size_t t = 0; t < ny; t++) xr[t] = xi[t] = 0;
    for (size_t j = 0; j < len; j++) {
        const double *v = w->basis + j * ny, yr = vec[j + cr * len];
        const double yi = im[i] != 0 ? vec[j + ci * len] : 0;
        for (size_t t = 0; t < ny; t++) xr[t] += yr * v[t], xi[t] += yi * v[t];
    }
    return mode_energy(w, xr, im[i] != 0 ? xi : NULL, -w->mu_re[k]);
}

/* The pencil's factors of shifted_lu as a band. */
static band pencil_band(const whirl_cstab *w)
{
    band m = {w->lu, N_FIELDS * w->np, w->kl, w->ku, w->ldab, w->ipiv, w->lnz, w->unz};
    return m;
}

/* The banded LU factors of R (A - s B) into w->lu (pivots w->ipiv), R the row equilibration
 * (w->row_a): s = shift, or if that is an eigenvalue shift 1.7^k (k < tries). */
static int shifted_lu(whirl_cstab *w, double shift, int tries)
{
    const size_t np = w->np, n = N_FIELDS * np, ldab = w->ldab, off = w->kl + w->ku;
    int info = 1;
    for (int k = 0; k < tries && info != 0; k++) { /* s an eigenvalue: another s */
        w->shift = shift * pow(1.7, k);
        memcpy(w->lu, w->ab, ldab * n * sizeof(double));
        for (size_t g = 0; g < np; g++)
            for (size_t a = 0; a < N_FIELDS; a++)
                for (size_t c = 0; c < N_FIELDS; c++) {
                    const double b = w->bb[(g * N_FIELDS + a) * N_FIELDS + c];
                    const size_t i = N_FIELDS * g + a, col = N_FIELDS * g + c;
                    if (b != 0) w->lu[off + i - col + col * ldab] -= w->shift * b;
                }
        /* rows equilibrated (the rows of the second derivatives on short elements are ~1e8
         * times those of the conditions): the same solutions, less round-off */
        for (size_t i = 0; i < n; i++) w->row_a[i] = 0;
        for (size_t col = 0; col < n; col++) {
            const size_t i0 = col > w->ku ? col - w->ku : 0, i1 = col + w->kl < n ? col + w->kl : n - 1;
            for (size_t i = i0; i <= i1; i++)
                w->row_a[i] = fmax(w->row_a[i], fabs(w->lu[off + i - col + col * ldab]));
        }
        for (size_t i = 0; i < n; i++) w->row_a[i] = w->row_a[i] > 0 ? 1 / w->row_a[i] : 1;
        for (size_t col = 0; col < n; col++) {
            const size_t i0 = col > w->ku ? col - w->ku : 0, i1 = col + w->kl < n ? col + w->kl : n - 1;
            for (size_t i = i0; i <= i1; i++) w->lu[off + i - col + col * ldab] *= w->row_a[i];
        }
        const band m = pencil_band(w);
        info = band_lu(&m);
    }
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the shifted pencil is singular (zero pivot in column %d)",
                          info);
    return GSL_SUCCESS;
}

/* b = R B x for x = (u, w, vh) (3 np, field-major), b point-major (4 np). */
static void apply_b(const whirl_cstab *w, const double *x, double *b)
{
    const size_t np = w->np;
    const size_t src[N_FIELDS] = {0, np, 0, 2 * np}; /* where field c of x starts (tau: none) */
    for (size_t g = 0; g < np; g++)
        for (size_t a = 0; a < N_FIELDS; a++) {
            const double *row = w->bb + (g * N_FIELDS + a) * N_FIELDS;
            double sum = 0;
            for (size_t c = 0; c < N_FIELDS; c++)
                if (c != F_TAU && row[c] != 0) sum += row[c] * x[src[c] + g];
            b[N_FIELDS * g + a] = sum * w->row_a[N_FIELDS * g + a];
        }
}

/* y = the (u, w, vh) rows of (A - s B)^-1 B x, x = (u, w, vh) (3 np): one step of the Arnoldi
 * iteration, with the factors of shifted_lu. */
static int cstab_apply(void *data, const double *x, double *y)
{
    whirl_cstab *w = data;
    const size_t np = w->np;
    double *b = w->solve;
    apply_b(w, x, b);
    const band m = pencil_band(w);
    band_solve(&m, b);
    for (size_t g = 0; g < np; g++) {
        y[g] = b[N_FIELDS * g + F_U];
        y[np + g] = b[N_FIELDS * g + F_W];
        y[2 * np + g] = b[N_FIELDS * g + F_V];
    }
    return GSL_SUCCESS;
}

/* The eigenvalues theta of the block C of (A - s B)^-1 B on (u, w, vh) in full: C formed by
 * 3 np banded solves, then dgeev (into w->dre, w->dim, eigenvectors w->dvr). */
static int dense_eigen(whirl_cstab *w, int vectors)
{
    const size_t np = w->np, n = N_FIELDS * np, ny = N_DYNAMIC * np;
    int status = reserve_dense(w, np);
    if (status) return status;
    double *x = w->dx, *e = w->ritz; /* n x ny right-hand sides; a unit vector */
    for (size_t t = 0; t < ny; t++) e[t] = 0;
    for (size_t j = 0; j < ny; j++) {
        e[j] = 1;
        apply_b(w, e, x + j * n);
        e[j] = 0;
    }
    lapack_int info = whirl_la_dgbtrs_work(LAPACK_COL_MAJOR, 'N', (lapack_int)n, (lapack_int)w->kl,
                                          (lapack_int)w->ku, (lapack_int)ny, w->lu,
                                          (lapack_int)w->ldab, w->ipiv, x, (lapack_int)n);
    if (info != 0) return whirl_fail(GSL_EFAILED, "dgbtrs info %d", (int)info);
    for (size_t j = 0; j < ny; j++)
        for (size_t g = 0; g < np; g++) {
            w->dc[j * ny + g] = x[j * n + N_FIELDS * g + F_U];
            w->dc[j * ny + np + g] = x[j * n + N_FIELDS * g + F_W];
            w->dc[j * ny + 2 * np + g] = x[j * n + N_FIELDS * g + F_V];
        }
    int inf;
    status = whirl_worker_dgeev('N', vectors ? 'V' : 'N', ny, w->dc, ny, w->dre, w->dim, w->dvr,
                                ny, w->dwork, (int)w->dlwork, &inf);
    if (status) return status;
    if (inf != 0)
        return whirl_fail(GSL_EFAILED, "the eigenvalue iteration failed (dgeev info %d)", inf);
    return GSL_SUCCESS;
}

/* The Ritz values of the m-step Arnoldi factorisation into w->hre, w->him (eigenvectors of the
 * Hessenberg matrix in w->hvec); *done: every one with |theta| >= floor has a residual below
 * 1e-12 |theta|; *wanted: how many have |theta| >= floor. */
static int ritz(whirl_cstab *w, size_t m, double floor, int *done, size_t *wanted)
{
    const size_t km = CS_KRYLOV_MAX;
    for (size_t j = 0; j < m; j++)
        for (size_t i = 0; i < m; i++) w->hcopy[i + j * m] = w->hess[i + j * (km + 1)];
    lapack_int info = whirl_la_dgeev_work(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)m, w->hcopy,
                                         (lapack_int)m, w->hre, w->him, NULL, 1, w->hvec,
                                         (lapack_int)m, w->hwork, w->hlwork);
    if (info != 0)
        return whirl_fail(GSL_EFAILED, "the Ritz values' eigen-solve failed (dgeev info %d)",
                          (int)info);
    const double beta = m < km ? w->hess[m + (m - 1) * (km + 1)] : 0;
    *done = 1;
    *wanted = 0;
    for (size_t i = 0; i < m; i++) {
        const double mod = hypot(w->hre[i], w->him[i]);
        if (!(mod >= floor)) continue;
        ++*wanted;
        size_t cr = i, ci = i;
        const int cplx = w->him[i] != 0;
        if (cplx && w->him[i] > 0) ci = i + 1;
        if (cplx && w->him[i] < 0) cr = i - 1;
        const double last = hypot(w->hvec[m - 1 + cr * m], cplx ? w->hvec[m - 1 + ci * m] : 0);
        double len = 0;
        for (size_t r = 0; r < m; r++)
            len = hypot(len, hypot(w->hvec[r + cr * m], cplx ? w->hvec[r + ci * m] : 0));
        if (!(fabs(beta) * last <= 1e-12 * mod * len)) *done = 0;
    }
    return GSL_SUCCESS;
}

/* The dot product of a and b (n), in four partial sums: independent additions, which the
 * processor overlaps (a single sum waits for each addition in turn). */
static double dot4(const double *a, const double *b, size_t n)
{
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        s0 += a[i] * b[i];
        s1 += a[i + 1] * b[i + 1];
        s2 += a[i + 2] * b[i + 2];
        s3 += a[i + 3] * b[i + 3];
    }
    for (; i < n; i++) s0 += a[i] * b[i];
    return (s0 + s1) + (s2 + s3);
}

/* The theta of largest modulus of the block C by the Arnoldi iteration (header comment): into
 * w->hre, w->him (w->hm of them); GSL_CONTINUE if not converged in CS_KRYLOV_MAX steps. */
static int arnoldi_eigen(whirl_cstab *w, double cut)
{
    const size_t ny = N_DYNAMIC * w->np, km = CS_KRYLOV_MAX < ny ? CS_KRYLOV_MAX : ny;
    const double floor = 0.8 / (cut + fabs(w->shift));
    double *v = w->basis, *h = w->hess;
    memset(h, 0, (CS_KRYLOV_MAX + 1) * CS_KRYLOV_MAX * sizeof(double));
    double norm = 0;
    for (size_t i = 0; i < ny; i++) {
        v[i] = sin(0.7 * (double)i + 0.3) + 0.5;
        norm += v[i] * v[i];
    }
    norm = sqrt(norm);
    for (size_t i = 0; i < ny; i++) v[i] /= norm;
    size_t next = 24; /* the next look at the Ritz values */
    w->hm = 0;
    for (size_t step = 0; step < km; step++) {
        const double *x = v + step * ny;
        double *y = v + (step + 1) * ny;
        if (cstab_apply(w, x, y) != GSL_SUCCESS)
            return whirl_fail(GSL_EFAILED, "the banded solve failed");
        for (int pass = 0; pass < 2; pass++) /* Gram-Schmidt, twice */
            for (size_t j = 0; j <= step; j++) {
                const double *vj = v + j * ny, dot = dot4(vj, y, ny);
                for (size_t i = 0; i < ny; i++) y[i] -= dot * vj[i];
                h[j + step * (CS_KRYLOV_MAX + 1)] += dot;
            }
        norm = 0; /* the vectors are O(1): no scaling needed */
        for (size_t i = 0; i < ny; i++) norm += y[i] * y[i];
        norm = sqrt(norm);
        h[step + 1 + step * (CS_KRYLOV_MAX + 1)] = norm;
        const int breakdown = !(norm > 1e-300);
        if (!breakdown)
            for (size_t i = 0; i < ny; i++) y[i] /= norm;
        const size_t m = step + 1;
        if (m < next && !breakdown && m < km) continue;
        next = m + (m / 8 > 4 ? m / 8 : 4);
        int done = 0;
        size_t wanted = 0;
        int status = ritz(w, m, floor, &done, &wanted);
        if (status) return status;
        if (next < wanted + 16) next = wanted + 16; /* no stop before (wanted grows with m) */
        if (breakdown || m == ny || (done && m >= wanted + 16)) {
            w->hm = m;
            return GSL_SUCCESS;
        }
        if (whirl_stop_requested())
            return whirl_fail(WHIRL_EINTERRUPTED, "the eigen-solve at omega = " WHIRL_Q_RATE
                              "%g: stopped by request", w->omega);
    }
    return GSL_CONTINUE;
}

int whirl_cstab_spectrum(whirl_cstab *w, int signatures, whirl_spectrum *out)
{
    if (w->np == 0) return whirl_fail(GSL_EINVAL, "no linearisation to solve");
    const double fmax_kept = fmax(w->p.freq_max, 3 * w->omega);
    const double cut = fmax_kept * fmax_kept;
    int status = shifted_lu(w, CS_SHIFT, 4);
    if (status) return status;
    status = w->p.solver == 1 ? GSL_CONTINUE : arnoldi_eigen(w, cut);
    if (status == GSL_CONTINUE) { /* the reference, or the fall-back */
        w->hm = 0;
        status = dense_eigen(w, signatures);
    }
    if (status) return status;
    const size_t nt = w->hm ? w->hm : N_DYNAMIC * w->np;
    const double *tre = w->hm ? w->hre : w->dre, *tim = w->hm ? w->him : w->dim;
    size_t count = 0, zero = 0;
    double big = 0;
    for (size_t i = 0; i < nt; i++) {
        const double tr = tre[i], ti = tim[i], t2 = tr * tr + ti * ti;
        if (!(t2 > 0)) continue;
        const double re = w->shift + tr / t2, im = -ti / t2;
        if (!isfinite(re) || !isfinite(im) || hypot(re, im) > cut) continue;
        w->kept[count] = i;
        w->mu_re[count] = re;
        w->mu_im[count] = im;
        if (hypot(re, im) < hypot(w->mu_re[zero], w->mu_im[zero])) zero = count;
        count++;
        big = fmax(big, hypot(re, im));
    }
    if (w->mode > 0 && count > 0) { /* the rotation's mu = 0 */
        count--;
        for (size_t k = zero; k < count; k++) {
            w->mu_re[k] = w->mu_re[k + 1];
            w->mu_im[k] = w->mu_im[k + 1];
            w->kept[k] = w->kept[k + 1];
        }
    }
    const double level = 1e-8 * sqrt(big);
    whirl_windows_classify(out, count, w->mu_re, w->mu_im, level, signatures ? w->sig_out : NULL,
                           cstab_energy, w);
    return GSL_SUCCESS;
}

/* ---- windows ---- */

typedef struct cstab_search {
    whirl_cstab *w;
    const double *scan, *tip; /* the branch's tip radii at the scan's rates, for the seeds */
    size_t nscan;
    whirl_windows_stats *stats;
    double last_omega, last_tip; /* the last linearisation's rate and tip radius (0: none) */
} cstab_search;

/* The linearisation at omega, seeded by the tip radius of the nearest scan rate below or of the
 * last linearisation if that is nearer (the shooting then brackets its root in fewer shots); kept
 * if it is the workspace's already (the search evaluates some rates twice: a pair's extremum in
 * full). */
static int source_linearise(cstab_search *c, double omega)
{
    if (c->w->np > 0 && c->w->omega == omega) return GSL_SUCCESS;
    size_t j = 0;
    while (j + 1 < c->nscan && c->scan[j + 1] <= omega) j++;
    const int last = c->last_tip > 0 && fabs(omega - c->last_omega) < fabs(omega - c->scan[j]);
    c->stats->shapes++;
    if (c->w->p.progress) c->w->p.progress(c->w->p.progress_ctx, c->w->mode, omega);
    int status = whirl_cstab_linearise(c->w, omega, c->w->mode, last ? c->last_tip : c->tip[j],
                                       &c->last_tip);
    c->last_omega = omega;
    if (status) c->last_tip = 0;
    return status;
}

static int cstab_source_spectrum(void *data, double omega, int signatures, whirl_spectrum *out)
{
    cstab_search *c = data;
    int status = source_linearise(c, omega);
    if (!status) status = whirl_cstab_spectrum(c->w, signatures, out);
    return status;
}

/* The two mu nearest sigma at omega by shift-and-invert Arnoldi on the block of shifted_eigen. */
static int cstab_source_pair(void *data, double omega, double sigma, double *mu_re, double *mu_im)
{
    cstab_search *c = data;
    int status = source_linearise(c, omega);
    if (status) return status;
    if (shifted_lu(c->w, sigma, 1)) return GSL_CONTINUE; /* sigma is an eigenvalue */
    if (c->w->kr.q != N_DYNAMIC * c->w->np) {
        whirl_windows_arnoldi_release(&c->w->kr);
        if (whirl_windows_arnoldi_init(&c->w->kr, N_DYNAMIC * c->w->np))
            return whirl_fail(GSL_ENOMEM, "out of memory for the Arnoldi iteration");
    }
    return whirl_windows_arnoldi_pair(&c->w->kr, cstab_apply, c->w, sigma, mu_re, mu_im);
}

/* The collision discriminant D = Re (mu_1 - mu_2)^2 of the two mu nearest -freq^2 at omega on
 * the workspace of an edge's refinement (stability_windows.c); NAN if not obtained. */
typedef struct edge_args {
    whirl_cstab *w;
    int mode;
    double sigma;
    int status;
    double at[2], value[2]; /* the last two evaluations (Brent's start evaluates its ends again) */
} edge_args;

static double edge_value(double omega, void *data);

static double edge_function(double omega, void *data)
{
    edge_args *a = data;
    for (int i = 0; i < 2; i++)
        if (a->at[i] == omega) return a->value[i];
    const double v = edge_value(omega, data);
    a->at[1] = a->at[0], a->value[1] = a->value[0];
    a->at[0] = omega, a->value[0] = v;
    return v;
}

static double edge_value(double omega, void *data)
{
    edge_args *a = data;
    double re[2], im[2];
    if (a->status) return NAN;
    int status = whirl_cstab_linearise(a->w, omega, a->mode, 0, NULL);
    if (!status) status = shifted_lu(a->w, a->sigma, 3);
    if (!status && a->w->kr.q != N_DYNAMIC * a->w->np) {
        whirl_windows_arnoldi_release(&a->w->kr);
        if (whirl_windows_arnoldi_init(&a->w->kr, N_DYNAMIC * a->w->np))
            status = whirl_fail(GSL_ENOMEM, "out of memory for the Arnoldi iteration");
    }
    if (!status)
        status = whirl_windows_arnoldi_pair(&a->w->kr, cstab_apply, a->w, a->sigma, re, im) ==
                         GSL_SUCCESS
                     ? GSL_SUCCESS
                     : whirl_fail(GSL_EFAILED, "mode %d: the pair at omega = " WHIRL_Q_RATE
                                  "%.10g did not converge on the refined discretisation",
                                  a->mode, omega);
    if (status) {
        a->status = status;
        return NAN;
    }
    if (im[0] != 0 && fabs(im[0] + im[1]) <= 1e-12 * fabs(im[0])) return -4 * im[0] * im[0];
    const double dr = re[0] - re[1], di = im[0] - im[1];
    return dr * dr - di * di;
}

#define REFINE_ITER_MAX 100 /* Brent iterations locating a refined edge (each an eigen-solve) */

/* edge_function for the root finder: its status is the evaluation's */
static int edge_root(double x, void *ctx, double *fx)
{
    edge_args *a = ctx;
    *fx = edge_function(x, a);
    return a->status;
}

/* The edge at *omega (collision frequency freq; opens: stable below) located again on the refined
 * workspace wr by Brent's method on D: D at *omega says on which side the new edge lies (D > 0
 * on the stable side), steps of 1e-7 growing tenfold that way bracket it (at most 1e-2):
 * *omega becomes the new edge, *err the change. */
static int refine_edge(whirl_cstab *wr, int mode, double *edge, int opens, double freq,
                       double tol, double *err)
{
    const double omega = *edge;
    edge_args a = {wr, mode, -freq * freq, 0, {NAN, NAN}, {NAN, NAN}};
    const double f0 = edge_function(omega, &a);
    if (a.status) return a.status;
    *err = 0;
    if (f0 == 0) return GSL_SUCCESS;
    const double dir = (f0 > 0) == (opens != 0) ? 1 : -1; /* towards the unstable side if stable */
    double h = 1e-7, near = omega, far = omega + dir * h, ffar = edge_function(far, &a);
    while (!a.status && !(f0 * ffar < 0) && h < 1e-2) {
        near = far;
        h *= 10;
        far = omega + dir * h;
        ffar = edge_function(far, &a);
    }
    if (a.status) return a.status;
    if (!(f0 * ffar < 0))
        return whirl_fail(GSL_EFAILED, "mode %d: the edge at omega = " WHIRL_Q_RATE
                          "%.10g is not found within 1e-2 on the refined discretisation", mode,
                          omega);
    const whirl_root_opts opts = {tol, 0, REFINE_ITER_MAX, 0, 0, 0};
    whirl_root root;
    int status = whirl_root_brent(edge_root, &a, fmin(near, far), fmax(near, far), &opts, &root);
    if (a.status) return a.status;
    if (status == GSL_EMAXITER) status = GSL_SUCCESS; /* the bracket reached is the edge */
    if (status)
        return whirl_fail(status, "mode %d: the refined edge near omega = " WHIRL_Q_RATE
                          "%.10g was not located", mode, omega);
    const double lo = root.lower, hi = root.upper;
    *edge = (lo + hi) / 2;
    *err = fabs(*edge - omega);
    return GSL_SUCCESS;
}

/* The refinements of an edge: degree + 8 per level (64 at most), shape tolerance / 100, until
 * two successive levels agree to EDGE_TARGET, or EDGE_LEVELS levels are spent, or the change
 * grows from one level to the next (no longer the discretisation's error converging but the
 * round-off of the higher degree, whose differentiation matrices grow as p^2 / h: at some edges
 * degree 40 moved by 1e-7 where degrees 24 and 32 agreed to 2e-9): the last change is the
 * estimate, above EDGE_TARGET where the target was not reached. */
#define EDGE_LEVELS 3
#define EDGE_TARGET 1e-8

/* The workspace of refinement level (1..EDGE_LEVELS) of w, allocated at first use. */
static int level_workspace(const whirl_cstab *w, int level, whirl_cstab **wr)
{
    if (*wr != NULL) return GSL_SUCCESS;
    whirl_cstab_params rp = w->p;
    rp.degree = w->p.degree + 8 * level <= 64 ? w->p.degree + 8 * level : 64;
    rp.shape_tol = fmax(1e-14, w->p.shape_tol / 100);
    *wr = whirl_cstab_alloc(&rp);
    return *wr == NULL ? GSL_ENOMEM : GSL_SUCCESS; /* the parameters are valid: no memory */
}

/* The edge *edge (opens, collision frequency freq) refined by levels (EDGE_LEVELS above): the
 * edge of the finest level into *edge and the last change into *err; where the change grew, the
 * previous level's edge and the larger change. The levels after the first locate the edge to
 * tol / 10, so that their agreement is not the root finder's. */
static int refine_levels(const whirl_cstab *w, whirl_cstab **wr, int mode, double *edge,
                         int opens, double freq, double tol, double *err)
{
    int status = GSL_SUCCESS;
    for (int level = 1; level <= EDGE_LEVELS && !status; level++) {
        if (level > 1 && (*err <= EDGE_TARGET || w->p.degree + 8 * (level - 1) >= 64)) break;
        const double before = *edge, before_err = *err;
        status = level_workspace(w, level, &wr[level - 1]);
        if (!status)
            status = refine_edge(wr[level - 1], mode, edge, opens, freq, level > 1 ? tol / 10 : tol,
                                 err);
        if (!status && level > 1 && *err > before_err) { /* no longer converging */
            *edge = before;
            break;
        }
    }
    return status;
}

/* The closed edges of windows[0..count-1] located again on refined discretisations
 * (refine_levels), their last change the estimate of the error (whirl_window). */
static int edge_errors(const whirl_cstab *w, int mode, double tol, whirl_window *windows,
                       size_t count)
{
    whirl_cstab *wr[EDGE_LEVELS] = {NULL};
    int status = GSL_SUCCESS;
    for (size_t i = 0; i < count && !status; i++) {
        whirl_window *x = &windows[i];
        x->err_from = x->err_to = 0;
        if (!x->open_from && x->freq_from > 0)
            status = refine_levels(w, wr, mode, &x->from, 1, x->freq_from, tol, &x->err_from);
        if (!status && !x->open_to && x->freq_to > 0)
            status = refine_levels(w, wr, mode, &x->to, 0, x->freq_to, tol, &x->err_to);
    }
    for (int level = 0; level < EDGE_LEVELS; level++) whirl_cstab_free(wr[level]);
    return status;
}

int whirl_cstab_windows(whirl_cstab *w, int mode, const whirl_windows_params *p,
                        whirl_window *windows, size_t max, size_t *count,
                        whirl_windows_stats *stats)
{
    *count = 0;
    memset(stats, 0, sizeof *stats);
    if (mode < 1 || mode > WHIRL_MODE_MAX)
        return whirl_fail(GSL_EINVAL, "the mode must be in 1..%d, got %d", WHIRL_MODE_MAX, mode);
    double birth, *omega = NULL;
    size_t npts = 0;
    int status = whirl_continuum_critical(mode, w->p.tip_mass, &birth);
    if (!status) status = whirl_windows_range(p, mode, birth, &omega, &npts);
    if (status) return status;
    if (!(p->omega_max <= WHIRL_CONTINUUM_OMEGA_MAX)) {
        free(omega);
        return whirl_fail(GSL_EINVAL, "the continuum's rates end at omega = " WHIRL_Q_RATE "%g, "
                          "got omega = " WHIRL_Q_RATE "%g", WHIRL_CONTINUUM_OMEGA_MAX,
                          p->omega_max);
    }
    whirl_shape_info *info = malloc(npts * sizeof *info);
    int *exists = malloc(npts * sizeof *exists);
    double *tip = malloc(npts * sizeof *tip);
    status = (!info || !exists || !tip) ? whirl_fail(GSL_ENOMEM, "out of memory") : 0;
    if (!status) status = whirl_continuum_branch(mode, w->p.tip_mass, npts, omega, info, exists);
    for (size_t j = 0; j < npts && !status; j++) {
        tip[j] = info[j].tip_r;
        if (!exists[j])
            status = whirl_fail(GSL_EFAILED, "mode %d: no continuum shape at omega = " WHIRL_Q_RATE
                                "%g", mode, omega[j]);
    }
    w->mode = mode;
    w->np = 0; /* no linearisation of this search yet */
    cstab_search c = {w, omega, tip, npts, stats, 0, 0};
    windows_source src = {cstab_source_spectrum, p->krylov ? cstab_source_pair : NULL, &c, mode,
                          stats};
    if (!status) status = whirl_windows_search(&src, p, omega, npts, windows, max, count);
    if (!status) status = edge_errors(w, mode, p->tol, windows, *count);
    free(omega);
    free(info);
    free(exists);
    free(tip);
    return status;
}
