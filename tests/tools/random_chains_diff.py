#!/usr/bin/python3
"""Compares two runs of tests/bench_random_chains (their random_chains.csv, the same seeds and
chains): the modes that stop in one run only, the ends at 10 times the birth that moved by more
than TOL rad in some link angle (up to the mirror image), and the totals of steps, folds and
modes that take a branch point. Which of two moved ends is right, tests/tools/branch_mp.py decides.

Usage: random_chains_diff.py OLD.csv NEW.csv [--tol 1e-9]
"""
import argparse
import csv
import sys


def load(path):
    rows = {}
    with open(path, newline='') as f:
        for r in csv.DictReader(f):
            key = (int(r['seed']), int(r['chain']), int(r['mode']))
            n = int(r['links'])
            theta = None
            if r['status'] == '0':
                theta = [float(r['theta_%d' % (i + 1)]) for i in range(n)]
            rows[key] = (int(r['status']), int(r['steps']), int(r['folds']),
                         int(r['branch_points']), theta)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('old')
    ap.add_argument('new')
    ap.add_argument('--tol', type=float, default=1e-9)
    a = ap.parse_args()
    try:
        old, new = load(a.old), load(a.new)
    except (OSError, KeyError, ValueError) as e:
        sys.exit('random_chains_diff.py: cannot read the runs: %s' % e)
    if set(old) != set(new):
        sys.exit('random_chains_diff.py: the two runs hold different modes (other seeds or chains)')
    moved = stops_old = stops_new = 0
    for key in sorted(old):
        o, n = old[key], new[key]
        if o[0] and not n[0]:
            stops_old += 1
            print('stops in OLD only: seed %d chain %d mode %d' % key)
        elif n[0] and not o[0]:
            stops_new += 1
            print('stops in NEW only: seed %d chain %d mode %d' % key)
        elif not o[0]:
            d = min(max(abs(x - y) for x, y in zip(o[4], n[4])),
                    max(abs(x + y) for x, y in zip(o[4], n[4])))
            if d > a.tol:
                moved += 1
                print('moved by %.3g rad: seed %d chain %d mode %d' % ((d,) + key))
    for name, i in (('steps', 1), ('folds', 2)):
        print('%s: %d -> %d' % (name, sum(v[i] for v in old.values()),
                                sum(v[i] for v in new.values())))
    print('modes that take a branch point: %d -> %d' % (
        sum(v[3] > 0 for v in old.values()), sum(v[3] > 0 for v in new.values())))
    print('%d modes: %d stop in OLD only, %d in NEW only, %d ends moved' % (
        len(old), stops_old, stops_new, moved))


if __name__ == '__main__':
    main()
