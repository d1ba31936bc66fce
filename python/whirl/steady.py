"""Steady shapes of the whirling chain: critical rates, shapes and branches (whirl/steady.h).

Units: dimensionless by default (chain length L = 1, mass M = 1, gravity g = 1: rates in
sqrt(g/L), lengths in L, tensions in M g). Give ``length`` [m], ``mass`` [kg] and ``gravity``
[m/s^2] (the command line's --length, --mass, --gravity) to work in SI units instead: rates are
then in rad/s, lengths in m, tensions in N, tip masses in kg."""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from ._lazy import numpy as np
from . import _lib, _progress
from ._lib import ffi, lib, check, as_int, as_float, as_array

STANDARD_GRAVITY = 9.80665  # WHIRL_STANDARD_GRAVITY [m/s^2]: g once SI units are on
UNIT_MIN, UNIT_MAX = 1e-30, 1e30  # the command line's range of each unit (CLI_UNIT_MIN/MAX)

# A count of links whose arrays and continuation work would fill memory is refused before it
# reaches the library: about this many bytes per link for the N-link solvers (banded Newton
# systems, the path's history), ...
LINK_BYTES = 1024
# ... and for the linearisation: four (2N)^2 blocks, the (4N)^2 companion matrix and LAPACK's
# copy, about 640 N^2 bytes.
DENSE_BYTES = 640


class Units:
    """The scales of the physical units, with the command line's rule: no argument (or all None)
    is dimensionless (chain length L, mass M, gravity g all 1: rates in sqrt(g/L), lengths in L,
    times in sqrt(L/g), forces in M g); any of ``length`` [m], ``mass`` [kg], ``gravity``
    [m/s^2] switches to SI units, the others defaulting to 1 m, 1 kg and 9.80665 m/s^2 (as
    ``--length``, ``--mass``, ``--gravity`` do). Each in [1e-30, 1e30]; length and mass may be
    texts with a unit as on the command line ("60cm", "50 g").
    Derived scales: ``rate`` sqrt(g/L) [1/s], ``time`` [s], ``force`` M g [N], ``drag``
    (linear drag per unit length) M sqrt(g/L) / L, ``drag2`` M / L^2, ``damping`` M L^2
    sqrt(g/L). Immutable; pickles."""

    __slots__ = ("length", "mass", "gravity", "physical")
    length: float
    mass: float
    gravity: float
    physical: bool

    def __init__(self, length: Optional[float] = None, mass: Optional[float] = None,
                 gravity: Optional[float] = None) -> None:
        physical = not (length is None and mass is None and gravity is None)
        values = {}
        for name, value, default in (("length", length, 1.0), ("mass", mass, 1.0),
                                     ("gravity", gravity,
                                      STANDARD_GRAVITY if physical else 1.0)):
            # a unit in the text ("60cm", "50g") as the command line's --length, --mass; a
            # pint quantity (gravity too)
            v = default if value is None else as_float(value, name, positive=True, kind=name)
            if not UNIT_MIN <= v <= UNIT_MAX:
                raise ValueError("%s must be in [%g, %g], got %r" % (name, UNIT_MIN, UNIT_MAX,
                                                                     v))
            values[name] = v
        object.__setattr__(self, "length", values["length"])
        object.__setattr__(self, "mass", values["mass"])
        object.__setattr__(self, "gravity", values["gravity"])
        object.__setattr__(self, "physical", physical)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("Units are immutable")

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        if not self.physical:
            return (Units, ())
        return (Units, (self.length, self.mass, self.gravity))

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Units) and self.physical == other.physical
                and (self.length, self.mass, self.gravity)
                == (other.length, other.mass, other.gravity))

    def __hash__(self) -> int:
        return hash((self.physical, self.length, self.mass, self.gravity))

    @property
    def rate(self) -> float:
        return math.sqrt(self.gravity / self.length)

    @property
    def time(self) -> float:
        return 1.0 / self.rate

    @property
    def force(self) -> float:
        return self.mass * self.gravity

    @property
    def drag(self) -> float:
        return self.mass * self.rate / self.length

    @property
    def drag2(self) -> float:
        return self.mass / (self.length * self.length)

    @property
    def damping(self) -> float:
        return self.mass * self.length * self.length * self.rate

    def __repr__(self) -> str:
        if not self.physical:
            return "Units()"
        return "Units(length=%r, mass=%r, gravity=%r)" % (self.length, self.mass, self.gravity)


