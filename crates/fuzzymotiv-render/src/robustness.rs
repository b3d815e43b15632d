//! `robustness.svg`: a run's best robot under each perturbation
//! ([`RobustnessRecord`]s), one panel per measure (F, exploration, homing, battery, and a
//! run's recognition, missions done and terms beyond a, g, l, b: [`measures_of`]), the
//! perturbations down the side, each the mean (dot) with its 95 % interval (line) against the
//! unperturbed robot's mean (dashed line) and interval (grey band).

use fuzzymotiv_records::records::robustness::{RobustnessRecord, measures_of};

use crate::figure::axis::placed;
use crate::figure::{Area, Fill, Legend, MUTED, Mark, Stroke, Svg, Text, Ticks, text_width};

const PANEL_W: f64 = 190.0;
const GAP: f64 = 16.0;
const ROW_H: f64 = 18.0;
const TOP: f64 = 58.0;
const LEGEND_H: f64 = 50.0;

/// Colour of a perturbation whose interval leaves out the unperturbed mean, and of one that
/// holds it.
const CHANGED: &str = "#d62728";
const SAME: &str = "#1f77b4";

/// The figure of `records`, titled `title`; the unperturbed robot is the record labelled
/// `none` (else the first).
pub fn robustness_svg(title: &str, records: &[RobustnessRecord]) -> String {
    let label_w = records
        .iter()
        .map(|r| text_width(&r.perturbation, false))
        .fold(60.0, f64::max)
        + 16.0;
    let rows = records.len().max(1) as f64;
    let measures = measures_of(records);
    let w = label_w + (PANEL_W + GAP) * measures.len() as f64;
    let h = TOP + ROW_H * rows + 30.0 + LEGEND_H;
    let mut svg = Svg::new(w.round(), h.round(), 11);
    svg.text((8.0, 20.0), title, Text::START.bold().size(14.0));
    let base = records
        .iter()
        .position(|r| r.perturbation == "none")
        .unwrap_or(0);
    for (k, r) in records.iter().enumerate() {
        let y = TOP + ROW_H * (k as f64 + 0.5);
        let style = if k == base {
            Text::END.bold()
        } else {
            Text::END
        };
        svg.text((label_w - 8.0, y + 4.0), &r.perturbation, style);
    }
    for (m, (_, words)) in measures.iter().enumerate() {
        let x0 = label_w + (PANEL_W + GAP) * m as f64;
        panel(&mut svg, records, (m, words), base, x0);
    }
    legend(&mut svg, h - LEGEND_H + 8.0);
    svg.finish()
}

/// Panel `m` (a measure of [`measures_of`], shown as `words`) with its left edge at `x0`.
fn panel(
    svg: &mut Svg,
    records: &[RobustnessRecord],
    (m, words): (usize, &str),
    base: usize,
    x0: f64,
) {
    let values: Vec<(f64, f64, f64)> = records.iter().map(|r| r.measures()[m]).collect();
    let (first, last, ticks) = axis(&values);
    let bottom = TOP + ROW_H * records.len() as f64;
    let area = Area {
        x0: x0 + 6.0,
        x1: x0 + PANEL_W - 6.0,
        y0: bottom,
        y1: TOP,
    };
    let x = area.x_scale(first, last);
    area.title(svg, TOP - 10.0, words);
    let frame = (area.x1 - area.x0, bottom - TOP);
    svg.rect((area.x0, TOP), frame, Fill::outline(Stroke::of("#ccc")));
    let placed: Vec<(f64, String)> = placed(&ticks, x);
    for (xx, _) in &placed {
        svg.line((*xx, bottom), (*xx, bottom + 4.0), Stroke::of("#888"));
    }
    area.x_ticks(svg, &placed, 16.0, false, Text::MIDDLE.fill(MUTED));
    if let Some(&(bm, blo, bhi)) = values.get(base) {
        let band = (x.at(bhi) - x.at(blo), bottom - TOP);
        svg.rect((x.at(blo), TOP), band, Fill::of("#000").opacity(0.07));
        let dashed = Stroke::of(MUTED).dashed("3,3");
        svg.line((x.at(bm), TOP), (x.at(bm), bottom), dashed);
    }
    let base_mean = values.get(base).map_or(f64::NAN, |v| v.0);
    for (k, (r, &(mean, lo, hi))) in records.iter().zip(&values).enumerate() {
        let y = TOP + ROW_H * (k as f64 + 0.5);
        let colour = if k != base && (base_mean < lo || base_mean > hi) {
            CHANGED
        } else {
            SAME
        };
        svg.line((x.at(lo), y), (x.at(hi), y), Stroke::of(colour).width(2.0));
        let tip = format!("{}, {words}: {mean:.3} [{lo:.3}, {hi:.3}]", r.perturbation);
        svg.circle((x.at(mean), y), 3.5, Fill::of(colour), Some(&tip));
    }
}

