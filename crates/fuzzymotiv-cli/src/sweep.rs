//! Sweeps: `plan` expands a `[sweep]` into a stable list of jobs, `sweep` runs (a shard of)
//! them into `DIR/jobs/ID/`, `merge` builds the tables and plots.
//!
//! A job's seed derives from the base seed and the job's key (its motivation point, grid values
//! and replicate), never from its position in a shard, and its id is a hash of its fully
//! resolved config, so any batch scheduler can run any subset in any order.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fuzzymotiv::config::RawConfig;
use fuzzymotiv::seed::{Streams, hash_str};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

use crate::error::CliError;
use crate::files::{StagedDir, io_err, write_atomic};
use crate::inputs::{Loaded, resolve};
use crate::progress::Progress;
use crate::run::{execute, set_threads};

/// The `[sweep]` table.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    /// Replicates (seeds) per point; default 1.
    #[serde(default = "one")]
    replicates: usize,
    /// Explicit motivation points (C, H, O, E).
    #[serde(default)]
    motivations: Vec<[f64; 4]>,
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
}

/// Most jobs one sweep file may plan.
const MAX_JOBS: usize = 100_000;

const MOTIVATIONS: [&str; 4] = ["curiosity", "homing", "orientation", "energy"];

/// One job of a sweep.
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
}

/// A parsed sweep: the base config text, where it came from and the jobs.
pub struct Sweep {
    base_text: String,
    source: String,
    base_dir: PathBuf,
    /// The jobs, in plan order.
    pub jobs: Vec<Job>,
}

