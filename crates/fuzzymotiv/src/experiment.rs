//! The facade: a validated [`Experiment`] built once from a [`RawConfig`] and its rooms, with
//! its protocol ([`Experiment::runs`]), random streams and fuzzy fitness. Evaluation
//! ([`Evaluation`]), evolution ([`Evolution`], [`Experiment::evolve`]) and room
//! modelling ([`AemReport`], [`Experiment::environment_modelling`]) are methods of
//! `Experiment` written beside their own types.

pub(crate) mod config;
pub(crate) mod descriptors;
pub(crate) mod episodes;
pub(crate) mod evaluation;
pub(crate) mod evolution;
pub(crate) mod logged;
pub(crate) mod modelling;
pub(crate) mod outcome;
pub(crate) mod recorded;
pub(crate) mod robustness;
pub(crate) mod setup;
pub(crate) mod terms;

/// The sections of a config as written, each checked into its subsystem's parameters.
pub use config::{
    Coefficients, RawAem, RawFitness, RawFuzzy, RawGa, RawMotivations, RawNetwork, RawRobot,
    RawTrial,
};
pub use config::{
    Combination, EnergyMode, MAX_SEED, OrientationMode, RawConfig, Training, apply_sets, at_line,
    blame_set,
};
pub use descriptors::Descriptors;
pub use evaluation::{Evaluation, RoomScore, TermError};
pub use evolution::{
    Evolution, EvolveError, GenerationRecord, GenerationState, Observer, Population, Stopped,
};
pub use logged::{LoggedStep, LoggedTrial};
pub use modelling::{AemReport, AemRoom, AemTest, InstanceRun};
pub use outcome::{Outcome, RunError, Start};
pub use robustness::{Perturbation, RobustnessError, RobustnessRow};
pub use setup::{
    BuiltinRoomsOnly, RoomFile, RoomFiles, Setup, SetupError, UnreadableFile, parse_room_file,
};
pub use terms::{UserTerm, case_hint};

use serde::{Deserialize, Serialize};

use crate::evolution::ga::GaParams;
use crate::fitness::terms::Homing;
use crate::fitness::{Motivations, TskFitness};
use crate::modelling::aem::AemParams;
use crate::params::{FieldError, check};
use crate::random::seed::{Streams, hash_str};
use crate::simulation::controller::MlpShape;
use crate::simulation::randomise::Randomise;
use crate::simulation::robot::KHEPERA_RADIUS;
use crate::simulation::robot_spec::RobotSpec;
use crate::simulation::room::Room;
use crate::simulation::sensor_table::SensorTable;
use crate::simulation::trial::{Arena, TrialParams};

/// The label of the one evolution of all-rooms training (per-room training labels each by its
/// room); `best_genome.json` lists it under `runs`.
pub const ALL_ROOMS_RUN: &str = "all";

/// A validated experiment: its fields are private (read through the accessors below), so their
/// invariants hold and nothing downstream re-checks these values.
#[derive(Debug, Clone)]
pub struct Experiment {
    pub(crate) name: String,
    pub(crate) seed: u64,
    pub(crate) arenas: Vec<Arena>,
    pub(crate) training: Training,
    pub(crate) motivations: Motivations,
    pub(crate) fuzzy: TskFitness,
    pub(crate) ga: GaParams,
    pub(crate) trial: TrialParams,
    pub(crate) shape: MlpShape,
    pub(crate) energy: EnergyMode,
    pub(crate) orientation: OrientationMode,
    pub(crate) homing: Homing,
    pub(crate) aem: AemParams,
    pub(crate) plan: terms::TermPlan,
    pub(crate) combine: Combination,
    pub(crate) randomise: Option<Randomise>,
}

impl Experiment {
    /// Validates `raw` with its rooms already loaded (`rooms[i]` for `raw.rooms[i]`).
    pub fn new(
        raw: &RawConfig,
        rooms: Vec<Room>,
        source_name: &str,
    ) -> Result<Experiment, FieldError> {
        Self::with_terms(raw, rooms, &[], source_name)
    }

    /// [`Experiment::new`], with user-defined terms a motivation's `term` can name.
    pub fn with_terms(
        raw: &RawConfig,
        rooms: Vec<Room>,
        user: &[UserTerm],
        source_name: &str,
    ) -> Result<Experiment, FieldError> {
        Self::build(raw, rooms, user, ReadFiles::default()).map_err(|e| e.in_source(source_name))
    }

