#!/usr/bin/env sh
# Photon map benchmark against kiddo 6: build 1M photons, 1M k=100 queries at two radii.
# About five minutes on 2 cores; PHOTON_MAP_BENCH_QUICK=1 runs 100k queries in about one.
# Criterion's "Unable to complete 10 samples" warnings are expected: each sample is one pass
# over all queries. The summary table (medians, ratios to kiddo, memory) is printed at the end
# and kept in target/photon_map_bench.txt.
set -eu
cd "$(dirname "$0")/.."
cargo bench --bench photon_map "$@" 2>&1 | tee target/photon_map_bench.txt
