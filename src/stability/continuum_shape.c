/* The steady shape of the continuous chain by collocation, for its linearisation
 * (continuum_stability.c's header comment: the equations and their linearisation)
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
 * once k exceeds Omega sqrt(h) (an element of degree 16 from sigma = 0 had edges 1e-5 off). */
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
        const cstab_band jb = {jac, nn, kl, kl, ldab, w->ipiv, w->lnz, w->unz};
        const int info = cstab_band_lu(&jb);
        if (info != 0)
            return whirl_fail(GSL_EFAILED, "the collocation of the shape at omega = "
                              WHIRL_Q_RATE "%g is singular (zero pivot in column %d)", omega, info);
        cstab_band_solve(&jb, f);
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
int cstab_reserve_elements(whirl_cstab *w, size_t ne)
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
                      cstab_points_max(w), w->p.memory_mb);
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
 * shooting again. The points are bounded by the memory bound (cstab_points_max); old (*cap doubles)
 * holds the previous element set. */
static int solve_shape_in(whirl_cstab *w, double omega, double tip_r, double **old, size_t *cap)
{
    int status = sample_shape(w, omega, tip_r);
    if (status) return status;
    w->ne = CS_ELEMENTS_START;
    if ((status = cstab_reserve_elements(w, w->ne))) return status;
    for (size_t e = 0; e <= w->ne; e++) w->brk[e] = (double)e / (double)w->ne;
    const size_t P = (size_t)w->p.degree + 1;
    size_t nb = 0, one = 0; /* one: elements of the previous set to interpolate (0: none) */
    for (;;) { /* the phase, from the shooting's shape */
        if (w->ne * P > cstab_points_max(w)) return too_many_points(w, omega, w->ne + 1, "");
        w->np = w->ne * P;
        if ((status = cstab_reserve(w, w->np)) || (status = cstab_reserve_elements(w, w->ne))) return status;
        cstab_set_points(w);
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
        if ((status = cstab_reserve(w, w->np))) return status;
        cstab_set_points(w);
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
        if ((status = cstab_reserve_elements(w, w->ne))) return status;
        for (int pass = 0; pass < 2; pass++) {
            halve(w, omega, wrong, shape_resolved, sr, sq, &nb);
            if (nb > w->ne + 1 || wrong) break;
            if (off <= fmax(1e-7, 1e3 * w->p.shape_tol)) return GSL_SUCCESS;
            wrong = 1; /* resolved, yet not the shooting's shape: every element halved */
        }
        why = status ? "Newton's method failed" : wrong ? "not the shooting's shape" : "";
        if ((nb - 1) * P > cstab_points_max(w)) return too_many_points(w, omega, nb, why);
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

int cstab_solve_shape(whirl_cstab *w, double omega, double tip_r)
{
    double *old = NULL;
    size_t cap = 0;
    const int status = solve_shape_in(w, omega, tip_r, &old, &cap);
    free(old);
    return status;
}
