/* The peers' side of whirl's comparisons (tests/bench/bench_peers.c and tests/unit/dynamics/test_peers.c):
 * header-only (static functions), each part only when its package's headers were found
 * (WHIRL_HAVE_MUJOCO, WHIRL_HAVE_SUNDIALS; the Makefile checks).
 *
 * MuJoCo: the N-link chain of point masses as nested bodies. Body i hangs from mass i-1 (the
 * pivot for i = 1) by two hinges, about its x then its y axis, and carries mass i at (0, 0, -l_i)
 * of its frame; gravity -z, no contacts. MuJoCo refuses a moving body without rotational inertia
 * (at most 1e-15): each body gets 2e-15 about its centre, and the masses are given in units of
 * 1e-9 of whirl's (the motion of a point-mass chain does not depend on the mass scale), so that
 * this inertia is below 1e-14 of a link's m l^2 up to N = 1000; energies are compared after
 * dividing by the scale. MuJoCo's XML parser refuses elements nested deeper than 100, so the
 * chain is cut into files of 40 bodies, the innermost body of file k holding
 * <include file="chain_k+1.xml"/> (an included file's top element is dropped and its children
 * inserted where the include stands).
 * Coordinates: link i points along R_i (0, 0, -1), R_i = R_{i-1} Rx(a_i) Ry(b_i), so
 * R_{i-1}^T u_i = (-sin b, cos b sin a, -cos b cos a); the rates from du_i/dt = Om_i x u_i,
 * Om_i = Om_{i-1} + a_i' R_{i-1} e_x + b_i' R_{i-1} Rx(a_i) e_y (least squares in the two rates,
 * exact for velocities consistent with the links).
 * Check of the model (peer_mj_load): positions (xipos) and velocities (body Jacobians times
 * qvel) against whirl's, energy against whirl_dyn_diagnose's, and the hanging chain's
 * normal-mode frequencies against whirl_nlink_critical: from MuJoCo's mass matrix (x-hinges;
 * the y-hinges decouple at q = 0) and the Jacobian of its bias force (central differences at
 * 1e-2, 5e-3, 2.5e-3 with two Richardson steps, error O(h^6)), generalized symmetric
 * eigenproblem by LAPACK dsygv. The condition number kappa of that mass matrix (dpocon) bounds
 * the eigensolver's relative error of the highest frequencies, about eps kappa (kappa = 2e8 at
 * N = 100).
 *
 * SUNDIALS: ARKODE ERKStep and CVODE on whirl_dyn_rhs (a failed evaluation is recoverable: the
 * solver retries a smaller step), ARKODE optionally with whirl_dyn_project after every step
 * (ERKStepSetPostprocessStepFn). Needs bench_util.h (bench_now) included first. */
#ifndef WHIRL_PEER_GLUE_H
#define WHIRL_PEER_GLUE_H

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#ifdef WHIRL_HAVE_MUJOCO
#include <lapacke.h>
#include <mujoco/mujoco.h>

#define PEER_MJ_BODIES_PER_FILE 40
#define PEER_MJ_MASS_SCALE 1e9 /* MuJoCo mass = PEER_MJ_MASS_SCALE x whirl's mass */

typedef struct peer_mj {
    mjModel *m;
    mjData *d;
    double *qpos, *qvel; /* the start, 2 N each */
} peer_mj;

/* The agreement of MuJoCo's model with whirl's at the start. */
typedef struct peer_mj_check {
    size_t files;      /* XML files written */
    double dx, dv;     /* largest position and velocity difference of a mass */
    double energy;     /* MuJoCo's energy (in whirl's mass unit) */
    double de;         /* |energy - whirl's| */
    double dfreq;      /* largest relative difference of a hanging normal-mode frequency (-1:
                          not compared) */
    size_t worst_mode; /* where (1-based) */
    double kappa;      /* condition number of MuJoCo's x-hinge mass matrix at q = 0 */
    double freq_lo, freq_hi; /* MuJoCo's lowest and highest frequency */
} peer_mj_check;

/* 1 if the check passes: positions and velocities to 1e-12, energy to 1e-10, frequencies to
 * 1e-10 or, where larger, the eigensolver's bound eps kappa. */
static inline int peer_mj_agrees(const peer_mj_check *k)
{
    return k->dx <= 1e-12 && k->dv <= 1e-12 && k->de <= 1e-10 &&
           k->dfreq <= fmax(1e-10, DBL_EPSILON * k->kappa);
}

