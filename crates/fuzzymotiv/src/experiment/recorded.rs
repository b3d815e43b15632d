//! Terms of one's own, for the fronts: a config resolved with user-defined terms
//! ([`Setup::resolve_with_terms`]), and evaluation with the evaluation trials recorded, for a
//! front that computes its terms from whole trajectories (Python's batched user terms) and then
//! fills them in ([`Experiment::refit`]). The GA's own evaluation
//! ([`Experiment::evaluate_population`]) never records them.

use rayon::prelude::*;

use crate::evolution::population::Population;
use crate::experiment::config::{OrientationMode, RawConfig};
use crate::experiment::evaluation::{Evaluation, LANE_BATCH, RoomScore};
use crate::experiment::setup::{RoomFiles, Setup, SetupError};
use crate::experiment::terms::UserTerm;
use crate::experiment::{Experiment, Run};
use crate::fitness::RawMotivations;
use crate::simulation::controller::Mlp;
use crate::simulation::trial::Trajectory;

impl Setup {
    /// [`Setup::resolve`], with user-defined terms a motivation's `term` can name (the same
    /// rooms, checks, normalisation and errors; a motivation naming none of the library's
    /// terms nor of `user` is an error naming it).
    pub fn resolve_with_terms(
        raw: RawConfig,
        source_name: &str,
        files: &dyn RoomFiles,
        user: &[UserTerm],
    ) -> Result<Setup, SetupError> {
        if user.is_empty() {
            return Setup::resolve(raw, source_name, files);
        }
        // The rooms and every check that does not involve the motivations, as `resolve` does
        // them, with the paper's motivations standing in; then the config's own, with `user`.
        let mut stand_in = raw.clone();
        stand_in.motivations = RawMotivations::default();
        stand_in.fitness.end_at_mission = false;
        let rooms = Setup::resolve(stand_in, source_name, files)?;
        let mut resolved = rooms.raw;
        resolved.motivations = raw.motivations;
        resolved.fitness.end_at_mission = raw.fitness.end_at_mission;
        let shared = resolved.fuzzy.validated().ok();
        let notes = shared
            .and_then(|shared| resolved.motivations.normalise(&shared))
            .map(|sum| format!("{source_name}: motivations summed to {sum}, normalised to 1"))
            .into_iter()
            .collect();
        let arenas = rooms.experiment.arenas();
        let rooms = arenas.iter().map(|a| a.room().clone()).collect();
        let experiment = Experiment::with_terms(&resolved, rooms, user, source_name)?;
        Ok(Setup {
            raw: resolved,
            experiment,
            notes,
        })
    }
}

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
    /// room of `run`. The trials of a batch of individuals run four at a time in the lock-step
    /// lanes when their networks fit them, as [`Experiment::evaluate_population`]'s do; that
    /// changes no result.
    pub fn evaluate_population_recorded(
        &self,
        population: &Population,
        run: &Run,
        generation: usize,
    ) -> Vec<(Evaluation, Vec<Trajectory>)> {
        let networks: Vec<Mlp> = population
            .par_iter()
            .map(|g| Mlp::of_checked(population.shape(), g))
            .collect();
        let batches: Vec<&[Mlp]> = networks.chunks(LANE_BATCH).collect();
        batches
            .into_par_iter()
            .enumerate()
            .flat_map_iter(|(b, nets)| self.recorded_batch(nets, b * LANE_BATCH, run, generation))
            .collect()
    }

    /// [`Experiment::evaluate_recorded`] of the individuals `first..` whose networks are
    /// `nets`: their trials in the lanes ([`Experiment::recorded_in_lanes`]) when they fit,
    /// else one individual at a time. With online orientation the evaluations are the lanes'
    /// own ([`Experiment::evaluate_batch`], as `evaluate_recorded` takes `evaluate`'s).
    fn recorded_batch(
        &self,
        nets: &[Mlp],
        first: usize,
        run: &Run,
        generation: usize,
    ) -> Vec<(Evaluation, Vec<Trajectory>)> {
        let Some(recorded) = self.recorded_in_lanes(nets, first, run, generation) else {
            return (nets.iter().enumerate())
                .map(|(i, n)| self.evaluate_recorded(n, run, generation, first + i))
                .collect();
        };
        let online =
            self.orientation == OrientationMode::Online && self.motivations.orientation() > 0.0;
        let mut online_evaluations = match online {
            true => self
                .evaluate_batch(nets, first, run, generation)
                .into_iter(),
            false => Vec::new().into_iter(),
        };
        (recorded.into_iter())
            .map(|rooms| {
                let (mut per_room, mut trajectories) = (Vec::new(), Vec::new());
                for (terms, trajectory, executed) in rooms {
                    per_room.push(RoomScore {
                        f: 0.0,
                        terms,
                        executed,
                    });
                    trajectories.push(trajectory);
                }
                let mut evaluation = Evaluation {
                    fitness: 0.0,
                    per_room,
                };
                match online_evaluations.next() {
                    Some(e) => evaluation = e,
                    None => self.refit(&mut evaluation),
                }
                (evaluation, trajectories)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::BuiltinRoomsOnly;
    use crate::experiment::testing::{ORIENTED, experiment};

    /// A motivation may weigh a term the front supplies once it is registered; without it the
    /// config is refused naming the motivation, and weights are normalised as `resolve` does.
    #[test]
    fn a_supplied_term_resolves_only_when_registered() {
        let text = "rooms = [\"H\", \"T\"]\n[motivations]\ncuriosity = 0.3\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\nsmooth = { weight = 0.5004, term = \"smoothness\" }\n";
        let raw = RawConfig::parse(text, "c.toml", &[]).unwrap();
        let user = [UserTerm::supplied("smoothness")];
        let setup =
            Setup::resolve_with_terms(raw.clone(), "c.toml", &BuiltinRoomsOnly, &user).unwrap();
        assert_eq!(setup.experiment.motivations().len(), 5);
        assert_eq!(setup.experiment.room_names(), ["H", "T"]);
        assert_eq!(setup.experiment.user_terms().len(), 1);
        assert_eq!(setup.notes.len(), 1, "{:?}", setup.notes);
        let sum: f64 = setup.experiment.motivations().weights().iter().sum();
        assert!((sum - 1.0).abs() < 1e-12, "{sum}");
        let Err(SetupError::Field(e)) =
            Setup::resolve_with_terms(raw, "c.toml", &BuiltinRoomsOnly, &[])
        else {
            panic!("an unregistered term resolved");
        };
        assert_eq!(e.field, "motivations.smooth", "{e}");
    }

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

    /// A population's recorded evaluation, its trials in the lanes, is each individual's
    /// recorded alone (`evaluate_recorded`), evaluation and trajectories bit for bit: the
    /// paper's robot, `wheels` motion, the e-puck2, online orientation, another hidden size,
    /// and `[trial.randomise]` (which a recorded trial does not draw).
    #[test]
    fn recorded_population_in_the_lanes_equals_each_alone() {
        let cases: [&[&str]; 6] = [
            &[],
            &["robot.motion=\"wheels\""],
            &["robot.file=\"epuck2\"", "robot.motion=\"wheels\""],
            &ORIENTED,
            &["network.hidden=3"],
            &[
                "trial.randomise.noise=[0.0, 0.2]",
                "trial.randomise.wheel_bias=[-0.1, 0.1]",
            ],
        ];
        for extra in cases {
            let mut sets = vec!["ga.population=23", "trial.steps=150"];
            sets.extend(extra);
            let exp = experiment(&sets);
            let run = &exp.runs()[0];
            let population = exp.initial_population(run);
            let lanes = exp.evaluate_population_recorded(&population, run, 4);
            let alone: Vec<_> = (0..population.len())
                .map(|i| exp.evaluate_recorded(&population.network(i), run, 4, i))
                .collect();
            assert_eq!(format!("{lanes:?}"), format!("{alone:?}"), "{extra:?}");
        }
    }
}
