/* What the pieces of the equilibria search (src/steady/equilibria*.c) share: the scan of a
 * function of one variable and its roots' brackets, the N-link scans and the Newton workspace on
 * the link angles, the list of equilibria; the prototypes grouped by the file that defines them.
 * The method is described in equilibria.c. */
#ifndef WHIRL_EQUILIBRIA_INTERNAL_H
#define WHIRL_EQUILIBRIA_INTERNAL_H

#include <stddef.h>

#include "steady/steady_internal.h"
#include "whirl/steady.h"

#define SCAN_LEVELS_MAX 5
#define MATCH_ANGLE 1e-8     /* two polished equilibria with every link angle this close [rad]
                              * are the same (their tip radii then within MATCH_ANGLE L) */

/* ---- the scan of a function of one variable (equilibria_scan.c) ---- */

/* G and dG/dx at x; with s, sd not NULL, the tangents of the link angles H_i / V_i and their
 * derivatives with respect to x */
typedef int (*scan_fn)(void *ctx, double x, double *g, double *dg, double *s, double *sd);

typedef struct scan_problem {
    scan_fn f;
    void *ctx;
    size_t n_slopes; /* N */
    long budget;     /* residual evaluations of one level */
} scan_problem;

typedef struct bracket {
    double lo, hi; /* a sign change of the function between x = lo and x = hi */
} bracket;

typedef struct scan_out {
    bracket *br;       /* the root brackets */
    size_t n, cap;
    long evals;
    size_t unresolved;
} scan_out;

/* ---- the N-link chain's scans, Newton's method, quadruple precision (equilibria_nlink.c) ---- */

typedef struct nlink_scan {
    const whirl_chain *c;
    double omega, length; /* the rate; L = sum of the link lengths */
    double *slope, *slope_d; /* scratch of the tip shot (N each) */
} nlink_scan;

typedef struct angle_ws {
    const whirl_chain *c;
    double omega;
    nlink_balance *bal;
    double *theta, *r, *z, *t; /* N, N+1, N+1, N+1 */
    double *start;             /* N: the start of a refined root's Newton's method */
    double worst; /* largest sine of a link's angle to the force it carries, polished shapes */
} angle_ws;

typedef nlink_quad (*quad_fn)(const nlink_scan *s, nlink_quad p, double *theta);

/* ---- the list of equilibria (equilibria_list.c) ---- */

typedef struct eq_list {
    whirl_equilibrium *eq;
    size_t n, cap;
    int *source;   /* bit 1: tip scan, 2: pivot scan or solve, 4: continuation */
    size_t links;  /* N (0: no angles kept) */
    double window; /* 2 MATCH_ANGLE L: tip radii further apart are different equilibria */
    double *theta; /* the polished link angles of entry i at theta[i N ..] */
    size_t coincident; /* roots of one scan merged into an equilibrium of the same scan */
} eq_list;

/* ---- the report of the search's progress (equilibria.c) ---- */

typedef struct eq_progress {
    whirl_equilibria_progress_fn fn; /* NULL: none */
    void *ctx;
    int stages;
} eq_progress;

/* progress->fn at item done of total in stage (done 0: the stage begins; about 256 calls a
 * stage at most, the last item always) */
void eq_report(const eq_progress *p, int stage, size_t done, size_t total);

/* equilibria_scan.c: the adaptive sign-change scan */
int eq_sign_of(double g);
void eq_scan_out_free(scan_out *o);
int eq_scan_settled(const scan_problem *pb, double x0, double x1, size_t n0, scan_out *o,
                    int *levels);
int eq_polish(scan_fn f, void *ctx, double lo, double hi, double *x);
int eq_check_stop(size_t i, size_t n);

/* equilibria_nlink.c: the two N-link scans, Newton's method on the link angles, quadruple
 * precision */
double eq_tip_of_x(const nlink_scan *s, double x);
int eq_tip_fn(void *ctx, double x, double *g, double *dg, double *sl, double *sl_d);
int eq_angles_of_scan(const nlink_scan *s, double x, double *theta);
double eq_theta_of_y(double y);
int eq_pivot_fn(void *ctx, double y, double *g, double *dg, double *sl, double *sl_d);
void eq_linear_loads(const whirl_chain *c, double omega, double *per_tip, double *per_top);
void eq_angle_ws_free(angle_ws *w);
angle_ws *eq_angle_ws_alloc(const whirl_chain *c, double omega);
int eq_angle_polish(angle_ws *w, double *tip_r);
nlink_quad eq_tip_quad(const nlink_scan *s, nlink_quad a, double *theta);
nlink_quad eq_pivot_quad(const nlink_scan *s, nlink_quad tan_1, double *theta);
int eq_polish_root(angle_ws *aw, const nlink_scan *s, quad_fn f, double lo, double hi,
                   double *a, size_t *refined);

/* equilibria_list.c: the list of equilibria */
int eq_list_add(eq_list *l, double tip_r, const double *theta, int source);
size_t eq_list_merge(eq_list *l, double tip_r, const double *theta, int source, int *status);
int eq_list_unique(eq_list *l);

/* equilibria_follow.c: continuation of the curves through the roots */
int eq_continue_all(const whirl_chain *c, double omega, double factor, const double *crit,
                    eq_list *l, angle_ws *aw, whirl_equilibria *res);

#endif
