#!/usr/bin/env bash
# The pictures of the sky examples on the book's "The sky" page, at small sizes (the machines are
# shared): each scene is the example with only its image size and samples edited, rendered with
# its run time (wall, user and sys CPU) and the load average before and after (`uptime`).
#
#   scripts/sky_pictures.sh [MORGANA_BINARY] [OUT_DIR] [PYTHON]
#
# Defaults: target/release/morgana, /tmp/sky_pictures, python3 (it needs matplotlib for the
# twilight plot: scripts/setup_venv.sh, then .venv/bin/python). Writes, in OUT_DIR:
#   sky_noon/sky_noon.png      all-sky, 64 × 64, 512 samples per pixel (examples/sky_noon.toml),
#                              and sky_noon_x3.png, enlarged 3× by whole pixels (scripts/png_zoom.py)
#   sky_haze/sky_haze.png      all-sky, 64 × 64, 512 samples per pixel (examples/sky_haze.toml),
#                              and sky_haze_x3.png
#   sky_sunset/sky_sunset.png  96 × 48, 2 samples per pixel (examples/sky_sunset.toml; ~18 CPU
#                              minutes), and sky_sunset_x3.png
#   sky_twilight/twilight.png  the zenith through twilight, solar zenith 90–98° (examples/sky_twilight.toml)
#   times.txt                  what each took, with `uptime` before and after
# Copy the PNGs to docs/book/src/figures/sky/ to update the book.
set -euo pipefail
BIN=${1:-target/release/morgana}
OUT=${2:-/tmp/sky_pictures}
PY=${3:-python3}
mkdir -p "$OUT"
: > "$OUT/times.txt"

# run NAME SCENE [ARGS...]: renders SCENE into OUT/NAME, logging its time and the load.
run() {
  local name=$1 scene=$2
  shift 2
  { echo "== $name"; uptime; } >> "$OUT/times.txt"
  /usr/bin/time -a -o "$OUT/times.txt" -f "$name: %e s wall, %U s user, %S s sys" \
    "$BIN" render "$scene" --out "$OUT/$name" --quiet "$@" > /dev/null
  uptime >> "$OUT/times.txt"
}

# small SRC W H SPP DST: SRC with its image size and samples per pixel edited, checked.
small() {
  local src=$1 w=$2 h=$3 spp=$4 dst=$5
  local w0 h0 s0
  w0=$(grep -m1 '^width = ' "$src" | cut -d' ' -f3)
  h0=$(grep -m1 '^height = ' "$src" | cut -d' ' -f3)
  s0=$(grep -m1 '^spp = ' "$src" | cut -d' ' -f3)
  sed -e "s/^width = $w0\$/width = $w/" -e "s/^height = $h0\$/height = $h/" -e "s/^spp = $s0\$/spp = $spp/" "$src" > "$dst"
  grep -q "^width = $w\$" "$dst" && grep -q "^height = $h\$" "$dst" && grep -q "^spp = $spp\$" "$dst" \
    || { echo "sky_pictures.sh: $src no longer has the width, height and spp lines this script edits" >&2; exit 2; }
}

small examples/sky_noon.toml 64 64 512 "$OUT/sky_noon.toml"
run sky_noon "$OUT/sky_noon.toml"
python3 scripts/png_zoom.py "$OUT/sky_noon/sky_noon.png" "$OUT/sky_noon/sky_noon_x3.png" 0 0 64 64 3
small examples/sky_haze.toml 64 64 512 "$OUT/sky_haze.toml"
run sky_haze "$OUT/sky_haze.toml"
python3 scripts/png_zoom.py "$OUT/sky_haze/sky_haze.png" "$OUT/sky_haze/sky_haze_x3.png" 0 0 64 64 3
run sky_twilight examples/sky_twilight.toml --sun-zenith-deg 90,91,92,93,94,95,96,97,98
"$PY" scripts/plot_sun_sweep.py "$OUT/sky_twilight/sky_twilight_sun_sweep.csv" "$OUT/sky_twilight/twilight.png"
small examples/sky_sunset.toml 96 48 2 "$OUT/sky_sunset.toml"
run sky_sunset "$OUT/sky_sunset.toml"
python3 scripts/png_zoom.py "$OUT/sky_sunset/sky_sunset.png" "$OUT/sky_sunset/sky_sunset_x3.png" 0 0 96 48 3
cat "$OUT/times.txt"
