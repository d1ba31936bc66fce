#!/bin/sh
# The Python package's overhead over the C library (python/bench/bench_overhead.py).
out=${1:-out/bench}
build=$(dirname "${WHIRL:-build/whirl}")
/usr/bin/python3 python/bench/bench_overhead.py "$out" "$build"
