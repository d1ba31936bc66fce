#!/bin/sh
# The whirl demo: runs the program on showcase cases, writes CSV under out/demo/ and renders the
# figures with the gnuplot scripts of plots/, each as PNG and SVG, and the animations as GIF and
# MP4. Usage: sh scripts/demo.sh [BUILD_DIR]
# A plain sequential script: each part appends its own steps below.
set -e
build=${1:-build}
whirl=$build/whirl
out=out/demo
mkdir -p "$out"
# gnuplot, with any message on its standard error (a warning) stopping the demo; gif's count of
# frames is not a warning
plot() {
  gnuplot "$@" 2>"$out/gnuplot.err" || { cat "$out/gnuplot.err" >&2; exit 1; }
  if grep -v 'frames in animation sequence' "$out/gnuplot.err" | grep -q .; then
    echo "demo: gnuplot printed warnings for $*:" >&2; cat "$out/gnuplot.err" >&2; exit 1
  fi
  rm -f "$out/gnuplot.err"
}
# figure VARS SCRIPT OUT: the figure as OUT.png and OUT.svg (out='...' in VARS is added)
figure() {
  plot -e "$1; out='$3.png'" "$2"
  plot -e "$1; out='$3.svg'" "$2"
}

# ---- steady shapes: branches of modes 1-3 for omega 1..10, shapes at a few rates ----
echo "demo: steady shapes"
"$whirl" critical --modes 3 -o "$out/critical.csv"
"$whirl" sweep --modes 1,2,3 --omega-min 1 --omega-max 10 --omega-count 901 -o "$out/branches.csv"
"$whirl" sweep --modes 1,2,3 --omega-min 1 --omega-max 10 --omega-count 91 --links 10 \
  -o "$out/branches_n10.csv"
# each mode at three rates above its critical rate (the middle one also with 12 links)
shape_rates() { case $1 in 1) echo "1.3 2 5" ;; 2) echo "3 4.5 8" ;; 3) echo "4.6 6.5 10" ;; esac; }
for k in 1 2 3; do
  i=0
  for w in $(shape_rates $k); do
    i=$((i + 1))
    "$whirl" shape --omega $w --mode $k -o "$out/shape_k${k}_$i.csv"
    [ $i -eq 2 ] && "$whirl" shape --omega $w --mode $k --links 12 -o "$out/shape_k${k}_n12.csv"
  done
done
for fmt in png svg; do
  plot -e "dir='$out'; fmt='$fmt'" plots/shapes.gp
  plot -e "dir='$out'; fmt='$fmt'" plots/branches.gp
done
echo "demo: wrote $out/shapes.png $out/branches.png (and .svg)"

# ---- the teacher's figure: a 60 cm, 50 g chain at 2, 4 and 6 Hz in its 2-node shape ----
echo "demo: the classroom chain"
for ext in png svg; do
  "$whirl" shape --length 60cm --mass 50g --omega 2Hz,4Hz,6Hz --mode 2 --plot "$out/classroom_shapes.$ext"
done
"$whirl" simulate data/scenes/classroom.ini --set start.omega=4Hz --animate "$out/classroom_4hz.mp4"
"$whirl" simulate data/scenes/classroom.ini --set start.omega=4Hz --animate "$out/classroom_4hz.gif"
echo "demo: wrote $out/classroom_shapes.png (and .svg) $out/classroom_4hz.mp4 $out/classroom_4hz.gif"

# ---- dynamics: the 100-link chain seeded with its mode-2 shape, animated; the seed's double pendulum ----
echo "demo: dynamics"
"$whirl" simulate data/scenes/mode2.ini --set run.t_end=6 --set output.trace="$out/mode2.dat" \
  --set output.trace_every=0.1 -o "$out/mode2.csv"
plot -e "trace='$out/mode2.dat'; out='$out/mode2.gif'; mp4='$out/mode2.mp4'" plots/animate.gp
"$whirl" view "$out/mode2.dat" -o "$out/mode2.html"
"$whirl" simulate data/scenes/double_pendulum.ini --set run.t_end=20 -o "$out/double_pendulum.csv"
figure "csv='$out/double_pendulum.csv'" plots/simulate.gp "$out/double_pendulum"
echo "demo: wrote $out/mode2.gif $out/mode2.mp4 $out/mode2.html $out/double_pendulum.png"

# ---- stability: the map (linear analysis) at N = 25 and 50, and two perturbed runs ----
echo "demo: stability"
for n in 25 50; do
  "$whirl" stability --omega-min 1 --omega-max 10 --omega-count 181 --links $n --linear \
    -o "$out/stability_map_N$n.csv"
done
figure "files='$out/stability_map_N25.csv $out/stability_map_N50.csv'" plots/stability_map.gp \
  "$out/stability_map"
"$whirl" stability --omega 9 --mode 2 --links 25 --periods 1000 --trace "$out/unstable_trace.csv" \
  -o "$out/unstable_row.csv"
figure "csv='$out/unstable_trace.csv'" plots/deviation.gp "$out/deviation_unstable"
"$whirl" stability --omega 2 --mode 1 --links 25 --damping 0.01 --perturb 0.01 \
  --trace "$out/damped_trace.csv" -o "$out/damped_row.csv"
figure "csv='$out/damped_trace.csv'" plots/deviation.gp "$out/deviation_damped"
echo "demo: wrote $out/stability_map.png $out/deviation_unstable.png $out/deviation_damped.png"

# ---- the hand-swung chain: mode-1 branches with the pivot on a circle, and a trailing shape ----
echo "demo: driven pivot and air drag"
for e in 0.01 0.05; do
  for side in 1 -1; do
    "$whirl" driven --omega-min 0.6 --omega-max 2.2 --eps $e --drag 0.01 --side $side \
      -o "$out/driven_eps${e}_side$side.csv"
  done
done
figure "branch='$(ls "$out"/driven_eps*_side*.csv | tr '\n' ' ')'" plots/driven.gp "$out/driven_branches"
"$whirl" driven --omega 1.6 --eps 0.05 --drag 0.05 -o "$out/driven_shape.csv"
figure "shape='$out/driven_shape.csv'" plots/driven.gp "$out/driven_shape"
echo "demo: wrote $out/driven_branches.png $out/driven_shape.png"

# ---- from rest: spin-ups into 1, 2 and 3 nodes (strong linear drag, so that they settle fast) ----
echo "demo: spin-ups from rest"
for c in "1 2.0 0.10" "2 3.0 0.05" "3 5.0 0.05"; do
  set -- $c
  "$whirl" regime --omega $2 --eps $3 --drag 0.2 --trace "$out/spinup_$1.dat" --trace-every 0.25 \
    -o "$out/spinup_$1.csv"
  plot -e "trace='$out/spinup_$1.dat'; out='$out/spinup_$1.gif'; step=2; delay=5; width=480" \
    plots/animate.gp
done
echo "demo: wrote $out/spinup_1.gif $out/spinup_2.gif $out/spinup_3.gif"

# ---- the stability atlas of the continuum (modes 2-8 to omega 40): drawn from the committed
# windows of docs/guide/atlas.csv, not computed here (the run, whirl windows --atlas --modes 2-8
# --omega-max 40, takes some 7 minutes of processor time); the figure says so ----
echo "demo: stability atlas (drawn from docs/guide/atlas.csv)"
figure "csv='docs/guide/atlas.csv'; note='windows from docs/guide/atlas.csv (whirl windows --atlas --modes 2-8 --omega-max 40), not recomputed by the demo'" \
  plots/atlas.gp "$out/atlas"
echo "demo: wrote $out/atlas.png (and .svg)"
