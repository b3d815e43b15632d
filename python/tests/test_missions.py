"""Issue #52, the Python front: every motivation of a config (a fifth, or none of the paper's)
reaches fm.Problem, fm.run's rooms, fm.fuzzy_fitness; a term of one's own reaches fm.run's
run directory; a one-room config makes a Problem."""

from __future__ import annotations

import json
import pickle

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import run_cli

SMALL = {"ga.generations": 2, "ga.population": 6, "trial.steps": 100}
PAPER = ("curiosity", "homing", "orientation", "energy")


def test_a_five_motivation_mission_config_keeps_urgency_and_the_mission_measures(repo):
    """configs/fetch.toml (the paper's four and urgency): the Problem's motivations name
    urgency with its weight, its evaluation has five terms whose F is fuzzy_fitness of those
    motivations, and fm.run's rooms have the missions done and the mission terms, as
    summary.json has them."""
    config = str(repo / "configs/fetch.toml")
    p = fm.Problem(config, SMALL)
    assert p.motivations == pytest.approx((0.5, 0.1, 0.0, 0.1, 0.3))
    assert p.motivations.names == (*PAPER, "urgency")
    assert p.motivations.as_dict()["urgency"] == pytest.approx(0.3)
    assert p.term_names == ["a", "g", "l", "b", "urgency"]
    ev = p.evaluate(np.random.default_rng(1).normal(size=(4, p.genome_size)))
    assert ev.terms.shape == (4, 5, 5)
    per_room = np.stack([fm.fuzzy_fitness(p.motivations, ev.terms[:, r]) for r in range(5)], axis=1)
    assert ev.fitness == pytest.approx(per_room.mean(axis=1), abs=1e-12)

    res = fm.run(config, SMALL)
    rooms = res.rooms
    for column in ["mission_done_pct", "terms_pct.urgency", "terms_pct.goal", "terms_pct.safety"]:
        assert column in rooms and rooms[column].shape == (5,), column
    for row, summary in zip(range(5), res.summary["rooms"]):
        assert rooms["room"][row] == summary["room"]
        assert rooms["mission_done_pct"][row] == summary["mission_done_pct"]
        assert rooms["terms_pct.urgency"][row] == summary["terms_pct"]["urgency"]
    table = res.summary["motivations"]["table"]
    assert [m["name"] for m in table][-1] == "urgency"


def test_run_rooms_of_the_paper_config_have_no_mission_columns():
    res = fm.run(overrides={**SMALL, "rooms": ["H", "T"], "trial.steps": 50})
    assert list(res.rooms) == [
        "room", "average_fitness", "exploration_pct", "recognition_pct", "battery_pct",
        "homing_pct", "r_node",
    ]


def hurry_and_care(repo) -> str:
    """A config of two motivations, none of the paper's, in the fetch rooms."""
    rooms = ", ".join(json.dumps(str(repo / f"rooms/fetch-{r}.toml")) for r in ["H", "T"])
    return (
        f"rooms = [{rooms}]\n[motivations]\n"
        'hurry = { weight = 0.6, term = "urgency" }\ncare = { weight = 0.4, term = "safety" }\n'
    )


def test_problem_motivations_of_a_config_without_the_papers_four_are_its_own(repo):
    """Only hurry and care: their weights, not four zeros (inputs in alphabetical order)."""
    p = fm.Problem(config_text=hurry_and_care(repo), overrides={"trial.steps": 50})
    assert p.motivations == pytest.approx((0.4, 0.6))
    assert p.motivations.names == ("care", "hurry")
    assert p.term_names == ["safety", "urgency"]
    ev = p.evaluate(np.zeros((2, p.genome_size)))
    f = [fm.fuzzy_fitness(p.motivations, ev.terms[:, r]) for r in range(2)]
    assert ev.fitness == pytest.approx(np.mean(f, axis=0), abs=1e-12)


