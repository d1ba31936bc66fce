/* whirl: scenes. A scene is an INI file describing one simulation run of the N-link chain:
 * the chain, its start, the run (frame, integrator, forces) and what to write.
 *
 *   [units]  system = dimensionless | SI (default dimensionless): the units of every value in
 *            the scene and of the output. Dimensionless: lengths in L, masses in M, time in
 *            sqrt(L/g), rates in sqrt(g/L) (whirl's units when length, mass and gravity are 1).
 *            SI: m, kg, s, rad/s, N; gravity defaults to 9.80665 m/s^2. Either way a value of a
 *            physical kind may carry a unit suffix (whirl_parse_quantity: 60cm, 50g, 4Hz, 240rpm,
 *            5ms), which multiplies it by the suffix's factor to m, kg, rad/s or s.
 *   [chain]  dim = 2 | 3 (required), links = N (required), length (the chain's length, equal
 *            links; default 1) or lengths (comma list of N), mass (the chain's mass, equal
 *            masses; default 1) or masses (comma list of N), gravity (default 1, SI 9.80665)
 *   [start]  one of three starts:
 *            - omega, mode (both required): the exact N-link steady shape of mode k at omega
 *              (3D only), rotating rigidly at omega;
 *            - theta (required), theta_dot, phi, phi_dot (comma lists of N, default 0): the seed's
 *              angles [rad] and their rates [1/T] as seen in the inertial frame (zero rates:
 *              at rest in the inertial frame, whatever the run's frame); theta from the downward
 *              vertical, phi the azimuth from x; in 2D theta is signed in the x-z plane
 *              (x = l sin theta) and phi, phi_dot are not allowed;
 *            - hanging = true: straight down, moving with the pivot (at rest in the inertial
 *              frame when the pivot is fixed);
 *            and, for the steady and the hanging start, perturb (default 0), seed (default 1):
 *            each link direction turned by exactly perturb radians about a random axis
 *            perpendicular to it (GSL's MT19937 seeded with seed), lengths kept; in a planar
 *            scene (dim = 2) towards the perpendicular direction in the x-z plane, on the side
 *            of the random one.
 *   [run]    frame = inertial | rotating (default inertial; rotating needs dim = 3),
 *            method (default gauss2; see whirl_integrator_methods), dt > 0, t_end > 0 (both
 *            required), formulation = default | seed (default: default), omega (rate of the
 *            rotating frame and of the pivot drive; default the [start] omega, else 0),
 *            drive_radius, air_drag, air_drag_quadratic, internal_damping (>= 0, default 0),
 *            seed_sigma, seed_lambda (comma lists of N, 2D only; default none), tol (>= 0,
 *            default 0: fixed steps of dt; > 0: adaptive with tolerance tol, dt the first step),
 *            stop_deviation (> 0: stop once the deviation from the start's steady shape exceeds
 *            it, checked after every step, with tol > 0 at the output times; default none),
 *            threads (the cores one right-hand side of a long chain may use, default 1; see
 *            whirl_dyn_set_threads), pivot (the pivot's periodic path at the rate omega, in
 *            the grammar of whirl periodic --pivot: circle:R, ellipse:A,B, line:A[,DX,DY,DZ],
 *            vertical:A, eight:A,B or fourier:x1c=A,z2s=B,..., lengths in the scene's units;
 *            needs omega > 0, frame = inertial and no drive_radius; default none: the pivot
 *            moves as drive_radius says; read by whirl_scene_parse_with_pivot, below)
 *   [output] every (> 0, the output interval, default dt; the last row is at t_end), columns
 *            (comma list from t, tip_x, tip_y, tip_z, energy, jacobi, lz, constraint,
 *            deviation; t is always the first column; default all but deviation), trace (file
 *            of every mass's position; in the file a path relative to the scene's folder,
 *            neither absolute nor with a ".." component; in an override a path relative to
 *            the working directory; default none),
 *            trace_every (> 0, default every), reference_mode (K >= 1: the deviation is
 *            measured from the N-link steady shape of mode K at the [run] omega, 3D only;
 *            default: from the start's unperturbed steady or hanging shape)
 *
 * Syntax (inih): "key = value" lines under "[section]" headers, comment lines start with ';' or
 * '#', " ;" starts an inline comment, an indented line continues the previous key's list.
 * Keys may appear once. Overrides "section.key=value" replace or add keys after the file.
 * Every problem is reported as "FILE:LINE: [section] key: problem" (LINE absent for a missing
 * key, "FILE: --set section.key: problem" for an override). */
