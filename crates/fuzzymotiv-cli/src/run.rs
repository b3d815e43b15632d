//! `fuzzymotiv run`: evolve, model the rooms, write the run directory.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use fuzzymotiv::config::{RawConfig, Training};
use fuzzymotiv::evolution::{Evolution, GenerationRecord, GenerationState};
use fuzzymotiv::experiment::{Experiment, Run};
use fuzzymotiv::modelling::AemReport;
use fuzzymotiv::trial::Trajectory;
use serde::Serialize;

use crate::error::CliError;
use crate::files::{OutState, StagedDir, check_out, io_err, num, write_atomic};
use crate::inputs::{Loaded, load_config};
use crate::png::write_figure;
use crate::progress::Progress;
use crate::report;
use crate::svg::{best_paths_svg, fitness_svg, terms_svg};

/// Arguments of `fuzzymotiv run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// Experiment config (TOML; every key is optional, defaults in docs/model.md). Required, unless
    /// --resume DIR is given instead.
    #[arg(value_name = "CONFIG", required_unless_present = "resume")]
    pub config: Option<PathBuf>,
    /// Continue a killed run: DIR is the run's output directory (its `DIR.partial/` holds the
    /// checkpoint and resolved config). The result equals an uninterrupted run.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["config", "out", "seed", "sets", "force"])]
    pub resume: Option<PathBuf>,
    /// Output directory [default: runs/NAME]. The same command again finishes an unfinished
    /// run there or says it is done; another run's results there are kept unless --force.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace the results of another run in --out, or discard an unfinished one (its
    /// checkpoint), and start over.
    #[arg(long)]
    pub force: bool,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Base seed (overrides `seed` in the config): a whole number from 0 to 2^53 − 1.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::inputs::parse_seed)]
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
    let (loaded, out, resume) = match (&args.resume, &args.config) {
        (Some(dir), _) => {
            let staging = StagedDir::staging_path(dir);
            let cfg = staging.join("config.resolved.toml");
            if !cfg.is_file() {
                if dir.join("summary.json").is_file() {
                    eprintln!("{} is already complete; nothing to resume", dir.display());
                    return Ok(());
                }
                return Err(CliError::input(format!(
                    "--resume {}: no interrupted run there ({} not found); start it with `fuzzymotiv run CONFIG --out {}`",
                    dir.display(),
                    cfg.display(),
                    dir.display()
                )));
            }
            (load_config(Some(&cfg), &[], None)?, dir.clone(), true)
        }
        (None, Some(config)) => {
            let loaded = load_config(Some(config), &args.sets, args.seed)?;
            let out = args
                .out
                .clone()
                .unwrap_or_else(|| Path::new("runs").join(&loaded.raw.name));
            let id = [(
                "config.resolved.toml".to_string(),
                resolved_toml(&loaded.raw),
            )];
            match check_out(&out, &id, args.force)? {
                OutState::Done => {
                    eprintln!(
                        "{} already holds this run, finished (same resolved config); nothing to do. --force runs it again",
                        out.display()
                    );
                    return Ok(());
                }
                OutState::Unfinished => (loaded, out, true),
                OutState::Fresh => (loaded, out, false),
            }
        }
        (None, None) => return Err(CliError::input("give a CONFIG file or --resume DIR")),
    };
    let progress = Progress::new(&loaded.experiment, 1, args.quiet);
    progress.set_prefix(&format!(
        "{} seed {}",
        loaded.experiment.name(),
        loaded.experiment.seed()
    ));
    progress.note(&start_line(&loaded.experiment, &out));
    let done = execute(&loaded, &out, &progress, resume, args.png)?;
    progress.finish();
    print!("{}", table_markdown(&done.rows));
    eprintln!("wrote {} ({:.1} s)", out.display(), done.wall_seconds);
    Ok(())
}

/// What is about to run, said before the first generation (which may take long).
pub fn start_line(exp: &Experiment, out: &Path) -> String {
    format!(
        "{}: seed {}, {} × {} generations of {} robots, {} room(s) × {} steps per trial → {}",
        exp.name(),
        exp.seed(),
        exp.runs().len(),
        exp.ga().generations,
        exp.ga().population,
        exp.arenas().len(),
        exp.trial_params().steps,
        out.display()
    )
}

/// One row of the per-room table (docs/model.md §10).
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
    (0..exp.arenas().len())
        .map(|r| {
            let (evo, _) = robot_for_room(evolutions, r);
            exp.instance_trajectory(&evo.population[evo.best], &evo.run, r)
        })
        .collect()
}

/// Runs a loaded config and writes its run directory `out` (atomically), with `report.html`
/// and the figures (and their PNGs with `png`). After every generation a checkpoint is written
/// into the staging directory; with `resume`, an interrupted run continues from its last
/// checkpoint and ends with the same files.
pub fn execute(
    loaded: &Loaded,
    out: &Path,
    progress: &Progress,
    resume: bool,
    png: bool,
) -> Result<Finished, CliError> {
    execute_with(loaded, out, progress, resume, png, &mut |_| {})
}

