//! `fm.Problem`: one evolution's validated experiment, evaluated in batches for any optimiser.
//!
//! Built once by the loader `fm.run` uses; `evaluate` runs the library's own population
//! evaluation (the GA's streams: seed, run, generation, individual, room) on the library's
//! threads with the GIL released, so generation g's population gives the F that `fm.run`
//! logged for generation g, on any number of threads.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use fuzzymotiv::evolution::Genome;
use fuzzymotiv::evolution::Population;
use fuzzymotiv::experiment::Descriptors;
use fuzzymotiv::experiment::Evaluation;
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::experiment::{RawConfig, Training};
use fuzzymotiv::fitness::{LIBRARY_TERMS, TermId};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

use crate::terms::{load_with_terms, parse_config, record, resolve_with_terms, supplied_values};
use crate::{
    config_err, input_err, network_phrase, network_sizes, py_float, seed_arg, thread_pool,
    whole_number,
};

/// Distinct seeds whose experiments a problem keeps (besides its own).
const SEEDS_KEPT: usize = 4;

/// The native problem (`fuzzymotiv.Problem` wraps it).
#[pyclass(module = "fuzzymotiv._fuzzymotiv", name = "Problem", frozen)]
pub struct Problem {
    /// The resolved config (rooms recorded absolute), for experiments under other seeds.
    raw: RawConfig,
    exp: Arc<Experiment>,
    run: Run,
    pool: Option<rayon::ThreadPool>,
    /// Experiments built for other seeds, most recent last.
    others: Mutex<Vec<(u64, Arc<Experiment>)>>,
    /// The names of the terms Python supplies (`terms=`), in registration order.
    user: Vec<String>,
}

impl Problem {
    /// The experiment under `seed` (`None`: the config's), built by the loader once per seed.
    pub(crate) fn experiment_for(&self, seed: Option<u64>) -> PyResult<Arc<Experiment>> {
        let Some(seed) = seed.filter(|&s| s != self.exp.seed()) else {
            return Ok(self.exp.clone());
        };
        let mut others = self.others.lock().expect("not poisoned");
        if let Some((_, e)) = others.iter().find(|(s, _)| *s == seed) {
            return Ok(e.clone());
        }
        let mut raw = self.raw.clone();
        raw.seed = seed;
        let exp = Arc::new(
            resolve_with_terms(raw, Path::new("."), "(problem)", &self.user)
                .map_err(config_err)?
                .experiment,
        );
        if others.len() == SEEDS_KEPT {
            others.remove(0);
        }
        others.push((seed, exp.clone()));
        Ok(exp)
    }

    pub(crate) fn run(&self) -> &Run {
        &self.run
    }

    /// The resolved config under `seed`, as TOML (what a GA's state records).
    pub(crate) fn config_toml(&self, seed: u64) -> String {
        let mut raw = self.raw.clone();
        raw.seed = seed;
        raw.to_toml()
    }

    /// Runs `f` on the problem's pool (or rayon's global one), without the GIL; a panic (a
    /// bug) becomes a `RuntimeError`.
    pub(crate) fn compute<T: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce() -> T + Send,
    ) -> PyResult<T> {
        py.detach(|| {
            catch_unwind(AssertUnwindSafe(|| match &self.pool {
                Some(p) => p.install(f),
                None => f(),
            }))
        })
        .map_err(|payload| {
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            PyRuntimeError::new_err(format!("fuzzymotiv panicked (a bug): {msg}"))
        })
    }
}

/// Genomes from a `(population, genome_size)` array, checked: the width, finite weights.
pub(crate) fn genomes_arg(
    arg: &str,
    genomes: &PyReadonlyArray2<'_, f64>,
    exp: &Experiment,
) -> PyResult<Population> {
    let want = exp.shape().genome_len();
    let [rows, cols] = [genomes.shape()[0], genomes.shape()[1]];
    if cols != want {
        return Err(input_err(format!(
            "{arg}: expected a (population, {want}) array ({} has {want} weights; {}), got shape ({rows}, {cols})",
            network_phrase(exp),
            network_sizes(exp)
        )));
    }
    let view = genomes.as_array();
    if let Some(((i, j), v)) = view.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(input_err(format!(
            "{arg}: `{}` (row {i}, weight {j}) is not a finite number; expected the networks' weights",
            py_float(*v)
        )));
    }
    let genomes = view.rows().into_iter().map(|r| r.to_vec()).collect();
    exp.population(genomes)
        .map_err(|e| input_err(format!("{arg}: {e}")))
}

