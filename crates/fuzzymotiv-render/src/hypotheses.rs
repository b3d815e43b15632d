//! The report of a study of one's own (`fuzzymotiv study`), from its records only
//! (`fuzzymotiv_records::records::hypotheses`): `report.md` ([`report_md`]: the analysis
//! stated, the claims table, the forest plot, the rooms' results, the seeds' table, with
//! several base seeds each one's verdict beside the pooled one, and the study file quoted)
//! and `forest.svg` ([`forest_svg`], in [`crate::forest`]: every result's effect with its
//! interval, a panel per measure). A result's numbers are printed by one rule
//! ([`crate::claim_format`]: a percentage's to one decimal, else three significant digits; p
//! to three decimals); the CSV and JSON records keep them whole.

use std::fmt::Write as _;

use fuzzymotiv_records::records::hypotheses::{
    HolmOver, POOLED, PerSeedRow, RoomResultRow, Rule, StudyRecord,
};

pub use crate::forest::forest_svg;

use crate::claim_format::{RowFormat, p_text};

/// A setting as the report prints it (α, a confidence, an arm's level): 4 decimals at most,
/// `−` for negatives; the results' numbers go by [`RowFormat`].
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

/// `report.md`: the study, its analysis, its results and its file.
pub fn report_md(record: &StudyRecord, per_seed: &[PerSeedRow], study_text: &str) -> String {
    let mut s = format!("# Study `{}`\n\n", record.name);
    s.push_str(&arms_md(record));
    if !record.hypotheses.is_empty() {
        s.push_str(&analysis_md(record));
        s.push_str(&claims_md(record));
        s.push_str("![Every hypothesis's effect with its interval](forest.svg)\n\n");
        if record.base_seeds.len() > 1 {
            s.push_str(&replication_md(record));
            s.push_str(&crate::agreement::agreement_md(record));
        }
        s.push_str(&rooms_md(record));
    }
    s.push_str(&measures_md(record));
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
    let (per, which) = match bases.as_slice() {
        [one] => ("", format!("base seed {one}")),
        _ => (" per base seed", format!("base seeds {}", bases.join(", "))),
    };
    let _ = writeln!(
        s,
        "\n{} paired seeds{per} ({which}): every arm runs on the same seeds.\n",
        record.seeds,
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
        "## Analysis\n\nα = {}, {} % bootstrap intervals ({} resamples), minimum detectable difference at {} % power (normal approximation). Paired sign-flip permutation tests over the seeds (exact up to 16 seeds). A compare hypothesis tests the per-seed differences of the two arms; a difference the per-seed a − b against versus_a − versus_b (a difference of two paired differences); a trend the per-seed least-squares slopes against the arms' levels (per unit of level); a range the arm's mean against each bound (it holds when significantly above the lower and below the upper bound; p is the larger); rising the last generation's mean F against the first's. A hypothesis is judged on each run's mean over its rooms. Verdicts: {rule}; {holm}.\n\n",
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
        let f = RowFormat::of_claim(c);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | **{}** |",
            c.id,
            c.sentence,
            c.seeds,
            f.num(c.effect),
            f.interval(c.ci_low, c.ci_high),
            p_text(c.p),
            p_text(c.p_adjusted),
            f.mdd(c.mdd),
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
                RowFormat::of_claim(c).num(c.effect),
                p_text(c.p_adjusted)
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
        let f = room_format(record, r);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} |",
            r.id,
            r.room,
            f.num(r.effect),
            f.interval(r.ci_low, r.ci_high),
            p_text(r.p),
            p_text(r.p_adjusted),
            r.verdict
        );
    }
    s.push('\n');
    s
}

/// The format of a room's result: its hypothesis's kind and measure, its own numbers.
fn room_format(record: &StudyRecord, r: &RoomResultRow) -> RowFormat {
    let claim = record.claims.iter().find(|c| c.id == r.id);
    let (kind, measure) = claim.map_or(("", ""), |c| (c.kind.as_str(), c.measure.as_str()));
    let mut numbers = vec![r.effect, r.ci_low, r.ci_high];
    numbers.extend(r.mdd);
    RowFormat::of(kind, measure, &numbers)
}

