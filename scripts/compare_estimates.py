#!/usr/bin/env python3
"""How the volume map's estimate and the direct light's source change an example's image.

Renders each EXAMPLE (a name in examples/) four ways — `direct` = "photon_map" or
"shadow_rays", `volume_estimate` = "point" or "beam", set in [integrator] — and prints, per
variant, the image mean (all spectral channels of the EXR summed per pixel) over that of the
reference variant, the 5th percentile, median and 95th percentile of the ratio in blocks of
BLOCK × BLOCK pixels, and the CPU seconds of the render. The reference is shadow rays with the
beam estimate (shadow rays give exact single scattering, independent of the photon map), or
the first variant that rendered where a scene's curved paths refuse shadow rays.

    .venv/bin/python scripts/compare_estimates.py EXAMPLE... [--bin target/release/morgana]
        [--out /tmp/compare_estimates] [--block 8] [--shrink 1] [--variant 'LABEL: TOML; TOML'...]

`--variant` (repeatable) replaces the four variants by the given ones: a label, then
[integrator] lines separated by `;` (e.g. `--variant 'fixed 0.3 m: volume_estimate = "point";
volume_k = 100000; volume_max_radius = 0.3'`); the first variant is then the reference, and
`direct` stays the scene's unless a variant sets it.

Needs numpy and OpenEXR (scripts/requirements-colour.txt). The modified copies are written
beside the examples (examples/.estimate_*.toml, so that relative paths resolve) and removed."""
import argparse, glob, os, re, subprocess, sys
import numpy as np
import OpenEXR

# (label, [integrator] lines): the default variants, the reference last.
VARIANTS = [
    (f"{d.replace('_', ' ')}, {e}", [f'direct = "{d}"', f'volume_estimate = "{e}"'])
    for d in ("photon_map", "shadow_rays")
    for e in ("point", "beam")
]


def variant_file(example, lines, shrink):
    text = open(f"examples/{example}.toml").read()
    for line in lines:
        key = line.split("=")[0].strip()
        text = re.sub(rf"(?m)^{re.escape(key)} = .*\n", "", text)
    for key in ("width", "height"):
        text = re.sub(rf"(?m)^{key} = (\d+)", lambda m: f"{key} = {max(1, int(m.group(1)) // shrink)}", text, count=1)
    keys = "\n".join(lines)
    if re.search(r"(?m)^\[integrator\]$", text):
        text = re.sub(r"(?m)^\[integrator\]$", "[integrator]\n" + keys, text, count=1)
    else:
        text += "\n[integrator]\n" + keys + "\n"
    path = f"examples/.estimate_{example}.toml"
    open(path, "w").write(text)
    return path


def image(directory):
    exr = sorted(f for f in glob.glob(os.path.join(directory, "*.exr")))[0]
    chans = OpenEXR.File(exr, separate_channels=True).channels()
    spectral = [k for k in chans if k.startswith("S0.")]
    return np.sum([np.asarray(chans[k].pixels, dtype=np.float64) for k in spectral], axis=0)


def render(a, example, label, lines):
    out = os.path.join(a.out, example + "." + re.sub(r"[^A-Za-z0-9.]+", "_", label))
    os.makedirs(out, exist_ok=True)
    scene = variant_file(example, lines, a.shrink)
    try:
        timed = ["/usr/bin/time", "-f", "%U %S", "-o", os.path.join(out, "time")]
        run = subprocess.run(timed + [a.bin, "render", scene, "--out", out, "--quiet"], capture_output=True, text=True)
    finally:
        os.remove(scene)
    if run.returncode != 0:
        print(f"{example}, {label}: not rendered: {run.stderr.strip().splitlines()[-1]}")
        return None
    user, system = open(os.path.join(out, "time")).read().split()[-2:]
    return image(out), float(user) + float(system)


def blocks(im, b):
    h, w = (im.shape[0] // b) * b, (im.shape[1] // b) * b
    return im[:h, :w].reshape(h // b, b, w // b, b).mean(axis=(1, 3))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("examples", nargs="+")
    ap.add_argument("--bin", default="target/release/morgana")
    ap.add_argument("--out", default="/tmp/compare_estimates")
    ap.add_argument("--block", type=int, default=8)
    ap.add_argument("--shrink", type=int, default=1)
    ap.add_argument("--variant", action="append", default=[])
    a = ap.parse_args()
    variants = VARIANTS
    if a.variant:
        variants = [(v.split(":", 1)[0].strip(), [s.strip() for s in v.split(":", 1)[1].split(";") if s.strip()]) for v in a.variant]
        variants = variants[1:] + variants[:1]
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    a.bin = os.path.abspath(a.bin) if os.sep in a.bin else a.bin
    print(f"{'example':26s} {'variant':34s} {'mean/ref':>9s} {'blocks p5':>9s} {'median':>7s} {'p95':>7s} {'CPU s':>7s}")
    for ex in a.examples:
        done = {label: render(a, ex, label, lines) for label, lines in variants}
        done = {label: r for label, r in done.items() if r is not None}
        if not done:
            sys.exit(f"{ex}: no variant rendered")
        # The reference is the last variant (shadow rays with the beam estimate by default), or
        # the first that rendered where a scene refuses it.
        ref_label = variants[-1][0] if variants[-1][0] in done else next(iter(done))
        ref = done[ref_label][0]
        ref_blocks = blocks(ref, a.block)
        for label, (im, cpu) in done.items():
            r = blocks(im, a.block) / np.where(ref_blocks > 0, ref_blocks, np.nan)
            p5, med, p95 = np.nanpercentile(r, [5, 50, 95])
            print(f"{ex:26s} {label:34s} {im.mean() / ref.mean():9.4f} {p5:9.3f} {med:7.3f} {p95:7.3f} {cpu:7.1f}")
        print(f"{ex}: reference {ref_label}")


if __name__ == "__main__":
    main()
