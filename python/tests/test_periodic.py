"""whirl.periodic, periodic_path and chart_vertical against ``whirl periodic`` doing the same work:
every number the command line prints equals the Python result to the last bit (the library's
doubles, printed in full), those the command line scales by a unit to 1e-14 (the scalings may
differ by an ulp), and those it prints rounded (growth, e-folding) equal Python's rounded the
same way. Bad input: the command line's one-line messages."""
import os
import signal
import subprocess

import numpy as np
import pytest

import whirl

from conftest import BUILD

PROGRAM = os.path.join(BUILD, "whirl")
SI = dict(length=0.6, mass=0.05)
SI_ARGS = ["--length", "0.6", "--mass", "0.05"]


def _cli(tmp_path, *args):
    out = tmp_path / "cli.csv"
    subprocess.run([PROGRAM, "periodic", *args, "-o", str(out)], check=True,
                   stderr=subprocess.DEVNULL)
    return whirl.read_csv(out)


def _close(py, cli, rtol=1e-14):
    py, cli = np.asarray(py, dtype=float), np.asarray(cli, dtype=float)
    assert py.shape == cli.shape
    assert np.all(np.abs(py - cli) <= rtol * np.abs(cli)), (py, cli)


def test_a_motion_equals_the_command_line(tmp_path):
    args = ["--pivot", "ellipse:1cm,0.6cm", "--omega", "4Hz", "--links", "2", *SI_ARGS]
    table = _cli(tmp_path, *args)
    r = whirl.periodic("ellipse:1cm,0.6cm", "4Hz", links=2, **SI)
    assert table.units == r.units == whirl.Units(**SI)
    mu = r.multipliers
    assert np.array_equal(mu.real, table["re"]) and np.array_equal(mu.imag, table["im"])
    assert np.array_equal(np.hypot(mu.real, mu.imag), table["modulus"])
    assert np.array_equal(r.errors, table["err"])
    text = "\n".join(table.comments)
    assert "verdict=%s" % r.verdict in text and "edge=%s" % r.edge in text
    assert "|mu|max=%.15g +- %.2g;" % (r.max_modulus, r.max_modulus_err) in text
    assert "reciprocal-pair error %.2g" % r.reciprocal_err in text
    assert "Newton %d iterations, residual %.3g; %d steps" % (r.iterations, r.residual,
                                                              r.steps) in text
    period = float(text.split("period=")[1].split()[0])
    _close(r.period, period)
    _close(r.omega, 8 * np.pi)
    assert r.period == pytest.approx(0.25, rel=1e-15)
    # the state is the motion's: one period of it comes back (the run is the library's)
    assert r.x.shape == r.v.shape == (2, 3) and r.monodromy.shape == (8, 8)
    assert np.allclose(np.linalg.eigvals(r.monodromy)[np.argsort(
        -np.abs(np.linalg.eigvals(r.monodromy)))], mu, atol=1e-9)
    # a restart from the motion's state finds it again
    again = whirl.periodic("ellipse:1cm,0.6cm", "4Hz", links=2, start=r.state, **SI)
    assert np.max(np.abs(again.state - r.state)) < 1e-9


def test_an_unstable_motion_states_its_growth_as_the_command_line(tmp_path):
    args = ["--pivot", "vertical:0.2", "--omega", "1.8", "--links", "1", "--dim", "2"]
    table = _cli(tmp_path, *args)
    r = whirl.periodic("vertical:0.2", 1.8, links=1, dim=2)
    assert r.verdict == "unstable" and r.growth > 1
    text = "\n".join(table.comments)
    assert ("verdict=unstable growth=%.10g per period, e-folding %.6g periods"
            % (r.growth, r.efold_periods)) in text
    assert "(%s " % repr(r.efold_time) in text or "(%.17g " % r.efold_time in text
    assert np.array_equal(r.multipliers.real, table["re"])
    assert r.efold_time == pytest.approx(r.efold_periods * r.period, rel=1e-14)


def test_a_branch_with_its_event_equals_the_command_line(tmp_path):
    args = ["--pivot", "vertical:0.01", "--omega", "1.8", "--links", "1", "--dim", "2",
            "--amp-max", "0.3", "--up"]
    table = _cli(tmp_path, *args)
    b = whirl.periodic_path("vertical:0.01", 1.8, links=1, dim=2, amp_max=0.3, up=True)
    assert list(b.rows["event"]) == list(table["event"])
    assert list(b.events["event"]) == ["period-doubling"]
    for name in ("omega", "amplitude", "max_modulus", "fold_test", "flip_test", "torus_test",
                 "err"):
        assert np.array_equal(b.rows[name], table[name]), name
    assert list(b.rows["verdict"]) == list(table["verdict"])
    # the edges "+1", "-1", "complex": numbers where read_csv can read them
    assert [str(e) for e in b.rows["edge"]] == [e if isinstance(e, str) else "%+d" % e
                                                for e in table["edge"].tolist()]
    assert b.ended == "left the range" and b.parameter == "amplitude"


