"""Stability of the steady shapes of the N-link chain (whirl/stability.h, ``whirl stability``):
the linearisation in the co-rotating frame (M q'' + (G + C) q' + K q = 0) and a perturbed run.
Units as everywhere (see whirl.Units): dimensionless by default (rates and growth rates in
sqrt(g/L)), SI with length/mass/gravity or units given (rad/s, 1/s, s, m)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, check, as_int, as_float, as_array
from .steady import Chain, Units, _absent, _chain, _grid_text, _mode, units_of
from .dynamics import _method, _stats


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class StabilityResult(_lib.Result):
    """One shape's stability: ``eig_growth`` (largest real part of the linearisation's
    eigenvalues, the rotation symmetry's zeros removed [1/T]), ``eigenvalues`` (complex array
    [1/T]), and, unless linear, the perturbed run's ``sim_growth`` (fitted exponential rate, 0
    unless unstable), ``max_deviation`` (largest deviation / the initial one), ``duration`` [T]
    and ``stats``; ``index``: the negative directions of the amended potential (gravity minus
    centrifugal) at the shape; ``verdict``: "stable (minimum)" (bounded, index 0: an energy
    minimum, stable also with dissipation), "neutral (gyroscopic)" (bounded, index > 0: a saddle
    held by the Coriolis coupling, destabilised by any dissipation), "unstable" or "converging"
    (linear: from the sign of eig_growth and the index). ``tip_r``, ``node_count``: the shape's tip radius [L] and node count (the pivot
    plus the axis crossings); ``units``.
    With modes=True, per eigenvalue (same order as ``eigenvalues``) its mode q(t) =
    Re(v e^{lambda t}): ``displacements`` (complex, shape (count, N + 1, 3): the (dx, dy, dz) of
    each node, the pivot first, in the co-rotating frame [L]), ``angles`` (complex, (count, 2N):
    the link angles (a_1..a_N, b_1..b_N) of whirl/stability.h's chart, in-plane then out-of-plane
    for a planar shape [rad]), each mode scaled to a largest node displacement of 1 [L] (the
    angles alike), and ``krein`` (int, (count,)): +1 / -1 the sign of the energy of a neutral
    mode of the conservative chain, 0 otherwise. ``links``: the chain's link count."""

    omega: float
    mode: int
    tip_r: float
    node_count: int
    eig_growth: float
    eigenvalues: np.ndarray
    verdict: str
    index: int
    sim_growth: Optional[float] = None
    max_deviation: Optional[float] = None
    duration: Optional[float] = None
    stats: Optional[Dict[str, int]] = None
    units: Units = field(default_factory=Units)
    displacements: Optional[np.ndarray] = None
    angles: Optional[np.ndarray] = None
    krein: Optional[np.ndarray] = None
    links: Optional[int] = None

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # one row of whirl stability's columns, then the shape's tip radius and node count
        return ({"omega": self.omega, "mode": self.mode, "links": self.links,
                 "eig_growth": self.eig_growth, "sim_growth": self.sim_growth,
                 "max_deviation": self.max_deviation, "verdict": self.verdict,
                 "index": self.index, "tip_r": self.tip_r, "nodes": self.node_count},
                {"duration": self.duration})

    def __repr__(self) -> str:
        return "StabilityResult(omega=%g, mode=%d, eig_growth=%.6g, verdict=%s, index=%d)" % (
            self.omega, self.mode, self.eig_growth, self.verdict, self.index)


def _model(chain: Chain, omega: float, damping: float, drive_radius: float, air_drag: float,
           air_drag_quadratic: float, u: Optional[Units] = None) -> Any:
    u = u or Units()
    m = ffi.new("whirl_model *")
    m.chain = chain._c
    m.dim = 3
    m.frame = 1
    m.omega = omega
    m.internal_damping = as_float(damping, "damping", nonnegative=True, kind="damping",
                                  units=u) / u.damping
    m.drive_radius = as_float(drive_radius, "drive_radius", nonnegative=True,
                              kind="length", units=u) / u.length
    m.air_drag = as_float(air_drag, "air_drag", nonnegative=True, kind="drag",
                          units=u) / u.drag
    m.air_drag_quadratic = as_float(air_drag_quadratic, "air_drag_quadratic",
                                    nonnegative=True, kind="drag2", units=u) / u.drag2
    return m


