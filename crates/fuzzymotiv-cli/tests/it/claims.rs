//! `fuzzymotiv claims DIR --alpha A` on a finished study: the study's own claims are never
//! replaced, the claims at another α go beside them, and messages name only options the user
//! passed.

use crate::common;

use std::path::Path;

use common::{Fm, SMALL, stderr, stdout};

/// A small finished study in `dir`.
fn study(dir: &Path) -> Fm {
    Fm::new(["reproduce", "--quick", "--seeds", "2", "--quiet"])
        .out(dir)
        .sets(&SMALL)
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn claims_at_another_alpha_without_out_write_beside_the_study() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("results");
    study(&dir).ok();
    let (md, csv) = (read(&dir.join("claims.md")), read(&dir.join("claims.csv")));
    let d = dir.to_str().unwrap();

    // The guide's own usage (docs/guide/compare-and-claims.md): at another α the claims go to claims-alpha-0.1.* and are printed.
    let o = Fm::new(["claims", d, "--alpha", "0.1"]).ok();
    let at = read(&dir.join("claims-alpha-0.1.md"));
    assert!(at.contains("at p < α = 0.1") && stdout(&o) == at, "{at}");
    assert_eq!(
        read(&dir.join("claims.md")),
        md,
        "the study's claims are kept"
    );
    assert_eq!(
        read(&dir.join("claims.csv")),
        csv,
        "the study's claims are kept"
    );
    // The same again changes nothing; at the study's own α its files are the same tables.
    Fm::new(["claims", d, "--alpha", "0.1"]).ok();
    Fm::new(["claims", d]).ok();
    assert_eq!(read(&dir.join("claims.md")), md);

    // Files of other contents are kept without --force, and the message names no --out.
    let edited = dir.join("claims-alpha-0.1.csv");
    std::fs::write(&edited, "mine").unwrap();
    let o = Fm::new(["claims", d, "--alpha", "0.1"]).run();
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("claims-alpha-0.1.csv") && msg.contains("--force"),
        "{msg}"
    );
    assert!(!msg.contains("--out"), "names an option not passed: {msg}");
    assert_eq!(read(&edited), "mine");
    Fm::new(["claims", d, "--alpha", "0.1", "--force"]).ok();
    assert!(read(&edited) != "mine");

    // The new files are the study's own: the study is still done, and --force may replace it.
    let again = study(&dir).ok();
    assert!(
        stderr(&again).contains("nothing to do"),
        "{}",
        stderr(&again)
    );
    study(&dir).arg("--force").ok();
}

/// A claim is read back as the paper's claim whose sentence it is: a `summary.json` whose claim
/// is not one of them (here merely a claim's words) is refused with exit 2, naming the file, the
/// field and the claims there are, and nothing is written.
#[test]
fn a_claim_that_is_not_the_papers_is_refused_naming_the_file_and_field() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("results");
    study(&dir).ok();
    let summary = dir.join("summary.json");
    let text = read(&summary);
    let edited = text.replacen(
        "\"high curiosity uses more battery\"",
        "\"uses more battery\"",
        1,
    );
    assert_ne!(edited, text, "the study has the battery claim");
    std::fs::write(&summary, edited).unwrap();
    let o = Fm::new(["claims", dir.to_str().unwrap(), "--alpha", "0.1"]).run();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("summary.json")
            && e.contains("claim")
            && e.contains("`uses more battery` is not one of the paper's claims")
            && e.contains("high curiosity uses more battery"),
        "{e}"
    );
    assert!(!dir.join("claims-alpha-0.1.md").exists());
}
