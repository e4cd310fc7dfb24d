#!/usr/bin/env python3
"""The zenith through twilight with multiple scattering, by SASKTRAN2 (issue 19's spherical check).

SASKTRAN2 (University of Saskatchewan; PyPI `sasktran2`, pinned in
scripts/requirements-sasktran.txt) solves the radiative transfer equation in a spherical
atmosphere; its successive-orders source is the spherical multiple-scattering method of
SASKTRAN-HR (Zawada et al. 2015, Atmos. Meas. Tech. 8, 2609), the model whose single
scattering is the reference of Zawada et al. (2021) that tests/spherical_benchmarks.rs meets.

The atmosphere is that benchmark's (tests/data/zawada2021/number_density.csv: air at 1 km
levels to 100 km, R = 6371 km, black ground), pure Rayleigh with no depolarisation and the
benchmark's cross-sections at 351 nm (vertical optical depth 0.62) and 442 nm (0.24); the
observer 1 m above the ground looks at the zenith; the sun (a point, unit irradiance) at solar
zenith 80-96 deg. Scalar radiance (SASKTRAN2's default, one Stokes component), as morgana's.

For every wavelength and solar zenith it writes single scattering (no multiple-scattering
source) and single + multiple scattering with the successive-orders source: in SASKTRAN2's 1-D
geometry (its source computed for the observer's column and taken as horizontally uniform) at
two incoming quadratures (440 and 880 directions; the other settings SASKTRAN2's defaults), and
in its 2-D geometry (the source on a grid of horizontal angles -30..30 deg by 1 deg in the sun's
plane, 880 directions), so the file carries its own convergence and the spread between the
model's two geometries: tests/data/sasktran2_twilight/zenith_radiance.csv, which
tests/spherical_benchmarks.rs reads.

    scripts/setup_sasktran_venv.sh
    .venv-sasktran/bin/python scripts/sasktran_twilight.py [--out CSV]
    .venv-sasktran/bin/python scripts/sasktran_twilight.py --checks   # the README's trials

About ten minutes on the 2-vCPU machine.
"""

import argparse
import importlib.metadata
import time
from pathlib import Path

import numpy as np
import sasktran2 as sk

ROOT = Path(__file__).resolve().parent.parent
R_EARTH_M = 6_371_000.0
T_K = 250.0
# P = N R* T / N_A with USA76's constants, as tests/spherical_benchmarks.rs writes the air for
# morgana, so both models read the same number densities back.
R_STAR = 8.31432
N_A = 6.022169e23
# The benchmark's Rayleigh cross-sections, cm² (its data set; tests/spherical_benchmarks.rs).
CROSS_SECTION_CM2 = {351.0: 2.87884699e-26, 442.0: 1.10228657e-26}
SUN_ZENITHS_DEG = [80.0, 84.0, 88.0, 90.0, 91.0, 92.0, 93.0, 94.0, 95.0, 96.0]
EYE_M = 1.0
INCOMING = [440, 880]
# The 2-D geometry's horizontal grid, degrees from the observer toward the sun's side. A 0.5 deg
# grid and a -40..40 deg span each moved the 440-direction totals at 90, 94 and 96 deg by
# < 0.01 % in a trial run.
HORIZONTAL_DEG = np.arange(-30.0, 30.01, 1.0)


def benchmark_air():
    rows = np.loadtxt(ROOT / "tests/data/zawada2021/number_density.csv", delimiter=",", skiprows=1)
    altitude_m = rows[:, 0]
    n_per_m3 = rows[:, 1] * 1e6
    return altitude_m, n_per_m3 * R_STAR * T_K / N_A


def zenith_radiance(nm, sun_zenith_deg, incoming, two_d=False, **options):
    """SASKTRAN2's zenith radiance per unit irradiance; `incoming` None: single scattering;
    `two_d`: the 2-D geometry over `horizontal_deg` (default HORIZONTAL_DEG) instead of the
    1-D one. Options for --checks: `source` (a MultipleScatterSource), `air` (altitudes and
    pressures instead of the benchmark's), `source_altitudes_m` (the source's altitude grid)."""
    altitude_m, pressure_pa = options.get("air") or benchmark_air()
    config = sk.Config()
    config.num_threads = 2
    if incoming is None:
        config.multiple_scatter_source = sk.MultipleScatterSource.NoSource
    else:
        config.multiple_scatter_source = options.get("source", sk.MultipleScatterSource.SuccessiveOrders)
        config.num_successive_orders_incoming = incoming
        if "source_altitudes_m" in options:
            config.successive_orders_altitude_grid_m = options["source_altitudes_m"]
    mu0 = np.cos(np.radians(sun_zenith_deg))
    if two_d:
        horizontal = np.radians(options.get("horizontal_deg", HORIZONTAL_DEG))
        geometry = sk.Geometry2D(mu0, 0.0, R_EARTH_M, altitude_m, horizontal, sk.InterpolationMethod.LinearInterpolation)
    else:
        geometry = sk.Geometry1D(
            cos_sza=mu0,
            solar_azimuth=0.0,
            earth_radius_m=R_EARTH_M,
            altitude_grid_m=altitude_m,
            interpolation_method=sk.InterpolationMethod.LinearInterpolation,
            geometry_type=sk.GeometryType.Spherical,
        )
    viewing = sk.ViewingGeometry()
    # Angles at the observer: cos(view zenith) = 1 looks straight up.
    viewing.add_ray(sk.SolarAnglesObserverLocation(mu0, 0.0, 1.0, EYE_M))
    atmosphere = sk.Atmosphere(geometry, config, wavelengths_nm=np.array([nm]), calculate_derivatives=False)
    atmosphere.pressure_pa = pressure_pa
    atmosphere.temperature_k = np.full_like(pressure_pa, T_K)
    xs_m2 = CROSS_SECTION_CM2[nm] * 1e-4
    atmosphere["rayleigh"] = sk.constituent.Rayleigh(
        method="manual",
        wavelengths_nm=np.array([300.0, 800.0]),
        xs=np.array([xs_m2, xs_m2]),
        king_factor=np.array([1.0, 1.0]),
    )
    out = sk.Engine(config, geometry, viewing).calculate_radiance(atmosphere)
    return float(np.asarray(out["radiance"]).ravel()[0])


