/* whirl periodic --chart's file and --resume, shared by the vertical and the ellipse chart
 * (chart_file.c): the file's lock, its reading back by the library (periodic/chart_file.h: the
 * header, the rows, the state and every rule they must pass, whirl_chart_vertical_read's), the
 * state saved as the chart goes, and the end of a run. --resume reads -o FILE through its lock
 * (the maps' rules: resume.h, cli_lock); only the rates the file's state has not finished are
 * computed. */
#ifndef WHIRL_CLI_CHART_FILE_H
#define WHIRL_CLI_CHART_FILE_H

#include <stdio.h>

#include "cli/resume.h"
#include "periodic/chart_file.h"
#include "whirl/chain.h"

typedef struct chart_file {
    const cli_command *cmd;
    const char *path;   /* -o FILE (NULL: standard output) */
    cli_lock lock;
    chart_read rd;      /* the file read back (--resume): its rows and state */
    char *state;        /* the file's state (--resume), then the latest saved */
    int done;           /* the rates finished by the state saved */
    size_t rows_done;   /* the rows computed when it was saved */
    size_t state_cap;
} chart_file;

/* The file's units (periodic/chart_file.h) of the command's. */
chart_units chart_file_units(const cli_units *u);

/* Takes the lock of path; with resume, checks that it can be read. 0, or 1 after an error
 * (nothing to free then but chart_file_free). */
int chart_file_open(const cli_command *cmd, chart_file *f, const char *path, int resume);

/* After the library's reading into f->rd (chart_vertical_read, chart_ellipse_read) that gave
 * status: its refusal printed ("--resume: ..."), or the state read back taken. 0, or 1. */
int chart_file_read(chart_file *f, int status);

/* The library's save callback's work (chart_resume.h): the state after done rates, with rows
 * rows computed so far. 0, or GSL_ENOMEM. */
int chart_file_save(chart_file *f, int done, const char *state, size_t rows);

/* The state's lines, prefixed. */
void chart_file_write_state(const chart_file *f, FILE *fp);

/* The output written to f->path (out opened on it) put in place under the lock; 0 or 1. */
int chart_file_commit(chart_file *f, cli_out *out);

/* What a chart run needs once its file is open (rc: the opening's and the reading's, 0 if they
 * passed): the uniform chain of links links (*c) and the output on path (out), and with resume
 * the state read back copied (*state, the caller frees it). 0, or rc (or 1 after an error here)
 * with the chain and f freed. */
int chart_file_start(chart_file *f, int rc, int links, int resume, const cli_units *units,
                     whirl_chain **c, cli_out *out, char **state);

/* The end of a chart run that gave status: stopped (WHIRL_EINTERRUPTED) after the file was
 * written (written: 0, or 1 after an error), the message saying how far it came, of columns
 * rates, and CLI_EXIT_INTERRUPTED; any other failure (out aborted) its one-line error, a state
 * the library refused named as the file's (resumed: it came from --resume), and 1; else
 * written. */
int chart_file_finish(chart_file *f, int status, int written, int columns, int resumed,
                      const cli_units *units);

void chart_file_free(chart_file *f);

#endif
