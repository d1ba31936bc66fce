#!/bin/sh
# The compiler of the web build's objects (make web), printed as one command line: the clang that
# emcc itself runs, with the flags emcc gives it (emcc --cflags), when a probe compiled both ways
# gives the same object byte for byte; otherwise emcc. emcc starts Python and its configuration for
# every file (about 1 s of processor time each, the page's ~80 objects 80 s); clang alone takes
# 0.3 s. The link stays with emcc.
#
#   sh scripts/web-cc.sh GSL_PREFIX CFLAGS...    prints "CLANG FLAGS" or "emcc"
set -u
prefix=$1
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# a probe with a header of the library and one of GSL, as the objects have
cat >"$tmp/probe.c" <<'C'
#include <math.h>
#include <gsl/gsl_math.h>
double whirl_web_cc_probe(double x) { return gsl_isnan(x) ? 0 : sin(x) * x; }
C
if ! emcc "$@" -I"$prefix/include" -c "$tmp/probe.c" -o "$tmp/emcc.o" -v 2>"$tmp/v"; then
  echo emcc
  exit 0
fi
# emcc -v echoes the clang command it runs: its first word is the compiler
cc=$(grep -E '^ *"?/[^ ]*clang[^ ]*"? ' "$tmp/v" | grep -- ' -c ' | head -n 1 | awk '{print $1}' | tr -d '"')
flags=$(emcc --cflags 2>/dev/null)
if [ -n "$cc" ] && [ -x "$cc" ] && [ -n "$flags" ] &&
   "$cc" $flags "$@" -I"$prefix/include" -c "$tmp/probe.c" -o "$tmp/cc.o" 2>/dev/null &&
   cmp -s "$tmp/emcc.o" "$tmp/cc.o"; then
  echo "$cc $flags"
else
  echo emcc
fi
