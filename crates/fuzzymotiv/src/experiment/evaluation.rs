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
use crate::simulation::lanes::{Drawn, LaneTrial};
use crate::simulation::lanes_any::{lanes_fit, walk_lanes};
use crate::simulation::randomise::Draw;
use crate::simulation::robot::Pose;
use crate::simulation::trial::{ActionLog, Arena, Step, StepObserver, Trajectory, simulate};

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
        let own = self.drawn_arena(draw, room);
        let arena = own.as_deref().unwrap_or(&self.arenas[room]);
        let trial = arena.params();
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

    /// The arena of `room` for the robot `draw` makes of this experiment's (its perturbations
    /// applied as the robustness study applies them): `None` when the draw leaves the trial's
    /// parameters as they are (a wheel bias alone: the room as prepared), else the room
    /// prepared for the drawn body, sensors and noise.
    fn drawn_arena(&self, draw: &Draw, room: usize) -> Option<Box<Arena>> {
        let mut trial = self.trial;
        for p in Perturbation::of_draw(draw) {
            // The ranges were checked against the robot (Randomise::from_raw): every draw fits.
            trial = p.apply(trial).unwrap_or(trial);
        }
        let room = self.arenas[room].room().clone();
        (trial != self.trial).then(|| Box::new(Arena::new(room, &trial)))
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
    /// The trials of a room run four at a time in lock-step, their noise and networks in
    /// vector lanes (any robot and motion, randomised robots, online orientation, user-defined
    /// terms; a batch of one or two trials of any robot but the paper's one at a time); that
    /// changes no result.
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
    /// network fits them ([`lanes_fit`]), else one individual at a time
    /// ([`Experiment::evaluate_with`]). Each trial in the lanes is the trial
    /// [`Experiment::training_trial`] runs: its drawn robot with `[trial.randomise]`, its
    /// actions kept for online orientation (whose second runs also go through the lanes), its
    /// whole record for user-defined terms.
    pub(crate) fn evaluate_batch(
        &self,
        nets: &[Mlp],
        first: usize,
        run: &Run,
        generation: usize,
    ) -> Vec<Evaluation> {
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation() > 0.0;
        let fit = run.rooms.iter().all(|&r| {
            let arena = &self.arenas[r];
            nets.iter().all(|n| lanes_fit(arena, n))
        });
        if !fit {
            return (nets.iter().enumerate())
                .map(|(i, n)| self.evaluate_with(&mut n.clone(), run, generation, first + i))
                .collect();
        }
        let mut per_room = vec![Vec::with_capacity(run.rooms.len()); nets.len()];
        let mut first_vectors = vec![Vec::new(); nets.len()];
        for &r in &run.rooms {
            let seeds: Vec<u64> = (0..nets.len())
                .map(|i| self.eval_seed(run, generation, first + i, r))
                .collect();
            let trials = self.lane_trials(nets, r, &seeds, online);
            for (i, (terms, actions, executed)) in trials.into_iter().enumerate() {
                if online {
                    first_vectors[i].push(environment_vector(&actions, self.aem.encoder()));
                }
                per_room[i].push(RoomScore {
                    f: 0.0,
                    terms,
                    executed,
                });
            }
        }
        if online {
            self.online_in_lanes(nets, first, run, generation, &first_vectors, &mut per_room);
        }
        per_room.into_iter().map(|s| self.scored(s)).collect()
    }

    /// Online orientation's second runs of the individuals `first..` (networks `nets`) in
    /// the lanes: each classified by 1-NN against its first runs `first_vectors[i]`, and its l
    /// written into its scores `per_room[i]`, as [`Experiment::evaluate_with`] does.
    fn online_in_lanes(
        &self,
        nets: &[Mlp],
        first: usize,
        run: &Run,
        generation: usize,
        first_vectors: &[Vec<Vec<f64>>],
        per_room: &mut [Vec<RoomScore>],
    ) {
        let mut correct = vec![0; nets.len()];
        for (k, &r) in run.rooms.iter().enumerate() {
            let seeds: Vec<u64> = (0..nets.len())
                .map(|i| {
                    let key = self.room_key(r);
                    self.streams().online(run.tag, generation, first + i, key)
                })
                .collect();
            let trials = self.lane_trials(nets, r, &seeds, true);
            for (i, (_, actions, _)) in trials.iter().enumerate() {
                let v = environment_vector(actions, self.aem.encoder());
                if nearest_unique(&first_vectors[i], &v).ok().flatten() == Some(k) {
                    correct[i] += 1;
                }
            }
        }
        for (scores, c) in per_room.iter_mut().zip(correct) {
            let l = c as f64 / run.rooms.len() as f64;
            for s in scores {
                s.terms.l = l;
            }
        }
    }

    /// The training trials of the networks `nets` in `room` on the streams `seeds` (one each),
    /// in the lanes: each one's terms (user-defined ones included, `l` = 0), its actions (when
    /// `actions`, else none) and its executed steps, as [`Experiment::training_trial`] gives
    /// them. With neither actions nor user-defined terms (the paper's study), only the terms
    /// are recorded.
    fn lane_trials(
        &self,
        nets: &[Mlp],
        room: usize,
        seeds: &[u64],
        actions: bool,
    ) -> Vec<(FitnessTerms, Vec<Action>, usize)> {
        // Each trial's drawn robot, prepared once here: its own arena (or none) and wheel bias.
        let drawn: Vec<Option<DrawnRobot>> = (seeds.iter())
            .map(|&seed| {
                let draw = self.randomise.as_ref()?.draw(seed);
                Some((
                    self.drawn_arena(&draw, room),
                    draw.wheel_bias.unwrap_or(0.0),
                ))
            })
            .collect();
        let user = self.computes_user_terms();
        if !actions && !user {
            return self.in_lanes(
                nets,
                room,
                seeds,
                &drawn,
                |arena| self.recorder(arena),
                |_, r| (self.recorded_terms(&r), Vec::new(), r.executed()),
            );
        }
        let steps = self.trial.steps();
        let watch = |arena| Watch {
            recorder: self.recorder(arena),
            log: actions.then(|| ActionLog {
                actions: Vec::with_capacity(steps),
            }),
            trajectory: user.then(|| Trajectory::starting_at(arena.room().home, steps)),
        };
        self.in_lanes(nets, room, seeds, &drawn, watch, |arena, w| {
            let mut terms = self.recorded_terms(&w.recorder);
            if let Some(trajectory) = &w.trajectory {
                self.user_values(arena, trajectory, &mut terms);
            }
            let log = w.log.map(|l| l.actions).unwrap_or_default();
            (terms, log, w.recorder.executed())
        })
    }

    /// The evaluation trials of the networks `nets` (individuals `first..` of `generation`)
    /// in each room of `run`, in the lanes, each recorded whole: per network and room its terms
    /// (user-defined ones included, `l` = 0), its trajectory and its executed steps, as
    /// [`Experiment::observed_trial`] with a [`Trajectory`] watching gives them (the
    /// experiment's own robot: a recorded trial draws none). `None` when a network does not
    /// fit the lanes ([`lanes_fit`]).
    pub(crate) fn recorded_in_lanes(
        &self,
        nets: &[Mlp],
        first: usize,
        run: &Run,
        generation: usize,
    ) -> Option<Vec<Vec<(FitnessTerms, Trajectory, usize)>>> {
        let fit = (run.rooms.iter()).all(|&r| nets.iter().all(|n| lanes_fit(&self.arenas[r], n)));
        if !fit {
            return None;
        }
        let steps = self.trial.steps();
        let user = self.computes_user_terms();
        let own: Vec<Option<DrawnRobot>> = vec![None; nets.len()];
        let mut recorded: Vec<Vec<_>> = vec![Vec::with_capacity(run.rooms.len()); nets.len()];
        for &r in &run.rooms {
            let seeds: Vec<u64> = (0..nets.len())
                .map(|i| self.eval_seed(run, generation, first + i, r))
                .collect();
            let watch = |arena| Watch {
                recorder: self.recorder(arena),
                log: None,
                trajectory: Some(Trajectory::starting_at(arena.room().home, steps)),
            };
            let trials = self.in_lanes(nets, r, &seeds, &own, watch, |arena, w| {
                let mut terms = self.recorded_terms(&w.recorder);
                let trajectory = w.trajectory.unwrap_or_default();
                if user {
                    self.user_values(arena, &trajectory, &mut terms);
                }
                (terms, trajectory, w.recorder.executed())
            });
            for (all, trial) in recorded.iter_mut().zip(trials) {
                all.push(trial);
            }
        }
        Some(recorded)
    }

    /// Runs `nets` in `room` in the lanes, trial `i` on the stream `seeds[i]` in its drawn
    /// robot `drawn[i]` (arena and wheel bias) if it has one, watched by `watch` of its arena;
    /// `finish` of each trial's arena and observer, in order.
    fn in_lanes<'a, O: StepObserver, T>(
        &'a self,
        nets: &'a [Mlp],
        room: usize,
        seeds: &[u64],
        drawn: &'a [Option<DrawnRobot>],
        watch: impl Fn(&'a Arena) -> O,
        finish: impl Fn(&'a Arena, O) -> T,
    ) -> Vec<T> {
        let arena = &self.arenas[room];
        let mut trials: Vec<_> = (nets.iter().zip(seeds).zip(drawn))
            .map(|((net, &seed), drawn)| {
                let drawn = drawn.as_ref().map(|(own, bias)| Drawn {
                    arena: own.as_deref().unwrap_or(arena),
                    bias: *bias,
                });
                let here = drawn.map_or(arena, |d| d.arena);
                LaneTrial {
                    net,
                    seed,
                    observer: watch(here),
                    last: here.room().home,
                    drawn,
                }
            })
            .collect();
        walk_lanes(arena, &mut trials);
        (trials.into_iter())
            .map(|t| finish(t.drawn.map_or(arena, |d| d.arena), t.observer))
            .collect()
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

/// A trial's robot drawn by `[trial.randomise]`, as the lanes take it: its own arena (`None`:
/// the room as prepared; boxed, as an arena is large) and its wheel bias.
type DrawnRobot = (Option<Box<Arena>>, f64);

/// What watches an evaluation trial in the lanes when more than its terms is wanted: the
/// recorder of its terms, its actions (online orientation), its whole record (user-defined
/// terms), as [`Experiment::observed_trial`]'s observers.
struct Watch<'a> {
    recorder: TermsRecorder<&'a Arena>,
    log: Option<ActionLog>,
    trajectory: Option<Trajectory>,
}

impl StepObserver for Watch<'_> {
    #[inline]
    fn observe(&mut self, step: &Step) {
        self.recorder.observe(step);
        if let Some(log) = &mut self.log {
            log.observe(step);
        }
        if let Some(trajectory) = &mut self.trajectory {
            trajectory.observe(step);
        }
    }

    /// The recorder's (a mission done); the log and the record never end a trial.
    #[inline]
    fn finished(&self) -> bool {
        self.recorder.finished()
    }

    /// Only the record reads the motors.
    #[inline]
    fn reads_motors(&self) -> bool {
        self.trajectory.is_some()
    }
}

/// Individuals per task of [`Experiment::evaluate_population`]: enough for the lanes to stay
/// full (a lane idles only once fewer trials than lanes are left), few enough to share a
/// population among threads.
pub(crate) const LANE_BATCH: usize = 20;

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
    use crate::simulation::room::{BUILTIN_ROOMS, Room};

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

    /// Every evaluation the lanes now run scores exactly as each individual evaluated alone:
    /// `wheels` motion, the e-puck2 and the Thymio II, another hidden size, no noise,
    /// `[trial.randomise]` (each trial its own robot), online orientation (both runs in the
    /// lanes), and a user-defined term computed from each trial's whole record (its motors
    /// included).
    #[test]
    fn lanes_score_every_robot_motion_and_term_as_alone() {
        use crate::experiment::UserTerm;
        use crate::fitness::terms::TrialRecord;
        #[derive(Debug)]
        struct MeanLeftMotor;
        impl crate::fitness::Term for MeanLeftMotor {
            fn value(&self, r: &TrialRecord<'_>) -> f64 {
                let m = &r.trajectory.motors;
                m.iter().map(|m| m[0]).sum::<f64>() / m.len().max(1) as f64
            }
        }
        let randomise = [
            "trial.randomise.noise=[0.0, 0.12]",
            "trial.randomise.sensor_scale=[0.8, 1.2]",
            "trial.randomise.wheel_bias=[-0.1, 0.1]",
            "trial.randomise.radius=[27.5, 31.0]",
        ];
        let cases: Vec<Vec<&str>> = vec![
            vec!["robot.motion=\"wheels\""],
            vec!["robot.file=\"epuck2\"", "robot.motion=\"wheels\""],
            vec![
                "robot.file=\"thymio2\"",
                "robot.motion=\"wheels\"",
                "trial.steps=150",
            ],
            vec!["network.hidden=4", "trial.noise=0.0"],
            randomise.to_vec(),
            [&randomise[..], &["robot.motion=\"wheels\""]].concat(),
            ORIENTED.to_vec(),
            [&ORIENTED[..], &["robot.motion=\"wheels\""]].concat(),
        ];
        let user = [UserTerm::computed(
            "left",
            std::sync::Arc::new(MeanLeftMotor),
        )];
        // The paper's rooms, for the Thymio II scaled 3× for its 80 mm body (rooms/thymio2/).
        let rooms = |thymio: bool| -> Vec<Room> {
            let scaled = [
                include_str!("../../../../rooms/thymio2/H.toml"),
                include_str!("../../../../rooms/thymio2/T.toml"),
                include_str!("../../../../rooms/thymio2/L.toml"),
            ];
            match thymio {
                true => (scaled.iter())
                    .map(|t| Room::from_toml_str(t, "rooms/thymio2").unwrap())
                    .collect(),
                false => (BUILTIN_ROOMS.iter())
                    .map(|r| Room::builtin(r).unwrap())
                    .collect(),
            }
        };
        let build = |sets: &[String], thymio: bool, user: &[UserTerm]| {
            let raw = crate::experiment::RawConfig::parse("", "test", sets).unwrap();
            Experiment::with_terms(&raw, rooms(thymio), user, "test").unwrap()
        };
        for (k, case) in cases.iter().enumerate() {
            let mut sets: Vec<String> = ["ga.population=26", "trial.steps=200", "aem.epochs=10"]
                .iter()
                .chain(case)
                .map(|s| s.to_string())
                .collect();
            let thymio = case.iter().any(|s| s.contains("thymio2"));
            let exp = build(&sets, thymio, &[]);
            let with_user = (k == 0).then(|| {
                sets.push("motivations.curiosity=0.3".into());
                sets.push("motivations.steady={ weight = 0.5, term = \"left\" }".into());
                build(&sets, thymio, &user)
            });
            for exp in std::iter::once(&exp).chain(&with_user) {
                let run = &exp.runs()[0];
                let population = exp.initial_population(run);
                let alone: Vec<Evaluation> = (0..population.len())
                    .map(|i| exp.evaluate(&population.network(i), run, 2, i))
                    .collect();
                let lanes = exp.evaluate_population(&population, run, 2);
                assert_eq!(format!("{lanes:?}"), format!("{alone:?}"), "{case:?}");
            }
        }
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
