#!/usr/bin/env bash
# The green flash as a sequence in time (the book's "The sky" page): examples/green_flash.toml
# rendered with the sun's centre at true altitudes −1.00°, −1.02°, … −1.10° (solar zenith 91.00°
# … 91.10°, one `--sun-zenith-deg` run), every frame tone-mapped with one fixed exposure (the
# first frame's automatic one, so the frames compare), set side by side. Run from the
# repository root:
#
#   scripts/green_flash_sequence.sh [MORGANA_BINARY] [OUT_DIR]
#
# Defaults: target/release/morgana, /tmp/green_flash_sequence. Writes OUT_DIR/sequence.png (the
# strip), OUT_DIR/sun_zenith_*/ (each frame's EXR, PNG, report.json), OUT_DIR/frame_*.png (the
# fixed-exposure frames) and OUT_DIR/times.txt (wall and CPU time, load before and after).
# REUSE=1 skips the renders and tone-maps the frames already in OUT_DIR.
set -euo pipefail
BIN=${1:-target/release/morgana}
OUT=${2:-/tmp/green_flash_sequence}
ZENITHS=(91.00 91.02 91.04 91.06 91.08 91.10)
mkdir -p "$OUT"
list=$(IFS=,; echo "${ZENITHS[*]}")
if [ -z "${REUSE:-}" ]; then
  uptime > "$OUT/times.txt"
  /usr/bin/time -a -o "$OUT/times.txt" -f "sequence: %e s wall, %U s user, %S s sys" \
    "$BIN" render examples/green_flash.toml --sun-zenith-deg "$list" --out "$OUT" --quiet > /dev/null
  uptime >> "$OUT/times.txt"
fi
# The sweep names a folder by the angle as Rust prints it (91, 91.02, …).
dir_of() { python3 -c "import sys; x = float(sys.argv[1]); print('sun_zenith_' + (str(int(x)) if x.is_integer() else repr(x)))" "$1"; }
first="$OUT/$(dir_of "${ZENITHS[0]}")/green_flash.exr"
# The first (highest) sun's automatic exposure puts its 99th-percentile luminance at display
# white; `morgana tonemap` prints that luminance W (cd/m²), and the exposure of scale 2^EV = 1/W
# is then given to every frame.
white=$("$BIN" tonemap "$first" --out "$OUT/frame_auto.png" --fov-deg 0.3 | sed -n 's/.*display white at \([0-9.e+-]*\) cd\/m2.*/\1/p' | head -1)
[ -n "$white" ] || { echo "green_flash_sequence.sh: morgana tonemap did not print its display white" >&2; exit 2; }
ev=$(python3 -c "import math, sys; print(-math.log2(float(sys.argv[1])))" "$white")
echo "exposure: display white $white cd/m2, EV $ev" >> "$OUT/times.txt"
frames=()
for i in "${!ZENITHS[@]}"; do
  exr="$OUT/$(dir_of "${ZENITHS[$i]}")/green_flash.exr"
  "$BIN" tonemap "$exr" --out "$OUT/frame_$i.png" --exposure "$ev" --fov-deg 0.3 > /dev/null
  frames+=("$OUT/frame_$i.png")
done
python3 scripts/png_strip.py "$OUT/sequence.png" 4 "${frames[@]}"
cat "$OUT/times.txt"
