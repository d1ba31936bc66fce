/* Pivot paths (whirl/periodic.h): Fourier terms, the presets and the parser of their text.
 * p_k(t) = sum_j c_kj cos(j w t) + s_kj sin(j w t), so
 * p_k'  = sum_j j w (-c_kj sin + s_kj cos),  p_k'' = -sum_j (j w)^2 (c_kj cos + s_kj sin). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_math.h>

#include "core/error.h"
#include "whirl/periodic.h"

static const char axis_name[3] = {'x', 'y', 'z'};

static void path_clear(whirl_pivot_path *path, double omega)
{
    memset(path, 0, sizeof *path);
    path->omega = omega;
    path->harmonics = 1;
}

int whirl_pivot_check(const whirl_pivot_path *path, int dim)
{
    if (path == NULL) return whirl_fail(GSL_EINVAL, "no pivot path");
    if (!(isfinite(path->omega) && path->omega > 0))
        return whirl_fail(GSL_EINVAL, "pivot path: the rate must be positive and finite, got "
                          "omega=" WHIRL_Q_RATE "%g", path->omega);
    if (whirl_check_omega_max(path->omega)) return GSL_EINVAL;
    if (path->harmonics < 1 || path->harmonics > WHIRL_PIVOT_HARMONICS_MAX)
        return whirl_fail(GSL_EINVAL, "pivot path: harmonics must be 1..%d, got %d",
                          WHIRL_PIVOT_HARMONICS_MAX, path->harmonics);
    if (dim != 2 && dim != 3) return whirl_fail(GSL_EINVAL, "dim must be 2 or 3, got %d", dim);
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < path->harmonics; j++) {
            const double a[2] = {path->c[k][j], path->s[k][j]};
            for (int q = 0; q < 2; q++) {
                if (!isfinite(a[q]))
                    return whirl_fail(GSL_EINVAL, "pivot path: term %c%d%c is not finite",
                                      axis_name[k], j + 1, q ? 's' : 'c');
                if (dim == 2 && k == 1 && a[q] != 0)
                    return whirl_fail(GSL_EINVAL, "pivot path: term y%d%c moves the pivot out of "
                                      "the x-z plane of a planar model", j + 1, q ? 's' : 'c');
            }
        }
    return GSL_SUCCESS;
}

double whirl_pivot_period(const whirl_pivot_path *path) { return 2 * M_PI / path->omega; }

void whirl_pivot_eval(double t, double p[3], double pv[3], double pa[3], void *params)
{
    const whirl_pivot_path *path = params;
    for (int k = 0; k < 3; k++) p[k] = pv[k] = pa[k] = 0;
    for (int j = 1; j <= path->harmonics; j++) {
        const double w = j * path->omega, c = cos(w * t), s = sin(w * t);
        for (int k = 0; k < 3; k++) {
            const double a = path->c[k][j - 1], b = path->s[k][j - 1];
            if (a == 0 && b == 0) continue;
            const double pos = a * c + b * s;
            p[k] += pos;
            /* w b c - w a s rounds as the model's circle drive does (-eps w s, eps w c): a
             * circle path and drive_radius move the pivot bit for bit alike */
            pv[k] += w * b * c - w * a * s;
            pa[k] -= w * w * pos;
        }
    }
}

static int preset_check(double omega, const double *len, int n)
{
    if (!(isfinite(omega) && omega > 0))
        return whirl_fail(GSL_EINVAL, "pivot path: the rate must be positive and finite, got "
                          "omega=" WHIRL_Q_RATE "%g", omega);
    for (int i = 0; i < n; i++)
        if (!isfinite(len[i]))
            return whirl_fail(GSL_EINVAL, "pivot path: a length is not finite");
    return GSL_SUCCESS;
}

int whirl_pivot_circle(whirl_pivot_path *path, double omega, double r)
{
    return whirl_pivot_ellipse(path, omega, r, r);
}

int whirl_pivot_ellipse(whirl_pivot_path *path, double omega, double a, double b)
{
    const double len[2] = {a, b};
    if (path == NULL) return whirl_fail(GSL_EINVAL, "no pivot path");
    if (preset_check(omega, len, 2)) return GSL_EINVAL;
    path_clear(path, omega);
    path->c[0][0] = a;
    path->s[1][0] = b;
    return GSL_SUCCESS;
}

int whirl_pivot_line(whirl_pivot_path *path, double omega, double a, const double dir[3])
{
    if (path == NULL || dir == NULL) return whirl_fail(GSL_EINVAL, "no path or no direction");
    const double len[4] = {a, dir[0], dir[1], dir[2]};
    if (preset_check(omega, len, 4)) return GSL_EINVAL;
    const double norm = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(norm > 0 && isfinite(norm)))
        return whirl_fail(GSL_EINVAL, "pivot path: the line's direction is zero");
    path_clear(path, omega);
    for (int k = 0; k < 3; k++) path->c[k][0] = a * dir[k] / norm;
    return GSL_SUCCESS;
}

