//! `fuzzymotiv compare`'s numbers and pages: two settings' metrics per room and over all rooms,
//! each compared with `fuzzymotiv::statistics` (paired when the two share their seeds, else
//! unpaired), as [`CompareRow`]s, a Markdown page and a figure of the differences with their
//! intervals per room. Beside the paper's metrics ([`METRICS`]), the measures of runs that
//! follow missions or weigh terms of their own — `mission_done_pct` and `NAME_pct` per term
//! beyond a, g, l, b ([`MISSION_DONE`], [`term_metric`]) — are compared when both sides have
//! them.

use std::fmt::Write as _;

use fuzzymotiv::statistics::{self, Comparison, Settings, StatsError};

use crate::figure::{Anchor, Area, Fill, Legend, MUTED, Mark, Stroke, Svg, Text};
use crate::tables::p_text;
use fuzzymotiv_records::records::METRICS;
use fuzzymotiv_records::records::compare::{CompareRow, OVERALL};
pub use fuzzymotiv_records::records::test_runs::{MISSION_DONE, term_metric};

/// The metrics in words, in [`METRICS`] order, and their decimals.
pub const METRIC_LABELS: [(&str, usize); 5] = [
    ("average fitness F", 3),
    ("% optimal exploration", 1),
    ("% recognition", 1),
    ("% battery usage", 1),
    ("% homing", 1),
];

/// One seed, replicate or test run of a setting: per room, its values in its group's
/// [`Group::metrics`] order (none where it has no value).
#[derive(Debug, Clone, PartialEq)]
pub struct Unit {
    /// What pairs it with a unit of the other side: its seed (and test run).
    pub key: String,
    /// Per room, the values.
    pub rooms: Vec<Vec<Option<f64>>>,
}

/// One setting of an output: its name, its metrics and its units.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// The setting's name.
    pub name: String,
    /// The metrics of its units' values, in order: [`METRICS`], then its own (e.g.
    /// [`MISSION_DONE`], `goal_pct`) when it has them.
    pub metrics: Vec<String>,
    /// Its seeds, replicates or test runs.
    pub units: Vec<Unit>,
}

impl Group {
    /// A group of the paper's metrics ([`METRICS`]) and `extra` ones after them.
    pub fn new(name: impl Into<String>, extra: &[String], units: Vec<Unit>) -> Group {
        let metrics = METRICS.iter().map(|m| m.to_string());
        Group {
            name: name.into(),
            metrics: metrics.chain(extra.iter().cloned()).collect(),
            units,
        }
    }
}

/// For each unit of `a`, the unit of `b` with the same key, when the two have the same keys
/// (the same seeds): then the design is paired.
pub fn pairing(a: &Group, b: &Group) -> Option<Vec<usize>> {
    if a.units.len() != b.units.len() {
        return None;
    }
    a.units
        .iter()
        .map(|u| b.units.iter().position(|v| v.key == u.key))
        .collect()
}

/// The values of metric `m` in room `room` (`None`: the mean over rooms), one per unit, in
/// `order` (a unit index each); none if a unit lacks one.
fn values(g: &Group, order: &[usize], room: Option<usize>, m: usize) -> Option<Vec<f64>> {
    order
        .iter()
        .map(|&k| {
            let rooms = &g.units[k].rooms;
            match room {
                Some(r) => rooms.get(r)?.get(m).copied().flatten(),
                None => {
                    let v: Option<Vec<f64>> =
                        rooms.iter().map(|r| r.get(m).copied().flatten()).collect();
                    v.filter(|v| !v.is_empty()).map(|v| statistics::mean(&v))
                }
            }
        })
        .collect()
}

