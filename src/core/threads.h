/* Internal: the thread count of one parallel loop (see whirl_set_max_threads). */
#ifndef WHIRL_THREADS_H
#define WHIRL_THREADS_H

/* wanted threads, capped by whirl_set_max_threads and 1 in a child of fork(). */
int whirl_threads_for(int wanted);

#endif
