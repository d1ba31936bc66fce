/* whirl: time-domain dynamics of the N-link chain (point masses on massless rigid links), 2D
 * (the x-z plane) and 3D, in the inertial frame or in the frame co-rotating at omega about z.
 *
 * Two formulations of the same equations of motion:
 *  - WHIRL_FORMULATION_CARTESIAN (default): mass positions and velocities (or link vectors) with
 *    the link tensions as Lagrange multipliers, a symmetric tridiagonal solve per evaluation:
 *    O(N), no coordinate singularity (a chain hanging straight down works);
 *  - WHIRL_FORMULATION_SEED: the seed document's angles theta_i (from the downward vertical) and
 *    phi_i (azimuth from x) with its dense mass matrix: O(N^3), singular where sin(theta_i) = 0 in
 *    3D; the reference for small N.
 * The state vector y is the formulation's own; convert with whirl_dyn_set_state and
 * whirl_dyn_get_state. It is always y = (q, qdot), two halves of equal length with dq/dt = qdot
 * (Cartesian: the link vectors d_i = x_i - x_{i-1} and their rates in the model's frame, 3 per
 * link in 3D, (x, z) in 2D; seed: (theta, phi, theta', phi') in 3D, (theta, theta') in 2D). */
#ifndef WHIRL_DYNAMICS_H
#define WHIRL_DYNAMICS_H

#include <stddef.h>

#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/integrator.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { WHIRL_FRAME_INERTIAL = 0, WHIRL_FRAME_ROTATING = 1 } whirl_frame;
typedef enum { WHIRL_FORMULATION_CARTESIAN = 0, WHIRL_FORMULATION_SEED = 1 } whirl_formulation;

/* A quantity ramped in time by a C1 smooth step: from before t_start, to after t_end and
 * from + (to - from) s(u) between, u = (t - t_start) / (t_end - t_start), s(u) = u^2 (3 - 2 u)
 * (continuous with its first derivative; the second jumps at t_start and t_end). A ramp with
 * all four fields 0 is inactive (the default); an active one needs t_end > t_start, all finite. */
typedef struct whirl_ramp {
    double from;    /* value up to t_start */
    double to;      /* value from t_end on */
    double t_start; /* start of the ramp [T] */
    double t_end;   /* end of the ramp [T], > t_start */
} whirl_ramp;

/* The model: parameters only, never changed by the library. */
typedef struct whirl_model {
    const whirl_chain *chain;  /* the chain (not owned: must outlive the workspace) */
    int dim;                   /* 2 (planar, x-z) or 3 */
    whirl_frame frame;         /* frame of the state; WHIRL_FRAME_ROTATING needs dim = 3 */
    double omega;              /* rate of the co-rotating frame and of the pivot drive [1/T] */
    double drive_radius;       /* eps >= 0: the pivot moves on the horizontal circle
                                  (eps cos wt, eps sin wt, 0) of the inertial frame (2D: along x,
                                  eps cos wt); fixed at (eps, 0, 0) in the co-rotating frame */
    double air_drag;           /* c >= 0: linear drag -c l_i v_i on mass i, v_i its inertial
                                  velocity (c per unit length of a uniform chain) */
    double air_drag_quadratic; /* c2 >= 0: quadratic drag -c2 l_i |v_i| v_i */
    double internal_damping;   /* D >= 0: each joint resists the relative motion of the two
                                  links it joins, measured in the frame co-rotating at omega, the
                                  top joint's upper body being the drive shaft: Rayleigh function
                                  R = D/2 sum_i |w_i - w_{i-1}|^2, w_i = du_i/dt - omega z x u_i,
                                  u_i = unit vector of link i, w_0 = 0. Zero for the rigid
                                  rotation at omega. */
    /* the seed's forcing and damping on the angle theta_d (2D only): generalized force
       f_d = sigma_d - lambda_d thetadot_d; arrays of chain->n or NULL for none (seed eq. 25-26) */
    const double *seed_sigma;
    const double *seed_lambda;
    /* A drive that depends on time (default: both inactive, the constant drive above). When
       active, a ramp replaces the constant: eps(t) for drive_radius (from, to >= 0), omega(t)
       for omega (the drive's rate and, WHIRL_FRAME_ROTATING, the frame's: its angle, the
       drive's phase, is phi(t) = int_0^t omega, and the Euler force -omega' z x x acts). */
    whirl_ramp drive_radius_ramp;
    whirl_ramp omega_ramp;
} whirl_model;

