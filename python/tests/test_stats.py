"""fuzzymotiv.stats against SciPy: permutation p-values equal to the last bit where both
enumerate every arrangement, bootstrap intervals within a stated tolerance, and the module's
docstring examples."""

import doctest

import numpy as np
import pytest

scipy_stats = pytest.importorskip("scipy.stats")

import fuzzymotiv as fm
from fuzzymotiv import stats


def _mean_difference(x, y, axis):
    return np.mean(x, axis=axis) - np.mean(y, axis=axis)


def _mean_of_differences(x, y, axis):
    return np.mean(x - y, axis=axis)


def _scipy_p(a, b, permutation_type):
    statistic = _mean_of_differences if permutation_type == "samples" else _mean_difference
    res = scipy_stats.permutation_test(
        (np.asarray(a, float), np.asarray(b, float)),
        statistic,
        permutation_type=permutation_type,
        n_resamples=np.inf,
        vectorized=True,
        alternative="two-sided",
    )
    return float(res.pvalue)


_rng = np.random.default_rng(25)

# Paired: 2**n ≤ 2**16 sign patterns, so both enumerate them all. Integers (ties, zero
# differences), decimals whose sums tie only up to rounding, and continuous values.
PAIRED = [
    ([3, 4, 5, 6, 7], [1, 1, 1, 1, 1]),
    ([1, 2, 3, 4], [0, 0, 0, 8]),
    ([1, 2, 3], [2, 1, 3]),
    ([0.1, 0.2, 0.3, 0.7, 0.4], [0.0, 0.0, 0.0, 0.1, 0.5]),
    ([55.6, 61.6, 35.6, 80.0, 72.4, 48.0], [54.8, 35.6, 61.6, 70.2, 71.0, 52.2]),
    (list(_rng.integers(0, 10, 10)), list(_rng.integers(0, 10, 10))),
    (list(_rng.normal(70, 20, 12)), list(_rng.normal(65, 20, 12))),
    (list(_rng.normal(0, 1, 16)), list(_rng.normal(0.5, 1, 16))),
]

# Unpaired: C(n_a + n_b, n_a) ≤ 2**16 splits.
UNPAIRED = [
    ([1, 2], [3, 4]),
    ([5, 6], [1, 2, 3]),
    ([1, 4], [2, 3]),
    ([0.1, 0.2, 0.3], [0.3, 0.6, 0.0, 0.1]),
    (list(_rng.integers(0, 5, 5)), list(_rng.integers(0, 5, 5))),
    (list(_rng.normal(72, 15, 6)), list(_rng.normal(81, 15, 8))),
    (list(_rng.normal(0, 1, 8)), list(_rng.normal(1, 2, 8))),
]


@pytest.mark.parametrize("a,b", PAIRED)
def test_paired_p_equals_scipy_exactly(a, b):
    ours = stats.paired(a, b)
    assert ours["exact"] and ours["arrangements"] == 2 ** len(a)
    assert ours["p"] == _scipy_p(a, b, "samples")


@pytest.mark.parametrize("a,b", UNPAIRED)
def test_unpaired_p_equals_scipy_exactly(a, b):
    ours = stats.unpaired(a, b)
    assert ours["exact"]
    assert ours["p"] == _scipy_p(a, b, "independent")


def test_resampled_p_agrees_with_scipy_within_monte_carlo_error():
    """20 pairs: 2**20 patterns, so both draw random ones (99 999 each); the p-values agree
    within 5 Monte Carlo standard errors of their difference."""
    rng = np.random.default_rng(7)
    a, b = rng.normal(0.3, 1, 20), rng.normal(0, 1, 20)
    ours = stats.paired(a, b)
    assert not ours["exact"] and ours["arrangements"] == stats.PERMUTATION_RESAMPLES
    res = scipy_stats.permutation_test(
        (a, b), _mean_of_differences, permutation_type="samples", vectorized=True,
        n_resamples=stats.PERMUTATION_RESAMPLES, rng=np.random.default_rng(1),
    )
    p = float(res.pvalue)
    se = np.sqrt(2 * p * (1 - p / 2) * 2 / stats.PERMUTATION_RESAMPLES)
    assert abs(ours["p"] - p) <= 5 * se, (ours["p"], p)


