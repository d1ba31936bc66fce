"""Continuum steady shapes: whirl against scipy, time per shape at the accuracy each reaches.

Usage: /usr/bin/python3 tests/bench/bench_scipy.py DIR WHIRL [quick]
Writes DIR/scipy_shapes.csv and appends the headline ratios to DIR/headline.csv.

The shapes: the continuous uniform chain (length 1, mass 1, g = 1, no tip mass) spun at omega,
modes 1, 2, 3 at the rates omega = 5 .. 8 (61 rates, quick 21). With sigma the arclength from the
free end, r the distance from the axis and q the mean horizontal load per unit mass below sigma
(src/continuum.c derives it):
    dr/dsigma = -q / sqrt(1 + q^2),  dz/dsigma = 1 / sqrt(1 + q^2),
    dq/dsigma = (omega^2 r - q) / sigma,   q(0) = omega^2 r(0),  r(1) = 0 (pivot on the axis);
tension at the pivot T(1) = sqrt(1 + q(1)^2), tip radius a = r(0).
 - whirl: `whirl sweep --modes 1,2,3` over the same rates (continuation, its shooting with GSL
   rk8pd at 1e-13), one thread (OMP_NUM_THREADS=1): the time per shape is that of the sweep
   over all rates less that of the sweep over the first rate alone (program start, first
   shapes), divided by the shapes after the first (medians of 7);
 - scipy shooting: solve_ivp (DOP853, rtol = atol = 1e-12; a lower tolerance is tried too) from
   sigma0 = 1e-7 with the series r = a + r1 sigma, q = omega^2 a + omega^2 r1 sigma / 2,
   r1 = -q0 / sqrt(1 + q0^2) (error O(sigma0^2)), brentq (xtol 1e-14) on a for r(1; a) = 0,
   bracketed by continuation: the previous rate's a widened by 2 % steps until r(1) changes
   sign (the first rate of each mode from a scan of a over 100 points in (0, 1] for the root
   with mode - 1 axis crossings; not timed: the time per shape is the continuation steps');
 - scipy solve_bvp (tol 1e-8 on the residual, else 1e-6 if it fails: at 1e-10 it exceeds its
   node limit; at most 100000 nodes) on (r, q, z) with the
   singular term S y / sigma (S = [[0,0,0],[omega^2,-1,0],[0,0,0]]), started from the shooting
   solution of the previous rate (continuation; the first rate from that rate's shooting
   solution on 50 nodes).
Models checked identical first: the critical rates j_{0,k}/2 (scipy.special.jn_zeros) against
`whirl sweep` finding no mode k below them and, per shape, tip radius and top tension of the
tight shooting against whirl's (relative difference reported; it must be below 1e-9).
Accuracy of a method: max over the shapes of the relative error of tip_r and top_tension
against whirl's (whirl's own accuracy, about 1e-13, is checked by the tight shooting).
Ratio: scipy seconds per shape / whirl seconds per shape, both over the continuation steps."""
import math
import os
import subprocess
import sys
import time

import numpy as np
import scipy
from scipy.integrate import solve_bvp, solve_ivp
from scipy.optimize import brentq
from scipy.special import jn_zeros

SIGMA0 = 1e-7


def shot(a, omega, rtol, dense=False):
    w2 = omega * omega
    q0 = w2 * a
    r1 = -q0 / math.sqrt(1 + q0 * q0)

    def f(s, y):
        r, q, z = y
        root = math.sqrt(1 + q * q)
        return (-q / root, (w2 * r - q) / s, 1 / root)

    y0 = (a + r1 * SIGMA0, q0 + w2 * r1 * SIGMA0 / 2, SIGMA0)
    sol = solve_ivp(f, (SIGMA0, 1.0), y0, method="DOP853", rtol=rtol, atol=rtol,
                    dense_output=dense)
    return sol


def residual(a, omega, rtol):
    return shot(a, omega, rtol).y[0, -1]


def crossings(a, omega, rtol):
    sol = shot(a, omega, rtol, dense=True)
    r = sol.sol(np.linspace(SIGMA0, 1 - 1e-9, 4000))[0]
    return int(np.sum(np.sign(r[1:]) != np.sign(r[:-1])))


