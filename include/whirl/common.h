/* whirl: shared conventions of the library.
 *
 * Units: dimensionless unless a function says otherwise: chain length L = 1, total chain mass
 * M = 1, gravity g = 1; rates in sqrt(g/L), time in sqrt(L/g), forces and tensions in M g.
 * Axes: z points up, gravity is -g z, the pivot is the origin, the rotation axis is z.
 * Mode k = node count k = the pivot plus k-1 crossings of the axis below it.
 *
 * Status: every function that can fail returns an int status with GSL's codes (GSL_SUCCESS = 0,
 * GSL_EINVAL for bad arguments, GSL_EDOM for a mode that does not exist at a rate, GSL_ENOMEM,
 * GSL_EMAXITER, GSL_ERANGE for a non-finite result, GSL_EFAILED otherwise) and, when it is not
 * GSL_SUCCESS, leaves a one-line message that whirl_last_error() returns. The library never
 * prints and never aborts on numerical trouble. It does not touch GSL's error handler: callers
 * that do not want GSL to abort call gsl_set_error_handler_off() once (the whirl program does). */
#ifndef WHIRL_COMMON_H
#define WHIRL_COMMON_H

#include <gsl/gsl_errno.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* WHIRL_API marks the library's public functions. The shared library is compiled with
 * -fvisibility=hidden and exports these alone, so every symbol it exports starts with whirl_. */
#if defined(__GNUC__)
#define WHIRL_API __attribute__((visibility("default")))
#else
#define WHIRL_API
#endif

/* The highest mode of the models seeded by the continuous chain's shape of a mode: the driven
 * chain, the fit and the continuum's stability. The steady shapes, branches and critical rates
 * take more: every mode 1..N of an N-link chain at any N, and the continuum's modes up to
 * WHIRL_CONTINUUM_MODE_MAX (whirl/steady.h). */
#define WHIRL_MODE_MAX 64

/* The heaviest tip mass, in chain masses, of every model: beyond it the chain's weight (1) is
 * below the round-off of the tip's in the tension (sigma + m), and results would depend on the
 * rounding rather than the chain. */
#define WHIRL_TIP_MASS_MAX 1e12

/* The highest rotation rate any model accepts: forces ~ omega^2 (up to 1e200) times masses and
 * units stay finite. (The continuous chain has a lower limit, WHIRL_CONTINUUM_OMEGA_MAX.) */
#define WHIRL_OMEGA_MAX 1e100

/* The message of the last failure in the calling thread ("" if none), its numbers
 * dimensionless.
 * @return the message (the thread's own storage, rewritten by its next failure)
 */
WHIRL_API const char *whirl_last_error(void);
/* The status of that failure (GSL_SUCCESS if none): a function that returns NULL instead of a
 * status (an _alloc) leaves it here.
 * @return the status of the calling thread's last failure, GSL_SUCCESS if none
 */
WHIRL_API int whirl_last_status(void);
/* The message of the last failure with its physical quantities (rates, lengths, masses, times,
 * forces, drags, damping) in units, into buf (size bytes); returns buf. physical 0:
 * dimensionless, as whirl_last_error() but with a number of 16 or 17 digits written in the
 * fewest that read back to it (whirl_format_double). physical 1: SI for a chain of the length
 * [m], mass [kg] and gravity [m/s^2] given, each quantity followed by its unit (rad/s, or Hz if
 * rate_hz; m, kg, s, N; kg/(m s) a linear drag per length, kg/m^2 a quadratic one, kg m^2/s an
 * internal damping), with the significant digits the message gave it but at least 6 and at most
 * 15.
 * @param buf out: the message, NUL-terminated, cut at size - 1 bytes
 * @param size the bytes of buf (0: buf is left untouched)
 * @param physical 0: dimensionless numbers, 1: SI units
 * @param length the chain's length [m], > 0 (used when physical is 1)
 * @param mass the chain's mass [kg], > 0 (used when physical is 1)
 * @param gravity the gravity [m/s^2], > 0 (used when physical is 1)
 * @param rate_hz non-zero: rates in Hz, else in rad/s
 * @return buf
 */
WHIRL_API char *whirl_last_error_in_units(char *buf, size_t size, int physical, double length,
                                          double mass, double gravity, int rate_hz);

/* ---- a failure carried between threads ----
 * The last failure is per thread: work on OpenMP or other threads keeps its failure (status and
 * message, its quantities typed) in a record that the caller's thread restores after the join:
 *   whirl_error_record err[N];      (or one shared record: the first failure wins)
 *   #pragma omp parallel for
 *   for (i...) { err[i].status = GSL_SUCCESS; whirl_error_keep(&err[i], work(i)); }
 *   status = whirl_error_restore_first(err, N);   now whirl_last_error() is that failure's */
