/* Every planar relative equilibrium of the spun chain at one rate omega, with the branch each
 * lies on.
 *
 * N-link chain. Built up from the tip with tip radius a (src/nlink.c, src/nlink_path.c), the
 * shape is an equilibrium when the pivot lands on the axis: G(omega, a) = u_0 / |u| = 0, with
 * u_i = r_i / a, and G depends on a only through a^2. Every nontrivial equilibrium has a != 0
 * (a = 0 makes every r_i zero) and its mirror image has -a, so the equilibria are the roots of
 * G(omega, .) on 0 < a < L (L = sum l_i; for a >= L, r_0 >= a - L > 0).
 *
 * Completeness argument (three methods; the result lists their union and how they agree):
 * 1. Tip scan. Below the floor a_f = 1e-8 min_i V_i / |eta_i^0| (eta^0: the linear shot's
 *    horizontal loads per unit a, V_i the weight below link i) every tension differs from V_i
 *    by a factor 1 + O(1e-16): the shot is the linear one, G(omega, a) = G(omega, 0) to
 *    round-off, and G(omega, 0) != 0 unless omega is a critical rate (refused within 1e-10
 *    relative). So every root lies in [a_f, L). In x = ln(a / (L - a)) (logarithmic at both
 *    ends: high modes have tip radii down to 1e-18 of their largest radius, mode 1 at high rates
 *    a tip radius within ~1/(2 omega^4) of L) the interval [ln a_f - 9, 36] is cut into a grid,
 *    and each cell [x_l, x_r] with its midpoint x_m is accepted when (c) and either (a) or (b)
 *    hold:
 *      (a) G has one sign at the three points and min |G| > h max |G'| (h = x_r - x_l): G
 *          stays away from zero; or
 *      (b) G' has one strict sign at the three points and the cubic Hermite interpolant of the
 *          ends predicts G(x_m) to tau |G(x_r) - G(x_l)|: G is monotone on the cell, so it has
 *          at most one root, found by the sign change;
 *      (c) every link angle theta_i = atan(H_i / V_i) is resolved: it turns by at most 0.25 rad
 *          from each of the three points to the next, and the cubic Hermite interpolant of its
 *          tangent H_i / V_i (exact derivative) predicts theta_i(x_m) to tau rad;
 *    and otherwise halved, down to a width of 1e-14 (1 + |x|) (about 50 rounding units of x; a
 *    cell accepted there is counted as unresolved: a near-tangent root, i.e. omega within
 *    ~1e-28 of a fold). G' = dG/da da/dx is exact (forward differentiation of the recursion).
 *    The scan is repeated with a grid 4 times finer and tau 4 times smaller until two
 *    successive levels give the same count.
 *    Why (c): at high rates (|H_i| >> V_i) a link angle turns by nearly pi where H_i passes
 *    through zero, over a width ~ V_i / |dH_i/dx| that shrinks with the rate (1e-11 in x for 10
 *    links at omega = 40), and every link above it follows; G varies on that scale only
 *    there, so samples on either side show nothing of it (a and b passed on cells holding two
 *    roots 1e-7 apart in a: 10 links at omega = 30 lost 10 of 1084 roots to the pivot scan's
 *    count). G is a smooth function of a and the angles (r_0 = a - sum l_i sin theta_i), so a
 *    cell on which every angle is resolved, G included, holds what (a) and (b) say. Each H_i is
 *    a smooth function of the angles below link i, which is what the Hermite test on its
 *    tangent checks, from the tip up. Clusters of roots (a hundred on 7 links at omega = 21.1,
 *    some 1e-5 apart in a; over a thousand on 10 links at omega = 40, 1e-7 apart) are resolved
 *    this way.
 * 2. Pivot scan, an independent formulation: the top link's angle theta_1 in (0, pi/2) (every
 *    nontrivial equilibrium has theta_1 != 0, and theta_1 > 0 for one of the mirror pair) fixes
 *    the horizontal force at the pivot; going down the chain the force left below the tip,
 *    H_{N+1} / H_1, vanishes for an equilibrium (whirl_nlink_pivot_residual). Scanned the same
 *    way in y = ln(theta_1 / (pi/2 - theta_1)) from its own linear floor. Its roots must be those
 *    of method 1. Every root of either scan is polished by Newton's method on all link angles
 *    (equilibria_nlink.c), started from its own shot's angles, and two are the same equilibrium
 *    when every link angle agrees to 1e-8 rad.
 * 3. Continuation (whirl_nlink_path): every branch born at a critical rate below
 *    follow_factor * omega is followed from its birth, and the curve through every root not on
 *    one of them is followed both ways, each up to follow_factor * omega, until it returns to
 *    the hanging chain (a birth: the root is on that branch) or closes; each crossing of omega is
 *    matched against the scans' roots (a crossing they did not find counts as missed and is
 *    added). A curve starts from its root's polished link angles, and each crossing is polished
 *    from the path's own link angles there: where roots crowd (tip radii 1e-7 apart on 10 links
 *    at omega = 40) a tip radius does not single out one root to the shot, and a start from it
 *    failed on the first step or could begin on a neighbour. The path rejects a step on which
 *    its orientation test reverses (src/nlink_path.c): that is what a step that lands on the
 *    neighbouring curve looks like, and such jumps had put mode 7's branch of 10 links onto an
 *    isolated curve near omega = 12.89. Curves that meet no birth are isolated: they appear as pairs at folds, and the
 *    lowest fold found is reported as where the curve is born.
 * Limits: (b) and (c) test at three points per cell, they do not prove (two roots closer
 * than a cell on which the Hermite cubics fit G and every angle to tau would be missed by a
 * scan; the other scan, whose parameter runs the other way along the chain, and method 3 are
 * the checks). Curves that first cross omega after rising above follow_factor * omega are
 * followed from their own roots, and a birth reached only above that limit is not seen (the
 * root is then called isolated). The path sees a jump to the next curve (its orientation
 * reverses), not one over two curves at once, nor onto a curve closer than its shortest
 * tested step (1e-6) tells apart: the parity of the crossings (odd on a branch born below
 * omega that does not return to the hanging chain, even on a curve that meets no birth) is the
 * check (tests/test_equilibria.c). Features narrower than the cell floor (a rounding limit of
 * the parameter) are counted as unresolved. Where roots crowd within round-off of each other
 * (10 links at omega = 60: tip radii 3e-15 apart) a double shot's link angles can be too far
 * off for Newton's method: such a root is bisected again in quadruple precision and polished
 * from that shot's angles (equilibria_nlink.c, eq_polish_root); one that does not polish even
 * so (none on 10 links up to omega = 80, 4 of 1511 roots at 100) is counted as not polished and
 * left out, and the two scans' lists then differ (the result says by how many). Two roots of
 * one scan polished onto one equilibrium are counted (coincident; 0 expected). The cost is about
 * proportional to the number of equilibria, which at high rates grows about exponentially
 * with N (25 links: 1354 at omega = 30, 9672 at 35, about 75000 at 40): shot_budget bounds
 * each level and GSL_EMAXITER says when it is exceeded; method 3 costs thousands of steps per
 * root and can be left out (params.continuation = 0) to count. Duplicates among the scans'
 * roots are merged after sorting by tip radius (eq_list_unique), not by a search per root.
 *
 * Continuous chain: Kolodner (1955, Comm. Pure Appl. Math. 8:395, "Heavy rotating string - a
 * nonlinear eigenvalue problem") proves exactly n nontrivial shapes for omega_n < omega <=
 * omega_{n+1}, mode j with j - 1 axis crossings. Method 2 solves each mode 1..n
 * (whirl_continuum_solve, bracketing by the crossing count); method 1 counts the sign changes
 * of r(pivot; a) on a grid in ln a from 1e-9 / (1 + omega^2) (where the shot is linear) to 1,
 * doubled until the count repeats, and checks that each solved shape lies in its own
 * sign-change bracket.
 *
 * The search in files of one concern each (what they share in equilibria_internal.h): the
 * adaptive scan (equilibria_scan.c), the N-link scans, Newton's method on the link angles and
 * the quadruple-precision refinement (equilibria_nlink.c), the list of equilibria
 * (equilibria_list.c), the continuation (equilibria_follow.c); here the two chains' searches.
 *
 * References: Keller 1977 and Allgower & Georg 1990 (continuation, see nlink_path.c); Brent
 * 1973, "Algorithms for minimization without derivatives", ch. 4 (GSL roots/brent.c) for the
 * roots; Fritsch & Carlson 1980, SIAM J. Numer. Anal. 17:238 (monotone cubic Hermite
 * interpolation) for the test (b). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>
#include "core/error.h"
#include "steady/equilibria_internal.h"
#include "steady/steady_internal.h"

#define SCAN_X_TOP 36.0      /* top of the scan: L - a = L e^-36 ~ 2e-16 L */
#define SCAN_BELOW_FLOOR 9.0 /* the scan starts e^-9 ~ 1e-4 below the linear floor */
#define FLOOR_NONLINEAR 1e-8 /* |H_i| / V_i at the floor */
#define CRITICAL_GAP 1e-10   /* omega refused this close (relative) to a critical rate */

