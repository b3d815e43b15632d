//! `fuzzymotiv recognise`: the rooms a run's room model recognises in a real robot's logs
//! ([`crate::records::robot_log::recognise_logs`]), as Markdown and, into a directory,
//! `recognised.csv` and `recognised.md` written through the output guard
//! ([`recognise_into`]).

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::guard::{FilesState, check_files_dir, write_into};
use crate::records::robot_log::{recognise_logs, recognition_csv, recognition_md};

/// The names of the files written into `--out`.
pub const RECOGNISED_FILES: [&str; 2] = ["recognised.csv", "recognised.md"];

/// Recognises the rooms of `logs` with the room model of the run in `run`; with `out` (checked
/// before anything is read; other files of those names kept unless `force`) writes its files
/// there. Returns the Markdown table and, with `out`, whether the files were written or
/// already held it.
pub fn recognise_into(
    run: &Path,
    logs: &[PathBuf],
    out: Option<&Path>,
    force: bool,
) -> Result<(String, Option<FilesState>), CliError> {
    if let Some(out) = out {
        check_files_dir(out, "--out", &RECOGNISED_FILES)?;
    }
    let records = recognise_logs(run, logs)?;
    let md = recognition_md(run, &records);
    let Some(out) = out else {
        return Ok((md, None));
    };
    let files = vec![
        (
            out.join(RECOGNISED_FILES[0]),
            recognition_csv(&records).into_bytes(),
        ),
        (out.join(RECOGNISED_FILES[1]), md.clone().into_bytes()),
    ];
    let state = write_into(out, &files, "--out", force)?;
    Ok((md, Some(state)))
}
