#!/usr/bin/env python3
"""Plots a sun sweep: the `<name>_sun_sweep.csv` that `morgana render --sun-zenith-deg` writes
(columns sun_zenith_deg, sensor, view_zenith_deg, view_azimuth_deg, L_mean, L_<lo>_<hi>nm...),
as the radiance of one sensor direction in each band against the solar zenith angle, on a log
scale. Needs matplotlib (scripts/requirements-python.txt; scripts/setup_venv.sh installs it).

    python3 scripts/plot_sun_sweep.py SWEEP.csv OUT.png [VIEW_ZENITH_DEG]

VIEW_ZENITH_DEG (default 0: the zenith) picks the direction; rows of other directions are left
out. Exit status 2 with a message on a file it cannot read or a direction it does not hold.
"""
import csv
import sys


def main() -> int:
    if len(sys.argv) not in (3, 4):
        print("usage: plot_sun_sweep.py SWEEP.csv OUT.png [VIEW_ZENITH_DEG]", file=sys.stderr)
        return 2
    path, out = sys.argv[1], sys.argv[2]
    view = float(sys.argv[3]) if len(sys.argv) == 4 else 0.0
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print(f"plot_sun_sweep.py: cannot read {path}: {e}", file=sys.stderr)
        return 2
    rows = [r for r in rows if abs(float(r["view_zenith_deg"]) - view) < 1e-9]
    if not rows:
        print(f"plot_sun_sweep.py: {path} has no row at view zenith {view}°", file=sys.stderr)
        return 2
    bands = [k for k in rows[0] if k.startswith("L_") and k.endswith("nm")]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    zen = [float(r["sun_zenith_deg"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    cmap = plt.get_cmap("turbo")
    for i, b in enumerate(bands):
        lo, hi = b[2:-2].split("_")
        ax.semilogy(zen, [float(r[b]) for r in rows], "o-", ms=3, color=cmap(0.1 + 0.8 * i / max(1, len(bands) - 1)),
                    label=f"{float(lo):.0f}–{float(hi):.0f} nm")
    ax.set_xlabel("solar zenith angle (°)")
    ax.set_ylabel("radiance (W m⁻² sr⁻¹ nm⁻¹)")
    ax.set_title(f"{rows[0]['sensor']}: view zenith {view:g}°")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