/* R <- R * (rotation by angle a about axis k = 0 (x) or 1 (y)); row-major 3 x 3 */
static inline void peer_rotate_by(double R[9], int k, double a)
{
    const double c = cos(a), s = sin(a);
    double G[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, T[9];
    if (k == 0) G[4] = c, G[5] = -s, G[7] = s, G[8] = c;
    else G[0] = c, G[2] = s, G[6] = -s, G[8] = c;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            T[3 * i + j] = R[3 * i] * G[j] + R[3 * i + 1] * G[3 + j] + R[3 * i + 2] * G[6 + j];
    memcpy(R, T, sizeof T);
}

static inline void peer_cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double peer_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Hinge angles and rates for positions x and velocities v (3 per mass, pivot at the origin). */
static inline void peer_mj_coordinates(const whirl_chain *c, const double *x, const double *v,
                                       double *qpos, double *qvel)
{
    double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, om[3] = {0, 0, 0};
    double prev_x[3] = {0, 0, 0}, prev_v[3] = {0, 0, 0};
    for (size_t i = 0; i < c->n; i++) {
        double u[3], w[3], ur[3];
        for (int k = 0; k < 3; k++) {
            u[k] = (x[3 * i + k] - prev_x[k]) / c->length[i];
            w[k] = (v[3 * i + k] - prev_v[k]) / c->length[i];
            prev_x[k] = x[3 * i + k];
            prev_v[k] = v[3 * i + k];
        }
        for (int k = 0; k < 3; k++) ur[k] = R[k] * u[0] + R[3 + k] * u[1] + R[6 + k] * u[2];
        const double a = atan2(ur[1], -ur[2]), b = asin(fmax(-1, fmin(1, -ur[0])));
        const double A[3] = {R[0], R[3], R[6]};
        peer_rotate_by(R, 0, a);
        const double B[3] = {R[1], R[4], R[7]};
        peer_rotate_by(R, 1, b);
        double oxu[3], P[3], Q[3], r[3];
        peer_cross(om, u, oxu);
        for (int k = 0; k < 3; k++) r[k] = w[k] - oxu[k];
        peer_cross(A, u, P);
        peer_cross(B, u, Q);
        const double pp = peer_dot3(P, P), pq = peer_dot3(P, Q), qq = peer_dot3(Q, Q),
                     pr = peer_dot3(P, r), qr = peer_dot3(Q, r), det = pp * qq - pq * pq;
        const double ad = (qq * pr - pq * qr) / det, bd = (pp * qr - pq * pr) / det;
        for (int k = 0; k < 3; k++) om[k] += ad * A[k] + bd * B[k];
        qpos[2 * i] = a, qpos[2 * i + 1] = b;
        qvel[2 * i] = ad, qvel[2 * i + 1] = bd;
    }
}

/* Writes the model of chain c as dir/chain_0.xml .. chain_K.xml (main_path <- the first);
 * -1 with a message in msg if a file cannot be written. */
static inline int peer_mj_write_xml(const whirl_chain *c, const char *dir, char *main_path,
                                    size_t len, char *msg, size_t msglen)
{
    const size_t n = c->n, files = (n + PEER_MJ_BODIES_PER_FILE - 1) / PEER_MJ_BODIES_PER_FILE;
    for (size_t f = 0; f < files; f++) {
        char path[600];
        snprintf(path, sizeof path, "%s/chain_%zu.xml", dir, f);
        if (f == 0) snprintf(main_path, len, "%s", path);
        FILE *fp = fopen(path, "w");
        if (fp == NULL) {
            snprintf(msg, msglen, "cannot write %s", path);
            return -1;
        }
        if (f == 0)
            fprintf(fp, "<mujoco model=\"chain%zu\">\n  <compiler angle=\"radian\"/>\n"
                        "  <option gravity=\"0 0 %.17g\" integrator=\"RK4\">\n"
                        "    <flag contact=\"disable\" energy=\"enable\"/>\n  </option>\n"
                        "  <worldbody>\n",
                    n, -c->gravity);
        else fprintf(fp, "<mujoco>\n");
        const size_t first = f * PEER_MJ_BODIES_PER_FILE,
                     last = first + PEER_MJ_BODIES_PER_FILE < n ? first + PEER_MJ_BODIES_PER_FILE
                                                                 : n;
        for (size_t i = first; i < last; i++)
            fprintf(fp,
                    "<body name=\"m%zu\" pos=\"0 0 %.17g\"><joint type=\"hinge\" axis=\"1 0 0\"/>"
                    "<joint type=\"hinge\" axis=\"0 1 0\"/><inertial pos=\"0 0 %.17g\" "
                    "mass=\"%.17g\" diaginertia=\"2e-15 2e-15 2e-15\"/>\n",
                    i + 1, i == 0 ? 0.0 : -c->length[i - 1], -c->length[i],
                    PEER_MJ_MASS_SCALE * c->mass[i]);
        if (last < n) fprintf(fp, "<include file=\"chain_%zu.xml\"/>\n", f + 1);
        for (size_t i = first; i < last; i++) fprintf(fp, "</body>");
        fprintf(fp, "\n%s</mujoco>\n", f == 0 ? "  </worldbody>\n" : "");
        if (fclose(fp) != 0) {
            snprintf(msg, msglen, "cannot write %s", path);
            return -1;
        }
    }
    return 0;
}

static inline void peer_mj_free(peer_mj *mc)
{
    if (mc->d != NULL) mj_deleteData(mc->d);
    if (mc->m != NULL) mj_deleteModel(mc->m);
    free(mc->qpos);
    free(mc->qvel);
    memset(mc, 0, sizeof *mc);
}

/* The hanging chain's normal-mode frequencies of MuJoCo's model against whirl's (see the top);
 * fills dfreq, worst_mode, kappa, freq_lo, freq_hi. -1 on a failure. */
static inline int peer_mj_frequencies(const whirl_chain *c, peer_mj *mc, peer_mj_check *k)
{
    const size_t n = c->n, nv = 2 * n;
    mjModel *m = mc->m;
    mjData *d = mc->d;
    double *M = malloc(nv * nv * sizeof *M), *K = malloc(n * n * sizeof *K),
           *Mx = malloc(n * n * sizeof *Mx), *Mc = malloc(n * n * sizeof *Mc),
           *w = malloc(n * sizeof *w), *ref = malloc(n * sizeof *ref),
           *f = malloc(6 * n * sizeof *f);
    int status = -1;
    if (M == NULL || K == NULL || Mx == NULL || Mc == NULL || w == NULL || ref == NULL ||
        f == NULL)
        goto done;
    mj_resetData(m, d);
    mj_forward(m, d);
    mj_fullM(m, M, d->qM);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) Mx[i * n + j] = M[2 * i * nv + 2 * j];
    const double h = 1e-2, steps[6] = {h, -h, h / 2, -h / 2, h / 4, -h / 4};
    for (size_t j = 0; j < n; j++) {
        for (int q = 0; q < 6; q++) {
            mj_resetData(m, d);
            d->qpos[2 * j] = steps[q];
            mj_forward(m, d);
            for (size_t i = 0; i < n; i++) f[q * n + i] = d->qfrc_bias[2 * i];
        }
        for (size_t i = 0; i < n; i++) {
            double cd[3];
            for (int q = 0; q < 3; q++)
                cd[q] = (f[2 * q * n + i] - f[(2 * q + 1) * n + i]) / (2 * steps[2 * q]);
            const double r1 = (4 * cd[1] - cd[0]) / 3, r2 = (4 * cd[2] - cd[1]) / 3;
            K[i * n + j] = (16 * r2 - r1) / 15;
        }
    }
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < i; j++)
            K[i * n + j] = K[j * n + i] = 0.5 * (K[i * n + j] + K[j * n + i]);
    double anorm = 0, rcond = 0;
    for (size_t j = 0; j < n; j++) {
        double col = 0;
        for (size_t i = 0; i < n; i++) col += fabs(Mx[i * n + j]);
        anorm = fmax(anorm, col);
    }
    memcpy(Mc, Mx, n * n * sizeof *Mc);
    if (LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'U', (lapack_int)n, Mc, (lapack_int)n) != 0 ||
        LAPACKE_dpocon(LAPACK_ROW_MAJOR, 'U', (lapack_int)n, Mc, (lapack_int)n, anorm, &rcond) !=
            0)
        rcond = 0;
    k->kappa = rcond > 0 ? 1 / rcond : INFINITY;
    if (LAPACKE_dsygv(LAPACK_ROW_MAJOR, 1, 'N', 'U', (lapack_int)n, K, (lapack_int)n, Mx,
                      (lapack_int)n, w) != 0 ||
        whirl_nlink_critical(c, n, ref) != GSL_SUCCESS)
        goto done;
    k->dfreq = 0;
    for (size_t i = 0; i < n; i++)
        if (!(fabs(sqrt(w[i]) / ref[i] - 1) <= k->dfreq))
            k->dfreq = fabs(sqrt(w[i]) / ref[i] - 1), k->worst_mode = i + 1;
    k->freq_lo = sqrt(w[0]);
    k->freq_hi = sqrt(w[n - 1]);
    status = 0;
