"""Terms of your own, in Python: what a term function receives (:class:`Trials`) and how its
values are checked before they set F (docs/guide/motivations.md, "A term of your own, in
Python")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Mapping

import numpy as np
import numpy.typing as npt

from ._checks import _KINDS
from ._fuzzymotiv import FuzzymotivError

__all__ = ["TermFunction", "Trials"]


@dataclass(frozen=True)
class Trials:
    """One generation's evaluation trials, handed to each term function of
    ``Problem(terms={"name": fn})`` in one call: genome i's trial in room r (``rooms[r]``)
    is index ``[i, r]`` of every array. T is the trial length (``problem.steps``); a trial
    that ended early (at home, or its mission done) has its remaining steps marked ``idle``
    (the robot stands still).

    Attributes:
        x, y: the robot's centre (mm), ``(pop, rooms, T + 1)`` float64: the start, then after
            each step.
        heading: its heading (rad), ``(pop, rooms, T + 1)``.
        actions: the action of each step, ``(pop, rooms, T)`` int64: 0 straight, 1 left 30°,
            2 right 30°, 3 turn 180°.
        collisions: whether each step was blocked by a wall, ``(pop, rooms, T)`` bool.
        idle: whether each step came after the trial ended, ``(pop, rooms, T)`` bool.
        energy: the energy each step used, ``(pop, rooms, T)`` float64.
        sensors: the proximity readings of each step (noise included), one per sensor of the
            robot, ``(pop, rooms, T, N)`` float64 (N = 8 on the Khepera).
        executed: the steps executed before the trial ended, ``(pop, rooms)`` int64.
        rooms: the room names, in order.
        terms: the library's terms measured in each trial, ``name → (pop, rooms)``: ``a``,
            ``g``, ``l`` (0 here: orientation is measured across rooms), ``b``, and ``goal``,
            ``urgency``, ``waypoints``, ``safety`` when a motivation weighs a mission term.
    """

    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64]
    heading: npt.NDArray[np.float64]
    actions: npt.NDArray[np.int64]
    collisions: npt.NDArray[np.bool_]
    idle: npt.NDArray[np.bool_]
    energy: npt.NDArray[np.float64]
    sensors: npt.NDArray[np.float64]
    executed: npt.NDArray[np.int64]
    rooms: List[str]
    terms: Dict[str, npt.NDArray[np.float64]]

    @property
    def shape(self) -> tuple[int, int]:
        """``(pop, rooms)``: the shape a term function returns."""
        return (int(self.x.shape[0]), int(self.x.shape[1]))


TermFunction = Callable[[Trials], Any]
"""A term of your own: ``fn(trials)`` returns one value in [0, 1] per genome and room, an
array of shape ``trials.shape`` (``(pop, rooms)``)."""


def _term_names(terms: Mapping[str, TermFunction]) -> List[str]:
    """The names of ``terms=``, checked: a dict of names to callables."""
    if not isinstance(terms, Mapping):
        raise FuzzymotivError(
            f"terms: expected a dict of names to functions, e.g. terms={{\"smooth\": fn}}, got {type(terms).__name__}"
        )
    for name, fn in terms.items():
        if not isinstance(name, str):
            raise FuzzymotivError(f"terms: a term's name must be a string, got {name!r}")
        if not callable(fn):
            raise FuzzymotivError(
                f"terms[{name!r}]: expected a function fn(trials) -> (pop, rooms) values, got {type(fn).__name__}"
            )
    return list(terms)


def _values(name: str, value: Any, shape: tuple[int, int]) -> npt.NDArray[np.float64]:
    """A term function's result as a ``shape`` float array of values in [0, 1], or
    :class:`FuzzymotivError` naming the term."""
    expected = f"expected an array of shape {shape} (genomes, rooms) of numbers in [0, 1]"
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise FuzzymotivError(f"terms[{name!r}]: returned {type(value).__name__}, {expected}") from None
    if raw.dtype.kind not in "iufb":
        # numpy would read the strings "0.5" as numbers: a term returns numbers, not text.
        got = _KINDS.get(raw.dtype.kind, "no numbers")
        first = raw.reshape(-1)[0] if raw.size else None
        sample = repr(first.item() if isinstance(first, np.generic) else first)
        raise FuzzymotivError(
            f"terms[{name!r}]: returned {type(value).__name__} ({got}, dtype {raw.dtype}, "
            f"e.g. {sample}), {expected}"
        )
    v = raw.astype(np.float64)
    if v.shape != shape:
        raise FuzzymotivError(
            f"terms[{name!r}]: returned shape {v.shape}, expected {shape} (genomes, rooms), one value in [0, 1] per trial"
        )
    bad = np.argwhere(~((v >= 0.0) & (v <= 1.0)))
    if len(bad):
        i, r = (int(k) for k in bad[0])
        raise FuzzymotivError(
            f"terms[{name!r}]: `{float(v[i, r])!r}` (genome {i}, room {r}) is not a number in [0, 1]; a term's value must be one (NaN is not)"
        )
    return v


def _called(name: str, fn: TermFunction, trials: Trials) -> Any:
    """``fn(trials)``; an exception it raises becomes :class:`FuzzymotivError` naming the term
    (the original chained as its cause)."""
    try:
        return fn(trials)
    except Exception as e:
        raise FuzzymotivError(f"terms[{name!r}]: the function raised {type(e).__name__}: {e}") from e


def _supplier(terms: Mapping[str, TermFunction]) -> Callable[[Dict[str, Any]], npt.NDArray[np.float64]]:
    """The native evaluation's callback: the trials made into :class:`Trials`, each term
    function called once, their checked values stacked ``(pop, rooms, terms)``."""

    def supply(native: Dict[str, Any]) -> npt.NDArray[np.float64]:
        trials = Trials(**native)
        shape = trials.shape
        values = [_values(name, _called(name, fn, trials), shape) for name, fn in terms.items()]
        return np.ascontiguousarray(np.stack(values, axis=-1))

    return supply
