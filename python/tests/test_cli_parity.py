"""Every Python function against the command line that does the same work, with the same SI
arguments (--length 0.6 --mass 0.05 --gravity left to its default 9.80665, in both): every number
the command line prints compared with the Python result, to a relative 1e-12 (both print or
return the library's doubles; the unit scalings differ by a few ulps at most). The CSV files are
read back with whirl.read_csv, whose units must be the call's.

WHIRL_PARITY_REPORT=FILE appends one line per function: the numbers compared and the largest
relative difference."""
import os
import re
import subprocess

import numpy as np
import pytest

import whirl

SI = dict(length=0.6, mass=0.05)
SI_ARGS = ["--length", "0.6", "--mass", "0.05"]
RTOL = 1e-12


def _report(name, count, worst):
    path = os.environ.get("WHIRL_PARITY_REPORT")
    if path:
        with open(path, "a") as f:
            f.write("%s %d %.3g\n" % (name, count, worst))


class Compare:
    def __init__(self, name):
        self.name, self.count, self.worst = name, 0, 0.0

    def __call__(self, what, py, cli):
        py = np.atleast_1d(np.asarray(py, dtype=np.float64))
        cli = np.atleast_1d(np.asarray(cli, dtype=np.float64))
        assert py.shape == cli.shape, (self.name, what, py.shape, cli.shape)
        assert np.array_equal(np.isnan(py), np.isnan(cli)), (self.name, what)
        ok = ~np.isnan(py)
        scale = max(np.max(np.abs(cli[ok]), initial=0.0), 1e-300)
        diff = np.abs(py[ok] - cli[ok])
        # relative to each value, with the column's largest value as the floor (r = 0 on the axis)
        rel = diff / np.maximum(np.abs(cli[ok]), 1e-12 * scale) if diff.size else diff
        worst = float(np.max(rel, initial=0.0))
        assert worst <= RTOL, "%s %s: relative difference %.3g" % (self.name, what, worst)
        self.count += int(ok.sum())
        self.worst = max(self.worst, worst)

    def done(self):
        assert self.count > 0
        _report(self.name, self.count, self.worst)


def _cli(program, tmp_path, *args):
    out = tmp_path / "cli.csv"
    subprocess.run([program, *args, *SI_ARGS, "-o", str(out)], check=True,
                   stderr=subprocess.DEVNULL)
    table = whirl.read_csv(out)
    assert table.units == whirl.Units(**SI) and table.units.gravity == 9.80665
    return table


def test_critical(whirl_program, tmp_path):
    c = Compare("critical")
    for extra, kw in ((["--tip-mass", "0.01"], dict(tip_mass=0.01)),
                      (["--links", "12"], dict(links=12))):
        t = _cli(whirl_program, tmp_path, "critical", "--modes", "6", *extra)
        c("omega", whirl.critical(6, **kw, **SI), t["omega"])
    c.done()


@pytest.mark.parametrize("links", [None, 7])
def test_shape(whirl_program, tmp_path, links):
    extra = [] if links is None else ["--links", str(links)]
    if links is None:
        extra = ["--points", "41"]
    t = _cli(whirl_program, tmp_path, "shape", "--omega", "15", "--mode", "2", *extra)
    s = whirl.shape(15, 2, links=links, points=41, **SI)
    c = Compare("shape" + ("" if links is None else " (N-link)"))
    for name in ("s", "r", "z", "tension"):
        c(name, getattr(s, name), t[name])
    for name in ("omega", "tip_r", "max_r", "top_tension", "depth"):
        c(name, getattr(s, name), float(t.summary[name]))
    c("crossings", s.crossings, [float(v) for v in t.summary["crossing_s"].split(";") if v])
    assert s.node_count == int(t.summary["node_count"]) == 2
    c.done()


def test_sweep(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "sweep", "--modes", "1,2", "--omega-min", "8",
             "--omega-max", "20", "--omega-count", "5", "--links", "6")
    c = Compare("sweep")
    for k in (1, 2):
        rows = t["mode"] == k
        got = whirl.sweep(k, t["omega"][rows], links=6, **SI)[k]
        for name in ("omega", "tip_r", "max_r", "top_tension", "depth"):
            c(name, got[name], t[name][rows])
        c("node_count", got["node_count"], t["nodes"][rows])
    c.done()


