//! `fuzzymotiv.stats`: the library's statistics over seeds (`fuzzymotiv::statistics`) for
//! Python, each comparison as a dict. The methods are the library's, documented there.

use fuzzymotiv::statistics::{self, Comparison, Design, Expect, Settings, StatsError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::FuzzymotivError;

/// Bad samples or settings as a `FuzzymotivError` (a `ValueError`) with the library's message.
fn stats_err(e: StatsError) -> PyErr {
    FuzzymotivError::new_err(e.to_string())
}

/// "higher" / "lower" → the claim's direction.
fn expect_of(expect: Option<&str>) -> PyResult<Option<Expect>> {
    match expect {
        None => Ok(None),
        Some("higher") => Ok(Some(Expect::Higher)),
        Some("lower") => Ok(Some(Expect::Lower)),
        Some(other) => Err(FuzzymotivError::new_err(format!(
            "expect must be \"higher\" or \"lower\" (a than b), got {other:?}"
        ))),
    }
}

/// A comparison as a dict: the design and sizes, the means, the difference and its interval,
/// the p-value and how it was found, the smallest attainable p, the minimum detectable
/// difference (`None` without spread) and, given `expect`, the verdict.
fn comparison_dict<'py>(
    py: Python<'py>,
    c: &Comparison,
    expect: Option<Expect>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    match c.design {
        Design::Paired { n } => {
            d.set_item("design", "paired")?;
            d.set_item("n", n)?;
        }
        Design::Unpaired { n_a, n_b } => {
            d.set_item("design", "unpaired")?;
            d.set_item("n_a", n_a)?;
            d.set_item("n_b", n_b)?;
        }
    }
    d.set_item("mean_a", c.mean_a)?;
    d.set_item("mean_b", c.mean_b)?;
    d.set_item("difference", c.difference)?;
    d.set_item("ci_low", c.ci_low)?;
    d.set_item("ci_high", c.ci_high)?;
    d.set_item("confidence", c.confidence)?;
    d.set_item("p", c.p)?;
    d.set_item("exact", c.exact)?;
    d.set_item("arrangements", c.arrangements)?;
    d.set_item("min_p", c.min_p)?;
    d.set_item("alpha", c.alpha)?;
    d.set_item("power", c.power)?;
    d.set_item("mdd", c.mdd)?;
    if let Some(e) = expect {
        d.set_item("verdict", c.verdict(e).label())?;
    }
    Ok(d)
}

/// A paired (`design = "paired"`, one pair per seed: `fuzzymotiv::statistics::paired`) or
/// unpaired (`"unpaired"`, independent samples: `fuzzymotiv::statistics::unpaired`) comparison.
#[pyfunction]
#[pyo3(signature = (design, a, b, *, alpha=0.05, confidence=0.95, power=0.8,
    bootstrap_resamples=statistics::BOOTSTRAP_RESAMPLES,
    permutation_resamples=statistics::PERMUTATION_RESAMPLES, seed=0, expect=None))]
#[allow(clippy::too_many_arguments)]
fn stats_compare<'py>(
    py: Python<'py>,
    design: &str,
    a: Vec<f64>,
    b: Vec<f64>,
    alpha: f64,
    confidence: f64,
    power: f64,
    bootstrap_resamples: usize,
    permutation_resamples: usize,
    seed: u64,
    expect: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let compare = match design {
        "paired" => statistics::paired,
        "unpaired" => statistics::unpaired,
        other => {
            return Err(FuzzymotivError::new_err(format!(
                "design must be \"paired\" or \"unpaired\", got {other:?}"
            )));
        }
    };
    let expect = expect_of(expect)?;
    let settings = Settings {
        alpha,
        confidence,
        power,
        bootstrap_resamples,
        permutation_resamples,
        seed,
    };
    let c = py
        .detach(|| compare(&a, &b, &settings))
        .map_err(stats_err)?;
    comparison_dict(py, &c, expect)
}

/// Holm-adjusted p-values, in the input's order: `fuzzymotiv::statistics::holm`.
#[pyfunction]
fn stats_holm(p: Vec<f64>) -> Vec<f64> {
    statistics::holm(&p)
}

/// Adds the statistics functions to the native module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(stats_compare, m)?)?;
    m.add_function(wrap_pyfunction!(stats_holm, m)?)?;
    Ok(())
}
