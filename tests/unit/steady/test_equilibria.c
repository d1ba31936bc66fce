/* Tests of every equilibrium at a rate (src/equilibria.c):
 * - N = 5 at omega = 11.62: 1, 1, 3, 5, 7 equilibria with 1..5 nodes; the three methods agree
 *   (tip scan, pivot scan, continuation: nothing missed, every root identified); every shape
 *   balances each link to round-off; the equilibrium on branch k is the one whirl_nlink_solve
 *   returns for mode k; a plain uniform scan of the tip shot on 2^17 points (no refinement, no
 *   derivatives) finds the same tip radii;
 * - the isolated ones are born in pairs at their folds: just above each reported fold rate
 *   there are exactly two more equilibria than just below it, and they are the pair;
 * - N = 7 at omega = 21.1: a cluster of 103 equilibria, 11 of them with four nodes, the two scans
 *   in agreement, the count settled;
 * - high rates (6 and 8 links at omega = 25), where link angles flip over 1e-11 in the
 *   scan's parameter: the two scans find the same equilibria;
 * - 10 links at omega = 40, roots crowded to 1e-7 in tip radius: every one identified, each
 *   branch's crossing the shape whirl_nlink_solve returns, the isolated ones in pairs per fold,
 *   the count rising by two across four of the folds;
 * - 10 links at omega = 60, roots crowded within round-off (tip radii 3e-15 apart): every root of
 *   both scans polished (two of them from a shot in quadruple precision) onto an equilibrium of
 *   its own, the crowded ones as a 60-digit mpmath shot gives them;
 * - the continuum: Kolodner's count, exactly n shapes for omega_n < omega < omega_{n+1}, just
 *   above and just below the critical rates, with and without a tip mass;
 * - linear verdicts: those of the shapes of modes 1 and 2 as whirl_stability_mode gives them,
 *   mode 1 stable (eig_growth 0);
 * - the pivot scan's derivative against central differences;
 * - the error paths. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "steady/steady_internal.h"
#include "whirl/stability.h"
#include "whirl/steady.h"

static whirl_equilibria *find(const whirl_chain *c, double tip_mass, double omega, int stability)
{
    whirl_equilibria_params p = whirl_equilibria_defaults();
    p.stability = stability;
    whirl_equilibria *e = NULL;
    int status = whirl_equilibria_find(c, tip_mass, omega, &p, &e);
    if (status) print_error("omega=%g: %s\n", omega, whirl_last_error());
    assert_int_equal(status, GSL_SUCCESS);
    assert_non_null(e);
    return e;
}

/* The scans agree: both found every equilibrium, each root polished onto an equilibrium of its
 * own. */
static void assert_scans_agree(const whirl_equilibria *e)
{
    assert_int_equal(e->tip_roots, e->count);
    assert_int_equal(e->check_roots, e->count);
    assert_int_equal(e->matched, e->count);
    assert_int_equal(e->unpolished, 0);
    assert_int_equal(e->coincident, 0);
}

/* The methods agree: the scans, and the continuation missed none of the equilibria and
 * identified every one. */
static void assert_agreement(const whirl_equilibria *e)
{
    assert_scans_agree(e);
    assert_int_equal(e->missed, 0);
    assert_int_equal(e->unidentified, 0);
    assert_int_equal(e->wrong_parity, 0);
    assert_int_equal(e->tip_unresolved, 0);
    assert_true(e->tip_levels >= 2 && e->check_levels >= 2);
    assert_true(e->balance < 1e-13);
    for (size_t i = 1; i < e->count; i++) assert_true(e->eq[i].info.tip_r > e->eq[i - 1].info.tip_r);
}

