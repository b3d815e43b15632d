"""fm.Problem and fm.GA: batched evaluation and ask/tell against fm.run's evolution; descriptors;
the state round trip; bad input."""

import json
import warnings

import numpy as np
import pytest

import fuzzymotiv as fm

# Three rooms (one a room file), a small GA, short trials: fm.run and the hand-driven GA.
TINY = {"ga.generations": 5, "ga.population": 12, "trial.steps": 80, "aem.enabled": False}
COLUMNS = ["generation", "best", "mean", "std", "min", "max", "a", "g", "l", "b"]


def columns(table):
    """A DataFrame or a dict of arrays as a dict of lists."""
    if isinstance(table, dict):
        return {k: list(v) for k, v in table.items()}
    return {k: table[k].tolist() for k in table.columns}


@pytest.fixture(scope="module")
def config(repo):
    return str(repo / "configs/tiny.toml")


@pytest.fixture(scope="module")
def problem(config):
    return fm.Problem(config, TINY, threads=2)


@pytest.fixture(scope="module")
def reference(config):
    return columns(fm.run(config, TINY, threads=2).generations)


def drive(problem, ga, generations, descriptors=None):
    """ask → evaluate → tell, `generations` times; the evaluations of each generation."""
    evals = []
    for _ in range(generations):
        genomes = ga.ask()
        ev = problem.evaluate(genomes, generation=ga.generation, seed=ga.seed, descriptors=descriptors)
        ga.tell(ev.fitness, ev.terms)
        evals.append((genomes, ev))
    return evals


def test_attributes(problem):
    assert problem.genome_size == 68
    assert problem.rooms == ["H", "square", "U"]
    assert problem.motivations == pytest.approx((0.8, 0.1, 0.0, 0.1))
    assert (problem.seed, problem.run, problem.population, problem.generations) == (7, "all", 12, 5)
    assert problem.steps == 80


def test_five_generations_of_ask_tell_reproduce_fm_run(problem, reference):
    """The hand-driven GA logs exactly fm.run's generations.csv rows."""
    ga = fm.GA(problem)
    evals = drive(problem, ga, 5)
    assert ga.generation == 5
    mine = columns(ga.history)
    for c in COLUMNS:
        assert mine[c] == reference[c], c
    assert mine["room"] == ["all"] * 5
    # Evaluating generation g's population gives the F statistics fm.run logged for g.
    for g, (_, ev) in enumerate(evals):
        f = ev.fitness
        assert f.shape == (12,) and ev.terms.shape == (12, 3, 4)
        assert f.max() == reference["best"][g] == reference["max"][g]
        assert f.min() == reference["min"][g]
        assert f.mean() == pytest.approx(reference["mean"][g], abs=1e-12)
        assert f.std() == pytest.approx(reference["std"][g], abs=1e-12)
        # F is the mean over the rooms of the per-room TSK F of the terms.
        per_room = fm.fuzzy_fitness(problem.motivations, ev.terms.reshape(-1, 4)).reshape(12, 3)
        np.testing.assert_allclose(per_room.mean(axis=1), f, rtol=0, atol=1e-12)
    best = ga.best
    assert best.fitness == max(reference["best"])
    assert best.genome.shape == (68,)


def test_same_bytes_on_one_or_many_threads(config):
    genomes = fm.GA(fm.Problem(config, TINY)).ask()
    results = [
        fm.Problem(config, TINY, threads=t).evaluate(genomes, generation=3, descriptors=True)
        for t in (1, 3)
    ]
    for a, b in zip(results[0], results[1]):
        assert a.tobytes() == b.tobytes()


def test_generation_and_seed_choose_the_noise(problem, config):
    genomes = fm.GA(problem).ask()[:4]
    f0 = problem.evaluate(genomes).fitness
    assert problem.evaluate(genomes, generation=0).fitness.tobytes() == f0.tobytes()
    assert problem.evaluate(genomes, generation=1).fitness.tobytes() != f0.tobytes()
    other = problem.evaluate(genomes, seed=8).fitness
    assert other.tobytes() != f0.tobytes()
    # seed=8 is the problem built with seed 8.
    assert fm.Problem(config, TINY, seed=8).evaluate(genomes).fitness.tobytes() == other.tobytes()
    assert problem.evaluate(genomes, seed=7).fitness.tobytes() == f0.tobytes()


