/* Tests of the peers' side of the benchmarks (tests/lib/peer_glue.h): the comparisons in
 * tests/bench/bench_peers.c are only as good as the peers' models being whirl's.
 *  - MuJoCo: the chain of N = 10 (one XML file) and N = 90 (three, joined by <include>) loaded
 *    from the mode-2 start of bench_peers; positions and velocities equal to whirl's to 1e-12,
 *    energy to 1e-10, the hanging chain's normal-mode frequencies to 1e-10 at N = 10 and to
 *    the eigensolver's bound eps kappa at N = 90; MuJoCo's RK4 converges to whirl's motion (N = 10
 *    over one rotation period, whirl rk8 at tolerance 1e-12 as the reference) at fourth order:
 *    halving the step divides the distance by 16 within a factor 1.5, and it ends below 1e-7;
 *  - SUNDIALS: ARKODE (Verner 8-5-6) with whirl's projection at tolerance 1e-10 ends within 1e-7
 *    of whirl rk8's motion and on the constraints (1e-12), without projection it ends off them;
 *    CVODE Adams at 1e-10 within 1e-6.
 * The peers' packages are installed by scripts/deps.sh: a build without their headers fails
 * here, naming the package. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <gsl/gsl_errno.h>

#include "whirl/dynamics.h"
#include "whirl/steady.h"

#define BENCH_NAME "test_peers"
#include "bench_util.h"
#include "peer_glue.h"

#define PI 3.14159265358979323846
#define OMEGA 4.0

/* The start of bench_peers' scenes: chain, dynamics in the co-rotating frame, state y, inertial
 * positions and velocities, energy. */
typedef struct start {
    whirl_chain *chain;
    whirl_model model;
    whirl_dyn *dyn;
    double *y, *x, *v;
    double energy;
} start;

static void start_alloc(size_t n, start *s)
{
    s->chain = whirl_chain_alloc_uniform(n, 0);
    assert_non_null(s->chain);
    s->model = (whirl_model){
        .chain = s->chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = OMEGA};
    s->dyn = whirl_dyn_alloc(&s->model, WHIRL_FORMULATION_CARTESIAN);
    assert_non_null(s->dyn);
    s->y = malloc(whirl_dyn_size(s->dyn) * sizeof *s->y);
    s->x = calloc(3 * n, sizeof *s->x);
    s->v = calloc(3 * n, sizeof *s->v);
    assert_true(s->y != NULL && s->x != NULL && s->v != NULL);
    assert_int_equal(bench_scene_start(s->chain, OMEGA, s->x), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_set_state(s->dyn, 0, s->x, s->v, s->y), GSL_SUCCESS);
    assert_int_equal(
        whirl_dyn_get_state(s->dyn, 0, s->y, WHIRL_FRAME_INERTIAL, s->x, s->v), GSL_SUCCESS);
    whirl_dyn_diagnostics diag;
    assert_int_equal(whirl_dyn_diagnose(s->dyn, 0, s->y, &diag), GSL_SUCCESS);
    s->energy = diag.energy;
}

static void start_free(start *s)
{
    whirl_dyn_free(s->dyn);
    whirl_chain_free(s->chain);
    free(s->y), free(s->x), free(s->v);
}

/* Inertial positions at t_end of whirl rk8 at tolerance 1e-12 from the start. */
static void whirl_reference(const start *s, double t_end, double *xf)
{
    const size_t size = whirl_dyn_size(s->dyn), n = s->chain->n;
    double *y = malloc(size * sizeof *y), *vf = malloc(3 * n * sizeof *vf);
    whirl_integrator *it = whirl_integrator_alloc("rk8", s->dyn);
    assert_true(y != NULL && vf != NULL && it != NULL);
    memcpy(y, s->y, size * sizeof *y);
    double t = 0;
    assert_int_equal(whirl_integrator_advance(it, &t, y, t_end, 1e-3, 1e-12), GSL_SUCCESS);
    assert_int_equal(whirl_dyn_get_state(s->dyn, t, y, WHIRL_FRAME_INERTIAL, xf, vf),
                     GSL_SUCCESS);
    whirl_integrator_free(it);
    free(y);
    free(vf);
}

#ifdef WHIRL_HAVE_MUJOCO
/* A fresh directory for the XML files; removed by remove_dir. */
static void make_dir(char *dir, size_t len)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, len, "%s/whirl_peers_XXXXXX", tmp != NULL && tmp[0] ? tmp : "/tmp");
    assert_non_null(mkdtemp(dir));
}

