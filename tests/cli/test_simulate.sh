#!/bin/sh
# End-to-end tests of `whirl simulate`: the example scenes run, the physics holds (energy of the
# double pendulum, order of the Gauss methods, a steady shape stays steady, the trace keeps the
# link lengths, the two formulations agree), bad scenes fail cleanly, a failing or interrupted
# run keeps its rows.
. "$(dirname "$0")/lib.sh"
scenes="$(dirname "$0")/../../data/scenes"

# valid_csv FILE: '#' comments, then a header starting with t, then rows of as many numbers.
valid_csv() {
  awk -F, '/^#/ { next }
    !h { h = NF; ok = ($1 == "t"); next }
    { rows++; if (NF != h) ok = 0
      for (i = 1; i <= NF; i++) if ($i !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) ok = 0 }
    END { exit !(ok && rows > 0) }' "$1"
}
# column FILE NAME: the values of column NAME, one a line.
column() {
  awk -F, -v name="$2" '/^#/ { next } !c { for (i = 1; i <= NF; i++) if ($i == name) c = i; next }
    { print $c }' "$1"
}
# max_abs_change FILE NAME: max over the rows of |value - first value|.
max_abs_change() {
  column "$1" "$2" | awk 'NR == 1 { v0 = $1 } { d = $1 - v0; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "%.3g\n", m }'
}
max_of() { column "$1" "$2" | awk 'NR == 1 || $1 > m { m = $1 } END { printf "%.3g\n", m }'; }
last_of() { column "$1" "$2" | tail -n 1; }
# check NAME CONDITION (awk expression): pass or fail.
check() {
  if awk "BEGIN { exit !($2) }"; then pass "$1"; else fail "$1 ($2)"; fi
}

# ---- every example scene runs (briefly) and writes a valid CSV ----
for s in double_pendulum mode1 mode2 mode3 driven; do
  rm -f "$tmp/out.csv"
  if "$WHIRL" simulate "$scenes/$s.ini" --set run.t_end=0.1 -o "$tmp/out.csv" 2>"$tmp/stderr" \
     && valid_csv "$tmp/out.csv" && [ "$(last_of "$tmp/out.csv" t)" = 0.1 ] \
     && [ ! -s "$tmp/stderr" ]; then
    pass "scene $s runs"
  else fail "scene $s runs ($(head -c 300 "$tmp/stderr"))"; fi
done

# ---- double pendulum (seed 2.4): start, energy conservation, order of the Gauss methods ----
dp="$scenes/double_pendulum.ini"
"$WHIRL" simulate "$dp" --set run.t_end=20 --set run.method=gauss3 -o "$tmp/dp.csv"
row0=$(grep -v '^#' "$tmp/dp.csv" | sed -n 2p)
# tip = l (sin 1.2 + sin(-0.6)), -l (cos 1.2 + cos 0.6); energy = potential = sum m g z_i
check "double pendulum starts at theta = 1.2, -0.6" \
  "$(echo "$row0" | awk -F, '{ x = 0.5 * (sin(1.2) + sin(-0.6)); z = -0.5 * (cos(1.2) + cos(0.6))
     e = 0.5 * (-0.5 * cos(1.2)) + 0.5 * z; d = $2 - x; if (d < 0) d = -d; d2 = $3 - z; if (d2 < 0) d2 = -d2
     d3 = $4 - e; if (d3 < 0) d3 = -d3; print d + d2 + d3 }') < 1e-15"
check "double pendulum gauss3: energy conserved to 1e-11 over t = 20" \
  "$(max_abs_change "$tmp/dp.csv" energy) < 1e-11"
check "double pendulum gauss3: constraint kept to 1e-13" "$(max_of "$tmp/dp.csv" constraint) < 1e-13"
# the energy error shrinks like dt^4 (gauss2) and dt^6 (gauss3): ratios 16 and 64 per halving
for m in gauss2 gauss3; do
  "$WHIRL" simulate "$dp" --set run.t_end=10 --set run.method=$m --set run.dt=0.02 -o "$tmp/a.csv"
  "$WHIRL" simulate "$dp" --set run.t_end=10 --set run.method=$m --set run.dt=0.01 -o "$tmp/b.csv"
  ea=$(max_abs_change "$tmp/a.csv" energy); eb=$(max_abs_change "$tmp/b.csv" energy)
  lo=10; [ $m = gauss3 ] && lo=30
  check "double pendulum $m: energy error ratio $ea / $eb under step halving > $lo" "$ea / $eb > $lo"