/// Each arm's measures over the pooled seeds (`arms.csv`): mean ± sample sd of each seed's mean
/// over the rooms, then per room.
fn measures_md(record: &StudyRecord) -> String {
    let mut s = String::from(
        "## Measures per arm\n\nMean ± sample standard deviation over the seeds (`arms.csv`; each base seed's too).\n\n| arm | measure | room | seeds | mean ± sd |\n|---|---|---|---|---|\n",
    );
    for m in record.measures.iter().filter(|m| m.scope == POOLED) {
        let fmt = RowFormat::of("", &m.measure, &[m.mean, m.sd.unwrap_or(0.0)]);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} ± {} |",
            m.arm,
            m.measure,
            if m.room.is_empty() { "all" } else { &m.room },
            m.seeds,
            fmt.num(m.mean),
            fmt.mdd(m.sd)
        );
    }
    s.push('\n');
    s
}

/// Per seed, each arm's value (the mean over its rooms) of every measure, each measure's
/// column to one format (a percentage to one decimal, else three significant digits of the
/// column's largest value).
fn seeds_md(per_seed: &[PerSeedRow]) -> String {
    let mut measures: Vec<&str> = Vec::new();
    for r in per_seed.iter().filter(|r| r.room.is_empty()) {
        if !measures.contains(&r.measure.as_str()) {
            measures.push(&r.measure);
        }
    }
    let formats: Vec<RowFormat> = (measures.iter())
        .map(|m| {
            let values: Vec<f64> = (per_seed.iter())
                .filter(|r| r.room.is_empty() && r.measure == *m)
                .map(|r| r.value)
                .collect();
            RowFormat::of("", m, &values)
        })
        .collect();
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
        for (k, m) in measures.iter().enumerate() {
            let v = per_seed.iter().find(|x| {
                (x.base_seed, x.seed, x.arm.as_str()) == key && x.measure == *m && x.room.is_empty()
            });
            let _ = write!(
                s,
                " {} |",
                v.map_or_else(|| "–".into(), |x| formats[k].num(x.value))
            );
        }
        s.push('\n');
    }
    s.push('\n');
    s
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::claim_format::claim_line;
    use fuzzymotiv_records::records::hypotheses::{
        AnalysisRecord, ClaimRow, Direction, Hypothesis, Measure,
    };

    /// A pooled claim of `h` with this effect and interval (p 0.0625, detectable 3).
    pub(crate) fn claim(h: &Hypothesis, effect: f64, ci_low: f64, ci_high: f64) -> ClaimRow {
        ClaimRow {
            id: h.id().into(),
            kind: h.kind().into(),
            sentence: h.sentence(),
            measure: h.measure_column(),
            arms: h.arms().join(";"),
            expect: h.expect_label().into(),
            scope: POOLED.into(),
            seeds: 5,
            effect,
            ci_low,
            ci_high,
            p: 0.0625,
            p_adjusted: 0.0625,
            mdd: Some(3.0),
            verdict: "not significant".into(),
        }
    }

    /// A one-base-seed study of `hypotheses`, each with a pooled claim 40 [35, 45].
    pub(crate) fn record(hypotheses: Vec<Hypothesis>) -> StudyRecord {
        let claims = (hypotheses.iter())
            .map(|h| claim(h, 40.0, 35.0, 45.0))
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
            measures: Vec::new(),
            agreement: Vec::new(),
        }
    }

    /// A study without hypotheses (a sweep of arms) reports each arm's measures and no
    /// claims, forest plot or rooms' results.
    #[test]
    fn a_study_without_hypotheses_reports_its_arms_measures_and_no_claims() {
        let mut r = record(Vec::new());
        r.measures = vec![fuzzymotiv_records::records::hypotheses::ArmMeasureRow {
            scope: POOLED.into(),
            arm: "online".into(),
            measure: "recognition_pct".into(),
            room: String::new(),
            seeds: 5,
            mean: 42.5,
            sd: Some(3.26),
        }];
        let md = report_md(&r, &[], "");
        assert!(
            md.contains("| online | recognition_pct | all | 5 | 42.5 ± 3.3 |"),
            "{md}"
        );
        for absent in ["## Claims", "forest.svg", "## Per room", "## Analysis"] {
            assert!(!md.contains(absent), "{absent}: {md}");
        }
        let with = report_md(
            &record(vec![Hypothesis::Rising {
                id: "f".into(),
                arm: "a".into(),
            }]),
            &[],
            "",
        );
        assert!(with.contains("## Claims") && with.contains("## Measures per arm"));
    }

    #[test]
    fn a_study_file_with_a_code_fence_is_quoted_whole() {
        let r = record(Vec::new());
        let text = "# a comment with ``` in it\n[study]\nname = \"t\"";
        let md = report_md(&r, &[], text);
        assert!(md.ends_with(&format!("~~~~toml\n{text}\n~~~~\n")), "{md}");
    }

    /// Every number of a claim row goes by one rule: a percentage's effect, bounds and
    /// detectable difference to one decimal, another measure's to three significant digits of
    /// the row's largest, a trend's slope likewise; p to three decimals (`< 0.001` below).
    #[test]
    fn a_claim_rows_numbers_are_printed_to_one_precision() {
        let explores = Hypothesis::Compare {
            id: "explores".into(),
            measure: Measure::Exploration,
            a: "a".into(),
            b: "b".into(),
            expect: Direction::Higher,
        };
        let fitness = Hypothesis::Compare {
            id: "fitter".into(),
            measure: Measure::Fitness,
            a: "a".into(),
            b: "b".into(),
            expect: Direction::Higher,
        };
        let trend = Hypothesis::Trend {
            id: "trend".into(),
            measure: Measure::Exploration,
            arms: vec!["a".into(), "b".into()],
            expect: Direction::Higher,
        };
        let mut r = record(vec![explores, fitness, trend]);
        r.claims[0] = claim(&r.hypotheses[0], 7.304, 7.304, 32.4641);
        r.claims[0].mdd = Some(4.0);
        r.claims[0].p = 0.0001;
        r.claims[1] = claim(&r.hypotheses[1], 0.012345, -0.0021, 0.0301);
        r.claims[1].mdd = Some(0.01567);
        r.claims[1].p = 0.03125;
        r.claims[2] = claim(&r.hypotheses[2], 0.05123, -0.0004, 0.1);
        r.claims[2].mdd = None;
        let md = report_md(&r, &[], "");
        assert!(
            md.contains("| 7.3 | [7.3, 32.5] | < 0.001 | 0.062 | 4.0 |"),
            "{md}"
        );
        assert!(
            md.contains("| 0.0123 | [−0.0021, 0.0301] | 0.031 | 0.062 | 0.0157 |"),
            "{md}"
        );
        assert!(
            md.contains("| 0.051 | [0.000, 0.100] | 0.062 | 0.062 | – |"),
            "{md}"
        );
        // A zero slope's rounding noise prints as zeros, not to fifteen decimals.
        r.claims[2] = claim(&r.hypotheses[2], 1e-15, -2e-16, 3e-15);
        r.claims[2].mdd = Some(4e-15);
        assert!(
            claim_line(&r.claims[2]).ends_with("(effect 0.000, CI [0.000, 0.000], p 0.062)"),
            "{}",
            claim_line(&r.claims[2])
        );
        assert!(
            claim_line(&r.claims[0]).ends_with("(effect 7.3, CI [7.3, 32.5], p 0.062)"),
            "{}",
            claim_line(&r.claims[0])
        );
    }
}
