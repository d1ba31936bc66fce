"""No memory growth over 10^4 calls (every object the package allocates in C is freed)."""
import gc

import numpy as np

import whirl


def _rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS")


def _calls(k):
    whirl.shape(3.5 + 1e-4 * (k % 7), 2, links=8)
    whirl.critical(3, links=8)
    c = whirl.Chain(lengths=[0.5, 0.5], masses=[0.25, 0.75])
    sim = whirl.Simulation(c, method="rk4")
    sim.set_hanging()
    sim.run(0.02, 0.01)
    try:
        whirl.shape(1.0, 2, links=8)
    except whirl.Error:
        pass


def test_no_memory_growth_over_ten_thousand_calls():
    for k in range(500):  # warm-up: allocator pools, caches
        _calls(k)
    gc.collect()
    before = _rss_kib()
    for k in range(10000):
        _calls(k)
    gc.collect()
    growth = _rss_kib() - before
    # one leaked chain of 2 links (~100 bytes) per call would already be ~1 MB
    assert growth < 512, "RSS grew by %d KiB over 10^4 calls" % growth
