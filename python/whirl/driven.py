"""The hand-swung chain (whirl/driven.h, whirl/regime.h): the pivot driven on a horizontal
circle of radius drive_radius at rate omega, with air drag; its trailing steady shapes, and
spin-ups from rest. Dimensionless units (L = M = g = 1): rates in sqrt(g/L), times in
sqrt(L/g); positions in the frame co-rotating at omega, the pivot at (drive_radius, 0, 0)."""
import numpy as np

from . import _lib
from ._lib import ffi, lib, check, as_int, as_float
from .steady import Chain, _chain, _mode
from .dynamics import _choice, _FRAMES


class DrivenShape:
    """A steady shape of the hand-swung chain: arrays ``s`` (arclength), ``x``, ``y``, ``z``
    (co-rotating frame, z from the pivot) and ``tension`` from the pivot to the free end; ``tip``
    (3), ``tip_r``, ``top_force`` (3), ``top_tension``, ``nodes`` (node count, the pivot
    included), ``residual`` (how far the integrated top lands from the pivot [L])."""

    def __repr__(self):
        return "DrivenShape(omega=%g, nodes=%d, tip=(%.6g, %.6g, %.6g))" % (
            self.omega, self.nodes, *self.tip)


def _params(omega, drive_radius, air_drag, air_drag_quadratic, tip_mass):
    p = ffi.new("whirl_driven_params *")
    p.omega = as_float(omega, "omega", positive=True)
    p.drive_radius = as_float(drive_radius, "drive_radius", nonnegative=True)
    p.air_drag = as_float(air_drag, "air_drag", nonnegative=True)
    p.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic", nonnegative=True)
    p.tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True)
    return p


def driven(omega, mode, drive_radius, air_drag=0.0, air_drag_quadratic=0.0, side=1,
           links=None, tip_mass=0.0, points=201, tip_guess=None):
    """The steady shape of the hand-swung chain of ``mode`` at ``omega`` [sqrt(g/L)] with the
    pivot on a circle of radius ``drive_radius`` [L] and air drag (linear ``air_drag``,
    quadratic ``air_drag_quadratic``, per unit length), its tip on the pivot's side of the axis
    (side = 1) or opposite (-1), as ``whirl driven``. links=None: the continuum sampled at
    ``points`` arclengths (tip_mass [M] at its end); links=N or a Chain: the N-link chain.
    tip_guess=(X, Y): instead, the shape whose tip is found by Newton's method from that
    horizontal tip position (``mode`` may then be None; the result has its own node count).
    Returns a DrivenShape; whirl.Error (EDOM) if the shape does not exist or cannot be reached
    by continuation, EMAXITER if Newton does not converge from tip_guess."""
    if tip_guess is None or mode is not None:
        mode = _mode(mode, None, lib.WHIRL_MODE_MAX)  # seeded by the continuum's shape
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    chain = _chain(links, 0.0)
    p = _params(omega, drive_radius, air_drag, air_drag_quadratic, tip_mass)
    if chain is not None and p.tip_mass:
        raise ValueError("tip_mass applies to the continuum; an N-link chain carries its masses")
    c = ffi.NULL if chain is None else chain._c
    info = ffi.new("whirl_driven_info *")
    if tip_guess is None:
        check(lib.whirl_driven_mode(c, p, mode, side, info))
    else:
        guess = _lib.as_array(tip_guess, "tip_guess", shape=(2,))
        check(lib.whirl_driven_solve(c, p, _lib.dptr(guess), info))
    n = as_int(points, "points", minimum=2) if chain is None else chain.n + 1
    s, x, y, z, t = (np.empty(n) for _ in range(5))
    check(lib.whirl_driven_sample(c, p, info.tip, n, *(_lib.dptr(a) for a in (s, x, y, z, t))))
    out = DrivenShape()
    out.omega, out.mode = info.omega, info.nodes
    out.s, out.x, out.y, out.z, out.tension = s, x, y, z, t
    out.tip = np.array(list(info.tip))
    out.tip_r = info.tip_r
    out.top_force = np.array(list(info.top_force))
    out.top_tension = info.top_tension
    out.nodes = info.nodes
    out.residual = info.residual
    return out


class SpinUp:
    """A spin-up from rest (whirl_regime_run): ``state`` ("settled", "periodic",
    "quasiperiodic", "chaotic", "converging", "failed"), ``nodes`` (node count of the last
    shape; of the steady shape when settled), ``period`` (drive periods), ``t_end`` [T],
    ``shape_error`` (settled: RMS distance from the boundary-value shape [L]), ``lyapunov``,
    ``tip`` (co-rotating frame), ``tip_r``, ``steps``; with ``every``: the sampled frames
    ``t`` (times), ``x`` (positions (frames, N, 3) in the co-rotating frame), ``angle`` (angle
    of that frame: rotating x by it gives the inertial positions)."""

    def __repr__(self):
        return "SpinUp(state=%s, nodes=%d, t_end=%g)" % (self.state, self.nodes, self.t_end)


