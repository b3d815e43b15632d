//! The documents say what the records say.
//!
//! README.md, EXPERIMENTS.md, docs/**/*.md, bench/README.md and bench/HISTORY.md mark every table and number they
//! quote from a study (docs/results/README.md describes the markers):
//!
//! ```text
//! <!-- record ten-seed/claims.csv: claims -->
//! | claim | high | low | … |
//! <!-- end record -->
//! … MDD <!-- value ten-seed/claims.csv: claim~battery mdd .1 -->2.5<!-- end --> points …
//! ```
//!
//! Each marker is rendered again from the committed records under docs/results/ and compared
//! with the document. `FUZZYMOTIV_BLESS=1 cargo test -p fuzzymotiv-cli --test it documents::`
//! rewrites the documents from the records instead.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

type Row = BTreeMap<String, String>;
type Rendered = Result<Vec<String>, String>;

const BLOCK_START: &str = "<!-- record ";
const BLOCK_END: &str = "<!-- end record -->";
const VALUE_START: &str = "<!-- value ";
const VALUE_END: &str = "<!-- end -->";
const RENDERERS: &str = "rooms, claims, room-means, fig6, search-strength, \
    search-strength-exploration, ablation-claims, ablation-means, orientation, levels, \
    replication, behaviour, claim-differences, combination-claims, urgency, nsga-robots, \
    transfer, transfer-claims, transfer-pair";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The documents that quote studies, relative to the repository root.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![
        PathBuf::from("README.md"),
        PathBuf::from("EXPERIMENTS.md"),
        PathBuf::from("bench/README.md"),
        PathBuf::from("bench/HISTORY.md"),
    ];
    let mut stack = vec![PathBuf::from("docs")];
    while let Some(dir) = stack.pop() {
        for entry in fs::read_dir(root().join(&dir)).expect("docs/ is readable") {
            let path = dir.join(entry.expect("a docs/ entry").file_name());
            if root().join(&path).is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                docs.push(path);
            }
        }
    }
    docs.sort();
    docs
}

// ---------------------------------------------------------------------------------------------
// Reading records

fn read_csv(dir: &Path, file: &str) -> Result<Vec<Row>, String> {
    let path = dir.join(file);
    let mut reader = csv::Reader::from_path(&path)
        .map_err(|e| format!("cannot read the record {}: {e}", path.display()))?;
    let headers = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
        rows.push(
            headers
                .iter()
                .map(String::from)
                .zip(record.iter().map(String::from))
                .collect(),
        );
    }
    Ok(rows)
}

fn read_json(dir: &Path, file: &str) -> Result<serde_json::Value, String> {
    let path = dir.join(file);
    let text = fs::read_to_string(&path)
        .map_err(|e| format!("cannot read the record {}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

fn cell<'a>(row: &'a Row, column: &str) -> Result<&'a str, String> {
    row.get(column).map(String::as_str).ok_or_else(|| {
        let known: Vec<&str> = row.keys().map(String::as_str).collect();
        format!(
            "no column `{column}` in the record; its columns are {}",
            known.join(", ")
        )
    })
}

/// A number, or None for an empty cell.
fn opt_num(row: &Row, column: &str) -> Result<Option<f64>, String> {
    let text = cell(row, column)?;
    if text.is_empty() {
        return Ok(None);
    }
    text.parse()
        .map(Some)
        .map_err(|_| format!("column `{column}`: `{text}` is not a number"))
}

fn num(row: &Row, column: &str) -> Result<f64, String> {
    opt_num(row, column)?.ok_or_else(|| format!("column `{column}` is empty"))
}

fn json_num(value: &serde_json::Value, pointer: &str) -> Result<f64, String> {
    value
        .pointer(pointer)
        .and_then(serde_json::Value::as_f64)
        .ok_or_else(|| format!("summary.json has no number at {pointer}"))
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len() as f64
}

/// Sample standard deviation (n − 1).
fn std(values: &[f64]) -> f64 {
    let m = mean(values);
    let n = values.len() as f64;
    (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
}

// ---------------------------------------------------------------------------------------------
// Number formats: `fixed` and `signed` write a true minus (−), the `ascii_` ones a hyphen, as
// the study's own Markdown does.

fn ascii_fixed(x: f64, digits: usize) -> String {
    format!("{x:.digits$}")
}

fn ascii_signed(x: f64, digits: usize) -> String {
    format!("{x:+.digits$}")
}

fn fixed(x: f64, digits: usize) -> String {
    ascii_fixed(x, digits).replace('-', "−")
}

fn signed(x: f64, digits: usize) -> String {
    ascii_signed(x, digits).replace('-', "−")
}

fn opt_fixed(x: Option<f64>, digits: usize) -> String {
    x.map_or("—".into(), |x| fixed(x, digits))
}

fn table(header: &[&str], rows: Vec<String>) -> Vec<String> {
    let mut lines = vec![format!("| {} |", header.join(" | "))];
    lines.push(format!("|{}", "---|".repeat(header.len())));
    lines.extend(rows);
    lines
}

// ---------------------------------------------------------------------------------------------
// Renderers: one per kind of table.

/// Tables 1–2: `table1.csv` or `table2.csv`, mean ± std over seeds with the paper's value.
fn rooms(dir: &Path, file: &str) -> Rendered {
    let header = [
        "room",
        "average fitness",
        "% optimal exploration",
        "% recognition",
        "% battery usage",
        "% homing",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        let with_paper =
            |key: &str, digits: usize, paper_digits: usize| -> Result<String, String> {
                let value = opt_fixed(opt_num(&r, key)?, digits);
                let spread = opt_fixed(opt_num(&r, &format!("{key}_std"))?, digits);
                let paper = fixed(num(&r, &format!("paper_{key}"))?, paper_digits);
                Ok(format!("{value} ± {spread} ({paper})"))
            };
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} ± {} |",
            cell(&r, "room")?,
            with_paper("average_fitness", 4, 4)?,
            with_paper("exploration_pct", 1, 2)?,
            with_paper("recognition_pct", 0, 2)?,
            with_paper("battery_pct", 1, 2)?,
            fixed(num(&r, "homing_pct")?, 1),
            fixed(num(&r, "homing_pct_std")?, 1),
        ));
    }
    Ok(table(&header, rows))
}

