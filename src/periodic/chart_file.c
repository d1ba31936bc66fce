/* The charts' file read back (chart_file.h): the reading shared by both charts, and
 * whirl_chart_vertical_read, whirl_chart_ellipse_read over a file's bytes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "periodic/chart_file.h"
#include "periodic/chart_resume.h"

/* The longest line of a chart file: a row is five numbers (at most ~130 characters), a state's
 * line at most 400 (chart_state.c) and its prefix. */
#define CHART_LINE_MAX 1024

double chart_units_rate(const chart_units *u)
{
    return sqrt(u->gravity / u->length);
}

double chart_units_drag(const chart_units *u)
{
    return u->mass * chart_units_rate(u) / u->length;
}

long chart_state_value(const char *state, const char *key, long fallback)
{
    const size_t len = strlen(key);
    for (const char *s = state; s && (s = strstr(s, key)) != NULL; s += len)
        if ((s == state || s[-1] == ' ') && s[len] == '=') {
            char *end;
            const long x = strtol(s + len + 1, &end, 10);
            return end == s + len + 1 ? fallback : x;
        }
    return fallback;
}

static int by_text(const void *a, const void *b)
{
    const chart_kept *p = *(const chart_kept *const *)a, *q = *(const chart_kept *const *)b;
    const int c = strcmp(p->line, q->line);
    return c ? c : (p->lineno > q->lineno) - (p->lineno < q->lineno);
}

static int refuse_at(chart_read *r, const chart_kept *k, const char *why)
{
    whirl_resume_refuse_at(r->in, k->lineno, "%s", why);
    return GSL_EINVAL;
}

