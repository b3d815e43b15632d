"""NaN and infinities, bad threads and seeds raise FuzzymotivError with the CLI's
words; file-system failures raise FuzzymotivOSError, both a FuzzymotivError and an OSError."""

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import run_cli

NAN, INF = float("nan"), float("inf")
X = [0.8, 0.1, 0.0, 0.1]
SEED_WORDS = "is not a seed; a seed is a whole number from 0 to 9007199254740991 (2^53 − 1)"


def refused(call, message):
    with pytest.raises(fm.FuzzymotivError) as e:
        call()
    assert str(e.value) == message
    return e.value


def test_nan_and_inf_in_fuzzy_fitness_are_refused_naming_argument_position_value(cli):
    e = refused(
        lambda: fm.fuzzy_fitness(X, [NAN, 1, 1, 1]),
        "terms: `nan` (a) is not a finite number; expected four numbers (a, g, l, b)",
    )
    # The CLI's words for the same input.
    p = run_cli(cli, "fuzzy", "--motivations", "0.8,0.1,0,0.1", "--fitness", "nan,1,1,1", check=False)
    assert p.returncode == 2
    assert p.stderr.startswith("error: --fitness: `nan` (a) is not a finite number; expected four")
    assert str(e).startswith("terms: `nan` (a) is not a finite number; expected four")
    refused(
        lambda: fm.fuzzy_fitness(X, [1, 1, 1, -INF], explain=True),
        "terms: `-inf` (b) is not a finite number; expected four numbers (a, g, l, b)",
    )
    refused(
        lambda: fm.fuzzy_fitness([0.8, NAN, 0, 0.1], [1, 1, 1, 1]),
        "motivations: `nan` (H) is not a finite number; expected four numbers (C, H, O, E)",
    )
    refused(
        lambda: fm.fuzzy_fitness({"curiosity": INF}, [1]),
        "motivations: `inf` (curiosity) is not a finite number; expected 1 numbers (curiosity)",
    )
    many = np.ones((5, 4))
    many[3, 2] = INF
    for explain in (False, True):
        refused(
            lambda: fm.fuzzy_fitness(X, many, explain=explain),
            "terms: `inf` (row 3, l) is not a finite number; expected an n × 4 array of (a, g, l, b)",
        )
    refused(
        lambda: fm.fuzzy_fitness(X, [1, 1, 1, 1], peaks=[0, NAN, 1]),
        "peaks: `nan` (peak 1) is not a finite number; expected increasing numbers in [0, 1]",
    )
    refused(
        lambda: fm.fuzzy_fitness(X, [1, 1, 1, 1], peaks=[0, 1], coefficients=[0, INF]),
        'coefficients: `inf` (coefficient 1) is not a finite number; expected "linear", "ratio" or a list of numbers',
    )
    refused(
        lambda: fm.export_fll([NAN, 0.1, 0, 0.1]),
        "motivations: `nan` (C) is not a finite number; expected four numbers (C, H, O, E)",
    )


def test_nan_genome_in_simulate_is_refused():
    refused(
        lambda: fm.simulate(np.full(68, NAN), "H", seed=1),
        "genome: `nan` (weight 0) is not a finite number; expected the network's weights",
    )
    g = np.zeros(68)
    g[41] = -INF
    refused(
        lambda: fm.simulate(g, "H", seed=1),
        "genome: `-inf` (weight 41) is not a finite number; expected the network's weights",
    )


def test_seeds_are_whole_numbers_below_2_53(cli, repo):
    for seed, text in [(-1, "-1"), (2**53, "9007199254740992"), (2**64, "18446744073709551616"), (1.5, "1.5"), (True, "True")]:
        refused(lambda: fm.simulate(np.zeros(68), "H", seed=seed), f"seed: `{text}` {SEED_WORDS}")
        refused(lambda: fm.run(seed=seed), f"seed: `{text}` {SEED_WORDS}")
    p = run_cli(cli, "run", repo / "configs/tiny.toml", "--seed=-1", check=False)
    assert p.returncode == 2 and f"`-1` {SEED_WORDS}" in p.stderr
    tr = fm.simulate(np.zeros(68), "H", seed=np.int64(2**53 - 1), overrides={"trial.steps": 5})
    assert tr["seed"] == 2**53 - 1
    res = fm.run(repo / "configs/tiny.toml", {"ga.generations": 1, "trial.steps": 20, "aem.enabled": False}, seed=2**53 - 1)
    assert res.summary["seed"] == 2**53 - 1