/// The high and low parts of a claim's evidence ("high 91.2 % vs low 89.5 %",
/// "high 0.120, low 0.225", "high 0.120 → 0.742, low 0.225 → 0.708").
fn high_low(evidence: &str) -> Result<(String, String), String> {
    let body = evidence
        .strip_prefix("high ")
        .ok_or_else(|| format!("evidence `{evidence}` does not start with `high `"))?;
    let (high, low) = body
        .split_once(" vs low ")
        .or_else(|| body.split_once(", low "))
        .ok_or_else(|| format!("evidence `{evidence}` has no `low` part"))?;
    Ok((high.into(), low.into()))
}

fn is_summary_claim(row: &Row) -> Result<bool, String> {
    Ok(!cell(row, "claim")?.contains(" — "))
}

/// A claim as the documents name it: the study's name, its bound written short.
fn claim_name(row: &Row) -> Result<String, String> {
    Ok(cell(row, "claim")?.replace(" (between 0.05 and 0.15)", " (0.05–0.15)"))
}

/// The paper's claims over seeds: `claims.csv`.
fn claims(dir: &Path, file: &str) -> Rendered {
    let header = [
        "claim",
        "high",
        "low",
        "high − low [95 % CI]",
        "p",
        "verdict",
        "MDD",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        if !is_summary_claim(&r)? {
            continue;
        }
        let (high, low) = high_low(cell(&r, "evidence")?)?;
        let verdict = cell(&r, "verdict")?;
        let line = match opt_num(&r, "p")? {
            Some(p) => format!(
                "| {} | {high} | {low} | {} [{}, {}] | {} | {} | {} |",
                claim_name(&r)?,
                signed(num(&r, "difference")?, 1),
                signed(num(&r, "ci_low")?, 1),
                signed(num(&r, "ci_high")?, 1),
                fixed(p, 3),
                if verdict == "not significant" {
                    verdict.into()
                } else {
                    format!("**{verdict}**")
                },
                fixed(num(&r, "mdd")?, 1),
            ),
            None => format!(
                "| {} | {high} | {low} | — | — | {verdict} | — |",
                claim_name(&r)?
            ),
        };
        rows.push(line);
    }
    Ok(table(&header, rows))
}

/// Means over the five rooms per setting, and the mean and best F of the first and last
/// generation: a study's `summary.json`.
fn room_means(dir: &Path, file: &str) -> Rendered {
    let summary = read_json(dir, file)?;
    let header = [
        "setting",
        "% exploration",
        "% recognition",
        "% battery",
        "% homing",
        "mean F gen 0 → last",
        "best F gen 0 → last",
    ];
    let settings = summary["settings"]
        .as_array()
        .ok_or("summary.json has no settings")?;
    let mut rows = Vec::new();
    for (i, setting) in settings.iter().enumerate() {
        let over_rooms = |key: &str| {
            let values: Vec<f64> = setting["rows"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|row| row[key].as_f64())
                .collect();
            opt_fixed((!values.is_empty()).then(|| mean(&values)), 1)
        };
        let f = |generation: &str, which: &str| -> Result<String, String> {
            Ok(fixed(
                json_num(&summary, &format!("/settings/{i}/{generation}/{which}"))?,
                3,
            ))
        };
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} → {} | {} → {} |",
            setting["name"].as_str().ok_or("a setting without a name")?,
            over_rooms("exploration_pct"),
            over_rooms("recognition_pct"),
            over_rooms("battery_pct"),
            over_rooms("homing_pct"),
            f("first_generation", "mean")?,
            f("last_generation", "mean")?,
            f("first_generation", "best")?,
            f("last_generation", "best")?,
        ));
    }
    Ok(table(&header, rows))
}

/// The paper's Fig. 6 (read from the figure) beside a study's `summary.json`.
fn fig6(dir: &Path, file: &str) -> Rendered {
    let summary = read_json(dir, file)?;
    let ours = |setting: usize, generation: &str, which: &str| -> Result<String, String> {
        let pointer = format!("/settings/{setting}/{generation}/{which}");
        Ok(fixed(json_num(&summary, &pointer)?, 2))
    };
    // Settings: 0 high curiosity, 1 low curiosity (the study's order).
    let header = [
        "",
        "paper, low curiosity",
        "ours, low curiosity",
        "paper, high curiosity",
        "ours, high curiosity",
    ];
    let rows = vec![
        format!(
            "| mean F, generation 0 | 0.12 | {} | 0.05 | {} |",
            ours(1, "first_generation", "mean")?,
            ours(0, "first_generation", "mean")?
        ),
        format!(
            "| mean F, last generation | 0.29 | {} | 0.57 | {} |",
            ours(1, "last_generation", "mean")?,
            ours(0, "last_generation", "mean")?
        ),
        format!(
            "| best F, generation 0 → last | 0.28 → 0.34 | {} → {} | 0.47 → 0.68 | {} → {} |",
            ours(1, "first_generation", "best")?,
            ours(1, "last_generation", "best")?,
            ours(0, "first_generation", "best")?,
            ours(0, "last_generation", "best")?
        ),
    ];
    Ok(table(&header, rows))
}

const EXPLORATION_VS_30: &str = "low-curiosity exploration vs population 30";

/// The claims at each GA population: `search_strength.csv` and each `pop-N/claims.csv` (the
/// evidence of the two rows without a test).
fn search_strength(dir: &Path, folder: &str) -> Rendered {
    let dir = dir.join(folder);
    let header = [
        "population",
        "claim",
        "high",
        "low",
        "difference [95 % interval]",
        "p",
        "verdict",
        "detectable",
    ];
    let mut rows = Vec::new();
    for r in read_csv(&dir, "search_strength.csv")? {
        let (population, claim) = (cell(&r, "population")?, cell(&r, "claim")?);
        if claim == EXPLORATION_VS_30 {
            continue;
        }
        let verdict = cell(&r, "verdict")?;
        let line = match opt_num(&r, "high")? {
            Some(high) => format!(
                "| {population} | {claim} | {} % | {} % | {} [{}, {}] | {} | {verdict} | {} |",
                ascii_fixed(high, 1),
                ascii_fixed(num(&r, "low")?, 1),
                ascii_signed(num(&r, "difference")?, 1),
                ascii_signed(num(&r, "ci_low")?, 1),
                ascii_signed(num(&r, "ci_high")?, 1),
                ascii_fixed(num(&r, "p")?, 4),
                ascii_fixed(num(&r, "mdd")?, 1),
            ),
            None => {
                let pop_claims = read_csv(&dir, &format!("pop-{population}/claims.csv"))?;
                let evidence = select(&pop_claims, &[("claim", '=', claim)])?;
                let (high, low) = high_low(cell(evidence, "evidence")?)?;
                format!("| {population} | {claim} | | | high {high}, low {low} | | {verdict} | |")
            }
        };
        rows.push(line);
    }
    Ok(table(&header, rows))
}

