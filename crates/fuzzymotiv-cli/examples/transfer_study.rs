//! The transfer study's records and statistics (issue 54 item 3; `scripts/transfer_study.sh`
//! runs it): evolved controllers measured in fuzzymotiv and in Enki by `fuzzymotiv transfer`,
//! compared with the engine's own paired statistics ([`fuzzymotiv::statistics::paired`]: the
//! sign-flip permutation p, the percentile bootstrap interval, the minimum detectable
//! difference and the verdict rule of the study's claims).
//!
//! ```text
//! transfer_study collect STUDY TRANSFER > transfer.csv
//! transfer_study compare transfer.csv OUT_DIR      # OUT_DIR/comparison.csv, OUT_DIR/claims.csv
//! transfer_study pair A/transfer.csv B/transfer.csv > pair.csv
//! ```
//!
//! - `collect`: STUDY is a `fuzzymotiv reproduce` directory (SETTING/seed-K/ run directories),
//!   TRANSFER holds `transfer`'s outputs as SETTING/seed-K/ROOM/measures.csv. One row per
//!   setting, seed (the run's seed, from its config.resolved.toml), room and measure: the mean
//!   over the room's test runs in each world. `recognition_pct` of the simulator's test runs
//!   comes from the run's recognition.csv when its measures.csv has none (a reproduce run
//!   directory keeps no test_runs.csv; recognition.csv counts the same test runs).
//! - `compare`: per setting and measure, Enki against fuzzymotiv paired by seed (each seed's
//!   mean over rooms, as the study's claims take it; resampling seeded by the setting's first
//!   seed): comparison.csv. Per world, the paper's comparison claims (high against low curiosity
//!   paired by seed, resampling seeded by high curiosity's first seed, as `reproduce` does):
//!   claims.csv.
//! - `pair`: two transfer studies of the same seeds (A: robots evolved one way, B: another —
//!   `[trial.randomise]`, a sensor table measured in Enki), B against A paired by seed, per
//!   setting and measure in three worlds: `enki` and `fuzzymotiv` (each seed's mean over rooms)
//!   and `gap` (each seed's |Enki − fuzzymotiv|: does B's behaviour in Enki stay nearer its
//!   behaviour in the simulator?). Resampling seeded by the setting's first seed.
//!
//! Bad input (a missing file, a malformed cell) exits 2 naming the file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use fuzzymotiv::statistics::{Comparison, Expect, Settings, mean, paired};

/// The measures of measures.csv the study compares, with how a test run gives each.
const MEASURES: [&str; 6] = [
    "exploration_pct",
    "homing_pct",
    "battery_pct",
    "recognition_pct",
    "blocked_steps",
    "home_pct",
];

/// The paper's comparison claims: the claim, the measure, the direction (as reproduce's).
const CLAIMS: [(&str, &str, Expect); 4] = [
    (
        "high curiosity explores more than low curiosity",
        "exploration_pct",
        Expect::Higher,
    ),
    (
        "high curiosity uses more battery",
        "battery_pct",
        Expect::Higher,
    ),
    (
        "high curiosity recognises rooms better",
        "recognition_pct",
        Expect::Higher,
    ),
    (
        "high curiosity returns home less (lower % homing)",
        "homing_pct",
        Expect::Lower,
    ),
];

/// The two settings, in the study's order.
const SETTINGS: [&str; 2] = ["high-curiosity", "low-curiosity"];

type Row = BTreeMap<String, String>;

fn read_csv(path: &Path) -> Result<Vec<Row>, String> {
    let mut reader =
        csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let header = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
        rows.push(
            header
                .iter()
                .map(String::from)
                .zip(record.iter().map(String::from))
                .collect(),
        );
    }
    Ok(rows)
}

