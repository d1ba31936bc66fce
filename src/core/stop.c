/* The process-wide stop request (see include/whirl/common.h): a sig_atomic_t flag that signal
 * handlers may set and every long loop of the library polls. It is the one piece of global
 * state in the library, because the signals that raise it belong to the process. */
#include <signal.h>
#include <string.h>

#include "whirl/common.h"

static volatile sig_atomic_t stop_flag = 0;
static struct sigaction saved_int, saved_term;
static int signals_caught = 0;

void whirl_stop_request(void) { stop_flag = 1; }
int whirl_stop_requested(void) { return stop_flag != 0; }
void whirl_stop_clear(void) { stop_flag = 0; }

static void on_signal(int sig)
{
    (void)sig;
    stop_flag = 1;
}

int whirl_stop_catch_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    struct sigaction old_int, old_term;
    if (sigaction(SIGINT, &sa, &old_int) != 0) return GSL_EFAILED;
    if (sigaction(SIGTERM, &sa, &old_term) != 0) {
        sigaction(SIGINT, &old_int, NULL);
        return GSL_EFAILED;
    }
    if (!signals_caught) { /* keep the handlers from before the first call */
        saved_int = old_int;
        saved_term = old_term;
        signals_caught = 1;
    }
    return GSL_SUCCESS;
}

void whirl_stop_restore_signals(void)
{
    if (!signals_caught) return;
    sigaction(SIGINT, &saved_int, NULL);
    sigaction(SIGTERM, &saved_term, NULL);
    signals_caught = 0;
}
