#!/bin/sh
# The whirl demo: runs the program on showcase cases, writes CSV under out/demo/ and renders the
# PNG figures with the gnuplot scripts of plots/. Usage: sh scripts/demo.sh [BUILD_DIR]
# A plain sequential script: each part appends its own steps below.
set -e
build=${1:-build}
whirl=$build/whirl
out=out/demo
mkdir -p "$out"

# ---- steady shapes: branches of modes 1-3 for omega 1..10, shapes at a few rates ----
echo "demo: steady shapes"
"$whirl" critical --modes 3 -o "$out/critical.csv"
"$whirl" sweep --modes 1,2,3 --omega-min 1 --omega-max 10 --steps 900 -o "$out/branches.csv"
"$whirl" sweep --modes 1,2,3 --omega-min 1 --omega-max 10 --steps 90 --links 10 \
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
gnuplot -e "dir='$out'" plots/shapes.gp
gnuplot -e "dir='$out'" plots/branches.gp
echo "demo: wrote $out/shapes.png $out/branches.png"