/// Low-curiosity exploration at each population against population 30: the
/// `low-curiosity exploration vs population 30` rows of `search_strength.csv`.
fn search_strength_exploration(dir: &Path, file: &str) -> Rendered {
    let header = [
        "population",
        "low-curiosity % exploration (mean over seeds)",
        "difference to 30 [95 % interval]",
        "p",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        if cell(&r, "claim")? != EXPLORATION_VS_30 {
            continue;
        }
        let population = cell(&r, "population")?;
        let low = ascii_fixed(num(&r, "low")?, 1);
        rows.push(match opt_num(&r, "difference")? {
            Some(difference) => format!(
                "| {population} | {low} | {} [{}, {}] | {} |",
                ascii_signed(difference, 1),
                ascii_signed(num(&r, "ci_low")?, 1),
                ascii_signed(num(&r, "ci_high")?, 1),
                ascii_fixed(num(&r, "p")?, 4)
            ),
            None => format!("| {population} | {low} | — | — |"),
        });
    }
    Ok(table(&header, rows))
}

/// Each claim's verdict under each variant: the variants and claims of `ablation.csv` (its
/// columns name the claims, in the study's order), each verdict from the variant's own
/// `VARIANT/claims.csv` ("holds", "not significant", "opposite", "fails").
fn ablation_claims(dir: &Path, file: &str) -> Rendered {
    let header = [
        "variant",
        "explores more",
        "more battery",
        "recognises better",
        "homes less",
        "gen-0 mean F ≈ 0.1",
        "F rises",
    ];
    let path = dir.join(file);
    let names: Vec<String> = csv::Reader::from_path(&path)
        .and_then(|mut r| {
            r.headers()
                .map(|h| h.iter().skip(1).map(String::from).collect())
        })
        .map_err(|e| format!("cannot read the record {}: {e}", path.display()))?;
    if names.len() + 1 != header.len() {
        return Err(format!(
            "{} has {} claims, the table {}: the study's claims changed, so change the renderer \
             `ablation-claims` with them",
            path.display(),
            names.len(),
            header.len() - 1
        ));
    }
    let folder = Path::new(file).parent().unwrap_or(Path::new(""));
    let mut rows = Vec::new();
    for variant in read_csv(dir, file)? {
        let name = cell(&variant, "variant")?;
        let claims = read_csv(dir, &folder.join(name).join("claims.csv").to_string_lossy())?;
        let mut cells = vec![name.to_string()];
        for claim in &names {
            let row = (claims.iter())
                .find(|r| r.get("claim") == Some(claim))
                .ok_or_else(|| format!("{name}/claims.csv has no claim `{claim}`"))?;
            cells.push(cell(row, "verdict")?.to_string());
        }
        rows.push(format!("| {} |", cells.join(" | ")));
    }
    Ok(table(&header, rows))
}

/// Mean over rooms of one column of a `tableN.csv`.
fn table_mean(dir: &Path, file: &str, column: &str) -> Result<String, String> {
    let mut values = Vec::new();
    for r in read_csv(dir, file)? {
        values.extend(opt_num(&r, column)?);
    }
    Ok(opt_fixed((!values.is_empty()).then(|| mean(&values)), 1))
}

/// Means over rooms and seeds per variant: `VARIANT/table1.csv`, `table2.csv` and `claims.csv`
/// (first-generation mean F) of each variant listed in `ablation.csv`.
fn ablation_means(dir: &Path, folder: &str) -> Rendered {
    let dir = dir.join(folder);
    let header = [
        "variant",
        "% exploration (high / low)",
        "% battery",
        "% recognition",
        "% homing",
        "mean F gen 0 (high / low)",
    ];
    let mut rows = Vec::new();
    for variant in read_csv(&dir, "ablation.csv")? {
        let name = cell(&variant, "variant")?;
        let vdir = dir.join(name);
        let both = |column: &str| -> Result<String, String> {
            Ok(format!(
                "{} / {}",
                table_mean(&vdir, "table1.csv", column)?,
                table_mean(&vdir, "table2.csv", column)?
            ))
        };
        let claims = read_csv(&vdir, "claims.csv")?;
        let gen0 = |setting: &str| -> Result<String, String> {
            let row = select(
                &claims,
                &[("claim", '~', "first-generation"), ("claim", '~', setting)],
            )?;
            Ok(fixed(num(row, "difference")?, 3))
        };
        rows.push(format!(
            "| {name} | {} | {} | {} | {} | {} / {} |",
            both("exploration_pct")?,
            both("battery_pct")?,
            both("recognition_pct")?,
            both("homing_pct")?,
            gen0("— high-curiosity")?,
            gen0("— low-curiosity")?,
        ));
    }
    Ok(table(&header, rows))
}

/// "C=0.5,H=0.3,O=0,E=0.2" → ("(.5, .3, 0, .2)", O).
fn motivations_label(setting: &str) -> Result<(String, f64), String> {
    let mut parts = Vec::new();
    let mut orientation = 0.0;
    for part in setting.split(',') {
        let (key, value) = part
            .split_once('=')
            .ok_or_else(|| format!("setting `{setting}` is not of the form C=…,H=…,O=…,E=…"))?;
        if key == "O" {
            orientation = value
                .parse()
                .map_err(|_| format!("setting `{setting}`: O"))?;
        }
        parts.push(
            value
                .strip_prefix('0')
                .filter(|v| !v.is_empty())
                .unwrap_or(value),
        );
    }
    Ok((format!("({})", parts.join(", ")), orientation))
}

fn mean_std(values: &[f64], digits: usize) -> String {
    match values.len() {
        0 => "—".into(),
        1 => format!("{} ± —", fixed(values[0], digits)),
        _ => format!(
            "{} ± {}",
            fixed(mean(values), digits),
            fixed(std(values), digits)
        ),
    }
}

