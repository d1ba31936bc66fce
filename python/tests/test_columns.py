"""Results as data: as_dict() of every result in the command line's column names with their
units, the same names read_csv gives the command line's files, and to_pandas()."""
import subprocess
from dataclasses import dataclass

import numpy as np
import pandas
import pytest

import whirl
from whirl import _lib

SI = dict(length=0.6, mass=0.05)
SI_ARGS = ["--length", "0.6", "--mass", "0.05"]


def _cli(program, tmp_path, *args):
    out = tmp_path / "cli.csv"
    subprocess.run([program, *args, *SI_ARGS, "-o", str(out)], check=True,
                   stderr=subprocess.DEVNULL)
    return whirl.read_csv(out)


def _same_columns(py, table, absent=()):
    """Every column of the command line's file (but those ``absent`` from the result) is one of
    the result's, under the same label, with the same values (1e-12 relative: both are the
    library's doubles, scaled to SI)."""
    got, want = py.as_dict(), table.as_dict()
    assert set(absent) <= set(want)
    want = {k: v for k, v in want.items() if k not in absent}
    assert set(want) <= set(got), (sorted(want), sorted(got))
    for label, values in want.items():
        if values.dtype.kind == "U":
            assert list(got[label].astype(str)) == list(values), label
        else:
            np.testing.assert_allclose(got[label].astype(float), values, rtol=1e-12, atol=0,
                                       err_msg=label)
    return got


@pytest.mark.parametrize("links", [None, 7])
def test_shape_columns_are_the_files(whirl_program, tmp_path, links):
    extra = ["--points", "41"] if links is None else ["--links", str(links)]
    t = _cli(whirl_program, tmp_path, "shape", "--omega", "15", "--mode", "2", *extra)
    s = whirl.shape(15, 2, links=links, points=41, **SI)
    got = _same_columns(s, t)
    assert list(got) == ["s [m]", "r [m]", "z [m]", "tension [N]"]
    np.testing.assert_array_equal(got["r [m]"], s.r)
    # the summary line's quantities, as the file's
    frame = s.to_pandas()
    assert frame.attrs["omega [rad/s]"] == s.omega
    assert frame.attrs["node_count"] == 2
    assert float(t.to_pandas().attrs["tip_r [m]"]) == pytest.approx(s.tip_r, rel=1e-12)


def test_dimensionless_labels():
    s = whirl.shape(3.0, 2, points=11)
    assert list(s.as_dict()) == ["s [L]", "r [L]", "z [L]", "tension [M g]"]
    assert s.to_pandas().attrs["omega [sqrt(g/L)]"] == 3.0
    r = whirl.stability(3.0, 2, 10, linear=True)
    d = r.as_dict()
    assert d["omega [sqrt(g/L)]"][0] == 3.0 and d["eig_growth [sqrt(g/L)]"][0] == r.eig_growth
    assert d["verdict"][0] == r.verdict and d["links"][0] == 10
    assert np.isnan(d["sim_growth [sqrt(g/L)]"][0])  # linear: no run, as the file's empty field


def test_stability_spin_up_fit_are_rows_of_the_files(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "stability", "--omega", "12", "--mode", "2", "--links",
             "6", "--periods", "20")
    r = whirl.stability(12, 2, 6, periods=20, **SI)
    got = _same_columns(r, t)
    assert "eig_growth [1/s]" in got and "omega [rad/s]" in got
    t = _cli(whirl_program, tmp_path, "regime", "--omega", "12", "--eps", "0.02", "--links",
             "5", "--t-max", "20")
    # a map's row number, its point and class code are the map's, not the spin-up's
    got = _same_columns(whirl.spin_up(12, 0.02, 5, t_max=20, **SI), t,
                        absent=("index", "omega [rad/s]", "eps [m]", "class"))
    assert "t_end [s]" in got and "lyapunov [1/s]" in got
    shape = tmp_path / "shape.csv"
    subprocess.run([whirl_program, "shape", "--omega", "15", "--mode", "2", "--points", "30",
                    *SI_ARGS, "-o", str(shape)], check=True)
    data = whirl.read_csv(shape)
    t = _cli(whirl_program, tmp_path, "fit", "--shape", str(shape))
    got = _same_columns(whirl.fit(data["r"], data["z"], **SI), t)
    assert "rms_residual [m]" in got


