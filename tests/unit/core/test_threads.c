/* Tests of the library's thread count (src/core/threads.c): the setting's bounds, and a child of
 * fork() after the parent's parallel loops, which must compute on one thread the parent's numbers
 * instead of waiting forever in libgomp for threads the fork did not copy. The child runs under
 * alarm(): a hang fails the test instead of stalling it. */
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>
#include <omp.h>

#include "whirl/common.h"
#include "whirl/chain.h"
#include "whirl/steady.h"

#define RATES 400 /* a branch long enough for one block per thread (steady_branch.c) */

static void setting_bounds(void **state)
{
    (void)state;
    const int n = whirl_max_threads();
    assert_true(n >= 1);
    assert_int_equal(whirl_set_max_threads(-1), GSL_EINVAL);
    assert_int_equal(whirl_set_max_threads(WHIRL_THREADS_MAX + 1), GSL_EINVAL);
    assert_int_equal(whirl_set_max_threads(1), GSL_SUCCESS);
    assert_int_equal(whirl_max_threads(), 1);
    assert_int_equal(whirl_set_max_threads(0), GSL_SUCCESS);
    assert_int_equal(whirl_max_threads(), n);
    assert_int_equal(whirl_forked_child(), 0);
}

static int branch(const whirl_chain *c, double *tip)
{
    double omega[RATES];
    whirl_shape_info info[RATES];
    int exists[RATES];
    for (int j = 0; j < RATES; j++) omega[j] = 3.0 + 5.0 * j / (RATES - 1);
    const int status = whirl_nlink_branch(c, 2, RATES, omega, info, exists);
    for (int j = 0; j < RATES; j++) tip[j] = exists[j] ? info[j].tip_r : NAN;
    return status;
}

/* The child's checks; its exit status says which failed (0: none). */
static int child(const whirl_chain *c, const double *parent)
{
    alarm(60);
    if (!whirl_forked_child() || whirl_max_threads() != 1) return 2;
    if (whirl_set_max_threads(2) != GSL_EINVAL || whirl_set_max_threads(1) != GSL_SUCCESS)
        return 3;
    double tip[RATES];
    if (branch(c, tip) != GSL_SUCCESS) return 4;
    for (int j = 0; j < RATES; j++) /* 1e-10: the blocks' seeds differ with the thread count */
        if (!(fabs(tip[j] - parent[j]) <= 1e-10 * fabs(parent[j]))) return 5;
    return 0;
}

static void forked_child_computes(void **state)
{
    (void)state;
    omp_set_num_threads(4); /* the parent's pool holds threads from the first loop on */
    whirl_chain *c = whirl_chain_alloc_uniform(20, 0.0);
    assert_non_null(c);
    double tip[RATES];
    assert_int_equal(branch(c, tip), GSL_SUCCESS);
    assert_true(isfinite(tip[RATES - 1]));
    const pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) _exit(child(c, tip));
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_false(WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM); /* a hang */
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    whirl_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(setting_bounds),
        cmocka_unit_test(forked_child_computes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