def test_equilibria(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "equilibria", "--omega", "20", "--links", "6")
    rows, _ = whirl.equilibria(20, 6, **SI)
    c = Compare("equilibria")
    for name in ("born_at", "tip_r", "max_r", "depth", "top_tension", "eig_growth"):
        c(name, rows[name], t[name])
    c("node_count", rows["node_count"], t["nodes"])
    c("branch", rows["branch"], t["branch"])
    c.done()


def test_stability(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "stability", "--omega", "12", "--mode", "2", "--links",
             "6", "--periods", "20")
    r = whirl.stability(12, 2, 6, periods=20, **SI)
    c = Compare("stability")
    for name in ("eig_growth", "sim_growth", "max_deviation"):
        c(name, getattr(r, name), t[name])
    assert r.verdict == t["verdict"][0]
    c.done()


def test_stability_map(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "stability", "--omega-min", "8", "--omega-max", "20",
             "--omega-count", "5", "--modes", "2", "--links", "6", "--linear")
    m = whirl.stability_map(t["omega"], 2, 6, **SI)
    c = Compare("stability_map")
    c("omega", m["omega"], t["omega"])
    c("growth", m["growth"], t["eig_growth"])
    c.done()


def test_stability_windows(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "stability", "--windows", "--links", "6", "--modes", "2",
             "--omega-min", "5", "--omega-max", "40")
    w, stats = whirl.stability_windows(2, 6, 5, 40, **SI)
    c = Compare("stability_windows")
    for name in ("from", "to", "freq_from", "freq_to", "max_growth", "at"):
        c(name, w[name], t[name])
    c("open", np.concatenate([w["open_from"], w["open_to"]]),
      np.concatenate([t["open_from"], t["open_to"]]))
    c.done()


@pytest.mark.parametrize("extra,kw", [(["--damping", "1e-5"], dict(damping=1e-5)),
                                      (["--eps", "0.012", "--drag", "0.0002", "--side", "-1"],
                                       dict(drive_radius=0.012, air_drag=0.0002, side=-1))])
def test_dissipative_windows(whirl_program, tmp_path, extra, kw):
    t = _cli(whirl_program, tmp_path, "stability", "--windows", "--links", "6", "--modes", "2",
             "--omega-min", "8", "--omega-max", "20", *extra)
    w, stats = whirl.dissipative_windows(2, 6, omega_min=8, omega_max=20, **kw, **SI)
    c = Compare("dissipative_windows")
    for name in ("from", "to", "freq_from", "freq_to", "growth", "at"):
        c(name, w[name], t[name])
    c("open", np.concatenate([w["open_from"], w["open_to"]]),
      np.concatenate([t["open_from"], t["open_to"]]))
    assert list(w["verdict"]) == list(t["verdict"])
    c.done()


@pytest.mark.parametrize("links", [None, 5])
def test_driven(whirl_program, tmp_path, links):
    extra = ["--points", "9", "--drag", "0.001"] if links is None else ["--links", str(links)]
    t = _cli(whirl_program, tmp_path, "driven", "--omega", "12", "--mode", "2", "--eps", "0.003",
             *extra)
    kw = dict(points=9, air_drag=0.001) if links is None else dict(links=links)
    d = whirl.driven(12, 2, 0.003, **kw, **SI)
    c = Compare("driven" + ("" if links is None else " (N-link)"))
    for name in ("s", "x", "y", "z", "tension"):
        c(name, getattr(d, name), t[name])
    c("tip", d.tip, [float(t.summary["tip_" + k]) for k in "xyz"])
    for name in ("tip_r", "top_tension"):
        c(name, getattr(d, name), float(t.summary[name]))
    assert d.node_count == int(t.summary["node_count"])
    c.done()


