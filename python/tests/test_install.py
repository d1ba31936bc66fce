"""The package installs like any other. From the source, pip install --no-build-isolation in a
fresh venv with the system's packages (numpy, cffi); the wheel, in a venv without them that sees
numpy and cffi alone, where it stands alone: every library libwhirl links but the C library's own
comes from the wheel's folder (ldd, the loader's log, and a mount namespace where the system's
copies are unreadable). The installed package loads its own copy of libwhirl (whirl.LIBRARY_PATH
inside the venv), its version is the library's, and its answers are the checkout's. A copy of
python/ (WHIRL_SOURCE names the repository) keeps the source tree free of build files. A whirl
installed elsewhere (the system's Python after `make python`, the user's site) changes nothing:
pip installs into the venv even when it sees the same version outside (--ignore-installed from
the source; the wheel with --force-reinstall, as the guide says), the venv's own site comes first
on the path, and the user's site is left out (PYTHONNOUSERSITE)."""
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import whirl
from whirl import _build, _cdef

HERE = os.path.dirname(os.path.abspath(__file__))
PROBE = ("import whirl, json; print(json.dumps([whirl.__version__, whirl.LIBRARY_PATH, "
         "whirl.__file__, list(whirl.critical(3, length=0.6))]))")


def _copy_source(dst, repo):
    shutil.copytree(os.path.join(repo, "python"), dst,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "tests",
                                                  "examples", "bench", "libwhirl.so", "_ffi.py",
                                                  ".libs"))
    build = os.environ.get("WHIRL_BUILD", os.path.join(repo, "build"))
    # the library under test as it is (make would rebuild the sanitizer build with plain flags)
    env = dict(os.environ, WHIRL_SOURCE=repo,
               WHIRL_PREBUILT=os.path.join(build, "libwhirl.so"))
    env.pop("WHIRL_LIBRARY", None)
    env.pop("PYTHONPATH", None)
    env["PYTHONNOUSERSITE"] = "1"
    return dst, env


@pytest.fixture
def source(tmp_path, repo):
    return _copy_source(tmp_path / "python", repo)


def _venv(tmp_path, name):
    path = tmp_path / name
    # without pip of its own (3 s of processor time each): the system's pip, seen through the
    # system's site, installs into the venv it runs in
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", "--without-pip",
                    str(path)], check=True)
    return path / "bin" / "python"


def _probe(python, env, venv):
    import json
    out = subprocess.run([str(python), "-c", PROBE], cwd="/", env=env, check=True,
                         capture_output=True, text=True).stdout
    version, library, module, rates = json.loads(out)
    assert version == whirl.__version__ == whirl.LIBRARY_VERSION
    assert library.startswith(str(venv)) and library.endswith("/whirl/libwhirl.so"), library
    assert module.startswith(str(venv)), module
    np.testing.assert_array_equal(rates, whirl.critical(3, length=0.6))


def test_pip_install_source(tmp_path, source):
    src, env = source
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--ignore-installed", "--no-build-isolation",
                    "--no-deps", "--no-index", str(src)], check=True, env=env)
    _probe(python, env, tmp_path / "venv")


