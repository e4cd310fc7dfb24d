#!/usr/bin/env python3
"""Sky radiance by ring of view zenith angle, against a reference run: reads the outputs of
scripts/bench_sky.sh (OUT/seed1/*.csv and OUT/seed2/*.csv of the 256 × 256 equal-area all-sky
image over the hemisphere) and prints, for each ring of view zenith angle θ, the mean band-mean
radiance of the reference run and every other run's mean relative to it. A pixel at ρ (in units
of the image circle's radius) from the centre looks at θ = 2 asin(ρ sin 45°); the pixels that see
the sun's disc (brighter than 100 × the median, as bench_sky.sh's sky mean) are left out, and the
two seeds are averaged.

    scripts/sky_rings.py REFERENCE_OUT OTHER_OUT...
"""
import csv
import glob
import math
import sys

N = 256
RINGS_DEG = [(0, 30), (30, 60), (60, 75), (75, 85), (85, 89)]


def image(out, seed):
    path = glob.glob(f"{out}/seed{seed}/*.csv")[0]
    with open(path) as f:
        rows = list(csv.reader(f))
    head, body = rows[0], rows[1:]
    bands = [i for i, h in enumerate(head) if h.startswith("L_") or h.endswith("nm")]
    return {(int(r[0]), int(r[1])): sum(float(r[i]) for i in bands) / len(bands) for r in body}


def view_zenith_deg(i, j):
    rho = math.hypot(i + 0.5 - N / 2, j + 0.5 - N / 2) / (N / 2)
    return 2 * math.degrees(math.asin(rho * math.sin(math.radians(45)))) if rho < 1 else None


def ring_means(out):
    a, b = image(out, 1), image(out, 2)
    both = sorted(a[k] + b[k] for k in a)
    median = both[len(both) // 2]
    means = []
    for lo, hi in RINGS_DEG:
        vals = [(a[k] + b[k]) / 2 for k in a
                if (t := view_zenith_deg(*k)) is not None and lo <= t < hi and a[k] + b[k] <= 100 * median]
        means.append(sum(vals) / len(vals))
    return means


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    ref = ring_means(sys.argv[1])
    print("rings of view zenith (deg):", ", ".join(f"{lo}–{hi}" for lo, hi in RINGS_DEG))
    print(f"{sys.argv[1]} (W m^-2 sr^-1 nm^-1): " + ", ".join(f"{v:.4e}" for v in ref))
    for out in sys.argv[2:]:
        print(f"{out}: " + ", ".join(f"{100 * (v / r - 1):+.1f} %" for v, r in zip(ring_means(out), ref)))


if __name__ == "__main__":
    main()
