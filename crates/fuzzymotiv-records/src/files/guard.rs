//! Writing outputs without half-written files: everything goes to a temporary name first.

use std::path::{Path, PathBuf};

use crate::files::bounded::{InputKind, read_input, what_it_is};
use crate::files::error::CliError;
use crate::files::notes::Notes;
pub use crate::files::refusal::{CLI, OutputError, PYTHON, Spelling};

/// Writes `contents` to `path` via a temporary file in the same directory and a rename.
/// The temporary file is new (a unique `.tmpXXXXXX` name, created exclusively, so no other
/// file, link or concurrent writer's file is ever written through) and is removed on failure.
pub fn write_atomic(path: &Path, contents: impl AsRef<[u8]>) -> Result<(), CliError> {
    temp_with(path, contents.as_ref())?
        .persist(path)
        .map_err(|e| io_err(path, e.error))?;
    Ok(())
}

/// A new temporary file beside `path` holding `bytes` (deleted when dropped unless persisted).
fn temp_with(path: &Path, bytes: &[u8]) -> Result<tempfile::NamedTempFile, CliError> {
    use std::io::Write;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        // A file-system failure (exit 1, OSError in Python), said without the temporary name.
        return Err(CliError::io(format!(
            "{}: its folder {} does not exist (or is not a folder); create it, or choose \
             another path",
            path.display(),
            dir.display()
        )));
    }
    let mut builder = tempfile::Builder::new();
    builder.prefix(".tmp");
    // As `std::fs::write` creates files: 0o666 less the umask (a temporary file would be 0o600).
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut tmp = builder.tempfile_in(dir).map_err(|e| io_err(path, e))?;
    tmp.write_all(bytes)
        .and_then(|()| tmp.flush())
        .map_err(|e| io_err(path, e))?;
    Ok(tmp)
}

/// An I/O failure naming the path.
pub fn io_err(path: &Path, e: std::io::Error) -> CliError {
    CliError::Io {
        path: path.to_path_buf(),
        source: e,
    }
}

/// A run directory being written: files go into `<dir>.partial/`, which is renamed to `<dir>`
/// by [`StagedDir::commit`] (replacing an older `<dir>`), so `<dir>` is never half-written.
pub struct StagedDir {
    /// Final location.
    pub dir: PathBuf,
    /// Where files are written until commit.
    pub staging: PathBuf,
}

impl StagedDir {
    /// Where the staging directory of `dir` lives: `<dir>.partial`.
    pub fn staging_path(dir: &Path) -> PathBuf {
        let mut name = dir
            .file_name()
            .map(|n| n.to_os_string())
            .unwrap_or_else(|| "run".into());
        name.push(".partial");
        dir.with_file_name(name)
    }

    /// Reopens an existing staging directory (to resume an interrupted run), removing the
    /// temporary files that a killed process left in it (they would end up in the output).
    pub fn reopen(dir: &Path) -> Result<Self, CliError> {
        let staging = Self::staging_path(dir);
        if !staging.is_dir() {
            return Err(CliError::input(format!(
                "{}: no interrupted run to resume",
                staging.display()
            )));
        }
        remove_stale_temporaries(&staging)?;
        Ok(Self {
            dir: dir.to_path_buf(),
            staging,
        })
    }

    /// Starts a fresh staging directory for `dir` (refused up front if `dir` exists and is not
    /// an earlier fuzzymotiv output, since it would be replaced at the end). An older staging
    /// directory is discarded: callers check with [`check_out`] first.
    pub fn new(dir: &Path) -> Result<Self, CliError> {
        ensure_replaceable(dir)?;
        let staging = Self::staging_path(dir);
        if std::fs::symlink_metadata(&staging).is_ok() {
            remove_ours(&staging)?;
        }
        std::fs::create_dir_all(&staging).map_err(|e| io_err(&staging, e))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            staging,
        })
    }

    /// Path of a file inside the staging directory.
    pub fn path(&self, name: &str) -> PathBuf {
        self.staging.join(name)
    }

    /// Writes a file into the staging directory.
    pub fn write(&self, name: &str, contents: impl AsRef<[u8]>) -> Result<(), CliError> {
        write_atomic(&self.path(name), contents)
    }

    /// Moves the finished directory into place. An existing `dir` is replaced only when it is
    /// an earlier fuzzymotiv output (or empty); anything else is left alone.
    pub fn commit(self) -> Result<PathBuf, CliError> {
        ensure_replaceable(&self.dir)?;
        if self.dir.exists() {
            remove_ours(&self.dir)?;
        }
        std::fs::rename(&self.staging, &self.dir).map_err(|e| io_err(&self.dir, e))?;
        Ok(self.dir)
    }
}

