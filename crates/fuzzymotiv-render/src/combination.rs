//! `reproduce --combination`: does the fuzzy combination matter? The paper's study under the
//! TSK (the default) and under the two baselines of `[fitness] combine` (docs/model.md §8), and,
//! between each baseline and the TSK, the paired statistics of the behaviour the robots evolved
//! (exploration, homing, battery, recognition: each seed's mean over rooms, paired by seed) and
//! of each comparison claim's effect (high − low curiosity: the difference in differences).

use std::fmt::Write as _;

use fuzzymotiv::statistics::{Comparison, Settings, paired};
use fuzzymotiv_records::records::combination::{BehaviourRow, ClaimDifferenceRow};
use fuzzymotiv_records::records::paired::PairedStats;
use fuzzymotiv_records::records::paper_claims::ClaimId;
use fuzzymotiv_records::records::{ClaimRecord, StudySummary, TableRow};

use crate::figure::{Area, Fill, Legend, Mark, Stroke, Svg, Text, Ticks, colour};
use crate::study::{DEFAULT_MODEL, Variant, seed_means};
use crate::tables::verdict;

/// The study under each combination: the TSK first (the default model), then the baselines.
pub const COMBINATION: [Variant; 3] = [
    DEFAULT_MODEL,
    Variant {
        name: "weighted-sum",
        what: "fitness.combine = \"weighted-sum\" (F = Σ X_i·Y_i)",
        sets: &["fitness.combine=\"weighted-sum\""],
        first_release_rooms: false,
    },
    Variant {
        name: "weighted-squares",
        what: "fitness.combine = \"weighted-squares\" (F = Σ X_i·Y_i², the TSK on its peaks)",
        sets: &["fitness.combine=\"weighted-squares\""],
        first_release_rooms: false,
    },
];

/// The behaviour measures compared, as the tables name them. The last, the spread of the
/// test runs' final positions (`Experiment::end_spread`), is measured by the study beside the
/// tables.
pub const MEASURES: [&str; 5] = [
    "% optimal exploration",
    "% homing",
    "% battery usage",
    "% recognition",
    "% end spread",
];