/// The orientation study: `results.csv` (means over rooms, then mean ± std over seeds) and
/// each job's `jobs/ID/generations.csv` (the online l of the final population).
fn orientation(dir: &Path, folder: &str) -> Rendered {
    let dir = dir.join(folder);
    let header = [
        "(C, H, O, E)",
        "% recognition (SOM test)",
        "online l, final population",
        "% exploration",
        "% battery",
        "% homing",
    ];
    let results = read_csv(&dir, "results.csv")?;
    let mut settings: Vec<&str> = Vec::new();
    for r in &results {
        let setting = cell(r, "setting")?;
        if !settings.contains(&setting) {
            settings.push(setting);
        }
    }
    let mut rows = Vec::new();
    for setting in settings {
        let mine: Vec<&Row> = results.iter().filter(|r| r["setting"] == setting).collect();
        let mut jobs: Vec<&str> = mine.iter().map(|r| r["job_id"].as_str()).collect();
        jobs.dedup();
        let per_seed = |column: &str| -> Result<String, String> {
            let mut means = Vec::new();
            for job in &jobs {
                let mut values = Vec::new();
                for r in mine.iter().filter(|r| r["job_id"] == *job) {
                    values.extend(opt_num(r, column)?);
                }
                if !values.is_empty() {
                    means.push(mean(&values));
                }
            }
            Ok(mean_std(&means, 1))
        };
        let (label, o) = motivations_label(setting)?;
        let online = if o == 0.0 {
            "— (not computed, O = 0)".to_string()
        } else {
            let mut ls = Vec::new();
            for job in &jobs {
                let generations = read_csv(&dir, &format!("jobs/{job}/generations.csv"))?;
                ls.push(num(
                    generations.last().ok_or("an empty generations.csv")?,
                    "l",
                )?);
            }
            mean_std(&ls, 2)
        };
        rows.push(format!(
            "| {label} | {} | {online} | {} | {} | {} |",
            per_seed("recognition_pct")?,
            per_seed("exploration_pct")?,
            per_seed("battery_pct")?,
            per_seed("homing_pct")?,
        ));
    }
    Ok(table(&header, rows))
}

/// A motivation map's means over the settings sharing one level of a motivation (each
/// setting's mean over rooms first): `results.csv`; args: the motivation (curiosity, homing,
/// orientation, energy) and a comma-separated list of metrics.
fn levels(dir: &Path, file: &str, args: &[&str]) -> Rendered {
    let [motivation, metrics] = args else {
        return Err(
            "`levels` takes two arguments: a motivation and a comma-separated list of \
                    metrics, e.g. `levels curiosity exploration,battery`"
                .into(),
        );
    };
    let letter = match *motivation {
        "curiosity" => "C",
        "homing" => "H",
        "orientation" => "O",
        "energy" => "E",
        other => {
            return Err(format!(
                "`levels`: unknown motivation `{other}`; known: curiosity, homing, orientation, energy"
            ));
        }
    };
    let results = read_csv(dir, file)?;
    let levels = ["0", "0.2", "0.4", "0.6", "0.8", "1.0"];
    let mut header = vec![letter];
    header.extend(levels);
    let mut rows = Vec::new();
    for metric in metrics.split(',') {
        let label = match metric {
            "recognition" => "% recognition (SOM test)".to_string(),
            other => format!("% {other}"),
        };
        let column = format!("{metric}_pct");
        let mut cells = vec![label];
        for level in levels {
            let level: f64 = level.parse().expect("a level");
            cells.push(level_mean(&results, motivation, level, &column)?);
        }
        rows.push(format!("| {} |", cells.join(" | ")));
    }
    Ok(table(&header, rows))
}

fn level_mean(
    results: &[Row],
    motivation: &str,
    level: f64,
    column: &str,
) -> Result<String, String> {
    let mut per_setting: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for r in results {
        if (num(r, motivation)? - level).abs() < 1e-9 {
            let values = per_setting.entry(cell(r, "setting")?).or_default();
            values.extend(opt_num(r, column)?);
        }
    }
    let means: Vec<f64> = per_setting
        .values()
        .filter(|v| !v.is_empty())
        .map(|v| mean(v))
        .collect();
    Ok(if means.is_empty() {
        "—".into()
    } else {
        fixed(mean(&means), 0)
    })
}

/// The claims from two base seeds and pooled: `replication.csv` of `reproduce --replication`.
fn replication(dir: &Path, file: &str) -> Rendered {
    let header = [
        "claim",
        "base seed 1",
        "base seed 11",
        "pooled",
        "effect [95 % CI]",
        "p",
        "MDD",
        "at the edge",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        let stats = match opt_num(&r, "effect")? {
            Some(d) => format!(
                "{} [{}, {}] | {} | {}",
                signed(d, 1),
                signed(num(&r, "ci_low")?, 1),
                signed(num(&r, "ci_high")?, 1),
                fixed(num(&r, "p")?, 3),
                fixed(num(&r, "mdd")?, 1)
            ),
            None => "— | — | —".into(),
        };
        rows.push(format!(
            "| {} | {} | {} | {} | {stats} | {} | **{}** |",
            claim_name(&r)?,
            cell(&r, "verdict_a")?,
            cell(&r, "verdict_b")?,
            cell(&r, "verdict_pooled")?,
            if cell(&r, "at_edge")? == "true" {
                "yes"
            } else {
                "no"
            },
            cell(&r, "verdict")?
        ));
    }
    Ok(table(&header, rows))
}

/// The claims under each combination (`COMBINATION/claims.csv` of `reproduce --combination`):
/// per combination, each comparison claim's verdict with high and low.
fn combination_claims(dir: &Path, folder: &str) -> Rendered {
    let header = [
        "combination",
        "explores more",
        "more battery",
        "recognises better",
        "homes less",
    ];
    let mut rows = Vec::new();
    for (name, sub) in [
        ("tsk (the paper's)", "default"),
        ("weighted-sum", "weighted-sum"),
        ("weighted-squares", "weighted-squares"),
    ] {
        let mut cells = Vec::new();
        for r in read_csv(&dir.join(folder), &format!("{sub}/claims.csv"))? {
            if !is_summary_claim(&r)? || opt_num(&r, "p")?.is_none() {
                continue;
            }
            let (high, low) = high_low(cell(&r, "evidence")?)?;
            cells.push(format!("{} ({high} vs {low})", cell(&r, "verdict")?));
        }
        rows.push(format!("| {name} | {} |", cells.join(" | ")));
    }
    Ok(table(&header, rows))
}