/// Removes, under one of our staging directories, the temporary files (`.tmp*`, only ever
/// written by [`write_atomic`] and [`write_files`]) of a process that was killed mid-write.
fn remove_stale_temporaries(dir: &Path) -> Result<(), CliError> {
    for entry in std::fs::read_dir(dir)
        .map_err(|e| io_err(dir, e))?
        .flatten()
    {
        let path = entry.path();
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            continue;
        };
        if meta.is_dir() {
            remove_stale_temporaries(&path)?;
        } else if meta.is_file() && entry.file_name().to_string_lossy().starts_with(".tmp") {
            std::fs::remove_file(&path).map_err(|e| io_err(&path, e))?;
        }
    }
    Ok(())
}

/// Whether `dir` may be replaced by a new output: it does not exist, is an empty directory, or
/// is one of our outputs ([`is_ours`]). Anything else (a file, a device, a directory of the
/// user's) is never replaced, even with `--force`.
pub fn ensure_replaceable(dir: &Path) -> Result<(), CliError> {
    let Ok(meta) = std::fs::symlink_metadata(dir) else {
        return Ok(());
    };
    if meta.is_dir() && (is_empty_dir(dir) || is_ours(dir)) {
        Ok(())
    } else {
        Err(OutputError::NotAnOutput {
            dir: dir.to_path_buf(),
        }
        .into())
    }
}

/// Whether `dir` is one of our output directories: a run (`summary.json` or
/// `config.resolved.toml`), a study (`identity.json`) or a sweep (`plan.jsonl`).
pub fn is_ours(dir: &Path) -> bool {
    [
        "summary.json",
        "config.resolved.toml",
        IDENTITY,
        "plan.jsonl",
    ]
    .iter()
    .any(|f| dir.join(f).is_file())
}

/// The names of the files our outputs write (besides `*.svg` and `*.png` figures, `.tmp*`
/// temporary files and sweep jobs' `ID.lock` files): anything else in a directory about to be replaced is the user's.
const OUR_FILES: [&str; 38] = [
    "config.resolved.toml",
    "generations.csv",
    "best_genome.json",
    "population.json",
    "recognition.csv",
    "table.md",
    "summary.json",
    "report.html",
    "checkpoint.json",
    "job.json",
    "DONE",
    IDENTITY,
    "table1.md",
    "table1.csv",
    "table1_seeds.csv",
    "table2.md",
    "table2.csv",
    "table2_seeds.csv",
    "claims.md",
    "claims.csv",
    "ablation.md",
    "ablation.csv",
    "search_strength.md",
    "search_strength.csv",
    "plan.jsonl",
    "sweep.toml",
    "results.csv",
    "aggregate.csv",
    "aggregate.md",
    "test_runs.csv",
    "compare.md",
    "compare.csv",
    "study.toml",
    "per_seed.csv",
    "rooms.csv",
    "arms.csv",
    "study.json",
    "report.md",
];

/// The files under `dir` (recursively; a symbolic link counts as one, never followed) that none
/// of our outputs writes.
pub fn foreign_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return found;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        match std::fs::symlink_metadata(&path) {
            Ok(m) if m.is_dir() => found.extend(foreign_files(&path)),
            Ok(m) if m.is_file() && is_our_file(&name) => {}
            _ => found.push(path),
        }
    }
    found
}

fn is_our_file(name: &str) -> bool {
    OUR_FILES.contains(&name)
        || is_claims_at_alpha(name)
        || name.ends_with(".svg")
        || name.ends_with(".png")
        || name.starts_with(".tmp")
        || crate::files::job_lock::is_lock_name(name)
}

/// `claims-alpha-A.md` or `.csv`: the claims of a study at another α
/// (`claims_stem` of the render crate's `study`), beside its own.
fn is_claims_at_alpha(name: &str) -> bool {
    let alpha = name.strip_prefix("claims-alpha-").and_then(|rest| {
        rest.strip_suffix(".md")
            .or_else(|| rest.strip_suffix(".csv"))
    });
    alpha.is_some_and(|a| a.parse::<f64>().is_ok_and(|a| a > 0.0 && a < 1.0))
}

/// Refuses, before any work, to replace a directory that holds a file of the user's (see
/// [`foreign_files`]), even with `--force`.
pub fn ensure_only_ours(dir: &Path) -> Result<(), CliError> {
    if std::fs::symlink_metadata(dir).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(OutputError::LinkNeverReplaced {
            dir: dir.to_path_buf(),
        }
        .into());
    }
    let files = foreign_files(dir);
    if files.is_empty() {
        return Ok(());
    }
    Err(OutputError::NotOurs {
        dir: dir.to_path_buf(),
        files,
    }
    .into())
}

