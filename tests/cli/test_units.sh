#!/bin/sh
# Physical units end to end: for every command that takes or prints a physical quantity, a run
# in SI units (L = 0.6 m, M = 0.05 kg, g = 9.81 m/s^2, inputs given in Hz, rpm, cm, g, ...)
# equals the dimensionless run after conversion (each column divided by its unit), to 1e-9
# relative. The conversions are written out here, independently of the program's: rate
# sqrt(g/L), time sqrt(L/g), force M g, linear drag M sqrt(g/L) / L, quadratic drag M / L^2,
# joint damping M L^2 sqrt(g/L).
. "$(dirname "$0")/lib.sh"

L=0.6 M=0.05 G=9.81
units="--length 60cm --mass 50g --gravity $G"
val() { awk "BEGIN { L = $L; M = $M; G = $G; R = sqrt(G / L); pi = 4 * atan2(1, 1); printf \"%.17g\", $1 }"; }
R=$(val R) T=$(val "1 / R") F=$(val "M * G") C1=$(val "M * R / L") C2=$(val "M / (L * L)")
D=$(val "M * L * L * R")

# same NAME DIMLESS PHYSICAL SCALES: the data rows (after the header) of the two CSV files agree
# column by column once the physical one is divided by the scale of its column (SCALES: one per
# column, "-" for a text column compared as is, "0" for a column not compared).
same() {
  name=$1; a=$2; b=$3; scales=$4
  if [ ! -s "$a" ] || [ ! -s "$b" ]; then fail "$name (no output)"; return; fi
  grep -v '^#' "$a" | tail -n +2 >"$tmp/a.rows"
  grep -v '^#' "$b" | tail -n +2 >"$tmp/b.rows"
  if [ "$(wc -l <"$tmp/a.rows")" -gt 0 ] && [ "$(wc -l <"$tmp/a.rows")" -eq "$(wc -l <"$tmp/b.rows")" ] &&
     paste -d'|' "$tmp/a.rows" "$tmp/b.rows" | awk -F'|' -v scales="$scales" '
       BEGIN { ns = split(scales, s, " ") }
       { na = split($1, x, ","); nb = split($2, y, ",")
         if (na != nb || na != ns) { print "# columns: " na " " nb " " ns; bad = 1; exit }
         for (i = 1; i <= na; i++) {
           if (s[i] == "0") continue
           if (s[i] == "-") { if (x[i] != y[i]) { print "# row " NR " col " i ": " x[i] " " y[i]; bad = 1 }; continue }
           if (x[i] == "" && y[i] == "") continue
           u = y[i] / s[i]; d = u - x[i]; if (d < 0) d = -d
           m = x[i] < 0 ? -x[i] : x[i]
           if (d > 1e-9 * m + 1e-12) { print "# row " NR " col " i ": " x[i] " vs " u; bad = 1 }
         } }
       END { exit bad }'; then pass "$name"
  else fail "$name"; fi
}

# critical (g defaults to standard gravity once --length is given)
"$WHIRL" critical --modes 3 --links 20 -o "$tmp/a.csv"
"$WHIRL" critical --modes 3 --links 20 --length 0.6 --mass 0.05 -o "$tmp/b.csv"
same "critical: rad/s = sqrt(9.80665/L) x dimensionless" "$tmp/a.csv" "$tmp/b.csv" \
  "- $(awk 'BEGIN { printf "%.17g", sqrt(9.80665 / 0.6) }')"
grep -q '^# units: length=m mass=kg time=s rate=rad/s force=N L=0.6 M=0.05 g=9.80665$' "$tmp/b.csv" &&
  grep -q '^# units: dimensionless' "$tmp/a.csv" && pass "critical: the units line" || fail "critical: the units line"

# shape, the rate in Hz
"$WHIRL" shape --omega 3 --mode 2 --points 41 -o "$tmp/a.csv"
"$WHIRL" shape --omega "$(val "3 * R / (2 * pi)")Hz" --mode 2 --points 41 $units -o "$tmp/b.csv"
same "shape: --omega in Hz, lengths in m, tension in N" "$tmp/a.csv" "$tmp/b.csv" "$L $L $L $F"

# sweep, the rates in rpm
"$WHIRL" sweep --modes 1,2 --omega-min 2 --omega-max 5 --omega-count 7 -o "$tmp/a.csv"
"$WHIRL" sweep --modes 1,2 --omega-min "$(val "2 * R * 30 / pi")rpm" \
  --omega-max "$(val "5 * R * 30 / pi")rpm" --omega-count 7 $units -o "$tmp/b.csv"
