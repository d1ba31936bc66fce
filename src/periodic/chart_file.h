/* Internal: the charts' file as whirl periodic --chart writes it, and reading it back to resume
 * (the command line's --resume, whirl_chart_vertical_read and whirl_chart_ellipse_read): one
 * implementation of its header and of every rule a file read back must pass.
 *
 * A chart is written whole at the end (its rows by curve, gnuplot's blank line between curves),
 * also when stopped: then with only the rates finished and a comment line saying so. Its lines:
 *   the header: the comment lines that record every option changing a row, the "# units:" line
 *     and the columns' line (matched line for line: core/resume.h);
 *   among them the lines "# found: ..." (the counts, and where a stopped chart stopped);
 *   the rows;
 *   at the end the lines "# state: ...": the chart's state after its finished rates
 *     (chart_resume.h), from which a resume goes on as if it had never stopped.
 * Read back: the header must be this run's; every row is checked by its chart (its fields, a
 * rate and a value in the chart's range; against the state: a curve begun, a rate finished) and
 * here (no row twice, as many rows as the "# found: points=" line says, no comment among them
 * but the state's); the rates finished are the state's. Failures: GSL_EINVAL (a file refused,
 * its line named) or GSL_ENOMEM, with the message. */
#ifndef WHIRL_CHART_FILE_H
#define WHIRL_CHART_FILE_H

#include <stdio.h>

#include "core/resume.h"
#include "whirl/periodic.h"

#define CHART_FOUND "# found: "
#define CHART_STATE "# state: "

/* The units of the file, as the command line's (cli_units): SI when physical, for a chain of
 * length [m], mass [kg], gravity [m/s^2]; mass_given 0 adds the line saying M = 1 kg is
 * assumed. */
typedef struct chart_units {
    int physical;
    double length, mass, gravity;
    int mass_given;
} chart_units;

/* The scale of a rate, a length and a linear drag per length in the file (cli_units_scale's). */
double chart_units_rate(const chart_units *u);
double chart_units_drag(const chart_units *u);

/* A row read back: its text (with the newline), line, curve (from 1), rate and second value as
 * written (the file's units), and the rest of its fields: the vertical chart's edge (+1, -1) and
 * err, the ellipse chart's event (WHIRL_CYCLE_POINT for "none"), err, whether it is an end of a
 * curve on e = 0 and its rate's index (-1 at an end). */
typedef struct chart_kept {
    char *line;
    long lineno;
    int curve;
    double omega, value, err;
    int edge;
    whirl_cycle_event event;
    int end;
    int column;
} chart_kept;

/* A chart's file read back. */
typedef struct chart_read {
    whirl_resume *in;   /* kept for the refusals after the reading */
    chart_kept *kept;
    size_t n_kept;
    char *state;        /* the state's lines, without their prefix */
    size_t state_cap;
    int done;           /* the rates the state has finished (its columns=) */
} chart_read;

/* The first number after "key=" in the state's text, or fallback. */
long chart_state_value(const char *state, const char *key, long fallback);

/* The vertical chart's header into fp: params with its defaults applied
 * (chart_vertical_defaults), the chain of links links, the drag; found (NULL: none) the
 * "# found:" lines, written where they belong. */
void chart_vertical_defaults(whirl_chart_params *p);
void chart_vertical_head(FILE *fp, const whirl_chart_params *p, int links, double drag,
                         const chart_units *u, const char *found);
/* The vertical chart's file in read back (path: its name in messages): r filled. */
int chart_vertical_read(chart_read *r, FILE *in, const char *path, const whirl_chart_params *p,
                        int links, double drag, const chart_units *u);

/* The same for the ellipse chart. */
void chart_ellipse_defaults(whirl_ellipse_chart_params *p);
void chart_ellipse_head(FILE *fp, const whirl_ellipse_chart_params *p, int links,
                        const chart_units *u, const char *found);
int chart_ellipse_read(chart_read *r, FILE *in, const char *path,
                       const whirl_ellipse_chart_params *p, int links, const chart_units *u);

void chart_read_free(chart_read *r);

#endif
