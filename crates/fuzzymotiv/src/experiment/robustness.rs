//! Robustness to the reality gap (issue 37, item 3; the library's part): an evolved network
//! evaluated under the perturbations a real robot brings, on paired streams (the same seeds
//! for every perturbation), F and behaviour per trial: the paper's terms, and on a run that
//! follows missions or weighs terms of its own, those terms and whether each mission was done.
//!
//! ```
//! use fuzzymotiv::experiment::{BuiltinRoomsOnly, Perturbation, RawConfig, Setup};
//! let raw = RawConfig::parse("rooms = [\"square\", \"H\"]", "c", &["trial.steps=50".into()]).unwrap();
//! let exp = Setup::resolve(raw, "c", &BuiltinRoomsOnly).unwrap().experiment;
//! let genome = vec![0.1; 8 * 6 + 6 + 6 * 2 + 2]; // the paper's 8-6-2 network
//! let rows = exp.robustness(&genome, &[Perturbation::None, Perturbation::DeadSensor(2)], 3).unwrap();
//! assert_eq!(rows[0].f.len(), 3 * 2); // 3 trials in each of 2 rooms
//! ```

use crate::experiment::Experiment;
use crate::fitness::{FitnessTerms, TermId};
use crate::modelling::{Recognizer, SomError};
use crate::params::FieldError;
use crate::random::seed::hash_str;
use crate::simulation::controller::{GenomeError, Perturbed};
use crate::simulation::randomise::Draw;
use crate::simulation::robot::Motion;
use crate::simulation::sensor::{SensorModel, TableRef};
use crate::simulation::trial::{ActionLog, Arena};
use crate::simulation::trial_params::TrialParams;

/// One perturbation of the simulated robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Perturbation {
    /// The robot as evolved.
    None,
    /// Sensor and wheel noise level `trial.noise` (0–0.5).
    Noise(f64),
    /// Every reading of the sensor table multiplied by this factor (rounded, capped at 1023).
    TableScale(f64),
    /// Sensor `k` (0–7) reads 0.
    DeadSensor(usize),
    /// Both wheel speeds multiplied by 1 + this (e.g. ±0.1).
    WheelBias(f64),
    /// The body radius (mm) instead of the evolved one.
    Radius(f64),
}

impl Perturbation {
    /// The issue's set: noise 0–20 %, table ±30 %, each of the robot's `sensors` dead, wheel
    /// bias ±10 %, a body 10 % and 20 % larger than `radius`.
    pub fn standard(radius: f64, sensors: usize) -> Vec<Perturbation> {
        let mut all = vec![Perturbation::None];
        all.extend([0.0, 0.05, 0.1, 0.15, 0.2].map(Perturbation::Noise));
        all.extend([0.7, 0.85, 1.15, 1.3].map(Perturbation::TableScale));
        all.extend((0..sensors).map(Perturbation::DeadSensor));
        all.extend([-0.1, -0.05, 0.05, 0.1].map(Perturbation::WheelBias));
        all.extend([1.1, 1.2].map(|k| Perturbation::Radius(radius * k)));
        all
    }

    /// The standard set ([`Perturbation::standard`]) that a robot with `trial`'s parameters
    /// can take: without the `table×k` rows when its sensors are not read from a table
    /// (`sensor_model = "linear"`: [`Perturbation::applies_to`]).
    pub fn standard_for(trial: &TrialParams) -> Vec<Perturbation> {
        Perturbation::standard(trial.robot().radius(), trial.robot().sensors())
            .into_iter()
            .filter(|p| p.applies_to(trial))
            .collect()
    }

    /// Whether a robot with `trial`'s parameters can take this perturbation: every one except
    /// scaling the sensor table of a robot whose sensors have none (`sensor_model =
    /// "linear"`; scaling the built-in Khepera tables instead would change its sensors, not
    /// scale them).
    pub fn applies_to(&self, trial: &TrialParams) -> bool {
        !matches!(
            (self, trial.sensor_model()),
            (Perturbation::TableScale(_), SensorModel::Linear)
        )
    }

