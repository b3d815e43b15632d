//! Evolution: the initial population, breeding and the generation loop of a run, resumable from
//! any generation because every random stream is derived from (run, generation, individual, room).
//!
//! The loop is three public steps, so a custom loop (another optimiser's, Python's ask/tell)
//! can drive it: [`Experiment::initial_population`] (ask), [`Experiment::evaluate_population`]
//! (evaluate: F and the terms per individual), [`Experiment::breed`] (tell: needs only F).
//! [`Experiment::evolve`] is exactly these steps, with an observer after every generation:
//!
//! ```
//! use fuzzymotiv::experiment::RawConfig;
//! use fuzzymotiv::experiment::{BuiltinRoomsOnly, Setup};
//! use std::ops::ControlFlow;
//!
//! let sets = ["ga.population=6", "ga.generations=2", "trial.steps=50"].map(String::from);
//! let raw = RawConfig::parse("rooms = [\"H\", \"T\"]", "example", &sets).unwrap();
//! let exp = Setup::resolve(raw, "example", &BuiltinRoomsOnly).unwrap().experiment;
//! let run = &exp.runs()[0];
//! let mut population = exp.initial_population(run);
//! let mut history = Vec::new();
//! for generation in 0..2 {
//!     let evals = exp.evaluate_population(&population, run, generation);
//!     let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
//!     history.push(exp.generation_record(generation, &evals));
//!     if generation + 1 < 2 {
//!         population = exp.breed(&population, &fitness, run, generation).unwrap();
//!     }
//! }
//! let evolved = exp.evolve(run, &mut |_| ControlFlow::Continue(())).unwrap();
//! assert_eq!(evolved.history, history);
//! assert_eq!(evolved.population, population.into_genomes());
//! ```

use std::ops::ControlFlow;

use serde::{Deserialize, Serialize};

use crate::evolution::ga::{Genome, Stats, initial_population, next_generation};
pub use crate::evolution::population::{Population, PopulationError};
use crate::experiment::evaluation::{Evaluation, TermError};
use crate::experiment::{Experiment, Run};
use crate::fitness::terms::FitnessTerms;
use crate::random::rng::rng_from_seed;

impl Experiment {
    /// The initial population of a run.
    pub fn initial_population(&self, run: &Run) -> Population {
        let mut rng = rng_from_seed(self.streams().initial_population(run.tag));
        Population {
            shape: self.shape,
            genomes: initial_population(&self.ga, self.shape.genome_len(), &mut rng),
        }
    }

    /// `genomes` checked as a population of this experiment's network: at least one genome,
    /// each of the network's length ([`crate::simulation::controller::MlpShape::genome_len`]).
    pub fn population(&self, genomes: Vec<Genome>) -> Result<Population, PopulationError> {
        if genomes.is_empty() {
            return Err(PopulationError::Empty);
        }
        for (index, genome) in genomes.iter().enumerate() {
            (self.shape.check(genome))
                .map_err(|source| PopulationError::Genome { index, source })?;
        }
        Ok(Population {
            shape: self.shape,
            genomes,
        })
    }

    /// Statistics of an evaluated generation.
    pub fn generation_record(&self, generation: usize, evals: &[Evaluation]) -> GenerationRecord {
        let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
        let n = evals.len() as f64;
        let mut terms = FitnessTerms::default();
        for e in evals {
            terms.add_mean(&e.mean_terms(), n);
        }
        GenerationRecord {
            generation,
            stats: Stats::of(&fitness),
            terms,
        }
    }

    /// Breeds generation `generation + 1` from generation `generation` and its fitness F (one
    /// value per individual, higher is better): all that selection needs.
    pub fn breed(
        &self,
        population: &Population,
        fitness: &[f64],
        run: &Run,
        generation: usize,
    ) -> Result<Population, PopulationError> {
        if fitness.len() != population.len() {
            return Err(PopulationError::Fitness {
                expected: population.len(),
                got: fitness.len(),
            });
        }
        Ok(self.offspring(population, fitness, run, generation))
    }

    /// [`Experiment::breed`] of a population and its own fitness values (one per genome).
    fn offspring(
        &self,
        population: &Population,
        fitness: &[f64],
        run: &Run,
        generation: usize,
    ) -> Population {
        let mut rng = rng_from_seed(self.streams().breeding(run.tag, generation));
        Population {
            shape: population.shape,
            genomes: next_generation(population, fitness, &self.ga, &mut rng),
        }
    }

    /// Evolves one run from scratch, calling the observer `on_generation` after each generation
    /// (to report progress, save a checkpoint, or stop the run: [`ControlFlow::Break`]).
    pub fn evolve(
        &self,
        run: &Run,
        on_generation: &mut Observer<'_>,
    ) -> Result<Evolution, EvolveError> {
        let population = self.initial_population(run);
        self.evolve_from(run, 0, population, Vec::new(), on_generation)
    }

