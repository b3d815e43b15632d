//! `reproduce --replication`: do the paper's claims replicate? The study at two base seeds
//! (independent seeds), the claims from each and from their seeds pooled, and the verdicts of
//! each base seed's first n seeds for every n: the smallest n from which both agree with the
//! pooled verdicts is the number of seeds a study needs. A claim whose base seeds still
//! disagree at every n and whose pooled effect lies within one study's detectable difference
//! is at the edge of its power: its verdict is reported as "inconclusive".

use std::fmt::Write as _;

use fuzzymotiv_records::records::replication::{ReplicationRow, SeedsRow};
use fuzzymotiv_records::records::{ClaimRecord, SettingSummary, StudySummary};

use crate::figure::axis::GRID;
use crate::figure::{Area, Fill, Legend, Mark, PanelBox, Stroke, Svg, Text, colour};
use crate::study::{CLAIMS_ALPHA, claims};
use crate::tables::verdict;

/// The verdict of a claim as the replication compares it: a comparison's; for a check of
/// Fig. 6's curves, "holds" when every setting's test over seeds holds, "opposite" when one
/// shows the opposite, else "not significant" (its mark on means when it has no tests).
pub fn verdict_of(c: &ClaimRecord) -> String {
    if c.stats.is_some() || c.curves.is_empty() {
        return verdict(c).to_string();
    }
    if c.curves.iter().all(|t| t.verdict == "holds") {
        "holds".into()
    } else if c.curves.iter().any(|t| t.verdict == "opposite") {
        "opposite".into()
    } else {
        "not significant".into()
    }
}

/// The settings of a study with only its first `n` seeds.
pub fn first_seeds(study: &StudySummary, n: usize) -> Vec<SettingSummary> {
    study
        .settings
        .iter()
        .map(|s| {
            let mut s = s.clone();
            s.per_seed.truncate(n);
            s
        })
        .collect()
}

/// The settings of two studies of the same configs at different base seeds, their seeds
/// pooled (the first study's first).
pub fn pooled(a: &StudySummary, b: &StudySummary) -> Vec<SettingSummary> {
    a.settings
        .iter()
        .zip(&b.settings)
        .map(|(sa, sb)| {
            let mut s = sa.clone();
            s.per_seed.extend(sb.per_seed.iter().cloned());
            s
        })
        .collect()
}

/// The replication of two studies: per claim its verdicts, per number of seeds the verdicts
/// of both, and the number of seeds needed (see the module's docs).
pub fn replication(
    a: &StudySummary,
    b: &StudySummary,
) -> (
    Vec<ClaimRecord>,
    Vec<ReplicationRow>,
    Vec<SeedsRow>,
    Option<usize>,
) {
    let pooled_claims = claims(&pooled(a, b), CLAIMS_ALPHA);
    let target: Vec<String> = pooled_claims.iter().map(verdict_of).collect();
    let n = a.seeds.len().min(b.seeds.len());
    let by_seeds: Vec<SeedsRow> = (2..=n).map(|k| seeds_row(a, b, k, &target)).collect();
    let needed = seeds_needed(&by_seeds);
    let full_a = claims(&first_seeds(a, n), CLAIMS_ALPHA);
    let full_b = claims(&first_seeds(b, n), CLAIMS_ALPHA);
    let rows = pooled_claims
        .iter()
        .zip(full_a.iter().zip(&full_b))
        .map(|(p, (ca, cb))| row(p, ca, cb, needed.is_some()))
        .collect();
    (pooled_claims, rows, by_seeds, needed)
}

/// The smallest number of seeds from which on every row agrees (none when the last does not).
pub fn seeds_needed(by_seeds: &[SeedsRow]) -> Option<usize> {
    let agree: Vec<(usize, bool)> = by_seeds.iter().map(|r| (r.seeds, r.agree)).collect();
    fuzzymotiv_records::records::agreement::seeds_needed(&agree)
}

