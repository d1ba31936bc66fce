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

# ---- out of memory while reading: reported as such, never as the end of the file ----
# Under a limit on the address space (ulimit -v) a little above what a short input needs, a long
# one runs out of memory while it is read: its line (the scene's reader) or its points (fit,
# view) need 8 MiB and more beyond the limit. The limit is found by bisection on the short input
# (the program, its libraries and a short read), to 1 MiB. Not under the sanitizers, whose
# shadow memory needs terabytes of address space.
# least_vm PATTERN ARGS...: the least limit in KiB at which `whirl ARGS` prints PATTERN (0: none
# up to 4 GiB)
least_vm() {
  pat=$1; shift
  lo=1024 hi=4194304
  if ! (ulimit -v $hi; exec "$WHIRL" "$@") 2>&1 | grep -Eq "$pat"; then echo 0; return; fi
  while [ $((hi - lo)) -gt 1024 ]; do
    mid=$(((lo + hi) / 2))
    if (ulimit -v $mid; exec "$WHIRL" "$@") 2>&1 | grep -Eq "$pat"; then hi=$mid; else lo=$mid; fi
  done
  echo $hi
}
# out_of_memory NAME SHORT_PATTERN SHORT_FILE LONG_FILE PATTERN CMD...: CMD on SHORT_FILE gives
# SHORT_PATTERN under its least limit; on LONG_FILE under that limit plus 4 MiB, one line that
# matches PATTERN, exit 1, no output
out_of_memory() {
  name=$1; short_pat=$2; short=$3; long=$4; pat=$5; shift 5
  vm=$(least_vm "$short_pat" "$@" "$short")
  rm -f "$out"
  (ulimit -v $((vm + 4096)); exec "$WHIRL" "$@" "$long") >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  if [ "$vm" -gt 0 ] && [ $rc -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] &&
     grep -Eq "$pat" "$tmp/stderr" && [ ! -e "$out" ] && [ ! -s "$tmp/stdout" ]; then
    pass "$name: out of memory under ulimit -v $((vm + 4096)) KiB, said as such"
  else fail "$name: out of memory (least limit $vm KiB, rc=$rc, $(head -c 300 "$tmp/stderr"))"; fi
}
if [ -z "$WHIRL_SANITIZE" ]; then
  printf '; a scene with nothing in it\n' >"$tmp/short.ini"
  { printf '; '; head -c 12000000 /dev/zero | tr '\0' x; printf '\n[chain]\n'; } >"$tmp/longline.ini"
  out_of_memory "scene: a line of 12 MB" '\[chain\] dim: missing' "$tmp/short.ini" "$tmp/longline.ini" \
    'longline.ini:1: out of memory reading a line of [0-9]+ MiB$' simulate -o "$out"
  printf 'r,z\n0.1,-0.5\n' >"$tmp/short.csv"
  awk 'BEGIN {print "r,z"; for (i = 0; i < 1500000; i++) print "0.1,-0.5"}' >"$tmp/long.csv"
  out_of_memory "fit --shape: 1.5e6 points" 'has 1 points' "$tmp/short.csv" "$tmp/long.csv" \
    'long.csv:[0-9]+: out of memory for the points \([0-9]+ read\)$' fit -o "$out" --shape
  out_of_memory "view: 1.5e6 points" 'no chain in it' "$tmp/short.csv" "$tmp/long.csv" \
    'long.csv:[0-9]+: out of memory for the points \([0-9]+ read\)$' view -o "$out"
  rm -f "$tmp/longline.ini" "$tmp/long.csv"
fi

# ---- outputs that cannot destroy ----
"$WHIRL" shape --omega 3.3 --mode 2 --points 50 -o "$tmp/d.csv"
cp "$tmp/d.csv" "$tmp/d.keep"
expect_error "sweep -o x --events x: two outputs on one file" \
  "--events '.*x.csv' and --output '.*x.csv' are the same file" \
  sweep --modes 1 --links 5 --omega-min 2 --omega-max 3 --omega-count 3 -o "$tmp/x.csv" \
  --events "$tmp/x.csv"
