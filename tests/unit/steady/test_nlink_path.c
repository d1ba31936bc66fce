/* Tests of the N-link branches by pseudo-arclength continuation (src/nlink_path.c):
 * - critical rates of equal links and masses against sqrt(N x_k), x_k the zeros of the Laguerre
 *   polynomial L_N, computed here independently (Golub-Welsch: the eigenvalues of the Jacobi
 *   matrix of the three-term recurrence, GSL's symmetric eigensolver, polished by Newton's
 *   method on the recurrence), N = 5, 10, 25, 100, 200 (every mode, beyond the 64 of
 *   WHIRL_SHAPE_NODES);
 * - along a branch: the force balance of every mass at round-off, and continuity (no link angle
 *   changes by more than the step allows), on the N = 5 mode-4 branch up to omega = 45;
 * - near the birth the shape is the linear mode shape (the dense generalized eigenvector);
 * - a branch followed up and then back down retraces itself to 1e-10 and returns to the
 *   hanging chain at its birth rate;
 * - a fold located to 1e-10 in omega, checked by the pivot-end shooting (a second formulation):
 *   two equilibria just inside the fold, none just outside;
 * - every mode up to N, mode N just above omega_N;
 * - high rates, where the path goes over to the link angles (the tip shot loses digits there):
 *   N = 15 mode 7 to omega = 200, N = 100 mode 50 to omega = 300, every mode of N = 100 at
 *   twice omega_N, modes of N = 1000; at every accepted point the force across every link at
 *   round-off of the forces summed in it (computed here from the nodes), no link angle jump
 *   beyond what the step allows; a retrace up to omega = 200 and back to 1e-10 in the link
 *   angles;
 * - a tip mass of 1e12: the branch follows the sharp turn where the pinned string's symmetric
 *   branch splits (symmetric below it, asymmetric above, no branch point); a first point in the
 *   link angles where the shot cannot start a branch (a random chain's mode 9);
 * - branches that turn by a right angle within 5e-9 of arclength just below another mode's
 *   birth (random chains, lengths and masses over six decades): the link angles at ten times
 *   the birth against a 50-digit pseudo-arclength path in mpmath, no branch point on the way;
 * - the error paths; a branch that cannot be continued (a random chain of 10 links): the
 *   message names the mode, the rate the path reached and why;
 * - a middle mode of a long chain, which folds many times (N = 250 mode 80 to twice its birth):
 *   every fold that the same path with its steps capped to 0.003 finds, none passed over, at
 *   the same rates. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_sort_vector.h>

#include "steady/nlink_path_internal.h"
#include "whirl/steady.h"

/* The largest force imbalance of a mass, relative to the largest force on it, at (omega, tip_r);
 * the pivot must be on the axis to round-off. */
static double force_residual(const whirl_chain *c, double omega, double tip_r)
{
    size_t n = c->n;
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(r);
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r, r, z, t), GSL_SUCCESS);
    double worst = 0, w2 = omega * omega;
    for (size_t i = 1; i <= n; i++) {
        double m = c->mass[i - 1];
        double fr = m * w2 * r[i] - t[i] * (r[i] - r[i - 1]) / c->length[i - 1];
        double fz = -m * c->gravity - t[i] * (z[i] - z[i - 1]) / c->length[i - 1];
        if (i < n) {
            fr += t[i + 1] * (r[i + 1] - r[i]) / c->length[i];
            fz += t[i + 1] * (z[i + 1] - z[i]) / c->length[i];
        }
        /* relative to the largest force on the mass */
        double scale = fmax(t[i], m * fmax(c->gravity, w2 * fabs(r[i])));
        if (i < n) scale = fmax(scale, t[i + 1]);
        worst = fmax(worst, hypot(fr, fz) / scale);
    }
    /* the pivot on the axis to round-off: r_0 is a sum of N terms up to max |r| and moves with
     * the tip radius by a dr_0/da per unit relative change (a shot from the tip can be very
     * sensitive: a zigzag at a high rate), so |r_0| <~ 8 eps (a |dr_0/da| + N max |r|) */
    double r0 = r[0], h = 1e-6 * tip_r, plus, minus, r_max = 0;
    for (size_t i = 1; i <= n; i++) r_max = fmax(r_max, fabs(r[i]));
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r + h, r, z, t), GSL_SUCCESS);
    plus = r[0];
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r - h, r, z, t), GSL_SUCCESS);
    minus = r[0];
    double floor = 8 * DBL_EPSILON * (tip_r * fabs(plus - minus) / (2 * h) + (double)n * r_max);
    if (!(fabs(r0) <= floor)) print_message("omega %.17g tip %.17g: r0 %.3e floor %.3e\n", omega, tip_r, r0, floor);
    assert_true(fabs(r0) <= floor);
    free(r);
    return worst;
}

/* Link angles at (omega, tip_r). */
static void link_angles(const whirl_chain *c, double omega, double tip_r, double *theta)
{
    size_t n = c->n;
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(r);
    assert_int_equal(whirl_nlink_positions(c, omega, tip_r, r, z, t), GSL_SUCCESS);
    for (size_t i = 1; i <= n; i++) theta[i - 1] = atan2(r[i] - r[i - 1], z[i - 1] - z[i]);
    free(r);
}

/* The force across link i (the component of the resultant of the forces on the masses below it
 * perpendicular to the link: zero at an equilibrium) for the shape with link angles theta, the
 * nodes built from the pivot; the largest over the links relative to the forces summed in it
 * (V_i + omega^2 sum_{j >= i} m_j |r_j|, the scale of its round-off), and relative to the total
 * weight in *per_weight. */
static double angle_residual(const whirl_chain *c, double omega, const double *theta,
                             double *per_weight)
{
    /* in long double, so that the measure's own round-off stays below that of the angles */
    size_t n = c->n;
    long double *r = malloc((n + 1) * sizeof *r), h = 0, v = 0, sum = 0, weight = 0;
    long double w2 = (long double)omega * omega, worst = 0, pw = 0;
    assert_non_null(r);
    r[0] = 0;
    for (size_t i = 1; i <= n; i++) r[i] = r[i - 1] + c->length[i - 1] * sinl(theta[i - 1]);
    for (size_t i = 0; i < n; i++) weight += c->mass[i] * c->gravity;
    for (size_t i = n; i >= 1; i--) {
        long double m = c->mass[i - 1], load = m * w2 * r[i];
        h += load;
        v += m * c->gravity;
        sum += fabsl(load);
        long double across = fabsl(h * cosl(theta[i - 1]) - v * sinl(theta[i - 1]));
        worst = fmaxl(worst, across / (v + sum));
        pw = fmaxl(pw, across / weight);
    }
    free(r);
    *per_weight = (double)pw;
    return (double)worst;
}

/* The same for nodes r, z (pivot first): the link angles from the nodes. */
static double node_residual(const whirl_chain *c, double omega, const double *r, const double *z,
                            double *per_weight)
{
    size_t n = c->n;
    double *theta = malloc(n * sizeof *theta);
    assert_non_null(theta);
    for (size_t i = 1; i <= n; i++) theta[i - 1] = atan2(r[i] - r[i - 1], z[i - 1] - z[i]);
    double worst = angle_residual(c, omega, theta, per_weight);
    free(theta);
    return worst;
}

/* L_N(x) and L_{N-1}(x) by the recurrence (k+1) L_{k+1} = (2k+1-x) L_k - k L_{k-1}, both scaled
 * by the same factor (kept below 1e100); the largest |L_k| seen, with the same scaling, in
 * *scale. */
static void laguerre_pair(size_t n, double x, double *ln, double *ln1, double *scale)
{
    double l0 = 1, l1 = 1 - x;
    *scale = 1 + x;
    for (size_t m = 1; m < n; m++) {
        double l2 = ((2.0 * (double)m + 1 - x) * l1 - (double)m * l0) / ((double)m + 1);
        l0 = l1;
        l1 = l2;
        double big = fmax(fabs(l0), fabs(l1));
        if (big > 1e100) l0 /= big, l1 /= big, *scale /= big;
        *scale = fmax(*scale, fabs(l1));
    }
    *ln = l1;
    *ln1 = l0;
}

/* The round-off floor of angle_residual at link angles theta: its largest value over three
 * copies of theta with each angle moved by -1, 0 or +1 unit in the last place (a fixed
 * pseudo-random pattern). An equilibrium found to round-off scores no more than a few times it. */
static double ulp_floor(const whirl_chain *c, double omega, const double *theta)
{
    size_t n = c->n;
    double *moved = malloc(n * sizeof *moved), floor = 0, per_weight;
    unsigned state = 12345;
    assert_non_null(moved);
    for (int trial = 0; trial < 3; trial++) {
        for (size_t i = 0; i < n; i++) {
            state = state * 1103515245u + 12345u;
            moved[i] = theta[i] * (1 + DBL_EPSILON * (double)((int)((state >> 16) % 3) - 1));
        }
        floor = fmax(floor, angle_residual(c, omega, moved, &per_weight));
    }
    free(moved);
    return floor;
}

/* Zeros of L_N by Golub-Welsch (the Jacobi matrix has diagonal 2k + 1 and off-diagonal k; GSL's
 * symmetric eigensolver), each polished by Newton's method on the recurrence (x L_N' = N (L_N -
 * L_{N-1})): the eigenvalues carry an absolute error of eps times the matrix norm (4 N), too
 * much for the smallest zeros (~1.4 / N) at N = 200. */
static void laguerre_zeros(size_t n, double *x)
{
    gsl_matrix *j = gsl_matrix_calloc(n, n);
    gsl_vector *eval = gsl_vector_alloc(n);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc(n);
    for (size_t k = 0; k < n; k++) {
        gsl_matrix_set(j, k, k, 2.0 * (double)k + 1);
        if (k + 1 < n) {
            gsl_matrix_set(j, k, k + 1, (double)k + 1);
            gsl_matrix_set(j, k + 1, k, (double)k + 1);
        }
    }
    assert_int_equal(gsl_eigen_symm(j, eval, w), GSL_SUCCESS);
    gsl_sort_vector(eval);
    for (size_t k = 0; k < n; k++) {
        x[k] = gsl_vector_get(eval, k);
        double ln, ln1, scale;
        for (int it = 0; it < 4; it++) {
            laguerre_pair(n, x[k], &ln, &ln1, &scale);
            x[k] -= x[k] * ln / ((double)n * (ln - ln1));
        }
        /* a zero of L_N, and still the k-th: between its neighbours' eigenvalues */
        laguerre_pair(n, x[k], &ln, &ln1, &scale);
        assert_true(fabs(ln) <= 1e-8 * scale);
        if (k > 0) assert_true(x[k] > gsl_vector_get(eval, k - 1));
        if (k + 1 < n) assert_true(x[k] < gsl_vector_get(eval, k + 1));
    }
    gsl_eigen_symm_free(w);
    gsl_vector_free(eval);
    gsl_matrix_free(j);
}

static void test_critical_laguerre(void **state)
{
    (void)state;
    const size_t sizes[] = {5, 10, 25, 100, 200};
    for (size_t s = 0; s < 5; s++) {
        size_t n = sizes[s];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *crit = malloc(n * sizeof *crit), *x = malloc(n * sizeof *x);
        assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
        laguerre_zeros(n, x);
        double worst = 0;
        for (size_t k = 0; k < n; k++)
            worst = fmax(worst, fabs(crit[k] / sqrt((double)n * x[k]) - 1));
        print_message("N = %zu: critical rates vs sqrt(N x_k): %.2e\n", n, worst);
        assert_true(worst < 1e-12);
        /* the birth of every mode is polished on the shot itself, to the same rates */
        whirl_nlink_path *p = whirl_nlink_path_alloc(c);
        assert_non_null(p);
        for (size_t k = 0; k < n; k += n / 5) {
            assert_int_equal(whirl_nlink_path_birth(p, (int)k + 1), GSL_SUCCESS);
            assert_float_equal(p->omega_birth, sqrt((double)n * x[k]), 1e-12 * p->omega_birth);
        }
        whirl_nlink_path_free(p);
        free(crit);
        free(x);
        whirl_chain_free(c);
    }
}

