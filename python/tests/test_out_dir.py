"""fm.run(..., out=DIR) follows `fuzzymotiv run --out`'s rules: a finished run of the
same config is read back, an unfinished one resumed (after a failing callback or a kill -9),
another run's results are kept unless force=True, a foreign directory is never replaced."""

import json
import os
import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import run_cli

SMALL = {"ga.generations": 4, "ga.population": 10, "trial.steps": 80}
OTHER = {"ga.generations": 3, "ga.population": 10, "trial.steps": 80}


def sets(overrides):
    out = []
    for k, v in overrides.items():
        out += ["--set", f"{k}={v}"]
    return out


def files(d):
    """Every file under d (relative path → bytes), wall times taken out: summary.json's
    `wall_seconds`, the report's "wall time … s" (twice) and any embedded `wall_seconds`."""
    out = {}
    for p in sorted(d.rglob("*")):
        if not p.is_file():
            continue
        rel = str(p.relative_to(d))
        data = p.read_bytes()
        if rel == "summary.json":
            doc = json.loads(data)
            del doc["wall_seconds"]
            data = json.dumps(doc, sort_keys=True).encode()
        elif rel == "report.html":
            data = re.sub(rb"([Ww]all time(?: of this run:)?) [0-9.]+ s", rb"\1 - s", data)
            data = re.sub(rb'"wall_seconds": ?[0-9.eE+-]+', b'"wall_seconds":-', data)
        out[rel] = data
    return out


def stamps(d):
    return {str(p.relative_to(d)): (p.stat().st_mtime_ns, p.read_bytes()) for p in d.rglob("*") if p.is_file()}


def same_result(a, b, wall_time=True):
    """Two RunResults hold equal values (NaN equal to NaN); the summary's wall time too unless
    `wall_time` is False (a resumed run's is the sum of its sessions')."""
    for table in ("generations", "rooms"):
        ta, tb = getattr(a, table), getattr(b, table)
        assert list(ta) == list(tb)
        for k in ta:
            np.testing.assert_array_equal(ta[k], tb[k])  # NaN equal to NaN
    assert list(a.best_genomes) == list(b.best_genomes)
    for k in a.best_genomes:
        assert a.best_genomes[k].tolist() == b.best_genomes[k].tolist()
    assert a.best_genome.tolist() == b.best_genome.tolist()
    assert list(a.trajectories) == list(b.trajectories)
    for room, t in a.trajectories.items():
        for c in ("x", "y", "heading"):
            assert t[c].tolist() == b.trajectories[room][c].tolist(), (room, c)
    if wall_time:
        assert a.summary == b.summary
    else:
        assert dict(a.summary, wall_seconds=None) == dict(b.summary, wall_seconds=None)
    assert a.hidden == b.hidden


@pytest.fixture(scope="module")
def tiny(repo):
    return repo / "configs/tiny.toml"


@pytest.fixture(scope="module")
def uninterrupted(tiny, tmp_path_factory):
    out = tmp_path_factory.mktemp("whole") / "run"
    return fm.run(tiny, SMALL, out=out, threads=2), out


def test_finished_run_is_read_back_not_run_again(tiny, uninterrupted):
    first, out = uninterrupted
    before = stamps(out)
    calls = []
    again = fm.run(tiny, SMALL, out=out, threads=1, progress=lambda *a: calls.append(a))
    assert calls == []  # nothing ran
    assert stamps(out) == before  # nothing written
    assert again.out == out
    same_result(first, again)
    # The same numbers as a run without a directory.
    same_result(first, fm.run(tiny, SMALL), wall_time=False)


def test_per_room_run_without_aem_is_read_back_too(tiny, tmp_path):
    overrides = dict(SMALL, training="per-room", **{"aem.enabled": False})
    out = tmp_path / "per-room"
    first = fm.run(tiny, overrides, out=out)
    assert list(first.best_genomes) == ["H", "square", "U"]
    assert np.isnan(first.rooms["recognition_pct"]).all()
    again = fm.run(tiny, overrides, out=out)
    same_result(first, again)


def test_cli_run_directory_is_read_back(cli, tiny, uninterrupted, tmp_path):
    first, _ = uninterrupted
    out = tmp_path / "cli"
    run_cli(cli, "run", tiny, "--out", out, "--threads", "1", *sets(SMALL))
    before = stamps(out)
    again = fm.run(tiny, SMALL, out=out)
    assert stamps(out) == before
    same_result(again, first, wall_time=False)


def python_spelling(message):
    """A guard message of Python's, in the CLI's words (`out` → `--out`, `force=True` →
    `--force`)."""
    text = str(message).replace("force=True", "--force").replace("another out", "another --out")
    return "--" + text if text.startswith("out ") else text


def test_another_run_is_kept_unless_force(cli, tiny, tmp_path):
    out = tmp_path / "x"
    run_cli(cli, "run", tiny, "--out", out, *sets(OTHER))
    (out / "notes.txt").write_text("mine")
    before = stamps(out)
    with pytest.raises(fm.FuzzymotivError) as e:
        fm.run(tiny, SMALL, out=out)
    assert "holds the results of a different run" in str(e.value)
    assert stamps(out) == before
    # The CLI's message, word for word, but for Python's spelling of the options.
    p = run_cli(cli, "run", tiny, "--out", out, *sets(SMALL), check=False)
    assert p.returncode == 2 and p.stderr.strip() == f"error: {python_spelling(e.value)}"
    assert "force=True" in str(e.value) and "--force" not in str(e.value)
    # force=True never deletes a file fuzzymotiv did not write...
    with pytest.raises(fm.FuzzymotivError) as e:
        fm.run(tiny, SMALL, out=out, force=True)
    assert "notes.txt" in str(e.value)
    assert stamps(out) == before
    # ... and replaces the run once that file is gone.
    (out / "notes.txt").unlink()
    res = fm.run(tiny, SMALL, out=out, force=True)
    assert json.loads((out / "summary.json").read_text())["generations"] == 4
    assert res.summary["generations"] == 4


