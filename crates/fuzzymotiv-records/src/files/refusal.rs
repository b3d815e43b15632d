//! The output guard's refusals as facts ([`OutputError`]), worded by each front with its own
//! names for the output options ([`Spelling`]): the CLI's `--out` and `--force`, Python's `out`
//! and `force=True`, the lab's save name.

use std::path::{Path, PathBuf};

/// How a front names the output options in messages.
#[derive(Debug, Clone, Copy)]
pub struct Spelling {
    /// The output directory option, e.g. `--out`.
    pub out: &'static str,
    /// The replace option, e.g. `--force`.
    pub force: &'static str,
}

/// The command line's `--out` and `--force`.
pub const CLI: Spelling = Spelling {
    out: "--out",
    force: "--force",
};

/// Python's `out` and `force=True` (`fm.run(..., out=DIR, force=True)`).
pub const PYTHON: Spelling = Spelling {
    out: "out",
    force: "force=True",
};

/// Why the output guard refuses an output directory or file, with the paths and facts it
/// found. [`Display`](std::fmt::Display) words it as the CLI does; [`OutputError::render`] as any
/// front does.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.render(&CLI))]
pub enum OutputError {
    /// The output directory is the current directory, or holds it.
    CurrentDir {
        /// The output directory.
        dir: PathBuf,
    },
    /// The output directory's name ends in `.partial`, the name of another output's staging.
    StagingName {
        /// The output directory.
        dir: PathBuf,
    },
    /// The output directory is a symbolic link (never written through).
    OutIsLink {
        /// The output directory.
        dir: PathBuf,
    },
    /// The output directory names something that is not a directory.
    NotADirectory {
        /// The output directory.
        dir: PathBuf,
        /// What it is instead ([`what_it_is`](crate::files::bounded::what_it_is)).
        what: &'static str,
    },
    /// A directory that is not a fuzzymotiv output: never replaced.
    NotAnOutput {
        /// The directory.
        dir: PathBuf,
    },
    /// A directory to be replaced is a symbolic link: never replaced.
    LinkNeverReplaced {
        /// The directory.
        dir: PathBuf,
    },
    /// A directory to be replaced holds files fuzzymotiv did not write: never deleted.
    NotOurs {
        /// The directory.
        dir: PathBuf,
        /// The files of the user's found in it.
        files: Vec<PathBuf>,
    },
    /// The output directory's staging directory holds an unfinished output of another run.
    Unfinished {
        /// The output directory.
        dir: PathBuf,
        /// Its staging directory (`DIR.partial`).
        staging: PathBuf,
        /// Whether it is a run's (`fuzzymotiv run --resume DIR` continues it).
        resumable: bool,
        /// The model of fuzzymotiv that wrote it, when it is not this build's.
        model: Option<u32>,
    },
    /// The output directory holds the results of another run: kept unless forced.
    WouldReplace {
        /// The output directory.
        dir: PathBuf,
        /// The model of fuzzymotiv that wrote them, when it is not this build's.
        model: Option<u32>,
    },
    /// A sweep directory holds a sweep of another plan: kept unless forced.
    OtherPlan {
        /// The sweep directory.
        dir: PathBuf,
        /// How the plans differ.
        why: String,
    },
    /// A sweep directory holds another fuzzymotiv output (a run or a study): kept unless forced.
    NotASweep {
        /// The sweep directory.
        dir: PathBuf,
    },
    /// Two of the files an output would write are the same file.
    SameFileTwice {
        /// The option naming the files (e.g. `--out`, `path`).
        option: String,
        /// The file.
        path: PathBuf,
    },
    /// A file to write is not a regular file (a directory, a link, a device): never replaced.
    NotAFile {
        /// The option naming it, or "" when the file goes to the command's own place.
        option: String,
        /// The file.
        path: PathBuf,
        /// What it is ([`what_it_is`](crate::files::bounded::what_it_is)).
        what: &'static str,
    },
    /// `-` (standard output, one file) named as the directory of an output of several files.
    StdoutForSeveral {
        /// The option naming the directory (e.g. `--out`).
        option: String,
        /// The names of the files the output writes into its directory.
        files: Vec<String>,
    },
    /// A file to write exists with other contents: kept unless forced.
    FileDiffers {
        /// The option naming it, or "" when the file goes to the command's own place.
        option: String,
        /// The file.
        path: PathBuf,
    },
}

