"""The stability charts resumed (chart_vertical and chart_ellipse with resume=, as ``whirl
periodic --chart ... --resume``): a chart stopped by Ctrl-C (SIGINT sent from its progress
callback at a chosen rate: the library's stop request, polled within a monodromy) and resumed
from the interrupted result equals the chart that never stopped, field for field and bit for
bit, at every rate it can stop at; a result of other parameters, units or kind, or a state the
library refuses, is refused with one exception naming the difference."""
import dataclasses
import os
import resource
import signal
import subprocess
import sys

import numpy as np
import pytest

import whirl

from conftest import BUILD, REPO

PROGRAM = os.path.join(BUILD, "whirl")


def _stopped_at(chart, at, **kw):
    """chart(**kw) stopped by Ctrl-C when the progress reaches the rate ``at`` (the rates
    before it finished): the interrupted result (keep_interrupted=True)."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        def ctrl_c(done, total):  # the library's handler takes it: a stop request
            if done == at:
                os.kill(os.getpid(), signal.SIGINT)
        part = chart(progress=ctrl_c, keep_interrupted=True, **kw)
    finally:
        signal.signal(signal.SIGINT, old)
    assert not whirl.stop_requested()
    return part


def _vertical(**kw):
    # the hanging chain of two links: two tongues, each ended at its tip and joined across it
    # (the state carries tips and curves at a tip: tests/unit/periodic/test_chart_resume.c)
    return whirl.chart_vertical(1.8, 3, 0.4, links=2, columns=13, rows=20, **kw)


def _ellipse(**kw):
    # a curve that ends on e = 0 between the rates (test_chart_ellipse.c)
    return whirl.chart_ellipse(3.95, 4.1, 0.05, links=2, mode=2, side=-1, columns=4, **kw)


def _same_chart(a, b):
    assert a == b
    for name in a.points.dtype.names:  # the doubles bit for bit (== would pass -0.0 for 0.0)
        x, y = a.points[name], b.points[name]
        assert x.tobytes() == y.tobytes(), name


@pytest.mark.parametrize("at", [1, 5, 10])
def test_a_vertical_chart_stopped_and_resumed_is_the_whole_chart(at):
    full = _vertical()
    assert not full.interrupted and full.columns_done == 13 and full.points.size > 20
    part = _stopped_at(_vertical, at)
    # the stop polled within the rate under way, or the next (a rate may end before a poll)
    assert part.interrupted and at <= part.columns_done < 13
    assert part.state.startswith("vertical columns=%d " % part.columns_done)
    assert 0 < part.points.size < full.points.size
    resumed = _vertical(resume=part)
    _same_chart(resumed, full)
    # the stop's KeyboardInterrupt holds the same chart
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt, match="chart_vertical interrupted") as e:
            _vertical(progress=lambda d, t: d == at and os.kill(os.getpid(), signal.SIGINT))
    finally:
        signal.signal(signal.SIGINT, old)
    assert e.value.partial == part


def test_a_chart_stopped_twice_and_resumed_twice():
    full = _vertical(inverted=True)
    first = _stopped_at(_vertical, 4, inverted=True)
    second = _stopped_at(_vertical, 9, inverted=True, resume=first)
    assert 4 <= first.columns_done < 9 <= second.columns_done < 13
    assert second.points.size >= first.points.size
    _same_chart(_vertical(inverted=True, resume=second), full)
    # a finished chart resumed: nothing left to compute, the same chart
    _same_chart(_vertical(inverted=True, resume=full), full)


def test_a_damped_chart_in_si_units_resumed():
    kw = dict(length=0.6, mass=0.05, air_drag=0.02)
    full = whirl.chart_vertical("1.5Hz", "2.5Hz", "5cm", links=2, columns=6, rows=8, **kw)
    part = _stopped_at(whirl.chart_vertical, 3, omega_min="1.5Hz", omega_max="2.5Hz",
                       amp_max="5cm", links=2, columns=6, rows=8, **kw)
    assert " drag=" in part.state.split("\n")[0]
    resumed = whirl.chart_vertical("1.5Hz", "2.5Hz", "5cm", links=2, columns=6, rows=8,
                                   resume=part, **kw)
    _same_chart(resumed, full)


@pytest.fixture(scope="module")
def ellipse_full():
    return _ellipse()  # (the ellipse chart's rates are slow: computed once for the module)


@pytest.fixture(scope="module")
def ellipse_part():
    return _stopped_at(_ellipse, 2)


@pytest.mark.parametrize("at", [1, 2])
def test_an_ellipse_chart_stopped_and_resumed_is_the_whole_chart(at, ellipse_full,
                                                                  ellipse_part):
    full = ellipse_full
    part = ellipse_part if at == 2 else _stopped_at(_ellipse, at)
    assert part.interrupted and at <= part.columns_done < 4
    assert part.state.startswith("ellipse columns=%d " % part.columns_done)
    assert part.points.size < full.points.size
    _same_chart(_ellipse(resume=part), full)


def test_a_resume_of_other_parameters_is_refused(ellipse_part):
    part = _stopped_at(_vertical, 5)
    with pytest.raises(ValueError, match=r"resume: the chart was computed with omega_max=3\.0 "
                                         r"where this call has 3\.5"):
        whirl.chart_vertical(1.8, 3.5, 0.4, links=2, columns=13, rows=20, resume=part)
    with pytest.raises(ValueError, match="computed with chain="):
        whirl.chart_vertical(1.8, 3, 0.4, links=3, columns=13, rows=20, resume=part)
    with pytest.raises(ValueError, match="computed with inverted=False"):
        _vertical(inverted=True, resume=part)
    with pytest.raises(ValueError, match="computed with air_drag=0.0"):
        _vertical(air_drag=0.01, resume=part)
    with pytest.raises(ValueError, match="computed with rows=20 where this call has 200"):
        whirl.chart_vertical(1.8, 3, 0.4, links=2, columns=13, resume=part)
    # the defaults are the values they stand for
    _same_chart(_vertical(resume=part, steps=200, tol=1e-10, amp_min=0.02), _vertical())
    with pytest.raises(ValueError, match="resume it in the units it was begun in"):
        _vertical(resume=part, length=1.0)
    with pytest.raises(TypeError, match="resume must be the name of a file of whirl periodic "
                                        "--chart, or the Chart that chart_vertical returned"):
        _vertical(resume=ellipse_part)
    with pytest.raises(TypeError, match="or the EllipseChart that chart_ellipse returned"):
        _ellipse(resume=part)
    with pytest.raises(TypeError, match="got int"):
        _vertical(resume=5)
    with pytest.raises(ValueError, match="computed with side=-1 where this call has 1"):
        whirl.chart_ellipse(3.95, 4.1, 0.05, links=2, mode=2, side=1, columns=4,
                            resume=ellipse_part)


def test_a_state_the_library_refuses(ellipse_part):
    part = _stopped_at(_vertical, 5)
    done = "columns=%d " % part.columns_done
    crafted = [
        (part.state.replace(done, "columns=14 "), "state line 1: an integer out of range"),
        ("vertical %scount=0 curves=0 tips=0 drag=0.5\n" % done,
         "state line 1: a state of another air drag"),
        (part.state + "tip 2 0\n", "a line too many"),
        ("", "holds no chart state"),
    ]
    for state, why in crafted:
        bad = dataclasses.replace(part, state=state)
        with pytest.raises(ValueError, match=why) as e:
            _vertical(resume=bad)
        if state:  # the library's refusal: whirl.InvalidInput
            assert isinstance(e.value, whirl.InvalidInput)
            assert str(e.value).startswith("chart_vertical: resume: state line ")
    bad = dataclasses.replace(ellipse_part, state="ellipse columns=2 prev=2 curve=0 failed=0\n")
    with pytest.raises(whirl.InvalidInput, match="chart_ellipse: resume: state line 1: a count "
                                                  "out of range"):
        _ellipse(resume=bad)


# ---- a chart stopped by the command line (whirl periodic --chart ... -o FILE), resumed here ----

SIGNAL_RUN = os.path.join(REPO, "tests", "tools", "signal_run.py")
HANGING = ["--chart", "hanging", "--links", "2", "--omega-min", "1", "--omega-max", "6",
           "--omega-count", "250", "--amp-max", "0.8", "--amp-rows", "20"]
ELLIPSE = ["--chart", "ellipse", "--links", "2", "--eps", "0.05", "--mode", "2", "--side", "-1",
           "--omega-min", "3.9", "--omega-max", "4.2", "--omega-count", "8"]


def _hanging(**kw):
    return whirl.chart_vertical(1, 6, 0.8, links=2, columns=250, rows=20, **kw)


def _ellipse8(**kw):
    return whirl.chart_ellipse(3.9, 4.2, 0.05, links=2, mode=2, side=-1, columns=8, **kw)


def _cli_stopped(tmp_path, args, name):
    """The chart file of whirl periodic ARGS stopped by SIGINT halfway through (once it has used
    half the processor time of the whole chart's run, on one thread: tests/tools/signal_run.py,
    the stop after as much work on a loaded machine, or under the sanitizers, as on an idle
    one), and the same file resumed by the command line."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([PROGRAM, "periodic", *args, "-o", str(tmp_path / (name + "-full.csv"))],
                   env=env, check=True, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = 0.5 * (after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    out = tmp_path / (name + ".csv")
    report = tmp_path / (name + ".report")
    p = subprocess.run([sys.executable, SIGNAL_RUN, str(report), "INT", str(cpu), PROGRAM,
                        "periodic", *args, "-o", str(out)], env=env, capture_output=True,
                       text=True)
    assert p.returncode == 130 and "early=0" in report.read_text(), (p.stderr,
                                                                    report.read_text())
    assert "# found: interrupted after " in out.read_text()
    resumed = tmp_path / (name + "-cli.csv")
    resumed.write_bytes(out.read_bytes())
    subprocess.run([PROGRAM, "periodic", *args, "-o", str(resumed), "--resume"], env=env,
                   check=True, stderr=subprocess.DEVNULL)
    return out, whirl.read_csv(resumed)


def test_python_resumes_the_command_lines_stopped_vertical_chart(tmp_path):
    stopped, cli = _cli_stopped(tmp_path, HANGING, "hanging")
    before = stopped.read_bytes()
    resumed = _hanging(resume=stopped)
    assert stopped.read_bytes() == before  # read, not written
    # the command line's own resume, bit for bit, and the chart never stopped, field for field
    assert resumed.points.size == len(cli) > 0
    for name in ("curve", "edge", "omega", "amplitude", "err"):
        assert resumed.points[name].tobytes() == cli[name].astype(
            resumed.points[name].dtype).tobytes(), name
    _same_chart(resumed, _hanging())
    # resumed from the file, then stopped again here and resumed from that
    part = _stopped_at(_hanging, 230, resume=stopped)  # the file stopped about rate 125
    assert part.interrupted and part.columns_done >= 230
    _same_chart(_hanging(resume=part), resumed)


def test_python_resumes_the_command_lines_stopped_ellipse_chart(tmp_path):
    stopped, cli = _cli_stopped(tmp_path, ELLIPSE, "ellipse")
    resumed = _ellipse8(resume=stopped)
    assert resumed.points.size == len(cli) > 0
    for name in ("curve", "event", "omega", "ellipticity", "err"):
        assert np.array_equal(resumed.points[name], cli[name]), name
    kept = np.isnan(resumed.points["max_modulus"])  # the rows read back: the file has none
    assert 0 < np.count_nonzero(kept) < kept.size and np.all(resumed.points["max_modulus"][
        ~kept] > 0)
    # the chart never stopped (the command line's, whose rows are Python's: test_periodic.py)
    full = whirl.read_csv(tmp_path / "ellipse-full.csv")
    for name in ("omega", "ellipticity", "err"):
        assert resumed.points[name].tobytes() == full[name].tobytes(), name
    failed = int(full.comments[[c.startswith("found: points=") for c in full.comments].index(
        True)].split("failed: ")[1].split()[0])
    assert (resumed.failed, resumed.columns_done, resumed.interrupted) == (failed, 8, False)
    assert resumed.state.startswith("ellipse columns=8 ")


def test_a_file_not_this_charts_is_refused(tmp_path):
    stopped, _ = _cli_stopped(tmp_path, HANGING, "hanging")
    text = stopped.read_text()
    path = str(stopped)

    # other parameters: the first line that differs, as the command line names it
    with pytest.raises(whirl.InvalidInput, match="chart_vertical: resume: '%s' was not written "
                       "by a chart with these options: line 2 has 'to 6' where these options "
                       "write 'to 7'" % path):
        whirl.chart_vertical(1, 7, 0.8, links=2, columns=250, rows=20, resume=stopped)
    with pytest.raises(whirl.InvalidInput, match="line 1 has 'the hanging' where these options "
                                                 "write 'the inverted'"):
        _hanging(inverted=True, resume=stopped)
    with pytest.raises(whirl.InvalidInput, match="line 1 has 'steps=200 tol=1e-10' where these "
                                                 "options write 'steps=200 tol=1e-09'"):
        _hanging(tol=1e-9, resume=stopped)
    with pytest.raises(whirl.InvalidInput, match="was not written by a chart with these "
                                                 "options: line 1 has 'steps=200 tol=1e-10' "
                                                 "where these options write 'steps=200 "
                                                 "tol=6e-11'"):
        _hanging(length=0.6, resume=stopped)  # in SI units: the tolerance in m
    # another chart's file
    with pytest.raises(whirl.InvalidInput, match="line 1 has "):
        _ellipse8(resume=stopped)
    # crafted lines: the command line's refusals, the line named
    rows = [i for i, line in enumerate(text.split("\n")) if line[:1].isdigit()]
    lines = text.split("\n")
    crafted = {
        "an edge other than 1 or -1": (rows[0], lambda s: s.split(",", 2)[0] + ",2," +
                                       s.split(",", 2)[2]),
        "a negative error": (rows[1], lambda s: s.rsplit(",", 1)[0] + ",-1"),
        "a rate outside the chart": (rows[0], lambda s: ",".join(
            s.split(",")[:2] + ["7"] + s.split(",")[3:])),
        "a comment among the rows": (rows[1], lambda s: "# " + s),
    }
    for why, (i, change) in crafted.items():
        bad = list(lines)
        bad[i] = change(bad[i])
        f = tmp_path / "bad.csv"
        f.write_text("\n".join(bad))
        with pytest.raises(whirl.InvalidInput) as e:
            _hanging(resume=f)
        assert str(e.value) == ("chart_vertical: resume: %s:%d: %s: the file cannot be trusted "
                                "(remove the row, or start the chart afresh)" % (f, i + 1, why))
    # a row removed: the count of its "# found:" line
    f = tmp_path / "short.csv"
    f.write_text("\n".join(lines[:rows[0]] + lines[rows[0] + 1:]))
    with pytest.raises(whirl.InvalidInput, match="rows were removed or added"):
        _hanging(resume=f)
    # the state's lines crafted: the library's refusal of the state
    f = tmp_path / "state.csv"
    f.write_text(text.replace("# state: vertical columns=", "# state: vertical columns=9999"))
    with pytest.raises(whirl.InvalidInput, match="chart_vertical: resume: state line 1: "):
        _hanging(resume=f)
    # no state (cut short), no file, an empty file
    f.write_text("\n".join(line for line in lines if not line.startswith("# state:")))
    with pytest.raises(whirl.InvalidInput, match="holds no chart state"):
        _hanging(resume=f)
    with pytest.raises(FileNotFoundError):
        _hanging(resume=tmp_path / "none.csv")
    (tmp_path / "empty.csv").write_text("")
    with pytest.raises(whirl.InvalidInput, match="is empty"):
        _hanging(resume=tmp_path / "empty.csv")
    with pytest.raises(ValueError, match="the command line's charts are of the uniform chain"):
        whirl.chart_vertical(1, 6, 0.8, links=whirl.Chain(lengths=[0.25, 0.75],
                                                          masses=[0.5, 0.5]),
                             columns=250, rows=20, resume=stopped)


@pytest.mark.parametrize("mass", [None, 0.05, 1.0])
def test_a_finished_file_in_si_units_is_the_chart(tmp_path, mass):
    # SI units, with --mass or without it (M = 1 kg assumed, a line saying so, which a call
    # without mass expects; --mass 1 writes no such line and is the call with mass=1.0): a
    # finished file resumed is the chart, nothing computed
    out = tmp_path / "si.csv"
    extra = [] if mass is None else ["--mass", str(mass)]
    subprocess.run([PROGRAM, "periodic", "--chart", "hanging", "--links", "2", "--omega-min",
                    "1.5Hz", "--omega-max", "2.5Hz", "--omega-count", "6", "--amp-max", "5cm",
                    "--amp-rows", "8", "--length", "0.6", *extra, "-o", str(out)], check=True)
    kw = dict(links=2, columns=6, rows=8, length=0.6, mass=mass)
    full = whirl.chart_vertical("1.5Hz", "2.5Hz", "5cm", **kw)
    calls = []
    resumed = whirl.chart_vertical("1.5Hz", "2.5Hz", "5cm", resume=out,
                                   progress=lambda d, t: calls.append(d), **kw)
    assert calls == [6] and resumed.points.size > 0  # the rates all done already
    _same_chart(resumed, full)
    # the other mass's file: the units line differs
    with pytest.raises(whirl.InvalidInput, match="line 4 has "):
        whirl.chart_vertical("1.5Hz", "2.5Hz", "5cm", resume=out,
                             **dict(kw, mass=0.07 if mass else 0.05))