int whirl_pivot_eight(whirl_pivot_path *path, double omega, double a, double b)
{
    const double len[2] = {a, b};
    if (path == NULL) return whirl_fail(GSL_EINVAL, "no pivot path");
    if (preset_check(omega, len, 2)) return GSL_EINVAL;
    path_clear(path, omega);
    path->harmonics = 2;
    path->s[0][0] = a;
    path->s[1][1] = b;
    return GSL_SUCCESS;
}

/* ---- the parser ---- */

/* The longest text of one term kept for a message. */
#define TERM_MAX 64

/* One length term of text[0..len-1] into *v: whirl_parse_quantity, then in units of L. */
static int parse_length(const char *text, size_t len, double length, const char *what,
                        double *v)
{
    char buf[TERM_MAX];
    if (len == 0 || len >= sizeof buf)
        return whirl_fail(GSL_EINVAL, "pivot path: %s: expected a length, got '%.*s'", what,
                          (int)(len < sizeof buf ? len : sizeof buf - 1), text);
    memcpy(buf, text, len);
    buf[len] = '\0';
    int suffixed = 0;
    if (whirl_parse_quantity(buf, WHIRL_QUANTITY_LENGTH, v, &suffixed) != 0)
        return whirl_fail(GSL_EINVAL, "pivot path: %s: '%s' is not a length (a number, with "
                          "%s in SI units)", what, buf,
                          whirl_quantity_suffixes(WHIRL_QUANTITY_LENGTH));
    if (suffixed && !(length > 0))
        return whirl_fail(GSL_EINVAL, "pivot path: %s: '%s' has a unit: units need the chain's "
                          "length in SI units", what, buf);
    if (length > 0) *v /= length;
    if (!isfinite(*v))
        return whirl_fail(GSL_EINVAL, "pivot path: %s: '%s' is out of range", what, buf);
    return GSL_SUCCESS;
}

/* Splits the argument list args at commas into at most max items (start, length). */
static int split(const char *args, const char **item, size_t *len, int max)
{
    int n = 0;
    const char *p = args;
    for (;;) {
        const char *comma = strchr(p, ',');
        if (n == max) return max + 1;
        item[n] = p;
        len[n] = comma ? (size_t)(comma - p) : strlen(p);
        n++;
        if (!comma) break;
        p = comma + 1;
    }
    return n;
}

/* A "fourier:" term AXIS J KIND=LENGTH. */
static int parse_fourier_term(const char *t, size_t len, double length, whirl_pivot_path *path)
{
    const char *eq = memchr(t, '=', len);
    char name[TERM_MAX];
    const size_t name_len = eq ? (size_t)(eq - t) : len;
    snprintf(name, sizeof name, "%.*s", (int)(name_len < TERM_MAX ? name_len : TERM_MAX - 1), t);
    if (eq == NULL)
        return whirl_fail(GSL_EINVAL, "pivot path: term '%s' has no '=' (write e.g. x1c=1cm)",
                          name);
    int axis = -1, kind = -1;
    long j = 0;
    if (name_len >= 3) {
        const char *ax = strchr("xyz", name[0]);
        axis = ax && name[0] ? (int)(ax - "xyz") : -1;
        const char last = name[name_len - 1];
        kind = last == 'c' ? 0 : last == 's' ? 1 : -1;
        char *end;
        j = strtol(name + 1, &end, 10);
        if (end != name + name_len - 1 || name[1] < '0' || name[1] > '9') j = 0;
    }
    if (axis < 0 || kind < 0 || j < 1 || j > WHIRL_PIVOT_HARMONICS_MAX)
        return whirl_fail(GSL_EINVAL, "pivot path: term '%s' is not AXIS HARMONIC KIND (axis x, y "
                          "or z, harmonic 1..%d, kind c or s: e.g. x1c, z2s)", name,
                          WHIRL_PIVOT_HARMONICS_MAX);
    double v;
    int status = parse_length(eq + 1, len - name_len - 1, length, name, &v);
    if (status) return status;
    double *slot = kind ? &path->s[axis][j - 1] : &path->c[axis][j - 1];
    if (*slot != 0)
        return whirl_fail(GSL_EINVAL, "pivot path: term '%s' is given twice", name);
    *slot = v;
    if (j > path->harmonics) path->harmonics = (int)j;
    return GSL_SUCCESS;
}

