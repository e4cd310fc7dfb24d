#!/usr/bin/env bash
# Whole renders of shipped examples with two morgana binaries, one after the other:
#
#     [SHRINK=N] [THREADS=N] [BASE_KEYS='...'] [NEW_KEYS='...'] \
#         scripts/bench_examples.sh BASE_BIN NEW_BIN OUT EXAMPLE...     (EXAMPLE: a name in examples/)
#
# Each example is rendered with BASE_BIN, then with NEW_BIN (`render FILE --out OUT/EXAMPLE.{base,new}
# --quiet`), and the script prints the user + system CPU seconds of each process and, from its
# report.json, the CPU seconds of the eye pass and of the beam estimate's disc radii (how the two
# images differ: scripts/compare_images.py OUT EXAMPLE...). CPU time
# rather than wall time, so that other load on a shared machine distorts it less (it still adds
# some ±10 %: caches and memory are shared). Optional: SHRINK divides the camera's width and
# height (default 1: the shipped size), THREADS sets --threads, and BASE_KEYS / NEW_KEYS are TOML
# lines added to [integrator] for that side only (e.g. NEW_KEYS='volume_estimate = "beam"', to
# compare two settings with one binary). The modified copies are written beside the examples
# (examples/.bench_*.toml, so that their relative file paths still resolve) and removed after.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 4 ] || { sed -n 2,16p "$0" >&2; exit 2; }
base=$1 new=$2 out=$3
shift 3
shrink=${SHRINK:-1}
threads=()
[ -n "${THREADS:-}" ] && threads=(--threads "$THREADS")
mkdir -p "$out"
trap 'rm -f examples/.bench_*.toml' EXIT
# The example with its camera shrunk and `keys` added to [integrator]: a copy beside it, of the
# same name for both sides (an example without [output] name names its outputs after the file).
copy() {
  local ex=$1 keys=$2
  python3 - "examples/$ex.toml" "examples/.bench_$ex.toml" "$shrink" "$keys" <<'PY'
import re, sys
src, dst, shrink, keys = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
text = open(src).read()
for key in ("width", "height"):
    text = re.sub(rf"(?m)^{key} = (\d+)", lambda m: f"{key} = {max(1, int(m.group(1)) // shrink)}", text, count=1)
if keys:
    text = re.sub(r"(?m)^\[integrator\]$", lambda m: "[integrator]\n" + keys, text, count=1)
open(dst, "w").write(text)
PY
  echo "examples/.bench_$ex.toml"
}
printf '%-28s %10s %10s %16s %16s %12s\n' example "base CPU s" "new CPU s" "eye base" "eye new" "radii new"
for ex in "$@"; do
  for side in base new; do
    bin=$base keys=${BASE_KEYS:-}
    [ "$side" = new ] && bin=$new keys=${NEW_KEYS:-}
    file=$(copy "$ex" "$keys")
    dir="$out/$ex.$side"
    mkdir -p "$dir"
    /usr/bin/time -f "%U %S" -o "$dir/time" "$bin" render "$file" --out "$dir" --quiet "${threads[@]}" > "$dir/log" 2>&1
  done
  python3 - "$out" "$ex" <<'PY'
import json, sys
out, ex = sys.argv[1], sys.argv[2]
row = []
for side in ("base", "new"):
    user, sys_ = open(f"{out}/{ex}.{side}/time").read().split()[-2:]
    phases = {p["phase"]: p["cpu_seconds"] for p in json.load(open(f"{out}/{ex}.{side}/report.json"))["phases"]}
    row.append((float(user) + float(sys_), phases.get("eye pass", 0.0), phases.get("volume beam radii", 0.0)))
(b, eb, _), (n, en, rn) = row
print(f"{ex:28s} {b:10.1f} {n:10.1f} {eb:16.1f} {en:16.1f} {rn:12.1f}")
PY
done