/* The N = 5 mode-4 branch to omega = 45: continuous, every point an equilibrium. */
static void test_branch_continuous(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 4), GSL_SUCCESS);
    double th0[5], th1[5], worst = 0, jump = 0, per_weight;
    for (int i = 0; i < 5; i++) th0[i] = whirl_nlink_path_theta(p)[i];
    while (p->omega < 45) {
        double ds = p->ds;
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        worst = fmax(worst, angle_residual(c, p->omega, whirl_nlink_path_theta(p), &per_weight));
        for (int i = 0; i < 5; i++) th1[i] = whirl_nlink_path_theta(p)[i];
        for (int i = 0; i < 5; i++) {
            jump = fmax(jump, fabs(th1[i] - th0[i]) / ds);
            th0[i] = th1[i];
        }
        assert_true(p->steps < 5000);
    }
    print_message("N = 5 mode 4 to omega = 45: %ld steps, worst force residual %.2e, "
                  "largest link-angle change per unit step %.2f\n", p->steps, worst, jump);
    assert_true(worst < 1e-13);
    /* a link angle changes by at most ~sqrt(N) times the step's rms change */
    assert_true(jump < 2.5);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* Near the birth the shape is the linear mode: the eigenvector of K x = w^2 M x. */
static void test_birth_linear_shape(void **state)
{
    (void)state;
    const size_t n = 12;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0.37);
    gsl_matrix *k = gsl_matrix_calloc(n, n), *mm = gsl_matrix_calloc(n, n), *ev;
    gsl_vector *eval = gsl_vector_alloc(n);
    ev = gsl_matrix_alloc(n, n);
    gsl_eigen_gensymmv_workspace *w = gsl_eigen_gensymmv_alloc(n);
    for (size_t i = 0; i < n; i++) {
        double t = 0;
        for (size_t j = i; j < n; j++) t += c->mass[j] * c->gravity;
        double s = t / c->length[i];
        *gsl_matrix_ptr(k, i, i) += s;
        if (i > 0) {
            *gsl_matrix_ptr(k, i - 1, i - 1) += s;
            *gsl_matrix_ptr(k, i - 1, i) -= s;
            *gsl_matrix_ptr(k, i, i - 1) -= s;
        }
        gsl_matrix_set(mm, i, i, c->mass[i]);
    }
    assert_int_equal(gsl_eigen_gensymmv(k, mm, eval, ev, w), GSL_SUCCESS);
    gsl_eigen_gensymmv_sort(eval, ev, GSL_EIGEN_SORT_VAL_ASC);
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    for (size_t mode = 1; mode <= n; mode++) {
        double omega_k = sqrt(gsl_vector_get(eval, mode - 1)), dev[2];
        const double eps[2] = {1e-6, 1e-8};
        for (int e = 0; e < 2; e++) {
            double omega = omega_k * (1 + eps[e]);
            whirl_shape_info info;
            assert_int_equal(whirl_nlink_solve(c, omega, (int)mode, &info), GSL_SUCCESS);
            assert_int_equal(info.n_nodes, (int)mode - 1);
            assert_int_equal(whirl_nlink_positions(c, omega, info.tip_r, r, z, t), GSL_SUCCESS);
            /* both normalised to their tip value */
            double tip_v = gsl_matrix_get(ev, n - 1, mode - 1), big = 0;
            dev[e] = 0;
            for (size_t i = 1; i <= n; i++) {
                double lin = gsl_matrix_get(ev, i - 1, mode - 1) / tip_v;
                dev[e] = fmax(dev[e], fabs(r[i] / r[n] - lin));
                big = fmax(big, fabs(lin));
            }
            dev[e] /= big;
        }
        /* the departure from the linear shape is of order omega / omega_k - 1 (and of the
         * squared amplitude, which is of that order too) */
        print_message("mode %zu: shape vs linear mode %.2e (eps 1e-6), %.2e (eps 1e-8)\n", mode,
                      dev[0], dev[1]);
        assert_true(dev[1] < 1e-5 * 1e-2 * 10);
        assert_true(dev[0] / dev[1] > 50 && dev[0] / dev[1] < 200);
    }
    free(r);
    gsl_eigen_gensymmv_free(w);
    gsl_matrix_free(k);
    gsl_matrix_free(mm);
    gsl_matrix_free(ev);
    gsl_vector_free(eval);
    whirl_chain_free(c);
}

/* Up to omega_top and back: the same points at the same rates, back to the birth. */
static void test_retrace(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(10, 0);
    enum { nr = 9 };
    double rates[nr], up[nr], down[nr];
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 3), GSL_SUCCESS);
    const double birth = p->omega_birth;
    for (int j = 0; j < nr; j++) rates[j] = birth + 0.013 + 1.7 * j, up[j] = down[j] = NAN;
    while (p->omega < 20) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int j = 0; j < nr; j++) {
            double a;
            int found = whirl_nlink_path_crossings(p, rates[j], 1, &a);
            assert_true(found >= 0);
            if (found) up[j] = a;
        }
    }
    whirl_nlink_path_reverse(p);
    while (!p->ended) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int j = 0; j < nr; j++) {
            double a;
            int found = whirl_nlink_path_crossings(p, rates[j], 1, &a);
            assert_true(found >= 0);
            if (found) down[j] = a;
        }
        assert_true(p->steps < 10000);
    }
    double worst = 0;
    for (int j = 0; j < nr; j++) {
        assert_true(isfinite(up[j]) && isfinite(down[j]));
        worst = fmax(worst, fabs(up[j] - down[j]) / up[j]);
    }
    /* the last event: the return to the hanging chain at the birth rate */
    assert_int_equal(p->event[p->n_events - 1].kind, WHIRL_EVENT_RETURN);
    double back = p->event[p->n_events - 1].omega;
    print_message("retrace N = 10 mode 3 to omega = 20 and back: tip radii agree to %.2e, "
                  "return at %.17g (birth %.17g)\n", worst, back, birth);
    assert_true(worst < 1e-10);
    assert_float_equal(back, birth, 1e-10 * birth);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* Sign changes of the pivot-end residual for theta_1 in [lo, hi] on m + 1 points. */
static int pivot_sign_changes(const whirl_chain *c, double omega, double lo, double hi, int m)
{
    int count = 0;
    double prev = 0;
    for (int i = 0; i <= m; i++) {
        double res, th = lo + (hi - lo) * i / m;
        assert_int_equal(whirl_nlink_pivot_residual(c, omega, th, &res, NULL), GSL_SUCCESS);
        if (i > 0 && (res > 0) != (prev > 0)) count++;
        prev = res;
    }
    return count;
}

/* The N = 7 mode-4 branch turns back twice (an S): both folds located to 1e-10. */
static void test_folds(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(7, 0);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 4), GSL_SUCCESS);
    whirl_branch_event folds[2];
    int nf = 0;
    while (p->omega < 12) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int e = 0; e < p->n_events; e++) {
            assert_int_equal(p->event[e].kind, WHIRL_EVENT_FOLD);
            assert_true(nf < 2);
            folds[nf++] = p->event[e];
        }
    }
    assert_int_equal(nf, 2);
    double theta[7];
    for (int f = 0; f < 2; f++) {
        const whirl_branch_event *e = &folds[f];
        print_message("fold at omega = %.15f, tip radius %.6e\n", e->omega, e->tip_r);
        assert_true(force_residual(c, e->omega, e->tip_r) < 1e-13);
        link_angles(c, e->omega, e->tip_r, theta);
        /* pivot shooting: two equilibria near the fold on one side, none on the other */
        double d = 1e-10 * e->omega, h = 2e-3;
        int below = pivot_sign_changes(c, e->omega - d, theta[0] - h, theta[0] + h, 40000);
        int above = pivot_sign_changes(c, e->omega + d, theta[0] - h, theta[0] + h, 40000);
        print_message("  omega_f -+ 1e-10 omega_f: %d and %d equilibria nearby\n", below, above);
        assert_true((below == 2 && above == 0) || (below == 0 && above == 2));
        assert_true(f == 0 ? below == 2 : above == 2); /* a maximum, then a minimum */
    }
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* The node count's tail rule (whirl_nlink_node_arclengths) applied from mass b of a shape r whose
 * radii are all resolved: r with the radii of masses b+1..N set to zero against r as it is. The
 * counts must be equal; returns the largest difference of a node's arclength [L]. */
static double tail_rule_from(const whirl_chain *c, double omega, const double *r, size_t b)
{
    const size_t n = c->n;
    double *cut = malloc((n + 1 + 2 * n) * sizeof *cut), *direct = cut + n + 1, *tail = direct + n;
    assert_non_null(cut);
    for (size_t i = 0; i <= n; i++) cut[i] = i <= b ? r[i] : 0;
    size_t resolved_direct = 0, resolved_tail = 0;
    const size_t count = whirl_nlink_node_arclengths(c, omega, r, n, direct, &resolved_direct);
    assert_true(b >= 1 && b < resolved_direct);
    assert_int_equal(whirl_nlink_node_arclengths(c, omega, cut, n, tail, &resolved_tail), count);
    assert_int_equal(resolved_tail, b);
    double worst = 0;
    for (size_t j = 0; j < count; j++) worst = fmax(worst, fabs(tail[j] - direct[j]));
    free(cut);
    return worst;
}

/* Modes 1..N at and above their birth, mode N just above omega_N: every mode of N = 15 and 25,
 * and of N = 200 a sample of the modes beyond 64 (WHIRL_SHAPE_NODES: the summary holds the first
 * 64 nodes, whirl_nlink_node_arclengths lists them all). */
static void test_every_mode(void **state)
{
    (void)state;
    const size_t sizes[] = {15, 25, 200, 300};
    const size_t sample[] = {1, 64, 65, 66, 100, 133, 150, 167, 199, 200}, top[] = {299, 300};
    for (size_t s = 0; s < 4; s++) {
        size_t n = sizes[s];
        const size_t count = n == 200 ? sizeof sample / sizeof *sample : n == 300 ? 2 : n;
        whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
        double *crit = malloc(n * sizeof *crit), *node_s = malloc(n * sizeof *node_s);
        double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
        assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
        const double factors[] = {1 + 1e-9, 1 + 1e-4, 1.2};
        double worst = 0, tail_small = 0, tail_300 = 0;
        for (size_t i = 0; i < count; i++)
            for (int f = 0; f < 3; f++) {
                const size_t k = n == 200 ? sample[i] : n == 300 ? top[i] : i + 1;
                whirl_shape_info info;
                double omega = crit[k - 1] * factors[f], per_weight;
                int status = whirl_nlink_solve_nodes(c, omega, (int)k, &info, r, z, t);
                if (status) print_message("N %zu mode %zu: %s\n", n, k, whirl_last_error());
                assert_int_equal(status, GSL_SUCCESS);
                assert_int_equal(info.mode, (int)k);
                /* the tip of mode 300 of 300 at 1.2 times its birth, below 1e-308 of the
                 * largest radius, underflows to zero */
                assert_true(info.tip_r > 0 || (n == 300 && info.tip_r == 0 && r[n - 1] != 0));
                assert_true(r[n] >= 0 && fabs(r[0]) <= 1e-13 * info.max_r);
                double res = node_residual(c, omega, r, z, &per_weight);
                worst = fmax(worst, res);
                /* at round-off: N = 15, 25 below 1e-13; N = 200, whose floor grows with the
                 * rate (1e-12 to 1e-11), within 4 times that of its angles moved by an ulp */
                double bound = 1e-13;
                if (n > 25) {
                    for (size_t j = 1; j <= n; j++)
                        node_s[j - 1] = atan2(r[j] - r[j - 1], z[j - 1] - z[j]);
                    bound = 4 * ulp_floor(c, omega, node_s);
                }
                if (!(res < bound))
                    print_message("N %zu mode %zu at %.17g: force across a link %.3e\n", n, k,
                                  omega, res);
                assert_true(res < bound);
                /* the node count is the mode's near the birth; on N = 300, whose top modes
                 * decay to 1e-251 of their largest radius towards the tip (the linear mode
                 * shape's tail, computed with 1200 digits), at all three rates: every sign of
                 * that tail resolved (the first point of the branch from the linear mode shape
                 * with the relative accuracy of each link angle; it was 257 for mode 300 at
                 * 1 + 1e-9, from inverse iteration) */
                if (f == 0 || n == 300) assert_int_equal(info.n_nodes, (int)k - 1);
                /* every node listed, increasing along the chain; the summary's first ones */
                const size_t nodes = whirl_nlink_node_arclengths(c, omega, r, n, node_s, NULL);
                assert_int_equal(nodes, info.n_nodes);
                for (size_t j = 0; j < nodes; j++) {
                    assert_true(node_s[j] > (j ? node_s[j - 1] : 0) && node_s[j] < 1);
                    if (j < WHIRL_SHAPE_NODES) assert_true(node_s[j] == info.node_s[j]);
                }
                /* the tail rule of the count from an earlier mass than where radii underflow:
                 * on N = 15, 25 at 1 + 1e-9 times the birth (linear to about 1e-9) from every
                 * mass; on N = 300 from every 25th mass below the first whose radius is below
                 * 1e-20 of the largest */
                if (n <= 25 && f == 0)
                    for (size_t b = 1; b < n; b++)
                        tail_small = fmax(tail_small, tail_rule_from(c, omega, r, b));
                if (n == 300) {
                    size_t b = 1, resolved = 0;
                    while (fabs(r[b]) >= 1e-20 * info.max_r) b++;
                    whirl_nlink_node_arclengths(c, omega, r, 0, NULL, &resolved);
                    assert_true(b + 25 < resolved);
                    for (; b < resolved; b += 25)
                        tail_300 = fmax(tail_300, tail_rule_from(c, omega, r, b));
                }
            }
        print_message("N = %zu, modes %s at 1 + 1e-9, 1 + 1e-4 and 1.2 times their birth: "
                      "worst force across a link %.2e of the forces summed in it\n", n,
                      n == 200 ? "1, 64..66, 100, 133, 150, 167, 199, 200"
                               : n == 300 ? "299, 300" : "1..N", worst);
        /* the nodes move by the shape's departure from linear, proportional to omega / omega_k
         * - 1 (1.6e-4 and 1.9e-4 at 1 + 1e-4 on N = 15, 25); on N = 300 by round-off */
        if (n <= 25 || n == 300)
            print_message("  the count's tail rule from earlier masses: nodes moved by %.3g\n",
                          n <= 25 ? tail_small : tail_300);
        assert_true(tail_small < 4e-9 && tail_300 < 1e-15);
        /* the case: mode 15 of 15 at 26.85 (omega_15 = 26.8401) */
        if (n == 15) {
            whirl_shape_info info;
            assert_int_equal(whirl_nlink_solve(c, 26.85, 15, &info), GSL_SUCCESS);
            assert_int_equal(info.n_nodes, 14);
        }
        /* beyond N and below the birth: GSL_EDOM, the message naming the mode */
        if (n == 200) {
            whirl_shape_info info;
            assert_int_equal(whirl_nlink_solve(c, 1000, 201, &info), GSL_EDOM);
            assert_non_null(strstr(whirl_last_error(), "mode 201"));
            assert_int_equal(whirl_nlink_solve(c, crit[149] * (1 - 1e-6), 150, &info),
                             GSL_EDOM);
            assert_non_null(strstr(whirl_last_error(), "mode 150"));
        }
        free(r);
        free(node_s);
        free(crit);
        whirl_chain_free(c);
    }
}