def test_editable_install_uses_the_tree(tmp_path, repo):
    # pip install -e ./python in a venv with the system's packages: whirl is the tree's package
    # and loads the tree's build/libwhirl.so, although the environment sees an installed whirl
    # of the same version (here in the user's site, which comes after the venv's own, before the
    # system's)
    tree = tmp_path / "tree"
    (tree / "src").mkdir(parents=True)
    (tree / "build").mkdir()
    for name in ("Makefile", "LICENSE"):
        shutil.copyfile(os.path.join(repo, name), tree / name)
    shutil.copytree(os.path.join(repo, "include"), tree / "include")
    build = os.environ.get("WHIRL_BUILD", os.path.join(repo, "build"))
    shutil.copyfile(os.path.join(build, "libwhirl.so"), tree / "build" / "libwhirl.so")
    shutil.copytree(os.path.join(repo, "python"), tree / "python",
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "tests",
                                                  "examples", "libwhirl.so", "_ffi.py",
                                                  ".libs"))
    home = tmp_path / "home"
    env = {k: v for k, v in os.environ.items()
           if k not in ("WHIRL_LIBRARY", "PYTHONPATH", "PYTHONNOUSERSITE", "WHIRL_SOURCE")}
    env.update(HOME=str(home), WHIRL_PREBUILT=str(tree / "build" / "libwhirl.so"))
    user_site = subprocess.run(["/usr/bin/python3", "-c", "import site; "
                                "print(site.getusersitepackages())"], env=env, check=True,
                               capture_output=True, text=True).stdout.strip()
    assert user_site.startswith(str(home)), user_site
    subprocess.run(["/usr/bin/python3", "-m", "pip", "install", "-q", "--no-build-isolation",
                    "--no-deps", "--no-index", "--target", user_site, str(tree / "python")],
                   check=True, env=env, capture_output=True)
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-build-isolation",
                    "--no-deps", "--no-index", "-e", str(tree / "python")], check=True,
                   env=env, capture_output=True)
    out = subprocess.run([str(python), "-c", PROBE], cwd="/", env=env, check=True,
                         capture_output=True, text=True).stdout
    version, library, module, rates = json.loads(out)
    assert module == str(tree / "python" / "whirl" / "__init__.py"), module
    assert library == str(tree / "build" / "libwhirl.so"), library
    assert version == whirl.__version__
    np.testing.assert_array_equal(rates, whirl.critical(3, length=0.6))
    # the installed copy is there, and a Python outside the venv takes it
    out = subprocess.run(["/usr/bin/python3", "-c", PROBE], cwd="/", env=env, check=True,
                         capture_output=True, text=True).stdout
    assert json.loads(out)[2].startswith(user_site)
    # the source folder on the path brings nothing else that runs: `import setup` builds nothing
    subprocess.run([str(python), "-c", "import setup"], cwd="/", env=env, check=True,
                   capture_output=True)


@pytest.fixture(scope="module")
def wheel(tmp_path_factory, repo):
    """The wheel, built once for the tests below, as `make wheel` builds it."""
    tmp = tmp_path_factory.mktemp("wheel")
    src, env = _copy_source(tmp / "python", repo)
    wheels = tmp / "wheels"
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-build-isolation",
                    "--no-deps", "--no-index", "-w", str(wheels), str(src)], check=True, env=env)
    (path,) = wheels.iterdir()
    return path, env


def test_wheel_holds_the_library(wheel, repo):
    path, _ = wheel
    # any Python 3 on this platform: the package holds no CPython extension
    assert path.name == "whirl-%s-py3-none-linux_x86_64.whl" % whirl.__version__, path.name
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
        generated = z.read("whirl/_ffi.py").decode()
        readme = z.read("whirl/.libs/README").decode()
    assert "whirl/libwhirl.so" in names and "whirl/py.typed" in names
    assert "whirl/LICENSE" in names
    # every library that build/libwhirl.so links, but the C library's own, is in whirl/.libs
    # with the licence of the Debian package it came from
    linked = _linked(os.path.join(os.environ.get("WHIRL_BUILD", os.path.join(repo, "build")),
                                  "libwhirl.so"))
    libs = sorted(n[len("whirl/.libs/"):] for n in names
                  if n.startswith("whirl/.libs/lib"))
    assert libs == sorted(linked), (libs, linked)
    assert {"libgsl", "libnlopt", "libinih", "liblapacke", "libgomp"} <= {
        n.split(".so.")[0] for n in libs}, libs
    for soname in libs:
        (row,) = [line.split() for line in readme.splitlines() if line.startswith(soname + " ")]
        assert "whirl/.libs/licenses/%s.copyright" % row[2] in names, row
    # the declarations, parsed when the wheel was built, are those of the checkout's _cdef.py
    assert generated == _build.module_text(_cdef.CDEF)


