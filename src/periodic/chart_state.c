/* The vertical chart's state after its finished rates, as text and back (chart_resume.h): the
 * curves a later rate can touch (the alive ones, followed on; those ended at a tongue's tip, which
 * a new edge may join) and the tips reached. The curves ended otherwise are counted only: their
 * numbers are taken, and nothing reads them again. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "periodic/chart_resume.h"

#define STATE_LINE_MAX 400   /* a curve's line: 11 fields, the doubles at most 24 characters */
#define STATE_COUNT_MAX 1000000 /* curves and tips: far above any chart's (a few per mode) */

/* %.17g (read back bit for bit), or "none" for NAN. */
static const char *num(char *buf, double x)
{
    if (isnan(x)) return "none";
    snprintf(buf, 32, "%.17g", x);
    return buf;
}

int chart_state_write(const chart *ch, int done, char **text)
{
    int listed = 0;
    for (int i = 0; i < ch->count; i++) listed += ch->curves[i].alive || ch->curves[i].tipward;
    const size_t size = (size_t)(2 + listed + ch->tips_count) * STATE_LINE_MAX;
    char *t = malloc(size);
    if (t == NULL) return whirl_fail(GSL_ENOMEM, "out of memory for the chart's state");
    size_t len = (size_t)snprintf(t, size, "vertical columns=%d count=%d curves=%d tips=%d",
                                  done, ch->count, listed, ch->tips_count);
    if (ch->drag > 0) { /* absent without drag: the conservative chart's state as before */
        char b[32];
        len += (size_t)snprintf(t + len, size - len, " drag=%s", num(b, ch->drag));
    }
    len += (size_t)snprintf(t + len, size - len, "\n");
    for (int i = 0; i < ch->count; i++) {
        const chart_curve *cv = &ch->curves[i];
        if (!cv->alive && !cv->tipward) continue;
        char b[6][32];
        len += (size_t)snprintf(t + len, size - len, "curve %d %d %d %d %d %d %s %s %s %s %s\n",
                                i, (int)cv->kind + 2 * cv->sub, cv->mode, cv->id, cv->alive,
                                cv->tipward,
                                num(b[0], cv->a1), num(b[1], cv->a0), num(b[2], cv->w1),
                                num(b[3], cv->tip), num(b[4], cv->fill_top));
    }
    for (int i = 0; i < ch->tips_count; i++) {
        char b[32];
        char b1[32], b2[32];
        len += (size_t)snprintf(t + len, size - len, "tip %s %d %s %s\n",
                                num(b, ch->tips[i].omega), ch->tips[i].mode,
                                num(b1, ch->tips[i].top[0]), num(b2, ch->tips[i].top[1]));
    }
    *text = t;
    return GSL_SUCCESS;
}

/* The reading of one line: its words one by one. */
typedef struct reader {
    const char *s; /* the rest of the line */
    int line;
    const char *why; /* the first thing wrong, or NULL */
} reader;

/* The next word of the line into w (at most size - 1 characters); 0 at the line's end. */
static int next_word(reader *r, char *w, size_t size)
{
    r->s += strspn(r->s, " ");
    const size_t len = strcspn(r->s, " \n");
    if (len == 0 || len >= size) {
        if (len >= size && r->why == NULL) r->why = "a word too long";
        return 0;
    }
    memcpy(w, r->s, len);
    w[len] = '\0';
    r->s += len;
    return 1;
}

/* The next word as an integer in [lo, hi]. */
static int get_int(reader *r, const char *key, long lo, long hi)
{
    char w[64], *end;
    if (!next_word(r, w, sizeof w)) {
        if (r->why == NULL) r->why = "too few fields";
        return 0;
    }
    const size_t klen = key ? strlen(key) : 0;
    if (key && (strncmp(w, key, klen) != 0 || w[klen] != '=')) {
        if (r->why == NULL) r->why = "a field out of place";
        return 0;
    }
    const char *v = w + (key ? klen + 1 : 0);
    const long x = strtol(v, &end, 10);
    if (end == v || *end != '\0' || x < lo || x > hi) {
        if (r->why == NULL) r->why = "an integer out of range";
        return 0;
    }
    return (int)x;
}

/* The next word as a finite double in [lo, hi], or NAN for "none" if none_ok. */
static double get_num(reader *r, double lo, double hi, int none_ok)
{
    char w[64], *end;
    if (!next_word(r, w, sizeof w)) {
        if (r->why == NULL) r->why = "too few fields";
        return 0;
    }
    if (none_ok && strcmp(w, "none") == 0) return NAN;
    const double x = strtod(w, &end);
    if (end == w || *end != '\0' || !isfinite(x) || x < lo || x > hi) {
        if (r->why == NULL) r->why = "a number not finite or out of range";
        return 0;
    }
    return x;
}

/* The line ended where it should. */
static void line_end(reader *r)
{
    r->s += strspn(r->s, " ");
    if (*r->s != '\n' && *r->s != '\0' && r->why == NULL) r->why = "too many fields";
}

