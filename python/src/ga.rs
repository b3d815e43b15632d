//! `fm.GA`: the built-in genetic algorithm as ask/tell steps over the library's public steps
//! (`initial_population`, `generation_record`, `breed`), so that ask → `Problem.evaluate` →
//! tell is exactly `fm.run`'s evolution; its state is a plain, versioned dict.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use fuzzymotiv::evolution::Population;
use fuzzymotiv::evolution::{Genome, Stats, ranking};
use fuzzymotiv::experiment::GenerationRecord;
use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::experiment::{Evaluation, RoomScore};
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::fitness::{FitnessTerms, MissionTerms, TermId, UserValues};
use fuzzymotiv_pipeline::files::inputs::resolve;
use fuzzymotiv_pipeline::pipeline::continuation::{continue_runs, finished_config};
use numpy::{
    PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray3, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::{Deserialize, Serialize};

use crate::problem::{Problem, genomes_arg, population_array};
use crate::{config_err, input_err, py_err, py_float, seed_arg};

/// What `GA.state` holds (`format`, `version`): the next population, the records so far and
/// the best genome told, with the resolved config, so that a state restores on its own.
const FORMAT: &str = "fuzzymotiv.GA";
const VERSION: u32 = 1;

/// The model version of a state that names none (written before it was recorded).
fn model_one() -> u32 {
    1
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct State {
    format: String,
    version: u32,
    /// The model version that evaluated it ([`fuzzymotiv::MODEL_VERSION`]; 1 when absent).
    #[serde(default = "model_one")]
    model: u32,
    /// The resolved config (with the GA's seed), as TOML.
    config: String,
    /// The run's label (`all` or the room of a per-room run).
    run: String,
    seed: u64,
    /// The generation `ask` returns next.
    generation: usize,
    /// Its genomes (not yet evaluated).
    population: Vec<Genome>,
    history: Vec<Row>,
    best: Option<Best>,
}

/// A generation's record; the mean terms are `None` when `tell` was given none.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Row {
    generation: usize,
    mean: f64,
    std: f64,
    min: f64,
    max: f64,
    terms: Option<[f64; 4]>,
    /// The mean of each input term beyond a, g, l, b (mission and user terms), in input order;
    /// absent for the paper's four or when `tell` was given no terms.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    inputs: Option<Vec<f64>>,
}

/// The input terms of `exp` beyond the paper's a, g, l, b, in input order.
fn other_inputs(exp: &Experiment) -> Vec<TermId> {
    (exp.input_terms().iter().copied())
        .filter(|id| !matches!(id, TermId::A | TermId::G | TermId::L | TermId::B))
        .collect()
}

/// Terms with the values of `exp`'s inputs (in input order); a, g, l, b not among them NaN.
fn terms_of(exp: &Experiment, values: &[f64]) -> FitnessTerms {
    let mut t = FitnessTerms {
        a: f64::NAN,
        g: f64::NAN,
        l: f64::NAN,
        b: f64::NAN,
        ..Default::default()
    };
    t.user = UserValues::zeros(exp.user_terms().len());
    for (&id, &v) in exp.input_terms().iter().zip(values) {
        set_term(&mut t, id, v);
    }
    t
}

/// Sets term `id` of `t` to `v`.
fn set_term(t: &mut FitnessTerms, id: TermId, v: f64) {
    match id {
        TermId::A => t.a = v,
        TermId::G => t.g = v,
        TermId::L => t.l = v,
        TermId::B => t.b = v,
        TermId::User(k) => t.user.as_mut_slice()[k] = v,
        mission => {
            let m = t.mission.get_or_insert_with(MissionTerms::default);
            match mission {
                TermId::Goal => m.goal = v,
                TermId::Urgency => m.urgency = v,
                TermId::Waypoints => m.waypoints = v,
                _ => m.safety = v,
            }
        }
    }
}

/// The best genome told so far (the first of the highest F).
#[derive(Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Best {
    genome: Genome,
    fitness: f64,
    generation: usize,
}

/// The native GA (`fuzzymotiv.GA` wraps it).
#[pyclass(module = "fuzzymotiv._fuzzymotiv", name = "GA")]
pub struct Ga {
    exp: Arc<Experiment>,
    run: Run,
    config: String,
    generation: usize,
    population: Population,
    history: Vec<GenerationRecord>,
    best: Option<Best>,
    /// Whether `ask` was called since the GA was made or last told (not part of the state:
    /// a restored GA is asked again, which gives the same genomes).
    asked: bool,
}

