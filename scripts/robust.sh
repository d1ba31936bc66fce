#!/bin/sh
# The robustness campaign behind the table in tests/fuzz/README.md: runs whirl on hostile inputs
# by category and classifies each run as clean (exit 0 with a finite output, or exit 1 / 130 with
# a one-line error), crash (killed by a signal other than the one sent, or a sanitizer report),
# hang (still running after $LIMIT s), non-finite written (inf or nan in an output) and file left
# (a temporary or unasked file). Then the slowest Ctrl-C: the time from the signal to the exit of
# each long command (signalled 1 s after its start, or later where the slow part comes later).
# Usage: sh scripts/robust.sh [BUILD]   (ten minutes)
build=${1:-build}
W="$(cd "$(dirname "$build/whirl")" && pwd)/whirl"
LIMIT=${LIMIT:-30}
scenes="$(cd "$(dirname "$0")/../data/scenes" && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
stats="$work/.stats"
: >"$stats"

# try CATEGORY ARGS...: one run in an empty directory; the output goes to out.csv unless the
# arguments name one (or standard output is the output).
try() {
  cat=$1; shift
  rm -rf run; mkdir run; cd run || exit 1
  timeout -s KILL "$LIMIT" "$W" "$@" >stdout 2>stderr
  rc=$?
  crash=0; hang=0; nonfinite=0; left=0; clean=0
  if [ $rc -eq 137 ]; then hang=1
  elif [ $rc -gt 128 ] && [ $rc -ne 130 ] || grep -q -e 'Sanitizer' -e 'runtime error' stderr; then crash=1
  fi
  for f in $(ls -A | grep -v -e '^stdout$' -e '^stderr$'); do
    case "$f" in *.tmp.*|.tmp*) left=1 ;; esac
  done
  for f in $(ls -A | grep -v '^stderr$'); do
    [ -f "$f" ] && grep -v '^#' "$f" | grep -qiE '(^|[,; =])[-+]?(inf|nan)' && nonfinite=1
  done
  if [ $crash -eq 0 ] && [ $hang -eq 0 ] && [ $nonfinite -eq 0 ] && [ $left -eq 0 ]; then
    if [ $rc -eq 0 ] || { [ $rc -eq 1 ] || [ $rc -eq 130 ]; } && [ "$(wc -l <stderr)" -le 1 ]; then
      clean=1
    fi
  fi
  [ $clean -eq 1 ] || echo "  $cat: rc=$rc crash=$crash hang=$hang nonfinite=$nonfinite left=$left: whirl $*: $(head -c 200 stderr)" >&2
  cd .. || exit 1
  echo "$cat $clean $crash $hang $nonfinite $left" >>"$stats"
}

# ---- numbers at the edges of double, for every command ----
for v in 1e308 -1e308 1e-308 5e-324 0 -0 1e100 1e-100; do
  try overflow critical --modes 3 --tip-mass "$v" -o out.csv
  try overflow critical --links 5 --length "$v" -o out.csv
  try overflow shape --omega "$v" --mode 2 -o out.csv
  try overflow shape --omega 3 --mode 1 --tip-mass "$v" -o out.csv
  try overflow shape --omega "$v" --mode 1 --links 6 -o out.csv
  try overflow shape --omega "$v" --mode 3 --links 10 -o out.csv
  try overflow shape --omega 3 --mode 1 --mass "$v" --length 1 -o out.csv
  try overflow sweep --modes 1,2 --omega-min 1 --omega-max "$v" --omega-count 5 -o out.csv
  try overflow sweep --modes 1 --omega-min 2 --omega-max 3 --omega-count 3 --tip-mass "$v" -o out.csv
  try overflow stability --omega 2.5 --mode 1 --links 5 --damping "$v" --linear -o out.csv
  try overflow stability --omega "$v" --mode 1 --links 5 --linear -o out.csv
  try overflow minimize --omega "$v" --links 8 -o out.csv
  try overflow driven --omega "$v" --eps 0.01 -o out.csv
  try overflow driven --omega 3 --eps "$v" -o out.csv
  try overflow driven --omega 3 --eps 0.01 --drag "$v" -o out.csv
  try overflow regime --omega "$v" --eps 0.1 --t-max 60 --links 5 -o out.csv
  try overflow simulate "$scenes/double_pendulum.ini" --set "run.dt=$v" --set run.t_end=1 -o out.csv
  try overflow simulate "$scenes/double_pendulum.ini" --set "chain.gravity=$v" --set run.t_end=1 -o out.csv
  try overflow simulate "$scenes/double_pendulum.ini" --set "run.air_drag=$v" --set run.t_end=1 -o out.csv
  try overflow simulate "$scenes/hand_swung.ini" --set "run.omega=$v" --set run.t_end=1 --set chain.links=5 -o out.csv
