/* Internal: the integrator object and the interface each method family implements
 * (integrator.c: the driver and rk4; integrator_gauss.c; integrator_rk8.c; integrator_gsl.c). */
#ifndef WHIRL_INTEGRATOR_INTERNAL_H
#define WHIRL_INTEGRATOR_INTERNAL_H

#include <stddef.h>

#include "whirl/integrator.h"

/* A method (the public whirl_integrator_type). */
struct whirl_integrator_type {
    const char *name;
    int adaptive; /* 1 if advance with tol > 0 is allowed */
    const void *params; /* method-specific constant data (tableau, GSL step type) */
    int (*alloc)(struct whirl_integrator *it);
    void (*free)(void *state);
    /* One step of size h from (t, y), y in place, unprojected (the driver restores y on
     * failure). NULL: adaptive steps only. */
    int (*step)(struct whirl_integrator *it, double t, double h, double *y);
    /* One adaptive step towards t1 (tolerance tol): advances *t, may change *h. */
    int (*adaptive_step)(struct whirl_integrator *it, double *t, double t1, double *h, double tol,
                         double *y);
    /* The state y was changed outside the integrator (forget history). May be NULL. */
    void (*restart)(struct whirl_integrator *it);
};
typedef struct whirl_integrator_type integrator_method;

struct whirl_integrator {
    const integrator_method *method;
    whirl_system sys; /* a copy of the caller's */
    size_t size;
    whirl_integrator_stats stats;
    void *state;     /* the method's workspace */
    double *last_y;  /* the state the previous advance returned (history is valid for it) */
    double *backup;  /* the state before the current step */
    double last_t;
    int has_last;
    unsigned long adaptive_steps; /* accepted adaptive steps over the integrator's life */
    unsigned long max_steps;      /* cap on adaptive steps, accepted plus rejected */
};

/* Right-hand side with the evaluation counted in it->stats. */
int whirl_integrator_rhs(struct whirl_integrator *it, double t, const double *y, double *dydt);

#endif
