//! `fm.recognise`: the rooms a run's room model recognises in a robot's logs, the rows of
//! `fuzzymotiv recognise`'s recognised.csv as columns.

use std::path::PathBuf;

use fuzzymotiv_pipeline::records::robot_log::recognise_logs;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::py_err;

/// The rooms the run directory `run`'s room model recognises in `logs` (CSV files, one row
/// per step), as columns: `log`, `steps`, `used`, `room` (empty: not recognised), `winner`,
/// `straight`, `left`, `right`, `back`, and the gate's reasons: `r_node` (the recognised
/// room's r-node), `node_distance` (|winner − r_node|), `gate` (`aem.threshold`) and
/// `vector_distance` (to the room's stored vector), floats, NaN where no room is recognised
/// (as `fm.read_table` reads the CSV's empty cells).
#[pyfunction]
pub(crate) fn recognise<'py>(
    py: Python<'py>,
    run: PathBuf,
    logs: Vec<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let records = py.detach(|| recognise_logs(&run, &logs)).map_err(py_err)?;
    let d = PyDict::new(py);
    d.set_item(
        "log",
        records.iter().map(|r| r.log.clone()).collect::<Vec<_>>(),
    )?;
    d.set_item("steps", records.iter().map(|r| r.steps).collect::<Vec<_>>())?;
    d.set_item("used", records.iter().map(|r| r.used).collect::<Vec<_>>())?;
    d.set_item(
        "room",
        records.iter().map(|r| r.room.clone()).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "winner",
        records.iter().map(|r| r.winner).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "straight",
        records.iter().map(|r| r.straight).collect::<Vec<_>>(),
    )?;
    d.set_item("left", records.iter().map(|r| r.left).collect::<Vec<_>>())?;
    d.set_item("right", records.iter().map(|r| r.right).collect::<Vec<_>>())?;
    d.set_item("back", records.iter().map(|r| r.back).collect::<Vec<_>>())?;
    d.set_item(
        "r_node",
        records
            .iter()
            .map(|r| nan_if_none(r.r_node.map(|n| n as f64)))
            .collect::<Vec<_>>(),
    )?;
    d.set_item(
        "node_distance",
        records
            .iter()
            .map(|r| nan_if_none(r.node_distance.map(|n| n as f64)))
            .collect::<Vec<_>>(),
    )?;
    d.set_item("gate", records.iter().map(|r| r.gate).collect::<Vec<_>>())?;
    d.set_item(
        "vector_distance",
        records
            .iter()
            .map(|r| nan_if_none(r.vector_distance))
            .collect::<Vec<_>>(),
    )?;
    Ok(d)
}

/// A missing number as NaN, a column's empty cell.
fn nan_if_none(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}
