"""whirl.equilibria and the continuous chain's stability windows against the command line
(``whirl equilibria``, ``whirl windows`` without --links): the same rows to the
digits printed, and the evidence the command's comment lines give."""
import csv
import io
import math
import re
import subprocess

import numpy as np
import pytest

import whirl


def _cli(program, *args):
    out = subprocess.run([program, *args], capture_output=True, text=True, check=True).stdout
    comments = [l for l in out.splitlines() if l.startswith("#")]
    rows = list(csv.DictReader(io.StringIO("\n".join(l for l in out.splitlines()
                                                     if not l.startswith("#")))))
    return comments, rows


def _num(text):
    return float(text) if text not in ("", "inf") else (math.inf if text == "inf" else math.nan)


def _same(a, b):
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return a == pytest.approx(b, rel=1e-15, abs=0)


def _compare_rows(rows, cli_rows, units=1.0):
    assert len(rows) == len(cli_rows)
    for r, c in zip(rows, cli_rows):
        assert r["node_count"] == int(c["nodes"])
        if c["branch"] == "isolated":
            assert r["branch"] == 0
        elif c["branch"] in ("unidentified", ""):
            assert r["branch"] == -1
        else:
            assert r["branch"] == int(c["branch"])
        for field in ("born_at", "tip_r", "max_r", "depth", "top_tension", "eig_growth"):
            assert _same(float(r[field]), _num(c[field])), field


def test_five_links_as_the_cli(whirl_program):
    rows, ev = whirl.equilibria(11.62, 5)
    comments, cli = _cli(whirl_program, "equilibria", "--omega", "11.62", "--links", "5")
    _compare_rows(rows, cli)
    assert len(rows) == 17 and ev["born"] == 5
    assert ev["tip_roots"] == ev["check_roots"] == ev["matched"] == 17
    assert ev["missed"] == 0 and ev["unpolished"] == 0 and ev["balance"] < 1e-13
    assert "%d crossings of omega" % ev["crossings"] in comments[2]
    assert np.all(np.diff(rows["tip_r"]) > 0)


def test_high_rate_scans_only_as_the_cli(whirl_program):
    rows, ev = whirl.equilibria(25, 6, stability=False, branches=False)
    comments, cli = _cli(whirl_program, "equilibria", "--omega", "25", "--links", "6",
                         "--no-stability", "--no-branches")
    _compare_rows(rows, cli)
    assert len(rows) == 54 and ev["path_steps"] == 0
    assert ev["tip_roots"] == ev["check_roots"] == ev["matched"] == 54
    assert np.all(rows["branch"] == -1) and np.all(np.isnan(rows["eig_growth"]))
    m = re.search(r"tip scan: (\d+) roots .* pivot scan: (\d+) roots .* both: (\d+)", comments[1])
    assert m and [int(x) for x in m.groups()] == [54, 54, 54]


def test_continuum_is_kolodner_as_the_cli(whirl_program):
    rows, ev = whirl.equilibria(5)
    comments, cli = _cli(whirl_program, "equilibria", "--omega", "5")
    _compare_rows(rows, cli)
    # Kolodner: one shape per mode born below omega, mode k with k - 1 crossings
    assert ev["born"] == 3 and sorted(rows["node_count"]) == [1, 2, 3]
    assert list(rows["branch"]) == list(rows["node_count"])
    assert ev["tip_roots"] == 3 and ev["matched"] == 3


def test_physical_units():
    w = 11.62 * math.sqrt(9.81 / 0.5)
    rows, ev = whirl.equilibria(w, 5, stability=False, length=0.5, gravity=9.81)
    ref, _ = whirl.equilibria(11.62, 5, stability=False)
    assert len(rows) == 17
    assert rows["tip_r"] == pytest.approx(0.5 * ref["tip_r"], rel=1e-9)
    assert rows["born_at"] == pytest.approx(ref["born_at"] * math.sqrt(9.81 / 0.5), rel=1e-9)


def test_equilibria_bad_input():
    with pytest.raises(ValueError):
        whirl.equilibria(0, 5)
    with pytest.raises(whirl.Error):
        whirl.equilibria(1001, 5)
    with pytest.raises(whirl.Error):
        whirl.equilibria(51)  # the continuum's range
    with pytest.raises(whirl.Error):
        whirl.equilibria(3, 5, shot_budget=10)
    crit = whirl.critical(3, links=5)[-1]
    with pytest.raises(whirl.Error):
        whirl.equilibria(crit, 5)


def test_continuum_windows_as_the_cli(whirl_program):
    windows, stats = whirl.stability_windows(2, None, 4.39, 4.41)
    comments, cli = _cli(whirl_program, "windows", "--modes", "2",
                         "--omega-min", "4.39", "--omega-max", "4.41")
    assert len(windows) == len(cli) == 1
    w, c = windows[0], cli[0]
    assert c["links"] == "inf"
    for field in ("from", "to", "freq_from", "freq_to", "max_growth", "at", "err_from", "err_to"):
        assert _same(float(w[field]), _num(c[field])), field
    assert bool(w["open_from"]) == (c["open_from"] == "1")
    assert bool(w["open_to"]) == (c["open_to"] == "1")
    # mode 2 of the continuous chain loses stability near 4.4032 (the window opens inside)
    assert 4.39 < w["from"] < 4.41 and w["open_to"] and not w["open_from"]
    assert "%d eigen-solves" % (stats["solves_vectors"] + stats["solves_values"]
                                + stats["solves_krylov"]) in comments[1]


def test_continuum_windows_bad_input():
    with pytest.raises(ValueError):
        whirl.stability_windows(2, 10, 4.39, 4.41, degree=12)
    with pytest.raises(ValueError, match="degree must be >= 6"):
        whirl.stability_windows(2, None, 4.39, 4.41, degree=3)
    with pytest.raises(whirl.Error):
        whirl.stability_windows(3, None, 1.0, 2.0)  # mode 3 is born at 4.3
    with pytest.raises(ValueError, match="memory_mb must be in"):
        whirl.stability_windows(2, None, 4.39, 4.41, memory_mb=8)
    with pytest.raises(ValueError, match="memory_mb must be in"):
        whirl.stability_windows(2, None, 4.39, 4.41, memory_mb=1e7)
    with pytest.raises(ValueError, match="memory_mb"):
        whirl.stability_windows(2, 10, 4.39, 4.41, memory_mb=100)


def test_continuum_windows_memory_refused():
    # mode 8 at 20.5 needs 731 collocation points, more than the 720 that 16 MB hold (the
    # command line's test_stability.sh)
    with pytest.raises(whirl.Error, match="731 collocation points.*16 MB hold"):
        whirl.stability_windows(8, None, 20, 21, memory_mb=16)


def test_continuum_windows_memory_bound():
    # 32 MB hold mode 8's 731 collocation points
    windows, stats = whirl.stability_windows(8, None, 20, 21, memory_mb=32)
    assert stats["scan"] > 0
