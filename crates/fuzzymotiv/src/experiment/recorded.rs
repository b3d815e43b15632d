//! Evaluation with the evaluation trials recorded: for a front that computes terms of its own
//! from whole trajectories (Python's batched user terms) and then fills them in
//! ([`Experiment::refit`]). The GA's own evaluation ([`Experiment::evaluate_population`]) never
//! records them.

use rayon::prelude::*;

use crate::evolution::population::Population;
use crate::experiment::config::OrientationMode;
use crate::experiment::evaluation::{Evaluation, RoomScore};
use crate::experiment::{Experiment, Run};
use crate::simulation::controller::Mlp;
use crate::simulation::trial::Trajectory;

impl Experiment {
    /// Evaluates one individual as [`Experiment::evaluate`] does (the same [`Evaluation`], bit
    /// for bit) and records its evaluation trial in each room of `run`, in order (each trial
    /// runs through the same evaluation trial, with a [`Trajectory`] watching its steps). With
    /// online orientation, the evaluation is run once more to measure `l`.
    pub fn evaluate_recorded(
        &self,
        network: &Mlp,
        run: &Run,
        generation: usize,
        individual: usize,
    ) -> (Evaluation, Vec<Trajectory>) {
        let mut per_room = Vec::with_capacity(run.rooms.len());
        let mut trajectories = Vec::with_capacity(run.rooms.len());
        let mut net = network.clone();
        for &r in &run.rooms {
            let seed = self.eval_seed(run, generation, individual, r);
            let home = self.arenas[r].room().home;
            let mut trajectory = Trajectory::starting_at(home, self.trial.steps());
            let (terms, executed, _) = self.observed_trial(&mut net, r, seed, &mut trajectory);
            per_room.push(RoomScore {
                f: 0.0,
                terms,
                executed,
            });
            trajectories.push(trajectory);
        }
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation() > 0.0;
        if online {
            return (
                self.evaluate(network, run, generation, individual),
                trajectories,
            );
        }
        // As `evaluate` without online orientation: F per room, then their mean.
        let mut evaluation = Evaluation {
            fitness: 0.0,
            per_room,
        };
        self.refit(&mut evaluation);
        (evaluation, trajectories)
    }

    /// [`Experiment::evaluate_recorded`] for a population, in parallel (results in index
    /// order, independent of threads): per individual its evaluation and one trajectory per
    /// room of `run`.
    pub fn evaluate_population_recorded(
        &self,
        population: &Population,
        run: &Run,
        generation: usize,
    ) -> Vec<(Evaluation, Vec<Trajectory>)> {
        (0..population.len())
            .into_par_iter()
            .map(|i| self.evaluate_recorded(&population.network(i), run, generation, i))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::experiment::testing::{ORIENTED, experiment};

    /// The recorded evaluation is the GA's own, bit for bit (F and every term), under the
    /// paper's model, online orientation and a mission term; each room's trajectory has T + 1
    /// poses and as many executed steps as the evaluation counted.
    #[test]
    fn recorded_evaluation_equals_the_plain_one_bit_for_bit() {
        let safety = [
            "motivations.curiosity=0.6",
            "motivations.homing=0.1",
            "motivations.orientation=0.0",
            "motivations.energy=0.1",
            "motivations.care={ weight = 0.2, term = \"safety\" }",
        ];
        for extra in [&[][..], &ORIENTED[..], &safety[..]] {
            let exp = experiment(extra);
            let run = &exp.runs()[0];
            let population = exp.initial_population(run);
            let plain = exp.evaluate_population(&population, run, 1);
            let recorded = exp.evaluate_population_recorded(&population, run, 1);
            assert_eq!(plain.len(), recorded.len());
            for (p, (r, trajectories)) in plain.iter().zip(&recorded) {
                assert_eq!(p.fitness.to_bits(), r.fitness.to_bits(), "{extra:?}");
                assert_eq!(p, r, "{extra:?}");
                assert_eq!(trajectories.len(), run.rooms.len());
                for (t, s) in trajectories.iter().zip(&r.per_room) {
                    assert_eq!(t.poses.len(), exp.trial_params().steps() + 1);
                    assert_eq!(t.executed(), s.executed);
                }
            }
        }
    }
}
