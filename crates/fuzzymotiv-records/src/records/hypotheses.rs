//! The records of a study of one's own (`fuzzymotiv study STUDY.toml`): its typed hypotheses
//! ([`Hypothesis`], each over a [`Measure`] of the runs' records), the per-seed values they are
//! judged on (`per_seed.csv`, [`PerSeedRow`]), their results (`claims.csv`, [`ClaimRow`]; per
//! room `rooms.csv`, [`RoomResultRow`]) and the whole (`study.json`, [`StudyRecord`]). A
//! hypothesis's sentence is rendered from its fields ([`Hypothesis::sentence`]); no code reads
//! a sentence back.

use serde::{Deserialize, Serialize};

use crate::records::RoomRow;
use crate::records::test_runs::{metric_term, term_metric};

/// What a hypothesis measures: a column of a run's per-room table (`summary.json`'s `rooms`,
/// `table.md`), its value per seed the mean over the rooms. Written as its column name
/// (`exploration_pct`, `urgency_pct`, …); a study file may also give the short name
/// (`exploration`, `urgency`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "String", into = "String")]
pub enum Measure {
    /// The final population's mean F in the room (`average_fitness`).
    Fitness,
    /// % exploration (100·a) over the test runs.
    Exploration,
    /// % battery (100·b).
    Battery,
    /// % homing (100·g).
    Homing,
    /// % correct recognitions (runs with AEM only).
    Recognition,
    /// % of the test runs whose mission was done (runs that follow missions only).
    MissionDone,
    /// 100·term of a term beyond a, g, l, b (a mission's, e.g. `urgency`, or a user's), by name.
    Term(String),
    /// The population's mean F in the first generation (over the run's evolutions): a value
    /// of the whole run, not of a room ([`FIRST_MEAN_F`]; Fig. 6's "about 0.1").
    FirstMeanF,
    /// How far apart the test runs of the robot standing for a room end: the root-mean-square
    /// distance of their final positions from their centroid, in % of the room's largest
    /// distance (`Experiment::end_spread`, `reproduce --combination`'s "% end spread"). Not in
    /// a run's records: computed from the run read back ([`Measure::read_back`]).
    EndSpread,
    /// The mean step at which the room's test runs completed their mission, T (the trial's
    /// steps) for a test run that never did: lower is sooner (runs that follow missions only;
    /// computed from the run read back, [`Measure::read_back`]).
    TimeToGoal,
    /// One of the [`TRANSFERABLE`] measures of the run's controller transferred to Enki (an
    /// arm with a [`TransferSpec`]): its mean over the Enki test runs in the room
    /// (`enki_homing_pct`).
    Enki(Box<Measure>),
    /// The reality gap of a [`TRANSFERABLE`] measure: |Enki − fuzzymotiv| of the means over
    /// the test runs in each world (`gap_homing_pct`).
    Gap(Box<Measure>),
}

/// The measures a transfer measures in both worlds (`fuzzymotiv transfer`'s measures.csv).
pub const TRANSFERABLE: [Measure; 4] = [
    Measure::Exploration,
    Measure::Homing,
    Measure::Battery,
    Measure::Recognition,
];

/// The measure `name` (a column or a short name) if it is [`TRANSFERABLE`].
fn transferable(name: &str) -> Option<Measure> {
    let m = Measure::parse(name);
    TRANSFERABLE.contains(&m).then_some(m)
}

/// [`Measure::EndSpread`]'s column.
pub const END_SPREAD: &str = "end_spread_pct";
/// [`Measure::TimeToGoal`]'s column.
pub const TIME_TO_GOAL: &str = "time_to_goal";