def shoot(omega, mode, a_prev, rtol):
    """Tip radius of mode `mode` at omega; a_prev from continuation or None."""
    f = lambda a: residual(a, omega, rtol)
    if a_prev is None:
        grid = np.linspace(1e-2, 1.0, 100)
        vals = [f(a) for a in grid]
        for lo, hi, flo, fhi in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]):
            if flo * fhi < 0:
                a = brentq(f, lo, hi, xtol=1e-14, rtol=1e-15)
                if crossings(a, omega, rtol) == mode - 1:
                    return a
        raise RuntimeError("no mode %d at omega %g" % (mode, omega))
    lo, hi = a_prev, a_prev
    flo = fhi = f(a_prev)
    for _ in range(200):
        lo, hi = lo * 0.98, min(1.0, hi * 1.02)
        flo, fhi = f(lo), f(hi)
        if flo * fhi < 0:
            break
    else:
        raise RuntimeError("bracket lost at omega %g" % omega)
    # the narrowest bracket: from the side that changed sign next to a_prev
    mid = f(a_prev)
    if mid * flo < 0:
        return brentq(f, lo, a_prev, xtol=1e-14, rtol=1e-15)
    return brentq(f, a_prev, hi, xtol=1e-14, rtol=1e-15)


def top_tension(a, omega, rtol):
    q = shot(a, omega, rtol).y[1, -1]
    return math.sqrt(1 + q * q)


def run_shooting(rates, modes, rtol):
    """Shapes by shooting; seconds per shape over the continuation steps only (the first rate
    of each mode, found by a scan, is not timed: that favours scipy)."""
    out = {}
    secs, timed = 0.0, 0
    for k in modes:
        a = None
        for j, w in enumerate(rates):
            t0 = time.perf_counter()
            a = shoot(w, k, a, rtol)
            out[(round(w, 9), k)] = (a, top_tension(a, w, rtol))
            if j > 0:
                secs += time.perf_counter() - t0
                timed += 1
    return out, secs / timed


def run_bvp(rates, modes, start, tol):
    """Shapes by solve_bvp; seconds per shape over the continuation steps (as run_shooting)."""
    out = {}
    secs, timed = 0.0, 0
    for k in modes:
        guess = None
        for j, w in enumerate(rates):
            t0 = time.perf_counter()
            w2 = w * w
            S = np.array([[0, 0, 0], [w2, -1, 0], [0, 0, 0]], dtype=float)

            def f_reg(s, y):  # the non-singular part: the singular one is S y / s
                root = np.sqrt(1 + y[1] ** 2)
                return np.vstack((-y[1] / root, np.zeros_like(s), 1 / root))

            def bc(ya, yb):
                return np.array([ya[1] - w2 * ya[0], yb[0], ya[2]])

            if guess is None:
                a = start[(round(w, 9), k)][0]
                sol = shot(a, w, 1e-12, dense=True)
                x = np.linspace(0, 1, 50)
                y = sol.sol(np.maximum(x, SIGMA0))
                y[2] -= y[2][0]
            else:
                x, y = guess
            res = solve_bvp(f_reg, bc, x, y, S=S, tol=tol, max_nodes=100000)
            if not res.success:
                raise RuntimeError("solve_bvp failed at omega %g mode %d: %s"
                                   % (w, k, res.message))
            guess = (res.x, res.y)
            out[(round(w, 9), k)] = (res.y[0, 0], math.sqrt(1 + res.y[1, -1] ** 2))
            if j > 0:
                secs += time.perf_counter() - t0
                timed += 1
    return out, secs / timed


def run_whirl(whirl, rates, modes, path):
    cmd = [whirl, "sweep", "--modes", ",".join(map(str, modes)), "--omega-min", repr(rates[0]),
           "--omega-max", repr(rates[-1]), "--omega-count", str(len(rates)), "-o", path]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, env=env)
    secs = time.perf_counter() - t0
    out = {}
    with open(path) as fp:
        for line in fp:
            if line.startswith("#") or line.startswith("omega"):
                continue
            w, k, tip, _, top = line.split(",")[:5]
            out[(round(float(w), 9), int(k))] = (float(tip), float(top))
    return out, secs


