#!/bin/sh
# The manual: it builds with Sphinx with warnings as errors, its C API reference covers every
# symbol libwhirl.so exports, and every block marked <!-- runnable --> in README.md and docs/ runs
# as written, with the output the page shows (tests/tools/docs_test.py says how).
# The manual documents the plain build, so the sanitizer half of make check leaves this test out;
# run by hand with WHIRL_SANITIZE set it tests build/ too, as a program or a Python interpreter
# linked with build-sanitize's library would need the sanitizer runtimes first.
build=$(dirname "${WHIRL:-build/whirl}")
[ -n "$WHIRL_SANITIZE" ] && build=build
cd "$(dirname "$0")/../.." || exit 1
if ! /usr/bin/python3 -c 'import sphinx, myst_parser' 2>/dev/null; then
  echo "not ok 1 - the manual needs the Debian packages python3-sphinx python3-myst-parser (make deps)"
  echo "1..1"
  exit 1
fi
exec /usr/bin/python3 tests/tools/docs_test.py "$build"