done:
    free(M), free(K), free(Mx), free(Mc), free(w), free(ref), free(f);
    return status;
}

/* Loads the chain c into MuJoCo (XML under dir/mujoco_chainN/), sets the start (x, v inertial,
 * 3 per mass) and checks it against whirl (energy: whirl_dyn_diagnose's at the start;
 * frequencies: 1 to compare the hanging chain's normal modes too). -1 with a message (msglen
 * >= 2048 holds any) on a failure to load; the check is in *k (peer_mj_agrees). */
static inline int peer_mj_load(const whirl_chain *c, const char *dir, const double *x,
                               const double *v, double energy, int frequencies, peer_mj *mc,
                               peer_mj_check *k, char *msg, size_t msglen)
{
    const size_t n = c->n, nv = 2 * n;
    char sub[512], main_path[600], err[1000] = "";
    memset(mc, 0, sizeof *mc);
    memset(k, 0, sizeof *k);
    k->dfreq = -1;
    k->files = (n + PEER_MJ_BODIES_PER_FILE - 1) / PEER_MJ_BODIES_PER_FILE;
    snprintf(sub, sizeof sub, "%s/mujoco_chain%zu", dir, n);
    mkdir(sub, 0777);
    if (peer_mj_write_xml(c, sub, main_path, sizeof main_path, msg, msglen) != 0) return -1;
    mc->m = mj_loadXML(main_path, NULL, err, sizeof err);
    if (mc->m == NULL) {
        snprintf(msg, msglen, "MuJoCo refuses %s: %s", main_path, err);
        return -1;
    }
    mc->d = mj_makeData(mc->m);
    mc->qpos = malloc(nv * sizeof *mc->qpos);
    mc->qvel = malloc(nv * sizeof *mc->qvel);
    double *jac = malloc(3 * nv * sizeof *jac);
    if (mc->d == NULL || mc->qpos == NULL || mc->qvel == NULL || jac == NULL) {
        free(jac);
        snprintf(msg, msglen, "no memory for MuJoCo's model of N = %zu", n);
        return -1;
    }
    if ((size_t)mc->m->nbody != n + 1 || (size_t)mc->m->nv != nv) {
        free(jac);
        snprintf(msg, msglen, "MuJoCo's model of N = %zu has %d bodies and %d dofs", n,
                 mc->m->nbody, mc->m->nv);
        return -1;
    }
    mjModel *m = mc->m;
    mjData *d = mc->d;
    peer_mj_coordinates(c, x, v, mc->qpos, mc->qvel);
    memcpy(d->qpos, mc->qpos, nv * sizeof(double));
    memcpy(d->qvel, mc->qvel, nv * sizeof(double));
    mj_forward(m, d);
    mj_energyPos(m, d);
    mj_energyVel(m, d);
    k->energy = (d->energy[0] + d->energy[1]) / PEER_MJ_MASS_SCALE;
    k->de = fabs(k->energy - energy);
    for (size_t i = 0; i < n; i++) {
        const double *p = d->xipos + 3 * (i + 1);
        mj_jacBodyCom(m, d, jac, NULL, (int)i + 1);
        for (int q = 0; q < 3; q++) {
            double vq = 0;
            for (size_t j = 0; j < nv; j++) vq += jac[q * nv + j] * d->qvel[j];
            k->dx = fmax(k->dx, fabs(p[q] - x[3 * i + q]));
            k->dv = fmax(k->dv, fabs(vq - v[3 * i + q]));
        }
    }
    free(jac);
    if (frequencies && peer_mj_frequencies(c, mc, k) != 0) {
        snprintf(msg, msglen, "normal modes of the hanging chain failed (N = %zu)", n);
        return -1;
    }
    return 0;
}