def _linked(library, env=None):
    """{soname: file} of what the loader takes for ``library`` (ldd), but the C library's own
    (setup.py's SYSTEM)."""
    out = subprocess.run(["ldd", library], check=True, capture_output=True, text=True,
                         env=env).stdout
    found = {}
    for line in out.splitlines():
        assert "not found" not in line, out
        parts = line.split()
        if len(parts) >= 3 and parts[1] == "=>" and not parts[0].startswith(SYSTEM):
            found[parts[0]] = parts[2]
    return found


SYSTEM = ("ld-linux", "libc.so.", "libm.so.", "libgcc_s.so.", "libpthread.so.", "libdl.so.",
          "librt.so.", "libutil.so.", "libresolv.so.")


def _clean_venv(tmp_path, env):
    """A venv without the system's packages (python3 -m venv, no --system-site-packages) that
    sees numpy and cffi (with pycparser) alone: there is no index to install them from, so
    Debian's copies are linked into a folder of their own, which a .pth file puts on the
    venv's path, as the system's site would be. pip is the system's, run on the venv's
    interpreter (--python)."""
    venv = tmp_path / "venv"
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--without-pip", str(venv)], check=True)
    outside = tmp_path / "outside"
    outside.mkdir()
    for name in ("numpy", "cffi", "pycparser"):
        spec = importlib.util.find_spec(name)
        os.symlink(os.path.dirname(spec.origin), outside / name)
    backend = importlib.util.find_spec("_cffi_backend").origin
    os.symlink(backend, outside / os.path.basename(backend))
    (site,) = (venv / "lib").glob("python3*/site-packages")
    (site / "outside.pth").write_text(str(outside) + "\n")
    python = venv / "bin" / "python"
    out = subprocess.run([str(python), "-c", "import sys; print(sys.path)"], env=env,
                         cwd="/", check=True, capture_output=True, text=True).stdout
    assert "dist-packages" not in out, out  # nothing of the system's site
    return python, site, outside


def _pip(python, env, *args):
    subprocess.run(["/usr/bin/python3", "-m", "pip", "--python", str(python), "install", "-q",
                    "--no-index"] + list(args), check=True, env=env)


def _loaded(python, env, code):
    """Runs ``code``: the files of the shared libraries then mapped in the process (its
    /proc/self/maps, what the loader took, wherever it found it)."""
    out = subprocess.run([str(python), "-c", code + "; print(open('/proc/self/maps').read())"],
                         cwd="/", env=env, check=True, capture_output=True, text=True).stdout
    return {line.split()[-1] for line in out.splitlines()
            if len(line.split()) == 6 and ".so" in line.split()[-1]}


