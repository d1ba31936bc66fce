/* The most OpenMP threads one parallel loop of the library may use (see include/whirl/common.h),
 * and the rule that a child of fork() runs on one. GNU libgomp keeps the threads of its first
 * parallel region in a pool for the later ones; fork() copies the pool's bookkeeping but not its
 * threads, so a child's parallel region of more than one thread waits forever for threads that
 * do not exist (a region of one thread never touches the pool). The count is process-wide for
 * the reason the stop request is: fork() and the cores belong to the process. */
#include <pthread.h>
#include <stdatomic.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "whirl/common.h"
#include "core/error.h"
#include "core/threads.h"

static atomic_int max_threads = 0; /* 0: OpenMP's own count (OMP_NUM_THREADS, the cores) */
static atomic_int forked = 0;      /* 1 in a child of fork() */

static void in_child(void)
{
    atomic_store(&forked, 1);
}

/* Registered when the library is loaded, so that a child is marked whoever forks it and
 * whenever (multiprocessing's workers, a C program's own fork()). */
__attribute__((constructor)) static void register_fork_handler(void)
{
    pthread_atfork(NULL, NULL, in_child);
}

int whirl_set_max_threads(int threads)
{
    if (threads < 0 || threads > WHIRL_THREADS_MAX)
        return whirl_fail(GSL_EINVAL, "threads must be 0 (OpenMP's default) or 1..%d, got %d",
                          WHIRL_THREADS_MAX, threads);
    if (threads != 1 && atomic_load(&forked))
        return whirl_fail(GSL_EINVAL, "threads: a child of fork() runs on one thread (the "
                          "OpenMP threads of its parent do not survive the fork), got %d",
                          threads);
    atomic_store(&max_threads, threads);
    return GSL_SUCCESS;
}

int whirl_threads_for(int wanted)
{
    if (atomic_load(&forked)) return 1;
    const int cap = atomic_load(&max_threads);
    return cap > 0 && cap < wanted ? cap : wanted;
}

int whirl_max_threads(void)
{
    int n = 1;
#ifdef _OPENMP
    n = omp_get_max_threads();
#endif
    return whirl_threads_for(n);
}

int whirl_forked_child(void)
{
    return atomic_load(&forked);
}
