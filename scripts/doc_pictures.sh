#!/usr/bin/env bash
# The book's pictures re-rendered at full size until the image mean is known to 2 % (issue 17,
# "Docs": "re-render them with --target-rel-error 0.02 at >= 640x360 and give each one's cost").
#
#   scripts/doc_pictures.sh [NAME ...]      # default: every picture below; --list prints them
#
# Each picture is its example with the camera's width and height replaced (the aspect ratio kept
# where the example's own is wider than 16:9, so the view is the same), rendered by
# `morgana render --target-rel-error 0.02 --time CAP --threads 2` into out/doc_pictures/NAME/;
# its PNG preview (the render's own, as before) is copied over the book's. The cost — passes,
# the rule that stopped the run, the image mean's relative standard error and the mean over
# pixels of each pixel's, wall and CPU seconds
# (user + sys), the load average before and after — goes to out/doc_pictures/costs.csv and
# stdout. The machine is shared: quote CPU seconds, with the load.
#
# MORGANA_BIN overrides the binary (default: target/release/morgana, built here); THREADS the
# threads (default 2; CPU seconds are the cost either way); TARGET=pixels stops on the 95 %
# quantile of the pixels' relative errors instead of the image mean (`--target pixels`).
set -euo pipefail
cd "$(dirname "$0")/.."

# name  width  height  time cap  destination (relative to docs/)
PICTURES=(
  "fluorescent_glass_block 640 480 40min ocean/fluorescent_glass_block.png"
  "mirage_hot_road 800 360 60min curved/mirage_hot_road.png"
  "mirage_superior 900 360 60min curved/mirage_superior.png"
  "sunset_sea 640 480 20min curved/sunset_sea.png"
  "sunset_fog 640 480 30min curved/sunset_fog.png"
  "underwater_luminaire 640 480 60min ocean/underwater_luminaire.png"
)

if [[ "${1:-}" == "--list" ]]; then
  printf '%s\n' "${PICTURES[@]}"
  exit 0
fi
BIN=${MORGANA_BIN:-target/release/morgana}
if [[ -z "${MORGANA_BIN:-}" ]]; then
  cargo build --release --quiet --bin morgana
fi
OUT=out/doc_pictures
mkdir -p "$OUT"
THREADS=${THREADS:-2}
TARGET=${TARGET:-image}
[[ -f "$OUT/costs.csv" ]] || echo "date,name,width,height,target,passes,stopped,rel_error,mean_pixel_rel_error,wall_s,cpu_s,threads,load_before,load_after" > "$OUT/costs.csv"

load1() { cut -d' ' -f1 /proc/loadavg; }

for entry in "${PICTURES[@]}"; do
  read -r name width height cap dest <<<"$entry"
  if [[ $# -gt 0 ]] && [[ ! " $* " == *" $name "* ]]; then
    continue
  fi
  # The variant sits beside its example so that the example's relative paths still resolve.
  variant="examples/_doc_picture_$name.toml"
  trap 'rm -f "$variant"' EXIT
  sed -E "0,/^width = .*/s//width = $width/; 0,/^height = .*/s//height = $height/" "examples/$name.toml" > "$variant"
  grep -q "^width = $width$" "$variant" && grep -q "^height = $height$" "$variant"
  echo "doc_pictures: $name at ${width}x$height, $(date -u +%FT%TZ), $(uptime | sed 's/.*load average/load average/')"
  before=$(load1)
  /usr/bin/time -f "%e %U %S" -o "$OUT/$name.time" \
    "$BIN" render "$variant" --out "$OUT/$name" --threads "$THREADS" --quiet --target-rel-error 0.02 --target "$TARGET" --time "$cap" >/dev/null
  after=$(load1)
  rm -f "$variant"
  read -r wall user sys < "$OUT/$name.time"
  row=$(python3 - "$OUT/$name/report.json" <<'EOF'
import json, sys
p = json.load(open(sys.argv[1]))["progressive"]
print(f'{p["passes"]},{p["stopped"]["rule"]},{p["rel_error"]:.4f},{p["image_mean_rel_error"]:.4f}')
EOF
)
  cpu=$(python3 -c "print(f'{$user + $sys:.1f}')")
  echo "$(date -u +%FT%TZ),$name,$width,$height,$TARGET,$row,$wall,$cpu,$THREADS,$before,$after" | tee -a "$OUT/costs.csv"
  cp "$OUT/$name/$name.png" "docs/$dest"
done
echo "doc_pictures: done $(date -u +%FT%TZ), $(uptime | sed 's/.*load average/load average/')"
