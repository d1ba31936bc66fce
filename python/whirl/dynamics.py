"""The N-link chain in time (whirl/dynamics.h): a Simulation holds the model, the state and an
integrator of the library, and returns its run as numpy arrays.

Units: dimensionless (L = M = g = 1 for the uniform chain; a Chain of your own is in its own
units): time in sqrt(L/g), positions in L, energy in M g L."""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, check, as_int, as_float, as_array
from .periodic import _path as _pivot_path
from .steady import Chain, Units, _mode, links_count, units_of

_FRAMES = {"inertial": 0, "rotating": 1}
_FORMULATIONS = {"default": 0, "seed": 1}
# The largest fixed-step run, links x steps: the scenes' bound (WHIRL_SCENE_WORK_MAX, about an
# hour of work with the implicit methods); and the most output rows x links a run may write.
WORK_MAX = 1e10
# Stiff runs. A fixed step h of the explicit methods and of the Gauss methods' fixed-point stage
# iteration is stable for h x rate below about 2 (rk4: 2.785 on the negative real axis; the Gauss
# fixed point: 2 sqrt(3) = 3.46), rate the fastest decay the dissipation adds: the limit of
# whirl_scene_stiff (whirl/scene.h), 2 leaving room for the estimate. Past it, a Simulation whose
# method was not named runs with GSL's BDF (implicit, a Newton iteration, adaptive) at STIFF_TOL:
# on 30 links with D = 1e-3 and 1e-2 (h x rate 4.3 and 43 at dt = 0.01) its positions at t = 2
# are within 3e-8 and 2e-7 L of gauss2 at a 50 times smaller stable step (tol 1e-6: 1.4e-3 L,
# 1e-8: 2e-6 L), with D = 1e-2 in 1/5 to 1/7 of its processor time (docs/guide/python.md).
STIFF_H_RATE = 2.0
STIFF_METHOD = "gsl-msbdf"
STIFF_TOL = 1e-10
DEFAULT_METHOD = "gauss2"


class StiffWarning(RuntimeWarning):
    """A run whose fixed step the damping or the drag makes unstable, taken by the implicit
    method (gsl-msbdf, adaptive) instead of the default one; the message says why."""


def _choice(value: Any, name: str, table: Dict[str, int]) -> int:
    if not isinstance(value, str):
        raise TypeError("%s must be a string, got %r" % (name, value))
    if value not in table:
        raise ValueError("%s must be one of %s, got %r" % (name, ", ".join(table), value))
    return table[value]


def _method(method: Any) -> str:
    if not isinstance(method, str):
        raise TypeError("method must be a string, got %r" % (method,))
    known = _lib.methods()
    if method not in known:
        raise ValueError("method must be one of %s, got %r" % (", ".join(known), method))
    return method


