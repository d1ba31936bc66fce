/* whirl simulate SCENE [-o FILE] [--set section.key=value ...]: runs the scene (whirl/scene.h)
 * and writes the asked columns as CSV, and optionally the trace of every mass.
 *
 * The start state, in the run's frame at t = 0, with the pivot at p0 = (drive_radius, 0, 0)
 * moving at p0' (inertial 3D: (0, drive_radius omega, 0); else 0), and x_i relative to it:
 *  - steady: the N-link relative equilibrium of mode k at omega_s in the x-z plane
 *    (whirl_nlink_solve, whirl_nlink_positions), each link vector d turned by perturb about a
 *    random axis perpendicular to it, d' = |d| (cos p d^ + sin p b^), b^ uniform on the circle
 *    perpendicular to d^; velocity p0' + (omega_s - Omega) z x x_i, Omega = omega in the rotating
 *    frame and 0 in the inertial one (the rigid rotation at omega_s);
 *  - angles: link unit vectors u_i = (sin th cos ph, sin th sin ph, -cos th) (2D: (sin th, 0,
 *    -cos th)), x_i = sum_{k<=i} l_k u_k, velocities p0' + sum l_k du_k/dt;
 *  - hanging: u_i = -z, velocity p0', its link vectors turned by perturb as for the steady start.
 * Output rows at t = k every and at t_end; positions in the inertial frame; energy, jacobi, lz
 * and constraint from whirl_dyn_diagnose; deviation = whirl_deviation from the unperturbed
 * steady (or hanging) shape, or from the mode-K shape at omega with [output] reference_mode. Fixed steps are taken one call at a time, so that the stop
 * condition is checked after every step; Ctrl-C stops the integrator inside a step.
 * Exit status: 0 (also when the stop condition ends the run, with a note on stderr); 1 on bad
 * input (nothing written) or a failed run (the rows so far kept); 130 after Ctrl-C (rows kept). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>

#include "cli/cli.h"
#include "whirl/chain.h"
#include "whirl/dynamics.h"
#include "whirl/scene.h"
#include "whirl/steady.h"

/* Everything one run needs, allocated before the time loop. */
typedef struct run {
    const cli_command *cmd;
    whirl_scene scene;
    whirl_chain *chain;
    whirl_model model;
    whirl_dyn *dyn;
    whirl_integrator *integrator;
    size_t n;         /* links */
    double *y;        /* state */
    double *x, *v;    /* 3 per mass: positions and velocities */
    double *ref;      /* 3 per mass: the reference shape of the deviation, or NULL */
    cli_out csv, trace;
    int csv_open, trace_open;
    unsigned long rows, frames; /* written so far */
    int progress;               /* the progress line is showing */
} run;

/* "WHERE: message" for a key of the scene, as the one-line error of the command. */
static int key_error(const run *r, whirl_scene_key key, const char *message)
{
    char where[512];
    return cli_error(r->cmd, "%s: %s", whirl_scene_where(&r->scene, key, where, sizeof where),
                     message);
}

/* Pivot at t = 0 and its velocity in the run's frame (see whirl_model.drive_radius). */
static void pivot_start(const whirl_model *m, double *p0, double *pv0)
{
    p0[0] = m->drive_radius;
    p0[1] = p0[2] = 0;
    pv0[0] = pv0[1] = pv0[2] = 0;
    if (m->frame == WHIRL_FRAME_INERTIAL && m->dim == 3) pv0[1] = m->drive_radius * m->omega;
}

/* x_i = sum of the link vectors d_1..d_i (3 per link), in place. */
static void accumulate(size_t n, double *d)
{
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) d[3 * i + k] += d[3 * (i - 1) + k];
}

