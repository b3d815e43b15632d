"""Statistics over seeds: the library's tests, intervals and verdicts (``fuzzymotiv::statistics``).

The same code as the study's claims, so a comparison made here equals the CLI's.

- ``paired(a, b)``: one pair per seed. The effect is the mean of the differences a − b; the
  p-value is the two-sided sign-flip permutation test (exact over all 2**n sign patterns for
  n ≤ 16, else ``permutation_resamples`` seeded random patterns, p = 2 (k + 1) / (R + 1)).
- ``unpaired(a, b)``: independent samples. The effect is mean(a) − mean(b); the p-value is the
  two-sided permutation test over splits of the pooled values (exact up to 2**16 splits).
- Two-sided p = min(1, 2 · the smaller one-sided p), as ``scipy.stats.permutation_test``.
- ``ci_low``/``ci_high``: a percentile bootstrap interval (``bootstrap_resamples`` resamples,
  seeded), as ``scipy.stats.bootstrap(method='percentile')``.
- ``mdd``: the minimum detectable difference at level ``alpha`` and ``power``,
  (z_{1−α/2} + z_power) · SE (normal approximation); ``min_p``: the smallest p-value the design
  can give (1/16 for five pairs, so no claim can be shown at α = 0.05).
- ``holm(p)``: Holm's step-down adjusted p-values.

>>> from fuzzymotiv import stats
>>> r = stats.paired([3, 4, 5, 6, 7], [1, 1, 1, 1, 1], expect="higher")
>>> r["difference"], r["p"], r["verdict"]
(4.0, 0.0625, 'not significant')
>>> stats.holm([0.01, 0.04, 0.03])
[0.03, 0.06, 0.06]
"""

from __future__ import annotations

from typing import Any, List, Optional, Sequence

from . import _fuzzymotiv as _native

__all__ = ["paired", "unpaired", "holm", "BOOTSTRAP_RESAMPLES", "PERMUTATION_RESAMPLES"]

#: Bootstrap resamples of an interval (the default).
BOOTSTRAP_RESAMPLES = 10_000
#: Random arrangements of a permutation test too large to enumerate (the default).
PERMUTATION_RESAMPLES = 99_999


def _floats(name: str, values: Sequence[float]) -> List[float]:
    try:
        return [float(v) for v in values]
    except (TypeError, ValueError):
        raise _native.FuzzymotivError(f"{name}: expected a sequence of numbers, got {values!r}") from None


def paired(
    a: Sequence[float],
    b: Sequence[float],
    *,
    alpha: float = 0.05,
    confidence: float = 0.95,
    power: float = 0.8,
    bootstrap_resamples: int = BOOTSTRAP_RESAMPLES,
    permutation_resamples: int = PERMUTATION_RESAMPLES,
    seed: int = 0,
    expect: Optional[str] = None,
) -> dict[str, Any]:
    """Paired comparison of ``a`` and ``b`` (one pair per seed, same order).

    Returns a dict: ``design`` ("paired"), ``n``, ``mean_a``, ``mean_b``, ``difference``,
    ``ci_low``, ``ci_high``, ``confidence``, ``p``, ``exact``, ``arrangements``, ``min_p``,
    ``alpha``, ``power``, ``mdd`` (None for one pair) and, with ``expect`` ("higher" or
    "lower": the claim that a is higher or lower than b), ``verdict`` ("holds", "opposite" or
    "not significant").
    """
    return _native.stats_compare(
        "paired", _floats("a", a), _floats("b", b), alpha=alpha, confidence=confidence, power=power,
        bootstrap_resamples=bootstrap_resamples, permutation_resamples=permutation_resamples,
        seed=seed, expect=expect,
    )


def unpaired(
    a: Sequence[float],
    b: Sequence[float],
    *,
    alpha: float = 0.05,
    confidence: float = 0.95,
    power: float = 0.8,
    bootstrap_resamples: int = BOOTSTRAP_RESAMPLES,
    permutation_resamples: int = PERMUTATION_RESAMPLES,
    seed: int = 0,
    expect: Optional[str] = None,
) -> dict[str, Any]:
    """Unpaired comparison of independent samples ``a`` and ``b``.

    Returns the dict of :func:`paired` with ``design`` "unpaired" and ``n_a``, ``n_b``
    instead of ``n``.
    """
    return _native.stats_compare(
        "unpaired", _floats("a", a), _floats("b", b), alpha=alpha, confidence=confidence, power=power,
        bootstrap_resamples=bootstrap_resamples, permutation_resamples=permutation_resamples,
        seed=seed, expect=expect,
    )


def holm(p: Sequence[float]) -> List[float]:
    """Holm-adjusted p-values of a family of tests, in the input's order."""
    return _native.stats_holm(_floats("p", p))
