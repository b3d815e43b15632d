//! `fuzzymotiv run`: evolve, model the rooms, write the run directory.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use fuzzymotiv::config::{RawConfig, Training};
use fuzzymotiv::experiment::{AemReport, Evolution, Experiment};
use fuzzymotiv::trial::Trajectory;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

use crate::error::CliError;
use crate::files::{StagedDir, num};
use crate::inputs::{Loaded, load_config};
use crate::png::write_figure;
use crate::report;
use crate::svg::{fitness_svg, terms_svg, trajectories_svg};

/// Arguments of `fuzzymotiv run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// Experiment config (TOML); every key is optional (SPEC defaults).
    pub config: PathBuf,
    /// Output directory [default: runs/NAME].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Base seed (overrides `seed` in the config).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads [default: all cores]; results do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Override a config key, e.g. --set ga.population=20 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Also write a PNG beside every SVG figure.
    #[arg(long)]
    pub png: bool,
}

/// Configures rayon's global pool.
pub fn set_threads(threads: Option<usize>) -> Result<(), CliError> {
    if let Some(n) = threads {
        if n == 0 {
            return Err(CliError::input("--threads must be at least 1"));
        }
        // A second call (e.g. in-process tests) keeps the first pool; results do not depend on it.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
    }
    Ok(())
}

/// Entry point of `fuzzymotiv run`.
pub fn run(args: RunArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    let loaded = load_config(Some(&args.config), &args.sets, args.seed)?;
    let out = args
        .out
        .unwrap_or_else(|| Path::new("runs").join(&loaded.raw.name));
    let progress = progress_bar(&loaded.experiment, 1, "");
    let done = execute(&loaded, &out, &progress, args.png)?;
    progress.finish_and_clear();
    print!("{}", table_markdown(&done.rows));
    eprintln!("wrote {} ({:.1} s)", out.display(), done.wall_seconds);
    Ok(())
}

/// A progress bar over all generations of `settings` experiments like this one; hidden when
/// stderr is not a terminal.
pub fn progress_bar(exp: &Experiment, settings: usize, prefix: &str) -> ProgressBar {
    let total = (exp.runs().len() * exp.ga.generations * settings) as u64;
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template(
            "{prefix} [{elapsed_precise}] {wide_bar} gen {pos}/{len} {msg} (eta {eta})",
        )
        .expect("valid template"),
    );
    bar.set_prefix(prefix.to_string());
    bar
}

/// One row of the per-room table (SPEC §12).
#[derive(Debug, Clone, Serialize)]
pub struct RoomRow {
    /// Room name.
    pub room: String,
    /// Mean F of the final population in this room.
    pub average_fitness: f64,
    /// Mean 100·a over the test runs.
    pub exploration_pct: f64,
    /// Correct recognitions in %, when AEM ran.
    pub recognition_pct: Option<f64>,
    /// Mean 100·b over the test runs.
    pub battery_pct: f64,
    /// Mean 100·g over the test runs.
    pub homing: f64,
    /// The room instance's r-node.
    pub r_node: Option<usize>,
}

/// Everything a finished run produced.
pub struct Finished {
    /// One evolution per run of the protocol.
    pub evolutions: Vec<Evolution>,
    /// One AEM report per evolution.
    pub aem: Vec<AemReport>,
    /// The per-room table.
    pub rows: Vec<RoomRow>,
    /// Per room, the best robot's room-modelling run (the one whose actions became the room's
    /// stored instance): for figures and the replay.
    pub trajectories: Vec<Trajectory>,
    /// Wall time (s).
    pub wall_seconds: f64,
}

/// The evolution whose best robot stands for room `r` (the one robot of all-rooms training, or
/// the room's own robot), and the room's position among that evolution's rooms.
pub fn robot_for_room(evolutions: &[Evolution], r: usize) -> (&Evolution, usize) {
    match evolutions.len() {
        1 => (&evolutions[0], r),
        _ => (&evolutions[r], 0),
    }
}

/// The AEM report of the robot that stands for room `r` (see [`robot_for_room`]).
pub fn aem_for_room(aem: &[AemReport], r: usize) -> &AemReport {
    if aem.len() == 1 { &aem[0] } else { &aem[r] }
}

