#!/usr/bin/env python3
"""Are two builds' images equal within their noise? Renders one scene with two morgana binaries
at several seeds (reduced: the camera's width and height divided by SHRINK, PHOTONS photons)
and prints, per seed, the image mean and median pixel (over all spectral channels of the EXR)
of each, then the paired relative differences with one standard error over the seeds. Changes
to the curved-path numerics move the noise (each photon's path differs), not the light: the
paired difference of the median should be within about two standard errors of zero.

    python3 scripts/compare_seeds.py BASE_BIN NEW_BIN SCENE [--seeds 1-6] [--shrink 4]
        [--photons 20000] [--out /tmp/compare_seeds]

Needs numpy and OpenEXR (scripts/requirements-colour.txt)."""
import argparse, os, re, statistics, subprocess, sys
import numpy as np
import OpenEXR


def reduced(scene, shrink):
    text = open(scene).read()
    for key in ("width", "height"):
        text = re.sub(rf"(?m)^{key} = (\d+)", lambda m: f"{key} = {max(1, int(m.group(1)) // shrink)}", text, count=1)
    path = os.path.join(os.path.dirname(scene), ".compare_" + os.path.basename(scene))
    open(path, "w").write(text)
    return path


def stats(exr):
    chans = OpenEXR.File(exr, separate_channels=True).channels()
    data = np.concatenate([np.asarray(c.pixels, dtype=np.float64).ravel() for c in chans.values()])
    return float(data.mean()), float(np.median(data))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("base"); ap.add_argument("new"); ap.add_argument("scene")
    ap.add_argument("--seeds", default="1-6"); ap.add_argument("--shrink", type=int, default=4)
    ap.add_argument("--photons", type=int, default=20000); ap.add_argument("--out", default="/tmp/compare_seeds")
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.seeds.split("-"))
    scene = reduced(a.scene, a.shrink)
    name = os.path.splitext(os.path.basename(a.scene))[0]
    rows = []
    try:
        for seed in range(lo, hi + 1):
            row = []
            for tag, binary in (("base", a.base), ("new", a.new)):
                out = os.path.join(a.out, f"{name}-{tag}-{seed}")
                subprocess.run([binary, "render", scene, "--out", out, "--quiet", "--seed", str(seed),
                                "--photons", str(a.photons)], check=True, stdout=subprocess.DEVNULL)
                exr = [f for f in os.listdir(out) if f.endswith(".exr")][0]
                row.append(stats(os.path.join(out, exr)))
            rows.append(row)
            (bm, bmed), (nm, nmed) = row
            print(f"seed {seed}: mean {bm:.6g} -> {nm:.6g} ({100 * (nm / bm - 1):+.1f} %), "
                  f"median {bmed:.6g} -> {nmed:.6g} ({100 * (nmed / bmed - 1):+.2f} %)")
    finally:
        os.remove(scene)
    for i, what in ((0, "mean"), (1, "median")):
        d = [100 * (r[1][i] / r[0][i] - 1) for r in rows if r[0][i] != 0]
        se = statistics.stdev(d) / len(d) ** 0.5 if len(d) > 1 else float("nan")
        spread = [r[0][i] for r in rows]
        print(f"{what}: paired difference {statistics.mean(d):+.2f} % ± {se:.2f} % (one standard error, "
              f"{len(d)} seeds); base varies {min(spread):.4g} to {max(spread):.4g} over the seeds")


if __name__ == "__main__":
    sys.exit(main())
