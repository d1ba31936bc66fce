"""The hand-swung chain (whirl/driven.h, whirl/regime.h): the pivot driven on a horizontal
circle of radius drive_radius at rate omega, with air drag; its trailing steady shapes, and
spin-ups from rest. Positions in the frame co-rotating at omega, the pivot at
(drive_radius, 0, 0). Units as everywhere (see whirl.Units): dimensionless by default (rates in
sqrt(g/L), times in sqrt(L/g), lengths in L), SI with length/mass/gravity or units given."""
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _lib
from ._lib import ffi, lib, check, as_int, as_float
from .steady import POINTS_MAX, Chain, Units, _chain, _mode, links_count, units_of
from .dynamics import _choice, _FRAMES, _method


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class DrivenShape(_lib.Result):
    """A steady shape of the hand-swung chain: arrays ``s`` (arclength), ``x``, ``y``, ``z``
    (co-rotating frame, z from the pivot) and ``tension`` from the pivot to the free end;
    ``omega``; ``mode`` (the mode asked for: the free shape that seeded the continuation; None
    from a tip_guess), ``node_count`` (node count of the shape found, the pivot included),
    ``tip`` (3), ``tip_r``, ``top_force`` (3), ``top_tension``, ``residual`` (how far the
    integrated top lands from the pivot [L]), ``units``."""

    omega: float
    mode: Optional[int]
    node_count: int
    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    tension: np.ndarray
    tip: np.ndarray
    tip_r: float
    top_force: np.ndarray
    top_tension: float
    residual: float
    units: Units = field(default_factory=Units)

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # whirl driven's columns and summary line
        tip_x, tip_y, tip_z = (float(v) for v in self.tip)
        return ({"s": self.s, "x": self.x, "y": self.y, "z": self.z, "tension": self.tension},
                {"omega": self.omega, "mode": self.mode, "node_count": self.node_count,
                 "tip_x": tip_x, "tip_y": tip_y, "tip_z": tip_z, "tip_r": self.tip_r,
                 "top_tension": self.top_tension, "residual": self.residual})

    def __repr__(self) -> str:
        return "DrivenShape(omega=%g, node_count=%d, tip=(%.6g, %.6g, %.6g))" % (
            self.omega, self.node_count, *self.tip)


def _params(omega: float, drive_radius: float, air_drag: float, air_drag_quadratic: float,
            tip_mass: float, u: Units) -> Any:
    p = ffi.new("whirl_driven_params *")
    p.omega = as_float(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    p.drive_radius = as_float(drive_radius, "drive_radius", nonnegative=True,
                              kind="length", units=u) / u.length
    p.air_drag = as_float(air_drag, "air_drag", nonnegative=True, kind="drag",
                          units=u) / u.drag
    p.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic",
                                    nonnegative=True, kind="drag2", units=u) / u.drag2
    p.tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True, kind="mass", units=u) / u.mass
    return p


