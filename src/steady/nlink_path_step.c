/* One step of the N-link continuation (src/steady/nlink_path.c): the loop both formulations
 * share, the tip shot (nlink_path_shot.c) and the link angles (nlink_path_angles.c) behind
 * step_ops. A trial of length ds is predicted, corrected and measured by the formulation; the
 * tests common to both judge it (the turn of the tangent, the change of a link angle, the chord,
 * the orientation, in the link angles also the index and the eigenvalue nearest zero); a
 * rejected trial is shortened by the formulation (or handed over to the link angles); an
 * accepted one becomes the point, its events are located (nlink_path_events.c), and where an
 * event cannot be located the step is taken back by one undo: the path's public part and state
 * as they were before it (path_snapshot) and the start's link angles and tangent. */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"

/* A stop request at the current point. */
int path_stopped(const nlink_path *p)
{
    return whirl_fail(WHIRL_EINTERRUPTED, "stopped at omega=%.17g after %ld steps", p->pub.omega,
                      p->pub.steps);
}

/* The failure of the continuation at the last point (w0, a0) with a step below its smallest:
 * names the rate reached and why the last trial step was rejected (whirl_nlink_path_step adds
 * the mode). */
int path_fail_at(nlink_path *p, int status, double w0, double a0)
{
    if (p->pub.angles)
        return whirl_fail(status, "the continuation in the link angles fails at omega=%.17g "
                          "(tip radius %.6g, link tensions differing by a factor %.2g): %s at "
                          "the smallest step %g", w0, a0,
                          path_tension_spread(p->pub.chain, w0, a0), p->s.why, ds_smallest(p));
    return whirl_fail(status, "the continuation fails at omega=%.17g (tip radius %.6g): %s at "
                      "the smallest step %g", w0, a0, p->s.why, DS_MIN);
}

/* The accepted step's start, kept for the events, the crossings and the undo. */
static void keep_start(nlink_path *p, const double *m0, double w0, double a0, double ds)
{
    for (int i = 0; i < 3; i++) p->s.last.m0[i] = m0 ? m0[i] : 0;
    p->s.last.w0 = w0;
    p->s.last.a0 = a0;
    p->s.last.t_w = p->pub.t_omega;
    p->s.last.t_a = p->pub.t_tip;
    p->s.last.ds = ds;
    p->s.last.raw_sign = p->s.raw_sign;
    p->s.last.angles = p->pub.angles;
    p->s.last.det_sign = p->s.det_sign;
    p->s.last.index = p->s.index;
    p->s.last.mu = p->s.mu;
    p->s.last.mu_rate = p->s.mu_rate;
    p->s.last_rate_sign = p->s.rate_sign;
    for (size_t i = 0; i < p->pub.chain->n; i++)
        arr_theta0(p)[i] = arr_theta(p)[i], arr_t_theta0(p)[i] = arr_t_theta(p)[i];
    p->s.have_last = 1;
}

/* The path before an accepted step: all of it but the arrays. */
typedef struct path_snapshot {
    whirl_nlink_path pub;
    path_state s;
} path_snapshot;

/* Takes back the step of length ds after an event on it could not be located: the path as in
 * u (the arrays exchanged with their trials come back with their offsets; the start's link
 * angles and tangent, which the events' location used as scratch, from keep_start), its
 * evaluations counted on; the next trial half as long. The arclength is taken back as the step
 * added it. */
static void undo(nlink_path *p, const path_snapshot *u, double ds)
{
    const long shots = p->pub.shots;
    const double arclength = p->pub.arclength;
    p->pub = u->pub;
    p->s = u->s;
    for (size_t i = 0; i < p->pub.chain->n; i++)
        arr_theta(p)[i] = arr_theta0(p)[i], arr_t_theta(p)[i] = arr_t_theta0(p)[i];
    p->pub.shots = shots;
    p->pub.arclength = arclength - ds;
    p->pub.n_events = 0;
    p->pub.ended = 0;
    p->pub.rejected++;
    p->pub.ds = 0.5 * ds;
    p->s.have_last = 0;
    p->s.why = "an event between two points could not be located";
}