def test_problem_motivations_of_the_paper_config_are_still_c_h_o_e():
    """A tuple of four floats as before (unpacks, compares with a tuple), now named, pickled."""
    p = fm.Problem(overrides={"rooms": ["H", "T"], "trial.steps": 50})
    c, h, o, e = p.motivations
    assert (c, h, o, e) == pytest.approx((0.8, 0.1, 0.0, 0.1))
    assert isinstance(p.motivations, tuple) and p.motivations.names == PAPER
    again = pickle.loads(pickle.dumps(p.motivations))
    assert again == p.motivations and again.names == PAPER
    assert repr(again) == "MotivationWeights(curiosity=0.8, homing=0.1, orientation=0.0, energy=0.1)"


def test_problem_on_a_one_room_config_needs_no_aem_enabled_false():
    """A problem only evaluates: a one-room config (where room modelling cannot run) makes one,
    which evaluates as the same config with aem.enabled = false."""
    one = fm.Problem(overrides={"rooms": ["H"], "trial.steps": 50})
    off = fm.Problem(overrides={"rooms": ["H"], "trial.steps": 50, "aem.enabled": False})
    assert one.rooms == ["H"]
    g = np.random.default_rng(3).normal(size=(3, one.genome_size))
    assert np.array_equal(one.evaluate(g).fitness, off.evaluate(g).fitness)
    ga = fm.GA(one)
    genomes = ga.ask()
    ga.tell(one.evaluate(genomes, generation=0, seed=ga.seed).fitness)
    assert ga.generation == 1


def test_fuzzy_fitness_takes_any_number_of_motivations_as_the_cli(cli):
    """Five motivations by name (the paper's four and urgency) give the CLI's F; so do the
    same weights unnamed (x1..x5), and Problem.motivations of fetch.toml."""
    x = {"curiosity": 0.5, "homing": 0.1, "orientation": 0.0, "energy": 0.1, "urgency": 0.3}
    y = [0.95, 0.5, 0.0, 0.79, 0.6]
    f = fm.fuzzy_fitness(x, y)
    names = ["a", "g", "l", "b", "urgency"]
    out = run_cli(
        cli, "fuzzy", "--motivations", ",".join(f"{k}={v}" for k, v in x.items()),
        "--fitness", ",".join(f"{k}={v}" for k, v in zip(names, y)),
    )
    assert out.stdout.splitlines()[0] == f"{f:.12f}"
    assert fm.fuzzy_fitness(list(x.values()), y) == f
    weights = fm.MotivationWeights(x.values(), x.keys())
    assert fm.fuzzy_fitness(weights, y) == f
    many = fm.fuzzy_fitness(weights, np.array([y, [1.0] * 5]))
    assert many.shape == (2,) and many[0] == f and many[1] == pytest.approx(1.0)
    e = fm.fuzzy_fitness(weights, y, explain=True)
    assert e["fitness"] == f and all(len(r["labels"]) == 5 for r in e["rules"])
    assert "urgency is" in e["text"]
    assert fm.export_fll(weights).count("\n  rule: ") == 5**5
    # One and eight motivations.
    assert fm.fuzzy_fitness([1.0], [0.5]) == pytest.approx(0.25)
    assert fm.fuzzy_fitness([0.125] * 8, [1.0] * 8) == pytest.approx(1.0)


@pytest.mark.parametrize(
    "x, y, says",
    [
        ([0.1] * 9 + [0.1], [0.5] * 10, r"motivations: expected 1 to 8 weights, one per motivation .* got 10"),
        ([], [], r"motivations: expected 1 to 8 weights, one per motivation .* got 0"),
        ([0.5, 0.3, 0.2], [0.5, 0.5], r"terms: expected 3 values \(y1, y2, y3\), one per motivation, got 2"),
        ([0.25] * 4, [0.5] * 5, r"terms: expected four values \(a, g, l, b\), one per motivation, got 5"),
        ({"curiosity": 0.7, "urgency": 0.3}, np.zeros((2, 3)),
         r"terms: expected an n × 2 array of \(a, urgency\), one column per motivation, got shape \(2, 3\)"),
        ([0.5, 0.5, np.nan], [0, 0, 0], r"motivations: `nan` \(x3\) is not a finite number; expected 3 numbers \(x1, x2, x3\)"),
        ({"hurry": 0.5, "care": 0.6}, [0, 0], r"motivations: motivations must sum to 1, got 1\.1"),
    ],
)
def test_fuzzy_fitness_refuses_motivations_and_terms_of_the_wrong_number(x, y, says):
    with pytest.raises(fm.FuzzymotivError, match=says):
        fm.fuzzy_fitness(x, y)