def test_wheel_stands_alone(wheel, tmp_path):
    path, env = wheel
    python, site, outside = _clean_venv(tmp_path, env)
    # the environment sees a whirl of the same version already (the system's, say): the
    # documented command replaces it in the venv, where pip alone would keep it
    subprocess.run(["/usr/bin/python3", "-m", "pip", "install", "-q", "--no-index", "--no-deps",
                    "--target", str(outside), str(path)], check=True, env=env)
    _pip(python, env, "--force-reinstall", "--no-deps", str(path))
    _probe(python, env, tmp_path / "venv")
    # the declarations come parsed: neither pycparser nor cffi's parser at import
    out = subprocess.run([str(python), "-c", "import sys, whirl; print(sorted(m for m in "
                          "sys.modules if m.split('.')[0] in ('cffi', 'pycparser')))"],
                         cwd="/", env=env, check=True, capture_output=True, text=True).stdout
    assert out.strip() == "[]", out

    # every library libwhirl links, but the C library's own, resolves inside the wheel's folder
    libs = site / "whirl" / ".libs"
    library = str(site / "whirl" / "libwhirl.so")
    linked = _linked(library, env)
    assert linked and all(os.path.dirname(f) == str(libs) for f in linked.values()), linked
    # and the process maps them from there: all but those numpy mapped before (the loader
    # shares a library by its name, and these are ABI-compatible by it), and no system copy
    system = {soname: os.path.realpath(f) for soname, f in _linked(whirl.LIBRARY_PATH).items()}
    assert set(system) == set(linked), (system, linked)
    before = _loaded(python, env, "import numpy")
    numpy_libs = {soname for soname, f in system.items() if f in before}
    files = _loaded(python, env, "import whirl; whirl.shape(3.0, 1)")
    for soname in set(linked) - numpy_libs:
        assert str(libs / soname) in files and system[soname] not in files, (soname, files)
    assert any("libgsl" in f for f in files) and not [
        f for f in files if "/libgsl" in f and not f.startswith(str(libs))], files

    # the proof: the system's copies made unreadable (/dev/null mounted over them, in a mount
    # namespace of the test's own), first those numpy does not need, then all of them
    # (libwhirl loaded first, so that numpy takes the wheel's BLAS and LAPACK)
    if subprocess.run(["unshare", "-rm", "true"], capture_output=True).returncode != 0:
        pytest.skip("no user and mount namespaces here (unshare -rm) to hide the system's "
                    "libraries")
    for hide, first in ((set(linked) - numpy_libs, ""),
                        (set(linked), "import ctypes; ctypes.CDLL(%r); " % library)):
        files = sorted({system[soname] for soname in hide})
        script = ('for f in "$@"; do mount --bind /dev/null "$f" || exit 1; done; exec %s -c '
                  '"%simport whirl; print(list(whirl.critical(3, length=0.6)))"'
                  % (python, first))
        done = subprocess.run(["unshare", "-rm", "sh", "-c", script, "sh"] + files, cwd="/",
                              env=env, capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        np.testing.assert_array_equal(eval(done.stdout), whirl.critical(3, length=0.6))


def test_wheel_import_error_advice(wheel, tmp_path):
    # a wheel whose library does not load (here: a library it carries is damaged) names the
    # file and says what a wheel's user can do, which is not to build it
    path, env = wheel
    python, site, _ = _clean_venv(tmp_path, env)
    _pip(python, env, "--no-deps", str(path))
    (site / "whirl" / ".libs" / "libnlopt.so.0").write_bytes(b"")
    done = subprocess.run([str(python), "-c", "import whirl"], cwd="/", env=env,
                          capture_output=True, text=True)
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: whirl: cannot load libwhirl:"), last
    assert "libnlopt.so.0: file too short" in last and "reinstall" in last, last
    assert "`make" not in last and "Build it" not in last, last


# the layout the package's ffi gives every struct and constant that test_layout.py checks
# against the C headers
LAYOUT = ("from whirl import _cdef; from whirl._lib import ffi, lib; print(repr("
          "[(n, getattr(lib, n)) for n in _cdef.CONSTANTS] + [(n, ffi.sizeof(n), [(f, t.offset) "
          "for f, t in ffi.typeof(n).fields]) for n in _cdef.STRUCTS]))")


def test_generated_declarations_used_only_when_current(tmp_path, repo):
    # the package uses whirl/_ffi.py only when it was generated from its own _cdef.py, and
    # then lays out every struct as the parsed declarations do (test_layout.py: as C does)
    pkg = tmp_path / "whirl"
    shutil.copytree(os.path.join(repo, "python", "whirl"), pkg,
                    ignore=shutil.ignore_patterns("__pycache__", "libwhirl.so", ".libs"))
    env = dict(os.environ, PYTHONPATH=str(tmp_path))
    code = ("import sys, whirl, whirl._ffi; print(whirl._lib.ffi is whirl._ffi.ffi, "
            "'pycparser' in sys.modules, whirl.critical(1)[0])")
    parsed = subprocess.run([sys.executable, "-c", LAYOUT], cwd="/", env=env, check=True,
                            capture_output=True, text=True).stdout
    for cdef, current in ((_cdef.CDEF, True), (_cdef.CDEF + "\nint whirl_gone(void);\n", False)):
        _build.write_module(cdef, str(pkg / "_ffi.py"))
        out = subprocess.run([sys.executable, "-c", code], cwd="/", env=env, check=True,
                             capture_output=True, text=True).stdout.split()
        assert out[:2] == [str(current), str(not current)], out
        assert float(out[2]) == whirl.critical(1)[0]
        layout = subprocess.run([sys.executable, "-c", LAYOUT], cwd="/", env=env, check=True,
                                capture_output=True, text=True).stdout
        assert layout == parsed


def test_source_tree_keeps_its_declarations_parsed(tmp_path, repo):
    # from a source tree the first import parses the declarations and keeps the module made
    # from them in build/python/, which the next imports use, until _cdef.py changes
    tree = tmp_path / "tree"
    for d in ("src", "build", "python"):
        (tree / d).mkdir(parents=True)
    (tree / "Makefile").write_text("")
    shutil.copytree(os.path.join(repo, "python", "whirl"), tree / "python" / "whirl",
                    ignore=shutil.ignore_patterns("__pycache__", "libwhirl.so", ".libs",
                                                  "_ffi.py"))
    cache = tree / "build" / "python" / "whirl_ffi.py"
    env = dict(os.environ, PYTHONPATH=str(tree / "python"))

    def run():
        out = subprocess.run([sys.executable, "-c", "import sys, whirl; print('pycparser' in "
                              "sys.modules, whirl.critical(1)[0])"], cwd="/", env=env,
                             check=True, capture_output=True, text=True).stdout.split()
        assert float(out[1]) == whirl.critical(1)[0]
        return out[0] == "True"

    assert run() and cache.exists()  # parsed, and kept
    assert _build.module_text(_cdef.CDEF) == cache.read_text()
    assert not run()  # the kept module
    with open(tree / "python" / "whirl" / "_cdef.py", "a") as f:
        f.write('CDEF += "\\nint whirl_gone(void);\\n"\n')
    assert run() and "whirl_gone" in cache.read_text()  # parsed again, and kept again
    assert not run()


def test_wheel_holds_the_live_page(wheel, tmp_path):
    path, env = wheel
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
    # the live page of make web goes in when the library's build has it
    page = os.path.join(os.path.dirname(os.path.realpath(env["WHIRL_PREBUILT"])), "web",
                        "whirl-explore.html")
    assert ("whirl/whirl-explore.html" in names) == os.path.isfile(page)
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--ignore-installed", "--no-deps",
                    "--no-index", str(path)], check=True, env=env)
    _probe(python, env, tmp_path / "venv")
    if os.path.isfile(page):  # whirl.explore opens the package's copy
        env = {k: v for k, v in env.items() if k != "WHIRL_EXPLORE_PAGE"}
        out = subprocess.run([str(python), "-m", "whirl.explore", "--no-browser"], cwd="/",
                             env=env, check=True, capture_output=True, text=True).stdout
        assert out.startswith("whirl explore: file://" + str(tmp_path / "venv")), out
        assert out.strip().endswith("/whirl/whirl-explore.html"), out