/* The top modes of N = 1000 at 1 + 1e-9 times their birth, below the first point of the path,
 * which starts in the link angles at an amplitude of 1e-5 rad (1 + 1.66e-9 and 1 + 1.16e-9
 * times the birth of modes 1000 and 999): the point there with the amplitude whose rate is
 * omega (a secant method in the amplitude squared). Balanced to round-off, the pivot on the axis; mode 1000's radii alternate in sign
 * from mass to mass wherever they do not underflow (its tail decays below 1e-308 of the largest
 * radius). They were "not resolved" before. */
static void test_birth_gap(void **state)
{
    (void)state;
    const size_t n = 1000;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *crit = malloc(n * sizeof *crit), *theta = malloc(n * sizeof *theta);
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
    for (int k = 999; k <= 1000; k++) {
        whirl_shape_info info;
        const double omega = crit[k - 1] * (1 + 1e-9);
        int status = whirl_nlink_solve_nodes(c, omega, k, &info, r, z, t);
        if (status) print_message("N 1000 mode %d: %s\n", k, whirl_last_error());
        assert_int_equal(status, GSL_SUCCESS);
        assert_int_equal(info.mode, k);
        assert_true(info.omega == omega && fabs(r[0]) <= 1e-13 * info.max_r);
        double per_weight, res = node_residual(c, omega, r, z, &per_weight);
        for (size_t j = 1; j <= n; j++) theta[j - 1] = atan2(r[j] - r[j - 1], z[j - 1] - z[j]);
        const double bound = 4 * ulp_floor(c, omega, theta);
        print_message("N = 1000 mode %d at 1 + 1e-9 times its birth: largest radius %.3g, force "
                      "across a link %.3g of the forces summed in it (bound %.3g), %d nodes\n",
                      k, info.max_r, res, bound, info.n_nodes);
        assert_true(res < bound);
        if (k == 1000) {
            size_t resolved = 0;
            while (resolved < n && r[resolved + 1] != 0) resolved++;
            for (size_t j = resolved + 1; j <= n; j++) assert_true(r[j] == 0);
            for (size_t j = 1; j < resolved; j++) assert_true((r[j] > 0) != (r[j + 1] > 0));
            assert_true(resolved > 500 && resolved < n);
        }
        /* every node counted, those of the underflowed tail from the linearised balance (the
         * count stopped at the last radius not zero before: 612 crossings for mode 1000); mode
         * 1000 has 999 in a 60-digit tip shot at this rate, as in test_underflowed_tail */
        assert_int_equal(info.n_nodes, k - 1);
    }
    free(r);
    free(theta);
    free(crit);
    whirl_chain_free(c);
}

/* The top modes of N = 500 at 1 + 1e-4 and 1.2 times their birth, whose radii decay below the
 * smallest normal double from about mass 440 and 365 on (to 1e-424 and 1e-540 of the largest):
 * every node counted, those of the tail from the force balance linearised about the hanging chain
 * (src/nlink.c). References: the nonlinear tip shot r_{i-1} = r_i - l_i H_i / T_i of the same
 * chain at the same (double) omega in mpmath 1.2.1 (60 digits), its tip radius (6.27e-543 for
 * mode 500 at 1.2) rooted by the secant method on the pivot radius to 1e-59 of the largest: its
 * radii agree with whirl's normal ones to 2e-12, it has k - 1 sign changes, and its nodes,
 * interpolated linearly between masses, agree with all of whirl's to 7.2e-16. Listed: nodes 100,
 * 400 (in the tail) and the last. The count stopped at 375 crossings (mode 500 at 1.2) before. */
static void test_underflowed_tail(void **state)
{
    (void)state;
    const size_t n = 500;
    static const struct {
        int mode;
        double factor, omega, node[3];
    } ref[] = {
        {500, 1.2, 1186.557142904438,
         {0.20165733672980802761, 0.80192628325970455898, 0.99999928973128822748}},
        {500, 1 + 1e-4, 988.8964988489404,
         {0.20142767650193844758, 0.8018919644647541478, 0.99999897741758175704}},
        {499, 1.2, 1176.0258703846473,
         {0.20365063737314692417, 0.80392568496403808023, 0.99999927695346542603}},
        {499, 1 + 1e-4, 980.1195608097381,
         {0.20341272357915144782, 0.80389107039115595715, 0.99999895902119638399}},
    };
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *crit = malloc(n * sizeof *crit), *node_s = malloc(n * sizeof *node_s);
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(crit);
    assert_non_null(node_s);
    assert_non_null(r);
    assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
    double worst = 0;
    for (size_t i = 0; i < sizeof ref / sizeof *ref; i++) {
        const int k = ref[i].mode;
        const double omega = ref[i].omega;
        assert_true(fabs(omega / (crit[k - 1] * ref[i].factor) - 1) < 1e-15);
        whirl_shape_info info;
        int status = whirl_nlink_solve_nodes(c, omega, k, &info, r, z, t);
        if (status) print_message("N 500 mode %d: %s\n", k, whirl_last_error());
        assert_int_equal(status, GSL_SUCCESS);
        size_t resolved = 0;
        const size_t count = whirl_nlink_node_arclengths(c, omega, r, n, node_s, &resolved);
        assert_true(resolved > 300 && resolved < 450 && r[n] == 0);
        assert_int_equal(info.n_nodes, k - 1);
        assert_int_equal(count, k - 1);
        for (size_t j = 0; j < count; j++) {
            assert_true(node_s[j] > (j ? node_s[j - 1] : 0) && node_s[j] < 1);
            if (j < WHIRL_SHAPE_NODES) assert_true(node_s[j] == info.node_s[j]);
        }
        const size_t at[3] = {99, 399, count - 1};
        for (int j = 0; j < 3; j++) worst = fmax(worst, fabs(node_s[at[j]] - ref[i].node[j]));
    }
    print_message("N = 500, modes 499, 500 at 1 + 1e-4 and 1.2 times their birth: k - 1 nodes, "
                  "nodes 100, 400 and the last within %.2g of a 60-digit shot\n", worst);
    assert_true(worst < 2e-15);
    free(r);
    free(node_s);
    free(crit);
    whirl_chain_free(c);
}

/* The branch at several rates (whirl_nlink_branch, as sweep and stability use it) reaches the
 * rates between the birth and the first point of a path begun in the link angles, as the
 * single-rate solve does: N = 100, mode 100 at 1 + 1e-12 of its birth was left out before. The
 * shapes are the solve's, bit for bit, and the largest radius follows the pitchfork's square
 * root law, max_r ~ sqrt(omega - omega_k): between 1e-9 and 1e-6 to 1e-5 (the next order, and
 * the birth rate's round-off over 1e-9), and from 1e-12 to 1e-9 to 1e-3 (half an ulp of the
 * birth rate is 5e-5 of omega - omega_k at 1e-12). */
static void test_branch_birth_gap(void **state)
{
    (void)state;
    const size_t n = 100;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double crit[100];
    assert_int_equal(whirl_nlink_critical(c, n, crit), GSL_SUCCESS);
    for (int k = 99; k <= 100; k++) {
        const double f[3] = {1e-12, 1e-9, 1e-6};
        double omega[3];
        whirl_shape_info info[3], one;
        int exists[3];
        for (int j = 0; j < 3; j++) omega[j] = crit[k - 1] * (1 + f[j]);
        assert_int_equal(whirl_nlink_branch(c, k, 3, omega, info, exists), GSL_SUCCESS);
        for (int j = 0; j < 3; j++) {
            assert_true(exists[j]);
            assert_int_equal(whirl_nlink_solve(c, omega[j], k, &one), GSL_SUCCESS);
            assert_true(info[j].omega == omega[j] && info[j].tip_r == one.tip_r &&
                        info[j].max_r == one.max_r && info[j].n_nodes == one.n_nodes);
        }
        const double law = info[1].max_r / info[2].max_r / sqrt(1e-3);
        const double law_12 = info[0].max_r / info[1].max_r / sqrt(1e-3);
        print_message("N = 100 mode %d: max_r %.4g, %.4g, %.4g at 1 + 1e-12, 1e-9, 1e-6 of the "
                      "birth; their ratios over sqrt(1e-3), %.8f and %.8f\n", k, info[0].max_r,
                      info[1].max_r, info[2].max_r, law_12, law);
        assert_true(fabs(law - 1) < 1e-5 && fabs(law_12 - 1) < 1e-3);
    }
    whirl_chain_free(c);
}

/* Mode k of c from its birth until the path first crosses omega_top: at every accepted point
 * the force across the links (angle_residual, relative to the forces summed in a link and to
 * the weight), the largest change of a link angle per unit step, the steps made in the link
 * angles; the crossing's link angles into theta_top (if not NULL). */
typedef struct high_run {
    double worst, per_weight, jump, omega_reached;
    double per_ulp; /* the force across a link against ulp_floor, the largest ratio */
    long steps, angle_steps;
} high_run;