fn seeds_row(a: &StudySummary, b: &StudySummary, k: usize, target: &[String]) -> SeedsRow {
    let ca = claims(&first_seeds(a, k), CLAIMS_ALPHA);
    let cb = claims(&first_seeds(b, k), CLAIMS_ALPHA);
    let verdicts_a: Vec<String> = ca.iter().map(verdict_of).collect();
    let verdicts_b: Vec<String> = cb.iter().map(verdict_of).collect();
    let agree = verdicts_a
        .iter()
        .zip(&verdicts_b)
        .zip(target)
        .all(|((va, vb), t)| va == t && vb == t);
    SeedsRow {
        seeds: k,
        p_a: ca.iter().map(|c| c.stats.as_ref().map(|s| s.p)).collect(),
        p_b: cb.iter().map(|c| c.stats.as_ref().map(|s| s.p)).collect(),
        verdicts_a,
        verdicts_b,
        agree,
    }
}

/// One claim's row: `replicates` when some number of seeds made both base seeds agree.
fn row(p: &ClaimRecord, a: &ClaimRecord, b: &ClaimRecord, replicates: bool) -> ReplicationRow {
    let (va, vb, vp) = (verdict_of(a), verdict_of(b), verdict_of(p));
    let mdd = |c: &ClaimRecord| c.stats.as_ref().and_then(|s| s.mdd);
    let one_study = mdd(a).into_iter().chain(mdd(b)).fold(f64::NAN, f64::max);
    let effect = p.stats.as_ref().map(|s| s.difference);
    let at_edge = effect.is_some_and(|d| d.abs() <= one_study);
    let verdict = if !replicates && at_edge && (va != vp || vb != vp) {
        "inconclusive".to_string()
    } else {
        vp.clone()
    };
    ReplicationRow {
        claim: p.claim,
        verdict_a: va,
        verdict_b: vb,
        verdict_pooled: vp,
        effect,
        ci_low: p.stats.as_ref().map(|s| s.ci_low),
        ci_high: p.stats.as_ref().map(|s| s.ci_high),
        p: p.stats.as_ref().map(|s| s.p),
        mdd: mdd(p),
        at_edge,
        verdict,
    }
}

fn num(v: Option<f64>, decimals: usize) -> String {
    v.map_or("—".into(), |v| format!("{v:.decimals$}"))
}

/// The claims table (Markdown and CSV): per claim the verdict at each base seed, pooled, the
/// pooled statistics and the verdict reported; then the number of seeds needed.
pub fn replication_table(
    base: [u64; 2],
    seeds: usize,
    rows: &[ReplicationRow],
    needed: Option<usize>,
    prov: &str,
) -> (String, String) {
    let [a, b] = base;
    let mut md = format!(
        "{prov}\n\nThe paper's claims from two independent studies of {seeds} paired seeds each (base seeds {a} and {b}) and from their {} seeds pooled. \"At the edge\": the pooled effect is within the difference one study of {seeds} seeds detects with 80 % power (its MDD).\n\n| claim | base seed {a} | base seed {b} | pooled ({} seeds) | effect [95 % CI] | p | MDD (pooled) | at the edge | verdict |\n|---|---|---|---|---|---|---|---|---|\n",
        2 * seeds,
        2 * seeds
    );
    let mut csv = String::from(
        "claim,verdict_a,verdict_b,verdict_pooled,effect,ci_low,ci_high,p,mdd,at_edge,verdict\n",
    );
    for r in rows {
        let ci = match (r.effect, r.ci_low, r.ci_high) {
            (Some(d), Some(lo), Some(hi)) => format!("{d:+.1} [{lo:+.1}, {hi:+.1}]"),
            _ => "—".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {ci} | {} | {} | {} | **{}** |",
            r.claim,
            r.verdict_a,
            r.verdict_b,
            r.verdict_pooled,
            num(r.p, 4),
            num(r.mdd, 1),
            if r.at_edge { "yes" } else { "no" },
            r.verdict
        );
        let opt = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
        let _ = writeln!(
            csv,
            "\"{}\",{},{},{},{},{},{},{},{},{},{}",
            r.claim,
            r.verdict_a,
            r.verdict_b,
            r.verdict_pooled,
            opt(r.effect),
            opt(r.ci_low),
            opt(r.ci_high),
            opt(r.p),
            opt(r.mdd),
            r.at_edge,
            r.verdict
        );
    }
    md.push('\n');
    md.push_str(&match needed {
        Some(n) => format!(
            "From {n} seeds on (up to {seeds}), every claim's verdict at base seed {a} and at base seed {b} equals the pooled verdict: a study needs {n} seeds.\n"
        ),
        None => format!(
            "Up to {seeds} seeds, the verdicts at base seeds {a} and {b} do not all equal the pooled ones; claims at the edge of their power whose base seeds disagree are reported \"inconclusive\".\n"
        ),
    });
    (md, csv)
}

