#!/usr/bin/env python3
"""Sun-elevation sweep of the setting sun's flattening: the ratio of the refracted sun's
vertical to horizontal diameter as its lower limb goes from the horizon to 10° above it,
in the standard and tropical atmospheres and over the layered air of a Fata Morgana.

    .venv/bin/python examples/python/sun_flattening.py --out out/sun_flattening.png

Needs the package (scripts/python_test.sh installs it into .venv) and matplotlib.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import morgana


def flattening(atmosphere: str, elevations_deg):
    ratios = []
    for e in elevations_deg:
        sun = morgana.refraction(atmosphere, [e], sun_lower_limb_deg=e)["sun"]
        ratios.append(np.nan if sun is None else sun["ratio"])
    return np.array(ratios)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("out/sun_flattening.png"))
    args = ap.parse_args()
    elevations = np.linspace(0.0, 10.0, 41)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for atmosphere in ("usa76", "tropical", "fata_morgana"):
        ratio = flattening(atmosphere, elevations)
        ax.plot(elevations, ratio, label=atmosphere)
        print(f"{atmosphere}: vertical/horizontal diameter {ratio[np.searchsorted(elevations, 0.0)]:.3f} with the lower limb on the horizon")
    ax.set(xlabel="apparent elevation of the lower limb, °", ylabel="vertical / horizontal diameter",
           title="The flattened setting sun")
    ax.legend()
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