impl OutputError {
    /// The refusal in the words of a front whose options are spelled as `s` spells them.
    pub fn render(&self, s: &Spelling) -> String {
        let (out, force) = (s.out, s.force);
        match self {
            Self::CurrentDir { dir } => format!(
                "{out} {}: is the current directory (or holds it); every output goes into a \
                 directory of its own, which a run or study writes beside and then renames into \
                 place, so give a new directory, e.g. {out} results",
                dir.display()
            ),
            Self::StagingName { dir } => format!(
                "{out} {}: a name ending in .partial is where another output is written until it \
                 is finished; choose a name without .partial",
                dir.display()
            ),
            Self::OutIsLink { dir } => format!(
                "{out} {}: is a symbolic link, and an output directory is never written through a \
                 link; choose another {out} (e.g. the directory the link points to)",
                dir.display()
            ),
            Self::NotADirectory { dir, what } => format!(
                "{out} {}: is {what}, not a directory; choose another {out}",
                dir.display()
            ),
            Self::NotAnOutput { dir } => format!(
                "{}: exists and is not a fuzzymotiv output directory, so it will not be replaced \
                 (not even with {force}); choose another {out} (or remove it yourself)",
                dir.display()
            ),
            Self::LinkNeverReplaced { dir } => format!(
                "{}: is a symbolic link, which is never replaced (not even with {force}); choose \
                 another {out}",
                dir.display()
            ),
            Self::NotOurs { dir, files } => format!(
                "{}: holds {} file(s) that fuzzymotiv did not write ({}), which are never \
                 deleted, not even with {force}; move them elsewhere, or choose another {out}",
                dir.display(),
                files.len(),
                first_three(files)
            ),
            Self::Unfinished { .. } => self.render_unfinished(s),
            Self::WouldReplace { dir, model } => would_replace(s, dir, *model),
            Self::OtherPlan { dir, why } => format!(
                "{out} {}: holds a sweep of another plan ({why}); its results are kept. Choose \
                 another {out}, pass {force} to replace that sweep, or run the sweep file that \
                 made it ({})",
                dir.display(),
                dir.join("sweep.toml").display()
            ),
            Self::NotASweep { dir } => format!(
                "{out} {}: holds another fuzzymotiv output (a run or a study), not a sweep; it is \
                 kept. Choose another {out}, or pass {force} to replace it",
                dir.display()
            ),
            Self::SameFileTwice { option, path } => format!(
                "{option}: two of the files to write would both be {}; choose another {option} \
                 (e.g. a name ending in .html for a page)",
                path.display()
            ),
            Self::NotAFile { option, path, what } => not_a_file(s, option, path, what),
            Self::StdoutForSeveral { option, files } => format!(
                "{option} -: `-` is standard output, which takes one file, and this output is \
                 {} files ({}) written into a directory; give a directory, e.g. {option} results",
                files.len(),
                files.join(", ")
            ),
            Self::FileDiffers { option, path } => file_differs(s, option, path),
        }
    }

    /// [`OutputError::Unfinished`] in the words of `s`.
    fn render_unfinished(&self, s: &Spelling) -> String {
        let Self::Unfinished {
            dir,
            staging,
            resumable,
            model,
        } = self
        else {
            return String::new();
        };
        let how = if *resumable {
            format!(
                "continue it with `fuzzymotiv run --resume {}`, or ",
                dir.display()
            )
        } else {
            "continue it with the command that started it, or ".to_string()
        };
        let what = match model {
            Some(m) => format!(
                "an unfinished output of model {m} of fuzzymotiv (this build is model {}, whose \
                 results differ)",
                fuzzymotiv::MODEL_VERSION
            ),
            None => "an unfinished output of another run or command".to_string(),
        };
        format!(
            "{} {}: {} holds {what} (a checkpoint); {how}pass {} to discard it and start this one",
            s.out,
            dir.display(),
            staging.display(),
            s.force
        )
    }
}