done
# the seed's angle formulation and the Cartesian one give the same motion
"$WHIRL" simulate "$dp" --set run.t_end=3 --set run.method=gauss3 --set run.formulation=seed \
  -o "$tmp/seed.csv"
"$WHIRL" simulate "$dp" --set run.t_end=3 --set run.method=gauss3 -o "$tmp/cart.csv"
check "double pendulum: seed and default formulations agree to 1e-9 at t = 3" \
  "$(paste -d, "$tmp/seed.csv" "$tmp/cart.csv" | grep -v '^#' | tail -n 1 |
     awk -F, '{ d = $2 - $7; if (d < 0) d = -d; e = $3 - $8; if (e < 0) e = -e; print d + e }') < 1e-9"

# ---- the exact steady shape of mode 2 (N = 100) stays steady in the co-rotating frame ----
"$WHIRL" simulate "$scenes/mode2.ini" --set start.perturb=0 --set run.t_end=2 -o "$tmp/m2.csv"
check "mode 2, N = 100, rotating frame: deviation < 1e-12 over t = 2" \
  "$(max_of "$tmp/m2.csv" deviation) < 1e-12"
check "mode 2, N = 100, rotating frame: Jacobi integral constant to 1e-12" \
  "$(max_abs_change "$tmp/m2.csv" jacobi) < 1e-12"
# its tip turns at omega = 4 in the inertial frame: angle of the tip at t = 2 is 8 rad
check "mode 2: the tip turns at omega in the inertial frame" \
  "$(grep -v '^#' "$tmp/m2.csv" | awk -F, 'NR == 2 { r0 = $2 } END { pi = atan2(0, -1)
     a = atan2($3, $2) - 8; while (a > pi) a -= 2 * pi; while (a < -pi) a += 2 * pi
     if (a < 0) a = -a; print (r0 > 0) * a }') < 1e-9"
# the perturbation turns each link by exactly perturb: the start's deviation is linear in it
d1=$("$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=0.002 --set start.perturb=1e-4 |
     grep -v '^#' | sed -n 2p | cut -d, -f7)
d2=$("$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=0.002 --set start.perturb=2e-4 |
     grep -v '^#' | sed -n 2p | cut -d, -f7)
check "perturb: start deviation $d1 at 1e-4, $d2 at 2e-4 (ratio 2)" \
  "$d1 > 1e-6 && $d2 / $d1 > 1.999 && $d2 / $d1 < 2.001"
