"""Builds the whirl package with its own copy of libwhirl inside (whirl/libwhirl.so), and the
libraries that copy links (whirl/.libs), so that the package stands alone.

The library comes from the source tree this directory sits in (python/ of the whirl
repository): ``make -C .. build/libwhirl.so`` is run first (WHIRL_BUILD=DIR: another build
directory; WHIRL_PREBUILT=FILE: that library, without make), and its file is copied into the
package, which loads it before any other copy (whirl.LIBRARY_PATH). The live page
build/web/whirl-explore.html of `make web` goes in too when it is built (whirl.explore opens
it). Without the repository, or
when make fails, the build stops with one line saying what to run.

The libraries libwhirl links (GSL, NLopt, inih, LAPACKE with LAPACK and BLAS, OpenMP, gfortran's
runtime: ldd's list but the C library's own, which every Linux has) are copied from the system
into whirl/.libs, and patchelf sets the run-time search path of each copy, and of libwhirl, to
the folder it sits in ($ORIGIN), so that the loader takes them there before the system's; each
one's Debian copyright file goes beside them (whirl/.libs/licenses, listed in
whirl/.libs/README). WHIRL_VENDOR=0 leaves them out: a package that uses the system's
libraries (a distribution's). The declarations of whirl/_cdef.py are written, parsed, as the
module whirl/_ffi.py (whirl/_build.py). The wheel holds no CPython extension: it is tagged
py3-none-<platform>, for any Python 3 on this platform."""
import os
import re
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

try:
    from wheel.bdist_wheel import bdist_wheel
except ImportError:  # an install without the wheel package builds no wheel
    bdist_wheel = None

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


# The C library's own (glibc, the loader, libgcc_s: the manylinux policies' list), which every
# Linux has and which must be the system's: never copied
SYSTEM = ("linux-vdso.so.", "ld-linux", "libc.so.", "libm.so.", "libgcc_s.so.", "libpthread.so.",
          "libdl.so.", "librt.so.", "libutil.so.", "libresolv.so.")


def _run(cmd):
    try:
        return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    except OSError as e:
        _fail("cannot run %s (%s): sh scripts/deps.sh python installs what the package's build "
              "needs, or WHIRL_VENDOR=0 builds a package that uses the system's libraries"
              % (cmd[0], e))


def _linked(path):
    """{soname: file} of every library ``path`` loads (ldd: the whole closure), but SYSTEM's."""
    done = _run(["ldd", path])
    if done.returncode != 0:
        _fail("ldd %s failed: %s" % (path, done.stdout.strip()))
    found = {}
    for line in done.stdout.splitlines():
        if "not found" in line:
            _fail("%s needs %s, which this system lacks: run sh scripts/deps.sh build"
                  % (path, line.split()[0]))
        m = re.match(r"\s*(\S+) => (/\S+) \(0x", line)
        if m and not m.group(1).startswith(SYSTEM):
            found[m.group(1)] = os.path.realpath(m.group(2))
    return found


def _debian_package(path):
    """(package, version, source package, source version) that installed ``path``."""
    for p in (path, re.sub(r"^/usr/", "/", path)):  # merged /usr: dpkg may list either
        done = _run(["dpkg-query", "-S", p])
        if done.returncode == 0:
            pkg = done.stdout.split(":")[0].strip()
            info = _run(["dpkg-query", "-W", "-f", "${Version} ${source:Package} "
                         "${source:Version}", pkg]).stdout.split()
            if len(info) == 3:
                return (pkg,) + tuple(info)
    _fail("no Debian package owns %s, so its licence is unknown: build on Debian, or with "
          "WHIRL_VENDOR=0 (a package that uses the system's libraries)" % path)


