#!/bin/sh
# Command-line tests of the pivot's path in whirl simulate (--pivot PATH and the scene's [run]
# pivot): the same run either way, the circle path against the model's circle drive, the
# vertically shaken pendulum inside Mathieu's first tongue growing per period by whirl
# periodic's largest multiplier, the shaken inverted double pendulum staying up where the
# unshaken one falls (Acheson), SI units, bad input.
. "$(dirname "$0")/lib.sh"

# rows FILE: the CSV without its comment lines
rows() { grep -v '^#' "$1"; }
# max_diff A B: the largest |a - b| over the numbers of two CSVs of the same shape (header and
# rows), or "shape" if they differ in shape
max_diff() {
  rows "$1" >"$tmp/da"
  rows "$2" >"$tmp/db"
  if [ "$(wc -l <"$tmp/da")" -ne "$(wc -l <"$tmp/db")" ] \
     || [ "$(head -1 "$tmp/da")" != "$(head -1 "$tmp/db")" ]; then echo shape; return; fi
  paste -d, "$tmp/da" "$tmp/db" | awk -F, 'NR > 1 { h = NF / 2
      for (i = 1; i <= h; i++) { d = $i - $(i + h); if (d < 0) d = -d; if (d > m) m = d } }
    END { printf "%.3g\n", m }'
}

cat >"$tmp/hang.ini" <<'EOF'
[chain]
dim = 3
links = 5
[start]
hanging = true
perturb = 0.01
[run]
omega = 3
dt = 0.00390625
t_end = 4
[output]
every = 0.0625
EOF
# ---- the option and the key: the same run, the same CSV (the first line names the scene) ----
sed 's/^t_end = 4$/t_end = 4\npivot = ellipse:0.1,0.06/' "$tmp/hang.ini" >"$tmp/key.ini"
expect_ok "--pivot runs" simulate "$tmp/hang.ini" --pivot ellipse:0.1,0.06 -o "$tmp/opt.csv"
expect_ok "[run] pivot runs" simulate "$tmp/key.ini" -o "$tmp/key.csv"
expect_ok "--set run.pivot runs" simulate "$tmp/hang.ini" --set run.pivot=ellipse:0.1,0.06 -o "$tmp/set.csv"
if [ "$(sed 1d "$tmp/opt.csv" | md5sum)" = "$(sed 1d "$tmp/key.csv" | md5sum)" ] \
   && cmp -s "$tmp/opt.csv" "$tmp/set.csv" \
   && grep -qx '# pivot = fourier:x1c=0.1,y1s=0.06' "$tmp/opt.csv" \
   && [ "$(rows "$tmp/opt.csv" | wc -l)" -eq 66 ]; then
  pass "--pivot, [run] pivot and --set run.pivot: the same CSV"
else fail "--pivot, [run] pivot and --set run.pivot: the same CSV"; fi
# --pivot replaces the scene's key
expect_ok "--pivot over [run] pivot" simulate "$tmp/key.ini" --pivot vertical:0.05 -o "$tmp/over.csv"
if grep -qx '# pivot = fourier:z1c=0.05' "$tmp/over.csv"; then pass "--pivot replaces [run] pivot"
else fail "--pivot replaces [run] pivot"; fi