    /// [`Experiment::with_terms`], with the files the config names read by the front end
    /// ([`crate::experiment::Setup::resolve`]): the robot file `robot.file` names and the sensor
    /// table `trial.sensor_table` names.
    pub fn with_files(
        raw: &RawConfig,
        rooms: Vec<Room>,
        user: &[UserTerm],
        files: ReadFiles,
        source_name: &str,
    ) -> Result<Experiment, FieldError> {
        Self::build(raw, rooms, user, files).map_err(|e| e.in_source(source_name))
    }

    fn build(
        raw: &RawConfig,
        rooms: Vec<Room>,
        user: &[UserTerm],
        files: ReadFiles,
    ) -> Result<Experiment, FieldError> {
        check_name(&raw.name)?;
        check_rooms(&rooms)?;
        let fuzzy = raw.fuzzy.validated()?;
        let motivations = raw.motivations.validated(&fuzzy)?;
        let ga = GaParams::from_raw(&raw.ga)?;
        let spec = robot_of(&raw.robot, files.robot)?;
        let tolerance = raw.aem.action_tolerance;
        let trial = TrialParams::from_raw(&raw.trial, &raw.robot, spec, tolerance)?;
        let trial = match (&raw.trial.sensor_table, files.sensor_table) {
            (None, _) => trial,
            (Some(_), Some(table)) => trial.with_sensor_table(table_for(table, spec)?),
            (Some(file), None) => {
                return Err(FieldError::new(
                    "trial.sensor_table",
                    format!(
                        "the sensor table file \"{file}\" was not read: a front end reads it (Setup::resolve)"
                    ),
                ));
            }
        };
        let shape = raw.network.shape()?.with_inputs(spec.sensors())?;
        let aem = AemParams::from_raw(&raw.aem, trial.steps(), rooms.len())?;
        check(
            raw.fitness.orientation != OrientationMode::Online
                || (rooms.len() >= 2 && raw.training == Training::AllRooms),
            "fitness.orientation",
            || "\"online\" needs training = \"all-rooms\" with at least 2 rooms".into(),
        )?;
        check_clearance(&rooms, trial.robot().radius())?;
        let randomise = trial.randomise_of(&raw.trial)?;
        if let Some((_, largest)) = randomise.and_then(|r| r.radius) {
            check_clearance(&rooms, largest)
                .map_err(|e| FieldError::new("trial.randomise.radius", e.reason))?;
        }
        let plan = terms::TermPlan::resolve(
            &motivations,
            user,
            &rooms,
            raw.fitness.waypoints,
            raw.fitness.end_at_mission,
        )?;
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
            aem,
            plan,
            combine: raw.fitness.combine,
            randomise,
        })
    }

    /// Name (a plain file name: it names the output directory `runs/NAME`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Base seed of every random stream (≤ 2^53 − 1).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Rooms, prepared for trials, in config order (at least one, names unique).
    pub fn arenas(&self) -> &[Arena] {
        &self.arenas
    }

    /// Training protocol.
    pub fn training(&self) -> Training {
        self.training
    }

    /// Motivations X.
    pub fn motivations(&self) -> &Motivations {
        &self.motivations
    }

    /// The TSK evaluator.
    pub fn fuzzy(&self) -> &TskFitness {
        &self.fuzzy
    }

    /// GA parameters.
    pub fn ga(&self) -> &GaParams {
        &self.ga
    }

    /// Trial parameters (the robot body included).
    pub fn trial_params(&self) -> &TrialParams {
        &self.trial
    }

    /// The ranges each evaluation trial of the evolution draws its robot from
    /// (`[trial.randomise]`); none by default (every trial runs the configured robot).
    pub fn randomise(&self) -> Option<&Randomise> {
        self.randomise.as_ref()
    }

    /// Network shape.
    pub fn shape(&self) -> MlpShape {
        self.shape
    }

    /// Battery term direction.
    pub fn energy(&self) -> EnergyMode {
        self.energy
    }

    /// When `l` is measured.
    pub fn orientation(&self) -> OrientationMode {
        self.orientation
    }

    /// How `g` is measured.
    pub fn homing(&self) -> Homing {
        self.homing
    }

    /// Environment modelling parameters.
    pub fn aem(&self) -> &AemParams {
        &self.aem
    }

    /// Room names, in order.
    pub fn room_names(&self) -> Vec<String> {
        self.arenas.iter().map(|a| a.room().name.clone()).collect()
    }

    /// The evolutions the protocol asks for: one over all rooms, or one per room.
    pub fn runs(&self) -> Vec<Run> {
        match self.training {
            Training::AllRooms => vec![Run {
                label: ALL_ROOMS_RUN.into(),
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
}

/// The experiment's name names its output directory `runs/NAME`.
fn check_name(name: &str) -> Result<(), FieldError> {
    let safe_name = !name.is_empty()
        && name.len() <= 100
        && name != "."
        && name != ".."
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "._-".contains(c));
    check(safe_name, "name", || {
        format!(
            "must be a plain name of letters, digits, '.', '_' or '-' (it names the output directory runs/NAME), got {name:?}"
        )
    })
}

/// At least one room, and no two with the same name.
fn check_rooms(rooms: &[Room]) -> Result<(), FieldError> {
    check(!rooms.is_empty(), "rooms", || {
        "needs at least one room, e.g. rooms = [\"H\", \"T\", \"L\", \"square\", \"rectangle\"]"
            .into()
    })?;
    for (i, r) in rooms.iter().enumerate() {
        if let Some(j) = rooms[..i].iter().position(|o| o.name == r.name) {
            return Err(FieldError::new(
                format!("rooms[{i}]"),
                format!(
                    "room name \"{}\" is used twice (also rooms[{j}]); names must be unique",
                    r.name
                ),
            ));
        }
    }
    Ok(())
}

/// Room files are validated against the Khepera; a bigger body needs its own check.
/// The files a front end read for a config ([`Experiment::with_files`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct ReadFiles {
    /// The sensor table file `trial.sensor_table` names.
    pub sensor_table: Option<&'static SensorTable>,
    /// The robot file `robot.file` names (a built-in robot needs none).
    pub robot: Option<&'static RobotSpec>,
}

/// `table` (`trial.sensor_table`) when it has one entry per sensor of the robot `spec`.
fn table_for(
    table: &'static SensorTable,
    spec: &RobotSpec,
) -> Result<&'static SensorTable, FieldError> {
    check(
        table.sensors() == spec.sensors(),
        "trial.sensor_table",
        || {
            format!(
                "the table gives {} sensors, the robot {} has {}: a sensor table has one entry per sensor of the robot",
                table.sensors(),
                spec.name(),
                spec.sensors()
            )
        },
    )?;
    Ok(table)
}

