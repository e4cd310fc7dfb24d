#!/usr/bin/env bash
# Measurements for README "Distributed rendering (MPI)": 1 rank vs 2 ranks (one thread each) on
# this machine, per phase, for a photon-pass-heavy, an eye-pass-heavy and a curved-path scene; the static
# against the dynamic eye-pass schedule; then the cluster model (scripts/mpi_model.py) from the
# measured phase times and message sizes.
#
#   scripts/bench_mpi.sh [REPS]        (default 3 repetitions; the median of each phase is used)
#
# Results go to target/bench_mpi/ (one directory per run with its report.json, runs.csv, and
# the tables printed at the end, also in tables.md). Other processes on the machine distort wall
# times: the load average is recorded before every run (rerun when `uptime` shows < 0.5), and
# each phase's CPU time (report.json `cpu_seconds`) and each run's CPU time (/usr/bin/time) are
# recorded too; the model starts from the 1-rank runs' CPU times, which a loaded machine does not
# inflate.
# Needs OpenMPI (scripts/setup_mpi.sh) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
reps="${1:-3}"

MPIRUN=(mpirun --oversubscribe --bind-to none --mca mpi_yield_when_idle 1)
[ "$(id -u)" -eq 0 ] && MPIRUN+=(--allow-run-as-root)
out=target/bench_mpi
rm -rf "$out"
mkdir -p "$out"

cargo build --release --quiet --features mpi --bin morgana
bin="$out/morgana-mpi"
cp target/release/morgana "$bin"

scene() { # name width height spp gather_rays
  sed -e "s/^width = .*/width = $2/" -e "s/^height = .*/height = $3/" -e "s/^spp = .*/spp = $4/" \
      -e "s/^gather_rays = .*/gather_rays = $5/" -e "s/^name = \"default\"/name = \"$1\"/" \
      src/scene/default.toml >"$out/$1.toml"
}
# photons: 2M global + 2M caustic photons, final gathering, a small image.
scene photons 64 64 1 4
# eye: 200k + 200k photons, 192×192 pixels, 8 samples, 16 final-gather rays.
scene eye 192 192 8 16
# curved: the hot-road mirage (examples/mirage_hot_road.toml, Lucifer's Fig. 4 scene) at 64×32
# pixels, 1 sample, 100k photons: every photon and eye ray integrates a curved path.
sed -e "s/^width = .*/width = 64/" -e "s/^height = .*/height = 32/" -e "s/^spp = .*/spp = 1/" \
    -e "s#\.\./atmospheres/#$PWD/atmospheres/#" -e 's/^name = "mirage_hot_road"/name = "curved"/' \
    examples/mirage_hot_road.toml >"$out/curved.toml"
declare -A PHOTONS=([photons]=2000000 [eye]=200000 [curved]=100000)

echo "scene,config,rep,ranks,threads,load1,total_seconds,cpu_seconds" >"$out/runs.csv"
run() { # scene config rep ranks threads [extra args]
  local s="$1" c="$2" r="$3" np="$4" th="$5"
  shift 5
  local dir="$out/$s-$c-$r" load
  load="$(cut -d' ' -f1 /proc/loadavg)"
  local t0 t1
  t0="$(date +%s.%N)"
  # CPU seconds (user + system) of mpirun and all ranks: the work done, whatever else runs.
  /usr/bin/time -f "%U %S" -o "$out/time.txt" "${MPIRUN[@]}" -np "$np" "$bin" render "$out/$s.toml" --out "$dir" --threads "$th" --quiet \
    --photons "${PHOTONS[$s]}" --seed 3 "$@" >/dev/null
  t1="$(date +%s.%N)"
  local wall cpu
  wall="$(awk "BEGIN { print $t1 - $t0 }")"
  cpu="$(awk '{ print $1 + $2 }' "$out/time.txt")"
  echo "$s,$c,$r,$np,$th,$load,$wall,$cpu" >>"$out/runs.csv"
  printf '%-8s %-12s rep %s: %6.2f s wall, %6.2f s CPU (load %s)\n' "$s" "$c" "$r" "$wall" "$cpu" "$load"
}

for r in $(seq 1 "$reps"); do
  for s in photons eye curved; do
    run "$s" np1 "$r" 1 1
    run "$s" np2 "$r" 2 1
    run "$s" np2-static "$r" 2 1 --schedule static
  done
done

python3 scripts/mpi_model.py "$out" | tee "$out/tables.md"
