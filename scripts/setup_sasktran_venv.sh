#!/usr/bin/env bash
# Creates .venv-sasktran with the pinned SASKTRAN2 peer (scripts/requirements-sasktran.txt) for
# scripts/sasktran_twilight.py. A venv of its own: SASKTRAN2's numpy, scipy and pandas need not
# agree with the colour-science pins of .venv. Idempotent. Only that script needs it;
# ./scripts/test does not.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv-sasktran"
req="$root/scripts/requirements-sasktran.txt"

stamp="$venv/.requirements.sha256"
want="$(sha256sum "$req" | cut -d' ' -f1)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    echo "setup_sasktran_venv: $venv has SASKTRAN2"
    exit 0
fi
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet -r "$req"
"$venv/bin/python" -c "import importlib.metadata as m; print('setup_sasktran_venv: sasktran2', m.version('sasktran2'))"
echo "$want" > "$stamp"