def _stats(s: Any) -> Dict[str, int]:
    return {"steps": int(s.steps), "rejected": int(s.rejected), "rhs_evals": int(s.rhs_evals),
            "iterations": int(s.iterations)}


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class Trajectory(_lib.Result):
    """The output of Simulation.run: arrays over the output times ``t`` [T]: ``x`` (shape
    (len(t), N, 3): every mass's position in the inertial frame [L]; None with
    positions=False), ``energy`` (kinetic plus potential, inertial frame [M g L]), ``jacobi``
    (energy - omega L_z), ``lz`` [M L sqrt(g L)], ``constraint`` (the largest link-length error
    [L]), ``deviation`` (RMS distance of the masses from the start shape, minimised over a
    rotation about z [L]); ``stats`` the integrator's counters (steps, rejected, rhs_evals,
    iterations) over the run; ``interrupted`` True when Ctrl-C ended it early (the rows so far;
    only with Simulation.run(..., keep_interrupted=True)); ``method`` the integrator that ran
    it (gsl-msbdf for a stiff run of a Simulation whose method was not named). Units: the
    Simulation's.
    ``x_rotating``: the same positions in the frame co-rotating at the Simulation's omega about
    the vertical axis z through the pivot's circle (3D; None for a planar model or
    positions=False): x turned by -phi(t) about z, phi = omega t the phase of the rotation and
    of the pivot's drive (0 at t = 0, where the two frames coincide; the pivot then sits at
    (drive_radius, 0, 0)). A steady shape turning at omega, or the hand-swung chain's trailing
    shape, is fixed there (DrivenShape's frame)."""

    t: np.ndarray
    x: Optional[np.ndarray]
    energy: np.ndarray
    jacobi: np.ndarray
    lz: np.ndarray
    constraint: np.ndarray
    deviation: np.ndarray
    stats: Dict[str, int]
    units: Units = field(default_factory=Units)
    interrupted: bool = False
    method: Optional[str] = None
    x_rotating: Optional[np.ndarray] = None

    @property
    def tip(self) -> np.ndarray:
        """The free end's position over the run, shape (len(t), 3) [L]."""
        if self.x is None:
            raise ValueError("the run kept no positions (positions=False)")
        return self.x[:, -1, :]

    @property
    def tip_rotating(self) -> np.ndarray:
        """The free end's position in the co-rotating frame, shape (len(t), 3) [L]."""
        if self.x_rotating is None:
            raise ValueError("the run kept no co-rotating positions (positions=False, or a "
                             "planar model)")
        return self.x_rotating[:, -1, :]

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # whirl simulate's columns (a scene's [output] columns, all of them)
        columns: Dict[str, Any] = {"t": self.t}
        if self.x is not None:
            columns.update(tip_x=self.x[:, -1, 0], tip_y=self.x[:, -1, 1], tip_z=self.x[:, -1, 2])
        columns.update(energy=self.energy, jacobi=self.jacobi, lz=self.lz,
                       constraint=self.constraint, deviation=self.deviation)
        if self.x_rotating is not None:  # the co-rotating frame's tip, after simulate's columns
            tip = self.x_rotating[:, -1, :]
            columns.update(tip_x_rot=tip[:, 0], tip_y_rot=tip[:, 1], tip_z_rot=tip[:, 2])
        return columns, {"method": self.method, "interrupted": self.interrupted}

    def __repr__(self) -> str:
        span = ", t = %g..%g" % (self.t[0], self.t[-1]) if self.t.size else ""
        return "Trajectory(%d rows%s, %d steps%s)" % (
            self.t.size, span, self.stats["steps"], ", interrupted" if self.interrupted else "")


