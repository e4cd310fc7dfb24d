#!/usr/bin/env python3
"""morgana's zenith through twilight against SASKTRAN2, estimator by estimator (issue 19).

Renders the scene of tests/spherical_benchmarks.rs's SASKTRAN2 comparison -- the limb benchmark's
air of Zawada et al. (2021) (tests/data/zawada2021), pure Rayleigh at 351 or 442 nm, a black
round Earth, a sky_radiance sensor at the zenith 1 m up, a point sun of unit irradiance -- with
`--sun-zenith-deg` sweeps: single scattering (`photons = 0`), the path tracer, and the volume
photon map with the given photon counts (folded about the sun's axis where the plan folds), and
prints each run's zenith radiance against SASKTRAN2's 1-D and 2-D totals
(tests/data/sasktran2_twilight/zenith_radiance.csv, written by scripts/sasktran_twilight.py),
with each run's CPU seconds. Standard library only.

    scripts/twilight_sasktran.py [--bin target/release/morgana] [--out /tmp/twilight_sasktran]
        [--nm 351] [--zeniths 90,92,94,96] [--photons 1000000,10000000] [--seeds 1,2]
        [--path-samples 1000000] [--map-lines 'volume_k = 20'] [--runs single,path,map] [--eye-m 1]
"""

import argparse
import csv
import resource
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# The benchmark's Rayleigh cross-sections, cm² (its data set; tests/spherical_benchmarks.rs).
CROSS_SECTION_CM2 = {351.0: 2.87884699e-26, 442.0: 1.10228657e-26}
T_K = 250.0
R_STAR = 8.31432
N_A = 6.022169e23


def write_air(out):
    """The benchmark air as an atmosphere file (P = N R* T / N_A at 250 K, as the tests write it)."""
    rows = ["altitude_m,temperature_k,pressure_pa"]
    with open(ROOT / "tests/data/zawada2021/number_density.csv") as f:
        for row in list(csv.reader(f))[1:]:
            h, n_cm3 = float(row[0]), float(row[1])
            rows.append(f"{h!r},{T_K!r},{n_cm3 * 1e6 * R_STAR * T_K / N_A!r}")
    (out / "zawada2021.csv").write_text("\n".join(rows) + "\n")
    (out / "zawada2021.toml").write_text(
        'name = "zawada2021"\nprofile = "zawada2021.csv"\ntop_m = 100000.0\n'
        'earth = "spherical"\nearth_radius_m = 6371000.0\n'
    )


def scene(nm, integrator, samples, eye_m=1.0):
    xs = CROSS_SECTION_CM2[nm]
    return f"""
[camera]
position = [0.0, 1.0, 0.0]
look_at = [0.0, 2.0, 0.001]
fov_deg = 1.0
width = 1
height = 1

[output]
bands = 1
min_nm = {nm!r}
max_nm = {nm + 0.0002!r}

[integrator]
{integrator}
spp = 1

[world]
medium = "air"
earth = "spherical"

[[medium]]
name = "air"
type = "atmosphere"
atmosphere = {{ file = "zawada2021.toml" }}
rayleigh = {{ cross_section_cm2 = {{ nm = [300.0, 800.0], values = [{xs:e}, {xs:e}] }}, depolarisation = 0.0 }}

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "sphere"
center = [0.0, -6371000.0, 0.0]
radius = 6371000.0
material = "black"

[[light]]
type = "sun"
elevation_deg = 0.0
azimuth_deg = 90.0
angular_diameter_deg = 0.0
spectrum = 1.0
scale = 1.0

[[sensor]]
name = "sky"
type = "sky_radiance"
origin = [0.0, {eye_m!r}, 0.0]
directions_deg = [[0.0, 0.0]]
samples = {samples}
"""


def sweep(binary, out, name, text, seed, zeniths):
    """Zenith radiance per solar zenith, and the run's CPU seconds."""
    (out / f"{name}.toml").write_text(text)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(
        [binary, "render", str(out / f"{name}.toml"), "--out", str(out / f"{name}_{seed}"), "--seed", str(seed),
         "--sun-zenith-deg", ",".join(f"{z:g}" for z in zeniths), "--threads", "2", "--quiet"],
        check=True, stdout=subprocess.DEVNULL,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(out / f"{name}_{seed}" / f"{name}_sun_sweep.csv") as f:
        rows = list(csv.DictReader(f))
    return {float(r["sun_zenith_deg"]): float(r["L_mean"]) for r in rows}, cpu


def sasktran2(nm):
    with open(ROOT / "tests/data/sasktran2_twilight/zenith_radiance.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {float(r["sun_zenith_deg"]): (float(r["L_total_in880"]), float(r["L_total_2d_in880"]))
            for r in rows if float(r["wavelength_nm"]) == nm}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default=str(ROOT / "target/release/morgana"))
    ap.add_argument("--out", type=Path, default=Path("/tmp/twilight_sasktran"))
    ap.add_argument("--nm", type=float, default=351.0, choices=sorted(CROSS_SECTION_CM2))
    ap.add_argument("--zeniths", default="90,92,94,96")
    ap.add_argument("--photons", default="1000000,10000000")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--path-samples", type=int, default=1_000_000)
    ap.add_argument("--map-lines", default="", help="[integrator] lines added to the photon-map runs (\\n between)")
    ap.add_argument("--runs", default="single,path,map", help="which of single, path, map to run")
    ap.add_argument("--eye-m", type=float, default=1.0,
                    help="the sensor's height, m (SASKTRAN2's ratios hold only for the default 1 m)")
    args = ap.parse_args()
    zeniths = [float(z) for z in args.zeniths.split(",")]
    seeds = [int(s) for s in args.seeds.split(",")]
    args.out.mkdir(parents=True, exist_ok=True)
    write_air(args.out)
    extra = args.map_lines.replace("\\n", "\n")
    runs = [("single", "photons = 0\nmarch_step = 500.0", 256, seeds[:1]),
            ("path", 'method = "path"', args.path_samples, seeds)]
    runs += [(f"map_{p}", f"photons = {p}\n{extra}", 64, seeds) for p in args.photons.split(",") if p]
    wanted = args.runs.split(",")
    runs = [r for r in runs if r[0].split("_")[0] in wanted]
    reference = sasktran2(args.nm)
    print(f"{args.nm:g} nm; zenith radiance (sr^-1) and its ratio to SASKTRAN2's 1-D / 2-D totals")
    print("run".ljust(18) + "".join(f"{z:g} deg".rjust(34) for z in zeniths) + "   CPU s")
    for name, integrator, samples, run_seeds in runs:
        for seed in run_seeds:
            text = scene(args.nm, integrator, samples, args.eye_m)
            values, cpu = sweep(args.bin, args.out, name, text, seed, zeniths)
            cells = "".join(
                f"{values[z]:.4e} ({values[z] / reference[z][0]:.3f}/{values[z] / reference[z][1]:.3f})".rjust(34)
                for z in zeniths
            )
            print(f"{name} seed {seed}".ljust(18) + cells + f"{cpu:8.1f}", flush=True)


if __name__ == "__main__":
    main()