def test_descriptors(problem):
    genomes = fm.GA(problem).ask()
    plain = problem.evaluate(genomes, generation=2)
    assert plain.descriptors is None
    ev = problem.evaluate(genomes, generation=2, descriptors=True)
    # Asking for descriptors changes no F or term.
    assert ev.fitness.tobytes() == plain.fitness.tobytes()
    assert ev.terms.tobytes() == plain.terms.tobytes()
    d = ev.descriptors
    assert d.shape == (12, 3, len(fm.DESCRIPTORS)) == (12, 3, 9)
    assert ((d >= 0) & (d <= 1)).all()
    names = list(fm.DESCRIPTORS)
    np.testing.assert_array_equal(d[..., names.index("a")], ev.terms[..., 0])
    np.testing.assert_array_equal(d[..., names.index("g")], ev.terms[..., 1])
    np.testing.assert_array_equal(d[..., names.index("b")], ev.terms[..., 3])
    np.testing.assert_allclose(d[..., 5:].sum(axis=-1), 1.0, atol=1e-12)
    sel = problem.evaluate(genomes, generation=2, descriptors=["turn180", "x"]).descriptors
    np.testing.assert_array_equal(sel, d[..., [8, 0]])
    one = problem.evaluate(genomes, generation=2, descriptors="y").descriptors
    np.testing.assert_array_equal(one, d[..., [1]])


def test_descriptors_in_range():
    """x, y in the room's box, action fractions summing to 1 (the library's unit test checks
    them against the recorded trajectory on the same stream)."""
    p = fm.Problem(overrides={"rooms": ["square", "T"], "trial.steps": 60, "aem.enabled": False})
    rng = np.random.default_rng(0)
    d = p.evaluate(rng.uniform(-1, 1, (20, p.genome_size)), descriptors=True).descriptors
    assert d.shape == (20, 2, 9)
    assert ((d >= 0) & (d <= 1)).all()
    assert len(np.unique(d[:, 0, 0])) > 1 and len(np.unique(d[:, 1, 1])) > 1
    np.testing.assert_allclose(d[..., 5:].sum(axis=-1), 1.0, atol=1e-12)
    # With `actions` motion b = executed / T, so each fraction is a count over b·T steps.
    counts = d[..., 5:] * (d[..., 4:5] * 60)
    np.testing.assert_allclose(counts, np.round(counts), atol=1e-9)


def test_per_room_problems(config):
    per_room = dict(TINY, training="per-room")
    with pytest.raises(fm.FuzzymotivError, match="room.*per-room"):
        fm.Problem(config, per_room)
    with pytest.raises(fm.FuzzymotivError, match="room: no room 'X'|room: no room \"X\""):
        fm.Problem(config, per_room, room="X")
    with pytest.raises(fm.FuzzymotivError, match="room=.*per-room"):
        fm.Problem(config, TINY, room="H")
    reference = columns(fm.run(config, per_room, threads=2).generations)
    for room in ["H", "U"]:
        p = fm.Problem(config, per_room, room=room)
        assert p.rooms == [room] and p.run == room
        ga = fm.GA(p)
        drive(p, ga, 5)
        mine = columns(ga.history)
        rows = [i for i, r in enumerate(reference["room"]) if r == room]
        for c in COLUMNS:
            assert mine[c] == [reference[c][i] for i in rows], (room, c)


def test_state_round_trip(problem):
    ga = fm.GA(problem)
    drive(problem, ga, 2)
    state = ga.state
    assert state["format"] == "fuzzymotiv.GA" and state["version"] == 1
    assert state["generation"] == 2 and len(state["population"]) == 12
    assert all(isinstance(w, float) for w in state["population"][0])
    restored = fm.GA.from_state(json.loads(json.dumps(state)), problem)
    alone = fm.GA.from_state(json.loads(json.dumps(state)))  # from the state's own config
    assert restored.state == state == alone.state
    assert restored.ask().tobytes() == ga.ask().tobytes()
    drive(problem, ga, 3)
    drive(problem, restored, 3)
    drive(alone.problem, alone, 3)
    assert restored.state == ga.state == alone.state
    assert columns(restored.history) == columns(ga.history)


