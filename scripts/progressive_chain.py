"""A progressive morgana run observed along the way: one run, stopped and resumed (`--resume`)
at growing pass counts, so that the image after P passes can be read for every P of a schedule
(issue 17, "Measured goals"; docs/book/src/convergence.md, "Measured convergence").

A resumed run writes the bytes of an uninterrupted one (tests/progressive.rs,
`a_resumed_run_writes_the_bytes_of_an_uninterrupted_one`), so the image after P passes of the
chain is the image of a `--passes P` run. Each stop costs what a run's start and end cost
(reading the scene, the checkpoint, writing the outputs); the chain's CPU time includes it, so
it is a slight overestimate of what one run of P passes takes.

Used by scripts/consistency.py and scripts/peer_mitsuba.py (`--progressive`).
"""

from __future__ import annotations

import json
import math
import resource
import subprocess
from dataclasses import dataclass
from pathlib import Path


@dataclass
class Step:
    """The chain after `passes` passes."""

    passes: int
    # CPU seconds (user + sys) of every morgana process of the chain so far.
    cpu_s: float
    # Wall seconds of the passes, from report.json's history (continued across resumes).
    wall_s: float
    # The sum of the render phases report.json records, over the chain's runs.
    phase_s: float
    out: Path
    report: dict


def schedule(first: int = 2, ratio: float = math.sqrt(2.0)):
    """Pass counts growing geometrically: 2, 3, 4, 6, 8, 11, 16, 23, 32, 45, 64, ..."""
    p = float(first)
    last = 0
    while True:
        n = max(last + 1, round(p))
        yield n
        last = n
        p *= ratio


def run(binary: Path, scene: Path, out: Path, threads: int, max_cpu_s: float, extra: list[str] = (),
        log=print, first: int = 2):
    """Yields a `Step` after each stop of the chain until its CPU time reaches `max_cpu_s`. The
    last stop is placed, from the CPU time per pass so far, just past `max_cpu_s`."""
    cpu = phase = 0.0
    passes = 0
    for planned in schedule(first):
        if passes:
            per_pass = cpu / passes
            needed = math.ceil(1.02 * max_cpu_s / per_pass)
            planned = max(passes + 1, min(planned, needed))
        args = [str(binary), "render", str(scene), "--threads", str(threads), "--quiet", "--passes", str(planned)]
        args += ["--resume", str(out)] if passes else ["--out", str(out)]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(args + list(extra), check=True, stdout=subprocess.DEVNULL)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu += (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        report = json.loads((out / "report.json").read_text())
        phase += sum(p["seconds"] for p in report["phases"])
        passes = planned
        wall = report["progressive"]["history"][-1]["elapsed_s"]
        log(f"    {passes:5d} passes  CPU {cpu:8.1f} s  wall {wall:8.1f} s")
        yield Step(passes, cpu, wall, phase, out, report)
        if cpu >= max_cpu_s:
            return


def fit_slope(xs: list[float], ys: list[float]) -> tuple[float, float, int]:
    """Least-squares slope and intercept of ln y on ln x, and the points used."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    n = len(pts)
    if n < 2:
        return float("nan"), float("nan"), n
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return float("nan"), float("nan"), n
    slope = sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx
    return slope, my - slope * mx, n
