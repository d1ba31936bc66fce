/* The audit of the N-link continuation (src/nlink_path.c) on random chains: every mode of every
 * chain followed from its birth to its first crossing of 10 times the birth, as the README's
 * tables of random chains count it.
 *
 * The chains: GSL's mt19937 seeded with the seed; per chain N uniform in 2..NMAX
 * (gsl_rng_uniform_int), then the N lengths, then the N masses, each 10^(D (2u - 1)) for u
 * uniform in [0, 1) (lengths and masses over 2 D decades; the README's "six decades" is D = 3),
 * gravity 1. A mode's run stops at an error of the path or at MAX_STEPS steps.
 *
 * Usage: bench_random_chains [OUT [SEEDS [CHAINS [D [NMAX]]]]], SEEDS a range "A-B" or one seed
 * (default out/bench 1-12 300 3 12); bench_random_chains --chain SEED INDEX [D [NMAX]] prints the
 * arguments "--length l_1,..,l_N --mass m_1,..,m_N" of chain INDEX (from 0) of SEED, for
 * tests/tools/branch_mp.py (the 40-digit continuation that decides a mode's end). Writes
 * OUT/random_chains.csv, a row per mode:
 *   seed,chain,links,mode,status,steps,folds,branch_points,returns,theta_1,..
 * (status 0: reached 10 times the birth, and the link angles there follow, NMAX of them, empty
 * beyond N; otherwise the GSL status, the angles empty), and prints per seed and in all: the
 * modes, those that stop (with the message of each), the steps, the modes that take a branch
 * point and the folds. Two versions of the library are compared by their CSV files: the ends
 * that moved, up to the mirror image (tests/tools/branch_mp.py decides which is right). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/steady.h"

#define BENCH_NAME "bench_random_chains"
#include "bench_util.h"

#define MAX_STEPS 200000 /* per mode: a run that needs more is counted as stopping */
#define NMAX_LIMIT 64

typedef struct tally {
    long modes, stops, steps, branch_modes, folds;
} tally;

/* One chain: every mode to 10 times its birth, a row each. */
static void run_chain(FILE *csv, int seed, int index, size_t n, const double *length,
                      const double *mass, int nmax, tally *t)
{
    whirl_chain *c = whirl_chain_alloc(n, length, mass, 1);
    if (c == NULL) bench_die("chain");
    double crit[NMAX_LIMIT];
    if (whirl_nlink_critical(c, (int)n, crit)) bench_die("critical rates");
    whirl_nlink_path *p = whirl_nlink_path_alloc(c);
    if (p == NULL) bench_die("path");
    for (int k = 1; k <= (int)n; k++) {
        int status = whirl_nlink_path_birth(p, k);
        const double target = 10 * crit[k - 1];
        long folds = 0, branch_points = 0, returns = 0;
        int found = 0, capped = 0;
        double tip[WHIRL_PATH_EVENTS_MAX + 1];
        while (!status && !found) {
            if (p->steps >= MAX_STEPS) {
                status = GSL_EMAXITER;
                capped = 1;
                break;
            }
            status = whirl_nlink_path_step(p);
            for (int e = 0; e < p->n_events; e++) {
                folds += p->event[e].kind == WHIRL_EVENT_FOLD;
                branch_points += p->event[e].kind == WHIRL_EVENT_BRANCH_POINT;
                returns += p->event[e].kind == WHIRL_EVENT_RETURN;
            }
            if (!status) {
                found = whirl_nlink_path_crossings(p, target, WHIRL_PATH_EVENTS_MAX + 1, tip);
                if (found < 0) status = -found;
            }
        }
        t->modes++;
        t->steps += p->steps;
        t->folds += folds;
        t->branch_modes += branch_points > 0;
        if (status) {
            t->stops++;
            if (capped)
                printf("  seed %d chain %d (%zu links): mode %d: not at 10 times its birth after "
                       "%d steps\n", seed, index, n, k, MAX_STEPS);
            else
                printf("  seed %d chain %d (%zu links): %s\n", seed, index, n, whirl_last_error());
        }
        fprintf(csv, "%d,%d,%zu,%d,%d,%ld,%ld,%ld,%ld", seed, index, n, k, status, p->steps,
                folds, branch_points, returns);
        for (int i = 0; i < nmax; i++) {
            if (!status && i < (int)n) fprintf(csv, ",%.17g", whirl_nlink_path_cross_theta(p)[i]);
            else fputs(",", csv);
        }
        fputc('\n', csv);
    }
    whirl_nlink_path_free(p);
    whirl_chain_free(c);
}

/* "A" or "A-B" (0 <= A <= B) into *first, *last; 0 if the text is not that. */
static int parse_seeds(const char *text, int *first, int *last)
{
    char *end;
    long a = strtol(text, &end, 10), b = a;
    if (end == text) return 0;
    if (*end == '-') {
        const char *from = end + 1;
        b = strtol(from, &end, 10);
        if (end == from) return 0;
    }
    if (*end != '\0' || a < 0 || b < a || b > 1000000) return 0;
    *first = (int)a, *last = (int)b;
    return 1;
}

/* text as a number in [lo, hi] into *x; 0 if it is not one. */
static int parse_number(const char *text, double lo, double hi, double *x)
{
    char *end;
    *x = strtod(text, &end);
    return end != text && *end == '\0' && *x >= lo && *x <= hi;
}

