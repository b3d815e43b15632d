"""Shared fixtures: the repository root, the `fuzzymotiv` binary the API is checked against, and
the Python blocks of the documents (README.md, docs/guide/)."""

from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path
from typing import Callable

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


def python_blocks(text: str, heading: str | None = None) -> list[str]:
    """The ```python blocks of a Markdown text, or of its section under `heading` (a whole
    heading line, e.g. "## CMA-ES"), which ends at the next heading of its level or above
    (lines inside code blocks are not headings)."""
    lines = text.splitlines(keepends=True)
    if heading is not None:
        level = len(heading.split(" ", 1)[0])
        start = next((i for i, line in enumerate(lines) if line.rstrip("\n") == heading), None)
        assert start is not None, f"no heading {heading!r} in the document"
        section, fenced = [], False
        for line in lines[start + 1 :]:
            if line.startswith("```"):
                fenced = not fenced
            match = None if fenced else re.match(r"(#+) ", line)
            if match and len(match.group(1)) <= level:
                break
            section.append(line)
        lines = section
    return re.findall(r"^```python\n(.*?)^```", "".join(lines), re.S | re.M)


@pytest.fixture(scope="session")
def doc_blocks() -> Callable[..., list[str]]:
    """`doc_blocks("docs/guide/python.md", "## Frames and GIFs")`: that section's Python blocks
    (the whole document's without a heading); fails if there are none."""

    def blocks(path: str, heading: str | None = None) -> list[str]:
        found = python_blocks((REPO / path).read_text(encoding="utf-8"), heading)
        assert found, f"no ```python block in {path} {heading or ''}"
        return found

    return blocks