/// Removes one of our directories (a run, a study, a job, a staging directory) unless it holds a
/// file of the user's ([`ensure_only_ours`]).
pub fn remove_ours(dir: &Path) -> Result<(), CliError> {
    ensure_only_ours(dir)?;
    std::fs::remove_dir_all(dir).map_err(|e| io_err(dir, e))
}

/// The file naming what a study's output directory holds (its command and every run's
/// resolved config), written first, so that the same command finds and resumes it.
pub const IDENTITY: &str = "identity.json";

/// What an output directory (`--out DIR`) already holds, found before any work starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutState {
    /// Nothing of value: new, empty, or to be replaced (`--force`).
    Fresh,
    /// A finished output of this very command (same resolved config): nothing to do.
    Done,
    /// An unfinished output of this very command in `DIR.partial/`: it can be resumed.
    Unfinished,
}

/// What makes an output "the same": files (relative to the output directory) and the exact
/// contents this command would write there (e.g. `config.resolved.toml`).
pub type Identity = [(String, String)];

/// Checks `--out DIR` before any work: it must not be the current directory (or hold it), nor a
/// file; an earlier output of another run (another resolved config, or another kind of output)
/// and an unfinished one (a checkpoint) are replaced only with `force`; anything that is not a
/// fuzzymotiv output is never replaced. A refusal is an [`OutputError`] (whose `Display` names
/// the CLI's options). That `--force` replaces something is said to `notes`.
pub fn check_out(
    dir: &Path,
    id: &Identity,
    force: bool,
    notes: &dyn Notes,
) -> Result<OutState, CliError> {
    check_out_as(dir, id, force, &CLI, notes)
}

/// [`check_out`], with the `--force` note naming the option as `spelling` does (a refusal is an
/// [`OutputError`], which the caller words with [`OutputError::render`]).
pub fn check_out_as(
    dir: &Path,
    id: &Identity,
    force: bool,
    spelling: &Spelling,
    notes: &dyn Notes,
) -> Result<OutState, CliError> {
    let (state, replacing) = out_state(dir, id, force)?;
    if replacing {
        notes.note(&format!(
            "note: {}: {} will be replaced",
            spelling.force,
            dir.display()
        ));
    }
    Ok(state)
}

/// The state of `dir` for [`check_out`], and whether `--force` replaces something there.
fn out_state(dir: &Path, id: &Identity, force: bool) -> Result<(OutState, bool), CliError> {
    refuse_current_dir(dir)?;
    refuse_staging_name(dir)?;
    refuse_non_directory(dir)?;
    let staging = StagedDir::staging_path(dir);
    if force && std::fs::symlink_metadata(&staging).is_ok() {
        ensure_only_ours(&staging)?;
    }
    if staging.exists() && !force {
        if matches(&staging, id) {
            return Ok((OutState::Unfinished, false));
        }
        return Err(OutputError::Unfinished {
            dir: dir.to_path_buf(),
            resumable: staging.join("config.resolved.toml").is_file(),
            model: other_model(&staging, id),
            staging,
        }
        .into());
    }
    if !dir.exists() || is_empty_dir(dir) {
        return Ok((OutState::Fresh, false));
    }
    ensure_replaceable(dir)?;
    if matches(dir, id) && dir.join("summary.json").is_file() && !force {
        return Ok((OutState::Done, false));
    }
    if force {
        ensure_only_ours(dir)?;
        return Ok((OutState::Fresh, true));
    }
    Err(OutputError::WouldReplace {
        dir: dir.to_path_buf(),
        model: other_model(dir, id),
    }
    .into())
}

/// The model version that wrote `dir`'s identity files, when it is not this build's (a
/// `config.resolved.toml` or study identity without `(model N)` was written by model 1).
fn other_model(dir: &Path, id: &Identity) -> Option<u32> {
    const WRITTEN: &str = "Resolved configuration written by fuzzymotiv ";
    let (name, _) = id.first()?;
    let path = dir.join(name);
    if !path.is_file() {
        return None;
    }
    let text = read_input(&path, InputKind::record("record file")).ok()?;
    let after = &text[text.find(WRITTEN)? + WRITTEN.len()..];
    let line = after.split(['\n', '\\']).next().unwrap_or("");
    let model = match line.split_once(", model ") {
        Some((_, rest)) => rest.split(' ').next()?.parse().ok()?,
        None => 1,
    };
    (model != fuzzymotiv::MODEL_VERSION).then_some(model)
}

