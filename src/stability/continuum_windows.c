/* The windows of the continuous chain
 * (continuum_stability.c's header comment: the equations and their linearisation)
 * Windows (whirl_cstab_windows): the search of windows_search.c on these spectra, then each
 * closed edge located again as the root of the collision discriminant on refined
 * discretisations (degree + 8, shape_tol / 100; where that moves it by more than 1e-8, degree
 * + 16 and + 24 until two successive levels agree to 1e-8, or the change grows, the round-off of
 * the higher degree: refine_levels): near such an edge the pair
 * separates slowly, dD/domega is small, and an error of mu moves the edge by much more. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/linalg.h"

#include "whirl/continuum_stability.h"
#include "core/error.h"
#include "core/roots.h"
#include "core/worker.h"
#include "stability/continuum_internal.h"
#include "stability/windows_internal.h"

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
    if (cstab_shifted_lu(c->w, sigma, 1)) return GSL_CONTINUE; /* sigma is an eigenvalue */
    if (c->w->kr.q != N_DYNAMIC * c->w->np) {
        whirl_windows_arnoldi_release(&c->w->kr);
        if (whirl_windows_arnoldi_init(&c->w->kr, N_DYNAMIC * c->w->np))
            return whirl_fail(GSL_ENOMEM, "out of memory for the Arnoldi iteration");
    }
    return whirl_windows_arnoldi_pair(&c->w->kr, cstab_apply, c->w, sigma, mu_re, mu_im);
}

/* The collision discriminant D = Re (mu_1 - mu_2)^2 of the two mu nearest -freq^2 at omega on
 * the workspace of an edge's refinement (windows_search.c); NAN if not obtained. */
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
    if (!status) status = cstab_shifted_lu(a->w, a->sigma, 3);
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
    return *wr == NULL ? whirl_last_status() : GSL_SUCCESS;
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
