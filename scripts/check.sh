#!/bin/sh
# make check and make check-quick: every stage runs, whatever an earlier one gave, and one summary
# closes the run, its last line "check: N passed, N failed" (the tests of every stage summed, plus
# one failure for each stage that failed without counting tests: a build, the clang compile). The
# exit status is non-zero when any stage failed.
#
# Usage: check.sh BUILD [full|quick]
#   full: two lanes at once, which keeps both cores busy (a test waiting on a browser, a timer or
#     a pipe leaves its core to the other lane):
#       plain:     build (BUILD: the program, the libraries, every test program) -> every test,
#                  and tests/cli/install.sh
#       sanitizer: clang -Werror compile (build-clang) -> ASan/UBSan build (build-sanitize) ->
#                  every test but those of tests/sanitize-except.list, under the sanitizers,
#                  taken from a queue that the plain lane joins when its own tests are done
#     The plain lane prints as it goes; the sanitizer tests' output goes to
#     build-sanitize/check.log, the builds' lines and the failures are repeated at the end.
#   quick: the plain build and every test but the slow ones (tests/slow.list; the Python suite
#     without its tests marked slow), taken from one queue by two runs at once (the Python suite
#     first), for after every change
#     (docs/guide/build.md).
# JOBS: parallel compiles (default: the number of processors).
build=${1:-build}
mode=${2:-full}
here=$(cd "$(dirname "$0")" && pwd)
cd "$here/.." || exit 1
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
lane_pid=
if [ "$mode" = lane ]; then
  state=$CHECK_STATE
else
  state=$(mktemp -d)
  cleanup() {
    # an interrupted check ends the sanitizer lane's whole process group
    [ -n "$lane_pid" ] && kill -TERM "-$lane_pid" 2>/dev/null
    rm -rf "$state"
  }
  trap cleanup EXIT
  trap 'exit 130' INT
  trap 'exit 143' TERM
fi

# stage NAME LOG CMD...: runs CMD with its output appended to LOG (and shown as well when SHOW is
# 1), records in $state/NAME the exit status, the wall seconds and the closing line
# "tests: P passed, F failed" if CMD printed one.
stage() {
  name=$1 log=$2
  shift 2
  t0=$(date +%s)
  if [ "${SHOW:-0}" = 1 ]; then
    { "$@" 2>&1; echo $? >"$state/$name.rc"; } | tee -a "$log"
    rc=$(cat "$state/$name.rc")
  else
    "$@" >>"$log" 2>&1
    rc=$?
  fi
  result=$(grep -E '^tests: [0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
  echo "$rc $(($(date +%s) - t0)) $result" >"$state/$name"
  return "$rc"
}

# build_stage NAME DIR MAKEARGS...: make -s -jJOBS MAKEARGS, its output in DIR/build.log; the
# compiler's warnings and errors are printed (on failure the log's last lines)
build_stage() {
  bname=$1 bdir=$2
  shift 2
  mkdir -p "$bdir"
  blog=$bdir/build.log
  : >"$blog"
  stage "$bname" "$blog" make -s --no-print-directory -j"$jobs" "$@"
  brc=$?
  if [ $brc -eq 0 ]; then grep -E 'warning:|error:' "$blog" | head -n 40; else tail -n 30 "$blog"; fi
  echo "== $bname: $([ $brc -eq 0 ] && echo ok || echo FAILED) ($(cut -d' ' -f2 "$state/$bname") s; $blog)"
  return $brc
}

# The sanitizer tests: every test but those of tests/sanitize-except.list, as a queue that both
# lanes drain (the plain lane joins when its own tests are done), the heavy ones first
# (tests/cli/test_python.sh and those of tests/slow.list), so that the lanes end close together.
# queue_sanitizer_tests: one file per test in $state/queue, named in the order to run them.
queue_sanitizer_tests() {
  mkdir -p "$state/queue.new" "$state/results"
  except=" $(sed 's/#.*//; s|^build/|build-sanitize/|' tests/sanitize-except.list | tr '\n' ' ') "
  heavy=" tests/cli/test_python.sh $(sed 's/#.*//; s|^build/|build-sanitize/|' tests/slow.list | tr '\n' ' ') "
  k=1000 queued=" "
  for t in $heavy build-sanitize/tests/test_* tests/cli/test_*.sh; do
    case $t in *.d) continue ;; esac
    [ -f "$t" ] || continue
    case $except$queued in *" $t "*) continue ;; esac
    queued="$queued$t "
    k=$((k + 1))
    echo "$t" >"$state/queue.new/$k"
  done
  mv "$state/queue.new" "$state/queue"
}

