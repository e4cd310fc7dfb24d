#!/usr/bin/env bash
# Adds the pinned Mitsuba 3 peer (scripts/requirements-peer.txt) to the project's .venv, which
# scripts/setup_venv.sh creates with the colour-science environment (numpy, OpenEXR,
# OpenImageIO) that scripts/peer_mitsuba.py also uses. Idempotent, like setup_venv.sh. Only the
# benchmark needs this; ./scripts/test does not.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
req="$root/scripts/requirements-peer.txt"

"$root/scripts/setup_venv.sh"
stamp="$venv/.requirements-peer.sha256"
want="$(sha256sum "$req" | cut -d' ' -f1)"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    echo "setup_peer_venv: $venv has the Mitsuba peer"
    exit 0
fi
"$venv/bin/python" -m pip install --quiet -r "$req"
"$venv/bin/python" -c "import mitsuba, drjit; mitsuba.set_variant('scalar_spectral'); print('setup_peer_venv: mitsuba', mitsuba.__version__, '| drjit', drjit.__version__)"
echo "$want" > "$stamp"
