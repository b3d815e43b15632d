//! The native part of the `fuzzymotiv` Python package (`fuzzymotiv._fuzzymotiv`).
//!
//! Thin: configs are loaded, runs executed and run directories written by the very code of the
//! `fuzzymotiv` binary (the `fuzzymotiv-pipeline` library it shares), so results equal the CLI's for
//! the same config and seed. The Python layer (`fuzzymotiv/__init__.py`) adds pandas, tqdm and the
//! friendlier signatures.

use std::ops::ControlFlow;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::experiment::InstanceRun;
use fuzzymotiv::experiment::RunError;
use fuzzymotiv::experiment::{GenerationState, Observer};
use fuzzymotiv::fitness::{
    CoefficientScheme, MAX_MOTIVATIONS, Motivation, Motivations, PAPER_MOTIVATIONS, PAPER_TERMS,
    TskFitness,
};
use fuzzymotiv::simulation::Trajectory;
use fuzzymotiv::simulation::{BUILTIN_ROBOTS, RobotSpec};
use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{
    FilesState, OutState, PYTHON, StagedDir, check_files, check_out_as, write_files,
};
use fuzzymotiv_pipeline::files::inputs::{
    Loaded, load_config, load_robot, load_room_file, parse_seed, resolve, run_identity,
};
use fuzzymotiv_pipeline::files::notes::NoteList;
use fuzzymotiv_pipeline::pipeline::progress::NoProgress;
use fuzzymotiv_pipeline::pipeline::run_dir;
use fuzzymotiv_pipeline::records::checkpoint::{CHECKPOINT, Checkpoint, POPULATION};
use fuzzymotiv_pipeline::records::{
    BestGenome, Finished, Fixed, GenerationRow, RoomRow, RunSummary, read_csv, read_json,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyDict, PyList, PyTuple, PyType};
use rayon::prelude::*;
use rayon::{ThreadPool, ThreadPoolBuilder};

mod export;
mod frames;
mod ga;
mod gym;
mod problem;
mod recognise;
mod robustness;
mod stats;
mod study;
mod sweep;
mod terms;

// Module `fuzzymotiv` (where the package exports it), so that the error pickles: executors
// (Dask, submitit) send a job's error back to the process that waits for it.
create_exception!(
    fuzzymotiv,
    FuzzymotivError,
    PyValueError,
    "Bad input (config, room file, motivations, ...): the message is the CLI's, naming the file, the field and what is wrong."
);

create_exception!(
    fuzzymotiv,
    ConfigError,
    FuzzymotivError,
    "A config, its overrides, a room file or a sweep file that cannot be used: the message names the file, the field and what is wrong."
);
create_exception!(
    fuzzymotiv,
    OutputExistsError,
    FuzzymotivError,
    "An output that must not be replaced: another run's or file's contents at out= or path= (force=True replaces fuzzymotiv's own outputs), or a place that is never written (a directory of yours, the current directory)."
);
create_exception!(
    fuzzymotiv,
    ResetNeeded,
    FuzzymotivError,
    "A Gymnasium environment used before reset() (step() or render() with no episode running)."
);
create_exception!(
    fuzzymotiv,
    DependencyNotInstalled,
    FuzzymotivError,
    "An optional package a call needs is not installed (pandas, gymnasium, tqdm, ...): the message says what to pip install."
);

/// `FuzzymotivOSError(FuzzymotivError, OSError)`: a file-system failure, created when the
/// module is loaded (an exception with two bases cannot be declared with `create_exception!`).
static OS_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();

fn os_error_type(py: Python<'_>) -> PyResult<&Py<PyType>> {
    OS_ERROR.get_or_try_init(py, || {
        let bases = PyTuple::new(
            py,
            [
                py.get_type::<FuzzymotivError>(),
                py.get_type::<PyOSError>(),
            ],
        )?;
        let namespace = PyDict::new(py);
        namespace.set_item("__module__", "fuzzymotiv")?;
        // OSError's constructor (the base with the larger layout), so that the error also
        // unpickles where pickling goes through `cls.__new__(cls)` (tblib, which Dask installs).
        namespace.set_item("__new__", py.get_type::<PyOSError>().getattr("__new__")?)?;
        namespace.set_item(
            "__doc__",
            "A file-system failure (reading or writing a named path): both a FuzzymotivError and an OSError; the message is the CLI's.",
        )?;
        let t = py
            .import("builtins")?
            .getattr("type")?
            .call1(("FuzzymotivOSError", bases, namespace))?
            .cast_into::<PyType>()?;
        Ok(t.unbind())
    })
}

/// A CLI error as a Python exception, with the message the CLI prints after `error:` (a refused
/// output worded with Python's `out` and `force=True`), the class picked by the error: a refused
/// output → `OutputExistsError`; other bad input → `FuzzymotivError` (a `ValueError`); a
/// file-system failure → `FuzzymotivOSError` (a `FuzzymotivError` and an `OSError`, `.errno`
/// set when the OS gave one); another failure while running → `RuntimeError`.
fn py_err(e: CliError) -> PyErr {
    match e {
        CliError::Output(refusal) => OutputExistsError::new_err(refusal.render(&PYTHON)),
        CliError::Input(message) => FuzzymotivError::new_err(message),
        CliError::Setup(e) => FuzzymotivError::new_err(e.to_string()),
        CliError::StudyFile(e) => FuzzymotivError::new_err(e.to_string()),
        CliError::Runtime(message) => PyRuntimeError::new_err(message),
        CliError::Io { .. } | CliError::FileSystem(_) | CliError::ClosedStdout => {
            Python::attach(|py| os_err(py, &e))
        }
    }
}

/// The libraries' notes (e.g. that a config's motivations were normalised, that `force=True`
/// replaces an output) as Python warnings (`warnings.warn`, a `UserWarning`): how Python shows
/// what the command line says on stderr. The libraries never print.
pub(crate) fn warn_notes(notes: &[String]) -> PyResult<()> {
    Python::attach(|py| {
        let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
        for line in notes {
            let message = std::ffi::CString::new(line.as_str())
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            PyErr::warn(py, category.as_any(), &message, 1)?;
        }
        Ok(())
    })
}