done

# ---- work that had no bound ----
try work shape --omega 1e7 --mode 2 -o out.csv
try work shape --omega 1e300 --mode 2 -o out.csv
try work sweep --modes 1,2 --omega-min 1 --omega-max 1e7 --omega-count 11 -o out.csv
try work driven --omega 1e7 --eps 0.01 -o out.csv
try work simulate "$scenes/mode2.ini" --set run.method=rk8 --set run.tol=1e-87 -o out.csv
try work simulate "$scenes/mode2.ini" --set run.method=gsl-rk4imp --set run.tol=1e-87 --set run.air_drag=1e12 -o out.csv
try work simulate "$scenes/mode2.ini" --set run.method=gsl-rk4imp --set run.tol=1e-8 --set run.air_drag=1e300 --set chain.links=10 -o out.csv
try work simulate "$scenes/mode2.ini" --set run.t_end=1e12 -o out.csv
try work simulate "$scenes/mode2.ini" --set run.dt=1e-300 -o out.csv
try work regime --omega 1e-8 --eps 0.1 --t-max 50 -o out.csv
try work stability --omega 2 --mode 1 --links 5 --periods 1e300 -o out.csv
try work stability --omega 2 --mode 1 --links 5 --dt 1e-300 -o out.csv
"$W" shape --omega 3.3 --mode 2 --points 1000000 -o big.csv
try work fit --shape "$work/big.csv" -o out.csv

# ---- input read as written ----
printf '[chain]\ndim = 2\nlinks = 2\n[run]method = nosuchmethod\nt_end = 1\ndt = 0.1\n[start]\nhanging = 1\n' >h.ini
printf '[chain]\ndim = 2\0\nlinks = 2\n' >nul.ini
printf 'r,z\n0.3,-0.5\n0.3,-0.5\n0.3,-0.5\n' >same.csv
printf 'r,z\n0,-0.2\n0,-0.4\n0,-0.6\n' >axis.csv
printf 'r,z\n0.3,-0.5\n0.3\0,-0.6\n' >nul.csv
head -c 3000 /dev/urandom >random.bin
for f in h.ini nul.ini random.bin; do try input simulate "$work/$f" -o out.csv; done
for f in same.csv axis.csv nul.csv random.bin; do try input fit --shape "$work/$f" -o out.csv; done
try input stability --omega 2 --mode 1 --links 4 --periods 1 --trace '' -o out.csv
try input shape --omega 2 --mode 1 -o ''
try input fit --shape '' -o out.csv
try input regime --omega 3 --eps 0.1 --t-max 60 --links 5 --trace '' -o out.csv
try input simulate '' -o out.csv
try input shape --omega 2 --mode 1 -o /nonexistent/dir/out.csv

