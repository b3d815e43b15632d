//! The output model: one serde type per file that `run`, `reproduce` and `sweep` write and
//! read back, the in-memory outcome of a run they are made from, and the readers. A reader
//! that meets a missing or malformed field fails with an input error (exit code 2) naming the
//! file and the field.
//!
//! The JSON files were first written from JSON maps, whose keys come out sorted: the structs
//! of those files declare their fields in alphabetical order so that the bytes stay the same.
//! CSV cells keep their fixed decimals through [`Fixed`].
//!
//! | file | type |
//! |---|---|
//! | run `summary.json` | [`RunSummary`] |
//! | `best_genome.json` | [`BestGenome`] |
//! | `generations.csv` | [`GenerationRow`] |
//! | `recognition.csv` | [`RecognitionTable`] |
//! | `test_runs.csv` | [`test_runs::TestRunRow`] |
//! | reproduce `summary.json` | [`StudySummary`] (ablation: [`AblationSummary`]; search strength: [`StrengthSummary`]) |
//! | sweep `plan.jsonl`, `jobs/ID/job.json` | [`Job`] |
//! | sweep `results.csv` | [`SweepResults`] |
//! | sweep `aggregate.csv` | [`AggregateRow`] |
//! | `compare.csv` | [`compare::CompareRow`] |
//! | `robustness.csv` | [`robustness::RobustnessRecord`] |
//!
//! An experiment whose motivations are not the paper's four, or that measures a mission or
//! terms of its own ([`extra_terms`]), records more, by name: `generations.csv` a column per
//! extra term between `b` and `room` (the population mean), `best_genome.json` a `terms`
//! object per room, `summary.json` the motivation table (`motivations.table`: name, weight,
//! term) and per room `terms_pct` (the mean 100·term over the test runs) and
//! `mission_done_pct` (the share of test runs whose mission was done: waypoints visited, goal
//! reached); `table.md` shows the last two as "% missions done" and "% term" columns. The
//! paper's model records none of these, so its files keep their bytes.

use std::fmt;
use std::path::Path;

use fuzzymotiv::experiment::Experiment;
use fuzzymotiv::experiment::Outcome;
use fuzzymotiv::experiment::Training;
use fuzzymotiv::experiment::{Evolution, GenerationRecord};
use std::collections::BTreeMap;

use fuzzymotiv::fitness::FitnessTerms;
use fuzzymotiv::fitness::{Explanation, Motivations, TermId};
use fuzzymotiv::simulation::Trajectory;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::files::bounded::{InputKind, read_input};
use crate::files::error::CliError;

pub mod agreement;
pub mod checkpoint;
pub mod combination;
pub mod compare;
pub mod context;
pub mod export;
pub mod genome;
pub mod hypotheses;
pub mod paired;
pub mod paper_claims;
pub mod replication;
pub mod robot_log;
pub mod robustness;
pub mod test_runs;
pub mod urgency;

/// The model version of a record that names none: written before model versions were
/// recorded, by model 1.
pub fn model_one() -> u32 {
    1
}

/// The `program` field of every JSON file.
pub const PROGRAM: &str = "fuzzymotiv";

/// A float written with `D` decimals (a CSV cell), read back as any float.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Fixed<const D: usize>(pub f64);

impl<const D: usize> Serialize for Fixed<D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&format_args!("{:.*}", D, self.0))
    }
}

impl<'de, const D: usize> Deserialize<'de> for Fixed<D> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
        f64::deserialize(d).map(Fixed)
    }
}

impl<const D: usize> fmt::Display for Fixed<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:.*}", D, self.0)
    }
}

// ---------------------------------------------------------------------------------------------
// In memory: what a finished run produced.

/// Everything a finished run produced; the run directory's files are written from it.
pub struct Finished {
    /// The evolutions and the modelling of their best robots (which robot stands for which
    /// room is the library's rule: [`Outcome::robot_for_room`]).
    pub outcome: Outcome,
    /// The per-room table.
    pub rows: Vec<RoomRow>,
    /// Per room, the fuzzy fitness of the robot standing for it, rule by rule.
    pub fuzzy: Vec<RoomFuzzy>,
    /// Wall time (s).
    pub wall_seconds: f64,
}

impl Finished {
    /// The outcome of a run with its per-room table and fuzzy fitness explained.
    pub fn new(exp: &Experiment, outcome: Outcome, wall_seconds: f64) -> Finished {
        let rooms = 0..exp.arenas().len();
        let extra = extra_terms(exp);
        let rows = (rooms.clone())
            .map(|r| RoomRow::of(&outcome, r, &extra))
            .collect();
        let fuzzy = rooms.map(|r| RoomFuzzy::of(exp, &outcome, r)).collect();
        Finished {
            outcome,
            rows,
            fuzzy,
            wall_seconds,
        }
    }

    /// The trajectories of the best robots' room-modelling runs, one per room.
    pub fn trajectories(&self) -> Vec<&Trajectory> {
        self.outcome.trajectories()
    }
}

// ---------------------------------------------------------------------------------------------
// A run directory.

/// One row of `generations.csv`: the population's F and mean terms in one generation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GenerationRow {
    /// Generation index, from 0.
    pub generation: usize,
    /// F of the best individual (the population's maximum).
    pub best: Fixed<9>,
    /// Mean F.
    pub mean: Fixed<9>,
    /// Population standard deviation of F.
    pub std: Fixed<9>,
    /// Lowest F.
    pub min: Fixed<9>,
    /// Highest F (equal to `best`).
    pub max: Fixed<9>,
    /// Population mean of the exploration term a.
    pub a: Fixed<9>,
    /// Population mean of the homing term g.
    pub g: Fixed<9>,
    /// Population mean of the orientation term l.
    pub l: Fixed<9>,
    /// Population mean of the battery term b.
    pub b: Fixed<9>,
    /// The run's label: `all`, or the room a per-room robot was evolved in.
    pub room: String,
    /// Population means of the terms the experiment measures beyond a, g, l, b
    /// ([`extra_terms`]), by name: columns between `b` and `room`, only in the files of such
    /// experiments (written by [`generations_csv`], read by [`read_generations`]).
    #[serde(skip)]
    pub extra: Vec<(String, Fixed<9>)>,
}

/// The terms an experiment measures beyond the paper's a, g, l, b, by name, in the order the
/// records list them: the mission terms when a motivation weighs one of them (`goal` when a
/// room has a goal zone, `urgency`, `waypoints` when a room has waypoints, `safety`), then the
/// user-defined terms in registration order. None for the paper's model.
pub fn extra_terms(exp: &Experiment) -> Vec<(String, TermId)> {
    let mut out = Vec::new();
    if exp.measures_mission() {
        let rooms = || exp.arenas().iter().map(|a| &a.room().mission);
        let goal = rooms().any(|m| m.goal.is_some());
        let waypoints = rooms().any(|m| !m.waypoints.is_empty());
        let ids = [
            (TermId::Goal, goal),
            (TermId::Urgency, true),
            (TermId::Waypoints, waypoints),
            (TermId::Safety, true),
        ];
        for (id, _) in ids.into_iter().filter(|(_, on)| *on) {
            out.push((term_name(id).to_string(), id));
        }
    }
    for (k, u) in exp.user_terms().iter().enumerate() {
        out.push((u.name.clone(), TermId::User(k)));
    }
    out
}

fn term_name(id: TermId) -> &'static str {
    match id {
        TermId::A => "a",
        TermId::G => "g",
        TermId::L => "l",
        TermId::B => "b",
        TermId::Goal => "goal",
        TermId::Urgency => "urgency",
        TermId::Waypoints => "waypoints",
        TermId::Safety => "safety",
        TermId::User(_) => "user",
    }
}

