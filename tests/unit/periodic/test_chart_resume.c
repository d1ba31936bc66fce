/* Tests of the charts resumed from their state after a finished rate (whirl_chart_vertical_resume,
 * whirl_chart_ellipse_resume; periodic/chart_resume.h):
 * for every rate k of a chart, the chart begun at k from the state the uninterrupted chart saved
 * there gives, bit for bit, the points the uninterrupted chart gave from k on, and saves the same
 * states after it; the state read back is written back as it was. The hanging chain of two
 * links (two tongues, each ended at its tip and joined across it), the inverted chain (its edges
 * leaving through the range's sides) and the ellipse chart (a curve that ends on e = 0). A state
 * not the chart's is refused with GSL_EINVAL and its line named. A chart's file as whirl periodic
 * --chart writes it, stopped after k rates, read back (whirl_chart_vertical_read,
 * whirl_chart_ellipse_read): its rows bit for bit the points handed out before k, its state the
 * one saved there; a file of other options, a crafted row, no bytes refused. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/chart_file.h"
#include "whirl/periodic.h"

#define COLUMNS_MAX 64

/* What a run handed out: its points (either chart's, as bytes) with the rates done when each
 * came, and the state after each rate. */
typedef struct run {
    unsigned char *points;
    size_t size, n, cap;
    int *done_at; /* per point: the rates finished when it came */
    int done;
    char *state[COLUMNS_MAX + 1];
} run;

static void keep(run *r, const void *p)
{
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 64;
        r->points = realloc(r->points, r->cap * r->size);
        r->done_at = realloc(r->done_at, r->cap * sizeof *r->done_at);
        assert_non_null(r->points);
        assert_non_null(r->done_at);
    }
    memcpy(r->points + r->n * r->size, p, r->size);
    r->done_at[r->n++] = r->done;
}

static int keep_vertical(void *data, const whirl_chart_point *p)
{
    keep(data, p);
    return 0;
}

static int keep_ellipse(void *data, const whirl_ellipse_point *p)
{
    keep(data, p);
    return 0;
}

static int save(void *data, int done, const char *state)
{
    run *r = data;
    assert_true(done >= 0 && done <= COLUMNS_MAX);
    free(r->state[done]);
    r->state[done] = strdup(state);
    r->done = done;
    return 0;
}

static void run_free(run *r)
{
    free(r->points);
    free(r->done_at);
    for (int i = 0; i <= COLUMNS_MAX; i++) free(r->state[i]);
}

/* The doubles a and b bit for bit. */
static void same_double(double a, double b)
{
    assert_memory_equal(&a, &b, sizeof a);
}

/* Point i of r and point j of s the same, field by field (the doubles bit for bit). */
static void same_point(const run *r, size_t i, const run *s, size_t j)
{
    if (r->size == sizeof(whirl_chart_point)) {
        const whirl_chart_point *p = (const void *)(r->points + i * r->size);
        const whirl_chart_point *q = (const void *)(s->points + j * s->size);
        assert_int_equal(p->kind, q->kind);
        assert_int_equal(p->curve, q->curve);
        assert_int_equal(p->column, q->column);
        same_double(p->omega, q->omega);
        same_double(p->amplitude, q->amplitude);
        same_double(p->err, q->err);
    } else {
        const whirl_ellipse_point *p = (const void *)(r->points + i * r->size);
        const whirl_ellipse_point *q = (const void *)(s->points + j * s->size);
        assert_int_equal(p->event, q->event);
        assert_int_equal(p->curve, q->curve);
        assert_int_equal(p->column, q->column);
        same_double(p->omega, q->omega);
        same_double(p->ellipticity, q->ellipticity);
        same_double(p->err, q->err);
        same_double(p->max_modulus, q->max_modulus);
    }
}

/* The points of full from the rate k on are those of part, in the same order, bit for bit; the
 * states after k too. */
