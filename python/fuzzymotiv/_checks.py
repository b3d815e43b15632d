"""Argument checks shared by the package's modules: motivations, arrays of real numbers,
whole numbers (each refusal a FuzzymotivError naming the argument)."""

from __future__ import annotations

import operator
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._fuzzymotiv import FuzzymotivError

Motivations = Union[Sequence[float], Mapping[str, float]]
"""The motivations' weights X: numbers in [0, 1] summing to 1, one per motivation (1 to 8):
four are the paper's (C, H, O, E), any other number are named ``x1``, ``x2``, ... (weighing
``y1``, ``y2``, ...); or a dict of name to weight: exactly the motivations it names, none
added (``{"curiosity": .7, "homing": .3}`` is two motivations, as ``fuzzymotiv fuzzy
--motivations curiosity=0.7,homing=0.3`` and a config's ``[motivations]`` read them), in the
dict's order, each weighing the term of its own name (``curiosity``, ``homing``,
``orientation``, ``energy``: a, g, l, b); or :attr:`fuzzymotiv.Problem.motivations` (a
:class:`MotivationWeights`)."""

FloatArray = npt.NDArray[np.float64]


class MotivationWeights(Tuple[float, ...]):
    """The weights of a config's motivations, in input order (the order of the TSK's inputs,
    of :attr:`fuzzymotiv.Problem.term_names` and of the last axis of ``evaluate``'s terms): a
    tuple of floats — ``(C, H, O, E)`` for the paper's four, every other motivation after
    them — with their names in :attr:`names`. ``as_dict()`` gives ``{name: weight}``; it
    equals a plain tuple of the same weights, and :func:`fuzzymotiv.fuzzy_fitness` takes it.

    >>> w = MotivationWeights([0.5, 0.1, 0.0, 0.1, 0.3], ["curiosity", "homing", "orientation", "energy", "urgency"])
    >>> w == (0.5, 0.1, 0.0, 0.1, 0.3), w.as_dict()["urgency"]
    (True, 0.3)
    """

    names: Tuple[str, ...]
    """The motivations' names, in the order of the weights."""

    def __new__(cls, weights: Iterable[float], names: Iterable[str]) -> "MotivationWeights":
        w = tuple(float(v) for v in weights)
        n = tuple(str(v) for v in names)
        if len(w) != len(n):
            raise FuzzymotivError(f"MotivationWeights: {len(w)} weights but {len(n)} names")
        self = super().__new__(cls, w)
        self.names = n
        return self

    def __getnewargs__(self) -> Tuple[Tuple[float, ...], Tuple[str, ...]]:
        return (tuple(self), self.names)

    def as_dict(self) -> Dict[str, float]:
        """``{name: weight}``, in input order."""
        return dict(zip(self.names, self))

    def __repr__(self) -> str:
        return "MotivationWeights(" + ", ".join(f"{n}={w!r}" for n, w in zip(self.names, self)) + ")"


def _motivations(motivations: Any) -> Tuple[List[float], Optional[List[str]]]:
    """The weights and, unless they are the paper's four given as such (then None), the names
    of the motivations (see :data:`Motivations`)."""
    if isinstance(motivations, MotivationWeights):
        return list(motivations), list(motivations.names)
    if isinstance(motivations, Mapping):
        names = [str(k) for k in motivations]
        if not all(isinstance(k, str) for k in motivations):
            raise FuzzymotivError(f"motivations: a motivation's name must be a string, got keys {list(motivations)!r}")
        try:
            weights = {k: float(v) for k, v in motivations.items()}
        except (TypeError, ValueError):
            raise FuzzymotivError(f"motivations: expected a number for each motivation, got {dict(motivations)!r}") from None
        # Exactly the motivations named, in the dict's order (nothing of the paper's four added).
        return [weights[k] for k in names], names
    try:
        values = [float(v) for v in motivations]
    except (TypeError, ValueError):
        raise FuzzymotivError(
            f"motivations: expected numbers, one weight per motivation (the paper's four: C, H, O, E), got {motivations!r}"
        ) from None
    return values, None


_KINDS = {"c": "complex numbers", "O": "Python objects", "U": "strings", "S": "bytes", "b": "booleans"}


def _real_array(arg: str, value: Any, what: str) -> FloatArray:
    """``value`` as a float64 array, or FuzzymotivError naming ``arg`` and ``what`` was expected
    when it is not an array of real numbers: numpy itself would drop an imaginary part with a
    mere ComplexWarning, and read strings and objects as numbers."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError) as e:
        raise FuzzymotivError(f"{arg}: expected {what} of numbers ({e})") from None
    if a.dtype.kind not in "iuf":
        got = _KINDS.get(a.dtype.kind, "no real numbers")
        raise FuzzymotivError(
            f"{arg}: expected {what} of real numbers (float64), got {got} (dtype {a.dtype})"
        )
    return a.astype(np.float64, copy=False)


def _float_array(arg: str, value: Any, ndim: int, what: str) -> FloatArray:
    """``value`` as a C-contiguous float64 array of ``ndim`` dimensions, or FuzzymotivError."""
    a = _real_array(arg, value, what)
    if a.ndim != ndim:
        raise FuzzymotivError(f"{arg}: expected {what}, got an array of shape {a.shape}")
    return np.ascontiguousarray(a)


def _whole(arg: str, value: Any) -> int:
    try:
        return operator.index(value)
    except TypeError:
        raise FuzzymotivError(f"{arg}: expected a whole number, got {value!r}") from None