/* A row read twice: the later one refused. */
static int duplicates(chart_read *r)
{
    if (r->n_kept < 2) return GSL_SUCCESS;
    const chart_kept **order = malloc(r->n_kept * sizeof *order);
    if (order == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    for (size_t i = 0; i < r->n_kept; i++) order[i] = &r->kept[i];
    qsort(order, r->n_kept, sizeof *order, by_text);
    int status = GSL_SUCCESS;
    for (size_t i = 1; i < r->n_kept && status == GSL_SUCCESS; i++)
        if (strcmp(order[i]->line, order[i - 1]->line) == 0) {
            char why[64];
            snprintf(why, sizeof why, "the row of line %ld again", order[i - 1]->lineno);
            status = refuse_at(r, order[i], why);
        }
    free(order);
    return status;
}

/* text appended to the state (grown as needed). */
static int state_append(chart_read *r, const char *text)
{
    const size_t have = r->state ? strlen(r->state) : 0, len = strlen(text);
    if (have + len + 1 > r->state_cap) {
        const size_t cap = 2 * (have + len + 1) + 256;
        char *s = realloc(r->state, cap);
        if (s == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        r->state = s, r->state_cap = cap;
    }
    memcpy(r->state + have, text, len + 1);
    return GSL_SUCCESS;
}

typedef const char *(*row_check)(const void *ctx, const char *line, chart_kept *k);

static int refuse(chart_read *r, const char *why)
{
    whirl_resume_refuse(r->in, "%s", why);
    return GSL_EINVAL;
}

/* One line of the file after the header's (or a "# found: " line among them). */
static int read_line(chart_read *r, whirl_resume_kind kind, const char *line, long *points,
                     row_check check, const void *ctx)
{
    const size_t len = strlen(line);
    if (kind == WHIRL_RESUME_NOTE) {
        if (line[0] == '\n') return GSL_SUCCESS; /* a break between curves */
        if (strncmp(line, CHART_STATE, strlen(CHART_STATE)) == 0)
            return state_append(r, line + strlen(CHART_STATE));
        if (strncmp(line, CHART_FOUND, strlen(CHART_FOUND)) != 0 || r->n_kept > 0 || r->state)
            return refuse(r, "a comment among the rows");
        if (strncmp(line + strlen(CHART_FOUND), "points=", 7) != 0) return GSL_SUCCESS;
        char *end;
        const long p = strtol(line + strlen(CHART_FOUND) + 7, &end, 10);
        if (*points >= 0 || end == line + strlen(CHART_FOUND) + 7 || p < 0)
            return refuse(r, "a second or unreadable count of the points");
        *points = p;
        return GSL_SUCCESS;
    }
    if (r->state) return refuse(r, "a row after the chart's state");
    chart_kept k = {.lineno = whirl_resume_lineno(r->in), .column = -1};
    const char *why = check(ctx, line, &k);
    if (why) return refuse(r, why);
    if ((r->n_kept & (r->n_kept - 1)) == 0) { /* 0, 1, 2, 4, ...: doubled */
        chart_kept *grown = realloc(r->kept, (r->n_kept ? 2 * r->n_kept : 1) * sizeof *grown);
        if (grown == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
        r->kept = grown;
    }
    if ((k.line = malloc(len + 1)) == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    memcpy(k.line, line, len + 1);
    r->kept[r->n_kept++] = k;
    return GSL_SUCCESS;
}

/* The file in read into r: the header matched, the rows checked by check, the state's lines
 * gathered, the rows counted and compared. */
static int read_file(chart_read *r, FILE *in, const char *path, const char *header,
                     row_check check, const void *ctx)
{
    *r = (chart_read){.done = -1};
    const whirl_resume_params rp = {.header = header, .kind = "chart", .of = "options",
                                    .note = CHART_FOUND, .line_max = CHART_LINE_MAX, .blank = 1};
    if ((r->in = whirl_resume_alloc(in, path, &rp)) == NULL) return GSL_ENOMEM;
    long points = -1;
    int status = GSL_SUCCESS;
    const char *line;
    for (whirl_resume_kind kind;
         status == GSL_SUCCESS && (kind = whirl_resume_next(r->in, &line)) != WHIRL_RESUME_END;)
        status = kind == WHIRL_RESUME_ERROR ? whirl_last_status()
                                            : read_line(r, kind, line, &points, check, ctx);
    if (status) return status;
    if (r->state == NULL)
        return whirl_fail(GSL_EINVAL, "'%s' holds no chart state (its '%s' lines at the end): "
                          "not a chart of this version, or cut short", path, CHART_STATE);
    if (points != (long)r->n_kept)
        return whirl_fail(GSL_EINVAL, "'%s' holds %zu rows where its '%spoints=' line says "
                          "%ld: rows were removed or added; the file cannot be trusted", path,
                          r->n_kept, CHART_FOUND, points);
    r->done = (int)chart_state_value(r->state, "columns", -1);
    return duplicates(r);
}

/* The header of a chart into a string (to free), or NULL (GSL_ENOMEM). */
static char *head_text(void (*head)(FILE *, const void *, int, double, const chart_units *),
                       const void *p, int links, double drag, const chart_units *u)
{
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    if (mem == NULL) {
        whirl_fail(GSL_ENOMEM, "out of memory");
        return NULL;
    }
    head(mem, p, links, drag, u);
    if (fclose(mem) != 0) {
        free(text);
        whirl_fail(GSL_ENOMEM, "out of memory");
        return NULL;
    }
    return text;
}

void chart_read_free(chart_read *r)
{
    for (size_t i = 0; i < r->n_kept; i++) free(r->kept[i].line);
    free(r->kept);
    free(r->state);
    whirl_resume_free(r->in);
    *r = (chart_read){0};
}

/* ---- the vertical chart ---- */

static const char *unit(const chart_units *u, const char *si, const char *scaled)
{
    return u->physical ? si : scaled;
}

static void units_comment(FILE *fp, const chart_units *u)
{
    char m[WHIRL_FORMAT_MAX];
    whirl_write_units_line(fp, u->physical, u->length, u->mass, u->gravity);
    if (u->physical && !u->mass_given)
        fprintf(fp, "# mass: M=%s kg assumed (no --mass given); masses, forces and tensions "
                    "scale with M\n", whirl_format_double(m, u->mass));
}

void chart_vertical_defaults(whirl_chart_params *p)
{
    if (p->columns == 0) p->columns = 200;
    if (p->rows == 0) p->rows = 200;
    if (p->steps == 0) p->steps = 200;
    if (p->tol == 0) p->tol = 1e-10;
    if (p->amp_min == 0) p->amp_min = p->amp_max / p->rows;
}

void chart_vertical_head(FILE *fp, const whirl_chart_params *p, int links, double drag,
                         const chart_units *u, const char *found)
{
    const double rate = chart_units_rate(u), len = u->length;
    const char *ru = unit(u, "rad/s", "sqrt(g/L)"), *lu = unit(u, "m", "L");
    char a[WHIRL_FORMAT_MAX], b[WHIRL_FORMAT_MAX], c[WHIRL_FORMAT_MAX], d[WHIRL_FORMAT_MAX];
    char dragged[96] = "";
    if (drag > 0)
        snprintf(dragged, sizeof dragged, " drag=%s %s",
                 whirl_format_double(a, drag * chart_units_drag(u)),
                 unit(u, "kg/(m s)", "M sqrt(g/L)/L"));
    fprintf(fp, "# chart: the %s chain shaken vertically, A cos(omega t); links=%d steps=%d "
            "tol=%s %s%s; edge +1: a multiplier %s +1, -1: through -1 (period doubling)\n",
            p->inverted ? "inverted" : "hanging", links, p->steps,
            whirl_format_double(b, p->tol * len), lu, dragged,
            drag > 0 ? "through" : "pair through");
    fprintf(fp, "# omega from %s to %s %s (%d rates); A from %s to %s %s (%d rows scanned)\n",
            whirl_format_double(a, p->omega_min * rate),
            whirl_format_double(b, p->omega_max * rate), ru, p->columns,
            whirl_format_double(c, p->amp_min * len), whirl_format_double(d, p->amp_max * len),
            lu, p->rows);
    if (found) fputs(found, fp);
    units_comment(fp, u);
    fprintf(fp, "curve,edge,omega,amplitude,err\n");
}

/* The check of a row read back: its fields (the reader has checked their count and that they
 * are finite), a rate and an amplitude in the chart's range. */
typedef struct vertical_ctx {
    double omega_lo, omega_hi, amp_hi; /* the file's units, widened by 1e-12 */
} vertical_ctx;

static const char *vertical_row(const void *data, const char *line, chart_kept *k)
{
    const vertical_ctx *c = data;
    int end = -1;
    if (sscanf(line, "%d,%d,%lf,%lf,%lf%n", &k->curve, &k->edge, &k->omega, &k->value, &k->err,
               &end) != 5 || line[end] != '\n')
        return "not a row curve,edge,omega,amplitude,err";
    if (k->curve < 1) return "a curve number below 1";
    if (k->edge != 1 && k->edge != -1) return "an edge other than 1 or -1";
    if (!(k->omega >= c->omega_lo && k->omega <= c->omega_hi)) return "a rate outside the chart";
    if (!(k->value >= 0 && k->value <= c->amp_hi)) return "an amplitude outside the chart";
    if (!(k->err >= 0)) return "a negative error";
    return NULL;
}

/* The rows read back against the state: a curve it has begun, a rate it has reached (a point
 * near a tongue's tip lies up to a rate beyond the last one finished, chart.c). */
static int vertical_kept(chart_read *r, const whirl_chart_params *p, double rate)
{
    const long count = chart_state_value(r->state, "count", -1);
    const int done = r->done;
    if (count < 0 || done < 0 || done > p->columns) return 0; /* the library refuses the state */
    const double reach = done == 0 ? 0 : chart_grid(p->omega_min, p->omega_max, p->columns,
                                                    done < p->columns ? done : done - 1) * rate;
    for (size_t i = 0; i < r->n_kept; i++) {
        const chart_kept *k = &r->kept[i];
        if (k->curve > count) return refuse_at(r, k, "a curve the chart's state has not begun");
        if (k->omega > reach * (1 + 1e-12))
            return refuse_at(r, k, "a rate beyond those the state has finished");
    }
    return GSL_SUCCESS;
}

static void vertical_head(FILE *fp, const void *p, int links, double drag, const chart_units *u)
{
    chart_vertical_head(fp, p, links, drag, u, NULL);
}

int chart_vertical_read(chart_read *r, FILE *in, const char *path, const whirl_chart_params *p,
                        int links, double drag, const chart_units *u)
{
    const double rate = chart_units_rate(u), len = u->length;
    const vertical_ctx ctx = {.omega_lo = p->omega_min * rate * (1 - 1e-12),
                              .omega_hi = p->omega_max * rate * (1 + 1e-12),
                              .amp_hi = p->amp_max * len * (1 + 1e-12)};
    *r = (chart_read){.done = -1};
    char *head = head_text(vertical_head, p, links, drag, u);
    if (head == NULL) return GSL_ENOMEM;
    int status = read_file(r, in, path, head, vertical_row, &ctx);
    if (status == GSL_SUCCESS) status = vertical_kept(r, p, rate);
    free(head);
    return status;
}

/* ---- the ellipse chart ---- */

void chart_ellipse_defaults(whirl_ellipse_chart_params *p)
{
    if (p->columns == 0) p->columns = 50;
    if (p->e_max == 0) p->e_max = 1;
    if (p->mode == 0) p->mode = 2;
    if (p->steps == 0) p->steps = 400;
    if (p->step == 0) p->step = 0.01;
}

void chart_ellipse_head(FILE *fp, const whirl_ellipse_chart_params *p, int links,
                        const chart_units *u, const char *found)
{
    const double rate = chart_units_rate(u);
    char a[WHIRL_FORMAT_MAX], b[WHIRL_FORMAT_MAX], c[WHIRL_FORMAT_MAX];
    fprintf(fp, "# chart: the ellipticity of the hand-swung chain: pivot (a cos wt, a (1 - e) "
            "sin wt, 0), a=%s %s; the steady shape of mode %d (side %d) followed in e from the "
            "circle to where it is lost; links=%d steps=%d arc_step=%s\n",
            whirl_format_double(a, p->radius * u->length), unit(u, "m", "L"), p->mode, p->side,
            links, p->steps, whirl_format_double(b, p->step));
    fprintf(fp, "# omega from %s to %s %s (%d rates); e up to %s\n",
            whirl_format_double(a, p->omega_min * rate),
            whirl_format_double(b, p->omega_max * rate), unit(u, "rad/s", "sqrt(g/L)"),
            p->columns, whirl_format_double(c, p->e_max));
    if (found) fputs(found, fp);
    fprintf(fp, "# event: how the shape is lost (fold, branch: +1; period-doubling: -1; torus: "
            "two pairs meet on the unit circle); rows with ellipticity 0 end a curve where the "
            "circle's shape itself changes stability; err: in e, or in omega at an end\n");
    units_comment(fp, u);
    fprintf(fp, "curve,event,omega,ellipticity,err\n");
}

/* The check of a row read back: its fields, a rate in the chart's range, an ellipticity up to
 * e_max. */
typedef struct ellipse_ctx {
    double omega_lo, omega_hi, e_max; /* the file's units, the rates widened by 1e-12 */
} ellipse_ctx;

static const char *ellipse_row(const void *data, const char *line, chart_kept *k)
{
    const ellipse_ctx *c = data;
    char event[24];
    int end = -1;
    if (sscanf(line, "%d,%23[a-z-],%lf,%lf,%lf%n", &k->curve, event, &k->omega, &k->value,
               &k->err, &end) != 5 || line[end] != '\n')
        return "not a row curve,event,omega,ellipticity,err";
    const int none = strcmp(event, "none") == 0;
    k->event = WHIRL_CYCLE_POINT;
    for (int e = WHIRL_CYCLE_FOLD; e <= WHIRL_CYCLE_TORUS; e++)
        if (strcmp(event, whirl_cycle_event_name((whirl_cycle_event)e)) == 0)
            k->event = (whirl_cycle_event)e;
    if (!none && k->event == WHIRL_CYCLE_POINT)
        return "an event not fold, branch, period-doubling, torus or none";
    if (k->curve < 1) return "a curve number below 1";
    if (!(k->omega >= c->omega_lo && k->omega <= c->omega_hi)) return "a rate outside the chart";
    if (!(k->value >= 0 && k->value <= c->e_max)) return "an ellipticity outside 0..e_max";
    if (!(k->err >= 0)) return "a negative error";
    k->end = k->value == 0 && !none;
    if (none && k->value != c->e_max) return "none below e_max";
    return NULL;
}

/* The rows read back against the state: a curve it has begun, a rate it has finished (a row of
 * a rate: one of the grid's, once; an end: between two of them). */
static int ellipse_kept(chart_read *r, const whirl_ellipse_chart_params *p, double rate)
{
    const long curve = chart_state_value(r->state, "curve", -2);
    const int done = r->done;
    if (curve < -1 || done < 0 || done > p->columns) return 0; /* the library refuses it */
    char *seen = calloc((size_t)done + 1, 1);
    if (seen == NULL) return whirl_fail(GSL_ENOMEM, "out of memory");
    int status = GSL_SUCCESS;
    for (size_t i = 0; i < r->n_kept && status == GSL_SUCCESS; i++) {
        chart_kept *k = &r->kept[i];
        const char *why = NULL;
        int j = 0;
        char a[WHIRL_FORMAT_MAX], b[WHIRL_FORMAT_MAX];
        if (k->curve > curve + 1) why = "a curve the chart's state has not begun";
        else if (k->end) {
            if (done == 0 || k->omega > chart_grid(p->omega_min, p->omega_max, p->columns,
                                                  done - 1) * rate * (1 + 1e-12))
                why = "an end beyond the rates the state has finished";
        } else {
            while (j < done &&
                   strcmp(whirl_format_double(a, chart_grid(p->omega_min, p->omega_max,
                                                            p->columns, j) * rate),
                          whirl_format_double(b, k->omega)) != 0)
                j++;
            if (j == done) why = "a rate not on the grid of the rates the state has finished";
            else if (seen[j]++) why = "a second row of its rate";
            else k->column = j;
        }
        if (why) status = refuse_at(r, k, why);
    }
    free(seen);
    return status;
}

static void ellipse_head(FILE *fp, const void *p, int links, double drag, const chart_units *u)
{
    (void)drag;
    chart_ellipse_head(fp, p, links, u, NULL);
}

int chart_ellipse_read(chart_read *r, FILE *in, const char *path,
                       const whirl_ellipse_chart_params *p, int links, const chart_units *u)
{
    const double rate = chart_units_rate(u);
    const ellipse_ctx ctx = {.omega_lo = p->omega_min * rate * (1 - 1e-12),
                             .omega_hi = p->omega_max * rate * (1 + 1e-12), .e_max = p->e_max};
    *r = (chart_read){.done = -1};
    char *head = head_text(ellipse_head, p, links, 0, u);
    if (head == NULL) return GSL_ENOMEM;
    int status = read_file(r, in, path, head, ellipse_row, &ctx);
    if (status == GSL_SUCCESS) status = ellipse_kept(r, p, rate);
    free(head);
    return status;
}

/* ---- the public readers over a file's bytes ---- */

/* data as a stream (NULL: GSL_EINVAL for no bytes, GSL_ENOMEM). */
static FILE *open_bytes(const char *data, size_t size, const char *path)
{
    if (size == 0) { /* (fmemopen of no bytes may fail) */
        whirl_fail(GSL_EINVAL, "'%s' is empty: no chart of these options", path);
        return NULL;
    }
    FILE *in = fmemopen((void *)data, size, "r");
    if (in == NULL) whirl_fail(GSL_ENOMEM, "out of memory");
    return in;
}

static int check_units(int physical, double length, double mass, double gravity,
                       chart_units *u, int mass_given)
{
    *u = (chart_units){.physical = physical != 0, .length = 1, .mass = 1, .gravity = 1,
                       .mass_given = mass_given != 0};
    if (!physical) return GSL_SUCCESS;
    if (!(length > 0 && mass > 0 && gravity > 0 && isfinite(length) && isfinite(mass) &&
          isfinite(gravity)))
        return whirl_fail(GSL_EINVAL, "the units' length, mass and gravity must be positive and "
                          "finite");
    u->length = length, u->mass = mass, u->gravity = gravity;
    return GSL_SUCCESS;
}

int whirl_chart_vertical_read(const char *data, size_t size, const char *path,
                              const whirl_chart_params *params, int links, double air_drag,
                              int physical, double length, double mass, double gravity,
                              int mass_given, whirl_chart_row_fn row, void *row_data,
                              whirl_chart_save_fn state, void *state_data)
{
    chart_units u;
    int status = check_units(physical, length, mass, gravity, &u, mass_given);
    if (status) return status;
    whirl_chart_params p = params ? *params : (whirl_chart_params){0};
    chart_vertical_defaults(&p);
    FILE *in = open_bytes(data, size, path ? path : "the chart's file");
    if (in == NULL) return whirl_last_status();
    chart_read r;
    status = chart_vertical_read(&r, in, path ? path : "the chart's file", &p, links, air_drag,
                                 &u);
    fclose(in);
    for (size_t i = 0; status == GSL_SUCCESS && row && i < r.n_kept; i++) {
        const chart_kept *k = &r.kept[i];
        const whirl_chart_point pt = {
            .kind = k->edge > 0 ? WHIRL_FLOQUET_EDGE_PLUS_ONE : WHIRL_FLOQUET_EDGE_MINUS_ONE,
            .curve = k->curve - 1, .column = -1, .omega = k->omega, .amplitude = k->value,
            .err = k->err};
        status = row(row_data, &pt);
    }
    if (status == GSL_SUCCESS && state) status = state(state_data, r.done, r.state);
    chart_read_free(&r);
    return status;
}

int whirl_chart_ellipse_read(const char *data, size_t size, const char *path,
                             const whirl_ellipse_chart_params *params, int links, int physical,
                             double length, double mass, double gravity, int mass_given,
                             whirl_ellipse_chart_row_fn row, void *row_data,
                             whirl_chart_save_fn state, void *state_data)
{
    chart_units u;
    int status = check_units(physical, length, mass, gravity, &u, mass_given);
    if (status) return status;
    whirl_ellipse_chart_params p = params ? *params : (whirl_ellipse_chart_params){0};
    chart_ellipse_defaults(&p);
    FILE *in = open_bytes(data, size, path ? path : "the chart's file");
    if (in == NULL) return whirl_last_status();
    chart_read r;
    status = chart_ellipse_read(&r, in, path ? path : "the chart's file", &p, links, &u);
    fclose(in);
    for (size_t i = 0; status == GSL_SUCCESS && row && i < r.n_kept; i++) {
        const chart_kept *k = &r.kept[i];
        const whirl_ellipse_point pt = {.event = k->event, .curve = k->curve - 1,
                                        .column = k->end ? -1 : k->column, .omega = k->omega,
                                        .ellipticity = k->value, .err = k->err,
                                        .max_modulus = NAN};
        status = row(row_data, &pt);
    }
    if (status == GSL_SUCCESS && state) status = state(state_data, r.done, r.state);
    chart_read_free(&r);
    return status;
}