def fine_air(step_m=250.0):
    """The benchmark air at `step_m` levels, ln P read linearly between its 1 km ones."""
    altitude_m, pressure_pa = benchmark_air()
    fine = np.arange(0.0, altitude_m[-1] + 0.1, step_m)
    return fine, np.exp(np.interp(fine, altitude_m, np.log(pressure_pa)))


def checks():
    """The trial runs the data's README quotes: SASKTRAN2's convergence in its settings, its
    legacy source, and the benchmark air read at 250 m levels."""

    def row(label, cases, **kw):
        values = [zenith_radiance(nm, sza, *args, **kw) for nm, sza, args in cases]
        print(label + ": " + ", ".join(f"{nm:g}/{sza:g} {v:.5e}" for (nm, sza, _), v in zip(cases, values)), flush=True)

    deep = [(351.0, 96.0, (n,)) for n in (110, 220, 440, 880)]
    print("1-D, 351 nm, 96 deg, incoming 110/220/440/880: " + ", ".join(f"{zenith_radiance(*c[:2], *c[2]):.5e}" for c in deep))
    cases = [(351.0, s, (440,)) for s in (80.0, 90.0, 96.0)]
    row("1-D, 440 directions", cases)
    row("1-D, 440, source altitudes every 0.5 km", cases, source_altitudes_m=np.arange(250.0, 99800.0, 500.0))
    cases = [(351.0, s, (440, True)) for s in (90.0, 94.0, 96.0)]
    row("2-D, 440, horizontal -30..30 by 1 deg", cases)
    row("2-D, 440, horizontal -30..30 by 0.5 deg", cases, horizontal_deg=np.arange(-30.0, 30.01, 0.5))
    row("2-D, 440, horizontal -40..40 by 1 deg", cases, horizontal_deg=np.arange(-40.0, 40.01, 1.0))
    mixed = [(351.0, 90.0), (351.0, 96.0), (442.0, 93.0), (442.0, 94.0)]
    row("1-D, 440", [(nm, s, (440,)) for nm, s in mixed])
    row("1-D legacy source, 974", [(nm, s, (974,)) for nm, s in mixed], source=sk.MultipleScatterSource.SuccessiveOrdersLegacy)
    fine = [(351.0, 90.0), (351.0, 96.0), (442.0, 94.0), (442.0, 95.0)]
    row("single scattering", [(nm, s, (None,)) for nm, s in fine])
    row("single scattering, air at 250 m (log-linear)", [(nm, s, (None,)) for nm, s in fine], air=fine_air())
    row("1-D, 440", [(nm, s, (440,)) for nm, s in fine])
    row(
        "1-D, 440, air at 250 m (log-linear), source every 1 km",
        [(nm, s, (440,)) for nm, s in fine],
        air=fine_air(),
        source_altitudes_m=np.arange(500.0, 99600.0, 1000.0),
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "tests/data/sasktran2_twilight/zenith_radiance.csv")
    ap.add_argument("--checks", action="store_true", help="print the README's convergence trials instead (15 minutes)")
    args = ap.parse_args()
    if args.checks:
        checks()
        return
    version = importlib.metadata.version("sasktran2")
    lines = [
        f"# SASKTRAN2 {version}: zenith radiance 1 m above a black Earth (R = 6371 km) under the air of",
        "# Zawada et al. (2021) (tests/data/zawada2021), pure Rayleigh, no depolarisation, scalar, per unit",
        "# solar irradiance (sr^-1). L_single: no multiple-scattering source. L_total_in440, L_total_in880:",
        "# successive orders in the 1-D geometry with 440 and 880 incoming directions. L_total_2d_in880: in",
        "# the 2-D geometry (horizontal grid -30..30 deg by 1 deg), 880 directions. Written by",
        "# scripts/sasktran_twilight.py.",
        "wavelength_nm,sun_zenith_deg,L_single,L_total_in440,L_total_in880,L_total_2d_in880",
    ]
    start = time.time()
    for nm in CROSS_SECTION_CM2:
        for sza in SUN_ZENITHS_DEG:
            single = zenith_radiance(nm, sza, None)
            total = [zenith_radiance(nm, sza, n) for n in INCOMING]
            two_d = zenith_radiance(nm, sza, INCOMING[-1], two_d=True)
            lines.append(f"{nm:g},{sza:g},{single:.7e},{total[0]:.7e},{total[1]:.7e},{two_d:.7e}")
            print(f"{nm:g} nm, {sza:g} deg: single {single:.5e}, total {total[0]:.5e} / {total[1]:.5e}"
                  f" ({total[1] / single:.3f} x single; 440 vs 880: {total[0] / total[1] - 1:+.2e});"
                  f" 2-D {two_d:.5e} ({two_d / total[1] - 1:+.2e})  [{time.time() - start:.0f} s]", flush=True)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n")
    tmp.replace(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