/// The values of `extra` terms in `terms`, by name.
pub fn extra_values(extra: &[(String, TermId)], terms: &FitnessTerms) -> Vec<(String, f64)> {
    extra
        .iter()
        .map(|(name, id)| (name.clone(), terms.get(*id)))
        .collect()
}

impl GenerationRow {
    /// The row of `rec` in run `run` (the paper's columns only).
    pub fn of(rec: &GenerationRecord, run: &str) -> GenerationRow {
        Self::with_terms(rec, run, &[])
    }

    /// The row of `rec` in run `run`, with a column per term of `extra` ([`extra_terms`]).
    pub fn with_terms(
        rec: &GenerationRecord,
        run: &str,
        extra: &[(String, TermId)],
    ) -> GenerationRow {
        let (s, t) = (rec.stats, rec.terms);
        GenerationRow {
            extra: extra_values(extra, &t)
                .into_iter()
                .map(|(n, v)| (n, Fixed(v)))
                .collect(),
            generation: rec.generation,
            best: Fixed(s.max),
            mean: Fixed(s.mean),
            std: Fixed(s.std),
            min: Fixed(s.min),
            max: Fixed(s.max),
            a: Fixed(t.a),
            g: Fixed(t.g),
            l: Fixed(t.l),
            b: Fixed(t.b),
            room: run.to_string(),
        }
    }

    /// Every generation of every evolution, in order (the paper's columns only).
    pub fn all(evolutions: &[Evolution]) -> Vec<GenerationRow> {
        Self::all_of(&[], evolutions)
    }

    /// Every generation of every evolution, in order, with a column per term of `extra`.
    pub fn all_of(extra: &[(String, TermId)], evolutions: &[Evolution]) -> Vec<GenerationRow> {
        evolutions
            .iter()
            .flat_map(|e| {
                e.history
                    .iter()
                    .map(|r| GenerationRow::with_terms(r, &e.run.label, extra))
            })
            .collect()
    }
}

/// The columns of `generations.csv` before the extra terms'.
const GENERATION_COLUMNS: [&str; 10] = [
    "generation",
    "best",
    "mean",
    "std",
    "min",
    "max",
    "a",
    "g",
    "l",
    "b",
];

/// `generations.csv`'s text: the paper's columns, then one per extra term (by the first row's
/// names), then `room`. Rows without extra terms give the bytes they always gave.
pub fn generations_csv(rows: &[GenerationRow]) -> String {
    let Some(first) = rows.first().filter(|r| !r.extra.is_empty()) else {
        return to_csv(rows);
    };
    let mut w = csv_writer();
    let mut header: Vec<String> = GENERATION_COLUMNS.iter().map(|c| c.to_string()).collect();
    header.extend(first.extra.iter().map(|(n, _)| n.clone()));
    header.push("room".into());
    write_row(&mut w, header);
    for r in rows {
        let mut cells = vec![r.generation.to_string()];
        for v in [r.best, r.mean, r.std, r.min, r.max, r.a, r.g, r.l, r.b] {
            cells.push(v.to_string());
        }
        cells.extend(r.extra.iter().map(|(_, v)| v.to_string()));
        cells.push(r.room.clone());
        write_row(&mut w, cells);
    }
    csv_text(w)
}

/// Reads `generations.csv`: the paper's columns, and every other column but `room` as an extra
/// term's (a file of the paper's model has none).
pub fn read_generations(path: &Path) -> Result<Vec<GenerationRow>, CliError> {
    let mut rows: Vec<GenerationRow> = read_csv(path)?;
    let table = CsvTable::read(path)?;
    let names: Vec<String> = (table.headers.iter())
        .filter(|h| !GENERATION_COLUMNS.contains(&h.as_str()) && *h != "room")
        .cloned()
        .collect();
    for (k, row) in rows.iter_mut().enumerate() {
        for name in &names {
            let v: f64 = table.get(k, name)?;
            row.extra.push((name.clone(), Fixed(v)));
        }
    }
    Ok(rows)
}

/// One row of the per-room table (docs/model.md §10): `summary.json`'s `rooms`, `table.md`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomRow {
    /// Mean F of the final population in this room.
    pub average_fitness: f64,
    /// Mean 100·b over the test runs.
    pub battery_pct: f64,
    /// Mean 100·a over the test runs.
    pub exploration_pct: f64,
    /// Mean 100·g over the test runs (% homing). Earlier files call it `homing`, like the
    /// motivation weight; that name is still read, so their sweeps keep merging.
    #[serde(alias = "homing")]
    pub homing_pct: f64,
    /// The room instance's r-node, when AEM ran.
    pub r_node: Option<usize>,
    /// Correct recognitions in %, when AEM ran.
    pub recognition_pct: Option<f64>,
    /// Room name.
    pub room: String,
    /// % of the test runs whose mission was done (the room's waypoints visited and its goal
    /// reached: `done_at` set), when the experiment measures a mission ([`extra_terms`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mission_done_pct: Option<f64>,
    /// Mean 100·term over the test runs, for each term the experiment measures beyond a, g,
    /// l, b ([`extra_terms`]), by name; none for the paper's model.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub terms_pct: BTreeMap<String, f64>,
}

impl RoomRow {
    /// Room `r`'s row: all-rooms training uses the one robot everywhere, per-room training
    /// each room's own robot; with a column per term of `extra`.
    fn of(outcome: &Outcome, r: usize, extra: &[(String, TermId)]) -> RoomRow {
        let (evo, k) = outcome.robot_for_room(r);
        let a = &outcome.aem_for_room(r).rooms[r];
        let n = a.tests.len().max(1) as f64;
        let terms_pct = (extra.iter())
            .map(|(name, id)| {
                let sum: f64 = a.tests.iter().map(|t| 100.0 * t.terms.get(*id)).sum();
                (name.clone(), sum / n)
            })
            .collect();
        let measured = a.tests.iter().any(|t| t.terms.mission.is_some());
        let done = (a.tests.iter())
            .filter(|t| t.terms.mission.is_some_and(|m| m.done_at.is_some()))
            .count();
        RoomRow {
            mission_done_pct: measured.then(|| 100.0 * done as f64 / n),
            terms_pct,
            room: a.room.clone(),
            average_fitness: evo.mean_room_fitness(k),
            exploration_pct: a.exploration_pct,
            recognition_pct: a.recognition_pct,
            battery_pct: a.battery_pct,
            homing_pct: a.homing_pct,
            r_node: a.r_node,
        }
    }
}

/// The fuzzy fitness of the robot that stands for one room ([`Outcome::robot_for_room`]), in
/// that room, as the GA evaluated it in the last generation (one trial, with noise): its terms,
/// the fuzzy inputs Y they give and the rules that fired (docs/model.md §8).
#[derive(Debug, Clone, PartialEq)]
pub struct RoomFuzzy {
    /// Room name.
    pub room: String,
    /// The measured terms a, g, l, b.
    pub terms: FitnessTerms,
    /// F in this room.
    pub f: f64,
    /// The fuzzy inputs Y (b or 1 − b by the energy mode), before clamping.
    pub inputs: Vec<f64>,
    /// The firing rules and the sums that give F.
    pub explanation: Explanation,
}

impl RoomFuzzy {
    /// Room `r`'s: the library's [`Experiment::fuzzy_inputs`] and explanation of its robot's
    /// terms.
    fn of(exp: &Experiment, outcome: &Outcome, r: usize) -> RoomFuzzy {
        let (evo, k) = outcome.robot_for_room(r);
        let score = &evo.evaluations[evo.best].per_room[k];
        let inputs = exp.fuzzy_inputs(&score.terms);
        RoomFuzzy {
            room: exp.arenas()[r].room().name.clone(),
            terms: score.terms,
            f: score.f,
            explanation: exp.fuzzy().explain(exp.motivations(), &inputs),
            inputs,
        }
    }
}

