//! Terms Python supplies (`fm.Problem(..., terms={"name": fn})`): configs resolved with them
//! registered, the generation's evaluation trials handed to Python as numpy arrays, and the
//! values it returns checked and filled in.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use fuzzymotiv::experiment::RoomScore;
use fuzzymotiv::experiment::UserTerm;
use fuzzymotiv::experiment::{Evaluation, Experiment, RawConfig, Setup};
use fuzzymotiv::fitness::{FitnessTerms, LIBRARY_TERMS, Term, TermId, TrialRecord, UserValues};
use fuzzymotiv::simulation::Trajectory;
use fuzzymotiv_pipeline::files::bounded::read_input;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::inputs::{CONFIG, Loaded, RoomDir, resolve};
use numpy::ndarray::{Array2, Array3, Array4};
use numpy::{IntoPyArray, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{input_err, load, py_float};

/// `resolve`, with the terms named `user` supplied by Python (none: `resolve` itself).
pub(crate) fn resolve_with_terms(
    raw: RawConfig,
    base: &Path,
    source: &str,
    user: &[String],
) -> Result<Loaded, CliError> {
    if user.is_empty() {
        return resolve(raw, base, source);
    }
    let user: Vec<UserTerm> = user.iter().map(UserTerm::supplied).collect();
    resolve_with_user(raw, base, source, &user)
}

/// `resolve`, with the terms `user` registered.
fn resolve_with_user(
    raw: RawConfig,
    base: &Path,
    source: &str,
    user: &[UserTerm],
) -> Result<Loaded, CliError> {
    let setup = Setup::resolve_with_terms(raw, source, &RoomDir(base), user)?;
    Ok(Loaded {
        raw: setup.raw,
        experiment: setup.experiment,
        notes: setup.notes,
    })
}

/// `load`, with the terms named `user` supplied by Python.
pub(crate) fn load_with_terms(
    config_path: Option<&Path>,
    config_text: Option<&str>,
    sets: &[String],
    seed: Option<u64>,
    user: &[String],
) -> Result<Loaded, CliError> {
    if user.is_empty() {
        return load(config_path, config_text, sets, seed);
    }
    let (raw, base, source) = parse_config(config_path, config_text, sets, seed)?;
    resolve_with_terms(raw, &base, &source, user)
}

/// A config parsed the CLI's way, not yet resolved: a file (`config_path`, its folder the base
/// of its room files), TOML text or the built-in defaults (the working directory the base),
/// with `--set` overrides and a seed. Returns the raw config, the base and the source's name.
pub(crate) fn parse_config(
    config_path: Option<&Path>,
    config_text: Option<&str>,
    sets: &[String],
    seed: Option<u64>,
) -> Result<(RawConfig, PathBuf, String), CliError> {
    let mut sets = sets.to_vec();
    if let Some(s) = seed {
        sets.push(format!("seed={s}"));
    }
    let (text, source, base) = match (config_text, config_path) {
        (Some(text), _) => (text.to_string(), "(config text)".into(), PathBuf::from(".")),
        (None, Some(p)) => {
            let text = read_input(p, CONFIG)?;
            let base = p.parent().map(Path::to_path_buf).unwrap_or_default();
            (text, p.display().to_string(), base)
        }
        (None, None) => (
            String::new(),
            "(built-in defaults)".into(),
            PathBuf::from("."),
        ),
    };
    let raw = RawConfig::parse(&text, &source, &sets)?;
    Ok((raw, base, source))
}

/// A `(pop, rooms, len)` array of `f(trajectory)`'s values.
fn per_step<'py, T: numpy::Element + Copy>(
    py: Python<'py>,
    recorded: &[(Evaluation, Vec<Trajectory>)],
    len: usize,
    f: impl Fn(&Trajectory) -> Vec<T>,
) -> Bound<'py, PyAny> {
    let rooms = recorded.first().map_or(0, |(_, t)| t.len());
    let flat: Vec<T> = recorded
        .iter()
        .flat_map(|(_, ts)| ts.iter().flat_map(&f))
        .collect();
    Array3::from_shape_vec((recorded.len(), rooms, len), flat)
        .expect("pop × rooms × len")
        .into_pyarray(py)
        .into_any()
}

/// The generation's evaluation trials as the dict `fuzzymotiv.Trials` is made from.
pub(crate) fn record<'py>(
    py: Python<'py>,
    exp: &Experiment,
    rooms: &[String],
    recorded: &[(Evaluation, Vec<Trajectory>)],
) -> PyResult<Bound<'py, PyDict>> {
    let steps = exp.trial_params().steps();
    let sensors = exp.shape().inputs();
    record_trials(
        py,
        (steps, sensors),
        exp.measures_mission(),
        rooms,
        recorded,
    )
}

