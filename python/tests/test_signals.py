"""Signals during every long call, each in a child interpreter as a user's script would run it:
Ctrl-C (SIGINT) raises KeyboardInterrupt naming the call, soon after the signal; SIGTERM keeps
its default meaning and ends the process (killed by SIGTERM, not an exception a notebook's
``except KeyboardInterrupt`` would swallow). The child sets Python's own dispositions, as an
interactive session has them, also where the suite runs with SIGINT ignored.

The signal comes 0.4 s of the child's processor time into the call. WHIRL_SIGNAL_REPORT=FILE
appends one line per run: call, signal, seconds from the signal to the exit."""
import os
import signal
import subprocess
import sys
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))

# Each takes minutes (or more) uninterrupted, on one core.
CALLS = {
    "shape": "whirl.shape(9.5, 3, links=10**6)",
    "sweep": "whirl.sweep([1, 2, 3], np.linspace(1, 60, 4000), links=20000)",
    "equilibria": "whirl.equilibria(60.0, 40)",
    "stability": "whirl.stability(3.0, 1, 60, periods=1e5)",
    "stability_map": "whirl.stability_map(np.linspace(2, 10, 2000), 1, 150)",
    "stability_windows": "whirl.stability_windows(1, 300, 1, 60)",
    "fit": "whirl.fit(*(lambda s: (s.r, s.z))(whirl.shape(7, 3, points=400)), links=2000)",
    "spin_up": "whirl.spin_up(4.0, 0.05, 200, air_drag=0.05, t_max=2e4)",
    "Simulation.run": "sim.run(1e3, 1e-4, every=1e3, positions=False)",
    "run_scene": "whirl.run_scene(scene)",
}

CHILD = r"""
import os, signal, sys
import numpy as np
import whirl
signal.signal(signal.SIGINT, signal.default_int_handler)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
sim = whirl.Simulation(400, omega=3.0, method="rk4")
sim.set_steady(2)
scene = sys.argv[1]
print("ready", flush=True)
try:
    %s
except KeyboardInterrupt as e:
    print("KeyboardInterrupt:", e, flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


def _cpu(pid):
    """Processor seconds of the process (user and system, /proc/PID/stat)."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _run(tmp_path, name, sig):
    scene = tmp_path / "long.ini"
    scene.write_text("[chain]\ndim = 3\nlinks = 100\n[start]\nomega = 3\nmode = 2\n"
                     "[run]\ndt = 0.001\nt_end = 50000\n[output]\nevery = 1000\n")
    env = dict(os.environ, PYTHONPATH=os.path.join(HERE, os.pardir))
    p = subprocess.Popen([sys.executable, "-c", CHILD % CALLS[name], str(scene)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    assert p.stdout.readline().strip() == "ready"
    # inside the call: 0.4 s of the child's processor time after "ready", whose work before the
    # library is entered takes milliseconds, also under the sanitizers (a fixed wait on a loaded
    # machine could fall before the call starts)
    start = _cpu(p.pid)
    while _cpu(p.pid) < start + 0.4 and p.poll() is None:
        time.sleep(0.02)
    assert p.poll() is None, p.communicate()
    p.send_signal(sig)
    start = time.monotonic()
    try:
        out, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        pytest.fail("%s: no exit within 60 s of %s" % (name, signal.Signals(sig).name))
    took = time.monotonic() - start
    path = os.environ.get("WHIRL_SIGNAL_REPORT")
    if path:
        with open(path, "a") as f:
            f.write("%s %s %.3f\n" % (name, signal.Signals(sig).name, took))
    return p.returncode, out, err, took


@pytest.mark.parametrize("name", sorted(CALLS))
def test_ctrl_c_interrupts_naming_the_call(tmp_path, name):
    rc, out, err, took = _run(tmp_path, name, signal.SIGINT)
    assert rc == 3, (out, err)
    assert ("KeyboardInterrupt: whirl: %s " % name) in out, out
    assert "interrupted" in out
    assert took < 10, took


@pytest.mark.parametrize("name", sorted(CALLS))
def test_sigterm_terminates(tmp_path, name):
    rc, out, err, took = _run(tmp_path, name, signal.SIGTERM)
    assert rc == -signal.SIGTERM, (rc, out, err)
    assert "KeyboardInterrupt" not in out
    assert took < 10, took
