#!/usr/bin/env python3
"""Measure finished morgana renders again against a scene's current Mitsuba reference (issue 17,
"Measured goals"), at equal CPU time, without rendering anything.

    .venv/bin/python scripts/remeasure_mitsuba.py volume_caustic \\
        out/mitsuba_bench/volume_caustic/morgana_adaptive/volume_caustic.exr=306.0 ...

Each argument is an EXR (or a linear-sRGB .npy that `peer_mitsuba.py --progressive` keeps in
OUT/SCENE/stops/) and the CPU seconds it cost. For each, three errors against the reference
(out/mitsuba_bench/SCENE/reference.npz, rendered or extended by `peer_mitsuba.py
--reference-only --ref-spp N --ref-chunks M`), all over pixels and linear sRGB channels:

- corrected: sqrt(RMSE^2 - sigma_ref^2), sigma_ref^2 the reference's variance from its chunks'
  spread (what peer_mitsuba.py reports);
- split reference: sqrt(mean over pixels of (x - A)(x - B)), A and B the reference's two
  independent halves: unbiased for x's mean squared error whatever the reference's noise, with
  the standard error of that mean square from the products' spread (`Metric.cross`);
- masked: the corrected and the split-reference errors without the glint pixels, and the
  glints' share of the split-reference squared error.

Mitsuba's error at the same CPU time comes from the reference's own chunks, each an
independent Mitsuba run of `per` spp whose CPU time was recorded: Mitsuba is unbiased, so its
mean squared error at `per` spp is the mean over pixels of the chunks' sample variance
(unbiased for it from n chunks), and at CPU time t it is that times (CPU per chunk / t), since
its variance falls as 1/spp and its cost grows as spp. This uses n independent runs where
`peer_mitsuba.py` uses one run measured against the noisy reference.
"""

from __future__ import annotations

import argparse
import math
import sys
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peer_mitsuba as pm  # noqa: E402


def square_se(x: float, se: float, mean: float) -> str:
    """The standard error of a split-reference squared error x², relative to x² — or, where the
    estimate of x² came out at or below 0 (clipped to x = 0: the reference's noise exceeds the
    image's error), as the root of that standard error in % of the image mean."""
    if x > 0:
        return f"± {100 * se / x**2:.0f}%"
    return f"estimated ≤ 0, ± ({100 * math.sqrt(se) / mean:.1f}% of the mean)²"


def mitsuba_mse_per_chunk(z) -> tuple[float, float, float, float, int]:
    """(mean over pixels of one chunk's variance, that over the unmasked ..., CPU s per chunk,
    the standard error of the first from the chunks' spread, n). Needs the chunk images."""
    n = int(z["n"])
    mean = z["total"] / n
    var = np.maximum(z["squares"] - n * mean * mean, 0.0) / (n - 1)
    images = z["images"]
    cpu = float(z["cpu_seconds"]) / len(images)
    # The per-chunk squared deviations' mean over pixels, one number per single chunk: their
    # spread says how well n chunks pin the mean variance down (heavy tails show here).
    per_chunk = np.array([np.mean((img - mean) ** 2) for img in images]) * n / (n - 1)
    return float(var.mean()), var, cpu, float(per_chunk.std(ddof=1) / math.sqrt(len(per_chunk))), n


def load_image(path: Path) -> np.ndarray:
    return np.load(path) if path.suffix == ".npy" else pm.read_exr_rgb(path)


def own_standard_error(path: Path, rgb: np.ndarray) -> np.ndarray | None:
    """morgana's own standard error of each pixel's linear sRGB, from the EXR's `stderr.` layer
    with the bands taken as fully correlated (as a glint's coverage error is): each channel times
    the pixel's sum of band standard errors over its sum of band values. None for a .npy."""
    if path.suffix == ".npy":
        return None
    import OpenEXR

    ch = OpenEXR.File(str(path), separate_channels=True).channels()
    bands = sorted(k for k in ch if k.startswith("S0."))
    if not bands or f"stderr.{bands[0]}" not in ch:
        return None
    total = sum(np.asarray(ch[k].pixels, dtype=np.float64) for k in bands)
    se = sum(np.asarray(ch[f"stderr.{k}"].pixels, dtype=np.float64) for k in bands)
    return rgb * (se / np.maximum(total, 1e-300))[..., None]