def _vendor(package, library):
    """Copies the libraries ``library`` links into package/.libs with their licences, and
    points the run-time search paths at them."""
    libs = os.path.join(package, ".libs")
    licenses = os.path.join(libs, "licenses")
    shutil.rmtree(libs, ignore_errors=True)
    os.makedirs(licenses)
    readme = ["The libraries whirl/libwhirl.so links, copied from the Debian system the "
              "package was built",
              "on. Each one's licence: licenses/SOURCE.copyright, the copyright file of its "
              "Debian package;",
              "its source code: `apt-get source SOURCE=VERSION`, or "
              "https://sources.debian.org/src/SOURCE/VERSION/.", "",
              "%-18s %-14s %-22s %s" % ("library", "package", "SOURCE", "VERSION")]
    for soname, path in sorted(_linked(library).items()):
        dest = os.path.join(libs, soname)
        shutil.copyfile(path, dest)
        os.chmod(dest, 0o755)
        pkg, _, source, version = _debian_package(path)
        copyright_file = os.path.join("/usr/share/doc", pkg, "copyright")
        if not os.path.isfile(copyright_file):
            _fail("%s has no %s: its licence is unknown" % (pkg, copyright_file))
        shutil.copyfile(copyright_file, os.path.join(licenses, source + ".copyright"))
        readme.append("%-18s %-14s %-22s %s" % (soname, pkg, source, version))
        _patchelf(dest, "$ORIGIN")
    _patchelf(library, "$ORIGIN/.libs")
    with open(os.path.join(libs, "README"), "w") as f:
        f.write("\n".join(readme) + "\n")


def _patchelf(path, rpath):
    done = _run(["patchelf", "--set-rpath", rpath, path])
    if done.returncode != 0:
        _fail("patchelf --set-rpath %s %s failed: %s" % (rpath, path, done.stdout.strip()))


def _declarations(package):
    """whirl/_ffi.py from whirl/_cdef.py (whirl/_build.py; both read as files: importing the
    package would load libwhirl)."""
    import importlib.util
    mods = {}
    for name in ("_cdef", "_build"):
        spec = importlib.util.spec_from_file_location(
            "whirl_setup_" + name, os.path.join(HERE, "whirl", name + ".py"))
        mods[name] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mods[name])
    try:
        import cffi  # noqa: F401 (the build parses the declarations with it)
    except ImportError:
        _fail("the build needs cffi (Debian: python3-cffi; or pip install cffi, or leave out "
              "--no-build-isolation)")
    mods["_build"].write_module(mods["_cdef"].CDEF, os.path.join(package, "_ffi.py"))


class BuildWithLibrary(build_py):
    def run(self):
        super().run()
        lib = _library()
        package = os.path.join(self.build_lib, "whirl")
        dest = os.path.join(package, "libwhirl.so")
        os.makedirs(package, exist_ok=True)
        shutil.copyfile(lib, dest)
        os.chmod(dest, 0o755)
        shutil.copyfile(os.path.join(REPO, "LICENSE"), os.path.join(package, "LICENSE"))
        _declarations(package)
        if os.environ.get("WHIRL_VENDOR", "1") != "0":
            _vendor(package, dest)
        else:
            shutil.rmtree(os.path.join(package, ".libs"), ignore_errors=True)
        # the live page of `make web` (whirl.explore opens it), when it is built: the WebAssembly
        # build needs emscripten, which the package does not
        page = os.path.join(os.path.dirname(lib), "web", "whirl-explore.html")
        if os.path.isfile(page):
            shutil.copyfile(page, os.path.join(package, "whirl-explore.html"))


class BinaryDistribution(Distribution):
    """A wheel for this platform: the package holds shared libraries."""

    def has_ext_modules(self):
        return True


cmdclass = {"build_py": BuildWithLibrary}
if bdist_wheel is not None:
    class PlatformWheel(bdist_wheel):
        """Tagged py3-none-<platform>: any Python 3 (the package holds no CPython extension,
        only libraries that cffi opens), on this platform (linux_x86_64)."""

        def get_tag(self):
            return ("py3", "none", super().get_tag()[2])

    cmdclass["bdist_wheel"] = PlatformWheel

# pip and setuptools run this file as __main__; an editable install puts python/ on the path, where
# `import setup` must do nothing
if __name__ == "__main__":
    setup(version=_version(), cmdclass=cmdclass, distclass=BinaryDistribution)
