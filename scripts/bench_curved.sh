#!/usr/bin/env bash
# Timed renders of the curved-path scenes, for issue 18: prints, per scene, the wall time of the
# photon and eye passes and the integrator's work (accepted/rejected steps, chords) from
# report.json. Run from the repository root:
#
#   scripts/bench_curved.sh [MORGANA_BINARY] [OUT_DIR] [SCENE...]
#
# Defaults: target/release/morgana, /tmp/bench_curved, and sunset_sea, mirage_hot_road and
# mirage_superior at their shipped sizes. SHRINK=k divides the image's width and height by k (a
# copy of the scene beside it, removed after), PHOTONS=n overrides the photon count, SET="key = value"
# adds a line to the copy's [integrator] (e.g. SET="dispersion_bundles = false" for the per-wavelength
# paths), THREADS=n the worker threads. Any scene works (the ODE columns are "-" without curved
# paths). Compare two binaries in one run (one after the other,
# same machine load) by calling it twice with different binaries and out dirs. Wall times on the
# shared 2-vCPU machines vary by up to 2× with other work: quote ratios from one run.
set -euo pipefail
BIN=${1:-target/release/morgana}
OUT=${2:-/tmp/bench_curved}
shift 2 || true
SCENES=("$@")
if [ ${#SCENES[@]} -eq 0 ]; then
  SCENES=(examples/sunset_sea.toml examples/mirage_hot_road.toml examples/mirage_superior.toml)
fi
mkdir -p "$OUT"
for s in "${SCENES[@]}"; do
  name=$(basename "$s" .toml)
  scene=$s
  if [ -n "${SHRINK:-}${SET:-}" ]; then
    scene="$(dirname "$s")/.bench_$name.toml"
    python3 - "$s" "$scene" "${SHRINK:-1}" "${SET:-}" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
k = int(sys.argv[3])
for key in ("width", "height"):
    text = re.sub(rf"(?m)^{key} = (\d+)", lambda m: f"{key} = {max(1, int(m.group(1)) // k)}", text, count=1)
if sys.argv[4]:
    text = re.sub(r"(?m)^\[integrator\]$", "[integrator]\n" + sys.argv[4], text, count=1)
open(sys.argv[2], "w").write(text)
PY
  fi
  extra=()
  if [ -n "${PHOTONS:-}" ]; then extra=(--photons "$PHOTONS"); fi
  if [ -n "${THREADS:-}" ]; then extra+=(--threads "$THREADS"); fi
  "$BIN" render "$scene" --out "$OUT/$name" --quiet "${extra[@]}" > "$OUT/$name.log" 2>&1
  if [ -n "${SHRINK:-}${SET:-}" ]; then rm -f "$scene"; fi
  python3 - "$OUT/$name/report.json" "$name" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
ph = {p["phase"]: p for p in r["phases"]}
def work(c):
    if not c:
        return "-"
    tot = c["ode_steps"] + c["ode_rejected"]
    rej = c["ode_rejected"] / tot if tot else 0.0
    return f'steps {c["ode_steps"]} rejected {c["ode_rejected"]} ({100*rej:.1f} %) field samples {c["rhs_evals"]} chords {c["chords"]}'
for m in r.get("maps", []):
    print(f'{sys.argv[2]:<20} {m["map"]:<8} photon pass {m["trace_seconds"]:8.2f} s  {work(m["stats"].get("curved"))}')
eye = ph.get("eye pass", {})
print(f'{sys.argv[2]:<20} eye      pass        {eye.get("seconds", 0):8.2f} s  ({eye.get("cpu_seconds", 0):.1f} CPU s)  {work(r.get("eye_curved"))}  bundled lanes {r["rays"].get("bundled", 0)}')
print(f'{sys.argv[2]:<20} total               {r["total_seconds"]:8.2f} s')
PY
done
