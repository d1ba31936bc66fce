"""Steady shapes of the whirling chain: critical rates, shapes and branches (whirl/steady.h).

Units: dimensionless by default (chain length L = 1, mass M = 1, gravity g = 1: rates in
sqrt(g/L), lengths in L, tensions in M g). Give ``length`` [m], ``mass`` [kg] and ``gravity``
[m/s^2] (the command line's --length, --mass, --gravity) to work in SI units instead: rates are
then in rad/s, lengths in m, tensions in N, tip masses in kg."""
import math

import numpy as np

from . import _lib
from ._lib import ffi, lib, check, as_int, as_float, as_array


class Units:
    """The scales of the physical units: chain length [m], chain mass [kg], gravity [m/s^2]
    (all 1: dimensionless). ``rate`` = sqrt(g/L) [1/s], ``force`` = M g [N], ``time`` =
    sqrt(L/g) [s]."""

    def __init__(self, length=1.0, mass=1.0, gravity=1.0):
        self.length = as_float(length, "length", positive=True)
        self.mass = as_float(mass, "mass", positive=True)
        self.gravity = as_float(gravity, "gravity", positive=True)
        self.rate = math.sqrt(self.gravity / self.length)
        self.time = 1.0 / self.rate
        self.force = self.mass * self.gravity

    def __repr__(self):
        return "Units(length=%g, mass=%g, gravity=%g)" % (self.length, self.mass, self.gravity)


class Chain:
    """An N-link chain: N point masses on massless rigid links (whirl_chain).

    Chain(links, tip_mass=0): N equal links and masses, total length 1 and mass 1, g = 1, the
    tip mass [M] added to the last mass (the discrete model of the uniform chain).
    Chain(lengths=[...], masses=[...], gravity=1): any links [L] and masses [M].
    Attributes: ``n``, ``lengths``, ``masses`` (numpy copies), ``gravity``."""

    def __init__(self, links=None, tip_mass=0.0, lengths=None, masses=None, gravity=1.0):
        if links is not None:
            if lengths is not None or masses is not None:
                raise TypeError("give either links or lengths and masses, not both")
            n = as_int(links, "links", minimum=1)
            tip_mass = as_float(tip_mass, "tip_mass", nonnegative=True)
            ptr = lib.whirl_chain_alloc_uniform(n, tip_mass)
        else:
            if lengths is None or masses is None:
                raise TypeError("Chain needs links, or both lengths and masses")
            length = as_array(lengths, "lengths", positive=True)
            mass = as_array(masses, "masses", shape=length.shape, positive=True)
            g = as_float(gravity, "gravity", positive=True)
            ptr = lib.whirl_chain_alloc(length.size, _lib.dptr(length), _lib.dptr(mass), g)
        self._c = _lib.check_ptr(ptr, lib.whirl_chain_free)

    @property
    def n(self):
        return int(self._c.n)

    @property
    def lengths(self):
        return np.frombuffer(ffi.buffer(self._c.length, 8 * self.n), dtype=np.float64).copy()

    @property
    def masses(self):
        return np.frombuffer(ffi.buffer(self._c.mass, 8 * self.n), dtype=np.float64).copy()

    @property
    def gravity(self):
        return float(self._c.gravity)

    def __repr__(self):
        return "Chain(n=%d, length=%g, mass=%g, gravity=%g)" % (
            self.n, lib.whirl_chain_total_length(self._c), lib.whirl_chain_total_mass(self._c),
            self.gravity)


def _chain(links, tip_mass):
    """None for the continuum, else a Chain (an int builds the uniform chain)."""
    if links is None:
        return None
    if isinstance(links, Chain):
        if tip_mass:
            raise ValueError("tip_mass applies to a uniform chain given by its link count; "
                             "put it into the Chain's masses")
        return links
    return Chain(links, tip_mass)


def _mode(mode, chain, continuum_max=None):
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


