//! `forest.svg` of a study of one's own ([`forest_svg`]): every result's effect with its
//! interval, drawn in panels, one per measure and quantity (the difference between two arms,
//! a trend's slope per unit of level, a range's mean value, the mean F's rise), each with one
//! axis that every row of the panel shares, so that effects can be compared by eye. Rows of one
//! hypothesis stand together (pooled first, then each base seed).

use fuzzymotiv_records::records::hypotheses::{ClaimRow, Hypothesis, POOLED, StudyRecord};

use crate::claim_format::RowFormat;
use crate::figure::{Area, Fill, Legend, MUTED, Mark, Stroke, Svg, Text, Ticks, text_width};

/// Height of a result's row, px.
const ROW_H: f64 = 24.0;
/// Height of a panel's title line, px.
const TITLE_H: f64 = 24.0;
/// Height of a panel's axis (ticks and their labels) and the gap after it, px.
const AXIS_H: f64 = 40.0;
/// Width of the plotting area, px.
const PLOT_W: f64 = 360.0;

/// One panel: its title and its rows (indices into the record's claims).
struct Panel {
    key: (String, &'static str),
    title: String,
    rows: Vec<usize>,
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

/// The legend under the title: the colour of each verdict the study gave, in the order of
/// [`verdict_colour`].
fn verdict_legend(record: &StudyRecord) -> Legend<'static> {
    let entries: Vec<(Mark, String)> = ["holds", "opposite", "inconclusive", "not significant"]
        .into_iter()
        .filter(|v| record.claims.iter().any(|c| c.verdict == *v))
        .map(|v| {
            (
                Mark::Line(Stroke::of(verdict_colour(v)).width(4.0)),
                v.to_string(),
            )
        })
        .collect();
    Legend {
        entries,
        style: Text::START.fill(MUTED),
    }
}

/// The quantity a result's effect is (its panel's unit), by its kind.
fn quantity(kind: &str) -> &'static str {
    match kind {
        "trend" => "slope per unit of level",
        "range" => "the arm's mean",
        "rising" => "last generation − first",
        "difference" => "difference of two differences",
        _ => "difference between the arms",
    }
}

/// The record's results in panels, one per measure and quantity in the order they first
/// appear; in a panel each hypothesis's rows together, in the record's order of hypotheses.
fn panels(record: &StudyRecord) -> Vec<Panel> {
    let mut panels: Vec<Panel> = Vec::new();
    let order = |c: &ClaimRow| record.hypotheses.iter().position(|h| h.id() == c.id);
    let mut claims: Vec<usize> = (0..record.claims.len()).collect();
    claims.sort_by_key(|&k| order(&record.claims[k]));
    for k in claims {
        let c = &record.claims[k];
        let key = (c.measure.clone(), quantity(&c.kind));
        match panels.iter_mut().find(|p| p.key == key) {
            Some(p) => p.rows.push(k),
            None => {
                let hypothesis = record.hypotheses.iter().find(|h| h.id() == c.id);
                let measure = (hypothesis.and_then(Hypothesis::measure))
                    .map_or_else(|| "the mean F".into(), |m| m.label());
                let title = format!("{measure} ({}): {}", c.measure, key.1);
                panels.push(Panel {
                    key,
                    title,
                    rows: vec![k],
                });
            }
        }
    }
    panels
}

/// The reference values of a result: 0 (a difference, a slope) or a range's bounds.
fn references(record: &StudyRecord, c: &ClaimRow) -> Vec<f64> {
    match record.hypotheses.iter().find(|h| h.id() == c.id) {
        Some(Hypothesis::Range { min, max, .. }) => vec![*min, *max],
        _ => vec![0.0],
    }
}

