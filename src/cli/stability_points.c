/* whirl stability: the points of the single rate (--omega) or of the map, with their free
 * shapes' nodes, and the analysis of one point: the linearisation, the perturbed run
 * (whirl_stability_run_shape) and its trace (stability_cli.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli/stability_cli.h"
#include "core/error.h"

/* The hand-swung chain: any of its options given. */
static int driven(const stability_options *o) { return hand_cli_given(&o->hand); }

/* The size of one dimensionless unit of the kind in the user's units. */
static double unit(const stability_options *o, cli_unit kind)
{
    return cli_units_scale(&o->units, kind);
}

/* The work arrays of make_points: the map's rates, the shapes' summaries and existence, the
 * tensions of the solves. */
typedef struct point_work {
    double *omega;
    whirl_shape_info *info;
    int *exists;
    double *tension;
} point_work;

static void point_work_free(point_work *w)
{
    free(w->omega);
    free(w->info);
    free(w->exists);
    free(w->tension);
}

/* The single point at --omega, with its free shape's nodes (r then z, N + 1 each) unless the
 * chain is the hand-swung one. 0, or 1 after an error. */
static int single_point(const cli_command *cmd, const stability_options *o, const whirl_chain *c,
                        stability_point *p, double *nodes, double *tension)
{
    p->omega = o->omega;
    p->mode = o->mode;
    if (driven(o)) return 0;
    /* the nodes from the branch's link angles: at high rates the tip radius alone does not fix
     * the shape to round-off */
    const size_t links = c->n + 1;
    whirl_shape_info one;
    if (whirl_nlink_solve_nodes(c, o->omega, o->mode, &one, nodes, nodes + links, tension) !=
        GSL_SUCCESS)
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    p->tip_r = one.tip_r;
    p->r = nodes;
    p->z = nodes + links;
    return 0;
}

/* The map's points, mode by mode, in *n: for the free shapes the rates where the mode exists,
 * with their nodes (mode k's r and z from nodes + 2 k steps (N + 1)); for the hand-swung chain
 * every rate (its shapes are found in stability_cli_analyse()). 0, or 1 after an error. */
static int map_points(const cli_command *cmd, const stability_options *o, const whirl_chain *c,
                      stability_point *p, size_t *n, double *nodes, point_work *w)
{
    const size_t links = c->n + 1, steps = (size_t)o->steps;
    for (size_t j = 0; j < steps; j++)
        w->omega[j] = cli_grid(o->omega_min, o->omega_max, o->steps, (int)j);
    *n = 0;
    for (int k = 0; k < o->modes.n; k++) {
        const int mode = o->modes.v[k];
        double *r = nodes ? nodes + 2 * (size_t)k * steps * links : NULL;
        double *z = r ? r + steps * links : NULL;
        if (!driven(o) && whirl_nlink_branch_nodes(c, mode, steps, w->omega, w->info, w->exists,
                                                   r, z, w->tension) != GSL_SUCCESS)
            return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units)); /* it names the mode */
        for (size_t j = 0; j < steps; j++) {
            if (driven(o)) {
                p[*n] = (stability_point){.omega = w->omega[j], .mode = mode};
                ++*n;
            } else if (w->exists[j]) {
                p[*n] = (stability_point){.omega = w->omega[j], .mode = mode,
                                          .tip_r = w->info[j].tip_r, .r = r + j * links,
                                          .z = z + j * links};
                ++*n;
            }
        }
    }
    return 0;
}

/* The points of the single form or of the map (rates where the mode exists); *count of them,
 * their free shapes' nodes in *nodes (NULL for the hand-swung chain; the caller frees both).
 * Returns NULL after printing an error. */
stability_point *stability_cli_points(const cli_command *cmd, const stability_options *o,
                                      const whirl_chain *c, size_t *count, double **nodes)
{
    const size_t links = c->n + 1;
    const size_t steps = o->omega_given ? 1 : (size_t)o->steps;
    const size_t nmodes = o->omega_given ? 1 : (size_t)o->modes.n;
    point_work w = {malloc(steps * sizeof *w.omega), malloc(steps * sizeof *w.info),
                    malloc(steps * sizeof *w.exists),
                    driven(o) ? NULL : malloc(steps * links * sizeof *w.tension)};
    *nodes = driven(o) ? NULL : malloc(2 * nmodes * steps * links * sizeof **nodes);
    stability_point *p = calloc(steps * nmodes, sizeof *p);
    int rc = 0;
    if (!w.omega || !w.info || !w.exists || !p || (!driven(o) && (!w.tension || !*nodes)))
        rc = cli_error(cmd, "out of memory");
    else if (o->omega_given)
        rc = single_point(cmd, o, c, p, *nodes, w.tension);
    else
        rc = map_points(cmd, o, c, p, count, *nodes, &w);
    if (rc == 0 && o->omega_given) *count = 1;
    point_work_free(&w);
    if (rc == 0) return p;
    free(*nodes);
    *nodes = NULL;
    free(p);
    return NULL;
}

typedef struct trace_sink {
    FILE *fp;
    double time; /* the user's time unit in dimensionless ones */
} trace_sink;

/* Each sample of a run: a row of the trace (if any); stops the run on Ctrl-C. */
static int observe(double t, double ratio, void *data)
{
    const trace_sink *trace = data;
    if (trace->fp != NULL) fprintf(trace->fp, "%s,%s\n", CLI_NUM(t * trace->time), CLI_NUM(ratio));
    return cli_interrupted ? GSL_EFAILED : GSL_SUCCESS;
}

/* The perturbed run of the point p of model m from the shape linearised in w (its nodes);
 * trace: where the samples go (NULL: nowhere). */
