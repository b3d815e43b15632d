//! `fuzzymotiv reproduce`: the paper's study (docs/model.md §10) in one command.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use fuzzymotiv::config::RawConfig;
use fuzzymotiv::seed::Streams;

use crate::error::CliError;
use crate::files::{OutState, StagedDir, check_out, write_atomic};
use crate::inputs::{Loaded, resolve};
use crate::png::write_figure_at;
use crate::progress::Progress;
use crate::report::{Section, reproduce_page};
use crate::run::{Finished, RoomRow, execute, resolved_toml, set_threads, start_line};
use crate::svg::{best_paths_svg, fitness_svg};

/// Arguments of `fuzzymotiv reproduce`.
#[derive(clap::Args)]
pub struct ReproduceArgs {
    /// Output directory [default: results; with --quick results-quick; with --orientation
    /// results-orientation(-quick); with --ablation results-ablation(-quick)]. Another study's
    /// results there are kept unless --force.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Replace another study's results in --out (or an unfinished one) and start over.
    #[arg(long)]
    pub force: bool,
    /// No progress lines on stderr.
    #[arg(long, short)]
    pub quiet: bool,
    /// Base seed, a whole number from 0 to 2^53 − 1: the study's first seed is this seed, the
    /// others derive from it.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true, value_parser = crate::inputs::parse_seed)]
    pub seed: u64,
    /// Number of seeds per setting; tables give mean ± std over them and every seed's values.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=1000))]
    pub seeds: u64,
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
    /// Run the ablation instead: the study once with the default model and once with each new
    /// modelling choice switched back (motion, end at home, homing, rooms), and which of the
    /// paper's claims hold under each.
    #[arg(long, conflicts_with = "orientation")]
    pub ablation: bool,
}

