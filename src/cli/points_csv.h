/* The measured points of `whirl fit`: a CSV with columns r and z (header required, other
 * columns ignored, '#' comments and blank lines skipped). */
#ifndef WHIRL_POINTS_CSV_H
#define WHIRL_POINTS_CSV_H

#include <stdio.h>

#include "cli/cli.h"

#define POINTS_CSV_LINE_MAX 4096 /* longest line read, with its newline */
/* most bytes read: 20000 points (the most a fit takes) in full precision are under 1 MiB */
#define POINTS_CSV_BYTES_MAX ((size_t)64 << 20)

typedef struct points_csv {
    size_t n, cap; /* points read, room allocated */
    double *r, *z; /* n of each, in the file's units */
} points_csv;

/* Reads the r and z columns of the open stream fp (name: for messages) into p (start it as
 * {0, 0, NULL, NULL}; free it with points_csv_free even after an error). Returns 0, or 1 after
 * printing a one-line error "NAME:LINE: problem" (a NUL byte, a line too long, more than
 * POINTS_CSV_BYTES_MAX in all, a missing or non-numeric or non-finite value, no header, out of
 * memory, a stop request). */
int points_csv_read(const cli_command *cmd, FILE *fp, const char *name, points_csv *p);
/* points_csv_read on the file path ("-": standard input); anything but a regular file is
 * refused. */
int points_csv_read_path(const cli_command *cmd, const char *path, points_csv *p);
void points_csv_free(points_csv *p);

#endif
