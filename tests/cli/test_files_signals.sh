#!/bin/sh
# Files and signals (docs/guide/files-and-signals.md): every input bounded and read from a regular
# file, every output checked before the work and committed whole, every terminating signal handled
# like Ctrl-C.
. "$(dirname "$0")/lib.sh"
out="$tmp/out.csv"
scenes="$(dirname "$0")/../../data/scenes"

# ---- inputs: regular files only, bounded lines and sizes ----
expect_error "simulate /dev/zero: a device is refused" \
  "/dev/zero: cannot read: a character device, not a regular file" simulate /dev/zero -o "$out"
expect_error "fit --shape /dev/zero: a device is refused" \
  "/dev/zero: cannot read: a character device, not a regular file" fit --shape /dev/zero -o "$out"
expect_error "view /dev/zero: a device is refused" \
  "/dev/zero: cannot read: a character device, not a regular file" view /dev/zero -o "$out"
expect_error "simulate of a directory is refused" "cannot read: a directory" simulate "$tmp" -o "$out"
mkfifo "$tmp/fifo"
expect_error "simulate of a FIFO with no writer: refused at once, not waited on" \
  "fifo: cannot read: a FIFO, not a regular file" simulate "$tmp/fifo" -o "$out"
head -c 17000000 /dev/zero | tr '\0' 'x' >"$tmp/long.ini"
expect_error "scene: a line over 16 MiB is refused as it is read" \
  "long.ini:1: line longer than 16 MiB" simulate "$tmp/long.ini" -o "$out"
{ echo '[chain]'; yes '; a comment line of a scene file that never ends' | head -c 70000000; } \
  >"$tmp/big.ini"
expect_error "scene: more than 64 MiB is refused as it is read" \
  "big.ini:[0-9]+: more than 64 MiB of input" simulate "$tmp/big.ini" -o "$out"
rm -f "$tmp/long.ini" "$tmp/big.ini"
expect_error "fit --shape - from an endless stream of NUL bytes: the line cap ends it" \
  "standard input:1: line longer than 4 KiB" fit --shape - -o "$out" </dev/zero
yes '# c' | "$WHIRL" fit --shape - -o "$out" 2>"$tmp/stderr"
rc=$?
if [ $rc -eq 1 ] && grep -Eq "standard input:[0-9]+: more than 64 MiB of input" "$tmp/stderr" &&
   [ ! -e "$out" ]; then pass "fit --shape - from an endless stream of comments: the size cap ends it"
else fail "fit --shape - from an endless stream of comments (rc=$rc, $(head -c 200 "$tmp/stderr"))"; fi
printf '# trace: t\n0 0 0 0\n0 0 -1e200 0\n' >"$tmp/huge.dat"
expect_error "view: coordinates of 1e200 are refused (the page would draw inf)" \
  "huge.dat:3: a trace line needs four finite numbers .* at most 1e\+100" view "$tmp/huge.dat" -o "$out"

finish
