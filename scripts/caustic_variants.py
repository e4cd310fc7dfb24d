#!/usr/bin/env python3
"""The Mitsuba benchmark's volume caustic in variants, to find where morgana and Mitsuba differ
(issue 17, the "3 % deficit" of the book's convergence chapter).

    .venv/bin/python scripts/caustic_variants.py RENDERER VARIANT [--spp N] [--chunks K]
        [--passes P] [--threads 2] [--bin target/release/morgana] [--out out/caustic_variants]

RENDERER: `mitsuba` (volpath, the benchmark's translation `peer_mitsuba.to_mitsuba`), `path`
(morgana's path tracer) or `photon_map` (morgana's progressive photon mapping with the
benchmark chain's pass settings, `--passes` passes a chunk). VARIANT:

- `bench`: `benches/scenes/volume_caustic.toml` as benchmarked;
- `no_sphere`: without the glass sphere (the snooted light, the fog and the walls only);
- `panel`: the snoot and its light replaced by a 0.6 m × 0.6 m panel under the ceiling,
  0.01 m below it, facing down (radiance 22.5 W m⁻² sr⁻¹ nm⁻¹: the snooted light's power).

    .venv/bin/python scripts/caustic_variants.py compare A/chunks.npy B/chunks.npy

compares two saved sets of chunks: A's mean over B's for the whole image, its interior (8
pixels in from the edges) and that border, and 16 × 16-pixel blocks.

`--set KEY=VALUE` (repeatable; TOML values: `final_gather=true`, `gather_rays=4`) changes the
morgana renderers' `[integrator]` keys.

Renders `--chunks` independent chunks (seeds 100, 101, ...) of `--spp` samples (Mitsuba, path)
or of `--passes` passes (photon_map), saves them (OUT/VARIANT_RENDERER/chunks.npy, linear sRGB)
and prints the benchmark's region means, summed over the channels, with the standard error of
the chunks' mean, and the whole image's.
"""

from __future__ import annotations

import argparse
import sys
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peer_mitsuba as pm  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

PANEL = """[[light]]
name = "panel"
type = "area"
shape = "quad"
origin = [-0.3, 0.99, -0.3]
u = [0.6, 0.0, 0.0]
v = [0.0, 0.0, 0.6]
spectrum = 1.0
scale = 22.5
"""

# One pass of the benchmark's progressive chain (peer_mitsuba.SCENES["volume_caustic"]).
CHAIN_PASS = pm.SCENES["volume_caustic"].progressive


def variant(name: str) -> str:
    """The scene text of a variant."""
    base = (ROOT / pm.SCENES["volume_caustic"].toml).read_text()
    if name == "no_sphere":
        i = base.index('[[shape]]\nname = "glass sphere"')
        return base[:i] + base[base.index("\n[[", i + 1) + 1:]
    if name == "panel":
        # The snoot's four quads and its light are the file's last five tables.
        return base[: base.index("# The snoot")] + PANEL
    return base


def settings(pairs: list[str]):
    """(key, value) of each `--set KEY=VALUE`, the value read as TOML."""
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            sys.exit(f"--set {pair!r}: expected KEY=VALUE, e.g. final_gather=true")
        yield key.strip(), tomllib.loads(f"v = {value}")["v"]


def render(args) -> np.ndarray:
    """The chunks' linear sRGB images, (chunks, height, width, 3)."""
    text = variant(args.variant)
    out = args.out / f"{args.variant}_{args.renderer}"
    out.mkdir(parents=True, exist_ok=True)
    images = []
    if args.renderer == "mitsuba":
        runner = pm.MitsubaRunner(text, args.threads)
        images = [runner.render(args.spp, seed=100 + c)[0] for c in range(args.chunks)]
        runner.close()
    else:
        for c in range(args.chunks):
            if args.renderer == "path":
                integrator = {"method": "path", "spp": args.spp, "seed": 100 + c}
            else:
                integrator = CHAIN_PASS | {"passes": args.passes, "seed": 100 + c}
            integrator |= dict(settings(args.set))
            images.append(pm.run_morgana(args.bin, text, integrator, out, "m", args.threads).rgb)
    chunks = np.array(images)
    np.save(out / "chunks.npy", chunks)
    return chunks


def compare(a_path: Path, b_path: Path):
    """Prints A's means over B's (channels summed): whole image, interior, border, blocks."""
    a, b = (np.load(x).sum(axis=3) for x in (a_path, b_path))
    h, w = a.shape[1:]
    inner = np.zeros((h, w), bool)
    inner[8:-8, 8:-8] = True
    whole = a.mean() / b.mean()
    print(f"{a_path} over {b_path}: whole image {whole:.4f}, interior {a[:, inner].mean() / b[:, inner].mean():.4f}, "
          f"border {a[:, ~inner].mean() / b[:, ~inner].mean():.4f}")
    print("16 x 16-pixel blocks, top row first:")
    blocks = [x.reshape(len(x), h // 16, 16, w // 16, 16).mean(axis=(0, 2, 4)) for x in (a, b)]
    for row in blocks[0] / blocks[1]:
        print("  " + " ".join(f"{v:.3f}" for v in row))


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "compare":
        return compare(Path(sys.argv[2]), Path(sys.argv[3]))
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("renderer", choices=["mitsuba", "path", "photon_map"])
    p.add_argument("variant", choices=["bench", "no_sphere", "panel"])
    p.add_argument("--spp", type=int, default=512, help="samples per pixel of a chunk (mitsuba, path)")
    p.add_argument("--passes", type=int, default=16, help="passes of a chunk (photon_map)")
    p.add_argument("--chunks", type=int, default=8)
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="an [integrator] key of the morgana renderers (repeatable)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--bin", type=Path, default=ROOT / "target/release/morgana")
    p.add_argument("--out", type=Path, default=ROOT / "out/caustic_variants")
    args = p.parse_args()
    chunks = render(args)
    regions = dict(pm.SCENES["volume_caustic"].regions)
    regions["whole image"] = (0, 0, chunks.shape[2], chunks.shape[1])
    print(f"{args.variant}, {args.renderer}: {len(chunks)} chunks; region means (R + G + B) ± SE of the mean")
    for name, (x0, y0, x1, y1) in regions.items():
        v = chunks[:, y0:y1, x0:x1].reshape(len(chunks), -1, 3).mean(axis=1).sum(axis=1)
        se = v.std(ddof=1) / np.sqrt(len(v)) if len(v) > 1 else float("nan")
        print(f"  {name:18s} {v.mean():12.6g} ± {se:.3g}")


if __name__ == "__main__":
    main()
