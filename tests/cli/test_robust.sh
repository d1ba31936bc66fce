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
# a high mode at a rate where the tip radius no longer fixes the shape (continued in the link
# angles): its nodes from the branch's link angles, the pivot on the axis, three nodes
expect_ok "shape --links: mode 3 of 10 links at omega 1e4" shape --omega 1e4 --mode 3 --links 10 -o "$out"
pivot_r=$(grep -v '^#' "$out" | sed -n 2p | cut -d, -f2)
if grep -q 'node_count=3 ' "$out" && [ "$pivot_r" = "0" ]; then
  pass "mode 3 at omega 1e4: three nodes, the pivot on the axis"
else fail "mode 3 at omega 1e4: pivot r $pivot_r, $(head -n 1 "$out")"; fi
# mode 1 up to the highest rate: the tensions no longer overflow (H^2 ~ omega^4 did from 1e77). The
# chain is then horizontal but for a sag ~ g/omega^2: link j's slope is g M_j / (omega^2 X_j),
# so depth omega^2 = sum_j l_j M_j / X_j = 2 sum_{j=1..10} 1/(10 + j) for 10 equal links.
for w in 1e20 1e90; do
  "$WHIRL" shape --omega $w --mode 1 --links 10 -o "$tmp/flat.csv" 2>"$tmp/stderr"
  depth=$(head -n 1 "$tmp/flat.csv" | sed -n 's/.* depth=\([^ ]*\) .*/\1/p')
  if awk -v d="$depth" -v w=$w 'BEGIN { s = 0; for (j = 1; j <= 10; j++) s += 2 / (10 + j);
       r = d * w * w / s; exit !(r > 1 - 1e-12 && r < 1 + 1e-12) }'; then
    pass "shape --links 10 --omega $w: depth omega^2 is the horizontal chain's sag"
  else fail "shape --links 10 --omega $w: depth '$depth' ($(head -c 200 "$tmp/stderr"))"; fi
done
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

# ---- work without a bound is refused up front or capped ----
expect_error "shape: omega 1e7 is refused by the continuum (was minutes)" \
  "omega=1e\+07 is above 5000, the highest rate the continuum shooting resolves" \
  shape --omega 1e7 --mode 2 -o "$out"
expect_error "shape: omega 1e300 is refused (was endless)" "omega=1e\+300 is above 1e\+100" \
  shape --omega 1e300 --mode 2 -o "$out"
expect_error "shape --links: omega 1e300 is refused" "omega=1e\+300 is above 1e\+100" \
  shape --omega 1e300 --mode 2 --links 10 -o "$out"
expect_error "sweep: a branch reaching omega 1e7 is refused" "omega=2.5e\+06 is above 5000" \
  sweep --modes 1 --omega-min 1 --omega-max 1e7 --omega-count 5 -o "$out"
expect_error "driven: omega 1e7 is refused" "omega=1e\+07 is above 5000" \
  driven --omega 1e7 --eps 0.01 -o "$out"
scenes="$(dirname "$0")/../../data/scenes"
expect_error "simulate: rk8 at tol 1e-87 is refused (was endless)" \
  "run.tol: 1e-87 is below the round-off of doubles: use a tolerance >= 1e-16" \
  simulate "$scenes/mode2.ini" --set run.method=rk8 --set run.tol=1e-87 -o "$out"
expect_error "simulate: gsl-rk4imp at tol 1e-87 is refused" "below the round-off of doubles" \
  simulate "$scenes/mode2.ini" --set run.method=gsl-rk4imp --set run.tol=1e-87 \
  --set run.air_drag=1e12 -o "$out"
expect_error "simulate: links x t_end / dt beyond the budget is refused with the estimate" \
  "run.t_end: links x t_end / dt = 5e\+13 link-steps exceeds the budget of 1e\+10" \
  simulate "$scenes/mode2.ini" --set run.t_end=1e9 -o "$out"
expect_error "regime: omega 1e-8 within t_max 50 is refused (was far past t_max)" \
  "t_max - t_ramp = 30 holds 4.77e-08 drive periods .*the classification needs 16" \
  regime --omega 1e-8 --eps 0.1 --t-max 50 -o "$out"
expect_error "stability --windows: a scan of 4e6 points is refused (was half a minute to stop)" \
  "a scan from omega = 1.147956547 to omega = 1000000 in steps of delta omega = 0.25 has 4e\+06 points, more than 100000" \
  stability --windows --links 5 --omega-min 1 --omega-max 1e6 -o "$out"
expect_error "driven: a drag of 1e100 is refused (was more than 30 s)" \
  "drag coefficients above 1e\+06 are refused \(got 1e\+100, 0\)" \
  driven --omega 3 --eps 0.01 --drag 1e100 -o "$out"
expect_error "stability: 1e300 periods are refused up front (was endless)" \
  "1e\+300 periods in steps of .* more than 1e\+09" \
  stability --omega 2 --mode 1 --links 5 --periods 1e300 -o "$out"
expect_error "simulate: a drive rate of 1e308 is refused (wrote inf)" \
  "run.omega: \|omega\| must be at most 1e\+100" \
  simulate "$scenes/hand_swung.ini" --set run.omega=1e308 --set chain.links=5 -o "$out"
"$WHIRL" shape --omega 3.3 --mode 2 --points 20001 -o "$tmp/many.csv"
expect_error "fit: more than 20000 points are refused" "a fit takes at most 20000 points, got 20001" \
  fit --shape "$tmp/many.csv" -o "$out"