/// Where each setting's robots sit against the NSGA-II front: `robots.csv` of
/// examples/python/nsga2_terms.py (per setting: the robots' mean objectives, and how many are on,
/// beyond or dominated by the front, with the mean distance).
fn nsga_robots(dir: &Path, file: &str) -> Rendered {
    let header = [
        "setting",
        "robots",
        "mean a / g / b",
        "on the front",
        "beyond it",
        "dominated",
        "mean distance",
    ];
    let all = read_csv(dir, file)?;
    let mut settings: Vec<String> = Vec::new();
    for r in &all {
        let s = cell(r, "setting")?.to_string();
        if !settings.contains(&s) {
            settings.push(s);
        }
    }
    let mut rows = Vec::new();
    for s in settings {
        let mine: Vec<&Row> = all.iter().filter(|r| r["setting"] == s).collect();
        let avg = |c: &str| -> Result<f64, String> {
            let v = mine
                .iter()
                .map(|r| num(r, c))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(mean(&v))
        };
        let count = |p: &str| mine.iter().filter(|r| r["position"].starts_with(p)).count();
        rows.push(format!(
            "| {s} | {} | {} / {} / {} | {} | {} | {} | {} |",
            mine.len(),
            fixed(avg("a")?, 3),
            fixed(avg("g")?, 3),
            fixed(avg("b")?, 3),
            count("on"),
            count("beyond"),
            count("dominated"),
            fixed(avg("distance_to_front")?, 3)
        ));
    }
    Ok(table(&header, rows))
}

/// Each step up in urgency: `urgency.csv` of `reproduce --urgency`.
fn urgency(dir: &Path, file: &str) -> Rendered {
    let header = [
        "measure",
        "u",
        "seeds",
        "lower u",
        "higher u",
        "difference [95 % CI]",
        "p",
        "detectable",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        let verdict = cell(&r, "verdict")?;
        rows.push(format!(
            "| {} | {} → {} | {} | {} | {} | {} [{}, {}] | {} | {} | {} |",
            cell(&r, "measure")?,
            cell(&r, "from")?,
            cell(&r, "to")?,
            cell(&r, "pairs")?,
            fixed(num(&r, "mean_from")?, 1),
            fixed(num(&r, "mean_to")?, 1),
            signed(num(&r, "difference")?, 1),
            signed(num(&r, "ci_low")?, 1),
            signed(num(&r, "ci_high")?, 1),
            fixed(num(&r, "p")?, 3),
            fixed(num(&r, "detectable")?, 1),
            if verdict == "higher" || verdict == "lower" {
                format!("**{verdict}**")
            } else {
                verdict.to_string()
            }
        ));
    }
    Ok(table(&header, rows))
}

/// Each baseline combination against the TSK: `behaviour.csv` of `reproduce --combination`.
fn behaviour(dir: &Path, file: &str) -> Rendered {
    let header = [
        "combination",
        "setting",
        "measure",
        "baseline",
        "TSK",
        "baseline − TSK [95 % CI]",
        "p",
        "detectable",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        let verdict = cell(&r, "verdict")?;
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} [{}, {}] | {} | {} | {} |",
            cell(&r, "combination")?,
            cell(&r, "setting")?,
            cell(&r, "measure")?,
            fixed(num(&r, "mean_combination")?, 1),
            fixed(num(&r, "mean_tsk")?, 1),
            signed(num(&r, "difference")?, 1),
            signed(num(&r, "ci_low")?, 1),
            signed(num(&r, "ci_high")?, 1),
            fixed(num(&r, "p")?, 3),
            fixed(num(&r, "detectable")?, 1),
            if verdict == "higher" || verdict == "lower" {
                format!("**{verdict}**")
            } else {
                verdict.to_string()
            }
        ));
    }
    Ok(table(&header, rows))
}

/// Each baseline's claim effects against the TSK's (`claim_differences.csv` of
/// `reproduce --combination`): per claim, high − low under each, their difference, p, verdict.
fn claim_differences(dir: &Path, file: &str) -> Rendered {
    let header = [
        "combination",
        "claim",
        "high − low, baseline",
        "high − low, TSK",
        "baseline − TSK [95 % CI]",
        "p",
        "detectable",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        let verdict = cell(&r, "verdict")?;
        rows.push(format!(
            "| {} | {} | {} | {} | {} [{}, {}] | {} | {} | {} |",
            cell(&r, "combination")?,
            cell(&r, "claim")?,
            signed(num(&r, "effect_combination")?, 1),
            signed(num(&r, "effect_tsk")?, 1),
            signed(num(&r, "difference")?, 1),
            signed(num(&r, "ci_low")?, 1),
            signed(num(&r, "ci_high")?, 1),
            fixed(num(&r, "p")?, 3),
            fixed(num(&r, "detectable")?, 1),
            if verdict == "higher" || verdict == "lower" {
                format!("**{verdict}**")
            } else {
                verdict.to_string()
            }
        ));
    }
    Ok(table(&header, rows))
}

/// A transfer study measure's words (transfer/*.csv's `measure`).
fn transfer_measure(measure: &str) -> &str {
    match measure {
        "exploration_pct" => "% optimal exploration",
        "homing_pct" => "% homing",
        "battery_pct" => "% battery usage",
        "recognition_pct" => "% recognition",
        "blocked_steps" => "blocked steps",
        "home_pct" => "% of test runs home",
        other => other,
    }
}

/// A verdict of a direction in bold, any other as it is.
fn bold_direction(verdict: &str) -> String {
    if matches!(verdict, "higher" | "lower" | "holds" | "opposite") {
        format!("**{verdict}**")
    } else {
        verdict.to_string()
    }
}

/// Enki against fuzzymotiv per setting and measure: `transfer/comparison.csv` of
/// scripts/transfer_study.sh.
fn transfer(dir: &Path, file: &str) -> Rendered {
    let header = [
        "setting",
        "measure",
        "seeds",
        "fuzzymotiv",
        "Enki",
        "Enki − fuzzymotiv [95 % CI]",
        "p",
        "detectable",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} [{}, {}] | {} | {} | {} |",
            cell(&r, "setting")?,
            transfer_measure(cell(&r, "measure")?),
            cell(&r, "seeds")?,
            fixed(num(&r, "mean_fuzzymotiv")?, 1),
            fixed(num(&r, "mean_enki")?, 1),
            signed(num(&r, "difference")?, 1),
            signed(num(&r, "ci_low")?, 1),
            signed(num(&r, "ci_high")?, 1),
            fixed(num(&r, "p")?, 3),
            fixed(num(&r, "detectable")?, 1),
            bold_direction(cell(&r, "verdict")?)
        ));
    }
    Ok(table(&header, rows))
}

