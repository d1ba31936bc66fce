/* Running a scene (include/whirl/scene.h): the start state, the time loop and the CSV writers.
 *
 * The start state, in the run's frame at t = 0, the pivot at p0 = (drive_radius, 0, 0) moving
 * with the drive:
 *  - steady: the N-link relative equilibrium of mode k at omega_s in the x-z plane
 *    (whirl_nlink_solve_nodes), each link turned by perturb
 *    (whirl_perturb_links), turning rigidly at omega_s (whirl_dyn_state_from_shape);
 *  - angles: link unit vectors u_i = (sin th cos ph, sin th sin ph, -cos th) (2D: (sin th, 0,
 *    -cos th)), x_i = p0 + sum_{k<=i} l_k u_k, velocities p0' + sum l_k du_k/dt;
 *  - hanging: u_i = -z, moving with the pivot, its links turned by perturb as for the steady start.
 * Rows at t = k every and at t_end: positions in the inertial frame; energy, jacobi, lz and
 * constraint from whirl_dyn_diagnose; deviation = whirl_deviation from the unperturbed steady
 * (or hanging) shape, or from the mode-K shape at omega with [output] reference_mode. Fixed steps
 * are taken one call at a time, so that the stop condition and the stop request are checked
 * after every step; adaptive runs check at the output times (and the integrator every step). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "whirl/scene.h"
#include "whirl/steady.h"
#include "dynamics/dyn_internal.h"
#include "core/error.h"
#include "studies/scene_internal.h"

struct whirl_scene_work {
    const whirl_scene *scene;
    whirl_chain *chain;
    whirl_model model;
    whirl_dyn *dyn;
    whirl_integrator *integrator;
    size_t n;      /* links */
    double *y;     /* state */
    double *x, *v; /* 3 per mass: positions and velocities */
    double *ref;   /* 3 per mass: the reference shape of the deviation */
    double *links; /* 3 per link */
    double t;
    int has_pivot;          /* the pivot follows pivot (whirl_dyn_set_pivot), not the drive */
    whirl_pivot_path pivot; /* the scene's [run] pivot, copied */
};

/* "WHERE: message" for a key of the scene: the status with that message. */
static int key_fail(const whirl_scene *s, int status, whirl_scene_key key, const char *message)
{
    char where[512], copy[600];
    snprintf(copy, sizeof copy, "%s", message); /* message may be whirl_error_marked() */
    return whirl_fail(status, "%s: %s", whirl_scene_where(s, key, where, sizeof where), copy);
}

/* x_i = p0 + sum of the vectors d_1..d_i (3 per link) into x. */
static void accumulate(size_t n, const double *p0, const double *d, double *x)
{
    double r[3] = {p0[0], p0[1], p0[2]};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) x[3 * i + k] = r[k] += d[3 * i + k];
}

/* The link vectors (3 per link) of the N-link steady shape of mode k at omega, in the x-z plane;
 * key names the scene key to blame if there is none. */
