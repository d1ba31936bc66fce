"""Loading libwhirl, its errors as Python exceptions, Ctrl-C around long calls, and the checks
every argument passes before it reaches the library.

The shared library is looked for, in this order:
  1. the file named by the environment variable WHIRL_LIBRARY;
  2. libwhirl.so inside the package (a wheel from ``make wheel``, or ``pip install ./python``,
     carries its own, with the libraries it links in whirl/.libs); when the package has one,
     it is the one: if it does not load, the import fails rather than take another version;
  3. build/libwhirl.so of the source tree the package sits in (python/whirl -> ../../build),
     so that ``PYTHONPATH=python`` uses the library just built;
  4. the system's libwhirl (an installed prefix known to the dynamic linker).
``whirl.LIBRARY_PATH`` names the copy in use.
"""
from __future__ import annotations

import contextlib
import ctypes
import dataclasses
import functools
import importlib.util
import math
import numbers
import os
import signal
import threading
from typing import (Any, Callable, ContextManager, Dict, Iterator, List, Optional, Sequence, Tuple,
                    TypeVar)

from ._lazy import numpy as np
from ._cdef import CDEF

_HERE = os.path.dirname(os.path.abspath(__file__))
_PACKAGED = os.path.join(_HERE, "libwhirl.so")
_TREE = os.path.normpath(os.path.join(_HERE, os.pardir, os.pardir))
_IN_TREE = (os.path.isfile(os.path.join(_TREE, "Makefile"))
            and os.path.isdir(os.path.join(_TREE, "src")))


def _generated(path: Optional[str] = None) -> Any:
    """The FFI of a module generated from the declarations (whirl/_build.py): the package's
    whirl._ffi, or the file ``path``; None when there is none, it cannot be read (another cffi
    made it), or it was made from other declarations than _cdef.py's."""
    name = __name__.rsplit(".", 1)[0] + "._ffi"
    try:
        if path is None:
            module = importlib.import_module(name)
        else:
            spec = importlib.util.spec_from_file_location(name, path)
            if spec is None or spec.loader is None:
                return None
            module = importlib.util.module_from_spec(spec)
            spec.loader.exec_module(module)
    except Exception:  # whatever is wrong with a generated module, the declarations parse
        return None
    return module.ffi if getattr(module, "CDEF", None) == CDEF else None


def _declarations() -> Any:
    """cffi's FFI for the declarations of _cdef.py: the module generated from them when the
    package was built (whirl/_ffi.py: nothing to parse); in a source tree, which has none, the
    one kept in its build/python/ (written at the first import, again whenever _cdef.py
    changes); else parsed here (pycparser, a tenth of a second)."""
    found = _generated()
    if found is not None:
        return found
    cache = (os.path.join(_TREE, "build", "python", "whirl_ffi.py")
             if _IN_TREE and os.path.isdir(os.path.join(_TREE, "build")) else None)
    if cache is not None and os.path.exists(cache):
        found = _generated(cache)
        if found is not None:
            return found
    from cffi import FFI
    parsed = FFI()
    parsed.cdef(CDEF)
    if cache is not None:
        try:  # written whole, then renamed: another process reads the old file or the new
            from ._build import write_module
            os.makedirs(os.path.dirname(cache), exist_ok=True)
            part = "%s.%d.part" % (cache, os.getpid())
            write_module(CDEF, part)
            os.replace(part, cache)
        except (OSError, ImportError):
            pass  # a tree one cannot write to: parsed at every import
    return parsed


ffi = _declarations()


def _candidates() -> Iterator[str]:
    env = os.environ.get("WHIRL_LIBRARY")
    if env:
        yield env
        return
    yield _PACKAGED
    yield os.path.join(_TREE, "build", "libwhirl.so")
    import ctypes.util  # the system's copy: a few hundredths of a second, asked only here
    system = ctypes.util.find_library("whirl")
    if system:
        yield system
    yield "libwhirl.so"


def _advice() -> str:
    """What to do when no copy loads, for where this package sits."""
    if os.environ.get("WHIRL_LIBRARY"):
        return "WHIRL_LIBRARY must name a libwhirl.so that loads (or unset it)."
    if os.path.exists(_PACKAGED):
        libs = os.path.join(_HERE, ".libs")
        if os.path.isdir(libs):
            return ("The package's copy does not load although it carries the libraries it "
                    "links (%s): reinstall the package (pip install --force-reinstall --no-deps "
                    "whirl-*.whl), or set WHIRL_LIBRARY to a libwhirl.so that loads." % libs)
        return ("The package's copy uses the system's GSL, NLopt, LAPACKE, inih and OpenMP (a "
                "package built with WHIRL_VENDOR=0): install them, or install the wheel, which "
                "carries them.")
    if _IN_TREE:
        return ("Build it with `make build/libwhirl.so` in %s, or set WHIRL_LIBRARY." % _TREE)
    return ("This package has no libwhirl of its own: install the wheel (whirl-*.whl), which "
            "carries it, or set WHIRL_LIBRARY to a libwhirl.so.")


