"""The example scripts of python/examples/ run as a user runs them, and say what their
docstrings claim."""
import os
import re
import subprocess
import sys

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "examples")
PACKAGE = os.path.join(EXAMPLES, os.pardir)


def _run(name):
    env = dict(os.environ, PYTHONPATH=os.path.abspath(PACKAGE))
    return subprocess.run([sys.executable, os.path.join(EXAMPLES, name)], env=env, check=True,
                          capture_output=True, text=True).stdout


def test_seeded_mode_grows_at_the_eigenvalues_real_part():
    out = _run("seeded_mode.py")
    lam = float(re.search(r"lambda = (\S+) ", out).group(1))
    growth = float(re.search(r"growth of the run .*: (\S+)", out).group(1))
    assert "unstable" in out and lam > 0.1
    # the run's growth against the linearisation's eigenvalue, two independent computations
    # (a nonlinear integration and an eigen-solve): 5.7e-8 measured
    assert abs(growth / lam - 1) < 1e-6, out