/// Whether every identity file under `dir` has exactly the expected contents (a regular file
/// of another length is not read).
pub fn matches(dir: &Path, id: &Identity) -> bool {
    !id.is_empty()
        && id.iter().all(|(name, want)| {
            let path = dir.join(name);
            std::fs::metadata(&path).is_ok_and(|m| m.is_file() && m.len() == want.len() as u64)
                && std::fs::read_to_string(&path).is_ok_and(|have| have == *want)
        })
}

fn is_empty_dir(dir: &Path) -> bool {
    dir.read_dir().is_ok_and(|mut d| d.next().is_none())
}

/// `--out DIR` naming something that is not a directory (a file, a link, a FIFO, a device):
/// refused, saying which it is ([`what_it_is`]).
pub fn refuse_non_directory(dir: &Path) -> Result<(), CliError> {
    match std::fs::symlink_metadata(dir) {
        Ok(m) if m.file_type().is_symlink() => Err(OutputError::OutIsLink {
            dir: dir.to_path_buf(),
        }
        .into()),
        Ok(m) if !m.is_dir() => Err(OutputError::NotADirectory {
            dir: dir.to_path_buf(),
            what: what_it_is(&m),
        }
        .into()),
        _ => Ok(()),
    }
}

/// `--out NAME.partial`: refused, since `NAME.partial` is where the output `--out NAME` is
/// staged ([`StagedDir`]), which would take it for its own unfinished output and adopt or
/// discard it.
pub fn refuse_staging_name(dir: &Path) -> Result<(), CliError> {
    let name = dir.file_name().map(|n| n.to_string_lossy().into_owned());
    if name.is_some_and(|n| n.ends_with(".partial")) {
        return Err(OutputError::StagingName {
            dir: dir.to_path_buf(),
        }
        .into());
    }
    Ok(())
}

/// `--out .` (or any directory holding the current one) cannot be replaced atomically: refused.
pub fn refuse_current_dir(dir: &Path) -> Result<(), CliError> {
    let (Ok(here), Ok(out)) = (std::env::current_dir(), std::path::absolute(dir)) else {
        return Ok(());
    };
    let out = out.canonicalize().unwrap_or(out);
    let here = here.canonicalize().unwrap_or(here);
    if here.starts_with(&out) {
        return Err(OutputError::CurrentDir {
            dir: dir.to_path_buf(),
        }
        .into());
    }
    Ok(())
}

/// What a set of output files (a replay, an FLL export) already is, checked before writing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FilesState {
    /// Every file already holds exactly these bytes: nothing to write.
    Same,
    /// Write them (none exists, or `--force` replaces regular files that differ).
    Write,
}

/// Checks the files an output would write (`path`, bytes, and the option that named it, or
/// "" when the user named none: the files go to the command's own place, e.g. beside a study):
/// something that is not a regular file (a directory, a device, a FIFO, a symbolic link) is
/// never replaced, not even with `force`; a regular file with other contents is replaced only
/// with `force`; when every file already holds the same bytes there is nothing to do.
pub fn check_files(
    files: &[(PathBuf, Vec<u8>)],
    option: &str,
    force: bool,
) -> Result<FilesState, CliError> {
    // `y.json` and `./y.json` are one file: compared as absolute paths without `.` parts.
    let key = |p: &Path| -> PathBuf {
        let abs = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        (abs.components())
            .filter(|c| *c != std::path::Component::CurDir)
            .collect()
    };
    for (k, (path, _)) in files.iter().enumerate() {
        if files[..k].iter().any(|(p, _)| key(p) == key(path)) {
            return Err(OutputError::SameFileTwice {
                option: option.to_string(),
                path: path.clone(),
            }
            .into());
        }
    }
    let mut same = true;
    for (path, bytes) in files {
        let Ok(meta) = std::fs::symlink_metadata(path) else {
            same = false;
            continue;
        };
        if !meta.is_file() {
            return Err(OutputError::NotAFile {
                option: option.to_string(),
                path: path.clone(),
                what: what_it_is(&meta),
            }
            .into());
        }
        if meta.len() == bytes.len() as u64 && std::fs::read(path).is_ok_and(|have| have == *bytes)
        {
            continue;
        }
        same = false;
        if !force {
            return Err(OutputError::FileDiffers {
                option: option.to_string(),
                path: path.clone(),
            }
            .into());
        }
    }
    Ok(if same {
        FilesState::Same
    } else {
        FilesState::Write
    })
}