# ---- interrupts: SIGINT and SIGTERM after 1 s (or AFTER s), the time from the signal to the exit ----
printf '%-58s %s\n' "command, signal" "signal to exit [s]" >"$work/.latency"
# interrupt AFTER SIGNAL ARGS...
interrupt() {
  after=$1; sig=$2; shift 2
  rm -rf run; mkdir run; cd run || exit 1
  "$W" "$@" -o out.csv >stdout 2>stderr &
  pid=$!
  sleep "$after"
  t0=$(date +%s.%N)
  kill -"$sig" $pid
  wait $pid
  rc=$?
  t1=$(date +%s.%N)
  left=0; crash=0; clean=0
  for f in $(ls -A); do case "$f" in *.tmp.*) left=1 ;; esac; done
  [ $rc -gt 128 ] && [ $rc -ne 130 ] && crash=1
  [ $rc -eq 130 ] && [ $left -eq 0 ] && clean=1
  [ $clean -eq 1 ] || echo "  interrupt: rc=$rc left=$left: whirl $*: $(head -c 200 stderr)" >&2
  cd .. || exit 1
  echo "interrupt $clean $crash 0 0 $left" >>"$stats"
  printf '%-58s %.3f\n' "$1 $sig after $after s" "$(echo "$t1 - $t0" | bc)" >>"$work/.latency"
}
"$W" shape --omega 3.3 --mode 2 --points 10000 -o p10k.csv
for sig in INT TERM; do
  interrupt 1 $sig simulate "$scenes/mode2.ini" --set run.method=gsl-rk4imp --set run.tol=1e-8 --set run.air_drag=1e12 --set chain.links=10
  interrupt 1 $sig simulate "$scenes/mode2.ini" --set run.method=rk8 --set run.tol=1e-16 --set run.t_end=1000 --set run.stop_deviation=1e9
  interrupt 1 $sig simulate "$scenes/mode2.ini" --set run.method=gauss3 --set chain.links=1000 --set run.t_end=1000 --set run.stop_deviation=1e9
  interrupt 1 $sig regime --omega 3 --eps 0.1 --t-max 100000
  interrupt 1 $sig regime --omega-min 2 --omega-max 6 --omega-count 40 --eps 0.1
  interrupt 1 $sig stability --omega-min 2 --omega-max 8 --omega-count 401 --links 8 --periods 20
  interrupt 1 $sig stability --omega 3 --mode 2 --links 200 --periods 1000
  interrupt 1 $sig sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 --omega-count 30001
  interrupt 1 $sig sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 --omega-count 30001 --links 300
  interrupt 1 $sig driven --omega-min 1 --omega-max 4000 --eps 0.05
  interrupt 1 $sig fit --shape "$work/p10k.csv" --mode 2
  interrupt 1 $sig minimize --omega 40 --links 2000 --algorithm LN_BOBYQA
  interrupt 1 $sig critical --links 3000 --modes 64
  interrupt 1 $sig stability --omega 3 --mode 2 --links 300 --linear
  interrupt 2 $sig stability --windows --links 300 --omega-min 3 --omega-max 30 --modes 2
  interrupt 60 $sig minimize --omega 40 --links 2000 --algorithm LN_BOBYQA
  interrupt 1 $sig regime --sweep --omega-min 3 --omega-max 3.5 --omega-count 5000 --eps 0.1 --links 5 --t-max 60
  interrupt 3 $sig stability --windows --modes 2 --omega-min 2 --omega-max 10 --degree 64
  interrupt 20 $sig stability --windows --modes 2 --omega-min 4 --omega-max 5 --degree 64
  interrupt 1 $sig equilibria --links 100 --omega 15
done

echo "category   tried  clean-error/ok  crash  hang  non-finite  file-left"
awk '{t[$1]++; c[$1]+=$2; k[$1]+=$3; h[$1]+=$4; n[$1]+=$5; l[$1]+=$6}
     END {for (x in t) printf "%-10s %5d  %14d  %5d  %4d  %10d  %9d\n", x, t[x], c[x], k[x], h[x], n[x], l[x]}' "$stats"
echo
cat "$work/.latency"