def _load() -> Tuple[Any, str]:
    tried: List[str] = []
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            tried.append(path + " (missing)")
            continue
        try:
            return ffi.dlopen(path), path
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
            if path == _PACKAGED:  # the package's own, when it has one: no other version
                break
    raise ImportError("whirl: cannot load libwhirl: tried " + "; ".join(tried) + ". "
                      + _advice())


lib, LIBRARY_PATH = _load()
# The library stays loaded to the process's end: after a stop request a dense LAPACK solve it
# could not poll runs on in a thread of its own (src/core/worker.c), and the interpreter's
# finalisation would otherwise unload the library under it (cffi's handle is closed with the
# module), a crash at exit in about half the Ctrl-Cs of a stability map. ctypes never unloads.
_PIN = ctypes.CDLL(LIBRARY_PATH, mode=os.RTLD_NOW | getattr(os, "RTLD_NODELETE", 0))
LIBRARY_VERSION: str = ffi.string(lib.whirl_version()).decode()
# GSL's default error handler aborts the process: the library reports every failure by status.
lib.gsl_set_error_handler_off()

GSL_SUCCESS = 0
GSL_EFAILED = 5
GSL_ENOMEM = 8
_STATUS_NAMES = {1: "EDOM", 2: "ERANGE", 4: "EINVAL", 5: "EFAILED", 8: "ENOMEM", 9: "EBADFUNC",
                 11: "EMAXITER", 14: "ETOL", lib.WHIRL_EINTERRUPTED: "EINTERRUPTED"}


class Error(Exception):
    """A failure reported by libwhirl: ``message`` is the library's one-line message
    (whirl_last_error()), ``status`` its GSL status code (``status_name``: "EDOM" for a mode
    that does not exist at the rate, "EINVAL" for bad input, ...; an _alloc function of the
    library that returned NULL leaves its status too, whirl_last_status()).
    Bad values (EINVAL, EDOM) raise the subclass InvalidInput, which is also a ValueError."""

    def __init__(self, status: int, message: str) -> None:
        self.status = status
        self.status_name = _STATUS_NAMES.get(status, str(status))
        self.message = message
        super().__init__(message)

    def __reduce__(self) -> Tuple[Any, Tuple[int, str]]:
        return (type(self), (self.status, self.message))


class InvalidInput(Error, ValueError):
    """A value the library refuses (status EINVAL, or EDOM: a mode that does not exist at the
    rate): both a whirl.Error and a ValueError."""


_VALUE_STATUS = (1, 4)  # GSL_EDOM, GSL_EINVAL


def error(status: int, message: str) -> Error:
    """The exception for a library status: InvalidInput for bad values, else Error."""
    return (InvalidInput if status in _VALUE_STATUS else Error)(status, message)


def last_error() -> str:
    """The library's message of the last failure in this thread."""
    return ffi.string(lib.whirl_last_error()).decode("utf-8", "replace")


def interrupted(what: str) -> KeyboardInterrupt:
    return KeyboardInterrupt("whirl: %s interrupted" % what)


def last_error_in(units: Any) -> str:
    """The library's message of the last failure with its quantities in the user's units (the
    library types them: whirl_last_error_in_units; SI "omega=4.86 rad/s"; dimensionless: as it
    is)."""
    if units is None or not units.physical:
        return last_error()
    buf = ffi.new("char[]", 1024)
    text = lib.whirl_last_error_in_units(buf, len(buf), 1, units.length, units.mass,
                                         units.gravity, 0)
    return ffi.string(text).decode("utf-8", "replace")


# the unit of each kind of quantity in SI (a Units property of the same name scales it)
_SI_UNITS = {"rate": "rad/s", "length": "m", "mass": "kg", "time": "s", "force": "N",
             "drag": "kg/(m s)", "drag2": "kg/m^2", "damping": "kg m^2/s"}