# drain WORKER: takes tests from the queue (a rename claims one: only one worker can win it) and
# runs each under the sanitizers, its output appended whole to build-sanitize/check.log and its
# exit status and closing line to $state/results/WORKER
drain() {
  for q in "$state"/queue/*; do
    [ -f "$q" ] || continue
    mine=$state/results/claimed.$1.${q##*/}
    mv "$q" "$mine" 2>/dev/null || continue
    env WHIRL_SANITIZE=1 sh tests/run.sh build-sanitize "$(cat "$mine")" >"$mine.out" 2>&1
    echo "$? $(grep -E '^tests: [0-9]+ passed, [0-9]+ failed$' "$mine.out" | tail -n 1)" \
      >>"$state/results/$1"
    cat "$mine.out" >>build-sanitize/check.log
    grep -E '^== .*: [0-9]+ s, |^== FAILED' "$mine.out" | sed 's/^== /== sanitize: /'
  done
}

# drain_quick RUN: takes tests from the queue of make check-quick ($state/quick; a rename claims
# one) and runs each (tests/run.sh, WHIRL_QUICK set), then prints the closing line of them all,
# "tests: P passed, F failed"; non-zero if any failed
drain_quick() {
  qp=0 qf=0 qrc=0
  for q in "$state"/quick/*; do
    [ -f "$q" ] || continue
    mine=$state/quick/claimed.$1.${q##*/}
    mv "$q" "$mine" 2>/dev/null || continue
    env WHIRL_QUICK=1 sh tests/run.sh "$build" "$(cat "$mine")" >"$mine.out" 2>&1 || qrc=1
    sed '/^tests: [0-9]* passed, [0-9]* failed$/d' "$mine.out"
    last=$(grep -E '^tests: [0-9]+ passed, [0-9]+ failed$' "$mine.out" | tail -n 1)
    if [ -n "$last" ]; then
      qp=$((qp + $(echo "$last" | cut -d' ' -f2))) qf=$((qf + $(echo "$last" | cut -d' ' -f4)))
    else qf=$((qf + 1)) qrc=1; fi
  done
  echo "tests: $qp passed, $qf failed"
  return $qrc
}

# the sanitizer lane: the clang compile, the ASan/UBSan build (the Makefile's sanitize-programs),
# then the queue of the sanitizer tests
sanitizer_lane() {
  lane_log=build-sanitize/check.log
  mkdir -p build-sanitize
  : >"$lane_log"
  build_stage clang build-clang check-clang >>"$lane_log" 2>&1
  build_stage sanitize-build build-sanitize sanitize-programs >>"$lane_log" 2>&1
  date +%s >"$state/sanitize-tests.start"
  queue_sanitizer_tests
  drain sanitizer
}
if [ "$mode" = lane ]; then
  sanitizer_lane
  exit 0
fi

start=$(date +%s)
echo "check: $mode, $jobs parallel compiles, load $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
: >"$state/deps.log"
stage deps "$state/deps.log" sh scripts/deps.sh all || cat "$state/deps.log"

if [ "$mode" = full ]; then
  # the sanitizer lane: this script in lane mode, leading a process group of its own (setsid)
  CHECK_STATE=$state setsid sh "$here/check.sh" "$build" lane </dev/null >/dev/null 2>&1 &
  lane_pid=$!
fi