/// The motivations as files record them: the paper's X = (C, H, O, E) (0 where absent) and,
/// when they are not the paper's four, the whole table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotivationsRecord {
    /// Curiosity C.
    pub curiosity: f64,
    /// Energy E.
    pub energy: f64,
    /// Homing H.
    pub homing: f64,
    /// Orientation O.
    pub orientation: f64,
    /// Every motivation in input order (name, weight, term), when they are not the paper's
    /// four ([`Motivations::is_paper`]); absent in the paper's records.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub table: Vec<MotivationEntry>,
}

/// One motivation of a [`MotivationsRecord`]'s table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotivationEntry {
    /// Its name.
    pub name: String,
    /// The term it weighs.
    pub term: String,
    /// Its weight.
    pub weight: f64,
}

impl MotivationsRecord {
    /// The record of `m`.
    pub fn of(m: &Motivations) -> MotivationsRecord {
        let table = if m.is_paper() {
            Vec::new()
        } else {
            m.iter()
                .map(|x| MotivationEntry {
                    name: x.name().to_string(),
                    term: x.term().to_string(),
                    weight: x.weight(),
                })
                .collect()
        };
        MotivationsRecord {
            table,
            curiosity: m.curiosity(),
            energy: m.energy(),
            homing: m.homing(),
            orientation: m.orientation(),
        }
    }

    /// (C, H, O, E).
    pub fn as_array(&self) -> [f64; 4] {
        [self.curiosity, self.homing, self.orientation, self.energy]
    }

    /// The motivations as a title shows them: `(C,H,O,E) = [..]` for the paper's four,
    /// `name = weight, …` for others.
    pub fn label(&self) -> String {
        if self.table.is_empty() {
            format!("(C,H,O,E) = {:?}", self.as_array())
        } else {
            let parts: Vec<String> = (self.table.iter())
                .map(|m| format!("{} = {}", m.name, m.weight))
                .collect();
            parts.join(", ")
        }
    }
}

/// The population's best and mean F in one generation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GenerationStat {
    /// Best F (the population's maximum).
    pub best: f64,
    /// Mean F.
    pub mean: f64,
}

impl GenerationStat {
    /// The stat of `rec`.
    pub fn of(rec: &GenerationRecord) -> GenerationStat {
        GenerationStat {
            best: rec.stats.max,
            mean: rec.stats.mean,
        }
    }
}

/// One evolution in a run's `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Fitness of the best final individual.
    pub best_fitness: f64,
    /// The first generation.
    pub first_generation: GenerationStat,
    /// The last generation.
    pub last_generation: GenerationStat,
    /// The run's label.
    pub run: String,
}

/// A run directory's `summary.json` (also the Python bindings' `summary`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// GA generations.
    pub generations: usize,
    /// The motivations.
    pub motivations: MotivationsRecord,
    /// The experiment's name.
    pub name: String,
    /// GA population.
    pub population: usize,
    /// Always `fuzzymotiv`.
    pub program: String,
    /// The per-room table.
    pub rooms: Vec<RoomRow>,
    /// One entry per evolution.
    pub runs: Vec<RunRecord>,
    /// Base seed.
    pub seed: u64,
    /// Steps per trial.
    pub steps: usize,
    /// All-rooms or per-room training.
    pub training: Training,
    /// Program version.
    pub version: String,
    /// Model version ([`fuzzymotiv::MODEL_VERSION`]); 1 in records written before it was recorded.
    #[serde(default = "model_one")]
    pub model: u32,
    /// Wall time (s), over all sessions of a resumed run.
    pub wall_seconds: f64,
}

impl RunSummary {
    /// The summary of a finished run.
    pub fn of(exp: &Experiment, done: &Finished) -> RunSummary {
        let runs = done
            .outcome
            .evolutions
            .iter()
            .map(|evo| RunRecord {
                run: evo.run.label.clone(),
                first_generation: GenerationStat::of(evo.history.first().expect("a generation")),
                last_generation: GenerationStat::of(evo.history.last().expect("a generation")),
                best_fitness: evo.evaluations[evo.best].fitness,
            })
            .collect();
        RunSummary {
            program: PROGRAM.into(),
            version: fuzzymotiv::VERSION.into(),
            model: fuzzymotiv::MODEL_VERSION,
            name: exp.name().into(),
            seed: exp.seed(),
            motivations: MotivationsRecord::of(exp.motivations()),
            training: exp.training(),
            population: exp.ga().population(),
            generations: exp.ga().generations(),
            steps: exp.trial_params().steps(),
            rooms: done.rows.clone(),
            runs,
            wall_seconds: done.wall_seconds,
        }
    }
}

/// The network's shape in `best_genome.json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapeRecord {
    /// Hidden units.
    pub hidden: usize,
    /// Inputs (8).
    #[serde(default = "eight")]
    pub inputs: usize,
    /// Outputs (2).
    #[serde(default = "two")]
    pub outputs: usize,
}

fn eight() -> usize {
    8
}

fn two() -> usize {
    2
}

/// The terms and F of the best robot in one room, as the GA evaluated it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomTerms {
    /// Exploration.
    pub a: f64,
    /// Battery.
    pub b: f64,
    /// F in this room.
    pub f: f64,
    /// Homing.
    pub g: f64,
    /// Orientation.
    pub l: f64,
    /// Room name.
    pub room: String,
    /// The terms beyond a, g, l, b the experiment measures ([`extra_terms`]), by name; absent
    /// for the paper's model.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub terms: BTreeMap<String, f64>,
}

/// The best robot of one evolution in `best_genome.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GenomeRun {
    /// Its fitness (mean F over its rooms).
    pub fitness: f64,
    /// The generation it belongs to (the last).
    pub generation: usize,
    /// Its index in that generation.
    pub individual: usize,
    /// The run's label.
    pub run: String,
    /// Its terms per room.
    pub terms: Vec<RoomTerms>,
    /// Its network weights.
    pub weights: Vec<f64>,
}

/// `best_genome.json`: the best robot of the first evolution at the top level, every
/// evolution's in `runs`. `replay` needs only `shape.hidden` and `weights` (and `seed`, `runs`
/// when present), so a hand-written genome file may leave the rest out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BestGenome {
    /// Fitness of the top-level robot.
    #[serde(default)]
    pub fitness: f64,
    /// How the weights are laid out.
    #[serde(default)]
    pub layout: String,
    /// Always `fuzzymotiv`.
    #[serde(default)]
    pub program: String,
    /// The top-level robot's run label.
    #[serde(default)]
    pub run: String,
    /// Every evolution's best robot.
    #[serde(default)]
    pub runs: Vec<GenomeRun>,
    /// Base seed of the run that evolved it.
    #[serde(default)]
    pub seed: Option<u64>,
    /// The network's shape.
    pub shape: ShapeRecord,
    /// The top-level robot's terms per room.
    #[serde(default)]
    pub terms: Vec<RoomTerms>,
    /// Program version.
    #[serde(default)]
    pub version: String,
    /// Model version ([`fuzzymotiv::MODEL_VERSION`]); 1 in records written before it was recorded.
    #[serde(default = "model_one")]
    pub model: u32,
    /// The top-level robot's weights.
    pub weights: Vec<f64>,
}

/// The layout of the weights in a genome.
pub const GENOME_LAYOUT: &str =
    "per hidden unit [bias, 8 input weights], then per output [bias, hidden weights]";

