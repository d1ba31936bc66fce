"""The stability charts resumed (chart_vertical and chart_ellipse with resume=): the callbacks
that gather a chart's rows and the state saved after each finished rate
(whirl_chart_save_fn), the check of a chart to resume against the call, and the reading of a
chart written by ``whirl periodic --chart ... -o FILE`` (whirl_chart_vertical_read,
whirl_chart_ellipse_read: the command line's --resume, every rule its own)."""
from __future__ import annotations

import os
import re
from typing import Any, Callable, Dict, List

from ._lazy import numpy as np
from . import _lib
from ._lib import ffi, lib
from .steady import Chain, Units


@ffi.callback("int(void *, const whirl_chart_point *)", onerror=lambda *a: 8)
def _chart_row(data: Any, p: Any) -> int:
    rows: List[Any] = ffi.from_handle(data)
    rows.append((p.curve + 1, 1 if p.kind == 0 else -1, p.omega, p.amplitude, p.err, p.column))
    return 0


@ffi.callback("int(void *, const whirl_ellipse_point *)", onerror=lambda *a: 8)
def _ellipse_row(data: Any, p: Any) -> int:
    rows: List[Any] = ffi.from_handle(data)
    rows.append((p.event, p.curve + 1, p.column, p.omega, p.ellipticity, p.err, p.max_modulus))
    return 0


class _Saved:
    """The state a chart's save callback (whirl_chart_save_fn) was last handed: the rates
    finished, the state's text and the rows handed out until then (those of the rates
    finished: a rate's rows come before its state)."""

    def __init__(self, rows: List[Any], failed: int = 0) -> None:
        self.rows = rows
        self.done = 0
        self.state = ""
        self.count = 0
        self.failed = failed       # the ellipse chart's failed continuations at the save
        self.tick_failed = failed  # and at its last tick (the state's until the first)


@ffi.callback("int(void *, int, const char *)", onerror=lambda *a: 8)
def _chart_save(data: Any, done: int, state: Any) -> int:
    saved: _Saved = ffi.from_handle(data)
    saved.done, saved.state = done, ffi.string(state).decode("ascii")
    saved.count, saved.failed = len(saved.rows), saved.tick_failed
    return 0


def _resume_from(resume: Any, kind: type, what: str, params: Dict[str, Any], u: Units,
                 read: Callable[[str], Any]) -> Any:
    """The chart to resume (None: none), checked against this call: a file's name (read(path):
    the library reads and checks it), or a chart of kind that what returned, with the same
    parameters and units (ValueError naming the first difference); TypeError for anything else.
    The state itself the library checks (whirl_chart_vertical_resume,
    whirl_chart_ellipse_resume: "state line N: ...")."""
    if resume is None:
        return None
    if isinstance(resume, (str, os.PathLike)):
        return read(os.fspath(resume))
    if not isinstance(resume, kind):
        raise TypeError("resume must be the name of a file of whirl periodic --chart, or the "
                        "%s that %s returned (keep_interrupted=True) or that its "
                        "KeyboardInterrupt holds (partial), got %s"
                        % (kind.__name__, what, type(resume).__name__))
    chart: Any = resume
    if not chart.state:
        raise ValueError("resume: the %s holds no chart state (not one that %s returned)"
                         % (kind.__name__, what))
    if chart.units != u:  # first: the parameters kept are dimensionless
        raise ValueError("resume: the chart is in %r where this call has %r: resume it in the "
                         "units it was begun in" % (chart.units, u))
    scale = {"omega_min": u.rate, "omega_max": u.rate, "amp_min": u.length,
             "amp_max": u.length, "tol": u.length, "eps": u.length, "air_drag": u.drag}
    for name, value in params.items():
        if name not in chart._params:
            raise ValueError("resume: the %s records no %s (not one that %s returned)"
                             % (kind.__name__, name, what))
        if not _lib.same(chart._params[name], value):
            s = scale.get(name, 1)  # in the caller's units
            was, now = chart._params[name], value
            raise ValueError("resume: the chart was computed with %s=%r where this call has "
                             "%r: resume it with the parameters it was begun with"
                             % (name, was * s if s != 1 else was, now * s if s != 1 else now))
    return chart




