"""Results a scientist can keep and share: every result type survives pickle and deepcopy
field by field (N-link ones by their chain's lengths and masses), a Simulation restored from a
pickle continues as the original does, parallel scans with processes and threads give the
serial answers bit for bit, the units rule is the command line's, and counts beyond memory are
refused before they reach the library."""
import concurrent.futures
import copy
import dataclasses
import gc
import multiprocessing
import pickle

import numpy as np
import pytest

import whirl


def _same(a, b, path="result"):
    assert type(a) is type(b), path
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, path
        if a.dtype.names:
            for name in a.dtype.names:
                _same(a[name], b[name], "%s[%s]" % (path, name))
        else:
            assert np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"), path
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            _same(getattr(a, f.name), getattr(b, f.name), path + "." + f.name)
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            _same(a[k], b[k], "%s[%r]" % (path, k))
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, "%s[%d]" % (path, i))
    elif isinstance(a, float) and np.isnan(a):
        assert np.isnan(b), path
    elif isinstance(a, whirl.SceneRun):
        _same(a.__dict__, b.__dict__, path)
    elif isinstance(a, whirl.Error):
        assert (a.status, a.message, str(a)) == (b.status, b.message, str(b)), path
    else:
        assert a == b, path


def _results(tmp_path):
    SI = dict(length=0.6, mass=0.05)
    yield "Units", whirl.Units(**SI)
    yield "Chain", whirl.Chain(lengths=[0.1, 0.3, 0.6], masses=[1.0, 2.0, 0.5], gravity=2.0)
    yield "Shape", whirl.shape(15, 2, points=31, **SI)
    yield "Shape (N-link)", whirl.shape(15, 2, links=7, **SI)
    yield "sweep", whirl.sweep([1, 2], [8.0, 12.0], links=6, **SI)
    yield "equilibria", whirl.equilibria(20, 6, **SI)
    yield "StabilityResult", whirl.stability(12, 2, 6, periods=5, **SI)
    yield "stability_map", whirl.stability_map([8.0, 12.0], 2, 6, **SI)
    yield "stability_windows", whirl.stability_windows(2, 6, 5, 40, **SI)
    yield "DrivenShape", whirl.driven(12, 2, 0.003, points=9, **SI)
    yield "DrivenBranch", whirl.driven_branch(10, 12, 0.003, mode=2, links=6, **SI)
    yield "SpinUp", whirl.spin_up(12, 0.02, 5, t_max=20, every=1.0, **SI)
    shape = whirl.shape(15, 2, points=30, **SI)
    yield "FitResult", whirl.fit(shape.r, shape.z, **SI)
    sim = whirl.Simulation(6, omega=25, **SI)
    sim.set_steady(2, perturb=1e-3)
    yield "Trajectory", sim.run(0.05, 1e-3, every=0.01)
    scene = tmp_path / "s.ini"
    scene.write_text("[chain]\ndim = 3\nlinks = 5\n[start]\nomega = 3\nmode = 2\n"
                     "[run]\ndt = 0.01\nt_end = 0.1\n[output]\nevery = 0.05\n")
    yield "SceneRun", whirl.run_scene(scene, trace=True)
    yield "PeriodicResult", whirl.periodic("vertical:1cm", 9, links=2, dim=2, **SI)
    yield "PeriodicBranch", whirl.periodic_path("vertical:0.01", 1.8, dim=2, amp_max=0.1,
                                                up=True, max_points=3)
    yield "Chart", whirl.chart_vertical(1.6, 2.2, 0.3, columns=3, rows=10, **SI)
    yield "EllipseChart", whirl.chart_ellipse(3.95, 4.0, 0.05, links=2, mode=2, side=-1,
                                              columns=2)
    out = tmp_path / "shape.csv"
    import subprocess
    import os
    program = os.path.join(os.environ.get("WHIRL_BUILD", "build"), "whirl")
    subprocess.run([program, "shape", "--omega", "15", "--mode", "2", "--length", "0.6", "-o",
                    str(out)], check=True)
    yield "Table", whirl.read_csv(out)
    try:
        whirl.shape(2.0, 3)
    except whirl.InvalidInput as e:
        yield "InvalidInput", e


def test_every_result_pickles_and_deep_copies(tmp_path):
    names = []
    for name, result in _results(tmp_path):
        _same(pickle.loads(pickle.dumps(result)), result, name)
        _same(copy.deepcopy(result), result, name)
        names.append(name)
    assert len(names) == 21, names


