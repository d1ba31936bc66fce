"""The N-link chain in time (whirl/dynamics.h): a Simulation holds the model, the state and an
integrator of the library, and returns its run as numpy arrays.

Units: dimensionless (L = M = g = 1 for the uniform chain; a Chain of your own is in its own
units): time in sqrt(L/g), positions in L, energy in M g L."""
import numpy as np

from . import _lib
from ._lib import ffi, lib, check, as_int, as_float, as_array
from .steady import Chain, _mode

_FRAMES = {"inertial": 0, "rotating": 1}
_FORMULATIONS = {"default": 0, "seed": 1}


def _choice(value, name, table):
    if not isinstance(value, str):
        raise TypeError("%s must be a string, got %r" % (name, value))
    if value not in table:
        raise ValueError("%s must be one of %s, got %r" % (name, ", ".join(table), value))
    return table[value]


class Trajectory:
    """The output of Simulation.run: arrays over the output times ``t`` [T]: ``x`` (shape
    (len(t), N, 3): every mass's position in the inertial frame [L]), ``energy`` (kinetic plus
    potential, inertial frame), ``jacobi`` (energy - omega L_z), ``lz``, ``constraint`` (the
    largest link-length error [L]), ``deviation`` (RMS distance of the masses from the start
    shape, minimised over a rotation about z [L]); ``stats`` the integrator's counters (steps,
    rejected, rhs_evals, iterations) over the run."""

    def __init__(self, t, x, diag, deviation, stats):
        self.t = t
        self.x = x
        self.energy, self.jacobi, self.lz, self.constraint = (diag[:, k] for k in range(4))
        self.deviation = deviation
        self.stats = stats

    @property
    def tip(self):
        """The free end's position over the run, shape (len(t), 3) [L]."""
        return self.x[:, -1, :]

    def __repr__(self):
        return "Trajectory(%d rows, t = %g..%g, %d steps)" % (
            self.t.size, self.t[0], self.t[-1], self.stats["steps"])


