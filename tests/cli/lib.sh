# Helpers for the command-line tests: TAP lines "ok N - name" / "not ok N - name", and the plan
# "1..N" printed by finish at the end (a test that dies before finish has no plan: tests/run.sh
# counts it as failed).
# $WHIRL is the program under test.
n=0
fails=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

pass() { n=$((n + 1)); echo "ok $n - $1"; }
fail() { n=$((n + 1)); fails=$((fails + 1)); echo "not ok $n - $1"; }

# expect_error NAME PATTERN ARGS...: the command must exit non-zero, print nothing on stdout,
# print one line on stderr that matches PATTERN (grep -E), and leave no output file $tmp/out.csv.
expect_error() {
  name=$1; pattern=$2; shift 2
  rm -f "$tmp/out.csv"
  "$WHIRL" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  if [ $rc -ne 0 ] && [ ! -s "$tmp/stdout" ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] \
     && grep -Eq -- "$pattern" "$tmp/stderr" && [ ! -e "$tmp/out.csv" ] \
     && [ -z "$(ls "$tmp" | grep '^out.csv.')" ]; then
    pass "$name"
  else
    fail "$name (rc=$rc, stderr: $(head -c 300 "$tmp/stderr"))"
  fi
}

# expect_ok NAME ARGS...: the command must exit 0.
expect_ok() {
  name=$1; shift
  if "$WHIRL" "$@" >"$tmp/stdout" 2>"$tmp/stderr"; then pass "$name"
  else fail "$name (stderr: $(head -c 300 "$tmp/stderr"))"; fi
}

# expect_refused NAME PATTERN FILE ARGS...: whirl ARGS -o FILE --resume must exit 1 with one line
# matching PATTERN, no crash (the sanitizers' reports go to stderr: more than one line), and FILE
# left as it was.
expect_refused() {
  name=$1; pattern=$2; file=$3; shift 3
  cp "$file" "$tmp/before"
  "$WHIRL" "$@" -o "$file" --resume >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  if [ $rc -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -Eq -- "$pattern" "$tmp/stderr" &&
     cmp -s "$file" "$tmp/before" && [ -z "$(ls "$tmp" | grep '\.tmp\.')" ]; then
    pass "$name"
  else fail "$name (rc=$rc, stderr: $(head -c 300 "$tmp/stderr"))"; fi
}

# interrupt PID: sends SIGINT to the background command PID (started with
# `env --default-signal=INT`: the suite may run with SIGINT ignored) and waits for it; sets rc to
# its exit status and late to the seconds from the signal to its exit.
interrupt() {
  t0=$(date +%s.%N)
  kill -INT "$1"
  wait "$1"
  rc=$?
  late=$(echo "$(date +%s.%N) - $t0" | bc)
}

# signal_run SIGNAL CPU_SECONDS COMMAND...: runs COMMAND (its streams the caller's), sends SIGNAL
# once it has used CPU_SECONDS of processor time, waits for it (tests/tools/signal_run.py); the
# status is the command's. Then report FIELD gives the run's status, wall (s from the signal to
# the exit), cpu_after (processor s from the signal to the exit: the work done after a stop,
# which load does not stretch), cpu_before, early (1: it ended before the signal).
signal_run() { /usr/bin/python3 "$(dirname "$0")/../tools/signal_run.py" "$tmp/signal.report" "$@"; }
report() { sed -n "s/.*$1=\([^ ]*\).*/\1/p" "$tmp/signal.report"; }

finish() { echo "1..$n"; [ $fails -eq 0 ]; exit $?; }
