/* The N-link equilibria search's continuation (method in equilibria.c, completeness method 3):
 * the curves through the roots followed to their births, folds and returns, each root labelled
 * with its branch, and the parity check of the crossings. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/error.h"
#include "steady/equilibria_internal.h"
#include "steady/steady_internal.h"

#define PATH_STEPS_MAX 3000 /* continuation steps of one direction of one curve */

/* ---- N-link chain: continuation of the curves through the roots ---- */

typedef struct curve {
    int branch;        /* birth reached (k), 0 none */
    double fold_lo;    /* lowest fold found */
    size_t *members;   /* entries crossed */
    size_t n_members, cap;
    int failed;        /* a direction ended in a failure */
} curve;

static int curve_member(curve *cv, size_t i)
{
    for (size_t j = 0; j < cv->n_members; j++)
        if (cv->members[j] == i) return GSL_SUCCESS;
    if (cv->n_members == cv->cap) {
        size_t cap = cv->cap ? 2 * cv->cap : 16;
        size_t *m = realloc(cv->members, cap * sizeof *m);
        if (m == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        cv->members = m;
        cv->cap = cap;
    }
    cv->members[cv->n_members++] = i;
    return GSL_SUCCESS;
}

/* The birth whose critical rate is nearest omega (a return to the hanging chain). */
static int nearest_birth(const double *crit, size_t n, double omega)
{
    size_t best = 0;
    for (size_t k = 1; k < n; k++)
        if (fabs(crit[k] - omega) < fabs(crit[best] - omega)) best = k;
    return (int)best + 1;
}

/* Follows the path p (started) until its rate exceeds omega_max, it returns to the hanging
 * chain, it closes on the entry `start` (SIZE_MAX: no closure test) or it fails; every
 * crossing of omega goes into the list (source 4) and the curve. Returns 1 if it closed, 0
 * otherwise, or minus a status (an interrupt or no memory; a failed continuation only marks
 * the curve). */
static int follow_curve(whirl_nlink_path *p, double omega, double omega_max, const double *crit,
                        eq_list *l, curve *cv, size_t start, angle_ws *aw, whirl_equilibria *res)
{
    int status;
    while (p->omega <= omega_max && !p->ended) {
        if (p->steps >= PATH_STEPS_MAX) {
            /* the step budget: as a failure (below) */
            if (p->omega > omega) res->cut_short++;
            else cv->failed = 1;
            return 0;
        }
        status = whirl_nlink_path_step(p);
        res->path_steps++;
        if (status == WHIRL_EINTERRUPTED || status == GSL_ENOMEM) return -status;
        if (status) {
            /* above omega every crossing of omega before the failure has been seen: the curve
             * is cut short there (a birth lies beyond only if the curve comes back below
             * omega, through another root, followed on its own) */
            if (p->omega > omega) res->cut_short++;
            else cv->failed = 1;
            return 0;
        }
        for (int e = 0; e < p->n_events; e++) {
            const whirl_branch_event *ev = &p->event[e];
            if (ev->kind == WHIRL_EVENT_FOLD && ev->omega < cv->fold_lo) cv->fold_lo = ev->omega;
            if (ev->kind == WHIRL_EVENT_RETURN)
                cv->branch = nearest_birth(crit, p->chain->n, ev->omega);
        }
        double tip[WHIRL_PATH_EVENTS_MAX + 1];
        int found = whirl_nlink_path_crossings(p, omega, WHIRL_PATH_EVENTS_MAX + 1, tip);
        if (found < 0) {
            if (-found == WHIRL_EINTERRUPTED) return found;
            cv->failed = 1;
            return 0;
        }
        for (int k = 0; k < found; k++) {
            double a = fabs(tip[k]);
            size_t before = l->n;
            /* from the crossing's own link angles (the tip radius alone does not fix the
             * shape where roots crowd) */
            memcpy(aw->theta, whirl_nlink_path_cross_theta(p) + (size_t)k * l->links, l->links * sizeof *aw->theta);
            if ((status = eq_angle_polish(aw, &a))) {
                if (status == WHIRL_EINTERRUPTED || status == GSL_ENOMEM) return -status;
                cv->failed = 1;
                return 0;
            }
            size_t i = eq_list_merge(l, a, aw->theta, 4, &status);
            if (i == SIZE_MAX) return -status;
            res->crossings++;
            if (l->n > before) res->missed++;
            if ((status = curve_member(cv, i))) return -status;
            if (i == start && p->steps > 1) return 1;
        }
    }
    return 0;
}

static void label_curve(eq_list *l, const curve *cv, const double *crit)
{
    for (size_t j = 0; j < cv->n_members; j++) {
        whirl_equilibrium *e = &l->eq[cv->members[j]];
        if (e->branch > 0) continue;
        if (cv->branch > 0) {
            e->branch = cv->branch;
            e->born_at = crit[cv->branch - 1];
        } else if (!cv->failed) {
            e->branch = 0;
            e->born_at = isfinite(cv->fold_lo) ? cv->fold_lo : GSL_NAN;
        }
    }
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* The curves whose crossings of omega have the wrong parity. A branch born below omega that
 * does not return to the hanging chain starts below omega and ends above it: it crosses omega
 * an odd number of times; one that returns (returned[k - 1]) an even number. A curve that meets
 * no birth rises above omega at both ends: an even number. Its equilibria share born_at, the
 * same double (label_curve). */
static int parity_check(const eq_list *l, size_t n, const double *crit, double omega,
                        const int *returned, whirl_equilibria *res)
{
    double *fold = malloc((l->n + 1) * sizeof *fold);
    if (fold == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu folds", l->n);
    for (size_t k = 1; k <= n && crit[k - 1] < omega; k++) {
        size_t count = 0;
        for (size_t i = 0; i < l->n; i++) count += l->eq[i].branch == (int)k;
        res->wrong_parity += (count % 2 == 0) != (returned[k - 1] != 0);
    }
    size_t m = 0;
    for (size_t i = 0; i < l->n; i++)
        if (l->eq[i].branch == 0 && isfinite(l->eq[i].born_at)) fold[m++] = l->eq[i].born_at;
    qsort(fold, m, sizeof *fold, cmp_double);
    for (size_t i = 0, j; i < m; i = j) {
        for (j = i; j < m && fold[j] == fold[i]; j++) continue;
        res->wrong_parity += (j - i) % 2;
    }
    free(fold);
    return GSL_SUCCESS;
}

int eq_continue_all(const whirl_chain *c, double omega, double factor, const double *crit,
                    eq_list *l, angle_ws *aw, whirl_equilibria *res)
{
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    int *returned = calloc(c->n, sizeof *returned);
    if (p == NULL || returned == NULL) {
        whirl_nlink_path_free(p);
        free(returned);
        return whirl_fail(GSL_ENOMEM, "out of memory for the continuation");
    }
    double omega_max = factor * omega;
    int status = GSL_SUCCESS;
    curve cv = {0};
    /* every branch from its birth */
    for (size_t k = 1; k <= c->n && !status && crit[k - 1] <= omega_max; k++) {
        cv.branch = (int)k;
        cv.fold_lo = INFINITY;
        cv.n_members = 0;
        cv.failed = 0;
        if ((status = whirl_nlink_path_birth(p, (int)k))) break;
        int r = follow_curve(p, omega, omega_max, crit, l, &cv, SIZE_MAX, aw, res);
        if (r < 0) {
            status = -r;
            break;
        }
        returned[k - 1] = p->ended;
        cv.branch = (int)k; /* the birth it starts from, even if it returns at another */
        cv.failed = 0;      /* its crossings are on branch k whatever happened further on */
        label_curve(l, &cv, crit);
    }
    /* the curves through the roots no branch crossed: both ways */
    for (size_t i = 0; i < l->n && !status; i++) {
        if (l->eq[i].branch >= 0) continue;
        cv.branch = 0;
        cv.fold_lo = INFINITY;
        cv.n_members = 0;
        cv.failed = 0;
        if ((status = curve_member(&cv, i))) break;
        int closed = 0;
        for (int dir = -1; dir <= 1 && !closed && !status; dir += 2) {
            if (whirl_nlink_path_start_angles(p, omega, l->theta + i * l->links, dir)) {
                cv.failed = 1;
                continue;
            }
            int r = follow_curve(p, omega, omega_max, crit, l, &cv, i, aw, res);
            if (r < 0) status = -r;
            closed = r == 1;
        }
        if (!status) label_curve(l, &cv, crit);
    }
    if (!status) status = parity_check(l, c->n, crit, omega, returned, res);
    free(cv.members);
    free(returned);
    whirl_nlink_path_free(p);
    return status;
}
