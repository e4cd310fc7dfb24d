#!/usr/bin/env python3
"""A render read into colour-science: the mean spectrum of an image becomes a
colour.SpectralDistribution, whose CIE XYZ (k = 683 lm/W: luminance in cd m⁻²) and sRGB are
compared with the linear sRGB morgana computed for the same pixels.

    .venv/bin/python examples/python/colour_science.py [--scene examples/bluish_box.toml]

Needs the package and colour-science (both in .venv: scripts/setup_venv.sh, scripts/python_test.sh).
"""

import argparse
from pathlib import Path

import colour
import numpy as np

import morgana

EXAMPLES = Path(__file__).resolve().parent.parent


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", type=Path, default=EXAMPLES / "white_furnace.toml")
    ap.add_argument("--photons", type=int, default=50_000)
    args = ap.parse_args()
    result = morgana.render(morgana.Scene.from_file(args.scene).with_overrides(photons=args.photons), progress=False)
    mean = result.radiance.reshape(-1, result.radiance.shape[2]).mean(axis=0)
    # Band averages as a step spectrum on a 1 nm grid (each band's value over its width).
    edges = result.band_edges_nm
    grid = np.arange(np.ceil(edges[0]), np.floor(edges[-1]) + 1)
    values = mean[np.clip(np.searchsorted(edges, grid, side="right") - 1, 0, len(mean) - 1)]
    sd = colour.SpectralDistribution(dict(zip(grid, values)), name="mean radiance")
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    xyz = colour.sd_to_XYZ(sd, cmfs=cmfs, k=683.0, method="Integration")
    rgb_colour = colour.XYZ_to_sRGB(xyz, apply_cctf_encoding=False)
    rgb_morgana = result.rgb.reshape(-1, 3).mean(axis=0)
    print(f"scene {args.scene.name}: {len(mean)} bands {edges[0]:g}–{edges[-1]:g} nm")
    print(f"colour-science: XYZ = {np.round(xyz, 4)}, linear sRGB = {np.round(rgb_colour, 4)}")
    print(f"morgana:        linear sRGB = {np.round(rgb_morgana, 4)}")
    print(f"relative difference: {np.abs(rgb_colour - rgb_morgana).max() / np.abs(rgb_morgana).max():.2%}")


if __name__ == "__main__":
    main()