static void same_from(const run *full, const run *part, int k, int columns)
{
    size_t first = 0;
    while (first < full->n && full->done_at[first] < k) first++;
    assert_int_equal(full->n - first, part->n);
    for (size_t i = 0; i < part->n; i++) same_point(full, first + i, part, i);
    for (int j = k; j <= columns; j++) assert_string_equal(full->state[j], part->state[j]);
}

static void vertical_resumed(int inverted, int links, double omega_min, double omega_max,
                             int columns, double amp_max, double drag)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)links, 0);
    assert_non_null(c);
    const whirl_chart_params p = {.inverted = inverted, .omega_min = omega_min,
                                  .omega_max = omega_max, .columns = columns,
                                  .amp_max = amp_max, .rows = 20};
    run full = {.size = sizeof(whirl_chart_point)};
    assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, drag, NULL, keep_vertical, &full,
                                                 NULL, NULL, save, &full),
                     GSL_SUCCESS);
    /* the chart as whirl_chart_vertical (or _damped) gives it */
    run plain = {.size = sizeof(whirl_chart_point)};
    assert_int_equal(drag > 0 ? whirl_chart_vertical_damped(c, 2, &p, drag, keep_vertical, &plain,
                                                            NULL, NULL)
                              : whirl_chart_vertical(c, 2, &p, keep_vertical, &plain, NULL, NULL),
                     GSL_SUCCESS);
    assert_int_equal(plain.n, full.n);
    for (size_t i = 0; i < full.n; i++) same_point(&plain, i, &full, i);
    int tips = 0;
    for (int k = 0; k <= columns; k++) {
        run part = {.size = sizeof(whirl_chart_point)};
        assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, drag, full.state[k],
                                                     keep_vertical, &part, NULL, NULL, save,
                                                     &part),
                         GSL_SUCCESS);
        assert_string_equal(part.state[k], full.state[k]); /* read and written back */
        same_from(&full, &part, k, columns);
        tips += strstr(full.state[k], "\ntip ") != NULL;
        /* the drag recorded in every state (none without), and a state of another drag
           refused */
        assert_true((strstr(full.state[k], " drag=") != NULL) == (drag > 0));
        assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, drag > 0 ? 0 : 0.25,
                                                     full.state[k], NULL, NULL, NULL, NULL, NULL,
                                                     NULL),
                         GSL_EINVAL);
        assert_string_equal(whirl_last_error(), "state line 1: a state of another air drag");
        run_free(&part);
    }
    /* the states carried a tip across the rates (the damped chain's tongues have none) */
    if (!inverted) assert_true((tips > 0) == !(drag > 0));
    run_free(&full);
    run_free(&plain);
    whirl_chain_free(c);
}

/* A save that stops the chart after k rates: the chart returns its status, the points handed out
 * are the uninterrupted chart's before k, and the chart resumed from that state gives the rest. */
typedef struct stopping {
    run r;
    int at;
} stopping;

static int save_stop(void *data, int done, const char *state)
{
    stopping *s = data;
    save(&s->r, done, state);
    return done == s->at ? 99 : 0; /* any status not the chart's own */
}

static void test_stopped_by_save(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    assert_non_null(c);
    const whirl_chart_params p = {.omega_min = 1.8, .omega_max = 3, .columns = 13,
                                  .amp_max = 0.4, .rows = 20};
    run full = {.size = sizeof(whirl_chart_point)};
    assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, 0, NULL, keep_vertical, &full, NULL,
                                                 NULL, save, &full),
                     GSL_SUCCESS);
    for (int k = 1; k < 13; k += 5) {
        stopping s = {.r = {.size = sizeof(whirl_chart_point)}, .at = k};
        assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, 0, NULL, keep_vertical, &s.r, NULL,
                                                     NULL, save_stop, &s),
                         99);
        size_t before = 0;
        while (before < full.n && full.done_at[before] < k) before++;
        assert_int_equal(s.r.n, before);
        for (size_t i = 0; i < before; i++) same_point(&full, i, &s.r, i);
        run rest = {.size = sizeof(whirl_chart_point)};
        assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, 0, s.r.state[k], keep_vertical,
                                                     &rest, NULL, NULL, save, &rest),
                         GSL_SUCCESS);
        same_from(&full, &rest, k, 13);
        run_free(&rest);
        run_free(&s.r);
    }
    run_free(&full);
    whirl_chain_free(c);
}