static void test_five_links(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    double omega = 11.62;
    whirl_equilibria *e = find(c, 0, omega, 1);
    assert_agreement(e);
    int by_nodes[6] = {0};
    for (size_t i = 0; i < e->count; i++) by_nodes[e->eq[i].info.n_nodes + 1]++;
    const int expected[6] = {0, 1, 1, 3, 5, 7};
    for (int k = 1; k <= 5; k++) assert_int_equal(by_nodes[k], expected[k]);
    assert_int_equal(e->count, 17);
    assert_int_equal(e->born, 5);
    /* one equilibrium per branch here, the one whirl_nlink_solve returns */
    int on_branch[6] = {0};
    for (size_t i = 0; i < e->count; i++) {
        const whirl_equilibrium *q = &e->eq[i];
        assert_true(q->branch >= 0 && q->branch <= 5);
        if (q->branch == 0) {
            assert_true(q->born_at > 1 && q->born_at < omega);
            continue;
        }
        on_branch[q->branch]++;
        whirl_shape_info info;
        assert_int_equal(whirl_nlink_solve(c, omega, q->branch, &info), GSL_SUCCESS);
        assert_true(fabs(info.tip_r - q->info.tip_r) <= 1e-9 * q->info.tip_r);
        double crit[5];
        assert_int_equal(whirl_nlink_critical(c, 5, crit), GSL_SUCCESS);
        assert_true(fabs(q->born_at - crit[q->branch - 1]) <= 1e-12 * crit[q->branch - 1]);
        /* the shape's pivot lands on the axis: the tip shot's residual at round-off */
        double g;
        assert_int_equal(whirl_nlink_residual(c, omega, q->info.tip_r, &g, NULL, NULL),
                         GSL_SUCCESS);
        assert_true(fabs(g) < 1e-9);
    }
    for (int k = 1; k <= 5; k++) assert_int_equal(on_branch[k], 1);
    assert_int_equal(e->isolated, 12);
    /* a plain uniform scan in ln a (2^17 points, no refinement): the same roots */
    size_t m = 1 << 17, found = 0;
    double la = log(1e-12), prev = 0, a_prev = 0;
    for (size_t i = 0; i <= m; i++) {
        double a = exp(la * (1 - (double)i / (double)m)), g;
        if (a >= 1) a = 1 - 1e-15;
        assert_int_equal(whirl_nlink_residual(c, omega, a, &g, NULL, NULL), GSL_SUCCESS);
        if (i > 0 && (g > 0) != (prev > 0)) {
            /* exactly one equilibrium of the list in [a_prev, a] */
            int inside = 0;
            for (size_t j = 0; j < e->count; j++)
                inside += e->eq[j].info.tip_r >= a_prev * (1 - 1e-12) &&
                          e->eq[j].info.tip_r <= a * (1 + 1e-12);
            assert_int_equal(inside, 1);
            found++;
        }
        prev = g;
        a_prev = a;
    }
    assert_int_equal(found, e->count);
    /* mode 1 is stable, as the stability module says for the shape of mode 1 */
    whirl_stability *w = whirl_stability_alloc(5);
    whirl_model model = {0};
    model.chain = c;
    model.dim = 3;
    model.frame = WHIRL_FRAME_ROTATING;
    model.omega = omega;
    for (size_t i = 0; i < e->count; i++) {
        if (e->eq[i].branch != 1 && e->eq[i].branch != 2) continue;
        double growth;
        assert_int_equal(whirl_stability_mode(w, &model, e->eq[i].branch, NULL, &growth),
                         GSL_SUCCESS);
        assert_true(fabs(growth - e->eq[i].eig_growth) <= 1e-8 * (1 + fabs(growth)));
        if (e->eq[i].branch == 1) assert_true(e->eq[i].eig_growth == 0);
    }
    whirl_stability_free(w);
    whirl_equilibria_free(e);
    whirl_chain_free(c);
}

/* Each isolated curve's fold: two equilibria more just above it than just below, and the two
 * new ones are the closest pair to each other among the new list at the fold. */
