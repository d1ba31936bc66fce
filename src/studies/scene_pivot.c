/* Scenes: the pivot's path, [run] pivot (include/whirl/scene.h: why it lives beside whirl_scene
 * in a whirl_scene_pivot, not in it). The text is whirl_pivot_parse's (whirl/periodic.h) at the
 * scene's [run] omega in the scene's units: the chain of a scene is built in those units (SI: m,
 * s, g = 9.80665 m/s^2), so a path in SI units is parsed with the chain's length taken as 1 m
 * (its lengths stay in m) and a dimensionless one with none (a unit suffix is then refused). */
#include <stdio.h>
#include <string.h>

#include "whirl/scene.h"
#include "whirl/periodic.h"
#include "core/error.h"
#include "studies/scene_internal.h"

/* The checks of the path against the scene and the parse: GSL_SUCCESS with *path, or GSL_EINVAL
 * with a message without location. */
static int path_of(const whirl_scene *s, const char *text, whirl_pivot_path *path)
{
    if (s->frame != WHIRL_FRAME_INERTIAL)
        return whirl_fail(GSL_EINVAL, "a pivot path needs [run] frame = inertial (the path is "
                          "given in the inertial frame)");
    if (s->drive_radius != 0)
        return whirl_fail(GSL_EINVAL, "a pivot path conflicts with [run] drive_radius: give one "
                          "motion of the pivot (circle:R is the drive of radius R)");
    if (!(s->omega > 0))
        return whirl_fail(GSL_EINVAL, "a pivot path needs [run] omega > 0: the path's rate "
                          "(its period is 2 pi / omega)");
    if (text[0] == '\0') return whirl_fail(GSL_EINVAL, "must not be empty");
    const double length = s->physical ? 1.0 : 0.0; /* SI: lengths in m, over 1 m */
    int status = whirl_pivot_parse(text, s->omega, length, s->dim, path);
    if (status == GSL_SUCCESS || s->physical) return status;
    /* a dimensionless scene: in 3D the text reads in SI units and not without them only when
     * it has a unit (the scene's message then); else the first message again */
    whirl_pivot_path si, plain;
    if (whirl_pivot_parse(text, s->omega, 1.0, 3, &si) == GSL_SUCCESS &&
        whirl_pivot_parse(text, s->omega, 0.0, 3, &plain) != GSL_SUCCESS)
        return whirl_fail(GSL_EINVAL, "'%s' has a unit, but the scene is dimensionless: give "
                          "[units] system = SI (lengths in m), or lengths in units of L", text);
    return whirl_pivot_parse(text, s->omega, length, s->dim, path);
}

int whirl_scene_pivot_from_text(const whirl_scene *scene, const char *text,
                                whirl_scene_pivot *pivot)
{
    if (scene == NULL || text == NULL || pivot == NULL || scene->path == NULL)
        return whirl_fail(GSL_EINVAL, "whirl_scene_pivot_from_text: needs a parsed scene, a "
                          "text and pivot");
    whirl_pivot_path path;
    int status = path_of(scene, text, &path);
    if (status != GSL_SUCCESS) return status;
    *pivot = (whirl_scene_pivot){.given = 1, .line = 0, .path = path};
    return GSL_SUCCESS;
}

int sc_convert_pivot(const convert *v)
{
    const char *text = v->raw[SC_KEY_RUN_PIVOT];
    if (text == NULL) return GSL_SUCCESS;
    char where[300], msg[600];
    sc_where(v->scene, SC_KEY_RUN_PIVOT, v->line[SC_KEY_RUN_PIVOT], where, sizeof where);
    if (v->pivot == NULL)
        return whirl_fail(GSL_EINVAL, "%s: not read by whirl_scene_parse, whose whirl_scene has "
                          "no field for it: this program needs whirl_scene_parse_with_pivot",
                          where);
    whirl_scene_pivot pivot;
    if (whirl_scene_pivot_from_text(v->scene, text, &pivot) != GSL_SUCCESS) {
        snprintf(msg, sizeof msg, "%s", whirl_error_marked());
        return whirl_fail(GSL_EINVAL, "%s: %s", where, msg);
    }
    pivot.line = v->line[SC_KEY_RUN_PIVOT];
    *v->pivot = pivot;
    return GSL_SUCCESS;
}

#define NUM(x) whirl_format_double((char[WHIRL_FORMAT_MAX]){0}, (x))

void sc_write_pivot_text(FILE *fp, const whirl_pivot_path *p)
{
    static const char axis[3] = {'x', 'y', 'z'};
    int terms = 0;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < p->harmonics && j < WHIRL_PIVOT_HARMONICS_MAX; j++)
            for (int q = 0; q < 2; q++) {
                const double a = q ? p->s[k][j] : p->c[k][j];
                if (a == 0) continue;
                fprintf(fp, "%s%c%d%c=%s", terms++ ? "," : "fourier:", axis[k], j + 1,
                        q ? 's' : 'c', NUM(a));
            }
    if (terms == 0) fputs("line:0", fp);
}

/* "# pivot = fourier:x1c=A,y1s=B" (sc_write_pivot_text). */
static void write_pivot_line(FILE *fp, const whirl_pivot_path *p)
{
    fputs("# pivot = ", fp);
    sc_write_pivot_text(fp, p);
    fputc('\n', fp);
}

int sc_write_pivot_line(FILE *fp, const whirl_scene_pivot *pivot)
{
    if (pivot != NULL && pivot->given) write_pivot_line(fp, &pivot->path);
    return ferror(fp) ? whirl_fail(GSL_EFAILED, "cannot write the header") : GSL_SUCCESS;
}
