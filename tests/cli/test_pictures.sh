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
grep -q '>pivot (dot) on the rotation axis (dashed)<' "$tmp/shapes.svg" &&
  pass "the pivot and the rotation axis named" || fail "the pivot and the rotation axis named"
# true aspect ratio: the 2 Hz curve's extent in the picture over its extent in the CSV, the same
# scale across and down (to 2%, the picture's coordinates having 2 decimals)
"$WHIRL" shape $si --omega 2Hz --mode 2 -o "$tmp/s2.csv"
box=$(/usr/bin/python3 "$tools/svg_extent.py" "$tmp/shapes.svg" 31,78,156)
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
# whirl plot of the window files: the atlas (the committed one of the guide), windows of the
# N-link chain and of the continuum, intervals with dissipation (the classroom chain, SI units:
# a Hz axis), a file without windows; each to PNG and SVG through whirl, and through
# plots/plot.gp by hand with nothing on gnuplot's stderr (no warning)
gp=$(dirname "$0")/../../plots/plot.gp
cp "$(dirname "$0")/../../docs/guide/atlas.csv" "$tmp/atlas.csv"
"$WHIRL" stability --windows --links 10 --modes 2,3 --omega-min 4.3 --omega-max 8 -o "$tmp/wn.csv"
"$WHIRL" stability --windows --modes 2 --omega-min 4.38 --omega-max 4.42 --scan-step 0.05 \
  --tol 1e-7 -o "$tmp/wc.csv"
"$WHIRL" stability --windows --links 10 --modes 1,2 --omega-min 6 --omega-max 40 --scan-step 0.5 \
  $si --eps 1cm --drag 2.9e-3 --side -1 -o "$tmp/wd.csv"
"$WHIRL" stability --windows --links 10 --modes 2 --omega-min 3 --omega-max 4 -o "$tmp/w0.csv"
[ "$(grep -v '^#' "$tmp/w0.csv" | wc -l)" -eq 1 ] && pass "windows: 3..4 (N = 10) has none" ||
  fail "windows: 3..4 has windows: $(cat "$tmp/w0.csv")"
for f in atlas wn wc wd w0; do
  expect_ok "plot: $f.csv to PNG" plot "$tmp/$f.csv" -o "$tmp/$f.png"
  [ "$(head -c 8 "$tmp/$f.png" | od -An -c | tr -d ' ')" = '211PNG\r\n032\n' ] &&
    pass "plot: $f.png is a PNG" || fail "plot: $f.png is not a PNG"
  expect_ok "plot: $f.csv to SVG" plot "$tmp/$f.csv" -o "$tmp/$f.svg"
  gnuplot -e "file='$tmp/$f.csv'; out='$tmp/g.svg'" "$gp" >"$tmp/gp.out" 2>&1
  [ ! -s "$tmp/gp.out" ] && [ -s "$tmp/g.svg" ] && pass "plots/plot.gp: $f.csv without a warning" ||
    fail "plots/plot.gp: $f.csv: $(head -3 "$tmp/gp.out")"
done
# what each figure says: its title, the rate's unit, the births (atlas), the legend
has() { grep -qF ">$2<" "$tmp/$1.svg" && pass "plot: $1.svg shows '$2'" || fail "plot: $1.svg lacks '$2'"; }
has atlas 'Windows of instability of the whirling chain (continuum), births marked'
has atlas 'birth omega_k'
has wn 'Windows of instability of the whirling chain (10 links)'
has wn 'rotation rate omega [sqrt(g/L)]'
has wc 'Windows of instability of the whirling chain (continuum)'
has wd 'rotation rate omega [rad/s]'
has wd 'rotation frequency omega / 2 pi [Hz]'
has wd 'unstable (growth > 0)'
has wd 'converging (growth &lt; 0)'
has w0 'no window found in the examined ranges'
has w0 'examined range'
# one bar per interval in its verdict's colour (one more: the legend's sample)
for v in 'unstable:192,  57,  43' 'converging: 31, 120, 180'; do
  rows=$(grep -v '^#' "$tmp/wd.csv" | grep -c ",${v%%:*}\$")
  bars=$(grep -cF "fill = 'rgb(${v#*:})'" "$tmp/wd.svg")
  [ "$rows" -gt 0 ] && [ "$bars" -eq $((rows + 1)) ] && pass "plot: $rows ${v%%:*} intervals, $rows bars" ||
    fail "plot: $rows ${v%%:*} intervals, $bars bars of its colour (with the legend's)"
