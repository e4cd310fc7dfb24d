#!/usr/bin/env python3
"""Consistency and calibration of progressive photon mapping (issue 17, "Measured goals").

For each scene, a progressive run is stopped and resumed at growing pass counts
(scripts/progressive_chain.py) until its CPU time reaches --max-cpu; after each stop its image is
compared with the exact answer:

- furnace: examples/white_furnace.toml (64 x 64 pixels, 4 bands, 400 000 photons and k = 200 a
  pass, direct light from the map). Inside a closed sphere whose walls emit L_e = 2 and reflect
  ρ = 0.6, the radiance is L_e/(1 - ρ) = 5 in every pixel and band (tests/furnace.rs). Error:
  RMSE over pixels and bands, relative to 5.
- fog_box: benches/scenes/fog_box.toml with the first photon-map budget of the Mitsuba
  benchmark per pass (200 000 photons, volume_k 50, march step 0.1, 4 gather rays, 2 spp, shadow
  rays, final gathering). Error: RMSE over pixels and linear sRGB channels against the Mitsuba
  reference of scripts/peer_mitsuba.py (out/mitsuba_bench/fog_box/reference.npz; render it with
  `peer_mitsuba.py --reference-only --scenes fog_box`), its own noise removed in quadrature,
  relative to the reference's mean.

The slope of ln(error) on ln(CPU seconds) is fitted over --fit-from..--fit-to (10..300 s): the
goal is a straight line with slope between -1/3 and -1/2 (Knaus & Zwicker 2011: the noise of the
average of N passes falls as N^(-α/2), -1/3 at the default α = 2/3, and the bias as N^(α-1)).

Calibration: after each stop, the share of pixel-bands whose error is within ±t·SE of the
reported standard error (t the two-sided 95 % Student quantile for passes - 1 degrees of
freedom). Furnace: against the exact 5. Fog box (--calibrate): against a second, independent
chain of the same settings (another seed) run to the same CPU time, as the long reference; the
interval then uses √(SE_a² + SE_b²), the error of the difference. Goal: 95 % ± 3 %.

Run through scripts/bench_consistency.sh. Writes out/consistency/<scene>.csv and log.txt.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peer_mitsuba as pm  # noqa: E402
import progressive_chain as chain  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
EXACT_FURNACE = 5.0

FOG_PASS = {"method": "photon_map", **pm.PM_COMMON, **pm.SCENES["fog_box"].photon_map[0]}


def spectral(exr: Path) -> tuple[np.ndarray, np.ndarray | None]:
    """(values, standard errors) of the EXR's spectral channels, shape (bands, height, width)."""
    import OpenEXR

    ch = OpenEXR.File(str(exr), separate_channels=True).channels()
    names = sorted((c for c in ch if c.startswith("S0.")), key=lambda c: float(c[3:-2].replace(",", ".")))
    vals = np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in names])
    if all("stderr." + c in ch for c in names):
        return vals, np.stack([np.asarray(ch["stderr." + c].pixels, dtype=np.float64) for c in names])
    return vals, None


def t95(dof: int) -> float:
    from scipy.stats import t

    return float(t.ppf(0.975, max(dof, 1)))


def coverage(err: np.ndarray, se: np.ndarray, dof: int) -> float:
    """The share of values with |err| <= t·se (values with se = 0 and err = 0 count as covered)."""
    return float(np.mean(np.abs(err) <= t95(dof) * se))


def scene_text(name: str, alpha: float | None, seed: int) -> str:
    if name == "furnace":
        text = (ROOT / "examples/white_furnace.toml").read_text().replace("csv = true\n", "csv = false\npng = false\n")
        extra = f"seed = {seed}\n" + (f"alpha = {alpha}\n" if alpha else "")
        return text.replace('direct = "photon_map"\n', 'direct = "photon_map"\n' + extra)
    integ = {**FOG_PASS, "seed": seed, **({"alpha": alpha} if alpha else {})}
    return pm.variant_toml((ROOT / pm.SCENES["fog_box"].toml).read_text(), integ, "fog_box")