/// [`record`] of trials of `steps` steps of a robot of `sensors` sensors, with the mission
/// terms when `mission`.
fn record_trials<'py>(
    py: Python<'py>,
    (steps, sensors): (usize, usize),
    mission: bool,
    rooms: &[String],
    recorded: &[(Evaluation, Vec<Trajectory>)],
) -> PyResult<Bound<'py, PyDict>> {
    let (pop, n_rooms) = (recorded.len(), rooms.len());
    let d = PyDict::new(py);
    let poses = steps + 1;
    d.set_item(
        "x",
        per_step(py, recorded, poses, |t| {
            t.poses.iter().map(|p| p.x).collect()
        }),
    )?;
    d.set_item(
        "y",
        per_step(py, recorded, poses, |t| {
            t.poses.iter().map(|p| p.y).collect()
        }),
    )?;
    d.set_item(
        "heading",
        per_step(py, recorded, poses, |t| {
            t.poses.iter().map(|p| p.heading).collect()
        }),
    )?;
    d.set_item(
        "actions",
        per_step(py, recorded, steps, |t| {
            t.actions.iter().map(|&a| a as i64).collect()
        }),
    )?;
    d.set_item(
        "collisions",
        per_step(py, recorded, steps, |t| t.collisions.clone()),
    )?;
    d.set_item("idle", per_step(py, recorded, steps, |t| t.idle.clone()))?;
    d.set_item(
        "energy",
        per_step(py, recorded, steps, |t| t.energy.clone()),
    )?;
    let readings: Vec<f64> = (recorded.iter())
        .flat_map(|(_, ts)| ts.iter().flat_map(|t| t.sensors.iter()))
        .flat_map(|r| r.iter().copied())
        .collect();
    d.set_item(
        "sensors",
        Array4::from_shape_vec((pop, n_rooms, steps, sensors), readings)
            .expect("pop × rooms × T × sensors")
            .into_pyarray(py),
    )?;
    let executed: Vec<i64> = (recorded.iter())
        .flat_map(|(e, _)| e.per_room.iter().map(|s| s.executed as i64))
        .collect();
    d.set_item(
        "executed",
        Array2::from_shape_vec((pop, n_rooms), executed)
            .expect("pop × rooms")
            .into_pyarray(py),
    )?;
    d.set_item("rooms", rooms.to_vec())?;
    let terms = PyDict::new(py);
    let measured = if mission { 8 } else { 4 };
    for name in &LIBRARY_TERMS[..measured] {
        let id = TermId::library(name).expect("a library term");
        let values: Vec<f64> = (recorded.iter())
            .flat_map(|(e, _)| e.per_room.iter().map(move |s| s.terms.get(id)))
            .collect();
        let values = Array2::from_shape_vec((pop, n_rooms), values).expect("pop × rooms");
        terms.set_item(*name, values.into_pyarray(py))?;
    }
    d.set_item("terms", terms)?;
    Ok(d)
}

/// Fills each evaluation's supplied terms from `values` `(pop, rooms, U)`: the right shape, and
/// each value a number in [0, 1], or an error naming the term.
pub(crate) fn supplied_values(
    values: &Bound<'_, PyAny>,
    names: &[String],
    evals: &mut [Evaluation],
) -> PyResult<()> {
    let rooms = evals.first().map_or(0, |e| e.per_room.len());
    let want = [evals.len(), rooms, names.len()];
    let array: PyReadonlyArray3<'_, f64> = values.extract().map_err(|_| {
        input_err(format!(
            "terms {names:?}: expected their values as a float array of shape {want:?} (genomes, rooms, terms)"
        ))
    })?;
    if array.shape() != want {
        return Err(input_err(format!(
            "terms {names:?}: expected values of shape {want:?} (genomes, rooms, terms), got {:?}",
            array.shape()
        )));
    }
    for ((i, r, k), &v) in array.as_array().indexed_iter() {
        if !(0.0..=1.0).contains(&v) {
            return Err(input_err(format!(
                "terms[{:?}]: `{}` (genome {i}, room {r}) is not a number in [0, 1]; a term's value must be one",
                names[k],
                py_float(v)
            )));
        }
        evals[i].per_room[r].terms.user.as_mut_slice()[k] = v;
    }
    Ok(())
}

/// One finished trial in the one room of `exp` (an experiment of [`crate::gym::single_room`]):
/// its terms and its whole trajectory (`T` steps, the idle rest after an end at home included),
/// as [`supply_trials`] takes it.
pub(crate) fn one_trial(
    terms: FitnessTerms,
    trajectory: Trajectory,
) -> (Evaluation, Vec<Trajectory>) {
    let executed = trajectory.idle.iter().filter(|&&idle| !idle).count();
    let score = RoomScore {
        f: 0.0,
        terms,
        executed,
    };
    let evaluation = Evaluation {
        fitness: 0.0,
        per_room: vec![score],
    };
    (evaluation, vec![trajectory])
}