same "sweep: rates in rpm" "$tmp/a.csv" "$tmp/b.csv" "$R - $L $L $F $L -"

# minimize, with a tip mass in g
"$WHIRL" minimize --omega 3 --links 12 --tip-mass 0.2 -o "$tmp/a.csv"
"$WHIRL" minimize --omega "$(val "3 * R")" --links 12 --tip-mass "$(val "0.2 * M * 1000")g" $units \
  -o "$tmp/b.csv"
same "minimize: rad/s, tip mass in g" "$tmp/a.csv" "$tmp/b.csv" "$L $L $L $F"

# fit: a shape written in SI units, fitted in SI units
"$WHIRL" shape --omega 4.1 --mode 2 --points 37 -o "$tmp/s.csv"
"$WHIRL" shape --omega "$(val "4.1 * R")" --mode 2 --points 37 $units -o "$tmp/sp.csv"
"$WHIRL" fit --shape "$tmp/s.csv" -o "$tmp/a.csv"
"$WHIRL" fit --shape "$tmp/sp.csv" $units -o "$tmp/b.csv"
same "fit: omega in rad/s" "$tmp/a.csv" "$tmp/b.csv" "$R 0 - 0"

# stability: linear analysis with joint damping, one rate
"$WHIRL" stability --omega 2.5 --mode 1 --links 10 --damping 0.01 --linear -o "$tmp/a.csv"
"$WHIRL" stability --omega "$(val "2.5 * R")" --mode 1 --links 10 --damping "$(val "0.01 * $D")" \
  --linear $units -o "$tmp/b.csv"
same "stability: growth rates in 1/s, damping in kg m^2/s" "$tmp/a.csv" "$tmp/b.csv" "$R - - $R 0 0 - -"

# stability: the hand-swung map, eps in cm, linear drag in kg/(m s)
"$WHIRL" stability --omega-min 2 --omega-max 3 --omega-count 2 --modes 1 --links 8 --eps 0.03 \
  --drag 0.1 --linear -o "$tmp/a.csv"
"$WHIRL" stability --omega-min "$(val "2 * R")" --omega-max "$(val "3 * R")" --omega-count 2 \
  --modes 1 --links 8 --eps "$(val "0.03 * L * 100")cm" --drag "$(val "0.1 * $C1")" --linear $units \
  -o "$tmp/b.csv"
same "stability --eps --drag: map in SI units" "$tmp/a.csv" "$tmp/b.csv" "$R - - $R 0 0 - - $L $L -"

# driven: one shape with both drags
"$WHIRL" driven --omega 1.6 --eps 0.05 --drag 0.05 --drag-quadratic 0.02 --points 21 -o "$tmp/a.csv"
"$WHIRL" driven --omega "$(val "1.6 * R")" --eps "$(val "0.05 * L")" --drag "$(val "0.05 * $C1")" \
  --drag-quadratic "$(val "0.02 * $C2")" --points 21 $units -o "$tmp/b.csv"
same "driven: shape in SI units" "$tmp/a.csv" "$tmp/b.csv" "$L $L $L $L $F"
# the drag from the chain's description: C2 = rho CD d / 2 [kg/m^2]
"$WHIRL" driven --omega 1.6 --eps 0.05 --drag-quadratic "$(val "0.5 * 1.204 * 1.2 * 0.004 / $C2")" \
  --points 21 -o "$tmp/a.csv"
"$WHIRL" driven --omega "$(val "1.6 * R")" --eps "$(val "0.05 * L")" --drag-cd 1.2 --diameter 4mm \
  --points 21 $units -o "$tmp/b.csv"
same "driven: --drag-cd --diameter = the quadratic drag rho CD d / 2" "$tmp/a.csv" "$tmp/b.csv" \
  "$L $L $L $L $F"
# regime: one run from rest with its trace (eps in cm, times in s)
"$WHIRL" regime --omega 3 --eps 0.06 --links 6 --t-max 60 --drag 0.2 --trace "$tmp/a.dat" \
  --trace-every 5 -o "$tmp/a.csv"
"$WHIRL" regime --omega "$(val "3 * R")" --eps "$(val "0.06 * L * 100")cm" --links 6 \
  --t-max "$(val "60 / R")" --drag "$(val "0.2 * $C1")" --trace "$tmp/b.dat" --trace-every "$(val "5 / R")" \
  $units -o "$tmp/b.csv"
same "regime: one run in SI units" "$tmp/a.csv" "$tmp/b.csv" \
  "- $R $L - - - - $T $L $L $L - $R $L $L $L $L -"