/// Two transfer studies of the same seeds, paired (`pair.csv` of scripts/transfer_study.sh
/// `--against`): args are the label of this study's robots, then the worlds to show (`enki`,
/// `fuzzymotiv`, `gap`).
fn transfer_pair(dir: &Path, file: &str, args: &[&str]) -> Rendered {
    let [label, worlds @ ..] = args else {
        return Err(
            "transfer-pair needs a label and worlds, e.g. `transfer-pair randomised enki gap`"
                .into(),
        );
    };
    let difference = format!("{label} − plain [95 % CI]");
    let header = [
        "setting",
        "measure",
        "world",
        "seeds",
        "plain",
        label,
        difference.as_str(),
        "p",
        "detectable",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        let world = cell(&r, "world")?;
        if !worlds.contains(&world) {
            continue;
        }
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} | {} [{}, {}] | {} | {} | {} |",
            cell(&r, "setting")?,
            transfer_measure(cell(&r, "measure")?),
            if world == "gap" {
                "|Enki − fuzzymotiv|"
            } else {
                world
            },
            cell(&r, "seeds")?,
            fixed(num(&r, "mean_a")?, 1),
            fixed(num(&r, "mean_b")?, 1),
            signed(num(&r, "difference")?, 1),
            signed(num(&r, "ci_low")?, 1),
            signed(num(&r, "ci_high")?, 1),
            fixed(num(&r, "p")?, 3),
            fixed(num(&r, "detectable")?, 1),
            bold_direction(cell(&r, "verdict")?)
        ));
    }
    Ok(table(&header, rows))
}

/// The paper's claims in each world: `transfer/claims.csv` of scripts/transfer_study.sh.
fn transfer_claims(dir: &Path, file: &str) -> Rendered {
    let header = [
        "world",
        "claim",
        "seeds",
        "high",
        "low",
        "high − low [95 % CI]",
        "p",
        "detectable",
        "verdict",
    ];
    let mut rows = Vec::new();
    for r in read_csv(dir, file)? {
        rows.push(format!(
            "| {} | {} | {} | {} | {} | {} [{}, {}] | {} | {} | {} |",
            cell(&r, "world")?,
            cell(&r, "claim")?,
            cell(&r, "seeds")?,
            fixed(num(&r, "high")?, 1),
            fixed(num(&r, "low")?, 1),
            signed(num(&r, "difference")?, 1),
            signed(num(&r, "ci_low")?, 1),
            signed(num(&r, "ci_high")?, 1),
            fixed(num(&r, "p")?, 3),
            fixed(num(&r, "detectable")?, 1),
            bold_direction(cell(&r, "verdict")?)
        ));
    }
    Ok(table(&header, rows))
}

/// Renders a table marker's spec (`PATH: RENDERER [ARGS]`) from the records in `dir`.
fn render_block(dir: &Path, spec: &str) -> Rendered {
    let (path, how) = spec
        .split_once(": ")
        .ok_or_else(|| format!("`{spec}` is not `RECORD: RENDERER [ARGS]`"))?;
    let mut words = how.split_whitespace();
    let renderer = words
        .next()
        .ok_or_else(|| format!("`{spec}` names no renderer"))?;
    let args: Vec<&str> = words.collect();
    if !dir.join(path).exists() {
        return Err(format!("the record {path} is not in {}", dir.display()));
    }
    match renderer {
        "rooms" => rooms(dir, path),
        "claims" => claims(dir, path),
        "room-means" => room_means(dir, path),
        "fig6" => fig6(dir, path),
        "search-strength" => search_strength(dir, path),
        "search-strength-exploration" => search_strength_exploration(dir, path),
        "ablation-claims" => ablation_claims(dir, path),
        "ablation-means" => ablation_means(dir, path),
        "orientation" => orientation(dir, path),
        "levels" => levels(dir, path, &args),
        "replication" => replication(dir, path),
        "claim-differences" => claim_differences(dir, path),
        "behaviour" => behaviour(dir, path),
        "combination-claims" => combination_claims(dir, path),
        "urgency" => urgency(dir, path),
        "nsga-robots" => nsga_robots(dir, path),
        "transfer" => transfer(dir, path),
        "transfer-claims" => transfer_claims(dir, path),
        "transfer-pair" => transfer_pair(dir, path, &args),
        other => Err(format!(
            "unknown renderer `{other}`; the renderers are {RENDERERS}"
        )),
    }
}

// ---------------------------------------------------------------------------------------------
// Values quoted in prose

/// The one row matching every selector (column, `=` equal or `~` containing, text).
fn select<'a>(rows: &'a [Row], selectors: &[(&str, char, &str)]) -> Result<&'a Row, String> {
    let mut found = Vec::new();
    for row in rows {
        let mut all = true;
        for (column, op, text) in selectors {
            let value = cell(row, column)?;
            all &= if *op == '=' {
                value == *text
            } else {
                value.contains(text)
            };
        }
        if all {
            found.push(row);
        }
    }
    match found.as_slice() {
        [row] => Ok(row),
        _ => Err(format!("{} rows match {selectors:?}, not one", found.len())),
    }
}

/// Renders a value marker's spec: `FILE.csv: SELECTOR… COLUMN FORMAT`, where a selector is
/// `column=text` (equal) or `column~text` (contains), or `FILE.json: /JSON/POINTER FORMAT`; the
/// format is `.N` (N decimals), `+.N` (with its sign), `p` (a p-value by the report's rule:
/// three decimals, `< 0.001` below) or `text` (the record's text as it is).
fn render_value(dir: &Path, spec: &str) -> Result<String, String> {
    let (path, how) = spec
        .split_once(": ")
        .ok_or_else(|| format!("`{spec}` is not `RECORD: SELECTOR… COLUMN FORMAT`"))?;
    let words: Vec<&str> = how.split_whitespace().collect();
    let [selectors @ .., column, format] = words.as_slice() else {
        return Err(format!(
            "`{spec}` needs selectors, a column and a format (e.g. `.1`)"
        ));
    };
    if *format == "text" {
        return text_value(dir, path, selectors, column);
    }
    let x = if path.ends_with(".json") {
        if !selectors.is_empty() {
            return Err(format!(
                "`{spec}`: a JSON record takes one pointer and a format"
            ));
        }
        json_num(&read_json(dir, path)?, column)?
    } else {
        let rows = read_csv(dir, path)?;
        num(select(&rows, &parse_selectors(selectors)?)?, column)?
    };
    if *format == "p" {
        // A p-value by the report's one number rule (three decimals, `< 0.001` below).
        return Ok(fuzzymotiv_pipeline::render::claim_format::p_text(x));
    }
    let (sign, digits) = match format.strip_prefix('+') {
        Some(rest) => (true, rest),
        None => (false, *format),
    };
    let digits: usize = digits
        .strip_prefix('.')
        .and_then(|d| d.parse().ok())
        .ok_or_else(|| format!("format `{format}` is not `.N`, `+.N`, `p` or `text`"))?;
    Ok(if sign {
        signed(x, digits)
    } else {
        fixed(x, digits)
    })
}

