/* Tests of the stability atlas (include/whirl/atlas.h):
 *  - mode 2 to omega 11 chunk by chunk (chunks ending at 5, 10, 11) has the windows of one
 *    search over the whole range (whirl_cstab_windows, independent of the chunks): the window
 *    that opens below 10 and runs on past it is joined into one, open at 11; the Krein
 *    signatures at the closed edges are those of a collision of opposite signs (-1 below, +1
 *    above the first window);
 *  - the progress hook sees the rates of each chunk's search;
 *  - a chunk below the mode's birth is done with nothing computed; a chunk done or out of range
 *    is refused; a stop request leaves the atlas as it was;
 *  - the file's text read back (whirl_atlas_read_text) gives the same atlas, text for text; a
 *    file of other options, a row in no chunk done, a "# done" line of no chunk are refused
 *    with the line named, and leave the atlas empty; an unfinished last line is dropped;
 *  - every invalid parameter is refused with GSL_EINVAL. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/atlas.h"
#include "whirl/continuum_stability.h"

/* The progress hook's calls: their count, the modes and rates seen. */
typedef struct seen {
    int calls, mode;
    double omega_min, omega_max;
} seen;

static void on_rate(void *ctx, int mode, double omega)
{
    seen *s = ctx;
    if (s->calls++ == 0) s->omega_min = s->omega_max = omega;
    s->mode = mode;
    if (omega < s->omega_min) s->omega_min = omega;
    if (omega > s->omega_max) s->omega_max = omega;
}

static seen progress_seen;

/* The atlas of mode 2 to omega_max, no chunk done, its progress into progress_seen. */
static whirl_atlas *atlas_of_mode2(double omega_max, double scan_step)
{
    whirl_atlas_params p = whirl_atlas_defaults();
    p.progress = on_rate;
    p.progress_ctx = &progress_seen;
    p.n_modes = 1;
    p.modes[0] = 2;
    p.omega_max = omega_max;
    p.scan_step = scan_step;
    whirl_atlas *a = whirl_atlas_alloc(&p);
    assert_non_null(a);
    return a;
}

/* The file's text (malloc'd). */
static char *text_of(const whirl_atlas *a, size_t *len)
{
    *len = whirl_atlas_text(a, NULL, 0);
    char *t = malloc(*len + 1);
    assert_non_null(t);
    assert_int_equal(whirl_atlas_text(a, t, *len + 1), *len);
    assert_int_equal(strlen(t), *len);
    return t;
}

static whirl_atlas *computed; /* mode 2 to omega 11, every chunk done (shared by the tests) */

