//! The agreement section of a study's report at several base seeds (`report.md`, from its
//! `agreement.csv` rows): per number of seeds, each hypothesis's verdict at each base seed's
//! first seeds, marked where it differs from the pooled verdict, and the seeds the study
//! needs, as `reproduce --replication` reports the paper's claims.

use std::fmt::Write as _;

use fuzzymotiv_records::records::agreement::{AgreementRow, agree_by_seeds, seeds_needed};
use fuzzymotiv_records::records::hypotheses::{POOLED, StudyRecord};

/// The section (empty when the study has no agreement rows: one base seed).
pub fn agreement_md(record: &StudyRecord) -> String {
    let rows = &record.agreement;
    if rows.is_empty() {
        return String::new();
    }
    let ids: Vec<&str> = (record.claims.iter())
        .filter(|c| c.scope == POOLED)
        .map(|c| c.id.as_str())
        .collect();
    let bases: Vec<String> = record.base_seeds.iter().map(u64::to_string).collect();
    let mut s = format!(
        "## Agreement by seed count\n\nEach hypothesis judged on the first n seeds of each base seed ({}), by the analysis above; a verdict that is not the pooled one is marked ✗ (agreement.csv).\n\n| seeds |",
        bases.join(", ")
    );
    for id in &ids {
        let _ = write!(s, " {id} |");
    }
    s.push_str(" all agree |\n|---|");
    s.push_str(&"---|".repeat(ids.len() + 1));
    s.push('\n');
    let agree = agree_by_seeds(rows);
    for &(n, all) in &agree {
        let _ = write!(s, "| {n} |");
        for id in &ids {
            let cells: Vec<String> = (rows.iter())
                .filter(|r| r.seeds == n && r.id == *id)
                .map(cell)
                .collect();
            let _ = write!(s, " {} |", cells.join(" / "));
        }
        let _ = writeln!(s, " {} |", if all { "yes" } else { "no" });
    }
    let pooled: Vec<String> = (ids.iter())
        .filter_map(|id| rows.iter().find(|r| r.id == *id))
        .map(|r| format!("{} {}", r.id, r.pooled))
        .collect();
    let most = agree.last().map_or(0, |&(n, _)| n);
    let _ = writeln!(s, "\nThe pooled verdicts: {}.\n", pooled.join(", "));
    s.push_str(&match seeds_needed(&agree) {
        Some(n) => format!(
            "From {n} seeds on (up to {most}), every hypothesis's verdict at each base seed equals the pooled verdict: the study needs {n} seeds.\n\n"
        ),
        None => format!(
            "Up to {most} seeds, the base seeds' verdicts do not all equal the pooled ones: the study does not replicate at this size.\n\n"
        ),
    });
    s
}

fn cell(r: &AgreementRow) -> String {
    if r.agrees {
        r.verdict.clone()
    } else {
        format!("{} ✗", r.verdict)
    }
}