#ifndef WHIRL_SCENE_H
#define WHIRL_SCENE_H

#include <stddef.h>
#include <stdio.h>

#include "whirl/common.h"
#include "whirl/dynamics.h"
#include "whirl/periodic.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest fixed-step run a scene may ask for, links x t_end / dt (link-steps): a few hours
 * of work (about 1 us per link-step); larger runs are refused when the scene is read. */
#define WHIRL_SCENE_WORK_MAX 1e10
/* What the output and the rotation force on top of the steps, counted in the same budget: a row
 * every [output] every and a trace frame every trace_every each end a step (links x t_end /
 * every link-steps), and the adaptive methods take steps of order 1/omega in the rotating frame
 * (links x |omega| x t_end). The rows and the trace's points are bounded apart, for the files
 * they make: at most WHIRL_SCENE_ROWS_MAX rows (about 2 GB of CSV) and WHIRL_SCENE_TRACE_MAX
 * points (about 6 GB of trace). */
#define WHIRL_SCENE_ROWS_MAX 1e7
#define WHIRL_SCENE_TRACE_MAX 1e8

/* Every key of a scene; the index of whirl_scene.line. */
typedef enum {
    WHIRL_KEY_CHAIN_DIM,
    WHIRL_KEY_CHAIN_LINKS,
    WHIRL_KEY_CHAIN_LENGTH,
    WHIRL_KEY_CHAIN_LENGTHS,
    WHIRL_KEY_CHAIN_MASS,
    WHIRL_KEY_CHAIN_MASSES,
    WHIRL_KEY_CHAIN_GRAVITY,
    WHIRL_KEY_START_OMEGA,
    WHIRL_KEY_START_MODE,
    WHIRL_KEY_START_PERTURB,
    WHIRL_KEY_START_SEED,
    WHIRL_KEY_START_THETA,
    WHIRL_KEY_START_PHI,
    WHIRL_KEY_START_THETA_DOT,
    WHIRL_KEY_START_PHI_DOT,
    WHIRL_KEY_START_HANGING,
    WHIRL_KEY_RUN_FRAME,
    WHIRL_KEY_RUN_METHOD,
    WHIRL_KEY_RUN_DT,
    WHIRL_KEY_RUN_T_END,
    WHIRL_KEY_RUN_FORMULATION,
    WHIRL_KEY_RUN_OMEGA,
    WHIRL_KEY_RUN_DRIVE_RADIUS,
    WHIRL_KEY_RUN_AIR_DRAG,
    WHIRL_KEY_RUN_AIR_DRAG_QUADRATIC,
    WHIRL_KEY_RUN_INTERNAL_DAMPING,
    WHIRL_KEY_RUN_SEED_SIGMA,
    WHIRL_KEY_RUN_SEED_LAMBDA,
    WHIRL_KEY_RUN_TOL,
    WHIRL_KEY_RUN_STOP_DEVIATION,
    WHIRL_KEY_RUN_THREADS,
    WHIRL_KEY_OUTPUT_EVERY,
    WHIRL_KEY_OUTPUT_COLUMNS,
    WHIRL_KEY_OUTPUT_TRACE,
    WHIRL_KEY_OUTPUT_TRACE_EVERY,
    WHIRL_KEY_OUTPUT_REFERENCE_MODE,
    WHIRL_KEY_UNITS_SYSTEM,
    WHIRL_SCENE_NKEYS
} whirl_scene_key;

typedef enum {
    WHIRL_START_STEADY = 1, /* [start] omega, mode: the N-link steady shape */
    WHIRL_START_ANGLES,     /* [start] theta, ...: the seed's coordinates */
    WHIRL_START_HANGING     /* [start] hanging = true */
} whirl_start_kind;

