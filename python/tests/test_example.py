"""examples/python/small_study.py runs (quick mode) where matplotlib is installed."""

import os
import runpy


def test_small_study_example(repo, tmp_path, monkeypatch):
    import pytest

    pytest.importorskip("matplotlib")
    monkeypatch.setenv("FUZZYMOTIV_QUICK", "1")
    monkeypatch.chdir(tmp_path)
    ns = runpy.run_path(str(repo / "examples/python/small_study.py"))
    ns["main"](tmp_path / "study.png")
    assert (tmp_path / "study.png").stat().st_size > 10_000
    assert os.environ["FUZZYMOTIV_QUICK"] == "1"
