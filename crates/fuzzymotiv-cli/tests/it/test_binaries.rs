//! One integration-test binary per crate. Each test binary links the whole workspace, so a
//! binary per file made a fresh clone's `cargo test --workspace` compile and link the workspace
//! dozens of times (docs/guide/testing.md has the figures). A crate's integration tests are one
//! `tests/*.rs` file or the modules of one `tests/NAME/main.rs`; every `.rs` file (or folder with
//! a `mod.rs`) beside such a `main.rs` is one of its modules, or its tests would never compile
//! or run.

use std::fs;
use std::path::{Path, PathBuf};

use crate::common::repo;

/// The sorted entries of `dir`.
fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut all: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    all.sort();
    all
}

/// The test targets Cargo finds in `tests` (`tests/*.rs` and `tests/*/main.rs`), as paths
/// relative to `tests`.
fn test_targets(tests: &Path) -> Vec<String> {
    let name = |p: &Path| p.strip_prefix(tests).unwrap().display().to_string();
    let mut targets = Vec::new();
    for p in entries(tests) {
        if p.is_file() && p.extension().is_some_and(|e| e == "rs") {
            targets.push(name(&p));
        } else if p.join("main.rs").is_file() {
            targets.push(name(&p.join("main.rs")));
        }
    }
    targets
}

/// The `.rs` files beside `main` (and folders with a `mod.rs`) that `main` does not declare
/// as `mod NAME;`.
fn undeclared_modules(main: &Path) -> Vec<String> {
    let text = fs::read_to_string(main).unwrap();
    let declared = |m: &str| text.lines().any(|l| l.trim() == format!("mod {m};"));
    let dir = main.parent().unwrap();
    let mut missing = Vec::new();
    for p in entries(dir) {
        let module = match (p.is_file(), p.extension().is_some_and(|e| e == "rs")) {
            (true, true) if p != main => p.file_stem().unwrap().to_string_lossy().into_owned(),
            (false, _) if p.join("mod.rs").is_file() => {
                p.file_name().unwrap().to_string_lossy().into_owned()
            }
            _ => continue,
        };
        if !declared(&module) {
            missing.push(p.strip_prefix(dir).unwrap().display().to_string());
        }
    }
    missing
}

/// The crates' folders (`crates/*`).
fn crates() -> Vec<PathBuf> {
    entries(&repo().join("crates"))
        .into_iter()
        .filter(|k| k.join("Cargo.toml").is_file())
        .collect()
}

#[test]
fn each_crate_has_one_integration_test_binary() {
    let mut checked = 0;
    for krate in crates() {
        let manifest = fs::read_to_string(krate.join("Cargo.toml")).unwrap();
        assert!(
            !manifest.contains("[[test]]") && !manifest.contains("autotests"),
            "{}: a [[test]] target or autotests; test binaries are found, one per crate",
            krate.join("Cargo.toml").display()
        );
        let tests = krate.join("tests");
        if !tests.is_dir() {
            continue;
        }
        let targets = test_targets(&tests);
        assert!(
            targets.len() <= 1,
            "{} has {} integration-test binaries ({targets:?}): make each file a module of one \
             tests/it/main.rs",
            tests.display(),
            targets.len()
        );
        checked += targets.len();
    }
    assert!(checked >= 4, "only {checked} crates with tests found");
}

#[test]
fn every_test_file_is_a_module_of_its_binary() {
    let mut mains = 0;
    for tests in crates().iter().map(|k| k.join("tests")) {
        if !tests.is_dir() {
            continue;
        }
        for target in test_targets(&tests).iter().filter(|t| t.contains('/')) {
            let main = tests.join(target);
            let missing = undeclared_modules(&main);
            assert!(
                missing.is_empty(),
                "{} does not declare {missing:?} (`mod NAME;`): their tests never run",
                main.display()
            );
            mains += 1;
        }
    }
    assert!(mains >= 2, "only {mains} tests/*/main.rs found");
}

/// The two checks above on a made-up crate: a second binary and an undeclared file are found.
#[test]
fn a_second_test_binary_or_an_undeclared_file_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let tests = dir.path().join("tests");
    fs::create_dir_all(tests.join("it/common")).unwrap();
    fs::write(tests.join("it/main.rs"), "mod common;\nmod a;\n").unwrap();
    fs::write(tests.join("it/common/mod.rs"), "").unwrap();
    for file in ["it/a.rs", "it/b.rs", "extra.rs"] {
        fs::write(tests.join(file), "").unwrap();
    }
    assert_eq!(test_targets(&tests), ["extra.rs", "it/main.rs"]);
    assert_eq!(undeclared_modules(&tests.join("it/main.rs")), ["b.rs"]);
    fs::write(tests.join("it/main.rs"), "mod a;\nmod b;\n").unwrap();
    assert_eq!(undeclared_modules(&tests.join("it/main.rs")), ["common"]);
}
