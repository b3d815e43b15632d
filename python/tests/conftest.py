"""Shared fixtures: the repository root and the `fuzzymotiv` binary the API is checked against."""

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def cli() -> Path:
    """The CLI binary: $FUZZYMOTIV_BIN, else target/release or target/debug of the repository."""
    candidates = [os.environ.get("FUZZYMOTIV_BIN")] if os.environ.get("FUZZYMOTIV_BIN") else []
    candidates += [REPO / "target" / "release" / "fuzzymotiv", REPO / "target" / "debug" / "fuzzymotiv"]
    for c in candidates:
        if c and Path(c).is_file():
            return Path(c)
    pytest.fail(
        "the fuzzymotiv binary was not found: build it (cargo build -p fuzzymotiv-cli) "
        "or set FUZZYMOTIV_BIN"
    )


def run_cli(cli: Path, *args, check=True) -> subprocess.CompletedProcess:
    p = subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, cwd=REPO)
    if check and p.returncode != 0:
        raise AssertionError(f"fuzzymotiv {args} failed ({p.returncode}): {p.stderr}")
    return p
