/* Fuzz harness: the command-line option parser (cli_parse) on an argument vector cut from the
 * input at NUL and newline bytes, against a table with every option type (numbers, integers,
 * strings, integer lists, flags, an alias, the unit options), then the unit checks. Every input
 * must parse, print the help, or end in a one-line error. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "fuzz.h"

#define ARGS_MAX 32

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const cli_command cmd = {"fuzz", "[OPTIONS]", "The option parser under test.", NULL};
    char *text = malloc(size + 1);
    if (text == NULL) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    char *argv[ARGS_MAX + 1];
    int argc = 0;
    argv[argc++] = "fuzz";
    for (char *p = text; argc < ARGS_MAX && p <= text + size;) {
        size_t len = strcspn(p, "\n");
        p[len] = '\0';
        argv[argc++] = p;
        p += len + 1;
    }
    argv[argc] = NULL;
    double omega = 0;
    int mode = 0, flag = 0, omega_given = 0;
    const char *out = NULL, *positional[2];
    cli_int_list modes = {0, {0}};
    cli_units units = {1, 1, 1};
    const cli_option opts[] = {
        {"--omega", "-w", CLI_DOUBLE, &omega, &omega_given, "W", "a number"},
        {"--mode", NULL, CLI_INT, &mode, NULL, "K", "an integer"},
        {"--modes", NULL, CLI_INT_LIST, &modes, NULL, "LIST", "a list"},
        {"--linear", NULL, CLI_FLAG, &flag, NULL, "", "a flag"},
        {"--output", "-o", CLI_STRING, &out, NULL, "FILE", "a string"},
        CLI_UNITS_OPTIONS(units),
    };
    fuzz_quiet q; /* the help and the one-line errors are expected */
    fuzz_quiet_begin(&q);
    int rc = cli_parse(&cmd, argc, argv, opts, sizeof opts / sizeof opts[0], positional, 2);
    if (rc == 0) {
        cli_units_check(&cmd, &units);
        if (modes.n < 0 || modes.n > CLI_LIST_MAX) abort();
    }
    fuzz_quiet_end(&q);
    free(text);
    if (rc < 0 || rc > 2) abort();
    return 0;
}
