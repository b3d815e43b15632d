//! A saved genome (`best_genome.json`) and the config beside it: what `replay` and `export`
//! read from a run directory or a genome file.

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::records::{BestGenome, read_json};

/// A genome read from `best_genome.json`, checked.
#[derive(Debug, Clone)]
pub struct SavedGenome {
    /// The file it was read from.
    pub path: PathBuf,
    /// `shape.hidden`, in 1..=1024.
    pub hidden: usize,
    /// The main robot's weights.
    pub weights: Vec<f64>,
    /// The seed of the run that evolved it, when recorded.
    pub seed: Option<u64>,
    /// Per evolution (run label, weights), when the file lists them (per-room training).
    pub runs: Vec<(String, Vec<f64>)>,
}

/// Reads and checks a `best_genome.json`; errors name the file and field.
pub fn read_genome(path: &Path) -> Result<SavedGenome, CliError> {
    if !path.is_file() {
        return Err(CliError::input(format!(
            "{}: cannot read genome file: no such file",
            path.display()
        )));
    }
    let doc: BestGenome = read_json(path)?;
    let hidden = doc.shape.hidden;
    if !(1..=1024).contains(&hidden) {
        return Err(CliError::input(format!(
            "{}: field `shape.hidden`: {hidden} is not a number of hidden units in 1..=1024",
            path.display()
        )));
    }
    Ok(SavedGenome {
        path: path.to_path_buf(),
        hidden,
        weights: doc.weights,
        seed: doc.seed,
        runs: doc.runs.into_iter().map(|r| (r.run, r.weights)).collect(),
    })
}

/// The genome file and the config beside it (a run directory's, or one next to the file).
pub fn locate(src: &Path) -> Result<(PathBuf, Option<PathBuf>), CliError> {
    if src.is_dir() {
        let config = src.join("config.resolved.toml");
        if !config.is_file() {
            return Err(CliError::input(format!(
                "{}: not a run directory (no config.resolved.toml); pass a directory written by `fuzzymotiv run` or a best_genome.json",
                src.display()
            )));
        }
        Ok((src.join("best_genome.json"), Some(config)))
    } else if src.is_file() {
        let beside = src
            .parent()
            .map(|d| d.join("config.resolved.toml"))
            .filter(|c| c.is_file());
        Ok((src.to_path_buf(), beside))
    } else {
        Err(CliError::input(format!(
            "{}: no such run directory or genome file",
            src.display()
        )))
    }
}