/* Turns the vector d by angle p about an axis perpendicular to it chosen uniformly at random. */
static void turn_randomly(double *d, double p, gsl_rng *rng)
{
    const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double u[3] = {d[0] / len, d[1] / len, d[2] / len};
    /* e1: u x (the coordinate axis least aligned with u), normalised; e2 = u x e1 */
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(u[k]) < fabs(u[axis])) axis = k;
    double a[3] = {0, 0, 0}, e1[3], e2[3];
    a[axis] = 1;
    e1[0] = u[1] * a[2] - u[2] * a[1];
    e1[1] = u[2] * a[0] - u[0] * a[2];
    e1[2] = u[0] * a[1] - u[1] * a[0];
    const double n1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; k++) e1[k] /= n1;
    e2[0] = u[1] * e1[2] - u[2] * e1[1];
    e2[1] = u[2] * e1[0] - u[0] * e1[2];
    e2[2] = u[0] * e1[1] - u[1] * e1[0];
    const double psi = 2 * M_PI * gsl_rng_uniform(rng), c = cos(p), s = sin(p);
    for (int k = 0; k < 3; k++)
        d[k] = len * (c * u[k] + s * (cos(psi) * e1[k] + sin(psi) * e2[k]));
}

/* The link vectors d (3 per link) of the N-link steady shape of mode k at omega, in the x-z
 * plane; key names the scene key to blame if there is none. 0, or 1 after an error. */
static int mode_links(run *r, double omega, int mode, whirl_scene_key key, double *d)
{
    const size_t n = r->n;
    whirl_shape_info info;
    char msg[600];
    if (whirl_nlink_solve(r->chain, omega, mode, 0, &info) != GSL_SUCCESS) {
        snprintf(msg, sizeof msg, "no steady shape: %s", whirl_last_error());
        return key_error(r, key, msg);
    }
    double *rr = malloc(3 * (n + 1) * sizeof *rr), *zz = rr + n + 1, *tension = zz + n + 1;
    int status = rr ? whirl_nlink_positions(r->chain, omega, info.tip_r, rr, zz, tension)
                    : GSL_ENOMEM;
    if (status == GSL_SUCCESS)
        for (size_t i = 0; i < n; i++) {
            d[3 * i] = rr[i + 1] - rr[i];
            d[3 * i + 1] = 0;
            d[3 * i + 2] = zz[i + 1] - zz[i];
        }
    free(rr);
    if (status != GSL_SUCCESS) {
        snprintf(msg, sizeof msg, "steady shape: %s",
                 status == GSL_ENOMEM ? "out of memory" : whirl_last_error());
        return key_error(r, key, msg);
    }
    return 0;
}

/* Turns every link vector d_i of x by [start] perturb at random (seeded). 0, or 1 (error). */
static int perturb_links(run *r)
{
    const whirl_scene *s = &r->scene;
    if (!(s->perturb > 0)) return 0;
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (rng == NULL) return cli_error(r->cmd, "out of memory");
    gsl_rng_set(rng, s->seed);
    for (size_t i = 0; i < r->n; i++) turn_randomly(r->x + 3 * i, s->perturb, rng);
    gsl_rng_free(rng);
    return 0;
}

/* The seed's angles: x and v relative to the pivot. */
static void angle_start(run *r)
{
    const whirl_scene *s = &r->scene;
    for (size_t i = 0; i < r->n; i++) {
        const double th = s->theta[i], ph = s->phi[i], thd = s->theta_dot[i];
        const double phd = s->phi_dot[i], l = s->length[i];
        const double st = sin(th), ct = cos(th), sp = sin(ph), cp = cos(ph);
        double *x = r->x + 3 * i, *v = r->v + 3 * i;
        x[0] = l * st * cp;
        x[1] = l * st * sp;
        x[2] = -l * ct;
        v[0] = l * (thd * ct * cp - phd * st * sp);
        v[1] = l * (thd * ct * sp + phd * st * cp);
        v[2] = l * thd * st;
    }
    accumulate(r->n, r->x);
    accumulate(r->n, r->v);
}

