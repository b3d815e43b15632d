//! Evaluation: one individual's trials in the rooms of a run, on the evaluation (and online
//! orientation) streams, combined into its fuzzy fitness; populations are evaluated in parallel.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::evolution::population::Population;
use crate::experiment::config::OrientationMode;
use crate::experiment::robustness::Perturbed;
use crate::experiment::{Experiment, Perturbation, Run};
use crate::fitness::terms::{FitnessTerms, TermsRecorder, TrialRecord, UserValues};
use crate::modelling::aem::{Action, environment_vector};
use crate::modelling::recognition::nearest_unique;
use crate::params::Num;
use crate::random::rng::rng_from_seed;
use crate::simulation::controller::{Controller, GenomeError, Mlp};
use crate::simulation::lanes::{LaneTrial, lanes_fit, walk_lanes};
use crate::simulation::randomise::Draw;
use crate::simulation::robot::Pose;
use crate::simulation::trial::{ActionLog, Arena, StepObserver, Trajectory, simulate};

/// A user-defined term ([`crate::fitness::Term`]) that returned a value outside [0, 1], or
/// NaN: a bug in the term. The evaluation keeps the value as it came (clamping would hide the
/// bug in F); [`Experiment::check_terms`] finds it, and evolving or modelling the rooms
/// returns it as an error ([`crate::experiment::RunError::Term`]), never a panic.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the user-defined term {term:?} returned {}, outside [0, 1]: a term's value must be in [0, 1] (a bug in the term)",
    Num(*.value)
)]
pub struct TermError {
    /// The term's name.
    pub term: String,
    /// The value it returned.
    pub value: f64,
}

impl Experiment {
    /// The experiment's network for `genome`: an error when its length is not the network's
    /// ([`crate::simulation::controller::MlpShape::genome_len`]).
    pub fn network(&self, genome: &[f64]) -> Result<Mlp, GenomeError> {
        Mlp::from_genome(self.shape, genome)
    }

    /// Runs one trial of `network` in `room` with the random stream `seed`; returns the terms
    /// (`l` = 0) and the action labels.
    pub fn trial(&self, network: &Mlp, room: usize, seed: u64) -> (FitnessTerms, Vec<Action>) {
        let (terms, actions, _) = self.recorded_trial(&mut network.clone(), room, seed, true);
        (terms, actions)
    }

    /// One trial: its terms (`l` = 0), its actions (when `actions`, else none) and the number of
    /// steps it executed before it ended (the rest were idle). The network's state carries
    /// nothing from one trial to the next, so one network serves every trial of an individual.
    fn recorded_trial(
        &self,
        network: &mut Mlp,
        room: usize,
        seed: u64,
        actions: bool,
    ) -> (FitnessTerms, Vec<Action>, usize) {
        let mut log = ActionLog {
            actions: Vec::with_capacity(if actions { self.trial.steps() } else { 0 }),
        };
        let (terms, executed, _) = if actions {
            self.observed_trial(network, room, seed, &mut log)
        } else {
            self.observed_trial(network, room, seed, &mut ())
        };
        (terms, log.actions, executed)
    }

    /// One evaluation trial in `room` on the stream `seed`, each step also shown to `extra`:
    /// its terms (the mission's and the user-defined ones included; `l` = 0), the steps it
    /// executed and its final pose. Every evaluation trial runs through here.
    pub(crate) fn observed_trial<C: Controller + ?Sized, O: StepObserver>(
        &self,
        network: &mut C,
        room: usize,
        seed: u64,
        extra: &mut O,
    ) -> (FitnessTerms, usize, Pose) {
        self.observed_trial_in(&self.arenas[room], network, seed, extra)
    }