    /// The trial parameters `trial` under this perturbation (dead sensors and wheel bias are
    /// the controller's: unchanged here); an error for a body the robot cannot take, or for
    /// a table scale when the sensors are the `linear` model's (no table to scale).
    pub fn apply(&self, trial: TrialParams) -> Result<TrialParams, FieldError> {
        Ok(match *self {
            Perturbation::Noise(n) => trial.with_noise(n),
            Perturbation::TableScale(k) => {
                let table = match trial.sensor_model() {
                    SensorModel::Table(TableRef(t)) => t.clone(),
                    SensorModel::Sampled => trial.robot().spec().table().clone(),
                    SensorModel::Linear => {
                        return Err(FieldError::new(
                            "trial.sensor_model",
                            format!(
                                "{}: the \"linear\" sensor model has no sensor table to scale; a table scale applies to the \"sampled\" model (the robot file's tables or trial.sensor_table)",
                                self.label()
                            ),
                        ));
                    }
                };
                let max = trial.robot().spec().reading_max();
                trial.with_sensor_table(table.scaled(k, max).intern())
            }
            Perturbation::Radius(r) => {
                let b = trial.robot();
                let raw = crate::simulation::RawRobot {
                    file: None,
                    radius: Some(r),
                    wheel_base: Some(b.wheel_base()),
                    v_max: Some(b.v_max()),
                    motion: b.motion(),
                };
                trial.with_robot(crate::simulation::Robot::from_raw(&raw, b.spec())?)
            }
            Perturbation::None | Perturbation::DeadSensor(_) | Perturbation::WheelBias(_) => trial,
        })
    }

    /// What a reader of a study of `perturbations` on a robot with `trial`'s parameters should
    /// know about what they change (one sentence per family present), and the rows of the
    /// standard set left out because the robot cannot take them.
    pub fn notes(perturbations: &[Perturbation], trial: &TrialParams) -> Vec<String> {
        let has = |f: fn(&Perturbation) -> bool| perturbations.iter().any(f);
        let mut notes = Vec::new();
        if trial.sensor_model() == SensorModel::Linear
            && !has(|p| matches!(p, Perturbation::TableScale(_)))
        {
            notes.push("no table×k rows: this robot's sensors are the \"linear\" model, which has no sensor table to scale (scaling the robot file's tables instead would change its sensors, not scale them)".to_string());
        }
        if has(|p| matches!(p, Perturbation::Noise(_))) {
            notes.push("noise=n sets trial.noise, which perturbs the wheel speeds as well as the sensor readings (each multiplied by U(1 − n, 1 + n)): these rows are sensor and wheel noise together".to_string());
        }
        if has(|p| matches!(p, Perturbation::WheelBias(_))) {
            notes.push(match trial.robot().motion() {
                Motion::Actions => "wheels×k scales both motor commands' speeds alike; with `actions` motion the executed step is exact (a straight step is always v_max·dt), so the bias only moves the thresholds by which motor outputs become actions: the robot drives neither slower nor faster, and never curves".to_string(),
                Motion::Wheels => "wheels×k scales both wheel speeds alike: the robot drives slower or faster but does not curve (a left/right imbalance is not modelled)".to_string(),
            });
        }
        if has(|p| matches!(p, Perturbation::Radius(_))) {
            notes.push("radius=r enlarges the body for collisions only: the sensors stay at the robot's mount positions (the Khepera's about 25 mm from the centre), inside a larger body rather than on its edge".to_string());
        }
        notes
    }

    /// The perturbations of a randomised trial's draw ([`Draw`]), in the order noise, sensor
    /// scale, wheel bias, radius.
    pub fn of_draw(draw: &Draw) -> Vec<Perturbation> {
        let mut all = Vec::with_capacity(4);
        all.extend(draw.noise.map(Perturbation::Noise));
        all.extend(draw.sensor_scale.map(Perturbation::TableScale));
        all.extend(draw.wheel_bias.map(Perturbation::WheelBias));
        all.extend(draw.radius.map(Perturbation::Radius));
        all
    }

    /// A short name (`noise=0.1`, `dead=3`, …).
    pub fn label(&self) -> String {
        match *self {
            Perturbation::None => "none".into(),
            Perturbation::Noise(n) => format!("noise={n}"),
            Perturbation::TableScale(k) => format!("table×{k}"),
            Perturbation::DeadSensor(s) => format!("dead={s}"),
            Perturbation::WheelBias(b) => format!("wheels×{}", 1.0 + b),
            Perturbation::Radius(r) => format!("radius={r:.1}"),
        }
    }
}