expect_error "stability -o y --trace ./y: the same file by another name" "are the same file" \
  stability --omega 2 --mode 1 --links 5 -o "$tmp/y.csv" --trace "$tmp/./y.csv"
expect_error "fit --shape d.csv -o d.csv: the output is the input" \
  "--output '.*d.csv' is the input --shape '.*d.csv': it would be replaced" \
  fit --shape "$tmp/d.csv" -o "$tmp/d.csv"
cmp -s "$tmp/d.csv" "$tmp/d.keep" && pass "fit: the measured data are untouched" ||
  fail "fit: the measured data were changed"
cp "$scenes/mode2.ini" "$tmp/s.ini"
expect_error "simulate s.ini -o s.ini: the scene is not replaced" "s.ini' is the input file '.*s.ini'" \
  simulate "$tmp/s.ini" -o "$tmp/s.ini"
expect_error "-o a -o b: an option given twice" "option --output given twice" \
  shape --omega 2 --mode 1 -o "$tmp/a.csv" -o "$out"
cp "$tmp/d.keep" "$tmp/ro.csv"; chmod 444 "$tmp/ro.csv"
expect_error "-o on a read-only file is refused" "'.*ro.csv': the file is read-only" \
  shape --omega 2 --mode 1 -o "$tmp/ro.csv"
cmp -s "$tmp/ro.csv" "$tmp/d.keep" && pass "read-only file untouched" || fail "read-only file replaced"
expect_error "-o in a folder that does not exist: refused before the work" \
  "cannot write in '.*nodir'" fit --shape "$tmp/d.csv" -o "$tmp/nodir/fit.csv"
ln -s nowhere.csv "$tmp/dangling.csv"
expect_error "-o on a dangling symlink is refused" "a symbolic link to nothing" \
  shape --omega 2 --mode 1 -o "$tmp/dangling.csv"
cp "$tmp/d.keep" "$tmp/target.csv"; chmod 640 "$tmp/target.csv"; ln -s target.csv "$tmp/link.csv"
"$WHIRL" shape --omega 2 --mode 1 -o "$tmp/link.csv" 2>"$tmp/stderr"
if [ -L "$tmp/link.csv" ] && [ "$(stat -c %a "$tmp/target.csv")" = 640 ] &&
   grep -q 'omega=2' "$tmp/target.csv" && [ -z "$(ls "$tmp" | grep '\.tmp\.')" ]; then
  pass "-o through a symlink: the link kept, the target written with its mode 640"
else fail "-o through a symlink ($(ls -l "$tmp/link.csv" "$tmp/target.csv"), $(cat "$tmp/stderr"))"; fi
# ... and the target's owner: a file of another user (uid and gid 65534, nobody), which only root
# can make and write, keeps them
if [ "$(id -u)" -eq 0 ]; then
  cp "$tmp/d.keep" "$tmp/theirs.csv"; chown 65534:65534 "$tmp/theirs.csv"; chmod 604 "$tmp/theirs.csv"
  ln -s theirs.csv "$tmp/their_link.csv"
  "$WHIRL" shape --omega 2 --mode 1 -o "$tmp/their_link.csv" 2>"$tmp/stderr"
  if [ -L "$tmp/their_link.csv" ] && [ "$(stat -c '%u:%g %a' "$tmp/theirs.csv")" = "65534:65534 604" ] &&
     grep -q 'omega=2' "$tmp/theirs.csv" && [ -z "$(ls "$tmp" | grep '\.tmp\.')" ]; then
    pass "-o through a symlink as root: the target keeps its owner 65534:65534 and mode 604"
  else fail "-o through a symlink as root ($(stat -c '%u:%g %a' "$tmp/theirs.csv"), $(cat "$tmp/stderr"))"; fi
else
  pass "-o through a symlink keeps the target's owner # skip not root: only root can write another user's file"
