#!/usr/bin/env bash
# The refraction table's speed and accuracy (issue 18, item 4): `morgana refraction` over apparent
# zenith distances 0–90° in steps of 0.1° (901 rows) by quadrature of the refraction integral,
# timed as the whole process (startup included; median of RUNS runs) in wall time and in CPU time
# (user + system, all threads: the rows are computed in parallel, and on a shared machine the
# CPU time is the figure that does not depend on how many cores are free), and the largest
# difference from the ray trace through the same model atmosphere.
#
#   ./scripts/bench_refraction.sh [RUNS] [extra morgana refraction options, e.g. --humidity 0.9]
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-7}"
shift || true
[ "${SKIP_BUILD:-0}" = 1 ] || cargo build --release --quiet --bin morgana
bin=target/release/morgana
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$bin" "$runs" "$tmp" "$@" <<'PY'
import csv, resource, statistics, subprocess, sys, time
bin, runs, tmp, extra = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
base = [bin, "refraction", "--zenith-table-deg", "0,90,0.1"] + extra
cpu = lambda: (lambda u: u.ru_utime + u.ru_stime)(resource.getrusage(resource.RUSAGE_CHILDREN))
def run(method, out):
    t0, c0 = time.perf_counter(), cpu()
    subprocess.run(base + ["--method", method, "--csv", out], check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0, cpu() - c0
timed = [run("quadrature", f"{tmp}/q.csv") for _ in range(runs)]
quad, quad_cpu = [w for w, _ in timed], [c for _, c in timed]
trace = run("trace", f"{tmp}/t.csv")[0]
read = lambda p: [float(r["refraction_arcsec"]) for r in csv.DictReader(open(p))]
q, t = read(f"{tmp}/q.csv"), read(f"{tmp}/t.csv")
worst = max(range(len(q)), key=lambda i: abs(q[i] - t[i]))
print(f"options: {' '.join(extra) or '(defaults)'}")
print(f"quadrature, 901 zenith distances: median {1e3 * statistics.median(quad):.1f} ms over {runs} runs "
      f"(min {1e3 * min(quad):.1f} ms), process included; CPU time median {1e3 * statistics.median(quad_cpu):.1f} ms")
print(f"ray trace, same table: {1e3 * trace:.0f} ms (one run); ratio {trace / statistics.median(quad):.0f}x")
print(f"largest |quadrature - trace|: {abs(q[worst] - t[worst]):.5f} arcsec at zenith {0.1 * worst:.1f} deg "
      f"(refraction {t[worst]:.3f} arcsec)")
PY
