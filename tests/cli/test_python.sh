#!/bin/sh
# The Python package (python/) over build/libwhirl.so: its pytest suite, notebooks included, and
# mypy over its type hints, as TAP (one line per test, then the plan). In the sanitizer half the library is the ASan/UBSan
# build, and the interpreter gets the sanitizer runtimes preloaded (ASan must come first in the
# process); leak detection is off there (the interpreter itself keeps memory to its exit: the
# pytest suite measures growth over 10^4 calls instead) and so is ASan's quarantine of freed
# memory, which would otherwise count as growth. With WHIRL_SANITIZE or WHIRL_QUICK set the tests
# marked slow are left out (they run in the plain half of make check), with WHIRL_SANITIZE those
# of python/tests/sanitize-except.txt as well.
build=$(cd "$(dirname "${WHIRL:-build/whirl}")" && pwd)
preload=
if [ -n "$WHIRL_SANITIZE" ]; then
  for rt in libasan.so libubsan.so; do
    path=$(${CC:-cc} -print-file-name=$rt)
    if [ ! -f "$path" ]; then
      echo "not ok - python: the sanitizer runtime $rt is not found (${CC:-cc} -print-file-name)"
      echo "1..1"
      exit 1
    fi
    preload="$preload $path"
  done
  export ASAN_OPTIONS="detect_leaks=0:quarantine_size_mb=0:thread_local_quarantine_size_kb=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
fi
log=$(mktemp)
results=$(mktemp)
trap 'rm -f "$log" "$results"' EXIT
if [ ! -f "$build/libwhirl.so" ]; then
  echo "not ok - python: $build/libwhirl.so is not built" >"$results"
  rc=1
else
  # the tests marked slow (python/tests/conftest.py) run once, in the plain half, and so do those
  # marked plain_only (python/tests/sanitize-except.txt)
  if [ -n "$WHIRL_SANITIZE" ]; then set -- -m "not slow and not plain_only"
  elif [ -n "$WHIRL_QUICK" ]; then set -- -m "not slow"
  else set --; fi
  LD_PRELOAD="${preload# }" WHIRL_BUILD=$build WHIRL_LIBRARY=$build/libwhirl.so WHIRL_TAP=1 \
    /usr/bin/python3 -m pytest -q -p no:cacheprovider --durations=8 "$@" python/tests >"$log" 2>&1
  rc=$?
  grep -E '^(ok|not ok) ' "$log" >"$results"
  if [ $rc -ne 0 ]; then
    tail -n 40 "$log"
    echo "not ok - python: pytest exited with status $rc" >>"$results"
  else
    # the slowest tests, then pytest's closing line
    sed -n '/slowest 8 durations/,/^$/p' "$log" | grep -E '^[0-9.]+s ' | sed 's/^/# /'
    tail -n 1 "$log" | sed 's/^/# /'
  fi
fi
# the type hints (python/pyproject.toml's [tool.mypy]); once, in the plain half
if [ -z "$WHIRL_SANITIZE" ]; then
  if out=$(cd python && /usr/bin/python3 -m mypy whirl 2>&1); then
    echo "ok - python: mypy: $(echo "$out" | tail -n 1)" >>"$results"
  else
    echo "$out" | tail -n 20
    echo "not ok - python: mypy found type errors" >>"$results"
    rc=1
  fi
fi
cat "$results"
echo "1..$(wc -l <"$results" | tr -d ' ')"
exit $rc
