#!/usr/bin/env bash
# The volume map's point estimate against the beam estimate (issue 17 item 6; docs/book/src/
# convergence.md, "The beam estimate"): eye-pass CPU time, pass-to-pass noise and, on the fog
# box, RMSE against a path-traced reference, at equal photons, on reduced copies of
# examples/fog_box.toml and examples/volume_caustic.toml.
#
# Usage: scripts/bench_beam.sh [OUT_DIR]
#   env: SIZE (pixels a side, 32), SPP (4), PHOTONS (200000 a pass), PASSES (4), REF_SPP (16384),
#        THREADS (2)
# CPU seconds are quoted (user + sys of the eye pass, from report.json), since other work on a
# shared machine stretches wall time (see /work/shared/NOTES.md).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/morgana-bench-beam}
size=${SIZE:-32}; spp=${SPP:-4}; photons=${PHOTONS:-200000}; passes=${PASSES:-4}
ref_spp=${REF_SPP:-16384}; threads=${THREADS:-2}
cargo build --release --bin morgana -q
bin=target/release/morgana
mkdir -p "$out"

# variant SCENE NAME INTEGRATOR_LINES: the example at SIZE², SPP, writing only a CSV.
variant() {
    sed -e "s/^width = 128/width = $size/" -e "s/^height = 128/height = $size/" \
        -e "s/^spp = 8/spp = ${VSPP:-$spp}/" -e "s/^name = \"$1\"/name = \"$2\"\ncsv = true\nexr = false\npng = false/" \
        -e "s/^\[integrator\]/[integrator]\n$3/" -e "/^photons = /d" "examples/$1.toml"
}

run() { # SCENE NAME INTEGRATOR_LINES ARGS...
    local scene=$1 name=$2 lines=$3
    shift 3
    variant "$scene" "$name" "$lines" > "$out/$name.toml"
    "$bin" render "$out/$name.toml" --out "$out/$name" --threads "$threads" --quiet "$@" > /dev/null
}

python_summary() { # NAME [REFERENCE_NAME]
    python3 - "$out" "$@" <<'PY'
import csv, json, math, sys
out, name = sys.argv[1], sys.argv[2]
ref = sys.argv[3] if len(sys.argv) > 3 else None
def values(n):
    with open(f"{out}/{n}/{n}.csv") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    cols = [i for i, h in enumerate(head) if i >= 2 and not h.strip().endswith("_se")]
    return [float(r[i]) for r in rows[1:] for i in cols]
r = json.load(open(f"{out}/{name}/report.json"))
eye = sum(p["cpu_seconds"] for p in r["phases"] if p["phase"] == "eye pass")
radii = sum(p["cpu_seconds"] for p in r["phases"] if p["phase"] == "volume beam radii")
rel = r.get("progressive", {}).get("image_mean_rel_error")
line = f"{name:28s} eye pass {eye:8.1f} CPU s  beam radii {radii:5.1f} CPU s  mean pixel rel. SE {rel if rel is None else round(rel, 4)}"
if ref:
    a, b = values(name), values(ref)
    m = sum(b) / len(b)
    rmse = math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / len(b)) / m
    bias = (sum(a) / len(a) - m) / m
    line += f"  rel. RMSE {rmse:.4f}  image-mean bias {bias:+.4f}"
print(line)
PY
}

for est in point beam; do
    for scene in fog_box volume_caustic; do
        run "$scene" "${scene}_$est" "photons = $photons\nvolume_estimate = \"$est\"" --passes "$passes"
    done
    # Direct light from the maps too (as curved paths need): no shadow rays, no final gathering.
    run fog_box "fog_box_maps_$est" "photons = $photons\nvolume_estimate = \"$est\"\ndirect = \"photon_map\"" --passes "$passes"
done
# An unbiased reference for the fog box (area light: the path tracer sees all of it; the
# volume caustic's spotlight through glass is out of its reach).
[ -f "$out/fog_box_path/fog_box_path.csv" ] || VSPP=$ref_spp run fog_box fog_box_path "method = \"path\""
echo "SIZE=$size SPP=$spp PHOTONS=$photons PASSES=$passes REF_SPP=$ref_spp THREADS=$threads ($(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg))"
for est in point beam; do
    python_summary "fog_box_$est" fog_box_path
    python_summary "fog_box_maps_$est" fog_box_path
    python_summary "volume_caustic_$est"
done