static int perturbed_run(const stability_options *o, const whirl_model *m, whirl_stability *w,
                         stability_point *p, FILE *trace)
{
    whirl_stability_run_params rp = whirl_stability_run_defaults();
    rp.periods = o->periods;
    rp.perturbation = o->perturb;
    rp.seed = (unsigned long)o->seed;
    rp.method = o->method;
    rp.dt = o->dt;
    rp.observe = observe;
    trace_sink sink = {trace, unit(o, CLI_UNIT_TIME)};
    rp.observe_data = &sink;
    whirl_stability_run_result res;
    if (trace != NULL)
        fprintf(trace, "# omega %s, mode %d, links %d, damping %s, eps %s, drag "
                       "%s, drag_quadratic %s, eig_growth %s\nt,deviation\n",
                CLI_NUM(p->omega * unit(o, CLI_UNIT_RATE)), p->mode, o->links,
                CLI_NUM(o->damping * unit(o, CLI_UNIT_DAMPING)),
                CLI_NUM(m->drive_radius * unit(o, CLI_UNIT_LENGTH)),
                CLI_NUM(m->air_drag * unit(o, CLI_UNIT_DRAG)),
                CLI_NUM(m->air_drag_quadratic * unit(o, CLI_UNIT_DRAG2)),
                CLI_NUM(p->eig_growth * unit(o, CLI_UNIT_RATE)));
    const double *x, *y, *z;
    whirl_stability_nodes(w, &x, &y, &z);
    const int status = whirl_stability_run_shape(m, x, y, z, &rp, &res);
    /* a given step that the integration could not take (an implicit stage iteration that
     * diverges or does not converge): the failure names it (the run's steps are at most --dt
     * and the spacing of its 50 samples per period, stability.h: the integrator names the step
     * it took) */
    if (status == GSL_EMAXITER && o->dt > 0)
        return whirl_fail(status, "the run with --dt %g failed (steps of at most --dt and of "
                          "the spacing of the 50 samples per period): %s; give a smaller --dt, "
                          "or none (the default step)", o->dt * unit(o, CLI_UNIT_TIME),
                          whirl_error_marked());
    if (status) return status;
    if (trace != NULL)
        fprintf(trace, "# sim_growth %s fitted from t = %s to %s, verdict %s\n",
                CLI_NUM(res.sim_growth * unit(o, CLI_UNIT_RATE)),
                CLI_NUM(res.fit_from * unit(o, CLI_UNIT_TIME)),
                CLI_NUM(res.fit_to * unit(o, CLI_UNIT_TIME)), whirl_verdict_name(res.verdict));
    p->sim_growth = res.sim_growth;
    p->max_deviation = res.max_deviation;
    p->verdict = whirl_verdict_refine(res.verdict, p->index);
    /* A run whose deviation grows far faster than the fastest growth of the linearisation in its
     * linear stretch was not integrated: a step beyond the method's stability interval makes
     * every step multiply the error by |R(h lambda)| > 1, a growth ~ 1/h, whatever the chain
     * does. The default step stays inside the interval (whirl_default_step); a given one may
     * not. */
    if (o->dt > 0 && res.verdict == WHIRL_VERDICT_UNSTABLE &&
        res.sim_growth > 2 * fmax(p->eig_growth, 0) + 0.1 * p->omega)
        return whirl_fail(GSL_EFAILED, "the run with --dt %g grew at %g while the linearisation "
                          "gives %g at omega %g: the step is beyond the stability interval of "
                          "%s (an integration failure, not the chain); give a smaller --dt, or "
                          "none (the default step)", o->dt * unit(o, CLI_UNIT_TIME),
                          res.sim_growth * unit(o, CLI_UNIT_RATE),
                          p->eig_growth * unit(o, CLI_UNIT_RATE),
                          p->omega * unit(o, CLI_UNIT_RATE), o->method);
    return GSL_SUCCESS;
}

/* The perturbed run of one point (unless --linear), and for the hand-swung chain its linear
 * analysis (that of the free shapes is whirl_stability_map's, before); trace: where the samples
 * of the run go (NULL: nowhere). A driven map point whose shape does not exist is marked absent. */
int stability_cli_analyse(const stability_options *o, const whirl_chain *c, whirl_stability *w,
                          stability_point *p, FILE *trace)
{
    whirl_model m = {0};
    m.chain = c;
    m.dim = 3;
    m.frame = WHIRL_FRAME_ROTATING;
    m.omega = p->omega;
    m.internal_damping = o->damping;
    int status;
    if (driven(o)) {
        m.drive_radius = o->hand.eps;
        m.air_drag = o->hand.drag;
        m.air_drag_quadratic = o->hand.drag2;
        whirl_driven_info info;
        status = whirl_stability_driven_mode(w, &m, p->mode, o->hand.side, &info, &p->eig_growth);
        if (status == GSL_EDOM && !o->omega_given) {
            p->absent = 1;
            return GSL_SUCCESS;
        }
        p->tip[0] = info.tip[0];
        p->tip[1] = info.tip[1];
        p->tip_r = info.tip_r;
        p->nodes = info.nodes;
    } else {
        /* eig_growth from the map; the run needs the linearisation's nodes (same shape) */
        status = whirl_stability_linearise(w, &m, p->r, p->z);
    }
    if (!status) status = whirl_stability_index(w, &p->index);
    if (status) return status;
    if (o->linear) {
        p->verdict = whirl_verdict_linear(p->eig_growth, p->index);
        return GSL_SUCCESS;
    }
    return perturbed_run(o, &m, w, p, trace);
}
