#!/usr/bin/env python3
"""How the images of two binaries' renders differ, example by example: the image of each EXAMPLE
as `scripts/bench_examples.sh BASE_BIN NEW_BIN OUT EXAMPLE...` left it in OUT/EXAMPLE.base and
OUT/EXAMPLE.new (the spectral EXR's channels summed per pixel).

    .venv/bin/python scripts/compare_images.py OUT EXAMPLE... [--block 8]

Prints, per example, the image mean of the new render over the base's, and the 5th
percentile, median and 95th percentile of that ratio over blocks of BLOCK × BLOCK pixels (blocks
whose base mean is 0 left out). Same seeds on both sides make the difference the change's alone,
without noise. Needs numpy and OpenEXR (scripts/requirements-colour.txt)."""
import argparse
import glob
import os
import sys

import numpy as np
import OpenEXR


def image(directory):
    exrs = sorted(glob.glob(os.path.join(directory, "*.exr")))
    if not exrs:
        sys.exit(f"compare_images.py: no EXR in {directory}")
    chans = OpenEXR.File(exrs[0], separate_channels=True).channels()
    spectral = [k for k in chans if k.startswith("S0.")]
    return np.sum([np.asarray(chans[k].pixels, dtype=np.float64) for k in spectral], axis=0)


def blocks(img, b):
    h, w = img.shape[0] // b * b, img.shape[1] // b * b
    return img[:h, :w].reshape(h // b, b, w // b, b).mean(axis=(1, 3))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out")
    p.add_argument("examples", nargs="+")
    p.add_argument("--block", type=int, default=8)
    a = p.parse_args()
    for ex in a.examples:
        base, new = image(os.path.join(a.out, ex + ".base")), image(os.path.join(a.out, ex + ".new"))
        bb, nb = blocks(base, a.block), blocks(new, a.block)
        ratio = nb[bb > 0] / bb[bb > 0]
        p5, p50, p95 = np.percentile(ratio, [5, 50, 95])
        print(f"{ex}: image mean new/base {new.mean() / base.mean():.4f}; "
              f"{a.block} x {a.block} blocks p5/median/p95 {p5:.3f}/{p50:.3f}/{p95:.3f}")


if __name__ == "__main__":
    main()