def in_units(value: float, kind: str, units: Any) -> str:
    """A dimensionless quantity of the kind ("rate", "length", "time", ...) as text in the
    caller's units: "0.002 s" (SI, the shortest form that reads back, to 15 digits) or the
    number alone (dimensionless)."""
    if units is None or not units.physical:
        return repr(float(value))
    v = float("%.15g" % (value * getattr(units, kind)))
    return "%r %s" % (v, _SI_UNITS[kind])


def check(status: int, context: Optional[str] = None, units: Any = None) -> None:
    """Raises KeyboardInterrupt for WHIRL_EINTERRUPTED, InvalidInput for bad values and
    whirl.Error for any other failure, the library's message in the user's units."""
    if status == GSL_SUCCESS:
        return
    if status == lib.WHIRL_EINTERRUPTED:
        lib.whirl_stop_clear()
        if context is None and _active and threading.current_thread() is threading.main_thread():
            context = _active[0]  # the call the user made, not the library's inner step
        if context is None:
            raise KeyboardInterrupt("whirl: %s" % (last_error() or "interrupted"))
        raise interrupted(context)
    msg = last_error_in(units)
    if context and not msg.startswith(context + ":"):  # the library may name it already
        msg = "%s: %s" % (context, msg)
    raise error(status, msg)


def check_ptr(ptr: Any, free: Any = None) -> Any:
    """A pointer from an _alloc function, or whirl.Error with the library's message."""
    if ptr == ffi.NULL:
        msg = last_error() or "allocation failed"
        status = lib.whirl_last_status()  # NULL leaves the status beside the message
        raise MemoryError(msg) if status == GSL_ENOMEM else error(status or GSL_EFAILED, msg)
    return ffi.gc(ptr, free) if free is not None else ptr


# The signals besides SIGINT that whirl_stop_catch_signals may take over: each keeps the meaning
# Python gave it (SIGTERM: terminate), so that a scheduler's kill is never taken for Ctrl-C.
_KEEP = tuple(getattr(signal, name) for name in ("SIGTERM", "SIGHUP", "SIGQUIT")
              if hasattr(signal, name))


_nested = [0]  # interruptible blocks open in the main thread (only the outermost acts)
_active: List[str] = []  # the outermost one's name, while it is open


@contextlib.contextmanager
def interruptible(what: str) -> Iterator[None]:
    """Around a long library call named ``what``: Ctrl-C (SIGINT) raises the library's stop
    request (its handler, installed for the duration), which its long loops poll; afterwards
    Python's handler is back and a request that came in raises KeyboardInterrupt("whirl: WHAT
    interrupted") (a handler of the user's own is called instead). SIGTERM and the other
    terminating signals keep Python's disposition throughout. SIGINT ignored (a background
    job): the call is not interruptible, as Python would have it. Outside the main thread
    (where Python handles no signals) it does nothing. Blocks nest: inside another one it does
    nothing, so that a function around several library calls keeps the library's handler
    between them too (a Ctrl-C in its own Python code is the library's stop request, seen by
    its next call or at the end, and never Python's bare KeyboardInterrupt())."""
    if threading.current_thread() is not threading.main_thread() or _nested[0] > 0:
        yield
        return
    handler = signal.getsignal(signal.SIGINT)
    if handler in (signal.SIG_IGN, None):
        yield
        return
    keep = [(sig, signal.getsignal(sig)) for sig in _KEEP]
    lib.whirl_stop_clear()
    if lib.whirl_stop_catch_signals() != GSL_SUCCESS:
        raise Error(5, "cannot install the library's signal handlers")
    _nested[0] += 1
    _active.append(what)
    try:
        for sig, old in keep:
            if old is not None:
                signal.signal(sig, old)
        yield
    finally:
        _nested[0] -= 1
        _active.pop()
        lib.whirl_stop_restore_signals()
    if lib.whirl_stop_requested():
        lib.whirl_stop_clear()
        if handler is signal.default_int_handler or not callable(handler):
            raise interrupted(what)
        handler(signal.SIGINT, None)


def interruptible_if(long: bool, what: str) -> ContextManager[None]:
    """interruptible(what) around a call that may be long; nothing around one that cannot be
    (installing and restoring the handlers costs a few system calls, tens of microseconds)."""
    return interruptible(what) if long else contextlib.nullcontext()


def stop_requested() -> bool:
    """True once the library's stop request is raised (by Ctrl-C inside interruptible())."""
    return bool(lib.whirl_stop_requested())


def _physical_memory() -> int:
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return 1 << 34


MEMORY = _physical_memory()