/* The output columns, in the order of their names above. */
typedef enum {
    WHIRL_COLUMN_T,
    WHIRL_COLUMN_TIP_X,
    WHIRL_COLUMN_TIP_Y,
    WHIRL_COLUMN_TIP_Z,
    WHIRL_COLUMN_ENERGY,
    WHIRL_COLUMN_JACOBI,
    WHIRL_COLUMN_LZ,
    WHIRL_COLUMN_CONSTRAINT,
    WHIRL_COLUMN_DEVIATION,
    WHIRL_NCOLUMNS
} whirl_column;

/* The parsed scene with every default filled in. Arrays are owned (whirl_scene_free). */
typedef struct whirl_scene {
    char *path; /* the scene file, as given */

    /* [units] */
    int physical;     /* 1: SI (m, kg, s, rad/s, N); 0: dimensionless (default) */

    /* [chain] */
    int dim;              /* 2 (x-z plane) or 3 */
    size_t links;         /* N >= 1 */
    double *length;       /* N link lengths > 0; default chain_length/N each */
    double *mass;         /* N masses > 0; default chain_mass/N each */
    double chain_length;  /* the sum of length[] [L or m]; [chain] length, default 1 */
    double chain_mass;    /* the sum of mass[] [M or kg]; [chain] mass, default 1 */
    double gravity;       /* g > 0; default 1, with SI units 9.80665 [m/s^2] */

    /* [start] */
    whirl_start_kind start;
    double start_omega;    /* STEADY: rate of the steady shape, > 0 */
    int mode;              /* STEADY: node count, 1..links */
    double perturb;        /* STEADY, HANGING: angle each link direction is turned by [rad] */
    unsigned long seed;    /* STEADY, HANGING: seed of the random turns; default 1 */
    double *theta;         /* ANGLES: N angles from the downward vertical [rad]; else NULL */
    double *phi;           /* ANGLES: N azimuths from x [rad] (0 in 2D); else NULL */
    double *theta_dot;     /* ANGLES: N rates [1/T], default 0; else NULL */
    double *phi_dot;       /* ANGLES: N rates [1/T], default 0 (0 in 2D); else NULL */

    /* [run] */
    whirl_frame frame;             /* default inertial */
    char *method;                  /* integrator name, default "gauss2" (checked when run) */
    double dt;                     /* step, or the first step when tol > 0 [T], > 0 */
    double t_end;                  /* end time [T], > 0 */
    whirl_formulation formulation; /* default WHIRL_FORMULATION_CARTESIAN */
    double omega;                  /* whirl_model.omega: default start_omega (STEADY) or 0 */
    double drive_radius;           /* whirl_model fields, >= 0, default 0 */
    double air_drag;
    double air_drag_quadratic;
    double internal_damping;
    double *seed_sigma;            /* N values or NULL (2D only) */
    double *seed_lambda;           /* N values or NULL (2D only) */
    double tol;                    /* 0: fixed steps; > 0: adaptive tolerance */
    double stop_deviation;         /* > 0: stop threshold; 0: none */
    int threads;                   /* threads of one right-hand side (whirl_dyn_set_threads),
                                      1..WHIRL_DYN_THREADS_MAX; default 1 */

    /* [output] */
    double every;                  /* output interval [T] > 0; default dt */
    size_t n_columns;              /* >= 1; columns[0] is always WHIRL_COLUMN_T */
    whirl_column columns[WHIRL_NCOLUMNS];
    int want[WHIRL_NCOLUMNS];      /* want[c] = 1 if column c is written */
    char *trace;                   /* trace file or NULL */
    double trace_every;            /* [T] > 0; default every */
    int reference_mode;            /* K >= 1: deviation from the mode-K shape at omega; 0: from
                                      the start's shape (default) */

    /* where each key came from: its line (> 0), -1 for an override, 0 if absent (default) */
    int line[WHIRL_SCENE_NKEYS];
} whirl_scene;

