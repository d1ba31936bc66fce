/* Shooting on the tip radius, shared by the continuous and the N-link steady shapes.
 *
 * The mode-k shape has the tip radius a_k where the k-th zero of r leaves the chain through the
 * pivot: crossings(a) >= k for a < a_k and <= k - 1 above (Kolodner 1955, Comm. Pure Appl. Math.
 * 8:395, "Heavy rotating string - a nonlinear eigenvalue problem": one shape per mode). The
 * crossing count is an integer, so the bracket search on it cannot be fooled by the residual's
 * other roots; within a bracket where the count drops from exactly k to exactly k - 1, r(pivot)
 * changes sign once and Brent's method (GSL roots/brent.c; Brent 1973, "Algorithms for
 * minimization without derivatives", ch. 4) converges to round-off. Near the critical rate
 * a_k -> 0 like sqrt(omega - omega_k), hence the bracket search in log(a). */
#include <float.h>
#include <limits.h>
#include <math.h>

#include <gsl/gsl_math.h>

#include "core/error.h"
#include "core/roots.h"
#include "steady/steady_internal.h"

#define A_MIN_FRACTION 1e-9  /* smallest tip radius tried, relative to a_max */
#define SEED_STEP 1e-6       /* first relative step away from a seed; grows 8-fold */
#define BISECT_MAX 300
#define BRENT_MAX 200

typedef struct shot_call {
    steady_shot_fn shot;
    void *ws;
    int status;         /* a shot's failure inside Brent's iteration */
    double known_a[2];  /* the bracket's ends, whose residuals are known: not shot again */
    double known_res[2];
} shot_call;

static int residual_of(double a, void *p, double *res)
{
    shot_call *call = p;
    for (int i = 0; i < 2; i++)
        if (a == call->known_a[i]) {
            *res = call->known_res[i];
            return GSL_SUCCESS;
        }
    int crossings;
    int status = call->shot(call->ws, a, res, &crossings);
    if (status != GSL_SUCCESS) {
        call->status = status;
        *res = GSL_NAN;
    }
    return status;
}

/* Brent's method on residual(a) in [lo, hi] (opposite signs), to round-off (a residual exactly
 * 0 collapses the interval to the root). */
static int polish(shot_call *call, double lo, double hi, double *a)
{
    const whirl_root_opts o = {0, 4 * DBL_EPSILON, BRENT_MAX, 0, 0, 0};
    whirl_root r;
    int status = whirl_root_brent(residual_of, call, lo, hi, &o, &r);
    if (status == GSL_SUCCESS) {
        *a = r.root;
        return GSL_SUCCESS;
    }
    if (call->status || status == GSL_ENOMEM) return status; /* with the message */
    if (status == GSL_EMAXITER)
        return whirl_fail(GSL_EMAXITER, "no convergence of the tip radius in %d Brent steps",
                          BRENT_MAX);
    if (r.bracketed) return whirl_fail(GSL_EFAILED, "Brent iteration failed on the tip radius");
    return status;
}

/* One shot evaluated: the tip radius, residual, crossings below the pivot and the total count
 * of sign changes up to and including the pivot. */
typedef struct shot_point {
    double a, res;
    int below, total;
} shot_point;

static int take_shot(steady_shot_fn shot, void *ws, double a, shot_point *p)
{
    p->a = a;
    p->res = 0, p->below = p->total = 0;
    if (whirl_stop_requested()) return whirl_fail(WHIRL_EINTERRUPTED, "stopped by request");
    int status = shot(ws, a, &p->res, &p->below);
    /* after `below` changes from r > 0 the sign is (-1)^below; the pivot adds one if it differs */
    int pivot_flips = p->res != 0 && (p->res > 0) != (p->below % 2 == 0);
    p->total = p->below + pivot_flips;
    return status;
}

int whirl_steady_shoot_root(steady_shot_fn shot, void *ws, int mode, double a_max, double guess,
                            double *a)
{
    const double a_min = A_MIN_FRACTION * a_max;
    shot_point lo, hi;
    int status;

    if (guess > a_min && guess < a_max) {
        /* walk away from the seed, in steps growing 8-fold, until the count brackets mode */
        shot_point g;
        if ((status = take_shot(shot, ws, guess, &g)) != GSL_SUCCESS) return status;
        double step = SEED_STEP;
        if (g.total >= mode) {
            for (lo = g;; lo = hi, step *= 8) {
                if ((status = take_shot(shot, ws, fmin(lo.a * (1 + step), a_max), &hi)))
                    return status;
                if (hi.total < mode) break;
                if (hi.a == a_max)
                    return whirl_fail(GSL_EFAILED, "mode %d: crossings persist up to the largest "
                                      "tip radius " WHIRL_Q_LENGTH "%g", mode, a_max);
            }
        } else {
            for (hi = g;; hi = lo, step *= 8) {
                if ((status = take_shot(shot, ws, fmax(hi.a / (1 + step), a_min), &lo)))
                    return status;
                if (lo.total >= mode) break;
                if (lo.a == a_min)
                    return whirl_fail(GSL_EDOM, "mode %d does not exist at this rate", mode);
            }
        }
    } else {
        if ((status = take_shot(shot, ws, a_min, &lo)) != GSL_SUCCESS) return status;
        if (lo.total < mode)
            return whirl_fail(GSL_EDOM, "mode %d does not exist at this rate", mode);
        /* the whole range */
        if ((status = take_shot(shot, ws, a_max, &hi)) != GSL_SUCCESS) return status;
        if (hi.total >= mode)
            return whirl_fail(GSL_EFAILED, "mode %d: crossings persist up to the largest tip "
                              "radius " WHIRL_Q_LENGTH "%g", mode, a_max);
    }

    /* narrow until the only event between lo and hi is the k-th zero leaving through the
     * pivot: k - 1 crossings below it at both ends, the pivot's sign flipping */
    for (int iter = 0; !(lo.total == mode && hi.total == mode - 1 && lo.below == mode - 1 &&
                         hi.below == mode - 1);
         iter++) {
        if (iter == BISECT_MAX)
            return whirl_fail(GSL_EMAXITER, "mode %d: no bracket of the tip radius in %d "
                              "bisections", mode, BISECT_MAX);
        shot_point mid;
        double a_mid = hi.a > 2 * lo.a ? sqrt(lo.a * hi.a) : 0.5 * (lo.a + hi.a);
        if ((status = take_shot(shot, ws, a_mid, &mid)) != GSL_SUCCESS) return status;
        if (mid.total >= mode) lo = mid;
        else hi = mid;
    }
    shot_call call = {shot, ws, GSL_SUCCESS, {lo.a, hi.a}, {lo.res, hi.res}};
    return polish(&call, lo.a, hi.a, a);
}
