"""Terms of your own from Python (Problem(terms=...)), N motivations through Problem and GA."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import fuzzymotiv as fm

SMALL = """rooms = ["H", "T"]
[ga]
population = 4
generations = 2
[trial]
steps = 60
[aem]
enabled = false
"""


def one_term(name: str) -> str:
    """A config whose only motivation weighs the term `name`."""
    return SMALL + f'[motivations]\nown = {{ weight = 1.0, term = "{name}" }}\n'


def genomes(problem: fm.Problem, n: int = 3, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).normal(size=(n, problem.genome_size))


def constant(value: float):
    return lambda trials: np.full(trials.shape, value)


def smoothness(trials: fm.Trials) -> np.ndarray:
    """1 − mean |Δheading| / π over executed steps (a module-level function: it pickles)."""
    turn = np.abs(np.angle(np.exp(1j * np.diff(trials.heading, axis=-1))))
    moving = ~trials.idle
    return 1 - (turn * moving).sum(-1) / np.maximum(moving.sum(-1), 1) / np.pi


@pytest.mark.parametrize("value, f", [(0.25, 0.0625), (0.75, 0.5625), (0.0, 0.0), (1.0, 1.0)])
def test_a_user_term_of_known_value_sets_f_by_its_formula(value, f):
    """One motivation of weight 1 on a term of constant value v at a label's peak: F = 1 · v ·
    C(v) with C = the peak (as the Rust test of the same name)."""
    p = fm.Problem(config_text=one_term("mine"), terms={"mine": constant(value)})
    assert p.term_names == ["mine"]
    ev = p.evaluate(genomes(p))
    assert ev.terms.shape == (3, 2, 1)
    assert np.all(ev.terms == value)
    assert np.all(ev.fitness == f)


def test_a_user_term_changes_f_beside_the_paper_four():
    """The paper's four plus one of one's own: F moves with the term's value, the paper's terms
    stay those of the same trials."""
    cfg = SMALL + (
        "[motivations]\ncuriosity = 0.4\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\n"
        'steady = { weight = 0.4, term = "mine" }\n'
    )
    low = fm.Problem(config_text=cfg, terms={"mine": constant(0.0)})
    high = fm.Problem(config_text=cfg, terms={"mine": constant(1.0)})
    assert low.term_names == ["a", "g", "l", "b", "mine"]
    g = genomes(low, 4)
    e0, e1 = low.evaluate(g), high.evaluate(g)
    assert np.array_equal(e0.terms[..., :4], e1.terms[..., :4])
    assert np.all(e1.fitness > e0.fitness)


@pytest.mark.parametrize(
    "returned, says",
    [
        (lambda t: np.full(t.shape, 1.5), r"`1\.5` \(genome 0, room 0\) is not a number in \[0, 1\]"),
        (lambda t: np.full(t.shape, -0.1), r"`-0\.1` \(genome 0, room 0\) is not a number in \[0, 1\]"),
        (lambda t: np.where(np.arange(2) == 1, np.nan, 0.5) * np.ones(t.shape), r"`nan` \(genome 0, room 1\)"),
        (lambda t: np.zeros(t.shape[0]), r"returned shape \(3,\), expected \(3, 2\)"),
        (lambda t: "smooth", r"returned str \(strings, dtype <U6, e\.g\. 'smooth'\), expected an array of shape \(3, 2\)"),
    ],
)
def test_bad_term_values_raise_naming_the_term(returned, says):
    p = fm.Problem(config_text=one_term("wobble"), terms={"wobble": returned})
    with pytest.raises(fm.FuzzymotivError, match=r"terms\['wobble'\]: " + says):
        p.evaluate(genomes(p))


def test_terms_not_given_as_name_to_function_are_refused():
    with pytest.raises(fm.FuzzymotivError, match=r"terms\['x'\]: expected a function"):
        fm.Problem(config_text=one_term("x"), terms={"x": 0.5})
    with pytest.raises(fm.FuzzymotivError, match=r"terms: expected a dict"):
        fm.Problem(config_text=one_term("x"), terms=[constant(0.5)])


def test_a_motivation_weighing_an_unregistered_term_names_it():
    with pytest.raises(fm.ConfigError, match=r"motivations\.own.*\"mine\", which does not exist"):
        fm.Problem(config_text=one_term("mine"))
    with pytest.raises(fm.ConfigError, match=r"terms\.goal.*not one of the library's terms"):
        fm.Problem(config_text=one_term("goal"), terms={"goal": constant(0.5)})


def test_trials_hold_the_generations_evaluation_trials():
    calls = []

    def spy(trials: fm.Trials) -> np.ndarray:
        calls.append(trials)
        return np.full(trials.shape, 0.5)

    p = fm.Problem(config_text=one_term("spy"), terms={"spy": spy})
    g = genomes(p, 3)
    p.evaluate(g, generation=2)
    assert len(calls) == 1, "one batched call per evaluation"
    t = calls[0]
    assert isinstance(t, fm.Trials)
    assert t.shape == (3, 2) and t.rooms == ["H", "T"]
    for name in ("x", "y", "heading"):
        assert getattr(t, name).shape == (3, 2, 61) and getattr(t, name).dtype == np.float64
    for name, dtype in [("actions", np.int64), ("collisions", np.bool_), ("idle", np.bool_), ("energy", np.float64)]:
        assert getattr(t, name).shape == (3, 2, 60) and getattr(t, name).dtype == dtype, name
    assert t.sensors.shape == (3, 2, 60, 8)
    assert set(np.unique(t.actions)) <= {0, 1, 2, 3}
    assert np.array_equal(t.executed, (~t.idle).sum(-1))
    assert sorted(t.terms) == ["a", "b", "g", "l"]
    # The same trials as the plain evaluation's: its terms are theirs, for the same genomes.
    plain = fm.Problem(config_text=SMALL + "[motivations]\ncuriosity = 0.8\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\n")
    ev = plain.evaluate(g, generation=2)
    for k, name in enumerate("aglb"):
        assert np.array_equal(ev.terms[..., k], t.terms[name]), name
    # Every robot starts at home in each room.
    assert np.all(t.x[:, :, 0] == t.x[0, :, 0]) and np.all(t.y[:, :, 0] == t.y[0, :, 0])


def test_the_paper_config_keeps_four_terms_named_a_g_l_b():
    p = fm.Problem(config_text=SMALL)
    assert p.term_names == ["a", "g", "l", "b"]
    assert p.evaluate(genomes(p)).terms.shape == (3, 2, 4)


def test_five_motivations_run_through_problem_and_ga(repo):
    sizes = {"ga.population": 4, "trial.steps": 80, "aem.enabled": False}
    p = fm.Problem(repo / "configs" / "fetch.toml", sizes)
    assert p.term_names == ["a", "g", "l", "b", "urgency"]
    ga = fm.GA(p)
    for _ in range(2):
        ev = p.evaluate(ga.ask(), generation=ga.generation, seed=ga.seed)
        assert ev.terms.shape == (4, 5, 5)
        ga.tell(ev.fitness, ev.terms)
    h = ga.history
    assert np.allclose(h["urgency"][-1], ev.terms[..., 4].mean())
    again = fm.GA.from_state(ga.state, p)
    assert again.state == ga.state
    assert np.array_equal(again.history["urgency"], h["urgency"])
    with pytest.raises(fm.FuzzymotivError, match=r"expected shape \(4, 5, 5\).*a g l b urgency"):
        ga.ask()
        ga.tell(ev.fitness, ev.terms[..., :4])


def test_descriptors_may_name_any_measured_term(repo):
    p = fm.Problem(repo / "configs" / "fetch.toml", {"ga.population": 4, "trial.steps": 80, "aem.enabled": False})
    ev = p.evaluate(genomes(p), descriptors=["x", "urgency", "safety", "a"])
    assert ev.descriptors.shape == (3, 5, 4)
    assert np.array_equal(ev.descriptors[..., 1], ev.terms[..., 4])
    assert np.array_equal(ev.descriptors[..., 3], ev.terms[..., 0])
    assert np.all((ev.descriptors[..., 2] >= 0) & (ev.descriptors[..., 2] <= 1))
    with pytest.raises(fm.FuzzymotivError, match=r"unknown descriptor \"speed\".*\"urgency\""):
        p.evaluate(genomes(p), descriptors=["speed"])
    own = fm.Problem(config_text=one_term("mine"), terms={"mine": constant(0.25)})
    d = own.evaluate(genomes(own), descriptors=["mine", "x"]).descriptors
    assert np.all(d[..., 0] == 0.25)


def test_a_problem_with_terms_pickles_and_evolves_with_ga():
    p = fm.Problem(config_text=one_term("smooth"), terms={"smooth": smoothness})
    q = pickle.loads(pickle.dumps(p))
    g = genomes(p, 4)
    assert q.evaluate(g).fitness.tobytes() == p.evaluate(g).fitness.tobytes()
    ga = fm.GA(p)
    for _ in range(2):
        ev = p.evaluate(ga.ask(), generation=ga.generation, seed=ga.seed)
        assert np.all((ev.terms >= 0) & (ev.terms <= 1))
        ga.tell(ev.fitness, ev.terms)
    assert np.all((ga.history["smooth"] > 0) & (ga.history["smooth"] <= 1))
    assert ga.best is not None


def test_guide_term_of_your_own_runs_as_written(doc_blocks, capsys):
    """docs/guide/motivations.md, "A term of your own, in Python": the block runs and prints
    the five inputs and three generations' mean smoothness."""
    (code,) = doc_blocks("docs/guide/motivations.md", "## 6. A term of your own, in Python")
    exec(compile(code, "docs/guide/motivations.md (own term)", "exec"), {})
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "['a', 'g', 'l', 'b', 'smoothness']"
    assert out[1].startswith("[") and len(out[1].strip("[]").split()) == 3


def test_a_term_function_that_raises_is_a_fuzzymotiv_error_naming_it():
    """An exception inside a term function comes back as FuzzymotivError naming the term, the
    original chained as its cause."""

    def broken(trials):
        raise ZeroDivisionError("division by zero")

    p = fm.Problem(config_text=one_term("wobble"), terms={"wobble": broken})
    with pytest.raises(fm.FuzzymotivError, match=r"terms\['wobble'\]: the function raised ZeroDivisionError") as e:
        p.evaluate(genomes(p))
    assert isinstance(e.value.__cause__, ZeroDivisionError)


def test_terms_from_python_with_a_randomised_robot_are_refused():
    """The trials a Python term is computed from are recorded on the configured robot; with
    [trial.randomise] the GA's trials are drawn robots, so the two would disagree: refused."""
    cfg = one_term("mine") + "[trial.randomise]\nnoise = [0.0, 0.2]\n"
    p = fm.Problem(config_text=cfg, terms={"mine": constant(0.5)})
    with pytest.raises(fm.FuzzymotivError, match=r"\[trial\.randomise\]"):
        p.evaluate(genomes(p))
