//! `reproduce --search-strength`: the study at GA populations 30, 60, 100 and 200, each in
//! its own directory, then one table and one figure made from their summary.json records.

use crate::common;

use common::{Fm, run, stderr, stdout};

/// Small trials and few generations; the populations are the study's own.
const SIZES: [&str; 4] = [
    "ga.generations=2",
    "trial.steps=60",
    "aem.epochs=10",
    "aem.test_runs=2",
];

fn read(p: std::path::PathBuf) -> String {
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn search_strength_runs_every_population_and_tabulates_the_claims() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ss");
    let cmd = || {
        Fm::new(["reproduce", "--search-strength", "--seeds", "2", "--quiet"])
            .out(&out)
            .sets(&SIZES)
    };
    let o = cmd().ok();
    let md = read(out.join("search_strength.md"));
    assert_eq!(stdout(&o).trim_end(), md.trim_end());
    assert!(
        md.contains("GA population 30, 60, 100, 200 × 2 generations"),
        "{md}"
    );
    let csv = read(out.join("search_strength.csv"));
    for pop in [30, 60, 100, 200] {
        let dir = out.join(format!("pop-{pop}"));
        let summary: serde_json::Value =
            serde_json::from_str(&read(dir.join("summary.json"))).unwrap();
        assert_eq!(summary["population"], pop, "pop-{pop}/summary.json");
        // The table's row is the population's own paired test, read from its record.
        let claim = &summary["claims"][0];
        assert_eq!(
            claim["claim"],
            "high curiosity explores more than low curiosity"
        );
        let row = csv
            .lines()
            .find(|l| l.starts_with(&format!("{pop},\"high curiosity explores more")))
            .unwrap_or_else(|| panic!("no row for {pop}: {csv}"));
        let fields: Vec<&str> = row.split(',').collect();
        let difference: f64 = fields[4].parse().unwrap();
        assert_eq!(difference, claim["stats"]["difference"].as_f64().unwrap());
        assert_eq!(fields[8], claim["stats"]["verdict"].as_str().unwrap());
        assert!(dir.join("trajectories_low_curiosity.svg").is_file());
        assert!(dir.join("claims.md").is_file());
    }
    // Six claims per population, then the exploration rows.
    assert_eq!(csv.lines().count(), 1 + 4 * 6 + 4, "{csv}");
    assert!(md.contains("Low-curiosity exploration"), "{md}");
    let svg = read(out.join("search_strength.svg"));
    assert!(svg.contains("% exploration per setting") && svg.contains(">returns home less<"));
    assert_eq!(svg.matches(">GA population<").count(), 5, "five panels");
    // It opens as every figure does, in the one font stack.
    let font = format!(
        "font-family=\"{}\"",
        fuzzymotiv_pipeline::render::figure::FONT_STACK
    );
    assert!(svg.starts_with("<svg ") && svg.split('>').next().unwrap().contains(&font));
    // The same command again: done, nothing replaced.
    let again = cmd().ok();
    assert!(
        stderr(&again).contains("already holds this study"),
        "{}",
        stderr(&again)
    );
    assert_eq!(read(out.join("search_strength.md")), md);
}

#[test]
fn search_strength_is_its_own_kind_of_study() {
    let o = run(&["reproduce", "--search-strength", "--ablation"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--ablation"), "{}", stderr(&o));
}

/// The study sets the GA population itself: a `--set` of it (or of the whole `ga` table) would
/// make the four studies one, so it is refused before anything runs.
#[test]
fn a_set_of_the_population_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ss");
    for set in ["ga.population=10", "ga={population=10}"] {
        let o = Fm::new(["reproduce", "--search-strength", "--seeds", "2"])
            .out(&out)
            .sets(&[set])
            .run();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("sets `ga.population` itself"),
            "{}",
            stderr(&o)
        );
        assert!(!out.exists());
    }
}
