"""The README's Python session works as written (run as a doctest from the repository root)."""

import doctest
import re
import sys

import pytest


@pytest.mark.parametrize("pandas", [True, False], ids=["with-pandas", "numpy-only"])
def test_readme_python_session_runs_with_or_without_pandas(repo, tmp_path, monkeypatch, pandas):
    """The wheel needs only numpy, so the README's first session runs with numpy alone (pandas
    hidden from imports) as well as with pandas."""
    if pandas:
        pytest.importorskip("pandas")
    else:
        monkeypatch.setitem(sys.modules, "pandas", None)  # `import pandas` raises ImportError
    text = (repo / "README.md").read_text()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    session = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    session = session.replace('"hc.fll"', repr(str(tmp_path / "hc.fll")))
    monkeypatch.chdir(repo)
    test = doctest.DocTestParser().get_doctest(session, {}, "README", "README.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 8
    assert (tmp_path / "hc.fll").is_file()


def test_readme_own_optimiser(repo, monkeypatch, capsys):
    """The README's "Use your own optimiser" loop runs as written and improves F."""
    text = (repo / "README.md").read_text()
    section = text.split("\n### Use your own optimiser\n", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(repo)
    exec(compile(code, "README.md (Use your own optimiser)", "exec"), {})
    assert re.fullmatch(r"F \d\.\d{3} -> \d\.\d{3}\n", capsys.readouterr().out)


def test_readme_cma_loop(repo, monkeypatch, capsys):
    """The README's CMA-ES loop (ten lines) runs as written (where `cma` is installed)."""
    pytest.importorskip("cma")
    text = (repo / "README.md").read_text()
    section = text.split("\n### Use your own optimiser\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    code = next(b for b in blocks if "import cma" in b)
    assert len(code.strip().splitlines()) <= 10
    monkeypatch.chdir(repo)
    exec(compile(code, "README.md (CMA-ES)", "exec"), {})
    out = capsys.readouterr().out
    assert re.fullmatch(r"CMA-ES best F \d\.\d{3}\n", out), out