/// The best robot's room-modelling run in every room.
pub fn best_trajectories(exp: &Experiment, evolutions: &[Evolution]) -> Vec<Trajectory> {
    (0..exp.arenas.len())
        .map(|r| {
            let (evo, _) = robot_for_room(evolutions, r);
            exp.instance_trajectory(&evo.population[evo.best], &evo.run, r)
        })
        .collect()
}

/// Runs a loaded config and writes its run directory `out` (atomically), with `report.html`
/// and the figures (and their PNGs with `png`).
pub fn execute(
    loaded: &Loaded,
    out: &Path,
    progress: &ProgressBar,
    png: bool,
) -> Result<Finished, CliError> {
    let exp = &loaded.experiment;
    let start = Instant::now();
    let staged = StagedDir::new(out)?;
    staged.write("config.resolved.toml", resolved_toml(&loaded.raw))?;
    let mut evolutions = Vec::new();
    let mut csv = String::from("generation,best,mean,std,min,max,a,g,l,b,room\n");
    for run in exp.runs() {
        let evo = exp.evolve(&run, &mut |rec| {
            progress.inc(1);
            progress.set_message(format!("best F {:.3}", rec.stats.best));
        });
        for rec in &evo.history {
            let s = rec.stats;
            let t = rec.terms;
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{},{}",
                rec.generation,
                num(s.best),
                num(s.mean),
                num(s.std),
                num(s.min),
                num(s.max),
                num(t.a),
                num(t.g),
                num(t.l),
                num(t.b),
                run.label
            );
        }
        evolutions.push(evo);
    }
    staged.write("generations.csv", &csv)?;
    let aem: Vec<AemReport> = evolutions
        .iter()
        .map(|evo| exp.environment_modelling(&evo.population[evo.best], &evo.run))
        .collect::<Result<_, _>>()
        .map_err(|e| CliError::runtime(format!("environment modelling failed: {e}")))?;
    let rows = room_rows(exp, &evolutions, &aem);
    staged.write("best_genome.json", best_genome_json(exp, &evolutions)?)?;
    staged.write("recognition.csv", recognition_csv(exp, &aem, &rows))?;
    staged.write("table.md", table_markdown(&rows))?;
    let trajectories = best_trajectories(exp, &evolutions);
    let panels: Vec<_> = evolutions
        .iter()
        .map(|e| {
            let title = match exp.training {
                Training::AllRooms => {
                    format!("{} (C,H,O,E) = {:?}", exp.name, exp.motivations.as_array())
                }
                Training::PerRoom => format!("{}: robot evolved in {}", exp.name, e.run.label),
            };
            (title, e.history.clone())
        })
        .collect();
    write_figure(&staged, "fitness", &fitness_svg(&panels), png)?;
    write_figure(&staged, "terms", &terms_svg(&panels), png)?;
    let pairs: Vec<_> = exp
        .arenas
        .iter()
        .map(|a| a.room())
        .zip(trajectories.iter())
        .collect();
    let title = format!(
        "Best robot, {} (C, H, O, E) = {:?}",
        exp.name,
        exp.motivations.as_array()
    );
    write_figure(
        &staged,
        "trajectories",
        &trajectories_svg(&title, &pairs),
        png,
    )?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let summary = summary_json(exp, &evolutions, &rows, wall_seconds);
    staged.write(
        "summary.json",
        serde_json::to_string_pretty(&summary).expect("serialisable") + "\n",
    )?;
    let done = Finished {
        evolutions,
        aem,
        rows,
        trajectories,
        wall_seconds,
    };
    staged.write("report.html", report::run_page(loaded, &done))?;
    staged.commit()?;
    Ok(done)
}

/// The resolved config with the program version on top.
pub fn resolved_toml(raw: &RawConfig) -> String {
    format!(
        "# Resolved configuration written by fuzzymotiv {} (all keys, with the seed).\n# Re-run: fuzzymotiv run config.resolved.toml\n{}",
        fuzzymotiv::VERSION,
        raw.to_toml()
    )
}

