/* whirl stability --eigenvalues and --eigenvectors: every eigenvalue of the linearisation at one
 * rate (the symmetry's zeros removed) in increasing real part, or every mode, one row per mode
 * and node (stability_modes_csv.c), after comment lines with the growth, the index and the
 * verdict (stability_cli.h). */
#include <stdio.h>
#include <stdlib.h>

#include "cli/stability_cli.h"
#include "cli/stability_modes_csv.h"

/* The hand-swung chain: any of its options given. */
static int driven(const stability_options *o) { return hand_cli_given(&o->hand); }

/* The size of one dimensionless unit of the kind in the user's units. */
static double unit(const stability_options *o, cli_unit kind)
{
    return cli_units_scale(&o->units, kind);
}

/* order: 0..n-1 sorted by the real part of the eigenvalues (re, im), then the imaginary part. */
static void sort_eigenvalues(size_t *order, const double *re, const double *im, size_t n)
{
    for (size_t i = 0; i < n; i++) order[i] = i;
    for (size_t i = 1; i < n; i++) /* by real part, then imaginary part */
        for (size_t j = i; j > 0 && (re[order[j - 1]] > re[order[j]] ||
                                     (re[order[j - 1]] == re[order[j]] &&
                                      im[order[j - 1]] > im[order[j]]));
             j--) {
            const size_t t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
}

/* The n eigenvalues of the point p in the given order, after a comment line with its growth,
 * index and verdict. */
static void write_eigenvalues(FILE *fp, const stability_options *o, const stability_point *p,
                              size_t n, const double *re, const double *im,
                              const size_t *order, const whirl_stability_modes *md,
                              const whirl_chain *c)
{
    const double rate = unit(o, CLI_UNIT_RATE);
    char hand[200] = "";
    if (driven(o))
        snprintf(hand, sizeof hand, ", hand-swung: eps %s, drag %s, drag_quadratic %s, side %d",
                 CLI_NUM(o->hand.eps * unit(o, CLI_UNIT_LENGTH)),
                 CLI_NUM(o->hand.drag * unit(o, CLI_UNIT_DRAG)),
                 CLI_NUM(o->hand.drag2 * unit(o, CLI_UNIT_DRAG2)), o->hand.side);
    fprintf(fp, "# whirl stability --%s: omega %s, mode %d, %d links, damping %s%s; "
                "%zu eigenvalues lambda of the linearisation in the co-rotating frame "
                "(the rotation symmetry's zeros removed); growth %s, index %d, verdict "
                "%s\n", md ? "eigenvectors" : "eigenvalues", CLI_NUM(p->omega * rate), p->mode,
            o->links,
            CLI_NUM(o->damping * unit(o, CLI_UNIT_DAMPING)), hand, n,
            CLI_NUM(p->eig_growth * rate), p->index, whirl_verdict_name(p->verdict));
    if (md)
        fprintf(fp, "# modes: q(t) = Re(v e^{lambda t}); node displacements (dx, dy, dz) in the "
                    "co-rotating frame, largest 1; krein: energy sign of a neutral mode of the "
                    "conservative chain, else 0\n");
    cli_units_comment(fp, &o->units);
    if (md) {
        stability_modes_write(fp, md, order, c, rate, unit(o, CLI_UNIT_LENGTH));
        return;
    }
    fprintf(fp, "re,im\n");
    for (size_t i = 0; i < n; i++)
        fprintf(fp, "%s,%s\n", CLI_NUM(re[order[i]] * rate), CLI_NUM(im[order[i]] * rate));
}

/* The linearisation at the single point p in w, with its growth and verdict: 0, or 1 after an
 * error. */
static int linearise_point(const cli_command *cmd, stability_options *o, const whirl_chain *c,
                           whirl_stability *w, stability_point *p)
{
    o->linear = 1;
    if (stability_cli_analyse(o, c, w, p, NULL) != GSL_SUCCESS)
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    /* a free shape's growth is the map's (whirl_stability_map), not run here: from the
     * linearisation analyse made */
    if (!driven(o)) {
        if (whirl_stability_growth(w, &p->eig_growth) != GSL_SUCCESS)
            return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
        p->verdict = whirl_verdict_linear(p->eig_growth, p->index);
    }
    return 0;
}

/* The progress line while the dense solves of --eigenvalues run (whirl_stability_set_tick). */
typedef struct solve_line {
    cli_progress_state line;
    long links;
    double after; /* cli_progress_after() */
} solve_line;

static void solve_tick(void *data)
{
    solve_line *s = data;
    if (cli_wall_seconds() - s->line.start < s->after) return;
    cli_progress_text(&s->line, "eigen-solve of %ld links", s->links);
}

/* --eigenvalues: every eigenvalue of the linearisation at the one rate (the symmetry's zeros
 * removed), in increasing real part, with the index and the verdict in comment lines. */
int stability_cli_eigen(const cli_command *cmd, stability_options *o)
{
    whirl_chain *c = whirl_chain_alloc_uniform((size_t)o->links, 0);
    whirl_stability *w = whirl_stability_alloc((size_t)o->links);
    if (c == NULL || w == NULL) {
        whirl_chain_free(c);
        whirl_stability_free(w);
        return cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    }
    size_t count = 0;
    double *nodes = NULL;
    stability_point *pts = stability_cli_points(cmd, o, c, &count, &nodes);
    int rc = pts ? linearise_point(cmd, o, c, w, &pts[0]) : 1;
    size_t n = 0;
    const double *re = NULL, *im = NULL;
    solve_line progress = {.links = o->links, .after = cli_progress_after()};
    cli_progress_begin(&progress.line, cmd, "eigen-solve", 0, 0);
    whirl_stability_set_tick(w, solve_tick, &progress);
    whirl_stability_modes *md = NULL;
    if (!rc && o->eigenvectors && (md = whirl_stability_modes_alloc((size_t)o->links)) == NULL)
        rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    int solved = rc ? GSL_SUCCESS : whirl_stability_eigenvalues(w, &n, &re, &im);
    if (!rc && !solved && md) solved = whirl_stability_eigenvectors(w, md);
    cli_progress_clear(&progress.line);
    if (solved != GSL_SUCCESS) rc = cli_error(cmd, "%s", CLI_LIBRARY_ERROR(&o->units));
    size_t *order = rc ? NULL : malloc((n + 1) * sizeof *order);
    if (!rc && order == NULL) rc = cli_error(cmd, "out of memory");
    cli_out out;
    if (!rc && cli_out_open(cmd, &out, o->output)) rc = 1;
    if (!rc) {
        sort_eigenvalues(order, re, im, n);
        /* the modes' eigenvalues are those of re, im, in the same order */
        write_eigenvalues(out.fp, o, &pts[0], n, md ? md->re : re, md ? md->im : im, order, md,
                          c);
        if (cli_out_commit(cmd, &out)) rc = 1;
    }
    free(order);
    free(pts);
    free(nodes);
    whirl_stability_modes_free(md);
    whirl_stability_free(w);
    whirl_chain_free(c);
    return rc;
}