def units_of(length: Optional[float] = None, mass: Optional[float] = None,
             gravity: Optional[float] = None, units: Optional[Units] = None) -> Units:
    """The Units of a call: ``units`` (a Units object) or length/mass/gravity, not both."""
    if units is None:
        return Units(length, mass, gravity)
    if not isinstance(units, Units):
        raise TypeError("units must be a whirl.Units, got %r" % (units,))
    if not (length is None and mass is None and gravity is None):
        raise TypeError("give either units or length/mass/gravity, not both")
    return units


def links_count(links: Any, name: str = "links", dense: bool = False) -> int:
    """A link count as an int >= 1, refused if its work would not fit in memory."""
    n = as_int(links, name, minimum=1)
    if dense:
        return _lib.bounded(n, name, DENSE_BYTES, power=2)
    return _lib.bounded(n, name, LINK_BYTES)


class Chain:
    """An N-link chain: N point masses on massless rigid links (whirl_chain).

    Chain(links, tip_mass=0): N equal links and masses, total length 1 and mass 1, g = 1, the
    tip mass [M] added to the last mass (the discrete model of the uniform chain).
    Chain(lengths=[...], masses=[...], gravity=1): any links [L] and masses [M].
    Attributes: ``n``, ``lengths``, ``masses`` (numpy copies), ``gravity``. Pickles and copies
    by its lengths, masses and gravity; equal chains compare equal."""

    def __init__(self, links: Optional[int] = None, tip_mass: float = 0.0,
                 lengths: Optional[Union[Sequence[float], np.ndarray]] = None,
                 masses: Optional[Union[Sequence[float], np.ndarray]] = None,
                 gravity: float = 1.0) -> None:
        if links is not None:
            if lengths is not None or masses is not None:
                raise TypeError("give either links or lengths and masses, not both")
            n = links_count(links)
            tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True)
            ptr = lib.whirl_chain_alloc_uniform(n, tip_mass)
        else:
            if lengths is None or masses is None:
                raise TypeError("Chain needs links, or both lengths and masses")
            length = as_array(lengths, "lengths", positive=True)
            links_count(length.size, "len(lengths)")
            mass = as_array(masses, "masses", shape=length.shape, positive=True)
            g = as_float(gravity, "gravity", positive=True)
            ptr = lib.whirl_chain_alloc(length.size, _lib.dptr(length), _lib.dptr(mass), g)
        self._c = _lib.check_ptr(ptr, lib.whirl_chain_free)

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        return (_chain_from, (self.lengths, self.masses, self.gravity))

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Chain) and self.n == other.n
                and self.gravity == other.gravity
                and bool(np.array_equal(self.lengths, other.lengths))
                and bool(np.array_equal(self.masses, other.masses)))

    __hash__ = None  # type: ignore[assignment]

    @property
    def n(self) -> int:
        return int(self._c.n)

    @property
    def lengths(self) -> np.ndarray:
        return np.frombuffer(ffi.buffer(self._c.length, 8 * self.n), dtype=np.float64).copy()

    @property
    def masses(self) -> np.ndarray:
        return np.frombuffer(ffi.buffer(self._c.mass, 8 * self.n), dtype=np.float64).copy()

    @property
    def gravity(self) -> float:
        return float(self._c.gravity)

    def __repr__(self) -> str:
        return "Chain(n=%d, length=%g, mass=%g, gravity=%g)" % (
            self.n, lib.whirl_chain_total_length(self._c), lib.whirl_chain_total_mass(self._c),
            self.gravity)


def _chain_from(lengths: np.ndarray, masses: np.ndarray, gravity: float) -> Chain:
    return Chain(lengths=lengths, masses=masses, gravity=gravity)


