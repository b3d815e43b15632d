//! `fuzzymotiv fuzzy --export-fll`: the FLL file, refusal to overwrite, bad input.

use crate::common;

use common::{ok, run, stderr};

#[test]
fn export_fll_writes_refuses_overwrite_and_rejects_bad_motivations() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("hc.fll");
    let f = file.to_str().unwrap();
    ok(&["fuzzy", "--motivations", ".8,.1,0,.1", "--export-fll", f]);
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.starts_with("Engine: hc\n"));
    assert_eq!(text.matches("\n  rule: if ").count(), 625);
    assert!(text.contains("  term: r10 Linear 0.8 0.025 0 0 0\n"));

    let o = run(&["fuzzy", "--motivations", ".5,.3,0,.2", "--export-fll", f]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--force"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), text);

    let o = ok(&[
        "fuzzy",
        "--motivations",
        ".5,.3,0,.2",
        "--fitness",
        ".55,.3,0,.58",
        "--export-fll",
        f,
        "--force",
    ]);
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("0.263309"));
    assert!(
        std::fs::read_to_string(&file)
            .unwrap()
            .contains("(0.5,0.3,0,0.2)")
    );

    let bad = dir.path().join("bad.fll");
    let o = run(&[
        "fuzzy",
        "--motivations",
        ".8,.1,0,.2",
        "--export-fll",
        bad.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--motivations"), "{}", stderr(&o));
    assert!(!bad.exists());
}
