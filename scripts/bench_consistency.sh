#!/usr/bin/env bash
# Consistency and calibration of progressive photon mapping (issue 17, "Measured goals";
# docs/book/src/convergence.md, "Measured convergence"): the white furnace against its closed
# form and the fog box against the Mitsuba reference, each one progressive run stopped and
# resumed at growing pass counts up to --max-cpu CPU seconds (default 300), with the fitted
# slope of log error against log CPU time over 10..300 s and the share of pixel-bands the
# reported standard errors cover. Builds morgana, sets up .venv with the Mitsuba peer, renders
# (or reuses) the fog box's Mitsuba reference, then runs scripts/consistency.py with the
# arguments given (--help lists them; --scenes furnace needs no reference).
#
# Usage: scripts/bench_consistency.sh [--scenes furnace fog_box] [--max-cpu 300] [--alpha A]
# About 5 CPU minutes a scene and chain (its wall time grows with the machine's load: the log
# records it); the fog box's reference about 15 CPU minutes the first time.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet --bin morgana
./scripts/setup_peer_venv.sh
echo "bench_consistency: $(date -u +%FT%TZ), load: $(uptime | sed 's/.*load average/load average/')"
if [[ " $* " != *" --scenes furnace "* || " $* " == *"fog_box"* ]]; then
    .venv/bin/python scripts/peer_mitsuba.py --reference-only --scenes fog_box
fi
.venv/bin/python scripts/consistency.py "$@"
echo "bench_consistency: done $(date -u +%FT%TZ), load: $(uptime | sed 's/.*load average/load average/')"
