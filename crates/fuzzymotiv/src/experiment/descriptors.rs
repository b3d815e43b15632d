//! Behaviour descriptors (docs/model.md §7, "Behaviour descriptors"): per individual and room,
//! where its evaluation trial ended, its terms a, g, b and how often it took each action — what
//! quality-diversity methods (MAP-Elites) bin robots by. Computed only when asked
//! ([`Experiment::evaluate_described`]): the GA's own evaluation ([`Experiment::evaluate`]) never
//! records them.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::evolution::population::Population;
use crate::experiment::config::OrientationMode;
use crate::experiment::evaluation::{Evaluation, RoomScore};
use crate::experiment::{Experiment, Run};
use crate::fitness::terms::FitnessTerms;
use crate::simulation::controller::Mlp;
use crate::simulation::robot::{Action, Pose};
use crate::simulation::trial::{Step, StepObserver};

/// The behaviour of one individual's evaluation trial in one room. Every value is in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Descriptors {
    /// Final x of the robot's centre, normalised to the room's bounding box:
    /// `(x − x_min) / (x_max − x_min)` (the outline's box, [`crate::Room::bounds`]).
    pub x: f64,
    /// Final y, normalised likewise.
    pub y: f64,
    /// Exploration a of the trial.
    pub a: f64,
    /// Homing g of the trial.
    pub g: f64,
    /// Battery usage b of the trial.
    pub b: f64,
    /// Fraction of the executed steps (idle steps after the end at home not counted) labelled
    /// with each action, in the order of [`Descriptors::ACTIONS`]; they sum to 1.
    pub actions: [f64; 4],
}

impl Descriptors {
    /// The actions of [`Descriptors::actions`], in order.
    pub const ACTIONS: [Action; 4] = [
        Action::Straight,
        Action::Left30,
        Action::Right30,
        Action::Turn180,
    ];

    /// The names of [`Descriptors::as_array`]'s values, in order.
    pub const NAMES: [&'static str; 9] = [
        "x", "y", "a", "g", "b", "straight", "left30", "right30", "turn180",
    ];

    /// The values named by [`Descriptors::NAMES`], in order.
    pub fn as_array(&self) -> [f64; 9] {
        let [s, l, r, t] = self.actions;
        [self.x, self.y, self.a, self.g, self.b, s, l, r, t]
    }
}

/// Counts the actions of the executed steps.
#[derive(Debug, Clone, Copy, Default)]
struct ActionCounts([usize; 4]);

impl StepObserver for ActionCounts {
    #[inline]
    fn observe(&mut self, s: &Step) {
        // `Action`'s declaration order is `Descriptors::ACTIONS`' (a test checks it).
        self.0[s.action as usize] += usize::from(!s.idle);
    }
}

impl Experiment {
    /// Evaluates one individual as [`Experiment::evaluate`] does (the same [`Evaluation`], bit
    /// for bit) and describes its evaluation trial in each room of `run`, in order. Without
    /// online orientation this is one pass over each trial; with it, the evaluation trials are
    /// run once more to describe them.
    pub fn evaluate_described(
        &self,
        network: &Mlp,
        run: &Run,
        generation: usize,
        individual: usize,
    ) -> (Evaluation, Vec<Descriptors>) {
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation() > 0.0;
        let described: Vec<(RoomScore, Descriptors)> = run
            .rooms
            .iter()
            .map(|&r| {
                let seed = self.eval_seed(run, generation, individual, r);
                self.described_trial(&mut network.clone(), r, seed)
            })
            .collect();
        let descriptors = described.iter().map(|(_, d)| *d).collect();
        if online {
            return (
                self.evaluate(network, run, generation, individual),
                descriptors,
            );
        }
        // As `evaluate` without online orientation: F per room, then their mean.
        let mut per_room: Vec<RoomScore> = described.into_iter().map(|(s, _)| s).collect();
        for s in &mut per_room {
            s.f = self.fuzzy_fitness(&s.terms);
        }
        let fitness = per_room.iter().map(|s| s.f).sum::<f64>() / per_room.len() as f64;
        (Evaluation { fitness, per_room }, descriptors)
    }