/// Per number of seeds, both base seeds' verdicts of every claim (CSV, one row per seeds and
/// claim).
pub fn seeds_csv(claims: &[ClaimRecord], by_seeds: &[SeedsRow]) -> String {
    let mut csv = String::from("seeds,claim,verdict_a,p_a,verdict_b,p_b,agree\n");
    for r in by_seeds {
        for (k, c) in claims.iter().enumerate() {
            let opt = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
            let _ = writeln!(
                csv,
                "{},\"{}\",{},{},{},{},{}",
                r.seeds,
                c.claim,
                r.verdicts_a[k],
                opt(r.p_a[k]),
                r.verdicts_b[k],
                opt(r.p_b[k]),
                r.agree
            );
        }
    }
    csv
}

const PW: f64 = 420.0;
const PH: f64 = 260.0;
const ML: f64 = 58.0;
const MR: f64 = 14.0;
const MT: f64 = 44.0;
const MB: f64 = 44.0;
const PANEL: PanelBox = PanelBox {
    width: PW,
    height: PH,
    left: ML,
    right: MR,
    bottom: MB,
    top: MT,
};
/// The p axis: log10 from 10^-4 to 1.
const P_LO: f64 = -4.0;

/// The p-value of each comparison claim against the number of seeds, one panel per claim:
/// each base seed's first n seeds (a line each), the pooled p at the pooled count, and α.
pub fn replication_svg(base: [u64; 2], claims: &[ClaimRecord], by_seeds: &[SeedsRow]) -> String {
    let tested: Vec<usize> = (0..claims.len())
        .filter(|&k| claims[k].stats.is_some())
        .collect();
    let cols = 2usize;
    let rows = tested.len().div_ceil(cols).max(1);
    let h = PH * rows as f64 + 30.0;
    let mut s = Svg::new(PW * cols as f64, h, 12);
    let max_n = by_seeds.last().map_or(2, |r| r.seeds).max(2);
    for (i, &k) in tested.iter().enumerate() {
        let area = PANEL.area(i % cols, i / cols);
        panel(&mut s, area, &claims[k], k, by_seeds, max_n);
    }
    let line = |j: usize| Mark::Line(Stroke::of(colour(j)).width(2.0));
    let legend = Legend::new(vec![
        (line(0), format!("base seed {}", base[0])),
        (line(1), format!("base seed {}", base[1])),
        (Mark::Dot(colour(2)), "pooled".into()),
        (
            Mark::Line(Stroke::of("#000").dashed("5 4")),
            format!("α = {CLAIMS_ALPHA}"),
        ),
    ]);
    legend.flow(&mut s, (20.0, PW * cols as f64), h - 12.0, 16.0);
    s.finish()
}

/// The p-value axis of a panel: a grid line at each power of ten from 10^-4 to 1, the axes,
/// the dashed line at α and the axis labels.
fn p_axis(s: &mut Svg, area: Area, y: &dyn Fn(f64) -> f64) {
    for (p, label) in [
        (1e-4, "0.0001"),
        (1e-3, "0.001"),
        (1e-2, "0.01"),
        (0.1, "0.1"),
        (1.0, "1"),
    ] {
        s.line((area.x0, y(p)), (area.x1, y(p)), Stroke::of(GRID));
        s.text((area.x0 - 6.0, y(p) + 4.0), label, Text::END);
    }
    let alpha = y(CLAIMS_ALPHA);
    s.line(
        (area.x0, alpha),
        (area.x1, alpha),
        Stroke::of("#000").dashed("5 4"),
    );
    area.axes(s);
    let labels = (("seeds per base seed", 34.0), ("p (log scale)", ML - 16.0));
    area.labels(s, labels.0, labels.1, Text::MIDDLE);
}

