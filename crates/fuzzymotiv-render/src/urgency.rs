//! `reproduce --urgency`: the paper's future work, "urgency for completing specific missions".
//! The `fetch` mission (configs/fetch.toml: the paper's rooms with a goal zone in the far
//! corner) under urgency weights 0, 0.1, 0.2 and 0.3 taken from curiosity of the paper's
//! high-curiosity setting, paired seeds; per weight what the evolved robots do (success rate,
//! time to the goal, exploration, battery, homing) and each step up in urgency as a paired
//! comparison.

use std::fmt::Write as _;

use fuzzymotiv::statistics::{Comparison, Settings, mean_interval, mean_std, paired};
use fuzzymotiv_records::records::Finished;
use fuzzymotiv_records::records::paired::PairedStats;
use fuzzymotiv_records::records::urgency::{UrgencyRow, UrgencySeed};

use crate::figure::{Area, Fill, PanelBox, PathData, Stroke, Svg, Text, Ticks, colour};
use crate::study::Setting;

/// configs/fetch.toml, built into the binary (its `rooms` name the files of [`FETCH_ROOMS`]).
pub const FETCH_CONFIG: &str = include_str!("../../../configs/fetch.toml");

/// The fetch rooms (rooms/fetch-*.toml), built into the binary: the path configs name each
/// by, from the repository's root, and its text.
pub const FETCH_ROOMS: [(&str, &str); 5] = [
    (
        "rooms/fetch-H.toml",
        include_str!("../../../rooms/fetch-H.toml"),
    ),
    (
        "rooms/fetch-T.toml",
        include_str!("../../../rooms/fetch-T.toml"),
    ),
    (
        "rooms/fetch-L.toml",
        include_str!("../../../rooms/fetch-L.toml"),
    ),
    (
        "rooms/fetch-square.toml",
        include_str!("../../../rooms/fetch-square.toml"),
    ),
    (
        "rooms/fetch-rectangle.toml",
        include_str!("../../../rooms/fetch-rectangle.toml"),
    ),
];

/// The urgency weights of [`URGENCY`], in order.
pub const WEIGHTS: [f64; 4] = [0.0, 0.1, 0.2, 0.3];

const fn fetch(name: &'static str, tag: &'static str, sets: &'static [&'static str]) -> Setting {
    Setting {
        name,
        tag,
        config: FETCH_CONFIG,
        sets,
        rooms: &FETCH_ROOMS,
        paper: &[],
    }
}

/// The study's settings: (C, H, O, E, urgency) = (0.8 − u, 0.1, 0, 0.1, u) for each u of
/// [`WEIGHTS`], on the fetch rooms.
pub const URGENCY: [Setting; 4] = [
    fetch(
        "urgency-0.0",
        "urgency_0.0",
        &["motivations.curiosity=0.8", "motivations.urgency=0.0"],
    ),
    fetch(
        "urgency-0.1",
        "urgency_0.1",
        &["motivations.curiosity=0.7", "motivations.urgency=0.1"],
    ),
    fetch(
        "urgency-0.2",
        "urgency_0.2",
        &["motivations.curiosity=0.6", "motivations.urgency=0.2"],
    ),
    fetch(
        "urgency-0.3",
        "urgency_0.3",
        &["motivations.curiosity=0.5", "motivations.urgency=0.3"],
    ),
];

/// The comparisons, as indices into [`WEIGHTS`] (lower, higher): each step up, then the
/// lowest against the highest.
pub const STEPS: [(usize, usize); 4] = [(0, 1), (1, 2), (2, 3), (0, 3)];

/// The measures, as the tables name them.
pub const MEASURES: [&str; 5] = [
    "% success",
    "time to goal (steps)",
    "% optimal exploration",
    "% battery usage",
    "% homing",
];

