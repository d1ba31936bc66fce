#!/usr/bin/python3
"""Pixel box of one colour in a PNG (8-bit RGB or RGBA, not interlaced), for tests/cli/test_view.sh.

usage: png_extent.py FILE RRGGBB [TOP [X0,Y0,X1,Y1]]
Prints "x0 y0 x1 y1 count": the smallest box holding every pixel within a distance of 60 (in
RGB) of the colour, at rows >= TOP (default 0) and outside the box X0,Y0,X1,Y1 if given (a label
to leave out), and how many there are; "none" if no pixel is.
Only the standard library: the PNG is inflated with zlib and its rows unfiltered (PNG spec,
section 9: filter types 0-4)."""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise SystemExit(path + ': not a PNG')
    pos, idat, head = 8, b'', None
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            head = struct.unpack('>IIBBBBB', body)
        elif kind == b'IDAT':
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = head
    if depth != 8 or colour not in (2, 6) or interlace:
        raise SystemExit(path + ': only 8-bit RGB/RGBA, not interlaced')
    bpp = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        prev = line
    return width, height, bpp, rows


def main():
    path, hexcolour = sys.argv[1], sys.argv[2]
    top = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    skip = [int(v) for v in sys.argv[4].split(',')] if len(sys.argv) > 4 else [0, 0, -1, -1]
    want = [int(hexcolour[i:i + 2], 16) for i in (0, 2, 4)]
    width, height, bpp, rows = read_png(path)
    box, count = [width, height, -1, -1], 0
    for y in range(top, height):
        line = rows[y]
        for x in range(width):
            r, g, b = line[x * bpp:x * bpp + 3]
            if skip[0] <= x <= skip[2] and skip[1] <= y <= skip[3]:
                continue
            if (r - want[0]) ** 2 + (g - want[1]) ** 2 + (b - want[2]) ** 2 <= 3600:
                count += 1
                box = [min(box[0], x), min(box[1], y), max(box[2], x), max(box[3], y)]
    print('none' if count == 0 else '%d %d %d %d %d' % (box[0], box[1], box[2], box[3], count))


if __name__ == '__main__':
    main()