whirl_equilibria_params whirl_equilibria_defaults(void)
{
    whirl_equilibria_params p = {1, 2.0, 20000000L, 1};
    return p;
}

void whirl_equilibria_free(whirl_equilibria *e)
{
    if (e == NULL) return;
    free(e->eq);
    free(e);
}

void eq_report(const eq_progress *p, int stage, size_t done, size_t total)
{
    if (p->fn == NULL) return;
    const size_t every = total > 256 ? total / 256 : 1;
    if (done != 0 && done != total && done % every != 0) return;
    const whirl_equilibria_progress at = {stage, p->stages, done, total};
    p->fn(p->ctx, &at);
}

static int cmp_tip(const void *x, const void *y)
{
    double a = ((const whirl_equilibrium *)x)->info.tip_r;
    double b = ((const whirl_equilibrium *)y)->info.tip_r;
    return (a > b) - (a < b);
}

static int nlink_find(const whirl_chain *c, double omega, const whirl_equilibria_params *par,
                      angle_ws *aw, whirl_equilibria *res, eq_list *l, const eq_progress *rep)
{
    size_t n = c->n;
    double *crit = malloc(n * sizeof *crit);
    if (crit == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for %zu critical rates", n);
    int status = whirl_nlink_critical(c, n, crit);
    for (size_t k = 0; k < n && !status; k++) {
        if (fabs(omega / crit[k] - 1) <= CRITICAL_GAP)
            status = whirl_fail(GSL_EDOM, "omega=" WHIRL_Q_RATE "%.17g is the critical rate of "
                                "mode %zu (omega_%zu=" WHIRL_Q_RATE "%.17g): its branch is born "
                                "there, not separated from the hanging chain", omega, k + 1, k + 1,
                                crit[k]);
        if (crit[k] < omega) res->born++;
    }
    nlink_scan s = {c, omega, 0, NULL, NULL};
    for (size_t i = 0; i < n; i++) s.length += c->length[i];
    if (!status && (s.slope = malloc(2 * n * sizeof *s.slope)) == NULL)
        status = whirl_fail(GSL_ENOMEM, "out of memory for %zu links", n);
    s.slope_d = s.slope + n;
    double per_tip, per_top;
    eq_linear_loads(c, omega, &per_tip, &per_top);
    if (!status && !(isfinite(per_tip) && isfinite(per_top) && per_tip < 1e150 && per_top < 1e150))
        status = whirl_fail(GSL_ERANGE, "%zu links at omega=" WHIRL_Q_RATE "%g: the linear shot's "
                            "loads overflow (more than 1e150): too many links for this rate", n,
                            omega);
    scan_out tip = {0}, top = {0};
    size_t n0 = 256 + 16 * n;
    if (!status) {
        eq_report(rep, 1, 0, 1);
        res->tip_floor = FLOOR_NONLINEAR / per_tip;
        double x0 = log(res->tip_floor / s.length) - SCAN_BELOW_FLOOR;
        scan_problem pb = {eq_tip_fn, &s, n, par->shot_budget};
        status = eq_scan_settled(&pb, x0, SCAN_X_TOP, n0, &tip, &res->tip_levels);
        res->tip_shots = tip.evals;
        res->tip_unresolved = tip.unresolved;
    }
    if (!status) {
        eq_report(rep, 2, 0, 1);
        double y0 = log(FLOOR_NONLINEAR / per_top / M_PI_2) - SCAN_BELOW_FLOOR;
        scan_problem pb = {eq_pivot_fn, &s, n, par->shot_budget};
        status = eq_scan_settled(&pb, y0, SCAN_X_TOP, n0, &top, &res->check_levels);
        res->check_shots = top.evals;
    }
    /* the roots, polished */
    if (!status) eq_report(rep, 3, 0, tip.n + 1);
    for (size_t i = 0; i < tip.n && !status; i++) {
        double x, a = 0;
        if ((status = eq_check_stop(i, tip.n))) break;
        eq_report(rep, 3, i + 1, tip.n + 1);
        if (!(status = eq_polish(eq_tip_fn, &s, tip.br[i].lo, tip.br[i].hi, &x)))
            a = eq_tip_of_x(&s, x), status = eq_angles_of_scan(&s, x, aw->theta);
        if (!status)
            status = eq_polish_root(aw, &s, eq_tip_quad, eq_tip_of_x(&s, tip.br[i].lo),
                                    eq_tip_of_x(&s, tip.br[i].hi), &a, &res->refined);
        if (status == GSL_EFAILED || status == GSL_ESING) {
            res->unpolished++; /* reported; the other scan is the check */
            status = GSL_SUCCESS;
            continue;
        }
        if (!status) status = eq_list_add(l, a, aw->theta, 1);
    }
    res->tip_roots = tip.n;
    if (!status) eq_report(rep, 4, 0, top.n + 1);
    for (size_t i = 0; i < top.n && !status; i++) {
        double y, g, a;
        if ((status = eq_check_stop(i, top.n))) break;
        eq_report(rep, 4, i + 1, top.n + 1);
        if (!(status = eq_polish(eq_pivot_fn, &s, top.br[i].lo, top.br[i].hi, &y)))
            status = whirl_nlink_pivot_shot(c, omega, eq_theta_of_y(y), &g, NULL, &a, aw->theta,
                                            NULL, NULL);
        if (!status)
            status = eq_polish_root(aw, &s, eq_pivot_quad, tan(eq_theta_of_y(top.br[i].lo)),
                                    tan(eq_theta_of_y(top.br[i].hi)), &a, &res->refined);
        if (status == GSL_EFAILED || status == GSL_ESING) {
            res->unpolished++; /* reported; the other scan is the check */
            status = GSL_SUCCESS;
            continue;
        }
        if (!status) status = eq_list_add(l, a, aw->theta, 2);
    }
    res->check_roots = top.n;
    eq_scan_out_free(&tip);
    eq_scan_out_free(&top);
    free(s.slope);
    if (!status) status = eq_list_unique(l);
    res->coincident = l->coincident;
    for (size_t i = 0; i < l->n; i++) res->matched += (l->source[i] & 3) == 3;
    if (!status) eq_report(rep, 5, 0, 1);
    if (!status && par->continuation)
        status = eq_continue_all(c, omega, par->follow_factor, crit, l, aw, res);
    free(crit);
    return status;
}

/* ---- continuous chain ---- */

static int continuum_find(double tip_mass, double omega, whirl_equilibria *res, eq_list *l,
                          const eq_progress *rep)
{
    double crit[WHIRL_MODE_MAX + 1];
    int status = GSL_SUCCESS;
    int n = 0;
    for (int k = 1; k <= WHIRL_MODE_MAX + 1 && !status; k++) {
        if (k == WHIRL_MODE_MAX + 1) {
            status = whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g is above the birth of mode "
                                "%d, the most the continuum solver handles", omega,
                                WHIRL_MODE_MAX + 1);
            break;
        }
        if ((status = whirl_continuum_critical(k, tip_mass, &crit[k - 1]))) break;
        if (fabs(omega / crit[k - 1] - 1) <= CRITICAL_GAP)
            status = whirl_fail(GSL_EDOM, "omega=" WHIRL_Q_RATE "%.17g is the critical rate of "
                                "mode %d (omega_%d=" WHIRL_Q_RATE "%.17g): its branch is born "
                                "there, not separated from the hanging chain", omega, k, k,
                                crit[k - 1]);
        if (crit[k - 1] > omega) break;
        n = k;
    }
    res->born = n;
    /* method 2: Kolodner's shapes, one per mode */
    if (!status) eq_report(rep, 1, 0, (size_t)n + 1);
    for (int k = 1; k <= n && !status; k++) {
        whirl_shape_info info;
        eq_report(rep, 1, (size_t)k, (size_t)n + 1);
        if ((status = whirl_continuum_solve(omega, k, tip_mass, 0, &info))) break;
        if ((status = eq_list_add(l, info.tip_r, NULL, 2))) break;
        whirl_equilibrium *e = &l->eq[l->n - 1];
        e->info = info;
        e->branch = k;
        e->born_at = crit[k - 1];
        res->check_roots++;
    }
    /* method 1: sign changes of r(pivot) over ln a, doubled until the count repeats */
    double a_floor = 1e-9 / (1 + omega * omega), la = log(a_floor);
    size_t m = 32 + 8 * (size_t)n, prev_count = SIZE_MAX;
    double *a = NULL, *r = NULL;
    int *cr = NULL;
    res->tip_floor = a_floor;
    if (!status) eq_report(rep, 2, 0, SCAN_LEVELS_MAX);
    for (int level = 0; level < SCAN_LEVELS_MAX && !status; level++, m *= 2) {
        if (level > 0) eq_report(rep, 2, (size_t)level, SCAN_LEVELS_MAX);
        double *a2 = realloc(a, (m + 1) * sizeof *a), *r2 = NULL;
        if (a2) a = a2;
        if (a2) r2 = realloc(r, (m + 1) * sizeof *r);
        if (r2) r = r2;
        int *cr2 = r2 ? realloc(cr, (m + 1) * sizeof *cr) : NULL;
        if (cr2 == NULL) {
            status = whirl_fail(GSL_ENOMEM, "out of memory for %zu shots", m + 1);
            break;
        }
        cr = cr2;
        for (size_t i = 0; i <= m; i++) a[i] = i == m ? 1 : exp(la * (1 - (double)i / (double)m));
        if ((status = whirl_continuum_shots(omega, tip_mass, m + 1, a, r, cr))) break;
        res->tip_shots = (long)m + 1;
        res->tip_levels = level + 1;
        size_t count = 0, matched = 0;
        for (size_t i = 0; i < m; i++) {
            if (eq_sign_of(r[i]) == eq_sign_of(r[i + 1])) continue;
            count++;
            size_t inside = 0;
            for (size_t j = 0; j < l->n; j++)
                inside += l->eq[j].info.tip_r >= a[i] && l->eq[j].info.tip_r <= a[i + 1];
            matched += inside == 1;
        }
        if (count == prev_count) {
            res->tip_roots = count;
            res->matched = matched;
            break;
        }
        prev_count = count;
        if (level == SCAN_LEVELS_MAX - 1)
            status = whirl_fail(GSL_ETOL, "the continuum's root count did not settle in "
                                "%d levels", SCAN_LEVELS_MAX);
    }
    free(a);
    free(r);
    free(cr);
    return status;
}

