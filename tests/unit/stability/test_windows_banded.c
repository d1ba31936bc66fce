/* Tests of the banded path of the N-link window search (src/stability/nlink_banded.c)
 * against the dense path (every mu of A' by dgeev, signatures from its eigenvectors):
 *  - the bound it rests on, on the dense spectrum: every mu with |mu| > omega^2 is neutral and of
 *    positive energy;
 *  - the kept mu: every dense mu with |mu| <= omega^2 is kept, each kept mu is a dense mu to
 *    1e-10 of max(|mu|, omega^2) with the same Krein signature, the kept ones beyond omega^2 are
 *    neutral and of positive energy (the first of them ends the set), and the growth is the
 *    dense one; at neutral and unstable rates of modes 2-4 (and 2 and 6 at omega 14.3, 19.7), on a
 *    uniform and a non-uniform chain;
 *  - the windows of a search by the banded path against those of the dense path (--full), with
 *    no evaluation handed over to the dense one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "whirl/stability.h"
#include "stability/windows_internal.h"

/* A non-uniform chain of n links (lengths and masses varying along it, g != 1). */
static whirl_chain *uneven_chain(size_t n)
{
    double *len = malloc(n * sizeof *len), *mass = malloc(n * sizeof *mass);
    for (size_t i = 0; i < n; i++) {
        len[i] = (1 + 0.3 * sin(1.7 * (double)i + 0.3)) / (double)n;
        mass[i] = (1 + 0.25 * cos(2.3 * (double)i)) / (double)n;
    }
    whirl_chain *c = whirl_chain_alloc(n, len, mass, 1.37);
    free(len);
    free(mass);
    return c;
}

