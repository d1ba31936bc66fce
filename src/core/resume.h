/* Internal: reading back a file that a long computation writes its rows into as it goes, to
 * resume it (the stability atlas, and the program's stability and regime maps): the file must
 * begin with exactly the lines this run would write before its rows (the header, which records
 * every option that changes a row, the columns last), else it is refused in one line naming the
 * first difference; after the header every complete line is checked (whirl_resume_row_check:
 * the columns' count, finite numbers) and handed to the caller, which checks what only it knows
 * (a mode asked for, a point of the map, a chunk); anything else is refused with its line
 * number. An unfinished last line (a run killed while writing it) is dropped. Failures are
 * GSL_EINVAL (a refused file) or GSL_EFAILED (a read error), with the message. */
#ifndef WHIRL_CORE_RESUME_H
#define WHIRL_CORE_RESUME_H

#include <stddef.h>
#include <stdio.h>

typedef struct whirl_resume_params {
    const char *header; /* the lines this run writes before its rows, the columns' line last */
    const char *kind;   /* what the file holds, in messages: "map", "atlas" */
    const char *of;     /* what must be the same, in messages: "options", "parameters" */
    const char *note;   /* comment lines starting so are allowed among the header's lines and
                         * handed to the caller (the atlas's "# done "); NULL: none */
    size_t line_max;    /* the longest line accepted, in characters */
    int blank;          /* 1: an empty line among the rows is handed over as a comment (the
                         * charts' breaks between curves, for gnuplot); 0: refused as a row */
} whirl_resume_params;

/* The kinds of line whirl_resume_next hands over. */
typedef enum {
    WHIRL_RESUME_ERROR = -1, /* refused: the message is set */
    WHIRL_RESUME_END = 0,    /* the end of the file (an unfinished last line dropped) */
    WHIRL_RESUME_ROW = 1,    /* a complete row, whole and finite */
    WHIRL_RESUME_NOTE = 2    /* a comment line: one starting with params.note among the
                              * header's lines, or any after the header, or
                              * with params.blank an empty one after it */
} whirl_resume_kind;

typedef struct whirl_resume whirl_resume;

/* A reader of the file path (in: its stream; not closed here; path and params->header are
 * read, not copied, and must outlive the reader). NULL (GSL_ENOMEM) without memory. */
whirl_resume *whirl_resume_alloc(FILE *in, const char *path, const whirl_resume_params *params);
void whirl_resume_free(whirl_resume *r); /* NULL is a no-op */

/* The next line after the header, *line pointing to it (with its newline; valid until the next
 * call). The header's lines are matched on the way; a difference is refused with "'PATH' was
 * not written by a KIND with these OF: line N has 'X' where these OF write 'Y'". */
whirl_resume_kind whirl_resume_next(whirl_resume *r, const char **line);

/* The line number of the line last handed over. */
long whirl_resume_lineno(const whirl_resume *r);

/* Refuses the line last handed over: the message "PATH:N: WHY: the file cannot be trusted
 * (remove the row, or start the KIND afresh)" (GSL_EINVAL); returns WHIRL_RESUME_ERROR. */
int whirl_resume_refuse(whirl_resume *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* whirl_resume_refuse for the line lineno, read earlier (a row that only the lines after it show
 * wrong: the charts' state comes after their rows). */
int whirl_resume_refuse_at(whirl_resume *r, long lineno, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The first difference between the line want (this run's) and have (the file's), words apart
 * (spaces), as "'X' where these OF write 'Y'" into buf: the differing word of each with the word
 * before it. */
void whirl_resume_difference(const char *want, const char *have, const char *of, char *buf,
                             size_t size);

/* 0 if the row line (with its newline) has fields comma-separated fields, none beginning with
 * a number that is not finite (nan, inf, 1e999); else -1 and the reason in why. */
int whirl_resume_row_check(const char *line, size_t fields, char *why, size_t size);

#endif
