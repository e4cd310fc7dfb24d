#!/usr/bin/env python3
"""Set 8-bit RGB PNGs of one size side by side, a few black pixels apart (a film strip).

    scripts/png_strip.py OUT.png GAP IN.png [IN.png ...]

GAP is the number of black pixel columns between frames. Standard library only (the reader and
writer of scripts/png_zoom.py); the output is written beside OUT.png and renamed over it.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_zoom import read_png, write_png  # noqa: E402


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    dst, gap, paths = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    frames = [read_png(p) for p in paths]
    size = (len(frames[0][0]), len(frames[0]))
    for p, f in zip(paths, frames):
        if (len(f[0]), len(f)) != size:
            sys.exit(f"{p}: {len(f[0])}x{len(f)}, the first frame is {size[0]}x{size[1]}")
    black = [(0, 0, 0)] * gap
    rows = []
    for y in range(size[1]):
        row = []
        for i, f in enumerate(frames):
            row.extend((black if i else []) + f[y])
        rows.append(row)
    tmp = dst + ".part"
    write_png(tmp, rows)
    os.replace(tmp, dst)
    print(f"wrote {dst}: {len(rows[0])}x{len(rows)}")


if __name__ == "__main__":
    main()