static void remove_dir(const char *dir, size_t n)
{
    char path[700];
    for (size_t f = 0; f * PEER_MJ_BODIES_PER_FILE < n; f++) {
        snprintf(path, sizeof path, "%s/mujoco_chain%zu/chain_%zu.xml", dir, n, f);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/mujoco_chain%zu", dir, n);
    rmdir(path);
    rmdir(dir);
}

static void check_model(size_t n, double freq_tol)
{
    start s;
    start_alloc(n, &s);
    char dir[256], msg[2048] = "";
    make_dir(dir, sizeof dir);
    peer_mj mc;
    peer_mj_check k;
    const int status = peer_mj_load(s.chain, dir, s.x, s.v, s.energy, 1, &mc, &k, msg, sizeof msg);
    if (status != 0) fail_msg("%s", msg);
    print_message("N = %zu (%zu files): positions %.2g, velocities %.2g, energy %.2g, "
                  "frequencies %.2g (mode %zu, kappa %.2g)\n",
                  n, k.files, k.dx, k.dv, k.de, k.dfreq, k.worst_mode, k.kappa);
    assert_int_equal(k.files, (n + PEER_MJ_BODIES_PER_FILE - 1) / PEER_MJ_BODIES_PER_FILE);
    assert_true(k.dx <= 1e-12);
    assert_true(k.dv <= 1e-12);
    assert_true(k.de <= 1e-10);
    assert_true(k.dfreq >= 0 && k.dfreq <= freq_tol);
    assert_true(peer_mj_agrees(&k));
    if (n == 10) {
        /* fourth-order convergence of MuJoCo's RK4 to whirl's motion over one period */
        const double t_end = 2 * PI / OMEGA;
        double *xr = malloc(3 * n * sizeof *xr), *xm = malloc(3 * n * sizeof *xm);
        assert_true(xr != NULL && xm != NULL);
        whirl_reference(&s, t_end, xr);
        assert_true(peer_mj_run(&mc, t_end, 400, xm) >= 0);
        const double e1 = bench_max_distance(n, xm, xr);
        assert_true(peer_mj_run(&mc, t_end, 800, xm) >= 0);
        const double e2 = bench_max_distance(n, xm, xr);
        print_message("MuJoCo RK4 against whirl rk8, one period: %.3g (400 steps), %.3g (800), "
                      "ratio %.3g\n", e1, e2, e1 / e2);
        assert_true(e1 / e2 > 16 / 1.5 && e1 / e2 < 16 * 1.5);
        assert_true(e2 < 1e-7);
        free(xr);
        free(xm);
    }
    peer_mj_free(&mc);
    remove_dir(dir, n);
    start_free(&s);
}

static void test_mujoco_10(void **state)
{
    (void)state;
    check_model(10, 1e-10);
}

static void test_mujoco_90(void **state)
{
    (void)state;
    /* kappa ~ 1e8: the highest modes are resolved to a few 1e-10 (peer_glue.h) */
    check_model(90, 2e-8);
}
#else
static void test_mujoco_10(void **state)
{
    (void)state;
    fail_msg("MuJoCo's headers (mujoco/mujoco.h) were not found at build time: install "
             "libmujoco-dev (scripts/deps.sh)");
}

static void test_mujoco_90(void **state) { test_mujoco_10(state); }
#endif

#ifdef WHIRL_HAVE_SUNDIALS
/* on_constraints: 1 must end on them (1e-12), 0 must not, -1 not checked */
static void sundials_run(int table, int project, double tol, double max_dist, int on_constraints)
{
    start s;
    start_alloc(10, &s);
    SUNContext ctx;
    assert_int_equal(SUNContext_Create(NULL, &ctx), 0);
    const double t_end = 2 * PI / OMEGA;
    const size_t n = 10;
    double *xr = malloc(3 * n * sizeof *xr), *xs = malloc(3 * n * sizeof *xs),
           *vs = malloc(3 * n * sizeof *vs);
    assert_true(xr != NULL && xs != NULL && vs != NULL);
    whirl_reference(&s, t_end, xr);
    long steps, rhs;
    assert_int_equal(peer_sun_run(ctx, s.dyn, s.y, t_end, table, project, tol, 60, &steps, &rhs),
                     0);
    assert_int_equal(whirl_dyn_get_state(s.dyn, t_end, s.y, WHIRL_FRAME_INERTIAL, xs, vs),
                     GSL_SUCCESS);
    whirl_dyn_diagnostics diag;
    assert_int_equal(whirl_dyn_diagnose(s.dyn, t_end, s.y, &diag), GSL_SUCCESS);
    const double dist = bench_max_distance(n, xs, xr);
    print_message("%s%s tol %g: %ld steps, %ld rhs, distance from whirl rk8 %.3g, off the "
                  "constraints by %.3g\n", table >= 0 ? "ARKODE" : "CVODE Adams",
                  project ? " with projection" : "", tol, steps, rhs, dist, diag.constraint);
    assert_true(dist < max_dist);
    if (on_constraints == 1) assert_true(diag.constraint <= 1e-12);
    if (on_constraints == 0) assert_true(diag.constraint > 1e-12);
    free(xr), free(xs), free(vs);
    SUNContext_Free(&ctx);
    start_free(&s);
}

static void test_arkode(void **state)
{
    (void)state;
    sundials_run(ARKODE_VERNER_8_5_6, 1, 1e-10, 1e-7, 1);
    /* without the projection the drift is the solver's (a loose tolerance shows it) */
    sundials_run(ARKODE_VERNER_8_5_6, 0, 1e-5, 1e-2, 0);
}

static void test_cvode(void **state)
{
    (void)state;
    sundials_run(-1, 0, 1e-10, 1e-6, -1);
}
#else
static void test_arkode(void **state)
{
    (void)state;
    fail_msg("SUNDIALS' headers (arkode/arkode_erkstep.h, cvode/cvode.h) were not found at build "
             "time: install libsundials-dev (scripts/deps.sh)");
}

static void test_cvode(void **state) { test_arkode(state); }
#endif

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mujoco_10),
        cmocka_unit_test(test_mujoco_90),
        cmocka_unit_test(test_arkode),
        cmocka_unit_test(test_cvode),
    };
    return cmocka_run_group_tests_name("peers", tests, NULL, NULL);
}
