//! `fuzzymotiv reproduce`: the paper's study (docs/model.md §10) in one command.

use std::path::{Path, PathBuf};
use std::time::Instant;

use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::random::Streams;

use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::files::guard::{
    IDENTITY, OutState, StagedDir, check_out, matches, write_atomic,
};
use fuzzymotiv_io::files::inputs::{Loaded, resolve, resolved_toml};
use fuzzymotiv_io::note;
use fuzzymotiv_io::pipeline::lanes::{run_concurrently, set_threads};
use fuzzymotiv_io::pipeline::run_dir::{execute_or_resume, start_line};
use fuzzymotiv_io::pipeline::sweep_jobs::run_jobs;
use fuzzymotiv_io::pipeline::sweep_merge::merge_dir;
use fuzzymotiv_io::pipeline::sweep_plan::Sweep;
use fuzzymotiv_io::records::combination::CombinationSummary;
use fuzzymotiv_io::records::context::RenderContext;
use fuzzymotiv_io::records::replication::ReplicationSummary;
use fuzzymotiv_io::records::{
    AblationSummary, ClaimRecord, PROGRAM, StrengthSummary, StudySummary, VariantSummary,
    read_json, to_json,
};
use fuzzymotiv_io::render::combination::{
    COMBINATION, behaviour_rows, behaviour_svg, behaviour_table, claim_difference_rows,
    claim_difference_table,
};
use fuzzymotiv_io::render::figures::write_figure_at;
use fuzzymotiv_io::render::replication::{
    replication as replication_of, replication_svg, replication_table, seeds_csv,
};
use fuzzymotiv_io::render::report::{Section, reproduce_page, study_page};
use fuzzymotiv_io::render::strength::{SEARCH_STRENGTH, strength_svg, strength_table};
use fuzzymotiv_io::render::study::{
    ABLATION, CLAIMS_ALPHA, DEFAULT_MODEL, FIRST_RELEASE_ROOMS, SETTINGS, Setting, SettingRuns,
    Variant, claims as paper_claims, overall, seed_dir, seed_index,
};
use fuzzymotiv_io::render::svg::{FitnessPanel, best_paths_svg, fitness_panels_svg};
use fuzzymotiv_io::render::tables::{
    Provenance, ablation_table, claims_html, claims_table, spread_html, study_table, verdict,
};

use crate::args::OutputArgs;
use crate::png::{add_pngs, rasteriser};
use crate::progress::{JobsProgress, Progress};

/// Arguments of `fuzzymotiv reproduce`.
#[derive(clap::Args)]
#[command(
    mut_arg("out", |a| a.help("Output directory [default: results; with --quick results-quick; with --orientation results-orientation(-quick); with --ablation results-ablation(-quick); with --search-strength results-search-strength(-quick); with --combination, --replication or --urgency results-combination, results-replication or results-urgency (-quick)]. Another study's results there are kept unless --force")),
    mut_arg("force", |a| a.help("Replace another study's results in --out (or an unfinished one) and start over")),
    mut_arg("seed", |a| a.help("Base seed, a whole number from 0 to 2^53 − 1: the study's first seed is this seed, the others derive from it [default: 1]")),
)]
pub struct ReproduceArgs {
    /// --out, --force, --quiet, --seed (default 1: the study's first seed is this seed, the
    /// others derive from it).
    #[command(flatten)]
    pub output: OutputArgs,
    /// Number of seeds per setting; tables give mean ± std over them and every seed's values.
    /// Twenty by default: from eleven seeds on, homing's verdict and Fig. 6's checks agree at
    /// two base seeds (docs/guide/cli.md: why twenty seeds).
    #[arg(long, allow_hyphen_values = true, default_value_t = 20, value_parser = clap::builder::RangedI64ValueParser::<u64>::new().range(1..=1000))]
    pub seeds: u64,
    /// A fast look: GA 30 × 30 instead of the paper's 200 × 200.
    #[arg(long)]
    pub quick: bool,
    /// Worker threads, 1 to 256 [default: all cores]; up to this many (setting, seed) runs go on at once,
    /// sharing them; results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = fuzzymotiv_io::files::inputs::parse_threads)]
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
    /// Run the search-strength study instead: the study at GA populations 30, 60, 100 and 200
    /// (the paper's generations), and the paper's claims with their statistics at each, as one
    /// table and one figure (EXPERIMENTS.md).
    #[arg(long, conflicts_with_all = ["orientation", "ablation"])]
    pub search_strength: bool,
    /// Run the combination study instead: the study under the paper's TSK and under the two
    /// baselines of `[fitness] combine` (a weighted sum, a weighted sum of squares), the
    /// claims under each and, between each baseline and the TSK, the paired statistics of each
    /// claim's effect and of the behaviour (EXPERIMENTS.md: does the fuzzy combination matter?).
    #[arg(long, conflicts_with_all = ["orientation", "ablation", "search_strength"])]
    pub combination: bool,
    /// Run the replication study instead: the study at base seed --seed and at --seed + 10
    /// (--seeds each), the claims from each and from all their seeds pooled, and from how
    /// many seeds on both base seeds give the pooled verdicts (EXPERIMENTS.md: why N seeds).
    #[arg(long, conflicts_with_all = ["orientation", "ablation", "search_strength", "combination"])]
    pub replication: bool,
    /// Run the urgency study instead: the fetch mission (configs/fetch.toml: the paper's rooms
    /// with a goal zone in the far corner, built in) with urgency weights 0, 0.1, 0.2 and 0.3
    /// taken from curiosity of the high-curiosity setting, the same seeds for each; success
    /// rate, time to the goal, exploration, battery and homing per weight, and each step up in
    /// urgency compared (EXPERIMENTS.md: the paper's future work).
    #[arg(long, conflicts_with_all = ["orientation", "ablation", "search_strength", "combination", "replication"])]
    pub urgency: bool,
}

