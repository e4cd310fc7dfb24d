"""Shared helpers: the repository root, the CLI binary, and a runner for it."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def cli_path() -> Path:
    """The morgana binary the tests compare with (MORGANA_BIN, else target/release/morgana)."""
    return Path(os.environ.get("MORGANA_BIN", ROOT / "target" / "release" / "morgana"))


@pytest.fixture(scope="session")
def cli():
    """Runs `morgana ARGS...`; returns its stdout (fails the test on a non-zero exit)."""
    binary = cli_path()
    if not binary.exists():
        pytest.fail(f"{binary} is missing: build it with `cargo build --release --bin morgana`")

    def run(*args: str) -> str:
        done = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, f"morgana {' '.join(map(str, args))}: {done.stderr}"
        return done.stdout

    return run
