"""The documents' Python code works as written (run from the repository root): the README's
first look, and the guide's session (docs/guide/python.md, as a doctest) and optimiser loops
(docs/guide/optimisers.md). The guide's frames and Gymnasium code are run by test_frames.py and
test_gym.py."""

import doctest
import re
import sys

import pytest


def test_readme_first_look_runs(repo, doc_blocks, monkeypatch, capsys):
    """The README's five-line Python example runs as written and prints F and the run."""
    (code,) = doc_blocks("README.md")
    assert len(code.strip().splitlines()) <= 5
    monkeypatch.chdir(repo)
    exec(compile(code, "README.md (Python)", "exec"), {})
    out = capsys.readouterr().out
    assert re.match(r"0\.79721969\d*\n<RunResult 'tiny' seed 7 .*> 0\.92", out), out


@pytest.mark.parametrize("pandas", [True, False], ids=["with-pandas", "numpy-only"])
def test_guide_python_session_runs_with_or_without_pandas(
    repo, doc_blocks, tmp_path, monkeypatch, pandas
):
    """The wheel needs only numpy, so the guide's opening session runs with numpy alone (pandas
    hidden from imports) as well as with pandas."""
    if pandas:
        pytest.importorskip("pandas")
    else:
        monkeypatch.setitem(sys.modules, "pandas", None)  # `import pandas` raises ImportError
    session = doc_blocks("docs/guide/python.md", "# Python")[0]
    session = session.replace('"hc.fll"', repr(str(tmp_path / "hc.fll")))
    monkeypatch.chdir(repo)
    test = doctest.DocTestParser().get_doctest(session, {}, "python.md", "docs/guide/python.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 8
    assert (tmp_path / "hc.fll").is_file()


def test_guide_own_optimiser(repo, doc_blocks, monkeypatch, capsys):
    """The guide's (1+λ) random search (the first block of optimisers.md) runs as written and
    improves F."""
    code = doc_blocks("docs/guide/optimisers.md")[0]
    monkeypatch.chdir(repo)
    exec(compile(code, "docs/guide/optimisers.md (random search)", "exec"), {})
    assert re.fullmatch(r"F \d\.\d{3} -> \d\.\d{3}\n", capsys.readouterr().out)


def test_guide_cma_loop(repo, doc_blocks, monkeypatch, capsys):
    """The guide's CMA-ES loop (ten lines) runs as written (where `cma` is installed)."""
    pytest.importorskip("cma")
    (code,) = doc_blocks("docs/guide/optimisers.md", "## CMA-ES")
    assert "import cma" in code and len(code.strip().splitlines()) <= 10
    monkeypatch.chdir(repo)
    exec(compile(code, "docs/guide/optimisers.md (CMA-ES)", "exec"), {})
    out = capsys.readouterr().out
    assert re.fullmatch(r"CMA-ES best F \d\.\d{3}\n", out), out
