"""Tables (``generations.csv``, the rooms table, a sweep's ``results.csv``...) as returned by
:func:`fuzzymotiv.run`, :attr:`fuzzymotiv.GA.history` and :func:`fuzzymotiv.merge`.

One return type whatever is installed: a :class:`Table`, a dict of numpy arrays (column name →
one value per row). Why numpy and not pandas: the wheel needs only numpy, and a result whose
type depends on what else happens to be installed breaks code that moves to another machine;
numpy arrays are what the optimisers (CMA-ES, MAP-Elites, the GA's ask/tell) and plotting take.
``table.to_pandas()`` gives a DataFrame when pandas is installed.

Until 0.1 these were DataFrames when pandas was installed: for one release a DataFrame's
attributes (``.iloc``, ``.columns``, ``.equals``, ``.plot``, ...) still work on a Table, through
``to_pandas()``, with a DeprecationWarning. (``len()`` is a dict's: the number of columns;
:attr:`Table.rows` is the number of rows.)
"""

from __future__ import annotations

import csv
import os
import warnings
from typing import Any, Dict, Mapping, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._fuzzymotiv import DependencyNotInstalled

__all__ = ["Table"]


class Table(Dict[str, npt.NDArray[Any]]):
    """A table as its columns: a dict from column name to a numpy array (float64 for numbers,
    str for text), every column one value per row, in the file's column order."""

    @property
    def rows(self) -> int:
        """The number of rows."""
        return len(next(iter(self.values()))) if self else 0

    def to_pandas(self) -> Any:
        """The table as a pandas DataFrame (DependencyNotInstalled without pandas)."""
        try:
            import pandas as pd
        except ImportError:
            raise DependencyNotInstalled(
                "to_pandas() needs pandas (pip install pandas, or fuzzymotiv[pandas])"
            ) from None
        return pd.DataFrame({k: v for k, v in self.items()})

    def __getattr__(self, name: str) -> Any:
        """A DataFrame attribute, deprecated (these tables were DataFrames until 0.1)."""
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            import pandas as pd
        except ImportError:
            raise AttributeError(
                f"'Table' object has no attribute {name!r} (a Table is a dict of numpy arrays)"
            ) from None
        if not hasattr(pd.DataFrame, name):
            raise AttributeError(f"'Table' object has no attribute {name!r}")
        warnings.warn(
            f"Table.{name}: these tables are dicts of numpy arrays now; DataFrame attributes "
            "work for one more release: use table.to_pandas().",
            DeprecationWarning,
            stacklevel=2,
        )
        return getattr(self.to_pandas(), name)


def table_of(columns: Mapping[str, Any]) -> Table:
    """A :class:`Table` of the native layer's columns (arrays or lists)."""
    return Table({str(k): np.asarray(v) for k, v in columns.items()})


def _column(values: Sequence[str]) -> npt.NDArray[Any]:
    """A CSV column as float64 when every non-empty cell is a number (empty cells NaN), else
    as text."""
    try:
        return np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
    except ValueError:
        return np.array(values, dtype=str)


def read_table(path: Union[str, "os.PathLike[str]"]) -> Table:
    """A CSV file with a header row as a :class:`Table`."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.reader(f)
        header = next(reader, [])
        rows = list(reader)
    return Table({name: _column([r[i] for r in rows]) for i, name in enumerate(header)})
