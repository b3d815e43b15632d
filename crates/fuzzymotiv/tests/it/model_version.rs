//! The model version moves with the goldens: results never change without a word.
//!
//! `tests/golden/model-versions.txt` records, per model version, a digest of every golden file
//! of the workspace (this crate's `tests/golden/` and the CLI's). A commit that regenerates the
//! goldens (results changed on purpose) must bump [`fuzzymotiv::MODEL_VERSION`] and add the new
//! digest as a new line; a change of the goldens under the same model version fails here.

use std::path::{Path, PathBuf};

/// The file of model versions and digests, beside this crate's goldens.
const VERSIONS: &str = "tests/golden/model-versions.txt";

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every golden folder of the workspace.
fn golden_dirs() -> [PathBuf; 2] {
    [
        crate_dir().join("tests/golden"),
        crate_dir().join("../fuzzymotiv-cli/tests/golden"),
    ]
}

/// The files under `dir`, recursively, sorted, as (path relative to `root`, path).
fn files(root: &Path, dir: &Path, out: &mut Vec<(String, PathBuf)>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            files(root, &path, out);
        } else {
            let rel = path.strip_prefix(root).unwrap().to_string_lossy();
            out.push((rel.replace('\\', "/"), path));
        }
    }
}

/// 64-bit FNV-1a, folded over `bytes` from `h`.
fn fnv1a(h: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(h, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The digest of the goldens: every file's name and contents (READMEs and the versions file
/// left out; the program version replaced by `VERSION`, so a release that changes no result
/// needs no new model). The study's `claims.csv` is left out too: it is the analysis of the
/// tables beside it (which are in), recomputable from a study's records by `fuzzymotiv
/// claims`, not the model; its golden still pins it (`default_study_reproduces_its_golden`).
fn goldens_digest() -> String {
    let mut all = Vec::new();
    for dir in golden_dirs() {
        let root = dir.parent().unwrap().parent().unwrap().to_path_buf();
        files(&root, &dir, &mut all);
    }
    all.retain(|(rel, _)| {
        !rel.ends_with("README.md")
            && !rel.ends_with("model-versions.txt")
            && !rel.ends_with("study/claims.csv")
    });
    all.sort();
    let mut h = 0xcbf2_9ce4_8422_2325;
    for (rel, path) in &all {
        let text = std::fs::read(path).unwrap();
        let text = String::from_utf8_lossy(&text).replace(fuzzymotiv::VERSION, "VERSION");
        h = fnv1a(h, rel.as_bytes());
        h = fnv1a(h, &[0]);
        h = fnv1a(h, text.as_bytes());
        h = fnv1a(h, &[0]);
    }
    format!("{h:016x}")
}

/// The (model, digest) lines of the versions file, in order.
fn recorded() -> Vec<(u32, String)> {
    let text = std::fs::read_to_string(crate_dir().join(VERSIONS)).unwrap();
    (text.lines())
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let mut words = l.split_whitespace();
            let model = words.next().unwrap().parse().unwrap();
            (model, words.next().unwrap_or("").to_string())
        })
        .collect()
}

/// The goldens' digest is the one recorded for this build's model version: regenerating the
/// goldens without bumping [`fuzzymotiv::MODEL_VERSION`] fails.
#[test]
fn goldens_change_only_with_the_model_version() {
    let digest = goldens_digest();
    let lines = recorded();
    let model = fuzzymotiv::MODEL_VERSION;
    let Some((_, want)) = lines.iter().find(|(m, _)| *m == model) else {
        panic!(
            "{VERSIONS} has no line for model {model}: add `{model} {digest}` (and say in the \
             commit why results changed)"
        );
    };
    assert_eq!(
        *want,
        digest,
        "the goldens changed, but fuzzymotiv::MODEL_VERSION is still {model}. If results changed \
         on purpose, bump MODEL_VERSION to {} and add `{} {digest}` to {VERSIONS} in the same \
         commit; if they changed by accident, that is a bug",
        model + 1,
        model + 1
    );
}

/// Model versions are recorded once each, in order, and the last one is this build's: a new
/// model adds a line, never rewrites an old one's.
#[test]
fn model_versions_are_recorded_in_order() {
    let models: Vec<u32> = recorded().iter().map(|(m, _)| *m).collect();
    let expected: Vec<u32> = (1..=fuzzymotiv::MODEL_VERSION).collect();
    assert_eq!(
        models, expected,
        "{VERSIONS}: one line per model, 1 to this build's"
    );
}
