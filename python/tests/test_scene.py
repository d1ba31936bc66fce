"""Scene files from Python: run_scene returns what `whirl simulate` writes (the same library run,
so equal to round-off in the CSV's 17-digit numbers), and Simulation.set_steady(perturb, seed)
is the scene's perturbed steady start."""
import os
import subprocess

import numpy as np
import pytest

import whirl

SI_SCENE = """[units]
system = SI
[chain]
dim = 3
links = 10
length = 60cm
mass = 50g
[start]
omega = 3Hz
mode = 2
perturb = 0.02
seed = 7
[run]
dt = 1ms
t_end = 0.3
air_drag = 0.01
[output]
every = 20ms
columns = t, tip_x, tip_y, tip_z, energy, lz, deviation
"""


def _csv(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    names = rows[0].strip().split(",")
    table = np.array([[float(v) for v in line.split(",")] for line in rows[1:]])
    return names, table, [line for line in open(path) if line.startswith("# units:")]


def test_run_scene_equals_the_command_line(tmp_path, whirl_program):
    scene = tmp_path / "si.ini"
    scene.write_text(SI_SCENE)
    out, trace = tmp_path / "out.csv", tmp_path / "trace.dat"
    subprocess.run([whirl_program, "simulate", str(scene), "--set", "output.trace=" + str(trace),
                    "--set", "output.trace_every=0.1", "-o", str(out)], check=True)
    names, table, units_line = _csv(out)
    run = whirl.run_scene(scene, trace=0.1)
    assert run.columns == names
    for k, name in enumerate(names):
        np.testing.assert_allclose(run[name], table[:, k], rtol=1e-15, atol=0)
    assert units_line == ["# units: length=m mass=kg time=s rate=rad/s force=N L=0.6 M=0.05 "
                          "g=9.80665\n"]
    assert run.units == {"physical": True, "length": 0.6, "mass": 0.05, "gravity": 9.80665}
    frames = [np.array([[float(v) for v in line.split()] for line in block.strip().split("\n")
                        if not line.startswith("#")])
              for block in open(trace).read().split("\n\n\n")]
    assert run.trace_x.shape == (len(frames), 11, 3)
    for f, frame in enumerate(frames):
        np.testing.assert_allclose(run.trace_x[f], frame[:, :3], rtol=1e-15, atol=1e-300)
        assert run.trace_t[f] == pytest.approx(frame[0, 3], rel=1e-15)
    assert run.stats["steps"] == 300 and not run.stopped and run.t == pytest.approx(0.3)


def test_overrides_as_list_string_or_dict(tmp_path):
    scene = tmp_path / "si.ini"
    scene.write_text(SI_SCENE)
    a = whirl.run_scene(scene, set=["run.t_end=0.1", "start.omega=4Hz"])
    b = whirl.run_scene(scene, set={"run.t_end": 0.1, "start.omega": "4Hz"})
    c = whirl.run_scene(scene, set="run.t_end=0.1")
    np.testing.assert_array_equal(a["tip_x"], b["tip_x"])
    assert a["t"][-1] == pytest.approx(0.1) and c["t"][-1] == pytest.approx(0.1)
    assert not np.allclose(a["tip_z"][0], c["tip_z"][0])  # 4 Hz flattens the shape


def test_set_steady_perturb_is_the_scenes_start(tmp_path):
    """The same perturbed start through the scene and through Simulation (dimensionless)."""
    scene = tmp_path / "d.ini"
    scene.write_text("[chain]\ndim = 3\nlinks = 12\n[start]\nomega = 3.4\nmode = 2\n"
                     "perturb = 0.05\nseed = 11\n[run]\ndt = 0.005\nt_end = 0.5\n"
                     "[output]\nevery = 0.1\ncolumns = t, tip_x, tip_y, tip_z, energy, deviation\n")
    run = whirl.run_scene(scene)
    sim = whirl.Simulation(12, omega=3.4, method="gauss2")
    sim.set_steady(2, perturb=0.05, seed=11)
    tr = sim.run(0.5, 0.005, every=0.1)
    np.testing.assert_allclose(tr.tip, np.column_stack([run["tip_x"], run["tip_y"],
                                                        run["tip_z"]]), rtol=0, atol=1e-13)
    np.testing.assert_allclose(tr.energy, run["energy"], rtol=1e-13)
    np.testing.assert_allclose(tr.deviation, run["deviation"], rtol=1e-9, atol=1e-15)
    # each link turned by exactly the angle asked, its length kept; another seed, another turn
    def links(perturb, seed):
        sim = whirl.Simulation(12, omega=3.4, method="gauss2")
        sim.set_steady(2, perturb=perturb, seed=seed)
        return np.diff(np.vstack([np.zeros(3), sim.positions()]), axis=0)
    plain, turned, other = links(0, 1), links(0.05, 11), links(0.05, 12)
    lengths = np.linalg.norm(plain, axis=1)
    np.testing.assert_allclose(np.linalg.norm(turned, axis=1), lengths, rtol=1e-14)
    cos = np.sum(plain * turned, axis=1) / lengths**2
    np.testing.assert_allclose(np.arccos(np.clip(cos, -1, 1)), 0.05, rtol=1e-9)
    assert not np.allclose(turned, other, atol=1e-6)


def test_scene_errors(tmp_path):
    bad = tmp_path / "bad.ini"
    bad.write_text("[chain]\ndim = 3\nlinks = 4\nlength = 1\nlengths = 0.5, 0.5, 0.5, 0.5\n")
    with pytest.raises(whirl.Error, match=r"bad.ini:4: \[chain\] length: conflicts with"):
        whirl.run_scene(bad)
    with pytest.raises(whirl.Error, match="cannot read"):
        whirl.run_scene(tmp_path / "missing.ini")
    with pytest.raises(ValueError, match="section.key=value"):
        whirl.run_scene(bad, set=["nonsense"])
    with pytest.raises(TypeError):
        whirl.run_scene(42)
    scene = tmp_path / "si.ini"
    scene.write_text(SI_SCENE)
    with pytest.raises(whirl.Error, match=r"--set run.method.*nosuch"):
        whirl.run_scene(scene, set={"run.method": "nosuch"})
    with pytest.raises(ValueError):
        whirl.Simulation(8, omega=3).set_steady(1, perturb=-1)