def test_spin_up(whirl_program, tmp_path):
    t = _cli(whirl_program, tmp_path, "regime", "--omega", "12", "--eps", "0.02", "--links", "5",
             "--t-max", "20")
    s = whirl.spin_up(12, 0.02, 5, t_max=20, **SI)
    c = Compare("spin_up")
    for name in ("t_end", "change", "lyapunov", "tip_r", "steps"):
        c(name, getattr(s, name), t[name])
    c("tip", s.tip, [t["tip_x"][0], t["tip_y"][0], t["tip_z"][0]])
    assert s.state == t["state"][0] and s.node_count == t["nodes"][0]
    c.done()


def test_fit(whirl_program, tmp_path):
    shape = tmp_path / "shape.csv"
    subprocess.run([whirl_program, "shape", "--omega", "15", "--mode", "2", "--points", "30",
                    *SI_ARGS, "-o", str(shape)], check=True)
    t = _cli(whirl_program, tmp_path, "fit", "--shape", str(shape))
    data = whirl.read_csv(shape)
    f = whirl.fit(data["r"], data["z"], **SI)
    c = Compare("fit")
    for name in ("omega", "omega_err", "mode", "rms_residual"):
        c(name, getattr(f, name), t[name])
    c.done()


def test_simulation(whirl_program, tmp_path):
    # whirl simulate of an SI scene against Simulation with the same units: the 60 cm, 50 g
    # chain of 12 links in its 2-node shape at 25 rad/s, perturbed, 0.2 s of gauss2
    scene = tmp_path / "s.ini"
    scene.write_text("[units]\nsystem = SI\n[chain]\ndim = 3\nlinks = 12\nlength = 0.6\n"
                     "mass = 0.05\n[start]\nomega = 25\nmode = 2\nperturb = 0.001\n"
                     "[run]\ndt = 0.5ms\nt_end = 0.2\n[output]\nevery = 0.02\n"
                     "columns = t, tip_x, tip_y, tip_z, energy, deviation\n")
    out = tmp_path / "cli.csv"
    subprocess.run([whirl_program, "simulate", str(scene), "-o", str(out)], check=True,
                   stderr=subprocess.DEVNULL)
    t = whirl.read_csv(out)
    assert t.units == whirl.Units(**SI)
    sim = whirl.Simulation(12, omega=25, **SI)
    sim.set_steady(2, perturb=0.001)
    tr = sim.run(0.2, 0.0005, every=0.02)
    c = Compare("Simulation")
    c("t", tr.t, t["t"])
    for k, name in enumerate(("tip_x", "tip_y", "tip_z")):
        c(name, tr.tip[:, k], t[name])
    c("energy", tr.energy, t["energy"])
    c("deviation", tr.deviation, t["deviation"])
    c.done()


@pytest.mark.parametrize("args,call", [
    (["shape", "--omega", "10", "--mode", "3", "--links", "20"],
     lambda: whirl.shape(10, 3, links=20, **SI)),
    (["stability", "--omega", "3", "--mode", "2", "--links", "10", "--linear"],
     lambda: whirl.stability(3.0, 2, 10, linear=True, **SI)),
])
def test_messages_in_the_same_units(whirl_program, args, call):
    # a refused mode: the rates in rad/s in both messages, to the digits the command line shows
    done = subprocess.run([whirl_program, *args, *SI_ARGS], capture_output=True, text=True)
    assert done.returncode != 0
    cli = done.stderr.strip().split(": ", 1)[1]
    with pytest.raises(whirl.InvalidInput) as e:
        call()
    py = str(e.value).split(": ", 1)[1] if str(e.value).startswith(args[0] + ":") else str(e.value)
    assert "rad/s" in cli and "rad/s" in py
    to_numbers = lambda text: [float(x) for x in re.findall(r"=(-?[0-9.]+(?:e[-+]?[0-9]+)?)", text)]
    np.testing.assert_allclose(to_numbers(py), to_numbers(cli), rtol=1e-14)
    assert re.sub(r"[0-9.]+", "#", py) == re.sub(r"[0-9.]+", "#", cli)