/// Numbers that must be finite (`F`, terms), or an error naming `arg` and the position.
fn finite_values<'a>(
    arg: &str,
    values: impl Iterator<Item = (String, &'a f64)>,
    usage: &str,
) -> PyResult<()> {
    for (at, v) in values {
        if !v.is_finite() {
            return Err(input_err(format!(
                "{arg}: `{}` ({at}) is not a finite number; {usage}",
                py_float(*v)
            )));
        }
    }
    Ok(())
}

impl Ga {
    fn record(&self, fitness: &[f64], terms: Option<&[f64]>, rooms: usize) -> GenerationRecord {
        let inputs = self.exp.input_terms().len();
        match terms {
            Some(terms) => {
                let evals: Vec<Evaluation> = fitness
                    .iter()
                    .zip(terms.chunks(rooms * inputs))
                    .map(|(&f, t)| Evaluation {
                        fitness: f,
                        per_room: t
                            .chunks(inputs)
                            .map(|values| RoomScore {
                                f: 0.0,
                                terms: terms_of(&self.exp, values),
                                executed: 0,
                            })
                            .collect(),
                    })
                    .collect();
                self.exp.generation_record(self.generation, &evals)
            }
            None => GenerationRecord {
                generation: self.generation,
                stats: Stats::of(fitness),
                terms: terms_of(&self.exp, &vec![f64::NAN; inputs]),
            },
        }
    }
}

#[pymethods]
impl Ga {
    #[new]
    #[pyo3(signature = (problem, seed=None, genomes=None))]
    fn new(
        problem: Bound<'_, Problem>,
        seed: Option<Bound<'_, PyAny>>,
        genomes: Option<PyReadonlyArray2<'_, f64>>,
    ) -> PyResult<Ga> {
        let problem = problem.get();
        let seed = seed.as_ref().map(seed_arg).transpose()?;
        let exp = problem.experiment_for(seed)?;
        let run = problem.run().clone();
        let population = match genomes {
            Some(g) => genomes_arg("genomes", &g, &exp)?,
            None => exp.initial_population(&run),
        };
        Ok(Ga {
            config: problem.config_toml(exp.seed()),
            exp,
            run,
            generation: 0,
            population,
            history: Vec::new(),
            best: None,
            asked: false,
        })
    }

