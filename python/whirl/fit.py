"""Fitting the rotation rate and mode to a measured shape (whirl/optimize.h, ``whirl fit``)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, Optional, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, check, as_int, as_float, as_array
from .steady import Chain, Units, units_of

# the command line's bounds (whirl fit --links; the library refuses more than 20000 points)
FIT_MAX_LINKS = 2000
FIT_MAX_SAMPLES = 10000000


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class FitResult(_lib.Result):
    """``omega`` and its standard error ``omega_err`` [sqrt(g/L), or rad/s], ``mode``,
    ``rms_residual`` (RMS distance of the points to the model curve [L, or m]), ``mirrored``
    (the points lie on the side r < 0), ``evaluations`` and ``failures`` of the model,
    ``units``."""

    omega: float
    omega_err: float
    mode: int
    rms_residual: float
    mirrored: bool
    evaluations: int
    failures: int
    units: Units = field(default_factory=Units)

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # whirl fit's row, then the fit's own counts
        return ({"omega": self.omega, "omega_err": self.omega_err, "mode": self.mode,
                 "rms_residual": self.rms_residual, "mirrored": self.mirrored,
                 "evaluations": self.evaluations, "failures": self.failures}, {})

    def __repr__(self) -> str:
        return "FitResult(omega=%.8g +- %.2g, mode=%d, rms_residual=%.3g)" % (
            self.omega, self.omega_err, self.mode, self.rms_residual)


def _uniform(chain: Chain, tip_mass: Any) -> Tuple[int, float]:
    """The link count and tip mass [M] of a Chain that is the uniform N-link chain (equal links
    of total length 1, equal masses of total 1 but for a tip mass on the last, g = 1: what
    Chain(N, tip_mass) builds), the only chain the fit's model has; ValueError otherwise."""
    if tip_mass:
        raise ValueError("tip_mass applies to a link count; a Chain carries its own masses")
    n = chain.n
    tip = float(chain.masses[-1] - chain.masses[0])
    same = Chain(n, max(tip, 0.0))
    # 1e-12: a chain typed in by hand (lengths [1/N] * N) differs from the library's in the
    # last bits
    if not (chain.gravity == 1.0 and np.allclose(chain.lengths, same.lengths, rtol=1e-12, atol=0)
            and np.allclose(chain.masses, same.masses, rtol=1e-12, atol=0)):
        raise ValueError("fit's model is the uniform N-link chain (links=N, tip_mass=...) or "
                         "the continuum: %r has unequal links or masses, or gravity != 1" % chain)
    return n, max(tip, 0.0)


def fit(r: Any, z: Any, mode: int = 0, links: Union[None, int, Chain] = None,
        tip_mass: float = 0.0,
        omega_max: Optional[float] = None, samples: Optional[int] = None,
        max_residual: float = 0.02, length: Optional[float] = None,
        mass: Optional[float] = None, gravity: Optional[float] = None,
        units: Optional[Units] = None, progress: Any = None) -> FitResult:
    """The rotation rate and mode that best explain measured points (r[i], z[i]) (signed
    distance from the axis and height, the pivot at the origin, any order; [L, or m with
    length given]), by least squares on the distance of each point to the model curve, as
    ``whirl fit``.
    mode=0: the best mode; K >= 1: mode K only. links=None: the continuous chain; N (at most
    2000): the uniform N-link chain (or a Chain that is one, Chain(N, tip_mass)). omega_max: the highest rate tried (default 50 sqrt(g/L));
    samples: points of the continuum's model polyline (default 4001). Units as everywhere
    (see Units): with length [m] the rates are in rad/s. Returns a FitResult; raises
    whirl.InvalidInput (a ValueError) when no mode has a shape in the range, or when the best
    fit leaves an rms residual above ``max_residual`` (a fraction of the chain's length, default
    0.02, the command line's --max-residual): no mode explains the points. progress: the modes
    tried (see whirl's progress=). Ctrl-C raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    r = as_array(r, "r", kind="length", units=u)
    z = as_array(z, "z", shape=r.shape, kind="length", units=u)
    if r.size < 3:
        raise ValueError("a fit needs at least 3 points, got %d" % r.size)
    m = ffi.new("whirl_fit_model *", lib.whirl_fit_model_defaults())
    if isinstance(links, Chain):
        links, tip_mass = _uniform(links, tip_mass)
    m.links = 0 if links is None else as_int(links, "links", minimum=1, maximum=FIT_MAX_LINKS)
    m.tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True, kind="mass", units=u) / u.mass
    if omega_max is not None:
        m.omega_max = as_float(omega_max, "omega_max", positive=True, kind="rate", units=u) / u.rate
    if samples is not None:
        m.samples = as_int(samples, "samples", minimum=2, maximum=FIT_MAX_SAMPLES)
    mode = as_int(mode, "mode", minimum=0, maximum=lib.WHIRL_MODE_MAX)
    limit = as_float(max_residual, "max_residual", positive=True)
    # the command line's arithmetic (times 1 / L): the optimiser's stop depends on the last bit
    scale = 1.0 / u.length
    rr, zz = r * scale, z * scale
    res = ffi.new("whirl_fit_result *")
    rep = _progress.report(progress, "fit", 1, "modes")
    tick = ffi.NULL
    if _progress.active(progress):
        @ffi.callback("whirl_fit_progress_fn")
        def tick(data: Any, k: int, first: int, last: int, evaluations: int) -> None:
            rep.set_total(last - first + 1)
            rep.c_update(k - first)  # the modes finished
    with rep:
        with _lib.interruptible("fit"):
            status = lib.whirl_fit_observed(m, r.size, _lib.dptr(rr), _lib.dptr(zz), mode, tick,
                                            ffi.NULL, res)
            rep.reraise()
        check(status, "fit", u)
        rep.finish()
    if not res.rms_residual <= limit:
        which = "mode %d" % mode if mode else "no mode"
        raise _lib.error(1, "fit: %s explains the shape: the best fit (mode %d, omega=%.6g%s) "
                            "leaves an rms residual of %.3g L, above max_residual %g"
                         % (which, res.mode, res.omega * u.rate,
                            " rad/s" if u.physical else "", res.rms_residual, limit))
    return FitResult(omega=res.omega * u.rate, omega_err=res.omega_err * u.rate,
                     mode=int(res.mode), rms_residual=res.rms_residual * u.length,
                     mirrored=bool(res.mirrored), evaluations=int(res.evaluations),
                     failures=int(res.failures), units=u)