impl Measure {
    /// The measure a name gives: a column name or its short form; any other name is a term's
    /// (checked against the runs' columns by the study's loader).
    pub fn parse(name: &str) -> Measure {
        match name {
            "average_fitness" | "fitness" => Measure::Fitness,
            "exploration_pct" | "exploration" => Measure::Exploration,
            "battery_pct" | "battery" => Measure::Battery,
            "homing_pct" | "homing" => Measure::Homing,
            "recognition_pct" | "recognition" => Measure::Recognition,
            "mission_done_pct" | "mission_done" => Measure::MissionDone,
            FIRST_MEAN_F => Measure::FirstMeanF,
            END_SPREAD | "end_spread" => Measure::EndSpread,
            TIME_TO_GOAL => Measure::TimeToGoal,
            other => {
                let world = |prefix: &str| other.strip_prefix(prefix).and_then(transferable);
                if let Some(m) = world("enki_") {
                    Measure::Enki(Box::new(m))
                } else if let Some(m) = world("gap_") {
                    Measure::Gap(Box::new(m))
                } else {
                    Measure::Term(metric_term(other).to_string())
                }
            }
        }
    }

    /// Its column in `summary.json`'s rooms and `test_runs.csv`.
    pub fn column(&self) -> String {
        match self {
            Measure::Fitness => "average_fitness".into(),
            Measure::Exploration => "exploration_pct".into(),
            Measure::Battery => "battery_pct".into(),
            Measure::Homing => "homing_pct".into(),
            Measure::Recognition => "recognition_pct".into(),
            Measure::MissionDone => "mission_done_pct".into(),
            Measure::Term(name) => term_metric(name),
            Measure::FirstMeanF => FIRST_MEAN_F.into(),
            Measure::EndSpread => END_SPREAD.into(),
            Measure::TimeToGoal => TIME_TO_GOAL.into(),
            Measure::Enki(m) => format!("enki_{}", m.column()),
            Measure::Gap(m) => format!("gap_{}", m.column()),
        }
    }

    /// Its value in one room of a run (`None` where the run does not measure it).
    pub fn of_room(&self, row: &RoomRow) -> Option<f64> {
        match self {
            Measure::Fitness => Some(row.average_fitness),
            Measure::Exploration => Some(row.exploration_pct),
            Measure::Battery => Some(row.battery_pct),
            Measure::Homing => Some(row.homing_pct),
            Measure::Recognition => row.recognition_pct,
            Measure::MissionDone => row.mission_done_pct,
            Measure::Term(name) => row.terms_pct.get(name).copied(),
            Measure::FirstMeanF
            | Measure::EndSpread
            | Measure::TimeToGoal
            | Measure::Enki(_)
            | Measure::Gap(_) => None,
        }
    }

    /// Whether it has a value per room (every measure but the whole run's [`FIRST_MEAN_F`]).
    pub fn per_room(&self) -> bool {
        *self != Measure::FirstMeanF
    }

    /// Whether its values are not in a run's records but computed from the run read back
    /// (its final population evaluated again, its test runs run again: the same bits as when
    /// it ran): [`Measure::EndSpread`], [`Measure::TimeToGoal`].
    pub fn read_back(&self) -> bool {
        matches!(self, Measure::EndSpread | Measure::TimeToGoal)
    }

    /// How a sentence names it: "the average F", "% exploration", "% urgency", ….
    pub fn label(&self) -> String {
        match self {
            Measure::Fitness => "the average F".into(),
            Measure::Exploration => "% exploration".into(),
            Measure::Battery => "% battery".into(),
            Measure::Homing => "% homing".into(),
            Measure::Recognition => "% recognition".into(),
            Measure::MissionDone => "% missions done".into(),
            Measure::Term(name) => format!("% {name}"),
            Measure::FirstMeanF => "the first generation's mean F".into(),
            Measure::EndSpread => "% end spread".into(),
            Measure::TimeToGoal => "the time to the goal (steps)".into(),
            Measure::Enki(m) => format!("{} in Enki", m.label()),
            Measure::Gap(m) => format!("the gap |Enki − fuzzymotiv| in {}", m.label()),
        }
    }
}

impl From<String> for Measure {
    fn from(name: String) -> Measure {
        Measure::parse(&name)
    }
}

impl From<Measure> for String {
    fn from(m: Measure) -> String {
        m.column()
    }
}

/// Which way a hypothesis says a value goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Higher (a comparison), increasing (a trend).
    #[serde(alias = "increasing")]
    Higher,
    /// Lower, decreasing.
    #[serde(alias = "decreasing")]
    Lower,
}

impl Direction {
    /// `higher` or `lower`.
    pub fn as_str(self) -> &'static str {
        match self {
            Direction::Higher => "higher",
            Direction::Lower => "lower",
        }
    }
}

