"""The chain with its pivot on a periodic path (whirl/periodic.h, ``whirl periodic``): the
periodic motion found by Newton's method on the period map and its Floquet multipliers, a branch
of periodic motions followed in the path's rate or amplitude with its events, and the stability
chart of the vertically shaken chain, and the ellipticity chart of the hand-swung chain.

A pivot path is given by the command line's grammar (whirl_pivot_parse): circle:R, ellipse:A,B,
line:A[,DX,DY,DZ], vertical:A, eight:A,B or fourier:x1c=A,z2s=B,... (lengths in the call's units,
or with a suffix m, cm, mm in SI units), at the rate ``omega``. Units as everywhere (whirl.Units):
rates in sqrt(g/L) or rad/s, lengths in L or m, times in sqrt(L/g) or s; multipliers, growth per
period and e-folding periods are numbers.

The chain may be damped and dragged: ``damping`` (the joints' internal damping), ``air_drag`` and
``air_drag_quadratic`` (the names and units of whirl.stability and whirl.driven; on the command
line ``--damping``, ``--drag`` and ``--drag-quadratic``), the forces of the time integrator
(whirl_periodic_alloc_model). Its multipliers are then not in reciprocal pairs: the verdict does
not use ``reciprocal_err`` (then a distance, not an error), and a branch's torus test is
prod_{i<j} (mu_i mu_j - 1): a complex pair crossing the unit circle."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, check, as_int, as_float
from .steady import Chain, Units, _chain, units_of
from ._chart_resume import (_Saved, _chart_row, _chart_save, _ellipse_row, _read_ellipse,
                            _read_vertical, _resume_from)

_NAMES = {"verdict": lib.whirl_floquet_verdict_name, "edge": lib.whirl_floquet_edge_name,
          "event": lib.whirl_cycle_event_name}


def _name(kind: str, value: int) -> str:
    return ffi.string(_NAMES[kind](value)).decode()


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class PeriodicResult(_lib.Result):
    """A periodic motion and its Floquet multipliers, as ``whirl periodic``: ``pivot`` (the path's
    text), ``omega`` [1/T] and ``period`` [T]; ``x``, ``v`` (shape (N, 3)): the masses'
    positions [L] and velocities [L/T] at t = 0 (inertial frame, z up; the pivot at its place at
    t = 0); ``state``: the library's state vector (whirl_periodic_state_size, dimensionless, for
    a restart: periodic(..., start=result.state)); ``multipliers`` (complex, by decreasing
    modulus) and ``errors`` (each one's error estimate, ``|mu(h/2) - mu(h)| / 15``);
    ``max_modulus`` and its ``max_modulus_err``; ``verdict`` ("stable", "neutral", "unstable"),
    ``growth`` (the largest ``|mu|`` per period when unstable, else 1), ``efold_periods`` and
    ``efold_time`` [T] (0 unless unstable), ``edge`` (how the largest left the unit circle, or
    the nearest edge: "+1", "-1", "complex"; the names of whirl_floquet_edge_name) and
    ``edge_distance`` [rad] (a damped chain's stable motion: 1 - ``max_modulus``);
    ``reciprocal_err`` (0 for the exact conservative chain; the damped chain's multipliers are
    not in pairs, and it is a distance there),
    ``residual``, ``orbit_change``, ``iterations``, ``steps`` (of the finer solve);
    ``monodromy`` (the tangent-space matrix); ``units``."""

    pivot: str
    omega: float
    period: float
    x: np.ndarray
    v: np.ndarray
    state: np.ndarray
    multipliers: np.ndarray
    errors: np.ndarray
    max_modulus: float
    max_modulus_err: float
    verdict: str
    growth: float
    efold_periods: float
    efold_time: float
    edge: str
    edge_distance: float
    reciprocal_err: float
    residual: float
    orbit_change: float
    iterations: int
    steps: int
    monodromy: np.ndarray
    units: Units = field(default_factory=Units)

    def __repr__(self) -> str:
        return ("PeriodicResult(pivot=%r, omega=%g, multipliers=%d, max_modulus=%.10g, "
                "verdict=%s, edge=%s)" % (self.pivot, self.omega, self.multipliers.size,
                                          self.max_modulus, self.verdict, self.edge))


BRANCH_DTYPE = [("event", "U16"), ("omega", "f8"), ("amplitude", "f8"),
                ("max_modulus", "f8"), ("verdict", "U8"), ("edge", "U8"),
                ("fold_test", "f8"), ("flip_test", "f8"), ("torus_test", "f8"),
                ("err", "f8"), ("arclength", "f8"), ("tangent", "f8"),
                ("reciprocal_err", "f8"), ("residual", "f8"), ("iterations", "i8")]


@dataclass(eq=False)
class PeriodicBranch(_lib.Result):
    """A branch of periodic motions, as ``whirl periodic --omega-min ... --omega-max`` (or
    --amp-max): ``rows`` a structured array, one row per point and event in the order of the
    branch, fields event ("point", "fold", "branch", "period-doubling", "torus"), omega [1/T],
    amplitude [L], max_modulus, verdict, edge, fold_test, flip_test, torus_test, err (an
    event's error estimate in the parameter [1/T or L]; 0 for a point), arclength, tangent,
    reciprocal_err, residual, iterations; ``events`` the rows that are events; ``parameter``
    ("omega" or "amplitude"); ``ended`` ("left the range", "max_points", or "interrupted": Ctrl-C
    with keep_interrupted=True, the rows so far); ``state`` the last point's state vector;
    ``units``."""

    pivot: str
    parameter: str
    rows: np.ndarray
    ended: str
    state: np.ndarray
    units: Units = field(default_factory=Units)

    @property
    def events(self) -> np.ndarray:
        return self.rows[self.rows["event"] != "point"]

    def __repr__(self) -> str:
        return "PeriodicBranch(pivot=%r, parameter=%s, rows=%d, events=%d, ended=%s)" % (
            self.pivot, self.parameter, self.rows.size, self.events.size, self.ended)


CHART_DTYPE = [("curve", "i8"), ("edge", "i8"), ("omega", "f8"), ("amplitude", "f8"),
               ("err", "f8")]


@dataclass(eq=False)
class Chart(_lib.Result):
    """The stability chart of the chain shaken vertically, A cos(omega t), as
    ``whirl periodic --chart``: ``points`` a structured array (curve from 1, edge +1 (a
    multiplier pair through +1) or -1 (through -1), omega [1/T], amplitude [L], err [L])
    ordered by curve, then rate, as the command line's CSV; ``inverted``; ``curves`` the count;
    ``interrupted`` (Ctrl-C with keep_interrupted=True, or the ``partial`` of the
    KeyboardInterrupt: the points of the rates finished); ``columns_done`` the rates finished;
    ``state`` the chart's state after them (the text of the command line's "# state:" lines,
    whirl_chart_vertical_resume: what chart_vertical(..., resume=chart) goes on from);
    ``units``."""

    inverted: bool
    links: int
    points: np.ndarray
    units: Units = field(default_factory=Units)
    interrupted: bool = False
    columns_done: int = 0
    state: str = field(default="", repr=False)
    _params: Dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def curves(self) -> int:
        return int(np.unique(self.points["curve"]).size)

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # the fields' rule (whirl.columns.split) without the state and the parameters kept
        from .columns import split
        return split({f: getattr(self, f) for f in ("inverted", "links", "points", "units",
                                                    "interrupted", "columns_done")})

    def __repr__(self) -> str:
        return "Chart(%s, links=%d, points=%d, curves=%d%s)" % (
            "inverted" if self.inverted else "hanging", self.links, self.points.size, self.curves,
            ", interrupted" if self.interrupted else "")


def _path(pivot: str, omega: Any, dim: int, u: Units) -> Any:
    if not isinstance(pivot, str):
        raise TypeError("pivot must be a text such as 'ellipse:1cm,0.6cm', got %r" % (pivot,))
    w = as_float(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    path = ffi.new("whirl_pivot_path *")
    status = lib.whirl_pivot_parse(pivot.encode("utf-8", "replace"), w,
                                   u.length if u.physical else 0.0, dim, path)
    check(status, "pivot", u)
    return path


def _arr(ptr: Any, n: int) -> np.ndarray:
    return np.frombuffer(ffi.buffer(ptr, 8 * n), dtype=np.float64).copy()


def _start(ws: Any, start: Any, chain: Chain, path: Any, dim: int, mode: int, side: int,
           u: Units, model: Any) -> np.ndarray:
    """The start state: "hanging", "inverted", "steady" (the circle drive's steady shape of
    ``mode``) or a state vector (a PeriodicResult's ``state``)."""
    size = int(lib.whirl_periodic_state_size(ws))
    y = np.empty(size)
    if not isinstance(start, str):
        a = _lib.as_array(start, "start", shape=(size,))
        y[:] = a
        return y
    if start in ("hanging", "inverted"):
        check(lib.whirl_periodic_start_vertical(ws, int(start == "inverted"), _lib.dptr(y)),
              "periodic", u)
        return y
    if start != "steady":
        raise ValueError("start must be 'hanging', 'inverted', 'steady' or a state vector, got %r"
                         % (start,))
    r = path.c[0][0]
    circle = ffi.new("whirl_pivot_path *")
    if (dim != 3 or not r > 0 or lib.whirl_pivot_circle(circle, path.omega, r) != 0
            or bytes(ffi.buffer(circle)) != bytes(ffi.buffer(path))):
        raise ValueError("start='steady' needs pivot circle:R with R > 0 and dim 3 (the steady "
                         "shapes of the circle drive)")
    mode = as_int(mode, "mode", minimum=1, maximum=chain.n)
    st = _lib.check_ptr(lib.whirl_stability_alloc(chain.n), lib.whirl_stability_free)
    m = ffi.new("whirl_model *")
    m.chain, m.dim, m.frame, m.omega, m.drive_radius = chain._c, 3, 1, path.omega, r
    m.air_drag, m.air_drag_quadratic = model.air_drag, model.air_drag_quadratic
    m.internal_damping = model.internal_damping
    growth = ffi.new("double *")
    check(lib.whirl_stability_driven_mode(st, m, mode, side, ffi.NULL, growth),
          "periodic: the steady start", u)
    x, yy, z = (ffi.new("const double **") for _ in range(3))
    lib.whirl_stability_nodes(st, x, yy, z)
    links = np.empty(3 * chain.n)
    check(lib.whirl_shape_links(chain.n, x[0], yy[0], z[0], _lib.dptr(links)), "periodic", u)
    check(lib.whirl_dyn_state_from_shape(lib.whirl_periodic_dyn(ws), 0.0, _lib.dptr(links),
                                         path.omega, _lib.dptr(y)), "periodic: the steady start", u)
    return y


def _setup(pivot: str, omega: Any, links: Union[int, Chain], dim: int, start: Any, mode: int,
           side: int, u: Units, damping: Any = 0.0, air_drag: Any = 0.0,
           air_drag_quadratic: Any = 0.0) -> Any:
    dim = as_int(dim, "dim", minimum=2, maximum=3)
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    chain = _chain(links, 0.0, dense=True)
    assert chain is not None
    path = _path(pivot, omega, dim, u)
    m = ffi.new("whirl_model *")
    m.chain, m.dim = chain._c, dim
    m.internal_damping = as_float(damping, "damping", nonnegative=True, kind="damping",
                                  units=u) / u.damping
    m.air_drag = as_float(air_drag, "air_drag", nonnegative=True, kind="drag", units=u) / u.drag
    m.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic", nonnegative=True,
                                    kind="drag2", units=u) / u.drag2
    ws = _lib.check_ptr(lib.whirl_periodic_alloc_model(m, path), lib.whirl_periodic_free)
    y = _start(ws, start, chain, path, dim, mode, side, u, m)
    return chain, path, ws, y


def _steps(steps: Optional[int]) -> int:
    return 0 if steps is None else as_int(steps, "steps", minimum=8, maximum=16777216)


def periodic(pivot: str, omega: Any, links: Union[int, Chain] = 1, dim: int = 3,
             start: Any = "hanging", mode: int = 1, side: int = 1, steps: Optional[int] = None,
             tol: Optional[float] = None, max_iter: Optional[int] = None,
             differences: bool = False, damping: Any = 0.0, air_drag: Any = 0.0,
             air_drag_quadratic: Any = 0.0, length: Optional[float] = None,
             mass: Optional[float] = None, gravity: Optional[float] = None,
             units: Optional[Units] = None) -> PeriodicResult:
    """The periodic motion of the N-link chain ``links`` (N or a Chain) in ``dim`` 2 (the x-z
    plane) or 3 with its pivot on the path ``pivot`` (text, e.g. "ellipse:1cm,0.6cm") at the
    rate ``omega`` [sqrt(g/L), or rad/s; a text such as "4Hz"], found by Newton's method on the
    period map from ``start`` ("hanging", "inverted", "steady": the circle drive's steady shape
    of ``mode`` on ``side``, or a state vector), with its Floquet multipliers and their error
    estimates from a second solve at twice the steps, as ``whirl periodic --pivot P --omega W``
    (``steps`` per period of the coarser solve, default 400; ``tol`` Newton's test, default
    1e-10; ``max_iter`` default 30; differences=True: the monodromy by central differences;
    ``damping``, ``air_drag``, ``air_drag_quadratic`` the damped and dragged chain, as
    --damping, --drag, --drag-quadratic, in their units). Returns a PeriodicResult. whirl.Error (EMAXITER, with the residual) if Newton's method does
    not converge; whirl.InvalidInput on a bad path (the message names the term); Ctrl-C raises
    KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    with _lib.interruptible("periodic"):
        chain, path, ws, y = _setup(pivot, omega, links, dim, start, mode, side, u, damping,
                                    air_drag, air_drag_quadratic)
        p = ffi.new("whirl_periodic_params *")
        p.steps = _steps(steps)
        p.tol = 0.0 if tol is None else as_float(tol, "tol", positive=True)
        p.max_iter = 0 if max_iter is None else as_int(max_iter, "max_iter", minimum=1,
                                                       maximum=1000)
        p.refine = 1
        p.monodromy = 1 if differences else 0
        r = ffi.new("whirl_periodic_result *")
        status = lib.whirl_periodic_find(ws, _lib.dptr(y), p, r)
    check(status, "periodic", u)
    n = int(r.count)
    k = int(lib.whirl_periodic_tangent_size(ws))
    x = np.empty(3 * chain.n)
    v = np.empty(3 * chain.n)
    check(lib.whirl_dyn_get_state(lib.whirl_periodic_dyn(ws), 0.0, _lib.dptr(y), 0,
                                  _lib.dptr(x), _lib.dptr(v)), "periodic", u)
    res = PeriodicResult(
        pivot=pivot, omega=path.omega * u.rate, period=r.period * u.time,
        x=x.reshape(chain.n, 3) * u.length, v=v.reshape(chain.n, 3) * (u.length * u.rate),
        state=y, multipliers=_arr(r.re, n) + 1j * _arr(r.im, n), errors=_arr(r.err, n),
        max_modulus=r.max_modulus, max_modulus_err=r.max_modulus_err,
        verdict=_name("verdict", r.verdict), growth=r.growth, efold_periods=r.efold_periods,
        efold_time=r.efold_time * u.time, edge=_name("edge", r.edge),
        edge_distance=r.edge_distance, reciprocal_err=r.reciprocal_err, residual=r.residual,
        orbit_change=r.orbit_change, iterations=int(r.iterations), steps=int(r.steps),
        monodromy=_arr(lib.whirl_periodic_monodromy(ws), k * k).reshape(k, k), units=u)
    _lib.finite("the periodic motion", res.omega, res.period, res.x, res.v, res.efold_time)
    return res


@ffi.callback("int(void *, const whirl_cycle_point *)", onerror=lambda *a: 8)
def _branch_row(data: Any, p: Any) -> int:
    rows: List[Any] = ffi.from_handle(data)
    rows.append((_name("event", p.event), p.omega, p.amplitude, p.max_modulus,
                 _name("verdict", p.verdict), _name("edge", p.edge), p.fold_test, p.flip_test,
                 p.torus_test, p.err, p.arclength, p.tangent, p.reciprocal_err, p.residual,
                 p.iterations))
    return 0


def periodic_path(pivot: str, omega: Any = None, links: Union[int, Chain] = 1, dim: int = 3,
                  omega_min: Any = None, omega_max: Any = None, amp_min: Any = None,
                  amp_max: Any = None, up: bool = False, start: Any = "hanging",
                  mode: int = 1, side: int = 1, arc_step: Optional[float] = None,
                  max_points: Optional[int] = None, steps: Optional[int] = None,
                  tol: Optional[float] = None, max_iter: Optional[int] = None,
                  damping: Any = 0.0, air_drag: Any = 0.0, air_drag_quadratic: Any = 0.0,
                  length: Optional[float] = None, mass: Optional[float] = None,
                  gravity: Optional[float] = None, units: Optional[Units] = None,
                  keep_interrupted: bool = False) -> PeriodicBranch:
    """The branch of periodic motions through the one found from ``start`` (as periodic()),
    followed by pseudo-arclength continuation in the path's rate (omega_min, omega_max; the
    start ``omega`` defaults to omega_max) or its amplitude (amp_max, amp_min default 0: the
    path scaled so that its largest Fourier amplitude is the parameter), towards larger values
    with up=True (default smaller), as ``whirl periodic --omega-min A --omega-max B`` (or
    --amp-max; ``arc_step`` its --arc-step, default 0.05; ``max_points`` default 10000). The
    folds of cycles, branch points, period doublings and torus bifurcations are located on the
    way (``damping``, ``air_drag``, ``air_drag_quadratic``: the damped and dragged chain, as
    periodic()). Returns a PeriodicBranch. Ctrl-C raises KeyboardInterrupt, or with
    keep_interrupted=True returns the rows so far (``ended`` "interrupted")."""
    u = units_of(length, mass, gravity, units)
    in_rate = omega_min is not None or omega_max is not None
    in_amp = amp_min is not None or amp_max is not None
    if in_rate == in_amp:
        raise ValueError("a branch follows one parameter: omega_min and omega_max (the rate) or "
                         "amp_max (the amplitude)")
    cp = ffi.new("whirl_cycle_params *")
    if in_rate:
        if omega_min is None or omega_max is None:
            raise ValueError("a branch in the rate needs both omega_min and omega_max")
        lo = as_float(omega_min, "omega_min", positive=True, kind="rate", units=u)
        hi = as_float(omega_max, "omega_max", positive=True, kind="rate", units=u)
        if omega is None:
            omega = hi
        cp.parameter, cp.min, cp.max = 0, lo / u.rate, hi / u.rate
    else:
        if amp_max is None:
            raise ValueError("a branch in the amplitude needs amp_max")
        if omega is None:
            raise ValueError("a branch in the amplitude needs omega")
        lo = 0.0 if amp_min is None else as_float(amp_min, "amp_min", nonnegative=True,
                                                  kind="length", units=u)
        hi = as_float(amp_max, "amp_max", positive=True, kind="length", units=u)
        cp.parameter, cp.min, cp.max = 1, lo / u.length, hi / u.length
    if not cp.max > cp.min:
        raise ValueError("the parameter's range is empty: %s_max must exceed %s_min"
                         % (("omega",) * 2 if in_rate else ("amp",) * 2))
    cp.direction = 1 if up else -1
    cp.step = 0.0 if arc_step is None else as_float(arc_step, "arc_step", positive=True)
    if not cp.step <= 1:
        raise ValueError("arc_step must be <= 1, got %r" % arc_step)
    cp.max_points = 0 if max_points is None else as_int(max_points, "max_points", minimum=2,
                                                        maximum=10000000)
    cp.steps = _steps(steps)
    cp.tol = 0.0 if tol is None else as_float(tol, "tol", positive=True)
    cp.max_iter = 0 if max_iter is None else as_int(max_iter, "max_iter", minimum=1,
                                                    maximum=1000)
    rows: List[Any] = []
    handle = ffi.new_handle(rows)
    ended: Optional[str] = None
    try:
        with _lib.interruptible("periodic_path"):
            chain, path, ws, y = _setup(pivot, omega, links, dim, start, mode, side, u, damping,
                                        air_drag, air_drag_quadratic)
            if in_rate and not cp.min <= path.omega <= cp.max:
                raise ValueError("omega (the branch's start) is outside [omega_min, omega_max]")
            status = lib.whirl_periodic_path(ws, _lib.dptr(y), cp, _branch_row, handle,
                                             ffi.NULL, ffi.NULL)
        check(status, "periodic_path", u)
    except KeyboardInterrupt:
        if not (keep_interrupted and rows):
            raise
        ended = "interrupted"
    out = np.array(rows, dtype=BRANCH_DTYPE)
    out["omega"] *= u.rate
    out["amplitude"] *= u.length
    out["err"] *= u.rate if in_rate else u.length
    points = int(np.count_nonzero(out["event"] == "point"))
    if ended is None:
        ended = "max_points" if points >= (cp.max_points or 10000) else "left the range"
    return PeriodicBranch(pivot=pivot, parameter="omega" if in_rate else "amplitude", rows=out,
                          ended=ended, state=y, units=u)


def chart_vertical(omega_min: Any, omega_max: Any, amp_max: Any, links: Union[int, Chain] = 1,
                   inverted: bool = False, amp_min: Any = None, columns: Optional[int] = None,
                   rows: Optional[int] = None, steps: Optional[int] = None,
                   tol: Any = None, length: Optional[float] = None,
                   mass: Optional[float] = None, gravity: Optional[float] = None,
                   units: Optional[Units] = None, keep_interrupted: bool = False,
                   air_drag: Any = 0.0, progress: Any = None, resume: Any = None) -> Chart:
    """The stability chart of the chain ``links`` (N or a Chain; in the x-z plane) hanging (or,
    inverted=True, standing up) with its pivot shaken vertically, A cos(omega t), over the rates
    [omega_min, omega_max] (``columns`` of them, default 200) and amplitudes up to ``amp_max``
    (``amp_min`` default amp_max / rows; ``rows`` scanned for new curves, default 200), as
    ``whirl periodic --chart hanging|inverted`` (``steps`` its --steps, default 200; ``tol`` its
    --edge-tol [L], default 1e-10 L). The edges are curves A(omega) located per rate to ``tol``.
    ``air_drag`` the linear air drag per unit length (--drag; whirl_chart_vertical_damped: the
    chain needs one mass per length). progress: the rates done (see whirl's progress=). Returns a
    Chart. Ctrl-C raises KeyboardInterrupt (its ``partial``: the chart of the rates finished,
    their points and the chart's state after them), or with keep_interrupted=True returns that
    chart marked interrupted.

    resume: such an interrupted Chart, or the name of a file that
    ``whirl periodic --chart hanging|inverted -o FILE`` wrote (stopped, or finished), as its
    ``--resume``: the points are kept and only the rates after its ``columns_done`` computed,
    from its ``state`` (whirl_chart_vertical_resume), the result equal to the chart that never
    stopped, bit for bit (it may be interrupted and resumed again). The call's parameters and
    units must be the chart's (ValueError naming the first that differs). A file is read and
    checked by the library as the command line reads it (whirl_chart_vertical_read: its header
    must be the one of these options, every row the chart's; read as it stands, not written):
    whirl.InvalidInput naming the first line that differs or the row refused; its chain is
    uniform (``links`` a count). A state the library refuses raises whirl.InvalidInput ("state
    line N: ...")."""
    u = units_of(length, mass, gravity, units)
    chain = _chain(links, 0.0, dense=True)
    assert chain is not None
    p = ffi.new("whirl_chart_params *")
    p.inverted = 1 if inverted else 0
    p.omega_min = as_float(omega_min, "omega_min", positive=True, kind="rate", units=u) / u.rate
    p.omega_max = as_float(omega_max, "omega_max", positive=True, kind="rate", units=u) / u.rate
    if not p.omega_max > p.omega_min:
        raise ValueError("omega_max must exceed omega_min")
    p.amp_max = as_float(amp_max, "amp_max", positive=True, kind="length", units=u) / u.length
    if amp_min is not None:
        p.amp_min = as_float(amp_min, "amp_min", nonnegative=True, kind="length",
                             units=u) / u.length
    if not p.amp_max > p.amp_min:
        raise ValueError("amp_max must exceed amp_min")
    p.columns = 0 if columns is None else as_int(columns, "columns", minimum=2, maximum=1000000)
    p.rows = 0 if rows is None else as_int(rows, "rows", minimum=2, maximum=1000000)
    p.steps = _steps(steps)
    if tol is not None:
        p.tol = as_float(tol, "tol", positive=True, kind="length", units=u) / u.length
    drag = as_float(air_drag, "air_drag", nonnegative=True, kind="drag", units=u) / u.drag
    # the parameters as the chart takes them (the defaults of whirl_chart_params), which a
    # resumed chart must share (the command line's header records the same)
    ncol, nrow = p.columns or 200, p.rows or 200
    params: Dict[str, Any] = {
        "chain": chain, "inverted": bool(inverted), "omega_min": p.omega_min,
        "omega_max": p.omega_max, "columns": ncol, "amp_max": p.amp_max, "rows": nrow,
        "amp_min": p.amp_min or p.amp_max / nrow, "steps": p.steps or 200,
        "tol": p.tol or 1e-10, "air_drag": drag}
    old = _resume_from(resume, Chart, "chart_vertical", params, u,
                       lambda path: _read_vertical(path, p, params["chain"], drag, u, params,
                                                   Chart))
    found: List[Any] = []
    handle = ffi.new_handle(found)
    saved = _Saved(found)
    saved_handle = ffi.new_handle(saved)
    state = ffi.NULL if old is None else old.state.encode("ascii", "replace")
    stop: Optional[KeyboardInterrupt] = None
    with _progress.report(progress, "chart_vertical", ncol, "rates") as rep:
        @ffi.callback("void(void *, const whirl_chart_progress *)")
        def tick(data: Any, at: Any) -> None:
            rep.c_update(at.column)  # the rates done before the one under way
        if old is not None:
            rep.update(old.columns_done)
        try:
            with _lib.interruptible("chart_vertical"):
                status = lib.whirl_chart_vertical_resume(chain._c, 2, p, drag, state, _chart_row,
                                                         handle, tick, ffi.NULL, _chart_save,
                                                         saved_handle)
                rep.reraise()
            check(status, "chart_vertical" if old is None else "chart_vertical: resume", u)
            rep.finish()
        except KeyboardInterrupt as e:
            stop = e
            del found[saved.count:]  # the rows of the rates finished (their state's)
    # by curve, then rate (its column, then omega: a tip's or a fold's points lie between two
    # rates), then as found: the command line's order
    found.sort(key=lambda row: (row[0], row[5], row[2]))
    out = np.array([row[:5] for row in found], dtype=CHART_DTYPE)
    out["omega"] *= u.rate
    out["amplitude"] *= u.length
    out["err"] *= u.length
    if old is not None:  # its rows first within a curve (its rates are the earlier ones)
        out = np.concatenate([old.points, out])
        out = out[np.argsort(out["curve"], kind="stable")]
    chart = Chart(inverted=bool(inverted), links=chain.n, points=out, units=u,
                  interrupted=stop is not None, columns_done=saved.done, state=saved.state,
                  _params=params)
    if stop is not None and not keep_interrupted:
        stop.partial = chart  # type: ignore[attr-defined]
        raise stop
    return chart


ELLIPSE_DTYPE = [("curve", "i8"), ("event", "U16"), ("omega", "f8"), ("ellipticity", "f8"),
                 ("err", "f8"), ("max_modulus", "f8")]


@dataclass(eq=False)
class EllipseChart(_lib.Result):
    """The ellipticity chart of the hand-swung chain, as ``whirl periodic --chart ellipse``:
    ``points`` a structured array in the command line's order (by rate, curve by curve) with
    its columns curve (from 1: a run of rates stable on the circle), event (how the steady shape
    is lost: fold, branch, period-doubling, torus; "none": not lost up to e_max, the row at
    e_max), omega [1/T], ellipticity (e_crit; 0 at an end of a curve on the circle) and err (in
    e, or in omega [1/T] at an end), and max_modulus (the largest multiplier's modulus there);
    ``eps`` the circle's radius [L], ``mode``, ``side``, ``e_max``, ``links``, ``failed`` (the
    continuations that stopped before an event: no row), ``curves`` the count; ``interrupted``
    (Ctrl-C with keep_interrupted=True, or the ``partial`` of the KeyboardInterrupt: the points
    of the rates finished); ``columns_done`` the rates finished; ``state`` the chart's state
    after them (the command line's "# state:" line, whirl_chart_ellipse_resume: what
    chart_ellipse(..., resume=chart) goes on from); ``units``."""

    eps: float
    mode: int
    side: int
    e_max: float
    links: int
    points: np.ndarray
    failed: int = 0
    units: Units = field(default_factory=Units)
    interrupted: bool = False
    columns_done: int = 0
    state: str = field(default="", repr=False)
    _params: Dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def curves(self) -> int:
        return int(np.unique(self.points["curve"]).size)

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # whirl periodic --chart ellipse's columns and comment lines
        return ({name: self.points[name] for name in ("curve", "event", "omega", "ellipticity",
                                                      "err")},
                {"eps": self.eps, "mode": self.mode, "side": self.side, "e_max": self.e_max,
                 "links": self.links, "failed": self.failed, "interrupted": self.interrupted,
                 "columns_done": self.columns_done})

    def __repr__(self) -> str:
        return "EllipseChart(eps=%g, mode=%d, side=%d, links=%d, points=%d, curves=%d%s)" % (
            self.eps, self.mode, self.side, self.links, self.points.size, self.curves,
            ", interrupted" if self.interrupted else "")


def chart_ellipse(omega_min: Any, omega_max: Any, eps: Any, links: Union[int, Chain] = 1,
                  mode: int = 2, side: int = 1, columns: Optional[int] = None,
                  e_max: Optional[float] = None, steps: Optional[int] = None,
                  arc_step: Optional[float] = None, progress: Any = None,
                  keep_interrupted: bool = False, length: Optional[float] = None,
                  mass: Optional[float] = None, gravity: Optional[float] = None,
                  units: Optional[Units] = None, resume: Any = None) -> EllipseChart:
    """The ellipticity chart of the hand-swung chain ``links`` (N or a Chain; 3D): per rate of
    [omega_min, omega_max] (``columns`` of them, default 50), how far the circle of radius
    ``eps`` may be flattened into the ellipse of semi-axes eps and eps (1 - e) before the steady
    shape of ``mode`` (default 2; ``side`` its seed's tip on the pivot's side, 1, or opposite,
    -1) is lost, as ``whirl periodic --chart ellipse --eps A --omega-min W --omega-max W``
    ``[--omega-count N --e-max E --steps S --arc-step H --mode K --side S]``
    (whirl_chart_ellipse): ``e_max`` the largest ellipticity followed (default 1), ``steps``
    the Gauss steps per period (default 400), ``arc_step`` the continuation's largest step
    (default 0.01). Rates and eps in the caller's units, or texts with a unit ("4Hz", "2cm"),
    as the command line takes them. progress: the rates done (see whirl's progress=). Returns
    an EllipseChart. Ctrl-C raises KeyboardInterrupt (its ``partial``: the chart of the rates
    finished, their points and the chart's state after them), or with keep_interrupted=True
    returns that chart marked interrupted.

    resume: such an interrupted EllipseChart, or the name of a file that
    ``whirl periodic --chart ellipse -o FILE`` wrote, as its ``--resume``: the points are kept
    and only the rates after its ``columns_done`` computed, from its ``state``
    (whirl_chart_ellipse_resume), the result equal to the chart that never stopped, bit for bit.
    The call's parameters and units must be the chart's (ValueError naming the first that
    differs); a file is read and checked as chart_vertical's (whirl_chart_ellipse_read), its
    rows' ``max_modulus`` NaN (the file has none); a state the library refuses raises
    whirl.InvalidInput ("state line 1: ...")."""
    u = units_of(length, mass, gravity, units)
    chain = _chain(links, 0.0, dense=True)
    assert chain is not None
    p = ffi.new("whirl_ellipse_chart_params *")
    p.radius = as_float(eps, "eps", positive=True, kind="length", units=u) / u.length
    p.omega_min = as_float(omega_min, "omega_min", positive=True, kind="rate", units=u) / u.rate
    p.omega_max = as_float(omega_max, "omega_max", positive=True, kind="rate", units=u) / u.rate
    if not p.omega_max > p.omega_min:
        raise ValueError("omega_max must exceed omega_min")
    p.mode = as_int(mode, "mode", minimum=1)
    p.side = as_int(side, "side")
    if p.side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % p.side)
    p.columns = 0 if columns is None else as_int(columns, "columns", minimum=2, maximum=1000000)
    if e_max is not None:
        p.e_max = as_float(e_max, "e_max", positive=True)
        if not p.e_max <= 1:
            raise ValueError("e_max must be in (0, 1], got %g" % p.e_max)
    p.steps = _steps(steps)
    if arc_step is not None:
        p.step = as_float(arc_step, "arc_step", positive=True)
        if not p.step <= 1:
            raise ValueError("arc_step must be in (0, 1], got %g" % p.step)
    ncol = p.columns or 50
    # the parameters as the chart takes them (the defaults of whirl_ellipse_chart_params), which
    # a resumed chart must share (the command line's header records the same)
    params: Dict[str, Any] = {
        "chain": chain, "eps": p.radius, "mode": p.mode, "side": p.side,
        "omega_min": p.omega_min, "omega_max": p.omega_max, "columns": ncol,
        "e_max": p.e_max or 1.0, "steps": p.steps or 400, "arc_step": p.step or 0.01}
    old = _resume_from(resume, EllipseChart, "chart_ellipse", params, u,
                       lambda path: _read_ellipse(path, p, params["chain"], u, params,
                                                  EllipseChart))
    found: List[Any] = []
    handle = ffi.new_handle(found)
    saved = _Saved(found, 0 if old is None else old.failed)
    saved_handle = ffi.new_handle(saved)
    state = ffi.NULL if old is None else old.state.encode("ascii", "replace")
    stop: Optional[KeyboardInterrupt] = None
    with _progress.report(progress, "chart_ellipse", ncol, "rates") as rep:
        @ffi.callback("void(void *, const whirl_ellipse_chart_progress *)")
        def tick(data: Any, at: Any) -> None:
            saved.tick_failed = at.failed
            rep.c_update(at.column)  # the rates done before the one under way
        if old is not None:
            rep.update(old.columns_done)
        try:
            with _lib.interruptible("chart_ellipse"):
                status = lib.whirl_chart_ellipse_resume(chain._c, p, state, _ellipse_row, handle,
                                                        tick, ffi.NULL, _chart_save,
                                                        saved_handle)
                rep.reraise()
            check(status, "chart_ellipse" if old is None else "chart_ellipse: resume", u)
            rep.finish()
        except KeyboardInterrupt as e:
            stop = e
            del found[saved.count:]  # the rows of the rates finished (their state's)
    rows = [(curve, "none" if event == 0 else ffi.string(lib.whirl_cycle_event_name(event))
             .decode(), w * u.rate, ellipticity, err * u.rate if column < 0 else err, modulus)
            for event, curve, column, w, ellipticity, err, modulus in found]
    points = np.array(rows, dtype=ELLIPSE_DTYPE)
    if old is not None:  # by rate: its rows are the earlier rates'
        points = np.concatenate([old.points, points])
    out = EllipseChart(eps=p.radius * u.length, mode=p.mode, side=p.side, e_max=p.e_max or 1.0,
                       links=chain.n, points=points, failed=saved.failed, units=u,
                       interrupted=stop is not None, columns_done=saved.done,
                       state=saved.state, _params=params)
    if stop is not None and not keep_interrupted:
        stop.partial = out  # type: ignore[attr-defined]
        raise stop
    return out
