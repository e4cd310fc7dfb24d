#!/usr/bin/env python3
"""Crop an 8-bit RGB PNG (as morgana writes them) and enlarge it by whole pixels.

    scripts/png_zoom.py IN.png OUT.png X0 Y0 X1 Y1 FACTOR

Keeps pixels x0 <= x < x1, y0 <= y < y1 and repeats each FACTOR times in both directions
(nearest neighbour: no new colours), so the one-pixel rims of a sunset show. Standard library
only; reads non-interlaced 8-bit RGB or RGBA PNGs with any filter.
"""

import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG file")
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace != 0:
                sys.exit(f"{path}: only non-interlaced 8-bit RGB/RGBA PNGs are supported")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
    raw, stride = zlib.decompress(idat), width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        ftype, line = raw[start], bytearray(raw[start + 1 : start + 1 + stride])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels : x * channels + 3]) for x in range(width)])
        prev = line
    return rows


def write_png(path, rows):
    height, width = len(rows), len(rows[0])
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    if len(sys.argv) != 8:
        sys.exit(__doc__)
    src, dst = sys.argv[1], sys.argv[2]
    x0, y0, x1, y1, k = (int(v) for v in sys.argv[3:])
    rows = read_png(src)
    if not (0 <= x0 < x1 <= len(rows[0]) and 0 <= y0 < y1 <= len(rows) and k >= 1):
        sys.exit(f"crop {x0},{y0},{x1},{y1} is not inside the {len(rows[0])}x{len(rows)} image, or factor < 1")
    out = []
    for row in rows[y0:y1]:
        big = [px for px in row[x0:x1] for _ in range(k)]
        out.extend([big] * k)
    write_png(dst, out)
    print(f"wrote {dst}: {len(out[0])}x{len(out)}")


if __name__ == "__main__":
    main()