/* The file of the chart stopped after k rates, as whirl periodic --chart writes it (the header
 * of periodic/chart_file.h, the rows of the rates finished, the state's lines), into a string
 * (to free). */
static char *vertical_file(const run *full, int k, const whirl_chart_params *p, int links,
                           size_t *kept)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    *kept = 0;
    while (*kept < full->n && full->done_at[*kept] < k) (*kept)++;
    char found[64];
    snprintf(found, sizeof found, CHART_FOUND "points=%zu curves=0\n", *kept);
    const chart_units u = {.length = 1, .mass = 1, .gravity = 1};
    chart_vertical_head(f, p, links, 0, &u, found);
    for (size_t i = 0; i < *kept; i++) {
        const whirl_chart_point *q = (const void *)(full->points + i * full->size);
        char a[WHIRL_FORMAT_MAX], b[WHIRL_FORMAT_MAX], c[WHIRL_FORMAT_MAX];
        fprintf(f, "%d,%d,%s,%s,%s\n", q->curve + 1,
                q->kind == WHIRL_FLOQUET_EDGE_PLUS_ONE ? 1 : -1, whirl_format_double(a, q->omega),
                whirl_format_double(b, q->amplitude), whirl_format_double(c, q->err));
    }
    for (const char *s = full->state[k]; *s;) {
        const size_t n = strcspn(s, "\n");
        fprintf(f, CHART_STATE "%.*s\n", (int)n, s);
        s += n + (s[n] == '\n');
    }
    assert_int_equal(fclose(f), 0);
    char *copy = strdup(text); /* (not the stream's buffer: gcc takes it for a local's) */
    assert_non_null(copy);
    free(text);
    return copy;
}