/// A file-system failure as `FuzzymotivOSError`, its `errno` the OS's error number (or None).
fn os_err(py: Python<'_>, e: &CliError) -> PyErr {
    let t = match os_error_type(py) {
        Ok(t) => t.bind(py).clone(),
        Err(err) => return err,
    };
    let err = PyErr::from_type(t, e.to_string());
    if let Some(n) = e.errno()
        && let Err(set) = err.value(py).setattr("errno", n)
    {
        return set;
    }
    err
}

/// [`py_err`] of an error loading a config, overrides, a room or a sweep file: bad input is a
/// `ConfigError`.
fn config_err(e: CliError) -> PyErr {
    match e {
        CliError::Input(message) => ConfigError::new_err(message),
        CliError::Setup(e) => ConfigError::new_err(e.to_string()),
        CliError::StudyFile(e) => ConfigError::new_err(e.to_string()),
        other => py_err(other),
    }
}

/// A float as Python spells it (`nan`, `inf`, `-inf`, `0.5`).
fn py_float(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{v:?}")
    }
}

/// NaN or ±inf in `values` refused, as the CLI refuses them (`parse_four`): the argument, the
/// position (`position(k)`) and the value, then what is expected.
fn finite(
    arg: &str,
    values: &[f64],
    position: impl Fn(usize) -> String,
    usage: &str,
) -> PyResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(k) => Err(input_err(format!(
            "{arg}: `{}` ({}) is not a finite number; {usage}",
            py_float(values[k]),
            position(k)
        ))),
    }
}

/// The motivations of `fm.fuzzy_fitness` and `fm.export_fll`, with what their errors call
/// each motivation and each term: C, H, O, E and a, g, l, b for the paper's four, else their
/// names and the TSK's input names.
struct Inputs {
    m: Motivations,
    paper: bool,
}

impl Inputs {
    /// What an error calls term `k`.
    fn term(&self, k: usize) -> String {
        if self.paper {
            PAPER_TERMS[k].into()
        } else {
            self.m.input_names()[k].clone()
        }
    }

    /// The terms, listed: `a, g, l, b` for the paper's four.
    fn term_list(&self) -> String {
        self.m.input_names().join(", ")
    }

    /// How many terms, in words for the paper's four (`four numbers (a, g, l, b)`).
    fn count(&self) -> String {
        match self.m.len() {
            4 => "four".into(),
            n => n.to_string(),
        }
    }

    /// `terms` has one finite value per motivation.
    fn check_terms(&self, terms: &[f64]) -> PyResult<()> {
        if terms.len() != self.m.len() {
            return Err(input_err(format!(
                "terms: expected {} values ({}), one per motivation, got {}",
                self.count(),
                self.term_list(),
                terms.len()
            )));
        }
        let usage = format!("expected {} numbers ({})", self.count(), self.term_list());
        finite("terms", terms, |k| self.term(k), &usage)
    }
}

/// The term a motivation named `name` weighs in `fm.fuzzy_fitness`: the paper's four their
/// own (a, g, l, b), `x1`… (unnamed weights) `y1`…, any other the term of its own name.
fn term_of(name: &str) -> String {
    if let Some(k) = PAPER_MOTIVATIONS.iter().position(|n| *n == name) {
        return PAPER_TERMS[k].into();
    }
    match name.strip_prefix('x') {
        Some(k) if !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()) => format!("y{k}"),
        _ => name.into(),
    }
}

/// Motivations as the CLI reads them (a sum within 1e-3 of 1 is normalised, silently here; the
/// normalised values are what is used): `weights` named `names`, or, without names, the
/// paper's C, H, O, E for four weights and `x1`, …, `xN` (weighing `y1`, …) for any other
/// number from 1 to [`MAX_MOTIVATIONS`].
fn motivations(weights: &[f64], names: Option<Vec<String>>) -> PyResult<Inputs> {
    let n = weights.len();
    if !(1..=MAX_MOTIVATIONS).contains(&n) {
        return Err(input_err(format!(
            "motivations: expected 1 to {MAX_MOTIVATIONS} weights, one per motivation (the paper's four: C, H, O, E), got {n}"
        )));
    }
    let names = match names {
        Some(names) if names.len() == n => names,
        Some(names) => {
            return Err(input_err(format!(
                "motivations: {n} weights but {} names",
                names.len()
            )));
        }
        None if n == 4 => PAPER_MOTIVATIONS.map(String::from).to_vec(),
        None => (1..=n).map(|k| format!("x{k}")).collect(),
    };
    let paper = names == PAPER_MOTIVATIONS;
    let usage = if paper {
        "expected four numbers (C, H, O, E)".to_string()
    } else {
        format!("expected {n} numbers ({})", names.join(", "))
    };
    let short = |k: usize| match paper {
        true => ["C", "H", "O", "E"][k].to_string(),
        false => names[k].clone(),
    };
    finite("motivations", weights, short, &usage)?;
    let list = (names.iter().zip(weights))
        .map(|(name, &w)| Motivation::new(name.clone(), w, term_of(name)))
        .collect();
    let m = Motivations::from_list(list)
        .map(|(m, _)| m)
        .map_err(|e| input_err(format!("motivations: {e}")))?;
    Ok(Inputs { m, paper })
}

/// The largest `threads`, the CLI's `--threads` bound ([`fuzzymotiv_pipeline::files::inputs::MAX_THREADS`],
/// which says why): more threads than this are surely a mistake (results do not depend on the
/// number).
const MAX_THREADS: i64 = fuzzymotiv_pipeline::files::inputs::MAX_THREADS as i64;

/// A whole number from a Python object (an `int`, a numpy integer; not a bool or a float), as
/// text, or the object's repr when it is not one.
fn whole_number(obj: &Bound<'_, PyAny>) -> Result<i128, String> {
    let repr = || obj.repr().map_or_else(|_| "?".into(), |r| r.to_string());
    if obj.is_instance_of::<PyBool>() {
        return Err(repr());
    }
    match obj.call_method0("__index__") {
        Ok(i) => i
            .str()
            .map_err(|_| repr())?
            .to_string()
            .parse()
            .map_err(|_| repr()),
        Err(_) => Err(repr()),
    }
}