def run_chain(args, name: str, seed: int, log) -> list[dict]:
    work = args.out / (f"{name}_seed{seed}" + (f"_alpha{args.alpha:g}" if args.alpha else ""))
    work.mkdir(parents=True, exist_ok=True)
    scene = work / f"{name}.toml"
    scene.write_text(scene_text(name, args.alpha, seed))
    metric = None
    if name == "fog_box":
        ref = np.load(args.reference)
        metric = pm.Metric.over(pm.Reference(ref["rgb"], ref["variance"], int(ref["spp"]), float(ref["seconds"])),
                                np.ones(ref["rgb"].shape[:2], dtype=bool))
    rows = []
    log(f"  {name}, seed {seed}: up to {args.max_cpu:g} CPU s, load {os.getloadavg()[0]:.1f}")
    for step in chain.run(args.bin, scene, work, args.threads, args.max_cpu, log=log):
        exr = work / ("white_furnace.exr" if name == "furnace" else "fog_box.exr")
        vals, se = spectral(exr)
        row = {"scene": name, "seed": seed, "passes": step.passes, "cpu_s": step.cpu_s, "wall_s": step.wall_s,
               "phase_s": step.phase_s, "load": os.getloadavg()[0],
               "k": step.report["progressive"]["history"][-1]["k"],
               "mean_rel_se": step.report["progressive"].get("image_mean_rel_error")}
        if name == "furnace":
            err = vals - EXACT_FURNACE
            row["rel_rmse"] = float(np.sqrt(np.mean(err**2))) / EXACT_FURNACE
            row["rel_rms_se"] = float(np.sqrt(np.mean(se**2))) / EXACT_FURNACE if se is not None else math.nan
            row["coverage"] = coverage(err, se, step.passes - 1) if se is not None else math.nan
        else:
            raw, corr = metric.errors(pm.read_exr_rgb(exr))
            row["rel_rmse"] = corr / metric.mean
            row["rel_rmse_raw"] = raw / metric.mean
            row["rel_rms_se"] = float(np.sqrt(np.mean(se**2)) / np.mean(vals)) if se is not None else math.nan
            np.save(work / f"bands_{step.passes}.npy", np.stack([vals, se if se is not None else 0 * vals]))
        rows.append(row)
        log(f"      rel. RMSE {row['rel_rmse']:.4g}  reported RMS SE {row['rel_rms_se']:.4g}"
            + (f"  coverage {row['coverage']:.3f}" if "coverage" in row else ""))
    return rows


def calibrate_fog(args, rows_a: list[dict], log) -> list[dict]:
    """Coverage of each stop of chain A against the long reference: the last stop of chain B
    (seed + 1000), or the EXR --calibrate-against names (another progressive run of the same
    settings and another seed, with its standard-error layer)."""
    if args.calibrate_against:
        vb, sb = spectral(args.calibrate_against)
        report = json.loads((args.calibrate_against.parent / "report.json").read_text())
        last = {"passes": report["progressive"]["passes"]}
        b_name = str(args.calibrate_against)
    else:
        rows_b = run_chain(args, "fog_box", args.seed + 1000, log)
        last = rows_b[-1]
        vb, sb = np.load(args.out / f"fog_box_seed{args.seed + 1000}" / f"bands_{last['passes']}.npy")
        b_name = f"seed {args.seed + 1000}"
    out = []
    for r in rows_a:
        va, sa = np.load(args.out / f"fog_box_seed{int(r['seed'])}" / f"bands_{r['passes']}.npy")
        if r["passes"] < 2:
            continue
        both = np.sqrt(sa**2 + sb**2)
        dof = min(r["passes"], last["passes"]) - 1
        c = coverage(va - vb, both, dof)
        z = (va - vb)[both > 0] / both[both > 0]
        out.append({"passes": r["passes"], "cpu_s": r["cpu_s"], "coverage": c, "rms_z": float(np.sqrt(np.mean(z**2)))})
        log(f"    fog box after {r['passes']:4d} passes ({r['cpu_s']:.0f} CPU s) against {b_name}'s "
            f"{last['passes']} passes: {100 * c:.1f} % of pixel-bands within ±t·SE, RMS z {out[-1]['rms_z']:.3f}")
    return out


