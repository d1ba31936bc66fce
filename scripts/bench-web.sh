#!/bin/sh
# The page of make web, measured (a benchmark, not a test): the file's size and its gzip size;
# in headless Chromium (tests/tools/web_page.py bench) the load time from file:// to the first
# shape drawn, the latency of a rate change (median and 95th percentile of 40 changes, each the
# continuum's shape and the 30-link verdict), the branch diagram's time, the perturbed run's
# speed against real time (40 turns of 30 links) and the page's memory;
# and the speed of the WebAssembly against the native build on the same work
# (tests/bench/bench_web.c: built natively and for Node), with the load of the machine.
#   sh scripts/bench-web.sh [BUILD]
set -eu
build=${1:-build}
export NODE_OPTIONS=--no-experimental-fetch NODE_PATH=/usr/share/nodejs
make -s BUILD="$build" web "$build/tests/bench_web" "$build/web/bench_web.js" >/dev/null
page=$build/web/whirl-explore.html
echo "load (uptime): $(uptime)"
echo "file: $page $(wc -c <"$page") bytes, gzip -9 $(gzip -9 <"$page" | wc -c) bytes"
echo "chromium: $(/usr/bin/python3 tests/tools/web_page.py bench "$page" 40)"
# the native build on one thread, as the WebAssembly (no OpenMP)
native=$(OMP_NUM_THREADS=1 "$build/tests/bench_web")
wasm=$(node "$build/web/bench_web.js")
echo "native, one thread (ms, median of 21; of 5 for page_run_10s):"; echo "$native"
echo "wasm under node $(node --version) (ms, median of 21; of 5 for page_run_10s):"; echo "$wasm"
echo "$native
$wasm" | awk '{ t[$2] = t[$2] " " $3 } END { for (k in t) { split(t[k], v, " "); printf "ratio wasm/native %s: %.2f\n", k, v[2] / v[1] } }'
echo "load (uptime): $(uptime)"
