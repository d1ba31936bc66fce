#!/usr/bin/python3
"""Extrapolates the N-link chain's window edges in 1/N and compares them with the continuum's.

Reads the continuum's windows (the CSV of `whirl windows --atlas`, e.g. docs/guide/atlas.csv)
and the N-link windows of `whirl windows --links N` at several N (one CSV per N).
Each closed edge of the continuum (and the opening edge of a window open at the range's end),
for the modes asked and below --omega-max, is matched at each N to the N-link edge of the same
kind (opening or closing) nearest in omega among those whose collision frequency agrees with the
continuum's to --freq-tol (relative, default 5 %), and each N-link edge serves one
continuum edge only: a narrow window missed at small N, two windows merged into one, or an edge
where a different pair collides shows as '-'.

The edges e_N, e_2N, e_4N of the three N of --fit are extrapolated by Richardson's rule with
the order fitted to them:
    p = log2((e_2N - e_N) / (e_4N - e_2N)),   E = e_4N + (e_4N - e_2N) / (2^p - 1),
and the error bar is the distance to the extrapolation of order 1, |E - (2 e_4N - e_2N)|.
Prints a Markdown table (the N columns, E +- bar (p), the continuum edge, the difference and
its ratio to the bar), then the N-link windows no continuum edge claimed, and a summary.

Usage: extrapolate_edges.py ATLAS.csv NLINK.csv... [--modes 4,5] [--omega-max 14]
                            [--fit 100,200,400] [--freq-tol 0.05]
"""
import argparse
import csv
import math
import sys


def read_rows(path):
    try:
        with open(path, newline='') as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith('#')))
    except OSError as e:
        sys.exit('extrapolate_edges: %s: %s' % (path, e.strerror))
    need = {'mode', 'from', 'to', 'open_from', 'open_to', 'freq_from', 'freq_to'}
    if not rows or not need <= set(rows[0]):
        sys.exit('extrapolate_edges: %s: not a windows CSV of whirl stability (columns %s)'
                 % (path, ', '.join(sorted(need))))
    return rows


def edges_of(row):
    """(kind, omega, frequency) of a window's edges that are collisions (not the range's ends)."""
    out = []
    if row['open_from'] == '0':
        out.append(('from', float(row['from']), float(row['freq_from'])))
    if row['open_to'] == '0':
        out.append(('to', float(row['to']), float(row['freq_to'])))
    return out


def richardson(e1, e2, e4):
    """Order, extrapolation and error bar of e1, e2, e4 at N, 2N, 4N (None if not monotone)."""
    d1, d2 = e2 - e1, e4 - e2
    if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0):
        return None
    p = math.log2(d1 / d2)
    if abs(p) < 1e-6:
        return None
    ext = e4 + d2 / (2 ** p - 1)
    return p, ext, abs(ext - (e4 + d2))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('atlas')
    ap.add_argument('nlink', nargs='+')
    ap.add_argument('--modes', default='4,5')
    ap.add_argument('--omega-max', type=float, default=14.0)
    ap.add_argument('--fit', help='the three N (N, 2N, 4N) of the fit; default the three largest')
    ap.add_argument('--freq-tol', type=float, default=0.05)
    a = ap.parse_args()
    modes = [int(m) for m in a.modes.split(',')]

    runs = {}  # N -> mode -> list of (kind, omega, freq)
    for path in a.nlink:
        for r in read_rows(path):
            if r.get('links', 'inf') == 'inf':
                sys.exit('extrapolate_edges: %s: not an N-link run (no --links)' % path)
            n = int(r['links'])
            runs.setdefault(n, {}).setdefault(int(r['mode']), []).extend(edges_of(r))
    ns = sorted(runs)
    fit = [int(x) for x in a.fit.split(',')] if a.fit else ns[-3:]
    if len(fit) != 3 or fit[1] != 2 * fit[0] or fit[2] != 2 * fit[1] or \
            any(n not in runs for n in fit):
        sys.exit('extrapolate_edges: --fit needs three of the runs\' N, each twice the last')

    cont = []
    for r in read_rows(a.atlas):
        m = int(r['mode'])
        if m in modes:
            cont.extend((m, k, w, fr) for k, w, fr in edges_of(r) if w <= a.omega_max)

    # matching: nearest edge of the same kind with agreeing frequency, each N-link edge once
    match = {}
    for n in ns:
        claimed = {}
        for i, (m, kind, w, fr) in enumerate(cont):
            cands = [e for e in runs[n].get(m, [])
                     if e[0] == kind and abs(e[2] - fr) <= a.freq_tol * abs(fr)]
            if not cands:
                continue
            e = min(cands, key=lambda c: abs(c[1] - w))
            if e in claimed:  # two continuum edges on one N-link edge: a merged window
                j = claimed[e]
                if abs(cont[j][2] - e[1]) <= abs(w - e[1]):
                    continue
                del match[(j, n)]
            claimed[e] = i
            match[(i, n)] = e

    print('| mode | edge | ' + ' | '.join('N = %d' % n for n in ns) +
          ' | extrapolated (p fitted to N = %s) | continuum | difference | difference / bar |'
          % ', '.join(str(n) for n in fit))
    print('|---|---|' + '---|' * len(ns) + '---|---|---|---|')
    ratios, unfitted = [], []
    for i, (m, kind, w, fr) in enumerate(cont):
        cells = ['%.6f' % match[(i, n)][1] if (i, n) in match else '-' for n in ns]
        res = None
        if all((i, n) in match for n in fit):
            res = richardson(*(match[(i, n)][1] for n in fit))
        if res is None:
            unfitted.append('mode %d %s %.6f' % (m, kind, w))
            tail = '- | %.6f | - | - |' % w
        else:
            p, ext, bar = res
            diff = abs(ext - w)
            ratios.append((diff / bar, m, kind, w))
            tail = '%.5f +- %.1e (p = %.2f) | %.6f | %.1e | %.2f |' % (ext, bar, p, w, diff,
                                                                       diff / bar)
        print('| %d | %s | %s | %s' % (m, kind, ' | '.join(cells), tail))

    print()
    for n in ns:
        used = {match[k] for k in match if k[1] == n}
        for m in modes:
            for e in runs[n].get(m, []):
                if e not in used:
                    print('N = %d, mode %d: %s edge %.6f (frequency %.4f) matches no continuum '
                          'edge' % (n, m, e[0], e[1], e[2]))
    within = sum(1 for r in ratios if r[0] <= 1)
    print('within the bar: %d of %d extrapolated edges' % (within, len(ratios)))
    if ratios:
        worst = max(ratios)
        print('worst difference / bar: %.2f (mode %d, %s %.6f)' % worst)
    if unfitted:
        print('not extrapolated (an edge unmatched at some N of the fit, or not monotone): ' +
              '; '.join(unfitted))


if __name__ == '__main__':
    main()
