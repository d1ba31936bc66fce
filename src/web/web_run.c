/* The page's runs in time (whirl_web.h): the perturbed run of the steady shape and the shaken
 * chain, frame by frame, each frame one JSON answer (web_internal.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"
#include "whirl/periodic.h"
#include "whirl/stability.h"
#include "whirl/steady.h"
#include "web/whirl_web.h"
#include "web/web_internal.h"

/* ---- the perturbed run: the state's chain seeded with its steady shape, each link turned by
 * RUN_PERTURB (whirl_perturb_links, seed 1: the command line's [start] perturb), integrated by
 * gauss2 in the co-rotating frame for RUN_PERIODS rotation periods at the library's default step
 * (whirl_default_step, shortened to divide a frame's time), RUN_FRAMES frames ---- */

#define RUN_PERIODS 40
#define RUN_FRAMES 400
#define RUN_PERTURB 1e-3 /* [rad] */
#define SHAKE_FRAMES 800     /* the shaken run's frames after the start */
#define SHAKE_PER_PERIOD 8   /* its frames per period of the path */
#define SHAKE_FREE 10        /* its frames per time unit sqrt(L/g) without a path */

struct whirl_web_run {
    web_state s;
    whirl_chain *c;
    whirl_dyn *d;
    whirl_integrator *it;
    whirl_pivot_path path;   /* the shaken run's pivot path */
    int shaken, moving;      /* a shaken run (whirl_web_shake_alloc); its pivot moves */
    int total;               /* frames in all, the start's included */
    double *y, *x, *v, *ref; /* the state; positions, velocities, the unperturbed positions */
    double t, every, dt;     /* [sqrt(L/g)] */
    int frames;              /* written so far (frame 0 is the start) */
    int failed;              /* the start or a step failed: s.field and s.message say why */
};

/* The unperturbed steady shape's links, the reference positions, then the perturbed start. */
static int run_start(whirl_web_run *r)
{
    web_state *s = &r->s;
    const size_t n = r->c->n;
    double *buf = malloc(3 * (n + 1) * sizeof *buf), *links = malloc(3 * n * sizeof *links);
    whirl_shape_info info;
    double h = 0;
    int status = buf && links ? GSL_SUCCESS : GSL_ENOMEM;
    if (status == GSL_SUCCESS)
        status = whirl_nlink_solve_nodes(r->c, s->w, s->mode, &info, buf, buf + n + 1,
                                         buf + 2 * (n + 1));
    if (status == GSL_SUCCESS) status = whirl_shape_links(n, buf, NULL, buf + n + 1, links);
    if (status == GSL_SUCCESS) status = whirl_dyn_state_from_shape(r->d, 0, links, s->w, r->y);
    if (status == GSL_SUCCESS)
        status = whirl_dyn_get_state(r->d, 0, r->y, WHIRL_FRAME_INERTIAL, r->ref, r->v);
    if (status == GSL_SUCCESS) status = whirl_perturb_links(n, links, RUN_PERTURB, 1);
    if (status == GSL_SUCCESS) status = whirl_dyn_state_from_shape(r->d, 0, links, s->w, r->y);
    /* the default step from the shape's link tensions (buf + 2 (n + 1) + 1: links 1..n) */
    if (status == GSL_SUCCESS)
        status = whirl_default_step(whirl_dyn_model(r->d), buf + 2 * (n + 1) + 1, "gauss2", &h);
    free(buf);
    free(links);
    if (status == GSL_ENOMEM) return web_state_fail(s, "", "out of memory");
    if (status != GSL_SUCCESS) return web_library_fail(s, "rate");
    r->every = RUN_PERIODS * 2 * M_PI / s->w / RUN_FRAMES;
    r->dt = r->every / ceil(r->every / h);
    return 0;
}

/* The run's dynamics of the model m, its pivot on r->path if it moves, gauss2 and the buffers. */
static int run_workspace(whirl_web_run *r, const whirl_model *m)
{
    web_state *s = &r->s;
    r->d = whirl_dyn_alloc(m, WHIRL_FORMULATION_CARTESIAN);
    if (r->d && r->moving && whirl_dyn_set_pivot(r->d, whirl_pivot_eval, &r->path) != GSL_SUCCESS)
        return web_library_fail(s, "pivot");
    /* gauss2 by its type, not by its name: the table of every method would bring GSL's ODE
     * solvers into the page (50 kB of WebAssembly it does not use) */
    whirl_system sys;
    r->it = r->d && whirl_dyn_system(r->d, &sys) == GSL_SUCCESS
                ? whirl_integrator_alloc_system(whirl_integrator_gauss2, &sys)
                : NULL;
    const size_t n = r->c->n;
    if (r->it == NULL) return web_library_fail(s, "links");
    r->y = malloc(whirl_dyn_size(r->d) * sizeof *r->y);
    r->x = malloc(9 * n * sizeof *r->x);
    if (r->y == NULL || r->x == NULL) return web_state_fail(s, "", "out of memory");
    r->v = r->x + 3 * n;
    r->ref = r->x + 6 * n;
    return 0;
}