def _bytes(n: float) -> str:
    for unit in ("B", "KB", "MB", "GB", "TB", "PB"):
        if n < 1000 or unit == "PB":
            return "%.3g %s" % (n, unit)
        n /= 1000
    return "%.3g PB" % n


def bounded(value: int, name: str, bytes_each: float, power: int = 1,
            hard: Optional[int] = None) -> int:
    """A count that drives memory or work, refused (ValueError naming the limit and the memory
    the count would need) when bytes_each * value**power exceeds half the machine's memory, or
    value exceeds ``hard`` (a limit the command line has too)."""
    limit = int((MEMORY / 2 / bytes_each) ** (1.0 / power))
    if hard is not None:
        limit = min(limit, hard)
    if value > limit:
        need = bytes_each * float(value) ** power
        raise ValueError("%s must be <= %d, got %d (it would need about %s of memory; this "
                         "machine has %s)" % (name, limit, value, _bytes(need), _bytes(MEMORY)))
    return value


# ---- argument checks: Python exceptions before anything reaches the library ----

def as_int(value: Any, name: str, minimum: Optional[int] = None,
           maximum: Optional[int] = None) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError("%s must be an integer, got %r" % (name, value))
    value = int(value)
    if minimum is not None and value < minimum:
        raise ValueError("%s must be >= %d, got %d" % (name, minimum, value))
    if maximum is not None and value > maximum:
        raise ValueError("%s must be <= %d, got %d" % (name, maximum, value))
    return value


# the kinds of quantity a text with a unit may give (whirl_quantity), by the name of the scale
# that divides them (Units.rate, .length, .mass, .time)
_QUANTITY = {"rate": 1, "length": 2, "mass": 3, "time": 4}


def quantity(text: str, name: str, kind: str, units: Any = None) -> float:
    """A number given as text, as the command line reads its options (whirl_parse_quantity):
    "4Hz", "60 cm", "50g", "2ms" (the kind's suffixes, SI after it) or a plain number. A
    suffix needs SI units (``units`` physical), as on the command line."""
    q = _QUANTITY[kind]
    v = ffi.new("double *")
    suffixed = ffi.new("int *")
    if lib.whirl_parse_quantity(text.encode("utf-8", "replace"), q, v, suffixed) != 0:
        raise ValueError("%s must be a number, optionally with a unit (%s), got %r"
                         % (name, ffi.string(lib.whirl_quantity_suffixes(q)).decode(), text))
    if suffixed[0] and units is not None and not units.physical:
        raise ValueError("%s=%r needs the chain's length: give length= (SI units), or %s as a "
                         "number in the chain's units" % (name, text, name))
    return float(v[0])


# pint quantities (where pint is installed): the SI unit each kind is converted to
_PINT_SI = {"rate": "rad/s", "length": "m", "mass": "kg", "time": "s", "drag": "kg/(m*s)",
            "drag2": "kg/m**2", "damping": "kg*m**2/s", "gravity": "m/s**2"}


def is_pint(value: Any) -> bool:
    """value is a pint Quantity (without importing pint)."""
    return type(value).__module__.split(".", 1)[0] == "pint" and hasattr(value, "magnitude")


def pint_value(value: Any, name: str, kind: Optional[str], units: Any) -> Any:
    """A pint Quantity's magnitude in the SI unit of the kind (a float or an array): rates in
    rad/s, a frequency in hertz read as turns per second, as the command line reads "4Hz" (pint
    itself would make 4 Hz 4 rad/s: it counts the radian as 1), a rate in rpm, turn/s or rad/s
    converted by pint; a dimensionless quantity is its number. Like a text with a unit, a unit
    needs SI units (``units`` physical)."""
    if value.dimensionless:
        return value.to("").magnitude
    if kind not in _PINT_SI:
        raise TypeError("%s takes a number without a unit, got %s" % (name, value))
    if units is not None and not units.physical:
        raise ValueError("%s=%s needs the chain's length: give length= (SI units), or %s as a "
                         "number in the chain's units" % (name, value, name))
    try:
        if kind == "rate" and any(u.endswith("hertz") for u in value._units):
            return 2 * math.pi * value.to("Hz").magnitude
        return value.to(_PINT_SI[kind]).magnitude
    except Exception as e:  # pint's DimensionalityError, without importing pint
        raise ValueError("%s must be a %s (%s), got %s: %s" % (name, kind, _PINT_SI[kind], value,
                                                             e)) from None


