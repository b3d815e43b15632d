//! The facade: a validated [`Experiment`] built once from a [`RawConfig`] and its rooms, with
//! its protocol ([`Experiment::runs`]), random streams and fuzzy fitness. Evaluation
//! ([`crate::evaluation`]), evolution ([`crate::evolution`], [`Experiment::evolve`]) and room
//! modelling ([`crate::modelling`], [`Experiment::environment_modelling`]) are methods of
//! `Experiment` written beside their own types.

use serde::{Deserialize, Serialize};

use crate::aem::Encoder;
use crate::config::{Coefficients, ConfigError, EnergyMode, OrientationMode, RawConfig, Training};
use crate::controller::MlpShape;
use crate::fitness::{FitnessTerms, Homing};
use crate::fuzzy::{FuzzyError, Motivations, TskFitness};
use crate::ga::GaParams;
use crate::robot::{KHEPERA_RADIUS, Khepera};
use crate::room::Room;
use crate::seed::{Streams, hash_str};
use crate::som::SomParams;
use crate::trial::{Arena, TrialParams};

/// Validated AEM parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AemParams {
    /// Whether AEM runs after evolution.
    pub enabled: bool,
    /// Action sequence → vector encoding.
    pub encoder: Encoder,
    /// SOM training parameters.
    pub som: SomParams,
    /// r-node gate (nodes).
    pub threshold: usize,
    /// Test runs per room.
    pub test_runs: usize,
    /// Action classification tolerance.
    pub action_tolerance: f64,
}

/// A validated experiment: nothing downstream re-checks these values.
#[derive(Debug, Clone)]
pub struct Experiment {
    /// Name.
    pub name: String,
    /// Base seed.
    pub seed: u64,
    /// Rooms, prepared for trials.
    pub arenas: Vec<Arena>,
    /// Training protocol.
    pub training: Training,
    /// Motivations X.
    pub motivations: Motivations,
    /// The TSK evaluator.
    pub fuzzy: TskFitness,
    /// GA parameters.
    pub ga: GaParams,
    /// Trial parameters.
    pub trial: TrialParams,
    /// Network shape.
    pub shape: MlpShape,
    /// Battery term direction.
    pub energy: EnergyMode,
    /// When `l` is measured.
    pub orientation: OrientationMode,
    /// How `g` is measured.
    pub homing: Homing,
    /// Environment modelling.
    pub aem: AemParams,
}

fn check(ok: bool, field: &str, reason: impl FnOnce() -> String) -> Result<(), (String, String)> {
    if ok {
        Ok(())
    } else {
        Err((field.to_string(), reason()))
    }
}

fn unit(v: f64) -> bool {
    v.is_finite() && (0.0..=1.0).contains(&v)
}

impl Experiment {
    /// Validates `raw` with its rooms already loaded (`rooms[i]` for `raw.rooms[i]`).
    pub fn new(
        raw: &RawConfig,
        rooms: Vec<Room>,
        source_name: &str,
    ) -> Result<Experiment, ConfigError> {
        Self::build(raw, rooms).map_err(|(field, reason)| ConfigError {
            source_name: source_name.to_string(),
            field,
            reason,
        })
    }