def test_another_kind_of_output_is_kept_unless_force(tiny, tmp_path):
    out = tmp_path / "study"
    out.mkdir()
    (out / "summary.json").write_text('{"program": "fuzzymotiv", "settings": []}')
    with pytest.raises(fm.FuzzymotivError, match="holds the results of a different run"):
        fm.run(tiny, SMALL, out=out)
    assert (out / "summary.json").read_text().startswith('{"program"')
    fm.run(tiny, SMALL, out=out, force=True)
    assert json.loads((out / "summary.json").read_text())["name"] == "tiny"


def test_foreign_directory_file_and_cwd_are_never_replaced(tiny, tmp_path, monkeypatch):
    foreign = tmp_path / "thesis"
    foreign.mkdir()
    (foreign / "chapter1.tex").write_text("precious")
    for force in (False, True):
        with pytest.raises(fm.FuzzymotivError, match="is not a fuzzymotiv output directory"):
            fm.run(tiny, SMALL, out=foreign, force=force)
    assert (foreign / "chapter1.tex").read_text() == "precious"
    assert not (tmp_path / "thesis.partial").exists()

    a_file = tmp_path / "file"
    a_file.write_text("x")
    with pytest.raises(fm.FuzzymotivError, match="is a regular file, not a directory"):
        fm.run(tiny, SMALL, out=a_file, force=True)

    here = tmp_path / "here"
    here.mkdir()
    monkeypatch.chdir(here)
    for out in (".", here, tmp_path):
        with pytest.raises(fm.FuzzymotivError, match="is the current directory"):
            fm.run(tiny, SMALL, out=out, force=True)
    assert list(here.iterdir()) == []
    with pytest.raises(fm.FuzzymotivError, match="empty path"):
        fm.run(tiny, SMALL, out="")


def interrupt_after(k):
    def progress(done, total, best):
        if done == k:
            raise RuntimeError(f"stop after generation {k}")

    return progress


def test_interrupted_run_resumes_to_the_files_of_an_uninterrupted_one(tiny, uninterrupted, tmp_path):
    whole, whole_out = uninterrupted
    out = tmp_path / "run"
    with pytest.raises(RuntimeError, match="stop after generation 2"):
        fm.run(tiny, SMALL, out=out, progress=interrupt_after(2))
    partial = tmp_path / "run.partial"
    assert not out.exists() and (partial / "checkpoint.json").is_file()
    calls = []
    res = fm.run(tiny, SMALL, out=out, progress=lambda *a: calls.append(a[:2]))
    assert calls == [(3, 4), (4, 4)]  # from generation 3 on, counted on
    assert not partial.exists()
    assert files(out) == files(whole_out)
    assert json.loads((out / "summary.json").read_text())["wall_seconds"] > 0
    same_result(res, whole, wall_time=False)


def test_unfinished_run_of_another_config_is_kept_unless_force(cli, tiny, tmp_path):
    out = tmp_path / "run"
    with pytest.raises(RuntimeError):
        fm.run(tiny, OTHER, out=out, progress=interrupt_after(1))
    checkpoint = (tmp_path / "run.partial" / "checkpoint.json").read_bytes()
    with pytest.raises(fm.FuzzymotivError) as e:
        fm.run(tiny, SMALL, out=out)
    assert "holds an unfinished output of another run" in str(e.value)
    assert (tmp_path / "run.partial" / "checkpoint.json").read_bytes() == checkpoint
    p = run_cli(cli, "run", tiny, "--out", out, *sets(SMALL), check=False)
    assert p.returncode == 2 and p.stderr.strip() == f"error: {python_spelling(e.value)}"
    res = fm.run(tiny, SMALL, out=out, force=True)
    assert res.summary["generations"] == 4 and not (tmp_path / "run.partial").exists()


KILLED = textwrap.dedent(
    """
    import os, signal, sys
    import fuzzymotiv as fm

    config, out, marker, k = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    overrides = {overrides!r}

    def progress(done, total, best):
        if done == k:
            with open(marker, "w") as f:
                f.write(str(done))
            os.kill(os.getpid(), signal.SIGKILL)

    fm.run(config, overrides, out=out, progress=progress)
    print("not killed")
    """
).format(overrides=SMALL)


def test_kill_9_mid_run_then_the_same_call_resumes(tiny, uninterrupted, tmp_path):
    _, whole_out = uninterrupted
    out, marker = tmp_path / "run", tmp_path / "killed-at"
    script = tmp_path / "killed.py"
    script.write_text(KILLED)
    p = subprocess.run([sys.executable, str(script), str(tiny), str(out), str(marker), "3"], capture_output=True, text=True)
    assert p.returncode == -9, p.stderr
    assert marker.read_text() == "3" and "not killed" not in p.stdout
    assert not out.exists() and (tmp_path / "run.partial" / "checkpoint.json").is_file()
    calls = []
    fm.run(tiny, SMALL, out=out, progress=lambda *a: calls.append(a[0]))
    assert calls == [4]
    assert files(out) == files(whole_out)
