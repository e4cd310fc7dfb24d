#!/usr/bin/env bash
# Creates (or updates) .venv-data at the repository root with the pinned pvlib environment used by
# scripts/gen_solar_spectrum.py. Idempotent: a venv whose installed set already matches
# scripts/requirements-data.txt is left alone. (scripts/setup_venv.sh makes the colour-science
# .venv; the two are kept apart so neither pins the other's numpy.)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv-data"
req="$root/scripts/requirements-data.txt"
python="${PYTHON:-python3.11}"
command -v "$python" >/dev/null 2>&1 || python=python3

if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
stamp="$venv/.requirements-data.sha256"
want="$(sha256sum "$req" | cut -d' ' -f1)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    echo "setup_venv_data: $venv is up to date"
    exit 0
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet -r "$req"
"$venv/bin/python" -c "import pvlib; print('setup_venv_data: pvlib', pvlib.__version__)"
echo "$want" > "$stamp"