/// Why a robustness study cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RobustnessError {
    /// The genome does not fit the experiment's network.
    #[error(transparent)]
    Genome(#[from] GenomeError),
    /// A perturbation the robot cannot take (e.g. a body too large for its step).
    #[error("perturbation: {0}")]
    Perturbation(#[from] FieldError),
    /// The room model cannot take a trial's actions (it was trained for another experiment).
    #[error("room model: {0}")]
    Recognition(#[from] SomError),
}

/// F and behaviour of every trial under one perturbation (trial `k` of room `r` at index
/// `r · trials + k`, on the same stream under every perturbation).
#[derive(Debug, Clone, PartialEq)]
pub struct RobustnessRow {
    /// The perturbation.
    pub perturbation: Perturbation,
    /// Each trial's F (the experiment's fuzzy fitness of its terms).
    pub f: Vec<f64>,
    /// Each trial's exploration term `a`.
    pub exploration: Vec<f64>,
    /// Each trial's homing term `g`.
    pub homing: Vec<f64>,
    /// Each trial's battery term `b`.
    pub battery: Vec<f64>,
    /// Per trial, 1 when the room model recognised its actions as its own room, else 0 (empty
    /// when no room model was given: [`Experiment::robustness_recognising`]).
    pub recognised: Vec<f64>,
    /// Per trial, 1 when its mission was done (its room's waypoints visited and its goal
    /// reached), else 0; empty when the experiment follows no mission
    /// ([`Experiment::measures_mission`]).
    pub missions_done: Vec<f64>,
    /// Each trial's value of every term the experiment measures beyond a, g, l, b
    /// ([`Experiment::robustness_terms`]): the mission terms when it follows missions, then
    /// its user-defined terms; empty for the paper's model.
    pub terms: Vec<(TermId, Vec<f64>)>,
}

impl RobustnessRow {
    /// An empty row of `p` with a column per term of `terms`.
    fn new(perturbation: Perturbation, terms: &[TermId]) -> RobustnessRow {
        RobustnessRow {
            perturbation,
            f: Vec::new(),
            exploration: Vec::new(),
            homing: Vec::new(),
            battery: Vec::new(),
            recognised: Vec::new(),
            missions_done: Vec::new(),
            terms: terms.iter().map(|&id| (id, Vec::new())).collect(),
        }
    }

    /// Adds one trial's terms, F `f` under them.
    fn push(&mut self, terms: &FitnessTerms, f: f64, mission: bool) {
        self.f.push(f);
        self.exploration.push(terms.a);
        self.homing.push(terms.g);
        self.battery.push(terms.b);
        if mission {
            let done = terms.mission.is_some_and(|m| m.done_at.is_some());
            self.missions_done.push(f64::from(u8::from(done)));
        }
        for (id, values) in &mut self.terms {
            values.push(terms.get(*id));
        }
    }
}

impl Experiment {
    /// Evaluates `genome` under each perturbation: `trials` trials per room, trial `k` on the
    /// stream `hash("robustness", seed, k, room)`, the same under every perturbation.
    pub fn robustness(
        &self,
        genome: &[f64],
        perturbations: &[Perturbation],
        trials: usize,
    ) -> Result<Vec<RobustnessRow>, RobustnessError> {
        self.robustness_recognising(genome, perturbations, trials, None)
    }

    /// [`Experiment::robustness`], and with a room model (the unperturbed robot's,
    /// [`Experiment::recognizer`]) whether each trial's actions are recognised as its room:
    /// does the robot still know where it is when its body or sensors differ?
    pub fn robustness_recognising(
        &self,
        genome: &[f64],
        perturbations: &[Perturbation],
        trials: usize,
        recognizer: Option<&Recognizer>,
    ) -> Result<Vec<RobustnessRow>, RobustnessError> {
        let net = self.network(genome)?;
        let extra = self.robustness_terms();
        let mut rows = Vec::with_capacity(perturbations.len());
        for &p in perturbations {
            let exp = self.perturbed(p)?;
            let mut row = RobustnessRow::new(p, &extra);
            for room in 0..exp.arenas.len() {
                for k in 0..trials {
                    let seed = hash_str(&format!("robustness/{}/{k}/{room}", self.seed));
                    let mut net = net.clone();
                    let mut c = Perturbed {
                        net: &mut net,
                        dead: match p {
                            Perturbation::DeadSensor(s) => Some(s),
                            _ => None,
                        },
                        bias: match p {
                            Perturbation::WheelBias(b) => b,
                            _ => 0.0,
                        },
                    };
                    let terms = match recognizer {
                        None => exp.observed_trial(&mut c, room, seed, &mut ()).0,
                        Some(rec) => {
                            let mut log = ActionLog::default();
                            let (terms, _, _) = exp.observed_trial(&mut c, room, seed, &mut log);
                            let (answer, _) = exp.recognise_actions(rec, &log.actions)?;
                            row.recognised
                                .push(f64::from(u8::from(answer == Some(room))));
                            terms
                        }
                    };
                    row.push(&terms, exp.fuzzy_fitness(&terms), self.measures_mission());
                }
            }
            rows.push(row);
        }
        Ok(rows)
    }

    /// The terms beyond a, g, l, b whose values a robustness row keeps
    /// ([`RobustnessRow::terms`]): the four mission terms when the experiment follows missions
    /// ([`Experiment::measures_mission`]), then each user-defined term; none for the paper's
    /// model.
    pub fn robustness_terms(&self) -> Vec<TermId> {
        let mission = [
            TermId::Goal,
            TermId::Urgency,
            TermId::Waypoints,
            TermId::Safety,
        ];
        let mission = mission.into_iter().filter(|_| self.measures_mission());
        mission
            .chain((0..self.user_terms().len()).map(TermId::User))
            .collect()
    }

    /// This experiment with the trial parameters `p` changes (dead sensors and wheel bias are
    /// the controller's: unchanged here).
    fn perturbed(&self, p: Perturbation) -> Result<Experiment, FieldError> {
        if matches!(
            p,
            Perturbation::None | Perturbation::DeadSensor(_) | Perturbation::WheelBias(_)
        ) {
            return Ok(self.clone());
        }
        let trial = p.apply(self.trial)?;
        let mut exp = self.clone();
        exp.arenas = (self.arenas.iter())
            .map(|a| Arena::new(a.room().clone(), &trial))
            .collect();
        exp.trial = trial;
        Ok(exp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::{BuiltinRoomsOnly, RawConfig, Setup};
    use crate::random::rng::{rng_from_seed, uniform};

    fn setup() -> (Experiment, Vec<f64>) {
        let sets = ["trial.steps=400".to_string()];
        let raw = RawConfig::parse("rooms = [\"square\", \"H\"]", "c", &sets).unwrap();
        let exp = Setup::resolve(raw, "c", &BuiltinRoomsOnly)
            .unwrap()
            .experiment;
        let mut g = rng_from_seed(3);
        let mut genome: Vec<f64> = (0..exp.shape.genome_len())
            .map(|_| uniform(&mut g, -1.0, 1.0))
            .collect();
        // Output biases (after the hidden units' [bias, 8 weights]; each output is [bias, hidden
        // weights]) that drive both wheels forward: the robot reaches the walls.
        let h = exp.shape.hidden();
        genome[9 * h] = 2.0;
        genome[9 * h + 1 + h] = 2.0;
        (exp, genome)
    }

    /// Paired streams: a perturbation that changes nothing gives the unperturbed trials exactly
    /// (the default noise 0.06, the built-in tables scaled by 1, the evolved radius).
    #[test]
    fn perturbations_that_change_nothing_give_the_same_trials() {
        let (exp, genome) = setup();
        let same = [
            Perturbation::None,
            Perturbation::Noise(0.06),
            Perturbation::TableScale(1.0),
            Perturbation::WheelBias(0.0),
            Perturbation::Radius(exp.trial.robot().radius()),
        ];
        let rows = exp.robustness(&genome, &same, 3).unwrap();
        for row in &rows[1..] {
            assert_eq!(row.f, rows[0].f, "{}", row.perturbation.label());
            assert_eq!(row.exploration, rows[0].exploration);
        }
        assert_eq!(rows[0].f.len(), 6);
        // The paper's model keeps no mission and no term beyond a, g, l, b.
        assert!(rows[0].missions_done.is_empty() && rows[0].terms.is_empty());
    }

    /// Recognising the trials' actions watches them without changing them: the same F and
    /// terms as without a room model, and one 0/1 answer per trial.
    #[test]
    fn recognising_the_trials_leaves_them_unchanged() {
        let (exp, genome) = setup();
        let net = exp.network(&genome).unwrap();
        let run = &exp.runs()[0];
        let rec = exp
            .recognizer(&net, run)
            .unwrap()
            .expect("room modelling is on");
        let all = [
            Perturbation::None,
            Perturbation::DeadSensor(2),
            Perturbation::Noise(0.2),
        ];
        let plain = exp.robustness(&genome, &all, 3).unwrap();
        let seen = exp
            .robustness_recognising(&genome, &all, 3, Some(&rec))
            .unwrap();
        for (p, s) in plain.iter().zip(&seen) {
            assert_eq!(
                (&p.f, &p.exploration, &p.battery),
                (&s.f, &s.exploration, &s.battery)
            );
            assert!(p.recognised.is_empty());
            assert_eq!(s.recognised.len(), s.f.len());
            assert!(s.recognised.iter().all(|&v| v == 0.0 || v == 1.0));
        }
    }

    /// A robot with `linear` sensors has no table to scale: the standard set leaves the
    /// `table×k` rows out (and says so), and applying one is an error rather than a swap to
    /// the scaled Khepera tables; with the `sampled` model the rows stay.
    #[test]
    fn a_linear_sensor_robot_gets_no_table_scale_rows() {
        let sets = [
            "trial.steps=60".to_string(),
            "trial.sensor_model=\"linear\"".to_string(),
        ];
        let raw = RawConfig::parse("rooms = [\"square\", \"H\"]", "c", &sets).unwrap();
        let exp = Setup::resolve(raw, "c", &BuiltinRoomsOnly)
            .unwrap()
            .experiment;
        let trial = *exp.trial_params();
        let all = Perturbation::standard_for(&trial);
        let scaled = |ps: &[Perturbation]| {
            ps.iter()
                .filter(|p| matches!(p, Perturbation::TableScale(_)))
                .count()
        };
        assert_eq!(scaled(&all), 0, "{all:?}");
        let standard = Perturbation::standard(trial.robot().radius(), 8);
        assert_eq!(all.len() + scaled(&standard), standard.len());
        let e = Perturbation::TableScale(1.3).apply(trial).unwrap_err();
        assert_eq!(e.field, "trial.sensor_model", "{e}");
        let notes = Perturbation::notes(&all, &trial);
        assert!(notes[0].starts_with("no table×k rows"), "{notes:?}");
        let (sampled, _) = setup();
        let rows = Perturbation::standard_for(sampled.trial_params());
        assert_eq!(scaled(&rows), 4);
        let notes = Perturbation::notes(&rows, sampled.trial_params());
        assert!(
            notes.iter().all(|n| !n.starts_with("no table×k")),
            "{notes:?}"
        );
        assert!(
            notes
                .iter()
                .any(|n| n.starts_with("wheels×k") && n.contains("`actions` motion")),
            "{notes:?}"
        );
        // The linear robot's own sensors, unscaled, still run under every other row.
        let genome = vec![0.1; exp.shape.genome_len()];
        let rows = exp.robustness(&genome, &all, 2).unwrap();
        assert_eq!(rows.len(), all.len());
    }

    /// A perturbation that matters changes the trials.
    #[test]
    fn blinding_the_robot_changes_its_trials() {
        let (exp, genome) = setup();
        let all: Vec<Perturbation> = (0..8).map(Perturbation::DeadSensor).collect();
        let base = exp.robustness(&genome, &[Perturbation::None], 2).unwrap();
        let rows = exp.robustness(&genome, &all, 2).unwrap();
        let changed = rows.iter().filter(|r| r.f != base[0].f).count();
        assert!(changed > 0, "{:?}", base[0].exploration);
        let noisy = exp
            .robustness(&genome, &[Perturbation::Noise(0.2)], 2)
            .unwrap();
        assert_ne!(noisy[0].exploration, base[0].exploration);
    }
}