build_stage build "$build" BUILD="$build" check-programs
: >"$build/check.log"
if [ "$mode" = quick ]; then
  # every test but the slow ones, taken from one queue by two runs at once (the second logged),
  # the Python suite (the longest by far) first, so that the two runs end close together
  slow=" $(sed 's/#.*//' tests/slow.list | tr '\n' ' ') "
  mkdir -p "$state/quick.new"
  k=1000 queued=" "
  for t in tests/cli/test_python.sh "$build"/tests/test_* tests/cli/test_*.sh; do
    case $t in *.d) continue ;; esac
    [ -f "$t" ] || continue
    case $slow in *" build/${t#"$build"/} "*|*" $t "*) continue ;; esac
    case $queued in *" $t "*) continue ;; esac
    queued="$queued$t "
    k=$((k + 1))
    echo "$t" >"$state/quick.new/$k"
  done
  mv "$state/quick.new" "$state/quick"
  : >"$build/check-2.log"
  stage tests-2 "$build/check-2.log" drain_quick 2 &
  two_pid=$!
  SHOW=1 stage tests "$build/check.log" drain_quick 1
  wait $two_pid
  echo "== the other run ($build/check-2.log):"
  grep -E '^== .*: [0-9]+ s, ' "$build/check-2.log"
  grep -E '^== FAILED' "$build/check-2.log"
else
  SHOW=1 stage tests "$build/check.log" sh tests/run.sh "$build" --also tests/cli/install.sh
fi

if [ -n "$lane_pid" ]; then
  echo "== the plain lane joins the sanitizer tests (build-sanitize/check.log)"
  while [ ! -d "$state/queue" ] && kill -0 "$lane_pid" 2>/dev/null; do sleep 1; done
  [ -d "$state/queue" ] && drain plain
  wait "$lane_pid"
  lane_pid=
  # the sanitizer tests as one stage: the exit statuses and the closing lines summed
  if [ -f "$state/sanitize-tests.start" ]; then
    cat "$state"/results/plain "$state"/results/sanitizer 2>/dev/null | awk -v t0="$(cat "$state/sanitize-tests.start")" -v now="$(date +%s)" '
      { if ($1 != 0) rc = 1; n++; p += $3; f += $5; if (NF < 6) { rc = 1; f++ } }
      END { if (n == 0) rc = 1; printf "%d %d tests: %d passed, %d failed\n", rc, now - t0, p, f }' >"$state/sanitize-tests"
  fi
  # its builds' lines, its tests' times and its failures
  sed -n '/^== build-sanitize\/tests\//q; /^== tests\//q; p' build-sanitize/check.log
  grep -E '^== .*: [0-9]+ s, |^== FAILED' build-sanitize/check.log | sed 's/^== /== sanitize: /'
fi

# the summary: each stage's result, then the sums
passed=0
failed=0
bad=0
echo "== check summary ($mode, $(($(date +%s) - start)) s wall, load now $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null))"
for name in deps build tests tests-2 clang sanitize-build sanitize-tests; do
  case $mode-$name in quick-clang|quick-sanitize-*|full-tests-2) continue ;; esac
  if [ ! -f "$state/$name" ]; then
    printf '   %-15s NOT RUN\n' "$name"
    failed=$((failed + 1)) bad=1
    continue
  fi
  read -r rc secs counts <"$state/$name"
  p=0 f=0
  if [ -n "$counts" ]; then
    p=$(echo "$counts" | cut -d' ' -f2)
    f=$(echo "$counts" | cut -d' ' -f4)
  fi
  if [ "$rc" -eq 0 ]; then verdict=ok; else verdict=FAILED bad=1; fi
  # a failed stage that counted no failure (a build, a crashed harness) counts one
  [ "$rc" -ne 0 ] && [ "$f" -eq 0 ] && f=1
  passed=$((passed + p)) failed=$((failed + f))
  printf '   %-15s %-7s %5s s%s\n' "$name" "$verdict" "$secs" "${counts:+   $counts}"
done
echo "check: $passed passed, $failed failed"
[ $bad -eq 0 ] && [ $failed -eq 0 ]
