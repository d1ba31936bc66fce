"""Results and inputs as a physicist uses them: every result equals its copy and differs from
another result with ``==`` (no "truth value of an array is ambiguous"), works in ``in`` and in
pytest's ``assert a == b``; every object has a short repr, the Simulation included; unit texts
("4Hz", "60cm", "50g", "2ms") and 0-d arrays are taken where the command line takes a number;
fit takes a Chain; a mode that never exists in a sweep or a map is said, not an empty answer;
Ctrl-C anywhere inside stability names the call."""
import copy
import os
import pickle
import signal
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import whirl

from test_results import _results

HERE = os.path.dirname(os.path.abspath(__file__))


def test_results_compare_by_value(tmp_path):
    names = []
    for name, result in _results(tmp_path):
        if isinstance(result, (whirl.Units, whirl.Chain, dict, np.ndarray, tuple, Exception)):
            continue
        twin = copy.deepcopy(result)
        assert twin == result and not (twin != result), name
        assert result == pickle.loads(pickle.dumps(result)), name
        assert result in [None, 3, twin], name
        assert result != object() and result != 0, name
        with pytest.raises(TypeError):
            hash(result)  # mutable: no hash, as before
        names.append(name)
    assert len(names) == 14, names


def test_results_that_differ_are_unequal():
    a, b = whirl.shape(15, 2), whirl.shape(15, 2)
    assert a == b
    b.r[3] += 1e-15
    assert a != b
    s = whirl.stability(12, 2, 6, linear=True)
    t = copy.deepcopy(s)
    t.eigenvalues = t.eigenvalues[:-1]  # a different shape of array
    assert s != t and s != whirl.stability(12.5, 2, 6, linear=True)
    assert whirl.shape(15, 2) != whirl.shape(15, 2, length=1.0)  # other units


def test_every_object_has_a_short_repr(tmp_path):
    for name, result in _results(tmp_path):
        if isinstance(result, (dict, np.ndarray, tuple)):
            continue  # numpy's and Python's own
        text = repr(result)
        assert len(text) < 400 and "\n" not in text and " object at 0x" not in text, (name, text)
    sim = whirl.Simulation(6, omega="3Hz", length="60cm", mass=0.05, air_drag=0.1)
    assert repr(sim) == ("Simulation(Chain(n=6, length=1, mass=1, gravity=1), dim=3, "
                         "frame='inertial', omega=18.8496, air_drag=0.1, method='gauss2', "
                         "no start state, Units(length=0.6, mass=0.05, gravity=9.80665))")
    sim.set_hanging()
    assert ", t=0, " in repr(sim)
    empty = whirl.Trajectory(np.empty(0), None, *(np.empty(0),) * 5, stats={"steps": 0})
    assert repr(empty) == "Trajectory(0 rows, 0 steps)"


def test_unit_texts_and_0d_arrays_are_numbers():
    si = dict(length=0.6, mass=0.05)
    ref = whirl.shape(8 * np.pi, 2, **si)
    assert whirl.shape("4Hz", 2, length="60cm", mass="50g") == ref
    assert whirl.shape("4 hz", 2, length="600 mm", mass=np.array(0.05)) == ref
    assert abs(whirl.shape("240rpm", 2, **si).tip_r - ref.tip_r) < 1e-15  # 240 * 2 pi / 60
    assert whirl.shape(np.array(8 * np.pi), 2, **si) == ref
    np.testing.assert_array_equal(whirl.sweep(2, np.array(15.0))[2]["omega"], [15.0])
    assert "drive_radius=0.01," in repr(whirl.Simulation(4, drive_radius="1cm", **si))
    sim = whirl.Simulation(4, omega="2Hz", **si)
    assert sim.omega == 4 * np.pi
    sim.set_hanging()
    tr = sim.run("20ms", "1ms", every="10ms")
    np.testing.assert_allclose(tr.t, [0, 0.01, 0.02], rtol=0, atol=1e-15)
    assert whirl.stability("4Hz", 2, 10, linear=True, **si) == \
        whirl.stability(8 * np.pi, 2, 10, linear=True, **si)
    # as on the command line: a unit needs the chain's length; the wrong kind is refused
    with pytest.raises(ValueError, match="omega='4Hz' needs the chain's length"):
        whirl.shape("4Hz", 2)
    with pytest.raises(ValueError, match=r"omega must be a number, optionally with a unit "
                                         r"\(rad/s, Hz or rpm\), got '4cm'"):
        whirl.shape("4cm", 2, **si)
    with pytest.raises(ValueError, match="length must be a number"):
        whirl.Units(length="60 Hz")
    with pytest.raises(TypeError, match="perturb must be a real number"):
        whirl.Simulation(4).set_steady(1, perturb="1e-3")  # a pure number keeps its type
    with pytest.raises(ValueError, match="one-dimensional"):
        whirl.sweep(2, np.ones((2, 2)))


