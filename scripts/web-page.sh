#!/bin/sh
# Writes the single-file page of make web: the page (src/web/explore.html) with the Worker's
# script in its <script type="text/plain" id="worker-src"> block, in place of the line
# /*WORKER*/: the library compiled to WebAssembly (emscripten's MODULARIZE glue with the module
# inside as base64, SINGLE_FILE) followed by src/web/worker.js. The page starts the Worker from
# that text through a Blob URL, so it works opened from disk (file://) and offline.
#   sh scripts/web-page.sh PAGE CORE_JS WORKER_JS OUT
set -eu
page=$1 core=$2 worker=$3 out=$4
# the block ends at the first "</script": the scripts must not hold one
if grep -qi '</script' "$core" "$worker"; then
  echo "web-page: $core or $worker holds </script, which would end the page's block" >&2
  exit 1
fi
[ "$(grep -c '^/\*WORKER\*/$' "$page")" = 1 ] || { echo "web-page: $page needs one /*WORKER*/ line" >&2; exit 1; }
awk -v core="$core" -v worker="$worker" '
  $0 == "/*WORKER*/" { while ((getline l < core) > 0) print l; while ((getline l < worker) > 0) print l; next }
  { print }' "$page" >"$out.tmp"
mv "$out.tmp" "$out"
