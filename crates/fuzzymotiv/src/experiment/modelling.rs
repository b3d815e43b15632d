//! Room modelling (action-based environment modelling, docs/model.md §9–§10): the best robot's
//! instance run per room trains a SOM, then test runs are recognised against it.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::experiment::{Experiment, Run};
use crate::fitness::terms::{FitnessTerms, largest_distance};
use crate::modelling::aem::{Action, environment_vector};
use crate::modelling::recognition::{Confusion, Explanation, Recognizer};
use crate::modelling::som::SomError;
use crate::random::rng::rng_from_seed;
use crate::simulation::controller::Mlp;
use crate::simulation::robot::Pose;
use crate::simulation::trial::Trajectory;

impl Experiment {
    /// The room-modelling run of `network` in `room` on the AEM instance stream of `run` (the
    /// very run whose actions become the room's stored instance): its whole trajectory, its
    /// terms and F. Replays and figures use it; [`Experiment::environment_modelling`] returns
    /// the ones it ran.
    pub fn instance_run(&self, network: &Mlp, run: &Run, room: usize) -> InstanceRun {
        let arena = &self.arenas[room];
        let seed = self.streams().aem_instance(run.tag, self.room_key(room));
        // Through the evaluation's own trial, so the mission and user terms are measured too.
        let mut trajectory = Trajectory::starting_at(arena.room().home, self.trial.steps());
        let (terms, _, _) = self.observed_trial(&mut network.clone(), room, seed, &mut trajectory);
        InstanceRun {
            trajectory,
            f: self.fuzzy_fitness(&terms),
            terms,
        }
    }

    /// Where `network`'s test runs in `room` end (the streams of the recognition tests of
    /// [`Experiment::environment_modelling`], so the very trials its table measures).
    pub fn test_run_ends(&self, network: &Mlp, run: &Run, room: usize) -> Vec<Pose> {
        (0..self.aem.test_runs())
            .map(|t| {
                let seed = self.streams().aem_test(run.tag, self.room_key(room), t);
                self.observed_trial(&mut network.clone(), room, seed, &mut ())
                    .2
            })
            .collect()
    }

    /// How far apart `network`'s test runs in `room` end: the root-mean-square distance of
    /// their final positions from their centroid, in % of the room's largest distance (0: they
    /// all end at one point).
    pub fn end_spread(&self, network: &Mlp, run: &Run, room: usize) -> f64 {
        let ends = self.test_run_ends(network, run, room);
        let n = ends.len().max(1) as f64;
        let (cx, cy) = ends.iter().fold((0.0, 0.0), |(x, y), p| (x + p.x, y + p.y));
        let (cx, cy) = (cx / n, cy / n);
        let ms = ends
            .iter()
            .map(|p| (p.x - cx).powi(2) + (p.y - cy).powi(2))
            .sum::<f64>()
            / n;
        100.0 * ms.sqrt() / largest_distance(self.arenas[room].room())
    }

    /// The SOM and room instances trained on `instances` (one per room) on the SOM stream of
    /// `run`; none with AEM disabled. [`Experiment::environment_modelling`] trains it so.
    fn train_recognizer(
        &self,
        instances: &[InstanceRun],
        run: &Run,
    ) -> Result<Option<Recognizer>, SomError> {
        if !self.aem.enabled() {
            return Ok(None);
        }
        let vectors: Vec<Vec<f64>> = instances
            .iter()
            .map(|i| environment_vector(&i.trajectory.actions, self.aem.encoder()))
            .collect();
        let mut som_rng = rng_from_seed(self.streams().som(run.tag));
        Recognizer::train(&vectors, self.aem.som(), self.aem.threshold(), &mut som_rng).map(Some)
    }