def critical(modes=3, links=None, tip_mass=0.0, length=1.0, mass=1.0, gravity=1.0):
    """The linear critical rates omega_1..omega_modes at which modes 1..modes bifurcate from the
    hanging chain, as an array [sqrt(g/L), or rad/s with physical units].

    links=None: the continuous chain (j_{0,k}/2 without a tip mass; with a tip mass [M, or kg]
    the roots of a J0/Y0 determinant); links=N or a Chain: the normal-mode frequencies of the
    hanging N-link chain. ``whirl critical`` on the command line."""
    u = Units(length, mass, gravity)
    modes = as_int(modes, "modes", minimum=1)
    m = as_float(tip_mass, "tip_mass", nonnegative=True) / u.mass
    chain = _chain(links, m)
    out = np.empty(modes)
    if chain is None:
        if modes > lib.WHIRL_CONTINUUM_MODE_MAX:
            raise ValueError("modes must be <= %d, got %d" % (lib.WHIRL_CONTINUUM_MODE_MAX,
                                                             modes))
        check(lib.whirl_continuum_critical_rates(modes, m, _lib.dptr(out)))
    else:
        if modes > chain.n:
            raise ValueError("a chain of %d links has modes 1..%d, asked for %d"
                             % (chain.n, chain.n, modes))
        check(lib.whirl_nlink_critical(chain._c, modes, _lib.dptr(out)))
    return out * u.rate


class Shape:
    """A steady shape (``whirl shape``): arrays ``s`` (arclength from the pivot), ``r`` (signed
    distance from the axis, the free end at r > 0), ``z`` (height, pivot 0, z <= 0) and
    ``tension`` [L, L, L, M g; or m, m, m, N], from the pivot to the free end (N-link chain:
    the pivot, then masses 1..N, tension of the link above); the summary ``omega``, ``mode``,
    ``tip_r``, ``max_r``, ``top_tension``, ``depth``, ``nodes`` (arclengths of the axis
    crossings below the pivot: all of them for the N-link chain, the first 64 for the
    continuum; where an N-link shape's radii underflow towards the tip, r is 0 or subnormal and
    the crossings there come from the force balance linearised about the hanging chain), and
    the branch it lies on: ``critical`` (omega_k where mode k is born) and ``links`` (None: the
    continuum)."""

    def __init__(self, info, nodes, s, r, z, tension, u, critical_args, links):
        self.omega = info.omega * u.rate
        self.mode = int(info.mode)
        self.tip_r = info.tip_r * u.length
        self.max_r = info.max_r * u.length
        self.top_tension = info.top_tension * u.force
        self.depth = info.depth * u.length
        self.nodes = nodes * u.length
        self.s, self.r, self.z = s * u.length, r * u.length, z * u.length
        self.tension = tension * u.force
        self._critical_args = critical_args
        self.links = links
        self.units = u

    @property
    def critical(self):
        """omega_k: the rate where this shape's mode is born [sqrt(g/L), or rad/s]."""
        mode, kwargs = self._critical_args
        return critical(mode, **kwargs)[-1]

    def __repr__(self):
        return ("Shape(omega=%.10g, mode=%d, tip_r=%.10g, top_tension=%.10g, depth=%.10g, "
                "%d points)" % (self.omega, self.mode, self.tip_r, self.top_tension, self.depth,
                                self.s.size))


def _solve(chain, omega, mode, m, guess, nodes=None):
    """nodes: (r, z, tension) arrays of N + 1 for the N-link chain's nodes, which come from the
    branch's link angles (at high rates the tip radius alone does not fix them)."""
    info = ffi.new("whirl_shape_info *")
    if chain is None:
        status = lib.whirl_continuum_solve(omega, mode, m, guess, info)
    elif nodes is None:
        status = lib.whirl_nlink_solve(chain._c, omega, mode, guess, info)
    else:
        status = lib.whirl_nlink_solve_nodes(chain._c, omega, mode, info,
                                             *(_lib.dptr(a) for a in nodes))
    return status, info