/// `threads`: a whole number from 1 to [`MAX_THREADS`].
/// `threads=`: a pool of that many threads to run in, or `None` for rayon's global pool.
pub(crate) fn thread_pool(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<ThreadPool>> {
    threads_arg(obj)?
        .map(|n| {
            ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))
        })
        .transpose()
}

fn threads_arg(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<usize>> {
    let Some(obj) = obj else { return Ok(None) };
    match whole_number(obj) {
        Ok(n) if n < 1 => Err(input_err(format!("threads must be at least 1, got {n}"))),
        Ok(n) if n > MAX_THREADS as i128 => Err(input_err(format!(
            "threads must be at most {MAX_THREADS}, got {n}"
        ))),
        Ok(n) => Ok(Some(n as usize)),
        Err(repr) => Err(input_err(format!(
            "threads must be a whole number from 1 to {MAX_THREADS}, got {repr}"
        ))),
    }
}

/// `seed`: a whole number from 0 to 2^53 − 1, with the CLI's message (`--seed`) otherwise.
fn seed_arg(obj: &Bound<'_, PyAny>) -> PyResult<u64> {
    let text = whole_number(obj).map_or_else(|repr| repr, |n| n.to_string());
    parse_seed(&text).map_err(|m| input_err(format!("seed: {m}")))
}

fn input_err(message: impl Into<String>) -> PyErr {
    FuzzymotivError::new_err(message.into())
}

/// The TSK from optional peaks and coefficients (`"linear"`, `"ratio"` or a list).
fn tsk(peaks: Option<Vec<f64>>, coefficients: Option<&Bound<'_, PyAny>>) -> PyResult<TskFitness> {
    let peaks = peaks.unwrap_or_else(|| fuzzymotiv::fitness::PAPER_PEAKS.to_vec());
    finite(
        "peaks",
        &peaks,
        |k| format!("peak {k}"),
        "expected increasing numbers in [0, 1]",
    )?;
    let result = match coefficients {
        None => TskFitness::with_scheme(peaks, CoefficientScheme::Linear),
        Some(c) => {
            if let Ok(name) = c.extract::<String>() {
                let scheme = match name.as_str() {
                    "linear" => CoefficientScheme::Linear,
                    "ratio" => CoefficientScheme::Ratio,
                    other => {
                        return Err(input_err(format!(
                            "coefficients: expected \"linear\", \"ratio\" or a list of numbers, got \"{other}\""
                        )));
                    }
                };
                TskFitness::with_scheme(peaks, scheme)
            } else {
                let values: Vec<f64> = c.extract().map_err(|_| {
                    input_err("coefficients: expected \"linear\", \"ratio\" or a list of numbers")
                })?;
                finite(
                    "coefficients",
                    &values,
                    |k| format!("coefficient {k}"),
                    "expected \"linear\", \"ratio\" or a list of numbers",
                )?;
                TskFitness::new(peaks, values)
            }
        }
    };
    result.map_err(|e| input_err(e.to_string()))
}

/// F for one term vector (`[a, g, l, b]` for the paper's four), one value per motivation.
#[pyfunction]
#[pyo3(signature = (motivations, terms, peaks=None, coefficients=None, names=None))]
fn fuzzy_fitness_one(
    motivations: Vec<f64>,
    terms: Vec<f64>,
    peaks: Option<Vec<f64>>,
    coefficients: Option<&Bound<'_, PyAny>>,
    names: Option<Vec<String>>,
) -> PyResult<f64> {
    let x = self::motivations(&motivations, names)?;
    x.check_terms(&terms)?;
    Ok(tsk(peaks, coefficients)?.evaluate(&x.m, &terms))
}

/// F for every row of an `n × N` float64 array (N motivations).
#[pyfunction]
#[pyo3(signature = (motivations, terms, peaks=None, coefficients=None, names=None))]
fn fuzzy_fitness_many<'py>(
    py: Python<'py>,
    motivations: Vec<f64>,
    terms: PyReadonlyArray2<'py, f64>,
    peaks: Option<Vec<f64>>,
    coefficients: Option<&Bound<'py, PyAny>>,
    names: Option<Vec<String>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let x = self::motivations(&motivations, names)?;
    let t = tsk(peaks, coefficients)?;
    let n = x.m.len();
    let usage = format!("expected an n × {n} array of ({})", x.term_list());
    if terms.shape()[1] != n {
        let [rows, cols] = [terms.shape()[0], terms.shape()[1]];
        return Err(input_err(format!(
            "terms: {usage}, one column per motivation, got shape ({rows}, {cols})"
        )));
    }
    let view = terms.as_array();
    if let Some(((i, j), v)) = view.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(input_err(format!(
            "terms: `{}` (row {i}, {}) is not a finite number; {usage}",
            py_float(*v),
            x.term(j)
        )));
    }
    let mut row = vec![0.0; n];
    let out: Vec<f64> = (view.rows().into_iter())
        .map(|r| {
            row.iter_mut().zip(r).for_each(|(o, &v)| *o = v);
            t.evaluate(&x.m, &row)
        })
        .collect();
    Ok(PyArray1::from_vec(py, out))
}

/// F with its firing rules: `{"fitness", "weight_sum", "rules": [{"number", "labels",
/// "label_names", "weight", "output"}]}`.
#[pyfunction]
#[pyo3(signature = (motivations, terms, peaks=None, coefficients=None, names=None))]
fn explain<'py>(
    py: Python<'py>,
    motivations: Vec<f64>,
    terms: Vec<f64>,
    peaks: Option<Vec<f64>>,
    coefficients: Option<&Bound<'py, PyAny>>,
    names: Option<Vec<String>>,
) -> PyResult<Bound<'py, PyDict>> {
    let x = self::motivations(&motivations, names)?;
    x.check_terms(&terms)?;
    let e = tsk(peaks, coefficients)?.explain(&x.m, &terms);
    let d = PyDict::new(py);
    d.set_item("fitness", e.fitness)?;
    d.set_item("weight_sum", e.weight_sum)?;
    let rules = PyList::empty(py);
    for r in &e.rules {
        let rd = PyDict::new(py);
        rd.set_item("number", r.number)?;
        rd.set_item("labels", r.labels.to_vec())?;
        rd.set_item("label_names", r.label_names.to_vec())?;
        rd.set_item("weight", r.weight)?;
        rd.set_item("output", r.output)?;
        rules.append(rd)?;
    }
    d.set_item("rules", rules)?;
    d.set_item("text", e.to_string())?;
    Ok(d)
}

