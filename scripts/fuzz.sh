#!/usr/bin/env bash
# The long fuzz run of issue 15: CASES cases (default 100,000) of every target of
# `morgana-fuzz` (scene, render, obj, luminaire, atmosphere, grid, tonemap, cli), seed SEED
# (default 1), on JOBS worker processes (default 2). Prints a histogram of outcomes per target
# (cases, time, cases/s) and appends every disallowed outcome, with the case's index and what
# it is made of, to LOG (default target/fuzz/findings.tsv). Exit 1 when any case's outcome was
# not allowed.
#
#   scripts/fuzz.sh                              # everything, 10^5 cases per target
#   CASES=1000 TARGETS="scene cli" scripts/fuzz.sh
#   target/release/morgana-fuzz case --target scene --seed 1 --index 4711 --dump /tmp/c  # one case again
#
# A finding is minimised into the regression corpus with
#   target/release/morgana-fuzz minimize --target T --seed S --index I --out tests/fuzz_corpus/T/what_broke.ext
# (the book's "Robustness" chapter).
set -euo pipefail
cd "$(dirname "$0")/.."

CASES="${CASES:-100000}"
SEED="${SEED:-1}"
JOBS="${JOBS:-2}"
TARGETS="${TARGETS:-scene render obj luminaire atmosphere grid tonemap cli}"
LOG="${LOG:-target/fuzz/findings.tsv}"

cargo build --release --quiet --bin morgana --bin morgana-fuzz
mkdir -p "$(dirname "$LOG")"
echo "morgana-fuzz: $CASES cases per target, seed $SEED, $JOBS jobs; $(nproc) CPUs ($(uname -m)), $(date -u '+%Y-%m-%d %H:%M UTC'); findings to $LOG"
status=0
for t in $TARGETS; do
  target/release/morgana-fuzz run --target "$t" --cases "$CASES" --seed "$SEED" --jobs "$JOBS" --log "$LOG" || status=1
done
exit $status