done
# a header like a window file's but of no kind: refused in one line (expect_error), no picture
printf '# units: dimensionless\nmode,links,from,to,something\n2,10,4,5,1\n' >"$tmp/odd.csv"
expect_error "plot: an unknown window-like header" 'not a file of whirl' plot "$tmp/odd.csv" -o "$tmp/pics/x.png"
expect_error "plot: no -o" '-o is required|--output is required' plot "$tmp/s2.csv"
expect_error "plot: a missing file" 'cannot read' plot "$tmp/none.csv" -o "$tmp/pics/x.png"
[ -z "$(ls -A "$tmp/pics")" ] && pass "plot: failures leave no file" || fail "plot: files left: $(ls -A "$tmp/pics")"

# simulate --animate: the teacher's run as MP4 and as GIF (under 1 MB for 5 s), cropped to what
# is drawn (ffprobe's size below the frame gnuplot draws, 640 x 736); a trace by whirl plot
scene=$(dirname "$0")/../../data/scenes/classroom.ini
expect_ok "simulate --animate MP4" simulate "$scene" --set start.omega=4Hz --set run.t_end=2 \
  --animate "$tmp/run.mp4"
[ ! -s "$tmp/stdout" ] && pass "--animate without -o: no CSV on stdout" || fail "--animate: CSV on stdout"
probe() { ffprobe -v error -select_streams v:0 -count_frames -show_entries \
  stream=codec_name,width,height,nb_read_frames -of csv=p=0 "$1"; }
info=$(probe "$tmp/run.mp4")
echo "# run.mp4: $info"
echo "$info" | awk -F, '{ exit !($1 == "h264" && $2 < 640 && $3 < 736 && $4 == 51) }' &&
  pass "MP4: H.264, cropped, 51 frames for 2 s (t = 0 to 2 s every 1/25 s)" || fail "MP4: $info"
expect_ok "simulate --animate GIF, 5 s" simulate "$scene" --set start.omega=4Hz --animate "$tmp/run.gif"
size=$(wc -c <"$tmp/run.gif")
info=$(probe "$tmp/run.gif")
echo "# run.gif: $size bytes, $info"
[ "$size" -lt 1000000 ] && echo "$info" | awk -F, '{ exit !($1 == "gif" && $4 == 126) }' &&
  pass "GIF: under 1 MB for 5 s (126 frames)" || fail "GIF: $size bytes, $info"
expect_error "--animate: an unknown extension" 'an animation is written as .mp4, .webm or .gif' \
  simulate "$scene" --animate "$tmp/pics/run.avi"
"$WHIRL" simulate "$scene" --set run.dt=0.5 --set run.t_end=1 --animate "$tmp/pics/run.mp4" \
  -o "$tmp/pics/out.csv" 2>"$tmp/stderr" && fail "--animate: a failed run exits 0" ||
  { grep -q 'dt = 0.5 s is larger than a quarter of the rotation period (0.25 s)' "$tmp/stderr" &&
    grep -q 'no file written' "$tmp/stderr" && pass "--animate: a failed run, dt named, no file" ||
    fail "--animate: a failed run: $(cat "$tmp/stderr")"; }