/* Parses and validates the scene file path with the overrides "section.key=value" applied
 * after it (n_overrides may be 0, overrides then NULL). On success fills *scene (free it with
 * whirl_scene_free). On failure returns GSL_EINVAL (GSL_ENOMEM, GSL_EFAILED for an unreadable
 * file) with the one-line message "FILE:LINE: [section] key: problem" in whirl_last_error(),
 * and leaves *scene empty (whirl_scene_free is still safe).
 * @param path the scene file's name
 * @param overrides the overrides "section.key=value", n_overrides, applied in order; NULL if none
 * @param n_overrides the overrides, >= 0
 * @param scene out: the scene, to free with whirl_scene_free (also after a failure)
 * @return GSL_SUCCESS, or GSL_EINVAL, GSL_ENOMEM or GSL_EFAILED with a message
 */
WHIRL_API int whirl_scene_parse(const char *path, const char *const *overrides, size_t n_overrides,
                                whirl_scene *scene);

/* whirl_scene_parse reading the open stream fp (not closed here; path names it in messages
 * and in scene->path).
 * @param fp the open stream of the scene file, read and not closed
 * @param path the file's name, in the messages and scene->path
 * @param overrides the overrides "section.key=value", n_overrides, applied in order; NULL if none
 * @param n_overrides the overrides, >= 0
 * @param scene out: the scene, to free with whirl_scene_free (also after a failure)
 * @return as whirl_scene_parse
 */
WHIRL_API int whirl_scene_parse_stream(FILE *fp, const char *path, const char *const *overrides,
                                       size_t n_overrides, whirl_scene *scene);

/* Frees the arrays of the scene and zeroes it; NULL is a no-op.
 * @param scene the scene, or NULL
 */
WHIRL_API void whirl_scene_free(whirl_scene *scene);

/* Writes the location of key into buf (size bytes): "FILE:LINE: [section] key",
 * "FILE: --set section.key" or "FILE: [section] key" (not given). Returns buf.
 * @param scene the parsed scene
 * @param key the key
 * @param buf out: the location, NUL-terminated, cut at size - 1 bytes
 * @param size the bytes of buf
 * @return buf
 */
WHIRL_API const char *whirl_scene_where(const whirl_scene *scene, whirl_scene_key key, char *buf,
                                        size_t size);

/* The name of output column c ("tip_x"), or NULL.
 * @param c the column
 * @return the name (static text), or NULL for no column
 */
WHIRL_API const char *whirl_column_name(whirl_column c);

/* ---- running a scene (src/scene_run.c) ----
 * The start state, in the run's frame at t = 0, the pivot at (drive_radius, 0, 0) moving with
 * the drive: steady: the N-link shape of mode k at [start] omega turning rigidly at that rate
 * (whirl_dyn_state_from_shape), each link turned by perturb (whirl_perturb_links); angles: the
 * seed's angles and rates (zero rates: at rest in the inertial frame but for the pivot's
 * motion); hanging: straight down, moving with the pivot, turned like the steady start.
 * Rows at t = k every and at t_end, the columns of the scene (positions in the inertial frame;
 * energy, jacobi, lz, constraint of whirl_dyn_diagnose; deviation by whirl_deviation from the
 * unperturbed start shape or the reference_mode shape). Fixed steps are taken one at a time: the
 * stop condition and the stop request are checked after every step. */

typedef struct whirl_scene_work whirl_scene_work; /* chain, model, dynamics, integrator, state */

/* What a run reports, through callbacks (any may be NULL; ctx is passed to each). A non-zero
 * return stops the run with that status. */
typedef struct whirl_scene_output {
    /* a row: value[WHIRL_NCOLUMNS] indexed by whirl_column (those not wanted are 0) */
    int (*row)(void *ctx, const double *value);
    /* a trace frame at t: the pivot (3) and the masses x (3 per mass, n) in the inertial frame,
       every [output] trace_every */
    int (*frame)(void *ctx, double t, const double *pivot, const double *x, size_t n);
    int (*progress)(void *ctx, double t); /* after every step (fixed) or output time */
    void *ctx;
} whirl_scene_output;