static void test_fold_pairs(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_equilibria *e = find(c, 0, 11.62, 0);
    double folds[32];
    int nf = 0;
    for (size_t i = 0; i < e->count; i++) {
        if (e->eq[i].branch != 0) continue;
        int seen = 0;
        for (int j = 0; j < nf; j++) seen |= folds[j] == e->eq[i].born_at;
        if (!seen) folds[nf++] = e->eq[i].born_at;
    }
    assert_int_equal(nf, 6);
    for (int j = 0; j < nf; j++) {
        whirl_equilibria *below = find(c, 0, folds[j] * (1 - 1e-7), 0);
        whirl_equilibria *above = find(c, 0, folds[j] * (1 + 1e-7), 0);
        assert_agreement(below);
        assert_agreement(above);
        assert_int_equal(above->count, below->count + 2);
        /* the new pair is isolated and born at this fold */
        int at_fold = 0;
        for (size_t i = 0; i < above->count; i++)
            at_fold += above->eq[i].branch == 0 &&
                       fabs(above->eq[i].born_at - folds[j]) <= 1e-9 * folds[j];
        assert_int_equal(at_fold, 2);
        whirl_equilibria_free(below);
        whirl_equilibria_free(above);
    }
    whirl_equilibria_free(e);
    whirl_chain_free(c);
}

static void test_seven_links_cluster(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(7, 0);
    whirl_equilibria *e = find(c, 0, 21.1, 0);
    assert_agreement(e);
    assert_int_equal(e->count, 103);
    int four = 0;
    for (size_t i = 0; i < e->count; i++) four += e->eq[i].info.n_nodes + 1 == 4;
    assert_int_equal(four, 11);
    /* the roots of the cluster near a = 0.07 are 1e-5 apart or closer, and distinct */
    double closest = INFINITY;
    for (size_t i = 1; i < e->count; i++)
        closest = fmin(closest, e->eq[i].info.tip_r / e->eq[i - 1].info.tip_r - 1);
    assert_true(closest < 1e-4 && closest > 1e-7);
    whirl_equilibria_free(e);
    whirl_chain_free(c);
}

/* High rates, where link angles flip over widths of 1e-11 in the scan's parameter: 6 links at
 * omega = 25 (three methods in agreement, every root identified by continuation) and 8 links at
 * omega = 25 (the scans only). Without the test on the link angles the tip scan settled on 50
 * and 200 roots where the pivot scan found 54 and 224 (and 226): the two scans, shooting from
 * opposite ends, must now find the same equilibria link angle by link angle, each balanced to
 * round-off, with no cell left unresolved. */
