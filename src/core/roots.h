/* Internal: the one bracketing root finder of the library, Brent's method (Brent 1973,
 * "Algorithms for minimization without derivatives", ch. 4; GSL's gsl_root_fsolver_brent).
 *
 * Given f(lo) and f(hi) of opposite signs (or one of them zero), Brent's method keeps a bracket
 * [lower, upper] of a sign change and shrinks it by inverse quadratic interpolation, the secant
 * or bisection, whichever is safe; it converges superlinearly on a smooth f and never slower
 * than bisection. Every iteration costs one evaluation of f. */
#ifndef WHIRL_CORE_ROOTS_H
#define WHIRL_CORE_ROOTS_H

/* The function: f(x) into *fx, GSL_SUCCESS or a failure status (the first failure ends the
 * search and is returned; f sets its message). f polls the stop request where its cost calls
 * for it (WHIRL_EINTERRUPTED); the finder itself does not. */
typedef int (*whirl_root_fn)(double x, void *ctx, double *fx);

typedef struct whirl_root_opts {
    /* converged when gsl_root_test_interval(lower, upper, epsabs, epsrel) succeeds:
     * upper - lower < epsabs + epsrel min(|lower|, |upper|) (min 0 if they differ in sign).
     * A test upper - lower <= w is epsabs = nextafter(w, INFINITY), epsrel = 0. */
    double epsabs, epsrel;
    int max_iter; /* Brent iterations at most (evaluations of f after the two ends) */
    /* known != 0: f_lo = f(lo) and f_hi = f(hi) are known, and f is not called at the ends
     * to start (an f with side effects, or an expensive one, is evaluated there once) */
    int known;
    double f_lo, f_hi;
} whirl_root_opts;

typedef struct whirl_root {
    double root;         /* Brent's estimate: the end of the bracket with the smaller |f| */
    double lower, upper; /* the last bracket */
    int iterations;      /* iterations done */
    int bracketed;       /* 1 if the search started: f at lo and hi finite, of opposite signs or
                          * one zero, and lo <= hi (GSL's conditions); else 0 */
} whirl_root;

/* Brent's method on f from the bracket [lo, hi]. Returns
 *  - GSL_SUCCESS when the bracket passed the test of o;
 *  - GSL_EMAXITER when it did not within o->max_iter iterations (no message: out holds the last
 *    estimate, which some callers accept);
 *  - f's first failure status;
 *  - GSL's status of a bracket it refuses (out->bracketed = 0: GSL_EINVAL, no sign change;
 *    GSL_EBADFUNC, f not finite) or of an iteration that fails (f not finite), no message;
 *  - GSL_ENOMEM, with its message.
 * out (all fields) is written in every case: the estimate where the search stopped (the
 * midpoint of [lo, hi] and the bracket [lo, hi] if no iteration was done). */
int whirl_root_brent(whirl_root_fn f, void *ctx, double lo, double hi, const whirl_root_opts *o,
                     whirl_root *out);

/* Brent's minimiser (Brent 1973, ch. 5; GSL's gsl_min_fminimizer_brent): golden sections and
 * parabolic interpolation within a bracket lo < x < hi with f(x) below f(lo) and f(hi), one
 * evaluation of f per iteration. The one minimisation loop of the library. */
typedef struct whirl_min_opts {
    /* converged when gsl_min_test_interval(lower, upper, epsabs, epsrel) succeeds */
    double epsabs, epsrel;
    int max_iter; /* iterations at most; the estimate after them is taken as it is */
    double below; /* stop as soon as the least value found is below it (-INFINITY: never) */
} whirl_min_opts;

typedef struct whirl_min {
    double x, f;         /* the least value found and where (the start's if no iteration) */
    double lower, upper; /* the last bracket */
    int iterations;      /* iterations done */
    int below;           /* 1 if it stopped on f < o->below */
} whirl_min;

/* Brent's minimisation of f from x in [lo, hi], the values fx, f_lo, f_hi known (f is not called
 * there). Returns
 *  - GSL_SUCCESS when the bracket passed the test of o, f fell below o->below, or o->max_iter
 *    iterations were done (out holds the last estimate);
 *  - f's first failure status;
 *  - GSL's status of a start it refuses (GSL_EINVAL: x outside (lo, hi) or f(x) not below both
 *    ends) or of an iteration that fails (GSL_FAILURE: no progress on a flat f), no message;
 *  - GSL_ENOMEM, with its message.
 * out (all fields) is written in every case. */
int whirl_min_brent(whirl_root_fn f, void *ctx, double x, double fx, double lo, double f_lo,
                    double hi, double f_hi, const whirl_min_opts *o, whirl_min *out);

#endif
