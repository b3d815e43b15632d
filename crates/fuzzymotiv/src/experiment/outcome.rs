//! The whole experiment as the paper runs it: every evolution of the protocol
//! ([`Experiment::runs`]), then environment modelling of each evolution's best robot, with
//! which robot stands for which room. Observers see every generation and may stop the run;
//! an evolution can start afresh, continue from a saved generation, or be already finished.

use std::ops::ControlFlow;

use crate::experiment::Experiment;
use crate::experiment::config::Training;
use crate::experiment::evaluation::TermError;
use crate::experiment::evolution::{
    Evolution, EvolveError, GenerationRecord, GenerationState, Population, Stopped,
};
use crate::experiment::modelling::{AemReport, InstanceRun};
use crate::modelling::som::SomError;
use crate::simulation::controller::GenomeError;
use crate::simulation::trial::Trajectory;

/// An observer of a whole experiment: called after every generation with the index of the
/// evolution (in [`Experiment::runs`]) and where it stands; [`ControlFlow::Break`] stops the
/// experiment there.
pub type RunObserver<'a> = dyn FnMut(usize, &GenerationState<'_>) -> ControlFlow<()> + 'a;

/// Where one evolution of an experiment starts.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Start {
    /// From its initial population.
    #[default]
    Fresh,
    /// From a generation not yet evaluated (what a checkpoint or [`Stopped`] holds).
    Continue(Stopped),
    /// Already finished: its final population and every generation's record (the final
    /// generation is evaluated again, which gives the same evaluations).
    Finished {
        /// The final generation.
        population: Population,
        /// Every generation's record.
        history: Vec<GenerationRecord>,
    },
}

/// An experiment stopped by its observer.
#[derive(Debug, Clone, PartialEq)]
pub struct Interrupted {
    /// The evolution that was stopped (its index in [`Experiment::runs`]).
    pub run: usize,
    /// Where it stopped.
    pub stopped: Stopped,
}

/// What a finished experiment produced: its evolutions and the modelling of their best robots.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// One evolution per run of the protocol, in [`Experiment::runs`] order.
    pub evolutions: Vec<Evolution>,
    /// The environment modelling of each evolution's best robot.
    pub modelling: Vec<AemReport>,
    training: Training,
}

