/* The discipline of --resume, shared by every long command that writes its rows into a file as
 * it goes (the stability map, the regime map, the atlas): the file is locked for the whole run
 * (cli_lock, cli.h); it must begin with exactly the lines this run would write before its rows
 * (the header, which records every option that changes a row, the columns last), else the
 * resume is refused in one line naming the first difference; after the header every complete
 * line is checked (the columns' count, finite numbers) and handed to the command, which
 * checks what only it knows (a mode asked for, a point of the map, a chunk); anything else
 * is refused with its line number. An unfinished last line (a run killed while writing it) is
 * dropped. The reading is the library's (core/resume.h); here its refusals are printed. */
#ifndef WHIRL_CLI_RESUME_H
#define WHIRL_CLI_RESUME_H

#include <stdio.h>

#include "cli/cli.h"
#include "core/resume.h"

/* The header, the kind and the limits (core/resume.h), and the kinds of line handed over:
 * CLI_RESUME_ERROR (refused: the message is printed), CLI_RESUME_END, CLI_RESUME_ROW,
 * CLI_RESUME_NOTE (a comment line: one starting with params.note among the header's lines, or
 * any after the header). */
typedef whirl_resume_params cli_resume_params;
typedef whirl_resume_kind cli_resume_kind;
#define CLI_RESUME_ERROR WHIRL_RESUME_ERROR
#define CLI_RESUME_END WHIRL_RESUME_END
#define CLI_RESUME_ROW WHIRL_RESUME_ROW
#define CLI_RESUME_NOTE WHIRL_RESUME_NOTE

typedef struct cli_resume cli_resume;

/* A reader of the file path (in: its stream, e.g. the lock's; not closed here). NULL after
 * printing "out of memory". */
cli_resume *cli_resume_alloc(const cli_command *cmd, FILE *in, const char *path,
                             const cli_resume_params *params);
void cli_resume_free(cli_resume *r);

/* The next line after the header, *line pointing to it (with its newline; valid until the next
 * call). The header's lines are matched on the way; a difference is refused with "--resume:
 * 'PATH' was not written by a KIND with these OF: line N has 'X' where these OF write 'Y'". */
cli_resume_kind cli_resume_next(cli_resume *r, const char **line);

/* The line number of the line last handed over. */
long cli_resume_lineno(const cli_resume *r);

/* Refuses the line last handed over: prints "--resume: PATH:N: WHY: the file cannot be trusted
 * (remove the row, or start the KIND afresh)" and returns CLI_RESUME_ERROR. */
int cli_resume_refuse(cli_resume *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* cli_resume_refuse for the line lineno, read earlier. */
int cli_resume_refuse_at(cli_resume *r, long lineno, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