impl ReproduceArgs {
    /// `--out`, or the default for the study and its size (a quick look never lands in the
    /// full study's directory).
    pub fn out_dir(&self) -> PathBuf {
        self.out.clone().unwrap_or_else(|| {
            let base = if self.orientation {
                "results-orientation"
            } else if self.ablation {
                "results-ablation"
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

/// One setting's runs, one per seed.
struct SettingRuns<'a> {
    setting: &'a Setting,
    seeds: Vec<u64>,
    loaded: Vec<Loaded>,
    finished: Vec<Finished>,
}

impl SettingRuns<'_> {
    /// The seed whose mean F over rooms is the median (the lower median for an even count):
    /// the robot the figures show.
    fn median(&self) -> usize {
        let score = |k: usize| {
            let rows = &self.finished[k].rows;
            rows.iter().map(|r| r.average_fitness).sum::<f64>() / rows.len().max(1) as f64
        };
        let mut order: Vec<usize> = (0..self.seeds.len()).collect();
        order.sort_by(|&a, &b| score(a).total_cmp(&score(b)).then(a.cmp(&b)));
        order[(order.len() - 1) / 2]
    }

    /// "seed S" or "median seed S of N".
    fn median_label(&self) -> String {
        let seed = self.seeds[self.median()];
        if self.seeds.len() == 1 {
            format!("seed {seed}")
        } else {
            format!("median seed {seed} of {}", self.seeds.len())
        }
    }
}

/// A variant of the study: the default model, or one modelling choice switched back.
pub struct Variant {
    /// Directory and table name.
    pub name: &'static str,
    /// What it switches back, in words.
    pub what: &'static str,
    /// Config overrides.
    pub sets: &'static [&'static str],
    /// Use the first release's rooms (rooms/first-release/) instead of the paper's.
    pub first_release_rooms: bool,
}

/// The default model: the paper's robot, rooms and home zone.
const DEFAULT_MODEL: Variant = Variant {
    name: "default",
    what: "the paper's robot (actions, end at home, escape homing, the paper's rooms)",
    sets: &[],
    first_release_rooms: false,
};

/// The ablation: the default model, then each new modelling choice switched back alone.
pub const ABLATION: [Variant; 5] = [
    DEFAULT_MODEL,
    Variant {
        name: "wheels",
        what: "robot.motion = \"wheels\" (continuous differential drive)",
        sets: &["robot.motion=\"wheels\""],
        first_release_rooms: false,
    },
    Variant {
        name: "no-end-at-home",
        what: "trial.end_at_home = false (every trial runs all T steps)",
        sets: &["trial.end_at_home=false"],
        first_release_rooms: false,
    },
    Variant {
        name: "distance-homing",
        what: "fitness.homing = \"distance\" (no escape condition)",
        sets: &["fitness.homing=\"distance\""],
        first_release_rooms: false,
    },
    Variant {
        name: "first-release-rooms",
        what: "the first release's rooms (rooms/first-release/)",
        sets: &[],
        first_release_rooms: true,
    },
];

/// The first release's five rooms (the files in rooms/first-release/, built into the binary).
const FIRST_RELEASE_ROOMS: [(&str, &str); 5] = [
    ("H", include_str!("../../../rooms/first-release/H.toml")),
    ("T", include_str!("../../../rooms/first-release/T.toml")),
    ("L", include_str!("../../../rooms/first-release/L.toml")),
    (
        "square",
        include_str!("../../../rooms/first-release/square.toml"),
    ),
    (
        "rectangle",
        include_str!("../../../rooms/first-release/rectangle.toml"),
    ),
];

/// One (setting, seed) config of a variant, validated.
fn load_one(
    args: &ReproduceArgs,
    setting: &Setting,
    seed: u64,
    variant: &Variant,
) -> Result<Loaded, CliError> {
    let mut sets = Vec::new();
    if args.quick {
        sets.push("ga.population=30".to_string());
        sets.push("ga.generations=30".to_string());
    }
    sets.push(format!("seed={seed}"));
    sets.extend(variant.sets.iter().map(|s| s.to_string()));
    sets.extend(args.sets.iter().cloned());
    let source = format!("built-in config {}", setting.name);
    let mut raw = RawConfig::parse(setting.config, &source, &sets)?;
    if !variant.first_release_rooms {
        return resolve(raw, std::path::Path::new("."), &source);
    }
    let mut rooms = Vec::new();
    raw.rooms.clear();
    for (name, text) in FIRST_RELEASE_ROOMS {
        let file = format!("rooms/first-release/{name}.toml");
        rooms.push(fuzzymotiv::room::Room::from_toml_str(text, &file).map_err(CliError::from)?);
        raw.rooms.push(file);
    }
    let experiment = fuzzymotiv::experiment::Experiment::new(&raw, rooms, &source)?;
    Ok(Loaded { raw, experiment })
}

/// The configs of every (setting, seed), validated before anything is written.
fn load_settings(
    args: &ReproduceArgs,
    seeds: &[u64],
    variant: &Variant,
) -> Result<Vec<Vec<Loaded>>, CliError> {
    SETTINGS
        .iter()
        .map(|s| {
            seeds
                .iter()
                .map(|&seed| load_one(args, s, seed, variant))
                .collect()
        })
        .collect()
}

/// Evolves every (setting, seed) of a variant into `dir/SETTING/seed-S/`.
fn run_study<'a>(
    args: &ReproduceArgs,
    seeds: &[u64],
    loaded: Vec<Vec<Loaded>>,
    dir: &Path,
    progress: &Progress,
    label: &str,
) -> Result<Vec<SettingRuns<'a>>, CliError> {
    let mut studies = Vec::new();
    for (setting, loaded) in SETTINGS.iter().zip(loaded) {
        let mut finished = Vec::new();
        for (seed, l) in seeds.iter().zip(&loaded) {
            progress.set_prefix(&format!("{label}{} seed {seed}", setting.name));
            let run_dir = dir.join(setting.name).join(format!("seed-{seed}"));
            progress.note(&start_line(&l.experiment, &run_dir));
            finished.push(execute(l, &run_dir, progress, false, args.png)?);
        }
        studies.push(SettingRuns {
            setting,
            seeds: seeds.to_vec(),
            loaded,
            finished,
        });
    }
    Ok(studies)
}

