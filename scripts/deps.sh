#!/bin/sh
# Installs the Debian packages whirl needs when run as root; otherwise prints the command.
pkgs="build-essential pkg-config libgsl-dev libnlopt-dev libinih-dev liblapacke-dev libcmocka-dev gnuplot-nox libopenmpi-dev openmpi-bin"
missing=""
for p in $pkgs; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" = 0 ]; then
  echo "whirl: installing Debian packages:$missing"
  export DEBIAN_FRONTEND=noninteractive
  { apt-get install -y -q $missing || { apt-get update -q && apt-get install -y -q $missing; }; } >&2 || {
    echo "whirl: apt-get install failed for:$missing" >&2; exit 1; }
else
  echo "whirl: missing Debian packages:$missing" >&2
  echo "whirl: install them with: sudo apt-get install -y$missing" >&2
  exit 1
fi