/* The tests both formulations make of a trial that converged (its measures in t): t->ok = 0
 * with the reason in p->s.why where one fails. In the crossing mode (link angles) only a step on
 * which the orientation reverses is taken; with the chord test set aside (chord_off) the chord
 * is not looked at. */
static void judge(nlink_path *p, step_ctx *x, step_trial *t)
{
    const int branch = t->ds > x->ds_branch && !x->crossing;
    if (t->turn > TURN_MAX && !x->crossing)
        t->ok = 0, p->s.why = "the tangent turns by more than 0.2 rad";
    if (t->dtheta > DTHETA_MAX) t->ok = 0, p->s.why = "a link angle changes by more than 0.2 rad";
    x->chord_failed = t->chord && !x->crossing && !x->chord_off;
    if (x->chord_failed) t->ok = 0, p->s.why = t->chord;
    if (t->flip && branch)
        t->ok = 0, p->s.why = "the orientation test changes sign (another curve close by)";
    if (t->jump && branch)
        t->ok = 0, p->s.why = "the index of the force balance changes by more than one (two "
                              "singular points passed over)";
    if (t->pair && branch)
        t->ok = 0, p->s.why = "an eigenvalue of the force balance crosses zero and back within "
                              "the step (two folds passed over)";
    if (!t->flip && x->crossing) t->ok = 0;
}

/* One accepted step with the formulation ops (which can hand the step over to the link angles,
 * STEP_ANGLES). */
static int step_with(nlink_path *p, const step_ops *ops)
{
    step_ctx x;
    ops->begin(p, &x);
    for (;;) {
        step_trial t = {.ds = p->pub.ds, .iters = NEWTON_MAX, .index = -1, .mu = NAN,
                        .mu_rate = NAN, .mu_min = INFINITY};
        ops->trial(p, &x, &t);
        if (t.ok) judge(p, &x, &t);
        int status = GSL_SUCCESS;
        if (t.ok) status = ops->ready(p, &x, &t);
        if (!t.ok) {
            p->pub.rejected++;
            status = ops->rejected(p, &x, &t);
        }
        if (status == STEP_RETRY) continue;
        if (status == STEP_ANGLES) {
            ops = &path_angle_ops;
            ops->begin(p, &x);
            continue;
        }
        if (status != GSL_SUCCESS) return status;
        path_snapshot u = {p->pub, p->s};
        keep_start(p, x.m0, x.w0, x.a0, t.ds);
        ops->accept(p, &x, &t);
        p->pub.arclength += t.ds;
        p->pub.steps++;
        status = path_find_events(p, t.flip);
        if (status != GSL_EFAILED) {
            if (t.iters <= NEWTON_EASY && t.turn < TURN_MAX / 2 && t.dtheta < DTHETA_MAX / 2)
                p->pub.ds = fmin(DS_GROW * t.ds, DS_MAX);
            return status;
        }
        /* an event the step passed could not be located (the curve between the two points is
         * more intricate than the step: two close folds, a near crossing of another branch):
         * back to the step's start, half the step */
        undo(p, &u, t.ds);
        if (x.crossing || p->pub.ds < x.ds_min) return path_fail_at(p, GSL_EFAILED, x.w0, x.a0);
    }
}

/* whirl_nlink_path_step, its failures not yet led by the mode */
int path_step(nlink_path *p)
{
    p->pub.n_events = 0;
    if (p->pub.ended)
        return whirl_fail(GSL_EDOM, "the branch ended on the hanging chain at omega=%.17g",
                          p->pub.omega);
    if (whirl_stop_requested()) return path_stopped(p);
    /* the formulation of this step: the link angles where the shot's round-off is felt, with
     * a hysteresis (each switch polishes the point on the other formulation) */
    if (!p->pub.angles && p->s.noise > NOISE_UP) path_to_angles(p);
    else if (p->pub.angles && p->s.stay > 0) p->s.stay--;
    else if (p->pub.angles && p->s.noise < NOISE_DOWN) path_to_shot(p);
    return step_with(p, p->pub.angles ? &path_angle_ops : &path_shot_ops);
}

int whirl_nlink_path_step(whirl_nlink_path *path)
{
    nlink_path *p = path_of(path);
    return path_name_mode(p, path_step(p));
}