/* The next line of text into r (from *text on); 0 at the end. */
static int next_line(const char **text, reader *r, const char *word)
{
    if (**text == '\0') return 0;
    r->s = *text;
    r->line++;
    const char *nl = strchr(*text, '\n');
    *text = nl ? nl + 1 : *text + strlen(*text);
    const size_t len = strlen(word);
    if (strncmp(r->s, word, len) != 0 || r->s[len] != ' ') {
        if (r->why == NULL) r->why = "a line out of place";
        return 1;
    }
    r->s += len;
    return 1;
}

int chart_state_read(chart *ch, const char *text, int *done)
{
    const whirl_chart_params *p = &ch->p;
    const double amp_lo = ch->p.inverted ? p->amp_min : 0; /* amp_floor */
    reader r = {0};
    if (!next_line(&text, &r, "vertical"))
        return whirl_fail(GSL_EINVAL, "state line 1: missing");
    const int columns = get_int(&r, "columns", 0, p->columns);
    const int count = get_int(&r, "count", 0, STATE_COUNT_MAX);
    const int listed = get_int(&r, "curves", 0, count);
    const int tips = get_int(&r, "tips", 0, STATE_COUNT_MAX);
    double drag = 0; /* the field is written only for a drag */
    r.s += strspn(r.s, " ");
    if (r.why == NULL && strncmp(r.s, "drag=", 5) == 0) {
        r.s += 5;
        drag = get_num(&r, 0, INFINITY, 0);
        if (r.why == NULL && !(drag > 0)) r.why = "a drag written as 0";
    }
    line_end(&r);
    if (r.why == NULL && drag != ch->drag) r.why = "a state of another air drag";
    if (r.why) return whirl_fail(GSL_EINVAL, "state line 1: %s", r.why);
    ch->curves = calloc((size_t)count + 1, sizeof *ch->curves);
    ch->tips = calloc((size_t)tips + 1, sizeof *ch->tips);
    if (ch->curves == NULL || ch->tips == NULL)
        return whirl_fail(GSL_ENOMEM, "out of memory for the chart's state");
    ch->cap = count + 1, ch->tips_cap = tips + 1;
    for (int i = 0; i < count; i++) /* ended: their numbers taken, nothing more */
        ch->curves[i] = (chart_curve){.id = i, .a1 = NAN, .a0 = NAN, .tip = NAN};
    ch->count = count;
    int prev = -1;
    for (int k = 0; k < listed; k++) {
        if (!next_line(&text, &r, "curve")) {
            r.line++, r.why = "missing";
            break;
        }
        const int i = get_int(&r, NULL, prev + 1, count - 1);
        if (r.why == NULL) prev = i;
        const int kind = get_int(&r, NULL, 0, 2 * ch->subs - 1); /* + 2 for the second sub */
        chart_curve cv = {.kind = (whirl_floquet_edge)(kind % 2), .sub = kind / 2};
        cv.mode = get_int(&r, NULL, 0, ch->n - 1);
        cv.id = get_int(&r, NULL, 0, i);
        cv.alive = get_int(&r, NULL, 0, 1);
        cv.tipward = get_int(&r, NULL, 0, 1);
        cv.a1 = get_num(&r, amp_lo, p->amp_max, 0);
        cv.a0 = get_num(&r, amp_lo - 2 * p->amp_max, 2 * p->amp_max, 1); /* tips', folds' */
        cv.w1 = get_num(&r, p->omega_min, p->omega_max, 0);
        cv.tip = get_num(&r, 0, p->omega_max, 1);
        cv.fill_top = get_num(&r, 0, p->amp_max, 0);
        cv.found = cv.alive;
        line_end(&r);
        if (r.why == NULL && !cv.alive && !cv.tipward) r.why = "a curve neither alive nor at a tip";
        if (r.why == NULL && cv.tipward && isnan(cv.tip)) r.why = "a curve at a tip without it";
        if (r.why) break;
        ch->curves[i] = cv;
    }
    for (int k = 0; r.why == NULL && k < tips; k++) {
        if (!next_line(&text, &r, "tip")) {
            r.line++, r.why = "missing";
            break;
        }
        ch->tips[k].omega = get_num(&r, 0, p->omega_max, 0);
        ch->tips[k].mode = get_int(&r, NULL, 0, ch->n - 1);
        ch->tips[k].top[0] = get_num(&r, 0, p->amp_max, 0);
        ch->tips[k].top[1] = get_num(&r, 0, p->amp_max, 0);
        line_end(&r);
    }
    ch->tips_count = tips;
    if (r.why == NULL && *text != '\0') {
        r.line++;
        r.why = "a line too many";
    }
    if (r.why) return whirl_fail(GSL_EINVAL, "state line %d: %s", r.line, r.why);
    *done = columns;
    return GSL_SUCCESS;
}