whirl_web_run *whirl_web_run_alloc(const char *query)
{
    whirl_web_run *r = calloc(1, sizeof *r);
    if (r == NULL) return NULL;
    web_state *s = &r->s;
    r->total = RUN_FRAMES + 1;
    if (web_read_state(s, query)) {
        r->failed = 1;
        return r;
    }
    double born = 0;
    r->c = web_chain_of(s, s->links ? s->links : VERDICT_LINKS);
    if (r->c == NULL || web_birth(s, r->c, s->mode, &born) != 0) {
        r->failed = 1;
        return r;
    }
    if (!(s->w > born)) {
        web_state_fail(s, "rate", "mode %d is born at %.4g %s: below it there is no shape to perturb",
                   s->mode, born / s->time / s->unit, s->unit_name);
        r->failed = 1;
        return r;
    }
    const whirl_model m = {.chain = r->c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = s->w,
                           .air_drag = s->drag, .air_drag_quadratic = s->drag2};
    r->failed = run_workspace(r, &m) != 0 || run_start(r) != 0;
    return r;
}

/* The shaken run's start: the chain straight down or up, each link turned by the tilt about y,
 * moving with the pivot; the step: whirl_default_step's under the tensions of the chain
 * hanging in the gravity raised by the pivot's largest acceleration (a bound in either
 * start); a frame every SHAKE_PER_PERIOD of the path's period (SHAKE_FREE of a time unit
 * sqrt(L/g) without a path). */
static int shake_start(whirl_web_run *r)
{
    web_state *s = &r->s;
    const size_t n = r->c->n;
    double *links = malloc(3 * n * sizeof *links), *tension = malloc(n * sizeof *tension);
    double amax = 0, h = 0;
    for (int j = 0; r->moving && j < r->path.harmonics; j++) {
        double a2 = 0;
        for (int k = 0; k < 3; k++) a2 += gsl_pow_2(r->path.c[k][j]) + gsl_pow_2(r->path.s[k][j]);
        amax += sqrt(a2) * gsl_pow_2((j + 1) * r->path.omega);
    }
    int status = links && tension ? GSL_SUCCESS : GSL_ENOMEM;
    double below = 0;
    for (size_t i = n; status == GSL_SUCCESS && i-- > 0;) {
        const double l = r->c->length[i];
        links[3 * i] = l * sin(s->tilt);
        links[3 * i + 1] = 0;
        links[3 * i + 2] = (s->inverted ? 1 : -1) * l * cos(s->tilt);
        below += r->c->mass[i];
        tension[i] = (r->c->gravity + amax) * below;
    }
    if (status == GSL_SUCCESS) status = whirl_dyn_state_from_shape(r->d, 0, links, 0, r->y);
    if (status == GSL_SUCCESS)
        status = whirl_default_step(whirl_dyn_model(r->d), tension, "gauss2", &h);
    free(links);
    free(tension);
    if (status == GSL_ENOMEM) return web_state_fail(s, "", "out of memory");
    if (status != GSL_SUCCESS) return web_library_fail(s, r->moving ? "shake" : "links");
    r->every = r->moving ? whirl_pivot_period(&r->path) / SHAKE_PER_PERIOD : 1.0 / SHAKE_FREE;
    const double steps = ceil(r->every / h) * SHAKE_FRAMES;
    if (steps * (double)n > SHAKE_WORK_MAX)
        return web_state_fail(s, "shake", "shake: %zu links on this path need %.3g steps, beyond "
                          "what the page computes live (fewer links, a smaller amplitude or "
                          "frequency)", n, steps);
    r->dt = r->every / ceil(r->every / h);
    return 0;
}