/* Integrates MuJoCo's chain from its start with RK4 at the step t_end / steps; x <- the masses'
 * positions at t_end. Returns the wall seconds, -1 if the state is not finite. */
static inline double peer_mj_run(peer_mj *mc, double t_end, long steps, double *x)
{
    mjModel *m = mc->m;
    mjData *d = mc->d;
    const size_t nv = (size_t)m->nv;
    mj_resetData(m, d);
    memcpy(d->qpos, mc->qpos, nv * sizeof(double));
    memcpy(d->qvel, mc->qvel, nv * sizeof(double));
    m->opt.timestep = t_end / (double)steps;
    m->opt.integrator = mjINT_RK4;
    const double t0 = bench_now();
    for (long k = 0; k < steps; k++) mj_step(m, d);
    mj_kinematics(m, d);
    double secs = bench_now() - t0;
    for (size_t i = 0; i < 3 * (nv / 2); i++) {
        x[i] = d->xipos[3 + i];
        if (!isfinite(x[i])) secs = -1;
    }
    return secs;
}
#endif

#ifdef WHIRL_HAVE_SUNDIALS
#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

static int peer_sun_rhs(realtype t, N_Vector y, N_Vector ydot, void *dyn)
{
    /* positive: a recoverable failure (the solver retries with a smaller step) */
    return whirl_dyn_rhs(t, NV_DATA_S(y), NV_DATA_S(ydot), dyn) == GSL_SUCCESS ? 0 : 1;
}