/// Compares setting `a` with `b` on every metric of `a` that `b` has too, in every room of
/// `rooms` and over all rooms: paired when [`pairing`] finds the same seeds, else unpaired. Room
/// p-values are Holm-adjusted over the rooms of a metric. Metrics without values on both sides
/// are left out.
pub fn compare_groups(
    a: &Group,
    b: &Group,
    rooms: &[String],
    settings: &Settings,
) -> Result<Vec<CompareRow>, StatsError> {
    let pairs = pairing(a, b);
    let order_a: Vec<usize> = (0..a.units.len()).collect();
    let order_b = pairs
        .clone()
        .unwrap_or_else(|| (0..b.units.len()).collect());
    let test = |room: Option<usize>, (ma, mb)| -> Result<Option<Comparison>, StatsError> {
        let (Some(va), Some(vb)) = (values(a, &order_a, room, ma), values(b, &order_b, room, mb))
        else {
            return Ok(None);
        };
        let c = if pairs.is_some() {
            statistics::paired(&va, &vb, settings)?
        } else {
            statistics::unpaired(&va, &vb, settings)?
        };
        Ok(Some(c))
    };
    let setting = if a.name == b.name {
        a.name.clone()
    } else {
        format!("{} vs {}", a.name, b.name)
    };
    let mut out = Vec::new();
    for (ma, metric) in a.metrics.iter().enumerate() {
        let Some(mb) = b.metrics.iter().position(|m| m == metric) else {
            continue;
        };
        let mut tested = Vec::new();
        for (r, room) in rooms.iter().enumerate() {
            if let Some(c) = test(Some(r), (ma, mb))? {
                tested.push((room.as_str(), c));
            }
        }
        let p: Vec<f64> = tested.iter().map(|(_, c)| c.p).collect();
        for ((room, c), p_holm) in tested.iter().zip(statistics::holm(&p)) {
            out.push(row(&setting, metric, room, c, p_holm));
        }
        if let Some(c) = test(None, (ma, mb))? {
            out.push(row(&setting, metric, OVERALL, &c, c.p));
        }
    }
    Ok(out)
}

fn row(setting: &str, metric: &str, room: &str, c: &Comparison, p_holm: f64) -> CompareRow {
    let (design, n_a, n_b) = match c.design {
        statistics::Design::Paired { n } => ("paired", n, n),
        statistics::Design::Unpaired { n_a, n_b } => ("unpaired", n_a, n_b),
    };
    CompareRow {
        setting: setting.into(),
        metric: metric.into(),
        room: room.into(),
        design: design.into(),
        n_a,
        n_b,
        mean_a: c.mean_a,
        mean_b: c.mean_b,
        difference: c.difference,
        ci_low: c.ci_low,
        ci_high: c.ci_high,
        p: c.p,
        exact: c.exact,
        p_holm,
        mdd: c.mdd,
    }
}

/// The label and decimals of a metric's name: one of [`METRICS`], [`MISSION_DONE`] ("% missions
/// done") or a term's ([`term_metric`]: "% NAME").
pub fn metric_label(metric: &str) -> (String, usize) {
    if let Some(k) = METRICS.iter().position(|m| *m == metric) {
        let (label, d) = METRIC_LABELS[k];
        return (label.to_string(), d);
    }
    if metric == MISSION_DONE {
        return ("% missions done".to_string(), 1);
    }
    match metric.strip_suffix("_pct") {
        Some(term) => (format!("% {term}"), 1),
        None => (metric.to_string(), 3),
    }
}

/// The rows of `rows` in (setting, metric) blocks, in their order.
pub fn blocks(rows: &[CompareRow]) -> Vec<&[CompareRow]> {
    let mut out: Vec<&[CompareRow]> = Vec::new();
    let mut start = 0;
    for k in 1..=rows.len() {
        let cut = k == rows.len()
            || rows[k].setting != rows[start].setting
            || rows[k].metric != rows[start].metric;
        if cut {
            out.push(&rows[start..k]);
            start = k;
        }
    }
    out
}

