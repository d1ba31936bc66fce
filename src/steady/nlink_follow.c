/* The drivers of the N-link continuation (src/steady/nlink_path.c): a branch followed from its
 * birth over a set of rates (whirl_nlink_follow, whirl_nlink_branch, whirl_nlink_solve and
 * their _nodes and _opt variants), with the progress reports and the bound on the steps. */
#include <limits.h>
#include <math.h>

#include "core/error.h"
#include "steady/nlink_path_internal.h"

#define STEPS_MIN 100000   /* accepted steps of one path: at least, */
#define STEPS_PER_LINK 200 /* and per link of the chain (a middle mode folds about once per 25
                            * steps, and the number of its folds below a given multiple of its
                            * birth grows with N) */
#define PROGRESS_STEPS 256 /* steps between two reports of the progress */
#define STEPS_CAP 1e15     /* the bound's largest value (a long on every platform) */

/* The bound on the accepted steps of a path on the chain c. */
static long steps_max(const whirl_chain *c)
{
    const double per_link = (double)STEPS_PER_LINK * (double)c->n;
    return per_link > STEPS_MIN ? (per_link < STEPS_CAP ? (long)per_link : (long)STEPS_CAP)
                                : STEPS_MIN;
}

whirl_nlink_follow_options whirl_nlink_follow_defaults(const whirl_chain *c)
{
    whirl_nlink_follow_options o = {c != NULL ? steps_max(c) : STEPS_MIN, NULL, NULL};
    return o;
}

/* The shape of the branch at omega between its birth and the first point of a path begun in the
 * link angles (birth_gap), into info and, where r is not NULL, r, z, tension. */
static int gap_shape(nlink_path *p, double omega, whirl_shape_info *info, double *r,
                     double *z, double *tension)
{
    const size_t n = p->pub.chain->n;
    double *th = arr_cross_theta(p);
    if (path_birth_gap(p, omega, th)) return GSL_EFAILED;
    if (r == NULL) r = scr_nodes(p), z = r + n + 1, tension = z + n + 1;
    return path_shape_info(p, 1, omega, tip_of(p->pub.chain, omega, th), th, info, r, z, tension);
}

/* Follows the path until its rate first exceeds omega_max, it returns to the hanging chain, or
 * visit returns non-zero (WHIRL_VISIT_STOP: success). visit gets every crossing of the rates
 * omega[0..n-1] (j its index, info filled) and every event (j = SIZE_MAX, event set); the link
 * angles of the shape visited are in arr_cross_theta(p) (a crossing) or arr_event_theta(p) (an
 * event). */
static int follow_path(nlink_path *p, double omega_max, size_t n, const double *omega,
                       whirl_nlink_visit_fn visit, void *ctx,
                       const whirl_nlink_follow_options *opt)
{
    const size_t links = p->pub.chain->n;
    double *r = scr_nodes(p), *z = r + links + 1, *t = z + links + 1;
    long folds = 0;
    if (opt && opt->steps_max < 0)
        return whirl_fail(GSL_EINVAL, "the bound on the continuation steps must be > 0 (0: the "
                          "default), got %ld", opt->steps_max);
    const long bound = opt && opt->steps_max > 0 ? opt->steps_max : steps_max(p->pub.chain);
    int first = p->pub.steps == 0; /* the first step from the birth is still to come */
    while (p->pub.omega <= omega_max && !p->pub.ended) {
        if (p->pub.steps >= bound)
            return whirl_fail(GSL_EMAXITER, "mode %d: %ld continuation steps from the birth at "
                              "omega=" WHIRL_Q_RATE "%.17g (arclength %.4g, %ld folds) reached "
                              "omega=" WHIRL_Q_RATE "%.17g at most (now at omega=" WHIRL_Q_RATE
                              "%.17g)", p->pub.mode, bound, p->pub.omega_birth, p->pub.arclength,
                              folds, p->pub.omega_hi, p->pub.omega);
        if (opt && opt->progress && p->pub.steps % PROGRESS_STEPS == 0) {
            const whirl_nlink_progress at = {p->pub.mode, p->pub.omega_birth, p->pub.steps,
                                             bound, folds, p->pub.omega,
                                             p->pub.omega_hi, p->pub.arclength};
            opt->progress(opt->progress_ctx, &at);
        }
        int status = whirl_nlink_path_step(&p->pub);
        if (status) return status;
        for (int e = 0; e < p->pub.n_events; e++) folds += p->pub.event[e].kind == WHIRL_EVENT_FOLD;
        /* crossings and events in the order of arclength: events first where they come
         * first is not needed by the callers, so crossings of a step follow its events */
        for (int e = 0; e < p->pub.n_events; e++) {
            whirl_shape_info info;
            const whirl_branch_event *ev = &p->pub.event[e];
            if ((status = path_shape_info(p, p->s.last.angles, ev->omega, ev->tip_r,
                                          arr_event_theta(p) + (size_t)e * links, &info, r, z, t)))
                return path_name_mode(p, status);
            if ((status = visit(ctx, SIZE_MAX, &info, ev)))
                return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
        }
        for (size_t j = 0; j < n; j++) {
            double tip[WHIRL_PATH_EVENTS_MAX + 1];
            int found =
                whirl_nlink_path_crossings(&p->pub, omega[j], WHIRL_PATH_EVENTS_MAX + 1, tip);
            if (found < 0) return -found;
            if (found == 0 && first && omega[j] > p->pub.omega_birth * (1 + GAP_MIN) &&
                omega[j] < p->pub.omega) {
                /* a rate between the birth and the first point, which the step's crossings do
                 * not resolve (a path begun in the link angles): gap_shape, or left out as not
                 * resolved where that does not converge */
                whirl_shape_info info;
                if (gap_shape(p, omega[j], &info, r, z, t) != GSL_SUCCESS) continue;
                p->pub.cross_angles[0] = 1; /* the visit's link angles are in cross_theta */
                if ((status = visit(ctx, j, &info, NULL)))
                    return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
            }
            for (int k = 0; k < found; k++) {
                whirl_shape_info info;
                const double *th = arr_cross_theta(p) + (size_t)k * links;
                if ((status = path_shape_info(p, p->pub.cross_angles[k], omega[j], tip[k], th,
                                              &info, r, z, t)))
                    return path_name_mode(p, status);
                if (k > 0) {
                    for (size_t i = 0; i < links; i++) arr_cross_theta(p)[i] = th[i];
                    p->pub.cross_angles[0] = p->pub.cross_angles[k];
                }
                if ((status = visit(ctx, j, &info, NULL)))
                    return status == WHIRL_VISIT_STOP ? GSL_SUCCESS : status;
            }
        }
        first = 0;
    }
    return GSL_SUCCESS;
}

