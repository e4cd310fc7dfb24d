#!/usr/bin/env bash
# Installs what `cargo build --features mpi` needs on Debian 12 (bookworm): OpenMPI (library,
# headers, mpirun) and libclang for rsmpi's bindgen. Idempotent: packages already at the pinned
# version are left alone. Versions are pinned to bookworm's when apt offers them (otherwise
# the candidate is installed and its version printed, so a drift is visible in the log).
set -euo pipefail

# Debian bookworm versions (checked with `apt-cache policy` on 2025 bookworm images).
declare -A PIN=(
  [libopenmpi-dev]="4.1.4-3+b1"
  [openmpi-bin]="4.1.4-3+b1"
  [libclang-dev]="1:14.0-55.7~deb12u1"
)

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  SUDO="sudo"
fi

installed_version() { dpkg-query -W -f='${Status} ${Version}\n' "$1" 2>/dev/null | awk '$3 == "installed" { print $4 }'; }

missing=()
for pkg in "${!PIN[@]}"; do
  if [ "$(installed_version "$pkg")" = "" ]; then
    missing+=("$pkg")
  fi
done

if [ "${#missing[@]}" -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  args=()
  for pkg in "${missing[@]}"; do
    if apt-cache madison "$pkg" | awk -F'|' '{ gsub(/ /, "", $2); print $2 }' | grep -qxF "${PIN[$pkg]}"; then
      args+=("$pkg=${PIN[$pkg]}")
    else
      echo "setup_mpi.sh: $pkg ${PIN[$pkg]} is not offered by apt; installing the candidate" >&2
      args+=("$pkg")
    fi
  done
  $SUDO apt-get install -y -qq --no-install-recommends "${args[@]}"
fi

for pkg in libopenmpi-dev openmpi-bin libclang-dev; do
  v="$(installed_version "$pkg")"
  if [ -z "$v" ]; then
    echo "setup_mpi.sh: $pkg is not installed" >&2
    exit 1
  fi
  note=""
  [ "$v" = "${PIN[$pkg]}" ] || note=" (pinned ${PIN[$pkg]})"
  echo "setup_mpi.sh: $pkg $v$note"
done
mpirun --version | head -n 1
