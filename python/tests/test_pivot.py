"""The pivot on a periodic path from Python: Simulation(..., pivot=PATH, omega=W) runs what
``whirl simulate --pivot PATH`` and a scene's [run] pivot run (the same library run: with steps
and output times that are sums of powers of two the numbers are equal to the last bit; in SI units,
where Python scales dimensionless results and the scene runs in its own units, to 1e-12
relative), the path means what whirl.periodic's pivot= means, and bad input is refused."""
import copy
import pickle
import subprocess

import numpy as np
import pytest

import whirl

SCENE = """[chain]
dim = 3
links = 5
[start]
hanging = true
[run]
omega = 3
dt = 0.00390625
t_end = 2
[output]
every = 0.0625
"""
PATH = "fourier:x1c=0.1,y1s=0.06,z2c=0.02"
COLUMNS = ("t", "tip_x", "tip_y", "tip_z", "energy", "jacobi", "lz", "constraint")


def _simulate(program, tmp_path, scene, *args):
    out = tmp_path / "cli.csv"
    subprocess.run([program, "simulate", str(scene), *args, "-o", str(out)], check=True,
                   stderr=subprocess.DEVNULL)
    return whirl.read_csv(out)


def _columns(tr):
    return dict(t=tr.t, tip_x=tr.tip[:, 0], tip_y=tr.tip[:, 1], tip_z=tr.tip[:, 2],
                energy=tr.energy, jacobi=tr.jacobi, lz=tr.lz, constraint=tr.constraint)


def test_simulation_equals_the_command_line_and_the_scene_to_the_last_bit(whirl_program,
                                                                          tmp_path):
    scene = tmp_path / "s.ini"
    scene.write_text(SCENE)
    cli = _simulate(whirl_program, tmp_path, scene, "--pivot", PATH)
    sim = whirl.Simulation(5, omega=3, pivot=PATH)
    assert sim.pivot == PATH
    sim.set_hanging()
    py = _columns(sim.run(2, 0.00390625, every=0.0625))
    run = whirl.run_scene(scene, set={"run.pivot": PATH})
    assert len(cli["t"]) == 33
    for name in COLUMNS:
        assert np.array_equal(py[name], cli[name]), name
        assert np.array_equal(run[name], cli[name]), name
    assert np.ptp(cli["tip_z"]) > 0.01  # the pivot's z term lifts the chain


def test_simulation_in_si_units_equals_the_scene(whirl_program, tmp_path):
    # the scene runs in m, s and g = 9.80665 m/s^2; Python in L, sqrt(L/g), scaled
    scene = tmp_path / "si.ini"
    scene.write_text("[units]\nsystem = SI\n[chain]\ndim = 3\nlinks = 4\nlength = 50cm\n"
                     "mass = 50g\n[start]\nhanging = true\n[run]\nomega = 2Hz\ndt = 1ms\n"
                     "t_end = 0.4\n[output]\nevery = 20ms\n")
    cli = _simulate(whirl_program, tmp_path, scene, "--pivot", "ellipse:2cm,1cm")
    assert cli.units == whirl.Units(length=0.5, mass=0.05)
    sim = whirl.Simulation(4, omega="2Hz", pivot="ellipse:2cm,1cm", length=0.5, mass=0.05)
    sim.set_hanging()
    py = _columns(sim.run(0.4, 0.001, every=0.02))
    for name in ("tip_x", "tip_y", "tip_z", "energy", "lz"):
        scale = np.max(np.abs(cli[name]))
        assert np.max(np.abs(py[name] - cli[name])) <= 1e-12 * scale, name
    assert py["tip_x"][0] == pytest.approx(0.02, abs=1e-15)