_PARAM_NAMES = {"internal_damping": "internal_damping", "dt": "dt", "t_ramp": "t_ramp",
                "t_max": "t_max", "settle_tol": "settle_tol",
                "settle_periods": "settle_periods", "periodic_tol": "periodic_tol",
                "lyapunov_periods": "lyapunov_periods", "chaos_lambda": "chaos_lambda",
                "perturb": "perturb", "seed": "seed"}


def spin_up(omega, drive_radius, links, air_drag=0.0, air_drag_quadratic=0.0, method=None,
            frame="rotating", every=None, **params):
    """Which steady shape a hand-swung chain settles into from rest (``whirl regime`` for one
    point): the N-link chain (``links``: N or a Chain) hangs at rest, the hand brings the top up
    to the circle of radius ``drive_radius`` [L] at rate ``omega`` [sqrt(g/L)] over t_ramp, with
    air drag, until the shape in the co-rotating frame stops changing or t_max.
    Further parameters (defaults from whirl_regime_defaults): internal_damping, dt,
    t_ramp, t_max, settle_tol, settle_periods, periodic_tol, lyapunov_periods,
    chaos_lambda, perturb, seed; method (default rk4), frame ("rotating" or "inertial").
    every > 0: record the masses every ``every`` time units. Returns a SpinUp. Ctrl-C raises
    KeyboardInterrupt."""
    chain = links if isinstance(links, Chain) else Chain(links)
    p = ffi.new("whirl_regime_params *", lib.whirl_regime_defaults(chain.n))
    p.omega = as_float(omega, "omega", positive=True)
    p.drive_radius = as_float(drive_radius, "drive_radius", positive=True)
    p.air_drag = as_float(air_drag, "air_drag", nonnegative=True)
    p.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic", nonnegative=True)
    p.frame = _choice(frame, "frame", _FRAMES)
    keep = []
    if method is not None:
        if not isinstance(method, str):
            raise TypeError("method must be a string, got %r" % (method,))
        keep.append(ffi.new("char[]", method.encode()))
        p.method = keep[-1]
    for key, value in params.items():
        if key not in _PARAM_NAMES:
            raise TypeError("spin_up() got an unexpected keyword argument %r" % key)
        if key in ("settle_periods", "lyapunov_periods", "seed"):
            setattr(p, key, as_int(value, key, minimum=0))
        else:
            setattr(p, key, as_float(value, key, nonnegative=True))
    check(lib.whirl_regime_check(p))
    w = _lib.check_ptr(lib.whirl_regime_alloc(chain._c), lib.whirl_regime_free)
    frames_t, frames_x, frames_a = [], [], []
    record = every is not None
    interval = as_float(every, "every", positive=True) if record else 1.0

    @ffi.callback("whirl_regime_observer")
    def observe(ctx, t, angle, pivot, x, n):
        if record:
            frames_t.append(t)
            frames_a.append(angle)
            frames_x.append(np.frombuffer(ffi.buffer(x, 24 * n), dtype=np.float64)
                            .reshape(n, 3).copy())
        # the observer is where a run from Python sees Ctrl-C
        return lib.WHIRL_EINTERRUPTED if lib.whirl_stop_requested() else 0

    lib.whirl_regime_observe(w, observe, ffi.NULL, interval)
    res = ffi.new("whirl_regime_result *")
    with _lib.interruptible():
        status = lib.whirl_regime_run(w, p, res)
    check(status)
    out = SpinUp()
    out.state = ffi.string(lib.whirl_regime_state_name(res.state)).decode()
    if res.state == lib.WHIRL_REGIME_FAILED:
        raise _lib.Error(5, "the spin-up failed: " + _lib.last_error())
    out.nodes, out.period, out.t_end = res.nodes, res.period, res.t_end
    out.change, out.remaining, out.shape_error = res.change, res.remaining, res.shape_error
    out.bvp_nodes, out.lyapunov = res.bvp_nodes, res.lyapunov
    out.tip, out.tip_r, out.steps = np.array(list(res.tip)), res.tip_r, res.steps
    out.t = np.array(frames_t)
    out.angle = np.array(frames_a)
    out.x = np.array(frames_x) if frames_x else np.empty((0, chain.n, 3))
    return out
