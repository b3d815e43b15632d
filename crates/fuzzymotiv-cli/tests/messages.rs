//! Messages of bad input: each names the option or field really at fault, states its real
//! range, and shows numbers compactly; all exit with status 2.

mod common;

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