whirl_web_run *whirl_web_shake_alloc(const char *query)
{
    whirl_web_run *r = calloc(1, sizeof *r);
    if (r == NULL) return NULL;
    web_state *s = &r->s;
    r->shaken = 1;
    r->total = SHAKE_FRAMES + 1;
    if (web_read_state(s, query)) {
        r->failed = 1;
        return r;
    }
    r->moving = s->pivot[0] != 0;
    if (r->moving && whirl_pivot_parse(s->pivot, s->shake_w, s->length, 3, &r->path)) {
        r->failed = web_library_fail(s, "pivot");
        return r;
    }
    r->c = web_chain_of(s, s->links ? s->links : VERDICT_LINKS);
    /* omega: the path's (whirl_default_step's period), 1 without a path */
    const whirl_model m = {.chain = r->c, .dim = 3, .frame = WHIRL_FRAME_INERTIAL,
                           .omega = r->moving ? s->shake_w : 1, .air_drag = s->drag,
                           .air_drag_quadratic = s->drag2};
    r->failed = r->c == NULL || run_workspace(r, &m) != 0 || shake_start(r) != 0;
    return r;
}

/* One frame at r->t (the chunk's first: no comma before it): t [s]; the deviation from the
 * unperturbed shape [m] (whirl_deviation: the RMS distance, minimised over a turn about the
 * axis), or for a shaken run the tip's height above the pivot [m] and the pivot's position;
 * then the masses' positions x, y, z [m] (7 digits: they are drawn) in the run's frame. */
static int run_frame(whirl_web_run *r, json *j, int first)
{
    const size_t n = r->c->n;
    double p[3] = {0, 0, 0}, pv[3], pa[3];
    int status = whirl_dyn_get_state(r->d, r->t, r->y, WHIRL_FRAME_INERTIAL, r->x, r->v);
    if (r->moving) whirl_pivot_eval(r->t, p, pv, pa, &r->path);
    const double dev = status != GSL_SUCCESS ? NAN
                       : r->shaken           ? r->x[3 * n - 1] - p[2]
                                             : whirl_deviation(n, r->x, r->ref);
    if (status == GSL_SUCCESS && !r->shaken && r->s.frame != WHIRL_FRAME_INERTIAL)
        status = whirl_dyn_get_state(r->d, r->t, r->y, r->s.frame, r->x, r->v);
    if (status != GSL_SUCCESS || !isfinite(dev))
        return web_library_fail(&r->s, r->shaken ? "shake" : "rate");
    web_put(j, "%s[", first ? "" : ",");
    web_put_number(j, r->t * r->s.time);
    web_put(j, ",");
    web_put_number(j, dev * r->s.length);
    for (int k = 0; r->shaken && k < 3; k++) web_put(j, ",%.7g", p[k] * r->s.length);
    for (size_t i = 0; i < 3 * n; i++) web_put(j, ",%.7g", r->x[i] * r->s.length);
    web_put(j, "]");
    r->frames++;
    return 0;
}

char *whirl_web_run_next(whirl_web_run *r, int count)
{
    if (r == NULL) return web_error_answer("", "no run");
    web_state *s = &r->s;
    const int last = r->total - 1;
    json j = {0};
    web_put(&j, "{\"links\":%zu,\"total\":%d", r->c ? r->c->n : 0, r->total);
    web_put_key_number(&j, "t_end", r->shaken ? last * r->every * s->time
                                          : RUN_PERIODS * 2 * M_PI / s->omega);
    const double period = !r->shaken ? 2 * M_PI / s->omega
                          : r->moving ? whirl_pivot_period(&r->path) * s->time
                                      : 0; /* a free swing: none */
    web_put_key_number(&j, "period", period);
    web_put_key_number(&j, "dt", r->dt * s->time);
    web_put(&j, ",\"steps\":%.0f", r->every > 0 ? round(r->every / r->dt) : 0);
    web_put(&j, ",\"frame\":\"%s\",\"shaken\":%s,\"frames\":[",
        r->shaken || s->frame == WHIRL_FRAME_INERTIAL ? "inertial" : "rotating",
        r->shaken ? "true" : "false");
    const int first = r->frames;
    while (!r->failed && r->frames - first < count && r->frames <= last) {
        if (r->frames > 0) { /* frame k at k every */
            if (whirl_integrator_advance(r->it, &r->t, r->y, r->frames * r->every, r->dt, 0) !=
                GSL_SUCCESS) {
                r->failed = web_library_fail(s, r->shaken ? "shake" : "rate");
                break;
            }
        }
        r->failed = run_frame(r, &j, r->frames == first) != 0;
    }
    web_put(&j, "],\"done\":%s}", r->frames > last ? "true" : "false");
    if (r->failed) {
        free(j.text);
        return web_error_answer(s->field, s->message);
    }
    return web_finish(&j);
}

void whirl_web_run_free(whirl_web_run *r)
{
    if (r == NULL) return;
    whirl_integrator_free(r->it);
    whirl_dyn_free(r->d);
    whirl_chain_free(r->c);
    free(r->y);
    free(r->x);
    free(r);
}