/// The FLL text of the TSK; written (atomically) to `path` when given.
#[pyfunction]
#[pyo3(signature = (motivations, path=None, peaks=None, coefficients=None, name=None, force=false, names=None))]
#[allow(clippy::too_many_arguments)]
fn export_fll(
    motivations: Vec<f64>,
    path: Option<PathBuf>,
    peaks: Option<Vec<f64>>,
    coefficients: Option<&Bound<'_, PyAny>>,
    name: Option<String>,
    force: bool,
    names: Option<Vec<String>>,
) -> PyResult<String> {
    let x = self::motivations(&motivations, names)?.m;
    let t = tsk(peaks, coefficients)?;
    let name = name.unwrap_or_else(|| {
        path.as_ref()
            .and_then(|p| p.file_stem())
            .map_or("fuzzymotiv".into(), |s| s.to_string_lossy().into_owned())
    });
    let text = fuzzymotiv::fitness::to_fll(&t, &x, &name);
    if let Some(path) = path {
        write_guarded(path, text.clone().into_bytes(), force)?;
    }
    Ok(text)
}

/// Writes `bytes` to `path` (the argument `path`) through the output guard: another file there
/// is kept unless `force` (the same bytes: nothing to do), and a directory, link, device or
/// FIFO is never replaced.
pub(crate) fn write_guarded(path: PathBuf, bytes: Vec<u8>, force: bool) -> PyResult<()> {
    let files = [(path, bytes)];
    if check_files(&files, "path", force).map_err(py_err)? == FilesState::Write {
        write_files(&files).map_err(py_err)?;
    }
    Ok(())
}

fn room_dict<'py>(py: Python<'py>, r: &Room) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let pts = |p: &[fuzzymotiv::simulation::Vec2]| -> PyResult<Bound<'py, PyAny>> {
        let flat: Vec<f64> = p.iter().flat_map(|v| [v.x, v.y]).collect();
        let a = Array2::from_shape_vec((p.len(), 2), flat).expect("n × 2");
        Ok(a.into_pyarray(py).into_any())
    };
    d.set_item("name", &r.name)?;
    d.set_item("outline", pts(&r.outline)?)?;
    let obstacles = PyList::empty(py);
    for o in &r.obstacles {
        obstacles.append(pts(o)?)?;
    }
    d.set_item("obstacles", obstacles)?;
    let home = PyDict::new(py);
    home.set_item("x", r.home.x)?;
    home.set_item("y", r.home.y)?;
    home.set_item("heading", r.home.heading)?;
    home.set_item("heading_deg", r.home.heading.to_degrees())?;
    d.set_item("home", home)?;
    let zone = PyDict::new(py);
    zone.set_item("x", r.home_zone.centre.x)?;
    zone.set_item("y", r.home_zone.centre.y)?;
    zone.set_item("radius", r.home_zone.radius)?;
    d.set_item("home_zone", zone)?;
    d.set_item("area", r.area())?;
    d.set_item("perimeter", r.perimeter())?;
    Ok(d)
}

/// The built-in rooms, then the room files `files` (validated as `fuzzymotiv rooms --check`).
#[pyfunction]
#[pyo3(signature = (files=None))]
fn rooms<'py>(py: Python<'py>, files: Option<Vec<PathBuf>>) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    match files {
        None => {
            for name in BUILTIN_ROOMS {
                out.append(room_dict(py, &Room::builtin(name).expect("built-in"))?)?;
            }
        }
        Some(files) => {
            for f in files {
                out.append(room_dict(py, &load_room_file(&f).map_err(config_err)?)?)?;
            }
        }
    }
    Ok(out)
}

/// Loads a config the CLI's way: a file (`config_path`) or TOML text, with `--set` overrides
/// (and a seed); room files are looked up beside the config (text: the working directory).
fn load(
    config_path: Option<&Path>,
    config_text: Option<&str>,
    sets: &[String],
    seed: Option<u64>,
) -> Result<Loaded, CliError> {
    match config_text {
        None => load_config(config_path, sets, seed),
        Some(text) => {
            let (raw, base, source) = terms::parse_config(None, Some(text), sets, seed)?;
            resolve(raw, &base, &source)
        }
    }
}

/// What a run returns to Python (plain Rust data, built without the GIL). A fresh run and a
/// finished run directory read back give equal values.
struct RunOutput {
    /// The rows of `generations.csv` (exact; 9 decimals when read back from a directory that
    /// an older build wrote, which has no `population.json`).
    generations: Vec<GenerationRow>,
    rows: Vec<RoomRow>,
    best: Vec<(String, Vec<f64>)>,
    summary: String,
    /// Per room: name and the best robot's room-modelling path (x, y, heading).
    paths: Vec<(String, Vec<[f64; 3]>)>,
    hidden: usize,
}

fn poses(t: &Trajectory) -> Vec<[f64; 3]> {
    t.poses.iter().map(|p| [p.x, p.y, p.heading]).collect()
}

fn output(loaded: &Loaded, done: Finished) -> RunOutput {
    let exp = &loaded.experiment;
    let summary = RunSummary::of(exp, &done);
    RunOutput {
        generations: GenerationRow::all(&done.outcome.evolutions),
        best: done
            .outcome
            .evolutions
            .iter()
            .map(|e| (e.run.label.clone(), e.population[e.best].clone()))
            .collect(),
        summary: serde_json::to_string(&summary).expect("serialisable"),
        paths: exp
            .room_names()
            .into_iter()
            .zip(done.trajectories())
            .map(|(n, t)| (n, poses(t)))
            .collect(),
        hidden: exp.shape().hidden(),
        rows: done.rows,
    }
}