# ---- interrupts: SIGINT or SIGTERM ends every long command with exit 128 + the signal's number
# (130, 143), rows kept where the command keeps rows, no temporary file left ----
# interrupt NAME SIGNAL ROWS ARGS...: runs `whirl ARGS -o $tmp/int/out.csv`, sends SIGNAL after
# 1 s; ROWS = keep: the output must then exist with its header and the rows done (possibly
# none); rows: likewise with at least one row; none: no output.
interrupt() {
  name=$1; sig=$2; rows=$3; shift 3
  rm -rf "$tmp/int"; mkdir "$tmp/int"
  "$WHIRL" "$@" -o "$tmp/int/out.csv" >"$tmp/int.stdout" 2>"$tmp/int.stderr" &
  pid=$!
  sleep 1
  kill -"$sig" $pid
  wait $pid
  rc=$?
  left=$(ls -A "$tmp/int" | grep -v '^out.csv$')
  kept=$( [ -f "$tmp/int/out.csv" ] && grep -cv '^#' "$tmp/int/out.csv" || echo 0)
  case $rows in
    keep) [ "$kept" -ge 1 ] ;;
    rows) [ "$kept" -ge 2 ] ;;
    *) [ ! -e "$tmp/int/out.csv" ] ;;
  esac
  output_ok=$?
  case $sig in INT) want=130 ;; TERM) want=143 ;; *) want=none ;; esac
  if [ $rc -eq $want ] && [ -z "$left" ] && [ $output_ok -eq 0 ]; then
    pass "interrupt ($sig): $name"
  else
    fail "interrupt ($sig): $name (rc=$rc, left: '$left', lines: $kept, stderr: $(head -c 200 "$tmp/int.stderr"))"
  fi
}
"$WHIRL" shape --omega 3.3 --mode 2 --points 10000 -o "$tmp/p10000.csv"
interrupt "simulate, adaptive gsl-rk4imp with extreme drag (stopped inside a step)" INT keep \
  simulate "$scenes/mode2.ini" --set run.method=gsl-rk4imp --set run.tol=1e-8 \
  --set run.air_drag=1e12 --set chain.links=10
interrupt "simulate, adaptive rk8" TERM keep simulate "$scenes/mode2.ini" --set run.method=rk8 \
  --set run.tol=1e-16 --set run.t_end=1000 --set run.stop_deviation=1e9
interrupt "regime, one run" INT none regime --omega 3 --eps 0.1 --t-max 100000
interrupt "regime, one run" TERM none regime --omega 3 --eps 0.1 --t-max 100000
interrupt "stability map" INT keep stability --omega-min 2 --omega-max 8 --omega-count 1201 --links 8 \
  --periods 20
interrupt "sweep" INT keep sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 --omega-count 30001
interrupt "driven branch" INT keep driven --omega-min 1 --omega-max 4000 --eps 0.05
interrupt "regime sweep (the points completed are kept)" INT rows regime --sweep --omega-min 3 \
  --omega-max 3.5 --omega-count 5000 --eps 0.1 --links 5 --t-max 60
interrupt "sweep of the N-link chain" TERM keep sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 \
  --omega-count 30001 --links 300
interrupt "fit of 10^4 points" INT none fit --shape "$tmp/p10000.csv" --mode 2
# a long continuation (mode 334 of 1000 links to omega 700: a minute): no output, one line naming
# the mode and the rate reached
interrupt "shape of a long N-link continuation" INT none shape --links 1000 --mode 334 --omega 700
if [ "$(wc -l <"$tmp/int.stderr")" -eq 1 ] && grep -Eq \
     '^whirl shape: interrupted in mode 334: stopped at omega=5[3-9][0-9.]* after [0-9]+ steps$' \
     "$tmp/int.stderr"; then pass "interrupt: the shape's line names the mode and the rate reached"
else fail "interrupt: the shape's line names the mode and the rate reached ($(head -c 300 "$tmp/int.stderr"))"; fi

# prompt NAME ARGS...: Ctrl-C during work that cannot poll (one dense solve) still ends the
# command at once. The command runs to its end twice (T seconds: the shorter, as another load
# on the machine only lengthens a run), then again with SIGINT at T/3: it must exit 130 within
# T/3 of the signal (the work left then takes about 2T/3). A run that ended with 0 had finished
# before the signal (the machine got faster): that says nothing, and the signal is sent again,
# at T/6, to another run.
prompt() {
  name=$1; shift
  full=
  for _ in 1 2; do
    t0=$(date +%s.%N)
    "$WHIRL" "$@" >/dev/null 2>&1
    t=$(echo "$(date +%s.%N) - $t0" | bc)
    if [ -z "$full" ] || [ "$(echo "$t < $full" | bc)" -eq 1 ]; then full=$t; fi
  done
  for part in 3 6; do
    third=$(echo "$full / $part" | bc -l)
    "$WHIRL" "$@" >/dev/null 2>"$tmp/int.stderr" &
    pid=$!
    sleep "$third"
    t0=$(date +%s.%N)
    kill -INT $pid
    wait $pid
    rc=$?
    late=$(echo "$(date +%s.%N) - $t0" | bc)
    [ $rc -ne 0 ] && break
  done
  if [ $rc -eq 130 ] && [ "$(echo "$late < $third" | bc)" -eq 1 ]; then
    pass "interrupt at a third of the run: $name ends at once"
  else
    fail "interrupt at a third of the run: $name (rc=$rc, run $full s, signal at T/$part, to exit $late s)"
  fi
}
prompt "stability of 250 links, the eigen-solve on a worker" \
  stability --omega 3 --mode 2 --links 250 --linear -o "$tmp/prompt.csv"

finish