static int peer_sun_project(realtype t, N_Vector y, void *dyn)
{
    return whirl_dyn_project(dyn, t, NV_DATA_S(y)) == GSL_SUCCESS ? 0 : -1;
}

/* One SUNDIALS run on the dynamics dyn from y (whirl's state, updated in place) at t = 0 to
 * t_end: ARKODE ERKStep with the table (project: whirl_dyn_project after every step) or, with
 * table < 0, CVODE Adams (fixed-point iteration); relative = absolute tolerance tol; given up
 * after max_secs of wall time (in pieces of 10^4 steps). Returns 0 on reaching t_end, -1 on a
 * failure of the solver, -2 if it cannot be set up; *steps, *rhs its counts. */
static inline int peer_sun_run(SUNContext ctx, whirl_dyn *dyn, double *y0, double t_end,
                               int table, int project, double tol, double max_secs, long *steps,
                               long *rhs)
{
    const size_t size = whirl_dyn_size(dyn);
    N_Vector y = N_VMake_Serial((sunindextype)size, y0, ctx);
    if (y == NULL) return -2;
    realtype t = 0;
    void *mem = NULL;
    SUNNonlinearSolver nls = NULL;
    int ok;
    if (table >= 0) {
        mem = ERKStepCreate(peer_sun_rhs, 0, y, ctx);
        ok = mem != NULL && ERKStepSetTableNum(mem, (ARKODE_ERKTableID)table) == 0 &&
             ERKStepSStolerances(mem, tol, tol) == 0 && ERKStepSetUserData(mem, dyn) == 0 &&
             ERKStepSetMaxNumSteps(mem, 10000) == 0 && ERKStepSetStopTime(mem, t_end) == 0 &&
             ERKStepSetMinStep(mem, 1e-12 * t_end) == 0 && ERKStepSetMaxHnilWarns(mem, -1) == 0 &&
             ERKStepSetErrFile(mem, NULL) == 0 &&
             (!project || ERKStepSetPostprocessStepFn(mem, peer_sun_project) == 0);
    } else {
        mem = CVodeCreate(CV_ADAMS, ctx);
        nls = SUNNonlinSol_FixedPoint(y, 0, ctx);
        ok = mem != NULL && nls != NULL && CVodeInit(mem, peer_sun_rhs, 0, y) == 0 &&
             CVodeSStolerances(mem, tol, tol) == 0 && CVodeSetUserData(mem, dyn) == 0 &&
             CVodeSetNonlinearSolver(mem, nls) == 0 && CVodeSetMaxNumSteps(mem, 10000) == 0 &&
             CVodeSetStopTime(mem, t_end) == 0 && CVodeSetMinStep(mem, 1e-12 * t_end) == 0 &&
             CVodeSetMaxHnilWarns(mem, -1) == 0 && CVodeSetErrFile(mem, NULL) == 0;
    }
    int status = -2;
    if (ok) {
        const double t0 = bench_now();
        int flag;
        do
            flag = table >= 0 ? ERKStepEvolve(mem, t_end, y, &t, ARK_NORMAL)
                              : CVode(mem, t_end, y, &t, CV_NORMAL);
        while ((table >= 0 ? flag == ARK_TOO_MUCH_WORK : flag == CV_TOO_MUCH_WORK) &&
               bench_now() - t0 < max_secs);
        status = flag < 0 || fabs(t - t_end) > 1e-9 * t_end ? -1 : 0;
    }
    *steps = *rhs = 0;
    if (table >= 0) {
        if (mem != NULL) {
            ERKStepGetNumSteps(mem, steps);
            ERKStepGetNumRhsEvals(mem, rhs);
            ERKStepFree(&mem);
        }
    } else {
        if (mem != NULL) {
            CVodeGetNumSteps(mem, steps);
            CVodeGetNumRhsEvals(mem, rhs);
            CVodeFree(&mem);
        }
        if (nls != NULL) SUNNonlinSolFree(nls);
    }
    N_VDestroy(y);
    return status;
}
#endif

#endif
