//! `fuzzymotiv reproduce`: the paper's study (SPEC §12) in one command.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use fuzzymotiv::config::RawConfig;

use crate::error::CliError;
use crate::files::{OutState, StagedDir, check_out};
use crate::inputs::resolve;
use crate::png::write_figure;
use crate::progress::Progress;
use crate::report::{Section, reproduce_page};
use crate::run::{Finished, RoomRow, execute, resolved_toml, set_threads, start_line};
use crate::svg::{best_paths_svg, fitness_svg};

/// Arguments of `fuzzymotiv reproduce`.
#[derive(clap::Args)]
pub struct ReproduceArgs {
    /// Output directory [default: results; with --quick results-quick; with --orientation
    /// results-orientation(-quick)]. Another study's results there are kept unless --force.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace another study's results in --out (or an unfinished one) and start over.
    #[arg(long)]
    pub force: bool,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Base seed of both settings: a whole number from 0 to 2^53 − 1.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true, value_parser = crate::inputs::parse_seed)]
    pub seed: u64,
    /// A fast look: GA 30 × 30 instead of the paper's 200 × 200.
    #[arg(long)]
    pub quick: bool,
    /// Worker threads [default: all cores]; results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Run the orientation study instead (configs/orientation-study.toml): does rewarding
    /// orientation (online recognition in the fitness) raise recognition, and at what cost?
    #[arg(long)]
    pub orientation: bool,
    /// Override a config key of both settings (repeatable), e.g. --set trial.steps=200.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Also write a PNG beside every SVG figure.
    #[arg(long)]
    pub png: bool,
}

