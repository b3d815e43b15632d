//! A study file: its tables read (unknown keys refused) and checked into a typed [`Study`]
//! whose runs are a sweep plan's jobs (arms × base seeds × seeds, the arms paired on each
//! seed). Every error names the file and the field; nothing is run or written before the
//! whole file is checked, every run's config included.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::at_line;
use fuzzymotiv::random::Streams;
use serde::Deserialize;

use crate::files::bounded::{InputKind, read_input};
use crate::files::error::CliError;
use crate::files::inputs::CONFIG;
use crate::pipeline::sweep_plan::{BaseConfig, PlannedJob, Sweep};
use crate::pipeline::transfer::ENKI_MODELS;
use crate::records::extra_terms;
use crate::records::hypotheses::{
    AnalysisRecord, ArmRecord, HolmOver, Hypothesis, Measure, Rule, TRANSFERABLE, TransferSpec,
};

/// A study file, read whole (at most [`crate::files::bounded::TEXT_LIMIT`] bytes).
pub const STUDY_FILE: InputKind = InputKind::text("study file");

/// The name of the study file in a study's output directory.
pub const STUDY_TOML: &str = "study.toml";

/// Most seeds per base seed, and most base seeds.
const MAX_SEEDS: usize = 10_000;

/// Most runs one study may plan (a sweep file's limit).
const MAX_RUNS: usize = 100_000;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    study: RawHeader,
    #[serde(default)]
    analysis: RawAnalysis,
    #[serde(default, rename = "arm")]
    arms: Vec<RawArm>,
    /// Read into [`Hypothesis`] one by one, so that an error names its index.
    #[serde(default, rename = "hypothesis")]
    hypotheses: Vec<toml::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHeader {
    name: String,
    seeds: usize,
    #[serde(default = "first_base")]
    base_seeds: Vec<u64>,
    #[serde(default)]
    config: Option<String>,
    #[serde(default)]
    set: toml::Table,
    /// Measures every arm's runs are reported on (`arms.csv`), beyond those the hypotheses read.
    #[serde(default)]
    measures: Vec<Measure>,
    #[serde(default)]
    transfer: Option<TransferSpec>,
}

/// Most Enki test runs per room of a transfer.
const MAX_TRANSFER_RUNS: usize = 1000;