/// A value marker's text as it stands in its record (format `text`): a JSON string at a
/// pointer, or a CSV cell.
fn text_value(dir: &Path, path: &str, selectors: &[&str], column: &str) -> Result<String, String> {
    if path.ends_with(".json") {
        let json = read_json(dir, path)?;
        return json
            .pointer(column)
            .and_then(serde_json::Value::as_str)
            .map(String::from)
            .ok_or_else(|| format!("{path} has no text at {column}"));
    }
    let rows = read_csv(dir, path)?;
    Ok(cell(select(&rows, &parse_selectors(selectors)?)?, column)?.to_string())
}

fn parse_selectors<'a>(selectors: &[&'a str]) -> Result<Vec<(&'a str, char, &'a str)>, String> {
    let mut parsed = Vec::new();
    for selector in selectors {
        let op = selector.find(['=', '~']).ok_or_else(|| {
            format!("selector `{selector}` is not `column=text` or `column~text`")
        })?;
        parsed.push((
            &selector[..op],
            selector.as_bytes()[op] as char,
            &selector[op + 1..],
        ));
    }
    Ok(parsed)
}

// ---------------------------------------------------------------------------------------------
// Documents

/// A place where a document and its records disagree.
struct Difference {
    line: usize,
    document: String,
    records: String,
}

/// Renders every marker of `text` from the records in `dir`: the text as the records say it,
/// and where it differs. An unreadable marker is an error naming its line.
fn render_document(text: &str, dir: &Path) -> Result<(String, Vec<Difference>), String> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out: Vec<String> = Vec::new();
    let mut differences = Vec::new();
    let (mut i, mut fenced) = (0, false);
    while i < lines.len() {
        let line = lines[i];
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        if fenced {
            out.push(line.into());
            i += 1;
            continue;
        }
        if let Some(spec) = line
            .strip_prefix(BLOCK_START)
            .and_then(|s| s.strip_suffix(" -->"))
        {
            let end = lines[i..]
                .iter()
                .position(|l| *l == BLOCK_END)
                .map(|n| i + n)
                .ok_or_else(|| format!("line {}: `{line}` has no `{BLOCK_END}`", i + 1))?;
            let rendered = render_block(dir, spec).map_err(|e| format!("line {}: {e}", i + 1))?;
            let current: Vec<String> = lines[i + 1..end].iter().map(|l| l.to_string()).collect();
            if current != rendered {
                differences.push(Difference {
                    line: i + 2,
                    document: current.join("\n"),
                    records: rendered.join("\n"),
                });
            }
            out.push(line.into());
            out.extend(rendered);
            out.push(BLOCK_END.into());
            i = end + 1;
            continue;
        }
        let rendered = render_values(line, dir).map_err(|e| format!("line {}: {e}", i + 1))?;
        if rendered != line {
            differences.push(Difference {
                line: i + 1,
                document: line.into(),
                records: rendered.clone(),
            });
        }
        out.push(rendered);
        i += 1;
    }
    let mut new_text = out.join("\n");
    if text.ends_with('\n') {
        new_text.push('\n');
    }
    Ok((new_text, differences))
}

/// A line with each `<!-- value RECORD: SELECTOR… COLUMN FORMAT -->TEXT<!-- end -->` re-rendered.
fn render_values(line: &str, dir: &Path) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find(VALUE_START) {
        let after = &rest[start + VALUE_START.len()..];
        let close = after.find(" -->").ok_or("a value marker without ` -->`")?;
        let spec = &after[..close];
        let body = &after[close + " -->".len()..];
        let end = body
            .find(VALUE_END)
            .ok_or_else(|| format!("the value marker `{spec}` has no `{VALUE_END}` on its line"))?;
        out.push_str(&rest[..start + VALUE_START.len() + close + " -->".len()]);
        out.push_str(&render_value(dir, spec)?);
        out.push_str(VALUE_END);
        rest = &body[end + VALUE_END.len()..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The record paths (relative to docs/results/) that a document's markers name.
fn quoted_records(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    let mut fenced = false;
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        }
        if fenced {
            continue;
        }
        let mut specs: Vec<&str> = Vec::new();
        if let Some(spec) = line.strip_prefix(BLOCK_START) {
            specs.push(spec);
        }
        specs.extend(line.split(VALUE_START).skip(1));
        for spec in specs {
            if let Some((path, _)) = spec.split_once(": ") {
                found.push((n + 1, path.to_string()));
            }
        }
    }
    found
}

fn records_dir() -> PathBuf {
    root().join("docs/results")
}

#[test]
fn documents_say_what_the_records_say() {
    let bless = std::env::var_os("FUZZYMOTIV_BLESS").is_some_and(|v| v == "1");
    let mut report = Vec::new();
    for doc in documents() {
        let text = fs::read_to_string(root().join(&doc)).expect("a readable document");
        let (new_text, differences) = match render_document(&text, &records_dir()) {
            Ok(rendered) => rendered,
            Err(e) => panic!("{}: {e}", doc.display()),
        };
        if bless && new_text != text {
            fs::write(root().join(&doc), &new_text).expect("the document is writable");
            eprintln!("rewrote {} ({} places)", doc.display(), differences.len());
        } else if !bless {
            for d in differences {
                report.push(format!(
                    "{}:{}\n  the document says:\n{}\n  the records say:\n{}",
                    doc.display(),
                    d.line,
                    d.document,
                    d.records
                ));
            }
        }
    }
    assert!(
        report.is_empty(),
        "the documents do not say what docs/results/ says (rewrite them with \
         `FUZZYMOTIV_BLESS=1 cargo test -p fuzzymotiv-cli --test it documents::` and review the \
         diff):\n\n{}",
        report.join("\n\n")
    );
}