/// `--out DIR` of an output of a few files written into a directory (`recognise`,
/// `robustness`, `compare`, `export --to c`: their `names`), checked before any work as
/// [`check_out`] checks an output directory: `-` is refused (standard output takes one file),
/// so are the current directory (or one holding it), a name ending in `.partial` and anything
/// that is not a directory (a file, a device, a link: said which). The files themselves are
/// then checked by [`check_files`] and written by [`write_into`].
pub fn check_files_dir(dir: &Path, option: &str, names: &[&str]) -> Result<(), CliError> {
    if dir.as_os_str() == "-" {
        return Err(OutputError::StdoutForSeveral {
            option: option.to_string(),
            files: names.iter().map(|n| n.to_string()).collect(),
        }
        .into());
    }
    refuse_current_dir(dir)?;
    refuse_staging_name(dir)?;
    refuse_non_directory(dir)
}

/// Writes `files`, all in the directory `dir` (created if missing), through the guard
/// ([`check_files`], then [`write_files`]); `dir` was checked by [`check_files_dir`]. Returns
/// [`FilesState::Same`] when they already held these bytes (nothing written).
pub fn write_into(
    dir: &Path,
    files: &[(PathBuf, Vec<u8>)],
    option: &str,
    force: bool,
) -> Result<FilesState, CliError> {
    let state = check_files(files, option, force)?;
    if state == FilesState::Write {
        std::fs::create_dir_all(dir).map_err(|e| io_err(dir, e))?;
        write_files(files)?;
    }
    Ok(state)
}

/// Writes a checked set of files: every one to a new temporary file first (all of them, so a
/// full disk fails before any file is replaced), then each renamed into place.
pub fn write_files(files: &[(PathBuf, Vec<u8>)]) -> Result<(), CliError> {
    let tmps = files
        .iter()
        .map(|(path, bytes)| temp_with(path, bytes))
        .collect::<Result<Vec<_>, _>>()?;
    for ((path, _), tmp) in files.iter().zip(tmps) {
        tmp.persist(path).map_err(|e| io_err(path, e.error))?;
    }
    Ok(())
}

/// Formats a float for CSV with fixed precision (stable across runs and platforms).
pub fn num(v: f64) -> String {
    format!("{v:.9}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::notes::{NoNotes, NoteList};

    /// A directory holding a finished run whose resolved config is `config`.
    fn finished_run(config: &str) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("config.resolved.toml"), config).unwrap();
        std::fs::write(dir.path().join("summary.json"), "{}").unwrap();
        dir
    }

    fn identity(config: &str) -> Vec<(String, String)> {
        vec![("config.resolved.toml".into(), config.into())]
    }

    #[test]
    fn another_runs_output_is_refused_with_its_path_as_would_replace() {
        let run = finished_run("a = 1\n");
        match check_out(run.path(), &identity("a = 2\n"), false, &NoNotes) {
            Err(CliError::Output(OutputError::WouldReplace { dir, model: None })) => {
                assert_eq!(dir, run.path());
            }
            other => panic!("{other:?}"),
        }
    }

    /// Issue #56 item 2: that `--force` replaces an earlier output is a note handed to the
    /// caller (the CLI prints it, Python warns), in the front's spelling; nothing is printed.
    #[test]
    fn force_replacing_an_output_is_a_note_to_the_caller() {
        let run = finished_run("a = 1\n");
        let notes = NoteList::default();
        let state = check_out_as(run.path(), &identity("a = 2\n"), true, &PYTHON, &notes);
        assert!(matches!(state, Ok(OutState::Fresh)), "{state:?}");
        assert_eq!(
            notes.take(),
            [format!(
                "note: {}: {} will be replaced",
                PYTHON.force,
                run.path().display()
            )]
        );
        let same = check_out_as(run.path(), &identity("a = 1\n"), false, &PYTHON, &notes);
        assert!(same.is_ok() && notes.take().is_empty());
    }

    #[test]
    fn a_file_of_the_users_is_refused_as_not_ours_even_with_force() {
        let run = finished_run("a = 1\n");
        let notes = run.path().join("notes.txt");
        std::fs::write(&notes, "mine").unwrap();
        match check_out(run.path(), &identity("a = 2\n"), true, &NoNotes) {
            Err(CliError::Output(OutputError::NotOurs { dir, files })) => {
                assert_eq!((dir.as_path(), files), (run.path(), vec![notes]));
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_file_with_other_contents_is_refused_as_file_differs() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("page.html");
        std::fs::write(&path, "old").unwrap();
        let files = [(path.clone(), b"new".to_vec())];
        match check_files(&files, "--out", false) {
            Err(CliError::Output(OutputError::FileDiffers { option, path: p })) => {
                assert_eq!((option.as_str(), p), ("--out", path));
            }
            other => panic!("{other:?}"),
        }
    }
}