def test_fit_takes_a_chain():
    s = whirl.shape(7, 2, links=20, tip_mass=0.1)
    a = whirl.fit(s.r, s.z, links=20, tip_mass=0.1)
    assert whirl.fit(s.r, s.z, links=whirl.Chain(20, tip_mass=0.1)) == a
    n = 20
    by_hand = whirl.Chain(lengths=[1 / n] * n, masses=[1 / n] * (n - 1) + [1 / n + 0.1])
    assert abs(whirl.fit(s.r, s.z, links=by_hand).omega - a.omega) < 1e-9
    with pytest.raises(ValueError, match="uniform N-link chain"):
        whirl.fit(s.r, s.z, links=whirl.Chain(lengths=[0.5, 0.5], masses=[1.0, 2.0]))
    with pytest.raises(ValueError, match="tip_mass applies to a link count"):
        whirl.fit(s.r, s.z, links=whirl.Chain(20), tip_mass=0.1)


def test_a_mode_that_never_exists_is_said():
    grid = np.linspace(1, 2, 5)
    with pytest.raises(whirl.InvalidInput, match="no mode exists on the grid 1 sqrt\\(g/L\\) "
                                                 "to 2 sqrt\\(g/L\\): mode 3 exists only above "
                                                 "4.3268"):
        whirl.sweep(3, grid)
    with pytest.warns(whirl.EmptyBranchWarning, match="no rows for mode 3: mode 3 exists only "
                                                      "above 4.3268"):
        out = whirl.sweep([1, 3], grid)
    assert out[1].size == 4 and out[3].size == 0  # mode 1 is born at 1.2
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        whirl.sweep([1, 2], np.linspace(1, 3, 5))  # mode 2 exists on part of it: no warning
    with pytest.raises(whirl.InvalidInput, match="stability_map: no rate of the grid 1 rad/s "
                                                 "to 2 rad/s has a shape of mode 3: mode 3 "
                                                 "exists only above"):
        whirl.stability_map(grid, 3, 10, length=0.6)


CHILD = textwrap.dedent("""
    import os, signal, sys
    import whirl
    stability = sys.modules["whirl.stability"]
    signal.signal(signal.SIGINT, signal.default_int_handler)
    eigenvalues = stability._eigenvalues

    def ctrl_c_between(w):  # Ctrl-C in the Python code between the linearisation and the run
        os.kill(os.getpid(), signal.SIGINT)
        return eigenvalues(w)

    stability._eigenvalues = ctrl_c_between
    try:
        whirl.stability(4.0, 2, 20, periods=50)
        print("finished")
    except KeyboardInterrupt as e:
        print("KeyboardInterrupt(%r)" % str(e))
""")


def test_ctrl_c_between_the_calls_of_stability_names_it(tmp_path):
    script = tmp_path / "child.py"
    script.write_text(CHILD)
    env = dict(os.environ, PYTHONPATH=os.path.join(HERE, os.pardir))
    p = subprocess.run([sys.executable, str(script)], env=env, capture_output=True, text=True,
                       timeout=120)
    assert p.stdout.strip() == "KeyboardInterrupt('whirl: stability interrupted')", \
        p.stdout + p.stderr