def as_float(value: Any, name: str, positive: bool = False, nonnegative: bool = False,
             kind: Optional[str] = None, units: Any = None) -> float:
    """value as a finite float: a real number, a 0-d array, a pint Quantity (in SI, see
    pint_value), or (where ``kind`` names the quantity: "rate", "length", "mass", "time") a text
    with a unit, as the command line takes it (quantity())."""
    if type(value) is not float:  # the common case skips the abstract-class checks
        if is_pint(value):
            value = pint_value(value, name, kind, units)
            if isinstance(value, np.ndarray) and value.ndim == 0:
                value = float(value)
        if isinstance(value, str) and kind in _QUANTITY:
            value = quantity(value, name, kind, units)
        elif isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "fiu":
            value = float(value)
        elif isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError("%s must be a real number%s, got %r"
                            % (name, " (or a text with a unit)" if kind in _QUANTITY
                               else " (or a pint quantity)" if kind in _PINT_SI else "", value))
        value = float(value)
    if not math.isfinite(value):
        raise ValueError("%s must be finite, got %r" % (name, value))
    if positive and not value > 0:
        raise ValueError("%s must be > 0, got %r" % (name, value))
    if nonnegative and not value >= 0:
        raise ValueError("%s must be >= 0, got %r" % (name, value))
    return value


def as_array(values: Any, name: str, shape: Optional[Sequence[int]] = None,
             positive: bool = False, allow_empty: bool = False, kind: Optional[str] = None,
             units: Any = None) -> np.ndarray:
    """A C-contiguous float64 copy of values (a 1-D sequence, or of the given shape), finite.
    Where ``kind`` names the quantity (as as_float): a pint array, or a sequence whose items
    are texts with a unit ("4Hz") or pint quantities, in SI."""
    if is_pint(values):
        values = pint_value(values, name, kind, units)
    elif kind is not None and isinstance(values, (list, tuple)):
        # item by item (numpy would strip a pint item's unit); a nested list goes to numpy
        if any(isinstance(v, str) or is_pint(v) for v in values):
            values = [as_float(v, "%s[%d]" % (name, i), kind=kind, units=units)
                      for i, v in enumerate(values)]
    elif kind is not None and isinstance(values, np.ndarray) and values.dtype.kind in "OU":
        values = np.array([as_float(v, "%s[%d]" % (name, i), kind=kind, units=units)
                           for i, v in enumerate(values.flat)]).reshape(values.shape)
    try:
        a = np.array(values, dtype=np.float64, order="C")
    except (TypeError, ValueError) as e:
        raise TypeError("%s must be an array of numbers: %s" % (name, e)) from None
    if shape is None:
        if a.ndim == 0:  # one number (a 0-d array): an array of one
            a = a.reshape(1)
        if a.ndim != 1:
            raise ValueError("%s must be one-dimensional, got shape %s" % (name, a.shape))
    elif a.shape != tuple(shape):
        raise ValueError("%s must have shape %s, got %s" % (name, tuple(shape), a.shape))
    if a.size == 0 and not allow_empty:
        raise ValueError("%s must not be empty" % name)
    if not np.all(np.isfinite(a)):
        raise ValueError("%s must be finite (it holds NaN or inf)" % name)
    if positive and not np.all(a > 0):
        raise ValueError("%s must be > 0" % name)
    return a


def dptr(a: np.ndarray) -> Any:
    """The double * of a C-contiguous float64 array (which must outlive the call)."""
    return ffi.from_buffer("double[]", a)


def methods() -> List[str]:
    """The integrator names the library knows (whirl_integrator_methods)."""
    out: List[str] = []
    p = lib.whirl_integrator_methods()
    i = 0
    while p[i] != ffi.NULL:
        out.append(ffi.string(p[i]).decode())
        i += 1
    return out


def finite(name: str, *values: Any) -> None:
    """Refuses a result that overflowed in the user's units (the command line refuses such
    units before the work; a value of the library times a unit scale can still leave the
    doubles)."""
    for v in values:
        if not (math.isfinite(v) if isinstance(v, float) else np.isfinite(v).all()):
            raise ValueError("%s is not finite in these units (inf or NaN): choose units "
                             "nearer to the chain's own scales" % name)


# ---- threads ----

