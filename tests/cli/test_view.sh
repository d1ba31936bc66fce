#!/bin/sh
# Command-line tests of whirl view: the page it writes for a shape and for a trace, loaded in a
# real headless browser (Debian's chromium): no console message at all (the page logs nothing,
# so any line is an error), and the chain drawn where the projection puts it, with equal scaling
# of the axes (the box of the chain's pixels in the screenshot against the shape's own extent).
# The browser part runs in the plain half; the sanitizer half runs whirl view itself.
. "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)

# browser URL SHOT: screenshot of an 800 x 600 window; the console lines into $tmp/console
browser() {
  timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars \
    --enable-logging=stderr --v=0 --window-size=800,600 --screenshot="$2" "file://$1" \
    2>"$tmp/chromium.log" >/dev/null
  grep 'CONSOLE' "$tmp/chromium.log" >"$tmp/console"
}

# ---- a mode-2 shape, seen from the front (camera 0,0): the page's layout puts the shape's height
# over 84% of the canvas (800 x 536 below the 64-pixel bar) unless its width limits it ----
"$WHIRL" shape --omega 3 --mode 2 --points 81 -o "$tmp/s2.csv"
expect_ok "view of a shape" view "$tmp/s2.csv" --camera 0,0 -o "$tmp/s2.html"
if grep -q '"kind": "shapes"' "$tmp/s2.html" && grep -q '"omega": 3,' "$tmp/s2.html" &&
   ! grep -q 'http' "$tmp/s2.html"; then pass "shape page: data block, omega, no network address"
else fail "shape page: data block, omega, no network address"; fi

if [ -z "$WHIRL_SANITIZE" ]; then
  browser "$tmp/s2.html" "$tmp/s2.png"
  if [ -s "$tmp/s2.png" ] && [ ! -s "$tmp/console" ]; then pass "shape page loads without console messages"
  else fail "shape page loads without console messages ($(head -c 300 "$tmp/console"))"; fi
  box=$(/usr/bin/python3 "$here/../tools/png_extent.py" "$tmp/s2.png" 1f4e9c 64)
  expect=$(awk -F, '!/^#/ && NR > 1 && $1 != "s" { if (!n++) { x0 = x1 = $2; z0 = z1 = $3 }
      if ($2 < x0) x0 = $2; if ($2 > x1) x1 = $2; if ($3 < z0) z0 = $3; if ($3 > z1) z1 = $3 }
      END { r = (x1 > -x0 ? x1 : -x0); h = (z1 > 0 ? z1 : 0) - z0
            s = 800 * 0.84 / (2 * r); t = 536 * 0.84 / h; if (t < s) s = t
            printf "%.1f %.1f", (x1 - x0) * s, h * s }' "$tmp/s2.csv")
  echo "# chain pixels: $box; expected width and height $expect"
  check_box() {
    echo "$box $expect" | awk '{ w = $3 - $1; h = $4 - $2
      exit !(NF == 7 && (w - $6) ^ 2 < 25 && (h - $7) ^ 2 < 25 && $5 > 300) }'
  }
  if check_box; then pass "shape page: the chain's pixels span the projected extent to 5 px (equal axes)"
  else fail "shape page: the chain's pixels span the projected extent to 5 px (equal axes)"; fi
fi

# ---- a trace of the driven scene (50 links, pivot on a circle): frames, omega from its header ----
"$WHIRL" simulate data/scenes/driven.ini --set run.t_end=2 --set output.trace="$tmp/run.dat" \
  --set output.trace_every=0.5 -o "$tmp/run.csv"
expect_ok "view of a trace" view "$tmp/run.dat" -o "$tmp/run.html"
if grep -q '"kind": "trace"' "$tmp/run.html" && [ "$(grep -c '^{"t": ' "$tmp/run.html")" -eq 5 ] &&
   grep -Eq '"omega": [1-9]' "$tmp/run.html"; then pass "trace page: 5 frames, omega from the trace"
else fail "trace page: 5 frames, omega from the trace"; fi
if [ -z "$WHIRL_SANITIZE" ]; then
  browser "$tmp/run.html" "$tmp/run.png"
  box=$(/usr/bin/python3 "$here/../tools/png_extent.py" "$tmp/run.png" 1f4e9c 64)
  if [ ! -s "$tmp/console" ] && [ "$box" != none ]; then pass "trace page: loads without console messages, draws the chain"
  else fail "trace page: loads without console messages, draws the chain ($box; $(head -c 300 "$tmp/console"))"; fi
fi

# ---- bad input ----
expect_error "no file" "whirl view: give a trace or shape files" view -o "$tmp/out.csv"
expect_error "missing file" "whirl view: .*none.csv: cannot read" view "$tmp/none.csv" -o "$tmp/out.csv"
expect_error "bad camera" "whirl view: --camera needs AZ,EL" view "$tmp/s2.csv" --camera 10 -o "$tmp/out.csv"
expect_error "trace and shape" "whirl view: one trace, or any number of shapes" view "$tmp/run.dat" "$tmp/s2.csv" -o "$tmp/out.csv"
printf 'a,b\n1,2\n' >"$tmp/ab.csv"
expect_error "no shape columns" "whirl view: .*ab.csv:1: a shape needs columns r and z" view "$tmp/ab.csv" -o "$tmp/out.csv"
printf '0 0 0 0\n1 2 x 0\n' >"$tmp/bad.dat"
expect_error "bad trace line" "whirl view: .*bad.dat:2: a trace line needs four finite numbers" view "$tmp/bad.dat" -o "$tmp/out.csv"
finish
