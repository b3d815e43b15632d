//! The runs every study shares: each (setting, seed) config loaded and validated before
//! anything is written, the output opened (fresh, resumed or already done, [`open_out`]), the
//! runs evolved side by side into it ([`run_study`]) and the staged output committed.

use std::path::Path;
use std::time::Instant;

use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::random::Streams;

use crate::files::error::CliError;
use crate::files::guard::{IDENTITY, OutState, StagedDir, check_out, matches};
use crate::files::inputs::{Loaded, resolve, resolved_toml};
use crate::files::notes::Notes;
use crate::pipeline::lanes::run_concurrently;
use crate::pipeline::run_dir::{execute_or_resume, start_line};
use crate::records::context::RenderContext;
use crate::records::{ClaimRecord, PROGRAM, VariantSummary, to_json};
use crate::render::figures::{Rasterise, add_missing_pngs};
use crate::render::study::{
    DEFAULT_MODEL, FIRST_RELEASE_ROOMS, SETTINGS, Setting, SettingRuns, Variant, seed_dir,
    seed_index,
};

use super::{Front, ReproduceOptions};

/// One (setting, seed) config of a variant, validated.
fn load_one(
    options: &ReproduceOptions,
    setting: &Setting,
    seed: u64,
    variant: &Variant,
) -> Result<Loaded, CliError> {
    let mut sets = Vec::new();
    if options.quick {
        sets.push("ga.population=30".to_string());
        sets.push("ga.generations=30".to_string());
    }
    sets.push(format!("seed={seed}"));
    sets.extend(setting.sets.iter().map(|s| s.to_string()));
    sets.extend(variant.sets.iter().map(|s| s.to_string()));
    sets.extend(options.sets.iter().cloned());
    let source = format!("built-in config {}", setting.name);
    let mut raw = RawConfig::parse(setting.config, &source, &sets)?;
    let files: Vec<(String, &str)> = if variant.first_release_rooms {
        (FIRST_RELEASE_ROOMS.iter())
            .map(|(name, text)| (format!("rooms/first-release/{name}.toml"), *text))
            .collect()
    } else if !setting.rooms.is_empty() {
        chosen_rooms(&raw.rooms, setting)?
    } else {
        return resolve(raw, Path::new("."), &source);
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
    Ok(Loaded {
        raw,
        experiment,
        notes: Vec::new(),
    })
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
pub fn load_settings(
    options: &ReproduceOptions,
    settings: &[Setting],
    seeds: &[u64],
    variant: &Variant,
) -> Result<Vec<Vec<Loaded>>, CliError> {
    settings
        .iter()
        .map(|s| {
            seeds
                .iter()
                .map(|&seed| load_one(options, s, seed, variant))
                .collect()
        })
        .collect()
}

/// Evolves every (setting, seed) of a variant into `dir/SETTING/seed-NN/` (the seed's index,
/// [`seed_dir`]), as many runs at a time as there are threads ([`run_concurrently`]); each
/// run's progress is a view of `front`'s named `LABELSETTING seed #NN`.
pub fn run_study<'a>(
    front: Front<'_>,
    settings: &'a [Setting],
    seeds: &[u64],
    loaded: &[Vec<Loaded>],
    dir: &Path,
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
        let progress = front.progress.run(&name);
        let run_dir = dir.join(setting.name).join(seed_dir(k, n));
        progress.note(&start_line(&l.experiment, &run_dir));
        execute_or_resume(l, &run_dir, &*progress, front.png)
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

/// One study of `settings` under the default model, `name` in the output's identity: every
/// (setting, seed) config loaded and validated, the output opened ([`open_out`]) and every run
/// evolved into the staging directory ([`run_study`]). `None` when the output already holds it.
pub fn run_one_study<'a>(
    options: &ReproduceOptions,
    front: Front<'_>,
    settings: &'a [Setting],
    name: &str,
) -> Result<Option<(StagedDir, Vec<SettingRuns<'a>>)>, CliError> {
    let seeds = study_seeds(options);
    let loaded = load_settings(options, settings, &seeds, &DEFAULT_MODEL)?;
    let Some(staged) = open_out(options, front, settings, &[(name, &loaded)])? else {
        return Ok(None);
    };
    let progress = front.progress;
    progress.begin(&loaded[0][0].experiment, settings.len() * seeds.len());
    let studies = run_study(front, settings, &seeds, &loaded, &staged.staging, "")?;
    progress.end();
    Ok(Some((staged, studies)))
}

/// The seeds of the study: `options.seeds` of them from base seed `options.seed`.
pub fn study_seeds(options: &ReproduceOptions) -> Vec<u64> {
    seeds_of(options.seed, options.seeds)
}

/// The `n` seeds of a study at base seed `base`.
pub fn seeds_of(base: u64, n: u64) -> Vec<u64> {
    (0..n as usize)
        .map(|k| Streams::new(base).study(k))
        .collect()
}

/// The first config of the default variant (for provenance).
pub fn first_config(options: &ReproduceOptions, seeds: &[u64]) -> Result<Loaded, CliError> {
    load_one(options, &SETTINGS[0], seeds[0], &DEFAULT_MODEL)
}

/// A part of a study that sets config keys itself: its name, what it is, its overrides.
pub type Part<'a> = (&'a str, &'a str, &'a [&'a str]);

/// A `--set` of a key that a part of the study sets itself: refused, naming the part.
pub fn refuse_own_keys(sets: &[String], parts: &[Part<'_>]) -> Result<(), CliError> {
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

/// A variant's record in a study of variants' `summary.json`: its name, what it is and its
/// claims.
pub fn variant_summary(variant: &Variant, claims: &[ClaimRecord]) -> VariantSummary {
    VariantSummary {
        name: variant.name.into(),
        switched_back: variant.what.into(),
        claims: claims.to_vec(),
    }
}

/// Renames the staged output into place and says to `notes` where it went and how long it
/// took.
pub fn commit(staged: StagedDir, start: Instant, notes: &dyn Notes) -> Result<(), CliError> {
    let out = staged.commit()?;
    notes.note(&format!(
        "wrote {} ({:.1} s)",
        out.display(),
        start.elapsed().as_secs_f64()
    ));
    Ok(())
}

/// The PNGs a finished output lacks, and nothing else; says to `notes` how many.
pub fn add_pngs(dir: &Path, png: &dyn Rasterise, notes: &dyn Notes) -> Result<(), CliError> {
    let n = add_missing_pngs(dir, png)?;
    notes.note(&format!(
        "--png: {n} PNG figure(s) added to {}",
        dir.display()
    ));
    Ok(())
}

/// The notes of the study's configs (e.g. that `--set` motivations were normalised), said to
/// `notes` once: those of the first config that has any (the others say the same of theirs).
fn config_notes(variants: &[(&str, &Vec<Vec<Loaded>>)], notes: &dyn Notes) {
    let first = (variants.iter())
        .flat_map(|(_, loaded)| loaded.iter().flatten())
        .find(|l| !l.notes.is_empty());
    for line in first.into_iter().flat_map(|l| &l.notes) {
        notes.note(&format!("note: {line}"));
    }
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
fn identity(options: &ReproduceOptions, runs: &[(String, String)]) -> Vec<(String, String)> {
    let runs: serde_json::Map<String, serde_json::Value> = runs
        .iter()
        .map(|(path, config)| (path.clone(), config.clone().into()))
        .collect();
    let doc = serde_json::json!({
        "program": PROGRAM,
        "output": options.kind.identity(),
        "runs": runs
    });
    vec![(IDENTITY.to_string(), to_json(&doc))]
}

/// Checks the output before any work and opens its staging directory: `None` when it already
/// holds this very study (nothing to do but the missing PNGs with a rasteriser); an unfinished
/// study of the same configs is reopened (its finished runs are read back, the others resume);
/// another study is replaced only with `force`.
pub fn open_out(
    options: &ReproduceOptions,
    front: Front<'_>,
    settings: &[Setting],
    variants: &[(&str, &Vec<Vec<Loaded>>)],
) -> Result<Option<StagedDir>, CliError> {
    let out = options.out.as_path();
    config_notes(variants, front.progress);
    let runs = run_configs(settings, variants);
    let id = identity(options, &runs);
    // A study written before identity.json existed is recognised by its runs' configs.
    let legacy = !options.force
        && !out.join(IDENTITY).exists()
        && out.join("summary.json").is_file()
        && matches(out, &runs);
    let state = if legacy {
        OutState::Done
    } else {
        check_out(out, &id, options.force, front.progress)?
    };
    match state {
        OutState::Done => {
            front.progress.note(&format!(
                "{} already holds this study, finished (same resolved configs); nothing to do. --force runs it again",
                out.display()
            ));
            if let Some(png) = front.png {
                add_pngs(out, png, front.progress)?;
            }
            Ok(None)
        }
        OutState::Unfinished => {
            front.progress.note(&format!(
                "resuming the unfinished study in {}: finished runs are read back, the others continue",
                StagedDir::staging_path(out).display()
            ));
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
