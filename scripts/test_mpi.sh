#!/usr/bin/env bash
# Distributed rendering under MPI (README, "Distributed rendering (MPI)"): builds morgana with
# and without the `mpi` feature and checks, on this machine (`mpirun --oversubscribe`), that
#   1. 1, 2 and 3 ranks (and the MPI build run without mpirun, and the static schedule) give the
#      same EXR bytes as the non-MPI build, for a scene with global + caustic maps and final
#      gathering, one with a volume map (read by the point estimate, and by photon beams), one
#      with curved paths (the hot-road mirage: index
#      field, sun projection map, curved eye paths) and the zenith in twilight (a volume map folded
#      about the sun's axis); report.json lists the ranks and their photons;
#   2. errors are collective: a missing scene, a too-small --max-map-memory and ranks that do
#      not see the same scene (another command line; another copy of a file the scene names,
#      where `unshare -m` can bind-mount one for a single rank) end every rank with one message
#      and no output;
#   3. progressive passes give the same bytes on any rank count, also when resumed on another,
#      with and without adaptive sampling (--adaptive);
#   4. a rank killed (SIGKILL) during the photon pass or the eye pass makes mpirun fail and leaves
#      the output directory empty.
# Needs OpenMPI and libclang (scripts/setup_mpi.sh). Takes a few minutes, mostly the two builds.
set -euo pipefail
cd "$(dirname "$0")/.."

command -v mpirun >/dev/null || { echo "test_mpi.sh: mpirun not found; run scripts/setup_mpi.sh" >&2; exit 1; }
step() { printf '\n== %s ==\n' "$*"; }
fail() { echo "test_mpi.sh: FAIL: $*" >&2; echo "mpi: $passed passed, 1 failed"; exit 1; }
passed=0
ok() { passed=$((passed + 1)); echo "$*"; }

work="$(mktemp -d "${TMPDIR:-/tmp}/morgana-mpi-test.XXXXXX")"
trap 'rm -rf "$work"' EXIT

# No binding: on a shared machine a rank pinned to a busy core would just run slowly.
MPIRUN=(mpirun --oversubscribe --bind-to none --mca mpi_yield_when_idle 1)
[ "$(id -u)" -eq 0 ] && MPIRUN+=(--allow-run-as-root)
# A hung collective must fail the test, not the CI job's time limit.
LIMIT=(timeout --signal=KILL 300)

step "build without and with the mpi feature"
cargo build --release --quiet --bin morgana
cp target/release/morgana "$work/morgana-local"
cargo clippy --quiet --features mpi --lib --bins -- -D warnings
cargo build --release --quiet --features mpi --bin morgana
cp target/release/morgana "$work/morgana-mpi"
mpirun --version | head -n 1

# Small versions of two scenes: the default Cornell box (global and caustic maps, final gather,
# glass) and the fog box (volume map).
shrink() { # scene width height spp gather_rays
  sed -e "s/^width = .*/width = $2/" -e "s/^height = .*/height = $3/" -e "s/^spp = .*/spp = $4/" \
      -e "s/^gather_rays = .*/gather_rays = $5/" "$1"
}
shrink src/scene/default.toml 48 40 2 4 > "$work/box.toml"
shrink examples/fog_box.toml 40 32 2 4 > "$work/fog.toml"
# The fog box read by photon beams: each rank's flights gathered in batch order.
sed -e 's/^\[integrator\]/[integrator]\nvolume_estimate = "photon_beams"/' "$work/fog.toml" > "$work/beams.toml"
# The mirage's atmosphere file by its absolute path (the copy lives in $work).
shrink examples/mirage_hot_road.toml 40 20 1 4 | sed "s#\.\./atmospheres/#$PWD/atmospheres/#" > "$work/mirage.toml"
shrink src/scene/default.toml 192 160 8 16 > "$work/slow.toml"
# The zenith in twilight (sun 4° below the horizon): a volume map folded about the sun's axis,
# each rank folding its own photons before the map is assembled.
sed -e "s/^elevation_deg = 0.0/elevation_deg = -4.0/" examples/sky_twilight.toml > "$work/twilight.toml"