/// A built-in setting of the study with the paper's table.
pub struct Setting {
    /// Run directory name.
    pub name: &'static str,
    /// Figure/file tag.
    pub tag: &'static str,
    /// Built-in config.
    pub config: &'static str,
    /// The paper's table: room, average fitness, % exploration, % recognition, % battery.
    pub paper: [(&'static str, f64, f64, f64, f64); 5],
}

/// The paper's two settings (Tables 1 and 2).
pub const SETTINGS: [Setting; 2] = [
    Setting {
        name: "high-curiosity",
        tag: "high_curiosity",
        config: include_str!("../../../configs/high-curiosity.toml"),
        paper: [
            ("H", 0.6421, 93.84, 80.00, 79.19),
            ("T", 0.6686, 91.77, 100.00, 78.45),
            ("L", 0.6507, 97.04, 100.00, 79.58),
            ("square", 0.6699, 99.88, 100.00, 79.56),
            ("rectangle", 0.6377, 95.29, 100.00, 79.88),
        ],
    },
    Setting {
        name: "low-curiosity",
        tag: "low_curiosity",
        config: include_str!("../../../configs/low-curiosity.toml"),
        paper: [
            ("H", 0.2465, 54.66, 20.00, 57.90),
            ("T", 0.2694, 57.84, 0.00, 59.66),
            ("L", 0.2707, 57.93, 0.00, 59.67),
            ("square", 0.3274, 80.63, 100.00, 74.64),
            ("rectangle", 0.267, 57.70, 0.00, 59.60),
        ],
    },
];

impl ReproduceArgs {
    /// `--out`, or the default for the study and its size (a quick look never lands in the
    /// full study's directory).
    pub fn out_dir(&self) -> PathBuf {
        self.out.clone().unwrap_or_else(|| {
            let base = if self.orientation {
                "results-orientation"
            } else {
                "results"
            };
            PathBuf::from(if self.quick {
                format!("{base}-quick")
            } else {
                base.to_string()
            })
        })
    }
}

/// Entry point of `fuzzymotiv reproduce`.
pub fn reproduce(args: ReproduceArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    if args.orientation {
        return orientation_study(&args);
    }
    let out = args.out_dir();
    let start = Instant::now();
    let mut sets = Vec::new();
    if args.quick {
        sets.push("ga.population=30".to_string());
        sets.push("ga.generations=30".to_string());
    }
    sets.push(format!("seed={}", args.seed));
    sets.extend(args.sets.iter().cloned());
    // Validate both settings before anything is written.
    let loaded = SETTINGS
        .iter()
        .map(|s| {
            let source = format!("built-in config {}", s.name);
            let raw = RawConfig::parse(s.config, &source, &sets)?;
            resolve(raw, std::path::Path::new("."), &source)
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    // The study is "the same" when both settings' resolved configs are.
    let id: Vec<(String, String)> = SETTINGS
        .iter()
        .zip(&loaded)
        .map(|(s, l)| {
            (
                format!("{}/config.resolved.toml", s.name),
                resolved_toml(&l.raw),
            )
        })
        .collect();
    match check_out(&out, &id, args.force)? {
        OutState::Done => {
            eprintln!(
                "{} already holds this study, finished (same resolved configs); nothing to do. --force runs it again",
                out.display()
            );
            return Ok(());
        }
        OutState::Unfinished => {
            return Err(CliError::input(format!(
                "{}: an unfinished study of this command is in {}; reproduce cannot resume it: pass --force to discard it and start over",
                out.display(),
                StagedDir::staging_path(&out).display()
            )));
        }
        OutState::Fresh => {}
    }
    let staged = StagedDir::new(&out)?;
    let progress = Progress::new(&loaded[0].experiment, SETTINGS.len(), args.quiet);
    let mut finished: Vec<Finished> = Vec::new();
    for (setting, l) in SETTINGS.iter().zip(&loaded) {
        progress.set_prefix(&format!("{} seed {}", setting.name, args.seed));
        progress.note(&start_line(&l.experiment, &out.join(setting.name)));
        finished.push(execute(
            l,
            &staged.staging.join(setting.name),
            &progress,
            false,
            args.png,
        )?);
    }
    progress.finish();
    let mut settings_json = Vec::new();
    let mut panels = Vec::new();
    for (k, ((setting, l), done)) in SETTINGS.iter().zip(&loaded).zip(&finished).enumerate() {
        let (md, csv) = table(setting, &done.rows);
        staged.write(&format!("table{}.md", k + 1), &md)?;
        staged.write(&format!("table{}.csv", k + 1), &csv)?;
        println!(
            "Table {} — {} (C, H, O, E) = {:?}\n{md}",
            k + 1,
            setting.name,
            l.experiment.motivations.as_array()
        );
        let exp = &l.experiment;
        let evo = &done.evolutions[0];
        panels.push((
            format!(
                "{} (C,H,O,E) = {:?}",
                setting.name,
                exp.motivations.as_array()
            ),
            evo.history.clone(),
        ));
        let title = format!(
            "Best robot, {} (C, H, O, E) = {:?}",
            setting.name,
            exp.motivations.as_array()
        );
        write_figure(
            &staged,
            &format!("trajectories_{}", setting.tag),
            &best_paths_svg(&title, exp, &done.trajectories),
            args.png,
        )?;
        let m = exp.motivations;
        let rows: Vec<serde_json::Value> = done
            .rows
            .iter()
            .map(|r| {
                serde_json::json!({
                    "room": r.room,
                    "average_fitness": r.average_fitness,
                    "exploration_pct": r.exploration_pct,
                    "recognition_pct": r.recognition_pct,
                    "battery_pct": r.battery_pct,
                    "homing": r.homing,
                })
            })
            .collect();
        settings_json.push(serde_json::json!({
            "name": setting.name,
            "motivations": {"curiosity": m.curiosity, "homing": m.homing, "orientation": m.orientation, "energy": m.energy},
            "rows": rows,
            "first_generation": {"best": evo.history[0].stats.best, "mean": evo.history[0].stats.mean},
            "last_generation": {"best": evo.history.last().map(|h| h.stats.best), "mean": evo.history.last().map(|h| h.stats.mean)},
            "population": exp.ga.population,
            "generations": exp.ga.generations,
            "run_dir": setting.name,
            "confusion": done.aem.iter().map(|a| &a.confusion.counts).collect::<Vec<_>>(),
        }));
    }
    write_figure(&staged, "fitness", &fitness_svg(&panels), args.png)?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let sections: Vec<Section<'_>> = SETTINGS
        .iter()
        .zip(&loaded)
        .zip(&finished)
        .map(|((setting, l), done)| Section {
            id: setting.name,
            title: setting.name.to_string(),
            loaded: l,
            done,
            paper: Some(setting),
            link: Some(format!("{}/report.html", setting.name)),
        })
        .collect();
    staged.write(
        "report.html",
        reproduce_page(&sections, args.seed, &args.sets, wall_seconds),
    )?;
    let summary = serde_json::json!({
        "program": "fuzzymotiv",
        "version": fuzzymotiv::VERSION,
        "seed": args.seed,
        "quick": args.quick,
        "overrides": args.sets,
        "settings": settings_json,
        "wall_seconds": wall_seconds,
    });
    staged.write(
        "summary.json",
        serde_json::to_string_pretty(&summary).expect("serialisable") + "\n",
    )?;
    staged.commit()?;
    eprintln!(
        "wrote {} ({:.1} s)",
        out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn paper_row(setting: &Setting, room: &str) -> Option<(f64, f64, f64, f64)> {
    setting
        .paper
        .iter()
        .find(|p| p.0 == room)
        .map(|p| (p.1, p.2, p.3, p.4))
}

/// A table with the paper's values beside ours: (Markdown, CSV).
fn table(setting: &Setting, rows: &[RoomRow]) -> (String, String) {
    let mut md = String::from(
        "| room | average fitness (paper) | % optimal exploration (paper) | % recognition (paper) | % battery usage (paper) | % homing |\n|---|---|---|---|---|---|\n",
    );
    let mut csv = String::from(
        "room,average_fitness,paper_average_fitness,exploration_pct,paper_exploration_pct,recognition_pct,paper_recognition_pct,battery_pct,paper_battery_pct,homing_pct\n",
    );
    let opt = |v: Option<f64>, p: usize| v.map_or(String::new(), |v| format!("{v:.p$}"));
    for r in rows {
        let p = paper_row(setting, &r.room);
        let rec = r
            .recognition_pct
            .map_or("n/a".to_string(), |v| format!("{v:.0}"));
        let _ = writeln!(
            md,
            "| {} | {:.4} ({}) | {:.1} ({}) | {} ({}) | {:.1} ({}) | {:.1} |",
            r.room,
            r.average_fitness,
            opt(p.map(|p| p.0), 4),
            r.exploration_pct,
            opt(p.map(|p| p.1), 2),
            rec,
            opt(p.map(|p| p.2), 0),
            r.battery_pct,
            opt(p.map(|p| p.3), 2),
            r.homing
        );
        let _ = writeln!(
            csv,
            "{},{:.6},{},{:.4},{},{},{},{:.4},{},{:.4}",
            r.room,
            r.average_fitness,
            opt(p.map(|p| p.0), 4),
            r.exploration_pct,
            opt(p.map(|p| p.1), 2),
            opt(r.recognition_pct, 1),
            opt(p.map(|p| p.2), 2),
            r.battery_pct,
            opt(p.map(|p| p.3), 2),
            r.homing
        );
    }
    (md, csv)
}

/// The orientation study: a built-in sweep (three motivation settings × seeds, online
/// orientation), run in-process, then merged into tables and plots.
fn orientation_study(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let out = args.out_dir();
    let mut text = include_str!("../../../configs/orientation-study.toml").to_string();
    let mut sets: Vec<String> = Vec::new();
    sets.push(format!("seed={}", args.seed));
    if args.quick {
        sets.push("ga.population=30".into());
        sets.push("ga.generations=30".into());
        sets.push("sweep.replicates=2".into());
    }
    sets.extend(args.sets.iter().cloned());
    if !sets.is_empty() {
        // Apply overrides to the document (config keys and sweep keys alike).
        let mut table: toml::Table = toml::from_str(&text).expect("built-in sweep is valid TOML");
        fuzzymotiv::config::apply_sets(&mut table, &sets)?;
        text = toml::to_string(&table).expect("a table serialises");
    }
    let sweep = crate::sweep::Sweep::parse_str(
        &text,
        "built-in orientation study",
        std::path::Path::new("."),
    )?;
    let all: Vec<usize> = (0..sweep.jobs.len()).collect();
    eprintln!(
        "orientation study: {} jobs into {}",
        all.len(),
        out.display()
    );
    crate::sweep::run_jobs(&sweep, &text, &all, &out, args.quiet)?;
    crate::sweep::merge(crate::sweep::MergeArgs { dir: out })?;
    eprintln!(
        "orientation study done in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
