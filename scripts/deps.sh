#!/bin/sh
# Checks that what whirl needs is present (commands, pkg-config modules, headers) and installs the
# Debian packages that provide what is missing, when run as root; otherwise prints the command.
# When nothing is missing it needs neither dpkg nor apt.

have_cmd() { command -v "$1" >/dev/null 2>&1; }
have_pc() { have_cmd pkg-config && pkg-config --exists "$1"; }
# have_header COMPILER HEADER [FLAGS]: the compiler finds the header
have_header() { have_cmd "$1" && echo "#include <$2>" | "$1" $3 -E -xc - >/dev/null 2>&1; }
# have_py MODULE: Debian's Python 3 imports the module (the Python package and its tests)
have_py() { [ -x /usr/bin/python3 ] && /usr/bin/python3 -c "import $1" >/dev/null 2>&1; }

# Each line: Debian package, then the check that it is present.
checks='
build-essential  have_cmd cc && have_cmd make && have_cmd ar && have_cmd nm
pkg-config       have_cmd pkg-config
libgsl-dev       have_pc gsl
libnlopt-dev     have_pc nlopt
libinih-dev      have_pc inih
liblapacke-dev   have_pc lapacke
libcmocka-dev    have_pc cmocka
gnuplot-nox      have_cmd gnuplot
libopenmpi-dev   have_cmd mpicc
openmpi-bin      have_cmd mpirun
clang            have_cmd clang
libomp-dev       have_header clang omp.h -fopenmp
python3          test -x /usr/bin/python3
python3-cffi     have_py cffi
python3-numpy    have_py numpy
python3-scipy    have_py scipy
python3-pytest   have_py pytest
python3-matplotlib have_py matplotlib
python3-nbformat have_py nbformat
python3-mpmath   have_py mpmath
python3-nbclient have_py nbclient
python3-ipykernel have_py ipykernel
python3-pip      have_py pip
python3-setuptools have_py setuptools
python3-wheel    have_py wheel
python3-mypy     have_py mypy
libmujoco-dev    have_header cc mujoco/mujoco.h
libsundials-dev  have_header cc arkode/arkode_erkstep.h && have_header cc cvode/cvode.h
chromium         have_cmd chromium
python3-websocket have_py websocket
ffmpeg           have_cmd ffmpeg
bsdutils         have_cmd script
python3-sphinx   have_py sphinx
python3-myst-parser have_py myst_parser
libjs-mathjax    test -f /usr/share/javascript/mathjax/MathJax.js
'

missing=""
what=""
while read -r pkg check; do
  [ -n "$pkg" ] || continue
  if ! eval "$check"; then
    missing="$missing $pkg"
    what="$what
  $pkg (failed: $check)"
  fi
done <<EOF
$checks
EOF
[ -z "$missing" ] && exit 0
echo "whirl: missing:$what" >&2
if [ "$(id -u)" = 0 ] && have_cmd apt-get; then
  echo "whirl: installing Debian packages:$missing" >&2
  export DEBIAN_FRONTEND=noninteractive
  { apt-get install -y -q $missing || { apt-get update -q && apt-get install -y -q $missing; }; } >&2 || {
    echo "whirl: apt-get install failed for:$missing" >&2; exit 1; }
else
  echo "whirl: install them with: sudo apt-get install -y$missing" >&2
  exit 1
fi