def shape(omega, mode, links=None, tip_mass=0.0, points=201, tip_r_guess=0.0, length=1.0,
          mass=1.0, gravity=1.0):
    """The steady shape of mode ``mode`` (node count: the pivot plus mode-1 axis crossings) at
    the rotation rate ``omega`` [sqrt(g/L), or rad/s with length/mass/gravity given].

    links=None: the continuous chain sampled at ``points`` equally spaced arclengths (default
    201); links=N (or a Chain): the exact relative equilibrium of the N-link chain, one point per
    node. tip_mass [M, or kg]: a point mass at the free end. tip_r_guess > 0 seeds the root
    search (continuation). Returns a Shape. Raises whirl.Error (status_name "EDOM") if the mode
    does not exist at omega, naming its critical rate."""
    u = Units(length, mass, gravity)
    w = as_float(omega, "omega", positive=True) / u.rate
    m = as_float(tip_mass, "tip_mass", nonnegative=True) / u.mass
    guess = as_float(tip_r_guess, "tip_r_guess", nonnegative=True) / u.length
    chain = _chain(links, m)
    mode = _mode(mode, chain)
    if chain is None:
        n = as_int(points, "points", minimum=2)
    else:
        n = chain.n + 1
    s, r, z, t = (np.empty(n) for _ in range(4))
    status, info = _solve(chain, w, mode, m, guess, None if chain is None else (r, z, t))
    if status != _lib.GSL_SUCCESS:
        msg = _lib.last_error()
        if status == 1:  # GSL_EDOM: name where the mode is born, as the command line does
            try:
                wk = critical(mode, links=chain, tip_mass=0 if chain else tip_mass,
                              length=length, mass=mass, gravity=gravity)[-1]
                if omega < wk:
                    msg = ("mode %d does not exist at omega=%.17g: it exists only above "
                           "omega_%d=%.17g" % (mode, omega, mode, wk))
            except (ValueError, _lib.Error):
                pass
        raise _lib.Error(status, msg)
    if chain is None:
        check(lib.whirl_continuum_sample(w, m, info.tip_r, n, _lib.dptr(s), _lib.dptr(r),
                                         _lib.dptr(z), _lib.dptr(t)))
        # the continuum's first WHIRL_SHAPE_NODES from the pivot (n_nodes counts them all)
        nodes = np.array([info.node_s[j]
                          for j in range(min(info.n_nodes, lib.WHIRL_SHAPE_NODES))])
    else:
        # the nodes of the branch's own link angles (at high rates the tip radius alone does
        # not fix the shape to round-off); every axis crossing, not only the first
        # WHIRL_SHAPE_NODES the summary holds
        s[0] = 0
        np.cumsum(chain.lengths, out=s[1:])
        nodes = np.empty(max(info.n_nodes, 1))
        count = lib.whirl_nlink_node_arclengths(chain._c, info.omega, _lib.dptr(r), nodes.size,
                                                _lib.dptr(nodes), _lib.ffi.NULL)
        nodes = nodes[:min(count, nodes.size)]
    crit = (mode, dict(links=chain, tip_mass=0 if chain else tip_mass, length=length, mass=mass,
                       gravity=gravity))
    return Shape(info, nodes, s, r, z, t, u, crit, None if chain is None else chain.n)


BRANCH_DTYPE = np.dtype([("omega", "f8"), ("tip_r", "f8"), ("max_r", "f8"),
                         ("top_tension", "f8"), ("depth", "f8"), ("n_nodes", "i4")])


def sweep(modes, omega, links=None, tip_mass=0.0, length=1.0, mass=1.0, gravity=1.0):
    """The branches of the given modes over the rates ``omega`` (an array, any order;
    [sqrt(g/L), or rad/s]), each followed by continuation on all OpenMP threads (``whirl
    sweep``). Returns a dict {mode: structured array with fields omega, tip_r, max_r,
    top_tension, depth, n_nodes}, one row per rate where the mode exists, in the order of
    ``omega``. Ctrl-C raises KeyboardInterrupt."""
    u = Units(length, mass, gravity)
    if isinstance(modes, (int, np.integer)) and not isinstance(modes, bool):
        modes = [modes]
    w = as_array(omega, "omega", positive=True) / u.rate
    m = as_float(tip_mass, "tip_mass", nonnegative=True) / u.mass
    chain = _chain(links, m)
    try:
        modes = [_mode(k, chain) for k in modes]
    except TypeError:
        raise TypeError("modes must be an integer or a sequence of integers, got %r"
                        % (modes,)) from None
    n = w.size
    out = {}
    info = ffi.new("whirl_shape_info[]", n)
    exists = np.zeros(n, dtype=np.intc)
    ex = ffi.cast("int *", ffi.from_buffer(exists))
    for k in modes:
        with _lib.interruptible():
            if chain is None:
                status = lib.whirl_continuum_branch(k, m, n, _lib.dptr(w), info, ex)
            else:
                status = lib.whirl_nlink_branch(chain._c, k, n, _lib.dptr(w), info, ex)
        check(status, "mode %d" % k)
        rows = np.flatnonzero(exists)
        a = np.empty(rows.size, dtype=BRANCH_DTYPE)
        for i, j in enumerate(rows):
            f = info[j]
            a[i] = (w[j] * u.rate, f.tip_r * u.length, f.max_r * u.length,
                    f.top_tension * u.force, f.depth * u.length, f.n_nodes)
        out[k] = a
    return out