static void test_vertical_file_read(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    assert_non_null(c);
    whirl_chart_params p = {.omega_min = 1.8, .omega_max = 3, .columns = 13, .amp_max = 0.4,
                            .rows = 20};
    run full = {.size = sizeof(whirl_chart_point)};
    assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, 0, NULL, keep_vertical, &full, NULL,
                                                 NULL, save, &full),
                     GSL_SUCCESS);
    whirl_chart_params shown = p; /* the header's: the defaults applied */
    chart_vertical_defaults(&shown);
    for (int k = 3; k <= 13; k += 5) {
        size_t kept;
        char *text = vertical_file(&full, k, &shown, 2, &kept);
        run back = {.size = sizeof(whirl_chart_point)};
        assert_int_equal(whirl_chart_vertical_read(text, strlen(text), "c.csv", &p, 2, 0, 0, 0,
                                                   0, 0, 1, keep_vertical, &back, save, &back),
                         GSL_SUCCESS);
        /* the rows as the chart gave them, bit for bit (column not recorded), the state */
        assert_int_equal(back.n, kept);
        for (size_t i = 0; i < kept; i++) {
            whirl_chart_point *q = (void *)(back.points + i * back.size);
            assert_int_equal(q->column, -1);
            q->column = ((const whirl_chart_point *)(const void *)(full.points +
                                                                    i * full.size))->column;
            same_point(&full, i, &back, i);
        }
        assert_int_equal(back.done, k);
        assert_string_equal(back.state[k], full.state[k]);
        /* and resumed from it: the rest of the chart */
        run rest = {.size = sizeof(whirl_chart_point)};
        assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, 0, back.state[k], keep_vertical,
                                                     &rest, NULL, NULL, save, &rest),
                         GSL_SUCCESS);
        same_from(&full, &rest, k, 13);
        run_free(&rest);
        run_free(&back);
        /* other options: refused, the first difference named */
        whirl_chart_params other = p;
        other.omega_max = 3.5;
        assert_int_equal(whirl_chart_vertical_read(text, strlen(text), "c.csv", &other, 2, 0, 0,
                                                   0, 0, 0, 1, NULL, NULL, NULL, NULL),
                         GSL_EINVAL);
        assert_string_equal(whirl_last_error(), "'c.csv' was not written by a chart with these "
                                                "options: line 2 has 'to 3' where these options "
                                                "write 'to 3.5'");
        assert_int_equal(whirl_chart_vertical_read(text, strlen(text), "c.csv", &p, 3, 0, 0, 0,
                                                   0, 0, 1, NULL, NULL, NULL, NULL),
                         GSL_EINVAL);
        assert_int_equal(whirl_chart_vertical_read(text, strlen(text), "c.csv", &p, 2, 0.1, 0, 0,
                                                   0, 0, 1, NULL, NULL, NULL, NULL),
                         GSL_EINVAL);
        /* a row crafted: the first one's edge 2 */
        assert_non_null(strstr(text, "\n1,"));
        const size_t edge = (size_t)(strstr(text, "\n1,") - text) + 3; /* the edge's field */
        const size_t after = edge + strcspn(text + edge, ",");
        char *bad = malloc(strlen(text) + 2);
        assert_non_null(bad);
        snprintf(bad, strlen(text) + 2, "%.*s2%s", (int)edge, text, text + after);
        assert_int_equal(whirl_chart_vertical_read(bad, strlen(bad), "c.csv", &p, 2, 0, 0, 0, 0,
                                                   0, 1, NULL, NULL, NULL, NULL),
                         GSL_EINVAL);
        assert_non_null(strstr(whirl_last_error(), ": an edge other than 1 or -1: the file "
                                                   "cannot be trusted"));
        free(bad);
        free(text);
    }
    assert_int_equal(whirl_chart_vertical_read("", 0, "e.csv", &p, 2, 0, 0, 0, 0, 0, 1, NULL,
                                               NULL, NULL, NULL),
                     GSL_EINVAL);
    assert_string_equal(whirl_last_error(), "'e.csv' is empty: no chart of these options");
    run_free(&full);
    whirl_chain_free(c);
}

/* The ellipse chart's file stopped after k rates, read back: its rows the points handed out
 * before k (the rate's index found on the grid, -1 at an end; no max_modulus), its state. */