/// [`execute`], calling `hook` after every generation once its checkpoint is saved (the Python
/// bindings report progress and stop on Ctrl-C there; a hook that unwinds leaves the staging
/// directory resumable).
pub fn execute_with(
    loaded: &Loaded,
    out: &Path,
    progress: &Progress,
    resume: bool,
    png: bool,
    hook: &mut dyn FnMut(&GenerationState<'_>),
) -> Result<Finished, CliError> {
    let exp = &loaded.experiment;
    let start = Instant::now();
    let staged = if resume {
        StagedDir::reopen(out)?
    } else {
        StagedDir::new(out)?
    };
    let resolved = resolved_toml(&loaded.raw);
    if !resume {
        staged.write("config.resolved.toml", &resolved)?;
    }
    let runs = exp.runs();
    let mut checkpoint = if resume {
        let cp = Checkpoint::load(&staged.path(CHECKPOINT), &runs, exp)?;
        progress.note(&cp.resume_note(out, exp.ga().generations));
        cp
    } else {
        Checkpoint::fresh(&runs)
    };
    // Wall time of earlier sessions (before a resume) counts too.
    let earlier_seconds = checkpoint.wall_seconds;
    let mut evolutions = Vec::new();
    let mut csv = String::from("generation,best,mean,std,min,max,a,g,l,b,room\n");
    for (k, run) in runs.iter().enumerate() {
        let saved = checkpoint.runs[k].clone();
        progress.skip(saved.history.len());
        let mut write_error = None;
        let evo = if saved.done {
            exp.finished(run, saved.population_f64(), saved.history.clone())
        } else {
            let population = if saved.population.is_empty() {
                exp.initial_population(run)
            } else {
                saved.population_f64()
            };
            let mut on_generation = |state: &GenerationState<'_>| {
                let g = state.history.len();
                let best = state.record().stats.max;
                progress.generation(&run.label, g, exp.ga().generations, best);
                checkpoint.runs[k] = CheckpointRun::from_state(&run.label, state);
                checkpoint.wall_seconds = earlier_seconds + start.elapsed().as_secs_f64();
                if let Err(e) = checkpoint.save(&staged.path(CHECKPOINT)) {
                    write_error.get_or_insert(e);
                }
                hook(state);
            };
            exp.evolve_from(
                run,
                saved.history.len(),
                population,
                saved.history.clone(),
                &mut on_generation,
            )
        };
        if let Some(e) = write_error {
            return Err(e);
        }
        for rec in &evo.history {
            let s = rec.stats;
            let t = rec.terms;
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{},{}",
                rec.generation,
                num(s.max),
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
    staged.write(
        "table.md",
        table_markdown(&rows) + &provenance_line(exp, loaded),
    )?;
    let trajectories = best_trajectories(exp, &evolutions);
    let panels: Vec<_> = evolutions
        .iter()
        .map(|e| {
            let title = match exp.training() {
                Training::AllRooms => {
                    format!(
                        "{} (C,H,O,E) = {:?}",
                        exp.name(),
                        exp.motivations().as_array()
                    )
                }
                Training::PerRoom => format!("{}: robot evolved in {}", exp.name(), e.run.label),
            };
            (title, e.history.clone())
        })
        .collect();
    write_figure(&staged, "fitness", &fitness_svg(&panels), png)?;
    write_figure(&staged, "terms", &terms_svg(&panels), png)?;
    let title = format!(
        "Best robot, {} (C, H, O, E) = {:?}",
        exp.name(),
        exp.motivations().as_array()
    );
    write_figure(
        &staged,
        "trajectories",
        &best_paths_svg(&title, exp, &trajectories),
        png,
    )?;
    let wall_seconds = earlier_seconds + start.elapsed().as_secs_f64();
    let summary = summary_json(exp, &evolutions, &rows, wall_seconds);
    staged.write(
        "summary.json",
        serde_json::to_string_pretty(&summary).expect("serialisable") + "\n",
    )?;
    std::fs::remove_file(staged.path(CHECKPOINT))
        .map_err(|e| io_err(&staged.path(CHECKPOINT), e))?;
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

/// Where a table came from, as a Markdown line below it: program version, seed, GA size, trial
/// length and training (so a small trial run and a paper-scale one never look alike).
pub fn provenance_line(exp: &Experiment, loaded: &Loaded) -> String {
    format!(
        "\nfuzzymotiv {} · seed {} · GA {} robots × {} generations · {} steps per trial · training {}\n",
        fuzzymotiv::VERSION,
        exp.seed(),
        exp.ga().population,
        exp.ga().generations,
        exp.trial_params().steps,
        match loaded.raw.training {
            Training::AllRooms => "all-rooms",
            Training::PerRoom => "per-room",
        },
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
        "seed": exp.seed(),
        "shape": exp.shape(),
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

/// The contents of `summary.json` (also the Python bindings' `summary`).
pub fn summary_json(
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
                "first_generation": {"best": first.stats.max, "mean": first.stats.mean},
                "last_generation": {"best": last.stats.max, "mean": last.stats.mean},
                "best_fitness": evo.evaluations[evo.best].fitness,
            })
        })
        .collect();
    serde_json::json!({
        "program": "fuzzymotiv",
        "version": fuzzymotiv::VERSION,
        "name": exp.name(),
        "seed": exp.seed(),
        "motivations": exp.motivations(),
        "training": exp.training(),
        "population": exp.ga().population,
        "generations": exp.ga().generations,
        "steps": exp.trial_params().steps,
        "rooms": rows,
        "runs": runs,
        "wall_seconds": wall_seconds,
    })
}

/// File name of the checkpoint inside the staging directory.
pub const CHECKPOINT: &str = "checkpoint.json";

/// What a killed run needs to continue: per run of the protocol, the history so far and the
/// next population (floats stored as their exact bit patterns). The random streams are
/// derived per generation, so no generator state needs saving.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct Checkpoint {
    /// Format version.
    pub format: u32,
    /// Program version that wrote it.
    pub version: String,
    /// Wall time (s) of the run so far, over all sessions.
    #[serde(default)]
    pub wall_seconds: f64,
    /// One entry per run.
    pub runs: Vec<CheckpointRun>,
}