def test_warm_start_and_tell_without_terms(problem):
    start = np.full((3, problem.genome_size), 0.25)
    ga = fm.GA(problem, genomes=start)
    assert ga.ask().tobytes() == start.tobytes()
    ev = problem.evaluate(ga.ask())
    ga.tell(ev.fitness)
    assert ga.ask().shape == (12, problem.genome_size)  # the config's population from then on
    h = columns(ga.history)
    assert np.isnan(h["a"][0]) and h["best"][0] == ev.fitness.max()
    state = ga.state
    assert state["history"][0]["terms"] is None
    assert columns(fm.GA.from_state(state, problem).history)["mean"] == h["mean"]


def test_other_seed_ga(problem, config):
    ga = fm.GA(problem, seed=11)
    assert ga.seed == 11
    same = fm.GA(fm.Problem(config, TINY, seed=11))
    assert ga.ask().tobytes() == same.ask().tobytes()
    assert ga.ask().tobytes() != fm.GA(problem).ask().tobytes()


@pytest.mark.parametrize(
    "genomes, match",
    [
        (np.zeros((2, 60)), r"genomes: expected a \(population, 68\) array.*shape \(2, 60\)"),
        (np.zeros(68), r"genomes: expected a \(population, 68\) array, got an array of shape \(68,\)"),
        (np.zeros((2, 2, 68)), r"genomes: .*shape \(2, 2, 68\)"),
        ([[1.0, "x"]], r"genomes: expected"),
        (np.where(np.eye(2, 68) > 0, np.nan, 0.0), r"genomes: `nan` \(row 0, weight 0\)"),
        (np.full((1, 68), np.inf), r"genomes: `inf` \(row 0, weight 0\)"),
    ],
)
def test_bad_genomes(problem, genomes, match):
    with pytest.raises(fm.FuzzymotivError, match=match):
        problem.evaluate(genomes)


def test_bad_arguments(problem):
    g = np.zeros((2, 68))
    with pytest.raises(fm.FuzzymotivError, match="generation"):
        problem.evaluate(g, generation=-1)
    with pytest.raises(fm.FuzzymotivError, match="generation"):
        problem.evaluate(g, generation=1.5)
    with pytest.raises(fm.FuzzymotivError, match="seed"):
        problem.evaluate(g, seed=-3)
    with pytest.raises(fm.FuzzymotivError, match="descriptors: unknown descriptor 'z'|descriptors: unknown descriptor \"z\""):
        problem.evaluate(g, descriptors=["x", "z"])
    with pytest.raises(fm.FuzzymotivError, match="threads"):
        fm.Problem(overrides={"rooms": ["H"], "aem.enabled": False}, threads=0)
    ga = fm.GA(problem)
    ga.ask()
    with pytest.raises(fm.FuzzymotivError, match=r"F: expected 12 values .*got 3"):
        ga.tell(np.zeros(3))
    with pytest.raises(fm.FuzzymotivError, match=r"F: `nan` \(individual 1\)"):
        ga.tell(np.where(np.arange(12) == 1, np.nan, 0.0))
    with pytest.raises(fm.FuzzymotivError, match=r"terms: expected shape \(12, 3, 4\)"):
        ga.tell(np.zeros(12), np.zeros((12, 2, 4)))
    with pytest.raises(fm.FuzzymotivError, match="F: expected one value per genome"):
        ga.tell(np.zeros((12, 1)))
    assert ga.generation == 0  # nothing was told
    with pytest.raises(fm.FuzzymotivError, match="genomes: a population needs at least one genome"):
        fm.GA(problem, genomes=np.zeros((0, 68)))
    with pytest.raises(fm.FuzzymotivError, match="genomes: expected a"):
        fm.GA(problem, genomes=np.zeros((2, 5)))
    state = ga.state
    with pytest.raises(fm.FuzzymotivError, match="version"):
        fm.GA.from_state(dict(state, version=99), problem)
    with pytest.raises(fm.FuzzymotivError, match="state: genome 0"):
        fm.GA.from_state(dict(state, population=[[0.0] * 5]), problem)
    with pytest.raises(fm.FuzzymotivError, match="state"):
        fm.GA.from_state({"format": "x"}, problem)
    other = fm.Problem(overrides={"rooms": ["H"], "aem.enabled": False})
    with pytest.raises(fm.FuzzymotivError, match="problem: its config"):
        fm.GA.from_state(state, other)


