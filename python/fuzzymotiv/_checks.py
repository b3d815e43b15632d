"""Argument checks shared by the package's modules: motivations, arrays of real numbers,
whole numbers (each refusal a FuzzymotivError naming the argument)."""

from __future__ import annotations

import operator
from typing import Any, List, Mapping, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._fuzzymotiv import FuzzymotivError

Motivations = Union[Sequence[float], Mapping[str, float]]
"""(C, H, O, E): four numbers, or a dict with the config's keys (``curiosity``, ``homing``,
``orientation``, ``energy``; missing ones 0)."""

FloatArray = npt.NDArray[np.float64]


_MOTIVATION_KEYS = ("curiosity", "homing", "orientation", "energy")


def _motivations(motivations: Any) -> List[float]:
    """(C, H, O, E) from a sequence of four numbers or a dict with the config's keys."""
    if isinstance(motivations, Mapping):
        unknown = set(motivations) - set(_MOTIVATION_KEYS)
        if unknown:
            raise FuzzymotivError(
                f"motivations: unknown key(s) {sorted(unknown)}; expected {list(_MOTIVATION_KEYS)}"
            )
        return [float(motivations.get(k, 0.0)) for k in _MOTIVATION_KEYS]
    try:
        values = [float(v) for v in motivations]
    except (TypeError, ValueError):
        raise FuzzymotivError(
            f"motivations: expected four numbers (C, H, O, E), got {motivations!r}"
        ) from None
    if len(values) != 4:
        raise FuzzymotivError(
            f"motivations: expected four numbers (C, H, O, E), got {len(values)}"
        )
    return values


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