/// The value of measure `k` in a seed's table: the mean over the rooms that have it.
fn seed_value(rows: &[TableRow], k: usize) -> Option<f64> {
    let values: Vec<f64> = rows
        .iter()
        .filter_map(|r| match k {
            0 => r.exploration_pct,
            1 => r.homing_pct,
            2 => r.battery_pct,
            _ => r.recognition_pct,
        })
        .collect();
    (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
}

/// Every baseline against the TSK (the first study), per setting and measure, paired by seed.
/// `spreads[study][setting][seed]` is each seed's end spread (mean over rooms). Measures a
/// study does not have (recognition without room modelling) are left out.
pub fn behaviour_rows(
    studies: &[(&str, &StudySummary)],
    spreads: &[Vec<Vec<f64>>],
) -> Vec<BehaviourRow> {
    let Some(((_, tsk), rest)) = studies.split_first() else {
        return Vec::new();
    };
    let spread = |i: usize, si: usize, k: usize| spreads.get(i)?.get(si)?.get(k).copied();
    let mut out = Vec::new();
    for (i, (name, study)) in rest.iter().enumerate() {
        for (si, (s, base)) in study.settings.iter().zip(&tsk.settings).enumerate() {
            for (k, measure) in MEASURES.iter().enumerate() {
                let pairs: Option<Vec<(f64, f64)>> = if k == 4 {
                    (0..s.per_seed.len().min(base.per_seed.len()))
                        .map(|j| Some((spread(i + 1, si, j)?, spread(0, si, j)?)))
                        .collect()
                } else {
                    s.per_seed
                        .iter()
                        .zip(&base.per_seed)
                        .map(|(a, b)| Some((seed_value(&a.rows, k)?, seed_value(&b.rows, k)?)))
                        .collect()
                };
                let Some(pairs) = pairs.filter(|p| p.len() >= 2) else {
                    continue;
                };
                let (a, b): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
                let Ok(c) = paired(&a, &b, &Settings::default()) else {
                    continue;
                };
                out.push(row(name, &s.name, measure, &c));
            }
        }
    }
    out
}

fn row(combination: &str, setting: &str, measure: &str, c: &Comparison) -> BehaviourRow {
    BehaviourRow {
        combination: combination.into(),
        setting: setting.into(),
        measure: measure.into(),
        mean_combination: c.mean_a,
        mean_tsk: c.mean_b,
        // As the claims' verdicts: a difference within what the design detects is inconclusive.
        stats: PairedStats::of(c),
    }
}

/// Per seed, a claim's high − low (each setting's mean over rooms of `column`), for a study
/// of the paper's two settings (high curiosity first); none if a value is missing.
fn claim_effects(study: &StudySummary, claim: ClaimId) -> Option<Vec<f64>> {
    let [high, low] = study.settings.as_slice() else {
        return None;
    };
    let measure = claim.measure();
    let column = |r: &TableRow| measure.of_row(r);
    let (h, l) = (seed_means(high, column)?, seed_means(low, column)?);
    (h.len() == l.len()).then(|| h.iter().zip(&l).map(|(h, l)| h - l).collect())
}

/// Every baseline against the TSK (the first study), per comparison claim: the difference in
/// differences, (high − low)_baseline − (high − low)_TSK paired by seed, with `compare`'s
/// statistics (as the behaviour rows). Claims a study cannot test (recognition without room
/// modelling) are left out.
pub fn claim_difference_rows(studies: &[(&str, &StudySummary)]) -> Vec<ClaimDifferenceRow> {
    let Some(((_, tsk), rest)) = studies.split_first() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for (name, study) in rest {
        for claim in ClaimId::COMPARISONS {
            let (Some(a), Some(b)) = (claim_effects(study, claim), claim_effects(tsk, claim))
            else {
                continue;
            };
            if a.len() != b.len() || a.len() < 2 {
                continue;
            }
            let Ok(c) = paired(&a, &b, &Settings::default()) else {
                continue;
            };
            out.push(ClaimDifferenceRow {
                combination: (*name).into(),
                claim,
                effect_combination: c.mean_a,
                effect_tsk: c.mean_b,
                stats: PairedStats::of(&c),
            });
        }
    }
    out
}

/// The claims' differences between combinations as (Markdown, CSV).
pub fn claim_difference_table(rows: &[ClaimDifferenceRow], seeds: usize) -> (String, String) {
    let mut md = format!(
        "Does the combination change the claims' effects? Per claim, each baseline's high − low against the TSK's, paired by seed ({seeds} seeds; per seed (high − low)_baseline − (high − low)_TSK, each setting's value its mean over rooms; 95 % bootstrap interval, two-sided sign-flip permutation p, α = 0.05; \"detectable\" is the smallest difference this design finds with 80 % power; a difference within it is \"inconclusive\", whatever p; \"higher\"/\"lower\": a larger/smaller high − low under the baseline).\n\n| combination | claim | high − low, baseline | high − low, TSK | difference (95 % CI) | p | detectable | verdict |\n|---|---|---|---|---|---|---|---|\n"
    );
    let mut csv = String::from(
        "combination,claim,effect_combination,effect_tsk,difference,ci_low,ci_high,p,detectable,verdict\n",
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {:+.1} | {:+.1} | {:+.1} ({:+.1}, {:+.1}) | {:.3} | {:.1} | {} |",
            r.combination,
            r.claim,
            r.effect_combination,
            r.effect_tsk,
            r.stats.difference,
            r.stats.ci_low,
            r.stats.ci_high,
            r.stats.p,
            r.stats.detectable.unwrap_or(f64::NAN),
            r.stats.verdict
        );
        let _ = writeln!(
            csv,
            "{},\"{}\",{},{},{},{},{},{},{},{}",
            r.combination,
            r.claim,
            r.effect_combination,
            r.effect_tsk,
            r.stats.difference,
            r.stats.ci_low,
            r.stats.ci_high,
            r.stats.p,
            r.stats.detectable.unwrap_or(f64::NAN),
            r.stats.verdict
        );
    }
    (md, csv)
}

