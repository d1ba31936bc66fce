"""The hand-swung chain (whirl/driven.h, whirl/regime.h): the pivot driven on a horizontal
circle of radius drive_radius at rate omega, with air drag; its trailing steady shapes, and
spin-ups from rest. Positions in the frame co-rotating at omega, the pivot at
(drive_radius, 0, 0). Units as everywhere (see whirl.Units): dimensionless by default (rates in
sqrt(g/L), times in sqrt(L/g), lengths in L), SI with length/mass/gravity or units given."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
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
            progress: Any = None, **params: Any) -> SpinUp:
    """Which steady shape a hand-swung chain settles into from rest (``whirl regime`` for one
    point): the N-link chain (``links``: N or a Chain) hangs at rest, the hand brings the top up
    to the circle of radius ``drive_radius`` [L, or m] at rate ``omega`` [sqrt(g/L), or rad/s]
    over t_ramp, with air drag, until the shape in the co-rotating frame stops changing or
    t_max. Further parameters (defaults from whirl_regime_defaults; in the units of the
    command line's options): internal_damping, dt, t_ramp, t_max, settle_tol, settle_periods,
    periodic_tol, lyapunov_periods, chaos_lambda, perturb, seed; method (default rk4), frame
    ("rotating" or "inertial"). every > 0: record the masses every ``every`` [T]. The work is
    bounded (links x t_max / dt <= 1e10). progress: the time run [T] out of t_max plus the
    Lyapunov window's lyapunov_periods drive periods, the longest run (it ends sooner once
    settled; see whirl's progress=). Returns a SpinUp. Ctrl-C raises
    KeyboardInterrupt."""
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

    # the longest run: to t_max, then the Lyapunov window (lyapunov_periods drive periods)
    longest = p.t_max + p.lyapunov_periods * 2 * np.pi / p.omega
    rep = _progress.report(progress, "spin_up", longest * u.time, "s" if u.physical else "T")

    @ffi.callback("whirl_regime_observer")
    def observe(ctx: Any, t: float, angle: float, pivot: Any, x: Any, n: int) -> int:
        rep.c_update(t * u.time)
        if record:
            frames_t.append(t)
            frames_a.append(angle)
            frames_x.append(np.frombuffer(ffi.buffer(x, 24 * n), dtype=np.float64)
                            .reshape(n, 3).copy())
        # the observer is where a run from Python sees Ctrl-C
        return lib.WHIRL_EINTERRUPTED if lib.whirl_stop_requested() else 0

    lib.whirl_regime_observe(w, observe, ffi.NULL, interval)
    res = ffi.new("whirl_regime_result *")
    with rep:
        with _lib.interruptible("spin_up"):
            status = lib.whirl_regime_run(w, p, res)
            rep.reraise()
        check(status, "spin_up", u)
        rep.finish()
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


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class DrivenBranch(_lib.Result):
    """A branch of the hand-swung chain's steady shapes against the rate, in the order of the
    continuation (through its folds): arrays ``omega``, ``tip_x``, ``tip_y``, ``tip_r``,
    ``top_tension``, ``node_count``, ``fold`` (True: the point is a fold, where the branch turns
    back, located where the fold function vanishes), as the columns of
    ``whirl driven --omega-min A --omega-max B``; with stability (the N-link chain) per point
    ``eig_growth`` [1/T], ``index`` and ``verdict`` of its linearisation (else None);
    ``folds`` the folds' rates, in the order found; ``complete``: True if the branch left [omega_min, omega_max]
    (False: it stopped at max_points or on a step that would not converge); ``interrupted``:
    True if Ctrl-C ended it (only with keep_interrupted=True); ``units``."""

    omega: np.ndarray
    tip_x: np.ndarray
    tip_y: np.ndarray
    tip_r: np.ndarray
    top_tension: np.ndarray
    node_count: np.ndarray
    fold: np.ndarray
    folds: np.ndarray
    complete: bool
    eig_growth: Optional[np.ndarray] = None
    index: Optional[np.ndarray] = None
    verdict: Optional[np.ndarray] = None
    interrupted: bool = False
    units: Units = field(default_factory=Units)

    def __len__(self) -> int:
        return int(self.omega.size)

    def __repr__(self) -> str:
        span = (", omega %g..%g" % (self.omega.min(), self.omega.max())) if self.omega.size else ""
        return "DrivenBranch(%d points%s, %d folds%s%s)" % (
            self.omega.size, span, self.folds.size, ", with stability"
            if self.eig_growth is not None else "", ", interrupted" if self.interrupted else "")


def _point_stability(w: Any, chain: Chain, p: Any, q: Any, buf: List[np.ndarray]) -> Any:
    """(status, growth, index) of the linearisation about the branch's shape q of the N-link
    chain (as cmd_driven.c's point_stability)."""
    at = ffi.new("whirl_driven_params *", p[0])
    at.omega = q.omega
    n = chain.n + 1
    status = lib.whirl_driven_sample(chain._c, at, q.tip, n, *(_lib.dptr(a) for a in buf))
    m = ffi.new("whirl_model *")
    m.chain = chain._c
    m.dim = 3
    m.frame = 1  # WHIRL_FRAME_ROTATING
    m.omega = q.omega
    m.drive_radius = p.drive_radius
    m.air_drag = p.air_drag
    m.air_drag_quadratic = p.air_drag_quadratic
    growth = ffi.new("double *")
    index = ffi.new("int *")
    if not status:
        status = lib.whirl_stability_linearise_3d(w, m, *(_lib.dptr(a) for a in buf[1:4]))
    if not status:
        status = lib.whirl_stability_growth(w, growth)
    if not status:
        status = lib.whirl_stability_index(w, index)
    return status, float(growth[0]), int(index[0])


def driven_branch(omega_min: Any, omega_max: Any, drive_radius: Any, mode: int = 1,
                  air_drag: float = 0.0, air_drag_quadratic: float = 0.0, side: int = 1,
                  links: Union[None, int, Chain] = None, tip_mass: Any = 0.0,
                  omega: Any = None, up: bool = False, arc_step: float = 0.02,
                  max_points: int = 100000, stability: Optional[bool] = None,
                  keep_interrupted: bool = False, progress: Any = None,
                  length: Optional[float] = None, mass: Optional[float] = None,
                  gravity: Optional[float] = None,
                  units: Optional[Units] = None) -> DrivenBranch:
    """The branch of the hand-swung chain's steady shapes through the shape of ``mode`` (side
    +1 or -1; mode 0: the near-axis shape) at ``omega`` (default omega_max), followed by
    pseudo-arclength continuation through its folds towards smaller rates (up=True: larger)
    until it leaves [omega_min, omega_max], as
    ``whirl driven --omega-min A --omega-max B [--omega W] [--up] --eps E ...``
    ``[--links N --stability]`` (whirl_driven_branch). Arguments
    as whirl.driven's; ``arc_step``: the largest step of the continuation's arclength (in (0,
    1]), ``max_points``: most points. stability (default: with an N-link chain): the growth,
    index and verdict of the linearisation about every point (the N-link chain only).
    progress: the part of the work done, 0..1 (see whirl's progress=): the continuation's
    reach from the start towards the far end of the range (the first half of the work with
    stability, all of it without), then the points whose stability is computed. Returns a DrivenBranch; whirl.InvalidInput if
    the start shape does not exist. Ctrl-C raises KeyboardInterrupt naming the call (its
    ``partial``: the points so far), or with keep_interrupted=True returns them marked
    interrupted."""
    u = units_of(length, mass, gravity, units)
    mode = 0 if as_int(mode, "mode") == 0 else _mode(mode, None, lib.WHIRL_MODE_MAX)
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    lo = as_float(omega_min, "omega_min", positive=True, kind="rate", units=u) / u.rate
    hi = as_float(omega_max, "omega_max", positive=True, kind="rate", units=u) / u.rate
    if not lo < hi:
        raise ValueError("omega_min must be < omega_max, got %g and %g"
                         % (lo * u.rate, hi * u.rate))
    start_w = hi * u.rate if omega is None else omega
    p = _params(start_w, drive_radius, air_drag, air_drag_quadratic, tip_mass, u)
    if not lo <= p.omega <= hi:
        raise ValueError("omega (the branch's start) must be in [omega_min, omega_max], got %g"
                         % (p.omega * u.rate))
    step = as_float(arc_step, "arc_step", positive=True)
    if step > 1:
        raise ValueError("arc_step must be in (0, 1], got %g" % step)
    cap = _lib.bounded(as_int(max_points, "max_points", minimum=2, maximum=10000000),
                       "max_points", ffi.sizeof("whirl_driven_info") + 8)
    chain = _chain(links, 0.0, dense=stability is not False)
    if chain is not None and p.tip_mass:
        raise ValueError("tip_mass applies to the continuum; an N-link chain carries its masses")
    if stability is None:
        stability = chain is not None
    if stability and chain is None:
        raise ValueError("stability needs links (the N-link chain's linearisation)")
    c = ffi.NULL if chain is None else chain._c
    start = ffi.new("whirl_driven_info *")
    curve = _lib.check_ptr(lib.whirl_driven_curve_alloc(cap), lib.whirl_driven_curve_free)
    stopped = None
    # the work: the continuation's reach over the rates (towards the far end), then the points'
    # stability; 1 in all
    far = hi if up else lo
    share = 0.5 if stability else 1.0
    with _lib.interruptible("driven_branch"), \
            _progress.report(progress, "driven_branch", 1.0, "") as rep:
        status = lib.whirl_driven_mode(c, p, mode, side, start)
        if status == lib.WHIRL_EINTERRUPTED:
            check(status, "driven_branch")
        if status:
            check(status, "driven_branch: start at omega %.17g" % (p.omega * u.rate), u)
        tick = ffi.NULL
        if _progress.active(progress):
            reach = [0.0]

            @ffi.callback("whirl_driven_branch_tick_fn")
            def tick(data: Any, at: Any) -> None:
                # the farthest rate reached so far, as a part of the way to the far end
                rate = at.point[at.n - 1].omega
                if far != p.omega:
                    reach[0] = max(reach[0], min(1.0, (rate - p.omega) / (far - p.omega)))
                rep.c_update(share * reach[0])
        status = lib.whirl_driven_branch_tick(c, p, start, 1 if up else -1, lo, hi, step, curve,
                                              tick, ffi.NULL)
        rep.reraise()
        if status == lib.WHIRL_EINTERRUPTED:
            lib.whirl_stop_clear()
            stopped = _lib.last_error_in(u)
        elif status:
            check(status, "driven_branch", u)
        n = int(curve.n)
        growth = np.empty(n) if stability else None
        index = np.empty(n, dtype=int) if stability else None
        if stopped is None:
            rep.update(share)
        if stability and stopped is None:
            assert chain is not None and growth is not None and index is not None
            w = _lib.check_ptr(lib.whirl_stability_alloc(chain.n), lib.whirl_stability_free)
            buf = [np.empty(chain.n + 1) for _ in range(5)]
            for j in range(n):
                if lib.whirl_stop_requested():
                    lib.whirl_stop_clear()
                    stopped = "stopped by request in the stability of the points"
                    n = j
                    break
                status, growth[j], index[j] = _point_stability(w, chain, p, curve.point[j],
                                                               buf)
                if status == lib.WHIRL_EINTERRUPTED:
                    lib.whirl_stop_clear()
                    stopped = "stopped by request in the stability of the points"
                    n = j
                    break
                check(status, "driven_branch: stability at omega %.17g"
                      % (curve.point[j].omega * u.rate), u)
                rep.update(share + (1 - share) * (j + 1) / n)
        if stopped is None:
            rep.finish()
    pts = [curve.point[j] for j in range(n)]
    L = u.length
    out = DrivenBranch(omega=np.array([q.omega for q in pts]) * u.rate,
                       tip_x=np.array([q.tip[0] for q in pts]) * L,
                       tip_y=np.array([q.tip[1] for q in pts]) * L,
                       tip_r=np.array([q.tip_r for q in pts]) * L,
                       top_tension=np.array([q.top_tension for q in pts]) * u.force,
                       node_count=np.array([q.nodes for q in pts], dtype=int),
                       fold=np.array([bool(curve.fold[j]) for j in range(n)], dtype=bool),
                       folds=np.array(list(curve.fold_omega)[:curve.n_folds]) * u.rate,
                       complete=bool(curve.complete) and stopped is None,
                       interrupted=stopped is not None, units=u)
    if stability:
        assert growth is not None and index is not None
        out.eig_growth = growth[:n] * u.rate
        out.index = index[:n]
        out.verdict = np.array([ffi.string(lib.whirl_verdict_name(
            lib.whirl_verdict_linear(g, i))).decode() for g, i in zip(growth[:n], index[:n])],
            dtype=str)
    _lib.finite("the driven branch", out.omega, out.tip_r, out.top_tension)
    if stopped is not None and not keep_interrupted:
        e = KeyboardInterrupt("whirl: driven_branch interrupted (%s): %d points" % (stopped, n))
        e.partial = out  # type: ignore[attr-defined]
        raise e
    return out