#define WHIRL_ERROR_MAX 1024
typedef struct whirl_error_record {
    int status; /* GSL_SUCCESS: no failure */
    char text[WHIRL_ERROR_MAX]; /* the message (read it by whirl_error_restore) */
} whirl_error_record;

/* Copies this thread's last failure into r.
 * @param r out: the record, its status and message those of the thread's last failure
 */
WHIRL_API void whirl_error_save(whirl_error_record *r);
/* Makes r this thread's last failure; returns its status.
 * @param r the record to restore, a failure or GSL_SUCCESS
 * @return r->status
 */
WHIRL_API int whirl_error_restore(const whirl_error_record *r);
/* Restores the first record of r[0..n) that holds a failure and returns its status, or returns
 * GSL_SUCCESS if none does (one record per block of work: the caller reports the failure of the
 * earliest block, whatever the order the threads ended in).
 * @param r the records, n
 * @param n the records' count (0: none)
 * @return the status of the first record that holds a failure, GSL_SUCCESS if none does
 */
WHIRL_API int whirl_error_restore_first(const whirl_error_record *r, size_t n);
/* Keeps this thread's last failure in *slot if status is a failure and slot holds none yet
 * (thread-safe: for workers sharing one slot, the first to fail wins); returns status.
 * @param slot the record that keeps the first failure, its status GSL_SUCCESS until one is kept
 * @param status the status of the work just done
 * @return status, unchanged
 */
WHIRL_API int whirl_error_keep(whirl_error_record *slot, int status);

/* ---- stopping long work ----
 * One stop request per process, because the signals that raise it (SIGINT, SIGTERM, SIGQUIT,
 * SIGHUP, SIGPIPE, SIGXFSZ) are process-wide. Every long loop of the library (integrations, sweeps, maps, fits, root scans)
 * polls it at least every ~0.1 s of work, inside steps, and then returns WHIRL_EINTERRUPTED with
 * a message saying how far it got; what it computed until then stays valid. The request stays
 * set until whirl_stop_clear(). C and Python callers can raise it themselves (a GUI button, a
 * time limit) or let whirl_stop_catch_signals() raise it on Ctrl-C. */
#define WHIRL_EINTERRUPTED 1000 /* status of work stopped by a stop request */

/* Requests a stop. Async-signal-safe: may be called from a signal handler or another thread. */
WHIRL_API void whirl_stop_request(void);
/* Non-zero once a stop was requested and not cleared.
 * @return non-zero if a stop was requested and not cleared, else 0
 */
WHIRL_API int whirl_stop_requested(void);
/* The number of the signal that raised the request (SIGINT, ...), 0 when none did (no request,
 * or whirl_stop_request()).
 * @return the signal's number, or 0
 */
WHIRL_API int whirl_stop_signal(void);
/* Clears the request, so that new work runs to its end. */
WHIRL_API void whirl_stop_clear(void);
/* Installs handlers that raise the request on SIGINT, SIGTERM and SIGQUIT, and on SIGHUP,
 * SIGPIPE and SIGXFSZ unless they are ignored (nohup; Python ignores the last two), keeping the
 * previous handlers for whirl_stop_restore_signals(). A caught SIGPIPE or SIGXFSZ makes the
 * write that raised it fail (EPIPE, EFBIG) instead of killing the process. Returns GSL_SUCCESS
 * or GSL_EFAILED.
 * @return GSL_SUCCESS, or GSL_EFAILED if a handler could not be installed (those installed are
 *     restored)
 */
WHIRL_API int whirl_stop_catch_signals(void);
/* Restores the handlers that whirl_stop_catch_signals() replaced (no-op if it did not run). */
WHIRL_API void whirl_stop_restore_signals(void);

/* ---- threads ----
 * The library's parallel loops (steady branches over many rates, stability maps, the right-hand
 * side of a long chain with whirl_dyn_set_threads) run on OpenMP threads: at most
 * whirl_max_threads() of them. GNU libgomp's threads do not survive fork(): a parallel region in
 * a child forked after its parent ran one would wait forever for them. So in a child of fork()
 * (multiprocessing's default on Linux) every loop of the library runs on one thread, and
 * whirl_set_max_threads refuses more there. The setting is process-wide, like the stop
 * request, and thread-safe. */
#define WHIRL_THREADS_MAX 4096 /* a bound on the setting, far above any machine's cores */