int whirl_pivot_parse(const char *text, double omega, double length, int dim,
                      whirl_pivot_path *out)
{
    if (text == NULL || out == NULL) return whirl_fail(GSL_EINVAL, "no pivot path text");
    const char *colon = strchr(text, ':');
    const size_t name_len = colon ? (size_t)(colon - text) : strlen(text);
    static const struct {
        const char *name;
        int min, max; /* arguments */
        const char *form;
    } kinds[] = {{"circle", 1, 1, "circle:R"},          {"ellipse", 2, 2, "ellipse:A,B"},
                 {"line", 1, 4, "line:A[,DX,DY,DZ]"},   {"vertical", 1, 1, "vertical:A"},
                 {"eight", 2, 2, "eight:A,B"},
                 {"fourier", 1, 6 * WHIRL_PIVOT_HARMONICS_MAX, "fourier:x1c=A,..."}};
    int kind = -1;
    for (int i = 0; i < (int)(sizeof kinds / sizeof kinds[0]); i++)
        if (strlen(kinds[i].name) == name_len && strncmp(text, kinds[i].name, name_len) == 0)
            kind = i;
    if (kind < 0)
        return whirl_fail(GSL_EINVAL, "pivot path '%.*s': unknown kind (circle, ellipse, line, "
                          "vertical, eight or fourier)", (int)(name_len < TERM_MAX ? name_len : TERM_MAX), text);
    if (colon == NULL || colon[1] == '\0')
        return whirl_fail(GSL_EINVAL, "pivot path: %s needs its arguments: %s", kinds[kind].name,
                          kinds[kind].form);
    enum { ARGS_MAX = 6 * WHIRL_PIVOT_HARMONICS_MAX };
    const char *item[ARGS_MAX + 1];
    size_t len[ARGS_MAX + 1];
    const int n = split(colon + 1, item, len, kinds[kind].max);
    if (n < kinds[kind].min || n > kinds[kind].max)
        return whirl_fail(GSL_EINVAL, "pivot path: %s takes %s, got %s%d argument%s",
                          kinds[kind].name, kinds[kind].form, n > kinds[kind].max ? "more than " : "",
                          n > kinds[kind].max ? kinds[kind].max : n, n == 1 ? "" : "s");
    whirl_pivot_path path;
    double v[4] = {0, 0, 0, 0};
    int status = GSL_SUCCESS;
    static const char *const arg_names[][4] = {{"R"}, {"A", "B"}, {"A", "DX", "DY", "DZ"},
                                               {"A"}, {"A", "B"}};
    if (strcmp(kinds[kind].name, "fourier") == 0) {
        if (preset_check(omega, v, 0)) return GSL_EINVAL;
        path_clear(&path, omega);
        for (int i = 0; i < n && status == GSL_SUCCESS; i++)
            status = parse_fourier_term(item[i], len[i], length, &path);
    } else {
        for (int i = 0; i < n && status == GSL_SUCCESS; i++) {
            char what[TERM_MAX];
            snprintf(what, sizeof what, "%s %s", kinds[kind].name, arg_names[kind][i]);
            if (kind == 2 && i > 0) { /* a direction's components: pure numbers */
                char buf[TERM_MAX];
                snprintf(buf, sizeof buf, "%.*s", (int)(len[i] < TERM_MAX ? len[i] : TERM_MAX - 1),
                         item[i]);
                if (whirl_parse_quantity(buf, WHIRL_QUANTITY_NUMBER, &v[i], NULL) != 0)
                    status = whirl_fail(GSL_EINVAL, "pivot path: %s: '%s' is not a number", what,
                                        buf);
            } else {
                status = parse_length(item[i], len[i], length, what, &v[i]);
            }
        }
        if (status) return status;
        const double x_dir[3] = {1, 0, 0}, z_dir[3] = {0, 0, 1};
        switch (kind) {
        case 0: status = whirl_pivot_circle(&path, omega, v[0]); break;
        case 1: status = whirl_pivot_ellipse(&path, omega, v[0], v[1]); break;
        case 2:
            if (n != 1 && n != 4)
                return whirl_fail(GSL_EINVAL, "pivot path: line takes A or A,DX,DY,DZ, got %d "
                                  "arguments", n);
            status = whirl_pivot_line(&path, omega, v[0], n == 4 ? v + 1 : x_dir);
            break;
        case 3: status = whirl_pivot_line(&path, omega, v[0], z_dir); break;
        default: status = whirl_pivot_eight(&path, omega, v[0], v[1]); break;
        }
    }
    if (status == GSL_SUCCESS) status = whirl_pivot_check(&path, dim);
    if (status == GSL_SUCCESS) *out = path;
    return status;
}
