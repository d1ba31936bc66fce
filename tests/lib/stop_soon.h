/* For the tests of the stop request: a thread that requests a stop 5 ms after it starts, so that
 * the request arrives inside work that takes far longer (pthread_create(&t, NULL,
 * request_stop_soon, NULL), then the work, then pthread_join). */
#ifndef WHIRL_TEST_STOP_SOON_H
#define WHIRL_TEST_STOP_SOON_H

#include <pthread.h>
#include <time.h>

#include "whirl/common.h"

static void *request_stop_soon(void *arg)
{
    (void)arg;
    const struct timespec pause = {0, 5000000}; /* 5 ms */
    nanosleep(&pause, NULL);
    whirl_stop_request();
    return NULL;
}

#endif
