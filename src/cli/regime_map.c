/* whirl regime, the map (see cmd_regime.c for the command and the file's format): one row per
 * grid point, point index = i_eps n + i_omega, written to -o FILE as the points finish, in index
 * order. Each point is one independent run seeded by --seed + index. With Open MPI (built with
 * -DWHIRL_MPI, run by mpirun -n K) the points are dealt out in rounds of 4 x threads points per
 * rank: rank r takes the points r, r + K, r + 2K, ... of the round (neighbours on the grid, of
 * similar cost, spread over the ranks) and runs them on its OpenMP threads; rank 0 gathers the
 * results and appends them in index order, so the rows are those of a single process. Ctrl-C
 * stops after the current round with the finished points kept (exit 130); --resume reads FILE
 * (resume.h: its header that of these parameters, every row one of this map's points), drops an
 * unfinished last line and computes only the missing points. --folds FILE: the folds of the steady driven branches for every eps of the map. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_math.h>

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef WHIRL_MPI
#include <mpi.h>
#endif

#include "cli/regime_cli.h"
#include "cli/resume.h"
#include "whirl/driven.h"

#define RESULT_FIELDS 16 /* doubles per packed result */
#define FOLD_MODES 3

static void grid_point(const regime_options *o, long index, double *omega, double *eps)
{
    *omega = cli_grid(o->omega_min, o->omega_max, o->omega_steps, (int)(index % o->omega_steps));
    *eps = cli_grid(o->eps_min, o->eps_max, o->eps_steps, (int)(index / o->omega_steps));
}

static void write_map_row(FILE *fp, const regime_options *o, long index,
                          const whirl_regime_result *r)
{
    double omega, eps;
    grid_point(o, index, &omega, &eps);
    fprintf(fp, "%ld,%s,%s,", index, CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega)),
            CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, eps)));
    regime_cli_write_result(fp, o, r);
}

/* ---- packing a result for the gather (doubles, index first; index -1: no point) ---- */

static void pack(double *buf, long index, const whirl_regime_result *r)
{
    const double v[RESULT_FIELDS] = {(double)index, r->state, r->nodes, r->period, r->t_end,
                                     r->change, r->remaining, r->shape_error, r->bvp_nodes,
                                     r->lyapunov, r->tip[0], r->tip[1], r->tip[2], r->tip_r,
                                     (double)r->steps, 0};
    memcpy(buf, v, sizeof v);
}

static long unpack(const double *buf, whirl_regime_result *r)
{
    r->state = (whirl_regime_state)buf[1];
    r->nodes = (int)buf[2];
    r->period = (int)buf[3];
    r->t_end = buf[4];
    r->change = buf[5];
    r->remaining = buf[6];
    r->shape_error = buf[7];
    r->bvp_nodes = (int)buf[8];
    r->lyapunov = buf[9];
    for (int k = 0; k < 3; k++) r->tip[k] = buf[10 + k];
    r->tip_r = buf[13];
    r->steps = (unsigned long)buf[14];
    return (long)buf[0];
}

/* ---- the map file: fresh or resumed ---- */

/* The lines before the rows of a fresh map. */
static void write_head(FILE *fp, const regime_options *o, const whirl_chain *chain)
{
    fprintf(fp, "# whirl regime map: %d x %d points (omega x eps), node count from rest\n",
            o->omega_steps, o->eps_steps);
    regime_cli_write_parameters(fp, o);
    regime_cli_write_critical(fp, o, chain);
    fprintf(fp, "%s\n", regime_cli_map_columns);
}

/* A complete row of the map file (whole and finite): the point it names marked done[] and
 * counted in *n_done, the row copied to out; a row of no point of the map (an index beyond it,
 * or a rate and eps that are not its index's) or of one already read is refused. */
static int keep_row(cli_resume *in, const regime_options *o, const char *line, char *done,
                    long n_points, long *n_done, FILE *out)
{
    char *end;
    errno = 0;
    const long index = strtol(line, &end, 10);
    char *expect = NULL;
    size_t len = 0;
    if (end != line && *end == ',' && errno == 0 && index >= 0 && index < n_points) {
        FILE *mem = open_memstream(&expect, &len);
        if (mem == NULL) return cli_resume_refuse(in, "out of memory");
        double omega, eps;
        grid_point(o, index, &omega, &eps);
        fprintf(mem, "%ld,%s,%s,", index, CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, omega)),
                CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, eps)));
        if (fclose(mem) != 0) len = 0;
    }
    const int ours = expect && len > 0 && strncmp(line, expect, len) == 0;
    free(expect);
    if (!ours)
        return cli_resume_refuse(in, "'%.*s' is no point of this map (index, omega, eps)",
                                 (int)strcspn(line, "\n"), line);
    if (done[index]) return cli_resume_refuse(in, "point %ld read twice", index);
    done[index] = 1;
    ++*n_done;
    fputs(line, out);
    return 0;
}

