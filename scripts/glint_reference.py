#!/usr/bin/env python3
"""A deeper Mitsuba reference in a window of pixels: the glints of the volume caustic (issue 17,
"Measured goals"), where the 8 192-spp reference's chunks disagree with the geometric coverage.

    .venv/bin/python scripts/glint_reference.py [--scene volume_caustic] [--window 38,38,43,43]
        [--spp 1048576] [--chunks 32] [--threads 2] [--max-depth D] [--first-seed S]

Renders the scene's Mitsuba translation (`peer_mitsuba.to_mitsuba`, the same volpath integrator
as the reference) with the film cropped to the window (rows Y0 to Y1 − 1, columns X0 to X1 − 1,
as `remeasure_mitsuba.py --exclude` reads them), `--spp` samples per pixel in `--chunks`
independent chunks (seeds S + i, S = 2 000 000 by default: none shared with the reference's
chunks), on `--threads` worker processes. Saves the chunks' sums, squares and images beside the
reference (OUT/SCENE/glint_reference_Y0_X0_Y1_X1.npz; resumable from its .partial.npz after each
chunk) and prints the window's mean with the chunks' standard error and, if OUT/SCENE holds a
reference, per pixel of the window the new value and its standard error from the chunks' spread
beside the reference's, in luminance-like sums of the linear sRGB channels, and each pixel's
share of the window's 3 × 3 centre. `remeasure_mitsuba.py --glint-reference` puts every such
window into the reference.

`--max-depth D` limits volpath's path length (2: direct light and single scattering, the part a
renderer computes without photons) and adds `_depthD` to the file's name, which
`remeasure_mitsuba.py` leaves out of the reference.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peer_mitsuba as pm  # noqa: E402


def cropped(scene_text: str, window: tuple[int, int, int, int], mi, max_depth: int = -1) -> dict:
    """The Mitsuba scene with its film cropped to the window (and volpath's `max_depth` set:
    2 keeps single scattering and direct light only)."""
    y0, x0, y1, x1 = window
    d = pm.to_mitsuba(tomllib.loads(scene_text), mi)
    d["integrator"]["max_depth"] = max_depth
    d["sensor"]["film"] |= {"crop_offset_x": x0, "crop_offset_y": y0, "crop_width": x1 - x0, "crop_height": y1 - y0}
    return d


def worker(scene_text: str, window, max_depth: int, jobs, results):
    """One Mitsuba process: (spp, seed) requests answered with (linear sRGB, CPU seconds)."""
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    mi.set_log_level(mi.LogLevel.Warn)
    scene = mi.load_dict(cropped(scene_text, window, mi, max_depth))
    results.put("ready")
    while (job := jobs.get()) is not None:
        spp, seed = job
        c = time.process_time()
        img = np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float64)
        results.put((seed, pm.mitsuba_xyz_to_srgb(img), time.process_time() - c))


def render_chunks(scene_text: str, window, max_depth: int, per: int, seeds: list[int], threads: int, save):
    """Chunks of `per` spp, one per seed, on `threads` processes; `save(seed, img, cpu)` as each
    arrives."""
    import multiprocessing as mp

    ctx = mp.get_context("spawn")
    jobs, results = ctx.Queue(), ctx.Queue()
    procs = [ctx.Process(target=worker, args=(scene_text, window, max_depth, jobs, results), daemon=True)
             for _ in range(threads)]
    for proc in procs:
        proc.start()
    for _ in procs:
        results.get()
    for seed in seeds:
        jobs.put((per, seed))
    for _ in seeds:
        save(*results.get())
    for _ in procs:
        jobs.put(None)
    for proc in procs:
        proc.join(timeout=10)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", default="volume_caustic", choices=list(pm.SCENES))
    p.add_argument("--window", default="38,38,43,43", help="Y0,X0,Y1,X1: rows Y0..Y1-1, columns X0..X1-1")
    p.add_argument("--spp", type=int, default=1048576)
    p.add_argument("--chunks", type=int, default=32)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", type=Path, default=pm.ROOT / "out/mitsuba_bench")
    p.add_argument("--max-depth", type=int, default=-1,
                   help="volpath's max_depth (-1: unlimited, the reference's; 2: single scattering and direct light)")
    p.add_argument("--first-seed", type=int, default=2_000_000,
                   help="chunk i renders with seed FIRST_SEED + i (the default shares none with the reference's chunks)")
    args = p.parse_args(argv)
    window = tuple(int(v) for v in args.window.split(","))
    y0, x0, y1, x1 = window
    if not (y1 > y0 >= 0 and x1 > x0 >= 0):
        sys.exit(f"--window {args.window}: want Y0,X0,Y1,X1 with Y0 < Y1 and X0 < X1")
    if args.spp % args.chunks:
        sys.exit(f"--spp {args.spp} is not a multiple of --chunks {args.chunks}")
    per = args.spp // args.chunks
    scene_text = (pm.ROOT / pm.SCENES[args.scene].toml).read_text()
    out = args.out / args.scene
    out.mkdir(parents=True, exist_ok=True)
    depth = "" if args.max_depth == -1 else f"_depth{args.max_depth}"
    path = out / f"glint_reference_{y0}_{x0}_{y1}_{x1}{depth}.npz"
    partial = path.with_suffix(".partial.npz")
    key = f"{args.window} {per} {args.max_depth} {args.first_seed}"
    images, cpus, done = [], [], []
    if partial.exists():
        z = np.load(partial)
        if str(z["key"]) == key:
            images, cpus, done = list(z["images"]), list(z["cpus"]), list(z["seeds"])
            print(f"resuming: {len(done)} chunks of {per} spp")

    def save(seed, img, cpu):
        images.append(img)
        cpus.append(cpu)
        done.append(seed)
        tmp = partial.with_suffix(".tmp.npz")
        np.savez_compressed(tmp, images=np.stack(images), cpus=np.array(cpus), seeds=np.array(done), key=key)
        os.replace(tmp, partial)
        print(f"  chunk {len(done)}/{args.chunks}: {per} spp, CPU {cpu:.1f} s", flush=True)

    seeds = [args.first_seed + i for i in range(args.chunks) if args.first_seed + i not in done]
    if seeds:
        render_chunks(scene_text, window, args.max_depth, per, seeds, args.threads, save)
    stack = np.stack(images)
    n = len(stack)
    mean = stack.mean(0)
    var = stack.var(0, ddof=1) / n
    tmp = path.with_suffix(".tmp.npz")
    np.savez_compressed(tmp, window=np.array(window), rgb=mean, variance=var, images=stack, spp=per * n,
                        cpu_seconds=float(np.sum(cpus)))
    os.replace(tmp, path)
    partial.unlink(missing_ok=True)

    means = stack.sum(-1).mean((1, 2))
    print(f"window rows {y0}..{y1 - 1}, columns {x0}..{x1 - 1}, {per * n} spp: mean of the sums of the linear sRGB "
          f"channels {means.mean():.6g} ± {means.std(ddof=1) / math.sqrt(n):.3g} (chunks' spread)")
    if not (out / "reference.npz").exists():
        print(f"no {out / 'reference.npz'} to compare the window with")
        return 0
    z = np.load(out / "reference.npz")
    win = (slice(y0, y1), slice(x0, x1))
    ref, ref_var = z["rgb"][win].sum(-1), z["variance"][win].sum(-1)
    new, new_var = mean.sum(-1), var.sum(-1)
    print(f"window rows {y0}..{y1 - 1}, columns {x0}..{x1 - 1}: {per * n} spp here against the reference's {int(z['spp'])}"
          f" ({np.sum(cpus):.0f} CPU s); sums of the linear sRGB channels, ± one standard error")
    for j in range(new.shape[0]):
        cells = [f"{new[j, i]:9.4g} ± {math.sqrt(new_var[j, i]):7.2g} (ref {ref[j, i]:9.4g} ± {math.sqrt(ref_var[j, i]):7.2g})"
                 for i in range(new.shape[1])]
        print(f"  row {y0 + j}: " + " | ".join(cells))
    cy, cx = (y1 - y0 - 1) // 2, (x1 - x0 - 1) // 2
    centre = (slice(cy - 1, cy + 2), slice(cx - 1, cx + 2))
    print("shares of the centre 3 x 3 (new / reference):")
    for j in range(cy - 1, cy + 2):
        print("  " + "  ".join(f"({y0 + j},{x0 + i}) {new[j, i] / new[centre].sum():.3f} / {ref[j, i] / ref[centre].sum():.3f}"
                               for i in range(cx - 1, cx + 2)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
