/* The page's Floquet multipliers (whirl_web.h): the periodic motion of the shaken chain's
 * settings found by the library's periodic solver (include/whirl/periodic.h) as whirl periodic
 * finds it by default, and its multipliers with their error estimates and the verdict, one JSON
 * answer (web_internal.h).
 *
 * The settings are the shaken run's (whirl_web_shake_alloc): its chain (30 links for the
 * continuum, VERDICT_LINKS), its pivot path at its rate, its air drag; the start is its start,
 * the chain hanging straight down (whirl periodic's default, --start hanging) or standing
 * straight up (--start inverted), untilted: Newton's method on the period map from the vertical
 * chain. The solve is whirl periodic's with no option but the chain's: 400 Gauss steps per period
 * raised to the chain's bound, Newton's test 1e-10, 30 iterations, a second solve with the step
 * halved for the error estimate (Richardson: |mu(h/2) - mu(h)| / 15), the monodromy from the
 * variational equations. The dimensionless rate and drag are formed as the command line forms
 * them (the SI value over the unit sqrt(g/L), M sqrt(g/L) / L, M / L^2), so that the same
 * settings give the same doubles and the multipliers of whirl periodic bit for bit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_internal.h"
#include "whirl/chain.h"
#include "whirl/common.h"
#include "whirl/dynamics.h"
#include "whirl/periodic.h"
#include "web/whirl_web.h"
#include "web/web_internal.h"

/* The most work of a solve the page takes on: the coarser solve's Gauss steps per period times
 * the links squared (a step of the variational equations carries 4 N columns of N links). 30
 * links at the default 400 steps (3.6e5) take 0.6 s natively when Newton's method converges at
 * once and 15 s when it runs all its 30 iterations without converging (whirl periodic --pivot
 * circle:1cm --omega 3Hz --links 30 --length 60cm), twice that as WebAssembly: the bound
 * admits them and not much more. */
#define FLOQUET_WORK_MAX 4e5

/* The answer of a solve that converged: the motion's period and steps, the verdict with its
 * growth, the largest multiplier with its error, then every multiplier [re, im, |mu|, err]. */
static void put_result(json *j, const web_state *s, const whirl_periodic_result *r, size_t n,
                       int dissipative)
{
    /* the unit of time as the command line's (cli_units_scale: 1 over sqrt(g/L)) */
    const double time = 1 / sqrt(WHIRL_STANDARD_GRAVITY / s->length);
    web_put(j, "{\"links\":%zu,\"start\":\"%s\",\"dissipative\":%s", n,
            s->inverted ? "inverted" : "hanging", dissipative ? "true" : "false");
    web_put(j, ",\"unit\":");
    web_put_string(j, s->unit_name);
    web_put_key_number(j, "shake", s->shake_omega / s->unit);
    web_put_key_number(j, "period", r->period * time);
    web_put(j, ",\"steps\":%d,\"iterations\":%d", r->steps, r->iterations);
    web_put_key_number(j, "residual", r->residual);
    web_put(j, ",\"verdict\":");
    web_put_string(j, whirl_floquet_verdict_name(r->verdict));
    web_put(j, ",\"edge\":");
    web_put_string(j, whirl_floquet_edge_name(r->edge));
    web_put_key_number(j, "edge_distance", r->edge_distance);
    web_put_key_number(j, "growth", r->growth);
    web_put_key_number(j, "efold_periods", r->efold_periods);
    web_put_key_number(j, "efold_time", r->efold_time * time);
    web_put_key_number(j, "max_modulus", r->max_modulus);
    web_put_key_number(j, "max_modulus_err", r->max_modulus_err);
    web_put_key_number(j, "reciprocal_err", r->reciprocal_err);
    web_put_key_number(j, "orbit_change", r->orbit_change);
    /* |mu| as whirl periodic writes it: hypot of the parts */
    web_put(j, ",\"multipliers\":[");
    for (size_t i = 0; i < r->count; i++) {
        web_put(j, "%s[", i ? "," : "");
        web_put_number(j, r->re[i]);
        web_put(j, ",");
        web_put_number(j, r->im[i]);
        web_put(j, ",");
        web_put_number(j, hypot(r->re[i], r->im[i]));
        web_put(j, ",");
        web_put_number(j, r->err[i]);
        web_put(j, "]");
    }
    web_put(j, "]}");
}

char *whirl_web_floquet(const char *query)
{
    web_state s;
    if (web_read_state(&s, query)) return web_error_answer(s.field, s.message);
    if (!s.pivot[0])
        return web_error_answer("pivot", "pivot: none, a fixed pivot: the Floquet multipliers "
                                "are those of a motion under a moving pivot (choose a path)");
    /* the command line's units (cli_units_scale): the rate over sqrt(g/L), the drag over
     * M sqrt(g/L) / L and M / L^2 */
    const double rate = sqrt(WHIRL_STANDARD_GRAVITY / s.length);
    const double w = s.shake_omega / rate;
    whirl_pivot_path path;
    if (whirl_pivot_parse(s.pivot, w, s.length, 3, &path) != GSL_SUCCESS)
        return (web_library_fail(&s, "pivot"), web_error_answer(s.field, s.message));
    whirl_chain *c = web_chain_of(&s, s.links ? s.links : VERDICT_LINKS);
    const whirl_model m = {.chain = c, .dim = 3, .air_drag = s.drag_si / (s.mass * rate / s.length),
                           .air_drag_quadratic = s.drag2_si / (s.mass / (s.length * s.length))};
    whirl_periodic *wp = c ? whirl_periodic_alloc_model(&m, &path) : NULL;
    double *y = wp ? malloc(whirl_periodic_state_size(wp) * sizeof *y) : NULL;
    int failed = c == NULL;
    if (!failed && wp == NULL) failed = web_library_fail(&s, "pivot");
    if (!failed && y == NULL) failed = web_state_fail(&s, "", "out of memory");
    int steps = 0;
    if (!failed && (whirl_periodic_start_vertical(wp, s.inverted, y) != GSL_SUCCESS ||
                    periodic_steps_for(wp, y, 0, &steps) != GSL_SUCCESS))
        failed = web_library_fail(&s, "shake");
    if (!failed && (double)steps * (double)c->n * (double)c->n > FLOQUET_WORK_MAX)
        failed = web_state_fail(&s, "shake", "shake: %zu links on this path need %d steps per "
                                "period, beyond what the page solves for a periodic motion "
                                "(fewer links, a smaller amplitude or frequency)", c->n, steps);
    json j = {0};
    if (!failed) {
        whirl_periodic_result r;
        const whirl_periodic_params p = {.refine = 1}; /* whirl periodic's defaults */
        if (whirl_periodic_find(wp, y, &p, &r) != GSL_SUCCESS)
            failed = web_library_fail(&s, "shake"); /* one line: no multiplier */
        else
            put_result(&j, &s, &r, c->n, whirl_periodic_dissipative(wp));
    }
    free(y);
    whirl_periodic_free(wp);
    whirl_chain_free(c);
    if (failed) {
        free(j.text);
        return web_error_answer(s.field, s.message);
    }
    return web_finish(&j);
}
