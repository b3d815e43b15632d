"""fm.GA.from_run: a GA continuing a finished run directory reproduces a fresh longer run's
generations exactly and leaves the directory as it was; what cannot be continued is an error."""

import shutil
from pathlib import Path

import pytest

import fuzzymotiv as fm

SMALL = {"ga.population": 8, "trial.steps": 80, "aem.epochs": 10, "aem.test_runs": 2}
COLUMNS = ["generation", "best", "mean", "std", "min", "max", "a", "g", "l", "b"]


def columns(table):
    if isinstance(table, dict):
        return {k: list(v) for k, v in table.items()}
    return {k: table[k].tolist() for k in table.columns}


def snapshot(d: Path) -> dict:
    return {p.relative_to(d): p.read_bytes() for p in sorted(d.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def runs(repo, tmp_path_factory):
    """A finished 2-generation run directory and a fresh 4-generation run, per training."""
    tmp = tmp_path_factory.mktemp("runs")
    config = str(repo / "configs/tiny.toml")
    out = {}
    for training in ("all-rooms", "per-room"):
        o = {**SMALL, "training": training}
        if training == "per-room":
            o["rooms"] = ["H", "square"]
        short = tmp / f"short-{training}"
        fm.run(config, {**o, "ga.generations": 2}, threads=2, out=short)
        fresh = fm.run(config, {**o, "ga.generations": 4}, threads=2)
        out[training] = (short, columns(fresh.generations))
    return out


def continue_to(ga, generations):
    while ga.generation < generations:
        genomes = ga.ask()
        ev = ga.problem.evaluate(genomes, generation=ga.generation, seed=ga.seed)
        ga.tell(ev.fitness, ev.terms)


def test_from_run_continues_to_a_fresh_longer_run(runs):
    short, fresh = runs["all-rooms"]
    before = snapshot(short)
    ga = fm.GA.from_run(short, threads=2)
    assert ga.generation == 2 and ga.problem.generations == 2
    assert ga.best is not None and ga.best.generation == 1
    assert ga.best.fitness == fresh["best"][1]
    first = columns(ga.history)
    for c in COLUMNS:
        assert first[c] == fresh[c][:2], c
    continue_to(ga, 4)
    mine = columns(ga.history)
    for c in COLUMNS:
        assert mine[c] == fresh[c], c
    assert snapshot(short) == before, "from_run changed the run directory"


def test_from_run_per_room_needs_the_room(runs):
    short, fresh = runs["per-room"]
    with pytest.raises(fm.FuzzymotivError, match="room"):
        fm.GA.from_run(short)
    ga = fm.GA.from_run(short, room="square", threads=2)
    continue_to(ga, 4)
    mine = columns(ga.history)
    rows = [i for i, r in enumerate(fresh["room"]) if r == "square"]
    for c in COLUMNS:
        assert mine[c] == [fresh[c][i] for i in rows], c


def test_what_cannot_be_continued_is_an_error(runs, tmp_path, repo):
    short, _ = runs["all-rooms"]
    with pytest.raises(fm.FuzzymotivError, match="no such directory"):
        fm.GA.from_run(tmp_path / "nothing")
    older = tmp_path / "older"
    shutil.copytree(short, older)
    (older / "population.json").unlink()
    with pytest.raises(fm.FuzzymotivError, match="no population.json"):
        fm.GA.from_run(older)
    unfinished = tmp_path / "unfinished"
    unfinished.mkdir()
    with pytest.raises(fm.FuzzymotivError, match="config.resolved.toml"):
        fm.GA.from_run(unfinished)
    other = fm.Problem(str(repo / "configs/tiny.toml"), SMALL)
    with pytest.raises(fm.FuzzymotivError, match="problem: its config is not"):
        fm.GA.from_run(short, problem=other)
    with pytest.raises(fm.FuzzymotivError, match="problem: expected a fuzzymotiv.Problem"):
        fm.GA.from_run(short, problem="nope")  # type: ignore[arg-type]
