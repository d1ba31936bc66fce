#!/bin/sh
# The Python package (python/) over build/libwhirl.so: its pytest suite, notebooks included, as
# TAP (one line per test, then the plan). The plain half only: a sanitizer-built library cannot be
# loaded into python3 without preloading the sanitizer runtime into the interpreter.
build=$(cd "$(dirname "${WHIRL:-build/whirl}")" && pwd)
if [ -n "$WHIRL_SANITIZE" ]; then
  echo "# python: run by the plain half of make check"
  echo "1..0"
  exit 0
fi
log=$(mktemp)
results=$(mktemp)
trap 'rm -f "$log" "$results"' EXIT
if [ ! -f "$build/libwhirl.so" ]; then
  echo "not ok - python: $build/libwhirl.so is not built" >"$results"
  rc=1
else
  WHIRL_BUILD=$build WHIRL_LIBRARY=$build/libwhirl.so WHIRL_TAP=1 \
    /usr/bin/python3 -m pytest -q -p no:cacheprovider python/tests >"$log" 2>&1
  rc=$?
  grep -E '^(ok|not ok) ' "$log" >"$results"
  if [ $rc -ne 0 ]; then
    tail -n 40 "$log"
    echo "not ok - python: pytest exited with status $rc" >>"$results"
  else
    tail -n 1 "$log" | sed 's/^/# /'
  fi
fi
cat "$results"
echo "1..$(wc -l <"$results" | tr -d ' ')"
exit $rc