/* The fastest decay rate the dissipation adds to the motion [1/T]: the internal damping's,
 * about 16 D / min_i(m_i l_i^2) (16 D N^3 / (M L^2) for N equal links), plus the air drag's, at
 * most max_i l_i (c + 2 c2 v) / m_i (c L / M for a uniform chain, whatever N) with v the speed
 * of the steady rotation's fastest point, |omega| (L + drive_radius); 0 without either (the
 * reasons and measurements: src/dynamics/stiff.c). A fixed step h of the explicit methods and of
 * the Gauss methods' fixed-point stage iteration is unstable past h x rate = 2 or so (rk4:
 * 2.785, the Gauss fixed point: 3.46).
 * @param m the model (its ramps are not read)
 * @return the rate [1/T]; 0 without damping and drag, or for NULL, a model without a chain or a
 *     chain without links
 */
WHIRL_API double whirl_model_stiff_rate(const whirl_model *m);
/* What makes the model stiff, as the subject and verb of a sentence ("the internal damping
 * makes", "the air drag makes", "the internal damping and the air drag make"): each source
 * named that gives a tenth of whirl_model_stiff_rate or more.
 * @param m the model
 * @return a static string (never NULL)
 */
WHIRL_API const char *whirl_model_stiff_cause(const whirl_model *m);

typedef struct whirl_dyn whirl_dyn; /* workspace: all scratch memory of one right-hand side */

/* Allocates the workspace of model in formulation f (copies the model struct, not the chain).
 * NULL on invalid parameters (whirl_last_error names the first) or no memory.
 * @param model the model (copied; its chain is not, and must outlive the workspace)
 * @param f the formulation: WHIRL_FORMULATION_CARTESIAN (the default) or the seed's
 * @return the workspace, to free with whirl_dyn_free; NULL with a message on invalid parameters or
 *     no memory
 */
WHIRL_API whirl_dyn *whirl_dyn_alloc(const whirl_model *model, whirl_formulation f);
/* Frees the workspace. NULL is a no-op.
 * @param d the dynamics, or NULL
 */
WHIRL_API void whirl_dyn_free(whirl_dyn *d);

/* The model of d (its copy).
 * @param d the dynamics
 * @return the model, owned by d
 */
WHIRL_API const whirl_model *whirl_dyn_model(const whirl_dyn *d);

/* The drive at time t: radius eps(t) [L], rate omega(t) [1/T] and phase phi(t) [rad] (the
 * pivot's angle about z in the inertial frame and the co-rotating frame's angle, int_0^t omega;
 * omega t for a constant drive). Any output may be NULL.
 * @param d the dynamics
 * @param t the time [T]
 * @param radius out, or NULL: eps(t) [L]
 * @param omega out, or NULL: omega(t) [1/T]
 * @param phase out, or NULL: phi(t) [rad]
 */
WHIRL_API void whirl_dyn_drive_at(const whirl_dyn *d, double t, double *radius, double *omega,
                        double *phase);

/* Replaces the model's drive_radius_ramp and omega_ramp (NULL: keep that one) of d at time t,
 * e.g. to change the rate in the middle of a run; allocates nothing. The phase phi stays
 * continuous at t (from t on it is phi(t) plus the integral of the new omega(t) from t). The
 * state vector keeps its meaning (in the co-rotating frame: rates relative to the frame); for
 * the motion to stay smooth the new ramps should start from the drive's values at t. GSL_EINVAL
 * on an invalid ramp or t (d is then unchanged).
 * @param d the dynamics
 * @param t the time of the change [T]
 * @param radius the new drive_radius_ramp, or NULL to keep it
 * @param omega the new omega_ramp, or NULL to keep it
 * @return GSL_SUCCESS, or GSL_EINVAL with a message (d unchanged)
 */
WHIRL_API int whirl_dyn_set_ramps(whirl_dyn *d, double t, const whirl_ramp *radius,
                        const whirl_ramp *omega);
