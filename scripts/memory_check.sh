#!/usr/bin/env bash
# Compares morgana's memory estimate (report.json `memory.estimated_peak_bytes`, made before the
# photon maps are allocated) with the measured peak resident memory (`peak_memory_bytes`, VmHWM)
# on the shipped examples, and fails if any estimate is more than 20 % off.
#
#   scripts/memory_check.sh [EXAMPLE.toml ...]      (default: every examples/*.toml)
#
# Extra arguments for `morgana render` can be given in MORGANA_ARGS (e.g. "--threads 1").
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin morgana
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(examples/*.toml)
out="$(mktemp -d "${TMPDIR:-/tmp}/morgana-memory.XXXXXX")"
trap 'rm -rf "$out"' EXIT
printf '%-32s %12s %12s %8s  %s\n' scene estimated_MB measured_MB ratio largest_phase
fail=0
for s in "${scenes[@]}"; do
  name="$(basename "$s" .toml)"
  # shellcheck disable=SC2086
  target/release/morgana render "$s" --quiet --out "$out/$name" ${MORGANA_ARGS:-} >/dev/null
  python3 - "$out/$name/report.json" "$name" <<'PY' || fail=1
import json, sys
r = json.load(open(sys.argv[1]))
est, peak = r["memory"]["estimated_peak_bytes"], r["peak_memory_bytes"]
ratio = est / peak
print(f"{sys.argv[2]:32s} {est / 1e6:12.1f} {peak / 1e6:12.1f} {ratio:8.3f}  {r['memory']['largest_phase']}")
sys.exit(0 if abs(ratio - 1.0) <= 0.2 else 1)
PY
done
[ "$fail" = 0 ] || { echo "memory_check: an estimate is more than 20 % off the measured peak" >&2; exit 1; }
echo "memory_check: every estimate within 20 % of the measured peak"