    /// The recogniser `network` gets in `run`'s room modelling: its instance runs, then the SOM
    /// trained on them — the same one [`Experiment::environment_modelling`] tests (the same
    /// streams, so the same bits). None with AEM disabled.
    pub fn recognizer(&self, network: &Mlp, run: &Run) -> Result<Option<Recognizer>, SomError> {
        let instances: Vec<InstanceRun> = (0..self.arenas.len())
            .into_par_iter()
            .map(|r| self.instance_run(network, run, r))
            .collect();
        self.train_recognizer(&instances, run)
    }

    /// Recognises the room of an action sequence of any length (e.g. a real robot's log): its
    /// first `trial.steps` actions, a shorter one padded with `Straight` as the simulator
    /// labels the idle steps after a trial ended at home; encoded as the room modelling does.
    /// Returns the room (none: not recognised) and the SOM's winning node.
    pub fn recognise_actions(
        &self,
        recognizer: &Recognizer,
        actions: &[Action],
    ) -> Result<(Option<usize>, usize), SomError> {
        let v = self.log_vector(actions);
        Ok((recognizer.recognise(&v)?, recognizer.som.winner(&v)?))
    }

    /// [`Experiment::recognise_actions`] with its reasons ([`Recognizer::explain`]): the SOM's
    /// winner, the gate's width and, when a room is recognised, its r-node, their distance in
    /// nodes and the distance of the sequence's vector to the room's stored vector.
    pub fn explain_actions(
        &self,
        recognizer: &Recognizer,
        actions: &[Action],
    ) -> Result<Explanation, SomError> {
        recognizer.explain(&self.log_vector(actions))
    }

    /// The environment vector of an action sequence's first `trial.steps` actions, padded with
    /// `Straight` (see [`Experiment::recognise_actions`]).
    fn log_vector(&self, actions: &[Action]) -> Vec<f64> {
        let steps = self.trial.steps();
        let mut padded: Vec<Action> = actions.iter().copied().take(steps).collect();
        padded.resize(steps, Action::Straight);
        environment_vector(&padded, self.aem.encoder())
    }

    /// Action-based environment modelling with one robot (its network): an instance run per room, SOM
    /// training, then `test_runs` recognition tests per room (docs/model.md §9–§10). With AEM disabled
    /// the instance runs are still made (for figures) and the test runs still measure
    /// exploration, homing and battery, but nothing is recognised.
    pub fn environment_modelling(&self, network: &Mlp, run: &Run) -> Result<AemReport, SomError> {
        let rooms = self.arenas.len();
        let instances: Vec<InstanceRun> = (0..rooms)
            .into_par_iter()
            .map(|r| self.instance_run(network, run, r))
            .collect();
        let recognizer = self.train_recognizer(&instances, run)?;
        let tests = self.recognition_tests(network, run, recognizer.as_ref())?;
        let mut confusion = Confusion::new(rooms);
        let mut per_room: Vec<AemRoom> = instances
            .into_iter()
            .enumerate()
            .map(|(r, instance)| AemRoom {
                room: self.arenas[r].room().name.clone(),
                instance,
                r_node: recognizer.as_ref().map(|rec| rec.instances[r].r_node),
                tests: Vec::new(),
                correct: 0,
                recognition_pct: None,
                exploration_pct: 0.0,
                battery_pct: 0.0,
                homing_pct: 0.0,
            })
            .collect();
        for (r, test) in tests {
            confusion.record(r, test.answer);
            per_room[r].tests.push(test);
        }
        for (r, row) in per_room.iter_mut().enumerate() {
            let n = row.tests.len() as f64;
            row.correct = confusion.correct(r) as usize;
            row.recognition_pct = recognizer.is_some().then(|| confusion.percent(r));
            row.exploration_pct = row.tests.iter().map(|t| 100.0 * t.terms.a).sum::<f64>() / n;
            row.battery_pct = row.tests.iter().map(|t| 100.0 * t.terms.b).sum::<f64>() / n;
            row.homing_pct = row.tests.iter().map(|t| 100.0 * t.terms.g).sum::<f64>() / n;
        }
        Ok(AemReport {
            rooms: per_room,
            confusion,
            som_nodes: recognizer.as_ref().map_or(0, |rec| rec.som.nodes()),
        })
    }

