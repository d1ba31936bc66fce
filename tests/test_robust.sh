#!/bin/sh
# Robustness of the whirl program: inputs that once ran away, overflowed, were misread or left
# files behind now end in one-line errors naming the problem, with nothing written.
. "$(dirname "$0")/lib.sh"
out="$tmp/out.csv"

# ---- numbers that would not be finite ----
expect_error "sweep: a tip mass of 1e308 is refused" "tip mass 1e\+308 exceeds 1e\+12 chain masses" \
  sweep --modes 1 --omega-min 2 --omega-max 3 --omega-count 3 --tip-mass 1e308 -o "$out"
expect_error "shape --links: a tip mass of 1e308 is refused" "tip mass 1e\+308 exceeds" \
  shape --omega 2 --mode 1 --links 4 --tip-mass 1e308 -o "$out"
expect_error "critical: a rate unit sqrt(g/L) that overflows is refused" \
  "--length must be between 1e-30 and 1e\+30, got 1e-300" \
  critical --length 1e-300 --gravity 1e300 -o "$out"
expect_error "critical: --mass 1e308 is refused" "--mass must be between 1e-30 and 1e\+30, got 1e\+308" \
  critical --mass 1e308 -o "$out"
expect_error "shape: --mass 1e308 is refused" "--mass must be between" \
  shape --omega 2 --mode 1 --mass 1e308 -o "$out"
expect_error "shape --links: a rate whose tensions overflow fails cleanly" "^whirl shape: " \
  shape --omega 1e160 --mode 1 --links 3 -o "$out"
expect_error "stability: a damping of 1e308 is caught before LAPACK" \
  "the linearised matrix is not finite .*the damping 1e\+308" \
  stability --omega 2 --mode 1 --links 5 --damping 1e308 -o "$out"

# ---- input read as written ----
printf '[chain]\ndim = 2\nlinks = 2\n[run]method = nosuchmethod\nt_end = 1\ndt = 0.1\n[start]\nhanging = 1\n' \
  >"$tmp/after_header.ini"
expect_error "scene: text after a section header is an error with file:line" \
  "after_header.ini:4: text after the section header: 'method = nosuchmethod'" \
  simulate "$tmp/after_header.ini" -o "$out"
printf '[chain] ; the chain\ndim = 2\nlinks = 2\n[run]  # the run\nt_end = 0.2\ndt = 0.1\n[start]\nhanging = 1\n' \
  >"$tmp/header_comment.ini"
expect_ok "scene: a comment after a section header is allowed" simulate "$tmp/header_comment.ini" -o "$out"
printf '[chain]\ndim = 2\0\nlinks = 2\n' >"$tmp/nul.ini"
expect_error "scene: a NUL byte is reported as such" "nul.ini:2: NUL byte at column 8" \
  simulate "$tmp/nul.ini" -o "$out"
printf 'r,z\n0.3,-0.5\n0.3\0,-0.6\n' >"$tmp/nul.csv"
expect_error "fit: a NUL byte is reported as such" "nul.csv:3: NUL byte at column 4" \
  fit --shape "$tmp/nul.csv" -o "$out"
printf 'r,z\n0.3,-0.5\n0.3,-0.5\n0.3,-0.5\n' >"$tmp/same.csv"
expect_error "fit: three identical points are refused" \
  "at least 3 distinct points off the axis .*got 1 of 3" fit --shape "$tmp/same.csv" -o "$out"
printf 'r,z\n0,-0.2\n0,-0.4\n0,-0.6\n0,-0.8\n' >"$tmp/axis.csv"
expect_error "fit: points all on the axis are refused" \
  "at least 3 distinct points off the axis .*got 0 of 4" fit --shape "$tmp/axis.csv" -o "$out"
expect_error "fit: an empty file name is refused" "--shape: empty file name" fit --shape '' -o "$out"

# ---- empty paths refused before any work, nothing left behind ----
here=$(pwd)
WHIRL=$(cd "$(dirname "$WHIRL")" && pwd)/$(basename "$WHIRL")
cd "$tmp" || exit 1
expect_error "stability: --trace '' is refused and leaves no file" "empty output file name" \
  stability --omega 2 --mode 1 --links 4 --periods 1 --trace '' -o "$out"
cd "$here" || exit 1
if [ -z "$(ls -A "$tmp" | grep -v -e '\.ini$' -e '\.csv$' -e '^stdout$' -e '^stderr$')" ]; then
  pass "no temporary file left by the refused runs"
else fail "no temporary file left by the refused runs: $(ls -A "$tmp")"; fi
expect_error "shape: -o '' is refused" "empty output file name" shape --omega 2 --mode 1 -o ''

finish
