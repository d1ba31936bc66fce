"""Builds the whirl package with its own copy of libwhirl inside (whirl/libwhirl.so).

The library comes from the source tree this directory sits in (python/ of the whirl
repository): ``make -C .. build/libwhirl.so`` is run first (WHIRL_BUILD=DIR: another build
directory; WHIRL_PREBUILT=FILE: that library, without make), and its file is copied into the
package, which loads it before any other copy
(whirl.LIBRARY_PATH). The live page build/web/whirl-explore.html of `make web` goes in too when
it is built (whirl.explore opens it). Without the repository, or when make fails, the build stops with one line
saying what to run. The wheel is tagged for this platform (it carries a shared library); the
library's own dependencies (GSL, NLopt, LAPACKE, inih, OpenMP) stay the system's (scripts/deps.sh
installs them)."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = os.path.dirname(os.path.abspath(__file__))
# WHIRL_SOURCE=DIR: the repository, for a copy of python/ built elsewhere
REPO = os.path.abspath(os.environ.get("WHIRL_SOURCE", os.path.dirname(HERE)))


def _fail(message):
    sys.stderr.write("whirl: %s\n" % message)
    raise SystemExit(1)


def _version():
    header = os.path.join(REPO, "include", "whirl", "version.h")
    try:
        with open(header) as f:
            text = f.read()
    except OSError:
        _fail("cannot read %s: build the package from the whirl repository (pip install "
              "--no-build-isolation ./python)" % header)
    parts = [re.search(r"#define WHIRL_VERSION_%s (\d+)" % k, text) for k in
             ("MAJOR", "MINOR", "PATCH")]
    if not all(parts):
        _fail("no WHIRL_VERSION_MAJOR/MINOR/PATCH in %s" % header)
    return ".".join(m.group(1) for m in parts)


def _library():
    """The path of the library just built (make's target is up to date when nothing changed),
    or WHIRL_PREBUILT: a libwhirl.so built already (a packager's, or another build's such as the
    sanitizer build, whose flags make would otherwise replace), copied as it is."""
    prebuilt = os.environ.get("WHIRL_PREBUILT")
    if prebuilt:
        if not os.path.isfile(prebuilt):
            _fail("WHIRL_PREBUILT=%s is not a file: build it with `make` in %s" % (prebuilt,
                                                                                   REPO))
        return os.path.realpath(prebuilt)
    build = os.path.abspath(os.environ.get("WHIRL_BUILD", os.path.join(REPO, "build")))
    if not os.path.exists(os.path.join(REPO, "Makefile")):
        _fail("no Makefile in %s: build the package from the whirl repository" % REPO)
    target = os.path.join(build, "libwhirl.so")
    rel = os.path.relpath(target, REPO)
    cmd = ["make", "-C", REPO, "--no-print-directory", "BUILD=" + os.path.relpath(build, REPO),
           rel]
    try:
        done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    except OSError as e:
        _fail("cannot run make (%s): install build-essential (sh scripts/deps.sh), then run "
              "`make` in %s" % (e, REPO))
    if done.returncode != 0 or not os.path.exists(target):
        last = [line for line in done.stdout.splitlines() if line.strip()][-1:] or ["?"]
        _fail("building libwhirl failed (%s): run `sh scripts/deps.sh && make` in %s and see "
              "its errors" % (last[0].strip(), REPO))
    return os.path.realpath(target)


class BuildWithLibrary(build_py):
    def run(self):
        super().run()
        lib = _library()
        dest = os.path.join(self.build_lib, "whirl", "libwhirl.so")
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        shutil.copyfile(lib, dest)
        os.chmod(dest, 0o755)
        # the live page of `make web` (whirl.explore opens it), when it is built: the WebAssembly
        # build needs emscripten, which the package does not
        page = os.path.join(os.path.dirname(lib), "web", "whirl-explore.html")
        if os.path.isfile(page):
            shutil.copyfile(page, os.path.join(self.build_lib, "whirl", "whirl-explore.html"))


class BinaryDistribution(Distribution):
    """A wheel for this platform: the package holds a shared library."""

    def has_ext_modules(self):
        return True


setup(version=_version(), cmdclass={"build_py": BuildWithLibrary},
      distclass=BinaryDistribution)
