#!/usr/bin/env bash
# Creates (or updates) .venv at the repository root with the pinned environments of
# scripts/requirements-colour.txt (colour-science, used by scripts/colour_check.py) and
# scripts/requirements-python.txt (maturin, pytest, tqdm, matplotlib: the Python package's build,
# tests and examples; scripts/python_test.sh). Idempotent: a venv whose installed set already
# matches both files is left alone.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
reqs=("$root/scripts/requirements-colour.txt" "$root/scripts/requirements-python.txt")
python="${PYTHON:-python3.11}"
command -v "$python" >/dev/null 2>&1 || python=python3

if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
stamp="$venv/.requirements-colour.sha256"
want="$(cat "${reqs[@]}" | sha256sum | cut -d' ' -f1)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    echo "setup_venv: $venv is up to date"
    exit 0
fi
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet -r "${reqs[0]}" -r "${reqs[1]}"
"$venv/bin/python" -c "import colour, OpenImageIO, OpenEXR; print('setup_venv: colour', colour.__version__, '| OpenImageIO', OpenImageIO.VERSION_STRING)"
"$venv/bin/python" -c "import pytest, tqdm, matplotlib; print('setup_venv: pytest', pytest.__version__, '| tqdm', tqdm.__version__, '| matplotlib', matplotlib.__version__)"
"$venv/bin/maturin" --version
echo "$want" > "$stamp"