/// A file as a message names it: with its option, or alone when the user named no option (the
/// command's own place for the file), never an option the user did not pass.
fn named(option: &str, path: &Path) -> String {
    match option {
        "" => path.display().to_string(),
        _ => format!("{option} {}", path.display()),
    }
}

/// The first three of `files`, then `…` when there are more.
fn first_three(files: &[PathBuf]) -> String {
    let shown: Vec<String> = files
        .iter()
        .take(3)
        .map(|p| p.display().to_string())
        .collect();
    format!(
        "{}{}",
        shown.join(", "),
        if files.len() > 3 { ", …" } else { "" }
    )
}

/// The refusal of an output directory holding other results.
fn would_replace(s: &Spelling, dir: &Path, model: Option<u32>) -> String {
    let (out, force) = (s.out, s.force);
    format!(
        "{out} {}: holds {}; they are kept. Choose another {out}, or pass {force} to \
         replace them",
        dir.display(),
        match model {
            Some(m) => format!(
                "the results of model {m} of fuzzymotiv (this build is model {}, whose \
                 results differ)",
                fuzzymotiv::MODEL_VERSION
            ),
            None => "the results of a different run (another config, seed, size or \
                     command)"
                .into(),
        }
    )
}

/// The refusal of a file that is not a regular file.
fn not_a_file(s: &Spelling, option: &str, path: &Path, what: &str) -> String {
    let force = s.force;
    format!(
        "{}: is {what}, which is never replaced (not even with {force}); {}",
        named(option, path),
        match option {
            "" => "move it away",
            _ => "give the path of a new or regular file",
        }
    )
}

/// The refusal of a file that exists with other contents.
fn file_differs(s: &Spelling, option: &str, path: &Path) -> String {
    let force = s.force;
    format!(
        "{}: the file exists with other contents and is kept; pass {force} to replace \
         it{}",
        named(option, path),
        match option {
            "" => String::new(),
            _ => format!(", or choose another {option}"),
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn would_replace() -> OutputError {
        OutputError::WouldReplace {
            dir: PathBuf::from("runs/a"),
            model: None,
        }
    }

    #[test]
    fn the_cli_words_a_refusal_with_its_options() {
        assert_eq!(
            would_replace().to_string(),
            "--out runs/a: holds the results of a different run (another config, seed, size or \
             command); they are kept. Choose another --out, or pass --force to replace them"
        );
    }

    #[test]
    fn python_words_a_refusal_with_out_and_force_true() {
        assert_eq!(
            would_replace().render(&PYTHON),
            "out runs/a: holds the results of a different run (another config, seed, size or \
             command); they are kept. Choose another out, or pass force=True to replace them"
        );
        let differs = OutputError::FileDiffers {
            option: "path".into(),
            path: PathBuf::from("f.fll"),
        };
        assert_eq!(
            differs.render(&PYTHON),
            "path f.fll: the file exists with other contents and is kept; pass force=True to \
             replace it, or choose another path"
        );
    }

    #[test]
    fn a_file_in_the_commands_own_place_names_no_option() {
        let e = OutputError::NotAFile {
            option: String::new(),
            path: PathBuf::from("study/claims.md"),
            what: "a directory",
        };
        assert_eq!(
            e.to_string(),
            "study/claims.md: is a directory, which is never replaced (not even with --force); \
             move it away"
        );
    }

    #[test]
    fn files_of_the_users_are_listed_three_at_most() {
        let files = (1..=4)
            .map(|k| PathBuf::from(format!("d/{k}.txt")))
            .collect();
        let e = OutputError::NotOurs {
            dir: PathBuf::from("d"),
            files,
        };
        assert_eq!(
            e.render(&PYTHON),
            "d: holds 4 file(s) that fuzzymotiv did not write (d/1.txt, d/2.txt, d/3.txt, …), \
             which are never deleted, not even with force=True; move them elsewhere, or choose \
             another out"
        );
    }
}