typedef struct whirl_scene_result {
    double t;                     /* time reached [T] */
    unsigned long rows, frames;   /* rows and frames reported */
    int stopped;                  /* 1 if [run] stop_deviation ended the run */
    double deviation;             /* the deviation that stopped it */
    whirl_integrator_stats stats; /* of the run's integrator */
} whirl_scene_result;

/* Builds the chain, the model, the dynamics, the integrator and the start state of scene (which
 * must outlive the result). NULL on failure, with the message "FILE:LINE: [section] key:
 * problem" naming the key to blame (no steady shape of the mode, unknown method, a step the
 * method cannot take, ...).
 * @param scene the parsed scene (not owned: must outlive the workspace)
 * @return the workspace, to free with whirl_scene_work_free; NULL with a message on failure
 */
WHIRL_API whirl_scene_work *whirl_scene_work_alloc(const whirl_scene *scene);
/* Frees the workspace. NULL is a no-op.
 * @param w the workspace, or NULL
 */
WHIRL_API void whirl_scene_work_free(whirl_scene_work *w);

/* The run's dynamics and its current state (whirl_dyn_size values).
 * @param w the workspace
 * @return the dynamics, owned by the workspace
 */
WHIRL_API const whirl_dyn *whirl_scene_work_dyn(const whirl_scene_work *w);
/* The run's current state: whirl_dyn_size values.
 * @param w the workspace
 * @return the state, owned by the workspace and valid until its next use
 */
WHIRL_API const double *whirl_scene_work_state(const whirl_scene_work *w);

/* Runs from t = 0 to t_end (once per workspace), reporting through out. GSL_SUCCESS (also when
 * stop_deviation ended the run: res->stopped), WHIRL_EINTERRUPTED after a stop request, the
 * status of a callback that stopped it, or the integration's failure ("the run failed after t =
 * ..."); res describes how far it got in every case (the rows reported so far are valid).
 * @param w the workspace, not run yet
 * @param out the callbacks (each may be NULL)
 * @param res out: how far the run got
 * @return GSL_SUCCESS, GSL_EINVAL if w, out or res is NULL, WHIRL_EINTERRUPTED, a callback's
 *     status, or the integration's failure; with a message
 */
WHIRL_API int whirl_scene_work_run(whirl_scene_work *w, const whirl_scene_output *out,
                         whirl_scene_result *res);

/* The fastest decay rate the dissipation adds to the motion [1/T]: the internal damping's,
 * about 16 D / min_i(m_i l_i^2) (16 D N^3 / (M L^2) for N equal links), plus the air drag's, at
 * most max_i l_i (c + 2 c2 v) / m_i (c L / M for a uniform chain, whatever N) with v the speed
 * of the steady rotation's fastest point, |omega| (L + drive_radius); 0 without either.
 * @param scene the parsed scene
 * @return the rate [1/T, or 1/s with SI units]; 0 without damping and drag
 */
WHIRL_API double whirl_scene_damping_rate(const whirl_scene *scene);
/* 1 if the damping or the drag makes the scene's fixed step unstable for the explicit and
 * fixed-point methods (dt x whirl_scene_damping_rate > 2, tol = 0, a method other than
 * gsl-msbdf): a run that fails or blows up then needs a smaller dt or method = gsl-msbdf with
 * tol (its failure message says so, naming the internal damping, the air drag or both). The
 * rate in *rate (may be NULL).
 * @param scene the parsed scene
 * @param rate out: whirl_scene_damping_rate(scene), or NULL
 * @return 1 if the fixed step is past the dissipation's limit, else 0
 */
WHIRL_API int whirl_scene_stiff(const whirl_scene *scene, double *rate);

/* CSV: the header (comment lines, the last the units line of whirl_write_units_line, then the
 * column names), one row (the scene's columns of
 * value[WHIRL_NCOLUMNS]), one trace frame ("# t = T", then "x y z t" of the pivot and of every
 * mass; blocks after the first (index > 0) begin with two empty lines). GSL_EFAILED if fp has
 * an error.
 * @param fp the stream
 * @param scene the parsed scene: its options and columns
 * @return GSL_SUCCESS, or GSL_EFAILED with a message if fp has an error
 */