/// A hypothesis of a study: typed, its sentence rendered from its fields. Read from a study
/// file's `[[hypothesis]]` tables (`kind = "compare"`, …; unknown keys refused).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Hypothesis {
    /// `measure` is `expect` in arm `a` than in arm `b` (paired over seeds).
    Compare {
        /// Its id.
        id: String,
        /// What it measures.
        measure: Measure,
        /// The first arm.
        a: String,
        /// The arm it is compared with.
        b: String,
        /// Higher or lower in `a`.
        expect: Direction,
    },
    /// The paired difference `a` − `b` of `measure` is `expect` than `versus_a` − `versus_b`:
    /// per seed (a − b) − (versus_a − versus_b), a difference of two paired differences (e.g.
    /// a claim's effect under a baseline against its effect under the TSK).
    Difference {
        /// Its id.
        id: String,
        /// What it measures.
        measure: Measure,
        /// The first difference's first arm.
        a: String,
        /// The arm subtracted from `a`.
        b: String,
        /// The second difference's first arm.
        versus_a: String,
        /// The arm subtracted from `versus_a`.
        versus_b: String,
        /// Higher or lower: a − b against versus_a − versus_b.
        expect: Direction,
    },
    /// `measure` goes `expect` (increasing, decreasing) over `arms`, in the order of their
    /// `level`: the per-seed least-squares slope against the level.
    Trend {
        /// Its id.
        id: String,
        /// What it measures.
        measure: Measure,
        /// The arms, each with a `level`.
        arms: Vec<String>,
        /// Increasing or decreasing.
        expect: Direction,
    },
    /// `measure` in `arm` lies between `min` and `max`.
    Range {
        /// Its id.
        id: String,
        /// What it measures.
        measure: Measure,
        /// The arm.
        arm: String,
        /// The lower bound.
        min: f64,
        /// The upper bound.
        max: f64,
    },
    /// The population's mean F in `arm` rises from the first generation to the last.
    Rising {
        /// Its id.
        id: String,
        /// The arm.
        arm: String,
    },
}

/// The measure of a [`Hypothesis::Rising`]: the population's mean F in the first generation
/// and in the last (over the runs of per-room training).
pub const FIRST_MEAN_F: &str = "first_mean_f";
/// See [`FIRST_MEAN_F`].
pub const LAST_MEAN_F: &str = "last_mean_f";

impl Hypothesis {
    /// Its id.
    pub fn id(&self) -> &str {
        match self {
            Hypothesis::Compare { id, .. }
            | Hypothesis::Difference { id, .. }
            | Hypothesis::Trend { id, .. }
            | Hypothesis::Range { id, .. }
            | Hypothesis::Rising { id, .. } => id,
        }
    }

