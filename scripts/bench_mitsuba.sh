#!/usr/bin/env bash
# The benchmark against Mitsuba 3 (README, "Benchmark against Mitsuba 3"): builds morgana in
# release mode, adds the pinned Mitsuba 3 peer to .venv (scripts/setup_peer_venv.sh), then runs
# scripts/peer_mitsuba.py, which renders a Mitsuba reference per scene, the three series, and
# prints the equal-time table. Arguments go to peer_mitsuba.py (--help lists them; --quick runs
# the first three budgets only). About an hour on 2 cores the first time, half of it for the two
# references, which are kept in out/mitsuba_bench/*/reference.npz and reused while the translated
# scene is unchanged; about 25 minutes after that.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin morgana
./scripts/setup_peer_venv.sh
.venv/bin/python scripts/peer_mitsuba.py "$@"