def test_threads_are_a_whole_number_from_1_to_256(repo):
    refused(lambda: fm.run(threads=0), "threads must be at least 1, got 0")
    refused(lambda: fm.run(threads=-1), "threads must be at least 1, got -1")
    refused(lambda: fm.run(threads=257), "threads must be at most 256, got 257")
    refused(lambda: fm.run(threads=2**70), f"threads must be at most 256, got {2**70}")
    refused(lambda: fm.run(threads=2.0), "threads must be a whole number from 1 to 256, got 2.0")
    refused(lambda: fm.run(threads=True), "threads must be a whole number from 1 to 256, got True")
    res = fm.run(repo / "configs/tiny.toml", {"ga.generations": 1, "trial.steps": 20, "aem.enabled": False}, threads=np.int32(1))
    assert res.generations.rows == 1


def test_file_system_failures_are_os_errors(cli, repo, tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    with pytest.raises(OSError) as e:
        fm.run(repo / "configs/tiny.toml", {"ga.generations": 1, "trial.steps": 20}, out=blocker / "run")
    assert isinstance(e.value, fm.FuzzymotivError) and isinstance(e.value, fm.FuzzymotivOSError)
    assert type(e.value).__name__ == "FuzzymotivOSError"
    assert str(e.value).startswith(f"{blocker / 'run.partial'}: ")
    p = run_cli(cli, "run", repo / "configs/tiny.toml", "--set", "ga.generations=1", "--out", blocker / "run", check=False)
    assert p.returncode == 1 and p.stderr.strip().splitlines()[-1] == f"error: {e.value}"
    with pytest.raises(fm.FuzzymotivOSError) as e:
        fm.export_fll(X, blocker / "hc.fll")
    assert isinstance(e.value, OSError) and isinstance(e.value, fm.FuzzymotivError)
    # Bad input stays a plain FuzzymotivError (a ValueError), not an OSError.
    with pytest.raises(fm.FuzzymotivError) as e:
        fm.fuzzy_fitness(X, [NAN, 1, 1, 1])
    assert not isinstance(e.value, OSError)


def test_overrides_of_another_type_and_table_overrides(repo):
    """overrides that are neither a dict nor strings are named; a dict of tables sets only the
    keys it names (the config's others stay), as dotted keys do."""
    refused(
        lambda: fm.Problem(repo / "configs/tiny.toml", 5),
        'overrides: expected a dict of dotted keys (e.g. {"ga.population": 20}) or a list of '
        '"key=value" strings, got int',
    )
    tiny = fm.Problem(repo / "configs/tiny.toml")
    nested = fm.Problem(repo / "configs/tiny.toml", {"ga": {"generations": 3}, "trial": {"noise": 0.0}})
    assert (nested.population, nested.steps) == (tiny.population, tiny.steps)
    with pytest.raises(fm.FuzzymotivError, match="one value per override"):
        fm.Problem(repo / "configs/tiny.toml", ["ga.population=4\ntrial.steps=5"])


def test_descriptors_and_problem_arguments_are_named(repo):
    p = fm.Problem(repo / "configs/tiny.toml", {"trial.steps": 20})
    g = np.zeros((2, p.genome_size))
    with pytest.raises(fm.FuzzymotivError, match="descriptors: expected None, True, a name"):
        p.evaluate(g, descriptors=3)
    with pytest.raises(fm.FuzzymotivError, match="problem: expected a fuzzymotiv.Problem, got str"):
        fm.GA.from_state(fm.GA(p).state, "p")
