/* Files and numbers as text: the bounded reader (core/input.h) and locale-independent numbers
 * (whirl_format_double, whirl_parse_quantity, scene files) under a comma-decimal locale. */
#include <locale.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "core/input.h"
#include "whirl/common.h"
#include "whirl/scene.h"

/* A line of n 'x' and its newline, then the rest of the text, through the reader. */
static void test_reader_caps(void **state)
{
    (void)state;
    char text[] = "short\nxxxxxxxxxxxxxxxxxxxx\nlast";
    FILE *fp = fmemopen(text, strlen(text), "r");
    assert_non_null(fp);
    whirl_line_reader r = whirl_line_reader_init(fp, "t.txt", 12, 1000);
    assert_int_equal(whirl_line_read(&r), 1);
    assert_string_equal(r.line, "short\n");
    assert_int_equal(r.len, 6);
    assert_int_equal(whirl_line_read(&r), -1); /* 21 bytes > 12 */
    assert_int_equal(r.status, GSL_EINVAL);
    assert_string_equal(whirl_last_error(), "t.txt:2: line longer than 12 bytes (the longest read)");
    assert_int_equal(whirl_line_read(&r), -1); /* a failed reader stays failed */
    whirl_line_reader_free(&r);
    fclose(fp);

    fp = fmemopen(text, strlen(text), "r");
    r = whirl_line_reader_init(fp, "t.txt", 100, 10);
    assert_int_equal(whirl_line_read(&r), 1);
    assert_int_equal(whirl_line_read(&r), -1); /* 6 + 5 bytes > 10 */
    assert_string_equal(whirl_last_error(), "t.txt:2: more than 10 bytes of input (the most read)");
    whirl_line_reader_free(&r);
    fclose(fp);

    fp = fmemopen(text, strlen(text), "r");
    r = whirl_line_reader_init(fp, "t.txt", 100, 1000);
    assert_int_equal(whirl_line_read(&r), 1);
    assert_int_equal(whirl_line_read(&r), 1);
    assert_int_equal(whirl_line_read(&r), 1); /* the last line without its newline */
    assert_string_equal(r.line, "last");
    assert_int_equal(r.lineno, 3);
    assert_int_equal(whirl_line_read(&r), 0);
    whirl_line_reader_free(&r);
    fclose(fp);
}

/* A stop request ends the reading of an endless stream. */
static void test_reader_stop(void **state)
{
    (void)state;
    FILE *fp = fopen("/dev/zero", "r");
    assert_non_null(fp);
    whirl_line_reader r = whirl_line_reader_init(fp, "/dev/zero", (size_t)1 << 30, (size_t)1 << 40);
    whirl_stop_request();
    assert_int_equal(whirl_line_read(&r), -1);
    assert_int_equal(r.status, WHIRL_EINTERRUPTED);
    assert_true(r.total < ((size_t)1 << 21));
    whirl_stop_clear();
    whirl_line_reader_free(&r);
    fclose(fp);
    FILE *in;
    assert_int_equal(whirl_input_open("/dev/zero", &in), GSL_EINVAL);
    assert_string_equal(whirl_last_error(),
                        "/dev/zero: cannot read: a character device, not a regular file");
}

/* Under de_DE (a comma-decimal locale, built with localedef into a temporary LOCPATH) printf
 * writes 0,5; the library still reads and writes 0.5. */
static void test_comma_locale(void **state)
{
    (void)state;
    char dir[] = "/tmp/whirl-locale-XXXXXX", cmd[256];
    assert_non_null(mkdtemp(dir));
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
    if (system(cmd) != 0) fail_msg("localedef could not build de_DE.UTF-8 (package locales)");
    setenv("LOCPATH", dir, 1);
    if (setlocale(LC_ALL, "de_DE.UTF-8") == NULL) fail_msg("setlocale(de_DE.UTF-8) failed");
    char buf[WHIRL_FORMAT_MAX];
    snprintf(buf, sizeof buf, "%g", 0.5);
    assert_string_equal(buf, "0,5"); /* the locale is in force */
    assert_string_equal(whirl_format_double(buf, 0.5), "0.5");
    assert_string_equal(whirl_format_double(buf, 4.39), "4.39");
    double v;
    assert_int_equal(whirl_parse_quantity("0.25", WHIRL_QUANTITY_NUMBER, &v, NULL), 0);
    assert_true(v == 0.25);
    assert_int_equal(whirl_parse_quantity("2.5Hz", WHIRL_QUANTITY_RATE, &v, NULL), 0);
    assert_true(v == 2.5 * 6.283185307179586476925286766559);
    char scene[] = "[chain]\ndim = 2\nlinks = 2\n[start]\nhanging = true\n[run]\nt_end = 0.5\n"
                   "dt = 0.01\n";
    FILE *fp = fmemopen(scene, strlen(scene), "r");
    whirl_scene s;
    assert_int_equal(whirl_scene_parse_stream(fp, "c.ini", NULL, 0, &s), GSL_SUCCESS);
    assert_true(s.dt == 0.01 && s.t_end == 0.5);
    whirl_scene_free(&s);
    fclose(fp);
    setlocale(LC_ALL, "C");
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reader_caps),
        cmocka_unit_test(test_reader_stop),
        cmocka_unit_test(test_comma_locale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