/// The result of a finished run in `dir` that an older build wrote (no `population.json`, so
/// not [`run_dir::read_back`]), read back from its files: `generations.csv` (9 decimals),
/// `summary.json` (the per-room table), `best_genome.json`; the
/// trajectories are the best robots' room-modelling runs again (the very runs the report
/// draws: [`Finished::instance`]).
fn read_back_files(loaded: &Loaded, dir: &Path) -> Result<RunOutput, CliError> {
    let exp = &loaded.experiment;
    let generations: Vec<GenerationRow> = read_csv(&dir.join("generations.csv"))?;
    let summary: RunSummary = read_json(&dir.join("summary.json"))?;
    let genome_file = dir.join("best_genome.json");
    let genome: BestGenome = read_json(&genome_file)?;
    let runs = exp.runs();
    let fits = genome.runs.len() == runs.len()
        && genome
            .runs
            .iter()
            .zip(&runs)
            .all(|(g, run)| g.run == run.label && g.weights.len() == exp.shape().genome_len());
    if !fits {
        return Err(CliError::input(format!(
            "{}: its robots do not match the run's config (runs, network size); run again with force=True",
            genome_file.display()
        )));
    }
    let networks = (genome.runs.iter())
        .map(|g| exp.network(&g.weights))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| CliError::input(format!("{}: {e}", genome_file.display())))?;
    let paths = exp
        .room_names()
        .into_par_iter()
        .enumerate()
        .map(|(r, name)| {
            let (k, _) = exp.robot_for_room(r);
            let instance = exp.instance_run(&networks[k], &runs[k], r);
            (name, poses(&instance.trajectory))
        })
        .collect();
    Ok(RunOutput {
        generations,
        rows: summary.rooms.clone(),
        best: genome
            .runs
            .into_iter()
            .map(|g| (g.run, g.weights))
            .collect(),
        summary: serde_json::to_string(&summary).expect("serialisable"),
        paths,
        hidden: exp.shape().hidden(),
    })
}

/// The run itself (no GIL): in memory; or through the CLI's run-directory writer
/// (`fuzzymotiv_pipeline`) into `dir` (fresh or resumed, as `check_out` found it); or a finished `dir`
/// read back.
fn execute(
    loaded: &Loaded,
    out: Option<(&Path, OutState)>,
    hook: &mut Observer<'_>,
) -> Result<RunOutput, CliError> {
    let exp = &loaded.experiment;
    let done = match out {
        Some((dir, OutState::Done)) if dir.join(POPULATION).is_file() => {
            run_dir::read_back(exp, dir, &NoProgress)?
        }
        Some((dir, OutState::Done)) => return read_back_files(loaded, dir),
        Some((dir, state)) => {
            let resume = state == OutState::Unfinished;
            run_dir::execute_with(loaded, dir, &NoProgress, resume, None, hook)?
        }
        None => {
            let start = Instant::now();
            let outcome = exp.run(&mut |_, state| hook(state)).map_err(|e| match e {
                RunError::Interrupted(i) => CliError::runtime(format!(
                    "run cancelled after generation {}",
                    i.stopped.generation
                )),
                e => CliError::runtime(e.to_string()),
            })?;
            Finished::new(exp, outcome, start.elapsed().as_secs_f64())
        }
    };
    Ok(output(loaded, done))
}

/// Generations an unfinished run in `dir` has done already (its checkpoint), so that progress
/// counts on from there.
fn generations_done(loaded: &Loaded, dir: &Path) -> usize {
    let exp = &loaded.experiment;
    let path = StagedDir::staging_path(dir).join(CHECKPOINT);
    Checkpoint::load(&path, &exp.runs(), exp)
        .map_or(0, |cp| cp.runs.iter().map(|r| r.history.len()).sum())
}

/// Evolves as `fuzzymotiv run` does. Returns a dict of plain columns; see `fuzzymotiv.run`.
/// With `out`, the directory is checked as `fuzzymotiv run --out` checks it: the same finished
/// run is read back, an unfinished one resumed, another output replaced only with `force`.
/// `terms`: (name, `supply`) of each term Python computes ([`terms::PyTerm`]).
#[pyfunction]
#[pyo3(signature = (config_path=None, config_text=None, sets=Vec::new(), threads=None, out=None, progress=None, seed=None, force=false, terms=Vec::new()))]
#[allow(clippy::too_many_arguments)]
fn run<'py>(
    py: Python<'py>,
    config_path: Option<PathBuf>,
    config_text: Option<String>,
    sets: Vec<String>,
    threads: Option<Bound<'py, PyAny>>,
    out: Option<PathBuf>,
    progress: Option<Py<PyAny>>,
    seed: Option<Bound<'py, PyAny>>,
    force: bool,
    terms: Vec<(String, Py<PyAny>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let pool = thread_pool(threads.as_ref())?;
    let seed = seed.as_ref().map(seed_arg).transpose()?;
    let failed = terms::TermFailure::default();
    let loaded = terms::load_with_py_terms(
        config_path.as_deref(),
        config_text.as_deref(),
        &sets,
        seed,
        terms,
        &failed,
    )
    .map_err(config_err)?;
    warn_notes(&loaded.notes)?;
    let out = match out {
        None => None,
        Some(dir) => {
            // The identity of a run, as `fuzzymotiv run` checks it.
            let id = run_identity(&loaded.raw);
            let notes = NoteList::default();
            let state = check_out_as(&dir, &id, force, &PYTHON, &notes).map_err(py_err)?;
            warn_notes(&notes.take())?;
            Some((dir, state))
        }
    };
    let already = match &out {
        Some((dir, OutState::Unfinished)) => generations_done(&loaded, dir),
        _ => 0,
    };
    let control = Control::default();
    let result = std::thread::scope(|s| {
        let worker = s.spawn(|| {
            let body = || {
                let mut hook = control.hook(&progress, &loaded, already);
                catch_unwind(AssertUnwindSafe(|| {
                    execute(
                        &loaded,
                        out.as_ref().map(|(d, st)| (d.as_path(), *st)),
                        &mut hook,
                    )
                }))
            };
            let r = match &pool {
                Some(p) => p.install(body),
                None => body(),
            };
            control.finished.store(true, Ordering::SeqCst);
            r
        });
        control.wait(py);
        worker.join().expect("worker panics are caught")
    });
    // A term of Python's that failed stopped the run: its error, not the unwinding's.
    if let Some(e) = failed.lock().ok().and_then(|mut f| f.take()) {
        return Err(e);
    }
    let output = control.outcome(result)?;
    run_dict(py, output)
}