def worst(res, ref):
    e = 0.0
    for key, (a, t) in res.items():
        ra, rt = ref[key]
        e = max(e, abs(a / ra - 1), abs(t / rt - 1))
    return e


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: bench_scipy.py DIR WHIRL [quick]")
    out_dir, whirl = sys.argv[1], sys.argv[2]
    quick = len(sys.argv) > 3 and sys.argv[3] == "quick"
    count = 21 if quick else 61
    rates = list(np.linspace(5.0, 8.0, count))
    modes = (1, 2, 3)
    nshapes = count * len(modes)
    print("scipy %s, numpy %s; modes 1-3 at %d rates omega = 5 .. 8 (%d shapes)"
          % (scipy.__version__, np.__version__, count, nshapes))
    # the critical rates: whirl sweep finds mode k from j_{0,k}/2 on (a rate just below has none)
    tmp = os.path.join(out_dir, "scipy_whirl_sweep.csv")
    jz = jn_zeros(0, 3) / 2
    below, _ = run_whirl(whirl, [float(jz[2]) * (1 - 1e-6)], modes, tmp)
    above, _ = run_whirl(whirl, [float(jz[2]) * (1 + 1e-3)], modes, tmp)
    crit_ok = not any(k == 3 for (_, k) in below) and any(k == 3 for (_, k) in above)
    print("critical rate of mode 3 j_{0,3}/2 = %.12g: whirl has no mode 3 just below it and one "
          "just above: %s" % (jz[2], "yes" if crit_ok else "NO"))
    # whirl's marginal time per shape: the sweep over all rates less the sweep over the first
    # rate alone (program start, the first shape of each mode), medians of 3 each
    times, first = [], []
    for _ in range(7):
        ref, secs = run_whirl(whirl, rates, modes, tmp)
        times.append(secs)
        first.append(run_whirl(whirl, rates[:1], modes, tmp)[1])
    t_whirl = (sorted(times)[3] - sorted(first)[3]) / (nshapes - len(modes))
    print("whirl sweep: %.3g s for the %d shapes, %.3g s for the first rate alone"
          % (sorted(times)[3], nshapes, sorted(first)[3]))
    if len(ref) != nshapes or not t_whirl > 0:
        sys.exit("bench_scipy: whirl sweep gave %d shapes, expected %d" % (len(ref), nshapes))
    tight, t_tight = run_shooting(rates, modes, 1e-12)  # seconds per shape
    d_tight = worst(tight, ref)
    print("models: tight scipy shooting (rtol 1e-12) against whirl: largest relative difference "
          "of tip_r and top tension %.2g" % d_tight)
    if d_tight > 1e-9 or not crit_ok:
        sys.exit("bench_scipy: scipy's model and whirl's differ")
    rows = [("whirl sweep", t_whirl, 0.0)]
    rows.append(("scipy shooting rtol 1e-12", t_tight, d_tight))
    loose, t_loose = run_shooting(rates, modes, 1e-9)
    rows.append(("scipy shooting rtol 1e-9", t_loose, worst(loose, ref)))
    bvp_row = ("scipy solve_bvp", float("nan"), float("nan"))
    for tol in (1e-8, 1e-6):  # the tightest tolerance it completes
        try:
            bvp, t_bvp = run_bvp(rates, modes, tight, tol)
            bvp_row = ("scipy solve_bvp tol %g" % tol, t_bvp, worst(bvp, ref))
            break
        except RuntimeError as e:
            print("solve_bvp tol %g: %s" % (tol, e))
    rows.append(bvp_row)
    with open(os.path.join(out_dir, "scipy_shapes.csv"), "w") as fp:
        fp.write("method,seconds_per_shape,max_rel_error_vs_whirl,ratio_to_whirl\n")
        for name, t, e in rows:
            fp.write("%s,%.6g,%.3g,%.6g\n" % (name, t, e, t / t_whirl))
            print("  %-28s %10.3g s per shape  error %8.2g  ratio %8.3g"
                  % (name, t, e, t / t_whirl))
    # at equal accuracy: scipy's tightest shooting (its error is still above whirl's)
    best = rows[1]
    with open(os.path.join(out_dir, "headline.csv"), "a") as fp:
        ratio = best[1] / t_whirl
        fp.write("scipy_shooting,scipy shooting (%s; error %.2g) / whirl sweep per shape,%.3g,"
                 ">= 100,%s\n" % (best[0], best[2], ratio, "met" if ratio >= 100 else "not met"))
        loose = rows[2]
        fp.write("scipy_shooting_loose,scipy shooting (%s; error %.2g) / whirl sweep per shape,"
                 "%.3g,,\n" % (loose[0], loose[2], loose[1] / t_whirl))
        fp.write("shapes_per_second,whirl sweep continuum shapes per second (one thread),%.3g,,\n"
                 % (1 / t_whirl))
        b = rows[-1]
        if b[1] == b[1]:
            fp.write("scipy_bvp,%s (error %.2g) / whirl sweep per shape,%.3g,,\n"
                     % (b[0], b[2], b[1] / t_whirl))
        else:
            fp.write("scipy_bvp,scipy solve_bvp / whirl sweep per shape,,,failed at tol 1e-8 "
                     "and 1e-6\n")


if __name__ == "__main__":
    main()