/* The formulation of d.
 * @param d the dynamics
 * @return the formulation
 */
WHIRL_API whirl_formulation whirl_dyn_formulation(const whirl_dyn *d);

/* A pivot moved along any path: p(t), p'(t), p''(t) in the inertial frame (3 components each;
 * in 2D the y components are ignored). */
typedef void (*whirl_pivot_fn)(double t, double p[3], double pv[3], double pa[3], void *params);

/* Replaces the pivot's motion of d by pivot(t, ..., params) (NULL restores the model's drive).
 * The model must be in the inertial frame with drive_radius 0 and no ramp (the circle drive is
 * then one such path, whirl/periodic.h): GSL_EINVAL otherwise, d unchanged. The model's omega
 * keeps its other roles (the phase of whirl_dyn_state_from_shape, the reference frame of the
 * internal damping, whirl_default_step's period). params is not owned.
 * @param d the dynamics
 * @param pivot the pivot's path, or NULL to restore the model's drive
 * @param params passed to pivot (not owned)
 * @return GSL_SUCCESS, or GSL_EINVAL with a message (d unchanged)
 */
WHIRL_API int whirl_dyn_set_pivot(whirl_dyn *d, whirl_pivot_fn pivot, void *params);

/* Length of the state vector y.
 * @param d the dynamics
 * @return the length of the state vector y
 */
WHIRL_API size_t whirl_dyn_size(const whirl_dyn *d);

/* One chain on several cores: the Cartesian formulation's per-link passes of every right-hand
 * side (the coefficients and the accelerations, see src/dyn_cartesian.c) run on up to threads
 * OpenMP threads when N >= WHIRL_DYN_THREADS_MIN_LINKS; the two recursions between them stay
 * serial. Every value is computed as with one thread: results are bitwise the same. Default 1
 * (opt-in: each right-hand side then forks and joins twice, which pays only on idle cores; see
 * the README's measurements). GSL_EINVAL outside 1..WHIRL_DYN_THREADS_MAX. Calls from inside an
 * OpenMP parallel region run on one thread (nested parallelism is off); the count is capped by
 * whirl_set_max_threads, and is 1 in a child of fork() (see whirl_max_threads). */
#define WHIRL_DYN_THREADS_MIN_LINKS 4096
#define WHIRL_DYN_THREADS_MAX 256
/* Sets the threads of d's right-hand side (see above).
 * @param d the dynamics
 * @param threads the threads, 1..WHIRL_DYN_THREADS_MAX
 * @return GSL_SUCCESS, or GSL_EINVAL with a message
 */
WHIRL_API int whirl_dyn_set_threads(whirl_dyn *d, int threads);

/* dy/dt at (t, y), with GSL's signature (params = the whirl_dyn *): usable as a gsl_odeiv2_system.
 * Returns GSL_SUCCESS, or GSL_EBADFUNC if the result is not finite (or, in the seed formulation,
 * at its 3D singularity), with a message. Allocates nothing.
 * @param t the time [T]
 * @param y the state, whirl_dyn_size(d)
 * @param dydt out: dy/dt, whirl_dyn_size(d)
 * @param dyn the dynamics (a whirl_dyn *)
 * @return GSL_SUCCESS, or GSL_EBADFUNC with a message
 */
WHIRL_API int whirl_dyn_rhs(double t, const double y[], double dydt[], void *dyn);

/* State y from the positions x[3i..3i+2] and velocities v[3i..3i+2] of masses i = 1..N (x[0..2]
 * is mass 1) given in the model's frame at time t (in 2D the y components must be 0). The
 * positions must satisfy the link constraints to 1e-9 relative and the velocities be consistent
 * with them; y is then projected exactly onto the constraints. GSL_EINVAL otherwise, and for the
 * seed formulation at its 3D singularity.
 * @param d the dynamics
 * @param t the time [T]
 * @param x the masses' positions in the model's frame, 3 per mass (mass 1 first)
 * @param v their velocities, 3 per mass
 * @param y out: the state, whirl_dyn_size(d)
 * @return GSL_SUCCESS, or GSL_EINVAL on positions or velocities that break the constraints
 */
WHIRL_API int whirl_dyn_set_state(whirl_dyn *d, double t, const double *x, const double *v,
                                  double *y);