impl BestGenome {
    /// The best robots of a finished run.
    pub fn of(exp: &Experiment, evolutions: &[Evolution]) -> BestGenome {
        let names = exp.room_names();
        let extra = extra_terms(exp);
        let runs: Vec<GenomeRun> = evolutions
            .iter()
            .map(|evo| {
                let e = &evo.evaluations[evo.best];
                GenomeRun {
                    run: evo.run.label.clone(),
                    generation: evo.history.len() - 1,
                    individual: evo.best,
                    fitness: e.fitness,
                    terms: evo
                        .run
                        .rooms
                        .iter()
                        .zip(&e.per_room)
                        .map(|(&r, s)| RoomTerms {
                            room: names[r].clone(),
                            f: s.f,
                            a: s.terms.a,
                            g: s.terms.g,
                            l: s.terms.l,
                            b: s.terms.b,
                            terms: extra_values(&extra, &s.terms).into_iter().collect(),
                        })
                        .collect(),
                    weights: evo.population[evo.best].clone(),
                }
            })
            .collect();
        let first = runs[0].clone();
        let shape = exp.shape();
        BestGenome {
            program: PROGRAM.into(),
            version: fuzzymotiv::VERSION.into(),
            model: fuzzymotiv::MODEL_VERSION,
            seed: Some(exp.seed()),
            shape: ShapeRecord {
                hidden: shape.hidden(),
                inputs: shape.inputs(),
                outputs: shape.outputs(),
            },
            layout: GENOME_LAYOUT.into(),
            run: first.run,
            fitness: first.fitness,
            terms: first.terms,
            weights: first.weights,
            runs,
        }
    }
}

/// One row of `recognition.csv`: a room's test runs and what they were recognised as.
#[derive(Debug, Clone, PartialEq)]
pub struct RecognitionRow {
    /// The room the robot was in.
    pub room: String,
    /// Test runs in it.
    pub test_runs: u32,
    /// Correct recognitions.
    pub correct: u32,
    /// % recognition (written with one decimal; none with AEM disabled).
    pub recognition_pct: Option<f64>,
    /// Test runs recognised as each room (columns `as_ROOM`, in the table's room order).
    pub recognised_as: Vec<u32>,
    /// Test runs not recognised.
    pub not_recognised: u32,
}

/// `recognition.csv`: one row per room, one `as_ROOM` column per room.
#[derive(Debug, Clone, PartialEq)]
pub struct RecognitionTable {
    /// The rooms, in column order.
    pub rooms: Vec<String>,
    /// One row per room.
    pub rows: Vec<RecognitionRow>,
}

impl RecognitionTable {
    /// The confusion counts of a finished run (each room's robot's counts in its room).
    pub fn of(exp: &Experiment, done: &Finished) -> RecognitionTable {
        let rows = done
            .rows
            .iter()
            .enumerate()
            .map(|(r, row)| {
                let confusion = &done.outcome.aem_for_room(r).confusion;
                let counts = &confusion.counts[r];
                let (as_rooms, not) = counts.split_at(counts.len() - 1);
                RecognitionRow {
                    room: row.room.clone(),
                    test_runs: counts.iter().sum(),
                    correct: confusion.correct(r),
                    recognition_pct: row.recognition_pct,
                    recognised_as: as_rooms.to_vec(),
                    not_recognised: not[0],
                }
            })
            .collect();
        RecognitionTable {
            rooms: exp.room_names(),
            rows,
        }
    }

    fn header(&self) -> Vec<String> {
        let mut h: Vec<String> = ["room", "test_runs", "correct", "recognition_pct"]
            .map(String::from)
            .to_vec();
        h.extend(self.rooms.iter().map(|n| format!("as_{n}")));
        h.push("not_recognised".into());
        h
    }

    /// The file's text.
    pub fn to_csv(&self) -> String {
        let mut w = csv_writer();
        write_row(&mut w, self.header());
        for r in &self.rows {
            let mut cells = vec![
                r.room.clone(),
                r.test_runs.to_string(),
                r.correct.to_string(),
                r.recognition_pct
                    .map_or(String::new(), |p| Fixed::<1>(p).to_string()),
            ];
            cells.extend(r.recognised_as.iter().map(u32::to_string));
            cells.push(r.not_recognised.to_string());
            write_row(&mut w, cells);
        }
        csv_text(w)
    }

    /// Reads `recognition.csv`.
    pub fn read(path: &Path) -> Result<RecognitionTable, CliError> {
        let table = CsvTable::read(path)?;
        let rooms: Vec<String> = table
            .headers
            .iter()
            .filter_map(|h| h.strip_prefix("as_").map(String::from))
            .collect();
        let rows = (0..table.rows.len())
            .map(|i| {
                Ok(RecognitionRow {
                    room: table.get(i, "room")?,
                    test_runs: table.get(i, "test_runs")?,
                    correct: table.get(i, "correct")?,
                    recognition_pct: table.get_opt(i, "recognition_pct")?,
                    recognised_as: rooms
                        .iter()
                        .map(|n| table.get(i, &format!("as_{n}")))
                        .collect::<Result<_, _>>()?,
                    not_recognised: table.get(i, "not_recognised")?,
                })
            })
            .collect::<Result<_, CliError>>()?;
        Ok(RecognitionTable { rooms, rows })
    }
}

// ---------------------------------------------------------------------------------------------
// A `reproduce` directory.

/// A row of a study's tables in `summary.json`: means (or sample standard deviations, n − 1)
/// over seeds, or one seed's values; none where a value is missing (and a standard deviation
/// of one seed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TableRow {
    /// Average fitness.
    pub average_fitness: Option<f64>,
    /// % battery usage.
    pub battery_pct: Option<f64>,
    /// % optimal exploration.
    pub exploration_pct: Option<f64>,
    /// % homing (read also under its old name `homing`).
    #[serde(alias = "homing")]
    pub homing_pct: Option<f64>,
    /// % recognition.
    pub recognition_pct: Option<f64>,
    /// Room name.
    pub room: String,
}

impl TableRow {
    /// One seed's row.
    pub fn of(r: &RoomRow) -> TableRow {
        TableRow {
            room: r.room.clone(),
            average_fitness: Some(r.average_fitness),
            exploration_pct: Some(r.exploration_pct),
            recognition_pct: r.recognition_pct,
            battery_pct: Some(r.battery_pct),
            homing_pct: Some(r.homing_pct),
        }
    }
}

/// One seed of a setting in `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeedSummary {
    /// Per robot, its confusion counts (`counts[true room][answer]`, the last answer "not
    /// recognised").
    pub confusion: Vec<Vec<Vec<u32>>>,
    /// The first generation.
    pub first_generation: GenerationStat,
    /// The last generation.
    pub last_generation: GenerationStat,
    /// The seed's table.
    pub rows: Vec<TableRow>,
    /// Its run directory, relative to the study.
    pub run_dir: String,
    /// The seed.
    pub seed: u64,
}

/// One setting of the study in `summary.json`: `rows`, `first_generation` and
/// `last_generation` are means over seeds; `std` and `per_seed` give the spread.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SettingSummary {
    /// Mean over seeds of the first generation.
    pub first_generation: GenerationStat,
    /// GA generations.
    pub generations: usize,
    /// Mean over seeds of the last generation.
    pub last_generation: GenerationStat,
    /// The seed whose figures are shown.
    pub median_seed: u64,
    /// The setting's motivations.
    pub motivations: MotivationsRecord,
    /// The setting's name.
    pub name: String,
    /// Every seed.
    pub per_seed: Vec<SeedSummary>,
    /// GA population.
    pub population: usize,
    /// Means over seeds.
    pub rows: Vec<TableRow>,
    /// Sample standard deviations (n − 1) over seeds; none (`null`) with one seed.
    pub std: Vec<TableRow>,
}