static void test_chunks_joined_as_one_search(void **state)
{
    (void)state;
    whirl_atlas *a = atlas_of_mode2(11, 0.25);
    assert_int_equal(whirl_atlas_chunks(a), 3);
    double lo, hi;
    whirl_atlas_chunk_range(a, 2, &lo, &hi);
    assert_true(lo == 10 && hi == 11);
    for (size_t j = 0; j < 3; j++) {
        int did = -1;
        assert_int_equal(whirl_atlas_compute(a, 0, j, &did), GSL_SUCCESS);
        assert_int_equal(did, 1);
        assert_int_equal(whirl_atlas_done(a, 0, j), 1);
    }
    assert_int_equal(whirl_atlas_done_count(a), 3);
    /* the hook saw the rates of mode 2's search, within the chunks */
    assert_true(progress_seen.calls > 10 && progress_seen.mode == 2);
    assert_true(progress_seen.omega_min >= 1e-3 && progress_seen.omega_max <= 11);
    /* the same windows by one search from 1e-3 to 11 */
    whirl_cstab_params cp = whirl_cstab_defaults();
    whirl_cstab *w = whirl_cstab_alloc(&cp);
    assert_non_null(w);
    whirl_windows_params p = whirl_windows_defaults();
    p.omega_min = 1e-3;
    p.omega_max = 11;
    whirl_window win[8];
    size_t n = 0;
    whirl_windows_stats st;
    assert_int_equal(whirl_cstab_windows(w, 2, &p, win, 8, &n, &st), GSL_SUCCESS);
    whirl_cstab_free(w);
    size_t count;
    const whirl_atlas_row *r = whirl_atlas_rows(a, &count);
    assert_int_equal(count, n);
    assert_int_equal(n, 2);
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(r[i].mode, 2);
        assert_true(fabs(r[i].w.from - win[i].from) <= 2 * p.tol);
        assert_true(fabs(r[i].w.to - win[i].to) <= 2 * p.tol);
        assert_int_equal(r[i].w.open_from, win[i].open_from);
        assert_int_equal(r[i].w.open_to, win[i].open_to);
        assert_true(fabs(r[i].w.max_growth - win[i].max_growth) <= 1e-6 * win[i].max_growth);
    }
    /* the second window opens below 10, crosses the chunk's end, is open at 11 */
    assert_true(r[1].w.from < 10 && r[1].w.to == 11 && r[1].w.open_to == 1);
    assert_int_equal(r[0].sig_from, -1);
    assert_int_equal(r[0].sig_to, 1);
    assert_int_equal(r[1].sig_from, -1);
    assert_int_equal(r[1].sig_to, 0); /* open end */
    /* no chunk twice, none beyond */
    assert_int_equal(whirl_atlas_compute(a, 0, 1, NULL), GSL_EINVAL);
    assert_int_equal(whirl_atlas_compute(a, 0, 3, NULL), GSL_EINVAL);
    assert_int_equal(whirl_atlas_compute(a, 1, 0, NULL), GSL_EINVAL);
    computed = a;
}

static void test_birth_and_stop(void **state)
{
    (void)state;
    whirl_atlas_params p = whirl_atlas_defaults();
    p.n_modes = 2;
    p.modes[0] = 8; /* born near omega 12.2 */
    p.modes[1] = 2;
    p.omega_max = 10;
    whirl_atlas *a = whirl_atlas_alloc(&p);
    assert_non_null(a);
    int did = -1;
    assert_int_equal(whirl_atlas_compute(a, 0, 1, &did), GSL_SUCCESS);
    assert_int_equal(did, 0);
    assert_int_equal(whirl_atlas_done(a, 0, 1), 1);
    size_t count;
    whirl_atlas_rows(a, &count);
    assert_int_equal(count, 0);
    whirl_stop_request();
    assert_int_equal(whirl_atlas_compute(a, 1, 0, &did), WHIRL_EINTERRUPTED);
    whirl_stop_clear();
    assert_int_equal(did, 0);
    assert_int_equal(whirl_atlas_done(a, 1, 0), 0);
    assert_int_equal(whirl_atlas_done_count(a), 1);
    whirl_atlas_free(a);
}

