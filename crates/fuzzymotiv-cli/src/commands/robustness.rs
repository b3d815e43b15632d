//! `fuzzymotiv robustness`: a run's best robot under the perturbations a real robot brings
//! (paired streams), F and behaviour per perturbation with 95 % intervals, as CSV, Markdown and
//! a figure ([`fuzzymotiv_pipeline::records::robustness::robustness_of_run`] over
//! [`fuzzymotiv::experiment::Experiment::robustness`]).

use std::path::PathBuf;

use crate::console::{note, outln};
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files_dir, io_err, write_into};
use fuzzymotiv_pipeline::records::robustness::{robustness_csv, robustness_md, robustness_of_run};
use fuzzymotiv_pipeline::render::robustness::robustness_svg;

use crate::png::svg_to_png;

/// Arguments of `fuzzymotiv robustness`.
#[derive(clap::Args)]
pub struct RobustnessArgs {
    /// A run directory (its best_genome.json and config.resolved.toml).
    #[arg(value_name = "RUN_DIR")]
    pub run: PathBuf,
    /// The directory to write robustness.csv, robustness.md and robustness.svg into (created
    /// if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Trials per room and perturbation (the same streams under every perturbation).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(2..=10_000))]
    pub trials: u32,
    /// Also write robustness.png beside robustness.svg.
    #[arg(long)]
    pub png: bool,
    /// Replace existing files of these names that hold something else.
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv robustness`.
pub fn robustness(args: RobustnessArgs) -> Result<(), CliError> {
    let mut names = vec!["robustness.csv", "robustness.md", "robustness.svg"];
    if args.png {
        names.push("robustness.png");
    }
    check_files_dir(&args.out, "--out", &names)?;
    let study = robustness_of_run(&args.run, args.trials as usize)?;
    let records = study.records;
    let md = robustness_md(&records, &study.notes);
    let name = args.run.canonicalize().unwrap_or_else(|_| args.run.clone());
    let name = name.file_name().map_or(name.as_os_str(), |n| n);
    let title = format!("Robustness of {}'s best robot", name.to_string_lossy());
    let svg = robustness_svg(&title, &records);
    let mut files = vec![
        (
            args.out.join("robustness.csv"),
            robustness_csv(&records).into_bytes(),
        ),
        (args.out.join("robustness.md"), md.clone().into_bytes()),
    ];
    if args.png {
        let path = args.out.join("robustness.png");
        let png = svg_to_png(&svg).map_err(|e| io_err(&path, std::io::Error::other(e)))?;
        files.push((path, png));
    }
    files.push((args.out.join("robustness.svg"), svg.into_bytes()));
    if write_into(&args.out, &files, "--out", args.force)? == FilesState::Same {
        note!(
            "{} already holds these files; nothing to do",
            args.out.display()
        );
    }
    note!(
        "{} perturbations × {} trials per room",
        records.len(),
        args.trials
    );
    outln!("{md}")
}