class Simulation:
    """An N-link chain in the time domain (``whirl simulate``'s engine).

    Simulation(chain, dim=3, frame="inertial", omega=0, drive_radius=0, air_drag=0,
    air_drag_quadratic=0, internal_damping=0, formulation="default", method="gauss2",
    threads=1, length=None, mass=None, gravity=None, units=None, pivot=None)
      chain: a Chain or a link count N (the uniform chain); fixed for the Simulation's life;
      dim: 2 (planar, x-z) or 3; frame: "inertial" or "rotating" (co-rotating at omega, 3D);
      omega: rate of the rotating frame and of the pivot drive [1/T] (of the pivot's path);
      drive_radius: the pivot moves on the horizontal circle of this radius [L] at omega;
      pivot: the pivot moves on this periodic path at the rate omega (> 0) instead, a text as
        whirl.periodic's pivot= and a scene's [run] pivot take it: circle:R, ellipse:A,B,
        line:A[,DX,DY,DZ], vertical:A, eight:A,B or fourier:x1c=A,z2s=B,... (lengths in the
        Simulation's units, or with a suffix m, cm, mm in SI units); needs frame "inertial"
        and drive_radius 0 (circle:R is that drive, bit for bit);
      air_drag, air_drag_quadratic: linear and quadratic drag per unit length;
      internal_damping: joint damping in the co-rotating frame;
      formulation: "default" (link vectors and tensions, O(N)) or "seed" (angles, O(N^3));
      method: any of whirl.methods() (gauss2, gauss3, rk4, rk8, gsl-...); not given: gauss2,
        and gsl-msbdf with tol = 1e-10 (a StiffWarning says why) for a run whose fixed step the
        damping or drag makes stiff (dt x stiff_rate > 2); a method named keeps it, and a run of
        it that fails there says so;
      threads: cores for one right-hand side of a long chain (N >= 4096; whirl_dyn_set_threads:
        the same numbers, faster only on idle cores);
      length/mass/gravity or units: the units of every argument and result (see whirl.Units;
        default dimensionless: times in sqrt(L/g), lengths in L, energies in M g L).
    Start it with set_steady, set_hanging or set_state, then run(). Pickles and copies (its
    configuration, time and state; the integrator starts afresh, its counters at zero).

    Threads: a Simulation holds one state, so it serves one thread at a time. A call from a
    second thread while a first is inside one of its methods (run, set_*, positions, ...)
    raises whirl.InUse (a RuntimeError) at once and changes nothing; give each thread its own
    Simulation (copy.copy(sim) copies one). Separate Simulations run in parallel threads
    (the library releases the GIL). In a child of fork() (multiprocessing's default on Linux)
    the library runs on one thread: see whirl.set_max_threads."""

    def __init__(self, chain: Union[int, Chain], dim: int = 3, frame: str = "inertial",
                 omega: float = 0.0, drive_radius: float = 0.0, air_drag: float = 0.0,
                 air_drag_quadratic: float = 0.0, internal_damping: float = 0.0,
                 formulation: str = "default", method: Optional[str] = None, threads: int = 1,
                 length: Optional[float] = None, mass: Optional[float] = None,
                 gravity: Optional[float] = None, units: Optional[Units] = None,
                 pivot: Optional[str] = None) -> None:
        self._guard = _lib.Exclusive()
        u = units_of(length, mass, gravity, units)
        self.units = u
        self._chain = chain if isinstance(chain, Chain) else Chain(links_count(chain))
        self._args = dict(dim=dim, frame=frame, omega=omega, drive_radius=drive_radius,
                          air_drag=air_drag, air_drag_quadratic=air_drag_quadratic,
                          internal_damping=internal_damping, formulation=formulation,
                          method=method, threads=threads, pivot=pivot)
        self._model = ffi.new("whirl_model *")
        m = self._model
        m.chain = self._chain._c  # self._chain owns it for as long as the model lives
        m.dim = as_int(dim, "dim")
        if m.dim not in (2, 3):
            raise ValueError("dim must be 2 or 3, got %d" % m.dim)
        m.frame = _choice(frame, "frame", _FRAMES)
        m.omega = as_float(omega, "omega", kind="rate", units=u) / u.rate
        m.drive_radius = as_float(drive_radius, "drive_radius", nonnegative=True,
                                  kind="length", units=u) / u.length
        m.air_drag = as_float(air_drag, "air_drag", nonnegative=True, kind="drag",
                              units=u) / u.drag
        m.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic",
                                        nonnegative=True, kind="drag2", units=u) / u.drag2
        m.internal_damping = as_float(internal_damping, "internal_damping",
                                      nonnegative=True, kind="damping", units=u) / u.damping
        f = _choice(formulation, "formulation", _FORMULATIONS)
        if f == 1:
            links_count(self._chain.n, "links", dense=True)  # O(N^2) memory, O(N^3) work
        self._dyn = _lib.check_ptr(lib.whirl_dyn_alloc(m, f), lib.whirl_dyn_free)
        check(lib.whirl_dyn_set_threads(self._dyn, as_int(threads, "threads", minimum=1)))
        self._pivot: Any = None  # the path (dimensionless), referred to by the dynamics
        if pivot is not None:
            if not m.omega > 0:
                raise ValueError("pivot needs omega > 0: the path's rate (its period is "
                                 "2 pi / omega)")
            self._pivot = _pivot_path(pivot, omega, m.dim, u)
            check(lib.whirl_dyn_set_pivot(self._dyn, lib.whirl_pivot_eval, self._pivot),
                  "pivot", u)
        self.method = _method(DEFAULT_METHOD if method is None else method)
        self._it = _lib.check_ptr(lib.whirl_integrator_alloc(self.method.encode(), self._dyn),
                                  lib.whirl_integrator_free)
        self._stiff_it: Any = None  # the implicit method of stiff runs, made when first needed
        self.n = self._chain.n
        self._y = np.zeros(lib.whirl_dyn_size(self._dyn))
        self._t = ffi.new("double *", 0.0)
        self._x = np.zeros(3 * self.n)
        self._v = np.zeros(3 * self.n)
        self._ref: Optional[np.ndarray] = None
        self._diag = ffi.new("whirl_dyn_diagnostics *")

    def __repr__(self) -> str:
        # no guard: a repr (a debugger's, a log's) never waits for or disturbs another thread
        m, u = self._model, self.units
        extra = "".join(", %s=%g" % (name, value) for name, value in (
            ("drive_radius", m.drive_radius * u.length), ("air_drag", m.air_drag * u.drag),
            ("air_drag_quadratic", m.air_drag_quadratic * u.drag2),
            ("internal_damping", m.internal_damping * u.damping)) if value)
        start = "no start state" if self._ref is None else "t=%g" % self.t
        if self._pivot is not None:
            extra += ", pivot=%r" % self._args["pivot"]
        return "Simulation(%r, dim=%d, frame=%r, omega=%g%s, method=%r, %s%s)" % (
            self._chain, m.dim, self._args["frame"], self.omega, extra, self.method, start,
            ", %r" % u if u.physical else "")

    @property
    def chain(self) -> Chain:
        """The chain (read-only: the library's model refers to it)."""
        return self._chain

    @_lib.exclusive
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        state = (self._t[0], self._y.copy(), None if self._ref is None else self._ref.copy())
        return (_simulation_from, (self._chain, self._args, self.units, state))

    @property
    def t(self) -> float:
        """The current time [T]."""
        return float(self._t[0]) * self.units.time

    @property
    def omega(self) -> float:
        return float(self._model.omega) * self.units.rate

    @property
    def pivot(self) -> Optional[str]:
        """The pivot's path as given (None: the pivot moves as drive_radius says)."""
        pivot = self._args["pivot"]
        return None if pivot is None else str(pivot)

    @_lib.exclusive
    def set_state(self, x: Any, v: Any, t: float = 0.0) -> None:
        """Starts from the positions x [L] and velocities v of masses 1..N (arrays (N, 3), in
        the model's frame at time t [T]; 2D: y components 0). They must satisfy the link
        constraints to 1e-9 relative (whirl.InvalidInput otherwise). The deviation is measured
        from x."""
        u = self.units
        x = as_array(x, "x", shape=(self.n, 3), kind="length", units=u).ravel() / u.length
        v = as_array(v, "v", shape=(self.n, 3)).ravel() / (u.length / u.time)
        t = as_float(t, "t", kind="time", units=u) / u.time
        check(lib.whirl_dyn_set_state(self._dyn, t, _lib.dptr(x), _lib.dptr(v),
                                      _lib.dptr(self._y)))
        self._t[0] = t
        self._ref = self._inertial()

    @_lib.exclusive
    def set_steady(self, mode: int, omega: Optional[float] = None, perturb: float = 0.0,
                   seed: int = 1, along: Any = None, amplitude: float = 1e-6) -> None:
        """Starts from the exact steady shape of ``mode`` at ``omega`` [1/T] (default: the
        model's omega) in the x-z plane, turning rigidly at omega about z (3D), placed as the
        library places it (whirl_dyn_state_from_shape: the pivot at (drive_radius, 0, 0), in the
        inertial frame turned by the drive's phase at t = 0).

        perturb: each link direction turned by this angle [rad] towards a random direction
        perpendicular to it (the library's one perturbation rule, whirl_perturb_links: GSL's
        MT19937 seeded with ``seed``; lengths kept), as a scene's [start] perturb and seed.
        along: instead, a direction of 2N link angles (a_1..a_N, b_1..b_N), e.g. a mode of
        ``whirl.stability(..., modes=True).angles[k]`` at the same mode and omega (a complex one:
        its real part), the links turned along it in the linearisation's chart (whirl/stability.h,
        whirl_perturb_links_along), the largest by ``amplitude`` [rad]; at rest in the co-rotating
        frame. The deviation is measured from the unperturbed shape."""
        w = (self._model.omega if omega is None
             else as_float(omega, "omega", positive=True,
                           kind="rate", units=self.units) / self.units.rate)
        mode = _mode(mode, self._chain)
        perturb = as_float(perturb, "perturb", nonnegative=True)
        seed = as_int(seed, "seed", minimum=0, maximum=2**31 - 1)
        direction = None
        if along is not None:
            if perturb > 0:
                raise ValueError("give perturb or along, not both")
            direction = np.real(np.asarray(along)).astype(np.float64).ravel()
            if direction.shape != (2 * self.n,):
                raise ValueError("along must hold 2N = %d link angles, got %d"
                                 % (2 * self.n, direction.size))
            amplitude = as_float(amplitude, "amplitude", positive=True)
        if self._model.dim != 3:
            raise ValueError("a steady start needs dim = 3")
        info = ffi.new("whirl_shape_info *")
        r, z, tension = (np.empty(self.n + 1) for _ in range(3))
        with _lib.interruptible("set_steady"):
            status = lib.whirl_nlink_solve_nodes(self._chain._c, w, mode, info, _lib.dptr(r),
                                                 _lib.dptr(z), _lib.dptr(tension))
        check(status, "set_steady", self.units)
        links = np.empty(3 * self.n)
        check(lib.whirl_shape_links(self.n, _lib.dptr(r), ffi.NULL, _lib.dptr(z),
                                    _lib.dptr(links)))
        check(lib.whirl_dyn_state_from_shape(self._dyn, 0.0, _lib.dptr(links), w,
                                             _lib.dptr(self._y)))
        self._t[0] = 0.0
        self._ref = self._inertial()
        if perturb > 0 or direction is not None:
            if direction is not None:
                check(lib.whirl_perturb_links_along(self.n, _lib.dptr(links), amplitude,
                                                    _lib.dptr(direction)), "set_steady")
            else:
                check(lib.whirl_perturb_links(self.n, _lib.dptr(links), perturb, seed))
            check(lib.whirl_dyn_state_from_shape(self._dyn, 0.0, _lib.dptr(links), w,
                                                 _lib.dptr(self._y)))

    @_lib.exclusive
    def set_hanging(self) -> None:
        """Starts from the chain hanging straight down at rest (pivot on the axis); with a
        pivot path, straight down and moving with the pivot, placed at its place at t = 0 (a
        scene's [start] hanging = true: whirl_dyn_state_from_shape)."""
        if self._pivot is not None:
            links = np.zeros((self.n, 3))
            links[:, 2] = -np.asarray(self._chain.lengths, dtype=np.float64)
            check(lib.whirl_dyn_state_from_shape(self._dyn, 0.0, _lib.dptr(links.ravel()), 0.0,
                                                 _lib.dptr(self._y)), "set_hanging", self.units)
            self._t[0] = 0.0
            self._ref = self._inertial()
            return
        if self._model.drive_radius != 0:
            raise ValueError("set_hanging needs the pivot on the axis (drive_radius = 0)")
        x = np.zeros((self.n, 3))
        x[:, 2] = -np.cumsum(self._chain.lengths) * self.units.length
        self.set_state(x, np.zeros((self.n, 3)))

    def _inertial(self) -> np.ndarray:
        check(lib.whirl_dyn_get_state(self._dyn, self._t[0], _lib.dptr(self._y), 0,
                                      _lib.dptr(self._x), _lib.dptr(self._v)))
        return self._x.reshape(self.n, 3).copy()

    @_lib.exclusive
    def positions(self) -> np.ndarray:
        """The masses' positions in the inertial frame now, (N, 3) [L]."""
        return self._inertial() * self.units.length

    @_lib.exclusive
    def tensions(self) -> np.ndarray:
        """The link tensions now, N values [M g]."""
        out = np.empty(self.n)
        check(lib.whirl_dyn_tensions(self._dyn, self._t[0], _lib.dptr(self._y), _lib.dptr(out)))
        return out * self.units.force

    @_lib.exclusive
    def stats(self) -> Dict[str, int]:
        """The integrator's counters since it was made: steps, rejected, rhs_evals,
        iterations."""
        return _stats(lib.whirl_integrator_get_stats(self._it))

    @property
    def stiff_rate(self) -> float:
        """The fastest decay rate the dissipation adds to the motion [1/T], the library's
        (whirl_model_stiff_rate, whirl/dynamics.h): 16 D / min_i(m_i l_i^2) + max_i (l_i / m_i)
        (c + 2 c2 |omega| (L + eps)) for the internal damping D, the drags c, c2 and the drive
        radius eps; 0 without dissipation. A fixed step dt with dt x stiff_rate > 2 is past the
        explicit and fixed-point methods."""
        return self._stiff_rate() * self.units.rate

    def _stiff_rate(self) -> float:
        return float(lib.whirl_model_stiff_rate(self._model))

    def _stiff_words(self, dt: float) -> str:
        """Why the fixed step dt (dimensionless) is past the method: what makes the chain stiff,
        how fast, and what steps over it."""
        u = self.units
        rate = self._stiff_rate()
        what = ffi.string(lib.whirl_model_stiff_cause(self._model)).decode()
        return ("%s the chain stiff (decay rates up to about %.2g %s, dt x rate = %.2g): "
                "fixed steps of %s need dt below about %.2g%s, or method='%s' with tol (%g)"
                % (what, rate * u.rate, "1/s" if u.physical else "sqrt(g/L)", rate * dt,
                   self.method, STIFF_H_RATE / rate * u.time, " s" if u.physical else "",
                   STIFF_METHOD, STIFF_TOL))

    def _integrator(self, dt: float, tol: float) -> Tuple[Any, float, str]:
        """The integrator of a run with the step dt and tolerance tol (dimensionless), the
        tolerance it takes, and why the step is stiff ("" if it is not, or when the implicit
        method takes the run)."""
        if tol > 0 or self.method == STIFF_METHOD or not (
                self._stiff_rate() * dt > STIFF_H_RATE):
            return self._it, tol, ""
        why = self._stiff_words(dt)
        if self._args["method"] is not None:  # named: kept, and its failure says why
            return self._it, tol, why
        if self._stiff_it is None:
            self._stiff_it = _lib.check_ptr(
                lib.whirl_integrator_alloc(STIFF_METHOD.encode(), self._dyn),
                lib.whirl_integrator_free)
        warnings.warn("Simulation.run: %s; this run takes %s with tol=%g (name a method to "
                      "keep fixed steps)" % (why, STIFF_METHOD, STIFF_TOL), StiffWarning,
                      stacklevel=4)
        return self._stiff_it, STIFF_TOL, ""

    @_lib.exclusive
    def run(self, t_end: float, dt: float, every: Optional[float] = None, tol: float = 0.0,
            positions: bool = True, keep_interrupted: bool = False,
            progress: Any = None) -> Trajectory:
        """Integrates from the current time to t_end [T] with steps dt (tol = 0: fixed steps;
        tol > 0: adaptive with that tolerance, dt the first step), writing a row at the start,
        every ``every`` (default dt) and at t_end. positions=False skips the (rows, N, 3) array.
        The work is bounded before it starts (ValueError naming the bound and the memory):
        links x steps <= 1e10 for fixed steps, links x rows <= 1e10, and the rows' arrays
        within half the machine's memory. Returns a Trajectory. Ctrl-C raises
        KeyboardInterrupt (the state stays at the last step taken), or with
        keep_interrupted=True returns the rows so far marked interrupted; a failing step raises
        whirl.Error with the time. progress: the time integrated [T] out of t_end minus the
        start (see whirl's progress=), after every call of the integrator (at most 256 fixed
        steps, or one output interval)."""
        if self._ref is None:
            raise RuntimeError("no start state: call set_steady, set_hanging or set_state first")
        u = self.units
        t0 = self._t[0]
        t_end = as_float(t_end, "t_end", kind="time", units=u) / u.time
        if not t_end > t0:
            raise ValueError("t_end must be > the current time %g, got %g"
                             % (t0 * u.time, t_end * u.time))
        dt = as_float(dt, "dt", positive=True, kind="time", units=u) / u.time
        every = dt if every is None else as_float(every, "every", positive=True,
                                                  kind="time", units=u) / u.time
        tol = as_float(tol, "tol", nonnegative=True)
        it, tol, stiff = self._integrator(dt, tol)
        method = self.method if it is self._it else STIFF_METHOD
        span = t_end - t0
        steps = span / dt
        if tol == 0 and steps * self.n > WORK_MAX:
            raise ValueError("the run needs %.3g fixed steps of %d links: links x steps must be "
                             "<= %g (a larger dt, or tol > 0)" % (steps, self.n, WORK_MAX))
        rows_f = np.ceil(span / every * (1 - 1e-12)) + 1
        if rows_f * self.n > WORK_MAX:
            raise ValueError("the run asks for %.3g rows of %d links: links x rows must be <= %g "
                             "(a larger every)" % (rows_f, self.n, WORK_MAX))
        # the co-rotating positions beside the inertial ones (3D: a planar model has no
        # co-rotating frame)
        rotating = positions and self._model.dim == 3
        rows = _lib.bounded(int(rows_f), "rows (t_end / every)",
                            8 * (5 + (3 * self.n if positions else 0)
                                 + (3 * self.n if rotating else 0)))
        times = t0 + every * np.arange(rows, dtype=np.float64)
        times[-1] = t_end
        xs = np.empty((rows, self.n, 3)) if positions else None
        xr = np.empty((rows, self.n, 3)) if rotating else None
        vr = np.empty(3 * self.n)
        diag = np.empty((rows, 4))
        dev = np.empty(rows)
        before = _stats(lib.whirl_integrator_get_stats(it))
        y = _lib.dptr(self._y)
        ref = _lib.dptr(np.ascontiguousarray(self._ref).ravel())
        chunk = 256 * dt  # fixed steps: at most 256 per call, so that Ctrl-C is seen promptly
        done = 0
        rep = _progress.report(progress, "Simulation.run", span * u.time,
                               "s" if u.physical else "T")
        try:
            with rep, _lib.interruptible("Simulation.run"):
                for k in range(rows):
                    while self._t[0] < times[k]:
                        t1 = times[k]
                        if tol == 0 and self._t[0] + chunk * (1 + 1e-9) < t1:
                            t1 = self._t[0] + chunk
                        status = lib.whirl_integrator_advance(it, self._t, y, t1, dt, tol)
                        if status == _lib.GSL_SUCCESS and _lib.stop_requested():
                            # a stop between two calls: the same message as one inside a call
                            status = lib.WHIRL_EINTERRUPTED
                        if status != _lib.GSL_SUCCESS:
                            _stiff_check(status, "Simulation.run at t = %s"
                                         % _lib.in_units(self._t[0], "time", u), u, stiff)
                        rep.update((self._t[0] - t0) * u.time)
                    x = self._inertial()
                    if xs is not None:
                        xs[k] = x
                    if xr is not None:
                        check(lib.whirl_dyn_get_state(self._dyn, self._t[0], y, 1,
                                                      _lib.dptr(xr[k].reshape(-1)),
                                                      _lib.dptr(vr)))
                    check(lib.whirl_dyn_diagnose(self._dyn, self._t[0], y, self._diag))
                    d = self._diag
                    diag[k] = (d.energy, d.jacobi, d.lz, d.constraint)
                    dev[k] = lib.whirl_deviation(self.n, _lib.dptr(self._x), ref)
                    if not (np.all(np.isfinite(diag[k])) and np.isfinite(dev[k])):
                        raise _lib.Error(9, "the state is not finite at t = %s%s" % (
                            _lib.in_units(self._t[0], "time", u), "; " + stiff if stiff else ""))
                    done = k + 1
                rep.finish()
        except KeyboardInterrupt:
            if not keep_interrupted:
                raise
        after = _stats(lib.whirl_integrator_get_stats(it))
        stats = {k: after[k] - before[k] for k in after}
        energy = u.mass * u.gravity * u.length
        lz = u.mass * u.length * u.length / u.time
        return Trajectory(t=times[:done] * u.time,
                          x=None if xs is None else xs[:done] * u.length,
                          x_rotating=None if xr is None else xr[:done] * u.length,
                          energy=diag[:done, 0] * energy, jacobi=diag[:done, 1] * energy,
                          lz=diag[:done, 2] * lz, constraint=diag[:done, 3] * u.length,
                          deviation=dev[:done] * u.length, stats=stats, units=u,
                          interrupted=done < rows, method=method)


def _stiff_check(status: int, context: str, units: Units, stiff: str) -> None:
    """check(status, context, units), a failure of a stiff step (stiff: why) saying why."""
    try:
        check(status, context, units)
    except _lib.Error as e:
        if not stiff:
            raise
        raise _lib.error(e.status, "%s; %s" % (e.message, stiff)) from None


def _simulation_from(chain: Chain, args: Dict[str, Any], units: Units,
                     state: Tuple[float, np.ndarray, Optional[np.ndarray]]) -> Simulation:
    sim = Simulation(chain, units=units, **args)
    t, y, ref = state
    sim._t[0] = t
    sim._y[:] = y
    sim._ref = ref
    return sim