    /// [`Experiment::observed_trial`] in `arena` (a room of the experiment, maybe prepared for
    /// another robot).
    fn observed_trial_in<C: Controller + ?Sized, O: StepObserver>(
        &self,
        arena: &Arena,
        network: &mut C,
        seed: u64,
        extra: &mut O,
    ) -> (FitnessTerms, usize, Pose) {
        let mut rng = rng_from_seed(seed);
        let mut recorder = self.recorder(arena);
        let (last, trajectory) = if self.computes_user_terms() {
            let mut trajectory = Trajectory::starting_at(arena.room().home, self.trial.steps());
            let mut obs = (&mut recorder, (&mut *extra, &mut trajectory));
            (
                simulate(arena, network, &mut rng, &mut obs),
                Some(trajectory),
            )
        } else {
            let mut obs = (&mut recorder, &mut *extra);
            (simulate(arena, network, &mut rng, &mut obs), None)
        };
        let mut terms = self.recorded_terms(&recorder);
        if let Some(trajectory) = trajectory {
            self.user_values(arena, &trajectory, &mut terms);
        }
        (terms, recorder.executed(), last)
    }

    /// What records an evaluation trial's terms in `arena` (the mission's included).
    pub(crate) fn recorder<'a>(&self, arena: &'a Arena) -> TermsRecorder<&'a Arena> {
        let recorder = TermsRecorder::new(arena, self.homing);
        match self.plan.tracker(arena.room()) {
            Some(tracker) => recorder.with_mission(tracker),
            None => recorder,
        }
    }

    /// The terms `recorder` recorded, the user-defined ones still 0.
    pub(crate) fn recorded_terms(&self, recorder: &TermsRecorder<&Arena>) -> FitnessTerms {
        let mut terms = recorder.finish();
        terms.user = UserValues::zeros(self.plan.user.len());
        terms
    }

    /// Whether some user-defined term is computed from the trial's record (a Rust
    /// [`crate::fitness::terms::Term`]), so that every step must be recorded.
    fn computes_user_terms(&self) -> bool {
        self.plan.user.iter().any(|u| u.term.is_some())
    }

    /// An evolution's evaluation trial: [`Experiment::recorded_trial`], or with
    /// `[trial.randomise]` the robot drawn for this trial ([`Experiment::randomised_trial`]).
    /// The choice is made once per trial, never per step.
    fn training_trial(
        &self,
        network: &mut Mlp,
        room: usize,
        seed: u64,
        actions: bool,
    ) -> (FitnessTerms, Vec<Action>, usize) {
        match &self.randomise {
            None => self.recorded_trial(network, room, seed, actions),
            Some(r) => self.randomised_trial(&r.draw(seed), network, room, seed, actions),
        }
    }

    /// One trial of the robot `draw` makes of this experiment's (its perturbations applied as
    /// the robustness study applies them: the room prepared for the drawn body, sensors and
    /// noise; the wheel bias on the network's outputs).
    fn randomised_trial(
        &self,
        draw: &Draw,
        network: &mut Mlp,
        room: usize,
        seed: u64,
        actions: bool,
    ) -> (FitnessTerms, Vec<Action>, usize) {
        let mut trial = self.trial;
        for p in Perturbation::of_draw(draw) {
            // The ranges were checked against the robot (Randomise::from_raw): every draw fits.
            trial = p.apply(trial).unwrap_or(trial);
        }
        // A draw that leaves the trial's parameters as they are (a wheel bias alone) runs in the
        // room as prepared; any other is prepared for its robot.
        let drawn;
        let arena = if trial == self.trial {
            &self.arenas[room]
        } else {
            drawn = Arena::new(self.arenas[room].room().clone(), &trial);
            &drawn
        };
        let mut c = Perturbed {
            net: network,
            dead: None,
            bias: draw.wheel_bias.unwrap_or(0.0),
        };
        let mut log = ActionLog {
            actions: Vec::with_capacity(if actions { trial.steps() } else { 0 }),
        };
        let (terms, executed, _) = if actions {
            self.observed_trial_in(arena, &mut c, seed, &mut log)
        } else {
            self.observed_trial_in(arena, &mut c, seed, &mut ())
        };
        (terms, log.actions, executed)
    }

    /// The user-defined terms' values of a finished trial (supplied ones left at 0 for the front
    /// to fill in).
    pub(crate) fn user_values(
        &self,
        arena: &Arena,
        trajectory: &Trajectory,
        terms: &mut FitnessTerms,
    ) {
        let mut values = terms.user;
        for (v, u) in values.as_mut_slice().iter_mut().zip(&self.plan.user) {
            if let Some(term) = &u.term {
                let record = TrialRecord {
                    arena,
                    trajectory,
                    terms,
                };
                *v = term.value(&record);
            }
        }
        terms.user = values;
    }

    /// The first value outside [0, 1] (or NaN) of a user-defined term computed here (a Rust
    /// [`crate::fitness::Term`]; the values a front supplies are its own to check) in `terms`.
    pub fn check_terms<'a>(
        &self,
        terms: impl IntoIterator<Item = &'a FitnessTerms>,
    ) -> Result<(), TermError> {
        let computed: Vec<usize> = (self.plan.user.iter().enumerate())
            .filter(|(_, u)| u.term.is_some())
            .map(|(k, _)| k)
            .collect();
        if computed.is_empty() {
            return Ok(());
        }
        for t in terms {
            let values = t.user.as_slice();
            for &k in &computed {
                let value = values.get(k).copied().unwrap_or(0.0);
                if !(0.0..=1.0).contains(&value) {
                    let term = self.plan.user[k].name.clone();
                    return Err(TermError { term, value });
                }
            }
        }
        Ok(())
    }

    /// Recomputes an evaluation's F (each room's, then their mean) from its terms: for a front
    /// that filled in the values of supplied user terms ([`crate::experiment::UserTerm`]).
    pub fn refit(&self, evaluation: &mut Evaluation) {
        for s in &mut evaluation.per_room {
            s.f = self.fuzzy_fitness(&s.terms);
        }
        let n = evaluation.per_room.len() as f64;
        evaluation.fitness = evaluation.per_room.iter().map(|s| s.f).sum::<f64>() / n;
    }

    /// The random stream of individual `individual`'s evaluation trial in `room` in generation
    /// `generation` of `run`.
    pub fn eval_seed(&self, run: &Run, generation: usize, individual: usize, room: usize) -> u64 {
        self.streams()
            .evaluation(run.tag, generation, individual, self.room_key(room))
    }

    /// Evaluates one individual (its network) of generation `generation` in the rooms of `run`.
    pub fn evaluate(
        &self,
        network: &Mlp,
        run: &Run,
        generation: usize,
        individual: usize,
    ) -> Evaluation {
        self.evaluate_with(&mut network.clone(), run, generation, individual)
    }

    /// [`Experiment::evaluate`], running `network` itself.
    fn evaluate_with(
        &self,
        network: &mut Mlp,
        run: &Run,
        generation: usize,
        individual: usize,
    ) -> Evaluation {
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation() > 0.0;
        let mut per_room = Vec::with_capacity(run.rooms.len());
        let mut first_vectors = Vec::new();
        for &r in &run.rooms {
            let seed = self.eval_seed(run, generation, individual, r);
            let (terms, actions, executed) = self.training_trial(network, r, seed, online);
            if online {
                first_vectors.push(environment_vector(&actions, self.aem.encoder()));
            }
            per_room.push(RoomScore {
                f: 0.0,
                terms,
                executed,
            });
        }
        if online {
            // docs/model.md §10: a second run per room, classified by 1-NN against the first runs.
            let mut correct = 0;
            for (k, &r) in run.rooms.iter().enumerate() {
                let seed = self
                    .streams()
                    .online(run.tag, generation, individual, self.room_key(r));
                let (_, actions, _) = self.training_trial(network, r, seed, true);
                let v = environment_vector(&actions, self.aem.encoder());
                if nearest_unique(&first_vectors, &v).ok().flatten() == Some(k) {
                    correct += 1;
                }
            }
            let l = correct as f64 / run.rooms.len() as f64;
            for s in &mut per_room {
                s.terms.l = l;
            }
        }
        self.scored(per_room)
    }

    /// Evaluates a population in parallel (results in index order, independent of threads).
    /// With `actions` motion, sensor and wheel noise and the 8-6-2 network (the paper's robot),
    /// the trials of a room run four at a time in lock-step, their noise and networks in
    /// vector lanes; that changes no result.
    pub fn evaluate_population(
        &self,
        population: &Population,
        run: &Run,
        generation: usize,
    ) -> Vec<Evaluation> {
        let networks: Vec<Mlp> = population
            .par_iter()
            .map(|g| Mlp::of_checked(population.shape(), g))
            .collect();
        let batches: Vec<&[Mlp]> = networks.chunks(LANE_BATCH).collect();
        batches
            .into_par_iter()
            .enumerate()
            .flat_map_iter(|(b, nets)| self.evaluate_batch(nets, b * LANE_BATCH, run, generation))
            .collect()
    }

    /// Evaluates the individuals `first..` whose networks are `nets`: in the lanes when every
    /// trial fits them, else one individual at a time ([`Experiment::evaluate_with`]).
    fn evaluate_batch(
        &self,
        nets: &[Mlp],
        first: usize,
        run: &Run,
        generation: usize,
    ) -> Vec<Evaluation> {
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation() > 0.0;
        let fit = self.randomise.is_none()
            && !online
            && !self.computes_user_terms()
            && run.rooms.iter().all(|&r| {
                let arena = &self.arenas[r];
                nets.iter().all(|n| lanes_fit(arena, n))
            });
        if !fit {
            return (nets.iter().enumerate())
                .map(|(i, n)| self.evaluate_with(&mut n.clone(), run, generation, first + i))
                .collect();
        }
        let mut per_room = vec![Vec::with_capacity(run.rooms.len()); nets.len()];
        for &r in &run.rooms {
            let arena = &self.arenas[r];
            let mut trials: Vec<_> = (nets.iter().enumerate())
                .map(|(i, net)| LaneTrial {
                    net,
                    seed: self.eval_seed(run, generation, first + i, r),
                    observer: self.recorder(arena),
                    last: arena.room().home,
                    drawn: None,
                })
                .collect();
            walk_lanes(arena, &mut trials);
            for (scores, trial) in per_room.iter_mut().zip(&trials) {
                scores.push(RoomScore {
                    f: 0.0,
                    terms: self.recorded_terms(&trial.observer),
                    executed: trial.observer.executed(),
                });
            }
        }
        per_room.into_iter().map(|s| self.scored(s)).collect()
    }

    /// An evaluation of the per-room scores `per_room` (terms measured, F not yet combined).
    fn scored(&self, mut per_room: Vec<RoomScore>) -> Evaluation {
        for s in &mut per_room {
            s.f = self.fuzzy_fitness(&s.terms);
        }
        let fitness = per_room.iter().map(|s| s.f).sum::<f64>() / per_room.len() as f64;
        Evaluation { fitness, per_room }
    }
}