fn err(source: &str, field: &str, reason: impl Into<String>) -> CliError {
    CliError::input(format!("{source}: field `{field}`: {}", reason.into()))
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

impl Sweep {
    /// Reads a sweep file and expands its jobs (each validated as a config).
    pub fn load(path: &Path) -> Result<Sweep, CliError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            CliError::input(format!("{}: cannot read sweep file: {e}", path.display()))
        })?;
        let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::parse_str(&text, &path.display().to_string(), &base_dir)
    }

    /// Parses a sweep document; room files are relative to `base_dir`.
    pub fn parse_str(text: &str, source: &str, base_dir: &Path) -> Result<Sweep, CliError> {
        let source = source.to_string();
        let mut table: toml::Table = toml::from_str(text).map_err(|e| {
            err(
                &source,
                "(document)",
                format!("not valid TOML: {}", e.message().trim()),
            )
        })?;
        let sweep_value = table.remove("sweep").ok_or_else(|| {
            err(
                &source,
                "sweep",
                "a sweep file needs a [sweep] table (replicates, motivations, simplex, grid)",
            )
        })?;
        let sweep: RawSweep = sweep_value
            .try_into()
            .map_err(|e: toml::de::Error| err(&source, "sweep", e.message().trim().to_string()))?;
        let base_text = toml::to_string(&table).expect("a table serialises");
        let base = RawConfig::parse(&base_text, &source, &[])?;
        if sweep.replicates == 0 || sweep.replicates > 100_000 {
            return Err(err(
                &source,
                "sweep.replicates",
                format!("must be in 1..=100000, got {}", sweep.replicates),
            ));
        }
        let mut points: Vec<[f64; 4]> = sweep.motivations.clone();
        if let Some(simplex) = &sweep.simplex {
            points.extend(simplex_points(simplex, &source)?);
        }
        let mut axes: Vec<(String, Vec<toml::Value>)> = Vec::new();
        for (key, values) in &sweep.grid {
            let list = values.as_array().filter(|a| !a.is_empty()).ok_or_else(|| {
                err(
                    &source,
                    &format!("sweep.grid.{key}"),
                    "must be a non-empty list of values",
                )
            })?;
            axes.push((key.clone(), list.clone()));
        }
        let mut jobs = Vec::new();
        let motivation_axis: Vec<Option<[f64; 4]>> = if points.is_empty() {
            vec![None]
        } else {
            points.into_iter().map(Some).collect()
        };
        let mut combos: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
        for (key, values) in &axes {
            combos = combos
                .into_iter()
                .flat_map(|c| {
                    values.iter().map(move |v| {
                        let mut c = c.clone();
                        c.push((key.clone(), v.clone()));
                        c
                    })
                })
                .collect();
        }
        let planned = motivation_axis
            .len()
            .saturating_mul(combos.len())
            .saturating_mul(sweep.replicates);
        if planned > MAX_JOBS {
            return Err(err(
                &source,
                "sweep",
                format!(
                    "{planned} jobs planned; at most {MAX_JOBS} per sweep file (split it, or use a coarser step)"
                ),
            ));
        }
        let mut seen = std::collections::HashSet::new();
        for point in &motivation_axis {
            for combo in &combos {
                let mut overrides = Vec::new();
                let mut parts = Vec::new();
                if let Some(p) = point {
                    for (k, v) in MOTIVATIONS.iter().zip(p) {
                        overrides.push(format!("motivations.{k}={}", fmt_value(*v)));
                    }
                    parts.push(format!("C={},H={},O={},E={}", p[0], p[1], p[2], p[3]));
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
                if !seen.insert(setting.clone()) {
                    // The same point listed twice (e.g. explicitly and by the simplex): once.
                    continue;
                }
                for rep in 0..sweep.replicates {
                    let key = format!("{setting};rep={rep}");
                    // Keep the derived seed in 0..2^53: exact in TOML (signed 64-bit) and in
                    // JSON read as doubles (JavaScript, jq).
                    let seed = Streams::new(base.seed).sweep_job(&key);
                    let mut sets = overrides.clone();
                    sets.push(format!("seed={seed}"));
                    let raw =
                        RawConfig::parse(&base_text, &format!("{source} (job {key})"), &sets)?;
                    // The id covers the resolved config and the contents of its room files, so an
                    // edited room file is a new job rather than a finished one.
                    let mut resolved = raw.to_toml();
                    for room in &raw.rooms {
                        if let Ok(text) = std::fs::read_to_string(base_dir.join(room)) {
                            resolved.push_str(&text);
                        }
                    }
                    let id = format!("{:016x}", hash_str(&resolved));
                    jobs.push(Job {
                        index: jobs.len(),
                        id,
                        key,
                        setting: setting.clone(),
                        replicate: rep,
                        seed,
                        overrides: sets,
                    });
                }
            }
        }
        let sweep = Sweep {
            base_text,
            source,
            base_dir: base_dir.to_path_buf(),
            jobs,
        };
        // Validate every job now, so a bad point fails before anything runs.
        for job in &sweep.jobs {
            sweep.load_job(job)?;
        }
        Ok(sweep)
    }

    /// The validated config of a job.
    pub fn load_job(&self, job: &Job) -> Result<Loaded, CliError> {
        let source = format!("{} (job {})", self.source, job.key);
        let raw = RawConfig::parse(&self.base_text, &source, &job.overrides)?;
        resolve(raw, &self.base_dir, &source)
    }

    /// The plan as JSON lines.
    pub fn plan_jsonl(&self) -> String {
        self.jobs
            .iter()
            .map(|j| serde_json::to_string(j).expect("serialisable") + "\n")
            .collect()
    }
}

