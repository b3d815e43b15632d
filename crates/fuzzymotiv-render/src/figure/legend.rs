//! Legends ([`Legend`]): entries of a mark and a text, flowing left to right and wrapping at a
//! width, or one under another.

use super::doc::{Fill, Stroke, Svg, Text};

/// A legend entry's mark, 20 px wide.
#[derive(Debug, Clone, PartialEq)]
pub enum Mark<'a> {
    /// A line.
    Line(Stroke<'a>),
    /// A dot of a colour.
    Dot(&'a str),
    /// A line with a dot on it (an interval and its estimate).
    LineDot(&'a str),
    /// Swatches of shaded bands.
    Bands(Vec<&'a str>),
}

/// The width of a mark, and the gap from its left edge to the text (a dot's is narrower).
const MARK: f64 = 20.0;
const TEXT_AT: f64 = 26.0;
const DOT_TEXT_AT: f64 = 12.0;
/// The room after an entry's text before the next entry in a row.
const AFTER: f64 = 14.0;

/// A legend: its entries in order, each set in `style`.
#[derive(Debug, Clone, PartialEq)]
pub struct Legend<'a> {
    /// The entries: a mark and its text.
    pub entries: Vec<(Mark<'a>, String)>,
    /// How their texts are set.
    pub style: Text<'a>,
}

impl<'a> Legend<'a> {
    /// A legend of `entries` in the figure's plain text.
    pub fn new(entries: Vec<(Mark<'a>, String)>) -> Legend<'a> {
        Legend {
            entries,
            style: Text::START,
        }
    }

    /// The width entry `k` takes in a row of `svg`.
    fn entry_width(&self, svg: &Svg, k: usize) -> f64 {
        text_at(&self.entries[k].0) + svg.text_width(&self.entries[k].1, self.style) + AFTER
    }

    /// The width of the entries in one row.
    pub fn width(&self, svg: &Svg) -> f64 {
        (0..self.entries.len())
            .map(|k| self.entry_width(svg, k))
            .sum()
    }

    /// Where each entry goes when they flow from `x0`, wrapping before `x1`: (x, row).
    fn layout(&self, svg: &Svg, (x0, x1): (f64, f64)) -> Vec<(f64, usize)> {
        let (mut x, mut row) = (x0, 0);
        (0..self.entries.len())
            .map(|k| {
                let w = self.entry_width(svg, k);
                if x > x0 && x + w > x1 {
                    (x, row) = (x0, row + 1);
                }
                let at = (x, row);
                x += w;
                at
            })
            .collect()
    }

    /// The rows the entries take flowing in `width` px.
    pub fn rows(&self, svg: &Svg, width: f64) -> usize {
        (self.layout(svg, (0.0, width)).last()).map_or(1, |&(_, row)| row + 1)
    }

    /// Draws the entries flowing left to right from `x0`, wrapping before `x1`, rows
    /// `row_h` apart, the first row's text baseline at `top`.
    pub fn flow(&self, svg: &mut Svg, (x0, x1): (f64, f64), top: f64, row_h: f64) {
        for (k, (x, row)) in self.layout(svg, (x0, x1)).into_iter().enumerate() {
            self.entry(svg, k, (x, top + row_h * row as f64));
        }
    }

    /// Draws the entries one under another from `x`, `row_h` apart, the first text's
    /// baseline at `top`.
    pub fn column(&self, svg: &mut Svg, x: f64, top: f64, row_h: f64) {
        for k in 0..self.entries.len() {
            self.entry(svg, k, (x, top + row_h * k as f64));
        }
    }

    /// Entry `k`, its mark from `x`, its text's baseline at `y`.
    fn entry(&self, svg: &mut Svg, k: usize, (x, y): (f64, f64)) {
        let (mark, text) = &self.entries[k];
        let mid = y - 4.0;
        match mark {
            Mark::Line(stroke) => svg.line((x, mid), (x + MARK, mid), *stroke),
            Mark::Dot(colour) => svg.circle((x + 4.0, mid), 4.0, Fill::of(colour), None),
            Mark::LineDot(colour) => {
                svg.line((x, mid), (x + MARK, mid), Stroke::of(colour).width(2.0));
                svg.circle((x + MARK / 2.0, mid), 3.5, Fill::of(colour), None);
            }
            Mark::Bands(colours) => {
                let w = MARK / colours.len().max(1) as f64;
                for (j, colour) in colours.iter().enumerate() {
                    let fill = Fill::of(colour).opacity(0.45);
                    svg.rect((x + w * j as f64, y - 9.0), (w, 10.0), fill);
                }
            }
        }
        svg.text((x + text_at(mark), y), text, self.style);
    }
}

/// Where an entry's text starts after its mark's left edge.
fn text_at(mark: &Mark<'_>) -> f64 {
    match mark {
        Mark::Dot(_) => DOT_TEXT_AT,
        _ => TEXT_AT,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries flow left to right and wrap to a new row before the right edge; a dot's text
    /// sits closer to its mark than a line's.
    #[test]
    fn a_flowing_legend_wraps_before_its_right_edge() {
        let legend = Legend::new(vec![
            (Mark::Line(Stroke::of("#000")), "first entry".into()),
            (Mark::Dot("#f00"), "second entry".into()),
            (Mark::LineDot("#00f"), "third entry".into()),
        ]);
        let mut svg = Svg::new(400.0, 100.0, 12);
        let one_row = legend.width(&svg);
        assert_eq!(legend.rows(&svg, one_row + 1.0), 1);
        assert_eq!(legend.rows(&svg, one_row - 1.0), 2);
        legend.flow(&mut svg, (10.0, 10.0 + one_row - 1.0), 20.0, 16.0);
        let out = svg.finish();
        assert!(
            out.contains(r#"<text x="36" y="20">first entry</text>"#),
            "{out}"
        );
        // The third wrapped to the second row, at the left edge.
        assert!(
            out.contains(r#"<text x="36" y="36">third entry</text>"#),
            "{out}"
        );
        let second = 10.0 + legend.entry_width(&Svg::new(1.0, 1.0, 12), 0) + 12.0;
        assert!(
            out.contains(&format!(
                r#"<text x="{}" y="20">second entry</text>"#,
                crate::figure::px(second)
            )),
            "{out}"
        );
    }
}