static void follow_high(const whirl_chain *c, int mode, double omega_top, double *theta_top,
                        high_run *h)
{
    size_t n = c->n;
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_non_null(p);
    assert_int_equal(whirl_nlink_path_birth(p, mode), GSL_SUCCESS);
    double *prev = malloc(n * sizeof *prev), pw;
    assert_non_null(prev);
    for (size_t i = 0; i < n; i++) prev[i] = whirl_nlink_path_theta(p)[i];
    memset(h, 0, sizeof *h);
    int found = 0;
    while (!found) {
        double ds = p->ds;
        int status = whirl_nlink_path_step(p);
        if (status) print_message("N %zu mode %d: %s\n", n, mode, whirl_last_error());
        assert_int_equal(status, GSL_SUCCESS);
        assert_false(p->ended);
        h->worst = fmax(h->worst, angle_residual(c, p->omega, whirl_nlink_path_theta(p), &pw));
        h->per_weight = fmax(h->per_weight, pw);
        h->per_ulp = fmax(h->per_ulp, angle_residual(c, p->omega, whirl_nlink_path_theta(p), &pw) /
                                          ulp_floor(c, p->omega, whirl_nlink_path_theta(p)));
        for (size_t i = 0; i < n; i++) {
            h->jump = fmax(h->jump, fabs(whirl_nlink_path_theta(p)[i] - prev[i]) / ds);
            prev[i] = whirl_nlink_path_theta(p)[i];
        }
        h->angle_steps += p->angles;
        double a;
        found = whirl_nlink_path_crossings(p, omega_top, 1, &a);
        assert_true(found >= 0);
        assert_true(p->steps < 20000);
    }
    if (theta_top)
        for (size_t i = 0; i < n; i++) theta_top[i] = whirl_nlink_path_cross_theta(p)[i];
    h->steps = p->steps;
    h->omega_reached = p->omega;
    free(prev);
    whirl_nlink_path_free(p);
}

/* The checks of a high run: the force balance at round-off of the forces summed in each link
 * at every point (the floor of the balance in double at these rates grows with N: 5e-13 for
 * N = 15 at omega = 157, 1e-12 for N = 100 at 300, and one more Newton iteration on the link
 * angles does not lower it; bound: 200 N eps), no link angle changing by more than the metric allows (ds^2 >= |d theta|^2 /
 * N, so |d theta_i| <= sqrt(N) ds up to the chord's excess over the arc). */
static void check_high(const whirl_chain *c, int mode, double omega_top, const high_run *h)
{
    print_message("N = %zu mode %d to omega = %g: %ld steps (%ld in the link angles), force "
                  "across a link <= %.2e of the forces summed in it (%.2e of the weight), link "
                  "angle change per unit step <= %.2f (sqrt(N) = %.2f)\n", c->n, mode, omega_top,
                  h->steps, h->angle_steps, h->worst, h->per_weight, h->jump, sqrt((double)c->n));
    assert_true(h->worst < 200 * (double)c->n * DBL_EPSILON);
    assert_true(h->jump <= 1.05 * sqrt((double)c->n));
}

/* High rates: the tip shot loses digits (N = 15 mode 7 stopped at omega = 40.1, N = 100 mode 50
 * at 100.2 before the link angles); the path goes on in the link angles. */
static void test_high_rates(void **state)
{
    (void)state;
    high_run h;
    whirl_chain *c15 = whirl_chain_alloc_uniform(15, 0);
    double theta[100], r[101], z[101], t[101];
    follow_high(c15, 7, 200, theta, &h);
    check_high(c15, 7, 200, &h);
    assert_true(h.angle_steps > 0);
    /* the shape from whirl_nlink_solve_nodes at 200: the pivot on the axis, 7 nodes, the same
     * link angles as the path's crossing */
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve_nodes(c15, 200, 7, &info, r, z, t), GSL_SUCCESS);
    assert_true(r[0] == 0 && info.tip_r > 0);
    assert_int_equal(info.n_nodes, 6);
    for (size_t i = 1; i <= 15; i++)
        assert_float_equal(atan2(r[i] - r[i - 1], z[i - 1] - z[i]), theta[i - 1], 1e-12);
    whirl_chain *c100 = whirl_chain_alloc_uniform(100, 0);
    follow_high(c100, 50, 300, NULL, &h);
    check_high(c100, 50, 300, &h);
    assert_true(h.angle_steps > 0);
    whirl_chain_free(c15);
    whirl_chain_free(c100);
}

/* Every mode of N = 100 (every third and the last) at twice omega_N, and modes 2 and 10 of
 * N = 1000 at twice their birth. */
static void test_every_mode_high(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(100, 0);
    double crit[100], worst = 0, per_weight = 0;
    assert_int_equal(whirl_nlink_critical(c, 100, crit), GSL_SUCCESS);
    const double top = 2 * crit[99];
    high_run h;
    for (int k = 1; k <= 100; k += 3) {
        follow_high(c, k, top, NULL, &h);
        assert_true(h.worst < 200 * 100 * DBL_EPSILON);
        assert_true(h.jump <= 1.05 * sqrt(100.0));
        worst = fmax(worst, h.worst);
        per_weight = fmax(per_weight, h.per_weight);
    }
    print_message("N = 100, modes 1, 4, .., 100 at omega = %.4f (2 omega_N): force across a link "
                  "<= %.2e of the forces summed in it (%.2e of the weight)\n", top, worst,
                  per_weight);
    whirl_chain_free(c);
    whirl_chain *c1000 = whirl_chain_alloc_uniform(1000, 0);
    double crit1000[10];
    assert_int_equal(whirl_nlink_critical(c1000, 10, crit1000), GSL_SUCCESS);
    const int modes[] = {2, 10};
    for (int m = 0; m < 2; m++) {
        follow_high(c1000, modes[m], 2 * crit1000[modes[m] - 1], NULL, &h);
        check_high(c1000, modes[m], 2 * crit1000[modes[m] - 1], &h);
    }
    /* modes 500 and 1000 of 1000, where the shot polishes neither the birth nor the first step:
     * they start in the link angles, above their birth, balanced */
    whirl_nlink_path *p = whirl_nlink_path_alloc(c1000);
    for (int k = 500; k <= 1000; k += 500) {
        assert_int_equal(whirl_nlink_path_birth(p, k), GSL_SUCCESS);
        for (int s = 0; s < 3; s++) {
            assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
            /* the tip's sign only where the tail is resolved: mode 1000's tip radius is 1e-160
             * of its largest, below what link angles in double resolve */
            assert_true(p->angles && p->omega > p->omega_birth && (k == 1000 || p->tip_r > 0));
            double pw, res = angle_residual(c1000, p->omega, whirl_nlink_path_theta(p), &pw);
            assert_true(res < 200 * 1000 * DBL_EPSILON);
        }
        print_message("N = 1000 mode %d: born at %.10g, three steps in the link angles to %.10g\n",
                      k, p->omega_birth, p->omega);
    }
    whirl_nlink_path_free(p);
    whirl_chain_free(c1000);
}

/* Up to omega = 200 and back down on N = 15 mode 7: the same link angles at the same rates. */
static void test_retrace_high(void **state)
{
    (void)state;
    const size_t n = 15;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    enum { nr = 5 };
    const double rates[nr] = {45.3, 80.7, 120.1, 160.9, 190.2};
    double up[nr][15], down[nr][15];
    int seen_up[nr] = {0}, seen_down[nr] = {0};
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 7), GSL_SUCCESS);
    for (int dir = 0; dir < 2; dir++) {
        while (dir == 0 ? p->omega < 200 : p->omega > 40) {
            assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
            for (int j = 0; j < nr; j++) {
                double a;
                int found = whirl_nlink_path_crossings(p, rates[j], 1, &a);
                assert_true(found >= 0);
                if (!found) continue;
                double *dst = dir == 0 ? up[j] : down[j];
                for (size_t i = 0; i < n; i++) dst[i] = whirl_nlink_path_cross_theta(p)[i];
                (dir == 0 ? seen_up : seen_down)[j]++;
            }
            assert_true(p->steps < 20000);
        }
        if (dir == 0) whirl_nlink_path_reverse(p);
    }
    double worst = 0;
    for (int j = 0; j < nr; j++) {
        assert_int_equal(seen_up[j], 1);
        assert_int_equal(seen_down[j], 1);
        for (size_t i = 0; i < n; i++) worst = fmax(worst, fabs(up[j][i] - down[j][i]));
    }
    print_message("retrace N = 15 mode 7 to omega = 200 and back to 40: link angles agree to "
                  "%.2e rad\n", worst);
    assert_true(worst < 1e-10);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

static void test_errors(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(5, 0);
    whirl_shape_info info;
    double crit[5];
    assert_int_equal(whirl_nlink_critical(c, 5, crit), GSL_SUCCESS);
    /* above N */
    assert_int_equal(whirl_nlink_solve(c, 30, 6, &info), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "modes 1..5"));
    /* below the birth: says so, naming omega_k */
    assert_int_equal(whirl_nlink_solve(c, crit[2] * (1 - 1e-9), 3, &info), GSL_EDOM);
    assert_non_null(strstr(whirl_last_error(), "exists only above omega_3="));
    /* exactly at the birth: the hanging chain, not a shape of the mode */
    assert_int_equal(whirl_nlink_solve(c, crit[2], 3, &info), GSL_EDOM);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 0), GSL_EINVAL);
    assert_int_equal(whirl_nlink_path_birth(p, 6), GSL_EINVAL);
    assert_int_equal(whirl_nlink_path_start(p, NAN, 0.1, 1), GSL_EINVAL);
    /* a stop request ends a step */
    assert_int_equal(whirl_nlink_path_birth(p, 2), GSL_SUCCESS);
    whirl_stop_request();
    assert_int_equal(whirl_nlink_path_step(p), WHIRL_EINTERRUPTED);
    assert_int_equal(whirl_nlink_solve(c, 10, 2, &info), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
    /* a start from an equilibrium found by the birth path, in both directions */
    assert_int_equal(whirl_nlink_solve(c, 7.3, 2, &info), GSL_SUCCESS);
    assert_int_equal(whirl_nlink_path_start(p, 7.3, info.tip_r, -1), GSL_SUCCESS);
    assert_float_equal(p->tip_r, info.tip_r, 1e-13 * info.tip_r);
    assert_true(p->t_omega < 0);
    assert_null(whirl_nlink_path_alloc(NULL));
    whirl_nlink_path_free(NULL);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* The nodes of whirl_nlink_solve_nodes keep every link's length to round-off on a long chain
 * (10^4 links, mode 2 at omega = 4): radii formed as the balancing radius of each mass, a
 * difference of the loads on its two links, were off by 1e-9 of a link's length near the pivot;
 * and the pivot on the axis. */
static void test_nodes_lengths(void **state)
{
    (void)state;
    const size_t n = 10000;
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *r = malloc(3 * (n + 1) * sizeof *r), *z = r + n + 1, *t = z + n + 1;
    assert_non_null(c);
    assert_non_null(r);
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve_nodes(c, 4, 2, &info, r, z, t), GSL_SUCCESS);
    double worst = 0;
    for (size_t i = 1; i <= n; i++)
        worst = fmax(worst, fabs(hypot(r[i] - r[i - 1], z[i] - z[i - 1]) / c->length[i - 1] - 1));
    print_message("N = %zu mode 2 at omega 4: link lengths within %.3g relative\n", n, worst);
    assert_true(worst < 1e-12);
    assert_true(r[0] == 0 && r[n] > 0);
    free(r);
    whirl_chain_free(c);
}

/* The checks of a run on a chain whose balance is not resolved to 200 N eps of the forces summed
 * in a link in double: a heavy tip (its radius, 1e-12 of the chain's, carries the round-off of
 * the radii above it, multiplied by its centrifugal force, 1e-3 of its weight at 1e12), or
 * tensions over many decades: at every point the force across a link within 10 times its floor
 * with the angles moved by an ulp (ulp_floor: angles a few ulps off; 7 near the sharp turn of a
 * heavy tip's branch, where the balance is nearly singular), and no link angle changing by more
 * than the metric allows. */
static void check_ulp(const whirl_chain *c, int mode, double omega_top, const high_run *h)
{
    print_message("N = %zu mode %d to omega = %g: %ld steps (%ld in the link angles), force "
                  "across a link <= %.2f times its floor with the angles moved by an ulp, link "
                  "angle change per unit step <= %.2f (sqrt(N) = %.2f)\n", c->n, mode,
                  omega_top, h->steps, h->angle_steps, h->per_ulp, h->jump, sqrt((double)c->n));
    assert_true(h->per_ulp <= 10);
    assert_true(h->jump <= 1.05 * sqrt((double)c->n));
}

/* A visit of whirl_nlink_follow counting the branch points in *ctx. */
static int count_branch_points(void *ctx, size_t j, const whirl_shape_info *info,
                               const whirl_branch_event *event)
{
    (void)j;
    (void)info;
    if (event && event->kind == WHIRL_EVENT_BRANCH_POINT) ++*(int *)ctx;
    return 0;
}

/* How far the link angles theta (N) are from the shape of a string pinned at both ends that is
 * symmetric or antisymmetric about its middle (theta_i = -+theta_{N+1-i}): the smaller
 * largest difference, relative to the largest angle. */
