#!/usr/bin/env bash
# Multiple scattering through twilight (issue 19): the zenith radiance of
# examples/sky_twilight.toml at solar zenith 92, 94 and 96 degrees from
#   - single scattering (photons = 0, the example as shipped),
#   - the path tracer (method = "path", 10^6 sensor samples, seeds 1 and 2),
#   - the volume photon map with 10^6 and 10^7 photons (64 sensor samples), folded about the
#     sun's axis (axial_symmetry = true, the default) and not (axial_symmetry = false).
# Prints one table of the 6-band mean (W m^-2 sr^-1 nm^-1) and each run's wall and CPU time.
# Run from the repository root (about 5 minutes on 2 cores):
#
#   scripts/twilight_ms.sh [MORGANA_BINARY] [OUT_DIR]
set -euo pipefail
BIN=${1:-target/release/morgana}
OUT=${2:-/tmp/twilight_ms}
mkdir -p "$OUT"
ANGLES=92,94,96
scene() { # NAME, then sed expressions applied to the example
  local name=$1
  shift
  sed "$@" examples/sky_twilight.toml > "$OUT/$name.toml"
}
scene single -e 's/^samples = 4$/samples = 64/'
scene path -e 's/^photons = 0$/method = "path"/' -e 's/^samples = 4$/samples = 1000000/'
for n in 1000000 10000000; do
  scene "map_$n" -e "s/^photons = 0\$/photons = $n/" -e 's/^samples = 4$/samples = 64/'
  scene "unfolded_$n" -e "s/^photons = 0\$/photons = $n\naxial_symmetry = false/" -e 's/^samples = 4$/samples = 64/'
done
run() { # NAME SEED
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$OUT/$1_$2.cpu" "$BIN" render "$OUT/$1.toml" --out "$OUT/$1_$2" --seed "$2" \
    --sun-zenith-deg $ANGLES --quiet > /dev/null
  t1=$(date +%s.%N)
  echo "$t0 $t1" > "$OUT/$1_$2.wall"
}
RUNS=(single:1 path:1 path:2 map_1000000:1 unfolded_1000000:1 map_10000000:1 unfolded_10000000:1)
for r in "${RUNS[@]}"; do
  run "${r%%:*}" "${r##*:}"
done
python3 - "$OUT" "${RUNS[@]}" <<'PY'
import csv, sys
out, runs = sys.argv[1], sys.argv[2:]
print(f"{'run':<22} {'92 deg':>11} {'94 deg':>11} {'96 deg':>11} {'wall s':>7} {'cpu s':>7}")
for r in runs:
    name, seed = r.split(":")
    rows = list(csv.DictReader(open(f"{out}/{name}_{seed}/{name}_sun_sweep.csv")))
    values = " ".join(f"{float(row['L_mean']):>11.4e}" for row in rows)
    t0, t1 = map(float, open(f"{out}/{name}_{seed}.wall").read().split())
    user, system = map(float, open(f"{out}/{name}_{seed}.cpu").read().split())
    print(f"{name + ' seed ' + seed:<22} {values} {t1 - t0:>7.1f} {user + system:>7.1f}")
PY