/// Why a finished experiment has no outcome.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RunError {
    /// The observer stopped it.
    #[error("the run was stopped after generation {}", .0.stopped.generation)]
    Interrupted(Interrupted),
    /// [`Experiment::run_from`] was given a number of starts other than one per run.
    #[error("{got} starts given for an experiment of {expected} evolutions (one per run)")]
    Starts {
        /// The number of runs of the protocol.
        expected: usize,
        /// The number of starts given.
        got: usize,
    },
    /// An evolution's best genome does not fit the experiment's network.
    #[error("environment modelling: {0}")]
    Genome(#[from] GenomeError),
    /// Environment modelling failed.
    #[error("environment modelling failed: {0}")]
    Modelling(#[from] SomError),
    /// A user-defined term returned a value outside [0, 1] (a bug in the term).
    #[error(transparent)]
    Term(#[from] TermError),
}

impl Experiment {
    /// Evolves every run of the protocol from scratch and models the rooms.
    pub fn run(&self, observer: &mut RunObserver<'_>) -> Result<Outcome, RunError> {
        let starts = vec![Start::Fresh; self.runs().len()];
        self.run_from(starts, observer)
    }

    /// [`Experiment::run`], each evolution starting as `starts` says (one per run). The result
    /// equals an uninterrupted run's, because every random stream is derived from (run,
    /// generation, individual, room).
    pub fn run_from(
        &self,
        starts: Vec<Start>,
        observer: &mut RunObserver<'_>,
    ) -> Result<Outcome, RunError> {
        let runs = self.runs();
        if starts.len() != runs.len() {
            return Err(RunError::Starts {
                expected: runs.len(),
                got: starts.len(),
            });
        }
        let mut evolutions = Vec::with_capacity(runs.len());
        for (k, (run, start)) in runs.iter().zip(starts).enumerate() {
            let mut on_generation = |state: &GenerationState<'_>| observer(k, state);
            let evolution = match start {
                Start::Fresh => self.evolve(run, &mut on_generation),
                Start::Continue(s) => self.evolve_from(
                    run,
                    s.generation,
                    s.population,
                    s.history,
                    &mut on_generation,
                ),
                Start::Finished {
                    population,
                    history,
                } => Ok(self.finished(run, population, history)),
            };
            let evolution = evolution.map_err(|e| match e {
                EvolveError::Stopped(stopped) => {
                    RunError::Interrupted(Interrupted { run: k, stopped })
                }
                EvolveError::Term(e) => RunError::Term(e),
            })?;
            evolutions.push(evolution);
        }
        let modelling = self.model_rooms(&evolutions)?;
        Ok(Outcome {
            evolutions,
            modelling,
            training: self.training(),
        })
    }

    /// Environment modelling of every evolution's best robot.
    pub fn model_rooms(&self, evolutions: &[Evolution]) -> Result<Vec<AemReport>, RunError> {
        let mut reports = Vec::with_capacity(evolutions.len());
        for evo in evolutions {
            let best = self.network(&evo.population[evo.best])?;
            let report = self.environment_modelling(&best, &evo.run)?;
            self.check_terms(report.rooms.iter().map(|r| &r.instance.terms))?;
            reports.push(report);
        }
        Ok(reports)
    }

    /// [`Experiment::end_spread`] in every room, of the robot that stands for it in `outcome`.
    pub fn end_spreads(&self, outcome: &Outcome) -> Result<Vec<f64>, GenomeError> {
        (0..self.arenas.len())
            .map(|r| {
                let (evolution, _) = outcome.robot_for_room(r);
                let network = self.network(&evolution.population[evolution.best])?;
                Ok(self.end_spread(&network, &evolution.run, r))
            })
            .collect()
    }

    /// Which evolution's best robot stands for room `r`, and the room's position among that
    /// evolution's rooms: the one robot of all-rooms training, or the room's own robot.
    pub fn robot_for_room(&self, r: usize) -> (usize, usize) {
        robot_for_room(self.training(), r)
    }
}

fn robot_for_room(training: Training, r: usize) -> (usize, usize) {
    match training {
        Training::AllRooms => (0, r),
        Training::PerRoom => (r, 0),
    }
}

impl Outcome {
    /// An outcome from its parts (e.g. read back from files): `modelling[k]` models
    /// `evolutions[k]`'s best robot.
    pub fn new(exp: &Experiment, evolutions: Vec<Evolution>, modelling: Vec<AemReport>) -> Outcome {
        Outcome {
            evolutions,
            modelling,
            training: exp.training(),
        }
    }

    /// The evolution whose best robot stands for room `r` (see [`Experiment::robot_for_room`]),
    /// and the room's position among that evolution's rooms.
    pub fn robot_for_room(&self, r: usize) -> (&Evolution, usize) {
        let (k, position) = robot_for_room(self.training, r);
        (&self.evolutions[k], position)
    }

    /// The environment modelling of the robot that stands for room `r`.
    pub fn aem_for_room(&self, r: usize) -> &AemReport {
        &self.modelling[robot_for_room(self.training, r).0]
    }

    /// The room-modelling run of room `r`'s robot in room `r` (the run whose actions became
    /// the room's stored instance).
    pub fn instance(&self, r: usize) -> &InstanceRun {
        &self.aem_for_room(r).rooms[r].instance
    }

    /// The trajectories of [`Outcome::instance`], one per room.
    pub fn trajectories(&self) -> Vec<&Trajectory> {
        let rooms = self.modelling.first().map_or(0, |m| m.rooms.len());
        (0..rooms).map(|r| &self.instance(r).trajectory).collect()
    }
}

#[cfg(test)]
mod tests {
    use std::ops::ControlFlow;

    use super::*;
    use crate::experiment::testing::experiment;

    /// Stopped after a generation and continued, an experiment ends as an uninterrupted one.
    #[test]
    fn a_stopped_run_continues_to_the_same_outcome() {
        let exp = experiment(&["training=\"per-room\""]);
        let whole = exp.run(&mut |_, _| ControlFlow::Continue(())).unwrap();
        let mut seen = Vec::new();
        let stop = exp.run(&mut |k, s| {
            seen.push((k, s.history.len()));
            if k == 1 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        });
        let Err(RunError::Interrupted(i)) = stop else {
            panic!("the observer stopped it")
        };
        assert_eq!((i.run, i.stopped.generation), (1, 1));
        assert_eq!(seen, [(0, 1), (0, 2), (0, 3), (1, 1)]);
        let first = &whole.evolutions[0];
        let mut starts = vec![Start::Fresh; 5];
        starts[0] = Start::Finished {
            population: exp.population(first.population.clone()).unwrap(),
            history: first.history.clone(),
        };
        starts[1] = Start::Continue(i.stopped);
        let wrong = exp.run_from(vec![Start::Fresh], &mut |_, _| ControlFlow::Continue(()));
        assert!(matches!(
            wrong,
            Err(RunError::Starts {
                expected: 5,
                got: 1
            })
        ));
        let resumed = exp
            .run_from(starts, &mut |_, _| ControlFlow::Continue(()))
            .unwrap();
        for (a, b) in whole.evolutions.iter().zip(&resumed.evolutions) {
            assert_eq!((&a.history, &a.population), (&b.history, &b.population));
        }
        assert_eq!(whole.modelling, resumed.modelling);
    }

    /// Per-room training: room r's own robot stands for it; all-rooms: the one robot.
    #[test]
    fn the_robot_of_a_room_follows_the_protocol() {
        let per_room = experiment(&["training=\"per-room\""]);
        assert_eq!(per_room.robot_for_room(3), (3, 0));
        let all = experiment(&[]);
        assert_eq!(all.robot_for_room(3), (0, 3));
    }
}
