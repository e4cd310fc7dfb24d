#!/usr/bin/env bash
# The issue-19 sky benchmark: a 256 × 256 all-sky image (examples/sky_noon.toml, equal-area
# fisheye over the hemisphere, path tracer, all orders of Rayleigh scattering, 8 bands over
# 400–700 nm) with the sun at solar zenith 60°. It renders the scene twice at SPP samples per
# pixel with seeds 1 and 2 and measures the per-pixel relative noise of one render from their
# difference: σ/L = rms over pixels of (a − b)/((a + b)/2)/√2 (band-mean radiance, pixels wholly
# inside the image circle). Noise falls as 1/√spp, so the samples and time for 2 % are
# spp·(σ/L / 0.02)² and t·(σ/L / 0.02)². Run from the repository root:
#
#   scripts/bench_sky.sh [SPP] [MORGANA_BINARY] [OUT_DIR] [INTEGRATOR] [SUN_ELEVATION_DEG]
#
# Defaults: 8, target/release/morgana, /tmp/bench_sky, the example's path tracer and 30.0 (solar
# zenith 60°); SUN_ELEVATION_DEG = 0.5 is the issue's sunset (the same all-sky image with the sun's
# centre 0.5° above the horizon, its limb-darkened disc on the image circle). INTEGRATOR
# replaces the example's `method = "path"` line with other [integrator] lines (\n between them),
# e.g. 'method = "photon_map"\nphotons = 0' (ray-marched single scattering by shadow rays) or
# 'method = "photon_map"\nphotons = 200000' (the same plus the volume photon map's multiple
# scattering). After the renders it prints seed 1's report.json lines with the phase times,
# CPU times and photon, path and shadow-ray counts. Wall times on the shared 2-vCPU machines
# vary by up to 2× with other work: the script prints user + sys CPU time too. SIZE=64 (say)
# renders the same scene at SIZE × SIZE pixels instead, for quicker comparisons.
set -euo pipefail
SIZE=${SIZE:-256}
SPP=${1:-8}
BIN=${2:-target/release/morgana}
OUT=${3:-/tmp/bench_sky}
INTEGRATOR=${4:-method = \"path\"}
ELEVATION=${5:-30.0}
mkdir -p "$OUT"
SCENE="$OUT/sky_bench.toml"
sed -e "s/^width = 128$/width = $SIZE/" -e "s/^height = 128$/height = $SIZE/" \
    -e "s/^spp = 32$/spp = $SPP/" -e "s/^elevation_deg = 60.0$/elevation_deg = $ELEVATION/" \
    -e 's/^\[output\]$/[output]\ncsv = true\nexr = false\npng = false/' \
    -e "s/^method = \"path\"$/$INTEGRATOR/" \
    examples/sky_noon.toml > "$SCENE"
grep -q "^width = $SIZE$" "$SCENE" && grep -q "^spp = $SPP" "$SCENE" && grep -q "^elevation_deg = $ELEVATION$" "$SCENE" \
  && grep -q "^method = " "$SCENE" \
  || { echo "bench_sky.sh: examples/sky_noon.toml no longer has the lines this script edits" >&2; exit 2; }
sed -n '/^\[integrator\]/,/^$/p' "$SCENE"
uptime
for seed in 1 2; do
  /usr/bin/time -f "seed $seed: %e s wall, %U s user, %S s sys" \
    "$BIN" render "$SCENE" --seed "$seed" --out "$OUT/seed$seed" --quiet > /dev/null
done
python3 - "$OUT" "$SPP" "$SIZE" <<'PY'
import csv, glob, math, sys
out, spp = sys.argv[1], int(sys.argv[2])
def image(seed):
    path = glob.glob(f"{out}/seed{seed}/*.csv")[0]
    rows = list(csv.reader(open(path)))
    head, body = rows[0], rows[1:]
    bands = [i for i, h in enumerate(head) if h.startswith("L_") or h.endswith("nm")]
    return {(int(r[0]), int(r[1])): sum(float(r[i]) for i in bands) / len(bands) for r in body}
a, b = image(1), image(2)
n = int(sys.argv[3]); R = n / 2
inside = [k for k in a if math.hypot(abs(k[0] + 0.5 - R) + 0.5, abs(k[1] + 0.5 - R) + 0.5) < R - 1]
rel = [((a[k] - b[k]) / ((a[k] + b[k]) / 2)) ** 2 / 2 for k in inside if a[k] + b[k] > 0]
sigma = math.sqrt(sum(rel) / len(rel))
print(f"{len(inside)} pixels inside the circle; per-pixel relative noise at {spp} spp: {sigma:.4f}")
mean = [sum(img[k] for k in inside) / len(inside) for img in (a, b)]
print(f"mean radiance over the circle (band mean, W m^-2 sr^-1 nm^-1): seed 1 {mean[0]:.5e}, seed 2 {mean[1]:.5e}")
# The pixels that see the sun's disc hold most of that mean and differ between seeds by tens of
# per cent: the sky's own mean leaves out pixels brighter than 100 × the median (the disc).
both = sorted(a[k] + b[k] for k in inside)
sky = [k for k in inside if a[k] + b[k] <= 100 * both[len(both) // 2]]
mean = [sum(img[k] for k in sky) / len(sky) for img in (a, b)]
print(f"mean sky radiance without the {len(inside) - len(sky)} sun pixels: seed 1 {mean[0]:.5e}, seed 2 {mean[1]:.5e}")
k = (sigma / 0.02) ** 2
print(f"for 2 %: {spp * k:.0f} spp, {k:.2f} × the time of one render above")
PY
python3 - "$OUT/seed1/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("seed 1 report.json: total", f"{r['total_seconds']:.1f} s;",
      "; ".join(f"{p['phase']} {p['seconds']:.1f} s wall, {p['cpu_seconds']:.1f} s CPU" for p in r["phases"]))
print("  rays:", ", ".join(f"{k} {v}" for k, v in r["rays"].items()))
for m in r["maps"]:
    print("  map:", ", ".join(f"{k} {v}" for k, v in m.items() if not isinstance(v, (dict, list))))
PY
