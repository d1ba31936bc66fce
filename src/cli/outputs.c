/* Files and signals of the whirl program (docs/guide/files-and-signals.md): the exit status after
 * a signal. */
#include "cli/cli.h"

int cli_exit_status(int rc)
{
    if ((rc == 1 || rc == CLI_EXIT_INTERRUPTED) && whirl_stop_requested()) {
        const int sig = whirl_stop_signal();
        return sig > 0 ? 128 + sig : CLI_EXIT_INTERRUPTED;
    }
    return rc;
}
