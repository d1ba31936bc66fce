#!/bin/sh
# The studies behind the figures (`make study`): sh scripts/study.sh [PART] [OUT] [BUILD]
#   stability: eig_growth against omega (1..10, step 0.01) for modes 1-3 at N = 25, 50 and 100
#              (stability_map_N*.csv, stability_map.png) and the instability windows found;
#              STABILITY_LINKS="25 50" for other chains (N = 100 alone takes about half an
#              hour: 2200 eigen-solves of 400 rows);
#   regime:    the settled node count of a chain swung by hand from rest, over (omega, eps), with
#              the folds of the steady branches (regime_map.csv, regime_folds.csv, regime.png),
#              on 2 MPI ranks when the program has MPI.
#   all:       both (default).
set -e
part=${1:-all}
out=${2:-out/study}
build=${3:-build}
WHIRL=${WHIRL:-$build/whirl}
mkdir -p "$out"

stability() {
  links=${STABILITY_LINKS:-25 50 100}
  files=""
  for n in $links; do
    files="$files${files:+ }$out/stability_map_N$n.csv"
    start=$(date +%s)
    "$WHIRL" stability --omega-min 1 --omega-max 10 --omega-count 901 --links $n --linear \
      -o "$out/stability_map_N$n.csv"
    echo "map N = $n: $(( $(date +%s) - start )) s wall for $(grep -vc '^[#o]' "$out/stability_map_N$n.csv") analyses"
    # windows: maximal runs of rates with eig_growth > 0, per mode
    grep -v '^#' "$out/stability_map_N$n.csv" | awk -F, -v n=$n '
      NR == 1 { next }
      function close_window() { if (open) printf "  N = %d mode %d: unstable for omega in [%.2f, %.2f], max growth %.4g at %.2f\n", n, mode, from, to, gmax, at; open = 0 }
      $2 != mode { close_window(); mode = $2 }
      $4 > 0 { if (!open) { open = 1; from = $1; gmax = 0 } to = $1; if ($4 > gmax) { gmax = $4; at = $1 } next }
      { close_window() }
      END { close_window() }'
  done
  gnuplot -e "files='$files'; out='$out/stability_map.png'" \
    plots/stability_map.gp && echo "figure: $out/stability_map.png"
}

regime() {
  # the worked example of data/physical_example.md: a 0.5 m, 50 g, 4 mm chain, 1-4 Hz, 2-5 cm
  run="$WHIRL"
  if command -v mpirun >/dev/null 2>&1 && ldd "$WHIRL" | grep -q libmpi; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    run="mpirun --oversubscribe -n 2 $WHIRL"
  fi
  start=$(date +%s)
  $run regime --omega-min 1.4 --omega-max 5.6 --omega-count 15 --eps-min 0.04 --eps-max 0.10 \
    --eps-count 4 --drag-quadratic 0.0144 --t-max 3000 -o "$out/regime_map.csv" \
    --folds "$out/regime_folds.csv"
  echo "regime map: $(( $(date +%s) - start )) s wall ($run)"
  gnuplot -e "map='$out/regime_map.csv'; folds='$out/regime_folds.csv'; out='$out/regime.png'" \
    plots/regime.gp && echo "figure: $out/regime.png"
}

case $part in
  stability) stability ;;
  regime) regime ;;
  all) stability; regime ;;
  *) echo "study.sh: unknown part '$part' (stability, regime, all)" >&2; exit 1 ;;
esac