def deeper_window(path: Path, ref, var_chunk: np.ndarray, per: int) -> np.ndarray:
    """Puts the deeper render of `path` (scripts/glint_reference.py) into the reference `ref` in
    its window: mean, variance of the mean, and the two halves (its first and second half of
    chunks); returns Mitsuba's per-chunk variance `var_chunk` (one chunk of `per` spp) with the
    window's taken from the deeper chunks' spread, per sample, over `per` samples."""
    g = np.load(path)
    y0, x0, y1, x1 = (int(v) for v in g["window"])
    win = (slice(y0, y1), slice(x0, x1))
    images = g["images"]
    m = len(images)
    deep_per = int(g["spp"]) // m
    ref.rgb = ref.rgb.copy()
    ref.variance = ref.variance.copy()
    ref.rgb[win] = g["rgb"]
    ref.variance[win] = g["variance"]
    a, b = (h.copy() for h in ref.halves)
    a[win] = images[: m // 2].mean(0)
    b[win] = images[m // 2:].mean(0)
    ref.halves = (a, b)
    var_chunk = var_chunk.copy()
    var_chunk[win] = images.var(0, ddof=1) * deep_per / per
    print(f"reference rows {y0}..{y1 - 1}, columns {x0}..{x1 - 1} from {path.name}: {int(g['spp'])} spp in {m} chunks")
    return var_chunk


def blocks_z(img: np.ndarray, ref, size: int = 8) -> np.ndarray:
    """(morgana's block mean - the reference's) / the reference's standard error of it, per
    size x size block of luminance-like channel sums."""
    h, w = img.shape[:2]
    shape = (h // size, size, w // size, size)
    mean = lambda x: x.sum(-1)[: shape[0] * size, : shape[2] * size].reshape(shape).mean(axis=(1, 3))  # noqa: E731
    var = ref.variance.sum(-1)[: shape[0] * size, : shape[2] * size].reshape(shape).sum(axis=(1, 3)) / size**4
    return (mean(img) - mean(ref.rgb)) / np.sqrt(var)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene", choices=list(pm.SCENES))
    p.add_argument("renders", nargs="+", help="IMAGE=CPU_SECONDS (EXR or .npy)")
    p.add_argument("--out", type=Path, default=pm.ROOT / "out/mitsuba_bench")
    p.add_argument("--exclude", metavar="Y0,X0,Y1,X1", help="also measure without these pixels (rows Y0..Y1, "
                   "columns X0..X1, exclusive ends), e.g. a glint where the reference disagrees with its own "
                   "geometry (scripts/glint_coverage.py)")
    p.add_argument("--glint-reference", action="store_true",
                   help="replace the reference in the window of each OUT/SCENE/glint_reference_*.npz "
                   "(scripts/glint_reference.py) by that deeper render: its mean, its variance, its two "
                   "halves (the first and second half of its chunks), and Mitsuba's per-chunk variance "
                   "there from its chunks' spread scaled to the reference's spp per chunk")
    args = p.parse_args(argv)
    spec = pm.SCENES[args.scene]
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    z = np.load(args.out / args.scene / "reference.npz")
    if "images" not in z:
        p.error("the reference has no chunk images: extend it with peer_mitsuba.py --reference-only first")
    sums = pm.ChunkSums.from_arrays(z)
    ref = sums.reference()
    mse_mi, var_mi, cpu_mi, mse_mi_se, n = mitsuba_mse_per_chunk(z)
    if args.glint_reference:
        windows = sorted((args.out / args.scene).glob("glint_reference_*.npz"))
        # Windows of a depth-limited volpath (`glint_reference.py --max-depth`) are not the reference.
        windows = [w for w in windows if not w.name.endswith(".partial.npz") and "_depth" not in w.name]
        if not windows:
            p.error(f"--glint-reference: no glint_reference_*.npz in {args.out / args.scene}")
        for w in windows:
            var_mi = deeper_window(w, ref, var_mi, sums.per)
        mse_mi = float(var_mi.mean())
    full = pm.Metric.over(ref, np.ones(ref.rgb.shape[:2], dtype=bool))
    glints = pm.specular_light_mask(tomllib.loads((pm.ROOT / spec.toml).read_text()), spec.mask_glints_dilate) \
        if spec.mask_glints_dilate is not None else np.zeros(ref.rgb.shape[:2], dtype=bool)
    masked = pm.Metric.over(ref, ~glints)
    mse_mi_m = float(var_mi[~glints].mean())
    a, b = ref.halves
    half_noise = math.sqrt(float(np.mean((a - b) ** 2)) / 4)
    print(f"{args.scene}: reference {ref.spp} spp in {n} chunks of {sums.per}, mean {full.mean:.5g}; "
          f"its noise RMSE {full.noise:.5g} ({100 * full.noise / full.mean:.1f}% of the mean; "
          f"half the two halves' RMS difference: {100 * half_noise / full.mean:.1f}%)")
    print(f"Mitsuba, one chunk ({sums.per} spp, {cpu_mi:.1f} CPU s): RMSE {math.sqrt(mse_mi):.5g} "
          f"({100 * math.sqrt(mse_mi) / full.mean:.0f}% of the mean; its square ± {100 * mse_mi_se / mse_mi:.0f}%), "
          f"without the {int(glints.sum())} glint pixels {100 * math.sqrt(mse_mi_m) / masked.mean:.0f}%")
    print("image | CPU s | corrected | split reference (± SE of the square) | masked | Mitsuba | ratio "
          "| ratio (split) | masked Mitsuba | masked ratio")
    for spec_arg in args.renders:
        path, _, cpu = spec_arg.rpartition("=")
        cpu = float(cpu)
        img = load_image(Path(path))
        _, corr = full.errors(img)
        cross, cross_se = full.cross(img)
        _, corr_m = masked.errors(img)
        cross_m, _ = masked.cross(img)
        prod = np.sum((img - a) * (img - b), axis=-1)
        glint_share = float(prod[glints].sum() / prod.sum())
        mi = math.sqrt(mse_mi * cpu_mi / cpu)
        mi_m = math.sqrt(mse_mi_m * cpu_mi / cpu)
        lo = math.sqrt(max(cross**2 - 2 * cross_se, 0.0))
        hi = math.sqrt(cross**2 + 2 * cross_se)

        def pc(x, m=full.mean):
            return f"{100 * x / m:.1f}%"

        print(f"{path} | {cpu:.0f} | {pc(corr)} | {pc(cross)} ({pc(lo)}–{pc(hi)}) | {pc(corr_m, masked.mean)} | "
              f"{pc(mi)} | {corr / mi:.3f} | {cross / mi:.3f} ({lo / mi:.3f}–{hi / mi:.3f}) | "
              f"{pc(mi_m, masked.mean)} | {corr_m / mi_m:.3f}")
        if args.exclude:
            y0, x0, y1, x1 = (int(v) for v in args.exclude.split(","))
            keep = np.ones(ref.rgb.shape[:2], dtype=bool)
            keep[y0:y1, x0:x1] = False
            rest = pm.Metric.over(ref, keep)
            mi_r = math.sqrt(float(var_mi[keep].mean()) * cpu_mi / cpu)
            _, corr_r = rest.errors(img)
            cross_r, cross_r_se = rest.cross(img)
            print(f"    without rows {y0}..{y1 - 1}, columns {x0}..{x1 - 1}: corrected {pc(corr_r, rest.mean)}, "
                  f"split reference {pc(cross_r, rest.mean)} (its square {square_se(cross_r, cross_r_se, rest.mean)}), "
                  f"Mitsuba {pc(mi_r, rest.mean)}: ratio {corr_r / mi_r:.3f} (split {cross_r / mi_r:.3f})")
        own = own_standard_error(Path(path), img)
        if own is not None:
            for what, sel in (("the glint pixels", glints), ("the other pixels", ~glints)):
                mse = float(np.mean(((img - a) * (img - b))[sel]))
                print(f"    {what}: split-reference squared error / morgana's own variance "
                      f"(stderr layer, bands correlated) = {mse / float(np.mean(own[sel] ** 2)):.1f}")
        means = [float(img[sel].sum() / ref.rgb[sel].sum()) for sel in (~glints, glints)]
        print(f"    mean over the reference's: {means[0]:.4f} without the glint pixels, {means[1]:.4f} on them "
              f"(per channel without them: {', '.join(f'{img[~glints][:, c].sum() / ref.rgb[~glints][:, c].sum():.4f}' for c in range(3))})")
        if spec.regions:
            print("    regions, mean over the reference's: " + ", ".join(
                f"{name} {img[y0:y1, x0:x1].sum() / ref.rgb[y0:y1, x0:x1].sum():.3f}"
                for name, (y0, x0, y1, x1) in spec.regions.items()))
        z = blocks_z(img, ref)
        print(f"    8 x 8-pixel blocks: {int((abs(z) > 3).sum())} of {z.size} differ from the reference by more than 3 "
              f"of its standard errors ({int((z > 3).sum())} morgana-brighter); largest |z| {abs(z).max():.1f}")
        print(f"    masked, split reference: {pc(cross_m, masked.mean)} (ratio {cross_m / mi_m:.3f}); the glint pixels "
              f"hold {100 * glint_share:.0f}% of the split-reference squared error")
    return 0


if __name__ == "__main__":
    sys.exit(main())