/// A cell as a number; `None` when empty or absent.
fn cell(row: &Row, column: &str, path: &Path) -> Result<Option<f64>, String> {
    match row.get(column).map(String::as_str) {
        None | Some("") => Ok(None),
        Some(text) => text.parse().map(Some).map_err(|_| {
            format!(
                "{}: column `{column}`: `{text}` is not a number",
                path.display()
            )
        }),
    }
}

/// A test run's value of `measure` (home_pct: 100 if it came home, else 0).
fn measure_of(row: &Row, measure: &str, path: &Path) -> Result<Option<f64>, String> {
    if measure == "home_pct" {
        return Ok(Some(match cell(row, "home_at", path)? {
            Some(_) => 100.0,
            None => 0.0,
        }));
    }
    cell(row, measure, path)
}

/// The mean of `measure` over the test runs of `world` (none if a run has no value).
fn world_mean(
    rows: &[Row],
    world: &str,
    measure: &str,
    path: &Path,
) -> Result<Option<f64>, String> {
    let mut values = Vec::new();
    for row in rows
        .iter()
        .filter(|r| r.get("world").is_some_and(|w| w == world))
    {
        match measure_of(row, measure, path)? {
            Some(v) => values.push(v),
            None => return Ok(None),
        }
    }
    Ok((!values.is_empty()).then(|| mean(&values)))
}