/// One claim's panel: each base seed's p against its first n seeds, and the pooled p.
fn panel(
    s: &mut Svg,
    area: Area,
    claim: &ClaimRecord,
    k: usize,
    by_seeds: &[SeedsRow],
    max_n: usize,
) {
    let xs = area.x_scale(2.0, max_n as f64);
    let x = |n: usize| xs.at(n as f64);
    let ys = area.y_scale(P_LO, 0.0);
    let y = |p: f64| ys.at(p.max(1e-4).log10());
    area.title(s, area.y1 - MT + 18.0, &claim.claim.sentence());
    p_axis(s, area, &y);
    let step = if max_n > 12 { 2 } else { 1 };
    let ticks: Vec<(f64, String)> = (2..=max_n)
        .filter(|n| n % step == 0)
        .map(|n| (x(n), n.to_string()))
        .collect();
    area.x_ticks(s, &ticks, 16.0, false, Text::MIDDLE);
    let picks: [fn(&SeedsRow, usize) -> Option<f64>; 2] = [|r, k| r.p_a[k], |r, k| r.p_b[k]];
    for (j, pick) in picks.iter().enumerate() {
        let pts: Vec<(f64, f64)> = (by_seeds.iter())
            .filter_map(|r| pick(r, k).map(|p| (x(r.seeds), y(p))))
            .collect();
        s.polyline(&pts, Stroke::of(colour(j)).width(2.0), None);
    }
    if let Some(st) = &claim.stats {
        // The label sits above the point, or below it near the top of the panel.
        let ly = if y(st.p) - 8.0 < area.y1 + 14.0 {
            y(st.p) + 20.0
        } else {
            y(st.p) - 8.0
        };
        s.circle((x(max_n), y(st.p)), 5.0, Fill::of(colour(2)), None);
        let p = if st.p < 1e-4 {
            "< 0.0001".to_string()
        } else {
            format!("= {:.4}", st.p)
        };
        let label = format!("pooled {} seeds: p {p}", st.seeds);
        s.text((area.x1 - 8.0, ly), &label, Text::END);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(agree: &[bool]) -> Vec<SeedsRow> {
        agree
            .iter()
            .enumerate()
            .map(|(k, &agree)| SeedsRow {
                seeds: k + 2,
                verdicts_a: Vec::new(),
                verdicts_b: Vec::new(),
                p_a: Vec::new(),
                p_b: Vec::new(),
                agree,
            })
            .collect()
    }

    /// A pooled p below 0.0001 is written as "< 0.0001", escaped: the figure stays valid XML.
    #[test]
    fn a_tiny_pooled_p_is_escaped_in_the_figure() {
        let claim: ClaimRecord = serde_json::from_str(
            r#"{"claim": "high curiosity uses more battery", "evidence": "", "holds": true,
            "stats": {"seeds": 40,
            "difference": -13.0, "ci_low": -18.0, "ci_high": -8.0, "p": 0.0, "min_p": 0.0,
            "alpha": 0.05, "verdict": "holds", "mdd": 6.8}}"#,
        )
        .unwrap();
        let mut by = rows(&[true, true]);
        for r in &mut by {
            r.p_a = vec![Some(0.5)];
            r.p_b = vec![Some(0.01)];
        }
        let svg = replication_svg([1, 11], &[claim], &by);
        assert!(svg.contains("p &lt; 0.0001"), "{svg}");
        assert!(!svg.contains("p < 0.0001"));
    }

    /// The seeds needed are where agreement starts and lasts: a late disagreement moves it on,
    /// a disagreement at the last count tried means none.
    #[test]
    fn the_seeds_needed_are_where_agreement_starts_and_lasts() {
        assert_eq!(seeds_needed(&rows(&[true, true, true])), Some(2));
        assert_eq!(seeds_needed(&rows(&[false, true, true])), Some(3));
        assert_eq!(seeds_needed(&rows(&[true, false, true, true])), Some(4));
        assert_eq!(seeds_needed(&rows(&[true, true, false])), None);
        assert_eq!(seeds_needed(&rows(&[])), None);
    }
}