WHIRL_API int whirl_scene_write_header(FILE *fp, const whirl_scene *scene);
/* One CSV row of the scene's columns (see above).
 * @param fp the stream
 * @param scene the parsed scene: its columns
 * @param value the values indexed by whirl_column, WHIRL_NCOLUMNS
 * @return GSL_SUCCESS, or GSL_EFAILED with a message if fp has an error
 */
WHIRL_API int whirl_scene_write_row(FILE *fp, const whirl_scene *scene, const double *value);
/* One trace frame (see above).
 * @param fp the stream
 * @param index the frame's index, 0 for the first
 * @param t the time [T, or s with SI units]
 * @param pivot the pivot's position (3), inertial frame
 * @param x the masses' positions, 3 n, inertial frame
 * @param n the masses
 * @return GSL_SUCCESS, or GSL_EFAILED with a message if fp has an error
 */
WHIRL_API int whirl_scene_write_frame(FILE *fp, unsigned long index, double t, const double *pivot,
                            const double *x, size_t n);

/* The whole run: whirl_scene_work_alloc, the header and every row to csv, the frames to trace
 * (NULL: none), whirl_scene_work_free. Returns as whirl_scene_work_run (or the allocation's
 * failure).
 * @param scene the parsed scene
 * @param csv the stream of the rows
 * @param trace the stream of the frames, or NULL: none
 * @param res out: how far the run got
 * @return as whirl_scene_work_run (GSL_EINVAL also if scene, csv or res is NULL), or the
 *     allocation's failure
 */
WHIRL_API int whirl_scene_run(const whirl_scene *scene, FILE *csv, FILE *trace, whirl_scene_result *res);

/* ---- the pivot's path, [run] pivot (src/studies/scene_pivot.c) ----
 * [run] pivot = PATH moves the pivot along PATH (whirl/periodic.h: whirl_pivot_parse's grammar,
 * the text of whirl periodic --pivot) at the rate [run] omega, in the inertial frame; lengths in
 * the scene's units: L, or with [units] system = SI in m (a suffix cm or mm allowed). It needs
 * [run] omega > 0, frame = inertial and no drive_radius (circle:R is the drive of radius R, bit
 * for bit). The start moves with the pivot: at t = 0 the pivot is at p(0) with the velocity
 * p'(0), and every start is placed there as it is at (drive_radius, 0, 0) without a path; the
 * trace's pivot is p(t).
 *
 * The design keeps 2.3.0's ABI. whirl_scene is allocated by its caller, and its line[] has one
 * entry for each key of whirl_scene_key: a new key there, or a new field, would change its size
 * and break every program built against 2.3.0's header. So the key has no field and no
 * whirl_scene_key: whirl_scene, WHIRL_SCENE_NKEYS and every function above are as in 2.3.0, and
 * whirl_scene_parse, which has nowhere to keep the path, refuses a scene that gives the key
 * ("FILE:LINE: [run] pivot: ...", a one-line error as for any key it cannot take), so that no
 * program runs such a scene without its pivot unawares. The path is read into a
 * whirl_scene_pivot beside the scene by whirl_scene_parse_with_pivot (or from a text in the
 * scene's units by whirl_scene_pivot_from_text: whirl simulate --pivot), and the run takes it
 * by the _with_pivot variants below; each of them with pivot NULL (or pivot->given 0) is the
 * function of the same name without it. whirl_scene_pivot is allocated by its caller too, and
 * stays as it is: a later key gets a struct of its own. */
typedef struct whirl_scene_pivot {
    int given;             /* 1: the pivot follows path; 0: [run] pivot not given (the pivot
                              moves as drive_radius says, path unused) */
    int line;              /* where it came from, as whirl_scene.line: its line (> 0), -1 an
                              override, 0 not from the scene (whirl_scene_pivot_from_text) */
    whirl_pivot_path path; /* at the rate [run] omega; lengths [L, or m with SI units] */
} whirl_scene_pivot;

