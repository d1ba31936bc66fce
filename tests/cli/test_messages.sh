#!/bin/sh
# Command-line tests of the messages a newcomer meets: the valid names in every "unknown"
# message, silence when the reader of standard output goes away, a note on an implausible
# length or mass given without a unit, a file given where an option reads it, and the words of
# the shape's summary line (node_count: the pivot and the crossings; crossing_s: their
# arclengths).
. "$(dirname "$0")/lib.sh"

# the valid names: integrators, NLopt's algorithms, the commands
expect_error "stability: unknown --method lists the integrators" \
  "^whirl stability: --method: unknown integrator 'rk5' \(known: gauss2 .*gsl-msbdf.*\)$" \
  stability --omega 3 --mode 1 --method rk5
expect_error "regime: unknown --method lists the integrators" \
  "^whirl regime: --method: unknown integrator 'rk5' \(known: gauss2 .*gsl-msbdf.*\)$" \
  regime --omega 3 --eps 0.1 --method rk5
expect_error "minimize: unknown --algorithm lists NLopt's local algorithms" \
  "^whirl minimize: unknown NLopt algorithm 'foo' \(local ones: .*LD_LBFGS .*LN_BOBYQA.*\)$" \
  minimize --links 5 --omega 3 --algorithm foo
expect_error "an unknown command lists the commands" \
  "^whirl: unknown command 'frobnicate' \(known: critical shape .* plot view\)$" frobnicate
# every command of whirl --help is in that list
"$WHIRL" frobnicate 2>"$tmp/known"
missing=
for c in $("$WHIRL" --help | awk '/^commands:/ {on = 1; next} on && NF {print $1}'); do
  grep -q " $c[ )]" "$tmp/known" || missing="$missing $c"
done
if [ -z "$missing" ] && [ -n "$("$WHIRL" --help | awk '/^commands:/ {on = 1; next} on && NF' )" ]; then
  pass "the unknown command's list has every command"; else fail "the unknown command's list lacks:$missing"; fi

# whirl fit FILE: the file goes with --shape
expect_error "fit FILE points to --shape FILE" \
  "^whirl fit: unexpected argument 'nosuch.csv' \(did you mean --shape nosuch.csv\?\)$" fit nosuch.csv

# the reader of standard output goes away (| head -2): the lines before it were written, no
# message, the status of a process ended by SIGPIPE (141) when more than the pipe's buffer (64
# KiB on Linux) was left to write (a short output may all fit before head exits: status 0);
# SIGPIPE at its default, as in a shell
piped() { # piped NAME STATUSES ARGS...: runs whirl ARGS | head -2
  name=$1; want=$2; shift 2
  { env --default-signal=PIPE "$WHIRL" "$@" 2>"$tmp/pipe.err"; echo $? >"$tmp/pipe.rc"; } \
    | head -2 >"$tmp/pipe.out"
  if [ ! -s "$tmp/pipe.err" ] && echo " $want " | grep -q " $(cat "$tmp/pipe.rc") " \
     && [ "$(wc -l <"$tmp/pipe.out")" -eq 2 ]; then pass "$name"
  else fail "$name (rc $(cat "$tmp/pipe.rc"), stderr: $(head -c 300 "$tmp/pipe.err"))"; fi
}
piped "shape | head -2: silent" "0 141" shape --omega 3 --mode 1
piped "shape of 200001 points (16 MB) | head -2: silent, 141" 141 shape --omega 3 --mode 1 --points 200001
piped "sweep of 4000 rows (400 kB) | head -2: silent, 141" 141 sweep --omega-min 2 --omega-max 9 --omega-count 2000 --modes 1,2

# a length over 10 m or a mass under a gram, given as a bare number: a note, and the run goes on
expect_note() { # expect_note NAME PATTERN ARGS...: exit 0, stderr exactly one line matching
  name=$1; pattern=$2; shift 2
  if "$WHIRL" "$@" >"$tmp/stdout" 2>"$tmp/stderr" && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] \
     && grep -Eq -- "$pattern" "$tmp/stderr" && [ -s "$tmp/stdout" ]; then pass "$name"
  else fail "$name (stderr: $(head -c 300 "$tmp/stderr"))"; fi
}
expect_note "--length 60: a note" \
  "^whirl shape: note: --length 60 is 60 m, longer than 10 m \(write the unit if you meant otherwise: 60cm, 60mm\)$" \
  shape --omega 6 --mode 1 --length 60
expect_note "--mass 0.0005: a note" \
  "^whirl shape: note: --mass 0.0005 is 0.0005 kg \(0.5 g\), lighter than a gram" \
  shape --omega 6 --mode 1 --length 1 --mass 0.0005
for ok in "--length 60cm" "--length 2" "--length 10" "--length 0.6 --mass 50g" "--length 1 --mass 0.001"; do
  # shellcheck disable=SC2086
  if "$WHIRL" shape --omega 6 --mode 1 $ok >/dev/null 2>"$tmp/stderr" && [ ! -s "$tmp/stderr" ]; then
    pass "$ok: no note"; else fail "$ok: no note (stderr: $(head -c 300 "$tmp/stderr"))"; fi
done

# one word for each meaning: node_count (the pivot and the crossings), crossing_s (where)
"$WHIRL" shape --omega 6 --mode 3 >"$tmp/s3.csv"
if head -1 "$tmp/s3.csv" | grep -Eq '^# omega=6 mode=3 node_count=3 .* crossing_s=[0-9.e-]+;[0-9.e-]+$' \
   && ! head -1 "$tmp/s3.csv" | grep -q ' nodes='; then
  pass "shape: node_count=3 and two crossing_s"; else fail "shape: node_count=3 and two crossing_s ($(head -1 "$tmp/s3.csv"))"; fi
"$WHIRL" driven --omega 1.6 --eps 0.1 --links 8 >"$tmp/d.csv" 2>/dev/null
if grep -Eq '^# omega=1.6 mode=1 node_count=1 tip_x=' "$tmp/d.csv"; then
  pass "driven: node_count="; else fail "driven: node_count= ($(grep '^# omega' "$tmp/d.csv"))"; fi

finish
