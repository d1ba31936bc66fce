"""The stability charts resumed (chart_vertical and chart_ellipse with resume=, as ``whirl
periodic --chart ... --resume``): a chart stopped by Ctrl-C (SIGINT sent from its progress
callback at a chosen rate: the library's stop request, polled within a monodromy) and resumed
from the interrupted result equals the chart that never stopped, field for field and bit for
bit, at every rate it can stop at; a result of other parameters, units or kind, or a state the
library refuses, is refused with one exception naming the difference."""
import dataclasses
import os
import signal

import numpy as np
import pytest

import whirl


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


@pytest.mark.parametrize("at", [1, 2])
def test_an_ellipse_chart_stopped_and_resumed_is_the_whole_chart(at):
    full = _ellipse()
    part = _stopped_at(_ellipse, at)
    assert part.interrupted and at <= part.columns_done < 4
    assert part.state.startswith("ellipse columns=%d " % part.columns_done)
    assert part.points.size < full.points.size
    _same_chart(_ellipse(resume=part), full)


def test_a_resume_of_other_parameters_is_refused():
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
    with pytest.raises(TypeError, match="resume must be the Chart that chart_vertical"):
        _vertical(resume=_stopped_at(_ellipse, 2))
    with pytest.raises(TypeError, match="resume must be the EllipseChart"):
        _ellipse(resume=part)
    with pytest.raises(TypeError, match="resume must be the Chart"):
        _vertical(resume=part.state)
    with pytest.raises(ValueError, match="computed with side=-1 where this call has 1"):
        whirl.chart_ellipse(3.95, 4.1, 0.05, links=2, mode=2, side=1, columns=4,
                            resume=_stopped_at(_ellipse, 2))


def test_a_state_the_library_refuses():
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
    ell = _stopped_at(_ellipse, 2)
    bad = dataclasses.replace(ell, state="ellipse columns=2 prev=2 curve=0 failed=0\n")
    with pytest.raises(whirl.InvalidInput, match="chart_ellipse: resume: state line 1: a count "
                                                  "out of range"):
        _ellipse(resume=bad)