/* Caps the threads of every parallel loop of the library at threads (0: OpenMP's own count,
 * OMP_NUM_THREADS or the cores; the default). GSL_EINVAL outside 0..WHIRL_THREADS_MAX, or
 * other than 1 in a child of fork(). Results do not depend on it.
 * @param threads the cap, 0..WHIRL_THREADS_MAX (0: OpenMP's own count)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message for a cap out of range, or other than 1 in a
 *     child of fork()
 */
WHIRL_API int whirl_set_max_threads(int threads);
/* The threads a parallel loop of the library takes now (1 in a child of fork()).
 * @return the threads a parallel loop takes now, >= 1
 */
WHIRL_API int whirl_max_threads(void);
/* 1 in a child of fork() (the process runs the library on one thread), else 0.
 * @return 1 in a child of fork(), else 0
 */
WHIRL_API int whirl_forked_child(void);

/* ---- numbers as text ----
 * whirl_format_double writes x in the shortest of %.15g, %.16g, %.17g that strtod reads back
 * to the same double (17 digits always do), so 4.39 prints as 4.39 and not 4.3900000000000006,
 * and nothing is lost. Non-finite values print as "nan", "inf", "-inf". buf holds at least
 * WHIRL_FORMAT_MAX chars; returns buf. Thread-safe. */
#define WHIRL_FORMAT_MAX 32
/* Writes x as text in the fewest digits that read back to it (see above).
 * @param buf out: the text, at least WHIRL_FORMAT_MAX chars
 * @param x the number, any double
 * @return buf
 */
WHIRL_API char *whirl_format_double(char *buf, double x);

/* ---- quantities with units ----
 * The physical kinds a number given as text may carry a unit suffix for, and the SI unit it is
 * converted to: rate rad/s (suffixes rad/s, Hz = 2 pi rad/s, rpm = 2 pi/60 rad/s), length m
 * (m, cm, mm), mass kg (kg, g), time s (s, ms). */
typedef enum {
    WHIRL_QUANTITY_NUMBER, /* a pure number: no suffix */
    WHIRL_QUANTITY_RATE,
    WHIRL_QUANTITY_LENGTH,
    WHIRL_QUANTITY_MASS,
    WHIRL_QUANTITY_TIME
} whirl_quantity;

/* Standard gravity [m/s^2] (CGPM 1901): g when SI units are chosen and no gravity is given. */
#define WHIRL_STANDARD_GRAVITY 9.80665

/* Reads text, all of it: a finite double, optionally followed (spaces allowed: "4Hz", "4 Hz") by
 * one of the kind's suffixes, in any case ("4HZ"), which multiplies it by the suffix's factor. Returns 0 and sets *value (and
 * *suffixed to whether a suffix was given, if suffixed is not NULL), or -1 for anything else:
 * no number, trailing text that is not a suffix of the kind, overflow, inf, nan.
 * @param text the text, NUL-terminated (NULL: -1)
 * @param kind the kind of quantity, which sets the suffixes accepted
 * @param value out: the number in the kind's SI unit (untouched on -1)
 * @param suffixed out, or NULL: 1 if a suffix was given, else 0
 * @return 0, or -1 if the text is not a finite number with an optional suffix of the kind
 */
WHIRL_API int whirl_parse_quantity(const char *text, whirl_quantity kind, double *value,
                                   int *suffixed);
/* The suffixes of the kind, as words for a message: "rad/s, Hz or rpm" ("" for a number).
 * @param kind the kind of quantity
 * @return the suffixes as static text ("" for WHIRL_QUANTITY_NUMBER)
 */
WHIRL_API const char *whirl_quantity_suffixes(whirl_quantity kind);

/* Writes the line that states the units of a file, the same in every file whirl writes:
 *   # units: length=m mass=kg time=s rate=rad/s force=N L=0.6 M=0.05 g=9.80665
 * when physical (SI; L, M, g the chain's length, mass and gravity), else
 *   # units: dimensionless (length L, mass M, time sqrt(L/g), rate sqrt(g/L), force M g)
 * @param fp the stream to write to
 * @param physical non-zero: SI units, with length, mass and gravity; 0: dimensionless
 * @param length the chain's length L [m] (written when physical)
 * @param mass the chain's mass M [kg] (written when physical)
 * @param gravity the gravity g [m/s^2] (written when physical)
 */
WHIRL_API void whirl_write_units_line(FILE *fp, int physical, double length, double mass,
                                      double gravity);

#ifdef __cplusplus
}
#endif

#endif