/* whirl_scene_parse, also reading [run] pivot into *pivot (zeroed when absent, and on failure).
 * @param path the scene file's name
 * @param overrides the overrides "section.key=value" (run.pivot among them), n_overrides,
 *     applied in order; NULL if none
 * @param n_overrides the overrides, >= 0
 * @param scene out: the scene, to free with whirl_scene_free (also after a failure)
 * @param pivot out: the pivot's path, or NULL: whirl_scene_parse (the key refused)
 * @return as whirl_scene_parse
 */
WHIRL_API int whirl_scene_parse_with_pivot(const char *path, const char *const *overrides,
                                           size_t n_overrides, whirl_scene *scene,
                                           whirl_scene_pivot *pivot);
/* whirl_scene_parse_stream, also reading [run] pivot into *pivot (as above).
 * @param fp the open stream of the scene file, read and not closed
 * @param path the file's name, in the messages and scene->path
 * @param overrides the overrides "section.key=value", n_overrides, applied in order; NULL if none
 * @param n_overrides the overrides, >= 0
 * @param scene out: the scene, to free with whirl_scene_free (also after a failure)
 * @param pivot out: the pivot's path, or NULL: whirl_scene_parse_stream (the key refused)
 * @return as whirl_scene_parse
 */
WHIRL_API int whirl_scene_parse_stream_with_pivot(FILE *fp, const char *path,
                                                  const char *const *overrides,
                                                  size_t n_overrides, whirl_scene *scene,
                                                  whirl_scene_pivot *pivot);

/* *pivot <- the path text (the grammar of [run] pivot) for the parsed scene: at its [run]
 * omega, in its units, checked as the key is (omega > 0, frame = inertial, no drive_radius,
 * no y term in 2D); given 1, line 0. GSL_EINVAL with a one-line message without a location
 * (the caller names where the text came from), *pivot unchanged.
 * @param scene the parsed scene
 * @param text the path, e.g. "ellipse:1cm,0.6cm" (SI) or "vertical:0.05"
 * @param pivot out: the pivot's path (unchanged on failure)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_scene_pivot_from_text(const whirl_scene *scene, const char *text,
                                          whirl_scene_pivot *pivot);

/* whirl_scene_work_alloc with the pivot on pivot's path (copied; NULL or given 0: the scene's
 * drive). NULL with a message on failure, as whirl_scene_work_alloc.
 * @param scene the parsed scene (not owned: must outlive the workspace)
 * @param pivot the pivot's path (copied), or NULL
 * @return the workspace, to free with whirl_scene_work_free; NULL with a message on failure
 */
WHIRL_API whirl_scene_work *whirl_scene_work_alloc_with_pivot(const whirl_scene *scene,
                                                              const whirl_scene_pivot *pivot);

/* whirl_scene_write_header with the line "# pivot = fourier:TERMS" (the path's Fourier terms in
 * the grammar of [run] pivot, numbers in the shortest form that reads back exactly) after the
 * start's, when pivot is given.
 * @param fp the stream
 * @param scene the parsed scene
 * @param pivot the pivot's path, or NULL
 * @return GSL_SUCCESS, or GSL_EFAILED with a message if fp has an error
 */
WHIRL_API int whirl_scene_write_header_with_pivot(FILE *fp, const whirl_scene *scene,
                                                  const whirl_scene_pivot *pivot);

/* whirl_scene_run with the pivot on pivot's path (NULL or given 0: whirl_scene_run).
 * @param scene the parsed scene
 * @param pivot the pivot's path, or NULL
 * @param csv the stream of the rows
 * @param trace the stream of the frames, or NULL: none
 * @param res out: how far the run got
 * @return as whirl_scene_run
 */
WHIRL_API int whirl_scene_run_with_pivot(const whirl_scene *scene, const whirl_scene_pivot *pivot,
                                         FILE *csv, FILE *trace, whirl_scene_result *res);

#ifdef __cplusplus
}
#endif

#endif
