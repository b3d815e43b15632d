"""The TSK motivation fitness: the worked values of docs/model.md §8, the CLI, vectorisation, explain, errors, FLL."""

import doctest
import os

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import run_cli

WORKED = [
    ([0.8, 0.1, 0.0, 0.1], [0.95, 0.5, 0.0, 0.79], 0.797220),
    ([0.5, 0.3, 0.0, 0.2], [0.55, 0.3, 0.0, 0.58], 0.263309),
    ([0.25, 0.25, 0.25, 0.25], [1.0, 1.0, 1.0, 1.0], 1.0),
]


@pytest.mark.parametrize("x,y,expected", WORKED)
def test_worked_values_match_spec_and_cli(cli, x, y, expected):
    f = fm.fuzzy_fitness(x, y)
    assert isinstance(f, float)
    assert f == pytest.approx(expected, abs=5e-7)
    out = run_cli(cli, "fuzzy", "--motivations", ",".join(map(str, x)), "--fitness", ",".join(map(str, y)))
    # The CLI prints F with 12 decimals.
    assert out.stdout.splitlines()[0] == f"{f:.12f}"


def test_vectorised_equals_scalar_and_has_shape():
    rng = np.random.default_rng(5)
    y = rng.random((300, 4)) * 1.2 - 0.1  # some out of [0, 1]: clamped
    x = [0.5, 0.3, 0.0, 0.2]
    many = fm.fuzzy_fitness(x, y)
    assert isinstance(many, np.ndarray) and many.shape == (300,) and many.dtype == np.float64
    one_by_one = np.array([fm.fuzzy_fitness(x, row) for row in y])
    assert np.array_equal(many, one_by_one)
    # Worked values through the vectorised path; Fortran-ordered and integer input too.
    ys = np.asfortranarray([w[1] for w in WORKED[:2]])
    assert fm.fuzzy_fitness(x, ys)[1] == pytest.approx(0.263309, abs=5e-7)
    assert fm.fuzzy_fitness(x, np.ones((2, 4), dtype=int)).tolist() == [1.0, 1.0]
    assert fm.fuzzy_fitness(x, np.empty((0, 4))).shape == (0,)


def test_explain_lists_the_firing_rules():
    e = fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [0.95, 0.5, 0, 0.79], explain=True)
    assert e["fitness"] == fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [0.95, 0.5, 0, 0.79])
    assert len(e["rules"]) == 4
    assert sum(r["weight"] for r in e["rules"]) == pytest.approx(e["weight_sum"])
    f = sum(r["weight"] * r["output"] for r in e["rules"]) / e["weight_sum"]
    assert f == pytest.approx(e["fitness"], abs=1e-15)
    assert "if a is V.H. and g is M and l is V.L. and b is H" in e["text"]
    one = fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [1, 0.25, 0, 0], explain=True)
    assert [(r["number"], r["label_names"]) for r in one["rules"]] == [(10, ["V.H.", "L", "V.L.", "V.L."])]
    many = fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [[1, 0.25, 0, 0], [1, 1, 1, 1]], explain=True)
    assert [len(m["rules"]) for m in many] == [1, 1]


def test_motivations_as_dict_and_custom_fuzzy_settings():
    d = {"curiosity": 0.8, "homing": 0.1, "orientation": 0, "energy": 0.1}
    assert fm.fuzzy_fitness(d, [0.95, 0.5, 0, 0.79]) == fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [0.95, 0.5, 0, 0.79])
    r = fm.fuzzy_fitness([0.25] * 4, [1, 1, 1, 1], coefficients="ratio")
    assert r == pytest.approx(1.0)
    assert fm.fuzzy_fitness([0.25] * 4, [1, 1, 1, 1], peaks=[0, 1], coefficients=[0, 0.5]) == pytest.approx(0.5)


def test_errors_are_value_errors_naming_the_field(cli):
    with pytest.raises(fm.FuzzymotivError) as e:
        fm.fuzzy_fitness([0.8, 0.1, 0, 0.2], [0.5] * 4)
    assert isinstance(e.value, ValueError)
    msg = str(e.value)
    assert msg.startswith("motivations: motivations must sum to 1, got 1.1")
    # Same text as the CLI (which names its option instead of the argument).
    p = run_cli(cli, "fuzzy", "--motivations", "0.8,0.1,0,0.2", "--fitness", "0.5,0.5,0.5,0.5", check=False)
    assert p.returncode == 2
    assert p.stderr.strip() == "error: --" + msg
    with pytest.raises(ValueError, match="homing must be a number in"):
        fm.fuzzy_fitness([0.5, -0.1, 0.3, 0.3], [0.5] * 4)
    with pytest.raises(ValueError, match="terms: expected four values"):
        fm.fuzzy_fitness([0.25] * 4, [0.5] * 3)
    with pytest.raises(ValueError, match=r"n × 4"):
        fm.fuzzy_fitness([0.25] * 4, np.zeros((3, 5)))
    with pytest.raises(ValueError, match="fuzzy.peaks must be strictly increasing"):
        fm.fuzzy_fitness([0.25] * 4, [0.5] * 4, peaks=[0, 0.5, 0.5, 1])
    with pytest.raises(ValueError, match="coefficients: expected"):
        fm.fuzzy_fitness([0.25] * 4, [0.5] * 4, coefficients="cubic")