/// How the Python thread and the worker running a run talk: the worker says when it is
/// finished; Ctrl-C or a failing progress callback cancel it (at the next generation).
#[derive(Default)]
struct Control {
    cancel: AtomicBool,
    finished: AtomicBool,
    /// Progress callbacks made, and how many of them the Python thread has checked Ctrl-C
    /// after: the worker waits after each callback until it has, so a Ctrl-C raised during a
    /// callback stops the run at the next generation, however fast the generations are.
    called: std::sync::atomic::AtomicUsize,
    checked: std::sync::atomic::AtomicUsize,
    callback_error: Mutex<Option<PyErr>>,
    interrupted: Mutex<Option<PyErr>>,
}

impl Control {
    /// The worker's hook after every generation: report progress, stop when cancelled.
    fn hook<'a>(
        &'a self,
        progress: &'a Option<Py<PyAny>>,
        loaded: &Loaded,
        already: usize,
    ) -> impl FnMut(&GenerationState<'_>) -> ControlFlow<()> + 'a {
        let total = loaded.experiment.runs().len() * loaded.experiment.ga().generations();
        let mut done = already;
        move |state: &GenerationState<'_>| {
            done += 1;
            if let Some(cb) = progress {
                let best = state.record().stats.max;
                let r = Python::attach(|py| cb.call1(py, (done, total, best)).map(|_| ()));
                if let Err(e) = r {
                    *self.callback_error.lock().expect("not poisoned") = Some(e);
                    self.cancel.store(true, Ordering::SeqCst);
                }
                let call = self.called.fetch_add(1, Ordering::SeqCst) + 1;
                while self.checked.load(Ordering::SeqCst) < call {
                    std::thread::sleep(Duration::from_micros(200));
                }
            }
            if self.cancel.load(Ordering::SeqCst) {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        }
    }

    /// Waits (without the GIL, checking for Ctrl-C every 100 ms and after every progress
    /// callback) until the worker is done, and
    /// checks once more after it is: a Ctrl-C that came during a run shorter than the check's
    /// period is never lost (it raises here, not later in unrelated code).
    fn wait(&self, py: Python<'_>) {
        loop {
            let done = self.finished.load(Ordering::SeqCst);
            if !done {
                py.detach(|| {
                    for _ in 0..500 {
                        let waiting = self.called.load(Ordering::SeqCst)
                            > self.checked.load(Ordering::SeqCst);
                        if waiting || self.finished.load(Ordering::SeqCst) {
                            break;
                        }
                        std::thread::sleep(Duration::from_micros(200));
                    }
                });
            }
            let called = self.called.load(Ordering::SeqCst);
            let mut interrupted = self.interrupted.lock().expect("not poisoned");
            if interrupted.is_none()
                && let Err(e) = py.check_signals()
            {
                *interrupted = Some(e);
                self.cancel.store(true, Ordering::SeqCst);
            }
            drop(interrupted);
            // Checked after every callback made so far: the worker may go on.
            self.checked.store(called, Ordering::SeqCst);
            if done {
                break;
            }
        }
    }

    /// The run's output, or why there is none: Ctrl-C, the callback's error (both stop the run
    /// by breaking its observer), a CLI error, or a panic (a bug).
    fn outcome(
        &self,
        result: std::thread::Result<Result<RunOutput, CliError>>,
    ) -> PyResult<RunOutput> {
        if let Some(e) = self.interrupted.lock().expect("not poisoned").take() {
            return Err(e);
        }
        if let Some(e) = self.callback_error.lock().expect("not poisoned").take() {
            return Err(e);
        }
        match result {
            Ok(r) => r.map_err(py_err),
            Err(payload) => {
                let msg = payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                Err(PyRuntimeError::new_err(format!(
                    "fuzzymotiv panicked (a bug): {msg}"
                )))
            }
        }
    }
}

fn run_dict(py: Python<'_>, o: RunOutput) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("generations", generations_dict(py, &o.generations)?)?;
    d.set_item("rooms", rooms_dict(py, &o.rows)?)?;
    let best = PyDict::new(py);
    for (label, w) in o.best {
        best.set_item(label, PyArray1::from_vec(py, w))?;
    }
    d.set_item("best_genomes", best)?;
    let paths = PyDict::new(py);
    for (room, p) in o.paths {
        let pd = PyDict::new(py);
        pd.set_item(
            "x",
            PyArray1::from_vec(py, p.iter().map(|q| q[0]).collect()),
        )?;
        pd.set_item(
            "y",
            PyArray1::from_vec(py, p.iter().map(|q| q[1]).collect()),
        )?;
        pd.set_item(
            "heading",
            PyArray1::from_vec(py, p.iter().map(|q| q[2]).collect()),
        )?;
        paths.set_item(room, pd)?;
    }
    d.set_item("trajectories", paths)?;
    d.set_item("summary_json", o.summary)?;
    d.set_item("hidden", o.hidden)?;
    Ok(d)
}

/// The columns of `generations.csv`.
fn generations_dict<'py>(
    py: Python<'py>,
    generations: &[GenerationRow],
) -> PyResult<Bound<'py, PyDict>> {
    let g = PyDict::new(py);
    let col = |f: &dyn Fn(&GenerationRow) -> Fixed<9>| {
        PyArray1::from_vec(py, generations.iter().map(|r| f(r).0).collect())
    };
    g.set_item(
        "generation",
        PyArray1::from_vec(
            py,
            generations.iter().map(|r| r.generation as i64).collect(),
        ),
    )?;
    g.set_item("best", col(&|r| r.best))?;
    g.set_item("mean", col(&|r| r.mean))?;
    g.set_item("std", col(&|r| r.std))?;
    g.set_item("min", col(&|r| r.min))?;
    g.set_item("max", col(&|r| r.max))?;
    g.set_item("a", col(&|r| r.a))?;
    g.set_item("g", col(&|r| r.g))?;
    g.set_item("l", col(&|r| r.l))?;
    g.set_item("b", col(&|r| r.b))?;
    g.set_item(
        "room",
        generations
            .iter()
            .map(|r| r.room.clone())
            .collect::<Vec<_>>(),
    )?;
    Ok(g)
}