def set_max_threads(threads: int) -> None:
    """Caps the OpenMP threads of every parallel loop of the library (sweeps, stability maps, a
    long chain's right-hand side) at ``threads``; 0 restores OpenMP's own count
    (OMP_NUM_THREADS, or the cores). Results do not depend on it. In a child of fork() (the
    default start method of multiprocessing on Linux) the library runs on one thread, since
    the OpenMP threads of the parent do not survive a fork; asking for more there raises
    ValueError (whirl.InvalidInput)."""
    check(lib.whirl_set_max_threads(as_int(threads, "threads", minimum=0,
                                           maximum=lib.WHIRL_THREADS_MAX)))


def max_threads() -> int:
    """The threads a parallel loop of the library takes now (1 in a child of fork())."""
    return int(lib.whirl_max_threads())


_F = TypeVar("_F", bound=Callable[..., Any])


class InUse(RuntimeError):
    """An object with state (a Simulation) called from a second thread while a first is using
    it: refused, since both would move the one state."""


class Exclusive:
    """The guard of an object with state: one thread at a time. A call from another thread
    while one is inside raises InUse at once (nothing is changed); calls from the same thread
    nest. Cheap: one non-blocking lock acquisition per call."""

    __slots__ = ("_lock", "_owner", "_user")

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._owner: Optional[int] = None
        self._user = ""

    @contextlib.contextmanager
    def __call__(self, what: str) -> Iterator[None]:
        me = threading.get_ident()
        if self._owner == me:
            yield
            return
        if not self._lock.acquire(blocking=False):
            raise InUse("%s: this object is in use by another thread (%s); an object with "
                        "state serves one thread at a time: give each thread its own (a copy: "
                        "copy.copy) or lock around the calls" % (what, self._user))
        self._owner, self._user = me, what
        try:
            yield
        finally:
            self._owner, self._user = None, ""
            self._lock.release()


def exclusive(method: _F) -> _F:
    """A method of an object with state (``self._guard``, an Exclusive): one thread at a
    time."""
    what = method.__qualname__

    @functools.wraps(method)
    def guarded(self: Any, *args: Any, **kwargs: Any) -> Any:
        with self._guard(what):
            return method(self, *args, **kwargs)
    return guarded  # type: ignore[return-value]


# ---- results ----

def same(a: Any, b: Any) -> bool:
    """a and b hold the same values: arrays element by element (shape and dtype too; NaN equal
    to NaN, so that a result equals its copy), dicts, lists, tuples and dataclasses field by
    field, anything else by ==."""
    if type(a) is not type(b):
        return False
    if isinstance(a, np.ndarray):
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        if a.dtype.names:
            return all(same(a[name], b[name]) for name in a.dtype.names)
        return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"))
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if dataclasses.is_dataclass(a):
        return all(same(getattr(a, f.name), getattr(b, f.name))
                   for f in dataclasses.fields(a))
    if isinstance(a, float) and a != a:
        return b != b
    return bool(a == b)


class Result:
    """The equality of whirl's results (dataclasses holding arrays): two results are equal when
    they are of one type and every field holds the same values (same()), so that ``a == b``,
    ``x in results`` and ``assert a == b`` work (the dataclasses' own == would compare arrays
    into an array, whose truth is ambiguous). Results are mutable: not hashable.
    As data: ``as_dict()`` its table, {"omega [rad/s]": array, ...} in the command line's column
    names with their units (whirl.columns), ``to_pandas()`` the same as a DataFrame whose attrs
    hold the summary (the numbers of a whole table, as a file's key=value comment) and units."""

    def _columns(self) -> Tuple[Dict[str, Any], Dict[str, Any]]:
        """(columns, summary) by the command line's names; by default from the fields."""
        from .columns import split
        fields = ({f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
                  if dataclasses.is_dataclass(self) else dict(vars(self)))
        return split(fields)

    def as_dict(self) -> Dict[str, np.ndarray]:
        """The result's table as {column [unit]: 1-D array}, in the command line's column
        names (a result of one row, as StabilityResult: arrays of one)."""
        from .columns import labelled
        return labelled(self._columns()[0], getattr(self, "units", None))

    def to_pandas(self) -> Any:
        """as_dict() as a pandas DataFrame; its attrs hold the summary ({name [unit]: value})
        and "units" (repr of the units). ImportError without pandas."""
        from .columns import data_frame, label
        units = getattr(self, "units", None)
        summary = {label(k, units): v for k, v in self._columns()[1].items()}
        summary["units"] = repr(units)
        return data_frame(self.as_dict(), summary)

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        if dataclasses.is_dataclass(self):
            return all(same(getattr(self, f.name), getattr(other, f.name))
                       for f in dataclasses.fields(self))
        return same(vars(self), vars(other))

    __hash__ = None  # type: ignore[assignment]