    /// `compare`, `difference`, `trend`, `range` or `rising`.
    pub fn kind(&self) -> &'static str {
        match self {
            Hypothesis::Compare { .. } => "compare",
            Hypothesis::Difference { .. } => "difference",
            Hypothesis::Trend { .. } => "trend",
            Hypothesis::Range { .. } => "range",
            Hypothesis::Rising { .. } => "rising",
        }
    }

    /// The arms it reads, in its order.
    pub fn arms(&self) -> Vec<&str> {
        match self {
            Hypothesis::Compare { a, b, .. } => vec![a, b],
            Hypothesis::Difference {
                a,
                b,
                versus_a,
                versus_b,
                ..
            } => vec![a, b, versus_a, versus_b],
            Hypothesis::Trend { arms, .. } => arms.iter().map(String::as_str).collect(),
            Hypothesis::Range { arm, .. } | Hypothesis::Rising { arm, .. } => vec![arm],
        }
    }

    /// Its measure (none for [`Hypothesis::Rising`], which reads the generations' mean F).
    pub fn measure(&self) -> Option<&Measure> {
        match self {
            Hypothesis::Compare { measure, .. }
            | Hypothesis::Difference { measure, .. }
            | Hypothesis::Trend { measure, .. }
            | Hypothesis::Range { measure, .. } => Some(measure),
            Hypothesis::Rising { .. } => None,
        }
    }

    /// The column `claims.csv` names its measure by.
    pub fn measure_column(&self) -> String {
        self.measure()
            .map_or_else(|| "mean_f".into(), Measure::column)
    }

    /// `higher`, `lower` or `within` (a range).
    pub fn expect_label(&self) -> &'static str {
        match self {
            Hypothesis::Compare { expect, .. }
            | Hypothesis::Difference { expect, .. }
            | Hypothesis::Trend { expect, .. } => expect.as_str(),
            Hypothesis::Range { .. } => "within",
            Hypothesis::Rising { .. } => "higher",
        }
    }

    /// The sentence it states, from its fields.
    pub fn sentence(&self) -> String {
        match self {
            Hypothesis::Compare {
                measure,
                a,
                b,
                expect,
                ..
            } => format!(
                "{} is {} in {a} than in {b}",
                measure.label(),
                expect.as_str()
            ),
            Hypothesis::Difference {
                measure,
                a,
                b,
                versus_a,
                versus_b,
                expect,
                ..
            } => format!(
                "{} in {a} − {b} is {} than in {versus_a} − {versus_b}",
                measure.label(),
                expect.as_str()
            ),
            Hypothesis::Trend {
                measure,
                arms,
                expect,
                ..
            } => {
                let way = match expect {
                    Direction::Higher => "increases",
                    Direction::Lower => "decreases",
                };
                format!("{} {way} over {}", measure.label(), arms.join(" < "))
            }
            Hypothesis::Range {
                measure,
                arm,
                min,
                max,
                ..
            } => format!("{} in {arm} lies between {min} and {max}", measure.label()),
            Hypothesis::Rising { arm, .. } => {
                format!("the mean F in {arm} rises from the first generation to the last")
            }
        }
    }
}

/// How a verdict is reached from a test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Rule {
    /// The project's rule: inconclusive when |effect| is below the minimum detectable
    /// difference, else by p ([`fuzzymotiv::statistics::Comparison::verdict_with_power`]).
    Power,
    /// By p alone ([`fuzzymotiv::statistics::Comparison::verdict`]).
    P,
}

/// Which p-values Holm's method adjusts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HolmOver {
    /// The hypotheses' (in `claims.csv`), within each scope (pooled, each base seed).
    Hypotheses,
    /// Each hypothesis's rooms (in `rooms.csv`).
    Rooms,
    /// None.
    None,
}

/// The analysis a study declares (its `[analysis]` table), stated in its report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AnalysisRecord {
    /// Significance level α.
    pub alpha: f64,
    /// The intervals' coverage.
    pub confidence: f64,
    /// The power of the minimum detectable difference.
    pub power: f64,
    /// The verdict rule.
    pub rule: Rule,
    /// What Holm's method adjusts.
    pub holm: HolmOver,
}

/// One arm of a study as `study.json` records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArmRecord {
    /// Its name.
    pub name: String,
    /// Its config file, as the study file names it.
    pub config: String,
    /// Its overrides (the study's common ones first), as `--set` takes them.
    pub set: Vec<String>,
    /// Its level (the x of a trend), if it has one.
    pub level: Option<f64>,
    /// Whether its evolved robots are also measured in another world, and how.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transfer: Option<TransferSpec>,
}

/// An arm's evolved robots measured in another world (a study file's `transfer` table, of
/// `[study]` or of an `[[arm]]`): each run's controller driven in Enki by `fuzzymotiv
/// transfer` in each of its rooms, giving the [`Measure::Enki`] and [`Measure::Gap`] measures.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransferSpec {
    /// The world: `enki` (the only one).
    pub world: String,
    /// Test runs in Enki per room (`transfer --runs`).
    pub runs: usize,
    /// The rooms transferred (empty: every room of the run).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rooms: Vec<String>,
}

/// One value of `per_seed.csv`: a measure of one run (an arm at a seed) in one room, or over
/// all of them (`room` empty: the mean over the rooms, the value a hypothesis is judged on).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PerSeedRow {
    /// The base seed the seed derives from.
    pub base_seed: u64,
    /// The seed's number at that base seed, from 0.
    pub replicate: usize,
    /// The run's seed (the same in every arm: the arms are paired).
    pub seed: u64,
    /// The arm.
    pub arm: String,
    /// The measure's column ([`Measure::column`], [`FIRST_MEAN_F`], [`LAST_MEAN_F`]).
    pub measure: String,
    /// The room, or empty for the mean over the rooms (or a value of the whole run).
    pub room: String,
    /// The value.
    pub value: f64,
}