/// A panel's shared axis: its ticks over every row's interval, effect and references, and
/// the span drawn (the outer ticks).
fn axis(record: &StudyRecord, panel: &Panel) -> (Ticks, f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &k in &panel.rows {
        let c = &record.claims[k];
        for v in [c.ci_low, c.ci_high, c.effect]
            .into_iter()
            .chain(references(record, c))
            .filter(|v| v.is_finite())
        {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    // No span, or one of rounding noise only (a zero effect's 1e-15): an axis around its
    // centre (0 for noise around 0).
    let scale = 1.0 + lo.abs().max(hi.abs());
    if !(lo.is_finite() && hi.is_finite()) || hi - lo <= 1e-9 * scale {
        let centre = if lo.is_finite() && hi.is_finite() {
            (lo + hi) / 2.0
        } else {
            0.0
        };
        let centre = if centre.abs() < 1e-9 { 0.0 } else { centre };
        let half = if centre == 0.0 {
            1.0
        } else {
            centre.abs() * 0.1
        };
        (lo, hi) = (centre - half, centre + half);
    }
    // The span widened to the ticks' step on both sides, with a tick at each end.
    let step = Ticks::nice(lo, hi, 5, false).step;
    let (first, last) = ((lo / step).floor() as i64, (hi / step).ceil() as i64);
    let values = (first..=last).map(|k| k as f64 * step).collect();
    let ticks = Ticks { step, values };
    (ticks, first as f64 * step, last as f64 * step)
}

/// A row's label: its id, and its scope unless pooled.
fn label(c: &ClaimRow) -> String {
    if c.scope == POOLED {
        c.id.clone()
    } else {
        format!("{} ({})", c.id, c.scope)
    }
}

/// `forest.svg`: a panel per measure and quantity, its title, its rows (label; the interval
/// as a line and the effect as a dot coloured by the verdict; the reference dashed: 0 for a
/// difference or a slope, the bounds for a range; the numbers) over one shared axis with
/// round ticks and light grid lines.
pub fn forest_svg(record: &StudyRecord) -> String {
    let panels = panels(record);
    let left = 20.0
        + (record.claims.iter())
            .map(|c| text_width(&label(c), false))
            .fold(80.0, f64::max);
    let top = 58.0;
    let rows: usize = panels.iter().map(|p| p.rows.len()).sum();
    let width = left + PLOT_W + 300.0;
    let height = top + ROW_H * rows as f64 + (TITLE_H + AXIS_H) * panels.len() as f64;
    let mut s = Svg::new(width, height, 12);
    let title = "Effects (dots) and their 95 % intervals, a shared axis per measure; dashed: no \
                 difference (0), or a range's bounds";
    s.text((10.0, 22.0), title, Text::START.bold());
    verdict_legend(record).flow(&mut s, (10.0, width - 10.0), 42.0, 16.0);
    let mut y = top;
    for panel in &panels {
        y = draw_panel(&mut s, record, panel, left, y);
    }
    s.finish()
}

/// Draws one panel from `y` down; returns where the next begins.
fn draw_panel(s: &mut Svg, record: &StudyRecord, panel: &Panel, left: f64, y: f64) -> f64 {
    let (ticks, lo, hi) = axis(record, panel);
    s.text((10.0, y + 16.0), &panel.title, Text::START.bold());
    let (first, last) = (y + TITLE_H, y + TITLE_H + ROW_H * panel.rows.len() as f64);
    let area = Area {
        x0: left,
        x1: left + PLOT_W,
        y0: last,
        y1: first,
    };
    let x = area.x_scale(lo, hi);
    s.group("axis");
    let placed: Vec<(f64, String)> = (ticks.values.iter())
        .map(|&t| (x.at(t), ticks.label(t).replace('-', "−")))
        .collect();
    for (xx, _) in &placed {
        s.line((*xx, first), (*xx, last + 4.0), Stroke::of("#eee"));
    }
    area.x_ticks(s, &placed, 18.0, false, Text::MIDDLE.fill(MUTED));
    s.line((area.x0, last), (area.x1, last), Stroke::of(MUTED));
    s.end_group();
    let numbers_x = left + PLOT_W + 15.0;
    for (n, &k) in panel.rows.iter().enumerate() {
        let row_y = first + ROW_H * (n as f64 + 0.5);
        draw_row(
            s,
            record,
            &record.claims[k],
            (&|v| x.at(v), numbers_x),
            row_y,
        );
    }
    last + AXIS_H
}

/// Draws one result's row centred on `y`, on its panel's axis `x`, its numbers from
/// `numbers_x`.
fn draw_row(
    s: &mut Svg,
    record: &StudyRecord,
    c: &ClaimRow,
    (x, numbers_x): (&dyn Fn(f64) -> f64, f64),
    y: f64,
) {
    s.text((10.0, y + 4.0), &label(c), Text::START);
    for r in references(record, c) {
        let dashed = Stroke::of("#999").dashed("3,3");
        s.line((x(r), y - ROW_H * 0.5), (x(r), y + ROW_H * 0.5), dashed);
    }
    let colour = verdict_colour(&c.verdict);
    s.line(
        (x(c.ci_low), y),
        (x(c.ci_high), y),
        Stroke::of(colour).width(2.0),
    );
    s.circle((x(c.effect), y), 4.0, Fill::of(colour), None);
    let f = RowFormat::of_claim(c);
    let numbers = format!(
        "{} {} {}",
        f.num(c.effect),
        f.interval(c.ci_low, c.ci_high),
        c.verdict
    );
    s.text((numbers_x, y + 4.0), &numbers, Text::START);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hypotheses::tests::{claim, record};
    use fuzzymotiv_records::records::hypotheses::{Direction, Measure};

    fn compare(id: &str, measure: Measure) -> Hypothesis {
        Hypothesis::Compare {
            id: id.into(),
            measure,
            a: "a".into(),
            b: "b".into(),
            expect: Direction::Higher,
        }
    }

    /// The x of every dashed reference line of `svg`, in order.
    fn reference_xs(svg: &str) -> Vec<f64> {
        (svg.lines())
            .filter(|l| l.contains("stroke-dasharray"))
            .map(|l| {
                let at = l.find("x1=\"").unwrap() + 4;
                l[at..].split('"').next().unwrap().parse().unwrap()
            })
            .collect()
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
        assert_eq!(svg.matches("stroke-dasharray").count(), 2, "{svg}");
        assert_eq!(svg.matches("<circle").count(), 1);
        let svg = forest_svg(&record(vec![rising]));
        assert_eq!(svg.matches("stroke-dasharray").count(), 1, "{svg}");
        assert!(
            svg.contains(">the mean F (mean_f): last generation − first<"),
            "{svg}"
        );
    }

    /// The legend names the colour of each verdict the study gave, and only those.
    #[test]
    fn the_legend_names_each_verdict_given_in_its_colour() {
        let mut r = record(vec![
            compare("a", Measure::Exploration),
            compare("b", Measure::Homing),
        ]);
        r.claims[0].verdict = "holds".into();
        r.claims[1].verdict = "not significant".into();
        let svg = forest_svg(&r);
        for (verdict, colour) in [("holds", "#2ca02c"), ("not significant", "#7f7f7f")] {
            assert!(svg.contains(&format!(">{verdict}</text>")), "{svg}");
            assert!(
                svg.matches(colour).count() >= 3,
                "{verdict}: legend, interval, dot"
            );
        }
        for absent in ["opposite", "inconclusive"] {
            assert!(!svg.contains(&format!(">{absent}</text>")), "{absent}");
        }
    }

    /// Two comparisons of one measure with very different effects share their panel's axis:
    /// their zeros stand at the same x and the larger effect's dot further right; a third
    /// measure gets a panel (an axis) of its own. On a scale per row both zeros would sit at
    /// their own rows' x.
    #[test]
    fn the_rows_of_one_measure_share_one_axis_and_each_measure_has_its_own() {
        let mut r = record(vec![
            compare("small", Measure::Exploration),
            compare("large", Measure::Exploration),
            compare("homing", Measure::Homing),
        ]);
        r.claims[0] = claim(&r.hypotheses[0], 2.0, -1.0, 5.0);
        r.claims[1] = claim(&r.hypotheses[1], 30.0, 20.0, 40.0);
        r.claims[2] = claim(&r.hypotheses[2], -8.0, -12.0, -4.0);
        let svg = forest_svg(&r);
        assert_eq!(svg.matches("<g class=\"axis\">").count(), 2, "{svg}");
        let xs = reference_xs(&svg);
        assert_eq!(xs.len(), 3, "{svg}");
        assert_eq!(xs[0], xs[1], "one zero for the exploration panel: {svg}");
        let dots: Vec<f64> = (svg.lines())
            .filter(|l| l.contains("<circle"))
            .map(|l| {
                let at = l.find("cx=\"").unwrap() + 4;
                l[at..].split('"').next().unwrap().parse().unwrap()
            })
            .collect();
        assert!(
            dots[1] > dots[0] + 150.0,
            "30 stands well right of 2: {dots:?}"
        );
        assert!(svg.contains("% exploration (exploration_pct): difference between the arms"));
        assert!(svg.contains("% homing (homing_pct)"), "{svg}");
    }

    /// Ticks at round numbers under each panel, covering every row's interval, with a tick
    /// at each end of the axis and none of the step's missing between.
    #[test]
    fn a_panels_ticks_are_round_and_cover_its_intervals() {
        let mut r = record(vec![compare("x", Measure::Exploration)]);
        r.claims[0] = claim(&r.hypotheses[0], 7.304, 3.1, 32.4641);
        let svg = forest_svg(&r);
        for tick in [">0<", ">10<", ">20<", ">30<", ">40<"] {
            assert!(svg.contains(tick), "{tick}: {svg}");
        }
        assert!(svg.contains(">7.3 [3.1, 32.5] not significant<"), "{svg}");
        r.claims[0] = claim(&r.hypotheses[0], 0.4, -2.3, 6.5);
        let svg = forest_svg(&r);
        for tick in [">−4<", ">−2<", ">0<", ">2<", ">4<", ">6<", ">8<"] {
            assert!(svg.contains(tick), "{tick}: {svg}");
        }
    }

    /// A panel whose numbers are all rounding noise around 0 (a zero slope, 1e-15) gets an
    /// axis around 0 with round ticks, not ticks of fifteen decimals.
    #[test]
    fn a_panel_of_rounding_noise_gets_an_axis_around_zero() {
        let mut r = record(vec![compare("x", Measure::Exploration)]);
        r.claims[0] = claim(&r.hypotheses[0], 1e-15, -2e-16, 3e-15);
        let svg = forest_svg(&r);
        for tick in [">−1.0<", ">0.0<", ">1.0<"] {
            assert!(svg.contains(tick), "{tick}: {svg}");
        }
        assert!(!svg.contains("0.000000"), "{svg}");
    }
}