/// `compare.md`: `head` (what was compared, the design, the method), then one table per
/// setting and metric: means, A − B with its interval, p, Holm p ([`p_text`]: never `0.0000`)
/// and MDD; `*` marks p < α.
pub fn compare_md(head: &str, rows: &[CompareRow], alpha: f64) -> String {
    let mut md = format!("{head}\n");
    for block in blocks(rows) {
        let (label, d) = metric_label(&block[0].metric);
        let _ = write!(
            md,
            "\n## {}: {label}\n\n| room | n A | n B | mean A | mean B | A − B [95 % CI] | p | Holm p | MDD |\n|---|---|---|---|---|---|---|---|---|\n",
            block[0].setting
        );
        for r in block {
            let star = if r.p_holm < alpha { " *" } else { "" };
            let _ = writeln!(
                md,
                "| {} | {} | {} | {:.d$} | {:.d$} | {:+.d$} [{:+.d$}, {:+.d$}] | {} | {}{star} | {} |",
                r.room,
                r.n_a,
                r.n_b,
                r.mean_a,
                r.mean_b,
                r.difference,
                r.ci_low,
                r.ci_high,
                p_text(r.p),
                p_text(r.p_holm),
                r.mdd.map_or("—".into(), |m| format!("{m:.d$}"))
            );
        }
    }
    md
}

const PANEL_W: f64 = 250.0;
const ROW_H: f64 = 22.0;
const LABEL_W: f64 = 90.0;

/// The figure: one panel per setting (rows) and metric (columns), in each room and over all
/// rooms the difference A − B (dot) with its 95 % interval (line), against a line at 0; red
/// where the (Holm-adjusted) p < `alpha`.
pub fn compare_svg(title: &str, rows: &[CompareRow], alpha: f64) -> String {
    let blocks = blocks(rows);
    let mut settings: Vec<&str> = Vec::new();
    let mut metrics: Vec<&str> = Vec::new();
    for b in &blocks {
        if !settings.contains(&b[0].setting.as_str()) {
            settings.push(&b[0].setting);
        }
        if !metrics.contains(&b[0].metric.as_str()) {
            metrics.push(&b[0].metric);
        }
    }
    let most = blocks.iter().map(|b| b.len()).max().unwrap_or(1) as f64;
    let panel_h = 50.0 + ROW_H * most;
    let (w, h) = (
        LABEL_W + PANEL_W * metrics.len().max(1) as f64 + 10.0,
        40.0 + panel_h * settings.len().max(1) as f64 + LEGEND_H,
    );
    let mut svg = Svg::new(w.round(), h.round(), 11);
    svg.text((8.0, 20.0), title, Text::START.bold().size(14.0));
    for b in &blocks {
        let sx = settings
            .iter()
            .position(|s| *s == b[0].setting)
            .unwrap_or(0);
        let mx = metrics.iter().position(|m| *m == b[0].metric).unwrap_or(0);
        let (x0, y0) = (LABEL_W + PANEL_W * mx as f64, 40.0 + panel_h * sx as f64);
        panel(&mut svg, b, (x0, y0), mx == 0, alpha);
    }
    legend(&mut svg, h - LEGEND_H, alpha);
    svg.finish()
}

/// Height of [`compare_svg`]'s legend under its panels.
const LEGEND_H: f64 = 52.0;

/// What the colours and marks of [`compare_svg`] mean, one entry a row from `top`.
fn legend(svg: &mut Svg, top: f64, alpha: f64) {
    let legend = Legend::new(vec![
        (
            Mark::LineDot(SIGNIFICANT),
            format!("A − B, Holm-adjusted p < {alpha}: a difference"),
        ),
        (
            Mark::LineDot(NOT_SIGNIFICANT),
            format!("A − B, p ≥ {alpha}: no clear difference"),
        ),
    ]);
    legend.column(svg, 10.0, top + 12.0, 15.0);
    let note = "line: 95 % interval; dashed: A − B = 0";
    svg.text((10.0, top + 42.0), note, Text::START.fill(MUTED));
}