# Bootstrap: 100 000 resamples on each side. The percentile bounds are Monte Carlo estimates;
# their standard error is about 0.012 standard errors of the mean at this count, so the stated
# tolerance, 0.1 standard error of the estimate (sd/√n paired, √(s_a²/n_a + s_b²/n_b)
# unpaired), is about 8 of those.
B = 100_000
TOLERANCE_SE = 0.1


@pytest.mark.parametrize("a,b", [c for c in PAIRED if len(c[0]) >= 10])
def test_paired_bootstrap_interval_matches_scipy(a, b):
    d = np.asarray(a, float) - np.asarray(b, float)
    ours = stats.paired(a, b, bootstrap_resamples=B, seed=3)
    res = scipy_stats.bootstrap(
        (d,), np.mean, method="percentile", confidence_level=0.95, n_resamples=B,
        vectorized=True, rng=np.random.default_rng(3),
    )
    se = d.std(ddof=1) / np.sqrt(len(d))
    ci = res.confidence_interval
    assert abs(ours["ci_low"] - ci.low) <= TOLERANCE_SE * se, (ours["ci_low"], ci.low)
    assert abs(ours["ci_high"] - ci.high) <= TOLERANCE_SE * se, (ours["ci_high"], ci.high)


@pytest.mark.parametrize("a,b", [c for c in UNPAIRED if len(c[0]) >= 6])
def test_unpaired_bootstrap_interval_matches_scipy(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    ours = stats.unpaired(a, b, bootstrap_resamples=B, seed=3)
    res = scipy_stats.bootstrap(
        (a, b), _mean_difference, method="percentile", confidence_level=0.95,
        n_resamples=B, vectorized=True, paired=False, rng=np.random.default_rng(3),
    )
    se = np.sqrt(a.var(ddof=1) / len(a) + b.var(ddof=1) / len(b))
    ci = res.confidence_interval
    assert abs(ours["ci_low"] - ci.low) <= TOLERANCE_SE * se, (ours["ci_low"], ci.low)
    assert abs(ours["ci_high"] - ci.high) <= TOLERANCE_SE * se, (ours["ci_high"], ci.high)


def test_minimum_detectable_difference_uses_normal_quantiles():
    d = np.array([1.0, 2.0, 3.0, 4.0])
    r = stats.paired(d, np.zeros(4))
    z = scipy_stats.norm.ppf(0.975) + scipy_stats.norm.ppf(0.8)
    assert r["mdd"] == pytest.approx(z * d.std(ddof=1) / 2, rel=1e-8)
    assert stats.paired([1.0], [0.0])["mdd"] is None


def test_holm_matches_the_step_down_rule():
    p = [0.01, 0.04, 0.03, 0.2]
    assert stats.holm(p) == pytest.approx([0.04, 0.09, 0.09, 0.2])


def test_verdicts_and_deterministic_results():
    higher = stats.paired(range(10, 30), range(20), expect="higher")
    assert higher["verdict"] == "holds"
    assert stats.paired(range(20), range(10, 30), expect="higher")["verdict"] == "opposite"
    assert stats.paired([1, 2], [2, 1], expect="lower")["verdict"] == "not significant"
    assert stats.paired(range(10, 30), range(20)) == stats.paired(range(10, 30), range(20))


def test_bad_input_raises_fuzzymotiv_error():
    with pytest.raises(fm.FuzzymotivError, match="one value per seed"):
        stats.paired([1, 2], [1])
    with pytest.raises(fm.FuzzymotivError, match="no values"):
        stats.unpaired([], [1])
    with pytest.raises(fm.FuzzymotivError, match="finite"):
        stats.paired([float("nan")], [1])
    with pytest.raises(fm.FuzzymotivError, match="expect"):
        stats.paired([1], [1], expect="more")
    with pytest.raises(fm.FuzzymotivError, match="alpha"):
        stats.paired([1], [1], alpha=0)


def test_docstring_examples():
    failures, tried = doctest.testmod(stats, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert tried > 0 and failures == 0
