//! What `fuzzymotiv run` is asked to do ([`run_target`]): a fresh run of a config, the
//! unfinished run of the same config finished, a killed run resumed from its staging
//! directory (`--resume DIR`), a finished run continued to more generations in a new
//! directory (`--continue DIR --generations N --out NEW`), or nothing, when the run is there.
//! The command line parses the arguments, says the notes and runs the target
//! ([`crate::pipeline::run_dir::execute`]).

use std::path::{Path, PathBuf};

use crate::files::error::CliError;
use crate::files::guard::{OutState, StagedDir, check_out};
use crate::files::inputs::{Loaded, load_config, rooms_unchanged, run_identity};
use crate::files::notes::Notes;
use crate::pipeline::continuation::{continued_config, finished_config, stage_continued};

/// What `run`'s arguments ask for.
#[derive(Debug, Default)]
pub struct RunRequest {
    /// The config file (a fresh run, or the unfinished one of the same config in `out`).
    pub config: Option<PathBuf>,
    /// A killed run's output directory, to resume.
    pub resume: Option<PathBuf>,
    /// A finished run's directory, to continue (with `generations` and `out`).
    pub continue_from: Option<PathBuf>,
    /// With `continue_from`: the total number of generations.
    pub generations: Option<usize>,
    /// The output directory [default: `runs/NAME`].
    pub out: Option<PathBuf>,
    /// Config overrides, `KEY=VALUE`.
    pub sets: Vec<String>,
    /// The base seed, over the config's.
    pub seed: Option<u64>,
    /// Replace another run's results in `out`.
    pub force: bool,
}

/// What to do.
pub enum RunTarget {
    /// Nothing: the run in this directory is already there (the note says so).
    Done {
        /// The finished run's directory.
        dir: PathBuf,
        /// Why there is nothing to do.
        note: String,
    },
    /// Run (or resume) `loaded` into `out`.
    Run {
        /// The resolved config.
        loaded: Box<Loaded>,
        /// The output directory.
        out: PathBuf,
        /// Whether its checkpoint is resumed.
        resume: bool,
    },
}

/// The target of `req`: `--continue`, else `--resume`, else the config; refused (exit 2)
/// with a message naming the option when they do not go together. The config's notes (e.g.
/// motivations normalised) and that `force` replaces an output are said to `notes`.
pub fn run_target(req: &RunRequest, notes: &dyn Notes) -> Result<RunTarget, CliError> {
    if req.generations.is_some() && req.continue_from.is_none() {
        return Err(CliError::input(
            "--generations N goes with --continue DIR (the total to continue it to); \
             to run a config for N generations, use --set ga.generations=N",
        ));
    }
    match (&req.resume, &req.config) {
        _ if req.continue_from.is_some() => continue_target(req, notes),
        (Some(dir), _) => resume_target(dir, notes),
        (None, Some(config)) => config_target(config, req, notes),
        (None, None) => Err(CliError::input("give a CONFIG file or --resume DIR")),
    }
}

/// A loaded config's notes, each after `note: `, to `notes`.
fn config_notes(loaded: &Loaded, notes: &dyn Notes) {
    for line in &loaded.notes {
        notes.note(&format!("note: {line}"));
    }
}

/// `--resume DIR`: the interrupted run in `DIR.partial/`.
fn resume_target(dir: &Path, notes: &dyn Notes) -> Result<RunTarget, CliError> {
    let staging = StagedDir::staging_path(dir);
    let cfg = staging.join("config.resolved.toml");
    if !cfg.is_file() {
        if dir.join("summary.json").is_file() {
            return Ok(RunTarget::Done {
                dir: dir.to_path_buf(),
                note: format!("{} is already complete; nothing to resume", dir.display()),
            });
        }
        return Err(CliError::input(format!(
            "--resume {}: no interrupted run there ({} not found); start it with `fuzzymotiv run CONFIG --out {}`",
            dir.display(),
            cfg.display(),
            dir.display()
        )));
    }
    let loaded = load_config(Some(&cfg), &[], None)?;
    config_notes(&loaded, notes);
    let remedy = "resuming would evolve the rest of the run in another room. Restore the file, \
                  or start the run over with `fuzzymotiv run CONFIG --out DIR --force`";
    rooms_unchanged(&cfg, &loaded, remedy)?;
    Ok(RunTarget::Run {
        loaded: Box::new(loaded),
        out: dir.to_path_buf(),
        resume: true,
    })
}