/// Colour of a difference at p < α, and of one that is not.
const SIGNIFICANT: &str = "#d62728";
const NOT_SIGNIFICANT: &str = "#1f77b4";

/// One panel of [`compare_svg`] at (x0, y0); room labels on its left when `labels`.
fn panel(svg: &mut Svg, block: &[CompareRow], (x0, y0): (f64, f64), labels: bool, alpha: f64) {
    let (label, d) = metric_label(&block[0].metric);
    let reach = block
        .iter()
        .flat_map(|r| [r.ci_low.abs(), r.ci_high.abs(), r.difference.abs()])
        .fold(0.0_f64, f64::max);
    let reach = if reach > 0.0 { reach * 1.1 } else { 1.0 };
    let bottom = y0 + 30.0 + ROW_H * block.len() as f64;
    let area = Area {
        x0: x0 + 10.0,
        x1: x0 + PANEL_W - 15.0,
        y0: bottom,
        y1: y0 + 24.0,
    };
    let x = area.x_scale(-reach, reach);
    area.title(svg, y0 + 4.0, &label);
    svg.text(
        (area.mid_x(), y0 + 17.0),
        &block[0].setting,
        Text::MIDDLE.fill(MUTED),
    );
    let frame = (area.x1 - area.x0, area.y0 - area.y1);
    svg.rect((area.x0, area.y1), frame, Fill::outline(Stroke::of("#ccc")));
    let zero = Stroke::of("#888").dashed("3,3");
    svg.line((x.at(0.0), area.y1), (x.at(0.0), bottom), zero);
    for (k, r) in block.iter().enumerate() {
        let y = y0 + 30.0 + ROW_H * (k as f64 + 0.5);
        let colour = if r.p_holm < alpha {
            SIGNIFICANT
        } else {
            NOT_SIGNIFICANT
        };
        if labels {
            svg.text((x0 - 4.0, y + 4.0), &r.room, Text::END);
        }
        svg.line(
            (x.at(r.ci_low), y),
            (x.at(r.ci_high), y),
            Stroke::of(colour).width(2.0),
        );
        let tip = format!(
            "{}: {:+.d$} [{:+.d$}, {:+.d$}], p = {}",
            r.room,
            r.difference,
            r.ci_low,
            r.ci_high,
            p_text(r.p)
        );
        svg.circle((x.at(r.difference), y), 3.5, Fill::of(colour), Some(&tip));
    }
    let ends = Text::START.fill(MUTED);
    svg.text((area.x0, bottom + 13.0), &format!("{:+.d$}", -reach), ends);
    let right = Text {
        anchor: Anchor::End,
        ..ends
    };
    svg.text((area.x1, bottom + 13.0), &format!("{reach:+.d$}"), right);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue #52: a p below 0.0001 (and its Holm p) is printed in compare.md as claims.md
    /// prints it ([`p_text`]: `1.0e-5`), never as `0.0000`; so is the figure's tooltip.
    #[test]
    fn a_small_p_in_compare_md_is_printed_readably_not_as_zero() {
        let row = CompareRow {
            setting: "high vs low".into(),
            metric: "exploration_pct".into(),
            room: OVERALL.into(),
            design: "paired".into(),
            n_a: 20,
            n_b: 20,
            mean_a: 91.2,
            mean_b: 89.5,
            difference: 1.7,
            ci_low: 1.0,
            ci_high: 2.4,
            p: 1e-5,
            exact: false,
            p_holm: 1e-5,
            mdd: Some(0.8),
        };
        let md = compare_md("# Compare", std::slice::from_ref(&row), 0.05);
        assert!(md.contains("| 1.0e-5 | 1.0e-5 * |"), "{md}");
        assert!(!md.contains("0.0000"), "{md}");
        let svg = compare_svg("Compare", &[row], 0.05);
        assert!(svg.contains("p = 1.0e-5</title>"), "{svg}");
    }
}
