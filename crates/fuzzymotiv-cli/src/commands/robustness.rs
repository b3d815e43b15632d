//! `fuzzymotiv robustness`: a run's best robot under the perturbations a real robot brings
//! (paired streams), F and behaviour per perturbation with 95 % intervals, as CSV and Markdown
//! ([`fuzzymotiv::experiment::Experiment::robustness`]).

use std::path::PathBuf;

use fuzzymotiv::experiment::{Perturbation, RobustnessRow};
use fuzzymotiv::statistics::{mean, mean_interval};
use fuzzymotiv_io::files::error::CliError;
use fuzzymotiv_io::files::guard::{FilesState, check_files, write_files};
use fuzzymotiv_io::files::inputs::load_config;
use fuzzymotiv_io::records::genome::{locate, read_genome};
use fuzzymotiv_io::{note, outln};

/// Arguments of `fuzzymotiv robustness`.
#[derive(clap::Args)]
pub struct RobustnessArgs {
    /// A run directory (its best_genome.json and config.resolved.toml).
    #[arg(value_name = "RUN_DIR")]
    pub run: PathBuf,
    /// The directory to write robustness.csv and robustness.md into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Trials per room and perturbation (the same streams under every perturbation).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(2..=10_000))]
    pub trials: u32,
    /// Replace existing files of these names that hold something else.
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv robustness`.
pub fn robustness(args: RobustnessArgs) -> Result<(), CliError> {
    let (genome_path, config) = locate(&args.run)?;
    let Some(config) = config else {
        return Err(CliError::input(format!(
            "{}: no config.resolved.toml beside the genome; robustness needs a run directory",
            args.run.display()
        )));
    };
    let genome = read_genome(&genome_path)?;
    let loaded = load_config(Some(&config), &[], None)?;
    let exp = &loaded.experiment;
    let perturbations = Perturbation::standard(exp.trial_params().robot().radius());
    let rows = exp
        .robustness(&genome.weights, &perturbations, args.trials as usize)
        .map_err(|e| CliError::input(format!("{}: {e}", genome_path.display())))?;
    let (csv, md) = tables(&rows);
    let files = [
        (args.out.join("robustness.csv"), csv.into_bytes()),
        (args.out.join("robustness.md"), md.clone().into_bytes()),
    ];
    if check_files(&files, "--out", args.force)? == FilesState::Write {
        std::fs::create_dir_all(&args.out)
            .map_err(|e| fuzzymotiv_io::files::guard::io_err(&args.out, e))?;
        write_files(&files)?;
    }
    note!(
        "{} perturbations × {} trials per room",
        rows.len(),
        args.trials
    );
    outln!("{md}")
}

/// Mean and 95 % bootstrap interval of `v`.
fn summary(v: &[f64], seed: u64) -> (f64, f64, f64) {
    let (lo, hi) = mean_interval(v, 0.95, 2000, seed);
    (mean(v), lo, hi)
}

/// The CSV and the Markdown table.
fn tables(rows: &[RobustnessRow]) -> (String, String) {
    let mut csv = String::from(
        "perturbation,trials,f,f_lo,f_hi,exploration,exploration_lo,exploration_hi,homing,homing_lo,homing_hi,battery,battery_lo,battery_hi\n",
    );
    let mut md = String::from(
        "| perturbation | F (95 % CI) | exploration a | homing g | battery b |\n|---|---|---|---|---|\n",
    );
    for (k, r) in rows.iter().enumerate() {
        let cols = [&r.f, &r.exploration, &r.homing, &r.battery].map(|v| summary(v, k as u64 + 1));
        let nums: Vec<String> = (cols.iter())
            .flat_map(|&(m, lo, hi)| [m, lo, hi].map(|x| format!("{x:.6}")))
            .collect();
        csv.push_str(&format!(
            "{},{},{}\n",
            r.perturbation.label(),
            r.f.len(),
            nums.join(",")
        ));
        let cell = |(m, lo, hi): (f64, f64, f64)| format!("{m:.3} [{lo:.3}, {hi:.3}]");
        md.push_str(&format!(
            "| {} | {} | {} | {} | {} |\n",
            r.perturbation.label(),
            cell(cols[0]),
            cell(cols[1]),
            cell(cols[2]),
            cell(cols[3])
        ));
    }
    (csv, md)
}
