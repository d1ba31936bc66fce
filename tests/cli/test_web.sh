#!/bin/sh
# The page of make web (build/web/whirl-explore.html: libwhirl compiled to WebAssembly, one
# self-contained file) in headless Chromium, opened from file://: its shape, tip radius, node
# count and verdict against whirl shape and whirl stability of this build (1e-12 relative,
# verdicts identical), the windows, the CSV, PNG and SVG of what is shown, the perturbed run
# against whirl simulate (its speed against real time is printed, not asserted), the hanging
# chain below a mode's birth, the shaken pivot (Kapitza's preset: the 3-link chain held upside
# down over 100 periods, the pivot drawn moving), air drag slowing a free swing, a bad field
# named, the Floquet multipliers of the shaken settings (the largest |mu| shown against whirl
# periodic, Newton's method that does not converge shown in one line, Stop), an unknown address
# parameter named, Cancel (the Worker ended and restarted), no request off the machine, no
# console error
# (tests/tools/web_page.py drives it). The page is built here if it is missing or
# older than its sources (make web); a build that fails fails the test.
. "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "$(dirname "$WHIRL")" && pwd)
page=$build/web/whirl-explore.html

# (WEB, not BUILD: a make with BUILD=$build but without the build's own flags would rewrite
# $build/flags, and the next build of $build, a sanitizer's, would start over)
if make -s -C "$root" WEB="$build/web" web >"$tmp/make.log" 2>&1 && [ -s "$page" ]; then
  pass "make web writes $(basename "$page") ($(wc -c <"$page") bytes)"
else
  fail "make web ($(tail -n 5 "$tmp/make.log"))"
  finish
fi

# one file: no other file, no address outside it (the WebAssembly inside as base64)
if ! grep -Eq '(src|href)="(https?:)?//' "$page" && grep -q 'data:application/octet-stream;base64,' "$page"
then pass "the page is self-contained: no external script or style, the WebAssembly inside"
else fail "the page is self-contained"; fi

/usr/bin/python3 "$root/tests/tools/web_page.py" parity "$page" "$WHIRL" >"$tmp/parity" 2>"$tmp/parity.err"
[ -s "$tmp/parity" ] || fail "the page's driver ran ($(tail -n 5 "$tmp/parity.err"))"
while IFS= read -r line; do
  case $line in
    PASS\ *) pass "${line#PASS }" ;;
    INFO\ *) echo "# ${line#INFO }" ;;
    *) fail "${line#FAIL }" ;;
  esac
done <"$tmp/parity"
finish