/// A whole number ≥ 0 (`generation`).
fn index_arg(arg: &str, obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    match whole_number(obj) {
        Ok(n) if (0..=u32::MAX as i128).contains(&n) => Ok(n as usize),
        Ok(n) => Err(input_err(format!(
            "{arg}: expected a whole number from 0 to {}, got {n}",
            u32::MAX
        ))),
        Err(repr) => Err(input_err(format!(
            "{arg}: expected a whole number ≥ 0, got {repr}"
        ))),
    }
}

/// A descriptor column: one of [`Descriptors::NAMES`], or a fitness term by name.
#[derive(Clone, Copy)]
enum Column {
    Descriptor(usize),
    Term(TermId),
}

/// The terms `exp` measures, by name: its inputs (`term_names`), then the library's terms it
/// measures (a, g, l, b; the mission terms when a motivation weighs one) and its user terms.
fn measured_terms(exp: &Experiment) -> Vec<(String, TermId)> {
    let mut named: Vec<(String, TermId)> = (exp.motivations().input_names().into_iter())
        .zip(exp.input_terms().iter().copied())
        .collect();
    let library = LIBRARY_TERMS
        .iter()
        .take(if exp.measures_mission() { 8 } else { 4 })
        .map(|&n| (n.to_string(), TermId::library(n).expect("a library term")));
    let user =
        (exp.user_terms().iter().enumerate()).map(|(k, u)| (u.name.clone(), TermId::User(k)));
    for (name, id) in library.chain(user) {
        if !named.iter().any(|(n, _)| *n == name) {
            named.push((name, id));
        }
    }
    named
}

/// Descriptor columns from names (`None`: all of [`Descriptors::NAMES`], in order); a name
/// that is no descriptor may be any term the experiment measures.
fn descriptor_columns(names: Option<Vec<String>>, exp: &Experiment) -> PyResult<Vec<Column>> {
    let Some(names) = names else {
        return Ok((0..Descriptors::NAMES.len())
            .map(Column::Descriptor)
            .collect());
    };
    let terms = measured_terms(exp);
    names
        .iter()
        .map(|n| {
            if let Some(k) = Descriptors::NAMES.iter().position(|k| k == n) {
                return Ok(Column::Descriptor(k));
            }
            if let Some((_, id)) = terms.iter().find(|(t, _)| t == n) {
                return Ok(Column::Term(*id));
            }
            let terms: Vec<&str> = terms.iter().map(|(t, _)| t.as_str()).collect();
            Err(input_err(format!(
                "descriptors: unknown descriptor {n:?}; expected some of {:?} or of the terms {terms:?}",
                Descriptors::NAMES
            )))
        })
        .collect()
}

/// The evaluations of a population, with each room's descriptors when asked for.
type Evaluated = (Vec<Evaluation>, Option<Vec<Vec<Descriptors>>>);

#[pymethods]
impl Problem {
    #[new]
    #[pyo3(signature = (config_path=None, config_text=None, sets=Vec::new(), room=None, threads=None, seed=None, terms=Vec::new()))]
    fn new(
        config_path: Option<PathBuf>,
        config_text: Option<String>,
        sets: Vec<String>,
        room: Option<String>,
        threads: Option<Bound<'_, PyAny>>,
        seed: Option<Bound<'_, PyAny>>,
        terms: Vec<String>,
    ) -> PyResult<Problem> {
        let pool = thread_pool(threads.as_ref())?;
        let seed = seed.as_ref().map(seed_arg).transpose()?;
        let (path, text) = (config_path.as_deref(), config_text.as_deref());
        let (raw, _, _) = parse_config(path, text, &sets, seed).map_err(config_err)?;
        // A problem only evaluates fitness: room modelling (AEM), which needs two rooms, never
        // runs, so a one-room config needs no `aem.enabled = false`.
        let mut sets = sets;
        if raw.rooms.len() < 2 {
            sets.push("aem.enabled=false".into());
        }
        let loaded = load_with_terms(path, text, &sets, seed, &terms).map_err(config_err)?;
        crate::warn_notes(&loaded.notes)?;
        let exp = loaded.experiment;
        let runs = exp.runs();
        let labels: Vec<&str> = runs.iter().map(|r| r.label.as_str()).collect();
        let per_room = exp.training() == Training::PerRoom;
        let run = match room {
            None if !per_room => runs[0].clone(),
            None => {
                return Err(input_err(format!(
                    "room: training = \"per-room\" evolves one robot per room; choose one with room=NAME, one of {labels:?}"
                )));
            }
            Some(name) if !per_room => {
                return Err(input_err(format!(
                    "room: {name:?} given, but training = \"all-rooms\" evaluates every robot in all the rooms {labels:?} together; room= is for training = \"per-room\"",
                    labels = exp.room_names()
                )));
            }
            Some(name) => match runs.iter().find(|r| r.label == name) {
                Some(r) => r.clone(),
                None => {
                    return Err(input_err(format!(
                        "room: no room {name:?} in the config; expected one of {labels:?}"
                    )));
                }
            },
        };
        Ok(Problem {
            raw: loaded.raw,
            exp: Arc::new(exp),
            run,
            pool,
            others: Mutex::new(Vec::new()),
            user: terms,
        })
    }

