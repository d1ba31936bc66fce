"""Steady shapes from Python against independent results: Bessel zeros, analytic pendulum
frequencies, and the command line's CSV."""
import os
import subprocess

import numpy as np
import pytest
from scipy.special import jn_zeros

import whirl


def test_critical_continuum_is_half_the_bessel_zeros():
    # omega_k = j_{0,k} / 2 for the uniform chain without a tip mass
    np.testing.assert_allclose(whirl.critical(12), jn_zeros(0, 12) / 2, rtol=1e-12, atol=0)


def test_critical_tip_mass_equals_scipy_determinant_roots():
    # with a tip mass m: the roots of the J0/Y0 determinant of the linearised problem, here
    # bracketed by scipy on a grid of 1e-3 in omega (finer than any gap between roots) and
    # refined by brentq: all 300 in order, none missed
    from scipy.optimize import brentq
    from scipy.special import j0, j1, y0, y1

    def det(w, m):
        x0, x1 = 2 * w * np.sqrt(m), 2 * w * np.sqrt(1 + m)
        return ((j1(x0) - x0 / 2 * j0(x0)) * y0(x1)
                - (y1(x0) - x0 / 2 * y0(x0)) * j0(x1))

    for m in (0.0137, 0.4821, 3.7):
        got = whirl.critical(300, tip_mass=m)
        grid = np.arange(0.5, got[-1] + 0.25, 1e-3)
        d = det(grid, m)
        i = np.nonzero(np.signbit(d[:-1]) != np.signbit(d[1:]))[0]
        assert len(i) == 300
        ref = [brentq(det, grid[j], grid[j + 1], args=(m,), xtol=1e-14, rtol=1e-15) for j in i]
        np.testing.assert_allclose(got, ref, rtol=1e-13, atol=0)


def test_critical_physical_units_scale_by_sqrt_g_over_l():
    L, g = 0.6, 9.81
    np.testing.assert_allclose(whirl.critical(5, length=L, mass=0.05, gravity=g),
                               jn_zeros(0, 5) / 2 * np.sqrt(g / L), rtol=1e-12, atol=0)


def test_critical_double_pendulum_analytic():
    # two equal masses 1/2 on links 1/2: omega^2 = (g / l) (2 -+ sqrt 2)
    w = whirl.critical(2, links=2)
    np.testing.assert_allclose(w, np.sqrt(2 * np.array([2 - np.sqrt(2), 2 + np.sqrt(2)])),
                               rtol=1e-13)
    np.testing.assert_allclose(whirl.critical(1, links=1), [1.0], rtol=1e-14)


def test_critical_nlink_converges_to_continuum_at_first_order():
    exact = jn_zeros(0, 3) / 2
    e1 = np.abs(whirl.critical(3, links=100) - exact)
    e2 = np.abs(whirl.critical(3, links=200) - exact)
    np.testing.assert_allclose(e1 / e2, 2.0, rtol=0.05)


def _read_cli(path):
    summary = {}
    with open(path) as f:
        first = f.readline()
    for item in first[1:].split():
        k, v = item.split("=")
        summary[k] = v
    with open(path) as f:
        rows = [line for line in f if not line.startswith("#")]
    assert rows[0].strip() == "s,r,z,tension"
    data = np.loadtxt(rows[1:], delimiter=",")
    return summary, data


@pytest.mark.parametrize("args,kwargs", [
    (["--omega", "3.5", "--mode", "2"], dict(omega=3.5, mode=2)),
    (["--omega", "5.2", "--mode", "3", "--links", "40"], dict(omega=5.2, mode=3, links=40)),
    # beyond 64 modes: mode 150 of 200 just above its birth (252.93), its 149 crossings
    (["--omega", "258", "--mode", "150", "--links", "200"], dict(omega=258, mode=150, links=200)),
    # mode 500 of 500 at 1.2 times its birth, whose radii underflow below mass 363
    (["--omega", "1186.557", "--mode", "500", "--links", "500"],
     dict(omega=1186.557, mode=500, links=500)),
    (["--omega", "21", "--mode", "1", "--length", "0.5", "--mass", "0.05", "--gravity", "9.81",
      "--tip-mass", "0.01", "--points", "57"],
     dict(omega=21, mode=1, length=0.5, mass=0.05, gravity=9.81, tip_mass=0.01, points=57)),
])
def test_shape_matches_the_command_line_csv(tmp_path, whirl_program, args, kwargs):
    out = tmp_path / "shape.csv"
    subprocess.run([whirl_program, "shape", *args, "-o", str(out)], check=True)
    summary, data = _read_cli(out)
    s = whirl.shape(**kwargs)
    # the same library computation printed with %.17g: equal to round-off of the unit scaling
    for name, col in (("s", 0), ("r", 1), ("z", 2), ("tension", 3)):
        np.testing.assert_allclose(getattr(s, name), data[:, col], rtol=1e-15, atol=1e-16,
                                   err_msg=name)
    for name in ("tip_r", "max_r", "top_tension", "depth"):
        assert getattr(s, name) == pytest.approx(float(summary[name]), rel=1e-15, abs=1e-16)
    nodes = [float(v) for v in summary["crossing_s"].split(";") if v]
    np.testing.assert_allclose(s.crossings, nodes, rtol=1e-15)
    assert s.mode == int(summary["mode"])
    assert s.node_count == int(summary["node_count"])


