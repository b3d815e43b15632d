//! The report of a study of one's own (`fuzzymotiv study`), from its records only
//! (`fuzzymotiv_records::records::hypotheses`): `report.md` ([`report_md`]: the analysis
//! stated, the claims table, the forest plot, the rooms' results, the seeds' table, with
//! several base seeds each one's verdict beside the pooled one, and the study file quoted)
//! and `forest.svg` ([`forest_svg`]: every result's effect with its interval).

use std::fmt::Write as _;

use fuzzymotiv_records::records::hypotheses::{
    ClaimRow, HolmOver, Hypothesis, POOLED, PerSeedRow, Rule, StudyRecord,
};

use crate::plot::{esc, open, px, text_width};

/// A number as the report prints it: 4 significant decimals at most, `−` for negatives.
fn num(v: f64) -> String {
    let s = if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.2e}")
    } else {
        format!("{v:.4}")
    };
    let s = if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    s.replace('-', "−")
}

fn mdd(v: Option<f64>) -> String {
    v.map_or_else(|| "–".into(), num)
}

/// The colour of a verdict's mark.
fn verdict_colour(verdict: &str) -> &'static str {
    match verdict {
        "holds" => "#2ca02c",
        "opposite" => "#d62728",
        "inconclusive" => "#ff7f0e",
        _ => "#7f7f7f",
    }
}