/* Reads a map file (through the lock) that must begin with the lines a fresh map of these
 * parameters writes (resume.h): marks its complete rows in done[], counts them in *n_done and
 * rewrites the file with them only (an unfinished last line and the closing comments
 * dropped). Returns 0 or 1 after an error. */
static int resume_map(const cli_command *cmd, const regime_options *o, const whirl_chain *chain,
                      cli_lock *lock, char *done, long n_points, long *n_done)
{
    char *header = NULL;
    size_t header_len = 0;
    FILE *mem = open_memstream(&header, &header_len);
    if (mem == NULL) return cli_error(cmd, "out of memory");
    write_head(mem, o, chain);
    if (fclose(mem) != 0) {
        free(header);
        return cli_error(cmd, "out of memory");
    }
    const cli_resume_params rp = {.header = header, .kind = "map", .of = "parameters",
                                  .line_max = REGIME_LINE_MAX - 2};
    cli_resume *in = cli_resume_alloc(cmd, lock->fp, o->output, &rp);
    cli_out out;
    int rc = in ? cli_out_open(cmd, &out, o->output) : 1;
    if (rc) {
        cli_resume_free(in);
        free(header);
        return rc;
    }
    fputs(header, out.fp);
    *n_done = 0;
    const char *line;
    for (cli_resume_kind kind; !rc && (kind = cli_resume_next(in, &line)) != CLI_RESUME_END;) {
        if (kind == CLI_RESUME_ERROR) rc = 1;
        else if (kind == CLI_RESUME_NOTE && strncmp(line, "# computed ", 11) != 0)
            rc = cli_resume_refuse(in, "a comment among the rows") ? 1 : 0;
        else if (kind == CLI_RESUME_ROW)
            rc = keep_row(in, o, line, done, n_points, n_done, out.fp) ? 1 : 0;
    }
    cli_resume_free(in);
    free(header);
    if (rc != 0) {
        cli_out_abort(&out);
        return rc;
    }
    return cli_lock_commit(cmd, lock, &out);
}

static int fresh_map(const cli_command *cmd, const regime_options *o, const whirl_chain *chain,
                     cli_lock *lock)
{
    cli_out out;
    if (cli_out_open(cmd, &out, o->output) != 0) return 1;
    write_head(out.fp, o, chain);
    return cli_lock_commit(cmd, lock, &out);
}

/* ---- the map ---- */

static int max_threads(void)
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

