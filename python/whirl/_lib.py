"""Loading libwhirl, its errors as Python exceptions, and Ctrl-C around long calls.

The shared library is looked for, in this order:
  1. the file named by the environment variable WHIRL_LIBRARY;
  2. build/libwhirl.so of the source tree the package sits in (python/whirl -> ../../build),
     so that ``PYTHONPATH=python`` uses the library just built;
  3. libwhirl.so inside the installed package (``make python`` copies it there);
  4. the system's libwhirl (an installed prefix known to the dynamic linker).
"""
import contextlib
import ctypes.util
import math
import numbers
import os
import threading

import numpy as np
from cffi import FFI

from ._cdef import CDEF

ffi = FFI()
ffi.cdef(CDEF)

_HERE = os.path.dirname(os.path.abspath(__file__))


def _candidates():
    env = os.environ.get("WHIRL_LIBRARY")
    if env:
        return [env]
    found = [os.path.join(_HERE, os.pardir, os.pardir, "build", "libwhirl.so"),
             os.path.join(_HERE, "libwhirl.so")]
    system = ctypes.util.find_library("whirl")
    found += [system] if system else []
    return found + ["libwhirl.so"]


def _load():
    tried = []
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            tried.append(path + " (missing)")
            continue
        try:
            return ffi.dlopen(path), path
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
            if os.environ.get("WHIRL_LIBRARY"):
                break
    raise ImportError("whirl: cannot load libwhirl: tried " + "; ".join(tried)
                      + ". Build it with `make` (build/libwhirl.so) or set WHIRL_LIBRARY.")


lib, LIBRARY_PATH = _load()
# GSL's default error handler aborts the process: the library reports every failure by status.
lib.gsl_set_error_handler_off()

GSL_SUCCESS = 0
_STATUS_NAMES = {1: "EDOM", 2: "ERANGE", 4: "EINVAL", 5: "EFAILED", 8: "ENOMEM", 9: "EBADFUNC",
                 11: "EMAXITER", 14: "ETOL", lib.WHIRL_EINTERRUPTED: "EINTERRUPTED"}


class Error(Exception):
    """A failure reported by libwhirl: ``message`` is the library's one-line message
    (whirl_last_error()), ``status`` its GSL status code (``status_name``: "EDOM" for a mode
    that does not exist at the rate, "EINVAL" for bad input, ...; "EFAILED" when an _alloc
    function of the library returned NULL: bad parameters, named in the message, or no memory)."""

    def __init__(self, status, message):
        self.status = status
        self.status_name = _STATUS_NAMES.get(status, str(status))
        self.message = message
        super().__init__(message)


def last_error():
    """The library's message of the last failure in this thread."""
    return ffi.string(lib.whirl_last_error()).decode("utf-8", "replace")


def check(status, context=None):
    """Raises KeyboardInterrupt for WHIRL_EINTERRUPTED and whirl.Error for any other failure."""
    if status == GSL_SUCCESS:
        return
    if status == lib.WHIRL_EINTERRUPTED:
        lib.whirl_stop_clear()
        raise KeyboardInterrupt(last_error())
    msg = last_error()
    if context and not msg.startswith(context + ":"):  # the library may name it already
        msg = "%s: %s" % (context, msg)
    raise Error(status, msg)


def check_ptr(ptr, free=None):
    """A pointer from an _alloc function, or whirl.Error with the library's message."""
    if ptr == ffi.NULL:
        raise Error(lib.whirl_last_status() or 5, last_error() or "allocation failed")
    return ffi.gc(ptr, free) if free is not None else ptr


@contextlib.contextmanager
def interruptible():
    """Around a long library call: Ctrl-C (SIGINT) and SIGTERM raise the library's stop request
    (its own handlers, installed for the duration), which its long loops poll; afterwards
    Python's handlers are back and a request that came in raises KeyboardInterrupt. Outside the
    main thread (where Python handles no signals) it does nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    lib.whirl_stop_clear()
    if lib.whirl_stop_catch_signals() != GSL_SUCCESS:
        raise Error(5, "cannot install the library's signal handlers")
    try:
        yield
    finally:
        lib.whirl_stop_restore_signals()
    if lib.whirl_stop_requested():
        lib.whirl_stop_clear()
        raise KeyboardInterrupt("interrupted")


def stop_requested():
    """True once the library's stop request is raised (by Ctrl-C inside interruptible())."""
    return bool(lib.whirl_stop_requested())


# ---- argument checks: Python exceptions before anything reaches the library ----

def as_int(value, name, minimum=None, maximum=None):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError("%s must be an integer, got %r" % (name, value))
    value = int(value)
    if minimum is not None and value < minimum:
        raise ValueError("%s must be >= %d, got %d" % (name, minimum, value))
    if maximum is not None and value > maximum:
        raise ValueError("%s must be <= %d, got %d" % (name, maximum, value))
    return value


def as_float(value, name, positive=False, nonnegative=False):
    if type(value) is not float:  # the common case skips the abstract-class checks
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError("%s must be a real number, got %r" % (name, value))
        value = float(value)
    if not math.isfinite(value):
        raise ValueError("%s must be finite, got %r" % (name, value))
    if positive and not value > 0:
        raise ValueError("%s must be > 0, got %r" % (name, value))
    if nonnegative and not value >= 0:
        raise ValueError("%s must be >= 0, got %r" % (name, value))
    return value


def as_array(values, name, shape=None, positive=False, allow_empty=False):
    """A C-contiguous float64 copy of values (a 1-D sequence, or of the given shape), finite."""
    try:
        a = np.array(values, dtype=np.float64, order="C")
    except (TypeError, ValueError) as e:
        raise TypeError("%s must be an array of numbers: %s" % (name, e)) from None
    if shape is None:
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


def dptr(a):
    """The double * of a C-contiguous float64 array (which must outlive the call)."""
    return ffi.from_buffer("double[]", a)


def methods():
    """The integrator names the library knows (whirl_integrator_methods)."""
    out, p = [], lib.whirl_integrator_methods()
    i = 0
    while p[i] != ffi.NULL:
        out.append(ffi.string(p[i]).decode())
        i += 1
    return out