/// The pooled scope of a result: every seed of every base seed.
pub const POOLED: &str = "pooled";

/// The scope of a result over one base seed's seeds: `base=N`.
pub fn base_scope(base_seed: u64) -> String {
    format!("base={base_seed}")
}

/// One result of `claims.csv`: a hypothesis judged over one scope's seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimRow {
    /// The hypothesis's id.
    pub id: String,
    /// Its kind.
    pub kind: String,
    /// Its sentence ([`Hypothesis::sentence`]).
    pub sentence: String,
    /// Its measure's column.
    pub measure: String,
    /// Its arms, `;`-separated.
    pub arms: String,
    /// `higher`, `lower` or `within`.
    pub expect: String,
    /// [`POOLED`] or [`base_scope`].
    pub scope: String,
    /// Seeds (pairs) tested.
    pub seeds: usize,
    /// The effect: the mean paired difference (compare, rising), the mean of the per-seed
    /// differences of differences (difference), the mean slope per unit of level (trend) or
    /// the arm's mean (range).
    pub effect: f64,
    /// Lower bound of its bootstrap interval.
    pub ci_low: f64,
    /// Upper bound.
    pub ci_high: f64,
    /// The test's p-value (a range: the larger of its two tests', or the failed side's).
    pub p: f64,
    /// The p-value after Holm's adjustment (`p` when the analysis adjusts none here).
    pub p_adjusted: f64,
    /// The minimum detectable difference (empty with one seed).
    pub mdd: Option<f64>,
    /// `holds`, `opposite`, `not significant` or `inconclusive`.
    pub verdict: String,
}

/// One result of `rooms.csv`: a hypothesis judged in one room over one scope's seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomResultRow {
    /// The hypothesis's id.
    pub id: String,
    /// [`POOLED`] or [`base_scope`].
    pub scope: String,
    /// The room.
    pub room: String,
    /// The effect in this room (as [`ClaimRow::effect`]).
    pub effect: f64,
    /// Lower bound of its interval.
    pub ci_low: f64,
    /// Upper bound.
    pub ci_high: f64,
    /// The p-value.
    pub p: f64,
    /// After Holm's adjustment over the rooms (`p` unless the analysis adjusts rooms).
    pub p_adjusted: f64,
    /// The minimum detectable difference.
    pub mdd: Option<f64>,
    /// The verdict.
    pub verdict: String,
}

/// One row of `arms.csv`: a measure of one arm over one scope's seeds, in one room or over the
/// rooms (room empty: each seed's mean over the rooms, as in `per_seed.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArmMeasureRow {
    /// [`POOLED`] or [`base_scope`].
    pub scope: String,
    /// The arm.
    pub arm: String,
    /// The measure's column (as `per_seed.csv` names it).
    pub measure: String,
    /// The room, or empty for the mean over the rooms (or a value of the whole run).
    pub room: String,
    /// Seeds (runs) the values are over.
    pub seeds: usize,
    /// Their mean.
    pub mean: f64,
    /// Their sample standard deviation (n − 1; empty with one seed).
    pub sd: Option<f64>,
}