/// One of the paper's claims and whether the study shows it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimRecord {
    /// The claim, written as its sentence ([`paper_claims::ClaimId::sentence`]) and read back
    /// from it.
    pub claim: paper_claims::ClaimId,
    /// Fig. 6's checks over seeds, one per setting (none for the comparisons and in files
    /// written before them).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub curves: Vec<CurveStats>,
    /// The numbers behind the verdict.
    pub evidence: String,
    /// Whether the study shows it: for a comparison, its verdict is "holds".
    pub holds: bool,
    /// A comparison's statistics over seeds (high − low curiosity, paired by seed); none for
    /// the checks of Fig. 6's curves and in files written before them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stats: Option<ClaimStats>,
}

/// One setting's test of a Fig. 6 claim over seeds: the first generation's mean F against the
/// band 0.05–0.15 (two one-sided sign-flip tests), or the last generation's mean F against the
/// first's (paired by seed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurveStats {
    /// The setting.
    pub setting: String,
    /// Seeds.
    pub seeds: usize,
    /// What `value` is, in words.
    pub statistic: String,
    /// The mean over seeds of the statistic.
    pub value: f64,
    /// Lower bound of its 95 % percentile bootstrap interval.
    pub ci_low: f64,
    /// Upper bound of the interval.
    pub ci_high: f64,
    /// The test's p-value (see `statistic`).
    pub p: f64,
    /// "holds", "opposite" or "not significant" at `alpha`.
    pub verdict: String,
    /// The significance level of the verdict.
    pub alpha: f64,
}

/// The statistics of a comparison claim over seeds: see `fuzzymotiv::statistics` for the
/// methods (paired sign-flip permutation test, percentile bootstrap interval, minimum
/// detectable difference by the normal approximation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimStats {
    /// Paired seeds.
    pub seeds: usize,
    /// Mean over seeds of high − low (per seed, each setting's mean over rooms).
    pub difference: f64,
    /// Lower bound of its 95 % percentile bootstrap interval.
    pub ci_low: f64,
    /// Upper bound of the interval.
    pub ci_high: f64,
    /// Two-sided sign-flip permutation p-value.
    pub p: f64,
    /// The smallest p-value the test can give with these seeds: 2 / 2^seeds up to 16 seeds
    /// (every sign pattern), else 2 / (resamples + 1) (random sign patterns).
    pub min_p: f64,
    /// The significance level of the verdict.
    pub alpha: f64,
    /// "holds", "opposite", "not significant" or, when |difference| < `mdd`, "inconclusive".
    pub verdict: String,
    /// The smallest difference detectable with 80 % power at `alpha` with these seeds; none
    /// for one seed.
    pub mdd: Option<f64>,
    /// Per room, the same test (exploratory: p-values Holm-adjusted over the claim's rooms).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rooms: Vec<RoomClaimStats>,
}

/// One room's paired comparison of a claim.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomClaimStats {
    /// The room.
    pub room: String,
    /// Mean over seeds of high − low in this room.
    pub difference: f64,
    /// Lower bound of its 95 % percentile bootstrap interval.
    pub ci_low: f64,
    /// Upper bound of the interval.
    pub ci_high: f64,
    /// Two-sided sign-flip permutation p-value.
    pub p: f64,
    /// `p` Holm-adjusted over the claim's rooms.
    pub p_holm: f64,
    /// The verdict on the Holm-adjusted p-value.
    pub verdict: String,
}

/// `reproduce`'s `summary.json` (read by `scripts/seeds_table.py`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudySummary {
    /// The paper's claims.
    pub claims: Vec<ClaimRecord>,
    /// GA generations.
    pub generations: usize,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// GA population.
    pub population: usize,
    /// Always `fuzzymotiv`.
    pub program: String,
    /// Whether `--quick`.
    pub quick: bool,
    /// `--seed`.
    pub seed: u64,
    /// The study's seeds.
    pub seeds: Vec<u64>,
    /// The two settings.
    pub settings: Vec<SettingSummary>,
    /// Program version.
    pub version: String,
    /// Model version ([`fuzzymotiv::MODEL_VERSION`]); 1 in records written before it was recorded.
    #[serde(default = "model_one")]
    pub model: u32,
    /// Wall time (s).
    pub wall_seconds: f64,
}

/// One variant of the ablation in its `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariantSummary {
    /// The paper's claims under this variant.
    pub claims: Vec<ClaimRecord>,
    /// The variant's name (its directory).
    pub name: String,
    /// What it switches back, in words.
    pub switched_back: String,
}

/// `reproduce --ablation`'s `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AblationSummary {
    /// GA generations.
    pub generations: usize,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// GA population.
    pub population: usize,
    /// Always `fuzzymotiv`.
    pub program: String,
    /// Whether `--quick`.
    pub quick: bool,
    /// `--seed`.
    pub seed: u64,
    /// The study's seeds.
    pub seeds: Vec<u64>,
    /// Every variant.
    pub variants: Vec<VariantSummary>,
    /// Program version.
    pub version: String,
    /// Model version ([`fuzzymotiv::MODEL_VERSION`]); 1 in records written before it was recorded.
    #[serde(default = "model_one")]
    pub model: u32,
    /// Wall time (s).
    pub wall_seconds: f64,
}

/// `reproduce --search-strength`'s `summary.json`: each population's claims (its own study's
/// `summary.json`, in `pop-N/`, holds the rest).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrengthSummary {
    /// GA generations (the same at every population).
    pub generations: usize,
    /// `--set` overrides.
    pub overrides: Vec<String>,
    /// The GA populations, in the order of `variants`.
    pub populations: Vec<usize>,
    /// Always `fuzzymotiv`.
    pub program: String,
    /// Whether `--quick`.
    pub quick: bool,
    /// `--seed`.
    pub seed: u64,
    /// The study's seeds.
    pub seeds: Vec<u64>,
    /// Every population's claims (`name` is its directory, `pop-N`).
    pub variants: Vec<VariantSummary>,
    /// Program version.
    pub version: String,
    /// Model version ([`fuzzymotiv::MODEL_VERSION`]); 1 in records written before it was recorded.
    #[serde(default = "model_one")]
    pub model: u32,
    /// Wall time (s).
    pub wall_seconds: f64,
}

// ---------------------------------------------------------------------------------------------
// A sweep directory.

/// One job of a sweep: a line of `plan.jsonl`, and `jobs/ID/job.json`.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Job {
    /// Position in the plan (stable for a given sweep file).
    pub index: usize,
    /// Hash of the fully resolved config (16 hex digits).
    pub id: String,
    /// The job's key: its point and replicate, e.g. `C=0.8,H=0.1,O=0,E=0.1;rep=0`.
    pub key: String,
    /// The key without the replicate: jobs with equal settings share it.
    pub setting: String,
    /// Replicate number.
    pub replicate: usize,
    /// Seed derived from the base seed and the key.
    pub seed: u64,
    /// The `--set` overrides that make this job's config from the base.
    pub overrides: Vec<String>,
    /// The model version of the build that planned it ([`fuzzymotiv::MODEL_VERSION`]; 1 in
    /// plans written before it was recorded): a sweep is never finished by another model.
    #[serde(default = "model_one")]
    pub model: u32,
}

impl Job {
    /// The job's swept `[sweep.grid]` values: every override but the motivations and the seed,
    /// as (key, TOML value).
    pub fn grid_values(&self) -> Vec<(&str, &str)> {
        self.overrides
            .iter()
            .filter_map(|o| o.split_once('='))
            .filter(|(k, _)| *k != "seed" && !k.starts_with("motivations."))
            .collect()
    }

    /// Reads `plan.jsonl`.
    pub fn read_plan(path: &Path) -> Result<Vec<Job>, CliError> {
        let text = read_input(path, InputKind::record("sweep plan"))?;
        let jobs: Vec<Job> = (text.lines().enumerate())
            .filter(|(_, l)| !l.trim().is_empty())
            .map(|(i, l)| parse_json(l, &format!("{}: line {}", path.display(), i + 1)))
            .collect::<Result<_, _>>()?;
        if jobs.is_empty() {
            return Err(CliError::input(format!(
                "{}: the plan holds no jobs (an emptied file?); `fuzzymotiv plan SWEEP.toml --out \
                 {}` writes it again from the sweep file",
                path.display(),
                path.display()
            )));
        }
        Ok(jobs)
    }
}