def summarise(rows: list[dict], args, log):
    sel = [r for r in rows if args.fit_from <= r["cpu_s"] <= args.fit_to]
    for clock in ("cpu_s", "wall_s"):
        s, b, n = chain.fit_slope([r[clock] for r in sel], [r["rel_rmse"] for r in sel])
        log(f"    slope of ln(rel. RMSE) on ln({clock}) over {args.fit_from:g}..{args.fit_to:g} CPU s: "
            f"{s:.3f} ({n} points)")
    if len(sel) >= 4:
        half = len(sel) // 2
        s1, _, _ = chain.fit_slope([r["cpu_s"] for r in sel[: half + 1]], [r["rel_rmse"] for r in sel[: half + 1]])
        s2, _, _ = chain.fit_slope([r["cpu_s"] for r in sel[half:]], [r["rel_rmse"] for r in sel[half:]])
        log(f"    first half {s1:.3f}, second half {s2:.3f} (a flattening line has a smaller |slope| later)")
    s, _, n = chain.fit_slope([r["cpu_s"] for r in sel], [r["rel_rms_se"] for r in sel])
    log(f"    slope of the reported RMS standard error on CPU s: {s:.3f} ({n} points)")


def write_csv(path: Path, rows: list[dict]):
    if rows:
        keys = list(dict.fromkeys(k for r in rows for k in r))
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            w.writerows({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()} for r in rows)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bin", type=Path, default=ROOT / "target/release/morgana")
    p.add_argument("--out", type=Path, default=ROOT / "out/consistency")
    p.add_argument("--scenes", nargs="+", default=["furnace", "fog_box"], choices=["furnace", "fog_box"])
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--max-cpu", type=float, default=300.0, help="CPU seconds of each chain")
    p.add_argument("--fit-from", type=float, default=10.0)
    p.add_argument("--fit-to", type=float, default=300.0)
    p.add_argument("--alpha", type=float, default=None, help="[integrator] alpha (default: morgana's, 2/3)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--calibrate", action="store_true",
                   help="fog box: a second chain (seed + 1000) as the long reference for the calibration")
    p.add_argument("--calibrate-against", type=Path, default=None,
                   help="fog box: the long reference is this EXR (another seed's progressive run) instead")
    p.add_argument("--calibrate-only", action="store_true",
                   help="fog box: only the calibration, from the stops a previous run saved")
    p.add_argument("--reference", type=Path, default=ROOT / "out/mitsuba_bench/fog_box/reference.npz")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    log_file = open(args.out / "log.txt", "a")

    def log(msg):
        print(msg, flush=True)
        log_file.write(msg + "\n")
        log_file.flush()

    log(f"consistency: {time.strftime('%Y-%m-%d %H:%M:%S')}, threads {args.threads}, alpha {args.alpha or 'default'}, "
        f"load {os.getloadavg()}")
    suffix = f"_alpha{args.alpha:g}" if args.alpha else ""
    if args.calibrate_only:
        with open(args.out / f"fog_box{suffix}_seed{args.seed}.csv", newline="") as f:
            rows = [{k: (float(v) if k not in ("scene",) else v) for k, v in r.items()} for r in csv.DictReader(f)]
        for r in rows:
            r["passes"], r["seed"] = int(r["passes"]), int(r["seed"])
        write_csv(args.out / f"fog_box{suffix}_calibration.csv", calibrate_fog(args, rows, log))
        return 0
    for name in args.scenes:
        rows = run_chain(args, name, args.seed, log)
        summarise(rows, args, log)
        write_csv(args.out / f"{name}{suffix}_seed{args.seed}.csv", rows)
        if name == "fog_box" and (args.calibrate or args.calibrate_against):
            write_csv(args.out / f"fog_box{suffix}_calibration.csv", calibrate_fog(args, rows, log))
    log(f"consistency: done {time.strftime('%Y-%m-%d %H:%M:%S')}, load {os.getloadavg()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