SETTINGS = [
    [0.8, 0.1, 0.0, 0.1],
    [0.5, 0.3, 0.0, 0.2],
    [0.25, 0.25, 0.25, 0.25],
    [0.1, 0.2, 0.3, 0.4],
    [0.0, 0.0, 1.0, 0.0],
]


@pytest.mark.parametrize("x", SETTINGS)
def test_fll_in_pyfuzzylite_gives_our_f(x):
    fl = pytest.importorskip("fuzzylite")
    text = fm.export_fll(x)
    engine = fl.FllImporter().from_string(text)
    assert len(engine.rule_blocks[0].rules) == 625
    rng = np.random.default_rng(int(sum(v * 1000 for v in x)))
    y = rng.random((250, 4))
    y[:10] = np.round(y[:10] * 4) / 4  # exactly on the peaks
    y[10:20] = y[10:20] * 1.4 - 0.2  # outside [0, 1]: clamped by both
    for i, name in enumerate("aglb"):
        engine.input_variable(name).value = y[:, i]
    engine.process()
    theirs = np.asarray(engine.output_variable("F").value, dtype=float)
    ours = fm.fuzzy_fitness(x, y)
    assert theirs.shape == ours.shape == (250,)
    assert np.max(np.abs(theirs - ours)) < 1e-9


def test_fll_with_custom_peaks_in_pyfuzzylite():
    fl = pytest.importorskip("fuzzylite")
    x, peaks = [0.4, 0.3, 0.2, 0.1], [0.1, 0.3, 0.35, 0.9]
    text = fm.export_fll(x, peaks=peaks, coefficients="ratio")
    assert "Trapezoid" in text and text.count("\n  rule: ") == 256
    engine = fl.FllImporter().from_string(text)
    y = np.random.default_rng(3).random((200, 4))
    for i, name in enumerate("aglb"):
        engine.input_variable(name).value = y[:, i]
    engine.process()
    ours = fm.fuzzy_fitness(x, y, peaks=peaks, coefficients="ratio")
    assert np.max(np.abs(np.asarray(engine.output_variable("F").value) - ours)) < 1e-9


def test_export_fll_file_equals_cli_and_refuses_overwrite(cli, tmp_path):
    ours = tmp_path / "hc.fll"
    text = fm.export_fll([0.8, 0.1, 0, 0.1], ours)
    assert ours.read_text() == text
    theirs = tmp_path / "cli" / "hc.fll"
    theirs.parent.mkdir()
    run_cli(cli, "fuzzy", "--motivations", "0.8,0.1,0,0.1", "--export-fll", theirs)
    assert theirs.read_text() == text
    with pytest.raises(ValueError, match=r"exists with other contents.*force=True"):
        fm.export_fll([0.5, 0.3, 0, 0.2], ours)
    assert ours.read_text() == text
    fm.export_fll([0.8, 0.1, 0, 0.1], ours)  # the same text again: nothing to do
    fm.export_fll([0.5, 0.3, 0, 0.2], ours, force=True)
    assert "(0.5,0.3,0,0.2)" in ours.read_text()
    assert not list(tmp_path.glob(".tmp*"))


def test_export_fll_never_replaces_what_is_not_a_regular_file(tmp_path):
    """The output guard, as save_gif and the CLI: with force=True too, a directory, a link and a
    FIFO stay what they are."""
    fifo, link, folder = tmp_path / "f.fll", tmp_path / "l.fll", tmp_path / "d.fll"
    os.mkfifo(fifo)
    (tmp_path / "target.txt").write_text("mine")
    link.symlink_to(tmp_path / "target.txt")
    folder.mkdir()
    for path, what in [(fifo, "FIFO"), (link, "link"), (folder, "directory")]:
        with pytest.raises(fm.FuzzymotivError, match=what):
            fm.export_fll([0.8, 0.1, 0, 0.1], path, force=True)
    assert fifo.is_fifo() and link.is_symlink() and folder.is_dir()
    assert (tmp_path / "target.txt").read_text() == "mine"


def test_docstring_examples_run():
    """The examples in the docstrings of the package and of each of its topic modules."""
    import fuzzymotiv.config
    import fuzzymotiv.fuzzy
    import fuzzymotiv.optimisers
    import fuzzymotiv.rollouts

    total = 0
    for module in (fm, fm.fuzzy, fm.config, fm.rollouts, fm.optimisers):
        failures, tried = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
        assert failures == 0, module.__name__
        total += tried
    assert total >= 20


