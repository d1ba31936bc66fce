"""A pytest plugin that records, for each test of python/tests, which functions of libwhirl (the
cffi library object) the test calls, and how each call ended: "NAME" for a call that returned 0
or a non-NULL pointer (or anything else), "NAME!" for one that returned a non-zero int or NULL
(a failure status, an _alloc refused; a count above zero lands here too, which only makes the
record finer). A run of the whirl program is recorded as "program:COMMAND". Constants read from the library are recorded by name. Written as JSON
{"calls": {FILE::TEST: [entries]}, "seconds": {FILE::TEST: processor seconds of the interpreter, its
threads included}} to $WHIRL_LIBCALLS at the session's end; what the package does while it is
imported goes under "import". Used by tests/tools/python_sanitize_list.py.

    cd python && WHIRL_LIBCALLS=calls.json python3 -m pytest -p no:cacheprovider \
        -p pytest_libcalls -m "not slow" tests   (with tests/tools on PYTHONPATH)"""
import json
import os
import resource
import subprocess
import sys
import time

import pytest

_calls = {}
_current = ["import"]
_started = {}
_seconds = {}


def _processor():
    """The processor seconds so far of the interpreter and of its children that have ended."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


_Popen = subprocess.Popen


class _RecordingPopen(_Popen):
    """subprocess.Popen that records a run of the whirl program as "program:COMMAND" (its first
    argument), so that the tests which reach the library through the program count too."""

    def __init__(self, args, *rest, **kwargs):
        argv = [args] if isinstance(args, (str, bytes, os.PathLike)) else list(args)
        if argv and os.path.basename(str(argv[0])) == "whirl":
            command = str(argv[1]) if len(argv) > 1 else ""
            _calls.setdefault(_current[0], set()).add("program:" + command)
        super().__init__(args, *rest, **kwargs)


subprocess.Popen = _RecordingPopen


def _is_null(value):
    try:
        import whirl._lib as core
        return core.ffi.typeof(value).kind == "pointer" and value == core.ffi.NULL
    except (TypeError, AttributeError):
        return False


class _Recorder:
    """Stands for the library object: each attribute read is recorded, then answered by it."""

    def __init__(self, lib):
        object.__setattr__(self, "_lib", lib)

    def __getattr__(self, name):
        value = getattr(object.__getattribute__(self, "_lib"), name)
        if not callable(value):
            _calls.setdefault(_current[0], set()).add(name)
            return value

        def call(*args):
            # a library function passed as a function pointer is passed as itself
            result = value(*(getattr(a, "_whirl_real", a) for a in args))
            failed = (isinstance(result, int) and not isinstance(result, bool) and result != 0) \
                or (type(result).__name__ == "_CDataBase" or "CData" in type(result).__name__) \
                and _is_null(result)
            _calls.setdefault(_current[0], set()).add(name + ("!" if failed else ""))
            return result
        call._whirl_real = value
        return call

    def __dir__(self):
        return dir(object.__getattribute__(self, "_lib"))


def _wrap():
    import whirl._lib as core
    real = core.lib if not isinstance(core.lib, _Recorder) else object.__getattribute__(core.lib, "_lib")
    rec = core.lib if isinstance(core.lib, _Recorder) else _Recorder(real)
    for name, mod in list(sys.modules.items()):
        if (name == "whirl" or name.startswith("whirl.")) and getattr(mod, "lib", None) is real:
            mod.lib = rec


def _name(item):
    """FILE::TEST[PARAMS], as python/tests/conftest.py names a test."""
    return "%s::%s" % (os.path.basename(str(item.fspath)), item.name)


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    _wrap()
    _current[0] = _name(item)
    _started[_current[0]] = _processor()


@pytest.hookimpl(trylast=True)
def pytest_runtest_teardown(item):
    _seconds[_name(item)] = _processor() - _started.pop(_name(item), _processor())
    _current[0] = "import"


def pytest_sessionfinish(session):
    path = os.environ.get("WHIRL_LIBCALLS")
    if path:
        with open(path, "w") as f:
            json.dump({"calls": {k: sorted(v) for k, v in _calls.items()},
                       "seconds": _seconds}, f, indent=0)
