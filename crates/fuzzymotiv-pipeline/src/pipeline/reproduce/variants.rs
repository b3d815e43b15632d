//! A study of variants: the paper's study once per variant of the model (the ablation's
//! modelling choices, the search strength's populations, the combinations), each into
//! `OUT/VARIANT/` with its own tables, figures, claims and `summary.json`.

use std::time::Instant;

use crate::files::error::CliError;
use crate::files::guard::StagedDir;
use crate::files::inputs::Loaded;
use crate::records::ClaimRecord;
use crate::render::study::{SETTINGS, SettingRuns, Variant};

use super::paper::write_study;
use super::runs::{Part, load_settings, open_out, refuse_own_keys, run_study};
use super::{Front, ReproduceOptions};

/// A variant and its claims.
pub type VariantClaims = (&'static Variant, Vec<ClaimRecord>);

/// The staged output of a study of variants, and per variant its claims and what was measured.
pub type Measured<T> = (StagedDir, Vec<(VariantClaims, T)>);

/// Runs the study of every variant into `OUT/VARIANT/` (each with its tables, figures,
/// claims and summary.json); `None` when the output already holds them all.
pub fn run_variants(
    options: &ReproduceOptions,
    front: Front<'_>,
    seeds: &[u64],
    variants: &'static [Variant],
) -> Result<Option<(StagedDir, Vec<VariantClaims>)>, CliError> {
    let done = run_variants_measuring(options, front, seeds, variants, |_, _| Ok(()))?;
    Ok(done.map(|(staged, rows)| (staged, rows.into_iter().map(|(v, _)| v).collect())))
}

/// [`run_variants`], also measuring each variant's runs with `measure` (given the variant's
/// configs and its runs, per setting) while they are in memory.
pub fn run_variants_measuring<T>(
    options: &ReproduceOptions,
    front: Front<'_>,
    seeds: &[u64],
    variants: &'static [Variant],
    measure: impl Fn(&[Vec<Loaded>], &[SettingRuns<'_>]) -> Result<T, CliError>,
) -> Result<Option<Measured<T>>, CliError> {
    refuse_variant_keys(&options.sets, variants)?;
    let loaded = variants
        .iter()
        .map(|v| load_settings(options, &SETTINGS, seeds, v))
        .collect::<Result<Vec<_>, CliError>>()?;
    let pairs: Vec<_> = variants.iter().map(|v| v.name).zip(&loaded).collect();
    let Some(staged) = open_out(options, front, &SETTINGS, &pairs)? else {
        return Ok(None);
    };
    let runs = variants.len() * SETTINGS.len() * seeds.len();
    front.progress.begin(&loaded[0][0][0].experiment, runs);
    let mut rows = Vec::new();
    for (variant, loaded) in variants.iter().zip(loaded) {
        let dir = staged.staging.join(variant.name);
        let label = format!("{} · ", variant.name);
        let studies = run_study(front, &SETTINGS, seeds, &loaded, &dir, &label)?;
        let written = write_study(options, front, options.seed, &dir, &studies, Instant::now())?;
        let measured = measure(&loaded, &studies)?;
        rows.push(((variant, written.claims), measured));
    }
    front.progress.end();
    Ok(Some((staged, rows)))
}

/// A `--set` of a key that a variant sets itself would make the variants one study (the user's
/// value comes last): refused, naming the variant.
fn refuse_variant_keys(sets: &[String], variants: &[Variant]) -> Result<(), CliError> {
    let parts: Vec<Part<'_>> = (variants.iter())
        .map(|v| (v.name, v.what, v.sets))
        .collect();
    refuse_own_keys(sets, &parts)
}