def driven(omega: float, mode: Optional[int], drive_radius: float, air_drag: float = 0.0,
           air_drag_quadratic: float = 0.0, side: int = 1, links: Union[None, int, Chain] = None,
           tip_mass: float = 0.0, points: int = 201, tip_guess: Optional[Sequence[float]] = None,
           length: Optional[float] = None, mass: Optional[float] = None,
           gravity: Optional[float] = None, units: Optional[Units] = None) -> DrivenShape:
    """The steady shape of the hand-swung chain of ``mode`` at ``omega`` [sqrt(g/L), or rad/s]
    with the pivot on a circle of radius ``drive_radius`` [L, or m] and air drag (linear
    ``air_drag``, quadratic ``air_drag_quadratic``, per unit length, in the units of --drag and
    --drag-quadratic), its tip on the pivot's side of the axis (side = 1) or opposite (-1), as
    ``whirl driven``. links=None: the continuum sampled at ``points`` arclengths (tip_mass [M,
    or kg] at its end); links=N or a Chain: the N-link chain. tip_guess=(X, Y): instead, the
    shape whose tip is found by Newton's method from that horizontal tip position (``mode`` may
    then be None; the result has its own node count). Returns a DrivenShape; whirl.InvalidInput
    (EDOM) if the shape does not exist or cannot be reached by continuation, whirl.Error
    (EMAXITER) if Newton does not converge from tip_guess. mode=0: the near-axis shape, the
    hanging chain pulled out by the drive (the smallest of the triple-valued response past the
    fold; side plays no part)."""
    u = units_of(length, mass, gravity, units)
    if tip_guess is None or mode is not None:
        # seeded by the continuum's shape; mode 0: the near-axis shape (the hanging chain's)
        mode = 0 if as_int(mode, "mode") == 0 else _mode(mode, None, lib.WHIRL_MODE_MAX)
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    chain = _chain(links, 0.0)
    p = _params(omega, drive_radius, air_drag, air_drag_quadratic, tip_mass, u)
    if chain is not None and p.tip_mass:
        raise ValueError("tip_mass applies to the continuum; an N-link chain carries its masses")
    c = ffi.NULL if chain is None else chain._c
    info = ffi.new("whirl_driven_info *")
    with _lib.interruptible("driven"):
        if tip_guess is None:
            status = lib.whirl_driven_mode(c, p, mode, side, info)
        else:
            guess = _lib.as_array(tip_guess, "tip_guess", shape=(2,), kind="length",
                                  units=u) / u.length
            status = lib.whirl_driven_solve(c, p, _lib.dptr(guess), info)
    check(status, "driven", u)
    if chain is None:
        n = _lib.bounded(as_int(points, "points", minimum=2), "points", 40, hard=POINTS_MAX)
    else:
        n = chain.n + 1
    s, x, y, z, t = (np.empty(n) for _ in range(5))
    check(lib.whirl_driven_sample(c, p, info.tip, n, *(_lib.dptr(a) for a in (s, x, y, z, t))),
          "driven")
    L, F = u.length, u.force
    out = DrivenShape(omega=info.omega * u.rate, mode=mode, node_count=int(info.nodes),
                      s=s * L, x=x * L, y=y * L, z=z * L, tension=t * F,
                      tip=np.array(list(info.tip)) * L, tip_r=info.tip_r * L,
                      top_force=np.array(list(info.top_force)) * F,
                      top_tension=info.top_tension * F, residual=info.residual * L, units=u)
    _lib.finite("the driven shape", out.omega, out.x, out.y, out.z, out.tension,
                out.top_tension)
    return out


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class SpinUp(_lib.Result):
    """A spin-up from rest (whirl_regime_run): ``state`` ("settled", "periodic",
    "quasiperiodic", "chaotic", "converging", "failed"), ``node_count`` (of the last shape; of
    the steady shape when settled), ``period`` (drive periods), ``t_end`` [T], ``change`` and
    ``remaining`` [L], ``shape_error`` (settled: RMS distance from the boundary-value shape
    [L]), ``bvp_node_count``, ``lyapunov`` [1/T], ``tip`` (co-rotating frame), ``tip_r``,
    ``steps``; with ``every``: the sampled frames ``t`` (times), ``x`` (positions (frames, N,
    3) in the co-rotating frame), ``angle`` (angle of that frame: rotating x by it gives the
    inertial positions); ``units``."""

    state: str
    node_count: int
    period: int
    t_end: float
    change: float
    remaining: float
    shape_error: float
    bvp_node_count: int
    lyapunov: float
    tip: np.ndarray
    tip_r: float
    steps: int
    t: np.ndarray
    angle: np.ndarray
    x: np.ndarray
    units: Units = field(default_factory=Units)

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # one row of whirl regime's columns (the recorded frames aside); a remaining change
        # not estimated (inf) is NaN, as the file's empty field
        tip_x, tip_y, tip_z = (float(v) for v in self.tip)
        remaining = self.remaining if np.isfinite(self.remaining) else np.nan
        return ({"state": self.state, "nodes": self.node_count, "period": self.period,
                 "t_end": self.t_end, "change": self.change, "remaining": remaining,
                 "shape_error": self.shape_error, "bvp_nodes": self.bvp_node_count,
                 "lyapunov": self.lyapunov, "tip_x": tip_x, "tip_y": tip_y, "tip_z": tip_z,
                 "tip_r": self.tip_r, "steps": self.steps}, {})

    def __repr__(self) -> str:
        return "SpinUp(state=%s, node_count=%d, t_end=%g)" % (self.state, self.node_count,
                                                              self.t_end)


# spin_up's keyword parameters: the scale of each (a Units property name, or None: a number)
_PARAMS = {"internal_damping": "damping", "dt": "time", "t_ramp": "time", "t_max": "time",
           "settle_tol": "length", "settle_periods": None, "periodic_tol": "length",
           "lyapunov_periods": None, "chaos_lambda": "rate", "perturb": None, "seed": None}
_INT_PARAMS = ("settle_periods", "lyapunov_periods", "seed")


