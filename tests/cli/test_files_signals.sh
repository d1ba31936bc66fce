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

# ---- signals: each terminating signal ends a long command like Ctrl-C, with 128 + its number ----
# stop NAME SIGNAL STATUS ARGS...: runs `whirl ARGS -o $tmp/sig/out.csv`, sends SIGNAL after 1 s;
# the command must exit STATUS within 2 s of the signal, keep the output with its rows, leave no
# temporary file and say it was interrupted. Prints the time from the signal to the exit.
stop() {
  name=$1; sig=$2; want=$3; shift 3
  rm -rf "$tmp/sig"; mkdir "$tmp/sig"
  "$WHIRL" "$@" -o "$tmp/sig/out.csv" >/dev/null 2>"$tmp/sig.err" &
  pid=$!
  sleep 1
  t0=$(date +%s.%N)
  kill -"$sig" $pid
  wait $pid
  rc=$?
  late=$(echo "$(date +%s.%N) - $t0" | bc)
  left=$(ls -A "$tmp/sig" | grep -v '^out.csv$')
  kept=$( [ -f "$tmp/sig/out.csv" ] && grep -cv '^#' "$tmp/sig/out.csv" || echo 0)
  if [ $rc -eq "$want" ] && [ -z "$left" ] && [ "$kept" -ge 2 ] && grep -q interrupted "$tmp/sig.err" &&
     [ "$(echo "$late < 2" | bc)" -eq 1 ]; then
    pass "SIG$sig: $name: exit $rc in $late s, $((kept - 1)) rows kept, no temporary file"
  else
    fail "SIG$sig: $name (rc=$rc want $want, $late s, left '$left', $kept lines, $(head -c 200 "$tmp/sig.err"))"
  fi
}
map="stability --omega-min 2 --omega-max 8 --omega-count 1201 --links 8 --periods 20"
# shellcheck disable=SC2086
stop "stability map" HUP 129 $map
# shellcheck disable=SC2086
stop "stability map" QUIT 131 $map
# shellcheck disable=SC2086
stop "stability map" TERM 143 $map
stop "sweep" HUP 129 sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 --omega-count 30001
stop "driven branch" QUIT 131 driven --omega-min 1 --omega-max 4000 --eps 0.05
stop "regime sweep" HUP 129 regime --sweep --omega-min 3 --omega-max 3.5 --omega-count 5000 \
  --eps 0.1 --links 5 --t-max 60

# nohup: SIGHUP ignored stays ignored (the run ends normally)
nohup "$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=2 -o "$tmp/nohup.csv" \
  >"$tmp/nohup.out" 2>&1 &
pid=$!
sleep 0.5
kill -HUP $pid
wait $pid
rc=$?
if [ $rc -eq 0 ] && [ "$(grep -v '^#' "$tmp/nohup.csv" | tail -n 1 | cut -d, -f1)" = 2 ]; then
  pass "nohup: SIGHUP stays ignored, the run completes"
else fail "nohup: SIGHUP stays ignored (rc=$rc, $(head -c 200 "$tmp/nohup.out"))"; fi

# SIGPIPE: a reader that goes away ends the run with a write error (141), not a kill
( "$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=1e4 2>"$tmp/pipe.err"; echo $? >"$tmp/pipe.rc" ) |
  head -n 1 >/dev/null
rc=$(cat "$tmp/pipe.rc")
if [ "$rc" -eq 141 ] && grep -q 'cannot write standard output: Broken pipe' "$tmp/pipe.err"; then
  pass "SIGPIPE: | head -1 ends the run with a write error, exit 141"
else fail "SIGPIPE: | head -1 (rc=$rc, $(head -c 200 "$tmp/pipe.err"))"; fi

# SIGXFSZ: a file-size limit is a write error (153), and no temporary file is left
mkdir "$tmp/fsz"
( ulimit -f 64; exec "$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=1e4 -o "$tmp/fsz/out.csv" ) \
  2>"$tmp/fsz.err"
rc=$?
if [ $rc -eq 153 ] && [ -z "$(ls -A "$tmp/fsz")" ] && grep -q 'File too large' "$tmp/fsz.err"; then
  pass "SIGXFSZ: a file-size limit is a write error, exit 153, no file left"
else fail "SIGXFSZ: file-size limit (rc=$rc, left '$(ls -A "$tmp/fsz")', $(head -c 200 "$tmp/fsz.err"))"; fi

finish
