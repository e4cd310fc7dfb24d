#!/usr/bin/env bash
# Whole renders of shipped examples with two morgana binaries, one after the other:
#
#     scripts/bench_examples.sh BASE_BIN NEW_BIN OUT EXAMPLE...     (EXAMPLE: a name in examples/)
#
# Each example is rendered at its shipped size with BASE_BIN, then with NEW_BIN (`render
# examples/EXAMPLE.toml --out OUT/EXAMPLE.{base,new} --quiet`), and the script prints the user +
# system CPU seconds of each process and, from its report.json, the CPU seconds of the eye pass
# and of the beam estimate's disc radii. CPU time rather than wall time, so that other load on a
# shared machine distorts it less (it still adds some ±10 %: caches and memory are shared).
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 4 ] || { sed -n 2,9p "$0" >&2; exit 2; }
base=$1 new=$2 out=$3
shift 3
mkdir -p "$out"
printf '%-28s %10s %10s %16s %16s %12s\n' example "base CPU s" "new CPU s" "eye base" "eye new" "radii new"
for ex in "$@"; do
  for side in base new; do
    bin=$base
    [ "$side" = new ] && bin=$new
    dir="$out/$ex.$side"
    mkdir -p "$dir"
    /usr/bin/time -f "%U %S" -o "$dir/time" "$bin" render "examples/$ex.toml" --out "$dir" --quiet > "$dir/log" 2>&1
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