/// The run's seed, from its config.resolved.toml.
fn run_seed(run: &Path) -> Result<u64, String> {
    let path = run.join("config.resolved.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let value: toml::Table = text
        .parse()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    value
        .get("seed")
        .and_then(toml::Value::as_integer)
        .and_then(|s| u64::try_from(s).ok())
        .ok_or_else(|| format!("{}: no whole-number `seed`", path.display()))
}

/// The simulator's recognition of `room` from the run's recognition.csv, if it has one.
fn recorded_recognition(run: &Path, room: &str) -> Result<Option<f64>, String> {
    let path = run.join("recognition.csv");
    if !path.exists() {
        return Ok(None);
    }
    let rows = read_csv(&path)?;
    match rows
        .iter()
        .find(|r| r.get("room").is_some_and(|n| n == room))
    {
        Some(row) => cell(row, "recognition_pct", &path),
        None => Ok(None),
    }
}

/// The seed directories of a setting, in order.
fn seed_dirs(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut dirs: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    Ok(dirs)
}

/// The rooms transferred for one run, in the paper's order (the subdirectories holding
/// measures.csv; a scaled room such as the Thymio II's `H-x3` goes where its paper room does).
fn rooms(dir: &Path) -> Result<Vec<String>, String> {
    let mut rooms: Vec<String> = seed_dirs(dir)?
        .into_iter()
        .filter(|p| p.join("measures.csv").exists())
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    let order = ["H", "T", "L", "square", "rectangle"];
    let paper = |r: &str| r.split_once("-x").map_or(r, |(stem, _)| stem).to_string();
    rooms.sort_by_key(|r| {
        let stem = paper(r);
        order.iter().position(|o| *o == stem).unwrap_or(order.len())
    });
    Ok(rooms)
}

fn number(x: Option<f64>) -> String {
    x.map_or(String::new(), |v| v.to_string())
}

/// `collect`: the long CSV on stdout.
fn collect(study: &Path, transfer: &Path) -> Result<(), String> {
    println!("setting,seed,room,measure,fuzzymotiv,enki");
    for setting in SETTINGS {
        for seed_dir in seed_dirs(&transfer.join(setting))? {
            let name = seed_dir.file_name().unwrap_or_default();
            let run = study.join(setting).join(name);
            let seed = run_seed(&run)?;
            for room in rooms(&seed_dir)? {
                let path = seed_dir.join(&room).join("measures.csv");
                let rows = read_csv(&path)?;
                for measure in MEASURES {
                    let mut sim = world_mean(&rows, "fuzzymotiv", measure, &path)?;
                    if sim.is_none() && measure == "recognition_pct" {
                        sim = recorded_recognition(&run, &room)?;
                    }
                    let enki = world_mean(&rows, "enki", measure, &path)?;
                    println!(
                        "{setting},{seed},{room},{measure},{},{}",
                        number(sim),
                        number(enki)
                    );
                }
            }
        }
    }
    Ok(())
}

/// Per setting, seed (in the file's order) and world, each measure's mean over rooms.
struct SeedMeans {
    /// (setting, measure, world) → per seed, the mean over rooms (none if a room lacks it).
    values: BTreeMap<(String, String, String), Vec<Option<f64>>>,
    /// The seeds of each setting, in order.
    seeds: BTreeMap<String, Vec<u64>>,
}

/// (setting, measure, world) → per seed in order, its rooms' values.
type RoomValues = BTreeMap<(String, String, String), Vec<(u64, Vec<Option<f64>>)>>;

fn seed_means(path: &Path) -> Result<SeedMeans, String> {
    let rows = read_csv(path)?;
    let mut by_seed: RoomValues = BTreeMap::new();
    let mut seeds: BTreeMap<String, Vec<u64>> = BTreeMap::new();
    for row in &rows {
        let text = |c: &str| row.get(c).cloned().unwrap_or_default();
        let seed: u64 = text("seed").parse().map_err(|_| {
            format!(
                "{}: seed `{}` is not a number",
                path.display(),
                text("seed")
            )
        })?;
        let list = seeds.entry(text("setting")).or_default();
        if list.last() != Some(&seed) {
            list.push(seed);
        }
        for world in ["fuzzymotiv", "enki"] {
            let key = (text("setting"), text("measure"), world.to_string());
            let per_seed = by_seed.entry(key).or_default();
            if per_seed.last().is_none_or(|(s, _)| *s != seed) {
                per_seed.push((seed, Vec::new()));
            }
            let value = cell(row, world, path)?;
            per_seed.last_mut().expect("pushed").1.push(value);
        }
    }
    let values = by_seed
        .into_iter()
        .map(|(key, per_seed)| {
            let means = per_seed
                .into_iter()
                .map(|(_, v)| {
                    v.into_iter()
                        .collect::<Option<Vec<f64>>>()
                        .map(|v| mean(&v))
                })
                .collect();
            (key, means)
        })
        .collect();
    Ok(SeedMeans { values, seeds })
}

fn all(values: Option<&Vec<Option<f64>>>) -> Option<Vec<f64>> {
    values?.iter().copied().collect()
}

/// The statistics' settings of `setting`'s comparisons: resampling seeded by its first seed.
fn settings_of(m: &SeedMeans, setting: &str) -> Settings {
    let first = m.seeds.get(setting).and_then(|s| s.first()).copied();
    Settings {
        seed: first.unwrap_or(0),
        ..Settings::default()
    }
}

/// A comparison's last cells: difference, ci_low, ci_high, p, detectable, verdict.
fn stats_cells(c: &Comparison, verdict: &str) -> String {
    let (d, lo, hi, p) = (c.difference, c.ci_low, c.ci_high, c.p);
    format!("{d},{lo},{hi},{p},{},{verdict}", number(c.mdd))
}

/// comparison.csv: Enki against fuzzymotiv per setting and measure.
fn comparison_csv(m: &SeedMeans) -> String {
    let mut out = String::from(
        "setting,measure,seeds,mean_fuzzymotiv,mean_enki,difference,ci_low,ci_high,p,detectable,verdict\n",
    );
    for setting in SETTINGS {
        let options = settings_of(m, setting);
        for measure in MEASURES {
            let get = |w: &str| all(m.values.get(&(setting.into(), measure.into(), w.into())));
            let (Some(sim), Some(enki)) = (get("fuzzymotiv"), get("enki")) else {
                continue;
            };
            let Ok(c) = paired(&enki, &sim, &options) else {
                continue;
            };
            let verdict = c.verdict_with_power(Expect::Higher).direction_label();
            out += &format!(
                "{setting},{measure},{},{},{},{}\n",
                sim.len(),
                c.mean_b,
                c.mean_a,
                stats_cells(&c, verdict)
            );
        }
    }
    out
}

/// claims.csv: per world, the paper's comparison claims, high against low curiosity.
fn claims_csv(m: &SeedMeans) -> String {
    let mut out =
        String::from("world,claim,seeds,high,low,difference,ci_low,ci_high,p,detectable,verdict\n");
    let options = settings_of(m, SETTINGS[0]);
    for world in ["fuzzymotiv", "enki"] {
        for (claim, measure, expect) in CLAIMS {
            let get = |s: &str| all(m.values.get(&(s.into(), measure.into(), world.into())));
            let (Some(high), Some(low)) = (get(SETTINGS[0]), get(SETTINGS[1])) else {
                continue;
            };
            let Ok(c) = paired(&high, &low, &options) else {
                continue;
            };
            out += &format!(
                "{world},{claim},{},{},{},{}\n",
                high.len(),
                c.mean_a,
                c.mean_b,
                stats_cells(&c, c.verdict_with_power(expect).label())
            );
        }
    }
    out
}

/// A setting's per-seed values of `measure` in `world` (`gap`: |Enki − fuzzymotiv|).
fn world_values(m: &SeedMeans, setting: &str, measure: &str, world: &str) -> Option<Vec<f64>> {
    let get = |w: &str| all(m.values.get(&(setting.into(), measure.into(), w.into())));
    if world != "gap" {
        return get(world);
    }
    let (sim, enki) = (get("fuzzymotiv")?, get("enki")?);
    Some(sim.iter().zip(&enki).map(|(s, e)| (e - s).abs()).collect())
}

/// `pair`: B against A, paired by seed, per setting, measure and world.
fn pair(a_path: &Path, b_path: &Path) -> Result<(), String> {
    let (a, b) = (seed_means(a_path)?, seed_means(b_path)?);
    if a.seeds != b.seeds {
        return Err(format!(
            "{} and {} are not of the same settings and seeds ({:?} against {:?}): \
             a paired comparison needs both studies made with the same seeds",
            a_path.display(),
            b_path.display(),
            a.seeds,
            b.seeds
        ));
    }
    println!(
        "setting,measure,world,seeds,mean_a,mean_b,difference,ci_low,ci_high,p,detectable,verdict"
    );
    for setting in SETTINGS {
        let options = settings_of(&a, setting);
        for measure in MEASURES {
            for world in ["enki", "fuzzymotiv", "gap"] {
                let (Some(va), Some(vb)) = (
                    world_values(&a, setting, measure, world),
                    world_values(&b, setting, measure, world),
                ) else {
                    continue;
                };
                let Ok(c) = paired(&vb, &va, &options) else {
                    continue;
                };
                let verdict = c.verdict_with_power(Expect::Higher).direction_label();
                println!(
                    "{setting},{measure},{world},{},{},{},{}",
                    va.len(),
                    c.mean_b,
                    c.mean_a,
                    stats_cells(&c, verdict)
                );
            }
        }
    }
    Ok(())
}

fn compare(csv: &Path, out: &Path) -> Result<(), String> {
    let m = seed_means(csv)?;
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (name, text) in [
        ("comparison.csv", comparison_csv(&m)),
        ("claims.csv", claims_csv(&m)),
    ] {
        let path = out.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["collect", study, transfer] => collect(Path::new(study), Path::new(transfer)),
        ["compare", csv, out] => compare(Path::new(csv), Path::new(out)),
        ["pair", a, b] => pair(Path::new(a), Path::new(b)),
        _ => Err(
            "usage: transfer_study collect STUDY TRANSFER > transfer.csv | \
                  transfer_study compare transfer.csv OUT_DIR | \
                  transfer_study pair A/transfer.csv B/transfer.csv > pair.csv"
                .into(),
        ),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("transfer_study: {e}");
            ExitCode::from(2)
        }
    }
}