def _eigenvalues(w: Any) -> np.ndarray:
    count = ffi.new("size_t *")
    re = ffi.new("const double **")
    im = ffi.new("const double **")
    check(lib.whirl_stability_eigenvalues(w, count, re, im))
    n = count[0]
    r = np.frombuffer(ffi.buffer(re[0], 8 * n), dtype=np.float64)
    i = np.frombuffer(ffi.buffer(im[0], 8 * n), dtype=np.float64)
    return r + 1j * i


def _modes(w: Any, n: int) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The eigenvalues, displacements (count, N + 1, 3), angles (count, 2N) and Krein signatures
    of the last linearisation in w (whirl_stability_eigenvectors)."""
    md = _lib.check_ptr(lib.whirl_stability_modes_alloc(n), lib.whirl_stability_modes_free)
    check(lib.whirl_stability_eigenvectors(w, md))
    k = int(md.count)

    def arr(ptr: Any, size: int) -> np.ndarray:
        return np.frombuffer(ffi.buffer(ptr, 8 * size), dtype=np.float64).copy()
    lam = arr(md.re, k) + 1j * arr(md.im, k)
    d = (arr(md.node_re, k * 3 * (n + 1)) + 1j * arr(md.node_im, k * 3 * (n + 1)))
    a = arr(md.angle_re, k * 2 * n) + 1j * arr(md.angle_im, k * 2 * n)
    krein = np.frombuffer(ffi.buffer(md.krein, ffi.sizeof("int") * k), dtype=np.intc).astype(int)
    return lam, d.reshape(k, n + 1, 3), a.reshape(k, 2 * n), krein


@ffi.callback("int(double, double, void *)")
def _observe_stop(t: float, ratio: float, data: Any) -> int:
    """The perturbed run's observer: stops it (WHIRL_EINTERRUPTED) once a stop is requested."""
    return lib.WHIRL_EINTERRUPTED if lib.whirl_stop_requested() else 0


