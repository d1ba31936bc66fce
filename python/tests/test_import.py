"""``import whirl`` leaves numpy out (whirl._lazy): every module of the package imports without
it, the first call that needs it imports it, and the answers are those of a process where numpy
was imported first."""
import os
import subprocess
import sys

from whirl import _lazy

PACKAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir)


def _run(code):
    env = dict(os.environ, PYTHONPATH=os.path.abspath(PACKAGE))
    return subprocess.run([sys.executable, "-c", code], cwd="/", env=env, check=True,
                          capture_output=True, text=True).stdout


def test_import_whirl_leaves_numpy_out():
    _run("import whirl, sys; assert 'numpy' not in sys.modules")


def test_every_module_imports_without_numpy():
    out = _run("import pkgutil, sys, importlib, whirl\n"
               "names = sorted(m.name for m in pkgutil.iter_modules(whirl.__path__) "
               "if m.name != '_build')\n"
               "for name in names: importlib.import_module('whirl.' + name)\n"
               "print(len(names), 'numpy' in sys.modules)")
    count, numpy = out.split()
    assert int(count) > 10 and numpy == "False", out


def test_first_call_imports_numpy():
    code = ("import sys, whirl\n"
            "s = whirl.shape('2Hz', 1, links=20, length=0.6)\n"
            "print('numpy' in sys.modules, type(s.r).__module__, repr(list(s.r)))")
    lazy = _run(code).split(None, 2)
    eager = _run("import numpy\n" + code).split(None, 2)
    assert lazy[:2] == ["True", "numpy"], lazy
    assert lazy == eager


def test_lazy_module_keeps_what_it_gave():
    proxy = _lazy.LazyModule("json")
    assert "dumps" not in vars(proxy)
    import json
    assert proxy.dumps is json.dumps and vars(proxy)["dumps"] is json.dumps
    try:
        proxy.no_such_name
    except AttributeError:
        pass
    else:
        raise AssertionError("a missing attribute must raise AttributeError")
    assert "no_such_name" not in vars(proxy)