static void test_ellipse_file_read(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    assert_non_null(c);
    const whirl_ellipse_chart_params p = {.radius = 0.05, .mode = 2, .side = -1,
                                          .omega_min = 3.95, .omega_max = 4.1, .columns = 4};
    run full = {.size = sizeof(whirl_ellipse_point)};
    assert_int_equal(whirl_chart_ellipse_resume(c, &p, NULL, keep_ellipse, &full, NULL, NULL,
                                                save, &full),
                     GSL_SUCCESS);
    whirl_ellipse_chart_params shown = p;
    chart_ellipse_defaults(&shown);
    const chart_units u = {.length = 1, .mass = 1, .gravity = 1};
    for (int k = 2; k <= 4; k += 2) {
        size_t kept = 0, len = 0;
        while (kept < full.n && full.done_at[kept] < k) kept++;
        char *text = NULL, found[64];
        FILE *f = open_memstream(&text, &len);
        assert_non_null(f);
        snprintf(found, sizeof found, CHART_FOUND "points=%zu\n", kept);
        chart_ellipse_head(f, &shown, 2, &u, found);
        for (size_t i = 0; i < kept; i++) {
            const whirl_ellipse_point *q = (const void *)(full.points + i * full.size);
            char a[WHIRL_FORMAT_MAX], b[WHIRL_FORMAT_MAX], e[WHIRL_FORMAT_MAX];
            fprintf(f, "%d,%s,%s,%s,%s\n", q->curve + 1,
                    q->event == WHIRL_CYCLE_POINT ? "none" : whirl_cycle_event_name(q->event),
                    whirl_format_double(a, q->omega), whirl_format_double(b, q->ellipticity),
                    whirl_format_double(e, q->err));
        }
        fprintf(f, CHART_STATE "%s", full.state[k]);
        assert_int_equal(fclose(f), 0);
        run back = {.size = sizeof(whirl_ellipse_point)};
        assert_int_equal(whirl_chart_ellipse_read(text, len, "e.csv", &p, 2, 0, 0, 0, 0, 1,
                                                  keep_ellipse, &back, save, &back),
                         GSL_SUCCESS);
        assert_int_equal(back.n, kept);
        for (size_t i = 0; i < kept; i++) {
            whirl_ellipse_point *q = (void *)(back.points + i * back.size);
            const whirl_ellipse_point *o = (const void *)(full.points + i * full.size);
            assert_true(isnan(q->max_modulus));
            q->max_modulus = o->max_modulus;
            same_point(&full, i, &back, i);
        }
        assert_int_equal(back.done, k);
        assert_string_equal(back.state[k], full.state[k]);
        run_free(&back);
        /* the vertical chart's reader refuses it: its first line */
        const whirl_chart_params v = {.omega_min = 3.95, .omega_max = 4.1, .amp_max = 0.1};
        assert_int_equal(whirl_chart_vertical_read(text, len, "e.csv", &v, 2, 0, 0, 0, 0, 0, 1,
                                                   NULL, NULL, NULL, NULL),
                         GSL_EINVAL);
        assert_non_null(strstr(whirl_last_error(), "line 1 has "));
        free(text);
    }
    run_free(&full);
    whirl_chain_free(c);
}

static void test_hanging_two_links(void **state)
{
    (void)state;
    vertical_resumed(0, 2, 1.8, 3, 13, 0.4, 0);
}

/* The damped hanging chain's states: its drag carried, no tips (tongues lifted off A = 0). */
static void test_hanging_damped(void **state)
{
    (void)state;
    vertical_resumed(0, 2, 1.8, 3, 13, 0.4, 0.05);
}

static void test_inverted(void **state)
{
    (void)state;
    vertical_resumed(1, 1, 20, 30, 6, 0.2, 0);
}

static void test_ellipse(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    assert_non_null(c);
    const whirl_ellipse_chart_params p = {.radius = 0.05, .mode = 2, .side = -1,
                                          .omega_min = 3.95, .omega_max = 4.1, .columns = 4};
    run full = {.size = sizeof(whirl_ellipse_point)};
    assert_int_equal(whirl_chart_ellipse_resume(c, &p, NULL, keep_ellipse, &full, NULL, NULL,
                                                save, &full),
                     GSL_SUCCESS);
    assert_int_equal(full.n, 3); /* two rates and the end on e = 0 (test_chart_ellipse.c) */
    for (int k = 2; k <= 4; k += 2) { /* the curve under way, the end ahead; all done */
        run part = {.size = sizeof(whirl_ellipse_point)};
        assert_int_equal(whirl_chart_ellipse_resume(c, &p, full.state[k], keep_ellipse, &part,
                                                    NULL, NULL, save, &part),
                         GSL_SUCCESS);
        same_from(&full, &part, k, 4);
        run_free(&part);
    }
    /* states not the chart's */
    const char *bad[] = {"ellipse columns=5 prev=0 curve=0 failed=0\n",
                         "ellipse columns=2 prev=2 curve=0 failed=0\n",
                         "ellipse columns=2 prev=1 curve=-1 failed=0\n",
                         "ellipse columns=2 prev=1 curve=0 failed=0 x\n", "vertical columns=0\n"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(whirl_chart_ellipse_resume(c, &p, bad[i], NULL, NULL, NULL, NULL, NULL,
                                                    NULL),
                         GSL_EINVAL);
        assert_non_null(strstr(whirl_last_error(), "state line 1: "));
    }
    run_free(&full);
    whirl_chain_free(c);
}

