#!/usr/bin/env bash
# Creates (or updates) .venv at the repository root with the pinned colour-science environment
# used by scripts/colour_check.py. Idempotent: a venv whose installed set already matches
# scripts/requirements-colour.txt is left alone.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
req="$root/scripts/requirements-colour.txt"
python="${PYTHON:-python3.11}"
command -v "$python" >/dev/null 2>&1 || python=python3

if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
stamp="$venv/.requirements-colour.sha256"
want="$(sha256sum "$req" | cut -d' ' -f1)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    echo "setup_venv: $venv is up to date"
    exit 0
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet -r "$req"
"$venv/bin/python" -c "import colour, OpenImageIO, OpenEXR; print('setup_venv: colour', colour.__version__, '| OpenImageIO', OpenImageIO.VERSION_STRING)"
echo "$want" > "$stamp"