d3=$("$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=0.002 --set start.perturb=1e-4 \
     --set start.seed=2 | grep -v '^#' | sed -n 2p | cut -d, -f7)
check "perturb: another seed, another perturbation" "$d3 != $d1"

# ---- output times, columns, overrides ----
"$WHIRL" simulate "$dp" --set run.t_end=0.12 --set output.every=0.05 --set run.t_end=0.125 \
  --set output.columns=energy >"$tmp/rows.csv"
check "rows at 0, 0.05, 0.1 and t_end = 0.125 (the last --set wins)" \
  "\"$(column "$tmp/rows.csv" t | tr '\n' ' ')\" == \"0 0.05 0.1 0.125 \""
check "only the asked columns" "\"$(grep -v '^#' "$tmp/rows.csv" | head -n 1)\" == \"t,energy\""

# ---- trace: blocks of N + 1 points, pivot first, link lengths kept; driven pivot on its circle ----
"$WHIRL" simulate "$scenes/driven.ini" --set run.t_end=1 --set output.trace="$tmp/trace.dat" \
  --set output.trace_every=0.25 -o "$tmp/driven.csv"
check "trace: 5 blocks of 51 points" \
  "$(grep -c '^# t = ' "$tmp/trace.dat") == 5 && $(grep -c '^[-0-9]' "$tmp/trace.dat") == 255"
check "trace: pivot on the circle of radius 0.05 at omega = 3.5, links of length 1/50" \
  "$(awk '/^# t/ { k = 0; next }
       NF == 4 && k == 0 { px = $1 - 0.05 * cos(3.5 * $4); py = $2 - 0.05 * sin(3.5 * $4)
                           e = sqrt(px * px + py * py + $3 * $3) }
       NF == 4 && k > 0 { e = sqrt(($1 - x)^2 + ($2 - y)^2 + ($3 - z)^2) - 0.02 }
       NF == 4 { if (e < 0) e = -e; if (e > m) m = e; x = $1; y = $2; z = $3; k++ }
       END { print m + 0 }' "$tmp/trace.dat") < 1e-12"
check "trace: last block's tip is the CSV's tip at t = 1" \
  "$(tail -n 1 "$tmp/trace.dat" | cut -d' ' -f1) == $(last_of "$tmp/driven.csv" tip_x)"
# at t = 0 the hanging chain moves with the pivot: lz = M eps (eps omega) = 0.00875
check "driven pivot spins the chain up: lz grows from 0.00875" \
  "($(column "$tmp/driven.csv" lz | head -n 1) - 0.00875)^2 < 1e-30 && $(last_of "$tmp/driven.csv" lz) > 0.013"
out=$(gnuplot -e "trace='$tmp/trace.dat'; out='$tmp/anim.gif'" "$(dirname "$0")/../../plots/animate.gp" 2>&1)
if [ -s "$tmp/anim.gif" ] && [ "$(head -c 3 "$tmp/anim.gif")" = GIF ]; then pass "plots/animate.gp makes a GIF"
else fail "plots/animate.gp makes a GIF ($out)"; fi

# ---- stop condition ----
"$WHIRL" simulate "$scenes/mode2.ini" --set run.stop_deviation=1e-9 --set run.t_end=1 \
  -o "$tmp/stop.csv" 2>"$tmp/stderr"
rc=$?
if [ $rc -eq 0 ] && valid_csv "$tmp/stop.csv" && [ "$(last_of "$tmp/stop.csv" t)" = 0.002 ] \
   && grep -q 'stopped at t = 0.002: deviation' "$tmp/stderr"; then pass "stop_deviation stops the run"
else fail "stop_deviation stops the run (rc=$rc, $(cat "$tmp/stderr"))"; fi

# ---- bad scenes: one line naming file, line and key; no output ----
bad="$tmp/bad.ini"
cat >"$bad" <<'EOF'
[chain]
dim = 2
links = 2
[start]
theta = 0.5, 0.25
[run]
dt = -1
t_end = 1
EOF
expect_error "dt <= 0: file, line and key" "^whirl simulate: $bad:7: \[run\] dt: must be > 0, got -1\$" \
  simulate "$bad" -o "$tmp/out.csv"
expect_error "NaN" "^whirl simulate: $bad: --set run.t_end: must be a finite number \(optionally with s or ms\), got 'nan'\$" \
  simulate "$bad" --set run.dt=0.1 --set run.t_end=nan -o "$tmp/out.csv"
expect_error "list of the wrong length" "$bad: --set chain.lengths: expected 2 values \(links = 2\), got 3\$" \
  simulate "$bad" --set run.dt=0.1 --set chain.lengths=1,1,1 -o "$tmp/out.csv"
expect_error "non-positive mass" "$bad: --set chain.masses: value 2 must be > 0, got 0\$" \
  simulate "$bad" --set run.dt=0.1 --set chain.masses=1,0 -o "$tmp/out.csv"
expect_error "unknown key" "$bad: --set run.damping: unknown key" \
  simulate "$bad" --set run.damping=1 -o "$tmp/out.csv"
expect_error "deviation of a start that is not steady" \
  "$bad: --set output.columns: the deviation needs a reference" \
  simulate "$bad" --set run.dt=0.1 --set output.columns=deviation -o "$tmp/out.csv"
printf '[chain]\ndim = 3\nlinks = 2\n[strat]\n' >"$tmp/bad2.ini"
expect_error "unknown section" "$tmp/bad2.ini:4: \[strat\]: unknown section" \
  simulate "$tmp/bad2.ini" -o "$tmp/out.csv"
grep -v '^dt' "$bad" >"$tmp/bad3.ini"
expect_error "missing key" "^whirl simulate: $tmp/bad3.ini: \[run\] dt: missing\$" \
  simulate "$tmp/bad3.ini" -o "$tmp/out.csv"
expect_error "two starts" "mode2.ini: --set start.hanging: conflicts with \[start\] omega \(line [0-9]+\)" \
  simulate "$scenes/mode2.ini" --set start.hanging=1 -o "$tmp/out.csv"
expect_error "unknown method" "mode2.ini: --set run.method: .*gauss2" \
  simulate "$scenes/mode2.ini" --set run.method=euler -o "$tmp/out.csv"
expect_error "tolerance for a fixed-step method" "mode2.ini: --set run.tol: .*gauss2.* adaptive" \
  simulate "$scenes/mode2.ini" --set run.tol=1e-9 -o "$tmp/out.csv"
expect_error "multistep method without a tolerance" \
  "mode2.ini:[0-9]+: \[run\] dt: the integrator gsl-msadams takes adaptive steps only" \
  simulate "$scenes/mode2.ini" --set run.method=gsl-msadams -o "$tmp/out.csv"
expect_error "mode that does not exist at omega" "mode3.ini:[0-9]+: \[start\] mode: no steady shape" \
  simulate "$scenes/mode3.ini" --set start.omega=3 -o "$tmp/out.csv"
expect_error "missing scene file" "none.ini: cannot read" simulate "$tmp/none.ini" -o "$tmp/out.csv"
expect_error "no scene" "missing the scene file" simulate -o "$tmp/out.csv"

# ---- a run that blows up stops, names time and step, and leaves no file ----
rm -f "$tmp/out.csv" "$tmp/trace.dat"
"$WHIRL" simulate "$scenes/driven.ini" --set run.method=rk4 --set run.dt=0.1 --set run.t_end=50 \
  --set output.every=0.1 --set output.trace="$tmp/trace.dat" -o "$tmp/out.csv" 2>"$tmp/stderr"
rc=$?
# (the step, 0.1, is above half the period of the 50 links' fastest swing: a message says so first)
if [ $rc -ne 0 ] && [ "$(wc -l <"$tmp/stderr")" -eq 2 ] \
   && head -1 "$tmp/stderr" | grep -q 'dt = 0.1 sqrt(L/g) is larger than half the period' \
   && grep -Eq 'after t = [0-9.e-]+ \(step [0-9]+\)' "$tmp/stderr" && [ ! -e "$tmp/out.csv" ] \
   && [ ! -e "$tmp/trace.dat" ] && [ -z "$(ls "$tmp" | grep -E '^(out.csv|trace.dat).')" ]; then
  pass "non-finite state: message, no file"
else fail "non-finite state: message, no file (rc=$rc, $(cat "$tmp/stderr"))"; fi

# ---- Ctrl-C ends a run cleanly with its rows ----
rm -f "$tmp/out.csv"
"$WHIRL" simulate "$scenes/mode2.ini" --set run.t_end=1e5 -o "$tmp/out.csv" 2>"$tmp/stderr" &
pid=$!
i=0
while [ $i -lt 100 ]; do  # until some rows are written (at most 10 s)
  part=$(ls "$tmp" | grep '^out.csv.tmp' | head -n 1)
  [ -n "$part" ] && [ "$(wc -l <"$tmp/$part")" -gt 20 ] && break
  sleep 0.1; i=$((i + 1))
done
kill -INT $pid
wait $pid
rc=$?
if [ $rc -eq 130 ] && valid_csv "$tmp/out.csv" && grep -q 'interrupted at t = ' "$tmp/stderr" \
   && [ -z "$(ls "$tmp" | grep '^out.csv.')" ]; then pass "Ctrl-C keeps a valid CSV"
else fail "Ctrl-C keeps a valid CSV (rc=$rc, $(cat "$tmp/stderr"))"; fi

# [run] threads: two threads on a long chain write the same file, byte for byte
printf '[chain]\ndim = 3\nlinks = 6000\n[start]\nomega = 3\nmode = 2\nperturb = 0.01\n[run]\nframe = rotating\nmethod = rk4\ndt = 2e-6\nt_end = 1e-5\nair_drag = 0.1\n[output]\ncolumns = t, tip_x, tip_y, tip_z, energy, constraint\n' >"$tmp/long.ini"
"$WHIRL" simulate "$tmp/long.ini" -o "$tmp/one.csv" 2>/dev/null
"$WHIRL" simulate "$tmp/long.ini" --set run.threads=2 -o "$tmp/two.csv" 2>/dev/null
if [ -s "$tmp/one.csv" ] && [ "$(grep -vc '^#' "$tmp/one.csv")" -eq 7 ] && cmp -s "$tmp/one.csv" "$tmp/two.csv"; then
  pass "threads = 2: the same rows as one thread"
else fail "threads = 2: the same rows as one thread"; fi
expect_error "threads = 0" "run.threads: must be in 1..256, got 0" simulate "$tmp/long.ini" --set run.threads=0

# internal damping makes 100 links stiff (decay rates up to 16 D N^3 = 8e5 at D = 0.05): the
# failure of the Gauss step, and of rk4, names the stiffness and the method that works; the
# advised method runs; a failure without damping says nothing of it
stiff="the internal damping makes the chain stiff (decay rates up to about 8e+05 sqrt(g/L)"
stiff_re='the internal damping makes the chain stiff \(decay rates up to about 8e\+05 sqrt\(g/L\)'
expect_error "damped 100 links, gauss2: the stiffness named" \
  "Gauss stage iteration diverges.*; $stiff_re, dt x rate = 8\): fixed steps need dt below about 2.5e-06, or use method = gsl-msbdf with tol \(1e-6\); no file written" \
  simulate "$scenes/mode2.ini" --set run.internal_damping=0.05 --set run.dt=1e-5 --set run.t_end=0.1 -o "$tmp/out.csv"
grep -v stop_deviation "$scenes/mode2.ini" >"$tmp/nostop.ini"
expect_error "damped 100 links, rk4: the stiffness named" \
  "right-hand side is not finite.*; $stiff_re, dt x rate = 1.6e\+03\).*gsl-msbdf" \
  simulate "$tmp/nostop.ini" --set run.internal_damping=0.05 --set run.method=rk4 --set run.t_end=0.1 -o "$tmp/out.csv"
"$WHIRL" simulate "$scenes/mode2.ini" --set run.internal_damping=0.05 --set run.method=rk4 \
  --set run.t_end=0.1 -o "$tmp/out.csv" 2>"$tmp/stderr"
grep -q '^whirl simulate: stopped at t = ' "$tmp/stderr" && grep -q "note: $stiff" "$tmp/stderr" \
  && grep -q 'the deviation may be the steps.* instability' "$tmp/stderr" &&
  pass "damped rk4 stopped by its deviation: a note on the stiffness" || fail "damped rk4 stopped: $(cat "$tmp/stderr")"
expect_ok "damped 100 links: method = gsl-msbdf with tol runs" simulate "$scenes/mode2.ini" \
  --set run.internal_damping=0.05 --set run.method=gsl-msbdf --set run.tol=1e-6 --set run.t_end=0.1 -o "$tmp/out.csv"
[ ! -s "$tmp/stderr" ] && [ "$(grep -vc '^#' "$tmp/out.csv")" -gt 2 ] && pass "gsl-msbdf: rows, no message" ||
  fail "gsl-msbdf: $(cat "$tmp/stderr")"
"$WHIRL" simulate "$tmp/nostop.ini" --set run.method=rk4 --set run.dt=0.3 --set run.t_end=3 -o "$tmp/out.csv" 2>"$tmp/stderr"
! grep -q stiff "$tmp/stderr" && pass "no damping: nothing said of stiffness" || fail "no damping: $(cat "$tmp/stderr")"


# air drag makes a chain stiff too: the linear drag -c l_i v_i on a mass m_i decays at the rate
# c l_i / m_i, c = 2000 on data/scenes/driven.ini's 50 equal links (L = M = 1): 2e3, dt x rate
# = 2e-3 x 2e3 = 4, past the Gauss fixed point's 3.46 and rk4's 2.79; the quadratic drag
# -c2 l_i |v_i| v_i at most 2 c2 |v| l_i / m_i with |v| <= omega L: 2 x 1000 x 2 = 4e3 on
# mode1.ini (omega = 2). Each failure names the drag and the method that works, which runs, and
# agrees with rk4 at a step 20 times below the limit (dt = 2e-4: dt x rate = 0.4)
drag_re='the air drag makes the chain stiff \(decay rates up to about 2e\+03 sqrt\(g/L\), dt x rate = 4\): fixed steps need dt below about 0.001, or use method = gsl-msbdf with tol \(1e-6\); no file written'
expect_error "linear drag, gauss2: the stiffness named" "Gauss stage iteration diverges.*; $drag_re" \
  simulate "$scenes/driven.ini" --set run.air_drag=2000 --set run.t_end=0.2 -o "$tmp/out.csv"
expect_error "linear drag, rk4: the stiffness named" "right-hand side is not finite.*; $drag_re" \
  simulate "$scenes/driven.ini" --set run.air_drag=2000 --set run.method=rk4 --set run.t_end=0.2 -o "$tmp/out.csv"
expect_error "quadratic drag, gauss2: the stiffness named" \
  "Gauss stage iteration diverges.*; the air drag makes the chain stiff \(decay rates up to about 4e\+03 sqrt\(g/L\), dt x rate = 8\).*method = gsl-msbdf with tol" \
  simulate "$scenes/mode1.ini" --set run.air_drag_quadratic=1000 --set start.perturb=0 --set run.t_end=0.5 -o "$tmp/out.csv"
expect_error "internal damping and drag: both named" \
  "; the internal damping and the air drag make the chain stiff \(decay rates up to about 9e\+05 sqrt\(g/L\)" \
  simulate "$scenes/mode2.ini" --set run.internal_damping=0.05 --set run.air_drag=1e5 --set run.dt=1e-5 --set run.t_end=0.1 -o "$tmp/out.csv"
expect_ok "linear drag: method = gsl-msbdf with tol runs" simulate "$scenes/driven.ini" --set run.air_drag=2000 \
  --set run.method=gsl-msbdf --set run.tol=1e-6 --set run.t_end=0.2 --set output.every=0.1 -o "$tmp/bdf.csv"
"$WHIRL" simulate "$scenes/driven.ini" --set run.air_drag=2000 --set run.method=rk4 --set run.dt=2e-4 \
  --set run.t_end=0.2 --set output.every=0.1 -o "$tmp/ref.csv" 2>"$tmp/stderr2"
if [ ! -s "$tmp/stderr" ] && [ ! -s "$tmp/stderr2" ] && paste -d, "$tmp/bdf.csv" "$tmp/ref.csv" | awk -F, '
    /^#/ || $1 == "t" { next }
    { rows++; for (i = 2; i <= 4; i++) { d = $i - $(i + 8); if (d < 0) d = -d; if (d > m) m = d } }
    END { exit !(rows == 3 && m < 1e-5) }'; then
  pass "gsl-msbdf on the stiff drag: the tip within 1e-5 of rk4 at dt = 2e-4"
else fail "gsl-msbdf on the stiff drag: $(tail -n 1 "$tmp/bdf.csv") vs $(tail -n 1 "$tmp/ref.csv") $(cat "$tmp/stderr" "$tmp/stderr2")"; fi


# a planar hanging chain perturbed: each link turned by the angle in the x-z plane (was refused:
# the perturbation of space left the plane); one link at 0.01 starts with its tip at
# (+-sin 0.01, 0, -cos 0.01), and the header records the perturbation and its seed
printf '[chain]\ndim = 2\nlinks = 1\n[start]\nhanging = true\nperturb = 0.01\n[run]\nomega = 3\ndt = 0.01\nt_end = 0.01\n' \
  >"$tmp/planar.ini"
if "$WHIRL" simulate "$tmp/planar.ini" -o "$tmp/planar.csv" 2>"$tmp/stderr" &&
   grep -q '^# start: hanging, perturb 0.01 (seed 1)$' "$tmp/planar.csv" &&
   grep -v '^#' "$tmp/planar.csv" | awk -F, 'NR == 2 { x = $2 < 0 ? -$2 : $2
     exit !(x - sin(0.01) < 1e-15 && sin(0.01) - x < 1e-15 && $3 == 0 && $4 + cos(0.01) < 1e-15 &&
            -cos(0.01) - $4 < 1e-15) }'; then
  pass "a perturbed planar hanging chain: turned by 0.01 in the plane, the perturbation in the header"
else fail "a perturbed planar hanging chain: $(cat "$tmp/stderr"; grep -v '^#' "$tmp/planar.csv" | sed -n 2p)"; fi
# five links: every link turned by the angle, y = 0 throughout the run
sed 's/links = 1/links = 5/; s/t_end = 0.01/t_end = 1/' "$tmp/planar.ini" >"$tmp/planar5.ini"
if "$WHIRL" simulate "$tmp/planar5.ini" -o "$tmp/planar5.csv" 2>"$tmp/stderr" &&
   grep -v '^#' "$tmp/planar5.csv" | awk -F, 'NR > 1 && $3 != 0 { bad = 1 } END { exit bad || NR < 50 }'; then
  pass "a perturbed planar chain of 5 links runs in its plane"
else fail "a perturbed planar chain of 5 links: $(cat "$tmp/stderr")"; fi

finish
