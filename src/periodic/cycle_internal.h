/* Internal: the continuation of periodic motions (whirl_periodic_path), shared by
 * cycle_path.c (the branch: the corrector, the tangent, the steps) and cycle_events.c (the test
 * functions, the description of a point, the location of events). The method: cycle_path.c. */
#ifndef WHIRL_PERIODIC_CYCLE_INTERNAL_H
#define WHIRL_PERIODIC_CYCLE_INTERNAL_H

#include <gsl/gsl_linalg.h>

#include "periodic/periodic_internal.h"

#define BRENT_ITER 100
/* The torus test's least |rho_k - rho_l| below which two pairs are taken as equal by a symmetry
 * (round-off splits them by ~1e-15; two pairs meeting are this close only within ~1e-18 of the
 * meeting in the parameter, D being linear in it there). */
#define GAP_MIN 1e-9
/* The corrector's target at an event's evaluations: 1e-2 of Newton's test (with 1e-10 a fold's
 * rate moves by ~1e-11 with the residual left; measured on the circle drive, N = 2), not below
 * the round-off of a period; where round-off stops the iteration above it, Newton's test. */
#define EVENT_NEWTON_RATIO 1e-2
#define EVENT_NEWTON_FLOOR 1e-13
#define RICHARDSON 15.0
/* A change of the verdict along a step that no test's sign change explains (pairs equal by a
 * symmetry, as the 3D hanging chain's two planes: det(M + I) then has a double zero) is located
 * on the pairs' rho (cycle_events.c, rho_test): where a rho passes -+2, or (a complex pair) where
 * the largest |Im rho| passes STABILITY_THRESHOLD, which grows as c sqrt(p - p*) beyond the
 * meeting: the point lies (1e-8 / c)^2 ~ 1e-16 beyond it. How the largest multiplier left the
 * circle, at the step's unstable end: through +-1 if its imaginary part is below EDGE_ANGLE of
 * its modulus, else as a complex pair. */
#define STABILITY_THRESHOLD 1e-8
#define EDGE_ANGLE 1e-6

/* What is reported of a point or an event (buffers owned by the cycle). */
typedef struct report {
    whirl_cycle_point pt;
    double *y, *re, *im;
    double sigma; /* events: where on the step */
    double gap;   /* the torus test's least |rho_k - rho_l| */
} report;

/* The continuation under way. */
typedef struct cycle {
    whirl_periodic *w;
    whirl_cycle_params p;
    whirl_pivot_path base; /* the start's path */
    double base_amp;       /* its largest amplitude */
    size_t m, size, nb;
    int steps;
    double wpos, wrate;    /* the metric: 1 / L^2, 1 / (omega_ref L)^2 */
    /* the step's start (0) and end (1) */
    double *y0, *t0, *basis0, *mono0, *cols0, *pp0;
    double p0, tp0;
    double *y1, *t1, *basis1, *mono1, *cols1, *pp1;
    double *basis_j, *cols_j, *pp_j; /* the frame of the chord where it was refreshed */
    double p1, tp1;
    gsl_matrix *jac, *bord, *lu, *inv; /* (m+1)^2 chord, (m+1)^2 tangent, m^2 tests (2) */
    gsl_permutation *perm, *perm_b, *perm_m;
    gsl_vector *rhs, *sol; /* m + 1 */
    double *py, *tmp, *a, *b, *ys, *yf; /* size each */
    double f0[3];          /* the tests at the step's start */
    double gap0;           /* its torus test's least gap */
    int unstable0;         /* its verdict is unstable */
    double mu0[2];         /* its largest multiplier */
    double target;         /* the corrector's tolerance: p.tol, tighter for the events */
    double *zero;          /* m zeros: the errors of unrefined multipliers */
    double *sr, *si, *rr, *ri, *re_t, *im_t; /* m each: the torus test's scratch */
    char *used;
    report now, ev[3];
    double arclength;
    whirl_cycle_row_fn row;
    void *row_data;
    whirl_cycle_tick_fn tick;
    void *tick_data;
    whirl_cycle_progress progress;
} cycle;

/* w's path <- the start's at the parameter p. */
void cycle_set_param(cycle *c, double p);
/* The path's largest Fourier amplitude. */
double cycle_amplitude(const whirl_pivot_path *path);
/* "omega=VALUE" or "A=VALUE" (with the unit marker of core/error.h) into buf. */
const char *cycle_where(const cycle *c, double p, char *buf, size_t size);
#define WHERE(c, p) cycle_where((c), (p), (char[64]){0}, 64)
/* The corrector from (y, p), a start near the point at sigma of the step, with steps per
 * period; the predictor at sigma, corrected. GSL_EMAXITER (no message) on no convergence. */
int cycle_correct(cycle *c, double sigma, int steps, double *y, double *p, int *iters,
                  double *res);
int cycle_point_at(cycle *c, double sigma, int steps, double *y, double *p, int *iters,
                   double *res);
/* r <- the point (y, p) of w->mono: multipliers, verdict, tests (cycle_events.c). */
int cycle_describe(cycle *c, report *r, const double *y, double p, double tp, int iters,
                   double res);
/* The event of test kind (0: +1, 1: -1, 2: torus, 3: a change of the verdict) on the step of
 * length ds into r (r->pt.event WHIRL_CYCLE_POINT: none). */
int cycle_locate_event(cycle *c, int kind, double ds, report *r);

#endif
