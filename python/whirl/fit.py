"""Fitting the rotation rate and mode to a measured shape (whirl/optimize.h, ``whirl fit``)."""
from . import _lib
from ._lib import ffi, lib, check, as_int, as_float, as_array
from .steady import Units


class FitResult:
    """``omega`` and its standard error ``omega_err`` [sqrt(g/L), or rad/s], ``mode``,
    ``rms_residual`` (RMS distance of the points to the model curve [L, or m]), ``mirrored``
    (the points lie on the side r < 0), ``evaluations`` and ``failures`` of the model."""

    def __repr__(self):
        return "FitResult(omega=%.8g +- %.2g, mode=%d, rms_residual=%.3g)" % (
            self.omega, self.omega_err, self.mode, self.rms_residual)


def fit(r, z, mode=0, links=None, tip_mass=0.0, omega_max=None, samples=None, length=1.0,
        mass=1.0, gravity=1.0):
    """The rotation rate and mode that best explain measured points (r[i], z[i]) (signed
    distance from the axis and height, the pivot at the origin, any order; [L, or the unit of
    ``length``]), by least squares on the distance of each point to the model curve.
    mode=0: the best mode; K >= 1: mode K only. links=None: the continuous chain; N: the uniform
    N-link chain. omega_max: the highest rate tried (default 50 sqrt(g/L)); samples: points of
    the continuum's model polyline (default 4001). With length [m] and gravity [m/s^2] the
    rates are in rad/s. Returns a FitResult; whirl.Error if no mode fits."""
    u = Units(length, mass, gravity)
    r = as_array(r, "r")
    z = as_array(z, "z", shape=r.shape)
    if r.size < 3:
        raise ValueError("a fit needs at least 3 points, got %d" % r.size)
    m = ffi.new("whirl_fit_model *", lib.whirl_fit_model_defaults())
    m.links = 0 if links is None else as_int(links, "links", minimum=1)
    m.tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True) / u.mass
    if omega_max is not None:
        m.omega_max = as_float(omega_max, "omega_max", positive=True) / u.rate
    if samples is not None:
        m.samples = as_int(samples, "samples", minimum=2)
    mode = as_int(mode, "mode", minimum=0, maximum=lib.WHIRL_MODE_MAX)
    rr, zz = r / u.length, z / u.length
    res = ffi.new("whirl_fit_result *")
    with _lib.interruptible():
        status = lib.whirl_fit(m, r.size, _lib.dptr(rr), _lib.dptr(zz), mode, res)
    check(status)
    out = FitResult()
    out.omega, out.omega_err = res.omega * u.rate, res.omega_err * u.rate
    out.mode, out.rms_residual = res.mode, res.rms_residual * u.length
    out.mirrored, out.evaluations, out.failures = bool(res.mirrored), res.evaluations, res.failures
    return out