/// One row per result (hypothesis and scope): its label, then on its own scale (the
/// hypotheses measure different things) its interval as a line, its effect as a dot coloured
/// by the verdict, and the reference: 0 for a difference or a slope, the bounds for a range
/// (dashed); then the numbers.
pub fn forest_svg(record: &StudyRecord) -> String {
    let claims = &record.claims;
    let label = |c: &ClaimRow| {
        if c.scope == POOLED {
            c.id.clone()
        } else {
            format!("{} ({})", c.id, c.scope)
        }
    };
    let left = 20.0
        + claims
            .iter()
            .map(|c| text_width(&label(c), false))
            .fold(80.0, f64::max);
    let (plot_w, row_h, top) = (300.0, 34.0, 40.0);
    let width = left + plot_w + 280.0;
    let height = top + row_h * claims.len() as f64 + 20.0;
    let mut s = open(px(width), px(height), 12);
    let _ = writeln!(
        s,
        "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"10\" y=\"22\" font-weight=\"bold\">Effects and their intervals (each row on its own scale)</text>"
    );
    for (k, c) in claims.iter().enumerate() {
        let y = top + row_h * (k as f64 + 0.5);
        let refs = references(record, c);
        let lo = refs.iter().copied().fold(c.ci_low.min(c.effect), f64::min);
        let hi = refs.iter().copied().fold(c.ci_high.max(c.effect), f64::max);
        let pad = if hi > lo { (hi - lo) * 0.08 } else { 1.0 };
        let x = |v: f64| px(left + plot_w * (v - lo + pad) / (hi - lo + 2.0 * pad));
        let _ = writeln!(
            s,
            "<text x=\"10\" y=\"{}\">{}</text>",
            px(y + 4.0),
            esc(&label(c))
        );
        for r in refs {
            let _ = writeln!(
                s,
                "<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>",
                x(r),
                px(y - row_h * 0.4),
                px(y + row_h * 0.4)
            );
        }
        let colour = verdict_colour(&c.verdict);
        let _ = writeln!(
            s,
            "<line x1=\"{}\" x2=\"{}\" y1=\"{2}\" y2=\"{2}\" stroke=\"{colour}\" stroke-width=\"2\"/>\n<circle cx=\"{3}\" cy=\"{2}\" r=\"4\" fill=\"{colour}\"/>",
            x(c.ci_low),
            x(c.ci_high),
            px(y),
            x(c.effect)
        );
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\">{} [{}, {}] {}</text>",
            px(left + plot_w + 15.0),
            px(y + 4.0),
            esc(&num(c.effect)),
            esc(&num(c.ci_low)),
            esc(&num(c.ci_high)),
            esc(&c.verdict)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// The reference values of a result: 0 (a difference, a slope) or a range's bounds.
fn references(record: &StudyRecord, c: &ClaimRow) -> Vec<f64> {
    match record.hypotheses.iter().find(|h| h.id() == c.id) {
        Some(Hypothesis::Range { min, max, .. }) => vec![*min, *max],
        _ => vec![0.0],
    }
}

/// `report.md`: the study, its analysis, its results and its file.
pub fn report_md(record: &StudyRecord, per_seed: &[PerSeedRow], study_text: &str) -> String {
    let mut s = format!("# Study `{}`\n\n", record.name);
    s.push_str(&arms_md(record));
    s.push_str(&analysis_md(record));
    s.push_str(&claims_md(record));
    s.push_str("![Every hypothesis's effect with its interval](forest.svg)\n\n");
    if record.base_seeds.len() > 1 {
        s.push_str(&replication_md(record));
        s.push_str(&crate::agreement::agreement_md(record));
    }
    s.push_str(&rooms_md(record));
    s.push_str(&seeds_md(per_seed));
    let fence = if study_text.contains("```") {
        "~~~~"
    } else {
        "```"
    };
    let _ = write!(
        s,
        "## The study file\n\n{fence}toml\n{}{}{fence}\n",
        study_text,
        if study_text.ends_with('\n') { "" } else { "\n" }
    );
    s
}

fn arms_md(record: &StudyRecord) -> String {
    let mut s =
        String::from("## Arms\n\n| arm | config | overrides | level |\n|---|---|---|---|\n");
    for a in &record.arms {
        let set: Vec<String> = a.set.iter().map(|o| format!("`{o}`")).collect();
        let _ = writeln!(
            s,
            "| {} | `{}` | {} | {} |",
            a.name,
            a.config,
            if set.is_empty() {
                "–".into()
            } else {
                set.join(", ")
            },
            a.level.map_or_else(|| "–".into(), num)
        );
    }
    let bases: Vec<String> = record.base_seeds.iter().map(u64::to_string).collect();
    let _ = writeln!(
        s,
        "\n{} paired seeds per base seed (base seeds {}): every arm runs on the same seeds.\n",
        record.seeds,
        bases.join(", ")
    );
    s
}

fn analysis_md(record: &StudyRecord) -> String {
    let a = &record.analysis;
    let rule = match a.rule {
        Rule::Power => {
            "the project's rule: *inconclusive* when the effect is smaller than the minimum detectable difference, else *holds* / *opposite* when p < α (by the effect's sign), else *not significant*"
        }
        Rule::P => {
            "by p alone: *holds* / *opposite* when p < α (by the effect's sign), else *not significant*"
        }
    };
    let holm = match a.holm {
        HolmOver::Hypotheses => {
            "Holm's method adjusts the hypotheses' p-values (within the pooled seeds and within each base seed); the verdicts read the adjusted p"
        }
        HolmOver::Rooms => {
            "Holm's method adjusts each hypothesis's p-values over its rooms (the rooms' table); the claims are not adjusted"
        }
        HolmOver::None => "no p-value is adjusted",
    };
    format!(
        "## Analysis\n\nα = {}, {} % bootstrap intervals ({} resamples), minimum detectable difference at {} % power (normal approximation). Paired sign-flip permutation tests over the seeds (exact up to 16 seeds). A compare hypothesis tests the per-seed differences of the two arms; a trend the per-seed least-squares slopes against the arms' levels (per unit of level); a range the arm's mean against each bound (it holds when significantly above the lower and below the upper bound; p is the larger); rising the last generation's mean F against the first's. A hypothesis is judged on each run's mean over its rooms. Verdicts: {rule}; {holm}.\n\n",
        num(a.alpha),
        num(100.0 * a.confidence),
        fuzzymotiv::statistics::BOOTSTRAP_RESAMPLES,
        num(100.0 * a.power),
    )
}

fn claims_md(record: &StudyRecord) -> String {
    let mut s = String::from(
        "## Claims\n\n| id | hypothesis | seeds | effect | 95 % CI | p | p (Holm) | detectable | verdict |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    if record.analysis.confidence != 0.95 {
        s = s.replace(
            "95 % CI",
            &format!("{} % CI", num(100.0 * record.analysis.confidence)),
        );
    }
    for c in record.claims.iter().filter(|c| c.scope == POOLED) {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | [{}, {}] | {} | {} | {} | **{}** |",
            c.id,
            c.sentence,
            c.seeds,
            num(c.effect),
            num(c.ci_low),
            num(c.ci_high),
            num(c.p),
            num(c.p_adjusted),
            mdd(c.mdd),
            c.verdict
        );
    }
    s.push('\n');
    s
}

fn replication_md(record: &StudyRecord) -> String {
    let mut s = String::from("## Each base seed's verdict\n\n| id | pooled |");
    for b in &record.base_seeds {
        let _ = write!(s, " base seed {b} |");
    }
    s.push_str("\n|---|---|");
    s.push_str(&"---|".repeat(record.base_seeds.len()));
    s.push('\n');
    for pooled in record.claims.iter().filter(|c| c.scope == POOLED) {
        let _ = write!(s, "| {} | **{}** |", pooled.id, pooled.verdict);
        for c in record
            .claims
            .iter()
            .filter(|c| c.scope != POOLED && c.id == pooled.id)
        {
            let _ = write!(
                s,
                " {} ({}, p {}) |",
                c.verdict,
                num(c.effect),
                num(c.p_adjusted)
            );
        }
        s.push('\n');
    }
    s.push('\n');
    s
}

fn rooms_md(record: &StudyRecord) -> String {
    let mut s = String::from(
        "## Per room\n\n| id | room | effect | CI | p | p (Holm) | verdict |\n|---|---|---|---|---|---|---|\n",
    );
    for r in record.rooms.iter().filter(|r| r.scope == POOLED) {
        let _ = writeln!(
            s,
            "| {} | {} | {} | [{}, {}] | {} | {} | {} |",
            r.id,
            r.room,
            num(r.effect),
            num(r.ci_low),
            num(r.ci_high),
            num(r.p),
            num(r.p_adjusted),
            r.verdict
        );
    }
    s.push('\n');
    s
}

/// Per seed, each arm's value (the mean over its rooms) of every measure.
fn seeds_md(per_seed: &[PerSeedRow]) -> String {
    let mut measures: Vec<&str> = Vec::new();
    for r in per_seed.iter().filter(|r| r.room.is_empty()) {
        if !measures.contains(&r.measure.as_str()) {
            measures.push(&r.measure);
        }
    }
    let mut s = String::from("## Seeds\n\n| base seed | seed | arm |");
    for m in &measures {
        let _ = write!(s, " {m} |");
    }
    s.push_str("\n|---|---|---|");
    s.push_str(&"---|".repeat(measures.len()));
    s.push('\n');
    let mut seen: Vec<(u64, u64, &str)> = Vec::new();
    for r in per_seed {
        let key = (r.base_seed, r.seed, r.arm.as_str());
        if seen.contains(&key) {
            continue;
        }
        seen.push(key);
        let _ = write!(s, "| {} | {} | {} |", r.base_seed, r.seed, r.arm);
        for m in &measures {
            let v = per_seed.iter().find(|x| {
                (x.base_seed, x.seed, x.arm.as_str()) == key && x.measure == *m && x.room.is_empty()
            });
            let _ = write!(s, " {} |", v.map_or_else(|| "–".into(), |x| num(x.value)));
        }
        s.push('\n');
    }
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv_records::records::hypotheses::{AnalysisRecord, Measure};

    fn record(hypotheses: Vec<Hypothesis>) -> StudyRecord {
        let claims = (hypotheses.iter())
            .map(|h| ClaimRow {
                id: h.id().into(),
                kind: h.kind().into(),
                sentence: h.sentence(),
                measure: h.measure_column(),
                arms: h.arms().join(";"),
                expect: h.expect_label().into(),
                scope: POOLED.into(),
                seeds: 5,
                effect: 40.0,
                ci_low: 35.0,
                ci_high: 45.0,
                p: 0.0625,
                p_adjusted: 0.0625,
                mdd: Some(3.0),
                verdict: "not significant".into(),
            })
            .collect();
        StudyRecord {
            program: "fuzzymotiv".into(),
            model: 1,
            name: "t".into(),
            analysis: AnalysisRecord {
                alpha: 0.05,
                confidence: 0.95,
                power: 0.8,
                rule: Rule::Power,
                holm: HolmOver::Hypotheses,
            },
            base_seeds: vec![1],
            seeds: 5,
            arms: Vec::new(),
            hypotheses,
            claims,
            rooms: Vec::new(),
            agreement: Vec::new(),
        }
    }

    #[test]
    fn a_ranges_forest_row_draws_its_bounds_and_a_comparisons_its_zero() {
        let range = Hypothesis::Range {
            id: "r".into(),
            measure: Measure::Exploration,
            arm: "a".into(),
            min: 30.0,
            max: 50.0,
        };
        let rising = Hypothesis::Rising {
            id: "f".into(),
            arm: "a".into(),
        };
        let svg = forest_svg(&record(vec![range]));
        // The row's scale spans 30 … 50 (the bounds outside the interval 35 … 45), padded.
        assert_eq!(svg.matches("stroke-dasharray").count(), 2, "{svg}");
        assert_eq!(svg.matches("<circle").count(), 1);
        let svg = forest_svg(&record(vec![rising]));
        assert_eq!(svg.matches("stroke-dasharray").count(), 1, "{svg}");
    }

    #[test]
    fn a_study_file_with_a_code_fence_is_quoted_whole() {
        let r = record(Vec::new());
        let text = "# a comment with ``` in it\n[study]\nname = \"t\"";
        let md = report_md(&r, &[], text);
        assert!(md.ends_with(&format!("~~~~toml\n{text}\n~~~~\n")), "{md}");
    }
}