/* Positions and velocities of the masses (3 per mass, as above) at time t in the given frame.
 * @param d the dynamics
 * @param t the time [T]
 * @param y the state, whirl_dyn_size(d)
 * @param frame the frame of x and v (WHIRL_FRAME_INERTIAL or WHIRL_FRAME_ROTATING)
 * @param x out: the masses' positions, 3 per mass
 * @param v out: their velocities, 3 per mass
 * @return GSL_SUCCESS, or a status with a message
 */
WHIRL_API int whirl_dyn_get_state(const whirl_dyn *d, double t, const double *y, whirl_frame frame,
                                  double *x, double *v);

/* Projects y onto the constraint manifold (|x_i - x_{i-1}| = l_i and its time derivative);
 * a no-op for the seed formulation, whose coordinates satisfy the constraints by construction.
 * @param d the dynamics
 * @param t the time [T] (the constraints do not depend on it)
 * @param y the state, whirl_dyn_size(d), projected in place
 * @return GSL_SUCCESS, or GSL_ERANGE with a message if the state is not finite
 */
WHIRL_API int whirl_dyn_project(whirl_dyn *d, double t, double *y);

/* Tensions of the links (array of chain->n, [M g] in the dimensionless units) at (t, y).
 * @param d the dynamics
 * @param t the time [T]
 * @param y the state, whirl_dyn_size(d)
 * @param tension out: the link tensions [M g], chain->n
 * @return GSL_SUCCESS, or a status with a message (GSL_EBADFUNC if they are not finite)
 */
WHIRL_API int whirl_dyn_tensions(whirl_dyn *d, double t, const double *y, double *tension);

typedef struct whirl_dyn_diagnostics {
    double energy;     /* kinetic + potential energy in the inertial frame */
    double lz;         /* angular momentum about z, inertial frame */
    double jacobi;     /* energy - omega lz: conserved in the co-rotating frame without forces */
    double constraint; /* max over links of | |x_i - x_{i-1}| - l_i | */
} whirl_dyn_diagnostics;

/* The diagnostics of the state y at t.
 * @param d the dynamics
 * @param t the time [T]
 * @param y the state, whirl_dyn_size(d)
 * @param out out: energy, angular momentum, the Jacobi integral and the constraint's error
 * @return GSL_SUCCESS, or a status with a message
 */
WHIRL_API int whirl_dyn_diagnose(const whirl_dyn *d, double t, const double *y,
                                 whirl_dyn_diagnostics *out);

/* ---- start states (src/state.c) ---- */

/* links[3 i..3 i + 2] <- the link vector of link i + 1 of the shape whose n + 1 nodes (the pivot
 * first) are (nx, ny, nz) (ny NULL: a planar shape, y = 0), e.g. the r, z of
 * whirl_nlink_positions or the x, y, z of whirl_driven_sample. GSL_EINVAL on NULL arrays,
 * n = 0 or a node that is not finite.
 * @param n the links N
 * @param nx the nodes' x (or r), n + 1, the pivot first
 * @param ny the nodes' y, n + 1, or NULL for a planar shape
 * @param nz the nodes' z, n + 1
 * @param links out: the link vectors, 3 per link
 * @return GSL_SUCCESS, or GSL_EINVAL on NULL arrays, n = 0 or a node that is not finite
 */
WHIRL_API int whirl_shape_links(size_t n, const double *nx, const double *ny, const double *nz,
                      double *links);

/* The one perturbation rule of the library: each of the n link vectors (3 per link, in place)
 * turned by angle [rad] (>= 0) towards a random direction perpendicular to it, uniform on the
 * circle of such directions (GSL's MT19937 seeded with seed); lengths kept. GSL_EINVAL on NULL,
 * n = 0, a bad angle or a zero link; GSL_ENOMEM.
 * @param n the links N
 * @param links the link vectors, 3 per link, turned in place
 * @param angle the angle each is turned by [rad], >= 0
 * @param seed the seed of the random directions
 * @return GSL_SUCCESS, GSL_EINVAL or GSL_ENOMEM
 */
WHIRL_API int whirl_perturb_links(size_t n, double *links, double angle, unsigned long seed);

