#!/usr/bin/env python3
"""Is the GIL released during a render? Prints, measured in one run, the wall time of one
one-thread render, of two such renders in two processes (no GIL shared: the control for how many
cores are free right now) and of two in two Python threads of one process, with the ratios.
With the GIL released, two threads take about the time of two processes (about the time of one
render on an idle 2-core machine); with it held they would take twice one render.

    .venv/bin/python scripts/bench_python_gil.py [--photons 300000] [--repeats 3]

Needs the package installed in .venv (scripts/python_test.sh).
"""

import argparse
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

import morgana

SCENE = Path(__file__).resolve().parent.parent / "examples" / "white_furnace.toml"
CHILD = """
import sys, time, morgana
scene = morgana.Scene.from_file(sys.argv[1]).with_overrides(photons=int(sys.argv[2]), seed=1)
start = float(sys.argv[3])
time.sleep(max(0.0, start - time.time()))
morgana.render(scene, threads=1, progress=False)
print(time.time() - start)
"""


def one(scene) -> float:
    t0 = time.perf_counter()
    morgana.render(scene, threads=1, progress=False)
    return time.perf_counter() - t0


def two_processes(photons: int) -> float:
    start = time.time() + 1.5
    procs = [subprocess.Popen([sys.executable, "-c", CHILD, str(SCENE), str(photons), str(start)], stdout=subprocess.PIPE, text=True) for _ in range(2)]
    return max(float(p.communicate()[0]) for p in procs)


def two_threads(scene) -> float:
    t0 = time.perf_counter()
    ts = [threading.Thread(target=morgana.render, args=(scene,), kwargs=dict(threads=1, progress=False)) for _ in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--photons", type=int, default=300_000)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    scene = morgana.Scene.from_file(SCENE).with_overrides(photons=args.photons, seed=1)
    rows = {"one render": [], "two processes": [], "two threads": []}
    for _ in range(args.repeats):
        rows["one render"].append(one(scene))
        rows["two processes"].append(two_processes(args.photons))
        rows["two threads"].append(two_threads(scene))
    med = {k: statistics.median(v) for k, v in rows.items()}
    for k, v in med.items():
        print(f"{k:>14}: median {v:.2f} s of {args.repeats} ({', '.join(f'{x:.2f}' for x in rows[k])})")
    print(f"two threads / one render = {med['two threads'] / med['one render']:.2f} (2.0 if the GIL were held)")
    print(f"two threads / two processes = {med['two threads'] / med['two processes']:.2f} (1.0: threads run as freely as processes)")


if __name__ == "__main__":
    main()