/// Per-room rows: all-rooms uses the one robot everywhere; per-room uses each room's robot.
pub fn room_rows(exp: &Experiment, evolutions: &[Evolution], aem: &[AemReport]) -> Vec<RoomRow> {
    exp.room_names()
        .into_iter()
        .enumerate()
        .map(|(r, room)| {
            let (k, evo, rep) = match evolutions.len() {
                1 => (r, &evolutions[0], &aem[0]),
                _ => (0, &evolutions[r], &aem[r]),
            };
            let a = &rep.rooms[r];
            RoomRow {
                room,
                average_fitness: evo.mean_room_fitness(k),
                exploration_pct: a.exploration_pct,
                recognition_pct: a.recognition_pct,
                battery_pct: a.battery_pct,
                homing: a.homing_pct,
                r_node: a.r_node,
            }
        })
        .collect()
}

fn best_genome_json(exp: &Experiment, evolutions: &[Evolution]) -> Result<String, CliError> {
    let names = exp.room_names();
    let runs: Vec<serde_json::Value> = evolutions
        .iter()
        .map(|evo| {
            let e = &evo.evaluations[evo.best];
            let terms: Vec<serde_json::Value> = evo
                .run
                .rooms
                .iter()
                .zip(&e.per_room)
                .map(|(&r, s)| {
                    serde_json::json!({"room": names[r], "f": s.f, "a": s.terms.a, "g": s.terms.g, "l": s.terms.l, "b": s.terms.b})
                })
                .collect();
            serde_json::json!({
                "run": evo.run.label,
                "generation": evo.history.len() - 1,
                "individual": evo.best,
                "fitness": e.fitness,
                "terms": terms,
                "weights": evo.population[evo.best],
            })
        })
        .collect();
    let first = runs[0].clone();
    let doc = serde_json::json!({
        "program": "fuzzymotiv",
        "version": fuzzymotiv::VERSION,
        "seed": exp.seed,
        "shape": exp.shape,
        "layout": "per hidden unit [bias, 8 input weights], then per output [bias, hidden weights]",
        "run": first["run"],
        "fitness": first["fitness"],
        "terms": first["terms"],
        "weights": first["weights"],
        "runs": runs,
    });
    Ok(serde_json::to_string_pretty(&doc).expect("serialisable") + "\n")
}

fn recognition_csv(exp: &Experiment, aem: &[AemReport], rows: &[RoomRow]) -> String {
    let names = exp.room_names();
    let mut s = String::from("room,test_runs,correct,recognition_pct");
    for n in &names {
        let _ = write!(s, ",as_{n}");
    }
    s.push_str(",not_recognised\n");
    for (r, row) in rows.iter().enumerate() {
        let rep = if aem.len() == 1 { &aem[0] } else { &aem[r] };
        let counts = &rep.confusion.counts[r];
        let total: u32 = counts.iter().sum();
        let _ = write!(
            s,
            "{},{},{},{}",
            row.room,
            total,
            rep.confusion.correct(r),
            row.recognition_pct
                .map_or(String::new(), |p| format!("{p:.1}"))
        );
        for c in counts {
            let _ = write!(s, ",{c}");
        }
        s.push('\n');
    }
    s
}

/// The per-room table as Markdown.
pub fn table_markdown(rows: &[RoomRow]) -> String {
    let mut s = String::from(
        "| room | average fitness | % optimal exploration | % recognition | % battery usage | % homing |\n|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.3} | {:.1} | {} | {:.1} | {:.1} |",
            r.room,
            r.average_fitness,
            r.exploration_pct,
            r.recognition_pct
                .map_or("n/a".to_string(), |p| format!("{p:.0}")),
            r.battery_pct,
            r.homing
        );
    }
    s
}

fn summary_json(
    exp: &Experiment,
    evolutions: &[Evolution],
    rows: &[RoomRow],
    wall_seconds: f64,
) -> serde_json::Value {
    let runs: Vec<serde_json::Value> = evolutions
        .iter()
        .map(|evo| {
            let first = evo.history.first().expect("at least one generation");
            let last = evo.history.last().expect("at least one generation");
            serde_json::json!({
                "run": evo.run.label,
                "first_generation": {"best": first.stats.best, "mean": first.stats.mean},
                "last_generation": {"best": last.stats.best, "mean": last.stats.mean},
                "best_fitness": evo.evaluations[evo.best].fitness,
            })
        })
        .collect();
    serde_json::json!({
        "program": "fuzzymotiv",
        "version": fuzzymotiv::VERSION,
        "name": exp.name,
        "seed": exp.seed,
        "motivations": exp.motivations,
        "training": exp.training,
        "rooms": rows,
        "runs": runs,
        "wall_seconds": wall_seconds,
    })
}