def test_the_path_is_whirl_periodics():
    # one name, one meaning: the periodic motion whirl.periodic finds on the path (the circle
    # drive's 2-node shape, 3 links) comes back to itself after one period of a Simulation on
    # the same path, with the same steps (Gauss, order 4)
    res = whirl.periodic("circle:0.05", 4.0, links=3, start="steady", mode=2)
    sim = whirl.Simulation(3, omega=4.0, pivot="circle:0.05", method="gauss2")
    sim.set_state(res.x, res.v)
    tr = sim.run(res.period, res.period / res.steps, every=res.period)
    assert np.max(np.abs(tr.x[-1] - res.x)) < 1e-9
    assert np.max(np.abs(tr.x[-1] - tr.x[0])) < 1e-9
    # and the motion moved: half a period later the shape has turned with the pivot
    half = whirl.Simulation(3, omega=4.0, pivot="circle:0.05", method="gauss2")
    half.set_state(res.x, res.v)
    mid = half.run(res.period / 2, res.period / res.steps, every=res.period / 2)
    assert np.max(np.abs(mid.x[-1] - res.x)) > 0.1


def test_circle_path_is_drive_radius():
    # the same integrator and step, the inertial frame, the same start (tilted by 0.3 rad, moving
    # with the pivot): the same motion to round-off
    x = np.cumsum(np.tile([np.sin(0.3) / 6, 0, -np.cos(0.3) / 6], (6, 1)), axis=0)
    x[:, 0] += 0.08  # the pivot at (0.08, 0, 0) at t = 0
    v = np.zeros((6, 3))
    v[:, 1] = 2.5 * 0.08  # its velocity
    runs = []
    for kw in (dict(pivot="circle:0.08"), dict(drive_radius=0.08)):
        sim = whirl.Simulation(6, omega=2.5, **kw)
        sim.set_state(x, v)
        runs.append(sim.run(5.0, 0.005, every=0.5))
    assert np.max(np.abs(runs[0].x - runs[1].x)) < 1e-13
    assert np.max(np.abs(runs[0].x[-1] - runs[0].x[0])) > 0.1


def test_copies_keep_the_path():
    sim = whirl.Simulation(3, omega=2.0, pivot="vertical:0.1")
    sim.set_hanging()
    sim.run(1.0, 0.01)
    ref = copy.copy(sim).run(2.0, 0.01).x
    other = pickle.loads(pickle.dumps(sim))
    assert other.pivot == "vertical:0.1" and "pivot='vertical:0.1'" in repr(other)
    np.testing.assert_array_equal(other.run(2.0, 0.01).x, ref)
    assert np.ptp(ref[:, -1, 2]) > 0.05  # the shaken chain moves with its pivot


@pytest.mark.parametrize("kw,error,words", [
    (dict(pivot="circle:0.1"), ValueError, "pivot needs omega > 0"),
    (dict(pivot="circle:0.1", omega=2, frame="rotating"), whirl.InvalidInput,
     "a pivot path needs the inertial frame, drive radius 0"),
    (dict(pivot="circle:0.1", omega=2, drive_radius=0.1), whirl.InvalidInput,
     "a pivot path needs the inertial frame, drive radius 0"),
    (dict(pivot="square:1", omega=2), whirl.InvalidInput, "pivot path 'square': unknown kind"),
    (dict(pivot="circle:1cm", omega=2), whirl.InvalidInput, "has a unit"),
    (dict(pivot="ellipse:0.1,0.1", omega=2, dim=2), whirl.InvalidInput,
     "y1s moves the pivot out of the x-z plane"),
    (dict(pivot=0.1, omega=2), TypeError, "pivot must be a text"),
])
def test_bad_input(kw, error, words):
    with pytest.raises(error) as e:
        whirl.Simulation(3, **kw)
    assert words in str(e.value) and "\n" not in str(e.value)


def test_scene_file_with_the_key(tmp_path):
    # run_scene reads [run] pivot (whirl_scene_parse_with_pivot); a bad one names its line
    scene = tmp_path / "k.ini"
    scene.write_text(SCENE.replace("t_end = 2\n", "t_end = 2\npivot = vertical:0.05\n"))
    run = whirl.run_scene(scene)
    assert run["tip_z"][0] == pytest.approx(-1 + 0.05, abs=1e-15)
    scene.write_text(SCENE.replace("t_end = 2\n", "t_end = 2\npivot = vertical:x\n"))
    with pytest.raises(whirl.InvalidInput) as e:
        whirl.run_scene(scene)
    assert ":10: [run] pivot: pivot path: vertical A: 'x' is not a length" in str(e.value)