static void test_high_rates(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(6, 0);
    whirl_equilibria *e = find(c, 0, 25, 0);
    assert_agreement(e);
    assert_int_equal(e->count, 54);
    whirl_equilibria_free(e);
    whirl_chain_free(c);

    c = whirl_chain_alloc_uniform(8, 0);
    whirl_equilibria_params p = whirl_equilibria_defaults();
    p.stability = 0;
    p.continuation = 0;
    assert_int_equal(whirl_equilibria_find(c, 0, 25, &p, &e), GSL_SUCCESS);
    assert_scans_agree(e);
    assert_int_equal(e->tip_unresolved, 0);
    assert_true(e->balance < 1e-13);
    assert_true(e->count >= 226);
    size_t unlabelled = 0;
    for (size_t i = 0; i < e->count; i++) unlabelled += e->eq[i].branch == -1;
    assert_int_equal(unlabelled, e->count);
    assert_int_equal(e->path_steps, 0);
    whirl_equilibria_free(e);
    whirl_chain_free(c);
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* 10 links at omega = 40 (2.3 omega_10), 1332 equilibria, many in clusters whose tip radii agree
 * to 1e-7. Started from its tip radius, the continuation of 30 of them failed on its first step
 * (the shot there does not tell the neighbours apart) and they were left unidentified; mode 7's
 * branch jumped near omega = 12.89 onto an isolated curve 5% away in tip radius (the step's
 * corrector landed on it), so that branch crossed omega twice and one isolated equilibrium had
 * no partner. Now: every equilibrium identified; every branch crosses omega once, at the shape
 * whirl_nlink_solve returns for its mode; the isolated ones come in pairs per fold (a curve
 * that meets no birth rises above omega at both ends, so it crosses omega an even number of
 * times); and at four of the folds the count of the scans alone rises by exactly two across
 * the fold. */
static void test_ten_links_high_rate(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(10, 0);
    const double omega = 40;
    whirl_equilibria *e = find(c, 0, omega, 0);
    assert_agreement(e);
    assert_int_equal(e->count, 1332);
    assert_int_equal(e->born, 10);
    int on_branch[11] = {0};
    size_t n_iso = 0;
    double *fold = malloc(e->count * sizeof *fold);
    assert_non_null(fold);
    for (size_t i = 0; i < e->count; i++) {
        const whirl_equilibrium *q = &e->eq[i];
        assert_true(q->branch >= 0 && q->branch <= 10);
        if (q->branch == 0) {
            assert_true(q->born_at > 1 && q->born_at < omega);
            fold[n_iso++] = q->born_at;
            continue;
        }
        on_branch[q->branch]++;
        whirl_shape_info info;
        assert_int_equal(whirl_nlink_solve(c, omega, q->branch, &info), GSL_SUCCESS);
        assert_true(fabs(info.tip_r - q->info.tip_r) <= 1e-9 * q->info.tip_r);
        assert_int_equal(info.n_nodes, q->info.n_nodes);
    }
    for (int k = 1; k <= 10; k++) assert_int_equal(on_branch[k], 1);
    assert_int_equal(n_iso, e->isolated);
    assert_int_equal(n_iso, e->count - 10);
    /* the isolated equilibria by their curve's lowest fold: pairs (or more, an even number) */
    qsort(fold, n_iso, sizeof *fold, cmp_double);
    size_t n_fold = 0;
    for (size_t i = 0; i < n_iso;) {
        size_t j = i;
        while (j < n_iso && fold[j] - fold[i] <= 1e-9 * fold[i]) j++;
        assert_true((j - i) % 2 == 0);
        fold[n_fold++] = fold[i];
        i = j;
    }
    assert_true(n_fold >= n_iso / 4);
    /* the count of the scans alone across four folds, each 1e-6 (relative) or more from the
     * next: the lowest, the highest and two between */
    whirl_equilibria_params p = whirl_equilibria_defaults();
    p.stability = 0;
    p.continuation = 0;
    const size_t pick[4] = {0, n_fold / 3, 2 * n_fold / 3, n_fold - 1};
    for (int j = 0; j < 4; j++) {
        size_t k = pick[j];
        while (k + 1 < n_fold && ((k > 0 && fold[k] - fold[k - 1] <= 1e-6 * fold[k]) ||
                                  fold[k + 1] - fold[k] <= 1e-6 * fold[k]))
            k++;
        whirl_equilibria *below = NULL, *above = NULL;
        assert_int_equal(whirl_equilibria_find(c, 0, fold[k] * (1 - 1e-7), &p, &below),
                         GSL_SUCCESS);
        assert_int_equal(whirl_equilibria_find(c, 0, fold[k] * (1 + 1e-7), &p, &above),
                         GSL_SUCCESS);
        assert_int_equal(below->matched, below->count);
        assert_int_equal(above->matched, above->count);
        assert_int_equal(above->count, below->count + 2);
        whirl_equilibria_free(below);
        whirl_equilibria_free(above);
    }
    free(fold);
    whirl_equilibria_free(e);
    whirl_chain_free(c);
}

/* 10 links at omega = 60 (3.5 omega_10), 1506 equilibria, roots crowded within round-off: three
 * tip radii within 3e-15 of each other, the middle one with its top link at 1e-15 rad from the
 * vertical (it turns by a radian over 3.6e-18 in tip radius, less than the spacing of doubles
 * there), and a shape whose tip radius is 4.5e-16 (its lower link angles 1e-12 rad and less).
 * From the double shots' link angles Newton's method did not converge at the tip scan's middle
 * root (the top link's start off by 1.4 rad) nor at the pivot scan's root of the second shape,
 * so each scan lacked one equilibrium the other had (both: 1504 of 1506, not polished: 2). Now
 * both are refined in quadruple precision: every root of either scan polished, each on an
 * equilibrium of its own, the two scans in agreement on all 1506.
 * The reference, independent of the library: mpmath (60 digits, and the same to every digit
 * given at 80 digits on a grid twice as fine), the shot from the tip for 10 equal links and
 * masses (L = M = g = 1) at omega = 60 over x = ln(a / (1 - a)) in [-2.9478812562812,
 * -2.9478812562794] on 18000 points, each sign change of r_0 refined by findroot (r_0 ~ 1e-48):
 * exactly three roots,
 *   a = 0.04983674488450310751080604: 10 nodes, depth 0.76450917549002525092, top tension
 *       1.1552855586836483537, max_r 0.050161701814764244331;
 *   a = 0.04983674488450588749387310: 10 nodes, depth 0.88687494839502721539, top tension
 *       1 + 4.8e-31 (theta_1 = -9.8426047413657034e-16), max_r 0.050161701814761464521;
 *   a = 0.04983674488450866747694004: 9 nodes, depth 0.76450917549263789361, top tension
 *       1.1552855586836940548, max_r 0.050161701814758684712;
 * and the shot from the pivot, its root at ln(theta_1 / (pi/2 - theta_1)) =
 * 4.001768241262640468518658 (between neighbours 5.3e-14 away): tip radius
 * 4.469792644893128687888832e-16, 9 nodes, depth 0.77814600669742862371, top tension
 * 35.461098027432107087, max_r 0.099960230327603584193 (the tip shot from that radius lands on
 * the axis to 5e-30 with the same link angles). */
static void test_crowded_roots(void **state)
{
    (void)state;
    static const struct {
        double tip_r, depth, top_tension, max_r;
        int nodes;
    } ref[4] = {
        {0.04983674488450310751, 0.76450917549002525092, 1.1552855586836483537,
         0.050161701814764244331, 10},
        {0.04983674488450588749, 0.88687494839502721539, 1, 0.050161701814761464521, 10},
        {0.04983674488450866748, 0.76450917549263789361, 1.1552855586836940548,
         0.050161701814758684712, 9},
        {4.469792644893128687888832e-16, 0.77814600669742862371, 35.461098027432107087,
         0.099960230327603584193, 9},
    };
    whirl_chain *c = whirl_chain_alloc_uniform(10, 0);
    whirl_equilibria_params p = whirl_equilibria_defaults();
    p.stability = 0;
    p.continuation = 0;
    whirl_equilibria *e = NULL;
    assert_int_equal(whirl_equilibria_find(c, 0, 60, &p, &e), GSL_SUCCESS);
    assert_int_equal(e->count, 1506);
    assert_scans_agree(e);
    assert_int_equal(e->refined, 2);
    /* round-off of the check itself, which sums the radii from the pivot: 1.9e-13 at this rate
     * (horizontal loads up to 180 times the weight below), against 6e-15 on 5 links at 11.62 */
    assert_true(e->balance < 5e-13);
    for (int k = 0; k < 4; k++) {
        /* the equilibrium nearest in tip radius: within half the spacing of the three (2.8e-15),
         * each figure of its shape as mpmath's */
        size_t best = 0;
        for (size_t i = 1; i < e->count; i++)
            if (fabs(e->eq[i].info.tip_r - ref[k].tip_r) <
                fabs(e->eq[best].info.tip_r - ref[k].tip_r))
                best = i;
        const whirl_shape_info *q = &e->eq[best].info;
        assert_true(fabs(q->tip_r - ref[k].tip_r) < (k < 3 ? 1.4e-15 : 1e-14 * ref[k].tip_r));
        assert_int_equal(q->n_nodes + 1, ref[k].nodes);
        assert_true(fabs(q->depth - ref[k].depth) < 1e-13 * ref[k].depth);
        assert_true(fabs(q->top_tension - ref[k].top_tension) < 1e-13 * ref[k].top_tension);
        assert_true(fabs(q->max_r - ref[k].max_r) < 1e-13 * ref[k].max_r);
    }
    whirl_equilibria_free(e);
    whirl_chain_free(c);
}

/* Kolodner: exactly n shapes for omega_n < omega < omega_{n+1}. */
static void test_kolodner(void **state)
{
    (void)state;
    const double tip_mass[2] = {0, 0.37};
    for (int t = 0; t < 2; t++) {
        double crit[8];
        for (int k = 1; k <= 7; k++)
            assert_int_equal(whirl_continuum_critical(k, tip_mass[t], &crit[k - 1]), GSL_SUCCESS);
        for (int n = 1; n <= 6; n++) {
            const double rates[2] = {crit[n - 1] * (1 + 1e-6), crit[n] * (1 - 1e-6)};
            for (int j = 0; j < 2; j++) {
                whirl_equilibria *e = find(NULL, tip_mass[t], rates[j], 0);
                assert_int_equal(e->count, n);
                assert_int_equal(e->born, n);
                assert_int_equal(e->tip_roots, n);
                assert_int_equal(e->matched, n);
                for (size_t i = 0; i < e->count; i++) {
                    /* increasing tip radius: mode n first */
                    assert_int_equal(e->eq[i].branch, n - (int)i);
                    assert_int_equal(e->eq[i].info.n_nodes, n - 1 - (int)i);
                    assert_true(isnan(e->eq[i].eig_growth));
                }
                whirl_equilibria_free(e);
            }
        }
    }
}

/* The pivot scan's derivative (forward differentiation) against central differences, and its
 * link angles against the tip shot of the same shape. */
static void test_pivot_derivative(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(9, 0.23);
    const double rates[3] = {2.385, 7.1, 15.3}, angles[3] = {1e-3, 0.41, 1.37};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double g, d, gp, gm, tip, h = 1e-5 * angles[j], theta[9];
            assert_int_equal(whirl_nlink_pivot_shot(c, rates[i], angles[j], &g, &d, &tip, theta,
                                                    NULL, NULL),
                             GSL_SUCCESS);
            /* central differences at h and h/2, extrapolated (error O(h^4)) */
            double fd2[2];
            for (int k = 0; k < 2; k++) {
                double hk = k ? h / 2 : h;
                whirl_nlink_pivot_shot(c, rates[i], angles[j] + hk, &gp, NULL, NULL, NULL,
                                       NULL, NULL);
                whirl_nlink_pivot_shot(c, rates[i], angles[j] - hk, &gm, NULL, NULL, NULL,
                                       NULL, NULL);
                fd2[k] = (gp - gm) / (2 * hk);
            }
            double fd = (4 * fd2[1] - fd2[0]) / 3;
            assert_true(fabs(fd - d) <= 1e-6 * (fabs(d) + fabs(g) / angles[j]));
            assert_true(fabs(theta[0] - angles[j]) <= 1e-15);
            double r = whirl_nlink_pivot_residual(c, rates[i], angles[j], &gp, NULL);
            assert_int_equal(r, GSL_SUCCESS);
            assert_true(gp == g);
        }
    whirl_chain_free(c);
}