/// One run's saved state.
#[derive(Debug, Clone, Default, Serialize, serde::Deserialize)]
pub struct CheckpointRun {
    /// Run label.
    pub label: String,
    /// Whether the last generation has been evaluated (then `population` is the final one).
    pub done: bool,
    /// Per-generation records so far (floats printed by serde_json round-trip exactly).
    pub history: Vec<GenerationRecord>,
    /// Genomes to evaluate next (or the final population), as f64 bits.
    pub population: Vec<Vec<u64>>,
}

impl CheckpointRun {
    fn from_state(label: &str, state: &GenerationState<'_>) -> Self {
        let (done, pop) = match state.next {
            Some(next) => (false, next),
            None => (true, state.population),
        };
        CheckpointRun {
            label: label.to_string(),
            done,
            history: state.history.to_vec(),
            population: pop
                .iter()
                .map(|g| g.iter().map(|v| v.to_bits()).collect())
                .collect(),
        }
    }

    fn population_f64(&self) -> Vec<Vec<f64>> {
        self.population
            .iter()
            .map(|g| g.iter().map(|&b| f64::from_bits(b)).collect())
            .collect()
    }
}

impl Checkpoint {
    fn fresh(runs: &[Run]) -> Self {
        Checkpoint {
            format: 1,
            version: fuzzymotiv::VERSION.to_string(),
            wall_seconds: 0.0,
            runs: runs
                .iter()
                .map(|r| CheckpointRun {
                    label: r.label.clone(),
                    ..Default::default()
                })
                .collect(),
        }
    }

    fn load(path: &Path, runs: &[Run], exp: &Experiment) -> Result<Self, CliError> {
        if !path.is_file() {
            // Killed before the first generation finished: start over.
            return Ok(Self::fresh(runs));
        }
        let text = std::fs::read_to_string(path).map_err(|e| io_err(path, e))?;
        let cp: Checkpoint = serde_json::from_str(&text).map_err(|e| {
            CliError::input(format!(
                "{}: not a fuzzymotiv checkpoint: {e}",
                path.display()
            ))
        })?;
        let ok = cp.runs.len() == runs.len()
            && cp.runs.iter().zip(runs).all(|(c, r)| {
                c.label == r.label
                    && if c.done {
                        c.history.len() == exp.ga().generations
                            && c.population.len() == exp.ga().population
                    } else {
                        c.history.len() < exp.ga().generations
                    }
                    && c.population
                        .iter()
                        .all(|g| g.len() == exp.shape().genome_len())
                    && (c.history.is_empty() || c.population.len() == exp.ga().population)
            });
        if !ok {
            return Err(CliError::input(format!(
                "{}: the checkpoint does not match the run's config (runs, sizes); start the run again without --resume",
                path.display()
            )));
        }
        Ok(cp)
    }

    /// Says where a resumed run continues.
    fn resume_note(&self, out: &Path, generations: usize) -> String {
        match self.runs.iter().find(|r| !r.done) {
            Some(r) => format!(
                "resuming {} at generation {}/{generations}{} ({} generation(s) were done, {:.1} s)",
                out.display(),
                r.history.len() + 1,
                if self.runs.len() > 1 {
                    format!(" of the robot of {}", r.label)
                } else {
                    String::new()
                },
                r.history.len(),
                self.wall_seconds
            ),
            None => format!(
                "resuming {}: evolution finished, writing the results",
                out.display()
            ),
        }
    }

    fn save(&self, path: &Path) -> Result<(), CliError> {
        write_atomic(path, serde_json::to_vec(self).expect("serialisable"))
    }
}