def test_pip_runs_make(tmp_path, source, repo):
    # without WHIRL_PREBUILT setup.py runs make for build/libwhirl.so (up to date here: the
    # plain build; the sanitizer half's library is another build's)
    src, env = source
    del env["WHIRL_PREBUILT"]
    if os.environ.get("WHIRL_SANITIZE"):
        env["WHIRL_BUILD"] = os.path.join(repo, "build")
    python = _venv(tmp_path, "venv")
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--ignore-installed", "--no-build-isolation",
                    "--no-deps", "--no-index", str(src)], check=True, env=env)
    out = subprocess.run([str(python), "-c", "import whirl; print(whirl.LIBRARY_PATH)"],
                         cwd="/", env=env, check=True, capture_output=True, text=True).stdout
    assert out.strip().startswith(str(tmp_path / "venv"))


def test_build_without_the_repository_fails_in_one_line(tmp_path, source):
    src, env = source
    env["WHIRL_SOURCE"] = str(tmp_path / "nowhere")
    done = subprocess.run([sys.executable, str(src / "setup.py"), "--version"], env=env,
                          capture_output=True, text=True, cwd=str(src))
    assert done.returncode != 0
    lines = [line for line in done.stderr.splitlines() if line.startswith("whirl:")]
    assert len(lines) == 1 and "version.h" in lines[0], done.stderr