@_lib.interruptible("stability")  # one block: Ctrl-C between its library calls too
def stability(omega: float, mode: int, links: Union[int, Chain], damping: float = 0.0,
              linear: bool = False, periods: float = 100.0, perturb: float = 1e-10,
              method: str = "rk4", seed: int = 1, dt: float = 0.0, drive_radius: float = 0.0,
              air_drag: float = 0.0, air_drag_quadratic: float = 0.0, side: int = 1,
              length: Optional[float] = None, mass: Optional[float] = None,
              gravity: Optional[float] = None, units: Optional[Units] = None,
              modes: bool = False, along: Optional[int] = None,
              progress: Any = None) -> StabilityResult:
    """The stability of the steady shape of ``mode`` at ``omega`` [sqrt(g/L), or rad/s] of the
    N-link chain ``links`` (N or a Chain), as ``whirl stability --omega W --mode K --links N``
    (damping, dt, drive_radius, the drags in the units of --damping, --dt, --eps, --drag,
    --drag-quadratic).

    damping: internal damping D; linear=True: eigenvalues only (no run); otherwise a run of
    ``periods`` rotation periods from the shape with every link turned by ``perturb`` [rad]
    (``seed`` of the random directions) with ``method`` (default rk4) and step ``dt`` (0: the
    library's default). With drive_radius > 0 (and air_drag, air_drag_quadratic) the shape is
    the hand-swung chain's trailing shape on ``side`` +1 or -1, or with mode=0 its near-axis
    shape. modes=True: the modes too (StabilityResult's displacements, angles, krein; as
    ``whirl stability --eigenvectors``). along=k (an index into ``eigenvalues``): the run starts
    along mode k (the real part of its angles, the largest turned by ``perturb``) instead of
    random directions; implies modes. progress: the perturbed run's time [T] out of its
    ``periods`` (see whirl's progress=). Returns a StabilityResult;
    whirl.Error if the shape does not exist; Ctrl-C raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    chain = _chain(links, 0.0, dense=True)
    assert chain is not None
    w = as_float(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    m = _model(chain, w, damping, drive_radius, air_drag, air_drag_quadratic, u)
    driven = m.drive_radius > 0 or m.air_drag > 0 or m.air_drag_quadratic > 0
    # mode 0: the hand-swung chain's near-axis shape (whirl_driven_mode)
    mode = 0 if driven and as_int(mode, "mode") == 0 else _mode(mode, chain)
    ws = _lib.check_ptr(lib.whirl_stability_alloc(chain.n), lib.whirl_stability_free)
    growth = ffi.new("double *")
    with _lib.interruptible("stability"):
        if driven:
            info = ffi.new("whirl_driven_info *")
            status = lib.whirl_stability_driven_mode(ws, m, mode, side, info, growth)
            nodes = int(info.nodes)
        else:
            info = ffi.new("whirl_shape_info *")
            status = lib.whirl_stability_mode(ws, m, mode, info, growth)
            nodes = int(info.n_nodes) + 1
    check(status, "stability", u)
    g = float(growth[0])
    index = ffi.new("int *")
    check(lib.whirl_stability_index(ws, index), "stability", u)
    linear_verdict = lib.whirl_verdict_linear(g, index[0])
    res = StabilityResult(omega=w * u.rate, mode=mode, tip_r=info.tip_r * u.length,
                          node_count=nodes, eig_growth=g * u.rate,
                          eigenvalues=_eigenvalues(ws) * u.rate,
                          verdict=ffi.string(lib.whirl_verdict_name(linear_verdict)).decode(),
                          index=int(index[0]), units=u, links=chain.n)
    _lib.finite("the stability", res.omega, res.tip_r, res.eig_growth, res.eigenvalues)
    along_buf = None
    if modes or along is not None:
        lam, d, a, krein = _modes(ws, chain.n)
        # the library scales a mode to 1 L; in the caller's units to 1 length unit
        res.displacements = d
        res.angles = a / u.length
        res.krein = krein
        if along is not None:
            k = as_int(along, "along", minimum=0)
            if k >= len(lam):
                raise ValueError("along must be an index into the %d eigenvalues, got %d"
                                 % (len(lam), k))
            along_buf = ffi.new("double[]", [float(v) for v in a[k].real])
    if linear:
        return res
    p = ffi.new("whirl_stability_run_params *", lib.whirl_stability_run_defaults())
    p.periods = as_float(periods, "periods", positive=True)
    p.perturbation = as_float(perturb, "perturb", positive=True)
    p.seed = as_int(seed, "seed", minimum=0)
    name = ffi.new("char[]", _method(method).encode())
    p.method = name
    p.dt = as_float(dt, "dt", nonnegative=True, kind="time", units=u) / u.time
    p.observe = _observe_stop
    if along_buf is not None:
        p.along = along_buf
    x, y, z = (ffi.new("const double **") for _ in range(3))
    lib.whirl_stability_nodes(ws, x, y, z)
    out = ffi.new("whirl_stability_run_result *")
    span = p.periods * 2 * np.pi / w * u.time
    rep = _progress.report(progress, "stability", span, "s" if u.physical else "T")
    if _progress.active(progress):
        @ffi.callback("int(double, double, void *)")
        def observe(t: float, ratio: float, data: Any) -> int:
            rep.c_update(t * u.time)
            return lib.WHIRL_EINTERRUPTED if lib.whirl_stop_requested() else 0
        p.observe = observe
    with rep, _lib.interruptible("stability"):
        status = lib.whirl_stability_run_shape(m, x[0], y[0], z[0], p, out)
        rep.reraise()
        # the step asked for, in the caller's units (the run's own steps end at its samples)
        check(status, "stability" if p.dt == 0 else "stability (%s with dt = %s)"
              % (ffi.string(name).decode(), _lib.in_units(p.dt, "time", u)), u)
        rep.finish()
    res.sim_growth = out.sim_growth * u.rate
    res.max_deviation = out.max_deviation
    res.duration = out.duration * u.time
    res.verdict = ffi.string(lib.whirl_verdict_name(
        lib.whirl_verdict_refine(out.verdict, res.index))).decode()
    res.stats = _stats(out.stats)
    return res


MAP_DTYPE = [("omega", "f8"), ("tip_r", "f8"), ("growth", "f8")]


@_lib.interruptible("stability_map")  # one block: Ctrl-C between its library calls too
def stability_map(omega: Any, mode: int, links: Union[int, Chain], damping: float = 0.0,
                  length: Optional[float] = None, mass: Optional[float] = None,
                  gravity: Optional[float] = None, units: Optional[Units] = None,
                  progress: Any = None) -> np.ndarray:
    """The linear growth rate of ``mode`` of the N-link chain over the rates ``omega`` (array,
    [sqrt(g/L), or rad/s]), the branch followed by continuation, as ``whirl stability
    --omega-min ... --linear``. Returns a structured array (omega, tip_r, growth [1/T]) with one
    row per rate where the mode exists; growth > 0: unstable. whirl.InvalidInput when the mode
    exists at none of the rates (the message says where it is born). progress: the shapes
    analysed (see whirl's progress=). Ctrl-C raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    chain = _chain(links, 0.0, dense=True)
    assert chain is not None
    mode = _mode(mode, chain)
    w = as_array(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    _lib.bounded(w.size, "len(omega)", 24 * (chain.n + 1) + 64)
    damping = as_float(damping, "damping", nonnegative=True, kind="damping", units=u) / u.damping
    n = w.size
    info = ffi.new("whirl_shape_info[]", n)
    exists = np.zeros(n, dtype=np.intc)
    # the shapes' nodes from the branch's link angles (at high rates the tip radius alone does
    # not fix them)
    r, z, tension = (np.empty((n, chain.n + 1)) for _ in range(3))
    with _lib.interruptible("stability_map"):
        status = lib.whirl_nlink_branch_nodes(chain._c, mode, n, _lib.dptr(w), info,
                                              ffi.cast("int *", ffi.from_buffer(exists)),
                                              _lib.dptr(r), _lib.dptr(z), _lib.dptr(tension))
    check(status, "stability_map of mode %d" % mode, u)
    # the growth of each shape: the library's map (whirl_stability_map, as the command line's)
    rows = np.flatnonzero(exists)
    if rows.size == 0:
        raise _lib.error(1, "stability_map: no rate of the grid %s has a shape of mode %d: %s"
                         % (_grid_text(w, u), mode, _absent(mode, chain, 0.0, w, u)))
    pts = ffi.new("whirl_stability_point[]", max(rows.size, 1))
    for i, j in enumerate(rows):
        pts[i].omega = w[j]
        pts[i].r = _lib.dptr(r[j])
        pts[i].z = _lib.dptr(z[j])
    rep = _progress.report(progress, "stability_map", rows.size, "points")
    tick = ffi.NULL
    if _progress.active(progress):
        @ffi.callback("whirl_stability_map_progress")
        def tick(ctx: Any, done: int) -> None:  # on the thread that analysed the point
            rep.c_update(done)
    with rep:
        with _lib.interruptible("stability_map"):
            status = lib.whirl_stability_map(chain._c, damping, rows.size, pts, tick, ffi.NULL)
            rep.reraise()
        failed = [i for i in range(rows.size) if pts[i].status not in (_lib.GSL_SUCCESS, -1)]
        check(status, "stability_map at omega %.17g" % (w[rows[failed[0]]] * u.rate) if failed
              else "stability_map", u)
        rep.finish()
    out = np.empty(rows.size, dtype=MAP_DTYPE)
    for i, j in enumerate(rows):
        out[i] = (w[j], info[j].tip_r, pts[i].growth)
    out["omega"] *= u.rate
    out["tip_r"] *= u.length
    out["growth"] *= u.rate
    return out


WINDOW_DTYPE = [("from", "f8"), ("to", "f8"), ("open_from", "?"), ("open_to", "?"),
                ("freq_from", "f8"), ("freq_to", "f8"), ("max_growth", "f8"),
                ("at", "f8"), ("err_from", "f8"), ("err_to", "f8")]


def _windows_params(omega_min: Optional[float], omega_max: Optional[float],
                    scan_step: Optional[float], tol: Optional[float], u: Units) -> Any:
    """The whirl_windows_params of a window search; the defaults (None) are the command line's,
    in the dimensionless units: 1, 10, 0.25, 1e-9."""
    p = ffi.new("whirl_windows_params *", lib.whirl_windows_defaults())
    p.omega_min = 1.0 if omega_min is None else as_float(omega_min, "omega_min",
                                                         positive=True, kind="rate",
                                                         units=u) / u.rate
    p.omega_max = 10.0 if omega_max is None else as_float(omega_max, "omega_max",
                                                          positive=True, kind="rate",
                                                          units=u) / u.rate
    if not p.omega_min < p.omega_max:
        raise ValueError("omega_min must be < omega_max, got %g and %g"
                         % (p.omega_min * u.rate, p.omega_max * u.rate))
    p.scan_step = 0.25 if scan_step is None else as_float(scan_step, "scan_step",
                                                          positive=True, kind="rate",
                                                          units=u) / u.rate
    p.tol = 1e-9 if tol is None else as_float(tol, "tol", positive=True,
                                              kind="rate", units=u) / u.rate
    return p


def _memory_mb(value: Any) -> float:
    """The continuum's workspace bound [MB]: 16 up to the machine's memory (ValueError)."""
    mb = as_float(value, "memory_mb")
    machine = _lib.MEMORY / 1048576
    if not 16 <= mb <= min(machine, 1048576):
        raise ValueError("memory_mb must be in [16, %.0f] (the machine's memory), got %g"
                         % (min(machine, 1048576), mb))
    return mb


def stability_windows(mode: int, links: Union[None, int, Chain] = None,
                      omega_min: Optional[float] = None, omega_max: Optional[float] = None,
                      scan_step: Optional[float] = None, tol: Optional[float] = None,
                      krylov: bool = True, max_windows: int = 1024, degree: Optional[int] = None,
                      tip_mass: float = 0.0, memory_mb: Optional[float] = None,
                      length: Optional[float] = None,
                      mass: Optional[float] = None, gravity: Optional[float] = None,
                      units: Optional[Units] = None,
                      progress: Any = None) -> Tuple[np.ndarray, Dict[str, Any]]:
    """The windows of instability of ``mode`` of the conservative N-link chain (``links``: N or
    a Chain) or, with links=None, of the continuous chain (its string equations linearised by
    Chebyshev collocation on elements of ``degree``, default the library's 16, with a point mass
    ``tip_mass`` [M, or kg] at the free end; ``memory_mb``: the bound of its workspace, default
    the library's 1024 MB, 16 up to the machine's memory, as ``--memory``: a shape that needs
    more collocation points than it holds is refused with whirl.Error),
    for rates in [omega_min, omega_max] [sqrt(g/L), or rad/s; scan_step and tol too; the
    defaults, as the command line's, 1, 10, 0.25 and 1e-9 sqrt(g/L)], as
    ``whirl windows``: the edges are the rates where two eigenvalues collide (Krein
    collision), located to ``tol`` after a scan with spacing ``scan_step``. Returns (windows,
    stats): a structured array with fields from, to (the unstable interval), open_from, open_to
    (True: that end is the end of the range, not an edge), freq_from, freq_to (|Im lambda| where
    the pair meets [1/T]), max_growth [1/T], at (where it occurs) and err_from, err_to (the
    continuum's estimate of each edge's discretisation error; 0 for the N-link chain), in
    increasing omega; stats
    a dict of the search's counters. whirl.Error (EDOM) if the mode does not exist in the range;
    Ctrl-C raises KeyboardInterrupt. progress: the continuous chain's rates examined, from
    omega_min, out of omega_max - omega_min [1/T] (the N-link chain's search reports only its
    end; see whirl's progress=)."""
    u = units_of(length, mass, gravity, units)
    chain = _chain(links, 0.0, dense=True)
    mode = _mode(mode, chain, lib.WHIRL_MODE_MAX)
    if links is not None and (degree is not None or tip_mass or memory_mb is not None):
        raise ValueError("degree, tip_mass and memory_mb apply to the continuous chain "
                         "(links=None)")
    p = _windows_params(omega_min, omega_max, scan_step, tol, u)
    p.krylov = 1 if krylov else 0
    rep = _progress.report(progress, "stability_windows",
                           (p.omega_max - p.omega_min) * u.rate, "")
    cap = _lib.bounded(as_int(max_windows, "max_windows", minimum=1), "max_windows", 64)
    found = ffi.new("whirl_window[]", cap)
    count = ffi.new("size_t *")
    st = ffi.new("whirl_windows_stats *")
    if links is None:
        cp = ffi.new("whirl_cstab_params *", lib.whirl_cstab_defaults())
        if degree is not None:
            cp.degree = as_int(degree, "degree", minimum=6, maximum=64)
        cp.tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True,
                               kind="mass", units=u) / u.mass
        if memory_mb is not None:
            cp.memory_mb = _memory_mb(memory_mb)
        if _progress.active(progress):
            @ffi.callback("void(void *, int, double)")
            def tick(ctx: Any, k: int, omega: float) -> None:
                rep.c_update((omega - p.omega_min) * u.rate)
            cp.progress = tick
        ws = _lib.check_ptr(lib.whirl_cstab_alloc(cp), lib.whirl_cstab_free)
        with rep:
            with _lib.interruptible("stability_windows"):
                status = lib.whirl_cstab_windows(ws, mode, p, found, cap, count, st)
                rep.reraise()
            check(status, "stability_windows of mode %d" % mode, u)
            rep.finish()
    else:
        assert chain is not None
        ws = _lib.check_ptr(lib.whirl_windows_alloc(chain.n), lib.whirl_windows_free)
        with rep:
            with _lib.interruptible("stability_windows"):
                status = lib.whirl_windows_find(ws, chain._c, mode, p, found, cap, count, st)
            check(status, "stability_windows of mode %d" % mode, u)
            rep.finish()
    out = np.empty(count[0], dtype=WINDOW_DTYPE)
    for i in range(count[0]):
        f = found[i]
        out[i] = (getattr(f, "from"), f.to, bool(f.open_from), bool(f.open_to), f.freq_from, f.freq_to,
                  f.max_growth, f.at, f.err_from, f.err_to)
    for name in ("from", "to", "freq_from", "freq_to", "max_growth", "at", "err_from", "err_to"):
        out[name] *= u.rate
    stats = {k: getattr(st, k) for k in ("omega_from", "omega_to", "scan", "shapes",
                                          "solves_vectors", "solves_values", "solves_krylov",
                                          "approaches", "unresolved")}
    stats["omega_from"] *= u.rate
    stats["omega_to"] *= u.rate
    return out, stats


DISSIPATIVE_DTYPE = [("from", "f8"), ("to", "f8"), ("open_from", "?"), ("open_to", "?"),
                     ("freq_from", "f8"), ("freq_to", "f8"), ("growth", "f8"),
                     ("at", "f8"), ("verdict", "U10")]


def dissipative_windows(mode: int, links: Union[int, Chain], damping: float = 0.0,
                        drive_radius: float = 0.0, air_drag: float = 0.0,
                        air_drag_quadratic: float = 0.0, side: int = 1,
                        omega_min: Optional[float] = None, omega_max: Optional[float] = None,
                        scan_step: Optional[float] = None, tol: Optional[float] = None,
                        max_intervals: int = 1024, length: Optional[float] = None,
                        mass: Optional[float] = None, gravity: Optional[float] = None,
                        units: Optional[Units] = None,
                        progress: Any = None) -> Tuple[np.ndarray, Dict[str, Any]]:
    """The intervals of rates where ``mode`` of the N-link chain ``links`` (N or a Chain) is
    unstable or converging with dissipation, as ``whirl windows --links N`` with
    --damping or the hand-swung chain's drag (damping, drive_radius, air_drag,
    air_drag_quadratic in the units of --damping, --eps, --drag, --drag-quadratic; ``side`` of
    the hand-swung shape, +1 or -1). The growth max Re lambda is scanned with spacing
    ``scan_step`` over [omega_min, omega_max] (defaults as stability_windows's) and its roots,
    the edges, located to ``tol`` by Brent's method. Returns (intervals, stats): a structured
    array with fields from, to, open_from, open_to (True: the end of the range or of the
    hand-swung shape's existence, not an edge), freq_from, freq_to (|Im lambda| of the eigenvalue
    crossing at each edge [1/T]), growth (the largest growth of an unstable interval, the most
    negative of a converging one [1/T]), at (where) and verdict ("unstable" or "converging"),
    in increasing omega; stats a dict of the search's counters. whirl.Error without
    dissipation or if the mode does not exist in the range; Ctrl-C raises KeyboardInterrupt.
    progress: the search reports only its end (see whirl's progress=)."""
    u = units_of(length, mass, gravity, units)
    chain = _chain(links, 0.0, dense=True)
    assert chain is not None
    mode = _mode(mode, chain)
    side = as_int(side, "side")
    if side not in (1, -1):
        raise ValueError("side must be 1 or -1, got %d" % side)
    m = _model(chain, 0.0, damping, drive_radius, air_drag, air_drag_quadratic, u)
    p = _windows_params(omega_min, omega_max, scan_step, tol, u)
    cap = _lib.bounded(as_int(max_intervals, "max_intervals", minimum=1), "max_intervals", 64)
    found = ffi.new("whirl_dissipative_interval[]", cap)
    count = ffi.new("size_t *")
    st = ffi.new("whirl_windows_stats *")
    with _progress.report(progress, "dissipative_windows", 1, "search") as rep:
        with _lib.interruptible("dissipative_windows"):
            status = lib.whirl_windows_dissipative(m, mode, side, p, found, cap, count, st)
        check(status, "dissipative_windows of mode %d" % mode, u)
        rep.finish()
    out = np.empty(count[0], dtype=DISSIPATIVE_DTYPE)
    for i in range(count[0]):
        f = found[i]
        out[i] = (getattr(f, "from"), f.to, bool(f.open_from), bool(f.open_to), f.freq_from,
                  f.freq_to, f.growth, f.at, ffi.string(lib.whirl_verdict_name(f.verdict)).decode())
    for name in ("from", "to", "freq_from", "freq_to", "growth", "at"):
        out[name] *= u.rate
    stats = {k: getattr(st, k) for k in ("omega_from", "omega_to", "scan", "shapes",
                                          "solves_values")}
    stats["omega_from"] *= u.rate
    stats["omega_to"] *= u.rate
    return out, stats