static double asymmetry(size_t n, const double *theta)
{
    double sym = 0, anti = 0, top = 0;
    for (size_t i = 0; i < n; i++) {
        sym = fmax(sym, fabs(theta[i] + theta[n - 1 - i]));
        anti = fmax(anti, fabs(theta[i] - theta[n - 1 - i]));
        top = fmax(top, fabs(theta[i]));
    }
    return fmin(sym, anti) / top;
}

/* A tip mass of 1e12 chain masses (the largest the library takes): the chain is a massless
 * string under the tip's weight, pinned on the axis at both ends (the tip's radius is 1e-12 of
 * the chain's), with the beads of the chain on it. Its branches are symmetric or antisymmetric
 * about the middle of the string up to a rate where that symmetric branch splits (a pitchfork
 * of the pinned string); the weight of the links unfolds it at 1e-12, and the branch from the
 * birth turns there onto the asymmetric side within an arclength of 1e-7 (mode 4 of 6 links at
 * 1.19 times its birth). The path follows the turn, without a branch point, where it stopped
 * before (the tangent turning by more than 0.2 rad at the smallest step, 1e-7 then): symmetric
 * to 1e-6 below the turn, asymmetric above, balanced at round-off and with no link angle
 * changing by more than the step allows. Mode 16 of 30 links, which stopped at 1.03 times its
 * birth, reaches 5 times its birth. */
static void test_heavy_tip(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(6, 1e12);
    double crit[16], theta_low[6], theta_high[6];
    assert_int_equal(whirl_nlink_critical(c, 4, crit), GSL_SUCCESS);
    high_run h;
    follow_high(c, 4, 1.1 * crit[3], theta_low, &h);
    check_ulp(c, 4, 1.1 * crit[3], &h);
    follow_high(c, 4, 2.5 * crit[3], theta_high, &h);
    check_ulp(c, 4, 2.5 * crit[3], &h);
    print_message("N = 6, tip mass 1e12, mode 4: asymmetry %.2e at 1.1 times its birth, %.2f at "
                  "2.5 times\n", asymmetry(6, theta_low), asymmetry(6, theta_high));
    assert_true(asymmetry(6, theta_low) < 1e-6);
    assert_true(asymmetry(6, theta_high) > 0.1);
    int branch_points = 0;
    assert_int_equal(whirl_nlink_follow(c, 4, 2.5 * crit[3], 0, NULL, count_branch_points,
                                        &branch_points), GSL_SUCCESS);
    assert_int_equal(branch_points, 0);
    whirl_chain_free(c);
    c = whirl_chain_alloc_uniform(30, 1e12);
    assert_int_equal(whirl_nlink_critical(c, 16, crit), GSL_SUCCESS);
    follow_high(c, 16, 5 * crit[15], NULL, &h);
    check_ulp(c, 16, 5 * crit[15], &h);
    whirl_chain_free(c);
    /* 20 links, mode 4: near omega 1.899e7 the corrected points of steps below 1e-8 scatter by
     * their round-off across the turn, and the chord test rejected every step down to the
     * smallest; the step is then taken without it. At 2.5 times the birth the tip radius is
     * the one a path with steps of at most 0.01 and turns of at most 0.05 reaches,
     * 1.463901448e-14. */
    double theta20[20];
    c = whirl_chain_alloc_uniform(20, 1e12);
    assert_int_equal(whirl_nlink_critical(c, 4, crit), GSL_SUCCESS);
    const double w20 = 2.5 * crit[3];
    follow_high(c, 4, w20, theta20, &h);
    check_ulp(c, 4, w20, &h);
    const double tip20 = c->gravity * tan(theta20[19]) / (w20 * w20);
    print_message("N = 20, tip mass 1e12, mode 4 at 2.5 times its birth: tip radius %.10e\n",
                  tip20);
    assert_true(fabs(tip20 / 1.463901448e-14 - 1) < 1e-8);
    whirl_chain_free(c);
}

/* The link angles of mode k of c where its path from the birth first crosses omega_top, every
 * step at most cap if cap > 0 (the step control otherwise its own), into theta; returns the
 * steps. */
static long path_end(const whirl_chain *c, int mode, double omega_top, double cap, double *theta)
{
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_non_null(p);
    assert_int_equal(whirl_nlink_path_birth(p, mode), GSL_SUCCESS);
    double a;
    int found = 0;
    while (!found) {
        if (cap > 0 && p->ds > cap) p->ds = cap;
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        assert_false(p->ended);
        found = whirl_nlink_path_crossings(p, omega_top, 1, &a);
        assert_true(found >= 0);
        assert_true(p->steps < 20000);
    }
    for (size_t i = 0; i < c->n; i++) theta[i] = whirl_nlink_path_cross_theta(p)[i];
    const long steps = p->steps;
    whirl_nlink_path_free(p);
    return steps;
}

/* A tip mass of 1e12: the modes whose path, with steps of up to 0.1, passed over two splits of
 * the pinned string at nearly the same rate in one step, where the orientation test (a sign)
 * stays the same, and went on on the symmetric curve beyond them: at 2.5 times their birth
 * every link angle is the one the path with steps of at most 0.01 reaches (on the asymmetric
 * side), to 1e-6 rad; the index of the force balance changes by two on such a step, which is
 * halved. */
static void test_heavy_tip_jumps(void **state)
{
    (void)state;
    static const int cases[][2] = {{12, 11}, {16, 11}, {16, 15}, {20, 7}, {20, 15}, {20, 19},
                                   {24, 11}, {24, 15}, {24, 16}, {24, 22}, {24, 23}, {28, 11},
                                   {28, 19}, {28, 23}};
    double own[28], fine[28], crit[28];
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        const size_t n = (size_t)cases[j][0];
        const int mode = cases[j][1];
        whirl_chain *c = whirl_chain_alloc_uniform(n, 1e12);
        assert_int_equal(whirl_nlink_critical(c, (size_t)mode, crit), GSL_SUCCESS);
        const double top = 2.5 * crit[mode - 1];
        const long s_own = path_end(c, mode, top, 0, own);
        const long s_fine = path_end(c, mode, top, 0.01, fine);
        double diff = 0;
        for (size_t i = 0; i < n; i++) diff = fmax(diff, fabs(own[i] - fine[i]));
        print_message("N = %zu mode %d, tip mass 1e12, at 2.5 times its birth: %ld steps, %ld "
                      "with steps of at most 0.01; link angles apart by %.1e, asymmetry %.2f\n",
                      n, mode, s_own, s_fine, diff, asymmetry(n, own));
        assert_true(diff < 1e-6);
        assert_true(asymmetry(n, fine) > 0.1);
        whirl_chain_free(c);
    }
}

/* The first point of a branch whose shot from the tip cannot start it: in the link angles at a
 * finite amplitude. Mode 9 of this 9-link chain (lengths and masses over six decades) took a
 * first step on the shot of 2e-6 (a tip radius of 1e-30), handed over to the link angles there,
 * where the force balance at fixed omega does not tell the branch from the hanging chain, and
 * "returned to the hanging chain" at its birth; it exists up to 10 times its birth and beyond. */
static void test_birth_in_angles(void **state)
{
    (void)state;
    static const double length[9] = {256.12166294457347, 185.29461696498663,
        0.0034887389202929507, 0.55732974195864404, 0.0026911812629485539, 12.222769323043492,
        86.652235574616029, 10.631086868941122, 0.0010037141408547113};
    static const double mass[9] = {43.317971818439126, 25.40498816118885, 5.8941556052961337,
        273.09110382875366, 0.64032344319069756, 0.17163574324401901, 0.0049365769551823774,
        0.0038788587925004808, 0.020747158846853568};
    whirl_chain *c = whirl_chain_alloc(9, length, mass, 1);
    assert_non_null(c);
    double crit[9];
    assert_int_equal(whirl_nlink_critical(c, 9, crit), GSL_SUCCESS);
    high_run h;
    follow_high(c, 9, 10 * crit[8], NULL, &h);
    check_ulp(c, 9, 10 * crit[8], &h);
    whirl_chain_free(c);
}

/* A 12-link chain of a random audit (lengths and masses over six decades): test_near_births and
 * test_corners. */
static const double length12[12] = {6.4137541914433962, 0.69985078418033264,
    0.30445216588345081, 0.040501451846643347, 882.05113251028865, 105.55843472014749,
    379.95636790871288, 484.65009559407321, 0.0078598851595356005, 0.014259210818873328,
    0.23404188197373091, 0.0042769417477639222};
static const double mass12[12] = {0.588136706496169, 0.0037810206044739006,
    2.3210929408558481, 0.41819146771713517, 48.103996890005305, 0.0045684015998842158,
    0.83784451659396864, 2.6769554892953562, 0.33110164254819519, 0.089698702524540028,
    0.037324865515517835, 0.0042130898264247044};

/* Branches that pass close to the hanging chain at another mode's birth: modes 7 and 8 of this
 * 10-link chain meet the birth of mode 9 at omega = 196.2457, where part of the chain comes within
 * 1e-15 of hanging (a secondary pitchfork of the upper links, unfolded by the lower ones at that
 * scale: the branch turns by about a radian within an arclength of 1e-9), and mode 7 of the 12-link
 * chain of a random audit meets the birth of mode 8 at 11.1791 (its links 1..7 at 1e-10 rad
 * there). Both stopped with "the tangent turns by more than 0.2 rad at the smallest step 1e-10";
 * steps down to 1e-12 in the link angles follow the turn: a 60-digit pseudo-arclength path in
 * (omega, theta) with turns of at most 0.05 rad per step goes the same way (onto the upper links'
 * pitchfork; a natural continuation in omega jumps across it instead). Mode 9 of the third chain
 * failed at its own birth (the Jacobian there exactly singular in double, the linear mode shape
 * taken from the shot's d theta / d a, whose upper links are its round-off): its first point now
 * comes from the twisted factorization of the Jacobian. Mode 3 of the 5-link chain stopped on the
 * tip shot near omega = 92.5 with "a return to the hanging chain between omega=86.6 and 96.2 could
 * not be located": its tail (links 4 and 5, 1e-6 rad from hanging) turns there in a pitchfork of
 * its own, which the step of 0.1 went across, the tip radius changing sign; the step is now
 * halved, and the path follows the turn. Each reaches 10 times its birth, balanced at every point;
 * the 5-link chain's tip radius there is the one a path with steps of at most 0.01 and turns of
 * at most 0.05 reaches, 4.9718259981491416e-07. */
static void test_near_births(void **state)
{
    (void)state;
    static const double length10[10] = {0.0057345312859660349, 0.0080268025492075071,
        0.038398822692928283, 0.0010680033900683336, 1.9544875121297172, 4.1540710774219569,
        699.11308682519757, 30.768236891395865, 0.033047216381195635, 0.26458420431114649};
    static const double mass10[10] = {13.826388989566144, 2.4045304435807306, 6.0273741545159591,
        0.0080766022194672816, 3.420393787126256, 0.016414051020772945, 1.6254273412394882,
        4.8288160952370749, 0.042321538977457586, 47.515183489569964};
    static const double length_b[12] = {0.0043204635832964754, 15.59049893081143,
        0.052218545422964668, 0.78520350820823459, 19.126137090217345, 0.052759247012254401,
        0.026953662526442237, 100.49103184670962, 15.345957326808813, 171.03188630787901,
        0.0014228765994985385, 0.0035709974726516897};
    static const double mass_b[12] = {372.38577168706553, 0.019755899703838488,
        0.15081956291149995, 97.851286318238678, 63.145726299640586, 122.97685307924768,
        20.765136787077768, 0.077253464641679967, 4.1204361268157879, 0.047398828411023219,
        0.024477450669286391, 0.38449448270292941};
    static const double length5[5] = {0.0030176710884618693, 20.961159282034746,
        0.26445343003303606, 7.1026977860640752, 0.0089130777112692641};
    static const double mass5[5] = {14.014928340412791, 0.11826884094303312,
        0.0080223601269572148, 0.0010089896325930301, 16.514020441753747};
    const struct {
        size_t n;
        const double *length, *mass;
        int mode;
    } runs[] = {{10, length10, mass10, 7}, {10, length10, mass10, 8}, {12, length12, mass12, 7},
                {12, length_b, mass_b, 9}, {5, length5, mass5, 3}};
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        whirl_chain *c = whirl_chain_alloc(runs[k].n, runs[k].length, runs[k].mass, 1);
        assert_non_null(c);
        double crit[12];
        assert_int_equal(whirl_nlink_critical(c, runs[k].n, crit), GSL_SUCCESS);
        high_run h;
        const double top = 10 * crit[runs[k].mode - 1];
        follow_high(c, runs[k].mode, top, NULL, &h);
        print_message("N = %zu mode %d to omega = %g: %ld steps (%ld in the link angles), force "
                      "across a link <= %.2f times its floor with the angles moved by an ulp, "
                      "link angle change per unit step <= %.2f sqrt(N)\n", c->n, runs[k].mode,
                      top, h.steps, h.angle_steps, h.per_ulp, h.jump / sqrt((double)c->n));
        assert_true(h.per_ulp <= 10);
        /* no link angle changes by much more than sqrt(N) times the step (1.07 on the tip
         * shot's first steps from the birth of mode 7 of 10 links): a jump onto another curve
         * would be many times that */
        assert_true(h.jump <= 1.15 * sqrt((double)c->n));
        whirl_shape_info info;
        assert_int_equal(whirl_nlink_solve(c, 10 * crit[runs[k].mode - 1], runs[k].mode, &info),
                         GSL_SUCCESS);
        if (runs[k].n == 5) assert_true(fabs(info.tip_r / 4.9718259981491416e-07 - 1) < 1e-8);
        whirl_chain_free(c);
    }
}