grep -v '^#' "$tmp/a.dat" | awk 'NF' | sed 's/ /,/g; 1s/^/x,y,z,t\n/' >"$tmp/a.rows.csv"
grep -v '^#' "$tmp/b.dat" | awk 'NF' | sed 's/ /,/g; 1s/^/x,y,z,t\n/' >"$tmp/b.rows.csv"
same "regime: its trace in m and s" "$tmp/a.rows.csv" "$tmp/b.rows.csv" "$L $L $L $T"

# simulate: a scene in SI ([units] system = SI, the chain's length and mass as scalars, values with
# unit suffixes) against the dimensionless scene with every value converted here
cat >"$tmp/si.ini" <<EOF
[units]
system = SI
[chain]
dim = 3
links = 12
length = 60cm
mass = 50g
gravity = $G
[start]
omega = $(val "3.2 * R / (2 * pi)")Hz
mode = 2
perturb = 0.01
[run]
dt = $(val "0.01 / R * 1000")ms
t_end = $(val "4 / R")
air_drag = $(val "0.05 * $C1")
drive_radius = $(val "0.01 * L * 100")cm
[output]
every = $(val "0.5 / R")
columns = t, tip_x, tip_y, tip_z, energy, lz, deviation
trace = b.trace
trace_every = $(val "1 / R")
EOF
cat >"$tmp/dimless.ini" <<EOF
[chain]
dim = 3
links = 12
[start]
omega = 3.2
mode = 2
perturb = 0.01
[run]
dt = 0.01
t_end = 4
air_drag = 0.05
drive_radius = 0.01
[output]
every = 0.5
columns = t, tip_x, tip_y, tip_z, energy, lz, deviation
trace = a.trace
trace_every = 1
EOF
"$WHIRL" simulate "$tmp/dimless.ini" -o "$tmp/a.csv"
"$WHIRL" simulate "$tmp/si.ini" -o "$tmp/b.csv"
same "simulate: a scene in SI units (60cm, 50g, Hz, ms)" "$tmp/a.csv" "$tmp/b.csv" \
  "$T $L $L $L $(val "M * G * L") $(val "M * L * L * R") $L"
grep -q "^# units: length=m mass=kg time=s rate=rad/s force=N L=0.6 M=0.05 g=$G\$" "$tmp/b.csv" &&
  grep -q '^# units: dimensionless' "$tmp/a.csv" && pass "simulate: the units line" ||
  fail "simulate: the units line"
grep -v '^#' "$tmp/a.trace" | awk 'NF' | sed 's/ /,/g; 1s/^/x,y,z,t\n/' >"$tmp/a.rows.csv"
grep -v '^#' "$tmp/b.trace" | awk 'NF' | sed 's/ /,/g; 1s/^/x,y,z,t\n/' >"$tmp/b.rows.csv"
same "simulate: its trace in m and s" "$tmp/a.rows.csv" "$tmp/b.rows.csv" "$L $L $L $T"
grep -q "^# units: length=m mass=kg time=s rate=rad/s force=N L=0.6 M=0.05 g=$G\$" "$tmp/b.trace" &&
  pass "simulate: the trace's units line" || fail "simulate: the trace's units line"
# the scalar and the list of the same thing, and an unknown unit system
printf '[chain]\ndim = 3\nlinks = 2\nlength = 1\nlengths = 0.5, 0.5\n' >"$tmp/both.ini"
expect_error "simulate: length and lengths together" "conflicts with \[chain\] lengths" \
  simulate "$tmp/both.ini"
printf '[units]\nsystem = imperial\n' >"$tmp/imperial.ini"
expect_error "simulate: an unknown unit system" "must be one of dimensionless, SI, got 'imperial'" \
  simulate "$tmp/imperial.ini"