    /// The names of the TSK's inputs, one per motivation, in order (`a`, `g`, `l`, `b` for
    /// the paper's four): the last axis of `evaluate`'s terms.
    #[getter]
    fn term_names(&self) -> Vec<String> {
        self.exp.motivations().input_names()
    }

    /// The names of the terms Python supplies, in registration order.
    #[getter]
    fn user_terms(&self) -> Vec<String> {
        self.user.clone()
    }

    /// Weights per genome.
    #[getter]
    fn genome_size(&self) -> usize {
        self.exp.shape().genome_len()
    }

    /// Names of the rooms each genome is evaluated in, in order.
    #[getter]
    fn rooms(&self) -> Vec<String> {
        let names = self.exp.room_names();
        self.run.rooms.iter().map(|&r| names[r].clone()).collect()
    }

    /// The weights of every motivation of the config, in input order (the paper's C, H, O, E
    /// first when it has them), normalised as the config loader does.
    #[getter]
    fn motivations(&self) -> Vec<f64> {
        self.exp.motivations().weights()
    }

    /// The names of the motivations, in the order of `motivations`.
    #[getter]
    fn motivation_names(&self) -> Vec<String> {
        let m = self.exp.motivations();
        m.iter().map(|x| x.name().to_string()).collect()
    }

    /// The config's base seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.exp.seed()
    }

    /// The run's label: `all`, or the room of a per-room run.
    #[getter]
    fn label(&self) -> String {
        self.run.label.clone()
    }

    /// `ga.population` and `ga.generations` of the config.
    #[getter]
    fn ga_sizes(&self) -> (usize, usize) {
        let ga = self.exp.ga();
        (ga.population(), ga.generations())
    }

    /// The robot's name (`robot` of its file: `khepera`, `epuck2`, `thymio2`, ...).
    #[getter]
    fn robot(&self) -> String {
        self.exp.trial_params().robot().spec().name().to_string()
    }

    /// The robot's sensors: the network's inputs N.
    #[getter]
    fn sensors(&self) -> usize {
        self.exp.shape().inputs()
    }

    /// Hidden units of the network.
    #[getter]
    fn hidden(&self) -> usize {
        self.exp.shape().hidden()
    }

    /// The trial length T (steps).
    #[getter]
    fn steps(&self) -> usize {
        self.exp.trial_params().steps()
    }

    /// The names of every descriptor, in order.
    #[staticmethod]
    fn descriptor_names() -> Vec<&'static str> {
        Descriptors::NAMES.to_vec()
    }

    /// `(F, terms, descriptors or None, executed steps)` of a population: F `(pop,)`, terms
    /// `(pop, rooms, N)` in the order of `term_names`, descriptors `(pop, rooms, D)` in the
    /// order of `descriptors` (when `describe`). With supplied terms, `supply(trials)` is
    /// called once with the generation's evaluation trials (a dict of arrays) and returns their
    /// values `(pop, rooms, U)`, which set F.
    #[pyo3(signature = (genomes, generation, seed=None, describe=false, descriptors=None, supply=None))]
    #[allow(clippy::type_complexity, clippy::too_many_arguments)]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        genomes: PyReadonlyArray2<'py, f64>,
        generation: Bound<'py, PyAny>,
        seed: Option<Bound<'py, PyAny>>,
        describe: bool,
        descriptors: Option<Vec<String>>,
        supply: Option<Bound<'py, PyAny>>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyAny>,
        Option<Bound<'py, PyAny>>,
        usize,
    )> {
        let generation = index_arg("generation", &generation)?;
        let seed = seed.as_ref().map(seed_arg).transpose()?;
        let exp = self.experiment_for(seed)?;
        let columns = descriptor_columns(descriptors, &exp)?;
        let population = genomes_arg("genomes", &genomes, &exp)?;
        let (mut evals, described) = self.evaluated(
            py,
            &exp,
            &population,
            generation,
            describe,
            &columns,
            supply.as_ref(),
        )?;
        let (n, rooms) = (evals.len(), self.run.rooms.len());
        let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
        let inputs = exp.input_terms();
        let terms: Vec<f64> = evals
            .iter()
            .flat_map(|e| {
                e.per_room
                    .iter()
                    .flat_map(|s| inputs.iter().map(|&id| s.terms.get(id)))
            })
            .collect();
        let terms =
            Array3::from_shape_vec((n, rooms, inputs.len()), terms).expect("pop × rooms × N");
        let executed = evals.iter().map(Evaluation::executed).sum();
        let described = describe.then(|| {
            let mut flat = Vec::with_capacity(n * rooms * columns.len());
            for (i, e) in evals.iter_mut().enumerate() {
                for (r, s) in e.per_room.iter().enumerate() {
                    flat.extend(columns.iter().map(|c| match *c {
                        Column::Descriptor(k) => {
                            described.as_ref().expect("described")[i][r].as_array()[k]
                        }
                        Column::Term(id) => s.terms.get(id),
                    }));
                }
            }
            Array3::from_shape_vec((n, rooms, columns.len()), flat)
                .expect("pop × rooms × D")
                .into_pyarray(py)
                .into_any()
        });
        Ok((
            PyArray1::from_vec(py, fitness),
            terms.into_pyarray(py).into_any(),
            described,
            executed,
        ))
    }
}

