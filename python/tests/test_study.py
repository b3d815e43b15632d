"""Studies of one's own from Python (fm.study) against `fuzzymotiv study`, byte for byte: a
study of a new kind (the fetch mission on an e-puck2, three arms, two hypotheses over the
mission's term urgency) from a file and from a dict; Ctrl-C stops it and the same call resumes
it; shards; bad study files raise ConfigError naming the file and the field, with nothing
written. fm.study takes no terms= (docs/guide/studies.md): a Python term cannot be an arm's."""

import _thread
import signal
import warnings
from pathlib import Path

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import REPO, run_cli

# The records of the analysis; report.md quotes the study document as given (a file's text, or
# the TOML a dict is written as), so it is compared only between a file and the command line.
RECORDS = ["per_seed.csv", "claims.csv", "rooms.csv", "arms.csv", "study.json", "forest.svg"]


def study_dict(config=str(REPO / "configs" / "fetch.toml")):
    """The fetch mission on an e-puck2 at a tiny size: three arms of urgency's weight (taken
    from curiosity), two hypotheses on the mission's term, urgency (its time): the highest against
    the lowest, and the trend over the three."""
    return {
        "study": {
            "name": "epuck2-fetch",
            "seeds": 3,
            "config": config,
            "set": {
                "robot": "epuck2",
                "ga": {"population": 6, "generations": 3},
                "trial": {"steps": 80},
                "aem": {"enabled": False},
            },
        },
        "analysis": {"alpha": 0.05, "rule": "power", "holm": "hypotheses"},
        "arm": [
            {"name": "urgency-0.1", "level": 0.1, "set": {"motivations.curiosity": 0.7, "motivations.urgency": 0.1}},
            {"name": "urgency-0.3", "level": 0.3},
            {"name": "urgency-0.5", "level": 0.5, "set": {"motivations.curiosity": 0.3, "motivations.urgency": 0.5}},
        ],
        "hypothesis": [
            {"id": "sooner", "kind": "compare", "measure": "urgency", "a": "urgency-0.5", "b": "urgency-0.1", "expect": "higher"},
            {
                "id": "urgency-trend",
                "kind": "trend",
                "measure": "urgency",
                "arms": ["urgency-0.1", "urgency-0.3", "urgency-0.5"],
                "expect": "increasing",
            },
        ],
    }


STUDY_TOML = """\
[study]
name = "epuck2-fetch"
seeds = 3
config = "{config}"
set = {{ robot = "epuck2", ga = {{ population = 6, generations = 3 }}, trial = {{ steps = 80 }}, aem = {{ enabled = false }} }}

[analysis]
alpha = 0.05
rule = "power"
holm = "hypotheses"

[[arm]]
name = "urgency-0.1"
level = 0.1
set = {{ "motivations.curiosity" = 0.7, "motivations.urgency" = 0.1 }}

[[arm]]
name = "urgency-0.3"
level = 0.3

[[arm]]
name = "urgency-0.5"
level = 0.5
set = {{ "motivations.curiosity" = 0.3, "motivations.urgency" = 0.5 }}

[[hypothesis]]
id = "sooner"
kind = "compare"
measure = "urgency"
a = "urgency-0.5"
b = "urgency-0.1"
expect = "higher"

[[hypothesis]]
id = "urgency-trend"
kind = "trend"
measure = "urgency"
arms = ["urgency-0.1", "urgency-0.3", "urgency-0.5"]
expect = "increasing"
"""


@pytest.fixture(scope="module")
def by_cli(cli, tmp_path_factory):
    """The study file, and the directory `fuzzymotiv study` wrote for it."""
    tmp = tmp_path_factory.mktemp("study")
    path = tmp / "epuck2-fetch.toml"
    path.write_text(STUDY_TOML.format(config=REPO / "configs" / "fetch.toml"), encoding="utf-8")
    out = tmp / "cli"
    run_cli(cli, "study", path, "--out", out, "--threads", "2", "-q")
    return path, out


def same_bytes(a: Path, b: Path, files):
    for name in files:
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