# ---- the circle path of radius eps against the model's own circle drive (drive_radius): the
# same integrator and step in the inertial frame, the same motion to round-off (the path's
# formulas round as the drive's: whirl_pivot_eval); the trace's pivot too ----
expect_ok "circle path" simulate "$tmp/hang.ini" --pivot circle:0.08 --set output.trace="$tmp/tp.dat" -o "$tmp/circle.csv"
expect_ok "circle drive" simulate "$tmp/hang.ini" --set run.drive_radius=0.08 --set output.trace="$tmp/td.dat" -o "$tmp/drive.csv"
d=$(max_diff "$tmp/circle.csv" "$tmp/drive.csv")
moved=$(rows "$tmp/circle.csv" | awk -F, 'NR > 2 { d = $2 - 0.08; if (d < 0) d = -d; if (d > m) m = d } END { print m }')
echo "# circle path vs drive_radius, 5 links, 256 steps of gauss2: largest difference $d (the tip moved $moved)"
pivot_d=$(paste -d' ' "$tmp/tp.dat" "$tmp/td.dat" | awk '!/^#/ && NF == 8 { for (i = 1; i <= 4; i++) { x = $i - $(i + 4); if (x < 0) x = -x; if (x > m) m = x }; n++ }
  END { if (n != 65 * 6) print "few"; else printf "%.3g\n", m }')
if [ "$d" != shape ] && awk -v d="$d" -v m="$moved" -v p="$pivot_d" \
     'BEGIN { exit !(d < 1e-13 && m > 0.05 && p != "few" && p < 1e-15) }'; then
  pass "circle path = drive_radius to round-off ($d)"
else fail "circle path = drive_radius to round-off ($d, moved $moved, trace $pivot_d)"; fi

# the traces' first lines: the drive names its radius (eps=0.08), the path its terms in place of
# eps (which would say 0, a pivot at rest), as the CSV's "# pivot =" line; that text run again is
# the same motion; whirl view draws the drive's circle, and for the path none (its eps 0)
path=$(sed -n '1s/^# trace: .* omega=3 pivot=\([^ ]*\) drag=0 drag_quadratic=0 links=5$/\1/p' "$tmp/tp.dat")
expect_ok "the trace's path run again" simulate "$tmp/hang.ini" --pivot "$path" -o "$tmp/again.csv"
expect_ok "view of the path's trace" view "$tmp/tp.dat" -o "$tmp/tp.html"
expect_ok "view of the drive's trace" view "$tmp/td.dat" -o "$tmp/td.html"
if [ "$path" = "fourier:x1c=0.08,y1s=0.08" ] && ! head -1 "$tmp/tp.dat" | grep -q 'eps=' \
   && grep -qx "# pivot = $path" "$tmp/circle.csv" \
   && head -1 "$tmp/td.dat" | grep -q ' omega=3 eps=0.08 drag=0 ' && ! head -1 "$tmp/td.dat" | grep -q 'pivot=' \
   && cmp -s "$tmp/again.csv" "$tmp/circle.csv" \
   && grep -q '"eps": 0,' "$tmp/tp.html" && grep -q '"eps": 0.08000000000000000[0-9]*,' "$tmp/td.html"; then
  pass "trace header: the path named by its terms (no eps=0), read back to the same motion"
else fail "trace header: the path ($path; $(head -1 "$tmp/tp.dat"))"; fi

# ---- Mathieu: the pendulum (N = 1, planar) shaken vertically, A cos(omega t), A = 0.05, at
# omega = 2 (inside the first tongue), from theta = 1e-8 at rest: its swing at t = k T (T the
# period, 400 steps of gauss2 each) grows per period by whirl periodic's largest multiplier's
# modulus. The ratio over periods 30..60 (the decaying multiplier's part is then below 1e-4 of
# the growing one's; the swing stays below 2e-4 rad, linear): measured 2.7e-6 relative; the
# test allows 1e-4 ----
expect_ok "periodic Mathieu" periodic --pivot vertical:0.05 --omega 2 --links 1 --dim 2 -o "$tmp/mu.csv"
mu=$(sed -n 's/^# |mu|max=\([^ ]*\) .*/\1/p' "$tmp/mu.csv")
cat >"$tmp/mathieu.ini" <<'EOF'
[chain]
dim = 2
links = 1
[start]
theta = 1e-8
[run]
omega = 2
dt = 0.007853981633974483
t_end = 188.49555921538757
[output]
every = 3.141592653589793
columns = t, tip_x, tip_z
EOF
expect_ok "Mathieu run" simulate "$tmp/mathieu.ini" --pivot vertical:0.05 -o "$tmp/m.csv"
growth=$(rows "$tmp/m.csv" | awk -F, 'NR > 1 { x[NR - 2] = $2 < 0 ? -$2 : $2 }
  END { if (NR != 62) print "rows"; else printf "%.12g\n", exp(log(x[60] / x[30]) / 30) }')
echo "# Mathieu (A = 0.05, omega = 2): growth per period $growth, whirl periodic's |mu|max $mu"
if [ -n "$mu" ] && [ "$growth" != rows ] && awk -v g="$growth" -v m="$mu" \
     'BEGIN { r = (g - m) / m; if (r < 0) r = -r; exit !(m > 1.1 && r < 1e-4) }'; then
  pass "Mathieu: growth per period = |mu|max to 1e-4"
else fail "Mathieu: growth per period $growth vs |mu|max $mu"; fi

# ---- Acheson: the double pendulum (2 links, planar) started 0.04 rad from upright stays up
# for 477 periods when its pivot is shaken vertically, A = 0.02 L at omega = 100 sqrt(g/L)
# (whirl periodic: the inverted motion neutral, its multipliers on the unit circle), and falls
# without the shaking ----
expect_ok "periodic inverted" periodic --pivot vertical:0.02 --omega 100 --links 2 --dim 2 --start inverted -o "$tmp/inv.csv"
cat >"$tmp/up.ini" <<'EOF'
[chain]
dim = 2
links = 2
[start]
theta = 3.1, 3.1
[run]
omega = 100
dt = 3.14159265358979e-4
t_end = 30
[output]
every = 0.05
columns = t, tip_x, tip_z
EOF
expect_ok "shaken inverted" simulate "$tmp/up.ini" --pivot vertical:0.02 -o "$tmp/up.csv"
expect_ok "unshaken inverted" simulate "$tmp/up.ini" --pivot vertical:0 -o "$tmp/down.csv"
low_up=$(rows "$tmp/up.csv" | awk -F, 'NR > 1 && (NR == 2 || $3 < m) { m = $3 } END { print m }')
low_down=$(rows "$tmp/down.csv" | awk -F, 'NR > 1 && (NR == 2 || $3 < m) { m = $3 } END { print m }')
echo "# Acheson: the tip's lowest height shaken $low_up, unshaken $low_down (upright: 1)"
if grep -q '^# verdict=neutral' "$tmp/inv.csv" && [ "$(rows "$tmp/up.csv" | wc -l)" -eq 602 ] \
   && awk -v u="$low_up" -v d="$low_down" 'BEGIN { exit !(u > 0.95 && d < 0) }'; then
  pass "Acheson: the shaken inverted chain stays up, the unshaken one falls"
else fail "Acheson: the shaken inverted chain stays up ($low_up), the unshaken one falls ($low_down)"; fi

# ---- SI units: the path in cm, the rate in Hz; the same run as the dimensionless one scaled
# (L = 0.5 m: lengths over 0.5 m; the rate over sqrt(g/L)) ----
cat >"$tmp/si.ini" <<'EOF'
[units]
system = SI
[chain]
dim = 3
links = 3
length = 50cm
mass = 50g
[start]
hanging = true
[run]
omega = 2Hz
dt = 1ms
t_end = 0.5
pivot = ellipse:2cm,1cm
[output]
every = 0.1
EOF
expect_ok "SI path" simulate "$tmp/si.ini" -o "$tmp/si.csv"
if grep -qx '# pivot = fourier:x1c=0.02,y1s=0.01' "$tmp/si.csv" && grep -q '^# units: length=m' "$tmp/si.csv" \
   && rows "$tmp/si.csv" | awk -F, 'NR == 2 { d = $4 + 0.5; exit !($2 == 0.02 && $3 == 0 && d * d < 1e-30) }'; then
  pass "SI path: lengths in m, the pivot at (2 cm, 0) at t = 0"
else fail "SI path: lengths in m, the pivot at (2 cm, 0) at t = 0"; fi

# ---- --help and bad input: one line naming the option or the key, exit 1, nothing written ----
expect_ok "--help" simulate --help
if grep -q -- '--pivot PATH' "$tmp/stdout" && grep -q 'circle:R, ellipse:A,B' "$tmp/stdout"; then
  pass "--help shows --pivot"; else fail "--help shows --pivot"; fi
expect_error "unknown path" "^whirl simulate: --pivot: pivot path 'square': unknown kind" simulate "$tmp/hang.ini" --pivot square:1 -o "$tmp/out.csv"
expect_error "unit in a dimensionless scene" "^whirl simulate: --pivot: 'circle:1cm' has a unit, but the scene is dimensionless" simulate "$tmp/hang.ini" --pivot circle:1cm -o "$tmp/out.csv"
expect_error "bad length" "^whirl simulate: --pivot: .*ellipse B: 'abc' is not a length" simulate "$tmp/hang.ini" --pivot ellipse:0.1,abc -o "$tmp/out.csv"
expect_error "rotating frame" "^whirl simulate: --pivot: a pivot path needs \[run\] frame = inertial" simulate "$tmp/hang.ini" --pivot circle:0.1 --set run.frame=rotating -o "$tmp/out.csv"
expect_error "with drive_radius" "^whirl simulate: --pivot: a pivot path conflicts with \[run\] drive_radius" simulate "$tmp/hang.ini" --pivot circle:0.1 --set run.drive_radius=0.1 -o "$tmp/out.csv"
expect_error "no rate" "^whirl simulate: --pivot: a pivot path needs \[run\] omega > 0" simulate "$tmp/hang.ini" --pivot circle:0.1 --set run.omega=0 -o "$tmp/out.csv"
expect_error "y term in 2D" "^whirl simulate: --pivot: .*y1s moves the pivot out of the x-z plane" simulate "$tmp/mathieu.ini" --pivot ellipse:0.1,0.1 -o "$tmp/out.csv"
expect_error "empty" "^whirl simulate: --pivot: must not be empty" simulate "$tmp/hang.ini" --pivot "" -o "$tmp/out.csv"
expect_error "no value" "^whirl simulate: option --pivot needs a value" simulate "$tmp/hang.ini" --pivot
expect_error "given twice" "^whirl simulate: .*--pivot" simulate "$tmp/hang.ini" --pivot circle:0.1 --pivot circle:0.2 -o "$tmp/out.csv"
sed 's/^pivot = .*/pivot = circle:abc/' "$tmp/key.ini" >"$tmp/bad.ini"
expect_error "bad key" "^whirl simulate: $tmp/bad.ini:11: \[run\] pivot: pivot path: circle R: 'abc' is not a length" simulate "$tmp/bad.ini" -o "$tmp/out.csv"
expect_error "bad override" "^whirl simulate: $tmp/hang.ini: --set run.pivot: pivot path: circle R: 'x' is not a length" simulate "$tmp/hang.ini" --set run.pivot=circle:x -o "$tmp/out.csv"
# a step too long for the path's fastest harmonic: a note, the run goes on
expect_ok "coarse step" simulate "$tmp/hang.ini" --pivot fourier:x1c=0.01,z8c=0.001 --set run.dt=0.1 --set run.t_end=0.2
if grep -q "larger than a quarter of the pivot path's period" "$tmp/stderr"; then
  pass "coarse step: a note names the path's period"; else fail "coarse step: a note names the path's period"; fi
finish