impl Problem {
    /// The population's evaluations (the supplied terms filled in, F refitted) and, when some
    /// column is a descriptor, each room's descriptors (then, with supplied terms, the trials
    /// run once more to be recorded).
    #[allow(clippy::too_many_arguments)]
    fn evaluated(
        &self,
        py: Python<'_>,
        exp: &Experiment,
        population: &Population,
        generation: usize,
        describe: bool,
        columns: &[Column],
        supply: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Evaluated> {
        let run = &self.run;
        let descriptors = describe && columns.iter().any(|c| matches!(c, Column::Descriptor(_)));
        let supplied = !exp.user_terms().is_empty();
        let supply = match (supplied, supply) {
            (false, _) => None,
            (true, Some(f)) => Some(f),
            (true, None) => {
                return Err(input_err(
                    "terms: this problem has terms of its own, and evaluate was given no function to compute them",
                ));
            }
        };
        let (evals, described): Evaluated = self.compute(py, || match (descriptors, supplied) {
            (true, _) => {
                let (e, d) = exp
                    .evaluate_population_described(population, run, generation)
                    .into_iter()
                    .unzip();
                (e, Some(d))
            }
            (false, false) => (exp.evaluate_population(population, run, generation), None),
            (false, true) => (Vec::new(), None),
        })?;
        let Some(supply) = supply else {
            return Ok((evals, described));
        };
        if exp.randomise().is_some() {
            // The recorded trials are the configured robot's, not the ones `[trial.randomise]`
            // draws: refused rather than evaluated on other robots than the GA's.
            return Err(input_err(
                "terms: terms computed in Python cannot yet be combined with [trial.randomise] \
                 (their trials would be the configured robot's, not the drawn ones the rest of \
                 the evaluation uses); remove [trial.randomise] or compute the term in Rust \
                 (docs/guide/motivations.md)",
            ));
        }
        let recorded = self.compute(py, || {
            exp.evaluate_population_recorded(population, run, generation)
        })?;
        let trials = record(py, exp, &self.rooms(), &recorded)?;
        let values = supply.call1((trials,))?;
        let mut evals: Vec<Evaluation> = recorded.into_iter().map(|(e, _)| e).collect();
        supplied_values(&values, &self.user, &mut evals)?;
        for e in &mut evals {
            exp.refit(e);
        }
        Ok((evals, described))
    }
}

/// A population as a `(pop, genome_size)` array.
pub(crate) fn population_array<'py>(
    py: Python<'py>,
    population: &[Genome],
    len: usize,
) -> Bound<'py, PyAny> {
    let flat: Vec<f64> = population.iter().flatten().copied().collect();
    Array2::from_shape_vec((population.len(), len), flat)
        .expect("pop × genome_size")
        .into_pyarray(py)
        .into_any()
}