check_report() { # report.json ranks emitted
  python3 - "$1" "$2" "$3" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1])); ranks = int(sys.argv[2]); emitted = int(sys.argv[3])
d = r["distributed"]
assert d["ranks"] == ranks and len(d["per_rank"]) == ranks, d["ranks"]
for p in d["per_rank"]:
    assert p["phases"] and p["eye"]["rows"] >= 0, p
for m in r["maps"]:
    if m["map"] in ("volume", "photon beams"):
        continue
    shares = [ph for p in d["per_rank"] for ph in p["photons"] if ph["pass"] == m["map"]]
    assert len(shares) == ranks, (m["map"], shares)
    assert sum(s["emitted"] for s in shares) == m["emitted"] == emitted, (m["map"], shares)
assert sum(p["eye"]["rows"] for p in d["per_rank"]) == r["height"]
EOF
}

step "same image bytes for 1, 2 and 3 ranks as without MPI"
for scene in box fog beams mirage twilight; do
  out="$work/out-$scene"
  "$work/morgana-local" render "$work/$scene.toml" --out "$out/local" --photons 20000 --seed 7 --threads 2 --quiet >/dev/null
  ref="$(ls "$out/local"/*.exr)"
  runs=("singleton" "np1" "np2" "np3" "np2-static")
  for run in "${runs[@]}"; do
    args=(render "$work/$scene.toml" --out "$out/$run" --photons 20000 --seed 7 --threads 1 --quiet)
    case "$run" in
      singleton) "${LIMIT[@]}" "$work/morgana-mpi" "${args[@]}" >/dev/null; n=1 ;;
      np2-static) "${LIMIT[@]}" "${MPIRUN[@]}" -np 2 "$work/morgana-mpi" "${args[@]}" --schedule static >/dev/null; n=2 ;;
      np*) n="${run#np}"; "${LIMIT[@]}" "${MPIRUN[@]}" -np "$n" "$work/morgana-mpi" "${args[@]}" >/dev/null ;;
    esac
    got="$out/$run/$(basename "$ref")"
    cmp -s "$ref" "$got" || fail "$scene: $run EXR differs from the non-MPI build"
    check_report "$out/$run/report.json" "$n" 20000 || fail "$scene: $run report.json"
    ok "$scene: $run: EXR identical ($(stat -c %s "$got") bytes), report lists $n rank(s)"
  done
done
grep -q "volume photons are folded" "$work/out-twilight/np2/report.json" || fail "twilight: the plan does not fold the volume map"
ok "twilight: the volume map is folded about the sun's axis"

step "progressive passes: same bytes on 1, 2 and 3 ranks, and a resume on another rank count"
# Three passes (fresh maps, shrinking radii, the error layer) of the box (global and caustic maps,
# final gathering) and of the fog box (volume map); then a run stopped after two passes on 2
# ranks and resumed to three on 3 ranks must give the uninterrupted run's bytes.
for scene in box fog beams; do
for mode in uniform adaptive; do
  out="$work/prog-$scene-$mode"
  common=(render "$work/$scene.toml" --photons 10000 --seed 5 --quiet)
  # Adaptive sampling: rank 0 decides each pass's sample counts and sends them to the others.
  if [ "$mode" = adaptive ]; then common+=(--adaptive); fi
  "$work/morgana-local" "${common[@]}" --passes 3 --out "$out/local" --threads 2 >/dev/null
  ref="$(ls "$out/local"/*.exr)"
  for n in 1 2 3; do
    "${LIMIT[@]}" "${MPIRUN[@]}" -np "$n" "$work/morgana-mpi" "${common[@]}" --passes 3 --out "$out/np$n" \
      --threads 1 >/dev/null
    cmp -s "$ref" "$out/np$n/$(basename "$ref")" || fail "$scene ($mode): 3 passes on $n rank(s) differ from the non-MPI build"
  done
  python3 - "$out/np2/report.json" <<'PY' || fail "$scene ($mode): report.json of the 2-rank progressive run"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["progressive"]["passes"] == 3 and r["distributed"]["ranks"] == 2