/* The draw's D and NMAX from argv[at] and argv[at + 1], where given (else left as they are);
 * 0 if either is not a number in its range (0 <= D <= 12, 2 <= NMAX <= NMAX_LIMIT, whole). */
static int parse_draw(int argc, char **argv, int at, double *decades, double *nmax)
{
    return !(argc > at && !parse_number(argv[at], 0, 12, decades)) &&
           !(argc > at + 1 &&
             !(parse_number(argv[at + 1], 2, NMAX_LIMIT, nmax) && *nmax == floor(*nmax)));
}

/* The next chain of the draw: N in 2..nmax, then its N lengths and N masses, each 10^(D (2u - 1)).
 * Returns N. */
static size_t draw_chain(gsl_rng *r, double decades, int nmax, double *length, double *mass)
{
    const size_t n = 2 + gsl_rng_uniform_int(r, (unsigned long)nmax - 1);
    for (size_t i = 0; i < n; i++) length[i] = pow(10, decades * (2 * gsl_rng_uniform(r) - 1));
    for (size_t i = 0; i < n; i++) mass[i] = pow(10, decades * (2 * gsl_rng_uniform(r) - 1));
    return n;
}

/* --chain SEED INDEX [D [NMAX]]: the chain's arguments for tests/tools/branch_mp.py. */
static int print_chain(int argc, char **argv)
{
    double seed, index, decades = 3, nmax_x = 12;
    if (argc < 4 || argc > 6 || !(parse_number(argv[2], 0, 1000000, &seed) &&
                                  seed == floor(seed)) ||
        !(parse_number(argv[3], 0, 1e7, &index) && index == floor(index)) ||
        !parse_draw(argc, argv, 4, &decades, &nmax_x)) {
        fprintf(stderr, "%s: usage: %s --chain SEED INDEX [D [NMAX]] (0 <= D <= 12, 2 <= NMAX <= "
                "%d)\n", BENCH_NAME, BENCH_NAME, NMAX_LIMIT);
        return 2;
    }
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (r == NULL) bench_die("random numbers");
    gsl_rng_set(r, (unsigned long)seed);
    double length[NMAX_LIMIT], mass[NMAX_LIMIT];
    size_t n = 0;
    for (long k = 0; k <= (long)index; k++) n = draw_chain(r, decades, (int)nmax_x, length, mass);
    gsl_rng_free(r);
    const double *lists[2] = {length, mass};
    for (int j = 0; j < 2; j++) {
        fputs(j ? " --mass " : "--length ", stdout);
        for (size_t i = 0; i < n; i++) printf("%s%.17g", i ? "," : "", lists[j][i]);
    }
    printf("\n");
    return 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--chain") == 0) return print_chain(argc, argv);
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    int first = 1, last = 12;
    double chains_x = 300, decades = 3, nmax_x = 12;
    if ((argc > 2 && !parse_seeds(argv[2], &first, &last)) ||
        (argc > 3 && !(parse_number(argv[3], 1, 1e7, &chains_x) && chains_x == floor(chains_x))) ||
        !parse_draw(argc, argv, 4, &decades, &nmax_x) || argc > 6) {
        fprintf(stderr, "%s: usage: %s [OUT [SEEDS [CHAINS [D [NMAX]]]]] (SEEDS A-B with 0 <= A "
                "<= B, CHAINS >= 1, 0 <= D <= 12, 2 <= NMAX <= %d)\n", BENCH_NAME, BENCH_NAME,
                NMAX_LIMIT);
        return 2;
    }
    const int chains = (int)chains_x, nmax = (int)nmax_x;
    gsl_set_error_handler_off();
    FILE *csv = bench_open_csv(dir, "random_chains.csv");
    fputs("seed,chain,links,mode,status,steps,folds,branch_points,returns", csv);
    for (int i = 1; i <= nmax; i++) fprintf(csv, ",theta_%d", i);
    fputc('\n', csv);
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (r == NULL) bench_die("random numbers");
    tally all = {0, 0, 0, 0, 0};
    const double t0 = bench_now();
    printf("random chains: lengths and masses over %g decades, N in 2..%d, %d chains per seed\n",
           2 * decades, nmax, chains);
    for (int seed = first; seed <= last; seed++) {
        gsl_rng_set(r, (unsigned long)seed);
        tally t = {0, 0, 0, 0, 0};
        for (int index = 0; index < chains; index++) {
            double length[NMAX_LIMIT], mass[NMAX_LIMIT];
            const size_t n = draw_chain(r, decades, nmax, length, mass);
            run_chain(csv, seed, index, n, length, mass, nmax, &t);
        }
        printf("seed %d: %ld modes, %ld stop, %ld steps, %ld take a branch point, %ld folds\n",
               seed, t.modes, t.stops, t.steps, t.branch_modes, t.folds);
        all.modes += t.modes, all.stops += t.stops, all.steps += t.steps;
        all.branch_modes += t.branch_modes, all.folds += t.folds;
    }
    printf("all: %ld modes, %ld stop, %ld steps, %ld take a branch point, %ld folds (%.1f s)\n",
           all.modes, all.stops, all.steps, all.branch_modes, all.folds, bench_now() - t0);
    gsl_rng_free(r);
    if (fclose(csv)) bench_die("writing random_chains.csv");
    return 0;
}
