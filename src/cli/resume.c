/* --resume: the library's reader of a file being resumed (core/resume.h), its refusals printed
 * as the command's one-line errors (resume.h). */
#include <stdarg.h>
#include <stdlib.h>

#include "cli/resume.h"

struct cli_resume {
    const cli_command *cmd;
    whirl_resume *r;
};

/* The library's message of the refusal just made, printed: CLI_RESUME_ERROR. */
static int print_refusal(const cli_resume *r)
{
    cli_error(r->cmd, "--resume: %s", whirl_last_error());
    return CLI_RESUME_ERROR;
}

cli_resume *cli_resume_alloc(const cli_command *cmd, FILE *in, const char *path,
                             const cli_resume_params *params)
{
    cli_resume *r = calloc(1, sizeof *r);
    if (r) r->r = whirl_resume_alloc(in, path, params);
    if (r == NULL || r->r == NULL) {
        free(r);
        cli_error(cmd, "out of memory");
        return NULL;
    }
    r->cmd = cmd;
    return r;
}

void cli_resume_free(cli_resume *r)
{
    if (r == NULL) return;
    whirl_resume_free(r->r);
    free(r);
}

long cli_resume_lineno(const cli_resume *r)
{
    return whirl_resume_lineno(r->r);
}

int cli_resume_refuse(cli_resume *r, const char *fmt, ...)
{
    char why[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    whirl_resume_refuse(r->r, "%s", why);
    return print_refusal(r);
}

cli_resume_kind cli_resume_next(cli_resume *r, const char **line)
{
    const whirl_resume_kind kind = whirl_resume_next(r->r, line);
    return kind == WHIRL_RESUME_ERROR ? print_refusal(r) : kind;
}

int cli_resume_refuse_at(cli_resume *r, long lineno, const char *fmt, ...)
{
    char why[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    whirl_resume_refuse_at(r->r, lineno, "%s", why);
    return print_refusal(r);
}
