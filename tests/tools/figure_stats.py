#!/usr/bin/python3
"""Size and blank fraction of pictures (PNG, GIF, MP4, WebM), for the gallery's before/after table.

usage: figure_stats.py FILE...
Prints one line per file: "FILE bytes WxH blank=F empty=E frames=N": blank is the fraction of
the canvas outside the smallest box holding every pixel that is not the background (the colour
of the top-left pixel, to within 24 in each channel): the white margins; empty is the fraction of
the canvas farther than 20 px from any such pixel (in cells of 10 x 10 px): white space inside
the box too, such as a small drawing in a large frame. For a movie both are taken over ten
frames spread over it (ffmpeg writes them as PNG): the union of their boxes and of their inked
cells. Reads PNG with png_extent.read_png (standard library only)."""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_extent import read_png  # noqa: E402


CELL = 10


def ink_box(path, cells):
    """The box of the pixels that are not the background; their 10-px cells added to cells."""
    width, height, bpp, rows = read_png(path)
    bg = rows[0][0:3]
    x0, y0, x1, y1 = width, height, -1, -1
    for y in range(height):
        line = rows[y]
        for x in range(width):
            px = line[x * bpp:x * bpp + 3]
            if abs(px[0] - bg[0]) > 24 or abs(px[1] - bg[1]) > 24 or abs(px[2] - bg[2]) > 24:
                if x < x0: x0 = x
                if x > x1: x1 = x
                if y < y0: y0 = y
                if y > y1: y1 = y
                cells.add((x // CELL, y // CELL))
    return width, height, (x0, y0, x1, y1)


def empty_fraction(width, height, cells):
    """Cells farther than two cells from an inked one, over all cells."""
    nx, ny = (width + CELL - 1) // CELL, (height + CELL - 1) // CELL
    near = set()
    for (cx, cy) in cells:
        for dx in range(-2, 3):
            for dy in range(-2, 3):
                near.add((cx + dx, cy + dy))
    covered = sum(1 for cx in range(nx) for cy in range(ny) if (cx, cy) in near)
    return 1 - covered / float(nx * ny)


def frames_of(path, tmp):
    out = subprocess.run(['ffprobe', '-v', 'error', '-count_frames', '-select_streams', 'v:0',
                          '-show_entries', 'stream=nb_read_frames', '-of', 'csv=p=0', path],
                         capture_output=True, text=True).stdout.strip()
    n = int(out.split(',')[0]) if out else 1
    pngs = []
    for k in range(10):
        f = os.path.join(tmp, 'f%d.png' % k)
        i = (n - 1) * k // 9
        subprocess.run(['ffmpeg', '-loglevel', 'error', '-y', '-i', path, '-vf',
                        'select=eq(n\\,%d)' % i, '-frames:v', '1', '-pix_fmt', 'rgb24', f], check=True)
        pngs.append(f)
    return n, pngs


def main():
    for path in sys.argv[1:]:
        size = os.path.getsize(path)
        cells = set()
        if path.endswith('.png'):
            w, h, (x0, y0, x1, y1) = ink_box(path, cells)
            n = 1
        else:
            with tempfile.TemporaryDirectory() as tmp:
                n, pngs = frames_of(path, tmp)
                x0 = y0 = 10 ** 9
                x1 = y1 = -1
                for f in pngs:
                    w, h, b = ink_box(f, cells)
                    x0, y0, x1, y1 = min(x0, b[0]), min(y0, b[1]), max(x1, b[2]), max(y1, b[3])
        blank = 1 - max(0, x1 - x0 + 1) * max(0, y1 - y0 + 1) / float(w * h)
        print('%s %d %dx%d blank=%.2f empty=%.2f frames=%d'
              % (path, size, w, h, blank, empty_fraction(w, h, cells), n))


main()