def test_fll_with_five_motivations_agrees_with_pyfuzzylite_and_the_cli(cli, tmp_path):
    """N = 5 (the paper's four and urgency): the CLI's FLL export, evaluated by pyfuzzylite,
    gives the F of `fuzzymotiv fuzzy --fitness name=value,…` to 1e-9."""
    fl = pytest.importorskip("fuzzylite")
    x = "curiosity=0.5,homing=0.1,orientation=0,energy=0.1,urgency=0.3"
    path = tmp_path / "five.fll"
    run_cli(cli, "fuzzy", "--motivations", x, "--export-fll", path)
    engine = fl.FllImporter().from_string(path.read_text())
    assert len(engine.rule_blocks[0].rules) == 5**5
    names = ["a", "g", "l", "b", "urgency"]
    y = np.random.default_rng(5).random((12, 5))
    y[:3] = np.round(y[:3] * 4) / 4  # exactly on the peaks
    y[3] = [0, 1, 0, 1, 0]
    for i, name in enumerate(names):
        engine.input_variable(name).value = y[:, i]
    engine.process()
    theirs = np.asarray(engine.output_variable("F").value, dtype=float)
    for row, f in zip(y, theirs):
        values = ",".join(f"{n}={v!r}" for n, v in zip(names, row))
        out = run_cli(cli, "fuzzy", "--motivations", x, "--fitness", values).stdout
        assert abs(float(out.split()[0]) - f) < 1e-9, (values, out, f)


def test_a_dict_of_paper_motivations_means_exactly_those_named(cli):
    # As `fuzzymotiv fuzzy --motivations curiosity=0.7,homing=0.3` and a config's
    # [motivations]: two motivations (nothing of the paper's four added), Y of two terms in the
    # dict's order.
    x = {"curiosity": 0.7, "homing": 0.3}
    for a, g in [(0.95, 0.5), (0.2, 0.9), (1, 0)]:
        p = run_cli(cli, "fuzzy", "--motivations", "curiosity=0.7,homing=0.3", "--fitness", f"a={a},g={g}")
        want = float(p.stdout.split()[0])
        assert f"{fm.fuzzy_fitness(x, [a, g]):.12f}" == f"{want:.12f}"
        assert f"{fm.fuzzy_fitness({'homing': 0.3, 'curiosity': 0.7}, [g, a]):.12f}" == f"{want:.12f}"
        assert fm.fuzzy_fitness(x, [[a, g]])[0] == fm.fuzzy_fitness(x, [a, g])
    assert len(fm.fuzzy_fitness(x, [1, 0.25], explain=True)["rules"][0]["labels"]) == 2
    with pytest.raises(fm.FuzzymotivError, match=r"terms: expected 2 values \(a, g\)"):
        fm.fuzzy_fitness(x, [0.95, 0.5, 0, 0.79])
    fll = fm.export_fll(x)
    assert fll == run_cli(cli, "fuzzy", "--motivations", "curiosity=0.7,homing=0.3", "--export-fll", "-").stdout
    assert fll.count("\n  rule: ") == 25


def test_fuzzy_fitness_takes_the_engines_eight_motivations(cli):
    """Issue #56: fm.fuzzy_fitness takes as many motivations as the engine (eight: the paper's
    four and goal, safety, urgency, waypoints), giving the CLI's F; unnamed weights x1…x8 the
    same F; a ninth is refused; the paper's four-argument call stays as it was."""
    names = ["curiosity", "homing", "orientation", "energy", "goal", "safety", "urgency", "waypoints"]
    terms = ["a", "g", "l", "b", "goal", "safety", "urgency", "waypoints"]
    w = [0.2, 0.1, 0.1, 0.1, 0.2, 0.1, 0.1, 0.1]
    y = [0.9, 0.5, 0.25, 0.75, 1.0, 0.3, 0.6, 0.0]
    x = dict(zip(names, w))
    motivations = ",".join(f"{n}={v}" for n, v in x.items())
    fitness = ",".join(f"{t}={v}" for t, v in zip(terms, y))
    out = run_cli(cli, "fuzzy", "--motivations", motivations, "--fitness", fitness)
    f = fm.fuzzy_fitness(x, y)
    assert f"{f:.12f}" == out.stdout.split()[0]
    assert fm.fuzzy_fitness(w, y) == f
    assert fm.fuzzy_fitness(w, [y, y]).tolist() == [f, f]
    with pytest.raises(fm.FuzzymotivError, match=r"expected 1 to 8 weights"):
        fm.fuzzy_fitness(w + [0.0], y + [0.0])
    assert fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [0.95, 0.5, 0, 0.79]) == pytest.approx(0.797220, abs=5e-7)
