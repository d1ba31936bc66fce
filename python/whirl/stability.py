"""Stability of the steady shapes of the N-link chain (whirl/stability.h, ``whirl stability``):
the linearisation in the co-rotating frame (M q'' + (G + C) q' + K q = 0) and a perturbed run.
Dimensionless units: rates in sqrt(g/L), growth rates in sqrt(g/L)."""
import numpy as np

from . import _lib
from ._lib import ffi, lib, check, as_int, as_float, as_array
from .steady import Chain, _mode


class StabilityResult:
    """One shape's stability: ``eig_growth`` (largest real part of the linearisation's
    eigenvalues, the rotation symmetry's zeros removed [1/T]), ``eigenvalues`` (complex array),
    and, unless linear, the perturbed run's ``sim_growth`` (fitted exponential rate, 0 unless
    unstable), ``max_deviation`` (largest deviation / the initial one), ``duration`` [T] and
    ``stats``; ``index``: the negative directions of the amended potential (gravity minus
    centrifugal) at the shape; ``verdict``: "stable (minimum)" (bounded, index 0: an energy
    minimum, stable also with dissipation), "neutral (gyroscopic)" (bounded, index > 0: a saddle
    held by the Coriolis coupling, destabilised by any dissipation), "unstable" or "converging"
    (linear: from the sign of eig_growth and the index). ``tip_r``, ``nodes``: the shape's tip
    radius and node count."""

    def __repr__(self):
        return "StabilityResult(omega=%g, mode=%d, eig_growth=%.6g, verdict=%s, index=%d)" % (
            self.omega, self.mode, self.eig_growth, self.verdict, self.index)


def _model(chain, omega, damping, drive_radius, air_drag, air_drag_quadratic):
    m = ffi.new("whirl_model *")
    m.chain = chain._c
    m.dim = 3
    m.frame = 1
    m.omega = omega
    m.internal_damping = as_float(damping, "damping", nonnegative=True)
    m.drive_radius = as_float(drive_radius, "drive_radius", nonnegative=True)
    m.air_drag = as_float(air_drag, "air_drag", nonnegative=True)
    m.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic", nonnegative=True)
    return m


def _eigenvalues(w):
    count = ffi.new("size_t *")
    re = ffi.new("const double **")
    im = ffi.new("const double **")
    check(lib.whirl_stability_eigenvalues(w, count, re, im))
    n = count[0]
    r = np.frombuffer(ffi.buffer(re[0], 8 * n), dtype=np.float64)
    i = np.frombuffer(ffi.buffer(im[0], 8 * n), dtype=np.float64)
    return r + 1j * i


@ffi.callback("int(double, double, void *)")
def _observe_stop(t, ratio, data):
    """The perturbed run's observer: stops it (WHIRL_EINTERRUPTED) once a stop is requested."""
    return lib.WHIRL_EINTERRUPTED if lib.whirl_stop_requested() else 0