/// Individuals per task of [`Experiment::evaluate_population`]: enough for the lanes to stay
/// full (a lane idles only once fewer trials than lanes are left), few enough to share a
/// population among threads.
const LANE_BATCH: usize = 20;

/// F and terms of one individual in one room.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RoomScore {
    /// Fuzzy fitness F in this room.
    pub f: f64,
    /// The terms measured.
    pub terms: FitnessTerms,
    /// Steps the evaluation trial executed before it ended (the rest were idle): the work done.
    #[serde(default)]
    pub executed: usize,
}

/// One individual's evaluation: mean F over its rooms, and per-room scores.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Fitness used by the GA (mean F over the run's rooms).
    pub fitness: f64,
    /// Per room of the run, in order.
    pub per_room: Vec<RoomScore>,
}

impl Evaluation {
    /// Steps executed by the evaluation trials (the online second runs not counted).
    pub fn executed(&self) -> usize {
        self.per_room.iter().map(|s| s.executed).sum()
    }

    /// Mean terms over the rooms.
    pub fn mean_terms(&self) -> FitnessTerms {
        let n = self.per_room.len() as f64;
        let mut t = FitnessTerms::default();
        for s in &self.per_room {
            t.add_mean(&s.terms, n);
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::testing::{ORIENTED, experiment};

    /// A population evaluated in the lanes (`evaluate_population`) scores exactly as each
    /// individual evaluated alone (`evaluate`, which runs `simulate`): every bit of every F,
    /// term and executed count, for an evolved population whose trials end at home at
    /// different steps, and for a batch whose networks do not all fit the lanes.
    #[test]
    fn lanes_score_a_population_as_its_individuals_alone() {
        let exp = experiment(&["ga.population=24", "ga.generations=4", "trial.steps=250"]);
        let run = &exp.runs()[0];
        let evolved = exp.evolve(run, &mut |_| std::ops::ControlFlow::Continue(()));
        let mut population = Population {
            shape: exp.shape,
            genomes: evolved.unwrap().population,
        };
        let alone = |population: &Population| -> Vec<Evaluation> {
            (0..population.len())
                .map(|i| exp.evaluate(&population.network(i), run, 3, i))
                .collect()
        };
        let lanes = exp.evaluate_population(&population, run, 3);
        assert_eq!(format!("{lanes:?}"), format!("{:?}", alone(&population)));
        let steps = exp.trial.steps();
        let executed: Vec<usize> = lanes
            .iter()
            .flat_map(|e| &e.per_room)
            .map(|s| s.executed)
            .collect();
        assert!(
            executed.iter().any(|&n| n < steps),
            "no trial ended at home: {executed:?}"
        );
        // A weight that is not finite sends its batch (and only its batch) the individual way.
        population.genomes[5][7] = f64::INFINITY;
        let mixed = exp.evaluate_population(&population, run, 3);
        assert_eq!(format!("{mixed:?}"), format!("{:?}", alone(&population)));
    }

    /// Online l is exactly the off-line 1-NN computation on the same trajectories, run on the
    /// derived streams (EVAL for the first run, ONLINE for the second).
    #[test]
    fn online_orientation_equals_offline_nearest_neighbour() {
        let exp = experiment(&ORIENTED);
        let run = &exp.runs()[0];
        let genome = &exp.initial_population(run).network(3);
        let (g, i) = (2usize, 3usize);
        let eval = exp.evaluate(genome, run, g, i);
        let first: Vec<Vec<f64>> = run
            .rooms
            .iter()
            .map(|&r| {
                let seed = exp.eval_seed(run, g, i, r);
                environment_vector(&exp.trial(genome, r, seed).1, exp.aem.encoder())
            })
            .collect();
        let mut correct = 0;
        for (k, &r) in run.rooms.iter().enumerate() {
            let seed = exp.streams().online(run.tag, g, i, exp.room_key(r));
            assert_ne!(seed, exp.eval_seed(run, g, i, r));
            let v = environment_vector(&exp.trial(genome, r, seed).1, exp.aem.encoder());
            if crate::modelling::recognition::nearest_unique(&first, &v).unwrap() == Some(k) {
                correct += 1;
            }
        }
        let l = correct as f64 / run.rooms.len() as f64;
        assert!(
            eval.per_room.iter().all(|s| s.terms.l == l),
            "{eval:?} vs l = {l}"
        );
        // The first run's terms are those of the off-line evaluation on the same stream.
        let offline = experiment(&[
            "fitness.orientation=\"offline\"",
            "motivations.curiosity=0.4",
            "motivations.homing=0.2",
            "motivations.orientation=0.3",
            "motivations.energy=0.1",
        ]);
        let off = offline.evaluate(genome, run, g, i);
        for (a, b) in eval.per_room.iter().zip(&off.per_room) {
            assert_eq!(
                (a.terms.a, a.terms.g, a.terms.b),
                (b.terms.a, b.terms.g, b.terms.b)
            );
            assert_eq!(b.terms.l, 0.0);
        }
    }
}