def test_a_study_runs_from_python_with_the_command_lines_records(by_cli, tmp_path):
    path, cli_out = by_cli
    seen = []
    res = fm.study(path, out=tmp_path / "file", threads=2, progress=lambda done, total: seen.append((done, total)))
    same_bytes(res.out, cli_out, RECORDS + ["report.md"])
    assert res.analysed and (res.done, res.total) == (9, 9)
    assert seen[-1] == (9, 9) and seen == sorted(seen)
    assert list(res.claims["id"]) == ["sooner", "urgency-trend"]
    for column in ["effect", "ci_low", "ci_high", "p", "p_adjusted", "mdd"]:
        assert res.claims[column].dtype == np.float64, column
    assert set(res.claims["verdict"]) <= {"supported", "contradicted", "not significant", "inconclusive"}
    assert res.per_seed.rows > 0 and set(res.per_seed["arm"]) == {"urgency-0.1", "urgency-0.3", "urgency-0.5"}
    assert res.report == res.out / "report.md" and res.forest.read_text().startswith("<svg")
    # Each arm's measures; one base seed: no agreement to report.
    assert set(res.arms["arm"]) == set(res.per_seed["arm"]) and set(res.arms["scope"]) == {"pooled"}
    assert res.agreement is not None and res.agreement.rows == 0
    # A dict of the same document: the same records.
    from_dict = fm.study(study_dict(), out=tmp_path / "dict", threads=1)
    same_bytes(from_dict.out, cli_out, RECORDS)
    # Again: every run is there, nothing runs, the same tables.
    again = fm.study(path, out=tmp_path / "file")
    assert list(again.claims["p"]) == list(res.claims["p"])


def test_ctrl_c_stops_a_study_and_the_same_call_resumes_it(by_cli, tmp_path):
    _, cli_out = by_cli
    out = tmp_path / "interrupted"
    seen = []

    def progress(done, total):
        seen.append(done)
        if done >= 1:
            _thread.interrupt_main()  # what Ctrl-C does

    # A process started in the background inherits SIGINT ignored: give it Python's handler.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            fm.study(study_dict("configs/fetch.toml"), out=out, base_dir=REPO, threads=1, progress=progress)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert max(seen) < 9 and not (out / "claims.csv").exists()
    res = fm.study(study_dict("configs/fetch.toml"), out=out, base_dir=REPO, threads=1)
    assert res.analysed and res.done == 9
    # study.json names the config as the study does (here relative to base_dir).
    same_bytes(out, cli_out, [f for f in RECORDS if f != "study.json"])


def test_a_study_in_shards_is_analysed_by_the_call_that_finishes_it(by_cli, tmp_path):
    path, cli_out = by_cli
    out = tmp_path / "shards"
    first = fm.study(path, out=out, shard=(0, 2), threads=1)
    assert not first.analysed and first.claims is None and first.report is None
    assert (first.done, first.total) == (5, 9)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        last = fm.study(path, out=out, shard="1/2", threads=1)
    # How many jobs ran is returned (done, total), not warned.
    assert [str(w.message) for w in caught] == []
    assert last.analysed and (last.done, last.total) == (9, 9)
    same_bytes(out, cli_out, RECORDS + ["report.md"])
    with pytest.raises(fm.FuzzymotivError, match="--shard 2/2"):
        fm.study(path, out=out, shard=(2, 2))


def test_bad_studies_raise_config_error_naming_the_file_and_field_and_write_nothing(by_cli, tmp_path):
    path, _ = by_cli
    out = tmp_path / "never"
    bad = study_dict()
    bad["hypothesis"][0]["measure"] = "no_such_measure"
    with pytest.raises(fm.ConfigError, match=r"\(study dict\): field `hypothesis\[0\]\.measure`"):
        fm.study(bad, out=out)
    text = path.read_text(encoding="utf-8").replace("seeds = 3", "seeds = 0")
    bad_file = tmp_path / "bad.toml"
    bad_file.write_text(text, encoding="utf-8")
    with pytest.raises(fm.ConfigError, match=f"{bad_file}: field `study.seeds`"):
        fm.study(bad_file, out=out)
    with pytest.raises(fm.ConfigError, match="study.seeds"):
        fm.study(study_text=text, out=out, base_dir=REPO)
    with pytest.raises(fm.FuzzymotivError, match="study: expected"):
        fm.study(out=out)
    assert not out.exists()


def test_guide_studies_section_runs_as_written(doc_blocks, tmp_path, monkeypatch, capsys):
    """The guide's "Studies" code (docs/guide/python.md) runs as written, from a folder with
    the repository's configs and rooms."""
    (code,) = doc_blocks("docs/guide/python.md", "## Studies")
    for folder in ["configs", "rooms"]:
        (tmp_path / folder).symlink_to(REPO / folder)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "docs/guide/python.md (Studies)", "exec"), {})
    printed = capsys.readouterr().out
    assert "6/6 runs" in printed
    assert (tmp_path / "out" / "curiosity" / "claims.csv").is_file()