/* The tip shot with the link angles' tangents: G and dG/da as whirl_nlink_residual (the
 * continuation's shot), the angles as the nodes of whirl_nlink_positions, the tangents'
 * derivatives against central differences; and the pivot shot's tangents against its angles. */
static void test_tip_slopes(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(9, 0.23);
    const double rates[3] = {2.385, 7.1, 15.3}, tips[3] = {1e-4, 0.137, 0.71};
    double sl[9], sl_a[9], sp[9], sm[9], dummy[9], r[10], z[10], t[10], theta[9], pd[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double g, g_a, g2, g2_a, gp, gpa, h = 1e-6 * tips[j];
            whirl_nlink_tip_shot(c, rates[i], tips[j], &g, &g_a, sl, sl_a);
            assert_int_equal(whirl_nlink_residual(c, rates[i], tips[j], &g2, NULL, &g2_a),
                             GSL_SUCCESS);
            assert_true(fabs(g - g2) <= 1e-14 && fabs(g_a - g2_a) <= 1e-12 * fabs(g2_a));
            assert_int_equal(whirl_nlink_positions(c, rates[i], tips[j], r, z, t), GSL_SUCCESS);
            whirl_nlink_tip_shot(c, rates[i], tips[j] + h, &gp, &gpa, sp, dummy);
            whirl_nlink_tip_shot(c, rates[i], tips[j] - h, &gp, &gpa, sm, dummy);
            for (int k = 0; k < 9; k++) {
                double angle = atan2(r[k + 1] - r[k], z[k] - z[k + 1]);
                assert_true(fabs(atan(sl[k]) - angle) <= 1e-13);
                double fd = (sp[k] - sm[k]) / (2 * h);
                assert_true(fabs(fd - sl_a[k]) <= 1e-6 * (fabs(sl_a[k]) + fabs(sl[k]) / tips[j]));
            }
            /* the pivot shot at this shape's top angle */
            double top = atan(sl[0]);
            whirl_nlink_pivot_shot(c, rates[i], top, &gp, NULL, NULL, theta, sp, pd);
            for (int k = 0; k < 9; k++) assert_true(fabs(atan(sp[k]) - theta[k]) <= 1e-14);
            double ht = 1e-7, spp[9], spm[9];
            whirl_nlink_pivot_shot(c, rates[i], top + ht, &gp, NULL, NULL, NULL, spp, dummy);
            whirl_nlink_pivot_shot(c, rates[i], top - ht, &gp, NULL, NULL, NULL, spm, dummy);
            for (int k = 0; k < 9; k++)
                assert_true(fabs((spp[k] - spm[k]) / (2 * ht) - pd[k]) <=
                            1e-6 * (fabs(pd[k]) + fabs(sp[k] / top)));
        }
    whirl_chain_free(c);
}

