"""What a Python call adds to the C cost (make bench): whirl.shape of the 100-link chain per
call, and a 10^4-step simulation of it, against the same work done by the library without the
package (direct calls: the C cost) and by the whirl program. Times are CPU times (this process's,
or the child's for the program), medians of repeats in which the variants alternate, so that a
machine shared with other work still gives fair ratios. The CSV goes to
OUTDIR/python_overhead.csv.

usage: bench_overhead.py OUTDIR BUILD"""
import os
import resource
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, os.pardir, os.pardir))
outdir, build = sys.argv[1], os.path.abspath(sys.argv[2])
os.environ.setdefault("WHIRL_LIBRARY", os.path.join(build, "libwhirl.so"))
sys.path.insert(0, os.path.join(REPO, "python"))
import whirl  # noqa: E402
from whirl._lib import ffi, lib  # noqa: E402

def cpu():
    """CPU seconds of this process and of its finished children."""
    c = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + c.ru_utime + c.ru_stime


def medians(variants, inner, repeats):
    """Median CPU time per call of each function in variants (called inner times per repeat),
    the variants alternating within each of the repeats."""
    for f in variants:
        f()  # warm-up
    times = [[] for _ in variants]
    for _ in range(repeats):
        for k, f in enumerate(variants):
            t = cpu()
            for _ in range(inner):
                f()
            times[k].append((cpu() - t) / inner)
    return [float(np.median(x)) for x in times]


rows = []

# ---- whirl.shape at N = 100 (omega 3.5, mode 2) ----
N, OMEGA, MODE = 100, 3.5, 2
chain = whirl.Chain(N)
r, z, t = (np.empty(N + 1) for _ in range(3))
info = ffi.new("whirl_shape_info *")
rp, zp, tp = (ffi.cast("double *", ffi.from_buffer(a)) for a in (r, z, t))


def c_shape():
    lib.whirl_nlink_solve(chain._c, OMEGA, MODE, info)
    lib.whirl_nlink_positions(chain._c, OMEGA, info.tip_r, rp, zp, tp)


c, py, py_int = medians([c_shape, lambda: whirl.shape(OMEGA, MODE, links=chain),
                         lambda: whirl.shape(OMEGA, MODE, links=N)], 20, 31)
prog, = medians([lambda: subprocess.run(
    [os.path.join(build, "whirl"), "shape", "--omega", str(OMEGA), "--mode", str(MODE),
     "--links", str(N), "-o", os.devnull], check=True)], 5, 3)
rows.append(("shape_N100", c, py, py - c, (py - c) / c))
rows.append(("shape_N100_links_int", c, py_int, py_int - c, (py_int - c) / c))
print("CPU time. whirl.shape N = 100: C %.1f us, Python %.1f us (Chain given), %.1f us (links=100): "
      "overhead %.2f us = %.2f%% (%.2f us = %.2f%%); the whirl program %.0f us per run"
      % (c * 1e6, py * 1e6, py_int * 1e6, (py - c) * 1e6, 100 * (py - c) / c,
         (py_int - c) * 1e6, 100 * (py_int - c) / c, prog * 1e6))

# ---- the wrapper alone: the same at N = 2, where the C work is a few microseconds ----
small = whirl.Chain(2)
r2, z2, t2 = (np.empty(3) for _ in range(3))
rp2, zp2, tp2 = (ffi.cast("double *", ffi.from_buffer(a)) for a in (r2, z2, t2))


def c_small():
    lib.whirl_nlink_solve(small._c, OMEGA, MODE, info)
    lib.whirl_nlink_positions(small._c, OMEGA, info.tip_r, rp2, zp2, tp2)


c2, py2 = medians([c_small, lambda: whirl.shape(OMEGA, MODE, links=small)], 200, 31)
rows.append(("shape_N2", c2, py2, py2 - c2, (py2 - c2) / c2))
print("whirl.shape N = 2: C %.1f us, Python %.1f us: the wrapper's own cost %.1f us per call"
      % (c2 * 1e6, py2 * 1e6, (py2 - c2) * 1e6))

# ---- 10^4 steps of the mode-2 scene's chain (N = 100, gauss2, rotating frame) ----
STEPS, DT = 10000, 0.002
T_END = STEPS * DT
scene = os.path.join(REPO, "data", "scenes", "mode2.ini")


def program_run():
    subprocess.run([os.path.join(build, "whirl"), "simulate", scene, "-o", os.devnull,
                    "--set", "start.perturb=0", "--set", "run.stop_deviation=1",
                    "--set", "run.t_end=%g" % T_END, "--set", "output.every=%g" % T_END],
                   check=True)


def python_run():
    sim = whirl.Simulation(N, frame="rotating", omega=4.0, method="gauss2")
    sim.set_steady(2)
    sim.run(T_END, DT, every=T_END, positions=False)


def c_run():
    """The same integration by one library call (what the C program's loop does, without its
    per-step checks and output)."""
    sim = whirl.Simulation(N, frame="rotating", omega=4.0, method="gauss2")
    sim.set_steady(2)
    tp_ = ffi.new("double *", 0.0)
    y = ffi.cast("double *", ffi.from_buffer(sim._y))
    lib.whirl_integrator_advance(sim._it, tp_, y, T_END, DT, 0.0)


c, py, prog = medians([c_run, python_run, program_run], 1, 3)
rows.append(("simulate_N100_1e4_steps", c, py, py - c, (py - c) / c))
rows.append(("simulate_N100_1e4_steps_program", c, prog, prog - c, (prog - c) / c))
print("10^4 gauss2 steps, N = 100: one library call %.3f s, whirl.Simulation.run %.3f s "
      "(overhead %.1f ms = %.2f%%), the whirl program %.3f s (%.2f%%)"
      % (c, py, (py - c) * 1e3, 100 * (py - c) / c, prog, 100 * (prog - c) / c))

os.makedirs(outdir, exist_ok=True)
with open(os.path.join(outdir, "python_overhead.csv"), "w") as f:
    f.write("# medians of repeats on this machine; overhead = time - C time\n")
    f.write("case,c_seconds,seconds,overhead_seconds,overhead_fraction\n")
    for row in rows:
        f.write("%s,%.6g,%.6g,%.6g,%.6g\n" % row)