def test_a_branch_in_the_rate_in_si_units_equals_the_command_line(tmp_path):
    args = ["--pivot", "circle:3cm", "--omega", "5", "--links", "2", "--start", "steady",
            "--side", "-1", "--omega-min", "4.5", "--omega-max", "5.5", "--max-points", "4",
            *SI_ARGS]
    table = _cli(tmp_path, *args)
    b = whirl.periodic_path("circle:3cm", 5, links=2, start="steady", side=-1, omega_min=4.5,
                            omega_max=5.5, max_points=4, **SI)
    assert list(b.rows["event"]) == list(table["event"]) and b.ended == "max_points"
    for name in ("omega", "amplitude", "err"):
        _close(b.rows[name], table[name])
    for name in ("max_modulus", "fold_test", "flip_test", "torus_test"):
        assert np.array_equal(b.rows[name], table[name]), name


def test_a_damped_motion_equals_the_command_line(tmp_path):
    # the dragged and damped chain in SI units: the same numbers as the command line's
    # --drag, --drag-quadratic, --damping (the units of whirl.stability's air_drag, damping)
    args = ["--pivot", "circle:3cm", "--omega", "5", "--links", "2", "--start", "steady",
            "--drag", "0.01", "--drag-quadratic", "0.005", "--damping", "1e-4", *SI_ARGS]
    table = _cli(tmp_path, *args)
    r = whirl.periodic("circle:3cm", 5, links=2, start="steady", air_drag=0.01,
                       air_drag_quadratic=0.005, damping=1e-4, **SI)
    assert np.array_equal(r.multipliers.real, table["re"])
    assert np.array_equal(r.multipliers.imag, table["im"])
    text = "\n".join(table.comments)
    assert "dissipation: drag=0.01 drag_quadratic=0.005 damping=0.0001" in text
    assert "reciprocal-pair distance %.2g (the damped chain's multipliers are not in pairs" \
        % r.reciprocal_err in text
    # dissipation shrinks the phase space: |det M| < 1, no pairs mu, 1/mu
    assert abs(np.linalg.det(r.monodromy)) < 1 and r.reciprocal_err > 1e-3
    undamped = whirl.periodic("circle:3cm", 5, links=2, start="steady", **SI)
    assert undamped.reciprocal_err < 1e-10 and r.max_modulus < undamped.max_modulus


def test_a_damped_branch_locates_its_torus_as_the_command_line(tmp_path):
    args = ["--pivot", "circle:0.05", "--omega", "2.8", "--links", "3", "--start", "steady",
            "--side", "-1", "--mode", "2", "--drag", "0.05", "--omega-min", "2.8",
            "--omega-max", "2.9", "--up", "--arc-step", "0.02"]
    table = _cli(tmp_path, *args)
    b = whirl.periodic_path("circle:0.05", 2.8, links=3, start="steady", side=-1, mode=2,
                            air_drag=0.05, omega_min=2.8, omega_max=2.9, up=True, arc_step=0.02)
    assert list(b.events["event"]) == ["torus"]
    for name in ("omega", "max_modulus", "torus_test", "err"):
        assert np.array_equal(b.rows[name], table[name]), name
    # where the steady linearisation's growth rate passes 0 (tests/unit/periodic)
    assert abs(b.events["omega"][0] - 2.850665362775) < 1e-8


def test_negative_damping_is_refused():
    with pytest.raises(ValueError):
        whirl.periodic("vertical:0.1", 2, dim=2, damping=-1)


def test_a_chart_equals_the_command_line(tmp_path):
    args = ["--chart", "hanging", "--omega-min", "1.5", "--omega-max", "2.5", "--omega-count",
            "4", "--amp-max", "0.3", "--amp-rows", "12", "--links", "2"]
    table = _cli(tmp_path, *args)
    c = whirl.chart_vertical(1.5, 2.5, 0.3, links=2, columns=4, rows=12)
    assert c.points.size == len(table) > 0
    for name in ("curve", "edge", "omega", "amplitude", "err"):
        assert np.array_equal(c.points[name], table[name]), name
    si = whirl.chart_vertical("1.5Hz", "2.5Hz", "5cm", links=2, columns=3, rows=8, **SI)
    table = _cli(tmp_path, "--chart", "hanging", "--omega-min", "1.5Hz", "--omega-max", "2.5Hz",
                 "--omega-count", "3", "--amp-max", "5cm", "--amp-rows", "8", "--links", "2",
                 *SI_ARGS)
    assert si.points.size == len(table) > 0 and si.units == table.units
    for name in ("omega", "amplitude", "err"):
        _close(si.points[name], table[name])


