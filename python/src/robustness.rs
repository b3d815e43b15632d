//! `fm.robustness`: a run's best robot under the standard perturbations, the rows of
//! `fuzzymotiv robustness`'s robustness.csv as columns.

use std::path::PathBuf;

use fuzzymotiv_pipeline::records::robustness::{measures_of, robustness_of_run};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::py_err;

/// The robustness study of the run directory `run` (`trials` trials per room and
/// perturbation), as columns: `perturbation`, `trials`, then per measure its mean and the
/// bounds of its 95 % interval (`f`, `f_lo`, `f_hi`, `exploration`, …, and `recognition`
/// for a run with one room model).
#[pyfunction]
#[pyo3(signature = (run, trials=10))]
pub(crate) fn robustness<'py>(
    py: Python<'py>,
    run: PathBuf,
    trials: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let records = py
        .detach(|| robustness_of_run(&run, trials))
        .map_err(py_err)?
        .records;
    let d = PyDict::new(py);
    let labels: Vec<&str> = records.iter().map(|r| r.perturbation.as_str()).collect();
    d.set_item("perturbation", labels)?;
    let counts: Vec<usize> = records.iter().map(|r| r.trials).collect();
    d.set_item("trials", counts)?;
    for (m, (stem, _)) in measures_of(&records).iter().enumerate() {
        for (k, suffix) in ["", "_lo", "_hi"].iter().enumerate() {
            let column: Vec<f64> = records
                .iter()
                .map(|r| {
                    let (mean, lo, hi) = r.measures()[m];
                    [mean, lo, hi][k]
                })
                .collect();
            d.set_item(format!("{stem}{suffix}"), column)?;
        }
    }
    Ok(d)
}
