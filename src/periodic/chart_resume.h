/* Internal: the charts resumed after their finished rates (whirl periodic --chart --resume).
 *
 * Both charts go from rate to rate carrying what they know of their curves: the vertical chart
 * its followers (each curve's family, last two amplitudes, whether it ended at a tongue's tip)
 * and the tips reached, the ellipse chart whether the last rate was stable at e = 0, the curve
 * under way and the continuations that failed. That state after a finished rate, written as
 * lines of text (the doubles with 17 digits: read back bit for bit) and read back, makes the
 * rates after it the same as in an uninterrupted chart: a rate's points depend on the state and
 * the rate alone. The lines:
 *   vertical columns=J count=C curves=K tips=T [drag=C]   (J rates finished, C curves begun;
 *                                                  the linear air drag if not 0, 17 digits:
 *                                                  a state of another drag is refused)
 *   curve I KIND MODE ID ALIVE TIPWARD A1 A0 W1 TIP FILL_TOP   (K of them: the alive curves
 *                                                  and those ended at a tip; none: "none")
 *   tip OMEGA MODE TOP0 TOP1                        (T of them; the highest amplitude an edge
 *                                                  of each function came down from, 0: none)
 * and for the ellipse chart the single line
 *   ellipse columns=J prev=P curve=C failed=F
 * A state read back is checked whole (counts, ranges, finite numbers): GSL_EINVAL with "state
 * line N: what" otherwise. */
#ifndef WHIRL_CHART_RESUME_H
#define WHIRL_CHART_RESUME_H

#include "whirl/periodic.h"

/* The save callback (whirl_chart_save_fn, whirl/periodic.h). */
typedef whirl_chart_save_fn chart_save_fn;

/* whirl_chart_vertical_damped (air_drag 0: whirl_chart_vertical) from the state (NULL: from the
 * first rate), save called as above (may be NULL). */
int chart_vertical_run(const whirl_chain *c, int dim, const whirl_chart_params *params,
                       double air_drag, const char *state, whirl_chart_row_fn row,
                       void *row_data, whirl_chart_tick_fn tick, void *tick_data,
                       chart_save_fn save, void *save_data);

/* whirl_chart_ellipse from the state (NULL: from the first rate), save as above. */
int chart_ellipse_run(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                      const char *state, whirl_ellipse_chart_row_fn row, void *row_data,
                      whirl_ellipse_chart_tick_fn tick, void *tick_data, chart_save_fn save,
                      void *save_data);

/* The rate of column j of both charts: columns rates from lo to hi, both ends included. */
double chart_grid(double lo, double hi, int columns, int j);

/* ---- the vertical chart's internals (chart.c), its state (chart_state.c) ---- */

typedef struct chart_curve {
    whirl_floquet_edge kind;
    int sub;       /* the conservative chart's function of the kind: 0 u'(T/2) (+1) or u(T/2)
                      (-1), 1 v(T/2) or v'(T/2) (chart.c); always 0 with drag */
    int mode;      /* the mode whose factor's root it is (from 0, by increasing lambda) */
    int id;
    int alive;
    double a1, a0; /* the amplitude at the last rate and the one before (NAN: none; after a tip
                      or a fold the point one rate back on the edge's law or the fold's cap,
                      within 2 amp_max of the range: chart_tips.c, chart_folds.c) */
    int found;     /* located at the current rate */
    double w1;     /* the rate of a1 */
    int tipward;   /* (hanging) ended at a tongue's tip, its other edge not yet joined; (damped
                      hanging) ended low, a new edge of its family may join it */
    double tip;    /* that tip's rate; damped: the rate it ended at (NAN: none) */
    double fill_top; /* the highest amplitude of the other edge located from the tip (0: none) */
} chart_curve;

typedef struct chart_tip {
    double omega;
    int mode;
    double top[2]; /* per function (sub), the highest amplitude an edge came down from (0:
                      none) */
} chart_tip;

typedef struct chart chart;

/* One thread's workspace: the family and the rate of its evaluations. */
typedef struct chart_ws {
    const chart *ch;
    long monodromies;
    int mode;                /* of the root under way */
    whirl_floquet_edge kind; /* of the root under way */
    int sub;                 /* of the root under way */
    double shift;       /* (f(h/2) - f(h)) / 15 at the last fine evaluation of kind */
    double omega;       /* the rate of the evaluations; NAN: the chart's current rate */
    double amp;         /* the amplitude of fine_rate */
} chart_ws;