impl ReproduceArgs {
    /// `--seed`, by default 1.
    pub fn seed(&self) -> u64 {
        self.output.seed.unwrap_or(1)
    }

    /// `--out`, or the default for the study and its size (a quick look never lands in the
    /// full study's directory).
    pub fn out_dir(&self) -> PathBuf {
        self.output.out.clone().unwrap_or_else(|| {
            let base = if self.orientation {
                "results-orientation"
            } else if self.ablation {
                "results-ablation"
            } else if self.search_strength {
                "results-search-strength"
            } else if self.combination {
                "results-combination"
            } else if self.replication {
                "results-replication"
            } else if self.urgency {
                "results-urgency"
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
    sets.extend(setting.sets.iter().map(|s| s.to_string()));
    sets.extend(variant.sets.iter().map(|s| s.to_string()));
    sets.extend(args.sets.iter().cloned());
    let source = format!("built-in config {}", setting.name);
    let mut raw = RawConfig::parse(setting.config, &source, &sets)?;
    let files: Vec<(String, &str)> = if variant.first_release_rooms {
        (FIRST_RELEASE_ROOMS.iter())
            .map(|(name, text)| (format!("rooms/first-release/{name}.toml"), *text))
            .collect()
    } else if !setting.rooms.is_empty() {
        chosen_rooms(&raw.rooms, setting)?
    } else {
        return resolve(raw, std::path::Path::new("."), &source);
    };
    let mut rooms = Vec::new();
    raw.rooms.clear();
    for (file, text) in files {
        rooms.push(
            fuzzymotiv::simulation::Room::from_toml_str(text, &file).map_err(CliError::from)?,
        );
        raw.rooms.push(file);
    }
    let experiment = fuzzymotiv::experiment::Experiment::new(&raw, rooms, &source)?;
    Ok(Loaded { raw, experiment })
}

/// The built-in rooms of `setting` that its config's `rooms` name (by the file's path, its
/// name without `.toml`, or its room name); a room it does not have is refused, naming them.
fn chosen_rooms(
    names: &[String],
    setting: &Setting,
) -> Result<Vec<(String, &'static str)>, CliError> {
    let stem = |f: &str| {
        let base = f.rsplit('/').next().unwrap_or(f);
        base.strip_suffix(".toml").unwrap_or(base).to_string()
    };
    names
        .iter()
        .map(|name| {
            (setting.rooms.iter())
                .find(|(file, _)| stem(file) == stem(name))
                .map(|(file, text)| (file.to_string(), *text))
                .ok_or_else(|| {
                    let known: Vec<String> = setting.rooms.iter().map(|(f, _)| stem(f)).collect();
                    CliError::input(format!(
                        "rooms: `{name}` is not one of the rooms of the study's setting {} (it \
                         has its rooms built in: {}); choose among those, e.g. --set \
                         'rooms=[\"{}\"]'",
                        setting.name,
                        known.join(", "),
                        known[0]
                    ))
                })
        })
        .collect()
}

/// The configs of every (setting, seed), validated before anything is written.
pub(crate) fn load_settings(
    args: &ReproduceArgs,
    settings: &[Setting],
    seeds: &[u64],
    variant: &Variant,
) -> Result<Vec<Vec<Loaded>>, CliError> {
    settings
        .iter()
        .map(|s| {
            seeds
                .iter()
                .map(|&seed| load_one(args, s, seed, variant))
                .collect()
        })
        .collect()
}

/// Evolves every (setting, seed) of a variant into `dir/SETTING/seed-NN/` (the seed's index,
/// [`seed_dir`]), as many runs at a
/// time as there are threads ([`run_concurrently`]).
pub(crate) fn run_study<'a>(
    args: &ReproduceArgs,
    settings: &'a [Setting],
    seeds: &[u64],
    loaded: &[Vec<Loaded>],
    dir: &Path,
    progress: &Progress,
    label: &str,
) -> Result<Vec<SettingRuns<'a>>, CliError> {
    let n = seeds.len();
    let runs: Vec<(&Setting, usize, &Loaded)> = settings
        .iter()
        .zip(loaded)
        .flat_map(|(setting, loaded)| loaded.iter().enumerate().map(move |(k, l)| (setting, k, l)))
        .collect();
    let finished = run_concurrently(&runs, |&(setting, k, l)| {
        let name = format!("{label}{} seed #{}", setting.name, seed_index(k, n));
        let progress = progress.named(&name);
        let run_dir = dir.join(setting.name).join(seed_dir(k, n));
        progress.note(&start_line(&l.experiment, &run_dir));
        execute_or_resume(l, &run_dir, &progress, rasteriser(args.png))
    })?;
    let mut finished = finished.into_iter();
    Ok(settings
        .iter()
        .zip(loaded)
        .map(|(setting, loaded)| SettingRuns {
            setting,
            seeds: seeds.to_vec(),
            finished: finished.by_ref().take(seeds.len()).collect(),
            contexts: loaded.iter().map(RenderContext::of).collect(),
        })
        .collect())
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
    if args.search_strength {
        return search_strength(&args);
    }
    if args.combination {
        return combination(&args);
    }
    if args.replication {
        return replication(&args);
    }
    let start = Instant::now();
    let seeds = study_seeds(&args);
    let Some((staged, studies)) = run_one_study(&args, &SETTINGS, &seeds, DEFAULT_MODEL.name)?
    else {
        return Ok(());
    };
    let (claims, tables) = write_study(&args, args.seed(), &staged.staging, &studies, start)?;
    commit(staged, start)?;
    fuzzymotiv_io::out!("{tables}")?;
    print_claims(&claims)
}

/// One study of `settings` under the default model, `name` in the output's identity: every
/// (setting, seed) config loaded and validated, `--out` opened ([`open_out`]) and every run
/// evolved into the staging directory ([`run_study`]). `None` when `--out` already holds it.
pub(crate) fn run_one_study<'a>(
    args: &ReproduceArgs,
    settings: &'a [Setting],
    seeds: &[u64],
    name: &str,
) -> Result<Option<(StagedDir, Vec<SettingRuns<'a>>)>, CliError> {
    let loaded = load_settings(args, settings, seeds, &DEFAULT_MODEL)?;
    let Some(staged) = open_out(args, &args.out_dir(), settings, &[(name, &loaded)])? else {
        return Ok(None);
    };
    let progress = Progress::new(
        &loaded[0][0].experiment,
        settings.len() * seeds.len(),
        args.output.quiet,
    );
    let studies = run_study(
        args,
        settings,
        seeds,
        &loaded,
        &staged.staging,
        &progress,
        "",
    )?;
    progress.finish();
    Ok(Some((staged, studies)))
}

pub(crate) fn study_seeds(args: &ReproduceArgs) -> Vec<u64> {
    seeds_of(args.seed(), args.seeds)
}

/// The `n` seeds of a study at base seed `base`.
fn seeds_of(base: u64, n: u64) -> Vec<u64> {
    (0..n as usize)
        .map(|k| Streams::new(base).study(k))
        .collect()
}

/// A variant and its claims.
type VariantClaims = (&'static Variant, Vec<ClaimRecord>);

/// The staged output of a study of variants, and per variant its claims and what was measured.
type Measured<T> = (StagedDir, Vec<(VariantClaims, T)>);

/// Runs the study of every variant into `OUT/VARIANT/` (each with its tables, figures,
/// claims and summary.json); `None` when `--out` already holds them all.
fn run_variants(
    args: &ReproduceArgs,
    seeds: &[u64],
    variants: &'static [Variant],
) -> Result<Option<(StagedDir, Vec<VariantClaims>)>, CliError> {
    let done = run_variants_measuring(args, seeds, variants, |_, _| Ok(()))?;
    Ok(done.map(|(staged, rows)| (staged, rows.into_iter().map(|(v, _)| v).collect())))
}

/// [`run_variants`], also measuring each variant's runs with `measure` (given the variant's
/// configs and its runs, per setting) while they are in memory.
fn run_variants_measuring<T>(
    args: &ReproduceArgs,
    seeds: &[u64],
    variants: &'static [Variant],
    measure: impl Fn(&[Vec<Loaded>], &[SettingRuns<'_>]) -> Result<T, CliError>,
) -> Result<Option<Measured<T>>, CliError> {
    refuse_variant_keys(&args.sets, variants)?;
    let loaded = variants
        .iter()
        .map(|v| load_settings(args, &SETTINGS, seeds, v))
        .collect::<Result<Vec<_>, CliError>>()?;
    let out = args.out_dir();
    let pairs: Vec<_> = variants.iter().map(|v| v.name).zip(&loaded).collect();
    let Some(staged) = open_out(args, &out, &SETTINGS, &pairs)? else {
        return Ok(None);
    };
    let progress = Progress::new(
        &loaded[0][0][0].experiment,
        variants.len() * SETTINGS.len() * seeds.len(),
        args.output.quiet,
    );
    let mut rows = Vec::new();
    for (variant, loaded) in variants.iter().zip(loaded) {
        let dir = staged.staging.join(variant.name);
        let label = format!("{} · ", variant.name);
        let studies = run_study(args, &SETTINGS, seeds, &loaded, &dir, &progress, &label)?;
        let (claims, _) = write_study(args, args.seed(), &dir, &studies, Instant::now())?;
        let measured = measure(&loaded, &studies)?;
        rows.push(((variant, claims), measured));
    }
    progress.finish();
    Ok(Some((staged, rows)))
}

/// A part of a study that sets config keys itself: its name, what it is, its overrides.
pub(crate) type Part<'a> = (&'a str, &'a str, &'a [&'a str]);

/// A `--set` of a key that a variant sets itself would make the variants one study (the user's
/// value comes last): refused, naming the variant.
fn refuse_variant_keys(sets: &[String], variants: &[Variant]) -> Result<(), CliError> {
    let parts: Vec<Part<'_>> = (variants.iter())
        .map(|v| (v.name, v.what, v.sets))
        .collect();
    refuse_own_keys(sets, &parts)
}

/// A `--set` of a key that a part of the study sets itself: refused, naming the part.
pub(crate) fn refuse_own_keys(sets: &[String], parts: &[Part<'_>]) -> Result<(), CliError> {
    let key = |set: &str| {
        set.split_once('=')
            .map_or(set, |(k, _)| k)
            .trim()
            .to_string()
    };
    for set in sets {
        let user = key(set);
        for (name, what, own_sets) in parts {
            let clash = (own_sets.iter().map(|s| key(s)))
                .find(|own| *own == user || own.starts_with(&format!("{user}.")));
            if let Some(own) = clash {
                return Err(CliError::input(format!(
                    "--set {set}: this study sets `{own}` itself (its part `{name}`: {what}); \
                     leave the --set out, or run `fuzzymotiv reproduce --set {set}` for one study"
                )));
            }
        }
    }
    Ok(())
}

/// `reproduce --search-strength`: the study at every GA population of [`SEARCH_STRENGTH`],
/// then the claims with their statistics per population, tabulated from each population's
/// summary.json as `search_strength.md`/`.csv` and the figure `search_strength.svg`.
fn search_strength(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let seeds = study_seeds(args);
    let Some((staged, _)) = run_variants(args, &seeds, &SEARCH_STRENGTH)? else {
        return Ok(());
    };
    let studies = SEARCH_STRENGTH
        .iter()
        .map(|v| read_json(&staged.staging.join(v.name).join("summary.json")))
        .collect::<Result<Vec<StudySummary>, CliError>>()?;
    let (md, csv) = strength_table(&studies);
    staged.write("search_strength.md", &md)?;
    staged.write("search_strength.csv", &csv)?;
    write_figure_at(
        &staged.staging.join("search_strength.svg"),
        &strength_svg(&studies),
        rasteriser(args.png),
    )?;
    let summary = StrengthSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: args.seed(),
        seeds,
        quick: args.quick,
        generations: studies[0].generations,
        populations: studies.iter().map(|s| s.population).collect(),
        overrides: args.sets.clone(),
        variants: SEARCH_STRENGTH
            .iter()
            .zip(&studies)
            .map(|(v, s)| variant_summary(v, &s.claims))
            .collect(),
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start)?;
    fuzzymotiv_io::outln!("{md}")
}

/// `reproduce --combination`: the study under every combination of [`COMBINATION`], the claims
/// under each, each claim's effect and each baseline's behaviour against the TSK's
/// (`combination.md`, `claim_differences.csv`, `behaviour.csv`, `behaviour.svg`,
/// `summary.json`).
fn combination(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let seeds = study_seeds(args);
    let Some((staged, measured)) = run_variants_measuring(args, &seeds, &COMBINATION, end_spreads)?
    else {
        return Ok(());
    };
    let (rows, spreads): (Vec<VariantClaims>, Vec<_>) = measured.into_iter().unzip();
    let studies = COMBINATION
        .iter()
        .map(|v| read_json(&staged.staging.join(v.name).join("summary.json")))
        .collect::<Result<Vec<StudySummary>, CliError>>()?;
    let named: Vec<(&str, &StudySummary)> =
        COMBINATION.iter().map(|v| v.name).zip(&studies).collect();
    let behaviour = behaviour_rows(&named, &spreads);
    let claim_differences = claim_difference_rows(&named);
    let prov = Provenance::new(
        &seeds,
        &RenderContext::of(&rows_exp(args, &seeds)?),
        args.quick,
    );
    let (table, csv) = behaviour_table(&behaviour, seeds.len());
    let claims = fuzzymotiv_io::render::combination::claims_table(&rows, &prov.line());
    let (differences, differences_csv) = claim_difference_table(&claim_differences, seeds.len());
    let md = format!("{claims}\n\n{differences}\n\n{table}");
    staged.write("combination.md", &md)?;
    staged.write("claim_differences.csv", &differences_csv)?;
    staged.write("behaviour.csv", &csv)?;
    let figure = behaviour_svg(&behaviour);
    write_figure_at(
        &staged.staging.join("behaviour.svg"),
        &figure,
        rasteriser(args.png),
    )?;
    let parts: Vec<(String, String)> = (COMBINATION.iter())
        .map(|v| (format!("{}/report.html", v.name), v.name.to_string()))
        .collect();
    staged.write(
        "report.html",
        study_page(
            "Does the fuzzy combination matter?",
            start.elapsed().as_secs_f64(),
            &md,
            &[(
                figure.as_str(),
                "Each baseline − TSK per measure and setting, paired by seed, with its 95 % interval; a filled point is significant and at least the detectable difference.",
            )],
            &parts,
        ),
    )?;
    let summary = CombinationSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: args.seed(),
        seeds,
        quick: args.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: args.sets.clone(),
        combinations: rows
            .iter()
            .map(|(v, claims)| variant_summary(v, claims))
            .collect(),
        behaviour,
        end_spreads: spreads,
        claim_differences,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start)?;
    fuzzymotiv_io::outln!("{md}")
}

/// `reproduce --replication`: the default study at base seeds `--seed` and `--seed` + 10
/// (`OUT/base-S/`, each a whole study), then the claims from their seeds pooled and per number
/// of seeds both base seeds' verdicts (`replication.md`/`.csv`, `replication_seeds.csv`,
/// `replication.svg`, `summary.json`).
fn replication(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let bases = [args.seed(), args.seed().saturating_add(10)];
    let seeds = bases.map(|b| seeds_of(b, args.seeds));
    let names = bases.map(|b| format!("base-{b}"));
    let loaded = [0, 1].map(|i| load_settings(args, &SETTINGS, &seeds[i], &DEFAULT_MODEL));
    let [la, lb] = loaded;
    let loaded = [la?, lb?];
    let parts: Vec<(&str, &Vec<Vec<Loaded>>)> =
        names.iter().map(String::as_str).zip(&loaded).collect();
    let Some(staged) = open_out(args, &args.out_dir(), &SETTINGS, &parts)? else {
        return Ok(());
    };
    let progress = Progress::new(
        &loaded[0][0][0].experiment,
        2 * SETTINGS.len() * seeds[0].len(),
        args.output.quiet,
    );
    for (i, loaded) in loaded.iter().enumerate() {
        let dir = staged.staging.join(&names[i]);
        let label = format!("{} · ", names[i]);
        let studies = run_study(args, &SETTINGS, &seeds[i], loaded, &dir, &progress, &label)?;
        write_study(args, bases[i], &dir, &studies, Instant::now())?;
    }
    progress.finish();
    let [a, b] = [0, 1]
        .map(|i| read_json::<StudySummary>(&staged.staging.join(&names[i]).join("summary.json")));
    let (a, b) = (a?, b?);
    let (pooled, rows, by_seeds, needed) = replication_of(&a, &b);
    let prov = Provenance::new(&seeds[0], &RenderContext::of(&loaded[0][0][0]), args.quick);
    let (md, csv) = replication_table(bases, seeds[0].len(), &rows, needed, &prov.line());
    staged.write("replication.md", &md)?;
    staged.write("replication.csv", &csv)?;
    staged.write("replication_seeds.csv", seeds_csv(&pooled, &by_seeds))?;
    let figure = replication_svg(bases, &pooled, &by_seeds);
    write_figure_at(
        &staged.staging.join("replication.svg"),
        &figure,
        rasteriser(args.png),
    )?;
    let parts: Vec<(String, String)> = (names.iter())
        .map(|n| (format!("{n}/report.html"), n.clone()))
        .collect();
    staged.write(
        "report.html",
        study_page(
            "Verdicts that replicate: the study at two base seeds",
            start.elapsed().as_secs_f64(),
            &md,
            &[(
                figure.as_str(),
                "Per number of seeds, each claim's verdict at both base seeds (replication_seeds.csv).",
            )],
            &parts,
        ),
    )?;
    let summary = ReplicationSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        base_seeds: bases,
        seeds: seeds[0].len(),
        quick: args.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: args.sets.clone(),
        rows,
        by_seeds,
        seeds_needed: needed,
        pooled,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start)?;
    fuzzymotiv_io::outln!("{md}")
}

/// Per setting and seed, the end spread of the seed's robots (`Experiment::end_spreads`, mean
/// over rooms).
fn end_spreads(
    loaded: &[Vec<Loaded>],
    studies: &[SettingRuns<'_>],
) -> Result<Vec<Vec<f64>>, CliError> {
    loaded
        .iter()
        .zip(studies)
        .map(|(loaded, study)| {
            loaded
                .iter()
                .zip(&study.finished)
                .map(|(l, done)| {
                    let spreads = l.experiment.end_spreads(&done.outcome).map_err(|e| {
                        CliError::input(format!(
                            "a run's best genome does not fit its network: {e}"
                        ))
                    })?;
                    Ok(spreads.iter().sum::<f64>() / spreads.len().max(1) as f64)
                })
                .collect()
        })
        .collect()
}

/// `reproduce --ablation`: the study for every variant, then which claims hold under each.
fn ablation(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let seeds = study_seeds(args);
    let Some((staged, rows)) = run_variants(args, &seeds, &ABLATION)? else {
        return Ok(());
    };
    let prov = Provenance::new(
        &seeds,
        &RenderContext::of(&rows_exp(args, &seeds)?),
        args.quick,
    );
    let (md, csv) = ablation_table(&rows, &prov);
    staged.write("ablation.md", &md)?;
    staged.write("ablation.csv", &csv)?;
    let summary = AblationSummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: args.seed(),
        seeds,
        quick: args.quick,
        population: prov.population,
        generations: prov.generations,
        overrides: args.sets.clone(),
        variants: rows
            .iter()
            .map(|(v, claims)| variant_summary(v, claims))
            .collect(),
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    staged.write("summary.json", to_json(&summary))?;
    commit(staged, start)?;
    fuzzymotiv_io::outln!("{md}")
}

/// A variant's record in a study of variants' `summary.json`: its name, what it is and its
/// claims.
fn variant_summary(variant: &Variant, claims: &[ClaimRecord]) -> VariantSummary {
    VariantSummary {
        name: variant.name.into(),
        switched_back: variant.what.into(),
        claims: claims.to_vec(),
    }
}

/// Renames the staged output into place and says where it went and how long it took.
pub(crate) fn commit(staged: StagedDir, start: Instant) -> Result<(), CliError> {
    let out = staged.commit()?;
    note!(
        "wrote {} ({:.1} s)",
        out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Every run of a study by its path in the output, with its resolved config.
fn run_configs(
    settings: &[Setting],
    variants: &[(&str, &Vec<Vec<Loaded>>)],
) -> Vec<(String, String)> {
    let prefix = |name: &str| {
        if variants.len() == 1 {
            String::new()
        } else {
            format!("{name}/")
        }
    };
    variants
        .iter()
        .flat_map(|(v, loaded)| {
            settings
                .iter()
                .zip(loaded.iter())
                .flat_map(move |(s, seeds)| {
                    seeds.iter().enumerate().map(move |(k, l)| {
                        (
                            format!(
                                "{}{}/{}/config.resolved.toml",
                                prefix(v),
                                s.name,
                                seed_dir(k, seeds.len())
                            ),
                            resolved_toml(&l.raw),
                        )
                    })
                })
        })
        .collect()
}

/// What makes a study "the same": [`IDENTITY`] naming the kind of study and every run's
/// resolved config, written before the first run starts.
fn identity(args: &ReproduceArgs, runs: &[(String, String)]) -> Vec<(String, String)> {
    let kind = if args.ablation {
        "ablation"
    } else if args.search_strength {
        "search-strength"
    } else if args.combination {
        "combination"
    } else if args.replication {
        "replication"
    } else if args.urgency {
        "urgency"
    } else {
        "study"
    };
    let runs: serde_json::Map<String, serde_json::Value> = runs
        .iter()
        .map(|(path, config)| (path.clone(), config.clone().into()))
        .collect();
    let doc = serde_json::json!({ "program": PROGRAM, "output": kind, "runs": runs });
    vec![(IDENTITY.to_string(), to_json(&doc))]
}

/// Checks `--out` before any work and opens its staging directory: `None` when it already
/// holds this very study (nothing to do but the missing PNGs with `--png`); an unfinished study
/// of the same configs is reopened (its finished runs are read back, the others resume); another
/// study is replaced only with `--force`.
pub(crate) fn open_out(
    args: &ReproduceArgs,
    out: &Path,
    settings: &[Setting],
    variants: &[(&str, &Vec<Vec<Loaded>>)],
) -> Result<Option<StagedDir>, CliError> {
    let runs = run_configs(settings, variants);
    let id = identity(args, &runs);
    // A study written before identity.json existed is recognised by its runs' configs.
    let legacy = !args.output.force
        && !out.join(IDENTITY).exists()
        && out.join("summary.json").is_file()
        && matches(out, &runs);
    let state = if legacy {
        OutState::Done
    } else {
        check_out(out, &id, args.output.force)?
    };
    match state {
        OutState::Done => {
            note!(
                "{} already holds this study, finished (same resolved configs); nothing to do. --force runs it again",
                out.display()
            );
            if args.png {
                add_pngs(out)?;
            }
            Ok(None)
        }
        OutState::Unfinished => {
            note!(
                "resuming the unfinished study in {}: finished runs are read back, the others continue",
                StagedDir::staging_path(out).display()
            );
            Ok(Some(StagedDir::reopen(out)?))
        }
        OutState::Fresh => {
            let staged = StagedDir::new(out)?;
            for (name, text) in &id {
                staged.write(name, text)?;
            }
            Ok(Some(staged))
        }
    }
}

/// The first config of the default variant (for provenance).
fn rows_exp(args: &ReproduceArgs, seeds: &[u64]) -> Result<Loaded, CliError> {
    load_one(args, &SETTINGS[0], seeds[0], &DEFAULT_MODEL)
}

/// Tables, figures, claims, `report.html` and `summary.json` of a study in `dir`; the claims
/// are the study's own, each verdict from its records by the stated rule ([`paper_claims`]).
/// Returns the claims and the tables to print once the study is in place.
fn write_study(
    args: &ReproduceArgs,
    base: u64,
    dir: &Path,
    studies: &[SettingRuns<'_>],
    start: Instant,
) -> Result<(Vec<ClaimRecord>, String), CliError> {
    let mut printed = String::new();
    let provenance = Provenance::new(&studies[0].seeds, &studies[0].contexts[0], args.quick);
    let mut panels = Vec::new();
    for (k, study) in studies.iter().enumerate() {
        let (md, csv, seeds_csv) = study_table(study, &provenance);
        write_atomic(&dir.join(format!("table{}.md", k + 1)), &md)?;
        write_atomic(&dir.join(format!("table{}.csv", k + 1)), &csv)?;
        write_atomic(&dir.join(format!("table{}_seeds.csv", k + 1)), &seeds_csv)?;
        if !args.ablation {
            printed += &format!(
                "Table {} — {} (C, H, O, E) = {:?}\n{md}\n",
                k + 1,
                study.setting.name,
                study.contexts[study.median()].motivations.as_array(),
            );
        }
        panels.push(write_setting_figure(args, dir, study)?);
    }
    let fitness = fitness_panels_svg(&panels);
    write_figure_at(&dir.join("fitness.svg"), &fitness, rasteriser(args.png))?;
    let settings: Vec<_> = studies.iter().map(SettingRuns::summary).collect();
    let claims = paper_claims(&settings, CLAIMS_ALPHA);
    let (md, csv) = claims_table(&claims, &provenance);
    write_atomic(&dir.join("claims.md"), &md)?;
    write_atomic(&dir.join("claims.csv"), &csv)?;
    let wall_seconds = start.elapsed().as_secs_f64();
    write_atomic(
        &dir.join("report.html"),
        page(args, studies, &provenance, &claims, wall_seconds, &fitness),
    )?;
    let summary = StudySummary {
        program: PROGRAM.into(),
        version: fuzzymotiv::VERSION.into(),
        model: fuzzymotiv::MODEL_VERSION,
        seed: base,
        seeds: provenance.seeds.clone(),
        quick: args.quick,
        population: provenance.population,
        generations: provenance.generations,
        overrides: args.sets.clone(),
        settings,
        claims: claims.clone(),
        wall_seconds,
    };
    write_atomic(&dir.join("summary.json"), to_json(&summary))?;
    Ok((claims, printed))
}

/// The setting's trajectories figure (its median seed's best robot); returns its panel of the
/// study's fitness figure (medians and inter-quartile bands over seeds).
pub(crate) fn write_setting_figure(
    args: &ReproduceArgs,
    dir: &Path,
    study: &SettingRuns<'_>,
) -> Result<FitnessPanel, CliError> {
    let m = study.median();
    let ctx = &study.contexts[m];
    // `(C,H,O,E) = [..]` for the paper's four motivations, every weight by name for others.
    // A list of named weights follows the setting's name after a colon, as a run's title.
    let label = ctx.motivations.label();
    let sep = if label.starts_with('(') { " " } else { ": " };
    let title = format!(
        "{}{sep}{label}, {}",
        study.setting.name,
        study.median_label()
    );
    write_figure_at(
        &dir.join(format!("trajectories_{}.svg", study.setting.tag)),
        &best_paths_svg(
            &format!("Best robot, {title}"),
            &ctx.rooms,
            &study.finished[m].trajectories(),
        ),
        rasteriser(args.png),
    )?;
    // The legend says what is drawn over how many seeds.
    // (The name of a setting beyond the paper's four motivations says what it varies.)
    let panel = if ctx.motivations.table.is_empty() {
        format!("{} {:?}", study.setting.name, ctx.motivations.as_array())
    } else {
        study.setting.name.to_string()
    };
    Ok(study.fitness_panel(&panel))
}

/// The study's report page.
fn page(
    args: &ReproduceArgs,
    studies: &[SettingRuns<'_>],
    provenance: &Provenance,
    claims: &[ClaimRecord],
    wall_seconds: f64,
    fitness: &str,
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
                ctx: &study.contexts[m],
                done: &study.finished[m],
                paper: Some(study.setting),
                link: Some(format!("{}/report.html", study.run_dir(m))),
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
        fitness,
    )
}

fn print_claims(claims: &[ClaimRecord]) -> Result<(), CliError> {
    for c in claims {
        fuzzymotiv_io::outln!("{}: {} ({})", c.claim, verdict(c), c.evidence)?;
    }
    Ok(())
}

/// The orientation study: a built-in sweep (three motivation settings × seeds, online
/// orientation), run in-process, then merged into tables and plots.
fn orientation_study(args: &ReproduceArgs) -> Result<(), CliError> {
    let start = Instant::now();
    let out = args.out_dir();
    let mut text = include_str!("../../../../configs/orientation-study.toml").to_string();
    let mut sets: Vec<String> = Vec::new();
    sets.push(format!("seed={}", args.seed()));
    if args.quick {
        sets.push("ga.population=30".into());
        sets.push("ga.generations=30".into());
        sets.push("sweep.replicates=2".into());
    }
    sets.extend(args.sets.iter().cloned());
    if !sets.is_empty() {
        // Apply overrides to the document (config keys and sweep keys alike).
        let mut table: toml::Table = toml::from_str(&text).expect("built-in sweep is valid TOML");
        fuzzymotiv::experiment::apply_sets(&mut table, &sets)?;
        text = toml::to_string(&table).expect("a table serialises");
    }
    let sweep = Sweep::parse_str(
        &text,
        "built-in orientation study",
        std::path::Path::new("."),
    )?;
    let all: Vec<usize> = (0..sweep.jobs.len()).collect();
    note!(
        "orientation study: {} jobs into {}",
        all.len(),
        out.display()
    );
    run_jobs(
        &sweep,
        &text,
        &all,
        &out,
        args.output.force,
        &JobsProgress::new(args.output.quiet),
    )?;
    merge_dir(&out)?;
    if args.png {
        add_pngs(&out)?;
    }
    note!(
        "orientation study done in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
