"""run, simulate and rooms against the CLI's files; errors; Ctrl-C; both table code paths."""

import _thread
import csv
import json
import signal
import sys
import time

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import run_cli

TINY = {"ga.generations": 3, "trial.steps": 100}
COLUMNS = ["generation", "best", "mean", "std", "min", "max", "a", "g", "l", "b", "room"]


def sets(overrides):
    out = []
    for k, v in overrides.items():
        out += ["--set", f"{k}={v}"]
    return out


@pytest.fixture(scope="module")
def cli_run(cli, repo, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "tiny"
    run_cli(cli, "run", repo / "configs/tiny.toml", "--out", out, "--threads", "1", *sets(TINY))
    return out


@pytest.fixture(scope="module")
def py_run(repo):
    return fm.run(str(repo / "configs/tiny.toml"), TINY, threads=2)


def columns(table):
    """A DataFrame or a dict of arrays as a dict of lists."""
    if isinstance(table, dict):
        return {k: list(v) for k, v in table.items()}
    return {k: table[k].tolist() for k in table.columns}


def test_run_equals_cli_generations_csv(cli_run, py_run):
    with open(cli_run / "generations.csv") as f:
        rows = list(csv.DictReader(f))
    g = columns(py_run.generations)
    assert list(g) == COLUMNS
    assert len(rows) == len(g["best"]) == 3
    for k in COLUMNS:
        if k == "generation":
            assert [int(v) for v in g[k]] == [int(r[k]) for r in rows]
        elif k == "room":
            assert g[k] == [r[k] for r in rows]
        else:  # the CSV prints 9 decimals
            assert [f"{v:.9f}" for v in g[k]] == [r[k] for r in rows], k


def test_run_best_genome_summary_and_rooms_equal_cli(cli_run, py_run):
    genome = json.loads((cli_run / "best_genome.json").read_text())
    assert isinstance(py_run.best_genome, np.ndarray)
    assert py_run.best_genome.tolist() == genome["weights"]  # bit for bit
    summary = json.loads((cli_run / "summary.json").read_text())
    for k in ("name", "seed", "motivations", "training", "rooms", "runs"):
        assert py_run.summary[k] == summary[k], k
    rooms = columns(py_run.rooms)
    assert rooms["room"] == ["H", "square", "U"]
    assert rooms["average_fitness"] == [r["average_fitness"] for r in summary["rooms"]]
    assert set(py_run.trajectories) == {"H", "square", "U"}
    assert len(py_run.trajectories["H"]["x"]) == 101


def test_run_with_out_writes_the_cli_run_directory(cli_run, repo, tmp_path):
    out = tmp_path / "py-run"
    calls = []
    res = fm.run(repo / "configs/tiny.toml", TINY, out=out, progress=lambda *a: calls.append(a))
    assert res.out == out
    for name in ("generations.csv", "best_genome.json", "recognition.csv", "table.md"):
        assert (out / name).read_text() == (cli_run / name).read_text(), name
    assert (out / "report.html").is_file() and not (tmp_path / "py-run.partial").exists()
    assert [c[:2] for c in calls] == [(1, 3), (2, 3), (3, 3)]
    assert calls[-1][2] == pytest.approx(res.summary["runs"][0]["last_generation"]["best"])


def test_config_text_and_overrides_equal_the_config_file_and_set_strings(repo):
    text = (repo / "configs/tiny.toml").read_text().replace('"../rooms/U.toml"', '"rooms/U.toml"')
    a = fm.run(config_text=text, overrides={"ga.generations": 2, "trial.steps": 60, "rooms": ["H", "square"], "aem.enabled": False})
    b = fm.run(repo / "configs/tiny.toml", ["ga.generations=2", "trial.steps=60", 'rooms=["H","square"]', "aem.enabled=false"])
    assert columns(a.generations) == columns(b.generations)
    assert a.summary["rooms"][0]["room"] == "H" and len(a.summary["rooms"]) == 2


def test_simulate_equals_cli_replay(cli, cli_run, py_run, tmp_path):
    page = tmp_path / "rp" / "replay.html"
    run_cli(cli, "replay", cli_run, "--room", "H", "--seed", 11, "--out", page)
    doc = json.loads((tmp_path / "rp" / "replay.json").read_text())["rooms"][0]
    tr = fm.simulate(py_run.best_genome, "H", 11, config=cli_run / "config.resolved.toml")
    want = doc["trajectory"]
    t = len(want["motors"])
    assert tr["x"].shape == (t + 1,) and tr["sensors"].shape == (t, 8) and tr["motors"].shape == (t, 2)
    assert tr["x"].tolist() == [p["x"] for p in want["poses"]]
    assert tr["y"].tolist() == [p["y"] for p in want["poses"]]
    assert tr["heading"].tolist() == [p["heading"] for p in want["poses"]]
    assert tr["sensors"].tolist() == want["sensors"]
    assert tr["motors"].tolist() == want["motors"]
    assert tr["collision"].tolist() == want["collisions"]
    assert tr["action"].tolist() == doc["actions"]
    assert tr["idle"].dtype == bool and tr["idle"].tolist() == want["idle"]
    assert tr["energy"].tolist() == want["energy"]
    assert tr["escaped"].tolist() == want["escaped"]
    for k in "aglb":
        assert tr[k] == doc["terms"][k]
    assert tr["F"] == doc["f"]
    # Same genome, room and seed: the same trajectory; another seed: another one.
    again = fm.simulate(py_run.best_genome, "H", 11, config=cli_run / "config.resolved.toml")
    assert np.array_equal(again["x"], tr["x"])
    other = fm.simulate(py_run.best_genome, "H", 12, config=cli_run / "config.resolved.toml")
    assert not np.array_equal(other["x"], tr["x"])


def test_simulate_room_file_and_errors(repo, py_run):
    tr = fm.simulate(py_run.best_genome, repo / "rooms/U.toml", 1, overrides={"trial.steps": 30})
    assert tr["room"] == "U" and tr["motors"].shape == (30, 2)
    with pytest.raises(ValueError, match="genome: 3 weights, but an 8-6-2 network needs 68"):
        fm.simulate([0.0, 0.0, 0.0], "H", 1)
    with pytest.raises(ValueError, match="room nowhere: not a room of the config"):
        fm.simulate(py_run.best_genome, "nowhere", 1)


def test_rooms_and_room_files(cli, repo):
    rooms = fm.rooms()
    assert [r["name"] for r in rooms] == ["H", "T", "L", "square", "rectangle"]
    for r in rooms:
        assert r["outline"].ndim == 2 and r["outline"].shape[1] == 2
        assert set(r["home"]) == {"x", "y", "heading", "heading_deg"}
        assert set(r["home_zone"]) == {"x", "y", "radius"} and r["home_zone"]["radius"] > 0
        assert r["area"] > 0
    u = fm.load_room(repo / "rooms/U.toml")
    assert u["name"] == "U" and fm.rooms([repo / "rooms/U.toml"])[0]["name"] == "U"
    out = run_cli(cli, "rooms").stdout
    h = rooms[0]
    assert f"{h['area'] / 1e6:>10.3f}" in out.splitlines()[1]


def test_errors_carry_the_cli_message(cli, repo):
    config = repo / "configs/tiny.toml"
    with pytest.raises(fm.FuzzymotivError) as e:
        fm.run(config, {"ga.populaton": 5})
    p = run_cli(cli, "run", config, "--set", "ga.populaton=5", "--out", "/nonexistent/x", check=False)
    assert p.returncode == 2
    assert isinstance(e.value, ValueError)
    assert "ga" in str(e.value) and "populaton" in str(e.value)
    assert p.stderr.strip() == f"error: {e.value}"

    bad_room = repo / "crates/fuzzymotiv/tests/corpus/rooms/home-outside.toml"
    with pytest.raises(ValueError) as e:
        fm.load_room(bad_room)
    p = run_cli(cli, "rooms", "--check", bad_room, check=False)
    assert p.returncode == 2 and p.stderr.strip() == f"error: {e.value}"
    assert "field `home" in str(e.value)

    with pytest.raises(ValueError, match="config: the file .*no-such-config.toml does not exist"):
        fm.run(repo / "no-such-config.toml")
    with pytest.raises(ValueError, match="threads must be at least 1"):
        fm.run(config, TINY, threads=0)
    with pytest.raises(ValueError, match=r"ga.population"):
        fm.run(config_text="[ga]\npopulation = -3\n")


def test_ctrl_c_interrupts_a_run(repo):
    calls = []

    def progress(done, total, best):
        calls.append(done)
        if done == 2:
            _thread.interrupt_main()  # what Ctrl-C does

    # A process started in the background inherits SIGINT ignored, and interrupt_main() then
    # does nothing: give SIGINT Python's own handler, as an interactive Ctrl-C finds it.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        start = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            fm.run(repo / "configs/tiny.toml", {"ga.generations": 500, "trial.steps": 100}, progress=progress)
        assert time.monotonic() - start < 60
    finally:
        signal.signal(signal.SIGINT, previous)
    # The run stops at the generation after the callback that saw Ctrl-C.
    assert max(calls) == 2, calls


def test_progress_callback_errors_propagate(repo):
    def progress(done, total, best):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        fm.run(repo / "configs/tiny.toml", TINY, progress=progress)


def test_tables_without_pandas_are_dicts_of_arrays(repo, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas → ImportError
    res = fm.run(repo / "configs/tiny.toml", {"ga.generations": 2, "trial.steps": 50, "aem.enabled": False})
    assert isinstance(res.generations, dict) and list(res.generations) == COLUMNS
    assert isinstance(res.generations["best"], np.ndarray) and res.generations["best"].shape == (2,)
    assert isinstance(res.rooms, dict)


def test_tables_become_dataframes_with_to_pandas(repo):
    pd = pytest.importorskip("pandas")
    res = fm.run(repo / "configs/tiny.toml", {"ga.generations": 2, "trial.steps": 50, "aem.enabled": False})
    generations, rooms = res.generations.to_pandas(), res.rooms.to_pandas()
    assert isinstance(generations, pd.DataFrame) and list(generations.columns) == COLUMNS
    assert isinstance(rooms, pd.DataFrame) and rooms["room"].tolist() == ["H", "square", "U"]
