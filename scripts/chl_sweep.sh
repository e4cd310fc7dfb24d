#!/usr/bin/env sh
# Chlorophyll sweep: renders examples/chlorophyll_sweep.toml for Chl = 0.01 … 10 mg m⁻³ and
# writes OUT/rrs_sweep.csv (chl_mg_m3,wavelength_nm,Rrs_per_sr) and OUT/rrs_sweep.png.
# Usage: scripts/chl_sweep.sh [OUT] [PHOTONS]  (defaults: out/chl_sweep, 1000000; about half a minute
# per concentration on 2 cores at the default).
set -eu
cd "$(dirname "$0")/.."
OUT=${1:-out/chl_sweep}
PHOTONS=${2:-1000000}
mkdir -p "$OUT"
cargo build --release --bin morgana --bin morgana-rrs-plot
echo "chl_mg_m3,wavelength_nm,Rrs_per_sr" > "$OUT/rrs_sweep.csv"
for chl in 0.01 0.03 0.1 0.3 1 3 10; do
  sed "s/^chl_mg_m3 = .*/chl_mg_m3 = $chl/" examples/chlorophyll_sweep.toml > "$OUT/sweep_$chl.toml"
  ./target/release/morgana render "$OUT/sweep_$chl.toml" --out "$OUT/chl_$chl" --photons "$PHOTONS" --quiet > /dev/null
  awk -F, -v chl="$chl" 'NR > 1 && NF == 6 { print chl "," $2 "," $6 }' "$OUT/chl_$chl/chlorophyll_sweep_rrs_derived.csv" >> "$OUT/rrs_sweep.csv"
done
./target/release/morgana-rrs-plot "$OUT/rrs_sweep.csv" "$OUT/rrs_sweep.png"
echo "wrote $OUT/rrs_sweep.csv and $OUT/rrs_sweep.png"
