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
use fuzzymotiv_io::files::inputs::resolve;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

use crate::{config_err, input_err, load, py_float, seed_arg, thread_pool, whole_number};

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
            resolve(raw, Path::new("."), "(problem)")
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
    let shape = exp.shape();
    let want = shape.genome_len();
    let [rows, cols] = [genomes.shape()[0], genomes.shape()[1]];
    if cols != want {
        return Err(input_err(format!(
            "{arg}: expected a (population, {want}) array (an 8-{h}-2 network has {want} weights; network.hidden = {h}), got shape ({rows}, {cols})",
            h = shape.hidden()
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

/// Descriptor indices from names (`None`: all of them, in [`Descriptors::NAMES`] order).
fn descriptor_columns(names: Option<Vec<String>>) -> PyResult<Vec<usize>> {
    let Some(names) = names else {
        return Ok((0..Descriptors::NAMES.len()).collect());
    };
    names
        .iter()
        .map(|n| {
            Descriptors::NAMES
                .iter()
                .position(|k| k == n)
                .ok_or_else(|| {
                    input_err(format!(
                        "descriptors: unknown descriptor {n:?}; expected some of {:?}",
                        Descriptors::NAMES
                    ))
                })
        })
        .collect()
}

#[pymethods]
impl Problem {
    #[new]
    #[pyo3(signature = (config_path=None, config_text=None, sets=Vec::new(), room=None, threads=None, seed=None))]
    fn new(
        config_path: Option<PathBuf>,
        config_text: Option<String>,
        sets: Vec<String>,
        room: Option<String>,
        threads: Option<Bound<'_, PyAny>>,
        seed: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Problem> {
        let pool = thread_pool(threads.as_ref())?;
        let seed = seed.as_ref().map(seed_arg).transpose()?;
        let loaded = load(config_path.as_deref(), config_text.as_deref(), &sets, seed)
            .map_err(config_err)?;
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
        })
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

    /// The motivations (C, H, O, E), normalised as the config loader does.
    #[getter]
    fn motivations(&self) -> (f64, f64, f64, f64) {
        let m = self.exp.motivations();
        (m.curiosity(), m.homing(), m.orientation(), m.energy())
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
    /// `(pop, rooms, 4)`, descriptors `(pop, rooms, D)` in the order of `descriptors` (when
    /// `describe`).
    #[pyo3(signature = (genomes, generation, seed=None, describe=false, descriptors=None))]
    #[allow(clippy::type_complexity)]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        genomes: PyReadonlyArray2<'py, f64>,
        generation: Bound<'py, PyAny>,
        seed: Option<Bound<'py, PyAny>>,
        describe: bool,
        descriptors: Option<Vec<String>>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyAny>,
        Option<Bound<'py, PyAny>>,
        usize,
    )> {
        let generation = index_arg("generation", &generation)?;
        let seed = seed.as_ref().map(seed_arg).transpose()?;
        let columns = descriptor_columns(descriptors)?;
        let exp = self.experiment_for(seed)?;
        let population = genomes_arg("genomes", &genomes, &exp)?;
        let run = &self.run;
        let (evals, described): (Vec<Evaluation>, Option<Vec<Vec<Descriptors>>>) =
            self.compute(py, || {
                if describe {
                    let (e, d) = exp
                        .evaluate_population_described(&population, run, generation)
                        .into_iter()
                        .unzip();
                    (e, Some(d))
                } else {
                    (exp.evaluate_population(&population, run, generation), None)
                }
            })?;
        let (n, rooms) = (evals.len(), run.rooms.len());
        let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
        let terms: Vec<f64> = evals
            .iter()
            .flat_map(|e| e.per_room.iter().flat_map(|s| s.terms.as_array()))
            .collect();
        let terms = Array3::from_shape_vec((n, rooms, 4), terms).expect("pop × rooms × 4");
        let executed = evals.iter().map(Evaluation::executed).sum();
        let described = described.map(|d| {
            let flat: Vec<f64> = d
                .iter()
                .flatten()
                .flat_map(|x| {
                    let all = x.as_array();
                    columns.iter().map(move |&c| all[c])
                })
                .collect();
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