class Simulation:
    """An N-link chain in the time domain (``whirl simulate``'s engine).

    Simulation(chain, dim=3, frame="inertial", omega=0, drive_radius=0, air_drag=0,
    air_drag_quadratic=0, internal_damping=0, formulation="default", method="gauss2",
    threads=1)
      chain: a Chain or a link count N (the uniform chain);
      dim: 2 (planar, x-z) or 3; frame: "inertial" or "rotating" (co-rotating at omega, 3D);
      omega: rate of the rotating frame and of the pivot drive [1/T];
      drive_radius: the pivot moves on the horizontal circle of this radius [L] at omega;
      air_drag, air_drag_quadratic: linear and quadratic drag per unit length;
      internal_damping: joint damping in the co-rotating frame;
      formulation: "default" (link vectors and tensions, O(N)) or "seed" (angles, O(N^3));
      method: any of whirl.methods() (gauss2, gauss3, rk4, rk8, gsl-...);
      threads: cores for one right-hand side of a long chain (N >= 4096; whirl_dyn_set_threads:
        the same numbers, faster only on idle cores).
    Start it with set_steady, set_hanging or set_state, then run()."""

    def __init__(self, chain, dim=3, frame="inertial", omega=0.0, drive_radius=0.0,
                 air_drag=0.0, air_drag_quadratic=0.0, internal_damping=0.0,
                 formulation="default", method="gauss2", threads=1):
        self.chain = chain if isinstance(chain, Chain) else Chain(chain)
        self._model = ffi.new("whirl_model *")
        m = self._model
        m.chain = self.chain._c
        m.dim = as_int(dim, "dim")
        m.frame = _choice(frame, "frame", _FRAMES)
        m.omega = as_float(omega, "omega")
        m.drive_radius = as_float(drive_radius, "drive_radius", nonnegative=True)
        m.air_drag = as_float(air_drag, "air_drag", nonnegative=True)
        m.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic",
                                        nonnegative=True)
        m.internal_damping = as_float(internal_damping, "internal_damping", nonnegative=True)
        f = _choice(formulation, "formulation", _FORMULATIONS)
        self._dyn = _lib.check_ptr(lib.whirl_dyn_alloc(m, f), lib.whirl_dyn_free)
        check(lib.whirl_dyn_set_threads(self._dyn, as_int(threads, "threads", minimum=1)))
        if not isinstance(method, str):
            raise TypeError("method must be a string, got %r" % (method,))
        self.method = method
        self._it = _lib.check_ptr(lib.whirl_integrator_alloc(method.encode(), self._dyn),
                                  lib.whirl_integrator_free)
        self.n = self.chain.n
        self._y = np.zeros(lib.whirl_dyn_size(self._dyn))
        self._t = ffi.new("double *", 0.0)
        self._x = np.zeros(3 * self.n)
        self._v = np.zeros(3 * self.n)
        self._ref = None
        self._diag = ffi.new("whirl_dyn_diagnostics *")

    @property
    def t(self):
        """The current time [T]."""
        return self._t[0]

    @property
    def omega(self):
        return self._model.omega

    def set_state(self, x, v, t=0.0):
        """Starts from the positions x and velocities v of masses 1..N (arrays (N, 3), in the
        model's frame at time t; 2D: y components 0). They must satisfy the link constraints to
        1e-9 relative (whirl.Error otherwise). The deviation is measured from x."""
        x = as_array(x, "x", shape=(self.n, 3)).ravel()
        v = as_array(v, "v", shape=(self.n, 3)).ravel()
        t = as_float(t, "t")
        check(lib.whirl_dyn_set_state(self._dyn, t, _lib.dptr(x), _lib.dptr(v),
                                      _lib.dptr(self._y)))
        self._t[0] = t
        self._ref = self._inertial()

    def set_steady(self, mode, omega=None, perturb=0.0, seed=1):
        """Starts from the exact steady shape of ``mode`` at ``omega`` (default: the model's
        omega) in the x-z plane, turning rigidly at omega about z (3D), placed as the library
        places it (whirl_dyn_state_from_shape: the pivot at (drive_radius, 0, 0), in the
        inertial frame turned by the drive's phase at t = 0).

        perturb: each link direction turned by this angle [rad] towards a random direction
        perpendicular to it (the library's one perturbation rule, whirl_perturb_links: GSL's
        MT19937 seeded with ``seed``; lengths kept), as a scene's [start] perturb and seed.
        The deviation is measured from the unperturbed shape."""
        w = self.omega if omega is None else as_float(omega, "omega", positive=True)
        mode = _mode(mode, self.chain)
        perturb = as_float(perturb, "perturb", nonnegative=True)
        seed = as_int(seed, "seed", minimum=0, maximum=2**31 - 1)
        if self._model.dim != 3:
            raise ValueError("a steady start needs dim = 3")
        info = ffi.new("whirl_shape_info *")
        r, z, tension = (np.empty(self.n + 1) for _ in range(3))
        check(lib.whirl_nlink_solve_nodes(self.chain._c, w, mode, info, _lib.dptr(r),
                                          _lib.dptr(z), _lib.dptr(tension)))
        links = np.empty(3 * self.n)
        check(lib.whirl_shape_links(self.n, _lib.dptr(r), ffi.NULL, _lib.dptr(z),
                                    _lib.dptr(links)))
        check(lib.whirl_dyn_state_from_shape(self._dyn, 0.0, _lib.dptr(links), w,
                                             _lib.dptr(self._y)))
        self._t[0] = 0.0
        self._ref = self._inertial()
        if perturb > 0:
            check(lib.whirl_perturb_links(self.n, _lib.dptr(links), perturb, seed))
            check(lib.whirl_dyn_state_from_shape(self._dyn, 0.0, _lib.dptr(links), w,
                                                 _lib.dptr(self._y)))

    def set_hanging(self):
        """Starts from the chain hanging straight down at rest (pivot on the axis)."""
        if self._model.drive_radius != 0:
            raise ValueError("set_hanging needs the pivot on the axis (drive_radius = 0)")
        x = np.zeros((self.n, 3))
        x[:, 2] = -np.cumsum(self.chain.lengths)
        self.set_state(x, np.zeros((self.n, 3)))

    def _inertial(self):
        check(lib.whirl_dyn_get_state(self._dyn, self._t[0], _lib.dptr(self._y), 0,
                                      _lib.dptr(self._x), _lib.dptr(self._v)))
        return self._x.reshape(self.n, 3).copy()

    def positions(self):
        """The masses' positions in the inertial frame now, (N, 3) [L]."""
        return self._inertial()

    def tensions(self):
        """The link tensions now, N values [M g]."""
        out = np.empty(self.n)
        check(lib.whirl_dyn_tensions(self._dyn, self._t[0], _lib.dptr(self._y), _lib.dptr(out)))
        return out

    def stats(self):
        """The integrator's counters since it was made: steps, rejected, rhs_evals,
        iterations."""
        s = lib.whirl_integrator_get_stats(self._it)
        return {"steps": s.steps, "rejected": s.rejected, "rhs_evals": s.rhs_evals,
                "iterations": s.iterations}

    def run(self, t_end, dt, every=None, tol=0.0, positions=True):
        """Integrates from the current time to t_end [T] with steps dt (tol = 0: fixed steps;
        tol > 0: adaptive with that tolerance, dt the first step), writing a row at the start,
        every ``every`` (default dt) and at t_end. positions=False skips the (rows, N, 3) array.
        Returns a Trajectory. Ctrl-C raises KeyboardInterrupt (the state stays at the last step
        taken); a failing step raises whirl.Error with the time."""
        if self._ref is None:
            raise RuntimeError("no start state: call set_steady, set_hanging or set_state first")
        t0 = self._t[0]
        t_end = as_float(t_end, "t_end")
        if not t_end > t0:
            raise ValueError("t_end must be > the current time %g, got %g" % (t0, t_end))
        dt = as_float(dt, "dt", positive=True)
        every = dt if every is None else as_float(every, "every", positive=True)
        tol = as_float(tol, "tol", nonnegative=True)
        span = t_end - t0
        last = int(np.ceil(span / every * (1 - 1e-12)))
        times = np.array([t0 + k * every for k in range(last)] + [t_end])
        rows = times.size
        xs = np.empty((rows, self.n, 3)) if positions else None
        diag = np.empty((rows, 4))
        dev = np.empty(rows)
        before = self.stats()
        y = _lib.dptr(self._y)
        ref = _lib.dptr(np.ascontiguousarray(self._ref).ravel())
        chunk = 256 * dt  # fixed steps: at most 256 per call, so that Ctrl-C is seen promptly
        with _lib.interruptible():
            for k in range(rows):
                while self._t[0] < times[k]:
                    t1 = times[k]
                    if tol == 0 and self._t[0] + chunk * (1 + 1e-9) < t1:
                        t1 = self._t[0] + chunk
                    status = lib.whirl_integrator_advance(self._it, self._t, y, t1, dt, tol)
                    if status != _lib.GSL_SUCCESS:
                        check(status, "at t = %.17g" % self._t[0])
                    if _lib.stop_requested():
                        break
                if _lib.stop_requested():
                    break
                x = self._inertial()
                if positions:
                    xs[k] = x
                check(lib.whirl_dyn_diagnose(self._dyn, self._t[0], y, self._diag))
                d = self._diag
                diag[k] = (d.energy, d.jacobi, d.lz, d.constraint)
                dev[k] = lib.whirl_deviation(self.n, _lib.dptr(self._x), ref)
                if not (np.all(np.isfinite(diag[k])) and np.isfinite(dev[k])):
                    raise _lib.Error(9, "the state is not finite at t = %.17g" % self._t[0])
        after = self.stats()
        stats = {k: after[k] - before[k] for k in after}
        return Trajectory(times, xs, diag, dev, stats)
