#!/usr/bin/env bash
# The benchmark against Mitsuba 3 (README, "Benchmark against Mitsuba 3"): builds morgana in
# release mode, adds the pinned Mitsuba 3 peer to .venv (scripts/setup_peer_venv.sh), then runs
# scripts/peer_mitsuba.py, which renders a Mitsuba reference per scene, the three series, and
# prints the equal-time table. Arguments go to peer_mitsuba.py (--help lists them; --quick runs
# the first three budgets only). About an hour on 2 cores the first time, half of it for the two
# references, which are kept in out/mitsuba_bench/*/reference.npz and reused while the translated
# scene is unchanged; about 25 minutes after that.
#
# --progressive (issue 17, equal-time goals at 60 and 300 CPU s): instead of the one-pass
# budgets, morgana's progressive photon mapping as one run stopped and resumed at growing pass
# counts up to --max-cpu CPU seconds (scripts/progressive_chain.py), uniform and, on the volume
# caustic, adaptive (--adaptive); Mitsuba at --mitsuba-spp, its RMSE at longer times by the
# 1/sqrt(t) law of an unbiased estimator. Writes progressive_SCENES.csv and progressive_runs_SCENES.csv:
#   scripts/bench_mitsuba.sh --progressive --cpu-times 10 60 300
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin morgana
./scripts/setup_peer_venv.sh
.venv/bin/python scripts/peer_mitsuba.py "$@"