/// The terms Python supplies for finished trials in `room`, the one room of `exp`, as
/// `fm.Problem` gets them: `supply(trials)` called once with the trials as a `(n, 1, T + 1)`
/// batch, its values checked ([`supplied_values`]) and F refitted ([`Experiment::refit`]).
/// Returns each trial's evaluation: its terms with the supplied values, its F.
pub(crate) fn supply_trials(
    py: Python<'_>,
    exp: &Experiment,
    room: &str,
    mut recorded: Vec<(Evaluation, Vec<Trajectory>)>,
    names: &[String],
    supply: &Bound<'_, PyAny>,
) -> PyResult<Vec<Evaluation>> {
    for (e, _) in &mut recorded {
        for s in &mut e.per_room {
            s.terms.user = UserValues::zeros(names.len());
        }
    }
    let trials = record(py, exp, &[room.to_string()], &recorded)?;
    let values = supply.call1((trials,))?;
    let mut evals: Vec<Evaluation> = recorded.into_iter().map(|(e, _)| e).collect();
    supplied_values(&values, names, &mut evals)?;
    for e in &mut evals {
        exp.refit(e);
    }
    Ok(evals)
}

/// The first error of a term Python computes during `fm.run` (`terms=`), shared by its terms
/// and the run, which raises it.
pub(crate) type TermFailure = Arc<Mutex<Option<PyErr>>>;

/// What a [`PyTerm`] unwinds with after keeping its error in its [`TermFailure`]: not a panic
/// (no message is printed); `fm.run` catches it and raises the kept error.
struct TermFailed;

/// A term of `fm.run(terms={"name": fn})`: computed by the library from each finished trial
/// (an evaluation trial, a room-modelling run or a test run), as its own terms are, by
/// `supply(trials)` (`fuzzymotiv.trials._supplier` of the one term) called with the trial as a
/// `(1, 1)` batch, as `fm.simulate(terms=...)` gives it. A value outside [0, 1], of the wrong
/// shape or type, or an exception is kept in `failed`, and the run stops ([`TermFailed`]).
pub(crate) struct PyTerm {
    name: String,
    supply: Py<PyAny>,
    failed: TermFailure,
}

impl std::fmt::Debug for PyTerm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PyTerm({:?})", self.name)
    }
}

impl PyTerm {
    /// The term's value of `trial`, or why there is none.
    fn call(&self, py: Python<'_>, trial: &TrialRecord<'_>) -> PyResult<f64> {
        let mut terms = *trial.terms;
        terms.user = UserValues::zeros(1);
        let room = trial.arena.room().name.clone();
        let recorded = vec![one_trial(terms, trial.trajectory.clone())];
        let steps = trial.trajectory.actions.len();
        let sensors = trial.arena.sensors();
        let mission = trial.terms.mission.is_some();
        let trials = record_trials(py, (steps, sensors), mission, &[room], &recorded)?;
        let values = self.supply.bind(py).call1((trials,))?;
        let mut evals: Vec<Evaluation> = recorded.into_iter().map(|(e, _)| e).collect();
        supplied_values(&values, std::slice::from_ref(&self.name), &mut evals)?;
        Ok(evals[0].per_room[0].terms.user.as_slice()[0])
    }
}

impl Term for PyTerm {
    fn value(&self, trial: &TrialRecord<'_>) -> f64 {
        let failed = || self.failed.lock().map_or(true, |f| f.is_some());
        if failed() {
            std::panic::resume_unwind(Box::new(TermFailed));
        }
        match Python::attach(|py| self.call(py, trial)) {
            Ok(v) => v,
            Err(e) => {
                if let Ok(mut f) = self.failed.lock() {
                    f.get_or_insert(e);
                }
                std::panic::resume_unwind(Box::new(TermFailed))
            }
        }
    }
}

/// `load`, with the terms `terms` (name, `supply`) that Python computes registered as
/// [`PyTerm`]s sharing `failed`.
pub(crate) fn load_with_py_terms(
    config_path: Option<&Path>,
    config_text: Option<&str>,
    sets: &[String],
    seed: Option<u64>,
    terms: Vec<(String, Py<PyAny>)>,
    failed: &TermFailure,
) -> Result<Loaded, CliError> {
    if terms.is_empty() {
        return load(config_path, config_text, sets, seed);
    }
    let (raw, base, source) = parse_config(config_path, config_text, sets, seed)?;
    let user: Vec<UserTerm> = (terms.into_iter())
        .map(|(name, supply)| {
            let term = PyTerm {
                name: name.clone(),
                supply,
                failed: failed.clone(),
            };
            UserTerm::computed(name, Arc::new(term))
        })
        .collect();
    resolve_with_user(raw, &base, &source, &user)
}