int whirl_nlink_follow(const whirl_chain *c, int mode, double omega_max, size_t n,
                       const double *omega, whirl_nlink_visit_fn visit, void *ctx)
{
    return whirl_nlink_follow_opt(c, mode, omega_max, n, omega, visit, ctx, NULL);
}

int whirl_nlink_follow_opt(const whirl_chain *c, int mode, double omega_max, size_t n,
                           const double *omega, whirl_nlink_visit_fn visit, void *ctx,
                           const whirl_nlink_follow_options *opt)
{
    nlink_path *p = path_alloc(c);
    if (p == NULL) return whirl_last_status();
    int status = whirl_nlink_path_birth(&p->pub, mode);
    if (!status) status = follow_path(p, omega_max, n, omega, visit, ctx, opt);
    path_free(p);
    return status;
}

/* The first crossing of each rate; with nodes, those of the first crossing of rate j in row j
 * (c->n + 1 each). */
typedef struct first_ctx {
    whirl_shape_info *info;
    int *exists;
    size_t n, left;
    nlink_path *p;
    double *r, *z, *tension; /* NULL: not wanted */
} first_ctx;

static int first_visit(void *ctx, size_t j, const whirl_shape_info *info,
                       const whirl_branch_event *event)
{
    first_ctx *f = ctx;
    if (event != NULL || f->exists[j]) return 0;
    f->exists[j] = 1;
    f->info[j] = *info;
    if (f->r) {
        /* the visited crossing's nodes, from its link angles (the first k of the step is
         * copied to the front of cross_theta) */
        nlink_path *p = f->p;
        const size_t n = p->pub.chain->n;
        double *r = f->r + j * (n + 1), *z = f->z + j * (n + 1), *t = f->tension + j * (n + 1);
        int status;
        if (p->pub.cross_angles[0]) {
            whirl_nlink_balance_nodes(p->pub.chain, info->omega, arr_cross_theta(p), r, z, t);
            if (r[n] < 0)
                for (size_t i = 0; i <= n; i++) r[i] = -r[i];
            status = whirl_steady_check_samples(info->omega, n + 1, r, z, t);
        } else {
            status = whirl_nlink_positions(p->pub.chain, info->omega, info->tip_r, r, z, t);
        }
        if (status) return status;
    }
    return --f->left == 0 ? WHIRL_VISIT_STOP : 0;
}

/* The branch of mode at the rates omega[]: a path from the birth up to the largest of them (and
 * at least to twice the birth rate, where a branch that first turns to lower rates is seen). */