/// `study.json`: the study as run and what it found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyRecord {
    /// Always `fuzzymotiv`.
    pub program: String,
    /// The model version of the runs.
    pub model: u32,
    /// The study's name.
    pub name: String,
    /// The analysis.
    pub analysis: AnalysisRecord,
    /// The base seeds.
    pub base_seeds: Vec<u64>,
    /// Seeds per base seed.
    pub seeds: usize,
    /// The arms.
    pub arms: Vec<ArmRecord>,
    /// The hypotheses.
    pub hypotheses: Vec<Hypothesis>,
    /// The results (`claims.csv`).
    pub claims: Vec<ClaimRow>,
    /// The results per room (`rooms.csv`).
    pub rooms: Vec<RoomResultRow>,
    /// Each arm's measures (`arms.csv`): what a study without hypotheses reports.
    #[serde(default)]
    pub measures: Vec<ArmMeasureRow>,
    /// With several base seeds, every hypothesis judged on each base seed's first n seeds
    /// beside its pooled verdict (`agreement.csv`); empty (and not written) with one.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub agreement: Vec<crate::records::agreement::AgreementRow>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hypothesis_reads_from_its_kind_and_refuses_unknown_keys() {
        let h: Hypothesis = toml::from_str(
            "kind = \"compare\"\nid = \"x\"\nmeasure = \"urgency\"\na = \"hi\"\nb = \"lo\"\nexpect = \"higher\"\n",
        )
        .unwrap();
        assert_eq!(h.measure(), Some(&Measure::Term("urgency".into())));
        assert_eq!(h.sentence(), "% urgency is higher in hi than in lo");
        let stray = toml::from_str::<Hypothesis>(
            "kind = \"rising\"\nid = \"x\"\narm = \"hi\"\nmeasure = \"a\"\n",
        );
        assert!(
            stray
                .unwrap_err()
                .to_string()
                .contains("unknown field `measure`")
        );
    }

    #[test]
    fn a_measure_by_short_name_is_its_column() {
        for (name, column) in [
            ("fitness", "average_fitness"),
            ("exploration", "exploration_pct"),
            ("mission_done", "mission_done_pct"),
            ("safety_pct", "safety_pct"),
            ("goal", "goal_pct"),
        ] {
            assert_eq!(Measure::parse(name).column(), column);
        }
    }

    /// A difference of differences reads its four arms from its fields, in order, and states
    /// its sentence from them; end spread and time to the goal are measures by name, read back.
    #[test]
    fn a_difference_names_its_four_arms_and_its_sentence_says_which_is_subtracted() {
        let h: Hypothesis = toml::from_str(
            "kind = \"difference\"\nid = \"d\"\nmeasure = \"homing\"\na = \"high-sum\"\nb = \"low-sum\"\nversus_a = \"high-tsk\"\nversus_b = \"low-tsk\"\nexpect = \"higher\"\n",
        )
        .unwrap();
        assert_eq!(h.arms(), ["high-sum", "low-sum", "high-tsk", "low-tsk"]);
        assert_eq!(
            h.sentence(),
            "% homing in high-sum − low-sum is higher than in high-tsk − low-tsk"
        );
        assert_eq!((h.kind(), h.expect_label()), ("difference", "higher"));
        for (name, m) in [
            ("end_spread", Measure::EndSpread),
            ("end_spread_pct", Measure::EndSpread),
            ("time_to_goal", Measure::TimeToGoal),
        ] {
            assert_eq!(Measure::parse(name), m);
            assert!(m.read_back() && m.per_room() && !Measure::Homing.read_back());
        }
    }

    /// `first_mean_f` is the run's first-generation mean F, a value of the whole run: never a
    /// term's, and with no value per room.
    #[test]
    fn the_first_generation_mean_f_is_a_measure_of_the_whole_run() {
        let m = Measure::parse(FIRST_MEAN_F);
        assert_eq!(m, Measure::FirstMeanF);
        assert_eq!(m.column(), FIRST_MEAN_F);
        assert!(!m.per_room() && Measure::Homing.per_room());
    }

    /// A transferred measure is named by its world and a transferable measure (`enki_homing`,
    /// `gap_exploration_pct`); any other `enki_…` is a term's name.
    #[test]
    fn an_enki_or_gap_measure_is_a_transferable_measure_in_that_world() {
        let homing = Measure::Enki(Box::new(Measure::Homing));
        assert_eq!(Measure::parse("enki_homing"), homing);
        assert_eq!(
            Measure::parse("enki_homing_pct").column(),
            "enki_homing_pct"
        );
        let gap = Measure::parse("gap_exploration_pct");
        assert_eq!(gap, Measure::Gap(Box::new(Measure::Exploration)));
        assert_eq!(gap.label(), "the gap |Enki − fuzzymotiv| in % exploration");
        assert_eq!(
            Measure::parse("enki_urgency"),
            Measure::Term("enki_urgency".into())
        );
        assert!(homing.per_room());
    }
}
