#!/usr/bin/env python3
"""Tables for README "Distributed rendering (MPI)" from scripts/bench_mpi.sh's runs.

    python3 scripts/mpi_model.py target/bench_mpi

1. Measured: per phase, 1 rank against 2 ranks (one thread each), median over repetitions.
2. Eye-pass schedules: dynamic (guided self-scheduling) against static interleaved blocks.
3. Model: predicted speedup on P nodes (one rank of one thread each, as measured here) from the
   1-rank phase times and the message sizes of the run:

   T(P) = t_other + t_build                        serial on every rank: scene, kd-tree builds
        + (t_trace + t_encode + t_irr) / P         photon tracing, encoding, irradiance estimates
        + AG(M_maps, P) + AG(M_irr, P)             all-gathers of the maps and the cache values
        + t_eye / P + t_eye / H                    eye pass, plus the last lease (one row)
        + max(L/P (2a + poll) + I/(P b), I (P-1)/(P b))   leases: round trips and row data into
                                                   rank 0 (its link carries the whole image)
        + 20 ceil(log2 P) a                        small collectives (bounds, counts, reports)
   AG(M, P) = (P-1) a + (P-1)/P M / b              ring all-gather (Thakur, Rabenseifner & Gropp
                                                   2005, "Optimization of collective communication
                                                   operations in MPICH", IJHPCA 19(1))
   with M_maps = 32 bytes x stored photons, M_irr = 4 bytes x bands x cache points, I = 4 bytes x
   bands x pixels, L the leases the dispenser hands out (simulated), a the latency and b the
   bandwidth of the network: 1 GbE a = 50 us, b = 117 MB/s (TCP payload); 10 GbE a = 10 us,
   b = 1.17 GB/s; this machine's shared memory a = 2 us, b = 4 GB/s (for checking against the
   measured 2 ranks).
"""

import csv
import json
import math
import os
import statistics
import sys
from collections import defaultdict

POLL = 200e-6
NETWORKS = {"1 GbE": (50e-6, 117e6), "10 GbE": (10e-6, 1.17e9)}
SHM = (2e-6, 4e9)
NODES = [2, 6, 16, 64]


def load(root):
    runs = defaultdict(list)
    with open(os.path.join(root, "runs.csv")) as f:
        for row in csv.DictReader(f):
            d = os.path.join(root, f"{row['scene']}-{row['config']}-{row['rep']}")
            rep = json.load(open(os.path.join(d, "report.json")))
            rep["_wall"] = float(row["total_seconds"])
            rep["_load"] = float(row["load1"])
            rep["_cpu"] = float(row.get("cpu_seconds") or "nan")
            runs[(row["scene"], row["config"])].append(rep)
    return runs


def grouped(phases, key, total):
    """Phase times (`key`: "seconds" for wall, "cpu_seconds" for CPU) grouped for the model;
    `total` the run's total (wall, or CPU), from which "other" is what no phase covers."""
    g = dict.fromkeys(ORDER, 0.0)
    for p in phases:
        name, v = p["phase"], p.get(key, math.nan)
        if name.endswith("photon tracing"):
            g["photon tracing"] += v
        elif name.endswith("map gather"):
            g["map gather"] += v
        elif name.endswith("map build") or name == "irradiance cache build":
            g["kd-tree builds"] += v
        elif name == "irradiance precompute":
            g["irradiance precompute"] += v
        elif name == "irradiance gather":
            g["irradiance gather"] += v
        elif name == "eye pass":
            g["eye pass"] += v
    covered = sum(p.get(key, math.nan) for p in phases if p["phase"] not in ("colour conversion", "sensors"))
    g["other (scene, colour, init)"] = max(total - covered, 0.0)
    g["total"] = total
    return g


def groups(rep):
    """Wall seconds per group (rank 0's view)."""
    return grouped(rep["phases"], "seconds", rep["total_seconds"])


def cpu_groups(rep, rank=0):
    """CPU seconds per group on `rank`; its total is the whole run's CPU time (mpirun and all
    ranks, /usr/bin/time) for a 1-rank run, else the sum of the rank's phases (no "other")."""
    phases = rep["distributed"]["per_rank"][rank]["phases"]
    if rep["distributed"]["ranks"] == 1:
        return grouped(phases, "cpu_seconds", rep["_cpu"])
    return grouped(phases, "cpu_seconds", sum(p.get("cpu_seconds", math.nan) for p in phases))


def median_of(gs):
    vals = defaultdict(list)
    for g in gs:
        for k, v in g.items():
            vals[k].append(v)
    return {k: statistics.median(v) for k, v in vals.items()}


def best(reps):
    """Median over repetitions of each wall-time group (the machine is shared: the median
    resists one disturbed run either way)."""
    return median_of(map(groups, reps))


def best_cpu(reps, rank=0):
    """Median over repetitions of each CPU-time group on `rank`."""
    return median_of(cpu_groups(r, rank) for r in reps)


