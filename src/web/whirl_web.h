/* The flat interface of the page (src/web/whirl_web.c): the page's state as a query in, one
 * JSON object out (malloc'd; whirl_web_free), never NULL but for a lack of memory. */
#ifndef WHIRL_WEB_H
#define WHIRL_WEB_H

/* The steady shape of the state's mode at its rate (x, z, tension at the nodes or at 201
 * points of the continuum), its tip radius, node count and birth rate, and the linear verdict
 * of the N-link chain (30 links for the continuum); below the birth {"hanging": true, ...}. */
char *whirl_web_shape(const char *query);
/* The tip radius against the rate up to rmax of the modes born below it (at most 6). */
char *whirl_web_branches(const char *query);
/* The windows of instability of the state's mode up to rmax: [from, to, largest growth]. */
char *whirl_web_windows(const char *query);
void whirl_web_free(char *answer);

/* The periodic motion of the shaken run's settings (its chain, 30 links for the continuum; its
 * pivot path at the rate shake; drag and drag2; start hanging or inverted, untilted) found as
 * whirl periodic finds it (web_floquet.c), and its Floquet multipliers: {"links", "start",
 * "dissipative", "unit", "shake", "period" [s], "steps", "iterations", "residual", "verdict"
 * (stable, neutral, unstable), "edge", "edge_distance", "growth" (per period), "efold_periods",
 * "efold_time" [s], "max_modulus", "max_modulus_err", "reciprocal_err", "orbit_change",
 * "multipliers": [[re, im, |mu|, err], ...] by decreasing modulus}; a bad setting, a fixed
 * pivot, too much work or Newton's method that does not converge: {"error", "field"}. */
char *whirl_web_floquet(const char *query);

/* The perturbed run of the state: its chain (30 links for the continuum) seeded with its steady
 * shape, each link turned by 1 mrad, 40 rotation periods in 401 frames. NULL only for a lack of
 * memory; a bad state or a failed start is answered by the first whirl_web_run_next. */
typedef struct whirl_web_run whirl_web_run;
whirl_web_run *whirl_web_run_alloc(const char *query);
/* A shaken run of the state (the query's pivot path at the rate shake: whirl_pivot_parse's
 * grammar, "none" or absent for a fixed pivot; its chain, 30 links for the continuum, started
 * straight down or, start=inverted, straight up, each link turned by tilt degrees (default 5)
 * about y, moving with the pivot; drag and drag2 as for every run): SHAKE_FRAMES (800) frames
 * after the start, 8 to a period of the path (10 to a time unit sqrt(L/g) without one). Its
 * frames are [t, the tip's height above the pivot, px, py, pz (the pivot), x1, ..., zN],
 * inertial; "shaken": true. Read and freed as a perturbed run. */
whirl_web_run *whirl_web_shake_alloc(const char *query);
/* The next count frames: {"links", "total", "t_end", "period", "dt" (the step), "steps" (per frame), "frame", "shaken", "frames": [[t, deviation,
 * x1, y1, z1, ..., xN, yN, zN], ...], "done"} in SI, or {"error", "field"}. */
char *whirl_web_run_next(whirl_web_run *r, int count);
void whirl_web_run_free(whirl_web_run *r);

#endif
