#!/bin/sh
# Pictures: `whirl shape --plot` (several rates on one figure, true to scale, labels in the
# user's units), `whirl plot` (the kind of a file from its header; files of different kinds or
# units refused), no partial picture on failure; checked on the SVG's curves (their extent against
# the CSV's, independently of the program) and the PNG's header.
. "$(dirname "$0")/lib.sh"
tools=$(dirname "$0")/../tools
si="--length 60cm --mass 50g"

# the teacher's figure: three rates in Hz, one mode
expect_ok "shape: 2Hz,4Hz,6Hz --mode 2 --plot PNG" shape $si --omega 2Hz,4Hz,6Hz --mode 2 \
  --plot "$tmp/shapes.png"
if [ "$(head -c 8 "$tmp/shapes.png" | od -An -c | tr -d ' ')" = '211PNG\r\n032\n' ]; then
  pass "shape --plot: a PNG"; else fail "shape --plot: a PNG"; fi
expect_ok "shape --plot SVG" shape $si --omega 2Hz,4Hz,6Hz --mode 2 --plot "$tmp/shapes.svg"
expect_ok "shape --plot PDF" shape $si --omega 2Hz,4Hz,6Hz --mode 2 --plot "$tmp/shapes.pdf"
head -c 5 "$tmp/shapes.pdf" | grep -q '%PDF-' && pass "shape --plot: a PDF" || fail "shape --plot: a PDF"
# each curve labelled with its mode and its rate as given, short
for f in 2 4 6; do
  grep -q ">mode 2, $f Hz<" "$tmp/shapes.svg" && pass "label 'mode 2, $f Hz'" ||
    fail "label 'mode 2, $f Hz'"
done
grep -q '>pivot<' "$tmp/shapes.svg" && grep -q '>rotation axis<' "$tmp/shapes.svg" &&
  pass "the pivot and the rotation axis named" || fail "the pivot and the rotation axis named"
# true aspect ratio: the 2 Hz curve's extent in the picture over its extent in the CSV, the same
# scale across and down (to 2%, the picture's coordinates having 2 decimals)
"$WHIRL" shape $si --omega 2Hz --mode 2 -o "$tmp/s2.csv"
box=$(python3 "$tools/svg_extent.py" "$tmp/shapes.svg" 31,78,156)
data=$(grep -v '^#' "$tmp/s2.csv" | tail -n +2 | awk -F, 'NR == 1 { r0 = r1 = $2; z0 = z1 = $3 }
  { if ($2 < r0) r0 = $2; if ($2 > r1) r1 = $2; if ($3 < z0) z0 = $3; if ($3 > z1) z1 = $3 }
  END { print r1 - r0, z1 - z0 }')
if echo "$box $data" | awk '{ sx = ($3 - $1) / $6; sy = ($4 - $2) / $7; d = sx / sy - 1;
     if (d < 0) d = -d; print "# px per m across " sx ", down " sy; exit !($5 > 100 && d < 0.02) }'; then
  pass "true to scale: the same px per m across and down"; else fail "true to scale ($box / $data)"; fi
# the CSV names the rate as given
grep -q '^# rate: 2 Hz (omega=12.57 rad/s)$' "$tmp/s2.csv" && pass "shape: '# rate: 2 Hz (omega=12.57 rad/s)'" ||
  fail "shape: the rate line ($(grep '^# rate' "$tmp/s2.csv"))"
"$WHIRL" shape $si --omega 240rpm --mode 2 -o "$tmp/r.csv"
grep -q '^# rate: 240 rpm (omega=25.13 rad/s, 4 Hz)$' "$tmp/r.csv" && pass "shape: rpm and Hz" ||
  fail "shape: rpm ($(grep '^# rate' "$tmp/r.csv"))"
# one mode per rate
expect_ok "shape: a mode per rate" shape $si --omega 2Hz,6Hz --mode 1,3 --plot "$tmp/m.svg"
grep -q '>mode 1, 2 Hz<' "$tmp/m.svg" && grep -q '>mode 3, 6 Hz<' "$tmp/m.svg" &&
  pass "labels of a mode per rate" || fail "labels of a mode per rate"

# bad input: one line, non-zero, no picture (not even a temporary one)
rm -rf "$tmp/pics"; mkdir "$tmp/pics"
expect_error "--plot: an unknown extension" 'a figure is written as .png, .svg or .pdf' \
  shape $si --omega 4Hz --mode 2 --plot "$tmp/pics/x.jpg"
expect_error "--mode: neither one nor one per rate" 'one per rate' shape $si --omega 2Hz,4Hz,6Hz \
  --mode 1,2 --plot "$tmp/pics/x.png"
expect_error "several rates without --plot" 'draw them with --plot' shape $si --omega 2Hz,4Hz --mode 1
expect_error "a mode that does not exist at one rate: no picture" 'mode 2 does not exist' \
  shape $si --omega 1Hz,4Hz --mode 2 --plot "$tmp/pics/x.png"
[ -z "$(ls -A "$tmp/pics")" ] && pass "failures leave no file in the picture's folder" ||
  fail "failures leave files: $(ls -A "$tmp/pics")"

# whirl plot: shapes from files, a sweep, a stability map; refusals
"$WHIRL" shape $si --omega 4Hz --mode 2 -o "$tmp/s4.csv"
expect_ok "plot: two shape files" plot "$tmp/s2.csv" "$tmp/s4.csv" -o "$tmp/p.svg"
grep -q '>mode 2, 4 Hz<' "$tmp/p.svg" && pass "plot: labels from the files" || fail "plot: labels"
"$WHIRL" sweep --modes 1,2 --omega-min 2 --omega-max 6 --omega-count 9 -o "$tmp/b.csv"
expect_ok "plot: branches" plot "$tmp/b.csv" -o "$tmp/b.png"
"$WHIRL" shape --omega 4 --mode 2 -o "$tmp/d.csv"
expect_error "plot: files of different kinds" 'one figure shows files of one kind' \
  plot "$tmp/s2.csv" "$tmp/b.csv" -o "$tmp/pics/x.png"
expect_error "plot: files in different units" 'in different units' \
  plot "$tmp/s2.csv" "$tmp/d.csv" -o "$tmp/pics/x.png"
printf 'a,b\n1,2\n' >"$tmp/other.csv"
expect_error "plot: a file not of whirl's" 'not a file of whirl' plot "$tmp/other.csv" -o "$tmp/pics/x.png"
expect_error "plot: no -o" '-o is required|--output is required' plot "$tmp/s2.csv"
expect_error "plot: a missing file" 'cannot read' plot "$tmp/none.csv" -o "$tmp/pics/x.png"
[ -z "$(ls -A "$tmp/pics")" ] && pass "plot: failures leave no file" || fail "plot: files left: $(ls -A "$tmp/pics")"
finish