/// Entry point of `fuzzymotiv reproduce`.
pub fn reproduce(args: ReproduceArgs) -> Result<(), CliError> {
    set_threads(args.threads)?;
    if args.orientation {
        return orientation_study(&args);
    }
    if args.ablation {
        return ablation(&args);
    }
    let start = Instant::now();
    let seeds = study_seeds(&args);
    let loaded = load_settings(&args, &seeds, &DEFAULT_MODEL)?;
    let out = args.out_dir();
    if !fresh_out(&args, &out, &identity(&[(&DEFAULT_MODEL, &loaded)]))? {
        return Ok(());
    }
    let staged = StagedDir::new(&out)?;
    let progress = Progress::new(
        &loaded[0][0].experiment,
        SETTINGS.len() * seeds.len(),
        args.quiet,
    );
    let studies = run_study(&args, &seeds, loaded, &staged.staging, &progress, "")?;
    progress.finish();
    let claims = write_study(&args, &staged.staging, &studies, start)?;
    print_claims(&claims);
    commit(staged, start)
}

fn study_seeds(args: &ReproduceArgs) -> Vec<u64> {
    (0..args.seeds as usize)
        .map(|k| Streams::new(args.seed).study(k))
        .collect()
}

/// `reproduce --ablation`: the study for every variant, then which claims hold under each.
fn ablation(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let seeds = study_seeds(args);
    let loaded = ABLATION
        .iter()
        .map(|v| load_settings(args, &seeds, v))
        .collect::<Result<Vec<_>, CliError>>()?;
    let out = args.out_dir();
    let variants: Vec<_> = ABLATION.iter().zip(&loaded).collect();
    if !fresh_out(args, &out, &identity(&variants))? {
        return Ok(());
    }
    let staged = StagedDir::new(&out)?;
    let progress = Progress::new(
        &loaded[0][0][0].experiment,
        ABLATION.len() * SETTINGS.len() * seeds.len(),
        args.quiet,
    );
    let mut rows = Vec::new();
    for (variant, loaded) in ABLATION.iter().zip(loaded) {
        let dir = staged.staging.join(variant.name);
        let label = format!("{} · ", variant.name);
        let studies = run_study(args, &seeds, loaded, &dir, &progress, &label)?;
        let claims = write_study(args, &dir, &studies, Instant::now())?;
        rows.push((variant, claims));
    }
    progress.finish();
    let prov = Provenance::of(args, &seeds, &rows_exp(args, &seeds)?);
    let (md, csv) = ablation_table(&rows, &prov);
    staged.write("ablation.md", &md)?;
    staged.write("ablation.csv", &csv)?;
    let summary = serde_json::json!({
        "program": "fuzzymotiv",
        "version": fuzzymotiv::VERSION,
        "seed": args.seed,
        "seeds": seeds,
        "quick": args.quick,
        "population": prov.population,
        "generations": prov.generations,
        "overrides": args.sets,
        "variants": rows.iter().map(|(v, claims)| serde_json::json!({
            "name": v.name,
            "switched_back": v.what,
            "claims": claims_json(claims),
        })).collect::<Vec<_>>(),
        "wall_seconds": start.elapsed().as_secs_f64(),
    });
    staged.write(
        "summary.json",
        serde_json::to_string_pretty(&summary).expect("serialisable") + "\n",
    )?;
    println!("{md}");
    commit(staged, start)
}