/* y <- the state of d at time t (length whirl_dyn_size) of the shape whose link vectors are
 * links (3 per link, the shape's own frame: pivot first, z up) turning rigidly at the rate spin
 * [1/T] about the vertical through the pivot, which moves with the drive. In the co-rotating
 * frame the shape is placed as given, the pivot at (drive_radius, 0, 0); in the inertial frame
 * (3D) it is turned about z by the drive's phase at t, so that a steady shape at the model's
 * omega (from whirl_nlink_positions or whirl_driven_sample) is an equilibrium in either frame.
 * A planar model (dim 2) needs spin = 0. The links must have the chain's lengths (to 1e-9
 * relative, whirl_dyn_set_state). GSL_EINVAL with a message on NULL or inconsistent
 * arguments; GSL_ENOMEM (allocates 6 N doubles of scratch and frees them).
 * @param d the dynamics
 * @param t the time [T]
 * @param links the shape's link vectors, 3 per link (whirl_shape_links, perhaps
 *     whirl_perturb_links)
 * @param spin the rate the shape turns at about the vertical [1/T]: the model's omega for a steady
 *     shape
 * @param y out: the state, whirl_dyn_size(d)
 * @return GSL_SUCCESS, GSL_EINVAL with a message on NULL or inconsistent arguments, GSL_ENOMEM
 */
WHIRL_API int whirl_dyn_state_from_shape(whirl_dyn *d, double t, const double *links, double spin,
                               double *y);

/* *h <- the library's default fixed step for a run of the model m with the integrator method
 * near a shape with the link tensions tension[0..N-1] [M g]: the smallest of a 200th of the
 * period 2 pi / omega, the stability limit of the fastest transverse wave under the tensions
 * and those of the damping and the air drag (src/state.c gives the bounds). GSL_EINVAL on NULL
 * arguments, omega <= 0 or a negative tension.
 * @param m the model
 * @param tension the link tensions of the shape the run starts near [M g], N
 * @param method the integrator's name (whirl_integrator_methods)
 * @param h out: the step [T]
 * @return GSL_SUCCESS, or GSL_EINVAL on NULL arguments, omega <= 0 or a negative tension
 */
WHIRL_API int whirl_default_step(const whirl_model *m, const double *tension, const char *method,
                       double *h);

/* Deviation of the positions x (3 per mass, N masses) from the reference ref: the RMS over the
 * masses of their distance, minimised over a rotation of x about z.
 * @param n the masses N
 * @param x the positions, 3 per mass
 * @param ref the reference positions, 3 per mass
 * @return the RMS distance [L], minimised over a rotation of x about z
 */
WHIRL_API double whirl_deviation(size_t n, const double *x, const double *ref);

/* ---- integrators (whirl/integrator.h) on the dynamics ----
 * The Gauss methods' fixed-point stage iteration converges for h omega_max rho(A) < 1 with
 * omega_max ~ 2 N sqrt(T_top/(M g)) sqrt(g/L) for a uniform chain (whirl_default_step keeps
 * below it). */

/* sys <- the dynamics d as a general system: rhs whirl_dyn_rhs, project whirl_dyn_project,
 * size whirl_dyn_size(d), params d, second order, acceleration scale the chain's gravity.
 * GSL_EINVAL on NULL arguments.
 * @param d the dynamics (not owned)
 * @param sys out: the system
 * @return GSL_SUCCESS, or GSL_EINVAL with a message on NULL arguments
 */
WHIRL_API int whirl_dyn_system(whirl_dyn *d, whirl_system *sys);

/* An integrator of the method called method (whirl_integrator_methods) for the dynamics d (not
 * owned): whirl_integrator_alloc_system on whirl_dyn_system(d). NULL on an unknown method (the
 * message lists the known ones), d NULL or no memory.
 * @param method the method's name: gauss2, gauss3, rk4, rk8, gsl-msbdf, ...
 *     (whirl_integrator_methods)
 * @param d the dynamics (not owned)
 * @return the integrator, to free with whirl_integrator_free; NULL with a message on an unknown
 *     method (naming the known ones), d NULL or no memory
 */
WHIRL_API whirl_integrator *whirl_integrator_alloc(const char *method, whirl_dyn *d);

#ifdef __cplusplus
}
#endif

#endif
