"""Tables (RunResult.generations and .rooms, GA.history, SweepResult.results and .aggregate)
are one type whatever is installed: fm.Table, a dict of numpy arrays."""

import sys

import numpy as np
import pytest

import fuzzymotiv as fm
from fuzzymotiv.tables import read_table

TINY = {"ga.population": 4, "ga.generations": 2, "trial.steps": 20, "rooms": ["H", "T"],
        "aem.enabled": False}


@pytest.mark.parametrize("pandas", [True, False], ids=["with-pandas", "numpy-only"])
def test_run_and_ga_tables_are_dicts_of_numpy_arrays_whatever_is_installed(monkeypatch, pandas):
    if pandas:
        pytest.importorskip("pandas")
    else:
        monkeypatch.setitem(sys.modules, "pandas", None)
    res = fm.run(overrides=TINY, seed=3)
    for table in (res.generations, res.rooms):
        assert type(table) is fm.Table
        assert all(isinstance(v, np.ndarray) for v in table.values())
    assert list(res.generations)[:3] == ["generation", "best", "mean"]
    assert res.generations.rows == 2 and res.generations["best"].dtype == np.float64
    assert list(res.rooms["room"]) == ["H", "T"]
    ga = fm.GA(fm.Problem(overrides=TINY))
    ev = ga.problem.evaluate(ga.ask(), generation=ga.generation, seed=ga.seed)
    ga.tell(ev.fitness, ev.terms)
    assert type(ga.history) is fm.Table and ga.history.rows == 1


def test_a_csv_table_reads_numbers_as_float64_and_text_as_str(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("setting,room,F,n\nC=1,H,0.5,3\nC=0,T,,4\n")
    t = read_table(path)
    assert list(t) == ["setting", "room", "F", "n"] and t.rows == 2
    assert t["room"].tolist() == ["H", "T"] and t["n"].tolist() == [3.0, 4.0]
    assert t["F"][0] == 0.5 and np.isnan(t["F"][1])


def test_dataframe_attributes_of_a_table_still_work_with_a_deprecation_warning():
    pd = pytest.importorskip("pandas")
    table = fm.Table({"best": np.array([0.25, 0.5]), "room": np.array(["H", "T"])})
    with pytest.warns(DeprecationWarning, match="to_pandas"):
        assert table.iloc[-1]["best"] == 0.5
    with pytest.warns(DeprecationWarning):
        assert list(table.columns) == ["best", "room"]
    assert isinstance(table.to_pandas(), pd.DataFrame)
    with pytest.raises(AttributeError):
        table.no_such_attribute


def test_to_pandas_without_pandas_raises_dependency_not_installed(monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(fm.DependencyNotInstalled, match="pip install pandas"):
        fm.Table({"x": np.zeros(2)}).to_pandas()