/// Renames the staged output into place and says where it went and how long it took.
fn commit(staged: StagedDir, start: Instant) -> Result<(), CliError> {
    let out = staged.commit()?;
    eprintln!(
        "wrote {} ({:.1} s)",
        out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// What makes a study "the same": every run's resolved config, by its path in the output.
fn identity(variants: &[(&Variant, &Vec<Vec<Loaded>>)]) -> Vec<(String, String)> {
    let prefix = |v: &Variant| {
        if variants.len() == 1 {
            String::new()
        } else {
            format!("{}/", v.name)
        }
    };
    variants
        .iter()
        .flat_map(|(v, loaded)| {
            SETTINGS
                .iter()
                .zip(loaded.iter())
                .flat_map(move |(s, seeds)| {
                    seeds.iter().map(move |l| {
                        (
                            format!(
                                "{}{}/seed-{}/config.resolved.toml",
                                prefix(v),
                                s.name,
                                l.experiment.seed()
                            ),
                            resolved_toml(&l.raw),
                        )
                    })
                })
        })
        .collect()
}

/// Checks `--out` before any work: false when it already holds this very study (nothing to
/// do); an unfinished study cannot be resumed and is replaced only with `--force`.
fn fresh_out(args: &ReproduceArgs, out: &Path, id: &[(String, String)]) -> Result<bool, CliError> {
    match check_out(out, id, args.force)? {
        OutState::Done => {
            eprintln!(
                "{} already holds this study, finished (same resolved configs); nothing to do. --force runs it again",
                out.display()
            );
            Ok(false)
        }
        OutState::Unfinished => Err(CliError::input(format!(
            "{}: an unfinished study of this command is in {}; reproduce cannot resume it: pass --force to discard it and start over",
            out.display(),
            StagedDir::staging_path(out).display()
        ))),
        OutState::Fresh => Ok(true),
    }
}

/// The first config of the default variant (for provenance).
fn rows_exp(args: &ReproduceArgs, seeds: &[u64]) -> Result<Loaded, CliError> {
    load_one(args, &SETTINGS[0], seeds[0], &DEFAULT_MODEL)
}

/// Tables, figures, claims, `report.html` and `summary.json` of a study in `dir`.
fn write_study(
    args: &ReproduceArgs,
    dir: &Path,
    studies: &[SettingRuns<'_>],
    start: Instant,
) -> Result<Vec<Claim>, CliError> {
    let provenance = Provenance::of(args, &studies[0].seeds, &studies[0].loaded[0]);
    let mut panels = Vec::new();
    let mut settings_json = Vec::new();
    for (k, study) in studies.iter().enumerate() {
        let (md, csv, seeds_csv) = study_table(study, &provenance);
        write_atomic(&dir.join(format!("table{}.md", k + 1)), &md)?;
        write_atomic(&dir.join(format!("table{}.csv", k + 1)), &csv)?;
        write_atomic(&dir.join(format!("table{}_seeds.csv", k + 1)), &seeds_csv)?;
        let m = study.median();
        let exp = &study.loaded[m].experiment;
        if !args.ablation {
            println!(
                "Table {} — {} (C, H, O, E) = {:?}\n{md}",
                k + 1,
                study.setting.name,
                exp.motivations().as_array(),
            );
        }
        let title = format!(
            "{} (C,H,O,E) = {:?}, {}",
            study.setting.name,
            exp.motivations().as_array(),
            study.median_label()
        );
        // Panels are narrow: the setting and "median of N seeds" only.
        let panel = if study.seeds.len() == 1 {
            format!("{} {:?}", study.setting.name, exp.motivations().as_array())
        } else {
            format!(
                "{}, median of {} seeds",
                study.setting.name,
                study.seeds.len()
            )
        };
        panels.push((panel, study.finished[m].evolutions[0].history.clone()));
        write_figure_at(
            &dir.join(format!("trajectories_{}.svg", study.setting.tag)),
            &best_paths_svg(
                &format!("Best robot, {title}"),
                exp,
                &study.finished[m].trajectories,
            ),
            args.png,
        )?;
        settings_json.push(setting_json(study));
    }
    write_figure_at(&dir.join("fitness.svg"), &fitness_svg(&panels), args.png)?;
    let claims = claims(studies);
    let (md, csv) = claims_table(&claims, &provenance);
    write_atomic(&dir.join("claims.md"), &md)?;
    write_atomic(&dir.join("claims.csv"), &csv)?;
    let wall_seconds = start.elapsed().as_secs_f64();
    write_atomic(
        &dir.join("report.html"),
        page(args, studies, &provenance, &claims, wall_seconds),
    )?;
    let summary = serde_json::json!({
        "program": "fuzzymotiv",
        "version": fuzzymotiv::VERSION,
        "seed": args.seed,
        "seeds": provenance.seeds,
        "quick": args.quick,
        "population": provenance.population,
        "generations": provenance.generations,
        "overrides": args.sets,
        "settings": settings_json,
        "claims": claims_json(&claims),
        "wall_seconds": wall_seconds,
    });
    write_atomic(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(&summary).expect("serialisable") + "\n",
    )?;
    Ok(claims)
}

/// The study's report page.
fn page(
    args: &ReproduceArgs,
    studies: &[SettingRuns<'_>],
    provenance: &Provenance,
    claims: &[Claim],
    wall_seconds: f64,
) -> String {
    let spreads: Vec<String> = studies.iter().map(spread_html).collect();
    let sections: Vec<Section<'_>> = studies
        .iter()
        .zip(&spreads)
        .map(|(study, spread)| {
            let m = study.median();
            Section {
                id: study.setting.name,
                title: format!("{} ({})", study.setting.name, study.median_label()),
                loaded: &study.loaded[m],
                done: &study.finished[m],
                paper: Some(study.setting),
                link: Some(format!(
                    "{}/seed-{}/report.html",
                    study.setting.name, study.seeds[m]
                )),
                spread: Some(spread.as_str()),
                overall: Some(overall(study)),
            }
        })
        .collect();
    reproduce_page(
        &sections,
        &provenance.line(),
        &args.sets,
        wall_seconds,
        &claims_html(claims),
    )
}

/// What produced a table: version, seeds, GA size, quick or not.
struct Provenance {
    seeds: Vec<u64>,
    population: usize,
    generations: usize,
    quick: bool,
}

impl Provenance {
    fn of(args: &ReproduceArgs, seeds: &[u64], loaded: &Loaded) -> Provenance {
        Provenance {
            seeds: seeds.to_vec(),
            population: loaded.experiment.ga().population,
            generations: loaded.experiment.ga().generations,
            quick: args.quick,
        }
    }

    fn line(&self) -> String {
        let seeds: Vec<String> = self.seeds.iter().map(u64::to_string).collect();
        format!(
            "fuzzymotiv {} · {} seed{} ({}) · GA {} × {}{}",
            fuzzymotiv::VERSION,
            self.seeds.len(),
            if self.seeds.len() == 1 { "" } else { "s" },
            seeds.join(", "),
            self.population,
            self.generations,
            if self.quick { " · quick" } else { "" }
        )
    }
}

/// Mean and sample standard deviation (0 for one value).
fn mean_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    if values.len() < 2 {
        return (mean, 0.0);
    }
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// The table's five columns of a room row.
fn metrics(r: &RoomRow) -> [Option<f64>; 5] {
    [
        Some(r.average_fitness),
        Some(r.exploration_pct),
        r.recognition_pct,
        Some(r.battery_pct),
        Some(r.homing),
    ]
}

/// Per room and column, mean and std over seeds (none where a seed has no value).
fn room_stats(study: &SettingRuns<'_>, room: usize) -> [Option<(f64, f64)>; 5] {
    std::array::from_fn(|c| {
        let values: Option<Vec<f64>> = study
            .finished
            .iter()
            .map(|f| metrics(&f.rows[room])[c])
            .collect();
        values.map(|v| mean_std(&v))
    })
}

fn paper_row(setting: &Setting, room: &str) -> Option<[f64; 4]> {
    setting
        .paper
        .iter()
        .find(|p| p.0 == room)
        .map(|p| [p.1, p.2, p.3, p.4])
}

/// The study's table with the paper's values beside the means: (Markdown with a per-seed
/// table below, CSV of mean/std/paper per room, CSV of every seed's rows).
fn study_table(study: &SettingRuns<'_>, prov: &Provenance) -> (String, String, String) {
    const DIGITS: [usize; 5] = [4, 1, 0, 1, 1];
    let mut md = format!(
        "{}\n\nMean ± std over seeds (the paper's value in brackets).\n\n| room | average fitness | % optimal exploration | % recognition | % battery usage | % homing |\n|---|---|---|---|---|---|\n",
        prov.line()
    );
    let mut csv = String::from(
        "room,seeds,average_fitness,average_fitness_std,paper_average_fitness,exploration_pct,exploration_pct_std,paper_exploration_pct,recognition_pct,recognition_pct_std,paper_recognition_pct,battery_pct,battery_pct_std,paper_battery_pct,homing_pct,homing_pct_std\n",
    );
    let rows = &study.finished[0].rows;
    for (i, row) in rows.iter().enumerate() {
        let stats = room_stats(study, i);
        let paper = paper_row(study.setting, &row.room);
        let _ = write!(md, "| {} |", row.room);
        let _ = write!(csv, "{},{}", row.room, study.seeds.len());
        for (c, stat) in stats.iter().enumerate() {
            let p = paper.and_then(|p| p.get(c).copied());
            let d = DIGITS[c];
            let cell = stat.map_or("n/a".to_string(), |(m, s)| format!("{m:.d$} ± {s:.d$}"));
            let paper_cell = p.map_or(String::new(), |p| {
                format!(" ({p:.prec$})", prec = d.clamp(2, 4))
            });
            let _ = write!(md, " {cell}{paper_cell} |");
            let (m, s) = stat.map_or((String::new(), String::new()), |(m, s)| {
                (format!("{m:.6}"), format!("{s:.6}"))
            });
            let _ = write!(csv, ",{m},{s}");
            if c < 4 {
                let _ = write!(csv, ",{}", p.map_or(String::new(), |p| p.to_string()));
            }
        }
        md.push('\n');
        csv.push('\n');
    }
    md.push_str("\nPer seed:\n\n| room | seed | average fitness | % optimal exploration | % recognition | % battery usage | % homing |\n|---|---|---|---|---|---|---|\n");
    let mut seeds_csv = String::from(
        "room,seed,average_fitness,exploration_pct,recognition_pct,battery_pct,homing_pct\n",
    );
    for (i, row) in rows.iter().enumerate() {
        for (seed, f) in study.seeds.iter().zip(&study.finished) {
            let values = metrics(&f.rows[i]);
            let _ = write!(md, "| {} | {seed} |", row.room);
            let _ = write!(seeds_csv, "{},{seed}", row.room);
            for (c, v) in values.iter().enumerate() {
                let d = DIGITS[c];
                let _ = write!(md, " {} |", v.map_or("n/a".into(), |v| format!("{v:.d$}")));
                let _ = write!(
                    seeds_csv,
                    ",{}",
                    v.map_or(String::new(), |v| format!("{v:.6}"))
                );
            }
            md.push('\n');
            seeds_csv.push('\n');
        }
    }
    (md, csv, seeds_csv)
}

/// A setting in `summary.json`: the documented fields (rows, first and last generation) are
/// means over seeds; `std` and `per_seed` give the spread.
fn setting_json(study: &SettingRuns<'_>) -> serde_json::Value {
    let exp = &study.loaded[0].experiment;
    let m = exp.motivations();
    let rows = &study.finished[0].rows;
    let stats: Vec<_> = (0..rows.len()).map(|i| room_stats(study, i)).collect();
    let pick = |s: &[Option<(f64, f64)>; 5], c: usize, std: bool| {
        s[c].map(|(m, sd)| if std { sd } else { m })
    };
    let table = |std: bool| -> Vec<serde_json::Value> {
        rows.iter()
            .zip(&stats)
            .map(|(r, s)| {
                serde_json::json!({
                    "room": r.room,
                    "average_fitness": pick(s, 0, std),
                    "exploration_pct": pick(s, 1, std),
                    "recognition_pct": pick(s, 2, std),
                    "battery_pct": pick(s, 3, std),
                    "homing": pick(s, 4, std),
                })
            })
            .collect()
    };
    let per_seed: Vec<serde_json::Value> = study
        .seeds
        .iter()
        .zip(&study.finished)
        .map(|(seed, f)| {
            let h = &f.evolutions[0].history;
            serde_json::json!({
                "seed": seed,
                "run_dir": format!("{}/seed-{seed}", study.setting.name),
                "rows": f.rows.iter().map(|r| serde_json::json!({
                    "room": r.room,
                    "average_fitness": r.average_fitness,
                    "exploration_pct": r.exploration_pct,
                    "recognition_pct": r.recognition_pct,
                    "battery_pct": r.battery_pct,
                    "homing": r.homing,
                })).collect::<Vec<_>>(),
                "first_generation": {"best": h[0].stats.max, "mean": h[0].stats.mean},
                "last_generation": {"best": h.last().map(|x| x.stats.max), "mean": h.last().map(|x| x.stats.mean)},
                "confusion": f.aem.iter().map(|a| &a.confusion.counts).collect::<Vec<_>>(),
            })
        })
        .collect();
    serde_json::json!({
        "name": study.setting.name,
        "motivations": {"curiosity": m.curiosity, "homing": m.homing, "orientation": m.orientation, "energy": m.energy},
        "rows": table(false),
        "std": table(true),
        "first_generation": {"best": generation_stat(study, false, true), "mean": generation_stat(study, false, false)},
        "last_generation": {"best": generation_stat(study, true, true), "mean": generation_stat(study, true, false)},
        "population": exp.ga().population,
        "generations": exp.ga().generations,
        "median_seed": study.seeds[study.median()],
        "per_seed": per_seed,
    })
}

/// Mean of table column `c` (see [`metrics`]) over rooms and seeds; none if a value is missing.
fn grand_mean(study: &SettingRuns<'_>, c: usize) -> Option<f64> {
    let values: Option<Vec<f64>> = study
        .finished
        .iter()
        .flat_map(|f| f.rows.iter().map(move |r| metrics(r)[c]))
        .collect();
    values.map(|v| mean_std(&v).0)
}

/// Mean % exploration, % recognition and % battery over rooms and seeds.
fn overall(study: &SettingRuns<'_>) -> [Option<f64>; 3] {
    [
        grand_mean(study, 1),
        grand_mean(study, 2),
        grand_mean(study, 3),
    ]
}

/// Mean over seeds of the population's best (`best`) or mean F in the first or the last
/// generation.
fn generation_stat(study: &SettingRuns<'_>, last: bool, best: bool) -> f64 {
    let v: Vec<f64> = study
        .finished
        .iter()
        .map(|f| {
            let h = &f.evolutions[0].history;
            let rec = if last { &h[h.len() - 1] } else { &h[0] };
            if best { rec.stats.max } else { rec.stats.mean }
        })
        .collect();
    mean_std(&v).0
}

/// One of the paper's claims, tested on a study's means.
pub struct Claim {
    /// The claim in words.
    pub claim: &'static str,
    /// Whether our study shows it.
    pub holds: bool,
    /// The numbers behind the verdict.
    pub evidence: String,
}

/// The paper's claims (high vs low curiosity, and Fig. 6's fitness curves) on means over
/// rooms and seeds: `studies[0]` is high curiosity, `studies[1]` low curiosity.
fn claims(studies: &[SettingRuns<'_>]) -> Vec<Claim> {
    let (hc, lc) = (&studies[0], &studies[1]);
    let compare = |claim: &'static str, c: usize, more: bool| {
        let (h, l) = (grand_mean(hc, c), grand_mean(lc, c));
        let holds = matches!((h, l), (Some(h), Some(l)) if if more { h > l } else { h < l });
        let show = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.1} %"));
        Claim {
            claim,
            holds,
            evidence: format!("high {} vs low {}", show(h), show(l)),
        }
    };
    let first = [
        generation_stat(hc, false, false),
        generation_stat(lc, false, false),
    ];
    let last = [
        generation_stat(hc, true, false),
        generation_stat(lc, true, false),
    ];
    vec![
        compare("high curiosity explores more than low curiosity", 1, true),
        compare("high curiosity uses more battery", 3, true),
        compare("high curiosity recognises rooms better", 2, true),
        compare(
            "high curiosity returns home less (lower % homing)",
            4,
            false,
        ),
        Claim {
            claim: "first-generation mean F about 0.1 (between 0.05 and 0.15)",
            holds: first.iter().all(|f| (0.05..=0.15).contains(f)),
            evidence: format!("high {:.3}, low {:.3}", first[0], first[1]),
        },
        Claim {
            claim: "mean F rises over the generations",
            holds: last[0] > first[0] && last[1] > first[1],
            evidence: format!(
                "high {:.3} → {:.3}, low {:.3} → {:.3}",
                first[0], last[0], first[1], last[1]
            ),
        },
    ]
}

/// The claims as `summary.json` records them.
fn claims_json(claims: &[Claim]) -> Vec<serde_json::Value> {
    claims
        .iter()
        .map(|c| serde_json::json!({"claim": c.claim, "holds": c.holds, "evidence": c.evidence}))
        .collect()
}

fn mark(holds: bool) -> &'static str {
    if holds { "holds" } else { "fails" }
}

/// The claims as (Markdown, CSV).
fn claims_table(claims: &[Claim], prov: &Provenance) -> (String, String) {
    let mut md = format!(
        "{}\n\nThe paper's claims, on means over rooms and seeds.\n\n| claim | verdict | evidence |\n|---|---|---|\n",
        prov.line()
    );
    let mut csv = String::from("claim,holds,evidence\n");
    for c in claims {
        let _ = writeln!(md, "| {} | {} | {} |", c.claim, mark(c.holds), c.evidence);
        let _ = writeln!(csv, "\"{}\",{},\"{}\"", c.claim, c.holds, c.evidence);
    }
    (md, csv)
}

/// The claims as an HTML table for the report page.
fn claims_html(claims: &[Claim]) -> String {
    let mut html = String::from(
        "<h2 id=\"claims\">The paper's claims</h2>\n<table><tr><th>claim</th><th>verdict</th><th>evidence (means over rooms and seeds)</th></tr>\n",
    );
    for c in claims {
        let _ = writeln!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{}</td></tr>",
            crate::svg::esc(c.claim),
            mark(c.holds),
            crate::svg::esc(&c.evidence)
        );
    }
    html.push_str("</table>\n");
    html
}

fn print_claims(claims: &[Claim]) {
    for c in claims {
        println!("{}: {} ({})", c.claim, mark(c.holds), c.evidence);
    }
}

/// The ablation table: one row per variant, one column per claim, as (Markdown, CSV).
fn ablation_table(rows: &[(&Variant, Vec<Claim>)], prov: &Provenance) -> (String, String) {
    let mut md = format!(
        "{}\n\nWhich of the paper's claims hold when one modelling choice is switched back (means over rooms and seeds; each variant's own tables are in its directory).\n\n| variant | switched back |",
        prov.line()
    );
    let mut csv = String::from("variant");
    for c in &rows[0].1 {
        let _ = write!(md, " {} |", c.claim);
        let _ = write!(csv, ",\"{}\"", c.claim);
    }
    md.push_str("\n|---|---|");
    md.push_str(&"---|".repeat(rows[0].1.len()));
    md.push('\n');
    csv.push('\n');
    for (v, claims) in rows {
        let _ = write!(md, "| {} | {} |", v.name, v.what);
        let _ = write!(csv, "{}", v.name);
        for c in claims {
            let _ = write!(md, " {} ({}) |", mark(c.holds), c.evidence);
            let _ = write!(csv, ",{}", c.holds);
        }
        md.push('\n');
        csv.push('\n');
    }
    (md, csv)
}

/// The report's spread table of one setting: mean ± std over seeds and the range, per room.
fn spread_html(study: &SettingRuns<'_>) -> String {
    let mut html = String::from(
        "<table><tr><th>room</th><th>average fitness</th><th>% optimal exploration</th><th>% recognition</th><th>% battery usage</th><th>% homing</th></tr>\n",
    );
    for (i, row) in study.finished[0].rows.iter().enumerate() {
        let _ = write!(html, "<tr><td>{}</td>", crate::svg::esc(&row.room));
        for (c, stat) in room_stats(study, i).iter().enumerate() {
            let values: Vec<f64> = study
                .finished
                .iter()
                .filter_map(|f| metrics(&f.rows[i])[c])
                .collect();
            let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let d = if c == 0 { 3 } else { 1 };
            let _ = write!(
                html,
                "<td>{}</td>",
                stat.map_or("n/a".into(), |(m, s)| format!(
                    "{m:.d$} ± {s:.d$} <span class=\"paper\">[{lo:.d$}–{hi:.d$}]</span>"
                ))
            );
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</table>\n");
    let _ = writeln!(
        html,
        "<p class=\"caption\">Mean ± standard deviation over {} seeds ({}), with the range in brackets. The figures and the detailed sections below show the {}.</p>",
        study.seeds.len(),
        study
            .seeds
            .iter()
            .map(u64::to_string)
            .collect::<Vec<_>>()
            .join(", "),
        study.median_label()
    );
    html
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
