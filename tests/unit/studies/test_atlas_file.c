/* Tests of the atlas's file written by one run at a time (whirl_atlas_file, whirl/atlas.h):
 * - a run that starts afresh makes the file and holds it: a second writer is refused with the
 *   one-line message, whether it would make the file or resume it;
 * - a rewrite puts the new contents in place whole, keeps the file's mode, and passes the lock
 *   to the new file (the second writer is still refused, and the descriptor reads the new
 *   contents);
 * - the release frees the file for the next run, and removes the empty file a run made and
 *   never wrote;
 * - the paths that cannot be locked: a missing file to resume, a directory. */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/atlas.h"

/* The whole file at path, NUL-terminated, into buf (size). */
static size_t slurp(const char *path, char *buf, size_t size)
{
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    const size_t n = fread(buf, 1, size - 1, fp);
    buf[n] = '\0';
    fclose(fp);
    return n;
}

static void assert_refused(const char *path, int make)
{
    assert_null(whirl_atlas_file_alloc(path, make));
    assert_int_equal(whirl_last_status(), GSL_EFAILED);
    char want[4200];
    snprintf(want, sizeof want, "'%s' is being written by another run (locked): wait for it or "
             "write another file", path);
    assert_string_equal(whirl_last_error(), want);
}

static void test_one_writer_at_a_time(void **state)
{
    (void)state;
    char dir[] = "/tmp/whirl-atlas-file-XXXXXX", path[64], buf[64];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/atlas.csv", dir);
    whirl_atlas_file *f = whirl_atlas_file_alloc(path, 1);
    assert_non_null(f);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_true(st.st_size == 0 && whirl_atlas_file_made(f));
    assert_refused(path, 1);
    assert_refused(path, 0);
    /* made and never written: removed at the release */
    whirl_atlas_file_free(f);
    assert_int_not_equal(stat(path, &st), 0);
    assert_null(whirl_atlas_file_alloc(path, 0));
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "no such regular file"));

    /* rewritten: the contents whole, the mode kept, the lock passed to the new file */
    f = whirl_atlas_file_alloc(path, 1);
    assert_non_null(f);
    assert_int_equal(whirl_atlas_file_commit(f, "first\n", 6), GSL_SUCCESS);
    assert_int_equal(chmod(path, 0640), 0);
    assert_int_equal(whirl_atlas_file_commit(f, "second\nline\n", 12), GSL_SUCCESS);
    assert_int_equal(slurp(path, buf, sizeof buf), 12);
    assert_string_equal(buf, "second\nline\n");
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal(st.st_mode & 0777, 0640);
    assert_false(whirl_atlas_file_made(f));
    assert_refused(path, 0);
    assert_int_equal(pread(whirl_atlas_file_fd(f), buf, 6, 0), 6);
    assert_memory_equal(buf, "second", 6);
    whirl_atlas_file_free(f);
    /* released, and kept (written): the next run takes it */
    f = whirl_atlas_file_alloc(path, 0);
    assert_non_null(f);
    whirl_atlas_file_free(f);
    assert_int_equal(slurp(path, buf, sizeof buf), 12);

    /* a directory is not the file */
    assert_null(whirl_atlas_file_alloc(dir, 1));
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    assert_non_null(strstr(whirl_last_error(), "is not a regular file"));
    assert_null(whirl_atlas_file_alloc("", 1));
    assert_int_equal(whirl_last_status(), GSL_EINVAL);
    whirl_atlas_file_free(NULL);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(rmdir(dir), 0);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_writer_at_a_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