def test_a_damped_chart_equals_the_command_line(tmp_path):
    table = _cli(tmp_path, "--chart", "hanging", "--drag", "0.1", "--omega-min", "1.8",
                 "--omega-max", "2.2", "--omega-count", "3", "--amp-max", "0.3", "--amp-rows",
                 "12", "--links", "2")
    c = whirl.chart_vertical(1.8, 2.2, 0.3, links=2, columns=3, rows=12, air_drag=0.1)
    assert c.points.size == len(table) > 0
    for name in ("curve", "edge", "omega", "amplitude", "err"):
        assert np.array_equal(c.points[name], table[name]), name
    with pytest.raises(ValueError):
        whirl.chart_vertical(1.8, 2.2, 0.3, air_drag=-1)


ELLIPSE_ARGS = ["--chart", "ellipse", "--links", "2", "--eps", "0.05", "--mode", "2", "--side",
                "-1", "--omega-min", "3.95", "--omega-max", "4.1", "--omega-count", "4"]


def _ellipse(**kw):
    return whirl.chart_ellipse(3.95, 4.1, 0.05, links=2, mode=2, side=-1, columns=4, **kw)


def test_an_ellipse_chart_equals_the_command_line(tmp_path):
    table = _cli(tmp_path, *ELLIPSE_ARGS)
    calls = []
    c = _ellipse(progress=lambda done, total: calls.append((done, total)))
    assert c.points.size == len(table) > 0 and c.units == table.units
    for name in ("curve", "event", "omega", "ellipticity", "err"):
        assert np.array_equal(c.points[name], table[name]), name
    assert list(c.as_dict()) == ["curve", "event", "omega [sqrt(g/L)]", "ellipticity", "err"]
    assert [name.split(" ")[0] for name in c.as_dict()] == list(table.columns)
    assert repr(c) == "EllipseChart(eps=0.05, mode=2, side=-1, links=2, points=%d, curves=%d)" % (
        c.points.size, c.curves)
    dones = [d for d, t in calls]
    assert all(t == 4 for d, t in calls) and dones[-1] == 4
    assert all(b > a for a, b in zip(dones, dones[1:]))
    # SI units: the rates and the radius as the command line takes them, the same rows scaled
    w0 = np.sqrt(9.81 / 0.5)
    si = whirl.chart_ellipse(3.95 * w0, 4.1 * w0, "2.5cm", links=2, mode=2, side=-1, columns=4,
                             length=0.5, mass=0.05, gravity=9.81)
    table = _cli(tmp_path, "--chart", "ellipse", "--links", "2", "--eps", "2.5cm", "--mode", "2",
                 "--side", "-1", "--omega-min", repr(3.95 * w0), "--omega-max", repr(4.1 * w0),
                 "--omega-count", "4", "--length", "0.5", "--mass", "0.05", "--gravity", "9.81")
    assert si.points.size == len(table) == c.points.size and si.units == table.units
    assert si.eps == pytest.approx(0.025, rel=1e-15)
    for name in ("curve", "event", "ellipticity"):
        assert np.array_equal(si.points[name], table[name]), name
    for name in ("omega", "err"):
        _close(si.points[name], table[name])
    assert list(si.as_dict())[2] == "omega [rad/s]"


def test_an_ellipse_chart_stops_on_ctrl_c_keeping_its_points():
    full = _ellipse()
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        def ctrl_c(done, total):  # the library's handler takes it: a stop request
            if done == 2:
                os.kill(os.getpid(), signal.SIGINT)
        with pytest.raises(KeyboardInterrupt, match="chart_ellipse interrupted") as e:
            _ellipse(progress=ctrl_c)
        kept = _ellipse(progress=ctrl_c, keep_interrupted=True)
    finally:
        signal.signal(signal.SIGINT, old)
    assert not whirl.stop_requested()
    assert e.value.partial == kept and kept.interrupted and "interrupted" in repr(kept)
    assert 0 < kept.points.size < full.points.size
    assert np.array_equal(kept.points, full.points[:kept.points.size])
    with pytest.raises(ValueError, match="side must be 1 or -1"):
        whirl.chart_ellipse(3.95, 4.1, 0.05, side=0)
    with pytest.raises(ValueError, match="omega_max must exceed omega_min"):
        whirl.chart_ellipse(4.1, 3.95, 0.05)
    with pytest.raises(ValueError, match="e_max must be in"):
        whirl.chart_ellipse(3.95, 4.1, 0.05, e_max=2)