def test_driven_columns_are_the_files(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "driven", "--omega", "12", "--mode", "2", "--eps", "0.003",
             "--points", "9", "--drag", "0.001")
    d = whirl.driven(12, 2, 0.003, points=9, air_drag=0.001, **SI)
    got = _same_columns(d, t)
    assert list(got) == ["s [m]", "x [m]", "y [m]", "z [m]", "tension [N]"]


def test_trajectory_and_scene_columns_are_simulates(whirl_program, tmp_path):
    scene = tmp_path / "s.ini"
    scene.write_text("[units]\nsystem = SI\n[chain]\ndim = 3\nlinks = 12\nlength = 0.6\n"
                     "mass = 0.05\n[start]\nomega = 25\nmode = 2\nperturb = 0.001\n"
                     "[run]\ndt = 0.5ms\nt_end = 0.2\n[output]\nevery = 0.02\n"
                     "columns = t, tip_x, tip_y, tip_z, energy, jacobi, lz, constraint, "
                     "deviation\n")
    out = tmp_path / "cli.csv"
    subprocess.run([whirl_program, "simulate", str(scene), "-o", str(out)], check=True,
                   stderr=subprocess.DEVNULL)
    t = whirl.read_csv(out)
    sim = whirl.Simulation(12, omega=25, **SI)
    sim.set_steady(2, perturb=0.001)
    tr = sim.run(0.2, 0.0005, every=0.02)
    want = t.as_dict()
    got = tr.as_dict()
    assert list(want) == ["t [s]", "tip_x [m]", "tip_y [m]", "tip_z [m]", "energy [J]",
                          "jacobi [J]", "lz [kg m^2/s]", "constraint [m]", "deviation [m]"]
    assert set(want) <= set(got)
    for label in ("t [s]", "tip_x [m]", "tip_y [m]", "tip_z [m]", "energy [J]", "lz [kg m^2/s]"):
        np.testing.assert_allclose(got[label], want[label], rtol=1e-12, atol=1e-15, err_msg=label)
    run = whirl.run_scene(scene)
    assert run.as_dict().keys() == want.keys()
    for label, values in want.items():
        np.testing.assert_allclose(run.as_dict()[label], values, rtol=1e-15, err_msg=label)


def test_to_pandas_is_as_dict():
    u = whirl.Units(**SI)
    sim = whirl.Simulation(6, omega="4Hz", units=u)
    sim.set_steady(1)
    tr = sim.run("0.1s", "1ms", every="10ms")
    frame = tr.to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    d = tr.as_dict()
    assert list(frame.columns) == list(d) and len(frame) == tr.t.size == 11
    for label, values in d.items():
        np.testing.assert_array_equal(frame[label].to_numpy(), values)
    np.testing.assert_array_equal(frame["tip_x [m]"].to_numpy(), tr.x[:, -1, 0])
    assert frame.attrs["method"] == "gauss2" and frame.attrs["units"] == repr(u)
    one = whirl.stability(20.0, 2, 8, linear=True, units=u).to_pandas()
    assert len(one) == 1 and one["verdict"][0] in ("unstable", "neutral (gyroscopic)",
                                                   "stable (minimum)")


def test_results_without_columns_of_their_own():
    # the fields' rule (whirl.columns.split): 1-D arrays of the common length are the columns,
    # numbers the summary
    @dataclass(eq=False)
    class Branch(_lib.Result):
        omega: np.ndarray
        tip_r: np.ndarray
        mode: int
        units: whirl.Units

    b = Branch(np.array([1.0, 2.0, 3.0]), np.array([0.1, 0.2, 0.3]), 2, whirl.Units(**SI))
    assert list(b.as_dict()) == ["omega [rad/s]", "tip_r [m]"]
    assert b.to_pandas().attrs["mode"] == 2
