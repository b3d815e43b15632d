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
    """The TSK motivation fitness F of fitness terms Y under motivations X: for the paper's
    four, Y = (a, g, l, b) under X = (C, H, O, E); for N motivations (1 to 8), one term per
    motivation, in the motivations' order.

    ``motivations`` is N weights (four: the paper's C, H, O, E), a dict of name to weight
    (exactly the motivations it names, with the terms in the dict's order:
    ``{"curiosity": .7, "homing": .3}`` takes Y = (a, g), as ``fuzzymotiv fuzzy --motivations
    curiosity=0.7,homing=0.3``; a dict in another order than the CLI's — the paper's first,
    then the others alphabetically — gives the same F but for rounding in the last bits, and
    rules numbered in the dict's order), or
    :attr:`Problem.motivations` (a :class:`MotivationWeights`); ``fm.fuzzy_fitness(
    problem.motivations, ev.terms[:, r])`` gives room r's F of a problem's evaluation (with the
    shared labels). ``terms`` is one vector of N values (→ float) or an ``n × N`` array (→
    numpy array of n values). Terms are clamped to [0, 1]. ``explain=True`` returns, for one
    vector, a dict ``{"fitness", "weight_sum", "rules", "text"}`` whose ``rules`` are the
    firing rules (number, labels, label names, weight w, output f); for an array, a list of
    such dicts. ``peaks`` and ``coefficients`` (``"linear"``, ``"ratio"`` or a list) default
    to the paper's. Fewer than 1 or more than 8 motivations, a number of terms other than
    theirs, and NaN or infinite values anywhere raise :class:`FuzzymotivError` naming the
    argument (and the position and the value, as the CLI refuses them).

    >>> round(fuzzy_fitness([.8, .1, 0, .1], [.95, .5, 0, .79]), 6)
    0.79722
    >>> [r["number"] for r in fuzzy_fitness([.8, .1, 0, .1], [1, .25, 0, 0], explain=True)["rules"]]
    [10]
    >>> x = {"curiosity": .5, "homing": .1, "orientation": 0, "energy": .1, "urgency": .3}
    >>> round(fuzzy_fitness(x, [.95, .5, 0, .79, .6]), 6)
    0.633828
    """
    x, names = _motivations(motivations)
    y = _real_array("terms", terms, "a vector or an n × N array (N motivations)")
    coef = coefficients
    pk = None if peaks is None else [float(p) for p in peaks]
    if y.ndim == 1:
        if explain:
            return cast(Explanation, _native.explain(x, y.tolist(), pk, coef, names))
        return _native.fuzzy_fitness_one(x, y.tolist(), pk, coef, names)
    if y.ndim == 2:
        # Checks the shape and every row.
        many = _native.fuzzy_fitness_many(x, np.ascontiguousarray(y), pk, coef, names)
        if explain:
            return [cast(Explanation, _native.explain(x, row.tolist(), pk, coef, names)) for row in y]
        return many
    raise FuzzymotivError(
        f"terms: expected a vector of {len(x)} or an n × {len(x)} array, one value per motivation, got shape {y.shape}"
    )


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

    The text is the same as ``fuzzymotiv fuzzy --motivations C,H,O,E --export-fll FILE`` (for
    N motivations ``--motivations name=w,...``: ``motivations`` as :func:`fuzzy_fitness` takes
    them, 5^N rules; a dict's inputs in its order, the CLI's for a dict in the CLI's order).

    >>> text = export_fll([.8, .1, 0, .1])
    >>> text.count("\\n  rule: ")
    625
    """
    pk = None if peaks is None else [float(p) for p in peaks]
    x, names = _motivations(motivations)
    return _native.export_fll(
        x, None if path is None else os.fspath(path), pk, coefficients, name, force, names
    )
