#!/bin/sh
# Checks that what whirl needs for a purpose is present (commands, pkg-config modules, headers,
# Python modules) and installs the Debian packages that provide what is missing, without their
# recommendations, when run as root; otherwise prints the command. When nothing is missing it needs
# neither dpkg nor apt, and takes a few hundredths of a second: file tests, one pkg-config call,
# one Python start that locates (does not import) the modules.
#
# Usage: deps.sh GROUP...  (no GROUP, or "all": every group). The groups, by purpose:
#   run      what the program needs to draw: gnuplot, and ffmpeg for MP4 movies
#   build    the compiler and the libraries whirl links (make, make demo: run and build)
#   python   the Python package (make python, make wheel; patchelf points the wheel's libraries
#            at each other)
#   tests    make check's tools: cmocka, clang for the second compile (and its runtimes for make
#            fuzz), Open MPI, the Python suite's modules, a pseudo-terminal, bc, a German locale
#   docs     the manual (make docs, and its test in make check)
#   peers    the peers the benchmarks and tests/unit/dynamics/test_peers.c compare with
#   browser  headless Chromium for the viewer's and the live page's tests
# make check needs them all.
groups=${*:-all}
[ "$groups" = all ] && groups="run build python tests docs peers browser"

have_cmd() { command -v "$1" >/dev/null 2>&1; }
# have_pc MODULE: pkg-config knows it (the whole list is asked once first, below)
have_pc() { [ -n "$pc_all" ] || { have_cmd pkg-config && pkg-config --exists "$1"; }; }
# have_header HEADER: under /usr/include (Debian's place), or else the C compiler finds it
have_header() {
  [ -f "/usr/include/$1" ] || [ -f "/usr/include/x86_64-linux-gnu/$1" ] ||
    { have_cmd cc && echo "#include <$1>" | cc -E -xc - >/dev/null 2>&1; }
}
# have_py MODULE: Debian's Python 3 finds the module (located once for all, below, not imported)
have_py() { case " $py_found " in *" $1 "*) return 0 ;; esac; return 1; }

# Each line: group, Debian package, then the check that it is present.
checks='
run     gnuplot-nox        have_cmd gnuplot
run     ffmpeg             have_cmd ffmpeg
build   build-essential    have_cmd cc && have_cmd make && have_cmd ar && have_cmd nm
build   pkg-config         have_cmd pkg-config
build   libgsl-dev         have_pc gsl
build   libnlopt-dev       have_pc nlopt
build   libinih-dev        have_pc inih
build   liblapacke-dev     have_pc lapacke
python  python3            test -x /usr/bin/python3
python  python3-cffi       have_py cffi
python  python3-numpy      have_py numpy
python  python3-pip        have_py pip
python  python3-setuptools have_py setuptools
python  python3-wheel      have_py wheel
python  python3-venv       test -n "$(ls /usr/lib/python3*/ensurepip/__init__.py 2>/dev/null)"
python  patchelf           have_cmd patchelf
tests   libcmocka-dev      have_pc cmocka
tests   libopenmpi-dev     have_cmd mpicc
tests   openmpi-bin        have_cmd mpirun
tests   clang              have_cmd clang
tests   libomp-dev         test -n "$(ls /usr/lib/llvm-*/lib/clang/*/include/omp.h 2>/dev/null)" || { have_cmd clang && echo "#include <omp.h>" | clang -fopenmp -E -xc - >/dev/null 2>&1; }
tests   python3-scipy      have_py scipy
tests   python3-pytest     have_py pytest
tests   python3-matplotlib have_py matplotlib
tests   python3-nbformat   have_py nbformat
tests   python3-mpmath     have_py mpmath
tests   python3-nbclient   have_py nbclient
tests   python3-ipykernel  have_py ipykernel
tests   python3-mypy       have_py mypy
tests   python3-pandas     have_py pandas
tests   python3-pint       have_py pint
tests   bsdutils           have_cmd script
tests   bc                 have_cmd bc
tests   libclang-rt-dev    test -n "$(ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a 2>/dev/null)"
tests   locales            have_cmd localedef && test -f /usr/share/i18n/locales/de_DE
docs    python3-sphinx     have_py sphinx
docs    python3-myst-parser have_py myst_parser
docs    libjs-mathjax      test -f /usr/share/javascript/mathjax/MathJax.js
peers   libmujoco-dev      have_header mujoco/mujoco.h
peers   libsundials-dev    have_header arkode/arkode_erkstep.h && have_header cvode/cvode.h
browser chromium           have_cmd chromium
browser python3-websocket  have_py websocket
'

# the lines of the groups asked for
wanted=$(echo "$checks" | while read -r group rest; do
  case " $groups " in *" $group "*) echo "$group $rest" ;; esac
done)
# pkg-config once for every module asked for (one by one only if that fails)
pc_all=
modules=$(echo "$wanted" | awk '$3 == "have_pc" { printf " %s", $4 }')
[ -n "$modules" ] && have_cmd pkg-config && pkg-config --exists $modules && pc_all=1
# the Python modules asked for, located by one interpreter (importlib's find_spec reads no module)
py_found=
pymods=$(echo "$wanted" | awk '$3 == "have_py" { printf " %s", $4 }')
if [ -n "$pymods" ] && [ -x /usr/bin/python3 ]; then
  py_found=$(/usr/bin/python3 -c '
import sys
from importlib.util import find_spec
print(" ".join(m for m in sys.argv[1:] if find_spec(m) is not None))' $pymods 2>/dev/null)
fi

missing=""
what=""
while read -r group pkg check; do
  [ -n "$pkg" ] || continue
  if ! eval "$check"; then
    missing="$missing $pkg"
    what="$what
  $pkg ($group; failed: $check)"
  fi
done <<EOF
$wanted
EOF
[ -z "$missing" ] && exit 0
echo "whirl: missing:$what" >&2
if [ "$(id -u)" = 0 ] && have_cmd apt-get; then
  echo "whirl: installing Debian packages:$missing" >&2
  export DEBIAN_FRONTEND=noninteractive
  install() { apt-get install -y -q --no-install-recommends $missing; }
  { install || { apt-get update -q && install; }; } >&2 || {
    echo "whirl: apt-get install failed for:$missing" >&2; exit 1; }
else
  echo "whirl: install them with: sudo apt-get install -y --no-install-recommends$missing" >&2
  exit 1
fi