    /// [`Experiment::evaluate_described`] for a population, in parallel (results in index
    /// order, independent of threads).
    pub fn evaluate_population_described(
        &self,
        population: &Population,
        run: &Run,
        generation: usize,
    ) -> Vec<(Evaluation, Vec<Descriptors>)> {
        (0..population.len())
            .into_par_iter()
            .map(|i| self.evaluate_described(&population.network(i), run, generation, i))
            .collect()
    }

    /// One evaluation trial of `genome` in `room` on the stream `seed`: its score (F not yet
    /// combined, `l` = 0) and its descriptors.
    fn described_trial(
        &self,
        network: &mut Mlp,
        room: usize,
        seed: u64,
    ) -> (RoomScore, Descriptors) {
        let mut counts = ActionCounts::default();
        let (terms, executed, last) = self.observed_trial(network, room, seed, &mut counts);
        let score = RoomScore {
            f: 0.0,
            terms,
            executed,
        };
        (score, self.descriptors(room, last, &terms, counts))
    }

    fn descriptors(
        &self,
        room: usize,
        last: Pose,
        terms: &FitnessTerms,
        counts: ActionCounts,
    ) -> Descriptors {
        let (lo, hi) = self.arenas[room].room().bounds();
        let unit = |v: f64, lo: f64, hi: f64| ((v - lo) / (hi - lo)).clamp(0.0, 1.0);
        let executed = counts.0.iter().sum::<usize>().max(1) as f64;
        Descriptors {
            x: unit(last.x, lo.x, hi.x),
            y: unit(last.y, lo.y, hi.y),
            a: terms.a,
            g: terms.g,
            b: terms.b,
            actions: counts.0.map(|n| n as f64 / executed),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::experiment::testing::{ORIENTED, experiment};
    use crate::simulation::trial::run_trial;

    /// `Action as usize` indexes `Descriptors::ACTIONS`.
    #[test]
    fn action_order() {
        for (k, a) in super::Descriptors::ACTIONS.iter().enumerate() {
            assert_eq!(*a as usize, k);
        }
    }

    /// The described evaluation is the GA's evaluation, bit for bit, off-line and online; the
    /// descriptors are those of the recorded trajectory on the same stream.
    #[test]
    fn described_evaluation_equals_the_evaluation() {
        for sets in [&[][..], &ORIENTED[..]] {
            let exp = experiment(sets);
            let run = &exp.runs()[0];
            let population = exp.initial_population(run);
            let plain = exp.evaluate_population(&population, run, 2);
            let described = exp.evaluate_population_described(&population, run, 2);
            for (i, (p, (e, d))) in plain.iter().zip(&described).enumerate() {
                assert_eq!(p, e);
                assert_eq!(d.len(), run.rooms.len());
                for (k, &r) in run.rooms.iter().enumerate() {
                    let arena = &exp.arenas()[r];
                    let mut rng = crate::random::rng::rng_from_seed(exp.eval_seed(run, 2, i, r));
                    let tr = run_trial(arena, &mut population.network(i), &mut rng);
                    let last = tr.poses.last().unwrap();
                    let (lo, hi) = arena.room().bounds();
                    assert_eq!(d[k].x, (last.x - lo.x) / (hi.x - lo.x));
                    assert_eq!(d[k].y, (last.y - lo.y) / (hi.y - lo.y));
                    let executed = tr.executed();
                    let straight = (0..tr.len())
                        .filter(|&t| {
                            !tr.idle[t]
                                && tr.actions[t] == crate::simulation::robot::Action::Straight
                        })
                        .count();
                    assert_eq!(d[k].actions[0], straight as f64 / executed as f64);
                    assert!((d[k].actions.iter().sum::<f64>() - 1.0).abs() < 1e-12);
                    let t = e.per_room[k].terms;
                    assert_eq!((d[k].a, d[k].g, d[k].b), (t.a, t.g, t.b));
                }
            }
        }
    }
}
