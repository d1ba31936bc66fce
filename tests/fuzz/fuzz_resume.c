/* Fuzz harness: the readers of --resume (src/core/resume.c, through src/cli/resume.c) on arbitrary
 * bytes as the file being resumed: the atlas's (stability_atlas_check, whirl_atlas_read: its
 * header, "# done" lines and rows, for the modes 2,3 to omega 6, two chunks per mode), then the
 * shared reader under a map's header, whose rows must then be whole and finite. Every input must end in a file accepted or a one-line
 * error; the sanitizers catch the rest (an index past the chunks' array once). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/resume.h"
#include "cli/stability_atlas.h"
#include "fuzz.h"

#define MAP_FIELDS 4 /* columns of the map's header below */

/* The shared reader under a map's header: a row handed over must have MAP_FIELDS finite
 * numbers and end with its newline, else abort. */
static void read_map(const cli_command *cmd, FILE *fp)
{
    const cli_resume_params rp = {
        .header = "# whirl stability: 6 links, damping 0, linear analysis only\n"
                  "# map: omega 2 to 4, 3 rates, modes 1,2\n"
                  "omega,mode,links,eig_growth\n",
        .kind = "map", .of = "options", .note = "# done ", .line_max = 256};
    cli_resume *in = cli_resume_alloc(cmd, fp, "fuzz.csv", &rp);
    if (in == NULL) return;
    const char *line;
    for (cli_resume_kind kind; (kind = cli_resume_next(in, &line)) > CLI_RESUME_END;) {
        if (kind != CLI_RESUME_ROW) continue;
        const char *p = line;
        for (int k = 0; k < MAP_FIELDS; k++) {
            char *end;
            const double x = strtod(p, &end);
            const size_t len = strcspn(p, ",\n");
            if (len > 0 && end != p && !isfinite(x)) abort(); /* a non-finite number */
            p += len;
            if (*p != (k + 1 < MAP_FIELDS ? ',' : '\n')) abort(); /* another count of fields */
            p++;
        }
        if (*p != '\0') abort();
        if (cli_resume_lineno(in) < 4) abort(); /* a row before the header's end */
    }
    cli_resume_free(in);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const cli_command cmd = {"stability", "", "", NULL};
    const cli_int_list modes = {2, {2, 3}};
    if (size == 0) return 0; /* (fmemopen of no bytes fails) */
    FILE *fp = fmemopen((void *)data, size, "r");
    if (fp == NULL) return 0;
    fuzz_quiet q; /* the readers' one-line errors are expected */
    fuzz_quiet_begin(&q);
    const int rc = stability_atlas_check(&cmd, fp, "fuzz.csv", &modes, 6, 16, 1e-9, 0.25);
    rewind(fp);
    read_map(&cmd, fp);
    fuzz_quiet_end(&q);
    fclose(fp);
    if (rc != 0 && rc != 1) abort();
    return 0;
}