/* A run of mode `mode` of a chain from its birth to its first crossing of 10 times the birth
 * (to_ten): its steps, the events met by kind (events[WHIRL_EVENT_*]), the rates of its first
 * max_folds folds into fold_at, and the largest difference of its link angles there from end or
 * from end's mirror image, whichever is nearer. */
typedef struct ten_run {
    long steps;
    int events[4];
    double distance;
} ten_run;

static void to_ten(size_t n, const double *length, const double *mass, int mode,
                   const double *end, double *fold_at, int max_folds, ten_run *r)
{
    whirl_chain *c = whirl_chain_alloc(n, length, mass, 1);
    assert_non_null(c);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_non_null(p);
    assert_int_equal(whirl_nlink_path_birth(p, mode), GSL_SUCCESS);
    const double target = 10 * p->omega_birth;
    int found = 0;
    double tip[WHIRL_PATH_EVENTS_MAX + 1];
    memset(r, 0, sizeof *r);
    for (long steps = 0; !found && steps < 10000; steps++) {
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        for (int e = 0; e < p->n_events; e++) {
            const whirl_event_kind kind = p->event[e].kind;
            if (kind == WHIRL_EVENT_FOLD && r->events[kind] < max_folds)
                fold_at[r->events[kind]] = p->event[e].omega;
            r->events[kind]++;
        }
        found = whirl_nlink_path_crossings(p, target, WHIRL_PATH_EVENTS_MAX + 1, tip);
        assert_true(found >= 0);
    }
    assert_int_equal(found, 1);
    double same = 0, mirror = 0;
    for (size_t i = 0; i < n; i++) {
        same = fmax(same, fabs(whirl_nlink_path_cross_theta(p)[i] - end[i]));
        mirror = fmax(mirror, fabs(whirl_nlink_path_cross_theta(p)[i] + end[i]));
    }
    r->steps = p->steps;
    r->distance = fmin(same, mirror);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* Corners just below another mode's birth: mode 8 of a 12-link and a 9-link chain (lengths and
 * masses over six decades) pass within 1e-10 (relative) below the birth of mode 9 with part of
 * the chain all but hanging, and turn there by a right angle over an arclength of about 4e-9,
 * another curve of equilibria 1e-10 to 2e-10 away. The path took a reversal of its orientation
 * test on a step of 1e-9 there for a branch point and went on along that other curve, ending at
 * 10 times the birth 1.45 and 1.55 rad away from the branch; a probe now looks ahead with finer
 * steps and follows the turn. Mode 10 of the 12-link chain above turns within 1e-13 (relative)
 * below the birth of mode 11 at omega = 60.5124486, where the 50-digit path takes steps down to
 * 1e-17: its top five links, 1e-20 to 1e-15 rad from hanging, bend while the rate moves within
 * its round-off. Mode 10 of an 11-link chain (seed 2 of the README's random chains) turns where
 * the 40-digit path takes steps of 1.7e-17, which a look ahead whose finest step was 1e-16 took
 * for a branch point, ending 1.6 rad off; it goes down to 1e-18 now. Mode 7 of a third 9-link
 * chain went the right way before and must still. The reference: the link angles at 10 times the
 * birth from an independent 50-digit pseudo-arclength continuation in mpmath of the force balance
 * in (omega, theta), in the same metric, turns of at most 0.02 rad per step and every step's
 * orientation and index checked (tests/tools/branch_mp.py --length L --mass M MODE: its CROSS line; 40
 * digits for the 11-link chain). */
static void test_corners(void **state)
{
    (void)state;
    static const double length_a[12] = {0.035350988975983766, 0.75669569454246821,
        0.32845934013890316, 0.020326768502812585, 2.2652340137841711, 0.45754287785312786,
        4.2288237971426543, 198.4248599993677, 12.764992808177084, 3.0056614495915541,
        0.10488532688884442, 253.25708685712144};
    static const double mass_a[12] = {7.0504222524289499, 191.42565269492235,
        0.40884434092041139, 76.735985574243657, 0.0014559722666634754, 201.19295425113916,
        14.310337262877036, 1.1948508310681367, 14.869597527176841, 0.01030076036692045,
        0.077556098480104863, 47.521385083298341};
    static const double end_a[12] = {1.445165547539164, -0.046375833592764953,
        2.0501528335352348e-05, 3.4899469053183568e-05, -3.3028461118581966e-09,
        -3.4499299167308829e-09, -1.1750333868404033e-12, 2.1028429666459822e-08,
        -0.0014257665837115365, 1.5609484048604609, 1.5596871280578071, -0.012210028922129955};
    static const double length_b[9] = {0.070162066030373019, 111.81954152718886,
        2.3222961544612386, 23.062821237957106, 330.49317381274932, 0.14277270054558061,
        0.0037092662097338424, 22.915984884650165, 0.27251719136522617};
    static const double mass_b[9] = {0.0068675647299397914, 1.7013048900246917,
        0.07636857239449947, 7.896589309214459, 0.32922785172356628, 0.0724052084410058,
        183.34632586580688, 111.71786576971722, 0.0083645241425102553};
    static const double end_b[9] = {1.5608023682850978, -0.0006274267235814589,
        7.6471307268517278e-10, -2.0505934970029224e-15, -1.1119459644592979e-09,
        0.025971552721493634, -1.5534434385263649, 6.3857879076832439e-08,
        -3.6979829202771218e-15};
    static const double length_c[9] = {0.8624770221753858, 0.10941880901976603,
        1.7406746655743852, 2.7337776804982017, 90.524982180307802, 0.090124520184199364,
        1.3478017650844096, 0.46867340661603152, 0.0071712700659721787};
    static const double mass_c[9] = {0.0023397721798814248, 0.065100103846090149,
        0.028579361980291582, 69.524207910028281, 675.48491737981828, 0.082598129143583901,
        0.024182725185860465, 0.0013407704854452862, 14.088509789399636};
    static const double end_c[9] = {-0.80921705094650609, 1.3782255701280011,
        1.5640142191803372, -0.46415266599726046, 1.8804645148860566e-08,
        1.0811733978314748e-09, -1.8303496868658376e-06, 0.013594539208479145,
        -1.0933566087834345};
    static const double length_e[11] = {0.72797279613612398, 0.0022690681500526196,
        0.006491926481726364, 0.015975069751098574, 38.313501595981194, 342.37913689973078,
        0.0015751490705917433, 0.053664745916852927, 582.9529450096054, 0.076843773683814232,
        0.039999046010488301};
    static const double mass_e[11] = {0.18347902920841735, 17.347051726274756,
        0.013282959756605921, 1.5752586173499785, 0.0033168056859108857, 108.20010408606522,
        64.258489128035009, 0.016741976613517277, 37.884092590071404, 0.0015210788521924591,
        123.16876865370656};
    static const double end_e[11] = {-1.871191063205387498e-08, 0.0021826978381104272057,
        -1.5580899264129391254, 0.41813391667386620406, -8.014899267482777203e-09,
        7.647354684348351103e-15, -1.534804739863923166e-20, -6.435592987645522040e-15,
        1.104479196114788405e-11, -0.54744410641003248562, 1.5641931391098556376};
    static const double end_d[12] = {-5.510068271783418e-06, 0.0098771387153506751,
        -0.0024865934479776594, -1.43001257530022, 3.8524662939935253e-05,
        -1.5162467320018383e-11, 1.3342232979815041e-15, 6.1840531281516485e-17,
        -4.5241514691164682e-09, 2.320984168481202e-06, -0.0018538656341763743,
        1.5608152411436502};
    const struct {
        size_t n;
        const double *length, *mass, *end;
        int mode;
    } runs[] = {{12, length_a, mass_a, end_a, 8}, {9, length_b, mass_b, end_b, 8},
                {9, length_c, mass_c, end_c, 7}, {12, length12, mass12, end_d, 10},
                {11, length_e, mass_e, end_e, 10}};
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        ten_run r;
        to_ten(runs[k].n, runs[k].length, runs[k].mass, runs[k].mode, runs[k].end, NULL, 0, &r);
        print_message("%zu links, mode %d at 10 times its birth: %ld steps, %d branch points, "
                      "link angles %.1e rad from the 50-digit path\n", runs[k].n, runs[k].mode,
                      r.steps, r.events[WHIRL_EVENT_BRANCH_POINT], r.distance);
        assert_true(r.distance < 1e-12);
        assert_int_equal(r.events[WHIRL_EVENT_BRANCH_POINT], 0);
    }
}

/* Chains whose lengths and masses span six to twelve decades, each once stopped or sent off its
 * branch by the continuation's own arithmetic, now followed to 10 times the birth:
 * - mode 3 of a 6-link chain passes two folds, at omega = 0.4929787 and 0.4298846. A corrector's
 *   Newton iterate near the first lands on the fold to the last bit, where LAPACK's dgttrf finds
 *   a pivot of the force balance exactly zero; the fold could not be located and the path
 *   stalled at it. The zero pivot is now moved to -eps |A| (src/nlink_balance.c). Each fold is
 *   checked against the solution of the extended system R = 0, A phi = 0 (Moore & Spence 1980)
 *   by Newton's method in 40-digit mpmath, from the library's point: 0.492978728497649851028698
 *   and 0.429884560098057538983563.
 * - mode 4 of a 5-link chain: the tip shot's first step from the birth lands within 4e-15
 *   (relative) of the birth's rate, where the force balance at fixed omega cannot tell the
 *   branch from the hanging chain; handed over to the link angles there, the path fell onto the
 *   hanging chain and reported "the branch ended on the hanging chain" at omega = 2225.05, no
 *   critical rate. Such a first step now begins in the link angles from the linear mode shape.
 * - mode 4 of a 10-link chain: where the shot hands over to the link angles at a point the
 *   path takes for a fold, its polish at fixed omega fails; it now falls back on the hyperplane
 *   normal to the shot's tangent. Before, the shot failed there (or, by another route, the path
 *   ended 1.55 rad off the branch). Near omega = 1.4998725 the rate is stationary to 1e-10 over
 *   an arclength of 1e-5, the rate's part of the unit tangent falling to 3e-5 without changing
 *   sign (the 40-digit path: no fold), where the force balance's Jacobian is singular to working
 *   precision (|mu| of 1e-17 of |A|) and the computed tangent's rate part changes sign at random:
 *   the path reported 19 folds there, and reports none now that a sign counts only where mu is
 *   resolved (src/nlink_path.c, rate_sign).
 * - mode 5 of a 7-link chain, the same near omega = 58.0137796387: 6 folds within 2e-13 in omega
 *   reported before, none by the 40-digit path, none now.
 * - mode 3 of a 7-link chain (eight decades) turns back twice within 1.2e-5 in omega just above
 *   its birth, at 0.40899259 and 0.40898043: a step of 0.1 on the tip shot went across both, the
 *   rate at its ends moving on (t_omega of 2.1e-4 and 1.4e-3) and the rate itself by 1.9e-6
 *   where the tangents predict 8e-5; the tip shot had no test for two folds within a step, and
 *   the path reported none. The step is now halved where the rate's cubic Hermite interpolant
 *   turns back inside it (src/nlink_path.c, rate_turns_back). Both folds are checked against the
 *   extended system in 40-digit mpmath: 0.408992589151043604685 and 0.408980430164768980572.
 * The reference: the link angles at 10 times the birth from tests/tools/branch_mp.py (--dps 30 or 40:
 * its CROSS line), up to the mirror image, and its count of folds. */