def constant(value: float):
    return lambda trials: np.full(trials.shape, value)


SMOOTH = """rooms = ["H", "T"]
[motivations]
curiosity = 0.5
homing = 0.1
orientation = 0.0
energy = 0.1
smooth = 0.3
"""
RUN = {"ga.generations": 2, "ga.population": 6, "trial.steps": 50}


def test_run_with_a_term_of_your_own_uses_it_and_writes_it_to_the_run_directory(tmp_path):
    """fm.run(terms=...): the term sets F (another value, other fitness), and its % is in the
    rooms, summary.json, table.md and the report."""
    out = tmp_path / "smooth"
    res = fm.run(config_text=SMOOTH, overrides=RUN, terms={"smooth": constant(0.25)}, out=out)
    assert res.rooms["terms_pct.smooth"].tolist() == [25.0, 25.0]
    summary = json.loads((out / "summary.json").read_text())
    assert [r["terms_pct"]["smooth"] for r in summary["rooms"]] == [25.0, 25.0]
    table = (out / "table.md").read_text()
    assert "% smooth" in table.splitlines()[0]
    assert "smooth" in (out / "report.html").read_text()
    high = fm.run(config_text=SMOOTH, overrides=RUN, terms={"smooth": constant(1.0)})
    assert np.all(high.generations["best"] > res.generations["best"])
    # Read back: the finished directory again, the same result.
    again = fm.run(config_text=SMOOTH, overrides=RUN, terms={"smooth": constant(0.25)}, out=out)
    assert np.array_equal(again.generations["best"], res.generations["best"])


def test_run_with_a_failing_term_raises_naming_it_and_finishes_no_directory(tmp_path):
    out = tmp_path / "bad"
    with pytest.raises(fm.FuzzymotivError, match=r"terms\['smooth'\]: `2\.0` .* is not a number in \[0, 1\]"):
        fm.run(config_text=SMOOTH, overrides=RUN, terms={"smooth": constant(2.0)}, out=out)
    assert not out.exists()

    def raises(trials):
        raise KeyError("heading")

    with pytest.raises(fm.FuzzymotivError, match=r"terms\['smooth'\]: the function raised KeyError"):
        fm.run(config_text=SMOOTH, overrides=RUN, terms={"smooth": raises})
    with pytest.raises(fm.ConfigError, match=r"motivations\.smooth.*\"smooth\", which does not exist"):
        fm.run(config_text=SMOOTH, overrides=RUN)


def test_a_term_returning_strings_is_refused_naming_the_term_and_what_it_returned():
    """numpy reads "0.5" as a number; a term's value must be a number, not text."""
    strings = lambda trials: np.full(trials.shape, "0.5")  # noqa: E731
    says = r"terms\['smooth'\]: returned ndarray \(strings, dtype <U3, e\.g\. '0\.5'\), expected an array"
    p = fm.Problem(config_text=SMOOTH, overrides=RUN, terms={"smooth": strings})
    with pytest.raises(fm.FuzzymotivError, match=says):
        p.evaluate(np.zeros((2, p.genome_size)))
    with pytest.raises(fm.FuzzymotivError, match=says):
        fm.run(config_text=SMOOTH, overrides=RUN, terms={"smooth": strings})
    objects = lambda trials: np.full(trials.shape, None)  # noqa: E731
    with pytest.raises(fm.FuzzymotivError, match=r"returned ndarray \(Python objects, dtype object, e\.g\. None\)"):
        p = fm.Problem(config_text=SMOOTH, overrides=RUN, terms={"smooth": objects})
        p.evaluate(np.zeros((2, p.genome_size)))