#[test]
fn every_record_a_document_quotes_exists() {
    let mut missing = Vec::new();
    let mut quoted = 0;
    for doc in documents() {
        let text = fs::read_to_string(root().join(&doc)).expect("a readable document");
        for (line, path) in quoted_records(&text) {
            quoted += 1;
            if !records_dir().join(&path).exists() {
                missing.push(format!("{}:{line}: docs/results/{path}", doc.display()));
            }
        }
    }
    assert!(
        quoted > 0,
        "no document quotes a record: the markers are gone"
    );
    assert!(
        missing.is_empty(),
        "records the documents quote are missing:\n{}",
        missing.join("\n")
    );
}

fn small_records() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("a temp dir");
    fs::create_dir(dir.path().join("study")).unwrap();
    fs::write(
        dir.path().join("study/claims.csv"),
        "claim,p,mdd\nexplores,0.168,3.2\nbattery,0.0117,2.5\n",
    )
    .unwrap();
    dir
}

#[test]
fn a_marker_naming_an_unknown_renderer_fails_with_a_clear_message() {
    let dir = small_records();
    let doc = "text\n<!-- record study/claims.csv: nope -->\n| a |\n<!-- end record -->\n";
    let error = render_document(doc, dir.path())
        .err()
        .expect("an unknown renderer fails");
    assert!(
        error.starts_with("line 2: unknown renderer `nope`; the renderers are rooms"),
        "{error}"
    );
}

#[test]
fn a_value_naming_an_unknown_column_fails_with_a_clear_message() {
    let dir = small_records();
    let doc = "p is <!-- value study/claims.csv: claim=battery nope .3 -->0.012<!-- end -->.\n";
    let error = render_document(doc, dir.path())
        .err()
        .expect("an unknown column fails");
    assert_eq!(
        error,
        "line 1: no column `nope` in the record; its columns are claim, mdd, p"
    );
}

#[test]
fn a_value_renders_from_its_row_and_a_stale_one_is_a_difference() {
    let dir = small_records();
    let doc = "p <!-- value study/claims.csv: claim~batt p .3 -->0.011<!-- end --> here\n";
    let (text, differences) = render_document(doc, dir.path()).expect("renders");
    assert_eq!(
        text,
        "p <!-- value study/claims.csv: claim~batt p .3 -->0.012<!-- end --> here\n"
    );
    assert_eq!(differences.len(), 1);
    assert_eq!(differences[0].line, 1);
}

#[test]
fn a_marker_naming_a_missing_record_fails_with_a_clear_message() {
    let dir = small_records();
    let doc = "<!-- record study/table9.csv: rooms -->\n<!-- end record -->\n";
    let error = render_document(doc, dir.path())
        .err()
        .expect("a missing record fails");
    assert!(
        error.starts_with("line 1: the record study/table9.csv is not in "),
        "{error}"
    );
}

#[test]
fn a_stale_table_is_rewritten_from_its_record_and_named_by_its_line() {
    let dir = small_records();
    fs::write(
        dir.path().join("study/ablation.csv"),
        "variant,a,b,c,d,e,f\ndefault,false,true,false,true,false,true\n",
    )
    .unwrap();
    fs::create_dir_all(dir.path().join("study/default")).unwrap();
    fs::write(
        dir.path().join("study/default/claims.csv"),
        "claim,verdict\na,not significant\na — x,holds\nb,holds\nc,opposite\nd,holds\ne,fails\nf,holds\n",
    )
    .unwrap();
    let doc = "# A\n<!-- record study/ablation.csv: ablation-claims -->\n| old |\n<!-- end record -->\nafter\n";
    let (text, differences) = render_document(doc, dir.path()).expect("renders");
    assert_eq!(differences.len(), 1);
    assert_eq!(differences[0].line, 3);
    assert_eq!(differences[0].document, "| old |");
    assert!(
        text.contains("| default | not significant | holds | opposite | holds | fails | holds |\n<!-- end record -->\nafter\n"),
        "{text}"
    );
}

#[test]
fn a_value_reads_a_json_pointer() {
    let dir = small_records();
    fs::write(
        dir.path().join("study/summary.json"),
        r#"{"settings": [{"mean": -0.1234}]}"#,
    )
    .unwrap();
    let doc = "F <!-- value study/summary.json: /settings/0/mean +.2 -->0<!-- end -->\n";
    let (text, _) = render_document(doc, dir.path()).expect("renders");
    assert_eq!(
        text,
        "F <!-- value study/summary.json: /settings/0/mean +.2 -->−0.12<!-- end -->\n"
    );
}

/// Issue #52 item 7: the README gives the default study's time as docs/guide/performance.md
/// measured it (the first twenty-seed row, rounded to the second), in both places it says it,
/// and the CLI guide names the study's run directories up to the default number of seeds.
#[test]
fn the_readme_and_cli_guide_state_the_default_study_as_measured() {
    let read = |p: &str| fs::read_to_string(root().join(p)).unwrap();
    let (readme, performance, cli) = (
        read("README.md"),
        read("docs/guide/performance.md"),
        read("docs/guide/cli.md"),
    );
    let row = (performance.lines())
        .find(|l| l.contains("**the paper's twenty-seed study**"))
        .unwrap();
    let measured: f64 = row
        .split("wall time (")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let seconds = format!("{} s", measured.round());
    assert!(!readme.contains("four minutes"), "README: an old time");
    assert_eq!(
        readme.matches(&seconds).count(),
        2,
        "README quotes {seconds} twice"
    );
    assert_eq!(readme.matches("about a minute and a half").count(), 2);
    let help = std::process::Command::new(env!("CARGO_BIN_EXE_fuzzymotiv"))
        .args(["reproduce", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    let seeds_line = help
        .lines()
        .find(|l| l.contains("--seeds <SEEDS>"))
        .unwrap();
    let seeds: usize = (seeds_line
        .split("[default: ")
        .nth(1)
        .unwrap()
        .split(']')
        .next())
    .unwrap()
    .parse()
    .unwrap();
    assert!(
        cli.contains(&format!("`seed-{seeds:02}/`")),
        "cli.md: the last seed directory"
    );
}
