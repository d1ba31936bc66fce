#!/bin/sh
# Command-line tests of whirl view: the page it writes for a shape and for a trace, loaded in a
# real headless browser (Debian's chromium): no console message at all (the page logs nothing,
# so any line is an error), and the chain drawn where the projection puts it, with equal scaling
# of the axes (the box of the chain's pixels in the screenshot against the shape's own extent).
# The browser part runs in the plain half; the sanitizer half runs whirl view itself.
. "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)

# One headless Chromium for all the pages of this test (tests/tools/page.py), each page in a tab
# of its own, 800 x 600: browser URL SHOT takes a screenshot, dom URL prints the page's body tag
# after its script ran (its data- attributes); both put the page's console messages, one a line,
# into $tmp/console (the page logs nothing, so any line is an error).
if [ -z "$WHIRL_SANITIZE" ]; then
  started=$(/usr/bin/python3 "$here/../tools/page.py" start "$tmp/chromium")
  port=${started% *} chromium_pid=${started#* }
  [ -n "$started" ] || { echo "not ok 1 - headless chromium does not start"; echo "1..1"; exit 1; }
  # the browser's processor time (all its processes, its reaped children included), for the record
  stop_chromium() {
    for p in $(ps -s "$chromium_pid" -o pid= 2>/dev/null); do cat "/proc/$p/stat" 2>/dev/null; done |
      awk -v hz="$(getconf CLK_TCK)" '{ sub(/^.*\) /, ""); s += $12 + $13 + $14 + $15 }
        END { printf "# chromium: %.1f s of processor time\n", s / hz }'
    kill -TERM "-$chromium_pid" 2>/dev/null
    i=0
    while kill -0 "$chromium_pid" 2>/dev/null && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    rm -rf "$tmp"
  }
  trap stop_chromium EXIT
fi
browser() {
  timeout 120 /usr/bin/python3 "$here/../tools/page.py" shot "$port" "file://$1" "$2" "$tmp/console" ||
    echo "page.py shot failed" >"$tmp/console"
}
dom() {
  timeout 120 /usr/bin/python3 "$here/../tools/page.py" dom "$port" "file://$1" "$tmp/console" ||
    echo "page.py dom failed" >"$tmp/console"
}
attr() { echo "$1" | sed -n "s/.* data-$2=\"\([^\"]*\)\".*/\1/p"; }

# ---- a mode-2 shape, seen from the front (camera 0,0): the page's layout puts the shape's height
# over 84% of the canvas (800 wide, below the bar) unless its width limits it ----
"$WHIRL" shape --omega 3 --mode 2 --points 81 -o "$tmp/s2.csv"
expect_ok "view of a shape" view "$tmp/s2.csv" --camera 0,0 -o "$tmp/s2.html"
if grep -q '"kind": "shapes"' "$tmp/s2.html" && grep -q '"omega": 3,' "$tmp/s2.html" &&
   ! grep -q 'http' "$tmp/s2.html"; then pass "shape page: data block, omega, no network address"
else fail "shape page: data block, omega, no network address"; fi

if [ -z "$WHIRL_SANITIZE" ]; then
  browser "$tmp/s2.html" "$tmp/s2.png"
  if [ -s "$tmp/s2.png" ] && [ ! -s "$tmp/console" ]; then pass "shape page loads without console messages"
  else fail "shape page loads without console messages ($(head -c 300 "$tmp/console"))"; fi
  # the canvas below the bar (the bar's height from the page), the labels left out (#nolabels)
  browser "$tmp/s2.html#nolabels" "$tmp/s2.png"
  top=$(attr "$(dom "$tmp/s2.html")" canvas | cut -d' ' -f3)
  cw=800 ch=$((600 - top))
  box=$(/usr/bin/python3 "$here/../tools/png_extent.py" "$tmp/s2.png" 1f4e9c "$top")
  expect=$(awk -F, -v cw="$cw" -v ch="$ch" '!/^#/ && NR > 1 && $1 != "s" { if (!n++) { x0 = x1 = $2; z0 = z1 = $3 }
      if ($2 < x0) x0 = $2; if ($2 > x1) x1 = $2; if ($3 < z0) z0 = $3; if ($3 > z1) z1 = $3 }
      END { r = (x1 > -x0 ? x1 : -x0); h = (z1 > 0 ? z1 : 0) - z0
            s = cw * 0.84 / (2 * r); t = ch * 0.84 / h; if (t < s) s = t
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

# ---- the teacher's shapes (60 cm, 50 g; 2, 4, 6 Hz): labels "mode 2, F Hz" inside the 800-px
# window, the summary not clipped, no clock, the side view by default (the same pixels as
# --camera 0,0), a PNG of the view ----
for f in 2 4 6; do "$WHIRL" shape --length 60cm --mass 50g --omega ${f}Hz --mode 2 -o "$tmp/h$f.csv"; done
expect_ok "view of three shapes in Hz" view "$tmp/h2.csv" "$tmp/h4.csv" "$tmp/h6.csv" -o "$tmp/h.html"
grep -q '"label": "mode 2, 2 Hz"' "$tmp/h.html" && grep -q '"label": "mode 2, 6 Hz"' "$tmp/h.html" &&
  grep -q '"summary": "mode 2, 2 Hz; mode 2, 4 Hz; mode 2, 6 Hz"' "$tmp/h.html" &&
  pass "labels and summary: mode and rate in Hz as given" || fail "labels and summary in Hz"
"$WHIRL" view "$tmp/s2.csv" -o "$tmp/s2side.html"
if [ -z "$WHIRL_SANITIZE" ]; then
  body=$(dom "$tmp/h.html#export")
  echo "# $body"
  [ ! -s "$tmp/console" ] && pass "shapes page: no console messages" || fail "console: $(head -c 300 "$tmp/console")"
  canvas=$(attr "$body" canvas)
  if [ "$(attr "$body" labels | tr ';' '\n' | awk -v c="$canvas" 'BEGIN { split(c, w, " ") }
      NF == 4 && $1 >= 0 && $3 <= w[1] && $2 >= 0 && $4 <= w[2] { k++ } END { print k + 0 }')" = 3 ]; then
    pass "three labels, each inside the canvas ($canvas)"; else fail "labels: $(attr "$body" labels) in $canvas"; fi
  [ "$(attr "$body" summary-fits)" = yes ] && pass "the summary fits at 800 px" || fail "the summary is clipped"
  [ -z "$(attr "$body" clock)" ] && grep -q 'id="timeline" hidden' "$tmp/h.html" &&
    pass "no clock on static shapes" || fail "a clock on static shapes"
  [ "$(attr "$body" camera)" = "0 0" ] && pass "planar shapes: the side view by default" ||
    fail "camera $(attr "$body" camera)"
  attr "$body" export | grep -Eq '^data:image/png;base64, [0-9]{4,}$' && pass "export: a PNG of the view" ||
    fail "export: $(attr "$body" export)"
  # the default view of the planar shape draws the same pixels as the side view asked for
  a=$(attr "$(dom "$tmp/s2.html")" extent); b=$(attr "$(dom "$tmp/s2side.html")" extent)
  [ -n "$a" ] && [ "$a" = "$b" ] && pass "default view = --camera 0,0 ($a)" || fail "default view $b, side view $a"
fi

# ---- a trace: the time slider and frame stepping, the clock, the summary ----
"$WHIRL" simulate data/scenes/classroom.ini --set run.t_end=1 --set output.trace="$tmp/c.dat" \
  --set output.trace_every=0.1 -o /dev/null
expect_ok "view of the classroom trace" view "$tmp/c.dat" -o "$tmp/c.html"
grep -q '"summary": "30 links, omega = 25.13 rad/s (4 Hz)"' "$tmp/c.html" &&
  pass "trace summary: links, rate in rad/s and Hz" || fail "trace summary"
if [ -z "$WHIRL_SANITIZE" ]; then
  body=$(dom "$tmp/c.html#step=3")
  echo "# $body"
  [ ! -s "$tmp/console" ] && [ "$(attr "$body" frame)" = 3 ] &&
    [ "$(attr "$body" clock)" = "t = 0.30 s (inertial)" ] &&
    pass "three steps forward: frame 3, t = 0.30 s, no console messages" ||
    fail "stepping: frame $(attr "$body" frame), clock $(attr "$body" clock), $(head -c 200 "$tmp/console")"
  grep -q 'id="slider"' "$tmp/c.html" && [ "$(attr "$body" summary-fits)" = yes ] &&
    pass "trace page: a slider, the summary fits" || fail "trace page: slider or summary"
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
