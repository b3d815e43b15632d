//! Messages of bad input: each names the option or field really at fault, states its real
//! range, and shows numbers compactly; all exit with status 2.

mod common;

use std::path::Path;

use common::{Fm, repo, stderr};

/// `fuzzymotiv run` of the high-curiosity config with `sets`, expected to be refused with
/// status 2 before anything is written; returns its message.
fn refused_run(sets: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/high-curiosity.toml");
    let o = Fm::new(["run".as_ref(), cfg.as_os_str()])
        .out(&dir.path().join("out"))
        .sets(sets)
        .run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{sets:?}: {msg}");
    assert!(!dir.path().join("out").exists(), "{sets:?} wrote output");
    msg
}

#[test]
fn a_nan_motivation_is_blamed_on_its_own_field() {
    for name in ["curiosity", "homing", "orientation", "energy"] {
        let msg = refused_run(&[&format!("motivations.{name}=nan")]);
        assert!(
            msg.contains(&format!("field `motivations.{name}`")) && msg.contains("NaN"),
            "{name}: {msg}"
        );
        assert_eq!(msg.matches("motivations.").count(), 1, "{name}: {msg}");
    }
}

/// Every command that takes `--threads` refuses a number outside 1..=256 (and a negative one,
/// which clap would otherwise take for an option) with status 2 and a message naming
/// `--threads`, the range and the value, before starting anything.
#[test]
fn threads_outside_1_to_256_are_refused_naming_the_option_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = repo().join("configs/tiny.toml");
    let sweep = repo().join("configs/sweep-small.toml");
    let out = dir.path().join("out");
    let (cfg, sweep, out) = (
        cfg.to_str().unwrap(),
        sweep.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    let commands: [&[&str]; 5] = [
        &["run", cfg, "--out", out],
        &["reproduce", "--quick", "--out", out],
        &["bench", "--steps", "10"],
        &["sweep", sweep, "--out", out],
        &["lab", "--port", "0", "--dir", out],
    ];
    for command in commands {
        for threads in ["0", "-1", "257", "100000"] {
            let o = Fm::new(command).arg("--threads").arg(threads).run();
            let msg = stderr(&o);
            assert_eq!(
                o.status.code(),
                Some(2),
                "{command:?} --threads {threads}: {msg}"
            );
            for part in ["--threads", "from 1 to 256", &format!("got {threads}")] {
                assert!(msg.contains(part), "{command:?} --threads {threads}: {msg}");
            }
            assert!(
                !Path::new(out).exists(),
                "{command:?} --threads {threads} wrote {out}"
            );
        }
    }
}

/// Numeric options take a leading hyphen as the start of their value, so their own check
/// answers a negative number (not clap's "unexpected argument '-5'").
#[test]
fn negative_numbers_reach_the_options_own_check() {
    let o = Fm::new([
        "fuzzy",
        "--motivations",
        "-0.2,0.9,0.2,0.1",
        "--fitness",
        "1,1,1,1",
    ])
    .run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--motivations") && msg.contains("curiosity") && msg.contains("-0.2"),
        "{msg}"
    );
    // Fitness values are clamped to [0, 1], as the help says: -5 is 0.
    let clamped = Fm::new([
        "fuzzy",
        "--motivations",
        "0.8,0.1,0,0.1",
        "--fitness",
        "-5,0,0,0",
    ])
    .ok();
    let zero = Fm::new([
        "fuzzy",
        "--motivations",
        "0.8,0.1,0,0.1",
        "--fitness",
        "0,0,0,0",
    ])
    .ok();
    assert_eq!(common::stdout(&clamped), common::stdout(&zero));
    for (command, option) in [
        (&["claims", "study", "--alpha", "-0.5"][..], "--alpha"),
        (&["lab", "--port", "-1"][..], "--port"),
        (&["bench", "--steps", "-1"][..], "--steps"),
        (&["reproduce", "--seeds", "-1"][..], "--seeds"),
        (
            &["sweep", "s.toml", "--out", "o", "--index", "-1"][..],
            "--index",
        ),
        (
            &[
                "run",
                "--continue",
                "r",
                "--generations",
                "-1",
                "--out",
                "o",
            ][..],
            "--generations",
        ),
    ] {
        let value = command[command.iter().position(|a| *a == option).unwrap() + 1];
        let o = Fm::new(command).run();
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{command:?}: {msg}");
        assert!(
            msg.contains(option) && msg.contains(value) && !msg.contains("unexpected argument"),
            "{command:?}: {msg}"
        );
        assert!(!msg.contains("invalid digit"), "{command:?}: {msg}");
    }
}

/// A huge or tiny number is shown compactly (`1e300`), not as hundreds of digits.
#[test]
fn numbers_in_messages_are_shown_compactly() {
    for (set, field) in [
        ("ga.parent_fraction=1e300", "ga.parent_fraction"),
        ("motivations.homing=1e300", "motivations.homing"),
        ("trial.dt=-1e-300", "trial.dt"),
    ] {
        let msg = refused_run(&[set]);
        let value = set.split_once('=').unwrap().1;
        assert!(
            msg.contains(field) && msg.contains(&format!("got {value}")),
            "{set}: {msg}"
        );
        assert!(!msg.contains("0000000000"), "{set}: {msg}");
    }
    let o = Fm::new(["claims", "study", "--alpha", "1e300"]).run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--alpha") && msg.contains("got 1e300"),
        "{msg}"
    );
}

/// A value of the wrong type for a whole-number field (`1.5`, `-1`) is answered with the
/// field's own range, not "a whole number ≥ 0".
#[test]
fn type_errors_state_the_fields_real_range() {
    for (set, range) in [
        ("ga.population=1.5", "a whole number from 2 to 1000000"),
        ("ga.population=-1", "a whole number from 2 to 1000000"),
        ("ga.generations=2.5", "a whole number from 1 to 1000000"),
        ("trial.steps=-5", "a whole number from 1 to 10000000"),
        ("aem.test_runs=0.5", "a whole number from 1 to 100000"),
        ("network.hidden=\"six\"", "a whole number from 1 to 1024"),
        ("ga.elite=-1", "a whole number from 0 to ga.population − 1"),
        ("aem.threshold=-1", "a whole number ≥ 0"),
    ] {
        let msg = refused_run(&[set]);
        let field = set.split_once('=').unwrap().0;
        assert!(
            msg.contains(&format!("field `{field}`")) && msg.contains(range),
            "{set}: {msg}"
        );
    }
}
