#!/bin/sh
# Runs the tests and prints the closing line "tests: N passed, N failed"; exits non-zero unless
# every test program passed. Usage: run.sh [BUILD [TEST...]] or run.sh BUILD --also TEST...:
# without TEST, every test program BUILD/tests/test_* and every shell test tests/cli/test_*.sh; with
# --also, those and the TESTs. A TEST ending in .sh runs under sh with WHIRL=BUILD/whirl, any
# other is executed.
#
# A test program passes only if it exits with status 0 (not by a signal), prints exactly one TAP
# plan "1..N" (first or last), exactly N result lines "ok ..." / "not ok ...", no "not ok" and
# no skip ("# SKIP" / "# skip" after a result). The closing line counts the "not ok" lines, plus
# one for a test program that went wrong otherwise (signal, status, plan, skip).
build=${1:-build}
[ $# -gt 0 ] && shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export CMOCKA_MESSAGE_OUTPUT=TAP
passed=0
failed=0

# cpu_children: the processor time (user + system, seconds) of the shell's finished children so
# far, from the second line of the shell's `times` ("0m1.25s 0m0.31s"; run in this shell, not in a
# command substitution, whose subshell has children of its own); cpu_since T: what it grew by
# since T, to a tenth of a second.
cpu_children() {
  times >"$tmp/times"
  cpu=$(awk 'NR == 2 { for (i = 1; i <= 2; i++) { split($i, p, "m"); s += p[1] * 60 + p[2] } }
    END { printf "%.2f", s }' "$tmp/times")
}

# run_one TEST: runs it, copying its output, then judges the output and the exit status.
run_one() {
  t=$1
  echo "== $t"
  start=$(date +%s)
  cpu_children
  cpu0=$cpu
  case $t in
    *.sh) { WHIRL="$build/whirl" sh "$t" 2>&1; echo $? >"$tmp/rc"; } | tee "$tmp/out" ;;
    *) { "$t" 2>&1; echo $? >"$tmp/rc"; } | tee "$tmp/out" ;;
  esac
  rc=$(cat "$tmp/rc")
  ok=$(grep -Ec '^ok( |$)' "$tmp/out")
  notok=$(grep -Ec '^not ok( |$)' "$tmp/out")
  skips_ok=$(grep -Eic '^ok( [^#]*)?#[[:space:]]*skip' "$tmp/out")
  skips_notok=$(grep -Eic '^not ok( [^#]*)?#[[:space:]]*skip' "$tmp/out")
  skips=$((skips_ok + skips_notok))
  results=$((ok + notok))
  notok=$((notok - skips_notok))
  plans=$(grep -Ec '^1\.\.[0-9]+[[:space:]]*$' "$tmp/out")
  plan=$(grep -E '^1\.\.[0-9]+[[:space:]]*$' "$tmp/out" | head -n 1 | sed 's/^1\.\.//; s/[[:space:]]//g')
  why=""
  if [ "$rc" -gt 128 ]; then why="$why; killed by signal $((rc - 128))"
  elif [ "$rc" -ne 0 ] && [ "$notok" -eq 0 ]; then why="$why; exit status $rc after no failure"
  fi
  if [ "$plans" -eq 0 ]; then why="$why; no plan 1..N"
  elif [ "$plans" -gt 1 ]; then why="$why; $plans plans"
  elif [ "$results" -ne "$plan" ]; then why="$why; $results results for plan 1..$plan"
  fi
  [ "$skips" -gt 0 ] && why="$why; $skips skipped"
  # one failure for whatever went wrong besides the "not ok" lines
  passed=$((passed + ok - skips_ok))
  failed=$((failed + notok))
  [ -n "$why" ] && failed=$((failed + 1))
  [ "$notok" -gt 0 ] && why="$why; $notok not ok"
  cpu_children
  echo "== $t: $(($(date +%s) - start)) s, $(awk -v a="$cpu0" -v b="$cpu" 'BEGIN { printf "%.1f", b - a }') s cpu"
  if [ -n "$why" ] || [ "$rc" -ne 0 ]; then
    why="${why#; }"
    echo "== FAILED $t: ${why:-exit status $rc}"
    echo "$t: ${why:-exit status $rc}" >>"$tmp/failures"
  fi
}

# listed T: T is one of the TESTs after --except
listed() {
  for x in $except; do [ "$x" = "$1" ] && return 0; done
  return 1
}
except=
if [ $# -gt 0 ] && [ "$1" != --also ] && [ "$1" != --except ]; then
  for t in "$@"; do run_one "$t"; done
else
  mode=${1:---also}
  [ $# -gt 0 ] && shift
  if [ "$mode" = --except ]; then
    except="$*"
    set --
  fi
  for t in "$build"/tests/test_*; do
    case $t in *.d) continue ;; esac
    [ -x "$t" ] && ! listed "$t" && run_one "$t"
  done
  for t in tests/cli/test_*.sh; do
    [ -f "$t" ] && ! listed "$t" && run_one "$t"
  done
  for t in "$@"; do run_one "$t"; done
fi
if [ -s "$tmp/failures" ]; then
  echo "== failed:"
  sed 's/^/   /' "$tmp/failures"
fi
echo "tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ] && [ ! -s "$tmp/failures" ]
