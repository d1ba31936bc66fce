#!/bin/sh
# The adversarial campaign of docs/validation/robustness.md, rerun: each input a hostile or
# careless user might give, by category, and what came of it. Prints the table (Markdown):
# category, tried, clean error, crash, hang, non-finite written, file left, wrong answer silently,
# data lost, security.
# Usage: sh tests/tools/robustness_campaign.sh [BUILD]   (about two minutes; nice it)
build=${1:-build}
W=$(cd "$(dirname "$build/whirl")" && pwd)/whirl
scenes=$(cd "$(dirname "$0")/../../data/scenes" && pwd)
regress=$(cd "$(dirname "$0")/../fuzz/regress/scene" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
results="$tmp/results"
said=""
guard=""
: >"$results"
: >"$tmp/times"

# judge CATEGORY WANT RC DIR: one outcome. WANT: "error" (a one-line error, exit 1) or an exit
# status (a signal's 128 + n). A hang is exit 124 of timeout; a crash any other status >= 128
# that was not wanted; non-finite: nan or inf in a file left in DIR; file left: a temporary file,
# or after an error an output that was not there before (out*); wrong silently: exit 0 where
# an error was wanted, or an error that does not say what $said (grep -E; empty: anything) says;
# data lost: a line of $tmp/guard_rows (the rows of the file $guard when guard_file recorded
# them, or the chunk a first run had finished) is not in the file $guard (empty: none) any more;
# security: a file victim.txt beside the run's folder (written by a scene that reached outside).
judge() {
  cat=$1; want=$2; rc=$3; dir=$4
  crash=0; hang=0; nonfinite=0; left=0; wrong=0; clean=0; lost=0; security=0
  if [ "$rc" -eq 124 ]; then hang=1
  elif [ "$want" = error ] && [ "$rc" -eq 0 ]; then wrong=1
  elif [ "$want" = error ] && [ "$rc" -ge 128 ]; then crash=1
  elif [ "$want" != error ] && [ "$rc" -ne "$want" ]; then
    if [ "$rc" -ge 128 ]; then crash=1; else wrong=1; fi
  fi
  if [ -n "$(ls -A "$dir" | grep '\.tmp\.')" ]; then left=1; fi
  if [ "$want" = error ] && [ -n "$(ls -A "$dir" | grep '^out')" ]; then left=1; fi
  if cat "$dir"/* 2>/dev/null | grep -v '^#' | grep -Eqi '(^|[ ,])[-+]?(nan|inf)([ ,]|$)'; then
    nonfinite=1; fi
  if [ "$want" = error ] && [ "$(wc -l <"$dir/../err")" -ne 1 ]; then wrong=1; fi
  if [ -n "$said" ] && ! grep -Eq "$said" "$dir/../err"; then wrong=1; fi
  if [ -n "$guard" ] && grep -vxF -f "$guard" "$tmp/guard_rows" 2>/dev/null | grep -q .; then
    lost=1; fi
  if [ -e "$dir/../victim.txt" ]; then security=1; fi
  [ $crash$hang$nonfinite$left$wrong$lost$security = 0000000 ] && clean=1
  echo "$cat $clean $crash $hang $nonfinite $left $wrong $lost $security" >>"$results"
  [ $clean -eq 1 ] || echo "campaign: $cat (case $(grep -c "^$cat " "$results")): rc $rc," \
    "crash $crash hang $hang non-finite $nonfinite left $left wrong $wrong lost $lost" \
    "security $security, $(head -c 200 "$dir/../err")" >&2
}

# guard_file PATH: the file whose rows the next judged run must keep.
guard_file() { guard=$1; grep '^[0-9]' "$1" >"$tmp/guard_rows"; }

# try CATEGORY WANT ARGS...: runs whirl ARGS in a fresh folder (the working directory), 60 s at
# most, and judges it.
try() {
  cat=$1; want=$2; shift 2
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  (cd "$tmp/run/d" && timeout 60 "$W" "$@" >/dev/null 2>"$tmp/run/err" </dev/null)
  judge "$cat" "$want" $? "$tmp/run/d"
}

# signal CATEGORY SIG WANT ARGS...: sends SIG 1 s into the run.
signal() {
  cat=$1; sig=$2; want=$3; shift 3
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  (cd "$tmp/run/d" && exec timeout 60 env --default-signal="$sig" "$W" "$@" >/dev/null 2>"$tmp/run/err") &
  pid=$!
  sleep 1
  t0=$(date +%s.%N)
  pkill -"$sig" -P $pid -x whirl 2>/dev/null
  wait $pid
  rc=$?
  echo "$(echo "$(date +%s.%N) - $t0" | bc) SIG$sig whirl $*" >>"$tmp/times"
  judge "$cat" "$want" $rc "$tmp/run/d"
}

map="stability --omega-min 2 --omega-max 8 --omega-count 1201 --links 8 --periods 20 -o out.csv"
sweep="sweep --modes 1,2,3 --omega-min 2 --omega-max 4000 --omega-count 30001 -o out.csv"
driven="driven --omega-min 1 --omega-max 4000 --eps 0.05 -o out.csv"
rsweep="regime --sweep --omega-min 3 --omega-max 3.5 --omega-count 5000 --eps 0.1 --links 5 --t-max 60 -o out.csv"
for s in HUP QUIT TERM INT; do
  case $s in HUP) n=129 ;; QUIT) n=131 ;; TERM) n=143 ;; INT) n=130 ;; esac
  # shellcheck disable=SC2086
  { signal signals $s $n $map; signal signals $s $n $sweep; signal signals $s $n $driven
    signal signals $s $n $rsweep; }
done
rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
(cd "$tmp/run/d" && { timeout 60 "$W" simulate "$scenes/mode2.ini" --set run.t_end=1e4 2>"$tmp/run/err"; echo $? >"$tmp/rc"; } | head -n 1 >/dev/null)
judge signals 141 "$(cat "$tmp/rc")" "$tmp/run/d"
rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
(cd "$tmp/run/d" && ulimit -f 64 && timeout 60 "$W" simulate "$scenes/mode2.ini" --set run.t_end=1e4 -o out.csv 2>"$tmp/run/err")
judge signals 153 $? "$tmp/run/d"
mkfifo "$tmp/fifo"
try signals error shape --omega 2 --mode 1 -o "$tmp/fifo"
try signals error simulate "$tmp/fifo"

# endless or hostile input
try input error fit --shape /dev/zero -o out.csv
try input error simulate /dev/zero -o out.csv
try input error view /dev/zero -o out.csv
rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
(cd "$tmp/run/d" && timeout 60 "$W" fit --shape - -o out.csv </dev/zero 2>"$tmp/run/err")
judge input error $? "$tmp/run/d"
rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
(cd "$tmp/run/d" && yes '# c' | timeout 60 "$W" fit --shape - -o out.csv 2>"$tmp/run/err")
judge input error $? "$tmp/run/d"
head -c 17000000 /dev/zero | tr '\0' x >"$tmp/long.ini"
try input error simulate "$tmp/long.ini" -o out.csv
try input error simulate "$tmp" -o out.csv
# out of memory while reading, under ulimit -v a little above what a short input needs (found by
# bisection, to 1 MiB): said as such, not as the end of the file
# least_vm PATTERN ARGS...: the least limit in KiB at which `whirl ARGS` prints PATTERN
least_vm() {
  pat=$1; shift
  lo=1024 hi=4194304
  while [ $((hi - lo)) -gt 1024 ]; do
    mid=$(((lo + hi) / 2))
    if (ulimit -v $mid; exec "$W" "$@") 2>&1 | grep -Eq "$pat"; then hi=$mid; else lo=$mid; fi
  done
  echo $hi
}
printf '; nothing\n' >"$tmp/short.ini"
{ printf '; '; head -c 12000000 /dev/zero | tr '\0' x; printf '\n[chain]\n'; } >"$tmp/longline.ini"
printf 'r,z\n0.1,-0.5\n' >"$tmp/short.csv"
awk 'BEGIN {print "r,z"; for (i = 0; i < 1500000; i++) print "0.1,-0.5"}' >"$tmp/long.csv"
vm=$(least_vm 'dim: missing' simulate "$tmp/short.ini" -o /dev/null)
said='out of memory'
rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
(cd "$tmp/run/d" && ulimit -v $((vm + 4096)) && timeout 60 "$W" simulate "$tmp/longline.ini" -o out.csv 2>"$tmp/run/err")
judge input error $? "$tmp/run/d"
for c in fit view; do
  case $c in fit) opt=--shape short='has 1 points' ;; view) opt= short='no chain in it' ;; esac
  said=''
  vm=$(least_vm "$short" $c $opt "$tmp/short.csv" -o /dev/null)
  said='out of memory'
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  (cd "$tmp/run/d" && ulimit -v $((vm + 4096)) && timeout 60 "$W" $c $opt "$tmp/long.csv" -o out.csv 2>"$tmp/run/err")
  judge input error $? "$tmp/run/d"
done
said=''
rm -f "$tmp/longline.ini" "$tmp/long.csv"

# long phases: stopped promptly by SIGINT (exit 130, nothing written)
signal long INT 130 critical --links 60000 --modes 60000 -o out.csv
signal long INT 130 shape --omega 3.3 --mode 2 --points 10000000 -o out.csv
# the dense O(N^3) phases of 3000 links (LAPACK on a worker thread) and the banded window search
signal long INT 130 stability --windows --links 3000 --modes 2 --omega-min 3 --omega-max 4 --full -o out.csv
signal long TERM 143 stability --windows --links 3000 --modes 2 --omega-min 3 --omega-max 4 --full -o out.csv
signal long INT 130 stability --omega 4 --mode 2 --links 3000 --eigenvalues -o out.csv
signal long INT 130 stability --windows --links 3000 --modes 2 --omega-min 3 --omega-max 4 -o out.csv
try long error fit --shape "$scenes/../fit_example.csv" --links 10000000 -o out.csv
awk 'BEGIN {print "# omega=3 mode=2"; print "s,r,z,tension"
            for (i = 0; i < 3000000; i++) printf "%.15g,%.15g,%.15g,1\n", i * 1e-7, 0.1 * sin(i * 1e-6), -i * 3.3e-7}' \
  >"$tmp/big.csv"
signal long INT 130 view "$tmp/big.csv" -o out.html
rm -f "$tmp/big.csv"

# outputs that destroy
"$W" shape --omega 3.3 --mode 2 --points 50 -o "$tmp/d.csv"
cp "$scenes/mode2.ini" "$tmp/s.ini"
try outputs error sweep --modes 1 --links 5 --omega-min 2 --omega-max 3 --omega-count 3 -o x.csv --events x.csv
try outputs error stability --omega 2 --mode 1 --links 5 -o y.csv --trace ./y.csv
try outputs error fit --shape "$tmp/d.csv" -o "$tmp/d.csv"
try outputs error simulate "$tmp/s.ini" -o "$tmp/s.ini"
try outputs error shape --omega 2 --mode 1 -o a.csv -o b.csv
cp "$tmp/d.csv" "$tmp/ro.csv"; chmod 444 "$tmp/ro.csv"
try outputs error shape --omega 2 --mode 1 -o "$tmp/ro.csv"
ln -s nowhere "$tmp/dangling"
try outputs error shape --omega 2 --mode 1 -o "$tmp/dangling"
try outputs error simulate "$scenes/mode2.ini" --set run.t_end=0.5 --set output.trace=/dev/full -o out.csv
try outputs error fit --shape "$tmp/d.csv" -o "$tmp/no/dir/out.csv"
fast="--links 8 --drag 0.25 --t-max 150 --t-ramp 10"
big="--omega-min 1 --omega-max 4 --omega-count 40 --eps 0.05 $fast"
# shellcheck disable=SC2086
(cd "$tmp" && exec "$W" regime $big -o "$tmp/map.csv" 2>/dev/null) &
pid=$!
i=0
while [ "$(cat "$tmp/map.csv" 2>/dev/null | grep -c '^[0-9]')" -lt 1 ] && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
# shellcheck disable=SC2086
try outputs error regime $big -o "$tmp/map.csv" --resume
kill -INT $pid; wait $pid
for bad in nan inf 1e999 cut; do
  sh "$(dirname "$0")/bad_row.sh" "$tmp/map.csv" "$tmp/bad.csv" $bad
  # shellcheck disable=SC2086
  try outputs error regime $big -o "$tmp/bad.csv" --resume
done

# two runs started together on a map file that does not exist yet: one writes it, the other is
# refused with one line (clean); both exiting 0, or rows other than the winner's, is wrong
# together ROWS_A ARGS_A ROWS_B ARGS_B
together() {
  rows_a=$1; args_a=$2; rows_b=$3; args_b=$4
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  # shellcheck disable=SC2086
  (cd "$tmp/run/d" && exec timeout 60 "$W" $args_a -o map.csv >/dev/null 2>"$tmp/run/err_a") &
  pa=$!
  # shellcheck disable=SC2086
  (cd "$tmp/run/d" && exec timeout 60 "$W" $args_b -o map.csv >/dev/null 2>"$tmp/run/err_b") &
  pb=$!
  wait $pa; ra=$?; wait $pb; rb=$?
  rows=$(grep -v '^#' "$tmp/run/d/map.csv" 2>/dev/null | tail -n +2 | wc -l)
  if [ $ra -eq 0 ] && [ $rb -eq 1 ] && [ "$rows" -eq "$rows_a" ]; then cp "$tmp/run/err_b" "$tmp/run/err"; rc=1
  elif [ $rb -eq 0 ] && [ $ra -eq 1 ] && [ "$rows" -eq "$rows_b" ]; then cp "$tmp/run/err_a" "$tmp/run/err"; rc=1
  elif [ $ra -ge 124 ] || [ $rb -ge 124 ]; then rc=$((ra > rb ? ra : rb)); : >"$tmp/run/err"
  else rc=0; cat "$tmp/run/err_a" "$tmp/run/err_b" >"$tmp/run/err"; fi
  mv "$tmp/run/d/map.csv" "$tmp/run/map.csv" 2>/dev/null # the winner's map: not an output left
  said="is being written by another run"
  judge outputs error $rc "$tmp/run/d"
  said=''
}
rsw="regime --sweep --omega-min 3 --omega-max 3.5 --eps 0.1 --links 5 --t-max 60"
together 79 "$rsw --omega-count 40" 81 "$rsw --omega-count 41"
smap="stability --omega-max 8 --links 8 --periods 20 --omega-count 101"
# shellcheck disable=SC2086
"$W" $smap --omega-min 2 -o "$tmp/s2a.csv" && "$W" $smap --omega-min 2.5 -o "$tmp/s2b.csv"
together "$(grep -v '^#' "$tmp/s2a.csv" | tail -n +2 | wc -l)" "$smap --omega-min 2" \
  "$(grep -v '^#' "$tmp/s2b.csv" | tail -n +2 | wc -l)" "$smap --omega-min 2.5"
# through a symlink to another user's file (as root): its owner and mode kept, else wrong
if [ "$(id -u)" -eq 0 ]; then
  cp "$tmp/d.csv" "$tmp/theirs.csv"; chown 65534:65534 "$tmp/theirs.csv"; chmod 604 "$tmp/theirs.csv"
  ln -s "$tmp/theirs.csv" "$tmp/their_link.csv"
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  (cd "$tmp/run/d" && timeout 60 "$W" shape --omega 2 --mode 1 -o "$tmp/their_link.csv" >/dev/null 2>"$tmp/run/err")
  rc=$?
  [ $rc -eq 0 ] && [ "$(stat -c '%u:%g %a' "$tmp/theirs.csv")" = "65534:65534 604" ] && [ -L "$tmp/their_link.csv" ] && rc=keep
  # judged as an outcome wanted "keep": 0 with the owner and mode kept
  judge outputs 0 "$([ "$rc" = keep ] && echo 0 || echo 1)" "$tmp/run/d"
else echo "campaign: the symlink to another user's file skipped: not root" >&2; fi

# scenes that reach outside
mkdir "$tmp/scn"
for t in ../victim.txt /tmp/victim.txt a/../../victim.txt; do
  sed "s|^\[output\]|[output]\ntrace = $t|" "$scenes/mode2.ini" >"$tmp/scn/bad.ini"
  try scene error simulate "$tmp/scn/bad.ini" --set run.t_end=0.1 -o out.csv
done
sed "s|^\[output\]|[output]\ntrace = run.dat|" "$scenes/mode2.ini" >"$tmp/scn/ok.ini"
echo keep >"$tmp/scn/run.dat"
try scene error simulate "$tmp/scn/ok.ini" --set run.t_end=0.1 -o out.csv
try scene error simulate "$scenes/mode2.ini" --set "run.method=$(printf 'x\033]0;t\007\nline')" -o out.csv

# unbounded work from one key
for f in every_tiny every_overflow omega_t_end; do try work error simulate "$regress/$f.ini" -o out.csv; done
try work error simulate "$scenes/mode2.ini" --set output.trace=t.dat --set output.trace_every=1e-6 -o out.csv
# the fuzz timeouts at omega 2.5e6 and 4.6e6 in the rotating frame: beyond the budget refused,
# within it stopped at once by SIGINT with its rows
try work error simulate "$regress/omega_4.6e6_rk8pd.ini" --set run.t_end=2000 -o out.csv
signal work INT 130 simulate "$regress/omega_4.6e6_rk8pd.ini" -o out.csv
signal work INT 130 simulate "$regress/omega_2.5e6_rk8.ini" -o out.csv

# files given to --resume (the atlas, the maps): each refused in one line and left as it was.
# resume_try FILE ARGS...: whirl ARGS -o map.csv --resume in a fresh folder holding a copy of
# FILE as map.csv, which must come out unchanged (else data lost; nan or inf in it: non-finite).
resume_try() {
  f=$1; shift
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  cp "$f" "$tmp/run/d/map.csv"
  guard_file "$tmp/run/d/map.csv"
  inode=$(stat -c %i "$tmp/run/d/map.csv")
  (cd "$tmp/run/d" && timeout 60 "$W" "$@" -o map.csv --resume >/dev/null 2>"$tmp/run/err" </dev/null)
  rc=$?
  # the file as given (with its nan) is no output of the run unless the run wrote it
  if [ "$(stat -c %i "$tmp/run/d/map.csv" 2>/dev/null)" = "$inode" ] && cmp -s "$f" "$tmp/run/d/map.csv"; then
    mv "$tmp/run/d/map.csv" "$tmp/run/map.csv"
    guard="$tmp/run/map.csv"
  fi
  judge resume error $rc "$tmp/run/d"
  guard=''
}
atl="stability --atlas --modes 2,3 --omega-max 6"
# shellcheck disable=SC2086
"$W" $atl -o "$tmp/a6.csv" 2>/dev/null
sed '4a # done mode 3 omega 7.6 9' "$tmp/a6.csv" >"$tmp/r.csv"
# shellcheck disable=SC2086
resume_try "$tmp/r.csv" $atl
sed 's/^# done mode 2 omega 5 6$/# done mode 2 omega 3 6/' "$tmp/a6.csv" >"$tmp/r.csv"
# shellcheck disable=SC2086
resume_try "$tmp/r.csv" $atl
resume_try "$tmp/a6.csv" stability --atlas --modes 2 --omega-max 6
resume_try "$tmp/a6.csv" stability --atlas --modes 2,3 --omega-max 10
sed '1s/degree 16/degree 20/; 2s/degree=16/degree=20/' "$tmp/a6.csv" >"$tmp/r.csv"
# shellcheck disable=SC2086
resume_try "$tmp/r.csv" $atl
zeros=0000000000000000000000000000000000000000000000000000000000000000000000
for v in nan inf 1e999 "${zeros}1e999"; do
  sed "s/^2,[0-9.]*,/2,$v,/" "$tmp/a6.csv" >"$tmp/r.csv"
  # shellcheck disable=SC2086
  resume_try "$tmp/r.csv" $atl
done
sed 's/^3,/4,/' "$tmp/a6.csv" >"$tmp/r.csv"
# shellcheck disable=SC2086
resume_try "$tmp/r.csv" $atl
for v in "nan " "${zeros}1e999"; do
  awk -F, -v v="$v" 'BEGIN { OFS = "," } !done && /^[0-9]/ { $9 = v; done = 1 } { print }' \
    "$tmp/map.csv" >"$tmp/r.csv"
  # shellcheck disable=SC2086
  resume_try "$tmp/r.csv" regime $big
done
smap3="stability --omega-min 2 --omega-max 4 --omega-count 3 --modes 1,2 --links 6 --linear"
# shellcheck disable=SC2086
"$W" $smap3 -o "$tmp/s3.csv" 2>/dev/null
sed 's/^3,2,/3.5,2,/' "$tmp/s3.csv" >"$tmp/r.csv"
# shellcheck disable=SC2086
resume_try "$tmp/r.csv" $smap3
# an atlas another run writes: a second run, with --resume or afresh, is refused (it replaced
# the first's atlas with its own)
long="stability --atlas --modes 2 --omega-max 60"
for how in --resume ""; do
  rm -f "$tmp/along.csv"
  # shellcheck disable=SC2086
  (exec env --default-signal=INT "$W" $long -o "$tmp/along.csv" >/dev/null 2>&1) &
  pid=$!
  i=0
  while ! grep -q '^# done mode 2 omega 0 5' "$tmp/along.csv" 2>/dev/null && [ $i -lt 1500 ]; do
    sleep 0.02; i=$((i + 1))
  done
  rm -rf "$tmp/run"; mkdir -p "$tmp/run/d"
  said="is being written by another run"
  # shellcheck disable=SC2086
  (cd "$tmp/run/d" && timeout 60 "$W" $long -o "$tmp/along.csv" $how >/dev/null 2>"$tmp/run/err" </dev/null)
  rc=$?
  kill -INT $pid 2>/dev/null; wait $pid
  # the first run's chunk must be in the file (a second run that replaced it lost it)
  guard="$tmp/along.csv"
  echo '# done mode 2 omega 0 5' >"$tmp/guard_rows"
  judge resume error $rc "$tmp/run/d"
  said=''; guard=''
done

# silently wrong
try wrong error stability --omega 4 --mode 2 --links 60 --dt 0.05 -o out.csv
printf '# trace: t\n0 0 0 0\n0 0 -1e200 0\n' >"$tmp/huge.dat"
try wrong error view "$tmp/huge.dat" -o out.csv

echo "| category | tried | clean error | crash | hang | non-finite written | file left | wrong answer silently | data lost | security |"
echo "|---|---|---|---|---|---|---|---|---|---|"
awk '{ t[$1]++; for (k = 2; k <= 9; k++) s[$1, k] += $k; if (!($1 in o)) { o[$1] = ++n; name[n] = $1 } }
     END { for (i = 1; i <= n; i++) { c = name[i];
       printf "| %s | %d | %d | %d | %d | %d | %d | %d | %d | %d |\n", c, t[c], s[c,2], s[c,3], s[c,4], s[c,5], s[c,6], s[c,7], s[c,8], s[c,9] } }' "$results"
echo
echo "Time from the signal to the exit, slowest first (s):"
sort -rn "$tmp/times" | head -n 5 | awk '{ printf "- %.3f %s\n", $1, substr($0, index($0, $2)) }'