/* Fills r->y with the start state; r->ref with the reference shape if there is one. */
static int start_state(run *r)
{
    const whirl_scene *s = &r->scene;
    const size_t n = r->n;
    double p0[3], pv0[3], spin = 0;
    pivot_start(&r->model, p0, pv0);
    memset(r->v, 0, 3 * n * sizeof *r->v);
    if (s->start == WHIRL_START_ANGLES) {
        angle_start(r);
    } else { /* link vectors of the steady or the hanging shape, the reference, the turns */
        if (s->start == WHIRL_START_STEADY) {
            if (mode_links(r, s->start_omega, s->mode, WHIRL_KEY_START_MODE, r->x) != 0) return 1;
            spin = s->start_omega;
        } else {
            for (size_t i = 0; i < n; i++) {
                r->x[3 * i] = r->x[3 * i + 1] = 0;
                r->x[3 * i + 2] = -s->length[i];
            }
        }
        memcpy(r->ref, r->x, 3 * n * sizeof *r->x);
        accumulate(n, r->ref);
        if (perturb_links(r) != 0) return 1;
        accumulate(n, r->x);
    }
    if (s->reference_mode > 0) {
        if (mode_links(r, s->omega, s->reference_mode, WHIRL_KEY_OUTPUT_REFERENCE_MODE,
                       r->ref) != 0)
            return 1;
        accumulate(n, r->ref);
    }
    /* the rigid rotation at spin seen from the run's frame, plus the pivot's motion */
    const double w = spin - (r->model.frame == WHIRL_FRAME_ROTATING ? r->model.omega : 0);
    for (size_t i = 0; i < n; i++) {
        double *x = r->x + 3 * i, *v = r->v + 3 * i;
        v[0] += pv0[0] - w * x[1];
        v[1] += pv0[1] + w * x[0];
        v[2] += pv0[2];
        for (int k = 0; k < 3; k++) x[k] += p0[k];
        if (s->start != WHIRL_START_ANGLES || s->reference_mode > 0)
            for (int k = 0; k < 3; k++) r->ref[3 * i + k] += p0[k];
    }
    if (whirl_dyn_set_state(r->dyn, 0, r->x, r->v, r->y) != GSL_SUCCESS)
        return cli_error(r->cmd, "%s: [start]: %s", s->path, whirl_last_error());
    return 0;
}

