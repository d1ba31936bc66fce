/* The process-wide stop request (see include/whirl/common.h): a sig_atomic_t flag that signal
 * handlers may set and every long loop of the library polls. It is the one piece of global
 * state in the library, because the signals that raise it belong to the process. The flag holds
 * the number of the signal that raised it (-1: a request from a caller). */
#include <signal.h>
#include <string.h>

#include "whirl/common.h"

static volatile sig_atomic_t stop_flag = 0;

/* The signals caught: those that end a process when a user or the system sends them. SIGINT,
 * SIGTERM and SIGQUIT are caught always (a shell starts background jobs with SIGINT and SIGQUIT
 * ignored, and `kill -INT` must still stop them); SIGHUP, SIGPIPE and SIGXFSZ only when not
 * ignored (nohup ignores SIGHUP; Python ignores SIGPIPE and SIGXFSZ and expects write errors).
 * With SIGPIPE and SIGXFSZ caught, the write that raised them fails (EPIPE, EFBIG) and the work
 * stops: the caller sees a write error, not a killed process. */
static const struct {
    int sig;
    int always;
} caught[] = {{SIGINT, 1}, {SIGTERM, 1}, {SIGQUIT, 1}, {SIGHUP, 0}, {SIGPIPE, 0}, {SIGXFSZ, 0}};
#define N_CAUGHT (sizeof caught / sizeof caught[0])
static struct sigaction saved[N_CAUGHT];
static int installed[N_CAUGHT];
static int signals_caught = 0;

void whirl_stop_request(void) { stop_flag = -1; }
int whirl_stop_requested(void) { return stop_flag != 0; }
int whirl_stop_signal(void) { return stop_flag > 0 ? (int)stop_flag : 0; }
void whirl_stop_clear(void) { stop_flag = 0; }

static void on_signal(int sig)
{
    if (stop_flag <= 0) stop_flag = sig; /* the first signal names the stop */
}

int whirl_stop_catch_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < N_CAUGHT; i++) {
        struct sigaction old;
        if (sigaction(caught[i].sig, NULL, &old) != 0) return GSL_EFAILED;
        if (old.sa_handler == on_signal) continue; /* caught already */
        if (!caught[i].always && old.sa_handler == SIG_IGN) continue;
        if (sigaction(caught[i].sig, &sa, &old) != 0) {
            whirl_stop_restore_signals();
            return GSL_EFAILED;
        }
        saved[i] = old; /* the handler from before the first call */
        installed[i] = 1;
        signals_caught = 1;
    }
    return GSL_SUCCESS;
}

void whirl_stop_restore_signals(void)
{
    if (!signals_caught) return;
    for (size_t i = 0; i < N_CAUGHT; i++)
        if (installed[i]) {
            sigaction(caught[i].sig, &saved[i], NULL);
            installed[i] = 0;
        }
    signals_caught = 0;
}