EQUILIBRIA_DTYPE = np.dtype([("nodes", "i4"), ("branch", "i4"), ("born_at", "f8"),
                             ("tip_r", "f8"), ("max_r", "f8"), ("depth", "f8"),
                             ("top_tension", "f8"), ("eig_growth", "f8"), ("index", "i4")])

EQUILIBRIA_EVIDENCE = ("born", "tip_roots", "tip_floor", "tip_shots", "tip_levels",
                       "tip_unresolved", "check_roots", "check_shots", "check_levels", "matched",
                       "unpolished", "crossings", "missed", "isolated", "unidentified",
                       "path_steps", "cut_short", "balance", "wrong_parity", "refined",
                       "coincident")


def equilibria(omega, links=None, tip_mass=0.0, stability=True, branches=True,
               follow_factor=2.0, shot_budget=20000000, length=1.0, mass=1.0, gravity=1.0):
    """Every planar relative equilibrium at the rate ``omega`` [sqrt(g/L), or rad/s] (mirror
    images r -> -r counted once), as ``whirl equilibria``: of the N-link chain (links=N or a
    Chain) or of the continuous chain (links=None, Kolodner's shapes). Returns (rows, evidence):
    a structured array in increasing tip radius with fields nodes (the pivot plus the axis
    crossings), branch (k: on the branch born at omega_k; 0: isolated; -1: not identified, or
    branches=False), born_at (omega_k, or the lowest fold of an isolated curve; NaN if none),
    tip_r, max_r, depth, top_tension, eig_growth (largest real part of the linearisation;
    NaN for the continuum or stability=False) and index (negative directions of the amended
    potential; -1 where eig_growth is NaN); and a dict of the completeness evidence (the
    counts of the two scans and the continuation, tip_floor in lengths, balance the largest
    force across a link over its tension). branches=False skips the continuation (the scans
    only). Ctrl-C raises KeyboardInterrupt."""
    u = Units(length, mass, gravity)
    w = as_float(omega, "omega", positive=True) / u.rate
    m = as_float(tip_mass, "tip_mass", nonnegative=True) / u.mass
    chain = _chain(links, m)
    p = ffi.new("whirl_equilibria_params *", lib.whirl_equilibria_defaults())
    p.stability = 1 if stability else 0
    p.continuation = 1 if branches else 0
    p.follow_factor = as_float(follow_factor, "follow_factor", positive=True)
    p.shot_budget = as_int(shot_budget, "shot_budget", minimum=1)
    out = ffi.new("whirl_equilibria **")
    with _lib.interruptible():
        status = lib.whirl_equilibria_find(ffi.NULL if chain is None else chain._c, m, w, p, out)
    check(status)
    e = ffi.gc(out[0], lib.whirl_equilibria_free)
    rows = np.empty(e.count, dtype=EQUILIBRIA_DTYPE)
    for i in range(e.count):
        q = e.eq[i]
        rows[i] = (q.info.n_nodes + 1, q.branch, q.born_at * u.rate, q.info.tip_r * u.length,
                   q.info.max_r * u.length, q.info.depth * u.length,
                   q.info.top_tension * u.force, q.eig_growth * u.rate, q.index)
    evidence = {k: getattr(e, k) for k in EQUILIBRIA_EVIDENCE}
    evidence["tip_floor"] *= u.length
    return rows, evidence