fn simplex_points(s: &RawSimplex, source: &str) -> Result<Vec<[f64; 4]>, CliError> {
    let field = "sweep.simplex.step";
    if !(s.step.is_finite() && s.step > 0.0 && s.step <= 1.0) {
        return Err(err(
            source,
            field,
            format!("must be in (0, 1], got {}", s.step),
        ));
    }
    let n = (1.0 / s.step).round();
    if ((1.0 / s.step) - n).abs() > 1e-9 || n > 100.0 {
        return Err(err(
            source,
            field,
            format!(
                "1/step must be a whole number ≤ 100 (e.g. 0.1, 0.05), got step {}",
                s.step
            ),
        ));
    }
    let n = n as usize;
    let mut fixed = [None; 4];
    for (k, v) in &s.fixed {
        let i = MOTIVATIONS.iter().position(|m| m == k).ok_or_else(|| {
            err(
                source,
                &format!("sweep.simplex.fixed.{k}"),
                "not a motivation; use curiosity, homing, orientation or energy",
            )
        })?;
        let units = v * n as f64;
        if !(0.0..=1.0).contains(v) || (units - units.round()).abs() > 1e-9 {
            return Err(err(
                source,
                &format!("sweep.simplex.fixed.{k}"),
                format!("must be a multiple of the step in [0, 1], got {v}"),
            ));
        }
        fixed[i] = Some(units.round() as usize);
    }
    let fixed_units: usize = fixed.iter().flatten().sum();
    if fixed_units > n {
        return Err(err(
            source,
            "sweep.simplex.fixed",
            "fixed motivations sum to more than 1",
        ));
    }
    let free: Vec<usize> = (0..4).filter(|&i| fixed[i].is_none()).collect();
    let mut out = Vec::new();
    let mut units = [0usize; 4];
    for (i, f) in fixed.iter().enumerate() {
        if let Some(u) = f {
            units[i] = *u;
        }
    }
    fn rec(free: &[usize], left: usize, units: &mut [usize; 4], n: usize, out: &mut Vec<[f64; 4]>) {
        match free {
            [] => {
                if left == 0 {
                    out.push(units.map(|u| u as f64 / n as f64));
                }
            }
            [last] => {
                units[*last] = left;
                out.push(units.map(|u| u as f64 / n as f64));
            }
            [first, rest @ ..] => {
                for u in (0..=left).rev() {
                    units[*first] = u;
                    rec(rest, left - u, units, n, out);
                }
            }
        }
    }
    rec(&free, n - fixed_units, &mut units, n, &mut out);
    if out.is_empty() {
        return Err(err(
            source,
            "sweep.simplex",
            "no motivation point sums to 1 with these fixed values",
        ));
    }
    Ok(out)
}