/// The result columns of `results.csv` and `aggregate.csv`, in order.
pub const METRICS: [&str; 5] = [
    "average_fitness",
    "exploration_pct",
    "recognition_pct",
    "battery_pct",
    "homing_pct",
];

/// Prefix of the `results.csv` columns of `[sweep.grid]` keys.
pub const GRID_PREFIX: &str = "grid.";

/// Prefix of the `results.csv` columns of motivations beyond the paper's four.
pub const MOTIVATION_PREFIX: &str = "motivation.";

/// The `results.csv` column of the % of test runs whose mission was done.
const MISSION_DONE: &str = "mission_done_pct";

/// One row of `results.csv`: one room of one job.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepResultRow {
    /// The job's id.
    pub job_id: String,
    /// The job's plan index.
    pub index: usize,
    /// The job's setting (its point without the replicate).
    pub setting: String,
    /// Replicate number.
    pub replicate: usize,
    /// The job's seed.
    pub seed: u64,
    /// The job's resolved motivations.
    pub motivations: MotivationsRecord,
    /// The value of every swept `[sweep.grid]` key, in [`SweepResults::grid`] order (numbers
    /// as written in the sweep file, strings unquoted).
    pub grid: Vec<String>,
    /// Room name.
    pub room: String,
    /// The room's row of the job's table, in [`METRICS`] order (six decimals).
    pub values: [Option<f64>; 5],
    /// The weight of each motivation of [`SweepResults::motivations`] (none where the job's
    /// config lacks it).
    pub other_weights: Vec<Option<f64>>,
    /// The % of test runs whose mission was done, when the job follows missions.
    pub mission_done_pct: Option<f64>,
}

/// `results.csv`: the columns `job_id, index, setting, replicate, seed, curiosity, homing,
/// orientation, energy` (the motivation weights), one `motivation.NAME` column per other
/// motivation of a job, one `grid.KEY` column per swept key, `room`, the results [`METRICS`],
/// then `mission_done_pct` when a job follows missions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SweepResults {
    /// The motivations beyond the paper's four, in column order (first seen first).
    pub motivations: Vec<String>,
    /// Whether a job follows missions (then the `mission_done_pct` column).
    pub missions: bool,
    /// The swept `[sweep.grid]` keys, in column order.
    pub grid: Vec<String>,
    /// One row per (job, room).
    pub rows: Vec<SweepResultRow>,
}

const RESULT_HEAD: [&str; 9] = [
    "job_id",
    "index",
    "setting",
    "replicate",
    "seed",
    "curiosity",
    "homing",
    "orientation",
    "energy",
];

impl SweepResults {
    fn header(&self) -> Vec<String> {
        let mut h: Vec<String> = RESULT_HEAD.map(String::from).to_vec();
        h.extend(
            self.motivations
                .iter()
                .map(|k| format!("{MOTIVATION_PREFIX}{k}")),
        );
        h.extend(self.grid.iter().map(|k| format!("{GRID_PREFIX}{k}")));
        h.push("room".into());
        h.extend(METRICS.map(String::from));
        if self.missions {
            h.push(MISSION_DONE.into());
        }
        h
    }

    /// The file's text (CSV-escaped where a cell needs it).
    pub fn to_csv(&self) -> String {
        let mut w = csv_writer();
        write_row(&mut w, self.header());
        for r in &self.rows {
            let mut cells = vec![
                r.job_id.clone(),
                r.index.to_string(),
                r.setting.clone(),
                r.replicate.to_string(),
                r.seed.to_string(),
            ];
            let six = |v: Option<f64>| v.map_or(String::new(), |v| Fixed::<6>(v).to_string());
            cells.extend(r.motivations.as_array().map(|v| v.to_string()));
            cells.extend(
                (r.other_weights.iter()).map(|v| v.map_or(String::new(), |v| v.to_string())),
            );
            cells.extend(r.grid.iter().cloned());
            cells.push(r.room.clone());
            cells.extend(r.values.map(six));
            if self.missions {
                cells.push(six(r.mission_done_pct));
            }
            write_row(&mut w, cells);
        }
        csv_text(w)
    }

    /// Reads `results.csv`.
    pub fn read(path: &Path) -> Result<SweepResults, CliError> {
        let t = CsvTable::read(path)?;
        let grid: Vec<String> = t
            .headers
            .iter()
            .filter_map(|h| h.strip_prefix(GRID_PREFIX).map(String::from))
            .collect();
        let motivations: Vec<String> = (t.headers.iter())
            .filter_map(|h| h.strip_prefix(MOTIVATION_PREFIX).map(String::from))
            .collect();
        let missions = t.headers.iter().any(|h| h == MISSION_DONE);
        let rows = (0..t.rows.len())
            .map(|i| {
                Ok(SweepResultRow {
                    job_id: t.get(i, "job_id")?,
                    index: t.get(i, "index")?,
                    setting: t.get(i, "setting")?,
                    replicate: t.get(i, "replicate")?,
                    seed: t.get(i, "seed")?,
                    motivations: MotivationsRecord {
                        curiosity: t.get(i, "curiosity")?,
                        homing: t.get(i, "homing")?,
                        orientation: t.get(i, "orientation")?,
                        energy: t.get(i, "energy")?,
                        table: Vec::new(),
                    },
                    grid: grid
                        .iter()
                        .map(|k| t.get(i, &format!("{GRID_PREFIX}{k}")))
                        .collect::<Result<_, _>>()?,
                    room: t.get(i, "room")?,
                    values: [
                        t.get_opt(i, METRICS[0])?,
                        t.get_opt(i, METRICS[1])?,
                        t.get_opt(i, METRICS[2])?,
                        t.get_opt(i, METRICS[3])?,
                        t.get_opt(i, METRICS[4])?,
                    ],
                    other_weights: (motivations.iter())
                        .map(|k| t.get_opt(i, &format!("{MOTIVATION_PREFIX}{k}")))
                        .collect::<Result<_, _>>()?,
                    mission_done_pct: if missions {
                        t.get_opt(i, MISSION_DONE)?
                    } else {
                        None
                    },
                })
            })
            .collect::<Result<_, CliError>>()?;
        Ok(SweepResults {
            motivations,
            missions,
            grid,
            rows,
        })
    }
}

/// One row of `aggregate.csv`: mean and sample standard deviation (n − 1) over a setting's
/// replicates in one room (six decimals). A mean is empty where no replicate has a value, a
/// standard deviation where fewer than two have one (n = 1 has no spread to show).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AggregateRow {
    /// The setting.
    pub setting: String,
    /// Room name.
    pub room: String,
    /// Replicates.
    pub n: usize,
    /// Mean average fitness.
    pub average_fitness_mean: Option<Fixed<6>>,
    /// Its sample standard deviation (n − 1).
    pub average_fitness_std: Option<Fixed<6>>,
    /// Mean % exploration.
    pub exploration_pct_mean: Option<Fixed<6>>,
    /// Its sample standard deviation (n − 1).
    pub exploration_pct_std: Option<Fixed<6>>,
    /// Mean % recognition.
    pub recognition_pct_mean: Option<Fixed<6>>,
    /// Its sample standard deviation (n − 1).
    pub recognition_pct_std: Option<Fixed<6>>,
    /// Mean % battery usage.
    pub battery_pct_mean: Option<Fixed<6>>,
    /// Its sample standard deviation (n − 1).
    pub battery_pct_std: Option<Fixed<6>>,
    /// Mean % homing.
    pub homing_pct_mean: Option<Fixed<6>>,
    /// Its sample standard deviation (n − 1).
    pub homing_pct_std: Option<Fixed<6>>,
}