[ -z "$(ls -A "$tmp/pics")" ] && pass "animate: failures leave no file" || fail "animate: left $(ls -A "$tmp/pics")"
"$WHIRL" simulate "$scene" --set run.t_end=0.4 --set output.trace="$tmp/t.dat" -o "$tmp/t.csv"
expect_ok "plot: a trace to WebM" plot "$tmp/t.dat" -o "$tmp/t.webm"
probe "$tmp/t.webm" | grep -q '^vp9,' && pass "WebM: VP9" || fail "WebM: $(probe "$tmp/t.webm")"
expect_error "plot: a trace to PNG" 'an animation is written as' plot "$tmp/t.dat" -o "$tmp/pics/t.png"

# a figure of flat shapes (drawn 260 px high, more than they need): the curves inside the
# picture and true to scale (the box's margins were divided as integers: the box fell off the
# bottom of the picture)
"$WHIRL" shape --omega 3 --mode 1 -o "$tmp/f3.csv"
expect_ok "shape --plot: flat shapes" shape --omega 3,5 --mode 1 --plot "$tmp/flat.svg"
box=$(/usr/bin/python3 "$tools/svg_extent.py" "$tmp/flat.svg" 31,78,156)
height=$(grep -o ' height="[0-9.]*"' "$tmp/flat.svg" | head -1 | tr -dc '0-9.')
data=$(grep -v '^#' "$tmp/f3.csv" | tail -n +2 | awk -F, 'NR == 1 { r0 = r1 = $2; z0 = z1 = $3 }
  { if ($2 < r0) r0 = $2; if ($2 > r1) r1 = $2; if ($3 < z0) z0 = $3; if ($3 > z1) z1 = $3 }
  END { print r1 - r0, z1 - z0 }')
if echo "$box $height $data" | awk '{ sx = ($3 - $1) / $7; sy = ($4 - $2) / $8; d = sx / sy - 1;
     if (d < 0) d = -d; exit !($5 > 100 && d < 0.02 && $2 > 0 && $4 < $6 && sx > 300) }'; then
  pass "flat shapes: inside the picture, true to scale"; else fail "flat shapes ($box in $height / $data)"; fi

# branches: the title names the user's file, not the copy whirl plot draws from
expect_ok "plot: branches to SVG" plot "$tmp/b.csv" -o "$tmp/b.svg"
grep -qF '>Branches of steady shapes: b.csv<' "$tmp/b.svg" && ! grep -q 'f1\.csv' "$tmp/b.svg" &&
  pass "branches: titled with the file's name" || fail "branches: the title ($(grep -o 'Branches[^<]*' "$tmp/b.svg"))"
grep -qF '>mode 1<' "$tmp/b.svg" && grep -qF '>mode 2<' "$tmp/b.svg" && ! grep -qF '>mode 3<' "$tmp/b.svg" &&
  pass "branches: a key entry per mode in the file" || fail "branches: the key's entries"

# --size, --present: the picture fits the box, whole (its proportions kept)
png_size() { /usr/bin/python3 -c 'import struct, sys; d = open(sys.argv[1], "rb").read(24); print(*struct.unpack(">II", d[16:24]))' "$1"; }
expect_ok "plot --size 800" plot "$tmp/b.csv" -o "$tmp/b800.png" --size 800
[ "$(png_size "$tmp/b800.png")" = "800 360" ] && pass "--size 800: 800 x 360 (1200 x 540 scaled)" ||
  fail "--size 800: $(png_size "$tmp/b800.png")"
expect_ok "plot --present" plot "$tmp/b.csv" -o "$tmp/bp.png" --present
[ "$(png_size "$tmp/bp.png")" = "1920 864" ] && pass "--present: 1920 x 864 in 1920 x 1080" ||
  fail "--present: $(png_size "$tmp/bp.png")"
expect_ok "shape --plot --present --size 1280x720" shape $si --omega 2Hz,4Hz,6Hz --mode 2 \
  --plot "$tmp/sp.png" --present --size 1280x720
