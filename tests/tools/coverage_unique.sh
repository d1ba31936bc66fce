#!/bin/sh
# What the sanitizer half of make check would lose by leaving TESTs out: the lines of src/ that
# each TEST executes and no other test of the sanitizer half does. Builds BUILD (default
# build-cov; gcc --coverage, -O1), runs the sanitizer half's tests (every test but those of
# tests/sanitize-except.list, with WHIRL_SANITIZE=1 as there) except the TESTs, collects the
# lines they executed (tests/tools/coverage_lines.py), then runs each TEST alone and prints
# "TEST: N lines, U reached by no other test" and those U lines. docs/performance.md gives its
# results. TESTs as tests/run.sh takes them: build/tests/NAME (BUILD's copy is meant) or
# tests/cli/NAME.sh.
#
#   sh tests/tools/coverage_unique.sh tests/cli/test_simulate.sh build/tests/test_continuum
set -e
cd "$(dirname "$0")/../.."
build=${COVERAGE_BUILD:-build-cov}
out=$build/coverage
mkdir -p "$out"
nice -n 10 make -s --no-print-directory -j"${JOBS:-2}" BUILD="$build" OPT=-O1 \
  XCFLAGS=--coverage XLDFLAGS=--coverage check-programs
mine=$(printf '%s\n' "$@" | sed "s|^build/|$build/|")
except=$( (sed 's/#.*//; s|^build/|'"$build"'/|' tests/sanitize-except.list; echo "$mine") | tr -s ' \n' '\n' | grep .)
zero() { find "$build/src" -name '*.gcda' -delete; }
zero
WHIRL_SANITIZE=1 nice -n 10 sh tests/run.sh "$build" --except $except >"$out/base.log" 2>&1 || true
tail -n 1 "$out/base.log"
/usr/bin/python3 tests/tools/coverage_lines.py "$build" >"$out/base.lines"
echo "the other tests: $(wc -l <"$out/base.lines") lines"
for t in $mine; do
  zero
  WHIRL_SANITIZE=1 nice -n 10 sh tests/run.sh "$build" "$t" >"$out/one.log" 2>&1 || true
  /usr/bin/python3 tests/tools/coverage_lines.py "$build" >"$out/one.lines"
  LC_ALL=C comm -23 "$out/one.lines" "$out/base.lines" >"$out/unique.lines"
  echo "$t: $(wc -l <"$out/one.lines") lines, $(wc -l <"$out/unique.lines") reached by no other test"
  sed 's/^/  /' "$out/unique.lines"
done
