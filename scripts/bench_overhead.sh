#!/usr/bin/env sh
# Overhead of the inelastic-scattering and curved-path code on scenes that need neither:
# `scripts/bench_overhead.sh [BASE] [fog|default]`.
#
# Builds the `morgana` binary of BASE (default 0bea01f, the commit this work started from, which
# has neither inelastic nor curved-path code) and of the working tree, then renders a reduced fog
# box (`fog`, the default: a homogeneous medium of constant n = 1, no inelastic component: 48×48
# px, 200k photons, 2 spp, 8 gather rays, one thread) or the reduced default Cornell box
# (`default`: surfaces only, 128×128 px, 100k + 100k photons, 4 spp, 8 gather rays) ROUNDS times with each,
# alternating, and prints the median user CPU time of each and their ratio. Alternating runs and
# CPU time (not wall time) keep other load on a shared machine from favouring one side; the
# spread of the rounds is printed so the noise can be judged. Criterion's version of the same
# measurement (in-process) is `cargo bench --bench photon_trace`.
set -eu
cd "$(dirname "$0")/.."
BASE=${1:-0bea01f}
SCENE=${2:-fog}
ROUNDS=${ROUNDS:-7}
ROOT=$(pwd)
TMP=$(mktemp -d)
git worktree add --detach "$TMP/base" "$BASE" >/dev/null
trap 'git worktree remove --force "$TMP/base"; rm -rf "$TMP"' EXIT
# A target folder of its own: sharing target/ lets cargo mistake one build for the other.
(cd "$TMP/base" && CARGO_TARGET_DIR="$ROOT/target/overhead-base" cargo build --release --bin morgana -q)
cp target/overhead-base/release/morgana "$TMP/morgana-base"
cargo build --release --bin morgana -q
cp target/release/morgana "$TMP/morgana-head"
if cmp -s "$TMP/morgana-base" "$TMP/morgana-head"; then echo "the two binaries are identical: nothing to compare" >&2; exit 1; fi
if [ "$SCENE" = default ]; then
  sed -e 's/width = 256/width = 128/' -e 's/height = 256/height = 128/' -e 's/photons = 200000/photons = 100000/' \
      -e 's/spp = 16/spp = 4/' -e 's/gather_rays = 16/gather_rays = 8/' src/scene/default.toml > "$TMP/fog_small.toml"
else
  sed -e 's/width = 128/width = 48/' -e 's/height = 128/height = 48/' -e 's/photons = 400000/photons = 200000/' \
      -e 's/spp = 8/spp = 2/' -e 's/gather_rays = 16/gather_rays = 8/' examples/fog_box.toml > "$TMP/fog_small.toml"
fi
for i in $(seq "$ROUNDS"); do
  for side in base head; do
    /usr/bin/time -f "%U" -o "$TMP/t" "$TMP/morgana-$side" render "$TMP/fog_small.toml" --out "$TMP/out-$side" --threads 1 --quiet >/dev/null
    echo "$side $(cat "$TMP/t")" >> "$TMP/times"
  done
done
awk '{ t[$1] = t[$1] " " $2 } END { for (s in t) print s ":" t[s] }' "$TMP/times"
python3 - "$TMP/times" <<'PY'
import sys, statistics
rows = [l.split() for l in open(sys.argv[1])]
med = {s: statistics.median(float(t) for k, t in rows if k == s) for s in ("base", "head")}
print(f"median user CPU: base {med['base']:.2f} s, head {med['head']:.2f} s, head/base = {med['head'] / med['base']:.3f}")
PY