fi
# a second output that fails: neither is written, the message names it
rm -f "$out"
"$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=0.5 --set output.trace=/dev/full -o "$out" \
  2>"$tmp/stderr"
rc=$?
if [ $rc -ne 0 ] && [ ! -e "$out" ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] &&
   grep -q "cannot write /dev/full: No space left on device (no file written)" "$tmp/stderr" &&
   [ -z "$(ls "$tmp" | grep '^out.csv.tmp')" ]; then
  pass "--trace /dev/full: neither output written, the failing one named"
else fail "--trace /dev/full (rc=$rc, $(ls "$tmp" | grep out.csv), $(head -c 300 "$tmp/stderr"))"; fi
mkfifo "$tmp/wfifo"
expect_error "-o on a FIFO with no reader: refused at once" "wfifo': a FIFO with no reader" \
  shape --omega 2 --mode 1 -o "$tmp/wfifo"

# ---- maps: one run at a time, rows checked on --resume ----
fast="--links 8 --drag 0.25 --t-max 150 --t-ramp 10"
big="--omega-min 1 --omega-max 4 --omega-count 40 --eps 0.05 $fast"
# shellcheck disable=SC2086
"$WHIRL" regime $big -o "$tmp/map.csv" 2>/dev/null &
pid=$!
i=0
while [ "$(cat "$tmp/map.csv" 2>/dev/null | grep -c '^[0-9]')" -lt 1 ] && [ $i -lt 200 ]; do
  sleep 0.05; i=$((i + 1))
done
# shellcheck disable=SC2086
expect_error "regime --resume on a map another run writes: refused (locked)" \
  "map.csv' is being written by another run \(locked\)" regime $big -o "$tmp/map.csv" --resume
kill -INT $pid
wait $pid
rc=$?
[ $rc -eq 130 ] && pass "the first run kept the map (exit 130)" || fail "the first run (rc=$rc)"
for bad in nan inf 1e999 cut; do
  sh "$(dirname "$0")/../tools/bad_row.sh" "$tmp/map.csv" "$tmp/bad.csv" $bad
  # shellcheck disable=SC2086
  expect_error "regime --resume: a row with $bad is refused, not kept" \
    "bad.csv:[0-9]+: .*the file cannot be trusted" regime $big -o "$tmp/bad.csv" --resume
done

# a stability map being resumed is locked too (2 s into each run: its linearisation of the 1201
# rates comes first, a second and more on a loaded machine, before any row)
smap="stability --omega-min 2 --omega-max 8 --omega-count 1201 --links 8 --periods 20"
# shellcheck disable=SC2086
"$WHIRL" $smap -o "$tmp/smap.csv" 2>/dev/null &
pid=$!
sleep 2; kill -INT $pid; wait $pid
# shellcheck disable=SC2086
"$WHIRL" $smap -o "$tmp/smap.csv" --resume 2>/dev/null &
pid=$!
sleep 2
# shellcheck disable=SC2086
expect_error "stability --resume on a map another run writes: refused (locked)" \
  "smap.csv' is being written by another run \(locked\)" $smap -o "$tmp/smap.csv" --resume
kill -INT $pid; wait $pid
rc=$?
[ $rc -eq 130 ] && [ "$(grep -c '^[0-9]' "$tmp/smap.csv")" -gt 1 ] &&
  pass "the first stability run kept its map (exit 130)" || fail "the first stability run (rc=$rc)"

