/* The window search of stability_windows.c over any source of squared eigenvalues mu = lambda^2
 * of a family of linearisations in omega (the N-link chain's reduced problem, the continuum's
 * collocation): internal to the library. */
#ifndef WHIRL_WINDOWS_INTERNAL_H
#define WHIRL_WINDOWS_INTERNAL_H

#include <stddef.h>

#include "whirl/stability.h"

typedef struct windows_source {
    /* Every mu of the linearisation about the mode's shape at omega, with signatures if asked
     * (whirl_spectrum; pointers valid until the next call). */
    int (*spectrum)(void *data, double omega, int signatures, whirl_spectrum *out);
    /* The two mu nearest the real shift sigma at omega (nearest first), GSL_CONTINUE when they
     * are not obtained that way (the search then uses spectrum); NULL: never. */
    int (*pair)(void *data, double omega, double sigma, double *mu_re, double *mu_im);
    void *data;                  /* passed to both */
    int mode;                    /* for messages */
    whirl_windows_stats *stats;  /* counts of the search (the source counts its shapes) */
} windows_source;

/* The scan's rates for mode k born at birth: from max(omega_min, birth (1 + 1e-6)) to omega_max
 * in steps of p->scan_step, both ends included; *omega malloc'ed (caller frees). GSL_EINVAL on
 * bad parameters, GSL_EDOM if the range ends before the birth. */
int whirl_windows_range(const whirl_windows_params *p, int mode, double birth, double **omega,
                        size_t *npts);

/* The windows over the scan omega[0..npts-1] (stability_windows.c's header comment; the range's
 * end is p->omega_max). */
int whirl_windows_search(const windows_source *src, const whirl_windows_params *p,
                         const double *omega, size_t npts, whirl_window *windows, size_t max,
                         size_t *count);

#endif