    fn build(raw: &RawConfig, rooms: Vec<Room>) -> Result<Experiment, (String, String)> {
        const BIG: usize = 1_000_000;
        let safe_name = !raw.name.is_empty()
            && raw.name.len() <= 100
            && raw.name != "."
            && raw.name != ".."
            && raw
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "._-".contains(c));
        check(safe_name, "name", || {
            format!(
                "must be a plain name of letters, digits, '.', '_' or '-' (it names the output directory runs/NAME), got {:?}",
                raw.name
            )
        })?;
        check(!rooms.is_empty(), "rooms", || {
            "needs at least one room, e.g. rooms = [\"H\", \"T\", \"L\", \"square\", \"rectangle\"]"
                .into()
        })?;
        for (i, r) in rooms.iter().enumerate() {
            if let Some(j) = rooms[..i].iter().position(|o| o.name == r.name) {
                return Err((
                    format!("rooms[{i}]"),
                    format!(
                        "room name \"{}\" is used twice (also rooms[{j}]); names must be unique",
                        r.name
                    ),
                ));
            }
        }
        let m = &raw.motivations;
        let motivations = Motivations::new(m.curiosity, m.homing, m.orientation, m.energy)
            .map_err(|e| {
                let field = match &e {
                    FuzzyError::MotivationOutOfRange { name, .. } => format!("motivations.{name}"),
                    _ => "motivations".to_string(),
                };
                (field, e.to_string())
            })?;
        let ga = raw.ga;
        check((2..=BIG).contains(&ga.population), "ga.population", || {
            format!("must be an integer in 2..={BIG}, got {}", ga.population)
        })?;
        check(
            (1..=BIG).contains(&ga.generations),
            "ga.generations",
            || format!("must be an integer in 1..={BIG}, got {}", ga.generations),
        )?;
        check(ga.elite < ga.population, "ga.elite", || {
            format!(
                "must be smaller than ga.population ({}), got {}",
                ga.population, ga.elite
            )
        })?;
        check(
            ga.parent_fraction.is_finite() && ga.parent_fraction > 0.0 && ga.parent_fraction <= 1.0,
            "ga.parent_fraction",
            || format!("must be in (0, 1], got {}", ga.parent_fraction),
        )?;
        check(unit(ga.crossover), "ga.crossover", || {
            format!("must be a probability in [0, 1], got {}", ga.crossover)
        })?;
        check(unit(ga.mutation_rate), "ga.mutation_rate", || {
            format!("must be a probability in [0, 1], got {}", ga.mutation_rate)
        })?;
        check(
            ga.mutation_sigma.is_finite() && ga.mutation_sigma >= 0.0,
            "ga.mutation_sigma",
            || format!("must be a finite number ≥ 0, got {}", ga.mutation_sigma),
        )?;
        check(
            ga.weight_limit.is_finite() && ga.weight_limit > 0.0 && ga.weight_limit <= 1e6,
            "ga.weight_limit",
            || format!("must be in (0, 1e6], got {}", ga.weight_limit),
        )?;
        check(
            ga.init_range.is_finite() && ga.init_range >= 0.0 && ga.init_range <= ga.weight_limit,
            "ga.init_range",
            || format!("must be in [0, ga.weight_limit], got {}", ga.init_range),
        )?;
        let t = &raw.trial;
        check((1..=10 * BIG).contains(&t.steps), "trial.steps", || {
            format!("must be an integer in 1..={}, got {}", 10 * BIG, t.steps)
        })?;
        check(
            t.dt.is_finite() && t.dt > 0.0 && t.dt <= 10.0,
            "trial.dt",
            || format!("must be a time step in (0, 10] seconds, got {}", t.dt),
        )?;
        check(
            t.noise.is_finite() && (0.0..=0.5).contains(&t.noise),
            "trial.noise",
            || {
                format!(
                    "must be a noise level in [0, 0.5] (0.06 is the paper's 6 %), got {}",
                    t.noise
                )
            },
        )?;
        let robot: Khepera = raw.robot;
        check(
            robot.v_max.is_finite() && robot.v_max > 0.0,
            "robot.v_max",
            || format!("must be a speed > 0 (mm/s), got {}", robot.v_max),
        )?;
        // The sensor mounts are fixed (docs/model.md §3): they must sit inside the body, and a body far
        // larger than the sensors' reach would be blind.
        let mounts = crate::sensor::SENSOR_LAYOUT
            .iter()
            .map(|m| m.x.hypot(m.y))
            .fold(0.0, f64::max);
        check(
            robot.radius.is_finite() && robot.radius >= mounts && robot.radius <= 80.0,
            "robot.radius",
            || {
                format!(
                    "must be in [{mounts:.2}, 80] mm (the IR sensors sit {mounts:.2} mm from the centre and see 58 mm), got {}",
                    robot.radius
                )
            },
        )?;
        check(
            robot.wheel_base.is_finite() && robot.wheel_base > 0.0 && robot.wheel_base <= 1000.0,
            "robot.wheel_base",
            || format!("must be in (0, 1000] mm, got {}", robot.wheel_base),
        )?;
        let trial = TrialParams {
            steps: t.steps,
            dt: t.dt,
            noise: t.noise,
            sensor_model: t.sensor_model,
            robot,
            end_at_home: t.end_at_home,
            action_tolerance: raw.aem.action_tolerance,
        };
        check(trial.max_step() < robot.radius, "trial.dt", || {
            format!(
                "one step may move the robot {:.1} mm (robot.v_max × trial.dt × (1 + trial.noise)), which must stay below the body radius {} mm so it cannot pass through walls; use a smaller dt or v_max",
                trial.max_step(),
                robot.radius
            )
        })?;
        check(
            (1..=1024).contains(&raw.network.hidden),
            "network.hidden",
            || format!("must be in 1..=1024, got {}", raw.network.hidden),
        )?;
        let shape = MlpShape::with_hidden(raw.network.hidden);
        let fuzzy = match &raw.fuzzy.coefficients {
            Coefficients::Scheme(s) => TskFitness::with_scheme(raw.fuzzy.peaks.clone(), *s),
            Coefficients::Values(v) => TskFitness::new(raw.fuzzy.peaks.clone(), v.clone()),
        }
        .map_err(|e| {
            let field = match e {
                FuzzyError::CoefficientCount { .. } | FuzzyError::InvalidCoefficient { .. } => {
                    "fuzzy.coefficients"
                }
                _ => "fuzzy.peaks",
            };
            (field.to_string(), e.to_string())
        })?;
        let a = &raw.aem;
        let som = SomParams {
            nodes: a.som_nodes,
            epochs: a.epochs,
            sigma_start: a.sigma_start,
            sigma_end: a.sigma_end,
            rate_start: a.rate_start,
            rate_end: a.rate_end,
        };
        check(
            (1..=100_000).contains(&a.som_nodes),
            "aem.som_nodes",
            || format!("must be in 1..=100000, got {}", a.som_nodes),
        )?;
        check((1..=BIG).contains(&a.epochs), "aem.epochs", || {
            format!("must be in 1..={BIG}, got {}", a.epochs)
        })?;
        check(
            (1..=100_000).contains(&a.test_runs),
            "aem.test_runs",
            || format!("must be in 1..=100000, got {}", a.test_runs),
        )?;
        check(
            a.action_tolerance.is_finite() && (0.0..=2.0).contains(&a.action_tolerance),
            "aem.action_tolerance",
            || {
                format!(
                    "must be in [0, 2] (signed-speed units), got {}",
                    a.action_tolerance
                )
            },
        )?;
        for (name, v) in [
            ("aem.sigma_start", a.sigma_start),
            ("aem.sigma_end", a.sigma_end),
            ("aem.rate_start", a.rate_start),
            ("aem.rate_end", a.rate_end),
        ] {
            check(v.is_finite() && v > 0.0, name, || {
                format!("must be a finite number > 0, got {v}")
            })?;
        }
        check(
            !a.enabled || t.steps.saturating_mul(a.som_nodes) <= 50_000_000,
            "aem.som_nodes",
            || {
                format!(
                    "the SOM would hold aem.som_nodes × trial.steps = {} × {} weights; keep the product ≤ 5e7",
                    a.som_nodes, t.steps
                )
            },
        )?;
        check(!a.enabled || rooms.len() >= 2, "aem.enabled", || {
            format!(
                "room recognition needs at least 2 rooms, got {}; add rooms or set aem.enabled = false",
                rooms.len()
            )
        })?;
        let online = raw.fitness.orientation == OrientationMode::Online;
        check(
            !online || (rooms.len() >= 2 && raw.training == Training::AllRooms),
            "fitness.orientation",
            || "\"online\" needs training = \"all-rooms\" with at least 2 rooms".into(),
        )?;
        // Room files are validated against the Khepera; a bigger body needs its own check.
        if robot.radius > KHEPERA_RADIUS {
            for (i, r) in rooms.iter().enumerate() {
                let home = r.home.position();
                let clearance = r
                    .walls()
                    .iter()
                    .map(|w| w.dist_to(home))
                    .fold(f64::INFINITY, f64::min);
                check(clearance >= robot.radius, &format!("rooms[{i}]"), || {
                    format!(
                        "home of room \"{}\" is {clearance:.1} mm from a wall, closer than robot.radius {}",
                        r.name, robot.radius
                    )
                })?;
            }
        }
        let arenas = rooms.into_iter().map(|r| Arena::new(r, &trial)).collect();
        Ok(Experiment {
            name: raw.name.clone(),
            seed: raw.seed,
            arenas,
            training: raw.training,
            motivations,
            fuzzy,
            ga,
            trial,
            shape,
            energy: raw.fitness.energy,
            orientation: raw.fitness.orientation,
            homing: raw.fitness.homing,
            aem: AemParams {
                enabled: a.enabled,
                encoder: a.encoder,
                som,
                threshold: a.threshold,
                test_runs: a.test_runs,
                action_tolerance: a.action_tolerance,
            },
        })
    }

    /// Room names, in order.
    pub fn room_names(&self) -> Vec<String> {
        self.arenas.iter().map(|a| a.room().name.clone()).collect()
    }

    /// The evolutions the protocol asks for: one over all rooms, or one per room.
    pub fn runs(&self) -> Vec<Run> {
        match self.training {
            Training::AllRooms => vec![Run {
                label: "all".into(),
                tag: 0,
                rooms: (0..self.arenas.len()).collect(),
            }],
            Training::PerRoom => self
                .arenas
                .iter()
                .enumerate()
                .map(|(i, a)| Run {
                    label: a.room().name.clone(),
                    tag: hash_str(&a.room().name),
                    rooms: vec![i],
                })
                .collect(),
        }
    }

    /// The stream key of room `room` (the hash of its name).
    pub(crate) fn room_key(&self, room: usize) -> u64 {
        hash_str(&self.arenas[room].room().name)
    }

    /// The random streams of this experiment (docs/model.md §11).
    pub fn streams(&self) -> Streams {
        Streams::new(self.seed)
    }

    /// F for fitness terms under this experiment's motivations (battery direction applied).
    pub fn fuzzy_fitness(&self, terms: &FitnessTerms) -> f64 {
        self.fuzzy
            .evaluate(&self.motivations, self.fuzzy_inputs(terms))
    }

    /// The fuzzy inputs Y for fitness terms (with `energy = "conserve"`, Y₄ = 1 − b).
    pub fn fuzzy_inputs(&self, terms: &FitnessTerms) -> [f64; 4] {
        let b = match self.energy {
            EnergyMode::Use => terms.b,
            EnergyMode::Conserve => 1.0 - terms.b,
        };
        [terms.a, terms.g, terms.l, b]
    }
}