struct chart {
    const whirl_chain *c;
    whirl_chart_params p;
    chart_ws *ws;       /* one per thread */
    int threads;
    double omega;       /* the current rate */
    chart_curve *curves;
    int count, cap;
    int n;              /* the modes */
    double *coef;       /* sigma lambda_k (chart_modes.c), n */
    int *steps;         /* the coarser monodromy's steps per period, per mode */
    double *freq;       /* the unshaken chain's frequencies sqrt(g lambda_k) (hanging), n */
    int subs;           /* functions per kind: 2 (the half period's, conservative), 1 (drag) */
    chart_tip *tips;    /* the tips reached so far (one curve descends to each) */
    int tips_count, tips_cap;
    double drag;        /* the linear air drag c (whirl_model's), >= 0 */
    double gamma;       /* the modes' decay rate c l_i / m_i (chart_modes.c); 0 without drag */
};


/* chart.c's functions for chart_tips.c: the extrapolated function of ctx's (a chart_ws) mode,
 * kind and sub at the amplitude amp (its rate s->omega, NAN: the chart's) and at the rate omega
 * (its amplitude s->amp), whirl_root_fn's; the lowest amplitude of a bracket; 1 if the chart's
 * edges reach A = 0 at tongues' tips (the conservative hanging chain's). */
int chart_fine_edge(double amp, void *ctx, double *fx);
int chart_fine_rate(double omega, void *ctx, double *fx);
double chart_amp_floor(const chart *ch);
int chart_has_tips(const chart *ch);

/* ---- the tips (chart_tips.c, its header: why and how) ---- */
/* The edge cv ended at this rate heading for A = 0, with a tip of its mode's tongues of its kind
 * between its last rate and two rates on: its points down to the tip; if they reach it and no
 * edge did before, the tip (2 omega_k / n, 0) and the tongue's other edge from the tip up to the
 * next rate, all on cv's curve, cv waiting for that edge (tipward). */
int chart_descend_to_tip(chart *ch, chart_curve *cv, int column, whirl_chart_row_fn row,
                         void *row_data);
/* A new edge cv at this rate joined (*joined 1) to the other function's edge of its family that
 * ended at a tongue's tip at most two and a half rates before: one curve, cv's points down to
 * what was located from the tip. */
int chart_join_at_tip(chart *ch, chart_curve *cv, int column, whirl_chart_row_fn row,
                      void *row_data, int *joined);
/* A new edge cv given the number of the neighbouring edge of its family's other function at
 * this rate when the two bound one tongue there and that number is the edge's alone (hanging,
 * conservative). */
int chart_pair(chart *ch, chart_curve *cv);
/* The damped hanging chart (else nothing): cv ended at this rate not through the top, at its
 * tongue's lowest point perhaps: it waits (tipward, tip its last rate) two and a half rates for
 * a new edge of its family (chart_low_window ends the wait, at each rate), which chart_join_low
 * joins (*joined 1) when the rate between them lies inside the tongue at the higher of their
 * amplitudes. */
void chart_low_end(chart *ch, chart_curve *cv);
void chart_low_window(chart *ch);
int chart_join_low(chart *ch, chart_curve *cv, int *joined);
/* An edge's points at the amplitudes a, a + da, ... while in (a_lo, a_hi), each located in the
 * rate between w and tip on cv's function (chart_tips.c); the last amplitude located in *last. */
int chart_fill_rows(chart *ch, const chart_curve *cv, int column, double w, double tip,
                    double a, double da, double a_lo, double a_hi, double *last,
                    whirl_chart_row_fn row, void *row_data);
/* ---- the folds (chart_folds.c) ---- */
/* The caps of the edges that turned back in omega between the last rate and this one: among the
 * curves from first on (this rate's new ones), each pair of neighbouring edges of one function
 * born there gets the points of its turn, at the rows between them. */
int chart_fold_caps(chart *ch, int first, int column, whirl_chart_row_fn row, void *row_data);
/* The tip 2 omega_k / n in (w0, w1] of a tongue of the mode whose edges are of the kind (n odd:
 * -1, even: +1), the one nearest w1; NAN if none. */
double chart_tip_in(const chart *ch, double w0, double w1, int mode, whirl_floquet_edge kind);

/* The state of ch after `done` rates into *text (malloc'd). GSL_ENOMEM with a message. */
int chart_state_write(const chart *ch, int done, char **text);
/* ch's curves and tips from the state text (ch's modes and parameters set); *done: the rates
 * finished. GSL_EINVAL or GSL_ENOMEM with a message. */
int chart_state_read(chart *ch, const char *text, int *done);

#endif
