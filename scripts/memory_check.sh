#!/usr/bin/env bash
# Compares morgana's memory estimate (report.json `memory.estimated_peak_bytes`, made before the
# photon maps are allocated) with the measured peak resident memory (`peak_memory_bytes`, VmHWM)
# on the shipped examples, and fails if any estimate is more than 20 % off.
#
#   scripts/memory_check.sh [EXAMPLE.toml ...]      (default: every examples/*.toml)
#
# Extra arguments for `morgana render` can be given in MORGANA_ARGS (e.g. "--threads 1").
# SHRINK=k divides the camera's width and height by k (a copy of the scene beside it, removed
# after) and keeps every photon count: the photon maps, which dominate memory, stay full size
# while the eye pass takes k² times less time.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin morgana
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(examples/*.toml)
out="$(mktemp -d "${TMPDIR:-/tmp}/morgana-memory.XXXXXX")"
copy=""
trap 'rm -rf "$out"; [ -z "$copy" ] || rm -f "$copy"' EXIT
printf '%-32s %12s %12s %8s  %s\n' scene estimated_MB measured_MB ratio largest_phase
fail=0
for s in "${scenes[@]}"; do
  name="$(basename "$s" .toml)"
  scene=$s
  if [ -n "${SHRINK:-}" ]; then
    scene="$(dirname "$s")/.memory_$name.toml"
    copy=$scene
    python3 - "$s" "$scene" "$SHRINK" <<'PY'
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
k = int(sys.argv[3])
head, sep, tail = text.partition("[camera]")
if sep:
    nxt = re.search(r"^\[", tail, flags=re.M)
    cam, rest = (tail[: nxt.start()], tail[nxt.start():]) if nxt else (tail, "")
    for key in ("width", "height"):
        cam = re.sub(rf"^({key}\s*=\s*)(\d+)", lambda m: f"{m.group(1)}{max(1, int(m.group(2)) // k)}", cam, count=1, flags=re.M)
    text = head + sep + cam + rest
open(sys.argv[2], "w", encoding="utf-8").write(text)
PY
  fi
  # shellcheck disable=SC2086
  target/release/morgana render "$scene" --quiet --out "$out/$name" ${MORGANA_ARGS:-} >/dev/null
  if [ -n "$copy" ]; then rm -f "$copy"; copy=""; fi
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