def test_shape_physics_nodes_and_tension():
    s = whirl.shape(4.9, 3)
    assert len(s.crossings) == 2 and s.r[-1] > 0 and s.z[-1] < 0
    # r changes sign at the reported nodes
    for node in s.crossings:
        i = np.searchsorted(s.s, node)
        assert s.r[i - 1] * s.r[i] <= 0
    # the vertical force balance at the pivot: T cos(angle) = weight (dimensionless: 1)
    ds = s.s[1] - s.s[0]
    dz_ds = (-3 * s.z[0] + 4 * s.z[1] - s.z[2]) / (2 * ds)  # second order, error O(ds^2)
    assert s.top_tension * (-dz_ds) == pytest.approx(1.0, rel=1e-4)
    assert s.critical == pytest.approx(jn_zeros(0, 3)[-1] / 2, rel=1e-12)


def test_shape_counts_the_underflowed_tail():
    # mode 500 of 500 at 1.2 times its birth: the radii below the last normal double (from mass
    # 364 on) are 0 or subnormal; their crossings come from the linearised balance, all 499 listed
    s = whirl.shape(1186.557, 500, links=500)
    last = np.nonzero(np.abs(s.r) >= np.finfo(float).tiny)[0][-1]
    assert s.r[-1] == 0 and 300 < last < 450
    assert len(s.crossings) == 499 and np.all(np.diff(s.crossings) > 0)
    assert 0 < s.crossings[0] and s.crossings[-1] < 1 and np.sum(s.crossings > s.s[last]) > 100


def test_sweep_agrees_with_single_shapes():
    omega = np.linspace(1.0, 6.0, 26)
    b = whirl.sweep([1, 2], omega, links=30)
    assert set(b) == {1, 2}
    crit = whirl.critical(2, links=30)
    for k in (1, 2):
        np.testing.assert_array_equal(b[k]["omega"], omega[omega > crit[k - 1]])
        for row in b[k][::5]:
            s = whirl.shape(row["omega"], k, links=30)
            assert row["tip_r"] == pytest.approx(s.tip_r, rel=1e-9)
            assert row["top_tension"] == pytest.approx(s.top_tension, rel=1e-9)


def test_sharp_turn_against_the_mpmath_continuation():
    # Mode 8 of this 9-link chain (lengths and masses over six decades) turns by a right angle
    # within 4e-9 of arclength just below the birth of mode 9 (omega = 1061.985); a path that
    # took the turn for a branch point ended 1.55 rad away. The library's shape at ten times the
    # birth against tests/tools/branch_mp.py, an independent pseudo-arclength continuation in mpmath
    # (30 digits here, turns of at most 0.02 rad per step): every node to 1e-12 of the largest
    # radius, or the mirror image. The continuation's CROSS line is kept in
    # data/sharp_turn_mode8.txt (15 s of processor time to compute); the file's first line is the
    # command that computes it, checked here to name this chain. From the repository:
    #   c=$(head -n 1 python/tests/data/sharp_turn_mode8.txt | cut -c3-)
    #   { echo "# $c"; /usr/bin/python3 $c | grep -E '^(CROSS|# steps)'; } >new.txt
    lengths = [0.070162066030373019, 111.81954152718886, 2.3222961544612386, 23.062821237957106,
               330.49317381274932, 0.14277270054558061, 0.0037092662097338424,
               22.915984884650165, 0.27251719136522617]
    masses = [0.0068675647299397914, 1.7013048900246917, 0.07636857239449947, 7.896589309214459,
              0.32922785172356628, 0.0724052084410058, 183.34632586580688, 111.71786576971722,
              0.0083645241425102553]
    command = ("tests/tools/branch_mp.py --length %s --mass %s 8 --dps 30"
               % (",".join(map(repr, lengths)), ",".join(map(repr, masses))))
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data",
                           "sharp_turn_mode8.txt")) as f:
        out = f.read()
    assert out.splitlines()[0] == "# " + command, "the reference is another chain's"
    cross = [line.split() for line in out.splitlines() if line.startswith("CROSS")]
    assert len(cross) == 1, out[-500:]
    omega = float(cross[0][1])
    theta = np.array([float(v) for v in cross[0][2:2 + len(lengths)]])
    r_ref = np.concatenate(([0.0], np.cumsum(lengths * np.sin(theta))))
    z_ref = np.concatenate(([0.0], -np.cumsum(lengths * np.cos(theta))))
    s = whirl.shape(omega, 8, links=whirl.Chain(lengths=lengths, masses=masses))
    scale = np.max(np.abs(s.r))
    err = min(np.max(np.abs(s.r - r_ref)), np.max(np.abs(s.r + r_ref)))
    assert err < 1e-12 * scale
    assert np.max(np.abs(s.z - z_ref)) < 1e-12 * np.max(np.abs(s.z))