/// A seed's record under urgency weight `urgency`: its best robot's test runs (those of the
/// per-room table), means over rooms; the time to the goal over the test runs that reached it.
pub fn seed_record(
    setting: &str,
    urgency: f64,
    (index, seed): (usize, u64),
    done: &Finished,
) -> UrgencySeed {
    let rooms = done.rows.len().max(1) as f64;
    let mut success = 0.0;
    let mut steps = Vec::new();
    for r in 0..done.rows.len() {
        let tests = &done.outcome.aem_for_room(r).rooms[r].tests;
        let done_at: Vec<f64> = (tests.iter())
            .filter_map(|t| t.terms.mission.and_then(|m| m.done_at))
            .map(|s| s as f64)
            .collect();
        success += 100.0 * done_at.len() as f64 / tests.len().max(1) as f64;
        steps.extend(done_at);
    }
    let mean_of = |f: fn(&fuzzymotiv_records::records::RoomRow) -> f64| {
        done.rows.iter().map(f).sum::<f64>() / rooms
    };
    UrgencySeed {
        setting: setting.into(),
        urgency,
        index,
        seed,
        success_pct: success / rooms,
        time_to_goal: (!steps.is_empty()).then(|| steps.iter().sum::<f64>() / steps.len() as f64),
        exploration_pct: mean_of(|r| r.exploration_pct),
        battery_pct: mean_of(|r| r.battery_pct),
        homing_pct: mean_of(|r| r.homing_pct),
    }
}

/// Measure `k` of [`MEASURES`] of a seed.
pub fn value(s: &UrgencySeed, k: usize) -> Option<f64> {
    match k {
        0 => Some(s.success_pct),
        1 => s.time_to_goal,
        2 => Some(s.exploration_pct),
        3 => Some(s.battery_pct),
        _ => Some(s.homing_pct),
    }
}

/// The seeds of weight `w` (by their index in [`WEIGHTS`]), in seed order.
fn of_weight(per_seed: &[UrgencySeed], w: usize) -> Vec<&UrgencySeed> {
    per_seed
        .iter()
        .filter(|s| s.urgency == WEIGHTS[w])
        .collect()
}

/// Every step of [`STEPS`] for every measure, paired by seed (the seeds with a value under
/// both weights; a comparison of fewer than two pairs is left out).
pub fn comparisons(per_seed: &[UrgencySeed]) -> Vec<UrgencyRow> {
    let mut rows = Vec::new();
    for (k, measure) in MEASURES.iter().enumerate() {
        for &(lo, hi) in &STEPS {
            let (a, b) = (of_weight(per_seed, hi), of_weight(per_seed, lo));
            let pairs: Vec<(f64, f64)> = (a.iter())
                .filter_map(|x| {
                    let y = b.iter().find(|y| y.index == x.index)?;
                    Some((value(x, k)?, value(y, k)?))
                })
                .collect();
            if pairs.len() < 2 {
                continue;
            }
            let (to, from): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
            if let Ok(c) = paired(&to, &from, &Settings::default()) {
                rows.push(row(measure, (WEIGHTS[lo], WEIGHTS[hi]), to.len(), &c));
            }
        }
    }
    rows
}

fn row(measure: &str, (from, to): (f64, f64), pairs: usize, c: &Comparison) -> UrgencyRow {
    UrgencyRow {
        measure: measure.into(),
        from,
        to,
        pairs,
        mean_from: c.mean_b,
        mean_to: c.mean_a,
        // As the claims' verdicts: a difference within what the design detects is inconclusive.
        stats: PairedStats::of(c),
    }
}

/// "mean ± std" of the values present (with "(n of N)" when some seeds have none), or "—".
fn cell(values: &[Option<f64>]) -> String {
    let present: Vec<f64> = values.iter().flatten().copied().collect();
    if present.is_empty() {
        return "—".into();
    }
    let (m, sd) = mean_std(&present);
    let mut text = format!("{m:.1} ± {sd:.1}");
    if present.len() < values.len() {
        let _ = write!(text, " ({} of {})", present.len(), values.len());
    }
    text
}

