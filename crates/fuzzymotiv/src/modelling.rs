//! Room modelling (action-based environment modelling, docs/model.md §9–§10): the best robot's
//! instance run per room trains a SOM, then test runs are recognised against it.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::aem::environment_vector;
use crate::experiment::{Experiment, Run};
use crate::fitness::FitnessTerms;
use crate::recognition::{Confusion, Recognizer};
use crate::rng::rng_from_seed;
use crate::som::SomError;

impl Experiment {
    /// The full trajectory of `genome` in `room` on the AEM instance stream of `run` (the very
    /// run whose actions became the room's stored instance): for figures and replays.
    pub fn instance_trajectory(
        &self,
        genome: &[f64],
        run: &Run,
        room: usize,
    ) -> crate::trial::Trajectory {
        let seed = self.streams().aem_instance(run.tag, self.room_key(room));
        let mut rng = rng_from_seed(seed);
        crate::trial::run_trial(
            &self.arenas[room],
            &mut self.controller(genome),
            &self.trial,
            &mut rng,
        )
    }

    /// Action-based environment modelling with one robot: an instance run per room, SOM
    /// training, then `test_runs` recognition tests per room (docs/model.md §9–§10). With AEM disabled
    /// the test runs still measure exploration, homing and battery, and nothing is recognised.
    pub fn environment_modelling(&self, genome: &[f64], run: &Run) -> Result<AemReport, SomError> {
        let rooms = self.arenas.len();
        let recognizer = if self.aem.enabled {
            let vectors: Vec<Vec<f64>> = (0..rooms)
                .into_par_iter()
                .map(|r| {
                    let seed = self.streams().aem_instance(run.tag, self.room_key(r));
                    environment_vector(&self.trial(genome, r, seed).1, self.aem.encoder)
                })
                .collect();
            let mut som_rng = rng_from_seed(self.streams().som(run.tag));
            Some(Recognizer::train(
                &vectors,
                &self.aem.som,
                self.aem.threshold,
                &mut som_rng,
            )?)
        } else {
            None
        };
        let tests: Vec<(usize, AemTest)> = (0..rooms)
            .flat_map(|r| (0..self.aem.test_runs).map(move |t| (r, t)))
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|(r, t)| {
                let seed = self.streams().aem_test(run.tag, self.room_key(r), t);
                let (terms, actions) = self.trial(genome, r, seed);
                let (answer, winner) = match &recognizer {
                    Some(rec) => {
                        let v = environment_vector(&actions, self.aem.encoder);
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
            .collect::<Result<_, SomError>>()?;
        let mut confusion = Confusion::new(rooms);
        let mut per_room: Vec<AemRoom> = (0..rooms)
            .map(|r| AemRoom {
                room: self.arenas[r].room().name.clone(),
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

/// AEM results for one room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemRoom {
    /// Room name.
    pub room: String,
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
