#!/usr/bin/env bash
# Proves that a change did not change what morgana computes: renders the default scene and every
# example (reduced: a quarter of the resolution, few photons, fixed seed) with the binary built
# from BASE (a git revision, default: origin/main or main) and with the working tree, and compares
# every output byte for byte, except report.json (it holds timings).
#
#   ./scripts/identical_outputs.sh [BASE] [--photons N] [--only NAME]
#
# Exit 0 when all outputs are identical, 1 when any differs (the differing files are listed).
# The base is built in a git worktree under target/identical/base (kept between runs), unless
# MORGANA_BASE_BIN names a morgana binary already built from BASE.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

base=""
photons=20000
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --photons) photons="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) base="$1"; shift ;;
  esac
done
if [ -z "$base" ]; then
  if git rev-parse --verify -q origin/main >/dev/null; then base=origin/main; else base=main; fi
fi

work="$root/target/identical"
# The ocean tables: the base may predate the built-in ones and looks for them beside its checkout.
if [ -z "${MORGANA_OCEAN_DATA:-}" ] && [ -d "$root/../shared/data/ocean" ]; then
  export MORGANA_OCEAN_DATA="$root/../shared/data/ocean"
fi
mkdir -p "$work"
base_rev=$(git rev-parse "$base")
echo "identical_outputs: base $base ($base_rev) against the working tree"

# --- the two binaries ------------------------------------------------------------------------
if [ -n "${MORGANA_BASE_BIN:-}" ]; then
  # A binary already built from BASE (e.g. a copy of main's target/release/morgana): no worktree.
  base_bin=$MORGANA_BASE_BIN
  echo "identical_outputs: the base binary is $base_bin (MORGANA_BASE_BIN), taken to be built from $base_rev"
else
  if [ ! -d "$work/base" ]; then
    git worktree add --detach "$work/base" "$base_rev" >/dev/null
  else
    git -C "$work/base" checkout --detach -q "$base_rev"
  fi
  (cd "$work/base" && cargo build --release --quiet --bin morgana)
  base_bin="$work/base/target/release/morgana"
fi
cargo build --release --quiet --bin morgana
new_bin="$root/target/release/morgana"

# --- reduced copies of the examples, written beside them so relative paths still resolve ------
tmp_scenes=()
cleanup() { rm -f "${tmp_scenes[@]}"; }
trap cleanup EXIT
reduce() { # $1 source scene, $2 destination
  python3 - "$1" "$2" <<'PY'
import re, sys
src, dst = sys.argv[1], sys.argv[2]
text = open(src, encoding="utf-8").read()
def quarter(m):
    return f"{m.group(1)}{max(1, int(m.group(2)) // 4)}"
# Only the camera's width and height: the first `width =` / `height =` after [camera].
head, sep, tail = text.partition("[camera]")
if sep:
    nxt = re.search(r"^\[", tail, flags=re.M)
    cam, rest = (tail[: nxt.start()], tail[nxt.start():]) if nxt else (tail, "")
    cam = re.sub(r"^(width\s*=\s*)(\d+)", quarter, cam, count=1, flags=re.M)
    cam = re.sub(r"^(height\s*=\s*)(\d+)", quarter, cam, count=1, flags=re.M)
    text = head + sep + cam + rest
open(dst, "w", encoding="utf-8").write(text)
PY
}

names=(default)
for f in examples/*.toml; do names+=("$(basename "$f" .toml)"); done

status=0
for name in "${names[@]}"; do
  if [ -n "$only" ] && [ "$name" != "$only" ]; then continue; fi
  args=(--photons "$photons" --seed 7 --threads 2 --quiet)
  scene=()
  if [ "$name" != default ]; then
    copy="examples/.identical-$name.toml"
    tmp_scenes+=("$copy")
    reduce "examples/$name.toml" "$copy"
    scene=("$copy")
  fi
  for side in base new; do
    bin=$base_bin; [ $side = new ] && bin=$new_bin
    out="$work/out-$side/$name"
    rm -rf "$out"; mkdir -p "$out"
    if ! "$bin" render "${scene[@]}" --out "$out" "${args[@]}" >"$out.log" 2>&1; then
      echo "  $name: $side render failed (see $out.log)"; status=1; continue 2
    fi
  done
  differ=()
  for f in "$work/out-base/$name"/*; do
    b=$(basename "$f")
    [ "$b" = report.json ] && continue
    cmp -s "$f" "$work/out-new/$name/$b" || differ+=("$b")
  done
  for f in "$work/out-new/$name"/*; do
    b=$(basename "$f")
    [ -e "$work/out-base/$name/$b" ] || differ+=("$b (new only)")
  done
  count=$(find "$work/out-base/$name" -type f ! -name report.json | wc -l)
  if [ ${#differ[@]} -eq 0 ]; then
    echo "  $name: $count files identical"
  else
    echo "  $name: DIFFERENT: ${differ[*]}"; status=1
  fi
done
if [ $status -eq 0 ]; then echo "identical_outputs: all identical"; else echo "identical_outputs: differences found"; fi
exit $status