impl AggregateRow {
    /// The row of (`setting`, `room`) with `n` replicates and per metric (mean, sample std).
    pub fn new(
        setting: &str,
        room: &str,
        n: usize,
        stats: [(Option<f64>, Option<f64>); 5],
    ) -> AggregateRow {
        let [f, e, r, b, h] = stats.map(|(m, s)| (m.map(Fixed), s.map(Fixed)));
        AggregateRow {
            setting: setting.into(),
            room: room.into(),
            n,
            average_fitness_mean: f.0,
            average_fitness_std: f.1,
            exploration_pct_mean: e.0,
            exploration_pct_std: e.1,
            recognition_pct_mean: r.0,
            recognition_pct_std: r.1,
            battery_pct_mean: b.0,
            battery_pct_std: b.1,
            homing_pct_mean: h.0,
            homing_pct_std: h.1,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Writing and reading.

/// `value` as pretty JSON with a final newline (the JSON files' format).
pub fn to_json(value: &impl Serialize) -> String {
    serde_json::to_string_pretty(value).expect("records serialise") + "\n"
}

/// `rows` as CSV with a header from the field names (nothing for no rows).
pub fn to_csv<T: Serialize>(rows: &[T]) -> String {
    let mut w = csv_writer();
    for r in rows {
        w.serialize(r).expect("records serialise");
    }
    csv_text(w)
}

fn csv_writer() -> csv::Writer<Vec<u8>> {
    csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new())
}

fn write_row(w: &mut csv::Writer<Vec<u8>>, cells: Vec<String>) {
    w.write_record(&cells).expect("writing to memory");
}

fn csv_text(w: csv::Writer<Vec<u8>>) -> String {
    let bytes = w.into_inner().expect("writing to memory");
    String::from_utf8(bytes).expect("cells are text")
}

/// A record file fuzzymotiv wrote (JSON or CSV), read back whole (at most
/// [`crate::files::bounded::RECORD_LIMIT`] bytes).
const RECORD: InputKind = InputKind::record("record file");

/// Reads a JSON record file; a missing or malformed field is an input error naming the file
/// and the field.
pub fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T, CliError> {
    let text = read_input(path, RECORD)?;
    parse_json(&text, &path.display().to_string())
}

/// Parses JSON text from `source` (a file name, maybe with a line) into a record; a wrong value
/// says what its field takes in plain words ([`fuzzymotiv::params::deserialize_plain`]).
pub fn parse_json<T: DeserializeOwned>(text: &str, source: &str) -> Result<T, CliError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let mut track = serde_path_to_error::Track::new();
    let read = fuzzymotiv::params::deserialize_plain::<T, _>(
        serde_path_to_error::Deserializer::new(&mut de, &mut track),
    );
    let value = read.map_err(|inner| {
        let field = track.path().to_string();
        if inner.classify() != serde_json::error::Category::Data {
            CliError::input(format!("{source}: not valid JSON: {inner}"))
        } else if let Some(record) = array_for_record::<T>(text) {
            // serde reads an array as a struct's fields in order: say what was expected.
            CliError::input(format!(
                "{source}: expected a JSON object {{ \"key\": value, … }} (a {record} record), got an array"
            ))
        } else if field == "." {
            CliError::input(format!("{source}: {inner}"))
        } else {
            CliError::input(format!("{source}: field `{field}`: {inner}"))
        }
    })?;
    de.end()
        .map_err(|e| CliError::input(format!("{source}: not valid JSON: {e}")))?;
    Ok(value)
}

/// The record `T` when the document `text` is an array where its object belongs (serde then
/// reads the array as the struct's fields in order and says "invalid length 0, expected struct
/// BestGenome with 11 elements" or fails on an element): the name `T` is read under if `T` is
/// read as a struct, asked of `T`'s own `Deserialize`.
fn array_for_record<T: DeserializeOwned>(text: &str) -> Option<&'static str> {
    if !text.trim_start().starts_with('[') {
        return None;
    }
    let mut name = None;
    let _ = T::deserialize(StructName(&mut name));
    name
}

/// A deserializer that holds nothing and notes the name of the struct asked of it.
struct StructName<'a>(&'a mut Option<&'static str>);

