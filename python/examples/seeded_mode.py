"""A run seeded along the unstable mode inside a window of instability grows at the real part of
the mode's eigenvalue.

The 12-link chain's steady shape of mode 2 at omega = 6.3 sqrt(g/L) lies inside a window: its
linearisation in the co-rotating frame has a pair lambda = s +- i f with s > 0
(whirl.stability(..., modes=True) gives the eigenvalues and their modes). The run starts from
the exact steady shape with the links turned along that mode (Simulation.set_steady(along=...),
the largest turn 1e-10 rad) and integrates the full nonlinear equations. Its deviation from the
shape is e^{s t} times a factor periodic with the mode's period 2 pi / f; the mean of log
deviation over one period therefore grows exactly at s, which is measured between two of those
means. The window of the measurement starts at 1e4 times the initial deviation, after the
other modes the seed excites have become negligible (a start at rest in the co-rotating frame is
not a pure mode: it also excites the neutral modes, about 1% of the deviation at 100 times the
start), and ends at 1e6 times, a deviation of 1.5e-5 L, before the nonlinear terms matter.

Run from the repository's root: PYTHONPATH=python python3 python/examples/seeded_mode.py"""
import numpy as np

import whirl

LINKS, MODE, OMEGA = 12, 2, 6.3
SAMPLES = 64  # samples per period of the mode's oscillation


def measure():
    """(the eigenvalue lambda, the growth measured, the window's times, the run)."""
    st = whirl.stability(OMEGA, MODE, LINKS, linear=True, modes=True)
    k = int(np.argmax(st.eigenvalues.real))
    lam = st.eigenvalues[k]
    period = 2 * np.pi / abs(lam.imag)
    sim = whirl.Simulation(LINKS, omega=OMEGA, method="gauss2")
    sim.set_steady(MODE, along=st.angles[k], amplitude=1e-10)
    every = period / SAMPLES
    run = sim.run(t_end=80 * period, dt=every / 20, every=every, positions=False)
    # the mean of log(deviation) over the period that starts at each sample
    mean = np.convolve(np.log(run.deviation), np.ones(SAMPLES) / SAMPLES, mode="valid")
    t = run.t[:mean.size] + (SAMPLES - 1) / 2 * every
    start = np.log(run.deviation[0])
    i = int(np.argmax(mean > start + np.log(1e4)))
    j = int(np.argmax(mean > start + np.log(1e6)))
    if not 0 < i < j:
        raise RuntimeError("the run did not grow by 1e6 (eigenvalue %s)" % lam)
    growth = (mean[j] - mean[i]) / (t[j] - t[i])
    return st, lam, growth, (t[i], t[j]), run


def main():
    st, lam, growth, (t0, t1), run = measure()
    print("%d links, mode %d at omega %g: %s, index %d" % (LINKS, MODE, OMEGA, st.verdict,
                                                         st.index))
    print("unstable eigenvalue       lambda = %.10f %+.10fi" % (lam.real, lam.imag))
    print("run seeded along its mode: deviation %.3g L at t = 0, %.3g L at t = %.4g"
          % (run.deviation[0], run.deviation.max(), run.t[-1]))
    print("growth of the run (t = %.4g .. %.4g): %.10f" % (t0, t1, growth))
    print("relative difference from Re lambda: %.2e" % (growth / lam.real - 1))


if __name__ == "__main__":
    main()