assert r["progressive"]["history"][-1]["rel_error"] > 0
PY
  "${LIMIT[@]}" "${MPIRUN[@]}" -np 2 "$work/morgana-mpi" "${common[@]}" --passes 2 --out "$out/resumed" \
    --threads 1 >/dev/null
  "${LIMIT[@]}" "${MPIRUN[@]}" -np 3 "$work/morgana-mpi" "${common[@]}" --passes 3 --resume "$out/resumed" \
    --threads 1 >/dev/null
  cmp -s "$ref" "$out/resumed/$(basename "$ref")" || fail "$scene ($mode): 2 passes on 2 ranks resumed to 3 on 3 ranks differ"
  ok "$scene ($mode): 3 progressive passes identical on 1, 2 and 3 ranks and without MPI; 2 passes on 2 ranks resumed to 3 on 3 ranks identical"
done
done

step "the lease server answers while rank 0 renders"
# A worker waits one round trip per lease; a lease server that could not answer while rank 0
# renders would leave the worker waiting out the rest of the eye pass.
"${LIMIT[@]}" "${MPIRUN[@]}" -np 2 "$work/morgana-mpi" render "$work/slow.toml" --out "$work/share" --threads 1 \
  --quiet --photons 20000 >/dev/null
python3 - "$work/share/report.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))["distributed"]["per_rank"]
e = [p["eye"] for p in d]
print("rows, leases, compute s, wait s per rank:", [(x["rows"], x["leases"], round(x["compute_seconds"], 2), round(x["wait_seconds"], 3)) for x in e])
assert e[1]["leases"] >= 1 and e[1]["wait_seconds"] < 0.25 * e[1]["compute_seconds"], "the worker waited for leases"
EOF

step "errors end every rank with one message"
set +e
"${LIMIT[@]}" "${MPIRUN[@]}" -np 2 "$work/morgana-mpi" render "$work/missing.toml" --out "$work/err1" --quiet \
  >"$work/err1.log" 2>&1
rc=$?
set -e
[ "$rc" -ne 0 ] && [ "$rc" -ne 137 ] || fail "missing scene: mpirun exit code $rc"
[ "$(grep -c "cannot read scene file" "$work/err1.log")" -eq 1 ] || { cat "$work/err1.log"; fail "missing scene: not one message"; }
[ ! -e "$work/err1" ] || fail "missing scene: output written"
set +e
"${LIMIT[@]}" "${MPIRUN[@]}" -np 3 "$work/morgana-mpi" render "$work/box.toml" --out "$work/err2" --quiet \
  --photons 20000 --max-map-memory 64k >"$work/err2.log" 2>&1
rc=$?
set -e
[ "$rc" -ne 0 ] && [ "$rc" -ne 137 ] || fail "map memory: mpirun exit code $rc"
[ "$(grep -c -- "--max-map-memory" "$work/err2.log")" -eq 1 ] || { cat "$work/err2.log"; fail "map memory: not one message"; }
[ ! -e "$work/err2" ] || [ -z "$(ls -A "$work/err2")" ] || fail "map memory: output written"
ok "missing scene and --max-map-memory 64k: exit codes nonzero, one message each, no output"