# two runs started together on a map file that does not exist yet: the one that makes it holds
# the lock, the other is refused at once with one line; the file holds every row of the first
# (the two ask for different rows, so that the file tells which one wrote it)
# together NAME ROWS_A ARGS_A ROWS_B ARGS_B: ROWS_X, the data rows run X writes. The refusal says
# the file is locked or, when the first run ended between the other's open and its lock, that
# the file it opened was replaced.
together() {
  name=$1; rows_a=$2; args_a=$3; rows_b=$4; args_b=$5
  rm -rf "$tmp/tog"; mkdir "$tmp/tog"
  # shellcheck disable=SC2086
  "$WHIRL" $args_a -o "$tmp/tog/map.csv" >/dev/null 2>"$tmp/tog_a.err" &
  pa=$!
  # shellcheck disable=SC2086
  "$WHIRL" $args_b -o "$tmp/tog/map.csv" >/dev/null 2>"$tmp/tog_b.err" &
  pb=$!
  wait $pa; ra=$?; wait $pb; rb=$?
  want=-1 loser=/dev/null
  if [ $ra -eq 0 ] && [ $rb -eq 1 ]; then want=$rows_a loser=$tmp/tog_b.err
  elif [ $rb -eq 0 ] && [ $ra -eq 1 ]; then want=$rows_b loser=$tmp/tog_a.err; fi
  rows=$(grep -v '^#' "$tmp/tog/map.csv" 2>/dev/null | tail -n +2 | wc -l)
  if [ "$want" -ge 0 ] && [ "$rows" -eq "$want" ] && [ "$(wc -l <"$loser")" -eq 1 ] &&
     grep -Eq "map.csv' (is being written by another run \(locked\)|was replaced by another run while this one started)" "$loser" &&
     [ "$(ls -A "$tmp/tog")" = map.csv ]; then
    pass "$name: one run writes the new file ($rows rows), the other is refused"
  else fail "$name: two runs on a new file (rc $ra and $rb, $rows rows, $(ls -A "$tmp/tog"), $(cat "$tmp/tog_a.err" "$tmp/tog_b.err" | head -c 300))"; fi
}
rsw="regime --sweep --omega-min 3 --omega-max 3.5 --eps 0.1 --links 5 --t-max 60"
together "regime --sweep" 79 "$rsw --omega-count 40" 81 "$rsw --omega-count 41"
rmap="regime --omega-max 4 --omega-count 40 --eps 0.05 $fast"
together "regime map" 40 "$rmap --omega-min 1" 40 "$rmap --omega-min 1.5"
smap2="stability --omega-max 8 --links 8 --periods 20 --omega-count 101"
# the map's rows: the modes present at each of the 101 rates, counted from a run alone
# shellcheck disable=SC2086
"$WHIRL" $smap2 --omega-min 2 -o "$tmp/s2a.csv" && "$WHIRL" $smap2 --omega-min 2.5 -o "$tmp/s2b.csv"
together "stability map" "$(grep -v '^#' "$tmp/s2a.csv" | tail -n +2 | wc -l)" "$smap2 --omega-min 2" \
  "$(grep -v '^#' "$tmp/s2b.csv" | tail -n +2 | wc -l)" "$smap2 --omega-min 2.5"
# a run that fails after making the file removes it (no empty map left)
expect_error "stability map: a run that fails leaves no empty file it made" "beyond the stability interval" \
  stability --omega-min 3.9 --omega-max 4 --omega-count 2 --links 60 --dt 0.05 -o "$tmp/out.csv"

# ---- a scene cannot write outside its folder ----
mkdir "$tmp/scn" "$tmp/elsewhere"
for t in ../victim.txt /tmp/victim.txt sub/../../victim.txt; do
  sed "s|^\[output\]|[output]\ntrace = $t|" "$scenes/mode2.ini" >"$tmp/scn/bad.ini"
  grep -q "^trace = " "$tmp/scn/bad.ini" || printf '[output]\ntrace = %s\n' "$t" >>"$tmp/scn/bad.ini"
  expect_error "scene: trace = $t is refused" "\[output\] trace: must" \
    simulate "$tmp/scn/bad.ini" --set run.t_end=0.1 -o "$out"