static void test_text_read_back(void **state)
{
    (void)state;
    assert_non_null(computed);
    size_t len;
    char *text = text_of(computed, &len);
    assert_non_null(strstr(text, "# atlas: modes=2 omega_max=11 degree=16 tol=1e-09 "
                                 "scan_step=0.25\n"));
    assert_non_null(strstr(text, "# done mode 2 omega 10 11\nmode,from,to,"));
    /* the rows as whirl_atlas_row_text writes them, after the columns */
    size_t count;
    const whirl_atlas_row *r = whirl_atlas_rows(computed, &count);
    char row[256];
    assert_true(whirl_atlas_row_text(&r[1], row, sizeof row) < sizeof row);
    assert_string_equal(text + len - strlen(row), row);
    assert_int_equal(strncmp(row, "2,9.7460659", 11), 0);

    whirl_atlas *b = atlas_of_mode2(11, 0.25);
    assert_int_equal(whirl_atlas_read_text(b, text, len, "a.csv"), GSL_SUCCESS);
    size_t len2;
    char *again = text_of(b, &len2);
    assert_string_equal(again, text);
    free(again);
    /* an unfinished last line (a run killed while writing) is dropped */
    char *cut = malloc(len + 16);
    assert_non_null(cut);
    memcpy(cut, text, len);
    memcpy(cut + len, "2,10.5,10.6", 11);
    assert_int_equal(whirl_atlas_read_text(b, cut, len + 11, "a.csv"), GSL_SUCCESS);
    assert_int_equal(whirl_atlas_done_count(b), 3);
    /* the row of the chunk 0..5 without its "# done" line: in no chunk done */
    const char *done0 = strstr(text, "# done mode 2 omega 0 5\n");
    assert_non_null(done0);
    const size_t at = (size_t)(done0 - text), skip = strlen("# done mode 2 omega 0 5\n");
    memcpy(cut, text, at);
    memcpy(cut + at, text + at + skip, len - at - skip);
    assert_int_equal(whirl_atlas_read_text(b, cut, len - skip, "a.csv"), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "a.csv:7: a window of mode 2 at omega "
                                               "4.4032206"));
    assert_int_equal(whirl_atlas_done_count(b), 0);
    whirl_atlas_rows(b, &count);
    assert_int_equal(count, 0);
    /* a chunk that is none of this atlas's */
    memcpy(cut, text, len);
    memcpy(cut + at, "# done mode 2 omega 0 6\n", skip);
    assert_int_equal(whirl_atlas_read_text(b, cut, len, "a.csv"), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "a.csv:4: omega 0 6 is no chunk of this atlas"));
    free(cut);
    whirl_atlas_free(b);
    /* other options: the first difference named */
    whirl_atlas *c = atlas_of_mode2(11, 0.5);
    assert_int_equal(whirl_atlas_read_text(c, text, len, "a.csv"), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "'a.csv' was not written by an atlas with these "
                           "options: line 2 has 'tol=1e-09 scan_step=0.25' where these options "
                           "write 'tol=1e-09 scan_step=0.5'"));
    assert_int_equal(whirl_atlas_read_text(c, "", 0, "a.csv"), GSL_EINVAL);
    whirl_atlas_free(c);
    free(text);
    whirl_atlas_free(computed);
    computed = NULL;
}

static void test_errors(void **state)
{
    (void)state;
    const whirl_atlas_params d = whirl_atlas_defaults();
    assert_int_equal(d.n_modes, 7);
    assert_true(d.modes[0] == 2 && d.modes[6] == 8 && d.omega_max == 40 && d.degree == 16);
    whirl_atlas_params p = d;
    p.n_modes = 0;
    assert_null(whirl_atlas_alloc(&p));
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    p = d;
    p.modes[3] = 2; /* a mode twice */
    assert_null(whirl_atlas_alloc(&p));
    assert_non_null(strstr(whirl_last_error(), "repeat mode 2"));
    p = d;
    p.modes[0] = WHIRL_MODE_MAX + 1;
    assert_null(whirl_atlas_alloc(&p));
    const double bad_omega[] = {0, -1, 5001, NAN};
    for (size_t i = 0; i < sizeof bad_omega / sizeof *bad_omega; i++) {
        p = d;
        p.omega_max = bad_omega[i];
        assert_null(whirl_atlas_alloc(&p));
        assert_int_equal(whirl_last_status(), GSL_EINVAL);
    }
    p = d;
    p.tol = 0.5; /* not below scan_step */
    assert_null(whirl_atlas_alloc(&p));
    p = d;
    p.tol = 1e-14;
    assert_null(whirl_atlas_alloc(&p));
    p = d;
    p.degree = 4;
    assert_null(whirl_atlas_alloc(&p));
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    whirl_atlas_free(NULL);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chunks_joined_as_one_search),
        cmocka_unit_test(test_birth_and_stop),
        cmocka_unit_test(test_text_read_back),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