    /// The genomes of the current generation (the same until `tell`).
    fn ask<'py>(&mut self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.asked = true;
        population_array(py, &self.population, self.exp.shape().genome_len())
    }

    /// F of the asked genomes (higher is better), and optionally their terms `(pop, rooms,
    /// 4)` for the logged means; breeds the next generation.
    #[pyo3(signature = (fitness, terms=None))]
    fn tell(
        &mut self,
        fitness: PyReadonlyArray1<'_, f64>,
        terms: Option<PyReadonlyArray3<'_, f64>>,
    ) -> PyResult<()> {
        if !self.asked {
            return Err(input_err(format!(
                "tell: call ask() first: tell(F) takes the F of the genomes ask() returned, and \
                 ask() was not called for generation {} (telling before asking, or twice, would \
                 breed from genomes nobody evaluated)",
                self.generation
            )));
        }
        let n = self.population.len();
        let f = fitness.as_array().to_vec();
        if f.len() != n {
            return Err(input_err(format!(
                "F: expected {n} values (one per genome of ask()), got {}",
                f.len()
            )));
        }
        finite_values(
            "F",
            f.iter()
                .enumerate()
                .map(|(i, v)| (format!("individual {i}"), v)),
            "expected the F of each genome of ask()",
        )?;
        let rooms = self.run.rooms.len();
        let inputs = self.exp.input_terms().len();
        let terms: Option<Vec<f64>> = match terms {
            None => None,
            Some(t) => {
                let shape = t.shape();
                if shape != [n, rooms, inputs] {
                    return Err(input_err(format!(
                        "terms: expected shape ({n}, {rooms}, {inputs}) (genomes, rooms, the terms {}), got {shape:?}",
                        self.exp.motivations().input_names().join(" ")
                    )));
                }
                let view = t.as_array();
                finite_values(
                    "terms",
                    view.indexed_iter()
                        .map(|((i, r, k), v)| (format!("individual {i}, room {r}, term {k}"), v)),
                    "expected the terms problem.evaluate returned",
                )?;
                Some(view.iter().copied().collect())
            }
        };
        let record = self.record(&f, terms.as_deref(), rooms);
        let top = ranking(&f)[0];
        if self.best.as_ref().is_none_or(|b| f[top] > b.fitness) {
            self.best = Some(Best {
                genome: self.population[top].clone(),
                fitness: f[top],
                generation: self.generation,
            });
        }
        let next = self
            .exp
            .breed(&self.population, &f, &self.run, self.generation)
            .map_err(|e| input_err(format!("F: {e}")))?;
        self.history.push(record);
        self.population = next;
        self.generation += 1;
        self.asked = false;
        Ok(())
    }

    /// The generation `ask` returns (the number of `tell`s so far).
    #[getter]
    fn generation(&self) -> usize {
        self.generation
    }

    /// The base seed of the GA's streams (initial population, breeding; evaluate with it).
    #[getter]
    fn seed(&self) -> u64 {
        self.exp.seed()
    }

    /// `(genome, F, generation)` of the best genome told so far, or None.
    #[getter]
    fn best<'py>(&self, py: Python<'py>) -> Option<(Bound<'py, PyArray1<f64>>, f64, usize)> {
        self.best.as_ref().map(|b| {
            (
                PyArray1::from_vec(py, b.genome.clone()),
                b.fitness,
                b.generation,
            )
        })
    }

    /// The records of the generations told, as `generations.csv`'s columns.
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let h = &self.history;
        let col = |f: &dyn Fn(&GenerationRecord) -> f64| {
            PyArray1::from_vec(py, h.iter().map(f).collect())
        };
        d.set_item(
            "generation",
            PyArray1::from_vec(py, h.iter().map(|r| r.generation as i64).collect()),
        )?;
        d.set_item("best", col(&|r| r.stats.max))?;
        d.set_item("mean", col(&|r| r.stats.mean))?;
        d.set_item("std", col(&|r| r.stats.std))?;
        d.set_item("min", col(&|r| r.stats.min))?;
        d.set_item("max", col(&|r| r.stats.max))?;
        d.set_item("a", col(&|r| r.terms.a))?;
        d.set_item("g", col(&|r| r.terms.g))?;
        d.set_item("l", col(&|r| r.terms.l))?;
        d.set_item("b", col(&|r| r.terms.b))?;
        let names = self.exp.motivations().input_names();
        for (name, &id) in names.iter().zip(self.exp.input_terms()) {
            if !matches!(id, TermId::A | TermId::G | TermId::L | TermId::B) {
                d.set_item(name, col(&|r| r.terms.get(id)))?;
            }
        }
        d.set_item("room", vec![self.run.label.clone(); h.len()])?;
        Ok(d)
    }

    /// The state as JSON text (`fuzzymotiv.GA.state` parses it into a dict).
    fn state_json(&self) -> String {
        let others = other_inputs(&self.exp);
        let state = State {
            format: FORMAT.into(),
            version: VERSION,
            model: fuzzymotiv::MODEL_VERSION,
            config: self.config.clone(),
            run: self.run.label.clone(),
            seed: self.exp.seed(),
            generation: self.generation,
            population: self.population.to_vec(),
            history: self
                .history
                .iter()
                .map(|r| Row {
                    generation: r.generation,
                    mean: r.stats.mean,
                    std: r.stats.std,
                    min: r.stats.min,
                    max: r.stats.max,
                    terms: Some(r.terms.as_array()).filter(|t| t.iter().all(|v| v.is_finite())),
                    inputs: Some(others.iter().map(|&id| r.terms.get(id)).collect::<Vec<_>>())
                        .filter(|v| !v.is_empty() && v.iter().all(|v| v.is_finite())),
                })
                .collect(),
            best: self.best.clone(),
        };
        serde_json::to_string(&state).expect("finite numbers serialise")
    }

    /// The GA that continues the finished run in `dir` (its config is `problem`'s): its
    /// final population evaluated again and bred, at the generation after the last, with the
    /// run's history; `best` is the best of the final generation.
    #[staticmethod]
    #[pyo3(signature = (dir, problem=None))]
    fn from_run(dir: PathBuf, problem: Option<Bound<'_, Problem>>) -> PyResult<Ga> {
        let old = finished_config(&dir).map_err(py_err)?;
        let problem = problem.ok_or_else(|| input_err("problem: required"))?;
        let py = problem.py();
        let p = problem.get();
        let seed = old.experiment.seed();
        if p.config_toml(seed) != old.raw.to_toml() || p.experiment_for(None)?.seed() != seed {
            return Err(input_err(format!(
                "problem: its config is not the one of {}; pass none (the run's config.resolved.toml is used)",
                dir.display()
            )));
        }
        let label = p.run().label.clone();
        let continued = p.compute(py, || continue_runs(&dir, &old.experiment))?;
        let c = (continued.map_err(py_err)?.into_iter())
            .find(|c| c.finished.run.label == label)
            .ok_or_else(|| {
                input_err(format!(
                    "problem: run {label:?} is not in {}",
                    dir.display()
                ))
            })?;
        let done = c.finished.history.len();
        let best = Best {
            genome: c.finished.population[c.finished.best].clone(),
            fitness: c.finished.evaluations[c.finished.best].fitness,
            generation: done - 1,
        };
        Ok(Ga {
            config: p.config_toml(seed),
            exp: p.experiment_for(None)?,
            run: p.run().clone(),
            generation: done,
            population: c.next,
            history: c.finished.history,
            best: Some(best),
            asked: false,
        })
    }

    /// A GA from `state_json`'s text, with `problem`'s experiment when given (its config must
    /// be the state's), else with the state's own config.
    #[staticmethod]
    #[pyo3(signature = (text, problem=None))]
    fn from_state_json(text: &str, problem: Option<Bound<'_, Problem>>) -> PyResult<Ga> {
        let state = State::parse(text)?;
        let (exp, run) = state_experiment(&state, problem)?;
        state.check_genomes(exp.shape().genome_len())?;
        let history = history_of(&exp, &state.history);
        let population = exp
            .population(state.population)
            .map_err(|e| input_err(format!("state: {e}")))?;
        Ok(Ga {
            config: state.config,
            exp,
            run,
            generation: state.generation,
            population,
            history,
            best: state.best,
            asked: false,
        })
    }
}