done
sed "s|^\[output\]|[output]\ntrace = run.dat|" "$scenes/mode2.ini" >"$tmp/scn/ok.ini"
grep -q "^trace = " "$tmp/scn/ok.ini" || printf '[output]\ntrace = run.dat\n' >>"$tmp/scn/ok.ini"
whirl_abs=$(cd "$(dirname "$WHIRL")" && pwd)/$(basename "$WHIRL")
(cd "$tmp/elsewhere" && "$whirl_abs" simulate ../scn/ok.ini --set run.t_end=0.1 -o out.csv 2>"$tmp/stderr")
if [ -s "$tmp/scn/run.dat" ] && [ ! -e "$tmp/elsewhere/run.dat" ]; then
  pass "scene: trace = run.dat is written beside the scene, not in the working directory"
else fail "scene: trace beside the scene ($(cat "$tmp/stderr"))"; fi
expect_error "scene: an existing trace is not replaced" "run.dat' exists: a scene file replaces no file" \
  simulate "$tmp/scn/ok.ini" --set run.t_end=0.1 -o "$out"
expect_ok "scene: --overwrite lets it replace the trace" \
  simulate "$tmp/scn/ok.ini" --set run.t_end=0.1 --overwrite -o "$out"

# ---- messages: control characters escaped ----
"$WHIRL" simulate "$scenes/mode2.ini" --set "run.method=$(printf 'x\033]0;owned\007\nsecond')" \
  -o "$out" 2>"$tmp/stderr"
