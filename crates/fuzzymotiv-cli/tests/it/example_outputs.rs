//! The documents' examples, and the commands' default output directories, write only where git
//! ignores: a new user following the README or the guide leaves no untracked clutter in the repository.

use std::path::Path;
use std::process::Command;

use crate::common;

use common::repo;

/// The documents whose commands a user copies.
fn documents() -> Vec<String> {
    let mut files: Vec<String> = [
        "README.md",
        "EXPERIMENTS.md",
        "bench/README.md",
        "bench/HISTORY.md",
        "bench/enki/README.md",
    ]
    .map(String::from)
    .to_vec();
    for dir in [
        "docs",
        "docs/guide",
        "configs",
        "examples/slurm",
        "examples/htcondor",
        "examples/python",
    ] {
        for e in std::fs::read_dir(repo().join(dir)).unwrap() {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            if [".md", ".toml", ".sbatch", ".sub", ".py"]
                .iter()
                .any(|ext| name.ends_with(ext))
            {
                files.push(format!("{dir}/{name}"));
            }
        }
    }
    files
}

/// The first string literal of `text` ("…" or '…').
fn first_literal(text: &str) -> Option<&str> {
    let start = text.find(['"', '\''])?;
    let quote = text[start..].chars().next()?;
    let rest = &text[start + 1..];
    Some(&rest[..rest.find(quote)?])
}

/// The output paths a line writes to: the value after `--out`, `--export-fll`, `--dir`; the
/// string after Python's `out=` and `folder=`; the path (the first string) of `save_gif(…)`,
/// `export_fll(…)`.
fn outputs(line: &str) -> Vec<String> {
    let mut found = Vec::new();
    let words: Vec<&str> = line.split_whitespace().collect();
    for pair in words.windows(2) {
        if ["--out", "--export-fll", "--dir"].contains(&pair[0]) {
            found.push(
                pair[1]
                    .trim_matches(['"', '\'', ')', '`', ';', ':', ','])
                    .to_string(),
            );
        }
    }
    for key in ["out=", "folder="] {
        for (at, _) in line.match_indices(key) {
            let after = &line[at + key.len()..];
            if after.starts_with(['"', '\'']) {
                found.extend(first_literal(after).map(String::from));
            }
        }
    }
    for call in ["save_gif(", "export_fll("] {
        if let Some(at) = line.find(call) {
            let args = &line[at + call.len()..];
            let args = &args[..args.find(')').unwrap_or(args.len())];
            found.extend(first_literal(args).map(String::from));
        }
    }
    found
}

/// Whether `path` is a placeholder (`DIR`, `RUN_DIR/x`, `$OUT`) or outside the repository
/// (absolute, stdout) rather than a path the example writes in it.
fn not_in_the_repository(path: &str) -> bool {
    let placeholder =
        |part: &str| part.len() >= 2 && part.chars().all(|c| c.is_ascii_uppercase() || c == '_');
    path.is_empty()
        || path == "-"
        || path.starts_with(['/', '$', '-', '~', '<', '{'])
        || path.split(['/', '.', '-']).any(placeholder)
}

/// `path` relative to the repository: the README builds the wheel from `python/`, so its
/// `../X` is the repository's `X`.
fn in_the_repository(path: &str) -> &str {
    path.strip_prefix("../").unwrap_or(path)
}

/// Whether git ignores `path` of the repository as a file or as a directory (by its .gitignore).
fn ignored(path: &str) -> bool {
    ignored_as_written(path) || ignored_as_written(&format!("{path}/x"))
}

fn ignored_as_written(path: &str) -> bool {
    let o = Command::new("git")
        .args(["check-ignore", "--no-index", "-q", path])
        .current_dir(repo())
        .output()
        .expect("git runs");
    assert!(
        matches!(o.status.code(), Some(0 | 1)),
        "git check-ignore {path}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o.status.success()
}

#[test]
fn documented_examples_write_only_where_git_ignores() {
    let mut checked = 0;
    let mut clutter = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(repo().join(&doc)).unwrap();
        for (n, line) in text.lines().enumerate() {
            for path in outputs(line) {
                if not_in_the_repository(&path) {
                    continue;
                }
                checked += 1;
                if !ignored(in_the_repository(&path)) {
                    clutter.push(format!("{doc}:{}: {path}", n + 1));
                }
            }
        }
    }
    assert!(checked >= 15, "only {checked} example outputs found");
    assert!(
        clutter.is_empty(),
        "examples write where git does not ignore:\n{}",
        clutter.join("\n")
    );
}

#[test]
fn default_outputs_are_ignored_by_git() {
    // The commands' default directories, and the default file of examples/python/small_study.py.
    for default in [
        "results",
        "results-quick",
        "results-orientation",
        "results-ablation-quick",
        "results-search-strength",
        "lab/runs",
        "out/anything",
        "small_study.png",
    ] {
        assert!(ignored(&format!("{default}/x")), "{default} is not ignored");
    }
    assert!(!ignored("README.md") && Path::new(&repo().join("README.md")).is_file());
}

#[test]
fn example_outputs_are_found_in_every_form() {
    let line = r#"fm.sweep(plan, out="out/s", executor=x); fm.save_gif(v, "a.gif", fps=2)"#;
    assert_eq!(outputs(line), ["out/s", "a.gif"]);
    let line = "fuzzymotiv fuzzy --export-fll hc.fll && fuzzymotiv lab --dir lab2 --out x)";
    assert_eq!(outputs(line), ["hc.fll", "lab2", "x"]);
    assert_eq!(
        outputs(r#"text = fm.export_fll([.8, .1, 0, .1], "hc.fll")"#),
        ["hc.fll"]
    );
    assert!(
        !ignored("sweeps/small"),
        "a path outside .gitignore is found"
    );
}