# mismatch NAME EXPECTED PREFIX... -- EXTRA...: rank 0 renders the mirage as given, rank 1 through
# the PREFIX command and with the EXTRA arguments; the run must stop with one message naming
# rank 1 and EXPECTED, and no output.
mismatch() {
  local name="$1" expected="$2" out="$work/mismatch-$1" log="$work/mismatch-$1.log"
  shift 2
  local prefix=()
  while [ "$1" != "--" ]; do prefix+=("$1"); shift; done
  shift
  local args=(render "$work/mirage.toml" --out "$out" --quiet --photons 20000 --threads 1)
  set +e
  "${LIMIT[@]}" "${MPIRUN[@]}" -np 1 "$work/morgana-mpi" "${args[@]}" : \
    -np 1 "${prefix[@]}" "$work/morgana-mpi" "${args[@]}" "$@" >"$log" 2>&1
  local rc=$?
  set -e
  [ "$rc" -ne 0 ] && [ "$rc" -ne 137 ] || { cat "$log"; fail "mismatch $name: mpirun exit code $rc"; }
  [ "$(grep -c "do not see the same scene" "$log")" -eq 1 ] || { cat "$log"; fail "mismatch $name: not one message"; }
  grep -q "rank 1 .*$expected" "$log" || { cat "$log"; fail "mismatch $name: the message does not name rank 1 and $expected"; }
  [ ! -e "$out" ] || [ -z "$(ls -A "$out")" ] || fail "mismatch $name: output written"
  ok "mismatch $name: exit $rc, no output: $(grep -o "rank 1 .*" "$log" | head -n 1)"
}
mismatch command-line "the morgana version or the command line" env -- --seed 8
# A stale copy of the atmosphere file on "one node": rank 1 sees another file at the same path.
sed 's/^dT_k = 30.0/dT_k = 29.0/' atmospheres/hot_road.toml >"$work/hot_road_stale.toml"
if unshare -m true 2>/dev/null; then
  printf '#!/bin/sh\nmount --bind "%s" "%s" && exec "$@"\n' "$work/hot_road_stale.toml" \
    "$PWD/atmospheres/hot_road.toml" >"$work/stale.sh"
  chmod +x "$work/stale.sh"
  mismatch stale-file "hot_road.toml" unshare -m "$work/stale.sh" --
else
  echo "mismatch stale-file: skipped (unshare -m is not permitted here)"
fi

step "a killed rank fails the job and leaves no output"
descendants() { local c; for c in $(pgrep -P "$1" || true); do echo "$c"; descendants "$c"; done; }
# kill_during MARKER PHOTONS NAME: start 3 ranks, wait for rank 0's MARKER line, SIGKILL rank 1.
kill_during() {
  local marker="$1" photons="$2" out="$work/kill-$3" log="$work/kill-$3.log"
  "${LIMIT[@]}" "${MPIRUN[@]}" -np 3 "$work/morgana-mpi" render "$work/slow.toml" --out "$out" --threads 1 \
    --photons "$photons" >"$log" 2>&1 &
  local job=$! victim="" c
  for _ in $(seq 1 600); do
    grep -q "$marker" "$log" && break
    sleep 0.1
  done
  grep -q "$marker" "$log" || { cat "$log"; fail "kill: no '$marker' line"; }
  for c in $(descendants "$job"); do
    if tr '\0' '\n' <"/proc/$c/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1"; then victim="$c"; fi
  done
  [ -n "$victim" ] || fail "kill: rank 1 not found"
  kill -KILL "$victim"
  local rc=0
  wait "$job" || rc=$?
  [ "$rc" -ne 0 ] || fail "kill during '$marker': mpirun succeeded"
  ! grep -q "^wrote" "$log" || fail "kill during '$marker': outputs reported written"
  [ ! -e "$out" ] || [ -z "$(ls -A "$out")" ] || { ls -A "$out"; fail "kill during '$marker': files left in $out"; }
  grep -q "exited on signal 9" "$log" || { cat "$log"; fail "kill: mpirun did not name the killed rank"; }
  ok "killed rank 1 (pid $victim) during '$marker': mpirun exit $rc, no output; mpirun: $(grep -o "process rank 1 .*" "$log" | head -n 1)"
}
kill_during "global photons" 3000000 photon
kill_during "eye pass" 20000 eye

step "all MPI checks passed"
echo "mpi: $passed passed, 0 failed"