int whirl_equilibria_search(const whirl_chain *c, double tip_mass, double omega,
                            const whirl_equilibria_params *params,
                            const whirl_equilibria_verdict *verdict,
                            whirl_equilibria_progress_fn progress, void *ctx,
                            whirl_equilibria **out)
{
    *out = NULL;
    whirl_equilibria_params par = params ? *params : whirl_equilibria_defaults();
    if (!(par.follow_factor > 1 && isfinite(par.follow_factor) && par.shot_budget >= 1000))
        return whirl_fail(GSL_EINVAL, "equilibria: follow_factor must be > 1 and shot_budget "
                          ">= 1000");
    double omega_max = c ? WHIRL_EQUILIBRIA_OMEGA_MAX : WHIRL_EQUILIBRIA_CONTINUUM_OMEGA_MAX;
    if (!(isfinite(omega) && omega > 0 && omega <= omega_max))
        return whirl_fail(GSL_EINVAL, "omega=" WHIRL_Q_RATE "%g is out of range for %s: it must be "
                          "> 0 and at most omega=" WHIRL_Q_RATE "%g", omega,
                          c ? "the N-link chain" : "the continuum", omega_max);
    if (c != NULL && (c->n < 1 || c->n > WHIRL_EQUILIBRIA_LINKS_MAX))
        return whirl_fail(GSL_EINVAL, "a chain of 1..%d links for the equilibria, got %zu",
                          WHIRL_EQUILIBRIA_LINKS_MAX, c->n);
    whirl_equilibria *res = calloc(1, sizeof *res);
    if (res == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    res->omega = omega;
    res->n_links = c ? c->n : 0;
    eq_list l = {0};
    l.links = c ? c->n : 0;
    for (size_t i = 0; i < l.links; i++) l.window += 2 * MATCH_ANGLE * c->length[i];
    angle_ws *aw = c ? eq_angle_ws_alloc(c, omega) : NULL;
    int status = c && aw == NULL ? whirl_last_status() : GSL_SUCCESS;
    const eq_progress rep = {progress, ctx, c ? 6 : 2};
    if (!status)
        status = c ? nlink_find(c, omega, &par, aw, res, &l, &rep)
                   : continuum_find(tip_mass, omega, res, &l, &rep);
    if (!status && c) eq_report(&rep, 6, 0, l.n + 1);
    /* the shapes (polished once more, from their tip radii) and their linear verdicts */
    const int verdicts = c && par.stability && verdict != NULL;
    for (size_t i = 0; i < l.n && !status && c; i++) {
        whirl_equilibrium *e = &l.eq[i];
        if ((status = eq_check_stop(i, l.n))) break;
        eq_report(&rep, 6, i + 1, l.n + 1);
        memcpy(aw->theta, l.theta + i * l.links, l.links * sizeof *aw->theta);
        if ((status = eq_angle_polish(aw, &e->info.tip_r))) break;
        whirl_nlink_info_nodes(c, aw->r, aw->z, aw->t, omega, e->branch > 0 ? e->branch : 0,
                               &e->info);
        if ((status = whirl_steady_check_info(&e->info))) break;
        res->isolated += e->branch == 0;
        res->unidentified += e->branch < 0;
        if (verdicts)
            status = verdict->judge(verdict->ctx, aw->r, aw->z, &e->eig_growth, &e->index);
    }
    if (aw) res->balance = aw->worst;
    eq_angle_ws_free(aw);
    free(l.source);
    free(l.theta);
    if (status) {
        free(l.eq);
        free(res);
        return status;
    }
    if (c) eq_report(&rep, 6, l.n + 1, l.n + 1);
    else eq_report(&rep, 2, SCAN_LEVELS_MAX, SCAN_LEVELS_MAX);
    qsort(l.eq, l.n, sizeof *l.eq, cmp_tip);
    res->eq = l.eq;
    res->count = l.n;
    *out = res;
    return GSL_SUCCESS;
}