/// The bounds of every measure of the figure: F, the terms and the shares (recognition,
/// missions done) are all values in [0, 1].
const BOUNDS: (f64, f64) = (0.0, 1.0);

/// A panel's axis over `values` ((mean, lower bound, upper bound) per perturbation): the
/// drawn range (`first`, `last`) and its ticks. The ticks span the values; values all alike
/// get a span of 0.05 either side, cut at [`BOUNDS`] (all 0: 0 … 0.05; a share all 1: 0.95
/// … 1), so no tick lies beyond what the measure can be.
fn axis(values: &[(f64, f64, f64)]) -> (f64, f64, Ticks) {
    let lo = values
        .iter()
        .map(|v| v.1.min(v.0))
        .fold(f64::INFINITY, f64::min);
    let hi = values
        .iter()
        .map(|v| v.2.max(v.0))
        .fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        // A value beyond the bounds (none should be) stays on the axis.
        (
            (lo - 0.05).max(BOUNDS.0.min(lo)),
            (hi + 0.05).min(BOUNDS.1.max(hi)),
        )
    };
    // A margin keeps the extreme marks off the frame and the edge ticks' labels apart.
    let pad = (hi - lo) * 0.06;
    (lo - pad, hi + pad, Ticks::nice(lo, hi, 5, false))
}

/// What the colours and marks mean, from `top`.
fn legend(svg: &mut Svg, top: f64) {
    let legend = Legend::new(vec![
        (
            Mark::LineDot(CHANGED),
            "interval leaves out the unperturbed mean".into(),
        ),
        (
            Mark::LineDot(SAME),
            "interval holds the unperturbed mean".into(),
        ),
    ]);
    legend.column(svg, 10.0, top, 15.0);
    let note = "dot: mean; line: 95 % bootstrap interval; dashed line and grey band: the unperturbed robot (none)";
    svg.text((10.0, top + 30.0), note, Text::START.fill(MUTED));
}

#[cfg(test)]
mod tests {
    use super::*;
    use fuzzymotiv_records::records::Fixed;

    fn record(label: &str, f: f64) -> RobustnessRecord {
        let v = |x: f64| Fixed(x);
        RobustnessRecord {
            perturbation: label.into(),
            trials: 4,
            f: v(f),
            f_lo: v(f - 0.05),
            f_hi: v(f + 0.05),
            exploration: v(0.5),
            exploration_lo: v(0.4),
            exploration_hi: v(0.6),
            homing: v(0.2),
            homing_lo: v(0.1),
            homing_hi: v(0.3),
            battery: v(0.9),
            battery_lo: v(0.9),
            battery_hi: v(0.9),
            recognition: Some(v(0.75)),
            recognition_lo: Some(v(0.5)),
            recognition_hi: Some(v(1.0)),
            extra: Vec::new(),
        }
    }

    /// A panel whose values are all 0 (a term no trial scored) has its axis from 0 up, and
    /// one whose values are all 1 (a full battery) has no tick above 1.
    #[test]
    fn an_all_zero_measure_starts_at_0_and_a_share_axis_does_not_exceed_1() {
        let (_, _, zero) = axis(&[(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]);
        assert_eq!(zero.values.first(), Some(&0.0), "{zero:?}");
        assert!(zero.values.iter().all(|&t| t >= 0.0), "{zero:?}");
        let (_, _, full) = axis(&[(1.0, 1.0, 1.0)]);
        assert!(full.values.iter().all(|&t| t <= 1.0), "{full:?}");
        assert_eq!(full.values.last(), Some(&1.0), "{full:?}");
        // Values that differ keep the axis they always had.
        let (first, last, ticks) = axis(&[(0.5, 0.4, 0.6), (0.2, 0.1, 0.3)]);
        assert!((first - (0.1 - 0.03)).abs() < 1e-12 && (last - (0.6 + 0.03)).abs() < 1e-12);
        assert_eq!(ticks, Ticks::nice(0.1, 0.6, 5, false));
    }

    /// Every perturbation is named, every measure has a panel, and a perturbation whose
    /// interval leaves out the unperturbed mean is drawn in the "changed" colour.
    #[test]
    fn the_figure_names_every_perturbation_and_marks_the_ones_that_change_f() {
        let records = [
            record("none", 0.6),
            record("dead=3", 0.2),
            record("table×0.7", 0.62),
        ];
        let svg = robustness_svg("Robustness", &records);
        for r in &records {
            assert!(
                svg.contains(&format!(">{}</text>", r.perturbation)),
                "{svg}"
            );
        }
        assert_eq!(measures_of(&records).len(), 5);
        for (_, words) in measures_of(&records) {
            assert!(svg.contains(&format!(">{words}</text>")), "{words}");
        }
        assert_eq!(svg.matches(&format!("stroke=\"{CHANGED}\"")).count(), 2); // dead=3 + legend
        assert!(svg.ends_with("</svg>\n"));
    }
}