def stability(omega, mode, links, damping=0.0, linear=False, periods=100.0, perturb=1e-10,
              method="rk4", seed=1, dt=0.0, drive_radius=0.0, air_drag=0.0,
              air_drag_quadratic=0.0, side=1):
    """The stability of the steady shape of ``mode`` at ``omega`` [sqrt(g/L)] of the N-link
    chain ``links`` (N or a Chain), as ``whirl stability --omega W --mode K --links N``.

    damping: internal damping D; linear=True: eigenvalues only (no run); otherwise a run of
    ``periods`` rotation periods from the shape with every link turned by ``perturb`` [rad]
    (``seed`` of the random directions) with ``method`` (default rk4) and step ``dt`` (0: the
    library's default). With drive_radius > 0 (and air_drag, air_drag_quadratic) the shape is
    the hand-swung chain's trailing shape on ``side`` +1 or -1. Returns a StabilityResult;
    whirl.Error if the shape does not exist; Ctrl-C raises KeyboardInterrupt."""
    chain = links if isinstance(links, Chain) else Chain(links)
    w = as_float(omega, "omega", positive=True)
    mode = _mode(mode, chain)
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    m = _model(chain, w, damping, drive_radius, air_drag, air_drag_quadratic)
    ws = _lib.check_ptr(lib.whirl_stability_alloc(chain.n), lib.whirl_stability_free)
    growth = ffi.new("double *")
    res = StabilityResult()
    res.omega, res.mode = w, mode
    if m.drive_radius > 0 or m.air_drag > 0 or m.air_drag_quadratic > 0:
        info = ffi.new("whirl_driven_info *")
        check(lib.whirl_stability_driven_mode(ws, m, mode, side, info, growth))
        res.tip_r, res.nodes = info.tip_r, info.nodes
    else:
        info = ffi.new("whirl_shape_info *")
        check(lib.whirl_stability_mode(ws, m, mode, 0.0, info, growth))
        res.tip_r, res.nodes = info.tip_r, info.n_nodes + 1
    res.eig_growth = growth[0]
    index = ffi.new("int *")
    check(lib.whirl_stability_index(ws, index))
    res.index = index[0]
    res.eigenvalues = _eigenvalues(ws)
    res.sim_growth = res.max_deviation = res.duration = None
    res.stats = None
    if linear:
        v = lib.whirl_verdict_linear(res.eig_growth, res.index)
        res.verdict = ffi.string(lib.whirl_verdict_name(v)).decode()
        return res
    p = ffi.new("whirl_stability_run_params *", lib.whirl_stability_run_defaults())
    p.periods = as_float(periods, "periods", positive=True)
    p.perturbation = as_float(perturb, "perturb", positive=True)
    p.seed = as_int(seed, "seed", minimum=0)
    if not isinstance(method, str):
        raise TypeError("method must be a string, got %r" % (method,))
    name = ffi.new("char[]", method.encode())
    p.method = name
    p.dt = as_float(dt, "dt", nonnegative=True)
    p.observe = _observe_stop
    x, y, z = (ffi.new("const double **") for _ in range(3))
    lib.whirl_stability_nodes(ws, x, y, z)
    out = ffi.new("whirl_stability_run_result *")
    with _lib.interruptible():
        status = lib.whirl_stability_run_shape(m, x[0], y[0], z[0], p, out)
    check(status)
    res.sim_growth = out.sim_growth
    res.max_deviation = out.max_deviation
    res.duration = out.duration
    v = lib.whirl_verdict_refine(out.verdict, res.index)
    res.verdict = ffi.string(lib.whirl_verdict_name(v)).decode()
    s = out.stats
    res.stats = {"steps": s.steps, "rejected": s.rejected, "rhs_evals": s.rhs_evals,
                 "iterations": s.iterations}
    return res


MAP_DTYPE = np.dtype([("omega", "f8"), ("tip_r", "f8"), ("growth", "f8")])


def stability_map(omega, mode, links, damping=0.0):
    """The linear growth rate of ``mode`` of the N-link chain over the rates ``omega`` (array,
    [sqrt(g/L)]), the branch followed by continuation, as ``whirl stability --omega-min ...
    --linear``. Returns a structured array (omega, tip_r, growth [1/T]) with one row per rate
    where the mode exists; growth > 0: unstable. Ctrl-C raises KeyboardInterrupt."""
    chain = links if isinstance(links, Chain) else Chain(links)
    mode = _mode(mode, chain)
    w = as_array(omega, "omega", positive=True)
    n = w.size
    info = ffi.new("whirl_shape_info[]", n)
    exists = np.zeros(n, dtype=np.intc)
    # the shapes' nodes from the branch's link angles (at high rates the tip radius alone does
    # not fix them)
    r, z, tension = (np.empty((n, chain.n + 1)) for _ in range(3))
    with _lib.interruptible():
        status = lib.whirl_nlink_branch_nodes(chain._c, mode, n, _lib.dptr(w), info,
                                              ffi.cast("int *", ffi.from_buffer(exists)),
                                              _lib.dptr(r), _lib.dptr(z), _lib.dptr(tension))
    check(status, "mode %d" % mode)
    ws = _lib.check_ptr(lib.whirl_stability_alloc(chain.n), lib.whirl_stability_free)
    growth = ffi.new("double *")
    rows = np.flatnonzero(exists)
    out = np.empty(rows.size, dtype=MAP_DTYPE)
    with _lib.interruptible():
        for i, j in enumerate(rows):
            m = _model(chain, w[j], damping, 0.0, 0.0, 0.0)
            status = lib.whirl_stability_linearise(ws, m, _lib.dptr(r[j]), _lib.dptr(z[j]))
            if status == _lib.GSL_SUCCESS:
                status = lib.whirl_stability_growth(ws, growth)
            check(status, "omega %.17g" % w[j])
            out[i] = (w[j], info[j].tip_r, growth[0])
            if _lib.stop_requested():
                break
    return out