/// One evolution: its label (`all` or a room name), its stream tag and its rooms.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Run {
    /// `all` for all-rooms training, else the room name.
    pub label: String,
    /// Seed-derivation tag (0 for all-rooms, the room name's hash for per-room).
    pub tag: u64,
    /// Indices of the rooms each individual is evaluated in.
    pub rooms: Vec<usize>,
}

#[cfg(test)]
pub(crate) mod testing {
    use super::*;
    use crate::room::BUILTIN_ROOMS;

    pub(crate) fn experiment(extra: &[&str]) -> Experiment {
        let mut sets: Vec<String> = [
            "ga.population=8",
            "ga.generations=3",
            "trial.steps=120",
            "aem.epochs=10",
            "aem.test_runs=2",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        sets.extend(extra.iter().map(|s| s.to_string()));
        let raw = RawConfig::parse("", "test", &sets).unwrap();
        let rooms = BUILTIN_ROOMS
            .iter()
            .map(|r| Room::builtin(r).unwrap())
            .collect();
        Experiment::new(&raw, rooms, "test").unwrap()
    }

    pub(crate) const ORIENTED: [&str; 5] = [
        "fitness.orientation=\"online\"",
        "motivations.curiosity=0.4",
        "motivations.homing=0.2",
        "motivations.orientation=0.3",
        "motivations.energy=0.1",
    ];
}
