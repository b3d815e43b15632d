//! `fm.export_controller`: a run's controller as C99 or JSON, as `fuzzymotiv export` writes it.

use std::path::PathBuf;

use fuzzymotiv_pipeline::records::export::{
    ExportRequest, ExportTarget, KitTarget, build_export, export_controller as export,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::py_err;

/// The kit named by `target` (`None` and `"generic"`: none, the plain export of any format); an
/// unknown name raises naming `target`.
fn kit(target: Option<&str>) -> PyResult<Option<KitTarget>> {
    match target.map(|t| KitTarget::parse("target", t)).transpose() {
        Ok(Some(KitTarget::Generic)) | Ok(None) => Ok(None),
        Ok(kit) => Ok(kit),
        Err(e) => Err(py_err(e)),
    }
}

/// Writes the controller of the run directory or genome file `source` as `to` ("c": a
/// directory `out` receiving fm_controller.h and fm_controller.c, or with `target` a robot's
/// deployment kit; "json", "onnx": the file `out`); the paths written (or already holding this
/// export).
#[pyfunction]
#[pyo3(signature = (source, to, out, config=None, room=None, force=false, target=None))]
pub(crate) fn export_controller(
    source: PathBuf,
    to: &str,
    out: PathBuf,
    config: Option<PathBuf>,
    room: Option<String>,
    force: bool,
    target: Option<&str>,
) -> PyResult<Vec<String>> {
    let to = ExportTarget::parse("to", to).map_err(py_err)?;
    let done = export(&ExportRequest {
        source: &source,
        config: config.as_deref(),
        room: room.as_deref(),
        to,
        target: kit(target)?,
        out: &out,
        force,
        room_option: "room",
        out_option: "out",
        target_option: "target",
    })
    .map_err(py_err)?;
    Ok(done.files.iter().map(|p| p.display().to_string()).collect())
}

/// The one file of the JSON or ONNX export of `source`, as bytes, written nowhere: what
/// `fm.export_controller(..., out="-")` writes to standard output, as `fuzzymotiv export
/// --out -` does. A C export (two files) raises `ValueError`; a kit `target` is refused as
/// [`build_export`] refuses it (a kit is C code).
#[pyfunction]
#[pyo3(signature = (source, to, config=None, room=None, target=None))]
pub(crate) fn export_controller_bytes<'py>(
    py: Python<'py>,
    source: PathBuf,
    to: &str,
    config: Option<PathBuf>,
    room: Option<String>,
    target: Option<&str>,
) -> PyResult<Bound<'py, PyBytes>> {
    let to = ExportTarget::parse("to", to).map_err(py_err)?;
    let target = kit(target)?;
    if to == ExportTarget::C {
        return Err(PyValueError::new_err(
            "out: `-` (standard output) takes one file, but to=\"c\" writes two \
             (fm_controller.h and fm_controller.c); pass a directory",
        ));
    }
    let built = build_export(&ExportRequest {
        source: &source,
        config: config.as_deref(),
        room: room.as_deref(),
        to,
        target,
        out: std::path::Path::new("-"),
        force: false,
        room_option: "room",
        out_option: "out",
        target_option: "target",
    })
    .map_err(py_err)?;
    Ok(PyBytes::new(py, built.single_file("out").map_err(py_err)?))
}