WINDOW_DTYPE = np.dtype([("from", "f8"), ("to", "f8"), ("open_from", "?"), ("open_to", "?"),
                         ("freq_from", "f8"), ("freq_to", "f8"), ("max_growth", "f8"),
                         ("at", "f8"), ("err_from", "f8"), ("err_to", "f8")])


def stability_windows(mode, links=None, omega_min=1.0, omega_max=10.0, scan_step=0.25, tol=1e-9,
                      krylov=True, max_windows=1024, degree=None, tip_mass=0.0):
    """The windows of instability of ``mode`` of the conservative N-link chain (``links``: N or
    a Chain) or, with links=None, of the continuous chain (its string equations linearised by
    Chebyshev collocation on elements of ``degree``, default the library's 16, with a point mass
    ``tip_mass`` [M] at the free end), for rates in [omega_min, omega_max] [sqrt(g/L)], as
    ``whirl stability --windows``: the edges are the rates where two eigenvalues collide (Krein
    collision), located to ``tol`` after a scan with spacing ``scan_step``. Returns (windows,
    stats): a structured array with fields from, to (the unstable interval), open_from, open_to
    (True: that end is the end of the range, not an edge), freq_from, freq_to (|Im lambda| where
    the pair meets [1/T]), max_growth [1/T], at (where it occurs) and err_from, err_to (the
    continuum's estimate of each edge's discretisation error; 0 for the N-link chain), in
    increasing omega; stats
    a dict of the search's counters. whirl.Error (EDOM) if the mode does not exist in the range;
    Ctrl-C raises KeyboardInterrupt."""
    chain = None if links is None else links if isinstance(links, Chain) else Chain(links)
    mode = _mode(mode, chain, lib.WHIRL_MODE_MAX)
    if links is not None and (degree is not None or tip_mass):
        raise ValueError("degree and tip_mass apply to the continuous chain (links=None)")
    p = ffi.new("whirl_windows_params *", lib.whirl_windows_defaults())
    p.omega_min = as_float(omega_min, "omega_min", positive=True)
    p.omega_max = as_float(omega_max, "omega_max", positive=True)
    if not p.omega_min < p.omega_max:
        raise ValueError("omega_min must be < omega_max, got %g and %g" % (p.omega_min,
                                                                          p.omega_max))
    p.scan_step = as_float(scan_step, "scan_step", positive=True)
    p.tol = as_float(tol, "tol", positive=True)
    p.krylov = 1 if krylov else 0
    cap = as_int(max_windows, "max_windows", minimum=1)
    found = ffi.new("whirl_window[]", cap)
    count = ffi.new("size_t *")
    st = ffi.new("whirl_windows_stats *")
    if links is None:
        cp = ffi.new("whirl_cstab_params *", lib.whirl_cstab_defaults())
        if degree is not None:
            cp.degree = as_int(degree, "degree", minimum=1)
        cp.tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True)
        ws = _lib.check_ptr(lib.whirl_cstab_alloc(cp), lib.whirl_cstab_free)
        with _lib.interruptible():
            status = lib.whirl_cstab_windows(ws, mode, p, found, cap, count, st)
    else:
        ws = _lib.check_ptr(lib.whirl_windows_alloc(chain.n), lib.whirl_windows_free)
        with _lib.interruptible():
            status = lib.whirl_windows_find(ws, chain._c, mode, p, found, cap, count, st)
    check(status, "mode %d" % mode)
    out = np.empty(count[0], dtype=WINDOW_DTYPE)
    for i in range(count[0]):
        f = found[i]
        out[i] = (getattr(f, "from"), f.to, bool(f.open_from), bool(f.open_to), f.freq_from, f.freq_to,
                  f.max_growth, f.at, f.err_from, f.err_to)
    stats = {k: getattr(st, k) for k in ("omega_from", "omega_to", "scan", "shapes",
                                          "solves_vectors", "solves_values", "solves_krylov",
                                          "approaches", "unresolved")}
    return out, stats