# the library's error messages in the user's units: run the failing command dimensionless and in
# SI, and compare the two one-line errors. Every rate ("omega", "omega_k", ... and a number) of
# the SI line must carry "rad/s" and equal the dimensionless one times sqrt(g/L), to the digits
# printed (at least 6: 1e-5 relative); the rest of the text must be the same.
same_error() {
  name=$1; dimless=$2; physical=$3
  "$WHIRL" $dimless -o "$tmp/err.csv" 2>"$tmp/a.err" >/dev/null && { fail "$name (no error)"; return; }
  "$WHIRL" $physical -o "$tmp/err.csv" 2>"$tmp/b.err" >/dev/null && { fail "$name (no error)"; return; }
  if awk -v R="$R" -v name="$name" '
       function rates(line, unit, out,   n, rest, m, x) {
         n = 0; rest = line
         while (match(rest, /omega(_[A-Za-z0-9]+)?( = |=| )-?[0-9][0-9.e+-]*/)) {
           m = substr(rest, RSTART, RLENGTH); x = m; sub(/^omega(_[A-Za-z0-9]+)?( = |=| )/, "", x)
           out[++n] = x; out["tail" n] = substr(rest, RSTART + RLENGTH, length(unit))
           rest = substr(rest, RSTART + RLENGTH)
         }
         return n
       }
       NR == 1 { a = $0 } NR == 2 { b = $0 }
       END {
         na = rates(a, "", x); nb = rates(b, " rad/s", y)
         if (na == 0 || na != nb) { print "# " na " rates against " nb; exit 1 }
         for (i = 1; i <= na; i++) {
           if (y["tail" i] != " rad/s") { print "# rate " i " has no unit"; exit 1 }
           d = y[i] / R / x[i] - 1; if (d < 0) d = -d
           if (d > 1e-5) { print "# rate " i ": " x[i] " against " y[i] / R; exit 1 }
         }
         gsub(/-?[0-9][0-9.e+-]*( rad\/s)?/, "#", a); gsub(/-?[0-9][0-9.e+-]*( rad\/s)?/, "#", b)
         if (a != b) { print "# text differs: " a " | " b; exit 1 }
       }' "$tmp/a.err" "$tmp/b.err"; then pass "$name"
  else fail "$name: $(cat "$tmp/a.err") | $(cat "$tmp/b.err")"; fi
}
w2=$(val "2 * R") w30=$(val "30 * R")
same_error "error in SI: stability of a mode below its birth" \
  "stability --links 10 --mode 3 --omega 2" "stability --links 10 --mode 3 --omega $w2 $units"
same_error "error in SI: shape below the birth, continuum" \
  "shape --mode 3 --omega 2" "shape --mode 3 --omega $w2 $units"
same_error "error in SI: shape below the birth, N-link" \
  "shape --links 4 --mode 3 --omega 2" "shape --links 4 --mode 3 --omega $w2 $units"
same_error "error in SI: the bound on the continuation steps" \
  "shape --links 5 --mode 4 --omega 30 --max-steps 3" \
  "shape --links 5 --mode 4 --omega $w30 --max-steps 3 $units"
same_error "error in SI: windows beyond the range" \
  "stability --windows --links 10 --modes 3 --omega-min 0.5 --omega-max 2" \
  "stability --windows --links 10 --modes 3 --omega-min $(val "0.5 * R") --omega-max $w2 $units"
same_error "error in SI: equilibria at a birth" \
  "equilibria --links 5 --omega $("$WHIRL" critical --links 5 --modes 3 | grep -v '^#' | tail -n 1 | cut -d, -f2)" \
  "equilibria --links 5 --omega $(val "R * $("$WHIRL" critical --links 5 --modes 3 | grep -v '^#' | tail -n 1 | cut -d, -f2)") $units"



# A rate given in Hz: the library's messages give their rates in Hz, the same rates as in rad/s
# divided by 2 pi (to the 15 digits printed: 1e-12 relative).
"$WHIRL" shape --omega 4Hz --mode 9 --length 0.6 2>"$tmp/hz.err" >/dev/null
"$WHIRL" shape --omega "$(val "8 * pi")" --mode 9 --length 0.6 2>"$tmp/rad.err" >/dev/null
if grep -q '^whirl shape: mode 9 does not exist at omega=4 Hz: it exists only above omega_9=[0-9.]* Hz$' \
     "$tmp/hz.err" &&
   awk 'NR == 1 { split($0, a, "omega_9="); hz = a[2] + 0 }
        NR == 2 { split($0, b, "omega_9="); rad = b[2] + 0 }
        END { d = hz * 2 * 3.14159265358979323846 / rad - 1; if (d < 0) d = -d; exit !(d < 1e-12) }' \
     "$tmp/hz.err" "$tmp/rad.err"; then
  pass "error in SI with --omega in Hz: the rates in Hz"
else fail "error in SI with --omega in Hz: $(cat "$tmp/hz.err") | $(cat "$tmp/rad.err")"; fi

# Every rate and tip radius of a library message is typed (WHIRL_Q_RATE, WHIRL_Q_LENGTH), so that
# the lines above print it in SI: none of the library's format strings leaves one untyped.
root=$(dirname "$0")/../..
if /usr/bin/python3 "$root/tests/tools/message_quantities.py" "$root" >"$tmp/untyped"; then
  pass "every rate and tip radius of the library's messages is typed"
else
  fail "untyped quantities in messages: $(head -n 3 "$tmp/untyped" | tr '\n' ' ')"
fi

finish
