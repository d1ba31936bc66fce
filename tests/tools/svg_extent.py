#!/usr/bin/python3
"""Extent of a curve in a gnuplot SVG, for tests/cli/test_pictures.sh.

usage: svg_extent.py FILE R,G,B
Prints "x0 y0 x1 y1 n": the box of the longest sub-path (from one M to the next) among the
<path> elements stroked rgb(R, G, B), in the picture's coordinates (y down), and its number of
points; "none" if no path has that colour. Only the standard library (re)."""
import re
import sys


def main():
    path, colour = sys.argv[1], [int(c) for c in sys.argv[2].split(',')]
    text = open(path).read()
    best = []
    for m in re.finditer(r"<path stroke='rgb\(\s*(\d+),\s*(\d+),\s*(\d+)\)'[^>]*\sd='([^']*)'", text):
        if [int(m.group(i)) for i in (1, 2, 3)] != colour:
            continue
        for sub in m.group(4).split('M')[1:]:
            pts = [tuple(map(float, p.split(','))) for p in re.findall(r'-?[\d.]+,-?[\d.]+', sub)]
            if len(pts) > len(best):
                best = pts
    if not best:
        print('none')
        return
    xs, ys = [p[0] for p in best], [p[1] for p in best]
    print(min(xs), min(ys), max(xs), max(ys), len(best))


main()