def _cli_error(*args):
    p = subprocess.run([PROGRAM, "periodic", *args], capture_output=True, text=True)
    assert p.returncode != 0 and p.stdout == ""
    lines = p.stderr.strip().split("\n")
    assert len(lines) == 1, p.stderr
    return lines[0]


@pytest.mark.parametrize("pivot,dim", [("ellipse:1", 3), ("fourier:x9c=1", 3),
                                       ("fourier:y1c=0.1", 2), ("square:1", 3),
                                       ("circle:1cm", 3)])
def test_bad_paths_are_said_as_the_command_line_says_them(pivot, dim):
    cli = _cli_error("--pivot", pivot, "--omega", "2", "--dim", str(dim))
    with pytest.raises(whirl.InvalidInput) as e:
        whirl.periodic(pivot, 2, dim=dim)
    assert str(e.value).startswith("pivot: ")
    assert cli == "whirl periodic: --pivot: " + str(e.value)[len("pivot: "):]


def test_newton_that_does_not_converge_says_its_residual():
    with pytest.raises(whirl.Error) as e:
        whirl.periodic("ellipse:0.1,0.05", 2.5, links=2, max_iter=1)
    assert e.value.status_name == "EMAXITER" and "residual" in str(e.value)
    assert str(e.value).startswith("periodic: ")
    cli = _cli_error("--pivot", "ellipse:0.1,0.05", "--omega", "2.5", "--links", "2",
                     "--max-iter", "1")
    assert cli == "whirl periodic: " + str(e.value)[len("periodic: "):]


def test_bad_arguments_are_refused_before_the_library():
    with pytest.raises(TypeError):
        whirl.periodic(3, 2)
    with pytest.raises(ValueError, match="start must be"):
        whirl.periodic("circle:0.1", 2, start="sideways")
    with pytest.raises(ValueError, match="needs pivot circle"):
        whirl.periodic("ellipse:0.1,0.05", 2, start="steady")
    with pytest.raises(ValueError, match="one parameter"):
        whirl.periodic_path("vertical:0.01", 1.8, dim=2, omega_min=1, omega_max=2, amp_max=1)
    with pytest.raises(ValueError, match="outside"):
        whirl.periodic_path("vertical:0.01", 3, dim=2, omega_min=1, omega_max=2)
    with pytest.raises(ValueError, match="omega_max must exceed"):
        whirl.chart_vertical(2, 1, 0.3)
    with pytest.raises(ValueError, match="suffix|unit"):
        whirl.chart_vertical("1Hz", 2, 0.3)


CHILD = r"""
import signal, threading, os, whirl
# Python's own handler, whatever the runner left (a CI that ignores SIGINT passes that on)
signal.signal(signal.SIGINT, signal.default_int_handler)
threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
try:
    # minutes of work uninterrupted, so that the stop lands inside it however fast the machine
    whirl.periodic("vertical:0.05", 1.8, links=60, dim=3, steps=200000)
except KeyboardInterrupt as e:
    print(repr(e))
"""


def _child(tmp_path, text):
    """The standard output of the script text run in a Python of its own (a SIGINT of its own)."""
    script = tmp_path / "child.py"
    script.write_text(text)
    env = dict(os.environ, PYTHONPATH=os.path.join(os.path.dirname(__file__), os.pardir))
    p = subprocess.run(["/usr/bin/python3", str(script)], env=env, capture_output=True,
                       text=True, timeout=300)
    return p.stdout.strip() + p.stderr


def test_ctrl_c_names_the_call(tmp_path):
    assert _child(tmp_path, CHILD) == "KeyboardInterrupt('whirl: periodic interrupted')"


KEEP = r"""
import signal, threading, os, whirl
# Python's own handler, whatever the runner left (a CI that ignores SIGINT passes that on)
signal.signal(signal.SIGINT, signal.default_int_handler)
threading.Timer(2.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
# a branch of about a million points uninterrupted: the stop lands inside it
b = whirl.periodic_path("vertical:0.01", 1.8, dim=2, amp_max=0.3, up=True, arc_step=3e-7,
                        max_points=10**6, keep_interrupted=True)
full = whirl.periodic_path("vertical:0.01", 1.8, dim=2, amp_max=0.3, up=True, arc_step=3e-7,
                           max_points=b.rows.size)
print(b.ended, b.rows.size > 0, (b.rows == full.rows).all())
"""


def test_ctrl_c_keeps_the_rows_of_a_branch_when_asked(tmp_path):
    # the rows so far are the first rows of the branch run to that length
    assert _child(tmp_path, KEEP) == "interrupted True True"