def _chain(links: Union[None, int, Chain], tip_mass: float,
           dense: bool = False) -> Optional[Chain]:
    """None for the continuum, else a Chain (an int builds the uniform chain)."""
    if links is None:
        return None
    if isinstance(links, Chain):
        if tip_mass:
            raise ValueError("tip_mass applies to a uniform chain given by its link count; "
                             "put it into the Chain's masses")
        if dense:
            links_count(links.n, "links", dense=True)
        return links
    return Chain(links_count(links, dense=dense), tip_mass)


def _mode(mode: Any, chain: Optional[Chain], continuum_max: Optional[int] = None) -> int:
    """The N-link chain has modes 1..N (any N), the continuum's steady shapes
    1..WHIRL_CONTINUUM_MODE_MAX (continuum_max: the limit of a model built on them)."""
    if chain is None:
        top = lib.WHIRL_CONTINUUM_MODE_MAX if continuum_max is None else continuum_max
        return as_int(mode, "mode", minimum=1, maximum=top)
    mode = as_int(mode, "mode", minimum=1)
    if mode > chain.n:
        raise ValueError("mode %d does not exist: a chain of %d links has modes 1..%d"
                         % (mode, chain.n, chain.n))
    return mode


def critical(modes: int = 3, links: Union[None, int, Chain] = None, tip_mass: float = 0.0,
             progress: Any = None, length: Optional[float] = None, mass: Optional[float] = None,
             gravity: Optional[float] = None, units: Optional[Units] = None) -> np.ndarray:
    """The linear critical rates omega_1..omega_modes at which modes 1..modes bifurcate from the
    hanging chain, as an array [sqrt(g/L), or rad/s with physical units].

    links=None: the continuous chain (j_{0,k}/2 without a tip mass; with a tip mass [M, or kg]
    the roots of a J0/Y0 determinant); links=N or a Chain: the normal-mode frequencies of the
    hanging N-link chain. ``whirl critical`` on the command line (the same units rule: see
    Units). progress: the rates found (see whirl's progress=; the N-link chain's come in blocks
    of about 0.02 s, tens of thousands of links take seconds; the continuum's report their
    end). Ctrl-C raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    modes = as_int(modes, "modes", minimum=1)
    m = as_float(tip_mass, "tip_mass", nonnegative=True, kind="mass", units=u) / u.mass
    chain = _chain(links, m)
    out = np.empty(modes)
    if chain is None:
        if modes > lib.WHIRL_CONTINUUM_MODE_MAX:
            raise ValueError("modes must be <= %d, got %d" % (lib.WHIRL_CONTINUUM_MODE_MAX,
                                                             modes))
        with _progress.report(progress, "critical", modes, "rates") as rep:
            with _lib.interruptible("critical"):
                status = lib.whirl_continuum_critical_rates(modes, m, _lib.dptr(out))
            check(status, "critical", u)
            rep.finish()
    else:
        if modes > chain.n:
            raise ValueError("a chain of %d links has modes 1..%d, asked for %d"
                             % (chain.n, chain.n, modes))
        with _progress.report(progress, "critical", modes, "rates") as rep:
            with _lib.interruptible("critical"):
                if _progress.active(progress):
                    @ffi.callback("whirl_nlink_critical_progress_fn")
                    def found(ctx: Any, done: int, total: int) -> None:
                        rep.c_update(done)
                    status = lib.whirl_nlink_critical_report(chain._c, modes, _lib.dptr(out),
                                                             found, ffi.NULL)
                else:
                    status = lib.whirl_nlink_critical(chain._c, modes, _lib.dptr(out))
                rep.reraise()
            check(status, "critical", u)
            rep.finish()
    out *= u.rate
    _lib.finite("critical rates", out)
    return out


@dataclass(eq=False)  # _lib.Result's == (array-aware)
class Shape(_lib.Result):
    """A steady shape (``whirl shape``): arrays ``s`` (arclength from the pivot), ``r`` (signed
    distance from the axis, the free end at r > 0), ``z`` (height, pivot 0, z <= 0) and
    ``tension`` [L, L, L, M g; or m, m, m, N], from the pivot to the free end (N-link chain:
    the pivot, then masses 1..N, tension of the link above); the summary ``omega``, ``mode``,
    ``node_count`` (the pivot plus the axis crossings, as the command line's node_count: equal
    to the mode on its branch; a warning is issued where it differs), ``tip_r``, ``max_r``,
    ``top_tension``, ``depth``, ``crossings`` (arclengths of the axis crossings below the pivot:
    all of them for the N-link chain, the first 64 for the continuum; where an N-link shape's
    radii underflow towards the tip, r is 0 or subnormal and the crossings there come from the
    force balance linearised about the hanging chain; the command line's ``crossing_s=``), ``units``,
    and the branch it lies on: ``critical`` (omega_k where mode k is born), ``chain`` (None:
    the continuum) and ``tip_mass``. A dataclass: pickles and copies."""

    omega: float
    mode: int
    node_count: int
    tip_r: float
    max_r: float
    top_tension: float
    depth: float
    crossings: np.ndarray
    s: np.ndarray
    r: np.ndarray
    z: np.ndarray
    tension: np.ndarray
    units: Units = field(default_factory=Units)
    chain: Optional[Chain] = None
    tip_mass: float = 0.0

    @property
    def links(self) -> Optional[int]:
        """The link count (None: the continuum)."""
        return None if self.chain is None else self.chain.n

    @property
    def critical(self) -> float:
        """omega_k: the rate where this shape's mode is born [sqrt(g/L), or rad/s]."""
        return float(critical(self.mode, links=self.chain,
                              tip_mass=0.0 if self.chain else self.tip_mass,
                              units=self.units)[-1])

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        # whirl shape's columns and summary line
        return ({"s": self.s, "r": self.r, "z": self.z, "tension": self.tension},
                {"omega": self.omega, "mode": self.mode, "node_count": self.node_count,
                 "tip_r": self.tip_r, "max_r": self.max_r, "top_tension": self.top_tension,
                 "depth": self.depth, "tip_mass": self.tip_mass})

    def __repr__(self) -> str:
        return ("Shape(omega=%.10g, mode=%d, node_count=%d, tip_r=%.10g, top_tension=%.10g, "
                "depth=%.10g, %d points)" % (self.omega, self.mode, self.node_count, self.tip_r,
                                             self.top_tension, self.depth, self.s.size))


def _solve(chain: Optional[Chain], omega: float, mode: int, m: float, guess: float,
           nodes: Optional[Tuple[np.ndarray, ...]] = None) -> Tuple[int, Any]:
    """nodes: (r, z, tension) arrays of N + 1 for the N-link chain's nodes, which come from the
    branch's link angles (at high rates the tip radius alone does not fix them)."""
    info = ffi.new("whirl_shape_info *")
    # milliseconds below these sizes: no signal handlers to install
    long = (chain.n >= SHORT_LINKS) if chain is not None else mode > lib.WHIRL_MODE_MAX
    with _lib.interruptible_if(long, "shape"):
        if chain is None:
            status = lib.whirl_continuum_solve(omega, mode, m, guess, info)
        elif nodes is None:
            status = lib.whirl_nlink_solve(chain._c, omega, mode, info)
        else:
            status = lib.whirl_nlink_solve_nodes(chain._c, omega, mode, info,
                                                 *(_lib.dptr(a) for a in nodes))
    if status == lib.WHIRL_EINTERRUPTED:
        check(status, "shape")
    return status, info


# the command line's bound on the continuum's samples (whirl shape --points)
POINTS_MAX = 10000000
# shapes of fewer links or points take milliseconds: their calls skip the signal handlers
SHORT_LINKS = 1000
SHORT_POINTS = 100000


class Shapes(List[Shape]):
    """The shapes of shape(omega=array): a list of Shape, one per rate in the order given, with
    ``as_dict()`` and ``to_pandas()`` of their summaries in the columns of ``whirl sweep``
    (omega, mode, tip_r, max_r, top_tension, depth, nodes), labelled with their units."""

    def as_dict(self) -> Dict[str, np.ndarray]:
        from .columns import labelled
        rows = {"omega": [s.omega for s in self], "mode": [s.mode for s in self],
                "tip_r": [s.tip_r for s in self], "max_r": [s.max_r for s in self],
                "top_tension": [s.top_tension for s in self], "depth": [s.depth for s in self],
                "nodes": [s.node_count for s in self]}
        return labelled({k: np.array(v) for k, v in rows.items()},
                        self[0].units if self else Units())

    def to_pandas(self) -> Any:
        from .columns import data_frame
        return data_frame(self.as_dict(), {"units": repr(self[0].units if self else Units())})


def _many(value: Any) -> bool:
    """value is a sequence of rates (a list, a 1-D array, a pint array), not one."""
    if _lib.is_pint(value):
        value = value.magnitude
    return isinstance(value, (list, tuple)) or (isinstance(value, np.ndarray) and value.ndim > 0)


def shape(omega: Any, mode: int, links: Union[None, int, Chain] = None, tip_mass: float = 0.0,
          points: int = 201, tip_r_guess: float = 0.0, progress: Any = None,
          length: Optional[float] = None, mass: Optional[float] = None,
          gravity: Optional[float] = None, units: Optional[Units] = None) -> Any:
    """The steady shape of mode ``mode`` (node count: the pivot plus mode-1 axis crossings) at
    the rotation rate ``omega`` [sqrt(g/L), or rad/s with length/mass/gravity given].

    links=None: the continuous chain sampled at ``points`` equally spaced arclengths (default
    201, at most 10^7); links=N (or a Chain): the exact relative equilibrium of the N-link
    chain, one point per node. tip_mass [M, or kg]: a point mass at the free end. tip_r_guess
    > 0 seeds the root search (continuation). Returns a Shape; for a sequence of rates (a list,
    a 1-D array, a pint array; items may be texts with a unit, "4Hz") a Shapes, the list of
    their shapes in the order given (each solved as alone), progress= counting them (see
    whirl's progress=; one shape reports its end). Raises whirl.InvalidInput (a ValueError; status_name "EDOM") if the
    mode does not exist at omega, naming its critical rate. Ctrl-C raises KeyboardInterrupt;
    over a sequence of rates its ``partial`` holds the Shapes solved before it."""
    u = units_of(length, mass, gravity, units)
    if _many(omega):
        rates = as_array(omega, "omega", positive=True, kind="rate", units=u)
        # each shape keeps four arrays of its points (or nodes)
        size = (as_int(points, "points", minimum=2) if links is None
                else links.n + 1 if isinstance(links, Chain) else links_count(links) + 1)
        _lib.bounded(rates.size, "len(omega)", 32 * size + 256)
        return _shapes(rates, mode, links, tip_mass, points, tip_r_guess, progress, u)
    if _progress.active(progress):  # one shape: its end
        with _progress.report(progress, "shape", 1, "shapes") as rep:
            one = shape(omega, mode, links, tip_mass, points, tip_r_guess, units=u)
            rep.finish()
        return one
    w = as_float(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    m = as_float(tip_mass, "tip_mass", nonnegative=True, kind="mass", units=u) / u.mass
    guess = as_float(tip_r_guess, "tip_r_guess", nonnegative=True,
                     kind="length", units=u) / u.length
    chain = _chain(links, m)
    mode = _mode(mode, chain)
    if chain is None:
        n = _lib.bounded(as_int(points, "points", minimum=2), "points", 32, hard=POINTS_MAX)
    else:
        n = chain.n + 1
    s, r, z, t = (np.empty(n) for _ in range(4))
    status, info = _solve(chain, w, mode, m, guess, None if chain is None else (r, z, t))
    if status != _lib.GSL_SUCCESS:
        msg = _lib.last_error_in(u)
        if status == 1:  # GSL_EDOM: name where the mode is born, as the command line does
            try:
                wk = critical(mode, links=chain, tip_mass=0 if chain else tip_mass, units=u)[-1]
                if omega < wk:
                    msg = ("mode %d does not exist at omega=%.17g%s: it exists only above "
                           "omega_%d=%.17g%s" % (mode, omega, _rate_unit(u), mode, wk,
                                                  _rate_unit(u)))
            except (ValueError, _lib.Error):
                pass
        raise _lib.error(status, msg)
    if chain is None:
        with _lib.interruptible_if(n > SHORT_POINTS, "shape"):
            status = lib.whirl_continuum_sample(w, m, info.tip_r, n, _lib.dptr(s), _lib.dptr(r),
                                                _lib.dptr(z), _lib.dptr(t))
        check(status, "shape", u)
        # the continuum's first WHIRL_SHAPE_NODES from the pivot (n_nodes counts them all)
        crossings = np.array([info.node_s[j]
                              for j in range(min(info.n_nodes, lib.WHIRL_SHAPE_NODES))])
    else:
        # the nodes of the branch's own link angles (at high rates the tip radius alone does
        # not fix the shape to round-off); every axis crossing, not only the first
        # WHIRL_SHAPE_NODES the summary holds
        s[0] = 0
        np.cumsum(chain.lengths, out=s[1:])
        crossings = np.empty(max(info.n_nodes, 1))
        count = lib.whirl_nlink_node_arclengths(chain._c, info.omega, _lib.dptr(r),
                                                crossings.size, _lib.dptr(crossings),
                                                _lib.ffi.NULL)
        crossings = crossings[:min(count, crossings.size)]
    if u.physical:
        L, F = u.length, u.force
        crossings, s, r, z, t = crossings * L, s * L, r * L, z * L, t * F
        _lib.finite("the shape", r, z, t, info.omega * u.rate, info.top_tension * F)
    else:
        L = F = 1.0
    out = Shape(omega=info.omega * u.rate, mode=int(info.mode), node_count=info.n_nodes + 1,
                tip_r=info.tip_r * L, max_r=info.max_r * L, top_tension=info.top_tension * F,
                depth=info.depth * L, crossings=crossings, s=s, r=r, z=z, tension=t, units=u,
                chain=chain, tip_mass=float(tip_mass))
    if out.node_count != mode:
        import warnings
        warnings.warn("the shape of mode %d at omega=%.17g has %d nodes: its node count "
                      "differs from the mode" % (mode, omega, out.node_count), stacklevel=2)
    return out


def _shapes(rates: np.ndarray, mode: int, links: Union[None, int, Chain], tip_mass: float,
            points: int, tip_r_guess: float, progress: Any, u: Units) -> Shapes:
    """shape() over the rates (in the caller's units), one at a time: Ctrl-C between two of
    them or inside one raises KeyboardInterrupt with the shapes solved so far (``partial``)."""
    out = Shapes()
    with _progress.report(progress, "shape", rates.size, "shapes") as rep:
        try:
            with _lib.interruptible("shape"):
                for w in rates:
                    if lib.whirl_stop_requested():
                        lib.whirl_stop_clear()
                        raise _lib.interrupted("shape")
                    out.append(shape(float(w), mode, links, tip_mass, points, tip_r_guess,
                                     units=u))
                    rep.update(len(out))
        except KeyboardInterrupt as e:
            e.args = ("whirl: shape interrupted: %d of %d shapes" % (len(out), rates.size),)
            e.partial = out  # type: ignore[attr-defined]
            raise
        rep.finish()
    return out


def _rate_unit(u: Units) -> str:
    return " rad/s" if u.physical else ""


BRANCH_DTYPE = [("omega", "f8"), ("tip_r", "f8"), ("max_r", "f8"),
                ("top_tension", "f8"), ("depth", "f8"), ("node_count", "i4")]


@_lib.interruptible("sweep")  # one block: Ctrl-C between its library calls too
def sweep(modes: Union[int, Sequence[int]], omega: Any, links: Union[None, int, Chain] = None,
          tip_mass: float = 0.0, length: Optional[float] = None, mass: Optional[float] = None,
          gravity: Optional[float] = None, units: Optional[Units] = None,
          progress: Any = None) -> Dict[int, np.ndarray]:
    """The branches of the given modes over the rates ``omega`` (an array, any order;
    [sqrt(g/L), or rad/s]), each followed by continuation on all OpenMP threads (``whirl
    sweep``). Returns a dict {mode: structured array with fields omega, tip_r, max_r,
    top_tension, depth, node_count (the pivot plus the axis crossings, the command line's
    ``nodes`` column)}, one row per rate where the mode exists, in the order of ``omega``. A
    mode with no shape at any of the rates gets an empty array and an EmptyBranchWarning
    saying where it is born; when no mode asked for has one, whirl.InvalidInput (as the
    command line's "no mode exists on the grid"). progress: the modes done (see whirl's
    progress=). Ctrl-C raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    if isinstance(modes, (int, np.integer)) and not isinstance(modes, bool):
        modes = [int(modes)]
    assert not isinstance(modes, (bool, int))
    w = as_array(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    _lib.bounded(w.size, "len(omega)", 256 + (0 if links is None else 64), hard=POINTS_MAX)
    m = as_float(tip_mass, "tip_mass", nonnegative=True, kind="mass", units=u) / u.mass
    chain = _chain(links, m)
    try:
        mode_list = [_mode(k, chain) for k in modes]
    except TypeError:
        raise TypeError("modes must be an integer or a sequence of integers, got %r"
                        % (modes,)) from None
    n = w.size
    out = {}
    info = ffi.new("whirl_shape_info[]", n)
    exists = np.zeros(n, dtype=np.intc)
    ex = ffi.cast("int *", ffi.from_buffer(exists))
    rep = _progress.report(progress, "sweep", len(mode_list), "modes")
    for done, k in enumerate(mode_list, 1):
        with _lib.interruptible("sweep of mode %d" % k):
            if chain is None:
                status = lib.whirl_continuum_branch(k, m, n, _lib.dptr(w), info, ex)
            else:
                status = lib.whirl_nlink_branch(chain._c, k, n, _lib.dptr(w), info, ex)
        check(status, "sweep of mode %d" % k, u)
        rows = np.flatnonzero(exists)
        a = np.empty(rows.size, dtype=BRANCH_DTYPE)
        for i, j in enumerate(rows):
            f = info[j]
            a[i] = (w[j] * u.rate, f.tip_r * u.length, f.max_r * u.length,
                    f.top_tension * u.force, f.depth * u.length, f.n_nodes + 1)
        _lib.finite("the branch of mode %d" % k, *(a[c] for c in ("omega", "tip_r", "max_r", "top_tension", "depth")))
        out[k] = a
        rep.update(done)
    rep.close()
    empty = [k for k in mode_list if out[k].size == 0]
    if empty and len(empty) == len(set(mode_list)):  # nothing at all: the command line's error
        raise _lib.error(1, "sweep: no mode exists on the grid %s: %s"
                         % (_grid_text(w, u), _absent(empty[0], chain, m, w, u)))
    for k in empty:
        warnings.warn("sweep: no rows for mode %d: %s" % (k, _absent(k, chain, m, w, u)),
                      EmptyBranchWarning, stacklevel=3)
    return out


class EmptyBranchWarning(UserWarning):
    """A mode asked for that has no shape at any of the rates given (an empty array)."""


def _rate_text(w: float, u: Units) -> str:
    return "%.6g %s" % (w * u.rate, "rad/s" if u.physical else "sqrt(g/L)")


def _grid_text(w: np.ndarray, u: Units) -> str:
    return "%s to %s" % (_rate_text(float(w.min()), u), _rate_text(float(w.max()), u))


def _absent(mode: int, chain: Optional[Chain], tip_mass: float, w: np.ndarray, u: Units) -> str:
    """Why mode has no shape on the grid w (dimensionless): where it is born, as the command
    line says it."""
    born = np.empty(mode)
    if chain is None:
        status = lib.whirl_continuum_critical_rates(mode, tip_mass, _lib.dptr(born))
    else:
        status = lib.whirl_nlink_critical(chain._c, mode, _lib.dptr(born))
    if status == _lib.GSL_SUCCESS and w.max() < born[-1]:
        return "mode %d exists only above %s" % (mode, _rate_text(float(born[-1]), u))
    return "mode %d has no shape at these rates" % mode


EQUILIBRIA_DTYPE = [("node_count", "i4"), ("branch", "i4"), ("born_at", "f8"),
                    ("tip_r", "f8"), ("max_r", "f8"), ("depth", "f8"),
                    ("top_tension", "f8"), ("eig_growth", "f8"), ("index", "i4")]

EQUILIBRIA_EVIDENCE = ("born", "tip_roots", "tip_floor", "tip_shots", "tip_levels",
                       "tip_unresolved", "check_roots", "check_shots", "check_levels", "matched",
                       "unpolished", "crossings", "missed", "isolated", "unidentified",
                       "path_steps", "cut_short", "balance", "wrong_parity", "refined",
                       "coincident")


def equilibria(omega: float, links: Union[None, int, Chain] = None, tip_mass: float = 0.0,
               stability: bool = True, branches: bool = True, follow_factor: float = 2.0,
               shot_budget: int = 20000000, progress: Any = None,
               length: Optional[float] = None, mass: Optional[float] = None,
               gravity: Optional[float] = None,
               units: Optional[Units] = None) -> Tuple[np.ndarray, Dict[str, Any]]:
    """Every planar relative equilibrium at the rate ``omega`` [sqrt(g/L), or rad/s] (mirror
    images r -> -r counted once), as ``whirl equilibria``: of the N-link chain (links=N or a
    Chain) or of the continuous chain (links=None, Kolodner's shapes). Returns (rows, evidence):
    a structured array in increasing tip radius with fields node_count (the pivot plus the axis
    crossings; the command line's ``nodes``), branch (k: on the branch born at omega_k; 0:
    isolated; -1: not identified, or branches=False), born_at (omega_k, or the lowest fold of an
    isolated curve; NaN if none), tip_r, max_r, depth, top_tension, eig_growth (largest real
    part of the linearisation; NaN for the continuum or stability=False) and index (negative
    directions of the amended potential; -1 where eig_growth is NaN); and a dict of the
    completeness evidence (the counts of the two scans and the continuation, tip_floor in
    lengths, balance the largest force across a link over its tension). branches=False skips
    the continuation (the scans only). progress: the search's stages (see whirl's progress=;
    done counts the stages, with fractions within each: the N-link chain's 6, the scans, the
    polishing of their roots, the continuation and the shapes; the continuum's 2). Ctrl-C
    raises KeyboardInterrupt."""
    u = units_of(length, mass, gravity, units)
    w = as_float(omega, "omega", positive=True, kind="rate", units=u) / u.rate
    m = as_float(tip_mass, "tip_mass", nonnegative=True, kind="mass", units=u) / u.mass
    chain = _chain(links, m, dense=bool(stability))
    p = ffi.new("whirl_equilibria_params *", lib.whirl_equilibria_defaults())
    p.stability = 1 if stability else 0
    p.continuation = 1 if branches else 0
    p.follow_factor = as_float(follow_factor, "follow_factor", positive=True)
    p.shot_budget = as_int(shot_budget, "shot_budget", minimum=1)
    out = ffi.new("whirl_equilibria **")
    c = ffi.NULL if chain is None else chain._c
    with _progress.report(progress, "equilibria", 2 if chain is None else 6, "stages") as rep:
        with _lib.interruptible("equilibria"):
            if _progress.active(progress):
                @ffi.callback("whirl_equilibria_progress_fn")
                def stage(ctx: Any, at: Any) -> None:
                    rep.c_update(at.stage - 1 + at.done / at.total)
                status = lib.whirl_equilibria_find_progress(c, m, w, p, stage, ffi.NULL, out)
            else:
                status = lib.whirl_equilibria_find(c, m, w, p, out)
            rep.reraise()
        check(status, "equilibria", u)
        rep.finish()
    e = ffi.gc(out[0], lib.whirl_equilibria_free)
    rows = np.empty(e.count, dtype=EQUILIBRIA_DTYPE)
    for i in range(e.count):
        q = e.eq[i]
        rows[i] = (q.info.n_nodes + 1, q.branch, q.born_at * u.rate, q.info.tip_r * u.length,
                   q.info.max_r * u.length, q.info.depth * u.length,
                   q.info.top_tension * u.force, q.eig_growth * u.rate, q.index)
    _lib.finite("the equilibria", *(rows[c] for c in ("tip_r", "max_r", "depth",
                                                      "top_tension")))
    evidence = {k: getattr(e, k) for k in EQUILIBRIA_EVIDENCE}
    evidence["tip_floor"] *= u.length
    return rows, evidence
