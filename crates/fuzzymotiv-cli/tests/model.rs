//! The model switches through the binary: the first release's model still gives its results
//! byte for byte, and the default (the paper's robot) is what a plain run uses.

mod common;
use common::*;

/// `motion = "wheels"`, `end_at_home = false`, `homing = "distance"` with the first release's
/// rooms (rooms/first-release/) reproduce the first release: generations, best genome and
/// recognition files are byte-identical to the golden saved from it (tests/golden/first-release).
#[test]
fn first_release_model_reproduces_its_golden() {
    let golden = repo().join("crates/fuzzymotiv-cli/tests/golden/first-release");
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("run");
    ok(&[
        "run",
        golden.join("config.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--threads",
        "2",
        "--set",
        "robot.motion=\"wheels\"",
        "--set",
        "trial.end_at_home=false",
        "--set",
        "fitness.homing=\"distance\"",
    ]);
    for file in ["generations.csv", "best_genome.json", "recognition.csv"] {
        let want = std::fs::read_to_string(golden.join(file)).unwrap();
        let got = std::fs::read_to_string(dir.join(file)).unwrap();
        assert!(
            want == got,
            "{file} differs from the first release's golden"
        );
    }
}

/// The default model differs from the first release's on the same rooms (so the switches are
/// real), and the resolved config records the new keys with their defaults.
#[test]
fn default_model_is_the_papers_robot() {
    let golden = repo().join("crates/fuzzymotiv-cli/tests/golden/first-release");
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join("run");
    ok(&[
        "run",
        golden.join("config.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    let resolved = std::fs::read_to_string(dir.join("config.resolved.toml")).unwrap();
    for key in [
        "motion = \"actions\"",
        "end_at_home = true",
        "homing = \"escape\"",
    ] {
        assert!(resolved.contains(key), "{key} missing in:\n{resolved}");
    }
    let want = std::fs::read_to_string(golden.join("generations.csv")).unwrap();
    let got = std::fs::read_to_string(dir.join("generations.csv")).unwrap();
    assert_ne!(want, got);
}

/// Bad values of the new keys exit 2 and name the field.
#[test]
fn bad_model_keys_name_the_field() {
    let cfg = repo().join("configs/tiny.toml");
    for (set, field) in [
        ("robot.motion=\"hover\"", "robot.motion"),
        ("trial.end_at_home=3", "trial.end_at_home"),
        ("fitness.homing=\"near\"", "fitness.homing"),
    ] {
        let o = run(&[
            "run",
            cfg.to_str().unwrap(),
            "--set",
            set,
            "--out",
            "/nonexistent/x",
        ]);
        assert_eq!(o.status.code(), Some(2), "{set}: {}", stderr(&o));
        assert!(stderr(&o).contains(field), "{set}: {}", stderr(&o));
    }
}
