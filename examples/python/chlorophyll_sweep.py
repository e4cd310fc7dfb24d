#!/usr/bin/env python3
"""Chlorophyll sweep: downwelling irradiance Ed(z) and remote-sensing reflectance Rrs(λ) of deep
Case 1 water for chlorophyll 0.01–10 mg m⁻³, from examples/chlorophyll_sweep.toml changed as a
dict in a loop (the notebook version of scripts/chl_sweep.sh).

    .venv/bin/python examples/python/chlorophyll_sweep.py --out out/chl_sweep.png [--photons 1000000]

At the scene's 10^6 photons a sweep takes a few minutes on 2 cores; fewer photons give noisier
spectra.

Needs the package (scripts/python_test.sh installs it into .venv) and matplotlib.
"""

import argparse
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import morgana

EXAMPLES = Path(__file__).resolve().parent.parent
CHL_MG_M3 = [0.01, 0.1, 1.0, 10.0]
DEPTHS_M = [1.0, 2.0, 5.0, 10.0, 20.0]


def sweep(photons: int, seed: int):
    base = tomllib.loads((EXAMPLES / "chlorophyll_sweep.toml").read_text())
    for chl in CHL_MG_M3:
        base["medium"][0]["chl_mg_m3"] = chl
        base["sensor"][0]["depths_m"] = DEPTHS_M
        scene = morgana.Scene.from_dict(base, base_dir=EXAMPLES).with_overrides(photons=photons, seed=seed)
        yield chl, morgana.render(scene, progress=False)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("out/chl_sweep.png"))
    ap.add_argument("--photons", type=int, default=1_000_000)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    fig, (ax_ed, ax_rrs) = plt.subplots(1, 2, figsize=(11, 4.5))
    for chl, result in sweep(args.photons, args.seed):
        profile = result.sensors["rrs"]
        at = profile["wavelength_nm"] == 495  # the 490–500 nm band
        ax_ed.plot(profile["Ed"][at], profile["depth_m"][at], "o-", label=f"{chl:g} mg m⁻³")
        surface = result.derived["rrs"]["surface"]
        ax_rrs.plot(surface["wavelength_nm"], surface["Rrs_per_sr"], label=f"{chl:g} mg m⁻³")
        print(f"chl {chl:g} mg/m3: Rrs(445)/Rrs(555) = "
              f"{np.interp(445, surface['wavelength_nm'], surface['Rrs_per_sr']) / np.interp(555, surface['wavelength_nm'], surface['Rrs_per_sr']):.2f}")
    ax_ed.set(xscale="log", xlabel="Ed at 495 nm, W m⁻² nm⁻¹", ylabel="depth, m", title="Ed(z)")
    ax_ed.invert_yaxis()
    ax_rrs.set(xlabel="wavelength, nm", ylabel="Rrs, sr⁻¹", title="Rrs(λ)")
    for ax in (ax_ed, ax_rrs):
        ax.legend(title="chlorophyll")
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
