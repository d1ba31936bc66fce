/* A steady shape seeded into a run, and its deviation.
 *
 * The N-link chain (N point masses m_i = 1/N on massless links l_i = 1/N, gravity g = 1) spun at
 * the rate omega about the vertical through its pivot has relative equilibria: in the frame
 * co-rotating at omega every mass balances gravity, the centrifugal force m_i omega^2 (x, y, 0)
 * and the tensions of its two links,
 *   T_{i+1} u_{i+1} - T_i u_i + m_i (omega^2 r_i e_r - g e_z) = 0,   T_{N+1} = 0,
 * u_i the unit vector of link i. whirl_nlink_solve finds the one of mode k (k - 1 crossings of
 * the axis); here mode 1 at omega = 2.385. In the co-rotating frame it is a fixed point of the
 * equations of motion (whirl/dynamics.h); started exactly on it, the chain stays there, and each
 * link turned by 1e-4 rad (whirl_perturb_links) it oscillates about it: mode 1 is stable, so the
 * deviation (RMS distance of the masses from the shape) stays of the order of its start.
 *
 * Checks (exit 1 on failure): the unperturbed run stays on the shape to 1e-10 (the steady
 * solver and the dynamics are two formulations of the same equilibrium); the perturbed run's
 * deviation stays below 20 times its start over 20 periods; the Jacobi integral E - omega L_z,
 * conserved in the co-rotating frame without dissipation, drifts by less than 1e-9 relative.
 * Prints the perturbed run's deviation every 5 periods, the checks, and the integrator's
 * statistics. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_math.h>
#include <whirl.h>

#define N 12

/* Runs the shape (links, turned by angle) for `periods` periods; the largest deviation from the
 * shape ref (positions, 3 per mass) and the Jacobi drift. Returns 0, or 1 with a message. */
static int run(const whirl_chain *chain, double omega, const double *links, double angle,
               const double *ref, double periods, double *worst, double *start, double *drift)
{
    whirl_model model = {.chain = chain, .dim = 3, .frame = WHIRL_FRAME_ROTATING, .omega = omega};
    whirl_dyn *dyn = whirl_dyn_alloc(&model, WHIRL_FORMULATION_CARTESIAN);
    whirl_integrator *it = dyn ? whirl_integrator_alloc("gauss2", dyn) : NULL;
    double turned[3 * N], y[6 * N], x[3 * N], v[3 * N], tension[N], h;
    for (int k = 0; k < 3 * N; k++) turned[k] = links[k];
    int status = it ? GSL_SUCCESS : GSL_EFAILED;
    if (!status) status = whirl_dyn_state_from_shape(dyn, 0, links, omega, y);
    if (!status) status = whirl_dyn_tensions(dyn, 0, y, tension);
    if (!status) status = whirl_default_step(&model, tension, "gauss2", &h);
    if (!status && angle > 0) status = whirl_perturb_links(N, turned, angle, 7);
    if (!status) status = whirl_dyn_state_from_shape(dyn, 0, turned, omega, y);
    whirl_dyn_diagnostics d0, d1;
    if (!status) status = whirl_dyn_diagnose(dyn, 0, y, &d0);
    if (!status) status = whirl_dyn_get_state(dyn, 0, y, WHIRL_FRAME_ROTATING, x, v);
    *start = *worst = status ? 0 : whirl_deviation(N, x, ref);
    const double period = 2 * M_PI / omega;
    double t = 0;
    for (int k = 1; !status && k <= 4 * (int)periods; k++) {
        status = whirl_integrator_advance(it, &t, y, k * period / 4, h, 0);
        if (!status) status = whirl_dyn_get_state(dyn, t, y, WHIRL_FRAME_ROTATING, x, v);
        if (status) break;
        const double dev = whirl_deviation(N, x, ref);
        if (dev > *worst) *worst = dev;
        if (k % 20 == 0 && angle > 0) printf("perturbed %8.3f %.3e\n", t, dev);
    }
    if (!status) status = whirl_dyn_diagnose(dyn, t, y, &d1);
    *drift = status ? 0 : fabs(d1.jacobi - d0.jacobi) / fabs(d0.jacobi);
    if (!status) {
        whirl_integrator_stats st = whirl_integrator_get_stats(it);
        printf("# %s: step %.4g, %lu steps\n", angle > 0 ? "perturbed" : "exact", h, st.steps);
    } else {
        fprintf(stderr, "seeded_shape: %s\n", whirl_last_error());
    }
    whirl_integrator_free(it);
    whirl_dyn_free(dyn);
    return status != GSL_SUCCESS;
}

int main(void)
{
    gsl_set_error_handler_off();
    const double omega = 2.385;
    whirl_chain *chain = whirl_chain_alloc_uniform(N, 0);
    whirl_shape_info info;
    double r[N + 1], z[N + 1], tension[N + 1], links[3 * N], ref[3 * N];
    if (chain == NULL || whirl_nlink_solve(chain, omega, 1, &info) ||
        whirl_nlink_positions(chain, omega, info.tip_r, r, z, tension) ||
        whirl_shape_links(N, r, NULL, z, links)) {
        fprintf(stderr, "seeded_shape: %s\n", whirl_last_error());
        return 1;
    }
    for (int i = 0; i < N; i++) { /* the shape's masses in the co-rotating frame */
        ref[3 * i] = r[i + 1];
        ref[3 * i + 1] = 0;
        ref[3 * i + 2] = z[i + 1];
    }
    printf("# mode 1 at omega %g: tip radius %.8f\n", omega, info.tip_r);
    double worst0, start0, drift0, worst1, start1, drift1; /* start0 is 0 */
    if (run(chain, omega, links, 0, ref, 20, &worst0, &start0, &drift0) ||
        run(chain, omega, links, 1e-4, ref, 20, &worst1, &start1, &drift1))
        return 1;
    whirl_chain_free(chain);
    int ok = worst0 < 1e-10 && worst1 < 20 * start1 && drift0 < 1e-9 && drift1 < 1e-9;
    printf("# exact start: largest deviation below 1e-10: %s\n", worst0 < 1e-10 ? "yes" : "no");
    printf("# perturbed: start %.3e, largest %.3e, below 20 times the start: %s\n", start1, worst1,
           worst1 < 20 * start1 ? "yes" : "no");
    printf("# Jacobi drift below 1e-9 in both runs: %s\n",
           drift0 < 1e-9 && drift1 < 1e-9 ? "yes" : "no");
    printf("%s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