/* The dense and banded spectra of mode k of c at omega compared; 1 if the rate is unstable. */
static int compare_at(whirl_windows *w, whirl_stability *lin, const whirl_chain *c, int mode,
                      double omega)
{
    whirl_model m = {.chain = c, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_shape_info info;
    /* the shape and its linearisation as whirl_stability_mode makes them, without its growth (a
     * dgeev of the whole first-order system, three quarters of this test's time, read nowhere) */
    double *x = malloc((c->n + 1) * sizeof *x), *z = malloc((c->n + 1) * sizeof *z),
           *tension = malloc((c->n + 1) * sizeof *tension);
    assert_int_equal(whirl_nlink_solve_nodes(c, omega, mode, &info, x, z, tension), 0);
    assert_int_equal(whirl_stability_linearise(lin, &m, x, z), 0);
    free(x), free(z), free(tension);
    whirl_spectrum sp;
    assert_int_equal(whirl_windows_spectrum(w, lin, 1, &sp), 0);
    const size_t nd = sp.count;
    double *dre = malloc(nd * sizeof *dre), *dim = malloc(nd * sizeof *dim);
    int *dsig = malloc(nd * sizeof *dsig);
    memcpy(dre, sp.re, nd * sizeof *dre);
    memcpy(dim, sp.im, nd * sizeof *dim);
    memcpy(dsig, sp.signature, nd * sizeof *dsig);
    const double dgrowth = sp.growth, dlevel = sp.level, om2 = omega * omega;
    size_t inside = 0;
    for (size_t i = 0; i < nd; i++) {
        if (hypot(dre[i], dim[i]) <= om2) {
            inside++;
            continue;
        }
        /* beyond omega^2: neutral, positive energy */
        assert_true(sqrt(fmax(0, (hypot(dre[i], dim[i]) + dre[i]) / 2)) <= dlevel);
        assert_int_equal(dsig[i], 1);
    }
    assert_int_equal(whirl_windows_spectrum_banded(w, c, omega, lin, 1, &sp), 0);
    size_t kept_inside = 0, beyond = 0;
    for (size_t i = 0; i < sp.count; i++) {
        const double mod = hypot(sp.re[i], sp.im[i]);
        size_t best = 0;
        for (size_t k = 1; k < nd; k++)
            if (hypot(dre[k] - sp.re[i], dim[k] - sp.im[i]) <
                hypot(dre[best] - sp.re[i], dim[best] - sp.im[i]))
                best = k;
        assert_true(hypot(dre[best] - sp.re[i], dim[best] - sp.im[i]) <= 1e-10 * fmax(mod, om2));
        assert_int_equal(sp.signature[i], dsig[best]);
        if (mod <= om2) {
            kept_inside++;
        } else {
            beyond++;
            assert_int_equal(sp.signature[i], 1);
        }
    }
    assert_int_equal(kept_inside, inside);
    assert_true(beyond >= 1);
    assert_true(fabs(sp.growth - dgrowth) <= 1e-10 * fmax(dgrowth, omega));
    /* the round-off level: from the out-of-plane block's largest |mu|, not the whole A' */
    assert_true(sp.level >= 0.9 * dlevel && sp.level <= 1.1 * dlevel);
    free(dre);
    free(dim);
    free(dsig);
    return dgrowth > 0;
}

static void compare_chain(whirl_chain *c, int mode_max, double omega_max, int *neutral,
                          int *unstable)
{
    whirl_windows *w = whirl_windows_alloc(c->n);
    whirl_stability *lin = whirl_stability_alloc(c->n);
    double crit[8];
    assert_int_equal(whirl_nlink_critical(c, (size_t)mode_max, crit), 0);
    for (int mode = 2; mode <= mode_max; mode++)
        for (double omega = crit[mode - 1] * 1.03; omega < omega_max; omega += 0.83) {
            if (compare_at(w, lin, c, mode, omega))
                ++*unstable;
            else
                ++*neutral;
        }
    whirl_stability_free(lin);
    whirl_windows_free(w);
}

static void test_spectrum(void **state)
{
    (void)state;
    int neutral = 0, unstable = 0;
    whirl_chain *c = whirl_chain_alloc_uniform(100, 0);
    compare_chain(c, 4, 11, &neutral, &unstable);
    /* inside the windows of mode 2 (4.39..4.56 and from 9.68) */
    whirl_windows *w = whirl_windows_alloc(c->n);
    whirl_stability *lin = whirl_stability_alloc(c->n);
    assert_true(compare_at(w, lin, c, 2, 4.47));
    assert_true(compare_at(w, lin, c, 2, 9.9));
    /* high rates: some tens of mu kept */
    for (int mode = 2; mode <= 6; mode += 4)
        for (double omega = 14.3; omega < 25; omega += 5.4)
            if (compare_at(w, lin, c, mode, omega))
                unstable++;
            else
                neutral++;
    whirl_stability_free(lin);
    whirl_windows_free(w);
    whirl_chain_free(c);
    c = uneven_chain(48);
    compare_chain(c, 3, 9, &neutral, &unstable);
    whirl_chain_free(c);
    print_message("# banded against dense: %d neutral, %d unstable rates\n", neutral, unstable);
    assert_true(neutral > 20 && unstable > 3);
}

/* The windows of modes 2 and 3 of a 40-link chain by the banded path and by the dense one. */
static void test_windows(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(40, 0);
    whirl_windows *w = whirl_windows_alloc(c->n);
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_max = 9;
    size_t total = 0;
    for (int mode = 2; mode <= 3; mode++) {
        whirl_window fast[16], dense[16];
        size_t nfast, ndense;
        whirl_windows_stats st;
        p.krylov = 1;
        assert_int_equal(whirl_windows_find(w, c, mode, &p, fast, 16, &nfast, &st), 0);
        assert_int_equal(whirl_windows_fallbacks(w), 0);
        p.krylov = 0;
        assert_int_equal(whirl_windows_find(w, c, mode, &p, dense, 16, &ndense, &st), 0);
        assert_int_equal(nfast, ndense);
        for (size_t i = 0; i < nfast; i++) {
            print_message("# mode %d: [%.12f, %.12f] and [%.12f, %.12f]\n", mode, fast[i].from,
                          fast[i].to, dense[i].from, dense[i].to);
            assert_true(fabs(fast[i].from - dense[i].from) <= 1e-9);
            assert_true(fabs(fast[i].to - dense[i].to) <= 1e-9);
            assert_int_equal(fast[i].open_from, dense[i].open_from);
            assert_int_equal(fast[i].open_to, dense[i].open_to);
            assert_true(fabs(fast[i].max_growth - dense[i].max_growth) <=
                        1e-8 * dense[i].max_growth);
        }
        total += nfast;
    }
    assert_true(total >= 3);
    whirl_windows_free(w);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spectrum),
        cmocka_unit_test(test_windows),
    };
    return cmocka_run_group_tests_name("tests", tests, NULL, NULL);
}
