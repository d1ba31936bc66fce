/* Fuzz harness: the scene parser (whirl_scene_parse_stream) on arbitrary bytes and, when the
 * scene is valid and small, a short run of it by `whirl simulate` (at most 40 steps of at most 8
 * links, the output to /dev/null). Every input must end in a parsed scene or a one-line error;
 * the sanitizers catch the rest. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "fuzz.h"
#include "whirl/scene.h"

#define RUN_LINKS_MAX 8
#define RUN_STEPS_MAX 40
#define RUN_RADIANS_MAX 1e4 /* links x |omega| x t_end of a short run */

/* A short run of the scene text in a temporary file, t_end cut to RUN_STEPS_MAX steps. */
static void short_run(const uint8_t *data, size_t size, const whirl_scene *s)
{
    char path[] = "/tmp/whirl-fuzz-XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return;
    FILE *fp = fdopen(fd, "w");
    if (fp == NULL) {
        close(fd);
        unlink(path);
        return;
    }
    fwrite(data, 1, size, fp);
    fclose(fp);
    /* fixed steps end at every output time too: rows every "every" force steps of at most it */
    const double step = s->tol > 0 ? s->every : fmin(s->dt, s->every);
    const double t_cut = fmin(s->t_end, RUN_STEPS_MAX * step);
    /* the adaptive methods take steps ~ 1/omega in the rotating frame: a short run is one of
     * few radians too (the library's bound counts links |omega| t_end, whirl/scene.h) */
    if ((double)s->links * fabs(s->omega) * t_cut > RUN_RADIANS_MAX) {
        unlink(path);
        return;
    }
    char t_end[64];
    snprintf(t_end, sizeof t_end, "run.t_end=%.17g", t_cut);
    char *argv[] = {"simulate", path, "--set", t_end, "-o", "/dev/null", NULL};
    static const cli_command cmd = {"simulate", "", "", cmd_simulate};
    fuzz_quiet q; /* the command's one-line errors are expected */
    fuzz_quiet_begin(&q);
    cmd_simulate(&cmd, 6, argv);
    fuzz_quiet_end(&q);
    unlink(path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *fp = fmemopen((void *)data, size, "r");
    if (fp == NULL) return 0;
    whirl_scene s;
    int status = whirl_scene_parse_stream(fp, "fuzz.ini", NULL, 0, &s);
    fclose(fp);
    if (status != GSL_SUCCESS) {
        const char *msg = whirl_last_error();
        if (msg[0] == '\0' || strchr(msg, '\n') != NULL) abort(); /* one line, never empty */
        return 0;
    }
    /* small runs only; no trace file (its name comes from the input) */
    if (s.links <= RUN_LINKS_MAX && s.trace == NULL && size > 0)
        short_run(data, size, &s);
    whirl_scene_free(&s);
    return 0;
}
