/* The last failure's message, one per thread so that sweeps can run threads. */
#include <stdarg.h>
#include <stdio.h>

#include "whirl/common.h"
#include "error.h"

static _Thread_local char last_error[512];

const char *whirl_last_error(void) { return last_error; }

int whirl_fail(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return status;
}