static void test_wide_chains(void **state)
{
    (void)state;
    static const double length_a[6] = {630.33005332306675, 0.27500766827344486,
        174.81872058124804, 1.4411941992607589, 8.7492626352478684, 6.8690222534588523};
    static const double mass_a[6] = {12.394488685353037, 0.0016892875309677934,
        189.87315451839621, 23.436595581584179, 0.006442324773379496, 63.03504867928811};
    static const double end_a[6] = {-4.781645393876825730e-05, 0.023102088461326647899,
        0.023104719146899795003, -1.5641709981643918101, -1.5663208114236537786,
        -1.5663210522606348583};
    static const double length_b[5] = {0.00020000653783724246, 4.8946411383332427e-06,
        392030.14194413403, 64.590489722376191, 1.2944253980781326};
    static const double mass_b[5] = {0.0063534961973308358, 122.31343730443081,
        3040.567579273004, 5.0619419448599691e-05, 317.66724932499346};
    static const double end_b[5] = {-2.9400289858288358427e-21, -2.4092028973156036362e-21,
        1.0801333450446181290e-17, -0.020040870046259079667, 1.5609907104313135559};
    static const double length_c[10] = {0.0036562240126909737, 0.44084328951817064,
        2.7587669586471862e-05, 0.80487366894353563, 546.56969276689119,
        6.1669592018545456e-05, 0.0035821353635932147, 10166.134822036443, 1.5960193291413209,
        74.013597551022457};
    static const double mass_c[10] = {3.1906671193842886, 0.0028475288809263976,
        73587.63745891898, 3.3361796949069408e-05, 0.97473431470066951, 0.036732958619229102,
        0.00010956934181698877, 0.13881324572048581, 0.00072004338782051232,
        0.00059443697276225708};
    static const double end_c[10] = {1.5514174090303641811, 1.5514182421068862800,
        1.5514182421069210718, 0.00068234238347470777352, -0.00081417041372842584387,
        -0.00019387380603678162766, -1.5343069474987325282e-06, -8.0924221564943726457e-07,
        1.5608919317387428078, -0.021455690654361637889};
    static const double length_d[7] = {0.10087329152129333, 0.026318780561326995,
        0.0090974694516712511, 210.73037329387267, 578.6288726827753, 526.28775936892703,
        0.016055586349642992};
    static const double mass_d[7] = {3.33805174447191, 0.073114229071147993, 280.34103488196365,
        9.3007946242158201, 1.9916129258764625, 0.42241119653961684, 0.0080748100692745149};
    static const double end_d[7] = {0.313818289644083911743, -1.09278432037385566320,
        -1.09548512926404625341, 1.513357850838353697867e-06, -4.856731069221029322e-13,
        -5.72208916424475726815e-07, 1.56079616578636737316};
    static const double length_e[7] = {9636.9231974723316, 788.96920386832323,
        0.00017503334304547083, 0.00012409426253038452, 0.043021942215724668,
        0.14667519976064033, 6.9347500721724771};
    static const double mass_e[7] = {0.12822130438825816, 15.120366728913137,
        0.00028846328443776439, 0.29269396131203362, 0.00011984187386754951,
        0.0008996220057487721, 0.089233586728373768};
    static const double end_e[7] = {3.94313044616558088457227e-8,
        -0.00005248158224275984423910274, 1.533843462707804233746159, 1.533871952880489020453103, 1.562254391787351830646698,
        1.562265729877013084139852, 1.562349079460895866443229};
    static const double folds_a[2] = {0.492978728497649851028698, 0.429884560098057538983563};
    static const double folds_e[2] = {0.408992589151043604684978, 0.408980430164768980571546};
    const struct {
        size_t n;
        const double *length, *mass, *end, *folds;
        int mode, n_folds;
    } runs[] = {{6, length_a, mass_a, end_a, folds_a, 3, 2},
                {5, length_b, mass_b, end_b, NULL, 4, 0},
                {10, length_c, mass_c, end_c, NULL, 4, 0},
                {7, length_d, mass_d, end_d, NULL, 5, 0},
                {7, length_e, mass_e, end_e, folds_e, 3, 2}};
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        ten_run r;
        double fold_at[2];
        to_ten(runs[k].n, runs[k].length, runs[k].mass, runs[k].mode, runs[k].end, fold_at, 2,
               &r);
        const int folds = r.events[WHIRL_EVENT_FOLD];
        double fold_error = 0;
        for (int f = 0; runs[k].folds && f < runs[k].n_folds && f < folds; f++)
            fold_error = fmax(fold_error, fabs(fold_at[f] / runs[k].folds[f] - 1));
        print_message("%zu links, mode %d at 10 times its birth: %ld steps, %d folds (rates "
                      "%.1e from the extended system's), %d other events, link angles %.1e rad "
                      "from the mpmath path\n", runs[k].n, runs[k].mode, r.steps, folds,
                      fold_error, r.events[WHIRL_EVENT_BRANCH_POINT] +
                      r.events[WHIRL_EVENT_RETURN], r.distance);
        assert_true(r.distance < 1e-12);
        assert_int_equal(r.events[WHIRL_EVENT_BRANCH_POINT] + r.events[WHIRL_EVENT_RETURN], 0);
        assert_int_equal(folds, runs[k].n_folds);
        assert_true(fold_error < 1e-13);
    }
}

/* A branch meets the hanging chain only at a critical rate: at any other rate the hanging chain
 * is an isolated equilibrium. Mode 1 of this 11-link chain (lengths and masses over eleven
 * decades) leaves its birth, omega_1 = 8.0276357e-4, towards lower rates, and a step landed on
 * the hanging chain 4e-5 (relative) below it: the path reported "the branch ended on the hanging
 * chain" at omega = 8.0273064e-4, no critical rate. A return is now taken only within 1e-8 of a
 * critical rate (where the index of the hanging chain's force balance changes); elsewhere the
 * step is taken back and halved (here down to the smallest, and the path stops with a one-line
 * error naming the rate). Every return met must lie at a critical rate. */
static void test_no_false_return(void **state)
{
    (void)state;
    static const double length[11] = {471547.87652430119, 882464.78727897396,
        87559.056305644131, 133543.55344487427, 1291.674565929595, 3.4420302527524989e-06,
        0.0010441608491720345, 8.5760131719946422, 64071.911373003823, 5.2683769322812637,
        0.0036817092862023891};
    static const double mass[11] = {2624.8491907971998, 34005.277305055424, 28277.968467022256,
        3.1388899870734902e-06, 0.00030556973585918842, 4.7526282639460331e-06,
        383058.91210314538, 4344.1803034713566, 0.14739381443430533, 1.9076713976879238e-05,
        11.796767219715317};
    whirl_chain *c = whirl_chain_alloc(11, length, mass, 1);
    assert_non_null(c);
    double crit[11];
    assert_int_equal(whirl_nlink_critical(c, 11, crit), GSL_SUCCESS);
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_non_null(p);
    assert_int_equal(whirl_nlink_path_birth(p, 1), GSL_SUCCESS);
    int status = GSL_SUCCESS, returns = 0;
    for (long steps = 0; status == GSL_SUCCESS && !p->ended && p->omega <= 10 * crit[0] &&
                         steps < 10000; steps++) {
        status = whirl_nlink_path_step(p);
        for (int e = 0; e < p->n_events; e++) {
            if (p->event[e].kind != WHIRL_EVENT_RETURN) continue;
            double nearest = INFINITY;
            for (int k = 0; k < 11; k++)
                nearest = fmin(nearest, fabs(p->event[e].omega / crit[k] - 1));
            print_message("a return at omega %.17g, %.1e from a critical rate\n",
                          p->event[e].omega, nearest);
            assert_true(nearest < 1e-8);
            returns++;
        }
    }
    print_message("11 links, mode 1 (born at omega %.8g): %d returns; %s\n", crit[0], returns,
                  status ? whirl_last_error() : "no error");
    assert_true(status == GSL_SUCCESS || strchr(whirl_last_error(), '\n') == NULL);
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* A branch that cannot be continued: mode 4 of this 6-link chain (lengths and masses over eight
 * decades, link tensions differing by a factor 8e6) near omega = 26.0834, where its top three
 * links, 1e-10 to 1e-9 rad from hanging, bend by their own size within arclengths of 1e-10: the
 * path's corrected points there scatter by 1e-9 in the rate, and no step down to the smallest
 * is accepted (the corrector or the tangent's turn rejects each). (tests/tools/branch_mp.py follows it
 * in 40 digits with steps down to 5e-11: a limit of this continuation in double precision, not
 * of the branch.) The path, whirl_nlink_solve and whirl_nlink_branch return GSL_EFAILED with one
 * line naming the mode, the rate reached (the path's last point) and why. (Should the
 * continuation learn to pass here, this test needs another branch it cannot continue.) */
static void test_stalled_branch(void **state)
{
    (void)state;
    static const double length[6] = {0.0012922587406787884, 0.00017902550382390632,
        0.10220696674289667, 6.3390966531444954, 5091.3012894023204, 0.22932441501380871};
    static const double mass[6] = {1.1695728844445877e-05, 3759.5128350298978,
        3.6256413904149021, 0.0045631467174315227, 2.2911713280111182e-05,
        0.00044231089281488502};
    whirl_chain *c = whirl_chain_alloc(6, length, mass, 1);
    assert_non_null(c);
    double crit[6];
    assert_int_equal(whirl_nlink_critical(c, 6, crit), GSL_SUCCESS);
    const double target = 10 * crit[3];
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, 4), GSL_SUCCESS);
    int status = GSL_SUCCESS;
    for (long steps = 0; status == GSL_SUCCESS && p->omega <= target && steps < 100000; steps++)
        status = whirl_nlink_path_step(p);
    char message[512], where[64];
    snprintf(message, sizeof message, "%s", whirl_last_error());
    const double reached = p->omega;
    print_message("6 links, mode 4 (born at omega %.6g), to %.6g: %s\n", crit[3], target,
                  message);
    assert_int_equal(status, GSL_EFAILED);
    assert_true(reached > crit[3] && reached < target);
    snprintf(where, sizeof where, " fails at omega=%.17g ", reached);
    assert_int_equal(strncmp(message, "mode 4: the continuation", 24), 0);
    assert_non_null(strstr(message, where));
    /* why: the rejection of the last trial step */
    const char *why = strstr(message, "): "), *smallest = strstr(message, " at the smallest step");
    assert_non_null(why);
    assert_non_null(smallest);
    assert_true(smallest > why + 3);
    assert_null(strchr(message, '\n'));
    whirl_nlink_path_free(p);
    /* the drivers: the same failure and message */
    whirl_shape_info info;
    int exists;
    assert_int_equal(whirl_nlink_solve(c, target, 4, &info), GSL_EFAILED);
    assert_string_equal(whirl_last_error(), message);
    assert_int_equal(whirl_nlink_branch(c, 4, 1, &target, &info, &exists), GSL_EFAILED);
    assert_string_equal(whirl_last_error(), message);
    whirl_chain_free(c);
}

/* An event the path cannot locate names the step's rates: mode 5 of this 12-link chain meets the
 * hanging chain near omega_6 = 7.93 on a step of the tip shot whose return is not located; the
 * message gave the last corrector's rate, omega=-27.2, before. (Such a step on the shot is now
 * taken back and halved, and the path reaches 10 times the birth: the branch's shape.) */