def test_tell_before_ask_is_refused_and_breeds_nothing(problem):
    ga = fm.GA(problem)
    with pytest.raises(fm.FuzzymotivError, match=r"tell: call ask\(\) first.*generation 0"):
        ga.tell(np.zeros(12))
    assert ga.generation == 0 and ga.best is None and len(ga.state["history"]) == 0
    drive(problem, ga, 1)
    assert ga.generation == 1


def test_tell_twice_after_one_ask_is_refused(problem):
    ga = fm.GA(problem)
    ev = problem.evaluate(ga.ask(), generation=ga.generation, seed=ga.seed)
    ga.tell(ev.fitness)
    state = ga.state
    with pytest.raises(fm.FuzzymotivError, match=r"tell: call ask\(\) first.*generation 1"):
        ga.tell(ev.fitness)
    assert ga.state == state  # nothing bred
    restored = fm.GA.from_state(state, problem)  # a restored GA is asked again, too
    with pytest.raises(fm.FuzzymotivError, match=r"tell: call ask\(\) first"):
        restored.tell(ev.fitness)


def test_a_failed_tell_keeps_the_ask(problem):
    """A tell refused for its F can be repeated with the right F without asking again."""
    ga = fm.GA(problem)
    genomes = ga.ask()
    with pytest.raises(fm.FuzzymotivError, match="F: expected 12 values"):
        ga.tell(np.zeros(3))
    ev = problem.evaluate(genomes, generation=ga.generation, seed=ga.seed)
    ga.tell(ev.fitness)
    assert ga.generation == 1


@pytest.mark.parametrize(
    "dtype, kind",
    [(np.complex128, "complex numbers"), (object, "Python objects"), (str, "strings"), (bool, "booleans")],
)
def test_evaluate_refuses_genomes_that_are_not_real_numbers(problem, dtype, kind):
    genomes = np.zeros((2, problem.genome_size)).astype(dtype)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no ComplexWarning either: an error, not a warning
        with pytest.raises(fm.FuzzymotivError) as e:
            problem.evaluate(genomes)
    assert str(e.value).startswith(
        f"genomes: expected a (population, 68) array of real numbers (float64), got {kind} (dtype "
    )


def test_ga_refuses_genomes_fitness_and_terms_that_are_not_real_numbers(problem):
    complex_genomes = np.zeros((2, problem.genome_size), dtype=complex)
    with pytest.raises(fm.FuzzymotivError, match=r"genomes: .*got complex numbers \(dtype complex128\)"):
        fm.GA(problem, genomes=complex_genomes)
    ga = fm.GA(problem)
    ga.ask()
    with pytest.raises(fm.FuzzymotivError, match=r"F: .*real numbers \(float64\), got complex"):
        ga.tell(np.zeros(12) + 0.5j)
    with pytest.raises(fm.FuzzymotivError, match=r"F: .*got strings"):
        ga.tell(["0.5"] * 12)
    with pytest.raises(fm.FuzzymotivError, match=r"terms: .*got complex numbers"):
        ga.tell(np.zeros(12), np.zeros((12, 3, 4), dtype=complex))
    assert ga.generation == 0


def test_simulate_and_fuzzy_fitness_refuse_values_that_are_not_real_numbers():
    with pytest.raises(fm.FuzzymotivError, match=r"genome: .*got complex numbers"):
        fm.simulate(np.zeros(68, dtype=complex), "H", seed=1, overrides={"trial.steps": 5})
    with pytest.raises(fm.FuzzymotivError, match=r"terms: .*got strings"):
        fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], ["0.5", "0", "0", "0"])
    with pytest.raises(fm.FuzzymotivError, match=r"genome: .*got Python objects"):
        fm.frames(np.zeros(68, dtype=object), "H")
