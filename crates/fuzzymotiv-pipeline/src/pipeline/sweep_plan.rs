//! Sweep files: `plan` expands a `[sweep]` table into a stable list of jobs.
//!
//! A job's seed derives from the base seed and the job's key (its motivation point, grid values
//! and replicate), never from its position in a shard, and its id is a hash of its fully
//! resolved config, so any batch scheduler can run any subset in any order.

use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};

use fuzzymotiv::experiment::{RawConfig, at_line};
use fuzzymotiv::fitness::PAPER_MOTIVATIONS as MOTIVATIONS;
use fuzzymotiv::random::{Streams, hash_str};
use serde::Deserialize;

use crate::files::bounded::{InputKind, read_input};
use crate::files::error::CliError;
use crate::files::inputs::{Loaded, ROBOT_FILE, ROOM_FILE, load_robot, resolve};
use crate::records::Job;

/// The `[sweep]` table.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    /// Replicates (seeds) per point; default 1.
    #[serde(default = "one")]
    replicates: usize,
    /// Explicit motivation points: `[C, H, O, E]`, one weight per motivation of the base
    /// config in its order, or `{ name = weight, … }` (the others keep the base config's).
    #[serde(default)]
    motivations: Vec<toml::Value>,
    /// All motivation points on a simplex grid.
    #[serde(default)]
    simplex: Option<RawSimplex>,
    /// Cartesian product over other config keys: dotted key → list of values.
    #[serde(default)]
    grid: toml::Table,
}