    /// `test_runs` test runs per room of `network` on the AEM test streams of `run`, each with
    /// its terms and (when a recognizer is given) its answer and SOM winner: (room, test).
    fn recognition_tests(
        &self,
        network: &Mlp,
        run: &Run,
        recognizer: Option<&Recognizer>,
    ) -> Result<Vec<(usize, AemTest)>, SomError> {
        (0..self.arenas.len())
            .flat_map(|r| (0..self.aem.test_runs()).map(move |t| (r, t)))
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|(r, t)| {
                let seed = self.streams().aem_test(run.tag, self.room_key(r), t);
                let (terms, actions) = self.trial(network, r, seed);
                let (answer, winner) = match recognizer {
                    Some(rec) => {
                        let v = environment_vector(&actions, self.aem.encoder());
                        (rec.recognise(&v)?, Some(rec.som.winner(&v)?))
                    }
                    None => (None, None),
                };
                Ok((
                    r,
                    AemTest {
                        terms,
                        answer,
                        winner,
                    },
                ))
            })
            .collect()
    }
}

/// One AEM test run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AemTest {
    /// Terms measured in the test run.
    pub terms: FitnessTerms,
    /// The recognised room, if any.
    pub answer: Option<usize>,
    /// The SOM winner of the test vector (none with AEM disabled).
    pub winner: Option<usize>,
}

/// The room-modelling run of one robot in one room (see [`Experiment::instance_run`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InstanceRun {
    /// The whole trial, step by step.
    pub trajectory: Trajectory,
    /// Its terms (`l` = 0).
    pub terms: FitnessTerms,
    /// Its F under the experiment's motivations.
    pub f: f64,
}

/// AEM results for one room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemRoom {
    /// Room name.
    pub room: String,
    /// The robot's room-modelling run here: its actions are the room's stored instance.
    pub instance: InstanceRun,
    /// The instance's r-node (none with AEM disabled).
    pub r_node: Option<usize>,
    /// The test runs.
    pub tests: Vec<AemTest>,
    /// Correct recognitions.
    pub correct: usize,
    /// % recognition (none with AEM disabled).
    pub recognition_pct: Option<f64>,
    /// Mean 100·a over the tests.
    pub exploration_pct: f64,
    /// Mean 100·b over the tests.
    pub battery_pct: f64,
    /// Mean 100·g over the tests.
    pub homing_pct: f64,
}

/// The AEM outcome for one robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemReport {
    /// Per room.
    pub rooms: Vec<AemRoom>,
    /// Truth × answer counts.
    pub confusion: Confusion,
    /// Number of SOM nodes.
    pub som_nodes: usize,
}

#[cfg(test)]
mod tests {
    use crate::experiment::testing::experiment;
    use crate::fitness::terms::FitnessTerms;

    /// The room-modelling runs environment modelling returns are the instance runs (the ones
    /// whose actions became the stored instances), with the terms their trajectories measure.
    #[test]
    fn modelling_returns_its_instance_runs() {
        let exp = experiment(&[]);
        let run = exp.runs().remove(0);
        let genome = exp.initial_population(&run).network(0);
        let report = exp.environment_modelling(&genome, &run).unwrap();
        for (r, room) in report.rooms.iter().enumerate() {
            let again = exp.instance_run(&genome, &run, r);
            assert_eq!(room.instance, again);
            let (terms, actions) = exp.trial(
                &genome,
                r,
                exp.streams().aem_instance(run.tag, exp.room_key(r)),
            );
            assert_eq!(room.instance.terms, terms);
            assert_eq!(room.instance.trajectory.actions, actions);
            let measured =
                FitnessTerms::measure(&exp.arenas()[r], exp.homing(), &room.instance.trajectory);
            assert_eq!(room.instance.terms, measured);
            assert_eq!(room.instance.f, exp.fuzzy_fitness(&terms));
        }
    }
}
