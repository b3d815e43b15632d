//! `fm.export_controller`: a run's controller as C99 or JSON, as `fuzzymotiv export` writes it.

use std::path::PathBuf;

use fuzzymotiv_io::records::export::{ExportRequest, ExportTarget, export_controller as export};
use pyo3::prelude::*;

use crate::py_err;

/// Writes the controller of the run directory or genome file `source` as `to` ("c": a
/// directory `out` receiving fm_controller.h and fm_controller.c; "json": the file `out`);
/// the paths written (or already holding this export).
#[pyfunction]
#[pyo3(signature = (source, to, out, config=None, room=None, force=false))]
pub(crate) fn export_controller(
    source: PathBuf,
    to: &str,
    out: PathBuf,
    config: Option<PathBuf>,
    room: Option<String>,
    force: bool,
) -> PyResult<Vec<String>> {
    let to = ExportTarget::parse("to", to).map_err(py_err)?;
    let done = export(&ExportRequest {
        source: &source,
        config: config.as_deref(),
        room: room.as_deref(),
        to,
        out: &out,
        force,
        room_option: "room",
        out_option: "out",
    })
    .map_err(py_err)?;
    Ok(done.files.iter().map(|p| p.display().to_string()).collect())
}