/* whirl_equilibria_find_progress: the result of whirl_equilibria_find, with (stage, done)
 * never decreasing over the stages and ending at the last stage's total; a stop requested from
 * the report (in the polishing of the roots) ends the search with WHIRL_EINTERRUPTED. */
typedef struct eq_calls {
    int calls, stage, stages, ordered, stop_stage;
    size_t done, total;
} eq_calls;

static void count_stages(void *ctx, const whirl_equilibria_progress *at)
{
    eq_calls *k = ctx;
    k->ordered &= at->stage > k->stage || (at->stage == k->stage && at->done >= k->done);
    k->ordered &= at->stage >= 1 && at->stage <= at->stages && at->done <= at->total;
    k->calls++;
    k->stage = at->stage;
    k->stages = at->stages;
    k->done = at->done;
    k->total = at->total;
    if (at->stage == k->stop_stage) whirl_stop_request();
}

static void test_progress(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    for (int model = 0; model < 2; model++) {
        const whirl_chain *chain = model ? c : NULL;
        const double omega = model ? 9.0 : 8.0;
        whirl_equilibria *plain = NULL, *reported = NULL;
        assert_int_equal(whirl_equilibria_find(chain, 0, omega, NULL, &plain), GSL_SUCCESS);
        eq_calls k = {0, 0, 0, 1, 0, 0, 0};
        assert_int_equal(whirl_equilibria_find_progress(chain, 0, omega, NULL, count_stages, &k,
                                                        &reported),
                         GSL_SUCCESS);
        assert_true(k.ordered && k.stages == (model ? 6 : 2) && k.stage == k.stages &&
                    k.done == k.total && k.calls > k.stages);
        assert_true(plain->count == reported->count && plain->count > 2);
        for (size_t i = 0; i < plain->count; i++) {
            const whirl_equilibrium *a = &plain->eq[i], *b = &reported->eq[i];
            assert_true(a->branch == b->branch && a->index == b->index &&
                        a->info.n_nodes == b->info.n_nodes);
            assert_memory_equal(&a->info.tip_r, &b->info.tip_r, sizeof a->info.tip_r);
            assert_memory_equal(&a->born_at, &b->born_at, sizeof a->born_at);
            assert_memory_equal(&a->eig_growth, &b->eig_growth, sizeof a->eig_growth);
        }
        whirl_equilibria_free(plain);
        whirl_equilibria_free(reported);
    }
    eq_calls stop = {0, 0, 0, 1, 3, 0, 0};
    whirl_equilibria *e = NULL;
    assert_int_equal(whirl_equilibria_find_progress(c, 0, 9.0, NULL, count_stages, &stop, &e),
                     WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_null(e);
    assert_true(stop.ordered && stop.stage == 3);
    whirl_chain_free(c);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_equilibria *e = (whirl_equilibria *)&e;
    assert_int_equal(whirl_equilibria_find(c, 0, 0, NULL, &e), GSL_EINVAL);
    assert_null(e);
    assert_int_equal(whirl_equilibria_find(c, 0, NAN, NULL, &e), GSL_EINVAL);
    assert_int_equal(whirl_equilibria_find(c, 0, 1001, NULL, &e), GSL_EINVAL);
    assert_int_equal(whirl_equilibria_find(NULL, 0, 51, NULL, &e), GSL_EINVAL);
    double crit[5];
    assert_int_equal(whirl_nlink_critical(c, 5, crit), GSL_SUCCESS);
    assert_int_equal(whirl_equilibria_find(c, 0, crit[2], NULL, &e), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "critical rate of mode 3"));
    double j02;
    assert_int_equal(whirl_continuum_critical(2, 0, &j02), GSL_SUCCESS);
    assert_int_equal(whirl_equilibria_find(NULL, 0, j02, NULL, &e), GSL_EDOM);
    whirl_equilibria_params p = whirl_equilibria_defaults();
    p.follow_factor = 1;
    assert_int_equal(whirl_equilibria_find(c, 0, 3, &p, &e), GSL_EINVAL);
    p = whirl_equilibria_defaults();
    p.shot_budget = 2000;
    assert_int_equal(whirl_equilibria_find(c, 0, 11.62, &p, &e), GSL_EMAXITER);
    assert_null(e);
    whirl_chain *big = whirl_chain_alloc_uniform(WHIRL_EQUILIBRIA_LINKS_MAX + 1, 0);
    assert_int_equal(whirl_equilibria_find(big, 0, 3, NULL, &e), GSL_EINVAL);
    whirl_chain_free(big);
    whirl_equilibria_free(NULL);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_five_links), cmocka_unit_test(test_fold_pairs),
        cmocka_unit_test(test_seven_links_cluster), cmocka_unit_test(test_high_rates),
        cmocka_unit_test(test_ten_links_high_rate), cmocka_unit_test(test_crowded_roots),
        cmocka_unit_test(test_kolodner),
        cmocka_unit_test(test_pivot_derivative), cmocka_unit_test(test_tip_slopes),
        cmocka_unit_test(test_progress), cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests_name("equilibria", tests, NULL, NULL);
}