/* Builds the chain, the model, the workspaces and the start state. */
static int setup(run *r)
{
    const whirl_scene *s = &r->scene;
    r->n = s->links;
    r->chain = whirl_chain_alloc(s->links, s->length, s->mass, s->gravity);
    if (r->chain == NULL) return cli_error(r->cmd, "%s: [chain]: %s", s->path, whirl_last_error());
    r->model = (whirl_model){
        .chain = r->chain,
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
    r->dyn = whirl_dyn_alloc(&r->model, s->formulation);
    if (r->dyn == NULL) return cli_error(r->cmd, "%s: [run]: %s", s->path, whirl_last_error());
    r->integrator = whirl_integrator_alloc(s->method, r->dyn);
    if (r->integrator == NULL) return key_error(r, WHIRL_KEY_RUN_METHOD, whirl_last_error());
    r->y = malloc(whirl_dyn_size(r->dyn) * sizeof *r->y);
    r->x = malloc(3 * r->n * sizeof *r->x);
    r->v = malloc(3 * r->n * sizeof *r->v);
    r->ref = malloc(3 * r->n * sizeof *r->ref);
    if (!r->y || !r->x || !r->v || !r->ref) return cli_error(r->cmd, "out of memory");
    if (start_state(r) != 0) return 1;
    /* an advance of zero length checks the step and the tolerance against the method */
    double t = 0;
    if (whirl_integrator_advance(r->integrator, &t, r->y, 0, s->dt, s->tol) != GSL_SUCCESS)
        return key_error(r, s->tol > 0 ? WHIRL_KEY_RUN_TOL : WHIRL_KEY_RUN_DT, whirl_last_error());
    return 0;
}

static void teardown(run *r)
{
    if (r->csv_open) cli_out_abort(&r->csv);
    if (r->trace_open) cli_out_abort(&r->trace);
    free(r->y);
    free(r->x);
    free(r->v);
    free(r->ref);
    whirl_integrator_free(r->integrator);
    whirl_dyn_free(r->dyn);
    whirl_chain_free(r->chain);
    whirl_scene_free(&r->scene);
}

static const char *frame_name(whirl_frame f) { return f == WHIRL_FRAME_ROTATING ? "rotating" : "inertial"; }

static void write_header(run *r)
{
    const whirl_scene *s = &r->scene;
    FILE *fp = r->csv.fp;
    fprintf(fp, "# whirl simulate %s\n", s->path);
    fprintf(fp, "# N = %zu, dim = %d, frame = %s, omega = %s, method = %s, formulation = %s, "
                "dt = %s, tol = %s, t_end = %s\n",
            s->links, s->dim, frame_name(s->frame), CLI_NUM(s->omega), s->method,
            s->formulation == WHIRL_FORMULATION_SEED ? "seed" : "default", CLI_NUM(s->dt), CLI_NUM(s->tol),
            CLI_NUM(s->t_end));
    switch (s->start) {
    case WHIRL_START_STEADY:
        fprintf(fp, "# start: steady mode %d at omega %s, perturb %s (seed %lu)\n", s->mode,
                CLI_NUM(s->start_omega), CLI_NUM(s->perturb), s->seed);
        break;
    case WHIRL_START_ANGLES: fprintf(fp, "# start: theta, phi and their rates\n"); break;
    case WHIRL_START_HANGING: fprintf(fp, "# start: hanging\n"); break;
    }
    for (size_t c = 0; c < s->n_columns; c++)
        fprintf(fp, "%s%s", c ? "," : "", whirl_column_name(s->columns[c]));
    fputc('\n', fp);
}

/* Positions of the masses in the inertial frame into r->x. */
static int inertial_positions(run *r, double t)
{
    return whirl_dyn_get_state(r->dyn, t, r->y, WHIRL_FRAME_INERTIAL, r->x, r->v);
}

static int write_row(run *r, double t)
{
    const whirl_scene *s = &r->scene;
    const int *want = s->want;
    double value[WHIRL_NCOLUMNS] = {0};
    value[WHIRL_COLUMN_T] = t;
    if (want[WHIRL_COLUMN_TIP_X] || want[WHIRL_COLUMN_TIP_Y] || want[WHIRL_COLUMN_TIP_Z] ||
        want[WHIRL_COLUMN_DEVIATION]) {
        if (inertial_positions(r, t) != GSL_SUCCESS) return GSL_EFAILED;
        const double *tip = r->x + 3 * (r->n - 1);
        value[WHIRL_COLUMN_TIP_X] = tip[0];
        value[WHIRL_COLUMN_TIP_Y] = tip[1];
        value[WHIRL_COLUMN_TIP_Z] = tip[2];
        if (want[WHIRL_COLUMN_DEVIATION])
            value[WHIRL_COLUMN_DEVIATION] = whirl_deviation(r->n, r->x, r->ref);
    }
    if (want[WHIRL_COLUMN_ENERGY] || want[WHIRL_COLUMN_JACOBI] || want[WHIRL_COLUMN_LZ] ||
        want[WHIRL_COLUMN_CONSTRAINT]) {
        whirl_dyn_diagnostics diag;
        if (whirl_dyn_diagnose(r->dyn, t, r->y, &diag) != GSL_SUCCESS) return GSL_EFAILED;
        value[WHIRL_COLUMN_ENERGY] = diag.energy;
        value[WHIRL_COLUMN_JACOBI] = diag.jacobi;
        value[WHIRL_COLUMN_LZ] = diag.lz;
        value[WHIRL_COLUMN_CONSTRAINT] = diag.constraint;
    }
    for (size_t c = 0; c < s->n_columns; c++)
        fprintf(r->csv.fp, "%s%s", c ? "," : "", CLI_NUM(value[s->columns[c]]));
    fputc('\n', r->csv.fp);
    r->rows++;
    return GSL_SUCCESS;
}

/* One block of the trace: the pivot, then every mass, in the inertial frame. */
static int write_frame(run *r, double t)
{
    if (inertial_positions(r, t) != GSL_SUCCESS) return GSL_EFAILED;
    const whirl_model *m = &r->model;
    const double eps = m->drive_radius, wt = m->omega * t;
    FILE *fp = r->trace.fp;
    if (r->frames == 0) {
        const cli_units dimensionless = CLI_UNITS_INIT;
        cli_trace_header(fp, &dimensionless, "whirl simulate", m->omega, eps, m->air_drag,
                         m->air_drag_quadratic, (int)r->n);
    }
    fprintf(fp, "%s# t = %s\n%s %s %s %s\n", r->frames ? "\n\n" : "", CLI_NUM(t),
            CLI_NUM(eps * cos(wt)), CLI_NUM(m->dim == 3 ? eps * sin(wt) : 0.0), CLI_NUM(0.0), CLI_NUM(t));
    for (size_t i = 0; i < r->n; i++)
        fprintf(fp, "%s %s %s %s\n", CLI_NUM(r->x[3 * i]), CLI_NUM(r->x[3 * i + 1]), CLI_NUM(r->x[3 * i + 2]),
                CLI_NUM(t));
    r->frames++;
    return GSL_SUCCESS;
}

/* The k-th output time of the interval every: k every, and t_end as the last (k = last). */
static size_t last_index(double every, double t_end)
{
    return (size_t)ceil(t_end / every * (1 - 1e-12));
}
static double output_time(size_t k, size_t last, double every, double t_end)
{
    return k >= last ? t_end : (double)k * every;
}

static int all_finite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Ends the progress line, if one is showing, before a message. */
static void end_progress(run *r, double fraction)
{
    if (r->progress) cli_progress(r->cmd, "t", fraction, 1);
    r->progress = 0;
}

/* A failure of the library at t: the one-line error, exit status 1. */
static int fail_at(run *r, double t)
{
    end_progress(r, t / r->scene.t_end);
    return cli_error(r->cmd, "%s: at t = %s: %s", r->scene.path, CLI_NUM(t), whirl_last_error());
}

/* The time loop. Returns the exit status: 0 (also after a stop condition), 1 after a failure,
 * 130 after an interrupt; the rows written so far are kept in every case. */
static int simulate(run *r)
{
    const whirl_scene *s = &r->scene;
    const size_t size = whirl_dyn_size(r->dyn);
    const size_t last_row = last_index(s->every, s->t_end);
    const size_t last_frame = last_index(s->trace_every, s->t_end);
    size_t k_row = 0, k_frame = 0;
    double t = 0, shown = wall_seconds();
    int trace = s->trace != NULL, failed = 0;
    cli_catch_interrupts();
    write_header(r);
    for (;;) {
        const double t_row = output_time(k_row, last_row, s->every, s->t_end);
        const double t_frame =
            trace ? output_time(k_frame, last_frame, s->trace_every, s->t_end) : HUGE_VAL;
        /* outputs due at t */
        if ((t == t_row && write_row(r, t) != GSL_SUCCESS) ||
            (t == t_frame && write_frame(r, t) != GSL_SUCCESS)) {
            failed = fail_at(r, t);
            break;
        }
        k_row += t == t_row;
        k_frame += t == t_frame;
        if (t >= s->t_end) break;
        if (cli_interrupted) {
            end_progress(r, t / s->t_end);
            cli_error(r->cmd, "interrupted at t = %s: %lu rows kept", CLI_NUM(t), r->rows);
            failed = CLI_EXIT_INTERRUPTED;
            break;
        }
        /* advance to the next output, one step at a time with fixed steps (for the checks
         * below), in one call when adaptive */
        const double target = GSL_MIN(output_time(k_row, last_row, s->every, s->t_end),
                                      trace ? output_time(k_frame, last_frame, s->trace_every,
                                                          s->t_end) : HUGE_VAL);
        const double t1 = s->tol > 0 || t + s->dt * (1 + 1e-9) >= target ? target : t + s->dt;
        const int status = whirl_integrator_advance(r->integrator, &t, r->y, t1, s->dt, s->tol);
        if (status == WHIRL_EINTERRUPTED) continue; /* reported above, at the last good state */
        if (status != GSL_SUCCESS || !all_finite(r->y, size)) {
            whirl_integrator_stats st = whirl_integrator_get_stats(r->integrator);
            end_progress(r, t / s->t_end);
            cli_error(r->cmd, "%s: the run failed after t = %s (step %lu): %s; %lu rows kept",
                      s->path, CLI_NUM(t), st.steps + 1,
                      status != GSL_SUCCESS ? whirl_last_error() : "the state is not finite",
                      r->rows);
            failed = 1;
            break;
        }
        if (s->stop_deviation > 0) {
            if (inertial_positions(r, t) != GSL_SUCCESS) {
                failed = fail_at(r, t);
                break;
            }
            const double dev = whirl_deviation(r->n, r->x, r->ref);
            if (dev > s->stop_deviation) {
                /* the row at the stop (rows at t are otherwise written on the next pass) */
                if (write_row(r, t) != GSL_SUCCESS) failed = fail_at(r, t);
                end_progress(r, t / s->t_end);
                fprintf(stderr, "whirl %s: stopped at t = %s: deviation %.6g > %.6g\n",
                        r->cmd->name, CLI_NUM(t), dev, s->stop_deviation);
                break;
            }
        }
        if (wall_seconds() - shown > 0.25) {
            cli_progress(r->cmd, "t", t / s->t_end, 0);
            r->progress = 1;
            shown = wall_seconds();
        }
    }
    end_progress(r, t / s->t_end);
    return failed;
}

int cmd_simulate(const cli_command *cmd, int argc, char **argv)
{
    const char *output = NULL, *set_help = NULL; /* --set is taken out before cli_parse */
    const cli_option opts[] = {
        {"--output", "-o", CLI_STRING, &output, NULL, "FILE", "write the CSV to FILE (default stdout)"},
        {"--set", NULL, CLI_STRING, &set_help, NULL, "SEC.KEY=V",
         "override a key of the scene (repeatable)"},
    };
    /* --set may repeat: take every one out before the common parser sees the rest */
    const char **sets = malloc((size_t)argc * sizeof *sets);
    char **rest = malloc(((size_t)argc + 1) * sizeof *rest);
    if (sets == NULL || rest == NULL) {
        free(sets);
        free(rest);
        return cli_error(cmd, "out of memory");
    }
    size_t n_sets = 0;
    int n_rest = 0;
    rest[n_rest++] = argv[0];
    int rc = 0;
    for (int i = 1; i < argc && rc == 0; i++) {
        if (strcmp(argv[i], "--set") == 0) {
            if (i + 1 == argc) rc = cli_error(cmd, "option --set needs a value (SEC.KEY=V)");
            else sets[n_sets++] = argv[++i];
        } else if (strncmp(argv[i], "--set=", 6) == 0)
            sets[n_sets++] = argv[i] + 6;
        else
            rest[n_rest++] = argv[i];
    }
    rest[n_rest] = NULL;
    const char *scene_path = NULL;
    if (rc == 0) rc = cli_parse(cmd, n_rest, rest, opts, 2, &scene_path, 1);
    if (rc == 0 && scene_path == NULL) rc = cli_error(cmd, "missing the scene file (see --help)");

    run r;
    memset(&r, 0, sizeof r);
    r.cmd = cmd;
    if (rc == 0 && whirl_scene_parse(scene_path, sets, n_sets, &r.scene) != GSL_SUCCESS)
        rc = cli_error(cmd, "%s", whirl_last_error());
    free(sets);
    free(rest);
    if (rc != 0) return rc;
    if (r.scene.trace && strcmp(r.scene.trace, "-") == 0)
        rc = key_error(&r, WHIRL_KEY_OUTPUT_TRACE, "must be a file, not standard output");
    if (rc == 0) rc = setup(&r);
    if (rc == 0) rc = cli_out_open(cmd, &r.csv, output);
    if (rc == 0) r.csv_open = 1;
    if (rc == 0 && r.scene.trace) {
        rc = cli_out_open(cmd, &r.trace, r.scene.trace);
        if (rc == 0) r.trace_open = 1;
    }
    if (rc == 0) {
        rc = simulate(&r);
        /* whatever the outcome, the rows written so far are kept */
        if (r.trace_open) {
            r.trace_open = 0;
            if (cli_out_commit(cmd, &r.trace) != 0 && rc == 0) rc = 1;
        }
        r.csv_open = 0;
        if (cli_out_commit(cmd, &r.csv) != 0 && rc == 0) rc = 1;
    }
    teardown(&r);
    return rc;
}
