/* The libFuzzer entry point every harness in tests/fuzz/ defines; replay.c calls it on files. */
#ifndef WHIRL_FUZZ_H
#define WHIRL_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#endif