/// The claims under each combination, one row per combination, as Markdown (after `prov`, the
/// study's provenance line).
pub fn claims_table(rows: &[(&Variant, Vec<ClaimRecord>)], prov: &str) -> String {
    let mut md = format!(
        "{prov}\n\nThe paper's claims under each combination of the same motivations (means over rooms and seeds; each combination's own tables are in its directory).\n\n| combination | F |"
    );
    let Some((_, first)) = rows.first() else {
        return md;
    };
    for c in first {
        let _ = write!(md, " {} |", c.claim);
    }
    md.push_str("\n|---|---|");
    md.push_str(&"---|".repeat(first.len()));
    md.push('\n');
    for (v, claims) in rows {
        let name = if v.name == DEFAULT_MODEL.name {
            "tsk"
        } else {
            v.name
        };
        let what = if v.sets.is_empty() {
            "the paper's TSK rule base"
        } else {
            v.what
        };
        let _ = write!(md, "| {name} | {what} |");
        for c in claims {
            let _ = write!(md, " {} ({}) |", verdict(c), c.evidence);
        }
        md.push('\n');
    }
    md
}

/// The behaviour table as (Markdown, CSV).
pub fn behaviour_table(rows: &[BehaviourRow], seeds: usize) -> (String, String) {
    let mut md = format!(
        "Does the fuzzy combination change behaviour? Each baseline against the TSK, paired by seed ({seeds} seeds; each seed's value is its mean over rooms; 95 % bootstrap interval, two-sided sign-flip permutation p, α = 0.05; \"detectable\" is the smallest difference this design finds with 80 % power; a difference within it is \"inconclusive\", whatever p, as in the claims).\n\n| combination | setting | measure | baseline | TSK | difference (95 % CI) | p | detectable | verdict |\n|---|---|---|---|---|---|---|---|---|\n"
    );
    let mut csv = String::from(
        "combination,setting,measure,mean_combination,mean_tsk,difference,ci_low,ci_high,p,detectable,verdict\n",
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.1} | {:.1} | {:+.1} ({:+.1}, {:+.1}) | {:.3} | {:.1} | {} |",
            r.combination,
            r.setting,
            r.measure,
            r.mean_combination,
            r.mean_tsk,
            r.stats.difference,
            r.stats.ci_low,
            r.stats.ci_high,
            r.stats.p,
            r.stats.detectable.unwrap_or(f64::NAN),
            r.stats.verdict
        );
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{}",
            r.combination,
            r.setting,
            r.measure,
            r.mean_combination,
            r.mean_tsk,
            r.stats.difference,
            r.stats.ci_low,
            r.stats.ci_high,
            r.stats.p,
            r.stats.detectable.unwrap_or(f64::NAN),
            r.stats.verdict
        );
    }
    (md, csv)
}

const PANEL_W: f64 = 250.0;
const PANEL_H: f64 = 240.0;
const TOP: f64 = 44.0;
const BOTTOM: f64 = 56.0;
const LEFT: f64 = 46.0;

/// The figure: one panel per measure; in each, per setting and baseline, the paired difference
/// baseline − TSK (points) with its 95 % interval; a zero line. Filled points are significant and at least the detectable difference (verdict higher or lower).
pub fn behaviour_svg(rows: &[BehaviourRow]) -> String {
    let measures: Vec<&str> = MEASURES
        .iter()
        .copied()
        .filter(|m| rows.iter().any(|r| r.measure == *m))
        .collect();
    let height = PANEL_H + 30.0;
    let mut s = Svg::new(PANEL_W * measures.len().max(1) as f64, height, 12);
    let combos = distinct(rows.iter().map(|r| r.combination.as_str()));
    let settings = distinct(rows.iter().map(|r| r.setting.as_str()));
    for (k, m) in measures.iter().enumerate() {
        let panel: Vec<&BehaviourRow> = rows.iter().filter(|r| r.measure == *m).collect();
        draw_panel(&mut s, m, &panel, (&settings, &combos), k as f64 * PANEL_W);
    }
    let legend = Legend::new(
        (combos.iter().enumerate())
            .map(|(c, name)| (Mark::Dot(colour(c)), format!("{name} − TSK")))
            .collect(),
    );
    legend.flow(&mut s, (10.0, f64::INFINITY), height - 8.0, 16.0);
    s.finish()
}