/// The robot a config names: `read` (the file a front end read), else the built-in robot
/// `robot.file` names, else the paper's Khepera.
fn robot_of(
    raw: &crate::simulation::RawRobot,
    read: Option<&'static RobotSpec>,
) -> Result<&'static RobotSpec, FieldError> {
    match (read, raw.file.as_deref()) {
        (Some(spec), _) => Ok(spec),
        (None, None) => Ok(RobotSpec::khepera()),
        (None, Some(name)) => RobotSpec::builtin(name).ok_or_else(|| {
            FieldError::new(
                "robot.file",
                format!(
                    "\"{name}\" is not a built-in robot ({}) and the robot file was not read: a front end reads it (Setup::resolve)",
                    crate::simulation::BUILTIN_ROBOTS.join(", ")
                ),
            )
        }),
    }
}

fn check_clearance(rooms: &[Room], radius: f64) -> Result<(), FieldError> {
    crate::simulation::check_missions_reachable(rooms, radius)?;
    if radius <= KHEPERA_RADIUS {
        return Ok(());
    }
    for (i, r) in rooms.iter().enumerate() {
        let home = r.home.position();
        let clearance = r
            .walls()
            .iter()
            .map(|w| w.dist_to(home))
            .fold(f64::INFINITY, f64::min);
        check(clearance >= radius, &format!("rooms[{i}]"), || {
            format!(
                "home of room \"{}\" is {clearance:.1} mm from a wall, closer than robot.radius {radius}",
                r.name
            )
        })?;
    }
    Ok(())
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
    use crate::simulation::room::BUILTIN_ROOMS;

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::room::BUILTIN_ROOMS;

    /// The empty config validates to each validated type's own defaults (written once).
    #[test]
    fn defaults_are_the_validated_types_defaults() {
        let rooms = BUILTIN_ROOMS
            .iter()
            .map(|r| Room::builtin(r).unwrap())
            .collect();
        let exp = Experiment::new(&RawConfig::default(), rooms, "default").unwrap();
        assert_eq!(exp.trial_params(), &TrialParams::default());
        assert_eq!(exp.aem(), &AemParams::default());
        assert_eq!(exp.ga(), &GaParams::default());
        assert_eq!(exp.shape(), MlpShape::default());
        assert_eq!(exp.motivations(), &Motivations::high_curiosity());
        assert_eq!(exp.fuzzy(), &TskFitness::paper());
        assert_eq!((exp.name(), exp.seed()), ("experiment", 1));
        assert_eq!(exp.arenas().len(), BUILTIN_ROOMS.len());
    }
}