/// `urgency.md` (after `prov`, the study's provenance line) and `urgency.csv` (the
/// comparisons).
pub fn urgency_table(
    per_seed: &[UrgencySeed],
    rows: &[UrgencyRow],
    prov: &str,
) -> (String, String) {
    let seeds = of_weight(per_seed, 0).len();
    let mut md = format!(
        "{prov}\n\nThe fetch mission (the paper's rooms, a goal zone in the corner farthest from home) under urgency weights taken from curiosity of the paper's high-curiosity setting: (C, H, O, E, urgency) = (0.8 − u, 0.1, 0, 0.1, u), the same {seeds} seeds for every u. Each seed's value is its best robot's test runs, mean over rooms: success is the % of test runs that reached the goal; time to goal the mean step at which the successful ones did (seeds with none left out). Mean ± std over seeds.\n\n| u | (C, H, O, E, urgency) |"
    );
    for m in MEASURES {
        let _ = write!(md, " {m} |");
    }
    md.push_str("\n|---|---|");
    md.push_str(&"---|".repeat(MEASURES.len()));
    md.push('\n');
    for (w, u) in WEIGHTS.iter().enumerate() {
        let seeds = of_weight(per_seed, w);
        let _ = write!(md, "| {u:.1} | ({:.1}, 0.1, 0, 0.1, {u:.1}) |", 0.8 - u);
        for k in 0..MEASURES.len() {
            let values: Vec<Option<f64>> = seeds.iter().map(|s| value(s, k)).collect();
            let _ = write!(md, " {} |", cell(&values));
        }
        md.push('\n');
    }
    md.push_str("\nEach step up in urgency (and 0 → 0.3), paired by seed: the higher weight − the lower (95 % bootstrap interval, two-sided sign-flip permutation p, α = 0.05; \"detectable\" is the smallest difference this design finds with 80 % power; a difference within it is \"inconclusive\", whatever p; a comparison with fewer than two seeds that have the measure under both weights is left out).\n\n| measure | u | seeds | lower u | higher u | difference (95 % CI) | p | detectable | verdict |\n|---|---|---|---|---|---|---|---|---|\n");
    let mut csv = String::from(
        "measure,from,to,pairs,mean_from,mean_to,difference,ci_low,ci_high,p,detectable,verdict\n",
    );
    for r in rows {
        let detectable = r.stats.detectable.map_or("—".into(), |d| format!("{d:.1}"));
        let _ = writeln!(
            md,
            "| {} | {:.1} → {:.1} | {} | {:.1} | {:.1} | {:+.1} ({:+.1}, {:+.1}) | {:.3} | {detectable} | {} |",
            r.measure,
            r.from,
            r.to,
            r.pairs,
            r.mean_from,
            r.mean_to,
            r.stats.difference,
            r.stats.ci_low,
            r.stats.ci_high,
            r.stats.p,
            r.stats.verdict
        );
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            r.measure,
            r.from,
            r.to,
            r.pairs,
            r.mean_from,
            r.mean_to,
            r.stats.difference,
            r.stats.ci_low,
            r.stats.ci_high,
            r.stats.p,
            r.stats.detectable.map_or(String::new(), |d| d.to_string()),
            r.stats.verdict
        );
    }
    (md, csv)
}

/// `urgency_seeds.csv`: every seed's values under every weight.
pub fn seeds_csv(per_seed: &[UrgencySeed]) -> String {
    let mut csv = String::from(
        "setting,urgency,index,seed,success_pct,time_to_goal,exploration_pct,battery_pct,homing_pct\n",
    );
    for s in per_seed {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{}",
            s.setting,
            s.urgency,
            s.index,
            s.seed,
            s.success_pct,
            s.time_to_goal.map_or(String::new(), |t| t.to_string()),
            s.exploration_pct,
            s.battery_pct,
            s.homing_pct
        );
    }
    csv
}

const PW: f64 = 250.0;
const PH: f64 = 230.0;
const ML: f64 = 52.0;
const MR: f64 = 16.0;
const MT: f64 = 34.0;
const MB: f64 = 46.0;
const PANEL: PanelBox = PanelBox {
    width: PW,
    height: PH,
    left: ML,
    right: MR,
    bottom: MB,
    top: MT,
};
const COLS: usize = 3;