/// `CONFIG [--out DIR]`: a fresh run, or the unfinished one of the same config in `DIR`.
fn config_target(
    config: &Path,
    req: &RunRequest,
    notes: &dyn Notes,
) -> Result<RunTarget, CliError> {
    let loaded = load_config(Some(config), &req.sets, req.seed)?;
    config_notes(&loaded, notes);
    let out = (req.out.clone()).unwrap_or_else(|| Path::new("runs").join(&loaded.raw.name));
    let resume = match check_out(&out, &run_identity(&loaded.raw), req.force, notes)? {
        OutState::Done => {
            let note = format!(
                "{} already holds this run, finished (same resolved config); nothing to do. --force runs it again",
                out.display()
            );
            return Ok(RunTarget::Done { dir: out, note });
        }
        OutState::Unfinished => true,
        OutState::Fresh => false,
    };
    Ok(RunTarget::Run {
        loaded: Box::new(loaded),
        out,
        resume,
    })
}

/// `--continue DIR --generations N --out NEW`: the finished run in `DIR` continued to N
/// generations in `NEW` (staged from `DIR`'s final population; `DIR` is never written).
fn continue_target(req: &RunRequest, notes: &dyn Notes) -> Result<RunTarget, CliError> {
    let (Some(dir), Some(n), Some(out)) = (&req.continue_from, req.generations, &req.out) else {
        return Err(CliError::input(
            "--continue DIR needs --generations N (the total) and --out NEW",
        ));
    };
    let old = finished_config(dir)?;
    config_notes(&old, notes);
    let new = continued_config(dir, &old, n)?;
    if same_place(dir, out) {
        return Err(CliError::input(format!(
            "--out {}: is the run being continued; --continue never changes it: choose a new --out",
            out.display()
        )));
    }
    let resume = match check_out(out, &run_identity(&new.raw), req.force, notes)? {
        OutState::Done => {
            let note = format!(
                "{} already holds this run, finished ({n} generations); nothing to do. --force runs it again",
                out.display()
            );
            return Ok(RunTarget::Done {
                dir: out.clone(),
                note,
            });
        }
        OutState::Unfinished => true,
        OutState::Fresh => {
            stage_continued(dir, &old, &new, out)?;
            true
        }
    };
    Ok(RunTarget::Run {
        loaded: Box::new(new),
        out: out.clone(),
        resume,
    })
}

/// Whether two paths name the same directory (or `b` lies inside `a`).
fn same_place(a: &Path, b: &Path) -> bool {
    let canon = |p: &Path| {
        let parent = p.parent().filter(|q| !q.as_os_str().is_empty());
        let base = parent.map_or_else(|| Path::new(".").canonicalize(), |q| q.canonicalize());
        base.ok().map(|d| d.join(p.file_name().unwrap_or_default()))
    };
    match (a.canonicalize().ok(), canon(b)) {
        (Some(a), Some(b)) => b.starts_with(&a),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::notes::NoNotes;

    /// `--generations` without `--continue` is refused, nothing given asks for a config, and
    /// `--resume` of a directory with no run there says how to start it.
    #[test]
    fn a_run_request_that_does_not_go_together_is_refused_naming_its_options() {
        let e = |req: RunRequest| {
            run_target(&req, &NoNotes)
                .err()
                .expect("refused")
                .to_string()
        };
        let gens = e(RunRequest {
            config: Some("c.toml".into()),
            generations: Some(5),
            ..RunRequest::default()
        });
        assert!(
            gens.starts_with("--generations N goes with --continue DIR"),
            "{gens}"
        );
        assert_eq!(
            e(RunRequest::default()),
            "give a CONFIG file or --resume DIR"
        );
        let dir = std::env::temp_dir().join(format!("fm-no-run-{}", std::process::id()));
        let resume = e(RunRequest {
            resume: Some(dir.clone()),
            ..RunRequest::default()
        });
        assert!(resume.contains("no interrupted run there"), "{resume}");
        let cont = e(RunRequest {
            continue_from: Some(dir),
            ..RunRequest::default()
        });
        assert!(
            cont.contains("--continue DIR needs --generations N"),
            "{cont}"
        );
    }

    /// A directory and one inside it are the same place; a sibling is not.
    #[test]
    fn a_directory_inside_the_continued_run_is_its_place() {
        let dir = std::env::temp_dir();
        assert!(same_place(&dir, &dir.join("sub")));
        assert!(!same_place(
            &dir.join("a-run-that-is-not-there"),
            &dir.join("b")
        ));
    }
}