png_size "$tmp/sp.png" | awk '{ exit !($1 <= 1280 && $2 <= 720 && ($1 >= 1279 || $2 >= 719)) }' &&
  pass "shape --plot --size 1280x720: fits, one side full ($(png_size "$tmp/sp.png"))" ||
  fail "shape --plot --size 1280x720: $(png_size "$tmp/sp.png")"
expect_error "--size: not WxH" "--size needs WxH or W in pixels" plot "$tmp/b.csv" -o "$tmp/pics/x.png" --size big
expect_error "--size: too small" "each side must be 16 to 16384 pixels" plot "$tmp/b.csv" -o "$tmp/pics/x.png" --size 800x5
expect_error "--slow on a figure" "--slow applies to a movie" plot "$tmp/b.csv" -o "$tmp/pics/x.png" --slow 2
expect_error "--size without --plot" "shape the picture of --plot" shape --omega 3 --mode 1 --size 800

# movies: slow motion and frames per turn at 25 frames a second; a box
rate() { ffprobe -v error -select_streams v:0 -count_frames -show_entries \
  stream=r_frame_rate,nb_read_frames,width,height -of csv=p=0 "$1"; }
expect_ok "simulate --animate --slow 4" simulate "$scene" --set run.t_end=0.2 --animate "$tmp/slow.mp4" --slow 4
[ "$(rate "$tmp/slow.mp4" | cut -d, -f3-)" = "25/1,21" ] &&
  pass "--slow 4: 21 frames for 0.2 s (one every 1/100 s), 25 a second" || fail "--slow 4: $(rate "$tmp/slow.mp4")"
expect_ok "simulate --animate --frames-per-turn 24" simulate "$scene" --set run.t_end=0.25 \
  --animate "$tmp/fpt.mp4" --frames-per-turn 24
[ "$(rate "$tmp/fpt.mp4" | cut -d, -f3-)" = "25/1,25" ] &&
  pass "--frames-per-turn 24 at 4 Hz: 25 frames for 0.25 s, 25 a second" || fail "--frames-per-turn: $(rate "$tmp/fpt.mp4")"
expect_ok "simulate --animate --size 640x360" simulate "$scene" --set run.t_end=0.1 --animate "$tmp/box.mp4" --size 640x360
rate "$tmp/box.mp4" | awk -F, '{ exit !($1 <= 640 && $2 <= 360 && ($1 >= 638 || $2 >= 358)) }' &&
  pass "--size 640x360: the movie fits, one side full ($(rate "$tmp/box.mp4" | cut -d, -f1-2))" ||
  fail "--size 640x360: $(rate "$tmp/box.mp4")"
# whirl plot of a trace every 10 ms: --slow 2 is 50 frames a second, --slow 1 every other block
"$WHIRL" simulate "$scene" --set run.t_end=0.2 --set output.trace="$tmp/t10.dat" -o /dev/null
expect_ok "plot: a trace --slow 2" plot "$tmp/t10.dat" -o "$tmp/t2.mp4" --slow 2
[ "$(rate "$tmp/t2.mp4" | cut -d, -f3-)" = "50/1,21" ] && pass "plot --slow 2: 21 frames, 50 a second" ||
  fail "plot --slow 2: $(rate "$tmp/t2.mp4")"
expect_ok "plot: a trace --slow 1" plot "$tmp/t10.dat" -o "$tmp/t1.mp4" --slow 1
[ "$(rate "$tmp/t1.mp4" | cut -d, -f3-)" = "50/1,11" ] && pass "plot --slow 1: every other block, 11 frames, 50 a second" ||
  fail "plot --slow 1: $(rate "$tmp/t1.mp4")"
expect_error "--frames-per-turn: too many frames" "over 1500" simulate "$scene" --animate "$tmp/pics/x.mp4" --frames-per-turn 100
expect_error "--slow without --animate" "shape the movie of --animate" simulate "$scene" --slow 2
[ -z "$(ls -A "$tmp/pics")" ] && pass "sizes and movies: failures leave no file" || fail "left: $(ls -A "$tmp/pics")"
finish