impl<'de> serde::Deserializer<'de> for StructName<'_> {
    type Error = serde::de::value::Error;

    fn deserialize_any<V: serde::de::Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(serde::de::Error::custom("not a struct"))
    }

    fn deserialize_struct<V: serde::de::Visitor<'de>>(
        self,
        name: &'static str,
        _fields: &'static [&'static str],
        _visitor: V,
    ) -> Result<V::Value, Self::Error> {
        *self.0 = Some(name);
        Err(serde::de::Error::custom("a struct"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

/// Reads a CSV record file into rows of `T`; a missing or malformed cell is an input error
/// naming the file, the line and the column.
pub fn read_csv<T: DeserializeOwned>(path: &Path) -> Result<Vec<T>, CliError> {
    parse_csv(&read_input(path, RECORD)?, path)
}

/// [`read_csv`] of the text of `path`, already read.
fn parse_csv<T: DeserializeOwned>(text: &str, path: &Path) -> Result<Vec<T>, CliError> {
    let mut rdr = csv::Reader::from_reader(text.as_bytes());
    let headers = rdr.headers().map_err(|e| csv_error(path, None, e))?.clone();
    rdr.deserialize()
        .map(|r| r.map_err(|e| csv_error(path, Some(&headers), e)))
        .collect()
}

fn csv_error(path: &Path, headers: Option<&csv::StringRecord>, e: csv::Error) -> CliError {
    let at = e
        .position()
        .map_or(String::new(), |p| format!(" line {}:", p.line()));
    let message = match e.kind() {
        csv::ErrorKind::Deserialize { err, .. } => {
            let column = err
                .field()
                .and_then(|k| headers.and_then(|h| h.get(k as usize)));
            match column {
                Some(c) => format!("field `{c}`: {}", err.kind()),
                None => err.kind().to_string(),
            }
        }
        _ => e.to_string(),
    };
    CliError::input(format!("{}:{at} {message}", path.display()))
}

/// A CSV file read as text cells, looked up by column name (for files whose columns depend
/// on the run: `recognition.csv`, `results.csv`).
struct CsvTable {
    path: String,
    headers: Vec<String>,
    rows: Vec<csv::StringRecord>,
}

impl CsvTable {
    fn read(path: &Path) -> Result<CsvTable, CliError> {
        CsvTable::parse(&read_input(path, RECORD)?, path)
    }

    /// [`CsvTable::read`] of the text of `path`, already read.
    fn parse(text: &str, path: &Path) -> Result<CsvTable, CliError> {
        let mut rdr = csv::Reader::from_reader(text.as_bytes());
        let headers = rdr
            .headers()
            .map_err(|e| csv_error(path, None, e))?
            .iter()
            .map(String::from)
            .collect();
        let rows = rdr
            .records()
            .collect::<Result<_, _>>()
            .map_err(|e| csv_error(path, None, e))?;
        Ok(CsvTable {
            path: path.display().to_string(),
            headers,
            rows,
        })
    }

    /// The line of row `row` in the file.
    fn line(&self, row: usize) -> u64 {
        self.rows[row]
            .position()
            .map_or(row as u64 + 2, |p| p.line())
    }

    fn cell(&self, row: usize, column: &str) -> Result<&str, CliError> {
        let k = self
            .headers
            .iter()
            .position(|h| h == column)
            .ok_or_else(|| CliError::input(format!("{}: no column `{column}`", self.path)))?;
        self.rows[row].get(k).ok_or_else(|| {
            CliError::input(format!(
                "{}: line {}: field `{column}` is missing",
                self.path,
                self.line(row)
            ))
        })
    }

    fn get<T: Cell>(&self, row: usize, column: &str) -> Result<T, CliError> {
        let text = self.cell(row, column)?;
        text.parse().map_err(|_| {
            CliError::input(format!(
                "{}: line {}: field `{column}`: `{text}` is not {}",
                self.path,
                self.line(row),
                T::EXPECTED
            ))
        })
    }

    fn get_opt<T: Cell>(&self, row: usize, column: &str) -> Result<Option<T>, CliError> {
        if self.cell(row, column)?.is_empty() {
            Ok(None)
        } else {
            self.get(row, column).map(Some)
        }
    }
}

/// A value a CSV cell holds, and what a cell that is not one is told it should be.
trait Cell: std::str::FromStr {
    /// What the cell should hold, in a message: "a number", "a whole number".
    const EXPECTED: &'static str;
}

impl Cell for f64 {
    const EXPECTED: &'static str = "a number";
}

/// Text: every cell is one (its parse cannot fail).
impl Cell for String {
    const EXPECTED: &'static str = "text";
}

macro_rules! whole_number_cells {
    ($($t:ty),*) => {$(
        impl Cell for $t {
            const EXPECTED: &'static str = "a whole number";
        }
    )*};
}

whole_number_cells!(u32, u64, usize);

#[cfg(test)]
mod tests {
    use super::*;

    /// CSV records keep their fixed decimals when written and come back as written.
    #[test]
    fn csv_records_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let row = |g: usize| GenerationRow {
            generation: g,
            best: Fixed(0.5),
            mean: Fixed(0.25),
            std: Fixed(0.125),
            min: Fixed(0.0),
            max: Fixed(0.5),
            a: Fixed(1.0),
            g: Fixed(0.75),
            l: Fixed(0.0),
            b: Fixed(1.0 / 3.0),
            room: "a, \"b\"".into(),
            extra: Vec::new(),
        };
        let text = to_csv(&[row(0), row(1)]);
        assert_eq!(
            text.lines().nth(1).unwrap(),
            "0,0.500000000,0.250000000,0.125000000,0.000000000,0.500000000,1.000000000,0.750000000,0.000000000,0.333333333,\"a, \"\"b\"\"\""
        );
        let path = dir.path().join("generations.csv");
        std::fs::write(&path, &text).unwrap();
        let back: Vec<GenerationRow> = read_csv(&path).unwrap();
        assert_eq!(back[1].room, "a, \"b\"");
        assert_eq!(back[1].b.0, 0.333333333);

        let table = RecognitionTable {
            rooms: vec!["H".into(), "T".into()],
            rows: vec![RecognitionRow {
                room: "H".into(),
                test_runs: 5,
                correct: 4,
                recognition_pct: Some(80.0),
                recognised_as: vec![4, 0],
                not_recognised: 1,
            }],
        };
        let text = table.to_csv();
        assert_eq!(
            text,
            "room,test_runs,correct,recognition_pct,as_H,as_T,not_recognised\nH,5,4,80.0,4,0,1\n"
        );
        let path = dir.path().join("recognition.csv");
        std::fs::write(&path, &text).unwrap();
        assert_eq!(RecognitionTable::read(&path).unwrap(), table);
    }

    /// A malformed cell names the file, the line and the column.
    #[test]
    fn generations_with_extra_terms_round_trip_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("generations.csv");
        let text = "generation,best,mean,std,min,max,a,g,l,b,goal,urgency,room\n0,0.500000000,0.250000000,0.100000000,0.000000000,0.500000000,0.100000000,0.200000000,0.000000000,1.000000000,0.750000000,0.125000000,all\n";
        std::fs::write(&path, text).unwrap();
        let rows = read_generations(&path).unwrap();
        let names: Vec<&str> = rows[0].extra.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["goal", "urgency"]);
        assert_eq!(rows[0].extra[1].1, Fixed(0.125));
        assert_eq!(generations_csv(&rows), text);
        let paper: Vec<GenerationRow> = read_csv(&path).unwrap();
        assert!(paper[0].extra.is_empty());
        assert!(
            generations_csv(&paper).starts_with("generation,best,mean,std,min,max,a,g,l,b,room\n")
        );
    }

    #[test]
    fn bad_cells_name_their_column() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("generations.csv");
        std::fs::write(
            &path,
            "generation,best,mean,std,min,max,a,g,l,b,room\n0,0.5,oops,0,0,0.5,1,1,0,1,all\n",
        )
        .unwrap();
        let e = read_csv::<GenerationRow>(&path).unwrap_err();
        assert!(e.is_input(), "{e:?}");
        assert!(
            e.to_string().contains("line 2") && e.to_string().contains("field `mean`"),
            "{e}"
        );
        let path = dir.path().join("recognition.csv");
        std::fs::write(
            &path,
            "room,test_runs,correct,recognition_pct,as_H,not_recognised\nH,5,x,,4,1\n",
        )
        .unwrap();
        let e = RecognitionTable::read(&path).unwrap_err();
        assert!(e.to_string().contains("field `correct`"), "{e}");
    }

    /// A cell that does not parse says what it should hold: a count a whole number, a
    /// percentage a number.
    #[test]
    fn a_bad_cell_says_whether_a_number_or_a_whole_number_is_expected() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("recognition.csv");
        let header = "room,test_runs,correct,recognition_pct,as_H,not_recognised\n";
        std::fs::write(&path, format!("{header}H,5,4.5,80,4,1\n")).unwrap();
        let e = RecognitionTable::read(&path).unwrap_err().to_string();
        assert!(
            e.ends_with("field `correct`: `4.5` is not a whole number"),
            "{e}"
        );
        std::fs::write(&path, format!("{header}H,5,4,most,4,1\n")).unwrap();
        let e = RecognitionTable::read(&path).unwrap_err().to_string();
        assert!(
            e.ends_with("field `recognition_pct`: `most` is not a number"),
            "{e}"
        );
    }

    /// The homing result is `homing_pct` (the weight keeps `homing`); a room row or
    /// a study's table row written under the old name `homing` reads the same.
    #[test]
    fn old_homing_key_reads_as_homing_pct() {
        let row = RoomRow {
            average_fitness: 0.5,
            battery_pct: 90.0,
            exploration_pct: 80.0,
            homing_pct: 62.5,
            r_node: Some(3),
            recognition_pct: None,
            room: "H".into(),
            mission_done_pct: None,
            terms_pct: BTreeMap::new(),
        };
        let new = to_json(&row);
        assert!(new.contains("\"homing_pct\": 62.5") && !new.contains("\"homing\""));
        let old = new.replace("\"homing_pct\"", "\"homing\"");
        assert_eq!(parse_json::<RoomRow>(&old, "old").unwrap(), row);
        assert_eq!(parse_json::<RoomRow>(&new, "new").unwrap(), row);
        let table = TableRow::of(&row);
        let old = to_json(&table).replace("\"homing_pct\"", "\"homing\"");
        assert_eq!(parse_json::<TableRow>(&old, "old").unwrap(), table);
    }

    /// A JSON record with a value of the wrong type names the field's path.
    #[test]
    fn bad_json_fields_are_named() {
        let e =
            parse_json::<BestGenome>(r#"{"shape": {"hidden": "six"}, "weights": []}"#, "g.json")
                .unwrap_err();
        assert!(
            e.to_string().starts_with("g.json: field `shape.hidden`: "),
            "{e}"
        );
        let e = parse_json::<BestGenome>("{", "g.json").unwrap_err();
        assert!(e.to_string().contains("not valid JSON"), "{e}");
    }
}
