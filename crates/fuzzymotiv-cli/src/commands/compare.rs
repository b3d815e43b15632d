//! `compare A B --out DIR`: two runs, studies or sweep settings compared per room and overall
//! (`fuzzymotiv_pipeline::pipeline::compare`), written through the output guard.

use std::path::PathBuf;

use crate::console::note;
use fuzzymotiv_pipeline::files::error::CliError;
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files_dir, io_err, write_into};
use fuzzymotiv_pipeline::pipeline::compare::{check_comparable, choose, compare, load};
use fuzzymotiv_pipeline::render::study::CLAIMS_ALPHA;

use crate::png::svg_to_png;

/// Arguments of `fuzzymotiv compare`.
#[derive(clap::Args)]
pub struct CompareArgs {
    /// A: a run directory, a study directory (reproduce) or a merged sweep directory.
    pub a: PathBuf,
    /// B: an output of the same kind and rooms as A (may be A itself, with two --setting).
    pub b: PathBuf,
    /// Directory for compare.md, compare.csv and compare.svg (created if missing; files that
    /// differ are kept unless --force).
    #[arg(long)]
    pub out: PathBuf,
    /// A setting of a study or sweep: once, that setting of both; twice, A's then B's.
    #[arg(long = "setting", value_name = "S")]
    pub setting: Vec<String>,
    /// Significance level α of the `*` marks and of the minimum detectable difference.
    #[arg(long, allow_hyphen_values = true, default_value_t = CLAIMS_ALPHA)]
    pub alpha: f64,
    /// Also write compare.png beside compare.svg.
    #[arg(long)]
    pub png: bool,
    /// Replace compare.* files that differ (regular files only).
    #[arg(long)]
    pub force: bool,
}

/// Entry point of `fuzzymotiv compare`: reads both outputs, refuses different kinds or rooms,
/// compares the chosen settings and writes the files; prints compare.md.
pub fn compare_command(args: CompareArgs) -> Result<(), CliError> {
    if args.alpha.is_nan() || args.alpha <= 0.0 || args.alpha >= 1.0 {
        return Err(CliError::input(format!(
            "--alpha must be between 0 and 1 (exclusive), got {}",
            fuzzymotiv::params::Num(args.alpha)
        )));
    }
    check_files_dir(
        &args.out,
        "--out",
        &["compare.md", "compare.csv", "compare.svg"],
    )?;
    let a = load(&args.a, "A")?;
    let b = load(&args.b, "B")?;
    check_comparable(&a, &b)?;
    let pairs = choose(&a, &b, &args.setting)?;
    let done = compare(&a, &b, &pairs, args.alpha)?;
    let out = &args.out;
    let mut files = vec![
        (out.join("compare.md"), done.md.clone().into_bytes()),
        (out.join("compare.csv"), done.csv.into_bytes()),
    ];
    if args.png {
        let path = out.join("compare.png");
        let png = svg_to_png(&done.svg).map_err(|e| io_err(&path, std::io::Error::other(e)))?;
        files.push((path, png));
    }
    files.push((out.join("compare.svg"), done.svg.into_bytes()));
    if write_into(out, &files, "--out", args.force)? == FilesState::Same {
        note!("{} already holds these files; nothing to do", out.display());
    }
    crate::console::out!("{}", done.md)?;
    Ok(())
}
