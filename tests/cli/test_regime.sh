#!/bin/sh
# Command-line tests of whirl regime: one run, a map (order, resume after an interruption, the
# same rows on 2 MPI ranks when the program is built with MPI), a sweep, a trace, bad input.
. "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1
fast="--links 8 --drag 0.25 --t-max 150 --t-ramp 10"
rows() { grep -v '^#' "$1" | tail -n +2; }

# one run: comments, header, one settled row whose node count is that of the steady shape
expect_ok "one run" regime --omega 3.3 --eps 0.06 $fast -o "$tmp/one.csv"
if grep -q '^# regime: links=8 ' "$tmp/one.csv" && grep -q '^# critical rates' "$tmp/one.csv" \
   && [ "$(grep -v '^#' "$tmp/one.csv" | head -1 | cut -d, -f1-6)" = "index,omega,eps,state,class,nodes" ] \
   && [ "$(rows "$tmp/one.csv" | wc -l)" -eq 1 ] \
   && rows "$tmp/one.csv" | awk -F, '{exit !($4 == "settled" && $5 == 2 && $6 == 2 && $12 == 2 && $11 < 1e-3)}'; then
  pass "one run: settled into 2 nodes, the steady shape's count"; else fail "one run: settled into 2 nodes, the steady shape's count"; fi

# a trace for plots/animate.gp: one block per 0.5 time units, the pivot and 8 masses each
expect_ok "one run with a trace" regime --omega 3.3 --eps 0.06 $fast --trace "$tmp/trace.dat" --trace-every 0.5 -o "$tmp/one.csv"
t_end=$(rows "$tmp/one.csv" | cut -d, -f8)
blocks=$(grep -c '^# t = ' "$tmp/trace.dat")
if awk -v b="$blocks" -v t="$t_end" 'BEGIN {exit !(b == int(t / 0.5 + 1e-9) + 1)}' \
   && [ "$(grep -v '^#' "$tmp/trace.dat" | grep -c .)" -eq $((9 * blocks)) ]; then
  pass "trace: blocks every 0.5 of 9 points"; else fail "trace: blocks every 0.5 of 9 points ($blocks, t_end $t_end)"; fi

# a map: rows in index order, omega fastest
map="--omega-min 1 --omega-max 4 --omega-count 4 --eps-min 0.04 --eps-max 0.08 --eps-count 2 $fast"
expect_ok "map" regime $map -o "$tmp/map.csv" --folds "$tmp/folds.csv"
if [ "$(rows "$tmp/map.csv" | cut -d, -f1 | tr '\n' ' ')" = "0 1 2 3 4 5 6 7 " ] \
   && rows "$tmp/map.csv" | awk -F, 'NR == 6 {exit !($2 == 2 && $3 == 0.08)}' \
   && grep -q '^# computed 8 points in ' "$tmp/map.csv"; then
  pass "map: 8 rows in index order"; else fail "map: 8 rows in index order"; fi
if [ "$(grep -v '^#' "$tmp/folds.csv" | head -1)" = "eps,mode,side,fold,omega" ]; then
  pass "map: folds file"; else fail "map: folds file"; fi

# resume: a file cut in the middle of a row and missing the last rows is completed to the same rows
{ grep '^#' "$tmp/map.csv" | grep -v '^# computed'; grep -v '^#' "$tmp/map.csv" | head -4; \
  grep -v '^#' "$tmp/map.csv" | sed -n 5p | head -c 20; } >"$tmp/cut.csv"
expect_ok "resume" regime $map -o "$tmp/cut.csv" --resume
if [ "$(rows "$tmp/cut.csv")" = "$(rows "$tmp/map.csv")" ] && grep -q '^# computed 5 points' "$tmp/cut.csv"; then
  pass "resume: 5 points computed, same rows"; else fail "resume: 5 points computed, same rows"; fi

# an interrupted map keeps its rows (exit 130) and --resume completes it
big="--omega-min 1 --omega-max 4 --omega-count 40 --eps 0.05 $fast"
"$WHIRL" regime $big -o "$tmp/big.csv" 2>"$tmp/int.err" &
pid=$!
i=0
while [ "$(rows "$tmp/big.csv" 2>/dev/null | wc -l)" -lt 2 ] && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
kill -INT $pid
wait $pid
rc=$?
kept=$(rows "$tmp/big.csv" | wc -l)
if [ $rc -eq 130 ] && [ "$kept" -ge 2 ] && [ "$kept" -lt 40 ] && grep -q 'interrupted: .* --resume' "$tmp/int.err"; then
  pass "interrupt: exit 130, $kept rows kept"; else fail "interrupt: exit 130, rows kept (rc $rc, $kept rows)"; fi
expect_ok "interrupt: resume" regime $big -o "$tmp/big.csv" --resume
if [ "$(rows "$tmp/big.csv" | cut -d, -f1 | tr '\n' ' ')" = "$(seq 0 39 | tr '\n' ' ')" ]; then
  pass "interrupt: resumed to 40 rows in order"; else fail "interrupt: resumed to 40 rows in order"; fi
expect_error "resume with other parameters" "whirl regime: --resume: .* not written by a map with these parameters" \
  regime --omega-min 1 --omega-max 4 --omega-count 40 --eps 0.05 --links 8 --drag 0.3 --t-max 150 \
  --t-ramp 10 -o "$tmp/big.csv" --resume

