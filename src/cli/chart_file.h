/* whirl periodic --chart's file and --resume, shared by the vertical and the ellipse chart
 * (chart_file.c). A chart is written whole at the end (its rows by curve, gnuplot's blank line
 * between curves), also when stopped: then with only the rates finished and a comment line
 * saying so. Its lines:
 *   the header: the comment lines that record every option changing a row, the "# units:" line
 *     and the columns' line (matched by --resume, resume.h);
 *   among them the lines "# found: ..." (the counts, and where a stopped chart stopped);
 *   the rows;
 *   at the end the lines "# state: ...": the chart's state after its finished rates
 *     (periodic/chart_resume.h), from which --resume goes on as if it had never stopped.
 * --resume reads -o FILE through its lock (the maps' rules: resume.h, cli_lock): the header must
 * be this run's; every row is checked by the chart (its fields) and here (no row twice, as many
 * rows as the "# found: points=" line says, no comment among them but the state's); the rates
 * finished are the state's, and only the others are computed. */
#ifndef WHIRL_CLI_CHART_FILE_H
#define WHIRL_CLI_CHART_FILE_H

#include <stdio.h>

#include "cli/resume.h"
#include "whirl/chain.h"

#define CHART_FOUND "# found: "
#define CHART_STATE "# state: "

/* A row read back: its text (with the newline), line, curve (from 1), rate and second value as
 * written (the file's units). */
typedef struct chart_kept {
    char *line;
    long lineno;
    int curve;
    double omega, value;
    int end; /* the ellipse chart: an end of a curve on e = 0 */
} chart_kept;

/* The check of a row's fields by its chart: fills k (not line, lineno); NULL, or what is wrong. */
typedef const char *(*chart_row_check)(void *ctx, const char *line, chart_kept *k);

typedef struct chart_file {
    const cli_command *cmd;
    const char *path;   /* -o FILE (NULL: standard output) */
    cli_lock lock;
    cli_resume *in;     /* the reader (--resume), kept for the refusals after the reading */
    chart_kept *kept;
    size_t n_kept;
    char *state;        /* the file's state (--resume), then the latest saved */
    int done;           /* the rates finished by the state saved */
    size_t rows_done;   /* the rows computed when it was saved */
    size_t state_cap;
} chart_file;

/* Takes the lock of path and, with resume, reads it back: header is the text the chart writes
 * before its rows (without the "# found: " lines), check its rows' check. 0, or 1 after an
 * error (nothing to free then but chart_file_free). */
int chart_file_open(const cli_command *cmd, chart_file *f, const char *path, int resume,
                    const char *header, chart_row_check check, void *ctx);

/* The first number after "key=" in the state's text, or fallback. */
long chart_file_state_value(const chart_file *f, const char *key, long fallback);

/* Refuses the row k read back: the one-line error; 1. */
int chart_file_refuse(chart_file *f, const chart_kept *k, const char *why);

/* The library's save callback's work (chart_resume.h): the state after done rates, with rows
 * rows computed so far. 0, or GSL_ENOMEM. */
int chart_file_save(chart_file *f, int done, const char *state, size_t rows);

/* The state's lines, prefixed. */
void chart_file_write_state(const chart_file *f, FILE *fp);

/* The output written to f->path (out opened on it) put in place under the lock; 0 or 1. */
int chart_file_commit(chart_file *f, cli_out *out);

/* What a chart run needs once its file is open (rc: the opening's and the rows' checks, 0 if
 * they passed): the uniform chain of links links (*c) and the output on path (out), and with
 * resume the state read back copied (*state, the caller frees it). 0, or rc (or 1 after an error
 * here) with the chain and f freed. */
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