/// Per weight, the mean of measure `k` over the seeds that have it and its 95 % bootstrap
/// interval (none without values).
fn points(per_seed: &[UrgencySeed], k: usize) -> Vec<Option<(f64, f64, f64)>> {
    let s = Settings::default();
    (0..WEIGHTS.len())
        .map(|w| {
            let v: Vec<f64> = (of_weight(per_seed, w).iter())
                .filter_map(|x| value(x, k))
                .collect();
            if v.is_empty() {
                return None;
            }
            let (lo, hi) = mean_interval(&v, s.confidence, s.bootstrap_resamples, s.seed);
            Some((mean_std(&v).0, lo, hi))
        })
        .collect()
}

/// `urgency.svg`: one panel per measure, its mean over seeds against the urgency weight with
/// the 95 % bootstrap interval of the mean.
pub fn urgency_svg(per_seed: &[UrgencySeed]) -> String {
    let rows = MEASURES.len().div_ceil(COLS);
    let mut s = Svg::new(PW * COLS as f64, PH * rows as f64, 12);
    for k in 0..MEASURES.len() {
        let area = PANEL.area(k % COLS, k / COLS);
        panel(&mut s, area, k, &points(per_seed, k));
    }
    // The legend in the free cell of the grid (five panels in a 3 × 2 grid).
    let (lx, ly) = (2.0 * PW + 20.0, PH + MT + 10.0);
    for (i, line) in [
        "points: mean over seeds",
        "bars: its 95 % bootstrap interval",
        "u: urgency's weight; curiosity",
        "is 0.8 − u (H 0.1, O 0, E 0.1)",
    ]
    .iter()
    .enumerate()
    {
        s.text((lx, ly + 18.0 * i as f64), line, Text::START);
    }
    s.finish()
}

/// A panel's value axis over its points' intervals, padded, never below 0 (every measure is
/// at least 0: no negative axis below a flat line at 0): its ticks and the span drawn.
fn value_axis(present: &[(f64, f64, f64)]) -> (Ticks, f64, f64) {
    let lo = present.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let hi = present
        .iter()
        .map(|p| p.2)
        .fold(f64::NEG_INFINITY, f64::max);
    let pad = ((hi - lo) * 0.08).max(0.5);
    let bottom = (lo - pad).max(0.0);
    let ticks = Ticks::nice(bottom, hi + pad, 5, false);
    let (v0, v1) = (
        ticks.values[0].min(bottom),
        ticks.values.last().map_or(hi + pad, |t| t.max(hi + pad)),
    );
    (ticks, v0, v1)
}