def _file(path: Any, chain: Chain, what: str) -> bytes:
    """The bytes of a chart's file (as they stand: the command line renames a finished file
    into place, whole); the command line's charts are of the uniform chain."""
    if chain != Chain(chain.n):
        raise ValueError("%s: resume: the command line's charts are of the uniform chain "
                         "(--links N): give links as a count" % what)
    with open(path, "rb") as f:
        return f.read()


def _units(u: Units, data: bytes) -> List[Any]:
    # physical, length, mass, gravity, mass_given: a call in SI units with mass 1 kg is the
    # command line's run without --mass (M = 1 kg assumed, the file's line "# mass: M=1 kg
    # assumed") or with --mass 1 (no such line); the file tells which, and the library then
    # checks the rest of its header against the call
    assumed = b"\n# mass: M=1 kg assumed " in data.split(b"\ncurve,", 1)[0]
    return [int(u.physical), u.length, u.mass, u.gravity,
            0 if u.physical and u.mass == 1.0 and assumed else 1]


def _read_vertical(path: str, p: Any, chain: Chain, drag: float, u: Units,
                   params: Dict[str, Any], make: Callable[..., Any]) -> Any:
    """The chart of the file at path (whirl_chart_vertical_read): its rows (in the file's
    units, the call's: its header says so) and its state, as a Chart made by make."""
    what = "chart_vertical"
    data = _file(path, chain, what)
    rows: List[Any] = []
    saved = _Saved(rows)
    status = lib.whirl_chart_vertical_read(data, len(data), os.fsencode(path), p, chain.n, drag,
                                           *_units(u, data), _chart_row, ffi.new_handle(rows),
                                           _chart_save, ffi.new_handle(saved))
    if status:
        raise _lib.error(status, "%s: resume: %s" % (what, _lib.last_error()))
    from .periodic import CHART_DTYPE
    points = np.array([row[:5] for row in rows], dtype=CHART_DTYPE)
    return make(inverted=params["inverted"], links=chain.n, points=points, units=u,
                interrupted=saved.done < params["columns"], columns_done=saved.done,
                state=saved.state, _params=params)


def _read_ellipse(path: str, p: Any, chain: Chain, u: Units, params: Dict[str, Any],
                  make: Callable[..., Any]) -> Any:
    """The chart of the file at path (whirl_chart_ellipse_read), as an EllipseChart made by
    make: max_modulus NaN on its rows (the file has none)."""
    what = "chart_ellipse"
    data = _file(path, chain, what)
    rows: List[Any] = []
    saved = _Saved(rows)
    status = lib.whirl_chart_ellipse_read(data, len(data), os.fsencode(path), p, chain.n,
                                          *_units(u, data), _ellipse_row, ffi.new_handle(rows),
                                          _chart_save, ffi.new_handle(saved))
    if status:
        raise _lib.error(status, "%s: resume: %s" % (what, _lib.last_error()))
    from .periodic import ELLIPSE_DTYPE
    points = np.array([(curve, "none" if event == 0 else ffi.string(
        lib.whirl_cycle_event_name(event)).decode(), w, e, err, modulus)
        for event, curve, column, w, e, err, modulus in rows], dtype=ELLIPSE_DTYPE)
    failed = re.search(r" failed=(\d+)", saved.state)  # the state's (whirl_chart_ellipse_resume)
    return make(eps=params["eps"] * u.length, mode=params["mode"], side=params["side"],
                e_max=params["e_max"], links=chain.n, points=points,
                failed=int(failed.group(1)) if failed else 0, units=u,
                interrupted=saved.done < params["columns"], columns_done=saved.done,
                state=saved.state, _params=params)