    /// Continues a run at `generation` with `population` (not yet evaluated) and the records of
    /// the generations before it; the result equals an uninterrupted [`Experiment::evolve`],
    /// because every random stream is derived from (run, generation, individual, room). When the
    /// observer breaks after a generation that is not the last, the run stops there:
    /// [`Stopped`] holds what [`Experiment::evolve_from`] needs to continue it. A user-defined
    /// term that returns a value outside [0, 1] ends it with [`EvolveError::Term`].
    pub fn evolve_from(
        &self,
        run: &Run,
        generation: usize,
        mut population: Population,
        mut history: Vec<GenerationRecord>,
        on_generation: &mut Observer<'_>,
    ) -> Result<Evolution, EvolveError> {
        let mut g = generation;
        loop {
            let evals = self.evaluate_population(&population, run, g);
            self.check_terms(
                evals
                    .iter()
                    .flat_map(|e| e.per_room.iter().map(|s| &s.terms)),
            )?;
            history.push(self.generation_record(g, &evals));
            if g + 1 >= self.ga.generations() {
                // The last generation: the evolution is complete whatever the observer says.
                let _ = on_generation(&GenerationState {
                    history: &history,
                    population: &population,
                    next: None,
                });
                let best = crate::evolution::ga::ranking(
                    &evals.iter().map(|e| e.fitness).collect::<Vec<_>>(),
                )[0];
                return Ok(Evolution {
                    run: run.clone(),
                    history,
                    population: population.genomes,
                    evaluations: evals,
                    best,
                });
            }
            let fitness: Vec<f64> = evals.iter().map(|e| e.fitness).collect();
            let next = self.offspring(&population, &fitness, run, g);
            let flow = on_generation(&GenerationState {
                history: &history,
                population: &population,
                next: Some(&next[..]),
            });
            if flow.is_break() {
                return Err(EvolveError::Stopped(Stopped {
                    generation: g + 1,
                    population: next,
                    history,
                }));
            }
            population = next;
            g += 1;
        }
    }

    /// Rebuilds a finished evolution from its final population and history (the final
    /// generation is evaluated again on its own streams, giving the same evaluations).
    pub fn finished(
        &self,
        run: &Run,
        population: Population,
        history: Vec<GenerationRecord>,
    ) -> Evolution {
        let last = history.len().saturating_sub(1);
        let evals = self.evaluate_population(&population, run, last);
        let best =
            crate::evolution::ga::ranking(&evals.iter().map(|e| e.fitness).collect::<Vec<_>>())[0];
        Evolution {
            run: run.clone(),
            history,
            population: population.genomes,
            evaluations: evals,
            best,
        }
    }
}

/// Statistics of one generation (a row of `generations.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GenerationRecord {
    /// Generation index, from 0.
    pub generation: usize,
    /// Best/mean/std/min/max of F.
    pub stats: Stats,
    /// Population means of a, g, l, b.
    pub terms: FitnessTerms,
}

/// An observer of an evolution, called after every generation: it returns
/// [`ControlFlow::Break`] to stop the run there (stopping is data, not a panic).
pub type Observer<'a> = dyn FnMut(&GenerationState<'_>) -> ControlFlow<()> + 'a;

/// Why an evolution ended before its last generation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvolveError {
    /// Its observer stopped it ([`ControlFlow::Break`]).
    #[error("the evolution was stopped after generation {}", .0.generation)]
    Stopped(Stopped),
    /// A user-defined term returned a value outside [0, 1].
    #[error(transparent)]
    Term(#[from] TermError),
}

/// An evolution stopped by its observer: what [`Experiment::evolve_from`] continues it from.
#[derive(Debug, Clone, PartialEq)]
pub struct Stopped {
    /// The next generation's index (the generations before it are in `history`).
    pub generation: usize,
    /// The next generation's genomes, not yet evaluated.
    pub population: Population,
    /// The records of the generations done.
    pub history: Vec<GenerationRecord>,
}

/// Where an evolution stands after a generation: enough to checkpoint it.
#[derive(Debug, Clone, Copy)]
pub struct GenerationState<'a> {
    /// Records of every generation so far (the last is the one just evaluated).
    pub history: &'a [GenerationRecord],
    /// The generation just evaluated.
    pub population: &'a [Genome],
    /// The next generation (not yet evaluated), or `None` after the last generation.
    pub next: Option<&'a [Genome]>,
}

impl GenerationState<'_> {
    /// The record of the generation just evaluated.
    pub fn record(&self) -> &GenerationRecord {
        self.history.last().expect("at least one generation")
    }
}

/// The outcome of one evolution.
#[derive(Debug, Clone)]
pub struct Evolution {
    /// The run.
    pub run: Run,
    /// Per generation.
    pub history: Vec<GenerationRecord>,
    /// The final generation.
    pub population: Vec<Genome>,
    /// Its evaluations.
    pub evaluations: Vec<Evaluation>,
    /// Index of the best final individual.
    pub best: usize,
}