fn first_base() -> Vec<u64> {
    vec![1]
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct RawAnalysis {
    alpha: f64,
    confidence: f64,
    power: f64,
    rule: Rule,
    holm: HolmOver,
}

impl Default for RawAnalysis {
    fn default() -> RawAnalysis {
        let s = fuzzymotiv::statistics::Settings::default();
        RawAnalysis {
            alpha: s.alpha,
            confidence: s.confidence,
            power: s.power,
            rule: Rule::Power,
            holm: HolmOver::Hypotheses,
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawArm {
    name: String,
    #[serde(default)]
    config: Option<String>,
    #[serde(default)]
    set: toml::Table,
    #[serde(default)]
    level: Option<f64>,
    #[serde(default)]
    transfer: Option<TransferSpec>,
}

/// A checked study: its arms, seeds, analysis and typed hypotheses, and the plan of its runs.
pub struct Study {
    /// Its name.
    pub name: String,
    /// The study file's text (quoted in the report, copied to `study.toml`).
    pub text: String,
    /// The file's path as errors name it.
    pub source: String,
    /// The arms, in the file's order.
    pub arms: Vec<ArmRecord>,
    /// Seeds per base seed.
    pub seeds: usize,
    /// The base seeds (several: a replication, analysed pooled and per base seed).
    pub base_seeds: Vec<u64>,
    /// The declared analysis.
    pub analysis: AnalysisRecord,
    /// The hypotheses, in the file's order.
    pub hypotheses: Vec<Hypothesis>,
    /// The measures `[study] measures` names: every arm's values of them are reported (with
    /// those the hypotheses read), hypotheses or none.
    pub measures: Vec<Measure>,
    /// The runs: arms × base seeds × seeds, as a sweep's jobs (`setting` the arm's name).
    pub plan: Sweep,
}

/// The error of the file `source`'s `field` (a typed [`CliError::StudyFile`]).
fn err(source: &str, field: &str, reason: impl Into<String>) -> CliError {
    CliError::study_file(source, field, reason)
}

impl Study {
    /// Reads and checks a study file; config files are relative to its folder.
    pub fn load(path: &Path) -> Result<Study, CliError> {
        let text = read_input(path, STUDY_FILE)?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::parse_str(&text, &path.display().to_string(), &dir)
    }

    /// Parses and checks a study document whose config files are relative to `dir`.
    pub fn parse_str(text: &str, source: &str, dir: &Path) -> Result<Study, CliError> {
        let raw: RawStudy = toml::from_str(text).map_err(|e| {
            let field = e.span().map_or(String::new(), |s| field_at(text, s.start));
            CliError::input(format!(
                "{source}: {}not a valid study file{}: {}",
                if field.is_empty() {
                    String::new()
                } else {
                    format!("field `{field}`: ")
                },
                at_line(text, e.span()),
                e.message().trim()
            ))
        })?;
        let hypotheses = (raw.hypotheses.iter().enumerate())
            .map(|(i, h)| {
                h.clone().try_into().map_err(|e: toml::de::Error| {
                    err(source, &format!("hypothesis[{i}]"), e.message().trim())
                })
            })
            .collect::<Result<Vec<Hypothesis>, _>>()?;
        let analysis = check_analysis(&raw.analysis, source)?;
        check_header(&raw.study, source)?;
        let arms = check_arms(&raw, source)?;
        let bases = arm_configs(&raw, &arms, dir, source)?;
        let plan = plan(&raw.study, &arms, bases, source)?;
        check_transfers(&raw, &arms, &plan, source)?;
        let study = Study {
            name: raw.study.name.clone(),
            text: text.to_string(),
            source: source.to_string(),
            arms,
            seeds: raw.study.seeds,
            base_seeds: raw.study.base_seeds.clone(),
            analysis,
            hypotheses,
            measures: raw.study.measures.clone(),
            plan,
        };
        study.check_measures()?;
        study.check_hypotheses()?;
        Ok(study)
    }

    /// The index of arm `name`.
    pub fn arm_index(&self, name: &str) -> Option<usize> {
        self.arms.iter().position(|a| a.name == name)
    }

    /// The measures the runs of arm `k` write, by column (the per-room table's).
    fn columns(&self, k: usize) -> Result<Vec<String>, CliError> {
        let job = (self.plan.jobs.iter())
            .find(|j| j.setting == self.arms[k].name)
            .expect("every arm has runs");
        let exp = self.plan.load_job(job)?.experiment;
        let mut known = vec![Measure::Fitness, Measure::Exploration, Measure::Battery];
        known.push(Measure::Homing);
        if exp.aem().enabled() {
            known.push(Measure::Recognition);
        }
        if exp.measures_mission() {
            known.push(Measure::MissionDone);
        }
        known.extend((extra_terms(&exp).into_iter()).map(|(name, _)| Measure::Term(name)));
        known.push(Measure::FirstMeanF);
        known.push(Measure::EndSpread);
        if exp.measures_mission() {
            known.push(Measure::TimeToGoal);
        }
        if self.arms[k].transfer.is_some() {
            let transferred = (TRANSFERABLE.iter())
                .filter(|m| **m != Measure::Recognition || exp.aem().enabled());
            for m in transferred {
                known.push(Measure::Enki(Box::new(m.clone())));
                known.push(Measure::Gap(Box::new(m.clone())));
            }
        }
        Ok(known.iter().map(Measure::column).collect())
    }

    /// `measure` checked against what the runs of `arms` write, naming `field` if not.
    fn check_measure(&self, measure: &Measure, arms: &[&str], field: &str) -> Result<(), CliError> {
        for arm in arms {
            let columns = self.columns(self.arm_index(arm).expect("checked"))?;
            if !columns.contains(&measure.column()) {
                // A term is named as the study file names it (`hurry`, not its column).
                let named = match measure {
                    Measure::Term(name) => name.clone(),
                    other => other.column(),
                };
                let why = format!(
                    "unknown measure `{named}`: the runs of arm `{arm}` write {}",
                    columns.join(", ")
                );
                return Err(err(&self.source, field, why));
            }
        }
        Ok(())
    }

    /// The measures of `[study] measures`: each written by every arm's runs, none twice; a
    /// study needs hypotheses or measures to report.
    fn check_measures(&self) -> Result<(), CliError> {
        if self.hypotheses.is_empty() && self.measures.is_empty() {
            let why = "a study needs at least one [[hypothesis]], or the measures it reports \
                       of each arm (study.measures, e.g. [\"exploration\", \"recognition\"])";
            return Err(err(&self.source, "hypothesis", why));
        }
        let arms: Vec<&str> = self.arms.iter().map(|a| a.name.as_str()).collect();
        for (k, m) in self.measures.iter().enumerate() {
            let field = format!("study.measures[{k}]");
            if self.measures[..k].contains(m) {
                let why = format!("`{}` is listed twice", m.column());
                return Err(err(&self.source, &field, why));
            }
            self.check_measure(m, &arms, &field)?;
        }
        Ok(())
    }

    /// Every hypothesis checked: a unique id, known arms (two different ones to compare, at
    /// least three with levels for a trend), a measure every arm it reads writes.
    fn check_hypotheses(&self) -> Result<(), CliError> {
        let source = &self.source;
        let mut ids = BTreeSet::new();
        for (i, h) in self.hypotheses.iter().enumerate() {
            let at = |f: &str| format!("hypothesis[{i}].{f}");
            check_name(h.id(), source, &at("id"))?;
            if !ids.insert(h.id()) {
                return Err(err(
                    source,
                    &at("id"),
                    format!("`{}` is used twice", h.id()),
                ));
            }
            self.check_arms_of(h, i)?;
            if let Hypothesis::Range { min, max, .. } = h
                && !(min.is_finite() && max.is_finite() && min < max)
            {
                let why = format!("needs min < max, both finite; got {min} and {max}");
                return Err(err(source, &at("min"), why));
            }
            if let Some(measure) = h.measure() {
                self.check_measure(measure, &h.arms(), &at("measure"))?;
            }
        }
        Ok(())
    }

    /// The arms of hypothesis `i` checked.
    fn check_arms_of(&self, h: &Hypothesis, i: usize) -> Result<(), CliError> {
        let source = &self.source;
        let names: Vec<&str> = self.arms.iter().map(|a| a.name.as_str()).collect();
        let field = match h {
            Hypothesis::Compare { .. } => |k: usize| ["a", "b"][k].to_string(),
            Hypothesis::Difference { .. } => {
                |k: usize| ["a", "b", "versus_a", "versus_b"][k].to_string()
            }
            Hypothesis::Trend { .. } => |k: usize| format!("arms[{k}]"),
            _ => |_| "arm".to_string(),
        };
        for (k, arm) in h.arms().into_iter().enumerate() {
            if !names.contains(&arm) {
                let why = format!(
                    "unknown arm `{arm}`; the study's arms: {}",
                    names.join(", ")
                );
                return Err(err(source, &format!("hypothesis[{i}].{}", field(k)), why));
            }
        }
        match h {
            Hypothesis::Compare { a, b, .. } if a == b => Err(err(
                source,
                &format!("hypothesis[{i}].b"),
                format!("compares arm `{a}` with itself: a comparison needs two arms"),
            )),
            Hypothesis::Difference {
                a,
                b,
                versus_a,
                versus_b,
                ..
            } => self.check_difference([a, b, versus_a, versus_b], i),
            Hypothesis::Trend { arms, .. } => self.check_trend(arms, i),
            _ => Ok(()),
        }
    }

    /// A difference's arms: each pair two different arms, and the pairs not the same two.
    fn check_difference(&self, [a, b, c, d]: [&String; 4], i: usize) -> Result<(), CliError> {
        let field = |f: &str| format!("hypothesis[{i}].{f}");
        let within = |x: &str, f: &str| {
            let why = format!(
                "subtracts arm `{x}` from itself: each side of a difference is two different arms"
            );
            Err(err(&self.source, &field(f), why))
        };
        if a == b {
            return within(a, "b");
        }
        if c == d {
            return within(c, "versus_b");
        }
        if (a, b) == (c, d) || (a, b) == (d, c) {
            let why = format!(
                "the difference {c} − {d} is {a} − {b}'s own (or its negative): a difference \
                 compares two different pairs of arms (one pair: use kind = \"compare\")"
            );
            return Err(err(&self.source, &field("versus_a"), why));
        }
        Ok(())
    }

    /// A trend's arms: at least three, different, each with a `level`, the levels different.
    fn check_trend(&self, arms: &[String], i: usize) -> Result<(), CliError> {
        let source = &self.source;
        let field = format!("hypothesis[{i}].arms");
        let distinct: BTreeSet<&String> = arms.iter().collect();
        if distinct.len() < 3 || distinct.len() != arms.len() {
            let why = "a trend needs at least three different arms (two: use kind = \"compare\")";
            return Err(err(source, &field, why));
        }
        let mut levels = Vec::new();
        for name in arms {
            let arm = &self.arms[self.arm_index(name).expect("checked")];
            let Some(level) = arm.level else {
                let why = format!(
                    "arm `{name}` has no `level`: a trend is over ordered arms (give each a level, e.g. level = 0.3)"
                );
                return Err(err(source, &field, why));
            };
            if levels.contains(&level) {
                let why = format!("two arms have level {level}: a trend needs different levels");
                return Err(err(source, &field, why));
            }
            levels.push(level);
        }
        Ok(())
    }
}

/// The dotted path of the key at byte `at` of a study file: the table it is in (`analysis`,
/// `arm[1]` for the second `[[arm]]`) and the key, when `at` starts one (else the table).
fn field_at(text: &str, at: usize) -> String {
    let before = &text[..at.min(text.len())];
    let mut table = String::new();
    let mut counts: std::collections::BTreeMap<String, usize> = Default::default();
    for line in before.lines().map(str::trim) {
        if let Some(name) = line.strip_prefix("[[").and_then(|l| l.split("]]").next()) {
            let k = counts.entry(name.trim().to_string()).or_insert(0);
            table = format!("{}[{k}]", name.trim());
            *k += 1;
        } else if let Some(name) = line.strip_prefix('[').and_then(|l| l.split(']').next()) {
            table = name.trim().to_string();
        }
    }
    let rest = &text[at.min(text.len())..];
    let key: String = (rest.chars())
        .take_while(|c| c.is_ascii_alphanumeric() || "_-.\"".contains(*c))
        .collect();
    let starts_line = before
        .rsplit('\n')
        .next()
        .is_some_and(|l| l.trim().is_empty());
    match (table.is_empty(), starts_line && !key.is_empty()) {
        (_, false) => table,
        (true, true) => key,
        (false, true) => format!("{table}.{key}"),
    }
}

/// A name (arm, hypothesis id): letters, digits, `_`, `-` and `.`, at most 64 characters.
fn check_name(name: &str, source: &str, field: &str) -> Result<(), CliError> {
    let ok = (1..=64).contains(&name.len())
        && (name.chars()).all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
    if ok {
        Ok(())
    } else {
        let why = format!("`{name}`: use 1 to 64 letters, digits, `_`, `-` or `.`");
        Err(err(source, field, why))
    }
}

fn check_analysis(a: &RawAnalysis, source: &str) -> Result<AnalysisRecord, CliError> {
    for (name, v) in [
        ("alpha", a.alpha),
        ("confidence", a.confidence),
        ("power", a.power),
    ] {
        if !(v > 0.0 && v < 1.0) {
            let why = format!("must be between 0 and 1 (exclusive), got {v}");
            return Err(err(source, &format!("analysis.{name}"), why));
        }
    }
    Ok(AnalysisRecord {
        alpha: a.alpha,
        confidence: a.confidence,
        power: a.power,
        rule: a.rule,
        holm: a.holm,
    })
}

fn check_header(h: &RawHeader, source: &str) -> Result<(), CliError> {
    check_name(&h.name, source, "study.name")?;
    if h.seeds == 0 || h.seeds > MAX_SEEDS {
        let why = format!("must be in 1..={MAX_SEEDS}, got {}", h.seeds);
        return Err(err(source, "study.seeds", why));
    }
    let distinct: BTreeSet<u64> = h.base_seeds.iter().copied().collect();
    if h.base_seeds.is_empty() || h.base_seeds.len() > MAX_SEEDS {
        let why = "give one base seed, or several for a replication";
        return Err(err(source, "study.base_seeds", why));
    }
    if distinct.len() != h.base_seeds.len() {
        return Err(err(
            source,
            "study.base_seeds",
            "a base seed is listed twice",
        ));
    }
    Ok(())
}

/// The arms as records: names checked (unique), overrides flattened (the study's first).
fn check_arms(raw: &RawStudy, source: &str) -> Result<Vec<ArmRecord>, CliError> {
    if raw.arms.is_empty() {
        return Err(err(source, "arm", "a study needs at least one [[arm]]"));
    }
    let common = overrides(&raw.study.set, "study.set", source)?;
    let mut arms: Vec<ArmRecord> = Vec::new();
    for (k, arm) in raw.arms.iter().enumerate() {
        check_name(&arm.name, source, &format!("arm[{k}].name"))?;
        if arms.iter().any(|a| a.name == arm.name) {
            let why = format!("`{}` is used twice", arm.name);
            return Err(err(source, &format!("arm[{k}].name"), why));
        }
        if arm.level.is_some_and(|l| !l.is_finite()) {
            return Err(err(
                source,
                &format!("arm[{k}].level"),
                "must be a finite number",
            ));
        }
        let config =
            (arm.config.clone().or_else(|| raw.study.config.clone())).ok_or_else(|| {
                err(
                    source,
                    &format!("arm[{k}].config"),
                    "no config: give the arm one, or the study a default (study.config)",
                )
            })?;
        let mut set = common.clone();
        set.extend(overrides(&arm.set, &format!("arm[{k}].set"), source)?);
        let transfer = arm.transfer.clone().or_else(|| raw.study.transfer.clone());
        if let Some(t) = &transfer {
            check_transfer(t, &transfer_field(raw, k), source)?;
        }
        arms.push(ArmRecord {
            name: arm.name.clone(),
            config,
            set,
            level: arm.level,
            transfer,
        });
    }
    Ok(arms)
}

/// Where arm `k`'s transfer is declared: `arm[k].transfer`, or the study's.
fn transfer_field(raw: &RawStudy, k: usize) -> String {
    if raw.arms[k].transfer.is_some() {
        format!("arm[{k}].transfer")
    } else {
        "study.transfer".into()
    }
}

/// A transfer's world and runs.
fn check_transfer(t: &TransferSpec, field: &str, source: &str) -> Result<(), CliError> {
    if t.world != "enki" {
        let why = format!(
            "unknown world `{}`: the robots transfer to `enki` (fuzzymotiv transfer)",
            t.world
        );
        return Err(err(source, &format!("{field}.world"), why));
    }
    if t.runs == 0 || t.runs > MAX_TRANSFER_RUNS {
        let why = format!(
            "must be in 1..={MAX_TRANSFER_RUNS} Enki test runs per room, got {}",
            t.runs
        );
        return Err(err(source, &format!("{field}.runs"), why));
    }
    Ok(())
}

/// Every transferring arm's runs: a robot Enki has a model of, and the rooms named are the
/// run's (its first run's config, the arm's overrides applied).
fn check_transfers(
    raw: &RawStudy,
    arms: &[ArmRecord],
    plan: &Sweep,
    source: &str,
) -> Result<(), CliError> {
    for (k, arm) in arms.iter().enumerate() {
        let Some(t) = &arm.transfer else { continue };
        let field = transfer_field(raw, k);
        let job = (plan.jobs.iter())
            .find(|j| j.setting == arm.name)
            .expect("every arm has runs");
        let exp = plan.load_job(job)?.experiment;
        let robot = exp.trial_params().robot().spec().name().to_string();
        if !ENKI_MODELS.iter().any(|m| m.robot == robot) {
            let models: Vec<&str> = ENKI_MODELS.iter().map(|m| m.robot).collect();
            let why = format!(
                "arm `{}` runs the robot `{robot}`, which Enki has no model of (it has {})",
                arm.name,
                models.join(", ")
            );
            return Err(err(source, &field, why));
        }
        let rooms: Vec<String> = (exp.arenas().iter())
            .map(|a| a.room().name.clone())
            .collect();
        for (i, room) in t.rooms.iter().enumerate() {
            if !rooms.contains(room) {
                let why = format!(
                    "`{room}` is not a room of arm `{}`'s runs (they have {})",
                    arm.name,
                    rooms.join(", ")
                );
                return Err(err(source, &format!("{field}.rooms[{i}]"), why));
            }
        }
    }
    Ok(())
}

/// A `set` table as `--set` overrides (`key=value`), nested tables flattened to dotted keys.
fn overrides(table: &toml::Table, field: &str, source: &str) -> Result<Vec<String>, CliError> {
    let mut out = Vec::new();
    for (key, value) in table {
        match value {
            toml::Value::Table(inner) => {
                let nested = overrides(inner, &format!("{field}.{key}"), source)?;
                out.extend(nested.into_iter().map(|o| format!("{key}.{o}")));
            }
            _ if key == "seed" => {
                let why = "the seeds are the study's (study.seeds, study.base_seeds)";
                return Err(err(source, &format!("{field}.seed"), why));
            }
            v => out.push(format!("{key}={v}")),
        }
    }
    Ok(out)
}

/// Each arm's config (read relative to `dir`).
fn arm_configs(
    raw: &RawStudy,
    arms: &[ArmRecord],
    dir: &Path,
    source: &str,
) -> Result<Vec<BaseConfig>, CliError> {
    let mut bases = Vec::new();
    for (k, arm) in arms.iter().enumerate() {
        let path: PathBuf = dir.join(&arm.config);
        let field = if raw.arms[k].config.is_some() {
            format!("arm[{k}].config")
        } else {
            "study.config".to_string()
        };
        let text = read_input(&path, CONFIG)
            .map_err(|e| err(source, &field, format!("`{}`: {e}", arm.config)))?;
        bases.push(BaseConfig {
            text,
            source: format!("{source}: arm `{}` ({})", arm.name, path.display()),
            dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
        });
    }
    Ok(bases)
}

/// The runs: for each base seed and seed, every arm at that seed (the study's paired seeds,
/// [`Streams::study`], as `reproduce` derives them).
fn plan(
    h: &RawHeader,
    arms: &[ArmRecord],
    bases: Vec<BaseConfig>,
    source: &str,
) -> Result<Sweep, CliError> {
    let runs = (arms.len())
        .saturating_mul(h.base_seeds.len())
        .saturating_mul(h.seeds);
    if runs > MAX_RUNS {
        let why = format!(
            "{runs} runs planned (arms × base seeds × seeds); at most {MAX_RUNS} per study file"
        );
        return Err(err(source, "study.seeds", why));
    }
    let mut jobs = Vec::new();
    for &base in &h.base_seeds {
        for rep in 0..h.seeds {
            let seed = Streams::new(base).study(rep);
            for (k, arm) in arms.iter().enumerate() {
                jobs.push(PlannedJob {
                    base: k,
                    key: format!("{};base={base};rep={rep}", arm.name),
                    setting: arm.name.clone(),
                    replicate: rep,
                    seed,
                    overrides: arm.set.clone(),
                });
            }
        }
    }
    Sweep::of_jobs(bases, jobs, source, STUDY_TOML)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(study: &str) -> Result<Study, CliError> {
        let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
        let text = format!(
            "{study}\n[[arm]]\nname = \"a\"\n[[arm]]\nname = \"b\"\nset = {{ \"ga.population\" = 4 }}\n[[hypothesis]]\nid = \"h\"\nkind = \"rising\"\narm = \"a\"\n"
        );
        Study::parse_str(&text, "s.toml", &configs)
    }

    #[test]
    fn a_study_of_too_many_runs_is_refused_before_any_is_planned() {
        let bases: Vec<String> = (0..20).map(|b| b.to_string()).collect();
        let header = format!(
            "[study]\nname = \"big\"\nseeds = 10000\nbase_seeds = [{}]\nconfig = \"tiny.toml\"",
            bases.join(", ")
        );
        let started = std::time::Instant::now();
        let Err(e) = parse(&header) else {
            panic!("400000 runs planned");
        };
        assert!(e.to_string().contains("400000 runs planned"), "{e}");
        assert!(started.elapsed().as_secs() < 5, "refused before planning");
    }

    /// Issue #56: a study file's bad value is a typed error (the file and the field as data),
    /// bad input (exit 2), worded as before.
    #[test]
    fn a_bad_study_value_is_a_typed_study_file_error() {
        let header = "[study]\nname = \"p\"\nseeds = 0\nbase_seeds = [1]\nconfig = \"tiny.toml\"";
        let Err(e) = parse(header) else {
            panic!("seeds = 0 is refused");
        };
        assert!(e.is_input(), "{e:?}");
        let CliError::StudyFile(f) = &e else {
            panic!("not a study file error: {e:?}");
        };
        assert_eq!(
            (f.source_name.as_str(), f.field.as_str()),
            ("s.toml", "study.seeds")
        );
        assert!(
            e.to_string().starts_with("s.toml: field `study.seeds`: "),
            "{e}"
        );
    }

    #[test]
    fn paired_arms_share_each_seed_and_the_seeds_are_reproduces() {
        let study =
            parse("[study]\nname = \"p\"\nseeds = 2\nbase_seeds = [1, 7]\nconfig = \"tiny.toml\"")
                .unwrap();
        let seeds: Vec<(&str, u64)> = (study.plan.jobs.iter())
            .map(|j| (j.setting.as_str(), j.seed))
            .collect();
        let s = |b: u64, k: usize| Streams::new(b).study(k);
        assert_eq!(
            seeds,
            [
                ("a", s(1, 0)),
                ("b", s(1, 0)),
                ("a", s(1, 1)),
                ("b", s(1, 1)),
                ("a", s(7, 0)),
                ("b", s(7, 0)),
                ("a", s(7, 1)),
                ("b", s(7, 1))
            ]
        );
    }
}
