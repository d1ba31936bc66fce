/* What the page's files share (whirl_web.c: the answers' JSON, the query read as the page's
 * state, the shape, branches and windows; web_run.c: the perturbed and the shaken run;
 * web_floquet.c: the shaken settings' periodic motion and Floquet multipliers). Internal:
 * not installed, not exported (the shared library exports whirl_ symbols alone). */
#ifndef WHIRL_WEB_INTERNAL_H
#define WHIRL_WEB_INTERNAL_H

#include <stddef.h>

#include "whirl/chain.h"

#define VERDICT_LINKS 30    /* the N-link chain whose linearisation gives the continuum's verdict */
#define SHAKE_WORK_MAX 5e7  /* the most link-steps of a shaken run (~30 s as WebAssembly) */
#define PIVOT_MAX 256       /* the longest pivot path read [bytes] */

/* ---- the answer: a growing JSON text ---- */

typedef struct json {
    char *text;
    size_t len, cap;
    int failed; /* out of memory: the answer becomes NULL */
} json;

/* printf's format appended to the text (j->failed set when out of memory). */
void web_put(json *j, const char *fmt, ...);
/* x, in the fewest digits that read back to it ("null" if not finite). */
void web_put_number(json *j, double x);
/* A JSON string: quotes, backslashes and control characters escaped. */
void web_put_string(json *j, const char *s);
/* ',"key":x': a member after the first. */
void web_put_key_number(json *j, const char *key, double x);
/* The text closed and handed over (NULL when out of memory). */
char *web_finish(json *j);
/* {"error": message, "field": field} */
char *web_error_answer(const char *field, const char *message);

/* ---- the state: the query read with the command line's units ---- */

typedef struct web_state {
    double length, mass, tip; /* [m, kg, kg] */
    int links, mode;
    double omega, rmax;       /* [rad/s] */
    double unit;              /* rad/s per unit of the rate as given */
    const char *unit_name;    /* "Hz", "rpm", "rad/s" */
    double time;              /* the library's unit of time sqrt(L/g) [s] */
    double w, w_max;          /* omega, rmax in sqrt(g/L) */
    double m_tip;             /* tip / mass */
    whirl_frame frame;        /* the run's view: co-rotating (default) or inertial */
    double drag, drag2;       /* the air drag of the runs, in the library's units */
    double drag_si, drag2_si; /* the same as given [kg/(m s), kg/m^2] */
    char pivot[PIVOT_MAX];    /* the shaken run's pivot path (whirl_pivot_parse), "" or "none" */
    double shake_w;           /* its rate [sqrt(g/L)] */
    double shake_omega;       /* the same as given [rad/s] */
    int inverted;             /* the shaken run starts standing up (1) or hanging (0) */
    double tilt;              /* each link of its start turned by tilt [rad] */
    char field[16];           /* the parameter of a failure */
    char message[512];
} web_state;

/* The failure of field with its message (printf's format); 1. */
int web_state_fail(web_state *s, const char *field, const char *fmt, ...);
/* The library's last failure with its quantities in SI, as the state's failure; 1. */
int web_library_fail(web_state *s, const char *field);
/* The query read into s; 0, or 1 with s's failure. */
int web_read_state(web_state *s, const char *query);
/* The rate where mode is born on the hanging chain c (NULL: the continuum) [sqrt(g/L)]. */
int web_birth(web_state *s, const whirl_chain *c, int mode, double *w);
/* The chain of n links with the state's tip mass; NULL with s's failure. */
whirl_chain *web_chain_of(web_state *s, int n);

#endif