static int branch_path(nlink_path *p, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists, double *r, double *z, double *t,
                       const whirl_nlink_follow_options *opt)
{
    for (size_t j = 0; j < n; j++) {
        int status = whirl_steady_check_args(omega[j], mode, INT_MAX);
        if (status != GSL_SUCCESS) return status;
        exists[j] = 0;
    }
    if ((size_t)mode > p->pub.chain->n)
        return whirl_fail(GSL_EDOM, "mode %d does not exist: a chain of %zu links has modes "
                          "1..%zu", mode, p->pub.chain->n, p->pub.chain->n);
    int status = whirl_nlink_path_birth(&p->pub, mode);
    if (status) return status;
    double top = 2 * p->pub.omega_birth;
    for (size_t j = 0; j < n; j++) top = fmax(top, omega[j]);
    first_ctx f = {info, exists, n, n, p, r, z, t};
    if (n == 0) return GSL_SUCCESS;
    status = follow_path(p, top, n, omega, first_visit, &f, opt);
    if (status == GSL_EFAILED || status == GSL_EMAXITER) {
        /* a failure above every rate still missing, while looking for a turn of a branch
         * back below its birth: those rates are below the branch as far as it was followed */
        int below = 1;
        for (size_t j = 0; j < n; j++)
            if (!exists[j] && omega[j] >= p->pub.omega_lo) below = 0;
        if (below) status = GSL_SUCCESS;
    }
    return status;
}

int whirl_nlink_branch_nodes(const whirl_chain *c, int mode, size_t n, const double *omega,
                             whirl_shape_info *info, int *exists, double *r, double *z,
                             double *tension)
{
    if ((r == NULL) != (z == NULL) || (r == NULL) != (tension == NULL))
        return whirl_fail(GSL_EINVAL, "the nodes need all of r, z and tension, or none");
    nlink_path *p = path_alloc(c);
    if (p == NULL) return whirl_last_status();
    int status = branch_path(p, mode, n, omega, info, exists, r, z, tension, NULL);
    path_free(p);
    return status;
}

int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists)
{
    return whirl_nlink_branch_nodes(c, mode, n, omega, info, exists, NULL, NULL, NULL);
}

int whirl_nlink_solve_nodes(const whirl_chain *c, double omega, int mode,
                            whirl_shape_info *info, double *r, double *z, double *tension)
{
    return whirl_nlink_solve_nodes_opt(c, omega, mode, info, r, z, tension, NULL);
}

int whirl_nlink_solve_nodes_opt(const whirl_chain *c, double omega, int mode,
                                whirl_shape_info *info, double *r, double *z, double *tension,
                                const whirl_nlink_follow_options *opt)
{
    nlink_path *p = path_alloc(c);
    if (p == NULL) return whirl_last_status();
    int exists = 0;
    int status = branch_path(p, mode, 1, &omega, info, &exists, r, z, tension, opt);
    if (status == GSL_SUCCESS && !exists) {
        if (p->pub.ended)
            status = whirl_fail(GSL_EDOM, "mode %d does not exist at omega=" WHIRL_Q_RATE "%.17g: "
                                "its branch, born at omega_%d=" WHIRL_Q_RATE "%.17g, returns to "
                                "the hanging chain at omega=" WHIRL_Q_RATE "%.17g without reaching "
                                "it", mode, omega, mode, p->pub.omega_birth, p->pub.omega);
        else if (p->pub.omega_lo >= p->pub.omega_birth &&
                 omega > p->pub.omega_birth * (1 + GAP_MIN))
            /* above the birth but below the first point of a branch begun in the link angles
             * (birth_angles), where birth_gap does not converge: the mode exists there, it is
             * not resolved */
            status = whirl_fail(GSL_EFAILED, "mode %d at omega=" WHIRL_Q_RATE "%.17g is not "
                                "resolved: it lies between the birth omega_%d=" WHIRL_Q_RATE
                                "%.17g and the first point of the branch, at omega=" WHIRL_Q_RATE
                                "%.17g, where the tip shot cannot start it (begun in the link "
                                "angles at an amplitude of %g rad)", mode, omega, mode,
                                p->pub.omega_birth, p->pub.omega_lo, BIRTH_AMPLITUDE);
        else if (p->pub.omega_lo >= p->pub.omega_birth)
            status = whirl_steady_fail_missing(mode, omega, p->pub.omega_birth);
        else
            status = whirl_fail(GSL_EDOM, "mode %d does not exist at omega=" WHIRL_Q_RATE "%.17g: "
                                "its branch, born at omega_%d=" WHIRL_Q_RATE "%.17g, reaches down "
                                "to omega=" WHIRL_Q_RATE "%.17g only", mode, omega, mode,
                                p->pub.omega_birth, p->pub.omega_lo);
    }
    path_free(p);
    return status;
}

int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, whirl_shape_info *info)
{
    return whirl_nlink_solve_nodes(c, omega, mode, info, NULL, NULL, NULL);
}