def test_a_restored_simulation_continues_as_the_original():
    # rk4 keeps no state between steps: the same steps bit for bit (an implicit method starts
    # its iteration from the last step's stages, which a restored one has not: round-off apart)
    sim = whirl.Simulation(8, omega=3.0, method="rk4")
    sim.set_steady(2, perturb=1e-3)
    sim.run(0.5, 1e-3)
    twin = pickle.loads(pickle.dumps(sim))
    assert twin.chain == sim.chain and twin.t == sim.t
    a, b = sim.run(1.0, 1e-3, every=0.25), twin.run(1.0, 1e-3, every=0.25)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.deviation, b.deviation)


def test_the_chain_of_a_simulation_cannot_be_replaced():
    # the model refers to the chain: a reassigned one would be freed under it
    sim = whirl.Simulation(50, omega=3.0)
    with pytest.raises(AttributeError):
        sim.chain = whirl.Chain(3)
    gc.collect()
    sim.set_steady(1)
    assert sim.run(0.01, 1e-3).constraint.max() < 1e-9


def _shape_tip(omega):
    return whirl.shape(omega, 2, links=40, length=0.6, mass=0.05).tip_r


def test_parallel_scans_match_the_serial_one():
    rates = np.linspace(12.0, 30.0, 12)
    serial = [_shape_tip(w) for w in rates]
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=ctx) as pool:
        assert list(pool.map(_shape_tip, rates)) == serial
        shapes = list(pool.map(whirl.shape, rates, [2] * 12, [40] * 12))
    assert [s.tip_r for s in shapes] == [whirl.shape(w, 2, links=40).tip_r for w in rates]
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        assert list(pool.map(_shape_tip, rates)) == serial


def test_units_follow_the_command_line_rule():
    assert whirl.Units() == whirl.Units(None, None, None)
    assert not whirl.Units().physical and whirl.Units().gravity == 1.0
    assert whirl.Units(length=0.6).gravity == whirl.STANDARD_GRAVITY == 9.80665
    assert whirl.Units(mass=0.05).gravity == 9.80665
    assert whirl.Units(gravity=1.62).length == 1.0
    u = whirl.Units(length=0.6, mass=0.05)
    np.testing.assert_array_equal(whirl.critical(3, units=u), whirl.critical(3, length=0.6,
                                                                             mass=0.05))
    np.testing.assert_allclose(whirl.critical(3, length=0.6),
                               whirl.critical(3) * np.sqrt(9.80665 / 0.6), rtol=1e-15)
    with pytest.raises(TypeError, match="either units"):
        whirl.critical(3, length=0.6, units=u)
    for bad in (dict(length=1e-300, gravity=1e300), dict(mass=1e308)):
        with pytest.raises(ValueError, match="must be in"):
            whirl.critical(3, **bad)


@pytest.mark.parametrize("call,match", [
    (lambda: whirl.Chain(2**61), "links must be <= .* memory"),
    (lambda: whirl.critical(3, links=2**61), "links must be <= .* memory"),
    (lambda: whirl.Chain(10**9), "links must be <= .* memory"),
    (lambda: whirl.shape(3.0, 1, points=10**8), "points must be <= 10000000"),
    (lambda: whirl.stability(3.0, 1, 10**6), "links must be <= .* memory"),
    (lambda: whirl.fit([0.1, 0.2, 0.3], [-0.5, -0.9, -1.0], links=10**7), "links must be <= 2000"),
    (lambda: whirl.Simulation(10, dim=4), "dim must be 2 or 3"),
    (lambda: whirl.Simulation(10, method="rk5"), "method must be one of"),
    (lambda: whirl.fit([5, 6, 7], [5, 6, 7]), "no mode explains"),
])
def test_bounds_and_value_errors(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_runs_bounded_by_their_work():
    sim = whirl.Simulation(1)
    sim.set_hanging()
    with pytest.raises(ValueError, match="rows .* must be <= .* memory|links x rows"):
        sim.run(1, 1e-9)  # 1e9 rows
    with pytest.raises(ValueError, match="links x steps"):
        sim.run(1e17, 1.0, every=1e16)  # 1e17 steps
    assert sim.t == 0.0


def test_library_refuses_a_chain_whose_size_overflows():
    # whirl_chain_alloc_uniform itself (the package bounds links before it): n * sizeof(double)
    # would wrap round
    from whirl._lib import lib, ffi, last_error
    assert lib.whirl_chain_alloc_uniform(2**61, 0.0) == ffi.NULL
    assert "more memory than can be addressed" in last_error()


def test_results_finite_or_refused():
    with pytest.raises(ValueError):
        whirl.shape(10.0, 1, mass=1e308)
    s = whirl.shape(10.0, 1, mass=1e30)  # the largest mass the command line takes
    assert np.isfinite(s.top_tension)