static void test_bad_states(void **state)
{
    (void)state;
    whirl_chain *c = whirl_chain_alloc_uniform(2, 0);
    assert_non_null(c);
    const whirl_chart_params p = {.omega_min = 1.8, .omega_max = 3, .columns = 13,
                                  .amp_max = 0.4, .rows = 20};
    static const struct {
        const char *state, *why;
    } bad[] = {
        {"", "state line 1: missing"},
        {"vertical columns=14 count=0 curves=0 tips=0\n", "state line 1: an integer out of range"},
        {"vertical columns=1 count=1 curves=2 tips=0\n", "state line 1: an integer out of range"},
        {"vertical count=1 columns=1 curves=0 tips=0\n", "state line 1: a field out of place"},
        {"vertical columns=1 count=1 curves=1 tips=0\n", "state line 2: missing"},
        {"vertical columns=1 count=1 curves=1 tips=0\ncurve 0 1 2 0 1 0 0.1 none 1.8 none 0\n",
         "state line 2: an integer out of range"}, /* mode 2 of a chain of two */
        {"vertical columns=1 count=1 curves=1 tips=0\ncurve 0 1 0 0 1 0 nan none 1.8 none 0\n",
         "state line 2: a number not finite or out of range"},
        {"vertical columns=1 count=1 curves=1 tips=0\ncurve 0 1 0 0 1 0 0.5 none 1.8 none 0\n",
         "state line 2: a number not finite or out of range"}, /* above amp_max */
        {"vertical columns=1 count=2 curves=2 tips=0\ncurve 1 1 0 1 1 0 0.1 none 1.8 none 0\n"
         "curve 0 1 0 0 1 0 0.1 none 1.8 none 0\n",
         "state line 3: an integer out of range"}, /* not in order */
        {"vertical columns=1 count=1 curves=1 tips=0\ncurve 0 1 0 0 0 0 0.1 none 1.8 none 0\n",
         "state line 2: a curve neither alive nor at a tip"},
        {"vertical columns=1 count=1 curves=1 tips=0\ncurve 0 1 0 0 0 1 0.1 none 1.8 none 0\n",
         "state line 2: a curve at a tip without it"},
        {"vertical columns=1 count=0 curves=0 tips=1\ntip 2 0 0 0 1\n", "state line 2: too many fields"},
        {"vertical columns=1 count=0 curves=0 tips=0\ntip 2 0\n", "state line 2: a line too many"},
        {"vertical columns=1 count=99999999999 curves=0 tips=0\n",
         "state line 1: an integer out of range"},
        {"vertical columns=0 count=0 curves=0 tips=0 drag=0.1\n",
         "state line 1: a state of another air drag"}, /* the chart has none */
        {"vertical columns=0 count=0 curves=0 tips=0 drag=0\n",
         "state line 1: a drag written as 0"},
        {"vertical columns=0 count=0 curves=0 tips=0 drag=nan\n",
         "state line 1: a number not finite or out of range"},
        {"vertical columns=0 count=0 curves=0 tips=0 drag=0.1 x\n",
         "state line 1: too many fields"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(whirl_chart_vertical_resume(c, 2, &p, 0, bad[i].state, NULL, NULL, NULL,
                                                     NULL, NULL, NULL),
                         GSL_EINVAL);
        if (strcmp(whirl_last_error(), bad[i].why) != 0)
            fail_msg("state %zu: '%s', not '%s'", i, whirl_last_error(), bad[i].why);
    }
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hanging_two_links),
        cmocka_unit_test(test_hanging_damped),
        cmocka_unit_test(test_inverted),
        cmocka_unit_test(test_ellipse),
        cmocka_unit_test(test_bad_states),
        cmocka_unit_test(test_stopped_by_save),
        cmocka_unit_test(test_vertical_file_read),
        cmocka_unit_test(test_ellipse_file_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