fn distinct<'a>(items: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for i in items {
        if !out.contains(&i) {
            out.push(i);
        }
    }
    out
}

/// A panel's difference axis over its rows' intervals and 0, padded: its ticks and the span
/// drawn.
fn difference_axis(rows: &[&BehaviourRow]) -> (Ticks, f64, f64) {
    let (lo, hi) = rows.iter().fold((0.0f64, 0.0f64), |(lo, hi), r| {
        (lo.min(r.stats.ci_low), hi.max(r.stats.ci_high))
    });
    let pad = ((hi - lo) * 0.08).max(0.5);
    let ticks = Ticks::nice(lo - pad, hi + pad, 5, false);
    let y0 = ticks.values[0].min(lo - pad);
    let y1 = ticks.values.last().map_or(hi + pad, |t| t.max(hi + pad));
    (ticks, y0, y1)
}

/// Measure `title`'s panel from `ox`: per setting a slot, in it each baseline's difference
/// with its interval, filled where the verdict is higher or lower.
fn draw_panel(
    s: &mut Svg,
    title: &str,
    rows: &[&BehaviourRow],
    (settings, combos): (&[&str], &[&str]),
    ox: f64,
) {
    let area = Area {
        x0: ox + LEFT,
        x1: ox + PANEL_W - 12.0,
        y0: PANEL_H - BOTTOM,
        y1: TOP,
    };
    let (ticks, v0, v1) = difference_axis(rows);
    let y = area.y_scale(v0, v1);
    let centre = ox + PANEL_W / 2.0;
    s.text((centre, 20.0), title, Text::MIDDLE.bold());
    s.text(
        (centre, 34.0),
        "baseline − TSK (points)",
        Text::MIDDLE.size(10.0),
    );
    area.y_grid(s, &ticks, y, Text::END.size(10.0), None);
    s.line(
        (area.x0, y.at(0.0)),
        (area.x1, y.at(0.0)),
        Stroke::of("#333"),
    );
    let slot = (area.x1 - area.x0) / settings.len().max(1) as f64;
    for (i, setting) in settings.iter().enumerate() {
        let cx = area.x0 + slot * (i as f64 + 0.5);
        s.text((cx, area.y0 + 16.0), setting, Text::MIDDLE.size(10.0));
        for (c, combo) in combos.iter().enumerate() {
            let found = rows
                .iter()
                .find(|r| r.setting == *setting && r.combination == *combo);
            let Some(r) = found else {
                continue;
            };
            let x = cx + (c as f64 - (combos.len() as f64 - 1.0) / 2.0) * 14.0;
            let open = matches!(r.stats.verdict.as_str(), "not significant" | "inconclusive");
            let col = colour(c);
            let st = &r.stats;
            let ring = Stroke::of(col).width(2.0);
            s.line((x, y.at(st.ci_low)), (x, y.at(st.ci_high)), ring);
            let fill = Fill::of(if open { "white" } else { col }).stroked(ring);
            let tip = format!(
                "{combo} {setting} {title}: {:+.2} (p = {:.3})",
                st.difference, st.p
            );
            s.circle((x, y.at(st.difference)), 4.0, fill, Some(&tip));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(combination: &str, setting: &str, measure: &str, d: f64, p: f64) -> BehaviourRow {
        BehaviourRow {
            combination: combination.into(),
            setting: setting.into(),
            measure: measure.into(),
            mean_combination: 50.0 + d,
            mean_tsk: 50.0,
            stats: PairedStats {
                difference: d,
                ci_low: d - 2.0,
                ci_high: d + 2.0,
                p,
                detectable: Some(3.0),
                verdict: if p < 0.05 {
                    "higher"
                } else {
                    "not significant"
                }
                .into(),
            },
        }
    }

    /// A study's records (the committed five-seed study) and a copy whose high-curiosity
    /// battery is `shift` points higher in every room of seed `k` for each `k` in `seeds`.
    fn shifted(shift: f64, seeds: &[usize]) -> (StudySummary, StudySummary) {
        let tsk: StudySummary =
            serde_json::from_str(include_str!("../../../docs/results/five-seed/summary.json"))
                .unwrap();
        let mut other = tsk.clone();
        for &k in seeds {
            for r in &mut other.settings[0].per_seed[k].rows {
                r.battery_pct = r.battery_pct.map(|b| b + shift);
            }
        }
        (tsk, other)
    }

    /// Per claim, the baseline's high − low against the TSK's, paired by seed: a baseline
    /// whose high-curiosity battery is 4 points higher in every seed has a battery effect 4
    /// points larger (every seed the same: p is the smallest five seeds give), and the other
    /// claims' effects the TSK's (difference 0, not significant); the table and the CSV have a
    /// row each.
    #[test]
    fn each_claims_effect_is_compared_between_combinations_paired_by_seed() {
        let (tsk, sum) = shifted(4.0, &[0, 1, 2, 3, 4]);
        let rows = claim_difference_rows(&[("tsk", &tsk), ("weighted-sum", &sum)]);
        assert_eq!(rows.len(), ClaimId::COMPARISONS.len(), "{rows:?}");
        for r in &rows {
            let battery = r.claim == ClaimId::Battery;
            let want = if battery { 4.0 } else { 0.0 };
            assert!((r.stats.difference - want).abs() < 1e-9, "{r:?}");
            assert!(
                (r.effect_combination - r.effect_tsk - want).abs() < 1e-9,
                "{r:?}"
            );
            assert_eq!(r.combination, "weighted-sum");
            if battery {
                assert!((r.stats.p - 2.0 / 32.0).abs() < 1e-12, "{r:?}");
            } else {
                assert_eq!(r.stats.verdict, "not significant", "{r:?}");
            }
        }
        // One seed shifted: the effect differs by 4 / 5 on average, not in every seed.
        let (tsk, one) = shifted(4.0, &[2]);
        let rows = claim_difference_rows(&[("tsk", &tsk), ("weighted-squares", &one)]);
        let battery = rows.iter().find(|r| r.claim == ClaimId::Battery).unwrap();
        assert!((battery.stats.difference - 0.8).abs() < 1e-9, "{battery:?}");
        assert!(battery.stats.p > 0.05, "{battery:?}");
        let (md, csv) = claim_difference_table(&rows, 5);
        assert_eq!(
            md.matches("\n| weighted-squares | high curiosity").count(),
            4,
            "{md}"
        );
        assert!(md.contains("| +0.8 ("), "{md}");
        assert_eq!(csv.lines().count(), 1 + 4);
        assert!(csv.contains("weighted-squares,\"high curiosity uses more battery\","));
    }

    /// The table has a row per comparison and the figure a panel per measure, each point with
    /// its interval; a significant point is filled, the others hollow.
    #[test]
    fn the_behaviour_table_and_figure_show_every_comparison() {
        let rows = vec![
            row("weighted-sum", "high-curiosity", MEASURES[0], 4.0, 0.01),
            row("weighted-sum", "low-curiosity", MEASURES[0], -1.0, 0.4),
            row("weighted-squares", "high-curiosity", MEASURES[1], 0.5, 0.8),
        ];
        let (md, csv) = behaviour_table(&rows, 10);
        assert_eq!(md.matches("\n| weighted-").count(), 3, "{md}");
        assert!(
            md.contains("| +4.0 (+2.0, +6.0) | 0.010 | 3.0 | higher |"),
            "{md}"
        );
        assert_eq!(csv.lines().count(), 4);
        let svg = behaviour_svg(&rows);
        assert!(svg.starts_with("<svg"), "{svg}");
        assert_eq!(svg.matches("<circle cx").count(), 3 + 2, "{svg}");
        assert_eq!(svg.matches(r#"fill="white" stroke"#).count(), 2, "{svg}");
        assert!(svg.contains("% optimal exploration") && svg.contains("% homing"));
    }
}