# 2 MPI ranks: the same rows as the single process (under the sanitizers without leak detection:
# Open MPI's plugins keep allocations past exit); a program built without MPI ran the map on 1 rank
if command -v mpirun >/dev/null 2>&1 && ldd "$WHIRL" 2>/dev/null | grep -q libmpi; then
  [ "$(id -u)" = 0 ] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  if ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
     mpirun --oversubscribe -n 2 "$WHIRL" regime $map -o "$tmp/map2.csv" >"$tmp/mpi.out" 2>&1 \
     && [ "$(rows "$tmp/map2.csv")" = "$(rows "$tmp/map.csv")" ] \
     && grep -q '^# computed 8 points in .* on 2 rank' "$tmp/map2.csv"; then
    pass "mpirun -n 2: the rows of the single process"
  else fail "mpirun -n 2: the rows of the single process ($(head -c 300 "$tmp/mpi.out"))"; fi
elif grep -q '^# computed 8 points in .* on 1 rank' "$tmp/map.csv"; then
  pass "built without MPI: the map ran on 1 rank"
else fail "built without MPI: the map ran on 1 rank"; fi

# hysteresis: omega up then down, 2n - 1 rows
expect_ok "sweep" regime --sweep --omega-min 2 --omega-max 3 --omega-count 3 --eps 0.06 $fast --t-change 5 -o "$tmp/sweep.csv"
if [ "$(rows "$tmp/sweep.csv" | cut -d, -f1 | tr '\n' ' ')" = "up up up down down " ] \
   && [ "$(grep -v '^#' "$tmp/sweep.csv" | head -1 | cut -d, -f1-3)" = "leg,omega,state" ]; then
  pass "sweep: up and down rows"; else fail "sweep: up and down rows"; fi
expect_ok "regime --help" regime --help

# bad input: one line, non-zero exit, no file
o="-o $tmp/out.csv"
expect_error "nothing" "whirl regime: --omega \(one run\) or" regime --eps 0.1 $o
expect_error "no eps" "whirl regime: --eps .* is required" regime --omega 2 $o
expect_error "eps too big" "whirl regime: --eps must be in \[0, 1\) \(in L\), got 1.5" regime --omega 2 --eps 1.5 $o
expect_error "negative omega" "whirl regime: --omega must be > 0 \(in sqrt\(g/L\)\), got -2" regime --omega -2 --eps 0.1 $o
expect_error "negative drag" "whirl regime: --drag must be >= 0" regime --omega 2 --eps 0.1 --drag -1 $o
expect_error "negative quadratic drag" "whirl regime: --drag-quadratic must be >= 0" regime --omega 2 --eps 0.1 --drag-quadratic -1 $o
expect_error "zero dt" "whirl regime: --dt: dt must be > 0" regime --omega 2 --eps 0.1 --dt 0 $o
expect_error "t-max below ramp" "whirl regime: --t-max: t_max .* must exceed t_ramp" regime --omega 2 --eps 0.1 --t-max 5 $o
expect_error "settle tol" "whirl regime: --settle-tol: settle_tol must be > 0" regime --omega 2 --eps 0.1 --settle-tol 0 $o
expect_error "settle periods" "whirl regime: --settle-periods must be a whole number" regime --omega 2 --eps 0.1 --settle-periods 1.5 $o
expect_error "seed" "whirl regime: --seed must be a whole number" regime --omega 2 --eps 0.1 --seed -3 $o
expect_error "links" "whirl regime: --links must be between" regime --omega 2 --eps 0.1 --links 0 $o
expect_error "frame" "whirl regime: --frame must be rotating or inertial" regime --omega 2 --eps 0.1 --frame lab $o
expect_error "method" "whirl regime: --method: unknown integrator 'euler'" regime --omega 2 --eps 0.1 --method euler $o
expect_error "half a range" "whirl regime: a map or sweep needs --omega-min, --omega-max and --omega-count" regime --omega-min 1 --eps 0.1 $o
expect_error "inverted range" "whirl regime: need --omega-min < --omega-max" regime --omega-min 3 --omega-max 1 --omega-count 3 --eps 0.1 $o
expect_error "eps range" "whirl regime: --eps-min and --eps-max must lie in" regime --omega-min 1 --omega-max 2 --omega-count 3 --eps-min 0 --eps-max 0.1 --eps-count 2 $o
expect_error "steps" "whirl regime: --omega-count must be between" regime --omega-min 1 --omega-max 2 --omega-count 0 --eps 0.1 $o
expect_error "map to stdout" "whirl regime: a map needs -o FILE" regime --omega-min 1 --omega-max 2 --omega-count 2 --eps 0.1
expect_error "resume one run" "whirl regime: --resume applies to a map" regime --omega 2 --eps 0.1 --resume $o
expect_error "resume missing file" "whirl regime: --resume: cannot read" regime --omega-min 1 --omega-max 2 --omega-count 2 --eps 0.1 --resume -o "$tmp/none.csv"
expect_error "sweep inertial" "whirl regime: --sweep .* needs --frame rotating" regime --sweep --omega-min 1 --omega-max 2 --omega-count 2 --eps 0.1 --frame inertial $o
expect_error "sweep eps range" "whirl regime: an eps range is for a map" regime --sweep --omega-min 1 --omega-max 2 --omega-count 2 --eps-min 0.1 --eps-max 0.2 --eps-count 2 $o
expect_error "trace on a map" "whirl regime: --trace applies to one run" regime --omega-min 1 --omega-max 2 --omega-count 2 --eps 0.1 --trace "$tmp/t.dat" $o
expect_error "not a number" "whirl regime: option --eps needs a finite number" regime --omega 2 --eps abc $o
expect_error "unknown option" "whirl regime: unknown option '--bogus'" regime --omega 2 --eps 0.1 --bogus 1 $o
finish
