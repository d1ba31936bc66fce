/* The libFuzzer entry point every harness in tests/fuzz/ defines; replay.c calls it on files. */
#ifndef WHIRL_FUZZ_H
#define WHIRL_FUZZ_H

#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The sanitizers' reports go to this descriptor (weak: absent from a plain build). */
void __sanitizer_set_report_fd(void *fd) __attribute__((weak));

/* The one-line errors a harness expects are silenced by pointing the descriptors 1 and 2 at
 * /dev/null for the call (fuzz_quiet_begin / fuzz_quiet_end), never by assigning the streams
 * stdout and stderr themselves: the C library flushes its own streams at exit, and a stream
 * variable pointed elsewhere crashed it there (a SEGV in _IO_fflush at exit). The sanitizers'
 * reports keep a copy of the first descriptor 2, so a crash inside the call is still shown. */
typedef struct fuzz_quiet {
    int saved[2]; /* copies of 1 and 2 while silenced, -1 when not */
} fuzz_quiet;

static inline void fuzz_quiet_begin(fuzz_quiet *q)
{
    static int report = -1;
    if (report < 0 && (report = dup(2)) >= 0 && __sanitizer_set_report_fd)
        __sanitizer_set_report_fd((void *)(intptr_t)report);
    fflush(stdout);
    fflush(stderr);
    const int null = open("/dev/null", O_WRONLY);
    for (int k = 0; k < 2; k++) {
        q->saved[k] = null >= 0 ? dup(k + 1) : -1;
        if (q->saved[k] >= 0) dup2(null, k + 1);
    }
    if (null >= 0) close(null);
}

static inline void fuzz_quiet_end(fuzz_quiet *q)
{
    fflush(stdout);
    fflush(stderr);
    for (int k = 0; k < 2; k++)
        if (q->saved[k] >= 0) {
            dup2(q->saved[k], k + 1);
            close(q->saved[k]);
            q->saved[k] = -1;
        }
}

#endif