static int thread_id(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

/* Runs the points pending[first..first+count-1] on the threads, packed results into buf. Returns 0,
 * or 1 if a run returned an error status: the earliest point's failure is then this thread's
 * (whirl_last_error), carried from the thread that ran it in err[] (count records). */
static int run_block(const regime_options *o, whirl_regime **ws, const long *pending, long count,
                     double *buf, whirl_error_record *err)
{
#pragma omp parallel for schedule(dynamic, 1)
    for (long j = 0; j < count; j++) {
        whirl_regime_params p = o->p;
        grid_point(o, pending[j], &p.omega, &p.drive_radius);
        p.seed = o->p.seed + (unsigned long)pending[j];
        whirl_regime_result r;
        memset(&r, 0, sizeof r);
        const int status = whirl_regime_run(ws[thread_id()], &p, &r), ok = status == GSL_SUCCESS;
        err[j].status = GSL_SUCCESS;
        if (status != WHIRL_EINTERRUPTED) /* a stopped point is left to --resume */
            whirl_error_keep(&err[j], status);
        pack(buf + j * RESULT_FIELDS, ok ? pending[j] : -1, &r);
    }
    return whirl_error_restore_first(err, (size_t)count) != GSL_SUCCESS;
}

/* The folds of the steady driven branches of modes 1..FOLD_MODES, both sides, for every eps of
 * the map (rank 0, after the map). */
static int write_folds(const cli_command *cmd, const regime_options *o, const whirl_chain *chain)
{
    cli_out out;
    if (cli_out_open(cmd, &out, o->folds) != 0) return 1;
    whirl_driven_curve *curve = whirl_driven_curve_alloc(20000);
    if (curve == NULL) {
        cli_out_abort(&out);
        return cli_error(cmd, "out of memory");
    }
    fprintf(out.fp, "# folds of the steady driven branches (whirl_driven_branch), N-link chain\n");
    regime_cli_write_parameters(out.fp, o);
    fprintf(out.fp, "eps,mode,side,fold,omega\n");
    for (int ie = 0; ie < o->eps_steps && !cli_interrupted; ie++) {
        const double eps = cli_grid(o->eps_min, o->eps_max, o->eps_steps, ie);
        const whirl_driven_params dp = {.omega = o->omega_max, .drive_radius = eps,
                                        .air_drag = o->p.air_drag,
                                        .air_drag_quadratic = o->p.air_drag_quadratic};
        for (int mode = 1; mode <= FOLD_MODES; mode++)
            for (int side = 1; side >= -1; side -= 2) {
                whirl_driven_info start;
                if (whirl_driven_mode(chain, &dp, mode, side, &start) != GSL_SUCCESS) continue;
                if (whirl_driven_branch(chain, &dp, &start, -1, o->omega_min, o->omega_max,
                                        0.02, curve) != GSL_SUCCESS)
                    continue;
                for (size_t f = 0; f < curve->n_folds; f++)
                    fprintf(out.fp, "%s,%d,%d,%zu,%s\n", CLI_NUM(regime_cli_user(o, CLI_UNIT_LENGTH, eps)),
                            mode, side, f, CLI_NUM(regime_cli_user(o, CLI_UNIT_RATE, curve->fold_omega[f])));
            }
    }
    whirl_driven_curve_free(curve);
    return cli_out_commit(cmd, &out);
}

/* Collective over the ranks: the largest of v. */
static int all_max(const mpi_context *mc, int v)
{
#ifdef WHIRL_MPI
    if (mc->size > 1) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
#else
    (void)mc;
#endif
    return v;
}

/* Rank 0: the map file locked (one run at a time writes a map: from before the old one is read,
 * through the lock's stream, or a new path is made empty by this run so that two runs started
 * on it together are kept apart, until the run ends), started (a fresh map's header, or the old
 * rows read back into done, *n_done of them) and opened for appending (*fp). 0, or 1 after an
 * error. */
static int open_map(const cli_command *cmd, const regime_options *o, const whirl_chain *chain,
                    cli_lock *lock, char *done, long n_points, long *n_done, FILE **fp)
{
    int rc = 0;
    if (o->resume && access(o->output, F_OK) != 0)
        rc = cli_error(cmd, "--resume: cannot read '%s': %s", o->output, strerror(errno));
    if (rc == 0) rc = cli_lock_take(cmd, lock, o->output, !o->resume);
    if (rc == 0 && o->resume && lock->fp == NULL)
        rc = cli_error(cmd, "--resume: '%s' is not a regular file", o->output);
    if (rc == 0)
        rc = o->resume ? resume_map(cmd, o, chain, lock, done, n_points, n_done)
                       : fresh_map(cmd, o, chain, lock);
    if (rc == 0 && (*fp = fopen(o->output, "a")) == NULL)
        rc = cli_error(cmd, "cannot append to '%s': %s", o->output, strerror(errno));
    return rc;
}

/* Rank 0: the rows of a round of `round` points gathered in buf (point k of the round: rank
 * k % K, its k / K-th, at slot (k % K) block + k / K); returns the count written. */
static long write_round(FILE *fp, const regime_options *o, const mpi_context *mc,
                        const double *buf, long round, long block)
{
    long written = 0;
    for (long k = 0; k < round; k++) {
        whirl_regime_result r;
        const long slot = (k % mc->size) * block + k / mc->size;
        const long index = unpack(buf + slot * RESULT_FIELDS, &r);
        if (index < 0) continue;
        write_map_row(fp, o, index, &r);
        written++;
    }
    return written;
}

/* The state of a map's run on this rank. */
typedef struct map_run {
    long n_points, already, written;
    int threads, stop;
    double start; /* wall seconds */
    FILE *fp;     /* rank 0: the map */
} map_run;

/* Rank 0 at the end: the closing comment, the file closed, a stop reported, the folds. rc: the
 * run's status so far; returns the final one. */
static int close_map(const cli_command *cmd, const regime_options *o, const whirl_chain *chain,
                     const mpi_context *mc, map_run *m, cli_progress_state *progress, int rc)
{
    const double seconds = cli_wall_seconds() - m->start;
    cli_progress_update(progress, m->already + m->written, 1);
    if (rc == 0 && !m->stop)
        fprintf(m->fp, "# computed %ld points in %.3f s wall on %d rank(s) x %d thread(s)\n",
                m->written, seconds, mc->size, m->threads);
    if (fclose(m->fp) != 0 && rc == 0) rc = cli_error(cmd, "cannot write '%s'", o->output);
    if (rc == 0 && m->stop)
        rc = 130, cli_error(cmd, "interrupted: %ld of %ld points in '%s' (continue with "
                            "--resume)", m->already + m->written, m->n_points, o->output);
    if (rc == 0 && o->folds) rc = write_folds(cmd, o, chain);
    return rc;
}

int regime_cli_run_map(const cli_command *cmd, const regime_options *o, const whirl_chain *chain,
                   const mpi_context *mc)
{
    map_run m = {(long)o->omega_steps * o->eps_steps, 0, 0, max_threads(), 0, 0, NULL};
    const long n_points = m.n_points;
    const long block = all_max(mc, 4 * m.threads); /* points per rank and round */
    char *done = calloc((size_t)n_points, 1);
    long *pending = malloc((size_t)n_points * sizeof *pending);
    long *mine = malloc((size_t)block * sizeof *mine);
    double *buf = malloc((size_t)(block * mc->size) * RESULT_FIELDS * sizeof *buf);
    whirl_regime **ws = calloc((size_t)m.threads, sizeof *ws);
    whirl_error_record *err = malloc((size_t)block * sizeof *err);
    int rc = done && pending && mine && buf && ws && err ? 0 : 1;
    for (int k = 0; rc == 0 && k < m.threads; k++)
        if ((ws[k] = whirl_regime_alloc(chain)) == NULL) rc = 1;
    if (rc) cli_error(cmd, "out of memory");
    long n_done = 0;
    cli_lock lock = {0};
    if (mc->rank == 0 && rc == 0)
        rc = open_map(cmd, o, chain, &lock, done, n_points, &n_done, &m.fp);
    rc = all_max(mc, rc);
#ifdef WHIRL_MPI
    if (rc == 0 && mc->size > 1) MPI_Bcast(done, (int)n_points, MPI_CHAR, 0, MPI_COMM_WORLD);
#endif
    long n_pending = 0;
    for (long i = 0; rc == 0 && i < n_points; i++)
        if (!done[i]) pending[n_pending++] = i;
    m.already = n_points - n_pending;
    m.start = cli_wall_seconds();
    cli_progress_state progress;
    cli_progress_begin(&progress, cmd, "points", n_points, m.already);
    cli_catch_interrupts();
    for (long first = 0; rc == 0 && first < n_pending; first += block * mc->size) {
        const long round = GSL_MIN(block * mc->size, n_pending - first);
        long count = 0;
        for (long k = mc->rank; k < round; k += mc->size) mine[count++] = pending[first + k];
        for (long j = 0; j < block; j++) buf[j * RESULT_FIELDS] = -1;
        int failed = count > 0 ? run_block(o, ws, mine, count, buf, err) : 0;
        if (failed)
            cli_error(cmd, "a run failed on rank %d: %s", mc->rank, CLI_LIBRARY_ERROR(&o->units));
#ifdef WHIRL_MPI
        if (mc->size > 1)
            MPI_Gather(mc->rank == 0 ? MPI_IN_PLACE : buf, (int)(block * RESULT_FIELDS),
                       MPI_DOUBLE, buf, (int)(block * RESULT_FIELDS), MPI_DOUBLE, 0,
                       MPI_COMM_WORLD);
#endif
        if (mc->rank == 0) {
            m.written += write_round(m.fp, o, mc, buf, round, block);
            if (fflush(m.fp) != 0) failed = cli_error(cmd, "cannot write '%s'", o->output);
            cli_progress_update(&progress, m.already + m.written, 0);
        }
        rc = all_max(mc, failed);
        m.stop = all_max(mc, cli_interrupted != 0);
        if (m.stop) break;
    }
    if (mc->rank == 0 && m.fp) rc = close_map(cmd, o, chain, mc, &m, &progress, rc);
    cli_lock_release(&lock);
    for (int k = 0; ws && k < m.threads; k++) whirl_regime_free(ws[k]);
    free(ws);
    free(err);
    free(buf);
    free(mine);
    free(pending);
    free(done);
    return rc;
}
