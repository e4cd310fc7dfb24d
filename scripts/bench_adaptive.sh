#!/usr/bin/env bash
# Adaptive sampling against uniform passes at equal eye samples (issue 17 item 7;
# docs/book/src/convergence.md, "Adaptive sampling"), on the Mitsuba benchmark's volume caustic
# (benches/scenes/volume_caustic.toml: a small light in a snoot above a glass sphere in fog) at
# 64 × 64 pixels, 100 000 + 50 000 caustic photons a pass: 16 passes of 4 samples per pixel,
# uniform and adaptive (the same seed, so the same photon maps), against a reference of 64
# adaptive passes of 8 samples per pixel (another seed). Prints the RMSE over every pixel and
# band relative to the reference's mean, with the reference's noise removed in quadrature, the
# share of the squared error in the worst 1 % of pixels, and the adaptive/uniform ratio.
#
# Usage: scripts/bench_adaptive.sh
# It runs the ignored test tests/adaptive_sampling.rs::adaptive_sampling_lowers_the_glint_scenes_
# rmse_at_equal_samples on 2 threads (about 8 CPU minutes). The ratio is at equal eye samples,
# so the machine's load does not change it; the load is logged with the wall times.
set -euo pipefail
cd "$(dirname "$0")/.."
echo "bench_adaptive: $(date -u +%FT%TZ), load: $(uptime | sed 's/.*load average/load average/')"
cargo test --release --test adaptive_sampling -q adaptive_sampling_lowers_the_glint_scenes_rmse_at_equal_samples \
  -- --ignored --nocapture 2>&1 | grep -Ev '^(running|test result|$)'
echo "bench_adaptive: done $(date -u +%FT%TZ), load: $(uptime | sed 's/.*load average/load average/')"
