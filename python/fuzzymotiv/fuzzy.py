"""The TSK motivation fitness: F of fitness terms under motivations, its firing rules, and
its export as a fuzzylite engine."""

from __future__ import annotations

import os
from typing import List, Literal, Optional, Sequence, TypedDict, Union, cast, overload

import numpy as np
import numpy.typing as npt

from . import _fuzzymotiv as _native
from ._checks import FloatArray, Motivations, _motivations, _real_array
from ._fuzzymotiv import FuzzymotivError

__all__ = ["Coefficients", "Explanation", "FiringRule", "export_fll", "fuzzy_fitness"]

Coefficients = Union[Literal["linear", "ratio"], Sequence[float], None]
"""The rules' output coefficients: ``"linear"`` (the paper's), ``"ratio"`` or a list."""


class FiringRule(TypedDict):
    """One firing rule of :func:`fuzzy_fitness`'s explanation."""

    number: int
    labels: List[int]
    label_names: List[str]
    weight: float
    output: float


class Explanation(TypedDict):
    """What ``fuzzy_fitness(..., explain=True)`` returns for one vector of terms."""

    fitness: float
    weight_sum: float
    rules: List[FiringRule]
    text: str


@overload
def fuzzy_fitness(
    motivations: Motivations,
    terms: Sequence[float],
    explain: Literal[False] = ...,
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
) -> float: ...
@overload
def fuzzy_fitness(
    motivations: Motivations,
    terms: npt.ArrayLike,
    explain: Literal[False] = ...,
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
) -> Union[float, FloatArray]: ...
@overload
def fuzzy_fitness(
    motivations: Motivations,
    terms: npt.ArrayLike,
    explain: Literal[True],
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
) -> Union[Explanation, List[Explanation]]: ...
def fuzzy_fitness(
    motivations: Motivations,
    terms: npt.ArrayLike,
    explain: bool = False,
    *,
    peaks: Optional[Sequence[float]] = None,
    coefficients: Coefficients = None,
) -> Union[float, FloatArray, Explanation, List[Explanation]]:
    """The TSK motivation fitness F of fitness terms Y = (a, g, l, b) under motivations
    X = (C, H, O, E).

    ``terms`` is one vector of four values (→ float) or an ``n × 4`` array (→ numpy array of n
    values). Terms are clamped to [0, 1]. ``explain=True`` returns, for one vector, a dict
    ``{"fitness", "weight_sum", "rules", "text"}`` whose ``rules`` are the firing rules
    (number, labels, label names, weight w, output f); for an array, a list of such dicts.
    ``peaks`` and ``coefficients`` (``"linear"``, ``"ratio"`` or a list) default to the paper's.
    NaN or infinite values anywhere raise :class:`FuzzymotivError` naming the argument, the
    position and the value (as the CLI refuses them).

    >>> round(fuzzy_fitness([.8, .1, 0, .1], [.95, .5, 0, .79]), 6)
    0.79722
    >>> [r["number"] for r in fuzzy_fitness([.8, .1, 0, .1], [1, .25, 0, 0], explain=True)["rules"]]
    [10]
    """
    x = _motivations(motivations)
    y = _real_array("terms", terms, "a vector of 4 or an n × 4 array")
    coef = coefficients
    pk = None if peaks is None else [float(p) for p in peaks]
    if y.ndim == 1:
        if y.shape != (4,):
            raise FuzzymotivError(f"terms: expected four values (a, g, l, b), got {y.shape[0]}")
        if explain:
            return cast(Explanation, _native.explain(x, y.tolist(), pk, coef))
        return _native.fuzzy_fitness_one(x, y.tolist(), pk, coef)
    if y.ndim == 2:
        if y.shape[1] != 4:
            raise FuzzymotivError(
                f"terms: expected an n × 4 array of (a, g, l, b), got shape {y.shape}"
            )
        many = _native.fuzzy_fitness_many(x, np.ascontiguousarray(y), pk, coef)  # checks every row
        if explain:
            return [cast(Explanation, _native.explain(x, row.tolist(), pk, coef)) for row in y]
        return many
    raise FuzzymotivError(f"terms: expected a vector of 4 or an n × 4 array, got shape {y.shape}")


def export_fll(
    motivations: Motivations,
    path: Union[str, "os.PathLike[str]", None] = None,
    *,
    peaks: Optional[Sequence[float]] = None,
    coefficients: Coefficients = None,
    name: Optional[str] = None,
    force: bool = False,
) -> str:
    """The TSK of ``motivations`` as a fuzzylite FLL engine (625 rules by default); also written
    to ``path`` (atomically; a file with other contents is kept unless ``force=True``, the same
    text again is nothing to do, and a directory, link or device is never replaced).

    The text is the same as ``fuzzymotiv fuzzy --motivations C,H,O,E --export-fll FILE``.

    >>> text = export_fll([.8, .1, 0, .1])
    >>> text.count("\\n  rule: ")
    625
    """
    pk = None if peaks is None else [float(p) for p in peaks]
    return _native.export_fll(
        _motivations(motivations),
        None if path is None else os.fspath(path),
        pk,
        coefficients,
        name,
        force,
    )