if [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && ! grep -q "$(printf '\033')" "$tmp/stderr" &&
   grep -q 'x\\x1b]0;owned\\x07\\nsecond' "$tmp/stderr"; then
  pass "a value with an escape sequence and a newline is echoed escaped, on one line"
else fail "control characters in messages: $(od -c "$tmp/stderr" | head -5)"; fi

# ---- work bounds that count what forces work ----
regress="$(dirname "$0")/../fuzz/regress/scene"
expect_error "scene: every = 1e-9 (1e9 rows) is refused with the rows and their size" \
  "\[output\] every: t_end / every = 1e\+09 rows exceeds the bound of 1e\+07 rows \(they would take about 149 GiB\)" \
  simulate "$regress/every_tiny.ini" -o "$out"
expect_error "scene: every = 1e-300 is refused before any count is made an integer" \
  "t_end / every = 1e\+300 rows exceeds the bound" simulate "$regress/every_overflow.ini" -o "$out"
expect_error "scene: omega x t_end counts in the work budget" \
  "links x \(steps \+ rows \+ frames \+ \|omega\| t_end\) = 2e\+13 link-steps exceeds the budget of 1e\+10" \
  simulate "$regress/omega_t_end.ini" -o "$out"
expect_error "scene: trace points are bounded" "trace points exceeds the bound of 1e\+08" \
  simulate "$scenes/mode2.ini" --set output.trace="$tmp/t.dat" --set output.trace_every=1e-6 -o "$out"

expect_error "stability --dt beyond rk4's stability interval: an integration failure, not 'unstable'" \
  "the run with --dt 0.05 grew at [0-9.]+ while the linearisation gives 0 at omega 4: the step is beyond the stability interval of rk4" \
  stability --omega 4 --mode 2 --links 60 --dt 0.05 -o "$out"
expect_error "stability --dt beyond gauss2's reach: the failure names the step given" \
  "the run with --dt 0.05 failed \(steps of at most --dt .*\): the Gauss stage iteration diverges.*give a smaller --dt" \
  stability --omega 4 --mode 2 --links 60 --method gauss2 --dt 0.05 -o "$out"

# ---- long phases poll the stop request ----
# Promptness is measured in processor time, which load does not stretch (signal_run, lib.sh):
# the signal comes once the command has used a given processor time, and the work it does after
# the signal (its processor time from then to its exit) must be under a second; the wall time is
# printed, and bounded only against a hang (120 s, then SIGKILL).
# prompt NAME ARGS...: SIGINT 2 s of processor time into a long phase ends it with under a second
# of processor time more (about 0.1-0.3 s), exit 130, no file
prompt() {
  name=$1; shift
  rm -rf "$tmp/prompt"; mkdir "$tmp/prompt"
  signal_run INT 2 "$WHIRL" "$@" -o "$tmp/prompt/out.csv" >/dev/null 2>"$tmp/prompt.err"
  rc=$?
  late="$(report cpu_after) s of processor time ($(report wall) s wall)"
  if [ $rc -eq 130 ] && [ "$(report early)" = 0 ] && [ -z "$(ls -A "$tmp/prompt")" ] &&
     [ "$(echo "$(report cpu_after) < 1" | bc)" -eq 1 ]; then
    pass "SIGINT in $name: exit 130 after $late, nothing written"
  else fail "SIGINT in $name (rc=$rc, $late, $(ls -A "$tmp/prompt"), $(head -c 200 "$tmp/prompt.err"))"; fi
}
prompt "the eigenvalues of 60000 links (348 s in one call before)" critical --links 60000 --modes 60000
prompt "the sampling and writing of 10^7 points" shape --omega 3.3 --mode 2 --points 10000000
# --t-max 1e300: the progress line's total once cast 1e300 to a long (UBSan float-cast-overflow in
# the sanitizer half of make check)
prompt "regime --t-max 1e300" regime --omega 3 --eps 0.1 --links 4 --t-max 1e300

# ---- signals: each terminating signal ends a long command like Ctrl-C, with 128 + its number ----
# stop NAME SIGNAL STATUS ARGS...: runs `whirl ARGS -o $tmp/sig/out.csv`, sends SIGNAL once it
# has used 1 s of processor time ($stop_after s if set; the signal's default disposition for whirl
# even if this suite runs with it ignored: nohup ignores SIGHUP, and whirl rightly keeps an
# ignored SIGHUP ignored: tested below); the command must exit STATUS with under a second of
# processor time after the signal, keep the output with its rows, leave no temporary file and say
# it was interrupted.
stop() {
  name=$1; sig=$2; want=$3; shift 3
  rm -rf "$tmp/sig"; mkdir "$tmp/sig"
  signal_run "$sig" "${stop_after:-1}" "$WHIRL" "$@" -o "$tmp/sig/out.csv" >/dev/null 2>"$tmp/sig.err"
  rc=$?
  late="$(report cpu_after) s of processor time ($(report wall) s wall)"
  left=$(ls -A "$tmp/sig" | grep -v '^out.csv$')
  kept=$( [ -f "$tmp/sig/out.csv" ] && grep -cv '^#' "$tmp/sig/out.csv" || echo 0)
  if [ $rc -eq "$want" ] && [ "$(report early)" = 0 ] && [ -z "$left" ] && [ "$kept" -ge 2 ] &&
     grep -q interrupted "$tmp/sig.err" && [ "$(echo "$(report cpu_after) < 1" | bc)" -eq 1 ]; then
    pass "SIG$sig: $name: exit $rc after $late, $((kept - 1)) rows kept, no temporary file"
  else
    fail "SIG$sig: $name (rc=$rc want $want, $late, left '$left', $kept lines, $(head -c 200 "$tmp/sig.err"))"
  fi
}
# 301 rates: the map linearises every rate first (0.2 s of processor time, no row before it
# ends), then runs each for 80 periods, so the signal 2 s of processor time in finds rows
map="stability --omega-min 2 --omega-max 8 --omega-count 301 --links 8 --periods 80"
stop_after=2
# shellcheck disable=SC2086
stop "stability map" HUP 129 $map
# shellcheck disable=SC2086
stop "stability map" QUIT 131 $map
# shellcheck disable=SC2086
stop "stability map" TERM 143 $map
stop_after=
stop "sweep" HUP 129 sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 --omega-count 30001
stop "driven branch" QUIT 131 driven --omega-min 1 --omega-max 4000 --eps 0.05
stop "regime sweep" HUP 129 regime --sweep --omega-min 3 --omega-max 3.5 --omega-count 5000 \
  --eps 0.1 --links 5 --t-max 60

# the fuzz timeout at omega 4.6e6 (tests/fuzz/regress/scene): within the work budget, hours of
# adaptive steps of order 1/omega, stopped at once with its rows
stop "simulate at omega 4.6e6 in the rotating frame" INT 130 simulate "$regress/omega_4.6e6_rk8pd.ini"

# nohup: SIGHUP ignored stays ignored (the run ends normally). The run takes about 1 s idle (5 s
# of simulated time per 0.25 s); the signal comes at 0.3 s, when it is still running.
nohup "$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=20 -o "$tmp/nohup.csv" \
  >"$tmp/nohup.out" 2>&1 &
pid=$!
sleep 0.3
kill -HUP $pid || fail "nohup: the run ended before the signal"
wait $pid
rc=$?
if [ $rc -eq 0 ] && [ "$(grep -v '^#' "$tmp/nohup.csv" | tail -n 1 | cut -d, -f1)" = 20 ]; then
  pass "nohup: SIGHUP stays ignored, the run completes"
else fail "nohup: SIGHUP stays ignored (rc=$rc, $(head -c 200 "$tmp/nohup.out"))"; fi

# SIGPIPE: a reader that goes away ends the run (141, as a process killed by it), without a word
# (as coreutils: the reader chose to stop reading)
( "$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=1e4 2>"$tmp/pipe.err"; echo $? >"$tmp/pipe.rc" ) |
  head -n 1 >/dev/null
rc=$(cat "$tmp/pipe.rc")
if [ "$rc" -eq 141 ] && [ ! -s "$tmp/pipe.err" ]; then
  pass "SIGPIPE: | head -1 ends the run silently, exit 141"
else fail "SIGPIPE: | head -1 (rc=$rc, $(head -c 200 "$tmp/pipe.err"))"; fi

# SIGXFSZ: a file-size limit is a write error (153), and no temporary file is left
mkdir "$tmp/fsz"
( ulimit -f 64; exec "$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=1e4 -o "$tmp/fsz/out.csv" ) \
  2>"$tmp/fsz.err"
rc=$?
if [ $rc -eq 153 ] && [ -z "$(ls -A "$tmp/fsz")" ] && grep -q 'File too large' "$tmp/fsz.err"; then
  pass "SIGXFSZ: a file-size limit is a write error, exit 153, no file left"
else fail "SIGXFSZ: file-size limit (rc=$rc, left '$(ls -A "$tmp/fsz")', $(head -c 200 "$tmp/fsz.err"))"; fi

# SIGINT into the dense O(N^3) phases of a large chain (LAPACK's Cholesky, LU, dsyev and dgeev
# cannot read the stop request: they run on a worker thread while the command polls it): the
# window search with --full (the reduced matrix, then dgeev of 2000 rows) and --eigenvalues (the
# index's dsyev, then dgeev of 4000 rows), each minutes long at 1000 links, end with under a
# second of processor time after the signal (2 s of processor time in).
for dense in "--windows --links 1000 --modes 2 --omega-min 3 --omega-max 4 --full" \
             "--omega 4 --mode 2 --links 1000 --eigenvalues"; do
  mkdir -p "$tmp/dense"
  # shellcheck disable=SC2086 # the options are words
  signal_run INT 2 "$WHIRL" stability $dense -o "$tmp/dense/out.csv" 2>"$tmp/dense.err"
  rc=$?
  late="$(report cpu_after) s of processor time ($(report wall) s wall)"
  if [ "$rc" -eq 130 ] && [ "$(report early)" = 0 ] && [ "$(echo "$(report cpu_after) < 1" | bc)" -eq 1 ] &&
     [ -z "$(ls -A "$tmp/dense")" ] && grep -q 'stopped by request\|interrupted' "$tmp/dense.err"; then
    pass "stability $dense: SIGINT in the dense phase exits 130 after $late"
  else fail "stability $dense: SIGINT (rc=$rc, $late, left '$(ls -A "$tmp/dense")', $(head -c 200 "$tmp/dense.err"))"; fi
done

finish