/// Measure `k`'s panel over `area`: per weight the mean (point) with its interval (bar),
/// joined by a line.
fn panel(s: &mut Svg, area: Area, k: usize, points: &[Option<(f64, f64, f64)>]) {
    area.title(s, area.y1 - MT + 20.0, MEASURES[k]);
    let present: Vec<(f64, f64, f64)> = points.iter().flatten().copied().collect();
    if present.is_empty() {
        let note = Text::MIDDLE.size(11.0);
        s.text(
            (area.mid_x(), area.mid_y()),
            "no test run reached the goal",
            note,
        );
        return;
    }
    let (ticks, v0, v1) = value_axis(&present);
    let y = area.y_scale(v0, v1);
    area.y_grid(s, &ticks, y, Text::END.size(10.0), None);
    area.axes(s);
    area.x_label(s, ("urgency u", 34.0), Text::MIDDLE.size(11.0));
    let inner = Area {
        x0: area.x0 + 16.0,
        x1: area.x1 - 16.0,
        ..area
    };
    let x = inner.x_scale(0.0, (WEIGHTS.len() - 1) as f64);
    let ticks: Vec<(f64, String)> = (WEIGHTS.iter().enumerate())
        .map(|(w, u)| (x.at(w as f64), format!("{u:.1}")))
        .collect();
    area.x_ticks(s, &ticks, 16.0, false, Text::MIDDLE.size(10.0));
    let mut path = PathData::new();
    for (w, u) in WEIGHTS.iter().enumerate() {
        let Some((m, lo, hi)) = points[w] else {
            continue;
        };
        let xx = x.at(w as f64);
        path = path.line_to((xx, y.at(m)));
        s.line(
            (xx, y.at(lo)),
            (xx, y.at(hi)),
            Stroke::of(colour(0)).width(2.0),
        );
        let title = format!("u = {u:.1}: {m:.2} ({lo:.2}, {hi:.2})");
        s.circle((xx, y.at(m)), 4.0, Fill::of(colour(0)), Some(&title));
    }
    s.path(&path, Fill::outline(Stroke::of(colour(0)).width(1.5)), None);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::esc;

    fn seed(w: usize, index: usize, success: f64, time: Option<f64>) -> UrgencySeed {
        UrgencySeed {
            setting: URGENCY[w].name.into(),
            urgency: WEIGHTS[w],
            index,
            seed: 100 + index as u64,
            success_pct: success,
            time_to_goal: time,
            exploration_pct: 80.0 - 5.0 * w as f64 + index as f64,
            battery_pct: 70.0,
            homing_pct: 50.0 + index as f64 * 0.5,
        }
    }

    fn study() -> Vec<UrgencySeed> {
        (0..4)
            .flat_map(|w| {
                (1..=5).map(move |i| {
                    let time = (w > 0).then_some(300.0 - 40.0 * w as f64 + i as f64);
                    seed(w, i, 20.0 * w as f64 + i as f64, time)
                })
            })
            .collect()
    }

    /// The settings take urgency's weight from curiosity, (C, urgency) = (0.8 − u, u), on the
    /// fetch rooms.
    #[test]
    fn each_urgency_setting_takes_its_weight_from_curiosity() {
        for (s, u) in URGENCY.iter().zip(WEIGHTS) {
            assert_eq!(
                s.sets,
                [
                    format!("motivations.curiosity={:.1}", 0.8 - u),
                    format!("motivations.urgency={u:.1}")
                ]
            );
            assert_eq!(s.rooms.len(), 5);
        }
    }

    /// Every step of every measure is compared, paired by seed; time to the goal only where
    /// two seeds reached it under both weights (never at u = 0 here).
    #[test]
    fn each_step_up_in_urgency_is_compared_where_both_weights_have_the_measure() {
        let rows = comparisons(&study());
        let time: Vec<&UrgencyRow> = rows.iter().filter(|r| r.measure == MEASURES[1]).collect();
        assert_eq!(time.len(), 2, "only 0.1 → 0.2 and 0.2 → 0.3: {time:?}");
        assert_eq!(rows.len(), 4 * 4 + 2);
        let success = &rows[0];
        assert_eq!((success.from, success.to, success.pairs), (0.0, 0.1, 5));
        assert!((success.stats.difference - 20.0).abs() < 1e-9);
        assert!((time[0].stats.difference + 40.0).abs() < 1e-9);
        // The same difference at every seed: no spread, detectable 0, and p the smallest
        // five sign flips give (1/16) is not below α.
        assert_eq!(success.stats.verdict, "not significant");
        let (md, csv) = urgency_table(&study(), &rows, "prov");
        assert_eq!(csv.lines().count(), 1 + rows.len());
        assert!(md.contains("| 0.0 | (0.8, 0.1, 0, 0.1, 0.0) |"), "{md}");
        assert!(
            md.contains("| time to goal (steps) | 0.1 → 0.2 | 5 |"),
            "{md}"
        );
        assert_eq!(seeds_csv(&study()).lines().count(), 1 + 20);
    }

    /// The figure has a panel per measure, a point with its interval per weight that has
    /// values, and says so where no test run reached the goal.
    #[test]
    fn the_urgency_figure_draws_each_measure_against_the_weight() {
        let svg = urgency_svg(&study());
        assert!(svg.starts_with("<svg"), "{svg}");
        for m in MEASURES {
            assert!(svg.contains(&esc(m)), "{m}");
        }
        assert_eq!(svg.matches("<circle").count(), 4 * 5 - 1);
        let none: Vec<UrgencySeed> = (0..4).map(|w| seed(w, 1, 0.0, None)).collect();
        assert!(urgency_svg(&none).contains("no test run reached the goal"));
    }
}