static int mode_links(whirl_scene_work *w, double omega, int mode, whirl_scene_key key,
                      double *links)
{
    const size_t n = w->n;
    whirl_shape_info info;
    char msg[600];
    double *rr = malloc(3 * (n + 1) * sizeof *rr);
    if (rr == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    double *zz = rr + n + 1, *tension = zz + n + 1;
    if (whirl_nlink_solve_nodes(w->chain, omega, mode, &info, rr, zz, tension) != GSL_SUCCESS) {
        free(rr);
        snprintf(msg, sizeof msg, "no steady shape: %s", whirl_error_marked());
        return key_fail(w->scene, GSL_EDOM, key, msg);
    }
    int status = whirl_shape_links(n, rr, NULL, zz, links);
    free(rr);
    if (status != GSL_SUCCESS) {
        snprintf(msg, sizeof msg, "steady shape: %s", whirl_error_marked());
        return key_fail(w->scene, status, key, msg);
    }
    return GSL_SUCCESS;
}

/* The seed's angles: x and v from the angles and their rates. */
static int angle_start(whirl_scene_work *w, const double *p0)
{
    const whirl_scene *s = w->scene;
    double pos[3], vel[3], pp[3], pv[3], pa[3], omega;
    whirl_dyn_pivot(w->dyn, 0, pp, pv, pa);
    whirl_dyn_drive_at(w->dyn, 0, NULL, &omega, NULL);
    /* zero rates: at rest in the inertial frame but for the pivot's motion */
    const double wf = w->model.frame == WHIRL_FRAME_ROTATING ? omega : 0;
    memcpy(pos, p0, sizeof pos);
    memcpy(vel, pv, sizeof vel);
    for (size_t i = 0; i < w->n; i++) {
        const double th = s->theta[i], ph = s->phi[i], thd = s->theta_dot[i];
        const double phd = s->phi_dot[i], l = s->length[i];
        const double st = sin(th), ct = cos(th), sp = sin(ph), cp = cos(ph);
        const double d[3] = {l * st * cp, l * st * sp, -l * ct};
        const double dd[3] = {l * (thd * ct * cp - phd * st * sp),
                              l * (thd * ct * sp + phd * st * cp), l * thd * st};
        for (int k = 0; k < 3; k++) {
            w->x[3 * i + k] = pos[k] += d[k];
            w->v[3 * i + k] = vel[k] += dd[k];
        }
        w->v[3 * i] += wf * (pos[1] - p0[1]);
        w->v[3 * i + 1] -= wf * (pos[0] - p0[0]);
    }
    return whirl_dyn_set_state(w->dyn, 0, w->x, w->v, w->y);
}

/* A planar scene's perturbation: whirl_perturb_links turns link i of the unperturbed shape
 * (from the nodes ref, the pivot p0) by the angle towards a random direction perpendicular to it
 * in space; in the x-z plane the perpendicular direction is p = (u_z, 0, -u_x) up to its sign, so
 * the link is turned by the same angle towards p or -p, the side of the random direction's
 * component along p (the same seed, the same sides). */
static void planar_turn(const whirl_scene *s, size_t n, double *links, const double *ref,
                        const double *p0)
{
    for (size_t i = 0; i < n; i++) {
        const double *top = i == 0 ? p0 : ref + 3 * (i - 1), *bottom = ref + 3 * i;
        const double len = s->length[i];
        const double u[3] = {(bottom[0] - top[0]) / len, 0, (bottom[2] - top[2]) / len};
        const double p[3] = {u[2], 0, -u[0]};
        double *d = links + 3 * i;
        const double side = d[0] * p[0] + d[2] * p[2] >= 0 ? 1 : -1;
        for (int k = 0; k < 3; k++)
            d[k] = len * (cos(s->perturb) * u[k] + side * sin(s->perturb) * p[k]);
    }
}

/* w->y with the start state; w->ref with the reference shape. */
static int start_state(whirl_scene_work *w)
{
    const whirl_scene *s = w->scene;
    const size_t n = w->n;
    double p0[3], pv[3], pa[3];
    whirl_dyn_pivot(w->dyn, 0, p0, pv, pa);
    int status = GSL_SUCCESS;
    if (s->start == WHIRL_START_ANGLES) {
        status = angle_start(w, p0);
        memcpy(w->ref, w->x, 3 * n * sizeof *w->x);
    } else {
        double spin = 0;
        if (s->start == WHIRL_START_STEADY) {
            status = mode_links(w, s->start_omega, s->mode, WHIRL_KEY_START_MODE, w->links);
            spin = s->start_omega;
        } else {
            for (size_t i = 0; i < n; i++) {
                w->links[3 * i] = w->links[3 * i + 1] = 0;
                w->links[3 * i + 2] = -s->length[i];
            }
        }
        if (status) return status;
        accumulate(n, p0, w->links, w->ref);
        if (s->perturb > 0 && (status = whirl_perturb_links(n, w->links, s->perturb, s->seed)))
            return key_fail(s, status, WHIRL_KEY_START_PERTURB, whirl_error_marked());
        if (s->perturb > 0 && s->dim == 2) planar_turn(s, n, w->links, w->ref, p0);
        status = whirl_dyn_state_from_shape(w->dyn, 0, w->links, spin, w->y);
    }
    if (status) {
        char copy[512];
        snprintf(copy, sizeof copy, "%s", whirl_error_marked());
        return whirl_fail(status, "%s: [start]: %s", s->path, copy);
    }
    if (s->reference_mode > 0) {
        status = mode_links(w, s->omega, s->reference_mode, WHIRL_KEY_OUTPUT_REFERENCE_MODE,
                            w->links);
        if (status) return status;
        accumulate(n, p0, w->links, w->ref);
    }
    return GSL_SUCCESS;
}

void whirl_scene_work_free(whirl_scene_work *w)
{
    if (w == NULL) return;
    free(w->y);
    free(w->x);
    whirl_integrator_free(w->integrator);
    whirl_dyn_free(w->dyn);
    whirl_chain_free(w->chain);
    free(w);
}

/* The workspace of scene s into *out: GSL_SUCCESS, or the status of the failure (message set,
 * *out NULL). */
static int work_alloc(const whirl_scene *s, const whirl_scene_pivot *pivot,
                      whirl_scene_work **out)
{
    *out = NULL;
    if (s == NULL || s->links < 1 || s->length == NULL || s->mass == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_scene_work_alloc: needs a parsed scene");
    int status = GSL_EINVAL;
    whirl_scene_work *w = calloc(1, sizeof *w);
    if (w == NULL) goto nomem;
    w->scene = s;
    w->n = s->links;
    w->chain = whirl_chain_alloc(s->links, s->length, s->mass, s->gravity);
    if (w->chain == NULL) {
        whirl_fail(GSL_EINVAL, "%s: [chain]: %s", s->path, whirl_error_marked());
        goto fail;
    }
    w->model = (whirl_model){
        .chain = w->chain,
        .dim = s->dim,
        .frame = s->frame,
        .omega = s->omega,
        .drive_radius = s->drive_radius,
        .air_drag = s->air_drag,
        .air_drag_quadratic = s->air_drag_quadratic,
        .internal_damping = s->internal_damping,
        .seed_sigma = s->seed_sigma,
        .seed_lambda = s->seed_lambda,
    };
    w->dyn = whirl_dyn_alloc(&w->model, s->formulation);
    if (w->dyn == NULL) {
        whirl_fail(GSL_EINVAL, "%s: [run]: %s", s->path, whirl_error_marked());
        goto fail;
    }
    if (whirl_dyn_set_threads(w->dyn, s->threads > 0 ? s->threads : 1) != GSL_SUCCESS) {
        key_fail(s, GSL_EINVAL, WHIRL_KEY_RUN_THREADS, whirl_error_marked());
        goto fail;
    }
    if (pivot != NULL && pivot->given) { /* before the start state, which moves with it */
        w->pivot = pivot->path;
        w->has_pivot = 1;
        if (whirl_pivot_check(&w->pivot, s->dim) != GSL_SUCCESS ||
            whirl_dyn_set_pivot(w->dyn, whirl_pivot_eval, &w->pivot) != GSL_SUCCESS) {
            char where[512], copy[512];
            snprintf(copy, sizeof copy, "%s", whirl_error_marked());
            whirl_fail(GSL_EINVAL, "%s: %s", sc_where(s, SC_KEY_RUN_PIVOT, pivot->line, where,
                                                      sizeof where), copy);
            goto fail;
        }
    }
    w->integrator = whirl_integrator_alloc(s->method, w->dyn);
    if (w->integrator == NULL) {
        key_fail(s, GSL_EINVAL, WHIRL_KEY_RUN_METHOD, whirl_error_marked());
        goto fail;
    }
    w->y = malloc(whirl_dyn_size(w->dyn) * sizeof *w->y);
    w->x = malloc(12 * w->n * sizeof *w->x);
    if (!w->y || !w->x) goto nomem;
    w->v = w->x + 3 * w->n;
    w->ref = w->v + 3 * w->n;
    w->links = w->ref + 3 * w->n;
    if ((status = start_state(w)) != GSL_SUCCESS) goto fail;
    /* an advance of zero length checks the step and the tolerance against the method */
    double t = 0;
    if (whirl_integrator_advance(w->integrator, &t, w->y, 0, s->dt, s->tol) != GSL_SUCCESS) {
        key_fail(s, GSL_EINVAL, s->tol > 0 ? WHIRL_KEY_RUN_TOL : WHIRL_KEY_RUN_DT,
                 whirl_error_marked());
        goto fail;
    }
    *out = w;
    return GSL_SUCCESS;
nomem:
    status = whirl_fail(GSL_ENOMEM, "out of memory for the run of %zu links", s->links);
fail:
    whirl_scene_work_free(w);
    return status;
}

whirl_scene_work *whirl_scene_work_alloc_with_pivot(const whirl_scene *s,
                                                    const whirl_scene_pivot *pivot)
{
    whirl_scene_work *w;
    work_alloc(s, pivot, &w);
    return w;
}

whirl_scene_work *whirl_scene_work_alloc(const whirl_scene *s)
{
    return whirl_scene_work_alloc_with_pivot(s, NULL);
}

const whirl_dyn *whirl_scene_work_dyn(const whirl_scene_work *w) { return w->dyn; }
const double *whirl_scene_work_state(const whirl_scene_work *w) { return w->y; }

/* The columns at t (value[WHIRL_NCOLUMNS], indexed by whirl_column). */
static int row_values(whirl_scene_work *w, double t, double *value)
{
    const int *want = w->scene->want;
    memset(value, 0, WHIRL_NCOLUMNS * sizeof *value);
    value[WHIRL_COLUMN_T] = t;
    if (want[WHIRL_COLUMN_TIP_X] || want[WHIRL_COLUMN_TIP_Y] || want[WHIRL_COLUMN_TIP_Z] ||
        want[WHIRL_COLUMN_DEVIATION]) {
        int status = whirl_dyn_get_state(w->dyn, t, w->y, WHIRL_FRAME_INERTIAL, w->x, w->v);
        if (status) return status;
        const double *tip = w->x + 3 * (w->n - 1);
        value[WHIRL_COLUMN_TIP_X] = tip[0];
        value[WHIRL_COLUMN_TIP_Y] = tip[1];
        value[WHIRL_COLUMN_TIP_Z] = tip[2];
        if (want[WHIRL_COLUMN_DEVIATION])
            value[WHIRL_COLUMN_DEVIATION] = whirl_deviation(w->n, w->x, w->ref);
    }
    if (want[WHIRL_COLUMN_ENERGY] || want[WHIRL_COLUMN_JACOBI] || want[WHIRL_COLUMN_LZ] ||
        want[WHIRL_COLUMN_CONSTRAINT]) {
        whirl_dyn_diagnostics diag;
        int status = whirl_dyn_diagnose(w->dyn, t, w->y, &diag);
        if (status) return status;
        value[WHIRL_COLUMN_ENERGY] = diag.energy;
        value[WHIRL_COLUMN_JACOBI] = diag.jacobi;
        value[WHIRL_COLUMN_LZ] = diag.lz;
        value[WHIRL_COLUMN_CONSTRAINT] = diag.constraint;
    }
    return GSL_SUCCESS;
}

/* The pivot and the masses in the inertial frame at t, to the frame callback. */
static int frame_out(whirl_scene_work *w, double t, const whirl_scene_output *out)
{
    int status = whirl_dyn_get_state(w->dyn, t, w->y, WHIRL_FRAME_INERTIAL, w->x, w->v);
    if (status) return status;
    if (w->has_pivot) { /* the path is in the inertial frame */
        double p[3], pv[3], pa[3];
        whirl_dyn_pivot(w->dyn, t, p, pv, pa);
        return out->frame(out->ctx, t, p, w->x, w->n);
    }
    double eps, phase;
    whirl_dyn_drive_at(w->dyn, t, &eps, NULL, &phase);
    const double p[3] = {eps * cos(phase), w->model.dim == 3 ? eps * sin(phase) : 0.0, 0.0};
    return out->frame(out->ctx, t, p, w->x, w->n);
}

/* The k-th output time of the interval every: k every, and t_end as the last (k = last). */
static size_t last_index(double every, double t_end)
{
    /* the scene bounds t_end / every (WHIRL_SCENE_ROWS_MAX); the cap keeps the cast defined for
     * any scene built by hand */
    const double k = ceil(t_end / every * (1 - 1e-12));
    return k < 1e15 ? (size_t)k : (size_t)1e15;
}
static double output_time(size_t k, size_t last, double every, double t_end)
{
    return k >= last ? t_end : (double)k * every;
}

/* The scene's model as whirl_model_stiff_rate reads it: the chain and the dissipation. */
static whirl_model stiff_model(const whirl_scene *s, whirl_chain *c)
{
    *c = (whirl_chain){.n = s->links, .length = s->length, .mass = s->mass, .gravity = s->gravity};
    return (whirl_model){.chain = c, .dim = s->dim, .frame = s->frame, .omega = s->omega,
                         .drive_radius = s->drive_radius, .air_drag = s->air_drag,
                         .air_drag_quadratic = s->air_drag_quadratic,
                         .internal_damping = s->internal_damping};
}

double whirl_scene_damping_rate(const whirl_scene *s)
{
    if (s == NULL) return 0;
    whirl_chain c;
    const whirl_model m = stiff_model(s, &c);
    return whirl_model_stiff_rate(&m);
}

/* h rate above 2: past what a fixed step of the explicit and fixed-point methods takes (2.785
 * for rk4, 3.46 for the Gauss fixed point; 2 leaves room for the estimate's 16) */
#define STIFF_H_RATE 2.0

int whirl_scene_stiff(const whirl_scene *s, double *rate)
{
    const double r = whirl_scene_damping_rate(s);
    if (rate) *rate = r;
    return r > 0 && s->tol == 0 && r * s->dt > STIFF_H_RATE &&
           !(s->method && strcmp(s->method, "gsl-msbdf") == 0);
}

const char *sc_stiff_cause(const whirl_scene *s)
{
    whirl_chain c;
    const whirl_model m = stiff_model(s, &c);
    return whirl_model_stiff_cause(&m);
}

/* "the internal damping makes the chain stiff ...": what whirl_scene_stiff found, and the method
 * that steps over it (GSL's BDF, implicit with a Newton iteration, adaptive) */
static void stiff_words(const whirl_scene *s, double rate, char *buf, size_t size)
{
    snprintf(buf, size, "%s the chain stiff (decay rates up to "
             "about %.2g %s, dt x rate = %.2g): fixed steps need dt below about %.2g, or use "
             "method = gsl-msbdf with tol (1e-6)", sc_stiff_cause(s), rate,
             s->physical ? "/s" : "sqrt(g/L)", rate * s->dt, STIFF_H_RATE / rate);
}

int whirl_scene_work_run(whirl_scene_work *w, const whirl_scene_output *out,
                         whirl_scene_result *res)
{
    if (w == NULL || out == NULL || res == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_scene_work_run: needs w, out and res");
    const whirl_scene *s = w->scene;
    const size_t last_row = last_index(s->every, s->t_end);
    const size_t last_frame = last_index(s->trace_every, s->t_end);
    const int trace = out->frame != NULL && s->trace_every > 0;
    size_t k_row = 0, k_frame = 0;
    double t = 0, value[WHIRL_NCOLUMNS];
    memset(res, 0, sizeof *res);
    int status = GSL_SUCCESS;
    for (;;) {
        const double t_row = output_time(k_row, last_row, s->every, s->t_end);
        const double t_frame =
            trace ? output_time(k_frame, last_frame, s->trace_every, s->t_end) : HUGE_VAL;
        if (t == t_row) { /* outputs due at t */
            if ((status = row_values(w, t, value))) break;
            if (out->row && (status = out->row(out->ctx, value))) break;
            res->rows++;
        }
        if (t == t_frame) {
            if ((status = frame_out(w, t, out))) break;
            res->frames++;
        }
        k_row += t == t_row;
        k_frame += t == t_frame;
        if (t >= s->t_end) break;
        if (whirl_stop_requested()) {
            char num[WHIRL_FORMAT_MAX];
            status = whirl_fail(WHIRL_EINTERRUPTED, "interrupted at t = %s",
                                whirl_format_double(num, t));
            break;
        }
        /* to the next output, one step at a time with fixed steps (for the checks below), in
         * one call when adaptive */
        const double target = GSL_MIN(output_time(k_row, last_row, s->every, s->t_end),
                                      trace ? output_time(k_frame, last_frame, s->trace_every,
                                                          s->t_end) : HUGE_VAL);
        const double t1 = s->tol > 0 || t + s->dt * (1 + 1e-9) >= target ? target : t + s->dt;
        status = whirl_integrator_advance(w->integrator, &t, w->y, t1, s->dt, s->tol);
        if (status == WHIRL_EINTERRUPTED) continue; /* reported at the top of the loop */
        if (status != GSL_SUCCESS) {
            char copy[512], stiff[256] = "";
            snprintf(copy, sizeof copy, "%s", whirl_error_marked());
            double rate;
            if (whirl_scene_stiff(s, &rate)) {
                stiff[0] = ';', stiff[1] = ' ';
                stiff_words(s, rate, stiff + 2, sizeof stiff - 2);
            }
            status = whirl_fail(status, "the run failed after t = %.17g (step %lu): %s%s", t,
                                whirl_integrator_get_stats(w->integrator).steps + 1, copy, stiff);
            break;
        }
        if (s->stop_deviation > 0) {
            status = whirl_dyn_get_state(w->dyn, t, w->y, WHIRL_FRAME_INERTIAL, w->x, w->v);
            if (status) break;
            const double dev = whirl_deviation(w->n, w->x, w->ref);
            if (dev > s->stop_deviation) { /* the row at the stop */
                res->stopped = 1;
                res->deviation = dev;
                if ((status = row_values(w, t, value))) break;
                if (out->row && (status = out->row(out->ctx, value))) break;
                res->rows++;
                break;
            }
        }
        if (out->progress && (status = out->progress(out->ctx, t))) break;
    }
    res->t = t;
    res->stats = whirl_integrator_get_stats(w->integrator);
    return status;
}

/* ---- CSV (numbers by whirl_format_double: the shortest that reads back exactly) ---- */

#define NUM(x) whirl_format_double((char[WHIRL_FORMAT_MAX]){0}, (x))

static const char *frame_name(whirl_frame f)
{
    return f == WHIRL_FRAME_ROTATING ? "rotating" : "inertial";
}

int whirl_scene_write_header(FILE *fp, const whirl_scene *s)
{
    return whirl_scene_write_header_with_pivot(fp, s, NULL);
}

int whirl_scene_write_header_with_pivot(FILE *fp, const whirl_scene *s,
                                        const whirl_scene_pivot *pivot)
{
    if (fp == NULL || s == NULL) return whirl_fail(GSL_EINVAL, "no file or no scene");
    fprintf(fp, "# whirl simulate %s\n", s->path);
    fprintf(fp, "# N = %zu, dim = %d, frame = %s, omega = %s, method = %s, formulation = %s, "
                "dt = %s, tol = %s, t_end = %s\n",
            s->links, s->dim, frame_name(s->frame), NUM(s->omega), s->method,
            s->formulation == WHIRL_FORMULATION_SEED ? "seed" : "default", NUM(s->dt),
            NUM(s->tol), NUM(s->t_end));
    switch (s->start) {
    case WHIRL_START_STEADY:
        fprintf(fp, "# start: steady mode %d at omega %s, perturb %s (seed %lu)\n", s->mode,
                NUM(s->start_omega), NUM(s->perturb), s->seed);
        break;
    case WHIRL_START_ANGLES: fprintf(fp, "# start: theta, phi and their rates\n"); break;
    case WHIRL_START_HANGING:
        if (s->perturb > 0)
            fprintf(fp, "# start: hanging, perturb %s (seed %lu)\n", NUM(s->perturb), s->seed);
        else
            fprintf(fp, "# start: hanging\n");
        break;
    }
    if (sc_write_pivot_line(fp, pivot) != GSL_SUCCESS) return GSL_EFAILED;
    whirl_write_units_line(fp, s->physical, s->chain_length, s->chain_mass, s->gravity);
    for (size_t c = 0; c < s->n_columns; c++)
        fprintf(fp, "%s%s", c ? "," : "", whirl_column_name(s->columns[c]));
    fputc('\n', fp);
    return ferror(fp) ? whirl_fail(GSL_EFAILED, "cannot write the header") : GSL_SUCCESS;
}

int whirl_scene_write_row(FILE *fp, const whirl_scene *s, const double *value)
{
    for (size_t c = 0; c < s->n_columns; c++)
        fprintf(fp, "%s%s", c ? "," : "", NUM(value[s->columns[c]]));
    fputc('\n', fp);
    return ferror(fp) ? whirl_fail(GSL_EFAILED, "cannot write a row") : GSL_SUCCESS;
}

int whirl_scene_write_frame(FILE *fp, unsigned long index, double t, const double *pivot,
                            const double *x, size_t n)
{
    fprintf(fp, "%s# t = %s\n%s %s %s %s\n", index ? "\n\n" : "", NUM(t), NUM(pivot[0]),
            NUM(pivot[1]), NUM(pivot[2]), NUM(t));
    for (size_t i = 0; i < n; i++)
        fprintf(fp, "%s %s %s %s\n", NUM(x[3 * i]), NUM(x[3 * i + 1]), NUM(x[3 * i + 2]), NUM(t));
    return ferror(fp) ? whirl_fail(GSL_EFAILED, "cannot write a frame") : GSL_SUCCESS;
}

/* ---- the whole run to streams ---- */

typedef struct stream_ctx {
    const whirl_scene *scene;
    FILE *csv, *trace;
    unsigned long frames;
} stream_ctx;

static int stream_row(void *ctx, const double *value)
{
    const stream_ctx *c = ctx;
    return whirl_scene_write_row(c->csv, c->scene, value);
}

static int stream_frame(void *ctx, double t, const double *pivot, const double *x, size_t n)
{
    stream_ctx *c = ctx;
    return whirl_scene_write_frame(c->trace, c->frames++, t, pivot, x, n);
}

int whirl_scene_run(const whirl_scene *s, FILE *csv, FILE *trace, whirl_scene_result *res)
{
    return whirl_scene_run_with_pivot(s, NULL, csv, trace, res);
}

int whirl_scene_run_with_pivot(const whirl_scene *s, const whirl_scene_pivot *pivot, FILE *csv,
                               FILE *trace, whirl_scene_result *res)
{
    if (s == NULL || csv == NULL || res == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_scene_run: needs a scene, a CSV stream and res");
    whirl_scene_work *w;
    int status = work_alloc(s, pivot, &w);
    if (status) return status;
    stream_ctx c = {s, csv, trace, 0};
    const whirl_scene_output out = {.row = stream_row, .frame = trace ? stream_frame : NULL,
                                    .ctx = &c};
    status = whirl_scene_write_header_with_pivot(csv, s, pivot);
    if (status == GSL_SUCCESS) status = whirl_scene_work_run(w, &out, res);
    whirl_scene_work_free(w);
    return status;
}