static void test_unlocated_event(void **state)
{
    (void)state;
    static const double length[12] = {0.70403423566254408, 0.0028799247651691614,
        179.62487807681703, 0.55409840839684177, 7.0846261124165908, 2.1244018786508869,
        315.91485889581793, 0.0038842487934508513, 7.4303958899335383, 1.2598171177511306,
        42.309625851784432, 0.0023127677208833767};
    static const double mass[12] = {0.011440600590855081, 97.279005759553158,
        0.0097910690387522561, 0.37916439148618519, 254.12836818080615, 0.085565408476195495,
        24.871044560929754, 296.19505062745651, 102.7913799085638, 0.0046280411468803042,
        0.17736707190375597, 0.17457857631998686};
    whirl_chain *c = whirl_chain_alloc(12, length, mass, 1);
    assert_non_null(c);
    double crit[12];
    assert_int_equal(whirl_nlink_critical(c, 12, crit), GSL_SUCCESS);
    whirl_shape_info info;
    const int status = whirl_nlink_solve(c, 10 * crit[4], 5, &info);
    const char *message = whirl_last_error();
    print_message("12 links, mode 5 at 10 times its birth: %s\n", message);
    if (status == GSL_SUCCESS) {
        /* located after all: the shape is the branch's */
        assert_int_equal(info.mode, 5);
    } else {
        assert_int_equal(status, GSL_EFAILED);
        const char *between = strstr(message, " between omega=");
        assert_non_null(between);
        double w0 = 0, w1 = 0;
        assert_int_equal(sscanf(between, " between omega=%lf and omega=%lf", &w0, &w1), 2);
        assert_true(fmin(w0, w1) >= crit[4] && fmax(w0, w1) <= 10 * crit[4]);
        assert_null(strchr(message, '\n'));
    }
    whirl_chain_free(c);
}

/* whirl_nlink_branch_nodes: the row of each rate holds the nodes whirl_nlink_solve_nodes gives
 * at it (N = 15 mode 7 at 150 and 60, in that order, where the tip radius alone no longer fixes
 * them), a rate below the birth leaves its row as it was; all three arrays or none. */
static void test_branch_nodes(void **state)
{
    (void)state;
    enum { N = 15, ROW = N + 1 };
    whirl_chain *c = whirl_chain_alloc_uniform(N, 0);
    const double omega[3] = {150, 2, 60};
    double r[3 * ROW], z[3 * ROW], t[3 * ROW], r1[ROW], z1[ROW], t1[ROW];
    for (size_t i = 0; i < 3 * ROW; i++) r[i] = z[i] = t[i] = NAN;
    whirl_shape_info info[3], one;
    int exists[3];
    assert_int_equal(whirl_nlink_branch_nodes(c, 7, 3, omega, info, exists, r, z, t),
                     GSL_SUCCESS);
    assert_true(exists[0] && !exists[1] && exists[2]);
    for (size_t i = 0; i < ROW; i++) assert_true(isnan(r[ROW + i]) && isnan(t[ROW + i]));
    for (size_t j = 0; j < 3; j += 2) {
        assert_int_equal(whirl_nlink_solve_nodes(c, omega[j], 7, &one, r1, z1, t1), GSL_SUCCESS);
        assert_true(r[j * ROW] == 0);
        for (size_t i = 0; i < ROW; i++) {
            assert_float_equal(r[j * ROW + i], r1[i], 1e-15);
            assert_float_equal(z[j * ROW + i], z1[i], 1e-15);
            assert_float_equal(t[j * ROW + i], t1[i], 1e-15 * t1[i]);
        }
        assert_float_equal(info[j].tip_r, r[j * ROW + N], 1e-12 * info[j].tip_r);
    }
    assert_int_equal(whirl_nlink_branch_nodes(c, 7, 3, omega, info, exists, r, NULL, t),
                     GSL_EINVAL);
    whirl_chain_free(c);
}

/* The folds of the path of mode k of c up to omega_max, in their order, into omega[] (at most
 * max); with cap > 0, every step at most cap. Returns their number. */
static int fold_list(const whirl_chain *c, int mode, double omega_max, double cap, double *omega,
                     int max)
{
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    assert_int_equal(whirl_nlink_path_birth(p, mode), GSL_SUCCESS);
    int nf = 0;
    while (p->omega <= omega_max) {
        if (cap > 0 && p->ds > cap) p->ds = cap;
        assert_int_equal(whirl_nlink_path_step(p), GSL_SUCCESS);
        /* the index of the force balance changes by one at each fold, and nowhere else */
        int singular = 0;
        for (int e = 0; e < p->n_events; e++) singular += p->event[e].kind != WHIRL_EVENT_RETURN;
        /* the index and the last step's: the path's state (src/steady/nlink_path_internal.h) */
        const path_state *st = &path_of(p)->s;
        if (p->angles && st->last.angles)
            assert_int_equal(abs(st->index - st->last.index), singular);
        for (int e = 0; e < p->n_events; e++)
            if (p->event[e].kind == WHIRL_EVENT_FOLD) {
                assert_true(nf < max);
                omega[nf++] = p->event[e].omega;
            }
    }
    print_message("N = %zu mode %d to omega %.4g, steps %s %g: %ld steps, %d folds\n", c->n,
                  mode, omega_max, cap > 0 ? "capped to" : "up to", cap > 0 ? cap : p->ds,
                  p->steps, nf);
    whirl_nlink_path_free(p);
    return nf;
}

/* The folds of mode k of the uniform chain of n links up to factor times its birth, with the
 * path's own step control and with steps of at most 0.003: the same folds, at the same rates
 * (to 1e-10), in the same order; at least min_folds of them. */
static void same_folds(size_t n, int mode, double factor, int min_folds)
{
    whirl_chain *c = whirl_chain_alloc_uniform(n, 0);
    double *crit = malloc((size_t)mode * sizeof *crit);
    assert_non_null(crit);
    assert_int_equal(whirl_nlink_critical(c, (size_t)mode, crit), GSL_SUCCESS);
    enum { MAX = 200 };
    double own[MAX], fine[MAX];
    const int n_own = fold_list(c, mode, factor * crit[mode - 1], 0, own, MAX);
    const int n_fine = fold_list(c, mode, factor * crit[mode - 1], 0.003, fine, MAX);
    int same = 0;
    double worst = 0;
    while (same < n_own && same < n_fine && fabs(own[same] - fine[same]) <= 1e-10 * fine[same]) {
        worst = fmax(worst, fabs(own[same] - fine[same]) / fine[same]);
        same++;
    }
    if (same < n_fine)
        print_message("  fold number %d, at omega %.10g, passed over\n", same + 1,
                      fine[same]);
    print_message("  %d folds agree, to %.2e in omega\n", same, worst);
    assert_true(n_fine >= min_folds);
    assert_int_equal(n_own, n_fine);
    assert_int_equal(same, n_fine);
    free(crit);
    whirl_chain_free(c);
}

/* A middle mode of a long chain folds many times on its way up, in S-shaped pairs of folds
 * (a maximum and a minimum of the rate) that can be as small as 2e-4 in omega: the path with
 * its own step control finds each fold that the path with steps of at most 0.003 (a thirtieth
 * of the largest) finds, none passed over by a step, at the same rates. */
static void test_many_folds(void **state)
{
    (void)state;
    same_folds(250, 80, 2, 41);
}

/* Mode 75 of 300 links up to twice its birth: one S of two folds (omega 142.09756 and 142.09903,
 * 0.0015 apart) lay within one step whose ends had the same index, the same orientation and
 * tangents and chord the tests accept; the path went over it (110 folds of 112). The eigenvalue
 * of the force balance nearest zero crosses zero and back there, which its cubic interpolant
 * over the step shows. */
static void test_pair_in_step(void **state)
{
    (void)state;
    same_folds(300, 75, 2, 112);
}

/* What the progress reports of a continuation are checked against: the fold events visited so
 * far (follow visits a step's events before the next report) and the previous report. */
typedef struct progress_check {
    long folds_visited, reports, last_steps;
    double last_hi;
    int bad; /* a report disagreed */
} progress_check;

static int count_folds(void *ctx, size_t j, const whirl_shape_info *info,
                       const whirl_branch_event *event)
{
    (void)j;
    (void)info;
    if (event && event->kind == WHIRL_EVENT_FOLD) ((progress_check *)ctx)->folds_visited++;
    return 0;
}

static void check_progress(void *ctx, const whirl_nlink_progress *at)
{
    progress_check *k = ctx;
    if (at->mode != 80 || at->steps % 256 != 0 || at->steps != k->last_steps + 256 * (k->reports > 0)
        || at->steps_max != 100000 || at->folds != k->folds_visited || at->omega > at->omega_hi
        || at->omega_hi < k->last_hi || at->omega < at->omega_birth || !(at->arclength >= 0))
        k->bad++;
    k->reports++;
    k->last_steps = at->steps;
    k->last_hi = at->omega_hi;
}

/* The options of the drivers: the progress reports agree with what the path visits (folds,
 * steps every 256, the default bound 100000 for 250 links), a bound set by the caller stops
 * the path there with a message naming the mode and the rate reached, a bound not reached
 * changes nothing, and a negative one is refused. */
static void test_follow_options(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(250, 0);
    double crit[80];
    assert_int_equal(whirl_nlink_critical(c, 80, crit), GSL_SUCCESS);
    progress_check k = {0, 0, 0, 0, 0};
    whirl_nlink_follow_options opt = whirl_nlink_follow_defaults(c);
    assert_int_equal(opt.steps_max, 100000); /* 200 per link is less for 250 links */
    assert_null(opt.progress);
    whirl_chain *long_chain = whirl_chain_alloc_uniform(1000, 0);
    assert_int_equal(whirl_nlink_follow_defaults(long_chain).steps_max, 200000);
    whirl_chain_free(long_chain);
    opt.progress = check_progress;
    opt.progress_ctx = &k;
    assert_int_equal(whirl_nlink_follow_opt(c, 80, 2 * crit[79], 0, NULL, count_folds, &k, &opt),
                     GSL_SUCCESS);
    print_message("  N = 250 mode 80 to twice its birth: %ld progress reports, %ld folds\n",
                  k.reports, k.folds_visited);
    assert_int_equal(k.bad, 0);
    assert_true(k.reports >= 3);
    assert_true(k.folds_visited > 40);
    /* the same path under a bound it stays within: the same folds */
    progress_check again = {0, 0, 0, 0, 0};
    opt = (whirl_nlink_follow_options){k.last_steps + 256, NULL, NULL};
    assert_int_equal(whirl_nlink_follow_opt(c, 80, 2 * crit[79], 0, NULL, count_folds, &again,
                                            &opt), GSL_SUCCESS);
    assert_int_equal(again.folds_visited, k.folds_visited);
    /* a bound the path needs more than: GSL_EMAXITER, from follow and from solve */
    opt.steps_max = 300;
    assert_int_equal(whirl_nlink_follow_opt(c, 80, 2 * crit[79], 0, NULL, count_folds, &again,
                                            &opt), GSL_EMAXITER);
    assert_non_null(strstr(whirl_last_error(), "mode 80: 300 continuation steps"));
    double *nodes = malloc(3 * 251 * sizeof *nodes);
    assert_non_null(nodes);
    whirl_shape_info info;
    assert_int_equal(whirl_nlink_solve_nodes_opt(c, 2 * crit[79], 80, &info, nodes, nodes + 251,
                                                 nodes + 502, &opt), GSL_EMAXITER);
    assert_non_null(strstr(whirl_last_error(), "mode 80: 300 continuation steps"));
    opt.steps_max = -1;
    assert_int_equal(whirl_nlink_solve_nodes_opt(c, 2 * crit[79], 80, &info, nodes, nodes + 251,
                                                 nodes + 502, &opt), GSL_EINVAL);
    free(nodes);
    whirl_chain_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_critical_laguerre), cmocka_unit_test(test_branch_continuous),
        cmocka_unit_test(test_birth_linear_shape), cmocka_unit_test(test_retrace),
        cmocka_unit_test(test_folds),              cmocka_unit_test(test_every_mode),
        cmocka_unit_test(test_birth_gap),          cmocka_unit_test(test_underflowed_tail),
        cmocka_unit_test(test_branch_birth_gap),
        cmocka_unit_test(test_high_rates),         cmocka_unit_test(test_every_mode_high),
        cmocka_unit_test(test_retrace_high),       cmocka_unit_test(test_errors),
        cmocka_unit_test(test_nodes_lengths),
        cmocka_unit_test(test_heavy_tip),          cmocka_unit_test(test_heavy_tip_jumps),
        cmocka_unit_test(test_birth_in_angles),    cmocka_unit_test(test_near_births),
        cmocka_unit_test(test_corners),
        cmocka_unit_test(test_wide_chains),        cmocka_unit_test(test_no_false_return),
        cmocka_unit_test(test_stalled_branch),     cmocka_unit_test(test_unlocated_event),
        cmocka_unit_test(test_branch_nodes),
        cmocka_unit_test(test_many_folds),         cmocka_unit_test(test_pair_in_step),
        cmocka_unit_test(test_follow_options),
    };
    return cmocka_run_group_tests_name("nlink_path", tests, NULL, NULL);
}
