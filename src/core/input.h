/* Internal: reading text input with bounds. Every stream the library and the program read (scene
 * files, measured shapes, traces) goes through whirl_line_read, which caps the length of a line
 * and the bytes read in all, checks them while it reads (so /dev/zero or an endless pipe ends in
 * a message, not in the memory of the machine), tells a failed allocation from the end of the
 * file, and honours the stop request (whirl_stop_requested) while it reads. */
#ifndef WHIRL_INPUT_H
#define WHIRL_INPUT_H

#include <stddef.h>
#include <stdio.h>

/* Opens path for reading; anything but a regular file (a device such as /dev/zero, a directory,
 * a FIFO, a socket) is refused, and a FIFO is never waited on. Returns GSL_SUCCESS and sets *fp,
 * or a status with the message "PATH: cannot read: reason". */
int whirl_input_open(const char *path, FILE **fp);

typedef struct whirl_line_reader {
    FILE *fp;
    const char *name;  /* the file's name in messages */
    size_t line_max;   /* longest line accepted, newline included [bytes] */
    size_t total_max;  /* most bytes read in all */
    char *line;        /* the line read, NUL-terminated (it may hold NUL bytes itself: len) */
    size_t len;        /* its length in bytes, newline included */
    size_t cap;
    size_t total;      /* bytes read so far */
    long lineno;       /* number of the line read */
    int status;        /* GSL_SUCCESS, or the status of the failure */
} whirl_line_reader;

/* A reader of fp (name in messages) with the two caps. */
whirl_line_reader whirl_line_reader_init(FILE *fp, const char *name, size_t line_max,
                                         size_t total_max);
/* Reads the next line: 1 when one was read, 0 at the end of the input, -1 on a failure (its
 * status in r->status and the message, with the name and line, in whirl_last_error): a line
 * longer than line_max, more than total_max bytes, out of memory, a read error, a stop request
 * (WHIRL_EINTERRUPTED). */
int whirl_line_read(whirl_line_reader *r);
void whirl_line_reader_free(whirl_line_reader *r);

/* "12 MiB", "1 GiB": a byte count for messages (buf: at least 32 chars). */
const char *whirl_bytes_words(char *buf, size_t size, double bytes);

#endif