/// Arguments of `fuzzymotiv plan`.
#[derive(clap::Args)]
pub struct PlanArgs {
    /// Sweep file (a config with a `[sweep]` table).
    pub sweep: PathBuf,
    /// Print only the number of jobs (to size an array job).
    #[arg(long)]
    pub count: bool,
    /// Write the plan to this file instead of stdout.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Entry point of `fuzzymotiv plan`.
pub fn plan(args: PlanArgs) -> Result<(), CliError> {
    let sweep = Sweep::load(&args.sweep)?;
    if args.count {
        println!("{}", sweep.jobs.len());
    } else if let Some(out) = args.out {
        write_atomic(&out, sweep.plan_jsonl())?;
    } else {
        print!("{}", sweep.plan_jsonl());
    }
    Ok(())
}

/// Arguments of `fuzzymotiv sweep`.
#[derive(clap::Args)]
pub struct SweepArgs {
    /// Sweep file (a config with a `[sweep]` table).
    pub sweep: PathBuf,
    /// Output directory; jobs go to DIR/jobs/ID/.
    #[arg(long)]
    pub out: PathBuf,
    /// Run shard I of N (0-based): the jobs whose index ≡ I mod N.
    #[arg(long, value_name = "I/N", conflicts_with_all = ["index", "index_from_env"])]
    pub shard: Option<String>,
    /// Run only job K (0-based plan index).
    #[arg(long, conflicts_with = "index_from_env")]
    pub index: Option<usize>,
    /// Read the job index from an environment variable, e.g. SLURM_ARRAY_TASK_ID,
    /// JOB_COMPLETION_INDEX (Kubernetes) or an HTCondor $(Process) passed in the environment.
    #[arg(long, value_name = "VAR")]
    pub index_from_env: Option<String>,
    /// Worker threads per job [default: all cores]; results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
}

fn select(args: &SweepArgs, n: usize) -> Result<Vec<usize>, CliError> {
    if let Some(shard) = &args.shard {
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
    let index = match (&args.index, &args.index_from_env) {
        (Some(i), _) => Some(*i),
        (None, Some(var)) => {
            let v = std::env::var(var).map_err(|_| {
                CliError::input(format!("--index-from-env {var}: the variable is not set"))
            })?;
            Some(v.trim().parse().map_err(|_| {
                CliError::input(format!("--index-from-env {var}: `{v}` is not a job index"))
            })?)
        }
        (None, None) => None,
    };
    match index {
        Some(i) if i >= n => Err(CliError::input(format!(
            "job index {i} is out of range: the plan has {n} jobs (0..{})",
            n.saturating_sub(1)
        ))),
        Some(i) => Ok(vec![i]),
        None => Ok((0..n).collect()),
    }
}

/// Entry point of `fuzzymotiv sweep`.
pub fn sweep(args: SweepArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    let sweep = Sweep::load(&args.sweep)?;
    let selected = select(&args, sweep.jobs.len())?;
    let text = std::fs::read_to_string(&args.sweep).map_err(|e| io_err(&args.sweep, e))?;
    run_jobs(&sweep, &text, &selected, &args.out, args.quiet)
}

/// Runs the `selected` jobs of `sweep` into `out/jobs/ID/`, skipping finished ones. On a
/// terminal a bar counts jobs; otherwise each job prints plain progress lines (not with `quiet`).
pub fn run_jobs(
    sweep: &Sweep,
    text: &str,
    selected: &[usize],
    out: &Path,
    quiet: bool,
) -> Result<(), CliError> {
    let terminal = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let jobs_dir = out.join("jobs");
    std::fs::create_dir_all(&jobs_dir).map_err(|e| io_err(&jobs_dir, e))?;
    write_atomic(&out.join("plan.jsonl"), sweep.plan_jsonl())?;
    write_atomic(&out.join("sweep.toml"), text)?;
    let bar = if terminal && !quiet {
        ProgressBar::new(selected.len() as u64)
    } else {
        ProgressBar::hidden()
    };
    let (mut ran, mut skipped) = (0, 0);
    for &k in selected {
        let job = &sweep.jobs[k];
        let dir = jobs_dir.join(&job.id);
        bar.set_message(job.key.clone());
        if dir.join("DONE").is_file() {
            skipped += 1;
            bar.inc(1);
            continue;
        }
        let loaded = sweep.load_job(job)?;
        let resume = StagedDir::staging_path(&dir)
            .join(crate::run::CHECKPOINT)
            .is_file();
        let progress = if terminal || quiet {
            Progress::hidden()
        } else {
            let p = Progress::new(&loaded.experiment, 1, false);
            p.set_prefix(&format!(
                "job {} ({}/{} here) {} seed {}",
                job.id,
                ran + skipped + 1,
                selected.len(),
                job.key,
                job.seed
            ));
            p
        };
        execute(&loaded, &dir, &progress, resume, false)?;
        write_atomic(
            &dir.join("job.json"),
            serde_json::to_string_pretty(job).expect("serialisable") + "\n",
        )?;
        write_atomic(&dir.join("DONE"), "")?;
        ran += 1;
        bar.inc(1);
    }
    bar.finish_and_clear();
    eprintln!(
        "{ran} jobs run, {skipped} already done, {} in this selection, {} in the plan",
        selected.len(),
        sweep.jobs.len()
    );
    Ok(())
}

/// Arguments of `fuzzymotiv merge`.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// A sweep output directory (with plan.jsonl and jobs/).
    pub dir: PathBuf,
}

#[derive(Debug, Clone)]
struct ResultRow {
    job: Job,
    motivations: [f64; 4],
    room: String,
    values: [Option<f64>; 5],
}

const METRICS: [&str; 5] = [
    "average_fitness",
    "exploration_pct",
    "recognition_pct",
    "battery_pct",
    "homing",
];

/// Entry point of `fuzzymotiv merge`.
pub fn merge(args: MergeArgs) -> Result<(), CliError> {
    let plan_path = args.dir.join("plan.jsonl");
    let plan = std::fs::read_to_string(&plan_path).map_err(|e| {
        CliError::input(format!(
            "{}: cannot read the plan ({e}); is this a sweep directory?",
            plan_path.display()
        ))
    })?;
    let jobs: Vec<Job> = plan
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            serde_json::from_str(l)
                .map_err(|e| CliError::input(format!("{}: bad line: {e}", plan_path.display())))
        })
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    let mut missing = 0;
    for job in &jobs {
        let dir = args.dir.join("jobs").join(&job.id);
        if !dir.join("DONE").is_file() {
            missing += 1;
            continue;
        }
        let path = dir.join("summary.json");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).map_err(|e| io_err(&path, e))?)
                .map_err(|e| CliError::runtime(format!("{}: {e}", path.display())))?;
        let m = &s["motivations"];
        let motivations = MOTIVATIONS.map(|k| m[k].as_f64().unwrap_or(f64::NAN));
        for r in s["rooms"].as_array().into_iter().flatten() {
            rows.push(ResultRow {
                job: job.clone(),
                motivations,
                room: r["room"].as_str().unwrap_or("?").to_string(),
                values: METRICS.map(|k| r[k].as_f64()),
            });
        }
    }
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.6}"));
    let mut csv = String::from(
        "job_id,index,setting,replicate,seed,curiosity,homing,orientation,energy,room",
    );
    for m in METRICS {
        let _ = write!(csv, ",{m}");
    }
    csv.push('\n');
    for r in &rows {
        let _ = write!(
            csv,
            "{},{},\"{}\",{},{},{},{},{},{},{}",
            r.job.id,
            r.job.index,
            r.job.setting,
            r.job.replicate,
            r.job.seed,
            r.motivations[0],
            r.motivations[1],
            r.motivations[2],
            r.motivations[3],
            r.room
        );
        for v in r.values {
            let _ = write!(csv, ",{}", opt(v));
        }
        csv.push('\n');
    }
    write_atomic(&args.dir.join("results.csv"), &csv)?;
    // Aggregate: mean ± std over replicates per (setting, room), in plan order.
    let mut groups: Vec<((String, String), Vec<&ResultRow>)> = Vec::new();
    for r in &rows {
        let key = (r.job.setting.clone(), r.room.clone());
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => v.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let mut agg_csv = String::from("setting,room,n");
    let mut md = String::from("| setting | room | n |");
    for m in METRICS {
        let _ = write!(agg_csv, ",{m}_mean,{m}_std");
        let _ = write!(md, " {m} |");
    }
    agg_csv.push('\n');
    md.push_str("\n|---|---|---|");
    md.push_str(&"---|".repeat(METRICS.len()));
    md.push('\n');
    let mut per_setting: Vec<(String, [f64; 4], [Vec<f64>; 5])> = Vec::new();
    for ((setting, room), members) in &groups {
        let _ = write!(agg_csv, "\"{setting}\",{room},{}", members.len());
        let _ = write!(md, "| {setting} | {room} | {} |", members.len());
        for (k, _) in METRICS.iter().enumerate() {
            let vals: Vec<f64> = members.iter().filter_map(|r| r.values[k]).collect();
            let (mean, std) = mean_std(&vals);
            let _ = write!(agg_csv, ",{},{}", fmt_opt(mean), fmt_opt(std));
            let _ = write!(md, " {} ± {} |", fmt_short(mean), fmt_short(std));
        }
        agg_csv.push('\n');
        md.push('\n');
        let entry = match per_setting.iter_mut().position(|(s, _, _)| s == setting) {
            Some(i) => &mut per_setting[i],
            None => {
                per_setting.push((setting.clone(), members[0].motivations, Default::default()));
                per_setting.last_mut().expect("just pushed")
            }
        };
        for r in members {
            for k in 0..5 {
                if let Some(v) = r.values[k] {
                    entry.2[k].push(v);
                }
            }
        }
    }
    write_atomic(&args.dir.join("aggregate.csv"), &agg_csv)?;
    write_atomic(&args.dir.join("aggregate.md"), &md)?;
    let points: Vec<crate::svg::SettingPoint> = per_setting
        .iter()
        .map(|(s, m, vals)| crate::svg::SettingPoint {
            label: s.clone(),
            motivations: *m,
            values: std::array::from_fn(|k| mean_std(&vals[k + 1]).0),
        })
        .collect();
    write_atomic(
        &args.dir.join("summary.svg"),
        crate::svg::sweep_summary_svg(&points),
    )?;
    print!("{md}");
    eprintln!(
        "merged {} jobs ({} rows) into {}; {missing} of {} jobs not finished",
        jobs.len() - missing,
        rows.len(),
        args.dir.join("results.csv").display(),
        jobs.len()
    );
    Ok(())
}

fn mean_std(v: &[f64]) -> (Option<f64>, Option<f64>) {
    if v.is_empty() {
        return (None, None);
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let std = if v.len() > 1 {
        (v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    (Some(mean), Some(std))
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |v| format!("{v:.6}"))
}

fn fmt_short(v: Option<f64>) -> String {
    v.map_or("n/a".into(), |v| format!("{v:.2}"))
}