impl Evolution {
    /// Mean F of the final population in room position `k` of the run.
    pub fn mean_room_fitness(&self, k: usize) -> f64 {
        self.evaluations
            .iter()
            .map(|e| e.per_room[k].f)
            .sum::<f64>()
            / self.evaluations.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use std::ops::ControlFlow;

    use super::Evolution;
    use crate::experiment::testing::{ORIENTED, experiment};
    use crate::experiment::{Experiment, Run};

    /// The whole evolution of `run`, with an observer that never stops it.
    fn whole(exp: &Experiment, run: &Run) -> Evolution {
        exp.evolve(run, &mut |_| ControlFlow::Continue(()))
            .expect("never stopped")
    }

    /// With O = 0, online mode computes nothing extra and gives byte-identical evolutions.
    #[test]
    fn zero_orientation_online_equals_offline() {
        let off = experiment(&[]);
        let on = experiment(&["fitness.orientation=\"online\""]);
        let run = &off.runs()[0];
        let a = whole(&off, run);
        let b = whole(&on, run);
        assert_eq!(a.history, b.history);
        assert_eq!(a.population, b.population);
        assert_eq!(a.evaluations, b.evaluations);
    }

    /// Online orientation makes F depend on O and stays deterministic.
    #[test]
    fn online_orientation_is_deterministic_and_used() {
        let mut sets = ORIENTED.to_vec();
        sets.push("ga.population=40");
        let exp = experiment(&sets);
        let run = &exp.runs()[0];
        let x = whole(&exp, run);
        let y = whole(&exp, run);
        assert_eq!(x.history, y.history);
        assert!(
            x.history.iter().any(|h| h.terms.l > 0.0),
            "some robot recognises something"
        );
    }

    /// A resumed evolution equals an uninterrupted one.
    #[test]
    fn evolve_from_a_checkpoint_equals_uninterrupted() {
        let exp = experiment(&[]);
        let run = &exp.runs()[0];
        let mut saved = None;
        let full = exp
            .evolve(run, &mut |s| {
                if s.history.len() == 2 {
                    saved = Some((s.history.to_vec(), s.next.unwrap().to_vec()));
                }
                ControlFlow::Continue(())
            })
            .unwrap();
        let (history, next) = saved.unwrap();
        let next = exp.population(next).unwrap();
        let resumed = exp
            .evolve_from(run, history.len(), next, history, &mut |_| {
                ControlFlow::Continue(())
            })
            .unwrap();
        assert_eq!(full.history, resumed.history);
        assert_eq!(full.evaluations, resumed.evaluations);
        let last = exp.population(full.population.clone()).unwrap();
        let rebuilt = exp.finished(run, last, full.history.clone());
        assert_eq!(rebuilt.evaluations, full.evaluations);
    }

    /// An observer that breaks stops the run after that generation; continuing from what it
    /// returns gives the uninterrupted evolution.
    #[test]
    fn a_breaking_observer_stops_the_run_and_it_continues_exactly() {
        let exp = experiment(&[]);
        let run = &exp.runs()[0];
        let full = whole(&exp, run);
        let stopped = exp
            .evolve(run, &mut |s| {
                if s.history.len() == 2 {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            })
            .expect_err("stopped after generation 2");
        let super::EvolveError::Stopped(stopped) = stopped else {
            panic!("stopped by its observer: {stopped}")
        };
        assert_eq!(stopped.generation, 2);
        assert_eq!(stopped.history, full.history[..2]);
        let resumed = exp
            .evolve_from(
                run,
                stopped.generation,
                stopped.population,
                stopped.history,
                &mut |_| ControlFlow::Continue(()),
            )
            .unwrap();
        assert_eq!(resumed.history, full.history);
        assert_eq!(resumed.population, full.population);
    }

    /// A genome of the wrong length is an error naming both lengths, never a panic: as a
    /// network, and as a member of a population (which must not be empty either).
    #[test]
    fn wrong_genomes_are_errors() {
        use super::PopulationError;
        use crate::simulation::controller::GenomeError;
        let exp = experiment(&[]);
        let e = exp.network(&[0.5; 67]).unwrap_err();
        assert_eq!(
            e,
            GenomeError {
                inputs: 8,
                hidden: 6,
                expected: 68,
                actual: 67
            }
        );
        assert_eq!(
            e.to_string(),
            "a genome of the 8-6-2 network has 68 weights, got 67"
        );
        assert_eq!(exp.population(Vec::new()), Err(PopulationError::Empty));
        let e = exp
            .population(vec![vec![0.0; 68], vec![0.0; 69]])
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "genome 1 of the population: a genome of the 8-6-2 network has 68 weights, got 69"
        );
        let fine = exp.population(vec![vec![0.0; 68]; 3]).unwrap();
        assert_eq!((fine.len(), fine.shape()), (3, exp.shape()));
    }
}