fn one() -> usize {
    1
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSimplex {
    /// Grid step, e.g. 0.1 (1/step must be an integer).
    step: f64,
    /// Motivations held fixed, e.g. { orientation = 0.0 }; the others vary.
    #[serde(default)]
    fixed: BTreeMap<String, f64>,
    /// The motivations that vary, by name (any of the base config's); the others keep their
    /// `fixed` value, else the base config's weight. Without it, every motivation not fixed
    /// varies.
    #[serde(default)]
    over: Option<Vec<String>>,
}

/// A motivation point: one weight per motivation of the base config, in its order.
type Point = Vec<(String, f64)>;

/// The base config's motivations: names in input order, their weights, and whether each is
/// written as a table (then a sweep sets `motivations.NAME.weight`).
struct BaseMotivations {
    names: Vec<String>,
    weights: Vec<f64>,
    tables: Vec<bool>,
}

impl BaseMotivations {
    fn of(base: &RawConfig) -> BaseMotivations {
        let list = &base.motivations.list;
        BaseMotivations {
            names: list.iter().map(|(n, _)| n.clone()).collect(),
            weights: list.iter().map(|(_, m)| m.weight()).collect(),
            tables: (list.iter())
                .map(|(_, m)| matches!(m, fuzzymotiv::fitness::RawMotivation::Table(_)))
                .collect(),
        }
    }

    /// Whether they are the paper's four, in its order (then settings keep their old names).
    fn is_paper(&self) -> bool {
        self.names == MOTIVATIONS
    }

    /// The `--set` key of motivation `k`'s weight.
    fn key(&self, k: usize) -> String {
        let name = &self.names[k];
        if self.tables[k] {
            format!("motivations.{name}.weight")
        } else {
            format!("motivations.{name}")
        }
    }
}

/// Most jobs one sweep file may plan.
const MAX_JOBS: usize = 100_000;

/// A config a plan's jobs are made from: its text (a sweep file's without its `[sweep]`
/// table), the name its errors give it and the folder its room and robot files are relative to.
#[derive(Debug, Clone)]
pub struct BaseConfig {
    /// The config's TOML text.
    pub text: String,
    /// Where it came from, as errors name it (e.g. the file's path).
    pub source: String,
    /// The folder its room and robot files are relative to.
    pub dir: PathBuf,
}

/// A job of a plan given one by one ([`Sweep::of_jobs`], e.g. a study's arm and seed).
#[derive(Debug, Clone)]
pub struct PlannedJob {
    /// Its config: an index into the plan's [`BaseConfig`]s.
    pub base: usize,
    /// Its key (unique in the plan).
    pub key: String,
    /// Its setting (the key without the replicate).
    pub setting: String,
    /// Its replicate number.
    pub replicate: usize,
    /// Its seed (set as `seed=` after `overrides`).
    pub seed: u64,
    /// The `--set` overrides that make its config from its base (without the seed).
    pub overrides: Vec<String>,
}

/// A parsed sweep: the base configs, the file the plan comes from and the jobs.
pub struct Sweep {
    bases: Vec<BaseConfig>,
    /// The base config of each job, by plan index.
    job_base: Vec<usize>,
    source: String,
    /// The name of the plan's file in its output directory (`sweep.toml`, `study.toml`).
    file_name: &'static str,
    /// The jobs, in plan order.
    pub jobs: Vec<Job>,
    /// The notes of its configs, for the front to show (e.g. that the motivations were
    /// normalised): those of the first job that has any (the others say the same of theirs).
    pub notes: Vec<String>,
}

/// The error of the file `source`'s `field` (a typed [`CliError::StudyFile`]).
fn err(source: &str, field: &str, reason: impl Into<String>) -> CliError {
    CliError::study_file(source, field, reason)
}

fn fmt_value(v: f64) -> String {
    // Shortest representation that round-trips, always with a decimal point for TOML floats.
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// A sweep file, read whole (at most [`crate::files::bounded::TEXT_LIMIT`] bytes).
pub const SWEEP_FILE: InputKind = InputKind::text("sweep file");

impl Sweep {
    /// Reads a sweep file and expands its jobs (each validated as a config).
    pub fn load(path: &Path) -> Result<Sweep, CliError> {
        let text = read_input(path, SWEEP_FILE)?;
        let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::parse_str(&text, &path.display().to_string(), &base_dir)
    }

    /// Parses a sweep document; room files are relative to `base_dir`.
    pub fn parse_str(text: &str, source: &str, base_dir: &Path) -> Result<Sweep, CliError> {
        let (raw, base_text) = split_sweep(text, source)?;
        let base = RawConfig::parse(&base_text, source, &[])?;
        if raw.replicates == 0 || raw.replicates > 100_000 {
            return Err(err(
                source,
                "sweep.replicates",
                format!("must be in 1..=100000, got {}", raw.replicates),
            ));
        }
        let motivations = BaseMotivations::of(&base);
        let points = motivation_points(&raw, &motivations, source)?;
        let combos = grid_combinations(&raw.grid, source)?;
        let planned = points
            .len()
            .saturating_mul(combos.len())
            .saturating_mul(raw.replicates);
        if planned > MAX_JOBS {
            return Err(err(
                source,
                "sweep",
                format!(
                    "{planned} jobs planned; at most {MAX_JOBS} per sweep file (split it, or use a coarser step)"
                ),
            ));
        }
        let mut sweep = Sweep {
            bases: vec![BaseConfig {
                text: base_text,
                source: source.to_string(),
                dir: base_dir.to_path_buf(),
            }],
            job_base: Vec::new(),
            source: source.to_string(),
            file_name: "sweep.toml",
            jobs: Vec::new(),
            notes: Vec::new(),
        };
        let mut seen = HashSet::new();
        for point in &points {
            for combo in &combos {
                let (setting, overrides) = setting_of(&motivations, point.as_ref(), combo);
                // The same point listed twice (e.g. explicitly and by the simplex): once.
                if seen.insert(setting.clone()) {
                    sweep.add_replicates(&setting, &overrides, raw.replicates, base.seed)?;
                }
            }
        }
        // Validate every job now, so a bad point fails before anything runs.
        let mut notes = Vec::new();
        for job in &sweep.jobs {
            let loaded = sweep.load_job(job)?;
            if notes.is_empty() {
                notes = loaded.notes;
            }
        }
        sweep.notes = notes;
        Ok(sweep)
    }

    /// Fills the values `raw` leaves to its robot file (as [`fuzzymotiv::experiment::Setup`]
    /// records them); the robot file's text when it is a file (relative to the sweep file),
    /// empty for a built-in robot.
    fn resolve_robot(base_dir: &Path, raw: &mut RawConfig) -> Result<String, CliError> {
        use fuzzymotiv::simulation::RobotSpec;
        let (spec, text) = match raw.robot.file.as_deref() {
            None => (RobotSpec::khepera(), String::new()),
            Some(name) => match RobotSpec::builtin(name) {
                Some(spec) => (spec, String::new()),
                None => {
                    let path = base_dir.join(name);
                    let spec = load_robot(&path.display().to_string(), "robot.file")?;
                    (spec, read_input(&path, ROBOT_FILE)?)
                }
            },
        };
        raw.robot = raw.robot.resolved(spec);
        raw.trial = raw.trial.resolved(spec);
        Ok(text)
    }

    /// Adds the `replicates` jobs of one setting, each with its seed derived from its key.
    fn add_replicates(
        &mut self,
        setting: &str,
        overrides: &[String],
        replicates: usize,
        base_seed: u64,
    ) -> Result<(), CliError> {
        for rep in 0..replicates {
            let key = format!("{setting};rep={rep}");
            // Keep the derived seed in 0..2^53: exact in TOML (signed 64-bit) and in JSON read
            // as doubles (JavaScript, jq).
            let seed = Streams::new(base_seed).sweep_job(&key);
            self.add_job(PlannedJob {
                base: 0,
                key,
                setting: setting.to_string(),
                replicate: rep,
                seed,
                overrides: overrides.to_vec(),
            })?;
        }
        Ok(())
    }

    /// Adds one job, its id the hash of its resolved config.
    fn add_job(&mut self, planned: PlannedJob) -> Result<(), CliError> {
        let base = &self.bases[planned.base];
        let mut sets = planned.overrides;
        sets.push(format!("seed={}", planned.seed));
        let source = format!("{} (job {})", base.source, planned.key);
        let mut raw = RawConfig::parse(&base.text, &source, &sets)?;
        // The id covers the resolved config and the contents of its room and robot files,
        // so an edited file is a new job rather than a finished one (the model version is
        // the plan's: `Job::model`); the robot's values are in the config as a run records
        // them (the Khepera's jobs keep the ids they had before robots were files).
        let robot_file = Self::resolve_robot(&base.dir, &mut raw)?;
        let mut resolved = raw.to_toml();
        for room in &raw.rooms {
            if let Ok(text) = read_input(&base.dir.join(room), ROOM_FILE) {
                resolved.push_str(&text);
            }
        }
        resolved.push_str(&robot_file);
        self.job_base.push(planned.base);
        self.jobs.push(Job {
            index: self.jobs.len(),
            id: format!("{:016x}", hash_str(&resolved)),
            key: planned.key,
            setting: planned.setting,
            replicate: planned.replicate,
            seed: planned.seed,
            overrides: sets,
            model: fuzzymotiv::MODEL_VERSION,
        });
        Ok(())
    }

    /// A plan of `jobs` given one by one over the configs `bases` (a study's arms and seeds),
    /// whose file is `file_name` in its output directory (`source` names it in errors). Every
    /// job is validated as a config; two jobs of the same config (the same id) are refused.
    pub fn of_jobs(
        bases: Vec<BaseConfig>,
        jobs: Vec<PlannedJob>,
        source: &str,
        file_name: &'static str,
    ) -> Result<Sweep, CliError> {
        let mut sweep = Sweep {
            bases,
            job_base: Vec::new(),
            source: source.to_string(),
            file_name,
            jobs: Vec::new(),
            notes: Vec::new(),
        };
        for job in jobs {
            sweep.add_job(job)?;
        }
        let mut notes = Vec::new();
        for (k, job) in sweep.jobs.iter().enumerate() {
            if let Some(twin) = sweep.jobs[..k].iter().find(|j| j.id == job.id) {
                return Err(CliError::input(format!(
                    "{source}: jobs `{}` and `{}` have the same config (the same seed, config \
                     and overrides): give them different settings",
                    twin.key, job.key
                )));
            }
            let loaded = sweep.load_job(job)?;
            if notes.is_empty() {
                notes = loaded.notes;
            }
        }
        sweep.notes = notes;
        Ok(sweep)
    }

    /// The name of the plan's file in its output directory: `sweep.toml` for a sweep file.
    pub fn file_name(&self) -> &'static str {
        self.file_name
    }

    /// Where the plan comes from, as its errors name it.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The validated config of a job.
    pub fn load_job(&self, job: &Job) -> Result<Loaded, CliError> {
        // A job of another plan (read from a file) counts as one of the first config's.
        let base = &self.bases[self.job_base.get(job.index).copied().unwrap_or(0)];
        let source = format!("{} (job {})", base.source, job.key);
        let raw = RawConfig::parse(&base.text, &source, &job.overrides)?;
        resolve(raw, &base.dir, &source)
    }

    /// The plan as JSON lines.
    pub fn plan_jsonl(&self) -> String {
        self.jobs
            .iter()
            .map(|j| serde_json::to_string(j).expect("records serialise") + "\n")
            .collect()
    }
}

/// The `[sweep]` table and the rest of the document (the base config) as TOML text.
fn split_sweep(text: &str, source: &str) -> Result<(RawSweep, String), CliError> {
    let mut table: toml::Table = toml::from_str(text).map_err(|e| {
        err(
            source,
            "(document)",
            format!(
                "not valid TOML{}: {}",
                at_line(text, e.span()),
                e.message().trim()
            ),
        )
    })?;
    let sweep_value = table.remove("sweep").ok_or_else(|| {
        err(
            source,
            "sweep",
            "a sweep file needs a [sweep] table (replicates, motivations, simplex, grid)",
        )
    })?;
    let sweep: RawSweep = sweep_value
        .try_into()
        .map_err(|e: toml::de::Error| err(source, "sweep", e.message().trim().to_string()))?;
    Ok((sweep, toml::to_string(&table).expect("a table serialises")))
}

/// The motivation points (explicit, then the simplex's), or one "no point" when none.
fn motivation_points(
    sweep: &RawSweep,
    base: &BaseMotivations,
    source: &str,
) -> Result<Vec<Option<Point>>, CliError> {
    let mut points: Vec<Point> = (sweep.motivations.iter().enumerate())
        .map(|(i, v)| explicit_point(v, base, &format!("sweep.motivations[{i}]"), source))
        .collect::<Result<_, _>>()?;
    if let Some(simplex) = &sweep.simplex {
        points.extend(simplex_points(simplex, base, source)?);
    }
    Ok(if points.is_empty() {
        vec![None]
    } else {
        points.into_iter().map(Some).collect()
    })
}

/// One explicit point: a list of weights (the paper's four, or one per motivation of the base
/// config, in its order) or a table of weights by name (the others keep the base config's).
fn explicit_point(
    value: &toml::Value,
    base: &BaseMotivations,
    field: &str,
    source: &str,
) -> Result<Point, CliError> {
    let weight = |v: &toml::Value, at: &str| -> Result<f64, CliError> {
        match v {
            toml::Value::Float(x) if x.is_finite() => Ok(*x),
            toml::Value::Integer(x) => Ok(*x as f64),
            _ => Err(err(
                source,
                at,
                format!("expected a weight (a number), got {v}"),
            )),
        }
    };
    let known = base.names.join(", ");
    match value {
        toml::Value::Array(list) => {
            let names: Vec<&str> = match list.len() {
                n if n == base.names.len() => base.names.iter().map(String::as_str).collect(),
                4 => MOTIVATIONS.to_vec(),
                n => {
                    let why = format!(
                        "{n} weights; give 4 (curiosity, homing, orientation, energy) or one per motivation of the config ({known}), or name them: {{ curiosity = 0.5, … }}"
                    );
                    return Err(err(source, field, why));
                }
            };
            (names.iter().zip(list).enumerate())
                .map(|(j, (n, v))| Ok((n.to_string(), weight(v, &format!("{field}[{j}]"))?)))
                .collect()
        }
        toml::Value::Table(table) if !table.is_empty() => {
            let mut point = Vec::new();
            // In the base config's order, so that a point's name does not depend on how the
            // sweep file lists it.
            for name in &base.names {
                if let Some(v) = table.get(name) {
                    point.push((name.clone(), weight(v, &format!("{field}.{name}"))?));
                }
            }
            if let Some(stray) = table.keys().find(|k| !base.names.contains(k)) {
                let why = format!("the config has no motivation {stray:?}; it has {known}");
                return Err(err(source, &format!("{field}.{stray}"), why));
            }
            Ok(point)
        }
        _ => Err(err(
            source,
            field,
            format!(
                "expected a list of weights [C, H, O, E] or a table {{ name = weight, … }}, got {value}"
            ),
        )),
    }
}

/// Every combination of the `[sweep.grid]` values, as (key, value) lists in key order.
fn grid_combinations(
    grid: &toml::Table,
    source: &str,
) -> Result<Vec<Vec<(String, toml::Value)>>, CliError> {
    let mut combos: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for (key, values) in grid {
        let list = values.as_array().filter(|a| !a.is_empty()).ok_or_else(|| {
            err(
                source,
                &format!("sweep.grid.{key}"),
                "must be a non-empty list of values",
            )
        })?;
        combos = combos
            .into_iter()
            .flat_map(|c| {
                list.iter().map(move |v| {
                    let mut c = c.clone();
                    c.push((key.clone(), v.clone()));
                    c
                })
            })
            .collect();
    }
    Ok(combos)
}

/// A setting's name (e.g. `C=0.8,H=0.1,O=0,E=0.1;trial.noise=0.06`, or `base`) and its
/// `--set` overrides.
/// A point over other motivations than the paper's four is named `name=weight,…`.
fn setting_of(
    base: &BaseMotivations,
    point: Option<&Point>,
    combo: &[(String, toml::Value)],
) -> (String, Vec<String>) {
    let mut overrides = Vec::new();
    let mut parts = Vec::new();
    if let Some(p) = point {
        let named: Vec<&str> = p.iter().map(|(n, _)| n.as_str()).collect();
        for (name, v) in p {
            let key = (base.names.iter().position(|n| n == name))
                .map_or_else(|| format!("motivations.{name}"), |k| base.key(k));
            overrides.push(format!("{key}={}", fmt_value(*v)));
        }
        if named == MOTIVATIONS {
            let w: Vec<f64> = p.iter().map(|(_, v)| *v).collect();
            parts.push(format!("C={},H={},O={},E={}", w[0], w[1], w[2], w[3]));
        } else {
            let each: Vec<String> = p.iter().map(|(n, v)| format!("{n}={v}")).collect();
            parts.push(each.join(","));
        }
    }
    for (k, v) in combo {
        overrides.push(format!("{k}={v}"));
        parts.push(format!("{k}={v}"));
    }
    let setting = if parts.is_empty() {
        "base".to_string()
    } else {
        parts.join(";")
    };
    (setting, overrides)
}

/// The motivation points of a simplex grid over the base config's motivations.
fn simplex_points(
    s: &RawSimplex,
    base: &BaseMotivations,
    source: &str,
) -> Result<Vec<Point>, CliError> {
    let n = simplex_divisions(s.step, source)?;
    let fixed = fixed_units(s, base, n, source)?;
    let fixed_units: usize = fixed.iter().flatten().sum();
    if fixed_units > n {
        return Err(err(
            source,
            "sweep.simplex.fixed",
            "fixed motivations sum to more than 1",
        ));
    }
    let free: Vec<usize> = (0..fixed.len()).filter(|&i| fixed[i].is_none()).collect();
    let mut units: Vec<usize> = fixed.iter().map(|f| f.unwrap_or(0)).collect();
    let mut out = Vec::new();
    spread_units(&free, n - fixed_units, &mut units, n, &mut out);
    if out.is_empty() {
        return Err(err(
            source,
            "sweep.simplex",
            "no motivation point sums to 1 with these fixed values",
        ));
    }
    let named = |w: Vec<f64>| base.names.iter().cloned().zip(w).collect();
    Ok(out.into_iter().map(named).collect())
}

/// 1/step, checked to be a whole number ≤ 100.
fn simplex_divisions(step: f64, source: &str) -> Result<usize, CliError> {
    let field = "sweep.simplex.step";
    if !(step.is_finite() && step > 0.0 && step <= 1.0) {
        return Err(err(
            source,
            field,
            format!("must be in (0, 1], got {}", fuzzymotiv::params::Num(step)),
        ));
    }
    let n = (1.0 / step).round();
    if ((1.0 / step) - n).abs() > 1e-9 || n > 100.0 {
        return Err(err(
            source,
            field,
            format!("1/step must be a whole number ≤ 100 (e.g. 0.1, 0.05), got step {step}"),
        ));
    }
    Ok(n as usize)
}

/// The fixed motivations in steps of 1/n, per motivation of the base config (none where
/// free): those `fixed` names, and with `over`, every one it leaves out at its base weight.
fn fixed_units(
    s: &RawSimplex,
    base: &BaseMotivations,
    n: usize,
    source: &str,
) -> Result<Vec<Option<usize>>, CliError> {
    let known = || {
        if base.is_paper() {
            "use curiosity, homing, orientation or energy".to_string()
        } else {
            format!("use one of the config's: {}", base.names.join(", "))
        }
    };
    let position = |field: &str, k: &str| {
        (base.names.iter().position(|m| m == k))
            .ok_or_else(|| err(source, field, format!("not a motivation; {}", known())))
    };
    let mut fixed = vec![None; base.names.len()];
    if let Some(over) = &s.over {
        let mut free = vec![false; base.names.len()];
        for (j, k) in over.iter().enumerate() {
            let field = format!("sweep.simplex.over[{j}]");
            let i = position(&field, k)?;
            if s.fixed.contains_key(k) || free[i] {
                let why = "is named twice (in `over` and `fixed`, or twice in `over`)";
                return Err(err(source, &field, format!("{k} {why}")));
            }
            free[i] = true;
        }
        for i in (0..free.len()).filter(|&i| !free[i]) {
            let field = format!("motivations.{}", base.names[i]);
            let kept = in_units(base.weights[i], n, source, &field).map_err(|_| {
                let why = "not a multiple of sweep.simplex.step; a motivation `over` leaves out keeps its weight: give it one in sweep.simplex.fixed";
                let w = fuzzymotiv::params::Num(base.weights[i]);
                err(source, &field, format!("is {w}, {why}"))
            })?;
            fixed[i] = Some(kept);
        }
    }
    for (k, v) in &s.fixed {
        let field = format!("sweep.simplex.fixed.{k}");
        let i = position(&field, k)?;
        fixed[i] = Some(in_units(*v, n, source, &field)?);
    }
    Ok(fixed)
}

/// A weight in steps of 1/n, checked to be a multiple of the step in [0, 1].
fn in_units(v: f64, n: usize, source: &str, field: &str) -> Result<usize, CliError> {
    let units = v * n as f64;
    if !(0.0..=1.0).contains(&v) || (units - units.round()).abs() > 1e-9 {
        return Err(err(
            source,
            field,
            format!(
                "must be a multiple of the step in [0, 1], got {}",
                fuzzymotiv::params::Num(v)
            ),
        ));
    }
    Ok(units.round() as usize)
}

/// Every way to spread `left` units over the `free` motivations (the first free one from most
/// to fewest), pushing each point (units / n).
fn spread_units(
    free: &[usize],
    left: usize,
    units: &mut [usize],
    n: usize,
    out: &mut Vec<Vec<f64>>,
) {
    let point = |units: &[usize]| units.iter().map(|&u| u as f64 / n as f64).collect();
    match free {
        [] => {
            if left == 0 {
                out.push(point(units));
            }
        }
        [last] => {
            units[*last] = left;
            out.push(point(units));
        }
        [first, rest @ ..] => {
            for u in (0..=left).rev() {
                units[*first] = u;
                spread_units(rest, left - u, units, n, out);
            }
        }
    }
}

/// The jobs of a plan of `n` that one call runs: shard `I/N` (`--shard`: the jobs whose index
/// is I modulo N), job `index` alone, or every job; refused (naming the option) when the shard
/// is not `I/N` with 0 ≤ I < N or the index is past the plan.
pub fn select_jobs(
    n: usize,
    shard: Option<&str>,
    index: Option<usize>,
) -> Result<Vec<usize>, CliError> {
    if let Some(shard) = shard {
        let bad = || {
            CliError::input(format!(
                "--shard {shard}: expected I/N with 0 ≤ I < N, e.g. --shard 0/3"
            ))
        };
        let (i, k) = shard.split_once('/').ok_or_else(bad)?;
        let (i, k): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            k.trim().parse().map_err(|_| bad())?,
        );
        if k == 0 || i >= k {
            return Err(bad());
        }
        return Ok((0..n).filter(|j| j % k == i).collect());
    }
    match index {
        Some(i) if i >= n => Err(CliError::input(format!(
            "job index {i} is out of range: the plan has {n} jobs (0..{})",
            n.saturating_sub(1)
        ))),
        Some(i) => Ok(vec![i]),
        None => Ok((0..n).collect()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_text_that_is_not_toml_names_the_line_and_column() {
        let text = "[sweep]\nreplicates = 1\n[[[garbage\n";
        let Err(e) = Sweep::parse_str(text, "s.toml", Path::new(".")) else {
            panic!("garbage parsed as a sweep");
        };
        let message = e.to_string();
        assert!(
            message.contains("not valid TOML (line 3, column "),
            "{message}"
        );
    }

    /// A base config of five motivations (the paper's four + urgency over a goal).
    fn five(sweep: &str) -> Result<Sweep, CliError> {
        let text = format!(
            "rooms = [\"../rooms/fetch-H.toml\"]\n[aem]\nenabled = false\n[ga]\npopulation = 4\ngenerations = 1\n[motivations]\ncuriosity = 0.5\nhoming = 0.1\norientation = 0.0\nenergy = 0.0\nurgency = {{ weight = 0.4, term = \"urgency\" }}\n{sweep}"
        );
        let configs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../configs");
        Sweep::parse_str(&text, "s.toml", &configs)
    }

    #[test]
    fn simplex_over_three_named_motivations_plans_their_points() {
        let sweep = five(
            "[sweep]\nsimplex = { step = 0.5, over = [\"curiosity\", \"urgency\", \"homing\"] }\n",
        )
        .unwrap();
        let settings: Vec<&str> = sweep.jobs.iter().map(|j| j.setting.as_str()).collect();
        // orientation and energy keep the base config's 0; the three spread 1 in halves, the
        // first (in the config's order) from most to fewest.
        assert_eq!(
            settings,
            [
                "curiosity=1,homing=0,orientation=0,energy=0,urgency=0",
                "curiosity=0.5,homing=0.5,orientation=0,energy=0,urgency=0",
                "curiosity=0.5,homing=0,orientation=0,energy=0,urgency=0.5",
                "curiosity=0,homing=1,orientation=0,energy=0,urgency=0",
                "curiosity=0,homing=0.5,orientation=0,energy=0,urgency=0.5",
                "curiosity=0,homing=0,orientation=0,energy=0,urgency=1",
            ]
        );
        let urgency = sweep.load_job(&sweep.jobs[5]).unwrap();
        assert_eq!(
            urgency.experiment.motivations().weight_of("urgency"),
            Some(1.0)
        );
    }

    #[test]
    fn explicit_points_name_their_motivations_or_give_one_weight_each() {
        let sweep = five(
            "[sweep]\nmotivations = [{ urgency = 0.3, curiosity = 0.6 }, [0.2, 0.1, 0.0, 0.0, 0.7]]\n",
        )
        .unwrap();
        let settings: Vec<&str> = sweep.jobs.iter().map(|j| j.setting.as_str()).collect();
        assert_eq!(
            settings,
            [
                "curiosity=0.6,urgency=0.3",
                "curiosity=0.2,homing=0.1,orientation=0,energy=0,urgency=0.7",
            ]
        );
        let named = sweep.load_job(&sweep.jobs[0]).unwrap();
        let m = named.experiment.motivations();
        // Homing keeps the base config's 0.1.
        assert_eq!(
            (
                m.weight_of("curiosity"),
                m.weight_of("homing"),
                m.weight_of("urgency")
            ),
            (Some(0.6), Some(0.1), Some(0.3))
        );
    }

    #[test]
    fn an_explicit_point_with_a_stray_name_or_count_says_what_would_be_right() {
        let cases = [
            (
                "[{ hunger = 1.0 }]",
                "sweep.motivations[0].hunger",
                "it has curiosity, homing",
            ),
            ("[[0.5, 0.5]]", "sweep.motivations[0]", "2 weights; give 4"),
            (
                "[[0.5, 0.5, 0.0, \"x\", 0.0]]",
                "sweep.motivations[0][3]",
                "expected a weight",
            ),
            (
                "[0.5]",
                "sweep.motivations[0]",
                "expected a list of weights",
            ),
        ];
        for (points, field, what) in cases {
            let Err(e) = five(&format!("[sweep]\nmotivations = {points}\n")) else {
                panic!("{points} planned");
            };
            let message = e.to_string();
            assert!(
                message.contains(&format!("`{field}`")) && message.contains(what),
                "{points}: {message}"
            );
        }
    }

    #[test]
    fn simplex_over_a_name_the_config_lacks_says_which_it_has() {
        let Err(e) =
            five("[sweep]\nsimplex = { step = 0.5, over = [\"curiosity\", \"hunger\"] }\n")
        else {
            panic!("an unknown motivation was swept");
        };
        let message = e.to_string();
        assert!(
            message.contains("sweep.simplex.over[1]")
                && message.contains("curiosity, homing, orientation, energy, urgency"),
            "{message}"
        );
    }

    /// A shard runs every N-th job from I, an index its one job, neither every job; a shard
    /// that is not I/N with I < N, or an index past the plan, is refused.
    #[test]
    fn a_shard_or_an_index_selects_the_jobs_it_names() {
        assert_eq!(select_jobs(7, Some("1/3"), None).unwrap(), vec![1, 4]);
        assert_eq!(select_jobs(7, None, Some(6)).unwrap(), vec![6]);
        assert_eq!(select_jobs(3, None, None).unwrap(), vec![0, 1, 2]);
        for bad in ["3/3", "1", "a/2", "0/0"] {
            let e = select_jobs(7, Some(bad), None).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("--shard {bad}: expected I/N")),
                "{e}"
            );
        }
        let e = select_jobs(7, None, Some(7)).unwrap_err().to_string();
        assert!(e.contains("job index 7 is out of range"), "{e}");
    }
}
