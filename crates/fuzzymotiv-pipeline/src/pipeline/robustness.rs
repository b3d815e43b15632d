//! `fuzzymotiv robustness`: a run's best robot under the perturbations a real robot brings,
//! measured ([`crate::records::robustness::robustness_of_run`]) and written through the output
//! guard as `robustness.csv`, `robustness.md`, `robustness.svg` (and `robustness.png`)
//! ([`robustness_into`]).

use std::path::Path;

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files_dir, io_err, write_into};
use crate::records::robustness::{robustness_csv, robustness_md, robustness_of_run};
use crate::render::figures::Rasterise;
use crate::render::robustness::robustness_svg;

/// What [`robustness_into`] did.
#[derive(Debug)]
pub struct RobustnessDone {
    /// `robustness.md`.
    pub md: String,
    /// How many perturbations were measured.
    pub perturbations: usize,
    /// Whether the files were written or already held these results.
    pub state: FilesState,
}

/// The robustness of the best robot of the run in `run` over `trials` trials per room and
/// perturbation, written into `out` (checked before anything runs; other files of those names
/// kept unless `force`), with `robustness.png` drawn by `png` if given.
pub fn robustness_into(
    run: &Path,
    out: &Path,
    trials: usize,
    png: Option<&dyn Rasterise>,
    force: bool,
) -> Result<RobustnessDone, CliError> {
    let mut names = vec!["robustness.csv", "robustness.md", "robustness.svg"];
    if png.is_some() {
        names.push("robustness.png");
    }
    check_files_dir(out, "--out", &names)?;
    let study = robustness_of_run(run, trials)?;
    let records = study.records;
    let md = robustness_md(&records, &study.notes);
    let name = run.canonicalize().unwrap_or_else(|_| run.to_path_buf());
    let name = name.file_name().map_or(name.as_os_str(), |n| n);
    let title = format!("Robustness of {}'s best robot", name.to_string_lossy());
    let svg = robustness_svg(&title, &records);
    let mut files = vec![
        (
            out.join("robustness.csv"),
            robustness_csv(&records).into_bytes(),
        ),
        (out.join("robustness.md"), md.clone().into_bytes()),
    ];
    if let Some(png) = png {
        let path = out.join("robustness.png");
        let bytes = (png.png(&svg)).map_err(|e| io_err(&path, std::io::Error::other(e)))?;
        files.push((path, bytes));
    }
    files.push((out.join("robustness.svg"), svg.into_bytes()));
    let state = write_into(out, &files, "--out", force)?;
    Ok(RobustnessDone {
        md,
        perturbations: records.len(),
        state,
    })
}