/// The per-room table's columns.
fn rooms_dict<'py>(py: Python<'py>, rows: &[RoomRow]) -> PyResult<Bound<'py, PyDict>> {
    let rooms = PyDict::new(py);
    rooms.set_item(
        "room",
        rows.iter().map(|r| r.room.clone()).collect::<Vec<_>>(),
    )?;
    let rcol = |f: &dyn Fn(&RoomRow) -> f64| {
        PyArray1::from_vec(py, rows.iter().map(f).collect::<Vec<_>>())
    };
    rooms.set_item("average_fitness", rcol(&|r| r.average_fitness))?;
    rooms.set_item("exploration_pct", rcol(&|r| r.exploration_pct))?;
    rooms.set_item(
        "recognition_pct",
        rcol(&|r| r.recognition_pct.unwrap_or(f64::NAN)),
    )?;
    rooms.set_item("battery_pct", rcol(&|r| r.battery_pct))?;
    rooms.set_item("homing_pct", rcol(&|r| r.homing_pct))?;
    rooms.set_item("r_node", rows.iter().map(|r| r.r_node).collect::<Vec<_>>())?;
    // A mission run's columns, as table.md has them: % missions done, then one per term
    // measured beyond a, g, l, b (`terms_pct.NAME`, summary.json's `terms_pct`).
    if rows.iter().any(|r| r.mission_done_pct.is_some()) {
        rooms.set_item(
            "mission_done_pct",
            rcol(&|r| r.mission_done_pct.unwrap_or(f64::NAN)),
        )?;
    }
    let mut terms: Vec<&String> = rows.iter().flat_map(|r| r.terms_pct.keys()).collect();
    terms.sort();
    terms.dedup();
    for name in terms {
        let values = rcol(&|r| r.terms_pct.get(name).copied().unwrap_or(f64::NAN));
        rooms.set_item(format!("terms_pct.{name}"), values)?;
    }
    Ok(rooms)
}

/// One trial of `genome` in `room` under base seed `seed`, exactly as `fuzzymotiv replay
/// --room ROOM --seed SEED` runs it (the room-modelling stream of that seed). With `terms`
/// (the names of terms Python supplies), `supply` is called once with the trial as a
/// `(1, 1, T + 1)` batch; their values, by name, set F.
#[pyfunction]
#[pyo3(signature = (genome, room, seed, config_path=None, config_text=None, sets=Vec::new(), terms=Vec::new(), supply=None))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    genome: Vec<f64>,
    room: String,
    seed: Bound<'py, PyAny>,
    config_path: Option<PathBuf>,
    config_text: Option<String>,
    sets: Vec<String>,
    terms: Vec<String>,
    supply: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let seed = seed_arg(&seed)?;
    finite(
        "genome",
        &genome,
        |k| format!("weight {k}"),
        "expected the network's weights",
    )?;
    let loaded = terms::load_with_terms(
        config_path.as_deref(),
        config_text.as_deref(),
        &sets,
        Some(seed),
        &terms,
    )
    .map_err(config_err)?;
    warn_notes(&loaded.notes)?;
    // As `replay`: neither recognition nor online orientation changes a trajectory.
    let exp = gym::single_room(&loaded, &room, &terms)?;
    let instance = instance_of(py, &exp, &genome)?;
    let d = trajectory_dict(py, &instance.trajectory, exp.shape().inputs())?;
    let name = &exp.arenas()[0].room().name;
    let (mut values, mut f) = (instance.terms, instance.f);
    if let (false, Some(supply)) = (terms.is_empty(), &supply) {
        let trial = terms::one_trial(values, instance.trajectory);
        let e = terms::supply_trials(py, &exp, name, vec![trial], &terms, supply)?.remove(0);
        (values, f) = (e.per_room[0].terms, e.fitness);
    }
    d.set_item("a", values.a)?;
    d.set_item("g", values.g)?;
    d.set_item("l", values.l)?;
    d.set_item("b", values.b)?;
    for (t, v) in terms.iter().zip(values.user.as_slice()) {
        if d.contains(t)? || ["F", "room", "seed"].contains(&t.as_str()) {
            return Err(input_err(format!(
                "terms[{t:?}]: simulate reports each term of your own by its name, and {t:?} is one of its other columns; name the term otherwise"
            )));
        }
        d.set_item(t, v)?;
    }
    d.set_item("F", f)?;
    d.set_item("room", name)?;
    d.set_item("seed", seed)?;
    Ok(d)
}

/// The instance run of `genome` in `exp`'s one room (`exp` from [`gym::single_room`]), as
/// `fm.simulate` and `fm.frames` run it; a genome of the wrong length names the network's size.
fn instance_of(py: Python<'_>, exp: &Experiment, genome: &[f64]) -> PyResult<InstanceRun> {
    let want = exp.shape().genome_len();
    if genome.len() != want {
        return Err(input_err(format!(
            "genome: {} weights, but {} needs {want} ({})",
            genome.len(),
            network_phrase(exp),
            network_sizes(exp)
        )));
    }
    let run = exp.runs().remove(0);
    let network = exp.network(genome).map_err(|e| input_err(e.to_string()))?;
    Ok(py.detach(|| exp.instance_run(&network, &run, 0)))
}

/// `exp`'s network as errors name it: `an 8-6-2 network`, `a 7-6-2 network`.
pub(crate) fn network_phrase(exp: &Experiment) -> String {
    let s = exp.shape();
    let n = s.inputs();
    let article = if [8, 11, 18].contains(&n) { "an" } else { "a" };
    format!("{article} {n}-{}-2 network", s.hidden())
}