ORDER = ["photon tracing", "map gather", "kd-tree builds", "irradiance precompute", "irradiance gather",
         "eye pass", "other (scene, colour, init)", "total"]


def leases(rows, ranks):
    """Leases the dynamic dispenser hands out (tiles.rs: ceil(R / 4P) rows each)."""
    n, left = 0, rows
    while left > 0:
        left -= min(left, -(-left // (4 * ranks)))
        n += 1
    return n


def sizes(rep):
    bands = rep["wavelengths"]["bands"]
    stored = sum(m["stored"] for m in rep["maps"])
    return {
        "maps": 32 * stored,
        "irr": 4 * bands * rep["irradiance_points"],
        "image": 4 * bands * rep["width"] * rep["height"],
        "rows": rep["height"],
        "stored": stored,
    }


def ag(m, p, a, b):
    return (p - 1) * a + (p - 1) / p * m / b if p > 1 else 0.0


def model(g, s, p, a, b):
    t = g["other (scene, colour, init)"] + g["kd-tree builds"]
    t += (g["photon tracing"] + g["map gather"] + g["irradiance precompute"]) / p
    t += ag(s["maps"], p, a, b) + ag(s["irr"], p, a, b)
    t += g["eye pass"] / p + (g["eye pass"] / s["rows"] if p > 1 else 0.0)
    if p > 1:
        lw = leases(s["rows"], p) / p
        t += max(lw * (2 * a + POLL) + s["image"] / (p * b), s["image"] * (p - 1) / (p * b))
        t += 20 * math.ceil(math.log2(p)) * a
    return t


def scaled(g, s, photons=1.0, eye=1.0, pixels=1.0):
    """A workload extrapolated from a measured one: photon-pass terms and map bytes times
    `photons` (kd-tree builds times photons · log(n·photons) / log(n)), the eye pass times `eye`,
    the image (rows, bytes) times `pixels`."""
    g, s = dict(g), dict(s)
    n = max(s["stored"], 2)
    for k in ("photon tracing", "map gather", "irradiance precompute", "irradiance gather"):
        g[k] *= photons
    g["kd-tree builds"] *= photons * math.log(n * photons) / math.log(n)
    g["eye pass"] *= eye
    for k in ("maps", "irr", "stored"):
        s[k] *= photons
    s["image"] *= pixels
    s["rows"] = round(s["rows"] * math.sqrt(pixels))
    g["total"] = sum(g[k] for k in ORDER if k != "total")
    return g, s


def limit(g, s, a, b):
    """Speedup as P grows without bound."""
    serial = g["other (scene, colour, init)"] + g["kd-tree builds"] + g["eye pass"] / s["rows"]
    serial += (s["maps"] + s["irr"] + s["image"]) / b
    return g["total"] / serial


def has_cpu(reps):
    return all("cpu_seconds" in p for r in reps for p in r["phases"]) and all(r["_cpu"] == r["_cpu"] for r in reps)


def model_inputs(reps):
    """The 1-rank phase times the model starts from: CPU seconds where measured (a rank of one
    thread: its wall time on a core of its own, whatever else loads the machine), else wall."""
    return (best_cpu(reps), "CPU") if has_cpu(reps) else (best(reps), "wall")


def rank_cpu(c2, k):
    """A phase's CPU time on 2 ranks as a quiet machine would show it: the slower rank's for
    phases split in advance; the ranks' mean for the eye pass, whose rows go to whichever rank
    asks (on a loaded machine the rank that got more CPU took more rows)."""
    a, b = c2[0].get(k, 0.0), c2[1].get(k, 0.0)
    return 0.5 * (a + b) if k == "eye pass" else max(a, b)


def measured_table(runs, sc):
    one, two = best(runs[(sc, "np1")]), best(runs[(sc, "np2")])
    s = sizes(runs[(sc, "np1")][0])
    print(f"### Scene `{sc}`: {s['stored']:,} stored photons, {runs[(sc, 'np1')][0]['width']}×{s['rows']} pixels\n")
    cpu = has_cpu(runs[(sc, "np1")]) and has_cpu(runs[(sc, "np2")])
    c1 = best_cpu(runs[(sc, "np1")]) if cpu else {}
    c2 = [best_cpu(runs[(sc, "np2")], r) for r in (0, 1)] if cpu else []
    print("| phase | wall, 1 rank (s) | wall, 2 ranks (s) | wall speedup | CPU, 1 rank (s) | CPU, 2 ranks: rank 0 / rank 1 (s) | work speedup |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for k in ORDER:
        if one.get(k, 0) < 1e-4 and two.get(k, 0) < 1e-4:
            continue
        sp = one[k] / two[k] if two.get(k, 0) > 0 else math.nan
        if cpu and k not in ("other (scene, colour, init)", "total"):
            worst = rank_cpu(c2, k)
            ws = f"{c1[k] / worst:.2f}" if worst > 0 else "–"
            cells = f"{c1[k]:.2f} | {c2[0][k]:.2f} / {c2[1][k]:.2f} | {ws}"
        elif cpu and k == "total":
            t2 = statistics.median(r["_cpu"] for r in runs[(sc, "np2")])
            cells = f"{c1[k]:.2f} | {t2:.2f} (both, whole run) | –"
        else:
            cells = "– | – | –"
        print(f"| {k} | {one[k]:.3f} | {two[k]:.3f} | {sp:.2f} | {cells} |")
    if cpu:
        # On a quiet machine each phase would take its slower rank's CPU time (one thread each).
        quiet2 = sum(rank_cpu(c2, k) for k in ORDER[:-2]) + c1["other (scene, colour, init)"]
        print(f"| quiet 2 cores (Σ rank CPU per phase + 1-rank other) | | | | {c1['total']:.2f} "
              f"| {quiet2:.2f} | {c1['total'] / quiet2:.2f} |")
    rep2 = runs[(sc, "np2")][0]["distributed"]
    print(f"\nBytes received over both ranks (2 ranks): maps {rep2['map_allgather_bytes']:,}, irradiance "
          f"{rep2['irradiance_allgather_bytes']:,}, tiles {rep2['tile_bytes']:,}.\n")


def schedule_table(runs, scenes):
    print("### Eye-pass schedules (2 ranks)\n")
    print("| scene | schedule | eye pass wall (s) | rank compute wall (s) | imbalance max/mean | worker wait (s) |")
    print("|---|---|---:|---:|---:|---:|")
    for sc in scenes:
        for cfg, name in (("np2", "dynamic"), ("np2-static", "static")):
            if (sc, cfg) not in runs:
                continue
            reps = runs[(sc, cfg)]
            r = sorted(reps, key=lambda x: best([x])["eye pass"])[len(reps) // 2]  # the median run
            comp = [p["eye"]["compute_seconds"] for p in r["distributed"]["per_rank"]]
            wait = sum(p["eye"]["wait_seconds"] for p in r["distributed"]["per_rank"][1:])
            imb = max(comp) / (sum(comp) / len(comp))
            print(f"| {sc} | {name} | {best([r])['eye pass']:.3f} | {' / '.join(f'{c:.2f}' for c in comp)} "
                  f"| {imb:.3f} | {wait:.3f} |")


def model_table(runs, scenes):
    print("\n### Model: predicted speedup on P nodes\n")
    print("Nodes of one rank with one thread; speedup against one such node. Inputs: the 1-rank runs'")
    print("median phase times (CPU seconds where measured, see above), the runs' message sizes.\n")
    print("| workload | network | P = 2 | P = 6 | P = 16 | P = 64 | limit P → ∞ |")
    print("|---|---|---:|---:|---:|---:|---:|")
    rows = []
    for sc in scenes:
        g, basis = model_inputs(runs[(sc, "np1")])
        rows.append((f"{sc} (measured, {basis} inputs)", g, sizes(runs[(sc, "np1")][0])))
    if ("photons", "np1") in runs:
        g, _ = model_inputs(runs[("photons", "np1")])
        s = sizes(runs[("photons", "np1")][0])
        rows.append(("photons × 25: 10⁸ emitted photons (extrapolated)", *scaled(g, s, photons=25)))
    if ("eye", "np1") in runs:
        g, _ = model_inputs(runs[("eye", "np1")])
        s = sizes(runs[("eye", "np1")][0])
        rows.append(("eye × 400: 768×768 pixels, 25× the samples (extrapolated)", *scaled(g, s, eye=400, pixels=16)))
    if ("curved", "np1") in runs:
        g, _ = model_inputs(runs[("curved", "np1")])
        s = sizes(runs[("curved", "np1")][0])
        rows.append(("curved × 1000: 10⁸ photons of the mirage (extrapolated)", *scaled(g, s, photons=1000)))
    for name, g, s in rows:
        t1 = model(g, s, 1, 0, 1)
        a, b = SHM
        print(f"| {name}, T(1) = {t1:.1f} s | shared memory | {t1 / model(g, s, 2, a, b):.2f} | | | | |")
        for net, (a, b) in NETWORKS.items():
            cells = " | ".join(f"{t1 / model(g, s, p, a, b):.2f}" for p in NODES)
            print(f"| {name} | {net} | {cells} | {limit(g, s, a, b):.1f} |")
    print("\nLucifer (Gutierrez et al. 2005, §6): 4.2–4.8 on 6 nodes (Pentium 4, network not stated).")


def main(root):
    runs = load(root)
    known = ["photons", "eye", "curved"]
    scenes = sorted({s for s, _ in runs}, key=lambda s: known.index(s) if s in known else 9)
    loads = [r["_load"] for reps in runs.values() for r in reps]
    print(f"Load average before the runs: {min(loads):.2f}–{max(loads):.2f} (2 cores). Wall times count the")
    print("time a rank was not scheduled; CPU times (user + system of the rank's process) count its work.\n")
    for sc in scenes:
        measured_table(runs, sc)
    schedule_table(runs, scenes)
    model_table(runs, scenes)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "target/bench_mpi")