def spin_up(omega: float, drive_radius: float, links: Union[int, Chain], air_drag: float = 0.0,
            air_drag_quadratic: float = 0.0, method: Optional[str] = None,
            frame: str = "rotating", every: Optional[float] = None,
            length: Optional[float] = None, mass: Optional[float] = None,
            gravity: Optional[float] = None, units: Optional[Units] = None,
            **params: Any) -> SpinUp:
    """Which steady shape a hand-swung chain settles into from rest (``whirl regime`` for one
    point): the N-link chain (``links``: N or a Chain) hangs at rest, the hand brings the top up
    to the circle of radius ``drive_radius`` [L, or m] at rate ``omega`` [sqrt(g/L), or rad/s]
    over t_ramp, with air drag, until the shape in the co-rotating frame stops changing or
    t_max. Further parameters (defaults from whirl_regime_defaults; in the units of the
    command line's options): internal_damping, dt, t_ramp, t_max, settle_tol, settle_periods,
    periodic_tol, lyapunov_periods, chaos_lambda, perturb, seed; method (default rk4), frame
    ("rotating" or "inertial"). every > 0: record the masses every ``every`` [T]. The work is
    bounded (links x t_max / dt <= 1e10). Returns a SpinUp. Ctrl-C raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    chain = links if isinstance(links, Chain) else Chain(links_count(links))
    p = ffi.new("whirl_regime_params *", lib.whirl_regime_defaults(chain.n))
    p.omega = as_float(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    p.drive_radius = as_float(drive_radius, "drive_radius", positive=True,
                              kind="length", units=u) / u.length
    p.air_drag = as_float(air_drag, "air_drag", nonnegative=True, kind="drag",
                          units=u) / u.drag
    p.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic",
                                    nonnegative=True, kind="drag2", units=u) / u.drag2
    p.frame = _choice(frame, "frame", _FRAMES)
    keep = []
    if method is not None:
        keep.append(ffi.new("char[]", _method(method).encode()))
        p.method = keep[-1]
    for key, value in params.items():
        if key not in _PARAMS:
            raise TypeError("spin_up() got an unexpected keyword argument %r" % key)
        if key in _INT_PARAMS:
            setattr(p, key, as_int(value, key, minimum=0))
        else:
            scale = _PARAMS[key]
            v = as_float(value, key, nonnegative=True)
            setattr(p, key, v / getattr(u, scale) if scale else v)
    check(lib.whirl_regime_check(p), "spin_up", u)
    from .dynamics import WORK_MAX
    if p.t_max / p.dt * chain.n > WORK_MAX:
        raise ValueError("the spin-up needs %.3g steps of %d links: links x t_max / dt must be "
                         "<= %g" % (p.t_max / p.dt, chain.n, WORK_MAX))
    w = _lib.check_ptr(lib.whirl_regime_alloc(chain._c), lib.whirl_regime_free)
    frames_t: List[float] = []
    frames_x: List[np.ndarray] = []
    frames_a: List[float] = []
    record = every is not None
    # the observer's times split the steps: without frames, the command line's interval (once
    # per time unit, or t_max / 100 on a short run), so that a run is the command line's run
    interval = (as_float(every, "every", positive=True, kind="time", units=u) / u.time if record
                else min(1.0, p.t_max / 100))
    if record and (p.t_max / interval + 1) * chain.n > WORK_MAX:
        raise ValueError("every asks for %.3g frames of %d links: links x frames must be "
                         "<= %g" % (p.t_max / interval, chain.n, WORK_MAX))
    if record:
        _lib.bounded(int(p.t_max / interval) + 2, "frames (t_max / every)", 24 * chain.n + 16)

    @ffi.callback("whirl_regime_observer")
    def observe(ctx: Any, t: float, angle: float, pivot: Any, x: Any, n: int) -> int:
        if record:
            frames_t.append(t)
            frames_a.append(angle)
            frames_x.append(np.frombuffer(ffi.buffer(x, 24 * n), dtype=np.float64)
                            .reshape(n, 3).copy())
        # the observer is where a run from Python sees Ctrl-C
        return lib.WHIRL_EINTERRUPTED if lib.whirl_stop_requested() else 0

    lib.whirl_regime_observe(w, observe, ffi.NULL, interval)
    res = ffi.new("whirl_regime_result *")
    with _lib.interruptible("spin_up"):
        status = lib.whirl_regime_run(w, p, res)
    check(status, "spin_up", u)
    state = ffi.string(lib.whirl_regime_state_name(res.state)).decode()
    if res.state == lib.WHIRL_REGIME_FAILED:
        raise _lib.Error(5, "the spin-up failed: " + _lib.last_error())
    L = u.length
    return SpinUp(state=state, node_count=int(res.nodes), period=int(res.period),
                  t_end=res.t_end * u.time, change=res.change * L, remaining=res.remaining * L,
                  shape_error=res.shape_error * L, bvp_node_count=int(res.bvp_nodes),
                  lyapunov=res.lyapunov * u.rate, tip=np.array(list(res.tip)) * L,
                  tip_r=res.tip_r * L, steps=int(res.steps),
                  t=np.array(frames_t) * u.time, angle=np.array(frames_a),
                  x=(np.array(frames_x) if frames_x else np.empty((0, chain.n, 3))) * L,
                  units=u)
