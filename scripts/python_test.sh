#!/usr/bin/env bash
# Builds the Python package (python/: PyO3 over this library, an abi3 wheel for CPython >= 3.9)
# with the pinned maturin of scripts/requirements-python.txt, installs it into .venv, checks that
# the book's API page (scripts/gen_python_api.py) matches the installed docstrings, and runs the
# pytest suite (python/tests/), which compares with target/release/morgana (built first). The
# native module shares this workspace's target directory, so the library is not built twice;
# ./scripts/test lints it with the workspace's clippy. Extra arguments go to pytest (-k gil).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
./scripts/setup_venv.sh
py="$root/.venv/bin/python"
export PYO3_PYTHON="$py"
cargo build --release --quiet --workspace --bin morgana
rm -rf target/wheels
(cd python && "$root/.venv/bin/maturin" build --release --quiet --interpreter "$py" --out "$root/target/wheels")
"$py" -m pip install --quiet --force-reinstall --no-deps target/wheels/morgana-*.whl
# The book's API page is generated from the installed package's docstrings: it must be current.
(cd target && "$py" "$root/scripts/gen_python_api.py" --check)
# From target/: the source folder python/morgana (without its native module) must not shadow
# the installed package.
(cd target && MORGANA_BIN="$root/target/release/morgana" "$py" -m pytest -q -p no:cacheprovider "$root/python/tests" "$@")