impl State {
    /// A GA state from `state_json`'s text, of this format and this model.
    fn parse(text: &str) -> PyResult<State> {
        let state: State = serde_json::from_str(text)
            .map_err(|e| input_err(format!("state: not a GA state ({e})")))?;
        if state.format != FORMAT || state.version != VERSION {
            return Err(input_err(format!(
                "state: format {:?} version {} is not {FORMAT:?} version {VERSION}; it was written by another version of fuzzymotiv",
                state.format, state.version
            )));
        }
        if state.model != fuzzymotiv::MODEL_VERSION {
            return Err(input_err(format!(
                "state: evaluated by model {} of fuzzymotiv, and this build is model {}, whose results differ; continuing it would mix two models in one evolution",
                state.model,
                fuzzymotiv::MODEL_VERSION
            )));
        }
        Ok(state)
    }

    /// Checks the population (not empty) and every genome (`len` finite weights), and that
    /// the history has one record per generation told.
    fn check_genomes(&self, len: usize) -> PyResult<()> {
        if self.population.is_empty() {
            return Err(input_err("state: an empty population"));
        }
        let genomes = (self.population.iter()).chain(self.best.iter().map(|b| &b.genome));
        for (i, g) in genomes.enumerate() {
            if g.len() != len || g.iter().any(|v| !v.is_finite()) {
                return Err(input_err(format!(
                    "state: genome {i} is not {len} finite weights"
                )));
            }
        }
        if self.history.len() != self.generation {
            return Err(input_err(format!(
                "state: {} records for generation {}; expected one per generation told",
                self.history.len(),
                self.generation
            )));
        }
        Ok(())
    }
}

/// The experiment and run of `state`: `problem`'s when given (its config and run must be the
/// state's), else its own config's.
fn state_experiment(
    state: &State,
    problem: Option<Bound<'_, Problem>>,
) -> PyResult<(Arc<Experiment>, Run)> {
    if let Some(p) = problem {
        let p = p.get();
        if p.config_toml(state.seed) != state.config || p.run().label != state.run {
            return Err(input_err(
                "problem: its config or run is not the state's; pass the problem the GA was made with, or none (the state's config is used)",
            ));
        }
        return Ok((p.experiment_for(Some(state.seed))?, p.run().clone()));
    }
    let source = "(GA state)";
    let raw = RawConfig::parse(&state.config, source, &[]).map_err(|e| config_err(e.into()))?;
    let exp = resolve(raw, Path::new("."), source)
        .map_err(config_err)?
        .experiment;
    let run = (exp.runs().into_iter())
        .find(|r| r.label == state.run)
        .ok_or_else(|| input_err(format!("state: run {:?} is not in its config", state.run)))?;
    Ok((Arc::new(exp), run))
}

/// The generation records of a state's `rows` (terms it lacks are NaN).
fn history_of(exp: &Experiment, rows: &[Row]) -> Vec<GenerationRecord> {
    let others = other_inputs(exp);
    (rows.iter())
        .map(|r| {
            let mut terms = terms_of(exp, &[]);
            [terms.a, terms.g, terms.l, terms.b] = r.terms.unwrap_or([f64::NAN; 4]);
            for (k, &id) in others.iter().enumerate() {
                let v = r.inputs.as_ref().and_then(|v| v.get(k).copied());
                set_term(&mut terms, id, v.unwrap_or(f64::NAN));
            }
            GenerationRecord {
                generation: r.generation,
                stats: Stats {
                    mean: r.mean,
                    std: r.std,
                    min: r.min,
                    max: r.max,
                },
                terms,
            }
        })
        .collect()
}