/// Where `exp`'s network's sizes come from, for errors: `network.hidden = 6; robot khepera: 8
/// sensors`.
pub(crate) fn network_sizes(exp: &Experiment) -> String {
    let spec = exp.trial_params().robot().spec();
    format!(
        "network.hidden = {}; robot {}: {} sensors",
        exp.shape().hidden(),
        spec.name(),
        spec.sensors()
    )
}

/// The robot `robot=` names, read as the CLI reads one (`load_robot`): a built-in robot
/// ([`BUILTIN_ROBOTS`]) or a robot file (a path, relative to the working directory), checked
/// (a bad file's error names it and its field). Returns `name`, `file` (the built-in name or
/// the file's absolute path: what a config's `robot.file` takes), `sensors`, `labels`,
/// `reading_max` and `radius`.
#[pyfunction]
fn robot_info(py: Python<'_>, robot: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let entry = robot.to_string_lossy().into_owned();
    let file = if RobotSpec::builtin(&entry).is_some() {
        entry
    } else {
        let path = std::path::absolute(&robot).unwrap_or(robot.clone());
        if entry.is_empty() || !path.is_file() {
            return Err(ConfigError::new_err(format!(
                "robot: {entry:?} is neither a built-in robot ({}) nor a robot file (looked for {})",
                BUILTIN_ROBOTS.join(", "),
                path.display()
            )));
        }
        path.display().to_string()
    };
    let spec = load_robot(&file, "robot").map_err(config_err)?;
    let d = PyDict::new(py);
    d.set_item("name", spec.name())?;
    d.set_item("file", file)?;
    d.set_item("sensors", spec.sensors())?;
    d.set_item("labels", spec.labels().to_vec())?;
    d.set_item("reading_max", spec.reading_max())?;
    d.set_item("radius", spec.radius())?;
    Ok(d)
}

/// A trajectory as numpy columns (poses, `sensors` readings per step, motors and the
/// per-step flags).
fn trajectory_dict<'py>(
    py: Python<'py>,
    tr: &Trajectory,
    sensors: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let poses =
        |k: usize| -> Vec<f64> { tr.poses.iter().map(|p| [p.x, p.y, p.heading][k]).collect() };
    d.set_item("x", PyArray1::from_vec(py, poses(0)))?;
    d.set_item("y", PyArray1::from_vec(py, poses(1)))?;
    d.set_item("heading", PyArray1::from_vec(py, poses(2)))?;
    let t = tr.sensors.len();
    let flat: Vec<f64> = tr.sensors.iter().flat_map(|r| r.iter().copied()).collect();
    d.set_item(
        "sensors",
        Array2::from_shape_vec((t, sensors), flat)
            .expect("T × N")
            .into_pyarray(py),
    )?;
    let motors: Vec<f64> = tr.motors.iter().flatten().copied().collect();
    d.set_item(
        "motors",
        Array2::from_shape_vec((tr.motors.len(), 2), motors)
            .expect("T × 2")
            .into_pyarray(py),
    )?;
    let actions: Vec<&str> = tr.actions.iter().map(|a| a.label()).collect();
    d.set_item("action", numpy_strings(py, &actions)?)?;
    d.set_item("idle", PyArray1::from_vec(py, tr.idle.clone()))?;
    d.set_item("energy", PyArray1::from_vec(py, tr.energy.clone()))?;
    d.set_item("escaped", PyArray1::from_vec(py, tr.escaped.clone()))?;
    d.set_item("collision", PyArray1::from_vec(py, tr.collisions.clone()))?;
    Ok(d)
}

/// A numpy array of Python strings (dtype `<U…`).
fn numpy_strings<'py>(py: Python<'py>, items: &[&str]) -> PyResult<Bound<'py, PyAny>> {
    let np = py.import("numpy")?;
    np.call_method1("array", (items.to_vec(),))
}

/// The native module `fuzzymotiv._fuzzymotiv`.
#[pymodule]
fn _fuzzymotiv(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("FuzzymotivError", m.py().get_type::<FuzzymotivError>())?;
    m.add("FuzzymotivOSError", os_error_type(m.py())?.bind(m.py()))?;
    m.add("ConfigError", m.py().get_type::<ConfigError>())?;
    m.add("OutputExistsError", m.py().get_type::<OutputExistsError>())?;
    m.add("ResetNeeded", m.py().get_type::<ResetNeeded>())?;
    m.add(
        "DependencyNotInstalled",
        m.py().get_type::<DependencyNotInstalled>(),
    )?;
    m.add("MAX_THREADS", MAX_THREADS)?;
    m.add("ROBOTS", BUILTIN_ROBOTS.to_vec())?;
    m.add("VERSION", fuzzymotiv::VERSION)?;
    m.add("MODEL_VERSION", fuzzymotiv::MODEL_VERSION)?;
    m.add_function(wrap_pyfunction!(fuzzy_fitness_one, m)?)?;
    m.add_function(wrap_pyfunction!(fuzzy_fitness_many, m)?)?;
    m.add_function(wrap_pyfunction!(explain, m)?)?;
    m.add_function(wrap_pyfunction!(export_fll, m)?)?;
    m.add_function(wrap_pyfunction!(export::export_controller, m)?)?;
    m.add_function(wrap_pyfunction!(export::export_controller_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(robustness::robustness, m)?)?;
    m.add_function(wrap_pyfunction!(recognise::recognise, m)?)?;
    m.add_function(wrap_pyfunction!(rooms, m)?)?;
    m.add_function(wrap_pyfunction!(robot_info, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(frames::frames, m)?)?;
    m.add_function(wrap_pyfunction!(frames::save_gif, m)?)?;
    m.add_function(wrap_pyfunction!(frames::last_frame, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_plan, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_run_job, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_prepare, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_merge, m)?)?;
    m.add_function(wrap_pyfunction!(study::study_run, m)?)?;
    m.add_class::<problem::Problem>()?;
    m.add_class::<ga::Ga>()?;
    m.add_class::<gym::GymCore>()?;
    m.add_function(wrap_pyfunction!(gym::network_outputs, m)?)?;
    stats::register(m)?;
    Ok(())
}
